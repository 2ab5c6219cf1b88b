//! The Paden–Kahan subproblems in product-of-exponentials form (Murray, Li & Sastry, *A
//! Mathematical Introduction to Robotic Manipulation*, §3.3; Lynch & Park, *Modern Robotics*,
//! §6.1), with the least-squares answers of IK-Geo (Elias & Wen 2022) where the exact problem
//! has none.
//!
//! Each revolute joint moves points by `e^{[S]θ}` with the unit screw axis
//! `S = (ω̂, −ω̂ × r)` of the line through `r` along `ω̂`:
//!
//! ```text
//! e^{[S]θ} x = r + R(ω̂, θ) (x − r),   R(ω̂, θ) = I + sin θ [ω̂] + (1 − cos θ) [ω̂]²
//! ```
//!
//! so every subproblem is first written about `r`: `u = p − r`, `w = q − r`, and `u⊥ = u − ω̂ (ω̂·u)`
//! is the part of `u` that the rotation turns. A rotation of directions (`R x = y`) is the same
//! problem with an axis through the origin. Every function returns fixed-size results and
//! allocates nothing; angles are in `(−π, π]`.

use crate::scalar::sin_cos_f64;
use crate::spatial::{Se3, Twist};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

/// Relative size below which the part of a vector that a rotation turns counts as zero: the
/// angle is then free, and [`sp1`] and [`sp4`] answer `θ = 0`.
const DEGENERATE: f64 = 1e-12;

/// The angle `θ` wrapped into `(−π, π]`.
#[inline]
pub(crate) fn wrap(theta: f64) -> f64 {
    if theta > -PI && theta <= PI {
        return theta;
    }
    let t = theta.rem_euclid(2.0 * PI);
    if t > PI {
        t - 2.0 * PI
    } else {
        t
    }
}

/// A revolute joint's line: the unit direction `ω̂` and a point `r` on it, the two halves of
/// its unit screw axis `S = (ω̂, −ω̂ × r)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Axis {
    /// `ω̂`, unit.
    pub w: Vector3<f64>,
    /// A point on the line.
    pub r: Vector3<f64>,
}

impl Axis {
    /// The line of the unit screw `S = (ω, v)` with `ω ≠ 0`: `ω̂ = ω / |ω|` and the point
    /// `r = ω̂ × v / |ω|` closest to the origin (`−ω̂ × r = v / |ω|` for a revolute screw).
    pub(crate) fn from_screw(s: &Twist) -> Axis {
        let omega = Vector3::new(s[0], s[1], s[2]);
        let v = Vector3::new(s[3], s[4], s[5]);
        let norm = omega.norm();
        let w = omega / norm;
        Axis {
            w,
            r: w.cross(&v) / norm,
        }
    }

    /// The same line, described by its point closest to `x`.
    pub(crate) fn anchored_near(&self, x: &Vector3<f64>) -> Axis {
        Axis {
            w: self.w,
            r: self.r + self.w * self.w.dot(&(x - self.r)),
        }
    }

    /// The line along `w` (normalised) through `r`.
    pub(crate) fn through(r: Vector3<f64>, w: Vector3<f64>) -> Axis {
        Axis {
            w: w.normalize(),
            r,
        }
    }

    /// The same line turning the other way: the screw `−S`, so `e^{[−S]θ} = e^{−[S]θ}`.
    pub(crate) fn reversed(&self) -> Axis {
        Axis {
            w: -self.w,
            r: self.r,
        }
    }

    /// The same direction through the origin: the rotation `R(ω̂, θ)` acting on directions.
    pub(crate) fn direction(&self) -> Axis {
        Axis {
            w: self.w,
            r: Vector3::zeros(),
        }
    }

    /// `R(ω̂, θ) = I + sin θ [ω̂] + (1 − cos θ) [ω̂]²` from `(sin θ, cos θ)` (Rodrigues).
    #[inline]
    pub(crate) fn rotation(&self, sin: f64, cos: f64) -> Matrix3<f64> {
        let w = &self.w;
        let k = 1.0 - cos;
        let (xy, xz, yz) = (k * w.x * w.y, k * w.x * w.z, k * w.y * w.z);
        let (sx, sy, sz) = (sin * w.x, sin * w.y, sin * w.z);
        Matrix3::new(
            cos + k * w.x * w.x,
            xy - sz,
            xz + sy,
            xy + sz,
            cos + k * w.y * w.y,
            yz - sx,
            xz - sy,
            yz + sx,
            cos + k * w.z * w.z,
        )
    }

