//! Identification of inertial parameters: the standard parameters and their names, the base
//! (identifiable) parameters by QR with column pivoting, least squares from a log of states and
//! torques (streaming), a physically consistent estimate, exciting Fourier trajectories and the
//! differentiating filter used when a log has no accelerations.
//!
//! **Parameters.** `π` stacks the ten standard parameters of every moving body in joint order
//! (see [`body_parameters`]: `m, mx, my, mz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`, first moment and
//! rotational inertia about the body frame origin, body-frame axes), optionally followed by two
//! friction parameters per joint, `fv` (viscous, N·m·s/rad or N·s/m) and `fc` (Coulomb), with
//! the joint torque `τ = Y(q, q̇, q̈) π_inertial + fv q̇ + fc sign(q̇)`.
//!
//! **Base parameters.** Some columns of the stacked regressor are zero or linear combinations
//! of others for every state. [`BaseParameters::new`] stacks the regressor at random states,
//! factors it `W P = Q R` by Householder QR with column pivoting, takes the numerical rank `r`
//! and writes the dependent columns as `W_d = W_i β` with `β = R₁₁⁻¹ R₁₂`; the base parameters
//! are `π_b = π_i + β π_d` (each an independent standard parameter plus a combination of the
//! dependent ones), and `τ = W_i π_b` exactly.
//!
//! **Least squares.** [`LeastSquares`] accumulates the rows `[W_i | τ]` of a log into an
//! upper-triangular factor (a QR update per block of samples: memory does not grow with the
//! log), then [`LeastSquares::solve`] returns `π̂_b = R⁻¹ z`, standard deviations
//! `σ √diag((RᵀR)⁻¹)` with `σ² = RSS / (rows − r)`, and the condition number of the
//! regressor.
//!
//! Identification works on `f64` models (it is batch analysis over a log, not a per-call
//! algorithm); the regressor itself, [`regressor`], is generic over the scalar type and
//! allocation-free.

use crate::dynamics::pack_parameters;
use crate::dynamics::{
    body_parameters, inertia_from_parameters, model_parameters, regressor, PARAMETERS_PER_BODY,
    PARAMETER_NAMES,
};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;
use nalgebra::{DMatrix, DVector, Matrix4};

/// Names of the standard parameters, `<parameter>_<body>` (e.g. `m_upper_arm_link`,
/// `Izz_shoulder_link`), then `fv_<joint>`, `fc_<joint>` per joint when `friction`.
///
/// ```
/// let m = screwdyn::builtin::planar2();
/// let names = screwdyn::identification::parameter_names(&m, true);
/// assert_eq!(names.len(), 24);
/// assert_eq!(names[0], "m_link1");
/// assert_eq!(names[21], "fc_joint1");
/// ```
pub fn parameter_names(model: &Model, friction: bool) -> Vec<String> {
    let mut out = Vec::new();
    for b in model.bodies() {
        for p in PARAMETER_NAMES {
            out.push(format!("{p}_{}", b.name));
        }
    }
    if friction {
        for j in model.joints() {
            out.push(format!("fv_{}", j.name));
            out.push(format!("fc_{}", j.name));
        }
    }
    out
}

/// The model's standard parameters `π` (see the module docs), with the joints' `damping` and
/// `friction` coefficients as `fv`, `fc` when `friction`.
pub fn standard_parameters(model: &Model, friction: bool) -> DVector<f64> {
    let pi = model_parameters(model);
    if !friction {
        return pi;
    }
    let n = model.nv();
    let mut out = DVector::zeros(pi.len() + 2 * n);
    out.rows_mut(0, pi.len()).copy_from(&pi);
    for (i, j) in model.joints().iter().enumerate() {
        out[pi.len() + 2 * i] = j.damping;
        out[pi.len() + 2 * i + 1] = j.friction;
    }
    out
}

/// Number of standard parameters: `10 n`, plus `2 n` with friction.
pub fn parameter_count(model: &Model, friction: bool) -> usize {
    PARAMETERS_PER_BODY * model.nbodies() + if friction { 2 * model.nv() } else { 0 }
}

/// `sign(q̇)` as used by the Coulomb friction column (0 at rest).
fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The full regressor (n × [`parameter_count`]) at one state: [`regressor`] followed by the
/// friction columns (`q̇_i` and `sign(q̇_i)` in row `i`) when `friction`.
///
/// # Errors
/// As [`regressor`]; `out` of the wrong shape is an `InvalidArgument`.
pub fn full_regressor(
    model: &Model,
    ws: &mut Workspace,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    friction: bool,
    out: &mut DMatrix<f64>,
) -> Result<()> {
    let n = model.nv();
    let p = parameter_count(model, friction);
    if out.shape() != (n, p) {
        return Err(Error::InvalidArgument(format!(
            "the regressor buffer is {}×{}, it must be {n}×{p}",
            out.nrows(),
            out.ncols()
        )));
    }
    let y = regressor(model, ws, q, v, a)?;
    let inertial = PARAMETERS_PER_BODY * n;
    out.columns_mut(0, inertial).copy_from(y);
    if friction {
        out.columns_mut(inertial, 2 * n).fill(0.0);
        for i in 0..n {
            out[(i, inertial + 2 * i)] = v[i];
            out[(i, inertial + 2 * i + 1)] = sign(v[i]);
        }
    }
    Ok(())
}

