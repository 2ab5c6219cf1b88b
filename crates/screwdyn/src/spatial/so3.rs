//! Rotations: the hat/vee maps of so(3), and the exponential and logarithm of SO(3).
//!
//! Lynch & Park, *Modern Robotics* ("Exponential Coordinates of R.B. Motion"): a rotation by angle `θ` about the unit
//! axis `n̂` is `R = e^{[n̂]θ}`; `exp_so3` takes the exponential coordinates `ω = n̂θ` directly.

use crate::scalar::{real, Real};
use nalgebra::{Matrix3, Vector3};

/// `[ω]`: the skew-symmetric matrix with `[ω] x = ω × x` (the hat map of so(3)).
///
/// ```
/// use nalgebra::Vector3;
/// let w = Vector3::new(1.0, 2.0, 3.0);
/// let x = Vector3::new(-1.0, 0.5, 2.0);
/// assert!((screwdyn::spatial::hat(&w) * x - w.cross(&x)).norm() < 1e-15);
/// ```
#[inline]
pub fn hat<T: Real>(w: &Vector3<T>) -> Matrix3<T> {
    let z = T::zero();
    Matrix3::new(z, -w.z, w.y, w.z, z, -w.x, -w.y, w.x, z)
}

/// The vee map of so(3): the vector of a skew-symmetric matrix (uses its antisymmetric part).
///
/// ```
/// use nalgebra::Vector3;
/// let w = Vector3::new(1.0, 2.0, 3.0);
/// assert_eq!(screwdyn::spatial::vee(&screwdyn::spatial::hat(&w)), w);
/// ```
#[inline]
pub fn vee<T: Real>(m: &Matrix3<T>) -> Vector3<T> {
    let h: T = real(0.5);
    Vector3::new(
        (m[(2, 1)] - m[(1, 2)]) * h,
        (m[(0, 2)] - m[(2, 0)]) * h,
        (m[(1, 0)] - m[(0, 1)]) * h,
    )
}

/// `sin φ / φ`, accurate down to `φ = 0`.
#[inline]
pub(crate) fn sinc<T: Real>(phi: T) -> T {
    if phi.abs() < real(0.1) {
        let p2 = phi * phi;
        T::one() - p2 / real(6.0) + p2 * p2 / real(120.0) - p2 * p2 * p2 / real(5040.0)
            + p2 * p2 * p2 * p2 / real(362880.0)
    } else {
        phi.sin() / phi
    }
}

/// `(1 − cos φ) / φ²`, accurate down to `φ = 0`.
#[inline]
pub(crate) fn one_minus_cos_over_sq<T: Real>(phi: T) -> T {
    if phi.abs() < real(0.1) {
        let p2 = phi * phi;
        real::<T>(0.5) - p2 / real(24.0) + p2 * p2 / real(720.0) - p2 * p2 * p2 / real(40320.0)
            + p2 * p2 * p2 * p2 / real(3628800.0)
    } else {
        let s = (phi * real(0.5)).sin();
        real::<T>(2.0) * s * s / (phi * phi)
    }
}

/// `(φ − sin φ) / φ³`, accurate down to `φ = 0`.
#[inline]
pub(crate) fn phi_minus_sin_over_cube<T: Real>(phi: T) -> T {
    if phi.abs() < real(0.1) {
        let p2 = phi * phi;
        real::<T>(1.0 / 6.0) - p2 / real(120.0) + p2 * p2 / real(5040.0)
            - p2 * p2 * p2 / real(362880.0)
            + p2 * p2 * p2 * p2 / real(39916800.0)
    } else {
        (phi - phi.sin()) / (phi * phi * phi)
    }
}

/// `e^{[ω]}`: the rotation by angle `|ω|` about `ω/|ω|` (Rodrigues' formula, Lynch & Park, *Modern Robotics*).
///
/// ```
/// use nalgebra::Vector3;
/// let r = screwdyn::spatial::exp_so3(&Vector3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
/// assert!((r * Vector3::x() - Vector3::y()).norm() < 1e-15);
/// ```
pub fn exp_so3<T: Real>(w: &Vector3<T>) -> Matrix3<T> {
    let phi = w.norm();
    let k = hat(w);
    Matrix3::identity() + k * sinc(phi) + k * k * one_minus_cos_over_sq(phi)
}

/// The logarithm of SO(3): exponential coordinates `ω = n̂θ` with `θ ∈ [0, π]` and
/// `e^{[ω]} = R`. Robust near `θ = 0` (no `acos`) and near `θ = π` (axis from the symmetric part).
///
/// ```
/// use nalgebra::Vector3;
/// use screwdyn::spatial::{exp_so3, log_so3};
/// let w = Vector3::new(0.3, -1.2, 2.0);
/// assert!((log_so3(&exp_so3(&w)) - w).norm() < 1e-12);
/// ```
pub fn log_so3<T: Real>(r: &Matrix3<T>) -> Vector3<T> {
    let a = vee(r); // = sin θ n̂
    let s = a.norm();
    let c = (r.trace() - T::one()) * real(0.5);
    let theta = s.atan2(c);
    if c > real(-0.5) {
        // θ < 2π/3: sin θ is well away from zero relative to θ.
        a / sinc(theta)
    } else {
        // Near π: (R + Rᵀ)/2 − cos θ I = (1 − cos θ) n̂ n̂ᵀ; take its largest column.
        let b: Matrix3<T> = (r + r.transpose()) * real::<T>(0.5) - Matrix3::identity() * c;
        let mut k = 0;
        for i in 1..3 {
            if b[(i, i)] > b[(k, k)] {
                k = i;
            }
        }
        let mut n = b.column(k) / (b[(k, k)] * (T::one() - c)).sqrt();
        if n.dot(&a) < T::zero() {
            n = -n;
        }
        n * theta
    }
}
