//! The numeric commands against the seeds' two-link closed forms (seeds 003/004: m = L = 1,
//! gravity 9.81 along −y) and against the library's algorithms on the UR5 and a URDF robot;
//! The JSON keys and CSV columns of docs/cli.md; batch input of 1000 states.

mod common;
use common::*;
use screwdyn::dynamics::{self, ForwardMethod};
use screwdyn::{io::load_model, Workspace};

const G: f64 = 9.81;

/// Seed 003/004 closed forms of the planar arm: (M, C q̇, g).
fn planar2(q: [f64; 2], v: [f64; 2]) -> ([[f64; 2]; 2], [f64; 2], [f64; 2]) {
    let (c1, c2, s2, c12) = (q[0].cos(), q[1].cos(), q[1].sin(), (q[0] + q[1]).cos());
    let m = [[3.0 + 2.0 * c2, 1.0 + c2], [1.0 + c2, 1.0]];
    let cv = [-s2 * v[1] * v[1] - 2.0 * s2 * v[0] * v[1], s2 * v[0] * v[0]];
    let g = [2.0 * G * c1 + G * c12, G * c12];
    (m, cv, g)
}

const Q: [f64; 2] = [0.3, -0.7];
const V: [f64; 2] = [1.2, -0.4];
const A: [f64; 2] = [0.5, 2.0];

#[test]
fn inverse_dynamics_matches_seed_closed_form() {
    let (m, cv, g) = planar2(Q, V);
    let expect: Vec<f64> = (0..2)
        .map(|i| m[i][0] * A[0] + m[i][1] * A[1] + cv[i] + g[i])
        .collect();
    for cmd in ["inverse-dynamics", "rnea"] {
        let v = json(&[
            cmd,
            "builtin:planar2",
            "--q",
            &csv(&Q),
            "--v",
            &csv(&V),
            "--a",
            &csv(&A),
        ]);
        assert_eq!(v["joints"], serde_json::json!(["joint1", "joint2"]));
        close(&vec(&v["tau"]), &expect, 1e-12);
    }
    // --v and --a default to zero: gravity alone.
    let v = json(&["rnea", "builtin:planar2", "--q", &csv(&Q)]);
    close(&vec(&v["tau"]), &g, 1e-12);
    // --gravity overrides the model's: none at all gives M q̈ + C q̇.
    let v = json(&[
        "rnea",
        "builtin:planar2",
        "--q",
        &csv(&Q),
        "--v",
        &csv(&V),
        "--a",
        &csv(&A),
        "--gravity",
        "0,0,0",
    ]);
    let expect: Vec<f64> = (0..2)
        .map(|i| m[i][0] * A[0] + m[i][1] * A[1] + cv[i])
        .collect();
    close(&vec(&v["tau"]), &expect, 1e-12);
}

#[test]
fn matrices_and_energy_match_seed_closed_form() {
    let (m, cv, g) = planar2(Q, V);
    let q = csv(&Q);
    let v = csv(&V);
    for cmd in ["mass-matrix", "crba"] {
        let out = json(&[cmd, "builtin:planar2", "--q", &q]);
        let mm = mat(&out["mass_matrix"]);
        close(&mm[0], &m[0], 1e-12);
        close(&mm[1], &m[1], 1e-12);
    }
    let c = mat(&json(&["coriolis", "builtin:planar2", "--q", &q, "--v", &v])["coriolis_matrix"]);
    let cqd: Vec<f64> = c.iter().map(|r| r[0] * V[0] + r[1] * V[1]).collect();
    close(&cqd, &cv, 1e-12);
    let gt = json(&["gravity", "builtin:planar2", "--q", &q]);
    close(&vec(&gt["gravity_torque"]), &g, 1e-12);
    let h = json(&["nonlinear-effects", "builtin:planar2", "--q", &q, "--v", &v]);
    close(
        &vec(&h["nonlinear_effects"]),
        &[cv[0] + g[0], cv[1] + g[1]],
        1e-12,
    );
    let e = json(&["energy", "builtin:planar2", "--q", &q, "--v", &v]);
    let ke = 0.5
        * (0..2)
            .map(|i| (0..2).map(|j| V[i] * m[i][j] * V[j]).sum::<f64>())
            .sum::<f64>();
    let pe = G * (2.0 * Q[0].sin() + (Q[0] + Q[1]).sin());
    close(
        &[f(&e["kinetic_energy"]), f(&e["potential_energy"])],
        &[ke, pe],
        1e-12,
    );
    close(&[f(&e["total_energy"])], &[ke + pe], 1e-12);
}

