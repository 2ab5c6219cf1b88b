//! Simulation against physics: the small-angle pendulum period, energy conservation and decay,
//! integrator agreement, computed-torque tracking, and torque profiles equal to RNEA.

use screwdyn::dynamics::{inverse_dynamics, ForwardMethod};
use screwdyn::sim::*;
use screwdyn::{builtin, Workspace};
use std::f64::consts::PI;

fn passive(duration: f64, dt: f64, integrator: Integrator, every: usize) -> SimOptions {
    SimOptions {
        duration,
        dt,
        integrator,
        effects: JointEffects::none(),
        record_every: every,
        ..Default::default()
    }
}

/// A passive run (no torque, no disturbance) from `(q0, v0)`.
fn run_passive(m: &screwdyn::Model, q0: &[f64], v0: &[f64], opts: &SimOptions) -> Recording {
    simulate(m, q0, v0, &mut ZeroTorque, &[], opts, &mut |_| {}).unwrap()
}

#[test]
fn pendulum_small_amplitude_period_matches_two_pi_sqrt_l_over_g() {
    let (l, g) = (0.8, 9.81);
    let m = builtin::pendulum_with(l, 1.0);
    let run = run_passive(&m, &[0.01], &[0.0], &passive(6.0, 1e-3, Integrator::Rk4, 1));
    // Downward zero crossings of q, linearly interpolated.
    let mut crossings = Vec::new();
    for k in 1..run.len() {
        let (a, b) = (run.q[k - 1][0], run.q[k][0]);
        if a > 0.0 && b <= 0.0 {
            crossings.push(run.t[k - 1] + (run.t[k] - run.t[k - 1]) * a / (a - b));
        }
    }
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let expected = 2.0 * PI * (l / g).sqrt();
    assert!(
        ((period - expected) / expected).abs() < 1e-3,
        "{period} vs {expected}"
    );
}

fn ur5_start() -> (Vec<f64>, Vec<f64>) {
    (
        vec![0.3, -1.2, 1.0, -0.5, 0.7, 0.2],
        vec![1.5, -1.3, 1.8, 1.2, -1.6, 2.0],
    )
}

/// `ZeroTorque` says it is zero, so the simulator keeps a zero torque instead of calling it:
/// the run is the one of a controller that is called at every evaluation and returns zeros
/// (`ConstantTorque` of zeros), to the bit, with and without joint effects.
#[test]
fn a_zero_controller_is_not_called_and_changes_nothing() {
    let m = builtin::load("ur5").unwrap();
    let (q0, v0) = ur5_start();
    assert!(ZeroTorque.is_zero() && !ConstantTorque(vec![0.0; 6]).is_zero());
    for effects in [JointEffects::none(), JointEffects::default()] {
        let opts = SimOptions {
            effects,
            ..passive(0.2, 1e-3, Integrator::Rk4, 1)
        };
        let skipped = simulate(&m, &q0, &v0, &mut ZeroTorque, &[], &opts, &mut |_| {}).unwrap();
        let mut zeros = ConstantTorque(vec![0.0; 6]);
        let called = simulate(&m, &q0, &v0, &mut zeros, &[], &opts, &mut |_| {}).unwrap();
        assert_eq!(skipped.q, called.q);
        assert_eq!(skipped.v, called.v);
        assert_eq!(skipped.tau, called.tau);
    }
}

/// The largest `|E(t) − E(0)|` over the samples `range` of a run.
fn energy_deviation(run: &Recording, range: std::ops::Range<usize>) -> f64 {
    let e0 = run.total_energy[0];
    run.total_energy[range]
        .iter()
        .map(|e| (e - e0).abs())
        .fold(0.0, f64::max)
}

fn max_energy_deviation(run: &Recording) -> f64 {
    energy_deviation(run, 0..run.len())
}

