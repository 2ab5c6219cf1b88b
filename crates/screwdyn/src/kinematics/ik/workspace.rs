//! `IkWorkspace`: every buffer one numerical solve needs, made once per solver.

use super::numerical::IkSolver;
use crate::error::{Error, Result};
use crate::workspace::Workspace;
use nalgebra::Matrix6xX;

/// The buffers of [`IkSolver::solve`]: made once with [`IkWorkspace::new`] for a solver, then
/// reused by every solve, which allocates nothing.
///
/// ```
/// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
/// let m = screwdyn::builtin::load("ur5").unwrap();
/// let solver = IkSolver::new(&m, &[IkTask::pose(m.frame_id("tool0").unwrap())], IkOptions::default()).unwrap();
/// let ws = IkWorkspace::new(&solver);
/// assert_eq!(ws.kinematics().pose_in_world.len(), 6);
/// ```
#[derive(Clone, Debug)]
pub struct IkWorkspace {
    /// Forward kinematics and the joints' screw axes of the current `q`.
    pub(super) kinematics: Workspace,
    /// One frame's body Jacobian `J_f^{f,0}`, 6 × nq.
    pub(super) jacobian: Matrix6xX<f64>,
    /// The weighted stacked Jacobian `W J` of every task, rows × active joints, row-major.
    pub(super) stacked: Vec<f64>,
    /// The weighted stacked error `W e`.
    pub(super) error: Vec<f64>,
    /// `Jᵀ W² J + λ I`, then its Cholesky factor (active × active, row-major).
    pub(super) normal: Vec<f64>,
    /// The right-hand side, then the step `Δθ` (one per active joint).
    pub(super) step: Vec<f64>,
    /// The secondary objective's step `d` (one per active joint).
    pub(super) secondary: Vec<f64>,
    /// The moving joints held on their limits for the current step.
    pub(super) locked: Vec<bool>,
    /// The iterate `θ` (nq).
    pub(super) q: Vec<f64>,
    /// The iterate before the last step (nq).
    pub(super) previous: Vec<f64>,
    /// The best `θ` found so far (nq).
    pub(super) best: Vec<f64>,
    /// The closed-form solutions, when the solver has a closed form.
    pub(super) solutions: [[f64; 6]; 8],
    /// The size this workspace was made for: (nq, rows, active joints).
    pub(super) shape: (usize, usize, usize),
}

impl IkWorkspace {
    /// The buffers for `solver`.
    pub fn new(solver: &IkSolver) -> IkWorkspace {
        let (nq, rows, cols) = solver.shape();
        IkWorkspace {
            kinematics: Workspace::new(solver.model()),
            jacobian: Matrix6xX::zeros(nq),
            stacked: vec![0.0; rows * cols],
            error: vec![0.0; rows],
            normal: vec![0.0; cols * cols],
            step: vec![0.0; cols],
            secondary: vec![0.0; cols],
            locked: vec![false; cols],
            q: vec![0.0; nq],
            previous: vec![0.0; nq],
            best: vec![0.0; nq],
            solutions: [[0.0; 6]; 8],
            shape: (nq, rows, cols),
        }
    }

    /// The kinematics workspace: after a solve, the forward kinematics of the returned `q`
    /// (`pose_in_world`).
    pub fn kinematics(&self) -> &Workspace {
        &self.kinematics
    }

    /// An error unless this workspace was made for `solver`.
    pub(super) fn check(&self, solver: &IkSolver) -> Result<()> {
        if self.shape != solver.shape() {
            return Err(Error::InvalidArgument(format!(
                "the IK workspace was made for another solver ({} joints, {} task rows, {} moving joints; this one has {:?}): make one with IkWorkspace::new",
                self.shape.0, self.shape.1, self.shape.2, solver.shape()
            )));
        }
        self.kinematics.check(solver.model())
    }
}
