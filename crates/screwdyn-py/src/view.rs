//! `Model.view`: the page of `screwdyn_view::render_html` (the same page as `screwdyn view`),
//! wrapped in `screwdyn._view.View`; and `SimResult.save`: a recording written by the
//! library's CSV/JSON writers.

use crate::compute::arg;
use crate::convert::{self, as_int, empty_tuple, python_class, ArrayIn, StateIn};
use crate::errors::{call_err, guard};
use crate::model::PyModel;
use numpy::PyUntypedArrayMethods;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyInt, PyString};
use screwdyn::sim::Recording;
use screwdyn::Model;
use screwdyn_view::{read_run, render_html, Run, ViewOptions, WarningKind};
use std::path::PathBuf;

/// Adds the view's functions and defaults to the native module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
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

// `view`'s text signature spells the library's caps out; these fail the build if they change.
const _: () = assert!(screwdyn_view::DEFAULT_MAX_TRIANGLES == 200_000);
const _: () = assert!(screwdyn_view::DEFAULT_MAX_SAMPLES == 1000);

/// The notebook frame's default width, a CSS length.
fn default_width() -> Py<PyAny> {
    Python::attach(|py| PyString::new(py, "100%").into_any().unbind())
}

/// The notebook frame's default height, in pixels.
fn default_height() -> Py<PyAny> {
    Python::attach(|py| PyInt::new(py, 600).into_any().unbind())
}

#[pymethods]
impl PyModel {
    /// The robot in 3-D (the page of ``screwdyn view``), displayed inline in Jupyter: orbit,
    /// zoom and pan, a floor grid, the base frame, and toggleable overlays (link frames ``{i}``,
    /// joint screw axes, centres of mass, the end-effector path of a run).
    ///
    /// q: the configuration shown (``(nq,)``; zeros by default). Not combined with ``run``.
    /// run: a run to animate (play/pause, time slider, speed, synchronised plot of ``q``, ``τ``
    ///     and the energies, joints past a limit highlighted): a :class:`SimResult` from
    ///     :meth:`simulate`, a :class:`TorqueProfile`, or the path of a run ``.csv``/``.json``
    ///     file as written by ``screwdyn simulate --output`` or :meth:`SimResult.save`.
    /// urdf: the URDF (``<visual>`` elements) or MJCF file (visual geoms: groups 0–2, with their
    ///     colours) whose visuals are drawn (default: the file the model was loaded from, when it
    ///     is a URDF or MJCF file; otherwise the skeleton from the screw axes).
    /// package_path: folders searched for ``package://`` meshes before ``ROS_PACKAGE_PATH``
    ///     (``--package-path``).
    /// max_triangles: cap on the embedded mesh triangles (``--max-triangles``; larger meshes are
    ///     decimated, with a warning). max_samples: cap on the run samples embedded
    ///     (``--max-samples``; evenly strided, limit violations of dropped samples kept).
    /// title: the page title (default: the model's name). width, height: the notebook frame's
    ///     size (pixels or a CSS length).
    ///
    /// Returns a :class:`View` (``.html``, ``.save(path)``, ``.warnings``). Raises ValueError with
    /// the library's sentence for a run whose joints are not the model's, a bad ``q``, a
    /// non-finite value; FileNotFoundError for a missing run file.
    // The text signature shows the defaults Rust cannot write as literals.
    #[pyo3(
        signature = (q = None, run = None, *, urdf = None, package_path = empty_tuple(), max_triangles = screwdyn_view::DEFAULT_MAX_TRIANGLES, max_samples = screwdyn_view::DEFAULT_MAX_SAMPLES, title = None, width = default_width(), height = default_height()),
        text_signature = "($self, q=None, run=None, *, urdf=None, package_path=(), max_triangles=200000, max_samples=1000, title=None, width='100%', height=600)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn view<'py>(
        &self,
        py: Python<'py>,
        q: Option<&Bound<'py, PyAny>>,
        run: Option<&Bound<'py, PyAny>>,
        urdf: Option<PathBuf>,
        package_path: Py<PyAny>,
        #[pyo3(from_py_with = as_int)] max_triangles: usize,
        #[pyo3(from_py_with = as_int)] max_samples: usize,
        title: Option<String>,
        width: Py<PyAny>,
        height: Py<PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let data = self.compute(py, |c| {
            // In the order the arguments were checked when `view` was written in Python.
            let run = run.map(RunArg::of).transpose()?;
            let package_paths = package_paths(package_path.bind(py))?;
            let q: Option<StateIn<'_>> = q.map(|q| q.extract()).transpose()?;
            let m = &self.model;
            if q.is_some() && run.is_some() {
                return Err(PyValueError::new_err(
                    "q cannot be combined with run (the run gives the configurations)",
                ));
            }
            let q = q
                .as_ref()
                .map(|q| c.one("view", [arg(q, "q")], |[q]| Ok(q.to_vec())));
            let q = q.transpose()?;
            let run = run.map(|r| r.read(m, max_samples)).transpose()?;
            // The model's own URDF is not read again; one given as `urdf` is.
            let (description, description_text) = match urdf {
                Some(path) => (Some(path), None),
                None => self.description_source().unzip(),
            };
            let options = ViewOptions {
                q,
                run,
                description,
                description_text,
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
        })?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("width", width)?;
        kwargs.set_item("height", height)?;
        python_class(py, "screwdyn._view", "View")?.call((data,), Some(&kwargs))
    }
}

