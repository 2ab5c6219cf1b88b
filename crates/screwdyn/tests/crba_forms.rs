//! The composite-rigid-body algorithm (everything in {0}, composite inertias by their ten
//! parameters) against `Σ_i J_iᵀ 𝔍_i J_i` built from the body Jacobians of forward kinematics,
//! an independent formula, on random trees with branches and on chains up to 200 joints, with
//! every kind of joint axis (coordinate axes with either sign, axes off the origin, general
//! screws), home rotations that are the identity, quarter turns about x or general, and
//! armatures (on the diagonal only); the result is symmetric and positive definite.
mod common;

use nalgebra::{DMatrix, Vector3, Vector6};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::dynamics::crba;
use screwdyn::kinematics::forward_kinematics;
use screwdyn::model::{JointSpec, ModelBuilder};
use screwdyn::spatial::{exp_so3, Se3};
use screwdyn::{Model, Workspace};

/// A random tree (a chain when `branch` is 0) whose joints mix every specialised axis shape.
fn mixed_axes(rng: &mut StdRng, n: usize, branch: f64) -> Model {
    let mut b = ModelBuilder::new("mixed");
    b.gravity(Vector3::new(0.0, 0.0, -9.81));
    for i in 0..n {
        let parent = if i == 0 || rng.gen_bool(branch) {
            "base".to_string()
        } else if branch == 0.0 {
            format!("l{}", i - 1)
        } else {
            format!("l{}", rng.gen_range(0..i))
        };
        random_link(rng, &mut b, i, &parent);
    }
    b.build().expect("valid model")
}

/// Adds link `l{i}` on `parent` by joint `j{i}`, of any specialised axis shape, with a random
/// home pose, armature and inertia.
fn random_link(rng: &mut StdRng, b: &mut ModelBuilder, i: usize, parent: &str) {
    let k = rng.gen_range(0..3);
    let sign = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
    let mut e = Vector3::zeros();
    e[k] = sign;
    let kind = rng.gen_range(0..5);
    let screw = match kind {
        // Revolute about ±ê_k through the origin (most arms), twice as likely.
        0 | 1 => Vector6::new(e.x, e.y, e.z, 0.0, 0.0, 0.0),
        2 => Vector6::new(0.0, 0.0, 0.0, e.x, e.y, e.z),
        3 => {
            // About ±ê_k through a point off the origin.
            let mut r = Vector3::new(rng.gen_range(-0.3..0.3), rng.gen_range(-0.3..0.3), 0.0);
            r[k] = 0.0;
            let l = r.cross(&e);
            Vector6::new(e.x, e.y, e.z, l.x, l.y, l.z)
        }
        _ => {
            let w =
                Vector3::new(rng.gen_range(-1.0..1.0), 0.4, rng.gen_range(-1.0..1.0)).normalize();
            let l = Vector3::new(0.1, -0.2, 0.05).cross(&w);
            Vector6::new(w.x, w.y, w.z, l.x, l.y, l.z)
        }
    };
    let spec = if kind == 2 {
        JointSpec::prismatic(&format!("j{i}"))
    } else {
        JointSpec::revolute(&format!("j{i}"))
    };
    // Home rotations as on real arms: the identity, a quarter turn about x written as
    // `rpy = (±π/2, 0, 0)` (entries within rounding of 0 and ±1), or anything.
    let quarter = std::f64::consts::FRAC_PI_2;
    let rotation = match rng.gen_range(0..4) {
        0 => nalgebra::Matrix3::identity(),
        1 => Se3::from_rpy(quarter, 0.0, 0.0).rotation,
        2 => Se3::from_rpy(-quarter, 0.0, 0.0).rotation,
        _ => exp_so3(&Vector3::new(
            rng.gen_range(-2.0..2.0),
            rng.gen_range(-2.0..2.0),
            rng.gen_range(-2.0..2.0),
        )),
    };
    let home = Se3::new(
        rotation,
        Vector3::new(
            rng.gen_range(-0.5..0.5),
            rng.gen_range(-0.5..0.5),
            rng.gen_range(-0.5..0.5),
        ),
    );
    b.link(
        &format!("l{i}"),
        parent,
        spec.screw_in_child(screw).armature(rng.gen_range(0.0..0.2)),
        home,
        common::random_inertia(rng),
    );
}

/// A chain `l0 … l{len−1}` on the base with leaf bodies: `leaves[j]` is the chain link the
/// j-th leaf hangs on (`None`: the base), declared after the chain except the leaves on the
/// base at even `j`, declared before it (so that the chain does not start at body 0).
fn chain_with_leaves(rng: &mut StdRng, len: usize, leaves: &[Option<usize>]) -> Model {
    let mut b = ModelBuilder::new("leaves");
    b.gravity(Vector3::new(0.0, 0.0, -9.81));
    let on = |p: Option<usize>| p.map_or("base".to_string(), |p| format!("l{p}"));
    for (j, p) in leaves.iter().enumerate() {
        if p.is_none() && j % 2 == 0 {
            random_link(rng, &mut b, len + j, "base");
        }
    }
    for i in 0..len {
        random_link(rng, &mut b, i, &on(i.checked_sub(1)));
    }
    for (j, p) in leaves.iter().enumerate() {
        if p.is_some() || j % 2 == 1 {
            random_link(rng, &mut b, len + j, &on(*p));
        }
    }
    b.build().expect("valid model")
}

