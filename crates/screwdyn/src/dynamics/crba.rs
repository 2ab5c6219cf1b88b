//! The joint-space mass matrix by the composite-rigid-body algorithm (O(n²) on a tree), and its
//! inverse.

use super::cholesky::{singular_error, with_small_size};
use crate::error::Result;
use crate::kinematics::{forward_kinematics, poses_in_parent};
use crate::model::{JointMotion, Model};
use crate::scalar::Real;
use crate::spatial::{CompositeInertia, Se3, Wrench};
use crate::workspace::Workspace;
use nalgebra::DMatrix;
use nalgebra::Vector3;

/// The mass matrix `M(q)` by the composite-rigid-body algorithm: composite inertias
/// `𝔍ᶜ_i = 𝔍_i + Σ_children 𝔍ᶜ_c` (backward), then `M_ij = S_iᵀ 𝔍ᶜ_j S_j` for every `i`
/// supporting `j`, walking up the tree. Equal to the `M = Sᵀ Lᵀ 𝔍 L S` (Lynch & Park, *Modern
/// Robotics*) and to the `Σ_i J_iᵀ 𝔍^{i,i} J_i`. Each joint's armature `I_a,i` (the rotor inertia
/// reflected to it, [`Joint::armature`](crate::model::Joint::armature)) is added to its diagonal
/// entry: `M_ii = S_iᵀ 𝔍ᶜ_i S_i + I_a,i`. Returns `ws.mass_matrix` (both triangles filled).
///
/// Two equivalent forms, chosen by the size of the model:
/// [`crba_local`] (every quantity in its own body frame, no forward kinematics) for models of at
/// most [`CRBA_LOCAL_MAX_BODIES`] bodies, [`crba_in_base_frame`] (everything in {0}) beyond, where
/// its six-term dot products beat the changes of frame of the local form (one per body and
/// ancestor: `n(n−1)/2` on a chain). Which
/// workspace entries each one writes besides `ws.mass_matrix` is listed on each; use
/// [`forward_kinematics`] for world poses.
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
/// ```
pub fn crba<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    if model.nbodies() <= CRBA_LOCAL_MAX_BODIES {
        crba_local(model, ws, q)
    } else {
        crba_in_base_frame(model, ws, q)
    }
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

/// The largest model (in bodies) for which [`crba`] uses the local form [`crba_local`]; larger
/// models use [`crba_in_base_frame`]. Chosen by instruction counts (callgrind, per call, AVX2
/// build): UR5 (6 bodies, a chain) 3876 local against 4224 in {0}; Panda (9 bodies, a chain of
/// 7 and two fingers) about 7250 local against 6510 in {0}. Fitted, the local form costs about
/// 420 instructions a body (`sin_cos`, the composite's change of frame) plus 100 for each
/// (body, ancestor) pair (a wrench's change of frame), the base frame 670 a body (forward
/// kinematics, the change of frame to {0}, the screw in {0}) plus 14 a pair (a six-term dot
/// product): the local form wins while the pairs are fewer than about 2.9 per body, i.e. on
/// every tree of up to 6 bodies and on no chain longer than 6.
pub const CRBA_LOCAL_MAX_BODIES: usize = 6;

/// [`crba`] with everything in the base frame {0}: `𝔍ᶜ_i` is summed from the bodies' inertias
/// `Ad_{H_0^i}ᵀ 𝔍^{i,i} Ad_{H_0^i}`, and `S_i` is the space-Jacobian column
/// `Ad_{H_i^0} S_i^{i,λ(i)}`, so each off-diagonal entry is a single 6-vector dot product (no
/// per-ancestor change of frame). Runs [`forward_kinematics`] first, so it also fills
/// `ws.pose_in_parent` and `ws.pose_in_world`, and fills `ws.screw_in_world`.
///
/// # Errors
/// As [`crba`].
///
/// ```
/// use screwdyn::{builtin, dynamics::{crba_in_base_frame, crba_local}, Workspace};
/// let m = builtin::load("ur5").unwrap();
/// let mut ws = Workspace::new(&m);
/// let q = [0.1, -0.7, 1.2, 0.3, -0.4, 0.9];
/// let base = crba_in_base_frame(&m, &mut ws, &q).unwrap().clone();
/// assert!((base - crba_local(&m, &mut ws, &q).unwrap()).amax() < 1e-12);
/// ```
pub fn crba_in_base_frame<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    forward_kinematics(model, ws, q)?;
    ws.ensure_square()?;
    crba_given_poses(model, ws);
    Ok(&ws.mass_matrix)
}

