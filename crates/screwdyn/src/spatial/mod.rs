//! Spatial algebra in the notation of docs/notation.md: `SE(3)`, `so(3)`/`se(3)`, twists and wrenches
//! (angular first), `Ad`, `ad`, exponential and logarithm, and the spatial inertia `𝔍`.
//!
//! ```
//! use nalgebra::Vector6;
//! use screwdyn::spatial::{ad, Se3};
//! let h = Se3::exp(&Vector6::new(0.2, 0.1, -0.3, 1.0, 0.0, 0.5));
//! let v = Vector6::new(1.0, 0.0, 0.0, 0.0, 2.0, 0.0);
//! // Ad_{H} Ad_{H⁻¹} V = V
//! assert!((h.act_twist(&h.inv_act_twist(&v)) - v).norm() < 1e-14);
//! assert!(ad(&v, &v).norm() == 0.0);
//! ```

mod composite_inertia;
pub(crate) mod fused;
mod inertia;
pub(crate) mod inertia_in_world;
mod pose;
mod se3;
mod so3;
mod twist;

pub use composite_inertia::CompositeInertia;
pub use inertia::{parallel_axis_term, InertiaProblem, SpatialInertia};
pub use pose::{check_rotation, ROTATION_TOLERANCE};
pub use se3::Se3;
pub use so3::{exp_so3, hat, log_so3, vee};
pub use twist::{
    ad, ad_matrix, ad_transpose, ang, hat6, helical_screw, lin, prismatic_screw, revolute_screw,
    twist, vee6, Twist, Wrench,
};
