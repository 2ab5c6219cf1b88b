//! Armature (the rotor inertia reflected to a joint, `I_a,i`) in every dynamics algorithm:
//! `M(q) = M_bodies(q) + diag(I_a)`, `τ = … + I_a q̈`. Each test uses non-zero armatures and
//! checks against independent evidence: an analytic pendulum, RNEA columns, `M⁻¹`, energy
//! balance, finite differences, and agreement between independent algorithms.

mod common;

use common::{assert_close, random_tree, random_vec};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3, Vector6};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::batch::{self, BatchWorkspace, Rows};
use screwdyn::dynamics::*;
use screwdyn::identification::{standard_parameters, BaseParameters, LeastSquares, Residuals};
use screwdyn::model::{JointSpec, ModelBuilder};
use screwdyn::sim::*;
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{Model, Workspace};
use std::f64::consts::PI;

/// A random tree (revolute, prismatic and helical joints) with armatures in `[0.05, 0.5)`.
fn tree_with_armature(seed: u64, n: usize) -> Model {
    let mut rng = StdRng::seed_from_u64(seed);
    let m = random_tree(&mut rng, n, true);
    let a: Vec<f64> = (0..n).map(|_| rng.gen_range(0.05..0.5)).collect();
    m.with_armature(&a).unwrap()
}

fn state(seed: u64, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut rng = StdRng::seed_from_u64(seed);
    (
        random_vec(&mut rng, n, 2.0),
        random_vec(&mut rng, n, 1.5),
        random_vec(&mut rng, n, 1.0),
    )
}

/// A rod pendulum about z: mass `m`, centre of mass `l` below the pivot, `I_zz` about the
/// centre of mass, armature `ia`; gravity −9.81 ŷ.
fn rod_pendulum(m: f64, l: f64, izz: f64, ia: f64) -> Model {
    let mut b = ModelBuilder::new("rod");
    b.gravity(Vector3::new(0.0, -9.81, 0.0)).link(
        "rod",
        "base",
        JointSpec::revolute("pivot")
            .screw_in_parent(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0))
            .armature(ia),
        Se3::identity(),
        SpatialInertia::new(
            m,
            Vector3::new(0.0, -l, 0.0),
            Matrix3::from_diagonal(&Vector3::new(0.1, 0.02, izz)),
        ),
    );
    b.build().unwrap()
}

#[test]
fn pendulum_with_armature_is_m_l2_plus_i_plus_ia() {
    let (mass, l, izz, ia) = (2.0, 0.5, 0.15, 0.3);
    let m = rod_pendulum(mass, l, izz, ia);
    let inertia = mass * l * l + izz + ia; // 0.95
    let mut ws = Workspace::new(&m);
    let (q, v, a) = (0.7_f64, -1.3, 2.1);
    let g = mass * 9.81 * l * q.sin();
    assert!((crba(&m, &mut ws, &[q]).unwrap()[(0, 0)] - inertia).abs() < 1e-14);
    assert!((rnea(&m, &mut ws, &[q], &[v], &[a]).unwrap()[0] - (inertia * a + g)).abs() < 1e-13);
    let tau = 1.7;
    let expect = (tau - g) / inertia;
    for method in [
        ForwardMethod::Aba,
        ForwardMethod::Crba,
        ForwardMethod::WalkerOrin,
    ] {
        let qdd = forward_dynamics(&m, &mut ws, &[q], &[v], &[tau], None, method).unwrap()[0];
        assert!(
            (qdd - expect).abs() < 1e-13,
            "{method:?}: {qdd} vs {expect}"
        );
    }
    let k = kinetic_energy(&m, &mut ws, &[q], &[v]).unwrap();
    assert!((k - 0.5 * inertia * v * v).abs() < 1e-14);
    let cf = closed_form(&m, &[q], &[v]).unwrap();
    assert!((cf.m[(0, 0)] - inertia).abs() < 1e-14);
    let nm = classic_newton_euler(&m, &[q], &[v], &[a]).unwrap();
    assert!((nm[0].tau - (inertia * a + g)).abs() < 1e-13);
}

