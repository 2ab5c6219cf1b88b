//! Accelerations from logged velocities: a Savitzky–Golay differentiator over a sliding window.

use crate::error::{Error, Result};

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
