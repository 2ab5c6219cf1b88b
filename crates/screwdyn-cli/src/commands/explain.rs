//! `explain`: the recursive Newton–Euler iterations of seeds 000/002, step by step, re-derived
//! here from the library's spatial operators so that a student can check a homework line by line:
//!
//! - forward, `i = 1 … n`: `H_i^{λ(i)}(θ_i) = H_i^{λ(i)}(0) e^{S̃ θ_i}`,
//!   `V_i^{i,0} = Ad_{H_{λ(i)}^i} V_{λ(i)} + S_i θ̇_i`,
//!   `V̇_i^{i,0} = Ad_{H_{λ(i)}^i} V̇_{λ(i)} − ad_{S_i θ̇_i}(Ad_{H_{λ(i)}^i} V_{λ(i)}) + S_i θ̈_i`,
//!   with `V_0 = 0` and `V̇_0 = (0, −g)` (gravity as a base acceleration);
//! - backward, `i = n … 1`: `W_{λ(i)}^{i,i} = 𝔍^{i,i} V̇_i − ad_{V_i}ᵀ(𝔍^{i,i} V_i)
//!   − W_ext^{i,i} + Σ_children Ad_{H_i^c}ᵀ W_i^{c,c}`, `τ_i = (S_i^{i,λ(i)})ᵀ W_{λ(i)}^{i,i}`
//!   (seed 000's external wrench on link `i`, from `--wrench` and `--tip-wrench`).

use super::kinematics::TWIST_ROWS;
use super::{external_wrenches, load, names, run_states};
use crate::args::ExplainArgs;
use crate::output::{fmt, Report, Value};
use crate::CliError;
use nalgebra::{DMatrix, Vector3};
use screwdyn::dynamics::ExternalWrenches;
use screwdyn::spatial::{ad, ad_transpose, twist, Se3, Twist, Wrench};
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

/// The seeds' quantities of one RNEA run.
pub struct Iterations {
    pub pose: Vec<Se3>,
    pub twist: Vec<Twist>,
    pub twist_dot: Vec<Twist>,
    pub wrench: Vec<Wrench>,
    pub tau: Vec<f64>,
    pub text: String,
}

