//! Targets and starts as the front-ends receive them: a position and a quaternion (the CLI's
//! `x,y,z,qw,qx,qy,qz`), a 4×4 homogeneous matrix (Python's arrays), and the default start.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::Se3;
use nalgebra::{Matrix4, Quaternion, Vector3};

/// A quaternion counts as a unit quaternion when `|‖q‖ − 1|` is at most this; it is then
/// normalised (so quaternions printed with 7 digits are accepted).
pub const QUATERNION_TOLERANCE: f64 = 1e-6;

/// The bottom row of a homogeneous matrix must be `(0, 0, 0, 1)` within this.
pub const BOTTOM_ROW_TOLERANCE: f64 = 1e-9;

/// The pose with origin `position` (m) and the rotation of the unit quaternion
/// `quaternion_wxyz = (w, x, y, z)` (scalar first), both in the world frame:
/// `R = I + 2w[u] + 2[u]²` with `u = (x, y, z)` after normalisation.
///
/// `what` names the target in messages (`"target"`, `"line 3"`).
///
/// # Errors
/// [`Error::NonFinite`] for NaN or infinity, [`Error::InvalidArgument`] when `‖q‖` differs
/// from 1 by more than [`QUATERNION_TOLERANCE`].
///
/// ```
/// use screwdyn::kinematics::ik::target_from_quaternion;
/// // A half turn about z.
/// let t = target_from_quaternion([0.1, 0.2, 0.3], [0.0, 0.0, 0.0, 1.0], "target").unwrap();
/// assert!((t.rotation[(0, 0)] + 1.0).abs() < 1e-15 && (t.rotation[(2, 2)] - 1.0).abs() < 1e-15);
/// assert_eq!(t.translation.y, 0.2);
/// let e = target_from_quaternion([0.0; 3], [1.0, 0.1, 0.0, 0.0], "target").unwrap_err();
/// assert!(e.to_string().contains("1e-6"));
/// ```
pub fn target_from_quaternion(
    position: [f64; 3],
    quaternion_wxyz: [f64; 4],
    what: &str,
) -> Result<Se3> {
    let values = position.iter().chain(quaternion_wxyz.iter());
    if let Some((k, v)) = values.enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(Error::NonFinite {
            what: format!("the {what} x,y,z,qw,qx,qy,qz"),
            index: k,
            value: v.to_string(),
        });
    }
    let [w, x, y, z] = quaternion_wxyz;
    let q = Quaternion::new(w, x, y, z);
    let norm = q.norm();
    if (norm - 1.0).abs() > QUATERNION_TOLERANCE {
        return Err(Error::InvalidArgument(format!(
            "the {what}'s quaternion (qw, qx, qy, qz) = ({w}, {x}, {y}, {z}) has norm {norm}, not 1 within {QUATERNION_TOLERANCE:e}"
        )));
    }
    // The rotation is the library's one quaternion rule (normalised, scalar first).
    let rotation = Se3::from_quaternion(quaternion_wxyz)?.rotation;
    Ok(Se3::new(rotation, Vector3::from(position)))
}

/// The pose of a 4×4 homogeneous matrix `[R p; 0 1]` (`what` names it in messages). The
/// rotation is checked by the solver ([`ORTHONORMAL_TOLERANCE`](super::ORTHONORMAL_TOLERANCE)).
///
/// # Errors
/// [`Error::NonFinite`] for NaN or infinity (`index` counts the entries row by row),
/// [`Error::InvalidArgument`] when the bottom row is not `(0, 0, 0, 1)` within
/// [`BOTTOM_ROW_TOLERANCE`].
///
/// ```
/// use nalgebra::Matrix4;
/// use screwdyn::kinematics::ik::target_from_matrix;
/// let mut m = Matrix4::identity();
/// m[(0, 3)] = 0.5;
/// assert_eq!(target_from_matrix(&m, "target").unwrap().translation.x, 0.5);
/// m[(3, 0)] = 1.0;
/// assert!(target_from_matrix(&m, "target").is_err());
/// ```
pub fn target_from_matrix(matrix: &Matrix4<f64>, what: &str) -> Result<Se3> {
    for r in 0..4 {
        for c in 0..4 {
            let v = matrix[(r, c)];
            if !v.is_finite() {
                return Err(Error::NonFinite {
                    what: format!("the {what} (a 4×4 matrix, entries row by row)"),
                    index: 4 * r + c,
                    value: v.to_string(),
                });
            }
        }
    }
    let bottom = [
        matrix[(3, 0)],
        matrix[(3, 1)],
        matrix[(3, 2)],
        matrix[(3, 3)],
    ];
    let off = bottom
        .iter()
        .zip([0.0, 0.0, 0.0, 1.0])
        .map(|(v, e)| (v - e).abs())
        .fold(0.0, f64::max);
    if off > BOTTOM_ROW_TOLERANCE {
        return Err(Error::InvalidArgument(format!(
            "the {what}'s bottom row is ({}, {}, {}, {}), not (0, 0, 0, 1) within {BOTTOM_ROW_TOLERANCE:e}",
            bottom[0], bottom[1], bottom[2], bottom[3]
        )));
    }
    Ok(Se3::from_matrix(matrix))
}

