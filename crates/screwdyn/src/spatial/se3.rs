//! Homogeneous transforms `H ∈ SE(3)`, their adjoint actions on twists and wrenches, and the
//! exponential and logarithm of SE(3).
//!
//! Notation (Lynch & Park, *Modern Robotics*): `H_c^p` is the pose of frame `c` in frame `p`; it maps coordinates
//! in `c` to coordinates in `p`. `Ad_{H_c^p}` maps a twist written in `c` to the same twist written
//! in `p`; `Ad_{H_c^p}ᵀ` maps a wrench written in `p` to the same wrench written in `c`.
//! Twists are angular first, `V = (ω, v)`; wrenches moment first, `W = (m, f)`.
//!
//! [`Se3`] stores a rotation matrix and a translation and applies every operator to vectors
//! directly, never forming a 6×6 matrix in a hot path. nalgebra's `IsometryMatrix3` stores the
//! same two parts; we keep our own small type so that the operators (`Ad`, `Adᵀ`, their
//! inverses) are methods with the names.

use super::so3::{exp_so3, hat, log_so3, one_minus_cos_over_sq, phi_minus_sin_over_cube};
use super::twist::{ang, lin, Twist, Wrench};
use crate::scalar::{real, Real};
use nalgebra::{Matrix3, Matrix4, Matrix6, Vector3, Vector6};

/// `(sin t, cos t)`, exact (`0`, `±1`) when `t` is within `1e-12` rad of a multiple of `π/2`.
fn quarter_exact_sin_cos<T: Real>(t: T) -> (T, T) {
    let quarter = T::frac_pi_2();
    let k = (t / quarter).round();
    if (t - k * quarter).abs() > real(1e-12) {
        return crate::scalar::sin_cos(t);
    }
    let four: T = real(4.0);
    let m = k - (k / four).floor() * four;
    let (zero, one) = (T::zero(), T::one());
    if m == zero {
        (zero, one)
    } else if m == one {
        (one, zero)
    } else if m == real(2.0) {
        (zero, -one)
    } else {
        (-one, zero)
    }
}

/// A rigid-body transform `H = [R p; 0 1] ∈ SE(3)`.
///
/// ```
/// use nalgebra::Vector3;
/// use screwdyn::spatial::Se3;
/// let h = Se3::from_rpy(0.0, 0.0, std::f64::consts::FRAC_PI_2).with_translation(Vector3::new(1.0, 0.0, 0.0));
/// let p = h.act_point(&Vector3::new(1.0, 0.0, 0.0));
/// assert!((p - Vector3::new(1.0, 1.0, 0.0)).norm() < 1e-15);
/// assert!((h.inverse() * h).is_identity(1e-15));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Se3<T: Real = f64> {
    /// `R`: the orientation of the moving frame in the reference frame.
    pub rotation: Matrix3<T>,
    /// `p`: the origin of the moving frame in the reference frame.
    pub translation: Vector3<T>,
}

impl<T: Real> Default for Se3<T> {
    fn default() -> Self {
        Self::identity()
    }
}

impl<T: Real> Se3<T> {
    /// The identity transform.
    pub fn identity() -> Self {
        Se3 {
            rotation: Matrix3::identity(),
            translation: Vector3::zeros(),
        }
    }

    /// `H = [R p; 0 1]` from its parts (`R` is trusted to be a rotation).
    pub fn new(rotation: Matrix3<T>, translation: Vector3<T>) -> Self {
        Se3 {
            rotation,
            translation,
        }
    }

    /// A pure translation.
    pub fn from_translation(p: Vector3<T>) -> Self {
        Se3::new(Matrix3::identity(), p)
    }

    /// Replaces the translation, keeping the rotation.
    pub fn with_translation(mut self, p: Vector3<T>) -> Self {
        self.translation = p;
        self
    }

    /// The URDF rotation `rpy`: fixed-axis X-Y-Z, i.e. `R = Rz(yaw)·Ry(pitch)·Rx(roll)`.
    ///
    /// Angles within `1e-12` rad of a multiple of `π/2` (such as the `1.5707963267948966` of
    /// URDF files and DH tables) give exact `0` and `±1` sines and cosines, so a frame turned by a
    /// quarter turn has its axes exactly on the parent's axes (not `6e-17` off), and the joint
    /// axes in it are recognised as coordinate axes (see
    /// [`JointMotion`](crate::model::JointMotion)).
    ///
    /// ```
    /// use screwdyn::spatial::Se3;
    /// let h = Se3::from_rpy(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
    /// assert_eq!(h.rotation[(1, 1)], 0.0); // cos(π/2), exactly
    /// assert_eq!(h.rotation[(2, 1)], 1.0);
    /// let g = Se3::from_rpy(0.3_f64, -0.2, 0.1);
    /// assert!((g.rotation[(2, 0)] + (-0.2_f64).sin()).abs() < 1e-16);
    /// ```
    pub fn from_rpy(roll: T, pitch: T, yaw: T) -> Self {
        let (sr, cr) = quarter_exact_sin_cos(roll);
        let (sp, cp) = quarter_exact_sin_cos(pitch);
        let (sy, cy) = quarter_exact_sin_cos(yaw);
        let r = Matrix3::new(
            cy * cp,
            cy * sp * sr - sy * cr,
            cy * sp * cr + sy * sr,
            sy * cp,
            sy * sp * sr + cy * cr,
            sy * sp * cr - cy * sr,
            -sp,
            cp * sr,
            cp * cr,
        );
        Se3::new(r, Vector3::zeros())
    }

