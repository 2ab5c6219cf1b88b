//! [`JointMotion`]: a joint's screw axis `S_i^{i,λ(i)}`, classified once at model build time so
//! the per-call algorithms can use cheap special cases.
//!
//! Most joints of real arms turn about (or slide along) a coordinate axis of the child frame
//! through its origin: `S = (±ê_k, 0)` or `S = (0, ±ê_k)`. For those, `e^{[S]q}` is a plain
//! rotation about `ê_k` (one `sin_cos`, no series), `S q̇` has one non-zero entry and `Sᵀ W`
//! reads one entry. The joints of standard-DH tables turn about a coordinate axis of the child
//! frame that misses its origin (`S = (±ê_k, r × ±ê_k)`): their pose and base-frame axis are
//! special-cased too. Everything else (general revolute, prismatic and helical axes) goes through
//! the general screw formulas. Every algorithm reaches the joint's screw through the methods
//! here, so the specialisation lives in this one place.

use crate::scalar::Real;
use crate::spatial::{ad, ang, lin, Se3, Twist, Wrench};
use nalgebra::{Matrix3, Vector3, Vector6};

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
    /// Rotation about `ω = sign · ê_axis` through the point `point` of the child frame
    /// (`point ⊥ ê_axis`, the foot of the perpendicular from the origin): `S = (ω, point × ω)`.
    /// Standard-DH joints with a non-zero link length `a` look like this from their child frame.
    RevoluteOffsetAxis {
        /// 0, 1 or 2 for x, y, z.
        axis: usize,
        /// `±1`.
        sign: T,
        /// A point on the axis, perpendicular to it.
        point: Vector3<T>,
        /// `S` itself, for the operations that use it whole.
        screw: Twist<T>,
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
        if let Some((axis, sign)) = unit(0) {
            if s[3 + axis] == T::zero() {
                // v = r × ω with r ⊥ ω gives r = ω × v (exact: ω only permutes and signs v).
                let omega = Vector3::new(s[0], s[1], s[2]);
                let point = omega.cross(&Vector3::new(s[3], s[4], s[5]));
                return JointMotion::RevoluteOffsetAxis {
                    axis,
                    sign,
                    point,
                    screw: *s,
                };
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
            JointMotion::General { screw } | JointMotion::RevoluteOffsetAxis { screw, .. } => screw,
        }
    }

    /// `H(0) e^{[S]q}`: the pose of the child in the parent given its home pose `home`
    /// (Lynch & Park, *Modern Robotics*, forward iterations), composed without forming `e^{[S]q}` for axis joints.
    // Always inlined, so that the CPU-specific clones of forward kinematics compile it too.
    #[inline(always)]
    pub fn pose_in_parent(&self, home: &Se3<T>, q: T) -> Se3<T> {
        let sin_cos = if self.turns() {
            crate::scalar::sin_cos(self.angle(q))
        } else {
            (T::zero(), T::one())
        };
        self.pose_in_parent_given(home, q, sin_cos)
    }

    /// Whether the joint turns about a coordinate axis (a revolute axis joint, with or without
    /// offset): whether its pose needs the sine and cosine of [`JointMotion::angle`].
    #[inline(always)]
    pub fn turns(&self) -> bool {
        matches!(
            self,
            JointMotion::RevoluteAxis { .. } | JointMotion::RevoluteOffsetAxis { .. }
        )
    }

    /// The angle `θ = ±q` the joint turns about its coordinate axis (revolute axis joints, with
    /// or without offset), whose sine and cosine [`JointMotion::pose_in_parent_given`] takes;
    /// zero for the other joints.
    ///
    /// ```
    /// use nalgebra::Vector6;
    /// use screwdyn::model::JointMotion;
    /// let m = JointMotion::classify(&Vector6::new(0.0, -1.0, 0.0, 0.0, 0.0, 0.0));
    /// assert_eq!(m.angle(0.3), -0.3);
    /// ```
    #[inline(always)]
    pub fn angle(&self, q: T) -> T {
        match *self {
            JointMotion::RevoluteAxis { sign, .. }
            | JointMotion::RevoluteOffsetAxis { sign, .. } => q * sign,
            _ => T::zero(),
        }
    }

    /// [`JointMotion::pose_in_parent`] given `(sin θ, cos θ)` of [`JointMotion::angle`]`(q)`,
    /// computed beforehand (for all joints at once, by [`crate::scalar::sin_cos_lanes`], in
    /// forward kinematics). Prismatic and general joints ignore it.
    ///
    /// ```
    /// use nalgebra::Vector6;
    /// use screwdyn::{model::JointMotion, spatial::Se3};
    /// let m = JointMotion::classify(&Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0));
    /// let home = Se3::from_rpy(0.1, 0.2, 0.3);
    /// let q = 0.7_f64;
    /// let given = m.pose_in_parent_given(&home, q, m.angle(q).sin_cos());
    /// assert!((given.to_matrix() - m.pose_in_parent(&home, q).to_matrix()).amax() < 1e-15);
    /// ```
    #[inline(always)]
    pub fn pose_in_parent_given(&self, home: &Se3<T>, q: T, sin_cos: (T, T)) -> Se3<T> {
        self.pose_in_parent_with::<false>(home, q, sin_cos)
    }

    /// [`JointMotion::pose_in_parent_given`] with the turned columns' products fused
    /// (`mul_add`: for the CPU-specific clones of forward kinematics that have fused
    /// multiply–adds; a library call without). Within rounding of the unfused form.
    #[inline(always)]
    pub(crate) fn pose_in_parent_given_fused(
        &self,
        home: &Se3<T>,
        q: T,
        sin_cos: (T, T),
    ) -> Se3<T> {
        self.pose_in_parent_with::<true>(home, q, sin_cos)
    }

    /// The pose of [`JointMotion::pose_in_parent_given`], its turned columns fused when `FUSED`.
    #[inline(always)]
    fn pose_in_parent_with<const FUSED: bool>(
        &self,
        home: &Se3<T>,
        q: T,
        (s, c): (T, T),
    ) -> Se3<T> {
        match *self {
            JointMotion::RevoluteAxis { axis, .. } => {
                let (rot, _) = rotate_about_axis::<_, FUSED>(&home.rotation, axis, s, c);
                Se3::new(rot, home.translation)
            }
            JointMotion::RevoluteOffsetAxis { axis, point, .. } => {
                // H(0) (Rot_k(θ), (1 − Rot_k(θ)) r): p = p(0) + R(0) r − R(0) Rot_k(θ) r, where
                // r = r_i ê_i + r_j ê_j only meets the two columns that turn.
                let (rot, (i, j)) = rotate_about_axis::<_, FUSED>(&home.rotation, axis, s, c);
                let r0 = &home.rotation;
                let p = home.translation
                    + (r0.column(i) - rot.column(i)) * point[i]
                    + (r0.column(j) - rot.column(j)) * point[j];
                Se3::new(rot, p)
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

    /// `v + S x`, in place.
    #[inline]
    pub fn add_scaled(&self, v: &mut Twist<T>, x: T) {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => v[axis] += sign * x,
            JointMotion::PrismaticAxis { axis, sign } => v[3 + axis] += sign * x,
            JointMotion::General { screw } | JointMotion::RevoluteOffsetAxis { screw, .. } => {
                *v += screw * x
            }
        }
    }

    /// `Sᵀ W`: the joint-space component of a wrench (power per unit joint speed).
    #[inline]
    pub fn dot(&self, w: &Wrench<T>) -> T {
        match *self {
            JointMotion::RevoluteAxis { axis, sign } => w[axis] * sign,
            JointMotion::PrismaticAxis { axis, sign } => w[3 + axis] * sign,
            JointMotion::General { screw } | JointMotion::RevoluteOffsetAxis { screw, .. } => {
                screw.dot(w)
            }
        }
    }

    /// `ad_{S x} V`: the Lie bracket `[S x, V]` (the velocity-product term).
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
            JointMotion::General { screw } | JointMotion::RevoluteOffsetAxis { screw, .. } => {
                ad(&(screw * x), v)
            }
        }
    }

    /// `Ad_H S`: the screw axis written in the frame `H` maps from (e.g. the base frame, with
    /// `H = H_i^0`: a column of the space Jacobian).
    // Always inlined: returned through memory from an out-of-line call, the 6-vector is stored
    // in halves and reloaded whole by the caller, a store-forwarding stall that cost CRBA a
    // tenth of its time (perf annotate, x86-64).
    #[inline(always)]
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
            JointMotion::RevoluteOffsetAxis {
                axis, sign, point, ..
            } => {
                // ω⁰ = R ω, through the point p + R r.
                let w = h.rotation.column(axis) * sign;
                let w = Vector3::new(w[0], w[1], w[2]);
                let at = h.act_point(&point);
                let l = at.cross(&w);
                Vector6::new(w.x, w.y, w.z, l.x, l.y, l.z)
            }
            JointMotion::General { screw } => h.act_twist(&screw),
        }
    }
}

