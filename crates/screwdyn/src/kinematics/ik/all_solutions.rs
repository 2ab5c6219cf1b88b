//! Every solution of an arm with a closed form: the closed-form branches shifted by whole
//! turns into the joint limits, each checked by forward kinematics (and refined by the
//! numerical iteration when the check fails), duplicates removed.

use super::numerical::IkSolver;
use super::result::IkResult;
use super::seed::shift_into_limits;
use super::workspace::IkWorkspace;
use crate::error::Result;
use crate::spatial::Se3;

/// Two solutions whose joints all agree within this (rad or m) are one.
const SAME: f64 = 1e-6;

/// One solution of [`IkSolver::solve_all`].
#[derive(Clone, Debug, PartialEq)]
pub struct IkSolution {
    /// The joint positions (length `nq`; joints the tasks do not need keep `q0`).
    pub q: Vec<f64>,
    /// Its check (always a success: failed branches are left out).
    pub result: IkResult,
}

impl IkSolver {
    /// Every solution for `target` of an arm with a closed form (up to 8 for a 6R arm with a
    /// spherical wrist or three parallel axes): each closed-form branch is shifted by whole
    /// turns into the joint limits (the shift nearest `q0`; a branch that no shift fits is
    /// left out), checked by forward kinematics as [`solve`](IkSolver::solve) checks its
    /// answer — if the check fails (round-off near a singularity), refined by the numerical
    /// iteration (one attempt, no restarts) and checked again — and kept if it succeeds and
    /// differs from those already kept. Sorted by distance from `q0`.
    ///
    /// For any other arm or task (no [`closed_form`](IkSolver::closed_form)), the one answer
    /// of [`solve`](IkSolver::solve), if it succeeds. Allocates the returned solutions.
    ///
    /// # Errors
    /// As [`solve`](IkSolver::solve).
    ///
    /// ```
    /// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
    /// use screwdyn::kinematics::{forward_kinematics, frame_pose};
    /// use screwdyn::{builtin, Workspace};
    /// let ur5 = builtin::load("ur5").unwrap();
    /// let tool = ur5.frame_id("tool0").unwrap();
    /// let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    /// let mut ws = IkWorkspace::new(&solver);
    /// let mut kin = Workspace::new(&ur5);
    /// forward_kinematics(&ur5, &mut kin, &[0.3, -1.2, 1.5, -0.4, 1.1, 0.7]).unwrap();
    /// let target = frame_pose(&ur5, &kin, tool).unwrap();
    /// let all = solver.solve_all(&mut ws, &target, &[0.0; 6]).unwrap();
    /// assert_eq!(all.len(), 8);
    /// for s in &all {
    ///     forward_kinematics(&ur5, &mut kin, &s.q).unwrap();
    ///     let pose = frame_pose(&ur5, &kin, tool).unwrap();
    ///     assert!((pose.translation - target.translation).norm() <= 1e-6);
    /// }
    /// ```
    pub fn solve_all(
        &self,
        ws: &mut IkWorkspace,
        target: &Se3,
        q0: &[f64],
    ) -> Result<Vec<IkSolution>> {
        let n = self.model.nq();
        let targets = std::slice::from_ref(target);
        let mut kept: Vec<IkSolution> = Vec::new();
        let Some(cf) = &self.closed_form else {
            let mut q = vec![0.0; n];
            let result = self.solve(ws, targets, q0, &mut q)?;
            if result.success {
                kept.push(IkSolution { q, result });
            }
            return Ok(kept);
        };
        // Checks the inputs before the closed form reads the target.
        ws.check(self)?;
        self.check_inputs(targets, q0, n)?;
        let mut solutions = [[0.0; 6]; 8];
        let count = cf.solve(target, &mut solutions);
        let joints = cf.joints();
        for theta in &solutions[..count] {
            let mut start = q0.to_vec();
            let fits = (0..6).all(|k| {
                let j = joints[k];
                match shift_into_limits(theta[k], q0[j], self.lower[j], self.upper[j]) {
                    Some(v) => {
                        start[j] = v;
                        true
                    }
                    None => false,
                }
            });
            if !fits {
                continue;
            }
            // A branch that forward kinematics confirms as it is (the closed form is exact to
            // round-off) needs no refinement.
            let (q, result) = match self.confirmed(ws, targets, &start)? {
                Some(result) => (start, result),
                None => {
                    let mut q = vec![0.0; n];
                    let result = self.solve_from(ws, targets, q0, &mut q, 0, Some(&start))?;
                    (q, result)
                }
            };
            let known = kept
                .iter()
                .any(|s| s.q.iter().zip(&q).all(|(a, b)| (a - b).abs() <= SAME));
            if result.success && !known {
                kept.push(IkSolution { q, result });
            }
        }
        let distance =
            |q: &[f64]| -> f64 { q.iter().zip(q0).map(|(a, b)| (a - b) * (a - b)).sum() };
        kept.sort_by(|a, b| distance(&a.q).total_cmp(&distance(&b.q)));
        Ok(kept)
    }
}
