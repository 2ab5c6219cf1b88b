//! The shipped robots in `models/` against their published numbers and each other.

use nalgebra::{DMatrix, Matrix6xX, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use screwdyn::dynamics::{inverse_dynamics, ExternalWrenches};
use screwdyn::io::load_model;
use screwdyn::kinematics::{
    compute_joint_jacobians, forward_kinematics, frame_pose, link_jacobian,
};
use screwdyn::spatial::Se3;
use screwdyn::{Model, Workspace};
use std::f64::consts::FRAC_PI_2;

const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../models/");

fn file(name: &str) -> Model {
    let p = format!("{MODELS}{name}");
    load_model(&p).unwrap_or_else(|e| panic!("{e}"))
}

/// Seed 001: `M(q) = Σ_i J_i^{i,0}ᵀ 𝔍^{i,i} J_i^{i,0}`.
fn mass_matrix(m: &Model, q: &[f64]) -> DMatrix<f64> {
    let n = m.nq();
    let mut ws = Workspace::new(m);
    compute_joint_jacobians(m, &mut ws, q).unwrap();
    let mut out = DMatrix::zeros(n, n);
    let mut j = Matrix6xX::zeros(n);
    for (i, b) in m.bodies().iter().enumerate() {
        link_jacobian(m, &ws, i, &mut j).unwrap();
        let jd = DMatrix::from_column_slice(6, n, j.as_slice());
        out +=
            jd.transpose() * DMatrix::from_column_slice(6, 6, b.inertia.matrix().as_slice()) * jd;
    }
    out
}

fn pose(m: &Model, q: &[f64], frame: &str) -> nalgebra::Matrix4<f64> {
    let mut ws = Workspace::new(m);
    forward_kinematics(m, &mut ws, q).unwrap();
    frame_pose(m, &ws, m.frame_id(frame).unwrap())
        .unwrap()
        .to_matrix()
}

fn random_q(m: &Model, rng: &mut impl Rng) -> Vec<f64> {
    m.joints()
        .iter()
        .map(|j| rng.gen_range(j.limits.lower.max(-3.0)..j.limits.upper.min(3.0)))
        .collect()
}

#[test]
fn every_builtin_equals_its_file_in_models() {
    for (name, path, _) in screwdyn::builtin::FILES {
        let built = screwdyn::builtin::load(name).unwrap();
        let from_disk = file(path);
        assert_eq!(built.joints(), from_disk.joints(), "{name}");
        assert_eq!(built.bodies(), from_disk.bodies(), "{name}");
        assert_eq!(built.frames(), from_disk.frames(), "{name}");
    }
}

#[test]
fn every_builtin_has_a_symmetric_positive_definite_mass_matrix() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(3);
    for name in screwdyn::builtin::NAMES {
        let m = screwdyn::builtin::load(name).unwrap();
        for _ in 0..5 {
            let mm = mass_matrix(&m, &random_q(&m, &mut rng));
            assert!((&mm - mm.transpose()).amax() < 1e-12, "{name}");
            assert!(
                mm.clone().cholesky().is_some(),
                "{name}: M not positive definite\n{mm}"
            );
        }
    }
}

#[test]
fn ur5_home_pose_follows_from_its_published_dh_table() {
    let m = screwdyn::builtin::load("ur5").unwrap();
    let (d1, a2, a3, d4, d5, d6) = (0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823);
    // By hand from seed 004's A_1 ⋯ A_6 at q = 0: the flange sits at (a2 + a3, −(d4 + d6), d1 − d5)
    // with x along x0, y along z0 (after α4 = π/2, α5 = −π/2) and z along −y0.
    let h = pose(&m, &[0.0; 6], "tool0");
    let want_p = Vector3::new(a2 + a3, -(d4 + d6), d1 - d5);
    assert!((h.fixed_view::<3, 1>(0, 3) - want_p).amax() < 1e-12, "{h}");
    let want_r = nalgebra::Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
    assert!((h.fixed_view::<3, 3>(0, 0) - want_r).amax() < 1e-12, "{h}");
    // The published link masses.
    let masses: Vec<f64> = m.bodies().iter().map(|b| b.inertia.mass).collect();
    assert_eq!(masses, vec![3.7, 8.393, 2.33, 1.219, 1.219, 0.1879]);
    assert_eq!(m.joint_names()[0], "shoulder_pan_joint");
}