#[test]
fn small_oscillations_of_a_pendulum_with_armature_have_its_period() {
    // T = 2π √((m l² + I + I_a) / (m g l)).
    let (mass, l, izz, ia) = (1.0, 0.8, 0.05, 0.4);
    let m = rod_pendulum(mass, l, izz, ia);
    let opts = SimOptions {
        duration: 8.0,
        dt: 1e-3,
        integrator: Integrator::Rk4,
        effects: JointEffects::none(),
        ..Default::default()
    };
    let run = simulate(
        &m,
        &[0.01],
        &[0.0],
        &mut ZeroTorque,
        &[],
        &opts,
        &mut |_| {},
    )
    .unwrap();
    let mut crossings = Vec::new();
    for k in 1..run.len() {
        let (a, b) = (run.q[k - 1][0], run.q[k][0]);
        if a > 0.0 && b <= 0.0 {
            crossings.push(run.t[k - 1] + (run.t[k] - run.t[k - 1]) * a / (a - b));
        }
    }
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let expected = 2.0 * PI * ((mass * l * l + izz + ia) / (mass * 9.81 * l)).sqrt();
    assert!(
        ((period - expected) / expected).abs() < 1e-3,
        "{period} vs {expected}"
    );
}

#[test]
fn mass_matrix_columns_are_rnea_at_unit_accelerations() {
    for seed in 0..4 {
        let n = 7;
        let m = tree_with_armature(seed, n);
        let (q, v, _) = state(100 + seed, n);
        let mut ws = Workspace::new(&m);
        let mm = crba(&m, &mut ws, &q).unwrap().clone();
        let g = gravity_torque(&m, &mut ws, &q).unwrap().clone();
        for i in 0..n {
            let mut e = vec![0.0; n];
            e[i] = 1.0;
            let col = rnea(&m, &mut ws, &q, &vec![0.0; n], &e).unwrap() - &g;
            assert_close(col.as_slice(), mm.column(i).as_slice(), 1e-12, "M column");
        }
        // The armature adds exactly diag(I_a) to the bodies' mass matrix.
        let bare = m.with_armature(&vec![0.0; n]).unwrap();
        let mut wb = Workspace::new(&bare);
        let diff = &mm - crba(&bare, &mut wb, &q).unwrap();
        let ia = DMatrix::from_diagonal(&DVector::from_iterator(
            n,
            m.joints().iter().map(|j| j.armature),
        ));
        assert!((diff - ia).amax() < 1e-12);
        // Every other route to M agrees: the closed form, the derivatives, Walker–Orin.
        let cf = closed_form(&m, &q, &v).unwrap();
        assert!((&cf.m - &mm).amax() < 1e-11);
        rnea_derivatives(&m, &mut ws, &q, &v, &vec![0.0; n], None).unwrap();
        assert!((&ws.mass_matrix - &mm).amax() < 1e-12);
        let zero = vec![0.0; n];
        forward_dynamics(&m, &mut ws, &q, &v, &zero, None, ForwardMethod::WalkerOrin).unwrap();
        assert!((&ws.mass_matrix - &mm).amax() < 1e-12);
    }
}

#[test]
fn every_inverse_dynamics_agrees_and_aba_inverts_it() {
    for seed in 0..4 {
        let n = 6;
        let m = tree_with_armature(10 + seed, n);
        let (q, v, a) = state(200 + seed, n);
        let mut ws = Workspace::new(&m);
        let tau = rnea(&m, &mut ws, &q, &v, &a).unwrap().clone();
        // τ = M q̈ + h with h = RNEA(q, q̇, 0).
        let h = nonlinear_effects(&m, &mut ws, &q, &v).unwrap().clone();
        let mm = crba(&m, &mut ws, &q).unwrap().clone();
        let a_vec = DVector::from_column_slice(&a);
        assert_close(
            tau.as_slice(),
            (&mm * &a_vec + &h).as_slice(),
            1e-12,
            "M a + h",
        );
        let cf = closed_form(&m, &q, &v).unwrap();
        let tau_cf = cf.inverse_dynamics(&a, None).unwrap();
        assert_close(tau_cf.as_slice(), tau.as_slice(), 1e-11, "closed form");
        let (_, _, tau_stacked) = cf.stacked_dynamics(&a).unwrap();
        assert_close(tau_stacked.as_slice(), tau.as_slice(), 1e-11, "stacked");
        let classic: Vec<f64> = classic_newton_euler(&m, &q, &v, &a)
            .unwrap()
            .iter()
            .map(|l| l.tau)
            .collect();
        assert_close(&classic, tau.as_slice(), 1e-12, "classic Newton–Euler");
        let trace = rnea_trace(&m, &q, &v, &a, None).unwrap();
        assert_close(&trace.tau, tau.as_slice(), 1e-15, "trace");
        rnea_derivatives(&m, &mut ws, &q, &v, &a, None).unwrap();
        assert_close(
            ws.tau.as_slice(),
            tau.as_slice(),
            1e-12,
            "derivative passes' τ",
        );
        // Forward dynamics three ways returns q̈ = M⁻¹(τ − h) = a.
        for method in [
            ForwardMethod::Aba,
            ForwardMethod::Crba,
            ForwardMethod::WalkerOrin,
        ] {
            let qdd = forward_dynamics(&m, &mut ws, &q, &v, tau.as_slice(), None, method).unwrap();
            assert_close(qdd.as_slice(), &a, 1e-10, "forward dynamics");
        }
        let minv = mass_matrix_inverse(&m, &mut ws, &q).unwrap().clone();
        let via_inverse = &minv * (&tau - &h);
        assert_close(via_inverse.as_slice(), &a, 1e-10, "M⁻¹(τ − h)");
    }
}

