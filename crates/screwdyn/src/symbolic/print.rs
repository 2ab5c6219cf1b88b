//! Printing canonical polynomials the way the notes write them: angle sums recombined
//! (`c1 c2 − s1 s2 → c12`), terms collected on the inertial parameters or on the configuration,
//! `θ`, `θ̇`, `c₁₂` abbreviations (or `cos(θ1 + θ2)`), as text, LaTeX or plain ASCII.

use super::params::{ParamKind, ParamTable};
use super::poly::{mono_mul, Mono, Poly, Var};
use std::cmp::Ordering;
use std::collections::{BTreeSet, HashMap};

/// How to write an expression.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// Unicode text like the notes: `m2 L1 L2 c₁₂ θ̇₁²` (or `cos(θ1 + θ2)` without abbreviations).
    Text {
        /// `c₁₂` rather than `cos(θ1 + θ2)`.
        abbrev: bool,
    },
    /// LaTeX: `m_{2} L_{1} c_{12} \dot{\theta}_{1}^{2}`.
    Latex {
        /// `c_{12}` rather than `\cos(\theta_{1} + \theta_{2})`.
        abbrev: bool,
    },
    /// Plain ASCII that SymPy and most languages parse: `m2*L1*cos(q1 + q2)*qd1**2`.
    Ascii,
}

/// Which factors are pulled out when terms are grouped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Collect {
    /// Group on the inertial parameters: `m1 L1² + m2 (L1² + 2 L1 L2 c₂ + L2²)`.
    #[default]
    Inertial,
    /// Group on everything else (the 003/004 layout):
    /// `(m1 + m2) L1² + 2 m2 L1 L2 c₂ + m2 L2²`.
    Config,
    /// No grouping: one term after the other.
    None,
}

impl std::str::FromStr for Collect {
    type Err = crate::Error;
    fn from_str(s: &str) -> std::result::Result<Self, crate::Error> {
        match crate::error::choice_key(s).as_str() {
            "inertial" => Ok(Collect::Inertial),
            "config" | "configuration" => Ok(Collect::Config),
            "none" => Ok(Collect::None),
            _ => Err(crate::Error::UnknownChoice {
                what: "collect mode",
                got: s.into(),
                expected: "inertial, config or none",
            }),
        }
    }
}

