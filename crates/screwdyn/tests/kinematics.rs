//! Kinematics against independent sources: the PoE formula, central finite differences of the
//! forward kinematics, and the planar two-link closed form of seeds 003/004.

#![allow(clippy::needless_range_loop)] // index loops read like the math

use nalgebra::{Matrix3, Matrix6xX, Vector3, Vector6};
use rand::{rngs::StdRng, Rng, SeedableRng};
use screwdyn::kinematics::*;
use screwdyn::model::{JointSpec, ModelBuilder};
use screwdyn::spatial::{helical_screw, prismatic_screw, revolute_screw, Se3, SpatialInertia};
use screwdyn::{builtin, Model, Workspace};

fn unit(rng: &mut StdRng) -> Vector3<f64> {
    loop {
        let v = Vector3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
        if v.norm() > 0.2 {
            return v.normalize();
        }
    }
}

/// A random tree of `n` bodies (parents chosen at random among earlier bodies when `branch`),
/// mixing revolute, prismatic and helical joints, with random fixed links and extra frames.
fn random_tree(rng: &mut StdRng, n: usize, branch: bool) -> Model {
    let mut b = ModelBuilder::new("random");
    let mut names = vec!["base".to_string()];
    for i in 0..n {
        let parent = if branch {
            names[rng.gen_range(0..names.len())].clone()
        } else {
            names.last().unwrap().clone()
        };
        let home = Se3::exp(&Vector6::from_fn(|_, _| rng.gen_range(-1.0..1.0)));
        let (r, n_) = (Vector3::from_fn(|_, _| rng.gen_range(-0.5..0.5)), unit(rng));
        let spec = match i % 3 {
            0 => JointSpec::revolute(&format!("j{i}")).screw_in_child(revolute_screw(n_, r)),
            1 => JointSpec::prismatic(&format!("j{i}")).screw_in_parent(prismatic_screw(n_)),
            _ => {
                JointSpec::helical(&format!("j{i}"), 0.1).screw_in_child(helical_screw(n_, r, 0.1))
            }
        };
        // A uniform box of random size, mass and orientation: physical by construction.
        let (mass, d) = (
            rng.gen_range(0.5..2.0),
            Vector3::from_fn(|_, _| rng.gen_range(0.05..0.6)),
        );
        let r = Se3::exp(&Vector6::new(
            rng.gen_range(-2.0..2.0),
            rng.gen_range(-2.0..2.0),
            rng.gen_range(-2.0..2.0),
            0.0,
            0.0,
            0.0,
        ))
        .rotation;
        let principal = Matrix3::from_diagonal(&Vector3::new(
            d.y * d.y + d.z * d.z,
            d.x * d.x + d.z * d.z,
            d.x * d.x + d.y * d.y,
        )) * (mass / 12.0);
        let inertia = SpatialInertia::new(
            mass,
            Vector3::from_fn(|_, _| rng.gen_range(-0.2..0.2)),
            r * principal * r.transpose(),
        );
        let name = format!("l{i}");
        b.link(&name, &parent, spec, home, inertia);
        if i % 4 == 3 {
            // A fixed child link, merged into this body but kept as a frame.
            let fixed = format!("f{i}");
            b.link(
                &fixed,
                &name,
                JointSpec::fixed(&format!("fj{i}")),
                Se3::exp(&Vector6::from_fn(|_, _| rng.gen_range(-1.0..1.0))),
                SpatialInertia::point_mass(0.3, Vector3::new(0.1, 0.0, 0.0)),
            );
            b.frame(
                &format!("tool{i}"),
                &fixed,
                Se3::exp(&Vector6::from_fn(|_, _| rng.gen_range(-1.0..1.0))),
            );
        }
        names.push(name);
    }
    b.build().unwrap()
}

fn random_q(rng: &mut StdRng, n: usize) -> Vec<f64> {
    (0..n).map(|_| rng.gen_range(-2.0..2.0)).collect()
}

fn poses(m: &Model, q: &[f64]) -> Vec<Se3> {
    let mut ws = Workspace::new(m);
    forward_kinematics(m, &mut ws, q).unwrap();
    (0..m.frames().len())
        .map(|f| frame_pose(m, &ws, f).unwrap())
        .collect()
}

