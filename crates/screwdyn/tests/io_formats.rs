//! The description formats agree with each other and with the seeds (issue 3).
//!
//! Mass matrices are computed here with the seed-001 formula
//! `M(q) = Σ_i J_i^{i,0}(q)ᵀ 𝔍^{i,i} J_i^{i,0}(q)`, independently of the dynamics module.

use nalgebra::{DMatrix, Matrix6xX};
use rand::{Rng, SeedableRng};
use screwdyn::io::{load_model, LoadOptions};
use screwdyn::kinematics::{compute_joint_jacobians, frame_pose, link_jacobian};
use screwdyn::{Model, Workspace};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/");
const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../models/");

fn data(name: &str) -> String {
    format!("{DATA}{name}")
}

fn load(path: &str) -> Model {
    load_model(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Seed 001: `M(q) = Σ_i J_iᵀ 𝔍_i J_i` with the body Jacobians `J_i^{i,0}`.
fn mass_matrix(m: &Model, q: &[f64]) -> DMatrix<f64> {
    let n = m.nq();
    let mut ws = Workspace::new(m);
    compute_joint_jacobians(m, &mut ws, q).unwrap();
    let mut out = DMatrix::zeros(n, n);
    let mut j = Matrix6xX::zeros(n);
    for (i, b) in m.bodies().iter().enumerate() {
        link_jacobian(m, &ws, i, &mut j).unwrap();
        let jd = DMatrix::from_column_slice(6, n, j.as_slice());
        let inertia = DMatrix::from_column_slice(6, 6, b.inertia.matrix().as_slice());
        out += jd.transpose() * inertia * jd;
    }
    out
}

fn pose(m: &Model, q: &[f64], frame: &str) -> nalgebra::Matrix4<f64> {
    let mut ws = Workspace::new(m);
    screwdyn::kinematics::forward_kinematics(m, &mut ws, q).unwrap();
    frame_pose(m, &ws, m.frame_id(frame).unwrap())
        .unwrap()
        .to_matrix()
}

/// Random configurations within `[-2, 2]` (prismatic joints within their limits).
fn random_q(m: &Model, rng: &mut impl Rng) -> Vec<f64> {
    m.joints()
        .iter()
        .map(|j| {
            let lo = j.limits.lower.max(-2.0);
            let hi = j.limits.upper.min(2.0);
            rng.gen_range(lo..hi)
        })
        .collect()
}

/// Same joint names, same poses of every frame in `frames`, same mass matrices (1e-12).
fn assert_same_robot(models: &[(&str, Model)], frames: &[&str], trials: usize) {
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let (name0, m0) = &models[0];
    for _ in 0..trials {
        let q = random_q(m0, &mut rng);
        let mm0 = mass_matrix(m0, &q);
        for (name, m) in &models[1..] {
            assert_eq!(m.joint_names(), m0.joint_names(), "{name} vs {name0}");
            let mm = mass_matrix(m, &q);
            let d = (&mm - &mm0).amax();
            assert!(
                d < 1e-12,
                "mass matrix of {name} differs from {name0} by {d:e} at {q:?}"
            );
            for f in frames {
                let d = (pose(m, &q, f) - pose(m0, &q, f)).amax();
                assert!(
                    d < 1e-12,
                    "pose of {f} in {name} differs from {name0} by {d:e}"
                );
            }
        }
    }
}

#[test]
fn arm3_is_the_same_robot_as_urdf_dh_poe_and_native_toml() {
    let models = [
        ("dh", load(&data("arm3_dh.toml"))),
        ("native", load(&data("arm3_native.toml"))),
        ("urdf", load(&data("arm3.urdf"))),
        ("poe", load(&data("arm3_poe.toml"))),
    ];
    assert_same_robot(&models, &["base", "link1", "link2", "link3", "tool"], 25);
    // The PoE's M is the same tool point.
    let q = [0.3, -0.7, 0.12];
    let poe = &models[3].1;
    assert!((pose(poe, &q, "ee") - pose(&models[0].1, &q, "tool")).amax() < 1e-12);
    // The inertias really are non-trivial (off-diagonal terms, CoM off the origin).
    let b = &models[0].1.bodies()[0].inertia;
    assert!(b.inertia_com[(0, 1)] != 0.0 && b.com.norm() > 0.05);
}

#[test]
fn planar2_in_every_format_matches_the_seed_closed_form() {
    let models = [
        ("builtin", load("builtin:planar2")),
        ("native", load(&format!("{MODELS}planar2.toml"))),
        ("dh", load(&data("planar2_dh.toml"))),
        ("modified-dh", load(&data("planar2_mdh.toml"))),
        ("poe", load(&data("planar2_poe.toml"))),
        ("urdf", load(&data("planar2.urdf"))),
    ];
    assert_same_robot(&models, &["base", "link1", "link2"], 10);
    // Seed 003/004: M11 = m1 L1² + m2 (L1² + L2² + 2 L1 L2 c2), M12 = m2 (L2² + L1 L2 c2), M22 = m2 L2².
    for (name, m) in &models {
        for q2 in [0.0, 0.4, 1.9, -2.5] {
            let mm = mass_matrix(m, &[0.8, q2]);
            let c2 = f64::cos(q2);
            let want = [[3.0 + 2.0 * c2, 1.0 + c2], [1.0 + c2, 1.0]];
            for r in 0..2 {
                for c in 0..2 {
                    assert!((mm[(r, c)] - want[r][c]).abs() < 1e-12, "{name}: M = {mm}");
                }
            }
        }
    }
}

#[test]
fn models_planar2_toml_equals_builtin_planar2() {
    assert_eq!(
        load(&format!("{MODELS}planar2.toml")),
        screwdyn::builtin::planar2()
    );
}

const OUT_OF_ORDER: &str = r#"<robot name="tree">
  <link name="a2"><inertial><mass value="1"/></inertial></link>
  <link name="b1"><inertial><mass value="1"/></inertial></link>
  <link name="root"/>
  <link name="a"><inertial><mass value="1"/></inertial></link>
  <link name="b"><inertial><mass value="1"/></inertial></link>
  <link name="a1"><inertial><mass value="1"/></inertial></link>
  <joint name="j_b1" type="revolute"><parent link="b"/><child link="b1"/><axis xyz="0 1 0"/></joint>
  <joint name="j_a2" type="prismatic"><parent link="a"/><child link="a2"/><axis xyz="1 0 0"/></joint>
  <joint name="j_b" type="continuous"><parent link="root"/><child link="b"/><origin xyz="0 0 1"/></joint>
  <joint name="j_a1" type="revolute"><parent link="a"/><child link="a1"/></joint>
  <joint name="j_a" type="revolute"><parent link="root"/><child link="a"/><axis xyz="0 0 1"/></joint>
</robot>"#;

#[test]
fn joint_order_is_depth_first_from_the_root_children_in_file_order() {
    let m = screwdyn::io::load_str(OUT_OF_ORDER, "tree.urdf", &LoadOptions::default()).unwrap();
    // DESIGN §4 by hand: root's children in file order are b (j_b) then a (j_a); b's child b1;
    // a's children in file order a2 (j_a2) then a1 (j_a1).
    assert_eq!(m.joint_names(), vec!["j_b", "j_b1", "j_a", "j_a2", "j_a1"]);
    assert_eq!(m.parents(), &[None, Some(0), None, Some(2), Some(2)]);
    assert_eq!(m.base().name, "root");
    // The same tree in native TOML, bodies listed out of order, gives the same order.
    let toml = r#"
format = "screwdyn"
base = "root"
[[body]]
name = "b1"
parent = "b"
joint = "j_b1"
type = "revolute"
screw_in_child = [0, 1, 0, 0, 0, 0]
mass = 1
[[body]]
name = "a2"
parent = "a"
joint = "j_a2"
type = "prismatic"
screw_in_child = [0, 0, 0, 1, 0, 0]
mass = 1
[[body]]
name = "b"
parent = "root"
joint = "j_b"
type = "continuous"
home = { xyz = [0, 0, 1] }
screw_in_child = [1, 0, 0, 0, 0, 0]
mass = 1
[[body]]
name = "a1"
parent = "a"
joint = "j_a1"
type = "revolute"
screw_in_child = [1, 0, 0, 0, 0, 0]
mass = 1
[[body]]
name = "a"
parent = "root"
joint = "j_a"
type = "revolute"
screw_in_child = [0, 0, 1, 0, 0, 0]
mass = 1
"#;
    let n = screwdyn::io::load_str(toml, "tree.toml", &LoadOptions::default()).unwrap();
    assert_eq!(n.joint_names(), m.joint_names());
    assert_eq!(n.parents(), m.parents());
    assert_same_robot(&[("urdf", m), ("toml", n)], &["a1", "a2", "b1"], 5);
}

#[test]
fn urdf_details_axis_inertial_rotation_limits_dynamics_mimic_meshes() {
    let text = r#"<robot name="d">
  <link name="base"><visual><geometry><mesh filename="package://d/base.stl"/></geometry></visual></link>
  <link name="l1">
    <inertial><origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/><mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="2.5"/></inertial>
    <collision><geometry><mesh filename="l1.dae"/></geometry></collision>
  </link>
  <link name="l2"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 3 4"/>
    <limit lower="-1" upper="2" effort="30" velocity="4"/><dynamics damping="0.5" friction="0.2"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="3" velocity="1"/><mimic joint="j1" multiplier="-2" offset="0.1"/></joint>
</robot>"#;
    let m = screwdyn::io::load_str(text, "d.urdf", &LoadOptions::default()).unwrap();
    let j1 = &m.joints()[0];
    // The axis is normalised: (0, 3, 4)/5.
    assert!((j1.screw - nalgebra::Vector6::new(0.0, 0.6, 0.8, 0.0, 0.0, 0.0)).amax() < 1e-15);
    assert_eq!(
        (
            j1.limits.lower,
            j1.limits.upper,
            j1.limits.effort,
            j1.limits.velocity
        ),
        (-1.0, 2.0, 30.0, 4.0)
    );
    assert_eq!((j1.damping, j1.friction), (0.5, 0.2));
    // I_c = R I Rᵀ with R = Rz(90°): the x and y moments swap.
    let i = &m.bodies()[0].inertia;
    assert!(
        (i.inertia_com[(0, 0)] - 2.0).abs() < 1e-15 && (i.inertia_com[(1, 1)] - 1.0).abs() < 1e-15
    );
    // A continuous joint has no position limits; the mimic tag is kept, the joint independent.
    let j2 = &m.joints()[1];
    let none = screwdyn::model::JointLimits::<f64>::default();
    assert_eq!((j2.limits.lower, j2.limits.upper), (none.lower, none.upper));
    assert_eq!((j2.limits.effort, j2.limits.velocity), (3.0, 1.0));
    assert_eq!(
        j2.mimic
            .as_ref()
            .map(|x| (x.joint.as_str(), x.multiplier, x.offset)),
        Some(("j1", -2.0, 0.1))
    );
    assert_eq!(m.nq(), 2);
    assert_eq!(m.meshes().len(), 2);
    assert_eq!(m.meshes()[1], ("l1".to_string(), "l1.dae".to_string()));
}

fn assert_round_trip(m: &Model, what: &str) {
    let text = screwdyn::io::urdf::to_urdf_string(m).unwrap();
    let back = screwdyn::io::load_str(&text, "export.urdf", &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{what}: {e}\n{text}"))
        .with_gravity(m.gravity())
        .unwrap();
    let frames: Vec<&str> = m.frames().iter().map(|f| f.name.as_str()).collect();
    assert_same_robot(
        &[(what, m.clone()), ("exported", back.clone())],
        &frames,
        10,
    );
    for (a, b) in m.joints().iter().zip(back.joints()) {
        assert_eq!(
            (a.limits.lower, a.limits.upper),
            (b.limits.lower, b.limits.upper),
            "{what}"
        );
        assert_eq!(
            (a.limits.effort, a.limits.velocity),
            (b.limits.effort, b.limits.velocity),
            "{what}"
        );
        assert_eq!(
            (a.damping, a.friction, &a.mimic),
            (b.damping, b.friction, &b.mimic),
            "{what}"
        );
    }
    assert!((m.total_mass() - back.total_mass()).abs() < 1e-12);
    assert_eq!(m.meshes(), back.meshes());
}

#[test]
fn exported_urdf_loads_back_to_the_same_model() {
    for path in [
        data("arm3_dh.toml"),
        data("arm3_poe.toml"),
        data("arm3.urdf"),
        data("planar2_mdh.toml"),
    ] {
        assert_round_trip(&load(&path), &path);
    }
    for name in screwdyn::builtin::NAMES {
        assert_round_trip(&load(&format!("builtin:{name}")), name);
    }
    // A URDF whose axes pass through the link origins comes back link for link.
    let m = screwdyn::io::load_str(OUT_OF_ORDER, "tree.urdf", &LoadOptions::default()).unwrap();
    let text = screwdyn::io::urdf::to_urdf_string(&m).unwrap();
    let back = screwdyn::io::load_str(&text, "tree.urdf", &LoadOptions::default()).unwrap();
    for (a, b) in m.bodies().iter().zip(back.bodies()) {
        assert_eq!(a.name, b.name);
        assert!((a.inertia.matrix() - b.inertia.matrix()).amax() < 1e-15);
    }
    for (a, b) in m.joints().iter().zip(back.joints()) {
        assert!(
            (a.screw - b.screw).amax() < 1e-15
                && (a.home.to_matrix() - b.home.to_matrix()).amax() < 1e-15
        );
    }
}

#[test]
fn helical_joints_cannot_be_exported_to_urdf() {
    let toml = "format = \"screwdyn\"\n[[body]]\nname = \"nut\"\nparent = \"base\"\ntype = \"helical\"\npitch = 0.01\nscrew_in_child = [0, 0, 1, 0, 0, 0.01]\nmass = 1\n";
    let m = screwdyn::io::load_str(toml, "screw.toml", &LoadOptions::default()).unwrap();
    let e = screwdyn::io::urdf::to_urdf_string(&m)
        .unwrap_err()
        .to_string();
    assert!(e.contains("nut_joint") && e.contains("helical"), "{e}");
}

#[test]
fn native_rotations_as_rpy_quaternion_or_matrix_agree_and_gravity_is_read() {
    // Rz(π/2): rpy (0, 0, π/2), quaternion (cos π/4, 0, 0, sin π/4), matrix [[0,-1,0],[1,0,0],[0,0,1]].
    let h = std::f64::consts::FRAC_PI_4;
    let poses = [
        "rpy = [0, 0, 1.5707963267948966]".to_string(),
        format!("quaternion = [{}, 0, 0, {}]", h.cos(), h.sin()),
        "rotation = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]".to_string(),
    ];
    let mut homes = Vec::new();
    for p in &poses {
        let text = format!(
            "format = \"screwdyn\"\ngravity = [1, 2, 3]\n[[body]]\nname = \"a\"\nparent = \"base\"\ntype = \"revolute\"\nhome = {{ xyz = [1, 2, 3], {p} }}\nscrew_in_parent = [0, 0, 1, 0, 0, 0]\nmass = 1\n"
        );
        let m = screwdyn::io::load_str(&text, "r.toml", &LoadOptions::default()).unwrap();
        assert_eq!(m.gravity(), nalgebra::Vector3::new(1.0, 2.0, 3.0));
        homes.push(m.joints()[0].home.to_matrix());
    }
    let want = nalgebra::Matrix4::new(
        0.0, -1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 3.0, 0.0, 0.0, 0.0, 1.0,
    );
    for h in homes {
        assert!((h - want).amax() < 1e-15, "{h}");
    }
    // The default gravity of every TOML format is (0, 0, −9.81); planar2's files override it.
    let dh = screwdyn::io::load_str(
        "format = \"dh\"\n[[row]]\ntype = \"P\"\nmass = 1\n",
        "p.toml",
        &LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(dh.gravity(), nalgebra::Vector3::new(0.0, 0.0, -9.81));
    assert_eq!(
        load(&data("planar2_poe.toml")).gravity(),
        nalgebra::Vector3::new(0.0, -9.81, 0.0)
    );
}
