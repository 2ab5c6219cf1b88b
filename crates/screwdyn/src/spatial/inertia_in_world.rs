//! A body's rigid inertia moved to the base frame {0} from its ten parameters, for the
//! base-frame algorithms (ABA, the RNEA in {0} and the CRBA's composite inertias): `𝔍^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}` is never
//! formed by 6×6 products, only `m`, `c^0` and the six entries of `I_c^0`.

use super::fused::cross;
use crate::scalar::Real;
use crate::spatial::{ang, lin, twist, Se3, SpatialInertia, Twist, Wrench};
use nalgebra::{Matrix3, Matrix6, Vector3};

/// Body `i`'s inertia in {0}, given `h = H_i^0 = (R, p)`: the mass `m`, the centre of mass
/// `c^0 = R c + p` and the rotational inertia about it `I_c^0 = R I_c Rᵀ` (symmetric, six entries).
pub(crate) struct InertiaInWorld<T: Real> {
    pub(crate) mass: T,
    pub(crate) com: Vector3<T>,
    /// `I_c^0` as `(I₀₀, I₁₁, I₂₂, I₀₁, I₀₂, I₁₂)`.
    pub(crate) rotational: [T; 6],
}

impl<T: Real> InertiaInWorld<T> {
    /// `m`, `c^0 = R c + p` and `I_c^0 = R I_c Rᵀ` of `body` (given in its own frame) at `h = H_i^0`.
    #[inline(always)]
    pub(crate) fn new(body: &SpatialInertia<T>, h: &Se3<T>) -> Self {
        let (r, ic) = (&h.rotation, &body.inertia_com);
        // A = R I_c, row by row.
        let a = Matrix3::from_fn(|row, k| {
            r[(row, 2)].mul_add(
                ic[(2, k)],
                r[(row, 1)].mul_add(ic[(1, k)], r[(row, 0)] * ic[(0, k)]),
            )
        });
        // (A Rᵀ)_{jk} = row j of A · row k of R; symmetric, so six are formed.
        let dot = |j: usize, k: usize| {
            a[(j, 2)].mul_add(
                r[(k, 2)],
                a[(j, 1)].mul_add(r[(k, 1)], a[(j, 0)] * r[(k, 0)]),
            )
        };
        Self {
            mass: body.mass,
            com: com_in_world(body, h),
            rotational: [
                dot(0, 0),
                dot(1, 1),
                dot(2, 2),
                dot(0, 1),
                dot(0, 2),
                dot(1, 2),
            ],
        }
    }

    /// The momentum `(l, f) = 𝔍^0 x` of the twist `x = (x_ω, x_v)`:
    /// `f = m (x_v − c^0 × x_ω)`, `l = I_c^0 x_ω + c^0 × f`.
    #[inline(always)]
    pub(crate) fn momentum(&self, x: &Twist<T>) -> Wrench<T> {
        let [i00, i11, i22, i01, i02, i12] = self.rotational;
        let (w, v) = (ang(x), lin(x));
        let f = (v - cross(&self.com, &w)) * self.mass;
        let l = Vector3::new(
            i02.mul_add(w.z, i01.mul_add(w.y, i00 * w.x)),
            i12.mul_add(w.z, i11.mul_add(w.y, i01 * w.x)),
            i22.mul_add(w.z, i12.mul_add(w.y, i02 * w.x)),
        ) + cross(&self.com, &f);
        twist(l, f)
    }

    /// The bias wrench `−ad_Vᵀ 𝔍^0 V` of the twist `V = (ω, v)` from the ten parameters:
    /// with the centre of mass's velocity `v_c = v + ω × c^0` and `g = m ω × v_c`,
    /// `−ad_Vᵀ 𝔍^0 V = (ω × I_c^0 ω + c^0 × g, g)`. (It equals
    /// [`velocity_product_wrench`]`(V, 𝔍^0 V)`: with `f = m v_c` and `l = I_c^0 ω + c^0 × f`,
    /// `v × f = −(ω × c^0) × f` as `v_c × f = 0`, and `ω × (c^0 × f) − (ω × c^0) × f =
    /// c^0 × (ω × f)` by the Jacobi identity.) 36 products against 51 through the momentum.
    #[inline(always)]
    pub(crate) fn velocity_product_wrench(&self, vel: &Twist<T>) -> Wrench<T> {
        let [i00, i11, i22, i01, i02, i12] = self.rotational;
        let (w, v, c) = (ang(vel), lin(vel), &self.com);
        // v_c = v + ω × c^0.
        let vc = Vector3::new(
            w.y.mul_add(c.z, (-w.z).mul_add(c.y, v.x)),
            w.z.mul_add(c.x, (-w.x).mul_add(c.z, v.y)),
            w.x.mul_add(c.y, (-w.y).mul_add(c.x, v.z)),
        );
        // g = ω × (m v_c).
        let g = cross(&w, &(vc * self.mass));
        // I_c^0 ω, then ω × I_c^0 ω + c^0 × g.
        let iw = Vector3::new(
            i02.mul_add(w.z, i01.mul_add(w.y, i00 * w.x)),
            i12.mul_add(w.z, i11.mul_add(w.y, i01 * w.x)),
            i22.mul_add(w.z, i12.mul_add(w.y, i02 * w.x)),
        );
        let wiw = cross(&w, &iw);
        let l = Vector3::new(
            c.y.mul_add(g.z, (-c.z).mul_add(g.y, wiw.x)),
            c.z.mul_add(g.x, (-c.x).mul_add(g.z, wiw.y)),
            c.x.mul_add(g.y, (-c.y).mul_add(g.x, wiw.z)),
        );
        twist(l, g)
    }

