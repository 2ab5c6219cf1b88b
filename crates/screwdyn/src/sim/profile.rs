//! Torque profiles: inverse dynamics along a trajectory, peak and RMS torque per joint and
//! every sample over the joint's effort limit — the question "how much torque is needed
//! to accelerate the manipulator from rest to constant velocity, and then back to stop?".

use super::record::{Recording, Sample, SampleSink};
use super::setting::{check, Range};
use super::trajectory::Trajectory;
use crate::dynamics::{inverse_dynamics, kinetic_energy, potential_energy};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;

/// One sample over an effort limit.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// Joint index.
    pub joint: usize,
    /// Time (s).
    pub t: f64,
    /// The required torque.
    pub tau: f64,
    /// The joint's effort limit.
    pub limit: f64,
}

/// Per joint, the samples over the effort limit summarised: how many, when the first was,
/// and the largest required `|τ|`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViolationSummary {
    /// Number of samples over the limit.
    pub count: usize,
    /// Time of the first one (s).
    pub first_time: f64,
    /// The largest `|τ_i|` over the limit.
    pub worst: f64,
}

/// The result of [`torque_profile`].
#[derive(Clone, Debug, PartialEq)]
pub struct TorqueProfile {
    /// The sampled motion and the required torques (`tau`), energies included.
    pub samples: Recording,
    /// `max |τ_i|` per joint.
    pub peak: Vec<f64>,
    /// The time of that peak (the first, on ties), per joint.
    pub peak_time: Vec<f64>,
    /// `√(mean τ_i²)` per joint.
    pub rms: Vec<f64>,
    /// Effort limit per joint (∞ if none).
    pub effort_limit: Vec<f64>,
    /// Every sample whose `|τ_i|` exceeds the limit.
    pub violations: Vec<Violation>,
    /// Per joint: the violations summarised (`None` where the joint stays within its limit).
    pub violation_summary: Vec<Option<ViolationSummary>>,
}

impl TorqueProfile {
    /// The joints that exceed their effort limit somewhere, in joint order.
    pub fn joints_over_limit(&self) -> Vec<usize> {
        (0..self.peak.len())
            .filter(|&i| self.violation_summary[i].is_some())
            .collect()
    }
}

/// The default largest number of samples [`torque_profile`] computes (10 million): a profile is
/// held in memory, so a step or duration that asks for more is refused before anything is
/// allocated; [`torque_profile_limited`] sets another bound.
pub const MAX_PROFILE_SAMPLES: usize = 10_000_000;

/// Inverse dynamics (RNEA with gravity, Lynch & Park, *Modern Robotics*) at every `dt` along `trajectory`, end
/// included, plus the torque the joints' springs and Coulomb friction take
/// ([`Joint::spring_and_friction_torque`](crate::model::Joint::spring_and_friction_torque)), with peak, RMS and
/// effort-limit statistics per joint — at most
/// [`MAX_PROFILE_SAMPLES`] samples.
///
/// # Errors
/// [`Error::InvalidArgument`] when the trajectory's joints do not match the model, `dt` is not
/// positive and finite, or the profile would have more than [`MAX_PROFILE_SAMPLES`] samples.
///
/// ```
/// use screwdyn::sim::{torque_profile, Trapezoid};
/// let m = screwdyn::builtin::planar2();
/// let traj = Trapezoid::new(&[0.0, 0.0], &[1.0, 0.5], &[1.0, 1.0], &[2.0, 2.0], true).unwrap();
/// let p = torque_profile(&m, &traj, 0.01).unwrap();
/// assert!(p.peak[0] >= p.rms[0] && p.violations.is_empty());
/// assert!(torque_profile(&m, &traj, 1e-12).unwrap_err().to_string().contains("samples"));
/// ```
pub fn torque_profile(
    model: &Model,
    trajectory: &dyn Trajectory,
    dt: f64,
) -> Result<TorqueProfile> {
    torque_profile_limited(model, trajectory, dt, MAX_PROFILE_SAMPLES)
}

