//! The spatial operators on [`Lanes`]: poses, twists and wrenches of `L` states at once,
//! each operation the lane-wise copy of its scalar counterpart in [`crate::spatial`].
//!
//! Vectors are arrays of lanes (`V3 = [Lanes; 3]`, `V6 = [Lanes; 6]`, angular part first);
//! quantities that are the same for every state (a body's inertia, a joint's home pose) stay
//! plain `f64` and are broadcast by the arithmetic.

use super::lanes::Lanes;
use crate::spatial::inertia_in_world::InertiaForm;
use crate::spatial::SpatialInertia;

/// A 3-vector of lanes.
pub type V3<const L: usize> = [Lanes<L>; 3];
/// A twist `(ω, v)` or wrench `(m, f)` of lanes.
pub type V6<const L: usize> = [Lanes<L>; 6];
/// A 6×6 matrix of lanes, `m[row][col]`.
pub type M6<const L: usize> = [[Lanes<L>; 6]; 6];

/// `V̇_base = (0, −g)` ([`crate::dynamics::base_acceleration`]) in every lane.
#[inline(always)]
pub fn gravity_twist<const L: usize>(model: &crate::Model) -> V6<L> {
    let b = crate::dynamics::base_acceleration(model);
    each!(6, |k| Lanes::splat(b[k]))
}

/// All lanes zero.
#[inline(always)]
pub fn zero6<const L: usize>() -> V6<L> {
    [Lanes::zero(); 6]
}

/// The angular (first) half.
#[inline(always)]
pub fn ang<const L: usize>(v: &V6<L>) -> V3<L> {
    [v[0], v[1], v[2]]
}

/// The linear (second) half.
#[inline(always)]
pub fn lin<const L: usize>(v: &V6<L>) -> V3<L> {
    [v[3], v[4], v[5]]
}

/// `(a, b)` as one 6-vector.
#[inline(always)]
pub fn join<const L: usize>(a: V3<L>, b: V3<L>) -> V6<L> {
    [a[0], a[1], a[2], b[0], b[1], b[2]]
}

/// `a × b`.
#[inline(always)]
pub fn cross<const L: usize>(a: &V3<L>, b: &V3<L>) -> V3<L> {
    [
        a[1].mul_add(b[2], -(a[2] * b[1])),
        a[2].mul_add(b[0], -(a[0] * b[2])),
        a[0].mul_add(b[1], -(a[1] * b[0])),
    ]
}

/// `a × b` for a vector `a` that is the same in every lane.
#[inline(always)]
pub fn cross_const<const L: usize>(a: &[f64; 3], b: &V3<L>) -> V3<L> {
    [
        b[2].mul_add(a[1], -(b[1] * a[2])),
        b[0].mul_add(a[2], -(b[2] * a[0])),
        b[1].mul_add(a[0], -(b[0] * a[1])),
    ]
}

/// `a + b`, `a − b`, `a x` (lanes `x`) and `aᵀ b` (summed in index order) for 3- and
/// 6-vectors, written out entry by entry (see [`each!`](super::each)).
macro_rules! vector_ops {
    ($n:tt, $add:ident, $sub:ident, $scale:ident, $dot:ident) => {
        #[doc = concat!("`a + b` for ", stringify!($n), "-vectors.")]
        #[inline(always)]
        pub fn $add<const L: usize>(a: &[Lanes<L>; $n], b: &[Lanes<L>; $n]) -> [Lanes<L>; $n] {
            each!($n, |k| a[k] + b[k])
        }
        #[doc = concat!("`a − b` for ", stringify!($n), "-vectors.")]
        #[inline(always)]
        pub fn $sub<const L: usize>(a: &[Lanes<L>; $n], b: &[Lanes<L>; $n]) -> [Lanes<L>; $n] {
            each!($n, |k| a[k] - b[k])
        }
        #[doc = concat!("`a x` for ", stringify!($n), "-vectors.")]
        #[inline(always)]
        #[allow(dead_code)] // kept for both sizes; only the 6-vector form has a caller
        pub fn $scale<const L: usize>(a: &[Lanes<L>; $n], x: Lanes<L>) -> [Lanes<L>; $n] {
            each!($n, |k| a[k] * x)
        }
        #[doc = concat!("`aᵀ b` for ", stringify!($n), "-vectors, summed in index order (fused).")]
        #[inline(always)]
        pub fn $dot<const L: usize>(a: &[Lanes<L>; $n], b: &[Lanes<L>; $n]) -> Lanes<L> {
            dot!($n, |k| a[k], b[k])
        }
    };
}

