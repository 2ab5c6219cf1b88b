//! `explain`: the recursive Newton–Euler iterations of Lynch & Park's *Modern Robotics*, step by step
//! ([`screwdyn::dynamics::rnea_trace`]), printed so that a student can check a homework line by
//! line:
//!
//! - forward, `i = 1 … n`: `H_i^{λ(i)}(θ_i) = H_i^{λ(i)}(0) e^{S̃ θ_i}`,
//!   `V_i^{i,0} = Ad_{H_{λ(i)}^i} V_{λ(i)} + S_i θ̇_i`,
//!   `V̇_i^{i,0} = Ad_{H_{λ(i)}^i} V̇_{λ(i)} − ad_{S_i θ̇_i}(Ad_{H_{λ(i)}^i} V_{λ(i)}) + S_i θ̈_i`,
//!   with `V_0 = 0` and `V̇_0 = (0, −g)` (gravity as a base acceleration);
//! - backward, `i = n … 1`: `W_{λ(i)}^{i,i} = 𝔍^{i,i} V̇_i − ad_{V_i}ᵀ(𝔍^{i,i} V_i)
//!   − W_ext^{i,i} + Σ_children Ad_{H_i^c}ᵀ W_i^{c,c}`, `τ_i = (S_i^{i,λ(i)})ᵀ W_{λ(i)}^{i,i}`
//!   (the external wrench on link `i`, from `--wrench` and `--tip-wrench`).

use super::inputs::{external_wrenches, load, names};
use super::kinematics::TWIST_ROWS;
use super::states::run_states;
use crate::args::ExplainArgs;
use crate::output::{fmt, Report, Value};
use crate::CliError;
use nalgebra::DMatrix;
use screwdyn::dynamics::{rnea_trace, RneaTrace};
use screwdyn::spatial::{Se3, Twist, Wrench};
use screwdyn::Model;

const WRENCH_ROWS: [&str; 6] = ["mx", "my", "mz", "fx", "fy", "fz"];

fn six(x: &Twist) -> String {
    let c: Vec<String> = x.iter().map(|v| fmt(*v)).collect();
    format!("({} | {})", c[..3].join(", "), c[3..].join(", "))
}

fn pose_lines(h: &Se3, indent: &str) -> String {
    let m = h.to_matrix();
    (0..4)
        .map(|r| {
            let row: Vec<String> = (0..4).map(|c| format!("{:>12}", fmt(m[(r, c)]))).collect();
            format!("{indent}[{} ]\n", row.join(""))
        })
        .collect()
}

