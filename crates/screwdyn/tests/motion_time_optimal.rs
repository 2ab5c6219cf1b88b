//! Time-optimal timing (TOPP-RA) against analytic cases, and every result checked with inverse
//! dynamics.

use nalgebra::Vector3;
use screwdyn::motion::{time_optimal, CubicSpline, LimitKind, TimeOptimalOptions, TimingLimits};
use screwdyn::sim::{torque_profile, Trajectory};
use screwdyn::{builtin, Model};

/// A 0.5 m, 2 kg pendulum in zero gravity: constant inertia I = m l² = 0.5 kg·m².
fn free_pendulum() -> Model {
    builtin::pendulum_with(0.5, 2.0)
        .with_gravity(Vector3::zeros())
        .unwrap()
}

fn limits(v: f64, a: f64, tau: f64) -> TimingLimits {
    TimingLimits {
        velocity: vec![v],
        acceleration: vec![a],
        effort: vec![tau],
    }
}

fn line(d: f64) -> CubicSpline {
    CubicSpline::new(&[0.0, 1.0], &[vec![0.0], vec![d]]).unwrap()
}

#[test]
fn constant_inertia_under_a_torque_limit_is_bang_bang() {
    // Accelerate at τmax / I for half the distance, brake for the other: T = 2 √(d I / τmax),
    // with τmax the limit less the default margin of 10⁻⁴.
    let (d, inertia, limit) = (1.2, 0.5, 3.0);
    let tau = limit * (1.0 - 1e-4);
    let m = free_pendulum();
    let inf = f64::INFINITY;
    let timed = time_optimal(&m, line(d), &limits(inf, inf, limit), &Default::default()).unwrap();
    let expected = 2.0 * (d * inertia / tau).sqrt();
    assert!(
        (timed.duration() - expected).abs() < 1e-9 * expected,
        "{} vs {expected}",
        timed.duration()
    );
    // The torque is +τmax, then −τmax (inverse dynamics along the result).
    let p = torque_profile(&m, &timed, 1e-3).unwrap();
    for k in 0..p.samples.len() {
        let (t, tau_k) = (p.samples.t[k], p.samples.tau[k][0]);
        if (t - expected / 2.0).abs() > 2e-3 && t > 0.0 && t < expected - 1e-9 {
            assert!((tau_k.abs() - tau).abs() < 1e-9, "t = {t}: τ = {tau_k}");
            assert_eq!(tau_k > 0.0, t < expected / 2.0);
        }
    }
}

#[test]
fn a_velocity_limit_adds_a_cruise() {
    // Trapezoid: T = d / v + v I / τmax when the triangle would be faster than v.
    let (d, inertia, tau, v) = (3.0, 0.5, 3.0, 2.0);
    let m = free_pendulum();
    // The switch to cruising lies at s = v² I / (2 τmax d) = 1/9: exact on a grid of 900
    // intervals without the margin; within the duration tolerance on the refined grid.
    let fixed = TimeOptimalOptions {
        grid: Some(900),
        limit_margin: 0.0,
        ..Default::default()
    };
    let timed = time_optimal(&m, line(d), &limits(v, f64::INFINITY, tau), &fixed).unwrap();
    let expected = d / v + v * inertia / tau;
    assert!(
        (timed.duration() - expected).abs() < 1e-9 * expected,
        "{} vs {expected}",
        timed.duration()
    );
    let timed = time_optimal(
        &m,
        line(d),
        &limits(v, f64::INFINITY, tau),
        &Default::default(),
    )
    .unwrap();
    assert!(timed.duration() >= expected && timed.duration() < expected * (1.0 + 1e-3));
    assert!(timed.report().max_excess <= 0.0);
    // And an acceleration limit below τmax / I = 6 rad/s² takes over: T = d / v + v / a.
    let a = 4.0;
    let timed = time_optimal(&m, line(d), &limits(v, a, tau), &fixed).unwrap();
    let expected = d / v + v / a;
    assert!((timed.duration() - expected).abs() < 1e-9 * expected);
}

fn ur5_path() -> CubicSpline {
    CubicSpline::chord_length(&[
        vec![0.0, -1.8, 1.4, -1.2, -1.6, 0.0],
        vec![0.8, -1.2, 1.0, -1.4, -1.6, 0.5],
        vec![1.6, -1.6, 1.8, -1.0, -1.2, 1.0],
        vec![2.2, -1.0, 1.2, -1.6, -1.6, 0.3],
    ])
    .unwrap()
}

