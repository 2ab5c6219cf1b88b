//! The binary's `fk`, `jacobian` and `info` commands, checked against the planar two-link
//! closed form of seeds 003/004 and for clean errors.

use assert_cmd::Command;
use serde_json::Value;

fn run_json(args: &[&str]) -> Value {
    let out = Command::cargo_bin("screwdyn")
        .unwrap()
        .args(args)
        .args(["--format", "json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn fails(args: &[&str], expected: &str) {
    let out = Command::cargo_bin("screwdyn")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(expected), "{err}");
    assert!(!err.contains("panicked"));
    assert_eq!(err.trim().lines().count(), 1, "one sentence: {err}");
}

#[test]
fn fk_of_planar2_matches_closed_form() {
    let (q1, q2) = (0.3_f64, -0.8_f64);
    let v = run_json(&["fk", "builtin:planar2", "--q", "0.3,-0.8"]);
    assert_eq!(v["joints"], serde_json::json!(["joint1", "joint2"]));
    let h = &v["poses"]["link2"];
    let x = h[0][3].as_f64().unwrap();
    let y = h[1][3].as_f64().unwrap();
    assert!((x - (q1.cos() + (q1 + q2).cos())).abs() < 1e-12);
    assert!((y - (q1.sin() + (q1 + q2).sin())).abs() < 1e-12);
    // Rotation about z by q1 + q2.
    assert!((h[0][0].as_f64().unwrap() - (q1 + q2).cos()).abs() < 1e-12);
    assert_eq!(h[3], serde_json::json!([0.0, 0.0, 0.0, 1.0]));
}

#[test]
fn jacobian_of_planar2_matches_closed_form() {
    let (q1, q2) = (0.3_f64, -0.8_f64);
    let v = run_json(&[
        "jacobian",
        "builtin:planar2",
        "--q",
        "0.3,-0.8",
        "--frame",
        "link2",
        "--reference",
        "world-aligned",
    ]);
    let j = &v["jacobian"];
    let at = |r: usize, c: usize| j[r][c].as_f64().unwrap();
    // ẋ = −(s1 + s12) q̇1 − s12 q̇2, ẏ = (c1 + c12) q̇1 + c12 q̇2, ω_z = q̇1 + q̇2.
    assert!((at(3, 0) + q1.sin() + (q1 + q2).sin()).abs() < 1e-12);
    assert!((at(3, 1) + (q1 + q2).sin()).abs() < 1e-12);
    assert!((at(4, 0) - q1.cos() - (q1 + q2).cos()).abs() < 1e-12);
    assert!((at(4, 1) - (q1 + q2).cos()).abs() < 1e-12);
    assert_eq!(at(2, 0), 1.0);
    assert_eq!(at(2, 1), 1.0);
}

#[test]
fn info_reports_the_tree() {
    let v = run_json(&["info", "builtin:planar2"]);
    assert_eq!(v["nq"], 2);
    assert_eq!(v["total_mass"], 2.0);
    assert_eq!(v["gravity"], serde_json::json!([0.0, -9.81, 0.0]));
}

#[test]
fn bad_input_is_one_sentence_and_exit_2() {
    fails(
        &["fk", "builtin:planar2", "--q", "0.1"],
        "--q has 1 values, the model has 2 joints: joint1, joint2",
    );
    fails(
        &["fk", "builtin:planar2", "--q", "0.1,abc"],
        "--q: 'abc' is not a number",
    );
    fails(
        &["fk", "builtin:planar2", "--q", "0.1,NaN"],
        "--q contains a non-finite value",
    );
    fails(&["fk", "builtin:nope"], "no built-in robot named 'nope'");
    fails(
        &["jacobian", "builtin:planar2", "--frame", "hand"],
        "no frame named 'hand'",
    );
}

#[test]
fn bench_json_has_every_default_algorithm() {
    let v = run_json(&["bench", "builtin:ur5", "--batches", "3", "--calls", "100"]);
    assert_eq!(v["model"], "ur5");
    assert_eq!(v["nq"], 6);
    for key in ["fk", "jacobians", "rnea", "crba", "aba"] {
        let ns = v["ns_per_call"][key].as_f64().unwrap_or(-1.0);
        assert!(ns > 0.0, "{key}: {ns}");
    }
}

#[test]
fn bench_rejects_an_unknown_algorithm() {
    fails(
        &["bench", "builtin:ur5", "--algorithms", "fk,warp"],
        "unknown algorithm 'warp'",
    );
}

/// A planar two-link MJCF arm (unit links about z) with two named configurations.
const KEYFRAMES_XML: &str = r#"<mujoco model="two">
  <compiler angle="radian"/>
  <worldbody>
    <body name="l1">
      <joint name="j1" type="hinge" axis="0 0 1" range="-3 3"/>
      <geom type="capsule" fromto="0 0 0 1 0 0" size="0.05" mass="1"/>
      <body name="l2" pos="1 0 0">
        <joint name="j2" type="hinge" axis="0 0 1" range="-3 3"/>
        <geom type="capsule" fromto="0 0 0 1 0 0" size="0.05" mass="1"/>
        <site name="tip" pos="1 0 0"/>
      </body>
    </body>
  </worldbody>
  <keyframe><key name="home" qpos="0.3 -0.8"/><key name="far" qpos="1 0.5"/></keyframe>
</mujoco>
"#;

#[test]
fn keyframes_stand_for_q_q0_and_qf() {
    let dir = std::env::temp_dir().join(format!("screwdyn-keyframes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("two.xml");
    std::fs::write(&file, KEYFRAMES_XML).unwrap();
    let m = file.to_str().unwrap();
    // --q key:home: the tip of the planar arm at (cos q1 + cos(q1+q2), sin q1 + sin(q1+q2)).
    let v = run_json(&["fk", m, "--q", "key:home", "--frame", "tip"]);
    let tip = &v["poses"]["tip"];
    let (q1, q2) = (0.3_f64, -0.8_f64);
    let x = q1.cos() + (q1 + q2).cos();
    let y = q1.sin() + (q1 + q2).sin();
    assert!((tip[0][3].as_f64().unwrap() - x).abs() < 1e-12, "{v}");
    assert!((tip[1][3].as_f64().unwrap() - y).abs() < 1e-12, "{v}");
    // --q0 (simulate): the run starts at the key's values.
    let run = run_json(&["simulate", m, "--q0", "key:home", "--duration", "0.002"]);
    assert_eq!(run["q.j1"][0].as_f64(), Some(0.3));
    assert_eq!(run["q.j2"][0].as_f64(), Some(-0.8));
    // --q0 and --qf (torque-profile): the quintic runs from one key to the other.
    let csv = dir.join("profile.csv");
    let out = Command::cargo_bin("screwdyn")
        .unwrap()
        .args(["torque-profile", m, "--q0", "key:home", "--qf", "key:far"])
        .args(["--output", csv.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let row = |line: &str| -> Vec<f64> { line.split(',').map(|x| x.parse().unwrap()).collect() };
    let first = row(text.lines().nth(1).unwrap());
    let last = row(text.lines().last().unwrap());
    assert_eq!(&first[1..3], &[0.3, -0.8]);
    assert!(
        (last[1] - 1.0).abs() < 1e-12 && (last[2] - 0.5).abs() < 1e-12,
        "{last:?}"
    );
    fails(
        &["fk", m, "--q", "key:nope"],
        "no keyframe named 'nope' (known: home, far)",
    );
    std::fs::remove_dir_all(&dir).ok();
}
