//! `simulate --controller computed-torque --target-trajectory RUN.CSV`: the motion written by
//! `torque-profile --output` tracked on the exact model, whose closed-loop error obeys
//! `ë + K_d ė + K_p e = 0` from zero, so it stays zero and the torques are the profile's.

mod common;
use common::*;

const UR5_WAYPOINTS: &str = "q.shoulder_pan_joint,q.shoulder_lift_joint,q.elbow_joint,q.wrist_1_joint,q.wrist_2_joint,q.wrist_3_joint
0.0,-1.8,1.4,-1.2,-1.6,0.0
0.8,-1.2,1.0,-1.4,-1.6,0.5
1.6,-1.6,1.8,-1.0,-1.2,1.0
";

/// The header and rows of a CSV run file.
fn read(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

#[test]
fn a_time_optimal_motion_is_tracked_with_its_own_torques() {
    let waypoints = tmp("track_waypoints.csv");
    std::fs::write(&waypoints, UR5_WAYPOINTS).unwrap();
    let profile = tmp("track_topp.csv");
    let out = json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "time-optimal",
        "--waypoints",
        waypoints.to_str().unwrap(),
        "--output",
        profile.to_str().unwrap(),
    ]);
    let duration = f(&out["duration"]);
    let run = tmp("track_run.csv");
    // The step a tenth of the sample step (RK4 is exact to 10⁻⁹ on the quintics between
    // samples, whose accelerations jump where s̈ switches), the run recorded every 1 ms.
    ok(&[
        "simulate",
        "builtin:ur5",
        "--controller",
        "computed-torque",
        "--target-trajectory",
        profile.to_str().unwrap(),
        "--no-effects",
        "--dt",
        "1e-4",
        "--record-every",
        "10",
        "--duration",
        &format!("{}", duration + 0.05),
        "--output",
        run.to_str().unwrap(),
    ]);
    let (h_ref, reference) = read(&profile);
    let (h_run, simulated) = read(&run);
    let last_full = reference[reference.len() - 2][0];
    let mut compared = 0;
    for r in reference.iter().filter(|r| r[0] <= last_full) {
        let s = simulated
            .iter()
            .find(|s| (s[0] - r[0]).abs() < 1e-9)
            .unwrap();
        for (k, name) in h_ref.iter().enumerate() {
            let Some(i) = h_run.iter().position(|h| h == name) else {
                continue;
            };
            let tol = match name.split('.').next() {
                Some("q") => 1e-8,
                Some("tau") => 1e-4, // N·m, of limits of 28 and 150
                _ => continue,
            };
            assert!(
                (s[i] - r[k]).abs() < tol,
                "t = {}: {name} {} against {}",
                r[0],
                s[i],
                r[k]
            );
        }
        compared += 1;
    }
    assert!(compared > 500, "{compared} samples");
}

#[test]
fn a_target_trajectory_is_refused_where_it_does_not_fit() {
    let profile = tmp("track_jl.csv");
    ok(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "jerk-limited",
        "--q0",
        "0,-1.5,1.5,-1,-1.5,0",
        "--qf",
        "1,-1,1,-1.5,-1,0.5",
        "--amax",
        "8",
        "--jmax",
        "60",
        "--output",
        profile.to_str().unwrap(),
    ]);
    let p = profile.to_str().unwrap();
    fails(
        &[
            "simulate",
            "builtin:ur5",
            "--controller",
            "pd",
            "--target-trajectory",
            p,
        ],
        "--target-trajectory is not used by --controller pd",
    );
    fails(
        &[
            "simulate",
            "builtin:ur5",
            "--controller",
            "computed-torque",
            "--target-trajectory",
            p,
            "--target",
            "0,0,0,0,0,0",
        ],
        "--target and --target-trajectory are alternatives",
    );
    let short = tmp("track_short.csv");
    std::fs::write(&short, "t,q.shoulder_pan_joint\n0,0\n").unwrap();
    fails(
        &[
            "simulate",
            "builtin:ur5",
            "--controller",
            "computed-torque",
            "--target-trajectory",
            short.to_str().unwrap(),
        ],
        "the column 'v.shoulder_pan_joint' is missing",
    );
    // Tracked from its start by default: the run's first row is the file's.
    let run = json(&[
        "simulate",
        "builtin:ur5",
        "--controller",
        "computed-torque",
        "--target-trajectory",
        p,
        "--no-effects",
        "--duration",
        "0.1",
    ]);
    let joints = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"];
    let first: Vec<f64> = joints
        .iter()
        .map(|j| f(&run[format!("q.{j}")][0]))
        .collect();
    close(&first, &[0.0, -1.5, 1.5], 1e-12);
}
