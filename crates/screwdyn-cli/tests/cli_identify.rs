//! `derivatives`, `regressor` and `identify` (issue 15): the derivatives against central
//! differences of the seeds' two-link closed form (seeds 003/004, m = L = 1), JSON keys and
//! batch CSV columns; `Y π = τ`; identification from an exciting log with noise (with and
//! without accelerations in the log, unconstrained and physically consistent); bad logs.

mod common;
use common::*;

const G: f64 = 9.81;

/// Seed 003/004: τ = M(q) q̈ + C(q, q̇) q̇ + g(q) of the planar arm.
fn planar_tau(q: &[f64], v: &[f64], a: &[f64]) -> Vec<f64> {
    let (c1, c2, s2, c12) = (q[0].cos(), q[1].cos(), q[1].sin(), (q[0] + q[1]).cos());
    let m = [[3.0 + 2.0 * c2, 1.0 + c2], [1.0 + c2, 1.0]];
    let cv = [-s2 * v[1] * v[1] - 2.0 * s2 * v[0] * v[1], s2 * v[0] * v[0]];
    let g = [2.0 * G * c1 + G * c12, G * c12];
    (0..2)
        .map(|i| m[i][0] * a[0] + m[i][1] * a[1] + cv[i] + g[i])
        .collect()
}

/// Central differences of the closed form in argument `which` (0 = q, 1 = v, 2 = a).
fn fd(q: &[f64], v: &[f64], a: &[f64], which: usize) -> [[f64; 2]; 2] {
    let h = 1e-6;
    let mut out = [[0.0; 2]; 2];
    for j in 0..2 {
        let mut args = [q.to_vec(), v.to_vec(), a.to_vec()];
        args[which][j] += h;
        let p = planar_tau(&args[0], &args[1], &args[2]);
        args[which][j] -= 2.0 * h;
        let m = planar_tau(&args[0], &args[1], &args[2]);
        for i in 0..2 {
            out[i][j] = (p[i] - m[i]) / (2.0 * h);
        }
    }
    out
}

fn close_mat(got: &[Vec<f64>], want: &[[f64; 2]; 2], tol: f64) {
    for i in 0..2 {
        close(&got[i], &want[i], tol);
    }
}

#[test]
fn derivatives_match_the_seed_closed_form() {
    let (q, v, a) = ([0.3, -0.7], [1.2, -0.4], [0.5, 2.0]);
    let out = json(&[
        "derivatives",
        "builtin:planar2",
        "--q",
        &csv(&q),
        "--v",
        &csv(&v),
        "--a",
        &csv(&a),
    ]);
    for key in ["dtau_dq", "dtau_dv", "dqdd_dq", "dqdd_dv", "minv"] {
        assert!(out.get(key).is_some(), "{key} missing");
    }
    close_mat(&mat(&out["dtau_dq"]), &fd(&q, &v, &a, 0), 1e-7);
    close_mat(&mat(&out["dtau_dv"]), &fd(&q, &v, &a, 1), 1e-7);
    // ∂q̈/∂τ = M⁻¹ and ∂q̈/∂q = −M⁻¹ ∂τ/∂q with the seed's M.
    let m = fd(&q, &v, &a, 2);
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let minv = [
        [m[1][1] / det, -m[0][1] / det],
        [-m[1][0] / det, m[0][0] / det],
    ];
    close_mat(&mat(&out["minv"]), &minv, 1e-7);
    let dq = fd(&q, &v, &a, 0);
    let mut want = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            want[i][j] = -(minv[i][0] * dq[0][j] + minv[i][1] * dq[1][j]);
        }
    }
    close_mat(&mat(&out["dqdd_dq"]), &want, 1e-6);
}

#[test]
fn derivatives_batch_rows_and_csv_columns() {
    let path = tmp("deriv_states.csv");
    std::fs::write(
        &path,
        "q.joint1,q.joint2,v.joint1,a.joint2\n0.1,0.2,0.3,0.4\n-0.5,1.0,0.0,0.0\n0.7,0.7,-1,2\n",
    )
    .unwrap();
    let p = path.to_str().unwrap();
    let v = json(&["derivatives", "builtin:planar2", "--input", p]);
    let rows = v.as_array().unwrap();
    assert_eq!(rows.len(), 3);
    let want = fd(&[-0.5, 1.0], &[0.0, 0.0], &[0.0, 0.0], 0);
    close_mat(&mat(&rows[1]["dtau_dq"]), &want, 1e-7);
    let text = ok(&[
        "derivatives",
        "builtin:planar2",
        "--input",
        p,
        "--format",
        "csv",
    ]);
    let header = text.lines().next().unwrap();
    assert!(header.contains("dtau_dq.joint1.joint2") && header.contains("minv.joint2.joint2"));
    assert_eq!(text.lines().count(), 4);
}

#[test]
fn regressor_times_parameters_is_the_torque() {
    let (q, v, a) = ([0.3, -0.7], [1.2, -0.4], [0.5, 2.0]);
    let out = json(&[
        "regressor",
        "builtin:planar2",
        "--q",
        &csv(&q),
        "--v",
        &csv(&v),
        "--a",
        &csv(&a),
        "--friction",
    ]);
    let y = mat(&out["regressor"]);
    let pi = vec(&out["parameters"]);
    assert_eq!(pi.len(), 24);
    let tau: Vec<f64> = y
        .iter()
        .map(|row| row.iter().zip(&pi).map(|(a, b)| a * b).sum())
        .collect();
    close(&tau, &planar_tau(&q, &v, &a), 1e-12);
    let base = json(&["regressor", "builtin:planar2", "--base"]);
    assert_eq!(base["rank"], 6);
    assert!(base["base_parameters"]
        .as_object()
        .unwrap()
        .contains_key("mx_link2 + m_link2"));
}