/// Runs both passes and writes the narrative; `ext` adds external wrenches on the bodies.
pub fn iterations(
    m: &Model,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    ext: Option<&ExternalWrenches>,
) -> Iterations {
    let n = m.nq();
    // 1-based seed indices: body i is index i − 1, the base is 0.
    let idx = |i: usize| i + 1;
    let par = |i: usize| m.parent(i).map(|p| p + 1).unwrap_or(0);
    let g = m.gravity();
    let vdot0: Twist = twist(Vector3::zeros(), -g);
    let mut t = String::new();
    t.push_str(
        "Recursive Newton–Euler algorithm (seeds 000/002), twists (ω | v), wrenches (m | f).\n",
    );
    t.push_str(&format!(
        "Base: V_0^{{0,0}} = 0, V̇_0^{{0,0}} = (0, −g) = {}  (gravity as a base acceleration)\n\n",
        six(&vdot0)
    ));
    t.push_str("Forward iterations, i = 1 … n:\n");
    let (mut pose, mut tw, mut twd) = (Vec::new(), Vec::new(), Vec::new());
    for (i, joint) in m.joints().iter().enumerate() {
        let (k, p) = (idx(i), par(i));
        let h = joint.pose_in_parent(q[i]);
        let (v_par, vd_par) = match m.parent(i) {
            Some(pi) => (h.inv_act_twist(&tw[pi]), h.inv_act_twist(&twd[pi])),
            None => (Twist::zeros(), h.inv_act_twist(&vdot0)),
        };
        let s = joint.screw;
        let s_qd = s * v[i];
        let vi = v_par + s_qd;
        let vdi = vd_par - ad(&s_qd, &v_par) + s * a[i];
        t.push_str(&format!(
            "\n i = {k}: joint '{}' ({}), body '{}', parent {p}{}\n",
            joint.name,
            joint.kind.name(),
            m.bodies()[i].name,
            if p == 0 { " (base)" } else { "" }
        ));
        t.push_str(&format!(
            "   θ_{k} = {}, θ̇_{k} = {}, θ̈_{k} = {}\n",
            fmt(q[i]),
            fmt(v[i]),
            fmt(a[i])
        ));
        t.push_str(&format!("   S_{k}^{{{k},{p}}} = {}\n", six(&s)));
        t.push_str(&format!(
            "   H_{k}^{p}(θ_{k}) = H_{k}^{p}(0) e^{{S̃_{k} θ_{k}}} =\n{}",
            pose_lines(&h, "      ")
        ));
        t.push_str(&format!(
            "   Ad_{{H_{p}^{k}}} V_{p}^{{{p},0}} = {}\n",
            six(&v_par)
        ));
        t.push_str(&format!(
            "   V_{k}^{{{k},0}} = Ad_{{H_{p}^{k}}} V_{p}^{{{p},0}} + S_{k}^{{{k},{p}}} θ̇_{k} = {}\n",
            six(&vi)
        ));
        t.push_str(&format!(
            "   V̇_{k}^{{{k},0}} = Ad_{{H_{p}^{k}}} V̇_{p}^{{{p},0}} − ad_{{S_{k} θ̇_{k}}}(Ad_{{H_{p}^{k}}} V_{p}^{{{p},0}}) + S_{k}^{{{k},{p}}} θ̈_{k} = {}\n",
            six(&vdi)
        ));
        pose.push(h);
        tw.push(vi);
        twd.push(vdi);
    }
    t.push_str("\nBackward iterations, i = n … 1:\n");
    let mut w = vec![Wrench::zeros(); n];
    let mut tau = vec![0.0; n];
    // H_i^0, for wrenches given in the base frame.
    let mut world = vec![Se3::identity(); n];
    for i in 0..n {
        world[i] = match m.parent(i) {
            Some(p) => world[p].compose(&pose[i]),
            None => pose[i],
        };
    }
    for i in (0..n).rev() {
        let (k, p) = (idx(i), par(i));
        let inertia = &m.bodies()[i].inertia;
        let own = inertia.apply(&twd[i]) - ad_transpose(&tw[i], &inertia.apply(&tw[i]));
        t.push_str(&format!("\n i = {k}: body '{}'\n", m.bodies()[i].name));
        t.push_str(&format!(
            "   𝔍^{{{k},{k}}} V̇_{k} − ad_{{V_{k}}}ᵀ(𝔍^{{{k},{k}}} V_{k}) = {}\n",
            six(&own)
        ));
        let mut total = own;
        if let Some(ext) = ext {
            let we = ext.on_body_at(&world[i], i);
            if we != Wrench::zeros() {
                t.push_str(&format!("   − W_ext^{{{k},{k}}} = {}\n", six(&-we)));
                total -= we;
            }
        }
        for &c in m.children(i) {
            let kc = idx(c);
            let back = pose[c].inv_act_transpose_wrench(&w[c]);
            t.push_str(&format!(
                "   + Ad_{{H_{k}^{kc}}}ᵀ W_{k}^{{{kc},{kc}}} = {}\n",
                six(&back)
            ));
            total += back;
        }
        w[i] = total;
        tau[i] = m.joints()[i].screw.dot(&total);
        t.push_str(&format!("   W_{p}^{{{k},{k}}} = {}\n", six(&total)));
        t.push_str(&format!(
            "   τ_{k} = (S_{k}^{{{k},{p}}})ᵀ W_{p}^{{{k},{k}}} = {}\n",
            fmt(tau[i])
        ));
    }
    t.push_str("\nJoint torques:\n");
    for (i, j) in m.joints().iter().enumerate() {
        t.push_str(&format!("   τ_{} ({}) = {}\n", idx(i), j.name, fmt(tau[i])));
    }
    Iterations {
        pose,
        twist: tw,
        twist_dot: twd,
        wrench: w,
        tau,
        text: t,
    }
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
        let it = iterations(&m, &s.q, &s.v, &s.a, ext.as_ref());
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
            let h = it.pose[i].to_matrix();
            vec![
                (
                    "H".into(),
                    Value::numbered(&DMatrix::from_iterator(4, 4, h.iter().copied())),
                ),
                ("V".into(), Value::six(TWIST_ROWS, it.twist[i].as_slice())),
                (
                    "Vdot".into(),
                    Value::six(TWIST_ROWS, it.twist_dot[i].as_slice()),
                ),
            ]
        });
        let backward = per_body(&|i| {
            vec![
                ("W".into(), Value::six(WRENCH_ROWS, it.wrench[i].as_slice())),
                ("tau".into(), Value::Scalar(it.tau[i])),
            ]
        });
        let mut r = Report::new();
        r.add("joints", Value::Names(j.clone()))
            .add("forward", forward)
            .add("backward", backward)
            .add("tau", Value::joints(&j, &it.tau));
        r.table = Some(it.text);
        Ok(r)
    })
}