/// SplitMix64: a small deterministic generator for the random states.
struct SplitMix(u64);

impl SplitMix {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// Position range of a joint for random states: its limits, clamped to `[−π, π]` when wider.
fn joint_range(model: &Model, i: usize) -> (f64, f64) {
    let l = &model.joints()[i].limits;
    let pi = std::f64::consts::PI;
    let lo = if l.lower.is_finite() {
        l.lower.max(-pi)
    } else {
        -pi
    };
    let hi = if l.upper.is_finite() {
        l.upper.min(pi)
    } else {
        pi
    };
    if hi > lo {
        (lo, hi)
    } else {
        (-pi, pi)
    }
}

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
    /// (`states · n` below the number of standard parameters); errors of [`regressor`].
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
        let mut rng = SplitMix(seed ^ 0x005E_ED0F_BA5E);
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

/// Streaming least squares for the base parameters: add samples with [`LeastSquares::add`],
/// then [`LeastSquares::solve`]. Memory is `O(r²)` whatever the number of samples.
#[derive(Clone, Debug)]
pub struct LeastSquares {
    base: BaseParameters,
    /// Upper-triangular factor of `[W_i | τ]` so far, (r + 1) × (r + 1).
    factor: DMatrix<f64>,
    /// Rows waiting to be folded into `factor`.
    pending: DMatrix<f64>,
    pending_rows: usize,
    samples: usize,
    full: DMatrix<f64>,
    ws: Workspace,
}

/// Samples folded into the factor at once.
const BLOCK_SAMPLES: usize = 64;

/// The result of [`LeastSquares::solve`].
#[derive(Clone, Debug)]
pub struct Estimate {
    /// `π̂_b`, in the order of [`BaseParameters::expressions`].
    pub values: DVector<f64>,
    /// Standard deviation of each estimate, `σ √diag((W_iᵀ W_i)⁻¹)`.
    pub std_dev: DVector<f64>,
    /// Condition number of the base regressor `W_i` (ratio of its extreme singular values).
    pub condition_number: f64,
    /// `σ`: the RMS torque residual over all joints and samples, corrected for the degrees of
    /// freedom (`√(RSS / (rows − r))`).
    pub sigma: f64,
    /// Number of samples used.
    pub samples: usize,
}

impl LeastSquares {
    /// An empty problem for `model`'s base parameters.
    pub fn new(model: &Model, base: BaseParameters) -> Self {
        let n = model.nv();
        let r = base.rank();
        let p = base.standard_names.len();
        LeastSquares {
            factor: DMatrix::zeros(r + 1, r + 1),
            pending: DMatrix::zeros(BLOCK_SAMPLES * n, r + 1),
            pending_rows: 0,
            samples: 0,
            full: DMatrix::zeros(n, p),
            ws: Workspace::new(model),
            base,
        }
    }

    /// The base parameters being estimated.
    pub fn base(&self) -> &BaseParameters {
        &self.base
    }

    /// Number of samples added.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Adds one sample `(q, q̇, q̈, τ)`.
    ///
    /// # Errors
    /// Wrong lengths or non-finite values (named `q`, `v`, `a`, `tau`).
    pub fn add(
        &mut self,
        model: &Model,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        tau: &[f64],
    ) -> Result<()> {
        model.check_vector(tau, "tau")?;
        full_regressor(
            model,
            &mut self.ws,
            q,
            v,
            a,
            self.base.friction,
            &mut self.full,
        )?;
        let n = model.nv();
        let r = self.base.rank();
        for (i, t) in tau.iter().enumerate() {
            let row = self.pending_rows + i;
            for (c, &k) in self.base.independent.iter().enumerate() {
                self.pending[(row, c)] = self.full[(i, k)];
            }
            self.pending[(row, r)] = *t;
        }
        self.pending_rows += n;
        self.samples += 1;
        if self.pending_rows == self.pending.nrows() {
            self.fold();
        }
        Ok(())
    }

