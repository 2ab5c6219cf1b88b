//! A body's rigid inertia moved to the base frame {0} from its ten parameters, for the
//! base-frame algorithms (ABA, the RNEA in {0} and the CRBA's composite inertias): `𝔍^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}` is never
//! formed by 6×6 products, only `m`, `c^0` and the six entries of `I_c^0`.

use super::fused::cross;
use crate::scalar::Real;
use crate::spatial::{ang, lin, twist, Se3, SpatialInertia, Twist, Wrench};
use nalgebra::{Matrix3, Matrix6, SymmetricEigen, Vector3};

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
        Self::with_form(body, &InertiaForm::General, h)
    }

    /// As [`InertiaInWorld::new`], with `I_c^0 = R I_c Rᵀ` formed from `form`, the shape of
    /// `body.inertia_com` ([`InertiaForm::of`] of it: the model's derived per-body forms).
    #[inline(always)]
    pub(crate) fn with_form(body: &SpatialInertia<T>, form: &InertiaForm<T>, h: &Se3<T>) -> Self {
        Self {
            mass: body.mass,
            com: com_in_world(body, h),
            rotational: form.rotated(&body.inertia_com, &h.rotation),
        }
    }

    /// The momentum `(l, f) = 𝔍^0 x` of the twist `x = (x_ω, x_v)`:
    /// `f = m (x_v − c^0 × x_ω)`, `l = I_c^0 x_ω + c^0 × f`.
    #[inline(always)]
    pub(crate) fn momentum(&self, x: &Twist<T>) -> Wrench<T> {
        let (w, v) = (ang(x), lin(x));
        let f = (v - cross(&self.com, &w)) * self.mass;
        let l = self.rotational_times(&w) + cross(&self.com, &f);
        twist(l, f)
    }

    /// `I_c^0 w` from the six entries of the symmetric `I_c^0`, fused.
    #[inline(always)]
    fn rotational_times(&self, w: &Vector3<T>) -> Vector3<T> {
        let [i00, i11, i22, i01, i02, i12] = self.rotational;
        Vector3::new(
            i02.mul_add(w.z, i01.mul_add(w.y, i00 * w.x)),
            i12.mul_add(w.z, i11.mul_add(w.y, i01 * w.x)),
            i22.mul_add(w.z, i12.mul_add(w.y, i02 * w.x)),
        )
    }

    /// The bias wrench `−ad_Vᵀ 𝔍^0 V` of the twist `V = (ω, v)` from the ten parameters:
    /// with the centre of mass's velocity `v_c = v + ω × c^0` and `g = m ω × v_c`,
    /// `−ad_Vᵀ 𝔍^0 V = (ω × I_c^0 ω + c^0 × g, g)`. (It equals `(ω × l + v × f, ω × f)` of the
    /// momentum `(l, f) = 𝔍^0 V`: with `f = m v_c` and `l = I_c^0 ω + c^0 × f`,
    /// `v × f = −(ω × c^0) × f` as `v_c × f = 0`, and `ω × (c^0 × f) − (ω × c^0) × f =
    /// c^0 × (ω × f)` by the Jacobi identity.) 36 products against 51 through the momentum.
    #[inline(always)]
    pub(crate) fn velocity_product_wrench(&self, vel: &Twist<T>) -> Wrench<T> {
        let (w, v, c) = (ang(vel), lin(vel), &self.com);
        // v_c = v + ω × c^0.
        let vc = Vector3::new(
            w.y.mul_add(c.z, (-w.z).mul_add(c.y, v.x)),
            w.z.mul_add(c.x, (-w.x).mul_add(c.z, v.y)),
            w.x.mul_add(c.y, (-w.y).mul_add(c.x, v.z)),
        );
        // g = ω × (m v_c).
        let g = cross(&w, &(vc * self.mass));
        // ω × I_c^0 ω + c^0 × g.
        let wiw = cross(&w, &self.rotational_times(&w));
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

/// `R I_c Rᵀ` by the general products (27 + 18 fused multiply–adds), as
/// `(I₀₀, I₁₁, I₂₂, I₀₁, I₀₂, I₁₂)`.
#[inline(always)]
fn rotated_general<T: Real>(ic: &Matrix3<T>, r: &Matrix3<T>) -> [T; 6] {
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
    [
        dot(0, 0),
        dot(1, 1),
        dot(2, 2),
        dot(0, 1),
        dot(0, 2),
        dot(1, 2),
    ]
}

/// The shape of a body's rotational inertia `I_c` (in its own frame {i}) that decides how
/// `R I_c Rᵀ` is formed. With zero products of inertia, `I_c = diag(d₀, d₁, d₂) =
/// a·1 + Σ_k μ_k e_k e_kᵀ` (`μ_k = d_k − a`), so `R I_c Rᵀ = a·1 + Σ_k μ_k r_k r_kᵀ` with
/// `r_k = R e_k` the k-th column of `R`: no product `R I_c` is formed. Published arms mostly
/// have such inertias (a cylinder along a coordinate axis has two equal moments: one term).
/// Only exactly-zero products and exactly-equal moments are used for these shapes; an `I_c`
/// with products of inertia is written the same way by its principal axes (`Principal`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum InertiaForm<T: Real> {
    /// `I_c = a·1 + μ e_k e_kᵀ` (`k = axis`; spherical when `μ = 0`):
    /// `R I_c Rᵀ = a·1 + μ r_k r_kᵀ` (3 products, 6 fused multiply–adds).
    Axisymmetric { a: T, mu: T, axis: usize },
    /// `I_c = a·1 + μ₀ e_j e_jᵀ + μ₁ e_k e_kᵀ` (`[j, k] = axes`, `a` the third moment):
    /// `R I_c Rᵀ = a·1 + μ₀ r_j r_jᵀ + μ₁ r_k r_kᵀ` (6 products, 12 fused multiply–adds).
    Diagonal { a: T, mu: [T; 2], axes: [usize; 2] },
    /// Nonzero products of inertia, by the principal axes: `I_c = a·1 + u₀u₀ᵀ + u₁u₁ᵀ` with
    /// `a` the smallest principal moment and `u_k = √(μ_k) v_k` (`v_k` the unit principal axes
    /// of the other two moments, `μ_k ≥ 0` their excess over `a`), found once when the model is
    /// built: `R I_c Rᵀ = a·1 + w₀w₀ᵀ + w₁w₁ᵀ` with `w_k = R u_k` (18 operations for the
    /// `w_k`, 12 for the sum: 30 against the general products' 45). Equal to the general
    /// products up to rounding.
    Principal { a: T, u: [Vector3<T>; 2] },
    /// `R I_c Rᵀ` by the general products (an `I_c` that is not exactly symmetric, or whose
    /// principal axes were not found to rounding accuracy).
    General,
}

