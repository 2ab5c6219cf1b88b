//! Joint effects added to the commanded torque: effort saturation, viscous damping, joint
//! springs, smoothed Coulomb friction and position limits as a stiff spring–damper.

use super::setting::{check, Range};
use crate::dynamics::mass_matrix_inverse;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;

/// Which joint effects act, and how. The total joint torque is
///
/// ```text
/// τ = sat(τ_cmd, ±effort) − b q̇ − k (q − q_spring) − f tanh(q̇ / ε) + τ_limit
/// ```
///
/// with `b` (damping), `k` and `q_spring` (the joint spring's stiffness and rest position) and
/// `f` (Coulomb friction) from the model (the damping and spring terms are MuJoCo's passive
/// force `qfrc_passive` of a joint), `ε` the friction smoothing
/// speed (so the ODE stays smooth and well posed), and, outside `[lower, upper]`,
/// `τ_limit = −k (q − bound) − d q̇`: a one-sided spring–damper stop.
///
/// **The stop is scaled to the joint.** With `I` the inertia the joint moves when every other
/// joint is free (`1 / (M⁻¹)_ii`, taken at the configuration where the joint is in its stop —
/// the inertia a shoulder sees changes tenfold between an extended and a folded arm, and a stop
/// tuned for the first would make an explicit integrator diverge on the second; see
/// [`EffectGains::refresh_stops`]), time constant `T` and damping
/// ratio `ζ`, `k = I / T²` and `d = 2 ζ I / T`: every joint's stop behaves like a critically
/// damped (for `ζ = 1`) oscillator of period `2πT`, whether it holds a 0.2 kg wrist or a whole
/// arm. A joint hitting the stop at speed `w` goes in by `w T / e` (for `ζ = 1`), or bounces out
/// at `w e^{−ζπ/√(1−ζ²)}` (for `ζ < 1`). A fixed stiffness for all joints cannot work: stiff
/// enough to hold a shoulder, it is far too stiff for an explicit integrator on a wrist.
///
/// **Stability of fixed steps.** [`EffectGains::new`] keeps `T ≥ 4 dt` and raises `ε` to at
/// least `4 f dt / I`, so that the stiffest term of each joint (`d / I` and `f / (ε I)`) stays
/// well inside the stability region of the explicit integrators at step `dt`.
///
/// ```
/// use screwdyn::sim::JointEffects;
/// let e = JointEffects::default();
/// assert!(e.saturate && e.damping && e.springs && e.friction && e.position_limits);
/// assert_eq!((e.limit_time_constant, e.limit_damping_ratio), (0.01, 1.0));
/// assert!(JointEffects::none().total_torque_is_commanded());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointEffects {
    /// Clamp the commanded torque to the effort limits.
    pub saturate: bool,
    /// Viscous damping `−b q̇`.
    pub damping: bool,
    /// Joint springs `−k (q − q_spring)`.
    pub springs: bool,
    /// Coulomb friction `−f tanh(q̇/ε)`.
    pub friction: bool,
    /// Smoothing speed `ε` of the friction (rad/s or m/s); raised per joint where a fixed step
    /// needs it (see above).
    pub friction_smoothing: f64,
    /// Position limits as a spring–damper stop.
    pub position_limits: bool,
    /// Time constant `T` of the stop (s): `k = I/T²`, `d = 2ζI/T`; at least `4 dt` in use.
    pub limit_time_constant: f64,
    /// Damping ratio `ζ` of the stop (1 = critically damped, no bounce).
    pub limit_damping_ratio: f64,
}

impl Default for JointEffects {
    fn default() -> Self {
        JointEffects {
            saturate: true,
            damping: true,
            springs: true,
            friction: true,
            friction_smoothing: 1e-3,
            position_limits: true,
            limit_time_constant: 0.01,
            limit_damping_ratio: 1.0,
        }
    }
}

/// The per-joint constants of the effects for one simulation: stop stiffness `k_i` and damping
/// `d_i`, and friction smoothing `ε_i` (see [`JointEffects`]).
#[derive(Clone, Debug, PartialEq)]
pub struct EffectGains {
    /// `k_i = I_i / T²` (N·m/rad or N/m).
    pub stop_stiffness: Vec<f64>,
    /// `d_i = 2 ζ I_i / T` (N·m·s/rad or N·s/m).
    pub stop_damping: Vec<f64>,
    /// `ε_i = max(ε, 4 f_i dt / I_i)` (rad/s or m/s).
    pub friction_smoothing: Vec<f64>,
    /// The stop's time constant in use, `max(T, 4 dt)` (s).
    pub time_constant: f64,
    /// The stop's damping ratio `ζ`.
    pub damping_ratio: f64,
}