/// `R Rot_k(θ)` given `s = sin θ`, `c = cos θ`: only the two columns `(i, j)` other than `k`
/// change; returns them too.
#[inline(always)]
fn rotate_about_axis<T: Real, const FUSED: bool>(
    r: &Matrix3<T>,
    axis: usize,
    s: T,
    c: T,
) -> (Matrix3<T>, (usize, usize)) {
    // One code path per axis, so that the columns are known at compile time.
    match axis {
        0 => (rotate_columns::<_, 1, 2, FUSED>(r, s, c), (1, 2)),
        1 => (rotate_columns::<_, 2, 0, FUSED>(r, s, c), (2, 0)),
        _ => (rotate_columns::<_, 0, 1, FUSED>(r, s, c), (0, 1)),
    }
}

/// Columns `I`, `J` of `R` turned by the angle whose sine and cosine are `s`, `c`
/// (`a c + b s` and `b c − a s`, each one product and one `mul_add` when `FUSED`).
#[inline(always)]
fn rotate_columns<T: Real, const I: usize, const J: usize, const FUSED: bool>(
    r: &Matrix3<T>,
    s: T,
    c: T,
) -> Matrix3<T> {
    let mut rot = *r;
    for k in 0..3 {
        let (a, b) = (r[(k, I)], r[(k, J)]);
        if FUSED {
            rot[(k, I)] = a.mul_add(c, b * s);
            rot[(k, J)] = b.mul_add(c, -(a * s));
        } else {
            rot[(k, I)] = a * c + b * s;
            rot[(k, J)] = b * c - a * s;
        }
    }
    rot
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fused poses of forward kinematics' FMA clones agree with the unfused ones to
    /// rounding, for every joint shape (the unfused ones are checked against the general
    /// screw formulas below).
    #[test]
    fn fused_poses_agree_with_the_unfused_ones() {
        let screws: [Twist<f64>; 6] = [
            Vector6::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            Vector6::new(0.0, -1.0, 0.0, 0.0, 0.0, 0.0),
            Vector6::new(0.0, 0.0, 1.0, 0.0, -0.425, 0.0),
            Vector6::new(0.0, -1.0, 0.0, 0.2, 0.0, 0.1),
            Vector6::new(0.0, 0.0, 0.0, 1.0, 0.0, 0.0),
            Vector6::new(0.6, 0.8, 0.0, 0.1, -0.2, 0.3),
        ];
        let home = Se3::from_rpy(0.3, -1.2, 2.1).with_translation(Vector3::new(0.2, -0.4, 1.1));
        for s in &screws {
            let jm = JointMotion::classify(s);
            for q in [0.0, 0.8, -2.3, 3.1] {
                let sc = jm.angle(q).sin_cos();
                let fused = jm.pose_in_parent_given_fused(&home, q, sc);
                let plain = jm.pose_in_parent_given(&home, q, sc);
                assert!(
                    (fused.to_matrix() - plain.to_matrix()).amax() < 4.0 * f64::EPSILON,
                    "{jm:?} q={q}"
                );
            }
        }
    }

    /// Every special case agrees with the general screw formulas it replaces (which are checked
    /// against the matrix-exponential series in the spatial tests).
    #[test]
    fn special_cases_agree_with_the_general_screw_formulas() {
        let screws: [Twist<f64>; 10] = [
            Vector6::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            Vector6::new(0.0, -1.0, 0.0, 0.0, 0.0, 0.0),
            Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0),
            Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0),
            Vector6::new(0.0, 0.0, 0.0, 1.0, 0.0, 0.0),
            // Standard-DH offset axes: z through (0.425, 0, 0), −y through (0.1, 0, −0.2), x.
            Vector6::new(0.0, 0.0, 1.0, 0.0, -0.425, 0.0),
            Vector6::new(0.0, -1.0, 0.0, 0.2, 0.0, 0.1),
            Vector6::new(1.0, 0.0, 0.0, 0.0, 0.3, -0.7),
            // General: a tilted axis, and a helical screw.
            Vector6::new(0.6, 0.8, 0.0, 0.1, -0.2, 0.3),
            Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.05),
        ];
        let kinds = [
            "RevoluteAxis",
            "RevoluteAxis",
            "RevoluteAxis",
            "PrismaticAxis",
            "PrismaticAxis",
            "RevoluteOffsetAxis",
            "RevoluteOffsetAxis",
            "RevoluteOffsetAxis",
            "General",
            "General",
        ];
        let home = Se3::from_rpy(0.3, -1.2, 2.1).with_translation(Vector3::new(0.2, -0.4, 1.1));
        let h = Se3::from_rpy(-0.7, 0.4, -2.6).with_translation(Vector3::new(-1.0, 0.5, 0.3));
        let v = Vector6::new(0.3, -0.1, 0.7, 1.5, -0.4, 0.2);
        let w = Vector6::new(-0.2, 0.9, 0.4, 3.0, 1.0, -2.0);
        for (s, kind) in screws.iter().zip(kinds) {
            let jm = JointMotion::classify(s);
            assert!(format!("{jm:?}").starts_with(kind), "{s:?} gave {jm:?}");
            assert_eq!(jm.screw(), *s);
            for q in [0.0, 0.8, -2.3] {
                let fast = jm.pose_in_parent(&home, q);
                let general = home.compose(&Se3::exp_screw(s, q));
                assert!(
                    (fast.to_matrix() - general.to_matrix()).amax() < 1e-14,
                    "{kind} q={q}"
                );
                let mut x = v;
                jm.add_scaled(&mut x, q);
                assert!((x - (v + s * q)).amax() < 1e-15);
                assert!((jm.ad_scaled(q, &v) - ad(&(s * q), &v)).amax() < 1e-14);
            }
            assert!((jm.dot(&w) - s.dot(&w)).abs() < 1e-14);
            assert!((jm.act(&h) - h.act_twist(s)).amax() < 1e-14, "{kind}");
        }
    }
}
