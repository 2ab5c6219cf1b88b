//! Whole derivations as documents: text like the notes, LaTeX, JSON.

use super::print::{latex_name, Collect, Printer, Style};
use super::{Derivation, Quantity};
use serde_json::{json, Map, Value};

fn title(q: Quantity) -> &'static str {
    match q {
        Quantity::MassMatrix => "mass matrix M(θ)",
        Quantity::Coriolis => "Coriolis/centrifugal matrix C(θ, θ̇) and C(θ, θ̇) θ̇",
        Quantity::Gravity => "gravity torques g(θ)",
        Quantity::Torque => "inverse dynamics τ = M(θ) θ̈ + C(θ, θ̇) θ̇ + g(θ)",
        Quantity::Fk => "forward kinematics H(θ)",
        Quantity::Jacobian => "Jacobian J(θ) (angular rows first)",
        Quantity::Energy => "kinetic energy K(θ, θ̇) and potential energy P(θ)",
        Quantity::Regressor => "regressor Y(θ, θ̇, θ̈), τ = Y π",
    }
}

fn label(name: &str, rows: usize, cols: usize, r: usize, c: usize, latex: bool) -> String {
    let big = rows >= 10 || cols >= 10;
    let idx = if rows == 1 && cols == 1 {
        String::new()
    } else if cols == 1 || rows == 1 {
        format!("{}", if cols == 1 { r + 1 } else { c + 1 })
    } else if big {
        format!("{},{}", r + 1, c + 1)
    } else {
        format!("{}{}", r + 1, c + 1)
    };
    let base = match (name, latex) {
        ("Cθ̇", false) => "(C θ̇)".to_string(),
        ("Cθ̇", true) => "(C\\dot{\\theta})".to_string(),
        ("τ", true) => "\\tau".to_string(),
        (n, _) => n.to_string(),
    };
    match (latex, idx.is_empty(), big) {
        (_, true, _) => base,
        (true, false, _) => format!("{base}_{{{idx}}}"),
        (false, false, true) => format!("{base}[{idx}]"),
        (false, false, false) => format!("{base}{idx}"),
    }
}

impl Derivation {
    fn symbol_lines(&self) -> Vec<String> {
        self.params
            .symbols()
            .iter()
            .map(|(_, p)| format!("{} = {} ({})", p.name, p.value, p.meaning))
            .collect()
    }

    /// The derivation as text like the notes: a header (model, joints, symbols with their model
    /// values), one line per entry (`M11 = m1 L1² + m2 (L1² + 2 L1 L2 c₂ + L2²)`) and the legend
    /// of abbreviations (`c₁₂ = cos(θ₁ + θ₂)`).
    pub fn render_text(&self, abbrev: bool, collect: Collect) -> String {
        let p = Printer::new(&self.params, Style::Text { abbrev }, collect);
        let mut out = format!("# {} of {}\n", title(self.quantity), self.model);
        let joints: Vec<String> = self
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| format!("θ{} = {j}", i + 1))
            .collect();
        out.push_str(&format!("# joints: {}\n", joints.join(", ")));
        let syms = self.symbol_lines();
        if syms.is_empty() {
            out.push_str("# all parameters numeric (the model's values; --symbols to keep some)\n");
        } else {
            out.push_str(&format!("# symbols (model value): {}\n", syms.join("; ")));
        }
        let terms: usize = self
            .matrices
            .iter()
            .flat_map(|m| m.entries.iter().map(|e| e.len()))
            .sum();
        out.push_str(&format!("# expanded form: {terms} terms in all\n"));
        for m in &self.matrices {
            for r in 0..m.rows {
                for c in 0..m.cols {
                    let e = &m.entries[r * m.cols + c];
                    out.push_str(&format!(
                        "{} = {}\n",
                        label(&m.name, m.rows, m.cols, r, c, false),
                        p.poly(e)
                    ));
                }
            }
        }
        let legend = p.legend();
        if !legend.is_empty() {
            out.push_str(&format!("where {}\n", legend.join(", ")));
        }
        out
    }

    /// The derivation as a LaTeX `aligned` block with the legend in a comment.
    pub fn render_latex(&self, abbrev: bool, collect: Collect) -> String {
        let p = Printer::new(&self.params, Style::Latex { abbrev }, collect);
        let mut out = format!(
            "% {} of {} (joints: {})\n",
            title(self.quantity),
            self.model,
            self.joints.join(", ")
        );
        for (_, s) in self.params.symbols() {
            out.push_str(&format!(
                "% {} = {} ({})\n",
                latex_name(&s.name),
                s.value,
                s.meaning
            ));
        }
        out.push_str("\\begin{aligned}\n");
        let mut lines = Vec::new();
        for m in &self.matrices {
            for r in 0..m.rows {
                for c in 0..m.cols {
                    lines.push(format!(
                        "{} &= {}",
                        label(&m.name, m.rows, m.cols, r, c, true),
                        p.poly(&m.entries[r * m.cols + c])
                    ));
                }
            }
        }
        out.push_str(&lines.join(" \\\\\n"));
        out.push_str("\n\\end{aligned}\n");
        let legend = p.legend();
        if !legend.is_empty() {
            out.push_str(&format!("% where {}\n", legend.join(", ")));
        }
        out
    }

    /// The derivation as JSON: `model`, `quantity`, `joints`, `variables` (`q1` → joint name),
    /// `symbols` (name → value, meaning) and, per matrix, a list of rows of SymPy-parsable
    /// expressions in `q1, qd1, qdd1` and the symbol names.
    pub fn render_json(&self) -> Value {
        let p = Printer::new(&self.params, Style::Ascii, Collect::Inertial);
        let mut mats = Map::new();
        for m in &self.matrices {
            let rows: Vec<Value> = (0..m.rows)
                .map(|r| {
                    Value::Array(
                        (0..m.cols)
                            .map(|c| Value::String(p.poly(&m.entries[r * m.cols + c])))
                            .collect(),
                    )
                })
                .collect();
            let key = match m.name.as_str() {
                "Cθ̇" => "C_qd".to_string(),
                "τ" => "tau".to_string(),
                n => n.to_string(),
            };
            mats.insert(key, Value::Array(rows));
        }
        let vars: Map<String, Value> = self
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| (format!("q{}", i + 1), Value::String(j.clone())))
            .collect();
        let syms: Vec<Value> = self
            .params
            .symbols()
            .iter()
            .map(|(_, s)| json!({"name": s.name, "value": s.value, "meaning": s.meaning}))
            .collect();
        json!({
            "model": self.model,
            "quantity": self.quantity.function_name(),
            "joints": self.joints,
            "variables": vars,
            "symbols": syms,
            "expressions": mats,
        })
    }
}
