//! Torque inputs and controllers: zero, constant, an interpolated time series, PD with gravity
//! compensation, and computed-torque control; the [`Controller`] trait for your own.

use super::trajectory::Trajectory;
use crate::dynamics::{crba, gravity_torque, inverse_dynamics};
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

    /// Whether [`Controller::torque`] always writes zeros (no actuation): the simulator then
    /// keeps a zero torque and does not call it. `false` unless a controller says otherwise.
    ///
    /// ```
    /// use screwdyn::sim::{ConstantTorque, Controller, ZeroTorque};
    /// assert!(ZeroTorque.is_zero());
    /// assert!(!ConstantTorque(vec![0.0; 2]).is_zero());
    /// ```
    fn is_zero(&self) -> bool {
        false
    }
}

/// No actuation: the robot moves passively.
#[derive(Clone, Copy, Debug, Default)]
pub struct ZeroTorque;

impl Controller for ZeroTorque {
    fn torque(&mut self, _t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]) -> Result<()> {
        tau.fill(0.0);
        Ok(())
    }

    fn is_zero(&self) -> bool {
        true
    }
}

/// The same torques at all times.
#[derive(Clone, Debug)]
pub struct ConstantTorque(pub Vec<f64>);

impl Controller for ConstantTorque {
    fn torque(&mut self, _t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]) -> Result<()> {
        check_output_len("the constant torque", self.0.len(), tau)?;
        tau.copy_from_slice(&self.0);
        Ok(())
    }
}

/// `Err(InvalidArgument)` when a controller holding `len` torques is asked for `tau.len()`.
fn check_output_len(what: &str, len: usize, tau: &[f64]) -> Result<()> {
    if len != tau.len() {
        return Err(Error::InvalidArgument(format!(
            "{what} has {len} values, but the robot has {} joints",
            tau.len()
        )));
    }
    Ok(())
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
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) for no samples, rows of different lengths or times that do not increase strictly; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞.
    pub fn new(times: Vec<f64>, values: Vec<Vec<f64>>) -> Result<Self> {
        if times.is_empty() || times.len() != values.len() {
            return Err(Error::InvalidArgument(format!(
                "a torque series needs one torque vector per time (got {} times, {} vectors)",
                times.len(),
                values.len()
            )));
        }
        if let Some(k) = values.iter().position(|v| v.len() != values[0].len()) {
            return Err(Error::InvalidArgument(format!(
                "torque series row {} has {} values, the first has {}",
                k + 1,
                values[k].len(),
                values[0].len()
            )));
        }
        if let Some(k) = times.iter().position(|t| !t.is_finite()) {
            return Err(Error::NonFinite {
                what: "the torque series times".into(),
                index: k,
                value: format!("{:?}", times[k]),
            });
        }
        for (k, row) in values.iter().enumerate() {
            crate::model::check_finite(row, &format!("torque series row {}", k + 1))?;
        }
        if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
            return Err(Error::InvalidArgument(format!(
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
        check_output_len("the torque series", self.values[0].len(), tau)?;
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
/// `τ = K_p (q_d − q) − K_d q̇ + g(q)` (the `g(θ)`, from the controller's own model).
#[derive(Clone, Debug)]
pub struct PdGravity {
    model: Model,
    ws: Workspace,
    target: Vec<f64>,
    kp: Vec<f64>,
    kd: Vec<f64>,
}

/// The natural frequency (rad/s) of the default gains: each joint, seen alone with its own
/// inertia, responds like `ë + 2ζω ė + ω² e = 0` with `ω = 10` rad/s and `ζ = 1`.
pub const DEFAULT_NATURAL_FREQUENCY: f64 = 10.0;

impl PdGravity {
    /// Default gains for a PD controller around `target`: critically damped at
    /// [`DEFAULT_NATURAL_FREQUENCY`] on each joint's own inertia `M_ii(target)`,
    /// `K_p = ω² M_ii`, `K_d = 2ω M_ii` (100 and 20 times `M_ii`).
    ///
    /// # Errors
    /// As [`crba`](crate::dynamics::crba) for a bad `target`.
    ///
    /// ```
    /// use screwdyn::{builtin, sim::PdGravity};
    /// let m = builtin::planar2();
    /// let (kp, kd) = PdGravity::default_gains(&m, &[0.0, 0.0]).unwrap();
    /// // By hand: M_11 = 5, M_22 = 1 at θ2 = 0 (unit masses and lengths).
    /// assert_eq!((kp, kd), (vec![500.0, 100.0], vec![100.0, 20.0]));
    /// ```
    pub fn default_gains(model: &Model, target: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
        let mut ws = Workspace::new(model);
        let mm = crba(model, &mut ws, target)?;
        let w = DEFAULT_NATURAL_FREQUENCY;
        let diag = (0..model.nq()).map(|i| mm[(i, i)]);
        Ok((
            diag.clone().map(|d| w * w * d).collect(),
            diag.map(|d| 2.0 * w * d).collect(),
        ))
    }

    /// Gains per joint; `model` is the controller's model (it may differ from the plant).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch)/[`Error::NonFinite`](crate::Error::NonFinite) for a target or gain vector of the wrong length or with NaN/∞.
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
        self.model.check_vector(v, "v")?;
        check_output_len("PD control", self.target.len(), tau)?;
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
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch)/[`Error::NonFinite`](crate::Error::NonFinite) for a bad gain vector; [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the reference has another number of joints.
    pub fn new(
        model: Model,
        reference: Box<dyn Trajectory>,
        kp: Vec<f64>,
        kd: Vec<f64>,
    ) -> Result<Self> {
        model.check_vector(&kp, "kp")?;
        model.check_vector(&kd, "kd")?;
        if reference.nq() != model.nq() {
            return Err(Error::InvalidArgument(format!(
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

impl ComputedTorque {
    /// Default gains: `K_p = ω²`, `K_d = 2ω` per joint with ω =
    /// [`DEFAULT_NATURAL_FREQUENCY`], so the tracking error of each joint is critically damped
    /// (`ë + 20 ė + 100 e = 0`).
    ///
    /// ```
    /// let (kp, kd) = screwdyn::sim::ComputedTorque::default_gains(2);
    /// assert_eq!((kp, kd), (vec![100.0; 2], vec![20.0; 2]));
    /// ```
    pub fn default_gains(nq: usize) -> (Vec<f64>, Vec<f64>) {
        let w = DEFAULT_NATURAL_FREQUENCY;
        (vec![w * w; nq], vec![2.0 * w; nq])
    }
}

impl Controller for ComputedTorque {
    fn torque(&mut self, t: f64, q: &[f64], v: &[f64], tau: &mut [f64]) -> Result<()> {
        self.reference
            .sample(t, &mut self.qd, &mut self.vd, &mut self.ad)?;
        self.model.check_vector(q, "q")?;
        self.model.check_vector(v, "v")?;
        check_output_len("computed-torque control", self.cmd.len(), tau)?;
        for i in 0..q.len() {
            self.cmd[i] =
                self.ad[i] + self.kd[i] * (self.vd[i] - v[i]) + self.kp[i] * (self.qd[i] - q[i]);
        }
        let out = inverse_dynamics(&self.model, &mut self.ws, q, v, &self.cmd, None)?;
        tau.copy_from_slice(out.as_slice());
        Ok(())
    }
}