/// Recombines angle sums: `K c_A c_B − K s_A s_B → K c_{A+B}` and
/// `K s_A c_B + K c_A s_B → K s_{A+B}`, repeated until nothing changes (so `c₁₂₃` appears on a
/// chain of three parallel joints). The result is equal as a function, but no longer in the
/// canonical form (use it for printing only).
pub fn recombine(p: &Poly) -> Poly {
    let mut terms: HashMap<Mono, f64> = p.terms().iter().cloned().collect();
    loop {
        let mut changed = false;
        let mut keys: Vec<Mono> = terms.keys().cloned().collect();
        keys.sort();
        for mono in keys {
            let Some(&coef) = terms.get(&mono) else {
                continue;
            };
            let trig: Vec<(usize, Var)> = mono
                .iter()
                .enumerate()
                .filter(|(_, (v, e))| *e == 1 && matches!(v, Var::Cos(_) | Var::Sin(_)))
                .map(|(i, (v, _))| (i, *v))
                .collect();
            'pairs: for x in 0..trig.len() {
                for y in 0..trig.len() {
                    if x == y {
                        continue;
                    }
                    let (va, vb) = (trig[x].1, trig[y].1);
                    let (ma, mb) = (mask(va), mask(vb));
                    if ma & mb != 0 || ma > mb {
                        continue;
                    }
                    let rest: Mono = mono
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| *i != trig[x].0 && *i != trig[y].0)
                        .map(|(_, t)| *t)
                        .collect();
                    // c_A c_B with −s_A s_B, or s_A c_B with c_A s_B.
                    let (partner, want, result) = match (va, vb) {
                        (Var::Cos(_), Var::Cos(_)) => (
                            [(Var::Sin(ma), 1), (Var::Sin(mb), 1)],
                            -coef,
                            Var::Cos(ma | mb),
                        ),
                        (Var::Sin(_), Var::Cos(_)) => (
                            [(Var::Cos(ma), 1), (Var::Sin(mb), 1)],
                            coef,
                            Var::Sin(ma | mb),
                        ),
                        _ => continue,
                    };
                    let mut pm = partner.to_vec();
                    pm.sort();
                    let pmono = mono_mul(&rest, &pm);
                    let Some(&pc) = terms.get(&pmono) else {
                        continue;
                    };
                    if (pc - want).abs() > 1e-9 * want.abs() {
                        continue;
                    }
                    terms.remove(&mono);
                    terms.remove(&pmono);
                    let new = mono_mul(&rest, &[(result, 1)]);
                    *terms.entry(new).or_insert(0.0) += coef;
                    changed = true;
                    break 'pairs;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let mut out: Vec<(Mono, f64)> = terms.into_iter().filter(|(_, c)| *c != 0.0).collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Poly::from_sorted_unchecked(out)
}

fn mask(v: Var) -> u64 {
    match v {
        Var::Cos(m) | Var::Sin(m) => m,
        _ => 0,
    }
}

/// Printing order of monomials: earlier variables first, higher powers first.
fn mono_order(a: &Mono, b: &Mono) -> Ordering {
    for (x, y) in a.iter().zip(b.iter()) {
        match x.0.cmp(&y.0) {
            Ordering::Equal => match y.1.cmp(&x.1) {
                Ordering::Equal => continue,
                o => return o,
            },
            o => return o,
        }
    }
    a.len().cmp(&b.len())
}

/// Writes polynomials in one [`Style`] with one [`Collect`] mode, remembering which
/// abbreviations it used (for the legend).
pub struct Printer<'a> {
    params: &'a ParamTable,
    style: Style,
    collect: Collect,
    used: std::cell::RefCell<BTreeSet<Var>>,
}

const SUB: [&str; 10] = ["₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"];
const SUP: [&str; 10] = ["⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"];

fn digits(n: usize, table: &[&str; 10]) -> String {
    n.to_string()
        .chars()
        .map(|c| table[c.to_digit(10).unwrap_or(0) as usize])
        .collect()
}

/// A number for people: integers as integers, others to 6 significant digits.
pub fn fmt_number(x: f64) -> String {
    if x == x.round() && x.abs() < 1e9 {
        return format!("{}", x as i64);
    }
    let a = x.abs();
    if !(1e-4..1e6).contains(&a) {
        return format!("{x:.5e}");
    }
    let decimals = (5 - a.log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{x:.decimals$}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

impl<'a> Printer<'a> {
    /// A printer.
    pub fn new(params: &'a ParamTable, style: Style, collect: Collect) -> Self {
        Printer {
            params,
            style,
            collect,
            used: Default::default(),
        }
    }

    fn many(&self) -> bool {
        // Joint indices ≥ 10 need separators in abbreviations.
        false
    }

    fn indices(&self, m: u64) -> Vec<usize> {
        (0..64)
            .filter(|b| m & (1 << b) != 0)
            .map(|b| b + 1)
            .collect()
    }

    fn sub_list(&self, idx: &[usize]) -> String {
        let sep = idx.iter().any(|&i| i >= 10) || self.many();
        match self.style {
            Style::Text { .. } => idx
                .iter()
                .map(|&i| digits(i, &SUB))
                .collect::<Vec<_>>()
                .join(if sep { "," } else { "" }),
            _ => idx
                .iter()
                .map(|i| i.to_string())
                .collect::<Vec<_>>()
                .join(if sep { "," } else { "" }),
        }
    }

    fn theta(&self, i: usize) -> String {
        match self.style {
            Style::Text { abbrev: true } => format!("θ{}", digits(i, &SUB)),
            Style::Text { abbrev: false } => format!("θ{i}"),
            Style::Latex { .. } => format!("\\theta_{{{i}}}"),
            Style::Ascii => format!("q{i}"),
        }
    }

    fn angle_sum(&self, m: u64) -> String {
        let idx = self.indices(m);
        let parts: Vec<String> = idx.iter().map(|&i| self.theta(i)).collect();
        parts.join(" + ")
    }

    fn param_name(&self, k: usize) -> String {
        let name = &self.params.params[k].name;
        match self.style {
            Style::Latex { .. } => latex_name(name),
            _ => name.clone(),
        }
    }

    /// One variable, without its power.
    pub fn var(&self, v: Var) -> String {
        self.used.borrow_mut().insert(v);
        let abbrev = matches!(
            self.style,
            Style::Text { abbrev: true } | Style::Latex { abbrev: true }
        );
        match v {
            Var::Param(k) => self.param_name(usize::from(k)),
            Var::Cos(m) | Var::Sin(m) => {
                let is_cos = matches!(v, Var::Cos(_));
                if abbrev {
                    let letter = if is_cos { "c" } else { "s" };
                    let sub = self.sub_list(&self.indices(m));
                    match self.style {
                        Style::Latex { .. } => format!("{letter}_{{{sub}}}"),
                        _ => format!("{letter}{sub}"),
                    }
                } else {
                    let f = if is_cos { "cos" } else { "sin" };
                    match self.style {
                        Style::Latex { .. } => format!("\\{f}({})", self.angle_sum(m)),
                        _ => format!("{f}({})", self.angle_sum(m)),
                    }
                }
            }
            Var::Q(i) => self.theta(usize::from(i) + 1),
            Var::Qd(i) | Var::Qdd(i) => {
                let i = usize::from(i) + 1;
                let dd = matches!(v, Var::Qdd(_));
                match self.style {
                    Style::Text { abbrev: true } => {
                        format!(
                            "θ{}{}",
                            if dd { "\u{308}" } else { "\u{307}" },
                            digits(i, &SUB)
                        )
                    }
                    Style::Text { abbrev: false } => {
                        format!("θ{}{i}", if dd { "\u{308}" } else { "\u{307}" })
                    }
                    Style::Latex { .. } => {
                        format!("\\{}{{\\theta}}_{{{i}}}", if dd { "ddot" } else { "dot" })
                    }
                    Style::Ascii => format!("{}{i}", if dd { "qdd" } else { "qd" }),
                }
            }
        }
    }

    fn power(&self, base: String, e: u8) -> String {
        if e == 1 {
            return base;
        }
        match self.style {
            Style::Text { .. } => format!("{base}{}", digits(usize::from(e), &SUP)),
            Style::Latex { .. } => format!("{base}^{{{e}}}"),
            Style::Ascii => format!("{base}**{e}"),
        }
    }

    fn mono(&self, m: &[(Var, u8)]) -> String {
        let sep = match self.style {
            Style::Ascii => "*",
            Style::Latex { .. } => " \\, ",
            Style::Text { .. } => " ",
        };
        m.iter()
            .map(|(v, e)| self.power(self.var(*v), *e))
            .collect::<Vec<_>>()
            .join(sep)
    }

    fn number(&self, x: f64) -> String {
        match self.style {
            Style::Ascii => format!("{x:?}"),
            _ => fmt_number(x),
        }
    }

    /// `coef · mono` without the sign; the sign is returned separately.
    fn term(&self, coef: f64, m: &[(Var, u8)]) -> (bool, String) {
        let neg = coef < 0.0;
        let a = coef.abs();
        let body = self.mono(m);
        let s = if m.is_empty() {
            self.number(a)
        } else if a == 1.0 {
            body
        } else {
            let sep = match self.style {
                Style::Ascii => "*",
                Style::Latex { .. } => " \\, ",
                Style::Text { .. } => " ",
            };
            format!("{}{sep}{body}", self.number(a))
        };
        (neg, s)
    }

    fn join(&self, parts: Vec<(bool, String)>) -> String {
        let minus = match self.style {
            Style::Text { .. } => "−",
            _ => "-",
        };
        let mut out = String::new();
        for (k, (neg, s)) in parts.into_iter().enumerate() {
            if k == 0 {
                if neg {
                    out.push_str(minus);
                }
            } else {
                out.push_str(if neg { " − " } else { " + " });
                if neg && !matches!(self.style, Style::Text { .. }) {
                    out.truncate(out.len() - " − ".len());
                    out.push_str(" - ");
                }
            }
            out.push_str(&s);
        }
        if out.is_empty() {
            "0".into()
        } else {
            out
        }
    }

    fn is_inertial(&self, v: Var) -> bool {
        match v {
            Var::Param(k) => matches!(
                self.params.params[usize::from(k)].kind,
                ParamKind::Mass(_)
                    | ParamKind::Inertia(..)
                    | ParamKind::Com(..)
                    | ParamKind::Armature(_)
            ),
            _ => false,
        }
    }

    /// A polynomial, angle sums recombined and terms collected.
    pub fn poly(&self, p: &Poly) -> String {
        let r = recombine(p);
        let mut terms: Vec<(Mono, f64)> = r.terms().to_vec();
        terms.sort_by(|a, b| mono_order(&a.0, &b.0));
        if self.collect == Collect::None {
            return self.join(terms.iter().map(|(m, c)| self.term(*c, m)).collect());
        }
        // Split each monomial into (key, inner) and group on the key.
        let mut groups: Vec<(Mono, Vec<(Mono, f64)>)> = Vec::new();
        for (m, c) in terms {
            let (inert, other): (Mono, Mono) = m.iter().partition(|(v, _)| self.is_inertial(*v));
            let (key, inner) = match self.collect {
                Collect::Inertial => (inert, other),
                _ => (other, inert),
            };
            match groups.iter_mut().find(|(k, _)| *k == key) {
                Some((_, list)) => list.push((inner, c)),
                None => groups.push((key, vec![(inner, c)])),
            }
        }
        groups.sort_by(|a, b| mono_order(&a.0, &b.0));
        let mul = match self.style {
            Style::Ascii => "*",
            Style::Latex { .. } => " \\, ",
            Style::Text { .. } => " ",
        };
        let parts = groups
            .into_iter()
            .map(|(key, mut inner)| {
                inner.sort_by(|a, b| mono_order(&a.0, &b.0));
                if inner.len() == 1 || key.is_empty() {
                    let merged: Vec<(bool, String)> = inner
                        .iter()
                        .map(|(m, c)| {
                            let (a, b) = match self.collect {
                                Collect::Inertial => (&key, m),
                                _ => (m, &key),
                            };
                            let mut full: Mono = a.clone();
                            full.extend(b.iter().cloned());
                            self.term(*c, &full)
                        })
                        .collect();
                    if merged.len() == 1 {
                        return merged.into_iter().next().expect("one");
                    }
                    return (false, self.join(merged));
                }
                // Pull a common sign out of the parenthesis.
                let all_neg = inner.iter().all(|(_, c)| *c < 0.0);
                let sum = self.join(
                    inner
                        .iter()
                        .map(|(m, c)| self.term(if all_neg { -c } else { *c }, m))
                        .collect(),
                );
                let k = self.mono(&key);
                let s = match self.collect {
                    Collect::Inertial => format!("{k}{mul}({sum})"),
                    _ => format!("({sum}){mul}{k}"),
                };
                (all_neg, s)
            })
            .collect();
        self.join(parts)
    }

    /// The legend of the abbreviations used so far: `c₁₂ = cos(θ₁ + θ₂)`, one per line.
    pub fn legend(&self) -> Vec<String> {
        if !matches!(
            self.style,
            Style::Text { abbrev: true } | Style::Latex { abbrev: true }
        ) {
            return Vec::new();
        }
        let used = self.used.borrow().clone();
        used.into_iter()
            .filter_map(|v| match v {
                Var::Cos(m) | Var::Sin(m) => {
                    let short = self.var(v);
                    let f = if matches!(v, Var::Cos(_)) {
                        "cos"
                    } else {
                        "sin"
                    };
                    let idx = self.indices(m);
                    let arg = match self.style {
                        Style::Latex { .. } => idx
                            .iter()
                            .map(|i| format!("\\theta_{{{i}}}"))
                            .collect::<Vec<_>>()
                            .join(" + "),
                        _ => idx
                            .iter()
                            .map(|&i| self.theta(i))
                            .collect::<Vec<_>>()
                            .join(" + "),
                    };
                    Some(match self.style {
                        Style::Latex { .. } => format!("{short} = \\{f}({arg})"),
                        _ => format!("{short} = {f}({arg})"),
                    })
                }
                _ => None,
            })
            .collect()
    }
}

/// `m_link2` → `m_{\mathrm{link2}}`, `Ixx1` → `I_{xx1}`, `L1` → `L_{1}`, `g` → `g`.
pub fn latex_name(name: &str) -> String {
    if let Some((head, tail)) = name.split_once('_') {
        return format!("{head}_{{\\mathrm{{{}}}}}", tail.replace('_', "\\_"));
    }
    let mut chars = name.chars();
    let first: String = chars.next().map(String::from).unwrap_or_default();
    let rest: String = chars.collect();
    if rest.is_empty() {
        first
    } else {
        format!("{first}_{{{rest}}}")
    }
}