#[test]
fn ur5_within_its_limits_with_one_limit_active_at_every_instant() {
    let m = builtin::load("ur5").unwrap();
    let limits = TimingLimits {
        acceleration: vec![8.0; 6],
        ..TimingLimits::from_model(&m)
    };
    let timed = time_optimal(&m, ur5_path(), &limits, &Default::default()).unwrap();
    let report = timed.report();
    eprintln!("{report:?} duration {}", timed.duration());
    // Inverse dynamics along the result: every torque, speed and acceleration within its limit.
    let p = torque_profile(&m, &timed, 5e-4).unwrap();
    let rec = &p.samples;
    let mut saturated = 0;
    for k in 0..rec.len() {
        let mut nearest = 0.0_f64;
        for j in 0..6 {
            let r = [
                rec.tau[k][j].abs() / limits.effort[j],
                rec.v[k][j].abs() / limits.velocity[j],
                rec.a[k][j].abs() / limits.acceleration[j],
            ];
            for x in r {
                assert!(x <= 1.0, "t = {}: joint {j} at {x} of a limit", rec.t[k]);
                nearest = nearest.max(x);
            }
        }
        // Time-optimal: some limit is (within 3 %) reached at almost every instant: away from the
        // switches and the grid intervals around them (95.5 % of samples within 1 % at 1600 intervals).
        if nearest > 0.97 {
            saturated += 1;
        }
    }
    assert!(
        saturated as f64 > 0.97 * rec.len() as f64,
        "{saturated} of {}",
        rec.len()
    );
    // The duration has converged: a grid twice as fine changes it by less than 0.1 %, and it
    // decreases as the grid is refined (each grid's timing is feasible for the finer one).
    let &[.., (_, a), (_, b)] = report.durations.as_slice() else {
        panic!()
    };
    assert!((a - b).abs() < 1e-3 * b);
    assert!(report.durations.windows(2).all(|w| w[1].1 <= w[0].1));
    // It ends at rest at the last waypoint.
    let (mut q, mut v, mut acc) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    timed
        .sample(timed.duration(), &mut q, &mut v, &mut acc)
        .unwrap();
    assert!(q
        .iter()
        .zip([2.2, -1.0, 1.2, -1.6, -1.6, 0.3])
        .all(|(a, b)| (a - b).abs() < 1e-12));
    assert!(v.iter().all(|x| x.abs() < 1e-12));
}

/// `|x − y| ≤ 10⁻¹² max(|x|, |y|)` for every pair.
fn close(x: &[f64], y: &[f64]) -> bool {
    x.len() == y.len()
        && x.iter()
            .zip(y)
            .all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()))
}

#[test]
fn the_check_reports_the_torque_profile_at_its_step() {
    // The check's statistics are those of sim's torque profile of the result every
    // `check_step` (the same samples through Trajectory::sample), the check's torques from the
    // batch inverse dynamics (eight samples side by side in SIMD lanes, fused multiply–adds),
    // the profile's from the per-call RNEA: equal to round-off (10⁻¹² relative), the times,
    // counts and the sample count exactly. Timed within twice the model's effort limits, the
    // motion goes over the model's own limits, which both count against.
    let m = builtin::load("ur5").unwrap();
    let mut limits = TimingLimits::from_model(&m);
    limits.effort.iter_mut().for_each(|e| *e *= 2.0);
    limits.velocity = vec![f64::INFINITY; 6];
    let timed = time_optimal(&m, ur5_path(), &limits, &Default::default()).unwrap();
    let report = timed.report();
    let p = torque_profile(&m, &timed, TimeOptimalOptions::default().check_step).unwrap();
    let s = &report.profile;
    assert_eq!(s.samples, p.samples.len());
    assert!(close(&s.peak, &p.peak), "{:?} vs {:?}", s.peak, p.peak);
    assert!(close(&s.rms, &p.rms), "{:?} vs {:?}", s.rms, p.rms);
    assert_eq!(s.peak_time, p.peak_time);
    assert_eq!(s.effort_limit, p.effort_limit);
    for (ours, theirs) in s.violation_summary.iter().zip(&p.violation_summary) {
        match (ours, theirs) {
            (None, None) => {}
            (Some(a), Some(b)) => {
                assert_eq!((a.count, a.first_time), (b.count, b.first_time));
                assert!(close(&[a.worst], &[b.worst]), "{} vs {}", a.worst, b.worst);
            }
            _ => panic!("{ours:?} vs {theirs:?}"),
        }
    }
    assert!(s.violation_summary.iter().any(Option::is_some));
}

/// `|value| / limit − 1` of every sample, joint and kind of limit, recomputed sample by sample
/// with the per-call inverse dynamics (`torque_profile`, springs and friction included) at the
/// check's step.
fn excesses_by_profile(
    m: &Model,
    timed: &dyn Trajectory,
    limits: &TimingLimits,
) -> Vec<(f64, LimitKind, usize, f64)> {
    let p = torque_profile(m, timed, TimeOptimalOptions::default().check_step).unwrap();
    let rec = &p.samples;
    let mut all = Vec::new();
    for k in 0..rec.len() {
        for j in 0..m.nq() {
            for (kind, x) in [
                (LimitKind::Velocity, rec.v[k][j].abs() / limits.velocity[j]),
                (
                    LimitKind::Acceleration,
                    rec.a[k][j].abs() / limits.acceleration[j],
                ),
                (LimitKind::Torque, rec.tau[k][j].abs() / limits.effort[j]),
            ] {
                all.push((x - 1.0, kind, j, rec.t[k]));
            }
        }
    }
    all
}

