//! Computed-torque control tracking the fastest motions: with the controller's model exact, the
//! closed loop's error obeys `ë + K_d ė + K_p e = 0` from `e(0) = ė(0) = 0`, so it stays 0, and
//! the commanded torques are the trajectory's inverse dynamics.

use screwdyn::dynamics::rnea;
use screwdyn::motion::{
    time_optimal, CubicSpline, JerkLimited, SampledTrajectory, TimeOptimalOptions, TimingLimits,
};
use screwdyn::sim::{
    simulate, torque_profile, ComputedTorque, JointEffects, Recording, SimOptions, Trajectory,
};
use screwdyn::{builtin, Model, Workspace};

fn ur5_path() -> CubicSpline {
    CubicSpline::chord_length(&[
        vec![0.0, -1.8, 1.4, -1.2, -1.6, 0.0],
        vec![0.8, -1.2, 1.0, -1.4, -1.6, 0.5],
        vec![1.6, -1.6, 1.8, -1.0, -1.2, 1.0],
    ])
    .unwrap()
}

/// Simulates computed-torque control of `reference` on the exact model from its start, RK4
/// with step `dt`, recording every `record_every` steps.
fn track(
    m: &Model,
    reference: Box<dyn Trajectory + Send>,
    (dt, record_every): (f64, usize),
) -> Recording {
    let duration = reference.duration() + 0.05;
    let n = m.nq();
    let (mut q0, mut v0, mut a0) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    reference.sample(0.0, &mut q0, &mut v0, &mut a0).unwrap();
    let (kp, kd) = ComputedTorque::default_gains(n);
    let mut ct = ComputedTorque::new(m.clone(), reference, kp, kd).unwrap();
    let opts = SimOptions {
        duration,
        dt,
        record_every,
        effects: JointEffects::none(),
        ..Default::default()
    };
    simulate(m, &q0, &v0, &mut ct, &[], &opts, &mut |_| {}).unwrap()
}

/// The largest `|q − q_d|` along the run up to `until`, and the largest
/// `|τ − RNEA(q_d, q̇_d, q̈_d)|` as a fraction of the largest torque.
fn errors(m: &Model, run: &Recording, reference: &dyn Trajectory, until: f64) -> (f64, f64) {
    let n = m.nq();
    let mut ws = Workspace::new(m);
    let (mut q, mut v, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut e, mut dtau, mut peak) = (0.0_f64, 0.0_f64, 0.0_f64);
    for k in (0..run.t.len()).filter(|&k| run.t[k] <= until) {
        reference.sample(run.t[k], &mut q, &mut v, &mut a).unwrap();
        let tau = rnea(m, &mut ws, &q, &v, &a).unwrap();
        for j in 0..n {
            e = e.max((run.q[k][j] - q[j]).abs());
            dtau = dtau.max((run.tau[k][j] - tau[j]).abs());
            peak = peak.max(tau[j].abs());
        }
    }
    (e, dtau / peak)
}

#[test]
fn a_time_optimal_motion_read_back_from_its_samples_is_tracked_exactly() {
    let m = builtin::load("ur5").unwrap();
    let timed = time_optimal(
        &m,
        ur5_path(),
        &TimingLimits::from_model(&m),
        &TimeOptimalOptions::default(),
    )
    .unwrap();
    // The samples `torque-profile --output` writes, read back as a trajectory.
    let p = torque_profile(&m, &timed, 1e-3).unwrap();
    let r = &p.samples;
    let sampled =
        SampledTrajectory::new(r.t.clone(), r.q.clone(), r.v.clone(), r.a.clone()).unwrap();
    // Its accelerations jump between samples where s̈ switches, which the quintics between
    // samples follow with a large fifth derivative: RK4's local error `∝ h⁵ q⁽⁵⁾`, so the step
    // is a tenth of the sample step (and divides it). At the end the acceleration drops to 0
    // within the last, shorter interval, inside an RK4 step: exact up to the last full
    // sample, a small error after it, decaying.
    let run = track(&m, Box::new(sampled.clone()), (1e-4, 10));
    let last_full = r.t[r.t.len() - 2];
    let (e, dtau) = errors(&m, &run, &sampled, last_full);
    assert!(e < 1e-8, "tracking error {e} rad");
    let (e_end, _) = errors(&m, &run, &sampled, f64::INFINITY);
    assert!(e_end < 1e-4, "tracking error {e_end} rad after the end");
    assert!(
        dtau < 1e-6,
        "torque off the inverse dynamics by {dtau} of the peak"
    );
    // The torques are the profile's (inverse dynamics of the timed motion) at its samples.
    let mut worst = 0.0_f64;
    for (k, t) in r.t.iter().enumerate().filter(|(_, t)| **t <= last_full) {
        let i = run.t.iter().position(|x| (x - t).abs() < 1e-9).unwrap();
        for j in 0..m.nq() {
            worst = worst.max((run.tau[i][j] - r.tau[k][j]).abs() / m.joints()[j].limits.effort);
        }
    }
    assert!(
        worst < 1e-6,
        "torque off the profile's by {worst} of the limit"
    );
    // After the end it holds the last sample at rest.
    let (last, end) = (run.q.last().unwrap(), r.q.last().unwrap());
    for (x, y) in last.iter().zip(end) {
        assert!((x - y).abs() < 1e-4, "{x} against {y}");
    }
}

#[test]
fn a_jerk_limited_motion_is_tracked_exactly() {
    let m = builtin::load("ur5").unwrap();
    let q0 = [0.0, -1.5, 1.5, -1.0, -1.5, 0.0];
    let qf = [1.0, -1.0, 1.0, -1.5, -1.0, 0.5];
    let jl = JerkLimited::new(&q0, &qf, &[2.0; 6], &[8.0; 6], &[60.0; 6]).unwrap();
    let run = track(&m, Box::new(jl.clone()), (1e-3, 1));
    let (e, dtau) = errors(&m, &run, &jl, f64::INFINITY);
    assert!(e < 1e-7, "tracking error {e} rad");
    assert!(
        dtau < 1e-6,
        "torque off the inverse dynamics by {dtau} of the peak"
    );
}

#[test]
fn bad_samples_are_refused_naming_the_sample() {
    let row = || vec![vec![0.0; 2]; 3];
    let e = SampledTrajectory::new(vec![0.0, 0.1, 0.1], row(), row(), row()).unwrap_err();
    assert!(e.to_string().contains("sample 3"), "{e}");
    let e = SampledTrajectory::new(vec![0.5, 0.6, 0.7], row(), row(), row()).unwrap_err();
    assert!(e.to_string().contains("t = 0.5"), "{e}");
    let mut q = row();
    q[1][1] = f64::NAN;
    let e = SampledTrajectory::new(vec![0.0, 0.1, 0.2], q, row(), row()).unwrap_err();
    assert!(e.to_string().contains("sample 2"), "{e}");
}
