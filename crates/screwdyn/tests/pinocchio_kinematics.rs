//! Kinematics against Pinocchio (issue 4): frame poses and frame Jacobians in the world, local
//! and world-aligned references at 20 random states of the UR5, the Panda (with its prismatic
//! fingers) and a random tree of unaligned revolute and prismatic joints. Reference values:
//! `scripts/gen_reference.py`, converted to angular first.

#[path = "common/pinocchio.rs"]
mod pinocchio;

use nalgebra::{DMatrix, Matrix6xX};
use pinocchio::{jacobian, load_fixture, matrix4, ROBOTS};
use screwdyn::kinematics::{
    compute_joint_jacobians, forward_kinematics, frame_jacobian, frame_pose, Reference,
};
use screwdyn::model::FrameKind;
use screwdyn::Workspace;

const TOL: f64 = 1e-9;

/// Largest `|got − want| / max(1, |want|)` over the entries.
fn rel_err(got: &DMatrix<f64>, want: &DMatrix<f64>) -> f64 {
    assert_eq!(got.shape(), want.shape());
    got.iter()
        .zip(want.iter())
        .map(|(g, w)| (g - w).abs() / w.abs().max(1.0))
        .fold(0.0, f64::max)
}

fn dyn6(m: &Matrix6xX<f64>) -> DMatrix<f64> {
    DMatrix::from_fn(6, m.ncols(), |i, j| m[(i, j)])
}

#[test]
fn joint_names_order_and_frames_match_pinocchio() {
    for robot in ROBOTS {
        let (model, fx) = load_fixture(robot);
        assert_eq!(
            model.joint_names(),
            fx.joint_names(),
            "{robot}: joint order"
        );
        assert_eq!(model.nq(), fx.joints.len());
        for (i, j) in fx.joints.iter().enumerate() {
            assert_eq!(
                model.parent(i).unwrap(),
                j.parent,
                "{robot}: parent of {}",
                j.name
            );
            assert_eq!(
                model.bodies()[i].name,
                j.body_name,
                "{robot}: body of {}",
                j.name
            );
            let kind = model.joints()[i].kind.name();
            assert_eq!(kind, j.kind, "{robot}: kind of {}", j.name);
        }
        for f in &fx.frames {
            let id = model.frame_id(&f.name).unwrap();
            let frame = &model.frames()[id];
            assert_eq!(frame.body, f.joint, "{robot}: body of frame {}", f.name);
            let want = DMatrix::from_iterator(4, 4, f.placement.se3().to_matrix().iter().copied());
            let got = DMatrix::from_iterator(4, 4, frame.placement.to_matrix().iter().copied());
            assert!(
                rel_err(&got, &want) < 1e-15,
                "{robot}: placement of {}",
                f.name
            );
        }
        assert_eq!(
            model.gravity(),
            nalgebra::Vector3::from(fx.gravity),
            "{robot}: gravity"
        );
        assert!(fx.states.len() >= 20, "{robot}: {} states", fx.states.len());
    }
}

#[test]
fn frame_poses_match_pinocchio() {
    for robot in ROBOTS {
        let (model, fx) = load_fixture(robot);
        let mut ws = Workspace::new(&model);
        for (k, s) in fx.states.iter().enumerate() {
            forward_kinematics(&model, &mut ws, &s.q).unwrap();
            // Frames on a moving body: the fixture's pose at q.
            for (name, rows) in &s.frame_poses {
                let got = frame_pose(&model, &ws, model.frame_id(name).unwrap())
                    .unwrap()
                    .to_matrix();
                let want = matrix4(rows);
                let err = rel_err(
                    &DMatrix::from_iterator(4, 4, got.iter().copied()),
                    &DMatrix::from_iterator(4, 4, want.iter().copied()),
                );
                assert!(
                    err < TOL,
                    "{robot} state {k}: pose of {name}: error {err:e}\n got {got}\n want {want}"
                );
            }
            // Frames on the base do not move: their pose is their placement.
            for f in fx.frames.iter().filter(|f| f.joint.is_none()) {
                let id = model.frame_id(&f.name).unwrap();
                assert!(!s.frame_poses.contains_key(&f.name));
                let got = frame_pose(&model, &ws, id).unwrap().to_matrix();
                let want = f.placement.se3().to_matrix();
                assert!(
                    (got - want).amax() < TOL,
                    "{robot}: pose of base frame {}",
                    f.name
                );
            }
            // Every frame on a moving body has a reference pose.
            for f in model.frames().iter().filter(|f| f.body.is_some()) {
                assert!(
                    s.frame_poses.contains_key(&f.name),
                    "{robot}: no reference pose for frame {}",
                    f.name
                );
            }
        }
    }
}