#[test]
fn the_batched_check_agrees_with_the_per_sample_inverse_dynamics() {
    // UR5 (speed and torque limits) and Panda (acceleration and torque limits), five waypoints:
    // the check's largest excess and the torque statistics against the per-call RNEA sample by
    // sample, to 10⁻¹² relative.
    let ur5 = builtin::load("ur5").unwrap();
    let panda = builtin::load("panda").unwrap();
    let mut panda_limits = TimingLimits::from_model(&panda);
    panda_limits.velocity = vec![f64::INFINITY; 7];
    panda_limits.acceleration = vec![15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0];
    let cases = [
        (
            &ur5,
            TimingLimits::from_model(&ur5),
            vec![
                vec![-1.0, -2.0, 2.0, -1.5, -1.5, 0.0],
                vec![-0.3, -1.5, 1.2, -1.0, -1.2, 0.6],
                vec![0.4, -1.0, 0.6, -0.8, -1.6, 1.2],
                vec![1.0, -1.4, 1.5, -1.6, -2.0, 0.4],
                vec![1.8, -0.8, 0.8, -1.2, -1.4, -0.4],
            ],
        ),
        (
            &panda,
            panda_limits,
            vec![
                vec![-1.0, -0.3, 0.2, -2.2, 0.1, 1.6, 0.0],
                vec![-0.4, 0.3, -0.2, -1.6, 0.5, 2.2, 0.6],
                vec![0.2, 0.0, 0.3, -2.0, -0.2, 1.4, 1.2],
                vec![0.8, -0.4, -0.1, -2.6, 0.3, 1.9, 0.4],
                vec![1.4, 0.2, 0.2, -1.8, -0.4, 2.4, -0.3],
            ],
        ),
    ];
    for (m, limits, points) in cases {
        let options = TimeOptimalOptions {
            grid: Some(1000),
            ..Default::default()
        };
        let path = CubicSpline::chord_length(&points).unwrap();
        let timed = time_optimal(m, path, &limits, &options).unwrap();
        let report = timed.report();
        // The largest excess, and the excess of the sample, joint and kind the check names
        // (within 10⁻¹² of the largest: along a time-optimal motion many samples are as near).
        let all = excesses_by_profile(m, &timed, &limits);
        let largest = all.iter().map(|e| e.0).fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (report.max_excess - largest).abs() <= 1e-12,
            "{}: {} vs {largest}",
            m.name(),
            report.max_excess
        );
        let (kind, joint, t) = report.worst;
        let named = all
            .iter()
            .find(|e| (e.1, e.2, e.3) == (kind, joint, t))
            .unwrap();
        assert!(
            (named.0 - largest).abs() <= 1e-12,
            "{}: {named:?}",
            m.name()
        );
        let p = torque_profile(m, &timed, options.check_step).unwrap();
        assert!(close(&report.profile.peak, &p.peak), "{}", m.name());
        assert!(close(&report.profile.rms, &p.rms), "{}", m.name());
    }
}

#[test]
fn bad_input_is_one_sentence_naming_where() {
    let m = builtin::load("ur5").unwrap();
    let ok = TimingLimits::from_model(&m);
    let opts = TimeOptimalOptions::default();
    let err =
        |l: &TimingLimits, p: CubicSpline| time_optimal(&m, p, l, &opts).unwrap_err().to_string();
    // Gravity alone above an effort limit: the shoulder holding the stretched arm.
    let weak = TimingLimits {
        effort: vec![150.0, 20.0, 150.0, 28.0, 28.0, 28.0],
        ..ok.clone()
    };
    let e = err(&weak, ur5_path());
    assert!(
        e.contains("gravity alone needs 20.049 at joint shoulder_lift_joint at s = 0.325407, more than its effort limit 20 allows"),
        "{e}"
    );
    // Zero, negative and NaN limits.
    for bad in [0.0, -1.0, f64::NAN] {
        let mut l = ok.clone();
        l.velocity[2] = bad;
        assert!(err(&l, ur5_path()).contains("velocity limits must be positive"));
    }
    let short = TimingLimits {
        effort: vec![1.0],
        ..ok.clone()
    };
    assert!(err(&short, ur5_path()).contains("effort limits has 1 values"));
    // A waypoint outside the position limits (the Panda's fourth joint stays below −0.0698).
    let panda = builtin::load("panda").unwrap();
    let p = CubicSpline::chord_length(&[
        vec![0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0],
        vec![0.5, 0.0, 0.0, 0.0, 0.0, 1.5, 0.0],
    ])
    .unwrap();
    let e = time_optimal(&panda, p, &TimingLimits::from_model(&panda), &opts)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("position limits of joint") && e.contains("s = "),
        "{e}"
    );
    // A path of the wrong number of joints.
    assert!(err(&ok, line(1.0)).contains("the path has 1 joints"));
}

