//! The joint-space mass matrix by the composite-rigid-body algorithm (O(n²) on a tree), and its
//! inverse.

use crate::error::{Error, Result};
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::{hat, Se3, SpatialInertia, Twist, Wrench};
use crate::workspace::Workspace;
use nalgebra::{DMatrix, Matrix3, Vector3, Vector6};

/// A spatial inertia stored by the parameters it is linear in — mass `m`, first moment `h = m c`
/// and rotational inertia `I_o` about the frame origin — so that the inertias of several bodies
/// add exactly (composite bodies of the CRBA). `𝔍 = [I_o [h]; [h]ᵀ m·1]`.
///
/// ```
/// use nalgebra::{Matrix3, Vector3};
/// use screwdyn::{dynamics::CompositeInertia, spatial::{Se3, SpatialInertia}};
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

/// The mass matrix `M(q)` by the composite-rigid-body algorithm: composite inertias
/// `𝔍ᶜ_i = 𝔍_i + Σ_children 𝔍ᶜ_c` (backward), then `M_ij = S_iᵀ 𝔍ᶜ_j S_j` for every `i`
/// supporting `j`, walking up the tree. Equal to the seeds' `M = Sᵀ Lᵀ 𝔍 L S` (seed 000) and to
/// seed 001's `Σ_i J_iᵀ 𝔍^{i,i} J_i`.
///
/// Everything is written in the base frame {0}: `𝔍ᶜ_i` is summed from the bodies' inertias
/// `Ad_{H_0^i}ᵀ 𝔍^{i,i} Ad_{H_0^i}`, and `S_i` is the space-Jacobian column
/// `Ad_{H_i^0} S_i^{i,λ(i)}`, so each off-diagonal entry is a single 6-vector dot product (no
/// per-ancestor change of frame). Also fills `ws.screw_in_world`.
/// Returns `ws.mass_matrix` (both triangles filled).
///
/// ```
/// use screwdyn::{builtin, dynamics::crba, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let mm = crba(&m, &mut ws, &[0.0, 0.0]).unwrap();
/// // Seed 004: D11 = 5, D12 = 2, D22 = 1 at θ2 = 0 (all masses and lengths 1).
/// assert!((mm[(0, 0)] - 5.0).abs() < 1e-12 && (mm[(0, 1)] - 2.0).abs() < 1e-12);
/// ```
pub fn crba<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    forward_kinematics(model, ws, q)?;
    crba_given_poses(model, ws);
    Ok(&ws.mass_matrix)
}

/// Alias of [`crba`]: the joint-space mass matrix `M(q)`.
pub fn mass_matrix<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    crba(model, ws, q)
}

pub(crate) fn crba_given_poses<T: Real>(model: &Model<T>, ws: &mut Workspace<T>) {
    let n = model.nbodies();
    let (motions, parents, bodies) = (model.motions(), model.parents(), &model.body_composite);
    let ci = &mut ws.composite_inertia[..n];
    let piw = &ws.pose_in_world[..n];
    for i in 0..n {
        ci[i] = bodies[i].transformed(&piw[i]);
    }
    for i in (0..n).rev() {
        if let Some(p) = parents[i] {
            let c = ci[i];
            ci[p].add(&c);
        }
    }
    let s = &mut ws.screw_in_world[..n];
    for i in 0..n {
        s[i] = motions[i].act(&piw[i]);
    }
    // Bodies on different branches do not couple: those entries stay zero (on a chain every
    // entry is written below).
    let mm = &mut ws.mass_matrix;
    assert!(
        mm.nrows() == n && mm.ncols() == n,
        "workspace made for another model"
    );
    if !model.is_chain {
        mm.as_mut_slice().fill(T::zero());
    }
    for i in 0..n {
        let f = ci[i].apply(&s[i]);
        // SAFETY: i < n and every ancestor k < i, and `mm` is n × n (asserted above).
        unsafe { *mm.get_unchecked_mut((i, i)) = s[i].dot(&f) };
        let mut k = i;
        while let Some(p) = parents[k] {
            k = p;
            debug_assert!(k < i);
            let mij = s[k].dot(&f);
            unsafe {
                *mm.get_unchecked_mut((k, i)) = mij;
                *mm.get_unchecked_mut((i, k)) = mij;
            }
        }
    }
}

/// In-place Cholesky factorisation `M = L Lᵀ` of the symmetric matrix in `a` (lower triangle
/// overwritten with `L`). `Err(pivot index)` when `M` is not positive definite.
pub(crate) fn cholesky_in_place<T: Real>(a: &mut DMatrix<T>) -> std::result::Result<(), usize> {
    let n = a.nrows();
    let scale = (0..n).fold(T::zero(), |s, i| s.max(a[(i, i)].abs()));
    let tiny = scale * T::default_epsilon() * crate::scalar::real(64.0);
    for j in 0..n {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= a[(j, k)] * a[(j, k)];
        }
        if d.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err(j);
        }
        let d = d.sqrt();
        a[(j, j)] = d;
        for i in j + 1..n {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= a[(i, k)] * a[(j, k)];
            }
            a[(i, j)] = s / d;
        }
    }
    Ok(())
}

