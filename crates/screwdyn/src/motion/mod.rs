//! Motion planning in time: the fastest timing of a joint-space path within velocity,
//! acceleration and torque limits (TOPP-RA, [`time_optimal`]), and jerk-limited point-to-point
//! motion ([`JerkLimited`]), and Cartesian moves on a line or an arc ([`cartesian_move`]); a
//! sampled motion read back for tracking ([`SampledTrajectory`]); the user guide is
//! `docs/motion.md`.
//!
//! ```
//! use screwdyn::motion::{time_optimal, CubicSpline, TimeOptimalOptions, TimingLimits};
//! use screwdyn::sim::{torque_profile, Trajectory};
//! let m = screwdyn::builtin::load("ur5").unwrap();
//! let path = CubicSpline::chord_length(&[
//!     vec![0.0, -1.5, 1.0, 0.0, 0.0, 0.0],
//!     vec![1.0, -1.0, 1.5, 0.5, 0.5, 0.0],
//! ]).unwrap();
//! let timed = time_optimal(&m, path, &TimingLimits::from_model(&m), &TimeOptimalOptions::default()).unwrap();
//! let profile = torque_profile(&m, &timed, 1e-3).unwrap();
//! assert!(profile.peak.iter().zip(&profile.effort_limit).all(|(p, l)| p <= l));
//! ```

mod cartesian;
mod check;
mod grid_coefficients;
mod jerk_limited;
mod path_dynamics;
mod reachability;
mod spline;
mod time_optimal;
mod tracking;

pub use cartesian::{
    cartesian_move, cartesian_move_along, CartesianMove, CartesianOptions, CartesianPath,
};
pub use jerk_limited::JerkLimited;
pub use path_dynamics::{PathDynamics, PathPoint};
pub use reachability::LimitKind;
pub use spline::{CubicSpline, Path};
pub use time_optimal::{
    limit_fractions, time_optimal, TimeOptimal, TimeOptimalOptions, TimingLimits, TimingReport,
};
pub use tracking::SampledTrajectory;