#[test]
fn kinetic_energy_includes_the_rotors_and_its_rate_is_the_power() {
    for seed in 0..3 {
        let n = 6;
        let m = tree_with_armature(20 + seed, n);
        let (q, v, tau) = state(300 + seed, n);
        let mut ws = Workspace::new(&m);
        let k = kinetic_energy(&m, &mut ws, &q, &v).unwrap();
        let k_m = kinetic_energy_mass_matrix(&m, &mut ws, &q, &v).unwrap();
        assert!((k - k_m).abs() < 1e-12 * k.abs().max(1.0), "{k} vs {k_m}");
        // d/dt (K + P) = q̇ᵀ τ along the motion q̈ = FD(q, q̇, τ), by central differences of
        // the second-order Taylor path.
        let qdd = aba(&m, &mut ws, &q, &v, &tau).unwrap().clone();
        let h = 1e-5;
        let mut energy_at = |s: f64| {
            let qs: Vec<f64> = (0..n)
                .map(|i| q[i] + s * v[i] + 0.5 * s * s * qdd[i])
                .collect();
            let vs: Vec<f64> = (0..n).map(|i| v[i] + s * qdd[i]).collect();
            total_energy(&m, &mut ws, &qs, &vs).unwrap()
        };
        let rate = (energy_at(h) - energy_at(-h)) / (2.0 * h);
        let p = power(&m, &tau, &v).unwrap();
        assert!((rate - p).abs() < 1e-6 * p.abs().max(1.0), "{rate} vs {p}");
    }
}

#[test]
fn derivatives_with_armature_match_finite_differences() {
    let n = 5;
    let m = tree_with_armature(30, n);
    let (q, v, a) = state(400, n);
    let mut ws = Workspace::new(&m);
    let h = 1e-6;
    rnea_derivatives(&m, &mut ws, &q, &v, &a, None).unwrap();
    let (dq, dv, mm) = (
        ws.dtau_dq.clone(),
        ws.dtau_dv.clone(),
        ws.mass_matrix.clone(),
    );
    let mut fd = |x: &[f64], which: usize, j: usize| {
        let (mut p, mut n_) = (x.to_vec(), x.to_vec());
        p[j] += h;
        n_[j] -= h;
        let (tp, tn) = match which {
            0 => (
                rnea(&m, &mut ws, &p, &v, &a).unwrap().clone(),
                rnea(&m, &mut ws, &n_, &v, &a).unwrap().clone(),
            ),
            1 => (
                rnea(&m, &mut ws, &q, &p, &a).unwrap().clone(),
                rnea(&m, &mut ws, &q, &n_, &a).unwrap().clone(),
            ),
            _ => (
                rnea(&m, &mut ws, &q, &v, &p).unwrap().clone(),
                rnea(&m, &mut ws, &q, &v, &n_).unwrap().clone(),
            ),
        };
        (tp - tn) / (2.0 * h)
    };
    for j in 0..n {
        assert_close(
            fd(&q, 0, j).as_slice(),
            dq.column(j).as_slice(),
            1e-6,
            "∂τ/∂q",
        );
        assert_close(
            fd(&v, 1, j).as_slice(),
            dv.column(j).as_slice(),
            1e-6,
            "∂τ/∂q̇",
        );
        assert_close(
            fd(&a, 2, j).as_slice(),
            mm.column(j).as_slice(),
            1e-6,
            "∂τ/∂q̈",
        );
    }
    let tau = a.clone();
    aba_derivatives(&m, &mut ws, &q, &v, &tau, None).unwrap();
    let (dqdd_dq, dqdd_dv, minv) = (
        ws.dqdd_dq.clone(),
        ws.dqdd_dv.clone(),
        ws.mass_matrix_inverse.clone(),
    );
    let mut fd_aba = |which: usize, j: usize| {
        let x = [&q, &v, &tau][which];
        let (mut p, mut n_) = (x.to_vec(), x.to_vec());
        p[j] += h;
        n_[j] -= h;
        let mut at = |y: &[f64]| match which {
            0 => aba(&m, &mut ws, y, &v, &tau).unwrap().clone(),
            1 => aba(&m, &mut ws, &q, y, &tau).unwrap().clone(),
            _ => aba(&m, &mut ws, &q, &v, y).unwrap().clone(),
        };
        (at(&p) - at(&n_)) / (2.0 * h)
    };
    for j in 0..n {
        assert_close(
            fd_aba(0, j).as_slice(),
            dqdd_dq.column(j).as_slice(),
            1e-6,
            "∂q̈/∂q",
        );
        assert_close(
            fd_aba(1, j).as_slice(),
            dqdd_dv.column(j).as_slice(),
            1e-6,
            "∂q̈/∂q̇",
        );
        assert_close(
            fd_aba(2, j).as_slice(),
            minv.column(j).as_slice(),
            1e-6,
            "∂q̈/∂τ",
        );
    }
}

