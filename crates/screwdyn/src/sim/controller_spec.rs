//! [`ControllerSpec`]: a controller described as data — its kind, target or reference, and
//! gains or `None` for the defaults — checked and built for a model in one call. The front
//! ends (CLI flags, Python objects) fill one in; the rules live here.

use super::controller::{
    ComputedTorque, ConstantTorque, Controller, PdGravity, TorqueSeries, ZeroTorque,
};
use super::trajectory::Trajectory;
use crate::error::Result;
use crate::model::Model;

/// Which controller to run, with the gains left to their defaults where `None`.
///
/// [`build`](ControllerSpec::build) checks every vector against the model (naming it: `kp`,
/// `kd`, `the PD target`, `the constant torque`, `torque series row k`) and fills in the
/// default gains, critically damped at
/// [`DEFAULT_NATURAL_FREQUENCY`](super::DEFAULT_NATURAL_FREQUENCY) `ω = 10` rad/s:
/// - PD + gravity: `K_p = ω² M_ii(target)`, `K_d = 2ω M_ii(target)`
///   ([`PdGravity::default_gains`]);
/// - computed torque: `K_p = ω²`, `K_d = 2ω` ([`ComputedTorque::default_gains`]).
///
/// ```
/// use screwdyn::sim::{simulate, ControllerSpec, SimOptions};
/// // PD + gravity compensation with the default gains holds the two-link arm at its target.
/// let m = screwdyn::builtin::planar2();
/// let spec = ControllerSpec::PdGravity { target: vec![0.5, -0.3], kp: None, kd: None };
/// let mut pd = spec.build(&m).unwrap();
/// let opts = SimOptions { duration: 3.0, record_every: 100, ..Default::default() };
/// let run = simulate(&m, &[0.0, 0.0], &[0.0, 0.0], pd.as_mut(), &[], &opts, &mut |_| {}).unwrap();
/// let q = run.q.last().unwrap();
/// assert!((q[0] - 0.5).abs() < 1e-3 && (q[1] + 0.3).abs() < 1e-3);
///
/// let bad = ControllerSpec::PdGravity { target: vec![0.0; 2], kp: Some(vec![1.0; 3]), kd: None };
/// assert!(bad.build(&m).err().unwrap().to_string().starts_with("kp has 3 values"));
/// ```
pub enum ControllerSpec {
    /// No actuation ([`ZeroTorque`]).
    Zero,
    /// The same torques at all times ([`ConstantTorque`]), one per joint.
    Constant(Vec<f64>),
    /// Torques at strictly increasing `times`, one row of joint torques per time, linearly
    /// interpolated ([`TorqueSeries`]).
    Series {
        /// Sample times (s).
        times: Vec<f64>,
        /// One torque per joint at each time.
        values: Vec<Vec<f64>>,
    },
    /// PD control to `target` with gravity compensation ([`PdGravity`]).
    PdGravity {
        /// The joint positions to hold.
        target: Vec<f64>,
        /// Proportional gains per joint (`None`: `ω² M_ii(target)`).
        kp: Option<Vec<f64>>,
        /// Derivative gains per joint (`None`: `2ω M_ii(target)`).
        kd: Option<Vec<f64>>,
    },
    /// Computed-torque control tracking `reference` ([`ComputedTorque`]).
    ComputedTorque {
        /// The trajectory to track.
        reference: Box<dyn Trajectory + Send>,
        /// Proportional gains per joint (`None`: `ω²`).
        kp: Option<Vec<f64>>,
        /// Derivative gains per joint (`None`: `2ω`).
        kd: Option<Vec<f64>>,
    },
}

impl std::fmt::Debug for ControllerSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ControllerSpec::Zero => f.write_str("Zero"),
            ControllerSpec::Constant(tau) => f.debug_tuple("Constant").field(tau).finish(),
            ControllerSpec::Series { times, values } => f
                .debug_struct("Series")
                .field("times", times)
                .field("values", values)
                .finish(),
            ControllerSpec::PdGravity { target, kp, kd } => f
                .debug_struct("PdGravity")
                .field("target", target)
                .field("kp", kp)
                .field("kd", kd)
                .finish(),
            ControllerSpec::ComputedTorque { reference, kp, kd } => {
                let reference = format!(
                    "a trajectory of {} joints over {} s",
                    reference.nq(),
                    reference.duration()
                );
                f.debug_struct("ComputedTorque")
                    .field("reference", &reference)
                    .field("kp", kp)
                    .field("kd", kd)
                    .finish()
            }
        }
    }
}

impl ControllerSpec {
    /// The controller for `model` (which it keeps a copy of where it needs one), with the
    /// default gains filled in.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) /
    /// [`Error::NonFinite`](crate::Error::NonFinite) for a vector that does not have one
    /// finite value per joint, named as above;
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) for torque series times that
    /// are missing or do not increase, or a reference with another number of joints.
    pub fn build(self, model: &Model) -> Result<Box<dyn Controller>> {
        Ok(match self {
            ControllerSpec::Zero => Box::new(ZeroTorque),
            ControllerSpec::Constant(tau) => {
                model.check_vector(&tau, "the constant torque")?;
                Box::new(ConstantTorque(tau))
            }
            ControllerSpec::Series { times, values } => {
                for (k, row) in values.iter().enumerate() {
                    model.check_vector(row, &format!("torque series row {}", k + 1))?;
                }
                Box::new(TorqueSeries::new(times, values)?)
            }
            ControllerSpec::PdGravity { target, kp, kd } => {
                model.check_vector(&target, "the PD target")?;
                let (kp, kd) = gains(model, kp, kd, || PdGravity::default_gains(model, &target))?;
                Box::new(PdGravity::new(model.clone(), target, kp, kd)?)
            }
            ControllerSpec::ComputedTorque { reference, kp, kd } => {
                let (kp, kd) = gains(model, kp, kd, || {
                    Ok(ComputedTorque::default_gains(model.nq()))
                })?;
                Box::new(ComputedTorque::new(model.clone(), reference, kp, kd)?)
            }
        })
    }
}

/// `kp` and `kd`, checked, with `defaults` (computed only when needed) where `None`.
fn gains(
    model: &Model,
    kp: Option<Vec<f64>>,
    kd: Option<Vec<f64>>,
    defaults: impl FnOnce() -> Result<(Vec<f64>, Vec<f64>)>,
) -> Result<(Vec<f64>, Vec<f64>)> {
    for (gain, name) in [(&kp, "kp"), (&kd, "kd")] {
        if let Some(g) = gain {
            model.check_vector(g, name)?;
        }
    }
    Ok(match (kp, kd) {
        (Some(kp), Some(kd)) => (kp, kd),
        (kp, kd) => {
            let (kp0, kd0) = defaults()?;
            (kp.unwrap_or(kp0), kd.unwrap_or(kd0))
        }
    })
}
