//! The reach bound of a frame: no configuration takes its origin farther than a radius from a
//! point fixed in the world, so a target beyond it is unreachable whatever the limits.

use crate::error::Result;
use crate::kinematics::frame_pose;
use crate::model::{JointKind, Model};
use crate::spatial::{ang, lin};
use crate::workspace::Workspace;
use nalgebra::Vector3;

/// The joints that move a frame, when all of them rotate: the chain whose reach is bounded.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Reach {
    frame: usize,
    /// Root to tip.
    chain: Vec<usize>,
}

impl Reach {
    /// The chain of `frame` when every joint that moves it is a rotation (revolute or
    /// continuous); `None` for a frame on the base or a chain with a sliding (prismatic or
    /// helical) joint, which has no bound without its travel.
    pub(super) fn of(model: &Model, frame: usize) -> Result<Option<Reach>> {
        let Some(body) = model.frame(frame)?.body else {
            return Ok(None);
        };
        let chain = model.support(body)?;
        let joints = model.joints();
        let rotations = chain
            .iter()
            .all(|&j| matches!(joints[j].kind, JointKind::Revolute | JointKind::Continuous));
        Ok(rotations.then_some(Reach { frame, chain }))
    }

    /// How far `position` lies beyond the ball the frame's origin cannot leave (≤ 0 inside
    /// it), from the joints' screws in `kinematics` at any one configuration (after
    /// [`compute_joint_jacobians`](crate::kinematics::compute_joint_jacobians)).
    ///
    /// With `p_k` a point on the axis of the chain's `k`-th joint (`p = ω × v` of its screw
    /// `S = (ω, v)`, the foot of the perpendicular from the origin) and `o` the frame's origin,
    /// all at that configuration: `p_k` and `p_{k+1}` are both fixed in the body between
    /// joints `k` and `k+1` (a rotation about an axis keeps the points of that axis), so
    /// `|p_{k+1} − p_k|` is the same in every configuration, and so is `|o − p_last|`. By the
    /// triangle inequality `|o(θ) − p_1| ≤ Σ_k |p_{k+1} − p_k| + |o − p_last|` for every `θ`,
    /// and `p_1` does not move.
    pub(super) fn beyond(
        &self,
        model: &Model,
        kinematics: &Workspace,
        position: &Vector3<f64>,
    ) -> Result<f64> {
        let point = |j: usize| {
            let s = &kinematics.screw_in_world[j];
            let (w, v) = (ang(s), lin(s));
            w.cross(&v) / w.norm_squared()
        };
        let mut radius = 0.0;
        for pair in self.chain.windows(2) {
            radius += (point(pair[1]) - point(pair[0])).norm();
        }
        let last = point(self.chain[self.chain.len() - 1]);
        radius += (frame_pose(model, kinematics, self.frame)?.translation - last).norm();
        Ok((position - point(self.chain[0])).norm() - radius)
    }
}