/// The narrative of a [`RneaTrace`] in the notation of docs/notation.md (1-based body indices, the base is
/// 0).
pub fn narrative(m: &Model, it: &RneaTrace) -> String {
    let idx = |i: usize| i + 1;
    let par = |i: usize| m.parents()[i].map_or(0, |p| p + 1);
    let mut t = String::new();
    t.push_str(
        "Recursive Newton–Euler algorithm (Lynch & Park, *Modern Robotics*), twists (ω | v), wrenches (m | f).\n",
    );
    t.push_str(&format!(
        "Base: V_0^{{0,0}} = 0, V̇_0^{{0,0}} = (0, −g) = {}  (gravity as a base acceleration)\n\n",
        six(&it.base_acceleration)
    ));
    t.push_str("Forward iterations, i = 1 … n:\n");
    for (i, (joint, f)) in m.joints().iter().zip(&it.forward).enumerate() {
        let (k, p) = (idx(i), par(i));
        t.push_str(&format!(
            "\n i = {k}: joint '{}' ({}), body '{}', parent {p}{}\n",
            joint.name,
            joint.kind.name(),
            m.bodies()[i].name,
            if p == 0 { " (base)" } else { "" }
        ));
        t.push_str(&format!(
            "   θ_{k} = {}, θ̇_{k} = {}, θ̈_{k} = {}\n",
            fmt(f.q),
            fmt(f.v),
            fmt(f.a)
        ));
        t.push_str(&format!("   S_{k}^{{{k},{p}}} = {}\n", six(&joint.screw)));
        t.push_str(&format!(
            "   H_{k}^{p}(θ_{k}) = H_{k}^{p}(0) e^{{S̃_{k} θ_{k}}} =\n{}",
            pose_lines(&f.pose_in_parent, "      ")
        ));
        t.push_str(&format!(
            "   Ad_{{H_{p}^{k}}} V_{p}^{{{p},0}} = {}\n",
            six(&f.parent_twist)
        ));
        t.push_str(&format!(
            "   V_{k}^{{{k},0}} = Ad_{{H_{p}^{k}}} V_{p}^{{{p},0}} + S_{k}^{{{k},{p}}} θ̇_{k} = {}\n",
            six(&f.twist)
        ));
        t.push_str(&format!(
            "   V̇_{k}^{{{k},0}} = Ad_{{H_{p}^{k}}} V̇_{p}^{{{p},0}} − ad_{{S_{k} θ̇_{k}}}(Ad_{{H_{p}^{k}}} V_{p}^{{{p},0}}) + S_{k}^{{{k},{p}}} θ̈_{k} = {}\n",
            six(&f.twist_dot)
        ));
    }
    t.push_str("\nBackward iterations, i = n … 1:\n");
    for i in (0..m.nq()).rev() {
        let (k, p) = (idx(i), par(i));
        let b = &it.backward[i];
        t.push_str(&format!("\n i = {k}: body '{}'\n", m.bodies()[i].name));
        t.push_str(&format!(
            "   𝔍^{{{k},{k}}} V̇_{k} − ad_{{V_{k}}}ᵀ(𝔍^{{{k},{k}}} V_{k}) = {}\n",
            six(&b.inertial)
        ));
        if b.external != Wrench::zeros() {
            t.push_str(&format!("   − W_ext^{{{k},{k}}} = {}\n", six(&-b.external)));
        }
        for (c, back) in &b.from_children {
            let kc = idx(*c);
            t.push_str(&format!(
                "   + Ad_{{H_{k}^{kc}}}ᵀ W_{k}^{{{kc},{kc}}} = {}\n",
                six(back)
            ));
        }
        t.push_str(&format!("   W_{p}^{{{k},{k}}} = {}\n", six(&b.wrench)));
        t.push_str(&format!(
            "   τ_{k} = (S_{k}^{{{k},{p}}})ᵀ W_{p}^{{{k},{k}}} = {}\n",
            fmt(b.tau)
        ));
    }
    t.push_str("\nJoint torques:\n");
    for (i, j) in m.joints().iter().enumerate() {
        t.push_str(&format!(
            "   τ_{} ({}) = {}\n",
            idx(i),
            j.name,
            fmt(it.tau[i])
        ));
    }
    t
}

/// `screwdyn explain MODEL --q --v --a`.
pub fn explain(a: &ExplainArgs) -> Result<(), CliError> {
    if a.style != crate::args::ExplainStyle::LieGroup {
        return super::classic::explain_classic(a);
    }
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let j = names(&m);
    let ext = external_wrenches(&m, &a.wrenches.wrench, &a.wrenches.tip_wrench)?;
    let flags = [
        ("q", a.q.as_deref()),
        ("v", a.v.as_deref()),
        ("a", a.a.as_deref()),
    ];
    run_states(&m, &a.common, &flags, |s| {
        let it = rnea_trace(&m, &s.q, &s.v, &s.a, ext.as_ref())?;
        let per_body = |f: &dyn Fn(usize) -> Vec<(String, Value)>| {
            Value::Map(
                m.bodies()
                    .iter()
                    .enumerate()
                    .map(|(i, b)| (b.name.clone(), Value::Map(f(i))))
                    .collect(),
            )
        };
        let forward = per_body(&|i| {
            let h = it.forward[i].pose_in_parent.to_matrix();
            vec![
                (
                    "H".into(),
                    Value::numbered(&DMatrix::from_iterator(4, 4, h.iter().copied())),
                ),
                (
                    "V".into(),
                    Value::six(TWIST_ROWS, it.forward[i].twist.as_slice()),
                ),
                (
                    "Vdot".into(),
                    Value::six(TWIST_ROWS, it.forward[i].twist_dot.as_slice()),
                ),
            ]
        });
        let backward = per_body(&|i| {
            vec![
                (
                    "W".into(),
                    Value::six(WRENCH_ROWS, it.backward[i].wrench.as_slice()),
                ),
                ("tau".into(), Value::Scalar(it.tau[i])),
            ]
        });
        let mut r = Report::new();
        r.add("joints", Value::Names(j.clone()))
            .add("forward", forward)
            .add("backward", backward)
            .add("tau", Value::joints(&j, &it.tau));
        r.table = Some(narrative(&m, &it));
        Ok(r)
    })
}
