//! Analytical derivatives of the dynamics (issue 15) against central finite differences of the
//! library's own RNEA and ABA, on random trees (revolute about unaligned and offset axes,
//! prismatic, helical; branching) and a chain that uses every special-cased joint shape
//! (axis-aligned revolute and prismatic, standard-DH offset axis, helical), with external
//! wrenches given both in body frames and in the base frame; plus the invariant
//! `∂τ/∂q̇ = 2 C(q, q̇)` (Christoffel Coriolis matrix, no wrenches).

mod common;

use common::{random_tree, random_vec};
use nalgebra::{DMatrix, Vector3, Vector6};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::dynamics::{
    aba_derivatives, coriolis_matrix, crba, forward_dynamics, inverse_dynamics,
    mass_matrix_inverse, rnea_derivatives, ExternalWrenches, ForwardMethod,
};
use screwdyn::model::{JointMotion, JointSpec};
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{Model, ModelBuilder, Workspace};

/// A chain whose joints take every special-cased `JointMotion` path.
fn special_chain() -> Model {
    let mut b = ModelBuilder::new("special");
    b.gravity(Vector3::new(0.2, -0.3, -9.81));
    let joints: [(JointSpec, Vector6<f64>); 6] = [
        (
            JointSpec::revolute("rz"),
            Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0),
        ),
        (
            JointSpec::revolute("offset"),
            Vector6::new(0.0, -1.0, 0.0, 0.2, 0.0, 0.1),
        ),
        (
            JointSpec::prismatic("px"),
            Vector6::new(0.0, 0.0, 0.0, -1.0, 0.0, 0.0),
        ),
        (
            JointSpec::helical("screw", 0.05),
            Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.05),
        ),
        (
            JointSpec::revolute("tilted"),
            Vector6::new(0.6, 0.8, 0.0, 0.1, -0.075, 0.3),
        ),
        (
            JointSpec::revolute("offset_x"),
            Vector6::new(1.0, 0.0, 0.0, 0.0, 0.3, -0.7),
        ),
    ];
    let mut parent = "base".to_string();
    for (k, (spec, screw)) in joints.into_iter().enumerate() {
        let name = format!("l{k}");
        let home = Se3::from_rpy(0.3 * k as f64, -0.2, 0.5 - 0.1 * k as f64)
            .with_translation(Vector3::new(0.1, 0.2 - 0.05 * k as f64, 0.3));
        let inertia = SpatialInertia::new(
            1.0 + 0.3 * k as f64,
            Vector3::new(0.05, -0.1, 0.15),
            nalgebra::Matrix3::new(0.03, 0.002, -0.001, 0.002, 0.04, 0.003, -0.001, 0.003, 0.05),
        );
        b.link(&name, &parent, spec.screw_in_child(screw), home, inertia);
        parent = name;
    }
    b.build().unwrap()
}

fn external(model: &Model, rng: &mut StdRng) -> ExternalWrenches {
    let mut ext = ExternalWrenches::new(model);
    for i in 0..model.nbodies() {
        let w = |rng: &mut StdRng| Vector6::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        ext.add_local(i, w(rng)).unwrap();
        if i % 2 == 1 {
            ext.add_world(i, w(rng)).unwrap();
        }
    }
    ext
}

