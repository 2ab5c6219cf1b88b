//! The binary's `ik` command: every answer checked by the `fk` command (forward kinematics of
//! the returned q reaches the target) and against the joint limits, the planar two-link arm
//! against its closed form, batches against single solves, and bad input.

mod common;

use common::{bin, f, fails, json, mat, ok, tmp, vec};
use serde_json::Value;

/// Joint limits (lower, upper) of a model, from `info` (null for none).
fn limits(model: &str) -> Vec<(f64, f64)> {
    let info = json(&["info", model]);
    info["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| {
            (
                j["lower"].as_f64().unwrap_or(f64::NEG_INFINITY),
                j["upper"].as_f64().unwrap_or(f64::INFINITY),
            )
        })
        .collect()
}

/// The 4×4 pose of `frame` at `q`, by the `fk` command.
fn pose(model: &str, frame: &str, q: &[f64]) -> Vec<Vec<f64>> {
    let q: Vec<String> = q.iter().map(|v| v.to_string()).collect();
    let v = json(&["fk", model, "--frame", frame, "--q", &q.join(",")]);
    mat(&v["poses"][frame])
}

/// `x,y,z,qw,qx,qy,qz` of a pose (Shepperd's method for the quaternion).
fn pose_text(h: &[Vec<f64>]) -> String {
    let r = |i: usize, j: usize| h[i][j];
    let trace = r(0, 0) + r(1, 1) + r(2, 2);
    let (w, x, y, z) = if trace > 0.0 {
        let s = 2.0 * (1.0 + trace).sqrt();
        (
            0.25 * s,
            (r(2, 1) - r(1, 2)) / s,
            (r(0, 2) - r(2, 0)) / s,
            (r(1, 0) - r(0, 1)) / s,
        )
    } else if r(0, 0) > r(1, 1) && r(0, 0) > r(2, 2) {
        let s = 2.0 * (1.0 + r(0, 0) - r(1, 1) - r(2, 2)).sqrt();
        (
            (r(2, 1) - r(1, 2)) / s,
            0.25 * s,
            (r(0, 1) + r(1, 0)) / s,
            (r(0, 2) + r(2, 0)) / s,
        )
    } else if r(1, 1) > r(2, 2) {
        let s = 2.0 * (1.0 + r(1, 1) - r(0, 0) - r(2, 2)).sqrt();
        (
            (r(0, 2) - r(2, 0)) / s,
            (r(0, 1) + r(1, 0)) / s,
            0.25 * s,
            (r(1, 2) + r(2, 1)) / s,
        )
    } else {
        let s = 2.0 * (1.0 + r(2, 2) - r(0, 0) - r(1, 1)).sqrt();
        (
            (r(1, 0) - r(0, 1)) / s,
            (r(0, 2) + r(2, 0)) / s,
            (r(1, 2) + r(2, 1)) / s,
            0.25 * s,
        )
    };
    format!("{},{},{},{w},{x},{y},{z}", h[0][3], h[1][3], h[2][3])
}

/// The largest position (m) and rotation-angle (rad) differences of two poses.
fn pose_errors(a: &[Vec<f64>], b: &[Vec<f64>]) -> (f64, f64) {
    let dp = (0..3)
        .map(|i| (a[i][3] - b[i][3]).powi(2))
        .sum::<f64>()
        .sqrt();
    // trace(Aᵀ B) = 1 + 2 cos θ.
    let trace: f64 = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| a[i][j] * b[i][j])
        .sum();
    let angle = ((trace - 1.0) / 2.0).clamp(-1.0, 1.0).acos();
    (dp, angle)
}

/// Random configurations within the limits (a fixed linear congruential sequence).
fn configurations(lims: &[(f64, f64)], count: usize) -> Vec<Vec<f64>> {
    let mut state = 12345_u64;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            lims.iter()
                .map(|&(lo, hi)| {
                    let (lo, hi) = (lo.max(-3.0), hi.min(3.0));
                    lo + (hi - lo) * uniform()
                })
                .collect()
        })
        .collect()
}

fn within(q: &[f64], lims: &[(f64, f64)]) -> bool {
    q.iter().zip(lims).all(|(v, (lo, hi))| lo <= v && v <= hi)
}

