//! Composite spatial inertia: a spatial inertia stored by the quantities it is linear in, so
//! that the inertias of several bodies add exactly (the composite bodies of the CRBA, Lynch & Park, *Modern Robotics*
//! `M = Σ_i J_iᵀ 𝔍_i J_i` summed over subtrees).

use super::inertia::SpatialInertia;
use super::inertia_in_world::{InertiaForm, InertiaInWorld};
use super::se3::Se3;
use super::so3::hat;
use super::twist::{Twist, Wrench};
use crate::scalar::Real;
use nalgebra::{Matrix3, Vector3, Vector6};

/// A spatial inertia stored by the parameters it is linear in — mass `m`, first moment `h = m c`
/// and rotational inertia `I_o` about the frame origin — so that the inertias of several bodies
/// add exactly (composite bodies of the CRBA). `𝔍 = [I_o [h]; [h]ᵀ m·1]`.
///
/// ```
/// use nalgebra::{Matrix3, Vector3};
/// use screwdyn::spatial::{CompositeInertia, Se3, SpatialInertia};
/// let a = SpatialInertia::new(2.0, Vector3::new(0.1, 0.0, 0.3), Matrix3::identity() * 0.2);
/// let h = Se3::from_rpy(0.1, 0.2, 0.3).with_translation(Vector3::new(1.0, 2.0, 3.0));
/// let c = CompositeInertia::from(&a).transformed(&h);
/// assert!((c.matrix() - a.transformed(&h).matrix()).amax() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompositeInertia<T: Real = f64> {
    /// `m`.
    pub mass: T,
    /// `h = m c`.
    pub first_moment: Vector3<T>,
    /// `I_o = I_c + m([c]ᵀ[c])`: rotational inertia about the frame origin.
    pub inertia_origin: Matrix3<T>,
}

impl<T: Real> From<&SpatialInertia<T>> for CompositeInertia<T> {
    fn from(i: &SpatialInertia<T>) -> Self {
        CompositeInertia {
            mass: i.mass,
            first_moment: i.com * i.mass,
            inertia_origin: i.inertia_about_origin(),
        }
    }
}

impl<T: Real> CompositeInertia<T> {
    /// Nothing.
    pub fn zero() -> Self {
        CompositeInertia {
            mass: T::zero(),
            first_moment: Vector3::zeros(),
            inertia_origin: Matrix3::zeros(),
        }
    }

    /// The sum of two inertias given in the same frame.
    #[inline]
    pub fn add(&mut self, o: &CompositeInertia<T>) {
        self.mass += o.mass;
        self.first_moment += o.first_moment;
        self.inertia_origin += o.inertia_origin;
    }

    /// This inertia, given in frame `b`, written in frame `a`, where `h = H_b^a`:
    /// `Ad_{H_a^b}ᵀ 𝔍 Ad_{H_a^b}`.
    #[inline]
    pub fn transformed(&self, h: &Se3<T>) -> Self {
        // With h' = R h: I_o' = R I_o Rᵀ − [h'][p] − [p][h'] − m [p][p], and
        // [a][b] = b aᵀ − (a·b) 1, so the three translation terms are the symmetric
        // 2(h'·p) 1 − p h'ᵀ − h' pᵀ + m (|p|² 1 − p pᵀ) (no 3×3 products).
        let r = &h.rotation;
        let p = &h.translation;
        let rh = r * self.first_moment;
        let ri = r * self.inertia_origin;
        let m = self.mass;
        let diag = (rh.dot(p) * crate::scalar::real(2.0)) + p.dot(p) * m;
        let mut io = Matrix3::zeros();
        for a in 0..3 {
            for b in a..3 {
                // (R I Rᵀ)_ab = Σ_k (R I)_ak R_bk
                let rir = ri[(a, 0)] * r[(b, 0)] + ri[(a, 1)] * r[(b, 1)] + ri[(a, 2)] * r[(b, 2)];
                let t = rir - p[a] * rh[b] - rh[a] * p[b] - p[a] * p[b] * m;
                io[(a, b)] = t;
                io[(b, a)] = t;
            }
            io[(a, a)] += diag;
        }
        CompositeInertia {
            mass: m,
            first_moment: rh + p * m,
            inertia_origin: io,
        }
    }