#[test]
fn passive_ur5_conserves_energy_with_rk4() {
    // Without gravity the energy is all kinetic, so the relative drift |E − E0| / E0 is well
    // defined; RK4 at 1 ms for 10 s from a non-trivial state (joints at up to 2 rad/s).
    let m = builtin::load("ur5")
        .unwrap()
        .with_gravity(nalgebra::Vector3::zeros())
        .unwrap();
    let (q0, v0) = ur5_start();
    let run = run_passive(&m, &q0, &v0, &passive(10.0, 1e-3, Integrator::Rk4, 100));
    let drift = max_energy_deviation(&run) / run.total_energy[0];
    assert!(drift < 1e-6, "RK4 relative energy drift {drift}");
}

/// A non-trivial state about the UR5's hanging rest (`q₂ ≈ π/2`, arm below the shoulder), with
/// every joint moving at up to 2 rad/s: under gravity the wrist reaches ~25 rad/s.
fn ur5_swinging_start() -> (Vec<f64>, Vec<f64>) {
    (vec![0.3, 1.9, -0.4, -1.0, 1.2, 0.5], ur5_start().1)
}

/// The largest `|E(t) − E(0)|` of a run over its largest kinetic energy (with gravity the
/// potential's zero is arbitrary, so `E(0)` is not a scale; the kinetic energy is).
fn drift_over_kinetic_scale(run: &Recording) -> f64 {
    let scale = run.kinetic_energy.iter().cloned().fold(0.0, f64::max);
    max_energy_deviation(run) / scale
}

#[test]
fn passive_ur5_under_gravity_conserves_energy_with_rk4() {
    // The test with gravity on: RK4 at 1 ms for 10 s, from a non-trivial state, drift
    // below 1e-6 of the energy scale (observed ~6e-9). Halving the step divides the drift by
    // ~2⁴ = 16 (RK4 is fourth order), so the drift is the integrator's truncation error and not
    // a bias in the dynamics (which no step size would remove).
    let m = builtin::load("ur5").unwrap();
    let (q0, v0) = ur5_swinging_start();
    let run = |dt: f64| run_passive(&m, &q0, &v0, &passive(10.0, dt, Integrator::Rk4, 10));
    let coarse = drift_over_kinetic_scale(&run(1e-3));
    assert!(coarse < 1e-6, "RK4 energy drift {coarse} at 1 ms");
    let fine = drift_over_kinetic_scale(&run(5e-4));
    assert!(
        coarse / fine > 8.0,
        "RK4 drift should fall ~16× when the step halves: {coarse} → {fine}"
    );
}

#[test]
fn falling_ur5_conserves_energy_with_rk4() {
    // With gravity the arm falls from rest and its 0.19 kg wrist whips past 140 rad/s; the
    // potential's zero is arbitrary, so the drift is measured against the largest kinetic
    // energy of the motion. At 1 ms RK4 drifts by about 8e-6 of it here (the wrist turns
    // 0.14 rad per step). At 0.5 ms the drift sat between 5e-7 and 1.2e-6 depending on
    // last-bit rounding in the dynamics (the fall is chaotic, so rounding picks which near-miss
    // of the wrist whip the run sees); at 0.25 ms it is about 6e-9, far from the bound.
    let m = builtin::load("ur5").unwrap();
    let q0 = [0.0, -1.57, 0.0, -1.57, 0.0, 0.0];
    let run = run_passive(
        &m,
        &q0,
        &[0.0; 6],
        &passive(10.0, 2.5e-4, Integrator::Rk4, 200),
    );
    let drift = drift_over_kinetic_scale(&run);
    assert!(
        drift < 1e-6,
        "RK4 energy drift {drift} of the kinetic scale"
    );
}

