//! `M⁻¹` and `∂q̈/∂x = −M⁻¹ ∂τ/∂x` of `aba_derivatives`, formed by articulated-body sweeps
//! (`dynamics/articulated_inverse.rs`), against independent computations: `M⁻¹ M = 1` with `M`
//! from CRBA, the dense Cholesky inverse of `mass_matrix_inverse` (CRBA + `L⁻ᵀ L⁻¹`), the dense
//! products `−M⁻¹ ∂τ/∂x` with `∂τ/∂x` from `rnea_derivatives`, and central finite differences
//! of `aba`; on random chains (up to 200 joints), branched trees (several roots, nested
//! branches) and models with armature.

mod common;

use common::{random_inertia, random_tree, random_vec};
use nalgebra::{DMatrix, Vector3, Vector6};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::dynamics::{aba, aba_derivatives, crba, mass_matrix_inverse, rnea_derivatives};
use screwdyn::model::JointSpec;
use screwdyn::spatial::Se3;
use screwdyn::{Model, ModelBuilder, Workspace};

/// A serial chain of `n` revolute joints about random offset axes, random home poses and
/// inertias.
fn random_chain(rng: &mut StdRng, n: usize) -> Model {
    let mut b = ModelBuilder::new("chain");
    b.gravity(Vector3::new(0.0, 0.0, -9.81));
    for i in 0..n {
        let parent = if i == 0 {
            "base".to_string()
        } else {
            format!("l{}", i - 1)
        };
        let axis =
            Vector3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 1.0).normalize();
        let point = Vector3::new(rng.gen_range(-0.1..0.1), rng.gen_range(-0.1..0.1), 0.0);
        let l = -axis.cross(&point);
        let home = Se3::from_rpy(
            rng.gen_range(-0.5..0.5),
            rng.gen_range(-0.5..0.5),
            rng.gen_range(-0.5..0.5),
        )
        .with_translation(Vector3::new(0.05, 0.0, rng.gen_range(0.05..0.2)));
        b.link(
            &format!("l{i}"),
            &parent,
            JointSpec::revolute(&format!("j{i}"))
                .screw_in_child(Vector6::new(axis.x, axis.y, axis.z, l.x, l.y, l.z)),
            home,
            random_inertia(rng),
        );
    }
    b.build().expect("random chain is valid")
}

/// `model` with random armatures in `[0.05, 0.5)`.
fn with_armature(model: Model, rng: &mut StdRng) -> Model {
    let a: Vec<f64> = (0..model.nv()).map(|_| rng.gen_range(0.05..0.5)).collect();
    model.with_armature(&a).unwrap()
}

/// `max |a − b| / max |b|`.
fn relative(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    (a - b).amax() / b.amax()
}

/// The models of these tests, labelled: chains, branched trees, armatures; sizes on both sides
/// of the sweeps' block width.
fn models() -> Vec<(String, Model)> {
    let mut rng = StdRng::seed_from_u64(31);
    let mut out = Vec::new();
    for n in [1, 2, 3, 4, 5, 7, 8, 9, 13, 30] {
        out.push((format!("chain {n}"), random_chain(&mut rng, n)));
        out.push((format!("tree {n}"), random_tree(&mut rng, n, true)));
        let m = random_tree(&mut rng, n, false);
        out.push((
            format!("tree {n} with armature"),
            with_armature(m, &mut rng),
        ));
    }
    out.push(("tree 60".into(), random_tree(&mut rng, 60, true)));
    let chain = random_chain(&mut rng, 200);
    out.push((
        "chain 200 with armature".into(),
        with_armature(chain, &mut rng),
    ));
    out
}

#[test]
fn the_trees_branch() {
    // The sweeps keep one slot per nesting of branches: make sure nested branches and several
    // roots are among the models.
    let models = models();
    let branched = |m: &Model| {
        let p = m.parents();
        let roots = p.iter().filter(|x| x.is_none()).count();
        let fork = (0..p.len()).any(|i| p.iter().filter(|x| **x == Some(i)).count() > 1);
        (roots > 1, fork)
    };
    assert!(models.iter().any(|(_, m)| branched(m) == (true, true)));
}