    /// The URDF `rpy` angles of the rotation (inverse of [`Se3::from_rpy`]).
    pub fn rpy(&self) -> (T, T, T) {
        let r = &self.rotation;
        let pitch = (-r[(2, 0)]).atan2((r[(0, 0)] * r[(0, 0)] + r[(1, 0)] * r[(1, 0)]).sqrt());
        let cp = pitch.cos();
        if cp.abs() > real(1e-10) {
            (
                r[(2, 1)].atan2(r[(2, 2)]),
                pitch,
                r[(1, 0)].atan2(r[(0, 0)]),
            )
        } else {
            // Gimbal lock: roll and yaw share one degree of freedom; put it all in yaw.
            (T::zero(), pitch, (-r[(0, 1)]).atan2(r[(1, 1)]))
        }
    }

    /// From a 4×4 homogeneous matrix (the bottom row is ignored).
    pub fn from_matrix(m: &Matrix4<T>) -> Self {
        Se3::new(
            m.fixed_view::<3, 3>(0, 0).into_owned(),
            m.fixed_view::<3, 1>(0, 3).into_owned(),
        )
    }

    /// The 4×4 homogeneous matrix `[R p; 0 1]`.
    pub fn to_matrix(&self) -> Matrix4<T> {
        let mut m = Matrix4::identity();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.rotation);
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&self.translation);
        m
    }

    /// `H⁻¹ = [Rᵀ −Rᵀp; 0 1]`.
    #[inline]
    pub fn inverse(&self) -> Self {
        let rt = self.rotation.transpose();
        Se3::new(rt, -(rt * self.translation))
    }

    /// `H₁ H₂`.
    #[inline]
    pub fn compose(&self, other: &Se3<T>) -> Self {
        Se3::new(
            self.rotation * other.rotation,
            self.rotation * other.translation + self.translation,
        )
    }

    /// [`Se3::compose`] with fused multiply–adds: each entry of `R R₂` and `R p₂ + p` one
    /// product and two `mul_add`s (one instruction each on a CPU with FMA, a library call
    /// without: for CPU-specific clones that have them). Within rounding of [`Se3::compose`].
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use screwdyn::spatial::Se3;
    /// let a = Se3::from_rpy(0.3, -1.2, 2.1).with_translation(Vector3::new(0.2, -0.4, 1.1));
    /// let b = Se3::from_rpy(-0.7, 0.4, -2.6).with_translation(Vector3::new(-1.0, 0.5, 0.3));
    /// let (fused, plain) = (a.compose_fused(&b), a.compose(&b));
    /// assert!((fused.to_matrix() - plain.to_matrix()).amax() < 4.0 * f64::EPSILON);
    /// ```
    #[inline(always)]
    pub fn compose_fused(&self, other: &Se3<T>) -> Self {
        let (a, b, t) = (&self.rotation, &other.rotation, &other.translation);
        let rotation = Matrix3::from_fn(|i, j| {
            a[(i, 2)].mul_add(
                b[(2, j)],
                a[(i, 1)].mul_add(b[(1, j)], a[(i, 0)] * b[(0, j)]),
            )
        });
        let translation = Vector3::from_fn(|i, _| {
            a[(i, 2)].mul_add(
                t.z,
                a[(i, 1)].mul_add(t.y, a[(i, 0)].mul_add(t.x, self.translation[i])),
            )
        });
        Se3::new(rotation, translation)
    }

    /// `H⁻¹ H₂` without forming the inverse.
    #[inline]
    pub fn inv_compose(&self, other: &Se3<T>) -> Self {
        let rt = self.rotation.transpose();
        Se3::new(
            rt * other.rotation,
            rt * (other.translation - self.translation),
        )
    }

    /// `R x + p`: a point given in the moving frame, written in the reference frame.
    #[inline]
    pub fn act_point(&self, x: &Vector3<T>) -> Vector3<T> {
        self.rotation * x + self.translation
    }

    /// `Ad_H V = (R ω, p × Rω + R v)`: a twist given in the moving frame, written in the
    /// reference frame (Lynch & Park, *Modern Robotics*: `V^{p} = Ad_{H_c^p} V^{c}`).
    #[inline]
    pub fn act_twist(&self, v: &Twist<T>) -> Twist<T> {
        let w = self.rotation * ang(v);
        let l = self.translation.cross(&w) + self.rotation * lin(v);
        Vector6::new(w.x, w.y, w.z, l.x, l.y, l.z)
    }

    /// `Ad_{H⁻¹} V = (Rᵀ ω, Rᵀ (v − p × ω))`: a twist given in the reference frame, written in
    /// the moving frame (Lynch & Park, *Modern Robotics*: `Ad_{H_{i-1}^i} V_{i-1}` with `H = H_i^{i-1}`).
    #[inline]
    pub fn inv_act_twist(&self, v: &Twist<T>) -> Twist<T> {
        let w0 = ang(v);
        let w = self.rotation.tr_mul(&w0);
        let l = self
            .rotation
            .tr_mul(&(lin(v) - self.translation.cross(&w0)));
        Vector6::new(w.x, w.y, w.z, l.x, l.y, l.z)
    }

    /// `Ad_Hᵀ W = (Rᵀ (m − p × f), Rᵀ f)`: a wrench given in the reference frame, written in the
    /// moving frame. Power is preserved: `(Ad_Hᵀ W)ᵀ V = Wᵀ (Ad_H V)`.
    #[inline]
    pub fn act_transpose_wrench(&self, w: &Wrench<T>) -> Wrench<T> {
        let f0 = lin(w);
        let m = self
            .rotation
            .tr_mul(&(ang(w) - self.translation.cross(&f0)));
        let f = self.rotation.tr_mul(&f0);
        Vector6::new(m.x, m.y, m.z, f.x, f.y, f.z)
    }

    /// `Ad_{H⁻¹}ᵀ W = (R m + p × R f, R f)`: a wrench given in the moving frame, written in the
    /// reference frame (Lynch & Park, *Modern Robotics* backward pass: `Ad_{H_i^{i+1}}ᵀ W_i^{i+1,i+1}` with
    /// `H = H_{i+1}^i`).
    #[inline]
    pub fn inv_act_transpose_wrench(&self, w: &Wrench<T>) -> Wrench<T> {
        let f = self.rotation * lin(w);
        let m = self.rotation * ang(w) + self.translation.cross(&f);
        Vector6::new(m.x, m.y, m.z, f.x, f.y, f.z)
    }

    /// The 6×6 matrix `Ad_H = [R 0; [p]R R]` (for teaching and the closed form, not hot paths).
    ///
    /// ```
    /// use nalgebra::{Vector3, Vector6};
    /// use screwdyn::spatial::Se3;
    /// let h = Se3::from_rpy(0.1, 0.2, 0.3).with_translation(Vector3::new(1.0, -2.0, 0.5));
    /// let v = Vector6::new(0.1, 0.2, 0.3, 0.4, 0.5, 0.6);
    /// assert!((h.adjoint_matrix() * v - h.act_twist(&v)).norm() < 1e-14);
    /// ```
    pub fn adjoint_matrix(&self) -> Matrix6<T> {
        let mut m = Matrix6::zeros();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.rotation);
        m.fixed_view_mut::<3, 3>(3, 3).copy_from(&self.rotation);
        m.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&(hat(&self.translation) * self.rotation));
        m
    }

    /// `e^{[ξ]}` for a twist `ξ = (φ, ρ)` (Lynch & Park, *Modern Robotics*):
    /// `R = e^{[φ]}`, `p = (I + B[φ] + C[φ]²) ρ` with `B = (1 − cos|φ|)/|φ|²`,
    /// `C = (|φ| − sin|φ|)/|φ|³`, series-expanded near zero.
    ///
    /// ```
    /// use nalgebra::Vector6;
    /// use screwdyn::spatial::Se3;
    /// // A revolute screw about z through (1, 0, 0): S = (ẑ, −ẑ × r) = (0,0,1, 0,-1,0).
    /// let s = Vector6::new(0.0, 0.0, 1.0, 0.0, -1.0, 0.0);
    /// let h = Se3::exp(&(s * std::f64::consts::PI));
    /// // The origin swings round the axis to (2, 0, 0).
    /// assert!((h.translation - nalgebra::Vector3::new(2.0, 0.0, 0.0)).norm() < 1e-15);
    /// ```
    pub fn exp(xi: &Twist<T>) -> Self {
        let phi = ang(xi);
        let rho = lin(xi);
        let k = hat(&phi);
        let t = phi.norm();
        let kr = k * rho;
        let p = rho + kr * one_minus_cos_over_sq(t) + k * kr * phi_minus_sin_over_cube(t);
        Se3::new(exp_so3(&phi), p)
    }

    /// `e^{[S]θ}`: the displacement of a joint with screw axis `S` by `θ` (Lynch & Park, *Modern Robotics*:
    /// `H_c^p(θ) = H_c^p(0) e^{[S_c^{c,p}]θ}`).
    #[inline]
    pub fn exp_screw(screw: &Twist<T>, theta: T) -> Self {
        Se3::exp(&(screw * theta))
    }

    /// The logarithm of SE(3): the twist `ξ` with `e^{[ξ]} = H` and `|ω| ≤ π`. Robust near
    /// `|ω| = 0` and `|ω| = π`.
    ///
    /// ```
    /// use nalgebra::Vector6;
    /// use screwdyn::spatial::Se3;
    /// let xi = Vector6::new(0.5, -0.4, 0.3, 1.0, 2.0, -3.0);
    /// assert!((Se3::exp(&xi).log() - xi).norm() < 1e-12);
    /// ```
    pub fn log(&self) -> Twist<T> {
        let phi = log_so3(&self.rotation);
        let t = phi.norm();
        // k = (1 − (t/2) cot(t/2)) / t², finite at t = π, series near 0.
        let k: T = if t < real(0.1) {
            let t2 = t * t;
            real::<T>(1.0 / 12.0) + t2 / real(720.0) + t2 * t2 / real(30240.0)
        } else {
            let h = t * real(0.5);
            (T::one() - h * h.cos() / h.sin()) / (t * t)
        };
        let kp = hat(&phi) * self.translation;
        let rho: Vector3<T> = self.translation - kp * real::<T>(0.5) + hat(&phi) * kp * k;
        Vector6::new(phi.x, phi.y, phi.z, rho.x, rho.y, rho.z)
    }

    /// Whether `H` is the identity within `tol` (entrywise).
    pub fn is_identity(&self, tol: T) -> bool {
        (self.rotation - Matrix3::identity()).amax() <= tol && self.translation.amax() <= tol
    }
}