#[test]
fn refining_reuses_the_coarse_grid_exactly() {
    // Each refinement copies the rows of the previous grid's points instead of recomputing
    // them: every duration it reports is the one a fixed grid of that size gives on its own.
    let m = builtin::load("ur5").unwrap();
    let limits = TimingLimits::from_model(&m);
    let refined = time_optimal(&m, ur5_path(), &limits, &TimeOptimalOptions::default()).unwrap();
    let durations = &refined.report().durations;
    assert!(durations.len() >= 3, "{durations:?}");
    for &(grid, duration) in durations {
        let options = TimeOptimalOptions {
            grid: Some(grid),
            ..Default::default()
        };
        let fixed = time_optimal(&m, ur5_path(), &limits, &options).unwrap();
        assert_eq!(fixed.duration(), duration, "grid {grid}");
    }
}

#[test]
fn coulomb_friction_shifts_the_bang_bang_and_the_profile_shows_it() {
    // With Coulomb friction f against the motion the motor accelerates at (τmax − f) / I and
    // brakes at (τmax + f) / I (friction helps): v² = 2 a₁ d₁ = 2 a₂ d₂, d₁ + d₂ = d,
    // T = v / a₁ + v / a₂.
    let (d, inertia, limit, f) = (1.2, 0.5, 3.0, 0.8);
    let tau = limit * (1.0 - 1e-4);
    let m = free_pendulum().with_joint_friction(&[0.0], &[f]).unwrap();
    let inf = f64::INFINITY;
    let timed = time_optimal(&m, line(d), &limits(inf, inf, limit), &Default::default()).unwrap();
    let (a1, a2) = ((tau - f) / inertia, (tau + f) / inertia);
    let d1 = d * a2 / (a1 + a2);
    let v = (2.0 * a1 * d1).sqrt();
    let expected = v / a1 + v / a2;
    // The switch at s = a₂ / (a₁ + a₂) is not a grid point: the grid's timing is slower, to
    // first order in the interval.
    assert!(
        timed.duration() >= expected && timed.duration() < expected * (1.0 + 1e-4),
        "{} vs {expected}",
        timed.duration()
    );
    // The profile's τ is what the motor gives, friction included: +τmax accelerating, −τmax
    // braking, never over the limit (inverse dynamics alone would show τmax − f and τmax + f).
    let p = torque_profile(&m, &timed, 1e-3).unwrap();
    assert!(p.violations.is_empty(), "{:?}", p.violations.first());
    let switch = v / a1;
    for k in 0..p.samples.len() {
        let (t, tau_k) = (p.samples.t[k], p.samples.tau[k][0]);
        if (t - switch).abs() > 2e-3 && t > 0.0 && t < expected - 1e-9 {
            assert!((tau_k.abs() - tau).abs() < 1e-6, "t = {t}: τ = {tau_k}");
            assert_eq!(tau_k > 0.0, t < switch);
        }
    }
}

#[test]
fn a_joint_spring_is_part_of_the_timing() {
    // A spring k (q − 0) on the free pendulum needs k q to hold the joint: with k = 10 and
    // τmax = 3 the line from 0 to 1.2 rad is infeasible from q = 0.3, i.e. s = 0.25.
    let m = free_pendulum().with_springs(&[10.0], &[0.0]).unwrap();
    let inf = f64::INFINITY;
    let err = time_optimal(&m, line(1.2), &limits(inf, inf, 3.0), &Default::default())
        .unwrap_err()
        .to_string();
    let s: f64 = err
        .split("s = ")
        .nth(1)
        .and_then(|r| r.split(|c: char| c != '.' && !c.is_ascii_digit()).next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no s in: {err}"));
    assert!((s - 0.25).abs() < 0.01, "{err}");
    // Within reach of the spring (0 → 0.25 rad, k q ≤ 2.5 N·m) the profile's torques — spring
    // included — stay within the limit, and reach it while accelerating.
    let timed = time_optimal(&m, line(0.25), &limits(inf, inf, 3.0), &Default::default()).unwrap();
    let p = torque_profile(&m, &timed, 1e-3).unwrap();
    assert!(p.violations.is_empty(), "{:?}", p.violations.first());
    assert!((p.peak[0] - 3.0).abs() < 1e-2, "peak {}", p.peak[0]);
}