#[test]
fn symplectic_euler_energy_error_does_not_grow() {
    // Symplectic Euler at 1 ms: the energy error oscillates but shows no secular growth: the
    // second half of a 10 s run is no worse than the first half (with a 2× margin).
    let m = builtin::load("ur5")
        .unwrap()
        .with_gravity(nalgebra::Vector3::zeros())
        .unwrap();
    let (q0, v0) = ur5_start();
    let run = run_passive(
        &m,
        &q0,
        &v0,
        &passive(10.0, 1e-3, Integrator::SymplecticEuler, 10),
    );
    let e0 = run.total_energy[0];
    let half = run.len() / 2;
    let err = |r| energy_deviation(&run, r);
    let (first, second) = (err(0..half), err(half..run.len()));
    assert!(
        second < 2.0 * first,
        "Euler energy error grows: {first} then {second}"
    );
    assert!(
        first / e0 < 0.05,
        "Euler energy error too large: {}",
        first / e0
    );
}

#[test]
fn symplectic_euler_energy_error_stays_bounded_under_gravity() {
    // The swinging UR5 under gravity, symplectic Euler at 1 ms for 10 s: the energy error
    // settles (about 8 % of the kinetic scale) instead of growing; the second half of the run
    // is no worse than the first (2× margin), unlike explicit Euler whose error compounds.
    let m = builtin::load("ur5").unwrap();
    let (q0, v0) = ur5_swinging_start();
    let run = run_passive(
        &m,
        &q0,
        &v0,
        &passive(10.0, 1e-3, Integrator::SymplecticEuler, 10),
    );
    let scale = run.kinetic_energy.iter().cloned().fold(0.0, f64::max);
    let half = run.len() / 2;
    let err = |r| energy_deviation(&run, r) / scale;
    let (first, second) = (err(0..half), err(half..run.len()));
    assert!(
        second < 2.0 * first && second < 0.2,
        "Euler energy error grows: {first} then {second}"
    );
}

#[test]
fn dormand_prince_meets_its_tolerance_against_fine_rk4() {
    let m = builtin::load("ur5").unwrap();
    let (q0, v0) = ur5_start();
    let fine = run_passive(&m, &q0, &v0, &passive(1.0, 1e-4, Integrator::Rk4, 10_000));
    let tol = 1e-8;
    let dp = passive(
        1.0,
        1e-2,
        Integrator::DormandPrince {
            rtol: tol,
            atol: tol,
        },
        100,
    );
    let run = run_passive(&m, &q0, &v0, &dp);
    let (a, b) = (fine.q.last().unwrap(), run.q.last().unwrap());
    let err = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(err < 1e-6, "Dormand-Prince differs from fine RK4 by {err}");
}

#[test]
fn damping_makes_energy_decrease_monotonically() {
    let m = with_damping(&builtin::load("ur5").unwrap(), 0.05)
        .with_gravity(nalgebra::Vector3::zeros())
        .unwrap();
    let (q0, v0) = ur5_start();
    let opts = SimOptions {
        duration: 3.0,
        dt: 1e-3,
        effects: JointEffects {
            damping: true,
            ..JointEffects::none()
        },
        record_every: 10,
        ..Default::default()
    };
    let run = run_passive(&m, &q0, &v0, &opts);
    for k in 1..run.len() {
        assert!(
            run.total_energy[k] < run.total_energy[k - 1] + 1e-12,
            "energy rose at t = {}",
            run.t[k]
        );
    }
    // Power balance: the energy lost equals the work of the damping torques, ∫ Σ b q̇ᵢ² dt
    // (trapezoidal rule over the 10 ms samples).
    let power = |k: usize| run.v[k].iter().map(|x| 0.05 * x * x).sum::<f64>();
    let dissipated: f64 = (1..run.len())
        .map(|k| 0.5 * (power(k) + power(k - 1)) * (run.t[k] - run.t[k - 1]))
        .sum();
    let lost = run.total_energy[0] - run.total_energy[run.len() - 1];
    assert!(lost > 0.1 * run.total_energy[0]);
    assert!(
        (lost - dissipated).abs() < 1e-3 * lost,
        "lost {lost}, dissipated {dissipated}"
    );
}

