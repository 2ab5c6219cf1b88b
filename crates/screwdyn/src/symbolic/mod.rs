//! Symbolic equations of motion and code generation (issue 14).
//!
//! Textbooks derive `M(θ)`, `C(θ, θ̇)` and `g(θ)` by hand (Craig, *Introduction to Robotics*) or
//! with MATLAB's `syms` (Lynch & Park, *Modern Robotics*). This module produces them — and `τ(θ, θ̇, θ̈)`, `H_e^0(θ)`, Jacobians, energies
//! and the regressor `Y` — as expressions in the joint variables, with any of the robot's
//! parameters kept as symbols ([`ParamTable::select`]), and writes them as text, LaTeX, JSON or
//! code (C, Python, Rust, MATLAB).
//!
//! # Representation, and why not a general CAS
//!
//! Every joint transform `H_i^{λ(i)}(0) e^{[S_i]θ_i}` is linear in `cos θ_i` and `sin θ_i` (and
//! in `θ_i` for a prismatic or helical joint); the mechanics only multiplies and adds such
//! entries, the parameters and `θ̇`, `θ̈`. So every quantity is a *polynomial* in `c_i = cos θ_i`,
//! `s_i = sin θ_i`, `θ_j`, `θ̇`, `θ̈` and the parameters, and two representations suffice:
//!
//! - [`Poly`]: a sparse polynomial kept canonical by `s_i² → 1 − c_i²`. Canonical means two
//!   expressions are equal exactly when their forms are equal — no `simplify` needed, which is
//!   where a general CAS spends its minutes (the "expression swell" of MATLAB/SymPy on a 6-axis
//!   arm). Printing recombines angle sums (`c1 c2 − s1 s2 → c12`) and collects on the inertial
//!   parameters or on the configuration ([`Collect`]).
//! - [`Sx`]: an expression graph with hash-consing for code generation. Running the recursive
//!   algorithms on it shares every common subexpression by construction and never expands, so
//!   `τ` of a 7-axis arm is a few hundred operations produced in milliseconds.
//!
//! The mechanics ([`SymRobot`]) is written once over a small [`Ring`] trait and runs on both
//! (and on `f64`). An e-graph crate such as `egg` would find the same angle-sum rewrites but
//! pulls in a large dependency for what is a two-rule rewrite on a canonical form; the module
//! stays dependency-free.
//!
//! Numeric parameters are `f64` coefficients; values within `1e-12` of `0`, `±1` (e.g.
//! `cos(π/2)` of a DH twist) are made exact, and a coefficient that cancels to below `1e-12` of
//! the terms that produced it is round-off and dropped.
//!
//! ```
//! use screwdyn::{builtin, symbolic::{derive, Options, Quantity}};
//! let model = builtin::planar2();
//! let opts = Options { symbols: "all".into(), ..Options::default() };
//! let d = derive(&model, Quantity::MassMatrix, &opts).unwrap();
//! // Craig, *Introduction to Robotics*: M22 = m2 L2².
//! assert_eq!(d.entry_text(0, 1, 1), "m2 L2²");
//! ```

mod codegen;
pub mod dag;
mod lagrange;
mod mechanics;
mod params;
mod poly;
mod print;
mod render;
mod ring;

pub use codegen::{generate, CodeUnit, Language};
pub use dag::{Input, Sx};
pub use lagrange::{lagrange_steps, LagrangeSteps};
pub use mechanics::{SymRobot, Vars};
pub use params::{clean, Param, ParamKind, ParamTable};
pub use poly::{mono_mul, with_term_limit, Mono, Poly, Var};
pub use print::{recombine, Collect, Printer, Style};
pub use ring::{Inertia, Pose, Ring, Tw, M3, V3};

use crate::error::{Error, Result};
use crate::kinematics::Reference;
use crate::model::Model;

/// What to derive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// `M(θ)`.
    MassMatrix,
    /// `C(θ, θ̇)` and `C θ̇`.
    Coriolis,
    /// `g(θ)`.
    Gravity,
    /// `τ(θ, θ̇, θ̈)`.
    Torque,
    /// `H_f^0(θ)` of a frame.
    Fk,
    /// The 6×n Jacobian of a frame.
    Jacobian,
    /// Kinetic and potential energy.
    Energy,
    /// The regressor `Y(θ, θ̇, θ̈)`, `τ = Y π`.
    Regressor,
}

