//! The base (identifiable) parameters: the regressor stacked at random states, factored by a
//! greedy rank-revealing Householder QR in a preferred order, the dependent columns written as
//! combinations of the independent ones.

use super::parameters::{full_regressor, parameter_count, parameter_names};
use super::random::{joint_range, SplitMix};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;
use nalgebra::{DMatrix, DVector};

/// The number of random states [`BaseParameters::with_defaults`] stacks (the CLI's `--states`
/// default and Python's `states=` default): 100 states of `n` equations each span the `10 n`
/// (+ `2 n` friction) standard parameters many times over.
pub const DEFAULT_STATES: usize = 100;

/// The seed of the random states [`BaseParameters::with_defaults`] draws (the front-ends'
/// default): the same seed gives the same base parameters on every machine.
pub const DEFAULT_SEED: u64 = 1;

/// Householder QR of `a` (m × p) taking the columns in the order `order` and keeping a column
/// only when the part of it that earlier kept columns do not explain is above `1e-8` of its
/// norm (greedy rank-revealing QR). Returns the kept and the dropped columns; on return the
/// first `r` rows of `a` hold `R` for the kept columns (upper triangular in their order) and
/// the coordinates of the dropped ones.
fn greedy_qr(a: &mut DMatrix<f64>, order: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let m = a.nrows();
    let (mut kept, mut dropped) = (Vec::new(), Vec::new());
    let mut reflectors: Vec<(usize, DVector<f64>, f64)> = Vec::new();
    for &j in order {
        let norm = a.column(j).norm();
        // Apply the reflectors so far to column j.
        for (k, u, un) in &reflectors {
            let mut col = a.view_mut((*k, j), (m - k, 1));
            let d = u.dot(&col) * 2.0 / un;
            col -= u * d;
        }
        let k = kept.len();
        if k >= m {
            dropped.push(j);
            continue;
        }
        let x: DVector<f64> = a.view((k, j), (m - k, 1)).column(0).clone_owned();
        let alpha = x.norm();
        if norm == 0.0 || alpha <= 1e-8 * norm {
            dropped.push(j);
            continue;
        }
        let alpha = if x[0] > 0.0 { -alpha } else { alpha };
        let mut u = x;
        u[0] -= alpha;
        let un = u.norm_squared();
        let mut col = a.view_mut((k, j), (m - k, 1));
        let d = u.dot(&col) * 2.0 / un;
        col -= &u * d;
        reflectors.push((k, u, un));
        kept.push(j);
    }
    (kept, dropped)
}

/// The order in which [`BaseParameters::new`] tries the standard parameters: friction, then
/// rotational inertias, first moments and masses last (each class from the base to the tip),
/// so that masses and distal parameters are folded into proximal inertias and first moments
/// (the classical regrouping, e.g. `Izz_1 + L₁² m_2`).
fn preferred_order(model: &Model, friction: bool) -> Vec<usize> {
    let nb = model.nbodies();
    let mut order = Vec::new();
    if friction {
        order.extend(10 * nb..10 * nb + 2 * model.nv());
    }
    for class in [4..10, 1..4, 0..1] {
        for b in 0..nb {
            order.extend(class.clone().map(|c| 10 * b + c));
        }
    }
    order
}

/// The identifiable combinations of the standard parameters (see the module docs).
#[derive(Clone, Debug)]
pub struct BaseParameters {
    /// Whether the two friction parameters per joint are included.
    pub friction: bool,
    /// Names of all standard parameters ([`parameter_names`]).
    pub standard_names: Vec<String>,
    /// Standard parameters kept as the leading term of each base parameter (`r` of them).
    pub independent: Vec<usize>,
    /// Standard parameters folded into the base parameters (or unidentifiable).
    pub dependent: Vec<usize>,
    /// `β` (r × number of dependent parameters): `π_b = π_i + β π_d`.
    pub beta: DMatrix<f64>,
}

