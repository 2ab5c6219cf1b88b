//! Poses from the outside world, checked: a 4×4 homogeneous matrix or a rotation matrix
//! (finite, orthonormal with determinant +1), unit quaternions `(w, x, y, z)` (scalar first),
//! and the quaternion of a rotation. The front-ends' pose helpers (Python's `screwdyn.se3`)
//! read their arrays through these.

use super::se3::Se3;
use crate::error::{Error, Result};
use crate::scalar::{real, Real};
use nalgebra::{Matrix3, Matrix4, Quaternion, Rotation3, UnitQuaternion, Vector3};

/// How far `RᵀR` may be from the identity (entrywise) for `R` to count as a rotation: the
/// tolerance of the description formats' `rotation = […]`.
pub const ROTATION_TOLERANCE: f64 = 1e-6;

/// `Err` naming `what` and the first non-finite entry of a row-major `rows × cols` array.
fn check_finite<T: Real>(values: &[T], cols: usize, what: &str) -> Result<()> {
    match values.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(k) => Err(Error::InvalidArgument(format!(
            "{what} has a non-finite entry ({:?}) at row {}, column {}",
            values[k],
            k / cols,
            k % cols
        ))),
    }
}

/// Checks that `r` is a rotation: finite, `RᵀR = I` within [`ROTATION_TOLERANCE`] and
/// `det R = +1` (not a reflection).
///
/// # Errors
/// [`Error::InvalidArgument`] naming `what` and what is wrong.
///
/// ```
/// use nalgebra::Matrix3;
/// use screwdyn::spatial::check_rotation;
/// assert!(check_rotation(&Matrix3::<f64>::identity(), "R").is_ok());
/// let e = check_rotation(&(Matrix3::<f64>::identity() * 2.0), "R").unwrap_err();
/// assert_eq!(e.to_string(), "R is not a rotation: RᵀR differs from the identity by 3 (more than 1e-6)");
/// ```
pub fn check_rotation<T: Real>(r: &Matrix3<T>, what: &str) -> Result<()> {
    let rows: Vec<T> = r.transpose().iter().copied().collect();
    check_finite(&rows, 3, what)?;
    let off = (r.transpose() * r - Matrix3::identity()).amax();
    if off > real(ROTATION_TOLERANCE) {
        return Err(Error::InvalidArgument(format!(
            "{what} is not a rotation: RᵀR differs from the identity by {off} (more than {ROTATION_TOLERANCE:e})"
        )));
    }
    if r.determinant() < T::zero() {
        return Err(Error::InvalidArgument(format!(
            "{what} is a reflection (determinant −1), not a rotation"
        )));
    }
    Ok(())
}

impl<T: Real> Se3<T> {
    /// The pose of a 4×4 homogeneous matrix `[R p; 0 1]`, checked: finite, `R` a rotation
    /// ([`check_rotation`]), bottom row `(0, 0, 0, 1)`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `what` and what is wrong.
    ///
    /// ```
    /// use nalgebra::Matrix4;
    /// use screwdyn::spatial::Se3;
    /// let h = Se3::<f64>::checked_from_matrix(&Matrix4::identity(), "H").unwrap();
    /// assert!(h.is_identity(0.0));
    /// let mut m = Matrix4::<f64>::identity();
    /// m[(3, 0)] = 1.0;
    /// let e = Se3::checked_from_matrix(&m, "H").unwrap_err().to_string();
    /// assert_eq!(e, "H is not a homogeneous transform: its bottom row is not (0, 0, 0, 1)");
    /// ```
    pub fn checked_from_matrix(m: &Matrix4<T>, what: &str) -> Result<Self> {
        let rows: Vec<T> = m.transpose().iter().copied().collect();
        check_finite(&rows, 4, what)?;
        let bottom = [T::zero(), T::zero(), T::zero(), T::one()];
        if (0..4).any(|j| m[(3, j)] != bottom[j]) {
            return Err(Error::InvalidArgument(format!(
                "{what} is not a homogeneous transform: its bottom row is not (0, 0, 0, 1)"
            )));
        }
        let h = Se3::from_matrix(m);
        check_rotation(&h.rotation, &format!("the rotation part of {what}"))?;
        Ok(h)
    }

    /// The rotation of the quaternion `q = (w, x, y, z)` (scalar first), normalised first;
    /// `R = I + 2w[u] + 2[u]²` for the unit quaternion `(w, u)`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a zero or non-finite quaternion.
    ///
    /// ```
    /// use screwdyn::spatial::Se3;
    /// // A quarter turn about z: (cos π/4, 0, 0, sin π/4), scaled by 2 (normalised first).
    /// let s = std::f64::consts::FRAC_1_SQRT_2 * 2.0;
    /// let h = Se3::from_quaternion([s, 0.0, 0.0, s]).unwrap();
    /// assert!((h.rotation[(1, 0)] - 1.0).abs() < 1e-15 && h.rotation[(0, 0)].abs() < 1e-15);
    /// assert!(Se3::<f64>::from_quaternion([0.0; 4]).is_err());
    /// ```
    pub fn from_quaternion(q: [T; 4]) -> Result<Self> {
        // Scaled first, so that a huge quaternion normalises instead of overflowing.
        let scale = q.iter().fold(T::zero(), |m, c| m.max(c.abs()));
        if !(scale.is_finite() && scale > T::zero()) || q.iter().any(|c| !c.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "the quaternion {:?} is zero or not finite: it has no rotation",
                q
            )));
        }
        let [w, x, y, z] = q.map(|c| c / scale);
        let unit = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
        Ok(Se3::new(
            unit.to_rotation_matrix().into_inner(),
            Vector3::zeros(),
        ))
    }

    /// The unit quaternion `(w, x, y, z)` (scalar first) of the rotation, with `w ≥ 0` (of the
    /// two quaternions `±q` of a rotation, the one with the non-negative scalar part).
    ///
    /// ```
    /// use screwdyn::spatial::Se3;
    /// let h = Se3::from_rpy(0.0, 0.0, std::f64::consts::FRAC_PI_2);
    /// let [w, x, y, z] = h.quaternion();
    /// let s = std::f64::consts::FRAC_1_SQRT_2;
    /// assert!((w - s).abs() < 1e-15 && x.abs() < 1e-15 && y.abs() < 1e-15 && (z - s).abs() < 1e-15);
    /// ```
    pub fn quaternion(&self) -> [T; 4] {
        let q =
            UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(self.rotation));
        let sign = if q.w < T::zero() { -T::one() } else { T::one() };
        [q.w * sign, q.i * sign, q.j * sign, q.k * sign]
    }
}