    /// Folds the pending rows into the triangular factor (QR of `[factor; pending]`).
    fn fold(&mut self) {
        if self.pending_rows == 0 {
            return;
        }
        let k = self.factor.nrows();
        let mut stacked = DMatrix::zeros(k + self.pending_rows, k);
        stacked.view_mut((0, 0), (k, k)).copy_from(&self.factor);
        stacked
            .view_mut((k, 0), (self.pending_rows, k))
            .copy_from(&self.pending.view((0, 0), (self.pending_rows, k)));
        let r = stacked.qr().r();
        self.factor.fill(0.0);
        let rows = r.nrows().min(k);
        self.factor
            .view_mut((0, 0), (rows, k))
            .copy_from(&r.view((0, 0), (rows, k)));
        self.pending_rows = 0;
    }

    /// Solves for the base parameters.
    ///
    /// # Errors
    /// `InvalidArgument` for too few samples (fewer equations than base parameters plus one)
    /// or a rank-deficient log (a base parameter the motion does not excite: condition number
    /// above `1e10`), naming the worst-determined parameter.
    pub fn solve(&mut self) -> Result<Estimate> {
        self.fold();
        let r = self.base.rank();
        let n_rows = self.samples * (self.full.nrows());
        if n_rows <= r {
            return Err(Error::InvalidArgument(format!(
                "too few samples: {} sample(s) give {n_rows} torque equations for {r} base \
                 parameters (need more than {r})",
                self.samples
            )));
        }
        let rm = self.factor.view((0, 0), (r, r)).upper_triangle();
        let z = self.factor.view((0, r), (r, 1)).clone_owned();
        let sv = rm.singular_values();
        let (smax, smin) = (sv.max(), sv.min());
        let cond = if smin > 0.0 {
            smax / smin
        } else {
            f64::INFINITY
        };
        if cond.is_nan() || cond >= 1e10 {
            // The parameter whose diagonal entry in R is smallest is the least excited.
            let worst = (0..r)
                .min_by(|&a, &b| rm[(a, a)].abs().total_cmp(&rm[(b, b)].abs()))
                .unwrap_or(0);
            return Err(Error::InvalidArgument(format!(
                "the log is rank-deficient (regressor condition number {cond:.3e}): the motion \
                 does not excite the base parameter '{}'; record a richer trajectory (e.g. \
                 `screwdyn identify --excite`)",
                self.base.standard_names[self.base.independent[worst]]
            )));
        }
        let mut x = z.clone();
        rm.solve_upper_triangular_mut(&mut x);
        let rss = self.factor[(r, r)] * self.factor[(r, r)];
        let sigma = (rss / (n_rows - r) as f64).sqrt();
        // diag((RᵀR)⁻¹) = squared row norms of R⁻¹.
        let mut rinv = DMatrix::identity(r, r);
        rm.solve_upper_triangular_mut(&mut rinv);
        let std_dev = DVector::from_fn(r, |i, _| sigma * rinv.row(i).norm());
        Ok(Estimate {
            values: DVector::from_column_slice(x.as_slice()),
            std_dev,
            condition_number: cond,
            sigma,
            samples: self.samples,
        })
    }

    /// The information factor `R` (r × r, upper triangular, `RᵀR = W_iᵀ W_i`) and `z`
    /// (`R π̂_b = z`) accumulated so far, for constrained solves.
    pub fn factor(&mut self) -> (DMatrix<f64>, DVector<f64>) {
        self.fold();
        let r = self.base.rank();
        (
            self.factor.view((0, 0), (r, r)).upper_triangle(),
            DVector::from_column_slice(self.factor.view((0, r), (r, 1)).clone_owned().as_slice()),
        )
    }
}

/// Per-joint torque residuals of an estimate on a log (RMS per joint), accumulated sample by
/// sample: `τ − W_i π̂_b`.
#[derive(Clone, Debug)]
pub struct Residuals {
    sum_squares: Vec<f64>,
    samples: usize,
    full: DMatrix<f64>,
    ws: Workspace,
}

impl Residuals {
    /// An empty accumulator for `model` with parameters of `base`.
    pub fn new(model: &Model, base: &BaseParameters) -> Self {
        Residuals {
            sum_squares: vec![0.0; model.nv()],
            samples: 0,
            full: DMatrix::zeros(model.nv(), base.standard_names.len()),
            ws: Workspace::new(model),
        }
    }

    /// The predicted torque `W_i π̂_b` at one state, written into `out`.
    ///
    /// # Errors
    /// Wrong lengths or non-finite values.
    #[allow(clippy::too_many_arguments)]
    pub fn predict(
        &mut self,
        model: &Model,
        base: &BaseParameters,
        values: &DVector<f64>,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        out: &mut [f64],
    ) -> Result<()> {
        full_regressor(model, &mut self.ws, q, v, a, base.friction, &mut self.full)?;
        for (i, o) in out.iter_mut().enumerate() {
            *o = base
                .independent
                .iter()
                .enumerate()
                .map(|(c, &k)| self.full[(i, k)] * values[c])
                .sum();
        }
        Ok(())
    }