fn with_damping(m: &screwdyn::Model, b: f64) -> screwdyn::Model {
    m.with_joint_friction(&vec![b; m.nq()], &vec![0.0; m.nq()])
        .unwrap()
}

#[test]
fn computed_torque_tracks_a_quintic_on_the_panda() {
    let m = builtin::load("panda").unwrap();
    let n = m.nq();
    let q0 = vec![0.0, -0.5, 0.0, -2.0, 0.0, 1.5, 0.7][..n.min(7)].to_vec();
    let mut q0 = q0;
    q0.resize(n, 0.01);
    let qf: Vec<f64> = q0
        .iter()
        .enumerate()
        .map(|(i, x)| x + 0.3 * if i % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let reference = Quintic::rest_to_rest(&q0, &qf, 2.0).unwrap();
    let mut ctrl = ComputedTorque::new(
        m.clone(),
        Box::new(reference.clone()),
        vec![100.0; n],
        vec![20.0; n],
    )
    .unwrap();
    let opts = SimOptions {
        duration: 2.5,
        dt: 1e-3,
        effects: JointEffects::none(),
        ..Default::default()
    };
    let run = simulate(&m, &q0, &vec![0.0; n], &mut ctrl, &[], &opts, &mut |_| {}).unwrap();
    let (mut qd, mut vd, mut ad) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut sum = 0.0;
    for k in 0..run.len() {
        reference
            .sample(run.t[k], &mut qd, &mut vd, &mut ad)
            .unwrap();
        sum += (0..n).map(|i| (run.q[k][i] - qd[i]).powi(2)).sum::<f64>() / n as f64;
    }
    let rms = (sum / run.len() as f64).sqrt();
    assert!(rms < 1e-6, "tracking RMS error {rms}");
}

#[test]
fn trapezoid_torque_profile_equals_rnea_and_flags_a_too_fast_profile() {
    let m = builtin::load("ur5").unwrap();
    let n = m.nq();
    let q0 = vec![0.0; n];
    let qf = vec![1.0, -0.8, 0.6, 0.4, -0.3, 0.2];
    let gentle = Trapezoid::new(&q0, &qf, &vec![0.5; n], &vec![0.5; n], true).unwrap();
    let p = torque_profile(&m, &gentle, 0.01).unwrap();
    let mut ws = Workspace::new(&m);
    for k in (0..p.samples.len()).step_by(7) {
        let s = &p.samples;
        let tau = inverse_dynamics(&m, &mut ws, &s.q[k], &s.v[k], &s.a[k], None).unwrap();
        for i in 0..n {
            assert!((tau[i] - s.tau[k][i]).abs() < 1e-12);
        }
    }
    for i in 0..n {
        let rms = (p.samples.tau.iter().map(|t| t[i] * t[i]).sum::<f64>() / p.samples.len() as f64)
            .sqrt();
        assert!((rms - p.rms[i]).abs() < 1e-9 * (1.0 + rms));
        assert!(p.samples.tau.iter().all(|t| t[i].abs() <= p.peak[i]));
    }
    assert!(
        p.violations.is_empty(),
        "gentle profile flagged: {:?}",
        &p.violations[..1]
    );
    // Far too fast: 50 rad/s², surely beyond the shoulder's effort limit.
    let brutal = Trapezoid::new(&q0, &qf, &vec![10.0; n], &vec![50.0; n], true).unwrap();
    let p = torque_profile(&m, &brutal, 0.005).unwrap();
    assert!(!p.violations.is_empty());
    let v = &p.violations[0];
    assert!(v.tau.abs() > v.limit && v.limit == m.joints()[v.joint].limits.effort);
}

#[test]
fn all_three_forward_methods_give_the_same_motion() {
    let m = builtin::load("ur5").unwrap();
    let (q0, v0) = ur5_start();
    let runs: Vec<_> = [
        ForwardMethod::Aba,
        ForwardMethod::Crba,
        ForwardMethod::WalkerOrin,
    ]
    .iter()
    .map(|&method| {
        simulate(
            &m,
            &q0,
            &v0,
            &mut ZeroTorque,
            &[],
            &SimOptions {
                method,
                ..passive(0.2, 1e-3, Integrator::Rk4, 200)
            },
            &mut |_| {},
        )
        .unwrap()
    })
    .collect();
    for r in &runs[1..] {
        for (a, b) in r.q.last().unwrap().iter().zip(runs[0].q.last().unwrap()) {
            assert!((a - b).abs() < 1e-9);
        }
    }
}

#[test]
fn a_disturbance_wrench_pushes_the_arm_only_while_active() {
    let m = builtin::planar2();
    let push = Disturbance {
        body: 1,
        wrench: nalgebra::Vector6::new(0.0, 0.0, 0.0, 0.0, 5.0, 0.0),
        in_world: true,
        start: 0.1,
        end: 0.2,
    };
    let opts = SimOptions {
        duration: 0.3,
        effects: JointEffects::none(),
        ..Default::default()
    };
    let g = m.with_gravity(nalgebra::Vector3::zeros()).unwrap();
    let run = simulate(
        &g,
        &[0.0, 0.0],
        &[0.0, 0.0],
        &mut ZeroTorque,
        &[push],
        &opts,
        &mut |_| {},
    )
    .unwrap();
    // Nothing moves before the push; afterwards the tip has been pushed towards +y.
    assert!(run.q[90].iter().all(|x| x.abs() < 1e-15));
    assert!(run.q[300][0] > 0.0);
    // After the push the energy is constant again (no gravity, no effects).
    let e = &run.total_energy;
    assert!((e[250] - e[300]).abs() < 1e-9 * e[300]);
}

/// A 1 m, 1 kg pendulum about z with the given joint limits and friction (I = m l² = 1 kg·m²).
fn limited_pendulum(lower: f64, upper: f64, effort: f64, friction: f64) -> screwdyn::Model {
    use screwdyn::model::{JointSpec, ModelBuilder};
    use screwdyn::spatial::{Se3, SpatialInertia};
    let mut b = ModelBuilder::new("limited");
    b.gravity(nalgebra::Vector3::zeros()).link(
        "bob",
        "base",
        JointSpec::revolute("pivot")
            .screw_in_parent(nalgebra::Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0))
            .limits(lower, upper)
            .effort_limit(effort)
            .friction(friction),
        Se3::from_translation(nalgebra::Vector3::new(0.0, -1.0, 0.0)),
        SpatialInertia::point_mass(1.0, nalgebra::Vector3::zeros()),
    );
    b.build().unwrap()
}

