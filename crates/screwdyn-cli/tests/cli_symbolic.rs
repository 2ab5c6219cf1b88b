//! `screwdyn symbolic`: the printed seed forms, and generated code compiled (C with `cc`, Rust
//! with `rustc`) or run (Python with `python3`) and compared with the numeric library at random
//! states to 1e-12.

mod common;

use common::{fails, ok, tmp, Lcg};
use nalgebra::Matrix6xX;
use screwdyn::dynamics::{
    closed_form, crba, gravity_torque, kinetic_energy, potential_energy, rnea,
};
use screwdyn::kinematics::{
    compute_joint_jacobians, forward_kinematics, frame_jacobian, frame_pose, Reference,
};
use screwdyn::{builtin, Model, Workspace};
use std::fmt::Write;
use std::process::Command;

const QUANTITIES: [(&str, &str); 8] = [
    ("mass-matrix", "mass_matrix"),
    ("coriolis", "coriolis_matrix"),
    ("gravity", "gravity_torque"),
    ("torque", "inverse_dynamics"),
    ("fk", "forward_kinematics"),
    ("jacobian", "jacobian"),
    ("energy", "energy"),
    ("regressor", "regressor"),
];

fn uses(q: &str) -> (bool, bool, bool) {
    match q {
        "coriolis" | "energy" => (true, true, false),
        "torque" | "regressor" => (true, true, true),
        _ => (true, false, false),
    }
}

/// The numeric library's value of a quantity, row-major (the regressor as `Y π = τ`, see
/// `apply`).
fn expected(m: &Model, q: &str, x: &[f64], v: &[f64], a: &[f64]) -> Vec<f64> {
    let mut ws = Workspace::new(m);
    let n = m.nq();
    let tool = m.body_frame(n - 1).unwrap();
    match q {
        "mass-matrix" => crba(m, &mut ws, x)
            .unwrap()
            .transpose()
            .iter()
            .copied()
            .collect(),
        "coriolis" => closed_form(m, x, v)
            .unwrap()
            .c
            .transpose()
            .iter()
            .copied()
            .collect(),
        "gravity" => gravity_torque(m, &mut ws, x)
            .unwrap()
            .iter()
            .copied()
            .collect(),
        "torque" | "regressor" => rnea(m, &mut ws, x, v, a).unwrap().iter().copied().collect(),
        "fk" => {
            forward_kinematics(m, &mut ws, x).unwrap();
            frame_pose(m, &ws, tool)
                .unwrap()
                .to_matrix()
                .transpose()
                .iter()
                .copied()
                .collect()
        }
        "jacobian" => {
            compute_joint_jacobians(m, &mut ws, x).unwrap();
            let mut j = Matrix6xX::zeros(n);
            frame_jacobian(m, &ws, tool, Reference::Local, &mut j).unwrap();
            j.transpose().iter().copied().collect()
        }
        "energy" => vec![
            kinetic_energy(m, &mut ws, x, v).unwrap(),
            potential_energy(m, &mut ws, x).unwrap(),
        ],
        _ => unreachable!(),
    }
}

/// For the regressor, `Y π` with the model's inertial parameters (an independent check: it must
/// equal the library's τ); other quantities unchanged.
fn apply(m: &Model, q: &str, out: Vec<f64>) -> Vec<f64> {
    if q != "regressor" {
        return out;
    }
    let n = m.nq();
    let pi: Vec<f64> = m
        .bodies()
        .iter()
        .flat_map(|b| {
            let i = &b.inertia;
            let io = i.inertia_about_origin();
            let h = i.com * i.mass;
            [
                i.mass,
                h.x,
                h.y,
                h.z,
                io[(0, 0)],
                io[(0, 1)],
                io[(0, 2)],
                io[(1, 1)],
                io[(1, 2)],
                io[(2, 2)],
            ]
        })
        .collect();
    (0..n)
        .map(|i| (0..10 * n).map(|k| out[i * 10 * n + k] * pi[k]).sum())
        .collect()
}

fn assert_close(got: &[f64], want: &[f64], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: sizes");
    let scale = want.iter().fold(1.0_f64, |s, x| s.max(x.abs()));
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= 1e-12 * scale, "{what}[{i}]: {g} vs {w}");
    }
}