    /// `e^{[S]θ} = [R  (I − R) r; 0 1]`, the displacement of the joint by `θ`.
    #[inline]
    pub(crate) fn exp(&self, theta: f64) -> Se3 {
        let (s, c) = sin_cos_f64(theta);
        let rotation = self.rotation(s, c);
        Se3::new(rotation, self.r - rotation * self.r)
    }
}

/// The answer of subproblem 1: the angle and how far it misses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Turn {
    /// `θ`, in `(−π, π]`.
    pub theta: f64,
    /// `|e^{[S]θ} p − q|`: zero when the problem is exact.
    pub miss: f64,
}

/// Subproblem 1, rotation about one axis: the `θ` with `e^{[S]θ} p = q`.
///
/// About `r`: `R(ω̂, θ) u⊥ = w⊥`, so `θ = atan2(ω̂·(u⊥ × w⊥), u⊥·w⊥)`. When `ω̂·u ≠ ω̂·w` or
/// `|u⊥| ≠ |w⊥|` there is no exact answer and this `θ` minimises `|e^{[S]θ} p − q|`, which is
/// then `√((ω̂·u − ω̂·w)² + (|u⊥| − |w⊥|)²)`. When `p` or `q` lies on the axis (`|u⊥|` or `|w⊥|`
/// below 10⁻¹² of the larger of `|u|`, `|w|`) every `θ` is as good: the answer is `θ = 0`.
#[inline]
pub(crate) fn sp1(axis: &Axis, p: &Vector3<f64>, q: &Vector3<f64>) -> Turn {
    let (u, w) = (p - axis.r, q - axis.r);
    let (along_u, along_w) = (axis.w.dot(&u), axis.w.dot(&w));
    let (u_perp, w_perp) = (u - axis.w * along_u, w - axis.w * along_w);
    let (u_norm, w_norm) = (u_perp.norm(), w_perp.norm());
    // √(x² + y²) written out: `hypot`'s guard against overflow costs as much as the rest.
    let (da, dn) = (along_u - along_w, u_norm - w_norm);
    let miss = (da * da + dn * dn).sqrt();
    let degenerate = DEGENERATE * u.norm().max(w.norm());
    let theta = if u_norm <= degenerate || w_norm <= degenerate {
        0.0
    } else {
        axis.w
            .dot(&u_perp.cross(&w_perp))
            .atan2(u_perp.dot(&w_perp))
    };
    Turn { theta, miss }
}

/// Up to two angles: `count` of them in `theta`. `count = 1` also answers a problem without an
/// exact solution (its least-squares angle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Roots {
    /// The angles, in `(−π, π]`.
    pub theta: [f64; 2],
    /// How many of `theta` are answers (1 or 2).
    pub count: usize,
}

impl Roots {
    fn one(theta: f64) -> Roots {
        Roots {
            theta: [wrap(theta), 0.0],
            count: 1,
        }
    }
}