#[test]
fn position_limit_is_a_spring_damper_stop_scaled_to_the_joint() {
    // The stop is k = I/T², d = 2ζI/T with I the joint's inertia (1 kg·m² for this 1 kg, 1 m
    // pendulum), so the joint inside the stop is the oscillator ẍ + (2ζ/T) ẋ + x/T² = 0.
    // Critically damped (ζ = 1), entering at speed w: x(t) = w t e^{−t/T}, deepest w T / e, no
    // bounce. Underdamped (ζ = 0.2): it leaves at w e^{−ζπ/√(1−ζ²)} (the restitution of a
    // damped spring).
    let m = limited_pendulum(-0.2, 0.2, f64::INFINITY, 0.0);
    let (w, t) = (2.0, 0.01);
    let run_with = |zeta: f64, duration: f64| {
        let effects = JointEffects {
            friction: false,
            limit_time_constant: t,
            limit_damping_ratio: zeta,
            ..JointEffects::default()
        };
        let opts = SimOptions {
            duration,
            dt: 1e-5,
            effects,
            record_every: 10,
            ..Default::default()
        };
        run_passive(&m, &[0.0], &[w], &opts)
    };
    let run = run_with(1.0, 0.2);
    let deepest = run.q.iter().map(|q| q[0]).fold(f64::MIN, f64::max) - 0.2;
    let expected = w * t / std::f64::consts::E;
    assert!(
        (deepest - expected).abs() < 1e-3 * expected,
        "penetration {deepest} vs w T / e = {expected}"
    );
    let entered = run.q.iter().position(|q| q[0] > 0.2).unwrap();
    assert!(
        run.q[entered..].iter().all(|q| q[0] > 0.2 - 1e-9),
        "critically damped: no bounce out of the stop"
    );
    let zeta: f64 = 0.2;
    let run = run_with(zeta, 0.3);
    let out = run.v.last().unwrap()[0];
    let expected = -w * (-zeta * PI / (1.0 - zeta * zeta).sqrt()).exp();
    assert!(
        (out - expected).abs() < 1e-3 * expected.abs(),
        "exit speed {out} vs {expected}"
    );
}

