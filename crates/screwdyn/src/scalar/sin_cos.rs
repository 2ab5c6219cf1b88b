//! `(sin θ, cos θ)` of a joint angle, the one transcendental call of every joint transform
//! `e^{[S]θ}` (the product of exponentials).
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
        return (kernel_sin::<false>(x, 0.0), kernel_cos::<false>(x, 0.0));
    }
    // Huge angles, ±∞ and NaN (for which the comparison is false).
    if ax.partial_cmp(&MEDIUM) != Some(std::cmp::Ordering::Less) {
        return x.sin_cos();
    }
    let (n, y0, y1) = reduce(x);
    let (s, c) = (kernel_sin::<false>(y0, y1), kernel_cos::<false>(y0, y1));
    match n & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// The angle `x = n π/2 + r − w` after the first piece of `π/2`, for the batch kernels'
/// `sin`/`cos` (`batch::Lanes::sin_cos`), which take the steps below lane by lane:
/// [`Reduction::first`], [`Reduction::cancelled`], [`Reduction::rest`] for the lanes that need
/// it, then [`Reduction::sin_cos`]. The same scheme as [`sin_cos_f64`] (the second and third
/// pieces together, where that takes them one by one), with every product that is added
/// fused ([`f64::mul_add`]): one instruction with FMA, and never less accurate. Within one ulp
/// of the exact values for `|x| < SIN_COS_MEDIUM`; may differ from [`sin_cos_f64`] in the
/// last bit.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Reduction {
    /// `n + 1.5·2⁵²`, whose low mantissa bits are those of `n`.
    pub(crate) shifted: f64,
    /// `n` as a double.
    pub(crate) n: f64,
    /// The remainder so far, and the part `w` of it still to subtract.
    pub(crate) r: f64,
    pub(crate) w: f64,
}

impl Reduction {
    /// `n = round(2x/π)`, `r = x − n P₁`, `w = n P₁ₜ` (Cody–Waite's first piece `P₁` of `π/2`
    /// and its tail `P₁ₜ`), fused when `FUSED`.
    #[inline(always)]
    pub(crate) fn first<const FUSED: bool>(x: f64) -> Reduction {
        let shifted = madd::<FUSED>(x, INV_PIO2, TO_INT);
        let n = shifted - TO_INT;
        // n P₁ is exact (n below 2²⁰, P₁ of 33 bits), so fusing changes nothing here.
        Reduction {
            shifted,
            n,
            r: madd::<FUSED>(-n, PIO2_1, x),
            w: n * PIO2_1T,
        }
    }

    /// The next piece `P` of `π/2` and its tail `Pₜ`, from `t = r`: `w = n P`, `r = t − w`,
    /// then `w = n Pₜ − ((t − r) − w)`, the part of `n (P + Pₜ)` still to subtract.
    #[inline(always)]
    fn next_piece<const FUSED: bool>(self, piece: f64, tail: f64) -> Reduction {
        let (n, t) = (self.n, self.r);
        let w = n * piece;
        let r = t - w;
        Reduction {
            r,
            w: madd::<FUSED>(n, tail, -((t - r) - w)),
            ..self
        }
    }

    /// Whether `r − w` lost more than 16 bits to cancellation against `x` (as [`reduce`]
    /// decides): then the first piece is not enough.
    #[inline(always)]
    pub(crate) fn cancelled(&self, x: f64) -> bool {
        exponent(x) - exponent(self.r - self.w) > 16
    }

    /// The second and third pieces, from `x − n P₁` again.
    #[inline(always)]
    pub(crate) fn rest(self) -> Reduction {
        self.next_piece::<true>(PIO2_2, PIO2_2T)
            .next_piece::<true>(PIO2_3, PIO2_3T)
    }