impl std::str::FromStr for Quantity {
    type Err = crate::Error;
    fn from_str(s: &str) -> std::result::Result<Self, crate::Error> {
        Ok(match crate::error::choice_key(s).as_str() {
            "mass-matrix" | "m" => Quantity::MassMatrix,
            "coriolis" | "c" => Quantity::Coriolis,
            "gravity" | "g" => Quantity::Gravity,
            "torque" | "tau" | "inverse-dynamics" => Quantity::Torque,
            "fk" => Quantity::Fk,
            "jacobian" => Quantity::Jacobian,
            "energy" => Quantity::Energy,
            "regressor" => Quantity::Regressor,
            _ => {
                return Err(crate::Error::UnknownChoice {
                    what: "quantity",
                    got: s.into(),
                    expected:
                        "mass-matrix, coriolis, gravity, torque, fk, jacobian, energy or regressor",
                })
            }
        })
    }
}

impl Quantity {
    /// The generated function's name.
    pub fn function_name(&self) -> &'static str {
        match self {
            Quantity::MassMatrix => "mass_matrix",
            Quantity::Coriolis => "coriolis_matrix",
            Quantity::Gravity => "gravity_torque",
            Quantity::Torque => "inverse_dynamics",
            Quantity::Fk => "forward_kinematics",
            Quantity::Jacobian => "jacobian",
            Quantity::Energy => "energy",
            Quantity::Regressor => "regressor",
        }
    }
    /// Which of `(q, v, a)` the quantity depends on.
    pub fn uses(&self) -> (bool, bool, bool) {
        match self {
            Quantity::Coriolis | Quantity::Energy => (true, true, false),
            Quantity::Torque | Quantity::Regressor => (true, true, true),
            _ => (true, false, false),
        }
    }
}

/// Which factorisation of the velocity terms `C θ̇` to give as `C`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum CoriolisForm {
    /// The stacked closed form's own `C = Sᵀ Lᵀ [−𝔍 L ad_{Sθ̇} A − ad_Vᵀ 𝔍] L S`.
    #[default]
    Seed,
    /// Christoffel symbols of the first kind, `C_ij = Σ_k ½(∂M_ij/∂θ_k + ∂M_ik/∂θ_j −
    /// ∂M_jk/∂θ_i) θ̇_k` (the Euler–Lagrange `D_ijk`), for which `Ṁ − 2C` is skew-symmetric.
    Christoffel,
}

impl std::str::FromStr for CoriolisForm {
    type Err = crate::Error;
    fn from_str(s: &str) -> std::result::Result<Self, crate::Error> {
        match crate::error::choice_key(s).as_str() {
            "seed" | "closed-form" => Ok(CoriolisForm::Seed),
            "christoffel" => Ok(CoriolisForm::Christoffel),
            _ => Err(crate::Error::UnknownChoice {
                what: "Coriolis form",
                got: s.into(),
                expected: "closed-form or christoffel",
            }),
        }
    }
}

/// Options of [`derive()`] and [`generate`].
#[derive(Clone, Debug)]
pub struct Options {
    /// The parameters kept as symbols (see [`ParamTable::select`]); `""` keeps all numeric.
    pub symbols: String,
    /// The frame for `fk` and `jacobian` (default: the last body's frame).
    pub frame: Option<String>,
    /// The Jacobian's reference frame.
    pub reference: Reference,
    /// Which `C`.
    pub coriolis: CoriolisForm,
    /// The largest number of terms one expanded expression may have ([`derive()`] only).
    pub max_terms: usize,
    /// The largest number of graph nodes code generation may build ([`generate`] only).
    pub max_ops: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            symbols: String::new(),
            frame: None,
            reference: Reference::Local,
            coriolis: CoriolisForm::Seed,
            max_terms: DEFAULT_MAX_TERMS,
            max_ops: DEFAULT_MAX_OPS,
        }
    }
}

/// The default of [`Options::max_terms`].
pub const DEFAULT_MAX_TERMS: usize = 20_000;
/// The default of [`Options::max_ops`].
pub const DEFAULT_MAX_OPS: usize = 2_000_000;
/// The largest model (joints) the polynomial form takes (angle bit masks are 64 bits).
pub const MAX_JOINTS: usize = 64;

/// A named matrix of canonical polynomials.
#[derive(Clone, Debug)]
pub struct SymMatrix {
    /// Printed name (`M`, `C`, `Cθ̇`, `g`, `τ`, `H`, `J`, `K`, `P`, `Y`).
    pub name: String,
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// Entries, row-major.
    pub entries: Vec<Poly>,
}

/// The result of [`derive()`]: the quantity's matrices and everything needed to print them.
#[derive(Clone, Debug)]
pub struct Derivation {
    /// Model name.
    pub model: String,
    /// Joint names in model order.
    pub joints: Vec<String>,
    /// What was derived.
    pub quantity: Quantity,
    /// The parameter table (which are symbols, and the numeric values of the others).
    pub params: ParamTable,
    /// The matrices (`C` and `C θ̇` for the Coriolis quantity, `K` and `P` for energy).
    pub matrices: Vec<SymMatrix>,
}