#[test]
fn minv_by_sweeps_inverts_the_mass_matrix_and_matches_the_cholesky_inverse() {
    let mut rng = StdRng::seed_from_u64(7);
    for (label, m) in models() {
        let n = m.nv();
        let (q, v, tau) = (
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 5.0),
        );
        let mut ws = Workspace::new(&m);
        aba_derivatives(&m, &mut ws, &q, &v, &tau, None).unwrap();
        let minv = ws.mass_matrix_inverse.clone();
        let mut other = Workspace::new(&m);
        let mass = crba(&m, &mut other, &q).unwrap().clone();
        let eye = &minv * &mass;
        let err = (eye - DMatrix::<f64>::identity(n, n)).amax();
        assert!(err < 1e-9, "{label}: ‖M⁻¹ M − 1‖ = {err:e}");
        assert!(
            (&minv - minv.transpose()).amax() == 0.0,
            "{label}: M⁻¹ is not symmetric"
        );
        let dense = mass_matrix_inverse(&m, &mut other, &q).unwrap().clone();
        let rel = relative(&minv, &dense);
        assert!(
            rel < 1e-10,
            "{label}: M⁻¹ off the Cholesky inverse by {rel:e}"
        );
        // ∂q̈/∂q and ∂q̈/∂q̇ against the dense products −M⁻¹ ∂τ/∂x, ∂τ/∂x at q̈ = ABA(q, q̇, τ).
        let qdd = aba(&m, &mut other, &q, &v, &tau).unwrap().clone();
        rnea_derivatives(&m, &mut other, &q, &v, qdd.as_slice(), None).unwrap();
        for (got, dtau, what) in [
            (&ws.dqdd_dq, &other.dtau_dq, "dqdd_dq"),
            (&ws.dqdd_dv, &other.dtau_dv, "dqdd_dv"),
        ] {
            let want = -(&dense * dtau);
            let rel = relative(got, &want);
            assert!(rel < 1e-10, "{label}: {what} off −M⁻¹ ∂τ by {rel:e}");
        }
    }
}

#[test]
fn aba_derivatives_match_central_differences_on_a_branched_tree_with_armature() {
    let mut rng = StdRng::seed_from_u64(11);
    let m = with_armature(random_tree(&mut rng, 23, true), &mut rng);
    assert!(m.parents().iter().filter(|p| p.is_none()).count() > 1);
    let n = m.nv();
    let (q, v, tau) = (
        random_vec(&mut rng, n, 2.0),
        random_vec(&mut rng, n, 2.0),
        random_vec(&mut rng, n, 5.0),
    );
    let mut ws = Workspace::new(&m);
    aba_derivatives(&m, &mut ws, &q, &v, &tau, None).unwrap();
    let mut fd_ws = Workspace::new(&m);
    let h = 1e-6;
    let mut central = |which: usize| {
        let mut out = DMatrix::zeros(n, n);
        for j in 0..n {
            let mut x = [q.clone(), v.clone(), tau.clone()];
            x[which][j] += h;
            let plus = aba(&m, &mut fd_ws, &x[0], &x[1], &x[2]).unwrap().clone();
            x[which][j] -= 2.0 * h;
            let minus = aba(&m, &mut fd_ws, &x[0], &x[1], &x[2]).unwrap().clone();
            out.set_column(j, &((plus - minus) / (2.0 * h)));
        }
        out
    };
    for (which, got, what) in [
        (0, &ws.dqdd_dq, "dqdd_dq"),
        (1, &ws.dqdd_dv, "dqdd_dv"),
        (2, &ws.mass_matrix_inverse, "minv"),
    ] {
        let want = central(which);
        let err = (got - &want).amax() / want.amax().max(1.0);
        assert!(err < 1e-6, "{what}: off the central differences by {err:e}");
    }
}

#[test]
fn minv_by_sweeps_matches_the_cholesky_inverse_on_many_small_trees() {
    // Every shape of small tree the random builder makes (roots, forks, nested branches at
    // every position relative to the sweeps' blocks of columns).
    let mut rng = StdRng::seed_from_u64(3);
    for n in 1..40 {
        for _ in 0..20 {
            let m = random_tree(&mut rng, n, false);
            let q = random_vec(&mut rng, n, 2.0);
            let mut ws = Workspace::new(&m);
            aba_derivatives(&m, &mut ws, &q, &q, &q, None).unwrap();
            let mut other = Workspace::new(&m);
            let dense = mass_matrix_inverse(&m, &mut other, &q).unwrap().clone();
            let rel = relative(&ws.mass_matrix_inverse, &dense);
            assert!(rel < 1e-10, "parents {:?}: M⁻¹ off by {rel:e}", m.parents());
        }
    }
}