impl BaseParameters {
    /// Finds the base parameters of `model` numerically: the full regressor stacked at
    /// `states` random states (positions uniform within the joint limits, clamped to ±π;
    /// velocities and accelerations uniform in [−2, 2]), then a greedy Householder QR that
    /// pivots in a fixed preferred order (friction, rotational inertias, first moments, masses;
    /// base to tip) and keeps a column when more than `1e-8` of its norm is not explained by
    /// the columns kept before it; coefficients of `β` below `1e-10` are zeroed.
    ///
    /// # Errors
    /// `InvalidArgument` when `states` is too small to span the parameters
    /// (`states · n` below the number of standard parameters); errors of
    /// [`regressor`](crate::dynamics::regressor).
    ///
    /// ```
    /// use screwdyn::identification::BaseParameters;
    /// let m = screwdyn::builtin::planar2(); // a planar 2R arm: six base parameters
    /// let b = BaseParameters::new(&m, false, 50, 1).unwrap();
    /// assert_eq!(b.rank(), 6);
    /// assert_eq!(b.expressions()[4], "mx_link2 + m_link2"); // link 2's frame is at its end
    /// ```
    pub fn new(model: &Model, friction: bool, states: usize, seed: u64) -> Result<Self> {
        let n = model.nv();
        let p = parameter_count(model, friction);
        if states * n < p {
            return Err(Error::InvalidArgument(format!(
                "{states} random states give {} equations for {p} standard parameters; use at \
                 least {}",
                states * n,
                p.div_ceil(n)
            )));
        }
        let mut ws = Workspace::new(model);
        let mut w = DMatrix::zeros(states * n, p);
        let mut block = DMatrix::zeros(n, p);
        let mut rng = SplitMix::new(seed ^ 0x005E_ED0F_BA5E);
        let (mut q, mut v, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for s in 0..states {
            for i in 0..n {
                let (lo, hi) = joint_range(model, i);
                q[i] = rng.uniform(lo, hi);
                v[i] = rng.uniform(-2.0, 2.0);
                a[i] = rng.uniform(-2.0, 2.0);
            }
            full_regressor(model, &mut ws, &q, &v, &a, friction, &mut block)?;
            w.view_mut((s * n, 0), (n, p)).copy_from(&block);
        }
        let (independent, dependent) = greedy_qr(&mut w, &preferred_order(model, friction));
        let rank = independent.len();
        let r11 = w
            .select_columns(independent.iter())
            .rows(0, rank)
            .upper_triangle();
        let r12 = w
            .select_columns(dependent.iter())
            .rows(0, rank)
            .clone_owned();
        let mut beta = r12;
        if rank > 0 && !r11.solve_upper_triangular_mut(&mut beta) {
            return Err(Error::Numerical(
                "the base-parameter factorisation is singular".into(),
            ));
        }
        beta.iter_mut()
            .filter(|x| x.abs() < 1e-10)
            .for_each(|x| *x = 0.0);
        Ok(BaseParameters {
            friction,
            standard_names: parameter_names(model, friction),
            independent,
            dependent,
            beta,
        })
    }

    /// [`BaseParameters::new`] with [`DEFAULT_STATES`] random states drawn with
    /// [`DEFAULT_SEED`]: the base parameters the command line and Python find unless told
    /// otherwise.
    ///
    /// # Errors
    /// As [`BaseParameters::new`].
    ///
    /// ```
    /// use screwdyn::identification::{BaseParameters, DEFAULT_SEED, DEFAULT_STATES};
    /// let m = screwdyn::builtin::planar2();
    /// let b = BaseParameters::with_defaults(&m, false).unwrap();
    /// let same = BaseParameters::new(&m, false, DEFAULT_STATES, DEFAULT_SEED).unwrap();
    /// assert_eq!(b.expressions(), same.expressions());
    /// ```
    pub fn with_defaults(model: &Model, friction: bool) -> Result<Self> {
        BaseParameters::new(model, friction, DEFAULT_STATES, DEFAULT_SEED)
    }

    /// Number of base parameters `r`.
    pub fn rank(&self) -> usize {
        self.independent.len()
    }

    /// `K` (r × p): `π_b = K π`.
    pub fn combination_matrix(&self) -> DMatrix<f64> {
        let p = self.standard_names.len();
        let mut k = DMatrix::zeros(self.rank(), p);
        for (row, &i) in self.independent.iter().enumerate() {
            k[(row, i)] = 1.0;
            for (c, &d) in self.dependent.iter().enumerate() {
                k[(row, d)] = self.beta[(row, c)];
            }
        }
        k
    }

    /// The base parameters of a standard parameter vector: `π_b = K π`.
    pub fn base_values(&self, standard: &DVector<f64>) -> DVector<f64> {
        self.combination_matrix() * standard
    }

    /// Each base parameter as a readable combination of standard parameters, e.g.
    /// `Iyy_upper_arm_link + 0.18 m_forearm_link + 0.18 m_wrist_1_link`.
    pub fn expressions(&self) -> Vec<String> {
        (0..self.rank())
            .map(|row| {
                let mut s = self.standard_names[self.independent[row]].clone();
                for (c, &d) in self.dependent.iter().enumerate() {
                    let b = self.beta[(row, c)];
                    if b == 0.0 {
                        continue;
                    }
                    let (op, mag) = if b < 0.0 { ("−", -b) } else { ("+", b) };
                    let name = &self.standard_names[d];
                    if (mag - 1.0).abs() < 1e-9 {
                        s.push_str(&format!(" {op} {name}"));
                    } else {
                        s.push_str(&format!(" {op} {} {name}", format_coefficient(mag)));
                    }
                }
                s
            })
            .collect()
    }

    /// The columns of a full regressor block that multiply the base parameters (`W_i`).
    pub fn base_columns(&self, full: &DMatrix<f64>) -> DMatrix<f64> {
        full.select_columns(self.independent.iter())
    }
}

/// Six significant digits, without trailing zeros.
fn format_coefficient(x: f64) -> String {
    let s = format!("{x:.6}");
    if x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e6) {
        return format!("{x:.5e}");
    }
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}