#[test]
fn batch_kernels_agree_with_the_single_state_algorithms() {
    let n = 6;
    let m = tree_with_armature(40, n);
    let states = 11; // one group of eight and three one by one
    let mut rng = StdRng::seed_from_u64(500);
    let q = random_vec(&mut rng, states * n, 2.0);
    let v = random_vec(&mut rng, states * n, 1.5);
    let a = random_vec(&mut rng, states * n, 1.0);
    let mut bws = BatchWorkspace::new(&m);
    let mut tau = vec![0.0; states * n];
    let mut mm = vec![0.0; states * n * n];
    let mut qdd = vec![0.0; states * n];
    batch::rnea(
        &m,
        &mut bws,
        Rows::Stacked(&q),
        Rows::Stacked(&v),
        Rows::Stacked(&a),
        &mut tau,
    )
    .unwrap();
    batch::crba(&m, &mut bws, Rows::Stacked(&q), &mut mm).unwrap();
    batch::aba(
        &m,
        &mut bws,
        Rows::Stacked(&q),
        Rows::Stacked(&v),
        Rows::Stacked(&tau),
        &mut qdd,
    )
    .unwrap();
    let mut ws = Workspace::new(&m);
    for s in 0..states {
        let r = s * n..(s + 1) * n;
        let t = rnea(&m, &mut ws, &q[r.clone()], &v[r.clone()], &a[r.clone()]).unwrap();
        assert_close(&tau[r.clone()], t.as_slice(), 1e-12, "batch RNEA");
        let single = crba(&m, &mut ws, &q[r.clone()]).unwrap();
        assert_close(
            &mm[s * n * n..(s + 1) * n * n],
            single.as_slice(),
            1e-12,
            "batch CRBA",
        );
        // ABA of RNEA's torque gives back the acceleration.
        assert_close(&qdd[r.clone()], &a[r], 1e-9, "batch ABA");
    }
}

#[test]
fn regressor_leaves_the_known_armature_term_and_identification_subtracts_it() {
    let n = 5;
    let m = tree_with_armature(50, n);
    let mut ws = Workspace::new(&m);
    let pi = model_parameters(&m);
    let mut known = vec![0.0; n];
    for seed in 0..3 {
        let (q, v, a) = state(600 + seed, n);
        let tau = rnea(&m, &mut ws, &q, &v, &a).unwrap().clone();
        armature_torque(&m, &a, &mut known).unwrap();
        let y = regressor(&m, &mut ws, &q, &v, &a).unwrap();
        let t = y * &pi + DVector::from_column_slice(&known);
        assert_close(t.as_slice(), tau.as_slice(), 1e-11, "Y π + I_a q̈");
    }
    // Noise-free torques of a model with armature: least squares recovers the base parameters
    // exactly, and the residuals vanish.
    let base = BaseParameters::new(&m, false, 60, 3).unwrap();
    let truth = base.base_values(&standard_parameters(&m, false));
    let mut ls = LeastSquares::new(&m, base.clone());
    let mut log = Vec::new();
    for seed in 0..40 {
        let (q, v, a) = state(700 + seed, n);
        let tau = rnea(&m, &mut ws, &q, &v, &a).unwrap().as_slice().to_vec();
        ls.add(&m, &q, &v, &a, &tau).unwrap();
        log.push((q, v, a, tau));
    }
    let est = ls.solve().unwrap();
    assert_close(
        est.values.as_slice(),
        truth.as_slice(),
        1e-8,
        "base parameters",
    );
    let mut res = Residuals::new(&m, &base);
    let mut pred = vec![0.0; n];
    for (q, v, a, tau) in &log {
        res.add(&m, &base, &est.values, q, v, a, tau, &mut pred)
            .unwrap();
        assert_close(&pred, tau, 1e-8, "predicted torque");
    }
}

