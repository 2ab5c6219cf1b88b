//! A joint's screw for the batch kernels: `H_i^{λ(i)}(q) = H_i^{λ(i)}(0) e^{[S]q}` (Lynch & Park, *Modern Robotics*,
//! forward iterations) and the products with `S` the algorithms need, on lanes.
//!
//! Two shapes: the joints of most arms, which turn about a coordinate axis of their frame
//! through its origin (as [`JointMotion::RevoluteAxis`]: a rotation of two columns of the home
//! rotation, one entry of `S`), and every other screw, whose pose is written once, when the
//! batch workspace is made, as `R(q) = R₀ + sin(|ω|q) R₁ + cos(|ω|q) R₂` and
//! `p(q) = p₀ + q p₁ + sin(|ω|q) p₂ + cos(|ω|q) p₃` (Rodrigues' formula and the screw's
//! translation `(1 q + (1 − cos)[ω]/|ω|² + (|ω|q − sin)[ω]²/|ω|³) v` of Lynch & Park's *Modern Robotics*, multiplied
//! out with the home pose).

use super::lanes::Lanes;
use super::spatial::{cross, join, Pose, V6};
use crate::model::{JointMotion, Model};
use crate::spatial::{hat, Se3};
use nalgebra::{Matrix3, Vector3};

/// The coefficients of a general joint's pose (see the module documentation).
#[derive(Clone, Debug)]
pub struct ScrewPose {
    /// `|ω|`: the angle of `sin` and `cos` is `|ω| q` (zero for a prismatic joint).
    rate: f64,
    /// `R₀, R₁, R₂`, home rotation included.
    r: [Matrix3<f64>; 3],
    /// `p₀, p₁, p₂, p₃`, home pose included.
    p: [Vector3<f64>; 4],
}

/// A joint as the batch kernels use it.
#[derive(Clone, Debug)]
pub enum LaneJoint {
    /// Rotation about `sign ê_axis` through the child-frame origin.
    Axis {
        /// 0, 1, 2 for x, y, z.
        axis: usize,
        /// `±1`.
        sign: f64,
        /// `H_i^{λ(i)}(0)`.
        home: Se3<f64>,
    },
    /// Any other screw `S`.
    Screw {
        /// `S = (ω, v)`.
        screw: [f64; 6],
        /// The pose coefficients.
        pose: Box<ScrewPose>,
    },
}

impl LaneJoint {
    /// The joints of `model`, in body order.
    pub fn of(model: &Model) -> Vec<LaneJoint> {
        model
            .joints()
            .iter()
            .zip(model.motions())
            .map(|(j, m)| match *m {
                JointMotion::RevoluteAxis { axis, sign } => LaneJoint::Axis {
                    axis,
                    sign,
                    home: j.home,
                },
                _ => {
                    let s = m.screw();
                    LaneJoint::Screw {
                        screw: [s[0], s[1], s[2], s[3], s[4], s[5]],
                        pose: Box::new(ScrewPose::new(&j.home, &m.screw())),
                    }
                }
            })
            .collect()
    }

    /// `(sin, cos)` of the joint's angle at `q` (`±q` about an axis, `|ω| q` for a screw; zeros
    /// for a prismatic joint, which has none), for [`LaneJoint::pose_in_parent`].
    #[inline(always)]
    pub fn sin_cos<const L: usize>(&self, q: Lanes<L>) -> (Lanes<L>, Lanes<L>) {
        match self {
            LaneJoint::Axis { sign, .. } => (q * *sign).sin_cos(),
            LaneJoint::Screw { pose, .. } if pose.rate != 0.0 => (q * pose.rate).sin_cos(),
            LaneJoint::Screw { .. } => (Lanes::zero(), Lanes::zero()),
        }
    }

    /// `H_i^{λ(i)}(q)` in every lane, given `(s, c)` = [`LaneJoint::sin_cos`]`(q)`.
    #[inline(always)]
    pub fn pose_in_parent<const L: usize>(
        &self,
        q: Lanes<L>,
        (s, c): (Lanes<L>, Lanes<L>),
    ) -> Pose<L> {
        match self {
            LaneJoint::Axis { axis, home, .. } => {
                // R(0) Rot_k(θ): columns (i, j) of R(0) turn (as JointMotion::pose_in_parent).
                let r0 = &home.rotation;
                let r = match axis {
                    0 => turn::<L, 1, 2>(r0, s, c),
                    1 => turn::<L, 2, 0>(r0, s, c),
                    _ => turn::<L, 0, 1>(r0, s, c),
                };
                let t = &home.translation;
                Pose {
                    r,
                    p: [Lanes::splat(t.x), Lanes::splat(t.y), Lanes::splat(t.z)],
                }
            }
            LaneJoint::Screw { pose, .. } => pose.at(q, s, c),
        }
    }

    /// `v + S x`, in place.
    #[inline(always)]
    pub fn add_scaled<const L: usize>(&self, v: &mut V6<L>, x: Lanes<L>) {
        match self {
            LaneJoint::Axis { axis, sign, .. } => v[*axis] += x * *sign,
            LaneJoint::Screw { screw, .. } => *v = each!(6, |k| v[k] + x * screw[k]),
        }
    }

    /// `Sᵀ W`.
    #[inline(always)]
    pub fn dot<const L: usize>(&self, w: &V6<L>) -> Lanes<L> {
        match self {
            LaneJoint::Axis { axis, sign, .. } => w[*axis] * *sign,
            LaneJoint::Screw { screw, .. } => dot!(6, |k| w[k], screw[k]),
        }
    }

