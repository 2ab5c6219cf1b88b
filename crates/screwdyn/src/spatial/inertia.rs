//! The 6×6 spatial inertia `𝔍` of a rigid body, stored by its ten parameters.
//!
//! Lynch & Park, *Modern Robotics* (kinetic energy `E = ½ Vᵀ 𝔍 V`) and Lynch & Park, *Modern Robotics* (`I_1 = [0 0; 0 m₁I]` for a point mass
//! at the frame origin). With mass `m`, centre of mass `c` and rotational inertia `I_c` about the
//! CoM (axes of the body frame), the angular-first spatial inertia about the frame origin is
//!
//! ```text
//! 𝔍 = [ I_c − m[c][c]   m[c] ]
//!     [ −m[c]           m·I  ]
//! ```
//! whose upper-left block is the parallel-axis theorem of Craig's *Introduction to Robotics*.

use super::se3::Se3;
use super::twist::{ang, lin, twist, Twist, Wrench};
use crate::error::{Error, Result};
use crate::scalar::{real, Real};

/// Why a body's inertia is not physically consistent (see
/// [`SpatialInertia::physical_problem`]); principal moments are sorted ascending.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InertiaProblem {
    /// A NaN or infinite entry.
    NonFinite,
    /// Mass below zero.
    NegativeMass(f64),
    /// The rotational inertia is not symmetric.
    NotSymmetric,
    /// A principal moment is negative.
    NotPositiveSemiDefinite([f64; 3]),
    /// Two principal moments add up to less than the third (no mass distribution has them).
    TriangleInequality([f64; 3]),
}

impl std::fmt::Display for InertiaProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            InertiaProblem::NonFinite => write!(f, "has a non-finite entry"),
            InertiaProblem::NegativeMass(m) => write!(f, "has negative mass {m}"),
            InertiaProblem::NotSymmetric => write!(f, "is not symmetric"),
            InertiaProblem::NotPositiveSemiDefinite([a, b, c]) => write!(
                f,
                "is not positive semi-definite (principal moments {a:e}, {b:e}, {c:e})"
            ),
            InertiaProblem::TriangleInequality([a, b, c]) => write!(
                f,
                "breaks the triangle inequality (principal moments {a:e} + {b:e} < {c:e})"
            ),
        }
    }
}
use nalgebra::{Matrix3, Matrix6, Vector3};

/// Spatial inertia of one rigid body: mass, centre of mass and rotational inertia about the CoM,
/// all in the body frame.
///
/// ```
/// use nalgebra::{Matrix3, Vector3, Vector6};
/// use screwdyn::spatial::SpatialInertia;
/// // A point mass m = 2 at the frame origin: the I = [0 0; 0 m I].
/// let i = SpatialInertia::point_mass(2.0_f64, Vector3::zeros());
/// let j = i.matrix();
/// assert_eq!(j[(3, 3)], 2.0);
/// assert_eq!(j[(0, 0)], 0.0);
/// // Kinetic energy of a pure translation at 3 m/s: ½ m v².
/// let v = Vector6::new(0.0, 0.0, 0.0, 3.0, 0.0, 0.0);
/// assert!((i.kinetic_energy(&v) - 9.0_f64).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpatialInertia<T: Real = f64> {
    /// `m` (kg).
    pub mass: T,
    /// `c`: the centre of mass in the body frame (m).
    pub com: Vector3<T>,
    /// `I_c`: rotational inertia about the CoM, body-frame axes (kg·m²).
    pub inertia_com: Matrix3<T>,
}

impl<T: Real> Default for SpatialInertia<T> {
    fn default() -> Self {
        Self::zero()
    }
}

impl<T: Real> SpatialInertia<T> {
    /// The inertia of nothing (massless body).
    pub fn zero() -> Self {
        SpatialInertia {
            mass: T::zero(),
            com: Vector3::zeros(),
            inertia_com: Matrix3::zeros(),
        }
    }

    /// From mass, centre of mass and rotational inertia about the centre of mass.
    pub fn new(mass: T, com: Vector3<T>, inertia_com: Matrix3<T>) -> Self {
        SpatialInertia {
            mass,
            com,
            inertia_com,
        }
    }