#[test]
fn default_effects_keep_the_builtin_arms_stable_at_one_millisecond() {
    // Released at rest with every effect on, the UR5's and the Panda's joints swing into their
    // limit stops; the stops, scaled to each joint's inertia, keep RK4 at 1 ms stable (a single
    // stiffness for all joints made the light wrists diverge), and each joint stays within a
    // few stop time constants' travel of its limits.
    for name in ["ur5", "panda"] {
        let m = builtin::load(name).unwrap();
        let opts = SimOptions {
            duration: 10.0,
            dt: 1e-3,
            record_every: 10,
            ..Default::default()
        };
        let q0 = vec![0.0; m.nq()];
        let run = simulate(&m, &q0, &q0, &mut ZeroTorque, &[], &opts, &mut |_| {})
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        for (i, j) in m.joints().iter().enumerate() {
            let (lo, hi) = (j.limits.lower, j.limits.upper);
            let worst = run
                .q
                .iter()
                .map(|q| (lo - q[i]).max(q[i] - hi))
                .fold(f64::MIN, f64::max);
            assert!(
                worst < 0.5,
                "{name} joint {}: {worst} rad past its limit",
                j.name
            );
        }
    }
}
#[test]
fn coulomb_friction_holds_below_and_slips_above_its_level() {
    let m = limited_pendulum(-10.0, 10.0, f64::INFINITY, 0.5);
    let opts = SimOptions {
        duration: 1.0,
        dt: 1e-4,
        effects: JointEffects::default(),
        ..Default::default()
    };
    // 0.3 N·m < 0.5 N·m of friction: (almost) no motion, only the smoothing creep v = ε atanh(0.6).
    let run = simulate(
        &m,
        &[0.0],
        &[0.0],
        &mut ConstantTorque(vec![0.3]),
        &[],
        &opts,
        &mut |_| {},
    )
    .unwrap();
    let creep = opts.effects.friction_smoothing * (0.6f64).atanh();
    assert!((run.v.last().unwrap()[0] - creep).abs() < 1e-6);
    // 1 N·m: slides with q̈ = (1 − 0.5) / I once moving, so v(1 s) ≈ 0.5 rad/s.
    let run = simulate(
        &m,
        &[0.0],
        &[0.0],
        &mut ConstantTorque(vec![1.0]),
        &[],
        &opts,
        &mut |_| {},
    )
    .unwrap();
    assert!(
        (run.v.last().unwrap()[0] - 0.5).abs() < 2e-3,
        "{}",
        run.v.last().unwrap()[0]
    );
}

#[test]
fn effort_saturation_clamps_the_commanded_torque() {
    let m = limited_pendulum(-10.0, 10.0, 2.0, 0.0);
    let opts = SimOptions {
        duration: 1.0,
        dt: 1e-3,
        effects: JointEffects::default(),
        ..Default::default()
    };
    let run = simulate(
        &m,
        &[0.0],
        &[0.0],
        &mut ConstantTorque(vec![5.0]),
        &[],
        &opts,
        &mut |_| {},
    )
    .unwrap();
    // τ = min(5, 2) = 2 N·m on I = 1 kg·m²: q̈ = 2, v(1) = 2, q(1) = 1.
    assert!(run.tau.iter().all(|t| t[0] == 2.0));
    assert!(
        (run.v.last().unwrap()[0] - 2.0).abs() < 1e-9
            && (run.q.last().unwrap()[0] - 1.0).abs() < 1e-9
    );
}

