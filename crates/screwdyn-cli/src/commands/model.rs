//! `info`, `check` and `export`.

use super::inputs::load;
use crate::args::{CheckArgs, ExportArgs, ExportFormat, Format, ModelArgs};
use crate::output::{fmt, resolve, table, write_stdout};
use crate::CliError;
use screwdyn::io::LoadOptions;
use screwdyn::{Model, Workspace};
use std::path::Path;

/// Indentation stops growing at this depth (deeper levels say their depth), so the drawing of
/// a long chain stays linear in its length.
const MAX_TREE_INDENT: usize = 24;

/// The kinematic tree below the root, one line per joint, depth-first (iterative: a chain of
/// any length draws without deep recursion).
fn tree(model: &Model, out: &mut String) {
    let roots = (0..model.nq()).filter(|&i| model.parents()[i].is_none());
    let mut stack: Vec<(usize, usize)> = roots.rev().map(|k| (k, 0)).collect();
    let children = |b: usize| model.children(b).unwrap_or(&[]);
    while let Some((k, depth)) = stack.pop() {
        let j = &model.joints()[k];
        let indent = "   ".repeat(depth.min(MAX_TREE_INDENT));
        let deep = if depth > MAX_TREE_INDENT {
            format!("[depth {depth}] ")
        } else {
            String::new()
        };
        out.push_str(&format!(
            "{indent}{deep}└─ {} ({} {}) → {}\n",
            j.name,
            j.kind.name(),
            k,
            model.bodies()[k].name
        ));
        stack.extend(children(k).iter().rev().map(|&c| (c, depth + 1)));
    }
}

/// `screwdyn info MODEL`.
pub fn info(a: &ModelArgs) -> Result<(), CliError> {
    let m = load(a, None)?;
    let g = m.gravity();
    match resolve(a.format) {
        Format::Json | Format::Csv => {
            let joints: Vec<_> = m
                .joints()
                .iter()
                .map(|j| {
                    serde_json::json!({
                        "name": j.name, "kind": j.kind.name(), "screw": j.screw.as_slice(),
                        "lower": finite(j.limits.lower), "upper": finite(j.limits.upper),
                        "velocity": finite(j.limits.velocity), "effort": finite(j.limits.effort),
                        "damping": j.damping, "friction": j.friction, "armature": j.armature,
                        "stiffness": j.stiffness, "springref": j.springref,
                    })
                })
                .collect();
            let bodies: Vec<_> = m
                .bodies()
                .iter()
                .enumerate()
                .map(|(i, b)| serde_json::json!({
                    "name": b.name, "mass": b.inertia.mass, "com": b.inertia.com.as_slice(),
                    "parent": m.parents()[i].map(|p| m.bodies()[p].name.clone()).unwrap_or_else(|| m.base().name.clone()),
                }))
                .collect();
            let frames: Vec<_> = m
                .frames()
                .iter()
                .map(|f| {
                    serde_json::json!({
                        "name": f.name,
                        "body": f.body.map(|b| m.bodies()[b].name.clone()).unwrap_or_else(|| m.base().name.clone()),
                    })
                })
                .collect();
            let v = serde_json::json!({
                "model": m.name(), "nq": m.nq(), "joints": joints, "bodies": bodies,
                "frames": frames, "total_mass": m.total_mass(), "gravity": g.as_slice(),
            });
            if a.format == Some(Format::Csv) {
                return Err(CliError::input(
                    "info has no CSV form; use --format table or --format json",
                ));
            }
            write_stdout(&format!(
                "{}\n",
                serde_json::to_string_pretty(&v).expect("JSON of numbers")
            ))
        }
        Format::Table => {
            let mut out = format!(
                "model {}: nq = {}, total mass {} kg, gravity ({}, {}, {}) m/s²\n\n",
                m.name(),
                m.nq(),
                fmt(m.total_mass()),
                g.x,
                g.y,
                g.z
            );
            let mut t = table();
            // The armature and spring columns only when some joint has one.
            let armature = m.joints().iter().any(|j| j.armature != 0.0);
            let springs = m.joints().iter().any(|j| j.stiffness != 0.0);
            let mut header = vec![
                "joint",
                "kind",
                "screw S_i^{i,λ(i)} (ω | v)",
                "lower",
                "upper",
                "velocity",
                "effort",
            ];
            if armature {
                header.push("armature");
            }
            if springs {
                header.extend(["stiffness", "springref"]);
            }
            t.set_header(header);
            for j in m.joints() {
                let s: Vec<String> = j.screw.iter().map(|x| format!("{x:.3}")).collect();
                let mut row = vec![
                    j.name.clone(),
                    j.kind.name().to_string(),
                    format!("({} | {})", s[..3].join(", "), s[3..].join(", ")),
                    lim(j.limits.lower),
                    lim(j.limits.upper),
                    lim(j.limits.velocity),
                    lim(j.limits.effort),
                ];
                if armature {
                    row.push(fmt(j.armature));
                }
                if springs {
                    row.extend([fmt(j.stiffness), fmt(j.springref)]);
                }
                t.add_row(row);
            }
            out.push_str(&format!("{t}\n\n"));
            let mut t = table();
            t.set_header(vec!["body", "mass (kg)", "CoM in body frame (m)"]);
            for b in m.bodies() {
                let c = b.inertia.com;
                t.add_row(vec![
                    b.name.clone(),
                    fmt(b.inertia.mass),
                    format!("({:.4}, {:.4}, {:.4})", c.x, c.y, c.z),
                ]);
            }
            out.push_str(&format!("{t}\n"));
            let frames: Vec<&str> = m.frames().iter().map(|f| f.name.as_str()).collect();
            out.push_str(&format!("\nframes: {}\n", frames.join(", ")));
            out.push_str(&format!("\ntree:\n{}\n", m.base().name));
            tree(&m, &mut out);
            write_stdout(&out)
        }
    }
}

