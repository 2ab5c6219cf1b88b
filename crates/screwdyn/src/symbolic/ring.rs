//! The arithmetic the symbolic mechanics is written over, and the spatial algebra
//! (`Ad`, `ad`, `adᵀ`, poses, spatial inertia) on 3-vectors of any [`Ring`].
//!
//! One implementation of the mechanics serves three rings: [`Poly`] (the canonical form, for
//! printing and symbolic equality), [`Sx`](super::dag::Sx) (an expression graph with hash-consing,
//! for code generation) and `f64` (a plain numeric check of the same code).

use super::poly::Poly;

/// A commutative ring with `f64` constants: what the symbolic mechanics needs.
pub trait Ring: Clone {
    /// The constant `x`.
    fn constant(x: f64) -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self − o`.
    fn sub(&self, o: &Self) -> Self;
    /// `self · o`.
    fn mul(&self, o: &Self) -> Self;
    /// `−self`.
    fn neg(&self) -> Self;
    /// Whether this is exactly zero (lets the mechanics skip work).
    fn is_zero(&self) -> bool;
    /// `0`.
    fn zero() -> Self {
        Self::constant(0.0)
    }
    /// `k · self`.
    fn scale(&self, k: f64) -> Self {
        if k == 1.0 {
            self.clone()
        } else if k == -1.0 {
            self.neg()
        } else {
            self.mul(&Self::constant(k))
        }
    }
}

impl Ring for f64 {
    fn constant(x: f64) -> Self {
        x
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn neg(&self) -> Self {
        -self
    }
    fn is_zero(&self) -> bool {
        *self == 0.0
    }
}

impl Ring for Poly {
    fn constant(x: f64) -> Self {
        Poly::constant(x)
    }
    fn add(&self, o: &Self) -> Self {
        Poly::add(self, o)
    }
    fn sub(&self, o: &Self) -> Self {
        Poly::sub(self, o)
    }
    fn mul(&self, o: &Self) -> Self {
        Poly::mul(self, o)
    }
    fn neg(&self) -> Self {
        Poly::neg(self)
    }
    fn is_zero(&self) -> bool {
        Poly::is_zero(self)
    }
    fn scale(&self, k: f64) -> Self {
        Poly::scale(self, k)
    }
}

/// A 3-vector over a ring.
#[derive(Clone, Debug)]
pub struct V3<R>(pub [R; 3]);

impl<R: Ring> V3<R> {
    /// `0`.
    pub fn zero() -> Self {
        V3([R::zero(), R::zero(), R::zero()])
    }
    /// From numbers.
    pub fn constant(x: [f64; 3]) -> Self {
        V3(x.map(R::constant))
    }
    /// `a + b`.
    pub fn add(&self, o: &Self) -> Self {
        V3([0, 1, 2].map(|i| self.0[i].add(&o.0[i])))
    }
    /// `a − b`.
    pub fn sub(&self, o: &Self) -> Self {
        V3([0, 1, 2].map(|i| self.0[i].sub(&o.0[i])))
    }
    /// `−a`.
    pub fn neg(&self) -> Self {
        V3([0, 1, 2].map(|i| self.0[i].neg()))
    }
    /// `k a` for a ring scalar `k`.
    pub fn times(&self, k: &R) -> Self {
        V3([0, 1, 2].map(|i| self.0[i].mul(k)))
    }
    /// `a · b`.
    pub fn dot(&self, o: &Self) -> R {
        dot3(&self.0, &o.0)
    }
    /// `a × b`.
    pub fn cross(&self, o: &Self) -> Self {
        let (a, b) = (&self.0, &o.0);
        V3([
            a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
            a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
            a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
        ])
    }
}

fn dot3<R: Ring>(a: &[R; 3], b: &[R; 3]) -> R {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

/// A 3×3 matrix over a ring, row-major.
#[derive(Clone, Debug)]
pub struct M3<R>(pub [[R; 3]; 3]);

impl<R: Ring> M3<R> {
    /// The identity.
    pub fn identity() -> Self {
        M3([0, 1, 2].map(|i| [0, 1, 2].map(|j| R::constant(if i == j { 1.0 } else { 0.0 }))))
    }
    /// From numbers (row-major).
    pub fn constant(m: [[f64; 3]; 3]) -> Self {
        M3(m.map(|r| r.map(R::constant)))
    }
    /// Row `i`.
    pub fn row(&self, i: usize) -> V3<R> {
        V3(self.0[i].clone())
    }
    /// Column `j`.
    pub fn col(&self, j: usize) -> V3<R> {
        V3([0, 1, 2].map(|i| self.0[i][j].clone()))
    }
    /// `A x`.
    pub fn mul_v(&self, x: &V3<R>) -> V3<R> {
        V3([0, 1, 2].map(|i| dot3(&self.0[i], &x.0)))
    }
    /// `Aᵀ x`.
    pub fn tr_mul_v(&self, x: &V3<R>) -> V3<R> {
        V3([0, 1, 2].map(|j| self.col(j).dot(x)))
    }
    /// `A B`.
    pub fn mul_m(&self, b: &M3<R>) -> M3<R> {
        let cols = [b.col(0), b.col(1), b.col(2)];
        M3([0, 1, 2].map(|i| [0, 1, 2].map(|j| dot3(&self.0[i], &cols[j].0))))
    }
    /// `Aᵀ`.
    pub fn transpose(&self) -> M3<R> {
        M3([0, 1, 2].map(|i| [0, 1, 2].map(|j| self.0[j][i].clone())))
    }
}

/// A pose `H = (R, p)` over a ring.
#[derive(Clone, Debug)]
pub struct Pose<R> {
    /// Rotation.
    pub r: M3<R>,
    /// Translation.
    pub p: V3<R>,
}

impl<R: Ring> Pose<R> {
    /// The identity pose.
    pub fn identity() -> Self {
        Pose {
            r: M3::identity(),
            p: V3::zero(),
        }
    }
    /// `H_a H_b`.
    pub fn compose(&self, o: &Pose<R>) -> Pose<R> {
        Pose {
            r: self.r.mul_m(&o.r),
            p: self.r.mul_v(&o.p).add(&self.p),
        }
    }
    /// `R x + p`.
    pub fn act_point(&self, x: &V3<R>) -> V3<R> {
        self.r.mul_v(x).add(&self.p)
    }
    /// `Ad_H V = (R ω, p × Rω + R v)`.
    pub fn act_twist(&self, v: &Tw<R>) -> Tw<R> {
        let w = self.r.mul_v(&v.w);
        let l = self.p.cross(&w).add(&self.r.mul_v(&v.v));
        Tw { w, v: l }
    }
    /// `Ad_{H⁻¹} V = (Rᵀ ω, Rᵀ (v − p × ω))`.
    pub fn inv_act_twist(&self, v: &Tw<R>) -> Tw<R> {
        Tw {
            w: self.r.tr_mul_v(&v.w),
            v: self.r.tr_mul_v(&v.v.sub(&self.p.cross(&v.w))),
        }
    }
    /// `Ad_{H⁻¹}ᵀ W = (R m + p × R f, R f)`: a wrench of the moving frame in the reference frame.
    pub fn inv_act_transpose_wrench(&self, w: &Tw<R>) -> Tw<R> {
        let f = self.r.mul_v(&w.v);
        Tw {
            w: self.r.mul_v(&w.w).add(&self.p.cross(&f)),
            v: f,
        }
    }
}

/// A twist `(ω, v)` or a wrench `(m, f)` over a ring (angular first).
#[derive(Clone, Debug)]
pub struct Tw<R> {
    /// Angular part (ω or moment).
    pub w: V3<R>,
    /// Linear part (v or force).
    pub v: V3<R>,
}

impl<R: Ring> Tw<R> {
    /// `0`.
    pub fn zero() -> Self {
        Tw {
            w: V3::zero(),
            v: V3::zero(),
        }
    }
    /// `a + b`.
    pub fn add(&self, o: &Self) -> Self {
        Tw {
            w: self.w.add(&o.w),
            v: self.v.add(&o.v),
        }
    }
    /// `a − b`.
    pub fn sub(&self, o: &Self) -> Self {
        Tw {
            w: self.w.sub(&o.w),
            v: self.v.sub(&o.v),
        }
    }
    /// `k a`.
    pub fn times(&self, k: &R) -> Self {
        Tw {
            w: self.w.times(k),
            v: self.v.times(k),
        }
    }
    /// `Wᵀ V` (pairing of a wrench with a twist).
    pub fn dot(&self, o: &Self) -> R {
        self.w.dot(&o.w).add(&self.v.dot(&o.v))
    }
    /// `ad_V X = (ω × ω_x, ω × v_x + v × ω_x)` (Lynch & Park, *Modern Robotics*).
    pub fn ad(&self, x: &Self) -> Self {
        Tw {
            w: self.w.cross(&x.w),
            v: self.w.cross(&x.v).add(&self.v.cross(&x.w)),
        }
    }
    /// `ad_Vᵀ W = (−ω × m − v × f, −ω × f)`.
    pub fn ad_transpose(&self, wr: &Self) -> Self {
        Tw {
            w: self.w.cross(&wr.w).add(&self.v.cross(&wr.v)).neg(),
            v: self.w.cross(&wr.v).neg(),
        }
    }
    /// The six entries, angular first.
    pub fn entries(&self) -> [R; 6] {
        [
            self.w.0[0].clone(),
            self.w.0[1].clone(),
            self.w.0[2].clone(),
            self.v.0[0].clone(),
            self.v.0[1].clone(),
            self.v.0[2].clone(),
        ]
    }
}

/// A spatial inertia by its ten parameters about the body-frame origin — `m`, the first moment
/// `h = m c` and the rotational inertia `I_o = I_c + m (cᵀc 1 − c cᵀ)` (the parallel-axis
/// theorem) — so that `𝔍 = [I_o [h]; −[h] m·1]` is linear in them.
#[derive(Clone, Debug)]
pub struct Inertia<R> {
    /// Mass.
    pub m: R,
    /// First moment `m c`.
    pub h: V3<R>,
    /// Rotational inertia about the frame origin.
    pub io: M3<R>,
}

impl<R: Ring> Inertia<R> {
    /// From mass, centre of mass and rotational inertia about the centre of mass.
    pub fn from_com(m: R, c: &V3<R>, ic: &M3<R>) -> Self {
        let h = c.times(&m);
        let cc = c.dot(c);
        let io = M3([0, 1, 2].map(|i| {
            [0, 1, 2].map(|j| {
                let outer = c.0[i].mul(&c.0[j]);
                let pa = if i == j { cc.sub(&outer) } else { outer.neg() };
                ic.0[i][j].add(&pa.mul(&m))
            })
        }));
        Inertia { m, h, io }
    }
    /// `𝔍 V = (I_o ω + h × v, m v − h × ω)`.
    pub fn apply(&self, x: &Tw<R>) -> Tw<R> {
        Tw {
            w: self.io.mul_v(&x.w).add(&self.h.cross(&x.v)),
            v: x.v.times(&self.m).sub(&self.h.cross(&x.w)),
        }
    }
}