#[test]
fn ur5_urdf_and_dh_table_are_the_same_robot() {
    let dh = file("ur5.toml");
    let urdf = file("ur5.urdf");
    assert_eq!(dh.joint_names(), urdf.joint_names());
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    // UR5's standard DH table (d, a, α per row).
    let d = [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823];
    let a = [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0];
    let alpha = [FRAC_PI_2, 0.0, 0.0, FRAC_PI_2, -FRAC_PI_2, 0.0];
    let links = [
        "shoulder_link",
        "upper_arm_link",
        "forearm_link",
        "wrist_1_link",
        "wrist_2_link",
        "wrist_3_link",
    ];
    for _ in 0..20 {
        let q = random_q(&dh, &mut rng);
        assert!((mass_matrix(&dh, &q) - mass_matrix(&urdf, &q)).amax() < 1e-12);
        for f in ["base_link", "tool0"] {
            assert!(
                (pose(&dh, &q, f) - pose(&urdf, &q, f)).amax() < 1e-12,
                "{f}"
            );
        }
        // The URDF's link i sits on joint i's axis; the DH frame {i} of the same link follows
        // by the row's Trans_z(d) Trans_x(a) Rot_x(α).
        for (i, link) in links.iter().enumerate() {
            let row = Se3::from_translation(Vector3::new(0.0, 0.0, d[i]))
                * Se3::from_translation(Vector3::new(a[i], 0.0, 0.0))
                * Se3::new(
                    Rotation3::from_axis_angle(&Vector3::x_axis(), alpha[i]).into_inner(),
                    Vector3::zeros(),
                );
            let via_urdf = pose(&urdf, &q, link) * row.to_matrix();
            assert!((pose(&dh, &q, link) - via_urdf).amax() < 1e-12, "{link}");
        }
    }
    for (a, b) in dh.joints().iter().zip(urdf.joints()) {
        assert_eq!(a.limits, b.limits);
    }
}

/// The link (body), joint and frame names of a model.
fn names(m: &Model) -> (Vec<String>, Vec<String>, Vec<String>) {
    (
        m.bodies().iter().map(|b| b.name.clone()).collect(),
        m.joint_names().iter().map(|j| j.to_string()).collect(),
        m.frames().iter().map(|f| f.name.clone()).collect(),
    )
}

#[test]
fn builtin_ur5_and_its_urdf_file_have_the_published_names() {
    // Issue 25: the same robot under two sets of link names, so `fext` on "wrist_3_link"
    // worked on one and not the other. Both now use the names of Universal Robots' published
    // UR5 URDF (ur_description, as in example-robot-data 6.0.0): links base_link,
    // shoulder_link … wrist_3_link, tool0; joints shoulder_pan_joint … wrist_3_joint.
    let builtin = screwdyn::builtin::load("ur5").unwrap();
    let urdf = file("ur5.urdf");
    assert_eq!(names(&builtin), names(&urdf));
    let (bodies, joints, frames) = names(&builtin);
    assert_eq!(
        bodies,
        [
            "shoulder_link",
            "upper_arm_link",
            "forearm_link",
            "wrist_1_link",
            "wrist_2_link",
            "wrist_3_link"
        ]
    );
    assert_eq!(
        joints,
        [
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint"
        ]
    );
    assert_eq!(frames.first().map(String::as_str), Some("base_link"));
    assert_eq!(frames.last().map(String::as_str), Some("tool0"));
    // The same wrench (in the world frame) on "wrist_3_link" needs the same torques on both:
    // τ = RNEA(q, q̇, q̈) − J_6ᵀ W.
    let mut rng = rand::rngs::StdRng::seed_from_u64(25);
    let q = random_q(&builtin, &mut rng);
    let v: Vec<f64> = (0..6).map(|_| rng.gen_range(-1.0..1.0)).collect();
    let acc: Vec<f64> = (0..6).map(|_| rng.gen_range(-1.0..1.0)).collect();
    let w = nalgebra::Vector6::new(0.1, -0.2, 0.3, 5.0, -4.0, 3.0);
    let tau = |m: &Model| {
        let mut ext = ExternalWrenches::new(m);
        ext.add_on_link(m, m.frame_id("wrist_3_link").unwrap(), w, true)
            .unwrap();
        let mut ws = Workspace::new(m);
        inverse_dynamics(m, &mut ws, &q, &v, &acc, Some(&ext))
            .unwrap()
            .clone()
    };
    let (a, b) = (tau(&builtin), tau(&urdf));
    assert!((&a - &b).amax() < 1e-9 * (1.0 + a.amax()), "{a} vs {b}");
    let mut ws = Workspace::new(&builtin);
    let free = inverse_dynamics(&builtin, &mut ws, &q, &v, &acc, None)
        .unwrap()
        .clone();
    assert!((&a - &free).amax() > 1e-3, "the wrench acts");
}

