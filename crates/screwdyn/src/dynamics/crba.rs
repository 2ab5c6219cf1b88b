//! The joint-space mass matrix by the composite-rigid-body algorithm (O(n²) on a tree), and its
//! inverse.

use super::cholesky::{cholesky_in_place, cholesky_solve_in_place, singular_error};
use crate::error::Result;
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::Real;
use crate::workspace::Workspace;
use nalgebra::DMatrix;

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
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
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
    if !model.is_chain {
        mm.as_mut_slice().fill(T::zero());
    }
    for i in 0..n {
        let f = ci[i].apply(&s[i]);
        mm[(i, i)] = s[i].dot(&f);
        let mut k = i;
        while let Some(p) = parents[k] {
            k = p;
            let mij = s[k].dot(&f);
            mm[(k, i)] = mij;
            mm[(i, k)] = mij;
        }
    }
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
    ws.cholesky.copy_from(&ws.mass_matrix);
    cholesky_in_place(&mut ws.cholesky).map_err(|j| singular_error(model, j))?;
    ws.mass_matrix_inverse.fill(T::zero());
    ws.mass_matrix_inverse.fill_diagonal(T::one());
    for c in 0..model.nv() {
        cholesky_solve_in_place(&ws.cholesky, ws.mass_matrix_inverse.column_mut(c));
    }
    Ok(&ws.mass_matrix_inverse)
}