    /// From mass, centre of mass and rotational inertia about the frame origin, using the
    /// parallel-axis theorem backwards (Craig, *Introduction to Robotics*: `ᶜI = ᴬI − m(cᵀc I − c cᵀ)`).
    pub fn from_inertia_about_origin(mass: T, com: Vector3<T>, inertia_origin: Matrix3<T>) -> Self {
        SpatialInertia::new(mass, com, inertia_origin - parallel_axis_term(mass, &com))
    }

    /// A point mass `m` at `at` (no rotational inertia about its CoM).
    pub fn point_mass(mass: T, at: Vector3<T>) -> Self {
        SpatialInertia::new(mass, at, Matrix3::zeros())
    }

    /// `ᴬI = ᶜI + m(cᵀc I − c cᵀ)`: rotational inertia about the frame origin (Craig, *Introduction to Robotics*,
    /// parallel-axis theorem).
    pub fn inertia_about_origin(&self) -> Matrix3<T> {
        self.inertia_com + parallel_axis_term(self.mass, &self.com)
    }

    /// The 6×6 matrix `𝔍` (angular first) about the frame origin:
    /// `[I_c − m[c][c]  m[c]; −m[c]  m·1]`, with `−m[c][c] = m (cᵀc 1 − c cᵀ)` (the
    /// parallel-axis theorem of Craig's *Introduction to Robotics*), written out entry by entry.
    #[inline]
    pub fn matrix(&self) -> Matrix6<T> {
        let (m, c, i) = (self.mass, &self.com, &self.inertia_com);
        let (mx, my, mz) = (m * c.x, m * c.y, m * c.z);
        let (xx, yy, zz) = (mx * c.x, my * c.y, mz * c.z);
        let (xy, xz, yz) = (mx * c.y, mx * c.z, my * c.z);
        let zero = T::zero();
        #[rustfmt::skip]
        let j = Matrix6::new(
            i[(0, 0)] + yy + zz, i[(0, 1)] - xy,      i[(0, 2)] - xz,      zero, -mz,  my,
            i[(1, 0)] - xy,      i[(1, 1)] + xx + zz, i[(1, 2)] - yz,      mz,   zero, -mx,
            i[(2, 0)] - xz,      i[(2, 1)] - yz,      i[(2, 2)] + xx + yy, -my,  mx,   zero,
            zero,                mz,                  -my,                 m,    zero, zero,
            -mz,                 zero,                mx,                  zero, m,    zero,
            my,                  -mx,                 zero,                zero, zero, m,
        );
        j
    }

    /// Recovers the ten parameters from a 6×6 spatial inertia; fails when it does not have the
    /// structure `[I m[c]; −m[c] m·1]` (within `1e-9` relative).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] saying which block is malformed.
    pub fn from_matrix(j: &Matrix6<T>) -> Result<Self> {
        let m = j[(3, 3)];
        let scale = j.amax().max(T::one());
        let tol = scale * real(1e-9);
        let lower = j.fixed_view::<3, 3>(3, 3).into_owned() - Matrix3::identity() * m;
        if lower.amax() > tol {
            return Err(Error::InvalidArgument(format!(
                "the 6×6 spatial inertia is malformed: {}",
                "its lower-right block is not m times the identity"
            )));
        }
        if (j - j.transpose()).amax() > tol {
            return Err(Error::InvalidArgument(format!(
                "the 6×6 spatial inertia is malformed: {}",
                "it is not symmetric"
            )));
        }
        let mc = j.fixed_view::<3, 3>(0, 3).into_owned();
        if (mc + mc.transpose()).amax() > tol {
            return Err(Error::InvalidArgument(format!(
                "the 6×6 spatial inertia is malformed: {}",
                "its upper-right block is not skew-symmetric (m[c])"
            )));
        }
        let com = if m > T::zero() {
            super::so3::vee(&mc) / m
        } else {
            Vector3::zeros()
        };
        Ok(SpatialInertia::from_inertia_about_origin(
            m,
            com,
            j.fixed_view::<3, 3>(0, 0).into_owned(),
        ))
    }