/// Counts the calls of the torque law, applying no torque.
struct Counting(usize);

impl Controller for Counting {
    fn torque(&mut self, _t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]) -> screwdyn::Result<()> {
        self.0 += 1;
        tau.fill(0.0);
        Ok(())
    }
}

/// Recording a sample costs no extra evaluation of the dynamics: RK4 evaluates the state
/// equation four times per step, and the first evaluation of a step is at the state just
/// recorded, so a run of `N` steps evaluates it `4 N + 1` times (the last sample's) whether it
/// records every step or only the ends; and the recorded states are the same.
#[test]
fn recording_every_step_adds_no_dynamics_evaluation_and_changes_nothing() {
    let m = builtin::load("ur5").unwrap();
    let (q0, v0) = ur5_swinging_start();
    let steps = 200;
    let mut runs = Vec::new();
    for every in [1, 1_000_000] {
        let opts = passive(steps as f64 * 1e-3, 1e-3, Integrator::Rk4, every);
        let mut count = Counting(0);
        let run = simulate(&m, &q0, &v0, &mut count, &[], &opts, &mut |_| {}).unwrap();
        assert_eq!(count.0, 4 * steps + 1, "record_every = {every}");
        runs.push(run);
    }
    let (all, ends) = (&runs[0], &runs[1]);
    assert_eq!((all.len(), ends.len()), (steps + 1, 2));
    assert_eq!(all.q.last(), ends.q.last());
    assert_eq!(all.a.last(), ends.a.last());
}

/// A controller that returns `value` for joint `joint` (and 0 elsewhere) from `from` seconds on.
struct Bad {
    joint: usize,
    value: f64,
    from: f64,
}

impl Controller for Bad {
    fn torque(&mut self, t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]) -> screwdyn::Result<()> {
        tau.fill(0.0);
        if t >= self.from {
            tau[self.joint] = self.value;
        }
        Ok(())
    }
}

#[test]
fn a_non_finite_torque_or_acceleration_stops_the_run_naming_the_joint() {
    // The plant checks every torque and every acceleration it hands the stepper (ABA then does
    // not check them again): for each length of the vectorised check (1, 4 and 7 joints), a NaN
    // or infinite torque in any joint stops the run with an error naming that joint.
    for name in ["pendulum", "ur5", "panda"] {
        let m = builtin::load(name).unwrap();
        let n = m.nq();
        let opts = passive(0.1, 1e-3, Integrator::Rk4, 1);
        for joint in 0..n {
            for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                let mut c = Bad {
                    joint,
                    value,
                    from: 0.05,
                };
                let q0 = vec![0.1; n];
                let err = simulate(&m, &q0, &vec![0.0; n], &mut c, &[], &opts, &mut |_| {})
                    .unwrap_err()
                    .to_string();
                let name = &m.joints()[joint].name;
                assert!(
                    err.contains("non-finite torque") && err.contains(&format!("'{name}'")),
                    "{err}"
                );
            }
        }
        // A finite torque of 1e300 N·m makes the accelerations overflow: the run stops with
        // the divergence error, naming a joint, instead of integrating infinities.
        let mut c = Bad {
            joint: 0,
            value: 1e300,
            from: 0.0,
        };
        let err = simulate(
            &m,
            &vec![0.1; n],
            &vec![0.0; n],
            &mut c,
            &[],
            &opts,
            &mut |_| {},
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("became non-finite")
                && m.joints()
                    .iter()
                    .any(|j| err.contains(&format!("'{}'", j.name))),
            "{err}"
        );
    }
}
