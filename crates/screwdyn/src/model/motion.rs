//! [`JointMotion`]: a joint's screw axis `S_i^{i,λ(i)}`, classified once at model build time so
//! the per-call algorithms can use cheap special cases.
//!
//! Most joints of real arms turn about (or slide along) a coordinate axis of the child frame
//! through its origin: `S = (±ê_k, 0)` or `S = (0, ±ê_k)`. For those, `e^{[S]q}` is a plain
//! rotation about `ê_k` (one `sin_cos`, no series), `S q̇` has one non-zero entry and `Sᵀ W`
//! reads one entry. Everything else (general revolute, prismatic and helical axes) goes through
//! the general screw formulas. Every algorithm reaches the joint's screw through the methods
//! here, so the specialisation lives in this one place.

use crate::scalar::Real;
use crate::spatial::{ad, ang, lin, Se3, Twist, Wrench};
use nalgebra::{Matrix6, Vector3, Vector6};

/// A joint's screw axis in the child frame, specialised by shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointMotion<T: Real = f64> {
    /// Rotation about `sign · ê_axis` through the child-frame origin: `S = (sign ê_axis, 0)`.
    RevoluteAxis {
        /// 0, 1 or 2 for x, y, z.
        axis: usize,
        /// `±1`.
        sign: T,
    },
    /// Translation along `sign · ê_axis`: `S = (0, sign ê_axis)`.
    PrismaticAxis {
        /// 0, 1 or 2 for x, y, z.
        axis: usize,
        /// `±1`.
        sign: T,
    },
    /// Any other screw `S = (ω, v)`.
    General {
        /// `S` itself.
        screw: Twist<T>,
    },
}

impl<T: Real> JointMotion<T> {
    /// Classifies a screw axis (exact comparisons: only axes that are exactly `±ê_k` are
    /// specialised).
    ///
    /// ```
    /// use nalgebra::Vector6;
    /// use screwdyn::model::JointMotion;
    /// let m = JointMotion::classify(&Vector6::new(0.0, -1.0, 0.0, 0.0, 0.0, 0.0));
    /// assert_eq!(m, JointMotion::RevoluteAxis { axis: 1, sign: -1.0 });
    /// assert_eq!(m.screw(), Vector6::new(0.0, -1.0, 0.0, 0.0, 0.0, 0.0));
    /// ```
    pub fn classify(s: &Twist<T>) -> Self {
        let unit = |k: usize| -> Option<(usize, T)> {
            let nz: Vec<usize> = (0..3).filter(|&i| s[k + i] != T::zero()).collect();
            match nz.as_slice() {
                [i] if s[k + *i] == T::one() || s[k + *i] == -T::one() => Some((*i, s[k + *i])),
                _ => None,
            }
        };
        let zero = |k: usize| (0..3).all(|i| s[k + i] == T::zero());
        if zero(3) {
            if let Some((axis, sign)) = unit(0) {
                return JointMotion::RevoluteAxis { axis, sign };
            }
        }
        if zero(0) {
            if let Some((axis, sign)) = unit(3) {
                return JointMotion::PrismaticAxis { axis, sign };
            }
        }
        JointMotion::General { screw: *s }
    }

