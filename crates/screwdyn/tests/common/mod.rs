//! Shared helpers for the integration tests: random kinematic trees with physical inertias.
#![allow(dead_code)]

use nalgebra::{Matrix3, Vector3, Vector6};
use rand::rngs::StdRng;
use rand::Rng;
use screwdyn::dynamics::ExternalWrenches;
use screwdyn::model::{JointSpec, ModelBuilder};
use screwdyn::spatial::{exp_so3, Se3, SpatialInertia};
use screwdyn::Model;

/// A random unit vector.
pub fn unit(rng: &mut StdRng) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        let n = v.norm();
        if n > 0.2 && n < 1.0 {
            return v / n;
        }
    }
}

fn vec3(rng: &mut StdRng, r: f64) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-r..r),
        rng.gen_range(-r..r),
        rng.gen_range(-r..r),
    )
}

fn rotation(rng: &mut StdRng) -> Matrix3<f64> {
    exp_so3(&(unit(rng) * rng.gen_range(0.0..3.0)))
}

/// A random physical inertia: a box of random size and mass, rotated, CoM off the origin.
pub fn random_inertia(rng: &mut StdRng) -> SpatialInertia {
    let m = rng.gen_range(0.5..3.0);
    let (a, b, c) = (
        rng.gen_range(0.05..0.6),
        rng.gen_range(0.05..0.6),
        rng.gen_range(0.05..0.6),
    );
    let d = Matrix3::from_diagonal(&Vector3::new(
        m / 12.0 * (b * b + c * c),
        m / 12.0 * (a * a + c * c),
        m / 12.0 * (a * a + b * b),
    ));
    let r = rotation(rng);
    SpatialInertia::new(m, vec3(rng, 0.3), r * d * r.transpose())
}

/// A random tree of `n` moving bodies: revolute joints (and, if `mixed`, prismatic and helical
/// ones), random home poses and axes, random physical inertias, branching at random.
pub fn random_tree(rng: &mut StdRng, n: usize, mixed: bool) -> Model {
    let mut b = ModelBuilder::new("random");
    b.gravity(Vector3::new(0.3, -0.5, -9.81));
    for i in 0..n {
        let parent = if i == 0 || rng.gen_bool(0.15) {
            "base".to_string()
        } else {
            format!("l{}", rng.gen_range(0..i))
        };
        let axis = unit(rng);
        let point = vec3(rng, 0.2);
        let kind = if mixed { rng.gen_range(0..3) } else { 0 };
        let (spec, screw) = match kind {
            0 => (
                JointSpec::revolute(&format!("j{i}")),
                Vector6::from_iterator(
                    axis.iter()
                        .copied()
                        .chain((-axis.cross(&point)).iter().copied()),
                ),
            ),
            1 => (
                JointSpec::prismatic(&format!("j{i}")),
                Vector6::new(0.0, 0.0, 0.0, axis.x, axis.y, axis.z),
            ),
            _ => {
                let pitch = rng.gen_range(-0.2..0.2);
                let l = -axis.cross(&point) + axis * pitch;
                (
                    JointSpec::helical(&format!("j{i}"), pitch),
                    Vector6::new(axis.x, axis.y, axis.z, l.x, l.y, l.z),
                )
            }
        };
        let home = Se3::new(rotation(rng), vec3(rng, 0.6));
        b.link(
            &format!("l{i}"),
            &parent,
            spec.screw_in_child(screw),
            home,
            random_inertia(rng),
        );
    }
    b.frame(
        "tool",
        &format!("l{}", n - 1),
        Se3::new(rotation(rng), vec3(rng, 0.3)),
    );
    b.build().expect("random tree is valid")
}

pub fn random_vec(rng: &mut StdRng, n: usize, r: f64) -> Vec<f64> {
    (0..n).map(|_| rng.gen_range(-r..r)).collect()
}

/// `|a − b| ≤ tol · max(1, |b|)` entrywise, with a message.
pub fn assert_close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: lengths differ");
    let scale = b.iter().fold(1.0_f64, |s, x| s.max(x.abs()));
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tol * scale,
            "{what}[{i}]: {x} vs {y} (tol {tol} × {scale})\n{a:?}\n{b:?}"
        );
    }
}

/// A two-link arm whose second link has no mass and no inertia: `D = 0` at its joint, so the
/// mass matrix is singular in every state.
pub fn massless_tip() -> Model {
    let mut b = ModelBuilder::new("ghost");
    b.strict(false).link(
        "l1",
        "base",
        JointSpec::revolute("j1").screw_in_child(Vector6::new(0., 0., 1., 0., 0., 0.)),
        Se3::identity(),
        SpatialInertia::new(1.0, Vector3::new(0.5, 0.0, 0.0), Matrix3::identity() * 0.01),
    );
    b.link(
        "l2",
        "l1",
        JointSpec::revolute("j2").screw_in_child(Vector6::new(0., 0., 1., 0., 0., 0.)),
        Se3::from_translation(Vector3::new(1.0, 0.0, 0.0)),
        SpatialInertia::zero(),
    );
    b.build().unwrap()
}

/// A serial chain of `n` revolute and prismatic joints with random axes, home poses (links of
/// 0.05–0.2 m) and physical inertias.
pub fn random_chain(rng: &mut StdRng, n: usize) -> Model {
    let mut b = ModelBuilder::new("chain");
    b.gravity(Vector3::new(0.2, 0.1, -9.81));
    for i in 0..n {
        let parent = if i == 0 {
            "base".to_string()
        } else {
            format!("l{}", i - 1)
        };
        let axis = unit(rng);
        let (spec, screw) = if rng.gen_bool(0.8) {
            let point = unit(rng) * 0.05;
            let l = -axis.cross(&point);
            (
                JointSpec::revolute(&format!("j{i}")),
                Vector6::new(axis.x, axis.y, axis.z, l.x, l.y, l.z),
            )
        } else {
            (
                JointSpec::prismatic(&format!("j{i}")),
                Vector6::new(0.0, 0.0, 0.0, axis.x, axis.y, axis.z),
            )
        };
        let home = Se3::new(
            exp_so3(&(unit(rng) * rng.gen_range(0.0..3.0))),
            unit(rng) * rng.gen_range(0.05..0.2),
        );
        b.link(
            &format!("l{i}"),
            &parent,
            spec.screw_in_child(screw),
            home,
            random_inertia(rng),
        );
    }
    b.frame("tool", &format!("l{}", n - 1), Se3::identity());
    b.build().expect("random chain is valid")
}

/// Wrenches on every body, given in the body's frame or in {0} at random, and one at the first
/// frame on a moving body.
pub fn random_external(model: &Model, rng: &mut StdRng) -> ExternalWrenches {
    let mut ext = ExternalWrenches::new(model);
    for i in 0..model.nbodies() {
        let w = Vector6::from_vec(random_vec(rng, 6, 2.0));
        if rng.gen_bool(0.5) {
            ext.add_local(i, w).unwrap();
        } else {
            ext.add_world(i, w).unwrap();
        }
    }
    if let Some(tool) = model.frames().iter().position(|f| f.body.is_some()) {
        ext.add_tip(model, tool, Vector6::from_vec(random_vec(rng, 6, 2.0)))
            .unwrap();
    }
    ext
}
