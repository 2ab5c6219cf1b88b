//! Torque residuals of an estimate on a log, per joint.

use super::base_parameters::BaseParameters;
use super::parameters::full_regressor;
use crate::error::Result;
use crate::model::Model;
use crate::workspace::Workspace;
use nalgebra::{DMatrix, DVector};

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

    /// The predicted torque `W_i π̂_b + I_a q̈` at one state (the joints' armatures known, the
    /// model's), written into `out`.
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
        // τ̂_i = (W π̂_b)_i + I_a,i q̈_i (the armature a known term, the model's).
        for (i, (o, j)) in out.iter_mut().zip(model.joints()).enumerate() {
            *o = base
                .independent
                .iter()
                .enumerate()
                .map(|(c, &k)| self.full[(i, k)] * values[c])
                .sum::<f64>()
                + j.armature * a[i];
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