impl EffectGains {
    /// The gains of `effects` for `model`, scaled by the joint inertias `I_i = 1/(M⁻¹)_ii` at
    /// `q0`, for a step of `dt`. Errors name the bad setting.
    ///
    /// # Errors
    /// As [`JointEffects::validate`]; errors of [`mass_matrix_inverse`](crate::dynamics::mass_matrix_inverse) at `q0`.
    ///
    /// ```
    /// use screwdyn::sim::{EffectGains, JointEffects};
    /// // The 1 kg, 1 m pendulum moves I = m l² = 1 kg·m²: k = I/T², d = 2ζI/T.
    /// let m = screwdyn::builtin::pendulum();
    /// let g = EffectGains::new(&JointEffects::default(), &m, &[0.0], 1e-3).unwrap();
    /// assert!((g.stop_stiffness[0] - 1.0 / 0.01_f64.powi(2)).abs() < 1e-9);
    /// assert!((g.stop_damping[0] - 2.0 / 0.01).abs() < 1e-9);
    /// ```
    pub fn new(effects: &JointEffects, model: &Model, q0: &[f64], dt: f64) -> Result<Self> {
        let n = model.nq();
        let (t, zeta, eps) = (
            effects.limit_time_constant,
            effects.limit_damping_ratio,
            effects.friction_smoothing,
        );
        effects.validate()?;
        let needs_friction = effects.friction && model.joints().iter().any(|j| j.friction != 0.0);
        if !(effects.position_limits || needs_friction) {
            return Ok(EffectGains {
                stop_stiffness: vec![0.0; n],
                stop_damping: vec![0.0; n],
                friction_smoothing: vec![eps; n],
                time_constant: t.max(4.0 * dt),
                damping_ratio: zeta,
            });
        }
        let mut ws = Workspace::new(model);
        let minv = mass_matrix_inverse(model, &mut ws, q0)?;
        let inertia: Vec<f64> = (0..n).map(|i| 1.0 / minv[(i, i)]).collect();
        let t = t.max(4.0 * dt);
        Ok(EffectGains {
            stop_stiffness: inertia.iter().map(|i| i / (t * t)).collect(),
            stop_damping: inertia.iter().map(|i| 2.0 * zeta * i / t).collect(),
            friction_smoothing: model
                .joints()
                .iter()
                .zip(&inertia)
                .map(|(j, i)| eps.max(4.0 * j.friction * dt / i))
                .collect(),
            time_constant: t,
            damping_ratio: zeta,
        })
    }

    /// Re-tunes the stops of the joints that are beyond a position limit at `q` to the inertia
    /// they feel there, `I_i = 1 / (M⁻¹(q))_ii`: `k_i = I_i / T²`, `d_i = 2ζ I_i / T`. The
    /// simulator calls it whenever a joint is in its stop (`M⁻¹` costs O(n³) only then).
    ///
    /// # Errors
    /// As [`mass_matrix_inverse`] (a bad `q`, a workspace made for another model, a singular
    /// mass matrix).
    ///
    /// ```
    /// use screwdyn::sim::{EffectGains, JointEffects};
    /// use screwdyn::Workspace;
    /// let m = screwdyn::builtin::load("ur5").unwrap();
    /// let mut g = EffectGains::new(&JointEffects::default(), &m, &[0.0; 6], 1e-3).unwrap();
    /// let mut ws = Workspace::new(&m);
    /// let folded = [7.0, -2.5, 2.8, 0.0, 0.0, 0.0]; // the pan joint past its 2π limit
    /// let before = g.stop_stiffness[0];
    /// g.refresh_stops(&m, &mut ws, &folded).unwrap();
    /// assert!(g.stop_stiffness[0] < before); // a folded arm turns more easily about its base
    /// ```
    pub fn refresh_stops(&mut self, model: &Model, ws: &mut Workspace, q: &[f64]) -> Result<()> {
        let minv = mass_matrix_inverse(model, ws, q)?;
        let t = self.time_constant;
        for (i, j) in model.joints().iter().enumerate() {
            if q[i] > j.limits.upper || q[i] < j.limits.lower {
                let inertia = 1.0 / minv[(i, i)];
                self.stop_stiffness[i] = inertia / (t * t);
                self.stop_damping[i] = 2.0 * self.damping_ratio * inertia / t;
            }
        }
        Ok(())
    }