impl<T: Real> InertiaForm<T> {
    /// The form of `ic` (`I_c` in the body's own frame).
    pub(crate) fn of(ic: &Matrix3<T>) -> Self {
        let zero = T::zero();
        let products_zero = (0..3).all(|j| (0..3).all(|k| j == k || ic[(j, k)] == zero));
        if !products_zero {
            return Self::principal(ic).unwrap_or(Self::General);
        }
        let d = [ic[(0, 0)], ic[(1, 1)], ic[(2, 2)]];
        // The odd moment out of two equal ones (or any, when all three are equal).
        let odd = match (d[0] == d[1], d[0] == d[2], d[1] == d[2]) {
            (true, _, _) => Some(2),
            (false, true, _) => Some(1),
            (false, false, true) => Some(0),
            (false, false, false) => None,
        };
        if let Some(k) = odd {
            let a = d[(k + 1) % 3];
            return Self::Axisymmetric {
                a,
                mu: d[k] - a,
                axis: k,
            };
        }
        // Three distinct moments: `a` the smallest, so that both μ are positive.
        let smallest = (0..3)
            .min_by(|&j, &k| d[j].partial_cmp(&d[k]).unwrap_or(std::cmp::Ordering::Equal))
            .unwrap_or(0);
        let axes = [(smallest + 1) % 3, (smallest + 2) % 3];
        let a = d[smallest];
        Self::Diagonal {
            a,
            mu: [d[axes[0]] - a, d[axes[1]] - a],
            axes,
        }
    }