/// Solves `L Lᵀ x = b` in place, with `L` in the lower triangle of `l`.
pub(crate) fn cholesky_solve_in_place<T: Real>(
    l: &DMatrix<T>,
    mut b: nalgebra::DVectorViewMut<'_, T>,
) {
    let n = l.nrows();
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[(i, k)] * b[k];
        }
        b[i] = s / l[(i, i)];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[(k, i)] * b[k];
        }
        b[i] = s / l[(i, i)];
    }
}

pub(crate) fn singular_error<T: Real>(model: &Model<T>, j: usize) -> Error {
    Error::Numerical(format!(
        "the mass matrix is singular or not positive definite at joint '{}' (is the chain \
         beyond it massless?)",
        model.joints()[j].name
    ))
}

/// `M(q)⁻¹` by CRBA and a Cholesky factorisation. Returns `ws.mass_matrix_inverse`;
/// `Error::Numerical` when `M` is singular (e.g. a massless chain).
///
/// ```
/// use screwdyn::{builtin, dynamics::mass_matrix_inverse, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let minv = mass_matrix_inverse(&m, &mut ws, &[0.0, 1.0]).unwrap().clone();
/// let eye = &ws.mass_matrix * minv;
/// assert!((eye - nalgebra::DMatrix::<f64>::identity(2, 2)).amax() < 1e-12);
/// ```
pub fn mass_matrix_inverse<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    crba(model, ws, q)?;
    invert_mass_matrix(model, ws)?;
    Ok(&ws.mass_matrix_inverse)
}

/// `ws.mass_matrix_inverse = ws.mass_matrix⁻¹` by a Cholesky factorisation `M = L Lᵀ` (in
/// `ws.cholesky`, lower triangle), the inverse `L⁻¹` and `M⁻¹ = L⁻ᵀ L⁻¹`, all by operations on
/// contiguous columns (column-major storage).
pub(crate) fn invert_mass_matrix<T: Real>(model: &Model<T>, ws: &mut Workspace<T>) -> Result<()> {
    let n = model.nv();
    ws.cholesky.copy_from(&ws.mass_matrix);
    let a = &mut ws.cholesky.as_mut_slice()[..n * n];
    let scale = (0..n).fold(T::zero(), |s, i| s.max(a[i * n + i].abs()));
    let tiny = scale * T::default_epsilon() * crate::scalar::real(64.0);
    // Right-looking Cholesky: column j of L, then update the trailing lower triangle.
    for j in 0..n {
        let d = a[j * n + j];
        if d.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err(singular_error(model, j));
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        let inv = T::one() / d;
        for x in &mut a[j * n + j + 1..(j + 1) * n] {
            *x *= inv;
        }
        let (head, tail) = a.split_at_mut((j + 1) * n);
        let lj = &head[j * n..(j + 1) * n];
        for (c, col) in tail.chunks_exact_mut(n).enumerate() {
            let c = c + j + 1;
            let f = lj[c];
            for (x, l) in col[c..].iter_mut().zip(&lj[c..]) {
                *x -= f * *l;
            }
        }
    }
    // L⁻¹ (lower triangular) in place of L: column c solves L x = e_c.
    for c in 0..n {
        // x_k for k < c is zero; work on column c of the result, stored in the upper part of
        // mass_matrix_inverse first.
        let out = &mut ws.mass_matrix_inverse.as_mut_slice()[c * n..(c + 1) * n];
        out.fill(T::zero());
        out[c] = T::one();
        for k in c..n {
            let col = &a[k * n..(k + 1) * n];
            let xk = out[k] / col[k];
            out[k] = xk;
            for (o, l) in out[k + 1..].iter_mut().zip(&col[k + 1..]) {
                *o -= xk * *l;
            }
        }
    }
    // M⁻¹_ij = Σ_{k ≥ max(i, j)} L⁻¹_ki L⁻¹_kj: dots of columns of L⁻¹. The strict upper
    // triangle of L⁻¹ is zero, so it takes M⁻¹_ij (i < j) first; then the diagonal; then the
    // lower triangle is mirrored over L⁻¹ (`cholesky` keeps L).
    let minv = &mut ws.mass_matrix_inverse.as_mut_slice()[..n * n];
    let dot = |m: &[T], i: usize, j: usize| {
        let mut s = T::zero();
        for (x, y) in m[i * n + j..(i + 1) * n]
            .iter()
            .zip(&m[j * n + j..(j + 1) * n])
        {
            s += *x * *y;
        }
        s
    };
    for j in 1..n {
        for i in 0..j {
            minv[j * n + i] = dot(minv, i, j);
        }
    }
    for j in 0..n {
        minv[j * n + j] = dot(minv, j, j);
    }
    for j in 0..n {
        for i in j + 1..n {
            minv[j * n + i] = minv[i * n + j];
        }
    }
    Ok(())
}
