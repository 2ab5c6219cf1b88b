//! Arms whose last three axes meet in one point `p_w`, the wrist centre (Puma 560, ABB IRB,
//! KUKA KR, Stäubli, Fanuc): the position of `p_w` fixes `θ₁, θ₂, θ₃`, then the orientation fixes
//! `θ₄, θ₅, θ₆` (Pieper's decoupling; Murray, Li & Sastry §3.3, *Modern Robotics* §6.1.1).
//!
//! With `G = T_d M⁻¹ = e^{[S₁]θ₁} ⋯ e^{[S₆]θ₆}` and `e^{[S₄]θ₄} e^{[S₅]θ₅} e^{[S₆]θ₆} p_w = p_w`:
//!
//! ```text
//! e^{[S₁]θ₁} e^{[S₂]θ₂} e^{[S₃]θ₃} p_w = G p_w = p_d                      (position)
//! R(ω̂₄, θ₄) R(ω̂₅, θ₅) R(ω̂₆, θ₆) = (R₁ R₂ R₃)ᵀ R_G = R_w                 (orientation)
//! ```

use super::super::subproblems::{sp1, sp2, sp3, sp4, Axis};
use super::geometry::{
    along, distance_to_line, meet, meeting_point, parallel, perpendicular_unit, sine, ANGLE_TOL,
    DISTANCE_TOL,
};
use super::Tolerance;
use crate::scalar::sin_cos_f64;
use crate::spatial::Se3;
use nalgebra::{Matrix3, Vector3};

/// How the first three joints place the wrist centre.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Position {
    /// Axes 2 and 3 parallel (along `n`), axis 1 not: the elbow arms.
    Parallel23 { n: Vector3<f64> },
    /// Axes 1 and 2 meet at `c`, axis 3 passes elsewhere.
    Meeting12 { c: Vector3<f64> },
}

/// The geometry of a spherical-wrist arm, idealised: the wrist axes through one point, the
/// parallel axes exactly parallel, the meeting axes through one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SphericalWrist {
    axes: [Axis; 6],
    wrist_center: Vector3<f64>,
    position: Position,
    /// A unit vector perpendicular to `ω̂₆`, turned by `θ₆` only.
    across_6: Vector3<f64>,
}

/// `R(ω̂, θ)` of an axis.
#[inline]
fn rotation(axis: &Axis, theta: f64) -> Matrix3<f64> {
    let (s, c) = sin_cos_f64(theta);
    axis.rotation(s, c)
}

impl SphericalWrist {
    /// The family's geometry when the six axes (world frame, home pose, base to tip) have it.
    pub(crate) fn detect(axes: &[Axis; 6]) -> Option<SphericalWrist> {
        let [a1, a2, a3, a4, a5, a6] = axes;
        // Axes 4, 5, 6 cross each other (4 ∦ 5, 5 ∦ 6) and meet in one point.
        if sine(a4, a5) <= ANGLE_TOL || sine(a5, a6) <= ANGLE_TOL {
            return None;
        }
        let (wrist_center, spread) = meeting_point(&[a4, a5, a6])?;
        if spread > DISTANCE_TOL || distance_to_line(&wrist_center, a3) <= DISTANCE_TOL {
            return None;
        }
        let mut ideal = *axes;
        for (i, axis) in [a4, a5, a6].into_iter().enumerate() {
            ideal[3 + i] = Axis {
                w: axis.w,
                r: wrist_center,
            };
        }
        let distinct_23 = distance_to_line(&a3.r, a2) > DISTANCE_TOL;
        let position = if parallel(a2, a3) && !parallel(a1, a2) && distinct_23 {
            // Axis 3 made exactly parallel to axis 2.
            ideal[2] = along(a3, &a2.w);
            Position::Parallel23 { n: a2.w }
        } else {
            let c = meet(a1, a2)?;
            if distance_to_line(&c, a3) <= DISTANCE_TOL {
                return None;
            }
            ideal[0].r = c;
            ideal[1].r = c;
            Position::Meeting12 { c }
        };
        let across_6 = perpendicular_unit(a6, &a5.w);
        Some(SphericalWrist {
            axes: ideal,
            wrist_center,
            position,
            across_6,
        })
    }