#[test]
fn forward_dynamics_inverts_the_closed_form() {
    // τ from the seed's closed form; every method must give back q̈.
    let (m, cv, g) = planar2(Q, V);
    let tau: Vec<f64> = (0..2)
        .map(|i| m[i][0] * A[0] + m[i][1] * A[1] + cv[i] + g[i])
        .collect();
    for (cmd, method) in [
        ("forward-dynamics", "aba"),
        ("aba", "crba"),
        ("aba", "walker-orin"),
    ] {
        let out = json(&[
            cmd,
            "builtin:planar2",
            "--q",
            &csv(&Q),
            "--v",
            &csv(&V),
            "--tau",
            &csv(&tau),
            "--method",
            method,
        ]);
        close(&vec(&out["qdd"]), &A, 1e-10);
    }
}

#[test]
fn external_wrenches_enter_as_jacobian_transpose() {
    // Seed 000: a tip pushing 1 N along its local y at q = 0 needs τ = (L1 + L2, L2) · 1 N.
    let out = json(&[
        "rnea",
        "builtin:planar2",
        "--gravity",
        "0,0,0",
        "--tip-wrench",
        "link2:0,0,0,0,1,0",
    ]);
    close(&vec(&out["tau"]), &[2.0, 1.0], 1e-12);
    // The environment pushing on link 2 with the same force (body frame): the opposite torques.
    let out = json(&[
        "rnea",
        "builtin:planar2",
        "--gravity",
        "0,0,0",
        "--wrench",
        "link2:0,0,0,0,1,0",
    ]);
    close(&vec(&out["tau"]), &[-2.0, -1.0], 1e-12);
    // Holding the bobs up from outside (world frame) cancels gravity: f = m g ŷ on each, the
    // moment about the base origin r × f.
    let out = json(&[
        "rnea",
        "builtin:planar2",
        "--wrench",
        "link1:0,0,9.81,0,9.81,0@world",
        "--wrench",
        "link2:0,0,19.62,0,9.81,0@world",
    ]);
    close(&vec(&out["tau"]), &[0.0, 0.0], 1e-12);
}

#[test]
fn a_wrench_on_a_fixed_joint_link_is_the_same_spatial_wrench_on_its_body() {
    // In world coordinates (moment about the world origin) a wrench does not depend on which
    // rigidly joined link it is applied to: tool0 is fixed to wrist_3_link in the UR5 URDF.
    let ur5 = "../../models/ur5.urdf";
    let w = "0.1,-0.2,0.3,5,-4,3@world";
    let state = [
        "--q",
        "0.3,-1.1,1.2,-0.4,0.9,0.2",
        "--v",
        "0.5,0,-0.3,0.2,0,0.1",
    ];
    let on = |link: &str| {
        let arg = format!("{link}:{w}");
        let mut args = vec!["rnea", ur5, "--wrench", arg.as_str()];
        args.extend_from_slice(&state);
        vec(&json(&args)["tau"])
    };
    let (tool, wrist) = (on("tool0"), on("wrist_3_link"));
    close(&tool, &wrist, 1e-10);
    // …and it does act: without it the torques differ.
    let mut args = vec!["rnea", ur5];
    args.extend_from_slice(&state);
    let free = vec(&json(&args)["tau"]);
    assert!(free.iter().zip(&tool).any(|(a, b)| (a - b).abs() > 0.1));
    fails(&["rnea", ur5, "--wrench", "nowhere:0,0,0,0,0,1"], "nowhere");
}