    /// `𝔍 V`: the momentum wrench of a body moving with twist `V` (structured, 6×6-free).
    #[inline]
    pub fn apply(&self, v: &Twist<T>) -> Wrench<T> {
        let w = ang(v);
        // Linear momentum m(v − c × ω); angular momentum about the origin I_c ω + c × p.
        let p = (lin(v) - self.com.cross(&w)) * self.mass;
        let l = self.inertia_com * w + self.com.cross(&p);
        twist(l, p)
    }

    /// `½ Vᵀ 𝔍 V` (Lynch & Park, *Modern Robotics*).
    pub fn kinetic_energy(&self, v: &Twist<T>) -> T {
        self.apply(v).dot(v) * real(0.5)
    }

    /// This inertia, given in frame `b`, expressed in frame `a`, where `h = H_b^a`:
    /// `𝔍^a = Ad_{H_a^b}ᵀ 𝔍^b Ad_{H_a^b}` (change of frame; structured: `c ↦ Rc + p`,
    /// `I_c ↦ R I_c Rᵀ`).
    ///
    /// ```
    /// use nalgebra::{Matrix3, Vector3};
    /// use screwdyn::spatial::{Se3, SpatialInertia};
    /// let i = SpatialInertia::new(2.0, Vector3::new(0.1, 0.2, 0.3), Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)));
    /// let h = Se3::from_rpy(0.3, -0.2, 0.5).with_translation(Vector3::new(1.0, 0.0, -1.0));
    /// let ad = h.inverse().adjoint_matrix();
    /// let expected = ad.transpose() * i.matrix() * ad;
    /// assert!((i.transformed(&h).matrix() - expected).amax() < 1e-12);
    /// ```
    #[inline(always)]
    pub fn transformed(&self, h: &Se3<T>) -> Self {
        let r = &h.rotation;
        let a = r * self.inertia_com;
        // R I_c Rᵀ = A Rᵀ is symmetric: entry (i, j) is row i of A dotted with row j of R, and
        // only six are formed.
        let dot = |i: usize, j: usize| {
            a[(i, 0)] * r[(j, 0)] + a[(i, 1)] * r[(j, 1)] + a[(i, 2)] * r[(j, 2)]
        };
        let (i01, i02, i12) = (dot(0, 1), dot(0, 2), dot(1, 2));
        #[rustfmt::skip]
        let rotated = Matrix3::new(
            dot(0, 0), i01,       i02,
            i01,       dot(1, 1), i12,
            i02,       i12,       dot(2, 2),
        );
        SpatialInertia::new(self.mass, h.act_point(&self.com), rotated)
    }

    /// The inertia of two bodies rigidly joined (both given in the same frame).
    pub fn combined(&self, other: &SpatialInertia<T>) -> Self {
        let m = self.mass + other.mass;
        let about_origin = self.inertia_about_origin() + other.inertia_about_origin();
        if m <= T::zero() {
            // Massless parts still carry rotational inertia (a motor rotor's reflected
            // inertia, say): with no mass there is no centre of mass to shift it to, so it is
            // kept about the frame origin.
            return SpatialInertia::new(m, Vector3::zeros(), about_origin);
        }
        let com = (self.com * self.mass + other.com * other.mass) / m;
        SpatialInertia::from_inertia_about_origin(m, com, about_origin)
    }

    /// Checks physical consistency: finite, non-negative mass, symmetric `I_c` with non-negative
    /// principal moments satisfying the triangle inequality (`I₁ + I₂ ≥ I₃` for every ordering).
    /// Tolerances scale with the body (see [`SpatialInertia::physical_problem`]).
    ///
    /// # Errors
    /// [`Error::InvalidModel`] whose message reads "the inertia …" and says what is wrong.
    pub fn check_physical(&self) -> Result<()> {
        match self.physical_problem() {
            None => Ok(()),
            Some(p) => Err(Error::InvalidModel(format!("the inertia {p}"))),
        }
    }

