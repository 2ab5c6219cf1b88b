//! The library's errors as Python exceptions, and the panic guard.

use pyo3::exceptions::{
    PyFileExistsError, PyFileNotFoundError, PyOSError, PyPermissionError, PyRuntimeError,
    PyValueError,
};
use pyo3::prelude::*;
use screwdyn::Error;
use std::io::ErrorKind;

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

/// The `OSError` subclass Python's own file functions raise for an I/O error of `kind`.
fn os_error(kind: ErrorKind, message: String) -> PyErr {
    match kind {
        ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        ErrorKind::PermissionDenied => PyPermissionError::new_err(message),
        ErrorKind::AlreadyExists => PyFileExistsError::new_err(message),
        _ => PyOSError::new_err(message),
    }
}

/// An error of an algorithm call: bad shapes or values (also a batch state's, `state k: …`) are
/// `ValueError`s with the library's sentence; I/O errors are `OSError`s chosen by their kind.
pub fn call_err(e: Error) -> PyErr {
    match e {
        Error::Io { kind, message, .. } => os_error(kind, message),
        other => PyValueError::new_err(other.to_string()),
    }
}

/// An error while loading a description: `FileNotFoundError` for a missing file (any
/// `OSError` by the I/O error's kind), `ModelError` for a broken description.
pub fn load_err(e: Error) -> PyErr {
    match e {
        Error::Io { kind, message, .. } => os_error(kind, message),
        other => ModelError::new_err(other.to_string()),
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