    /// Adds the residual of one sample; returns the predicted torques in `predicted`.
    ///
    /// # Errors
    /// Wrong lengths or non-finite values.
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &mut self,
        model: &Model,
        base: &BaseParameters,
        values: &DVector<f64>,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        tau: &[f64],
        predicted: &mut [f64],
    ) -> Result<()> {
        model.check_vector(tau, "tau")?;
        self.predict(model, base, values, q, v, a, predicted)?;
        for i in 0..tau.len() {
            let e = tau[i] - predicted[i];
            self.sum_squares[i] += e * e;
        }
        self.samples += 1;
        Ok(())
    }

    /// RMS residual per joint.
    pub fn rms(&self) -> Vec<f64> {
        let n = self.samples.max(1) as f64;
        self.sum_squares.iter().map(|s| (s / n).sqrt()).collect()
    }
}

/// Pseudo-inertia `J = [½tr(I)1 − I, h; hᵀ, m]` of ten body parameters (`I` about the origin);
/// the body is physically consistent exactly when `J` is positive (semi)definite.
fn pseudo_inertia(p: &[f64]) -> Matrix4<f64> {
    let i = nalgebra::Matrix3::new(p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9]);
    let s = nalgebra::Matrix3::identity() * (0.5 * i.trace()) - i;
    let mut j = Matrix4::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&s);
    j[(0, 3)] = p[1];
    j[(1, 3)] = p[2];
    j[(2, 3)] = p[3];
    j[(3, 0)] = p[1];
    j[(3, 1)] = p[2];
    j[(3, 2)] = p[3];
    j[(3, 3)] = p[0];
    j
}

/// Ten body parameters of a pseudo-inertia (inverse of [`pseudo_inertia`]).
fn parameters_of_pseudo_inertia(j: &Matrix4<f64>) -> [f64; 10] {
    let s = j.fixed_view::<3, 3>(0, 0);
    // I = tr(Σ) 1 − Σ.
    let i = nalgebra::Matrix3::identity() * s.trace() - s;
    let h = nalgebra::Vector3::new(j[(0, 3)], j[(1, 3)], j[(2, 3)]);
    pack_parameters(j[(3, 3)], &h, &i)
}

/// Log-Cholesky coordinates (10 numbers) → pseudo-inertia `J = U Uᵀ`, `U` upper triangular
/// with diagonal `e^{θ}` (Rucker & Wensing 2022): every coordinate vector is a physically
/// consistent body, and every body with a positive-definite `J` has coordinates.
fn pseudo_inertia_of_log_cholesky(t: &[f64]) -> Matrix4<f64> {
    let u = Matrix4::new(
        t[0].exp(),
        t[4],
        t[5],
        t[6],
        0.0,
        t[1].exp(),
        t[7],
        t[8],
        0.0,
        0.0,
        t[2].exp(),
        t[9],
        0.0,
        0.0,
        0.0,
        t[3].exp(),
    );
    u * u.transpose()
}

/// Log-Cholesky coordinates of a positive-definite pseudo-inertia (its `U Uᵀ` factorisation).
fn log_cholesky_of_pseudo_inertia(j: &Matrix4<f64>) -> Option<[f64; 10]> {
    // U Uᵀ with U upper triangular: Cholesky of the row/column-reversed matrix.
    let rev = Matrix4::from_fn(|r, c| j[(3 - r, 3 - c)]);
    let l = rev.cholesky()?.l();
    let u = Matrix4::from_fn(|r, c| l[(3 - r, 3 - c)]);
    Some([
        u[(0, 0)].ln(),
        u[(1, 1)].ln(),
        u[(2, 2)].ln(),
        u[(3, 3)].ln(),
        u[(0, 1)],
        u[(0, 2)],
        u[(0, 3)],
        u[(1, 2)],
        u[(1, 3)],
        u[(2, 3)],
    ])
}

/// Whether ten body parameters describe a physically consistent body: positive mass and a
/// positive-semidefinite pseudo-inertia (to `1e-12` of its trace), which is the mass
/// distribution of a real body (Wensing, Kim & Slotine 2017); it implies the triangle
/// inequalities of the rotational inertia about the centre of mass.
pub fn is_physically_consistent(p: &[f64]) -> bool {
    let j = pseudo_inertia(p);
    let eig = j.symmetric_eigenvalues();
    let scale = j.trace().abs().max(f64::MIN_POSITIVE);
    p[0] > 0.0 && eig.iter().all(|e| *e >= -1e-12 * scale)
}

