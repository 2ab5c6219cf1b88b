//! The library's errors as Python exceptions, and the panic guard.

use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use screwdyn::Error;

pyo3::create_exception!(
    _screwdyn,
    ModelError,
    PyValueError,
    "A robot description that cannot be loaded (syntax, unknown keys, bad tree, bad inertia); \
     the message names the file and, where known, the line. A subclass of ValueError."
);

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ModelError", m.py().get_type::<ModelError>())?;
    Ok(())
}

/// An error of an algorithm call: bad shapes or values are `ValueError`s with the library's
/// sentence.
pub fn call_err(e: Error) -> PyErr {
    match e {
        Error::Io(msg) => PyOSError::new_err(msg),
        other => PyValueError::new_err(other.to_string()),
    }
}

/// An error while loading a description: `FileNotFoundError` for a missing file,
/// `ModelError` for a broken description.
pub fn load_err(e: Error, path: Option<&str>) -> PyErr {
    match e {
        Error::Io(msg) => match path {
            Some(p) if !std::path::Path::new(p).exists() => PyFileNotFoundError::new_err(msg),
            _ => PyOSError::new_err(msg),
        },
        Error::UnknownName { .. } => ModelError::new_err(e.to_string()),
        other => ModelError::new_err(other.to_string()),
    }
}

/// Prefixes an error of state `k` of a batch.
pub fn in_state(e: Error, k: Option<usize>) -> PyErr {
    match k {
        Some(k) => PyValueError::new_err(format!("state {k}: {e}")),
        None => call_err(e),
    }
}

/// Runs `f`, turning a Rust panic into a `RuntimeError` naming it as an internal error.
pub fn guard<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            let what = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown panic".into());
            Err(PyRuntimeError::new_err(format!(
                "internal error in screwdyn (a Rust panic, please report it): {what}"
            )))
        }
    }
}
