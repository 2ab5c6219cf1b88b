//! Code generation: one function per quantity, straight-line code from the expression graph
//! (common subexpressions computed once), in C, Python, Rust or MATLAB.
//!
//! Calling convention (the same in every language): the function is named after the quantity
//! (`mass_matrix`, `coriolis_matrix`, `gravity_torque`, `inverse_dynamics`,
//! `forward_kinematics`, `jacobian`, `energy`, `regressor`) and takes the joint vectors it needs
//! in the order `q, v, a` (model joint order), then the symbolic parameters — Python as keyword
//! arguments, C, Rust and MATLAB as one `params` array in the order the header lists. The result
//! is row-major: C writes it into a last `double *out` argument, Python returns nested lists,
//! Rust a nested array, MATLAB a matrix.

use super::dag::{self, Graph, Input, Op, Sx};
use super::mechanics::{SymRobot, Vars};
use super::params::ParamTable;
use super::{check_model, christoffel, derive, frame_pose_in, pick_frame, pose_const};
use super::{CoriolisForm, Options, Quantity};
use crate::error::{Error, Result};
use crate::model::Model;
use std::fmt::Write;

/// A target language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Language {
    /// C99 (`#include <math.h>`).
    C,
    /// Python 3 (`import math`).
    Python,
    /// Rust.
    Rust,
    /// MATLAB / Octave.
    Matlab,
}

/// A quantity as an expression graph, ready to be written as code.
#[derive(Clone, Debug)]
pub struct CodeUnit {
    /// Model name.
    pub model: String,
    /// Joint names in model order.
    pub joints: Vec<String>,
    /// The quantity.
    pub quantity: Quantity,
    /// Parameters (the symbolic ones become arguments).
    pub params: ParamTable,
    /// The graph.
    pub graph: Graph,
    /// The outputs, row-major.
    pub outputs: Vec<Sx>,
    /// Result rows.
    pub rows: usize,
    /// Result columns.
    pub cols: usize,
    /// What the result is, for the header comment.
    pub description: String,
}

fn graph_vars(g: &Graph, n: usize, table: &ParamTable) -> Vars<Sx> {
    let inp = |f: fn(u16) -> Input| {
        (0..n)
            .map(|i| Sx::node(g, Op::In(f(i as u16))))
            .collect::<Vec<_>>()
    };
    Vars {
        c: (0..n).map(|i| Sx::node(g, Op::Cos(i as u16))).collect(),
        s: (0..n).map(|i| Sx::node(g, Op::Sin(i as u16))).collect(),
        q: inp(Input::Q),
        qd: inp(Input::V),
        qdd: inp(Input::A),
        p: table
            .params
            .iter()
            .enumerate()
            .map(|(k, p)| {
                if p.symbolic {
                    Sx::node(g, Op::In(Input::Param(k as u16)))
                } else {
                    Sx::C(p.value)
                }
            })
            .collect(),
    }
}

/// Builds `quantity` as an expression graph by running the recursions on graph values
/// (nothing is expanded; `C` in the Christoffel form goes through the polynomial form of `M`).
///
/// ```
/// use screwdyn::{builtin, symbolic::{generate, Language, Options, Quantity}};
/// let unit = generate(&builtin::load("ur5").unwrap(),
///                     Quantity::Torque, &Options::default()).unwrap();
/// let c = unit.emit(Language::C);
/// assert!(c.contains("void inverse_dynamics(const double *q, const double *v, const double *a, double *out)"));
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for an unknown symbol or frame or a model without joints.
pub fn generate(model: &Model, quantity: Quantity, options: &Options) -> Result<CodeUnit> {
    check_model(model)?;
    let mut table = ParamTable::new(model);
    table.select(&options.symbols)?;
    let g: Graph = Default::default();
    let built = dag::with_node_limit(options.max_ops, || {
        build(model, quantity, options, &g, &table)
    });
    let (outputs, rows, cols, description) = built.ok_or_else(|| {
        Error::InvalidArgument(format!(
            "the generated {} of '{}' needs more than {} operations (the max-ops limit); raise \
             it (--max-ops) if the machine has the memory",
            quantity.function_name().replace('_', " "),
            model.name(),
            options.max_ops
        ))
    })??;
    Ok(CodeUnit {
        model: model.name().to_string(),
        joints: model.joint_names().iter().map(|s| s.to_string()).collect(),
        quantity,
        params: table,
        graph: g,
        outputs,
        rows,
        cols,
        description,
    })
}

type Built = (Vec<Sx>, usize, usize, String);