impl Derivation {
    /// Entry `(r, c)` of matrix `k` as text with abbreviations, collected on the inertial
    /// parameters.
    pub fn entry_text(&self, k: usize, r: usize, c: usize) -> String {
        let m = &self.matrices[k];
        Printer::new(
            &self.params,
            Style::Text { abbrev: true },
            Collect::Inertial,
        )
        .poly(&m.entries[r * m.cols + c])
    }
    /// Evaluates matrix `k` at a state, with the symbols at the model's values.
    pub fn eval(&self, k: usize, q: &[f64], v: &[f64], a: &[f64]) -> Vec<f64> {
        let value = |x: Var| match x {
            Var::Param(i) => self.params.params[usize::from(i)].value,
            Var::Cos(mask) => angle(mask, q).cos(),
            Var::Sin(mask) => angle(mask, q).sin(),
            Var::Q(i) => q[usize::from(i)],
            Var::Qd(i) => v[usize::from(i)],
            Var::Qdd(i) => a[usize::from(i)],
        };
        self.matrices[k]
            .entries
            .iter()
            .map(|p| p.eval(&value))
            .collect()
    }
}

fn angle(mask: u64, q: &[f64]) -> f64 {
    (0..64).filter(|b| mask & (1 << b) != 0).map(|b| q[b]).sum()
}

/// The polynomial variables: `c_i`, `s_i`, `θ_i`, `θ̇_i`, `θ̈_i`, and each parameter as a symbol
/// or its value.
pub fn poly_vars(n: usize, table: &ParamTable) -> Vars<Poly> {
    let v = |f: fn(u16) -> Var| (0..n).map(|i| Poly::var(f(i as u16))).collect::<Vec<_>>();
    Vars {
        c: (0..n).map(|i| Poly::var(Var::Cos(1 << i))).collect(),
        s: (0..n).map(|i| Poly::var(Var::Sin(1 << i))).collect(),
        q: v(Var::Q),
        qd: v(Var::Qd),
        qdd: v(Var::Qdd),
        p: table
            .params
            .iter()
            .enumerate()
            .map(|(k, p)| {
                if p.symbolic {
                    Poly::var(Var::Param(k as u16))
                } else {
                    Poly::constant(p.value)
                }
            })
            .collect(),
    }
}

/// The frame for `fk`/`jacobian`: `(name, body, placement)`.
pub(crate) fn pick_frame(model: &Model, frame: Option<&str>) -> Result<(String, usize)> {
    let id = match frame {
        Some(f) => model.frame_id(f)?,
        None => model.body_frame(model.nbodies() - 1)?,
    };
    let f = &model.frames()[id];
    if f.body.is_none() {
        return Err(Error::InvalidArgument(format!(
            "frame '{}' is the fixed base: its pose and Jacobian are constant (pick a frame on a \
             moving body)",
            f.name
        )));
    }
    Ok((f.name.clone(), id))
}

pub(crate) fn check_model(model: &Model) -> Result<()> {
    if model.nq() == 0 {
        return Err(Error::InvalidArgument(
            "the model has no moving joints: nothing to derive".into(),
        ));
    }
    Ok(())
}

