//! Numerical inverse kinematics: Levenberg–Marquardt with error-scaled damping on the
//! body-frame pose error, joint limits kept at every step, seeded random restarts, and a final
//! check by forward kinematics.

use super::closed_form::ClosedForm;
use super::lm;
use super::options::{IkOptions, IkTask};
use super::pose_error::{body_error, check_target, measured};
use super::reach::Reach;
use super::restart::{sample_range, SplitMix};
use super::result::{IkFailure, IkResult};
use super::seed::nearest_closed_form;
use super::subproblems::wrap;
use super::workspace::IkWorkspace;
use crate::error::{Error, Result};
use crate::kinematics::{
    compute_joint_jacobians, forward_kinematics, frame_jacobian, frame_pose, Reference,
};
use crate::model::{JointKind, Model};
use crate::spatial::Se3;
use std::time::Instant;

/// An attempt stops when both errors are below this fraction of their tolerances.
const STOP_FRACTION: f64 = 1e-3;
/// An attempt is abandoned after this many iterations without a relative decrease of the
/// weighted error by [`PROGRESS`].
const STALL_ITERATIONS: usize = 8;
/// See [`STALL_ITERATIONS`].
const PROGRESS: f64 = 1e-3;
/// With a secondary objective, an attempt that meets its tasks goes on along their
/// self-motion until the secondary step is below this (rad or m).
const SECONDARY_STEP: f64 = 1e-6;
/// A refused step multiplies the damping by this; an accepted one divides it (down to 1).
const REFUSED: f64 = 4.0;
/// Polishing ends when the damping's multiplier exceeds this (no step lowers the error).
const MAX_MULTIPLIER: f64 = 1e12;

/// How an attempt (one run of the iteration from one start) ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum End {
    /// Both errors within the tolerances.
    Converged,
    /// The error stopped decreasing.
    Stalled,
    /// `max_iterations` reached while the error was still decreasing.
    OutOfIterations,
    /// The time limit passed.
    OutOfTime,
}

/// What the attempts of one solve share: the best `q` so far (in the workspace) and how it was
/// found.
struct Search {
    /// `max(position_error / tol, orientation_error / tol)` of the best `q`.
    best_score: f64,
    /// How the attempt that found the best `q` ended.
    best_end: End,
    /// Whether the current attempt improved the best.
    improved: bool,
    iterations: usize,
}

