//! The check of a timing: the result sampled every `check_step` seconds, each sample's
//! velocities, accelerations and torques compared with the limits, the torques summarised as a
//! torque profile would summarise them.
//!
//! The torques are the inverse dynamics of [`crate::batch::rnea`] (Lynch & Park, *Modern
//! Robotics*: `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` with the joints' armature) of
//! [`SAMPLES_PER_CALL`] samples at a time, eight side by side in SIMD lanes, plus each joint's
//! spring and Coulomb friction `k (q − q_spring) + f sign(q̇)` per sample, as
//! [`crate::sim::torque_profile`] adds them. The lanes fuse multiply–adds, so a torque can differ
//! from the per-call [`crate::dynamics::rnea`]'s in its last bits (a few units of 10⁻¹⁶
//! relative); the comparison with each limit is the same strict `|value| / limit − 1` of every
//! sample.

use super::reachability::LimitKind;
use super::spline::Path;
use super::time_optimal::{Timing, TimingLimits};
use crate::batch::{self, BatchWorkspace, Rows};
use crate::dynamics::rnea;
use crate::model::Model;
use crate::sim::{ProfileSummary, TorqueStatistics};
use crate::workspace::Workspace;

/// Samples per call of the batch inverse dynamics: eight groups of eight lanes (the call's
/// checks of the model and the inputs are made once for all of them).
pub(super) const SAMPLES_PER_CALL: usize = 8 * batch::LANES;

/// What a check found: the largest excess `|value| / limit − 1`, where it occurs (kind, joint,
/// time), the number of samples and their torque statistics.
pub(super) type CheckResult = (f64, (LimitKind, usize, f64), usize, ProfileSummary);

/// The buffers of [`check_limits`], made once per timing: [`SAMPLES_PER_CALL`] samples' `q`, `q̇`, `q̈`, `τ` (row-major, one sample after the other),
/// and `1 / limit` of every limit.
pub(super) struct CheckWorkspace {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    tau: Vec<f64>,
    times: Vec<f64>,
    /// `1 / limit` for velocity, acceleration and torque: one division per limit, not per
    /// sample.
    per_limit: [Vec<f64>; 3],
}

impl CheckWorkspace {
    /// The buffers for `model` and `limits` (of the model's length, checked by the caller).
    pub(super) fn new(model: &Model, limits: &TimingLimits) -> Self {
        let rows = SAMPLES_PER_CALL * model.nq();
        let per_limit = |l: &[f64]| l.iter().map(|x| 1.0 / x).collect::<Vec<_>>();
        CheckWorkspace {
            q: vec![0.0; rows],
            qd: vec![0.0; rows],
            qdd: vec![0.0; rows],
            tau: vec![0.0; rows],
            times: vec![0.0; SAMPLES_PER_CALL],
            per_limit: [
                per_limit(&limits.velocity),
                per_limit(&limits.acceleration),
                per_limit(&limits.effort),
            ],
        }
    }
}