    /// Whether a joint is beyond one of its position limits at `q`.
    pub fn any_in_stop(model: &Model, q: &[f64]) -> bool {
        model
            .joints()
            .iter()
            .zip(q)
            .any(|(j, &x)| x > j.limits.upper || x < j.limits.lower)
    }
}

impl JointEffects {
    /// Checks the settings, whether or not their effect is switched on: the limit stops' time
    /// constant finite and positive, their damping ratio finite and non-negative, the friction
    /// smoothing speed finite and positive. The error names the field
    /// (`effects.limit_time_constant`, `effects.limit_damping_ratio`,
    /// `effects.friction_smoothing`).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for the first setting out of its range.
    ///
    /// ```
    /// use screwdyn::sim::JointEffects;
    /// assert!(JointEffects::default().validate().is_ok());
    /// let e = JointEffects { limit_time_constant: -1.0, ..JointEffects::none() };
    /// assert!(e.validate().unwrap_err().to_string()
    ///     .starts_with("effects.limit_time_constant must be positive (got -1)"));
    /// ```
    pub fn validate(&self) -> Result<()> {
        check(
            "effects.limit_time_constant",
            self.limit_time_constant,
            Range::Positive,
            "the time constant of the position-limit stops in seconds",
        )?;
        check(
            "effects.limit_damping_ratio",
            self.limit_damping_ratio,
            Range::NonNegative,
            "the damping ratio of the position-limit stops",
        )?;
        check(
            "effects.friction_smoothing",
            self.friction_smoothing,
            Range::Positive,
            "the speed in rad/s or m/s that smooths Coulomb friction",
        )
    }

    /// No effects at all: the applied torque is the commanded torque.
    pub fn none() -> Self {
        JointEffects {
            saturate: false,
            damping: false,
            springs: false,
            friction: false,
            position_limits: false,
            ..JointEffects::default()
        }
    }

    /// Whether every effect is off.
    pub fn total_torque_is_commanded(&self) -> bool {
        !(self.saturate || self.damping || self.springs || self.friction || self.position_limits)
    }

    /// Writes the total joint torque for commanded `cmd` at state `(q, v)` into `tau`, with the
    /// per-joint constants `gains` ([`EffectGains::new`]).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when a slice or the gains do not have one entry per joint.
    pub fn apply(
        &self,
        model: &Model,
        gains: &EffectGains,
        q: &[f64],
        v: &[f64],
        cmd: &[f64],
        tau: &mut [f64],
    ) -> Result<()> {
        let n = model.nq();
        let lens = [q.len(), v.len(), cmd.len(), tau.len()];
        let gains_n = [
            gains.stop_stiffness.len(),
            gains.stop_damping.len(),
            gains.friction_smoothing.len(),
        ];
        if lens.iter().chain(&gains_n).any(|&l| l != n) {
            return Err(Error::InvalidArgument(format!(
                "joint effects on {n} joints were given q, q̇, the command and τ of {:?} values and gains for {:?}",
                lens, gains_n
            )));
        }
        if self.total_torque_is_commanded() {
            tau.copy_from_slice(cmd);
            return Ok(());
        }
        for (i, j) in model.joints().iter().enumerate() {
            let mut t = cmd[i];
            if self.saturate {
                t = t.clamp(-j.limits.effort, j.limits.effort);
            }
            if self.damping {
                t -= j.damping * v[i];
            }
            // τ_spring = −k (q − q_spring)
            if self.springs && j.stiffness != 0.0 {
                t -= j.stiffness * (q[i] - j.springref);
            }
            if self.friction && j.friction != 0.0 {
                t -= j.friction * (v[i] / gains.friction_smoothing[i]).tanh();
            }
            if self.position_limits {
                let (k, d) = (gains.stop_stiffness[i], gains.stop_damping[i]);
                if q[i] > j.limits.upper {
                    t -= k * (q[i] - j.limits.upper) + d * v[i];
                } else if q[i] < j.limits.lower {
                    t -= k * (q[i] - j.limits.lower) + d * v[i];
                }
            }
            tau[i] = t;
        }
        Ok(())
    }
}
