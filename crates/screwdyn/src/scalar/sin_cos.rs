//! `(sin θ, cos θ)` of a joint angle, the one transcendental call of every joint transform
//! `e^{[S]θ}` (seed 000's product of exponentials).
//!
//! Why not `f64::sin_cos`: on the 2-core x86-64 machine the benchmarks run on, glibc's `sincos`
//! costs 25–55 ns per call (a call through the PLT, then its general argument reduction), which
//! is a sixth to a quarter of a whole 6-joint RNEA, CRBA or ABA (`perf record`, BENCHMARKS.md).
//! The `libm` crate (a port of musl) is inlinable but measured only a third faster, and the
//! SIMD math crates either need a nightly compiler (`sleef`) or trade accuracy for speed
//! (`fastapprox`, `micromath`). So [`sin_cos`] is the classic fdlibm scheme written out here,
//! inlined into the kinematics:
//!
//! 1. **Reduction** `θ = n π/2 + r`, `|r| ≤ π/4`, by Cody and Waite: `π/2` split into pieces of
//!    33 bits, so `n · piece` is exact for `|n| < 2²⁰`; a second and third piece are subtracted
//!    only when the first leaves a cancellation. The remainder is kept as `y₀ + y₁` (head and
//!    tail), good to about 2⁻¹⁰⁰ relative to `π/2`.
//! 2. **Kernels**: odd and even minimax polynomials in `r²` of degree 13 and 14 on `[−π/4, π/4]`
//!    (fdlibm's coefficients; error below 2⁻⁵⁸), with the tail `y₁` folded in to first order.
//! 3. **Quadrant**: `n mod 4` swaps and negates the two results.
//!
//! Both results are within one unit in the last place of the exact values (the tests compare
//! with glibc over a million angles and at multiples of `π/2`). Angles beyond `|θ| ≥ 2²⁰ π/2`
//! (≈ 1.6·10⁶ rad), infinities and NaN go to `f64::sin_cos`. Other scalar types (`f32`, dual
//! numbers) keep their own `sin_cos`.

use super::Real;
use std::any::Any;

/// `(sin x, cos x)`: the fast path of this module for `f64`, `T::sin_cos` for any other `T`.
///
/// ```
/// let (s, c) = screwdyn::scalar::sin_cos(2.0_f64);
/// assert!((s - 2.0_f64.sin()).abs() <= f64::EPSILON && (c - 2.0_f64.cos()).abs() <= f64::EPSILON);
/// let (s32, _) = screwdyn::scalar::sin_cos(2.0_f32);
/// assert_eq!(s32, 2.0_f32.sin());
/// ```
#[inline(always)]
pub fn sin_cos<T: Real>(x: T) -> (T, T) {
    // The type test is resolved at compile time for each `T`.
    match (&x as &dyn Any).downcast_ref::<f64>() {
        Some(&x) => {
            let (s, c) = sin_cos_f64(x);
            (super::real(s), super::real(c))
        }
        None => x.sin_cos(),
    }
}

/// `2/π`.
const INV_PIO2: f64 = std::f64::consts::FRAC_2_PI;
/// `π/2` in three 33-bit pieces and their tails (fdlibm's `pio2_1`, `pio2_1t`, …).
const PIO2_1: f64 = 1.570_796_326_734_125_6;
const PIO2_1T: f64 = 6.077_100_506_506_192e-11;
const PIO2_2: f64 = 6.077_100_506_303_966e-11;
const PIO2_2T: f64 = 2.022_266_248_795_950_6e-21;
const PIO2_3: f64 = 2.022_266_248_711_166_5e-21;
const PIO2_3T: f64 = 8.478_427_660_368_9e-32;
/// Adding and subtracting `1.5 · 2⁵²` rounds a double below 2⁵¹ to the nearest integer.
const TO_INT: f64 = 1.5 / f64::EPSILON;
/// Beyond `2²⁰ π/2` the reduction's products `n · PIO2_k` are no longer exact.
const MEDIUM: f64 = 1_647_099.0;

