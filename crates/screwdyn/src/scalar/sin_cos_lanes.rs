//! `(sin θ, cos θ)` of up to eight angles at once: [`sin_cos_lanes`] for every joint of a
//! chunk before the forward-kinematics loop, and [`sin_cos_array`] behind the batch kernels'
//! `Lanes::sin_cos`.
//!
//! The scheme is that of [`sin_cos_f64`](super::sin_cos_f64) (Cody–Waite reduction by `π/2`,
//! fdlibm's minimax polynomials of degree 13 and 14, the quadrant by selects), written without
//! branches on the values so that the compiler evaluates the eight angles side by side in
//! vector registers (one AVX-512 register, or two AVX2 ones, in the CPU-specific clones of the
//! callers). Why not a SIMD crate (`wide`'s `f64x4::sin_cos`): the stable crates choose their
//! instruction set when this library is compiled, which for a portable build is SSE2, where
//! plain arrays inlined into run-time-dispatched clones reach AVX2 and AVX-512; and `wide`'s
//! sine is a Cephes-style kernel with a one-piece reduction, less accurate near large
//! multiples of `π/2` than the three-piece reduction here.

use super::sin_cos::Reduction;
use super::{Real, SIN_COS_MEDIUM};
use std::any::Any;

/// `(sin x_l, cos x_l)` of `L` angles (4 or 8: one or two AVX2 registers, one AVX-512
/// register): for `f64` the fast path of [`sin_cos`](super::sin_cos) in lanes (the products
/// fused, so only where the CPU has fused multiply–adds), `T::sin_cos` lane by lane for any
/// other `T`. The type test is resolved at compile time.
///
/// ```
/// let x = [0.0, 0.5, -1.0, 2.0, 3.0, -4.0, 10.0, 100.0_f64];
/// let (s, c) = screwdyn::scalar::sin_cos_lanes(x);
/// for l in 0..8 {
///     assert!((s[l] - x[l].sin()).abs() <= 2.0 * f64::EPSILON * x[l].sin().abs().max(1.0));
///     assert!((c[l] - x[l].cos()).abs() <= 2.0 * f64::EPSILON * x[l].cos().abs().max(1.0));
/// }
/// let (s32, _) = screwdyn::scalar::sin_cos_lanes([0.25_f32; 8]);
/// assert_eq!(s32[3], 0.25_f32.sin());
/// ```
#[inline(always)]
pub fn sin_cos_lanes<T: Real, const L: usize>(x: [T; L]) -> ([T; L], [T; L]) {
    match (&x as &dyn Any).downcast_ref::<[f64; L]>() {
        Some(&x64) => {
            let (s, c) = sin_cos_array(x64);
            (s.map(super::real), c.map(super::real))
        }
        None => {
            let mut s = [T::zero(); L];
            let mut c = [T::zero(); L];
            for l in 0..L {
                (s[l], c[l]) = x[l].sin_cos();
            }
            (s, c)
        }
    }
}

/// `(sin x_l, cos x_l)` of every lane, each within one unit in the last place: the reduction
/// and polynomials of [`sin_cos_f64`](super::sin_cos_f64) lane by lane, with fused
/// multiply–adds ([`f64::mul_add`]: one instruction on a CPU with FMA, a slow library call
/// without), and its branches taken for the whole group: the second and third pieces of `π/2`
/// only when some lane's first-piece remainder cancelled (an angle within about 2⁻¹⁶ of a
/// multiple of `π/2`), and then kept only in those lanes, so every lane's result depends on
/// that lane alone. Angles beyond `|x| ≥ 2²⁰ π/2` (≈ 1.6·10⁶ rad), ±∞ and NaN go to
/// `f64::sin_cos`. May differ from [`sin_cos_f64`](super::sin_cos_f64) in the last bit.
#[inline(always)]
pub(crate) fn sin_cos_array<const L: usize>(x: [f64; L]) -> ([f64; L], [f64; L]) {
    let mut red = Reductions::<L>::default();
    let (mut cancelled, mut outside) = (false, false);
    for (l, &x) in x.iter().enumerate() {
        let r = Reduction::first::<true>(x);
        cancelled |= r.cancelled(x);
        outside |= beyond_fast_range(x);
        red.set(l, r);
    }
    if cancelled {
        further_pieces(&x, &mut red);
    }
    let (mut s, mut c) = ([0.0; L], [0.0; L]);
    for (l, (s, c)) in s.iter_mut().zip(&mut c).enumerate() {
        (*s, *c) = red.get(l).sin_cos();
    }
    if outside {
        fix_large(&x, &mut s, &mut c);
    }
    (s, c)
}

/// `|x| ≥ 2²⁰ π/2`, ±∞ or NaN: beyond the branch-free reduction.
#[inline(always)]
fn beyond_fast_range(x: f64) -> bool {
    x.abs() >= SIN_COS_MEDIUM || x.is_nan()
}

