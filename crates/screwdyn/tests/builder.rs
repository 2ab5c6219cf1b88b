//! The model builder: depth-first ordering, fixed-joint merging and its error messages.

use nalgebra::{Matrix3, Vector3, Vector6};
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::model::{FrameKind, JointSpec, ModelBuilder};
use screwdyn::spatial::{prismatic_screw, Se3, SpatialInertia};
use screwdyn::Workspace;

fn rz() -> Vector6<f64> {
    Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0)
}
fn mass(m: f64) -> SpatialInertia {
    SpatialInertia::new(m, Vector3::new(0.1, 0.0, 0.0), Matrix3::identity() * 0.01)
}
fn t(x: f64, y: f64, z: f64) -> Se3 {
    Se3::from_translation(Vector3::new(x, y, z))
}

#[test]
fn joints_are_ordered_depth_first_in_declaration_order() {
    // Declared out of order: the torso's children come before the torso itself.
    let mut b = ModelBuilder::new("tree");
    b.link(
        "l_upper",
        "torso",
        JointSpec::revolute("l_shoulder").screw_in_child(rz()),
        t(0.0, 0.2, 0.0),
        mass(1.0),
    )
    .link(
        "r_upper",
        "torso",
        JointSpec::revolute("r_shoulder").screw_in_child(rz()),
        t(0.0, -0.2, 0.0),
        mass(1.0),
    )
    .link(
        "r_lower",
        "r_upper",
        JointSpec::revolute("r_elbow").screw_in_child(rz()),
        t(0.3, 0.0, 0.0),
        mass(1.0),
    )
    .link(
        "torso",
        "base",
        JointSpec::revolute("waist").screw_in_child(rz()),
        t(0.0, 0.0, 0.5),
        mass(5.0),
    )
    .link(
        "l_lower",
        "l_upper",
        JointSpec::revolute("l_elbow").screw_in_child(rz()),
        t(0.3, 0.0, 0.0),
        mass(1.0),
    );
    let m = b.build().unwrap();
    assert_eq!(
        m.joint_names(),
        vec!["waist", "l_shoulder", "l_elbow", "r_shoulder", "r_elbow"]
    );
    assert_eq!(m.parents(), &[None, Some(0), Some(1), Some(0), Some(3)]);
}

#[test]
fn fixed_joints_merge_mass_and_keep_the_frame() {
    let mut b = ModelBuilder::new("fixed");
    b.link(
        "arm",
        "base",
        JointSpec::revolute("j1").screw_in_child(rz()),
        t(0.0, 0.0, 1.0),
        SpatialInertia::point_mass(2.0, Vector3::zeros()),
    )
    .link(
        "hand",
        "arm",
        JointSpec::fixed("wrist"),
        t(1.0, 0.0, 0.0),
        SpatialInertia::point_mass(1.0, Vector3::zeros()),
    )
    .link(
        "finger",
        "hand",
        JointSpec::prismatic("slide").screw_in_child(prismatic_screw(Vector3::x())),
        t(0.5, 0.0, 0.0),
        SpatialInertia::point_mass(0.5, Vector3::zeros()),
    )
    .frame("tip", "finger", t(0.1, 0.0, 0.0));
    let m = b.build().unwrap();
    assert_eq!(m.nq(), 2);
    // The merged body: 3 kg with the CoM at (2·0 + 1·1)/3 = 1/3 along x.
    let arm = &m.bodies()[0].inertia;
    assert!((arm.mass - 3.0).abs() < 1e-15);
    assert!((arm.com - Vector3::new(1.0 / 3.0, 0.0, 0.0)).norm() < 1e-15);
    // Its inertia about the arm origin is Σ m r² = 1 kg · 1 m² about y and z.
    let io = arm.inertia_about_origin();
    assert!((io[(2, 2)] - 1.0).abs() < 1e-14 && (io[(1, 1)] - 1.0).abs() < 1e-14);
    // The finger hangs off the arm body with home composed through the hand.
    assert_eq!(m.parent(1).unwrap(), Some(0));
    assert!((m.joints()[1].home.translation - Vector3::new(1.5, 0.0, 0.0)).norm() < 1e-15);
    let hand = m.frame_id("hand").unwrap();
    assert_eq!(m.frames()[hand].kind, FrameKind::FixedLink);
    let mut ws = Workspace::new(&m);
    forward_kinematics(&m, &mut ws, &[std::f64::consts::FRAC_PI_2, 0.2]).unwrap();
    let tip = frame_pose(&m, &ws, m.frame_id("tip").unwrap())
        .unwrap()
        .translation;
    // Rotated by 90° about z: x ↦ y. The tip sits at 1 + 0.5 + 0.2 + 0.1 = 1.8 along the arm.
    assert!((tip - Vector3::new(0.0, 1.8, 1.0)).norm() < 1e-14, "{tip}");
}