#[test]
fn closed_form_and_lagrange_follow_seed_004() {
    let half_pi = std::f64::consts::FRAC_PI_2;
    let q = format!("0,{half_pi}");
    let cf = json(&["closed-form", "builtin:planar2", "--q", &q, "--v", "0.5,-1"]);
    for key in [
        "A",
        "L",
        "S",
        "inertia",
        "J",
        "mass_matrix",
        "coriolis_matrix",
        "gravity_torque",
    ] {
        assert!(!cf[key].is_null(), "{key}");
    }
    assert_eq!(mat(&cf["A"]).len(), 12);
    assert_eq!(mat(&cf["S"])[0].len(), 2);
    let mm = mat(&cf["mass_matrix"]);
    close(&mm[0], &[3.0, 1.0], 1e-12);
    close(&mm[1], &[1.0, 1.0], 1e-12);
    // L has identity diagonal blocks.
    assert_eq!(mat(&cf["L"])[7][7], 1.0);
    // Seed 004's table at θ2 = 90°: D11 = 3, D12 = 1, D22 = 1; effective inertia of joint 1:
    // 3 locked, D11 − D12²/D22 = 2 free; D_112 = −m2 l1 l2 sin θ2 = −1, D_211 = 1.
    let l = json(&["lagrange", "builtin:planar2", "--q", &q]);
    close(&mat(&l["D_ij"])[0], &[3.0, 1.0], 1e-12);
    close(&vec(&l["effective_inertia_locked"]), &[3.0, 1.0], 1e-12);
    close(&vec(&l["effective_inertia_free"]), &[2.0, 2.0 / 3.0], 1e-12);
    close(&[mat(&l["D_ijk"]["joint1"])[0][1]], &[-1.0], 1e-12);
    close(&[mat(&l["D_ijk"]["joint2"])[0][0]], &[1.0], 1e-12);
    close(&vec(&l["D_i"]), &[2.0 * G, 0.0], 1e-12);
}

/// `explain --format json` at state `(q, v, a)`, with `extra` arguments.
fn explain_json(spec: &str, q: &[f64], v: &[f64], a: &[f64], extra: &[&str]) -> serde_json::Value {
    let (q, v, a) = (csv(q), csv(v), csv(a));
    let mut args = vec!["explain", spec, "--q", &q, "--v", &v, "--a", &a];
    args.extend_from_slice(extra);
    json(&args)
}

#[test]
fn explain_prints_the_seed_iterations_and_rnea_torques() {
    // Planar arm: the printed τ is the seed's closed form.
    let (m, cv, g) = planar2(Q, V);
    let expect: Vec<f64> = (0..2)
        .map(|i| m[i][0] * A[0] + m[i][1] * A[1] + cv[i] + g[i])
        .collect();
    let args = [
        "explain",
        "builtin:planar2",
        "--q",
        &csv(&Q),
        "--v",
        &csv(&V),
        "--a",
        &csv(&A),
    ];
    let out = json(&args);
    close(&vec(&out["tau"]), &expect, 1e-12);
    // V_2 in frame 2 and the base acceleration standing in for gravity.
    assert_eq!(vec(&out["forward"]["link1"]["Vdot"]).len(), 6);
    let mut table_args = args.to_vec();
    table_args.extend(["--format", "table"]);
    let text = ok(&table_args);
    for needle in [
        "H_2^1(θ_2)",
        "V_1^{1,0} = Ad_{H_0^1} V_0^{0,0} + S_1^{1,0} θ̇_1",
        "V̇_2^{2,0}",
        "W_1^{2,2}",
        "+ Ad_{H_1^2}ᵀ W_1^{2,2}",
        "τ_1 = (S_1^{1,0})ᵀ W_0^{1,1}",
    ] {
        assert!(text.contains(needle), "missing {needle} in\n{text}");
    }
    assert!(
        text.contains(&format!("τ_2 (joint2) = {:.6}", expect[1])),
        "{text}"
    );
    // UR5 and a branched tree: the printed τ equals the library's RNEA.
    for (spec, n) in [("builtin:ur5", 6), ("builtin:branched", 0)] {
        let model = load_model(spec).unwrap();
        let n = if n == 0 { model.nq() } else { n };
        let mut r = Lcg(7);
        let (q, v, a) = (r.vec(n), r.vec(n), r.vec(n));
        let out = explain_json(spec, &q, &v, &a, &[]);
        let mut ws = Workspace::new(&model);
        let tau = dynamics::rnea(&model, &mut ws, &q, &v, &a).unwrap();
        close(&vec(&out["tau"]), tau.as_slice(), 1e-10);
    }
}