/// [`crba`] with every quantity in its own body frame (Featherstone's composite-rigid-body
/// algorithm in local coordinates): no forward kinematics, only each joint's pose in its parent
/// `H_i^{λ(i)}(q_i)`. Backward, from the leaves: `𝔍ᶜ_i` (in frame {i}) is whole once its
/// children are added; the column `F = 𝔍ᶜ_i S_i` gives `M_ii = S_iᵀ F + I_a,i`; carried up the
/// ancestors as a wrench, `F ← Ad_{H_k^{λ(k)}}⁻ᵀ F` (frame {k} to {λ(k)}), each gives
/// `M_{λ(k) i} = S_{λ(k)}ᵀ F`; then `𝔍ᶜ_{λ(i)} += Ad_{H_{λ(i)}^i}ᵀ 𝔍ᶜ_i Ad_{H_{λ(i)}^i}`.
/// Writes `ws.pose_in_parent` and `ws.composite_inertia` (each in its own body frame); leaves
/// `ws.pose_in_world` as it was.
///
/// # Errors
/// As [`crba`].
///
/// ```
/// use screwdyn::{builtin, dynamics::crba_local, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let mm = crba_local(&m, &mut ws, &[0.0, std::f64::consts::FRAC_PI_2]).unwrap();
/// // By hand: D11 = 3, D12 = 1, D22 = 1 at θ2 = 90° (all masses and lengths 1).
/// assert!((mm[(0, 0)] - 3.0).abs() < 1e-12 && (mm[(1, 0)] - 1.0).abs() < 1e-12);
/// ```
pub fn crba_local<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DMatrix<T>> {
    // H_i^{λ(i)} = H_i^{λ(i)}(0) e^{[S_i] q_i} (checks `ws` and `q`).
    poses_in_parent(model, ws, q)?;
    ws.ensure_square()?;
    local_given_poses(model, ws);
    Ok(&ws.mass_matrix)
}

/// `𝔍 S` for a joint's screw axis `S`, reading the axis joints' columns out of the ten
/// parameters: `𝔍 (ê_k, 0) = (I_o ê_k, ê_k × h)` and `𝔍 (0, ê_k) = (h × ê_k, m ê_k)`.
#[inline(always)]
fn inertia_times_axis<T: Real>(c: &CompositeInertia<T>, motion: &JointMotion<T>) -> Wrench<T> {
    let (io, h, z) = (&c.inertia_origin, &c.first_moment, T::zero());
    match *motion {
        JointMotion::RevoluteAxis { axis, sign } => {
            let l = match axis {
                0 => [z, -h.z, h.y],
                1 => [h.z, z, -h.x],
                _ => [-h.y, h.x, z],
            };
            Wrench::new(
                io[(0, axis)] * sign,
                io[(1, axis)] * sign,
                io[(2, axis)] * sign,
                l[0] * sign,
                l[1] * sign,
                l[2] * sign,
            )
        }
        JointMotion::PrismaticAxis { axis, sign } => {
            let a = match axis {
                0 => [z, h.z, -h.y],
                1 => [-h.z, z, h.x],
                _ => [h.y, -h.x, z],
            };
            let mut w = Wrench::new(a[0] * sign, a[1] * sign, a[2] * sign, z, z, z);
            w[3 + axis] = c.mass * sign;
            w
        }
        _ => c.apply(&motion.screw()),
    }
}

/// `(c, s)` of the turn `R = Rot_K(θ)` about the coordinate axis `K` whose plane is `(I, J)`:
/// `R ê_I = c ê_I + s ê_J`.
#[inline(always)]
fn cos_sin<T: Real, const I: usize, const J: usize>(r: &nalgebra::Matrix3<T>) -> (T, T) {
    (r[(I, I)], r[(J, I)])
}

/// `v ↦ Rot_K(θ) v` in the plane `(I, J)`.
#[inline(always)]
fn turn<T: Real, const I: usize, const J: usize>(v: &mut [T; 6], c: T, s: T) {
    for half in [0, 3] {
        let (a, b) = (v[half + I], v[half + J]);
        v[half + I] = c * a - s * b;
        v[half + J] = s * a + c * b;
    }
}

/// A wrench `W = (m, f)` in frame {i} written in the parent's frame, `Ad_{H_i^λ}⁻ᵀ W =
/// (R m + p × R f, R f)` with `H_i^λ = (R, p)`. When the joint's home has no rotation, an axis
/// joint's `R` is a turn about a coordinate axis (revolute) or the identity (prismatic): then
/// `R` only mixes two entries of each half.
#[inline(always)]
fn wrench_to_parent<T: Real>(
    h: &Se3<T>,
    motion: &JointMotion<T>,
    unrotated: bool,
    w: &Wrench<T>,
) -> Wrench<T> {
    if unrotated {
        let mut v = [w[0], w[1], w[2], w[3], w[4], w[5]];
        let r = &h.rotation;
        let turned = match *motion {
            JointMotion::RevoluteAxis { axis: 0, .. } => {
                let (c, s) = cos_sin::<T, 1, 2>(r);
                turn::<T, 1, 2>(&mut v, c, s);
                true
            }
            JointMotion::RevoluteAxis { axis: 1, .. } => {
                let (c, s) = cos_sin::<T, 2, 0>(r);
                turn::<T, 2, 0>(&mut v, c, s);
                true
            }
            JointMotion::RevoluteAxis { .. } => {
                let (c, s) = cos_sin::<T, 0, 1>(r);
                turn::<T, 0, 1>(&mut v, c, s);
                true
            }
            JointMotion::PrismaticAxis { .. } => true,
            _ => false,
        };
        if turned {
            // m' = R m + p × f'
            let p = &h.translation;
            let f = Vector3::new(v[3], v[4], v[5]);
            let pf = p.cross(&f);
            return Wrench::new(v[0] + pf.x, v[1] + pf.y, v[2] + pf.z, f.x, f.y, f.z);
        }
    }
    h.inv_act_transpose_wrench(w)
}