vector_ops!(3, add3, sub3, scale3, dot3);
vector_ops!(6, add6, sub6, scale6, dot6);

/// A pose `H = (R, p)` in every lane; `r[row][col]`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pose<const L: usize> {
    /// The rotation `R`.
    pub r: [[Lanes<L>; 3]; 3],
    /// The translation `p`.
    pub p: V3<L>,
}

impl<const L: usize> Pose<L> {
    /// `R x` for lanes `x`.
    #[inline(always)]
    pub fn rotate(&self, x: &V3<L>) -> V3<L> {
        let r = &self.r;
        each!(3, |i| dot!(3, |k| r[i][k], x[k]))
    }

    /// `Rᵀ x`.
    #[inline(always)]
    pub fn rotate_back(&self, x: &V3<L>) -> V3<L> {
        let r = &self.r;
        each!(3, |i| dot!(3, |k| r[k][i], x[k]))
    }

    /// `H₁ H₂`: `(R₁ R₂, R₁ p₂ + p₁)` ([`Se3::compose`](crate::spatial::Se3::compose)).
    #[inline(always)]
    pub fn compose(&self, o: &Pose<L>) -> Pose<L> {
        let (a, b) = (&self.r, &o.r);
        Pose {
            r: each33!(|i, j| dot!(3, |k| a[i][k], b[k][j])),
            p: each!(3, |i| dot!(3, |k| a[i][k], o.p[k]; self.p[i])),
        }
    }

    /// `R x + p` ([`Se3::act_point`](crate::spatial::Se3::act_point)) for a point the same in
    /// every lane.
    #[inline(always)]
    pub fn act_point_const(&self, x: &[f64; 3]) -> V3<L> {
        let (r, p) = (&self.r, &self.p);
        each!(3, |i| dot!(3, |k| r[i][k], x[k]; p[i]))
    }

    /// `Ad_{H⁻¹} V = (Rᵀ ω, Rᵀ (v − p × ω))` ([`Se3::inv_act_twist`](crate::spatial::Se3::inv_act_twist)).
    #[inline(always)]
    pub fn inv_act_twist(&self, v: &V6<L>) -> V6<L> {
        let w0 = ang(v);
        let w = self.rotate_back(&w0);
        let l = self.rotate_back(&sub3(&lin(v), &cross(&self.p, &w0)));
        join(w, l)
    }

    /// `Ad_{H⁻¹}ᵀ W = (R m + p × R f, R f)`
    /// ([`Se3::inv_act_transpose_wrench`](crate::spatial::Se3::inv_act_transpose_wrench)).
    #[inline(always)]
    pub fn inv_act_transpose_wrench(&self, w: &V6<L>) -> V6<L> {
        let f = self.rotate(&lin(w));
        let m = add3(&self.rotate(&ang(w)), &cross(&self.p, &f));
        join(m, f)
    }

    /// `Ad_H S = (R ω, p × R ω + R v)` for a screw `S` the same in every lane
    /// ([`Se3::act_twist`](crate::spatial::Se3::act_twist)).
    #[inline(always)]
    pub fn act_screw(&self, s: &[f64; 6]) -> V6<L> {
        let r = &self.r;
        let w: V3<L> = each!(3, |i| dot!(3, |k| r[i][k], s[k]));
        let rv: V3<L> = each!(3, |i| dot!(3, |k| r[i][k], s[3 + k]));
        join(w, add3(&cross(&self.p, &w), &rv))
    }
}