#[test]
fn explain_takes_external_wrenches() {
    // Statics of the planar arm (unit links, no gravity) with its tip pushing 1 N along link 2's
    // own y axis: τ = J_eᵀ W_tip = (1 + cos θ₂, 1), the lever arms of the force about each joint.
    let q2: f64 = 0.5;
    let args = [
        "explain",
        "builtin:planar2",
        "--gravity",
        "0,0,0",
        "--q",
        "0.3,0.5",
        "--tip-wrench",
        "link2:0,0,0,0,1,0",
    ];
    let out = json(&args);
    close(&vec(&out["tau"]), &[1.0 + q2.cos(), 1.0], 1e-12);
    let mut table_args = args.to_vec();
    table_args.extend(["--format", "table"]);
    let text = ok(&table_args);
    assert!(
        text.contains("− W_ext^{2,2} = (0, 0, 0 | 0, 1.000000, 0)"),
        "{text}"
    );
    // A base-frame wrench on a UR5 body: the printed τ equals the library's RNEA with it.
    let model = load_model("builtin:ur5").unwrap();
    let mut r = Lcg(3);
    let (q, v, a) = (r.vec(6), r.vec(6), r.vec(6));
    let out = explain_json(
        "builtin:ur5",
        &q,
        &v,
        &a,
        &["--wrench", "wrist_2_link:0.1,-0.2,0.3,5,-4,3@world"],
    );
    let mut ext = dynamics::ExternalWrenches::new(&model);
    let body = model.body_id("wrist_2_link").unwrap();
    ext.add_world(body, nalgebra::Vector6::new(0.1, -0.2, 0.3, 5.0, -4.0, 3.0))
        .unwrap();
    let mut ws = Workspace::new(&model);
    let tau = dynamics::inverse_dynamics(&model, &mut ws, &q, &v, &a, Some(&ext)).unwrap();
    close(&vec(&out["tau"]), tau.as_slice(), 1e-10);
}

#[test]
fn urdf_and_ur5_match_the_library() {
    for spec in [ARM3, "builtin:ur5"] {
        let model = load_model(spec).unwrap();
        let n = model.nq();
        let mut r = Lcg(11);
        let (q, v, a) = (r.vec(n), r.vec(n), r.vec(n));
        let mut ws = Workspace::new(&model);
        let tau = dynamics::rnea(&model, &mut ws, &q, &v, &a).unwrap().clone();
        let out = json(&[
            "rnea",
            spec,
            "--q",
            &csv(&q),
            "--v",
            &csv(&v),
            "--a",
            &csv(&a),
        ]);
        close(&vec(&out["tau"]), tau.as_slice(), 1e-10);
        let mm = dynamics::crba(&model, &mut ws, &q).unwrap().clone();
        let out = mat(&json(&["crba", spec, "--q", &csv(&q)])["mass_matrix"]);
        for (i, row) in out.iter().enumerate() {
            close(row, &mm.row(i).iter().copied().collect::<Vec<_>>(), 1e-10);
        }
        let qdd = dynamics::forward_dynamics(
            &model,
            &mut ws,
            &q,
            &v,
            tau.as_slice(),
            None,
            ForwardMethod::Aba,
        )
        .unwrap()
        .clone();
        let out = json(&[
            "aba",
            spec,
            "--q",
            &csv(&q),
            "--v",
            &csv(&v),
            "--tau",
            &csv(tau.as_slice()),
        ]);
        close(&vec(&out["qdd"]), qdd.as_slice(), 1e-9);
        close(&vec(&out["qdd"]), &a, 1e-8);
    }
}

