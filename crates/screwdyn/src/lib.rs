//! # screwdyn
//!
//! Kinematics, dynamics and simulation of robot manipulators in the screw-theory / Lie-group
//! formulation of Lynch & Park's *Modern Robotics* and Featherstone's *Rigid Body Dynamics
//! Algorithms*: twists and wrenches
//! angular first, `Ad` and `ad`, product of exponentials, the recursive Newton–Euler algorithm
//! and the closed-form `M(θ) = Sᵀ Lᵀ 𝔍 L S`.
//!
//! Data flows one way: a description → an immutable [`Model`] → algorithms that write into a
//! preallocated [`Workspace`] → results.
//!
//! ```
//! use screwdyn::{builtin, kinematics, Workspace};
//! let model = builtin::planar2();
//! let mut ws = Workspace::new(&model);
//! kinematics::forward_kinematics(&model, &mut ws, &[0.0, 0.0]).unwrap();
//! let tip = kinematics::frame_pose(&model, &ws, model.frame_id("link2").unwrap()).unwrap();
//! assert_eq!(tip.translation.x, 2.0);
//! ```

pub mod batch;
pub mod dynamics;
mod error;
pub mod format;
pub mod identification;
pub mod inertia;
pub mod io;
pub mod kinematics;
pub mod model;
pub mod motion;
pub mod scalar;
pub mod sim;
pub mod spatial;
pub mod symbolic;
mod workspace;

pub use error::{Error, Result};
pub use io::builtin;
pub use model::{check_result, Model, ModelBuilder};
pub use scalar::{real, Real};
pub use workspace::{Workspace, EAGER_SQUARE_BUFFERS};
