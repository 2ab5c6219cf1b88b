//! The joint-space mass matrix by the composite-rigid-body algorithm (O(n²) on a tree), and its
//! inverse.

use super::cholesky::{singular_error, with_small_size};
use crate::error::Result;
use crate::kinematics::forward_kinematics;
use crate::model::{Model, Spine};
use crate::scalar::Real;
use crate::spatial::fused::{cross, dot6};
use crate::spatial::{ang, lin, twist, CompositeInertia, Twist, Wrench};
use crate::workspace::Workspace;
use nalgebra::DMatrix;
use nalgebra::Vector3;

/// The mass matrix `M(q)` by the composite-rigid-body algorithm, everything in the base frame
/// {0} (Featherstone's composite inertias, summed where no change of frame is needed):
///
/// 1. forward kinematics `H_i^0 = (R_i, p_i)`, then body by body the joint's screw
///    `s_i = Ad_{H_i^0} S_i` (a space-Jacobian column) and the body's inertia in {0} by its ten
///    parameters: `c_i⁰ = R_i c_i + p_i`, `h = m_i c_i⁰`,
///    `I_o = R_i I_{c,i} R_iᵀ + m_i(|c_i⁰|² 1 − c_i⁰ c_i⁰ᵀ)` (about the origin of {0}; with
///    no products of inertia, `I_{c,i} = a·1 + Σ_k μ_k e_k e_kᵀ` and `R_i I_{c,i} R_iᵀ =
///    a·1 + Σ_k μ_k r_k r_kᵀ`, `r_k` the columns of `R_i`: one term for two equal moments);
/// 2. from the leaves: `𝔍ᶜ_i = 𝔍_i^0 + Σ_children 𝔍ᶜ_c` (ten additions per child),
///    `F_i = 𝔍ᶜ_i s_i = (I_o ω + h × v, m v − h × ω)` for `s_i = (ω, v)`,
///    `M_ii = s_iᵀ F_i + I_a,i` and `M_ki = M_ik = s_kᵀ F_i` for every ancestor `k` of `i`
///    (entries of bodies on different branches are zero). On a serial chain (`λ(i) = i − 1`)
///    the body's inertia from step 1 is added to its child's composite while that is still in
///    registers; the ancestors are then the one run `0..i`.
///    The same on a chain with leaf bodies (fingers, tool bodies: the Panda), where
///    `𝔍ᶜ_i = 𝔍_i^0 + 𝔍ᶜ_{i+1} + Σ_leaves 𝔍_l^0`: each leaf's column is formed when its
///    parent is reached, and its inertia added to the parent's composite in registers.
///
/// Equal to Lynch & Park's `M = Sᵀ Lᵀ 𝔍 L S` (*Modern Robotics*) and to `Σ_i J_iᵀ 𝔍^{i,i} J_i`.
/// Each joint's armature `I_a,i` (the rotor inertia reflected to it,
/// [`Joint::armature`](crate::model::Joint::armature)) is added to its diagonal entry only.
/// Returns `ws.mass_matrix` (both triangles filled); also writes `ws.pose_in_parent`,
/// `ws.pose_in_world`, `ws.screw_in_world` (and `ws.screw_in_world_by_coordinate`) and
/// `ws.composite_inertia` (`𝔍ᶜ_i` in {0}).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::crba, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let mm = crba(&m, &mut ws, &[0.0, 0.0]).unwrap();
/// // By hand: D11 = 5, D12 = 2, D22 = 1 at θ2 = 0 (all masses and lengths 1).
/// assert!((mm[(0, 0)] - 5.0).abs() < 1e-12 && (mm[(0, 1)] - 2.0).abs() < 1e-12);
/// let mm = crba(&m, &mut ws, &[0.0, std::f64::consts::FRAC_PI_2]).unwrap();
/// // D11 = 3, D12 = 1 at θ2 = 90°.
/// assert!((mm[(0, 0)] - 3.0).abs() < 1e-12 && (mm[(1, 0)] - 1.0).abs() < 1e-12);
/// ```
pub fn crba<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    forward_kinematics(model, ws, q)?;
    ws.ensure_square()?;
    crba_given_poses(model, ws);
    Ok(&ws.mass_matrix)
}

/// Alias of [`crba`]: the joint-space mass matrix `M(q)`.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
pub fn mass_matrix<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    crba(model, ws, q)
}