/// Whether `x` is a `str` or an `os.PathLike`.
fn is_path_like(x: &Bound<'_, PyAny>) -> PyResult<bool> {
    Ok(
        x.is_instance_of::<PyString>()
            || x.is_instance(&python_class(x.py(), "os", "PathLike")?)?,
    )
}

/// The `package_path` argument: one folder or a sequence of them.
fn package_paths(p: &Bound<'_, PyAny>) -> PyResult<Vec<PathBuf>> {
    if is_path_like(p)? {
        return Ok(vec![p.extract()?]);
    }
    p.try_iter()?.map(|p| p?.extract()).collect()
}

/// The `run` argument of `view`: the path of a run file, or a `SimResult` / `TorqueProfile`.
enum RunArg<'a, 'py> {
    File(&'a Bound<'py, PyAny>),
    Result(&'a Bound<'py, PyAny>),
}

impl<'a, 'py> RunArg<'a, 'py> {
    fn of(run: &'a Bound<'py, PyAny>) -> PyResult<Self> {
        if run.is_instance_of::<PyBytes>() || is_path_like(run)? {
            Ok(RunArg::File(run))
        } else if run.hasattr("joint_names")? {
            Ok(RunArg::Result(run))
        } else {
            Err(PyTypeError::new_err(
                "run is a path to a run .csv/.json file, a SimResult or a TorqueProfile",
            ))
        }
    }

    /// The run to animate: a file read by the library's `read_run`, or the recording's arrays.
    fn read(self, model: &Model, max_samples: usize) -> PyResult<Run> {
        match self {
            RunArg::Result(r) => {
                let rec = recording(r)?;
                Run::from_recording(&rec, model, max_samples).map_err(call_err)
            }
            RunArg::File(p) => {
                let path: PathBuf = p.extract().map_err(|_| {
                    PyTypeError::new_err(
                        "run is a path to a run .csv/.json file, a SimResult or a TorqueProfile",
                    )
                })?;
                read_run(&path, model, max_samples).map_err(call_err)
            }
        }
    }
}

/// A `(T, n)` array as rows, checked to have `n` columns.
fn rows(a: &ArrayIn<'_>, name: &str, t: usize, n: usize) -> PyResult<Vec<Vec<f64>>> {
    let shape = a.shape();
    if shape.len() != 2 || shape[0] != t || shape[1] != n {
        return Err(PyValueError::new_err(format!(
            "the recording's {name} has shape {shape:?}, expected ({t}, {n}) (one row per sample, one column per joint)"
        )));
    }
    Ok(convert::rows_of(a))
}

/// A `(T,)` array as a vector.
fn series(a: &ArrayIn<'_>, name: &str, t: usize) -> PyResult<Vec<f64>> {
    if a.shape() != [t] {
        return Err(PyValueError::new_err(format!(
            "the recording's {name} has shape {:?}, expected ({t},)",
            a.shape()
        )));
    }
    Ok(convert::contiguous(a).into_owned())
}

/// A library [`Recording`] from the arrays of a `SimResult` (or of a `TorqueProfile`'s
/// `samples`): `joint_names`, `t`, `q`, `v`, `a`, `tau` and the energies (poses are not carried).
fn recording(result: &Bound<'_, PyAny>) -> PyResult<Recording> {
    let samples = if result.hasattr("samples")? {
        result.getattr("samples")?
    } else {
        result.clone()
    };
    let joints: Vec<String> = samples.getattr("joint_names")?.extract()?;
    let arr = |name: &str| -> PyResult<ArrayIn<'_>> { samples.getattr(name)?.extract() };
    let t: Vec<f64> = {
        let a = arr("t")?;
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
    rec.q = rows(&arr("q")?, "q", nt, n)?;
    rec.v = rows(&arr("v")?, "v", nt, n)?;
    rec.a = rows(&arr("a")?, "a", nt, n)?;
    rec.tau = rows(&arr("tau")?, "tau", nt, n)?;
    rec.kinetic_energy = series(&arr("kinetic_energy")?, "kinetic_energy", nt)?;
    rec.potential_energy = series(&arr("potential_energy")?, "potential_energy", nt)?;
    rec.total_energy = series(&arr("total_energy")?, "total_energy", nt)?;
    Ok(rec)
}

/// Writes `text` to `path` atomically (temporary file, then rename).
#[pyfunction]
fn _write_text_atomically(path: PathBuf, text: &str) -> PyResult<()> {
    screwdyn_view::write_atomically(&path, text.as_bytes()).map_err(call_err)
}

/// Writes a `SimResult` (or a `TorqueProfile`'s samples) as the CSV or JSON file `screwdyn
/// simulate --output` writes (by the extension of `path`).
#[pyfunction]
fn _save_recording(path: PathBuf, result: &Bound<'_, PyAny>) -> PyResult<()> {
    guard(|| {
        let rec = recording(result)?;
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
