//! Python bindings of the `screwdyn` library (the package `screwdyn`, native module
//! `screwdyn._screwdyn`). Bindings only: every quantity is computed by the library; this crate
//! parses NumPy arrays, checks their shapes, runs batches over rayon with the GIL released and
//! turns the library's errors (and any panic) into Python exceptions.
//!
//! # Where things are
//!
//! The files mirror the library's topics. `model` holds the class `Model` (`PyModel`): loading,
//! properties, pickling. Its methods are in `configuration`, `kinematics`, `dynamics`, `energy`, `worked` (the
//! closed form, Lagrangian coefficients and RNEA trace), `derivatives`, `identification`,
//! `simulation` and `view`; `trajectory` holds the class `Trajectory`, `symbolic` the entry of
//! `screwdyn.symbolic`. The infrastructure: `convert` (NumPy in and out), `batch` (one state
//! or `N` over rayon's threads), `compute` (the body every computing method shares: guard,
//! argument conversion, single-or-batch dispatch, run), `args` (frames, links, joints, wrenches,
//! reference frames by their Python forms) and `errors`.
//!
//! # How methods reach `Model`
//!
//! One way only: each topic file has its own `#[pymethods] impl PyModel` block (PyO3's
//! `multiple-pymethods` feature), so every method of `Model` — the Pinocchio-style aliases
//! `inverse_dynamics` and `mass_matrix` included, as methods sharing their docstring with
//! `rnea` and `crba` — is a native method with its signature and docstring next to its code.
//! The Python package adds nothing to `Model`: it holds only what is Python by nature (the
//! result classes of `_results.py` and `_view.py` these methods return, the controller and
//! disturbance classes, `screwdyn.dask`, `screwdyn.symbolic` and the `screwdyn.rnea(model, …)`
//! functions).

mod args;
mod batch;
mod compute;
mod configuration;
mod convert;
mod derivatives;
mod dynamics;
mod energy;
mod errors;
mod identification;
mod ik;
mod kinematics;
mod model;
mod se3;
mod simulation;
mod single;
mod symbolic;
mod trajectory;
mod view;
mod worked;

use pyo3::prelude::*;

/// Raises a Rust panic inside the panic guard, so the tests can check that a panic becomes a
/// Python `RuntimeError` and never crosses into Python as a `PanicException`.
#[pyfunction]
#[pyo3(signature = (message = "deliberate panic for the test suite"))]
fn _panic_for_tests(message: &str) -> PyResult<()> {
    errors::guard(|| -> PyResult<()> { panic!("{message}") })
}

/// Same as [`_panic_for_tests`], but the panic happens in a rayon worker thread with the GIL
/// released, as it would inside a batch.
#[pyfunction]
fn _panic_in_batch_for_tests(py: Python<'_>) -> PyResult<()> {
    use rayon::prelude::*;
    errors::guard(|| {
        py.detach(|| {
            (0..64usize).into_par_iter().for_each(|i| {
                if i == 63 {
                    panic!("deliberate panic in a worker thread");
                }
            })
        });
        Ok(())
    })
}

/// The native module; `screwdyn/__init__.py` re-exports it with the Python-side helpers.
#[pymodule]
fn _screwdyn(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    model::register(m)?;
    m.add_class::<trajectory::PyTrajectory>()?;
    symbolic::register(m)?;
    view::register(m)?;
    se3::register(m)?;
    m.add_function(wrap_pyfunction!(_panic_for_tests, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_in_batch_for_tests, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