/// `ad_V X = (ω × ω_x, v × ω_x + ω × v_x)` ([`crate::spatial::ad`]).
#[inline(always)]
pub fn ad<const L: usize>(v: &V6<L>, x: &V6<L>) -> V6<L> {
    let (w, wx) = (ang(v), ang(x));
    join(
        cross(&w, &wx),
        add3(&cross(&lin(v), &wx), &cross(&w, &lin(x))),
    )
}

/// `ad_Vᵀ W = (−ω × m − v × f, −ω × f)` ([`crate::spatial::ad_transpose`]).
#[inline(always)]
pub fn ad_transpose<const L: usize>(v: &V6<L>, w: &V6<L>) -> V6<L> {
    let (om, f) = (ang(v), lin(w));
    let a = cross(&om, &ang(w));
    let b = cross(&lin(v), &f);
    let c = cross(&om, &f);
    join(each!(3, |k| -a[k] - b[k]), each!(3, |k| -c[k]))
}

/// `𝔍 V` for a body inertia the same in every lane
/// ([`SpatialInertia::apply`]): `p = m (v − c × ω)`, `l = I_c ω + c × p`.
#[inline(always)]
pub fn apply_body_inertia<const L: usize>(j: &SpatialInertia<f64>, v: &V6<L>) -> V6<L> {
    let c = [j.com.x, j.com.y, j.com.z];
    let w = ang(v);
    let cw = cross_const(&c, &w);
    let p: V3<L> = each!(3, |k| (v[3 + k] - cw[k]) * j.mass);
    let ic = &j.inertia_com;
    let cp = cross_const(&c, &p);
    let l = each!(3, |i| dot!(3, |k| w[k], ic[(i, k)]; cp[i]));
    join(l, p)
}

/// `a·1 + x₀y₀ᵀ + x₁y₁ᵀ` as `(00, 11, 22, 01, 02, 12)`, for `x_k` a multiple of `y_k` (the
/// lanes' copy of the scalar one in `spatial::inertia_in_world`).
#[inline(always)]
fn identity_plus_two_outer<const L: usize>(
    a: f64,
    [x0, y0]: [&V3<L>; 2],
    [x1, y1]: [&V3<L>; 2],
) -> [Lanes<L>; 6] {
    // Entries written out, no closures (see docs/architecture.md, "Batches").
    macro_rules! diagonal {
        ($d:expr) => {
            x1[$d].mul_add(y1[$d], x0[$d].mul_add(y0[$d], Lanes::splat(a)))
        };
    }
    macro_rules! off {
        ($d:expr, $e:expr) => {
            x1[$d].mul_add(y1[$e], x0[$d] * y0[$e])
        };
    }
    [
        diagonal!(0),
        diagonal!(1),
        diagonal!(2),
        off!(0, 1),
        off!(0, 2),
        off!(1, 2),
    ]
}

/// A spatial inertia in the ten parameters CRBA sums
/// ([`CompositeInertia`](crate::spatial::CompositeInertia)): the mass (the same in every
/// lane), the first moment `h = m c` and the rotational inertia about the origin.
#[derive(Clone, Copy, Debug, Default)]
pub struct Composite<const L: usize> {
    /// `m`.
    pub mass: f64,
    /// `h = m c`.
    pub first_moment: V3<L>,
    /// `I_o`, `[row][col]`.
    pub inertia_origin: [[Lanes<L>; 3]; 3],
}

impl<const L: usize> Composite<L> {
    /// `self += o`.
    #[inline(always)]
    pub fn add(&mut self, o: &Composite<L>) {
        self.mass += o.mass;
        self.first_moment = add3(&self.first_moment, &o.first_moment);
        let (a, b) = (&self.inertia_origin, &o.inertia_origin);
        self.inertia_origin = each33!(|i, j| a[i][j] + b[i][j]);
    }