/// The physically consistent estimate: standard parameters `π` with every body's
/// pseudo-inertia positive definite (and friction coefficients non-negative) minimising
/// `‖R K π − z‖² + λ ‖D (π − π₀)‖²` — the torque least-squares cost of the log (`R`, `z` from
/// [`LeastSquares::factor`]) plus a small pull (`λ = 1e-6` relative) towards the model's own
/// parameters `π₀` that fixes the directions the log cannot see (`D` scales each parameter by
/// its body's mass and size). Solved by Levenberg–Marquardt over the log-Cholesky coordinates
/// of Rucker & Wensing (2022), 10 per body, and `fv = e^{θ}`, `fc = e^{θ}` per joint.
/// Returns the standard parameters; their base parameters are `K π`.
///
/// # Errors
/// `Numerical` when the iteration does not produce a finite cost.
pub fn physical_estimate(
    model: &Model,
    base: &BaseParameters,
    r: &DMatrix<f64>,
    z: &DVector<f64>,
) -> Result<DVector<f64>> {
    let nb = model.nbodies();
    let nj = model.nv();
    let friction = base.friction;
    let p = base.standard_names.len();
    let k = base.combination_matrix();
    let rk = r * &k;
    // Starting point and prior: the model's parameters, made strictly consistent.
    let pi0 = standard_parameters(model, friction);
    let mut theta = Vec::with_capacity(p);
    let mut scale = DVector::zeros(p);
    for b in 0..nb {
        let pb: Vec<f64> = pi0.rows(10 * b, 10).iter().copied().collect();
        let m = pb[0].abs().max(1e-3);
        let size = {
            let tr = pb[4] + pb[6] + pb[9];
            (tr / m).abs().sqrt().max(0.05)
        };
        let mut j = pseudo_inertia(&pb);
        j += Matrix4::identity() * (1e-6 * m * size * size);
        j[(3, 3)] += 1e-6 * m;
        let t = log_cholesky_of_pseudo_inertia(&j).unwrap_or_else(|| {
            let mut t = [0.0; 10];
            t[0] = (0.1 * size * m.sqrt()).ln();
            t[1] = t[0];
            t[2] = t[0];
            t[3] = m.sqrt().ln();
            t
        });
        theta.extend_from_slice(&t);
        scale[10 * b] = 1.0 / m;
        for c in 1..4 {
            scale[10 * b + c] = 1.0 / (m * size);
        }
        for c in 4..10 {
            scale[10 * b + c] = 1.0 / (m * size * size);
        }
    }
    if friction {
        for i in 0..nj {
            theta.push(pi0[10 * nb + 2 * i].max(1e-6).ln());
            theta.push(pi0[10 * nb + 2 * i + 1].max(1e-6).ln());
            scale[10 * nb + 2 * i] = 1.0;
            scale[10 * nb + 2 * i + 1] = 1.0;
        }
    }
    let to_standard = |t: &[f64]| -> DVector<f64> {
        let mut pi = DVector::zeros(p);
        for b in 0..nb {
            let j = pseudo_inertia_of_log_cholesky(&t[10 * b..10 * b + 10]);
            pi.rows_mut(10 * b, 10)
                .copy_from_slice(&parameters_of_pseudo_inertia(&j));
        }
        if friction {
            for c in 0..2 * nj {
                pi[10 * nb + c] = t[10 * nb + c].exp();
            }
        }
        pi
    };
    let data_scale = z.norm().max(1e-12);
    let lambda = 1e-6 * data_scale;
    let residual = |t: &[f64]| -> DVector<f64> {
        let pi = to_standard(t);
        let mut res = DVector::zeros(rk.nrows() + p);
        res.rows_mut(0, rk.nrows()).copy_from(&(&rk * &pi - z));
        let prior = (&pi - &pi0).component_mul(&scale) * lambda;
        res.rows_mut(rk.nrows(), p).copy_from(&prior);
        res
    };
    // Jacobian = [R K; λ D] ∂π/∂θ, with ∂π/∂θ block diagonal (10 × 10 per body by central
    // differences of the log-Cholesky map, e^θ on the friction diagonal).
    let mut lin = DMatrix::zeros(rk.nrows() + p, p);
    lin.rows_mut(0, rk.nrows()).copy_from(&rk);
    for c in 0..p {
        lin[(rk.nrows() + c, c)] = lambda * scale[c];
    }
    let dpi = |t: &[f64]| -> DMatrix<f64> {
        let mut d = DMatrix::zeros(p, p);
        for b in 0..nb {
            for c in 0..10 {
                let mut tp = [0.0; 10];
                tp.copy_from_slice(&t[10 * b..10 * b + 10]);
                let mut tm = tp;
                let h = 1e-6 * tp[c].abs().max(1.0);
                tp[c] += h;
                tm[c] -= h;
                let fp = parameters_of_pseudo_inertia(&pseudo_inertia_of_log_cholesky(&tp));
                let fm = parameters_of_pseudo_inertia(&pseudo_inertia_of_log_cholesky(&tm));
                for r in 0..10 {
                    d[(10 * b + r, 10 * b + c)] = (fp[r] - fm[r]) / (2.0 * h);
                }
            }
        }
        if friction {
            for c in 0..2 * nj {
                d[(10 * nb + c, 10 * nb + c)] = t[10 * nb + c].exp();
            }
        }
        d
    };
    let mut res = residual(&theta);
    let mut cost = res.norm_squared();
    let mut mu = 1e-3;
    for _ in 0..100 {
        let jac = &lin * dpi(&theta);
        let g = jac.tr_mul(&res);
        let h = jac.tr_mul(&jac);
        let mut improved = false;
        for _ in 0..20 {
            let mut a = h.clone();
            for i in 0..p {
                a[(i, i)] += mu * h[(i, i)].max(1e-12);
            }
            let Some(ch) = a.cholesky() else {
                mu *= 10.0;
                continue;
            };
            let step = ch.solve(&(-&g));
            let cand: Vec<f64> = theta.iter().zip(step.iter()).map(|(t, s)| t + s).collect();
            let r2 = residual(&cand);
            let c2 = r2.norm_squared();
            if c2.is_finite() && c2 < cost {
                let done = (cost - c2) <= 1e-10 * cost;
                theta = cand;
                res = r2;
                cost = c2;
                mu = (mu / 3.0).max(1e-12);
                improved = !done;
                break;
            }
            mu *= 10.0;
        }
        if !improved {
            break;
        }
    }
    if !cost.is_finite() {
        return Err(Error::Numerical(
            "the physically consistent estimate did not converge".into(),
        ));
    }
    Ok(to_standard(&theta))
}

