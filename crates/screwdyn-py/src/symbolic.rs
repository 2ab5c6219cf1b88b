//! The library's symbolic engine (`screwdyn::symbolic::derive`) for `screwdyn.symbolic`: the
//! canonical polynomials are handed to Python term by term — exact structure, `f64`
//! coefficients — and the Python module builds the SymPy expressions from them.

use crate::args::reference;
use crate::errors::{call_err, guard};
use crate::model::PyModel;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use screwdyn::symbolic::{self, CoriolisForm, Options, Poly, Quantity, Var};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_symbolic_derive, m)?)?;
    m.add("SYMBOLIC_DEFAULT_MAX_TERMS", symbolic::DEFAULT_MAX_TERMS)?;
    Ok(())
}

/// The joints of an angle bit mask (0-based).
fn joints_of(mask: u64) -> Vec<usize> {
    (0..64).filter(|b| mask & (1u64 << b) != 0).collect()
}

/// One variable as `(kind, index, exponent)`: kind `p` (parameter index), `c`/`s` (cos/sin of
/// the sum of the joint angles in a tuple), `q`, `v`, `a` (joint index of `θ`, `θ̇`, `θ̈`).
fn var<'py>(py: Python<'py>, v: Var, e: u8) -> PyResult<Bound<'py, PyTuple>> {
    let (kind, idx): (&str, Bound<'py, PyAny>) = match v {
        Var::Param(k) => ("p", usize::from(k).into_pyobject(py)?.into_any()),
        Var::Cos(m) => ("c", PyTuple::new(py, joints_of(m))?.into_any()),
        Var::Sin(m) => ("s", PyTuple::new(py, joints_of(m))?.into_any()),
        Var::Q(i) => ("q", usize::from(i).into_pyobject(py)?.into_any()),
        Var::Qd(i) => ("v", usize::from(i).into_pyobject(py)?.into_any()),
        Var::Qdd(i) => ("a", usize::from(i).into_pyobject(py)?.into_any()),
    };
    PyTuple::new(
        py,
        [
            kind.into_pyobject(py)?.into_any(),
            idx,
            e.into_pyobject(py)?.into_any(),
        ],
    )
}

/// A polynomial as a list of `(coefficient, ((kind, index, exponent), …))` terms.
fn poly<'py>(py: Python<'py>, p: &Poly) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for (mono, coef) in p.terms() {
        let vars: Vec<Bound<'py, PyTuple>> = mono
            .iter()
            .map(|(v, e)| var(py, *v, *e))
            .collect::<PyResult<_>>()?;
        out.append((*coef, PyTuple::new(py, vars)?))?;
    }
    Ok(out)
}

/// Derives `quantity` (`mass-matrix`, `coriolis`, `gravity`, `torque`, `fk`, `jacobian`,
/// `energy`, `regressor`) as the engine's canonical polynomials: a dict with `model`, `joints`,
/// `quantity`, `params` (name, value, symbolic, group, meaning) and `matrices` (name, rows,
/// cols, entries row-major).
#[pyfunction]
#[pyo3(signature = (model, quantity, symbols, frame, reference_frame, coriolis, max_terms))]
#[allow(clippy::too_many_arguments)]
fn _symbolic_derive<'py>(
    py: Python<'py>,
    model: &PyModel,
    quantity: &str,
    symbols: &str,
    frame: Option<&Bound<'py, PyAny>>,
    reference_frame: &str,
    coriolis: &str,
    max_terms: usize,
) -> PyResult<Bound<'py, PyDict>> {
    guard(|| {
        let quantity: Quantity = quantity.parse().map_err(call_err)?;
        let coriolis: CoriolisForm = coriolis.parse().map_err(call_err)?;
        if max_terms == 0 {
            return Err(PyValueError::new_err("max_terms must be at least 1"));
        }
        let frame = match frame.filter(|f| !f.is_none()) {
            None => None,
            Some(f) => Some(model.model.frames()[model.frame(f)?].name.clone()),
        };
        let options = Options {
            symbols: symbols.to_string(),
            frame,
            reference: reference(reference_frame)?,
            coriolis,
            max_terms,
            ..Options::default()
        };
        let m = &model.model;
        let d = py
            .detach(|| symbolic::derive(m, quantity, &options))
            .map_err(call_err)?;
        let out = PyDict::new(py);
        out.set_item("model", &d.model)?;
        out.set_item("joints", &d.joints)?;
        out.set_item("quantity", quantity.function_name())?;
        let params = PyList::empty(py);
        for p in &d.params.params {
            let e = PyDict::new(py);
            e.set_item("name", &p.name)?;
            e.set_item("value", p.value)?;
            e.set_item("symbolic", p.symbolic)?;
            e.set_item("group", p.kind.group())?;
            e.set_item("meaning", &p.meaning)?;
            params.append(e)?;
        }
        out.set_item("params", params)?;
        let mats = PyList::empty(py);
        for s in &d.matrices {
            let entries = PyList::empty(py);
            for e in &s.entries {
                entries.append(poly(py, e)?)?;
            }
            mats.append((s.name.as_str(), s.rows, s.cols, entries))?;
        }
        out.set_item("matrices", mats)?;
        Ok(out)
    })
}