#[test]
fn poe_equals_recursion_on_random_trees() {
    let mut rng = StdRng::seed_from_u64(10);
    for trial in 0..20 {
        let m = random_tree(&mut rng, 3 + trial % 8, trial % 2 == 0);
        let q = random_q(&mut rng, m.nq());
        let mut ws = Workspace::new(&m);
        forward_kinematics(&m, &mut ws, &q).unwrap();
        let poe = forward_kinematics_poe(&m, &q).unwrap();
        for i in 0..m.nq() {
            let d = (poe[i].to_matrix() - ws.pose_in_world[i].to_matrix()).amax();
            assert!(d < 1e-12, "trial {trial} body {i}: {d}");
        }
    }
}

/// Central finite difference of the frame pose along joint j, as a twist in `reference`.
/// A chain of `n` joints about or along coordinate axes (revolute through the origin, revolute
/// about an offset axis, prismatic), with a helical joint every fifth: the joints whose sines
/// and cosines forward kinematics computes side by side, packed among the others.
fn axis_chain(rng: &mut StdRng, n: usize) -> Model {
    let mut b = ModelBuilder::new("axes");
    let mut parent = "base".to_string();
    for i in 0..n {
        let k = rng.gen_range(0..3);
        let sign = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        let axis = Vector3::ith(k, sign);
        let mut r = Vector3::from_fn(|_, _| rng.gen_range(-0.5..0.5));
        r[k] = 0.0;
        let name = format!("j{i}");
        let spec = match i % 5 {
            0 | 2 => {
                JointSpec::revolute(&name).screw_in_child(revolute_screw(axis, Vector3::zeros()))
            }
            1 => JointSpec::revolute(&name).screw_in_child(revolute_screw(axis, r)),
            3 => JointSpec::prismatic(&name).screw_in_parent(prismatic_screw(axis)),
            _ => JointSpec::helical(&name, 0.1).screw_in_child(helical_screw(unit(rng), r, 0.1)),
        };
        let home = Se3::exp(&Vector6::from_fn(|_, _| rng.gen_range(-1.0..1.0)));
        let link = format!("l{i}");
        b.link(
            &link,
            &parent,
            spec,
            home,
            SpatialInertia::point_mass(1.0, r),
        );
        parent = link;
    }
    b.build().unwrap()
}

#[test]
fn poe_equals_recursion_on_axis_chains_of_every_length() {
    // Lengths 1–20 give every tail of the packed sines and cosines (one angle, two to four,
    // five to eight) and several blocks; angles up to ±100 rad and near multiples of π/2.
    let mut rng = StdRng::seed_from_u64(31);
    for n in 1..=20 {
        let m = axis_chain(&mut rng, n);
        let turning = (0..n).filter(|i| i % 5 < 3).count();
        assert_eq!(m.motions().iter().filter(|j| j.turns()).count(), turning);
        for trial in 0..5 {
            let q: Vec<f64> = (0..n)
                .map(|i| match (trial + i) % 3 {
                    0 => rng.gen_range(-100.0..100.0),
                    1 => rng.gen_range(-40..40) as f64 * std::f64::consts::FRAC_PI_2,
                    _ => rng.gen_range(-2.0..2.0),
                })
                .collect();
            let mut ws = Workspace::new(&m);
            forward_kinematics(&m, &mut ws, &q).unwrap();
            let poe = forward_kinematics_poe(&m, &q).unwrap();
            for i in 0..n {
                // Relative to the pose's size: prismatic and helical joints travel up to 100 m.
                let scale = poe[i].to_matrix().amax().max(1.0);
                let d = (poe[i].to_matrix() - ws.pose_in_world[i].to_matrix()).amax();
                assert!(d < 1e-13 * scale, "n {n} trial {trial} body {i}: {d}");
            }
        }
    }
}

fn fd_column(m: &Model, q: &[f64], f: usize, j: usize, reference: Reference) -> Vector6<f64> {
    let h = 1e-6;
    let (mut qp, mut qm) = (q.to_vec(), q.to_vec());
    qp[j] += h;
    qm[j] -= h;
    let (p0, pp, pm) = (poses(m, q)[f], poses(m, &qp)[f], poses(m, &qm)[f]);
    match reference {
        // Spatial twist: [V] = Ḣ H⁻¹  →  log(H(q±h) H(q)⁻¹) / ±h
        Reference::World => {
            (pp.compose(&p0.inverse()).log() - pm.compose(&p0.inverse()).log()) / (2.0 * h)
        }
        // Body twist: [V] = H⁻¹ Ḣ
        Reference::Local => (p0.inv_compose(&pp).log() - p0.inv_compose(&pm).log()) / (2.0 * h),
        // Origin velocity and angular velocity, both in world axes.
        Reference::LocalWorldAligned => {
            let w = (pp.compose(&p0.inverse()).log() - pm.compose(&p0.inverse()).log()) / (2.0 * h);
            let v = (pp.translation - pm.translation) / (2.0 * h);
            Vector6::new(w[0], w[1], w[2], v.x, v.y, v.z)
        }
    }
}