/// Samples the timing every `step` seconds (and at its end) and returns the largest excess
/// `|value| / limit − 1` over velocity, acceleration and torque (inverse dynamics plus springs
/// and Coulomb friction), where it occurs (the first sample, joint and kind of the largest), the
/// number of samples and their torque statistics. A sample the inverse dynamics refuses
/// (non-finite) ends the check with an infinite excess at its time. `batch` is the timing's
/// batch workspace (the grid's coefficients use it too).
pub(super) fn check_limits(
    model: &Model,
    batch: &mut BatchWorkspace,
    cw: &mut CheckWorkspace,
    path: &dyn Path,
    timing: &Timing,
    step: f64,
) -> CheckResult {
    let n = path.nq();
    let duration = timing.duration();
    let samples = (duration / step).ceil() as usize + 1;
    let mut worst = (f64::NEG_INFINITY, (LimitKind::Torque, 0, 0.0));
    let mut stats = TorqueStatistics::new(model);
    let mut interval = 0;
    let mut first = 0;
    while first < samples {
        let count = SAMPLES_PER_CALL.min(samples - first);
        let rows = count * n;
        // q, q̇ = q' ṡ, q̈ = q' s̈ + q'' ṡ² of the samples first..first + count.
        for (i, t) in cw.times[..count].iter_mut().enumerate() {
            *t = ((first + i) as f64 * step).min(duration);
            let at = i * n..(i + 1) * n;
            Timing::to_joints(
                path,
                timing.state_after(*t, &mut interval),
                &mut cw.q[at.clone()],
                &mut cw.qd[at.clone()],
                &mut cw.qdd[at],
            );
        }
        // τ = M q̈ + C q̇ + g of every sample, eight side by side.
        let (q, qd, qdd) = (&cw.q[..rows], &cw.qd[..rows], &cw.qdd[..rows]);
        let tau = &mut cw.tau[..rows];
        let batched = batch::rnea(
            model,
            batch,
            Rows::Stacked(q),
            Rows::Stacked(qd),
            Rows::Stacked(qdd),
            tau,
        );
        // Refused: the samples one by one, to end at the first one refused.
        let mut valid = count;
        if batched.is_err() {
            let mut ws = Workspace::new(model);
            valid = (0..count)
                .position(|i| {
                    let at = i * n..(i + 1) * n;
                    match rnea(
                        model,
                        &mut ws,
                        &q[at.clone()],
                        &qd[at.clone()],
                        &qdd[at.clone()],
                    ) {
                        Ok(t) => {
                            tau[at].copy_from_slice(t.as_slice());
                            false
                        }
                        Err(_) => true,
                    }
                })
                .unwrap_or(count);
        }
        for i in 0..valid {
            let t = cw.times[i];
            let at = i * n..(i + 1) * n;
            let (q, qd, qdd, tau) = (&q[at.clone()], &qd[at.clone()], &qdd[at.clone()], &tau[at]);
            for (j, joint) in model.joints().iter().enumerate() {
                // + k (q − q_spring) + f sign(q̇)
                let tau_j = tau[j] + joint.spring_and_friction_torque(q[j], qd[j]);
                stats.add(j, t, tau_j);
                for (kind, value, per_limit) in [
                    (LimitKind::Velocity, qd[j], cw.per_limit[0][j]),
                    (LimitKind::Acceleration, qdd[j], cw.per_limit[1][j]),
                    (LimitKind::Torque, tau_j, cw.per_limit[2][j]),
                ] {
                    let excess = value.abs() * per_limit - 1.0;
                    if excess > worst.0 {
                        worst = (excess, (kind, j, t));
                    }
                }
            }
        }
        if valid < count {
            let k = first + valid;
            let t = cw.times[valid];
            return (
                f64::INFINITY,
                (LimitKind::Torque, 0, t),
                k + 1,
                stats.summary(k + 1),
            );
        }
        first += count;
    }
    (worst.0, worst.1, samples, stats.summary(samples))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::{time_optimal, CubicSpline, TimeOptimalOptions};
    use crate::sim::torque_profile;

    #[test]
    fn one_sample_over_a_limit_inside_a_group_of_eight_is_found_where_it_is() {
        // A UR5 timing, checked against an effort limit set between the largest and the
        // second largest |τ_j| of its samples (per-call inverse dynamics, torque_profile), for
        // a joint whose largest is neither the first nor the last sample of its group of
        // eight lanes: that one sample, and only it, is over, and the check names its time.
        let m = crate::builtin::load("ur5").unwrap();
        let path = CubicSpline::chord_length(&[
            vec![0.0, -1.8, 1.4, -1.2, -1.6, 0.0],
            vec![0.8, -1.2, 1.0, -1.4, -1.6, 0.5],
            vec![1.6, -1.6, 1.8, -1.0, -1.2, 1.0],
        ])
        .unwrap();
        let limits = TimingLimits::from_model(&m);
        let options = TimeOptimalOptions {
            grid: Some(200),
            ..Default::default()
        };
        let timed = time_optimal(&m, path, &limits, &options).unwrap();
        let step = options.check_step;
        let p = torque_profile(&m, &timed, step).unwrap();
        let tau = &p.samples.tau;
        let (j, k, largest, second) = (0..6)
            .find_map(|j| {
                let mut by_size: Vec<(f64, usize)> = tau
                    .iter()
                    .enumerate()
                    .map(|(k, t)| (t[j].abs(), k))
                    .collect();
                by_size.sort_by(|a, b| b.0.total_cmp(&a.0));
                let ((largest, k), (second, _)) = (by_size[0], by_size[1]);
                let inside = k >= 8 && (1..7).contains(&(k % 8));
                (inside && largest - second > 1e-9 * largest).then_some((j, k, largest, second))
            })
            .expect("a joint whose largest torque is inside a group");
        let mut tight = TimingLimits {
            velocity: vec![f64::INFINITY; 6],
            acceleration: vec![f64::INFINITY; 6],
            effort: limits.effort.iter().map(|e| 10.0 * e).collect(),
        };
        tight.effort[j] = 0.5 * (largest + second);
        let mut cw = CheckWorkspace::new(&m, &tight);
        let mut batch = BatchWorkspace::new(&m);
        let (excess, (kind, joint, t), samples, _) =
            check_limits(&m, &mut batch, &mut cw, timed.path(), timed.timing(), step);
        assert_eq!(samples, tau.len());
        assert_eq!((kind, joint, t), (LimitKind::Torque, j, p.samples.t[k]));
        let expected = largest / tight.effort[j] - 1.0;
        assert!(
            excess > 0.0 && (excess - expected).abs() < 1e-12,
            "{excess} vs {expected}"
        );
    }
}