    /// The physical-consistency problem of this inertia, if any, with tolerances that scale
    /// with the body: `ε · m · r²` where `r` is the larger of the centre-of-mass offset and the
    /// radius of gyration `√(tr I_c / m)` (or `ε · tr I_c` for a massless body), `ε = 1e-9`.
    /// Round-off in published files (principal moments of ±1e-20 on a body of 1e-6 kg·m²)
    /// passes; a real violation of the triangle inequality does not.
    ///
    /// ```
    /// use nalgebra::{Matrix3, Vector3};
    /// use screwdyn::spatial::{InertiaProblem, SpatialInertia};
    /// let rounded = SpatialInertia::new(0.05, Vector3::zeros(),
    ///     Matrix3::from_diagonal(&Vector3::new(1e-5, 1e-5, -1.4e-20)));
    /// assert_eq!(rounded.physical_problem(), None);
    /// let mount = SpatialInertia::new(0.1, Vector3::zeros(),
    ///     Matrix3::from_diagonal(&Vector3::new(0.001, 0.001, 0.01)));
    /// assert!(matches!(mount.physical_problem(), Some(InertiaProblem::TriangleInequality(_))));
    /// ```
    pub fn physical_problem(&self) -> Option<InertiaProblem> {
        let f = |x: T| -> f64 { x.to_subset().unwrap_or(f64::NAN) };
        let finite = self.mass.is_finite()
            && self.com.iter().all(|x| x.is_finite())
            && self.inertia_com.iter().all(|x| x.is_finite());
        if !finite {
            return Some(InertiaProblem::NonFinite);
        }
        if self.mass < T::zero() {
            return Some(InertiaProblem::NegativeMass(f(self.mass)));
        }
        let i = &self.inertia_com;
        let trace = i.trace().abs();
        let r2 = if self.mass > T::zero() {
            self.com.norm_squared().max(trace / self.mass)
        } else {
            T::zero()
        };
        let eps: T = real(1e-9);
        let tol = eps * (self.mass * r2).max(trace);
        if (i - i.transpose()).amax() > tol {
            return Some(InertiaProblem::NotSymmetric);
        }
        let eig = i.symmetric_eigenvalues();
        let mut moments = [f(eig[0]), f(eig[1]), f(eig[2])];
        moments.sort_by(|a, b| a.total_cmp(b));
        if eig.iter().any(|&e| e < -tol) {
            return Some(InertiaProblem::NotPositiveSemiDefinite(moments));
        }
        for k in 0..3 {
            let (a, b, c) = (eig[k], eig[(k + 1) % 3], eig[(k + 2) % 3]);
            if a + b < c - tol {
                return Some(InertiaProblem::TriangleInequality(moments));
            }
        }
        None
    }
}

impl SpatialInertia<f64> {
    /// Converts the scalar type.
    pub fn cast<U: Real>(&self) -> SpatialInertia<U> {
        SpatialInertia::new(
            real(self.mass),
            self.com.map(real),
            self.inertia_com.map(real),
        )
    }
}

/// `m (cᵀc I − c cᵀ)`, the parallel-axis term of Craig's *Introduction to Robotics*.
pub fn parallel_axis_term<T: Real>(mass: T, c: &Vector3<T>) -> Matrix3<T> {
    (Matrix3::identity() * c.dot(c) - c * c.transpose()) * mass
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `transformed(h).matrix()` equals the change of frame `Ad_{H⁻¹}ᵀ 𝔍 Ad_{H⁻¹}` done with 6×6
    /// adjoint matrices (Lynch & Park, *Modern Robotics*), for a body with an off-diagonal inertia and offset CoM.
    #[test]
    fn change_of_frame_matches_the_adjoint_sandwich() {
        let body = SpatialInertia::new(
            2.5,
            Vector3::new(0.1, -0.2, 0.3),
            Matrix3::new(0.3, 0.01, -0.02, 0.01, 0.2, 0.03, -0.02, 0.03, 0.25),
        );
        let h = Se3::from_rpy(0.4, -0.7, 1.9).with_translation(Vector3::new(0.5, -1.2, 0.8));
        let ad = h.inverse().adjoint_matrix();
        let expected = ad.transpose() * body.matrix() * ad;
        assert!((body.transformed(&h).matrix() - expected).amax() < 1e-12);
        // The matrix itself is the block formula with the parallel-axis theorem.
        let mc = super::super::so3::hat(&body.com) * body.mass;
        let mut j = Matrix6::zeros();
        j.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&body.inertia_about_origin());
        j.fixed_view_mut::<3, 3>(0, 3).copy_from(&mc);
        j.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-mc));
        j.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(Matrix3::identity() * body.mass));
        assert!((body.matrix() - j).amax() < 1e-15);
    }
}
