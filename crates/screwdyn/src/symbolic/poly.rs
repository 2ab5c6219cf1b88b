//! The canonical form: a sparse multivariate polynomial in `cos θ_i`, `sin θ_i`, `θ_j`, `θ̇_i`,
//! `θ̈_i` and the symbolic parameters, with `f64` coefficients, kept reduced by
//! `sin² θ_i = 1 − cos² θ_i`.
//!
//! Every joint transform of a revolute joint is linear in `(cos θ_i, sin θ_i)`, a prismatic or
//! helical joint adds `θ_j`, and the dynamics multiply and add such entries: every quantity of the
//! equations of motion is a polynomial in these variables. With `sin θ_i` kept to degree ≤ 1 the representation
//! is unique (the monomials `c^a` and `c^a s` of one angle are linearly independent functions), so
//! two expressions are equal exactly when their canonical forms are equal — the symbolic equality
//! the tests use.

use std::cell::Cell;
use std::collections::HashMap;

thread_local! {
    static LIMIT: Cell<usize> = const { Cell::new(usize::MAX) };
    static OVER: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` with at most `limit` terms per polynomial; returns `None` when a polynomial grew
/// past it (the computation is cut short, its result discarded).
pub fn with_term_limit<T>(limit: usize, f: impl FnOnce() -> T) -> Option<T> {
    let old = LIMIT.with(|l| l.replace(limit));
    OVER.with(|o| o.set(false));
    let out = f();
    LIMIT.with(|l| l.set(old));
    let over = OVER.with(|o| o.replace(false));
    (!over).then_some(out)
}

fn over_limit() -> bool {
    OVER.with(|o| o.get())
}

/// A variable of the polynomial ring. The derived order is the printing order: parameters
/// first (in the parameter table's order), then cosines, sines, joint positions, velocities and
/// accelerations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Var {
    /// A symbolic parameter: index into the parameter table.
    Param(u16),
    /// `cos` of the sum of the angles in the bit mask (one bit: `cos θ_i`; several bits only
    /// appear after `recombine` (in the printer) for printing).
    Cos(u64),
    /// `sin` of the sum of the angles in the bit mask.
    Sin(u64),
    /// `θ_i` itself (prismatic and helical joints).
    Q(u16),
    /// `θ̇_i`.
    Qd(u16),
    /// `θ̈_i`.
    Qdd(u16),
}

/// A monomial: variables with positive exponents, sorted by [`Var`].
pub type Mono = Vec<(Var, u8)>;

/// Relative size below which a coefficient produced by cancellation is round-off and dropped.
pub const CANCEL_TOL: f64 = 1e-12;

/// A polynomial in canonical form: terms sorted by monomial, no zero coefficients, `sin θ_i`
/// of degree ≤ 1 in every single-angle monomial.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Poly {
    terms: Vec<(Mono, f64)>,
}

/// The product of two monomials.
pub fn mono_mul(a: &[(Var, u8)], b: &[(Var, u8)]) -> Mono {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                out.push((a[i].0, a[i].1 + b[j].1));
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

/// Reduces `sin^k θ` (k ≥ 2) by `sin² = 1 − cos²`, pushing the resulting terms into `acc`.
fn push_reduced(mono: Mono, coef: f64, acc: &mut HashMap<Mono, (f64, f64)>) {
    if let Some(pos) = mono
        .iter()
        .position(|(v, e)| matches!(v, Var::Sin(_)) && *e >= 2)
    {
        let (v, e) = mono[pos];
        let Var::Sin(mask) = v else { unreachable!() };
        // s^e = s^(e−2) (1 − c²)
        let mut rest = mono.clone();
        if e == 2 {
            rest.remove(pos);
        } else {
            rest[pos].1 = e - 2;
        }
        push_reduced(rest.clone(), coef, acc);
        let with_c2 = mono_mul(&rest, &[(Var::Cos(mask), 2)]);
        push_reduced(with_c2, -coef, acc);
        return;
    }
    let slot = acc.entry(mono).or_insert((0.0, 0.0));
    slot.0 += coef;
    slot.1 = slot.1.max(coef.abs());
}

fn finish(acc: HashMap<Mono, (f64, f64)>) -> Poly {
    let mut terms: Vec<(Mono, f64)> = acc
        .into_iter()
        .filter(|(_, (c, scale))| c.abs() > CANCEL_TOL * scale)
        .map(|(m, (c, _))| (m, c))
        .collect();
    if terms.len() > LIMIT.with(|l| l.get()) {
        OVER.with(|o| o.set(true));
        return Poly::zero();
    }
    terms.sort_by(|a, b| a.0.cmp(&b.0));
    Poly { terms }
}

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly { terms: Vec::new() }
    }
    /// A constant.
    pub fn constant(c: f64) -> Self {
        if c == 0.0 {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Vec::new(), c)],
            }
        }
    }
    /// A single variable.
    pub fn var(v: Var) -> Self {
        Poly {
            terms: vec![(vec![(v, 1)], 1.0)],
        }
    }
    /// `coef · mono` (reduced).
    pub fn term(mono: Mono, coef: f64) -> Self {
        let mut acc = HashMap::new();
        let mut m = mono;
        m.sort_by_key(|a| a.0);
        push_reduced(m, coef, &mut acc);
        finish(acc)
    }
    /// Wraps terms already combined and sorted (the recombined printing form).
    pub fn from_sorted_unchecked(terms: Vec<(Mono, f64)>) -> Self {
        Poly { terms }
    }
    /// The terms, sorted by monomial.
    pub fn terms(&self) -> &[(Mono, f64)] {
        &self.terms
    }
    /// Builds from arbitrary terms (combined and reduced).
    pub fn from_terms(terms: impl IntoIterator<Item = (Mono, f64)>) -> Self {
        let mut acc = HashMap::new();
        for (mut m, c) in terms {
            m.sort_by_key(|a| a.0);
            push_reduced(m, c, &mut acc);
        }
        finish(acc)
    }
    /// Number of terms.
    #[allow(clippy::len_without_is_empty)] // `is_zero` is the polynomial's emptiness
    pub fn len(&self) -> usize {
        self.terms.len()
    }
    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }
    /// The value when it is a constant.
    pub fn as_constant(&self) -> Option<f64> {
        match self.terms.as_slice() {
            [] => Some(0.0),
            [(m, c)] if m.is_empty() => Some(*c),
            _ => None,
        }
    }
    /// `self + k·other`.
    pub fn add_scaled(&self, other: &Poly, k: f64) -> Poly {
        let (a, b) = (&self.terms, &other.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i].clone());
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push((b[j].0.clone(), k * b[j].1));
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let (x, y) = (a[i].1, k * b[j].1);
                    let s = x + y;
                    if s.abs() > CANCEL_TOL * x.abs().max(y.abs()) {
                        out.push((a[i].0.clone(), s));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend(a[i..].iter().cloned());
        out.extend(b[j..].iter().map(|(m, c)| (m.clone(), k * c)));
        out.retain(|(_, c)| *c != 0.0);
        if out.len() > LIMIT.with(|l| l.get()) {
            OVER.with(|o| o.set(true));
            return Poly::zero();
        }
        Poly { terms: out }
    }
    /// `self + other`.
    pub fn add(&self, other: &Poly) -> Poly {
        self.add_scaled(other, 1.0)
    }
    /// `self − other`.
    pub fn sub(&self, other: &Poly) -> Poly {
        self.add_scaled(other, -1.0)
    }
    /// `−self`.
    pub fn neg(&self) -> Poly {
        self.scale(-1.0)
    }
    /// `k · self`.
    pub fn scale(&self, k: f64) -> Poly {
        if k == 0.0 {
            return Poly::zero();
        }
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), c * k)).collect(),
        }
    }
    /// `self · other`, reduced by `sin² = 1 − cos²`.
    pub fn mul(&self, other: &Poly) -> Poly {
        if self.is_zero() || other.is_zero() || over_limit() {
            return Poly::zero();
        }
        if let Some(k) = self.as_constant() {
            return other.scale(k);
        }
        if let Some(k) = other.as_constant() {
            return self.scale(k);
        }
        let mut acc = HashMap::with_capacity(self.len() * other.len());
        for (ma, ca) in &self.terms {
            for (mb, cb) in &other.terms {
                push_reduced(mono_mul(ma, mb), ca * cb, &mut acc);
            }
        }
        finish(acc)
    }
    /// Evaluates with `value(var)`.
    pub fn eval(&self, value: &impl Fn(Var) -> f64) -> f64 {
        self.terms
            .iter()
            .map(|(m, c)| {
                m.iter()
                    .fold(*c, |p, (v, e)| p * value(*v).powi(i32::from(*e)))
            })
            .sum()
    }
    /// The largest exponent of any variable matching `pred`, and the total degree in them.
    pub fn degree_in(&self, pred: impl Fn(Var) -> bool) -> u32 {
        self.terms
            .iter()
            .map(|(m, _)| {
                m.iter()
                    .filter(|(v, _)| pred(*v))
                    .map(|(_, e)| u32::from(*e))
                    .sum()
            })
            .max()
            .unwrap_or(0)
    }
    /// `∂/∂x` for a variable that is not a trigonometric function (`θ_j`, `θ̇`, `θ̈`, parameter).
    pub fn diff_var(&self, x: Var) -> Poly {
        let terms = self.terms.iter().filter_map(|(m, c)| {
            let pos = m.iter().position(|(v, _)| *v == x)?;
            let e = m[pos].1;
            let mut mm = m.clone();
            if e == 1 {
                mm.remove(pos);
            } else {
                mm[pos].1 = e - 1;
            }
            Some((mm, c * f64::from(e)))
        });
        Poly::from_terms(terms)
    }
    /// `∂/∂θ_i` (through `cos θ_i`, `sin θ_i` and `θ_i`).
    pub fn diff_angle(&self, i: usize) -> Poly {
        let bit = 1u64 << i;
        let mut out: Vec<(Mono, f64)> = Vec::new();
        for (m, c) in &self.terms {
            for (pos, (v, e)) in m.iter().enumerate() {
                let d: Option<Vec<(Mono, f64)>> = match v {
                    Var::Cos(mask) if *mask == bit => Some(vec![(vec![(Var::Sin(bit), 1)], -1.0)]),
                    Var::Sin(mask) if *mask == bit => Some(vec![(vec![(Var::Cos(bit), 1)], 1.0)]),
                    Var::Q(j) if usize::from(*j) == i => Some(vec![(Vec::new(), 1.0)]),
                    Var::Cos(mask) | Var::Sin(mask) if mask & bit != 0 => {
                        panic!("diff_angle on a recombined polynomial")
                    }
                    _ => None,
                };
                let Some(d) = d else { continue };
                let mut rest = m.clone();
                if *e == 1 {
                    rest.remove(pos);
                } else {
                    rest[pos].1 = e - 1;
                }
                for (dm, dc) in d {
                    out.push((mono_mul(&rest, &dm), c * f64::from(*e) * dc));
                }
            }
        }
        Poly::from_terms(out)
    }
    /// The time derivative along the motion: `Σ_i ∂/∂θ_i · θ̇_i + ∂/∂θ̇_i · θ̈_i`.
    pub fn time_derivative(&self, n: usize) -> Poly {
        let mut out = Poly::zero();
        for i in 0..n {
            let i16 = i as u16;
            out = out.add(&self.diff_angle(i).mul(&Poly::var(Var::Qd(i16))));
            out = out.add(&self.diff_var(Var::Qd(i16)).mul(&Poly::var(Var::Qdd(i16))));
        }
        out
    }
    /// Whether `self` and `other` are equal up to a relative coefficient tolerance.
    pub fn approx_eq(&self, other: &Poly, rel: f64) -> bool {
        let d = self.sub(other);
        let scale = self
            .terms
            .iter()
            .chain(other.terms.iter())
            .fold(0.0_f64, |s, (_, c)| s.max(c.abs()));
        d.terms
            .iter()
            .all(|(_, c)| c.abs() <= rel * scale.max(1e-300))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn pythagoras_reduces_to_one() {
        let c = Poly::var(Var::Cos(1));
        let s = Poly::var(Var::Sin(1));
        let one = c.mul(&c).add(&s.mul(&s));
        assert_eq!(one, Poly::constant(1.0));
    }
    #[test]
    fn derivative_of_sin_cos() {
        let c = Poly::var(Var::Cos(1));
        let s = Poly::var(Var::Sin(1));
        // d/dθ (s c) = c² − s² = 2c² − 1
        let d = s.mul(&c).diff_angle(0);
        let expect = c.mul(&c).scale(2.0).sub(&Poly::constant(1.0));
        assert_eq!(d, expect);
    }
}
