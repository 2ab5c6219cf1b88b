//! Derivatives of the dynamics, the regressor and identification (the library's
//! `dynamics::{rnea_derivatives, aba_derivatives, regressor}` and `identification`), single or
//! batched. The Python layer (`screwdyn/__init__.py`) attaches them to `Model` and splits the
//! stacked results into tuples.

use crate::batch::{run, Batch, Rows};
use crate::convert::{self, joint_states, vector, StateIn};
use crate::errors::{call_err, guard};
use crate::model::PyModel;
use nalgebra::DMatrix;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use screwdyn::dynamics;
use screwdyn::dynamics::ExternalWrenches;
use screwdyn::identification::{self, BaseParameters, LeastSquares};
use screwdyn::{Model, Workspace};

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_rnea_derivatives, m)?)?;
    m.add_function(wrap_pyfunction!(_aba_derivatives, m)?)?;
    m.add_function(wrap_pyfunction!(_regressor, m)?)?;
    m.add_function(wrap_pyfunction!(_inertial_parameters, m)?)?;
    m.add_function(wrap_pyfunction!(_parameter_names, m)?)?;
    m.add_function(wrap_pyfunction!(_base_parameters, m)?)?;
    m.add_function(wrap_pyfunction!(_identify, m)?)?;
    Ok(())
}

/// The library's derivative function (`dynamics::rnea_derivatives` or `aba_derivatives`) at
/// one state, leaving its results in the workspace.
type Derivatives = fn(
    &Model,
    &mut Workspace,
    &[f64],
    &[f64],
    &[f64],
    Option<&ExternalWrenches>,
) -> screwdyn::Result<()>;

/// The external wrenches as the Python keywords give them (`fext`, `fext_world`,
/// `tip_wrenches`).
type WrenchDicts<'a, 'py> = [Option<&'a Bound<'py, PyDict>>; 3];

/// Runs `derivatives` on each of the (stacked) states `(x0, x1, x2)` under the external
/// wrenches `dicts` and writes the three `nq × nq` matrices `pick` takes from the workspace,
/// stacked as `(3, nq, nq)` per state.
fn three_matrices<'py>(
    py: Python<'py>,
    model: &PyModel,
    inputs: [(&StateIn<'py>, &'static str); 3],
    [fext, fext_world, tip_wrenches]: WrenchDicts<'_, 'py>,
    threads: Option<usize>,
    derivatives: Derivatives,
    pick: fn(&Workspace) -> [&DMatrix<f64>; 3],
) -> PyResult<Bound<'py, PyAny>> {
    guard(|| {
        let ext = model.wrenches(fext, fext_world, tip_wrenches)?;
        let m = &model.model;
        let [x0, x1, x2] = inputs.map(|(x, name)| joint_states(m, x, name));
        let (x0, x1, x2) = (x0?, x1?, x2?);
        let n = m.nq();
        run(
            py,
            m,
            &model.scratch,
            &[&x0, &x1, &x2],
            &[3, n, n],
            Batch::threads(threads),
            |m, s, r: &Rows<'_>, o| {
                derivatives(m, &mut s.ws, r[0], r[1], r[2], ext.as_ref())?;
                for (matrix, out) in pick(&s.ws).into_iter().zip(o.chunks_exact_mut(n * n)) {
                    convert::write_rows(matrix, out);
                }
                Ok(())
            },
        )
    })
}

/// `∂τ/∂q`, `∂τ/∂q̇` and `M = ∂τ/∂q̈` stacked as `(3, nq, nq)` (`(N, 3, nq, nq)` for stacked
/// states); `Model.rnea_derivatives` splits them.
#[pyfunction]
#[pyo3(signature = (model, q, v, a, fext, fext_world, tip_wrenches, threads))]
#[allow(clippy::too_many_arguments)]
fn _rnea_derivatives<'py>(
    py: Python<'py>,
    model: &PyModel,
    q: StateIn<'py>,
    v: StateIn<'py>,
    a: StateIn<'py>,
    fext: Option<&Bound<'py, PyDict>>,
    fext_world: Option<&Bound<'py, PyDict>>,
    tip_wrenches: Option<&Bound<'py, PyDict>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    three_matrices(
        py,
        model,
        [(&q, "q"), (&v, "v"), (&a, "a")],
        [fext, fext_world, tip_wrenches],
        threads,
        |m, ws, q, v, a, ext| dynamics::rnea_derivatives(m, ws, q, v, a, ext).map(|_| ()),
        |ws| [&ws.dtau_dq, &ws.dtau_dv, &ws.mass_matrix],
    )
}

/// `∂q̈/∂q`, `∂q̈/∂q̇` and `M⁻¹ = ∂q̈/∂τ` stacked as `(3, nq, nq)` (`(N, 3, nq, nq)`).
#[pyfunction]
#[pyo3(signature = (model, q, v, tau, fext, fext_world, tip_wrenches, threads))]
#[allow(clippy::too_many_arguments)]
fn _aba_derivatives<'py>(
    py: Python<'py>,
    model: &PyModel,
    q: StateIn<'py>,
    v: StateIn<'py>,
    tau: StateIn<'py>,
    fext: Option<&Bound<'py, PyDict>>,
    fext_world: Option<&Bound<'py, PyDict>>,
    tip_wrenches: Option<&Bound<'py, PyDict>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    three_matrices(
        py,
        model,
        [(&q, "q"), (&v, "v"), (&tau, "tau")],
        [fext, fext_world, tip_wrenches],
        threads,
        |m, ws, q, v, tau, ext| dynamics::aba_derivatives(m, ws, q, v, tau, ext).map(|_| ()),
        |ws| [&ws.dqdd_dq, &ws.dqdd_dv, &ws.mass_matrix_inverse],
    )
}