fn build(
    model: &Model,
    quantity: Quantity,
    options: &Options,
    g: &Graph,
    table: &ParamTable,
) -> Result<Built> {
    let n = model.nq();
    let g = g.clone();
    let vars = graph_vars(&g, n, table);
    let robot = SymRobot::new(model, table, &vars);
    Ok(match quantity {
        Quantity::MassMatrix => (robot.mass_matrix(), n, n, "M(q), n×n".to_string()),
        Quantity::Coriolis => {
            let c = match options.coriolis {
                CoriolisForm::Seed => robot.coriolis_seed(&vars.qd),
                CoriolisForm::Christoffel => {
                    let d = derive(model, Quantity::MassMatrix, options)?;
                    christoffel(&d.matrices[0].entries, n)
                        .iter()
                        .map(|p| dag::from_poly(&g, p))
                        .collect()
                }
            };
            let form = match options.coriolis {
                CoriolisForm::Seed => "the closed form",
                CoriolisForm::Christoffel => "Christoffel form",
            };
            (c, n, n, format!("C(q, v), n×n ({form})"))
        }
        Quantity::Gravity => (robot.gravity_torque(), n, 1, "g(q), n".into()),
        Quantity::Torque => (
            robot.inverse_dynamics(&vars.qd, &vars.qdd),
            n,
            1,
            "tau = M(q) a + C(q, v) v + g(q), n".into(),
        ),
        Quantity::Energy => (
            vec![robot.kinetic_energy(&vars.qd), robot.potential_energy()],
            2,
            1,
            "[kinetic energy, potential energy]".into(),
        ),
        Quantity::Regressor => (
            robot.regressor(&vars.qd, &vars.qdd),
            n,
            10 * n,
            "Y(q, v, a), n×10n, tau = Y pi with pi = per body (m, m cx, m cy, m cz, Ixx, Ixy, \
             Ixz, Iyy, Iyz, Izz) about the body frame origin"
                .into(),
        ),
        Quantity::Fk => {
            let (name, id) = pick_frame(model, options.frame.as_deref())?;
            let h = frame_pose_in(&robot, model, id);
            let mut e = Vec::with_capacity(16);
            for r in 0..3 {
                e.extend(h.r.0[r].iter().cloned());
                e.push(h.p.0[r].clone());
            }
            e.extend([0.0, 0.0, 0.0, 1.0].map(Sx::C));
            (e, 4, 4, format!("H_{name}^0(q), 4×4 homogeneous transform"))
        }
        Quantity::Jacobian => {
            let (name, id) = pick_frame(model, options.frame.as_deref())?;
            let f = &model.frames()[id];
            let body = f
                .body
                .ok_or_else(|| Error::InvalidArgument("base frame".into()))?;
            let j = robot.frame_jacobian(body, &pose_const(&f.placement), options.reference);
            (
                j,
                6,
                n,
                format!(
                    "Jacobian of frame {name} ({:?} reference), 6×n, angular rows first",
                    options.reference
                ),
            )
        }
    })
}

fn literal(x: f64) -> String {
    let s = format!("{x:?}");
    if x < 0.0 {
        format!("({s})")
    } else {
        s
    }
}

impl CodeUnit {
    /// The number of arithmetic operations (`+ − × neg`, `sin`, `cos`) after elimination of
    /// common subexpressions.
    pub fn op_count(&self) -> usize {
        dag::op_count(&self.graph, &self.outputs)
    }

    /// Evaluates the graph at a state (symbols at `params`, in [`CodeUnit::param_names`] order).
    pub fn eval(&self, q: &[f64], v: &[f64], a: &[f64], params: &[f64]) -> Vec<f64> {
        let pos = self.param_positions();
        dag::eval(&self.graph, &self.outputs, &|i| match i {
            Input::Q(k) => q[usize::from(k)],
            Input::V(k) => v[usize::from(k)],
            Input::A(k) => a[usize::from(k)],
            Input::Param(k) => params[pos[usize::from(k)]],
        })
    }

    /// The symbolic parameters' names, in argument order.
    pub fn param_names(&self) -> Vec<String> {
        self.params
            .symbols()
            .iter()
            .map(|(_, p)| p.name.clone())
            .collect()
    }

    /// The symbolic parameters' model values, in argument order.
    pub fn param_values(&self) -> Vec<f64> {
        self.params.symbols().iter().map(|(_, p)| p.value).collect()
    }

    /// Table index → argument position.
    fn param_positions(&self) -> Vec<usize> {
        let mut pos = vec![usize::MAX; self.params.params.len()];
        for (k, (i, _)) in self.params.symbols().iter().enumerate() {
            pos[*i] = k;
        }
        pos
    }

