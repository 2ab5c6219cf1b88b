//! One state, the call a Python loop makes (`model.rnea(q, v, a)` per time step), without the
//! bookkeeping of the general path (`compute` and `batch`): the joint vectors are already read
//! (on the stack up to [`INLINE`](crate::convert::INLINE) joints, [`StateIn::Inline`]), the
//! model's cached workspace is taken with one `try_lock`, and the kernel writes straight into
//! the one fresh NumPy array it returns. Nothing else is allocated.
//!
//! Anything this path does not take — stacked states, lists or other dtypes, a vector of the
//! wrong length, `out=`, `threads=0`, external wrenches — makes [`PyModel::single_state`] return
//! `None`, and the method goes on with the general path, whose checks and messages stay the one
//! source of errors. Both paths call the same library function on the same values, so they give
//! the same bits.

use crate::batch::Scratch;
use crate::convert::{all_finite, StateIn};
use crate::errors::{call_err, guard};
use crate::model::PyModel;
use numpy::{PyArray1, PyArray2, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;
use screwdyn::Model;

/// The most joints this path takes (the length of `ZEROS`).
const MAX_JOINTS: usize = 64;

/// The value of a joint vector left out (`v=None`): zero.
const ZEROS: [f64; MAX_JOINTS] = [0.0; MAX_JOINTS];

/// Whether a call's `threads` and `out` arguments allow the one-state path: no `out=` (the
/// general path checks and borrows it) and no `threads=0` (refused there with its message).
#[inline]
pub(crate) fn plain(threads: Option<usize>, out: Option<&Bound<'_, PyAny>>) -> bool {
    out.is_none() && threads != Some(0)
}

impl PyModel {
    /// `kernel(model, scratch, [q, v, …], out)` at the one state `joints` give (`None`: a
    /// vector left out, zero), into a fresh float64 array of `shape` (one or two dimensions),
    /// the result checked as the library's rule says (a NaN or ∞ computed from finite inputs
    /// is an overflow error, never returned). `None` when the arguments are not one
    /// float64 vector each of the model's length: the caller then takes the general path.
    pub(crate) fn single_state<'py, const K: usize>(
        &self,
        py: Python<'py>,
        joints: [Option<&StateIn<'py>>; K],
        shape: [usize; 2],
        kernel: impl FnOnce(&Model, &mut Scratch, [&[f64]; K], &mut [f64]) -> screwdyn::Result<()>,
    ) -> Option<PyResult<Bound<'py, PyAny>>> {
        let nq = self.model.nq();
        if nq > MAX_JOINTS {
            return None;
        }
        let mut rows: [&[f64]; K] = [&ZEROS[..nq]; K];
        for (row, joint) in rows.iter_mut().zip(joints) {
            if let Some(j) = joint {
                match j.vector() {
                    Some(x) if x.len() == nq => *row = x,
                    _ => return None,
                }
            }
        }
        Some(guard(|| {
            // A `(1, n)` shape stands for the vector `(n,)`.
            // SAFETY (both): a fresh, C-contiguous array of float64, not yet seen by any other
            // code, its values set to zero before the slice over them is made; the slice does
            // not outlive this block.
            let array = match shape {
                [1, n] => unsafe { PyArray1::<f64>::new(py, n, false) }.into_any(),
                [r, c] => unsafe { PyArray2::<f64>::new(py, [r, c], false) }.into_any(),
            };
            let out = unsafe {
                let a = array.cast_unchecked::<PyArrayDyn<f64>>();
                std::ptr::write_bytes(a.data(), 0, shape[0] * shape[1]);
                a.as_slice_mut()
            }
            .expect("a fresh array is contiguous");
            let run = |s: &mut Scratch| {
                kernel(&self.model, s, rows, out)?;
                if all_finite(out) {
                    return Ok(());
                }
                screwdyn::check_result(out, |i| format!("(entry {i})"))
            };
            match self.scratch.try_lock() {
                Ok(mut cached) => run(cached.get_or_insert_with(|| Scratch::new(&self.model))),
                // Another thread holds the cached workspace: a fresh one for this call.
                Err(_) => run(&mut Scratch::new(&self.model)),
            }
            .map_err(call_err)?;
            Ok(array)
        }))
    }
}
