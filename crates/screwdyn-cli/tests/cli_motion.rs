//! `torque-profile --trajectory time-optimal|jerk-limited`: results checked with inverse
//! dynamics and closed forms, bad input refused with one sentence.

mod common;
use common::*;
use screwdyn::io::load_model;
use screwdyn::Workspace;

const UR5_WAYPOINTS: &str = "q.shoulder_pan_joint,q.shoulder_lift_joint,q.elbow_joint,q.wrist_1_joint,q.wrist_2_joint,q.wrist_3_joint
0.0,-1.8,1.4,-1.2,-1.6,0.0
0.8,-1.2,1.0,-1.4,-1.6,0.5
1.6,-1.6,1.8,-1.0,-1.2,1.0
";

fn write(name: &str, text: &str) -> String {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn time_optimal_output_stays_within_the_limits_by_inverse_dynamics() {
    let path = write("ur5_waypoints.csv", UR5_WAYPOINTS);
    let out_csv = tmp("ur5_topp.csv");
    let out = json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "time-optimal",
        "--waypoints",
        &path,
        "--amax",
        "10",
        "--output",
        out_csv.to_str().unwrap(),
    ]);
    let duration = f(&out["duration"]);
    assert!(duration > 0.3 && duration < 3.0, "{duration}");
    assert!(f(&out["max_limit_excess"]) <= 0.0);
    for j in ["shoulder_pan_joint", "elbow_joint", "wrist_3_joint"] {
        assert_eq!(out["violations"][j]["count"].as_u64(), Some(0));
    }
    // Every row of the output: τ = RNEA(q, q̇, q̈) within the effort limits, |q̇| ≤ 3.15,
    // |q̈| ≤ 10, from rest to rest at the waypoints.
    let m = load_model("builtin:ur5").unwrap();
    let mut ws = Workspace::new(&m);
    let text = std::fs::read_to_string(&out_csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let names = m.joint_names();
    let pick = |row: &[f64], kind: &str| -> Vec<f64> {
        names
            .iter()
            .map(|n| row[col(&format!("{kind}.{n}"))])
            .collect()
    };
    let effort = [150.0, 150.0, 150.0, 28.0, 28.0, 28.0];
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() > 100);
    for row in &rows {
        let (q, v, a, tau) = (
            pick(row, "q"),
            pick(row, "v"),
            pick(row, "a"),
            pick(row, "tau"),
        );
        let id = screwdyn::dynamics::rnea(&m, &mut ws, &q, &v, &a).unwrap();
        for j in 0..6 {
            assert!((id[j] - tau[j]).abs() < 1e-9 * effort[j]);
            assert!(id[j].abs() <= effort[j], "t = {}: τ{j} = {}", row[0], id[j]);
            assert!(v[j].abs() <= 3.15 && a[j].abs() <= 10.0);
        }
    }
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    assert_eq!(pick(first, "q"), [0.0, -1.8, 1.4, -1.2, -1.6, 0.0]);
    let end = pick(last, "q");
    close(&end, &[1.6, -1.6, 1.8, -1.0, -1.2, 1.0], 1e-12);
    assert!(pick(last, "v").iter().all(|x| x.abs() < 1e-12));
    assert!((last[0] - duration).abs() < 1e-12);
    // Without speed limits (`inf`) the same path is faster: it is speed-limited almost everywhere.
    let limited = |vmax: &str| {
        f(&json(&[
            "torque-profile",
            "builtin:ur5",
            "--trajectory",
            "time-optimal",
            "--waypoints",
            &path,
            "--vmax",
            vmax,
        ])["duration"])
    };
    assert!(limited("inf") < 0.9 * limited("3.15"));
    let free = json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "time-optimal",
        "--waypoints",
        &path,
        "--amax",
        "10",
        "--vmax",
        "inf",
    ]);
    assert!(f(&free["duration"]) <= duration);
    // The report alone takes its statistics from the timing's check (the same samples every
    // --dt): they equal those of the profile computed while writing --output. The check's
    // inverse dynamics runs eight samples side by side in SIMD lanes (fused multiply–adds),
    // the written profile's is the per-call RNEA: peaks and RMS agree to round-off
    // (10⁻¹² (1 + |value|)), the duration, the times of the peaks, the violations and the limits
    // exactly.
    let alone = json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "time-optimal",
        "--waypoints",
        &path,
        "--amax",
        "10",
    ]);
    for key in ["duration", "peak_time", "violations", "effort_limit"] {
        assert_eq!(alone[key], out[key], "{key}");
    }
    for key in ["peak", "rms"] {
        close(&vec(&alone[key]), &vec(&out[key]), 1e-12);
    }
}

