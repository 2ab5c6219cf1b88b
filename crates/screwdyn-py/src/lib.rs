//! Python bindings of the `screwdyn` library (the package `screwdyn`, native module
//! `screwdyn._screwdyn`). Bindings only: every quantity is computed by the library; this crate
//! parses NumPy arrays, checks their shapes, runs batches over rayon with the GIL released and
//! turns the library's errors (and any panic) into Python exceptions.

mod analysis;
mod batch;
mod convert;
mod derivatives;
mod errors;
mod model;
mod sim;
mod symbolic;
mod view;

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
    m.add_class::<model::PyModel>()?;
    m.add_function(wrap_pyfunction!(model::load, m)?)?;
    m.add_function(wrap_pyfunction!(model::load_string, m)?)?;
    m.add_function(wrap_pyfunction!(model::builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(model::_unpickle_model, m)?)?;
    sim::register(m)?;
    derivatives::register(m)?;
    symbolic::register(m)?;
    view::register(m)?;
    m.add_function(wrap_pyfunction!(_panic_for_tests, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_in_batch_for_tests, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
