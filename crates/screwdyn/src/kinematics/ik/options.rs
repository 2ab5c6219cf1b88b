//! What the numerical solver is asked to do: the tasks (which frames, which axes) and the
//! options (tolerances, budget, damping, null-space objective, held joints).

use crate::error::{Error, Result};
use std::time::Duration;

/// One frame to place: its [`frame`](IkTask::frame) id and the weight of each axis of its pose
/// error, angular first (`ωx ωy ωz vx vy vz`, in the frame's own axes, see
/// [`IkSolver`](super::IkSolver)). A zero weight frees that axis: it is neither driven nor
/// checked.
///
/// ```
/// use screwdyn::kinematics::ik::IkTask;
/// assert_eq!(IkTask::pose(3).weights, [1.0; 6]);
/// assert_eq!(IkTask::position(3).weights, [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
/// // A 5-axis task: the tool may turn freely about its own z axis.
/// assert_eq!(IkTask::weighted(3, [1.0, 1.0, 0.0, 1.0, 1.0, 1.0]).weights[2], 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkTask {
    /// The frame id ([`Model::frame_id`](crate::Model::frame_id)).
    pub frame: usize,
    /// Weights of the error's axes `ωx ωy ωz vx vy vz` (rad and m are weighed as given: a
    /// weight of 1 on both makes 1 rad cost as much as 1 m).
    pub weights: [f64; 6],
}

impl IkTask {
    /// The full pose of `frame` (all six weights 1).
    pub fn pose(frame: usize) -> IkTask {
        IkTask {
            frame,
            weights: [1.0; 6],
        }
    }

    /// The position of `frame`'s origin only (orientation free).
    pub fn position(frame: usize) -> IkTask {
        IkTask {
            frame,
            weights: [0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        }
    }

    /// The orientation of `frame` only (position free).
    pub fn orientation(frame: usize) -> IkTask {
        IkTask {
            frame,
            weights: [1.0, 1.0, 1.0, 0.0, 0.0, 0.0],
        }
    }

    /// `frame` with the given axis weights (angular first).
    pub fn weighted(frame: usize, weights: [f64; 6]) -> IkTask {
        IkTask { frame, weights }
    }
}

/// Options of the numerical inverse kinematics ([`IkSolver`](super::IkSolver)). The defaults
/// (`IkOptions::default()`) are listed with each field.
///
/// ```
/// use screwdyn::kinematics::ik::IkOptions;
/// let o = IkOptions::default();
/// assert_eq!((o.position_tolerance, o.orientation_tolerance), (1e-6, 1e-6));
/// let strict = IkOptions { position_tolerance: 1e-9, max_restarts: 5, ..IkOptions::default() };
/// assert!(strict.validate().is_ok());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct IkOptions {
    /// Largest accepted distance between each frame's origin and its target (m). Default
    /// `1e-6`.
    pub position_tolerance: f64,
    /// Largest accepted rotation angle between each frame and its target (rad). Default `1e-6`.
    pub orientation_tolerance: f64,
    /// Iterations of one attempt before it is abandoned for a restart. Default `40`.
    pub max_iterations: usize,
    /// Random restarts after the first attempt. Default `50`.
    pub max_restarts: usize,
    /// Wall-clock budget of one solve, checked every iteration; `None` (the default) for none.
    pub time_limit: Option<Duration>,
    /// Seed of the random restarts (the same seed, the same answer). Default `0`.
    pub seed: u64,
    /// `w` of the error-scaled damping `λ = w E + λ_min`, with `E = ½ eᵀ W e` the weighted
    /// squared error. Default `0.1`.
    pub damping: f64,
    /// `λ_min` of the damping (bounds the step at a singularity). Default `1e-9`.
    pub min_damping: f64,
    /// Joints that keep their `q0` value (indices into `q`). Default none.
    pub held_joints: Vec<usize>,
    /// Gain of the secondary objective `½ ‖q − q_posture‖²` that redundant arms follow in the
    /// null space of their tasks. Default `0` (off: the damped least-squares steps already
    /// keep close to the start; a positive gain keeps closer to the posture at the price of
    /// slower convergence).
    pub posture_gain: f64,
    /// The posture `q_posture` (length `nq`); `None` (the default) for `q0`.
    pub posture: Option<Vec<f64>>,
    /// Gain of the secondary objective `½ Σ ((q_j − m_j)/r_j)²`, with `m_j` the middle and
    /// `r_j` the range of joint `j`'s limits, that keeps redundant arms away from their
    /// limits. Default `0` (off).
    pub limit_gain: f64,
    /// Start from the closed-form solution nearest `q0` when the arm has one (a single full
    /// pose task on a 6R arm with a spherical wrist or three parallel axes). Default `true`.
    pub closed_form: bool,
}

impl Default for IkOptions {
    fn default() -> Self {
        IkOptions {
            position_tolerance: 1e-6,
            orientation_tolerance: 1e-6,
            max_iterations: 40,
            max_restarts: 50,
            time_limit: None,
            seed: 0,
            damping: 0.1,
            min_damping: 1e-9,
            held_joints: Vec::new(),
            posture_gain: 0.0,
            posture: None,
            limit_gain: 0.0,
            closed_form: true,
        }
    }
}

impl IkOptions {
    /// Checks every number: tolerances positive and finite, gains and damping finite and not
    /// negative, `max_iterations` at least 1.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the option.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::IkOptions;
    /// let bad = IkOptions { position_tolerance: 0.0, ..IkOptions::default() };
    /// assert_eq!(
    ///     bad.validate().unwrap_err().to_string(),
    ///     "the IK option position_tolerance is 0, it must be positive and finite"
    /// );
    /// ```
    pub fn validate(&self) -> Result<()> {
        let positive = [
            ("position_tolerance", self.position_tolerance),
            ("orientation_tolerance", self.orientation_tolerance),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::InvalidArgument(format!(
                    "the IK option {name} is {v}, it must be positive and finite"
                )));
            }
        }
        let non_negative = [
            ("damping", self.damping),
            ("min_damping", self.min_damping),
            ("posture_gain", self.posture_gain),
            ("limit_gain", self.limit_gain),
        ];
        for (name, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::InvalidArgument(format!(
                    "the IK option {name} is {v}, it must be finite and not negative"
                )));
            }
        }
        if self.max_iterations == 0 {
            return Err(Error::InvalidArgument(
                "the IK option max_iterations is 0, it must be at least 1".into(),
            ));
        }
        if let Some(posture) = &self.posture {
            if let Some(k) = posture.iter().position(|v| !v.is_finite()) {
                return Err(Error::NonFinite {
                    what: "the IK option posture".into(),
                    index: k,
                    value: posture[k].to_string(),
                });
            }
        }
        Ok(())
    }
}
