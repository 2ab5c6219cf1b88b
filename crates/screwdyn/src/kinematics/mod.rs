//! Kinematics (Lynch & Park, *Modern Robotics*): poses of bodies and frames, Jacobians, twists and accelerations.
//!
//! ```
//! use nalgebra::Matrix6xX;
//! use screwdyn::{builtin, Workspace};
//! use screwdyn::kinematics::{compute_joint_jacobians, frame_jacobian, frame_pose, Reference};
//! let m = builtin::planar2();
//! let mut ws = Workspace::new(&m);
//! compute_joint_jacobians(&m, &mut ws, &[0.0, std::f64::consts::FRAC_PI_2]).unwrap();
//! let tip = m.frame_id("link2").unwrap();
//! assert!((frame_pose(&m, &ws, tip).unwrap().translation - nalgebra::Vector3::new(1.0, 1.0, 0.0)).norm() < 1e-15);
//! let mut j = Matrix6xX::zeros(m.nq());
//! frame_jacobian(&m, &ws, tip, Reference::World, &mut j).unwrap();
//! assert_eq!(j[(2, 0)], 1.0); // both joints turn about z
//! ```

mod forward;
pub mod ik;
mod jacobian;
mod motion;

pub(crate) use forward::world_poses_of_checked;
pub use forward::{forward_kinematics, forward_kinematics_poe, frame_pose, poses_in_parent};
pub use jacobian::{
    compute_joint_jacobians, frame_acceleration, frame_jacobian, frame_twist, link_jacobian,
    Reference,
};
pub use motion::{forward_acceleration, forward_velocity, frame_jdot_qdot};