fn arr(x: &[f64]) -> String {
    x.iter()
        .map(|v| format!("{v:?}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Parameter values in the order of the generated header (`[k] name = value (...)`).
fn header_params(code: &str) -> Vec<(String, f64)> {
    code.lines()
        .filter_map(|l| {
            let l = l.trim_start_matches(['/', '#', '%', ' ']);
            let rest = l.strip_prefix('[')?;
            let (_, rest) = rest.split_once("] ")?;
            let (name, rest) = rest.split_once(" = ")?;
            let value = rest.split_whitespace().next()?.parse().ok()?;
            Some((name.to_string(), value))
        })
        .collect()
}

struct Case {
    model: &'static str,
    symbols: &'static str,
    quantities: Vec<&'static str>,
}

fn run(cmd: &mut Command, what: &str) -> String {
    let out = cmd.output().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        out.status.success(),
        "{what}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn states(n: usize, k: usize) -> Vec<[Vec<f64>; 3]> {
    let mut r = Lcg(n as u64 * 31 + 7);
    (0..k)
        .map(|_| {
            let q: Vec<f64> = r.vec(n).iter().map(|x| 3.0 * x).collect();
            let v: Vec<f64> = r.vec(n).iter().map(|x| 2.0 * x).collect();
            let a: Vec<f64> = r.vec(n).iter().map(|x| 2.0 * x).collect();
            [q, v, a]
        })
        .collect()
}

fn check_c(case: &Case) {
    let m = builtin::load(case.model.trim_start_matches("builtin:")).unwrap();
    let n = m.nq();
    let mut src = String::from("#include <stdio.h>\n");
    let mut main = String::from("int main(void) {\n  double out[4096];\n");
    let st = states(n, 3);
    for (s, [q, v, a]) in st.iter().enumerate() {
        let _ = writeln!(
            main,
            "  double q{s}[] = {{{}}}, v{s}[] = {{{}}}, a{s}[] = {{{}}};",
            arr(q),
            arr(v),
            arr(a)
        );
    }
    let mut sizes = Vec::new();
    for qn in &case.quantities {
        let (_, fname) = QUANTITIES.iter().find(|(k, _)| k == qn).unwrap();
        let code = ok(&[
            "symbolic",
            case.model,
            "--quantity",
            qn,
            "--symbols",
            case.symbols,
            "--format",
            "c",
        ]);
        assert!(code.contains(&format!("void {fname}(")), "{code}");
        let params = header_params(&code);
        src.push_str(&code);
        let len = expected(&m, qn, &st[0][0], &st[0][1], &st[0][2]).len();
        let len = if *qn == "regressor" { 10 * n * n } else { len };
        sizes.push(len);
        let _ = writeln!(
            main,
            "  {{ double p[] = {{0{}}};",
            params
                .iter()
                .map(|(_, v)| format!(", {v:?}"))
                .collect::<String>()
        );
        for s in 0..st.len() {
            let (uq, uv, ua) = uses(qn);
            let mut args = Vec::new();
            if uq {
                args.push(format!("q{s}"));
            }
            if uv {
                args.push(format!("v{s}"));
            }
            if ua {
                args.push(format!("a{s}"));
            }
            if !params.is_empty() {
                args.push("p + 1".into());
            }
            args.push("out".into());
            let _ = writeln!(main, "    {fname}({});", args.join(", "));
            let _ = writeln!(
                main,
                "    for (int k = 0; k < {len}; k++) printf(\"%.17g \", out[k]); printf(\"\\n\");"
            );
        }
        main.push_str("  }\n");
    }
    main.push_str("  return 0;\n}\n");
    src.push_str(&main);
    let name = format!(
        "sym_{}_{}",
        case.model.replace(':', "_"),
        case.symbols.replace(',', "_")
    );
    let c = tmp(&format!("{name}.c"));
    let exe = tmp(&name);
    std::fs::write(&c, &src).unwrap();
    run(
        Command::new("cc")
            .args(["-O1", "-o"])
            .arg(&exe)
            .arg(&c)
            .arg("-lm"),
        "cc",
    );
    let out = run(&mut Command::new(&exe), "generated C");
    let mut lines = out.lines();
    for qn in &case.quantities {
        for [q, v, a] in &st {
            let got: Vec<f64> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            assert_close(
                &apply(&m, qn, got),
                &expected(&m, qn, q, v, a),
                &format!("C {} {qn}", case.model),
            );
        }
    }
}

#[test]
fn generated_c_matches_the_library() {
    let all = vec![
        "mass-matrix",
        "coriolis",
        "gravity",
        "torque",
        "fk",
        "jacobian",
        "energy",
        "regressor",
    ];
    for case in [
        Case {
            model: "builtin:planar2",
            symbols: "all",
            quantities: all.clone(),
        },
        Case {
            model: "builtin:ur5",
            symbols: "",
            quantities: all.clone(),
        },
        Case {
            model: "builtin:ur5",
            symbols: "mass,lengths,g",
            quantities: vec!["mass-matrix", "gravity", "torque"],
        },
        Case {
            model: "builtin:panda",
            symbols: "",
            quantities: vec![
                "mass-matrix",
                "coriolis",
                "gravity",
                "torque",
                "fk",
                "jacobian",
                "energy",
            ],
        },
        Case {
            model: "builtin:branched",
            symbols: "",
            quantities: all.clone(),
        },
    ] {
        check_c(&case);
    }
}

#[test]
fn generated_python_matches_the_library() {
    for (model, symbols) in [("builtin:planar2", "all"), ("builtin:ur5", "")] {
        let m = builtin::load(model.trim_start_matches("builtin:")).unwrap();
        let n = m.nq();
        let st = states(n, 2);
        for (qn, fname) in QUANTITIES {
            let code = ok(&[
                "symbolic",
                model,
                "--quantity",
                qn,
                "--symbols",
                symbols,
                "--format",
                "python",
            ]);
            let params = header_params(&code);
            let kw: String = params.iter().map(|(k, v)| format!(", {k}={v:?}")).collect();
            let mut script = code.clone();
            for [q, v, a] in &st {
                let (uq, uv, ua) = uses(qn);
                let mut args = Vec::new();
                if uq {
                    args.push(format!("[{}]", arr(q)));
                }
                if uv {
                    args.push(format!("[{}]", arr(v)));
                }
                if ua {
                    args.push(format!("[{}]", arr(a)));
                }
                let _ = writeln!(
                    script,
                    "print(' '.join(repr(x) for row in {fname}({}{kw}) for x in row))",
                    args.join(", ")
                );
            }
            let path = tmp(&format!("sym_{}_{qn}.py", model.replace(':', "_")));
            std::fs::write(&path, &script).unwrap();
            let out = run(Command::new("python3").arg(&path), "python3");
            for (line, [q, v, a]) in out.lines().zip(&st) {
                let got: Vec<f64> = line
                    .split_whitespace()
                    .map(|x| x.parse().unwrap())
                    .collect();
                assert_close(
                    &apply(&m, qn, got),
                    &expected(&m, qn, q, v, a),
                    &format!("Python {model} {qn}"),
                );
            }
        }
    }
}

#[test]
fn generated_rust_matches_the_library() {
    let model = "builtin:ur5";
    let m = builtin::load("ur5").unwrap();
    let st = states(6, 2);
    let mut src = String::new();
    let mut main = String::from("fn main() {\n");
    let qs = [
        "mass-matrix",
        "coriolis",
        "gravity",
        "torque",
        "jacobian",
        "energy",
    ];
    for qn in qs {
        let (_, fname) = QUANTITIES.iter().find(|(k, _)| *k == qn).unwrap();
        src.push_str(&ok(&[
            "symbolic",
            model,
            "--quantity",
            qn,
            "--format",
            "rust",
        ]));
        for [q, v, a] in &st {
            let (uq, uv, ua) = uses(qn);
            let mut args = Vec::new();
            if uq {
                args.push(format!("&[{}]", arr(q)));
            }
            if uv {
                args.push(format!("&[{}]", arr(v)));
            }
            if ua {
                args.push(format!("&[{}]", arr(a)));
            }
            let _ = writeln!(main, "    let r = {fname}({});\n    let s: Vec<String> = r.iter().flatten().map(|x| format!(\"{{:?}}\", x)).collect();\n    println!(\"{{}}\", s.join(\" \"));", args.join(", "));
        }
    }
    main.push_str("}\n");
    src.push_str(&main);
    let path = tmp("sym_ur5.rs");
    let exe = tmp("sym_ur5_rs");
    std::fs::write(&path, &src).unwrap();
    run(
        Command::new("rustc")
            .args(["--edition", "2021", "-o"])
            .arg(&exe)
            .arg(&path),
        "rustc",
    );
    let out = run(&mut Command::new(&exe), "generated Rust");
    let mut lines = out.lines();
    for qn in qs {
        for [q, v, a] in &st {
            let got: Vec<f64> = lines
                .next()
                .unwrap()
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            assert_close(&got, &expected(&m, qn, q, v, a), &format!("Rust ur5 {qn}"));
        }
    }
}

#[test]
fn text_reads_like_the_seeds() {
    let t = ok(&["symbolic", "builtin:planar2", "--symbols", "all"]);
    assert!(
        t.contains("M11 = m1 L1² + m2 (L1² + 2 L1 L2 c₂ + L2²)"),
        "{t}"
    );
    assert!(
        t.contains("M22 = m2 L2²") && t.contains("where c₂ = cos(θ₂)"),
        "{t}"
    );
    let t = ok(&[
        "symbolic",
        "builtin:planar2",
        "--symbols",
        "all",
        "--quantity",
        "gravity",
        "--collect",
        "config",
    ]);
    assert!(t.contains("g1 = (m1 + m2) g L1 c₁ + m2 g L2 c₁₂"), "{t}");
    assert!(t.contains("c₁₂ = cos(θ₁ + θ₂)"), "{t}");
    let t = ok(&[
        "symbolic",
        "builtin:planar2",
        "--symbols",
        "all",
        "--quantity",
        "gravity",
        "--no-abbrev",
    ]);
    assert!(t.contains("g2 = m2 g L2 cos(θ1 + θ2)"), "{t}");
    let t = ok(&[
        "symbolic",
        "builtin:planar2",
        "--symbols",
        "all",
        "--quantity",
        "coriolis",
        "--collect",
        "config",
    ]);
    assert!(
        t.contains("(C θ̇)1 = −2 m2 L1 L2 s₂ θ̇₁ θ̇₂ − m2 L1 L2 s₂ θ̇₂²"),
        "{t}"
    );
    assert!(t.contains("(C θ̇)2 = m2 L1 L2 s₂ θ̇₁²"), "{t}");
    let t = ok(&[
        "symbolic",
        "builtin:planar2",
        "--symbols",
        "all",
        "--quantity",
        "gravity",
        "--format",
        "latex",
    ]);
    assert!(
        t.contains("g_{2} &= m_{2} \\, g \\, L_{2} \\, c_{12}"),
        "{t}"
    );
    let j: serde_json::Value = serde_json::from_str(&ok(&[
        "symbolic",
        "builtin:planar2",
        "--symbols",
        "m2,L2",
        "--quantity",
        "mass-matrix",
        "--format",
        "json",
    ]))
    .unwrap();
    assert_eq!(j["expressions"]["M"][1][1], "m2*L2**2");
    assert_eq!(j["symbols"][0]["name"], "m2");
    // --output writes the same text to a file.
    let path = tmp("sym_planar2.txt");
    ok(&[
        "symbolic",
        "builtin:planar2",
        "--symbols",
        "all",
        "--output",
        path.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&path)
        .unwrap()
        .contains("M11 = m1 L1²"));
}

#[test]
fn bad_input_is_one_sentence() {
    fails(
        &["symbolic", "builtin:planar2", "--quantity", "speed"],
        "unknown quantity 'speed'",
    );
    fails(
        &["symbolic", "builtin:planar2", "--symbols", "m9"],
        "unknown symbol 'm9'",
    );
    fails(
        &[
            "symbolic",
            "builtin:panda",
            "--quantity",
            "torque",
            "--max-terms",
            "500",
        ],
        "--max-terms",
    );
    fails(
        &[
            "symbolic",
            "builtin:planar2",
            "--quantity",
            "fk",
            "--frame",
            "hand",
        ],
        "no frame named 'hand'",
    );
    fails(
        &["symbolic", "builtin:planar2", "--coriolis-form", "lagrange"],
        "unknown Coriolis form",
    );
}

#[test]
fn inertia_of_seed_003_shapes() {
    let j: serde_json::Value = serde_json::from_str(&ok(&[
        "inertia",
        "box",
        "--mass",
        "12",
        "--size",
        "1,2,3",
        "--about",
        "-0.5,-1,-1.5",
        "--format",
        "json",
    ]))
    .unwrap();
    // Seed 003: m/3 (l² + h²) = 52, −m/4 w l = −6, −m/4 h w = −9, −m/4 h l = −18.
    let i = common::mat(&j["inertia"]);
    common::close(&i[0], &[52.0, -6.0, -9.0], 1e-14);
    common::close(&i[1], &[-6.0, 40.0, -18.0], 1e-14);
    common::close(&i[2], &[-9.0, -18.0, 20.0], 1e-14);
    // Tutorial question 1: the cylinder about its end, m r²/4 + m h²/3.
    let j: serde_json::Value = serde_json::from_str(&ok(&[
        "inertia", "cylinder", "--mass", "2", "--size", "0.1,1", "--about", "0,0,-0.5", "--format",
        "json",
    ]))
    .unwrap();
    let i = common::mat(&j["inertia"]);
    common::close(
        &[i[0][0], i[2][2]],
        &[2.0 * 0.01 / 4.0 + 2.0 / 3.0, 0.01],
        1e-14,
    );
    fails(
        &["inertia", "box", "--mass", "1", "--size", "1,2"],
        "a box takes 3 sizes",
    );
    fails(&["inertia", "cone", "--mass", "1"], "unknown shape 'cone'");
    fails(
        &["inertia", "sphere", "--mass", "-1", "--size", "1"],
        "mass",
    );
}

#[test]
fn explain_classic_style_matches_rnea() {
    let args = ["--q", "0.3,-0.8", "--v", "1.1,-0.6", "--a", "0.4,0.9"];
    let mut c = vec![
        "explain",
        "builtin:planar2",
        "--style",
        "craig",
        "--format",
        "json",
    ];
    c.extend(args);
    let j: serde_json::Value = serde_json::from_str(&ok(&c)).unwrap();
    let mut r = vec!["inverse-dynamics", "builtin:planar2", "--format", "json"];
    r.extend(args);
    let t: serde_json::Value = serde_json::from_str(&ok(&r)).unwrap();
    common::close(&common::vec(&j["tau"]), &common::vec(&t["tau"]), 1e-12);
    assert!(j["note"].as_str().unwrap().contains("ω × v"));
    let text = ok(&[
        "explain",
        "builtin:planar2",
        "--style",
        "luh-walker-paul",
        "--format",
        "table",
    ]);
    assert!(
        text.contains("Luh–Walker–Paul") && text.contains("v̇_C"),
        "{text}"
    );
}

#[test]
fn closed_form_prints_the_stacked_recursion() {
    let args = ["--q", "0.3,-0.8", "--v", "1.1,-0.6", "--a", "0.4,0.9"];
    let mut c = vec!["closed-form", "builtin:planar2", "--format", "json"];
    c.extend(args);
    let j: serde_json::Value = serde_json::from_str(&ok(&c)).unwrap();
    let mut r = vec!["inverse-dynamics", "builtin:planar2", "--format", "json"];
    r.extend(args);
    let t: serde_json::Value = serde_json::from_str(&ok(&r)).unwrap();
    common::close(&common::vec(&j["tau"]), &common::vec(&t["tau"]), 1e-12);
    for key in ["V", "Vdot", "W", "ad_S_qdot", "ad_V", "Vdot_base"] {
        assert!(j.get(key).is_some(), "{key}");
    }
    // τ_i = S_iᵀ W_i with planar2's S_i = (0, 0, 1, 0, L_i, 0), L_i = 1 (ẑ through the joint,
    // one link length behind the frame).
    let w = common::vec(&j["W"]);
    let tau = common::vec(&j["tau"]);
    common::close(&tau, &[w[2] + w[4], w[8] + w[10]], 1e-12);
}

#[test]
fn lagrange_steps_print_seed_004() {
    let t = ok(&["lagrange", "builtin:planar2", "--steps"]);
    assert!(
        t.contains("∂L/∂θ1 = −(m1 + m2) g L1 c₁ − m2 g L2 c₁₂"),
        "{t}"
    );
    assert!(
        t.contains("d/dt(∂L/∂θ̇2) = m2 L1 L2 c₂ θ̈₁ − m2 L1 L2 s₂ θ̇₁ θ̇₂ + m2 L2² θ̈₁ + m2 L2² θ̈₂"),
        "{t}"
    );
    fails(
        &["lagrange", "builtin:planar2", "--steps", "--q", "0,0"],
        "drop --q",
    );
}