#[test]
fn jacobian_columns_equal_finite_differences_on_chains_and_trees() {
    let mut rng = StdRng::seed_from_u64(11);
    for trial in 0..8 {
        let m = random_tree(&mut rng, 4 + trial, trial % 2 == 1);
        let q = random_q(&mut rng, m.nq());
        let mut ws = Workspace::new(&m);
        compute_joint_jacobians(&m, &mut ws, &q).unwrap();
        let mut jac = Matrix6xX::zeros(m.nq());
        for f in 0..m.frames().len() {
            for reference in [
                Reference::World,
                Reference::Local,
                Reference::LocalWorldAligned,
            ] {
                frame_jacobian(&m, &ws, f, reference, &mut jac).unwrap();
                for j in 0..m.nq() {
                    let fd = fd_column(&m, &q, f, j, reference);
                    let d = (jac.column(j) - fd).amax();
                    assert!(
                        d < 1e-6,
                        "trial {trial} frame {} joint {j} {reference:?}: {d}",
                        m.frames()[f].name
                    );
                }
            }
        }
    }
}

#[test]
fn link_jacobians_are_the_seed_body_jacobians() {
    // J_i^{i,0} = Ad_{H_0^i} J_i^{0,0}; column i is S_i^{i,λ(i)} itself.
    let mut rng = StdRng::seed_from_u64(12);
    let m = random_tree(&mut rng, 7, true);
    let q = random_q(&mut rng, m.nq());
    let mut ws = Workspace::new(&m);
    compute_joint_jacobians(&m, &mut ws, &q).unwrap();
    let (mut jb, mut js) = (Matrix6xX::zeros(m.nq()), Matrix6xX::zeros(m.nq()));
    for i in 0..m.nq() {
        link_jacobian(&m, &ws, i, &mut jb).unwrap();
        frame_jacobian(&m, &ws, m.body_frame(i).unwrap(), Reference::World, &mut js).unwrap();
        let h0i = ws.pose_in_world[i].inverse().adjoint_matrix();
        assert!((jb.clone() - h0i * js.clone()).amax() < 1e-12);
        assert!((jb.column(i) - m.joints()[i].screw).amax() < 1e-12);
        for j in 0..m.nq() {
            if !m.supports(j, i).unwrap() {
                assert_eq!(jb.column(j).amax(), 0.0);
            }
        }
    }
}

#[test]
fn frame_twists_and_accelerations_match_jacobians_and_finite_differences() {
    let mut rng = StdRng::seed_from_u64(13);
    let m = random_tree(&mut rng, 8, true);
    let (q, v, a) = (
        random_q(&mut rng, 8),
        random_q(&mut rng, 8),
        random_q(&mut rng, 8),
    );
    let mut ws = Workspace::new(&m);
    compute_joint_jacobians(&m, &mut ws, &q).unwrap();
    forward_acceleration(&m, &mut ws, &q, &v, &a).unwrap();
    let mut jac = Matrix6xX::zeros(8);
    let vv = nalgebra::DVector::from_column_slice(&v);
    let dt = 1e-5;
    // q(t) = q + v t + a t²/2 around t = 0
    let at = |t: f64| -> (Vec<f64>, Vec<f64>) {
        (
            (0..8)
                .map(|k| q[k] + v[k] * t + 0.5 * a[k] * t * t)
                .collect(),
            (0..8).map(|k| v[k] + a[k] * t).collect(),
        )
    };
    for f in 0..m.frames().len() {
        for reference in [
            Reference::World,
            Reference::Local,
            Reference::LocalWorldAligned,
        ] {
            frame_jacobian(&m, &ws, f, reference, &mut jac).unwrap();
            let tw = frame_twist(&m, &ws, f, reference).unwrap();
            assert!((jac.clone() * vv.clone() - tw).amax() < 1e-12);
            // The acceleration is the time derivative of the twist components.
            let twist_at = |t: f64| {
                let (qt, vt) = at(t);
                let mut w2 = Workspace::new(&m);
                forward_velocity(&m, &mut w2, &qt, &vt).unwrap();
                frame_twist(&m, &w2, f, reference).unwrap()
            };
            let fd = (twist_at(dt) - twist_at(-dt)) / (2.0 * dt);
            let acc = frame_acceleration(&m, &ws, f, reference).unwrap();
            assert!(
                (acc - fd).amax() < 1e-6,
                "{reference:?} frame {f}: {acc} vs {fd}"
            );
        }
    }
}