/// [`torque_profile`] with at most `max_samples` samples.
///
/// # Errors
/// As [`torque_profile`], with `max_samples` as the bound; [`Error::InvalidArgument`] naming
/// the memory the samples would need when the machine cannot hold them (see
/// [`Recording::reserve`]).
pub fn torque_profile_limited(
    model: &Model,
    trajectory: &dyn Trajectory,
    dt: f64,
    max_samples: usize,
) -> Result<TorqueProfile> {
    let wanted = profile_samples(model, trajectory, dt, max_samples)?;
    let mut rec = Recording::new(
        model.joint_names().into_iter().map(String::from).collect(),
        vec![],
    );
    rec.reserve(wanted)?;
    let s = torque_profile_into(model, trajectory, dt, max_samples, &mut rec)?;
    // Every sample over a limit, from the recorded torques.
    let mut violations = Vec::new();
    for (t, tau) in rec.t.iter().zip(&rec.tau) {
        for (i, x) in tau.iter().enumerate() {
            if x.abs() > s.effort_limit[i] {
                violations.push(Violation {
                    joint: i,
                    t: *t,
                    tau: *x,
                    limit: s.effort_limit[i],
                });
            }
        }
    }
    Ok(TorqueProfile {
        samples: rec,
        peak: s.peak,
        peak_time: s.peak_time,
        rms: s.rms,
        effort_limit: s.effort_limit,
        violations,
        violation_summary: s.violation_summary,
    })
}

/// What [`torque_profile_into`] keeps of a profile: the statistics per joint, not the samples.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileSummary {
    /// The number of samples sent to the sink.
    pub samples: usize,
    /// `max |τ_i|` per joint.
    pub peak: Vec<f64>,
    /// The time of that peak (the first, on ties), per joint.
    pub peak_time: Vec<f64>,
    /// `√(mean τ_i²)` per joint.
    pub rms: Vec<f64>,
    /// Effort limit per joint (∞ if none).
    pub effort_limit: Vec<f64>,
    /// Per joint: the samples over the limit summarised (`None` where the joint stays within).
    pub violation_summary: Vec<Option<ViolationSummary>>,
}

/// The number of samples of a profile of `trajectory` every `dt` (end included), checked
/// against `max_samples`.
fn profile_samples(
    model: &Model,
    trajectory: &dyn Trajectory,
    dt: f64,
    max_samples: usize,
) -> Result<usize> {
    if trajectory.nq() != model.nq() {
        return Err(Error::InvalidArgument(format!(
            "the trajectory has {} joints, the model has {}",
            trajectory.nq(),
            model.nq()
        )));
    }
    check("dt", dt, Range::Positive, "the sampling step in seconds")?;
    let wanted = (trajectory.duration() / dt).ceil() + 1.0;
    if wanted.is_nan() || wanted > max_samples as f64 {
        return Err(Error::InvalidArgument(format!(
            "a profile of {:.6} s every {dt} s has {wanted:.0} samples, more than the limit of {max_samples} (use a larger step or raise the limit)",
            trajectory.duration()
        )));
    }
    Ok(wanted as usize)
}