impl Se3<f64> {
    /// Converts the scalar type (e.g. `f64 → f32`).
    pub fn cast<U: Real>(&self) -> Se3<U> {
        Se3::new(self.rotation.map(real), self.translation.map(real))
    }
}

impl<T: Real> std::ops::Mul for Se3<T> {
    type Output = Se3<T>;
    #[inline]
    fn mul(self, rhs: Se3<T>) -> Se3<T> {
        self.compose(&rhs)
    }
}

impl<T: Real> std::ops::Mul<&Se3<T>> for &Se3<T> {
    type Output = Se3<T>;
    #[inline]
    fn mul(self, rhs: &Se3<T>) -> Se3<T> {
        self.compose(rhs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn quarter_turns_are_exact_and_other_angles_are_the_scalar_sin_cos() {
        let cases = [
            (0.0, (0.0, 1.0)),
            (FRAC_PI_2, (1.0, 0.0)),
            (PI, (0.0, -1.0)),
            (-FRAC_PI_2, (-1.0, 0.0)),
            (3.0 * FRAC_PI_2, (-1.0, 0.0)),
            (-PI, (0.0, -1.0)),
            (4.0 * PI, (0.0, 1.0)),
        ];
        for (t, expected) in cases {
            assert_eq!(quarter_exact_sin_cos(t), expected, "t = {t}");
        }
        for t in [1e-9, 0.3, FRAC_PI_2 + 1e-9, FRAC_PI_2 - 3e-7, -2.5, 7.0] {
            assert_eq!(
                quarter_exact_sin_cos(t),
                crate::scalar::sin_cos(t),
                "t = {t}"
            );
            let (s, c) = quarter_exact_sin_cos(t);
            assert!(
                (s - t.sin()).abs() <= 2.0 * f64::EPSILON
                    && (c - t.cos()).abs() <= 2.0 * f64::EPSILON
            );
        }
    }

    /// `from_rpy` is nalgebra's `Rz(yaw) Ry(pitch) Rx(roll)` up to rounding.
    #[test]
    fn rpy_matches_the_product_of_elementary_rotations() {
        for (r, p, y) in [
            (0.3, -0.2, 0.1),
            (FRAC_PI_2, 0.4, -PI),
            (-1.1, FRAC_PI_2, 2.0),
        ] {
            let expected = Rotation3::from_axis_angle(&Vector3::z_axis(), y)
                * Rotation3::from_axis_angle(&Vector3::y_axis(), p)
                * Rotation3::from_axis_angle(&Vector3::x_axis(), r);
            let got = Se3::from_rpy(r, p, y).rotation;
            assert!((got - expected.into_inner()).amax() < 1e-15);
        }
    }
}
