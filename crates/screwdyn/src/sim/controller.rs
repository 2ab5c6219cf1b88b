//! Torque inputs and controllers: zero, constant, an interpolated time series, PD with gravity
//! compensation, and computed-torque control; the [`Controller`] trait for your own.

use super::trajectory::Trajectory;
use crate::dynamics::{gravity_torque, inverse_dynamics};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;

/// Computes the commanded joint torques `τ(t, q, q̇)`; called at every integrator stage.
///
/// ```
/// use screwdyn::sim::Controller;
/// /// A spring pulling every joint to zero.
/// struct Spring(f64);
/// impl Controller for Spring {
///     fn torque(&mut self, _t: f64, q: &[f64], _v: &[f64], tau: &mut [f64]) -> screwdyn::Result<()> {
///         for i in 0..q.len() { tau[i] = -self.0 * q[i]; }
///         Ok(())
///     }
/// }
/// let mut tau = [0.0; 2];
/// Spring(10.0).torque(0.0, &[0.1, -0.2], &[0.0, 0.0], &mut tau).unwrap();
/// assert_eq!(tau, [-1.0, 2.0]);
/// ```
pub trait Controller {
    /// Writes the commanded torques for time `t` and state `(q, v)` into `tau`.
    fn torque(&mut self, t: f64, q: &[f64], v: &[f64], tau: &mut [f64]) -> Result<()>;
}

/// No actuation: the robot moves passively.
#[derive(Clone, Copy, Debug, Default)]
pub struct ZeroTorque;

impl Controller for ZeroTorque {
    fn torque(&mut self, _t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]) -> Result<()> {
        tau.fill(0.0);
        Ok(())
    }
}

/// The same torques at all times.
#[derive(Clone, Debug)]
pub struct ConstantTorque(pub Vec<f64>);

impl Controller for ConstantTorque {
    fn torque(&mut self, _t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]) -> Result<()> {
        tau.copy_from_slice(&self.0);
        Ok(())
    }
}

/// Torques sampled at increasing times, linearly interpolated, held constant outside.
///
/// ```
/// use screwdyn::sim::{Controller, TorqueSeries};
/// let mut s = TorqueSeries::new(vec![0.0, 1.0], vec![vec![0.0], vec![2.0]]).unwrap();
/// let mut tau = [0.0];
/// s.torque(0.25, &[0.0], &[0.0], &mut tau).unwrap();
/// assert_eq!(tau[0], 0.5);
/// ```
#[derive(Clone, Debug)]
pub struct TorqueSeries {
    times: Vec<f64>,
    values: Vec<Vec<f64>>,
}

impl TorqueSeries {
    /// From sample times (strictly increasing) and one torque vector per time.
    pub fn new(times: Vec<f64>, values: Vec<Vec<f64>>) -> Result<Self> {
        if times.is_empty() || times.len() != values.len() {
            return Err(Error::InvalidModel(format!(
                "a torque series needs one torque vector per time (got {} times, {} vectors)",
                times.len(),
                values.len()
            )));
        }
        if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
            return Err(Error::InvalidModel(format!(
                "torque series times must increase strictly (row {} has t = {} after t = {})",
                k + 2,
                times[k + 1],
                times[k]
            )));
        }
        Ok(TorqueSeries { times, values })
    }
}

impl Controller for TorqueSeries {
    fn torque(&mut self, t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]) -> Result<()> {
        let n = self.times.len();
        let k = self.times.partition_point(|&tk| tk <= t);
        if k == 0 {
            tau.copy_from_slice(&self.values[0]);
        } else if k == n {
            tau.copy_from_slice(&self.values[n - 1]);
        } else {
            let s = (t - self.times[k - 1]) / (self.times[k] - self.times[k - 1]);
            for (i, x) in tau.iter_mut().enumerate() {
                *x = (1.0 - s) * self.values[k - 1][i] + s * self.values[k][i];
            }
        }
        Ok(())
    }
}

/// PD control to a fixed target with gravity compensation:
/// `τ = K_p (q_d − q) − K_d q̇ + g(q)` (seed 000's `g(θ)`, from the controller's own model).
#[derive(Clone, Debug)]
pub struct PdGravity {
    model: Model,
    ws: Workspace,
    target: Vec<f64>,
    kp: Vec<f64>,
    kd: Vec<f64>,
}

impl PdGravity {
    /// Gains per joint; `model` is the controller's model (it may differ from the plant).
    pub fn new(model: Model, target: Vec<f64>, kp: Vec<f64>, kd: Vec<f64>) -> Result<Self> {
        model.check_vector(&target, "the PD target")?;
        model.check_vector(&kp, "kp")?;
        model.check_vector(&kd, "kd")?;
        let ws = Workspace::new(&model);
        Ok(PdGravity {
            model,
            ws,
            target,
            kp,
            kd,
        })
    }
}

impl Controller for PdGravity {
    fn torque(&mut self, _t: f64, q: &[f64], v: &[f64], tau: &mut [f64]) -> Result<()> {
        let g = gravity_torque(&self.model, &mut self.ws, q)?;
        for i in 0..tau.len() {
            tau[i] = self.kp[i] * (self.target[i] - q[i]) - self.kd[i] * v[i] + g[i];
        }
        Ok(())
    }
}

/// Computed-torque control tracking a trajectory:
/// `τ = M(q)(q̈_d + K_d (q̇_d − q̇) + K_p (q_d − q)) + C(q, q̇) q̇ + g(q)`, evaluated in one RNEA
/// call with the commanded acceleration. With an exact model the tracking error obeys
/// `ë + K_d ė + K_p e = 0`.
pub struct ComputedTorque {
    model: Model,
    ws: Workspace,
    reference: Box<dyn Trajectory>,
    kp: Vec<f64>,
    kd: Vec<f64>,
    qd: Vec<f64>,
    vd: Vec<f64>,
    ad: Vec<f64>,
    cmd: Vec<f64>,
}

impl ComputedTorque {
    /// Tracks `reference` with gains `kp`, `kd`, using the controller's own `model`.
    pub fn new(
        model: Model,
        reference: Box<dyn Trajectory>,
        kp: Vec<f64>,
        kd: Vec<f64>,
    ) -> Result<Self> {
        model.check_vector(&kp, "kp")?;
        model.check_vector(&kd, "kd")?;
        if reference.nq() != model.nq() {
            return Err(Error::InvalidModel(format!(
                "the reference trajectory has {} joints, the model has {}",
                reference.nq(),
                model.nq()
            )));
        }
        let n = model.nq();
        let ws = Workspace::new(&model);
        Ok(ComputedTorque {
            model,
            ws,
            reference,
            kp,
            kd,
            qd: vec![0.0; n],
            vd: vec![0.0; n],
            ad: vec![0.0; n],
            cmd: vec![0.0; n],
        })
    }
}

impl Controller for ComputedTorque {
    fn torque(&mut self, t: f64, q: &[f64], v: &[f64], tau: &mut [f64]) -> Result<()> {
        self.reference
            .sample(t, &mut self.qd, &mut self.vd, &mut self.ad);
        for i in 0..q.len() {
            self.cmd[i] =
                self.ad[i] + self.kd[i] * (self.vd[i] - v[i]) + self.kp[i] * (self.qd[i] - q[i]);
        }
        let out = inverse_dynamics(&self.model, &mut self.ws, q, v, &self.cmd, None)?;
        tau.copy_from_slice(out.as_slice());
        Ok(())
    }
}
