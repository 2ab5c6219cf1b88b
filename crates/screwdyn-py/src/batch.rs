//! Running a library call over one state or `N` stacked states: the GIL is released and the
//! states are spread over rayon's threads, each with its own [`Workspace`] and
//! [`BatchWorkspace`]. Per-state calls go through [`run`]; the library's batch functions
//! ([`screwdyn::batch`]: RNEA, CRBA, ABA eight states at a time) through [`run_lanes`].
//! Results go to a fresh array, or to the caller's `out=` array ([`Batch`]).

use crate::convert::{batch_len, States};
use crate::errors::call_err;
use nalgebra::Matrix6xX;
use numpy::ndarray::IxDyn;
use numpy::{PyArrayDyn, PyArrayMethods, PyReadwriteArrayDyn};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyFloat;
use rayon::prelude::*;
use screwdyn::batch::{BatchWorkspace, Rows as LaneRows};
use screwdyn::{Model, Workspace};
use std::sync::Mutex;

/// Per-thread buffers: the library's workspaces and a Jacobian.
pub struct Scratch {
    pub ws: Workspace,
    pub batch: BatchWorkspace,
    pub jac: Matrix6xX<f64>,
}

impl Scratch {
    pub fn new(model: &Model) -> Self {
        Scratch {
            ws: Workspace::new(model),
            batch: BatchWorkspace::new(model),
            jac: Matrix6xX::zeros(model.nq()),
        }
    }
}

/// How a call runs: on `threads` threads (`None`: rayon's pool over all cores; `1`: the
/// calling thread), into `out` (a float64 array of the result's shape, NumPy's `out=`
/// convention) or, when `None`, into a fresh array.
#[derive(Clone, Copy)]
pub struct Batch<'a, 'py> {
    pub threads: Option<usize>,
    pub out: Option<&'a Bound<'py, PyAny>>,
}