#[test]
fn single_state_csv_has_design_columns() {
    let out = ok(&["crba", "builtin:planar2", "--q", "0,0", "--format", "csv"]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "mass_matrix.joint1.joint1,mass_matrix.joint1.joint2,mass_matrix.joint2.joint1,mass_matrix.joint2.joint2"
    );
    assert_eq!(lines[1], "5.0,2.0,2.0,1.0");
    assert_eq!(lines.len(), 2);
    let out = ok(&["energy", "builtin:planar2", "--q", "0,0", "--format", "csv"]);
    assert!(out.starts_with("kinetic_energy,potential_energy,total_energy,center_of_mass.x"));
    let out = ok(&["rnea", "builtin:planar2", "--format", "csv"]);
    assert_eq!(out.lines().next().unwrap(), "tau.joint1,tau.joint2");
    let out = ok(&["aba", "builtin:planar2", "--format", "csv"]);
    assert_eq!(out.lines().next().unwrap(), "qdd.joint1,qdd.joint2");
    let out = ok(&["gravity", "builtin:planar2", "--format", "csv"]);
    assert_eq!(
        out.lines().next().unwrap(),
        "gravity_torque.joint1,gravity_torque.joint2"
    );
    let out = ok(&["nonlinear-effects", "builtin:planar2", "--format", "csv"]);
    assert_eq!(
        out.lines().next().unwrap(),
        "nonlinear_effects.joint1,nonlinear_effects.joint2"
    );
    let out = ok(&["coriolis", "builtin:planar2", "--format", "csv"]);
    assert!(out.starts_with("coriolis_matrix.joint1.joint1,"));
    let out = ok(&["jacobian", "builtin:planar2", "--format", "csv"]);
    assert!(out.starts_with("frame,reference,jacobian.wx.joint1,jacobian.wx.joint2,"));
    // Tables work too and name the joints.
    let out = ok(&["crba", "builtin:planar2", "--format", "table"]);
    assert!(out.contains("joint2") && out.contains("5.000000"));
}

#[test]
fn batch_of_1000_states() {
    let model = load_model("builtin:ur5").unwrap();
    let names = model.joint_names();
    let n = model.nq();
    let mut r = Lcg(3);
    let mut text = String::new();
    // Columns in a shuffled order, no a.<joint> columns for the last joint (zero).
    let mut header = Vec::new();
    for key in ["a", "q", "v"] {
        for (i, j) in names.iter().enumerate() {
            if !(key == "a" && i == n - 1) {
                header.push(format!("{key}.{j}"));
            }
        }
    }
    text.push_str(&header.join(","));
    text.push('\n');
    let mut states = Vec::new();
    for _ in 0..1000 {
        let (mut a, q, v) = (r.vec(n), r.vec(n), r.vec(n));
        a[n - 1] = 0.0;
        let cells: Vec<String> = a[..n - 1]
            .iter()
            .chain(&q)
            .chain(&v)
            .map(|x| x.to_string())
            .collect();
        text.push_str(&cells.join(","));
        text.push('\n');
        states.push((q, v, a));
    }
    let path = tmp("states1000.csv");
    std::fs::write(&path, text).unwrap();
    let p = path.to_str().unwrap();
    let out = ok(&["rnea", "builtin:ur5", "--input", p, "--format", "csv"]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 1001);
    let expect_header: Vec<String> = names.iter().map(|j| format!("tau.{j}")).collect();
    assert_eq!(lines[0], expect_header.join(","));
    let mut ws = Workspace::new(&model);
    for (k, (q, v, a)) in states.iter().enumerate() {
        let tau = dynamics::rnea(&model, &mut ws, q, v, a).unwrap();
        let row: Vec<f64> = lines[k + 1]
            .split(',')
            .map(|c| c.parse().unwrap())
            .collect();
        close(&row, tau.as_slice(), 1e-12);
    }
    // JSON: an array of one object per row.
    let out = json(&["mass-matrix", "builtin:ur5", "--input", p]);
    let rows = out.as_array().unwrap();
    assert_eq!(rows.len(), 1000);
    let mm = dynamics::crba(&model, &mut ws, &states[999].0).unwrap();
    close(
        &mat(&rows[999]["mass_matrix"])[2],
        &mm.row(2).iter().copied().collect::<Vec<_>>(),
        1e-12,
    );
    assert_eq!(rows[0]["joints"].as_array().unwrap().len(), 6);
    // Matrices in batch CSV: <key>.<row joint>.<col joint>.
    let out = ok(&["crba", "builtin:ur5", "--input", p, "--format", "csv"]);
    assert!(out.starts_with("mass_matrix.shoulder_pan_joint.shoulder_pan_joint,mass_matrix.shoulder_pan_joint.shoulder_lift_joint,"));
    assert_eq!(out.lines().count(), 1001);
}