/// A composite inertia in frame {i} written in the parent's frame (`h = H_i^λ`), by the turn
/// about a coordinate axis and the shift when the joint's home has no rotation (see
/// [`wrench_to_parent`]), else by the general change of frame.
#[inline(always)]
fn composite_to_parent<T: Real>(
    c: &CompositeInertia<T>,
    h: &Se3<T>,
    motion: &JointMotion<T>,
    unrotated: bool,
) -> CompositeInertia<T> {
    if unrotated {
        let r = &h.rotation;
        let turned = match *motion {
            JointMotion::RevoluteAxis { axis: 0, .. } => {
                let (cos, sin) = cos_sin::<T, 1, 2>(r);
                Some(c.turned::<1, 2, 0>(cos, sin))
            }
            JointMotion::RevoluteAxis { axis: 1, .. } => {
                let (cos, sin) = cos_sin::<T, 2, 0>(r);
                Some(c.turned::<2, 0, 1>(cos, sin))
            }
            JointMotion::RevoluteAxis { .. } => {
                let (cos, sin) = cos_sin::<T, 0, 1>(r);
                Some(c.turned::<0, 1, 2>(cos, sin))
            }
            JointMotion::PrismaticAxis { .. } => Some(*c),
            _ => None,
        };
        if let Some(t) = turned {
            return t.shifted(&h.translation);
        }
    }
    c.transformed(h)
}

fn local_given_poses<T: Real>(model: &Model<T>, ws: &mut Workspace<T>) {
    let n = model.nbodies();
    let (joints, motions, parents, bodies) = (
        &model.joints()[..n],
        &model.motions()[..n],
        &model.parents()[..n],
        &model.body_composite[..n],
    );
    let unrotated = &model.home_unrotated[..n];
    let (pip, ci) = (&ws.pose_in_parent[..n], &mut ws.composite_inertia[..n]);
    // 𝔍ᶜ_i starts as body i's own inertia.
    ci.copy_from_slice(bodies);
    let data = &mut ws.mass_matrix.as_mut_slice()[..n * n];
    if !model.is_chain {
        // Bodies on different branches do not couple.
        data.fill(T::zero());
    }
    // Column i of the upper triangle (entry (k, i) is data[i n + k], every ancestor k < i),
    // from the leaves, then the lower triangle mirrored.
    for i in (0..n).rev() {
        let column = &mut data[i * n..(i + 1) * n];
        // F = 𝔍ᶜ_i S_i; M_ii = S_iᵀ F + I_a,i
        let mut f = inertia_times_axis(&ci[i], &motions[i]);
        column[i] = motions[i].dot(&f) + joints[i].armature;
        let mut k = i;
        while let Some(p) = parents[k] {
            // F in {λ(k)} = Ad_{H_k^{λ(k)}}⁻ᵀ F = (R m + p × R f, R f); M_{λ(k) i} = S_{λ(k)}ᵀ F
            f = wrench_to_parent(&pip[k], &motions[k], unrotated[k], &f);
            k = p;
            column[k] = motions[k].dot(&f);
        }
        // 𝔍ᶜ_{λ(i)} += 𝔍ᶜ_i written in {λ(i)}: Ad_{H_{λ(i)}^i}ᵀ 𝔍ᶜ_i Ad_{H_{λ(i)}^i}
        if let Some(p) = parents[i] {
            let c = composite_to_parent(&ci[i], &pip[i], &motions[i], unrotated[i]);
            ci[p].add(&c);
        }
    }
    mirror_upper_triangle(data, n);
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
    let data = ws.mass_matrix.as_mut_slice();
    if n == 0 {
        return;
    }
    if !model.is_chain {
        data.fill(T::zero());
    }
    // Column i of the upper triangle through one slice (column-major storage: entry (k, i) is
    // data[i n + k], with every ancestor k < i), then the lower triangle mirrored.
    // M_ii = S_iᵀ 𝔍ᶜ_i S_i + I_a,i, M_ki = S_kᵀ 𝔍ᶜ_i S_i for k supporting i.
    let joints = model.joints();
    for (i, column) in data.chunks_exact_mut(n).enumerate() {
        let f = ci[i].apply(&s[i]);
        column[i] = s[i].dot(&f) + joints[i].armature;
        let mut k = i;
        while let Some(p) = parents[k] {
            k = p;
            column[k] = s[k].dot(&f);
        }
    }
    mirror_upper_triangle(data, n);
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