    /// Writes the 6×6 `𝔍^0 = [I_c^0 − m[c^0][c^0]  m[c^0]; −m[c^0]  m·1]` into `out`, entry by
    /// entry in place (column-major order), with no 6×6 temporary to copy.
    #[inline(always)]
    pub(crate) fn write_matrix(&self, out: &mut Matrix6<T>) {
        let (m, c0) = (self.mass, &self.com);
        let [i00, i11, i22, i01, i02, i12] = self.rotational;
        let (mx, my, mz) = (m * c0.x, m * c0.y, m * c0.z);
        // −m[c][c] = m (cᵀc 1 − c cᵀ).
        let (xx, yy, zz) = (mx * c0.x, my * c0.y, mz * c0.z);
        let (xy, xz, yz) = (mx * c0.y, mx * c0.z, my * c0.z);
        let zero = T::zero();
        let (a00, a11, a22) = (i00 + yy + zz, i11 + xx + zz, i22 + xx + yy);
        let (a01, a02, a12) = (i01 - xy, i02 - xz, i12 - yz);
        #[rustfmt::skip]
        let columns = [
            [a00, a01, a02, zero, -mz, my],
            [a01, a11, a12, mz, zero, -mx],
            [a02, a12, a22, -my, mx, zero],
            [zero, mz, -my, m, zero, zero],
            [-mz, zero, mx, zero, m, zero],
            [my, -mx, zero, zero, zero, m],
        ];
        for (c, column) in columns.iter().enumerate() {
            for (r, x) in column.iter().enumerate() {
                out[(r, c)] = *x;
            }
        }
    }
}

/// `c^0 = R c + p`: the centre of mass of `body` in {0} at `h = H_i^0 = (R, p)`.
#[inline(always)]
pub(crate) fn com_in_world<T: Real>(body: &SpatialInertia<T>, h: &Se3<T>) -> Vector3<T> {
    let (r, c) = (&h.rotation, &body.com);
    Vector3::from_fn(|row, _| {
        r[(row, 2)].mul_add(
            c.z,
            r[(row, 1)].mul_add(c.y, r[(row, 0)].mul_add(c.x, h.translation[row])),
        )
    })
}

/// The bias wrench `−ad_Vᵀ 𝔍^0 V = (ω × l + v × f, ω × f)` of the twist `V = (ω, v)` whose
/// momentum is `(l, f) = 𝔍^0 V`.
#[inline(always)]
pub(crate) fn velocity_product_wrench<T: Real>(vel: &Twist<T>, momentum: &Wrench<T>) -> Wrench<T> {
    let (w, v) = (ang(vel), lin(vel));
    let (l, f) = (ang(momentum), lin(momentum));
    twist(cross(&w, &l) + cross(&v, &f), cross(&w, &f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::ad_matrix;
    use nalgebra::Vector6;

    /// The ten-parameter bias wrench against `−ad_Vᵀ 𝔍^0 V` by 6×6 products:
    /// `𝔍^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}` from the body-frame matrix.
    #[test]
    fn velocity_product_wrench_matches_six_by_six_products() {
        let body = SpatialInertia::new(
            2.3,
            Vector3::new(0.1, -0.25, 0.4),
            Matrix3::new(0.3, 0.02, -0.01, 0.02, 0.25, 0.03, -0.01, 0.03, 0.2),
        );
        let h = Se3::new(
            Se3::from_rpy(0.4, -0.7, 1.1).rotation,
            Vector3::new(0.5, -0.3, 0.8),
        );
        let vel = Vector6::new(0.7, -1.2, 0.4, 0.9, 0.3, -1.5);
        let ad_inv = h.inverse().adjoint_matrix();
        let inertia_in_world = ad_inv.transpose() * body.matrix() * ad_inv;
        let expected = -ad_matrix(&vel).transpose() * (inertia_in_world * vel);
        let got = InertiaInWorld::new(&body, &h).velocity_product_wrench(&vel);
        assert!((got - expected).norm() < 1e-13, "{got} vs {expected}");
    }
}