#[test]
fn panda_flange_at_zero_follows_from_its_published_modified_dh_table() {
    let m = screwdyn::builtin::load("panda").unwrap();
    assert_eq!(m.nq(), 7);
    // q = 0 by hand from Craig's transforms: x = a4 + a5 + a7 = 0.088,
    // z = d1 + d3 + d5 − d_flange = 0.333 + 0.316 + 0.384 − 0.107 = 0.926, flange z pointing down.
    let h = pose(&m, &[0.0; 7], "panda_link8");
    assert!(
        (h.fixed_view::<3, 1>(0, 3) - Vector3::new(0.088, 0.0, 0.926)).amax() < 1e-12,
        "{h}"
    );
    let want_r = nalgebra::Matrix3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
    assert!((h.fixed_view::<3, 3>(0, 0) - want_r).amax() < 1e-12, "{h}");
    // Joint 4's range is entirely negative (Franka's limits).
    assert!(m.joints()[3].limits.upper < 0.0);
}

#[test]
fn branched_robot_order_and_mirror_symmetry() {
    let m = screwdyn::builtin::load("branched").unwrap();
    assert_eq!(
        m.joint_names(),
        vec![
            "torso_yaw",
            "left_shoulder_pitch",
            "left_shoulder_roll",
            "left_elbow",
            "right_shoulder_pitch",
            "right_shoulder_roll",
            "right_elbow"
        ]
    );
    assert_eq!(
        m.parents(),
        &[None, Some(0), Some(1), Some(2), Some(0), Some(4), Some(5)]
    );
    // The head is merged into the torso: 12 + 3 kg.
    assert!((m.bodies()[0].inertia.mass - 15.0).abs() < 1e-12);
    // The right arm mirrors the left in the xz-plane: pitch and elbow (about y) keep their sign,
    // roll (about x) flips; the hands then mirror (y ↦ −y).
    let mut rng = rand::rngs::StdRng::seed_from_u64(5);
    for _ in 0..10 {
        let (p, r, e): (f64, f64, f64) = (
            rng.gen_range(-3.0..3.0),
            rng.gen_range(-1.5..1.5),
            rng.gen_range(-2.4..0.0),
        );
        let q = [0.0, p, r, e, p, -r, e];
        let (l, rt) = (pose(&m, &q, "left_hand"), pose(&m, &q, "right_hand"));
        assert!(
            (l[(0, 3)] - rt[(0, 3)]).abs() < 1e-12
                && (l[(1, 3)] + rt[(1, 3)]).abs() < 1e-12
                && (l[(2, 3)] - rt[(2, 3)]).abs() < 1e-12
        );
        // and the mass matrix entries of the two arms agree (up to the roll sign).
        let mm = mass_matrix(&m, &q);
        assert!((mm[(1, 1)] - mm[(4, 4)]).abs() < 1e-12 && (mm[(3, 3)] - mm[(6, 6)]).abs() < 1e-12);
    }
}
