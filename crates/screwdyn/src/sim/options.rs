//! [`SimOptions`]: how to simulate, and the rules every option must meet.

use super::effects::JointEffects;
use super::integrate::Integrator;
use super::setting::{check, Range};
use crate::dynamics::ForwardMethod;
use crate::error::{Error, Result};
use crate::model::Model;

/// How to simulate. [`simulate`](super::simulate) and [`simulate_into`](super::simulate_into)
/// refuse options that break [`SimOptions::validate`]'s rules; nothing is silently adjusted.
#[derive(Clone, Debug, PartialEq)]
pub struct SimOptions {
    /// Simulated time (s), finite and `≥ 0`.
    pub duration: f64,
    /// Step (s), finite and `> 0`: the fixed step of Euler and RK4, the output interval of
    /// Dormand–Prince.
    pub dt: f64,
    /// Integration scheme.
    pub integrator: Integrator,
    /// Forward-dynamics algorithm.
    pub method: ForwardMethod,
    /// Joint effects.
    pub effects: JointEffects,
    /// Record every k-th step (1 = every step; 0 is refused).
    pub record_every: usize,
    /// Frames whose poses are recorded.
    pub frames: Vec<usize>,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            duration: 1.0,
            dt: 1e-3,
            integrator: Integrator::Rk4,
            method: ForwardMethod::Aba,
            effects: JointEffects::default(),
            record_every: 1,
            frames: Vec::new(),
        }
    }
}

impl SimOptions {
    /// Checks every option for a run of `model`: `dt` finite and positive, `duration` finite
    /// and non-negative, `record_every` at least 1, Dormand–Prince tolerances, the joint
    /// effects' settings ([`JointEffects::validate`]) and the recorded frames. The error
    /// names the field as it is spelled here (`dt`, `duration`, `record_every`,
    /// `effects.limit_time_constant`…).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for the first option that breaks its rule.
    ///
    /// ```
    /// use screwdyn::sim::SimOptions;
    /// let m = screwdyn::builtin::pendulum();
    /// assert!(SimOptions::default().validate(&m).is_ok());
    /// let e = SimOptions { record_every: 0, ..Default::default() }.validate(&m).unwrap_err();
    /// assert!(e.to_string().starts_with("record_every must be at least 1 (got 0)"));
    /// let e = SimOptions { dt: -1e-3, ..Default::default() }.validate(&m).unwrap_err();
    /// assert!(e.to_string().starts_with("dt must be positive (got -0.001)"));
    /// ```
    pub fn validate(&self, model: &Model) -> Result<()> {
        check(
            "dt",
            self.dt,
            Range::Positive,
            "the integration step in seconds",
        )?;
        check(
            "duration",
            self.duration,
            Range::NonNegative,
            "the simulated time in seconds",
        )?;
        if self.record_every == 0 {
            return Err(Error::InvalidArgument(
                "record_every must be at least 1 (got 0); it is the number of steps between \
                 recorded samples"
                    .into(),
            ));
        }
        self.integrator.validate()?;
        self.effects.validate()?;
        for &f in &self.frames {
            model.frame(f)?;
        }
        Ok(())
    }
}