/// The ten parameters of body `b` within a standard parameter vector, as a spatial inertia.
pub fn body_inertia(standard: &DVector<f64>, b: usize) -> crate::spatial::SpatialInertia {
    let mut p = [0.0; 10];
    p.copy_from_slice(standard.rows(10 * b, 10).as_slice());
    inertia_from_parameters(&p)
}

/// The parameters of one body as stored in a model (re-export of [`body_parameters`] for
/// `f64`).
pub fn model_body_parameters(model: &Model, b: usize) -> [f64; 10] {
    body_parameters(&model.bodies()[b].inertia)
}

/// A finite Fourier series per joint, the exciting trajectory of Swevers et al. (1997):
/// `q_i(t) = q0_i + Σ_{l=1}^{L} (a_il / (l ω_f)) sin(l ω_f t) − (b_il / (l ω_f)) cos(l ω_f t)`,
/// periodic with period `2π/ω_f`, with `q̇` and `q̈` in closed form.
#[derive(Clone, Debug)]
pub struct FourierTrajectory {
    /// `ω_f` (rad/s).
    pub base_frequency: f64,
    /// `q0_i`.
    pub offset: Vec<f64>,
    /// `a_il`, joint-major (`L` per joint).
    pub sine: Vec<Vec<f64>>,
    /// `b_il`.
    pub cosine: Vec<Vec<f64>>,
}