/// Steps 1 and 2 of [`crba`] on the world poses of the last forward kinematics
/// (`ws.pose_in_world`), into `ws.mass_matrix` (square, checked by the callers); also used by
/// forward dynamics by CRBA.
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
pub(crate) fn crba_given_poses<T: Real>(model: &Model<T>, ws: &mut Workspace<T>) {
    let n = model.nbodies();
    if n == 0 {
        return;
    }
    let (motions, parents, bodies, joints) = (
        &model.motions()[..n],
        &model.parents()[..n],
        &model.bodies()[..n],
        &model.joints()[..n],
    );
    let forms = &model.body_inertia_form[..n];
    let Workspace {
        pose_in_world,
        screw_in_world,
        screw_in_world_by_coordinate,
        composite_inertia,
        mass_matrix,
        ..
    } = ws;
    let poses = &pose_in_world[..n];
    let screws = &mut screw_in_world[..n];
    let by_coordinate = &mut screw_in_world_by_coordinate[..6 * n];
    let composites = &mut composite_inertia[..n];
    // A chain, or a small chain with leaf bodies, carries its composite in registers; other
    // trees sum the bodies' inertias stored here (large chains with leaves too: one variant of
    // the pass fewer to compile, which kept the whole pass inlined in its CPU-specific clone).
    let side_by_side = n >= LONG_RUN;
    let spine = model
        .spine
        .as_ref()
        .filter(|s| !side_by_side || s.leaves.is_empty());
    let tree = spine.is_none();
    // 1. s_i = Ad_{H_i^0} S_i and 𝔍_i^0 (a tree's 𝔍ᶜ_i starts from it), body by body (on a large
    // model the screws are also stored coordinate by coordinate).
    for i in 0..n {
        let s = motions[i].act(&poses[i]);
        screws[i] = s;
        if side_by_side {
            for r in 0..6 {
                by_coordinate[r * n + i] = s[r];
            }
        }
        composites[i] =
            CompositeInertia::rigid_in_world_with_form(&bodies[i].inertia, &forms[i], &poses[i]);
    }
    // Bodies on different branches do not couple: those entries stay zero (on a chain every
    // entry is written below, on a chain with leaves the leaves' rows and columns are zeroed
    // when they are reached).
    let data = &mut mass_matrix.as_mut_slice()[..n * n];
    if tree {
        data.fill(T::zero());
    }
    // 2. Compiled apart for small models, whose runs of ancestors are all short (the vector
    // loops' setup would otherwise be paid for every joint), and for chains, whose composite
    // is carried from child to parent in registers.
    let screws = &*screws;
    let pass = Columns {
        parents,
        run_start: &model.run_start[..n],
        joints,
        screws,
        by_coordinate,
    };
    match spine {
        None if side_by_side => pass.tree::<true>(composites, data),
        None => pass.tree::<false>(composites, data),
        Some(spine) if side_by_side => {
            pass.chain_with_leaves::<true, false>(spine, composites, data)
        }
        Some(spine) if spine.leaves.is_empty() => {
            pass.chain_with_leaves::<false, false>(spine, composites, data)
        }
        Some(spine) => pass.chain_with_leaves::<false, true>(spine, composites, data),
    }
    if side_by_side {
        mirror_columns(data, n);
    }
}

/// What step 2 of [`crba`] reads.
struct Columns<'a, T: Real> {
    parents: &'a [Option<usize>],
    run_start: &'a [usize],
    joints: &'a [crate::model::Joint<T>],
    screws: &'a [Twist<T>],
    by_coordinate: &'a [T],
}

