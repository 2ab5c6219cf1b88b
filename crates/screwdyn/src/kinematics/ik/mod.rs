//! Inverse kinematics: the joint angles that put a frame at a target pose.
//!
//! [`ClosedForm`] gives every exact solution of the 6R arms that have a closed form (a
//! spherical wrist, or three consecutive parallel axes), from the Paden–Kahan subproblems.

mod closed_form;
mod subproblems;

pub use closed_form::{ClosedForm, ClosedFormFamily};
