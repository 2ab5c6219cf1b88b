//! The pose error of one frame against its target, and the checks of a target.

use super::options::IkTask;
use crate::error::{Error, Result};
use crate::spatial::{log_so3, Se3};
use nalgebra::{Matrix3, Vector3};

/// A target rotation counts as orthonormal when `‖RᵀR − I‖` (largest entry) and `|det R − 1|`
/// are at most this.
pub const ORTHONORMAL_TOLERANCE: f64 = 1e-9;

/// The body-frame pose error of a frame at `pose_in_world` against `target_in_world`,
/// angular first: `e = (log(Rᵀ R_d), Rᵀ (p_d − p))`.
///
/// Its rotation part is that of the body twist `V_b = log(T⁻¹ T_d)`; its translation part
/// equals `V_b`'s to first order and, unlike it, vanishes whenever the positions agree, so a
/// position-only or 5-axis task has its solutions where the weighed entries are zero.
pub(super) fn body_error(pose_in_world: &Se3, target_in_world: &Se3) -> [f64; 6] {
    // R_b^d = Rᵀ R_d, the target's rotation seen from the frame.
    let r: Matrix3<f64> = pose_in_world.rotation.transpose() * target_in_world.rotation;
    let w = log_so3(&r);
    let v: Vector3<f64> = pose_in_world.rotation.transpose()
        * (target_in_world.translation - pose_in_world.translation);
    [w.x, w.y, w.z, v.x, v.y, v.z]
}

/// The position (m) and orientation (rad) errors a task is checked on: the norms of the
/// error's weighed entries.
pub(super) fn measured(task: &IkTask, e: &[f64; 6]) -> (f64, f64) {
    let mut angular = 0.0;
    let mut linear = 0.0;
    for k in 0..3 {
        if task.weights[k] != 0.0 {
            angular += e[k] * e[k];
        }
        if task.weights[k + 3] != 0.0 {
            linear += e[k + 3] * e[k + 3];
        }
    }
    (linear.sqrt(), angular.sqrt())
}

/// An error unless `target` (target `index` of the call) is finite with an orthonormal,
/// right-handed rotation.
pub(super) fn check_target(target: &Se3, index: usize) -> Result<()> {
    let entries = target.rotation.iter().chain(target.translation.iter());
    if let Some((k, v)) = entries.enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(Error::NonFinite {
            what: format!("IK target {index}"),
            index: k,
            value: v.to_string(),
        });
    }
    let r = &target.rotation;
    let off = (r.transpose() * r - Matrix3::identity()).amax();
    let det = r.determinant();
    if off > ORTHONORMAL_TOLERANCE || (det - 1.0).abs() > ORTHONORMAL_TOLERANCE {
        return Err(Error::InvalidArgument(format!(
            "IK target {index}'s rotation is not orthonormal with determinant 1 (|RᵀR − I| = {off:.1e}, det R = {det}; the tolerance is {ORTHONORMAL_TOLERANCE:e})"
        )));
    }
    Ok(())
}