impl<T: Real> Columns<'_, T> {
    /// `F_i = 𝔍ᶜ_i s_i`, then `M_ii = s_iᵀ F_i + I_a,i` into `column` (column `i` of `M`).
    #[inline(always)]
    fn diagonal(&self, i: usize, composite: &CompositeInertia<T>, column: &mut [T]) -> Wrench<T> {
        let f = composite_times_screw(composite, &self.screws[i]);
        column[i] = dot6(&self.screws[i], &f) + self.joints[i].armature;
        f
    }

    /// Column `i` of `M` (column-major `data`) for every body of a tree, from the leaves: its
    /// upper part (entry `(k, i)` is `data[i n + k]`, every ancestor `k < i`, walked one
    /// unbranched run at a time) and, without `SIDE_BY_SIDE`, row `i` left of the diagonal
    /// (entry `(i, k)` is `data[k n + i]`). `composites` hold each body's own inertia and are
    /// summed into the parents on the way.
    #[inline(always)]
    fn tree<const SIDE_BY_SIDE: bool>(
        &self,
        composites: &mut [CompositeInertia<T>],
        data: &mut [T],
    ) {
        let n = self.screws.len();
        let parents = self.parents;
        for i in (0..n).rev() {
            // 𝔍ᶜ_i = 𝔍_i^0 + Σ_children 𝔍ᶜ_c: the children's were added when they were done.
            let composite = composites[i];
            let (left, right) = data.split_at_mut(i * n);
            let column = &mut right[..n];
            let f = self.diagonal(i, &composite, column);
            // M_ki = M_ik = s_kᵀ F_i for the ancestors k, one unbranched run of them at a time.
            let mut next = parents[i];
            while let Some(end) = next {
                let start = self.run_start[end];
                self.ancestors::<SIDE_BY_SIDE>(i, start, end + 1, column, left, &f);
                next = parents[start];
            }
            // 𝔍ᶜ_{λ(i)} += 𝔍ᶜ_i
            if let Some(p) = parents[i] {
                composites[p].add(&composite);
            }
        }
    }

    /// Columns of `M` for a chain with leaf bodies ([`Spine`]; a chain has no leaves), entries
    /// as in [`Self::tree`], from the chain's end: `𝔍ᶜ_i = 𝔍_i^0 + 𝔍ᶜ_{i+1} + Σ_leaves 𝔍_l^0`,
    /// each body's inertia moved to {0} here and the child's and leaves' added in registers;
    /// the ancestors of spine body `i` are the run `start..i`, those of a leaf on it
    /// `start..=i`. The leaves on the base come last (no ancestors).
    #[inline(always)]
    fn chain_with_leaves<const SIDE_BY_SIDE: bool, const LEAVES: bool>(
        &self,
        spine: &Spine,
        composites: &mut [CompositeInertia<T>],
        data: &mut [T],
    ) {
        let n = self.screws.len();
        // (A chain: the whole model, `0..n`.)
        let (start, end) = if LEAVES {
            (spine.start, spine.end)
        } else {
            (0, n)
        };
        // A leaf couples with its ancestors only: zero its column and its row in the spine's
        // columns after its parent.
        for leaf in spine.leaves.iter().filter(|_| LEAVES) {
            let l = leaf.body;
            let after_parent = leaf.parent.map_or(start, |p| p + 1);
            for later in data[after_parent * n..end * n].chunks_exact_mut(n) {
                later[l] = T::zero();
            }
            data[l * n..(l + 1) * n].fill(T::zero());
        }
        let mut leaves = spine.leaves.iter().peekable();
        // 𝔍ᶜ_{i+1}, carried to its parent.
        let mut child = CompositeInertia::zero();
        for i in (start..end).rev() {
            // 𝔍ᶜ_i = 𝔍_i^0 (step 1) + 𝔍ᶜ_{i+1}.
            let mut composite = composites[i];
            composite.add(&child);
            // The leaves on body i: their columns, and their inertias into 𝔍ᶜ_i.
            while let Some(leaf) = leaves.next_if(|l| LEAVES && l.parent == Some(i)) {
                let c = self.leaf::<SIDE_BY_SIDE>(leaf.body, start..i + 1, composites, data);
                composite.add(&c);
            }
            composites[i] = composite;
            child = composite;
            let (left, right) = data.split_at_mut(i * n);
            let column = &mut right[..n];
            let f = self.diagonal(i, &composite, column);
            if i > start {
                self.ancestors::<SIDE_BY_SIDE>(i, start, i, column, left, &f);
            }
        }
        for leaf in leaves.filter(|_| LEAVES) {
            self.leaf::<SIDE_BY_SIDE>(leaf.body, start..start, composites, data);
        }
    }

    /// Column `l` of `M` for a leaf body whose ancestors are the run `ancestors`: its inertia
    /// `𝔍ᶜ_l = 𝔍_l^0` moved to {0} (in `composites` from step 1; returned), `M_ll` and
    /// `M_kl = M_lk` for the ancestors (the other entries were zeroed before).
    #[inline(always)]
    fn leaf<const SIDE_BY_SIDE: bool>(
        &self,
        l: usize,
        ancestors: std::ops::Range<usize>,
        composites: &mut [CompositeInertia<T>],
        data: &mut [T],
    ) -> CompositeInertia<T> {
        let n = self.screws.len();
        let composite = composites[l];
        let (left, right) = data.split_at_mut(l * n);
        let column = &mut right[..n];
        let f = self.diagonal(l, &composite, column);
        self.ancestors::<SIDE_BY_SIDE>(l, ancestors.start, ancestors.end, column, left, &f);
        composite
    }

    /// `M_ki = s_kᵀ F_i` for the run of ancestors `start ≤ k < end` of joint `i`, into
    /// `column` (column `i`) and, without `SIDE_BY_SIDE`, into row `i` of the columns before
    /// (`left`, entry `(i, k)` at `left[k n + i]`).
    #[inline(always)]
    fn ancestors<const SIDE_BY_SIDE: bool>(
        &self,
        i: usize,
        start: usize,
        end: usize,
        column: &mut [T],
        left: &mut [T],
        f: &Wrench<T>,
    ) {
        let n = self.screws.len();
        if SIDE_BY_SIDE {
            let run = &mut column[start..end];
            if run.len() >= LONG_RUN {
                screw_products(run, self.by_coordinate, n, start, f);
            } else {
                for (m, s) in run.iter_mut().zip(&self.screws[start..end]) {
                    *m = dot6(s, f);
                }
            }
        } else {
            // (An exclusive range: `start..=end` iterated costs twice the instructions.)
            for k in start..end {
                let x = dot6(&self.screws[k], f);
                column[k] = x;
                left[k * n + i] = x;
            }
        }
    }
}