impl Batch<'_, '_> {
    /// On `threads` threads, into a fresh array.
    pub fn threads(threads: Option<usize>) -> Self {
        Batch { threads, out: None }
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
/// arguments are broadcast against stacked ones. Batches run with the GIL released, as `how`
/// says ([`Batch`]).
pub fn run<'py, F>(
    py: Python<'py>,
    model: &Model,
    cache: &Mutex<Option<Scratch>>,
    args: &[&States<'_>],
    out_shape: &[usize],
    how: Batch<'_, 'py>,
    kernel: F,
) -> PyResult<Bound<'py, PyAny>>
where
    F: Fn(&Model, &mut Scratch, &Rows<'_>, &mut [f64]) -> screwdyn::Result<()> + Sync,
{
    assert!(args.len() <= 4, "a kernel takes at most four arguments");
    let width: usize = out_shape.iter().product();
    let rows = |k: usize| {
        let mut r: Rows<'_> = [&[]; 4];
        for (j, a) in args.iter().enumerate() {
            r[j] = a.row(k);
        }
        r
    };
    run_chunks(
        py,
        model,
        cache,
        args,
        out_shape,
        how,
        |m, s, first, block| {
            for (j, o) in block.chunks_mut(width).enumerate() {
                kernel(m, s, &rows(first + j), o).map_err(|e| e.in_state(first + j))?;
            }
            Ok(())
        },
    )
}

/// Stacked states through the library batch function `f(model, batch_workspace, inputs, out)`
/// (one of [`screwdyn::batch`]'s: eight states side by side), a single state through the
/// per-call `one` (as [`run`]), shaped as [`run`] does. Each thread's share of the states is
/// one call of `f`, and every state of a batch gets the same bits however the batch is split
/// (threads, chunks, Dask partitions); a single state agrees with its row of a batch to
/// round-off.
#[allow(clippy::too_many_arguments)]
pub fn run_lanes<'py, F, G>(
    py: Python<'py>,
    model: &Model,
    cache: &Mutex<Option<Scratch>>,
    args: &[&States<'_>],
    out_shape: &[usize],
    how: Batch<'_, 'py>,
    f: F,
    one: G,
) -> PyResult<Bound<'py, PyAny>>
where
    F: Fn(&Model, &mut BatchWorkspace, &[LaneRows<'_>], &mut [f64]) -> screwdyn::Result<()> + Sync,
    G: Fn(&Model, &mut Scratch, &Rows<'_>, &mut [f64]) -> screwdyn::Result<()> + Sync,
{
    assert!(
        args.len() <= 3,
        "a batch function takes at most three joint vectors"
    );
    if batch_len(args)?.is_none() {
        return run(py, model, cache, args, out_shape, how, one);
    }
    let width: usize = out_shape.iter().product();
    run_chunks(
        py,
        model,
        cache,
        args,
        out_shape,
        how,
        |m, s, first, block| {
            let states = block.len().checked_div(width).unwrap_or(0);
            let mut inputs = [LaneRows::Same(&[]); 3];
            for (input, a) in inputs.iter_mut().zip(args) {
                *input = match a.n {
                    Some(_) => {
                        LaneRows::Stacked(&a.data[first * a.width..(first + states) * a.width])
                    }
                    None => LaneRows::Same(&a.data),
                };
            }
            f(m, &mut s.batch, &inputs[..args.len()], block).map_err(|e| e.offset_state(first))
        },
    )
}

/// The frame of [`run`] and [`run_lanes`]: takes the result array (fresh, or `how.out` once
/// its type, shape and layout are checked), releases the GIL and calls
/// `chunk(model, scratch, first_state, out_block)` on consecutive blocks of states (all of them
/// at once on one thread, [`CHUNK`] at a time over rayon's threads). Errors name the state.
fn run_chunks<'py, F>(
    py: Python<'py>,
    model: &Model,
    cache: &Mutex<Option<Scratch>>,
    args: &[&States<'_>],
    out_shape: &[usize],
    how: Batch<'_, 'py>,
    chunk: F,
) -> PyResult<Bound<'py, PyAny>>
where
    F: Fn(&Model, &mut Scratch, usize, &mut [f64]) -> screwdyn::Result<()> + Sync,
{
    let threads = check_threads(how.threads)?;
    let width: usize = out_shape.iter().product();
    // Every block of results is checked as the library's rule says: a NaN or ∞ computed from
    // finite inputs is an overflow error naming the state and the entry, never returned.
    let chunk = |m: &Model, s: &mut Scratch, first: usize, block: &mut [f64]| {
        chunk(m, s, first, block)?;
        if crate::convert::all_finite(block) {
            return Ok(());
        }
        let mut row = 0;
        screwdyn::check_result(block, |i| {
            row = i / width.max(1);
            format!("(entry {})", i % width.max(1))
        })
        .map_err(|e| e.in_state(first + row))
    };
    let n = batch_len(args)?;
    if n.is_none() && out_shape.is_empty() && how.out.is_none() {
        // One state, a scalar result: a Python float.
        let mut out = [0.0];
        single(model, cache, &mut out, &chunk)?;
        return Ok(PyFloat::new(py, out[0]).into_any());
    }
    let mut shape: Vec<usize> = n.into_iter().collect();
    shape.extend_from_slice(out_shape);
    let mut target = Target::new(py, how.out, &shape)?;
    let out = target.slice();
    let Some(n) = n else {
        single(model, cache, out, &chunk)?;
        return Ok(target.into_result());
    };
    let result = py.detach(|| -> screwdyn::Result<()> {
        if width == 0 || n == 0 {
            return Ok(());
        }
        let sequential = threads == Some(1) || n <= CHUNK;
        if sequential {
            let mut s = Scratch::new(model);
            return chunk(model, &mut s, 0, out);
        }
        let work = |out: &mut [f64]| {
            out.par_chunks_mut(CHUNK * width)
                .enumerate()
                .try_for_each_init(
                    || Scratch::new(model),
                    |s, (c, block)| chunk(model, s, c * CHUNK, block),
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
    result.map_err(call_err)?;
    Ok(target.into_result())
}

/// Where a call writes its result: a fresh array, or the caller's `out=` array, borrowed for
/// writing (rust-numpy's borrow check refuses an `out` that shares memory with an input).
enum Target<'py> {
    Fresh(Bound<'py, PyArrayDyn<f64>>),
    Given(Bound<'py, PyAny>, PyReadwriteArrayDyn<'py, f64>),
}

impl<'py> Target<'py> {
    fn new(py: Python<'py>, out: Option<&Bound<'py, PyAny>>, shape: &[usize]) -> PyResult<Self> {
        Ok(match out {
            // The result is written straight into a fresh NumPy array (no copy, no reshape).
            None => Target::Fresh(PyArrayDyn::<f64>::zeros(py, IxDyn(shape), false)),
            Some(o) => Target::Given(o.clone(), crate::convert::out_array(o, shape)?),
        })
    }

    /// The array's values, row-major.
    fn slice(&mut self) -> &mut [f64] {
        match self {
            // SAFETY: the array was just created, is C-contiguous and nothing else refers to
            // it yet.
            Target::Fresh(a) => unsafe { a.as_slice_mut() }.expect("a fresh array is contiguous"),
            Target::Given(_, a) => a
                .as_slice_mut()
                .expect("out_array checked that out is C-contiguous"),
        }
    }

    /// What the call returns: the array (`out` itself when given, as NumPy's functions do).
    fn into_result(self) -> Bound<'py, PyAny> {
        match self {
            Target::Fresh(a) => a.into_any(),
            Target::Given(o, _) => o,
        }
    }
}

/// One state: reuses the model's cached workspaces (no allocation), or fresh ones if another
/// thread holds them.
fn single<F>(
    model: &Model,
    cache: &Mutex<Option<Scratch>>,
    out: &mut [f64],
    chunk: &F,
) -> PyResult<()>
where
    F: Fn(&Model, &mut Scratch, usize, &mut [f64]) -> screwdyn::Result<()> + Sync,
{
    let r = match cache.try_lock() {
        Ok(mut guard) => {
            let s = guard.get_or_insert_with(|| Scratch::new(model));
            chunk(model, s, 0, out)
        }
        Err(_) => chunk(model, &mut Scratch::new(model), 0, out),
    };
    // A single state's error is not prefixed with a state number.
    r.map_err(|e| call_err(e.without_state()))
}