    /// [`InertiaForm::Principal`] of a symmetric `ic` with products of inertia (Lynch & Park,
    /// *Modern Robotics*, §8.2.1: `I_c = Σ_k λ_k v_k v_kᵀ` with orthonormal principal axes `v_k`),
    /// or `None` when `ic` is not exactly symmetric or finite, or when `a·1 + u₀u₀ᵀ + u₁u₁ᵀ`
    /// differs from `ic` by more than rounding (64 ε of its largest entry).
    fn principal(ic: &Matrix3<T>) -> Option<Self> {
        if *ic != ic.transpose() || !ic.iter().all(|x| x.is_finite()) {
            return None;
        }
        let eigen = SymmetricEigen::try_new(*ic, T::default_epsilon(), 1000)?;
        let moments = eigen.eigenvalues;
        let smallest = (0..3)
            .min_by(|&j, &k| {
                moments[j]
                    .partial_cmp(&moments[k])
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(0);
        let a = moments[smallest];
        let u = [(smallest + 1) % 3, (smallest + 2) % 3]
            .map(|k| eigen.eigenvectors.column(k) * (moments[k] - a).max(T::zero()).sqrt());
        let rebuilt =
            Matrix3::from_diagonal_element(a) + u[0] * u[0].transpose() + u[1] * u[1].transpose();
        let tolerance = ic.amax() * T::default_epsilon() * crate::scalar::real(64.0);
        ((rebuilt - ic).amax() <= tolerance).then_some(Self::Principal { a, u })
    }

    /// `R I_c Rᵀ` as `(I₀₀, I₁₁, I₂₂, I₀₁, I₀₂, I₁₂)`, where `ic = I_c` has this form.
    #[inline(always)]
    pub(crate) fn rotated(&self, ic: &Matrix3<T>, r: &Matrix3<T>) -> [T; 6] {
        let column = |k: usize| {
            let k = k.min(2);
            Vector3::new(r[(0, k)], r[(1, k)], r[(2, k)])
        };
        match *self {
            // a·1 + (μ r_k) r_kᵀ.
            Self::Axisymmetric { a, mu, axis } => {
                let rk = column(axis);
                let m = rk * mu;
                [
                    m.x.mul_add(rk.x, a),
                    m.y.mul_add(rk.y, a),
                    m.z.mul_add(rk.z, a),
                    m.x * rk.y,
                    m.x * rk.z,
                    m.y * rk.z,
                ]
            }
            // a·1 + (μ₀ r_j) r_jᵀ + (μ₁ r_k) r_kᵀ.
            Self::Diagonal { a, mu, axes } => {
                let (rj, rk) = (column(axes[0]), column(axes[1]));
                let (mj, mk) = (rj * mu[0], rk * mu[1]);
                identity_plus_two_outer(a, [&mj, &rj], [&mk, &rk])
            }
            // a·1 + w₀w₀ᵀ + w₁w₁ᵀ with w_k = R u_k.
            Self::Principal { a, u } => {
                let rotate = |u: &Vector3<T>| {
                    Vector3::from_fn(|row, _| {
                        r[(row, 2)].mul_add(u.z, r[(row, 1)].mul_add(u.y, r[(row, 0)] * u.x))
                    })
                };
                let (w0, w1) = (rotate(&u[0]), rotate(&u[1]));
                identity_plus_two_outer(a, [&w0, &w0], [&w1, &w1])
            }
            Self::General => rotated_general(ic, r),
        }
    }
}

/// `a·1 + x₀y₀ᵀ + x₁y₁ᵀ` as `(00, 11, 22, 01, 02, 12)`, for `x_k` a multiple of `y_k` (so
/// that the sum is symmetric), every sum of products fused.
#[inline(always)]
fn identity_plus_two_outer<T: Real>(
    a: T,
    [x0, y0]: [&Vector3<T>; 2],
    [x1, y1]: [&Vector3<T>; 2],
) -> [T; 6] {
    let diagonal = |p: usize| x1[p].mul_add(y1[p], x0[p].mul_add(y0[p], a));
    let off = |p: usize, q: usize| x1[p].mul_add(y1[q], x0[p] * y0[q]);
    [
        diagonal(0),
        diagonal(1),
        diagonal(2),
        off(0, 1),
        off(0, 2),
        off(1, 2),
    ]
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

    /// Uniform numbers in [−3.2, 3.2) (xorshift), reproducible from `state`.
    fn uniform_from(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 6.4 - 3.2
        }
    }

    /// `R I_c Rᵀ` from the form of `I_c` against the general products, for random rotations
    /// (largest entry error relative to the largest moment: 1e-15 for the exact shapes, 4e-15
    /// for the principal axes, which rebuild `I_c` to rounding); returns the form.
    fn check_form(ic: Matrix3<f64>) -> InertiaForm<f64> {
        let form = InertiaForm::of(&ic);
        let relative = match form {
            InertiaForm::Principal { .. } => 4e-15,
            _ => 1e-15,
        };
        let scale = ic.amax() * relative / 1e-15;
        let mut uniform = uniform_from(0x2545_f491_4f6c_dd1d);
        for _ in 0..200 {
            let r = Se3::from_rpy(uniform(), uniform(), uniform()).rotation;
            let expected = rotated_general(&ic, &r);
            let got = form.rotated(&ic, &r);
            for (g, e) in got.iter().zip(&expected) {
                assert!(
                    (g - e).abs() <= 1e-15 * scale,
                    "{form:?}: {got:?} vs {expected:?}"
                );
            }
            // and against R I_c Rᵀ by nalgebra's own products.
            let full = r * ic * r.transpose();
            let six = [
                full[(0, 0)],
                full[(1, 1)],
                full[(2, 2)],
                full[(0, 1)],
                full[(0, 2)],
                full[(1, 2)],
            ];
            for (g, e) in got.iter().zip(&six) {
                assert!(
                    (g - e).abs() <= 1e-15 * scale,
                    "{form:?}: {got:?} vs {six:?}"
                );
            }
        }
        form
    }

    #[test]
    fn spherical_inertia_rotates_to_itself() {
        let form = check_form(Matrix3::from_diagonal_element(0.37));
        assert_eq!(
            form,
            InertiaForm::Axisymmetric {
                a: 0.37,
                mu: 0.0,
                axis: 2
            }
        );
    }

    #[test]
    fn axisymmetric_inertias_about_each_axis() {
        // UR5 (example-robot-data) upper arm: ixx = iyy, about z; cylinders along x and y.
        let about_z = check_form(Matrix3::from_diagonal(&Vector3::new(
            0.22689067591,
            0.22689067591,
            0.0151074,
        )));
        assert!(matches!(about_z, InertiaForm::Axisymmetric { axis: 2, .. }));
        let about_x = check_form(Matrix3::from_diagonal(&Vector3::new(
            0.0151074,
            0.13388583541666668,
            0.13388583541666668,
        )));
        assert!(matches!(about_x, InertiaForm::Axisymmetric { axis: 0, .. }));
        let about_y = check_form(Matrix3::from_diagonal(&Vector3::new(
            0.0102675, 0.00666, 0.0102675,
        )));
        assert!(matches!(about_y, InertiaForm::Axisymmetric { axis: 1, .. }));
    }

    #[test]
    fn diagonal_inertias_take_the_smallest_moment_as_a() {
        for d in [[0.3, 0.2, 0.1], [0.1, 0.3, 0.2], [0.2, 0.1, 0.3]] {
            let form = check_form(Matrix3::from_diagonal(&Vector3::from(d)));
            let InertiaForm::Diagonal { a, mu, .. } = form else {
                panic!("{form:?}")
            };
            assert_eq!(a, 0.1);
            assert!(mu[0] > 0.0 && mu[1] > 0.0, "{form:?}");
        }
    }

    /// `a` and `u_k` of a principal form: `a·1 + u₀u₀ᵀ + u₁u₁ᵀ` rebuilds `ic` to 4e-15 of its
    /// largest entry, and `a` is its smallest eigenvalue (the characteristic polynomial
    /// `det(ic − a·1)` vanishes there, and `ic − a·1` is positive semidefinite).
    fn check_principal(ic: &Matrix3<f64>, form: &InertiaForm<f64>) {
        let InertiaForm::Principal { a, u } = *form else {
            panic!("{form:?}")
        };
        let rebuilt =
            Matrix3::from_diagonal_element(a) + u[0] * u[0].transpose() + u[1] * u[1].transpose();
        assert!(
            (rebuilt - ic).amax() <= 4e-15 * ic.amax(),
            "{rebuilt} vs {ic}"
        );
        let shifted = ic - Matrix3::from_diagonal_element(a);
        assert!(shifted.determinant().abs() <= 1e-15 * ic.amax().powi(3));
        // Positive semidefinite: the diagonal entries and the 2×2 principal minors.
        let scale = ic.amax();
        for k in 0..3 {
            assert!(shifted[(k, k)] >= -1e-15 * scale, "{shifted}");
            let (p, q) = ((k + 1) % 3, (k + 2) % 3);
            let minor = shifted[(p, p)] * shifted[(q, q)] - shifted[(p, q)] * shifted[(q, p)];
            assert!(minor >= -1e-15 * scale * scale, "{shifted}");
        }
    }

    #[test]
    fn inertias_with_products_take_their_principal_axes() {
        // Panda link 1 (franka_description): nonzero products.
        let ic = Matrix3::new(
            0.70337, -0.000139, 0.006772, -0.000139, 0.70661, 0.019169, 0.006772, 0.019169,
            0.009117,
        );
        let form = check_form(ic);
        check_principal(&ic, &form);
        // A single nonzero product is enough.
        let mut one = Matrix3::from_diagonal(&Vector3::new(0.2, 0.2, 0.1));
        one[(1, 2)] = 1e-9;
        one[(2, 1)] = 1e-9;
        check_principal(&one, &check_form(one));
        // A cylinder whose axis is not a coordinate axis: two equal principal moments.
        let tilted = Se3::from_rpy(0.3, -0.5, 0.9).rotation;
        let cylinder =
            tilted * Matrix3::from_diagonal(&Vector3::new(0.2, 0.2, 0.05)) * tilted.transpose();
        let symmetric = (cylinder + cylinder.transpose()) * 0.5;
        check_principal(&symmetric, &check_form(symmetric));
    }

    /// Random inertias `R₀ diag(d) R₀ᵀ` (moments satisfying the triangle inequality, from
    /// 1e-4 to 10) against the general products, each for 200 random rotations.
    #[test]
    fn random_inertias_by_their_principal_axes_match_the_general_products() {
        let mut uniform = uniform_from(0x9e37_79b9_7f4a_7c15);
        for _ in 0..200 {
            let scale = 10f64.powf(uniform() * 0.78 - 1.5);
            let (d0, d1) = ((uniform() + 3.3) * scale, (uniform() + 3.3) * scale);
            let d = Vector3::new(
                d0,
                d1,
                (d0 - d1).abs() + (d0 + d1 - (d0 - d1).abs()) * (uniform() + 3.2) / 6.4,
            );
            let r0 = Se3::from_rpy(uniform(), uniform(), uniform()).rotation;
            let full = r0 * Matrix3::from_diagonal(&d) * r0.transpose();
            let ic = (full + full.transpose()) * 0.5;
            let form = check_form(ic);
            check_principal(&ic, &form);
        }
    }

    /// An `I_c` that is not exactly symmetric keeps the general products (which read all nine
    /// entries), as does one with a non-finite entry.
    #[test]
    fn unsymmetric_or_non_finite_inertias_take_the_general_products() {
        let mut ic = Matrix3::new(0.3, 0.02, -0.01, 0.02, 0.25, 0.03, -0.01, 0.03, 0.2);
        ic[(0, 1)] = 0.021;
        assert_eq!(check_form(ic), InertiaForm::General);
        ic[(0, 1)] = f64::NAN;
        ic[(1, 0)] = f64::NAN;
        assert_eq!(InertiaForm::of(&ic), InertiaForm::General);
    }

    /// The UR5 (builtin:ur5, models/ur5.urdf) has cylinders along coordinate axes: every body
    /// takes the one-term rotation; the Panda's arm links have products (principal axes), its
    /// fingers diagonal inertias.
    #[test]
    fn published_arms_are_classified_once_per_body() {
        for name in ["ur5", "models/ur5.urdf", "panda"] {
            let path = if name.contains('/') {
                format!("{}/../../{name}", env!("CARGO_MANIFEST_DIR"))
            } else {
                format!("builtin:{name}")
            };
            let model = crate::io::load_model(&path).unwrap();
            let forms = &model.body_inertia_form;
            assert_eq!(forms.len(), model.nbodies());
            for (body, form) in model.bodies().iter().zip(forms) {
                assert_eq!(*form, InertiaForm::of(&body.inertia.inertia_com));
                let axisymmetric = matches!(form, InertiaForm::Axisymmetric { .. });
                assert_eq!(
                    axisymmetric,
                    name.contains("ur5"),
                    "{name} {}: {form:?}",
                    body.name
                );
                // No body of these arms keeps the general products.
                assert_ne!(*form, InertiaForm::General, "{name} {}", body.name);
            }
        }
    }
}
