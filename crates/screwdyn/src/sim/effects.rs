//! Joint effects added to the commanded torque: effort saturation, viscous damping, smoothed
//! Coulomb friction and position limits as a stiff spring–damper.

use crate::model::Model;

/// Which joint effects act, and how. The total joint torque is
///
/// ```text
/// τ = sat(τ_cmd, ±effort) − b q̇ − f tanh(q̇ / ε) + τ_limit
/// ```
///
/// with `b` (damping) and `f` (Coulomb friction) from the model, `ε` the friction smoothing
/// speed (so the ODE stays smooth and well posed), and, outside `[lower, upper]`,
/// `τ_limit = −k (q − bound) − d q̇` (a one-sided spring–damper stop).
///
/// ```
/// use screwdyn::sim::JointEffects;
/// let e = JointEffects::default();
/// assert!(e.saturate && e.damping && e.friction && e.position_limits);
/// assert!(JointEffects::none().total_torque_is_commanded());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointEffects {
    /// Clamp the commanded torque to the effort limits.
    pub saturate: bool,
    /// Viscous damping `−b q̇`.
    pub damping: bool,
    /// Coulomb friction `−f tanh(q̇/ε)`.
    pub friction: bool,
    /// Smoothing speed `ε` of the friction (rad/s or m/s).
    pub friction_smoothing: f64,
    /// Position limits as a spring–damper stop.
    pub position_limits: bool,
    /// Stop stiffness `k` (N·m/rad or N/m).
    pub limit_stiffness: f64,
    /// Stop damping `d` (N·m·s/rad or N·s/m).
    pub limit_damping: f64,
}

impl Default for JointEffects {
    fn default() -> Self {
        JointEffects {
            saturate: true,
            damping: true,
            friction: true,
            friction_smoothing: 1e-3,
            position_limits: true,
            limit_stiffness: 2000.0,
            limit_damping: 20.0,
        }
    }
}

impl JointEffects {
    /// No effects at all: the applied torque is the commanded torque.
    pub fn none() -> Self {
        JointEffects {
            saturate: false,
            damping: false,
            friction: false,
            position_limits: false,
            ..JointEffects::default()
        }
    }

    /// Whether every effect is off.
    pub fn total_torque_is_commanded(&self) -> bool {
        !(self.saturate || self.damping || self.friction || self.position_limits)
    }

    /// Writes the total joint torque for commanded `cmd` at state `(q, v)` into `tau`.
    pub fn apply(&self, model: &Model, q: &[f64], v: &[f64], cmd: &[f64], tau: &mut [f64]) {
        for (i, j) in model.joints().iter().enumerate() {
            let mut t = cmd[i];
            if self.saturate {
                t = t.clamp(-j.limits.effort, j.limits.effort);
            }
            if self.damping {
                t -= j.damping * v[i];
            }
            if self.friction && j.friction != 0.0 {
                t -= j.friction * (v[i] / self.friction_smoothing).tanh();
            }
            if self.position_limits {
                if q[i] > j.limits.upper {
                    t -= self.limit_stiffness * (q[i] - j.limits.upper) + self.limit_damping * v[i];
                } else if q[i] < j.limits.lower {
                    t -= self.limit_stiffness * (q[i] - j.limits.lower) + self.limit_damping * v[i];
                }
            }
            tau[i] = t;
        }
    }
}