/// CSV columns follow the design of docs/cli.md: `<key>.<joint>` for vectors, the rows of a
/// matrix in order as `<key>.<row joint>.<column joint>`, scalars by their key; JSON nests the
/// same matrix row by row. The values are the two-link closed form.
#[test]
fn csv_columns_follow_design() {
    let (m, _, _) = planar2(Q, V);
    let out = ok(&[
        "mass-matrix",
        "builtin:planar2",
        "--q",
        &csv(&Q),
        "--format",
        "csv",
    ]);
    let mut lines = out.lines();
    assert_eq!(
        lines.next().unwrap(),
        "mass_matrix.joint1.joint1,mass_matrix.joint1.joint2,mass_matrix.joint2.joint1,mass_matrix.joint2.joint2"
    );
    let row: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    close(&row, &[m[0][0], m[0][1], m[1][0], m[1][1]], 1e-12);
    let j = json(&["mass-matrix", "builtin:planar2", "--q", &csv(&Q)]);
    assert_eq!(j["joints"][1], "joint2");
    close(&[f(&j["mass_matrix"][1][0])], &[m[1][0]], 1e-12);
    let out = ok(&[
        "energy",
        "builtin:planar2",
        "--q",
        &csv(&Q),
        "--v",
        &csv(&V),
        "--format",
        "csv",
    ]);
    assert!(out.starts_with("kinetic_energy,potential_energy,total_energy,center_of_mass.x,"));
}

/// `--input -` reads the states from standard input: the torques are the library's RNEA of the
/// same states, and a bad row is named by its line of standard input while the good rows still
/// come out.
#[test]
fn batch_input_from_standard_input() {
    let model = load_model("builtin:planar2").unwrap();
    let states = [
        [0.3, -0.2, 0.5, 1.0, -0.4, 0.7],
        [1.1, 0.4, -0.6, 0.2, 0.9, -1.3],
    ];
    let mut text = String::from("q.joint1,q.joint2,v.joint1,v.joint2,a.joint1,a.joint2\n");
    for s in &states {
        text.push_str(&csv(s));
        text.push('\n');
    }
    let out = bin()
        .args(["rnea", "builtin:planar2", "--input", "-", "--format", "csv"])
        .write_stdin(text.clone())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 3);
    let mut ws = Workspace::new(&model);
    for (s, line) in states.iter().zip(&lines[1..]) {
        let tau = dynamics::rnea(&model, &mut ws, &s[0..2], &s[2..4], &s[4..6]).unwrap();
        let row: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        close(&row, tau.as_slice(), 1e-12);
    }
    text.push_str("0,zero,0,0,0,0\n");
    let out = bin()
        .args(["rnea", "builtin:planar2", "--input", "-", "--format", "csv"])
        .write_stdin(text)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 3);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("standard input:4: column 'q.joint2': 'zero' is not a number"),
        "{err}"
    );
}
