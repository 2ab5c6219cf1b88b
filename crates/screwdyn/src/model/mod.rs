//! The kinematic tree: joints, bodies, frames, gravity; built once, then read-only.
//!
//! Bodies and joints share one index: joint `i` moves body `i` relative to its parent body
//! `λ(i)` (`parent(i)`, `None` for the fixed base {0}). Indices follow a depth-first traversal
//! from the root link, children in the order they were declared, so `λ(i) < i`.
//!
//! ```
//! let m = screwdyn::builtin::planar2();
//! assert_eq!(m.nq(), 2);
//! assert_eq!(m.parent(1).unwrap(), Some(0));
//! assert_eq!(m.joint_names(), vec!["joint1", "joint2"]);
//! ```

mod builder;
mod configuration;
mod findings;
mod joint;
#[allow(clippy::module_inception)]
mod model;
pub(crate) use model::{check_finite, first_non_finite};
mod motion;
mod spine;
pub(crate) use spine::Spine;

pub use builder::{JointSpec, ModelBuilder};
pub use configuration::SplitMix64;
pub use findings::{PhysicalFinding, Problem};
pub use joint::{Joint, JointKind, JointLimits, Mimic};
pub use model::{check_result, Body, Frame, FrameKind, Model};
pub use motion::JointMotion;