#[test]
fn frame_jacobians_match_pinocchio() {
    for robot in ROBOTS {
        let (model, fx) = load_fixture(robot);
        let mut ws = Workspace::new(&model);
        let mut j = Matrix6xX::zeros(model.nq());
        let mut checked = 0;
        for (k, s) in fx.states.iter().enumerate() {
            compute_joint_jacobians(&model, &mut ws, &s.q).unwrap();
            for name in &fx.jacobian_frames {
                let id = model.frame_id(name).unwrap();
                for (reference, table) in [
                    (Reference::World, &s.jacobians_world),
                    (Reference::Local, &s.jacobians_local),
                    (
                        Reference::LocalWorldAligned,
                        &s.jacobians_local_world_aligned,
                    ),
                ] {
                    frame_jacobian(&model, &ws, id, reference, &mut j).unwrap();
                    let want = dyn6(&jacobian(&table[name]));
                    let err = rel_err(&dyn6(&j), &want);
                    assert!(
                        err < TOL,
                        "{robot} state {k}: {reference:?} Jacobian of {name}: error {err:e}\n got {j}\n want {want}"
                    );
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 3 * fx.jacobian_frames.len() * fx.states.len());
        // Frames on the base have a zero Jacobian.
        for f in model.frames().iter() {
            if f.kind == FrameKind::Base || f.body.is_none() {
                frame_jacobian(
                    &model,
                    &ws,
                    model.frame_id(&f.name).unwrap(),
                    Reference::World,
                    &mut j,
                )
                .unwrap();
                assert_eq!(j.amax(), 0.0, "{robot}: Jacobian of base frame {}", f.name);
            }
        }
    }
}

#[test]
fn fixture_dynamics_data_is_consistent() {
    // The dynamics module is not wired yet: check the loader exposes the data with the right
    // shapes and that Pinocchio's own identities hold (M v̇ + nle = τ, C v = nle − g).
    for robot in ROBOTS {
        let (model, fx) = load_fixture(robot);
        let n = model.nq();
        for s in &fx.states {
            for v in [&s.q, &s.v, &s.a, &s.tau_in, &s.tau, &s.gravity, &s.qdd] {
                assert_eq!(v.len(), n);
            }
            let m = pinocchio::dmatrix(&s.mass_matrix);
            let c = pinocchio::dmatrix(&s.coriolis_matrix);
            assert_eq!(m.shape(), (n, n));
            assert!((&m - m.transpose()).amax() < 1e-12, "{robot}: M symmetric");
            let qdd = nalgebra::DVector::from_column_slice(&s.qdd);
            let v = nalgebra::DVector::from_column_slice(&s.v);
            let nle = nalgebra::DVector::from_column_slice(&s.nonlinear_effects);
            let g = nalgebra::DVector::from_column_slice(&s.gravity);
            let tau_in = nalgebra::DVector::from_column_slice(&s.tau_in);
            let scale = 1.0 + tau_in.amax();
            assert!((&m * qdd + &nle - tau_in).amax() < 1e-8 * scale);
            let cv = nalgebra::DVector::from_column_slice(&s.coriolis_times_v);
            assert!((&c * v - &cv).amax() < 1e-9 * (1.0 + cv.amax()));
            assert!((nle - g - cv).amax() < 1e-12 * scale);
        }
    }
}
