//! Loading models and the `info` command.

use crate::args::{Format, ModelArgs};
use crate::output::resolve;
use crate::CliError;
use screwdyn::Model;

/// Loads `builtin:<name>` or a `.urdf` / `.toml` description file.
pub fn load(spec: &str) -> Result<Model, CliError> {
    Ok(screwdyn::io::load_model(spec)?)
}

fn tree(model: &Model, body: Option<usize>, depth: usize, out: &mut String) {
    let kids: Vec<usize> = match body {
        Some(b) => model.children(b).to_vec(),
        None => (0..model.nq())
            .filter(|&i| model.parent(i).is_none())
            .collect(),
    };
    for k in kids {
        let j = &model.joints()[k];
        out.push_str(&format!(
            "{}└─ {} ({} {}) → {}\n",
            "   ".repeat(depth),
            j.name,
            j.kind.name(),
            k,
            model.bodies()[k].name
        ));
        tree(model, Some(k), depth + 1, out);
    }
}

/// `screwdyn info MODEL`.
pub fn info(a: &ModelArgs) -> Result<(), CliError> {
    let m = load(&a.model)?;
    let g = m.gravity();
    match resolve(a.format) {
        Format::Json => {
            let joints: Vec<_> = m
                .joints()
                .iter()
                .map(|j| {
                    serde_json::json!({
                        "name": j.name, "kind": j.kind.name(), "screw": j.screw.as_slice(),
                        "lower": finite(j.limits.lower), "upper": finite(j.limits.upper),
                        "velocity": finite(j.limits.velocity), "effort": finite(j.limits.effort),
                    })
                })
                .collect();
            let bodies: Vec<_> = m
                .bodies()
                .iter()
                .map(|b| serde_json::json!({"name": b.name, "mass": b.inertia.mass, "com": b.inertia.com.as_slice()}))
                .collect();
            let frames: Vec<_> = m.frames().iter().map(|f| f.name.clone()).collect();
            let v = serde_json::json!({
                "model": m.name(), "nq": m.nq(), "joints": joints, "bodies": bodies,
                "frames": frames, "total_mass": m.total_mass(), "gravity": g.as_slice(),
            });
            println!(
                "{}",
                serde_json::to_string_pretty(&v).expect("JSON of numbers")
            );
        }
        _ => {
            println!(
                "model {}: nq = {}, total mass {:.4} kg, gravity ({}, {}, {}) m/s²",
                m.name(),
                m.nq(),
                m.total_mass(),
                g.x,
                g.y,
                g.z
            );
            println!("\njoint               kind          screw S_i^{{i,λ(i)}} (ω, v)                  lower      upper      effort");
            for j in m.joints() {
                let s: Vec<String> = j.screw.iter().map(|x| format!("{x:.3}")).collect();
                println!(
                    "{:<19} {:<13} ({:<40}) {:>9} {:>9} {:>9}",
                    j.name,
                    j.kind.name(),
                    s.join(", "),
                    lim(j.limits.lower),
                    lim(j.limits.upper),
                    lim(j.limits.effort)
                );
            }
            println!("\nbody                mass (kg)   CoM (m)");
            for b in m.bodies() {
                let c = b.inertia.com;
                println!(
                    "{:<19} {:>9.4}   ({:.4}, {:.4}, {:.4})",
                    b.name, b.inertia.mass, c.x, c.y, c.z
                );
            }
            let frames: Vec<&str> = m.frames().iter().map(|f| f.name.as_str()).collect();
            println!("\nframes: {}", frames.join(", "));
            let mut t = format!("\ntree:\n{}\n", m.base().name);
            tree(&m, None, 0, &mut t);
            print!("{t}");
        }
    }
    Ok(())
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