/// Copies the strict upper triangle of the column-major `n × n` matrix `data` onto its lower
/// triangle, walking the later columns in order (no index arithmetic per entry): column `c`
/// below the diagonal gets entry `c` of every later column.
#[inline(always)]
fn mirror_columns<T: Real>(data: &mut [T], n: usize) {
    for c in 0..n {
        let (head, tail) = data.split_at_mut((c + 1) * n);
        let below = &mut head[c * n + c + 1..];
        for (x, later) in below.iter_mut().zip(tail.chunks_exact(n)) {
            *x = later[c];
        }
    }
}

/// The shortest run of consecutive ancestors whose products `s_kᵀ F` [`crba`] forms side by
/// side from the screws stored coordinate by coordinate, and the smallest model whose pass is
/// compiled for that. Forming every run side by side cost the arms (at most 9 bodies, runs
/// shorter than 9) about 30 % more instructions, the vector loops' setup being paid for every
/// joint; on the 200-joint chain it cuts the instructions 2.9× (BENCHMARKS.md). Chosen between
/// the two, not tuned.
const LONG_RUN: usize = 16;

/// `out[j] = s_kᵀ f` for the consecutive joints `k = start + j`, the screws read coordinate by
/// coordinate (`by_coordinate[r n + k]`), so that several `k` are formed side by side.
#[inline(always)]
fn screw_products<T: Real>(
    out: &mut [T],
    by_coordinate: &[T],
    n: usize,
    start: usize,
    f: &Wrench<T>,
) {
    let len = out.len();
    let lane = |r: usize| &by_coordinate[r * n + start..r * n + start + len];
    let (s0, s1, s2, s3, s4, s5) = (lane(0), lane(1), lane(2), lane(3), lane(4), lane(5));
    for (j, o) in out.iter_mut().enumerate() {
        let p0 = s1[j].mul_add(f[1], s0[j] * f[0]);
        let p1 = s3[j].mul_add(f[3], s2[j] * f[2]);
        let p2 = s5[j].mul_add(f[5], s4[j] * f[4]);
        *o = (p0 + p1) + p2;
    }
}

// Products that are added are fused (`mul_add`: one instruction where the CPU has FMA, which the
// multiversioned clones above are compiled for, and never less accurate than two roundings).

