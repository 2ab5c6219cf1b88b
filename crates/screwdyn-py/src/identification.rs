//! `Model`'s identification (the library's `dynamics::regressor` and `identification`): the
//! regressor, the standard and base parameters, and least squares from logged samples.

use crate::batch::Batch;
use crate::compute::{arg, optional};
use crate::convert::{self, as_int, python_class, truthy, vector, StateIn};
use crate::errors::call_err;
use crate::model::PyModel;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use screwdyn::dynamics;
use screwdyn::identification::{self, BaseParameters, LeastSquares, DEFAULT_SEED, DEFAULT_STATES};

#[pymethods]
impl PyModel {
    /// The joint-torque regressor ``Y(q, q̇, q̈)``, ``(nq, 10 nq)`` (``(N, nq, 10 nq)``): the
    /// inverse dynamics (with gravity, no external wrench or friction) is linear in the standard
    /// parameters, ``rnea(q, v, a) = Y @ inertial_parameters()``. Columns ``10 k … 10 k + 9``
    /// belong to body ``k``: ``m, mx, my, mz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`` (first moment and
    /// inertia about the body frame origin, body axes; names in :meth:`parameter_names`).
    #[pyo3(signature = (q, v = None, a = None, *, threads = None))]
    fn regressor<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
        a: Option<StateIn<'py>>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let columns = dynamics::PARAMETERS_PER_BODY * self.model.nbodies();
        self.compute(py, |c| {
            c.each(
                Batch::threads(threads),
                [arg(&q, "q"), optional(&v, "v"), optional(&a, "a")],
                &[self.model.nq(), columns],
                |m, s, r, o| {
                    convert::write_rows(dynamics::regressor(m, &mut s.ws, r[0], r[1], r[2])?, o);
                    Ok(())
                },
            )
        })
    }

    /// The standard parameters ``π`` of the model, ``(10 nq,)`` in the order of the
    /// regressor's columns (then ``fv``, ``fc`` per joint: the joints' damping and Coulomb
    /// friction, when ``friction=True``).
    #[pyo3(signature = (friction = false))]
    fn inertial_parameters<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = truthy)] friction: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let pi = identification::standard_parameters(&self.model, friction);
        vector(py, pi.as_slice())
    }

    /// Names of the standard parameters: ``<parameter>_<link>`` (``m_link1``, ``Izz_link2``),
    /// then ``fv_<joint>``, ``fc_<joint>`` with ``friction``.
    #[pyo3(signature = (friction = false))]
    fn parameter_names(&self, #[pyo3(from_py_with = truthy)] friction: bool) -> Vec<String> {
        identification::parameter_names(&self.model, friction)
    }

    /// The base (identifiable) parameters, found numerically from the regressor stacked at
    /// ``states`` random states (QR with column pivoting in a fixed preferred order; the same as
    /// ``screwdyn regressor --base``): a :class:`BaseParameters` with readable expressions and
    /// ``K`` (``π_b = K π``).
    #[pyo3(signature = (friction = false, *, states = DEFAULT_STATES, seed = DEFAULT_SEED))]
    fn base_parameters<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = truthy)] friction: bool,
        #[pyo3(from_py_with = as_int)] states: usize,
        #[pyo3(from_py_with = as_int)] seed: u64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let data = self.compute(py, |_| {
            let b = py.detach(|| self.base(friction, states, seed))?;
            self.base_dict(py, &b)
        })?;
        python_class(py, "screwdyn._results", "BaseParameters")?.call1((data,))
    }

    /// Least-squares identification of the base parameters from stacked samples ``q``, ``v``,
    /// ``a``, ``tau`` of shape ``(N, nq)`` (the library's streaming QR, as ``screwdyn identify``):
    /// an :class:`Identification` with the estimates, their standard deviations, ``sigma`` and
    /// the condition number. ``friction=True`` adds ``fv q̇ + fc sign(q̇)`` per joint. Raises
    /// ValueError for too few samples or a log that does not excite every base parameter
    /// (condition number above 1e10), naming it.
    #[pyo3(signature = (q, v, a, tau, *, friction = false, states = DEFAULT_STATES, seed = DEFAULT_SEED))]
    #[allow(clippy::too_many_arguments)]
    fn identify<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        a: StateIn<'py>,
        tau: StateIn<'py>,
        #[pyo3(from_py_with = truthy)] friction: bool,
        #[pyo3(from_py_with = as_int)] states: usize,
        #[pyo3(from_py_with = as_int)] seed: u64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let data = self.compute(py, |c| {
            let m = &self.model;
            let samples = c.joints([arg(&q, "q"), arg(&v, "v"), arg(&a, "a"), arg(&tau, "tau")])?;
            let n = convert::batch_len(&samples.each_ref())?.unwrap_or(1);
            if samples.iter().any(|s| s.n.is_none()) && n > 1 {
                return Err(PyValueError::new_err(
                    "identify takes stacked samples: q, v, a and tau must all have shape (N, nq)",
                ));
            }
            let b = self.base(friction, states, seed)?;
            // Errors of a sample name it; `None` is an error of the solve.
            let result = py.detach(|| -> Result<_, (Option<usize>, screwdyn::Error)> {
                let mut ls = LeastSquares::new(m, b.clone());
                for k in 0..n {
                    let [q, v, a, tau] = samples.each_ref().map(|s| s.row(k));
                    ls.add(m, q, v, a, tau).map_err(|e| (Some(k), e))?;
                }
                ls.solve().map_err(|e| (None, e))
            });
            let est = result.map_err(|(k, e)| match k {
                Some(k) => PyValueError::new_err(format!("sample {k}: {e}")),
                None => call_err(e),
            })?;
            let d = self.base_dict(py, &b)?;
            d.set_item("values", vector(py, est.values.as_slice())?)?;
            d.set_item("std_dev", vector(py, est.std_dev.as_slice())?)?;
            d.set_item("condition_number", est.condition_number)?;
            d.set_item("sigma", est.sigma)?;
            d.set_item("samples", est.samples)?;
            Ok(d)
        })?;
        python_class(py, "screwdyn._results", "Identification")?.call1((data,))
    }
}

impl PyModel {
    /// The library's base parameters of the model, from the regressor at `states` random states.
    fn base(&self, friction: bool, states: usize, seed: u64) -> PyResult<BaseParameters> {
        BaseParameters::new(&self.model, friction, states, seed).map_err(call_err)
    }

    /// The base parameters as a dict: expressions, names, `K` (`π_b = K π`) and the model's own
    /// base values.
    fn base_dict<'py>(&self, py: Python<'py>, b: &BaseParameters) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("expressions", b.expressions())?;
        d.set_item("standard_names", &b.standard_names)?;
        let independent: Vec<&String> = b
            .independent
            .iter()
            .map(|&i| &b.standard_names[i])
            .collect();
        d.set_item("independent", independent)?;
        d.set_item(
            "combination_matrix",
            convert::matrix(py, &b.combination_matrix())?,
        )?;
        let standard = identification::standard_parameters(&self.model, b.friction);
        d.set_item(
            "model_values",
            vector(py, b.base_values(&standard).as_slice())?,
        )?;
        Ok(d)
    }
}