/// The second and third pieces of `π/2` for the lanes of `x` whose first-piece remainder
/// cancelled.
#[cold]
#[inline(never)]
fn further_pieces<const L: usize>(x: &[f64; L], red: &mut Reductions<L>) {
    for (l, &x) in x.iter().enumerate() {
        let r = red.get(l);
        if r.cancelled(x) {
            red.set(l, r.rest());
        }
    }
}

/// The [`Reduction`]s of `L` lanes, field by field, so that each field stays in one vector
/// register (an array of the structs made the compiler shuffle them in and out).
struct Reductions<const L: usize> {
    shifted: [f64; L],
    n: [f64; L],
    r: [f64; L],
    w: [f64; L],
}

impl<const L: usize> Default for Reductions<L> {
    #[inline(always)]
    fn default() -> Self {
        Reductions {
            shifted: [0.0; L],
            n: [0.0; L],
            r: [0.0; L],
            w: [0.0; L],
        }
    }
}

impl<const L: usize> Reductions<L> {
    #[inline(always)]
    fn get(&self, l: usize) -> Reduction {
        Reduction {
            shifted: self.shifted[l],
            n: self.n[l],
            r: self.r[l],
            w: self.w[l],
        }
    }

    #[inline(always)]
    fn set(&mut self, l: usize, red: Reduction) {
        (self.shifted[l], self.n[l], self.r[l], self.w[l]) = (red.shifted, red.n, red.r, red.w);
    }
}

/// The lanes of `x` too large for the fast reduction, through `f64::sin_cos`.
#[cold]
#[inline(never)]
fn fix_large<const L: usize>(x: &[f64; L], s: &mut [f64; L], c: &mut [f64; L]) {
    for l in 0..L {
        if beyond_fast_range(x[l]) {
            (s[l], c[l]) = x[l].sin_cos();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::ulps;

    const LANES: usize = 8;

    /// Within 2 ulp of glibc (each within one of the exact value) over ±100 rad, near multiples
    /// of π/2, at powers of ten up to 10³⁰⁰ and at the special values.
    #[test]
    fn agrees_with_glibc_over_joint_angles_and_special_values() {
        let mut xs = Vec::new();
        let mut x = 0.0_f64;
        for _ in 0..1_000_000 {
            x = (x + 0.618_033_988_749_894_9) % 1.0;
            xs.push((x - 0.5) * 200.0);
        }
        for k in (-4000..=4000).filter(|&k| k != 0) {
            let x = k as f64 * std::f64::consts::FRAC_PI_2;
            for d in [-2i64, -1, 0, 1, 2] {
                xs.push(f64::from_bits((x.to_bits() as i64 + d) as u64));
            }
        }
        for k in -300..=300 {
            xs.extend([10f64.powi(k), -(10f64.powi(k))]);
        }
        xs.extend([
            1.6e6,
            1.7e6,
            1e7,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            0.0,
            -0.0,
        ]);
        while xs.len() % LANES != 0 {
            xs.push(0.1);
        }
        for chunk in xs.chunks_exact(LANES) {
            let x: [f64; LANES] = chunk.try_into().unwrap();
            let (s, c) = sin_cos_lanes(x);
            for l in 0..LANES {
                let (s0, c0) = x[l].sin_cos();
                assert!(
                    ulps(s[l], s0) <= 2.0,
                    "sin({:e}) = {:e}, glibc {s0:e}",
                    x[l],
                    s[l]
                );
                assert!(
                    ulps(c[l], c0) <= 2.0,
                    "cos({:e}) = {:e}, glibc {c0:e}",
                    x[l],
                    c[l]
                );
            }
        }
        let (s, c) = sin_cos_lanes([
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ]);
        for l in 0..3 {
            assert!(s[l].is_nan() && c[l].is_nan(), "lane {l}");
        }
        assert_eq!((s[4], c[4]), (0.0, 1.0));
        assert!(ulps(s[3], 1.0_f64.sin()) <= 2.0 && ulps(c[3], 1.0_f64.cos()) <= 2.0);
        assert!(sin_cos_lanes([-0.0_f64; LANES]).0[0].is_sign_negative());
    }

    /// A lane's result does not depend on its neighbours: a cancelling or huge angle in one
    /// lane leaves the bits of the others as they are alone.
    #[test]
    fn lanes_are_independent() {
        let plain = [0.3, -2.7, 11.0, 1e-9, 3.2e4, -0.0, 7.0, 1.5];
        let (s, c) = sin_cos_lanes(plain);
        let mut mixed = plain;
        mixed[1] = std::f64::consts::FRAC_PI_2 * 1000.0;
        mixed[6] = 1e9;
        let (sm, cm) = sin_cos_lanes(mixed);
        for l in [0, 2, 3, 4, 5, 7] {
            assert_eq!(
                (s[l].to_bits(), c[l].to_bits()),
                (sm[l].to_bits(), cm[l].to_bits())
            );
        }
    }
}