/// An arm (revolute about z, then about y) with a rotated, offset tool on a fixed joint.
fn arm_with_fixed_tool() -> screwdyn::Model {
    let mut b = ModelBuilder::new("tool");
    b.gravity(Vector3::zeros())
        .link(
            "upper",
            "base",
            JointSpec::revolute("j1").screw_in_child(rz()),
            t(0.0, 0.0, 0.3),
            mass(2.0),
        )
        .link(
            "fore",
            "upper",
            JointSpec::revolute("j2").screw_in_child(Vector6::new(0.0, 1.0, 0.0, 0.0, 0.0, 0.0)),
            t(0.4, 0.0, 0.0),
            mass(1.0),
        )
        .link(
            "tool",
            "fore",
            JointSpec::fixed("flange"),
            Se3::from_rpy(0.3, -0.7, 1.1).with_translation(Vector3::new(0.25, 0.05, -0.1)),
            mass(0.5),
        )
        .frame("tcp", "tool", t(0.0, 0.0, 0.1));
    b.build().unwrap()
}

#[test]
fn a_wrench_on_a_fixed_joint_link_is_the_same_wrench_moved_to_its_body() {
    use screwdyn::dynamics::{inverse_dynamics, ExternalWrenches};
    use screwdyn::kinematics::{compute_joint_jacobians, frame_jacobian, Reference};
    let m = arm_with_fixed_tool();
    let tool = m.link_frame_id("tool").unwrap();
    assert_eq!(m.frames()[tool].kind, FrameKind::FixedLink);
    let fore = m.body_id("fore").unwrap();
    let w_tool = Vector6::new(0.2, -0.4, 0.7, 3.0, -1.0, 2.0);
    let (q, zero) = ([0.4, -0.9], [0.0, 0.0]);
    let mut ws = Workspace::new(&m);
    let mut on_tool = ExternalWrenches::new(&m);
    on_tool.add_on_link(&m, tool, w_tool, false).unwrap();
    let tau_tool = inverse_dynamics(&m, &mut ws, &q, &zero, &zero, Some(&on_tool)).unwrap();
    let tau_tool = tau_tool.clone();
    // Moved by hand: W^{b} = Ad_{H_b^f}ᵀ W^{f}, with H_b^f = (H_f^b)⁻¹ the 6×6 matrix of Ad.
    let placement = m.frames()[tool].placement;
    let w_fore = placement.inverse().adjoint_matrix().transpose() * w_tool;
    let mut on_fore = ExternalWrenches::new(&m);
    on_fore.add_local(fore, w_fore).unwrap();
    let tau_fore = inverse_dynamics(&m, &mut ws, &q, &zero, &zero, Some(&on_fore)).unwrap();
    let tau_fore = tau_fore.clone();
    assert!((tau_tool.clone() - tau_fore).norm() < 1e-13);
    // Statics without gravity: τ = −J_fᵀ W^{f} with the tool's body Jacobian J_f^{f,0}.
    compute_joint_jacobians(&m, &mut ws, &q).unwrap();
    let mut j = nalgebra::Matrix6xX::zeros(2);
    frame_jacobian(&m, &ws, tool, Reference::Local, &mut j).unwrap();
    let expected = -(j.transpose() * w_tool);
    assert!(
        (tau_tool.clone() - expected.clone()).norm() < 1e-13,
        "{tau_tool} {expected}"
    );
    // The same wrench written in the base frame: τ = −J^{0,0ᵀ} W^{0}, whichever link carries it.
    frame_jacobian(&m, &ws, tool, Reference::World, &mut j).unwrap();
    let mut in_world = ExternalWrenches::new(&m);
    in_world.add_on_link(&m, tool, w_tool, true).unwrap();
    let tau_world = inverse_dynamics(&m, &mut ws, &q, &zero, &zero, Some(&in_world)).unwrap();
    let tau_world = tau_world.clone();
    assert!((tau_world - (-(j.transpose() * w_tool))).norm() < 1e-13);
}