    fn header(&self, comment: &str) -> String {
        let (uq, uv, ua) = self.quantity.uses();
        let mut args: Vec<&str> = Vec::new();
        if uq {
            args.push("q");
        }
        if uv {
            args.push("v");
        }
        if ua {
            args.push("a");
        }
        let mut h = String::new();
        let mut line = |s: String| {
            let _ = writeln!(h, "{comment} {s}").map(|_| ());
        };
        line(format!(
            "{}: {} of model '{}', generated by screwdyn symbolic.",
            self.quantity.function_name(),
            self.description,
            self.model
        ));
        line(format!(
            "Joint order (q, v, a index 0..{}): {}.",
            self.joints.len(),
            self.joints.join(", ")
        ));
        line(format!(
            "Arguments: {}{}; result row-major, {}×{}.",
            args.join(", "),
            if self.params.symbols().is_empty() {
                String::new()
            } else {
                ", then the parameters".into()
            },
            self.rows,
            self.cols
        ));
        line(
            "Convention: twists and wrenches angular first (docs/notation.md), SI units, radians; \
             gravity from the model."
                .into(),
        );
        let syms = self.params.symbols();
        if !syms.is_empty() {
            line("Parameters (in order; the model's value in brackets):".into());
            for (k, (_, p)) in syms.iter().enumerate() {
                line(format!("  [{k}] {} = {} ({})", p.name, p.value, p.meaning));
            }
        }
        line(format!(
            "{} operations after common-subexpression elimination.",
            self.op_count()
        ));
        h
    }

    /// The code in `lang`.
    pub fn emit(&self, lang: Language) -> String {
        let nodes = self.graph.borrow().nodes.clone();
        let names = self.param_names();
        let spelling = Spelling {
            lang,
            nodes: &nodes,
            param_positions: self.param_positions(),
            param_names: &names,
        };
        // One assignment per live intermediate node, in evaluation order.
        let mut body = String::new();
        for id in dag::live_nodes(&self.graph, &self.outputs) {
            if let Some(statement) = spelling.statement(id) {
                let _ = writeln!(body, "{INDENT}{statement}");
            }
        }
        let args = self.arguments(lang, &names).join(", ");
        let fname = self.quantity.function_name();
        match lang {
            Language::C => self.emit_c(&spelling, fname, &args, &body),
            Language::Python => self.emit_python(&spelling, fname, &args, &body),
            Language::Rust => self.emit_rust(&spelling, fname, &args, &body),
            Language::Matlab => self.emit_matlab(&spelling, fname, &args, &body),
        }
    }

    /// The function's parameters in `lang`: the used state vectors, then the parameters (and
    /// in C the output array).
    fn arguments(&self, lang: Language, names: &[String]) -> Vec<String> {
        let (uq, uv, ua) = self.quantity.uses();
        let n = self.joints.len();
        let mut args: Vec<String> = [(uq, "q"), (uv, "v"), (ua, "a")]
            .into_iter()
            .filter(|(used, _)| *used)
            .map(|(_, name)| match lang {
                Language::C => format!("const double *{name}"),
                Language::Rust => format!("{name}: &[f64; {n}]"),
                Language::Python | Language::Matlab => name.to_string(),
            })
            .collect();
        if !names.is_empty() {
            match lang {
                Language::C => args.push("const double *params".into()),
                Language::Rust => args.push(format!("params: &[f64; {}]", names.len())),
                Language::Matlab => args.push("params".into()),
                // Python takes the parameters by name, after the state vectors.
                Language::Python => {
                    args.push("*".into());
                    args.extend(names.iter().cloned());
                }
            }
        }
        if lang == Language::C {
            args.push("double *out".into());
        }
        args
    }

    /// The outputs as nested row lists, `[[M11, M12], [M21, M22]]` (Python and Rust).
    fn nested_rows(&self, spelling: &Spelling) -> String {
        let rows: Vec<String> = (0..self.rows)
            .map(|r| {
                let cols: Vec<String> = (0..self.cols)
                    .map(|c| spelling.output(&self.outputs[r * self.cols + c]))
                    .collect();
                format!("[{}]", cols.join(", "))
            })
            .collect();
        format!("[{}]", rows.join(", "))
    }

    /// C: `void f(const double *q, …, double *out)` filling `out` row by row.
    fn emit_c(&self, spelling: &Spelling, fname: &str, args: &str, body: &str) -> String {
        let mut s = self.header("//");
        s.push_str("#include <math.h>\n\n");
        let _ = writeln!(s, "void {fname}({args}) {{");
        s.push_str(body);
        for (k, o) in self.outputs.iter().enumerate() {
            let _ = writeln!(s, "{INDENT}out[{k}] = {};", spelling.output(o));
        }
        s.push_str("}\n");
        s
    }

