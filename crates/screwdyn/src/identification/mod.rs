//! Identification of inertial parameters: the standard parameters and their names, the base
//! (identifiable) parameters by QR with column pivoting, least squares from a log of states and
//! torques (streaming), a physically consistent estimate, exciting Fourier trajectories and the
//! differentiating filter used when a log has no accelerations.
//!
//! **Parameters.** `π` stacks the ten standard parameters of every moving body in joint order
//! (see [`body_parameters`](crate::dynamics::body_parameters): `m, mx, my, mz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`, first moment and
//! rotational inertia about the body frame origin, body-frame axes), optionally followed by two
//! friction parameters per joint, `fv` (viscous, N·m·s/rad or N·s/m) and `fc` (Coulomb), with
//! the joint torque `τ = Y(q, q̇, q̈) π_inertial + fv q̇ + fc sign(q̇) + I_a q̈`.
//!
//! **Armature.** The joints' armatures `I_a,i` (rotor inertias reflected to the joints) are not
//! estimated: they are a known term taken from the model, like a motor's data-sheet value.
//! [`LeastSquares`] fits `Y π = τ − I_a q̈` and [`Residuals`] predicts `Y π̂ + I_a q̈` (an armature
//! about a fixed vertical axis could not be told apart from the first link's `Izz` anyway).
//!
//! **Base parameters.** Some columns of the stacked regressor are zero or linear combinations
//! of others for every state. [`BaseParameters::new`] stacks the regressor at random states,
//! factors it `W P = Q R` by Householder QR with column pivoting, takes the numerical rank `r`
//! and writes the dependent columns as `W_d = W_i β` with `β = R₁₁⁻¹ R₁₂`; the base parameters
//! are `π_b = π_i + β π_d` (each an independent standard parameter plus a combination of the
//! dependent ones), and `τ = W_i π_b` exactly.
//!
//! **Least squares.** [`LeastSquares`] accumulates the rows `[W_i | τ]` of a log into an
//! upper-triangular factor (a QR update per block of samples: memory does not grow with the
//! log), then [`LeastSquares::solve`] returns `π̂_b = R⁻¹ z`, standard deviations
//! `σ √diag((RᵀR)⁻¹)` with `σ² = RSS / (rows − r)`, and the condition number of the
//! regressor.
//!
//! **Physically consistent estimate.** [`LeastSquares::physical_estimate`] constrains every
//! body to a real mass distribution (a positive-definite pseudo-inertia, see
//! [`is_physically_consistent`]) and friction to non-negative coefficients.
//!
//! **Defaults.** The base parameters are found from [`DEFAULT_STATES`] random states drawn
//! with [`DEFAULT_SEED`] ([`BaseParameters::with_defaults`]) unless a caller chooses others;
//! the command line and Python use these.
//!
//! Identification works on `f64` models (it is batch analysis over a log, not a per-call
//! algorithm); the regressor itself, [`regressor`](crate::dynamics::regressor), is generic
//! over the scalar type and allocation-free.

mod base_parameters;
mod differentiator;
mod excitation;
mod least_squares;
mod parameters;
mod physical;
mod random;
mod residuals;

pub use base_parameters::{BaseParameters, DEFAULT_SEED, DEFAULT_STATES};
pub use differentiator::{FilteredSample, VelocityDifferentiator};
pub use excitation::{excitation_log, FourierTrajectory};
pub use least_squares::{Estimate, LeastSquares};
pub use parameters::{full_regressor, parameter_count, parameter_names, standard_parameters};
pub use physical::{is_physically_consistent, physical_estimate, PhysicalEstimate};
pub use residuals::Residuals;