#[test]
fn round_trips_are_confirmed_by_fk() {
    for (model, frame) in [("builtin:ur5", "tool0"), ("builtin:panda", "panda_link8")] {
        let lims = limits(model);
        for q in configurations(&lims, 3) {
            let target = pose(model, frame, &q);
            let v = json(&[
                "ik",
                model,
                "--frame",
                frame,
                "--target",
                &pose_text(&target),
            ]);
            assert_eq!(v["success"], Value::Bool(true), "{model} {q:?}: {v}");
            let answer = vec(&v["q"]);
            assert!(within(&answer, &lims), "{model}: {answer:?}");
            let (dp, dr) = pose_errors(&pose(model, frame, &answer), &target);
            assert!(dp <= 1e-6 && dr <= 1e-6, "{model}: {dp} m, {dr} rad");
            // The reported errors are those of the answer.
            assert!(f(&v["position_error"]) <= 1e-6 && f(&v["orientation_error"]) <= 1e-6);
        }
    }
}

#[test]
fn planar2_position_matches_the_closed_form() {
    // x = cos q1 + cos(q1 + q2), y = sin q1 + sin(q1 + q2): the target (1, 1) has the
    // elbow angle q2 = ±π/2 (law of cosines: 2 = 2 + 2 cos q2).
    let v = json(&[
        "ik",
        "builtin:planar2",
        "--frame",
        "link2",
        "--position",
        "1,1,0",
        "--q0",
        "0.1,1",
    ]);
    assert_eq!(v["success"], Value::Bool(true), "{v}");
    let q = vec(&v["q"]);
    assert!(
        (q[1].abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-6,
        "{q:?}"
    );
    let (x, y) = (
        q[0].cos() + (q[0] + q[1]).cos(),
        q[0].sin() + (q[0] + q[1]).sin(),
    );
    assert!((x - 1.0).abs() < 1e-6 && (y - 1.0).abs() < 1e-6);
}

#[test]
fn unreachable_target_is_not_an_error() {
    // Reach 2 m: the nearest point to (3, 0) is (2, 0), 1 m away.
    let v = json(&[
        "ik",
        "builtin:planar2",
        "--frame",
        "link2",
        "--position",
        "3,0,0",
        "--q0",
        "0.2,0.3",
    ]);
    assert_eq!(v["success"], Value::Bool(false));
    assert!((f(&v["position_error"]) - 1.0).abs() < 1e-6, "{v}");
    assert_ne!(v["failure"], Value::String("none".into()));
}

#[test]
fn batch_rows_are_solved_and_bad_rows_named() {
    let (model, frame) = ("builtin:ur5", "tool0");
    let lims = limits(model);
    let qs = configurations(&lims, 6);
    let mut text = String::from("x,y,z,qw,qx,qy,qz\n");
    for (k, q) in qs.iter().enumerate() {
        text.push_str(&pose_text(&pose(model, frame, q)));
        text.push('\n');
        if k == 1 {
            text.push_str("0.1,0.2,0.3\n"); // line 4: too few columns
        }
        if k == 3 {
            text.push_str("0.1,0.2,0.3,0.9,0,0,0\n"); // line 7: not a unit quaternion
        }
    }
    let input = tmp("ik_targets.csv");
    std::fs::write(&input, text).unwrap();
    let input = input.to_str().unwrap();
    let run = |threads: &str, out: &std::path::Path| {
        let o = bin()
            .args([
                "ik",
                model,
                "--frame",
                frame,
                "--input",
                input,
                "--threads",
                threads,
            ])
            .args(["--output", out.to_str().unwrap()])
            .output()
            .unwrap();
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let (one, two) = (tmp("ik_out1.csv"), tmp("ik_out2.csv"));
    let (code, err) = run("1", &one);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains(":4: the row has 3 fields, the header has 7"),
        "{err}"
    );
    assert!(
        err.contains(":7: the target's quaternion") && err.contains("1e-6"),
        "{err}"
    );
    assert!(
        err.contains("2 of 8 rows had bad input (lines 4, 7)"),
        "{err}"
    );
    assert_eq!(run("2", &two).0, Some(2));
    let written = std::fs::read_to_string(&one).unwrap();
    assert_eq!(
        written,
        std::fs::read_to_string(&two).unwrap(),
        "thread count changed answers"
    );
    let mut rows = csv::Reader::from_reader(written.as_bytes());
    let header = rows.headers().unwrap().clone();
    assert_eq!(&header[6], "success");
    let rows: Vec<csv::StringRecord> = rows.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 8, "one output row per target");
    let good: Vec<&csv::StringRecord> = rows
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != 2 && *k != 5)
        .map(|(_, r)| r)
        .collect();
    assert_eq!((&rows[2][6], &rows[5][6]), ("false", "false"));
    for (q, row) in qs.iter().zip(good) {
        assert_eq!(&row[6], "true");
        let answer: Vec<f64> = (0..6).map(|k| row[k].parse().unwrap()).collect();
        assert!(within(&answer, &lims));
        let (dp, dr) = pose_errors(&pose(model, frame, &answer), &pose(model, frame, q));
        assert!(dp <= 1e-6 && dr <= 1e-6, "{dp} {dr}");
    }
}