    /// A body's constant inertia, given in its frame, written in the frame `h` maps from, in
    /// the ten parameters
    /// ([`CompositeInertia::rigid_in_world`](crate::spatial::CompositeInertia::rigid_in_world)),
    /// through its centre of mass with `form` the shape of its `I_c` ([`InertiaForm`]): with
    /// `c⁰ = R c + p`, `h' = m c⁰` and `I_o' = R I_c Rᵀ + m(|c⁰|² 1 − c⁰ c⁰ᵀ)`, where an
    /// axisymmetric or diagonal `I_c` gives `R I_c Rᵀ = a·1 + Σ_k μ_k r_k r_kᵀ` from columns of
    /// `R` alone, one with products of inertia `a·1 + Σ_k (R u_k)(R u_k)ᵀ` by its principal
    /// axes, and any other `I_c` the products `(R I_c) Rᵀ`.
    #[inline(always)]
    pub fn rigid_in_world_with_form(
        body: &SpatialInertia<f64>,
        form: &InertiaForm<f64>,
        h: &Pose<L>,
    ) -> Composite<L> {
        let (r, p, m) = (&h.r, &h.p, body.mass);
        // R I_c Rᵀ as (00, 11, 22, 01, 02, 12).
        let rotated: [Lanes<L>; 6] = match *form {
            InertiaForm::Axisymmetric { a, mu, axis } => {
                let rk: V3<L> = each!(3, |i| r[i][axis]);
                let mk: V3<L> = each!(3, |i| rk[i] * mu);
                [
                    mk[0].mul_add(rk[0], Lanes::splat(a)),
                    mk[1].mul_add(rk[1], Lanes::splat(a)),
                    mk[2].mul_add(rk[2], Lanes::splat(a)),
                    mk[0] * rk[1],
                    mk[0] * rk[2],
                    mk[1] * rk[2],
                ]
            }
            InertiaForm::Diagonal { a, mu, axes } => {
                let rj: V3<L> = each!(3, |i| r[i][axes[0]]);
                let rk: V3<L> = each!(3, |i| r[i][axes[1]]);
                let mj: V3<L> = each!(3, |i| rj[i] * mu[0]);
                let mk: V3<L> = each!(3, |i| rk[i] * mu[1]);
                identity_plus_two_outer(a, [&mj, &rj], [&mk, &rk])
            }
            // a·1 + w₀w₀ᵀ + w₁w₁ᵀ with w_k = R u_k.
            InertiaForm::Principal { a, u } => {
                let w0: V3<L> = each!(3, |i| dot!(3, |k| r[i][k], u[0][k]));
                let w1: V3<L> = each!(3, |i| dot!(3, |k| r[i][k], u[1][k]));
                identity_plus_two_outer(a, [&w0, &w0], [&w1, &w1])
            }
            InertiaForm::General => {
                // (R I_c) then (R I_c Rᵀ)_ab = Σ_k (R I_c)_ak R_bk.
                let ic = &body.inertia_com;
                let ri = each33!(|a, b| dot!(3, |k| r[a][k], ic[(k, b)]));
                let e = |a: usize, b: usize| dot!(3, |k| ri[a][k], r[b][k]);
                [e(0, 0), e(1, 1), e(2, 2), e(0, 1), e(0, 2), e(1, 2)]
            }
        };
        let c = [body.com.x, body.com.y, body.com.z];
        let c0: V3<L> = each!(3, |i| dot!(3, |k| r[i][k], c[k]; p[i]));
        let hm: V3<L> = each!(3, |i| c0[i] * m);
        // m(|c⁰|² 1 − c⁰ c⁰ᵀ): the diagonal is h_y c⁰_y + h_z c⁰_z, …, the rest −h_a c⁰_b.
        let (xx, yy, zz) = (hm[0] * c0[0], hm[1] * c0[1], hm[2] * c0[2]);
        let [i00, i11, i22, i01, i02, i12] = rotated;
        let i01 = (-hm[0]).mul_add(c0[1], i01);
        let i02 = (-hm[0]).mul_add(c0[2], i02);
        let i12 = (-hm[1]).mul_add(c0[2], i12);
        let (i00, i11, i22) = (i00 + (yy + zz), i11 + (xx + zz), i22 + (xx + yy));
        Composite {
            mass: m,
            first_moment: hm,
            inertia_origin: [[i00, i01, i02], [i01, i11, i12], [i02, i12, i22]],
        }
    }

