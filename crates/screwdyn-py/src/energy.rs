//! `Model`'s energies, power and centre of mass (the library's `dynamics::energy`), single or
//! batched: a float for one state, an `(N,)` array for stacked states.

use crate::batch::Batch;
use crate::compute::arg;
use crate::convert::StateIn;
use crate::model::PyModel;
use pyo3::prelude::*;
use screwdyn::dynamics;

#[pymethods]
impl PyModel {
    /// Kinetic energy `½ Σ V_iᵀ 𝔍_i V_i` (J): a float, `(N,)` for stacked states.
    #[pyo3(signature = (q, v, *, threads = None, out = None))]
    fn kinetic_energy<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.compute(py, |c| {
            c.each(
                Batch { threads, out },
                [arg(&q, "q"), arg(&v, "v")],
                &[],
                |m, s, r, o| {
                    o[0] = dynamics::kinetic_energy(m, &mut s.ws, r[0], r[1])?;
                    Ok(())
                },
            )
        })
    }

    /// Potential energy `−Σ m_i gᵀ c_i` (J), zero at the base origin.
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn potential_energy<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.compute(py, |c| {
            c.each(Batch { threads, out }, [arg(&q, "q")], &[], |m, s, r, o| {
                o[0] = dynamics::potential_energy(m, &mut s.ws, r[0])?;
                Ok(())
            })
        })
    }

    /// Kinetic plus potential energy (J).
    #[pyo3(signature = (q, v, *, threads = None, out = None))]
    fn total_energy<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.compute(py, |c| {
            c.each(
                Batch { threads, out },
                [arg(&q, "q"), arg(&v, "v")],
                &[],
                |m, s, r, o| {
                    o[0] = dynamics::total_energy(m, &mut s.ws, r[0], r[1])?;
                    Ok(())
                },
            )
        })
    }

    /// Mechanical power `τᵀ v` (W).
    #[pyo3(signature = (tau, v, *, threads = None, out = None))]
    fn power<'py>(
        &self,
        py: Python<'py>,
        tau: StateIn<'py>,
        v: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.compute(py, |c| {
            c.each(
                Batch { threads, out },
                [arg(&tau, "tau"), arg(&v, "v")],
                &[],
                |m, _s, r, o| {
                    o[0] = dynamics::power(m, r[0], r[1])?;
                    Ok(())
                },
            )
        })
    }

    /// Centre of mass of the moving links in the base frame (m), `(3,)`.
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn center_of_mass<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.compute(py, |c| {
            c.each(
                Batch { threads, out },
                [arg(&q, "q")],
                &[3],
                |m, s, r, o| {
                    o.copy_from_slice(dynamics::center_of_mass(m, &mut s.ws, r[0])?.as_slice());
                    Ok(())
                },
            )
        })
    }
}