/// The numerical inverse kinematics of one or more frames of a model.
///
/// **Pose error.** For a frame at `T(θ) = (R, p)` and its target `T_d = (R_d, p_d)`, the
/// error is written in the frame's own axes, angular first:
/// `e = (log(Rᵀ R_d), Rᵀ (p_d − p))`. Its rotation part is that of the body twist
/// `V_b = log(T(θ)⁻¹ T_d)` of *Modern Robotics*' `IKinBody`; its translation part equals
/// `V_b`'s to first order and vanishes exactly when the positions agree (so position-only and
/// 5-axis tasks are exact). The body Jacobian `J_b(θ)` ([`frame_jacobian`] with
/// [`Reference::Local`]) maps `θ̇` to the body twist, so `J_b Δθ = e` to first order.
///
/// **Step.** With the tasks stacked and weighted (`W`, the [`IkTask::weights`]), the
/// Levenberg–Marquardt step with error-scaled damping (Sugihara 2011) is
/// `Δθ = (Jᵀ W² J + λ I)⁻¹ Jᵀ W² e`, `λ = w E + λ_min`, `E = ½ eᵀ W² e`: near the target the
/// damping vanishes and the step is Gauss–Newton's, quadratically convergent; far from it, or
/// near a singularity, the damping shortens the step. `IKinBody` is the undamped `Δθ = J_b⁺ V_b`.
/// For a redundant arm with a secondary objective ([`IkOptions::posture_gain`],
/// [`IkOptions::limit_gain`]), once the tasks are met within their tolerances each step also
/// carries `d = −k ∇h` in the null space of the tasks,
/// `Δθ = d + (Jᵀ W² J + λ I)⁻¹ Jᵀ W (W e − W J d)`, until `d` falls below `10⁻⁶`; the latest
/// `q` that meets the tasks is kept.
///
/// **Limits.** A joint on one of its limits whose descent direction `(Jᵀ W² e)_j` (or whose
/// step) points out of them is held for the step (its column left out, `Δθ_j = 0`), so that
/// the other joints make up for it. After each step every joint is put back within its limits
/// (`θ_j` clamped to `[lower, upper]`); a continuous joint (no limits) is wrapped to within `π`
/// of its `q0`.
/// Held joints and joints that move no task's frame keep their `q0`.
///
/// **Attempts.** The first attempt starts from `q0`, or from the closed-form solution nearest
/// `q0` when the arm has one ([`IkOptions::closed_form`]); that solution, when forward
/// kinematics confirms it within the tolerances and limits, is the answer with no iteration
/// at all. An attempt ends when both errors are
/// below `10⁻³` of their tolerances, when the error stops decreasing (8 iterations without a
/// relative decrease of `10⁻³`), or after [`IkOptions::max_iterations`]; then, unless the best
/// `q` so far is within the tolerances, the next attempt starts from joint values drawn
/// uniformly within the limits (`[−π, π]` for an unbounded rotation, `[−1, 1]` m for an
/// unbounded translation) by a generator seeded with [`IkOptions::seed`].
///
/// **Result.** The best `q` of all attempts is returned and checked by forward kinematics
/// (see [`IkResult`]). When no attempt met the tasks, that `q` is first polished by a monotone
/// descent (a step that raises the error is refused and the damping multiplied by 4, until no
/// step lowers it), so that the errors reported are those of the nearest pose.
///
/// ```
/// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
/// use screwdyn::kinematics::{forward_kinematics, frame_pose};
/// use screwdyn::{builtin, Workspace};
/// let panda = builtin::load("panda").unwrap();
/// let hand = panda.body_frame(6).unwrap();
/// let solver = IkSolver::new(&panda, &[IkTask::pose(hand)], IkOptions::default()).unwrap();
/// let mut ws = IkWorkspace::new(&solver);
/// // A target made by forward kinematics.
/// let mut kin = Workspace::new(&panda);
/// forward_kinematics(&panda, &mut kin, &[0.4, -0.3, 0.2, -2.0, 0.1, 1.8, 0.5]).unwrap();
/// let target = frame_pose(&panda, &kin, hand).unwrap();
/// let q0 = [0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0];
/// let mut q = [0.0; 7];
/// let result = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
/// assert!(result.success);
/// assert!(result.position_error <= 1e-6 && result.orientation_error <= 1e-6);
/// forward_kinematics(&panda, &mut kin, &q).unwrap();
/// assert!((frame_pose(&panda, &kin, hand).unwrap().translation - target.translation).norm() < 1e-6);
/// ```
#[derive(Clone, Debug)]
pub struct IkSolver {
    pub(super) model: Model,
    pub(super) tasks: Vec<IkTask>,
    pub(super) options: IkOptions,
    /// The joints the solver moves, ascending.
    pub(super) active: Vec<usize>,
    pub(super) lower: Vec<f64>,
    pub(super) upper: Vec<f64>,
    /// Continuous joints, wrapped to within π of `q0`.
    pub(super) wraps: Vec<bool>,
    /// Where restarts draw each joint from.
    pub(super) ranges: Vec<(f64, f64)>,
    /// More moving joints than weighed task axes.
    pub(super) redundant: bool,
    pub(super) closed_form: Option<ClosedForm>,
    /// Per task, the ball its frame's origin cannot leave, when the task weighs every
    /// position axis and the frame's chain has one ([`Reach::of`]).
    reach: Vec<Option<Reach>>,
}