/// The regressor `Y(q, q̇, q̈)`, `(nq, 10 nq)` (`(N, nq, 10 nq)`).
#[pyfunction]
#[pyo3(signature = (model, q, v, a, threads))]
fn _regressor<'py>(
    py: Python<'py>,
    model: &PyModel,
    q: StateIn<'py>,
    v: StateIn<'py>,
    a: StateIn<'py>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    guard(|| {
        let m = &model.model;
        let q = joint_states(m, &q, "q")?;
        let v = joint_states(m, &v, "v")?;
        let a = joint_states(m, &a, "a")?;
        let n = m.nq();
        run(
            py,
            m,
            &model.scratch,
            &[&q, &v, &a],
            &[n, dynamics::PARAMETERS_PER_BODY * m.nbodies()],
            Batch::threads(threads),
            |m, s, r: &Rows<'_>, o| {
                convert::write_rows(dynamics::regressor(m, &mut s.ws, r[0], r[1], r[2])?, o);
                Ok(())
            },
        )
    })
}

/// The standard parameters `π` (10 per body, then `fv`, `fc` per joint with `friction`).
#[pyfunction]
fn _inertial_parameters<'py>(
    py: Python<'py>,
    model: &PyModel,
    friction: bool,
) -> PyResult<Bound<'py, PyAny>> {
    vector(
        py,
        identification::standard_parameters(&model.model, friction).as_slice(),
    )
}

/// Names of the standard parameters, `<parameter>_<body>` (then `fv_<joint>`, `fc_<joint>`).
#[pyfunction]
fn _parameter_names(model: &PyModel, friction: bool) -> Vec<String> {
    identification::parameter_names(&model.model, friction)
}

fn base(model: &PyModel, friction: bool, states: usize, seed: u64) -> PyResult<BaseParameters> {
    BaseParameters::new(&model.model, friction, states, seed).map_err(call_err)
}

fn base_dict<'py>(
    py: Python<'py>,
    model: &PyModel,
    b: &BaseParameters,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("expressions", b.expressions())?;
    d.set_item("standard_names", &b.standard_names)?;
    d.set_item(
        "independent",
        b.independent
            .iter()
            .map(|&i| b.standard_names[i].clone())
            .collect::<Vec<_>>(),
    )?;
    d.set_item(
        "combination_matrix",
        convert::matrix(py, &b.combination_matrix())?,
    )?;
    let standard = identification::standard_parameters(&model.model, b.friction);
    d.set_item(
        "model_values",
        vector(py, b.base_values(&standard).as_slice())?,
    )?;
    Ok(d)
}

/// The base parameters: expressions, `K` (`π_b = K π`) and the model's own base values.
#[pyfunction]
#[pyo3(signature = (model, friction, states, seed))]
fn _base_parameters<'py>(
    py: Python<'py>,
    model: &PyModel,
    friction: bool,
    states: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    guard(|| {
        let b = py.detach(|| base(model, friction, states, seed))?;
        base_dict(py, model, &b)
    })
}

/// Least squares for the base parameters from stacked samples `(N, nq)` of `q, v, a, tau`.
#[pyfunction]
#[pyo3(signature = (model, q, v, a, tau, friction, states, seed))]
#[allow(clippy::too_many_arguments)]
fn _identify<'py>(
    py: Python<'py>,
    model: &PyModel,
    q: StateIn<'py>,
    v: StateIn<'py>,
    a: StateIn<'py>,
    tau: StateIn<'py>,
    friction: bool,
    states: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    guard(|| {
        let m = &model.model;
        let args = [
            joint_states(m, &q, "q")?,
            joint_states(m, &v, "v")?,
            joint_states(m, &a, "a")?,
            joint_states(m, &tau, "tau")?,
        ];
        let refs: Vec<&convert::States<'_>> = args.iter().collect();
        let n = convert::batch_len(&refs)?.unwrap_or(1);
        if args.iter().any(|s| s.n.is_none()) && n > 1 {
            return Err(PyValueError::new_err(
                "identify takes stacked samples: q, v, a and tau must all have shape (N, nq)",
            ));
        }
        let b = base(model, friction, states, seed)?;
        let result = py.detach(|| -> Result<_, (usize, screwdyn::Error)> {
            let mut ls = LeastSquares::new(m, b.clone());
            for k in 0..n {
                ls.add(
                    m,
                    args[0].row(k),
                    args[1].row(k),
                    args[2].row(k),
                    args[3].row(k),
                )
                .map_err(|e| (k, e))?;
            }
            ls.solve().map_err(|e| (usize::MAX, e))
        });
        let est = result.map_err(|(k, e)| {
            if k == usize::MAX {
                call_err(e)
            } else {
                PyValueError::new_err(format!("sample {k}: {e}"))
            }
        })?;
        let d = base_dict(py, model, &b)?;
        d.set_item("values", vector(py, est.values.as_slice())?)?;
        d.set_item("std_dev", vector(py, est.std_dev.as_slice())?)?;
        d.set_item("condition_number", est.condition_number)?;
        d.set_item("sigma", est.sigma)?;
        d.set_item("samples", est.samples)?;
        Ok(d)
    })
}
