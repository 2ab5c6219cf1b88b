//! Streaming least squares for the base parameters: rows `[W_i | τ]` folded into a triangular
//! factor block by block, then the estimate, its standard deviations and the condition number.

use super::base_parameters::BaseParameters;
use super::parameters::full_regressor;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;
use nalgebra::{DMatrix, DVector};

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

    /// Adds one sample `(q, q̇, q̈, τ)`. The joints' armatures are taken as known (the
    /// model's): the row fitted is `Y π = τ − I_a q̈`.
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
        let joints = model.joints();
        for (i, t) in tau.iter().enumerate() {
            let row = self.pending_rows + i;
            for (c, &k) in self.base.independent.iter().enumerate() {
                self.pending[(row, c)] = self.full[(i, k)];
            }
            // The armature is known (the model's): fit Y π = τ − I_a q̈.
            self.pending[(row, r)] = *t - joints[i].armature * a[i];
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
