//! Arms with three consecutive parallel axes 2 ∥ 3 ∥ 4 (along `n`) and the last two axes
//! meeting at a point `c₅₆` (Universal Robots UR3/5/10/16, the e-series, and their clones).
//!
//! With `G = T_d M⁻¹ = e^{[S₁]θ₁} ⋯ e^{[S₆]θ₆}`: rotations about lines along `n` keep `n·x`, and
//! `e^{[S₅]θ₅} e^{[S₆]θ₆}` keeps `c₅₆`, so
//!
//! ```text
//! n·(e^{−[S₁]θ₁} G c₅₆) = n·c₅₆                     θ₁ (subproblem 4)
//! n·(R₅ ω̂₆) = n·(R_a ω̂₆),  R_a = R₁ᵀ R_G            θ₅ (subproblem 4)
//! R₆ (R_aᵀ n) = R₅ᵀ n                              θ₆ (subproblem 1)
//! e^{[S₂]θ₂} e^{[S₃]θ₃} e^{[S₄]θ₄} = e^{−[S₁]θ₁} G e^{−[S₆]θ₆} e^{−[S₅]θ₅} = H
//! ```
//!
//! and the planar arm `H` is solved by subproblems 3 and 1 on a point of axis 4.

use super::super::subproblems::{sp1, sp3, sp4, wrap, Axis};
use super::geometry::{along, distance_to_line, meet, parallel, DISTANCE_TOL};
use super::Tolerance;
use crate::scalar::sin_cos_f64;
use crate::spatial::Se3;
use nalgebra::Vector3;

/// The geometry of a three-parallel arm, idealised: axes 3 and 4 exactly parallel to axis 2,
/// axes 5 and 6 through one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ThreeParallel {
    axes: [Axis; 6],
    /// `n = ω̂₂`.
    n: Vector3<f64>,
    /// Where axes 5 and 6 meet.
    c56: Vector3<f64>,
    /// A unit vector perpendicular to `n`.
    across_n: Vector3<f64>,
    /// `ω̂₃·n` and `ω̂₄·n` (±1): `θ₂ + s₃ θ₃ + s₄ θ₄` is the turn about `n`.
    signs: [f64; 2],
}

impl ThreeParallel {
    /// The family's geometry when the six axes (world frame, home pose, base to tip) have it.
    pub(crate) fn detect(axes: &[Axis; 6]) -> Option<ThreeParallel> {
        let [a1, a2, a3, a4, a5, a6] = axes;
        let n = a2.w;
        // 2 ∥ 3 ∥ 4 on three distinct lines; axes 1 and 5 not along n; axes 5 and 6 meet.
        if !parallel(a2, a3) || !parallel(a2, a4) || parallel(a1, a2) || parallel(a5, a2) {
            return None;
        }
        if distance_to_line(&a3.r, a2) <= DISTANCE_TOL
            || distance_to_line(&a4.r, a3) <= DISTANCE_TOL
        {
            return None;
        }
        let c56 = meet(a5, a6)?;
        let mut ideal = *axes;
        ideal[2] = along(a3, &n);
        ideal[3] = along(a4, &n);
        ideal[4].r = c56;
        ideal[5].r = c56;
        let across_n = super::geometry::perpendicular_unit(a2, &a1.w);
        let signs = [ideal[2].w.dot(&n), ideal[3].w.dot(&n)];
        Some(ThreeParallel {
            axes: ideal,
            n,
            c56,
            across_n,
            signs,
        })
    }

    /// Every exact solution for `G = T_d M⁻¹`, handed to `emit` (up to 2 × 2 × 2 branches; a
    /// branch is dropped as soon as one of its subproblems misses by more than `tolerance`).
    pub(crate) fn solve(&self, g: &Se3, tolerance: &Tolerance, emit: &mut impl FnMut([f64; 6])) {
        let [a1, a2, a3, a4, a5, a6] = &self.axes;
        let (n, c56) = (&self.n, &self.c56);
        let [s3, s4] = self.signs;
        let (d5, d6) = (a5.direction(), a6.direction());
        let about_n = Axis {
            w: *n,
            r: Vector3::zeros(),
        };
        // n·(e^{−[S₁]θ₁} G c₅₆) = n·c₅₆ (subproblem 4).
        let first = sp4(&a1.reversed(), n, &g.act_point(c56), n.dot(c56));
        for &theta1 in &first.theta[..first.count] {
            // e^{−[S₁]θ₁} G, whose rotation is R_a.
            let e1_inv_g = a1.reversed().exp(theta1).compose(g);
            let r_a = &e1_inv_g.rotation;
            // n·(R₅ ω̂₆) = n·(R_a ω̂₆) (subproblem 4 on directions).
            let fifth = sp4(&d5, n, &a6.w, n.dot(&(r_a * a6.w)));
            for &theta5 in &fifth.theta[..fifth.count] {
                let (s, c) = sin_cos_f64(theta5);
                let r5 = d5.rotation(s, c);
                // R₆ (R_aᵀ n) = R₅ᵀ n (subproblem 1); θ₆ = 0 when both lie on axis 6 (the
                // wrist singularity, where only θ₂ + θ₃ + θ₄ + θ₆ counts).
                let theta6 = sp1(&d6, &r_a.tr_mul(n), &r5.tr_mul(n)).theta;
                // H = e^{−[S₁]θ₁} G e^{−[S₆]θ₆} e^{−[S₅]θ₅} = e^{[S₂]θ₂} e^{[S₃]θ₃} e^{[S₄]θ₄}:
                // R_H must turn about n, by φ = θ₂ + s₃θ₃ + s₄θ₄ (subproblem 1).
                let h = e1_inv_g
                    .compose(&a6.reversed().exp(theta6))
                    .compose(&a5.reversed().exp(theta5));
                let x = &self.across_n;
                let turn = sp1(&about_n, x, &(h.rotation * x));
                let keeps_n = (h.rotation * n - n).norm();
                if turn.miss > tolerance.orientation || keeps_n > tolerance.orientation {
                    continue;
                }
                // Axis 4 keeps its points c₄: |e^{[S₃]θ₃} c₄ − r₂| = |H c₄ − r₂| (subproblem 3).
                let c4 = &a4.r;
                let y = h.act_point(c4);
                let third = sp3(a3, c4, &a2.r, (y - a2.r).norm());
                for &theta3 in &third.theta[..third.count] {
                    // e^{[S₂]θ₂} (e^{[S₃]θ₃} c₄) = H c₄ (subproblem 1). Exact, with R_H exact,
                    // it makes e^{[S₂]θ₂} e^{[S₃]θ₃} e^{[S₄]θ₄} = H.
                    let second = sp1(a2, &a3.exp(theta3).act_point(c4), &y);
                    if second.miss <= tolerance.position {
                        let theta2 = second.theta;
                        let theta4 = wrap(s4 * (turn.theta - theta2 - s3 * theta3));
                        emit([theta1, theta2, theta3, theta4, theta5, theta6]);
                    }
                }
            }
        }
    }
}
