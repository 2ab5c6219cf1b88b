//! The small spatial products of the base-frame algorithms (ABA, RNEA in {0}), with every product
//! that is added fused (`mul_add`: one instruction where the CPU has FMA, which the
//! multiversioned passes are compiled for, and never less accurate than the two roundings).

use crate::scalar::Real;
use crate::spatial::{ang, lin, twist, Twist};
use nalgebra::{Matrix6, Vector3};

/// `xᵀ y` of two 6-vectors, fused, summed as a tree `(x₀y₀ + x₁y₁) + (x₂y₂ + x₃y₃) + (x₄y₄ + x₅y₅)`:
/// the three pairs are independent, so the sum waits on four operations instead of six.
#[inline(always)]
pub(crate) fn dot6<T: Real>(x: &Twist<T>, y: &Twist<T>) -> T {
    let p0 = x[1].mul_add(y[1], x[0] * y[0]);
    let p1 = x[3].mul_add(y[3], x[2] * y[2]);
    let p2 = x[5].mul_add(y[5], x[4] * y[4]);
    (p0 + p1) + p2
}

/// `M x` for a 6×6 `M` stored by columns: `Σ_c M[:, c] x_c`, fused, the even and the odd columns
/// summed apart (two independent chains of three) and then added.
#[inline(always)]
pub(crate) fn mat6_vec<T: Real>(m: &Matrix6<T>, x: &Twist<T>) -> Twist<T> {
    Twist::from_fn(|r, _| {
        let even = m[(r, 4)].mul_add(x[4], m[(r, 2)].mul_add(x[2], m[(r, 0)] * x[0]));
        let odd = m[(r, 5)].mul_add(x[5], m[(r, 3)].mul_add(x[3], m[(r, 1)] * x[1]));
        even + odd
    })
}

/// `a × b`, fused.
#[inline(always)]
pub(crate) fn cross<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> Vector3<T> {
    Vector3::new(
        a.y.mul_add(b.z, -(a.z * b.y)),
        a.z.mul_add(b.x, -(a.x * b.z)),
        a.x.mul_add(b.y, -(a.y * b.x)),
    )
}

/// `ad_V X = (ω × ω_X, v × ω_X + ω × v_X)` for `V = (ω, v)`, fused.
#[inline(always)]
pub(crate) fn ad_fused<T: Real>(v: &Twist<T>, x: &Twist<T>) -> Twist<T> {
    let (w, wx) = (ang(v), ang(x));
    twist(cross(&w, &wx), cross(&lin(v), &wx) + cross(&w, &lin(x)))
}
