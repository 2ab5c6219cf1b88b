//! Inverse and forward dynamics, the matrices of the equations of motion, energies, the stacked
//! closed form and the Lagrangian coefficients.

use super::inputs::{external_wrenches, load, names};
use super::states::run_states;
use crate::args::{
    ClosedFormArgs, ForwardDynamicsArgs, InverseDynamicsArgs, LagrangeArgs, QArgs, QvArgs,
};
use crate::output::{Labels, Report, Value};
use crate::CliError;
use nalgebra::DMatrix;
use screwdyn::dynamics::{self, ForwardMethod};
use screwdyn::{Model, Workspace};

fn base(j: &Labels) -> Report {
    let mut r = Report::new();
    r.add("joints", Value::Names(j.clone()));
    r
}

/// `inverse-dynamics` (`rnea`): `tau`.
pub fn inverse_dynamics(a: &InverseDynamicsArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let ext = external_wrenches(&m, &a.wrenches.wrench, &a.wrenches.tip_wrench)?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    let flags = [
        ("q", a.q.as_deref()),
        ("v", a.v.as_deref()),
        ("a", a.a.as_deref()),
    ];
    run_states(&m, &a.common, &flags, |s| {
        let tau = dynamics::inverse_dynamics(&m, &mut ws, &s.q, &s.v, &s.a, ext.as_ref())?;
        let mut r = base(&j);
        r.add("tau", Value::joints(&j, tau.as_slice()));
        Ok(r)
    })
}

/// `mass-matrix` (`crba`): `mass_matrix`.
pub fn mass_matrix(a: &QArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    run_states(&m, &a.common, &[("q", a.q.as_deref())], |s| {
        let mm = dynamics::crba(&m, &mut ws, &s.q)?;
        let mut r = base(&j);
        r.add("mass_matrix", Value::joint_matrix(&j, mm));
        Ok(r)
    })
}

/// `coriolis`: `coriolis_matrix`.
pub fn coriolis(a: &QvArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    let flags = [("q", a.q.as_deref()), ("v", a.v.as_deref())];
    run_states(&m, &a.common, &flags, |s| {
        let c = dynamics::coriolis_matrix(&m, &mut ws, &s.q, &s.v)?;
        let mut r = base(&j);
        r.add("coriolis_matrix", Value::joint_matrix(&j, c));
        Ok(r)
    })
}

/// `gravity`: `gravity_torque`.
pub fn gravity(a: &QArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    run_states(&m, &a.common, &[("q", a.q.as_deref())], |s| {
        let g = dynamics::gravity_torque(&m, &mut ws, &s.q)?;
        let mut r = base(&j);
        r.add("gravity_torque", Value::joints(&j, g.as_slice()));
        Ok(r)
    })
}

/// `nonlinear-effects`: `nonlinear_effects`.
pub fn nonlinear_effects(a: &QvArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    let flags = [("q", a.q.as_deref()), ("v", a.v.as_deref())];
    run_states(&m, &a.common, &flags, |s| {
        let h = dynamics::nonlinear_effects(&m, &mut ws, &s.q, &s.v)?;
        let mut r = base(&j);
        r.add("nonlinear_effects", Value::joints(&j, h.as_slice()));
        Ok(r)
    })
}

/// `energy`: `kinetic_energy`, `potential_energy`, `total_energy`, `center_of_mass`.
pub fn energy(a: &QvArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    let xyz = crate::output::labels(&["x", "y", "z"]);
    let flags = [("q", a.q.as_deref()), ("v", a.v.as_deref())];
    run_states(&m, &a.common, &flags, |s| {
        let k = dynamics::kinetic_energy(&m, &mut ws, &s.q, &s.v)?;
        let p = dynamics::potential_energy(&m, &mut ws, &s.q)?;
        let c = dynamics::center_of_mass(&m, &mut ws, &s.q)
            .map(|c| vec![c.x, c.y, c.z])
            .unwrap_or_else(|_| vec![f64::NAN; 3]);
        let mut r = base(&j);
        r.add("kinetic_energy", Value::Scalar(k))
            .add("potential_energy", Value::Scalar(p))
            .add("total_energy", Value::Scalar(k + p))
            .add("center_of_mass", Value::Vector(xyz.clone(), c));
        Ok(r)
    })
}

