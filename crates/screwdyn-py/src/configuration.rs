//! `Model`'s configurations to start from (the library's `model::configuration`): the neutral
//! configuration and random configurations within the limits.

use crate::convert::{self, ArrayIn};
use crate::errors::call_err;
use crate::model::PyModel;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyInt;
use screwdyn::model::SplitMix64;

#[pymethods]
impl PyModel {
    /// The neutral configuration, `(nq,)`: zero for every joint, or the point of the joint's
    /// range nearest zero when zero is outside its limits (a joint limited to `[0.5, 2]` gives
    /// `0.5`). Pinocchio's `neutral(model)`.
    fn neutral<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::vector(py, &self.model.neutral())
    }

    /// The finite ranges random configurations are drawn from, `(nq, 2)` rows `[lo, hi]`: the
    /// joint limits, an infinite bound replaced by `∓π` (revolute, continuous, helical) or
    /// `∓1 m` (prismatic); a finite bound beyond that default gets the default width beyond it
    /// (a lower limit of 5 rad and no upper one gives `[5, 5 + 2π]`).
    #[getter]
    fn configuration_ranges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let flat: Vec<f64> = self
            .model
            .configuration_ranges()
            .iter()
            .flat_map(|&(lo, hi)| [lo, hi])
            .collect();
        convert::frozen(convert::array(py, flat, &[self.model.nq(), 2])?)
    }

    /// A random configuration, uniform over :attr:`configuration_ranges` (within the limits):
    /// `(nq,)`, or `(n, nq)` for `n` of them. `rng` is a `numpy.random.Generator` (its
    /// `random` draws the uniform numbers), an int seed (screwdyn's own SplitMix64 generator:
    /// the same configurations for the same seed on every machine), or None (a fresh
    /// `numpy.random.default_rng()`). Pinocchio's `randomConfiguration(model)`.
    #[pyo3(signature = (rng = None, n = None))]
    fn random_configuration<'py>(
        &self,
        py: Python<'py>,
        rng: Option<&Bound<'py, PyAny>>,
        n: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nq = self.model.nq();
        let count = match n {
            None => None,
            Some(n) => Some(count(n)?),
        };
        let rows = count.unwrap_or(1);
        // A NumPy generator's uniform numbers mapped onto the ranges, or screwdyn's own from a seed.
        let from_numpy = |generator: Bound<'py, PyAny>| -> PyResult<Vec<f64>> {
            let u: ArrayIn<'_> = generator.call_method1("random", ((rows, nq),))?.extract()?;
            let u = convert::contiguous(&u);
            self.model.configurations_at(&u).map_err(call_err)
        };
        let flat = match rng {
            None => from_numpy(py.import("numpy.random")?.call_method0("default_rng")?)?,
            Some(g) if g.hasattr("random")? => from_numpy(g.clone())?,
            Some(seed) => {
                let mut g = SplitMix64::new(seed_of(seed)?);
                self.model.random_configurations(&mut g, rows)
            }
        };
        match count {
            None => convert::array(py, flat, &[nq]),
            Some(n) => convert::array(py, flat, &[n, nq]),
        }
    }
}

/// An integer argument (Python's `int` or NumPy's, anything with `__index__`), or None when
/// `x` is not one.
fn index<'py>(x: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
    if x.is_instance_of::<PyInt>() {
        return Ok(Some(x.clone()));
    }
    if x.hasattr("__index__")? && !x.is_instance_of::<pyo3::types::PyFloat>() {
        return Ok(Some(x.call_method0("__index__")?));
    }
    Ok(None)
}

/// The seed of `random_configuration`'s `rng` when it is an integer.
fn seed_of(x: &Bound<'_, PyAny>) -> PyResult<u64> {
    let Some(i) = index(x)? else {
        return Err(PyTypeError::new_err(format!(
            "rng is a numpy.random.Generator, an int seed or None, got {}",
            x.get_type().name()?
        )));
    };
    i.extract::<u64>().map_err(|_| {
        PyValueError::new_err(format!(
            "rng as a seed is an integer in [0, 2**64), got {i}"
        ))
    })
}

/// The `n` of `random_configuration`: a non-negative int.
fn count(n: &Bound<'_, PyAny>) -> PyResult<usize> {
    let Some(i) = index(n)? else {
        return Err(PyTypeError::new_err(format!(
            "n is the number of configurations (an int) or None, got {}",
            n.get_type().name()?
        )));
    };
    i.extract::<usize>().map_err(|_| {
        PyValueError::new_err(format!(
            "n is the number of configurations, at least 0, got {i}"
        ))
    })
}