#[test]
fn a_wrench_needs_a_link_that_moves() {
    use screwdyn::dynamics::ExternalWrenches;
    let m = arm_with_fixed_tool();
    let mut ext = ExternalWrenches::new(&m);
    let w = Vector6::repeat(1.0);
    let e = m.link_frame_id("tcp").unwrap_err().to_string();
    assert!(
        e.contains("no link named 'tcp'") && e.contains("tool"),
        "{e}"
    );
    let tcp = m.frame_id("tcp").unwrap();
    let e = ext.add_on_link(&m, tcp, w, false).unwrap_err().to_string();
    assert_eq!(
        e,
        "an external wrench on 'tcp', which is a frame, not a link: name a link"
    );
    let base = m.link_frame_id("base").unwrap();
    let e = ext.add_on_link(&m, base, w, true).unwrap_err().to_string();
    assert_eq!(
        e,
        "an external wrench on link 'base', which is fixed to the base and cannot act on the robot"
    );
    let mut nan = w;
    nan[3] = f64::NAN;
    let tool = m.link_frame_id("tool").unwrap();
    assert!(ext.add_on_link(&m, tool, nan, false).is_err());
}

fn err(b: &ModelBuilder) -> String {
    b.build().unwrap_err().to_string()
}

#[test]
fn tree_errors_name_the_problem() {
    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "nowhere",
        JointSpec::revolute("ja").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert_eq!(
        err(&b),
        "joint 'ja' names parent link 'nowhere', which does not exist"
    );

    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("ja").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    )
    .link(
        "a",
        "base",
        JointSpec::revolute("jb").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert_eq!(err(&b), "two links are named 'a'");

    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("ja").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    )
    .link(
        "b",
        "base",
        JointSpec::revolute("jb").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    )
    .link(
        "a",
        "b",
        JointSpec::revolute("jc").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert!(
        err(&b).starts_with("link 'a' has two parents: 'base' (joint 'ja') and 'b' (joint 'jc')")
    );

    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("j").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    )
    .link(
        "b",
        "a",
        JointSpec::revolute("j").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert_eq!(err(&b), "two joints are named 'j'");

    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "b",
        JointSpec::revolute("ja").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    )
    .link(
        "b",
        "a",
        JointSpec::revolute("jb").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert_eq!(
        err(&b),
        "links a, b form a cycle and are not connected to the root link 'base'"
    );
}

#[test]
fn joint_and_inertia_errors_name_the_problem() {
    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("ja").screw_in_child(Vector6::new(0.0, 0.0, 2.0, 0.0, 0.0, 0.0)),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert!(err(&b).contains("joint 'ja' (revolute)") && err(&b).contains("unit vector"));

    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("ja").screw_in_child(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.3)),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert!(err(&b).contains("pitch"));

    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("ja"),
        t(0.0, 0.0, 0.0),
        mass(1.0),
    );
    assert_eq!(err(&b), "joint 'ja' has no screw axis");

    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("ja").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        SpatialInertia::point_mass(0.0, Vector3::zeros()),
    );
    assert_eq!(
        b.build().unwrap().physical_problems()[0].to_string(),
        "link 'a' is a moving leaf body with no mass: joint 'ja' moves nothing"
    );
    b.strict(true);
    assert!(err(&b).contains("link 'a' is a moving leaf body with no mass"));

    let mut b = ModelBuilder::new("x");
    let flat = SpatialInertia::new(
        1.0,
        Vector3::zeros(),
        Matrix3::from_diagonal(&Vector3::new(0.1, 0.1, 0.5)),
    );
    b.link(
        "a",
        "base",
        JointSpec::revolute("ja").screw_in_child(rz()),
        t(0.0, 0.0, 0.0),
        flat,
    );
    let m = b.build().unwrap();
    assert!(m.physical_problems()[0]
        .to_string()
        .starts_with("link 'a': its inertia breaks the triangle inequality"));
    b.strict(true);
    assert!(err(&b).starts_with("the model is not physically consistent: link 'a': its inertia breaks the triangle inequality"));
}
