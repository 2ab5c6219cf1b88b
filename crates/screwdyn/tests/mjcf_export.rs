//! Export to MJCF read back by the MJCF loader: the same joints (limits, damping, friction,
//! armature, effort), mass matrix, bias forces and frame poses at random states. (MuJoCo itself
//! checks the exported files in the Python suite, `test_mjcf_export.py`.)

mod common;

use common::{assert_close, random_tree, random_vec};
use rand::{rngs::StdRng, SeedableRng};
use screwdyn::dynamics::{crba, nonlinear_effects};
use screwdyn::io::mjcf::parse_mjcf;
use screwdyn::io::mjcf_export::to_mjcf_string;
use screwdyn::io::{load_str, LoadOptions};
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::model::FrameKind;
use screwdyn::{builtin, Model, Workspace};

const DH_ARM: &str = r#"
format = "dh"
[[row]]
type = "R"
a = 0.3
alpha = 1.5707963267948966
d = 0.4
armature = 0.3
damping = 0.4
friction = 0.1
limits = { lower = -3, upper = 3, effort = 80 }
mass = 3.0
com = [-0.15, 0.0, 0.02]
inertia = [0.02, 0.001, 0.0, 0.05, 0.002, 0.04]
[[row]]
type = "P"
alpha = -1.5707963267948966
theta = 0.1
armature = 0.05
limits = { lower = 0.0, upper = 0.3, effort = 100 }
mass = 1.0
inertia = [0.004, 0.0, 0.0, 0.004, 0.0, 0.002]
[[frame]]
name = "tool"
link = "link2"
pose = { xyz = [0.0, 0.05, 0.12], rpy = [0.3, -0.2, 0.9] }
"#;

fn round_trip(m: &Model, tol: f64) {
    let xml = to_mjcf_string(m).unwrap();
    let back = parse_mjcf(&xml, "exported.xml", &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}\n{xml}", m.name()));
    assert_eq!(back.joint_names(), m.joint_names());
    for (a, b) in back.joints().iter().zip(m.joints()) {
        assert_eq!(
            (a.armature, a.damping, a.friction),
            (b.armature, b.damping, b.friction),
            "{}",
            a.name
        );
        if b.limits.effort.is_finite() && b.limits.effort > 0.0 {
            assert_eq!(a.limits.effort, b.limits.effort, "{}", a.name);
        }
    }
    let n = m.nq();
    let (mut wa, mut wb) = (Workspace::new(&back), Workspace::new(m));
    let mut rng = StdRng::seed_from_u64(n as u64);
    for _ in 0..4 {
        let q = random_vec(&mut rng, n, 0.3);
        let v = random_vec(&mut rng, n, 2.0);
        let ma = crba(&back, &mut wa, &q).unwrap().clone();
        let mb = crba(m, &mut wb, &q).unwrap();
        assert_close(ma.as_slice(), mb.as_slice(), tol, "M");
        let ha = nonlinear_effects(&back, &mut wa, &q, &v).unwrap().clone();
        let hb = nonlinear_effects(m, &mut wb, &q, &v).unwrap();
        assert_close(ha.as_slice(), hb.as_slice(), tol, "C q̇ + g");
        forward_kinematics(&back, &mut wa, &q).unwrap();
        forward_kinematics(m, &mut wb, &q).unwrap();
        for (k, f) in m.frames().iter().enumerate() {
            if f.kind == FrameKind::Base {
                continue; // MuJoCo's world
            }
            let Ok(kb) = back.frame_id(&f.name) else {
                panic!("{}: frame '{}' lost", m.name(), f.name)
            };
            let pa = frame_pose(&back, &wa, kb).unwrap().to_matrix();
            let pb = frame_pose(m, &wb, k).unwrap().to_matrix();
            assert_close(pa.as_slice(), pb.as_slice(), tol, &f.name);
        }
    }
}

#[test]
fn exported_models_load_back_with_the_same_dynamics() {
    for name in ["ur5", "panda", "branched"] {
        round_trip(&builtin::load(name).unwrap(), 1e-12);
    }
    let dh = load_str(DH_ARM, "dh_arm.toml", &LoadOptions::default()).unwrap();
    round_trip(&dh, 1e-12);
    let mut rng = StdRng::seed_from_u64(3);
    round_trip(
        &random_tree(&mut rng, 5, false)
            .with_armature(&[0.1, 0.2, 0.0, 0.3, 0.05])
            .unwrap(),
        1e-12,
    );
    // Point masses come back with the 1e-14 bound MuJoCo needs.
    round_trip(&builtin::planar2(), 1e-12);
}
