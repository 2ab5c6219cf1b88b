//! `explain --style craig|luh-walker-paul`: the classic vector Newton–Euler table per link
//! (Craig, *Introduction to Robotics*), computed by `screwdyn::dynamics::classic_newton_euler`.

use super::inputs::{load, names};
use super::states::run_states;
use crate::args::{ExplainArgs, ExplainStyle};
use crate::output::{fmt, Report, Value};
use crate::CliError;
use nalgebra::Vector3;
use screwdyn::dynamics::classic_newton_euler;

const NOTE: &str = "The Lie-group trace (explain without --style) lists V̇ = (ω̇, v̇_body), the \
derivative of the body twist; the classical acceleration of the frame origin here is \
v̇ = v̇_body + ω × v. The forces agree: (n, f) is the trace's wrench W and τ = Sᵀ W.";

/// `label` padded to 8 columns, not counting combining marks (the dots of `ω̇`, `v̇`).
fn pad(label: &str) -> String {
    let width = label
        .chars()
        .filter(|c| !('\u{300}'..='\u{36f}').contains(c))
        .count();
    format!("{label}{}", " ".repeat(8usize.saturating_sub(width)))
}

fn vec3(x: &Vector3<f64>) -> String {
    format!("({}, {}, {})", fmt(x.x), fmt(x.y), fmt(x.z))
}

/// The classic table, one block per link, every vector in the link's own frame.
pub fn explain_classic(a: &ExplainArgs) -> Result<(), CliError> {
    if !a.wrenches.wrench.is_empty() || !a.wrenches.tip_wrench.is_empty() {
        return Err(CliError::input(
            "--wrench and --tip-wrench work with the lie-group style only (the classic table \
             starts from f = n = 0 beyond the last link, as Craig's *Introduction to Robotics* does)",
        ));
    }
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let j = names(&m);
    let (title, vc) = match a.style {
        ExplainStyle::LuhWalkerPaul => (
            "Luh–Walker–Paul recursive Newton–Euler, each link's vectors referred to \
             its own coordinates",
            "v̇_C (ā)",
        ),
        _ => (
            "Craig's iterative Newton–Euler (*Introduction to Robotics*): outward ω, ω̇, v̇, v̇_C, F, N; inward f, n, τ; \
             vectors in the link frames",
            "v̇_C",
        ),
    };
    let flags = [
        ("q", a.q.as_deref()),
        ("v", a.v.as_deref()),
        ("a", a.a.as_deref()),
    ];
    run_states(&m, &a.common, &flags, |s| {
        let t = classic_newton_euler(&m, &s.q, &s.v, &s.a)?;
        let xyz = || crate::output::labels(&["x", "y", "z"]);
        let v3 = |x: &Vector3<f64>| Value::Vector(xyz(), x.iter().copied().collect());
        let mut text = format!("{title}\n");
        let mut links = Vec::new();
        for (i, l) in t.iter().enumerate() {
            let body = &m.bodies()[i].name;
            text.push_str(&format!("{body} (joint {}):\n", j[i]));
            for (label, x) in [
                ("ω", &l.omega),
                ("ω̇", &l.omega_dot),
                ("v̇", &l.v_dot),
                (vc, &l.v_dot_com),
                ("F", &l.force),
                ("N", &l.moment),
                ("f", &l.f),
                ("n", &l.n),
            ] {
                text.push_str(&format!("  {} = {}\n", pad(label), vec3(x)));
            }
            text.push_str(&format!("  {} = {}\n", pad("τ"), fmt(l.tau)));
            links.push((
                body.clone(),
                Value::Map(vec![
                    ("omega".into(), v3(&l.omega)),
                    ("omega_dot".into(), v3(&l.omega_dot)),
                    ("v_dot".into(), v3(&l.v_dot)),
                    ("v_dot_com".into(), v3(&l.v_dot_com)),
                    ("F".into(), v3(&l.force)),
                    ("N".into(), v3(&l.moment)),
                    ("f".into(), v3(&l.f)),
                    ("n".into(), v3(&l.n)),
                    ("tau".into(), Value::Scalar(l.tau)),
                ]),
            ));
        }
        text.push_str(&format!("note: {NOTE}\n"));
        let tau: Vec<f64> = t.iter().map(|l| l.tau).collect();
        let mut r = Report::new();
        r.add("joints", Value::Names(j.clone()))
            .add("links", Value::Map(links))
            .add("tau", Value::joints(&j, &tau))
            .add("note", Value::Text(NOTE.into()));
        r.table = Some(text);
        Ok(r)
    })
}