/// Writes an exciting log of the UR5 with torque noise 0.05 N·m and identifies it.
#[test]
fn identify_recovers_the_model_from_an_exciting_log() {
    let log = tmp("ur5_excite.csv");
    let l = log.to_str().unwrap();
    let msg = ok(&[
        "identify",
        "builtin:ur5",
        "--excite",
        "--output",
        l,
        "--duration",
        "12",
        "--noise",
        "0.05",
        "--seed",
        "3",
    ]);
    assert!(msg.starts_with("wrote 1201 samples"), "{msg}");
    let truth = json(&["regressor", "builtin:ur5", "--base"]);
    let truth = truth["base_parameters"].as_object().unwrap().clone();
    let plot = tmp("ur5_residual.png");
    let out = json(&[
        "identify",
        "builtin:ur5",
        "--input",
        l,
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert!(std::fs::metadata(&plot).unwrap().len() > 1000);
    assert_eq!(out["samples"], 1201);
    assert!(f(&out["condition_number"]) > 1.0);
    for r in vec(&out["residual_rms"]) {
        assert!((r - 0.05).abs() < 0.01, "residual {r}");
    }
    let est = out["base_parameters"].as_object().unwrap();
    assert_eq!(est.len(), truth.len());
    for (name, e) in est {
        let (x, s, t) = (f(&e["value"]), f(&e["std_dev"]), f(&truth[name]));
        assert!((x - t).abs() <= 5.0 * s + 1e-9, "{name}: {x} ± {s} vs {t}");
    }

    // Without the a.* columns: Savitzky–Golay differentiation of v (exact data, so the only
    // error is the filter's; the estimates stay close).
    let text = std::fs::read_to_string(&log).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let keep: Vec<usize> = (0..header.len())
        .filter(|&i| !header[i].starts_with("a."))
        .collect();
    let mut stripped = keep
        .iter()
        .map(|&i| header[i])
        .collect::<Vec<_>>()
        .join(",")
        + "\n";
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        stripped += &(keep.iter().map(|&i| cells[i]).collect::<Vec<_>>().join(",") + "\n");
    }
    let log2 = tmp("ur5_excite_no_a.csv");
    std::fs::write(&log2, stripped).unwrap();
    let out = json(&["identify", "builtin:ur5", "--input", log2.to_str().unwrap()]);
    assert_eq!(out["samples"], 1201 - 10, "5 samples dropped at each end");
    for r in vec(&out["residual_rms"]) {
        assert!(r < 0.06, "residual {r}");
    }

    // Physically consistent estimate: still fits to the noise.
    let out = json(&["identify", "builtin:ur5", "--input", l, "--physical"]);
    assert_eq!(out["physical"], "yes");
    for r in vec(&out["residual_rms"]) {
        assert!(r < 0.07, "residual {r}");
    }
}

#[test]
fn bad_logs_are_one_sentence_errors() {
    // Too few samples.
    let p = tmp("short.csv");
    std::fs::write(
        &p,
        "t,q.pivot,v.pivot,a.pivot,tau.pivot\n0,0.1,0.2,0.3,1.0\n",
    )
    .unwrap();
    fails(
        &[
            "identify",
            "builtin:pendulum",
            "--input",
            p.to_str().unwrap(),
        ],
        "too few samples",
    );
    // NaN.
    std::fs::write(
        &p,
        "t,q.pivot,v.pivot,a.pivot,tau.pivot\n0,0.1,0.2,0.3,1.0\n0.1,NaN,0.2,0.3,1.0\n",
    )
    .unwrap();
    fails(
        &[
            "identify",
            "builtin:pendulum",
            "--input",
            p.to_str().unwrap(),
        ],
        "is not finite",
    );
    // Standard input cannot be read twice.
    fails(
        &["identify", "builtin:pendulum", "--input", "-"],
        "--input must name a file, not standard input",
    );
    // Missing column.
    std::fs::write(&p, "t,q.pivot,v.pivot\n0,0.1,0.2\n").unwrap();
    fails(
        &[
            "identify",
            "builtin:pendulum",
            "--input",
            p.to_str().unwrap(),
        ],
        "has no column 'tau.pivot'",
    );
    // Rank-deficient: the arm stands still at one configuration (gravity only).
    let mut text =
        "t,q.joint1,q.joint2,v.joint1,v.joint2,a.joint1,a.joint2,tau.joint1,tau.joint2\n"
            .to_string();
    let tau = planar_tau(&[0.3, 0.5], &[0.0, 0.0], &[0.0, 0.0]);
    for k in 0..200 {
        text += &format!(
            "{},0.3,0.5,0,0,0,0,{},{}\n",
            k as f64 * 0.01,
            tau[0],
            tau[1]
        );
    }
    std::fs::write(&p, text).unwrap();
    fails(
        &[
            "identify",
            "builtin:planar2",
            "--input",
            p.to_str().unwrap(),
        ],
        "rank-deficient",
    );
    fails(&["identify", "builtin:planar2"], "identify needs a log");
    fails(&["identify", "builtin:planar2", "--excite"], "--output");
    fails(
        &["derivatives", "builtin:planar2", "--q", "1,NaN"],
        "non-finite",
    );
}