    /// The inertia of a rigid body (`m`, centre of mass `c` and `I_c` in its own frame {i})
    /// written in {0}, where `pose_in_world = H_i^0 = (R, p)`: with `c⁰ = R c + p`,
    /// `h = m c⁰` and `I_o = R I_c Rᵀ + m(|c⁰|² 1 − c⁰ c⁰ᵀ)` (rotational inertia about the
    /// origin of {0}). `R I_c Rᵀ` is symmetric, so six of its entries are formed; every sum of
    /// products is fused. Equal to `CompositeInertia::from(body).transformed(pose_in_world)`
    /// (the shift there starts from `I_o` about the body's origin, here from `I_c`).
    ///
    /// ```
    /// use nalgebra::{Matrix3, Vector3};
    /// use screwdyn::spatial::{CompositeInertia, Se3, SpatialInertia};
    /// let body = SpatialInertia::new(2.0, Vector3::new(0.1, 0.0, 0.3), Matrix3::identity() * 0.2);
    /// let pose = Se3::from_rpy(0.1, 0.2, 0.3).with_translation(Vector3::new(1.0, 2.0, 3.0));
    /// let moved = CompositeInertia::rigid_in_world(&body, &pose);
    /// let general = CompositeInertia::from(&body).transformed(&pose);
    /// assert!((moved.matrix() - general.matrix()).amax() < 1e-12);
    /// ```
    #[inline(always)]
    pub fn rigid_in_world(body: &SpatialInertia<T>, pose_in_world: &Se3<T>) -> Self {
        Self::from_in_world(InertiaInWorld::new(body, pose_in_world))
    }

    /// [`CompositeInertia::rigid_in_world`] with `R I_c Rᵀ` formed from `form`, the shape of
    /// `body.inertia_com` (the model's derived per-body forms).
    #[inline(always)]
    pub(crate) fn rigid_in_world_with_form(
        body: &SpatialInertia<T>,
        form: &InertiaForm<T>,
        pose_in_world: &Se3<T>,
    ) -> Self {
        Self::from_in_world(InertiaInWorld::with_form(body, form, pose_in_world))
    }

    /// `h = m c⁰` and `I_o = I_c^0 + m(|c⁰|² 1 − c⁰ c⁰ᵀ)` from `m`, `c⁰` and `I_c^0`.
    #[inline(always)]
    fn from_in_world(inertia: InertiaInWorld<T>) -> Self {
        let InertiaInWorld {
            mass: m,
            com: c0,
            rotational: [i00, i11, i22, i01, i02, i12],
        } = inertia;
        let h = c0 * m;
        // m(|c⁰|² 1 − c⁰ c⁰ᵀ): the diagonal is h_y c⁰_y + h_z c⁰_z, …, the rest −h_a c⁰_b.
        let (xx, yy, zz) = (h.x * c0.x, h.y * c0.y, h.z * c0.z);
        let i01 = i01 - h.x * c0.y;
        let i02 = i02 - h.x * c0.z;
        let i12 = i12 - h.y * c0.z;
        #[rustfmt::skip]
        let inertia_origin = Matrix3::new(
            i00 + (yy + zz), i01, i02,
            i01, i11 + (xx + zz), i12,
            i02, i12, i22 + (xx + yy),
        );
        CompositeInertia {
            mass: m,
            first_moment: h,
            inertia_origin,
        }
    }

    /// `𝔍 V = (I_o ω + h × v, m v − h × ω)`.
    #[inline]
    pub fn apply(&self, v: &Twist<T>) -> Wrench<T> {
        let w = Vector3::new(v[0], v[1], v[2]);
        let l = Vector3::new(v[3], v[4], v[5]);
        let a = self.inertia_origin * w + self.first_moment.cross(&l);
        let f = l * self.mass - self.first_moment.cross(&w);
        Vector6::new(a.x, a.y, a.z, f.x, f.y, f.z)
    }

    /// The 6×6 matrix `𝔍`.
    pub fn matrix(&self) -> nalgebra::Matrix6<T> {
        let mut m = nalgebra::Matrix6::zeros();
        let hh = hat(&self.first_moment);
        m.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&self.inertia_origin);
        m.fixed_view_mut::<3, 3>(0, 3).copy_from(&hh);
        m.fixed_view_mut::<3, 3>(3, 0).copy_from(&hh.transpose());
        m.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(Matrix3::identity() * self.mass));
        m
    }
}