    /// The screw axis `S` as a 6-vector.
    pub fn screw(&self) -> Twist<T> {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => {
                let mut s = Twist::zeros();
                s[axis] = sign;
                s
            }
            JointMotion::PrismaticAxis { axis, sign } => {
                let mut s = Twist::zeros();
                s[3 + axis] = sign;
                s
            }
            JointMotion::General { screw } => screw,
        }
    }

    /// `H(0) e^{[S]q}`: the pose of the child in the parent given its home pose `home`
    /// (seed 000, forward iterations), composed without forming `e^{[S]q}` for axis joints.
    #[inline]
    pub fn pose_in_parent(&self, home: &Se3<T>, q: T) -> Se3<T> {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => {
                let (s, c) = (q * sign).sin_cos();
                let r = &home.rotation;
                // R(0) Rot_k(θ): only the two columns other than k change.
                let (i, j) = match axis {
                    0 => (1, 2),
                    1 => (2, 0),
                    _ => (0, 1),
                };
                let (ci, cj) = (r.column(i), r.column(j));
                let ni = ci * c + cj * s;
                let nj = cj * c - ci * s;
                let mut rot = *r;
                rot.set_column(i, &ni);
                rot.set_column(j, &nj);
                Se3::new(rot, home.translation)
            }
            JointMotion::PrismaticAxis { axis, sign } => {
                let d = q * sign;
                let col = home.rotation.column(axis);
                Se3::new(
                    home.rotation,
                    home.translation + Vector3::new(col[0] * d, col[1] * d, col[2] * d),
                )
            }
            JointMotion::General { screw } => home.compose(&Se3::exp_screw(&screw, q)),
        }
    }

    /// `S x`.
    #[inline]
    pub fn scaled(&self, x: T) -> Twist<T> {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => {
                let mut s = Twist::zeros();
                s[axis] = sign * x;
                s
            }
            JointMotion::PrismaticAxis { axis, sign } => {
                let mut s = Twist::zeros();
                s[3 + axis] = sign * x;
                s
            }
            JointMotion::General { screw } => screw * x,
        }
    }

    /// `v + S x`, in place.
    #[inline]
    pub fn add_scaled(&self, v: &mut Twist<T>, x: T) {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => v[axis] += sign * x,
            JointMotion::PrismaticAxis { axis, sign } => v[3 + axis] += sign * x,
            JointMotion::General { screw } => *v += screw * x,
        }
    }

    /// `Sᵀ W`: the joint-space component of a wrench (power per unit joint speed).
    #[inline]
    pub fn dot(&self, w: &Wrench<T>) -> T {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => w[axis] * sign,
            JointMotion::PrismaticAxis { axis, sign } => w[3 + axis] * sign,
            JointMotion::General { screw } => screw.dot(w),
        }
    }

    /// `ad_{S x} V`: the Lie bracket `[S x, V]` (seed 002's velocity-product term).
    #[inline]
    pub fn ad_scaled(&self, x: T, v: &Twist<T>) -> Twist<T> {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => {
                // (a ê_k) × w for both halves.
                let a = sign * x;
                let cross = |w: Vector3<T>| match axis {
                    0 => Vector3::new(T::zero(), -a * w.z, a * w.y),
                    1 => Vector3::new(a * w.z, T::zero(), -a * w.x),
                    _ => Vector3::new(-a * w.y, a * w.x, T::zero()),
                };
                let (w, l) = (cross(ang(v)), cross(lin(v)));
                Vector6::new(w.x, w.y, w.z, l.x, l.y, l.z)
            }
            JointMotion::PrismaticAxis { axis, sign } => {
                // ad_{(0, u)} (ω, v) = (0, u × ω).
                let a = sign * x;
                let w = ang(v);
                let l = match axis {
                    0 => Vector3::new(T::zero(), -a * w.z, a * w.y),
                    1 => Vector3::new(a * w.z, T::zero(), -a * w.x),
                    _ => Vector3::new(-a * w.y, a * w.x, T::zero()),
                };
                Vector6::new(T::zero(), T::zero(), T::zero(), l.x, l.y, l.z)
            }
            JointMotion::General { screw } => ad(&(screw * x), v),
        }
    }

    /// `Ad_H S`: the screw axis written in the frame `H` maps from (e.g. the base frame, with
    /// `H = H_i^0`: a column of the space Jacobian).
    #[inline]
    pub fn act(&self, h: &Se3<T>) -> Twist<T> {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => {
                let w = h.rotation.column(axis) * sign;
                let w = Vector3::new(w[0], w[1], w[2]);
                let l = h.translation.cross(&w);
                Vector6::new(w.x, w.y, w.z, l.x, l.y, l.z)
            }
            JointMotion::PrismaticAxis { axis, sign } => {
                let l = h.rotation.column(axis) * sign;
                Vector6::new(T::zero(), T::zero(), T::zero(), l[0], l[1], l[2])
            }
            JointMotion::General { screw } => h.act_twist(&screw),
        }
    }

    /// `𝔍 S` for a 6×6 (articulated) inertia `𝔍`: one column for axis joints.
    #[inline]
    pub fn inertia_column(&self, m: &Matrix6<T>) -> Wrench<T> {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => m.column(axis) * sign,
            JointMotion::PrismaticAxis { axis, sign } => m.column(3 + axis) * sign,
            JointMotion::General { screw } => m * screw,
        }
    }
}