    /// `𝔍 V = (I_o ω + h × v, m v − h × ω)` ([`CompositeInertia::apply`](crate::spatial::CompositeInertia::apply)).
    #[inline(always)]
    pub fn apply(&self, v: &V6<L>) -> V6<L> {
        let (w, l) = (ang(v), lin(v));
        let io = &self.inertia_origin;
        let hl = cross(&self.first_moment, &l);
        let hw = cross(&self.first_moment, &w);
        let a = each!(3, |i| dot!(3, |k| io[i][k], w[k]; hl[i]));
        let f = each!(3, |k| l[k].mul_add(self.mass, -hw[k]));
        join(a, f)
    }
}

/// A body's constant inertia written in the frame `h` maps from, as the 6×6 matrix
/// `[I_o  [h]; [h]ᵀ  m 1]` with `c ↦ R c + p`, `I_c ↦ R I_c Rᵀ`
/// ([`SpatialInertia::transformed`], then [`SpatialInertia::matrix`]), written to `out`; returns
/// `𝔍 V`.
#[inline(always)]
pub fn body_inertia_in<const L: usize>(
    j: &SpatialInertia<f64>,
    h: &Pose<L>,
    v: &V6<L>,
    out: &mut M6<L>,
) -> V6<L> {
    let r = &h.r;
    let ic = &j.inertia_com;
    let m = j.mass;
    // A = R I_c; R I_c Rᵀ: row a of A dotted with row b of R.
    let a = each33!(|i, b| dot!(3, |k| r[i][k], ic[(k, b)]));
    macro_rules! rot {
        ($i:expr, $b:expr) => {
            dot!(3, |k| a[$i][k], r[$b][k])
        };
    }
    let (i01, i02, i12) = (rot!(0, 1), rot!(0, 2), rot!(1, 2));
    let ic_w = [
        [rot!(0, 0), i01, i02],
        [i01, rot!(1, 1), i12],
        [i02, i12, rot!(2, 2)],
    ];
    let c = h.act_point_const(&[j.com.x, j.com.y, j.com.z]);
    // 𝔍 V with the transformed parameters: p = m (v − c × ω), l = I_c ω + c × p.
    let w = ang(v);
    let cw = cross(&c, &w);
    let p: V3<L> = each!(3, |k| (v[3 + k] - cw[k]) * m);
    let cp = cross(&c, &p);
    let l: V3<L> = each!(3, |i| dot!(3, |k| ic_w[i][k], w[k]; cp[i]));
    // About the origin: I_o = I_c + m (|c|² 1 − c cᵀ), h = m c; [h] upper right, [h]ᵀ lower left.
    let cc = dot3(&c, &c) * m;
    let hm: V3<L> = each!(3, |k| c[k] * m);
    let io = each33!(|i, k| ic_w[i][k] - hm[i] * c[k]);
    let (z, mm) = (Lanes::zero(), Lanes::splat(m));
    *out = [
        [io[0][0] + cc, io[0][1], io[0][2], z, -hm[2], hm[1]],
        [io[1][0], io[1][1] + cc, io[1][2], hm[2], z, -hm[0]],
        [io[2][0], io[2][1], io[2][2] + cc, -hm[1], hm[0], z],
        [z, hm[2], -hm[1], mm, z, z],
        [-hm[2], z, hm[0], z, mm, z],
        [hm[1], -hm[0], z, z, z, mm],
    ];
    join(l, p)
}

/// `M x` for a 6×6 matrix of lanes.
#[inline(always)]
pub fn mul6<const L: usize>(m: &M6<L>, x: &V6<L>) -> V6<L> {
    each!(6, |i| dot6(&m[i], x))
}