    /// `(sin x, cos x)` from the reduced angle: the polynomials, then the quadrant by selects.
    #[inline(always)]
    pub(crate) fn sin_cos(self) -> (f64, f64) {
        let y0 = self.r - self.w;
        let y1 = (self.r - y0) - self.w;
        let (s, c) = (kernel_sin::<true>(y0, y1), kernel_cos::<true>(y0, y1));
        // Quadrant 1 and 3 swap the two; 2 and 3 negate sin, 1 and 2 negate cos.
        let quadrant = self.shifted.to_bits();
        let (s, c) = if quadrant & 1 == 0 { (s, c) } else { (c, s) };
        let sign_s = if quadrant & 2 == 0 { 1.0 } else { -1.0 };
        let sign_c = if (quadrant + 1) & 2 == 0 { 1.0 } else { -1.0 };
        (s * sign_s, c * sign_c)
    }
}

/// Below this magnitude [`Reduction`] is exact (`2²⁰ π/2`).
pub(crate) const SIN_COS_MEDIUM: f64 = MEDIUM;

/// The biased exponent of `x`.
#[inline(always)]
fn exponent(x: f64) -> i64 {
    ((x.to_bits() >> 52) & 0x7ff) as i64
}

/// `x = n π/2 + y₀ + y₁` with `|y₀ + y₁| ≤ π/4` (Cody–Waite, up to three pieces of `π/2`).
#[inline(always)]
fn reduce(x: f64) -> (i64, f64, f64) {
    let mut red = Reduction::first::<false>(x);
    let mut y0 = red.r - red.w;
    let ex = exponent(x);
    // While the last subtraction cancelled more than 16 (then 49) bits, take the next piece.
    for (piece, tail, cancelled) in [(PIO2_2, PIO2_2T, 16), (PIO2_3, PIO2_3T, 49)] {
        if ex - exponent(y0) <= cancelled {
            break;
        }
        red = red.next_piece::<false>(piece, tail);
        y0 = red.r - red.w;
    }
    let y1 = (red.r - y0) - red.w;
    (red.n as i64, y0, y1)
}

/// `a b + c`, fused (one rounding) when `FUSED`.
#[inline(always)]
fn madd<const FUSED: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FUSED {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// `sin(x + y)` for `|x| ≤ π/4`, `y` a tail below half an ulp of `x`: an odd polynomial of
/// degree 13 (fdlibm's `__kernel_sin`), its products and sums fused when `FUSED`.
#[inline(always)]
fn kernel_sin<const FUSED: bool>(x: f64, y: f64) -> f64 {
    const S1: f64 = -1.666_666_666_666_663_2e-1;
    const S2: f64 = 8.333_333_333_322_49e-3;
    const S3: f64 = -1.984_126_982_985_795e-4;
    const S4: f64 = 2.755_731_370_707_006_8e-6;
    const S5: f64 = -2.505_076_025_340_686_3e-8;
    const S6: f64 = 1.589_690_995_211_55e-10;
    let z = x * x;
    let v = z * x;
    let m = madd::<FUSED>;
    let r = m(z, m(z, m(z, m(z, S6, S5), S4), S3), S2);
    // sin(x + y) ≈ sin x + y cos x, with cos x ≈ 1 − z/2 to the accuracy y needs.
    x - m(-v, S1, m(z, m(-v, r, 0.5 * y), -y))
}

/// `cos(x + y)` for `|x| ≤ π/4`: an even polynomial of degree 14 (fdlibm's `__kernel_cos`),
/// with `1 − z/2` added in two parts so no bit of it is lost; products and sums fused when
/// `FUSED`.
#[inline(always)]
fn kernel_cos<const FUSED: bool>(x: f64, y: f64) -> f64 {
    const C1: f64 = 4.166_666_666_666_66e-2;
    const C2: f64 = -1.388_888_888_887_411e-3;
    const C3: f64 = 2.480_158_728_947_673e-5;
    const C4: f64 = -2.755_731_435_139_066_3e-7;
    const C5: f64 = 2.087_572_321_298_175e-9;
    const C6: f64 = -1.135_964_755_778_819_5e-11;
    let z = x * x;
    let w = z * z;
    let m = madd::<FUSED>;
    let r = m(z, m(z, m(z, C3, C2), C1), w * w * m(z, m(z, C6, C5), C4));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + m(z, r, -(x * y)))
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