#[test]
fn passive_tree_with_armature_conserves_energy() {
    let n = 5;
    let m = tree_with_armature(60, n)
        .with_gravity(Vector3::zeros())
        .unwrap();
    let (q, v, _) = state(800, n);
    let opts = SimOptions {
        duration: 0.5,
        dt: 5e-4,
        integrator: Integrator::Rk4,
        effects: JointEffects::none(),
        ..Default::default()
    };
    let run = simulate(&m, &q, &v, &mut ZeroTorque, &[], &opts, &mut |_| {}).unwrap();
    let mut ws = Workspace::new(&m);
    // The recorded kinetic energy is ½ q̇ᵀ M q̇ with the armature.
    let last = run.len() - 1;
    let k_last = kinetic_energy_mass_matrix(&m, &mut ws, &run.q[last], &run.v[last]).unwrap();
    assert!((run.kinetic_energy[last] - k_last).abs() < 1e-12 * k_last);
    let e0 = run.total_energy[0];
    let drift = run
        .total_energy
        .iter()
        .fold(0.0_f64, |d, e| d.max((e - e0).abs()))
        / e0;
    assert!(drift < 1e-6, "relative energy drift {drift}");
}

#[test]
fn negative_or_non_finite_armature_is_refused() {
    let spec = |a: f64| {
        let mut b = ModelBuilder::new("bad");
        b.link(
            "l",
            "base",
            JointSpec::revolute("j")
                .screw_in_parent(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0))
                .armature(a),
            Se3::identity(),
            SpatialInertia::point_mass(1.0, Vector3::x()),
        );
        b.build()
    };
    for a in [-0.1, f64::NAN, f64::INFINITY] {
        let e = spec(a).unwrap_err().to_string();
        assert!(e.contains("joint 'j'") && e.contains("armature"), "{e}");
    }
    assert!(spec(0.2).is_ok());
    let e = screwdyn::builtin::planar2()
        .with_armature(&[0.1])
        .unwrap_err()
        .to_string();
    assert!(e.contains("armature"), "{e}");
}

#[test]
fn toml_formats_read_the_armature_key() {
    use screwdyn::io::{load_str, LoadOptions};
    let o = LoadOptions::default();
    let native = r#"
format = "screwdyn"
[[body]]
name = "l1"
parent = "base"
type = "revolute"
screw_in_parent = [0, 0, 1, 0, 0, 0]
armature = 0.25
mass = 1.0
com = [0.5, 0, 0]
"#;
    let m = load_str(native, "n.toml", &o).unwrap();
    assert_eq!(m.joints()[0].armature, 0.25);
    // M = m l² + I_a for the point mass 0.5 m from the axis.
    let mut ws = Workspace::new(&m);
    assert!((crba(&m, &mut ws, &[0.4]).unwrap()[(0, 0)] - (0.25 + 0.25)).abs() < 1e-14);
    let dh = "format = \"dh\"\n[[row]]\ntype = \"P\"\narmature = 0.5\nmass = 2.0\n";
    let m = load_str(dh, "d.toml", &o).unwrap();
    let mut ws = Workspace::new(&m);
    assert!((crba(&m, &mut ws, &[0.1]).unwrap()[(0, 0)] - 2.5).abs() < 1e-14);
    let poe = r#"
format = "poe"
Slist = [[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0]]
Mlist = [[[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
         [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]]
Glist = [[[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]],
         [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]]
armature = [0.1, 0.2]
"#;
    let m = load_str(poe, "p.toml", &o).unwrap();
    assert_eq!(
        m.joints().iter().map(|j| j.armature).collect::<Vec<_>>(),
        [0.1, 0.2]
    );
    let e = load_str(&poe.replace("[0.1, 0.2]", "[0.1]"), "p.toml", &o)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("p.toml") && e.contains("armature"), "{e}");
    let e = load_str(&native.replace("0.25", "-1.0"), "n.toml", &o)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("n.toml") && e.contains("armature must be non-negative"),
        "{e}"
    );
}