#[test]
fn jerk_limited_has_the_closed_form_duration() {
    // Joint 1 moves 10 rad at 2 rad/s, 1 rad/s², 1 rad/s³: 1 + 1 + 1 s up, 2 s cruise, 3 s down.
    let out = json(&[
        "torque-profile",
        "builtin:planar2",
        "--trajectory",
        "jerk-limited",
        "--qf",
        "10,1",
        "--vmax",
        "2",
        "--amax",
        "1",
        "--jmax",
        "1",
    ]);
    close(&[f(&out["duration"])], &[8.0], 1e-12);
}

#[test]
fn bad_motion_input_is_one_sentence() {
    let good = write("ur5_waypoints_ok.csv", UR5_WAYPOINTS);
    let base = [
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "time-optimal",
    ];
    let with = |extra: &[&str]| -> Vec<String> {
        base.iter().chain(extra).map(|s| s.to_string()).collect()
    };
    let run = |extra: &[&str], expected: &str| {
        let args = with(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&args, expected);
    };
    run(
        &[],
        "--waypoints is required with --trajectory time-optimal",
    );
    run(
        &["--waypoints", &good, "--qf", "1"],
        "--qf is not used by --trajectory time-optimal",
    );
    run(
        &["--waypoints", &good, "--vmax", "0"],
        "velocity limits must be positive",
    );
    run(&["--waypoints", &good, "--amax", "nan"], "acceleration limits must be positive (or infinite for none), but joint shoulder_pan_joint has NaN");
    run(
        &["--waypoints", &good, "--amax", "1,2"],
        "--amax has 2 values",
    );
    // Gravity alone needs more than the shoulder's 150 N·m.
    run(
        &["--waypoints", &good, "--gravity", "0,0,-200"],
        "gravity alone needs",
    );
    let s_back = write(
        "ur5_s_back.csv",
        &UR5_WAYPOINTS
            .replacen("q.shoulder_pan_joint", "s,q.shoulder_pan_joint", 1)
            .replacen("\n0.0,", "\n0,0.0,", 1)
            .replacen("\n0.8,", "\n1,0.8,", 1)
            .replacen("\n1.6,", "\n0.5,1.6,", 1),
    );
    run(&["--waypoints", &s_back], "must increase strictly");
    let outside = write(
        "ur5_outside.csv",
        &UR5_WAYPOINTS.replace("1.6,-1.6,1.8", "1.6,-1.6,7.0"),
    );
    run(
        &["--waypoints", &outside],
        "waypoint 2: joint elbow_joint = 7 is outside its position limits",
    );
    let bad_col = write(
        "ur5_bad_col.csv",
        &UR5_WAYPOINTS.replace("q.elbow_joint", "q.elbow"),
    );
    run(&["--waypoints", &bad_col], "unknown column 'q.elbow'");
    let nan = write(
        "ur5_nan.csv",
        &UR5_WAYPOINTS.replace("-1.4,-1.6,0.5", "-1.4,NaN,0.5"),
    );
    run(&["--waypoints", &nan], "is not a finite number");
    fails(
        &[
            "torque-profile",
            "builtin:ur5",
            "--trajectory",
            "jerk-limited",
            "--qf",
            "1,1,1,1,1,1",
            "--amax",
            "1",
        ],
        "--jmax is required with --trajectory jerk-limited",
    );
    fails(
        &[
            "torque-profile",
            "builtin:ur5",
            "--trajectory",
            "jerk-limited",
            "--qf",
            "1,1,1,1,1,1",
            "--amax",
            "1",
            "--jmax",
            "-1",
        ],
        "--jmax must be positive, but joint 0 has -1",
    );
    fails(
        &["torque-profile", "builtin:ur5", "--jmax", "1", "--qf", "1"],
        "--jmax is not used by --trajectory trapezoid",
    );
}

const UR5_Q0: &str = "0.3,-1.2,1.5,-1.9,-1.57,0.2";

/// The pose of tool0 at `q` as `x,y,z,qw,qx,qy,qz` shifted by `shift`, and its position.
fn tool_target(q: &[f64], shift: [f64; 3]) -> (String, nalgebra::Vector3<f64>) {
    let m = load_model("builtin:ur5").unwrap();
    let p = tool_pose(&m, q);
    let r = nalgebra::UnitQuaternion::from_matrix(&p.rotation);
    let t = p.translation + nalgebra::Vector3::from(shift);
    (
        format!(
            "{:.12},{:.12},{:.12},{:.12},{:.12},{:.12},{:.12}",
            t.x, t.y, t.z, r.w, r.i, r.j, r.k
        ),
        p.translation,
    )
}

fn tool_pose(m: &screwdyn::Model, q: &[f64]) -> screwdyn::spatial::Se3 {
    let mut ws = Workspace::new(m);
    screwdyn::kinematics::forward_kinematics(m, &mut ws, q).unwrap();
    screwdyn::kinematics::frame_pose(m, &ws, m.frame_id("tool0").unwrap()).unwrap()
}