impl FourierTrajectory {
    /// A random exciting trajectory for `model`: `harmonics` terms per joint at base frequency
    /// `base_frequency` (rad/s), coefficients drawn uniformly from `seed`, then scaled per joint
    /// so that the motion stays within 80 % of the joint's range (limits clamped to ±π) around
    /// its middle and within 80 % of its velocity limit when it has one.
    ///
    /// # Errors
    /// `InvalidArgument` for zero harmonics or a non-positive or non-finite frequency.
    ///
    /// ```
    /// use screwdyn::identification::FourierTrajectory;
    /// let m = screwdyn::builtin::planar2();
    /// let f = FourierTrajectory::random(&m, 5, 0.6, 3).unwrap();
    /// let (q, v, a) = f.sample(1.0);
    /// let (q2, _, _) = f.sample(1.0 + 2.0 * std::f64::consts::PI / 0.6);
    /// assert!((q[0] - q2[0]).abs() < 1e-9 && v.len() == 2 && a.len() == 2);
    /// ```
    pub fn random(model: &Model, harmonics: usize, base_frequency: f64, seed: u64) -> Result<Self> {
        if harmonics == 0 {
            return Err(Error::InvalidArgument(
                "an exciting trajectory needs at least one harmonic".into(),
            ));
        }
        if !(base_frequency > 0.0 && base_frequency.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "the base frequency must be positive and finite, not {base_frequency}"
            )));
        }
        let mut rng = SplitMix(seed.wrapping_mul(0x2545_F491_4F6C_DD1D) ^ 0xF0_0F);
        let n = model.nv();
        let mut f = FourierTrajectory {
            base_frequency,
            offset: vec![0.0; n],
            sine: vec![vec![0.0; harmonics]; n],
            cosine: vec![vec![0.0; harmonics]; n],
        };
        for i in 0..n {
            let (lo, hi) = joint_range(model, i);
            let amp_limit = 0.4 * (hi - lo);
            f.offset[i] = 0.5 * (lo + hi);
            for l in 0..harmonics {
                f.sine[i][l] = rng.uniform(-1.0, 1.0);
                f.cosine[i][l] = rng.uniform(-1.0, 1.0);
            }
            // Bounds of |q − q0| and |q̇| over all t from the coefficients.
            let (mut qb, mut vb) = (0.0, 0.0);
            for l in 0..harmonics {
                let w = (l + 1) as f64 * base_frequency;
                let c = f.sine[i][l].hypot(f.cosine[i][l]);
                qb += c / w;
                vb += c;
            }
            let mut s = amp_limit / qb;
            let vlim = model.joints()[i].limits.velocity;
            if vlim.is_finite() && vlim > 0.0 {
                s = s.min(0.8 * vlim / vb);
            }
            for l in 0..harmonics {
                f.sine[i][l] *= s;
                f.cosine[i][l] *= s;
            }
        }
        Ok(f)
    }

    /// `(q, q̇, q̈)` at time `t`.
    pub fn sample(&self, t: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = self.offset.len();
        let (mut q, mut v, mut a) = (self.offset.clone(), vec![0.0; n], vec![0.0; n]);
        for i in 0..n {
            for (l, (&sa, &cb)) in self.sine[i].iter().zip(&self.cosine[i]).enumerate() {
                let w = (l + 1) as f64 * self.base_frequency;
                let (s, c) = (w * t).sin_cos();
                q[i] += sa / w * s - cb / w * c;
                v[i] += sa * c + cb * s;
                a[i] += -sa * w * s + cb * w * c;
            }
        }
        (q, v, a)
    }

    /// The period `2π / ω_f` (s).
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.base_frequency
    }
}

/// Joint accelerations from logged velocities: a Savitzky–Golay differentiator that fits a
/// quadratic in time, by least squares, to each joint's velocity over a sliding window of
/// `2k + 1` samples and returns the fitted slope (and value) at the window centre. It works
/// with uneven sampling, is zero-phase (centred), and keeps only `2k + 1` samples in memory:
/// push samples in time order; each push after the first `2k` returns the completed centre
/// sample. The first and last `k` samples of a log have no full window and are dropped.
#[derive(Clone, Debug)]
pub struct VelocityDifferentiator {
    half_window: usize,
    /// Ring of `(t, q, v, tau)`.
    window: std::collections::VecDeque<WindowSample>,
}

/// `(t, q, v, tau)` kept in the differentiator's window.
type WindowSample = (f64, Vec<f64>, Vec<f64>, Vec<f64>);

/// One sample rebuilt by [`VelocityDifferentiator`]: `q`, `τ` as logged, `q̇` smoothed and
/// `q̈` differentiated.
#[derive(Clone, Debug, PartialEq)]
pub struct FilteredSample {
    /// Time.
    pub t: f64,
    /// Positions (as logged).
    pub q: Vec<f64>,
    /// Velocities (fitted value at the window centre).
    pub v: Vec<f64>,
    /// Accelerations (fitted slope at the window centre).
    pub a: Vec<f64>,
    /// Torques (as logged).
    pub tau: Vec<f64>,
}

impl VelocityDifferentiator {
    /// A differentiator over `2 half_window + 1` samples.
    ///
    /// # Errors
    /// `InvalidArgument` for a zero half window (a quadratic needs three samples).
    pub fn new(half_window: usize) -> Result<Self> {
        if half_window == 0 {
            return Err(Error::InvalidArgument(
                "the differentiation window needs a half width of at least 1 sample".into(),
            ));
        }
        Ok(VelocityDifferentiator {
            half_window,
            window: std::collections::VecDeque::with_capacity(2 * half_window + 1),
        })
    }