/// The start used when none is given: each joint at 0, or at the nearer end of its limits when
/// 0 lies outside them.
///
/// ```
/// use screwdyn::kinematics::ik::default_start;
/// let panda = screwdyn::builtin::load("panda").unwrap();
/// let q0 = default_start(&panda);
/// // The Panda's fourth joint moves within [−3.0718, −0.0698].
/// assert_eq!(q0[3], panda.joints()[3].limits.upper);
/// assert_eq!(q0[0], 0.0);
/// ```
pub fn default_start(model: &Model) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|j| 0.0_f64.clamp(j.limits.lower, j.limits.upper))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    /// Rotating a vector by the quaternion's matrix equals the Hamilton product `q v q*`.
    #[test]
    fn quaternion_rotation_is_hamilton_product() {
        let (w, x, y, z) = (0.3_f64, -0.5, 0.4, 0.2);
        let n = (w * w + x * x + y * y + z * z).sqrt();
        let q = [w / n, x / n, y / n, z / n];
        let t = target_from_quaternion([0.0; 3], q, "target").unwrap();
        let v = Vector3::new(0.7, -0.1, 0.25);
        // q v q* by hand: v' = v + 2 u × (u × v + w v).
        let u = Vector3::new(q[1], q[2], q[3]);
        let expected = v + 2.0 * u.cross(&(u.cross(&v) + q[0] * v));
        assert!((t.rotation * v - expected).amax() < 1e-14);
        assert!((t.rotation.determinant() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn seven_digit_quaternion_is_normalised() {
        // cos(π/4) and sin(π/4) rounded to 7 digits: norm 1 + 2.4e-8.
        let c = (std::f64::consts::FRAC_1_SQRT_2 * 1e7).round() / 1e7;
        let t = target_from_quaternion([0.0; 3], [c, 0.0, 0.0, c], "t").unwrap();
        assert!((t.rotation.transpose() * t.rotation - Matrix3::identity()).amax() < 1e-15);
        assert!((t.rotation[(1, 0)] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn bad_targets_are_named() {
        let e = target_from_quaternion([0.0, f64::NAN, 0.0], [1.0, 0.0, 0.0, 0.0], "line 4")
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "the line 4 x,y,z,qw,qx,qy,qz contains a non-finite value (NaN) at position 1"
        );
        let e = target_from_quaternion([0.0; 3], [2.0, 0.0, 0.0, 0.0], "target").unwrap_err();
        assert!(e.to_string().contains("has norm 2"), "{e}");
        let mut m = Matrix4::identity();
        m[(1, 2)] = f64::INFINITY;
        let e = target_from_matrix(&m, "target 3").unwrap_err();
        assert!(e.to_string().contains("position 6"), "{e}");
    }

    #[test]
    fn default_start_is_within_limits() {
        for name in ["ur5", "panda", "planar2", "branched"] {
            let m = crate::builtin::load(name).unwrap();
            for (q, j) in default_start(&m).iter().zip(m.joints()) {
                assert!(j.limits.lower <= *q && *q <= j.limits.upper, "{name}");
            }
        }
    }
}