impl IkSolver {
    /// A solver for `tasks` (each a frame of `model` and its axis weights) with `options`.
    /// Copies what it needs of the model.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for no task, a frame the model does not have, weights that
    /// are negative, not finite or all zero, a held joint the model does not have, a posture
    /// of the wrong length, options out of range ([`IkOptions::validate`]), or tasks that no
    /// joint moves.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask};
    /// let m = screwdyn::builtin::planar2();
    /// let tip = m.frame_id("link2").unwrap();
    /// assert!(IkSolver::new(&m, &[IkTask::position(tip)], IkOptions::default()).is_ok());
    /// let e = IkSolver::new(&m, &[IkTask::pose(42)], IkOptions::default()).unwrap_err();
    /// assert!(e.to_string().contains("frame"));
    /// ```
    pub fn new(model: &Model, tasks: &[IkTask], options: IkOptions) -> Result<IkSolver> {
        options.validate()?;
        if tasks.is_empty() {
            return Err(Error::InvalidArgument(
                "inverse kinematics needs at least one task (a frame and its target)".into(),
            ));
        }
        let n = model.nq();
        let mut moves = vec![false; n];
        for (t, task) in tasks.iter().enumerate() {
            let frame = model.frame(task.frame)?;
            if let Some(k) = task
                .weights
                .iter()
                .position(|w| !(w.is_finite() && *w >= 0.0))
            {
                return Err(Error::InvalidArgument(format!(
                    "IK task {t} (frame '{}') has weight {} on axis {k}: weights must be finite and not negative",
                    frame.name, task.weights[k]
                )));
            }
            if task.weights.iter().all(|&w| w == 0.0) {
                return Err(Error::InvalidArgument(format!(
                    "IK task {t} (frame '{}') has every weight zero: it constrains nothing",
                    frame.name
                )));
            }
            if let Some(body) = frame.body {
                for j in model.support(body)? {
                    moves[j] = true;
                }
            }
        }
        for &j in &options.held_joints {
            if j >= n {
                return Err(Error::InvalidArgument(format!(
                    "the held joint {j} does not exist: the model has {n} joints"
                )));
            }
            moves[j] = false;
        }
        if let Some(posture) = &options.posture {
            if posture.len() != n {
                return Err(model
                    .check_vector(posture, "the IK option posture")
                    .unwrap_err());
            }
        }
        let active: Vec<usize> = (0..n).filter(|&j| moves[j]).collect();
        if active.is_empty() {
            return Err(Error::InvalidArgument(
                "no joint moves the IK tasks' frames (they are on the base, or every joint that moves them is held)".into(),
            ));
        }
        let joints = model.joints();
        let lower: Vec<f64> = joints.iter().map(|j| j.limits.lower).collect();
        let upper: Vec<f64> = joints.iter().map(|j| j.limits.upper).collect();
        let wraps: Vec<bool> = joints
            .iter()
            .map(|j| {
                matches!(j.kind, JointKind::Continuous)
                    || (matches!(j.kind, JointKind::Revolute)
                        && j.limits.lower == f64::NEG_INFINITY
                        && j.limits.upper == f64::INFINITY)
            })
            .collect();
        let ranges = joints
            .iter()
            .map(|j| {
                let rotates = !matches!(j.kind, JointKind::Prismatic);
                sample_range(j.limits.lower, j.limits.upper, rotates)
            })
            .collect();
        let weighed_axes = tasks
            .iter()
            .map(|t| t.weights.iter().filter(|&&w| w != 0.0).count())
            .sum::<usize>();
        let full_single_pose = tasks.len() == 1 && tasks[0].weights.iter().all(|&w| w != 0.0);
        let closed_form = if options.closed_form && full_single_pose && active.len() == 6 {
            ClosedForm::detect(model, tasks[0].frame)?
                .filter(|cf| cf.joints().iter().all(|j| active.contains(j)))
        } else {
            None
        };
        let reach = tasks
            .iter()
            .map(|t| {
                if t.weights[3..].iter().all(|&w| w != 0.0) {
                    Reach::of(model, t.frame)
                } else {
                    Ok(None)
                }
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(IkSolver {
            reach,
            model: model.clone(),
            tasks: tasks.to_vec(),
            redundant: active.len() > weighed_axes,
            options,
            active,
            lower,
            upper,
            wraps,
            ranges,
            closed_form,
        })
    }

    /// The model the solver was made for.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The tasks, in the order targets are given.
    pub fn tasks(&self) -> &[IkTask] {
        &self.tasks
    }

    /// The options.
    pub fn options(&self) -> &IkOptions {
        &self.options
    }

    /// The joints the solver moves (those that move some task's frame, less the held ones),
    /// ascending.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask};
    /// let m = screwdyn::builtin::load("ur5").unwrap();
    /// let tool = m.frame_id("tool0").unwrap();
    /// let opts = IkOptions { held_joints: vec![5], ..IkOptions::default() };
    /// let solver = IkSolver::new(&m, &[IkTask::position(tool)], opts).unwrap();
    /// assert_eq!(solver.moving_joints(), [0, 1, 2, 3, 4]);
    /// ```
    pub fn moving_joints(&self) -> &[usize] {
        &self.active
    }

    /// The closed form the first attempt starts from, when the arm has one.
    pub fn closed_form(&self) -> Option<&ClosedForm> {
        self.closed_form.as_ref()
    }

    /// (nq, stacked rows, moving joints): what an [`IkWorkspace`] is sized by.
    pub(super) fn shape(&self) -> (usize, usize, usize) {
        (self.model.nq(), 6 * self.tasks.len(), self.active.len())
    }

    /// Solves for joint positions that put each task's frame at its target (`targets[t]` for
    /// `tasks()[t]`, poses in the world frame), starting from `q0`; writes them to `q_out` and
    /// reports how it went. Allocates nothing. An unreachable target is not an error: the
    /// result says `success: false`, and `q_out` holds the nearest pose found.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `ws` was made for another solver, the number of targets
    /// differs from the number of tasks, a target's rotation is not orthonormal (within
    /// `1e-9`), `q0` lies outside the joint limits or `q_out` has the wrong length;
    /// [`Error::NonFinite`] for NaN or infinity in a target or `q0`;
    /// [`Error::DimensionMismatch`] for a `q0` of the wrong length.
    pub fn solve(
        &self,
        ws: &mut IkWorkspace,
        targets: &[Se3],
        q0: &[f64],
        q_out: &mut [f64],
    ) -> Result<IkResult> {
        self.solve_from(ws, targets, q0, q_out, 0, None)
    }

    /// [`solve`](IkSolver::solve) with the random restarts drawn from `stream` of the seed;
    /// or, given a `start`, one attempt from there (no restarts).
    pub(super) fn solve_from(
        &self,
        ws: &mut IkWorkspace,
        targets: &[Se3],
        q0: &[f64],
        q_out: &mut [f64],
        stream: u64,
        start: Option<&[f64]>,
    ) -> Result<IkResult> {
        ws.check(self)?;
        self.check_inputs(targets, q0, q_out.len())?;
        let deadline = self.options.time_limit.map(|t| Instant::now() + t);
        let mut rng = SplitMix::new(self.options.seed, stream);
        ws.q.copy_from_slice(q0);
        ws.best.copy_from_slice(q0);
        let max_restarts = if start.is_some() {
            0
        } else {
            self.options.max_restarts
        };
        if let Some(start) = start {
            ws.q.copy_from_slice(start);
            self.project(&mut ws.q, q0);
        } else if let Some(cf) = &self.closed_form {
            let count = cf.solve(&targets[0], &mut ws.solutions);
            nearest_closed_form(
                cf,
                &ws.solutions[..count],
                q0,
                &self.lower,
                &self.upper,
                &mut ws.q,
            );
            // The closed form is exact to round-off: when forward kinematics confirms it, it
            // is the answer, without an iteration.
            q_out.copy_from_slice(&ws.q);
            if let Some(result) = self.confirmed(ws, targets, q_out)? {
                return Ok(result);
            }
        }
        let mut search = Search {
            best_score: f64::INFINITY,
            best_end: End::Stalled,
            improved: false,
            iterations: 0,
        };
        let mut restarts = 0;
        let out_of_time = loop {
            search.improved = false;
            let end = self.attempt(ws, targets, q0, deadline, &mut search, false)?;
            if search.improved {
                search.best_end = end;
            }
            let out_of_time = end == End::OutOfTime;
            if out_of_time || search.best_score <= 1.0 || restarts >= max_restarts {
                break out_of_time;
            }
            restarts += 1;
            ws.q.copy_from_slice(q0);
            for &j in &self.active {
                let (lo, hi) = self.ranges[j];
                ws.q[j] = rng.uniform(lo, hi);
            }
            self.project(&mut ws.q, q0);
        };
        if search.best_score > 1.0 && !out_of_time && start.is_none() {
            // No attempt met the tasks: descend monotonically from the best q to the nearest
            // pose (a refused step raises the damping), so that the reported errors are the
            // nearest pose's.
            ws.q.copy_from_slice(&ws.best);
            // How the search ended still says why it failed.
            let best_end = search.best_end;
            self.attempt(ws, targets, q0, deadline, &mut search, true)?;
            search.best_end = best_end;
        }
        q_out.copy_from_slice(&ws.best);
        let (position_error, orientation_error, within_limits) = self.verify(ws, targets, q_out)?;
        let success = position_error <= self.options.position_tolerance
            && orientation_error <= self.options.orientation_tolerance
            && within_limits;
        let failure = if success {
            None
        } else if self.beyond_reach(ws, targets, q_out)? {
            Some(IkFailure::Unreachable)
        } else if let Some(cf) = &self.closed_form {
            // Exact: the closed form has solutions (none of which fits the limits, or it would
            // have been the answer) or has none.
            if cf.solve(&targets[0], &mut ws.solutions) > 0 {
                Some(IkFailure::Limits)
            } else {
                Some(IkFailure::Unreachable)
            }
        } else if out_of_time || search.best_end == End::OutOfIterations {
            Some(IkFailure::Budget)
        } else if self.blocked_by_limits(ws, targets, q_out)? {
            Some(IkFailure::Limits)
        } else {
            Some(IkFailure::Unreachable)
        };
        Ok(IkResult {
            success,
            iterations: search.iterations,
            restarts,
            position_error,
            orientation_error,
            failure,
        })
    }

    /// One run of the iteration from `ws.q`, keeping the best `q` in `ws.best`.
    fn attempt(
        &self,
        ws: &mut IkWorkspace,
        targets: &[Se3],
        q0: &[f64],
        deadline: Option<Instant>,
        search: &mut Search,
        polish: bool,
    ) -> Result<End> {
        let o = &self.options;
        let mut lowest = f64::INFINITY;
        let mut stalled = 0;
        let secondary = self.redundant && (o.posture_gain > 0.0 || o.limit_gain > 0.0);
        // The damping's multiplier μ: λ = μ w E + λ_min; raised when a step is refused.
        let mut mu = 1.0;
        let mut previous_cost = f64::INFINITY;
        for iteration in 0..=o.max_iterations {
            let (mut position, mut orientation, mut cost) = self.evaluate(ws, targets)?;
            if polish && cost > previous_cost {
                // Polishing: a step that raised the error is refused; go back and damp more.
                ws.q.copy_from_slice(&ws.previous);
                (position, orientation, cost) = self.evaluate(ws, targets)?;
                mu *= REFUSED;
            } else {
                mu = f64::max(1.0, mu / REFUSED);
            }
            previous_cost = cost;
            ws.previous.copy_from_slice(&ws.q);
            let score =
                (position / o.position_tolerance).max(orientation / o.orientation_tolerance);
            // Among iterates that meet the tasks, the latest is best: the secondary objective
            // has moved it furthest.
            let met = score <= STOP_FRACTION;
            if score < search.best_score || met {
                search.best_score = score.max(STOP_FRACTION);
                search.improved = true;
                ws.best.copy_from_slice(&ws.q);
            }
            // d = −k ∇h once the tasks are met within their tolerances (a redundant arm then
            // moves along their self-motion), zero before and for other arms.
            let moving = secondary && score <= 1.0;
            self.secondary(&ws.q, q0, moving, &mut ws.secondary);
            let pull = ws.secondary.iter().fold(0.0, |m: f64, d| m.max(d.abs()));
            if met && pull <= SECONDARY_STEP {
                return Ok(End::Converged);
            }
            if iteration == o.max_iterations {
                break;
            }
            if met || polish {
                // Moving along the tasks' self-motion (the error is not expected to fall), or
                // polishing (every kept step lowers the error).
                if mu > MAX_MULTIPLIER {
                    return Ok(End::Stalled);
                }
            } else if cost < lowest * (1.0 - PROGRESS) {
                lowest = cost;
                stalled = 0;
            } else {
                stalled += 1;
                if stalled >= STALL_ITERATIONS {
                    return Ok(End::Stalled);
                }
            }
            if deadline.is_some_and(|d| Instant::now() >= d) {
                return Ok(End::OutOfTime);
            }
            // λ = w E + λ_min (error-scaled damping).
            let lambda = mu * o.damping * cost + o.min_damping;
            if !self.limited_step(ws, lambda) {
                return Ok(End::Stalled);
            }
            for (c, &j) in self.active.iter().enumerate() {
                ws.q[j] += ws.step[c];
            }
            self.project(&mut ws.q, q0);
            search.iterations += 1;
        }
        Ok(End::OutOfIterations)
    }

    /// The step over the joints free to move, into `ws.step`: a joint on one of its limits
    /// whose descent direction `(Jᵀ W² e)_c`, or whose step, points out of the limits is locked
    /// (its column left out, its step zero) and the step taken again without it, so that the
    /// other joints make up for it instead of the step being cut by the clamp (an active set,
    /// as in Bertsekas' projected Newton method). `false` when the normal matrix is singular.
    fn limited_step(&self, ws: &mut IkWorkspace, lambda: f64) -> bool {
        let cols = self.active.len();
        let rows = ws.error.len();
        let on_limit = |q: f64, j: usize, direction: f64| {
            !self.wraps[j]
                && ((q <= self.lower[j] && direction < 0.0)
                    || (q >= self.upper[j] && direction > 0.0))
        };
        for (c, &j) in self.active.iter().enumerate() {
            let g: f64 = (0..rows)
                .map(|r| ws.stacked[r * cols + c] * ws.error[r])
                .sum();
            ws.locked[c] = on_limit(ws.q[j], j, g);
        }
        // Each pass locks at least one more joint or ends.
        for _ in 0..=cols {
            if !lm::step(
                &ws.stacked,
                &ws.error,
                lambda,
                &ws.secondary,
                &ws.locked,
                &mut ws.normal,
                &mut ws.step,
            ) {
                return false;
            }
            let mut more = false;
            for (c, &j) in self.active.iter().enumerate() {
                if !ws.locked[c] && on_limit(ws.q[j], j, ws.step[c]) {
                    ws.locked[c] = true;
                    more = true;
                }
            }
            if !more {
                break;
            }
        }
        true
    }

    /// Forward kinematics and Jacobians at `ws.q`; fills the weighted stacked Jacobian and
    /// error; returns the largest position and orientation errors and `E = ½ eᵀ W² e`.
    fn evaluate(&self, ws: &mut IkWorkspace, targets: &[Se3]) -> Result<(f64, f64, f64)> {
        compute_joint_jacobians(&self.model, &mut ws.kinematics, &ws.q)?;
        let cols = self.active.len();
        let (mut position, mut orientation, mut cost) = (0.0_f64, 0.0_f64, 0.0);
        for (t, (task, target)) in self.tasks.iter().zip(targets).enumerate() {
            let pose = frame_pose(&self.model, &ws.kinematics, task.frame)?;
            frame_jacobian(
                &self.model,
                &ws.kinematics,
                task.frame,
                Reference::Local,
                &mut ws.jacobian,
            )?;
            let e = body_error(&pose, target);
            let (p, r) = measured(task, &e);
            position = position.max(p);
            orientation = orientation.max(r);
            for (k, &w) in task.weights.iter().enumerate() {
                let row = 6 * t + k;
                ws.error[row] = w * e[k];
                cost += 0.5 * ws.error[row] * ws.error[row];
                for (c, &j) in self.active.iter().enumerate() {
                    ws.stacked[row * cols + c] = w * ws.jacobian[(k, j)];
                }
            }
        }
        Ok((position, orientation, cost))
    }

    /// The secondary step `d = −k_p (θ − θ_posture) − k_l (θ − m) / r²` on the moving joints
    /// when `moving` (zero otherwise).
    fn secondary(&self, q: &[f64], q0: &[f64], moving: bool, d: &mut [f64]) {
        let o = &self.options;
        let posture = o.posture.as_deref().unwrap_or(q0);
        for (c, &j) in self.active.iter().enumerate() {
            d[c] = 0.0;
            if !moving {
                continue;
            }
            let mut offset = q[j] - posture[j];
            if self.wraps[j] {
                offset = wrap(offset);
            }
            d[c] -= o.posture_gain * offset;
            let (lo, hi) = (self.lower[j], self.upper[j]);
            if o.limit_gain > 0.0 && lo.is_finite() && hi.is_finite() && hi > lo {
                let range = hi - lo;
                d[c] -= o.limit_gain * (q[j] - 0.5 * (lo + hi)) / (range * range);
            }
        }
    }

    /// Puts every joint back within its limits; continuous joints within π of `q0`.
    fn project(&self, q: &mut [f64], q0: &[f64]) {
        for &j in &self.active {
            if self.wraps[j] {
                q[j] = q0[j] + wrap(q[j] - q0[j]);
            } else {
                q[j] = q[j].clamp(self.lower[j], self.upper[j]);
            }
        }
    }

    /// The result of `q` when forward kinematics confirms it (both tolerances, the limits),
    /// with no iteration taken; `None` otherwise.
    pub(super) fn confirmed(
        &self,
        ws: &mut IkWorkspace,
        targets: &[Se3],
        q: &[f64],
    ) -> Result<Option<IkResult>> {
        let (position_error, orientation_error, within_limits) = self.verify(ws, targets, q)?;
        let success = position_error <= self.options.position_tolerance
            && orientation_error <= self.options.orientation_tolerance
            && within_limits;
        Ok(success.then_some(IkResult {
            success,
            iterations: 0,
            restarts: 0,
            position_error,
            orientation_error,
            failure: None,
        }))
    }

    /// The final check, by forward kinematics of `q` alone: the largest position and
    /// orientation errors over the tasks and whether every joint is within its limits.
    fn verify(&self, ws: &mut IkWorkspace, targets: &[Se3], q: &[f64]) -> Result<(f64, f64, bool)> {
        forward_kinematics(&self.model, &mut ws.kinematics, q)?;
        let (mut position, mut orientation) = (0.0_f64, 0.0_f64);
        for (task, target) in self.tasks.iter().zip(targets) {
            let pose = frame_pose(&self.model, &ws.kinematics, task.frame)?;
            let (p, r) = measured(task, &body_error(&pose, target));
            position = position.max(p);
            orientation = orientation.max(r);
        }
        let within = q
            .iter()
            .zip(self.lower.iter().zip(&self.upper))
            .all(|(v, (lo, hi))| lo <= v && v <= hi);
        Ok((position, orientation, within))
    }

    /// Whether some task's target lies farther from its chain's first joint axis than the
    /// chain can reach ([`Reach`]), by more than the position tolerance.
    /// Leaves in `ws.kinematics` the screws and forward kinematics of `q`.
    fn beyond_reach(&self, ws: &mut IkWorkspace, targets: &[Se3], q: &[f64]) -> Result<bool> {
        compute_joint_jacobians(&self.model, &mut ws.kinematics, q)?;
        for (reach, target) in self.reach.iter().zip(targets) {
            if let Some(r) = reach {
                let beyond = r.beyond(&self.model, &ws.kinematics, &target.translation)?;
                if beyond > self.options.position_tolerance {
                    return Ok(true);
                }
            }
        }
        Ok(false)
    }

    /// Whether, at `q`, the error's descent direction `Jᵀ W² e` points mostly out of the limits
    /// of joints that sit on them.
    fn blocked_by_limits(&self, ws: &mut IkWorkspace, targets: &[Se3], q: &[f64]) -> Result<bool> {
        ws.q.copy_from_slice(q);
        self.evaluate(ws, targets)?;
        let cols = self.active.len();
        let rows = ws.error.len();
        let (mut blocked, mut free) = (0.0, 0.0);
        for (c, &j) in self.active.iter().enumerate() {
            let g: f64 = (0..rows)
                .map(|r| ws.stacked[r * cols + c] * ws.error[r])
                .sum();
            let at_lower = q[j] <= self.lower[j] && g < 0.0;
            let at_upper = q[j] >= self.upper[j] && g > 0.0;
            if at_lower || at_upper {
                blocked += g * g;
            } else {
                free += g * g;
            }
        }
        Ok(blocked > free)
    }

    pub(super) fn check_inputs(&self, targets: &[Se3], q0: &[f64], q_out_len: usize) -> Result<()> {
        if targets.len() != self.tasks.len() {
            return Err(Error::InvalidArgument(format!(
                "{} IK targets were given for {} tasks",
                targets.len(),
                self.tasks.len()
            )));
        }
        for (t, target) in targets.iter().enumerate() {
            check_target(target, t)?;
        }
        self.model.check_vector(q0, "q0")?;
        for (j, joint) in self.model.joints().iter().enumerate() {
            if !(self.lower[j] <= q0[j] && q0[j] <= self.upper[j]) {
                return Err(Error::InvalidArgument(format!(
                    "q0 of joint '{}' is {}, outside its limits [{}, {}]",
                    joint.name, q0[j], self.lower[j], self.upper[j]
                )));
            }
        }
        if q_out_len != self.model.nq() {
            return Err(Error::InvalidArgument(format!(
                "the IK output q has {} values, the model has {} joints",
                q_out_len,
                self.model.nq()
            )));
        }
        Ok(())
    }
}
