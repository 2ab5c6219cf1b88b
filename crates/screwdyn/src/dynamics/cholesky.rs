//! Cholesky factorisation `M = L Lᵀ` of the symmetric positive-definite mass matrix, in place
//! and allocation-free, and the two triangular solves: forward dynamics by CRBA and Walker–Orin
//! and `M⁻¹`.

use crate::error::Error;
use crate::model::Model;
use crate::scalar::Real;
use nalgebra::DMatrix;

/// The smallest pivot (a Cholesky diagonal, an articulated inertia `D_i`) taken as positive,
/// for entries of size `scale`: 64 ulp of it. Below it the mass matrix counts as singular.
#[inline]
pub(crate) fn singular_threshold<T: Real>(scale: T) -> T {
    scale * T::default_epsilon() * crate::scalar::real(64.0)
}

/// In-place Cholesky factorisation `M = L Lᵀ` of the symmetric matrix in `a` (lower triangle
/// overwritten with `L`). `Err(pivot index)` when `M` is not positive definite.
pub(crate) fn cholesky_in_place<T: Real>(a: &mut DMatrix<T>) -> std::result::Result<(), usize> {
    let n = a.nrows();
    let scale = (0..n).fold(T::zero(), |s, i| s.max(a[(i, i)].abs()));
    let tiny = singular_threshold(scale);
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