/// The torque profile of [`torque_profile_limited`], each sample sent to `sink` as soon as it
/// is computed and nothing else kept but the statistics: memory does not depend on the number
/// of samples, so a profile of any length can be written to a file (or stdout) as it goes.
/// When it fails part-way (a sink that cannot write), every sample before has reached the
/// sink.
///
/// # Errors
/// As [`torque_profile`], with `max_samples` as the bound; any error of the sink.
///
/// ```
/// use screwdyn::sim::{torque_profile, torque_profile_into, CsvSampleWriter, Trapezoid};
/// let m = screwdyn::builtin::planar2();
/// let traj = Trapezoid::new(&[0.0, 0.0], &[1.0, 0.5], &[1.0, 1.0], &[2.0, 2.0], true).unwrap();
/// let mut csv = CsvSampleWriter::new(Vec::new());
/// let s = torque_profile_into(&m, &traj, 0.01, 1000, &mut csv).unwrap();
/// let text = String::from_utf8(csv.into_inner()).unwrap();
/// assert_eq!(text.lines().count(), 1 + s.samples);
/// assert_eq!(s.peak, torque_profile(&m, &traj, 0.01).unwrap().peak);
/// ```
pub fn torque_profile_into(
    model: &Model,
    trajectory: &dyn Trajectory,
    dt: f64,
    max_samples: usize,
    sink: &mut dyn SampleSink,
) -> Result<ProfileSummary> {
    let wanted = profile_samples(model, trajectory, dt, max_samples)?;
    let steps = wanted - 1;
    let n = model.nq();
    let mut ws = Workspace::new(model);
    let (mut q, mut v, mut a, mut tau) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let joints: Vec<String> = model.joint_names().into_iter().map(String::from).collect();
    sink.begin(&joints, &[])?;
    let mut stats = TorqueStatistics::new(model);
    for k in 0..=steps {
        let t = (k as f64 * dt).min(trajectory.duration());
        trajectory.sample(t, &mut q, &mut v, &mut a)?;
        // τ = M(q) q̈ + C(q, q̇) q̇ + g(q) by RNEA, plus k (q − q_spring) + f sign(q̇).
        tau.copy_from_slice(inverse_dynamics(model, &mut ws, &q, &v, &a, None)?.as_slice());
        model.add_spring_and_friction_torques(&q, &v, &mut tau);
        for (i, &tau_i) in tau.iter().enumerate() {
            stats.add(i, t, tau_i);
        }
        let ke = kinetic_energy(model, &mut ws, &q, &v)?;
        let pe = potential_energy(model, &mut ws, &q)?;
        sink.push(&Sample {
            t,
            q: &q,
            v: &v,
            a: &a,
            tau: &tau,
            kinetic_energy: ke,
            potential_energy: pe,
            poses: &[],
        })?;
    }
    Ok(stats.summary(wanted))
}

/// Per joint `max |τ|` (the first time on ties), `Σ τ²` and the samples over the model's
/// effort limit, as a torque profile keeps them: what [`torque_profile_into`] and the check of
/// a time-optimal timing (`motion::time_optimal`) summarise their samples with.
pub(crate) struct TorqueStatistics {
    peak: Vec<f64>,
    peak_time: Vec<f64>,
    sum_of_squares: Vec<f64>,
    effort_limit: Vec<f64>,
    over: Vec<Option<ViolationSummary>>,
}

impl TorqueStatistics {
    pub(crate) fn new(model: &Model) -> Self {
        let n = model.nq();
        TorqueStatistics {
            peak: vec![0.0; n],
            peak_time: vec![0.0; n],
            sum_of_squares: vec![0.0; n],
            effort_limit: model.joints().iter().map(|j| j.limits.effort).collect(),
            over: vec![None; n],
        }
    }

    pub(crate) fn add(&mut self, j: usize, t: f64, tau: f64) {
        let magnitude = tau.abs();
        if magnitude > self.peak[j] {
            (self.peak[j], self.peak_time[j]) = (magnitude, t);
        }
        self.sum_of_squares[j] += tau * tau;
        if magnitude > self.effort_limit[j] {
            let s = self.over[j].get_or_insert(ViolationSummary {
                count: 0,
                first_time: t,
                worst: 0.0,
            });
            s.count += 1;
            s.worst = s.worst.max(magnitude);
        }
    }

    /// The statistics of `samples` samples; RMS `= √(Σ τ² / samples)`.
    pub(crate) fn summary(self, samples: usize) -> ProfileSummary {
        let count = samples as f64;
        ProfileSummary {
            samples,
            rms: self
                .sum_of_squares
                .iter()
                .map(|s| (s / count).sqrt())
                .collect(),
            peak: self.peak,
            peak_time: self.peak_time,
            effort_limit: self.effort_limit,
            violation_summary: self.over,
        }
    }
}
