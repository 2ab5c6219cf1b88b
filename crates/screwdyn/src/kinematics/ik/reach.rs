//! The reach bound of a frame: no configuration takes its origin farther than a radius from a
//! point fixed in the world, so a target beyond it is unreachable whatever the limits.

use crate::error::Result;
use crate::kinematics::compute_joint_jacobians;
use crate::model::{JointKind, Model};
use crate::spatial::{ang, lin};
use crate::workspace::Workspace;
use nalgebra::Vector3;

/// A ball that holds every position a frame's origin can take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Reach {
    /// A point on the axis of the first joint of the frame's chain (fixed in the world).
    pub(super) center: Vector3<f64>,
    pub(super) radius: f64,
}

impl Reach {
    /// The ball of `frame` when every joint that moves it is a rotation (revolute or
    /// continuous); `None` for a frame on the base or a chain with a sliding (prismatic or
    /// helical) joint, which has no bound without its travel.
    ///
    /// With `p_k` a point on the axis of the chain's `k`-th joint (`p = ω × v` of its screw
    /// `S = (ω, v)`, the foot of the perpendicular from the origin) and `o` the frame's origin,
    /// all taken at one configuration: `p_k` and `p_{k+1}` are both fixed in the body between
    /// joints `k` and `k+1` (a rotation about an axis keeps the points of that axis), so
    /// `|p_{k+1} − p_k|` is the same in every configuration, and so is `|o − p_last|`. By the
    /// triangle inequality `|o(θ) − p_1| ≤ Σ_k |p_{k+1} − p_k| + |o − p_last|` for every `θ`,
    /// and `p_1` does not move.
    pub(super) fn of(model: &Model, frame: usize, q: &[f64]) -> Result<Option<Reach>> {
        let Some(body) = model.frame(frame)?.body else {
            return Ok(None);
        };
        let chain = model.support(body)?;
        let joints = model.joints();
        if chain
            .iter()
            .any(|&j| !matches!(joints[j].kind, JointKind::Revolute | JointKind::Continuous))
        {
            return Ok(None);
        }
        let mut ws = Workspace::new(model);
        compute_joint_jacobians(model, &mut ws, q)?;
        let point = |j: usize| {
            let s = &ws.screw_in_world[j];
            let (w, v) = (ang(s), lin(s));
            w.cross(&v) / w.norm_squared()
        };
        let center = point(chain[0]);
        let mut radius = 0.0;
        for pair in chain.windows(2) {
            radius += (point(pair[1]) - point(pair[0])).norm();
        }
        let origin = crate::kinematics::frame_pose(model, &ws, frame)?.translation;
        radius += (origin - point(chain[chain.len() - 1])).norm();
        Ok(Some(Reach { center, radius }))
    }

    /// How far `position` lies beyond the ball (≤ 0 inside it).
    pub(super) fn beyond(&self, position: &Vector3<f64>) -> f64 {
        (position - self.center).norm() - self.radius
    }
}
