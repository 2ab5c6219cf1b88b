//! The Lagrangian steps in symbols: `L = K − P`, `∂L/∂θ̇_i`, `d/dt(∂L/∂θ̇_i)`, `∂L/∂θ_i`
//! and `τ_i = d/dt(∂L/∂θ̇_i) − ∂L/∂θ_i`.

use super::params::ParamTable;
use super::print::{Collect, Printer, Style};
use super::{derive, Options, Poly, Quantity, Var};
use crate::error::Result;
use crate::model::Model;

/// The intermediate expressions of the Euler–Lagrange equations.
#[derive(Clone, Debug)]
pub struct LagrangeSteps {
    /// Model name.
    pub model: String,
    /// Joint names.
    pub joints: Vec<String>,
    /// The parameters (which are symbols).
    pub params: ParamTable,
    /// `K(θ, θ̇)`.
    pub kinetic: Poly,
    /// `P(θ)`.
    pub potential: Poly,
    /// `∂L/∂θ̇_i`.
    pub dl_dqd: Vec<Poly>,
    /// `d/dt (∂L/∂θ̇_i)`.
    pub ddt_dl_dqd: Vec<Poly>,
    /// `∂L/∂θ_i`.
    pub dl_dq: Vec<Poly>,
    /// `τ_i = d/dt(∂L/∂θ̇_i) − ∂L/∂θ_i`.
    pub tau: Vec<Poly>,
}

/// Derives the steps from the symbolic energies: `L = K − P`, then `∂L/∂θ̇_i`, its time
/// derivative along the motion (`Σ_j ∂/∂θ_j θ̇_j + ∂/∂θ̇_j θ̈_j`), `∂L/∂θ_i` and `τ_i`.
///
/// ```
/// use screwdyn::{builtin, symbolic::{lagrange_steps, derive, Options, Quantity}};
/// let o = Options { symbols: "all".into(), ..Options::default() };
/// let s = lagrange_steps(&builtin::planar2(), &o).unwrap();
/// // The Euler–Lagrange τ is the Newton–Euler τ, symbol for symbol.
/// let t = derive(&builtin::planar2(), Quantity::Torque, &o).unwrap();
/// assert_eq!(s.tau[1], t.matrices[0].entries[1]);
/// ```
///
/// # Errors
/// As [`derive()`].
pub fn lagrange_steps(model: &Model, options: &Options) -> Result<LagrangeSteps> {
    let e = derive(model, Quantity::Energy, options)?;
    let (k, p) = (
        e.matrices[0].entries[0].clone(),
        e.matrices[1].entries[0].clone(),
    );
    let l = k.sub(&p);
    let n = model.nq();
    let dl_dqd: Vec<Poly> = (0..n).map(|i| l.diff_var(Var::Qd(i as u16))).collect();
    let ddt_dl_dqd: Vec<Poly> = dl_dqd.iter().map(|x| x.time_derivative(n)).collect();
    let dl_dq: Vec<Poly> = (0..n).map(|i| l.diff_angle(i)).collect();
    let tau = (0..n).map(|i| ddt_dl_dqd[i].sub(&dl_dq[i])).collect();
    Ok(LagrangeSteps {
        model: e.model,
        joints: e.joints,
        params: e.params,
        kinetic: k,
        potential: p,
        dl_dqd,
        ddt_dl_dqd,
        dl_dq,
        tau,
    })
}

impl LagrangeSteps {
    /// The steps as text (or plain ASCII with `style = Style::Ascii`), one line each.
    pub fn render(&self, style: Style, collect: Collect) -> String {
        let p = Printer::new(&self.params, style, collect);
        let ascii = style == Style::Ascii;
        let d = if ascii { "d" } else { "∂" };
        let (th, thd) = if ascii { ("q", "qd") } else { ("θ", "θ̇") };
        let mut out = format!(
            "# Euler–Lagrange steps for {}: L = K − P, τ_i = d/dt(∂L/∂θ̇_i) − ∂L/∂θ_i\n",
            self.model
        );
        let syms: Vec<String> = self
            .params
            .symbols()
            .iter()
            .map(|(_, s)| format!("{} = {}", s.name, s.value))
            .collect();
        if !syms.is_empty() {
            out.push_str(&format!("# symbols (model value): {}\n", syms.join(", ")));
        }
        out.push_str(&format!("K = {}\n", p.poly(&self.kinetic)));
        out.push_str(&format!("P = {}\n", p.poly(&self.potential)));
        for i in 0..self.tau.len() {
            let k = i + 1;
            out.push_str(&format!("{d}L/{d}{thd}{k} = {}\n", p.poly(&self.dl_dqd[i])));
            out.push_str(&format!(
                "d/dt({d}L/{d}{thd}{k}) = {}\n",
                p.poly(&self.ddt_dl_dqd[i])
            ));
            out.push_str(&format!("{d}L/{d}{th}{k} = {}\n", p.poly(&self.dl_dq[i])));
            let t = if ascii { "tau" } else { "τ" };
            out.push_str(&format!("{t}{k} = {}\n", p.poly(&self.tau[i])));
        }
        let legend = p.legend();
        if !legend.is_empty() {
            out.push_str(&format!("where {}\n", legend.join(", ")));
        }
        out
    }
}