/// `(sin x, cos x)` for `f64` (see the module documentation).
///
/// ```
/// use screwdyn::scalar::sin_cos_f64;
/// assert_eq!(sin_cos_f64(0.0), (0.0, 1.0));
/// let (s, c) = sin_cos_f64(-std::f64::consts::FRAC_PI_2);
/// assert!((s + 1.0).abs() <= f64::EPSILON && c.abs() < 1e-16);
/// ```
#[inline(always)]
pub fn sin_cos_f64(x: f64) -> (f64, f64) {
    let ax = x.abs();
    if ax <= std::f64::consts::FRAC_PI_4 {
        return (kernel_sin(x, 0.0), kernel_cos(x, 0.0));
    }
    // Huge angles, ±∞ and NaN (for which the comparison is false).
    if ax.partial_cmp(&MEDIUM) != Some(std::cmp::Ordering::Less) {
        return x.sin_cos();
    }
    let (n, y0, y1) = reduce(x);
    let (s, c) = (kernel_sin(y0, y1), kernel_cos(y0, y1));
    match n & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `(sin x, cos x)` for `|x| < SIN_COS_MEDIUM` without a branch: the full three-piece
/// reduction for every angle (more accurate than needed for most, never less), the same
/// polynomials, and the quadrant chosen by selects. The batch kernels take it lane by lane
/// ([`crate::batch::Lanes::sin_cos`]); the result is within one ulp of the exact value, and may
/// differ from [`sin_cos_f64`] in the last bit.
#[inline(always)]
pub(crate) fn sin_cos_reduced_fully(x: f64) -> (f64, f64) {
    // n = round(2x/π): its low bits are the low bits of the mantissa of x 2/π + 1.5·2⁵².
    let shifted = x * INV_PIO2 + TO_INT;
    let quadrant = shifted.to_bits();
    let f = shifted - TO_INT;
    let mut r = x - f * PIO2_1;
    let mut w = f * PIO2_1T;
    for (piece, tail) in [(PIO2_2, PIO2_2T), (PIO2_3, PIO2_3T)] {
        let t = r;
        w = f * piece;
        r = t - w;
        w = f * tail - ((t - r) - w);
    }
    let y0 = r - w;
    let y1 = (r - y0) - w;
    let (s, c) = (kernel_sin(y0, y1), kernel_cos(y0, y1));
    // Quadrant 1 and 3 swap the two; 2 and 3 negate sin, 1 and 2 negate cos.
    let (s, c) = if quadrant & 1 == 0 { (s, c) } else { (c, s) };
    let sign_s = if quadrant & 2 == 0 { 1.0 } else { -1.0 };
    let sign_c = if (quadrant + 1) & 2 == 0 { 1.0 } else { -1.0 };
    (s * sign_s, c * sign_c)
}

/// Below this magnitude [`sin_cos_reduced_fully`] is exact in its reduction (`2²⁰ π/2`).
pub(crate) const SIN_COS_MEDIUM: f64 = MEDIUM;

/// The biased exponent of `x`.
#[inline(always)]
fn exponent(x: f64) -> i64 {
    ((x.to_bits() >> 52) & 0x7ff) as i64
}

/// `x = n π/2 + y₀ + y₁` with `|y₀ + y₁| ≤ π/4` (Cody–Waite, up to three pieces of `π/2`).
#[inline(always)]
fn reduce(x: f64) -> (i64, f64, f64) {
    let f = x * INV_PIO2 + TO_INT - TO_INT;
    let n = f as i64;
    let mut r = x - f * PIO2_1;
    let mut w = f * PIO2_1T;
    let mut y0 = r - w;
    let ex = exponent(x);
    // While the last subtraction cancelled more than 16 (then 49) bits, take the next piece.
    for (piece, tail, cancelled) in [(PIO2_2, PIO2_2T, 16), (PIO2_3, PIO2_3T, 49)] {
        if ex - exponent(y0) <= cancelled {
            break;
        }
        let t = r;
        w = f * piece;
        r = t - w;
        w = f * tail - ((t - r) - w);
        y0 = r - w;
    }
    let y1 = (r - y0) - w;
    (n, y0, y1)
}

/// `sin(x + y)` for `|x| ≤ π/4`, `y` a tail below half an ulp of `x`: an odd polynomial of
/// degree 13 (fdlibm's `__kernel_sin`).
#[inline(always)]
fn kernel_sin(x: f64, y: f64) -> f64 {
    const S1: f64 = -1.666_666_666_666_663_2e-1;
    const S2: f64 = 8.333_333_333_322_49e-3;
    const S3: f64 = -1.984_126_982_985_795e-4;
    const S4: f64 = 2.755_731_370_707_006_8e-6;
    const S5: f64 = -2.505_076_025_340_686_3e-8;
    const S6: f64 = 1.589_690_995_211_55e-10;
    let z = x * x;
    let v = z * x;
    let r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    // sin(x + y) ≈ sin x + y cos x, with cos x ≈ 1 − z/2 to the accuracy y needs.
    x - ((z * (0.5 * y - v * r) - y) - v * S1)
}

/// `cos(x + y)` for `|x| ≤ π/4`: an even polynomial of degree 14 (fdlibm's `__kernel_cos`),
/// with `1 − z/2` added in two parts so no bit of it is lost.
#[inline(always)]
fn kernel_cos(x: f64, y: f64) -> f64 {
    const C1: f64 = 4.166_666_666_666_66e-2;
    const C2: f64 = -1.388_888_888_887_411e-3;
    const C3: f64 = 2.480_158_728_947_673e-5;
    const C4: f64 = -2.755_731_435_139_066_3e-7;
    const C5: f64 = 2.087_572_321_298_175e-9;
    const C6: f64 = -1.135_964_755_778_819_5e-11;
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

/// Units in the last place between `a` and `b`, measured at the scale of `b` (at least that of
/// 2⁻¹⁰⁰⁰ so that results near zero are compared absolutely): the tests' measure of `sin_cos`
/// here and of the lanes' in `batch`.
#[cfg(test)]
pub(crate) fn ulps(a: f64, b: f64) -> f64 {
    let scale = b.abs().max(1e-300);
    let ulp = f64::from_bits(scale.to_bits() & 0x7ff0_0000_0000_0000) * f64::EPSILON;
    (a - b).abs() / ulp
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both functions are within one ulp of the exact value, so they differ by at most two.
    fn agree(x: f64) {
        let (s, c) = sin_cos_f64(x);
        let (s0, c0) = x.sin_cos();
        assert!(ulps(s, s0) <= 2.0, "sin({x:e}) = {s:e}, glibc {s0:e}");
        assert!(ulps(c, c0) <= 2.0, "cos({x:e}) = {c:e}, glibc {c0:e}");
    }

    #[test]
    fn agrees_with_glibc_over_the_joint_range_and_beyond() {
        // A million angles spread over ±40 rad (joint angles and their multi-turn values), a
        // quasi-random sequence so every reduction quadrant and cancellation depth occurs.
        let mut x = 0.0_f64;
        for _ in 0..1_000_000 {
            x = (x + 0.618_033_988_749_894_9) % 1.0;
            agree((x - 0.5) * 80.0);
        }
        for k in -20..=20 {
            agree(10f64.powi(k));
            agree(-(10f64.powi(k)));
        }
        agree(1.6e6);
        agree(1e7);
        agree(1e300);
    }

    #[test]
    fn near_multiples_of_a_quarter_turn() {
        // Where the reduction cancels most: k π/2 rounded to a double, and its neighbours.
        for k in (-2000..=2000).filter(|&k| k != 0) {
            let x = k as f64 * std::f64::consts::FRAC_PI_2;
            for d in [-2i64, -1, 0, 1, 2] {
                let y = f64::from_bits((x.to_bits() as i64 + d) as u64);
                // Near a zero the results are tiny; they must still be right to the ulp.
                agree(y);
            }
        }
    }

    #[test]
    fn pythagoras_and_symmetry() {
        for i in 0..10_000 {
            let x = i as f64 * 1e-3 - 5.0;
            let (s, c) = sin_cos_f64(x);
            assert!((s * s + c * c - 1.0).abs() <= 4.0 * f64::EPSILON);
            let (sn, cn) = sin_cos_f64(-x);
            assert_eq!((sn, cn), (-s, c), "sin is odd and cos even at {x}");
        }
    }

    #[test]
    fn special_values() {
        assert_eq!(sin_cos_f64(0.0), (0.0, 1.0));
        assert!(sin_cos_f64(-0.0).0.is_sign_negative());
        let (s, c) = sin_cos_f64(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
        let (s, c) = sin_cos_f64(f64::INFINITY);
        assert!(s.is_nan() && c.is_nan());
        assert_eq!(sin_cos_f64(1e-300), (1e-300, 1.0));
    }

    #[test]
    fn other_scalars_use_their_own() {
        assert_eq!(sin_cos(0.7_f32), 0.7_f32.sin_cos());
    }
}
