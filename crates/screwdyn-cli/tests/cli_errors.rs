//! Every kind of bad input exits with status 2 and one sentence on stderr naming what and
//! where; nothing panics.

mod common;
use common::*;

const GHOST: &str = r#"<?xml version="1.0"?>
<robot name="ghost">
  <link name="base"/>
  <link name="l1"/>
  <link name="l2"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="revolute">
    <parent link="l1"/><child link="l2"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"#;

fn bad_inertia_urdf() -> String {
    let text = std::fs::read_to_string(ARM3).unwrap();
    let good = r#"<inertia ixx="0.004" ixy="-0.0002" ixz="0.0003" iyy="0.0035" iyz="0.0001" izz="0.001"/>"#;
    assert!(text.contains(good));
    let bad = r#"<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.1"/>"#;
    let path = tmp("bad_inertia.urdf");
    std::fs::write(&path, text.replace(good, bad)).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn usage_errors() {
    fails(&["frobnicate"], "unrecognized subcommand 'frobnicate'");
    fails(
        &["fk", "builtin:planar2", "--bogus"],
        "unexpected argument '--bogus'",
    );
    fails(
        &["rnea", "builtin:planar2", "--format", "xml"],
        "invalid value 'xml'",
    );
    fails(&["torque-profile", "builtin:ur5"], "--qf");
    fails(
        &["aba", "builtin:planar2", "--method", "magic"],
        "--method: unknown forward-dynamics method 'magic'",
    );
    fails(
        &["simulate", "builtin:planar2", "--integrator", "leapfrog"],
        "--integrator: unknown integrator 'leapfrog'",
    );
}

#[test]
fn files_that_cannot_be_read() {
    fails(
        &["info", "/nonexistent/robot.urdf"],
        "/nonexistent/robot.urdf: cannot be read",
    );
    fails(&["info", "robot.step"], "robot.step: unknown model format");
    fails(
        &[
            "rnea",
            "builtin:planar2",
            "--input",
            "/nonexistent/states.csv",
        ],
        "/nonexistent/states.csv: cannot be read",
    );
    fails(&["info", "builtin:nope"], "no built-in robot named 'nope'");
}

#[test]
fn bad_vectors() {
    fails(
        &["rnea", "builtin:ur5", "--q", "1,2,3,4,5"],
        "--q has 5 values, the model has 6 joints: shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint",
    );
    fails(
        &["rnea", "builtin:planar2", "--v", "1,x"],
        "--v: 'x' is not a number",
    );
    fails(
        &["rnea", "builtin:planar2", "--a", "inf,0"],
        "--a contains a non-finite value",
    );
    fails(
        &["aba", "builtin:planar2", "--tau", "NaN,0"],
        "--tau contains a non-finite value",
    );
    fails(
        &["crba", "builtin:planar2", "--q", "1,2,3"],
        "--q has 3 values, the model has 2 joints: joint1, joint2",
    );
    fails(
        &["rnea", "builtin:planar2", "--gravity", "0,1"],
        "--gravity needs 3 numbers",
    );
    fails(
        &["simulate", "builtin:planar2", "--q0", "0.1"],
        "--q0 has 1 values",
    );
    fails(
        &["simulate", "builtin:planar2", "--controller", "constant"],
        "--controller constant needs --tau",
    );
    fails(
        &["simulate", "builtin:planar2", "--dt", "0"],
        "--dt must be positive",
    );
    fails(
        &["simulate", "builtin:planar2", "--limit-time-constant", "-1"],
        "--limit-time-constant must be positive (got -1)",
    );
    fails(
        &[
            "simulate",
            "builtin:planar2",
            "--limit-damping-ratio",
            "nan",
        ],
        "--limit-damping-ratio must be non-negative (got NaN)",
    );
    fails(
        &["simulate", "builtin:planar2", "--kp", "1"],
        "--kp is not used by --controller zero",
    );
    fails(
        &[
            "torque-profile",
            "builtin:ur5",
            "--qf",
            "1,1,1,1,1,1",
            "--vmax",
            "-1",
        ],
        "must be positive",
    );
    fails(
        &["explain", "builtin:planar2", "--q", "0,0", "--v", "1"],
        "--v has 1 values",
    );
}

#[test]
fn unknown_names() {
    fails(
        &["jacobian", "builtin:planar2", "--frame", "hand"],
        "no frame named 'hand'",
    );
    fails(
        &["fk", "builtin:planar2", "--frame", "hand"],
        "no frame named 'hand'",
    );
    fails(
        &["rnea", "builtin:planar2", "--wrench", "arm:0,0,0,0,0,1"],
        "no link named 'arm'",
    );
    fails(
        &[
            "rnea",
            "builtin:planar2",
            "--tip-wrench",
            "hand:0,0,0,0,0,1",
        ],
        "no frame named 'hand'",
    );
    fails(
        &["rnea", "builtin:planar2", "--wrench", "link1:0,0,1"],
        "--wrench needs 6 numbers",
    );
    fails(
        &[
            "simulate",
            "builtin:planar2",
            "--disturbance",
            "link9:0,0,0,0,0,1@0-1",
        ],
        "no moving body named 'link9'",
    );
    fails(
        &[
            "simulate",
            "builtin:planar2",
            "--disturbance",
            "link1:0,0,0,0,0,1",
        ],
        "--disturbance 'link1:0,0,0,0,0,1' must look like",
    );
}

#[test]
fn bad_csv_files() {
    let p = tmp("unknown_column.csv");
    std::fs::write(&p, "q.joint1,q.elbow\n0,0\n").unwrap();
    let e = fails(
        &["rnea", "builtin:planar2", "--input", p.to_str().unwrap()],
        "unknown column 'q.elbow'",
    );
    assert!(e.contains("unknown_column.csv"));
    let p = tmp("not_a_number.csv");
    std::fs::write(&p, "q.joint1,q.joint2\n0,0\n0,zero\n").unwrap();
    fails(
        &["rnea", "builtin:planar2", "--input", p.to_str().unwrap()],
        "not_a_number.csv:3: column 'q.joint2': 'zero' is not a number",
    );
    let p = tmp("nan.csv");
    std::fs::write(&p, "q.joint1,v.joint2\n0,NaN\n").unwrap();
    fails(
        &["rnea", "builtin:planar2", "--input", p.to_str().unwrap()],
        "nan.csv:2: column 'v.joint2' is not finite",
    );
    let p = tmp("ragged.csv");
    std::fs::write(&p, "q.joint1,q.joint2\n0,0\n1\n").unwrap();
    fails(
        &["rnea", "builtin:planar2", "--input", p.to_str().unwrap()],
        "ragged.csv: line 3 has 1 fields",
    );
    let p = tmp("ok.csv");
    std::fs::write(&p, "q.joint1\n0\n").unwrap();
    fails(
        &[
            "rnea",
            "builtin:planar2",
            "--input",
            p.to_str().unwrap(),
            "--q",
            "0,0",
        ],
        "--q cannot be combined with --input",
    );
    let p = tmp("series_bad.csv");
    std::fs::write(&p, "time,tau.joint1\n0,1\n").unwrap();
    fails(
        &[
            "simulate",
            "builtin:planar2",
            "--controller",
            "series",
            "--torque-csv",
            p.to_str().unwrap(),
        ],
        "unknown column 'time'",
    );
    fails(
        &["simulate", "builtin:planar2", "--output", "run.txt"],
        "--output run.txt: the file name must end in .csv or .json",
    );
    fails(
        &["simulate", "builtin:planar2", "--plot", "run.pdf"],
        "--plot run.pdf: the file name must end in .png or .svg",
    );
}

#[test]
fn models_that_fail_their_checks() {
    let bad = bad_inertia_urdf();
    // The model loads (as Pinocchio would load it) with one warning line naming file:line,
    // link and problem; --strict makes it an error.
    let out = bin().args(["rnea", &bad]).output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    let warning = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(warning.lines().count(), 1, "{warning}");
    assert!(warning.starts_with("screwdyn: warning: "));
    assert!(warning.contains("bad_inertia.urdf:") && warning.contains("link 'link3'"));
    assert!(warning.contains("triangle inequality"));
    let e = fails(&["rnea", &bad, "--strict"], "triangle inequality");
    assert!(e.contains("bad_inertia.urdf") && e.contains("link3"));
    // check lists the problem on stdout and exits 2.
    let out = bin()
        .args(["check", &bad, "--format", "json"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["ok"], false);
    assert!(v["problems"][0]
        .as_str()
        .unwrap()
        .contains("triangle inequality"));
    // A massless chain: a warning from the loader, an error of --strict and of check, and
    // singular in forward dynamics, which names the joint.
    let ghost = tmp("ghost.urdf");
    std::fs::write(&ghost, GHOST).unwrap();
    let g = ghost.to_str().unwrap();
    fails(&["aba", g, "--strict"], "no mass");
    fails(&["check", g], "ghost.urdf fails its checks");
    for method in ["aba", "crba", "walker-orin"] {
        let e = fails(&["aba", g, "--method", method], "singular");
        assert!(e.contains("no mass") && e.contains("joint 'j2'"), "{e}");
    }
}

#[test]
fn batch_errors_name_the_row() {
    let p = tmp("singular_rows.csv");
    std::fs::write(&p, "q.j1\n0\n0\n").unwrap();
    let ghost = tmp("ghost2.urdf");
    std::fs::write(&ghost, GHOST).unwrap();
    fails(
        &[
            "aba",
            ghost.to_str().unwrap(),
            "--input",
            p.to_str().unwrap(),
        ],
        "singular_rows.csv:2 (row 1): ",
    );
}

/// Issue 12.3: a non-finite result is an error naming the quantity, never a NaN/null printed
/// with exit status 0.
#[test]
fn non_finite_results_are_errors_naming_the_quantity() {
    let e = fails(
        &[
            "rnea",
            "builtin:planar2",
            "--v",
            "1e200,1e200",
            "--format",
            "json",
        ],
        "the result tau.joint",
    );
    assert!(e.contains("not finite"), "{e}");
    fails(
        &[
            "rnea",
            "builtin:planar2",
            "--wrench",
            "link2:0,0,1e308,1e308,1e308,0",
            "--q",
            "0.5,0.5",
        ],
        "not finite",
    );
}