    /// Adds a sample; returns the filtered centre sample once the window is full.
    ///
    /// # Errors
    /// `InvalidArgument` when time does not increase.
    pub fn push(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &[f64],
    ) -> Result<Option<FilteredSample>> {
        if let Some(last) = self.window.back() {
            if t.partial_cmp(&last.0) != Some(std::cmp::Ordering::Greater) {
                return Err(Error::InvalidArgument(format!(
                    "time must increase from row to row to differentiate velocities (t = {t} \
                     after t = {})",
                    last.0
                )));
            }
        }
        let size = 2 * self.half_window + 1;
        if self.window.len() == size {
            self.window.pop_front();
        }
        self.window
            .push_back((t, q.to_vec(), v.to_vec(), tau.to_vec()));
        if self.window.len() < size {
            return Ok(None);
        }
        let c = &self.window[self.half_window];
        let t0 = c.0;
        // Normal equations of the quadratic fit in s = t − t0 (scaled by the window span).
        let span = (self.window[size - 1].0 - self.window[0].0).max(f64::MIN_POSITIVE);
        let mut ata = nalgebra::Matrix3::zeros();
        for (t, ..) in &self.window {
            let s = (t - t0) / span;
            let row = nalgebra::Vector3::new(1.0, s, s * s);
            ata += row * row.transpose();
        }
        let Some(inv) = ata.try_inverse() else {
            return Err(Error::InvalidArgument(
                "the sample times of a differentiation window are degenerate".into(),
            ));
        };
        let n = v.len();
        let (mut vf, mut af) = (vec![0.0; n], vec![0.0; n]);
        for j in 0..n {
            let mut atb = nalgebra::Vector3::zeros();
            for (t, _, vv, _) in &self.window {
                let s = (t - t0) / span;
                atb += nalgebra::Vector3::new(1.0, s, s * s) * vv[j];
            }
            let coef = inv * atb;
            vf[j] = coef[0];
            af[j] = coef[1] / span;
        }
        Ok(Some(FilteredSample {
            t: t0,
            q: c.1.clone(),
            v: vf,
            a: af,
            tau: c.3.clone(),
        }))
    }
}

/// The joint torques a log of `model` would record at `(q, q̇, q̈)`: inverse dynamics plus the
/// joints' viscous and Coulomb friction, `τ = RNEA(q, q̇, q̈) + fv q̇ + fc sign(q̇)`. Written into
/// `tau`.
///
/// # Errors
/// As [`rnea`](crate::dynamics::rnea).
pub fn logged_torque(
    model: &Model,
    ws: &mut Workspace,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    tau: &mut [f64],
) -> Result<()> {
    let t = crate::dynamics::rnea(model, ws, q, v, a)?;
    for (i, j) in model.joints().iter().enumerate() {
        tau[i] = t[i] + j.damping * v[i] + j.friction * sign(v[i]);
    }
    Ok(())
}

/// Samples `traj` every `1 / rate` seconds over `[0, duration]` and calls `sink(t, q, q̇, q̈, τ)`
/// with the torques of [`logged_torque`] plus Gaussian noise of standard deviation `noise`
/// (Box–Muller from a deterministic generator seeded with `seed`): the log an identification
/// experiment along an exciting trajectory would record. Streams: nothing is stored.
///
/// # Errors
/// `InvalidArgument` for a non-positive or non-finite duration or rate, or a negative noise;
/// errors of `sink` are passed on.
///
/// ```
/// use screwdyn::identification::{excitation_log, FourierTrajectory};
/// let m = screwdyn::builtin::planar2();
/// let traj = FourierTrajectory::random(&m, 3, 1.0, 7).unwrap();
/// let mut rows = 0;
/// excitation_log(&m, &traj, 1.0, 100.0, 0.0, 1, |_, _, _, _, _| {
///     rows += 1;
///     Ok::<(), screwdyn::Error>(())
/// })
/// .unwrap();
/// assert_eq!(rows, 101);
/// ```
#[allow(clippy::type_complexity)]
pub fn excitation_log<E: From<Error>>(
    model: &Model,
    traj: &FourierTrajectory,
    duration: f64,
    rate: f64,
    noise: f64,
    seed: u64,
    mut sink: impl FnMut(f64, &[f64], &[f64], &[f64], &[f64]) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    if !(duration > 0.0 && duration.is_finite() && rate > 0.0 && rate.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "the duration and the sampling rate must be positive and finite (got {duration} s \
             and {rate} Hz)"
        ))
        .into());
    }
    if !(noise >= 0.0 && noise.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "the torque noise must be a non-negative standard deviation, not {noise}"
        ))
        .into());
    }
    let mut ws = Workspace::new(model);
    let mut rng = SplitMix(seed ^ 0xA5A5_5A5A_1234_5678);
    let mut tau = vec![0.0; model.nv()];
    let samples = (duration * rate).floor() as usize;
    for k in 0..=samples {
        let t = k as f64 / rate;
        let (q, v, a) = traj.sample(t);
        logged_torque(model, &mut ws, &q, &v, &a, &mut tau)?;
        if noise > 0.0 {
            for x in tau.iter_mut() {
                let u1 = rng.uniform(f64::MIN_POSITIVE, 1.0);
                let u2 = rng.uniform(0.0, 1.0);
                *x += noise * (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
            }
        }
        sink(t, &q, &v, &a, &tau)?;
    }
    Ok(())
}