/// The tool positions of every row of a `torque-profile --output` CSV, with the time step.
fn tool_positions(path: &std::path::Path) -> Vec<nalgebra::Vector3<f64>> {
    let m = load_model("builtin:ur5").unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let cols: Vec<usize> = m
        .joint_names()
        .iter()
        .map(|n| header.iter().position(|h| *h == format!("q.{n}")).unwrap())
        .collect();
    lines
        .map(|l| {
            let row: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            let q: Vec<f64> = cols.iter().map(|&c| row[c]).collect();
            tool_pose(&m, &q).translation
        })
        .collect()
}

#[test]
fn linear_and_circular_moves_follow_their_paths_within_the_tool_speed() {
    let q0: Vec<f64> = UR5_Q0.split(',').map(|x| x.parse().unwrap()).collect();
    // A 0.2 m line along y at no more than 0.25 m/s.
    let (target, p0) = tool_target(&q0, [0.0, 0.2, 0.0]);
    let out_csv = tmp("ur5_linear.csv");
    let out = json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "linear",
        "--frame",
        "tool0",
        &format!("--q0={UR5_Q0}"),
        &format!("--target={target}"),
        "--speed",
        "0.25",
        "--output",
        out_csv.to_str().unwrap(),
    ]);
    assert!(f(&out["duration"]) > 0.2 / 0.25, "{out}");
    let positions = tool_positions(&out_csv);
    for p in &positions {
        let d = p - p0;
        assert!(d.x.abs() < 2e-6 && d.z.abs() < 2e-6, "{d:?} off the line");
        assert!((-2e-6..=0.2 + 2e-6).contains(&d.y), "{d:?}");
    }
    assert!((positions.last().unwrap().y - p0.y - 0.2).abs() < 1e-6);
    // The rows are 1 ms apart: a chord is never longer than the path, so ≤ 0.25 mm each.
    let fastest = positions
        .windows(2)
        .map(|w| (w[1] - w[0]).norm() / 1e-3)
        .fold(0.0, f64::max);
    assert!(
        fastest <= 0.25 * (1.0 + 1e-6) && fastest > 0.24,
        "{fastest}"
    );

    // Half a circle of radius 0.1 m centred 0.1 m along −x, through the quarter point.
    let (target, p0) = tool_target(&q0, [-0.2, 0.0, 0.0]);
    let center = p0 - nalgebra::Vector3::new(0.1, 0.0, 0.0);
    let via = center + nalgebra::Vector3::new(0.0, 0.1, 0.0);
    let out_csv = tmp("ur5_circular.csv");
    json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "circular",
        "--frame",
        "tool0",
        &format!("--q0={UR5_Q0}"),
        &format!("--target={target}"),
        &format!("--via={:.12},{:.12},{:.12}", via.x, via.y, via.z),
        "--output",
        out_csv.to_str().unwrap(),
    ]);
    for p in tool_positions(&out_csv) {
        let d = p - center;
        assert!(
            (d.norm() - 0.1).abs() < 2e-6 && d.z.abs() < 2e-6,
            "{d:?} off the circle"
        );
        assert!(d.y > -2e-6, "{d:?} on the wrong half");
    }
}

#[test]
fn cartesian_moves_report_where_they_fail() {
    let q0: Vec<f64> = UR5_Q0.split(',').map(|x| x.parse().unwrap()).collect();
    let (far, _) = tool_target(&q0, [-1.0, 0.0, 0.0]);
    let (near, _) = tool_target(&q0, [0.0, 0.1, 0.0]);
    let q0_flag = format!("--q0={UR5_Q0}");
    let base = ["torque-profile", "builtin:ur5", "--trajectory"];
    let run = |extra: &[&str], expected: &str| {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        fails(&args, expected)
    };
    let e = run(
        &[
            "linear",
            "--frame",
            "tool0",
            &q0_flag,
            &format!("--target={far}"),
        ],
        "the linear move of frame tool0 stops at",
    );
    assert!(
        e.contains("out of reach") && e.contains("m of 1.0000 m"),
        "{e}"
    );
    run(
        &["linear", &q0_flag, &format!("--target={near}")],
        "--frame is required with --trajectory linear",
    );
    run(
        &[
            "linear",
            "--frame",
            "tool0",
            &q0_flag,
            &format!("--target={near}"),
            "--via=0,0,0",
        ],
        "--via is not used by --trajectory linear",
    );
    run(
        &[
            "circular",
            "--frame",
            "tool0",
            &q0_flag,
            &format!("--target={near}"),
        ],
        "--via is required with --trajectory circular",
    );
    run(
        &[
            "linear",
            "--frame",
            "tool0",
            &q0_flag,
            &format!("--target={near}"),
            "--speed=-1",
        ],
        "--speed is -1",
    );
    run(
        &["quintic", "--qf", "0,0,0,0,0,0", "--speed", "1"],
        "--speed is not used by --trajectory quintic",
    );
}