    /// Every exact solution for `G = T_d M⁻¹`, handed to `emit` (up to 2 × 2 × 2 branches; a
    /// branch is dropped as soon as one of its subproblems misses by more than `tolerance`).
    pub(crate) fn solve(&self, g: &Se3, tolerance: &Tolerance, emit: &mut impl FnMut([f64; 6])) {
        let [a1, a2, a3, ..] = &self.axes;
        let wrist = &self.wrist_center;
        let target = g.act_point(wrist);
        match self.position {
            Position::Parallel23 { n } => {
                // Rotations about axes 2 and 3 keep n·x: n·(e^{−[S₁]θ₁} p_d) = n·p_w (subproblem 4).
                let first = sp4(&a1.reversed(), &n, &target, n.dot(wrist));
                for &theta1 in &first.theta[..first.count] {
                    let y = a1.reversed().exp(theta1).act_point(&target);
                    // Rotations about axis 2 keep distances to it:
                    // |e^{[S₃]θ₃} p_w − r₂| = |e^{−[S₁]θ₁} p_d − r₂| (subproblem 3).
                    let third = sp3(a3, wrist, &a2.r, (y - a2.r).norm());
                    for &theta3 in &third.theta[..third.count] {
                        // e^{[S₂]θ₂} (e^{[S₃]θ₃} p_w) = e^{−[S₁]θ₁} p_d (subproblem 1); its miss
                        // is the miss of the wrist centre.
                        let moved = a3.exp(theta3).act_point(wrist);
                        let second = sp1(a2, &moved, &y);
                        if second.miss <= tolerance.position {
                            self.orient(g, [theta1, second.theta, theta3], tolerance, emit);
                        }
                    }
                }
            }
            Position::Meeting12 { c } => {
                // Rotations about axes 1 and 2 keep distances to c:
                // |e^{[S₃]θ₃} p_w − c| = |p_d − c| (subproblem 3).
                let third = sp3(a3, wrist, &c, (target - c).norm());
                for &theta3 in &third.theta[..third.count] {
                    // e^{[S₁]θ₁} e^{[S₂]θ₂} (e^{[S₃]θ₃} p_w) = p_d (subproblem 2).
                    let moved = a3.exp(theta3).act_point(wrist);
                    let pairs = sp2(a1, a2, &moved, &target);
                    for i in 0..pairs.count {
                        if pairs.miss[i] <= tolerance.position {
                            let arm = [pairs.theta1[i], pairs.theta2[i], theta3];
                            self.orient(g, arm, tolerance, emit);
                        }
                    }
                }
            }
        }
    }

    /// The wrist angles for one placement of the first three joints.
    fn orient(
        &self,
        g: &Se3,
        arm: [f64; 3],
        tolerance: &Tolerance,
        emit: &mut impl FnMut([f64; 6]),
    ) {
        let [a1, a2, a3, a4, a5, a6] = &self.axes;
        let [theta1, theta2, theta3] = arm;
        // R_w = (R₁ R₂ R₃)ᵀ R_G.
        let r123 = rotation(a1, theta1) * rotation(a2, theta2) * rotation(a3, theta3);
        let r_w = r123.tr_mul(&g.rotation);
        // R₆ keeps ω̂₆: R₄ R₅ ω̂₆ = R_w ω̂₆ (subproblem 2 on directions).
        let (d4, d5, d6) = (a4.direction(), a5.direction(), a6.direction());
        let pairs = sp2(&d4, &d5, &a6.w, &(r_w * a6.w));
        for i in 0..pairs.count {
            let (theta4, theta5) = (pairs.theta1[i], pairs.theta2[i]);
            // R₆ x = (R₄ R₅)ᵀ R_w x for x ⟂ ω̂₆ (subproblem 1). With R₄ R₅ R₆ ω̂₆ = R_w ω̂₆, both
            // exact means R₄ R₅ R₆ = R_w.
            let r45 = rotation(a4, theta4) * rotation(a5, theta5);
            let x = &self.across_6;
            let sixth = sp1(&d6, x, &r45.tr_mul(&(r_w * x)));
            if pairs.miss[i] <= tolerance.orientation && sixth.miss <= tolerance.orientation {
                emit([theta1, theta2, theta3, theta4, theta5, sixth.theta]);
            }
        }
    }
}