#[test]
fn batch_of_positions_with_starts_as_json() {
    // Header without the quaternion: position targets; q0.<joint> columns give the starts,
    // which pick the elbow branch of the planar arm (q2 > 0 or < 0).
    let input = tmp("ik_positions.csv");
    std::fs::write(
        &input,
        "x,y,z,q0.joint1,q0.joint2\n1,1,0,0,1\n1,1,0,1.5,-1\n",
    )
    .unwrap();
    let out = ok(&[
        "ik",
        "builtin:planar2",
        "--frame",
        "link2",
        "--input",
        input.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let v: Value = serde_json::from_str(&out).unwrap();
    let rows = v.as_array().unwrap();
    assert_eq!(rows.len(), 2);
    let (a, b) = (vec(&rows[0]["q"]), vec(&rows[1]["q"]));
    assert!((a[1] - std::f64::consts::FRAC_PI_2).abs() < 1e-6, "{a:?}");
    assert!((b[1] + std::f64::consts::FRAC_PI_2).abs() < 1e-6, "{b:?}");
}

#[test]
fn bad_input_is_one_sentence() {
    let ur5 = "builtin:ur5";
    fails(
        &[
            "ik",
            ur5,
            "--frame",
            "nope",
            "--target",
            "0.3,0,0.4,1,0,0,0",
        ],
        "no frame named 'nope'",
    );
    fails(
        &[
            "ik",
            ur5,
            "--frame",
            "tool0",
            "--target",
            "0.3,0,0.4,1,0.1,0,0",
        ],
        "not 1 within 1e-6",
    );
    fails(
        &[
            "ik",
            ur5,
            "--frame",
            "tool0",
            "--target",
            "0.3,NaN,0.4,1,0,0,0",
        ],
        "non-finite value (NaN)",
    );
    fails(
        &["ik", ur5, "--frame", "tool0", "--target", "0.3,0,0.4,1,0,0"],
        "needs 7 numbers",
    );
    fails(
        &[
            "ik",
            ur5,
            "--frame",
            "tool0",
            "--target",
            "0.3,0,0.4,1,0,0,0",
            "--q0",
            "0,0,0,0,0,7",
        ],
        "outside its limits",
    );
    fails(&["ik", ur5, "--frame", "tool0"], "exactly one of --target");
    let input = tmp("ik_bad_header.csv");
    std::fs::write(&input, "x,y,qw,qx,qy,qz\n0,0,1,0,0,0\n").unwrap();
    fails(
        &[
            "ik",
            ur5,
            "--frame",
            "tool0",
            "--input",
            input.to_str().unwrap(),
        ],
        "no column 'z'",
    );
}

#[test]
fn all_closed_form_solutions_of_the_ur5_reach_the_target() {
    let (model, frame) = ("builtin:ur5", "tool0");
    let lims = limits(model);
    let target = pose(model, frame, &[0.3, -1.2, 1.5, -0.4, 1.1, 0.7]);
    let v = json(&[
        "ik",
        model,
        "--frame",
        frame,
        "--target",
        &pose_text(&target),
        "--all",
    ]);
    assert_eq!(
        v["closed_form"],
        Value::String("three parallel axes".into())
    );
    let solutions = mat(&v["solutions"]);
    // A generic UR5 pose: 8 branches (2 shoulders × 2 elbows × 2 wrists).
    assert_eq!(solutions.len(), 8);
    for (k, q) in solutions.iter().enumerate() {
        assert!(within(q, &lims));
        let (dp, dr) = pose_errors(&pose(model, frame, q), &target);
        assert!(dp <= 1e-6 && dr <= 1e-6, "solution {k}: {dp} {dr}");
        for other in &solutions[..k] {
            assert!(
                q.iter().zip(other).any(|(a, b)| (a - b).abs() > 1e-3),
                "duplicate"
            );
        }
    }
}

/// `--input` is one batch of the library streamed in chunks: a file longer than one chunk
/// (512 rows), with out-of-reach rows whose answers depend on each row's seed stream (they
/// take every restart), gives exactly the answers of the library's `solve_batch` on the same
/// targets — bit for bit, the numbers read back from the CSV — on 1 and 2 threads. Python's
/// `inverse_kinematics` on an `(N, 4, 4)` stack calls that same `solve_batch`.
#[test]
fn input_rows_get_the_answers_of_the_library_batch() {
    use screwdyn::kinematics::ik::{target_from_quaternion, IkOptions, IkSolver, IkTask};
    let (model, frame) = ("builtin:panda", "panda_link8");
    let panda = screwdyn::builtin::load("panda").unwrap();
    let lims: Vec<(f64, f64)> = panda
        .joints()
        .iter()
        .map(|j| (j.limits.lower, j.limits.upper))
        .collect();
    let tool = panda.frame_id(frame).unwrap();
    let placement = panda.frames()[tool].placement;
    let body = panda.frames()[tool].body.unwrap();
    let rows = 530;
    let mut text = String::from("x,y,z,qw,qx,qy,qz\n");
    let mut targets = Vec::new();
    for (k, q) in configurations(&lims, rows).iter().enumerate() {
        let h = screwdyn::kinematics::forward_kinematics_poe(&panda, q).unwrap()[body]
            .compose(&placement)
            .to_matrix();
        let mut h: Vec<Vec<f64>> = (0..4)
            .map(|i| (0..4).map(|j| h[(i, j)]).collect())
            .collect();
        if k % 30 == 7 {
            h[0][3] += 2.0; // beyond the Panda's reach (about 1.2 m)
        }
        let line = pose_text(&h);
        let v: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        targets.push(
            target_from_quaternion([v[0], v[1], v[2]], [v[3], v[4], v[5], v[6]], "target").unwrap(),
        );
        text.push_str(&line);
        text.push('\n');
    }
    let input = tmp("ik_stream.csv");
    std::fs::write(&input, text).unwrap();
    let options = IkOptions {
        max_restarts: 3,
        ..IkOptions::default()
    };
    let solver = IkSolver::new(&panda, &[IkTask::pose(tool)], options).unwrap();
    let q0 = screwdyn::kinematics::ik::default_start(&panda);
    let mut expected = vec![0.0; rows * 7];
    let results = solver.solve_batch(&targets, &q0, &mut expected, 2).unwrap();
    let unreachable = results
        .iter()
        .filter(|r| !r.as_ref().unwrap().success)
        .count();
    assert!(unreachable >= 10, "{unreachable} rows fail");
    for threads in ["1", "2"] {
        let out = ok(&[
            "ik",
            model,
            "--frame",
            frame,
            "--input",
            input.to_str().unwrap(),
            "--max-restarts",
            "3",
            "--threads",
            threads,
            "--format",
            "csv",
        ]);
        let mut reader = csv::Reader::from_reader(out.as_bytes());
        let written: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
        assert_eq!(written.len(), rows);
        for (k, row) in written.iter().enumerate() {
            let q: Vec<f64> = (0..7).map(|j| row[j].parse().unwrap()).collect();
            assert_eq!(
                q,
                expected[k * 7..(k + 1) * 7],
                "row {k} on {threads} threads"
            );
            let r = results[k].as_ref().unwrap();
            assert_eq!(&row[7], if r.success { "true" } else { "false" });
        }
    }
}
