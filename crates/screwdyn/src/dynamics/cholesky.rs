//! Cholesky factorisation `M = L Lᵀ` of the symmetric positive-definite mass matrix, in place
//! and allocation-free, and the two triangular solves: forward dynamics by CRBA and Walker–Orin
//! and `M⁻¹`.

use crate::error::Error;
use crate::model::Model;
use crate::scalar::Real;
use nalgebra::DMatrix;

/// Evaluates `$body` with `$n` bound to a compile-time constant when the size `$size` is that of
/// a common arm (1 to 12 joints), and to the run-time size otherwise. The kernels it calls are
/// `#[inline(always)]`, so each arm is compiled with its size known: the short loops over
/// `n ≤ 12` entries are unrolled and vectorised instead of running as scalar remainder loops.
macro_rules! with_small_size {
    ($size:expr, |$n:ident| $body:expr) => {
        match $size {
            1 => {
                let $n = 1;
                $body
            }
            2 => {
                let $n = 2;
                $body
            }
            3 => {
                let $n = 3;
                $body
            }
            4 => {
                let $n = 4;
                $body
            }
            5 => {
                let $n = 5;
                $body
            }
            6 => {
                let $n = 6;
                $body
            }
            7 => {
                let $n = 7;
                $body
            }
            8 => {
                let $n = 8;
                $body
            }
            9 => {
                let $n = 9;
                $body
            }
            10 => {
                let $n = 10;
                $body
            }
            11 => {
                let $n = 11;
                $body
            }
            12 => {
                let $n = 12;
                $body
            }
            other => {
                let $n = other;
                $body
            }
        }
    };
}
pub(crate) use with_small_size;

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