/// `forward-dynamics` (`aba`): `qdd`.
pub fn forward_dynamics(a: &ForwardDynamicsArgs) -> Result<(), CliError> {
    let method: ForwardMethod = a
        .method
        .parse()
        .map_err(|e: screwdyn::Error| CliError::input(format!("--method: {e}")))?;
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let ext = external_wrenches(&m, &a.wrenches.wrench, &a.wrenches.tip_wrench)?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    let flags = [
        ("q", a.q.as_deref()),
        ("v", a.v.as_deref()),
        ("tau", a.tau.as_deref()),
    ];
    run_states(&m, &a.common, &flags, |s| {
        let qdd =
            dynamics::forward_dynamics(&m, &mut ws, &s.q, &s.v, &s.tau, ext.as_ref(), method)?;
        let mut r = base(&j);
        r.add("qdd", Value::joints(&j, qdd.as_slice()));
        Ok(r)
    })
}

/// Labels `<body>.wx … <body>.vz` of stacked 6n twists / wrenches.
fn stacked_labels(m: &Model) -> Labels {
    m.bodies()
        .iter()
        .flat_map(|b| {
            ["wx", "wy", "wz", "vx", "vy", "vz"]
                .iter()
                .map(move |c| format!("{}.{c}", b.name))
        })
        .collect()
}

/// `closed-form`: the `A`, `L`, `S`, `𝔍`, `J`, `M`, `C`, `g` at one state.
pub fn closed_form(args: &ClosedFormArgs) -> Result<(), CliError> {
    let a = &args.qv;
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let j = names(&m);
    let six = stacked_labels(&m);
    let flags = [
        ("q", a.q.as_deref()),
        ("v", a.v.as_deref()),
        ("a", args.a.as_deref()),
    ];
    run_states(&m, &a.common, &flags, |s| {
        let cf = dynamics::closed_form(&m, &s.q, &s.v)?;
        let (vdot, w, tau) = cf.stacked_dynamics(&s.a)?;
        let stacked =
            |x: &nalgebra::DVector<f64>| Value::Vector(six.clone(), x.iter().copied().collect());
        let sq = |x: &DMatrix<f64>| Value::Matrix(six.clone(), six.clone(), x.clone());
        let tall = |x: &DMatrix<f64>| Value::Matrix(six.clone(), j.clone(), x.clone());
        let mut r = base(&j);
        r.add("A", sq(&cf.a))
            .add("L", sq(&cf.l))
            .add("S", tall(&cf.s))
            .add("inertia", sq(&cf.inertia))
            .add("J", tall(&cf.j))
            .add("mass_matrix", Value::joint_matrix(&j, &cf.m))
            .add("coriolis_matrix", Value::joint_matrix(&j, &cf.c))
            .add("gravity_torque", Value::joints(&j, cf.g.as_slice()))
            .add("ad_S_qdot", sq(&cf.ad_s_qdot))
            .add("V", stacked(&cf.v))
            .add("ad_V", sq(&cf.ad_v))
            .add("Vdot_base", stacked(&cf.vdot_base))
            .add("Vdot", stacked(&vdot))
            .add("W", stacked(&w))
            .add("tau", Value::joints(&j, tau.as_slice()));
        let mut t = String::from(
            "The stacked closed form (Lynch & Park, *Modern Robotics*): V = L S θ̇, J = L S,\n\
             M = Sᵀ Lᵀ 𝔍 L S, C = Sᵀ Lᵀ [−𝔍 L ad_{Sθ̇} A − ad_{LSθ̇}ᵀ 𝔍] L S, g = Sᵀ Lᵀ 𝔍 L V̇_base.\n\n",
        );
        for (key, title) in [
            ("A", "A(θ): block (i, λ(i)) = Ad_{H_{λ(i)}^i}"),
            ("L", "L(θ) = (I − A)⁻¹"),
            ("S", "S = blkdiag(S_i^{i,λ(i)})"),
            ("inertia", "𝔍 = blkdiag(𝔍^{i,i})"),
            ("J", "J = L S"),
            ("mass_matrix", "M(θ)"),
            (
                "coriolis_matrix",
                "C(θ, θ̇) (the closed form's own factorisation)",
            ),
            ("gravity_torque", "g(θ)"),
            ("ad_S_qdot", "ad_{Sθ̇} = blkdiag(ad_{S_i θ̇_i})"),
            ("V", "V = L S θ̇ (stacked body twists)"),
            ("ad_V", "ad_V = blkdiag(ad_{V_i})"),
            (
                "Vdot_base",
                "V̇_base: block 1 = Ad_{H_0^1} V̇_g, V̇_g = (0, −g)",
            ),
            ("Vdot", "V̇ = L S θ̈ − L ad_{Sθ̇} A V + L V̇_base"),
            ("W", "W = Lᵀ 𝔍 V̇ − Lᵀ ad_Vᵀ 𝔍 V"),
            ("tau", "τ = Sᵀ W"),
        ] {
            let v = &r
                .items
                .iter()
                .find(|(k, _)| k == key)
                .expect("added above")
                .1;
            let mut body = String::new();
            match v {
                Value::Matrix(rl, cl, x) => body = crate::output::matrix_table(rl, cl, x),
                Value::Vector(l, x) => {
                    for (l, x) in l.iter().zip(x) {
                        body.push_str(&format!("  {l:<16} {}\n", crate::output::fmt(*x)));
                    }
                }
                _ => {}
            }
            t.push_str(&format!("{title}:\n{body}\n"));
        }
        r.table = Some(t);
        Ok(r)
    })
}