/// `F = 𝔍 s = (I_o ω + h × v, m v − h × ω)` for a screw `s = (ω, v)` and an inertia given by its
/// ten parameters `(m, h, I_o)`, fused.
#[inline(always)]
fn composite_times_screw<T: Real>(c: &CompositeInertia<T>, s: &Twist<T>) -> Wrench<T> {
    let (io, h, m) = (&c.inertia_origin, &c.first_moment, c.mass);
    let (w, v) = (ang(s), lin(s));
    let h_x_v = cross(h, &v);
    let h_x_w = cross(h, &w);
    let l = Vector3::from_fn(|r, _| {
        io[(r, 2)].mul_add(
            w.z,
            io[(r, 1)].mul_add(w.y, io[(r, 0)].mul_add(w.x, h_x_v[r])),
        )
    });
    let f = Vector3::from_fn(|r, _| v[r].mul_add(m, -h_x_w[r]));
    twist(l, f)
}

/// `M(q)⁻¹` by CRBA and a Cholesky factorisation. Returns `ws.mass_matrix_inverse`;
/// `Error::Numerical` when `M` is singular (e.g. a massless chain).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞. [`Error::Numerical`](crate::Error::Numerical) when `M` is singular, naming the joint.
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
/// contiguous columns (column-major storage), compiled for the size at hand
/// ([`with_small_size`]).
pub(crate) fn invert_mass_matrix<T: Real>(model: &Model<T>, ws: &mut Workspace<T>) -> Result<()> {
    let n = model.nv();
    ws.cholesky.copy_from(&ws.mass_matrix);
    let a = &mut ws.cholesky.as_mut_slice()[..n * n];
    let minv = &mut ws.mass_matrix_inverse.as_mut_slice()[..n * n];
    match with_small_size!(n, |m| invert_columns(a, minv, m)) {
        Ok(()) => Ok(()),
        Err(j) => Err(singular_error(model, j)),
    }
}