/// Subproblem 4, rotation to a plane: the `θ` with `h·(e^{[S]θ} p) = d` (`h` need not be unit).
///
/// About `r`, with `R u = ω̂ (ω̂·u) + cos θ u⊥ + sin θ (ω̂ × u)`, the condition reads
/// `A cos θ + B sin θ = C` with `A = h·u⊥`, `B = h·(ω̂ × u)`, `C = d − h·r − (h·ω̂)(ω̂·u)`; with
/// `ρ = √(A² + B²)` and `φ = atan2(B, A)`, `θ = φ ± acos(C/ρ)`. When `|C| ≥ ρ` the plane is
/// out of reach (or just touched): the one answer `θ = φ` (or `φ + π` for `C < 0`) minimises
/// `|h·(e^{[S]θ} p) − d|`. When `ρ` is below 10⁻¹² of `|h| |u|` the left side does not depend
/// on `θ` (`p` on the axis, or `h` along it): the answer is `θ = 0`.
#[inline]
pub(crate) fn sp4(axis: &Axis, h: &Vector3<f64>, p: &Vector3<f64>, d: f64) -> Roots {
    let u = p - axis.r;
    let along = axis.w.dot(&u);
    let a = h.dot(&(u - axis.w * along));
    let b = h.dot(&axis.w.cross(&u));
    let c = d - h.dot(&axis.r) - h.dot(&axis.w) * along;
    let rho = (a * a + b * b).sqrt();
    if rho <= DEGENERATE * h.norm() * u.norm() || rho == 0.0 {
        return Roots::one(0.0);
    }
    let phi = b.atan2(a);
    if c.abs() >= rho {
        return Roots::one(if c > 0.0 { phi } else { phi + PI });
    }
    let psi = (c / rho).acos();
    Roots {
        theta: [wrap(phi + psi), wrap(phi - psi)],
        count: 2,
    }
}

/// Subproblem 3, rotation to a distance: the `θ` with `|e^{[S]θ} p − q| = δ`.
///
/// About `r`, `|R u − w|² = |u|² + |w|² − 2 w·(R u)`, so this is subproblem 4 with `h = q − r`
/// and `h·(R u) = (|u|² + |w|² − δ²) / 2` (IK-Geo's reduction). Out of reach, the one answer
/// minimises `| |e^{[S]θ} p − q|² − δ² |` (the nearest or farthest point of the circle).
#[inline]
pub(crate) fn sp3(axis: &Axis, p: &Vector3<f64>, q: &Vector3<f64>, delta: f64) -> Roots {
    let (u, w) = (p - axis.r, q - axis.r);
    let d = 0.5 * (u.norm_squared() + w.norm_squared() - delta * delta);
    // `sp4` about the origin of `u`: the axis through `r` with `u` and `h = w`.
    let about_r = axis.direction();
    sp4(&about_r, &w, &u, d)
}

/// Up to two pairs of angles `(θ₁, θ₂)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pairs {
    /// `θ₁` of each pair.
    pub theta1: [f64; 2],
    /// `θ₂` of each pair.
    pub theta2: [f64; 2],
    /// A bound on `|e^{[S₁]θ₁} e^{[S₂]θ₂} p − q|` of each pair: zero when it is exact.
    pub miss: [f64; 2],
    /// How many pairs are answers (1 or 2).
    pub count: usize,
}

/// Subproblem 2, rotation about two intersecting axes: the `(θ₁, θ₂)` with
/// `e^{[S₁]θ₁} e^{[S₂]θ₂} p = q`, for non-parallel axes meeting at the point `c = first.r`
/// (`second` must pass through it).
///
/// The intermediate point `z = e^{[S₂]θ₂} p = e^{−[S₁]θ₁} q` (about `c`) keeps `ω̂₂·z = ω̂₂·u`,
/// `ω̂₁·z = ω̂₁·w` and `|z| = |u|`. With `z = α ω̂₁ + β ω̂₂ + γ (ω̂₁ × ω̂₂)` and `k = ω̂₁·ω̂₂`:
///
/// ```text
/// α = (ω̂₁·w − k ω̂₂·u) / (1 − k²),   β = (ω̂₂·u − k ω̂₁·w) / (1 − k²),
/// γ² = (|u|² − α² − β² − 2 k α β) / (1 − k²)
/// ```
///
/// then `θ₂` takes `p` to `z` and `θ₁` takes `z` to `q` (subproblem 1), once for each sign of
/// `γ`; the pair misses by at most the sum of the two misses. When `γ² < 0` the two circles do
/// not meet: the one pair with `γ = 0` turns `p` and `q` as close as they come to the point `z`
/// of the plane of the axes. (`|u|²` is taken as the mean of `|u|²` and `|w|²`, equal when the
/// problem is exact.)
#[inline]
pub(crate) fn sp2(first: &Axis, second: &Axis, p: &Vector3<f64>, q: &Vector3<f64>) -> Pairs {
    let c = first.r;
    let (u, w) = (p - c, q - c);
    let (w1, w2) = (&first.w, &second.w);
    let k = w1.dot(w2);
    let sin2 = 1.0 - k * k;
    let (w1_w, w2_u) = (w1.dot(&w), w2.dot(&u));
    let alpha = (w1_w - k * w2_u) / sin2;
    let beta = (w2_u - k * w1_w) / sin2;
    let radius2 = 0.5 * (u.norm_squared() + w.norm_squared());
    let gamma2 = (radius2 - alpha * alpha - beta * beta - 2.0 * k * alpha * beta) / sin2;
    let in_plane = w1 * alpha + w2 * beta;
    let normal = w1.cross(w2);
    let mut pairs = Pairs {
        theta1: [0.0; 2],
        theta2: [0.0; 2],
        miss: [0.0; 2],
        count: if gamma2 > 0.0 { 2 } else { 1 },
    };
    let gamma = gamma2.max(0.0).sqrt();
    for (i, sign) in [1.0, -1.0].into_iter().enumerate().take(pairs.count) {
        let z = c + in_plane + normal * (sign * gamma);
        let (second_turn, first_turn) = (sp1(second, p, &z), sp1(first, &z, q));
        pairs.theta2[i] = second_turn.theta;
        pairs.theta1[i] = first_turn.theta;
        pairs.miss[i] = second_turn.miss + first_turn.miss;
    }
    pairs
}