    /// Python: `def f(q, …, *, params…)` returning nested lists.
    fn emit_python(&self, spelling: &Spelling, fname: &str, args: &str, body: &str) -> String {
        let mut s = self.header("#");
        s.push_str("import math\n\n\n");
        let _ = writeln!(s, "def {fname}({args}):");
        s.push_str(body);
        let _ = writeln!(s, "{INDENT}return {}", self.nested_rows(spelling));
        s
    }

    /// Rust: `pub fn f(q: &[f64; n], …) -> [[f64; cols]; rows]`.
    fn emit_rust(&self, spelling: &Spelling, fname: &str, args: &str, body: &str) -> String {
        let mut s = self.header("//");
        let _ = writeln!(
            s,
            "#[allow(clippy::all, unused_parens)]\npub fn {fname}({args}) -> [[f64; {}]; {}] {{",
            self.cols, self.rows
        );
        s.push_str(body);
        let _ = writeln!(s, "{INDENT}{}\n}}", self.nested_rows(spelling));
        s
    }

    /// MATLAB/Octave: `function out = f(q, …)` filling a rows × cols matrix, 1-based.
    fn emit_matlab(&self, spelling: &Spelling, fname: &str, args: &str, body: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "function out = {fname}({args})");
        s.push_str(&self.header("%"));
        s.push_str(body);
        let _ = writeln!(s, "{INDENT}out = zeros({}, {});", self.rows, self.cols);
        for r in 0..self.rows {
            for c in 0..self.cols {
                let value = spelling.output(&self.outputs[r * self.cols + c]);
                let _ = writeln!(s, "{INDENT}out({}, {}) = {value};", r + 1, c + 1);
            }
        }
        s.push_str("end\n");
        s
    }
}

/// The indentation of a generated function's body.
const INDENT: &str = "    ";

/// How one language spells the pieces of the expression graph: array elements, operands,
/// outputs and the assignment of an intermediate node.
struct Spelling<'a> {
    lang: Language,
    nodes: &'a [Op],
    /// The position of each parameter in the emitted parameter list.
    param_positions: Vec<usize>,
    param_names: &'a [String],
}

impl Spelling<'_> {
    /// `arr[k]`, or `arr(k + 1)` in MATLAB.
    fn index(&self, arr: &str, k: usize) -> String {
        if self.lang == Language::Matlab {
            format!("{arr}({})", k + 1)
        } else {
            format!("{arr}[{k}]")
        }
    }

    /// A node used as an operand: a literal, an input element or an intermediate `x<id>`.
    fn operand(&self, id: u32) -> String {
        match self.nodes[id as usize] {
            Op::Const(b) => literal(f64::from_bits(b)),
            Op::In(Input::Q(k)) => self.index("q", usize::from(k)),
            Op::In(Input::V(k)) => self.index("v", usize::from(k)),
            Op::In(Input::A(k)) => self.index("a", usize::from(k)),
            Op::In(Input::Param(k)) => {
                let p = self.param_positions[usize::from(k)];
                if self.lang == Language::Python {
                    self.param_names[p].clone()
                } else {
                    self.index("params", p)
                }
            }
            _ => format!("x{id}"),
        }
    }

    /// An output entry: a constant or a node.
    fn output(&self, o: &Sx) -> String {
        match o {
            Sx::C(c) => literal(*c),
            Sx::N(_, id) => self.operand(*id),
        }
    }

    /// The assignment `x<id> = …` of an intermediate node; `None` for constants and inputs.
    fn statement(&self, id: u32) -> Option<String> {
        let rhs = match self.nodes[id as usize] {
            Op::Const(_) | Op::In(_) => return None,
            Op::Cos(k) | Op::Sin(k) => {
                let q = self.index("q", usize::from(k));
                let f = if matches!(self.nodes[id as usize], Op::Cos(_)) {
                    "cos"
                } else {
                    "sin"
                };
                match self.lang {
                    Language::Rust => format!("{q}.{f}()"),
                    Language::Python => format!("math.{f}({q})"),
                    Language::C | Language::Matlab => format!("{f}({q})"),
                }
            }
            Op::Add(a, b) => format!("{} + {}", self.operand(a), self.operand(b)),
            Op::Sub(a, b) => format!("{} - {}", self.operand(a), self.operand(b)),
            Op::Mul(a, b) => format!("{} * {}", self.operand(a), self.operand(b)),
            Op::Neg(a) => format!("-{}", self.operand(a)),
        };
        Some(match self.lang {
            Language::C => format!("const double x{id} = {rhs};"),
            Language::Python => format!("x{id} = {rhs}"),
            Language::Rust => format!("let x{id}: f64 = {rhs};"),
            Language::Matlab => format!("x{id} = {rhs};"),
        })
    }
}
