//! Running a per-state library call over one state or `N` stacked states: the GIL is released
//! and the states are spread over rayon's threads, each with its own [`Workspace`].

use crate::convert::{batch_len, States};
use crate::errors::in_state;
use nalgebra::Matrix6xX;
use numpy::ndarray::IxDyn;
use numpy::{PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyFloat;
use rayon::prelude::*;
use screwdyn::{Model, Workspace};
use std::sync::Mutex;

/// Per-thread buffers: the library's workspace and a Jacobian.
pub struct Scratch {
    pub ws: Workspace,
    pub jac: Matrix6xX<f64>,
}

impl Scratch {
    pub fn new(model: &Model) -> Self {
        Scratch {
            ws: Workspace::new(model),
            jac: Matrix6xX::zeros(model.nq()),
        }
    }
}

/// The rows of the arguments for one state (up to four arguments).
pub type Rows<'a> = [&'a [f64]; 4];

/// States per rayon task: enough to amortise the scheduling, small enough to balance.
const CHUNK: usize = 512;

/// Checks a `threads` argument: `None` (all cores) or a positive count.
pub fn check_threads(threads: Option<usize>) -> PyResult<Option<usize>> {
    match threads {
        Some(0) => Err(PyValueError::new_err(
            "threads must be a positive number of threads or None for all cores",
        )),
        t => Ok(t),
    }
}

/// Calls `kernel(model, scratch, rows, out)` for every state of `args` and returns the results,
/// shaped `out_shape` for single arguments and `(N, *out_shape)` for stacked ones. Single
/// arguments are broadcast against stacked ones. Batches run with the GIL released, on
/// `threads` threads (`None`: rayon's pool over all cores; `1`: the calling thread).
pub fn run<'py, F>(
    py: Python<'py>,
    model: &Model,
    cache: &Mutex<Option<Scratch>>,
    args: &[&States<'_>],
    out_shape: &[usize],
    threads: Option<usize>,
    kernel: F,
) -> PyResult<Bound<'py, PyAny>>
where
    F: Fn(&Model, &mut Scratch, &Rows<'_>, &mut [f64]) -> screwdyn::Result<()> + Sync,
{
    assert!(args.len() <= 4, "a kernel takes at most four arguments");
    let threads = check_threads(threads)?;
    let width: usize = out_shape.iter().product();
    let rows = |k: usize| {
        let mut r: Rows<'_> = [&[]; 4];
        for (j, a) in args.iter().enumerate() {
            r[j] = a.row(k);
        }
        r
    };
    let n = batch_len(args)?;
    if n.is_none() && out_shape.is_empty() {
        // One state, a scalar result: a Python float.
        let mut out = [0.0];
        single(model, cache, &rows(0), &mut out, &kernel)?;
        return Ok(PyFloat::new(py, out[0]).into_any());
    }
    let mut shape: Vec<usize> = n.into_iter().collect();
    shape.extend_from_slice(out_shape);
    // The result is written straight into a fresh NumPy array (no copy, no reshape).
    let arr = PyArrayDyn::<f64>::zeros(py, IxDyn(&shape), false);
    // SAFETY: the array was just created, is C-contiguous and nothing else refers to it yet.
    let out = unsafe { arr.as_slice_mut() }.expect("a fresh array is contiguous");
    let Some(n) = n else {
        single(model, cache, &rows(0), out, &kernel)?;
        return Ok(arr.into_any());
    };
    let result = py.detach(|| -> Result<(), (usize, screwdyn::Error)> {
        if width == 0 || n == 0 {
            return Ok(());
        }
        let sequential = threads == Some(1) || n <= CHUNK;
        if sequential {
            let mut s = Scratch::new(model);
            for (k, o) in out.chunks_mut(width).enumerate() {
                kernel(model, &mut s, &rows(k), o).map_err(|e| (k, e))?;
            }
            return Ok(());
        }
        let work = |out: &mut [f64]| {
            out.par_chunks_mut(CHUNK * width)
                .enumerate()
                .try_for_each_init(
                    || Scratch::new(model),
                    |s, (c, block)| {
                        for (j, o) in block.chunks_mut(width).enumerate() {
                            let k = c * CHUNK + j;
                            kernel(model, s, &rows(k), o).map_err(|e| (k, e))?;
                        }
                        Ok(())
                    },
                )
        };
        match threads {
            Some(t) if t != rayon::current_num_threads() => {
                match rayon::ThreadPoolBuilder::new().num_threads(t).build() {
                    Ok(pool) => pool.install(|| work(out)),
                    Err(_) => work(out),
                }
            }
            _ => work(out),
        }
    });
    result.map_err(|(k, e)| in_state(e, Some(k)))?;
    Ok(arr.into_any())
}

/// One state: reuses the model's cached workspace (no allocation), or a fresh one if another
/// thread holds it.
fn single<F>(
    model: &Model,
    cache: &Mutex<Option<Scratch>>,
    rows: &Rows<'_>,
    out: &mut [f64],
    kernel: &F,
) -> PyResult<()>
where
    F: Fn(&Model, &mut Scratch, &Rows<'_>, &mut [f64]) -> screwdyn::Result<()> + Sync,
{
    let r = match cache.try_lock() {
        Ok(mut guard) => {
            let s = guard.get_or_insert_with(|| Scratch::new(model));
            kernel(model, s, rows, out)
        }
        Err(_) => kernel(model, &mut Scratch::new(model), rows, out),
    };
    r.map_err(|e| in_state(e, None))
}