/// `screwdyn check MODEL`: lists the model's physical-consistency problems and whether forward
/// dynamics works at `q = 0`; exit status 2 when there is any problem. For an MJCF file, also
/// every element and attribute the loader ignored (information, not a problem).
pub fn check(a: &CheckArgs) -> Result<(), CliError> {
    let loose = screwdyn::io::load_model_with(&a.model, &LoadOptions { strict: false })?;
    let ignored: Vec<String> =
        screwdyn::io::mjcf::report_of_file(&a.model, &LoadOptions { strict: false })?
            .unwrap_or_default()
            .iter()
            .map(|i| i.to_string())
            .collect();
    let mut problems: Vec<String> = loose
        .physical_problems()
        .iter()
        .map(|f| f.to_string())
        .collect();
    if loose.nq() > 0 {
        // O(n): ABA fails exactly where the mass matrix is singular, naming the joint.
        let mut ws = Workspace::new(&loose);
        let zero = vec![0.0; loose.nq()];
        if let Err(e) = screwdyn::dynamics::aba(&loose, &mut ws, &zero, &zero, &zero) {
            problems.push(format!("at q = 0: {e}"));
        }
    }
    let ok = problems.is_empty();
    match resolve(a.format) {
        Format::Table => {
            let mut out = format!(
                "{}: {} joints, {} bodies, total mass {} kg\n",
                a.model,
                loose.nq(),
                loose.nbodies(),
                fmt(loose.total_mass())
            );
            if ok {
                out.push_str("ok: every inertia is physically consistent\n");
            }
            for p in &problems {
                out.push_str(&format!("problem: {p}\n"));
            }
            if !ignored.is_empty() {
                out.push_str(&format!(
                    "the loader ignored {} element{} or attribute list{} (MJCF conformance):\n",
                    ignored.len(),
                    if ignored.len() == 1 { "" } else { "s" },
                    if ignored.len() == 1 { "" } else { "s" }
                ));
            }
            for i in &ignored {
                out.push_str(&format!("ignored: {i}\n"));
            }
            write_stdout(&out)?;
        }
        _ => {
            let v = serde_json::json!({"model": a.model, "ok": ok, "problems": problems, "ignored": ignored});
            write_stdout(&format!(
                "{}\n",
                serde_json::to_string_pretty(&v).expect("JSON of strings")
            ))?;
        }
    }
    if ok {
        Ok(())
    } else {
        Err(CliError::input(format!(
            "{} fails its checks ({} problem{}): {}",
            a.model,
            problems.len(),
            if problems.len() == 1 { "" } else { "s" },
            problems[0]
        )))
    }
}

/// `screwdyn export MODEL --to urdf|mjcf [--output FILE]` (`--format` is the same flag).
pub fn export(a: &ExportArgs) -> Result<(), CliError> {
    if let Some(p) = &a.output {
        crate::write::refuse_inputs("--output", p, &[Path::new(&a.model)])?;
    }
    let m = super::inputs::load_model(&a.model, a.strict)?;
    let text = match a.to {
        ExportFormat::Urdf => {
            let text = screwdyn::io::urdf::to_urdf_string(&m)?;
            for w in screwdyn::io::urdf::urdf_export_warnings(&m) {
                eprintln!("screwdyn: warning: {w}");
            }
            text
        }
        ExportFormat::Mjcf => {
            let text = screwdyn::io::mjcf_export::to_mjcf_string(&m)?;
            for w in screwdyn::io::mjcf_export::mjcf_export_warnings(&m) {
                eprintln!("screwdyn: warning: {w}");
            }
            text
        }
    };
    match &a.output {
        Some(p) => {
            crate::write::atomic(p, |w| {
                std::io::Write::write_all(w, text.as_bytes())
                    .map_err(|e| CliError::input(format!("cannot write {} ({e})", p.display())))
            })?;
            crate::write::announce(p);
            Ok(())
        }
        None => write_stdout(&text),
    }
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

fn lim(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.3}")
    } else {
        "-".into()
    }
}