/// Derives `quantity` in canonical polynomial form.
///
/// The expanded polynomial of a large model can be huge (`τ` of a 6-axis arm has hundreds of
/// thousands of terms); a polynomial that grows past `options.max_terms` stops the derivation
/// with an error naming the limit. Code formats ([`generate`]) do not expand and have no such
/// limit.
///
/// ```
/// use screwdyn::{builtin, symbolic::{derive, Options, Quantity}};
/// let opts = Options { symbols: "all".into(), ..Options::default() };
/// let g = derive(&builtin::planar2(), Quantity::Gravity, &opts).unwrap();
/// // Craig, *Introduction to Robotics*: G2 = m2 g L2 c12.
/// assert_eq!(g.entry_text(0, 1, 0), "m2 g L2 c₁₂");
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for an unknown symbol or frame, a model without joints or with more
/// than [`MAX_JOINTS`], or an expression past `options.max_terms`.
pub fn derive(model: &Model, quantity: Quantity, options: &Options) -> Result<Derivation> {
    check_model(model)?;
    let n = model.nq();
    if n > MAX_JOINTS {
        return Err(Error::InvalidArgument(format!(
            "the model has {n} joints; the expanded symbolic form takes at most {MAX_JOINTS} \
             (use a code format, which has no such limit)"
        )));
    }
    let mut table = ParamTable::new(model);
    table.select(&options.symbols)?;
    let frame = match quantity {
        Quantity::Fk | Quantity::Jacobian => Some(pick_frame(model, options.frame.as_deref())?),
        _ => None,
    };
    let vars = poly_vars(n, &table);
    let robot = SymRobot::new(model, &table, &vars);
    let square = |name: &str, e: Vec<Poly>, rows: usize, cols: usize| SymMatrix {
        name: name.into(),
        rows,
        cols,
        entries: e,
    };
    let matrices = with_term_limit(options.max_terms, || -> Vec<SymMatrix> {
        match quantity {
            Quantity::MassMatrix => vec![square("M", robot.mass_matrix(), n, n)],
            Quantity::Coriolis => {
                let c = match options.coriolis {
                    CoriolisForm::Seed => robot.coriolis_seed(&vars.qd),
                    CoriolisForm::Christoffel => christoffel(&robot.mass_matrix(), n),
                };
                let cv = (0..n)
                    .map(|i| {
                        (0..n).fold(Poly::zero(), |s, j| s.add(&c[i * n + j].mul(&vars.qd[j])))
                    })
                    .collect();
                vec![square("C", c, n, n), square("Cθ̇", cv, n, 1)]
            }
            Quantity::Gravity => vec![square("g", robot.gravity_torque(), n, 1)],
            Quantity::Torque => vec![square(
                "τ",
                robot.inverse_dynamics(&vars.qd, &vars.qdd),
                n,
                1,
            )],
            Quantity::Energy => vec![
                square("K", vec![robot.kinetic_energy(&vars.qd)], 1, 1),
                square("P", vec![robot.potential_energy()], 1, 1),
            ],
            Quantity::Regressor => {
                vec![square("Y", robot.regressor(&vars.qd, &vars.qdd), n, 10 * n)]
            }
            Quantity::Fk => {
                let (_, id) = frame.clone().expect("picked above");
                let h = frame_pose_in(&robot, model, id);
                let mut e: Vec<Poly> = Vec::with_capacity(16);
                for r in 0..3 {
                    e.extend(h.r.0[r].iter().cloned());
                    e.push(h.p.0[r].clone());
                }
                e.extend([0.0, 0.0, 0.0, 1.0].map(Poly::constant));
                vec![square("H", e, 4, 4)]
            }
            Quantity::Jacobian => {
                let (_, id) = frame.clone().expect("picked above");
                let f = &model.frames()[id];
                let placement = pose_const(&f.placement);
                let body = f.body.expect("checked by pick_frame");
                vec![square(
                    "J",
                    robot.frame_jacobian(body, &placement, options.reference),
                    6,
                    n,
                )]
            }
        }
    })
    .ok_or_else(|| {
        Error::InvalidArgument(format!(
            "the expanded {} of '{}' has more than {} terms in one expression (the max-terms \
             limit); raise it (--max-terms) or generate code (--format c, rust, python or \
             matlab), which does not expand",
            quantity.function_name().replace('_', " "),
            model.name(),
            options.max_terms
        ))
    })?;
    Ok(Derivation {
        model: model.name().to_string(),
        joints: model.joint_names().iter().map(|s| s.to_string()).collect(),
        quantity,
        params: table,
        matrices,
    })
}

/// A numeric pose as ring constants.
pub(crate) fn pose_const<R: Ring>(h: &crate::spatial::Se3) -> Pose<R> {
    Pose {
        r: M3::constant([0, 1, 2].map(|i| [0, 1, 2].map(|j| clean(h.rotation[(i, j)])))),
        p: V3::constant([0, 1, 2].map(|i| clean(h.translation[i]))),
    }
}

pub(crate) fn frame_pose_in<R: Ring>(robot: &SymRobot<R>, model: &Model, frame: usize) -> Pose<R> {
    let f = &model.frames()[frame];
    let body = f.body.expect("checked by pick_frame");
    robot.world_poses()[body].compose(&pose_const(&f.placement))
}

/// The Christoffel-form `C` from `M` (row-major):
/// `C_ij = Σ_k ½ (∂M_ij/∂θ_k + ∂M_ik/∂θ_j − ∂M_jk/∂θ_i) θ̇_k`.
pub fn christoffel(m: &[Poly], n: usize) -> Vec<Poly> {
    let dm: Vec<Vec<Poly>> = (0..n)
        .map(|k| m.iter().map(|e| e.diff_angle(k)).collect())
        .collect();
    let mut c = vec![Poly::zero(); n * n];
    for i in 0..n {
        for j in 0..n {
            let mut s = Poly::zero();
            for k in 0..n {
                let g = dm[k][i * n + j]
                    .add(&dm[j][i * n + k])
                    .sub(&dm[i][j * n + k])
                    .scale(0.5);
                s = s.add(&g.mul(&Poly::var(Var::Qd(k as u16))));
            }
            c[i * n + j] = s;
        }
    }
    c
}