/// `lagrange`: the `D_ij`, `D_ijk`, `D_i` and the effective inertias.
pub fn lagrange(args: &LagrangeArgs) -> Result<(), CliError> {
    if args.steps {
        return lagrange_steps(args);
    }
    let a = &args.qa;
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let j = names(&m);
    let mut ws = Workspace::new(&m);
    run_states(&m, &a.common, &[("q", a.q.as_deref())], |s| {
        let c = dynamics::lagrange_coefficients(&m, &s.q)?;
        let mut locked = Vec::new();
        let mut free = Vec::new();
        for i in 0..m.nq() {
            locked.push(dynamics::effective_inertia_locked(&m, &mut ws, &s.q, i)?);
            free.push(dynamics::effective_inertia_free(&m, &mut ws, &s.q, i)?);
        }
        let mut r = base(&j);
        r.add("D_ij", Value::joint_matrix(&j, &c.d_ij))
            .add(
                "D_ijk",
                Value::Map(
                    j.iter()
                        .zip(&c.d_ijk)
                        .map(|(n, d)| (n.clone(), Value::joint_matrix(&j, d)))
                        .collect(),
                ),
            )
            .add("D_i", Value::joints(&j, c.d_i.as_slice()))
            .add("effective_inertia_locked", Value::joints(&j, &locked))
            .add("effective_inertia_free", Value::joints(&j, &free));
        Ok(r)
    })
}

/// `lagrange --steps`: the symbolic Euler–Lagrange steps (text, or ASCII in JSON).
fn lagrange_steps(args: &LagrangeArgs) -> Result<(), CliError> {
    use screwdyn::symbolic::{lagrange_steps, Collect, Options, Style};
    let a = &args.qa;
    if a.q.is_some() || a.common.input.is_some() {
        return Err(CliError::input(
            "--steps derives the equations for every θ: drop --q and --input",
        ));
    }
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let options = Options {
        symbols: args.symbols.clone(),
        max_terms: args.max_terms,
        ..Options::default()
    };
    let s = lagrange_steps(&m, &options)?;
    let text = match a.common.model.format {
        Some(crate::args::Format::Json) => {
            let lines: Vec<serde_json::Value> = s
                .render(Style::Ascii, Collect::Inertial)
                .lines()
                .filter(|l| !l.starts_with('#'))
                .map(|l| serde_json::Value::String(l.to_string()))
                .collect();
            let mut t = serde_json::to_string_pretty(&serde_json::json!({
                "model": s.model, "joints": s.joints, "steps": lines
            }))
            .map_err(|e| CliError::internal(e.to_string()))?;
            t.push('\n');
            t
        }
        _ => s.render(
            Style::Text {
                abbrev: !args.no_abbrev,
            },
            Collect::Config,
        ),
    };
    crate::output::write_stdout(&text)
}