/// `M = Σ_i J_iᵀ 𝔍_i J_i` with `J_i`'s column `j` the screw of joint `j` (supporting `i`)
/// written in body `i`'s frame, plus the armatures: from forward kinematics only.
fn mass_matrix_from_jacobians(model: &Model, q: &[f64]) -> DMatrix<f64> {
    let n = model.nq();
    let mut ws = Workspace::new(model);
    forward_kinematics(model, &mut ws, q).unwrap();
    let mut m = DMatrix::zeros(n, n);
    for i in 0..n {
        let support = model.support(i).unwrap();
        let body_from_world = ws.pose_in_world[i].inverse();
        let inertia = model.bodies()[i].inertia.matrix();
        let cols: Vec<(usize, Vector6<f64>)> = support
            .iter()
            .map(|&j| {
                let s0 = ws.pose_in_world[j].act_twist(&model.joints()[j].screw);
                (j, body_from_world.act_twist(&s0))
            })
            .collect();
        for (a, sa) in &cols {
            for (b, sb) in &cols {
                m[(*a, *b)] += (sa.transpose() * inertia * sb)[(0, 0)];
            }
        }
    }
    for i in 0..n {
        m[(i, i)] += model.joints()[i].armature;
    }
    m
}

/// `crba` against `Σ_i J_iᵀ 𝔍_i J_i` (to 1e-12 of the largest entry), exactly symmetric and
/// positive definite (its Cholesky factor exists).
fn check(model: &Model, rng: &mut StdRng, states: usize) {
    let n = model.nq();
    let mut ws = Workspace::new(model);
    for _ in 0..states {
        let q = common::random_vec(rng, n, 3.0);
        let m = crba(model, &mut ws, &q).unwrap().clone();
        let sum = mass_matrix_from_jacobians(model, &q);
        let scale = sum.amax().max(1.0);
        assert!(
            (&m - &sum).amax() < 1e-12 * scale,
            "{}: crba vs Σ JᵀJ, n = {n}: {:e}\n{m}\n{sum}",
            model.name(),
            (&m - &sum).amax() / scale
        );
        assert_eq!(m, m.transpose(), "not symmetric, n = {n}");
        assert!(m.cholesky().is_some(), "not positive definite, n = {n}");
    }
}

#[test]
fn crba_equals_sum_of_body_jacobians_on_random_trees() {
    let mut rng = StdRng::seed_from_u64(31);
    for n in [1, 2, 3, 5, 6, 7, 8, 13, 25] {
        for _ in 0..4 {
            let model = mixed_axes(&mut rng, n, 0.25);
            check(&model, &mut rng, 5);
        }
    }
    // The general screws and helical joints of the shared random trees.
    for n in [4, 9, 20] {
        let model = common::random_tree(&mut rng, n, true);
        check(&model, &mut rng, 5);
    }
}

/// Chains up to 200 joints, and long trees with a few branches (whose ancestors are several
/// runs of consecutive indices).
#[test]
fn crba_equals_sum_of_body_jacobians_on_chains_and_long_trees() {
    let mut rng = StdRng::seed_from_u64(200);
    for n in [6, 7, 16, 60, 200] {
        let model = mixed_axes(&mut rng, n, 0.0);
        check(&model, &mut rng, 2);
    }
    for (n, branch) in [(9, 0.3), (30, 0.1), (80, 0.05), (200, 0.02)] {
        let model = mixed_axes(&mut rng, n, branch);
        check(&model, &mut rng, 2);
    }
}

/// Chains with leaf bodies (the Panda's shape: two fingers on the last arm link; several leaves
/// on one link; leaves on the base before and after the chain; a long chain with leaves whose
/// runs of ancestors are 16 and more long).
#[test]
fn crba_equals_sum_of_body_jacobians_on_chains_with_leaves() {
    let mut rng = StdRng::seed_from_u64(8);
    let shapes: [(usize, Vec<Option<usize>>); 6] = [
        (7, vec![Some(6), Some(6)]),
        (1, vec![Some(0), Some(0), None]),
        (5, vec![None, Some(2), Some(2), Some(2), Some(4), None]),
        (4, vec![Some(0), None, Some(3), Some(1)]),
        (3, vec![None, None]),
        (
            30,
            vec![Some(29), Some(20), Some(20), Some(3), None, Some(17)],
        ),
    ];
    for (len, leaves) in &shapes {
        let model = chain_with_leaves(&mut rng, *len, leaves);
        check(&model, &mut rng, 4);
    }
}

#[test]
fn crba_rejects_bad_input() {
    let mut rng = StdRng::seed_from_u64(1);
    let model = mixed_axes(&mut rng, 4, 0.3);
    let mut ws = Workspace::new(&model);
    assert!(crba(&model, &mut ws, &[0.0; 3]).is_err());
    assert!(crba(&model, &mut ws, &[0.0, f64::NAN, 0.0, 0.0]).is_err());
    let other = mixed_axes(&mut rng, 5, 0.3);
    let mut wrong = Workspace::new(&other);
    assert!(crba(&model, &mut wrong, &[0.0; 4]).is_err());
}