/// Central differences of `f` (a joint-space vector function) about `x`, column by column.
fn central(x: &[f64], h: f64, mut f: impl FnMut(&[f64]) -> Vec<f64>) -> DMatrix<f64> {
    let n = x.len();
    let mut out = DMatrix::zeros(n, n);
    for j in 0..n {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[j] += h;
        xm[j] -= h;
        let (fp, fm) = (f(&xp), f(&xm));
        for i in 0..n {
            out[(i, j)] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    out
}

fn assert_matrix_close(got: &DMatrix<f64>, want: &DMatrix<f64>, tol: f64, what: &str) {
    let scale = want.amax().max(1.0);
    let err = (got - want).amax();
    assert!(
        err <= tol * scale,
        "{what}: off by {err:e} (scale {scale})\ngot {got}\nwant {want}"
    );
}

fn check_against_finite_differences(m: &Model, rng: &mut StdRng, label: &str) {
    let n = m.nv();
    let (q, v, a) = (
        random_vec(rng, n, 2.0),
        random_vec(rng, n, 2.0),
        random_vec(rng, n, 2.0),
    );
    let ext = external(m, rng);
    let mut ws = Workspace::new(m);
    let mut fd_ws = Workspace::new(m);
    let h = 1e-6;
    let tol = 1e-6;

    rnea_derivatives(m, &mut ws, &q, &v, &a, Some(&ext)).unwrap();
    let mut id = |q: &[f64], v: &[f64], a: &[f64]| -> Vec<f64> {
        inverse_dynamics(m, &mut fd_ws, q, v, a, Some(&ext))
            .unwrap()
            .as_slice()
            .to_vec()
    };
    let tau = id(&q, &v, &a);
    let err = (ws.tau.as_slice().iter().zip(&tau))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(err < 1e-10, "{label}: τ off by {err}");
    let dq = central(&q, h, |x| id(x, &v, &a));
    assert_matrix_close(&ws.dtau_dq, &dq, tol, &format!("{label}: dtau_dq"));
    let dv = central(&v, h, |x| id(&q, x, &a));
    assert_matrix_close(&ws.dtau_dv, &dv, tol, &format!("{label}: dtau_dv"));
    let da = central(&a, h, |x| id(&q, &v, x));
    assert_matrix_close(&ws.mass_matrix, &da, tol, &format!("{label}: dtau_da"));

    let tau_in = random_vec(rng, n, 5.0);
    aba_derivatives(m, &mut ws, &q, &v, &tau_in, Some(&ext)).unwrap();
    let mut fd = |q: &[f64], v: &[f64], t: &[f64]| -> Vec<f64> {
        forward_dynamics(m, &mut fd_ws, q, v, t, Some(&ext), ForwardMethod::Aba)
            .unwrap()
            .as_slice()
            .to_vec()
    };
    let dq = central(&q, h, |x| fd(x, &v, &tau_in));
    assert_matrix_close(&ws.dqdd_dq, &dq, tol, &format!("{label}: dqdd_dq"));
    let dv = central(&v, h, |x| fd(&q, x, &tau_in));
    assert_matrix_close(&ws.dqdd_dv, &dv, tol, &format!("{label}: dqdd_dv"));
    let dt = central(&tau_in, h, |x| fd(&q, &v, x));
    assert_matrix_close(&ws.mass_matrix_inverse, &dt, tol, &format!("{label}: minv"));
}

#[test]
fn derivatives_match_central_differences_on_random_trees() {
    let mut rng = StdRng::seed_from_u64(15);
    for t in 0..16 {
        let n = rng.gen_range(1..10);
        let m = random_tree(&mut rng, n, t % 4 != 0);
        check_against_finite_differences(&m, &mut rng, &format!("tree {t} (n = {n})"));
    }
}

#[test]
fn derivatives_match_central_differences_on_every_joint_shape() {
    let m = special_chain();
    let shapes: Vec<String> = m
        .motions()
        .iter()
        .map(|jm| format!("{jm:?}").split(' ').next().unwrap().to_string())
        .collect();
    for kind in [
        "RevoluteAxis",
        "RevoluteOffsetAxis",
        "PrismaticAxis",
        "General",
    ] {
        assert!(
            shapes.iter().any(|s| s == kind),
            "{kind} missing: {shapes:?}"
        );
    }
    assert!(matches!(m.motions()[3], JointMotion::General { .. }));
    let mut rng = StdRng::seed_from_u64(3);
    for t in 0..5 {
        check_against_finite_differences(&m, &mut rng, &format!("special chain {t}"));
    }
    for name in ["builtin:ur5", "builtin:panda", "builtin:planar2"] {
        let m = screwdyn::io::load_model(name).unwrap();
        check_against_finite_differences(&m, &mut rng, name);
    }
}

/// `∂(C(q, q̇) q̇)/∂q̇ = 2 C` when `C` is built from Christoffel symbols (`Γ_ijk = Γ_ikj`).
#[test]
fn velocity_derivative_is_twice_the_coriolis_matrix() {
    let mut rng = StdRng::seed_from_u64(21);
    for t in 0..8 {
        let n = rng.gen_range(1..9);
        let m = random_tree(&mut rng, n, t % 2 == 0);
        let (q, v, a) = (
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 2.0),
        );
        let mut ws = Workspace::new(&m);
        rnea_derivatives(&m, &mut ws, &q, &v, &a, None).unwrap();
        let dtau_dv = ws.dtau_dv.clone();
        let c = coriolis_matrix(&m, &mut ws, &q, &v).unwrap() * 2.0;
        assert_matrix_close(&dtau_dv, &c, 1e-12, &format!("tree {t}: dtau_dv vs 2C"));
        // And ∂τ/∂q̈ is the CRBA mass matrix; ∂q̈/∂τ its inverse.
        rnea_derivatives(&m, &mut ws, &q, &v, &a, None).unwrap();
        let mm = ws.mass_matrix.clone();
        assert_matrix_close(&mm, crba(&m, &mut ws, &q).unwrap(), 1e-12, "M");
        aba_derivatives(&m, &mut ws, &q, &v, &a, None).unwrap();
        let minv = ws.mass_matrix_inverse.clone();
        assert_matrix_close(
            &minv,
            mass_matrix_inverse(&m, &mut ws, &q).unwrap(),
            1e-12,
            "M⁻¹",
        );
    }
}

#[test]
fn bad_arguments_are_errors() {
    let m = special_chain();
    let mut ws = Workspace::new(&m);
    let z = vec![0.0; m.nv()];
    let e = rnea_derivatives(&m, &mut ws, &z[1..], &z, &z, None).unwrap_err();
    assert!(e.to_string().contains("q has 5 values"), "{e}");
    let mut bad = z.clone();
    bad[2] = f64::NAN;
    let e = rnea_derivatives(&m, &mut ws, &z, &bad, &z, None).unwrap_err();
    assert!(
        e.to_string().contains("v contains a non-finite value"),
        "{e}"
    );
    let e = aba_derivatives(&m, &mut ws, &z, &z, &bad, None).unwrap_err();
    assert!(
        e.to_string().contains("tau contains a non-finite value"),
        "{e}"
    );
    let other = screwdyn::builtin::planar2();
    let mut ws_other = Workspace::new(&other);
    let e = aba_derivatives(&m, &mut ws_other, &z, &z, &z, None).unwrap_err();
    assert!(e.to_string().contains("workspace was made"), "{e}");
}

/// The derivatives are generic over the scalar: in `f32` they agree with `f64` to single
/// precision.
#[test]
fn derivatives_work_in_f32() {
    let m64 = special_chain();
    let m32: Model<f32> = m64.cast();
    let (q, v, a) = ([0.3, -0.2, 0.1, 0.5, -0.4, 0.2], [0.5; 6], [-0.3; 6]);
    let mut ws64 = Workspace::new(&m64);
    let mut ws32 = Workspace::new(&m32);
    let f = |x: &[f64]| x.iter().map(|y| *y as f32).collect::<Vec<f32>>();
    aba_derivatives(&m64, &mut ws64, &q, &v, &a, None).unwrap();
    aba_derivatives(&m32, &mut ws32, &f(&q), &f(&v), &f(&a), None).unwrap();
    for (x32, x64) in [
        (&ws32.dtau_dq, &ws64.dtau_dq),
        (&ws32.dqdd_dq, &ws64.dqdd_dq),
        (&ws32.dqdd_dv, &ws64.dqdd_dv),
    ] {
        let back = x32.map(|x| x as f64);
        assert_matrix_close(&back, x64, 1e-3, "f32");
    }
}

/// Frame twist derivatives (world and local) against central differences of
/// `kinematics::frame_twist`.
#[test]
fn frame_velocity_derivatives_match_central_differences() {
    use nalgebra::Matrix6xX;
    use screwdyn::dynamics::frame_velocity_derivatives;
    use screwdyn::kinematics::{forward_velocity, frame_twist, Reference};
    let mut rng = StdRng::seed_from_u64(44);
    for t in 0..6 {
        let n = rng.gen_range(1..8);
        let m = random_tree(&mut rng, n, t % 2 == 0);
        let tool = m.frame_id("tool").unwrap();
        let (q, v) = (random_vec(&mut rng, n, 2.0), random_vec(&mut rng, n, 2.0));
        let mut ws = Workspace::new(&m);
        for reference in [Reference::World, Reference::Local] {
            let (mut dq, mut dv) = (Matrix6xX::zeros(n), Matrix6xX::zeros(n));
            frame_velocity_derivatives(&m, &mut ws, tool, reference, &q, &v, &mut dq, &mut dv)
                .unwrap();
            let mut fd_ws = Workspace::new(&m);
            let mut twist = |q: &[f64], v: &[f64]| {
                forward_velocity(&m, &mut fd_ws, q, v).unwrap();
                frame_twist(&m, &fd_ws, tool, reference).unwrap()
            };
            let h = 1e-6;
            for j in 0..n {
                let (mut qp, mut qm) = (q.clone(), q.clone());
                qp[j] += h;
                qm[j] -= h;
                let d = (twist(&qp, &v) - twist(&qm, &v)) / (2.0 * h);
                assert!((dq.column(j) - d).amax() < 1e-6, "{reference:?} dq col {j}");
                let (mut vp, mut vm) = (v.clone(), v.clone());
                vp[j] += h;
                vm[j] -= h;
                let d = (twist(&q, &vp) - twist(&q, &vm)) / (2.0 * h);
                assert!((dv.column(j) - d).amax() < 1e-6, "{reference:?} dv col {j}");
            }
        }
        let (mut dq, mut dv) = (Matrix6xX::zeros(n), Matrix6xX::zeros(n));
        let e = frame_velocity_derivatives(
            &m,
            &mut ws,
            tool,
            Reference::LocalWorldAligned,
            &q,
            &v,
            &mut dq,
            &mut dv,
        )
        .unwrap_err();
        assert!(e.to_string().contains("not local-world-aligned"));
    }
}
