//! What a numerical inverse-kinematics solve reports.

/// Why a solve did not succeed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IkFailure {
    /// The target is out of reach: its position lies beyond the frame's reach bound (the
    /// farthest its origin can get from the chain's first joint axis, the sum of the distances
    /// between consecutive joint axes and from the last axis to the origin, for chains of
    /// revolute joints), or the arm's closed form has no solution, or, within that bound and
    /// without a closed form, the nearest pose found is a stationary point
    /// of the error that the limits do not block (or every attempt ended in a local minimum).
    /// The returned `q` is that nearest pose.
    Unreachable,
    /// The target is within reach but not within the limits: the arm's closed form has
    /// solutions, none within the limits, or (without a closed form) at the nearest pose found
    /// the error could only decrease further by moving joints beyond their limits.
    Limits,
    /// The iteration, restart or time budget ran out while the error was still decreasing.
    Budget,
}

impl IkFailure {
    /// A short lowercase word: `unreachable`, `limits` or `budget`.
    ///
    /// ```
    /// assert_eq!(screwdyn::kinematics::ik::IkFailure::Limits.name(), "limits");
    /// ```
    pub fn name(&self) -> &'static str {
        match self {
            IkFailure::Unreachable => "unreachable",
            IkFailure::Limits => "limits",
            IkFailure::Budget => "budget",
        }
    }
}

/// The outcome of [`IkSolver::solve`](super::IkSolver::solve); the joint positions themselves
/// are written to the caller's `q_out`.
///
/// `success` is set by a final check of the returned `q` alone: forward kinematics puts every
/// task's frame within [`position_tolerance`](super::IkOptions::position_tolerance) and
/// [`orientation_tolerance`](super::IkOptions::orientation_tolerance) of its target (on the
/// axes the task weighs) and every joint lies within its limits. The errors are those of
/// that check, for the returned `q`, whether it succeeded or not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkResult {
    /// The returned `q` reaches every target within the tolerances and the joint limits.
    pub success: bool,
    /// Iterations taken, over all attempts.
    pub iterations: usize,
    /// Random restarts taken (0 when the first attempt succeeded).
    pub restarts: usize,
    /// The largest distance between a frame's origin and its target (m), on the weighed
    /// axes.
    pub position_error: f64,
    /// The largest rotation angle between a frame and its target (rad), on the weighed axes.
    pub orientation_error: f64,
    /// Why the solve failed; `None` on success.
    pub failure: Option<IkFailure>,
}