    /// `ad_{S x} V` ([`JointMotion::ad_scaled`]).
    #[inline(always)]
    pub fn ad_scaled<const L: usize>(&self, x: Lanes<L>, v: &V6<L>) -> V6<L> {
        match self {
            LaneJoint::Axis { axis, sign, .. } => {
                // (a ê_k) × w for both halves.
                let a = x * *sign;
                let z = Lanes::zero();
                macro_rules! axis_cross {
                    ($w0:expr, $w1:expr, $w2:expr) => {
                        match axis {
                            0 => [z, -(a * $w2), a * $w1],
                            1 => [a * $w2, z, -(a * $w0)],
                            _ => [-(a * $w1), a * $w0, z],
                        }
                    };
                }
                join(axis_cross!(v[0], v[1], v[2]), axis_cross!(v[3], v[4], v[5]))
            }
            LaneJoint::Screw { screw, .. } => {
                let sx: V6<L> = each!(6, |k| x * screw[k]);
                super::spatial::ad(&sx, v)
            }
        }
    }

    /// `Ad_H S`: the joint's screw in the frame `h` maps from ([`JointMotion::act`]).
    #[inline(always)]
    pub fn act<const L: usize>(&self, h: &Pose<L>) -> V6<L> {
        match self {
            LaneJoint::Axis { axis, sign, .. } => {
                let w = [
                    h.r[0][*axis] * *sign,
                    h.r[1][*axis] * *sign,
                    h.r[2][*axis] * *sign,
                ];
                join(w, cross(&h.p, &w))
            }
            LaneJoint::Screw { screw, .. } => h.act_screw(screw),
        }
    }
}

/// [`LaneJoint::sin_cos`] of every joint, written to `out[i]` for joint `i` and returned:
/// taken before the recursions, in a loop of its own, so that the joints' sines and cosines,
/// which depend on `q` alone, are computed side by side by the processor rather than each
/// waiting in the chain of poses.
#[inline(always)]
pub(super) fn sin_cos_all<'o, const L: usize>(
    joints: &[LaneJoint],
    q: &[Lanes<L>],
    out: &'o mut [(Lanes<L>, Lanes<L>)],
) -> &'o [(Lanes<L>, Lanes<L>)] {
    let out = &mut out[..joints.len()];
    for ((j, &q), o) in joints.iter().zip(q).zip(out.iter_mut()) {
        *o = j.sin_cos(q);
    }
    out
}

/// `R` with columns `I`, `J` turned by the angle whose sine and cosine are `s`, `c`; the third
/// column as it is.
#[inline(always)]
fn turn<const L: usize, const I: usize, const J: usize>(
    r0: &Matrix3<f64>,
    s: Lanes<L>,
    c: Lanes<L>,
) -> [[Lanes<L>; 3]; 3] {
    each33!(|k, m| {
        let (a, b) = (r0[(k, I)], r0[(k, J)]);
        if m == I {
            c * a + s * b
        } else if m == J {
            c * b - s * a
        } else {
            Lanes::splat(r0[(k, m)])
        }
    })
}

impl ScrewPose {
    /// The coefficients of `H(0) e^{[S]q}` for the screw `s`.
    fn new(home: &Se3<f64>, s: &crate::spatial::Twist<f64>) -> ScrewPose {
        let omega = Vector3::new(s[0], s[1], s[2]);
        let v = Vector3::new(s[3], s[4], s[5]);
        let rate = omega.norm();
        let (r, p) = if rate == 0.0 {
            // e^{[S]q} = (1, v q).
            (
                [Matrix3::identity(), Matrix3::zeros(), Matrix3::zeros()],
                [Vector3::zeros(), v, Vector3::zeros(), Vector3::zeros()],
            )
        } else {
            // R = 1 + sin [k] + (1 − cos)[k]², k = ω/|ω|;
            // p = v q + (1 − cos)[ω]v/|ω|² + (|ω|q − sin)[ω]²v/|ω|³.
            let k = hat(&(omega / rate));
            let (w, w2) = (hat(&omega), hat(&omega) * hat(&omega));
            let (r2, r3) = (rate * rate, rate * rate * rate);
            (
                [Matrix3::identity() + k * k, k, -(k * k)],
                [w * v / r2, v + w2 * v / r2, -(w2 * v) / r3, -(w * v) / r2],
            )
        };
        let hr = &home.rotation;
        ScrewPose {
            rate,
            r: [hr * r[0], hr * r[1], hr * r[2]],
            p: [
                hr * p[0] + home.translation,
                hr * p[1],
                hr * p[2],
                hr * p[3],
            ],
        }
    }

    /// The pose at `q` in every lane, given `s`, `c` = `sin`, `cos` of `|ω| q`.
    #[inline(always)]
    fn at<const L: usize>(&self, q: Lanes<L>, s: Lanes<L>, c: Lanes<L>) -> Pose<L> {
        let [r0, r1, r2] = &self.r;
        let [p0, p1, p2, p3] = &self.p;
        if self.rate == 0.0 {
            return Pose {
                r: each33!(|i, j| Lanes::splat(r0[(i, j)])),
                p: each!(3, |i| q * p1[i] + p0[i]),
            };
        }
        Pose {
            r: each33!(|i, j| s * r1[(i, j)] + c * r2[(i, j)] + r0[(i, j)]),
            p: each!(3, |i| q * p1[i] + s * p2[i] + c * p3[i] + p0[i]),
        }
    }
}
