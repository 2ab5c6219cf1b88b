//! [`Lanes`]: `L` doubles, one per robot state, with element-wise arithmetic.
//!
//! The batch kernels are the scalar algorithms written once over `Lanes<L>`: every `+`, `−`,
//! `×`, `÷` acts on the `L` states side by side. The type is a plain array, so the compiler turns
//! each operation into SIMD instructions of whatever width the CPU-specific clone it is inlined
//! into allows (8 doubles in one AVX-512 register, 2 × 4 with AVX2), while the
//! result of every lane stays bit-for-bit what the same operations give on one `f64`: the
//! operations are IEEE additions, multiplications and fused multiply–adds
//! ([`Lanes::mul_add`], where the kernels ask for them) applied in the same order, never
//! reassociated. So `Lanes<1>` (one state) and `Lanes<8>` (eight) give identical numbers.
//!
//! Why not a SIMD crate: `std::simd` is nightly-only, and the stable crates (`wide`, simba's
//! `WideF64x4`) pick their instruction set when the library is compiled, which for a portable
//! build is SSE2; plain arrays inlined into run-time-dispatched clones reach AVX-512 without
//! giving up portable builds.

use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// `L` doubles, one per state, with element-wise arithmetic (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct Lanes<const L: usize>(pub [f64; L]);

impl<const L: usize> Default for Lanes<L> {
    #[inline(always)]
    fn default() -> Self {
        Self::splat(0.0)
    }
}

impl<const L: usize> From<f64> for Lanes<L> {
    #[inline(always)]
    fn from(x: f64) -> Self {
        Self::splat(x)
    }
}

impl<const L: usize> Lanes<L> {
    /// Every lane `x`.
    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        Lanes([x; L])
    }

    /// Every lane zero.
    #[inline(always)]
    pub fn zero() -> Self {
        Self::splat(0.0)
    }

    /// `(sin x, cos x)` of every lane, each within one unit in the last place
    /// ([`crate::scalar::sin_cos_array`]: the Cody–Waite reduction and fdlibm polynomials of
    /// [`crate::scalar::sin_cos_f64`] lane by lane, with fused multiply–adds; the further
    /// pieces of `π/2` only for the lanes that need them). Angles beyond `|x| ≥ 2²⁰ π/2`
    /// (≈ 1.6·10⁶ rad), ±∞ and NaN go to `f64::sin_cos`.
    #[inline(always)]
    pub fn sin_cos(self) -> (Self, Self) {
        let (s, c) = crate::scalar::sin_cos_array(self.0);
        (Lanes(s), Lanes(c))
    }

    /// `self a + b` in every lane, rounded once (a fused multiply–add, as [`f64::mul_add`]):
    /// one instruction for the eight lanes in the AVX-512 and AVX2 clones.
    #[inline(always)]
    pub fn mul_add(self, a: impl Into<Self>, b: Self) -> Self {
        let a = a.into();
        let mut r = self;
        for ((r, &a), &b) in r.0.iter_mut().zip(&a.0).zip(&b.0) {
            *r = r.mul_add(a, b);
        }
        r
    }

    /// The smallest lane, NaN if any lane is NaN.
    #[inline(always)]
    pub fn min_or_nan(self) -> f64 {
        self.0.iter().fold(
            f64::INFINITY,
            |m, &x| if x < m || x.is_nan() { x } else { m },
        )
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign_method:ident, $op:tt) => {
        impl<const L: usize> $trait for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                let mut r = [0.0; L];
                for l in 0..L {
                    r[l] = self.0[l] $op o.0[l];
                }
                Lanes(r)
            }
        }
        impl<const L: usize> $trait<f64> for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: f64) -> Self {
                let mut r = [0.0; L];
                for l in 0..L {
                    r[l] = self.0[l] $op o;
                }
                Lanes(r)
            }
        }
        impl<const L: usize> $trait<Lanes<L>> for f64 {
            type Output = Lanes<L>;
            #[inline(always)]
            fn $method(self, o: Lanes<L>) -> Lanes<L> {
                let mut r = [0.0; L];
                for l in 0..L {
                    r[l] = self $op o.0[l];
                }
                Lanes(r)
            }
        }
        impl<const L: usize> $assign_trait for Lanes<L> {
            #[inline(always)]
            fn $assign_method(&mut self, o: Self) {
                *self = *self $op o;
            }
        }
    };
}

lane_op!(Add, add, AddAssign, add_assign, +);
lane_op!(Sub, sub, SubAssign, sub_assign, -);
lane_op!(Mul, mul, MulAssign, mul_assign, *);
lane_op!(Div, div, DivAssign, div_assign, /);

impl<const L: usize> Neg for Lanes<L> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        let mut r = self.0;
        for x in r.iter_mut() {
            *x = -*x;
        }
        Lanes(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Element-wise arithmetic, lane by lane (formerly the type's doc example).
    #[test]
    fn arithmetic_acts_lane_by_lane() {
        let x = Lanes([1.0, 2.0, 3.0, 4.0]);
        let y = x * x - Lanes::splat(1.0);
        assert_eq!(y.0, [0.0, 3.0, 8.0, 15.0]);
        assert_eq!((y * 2.0).0[3], 30.0);
    }

    /// A few angles against `f64::sin`/`cos` (formerly `sin_cos`'s doc example).
    #[test]
    fn sin_cos_of_a_few_angles() {
        let (s, c) = Lanes([0.0, 1.0, -2.0, 1e3]).sin_cos();
        for (k, x) in [0.0_f64, 1.0, -2.0, 1e3].into_iter().enumerate() {
            assert!((s.0[k] - x.sin()).abs() <= 2.0 * f64::EPSILON);
            assert!((c.0[k] - x.cos()).abs() <= 2.0 * f64::EPSILON);
        }
    }

    /// One rounding per lane, as `f64::mul_add` (formerly `mul_add`'s doc example).
    #[test]
    fn mul_add_rounds_once_per_lane() {
        let x = Lanes([0.1, 3.0]);
        assert_eq!(
            x.mul_add(10.0, Lanes([-1.0, 1.0])).0,
            [0.1_f64.mul_add(10.0, -1.0), 31.0]
        );
    }

    /// One lane and eight lanes give the same bits (the property batches rely on).
    #[test]
    fn lane_count_does_not_change_the_bits() {
        let xs = [0.3, -2.7, 11.0, 1e-9, 3.2e4, -0.0, 7.0, 1.5e6];
        let (s8, c8) = Lanes(xs).sin_cos();
        for (l, &x) in xs.iter().enumerate() {
            let (s1, c1) = Lanes([x]).sin_cos();
            assert_eq!(s1.0[0].to_bits(), s8.0[l].to_bits());
            assert_eq!(c1.0[0].to_bits(), c8.0[l].to_bits());
        }
        let (a, b) = (Lanes(xs), Lanes(xs.map(|x| x * 0.7 + 1.0)));
        let r8 = (a * b + a / b - b) * 3.0;
        for (l, (&x, &y)) in xs.iter().zip(&b.0).enumerate() {
            let (x, y) = (Lanes([x]), Lanes([y]));
            let r1 = (x * y + x / y - y) * 3.0;
            assert_eq!(r1.0[0].to_bits(), r8.0[l].to_bits());
        }
    }
}
