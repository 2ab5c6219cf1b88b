//! Inverse kinematics: the joint angles that put a frame at a target pose.
//!
//! [`IkSolver`] is the numerical solver for any arm and any set of frames
//! (Levenberg–Marquardt with error-scaled damping, joint limits, random restarts, every answer
//! checked by forward kinematics); [`ClosedForm`] gives every exact solution of the 6R arms
//! that have a closed form (a spherical wrist, or three consecutive parallel axes), from the
//! Paden–Kahan subproblems, and is the numerical solver's first guess on those arms.

mod all_solutions;
mod batch;
mod closed_form;
mod lm;
mod numerical;
mod options;
mod pose_error;
mod reach;
mod restart;
mod result;
mod seed;
mod subproblems;
mod target;
mod workspace;

pub use all_solutions::IkSolution;
pub use batch::{IkJump, IkPath};
pub use closed_form::{ClosedForm, ClosedFormFamily};
pub use numerical::IkSolver;
pub use options::{IkOptions, IkTask};
pub use pose_error::ORTHONORMAL_TOLERANCE;
pub use result::{IkFailure, IkResult};
pub use target::{
    default_start, target_from_matrix, target_from_quaternion, BOTTOM_ROW_TOLERANCE,
    QUATERNION_TOLERANCE,
};
pub use workspace::IkWorkspace;