#[cfg(test)]
mod tests {
    //! Each subproblem against its defining equation: random axes, angles and points, the
    //! constructed answer recovered; least-squares answers against a dense scan of `θ`.
    use super::*;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    fn vec3(rng: &mut StdRng) -> Vector3<f64> {
        Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        )
    }

    fn axis(rng: &mut StdRng) -> Axis {
        Axis::through(vec3(rng), vec3(rng))
    }

    /// The rotation by `Se3::exp_screw` (the library's SE(3) exponential), independent of
    /// `Axis::exp`.
    fn moved(a: &Axis, theta: f64, p: &Vector3<f64>) -> Vector3<f64> {
        let s = crate::spatial::revolute_screw(a.w, a.r);
        Se3::exp_screw(&s, theta).act_point(p)
    }

    fn same_angle(a: f64, b: f64) -> bool {
        wrap(a - b).abs() < 1e-9
    }

    #[test]
    fn axis_exp_is_the_screw_exponential() {
        let mut rng = StdRng::seed_from_u64(1);
        for _ in 0..100 {
            let a = axis(&mut rng);
            let s = crate::spatial::revolute_screw(a.w, a.r);
            assert!((Axis::from_screw(&s).w - a.w).norm() < 1e-15);
            let theta = rng.gen_range(-4.0..4.0);
            let h = Se3::exp_screw(&s, theta);
            let g = Axis::from_screw(&s).exp(theta);
            assert!((h.to_matrix() - g.to_matrix()).amax() < 1e-14);
        }
    }

    #[test]
    fn sp1_recovers_the_angle_and_is_least_squares_otherwise() {
        let mut rng = StdRng::seed_from_u64(2);
        for _ in 0..200 {
            let a = axis(&mut rng);
            let p = vec3(&mut rng);
            let theta = rng.gen_range(-PI..PI);
            let q = moved(&a, theta, &p);
            let turn = sp1(&a, &p, &q);
            assert!(same_angle(turn.theta, theta) && turn.miss < 1e-14);
            // A q off the circle: no angle on a fine grid does better than sp1's, and the
            // miss is what it says.
            let q = q + vec3(&mut rng) * 0.3;
            let turn = sp1(&a, &p, &q);
            let best = (moved(&a, turn.theta, &p) - q).norm();
            assert!((turn.miss - best).abs() < 1e-14);
            for k in 0..2000 {
                let t = -PI + 2.0 * PI * k as f64 / 2000.0;
                assert!(best <= (moved(&a, t, &p) - q).norm() + 1e-12);
            }
        }
        // p on the axis: every angle is an answer, θ = 0 is chosen.
        let a = Axis::through(Vector3::zeros(), Vector3::z());
        let turn = sp1(&a, &Vector3::new(0.0, 0.0, 2.0), &Vector3::x());
        assert_eq!(turn.theta, 0.0);
        assert!((turn.miss - 5.0_f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn sp4_finds_both_angles_and_the_closest_one_out_of_reach() {
        let mut rng = StdRng::seed_from_u64(3);
        for _ in 0..200 {
            let a = axis(&mut rng);
            let (p, h) = (vec3(&mut rng), vec3(&mut rng));
            let theta = rng.gen_range(-PI..PI);
            let d = h.dot(&moved(&a, theta, &p));
            let roots = sp4(&a, &h, &p, d);
            assert_eq!(roots.count, 2);
            assert!(roots.theta.iter().any(|&t| same_angle(t, theta)));
            for &t in &roots.theta {
                assert!((h.dot(&moved(&a, t, &p)) - d).abs() < 1e-12);
            }
            // Out of reach: the one answer is the best of a fine grid.
            let far = d + 10.0 * rng.gen_range(-1.0..1.0_f64).signum();
            let roots = sp4(&a, &h, &p, far);
            assert_eq!(roots.count, 1);
            let best = (h.dot(&moved(&a, roots.theta[0], &p)) - far).abs();
            for k in 0..2000 {
                let t = -PI + 2.0 * PI * k as f64 / 2000.0;
                assert!(best <= (h.dot(&moved(&a, t, &p)) - far).abs() + 1e-12);
            }
        }
    }

    #[test]
    fn sp3_finds_both_angles_and_the_closest_one_out_of_reach() {
        let mut rng = StdRng::seed_from_u64(4);
        for _ in 0..200 {
            let a = axis(&mut rng);
            let (p, q) = (vec3(&mut rng), vec3(&mut rng));
            let theta = rng.gen_range(-PI..PI);
            let delta = (moved(&a, theta, &p) - q).norm();
            let roots = sp3(&a, &p, &q, delta);
            assert_eq!(roots.count, 2);
            assert!(roots.theta.iter().any(|&t| same_angle(t, theta)));
            for &t in &roots.theta {
                assert!(((moved(&a, t, &p) - q).norm() - delta).abs() < 1e-12);
            }
            let far = delta + 10.0;
            let roots = sp3(&a, &p, &q, far);
            assert_eq!(roots.count, 1);
            let err = |t: f64| ((moved(&a, t, &p) - q).norm() - far).abs();
            let best = err(roots.theta[0]);
            for k in 0..2000 {
                assert!(best <= err(-PI + 2.0 * PI * k as f64 / 2000.0) + 1e-12);
            }
        }
    }

    #[test]
    fn sp2_finds_both_pairs() {
        let mut rng = StdRng::seed_from_u64(5);
        for _ in 0..200 {
            let c = vec3(&mut rng);
            let (a1, a2) = (
                Axis::through(c, vec3(&mut rng)),
                Axis::through(c, vec3(&mut rng)),
            );
            let p = vec3(&mut rng);
            let (t1, t2) = (rng.gen_range(-PI..PI), rng.gen_range(-PI..PI));
            let q = moved(&a1, t1, &moved(&a2, t2, &p));
            let pairs = sp2(&a1, &a2, &p, &q);
            assert_eq!(pairs.count, 2);
            assert!(
                (0..2).any(|i| same_angle(pairs.theta1[i], t1) && same_angle(pairs.theta2[i], t2))
            );
            for i in 0..2 {
                let back = moved(&a1, pairs.theta1[i], &moved(&a2, pairs.theta2[i], &p));
                assert!((back - q).norm() < 1e-12 && pairs.miss[i] < 1e-12);
            }
        }
        // Two circles that do not meet: one finite pair.
        let (a1, a2) = (
            Axis::through(Vector3::zeros(), Vector3::z()),
            Axis::through(Vector3::zeros(), Vector3::x()),
        );
        let pairs = sp2(&a1, &a2, &Vector3::x(), &Vector3::z());
        assert_eq!(pairs.count, 1);
        assert!(pairs.theta1[0].is_finite() && pairs.theta2[0].is_finite());
        let back = moved(
            &a1,
            pairs.theta1[0],
            &moved(&a2, pairs.theta2[0], &Vector3::x()),
        );
        assert!(pairs.miss[0] >= (back - Vector3::z()).norm() - 1e-15 && pairs.miss[0] > 0.1);
    }
}
