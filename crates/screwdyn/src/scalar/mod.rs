//! The scalar type every algorithm is generic over.
//!
//! Algorithms take `T: Real`, which is any [`nalgebra::RealField`] that is also `Copy`:
//! `f64` (the default everywhere), `f32`, and later dual numbers or SIMD lane types, which
//! implement `RealField` through `simba`.

/// A real scalar: `f64`, `f32`, or any `Copy` [`nalgebra::RealField`].
///
/// ```
/// fn half<T: screwdyn::Real>(x: T) -> T { x * screwdyn::real(0.5) }
/// assert_eq!(half(3.0_f32), 1.5);
/// assert_eq!(half(3.0_f64), 1.5);
/// ```
pub trait Real: nalgebra::RealField + Copy {}
impl<T: nalgebra::RealField + Copy> Real for T {}

/// Converts an `f64` constant into the scalar type `T` (exact for `f64`, rounded for `f32`).
///
/// ```
/// let x: f32 = screwdyn::real(0.25);
/// assert_eq!(x, 0.25);
/// ```
#[inline(always)]
pub fn real<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

mod sin_cos;
mod sin_cos_lanes;
#[cfg(test)]
pub(crate) use sin_cos::ulps;
pub(crate) use sin_cos::SIN_COS_MEDIUM;
pub use sin_cos::{sin_cos, sin_cos_f64};
pub(crate) use sin_cos_lanes::sin_cos_array;
pub use sin_cos_lanes::sin_cos_lanes;