#[test]
fn jdot_qdot_equals_derivative_of_jacobian_along_qdot() {
    let mut rng = StdRng::seed_from_u64(14);
    let m = random_tree(&mut rng, 6, false);
    let (q, v) = (random_q(&mut rng, 6), random_q(&mut rng, 6));
    let vv = nalgebra::DVector::from_column_slice(&v);
    let h = 1e-6;
    let f = m.frames().len() - 1;
    for reference in [
        Reference::World,
        Reference::Local,
        Reference::LocalWorldAligned,
    ] {
        let jv = |s: f64| {
            let qs: Vec<f64> = (0..6).map(|k| q[k] + s * v[k]).collect();
            let mut ws = Workspace::new(&m);
            compute_joint_jacobians(&m, &mut ws, &qs).unwrap();
            let mut jac = Matrix6xX::zeros(6);
            frame_jacobian(&m, &ws, f, reference, &mut jac).unwrap();
            jac * vv.clone()
        };
        let fd = (jv(h) - jv(-h)) / (2.0 * h);
        let mut ws = Workspace::new(&m);
        let got = frame_jdot_qdot(&m, &mut ws, &q, &v, f, reference).unwrap();
        assert!((fd - got).amax() < 1e-6, "{reference:?}: {got} vs {fd}");
    }
}

#[test]
fn planar2_end_effector_matches_closed_form() {
    // Seeds 003/004: x = L1 c1 + L2 c12, y = L1 s1 + L2 s12.
    let (l1, l2) = (0.7, 0.4);
    let m = builtin::planar2_with(l1, l2, 1.0, 1.0);
    let mut rng = StdRng::seed_from_u64(15);
    let tip = m.frame_id("link2").unwrap();
    for _ in 0..50 {
        let q = random_q(&mut rng, 2);
        let p = poses(&m, &q)[tip].translation;
        let (c1, s1, c12, s12) = (
            q[0].cos(),
            q[0].sin(),
            (q[0] + q[1]).cos(),
            (q[0] + q[1]).sin(),
        );
        assert!((p.x - (l1 * c1 + l2 * c12)).abs() < 1e-14);
        assert!((p.y - (l1 * s1 + l2 * s12)).abs() < 1e-14);
        assert_eq!(p.z, 0.0);
    }
}

#[test]
fn f32_models_agree_with_f64() {
    let mut rng = StdRng::seed_from_u64(16);
    let m = random_tree(&mut rng, 6, true);
    let m32: Model<f32> = m.cast();
    let q = random_q(&mut rng, 6);
    let q32: Vec<f32> = q.iter().map(|&x| x as f32).collect();
    let mut ws = Workspace::new(&m32);
    compute_joint_jacobians(&m32, &mut ws, &q32).unwrap();
    let p64 = poses(&m, &q);
    for f in 0..m.frames().len() {
        let p = frame_pose(&m32, &ws, f)
            .unwrap()
            .to_matrix()
            .map(|x| x as f64);
        assert!((p - p64[f].to_matrix()).amax() < 1e-4);
    }
}

#[test]
fn bad_vectors_are_clear_errors() {
    let m = builtin::planar2();
    let mut ws = Workspace::new(&m);
    let e = forward_kinematics(&m, &mut ws, &[0.1])
        .unwrap_err()
        .to_string();
    assert_eq!(e, "q has 1 values, the model has 2 joints: joint1, joint2");
    let e = forward_velocity(&m, &mut ws, &[0.1, 0.2], &[f64::NAN, 0.0])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("v contains a non-finite value (NaN) at position 0"),
        "{e}"
    );
}
