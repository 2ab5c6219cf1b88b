//! `Model.view`: the page of `screwdyn_view::render_html` (the same page as `screwdyn view`),
//! and `SimResult.save`: a recording written by the library's CSV/JSON writers.

use crate::convert::{joint_states, ArrayIn};
use crate::errors::{call_err, guard};
use crate::model::PyModel;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use screwdyn::sim::Recording;
use screwdyn::Model;
use screwdyn_view::{read_run, render_html, Run, ViewOptions, WarningKind};
use std::path::PathBuf;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_view, m)?)?;
    m.add_function(wrap_pyfunction!(_save_recording, m)?)?;
    m.add_function(wrap_pyfunction!(_write_text_atomically, m)?)?;
    m.add(
        "VIEW_DEFAULT_MAX_TRIANGLES",
        screwdyn_view::DEFAULT_MAX_TRIANGLES,
    )?;
    m.add(
        "VIEW_DEFAULT_MAX_SAMPLES",
        screwdyn_view::DEFAULT_MAX_SAMPLES,
    )?;
    Ok(())
}

/// A `(T, n)` array as rows, checked to have `n` columns.
fn rows(a: &ArrayIn<'_>, name: &str, t: usize, n: usize) -> PyResult<Vec<Vec<f64>>> {
    let arr = a.as_array();
    let shape = arr.shape();
    if shape.len() != 2 || shape[0] != t || shape[1] != n {
        return Err(PyValueError::new_err(format!(
            "the recording's {name} has shape {shape:?}, expected ({t}, {n}) (one row per sample, one column per joint)"
        )));
    }
    Ok(arr.rows().into_iter().map(|r| r.to_vec()).collect())
}

fn series(a: &ArrayIn<'_>, name: &str, t: usize) -> PyResult<Vec<f64>> {
    let arr = a.as_array();
    if arr.shape() != [t] {
        return Err(PyValueError::new_err(format!(
            "the recording's {name} has shape {:?}, expected ({t},)",
            arr.shape()
        )));
    }
    Ok(arr.iter().copied().collect())
}

/// A library [`Recording`] from the arrays of a `SimResult`: `(joints, t, q, v, a, tau,
/// kinetic_energy, potential_energy, total_energy)` (poses are not carried).
fn recording(spec: &Bound<'_, PyTuple>) -> PyResult<Recording> {
    if spec.len() != 9 {
        return Err(PyTypeError::new_err(
            "a recording is (joints, t, q, v, a, tau, kinetic_energy, potential_energy, total_energy)",
        ));
    }
    let joints: Vec<String> = spec.get_item(0)?.extract()?;
    let arr = |k: usize| -> PyResult<ArrayIn<'_>> { spec.get_item(k)?.extract() };
    let t: Vec<f64> = {
        let a = arr(1)?;
        let v = a.as_array();
        if v.ndim() != 1 {
            return Err(PyValueError::new_err(format!(
                "the recording's t has shape {:?}, expected (T,)",
                v.shape()
            )));
        }
        v.iter().copied().collect()
    };
    let (nt, n) = (t.len(), joints.len());
    let mut rec = Recording::new(joints, Vec::new());
    rec.t = t;
    rec.q = rows(&arr(2)?, "q", nt, n)?;
    rec.v = rows(&arr(3)?, "v", nt, n)?;
    rec.a = rows(&arr(4)?, "a", nt, n)?;
    rec.tau = rows(&arr(5)?, "tau", nt, n)?;
    rec.kinetic_energy = series(&arr(6)?, "kinetic_energy", nt)?;
    rec.potential_energy = series(&arr(7)?, "potential_energy", nt)?;
    rec.total_energy = series(&arr(8)?, "total_energy", nt)?;
    Ok(rec)
}

/// Writes `text` to `path` atomically (temporary file, then rename).
#[pyfunction]
fn _write_text_atomically(path: PathBuf, text: &str) -> PyResult<()> {
    screwdyn_view::write_atomically(&path, text.as_bytes()).map_err(call_err)
}

/// Writes a recording as the CSV or JSON file `screwdyn simulate --output` writes (by the
/// extension of `path`).
#[pyfunction]
fn _save_recording(path: PathBuf, recording_spec: &Bound<'_, PyTuple>) -> PyResult<()> {
    guard(|| {
        let rec = recording(recording_spec)?;
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        let bytes = match ext.as_str() {
            "csv" => {
                let mut out = Vec::new();
                rec.write_csv(&mut out).map_err(call_err)?;
                out
            }
            "json" => {
                let mut text = rec.to_json().to_string();
                text.push('\n');
                text.into_bytes()
            }
            _ => {
                return Err(PyValueError::new_err(format!(
                    "{}: a run is saved as a .csv or .json file",
                    path.display()
                )))
            }
        };
        screwdyn_view::write_atomically(&path, &bytes).map_err(call_err)
    })
}

/// The run to animate: a path (read by the library's `read_run`) or a recording tuple.
fn run_of(model: &Model, run: &Bound<'_, PyAny>, max_samples: usize) -> PyResult<Run> {
    if let Ok(spec) = run.cast::<PyTuple>() {
        let rec = recording(spec)?;
        return Run::from_recording(&rec, model, max_samples).map_err(call_err);
    }
    let path: PathBuf = run.extract().map_err(|_| {
        PyTypeError::new_err(
            "run is a path to a run .csv/.json file, a SimResult or a TorqueProfile",
        )
    })?;
    if !path.exists() {
        return Err(pyo3::exceptions::PyFileNotFoundError::new_err(format!(
            "{}: no such run file",
            path.display()
        )));
    }
    read_run(&path, model, max_samples).map_err(call_err)
}

/// The page of `screwdyn view`: a dict with `html`, `warnings` (`(kind, message)` pairs),
/// `triangles` and `samples`.
#[pyfunction]
#[pyo3(signature = (model, q, run, urdf, package_paths, max_triangles, max_samples, title))]
#[allow(clippy::too_many_arguments)]
fn _view<'py>(
    py: Python<'py>,
    model: &PyModel,
    q: Option<ArrayIn<'py>>,
    run: Option<Bound<'py, PyAny>>,
    urdf: Option<PathBuf>,
    package_paths: Vec<PathBuf>,
    max_triangles: usize,
    max_samples: usize,
    title: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    guard(|| {
        let m = &model.model;
        if q.is_some() && run.is_some() {
            return Err(PyValueError::new_err(
                "q cannot be combined with run (the run gives the configurations)",
            ));
        }
        let q = match &q {
            Some(a) => Some(joint_states(m, a, "q")?.single("view")?.to_vec()),
            None => None,
        };
        let run = run.map(|r| run_of(m, &r, max_samples)).transpose()?;
        let urdf = urdf.or_else(|| model.urdf_path());
        let options = ViewOptions {
            q,
            run,
            urdf,
            package_paths,
            max_triangles,
            title,
        };
        let page = py.detach(|| render_html(m, &options)).map_err(call_err)?;
        let d = PyDict::new(py);
        d.set_item("html", &page.html)?;
        let warnings: Vec<(&str, String)> = page
            .warnings
            .iter()
            .map(|w| {
                let kind = match w.kind {
                    WarningKind::MeshMissing => "mesh-missing",
                    WarningKind::MeshUnreadable => "mesh-unreadable",
                    WarningKind::Decimated => "decimated",
                };
                (kind, w.message.clone())
            })
            .collect();
        d.set_item("warnings", warnings)?;
        d.set_item("triangles", page.triangles)?;
        d.set_item("samples", page.samples)?;
        Ok(d)
    })
}