/// [`invert_mass_matrix`] on the column-major `n × n` slices `a` (`M` in, `L` out in the lower
/// triangle) and `minv`; `Err(j)` when the pivot of column `j` is not positive.
#[inline(always)]
fn invert_columns<T: Real>(
    a: &mut [T],
    minv: &mut [T],
    n: usize,
) -> std::result::Result<(), usize> {
    let (a, minv) = (&mut a[..n * n], &mut minv[..n * n]);
    let scale = (0..n).fold(T::zero(), |s, i| s.max(a[i * n + i].abs()));
    let tiny = super::cholesky::singular_threshold(scale);
    // Right-looking Cholesky: column j of L, then update the trailing lower triangle.
    for j in 0..n {
        let d = a[j * n + j];
        if d.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err(j);
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
    // L⁻¹ (lower triangular), column c solving L x = e_c, last column first: (L⁻¹)_kk = 1/L_kk
    // is then already in place for every k > c, so each column takes one division.
    for c in (0..n).rev() {
        let (head, done) = minv.split_at_mut((c + 1) * n);
        let out = &mut head[c * n..];
        out.fill(T::zero());
        let inv_c = T::one() / a[c * n + c];
        out[c] = inv_c;
        // x_c = 1/L_cc, then x_k = (e_c − Σ_{r<k} L_kr x_r)_k / L_kk for k > c.
        for (o, l) in out[c + 1..].iter_mut().zip(&a[c * n + c + 1..(c + 1) * n]) {
            *o -= inv_c * *l;
        }
        for k in c + 1..n {
            let xk = out[k] * done[(k - c - 1) * n + k];
            out[k] = xk;
            let col = &a[k * n..(k + 1) * n];
            for (o, l) in out[k + 1..].iter_mut().zip(&col[k + 1..]) {
                *o -= xk * *l;
            }
        }
    }
    // M⁻¹_ij = Σ_{k ≥ max(i, j)} L⁻¹_ki L⁻¹_kj: dots of columns of L⁻¹. The strict upper
    // triangle of L⁻¹ is zero, so it takes M⁻¹_ij (i < j) first; then the diagonal; then the
    // lower triangle is mirrored over L⁻¹ (`cholesky` keeps L).
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
    mirror_upper_triangle(minv, n);
    Ok(())
}

/// Copies the strict upper triangle of the column-major `n × n` matrix `data` onto its lower
/// triangle: `A_rc = A_cr` for `r > c` (entry `(r, c)` is `data[c n + r]`).
#[inline(always)]
fn mirror_upper_triangle<T: Real>(data: &mut [T], n: usize) {
    for c in 0..n {
        for r in c + 1..n {
            data[c * n + r] = data[r * n + c];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{JointSpec, ModelBuilder};
    use crate::spatial::{Se3, SpatialInertia};
    use nalgebra::{Matrix3, Vector6};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// A chain `l0 … l{len−1}` with leaf bodies (`leaves[j]`: the chain link the j-th leaf
    /// hangs on, `None` the base; leaves on the base declared before the chain), random
    /// revolute or prismatic axes, home poses, inertias and armatures.
    fn chain_with_leaves(rng: &mut StdRng, len: usize, leaves: &[Option<usize>]) -> Model {
        let mut b = ModelBuilder::new("leaves");
        let mut link = |b: &mut ModelBuilder, name: String, parent: String| {
            let axis =
                Vector3::new(rng.gen_range(-1.0..1.0), 0.5, rng.gen_range(-1.0..1.0)).normalize();
            let (screw, spec) = if rng.gen_bool(0.2) {
                let s = Vector6::new(0.0, 0.0, 0.0, axis.x, axis.y, axis.z);
                (s, JointSpec::prismatic(&format!("j{name}")))
            } else {
                let v = Vector3::new(0.1, -0.2, 0.05).cross(&axis);
                let s = Vector6::new(axis.x, axis.y, axis.z, v.x, v.y, v.z);
                (s, JointSpec::revolute(&format!("j{name}")))
            };
            let home = Se3::from_rpy(rng.gen(), rng.gen(), rng.gen())
                .with_translation(Vector3::new(rng.gen(), rng.gen(), rng.gen()));
            let inertia = SpatialInertia::new(
                rng.gen_range(0.5..2.0),
                Vector3::new(rng.gen(), rng.gen(), rng.gen()) * 0.2,
                Matrix3::new(0.3, 0.01, 0.02, 0.01, 0.2, 0.03, 0.02, 0.03, 0.25),
            );
            let spec = spec.screw_in_child(screw).armature(rng.gen_range(0.0..0.1));
            b.link(&name, &parent, spec, home, inertia);
        };
        let on = |p: &Option<usize>| p.map_or("base".to_string(), |p| format!("l{p}"));
        for (j, p) in leaves.iter().enumerate().filter(|(_, p)| p.is_none()) {
            link(&mut b, format!("leaf{j}"), on(p));
        }
        for i in 0..len {
            link(&mut b, format!("l{i}"), on(&i.checked_sub(1)));
        }
        for (j, p) in leaves.iter().enumerate().filter(|(_, p)| p.is_some()) {
            link(&mut b, format!("leaf{j}"), on(p));
        }
        b.build().unwrap()
    }

    /// The pass for chains with leaves against the general tree pass (the same model with no
    /// spine): the same `M` and composite inertias up to rounding, from a workspace whose `M`
    /// held NaN.
    #[test]
    fn chain_with_leaves_equals_the_tree_pass() {
        let mut rng = StdRng::seed_from_u64(4);
        let shapes: [(usize, Vec<Option<usize>>); 4] = [
            (7, vec![Some(6), Some(6)]),
            (5, vec![None, Some(2), Some(2), Some(2), Some(4), None]),
            (2, vec![Some(0), None]),
            (12, vec![Some(11), Some(8), Some(8), None]),
        ];
        for (len, leaves) in &shapes {
            let model = chain_with_leaves(&mut rng, *len, leaves);
            let spine = model.spine.as_ref().expect("a chain with leaves");
            assert!(!spine.leaves.is_empty() && !model.is_chain);
            let mut tree = model.clone();
            tree.spine = None;
            let (mut ws, mut ws_tree) = (Workspace::new(&model), Workspace::new(&tree));
            for _ in 0..3 {
                let q: Vec<f64> = (0..model.nq()).map(|_| rng.gen_range(-3.0..3.0)).collect();
                // Every entry is written (the zeros too), whatever the matrix held before.
                ws.mass_matrix.fill(f64::NAN);
                let m = crba(&model, &mut ws, &q).unwrap().clone();
                let m_tree = crba(&tree, &mut ws_tree, &q).unwrap();
                let scale = m_tree.amax();
                assert!((&m - m_tree).amax() < 1e-13 * scale, "{m}\n{m_tree}");
                for (a, b) in ws.composite_inertia.iter().zip(&ws_tree.composite_inertia) {
                    assert!((a.matrix() - b.matrix()).amax() < 1e-12 * b.matrix().amax());
                }
            }
        }
    }
}
