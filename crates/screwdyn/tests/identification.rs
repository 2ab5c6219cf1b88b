//! Identification of inertial parameters (issue 15): base parameters by QR with pivoting
//! (`W_i π_b = Y π` at fresh states, the planar arm's known base parameters), least squares
//! from a noisy simulated log along an exciting Fourier trajectory (true base parameters
//! recovered within 5 standard deviations, held-out torques predicted to below the noise), the
//! physically consistent estimate, the Savitzky–Golay differentiator, and bad logs.

mod common;

use nalgebra::DVector;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::dynamics::rnea;
use screwdyn::identification::*;
use screwdyn::{Model, Workspace};

fn load(name: &str) -> Model {
    screwdyn::io::load_model(name).unwrap()
}

/// Standard normal by Box–Muller.
fn normal(rng: &mut StdRng) -> f64 {
    let (u1, u2): (f64, f64) = (rng.gen_range(1e-12..1.0), rng.gen_range(0.0..1.0));
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// τ = RNEA + fv q̇ + fc sign(q̇) (the model's joint damping and friction).
fn torque(m: &Model, ws: &mut Workspace, q: &[f64], v: &[f64], a: &[f64]) -> Vec<f64> {
    let mut tau = rnea(m, ws, q, v, a).unwrap().as_slice().to_vec();
    for (i, j) in m.joints().iter().enumerate() {
        tau[i] += j.damping * v[i] + j.friction * v[i].signum() * (v[i] != 0.0) as u8 as f64;
    }
    tau
}

#[test]
fn base_columns_reproduce_the_full_regressor() {
    for (name, friction) in [
        ("builtin:ur5", false),
        ("builtin:panda", true),
        ("builtin:branched", false),
        ("builtin:planar2", true),
    ] {
        let m = load(name);
        let b = BaseParameters::new(&m, friction, 40, 1).unwrap();
        let pi = standard_parameters(&m, friction);
        let pib = b.base_values(&pi);
        let mut ws = Workspace::new(&m);
        let mut y = nalgebra::DMatrix::zeros(m.nv(), parameter_count(&m, friction));
        let mut rng = StdRng::seed_from_u64(5);
        for _ in 0..5 {
            let q = common::random_vec(&mut rng, m.nv(), 3.0);
            let v = common::random_vec(&mut rng, m.nv(), 2.0);
            let a = common::random_vec(&mut rng, m.nv(), 2.0);
            full_regressor(&m, &mut ws, &q, &v, &a, friction, &mut y).unwrap();
            let full = &y * &pi;
            let base = b.base_columns(&y) * &pib;
            let want = torque(&m, &mut ws, &q, &v, &a);
            for i in 0..m.nv() {
                let scale = want[i].abs().max(1.0);
                assert!((full[i] - want[i]).abs() < 1e-12 * scale, "{name}: Yπ");
                assert!((base[i] - want[i]).abs() < 1e-9 * scale, "{name}: W_i π_b");
            }
        }
        assert!(
            b.rank() < pi.len(),
            "{name}: some parameters are not identifiable"
        );
    }
}

/// The planar two-link arm with gravity in its plane has six base parameters (Khalil &
/// Dombre); with each link frame at the link's far end (builtin:planar2's frames), the first
/// moments about the joints along the links are the classical `MX1R = mx1 + L1 m1 + L1 m2` and
/// `MX2R = mx2 + L2 m2`.
#[test]
fn planar_arm_base_parameters_are_the_textbook_ones() {
    let (l1, l2) = (0.7, 0.4);
    let m = screwdyn::builtin::planar2_with(l1, l2, 1.3, 0.8);
    let b = BaseParameters::new(&m, false, 60, 2).unwrap();
    assert_eq!(b.rank(), 6, "{:?}", b.expressions());
    let k = b.combination_matrix();
    let names = &b.standard_names;
    let col = |n: &str| names.iter().position(|x| x == n).unwrap();
    let row = |n: &str| b.independent.iter().position(|&i| i == col(n)).unwrap();
    let (r1, r2) = (row("mx_link1"), row("mx_link2"));
    for (r, n, want) in [
        (r1, "m_link1", l1),
        (r1, "m_link2", l1),
        (r2, "m_link2", l2),
        (r2, "m_link1", 0.0),
    ] {
        assert!(
            (k[(r, col(n))] - want).abs() < 1e-9,
            "{:?}",
            b.expressions()
        );
    }
    assert_eq!(b.expressions()[r2], "mx_link2 + 0.4 m_link2");
}

/// `(q, q̇, q̈, τ)` of one logged sample.
type LogRow = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

fn simulate_log(
    m: &Model,
    traj: &FourierTrajectory,
    samples: usize,
    dt: f64,
    noise: f64,
    rng: &mut StdRng,
) -> Vec<LogRow> {
    let mut ws = Workspace::new(m);
    (0..samples)
        .map(|k| {
            let (q, v, a) = traj.sample(k as f64 * dt);
            let mut tau = torque(m, &mut ws, &q, &v, &a);
            tau.iter_mut().for_each(|t| *t += noise * normal(rng));
            (q, v, a, tau)
        })
        .collect()
}

#[test]
fn noisy_fourier_log_recovers_the_base_parameters() {
    let m = load("builtin:ur5")
        .with_joint_friction(
            &[0.8, 0.6, 0.5, 0.2, 0.2, 0.1],
            &[1.5, 1.2, 1.0, 0.4, 0.3, 0.2],
        )
        .unwrap();
    let noise = 0.05;
    let mut rng = StdRng::seed_from_u64(11);
    let traj = FourierTrajectory::random(&m, 5, 2.0 * std::f64::consts::PI / 10.0, 4).unwrap();
    let log = simulate_log(&m, &traj, 1000, 0.02, noise, &mut rng);
    let base = BaseParameters::new(&m, true, 60, 3).unwrap();
    let truth = base.base_values(&standard_parameters(&m, true));
    let mut ls = LeastSquares::new(&m, base.clone());
    for (q, v, a, tau) in &log {
        ls.add(&m, q, v, a, tau).unwrap();
    }
    let est = ls.solve().unwrap();
    assert!(est.condition_number.is_finite() && est.condition_number > 1.0);
    assert!(
        (est.sigma - noise).abs() < 0.1 * noise,
        "σ = {} vs noise {noise}",
        est.sigma
    );
    for (i, expr) in base.expressions().iter().enumerate() {
        let err = (est.values[i] - truth[i]).abs();
        assert!(
            err <= 5.0 * est.std_dev[i] + 1e-9,
            "{expr}: {} vs true {} (σ {})",
            est.values[i],
            truth[i],
            est.std_dev[i]
        );
    }
    // Held-out trajectory: predicted torques match the noise-free ones to below the noise.
    let other = FourierTrajectory::random(&m, 5, 2.0 * std::f64::consts::PI / 8.0, 9).unwrap();
    let held = simulate_log(&m, &other, 500, 0.016, 0.0, &mut rng);
    let mut res = Residuals::new(&m, &base);
    let mut pred = vec![0.0; m.nv()];
    for (q, v, a, tau) in &held {
        res.add(&m, &base, &est.values, q, v, a, tau, &mut pred)
            .unwrap();
    }
    for (i, r) in res.rms().iter().enumerate() {
        assert!(*r < noise, "joint {i}: held-out RMS torque error {r}");
    }

    // The physically consistent estimate: every body consistent, friction non-negative, and
    // its torques almost as good on the held-out trajectory.
    let (r, z) = ls.factor();
    let pi = physical_estimate(&m, &base, &r, &z).unwrap();
    for b in 0..m.nbodies() {
        let p: Vec<f64> = pi.rows(10 * b, 10).iter().copied().collect();
        assert!(is_physically_consistent(&p), "body {b}: {p:?}");
    }
    assert!(pi.rows(60, 12).iter().all(|x| *x >= 0.0));
    let pib: DVector<f64> = base.base_values(&pi);
    // The library's one-call form gives the same numbers.
    let one_call = ls.physical_estimate(&m).unwrap();
    assert_eq!((&one_call.standard, &one_call.base_values), (&pi, &pib));
    let mut res = Residuals::new(&m, &base);
    for (q, v, a, tau) in &held {
        res.add(&m, &base, &pib, q, v, a, tau, &mut pred).unwrap();
    }
    for (i, r) in res.rms().iter().enumerate() {
        assert!(
            *r < 2.0 * noise,
            "joint {i}: physical estimate held-out RMS {r}"
        );
    }
}

/// The defaults both front-ends use (the command line's `--states`, Python's `states=` and
/// `seed=`) are the values they hard-coded before, and enough: more states drawn from another
/// seed find no further base parameter on any shipped robot.
#[test]
fn the_default_states_and_seed_find_every_base_parameter() {
    assert_eq!((DEFAULT_STATES, DEFAULT_SEED), (100, 1));
    for name in screwdyn::builtin::NAMES {
        let m = load(&format!("builtin:{name}"));
        for friction in [false, true] {
            let defaults = BaseParameters::with_defaults(&m, friction).unwrap();
            let same = BaseParameters::new(&m, friction, DEFAULT_STATES, DEFAULT_SEED).unwrap();
            assert_eq!(defaults.expressions(), same.expressions(), "{name}");
            let more = BaseParameters::new(&m, friction, 4 * DEFAULT_STATES, 7).unwrap();
            assert_eq!(defaults.rank(), more.rank(), "{name}, friction {friction}");
        }
    }
}

#[test]
fn bad_logs_are_one_sentence_errors() {
    let m = load("builtin:ur5");
    let base = BaseParameters::new(&m, false, 40, 3).unwrap();
    let mut ws = Workspace::new(&m);
    // Too few samples.
    let mut ls = LeastSquares::new(&m, base.clone());
    let (q, v, a) = (vec![0.1; 6], vec![0.2; 6], vec![0.3; 6]);
    let tau = torque(&m, &mut ws, &q, &v, &a);
    ls.add(&m, &q, &v, &a, &tau).unwrap();
    let e = ls.solve().unwrap_err().to_string();
    assert!(
        e.starts_with("too few samples: 1 sample(s) give 6 torque equations"),
        "{e}"
    );
    // Only the first joint moves: the other parameters are not excited.
    let mut ls = LeastSquares::new(&m, base.clone());
    for k in 0..500 {
        let t = k as f64 * 0.01;
        let (q, v, a) = (
            vec![t.sin(), 0.0, 0.0, 0.0, 0.0, 0.0],
            vec![t.cos(), 0.0, 0.0, 0.0, 0.0, 0.0],
            vec![-t.sin(), 0.0, 0.0, 0.0, 0.0, 0.0],
        );
        let tau = torque(&m, &mut ws, &q, &v, &a);
        ls.add(&m, &q, &v, &a, &tau).unwrap();
    }
    let e = ls.solve().unwrap_err().to_string();
    assert!(e.starts_with("the log is rank-deficient"), "{e}");
    // NaN torque.
    let e = ls
        .add(&m, &q, &v, &a, &[f64::NAN; 6])
        .unwrap_err()
        .to_string();
    assert!(e.contains("tau contains a non-finite value"), "{e}");
}

#[test]
fn savitzky_golay_differentiator_is_exact_on_quadratics_and_close_on_sines() {
    let mut d = VelocityDifferentiator::new(3).unwrap();
    let mut out = Vec::new();
    for k in 0..20 {
        // Uneven sampling.
        let t = k as f64 * 0.01 + 0.002 * (k % 3) as f64;
        let v = [1.0 + 2.0 * t - 3.0 * t * t, (5.0 * t).sin()];
        if let Some(s) = d.push(t, &[0.0, 0.0], &v, &[0.0, 0.0]).unwrap() {
            out.push(s);
        }
    }
    assert_eq!(
        out.len(),
        14,
        "the first and last 3 samples have no full window"
    );
    for s in &out {
        assert!((s.a[0] - (2.0 - 6.0 * s.t)).abs() < 1e-9);
        // Truncation error of the centred quadratic fit ≈ |v'''| Σs⁴ / (6 Σs²) ≈ 125 × 1.2e-4.
        assert!((s.a[1] - 5.0 * (5.0 * s.t).cos()).abs() < 2e-2);
    }
    assert!(
        d.push(0.0, &[0.0; 2], &[0.0; 2], &[0.0; 2]).is_err(),
        "time must increase"
    );
    assert!(VelocityDifferentiator::new(0).is_err());
}
