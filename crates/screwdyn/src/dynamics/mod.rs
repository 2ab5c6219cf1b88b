//! Dynamics: inverse dynamics (RNEA), the stacked closed form, mass matrix, Coriolis, gravity,
//! forward dynamics, energies and Lagrangian coefficients.
//!
//! Every per-call algorithm reads a [`Model`](crate::Model), writes into a
//! [`Workspace`](crate::Workspace) and allocates nothing; the closed form and the Lagrangian
//! coefficients are teaching/reference code and allocate.
//!
//! ```
//! use screwdyn::{builtin, dynamics, Workspace};
//! let m = builtin::planar2();
//! let mut ws = Workspace::new(&m);
//! let (q, v, a) = ([0.3, 0.5], [1.0, -0.5], [0.2, 0.1]);
//! let tau = dynamics::rnea(&m, &mut ws, &q, &v, &a).unwrap().clone();
//! // τ = M q̈ + C q̇ + g, and forward dynamics inverts it.
//! let qdd = dynamics::forward_dynamics(&m, &mut ws, &q, &v, tau.as_slice(), None,
//!                                      dynamics::ForwardMethod::Aba).unwrap();
//! assert!((qdd[0] - a[0]).abs() < 1e-12 && (qdd[1] - a[1]).abs() < 1e-12);
//! ```

mod aba;
mod articulated_inverse;
mod cholesky;
mod classic_newton_euler;
mod closed_form;
mod coriolis;
mod crba;
mod derivatives;
pub(crate) mod energy;
mod forward;
mod inputs;
mod lagrange;
mod regressor;
mod rnea;
mod rnea_in_world;
mod trace;
mod wrenches;

pub use aba::aba;
pub(crate) use aba::singular as singular_articulated_inertia;
pub(crate) use articulated_inverse::ArticulatedSweep;
pub(crate) use cholesky::singular_threshold;
pub use classic_newton_euler::{classic_newton_euler, ClassicLink};
pub use closed_form::{closed_form, ClosedForm, MAX_CLOSED_FORM_JOINTS};
pub use coriolis::coriolis_matrix;
pub use crba::{crba, mass_matrix, mass_matrix_inverse};
pub use derivatives::{aba_derivatives, frame_velocity_derivatives, rnea_derivatives};
pub use energy::{
    center_of_mass, kinetic_energy, kinetic_energy_mass_matrix, potential_energy, power,
    total_energy,
};
pub(crate) use forward::forward_dynamics_for_stepper;
pub use forward::{
    forward_dynamics, forward_dynamics_crba, forward_dynamics_walker_orin, ForwardMethod,
};
pub use lagrange::{
    effective_inertia, effective_inertia_free, effective_inertia_locked, lagrange_coefficients,
    mass_matrix_derivatives, LagrangeCoefficients, MAX_LAGRANGE_JOINTS,
};
pub(crate) use regressor::pack_parameters;
pub use regressor::{
    armature_torque, body_parameters, inertia_from_parameters, model_parameters, regressor,
    PARAMETERS_PER_BODY, PARAMETER_NAMES,
};
pub use rnea::{base_acceleration, gravity_torque, inverse_dynamics, nonlinear_effects, rnea};
pub use trace::{rnea_trace, BackwardStep, ForwardStep, RneaTrace};
pub use wrenches::{link_wrench_on_body, ExternalWrenches};
