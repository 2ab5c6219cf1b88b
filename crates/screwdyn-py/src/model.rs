//! `screwdyn.Model`: loading, properties, pickling, and every per-state algorithm of the
//! library (kinematics, Jacobians, dynamics, energies), single or batched.

use crate::batch::{run, run_lanes, Batch, Rows, Scratch};
use crate::convert::{self, fixed_states, joint_states, ArrayIn, StateIn, States};
use crate::errors::{call_err, guard, load_err, ModelError};
use crate::{analysis, sim};
use nalgebra::{Vector3, Vector6};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PySlice, PyTuple};
use screwdyn::dynamics::{self, ExternalWrenches, ForwardMethod};
use screwdyn::io::LoadOptions;
use screwdyn::kinematics::{self, Reference};
use screwdyn::Model;
use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::Mutex;

/// Where a model came from, so that a pickled model is rebuilt by the same library path.
#[derive(Clone, Debug)]
enum Source {
    Builtin(String),
    Text { text: String, file: String },
}

/// A robot model: a fixed-base kinematic tree with inertias (immutable except for `gravity`).
///
/// Made by `screwdyn.load(path_or_builtin)` or `screwdyn.load_string(text, format=...)`. Joint-space
/// arrays are float64 in the order of `joint_names`; twists and wrenches are angular first,
/// `(ω, v)` and `(m, f)`; units are SI and radians. Every per-state method takes one state
/// (`q` of shape `(nq,)`) or `N` stacked states (`(N, nq)`) and returns stacked results then,
/// computed in Rust over all cores with the GIL released (`threads=1` for the calling thread
/// only). A single argument is broadcast against stacked ones. `out=` (NumPy's convention)
/// writes the result into a float64, C-contiguous array of its exact shape, and returns it.
#[pyclass(name = "Model", module = "screwdyn._screwdyn")]
pub struct PyModel {
    pub model: Model,
    source: Source,
    strict: bool,
    gravity: Option<[f64; 3]>,
    joint_friction: Option<(Vec<f64>, Vec<f64>)>,
    /// A workspace reused by single-state calls (batches make one per thread).
    pub(crate) scratch: Mutex<Option<Scratch>>,
}

fn options(strict: bool) -> LoadOptions {
    LoadOptions { strict }
}

impl PyModel {
    /// The body of `forward_dynamics` and `aba`.
    #[allow(clippy::too_many_arguments)]
    fn forward<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        tau: StateIn<'py>,
        how: dynamics::ForwardMethod,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        batch: Batch<'_, 'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let ext = self.wrenches(fext, fext_world, tip_wrenches)?;
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            let tau = joint_states(&self.model, &tau, "tau")?;
            let nq = self.model.nq();
            if ext.is_none() && how == dynamics::ForwardMethod::Aba {
                // Without wrenches, the library's batch ABA (eight states side by side).
                return run_lanes(
                    py,
                    &self.model,
                    &self.scratch,
                    &[&q, &v, &tau],
                    &[nq],
                    batch,
                    |m, ws, r, o| screwdyn::batch::aba(m, ws, r[0], r[1], r[2], o),
                    |m, s, r, o| {
                        put(o, dynamics::aba(m, &mut s.ws, r[0], r[1], r[2])?);
                        Ok(())
                    },
                );
            }
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v, &tau],
                &[nq],
                batch,
                |m, s, r, o| {
                    put(
                        o,
                        dynamics::forward_dynamics(
                            m,
                            &mut s.ws,
                            r[0],
                            r[1],
                            r[2],
                            ext.as_ref(),
                            how,
                        )?,
                    );
                    Ok(())
                },
            )
        })
    }

    fn rebuild(
        source: Source,
        strict: bool,
        gravity: Option<[f64; 3]>,
        joint_friction: Option<(Vec<f64>, Vec<f64>)>,
    ) -> PyResult<Self> {
        let opts = options(strict);
        let mut model = match &source {
            Source::Builtin(name) => {
                screwdyn::io::load_model_with(&format!("builtin:{name}"), &opts)
                    .map_err(|e| load_err(e, None))?
            }
            Source::Text { text, file } => {
                screwdyn::io::load_str(text, file, &opts).map_err(|e| load_err(e, None))?
            }
        };
        if let Some(g) = gravity {
            model = model.with_gravity(Vector3::from(g)).map_err(call_err)?;
        }
        if let Some((d, f)) = &joint_friction {
            model = model.with_joint_friction(d, f).map_err(call_err)?;
        }
        Ok(PyModel {
            model,
            source,
            strict,
            gravity,
            joint_friction,
            scratch: Mutex::new(None),
        })
    }

    /// The URDF file the model was loaded from, when it was loaded from one that still exists
    /// (its `<visual>` elements are drawn by `view`).
    pub fn urdf_path(&self) -> Option<PathBuf> {
        match &self.source {
            Source::Text { file, .. } => {
                let lower = file.to_ascii_lowercase();
                let p = PathBuf::from(file);
                ((lower.ends_with(".urdf") || lower.ends_with(".xml")) && p.is_file()).then_some(p)
            }
            Source::Builtin(_) => None,
        }
    }

    /// A frame given by name or index.
    pub fn frame(&self, f: &Bound<'_, PyAny>) -> PyResult<usize> {
        let n = self.model.frames().len();
        name_or_index(f, "frame", n, "frames", |name| self.model.frame_id(name))
    }

    /// A moving link (body) given by name or index.
    pub fn link(&self, b: &Bound<'_, PyAny>) -> PyResult<usize> {
        let n = self.model.nbodies();
        name_or_index(b, "link", n, "moving links", |name| {
            self.model.body_id(name)
        })
    }

    /// A joint given by name or index.
    pub fn joint(&self, j: &Bound<'_, PyAny>) -> PyResult<usize> {
        let n = self.model.nq();
        name_or_index(j, "joint", n, "joints", |name| self.model.joint_id(name))
    }

    /// An optional joint-space argument; `None` is the zero vector.
    pub fn opt<'a>(
        &self,
        arr: &'a Option<StateIn<'_>>,
        name: &'static str,
    ) -> PyResult<States<'a>> {
        match arr {
            Some(a) => joint_states(&self.model, a, name),
            None => Ok(States {
                name,
                data: Cow::Owned(vec![0.0; self.model.nq()]),
                n: None,
                width: self.model.nq(),
            }),
        }
    }

    /// External wrenches from the keyword arguments `fext` (link → wrench on the link, in the
    /// link frame), `fext_world` (link → wrench on the link, in the base frame) and
    /// `tip_wrenches` (frame → wrench the frame applies to the environment, in that frame).
    pub fn wrenches(
        &self,
        fext: Option<&Bound<'_, PyDict>>,
        fext_world: Option<&Bound<'_, PyDict>>,
        tip_wrenches: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Option<ExternalWrenches>> {
        if fext.is_none() && fext_world.is_none() && tip_wrenches.is_none() {
            return Ok(None);
        }
        let mut ext = ExternalWrenches::new(&self.model);
        let wrench = |w: &Bound<'_, PyAny>, name: &'static str| -> PyResult<Vector6<f64>> {
            let arr: ArrayIn<'_> = w.extract()?;
            let s = fixed_states(&arr, name, 6, false)?;
            Ok(Vector6::from_column_slice(s.row(0)))
        };
        if let Some(d) = fext {
            for (k, w) in d.iter() {
                let b = self.link(&k)?;
                ext.add_local(b, wrench(&w, "a wrench of fext")?)
                    .map_err(call_err)?;
            }
        }
        if let Some(d) = fext_world {
            for (k, w) in d.iter() {
                let b = self.link(&k)?;
                ext.add_world(b, wrench(&w, "a wrench of fext_world")?)
                    .map_err(call_err)?;
            }
        }
        if let Some(d) = tip_wrenches {
            for (k, w) in d.iter() {
                let f = self.frame(&k)?;
                ext.add_tip(&self.model, f, wrench(&w, "a tip wrench")?)
                    .map_err(call_err)?;
            }
        }
        Ok(Some(ext))
    }
}

pub fn reference(s: &str) -> PyResult<Reference> {
    s.replace('_', "-")
        .parse::<Reference>()
        .map_err(PyValueError::new_err)
}

pub fn method(s: &str) -> PyResult<ForwardMethod> {
    s.replace('_', "-")
        .parse::<ForwardMethod>()
        .map_err(PyValueError::new_err)
}

/// Copies a library vector into the output row.
#[inline]
fn put(o: &mut [f64], x: &nalgebra::DVector<f64>) {
    o.copy_from_slice(x.as_slice());
}

/// Loads a model from a `.urdf` file, a `.toml` file (DH, modified DH, product of exponentials or
/// the native format, chosen by its `format` key) or `builtin:<name>`.
///
/// Raises FileNotFoundError for a missing file and screwdyn.ModelError (a ValueError) for a
/// description that cannot be loaded; the message names the file and line. Physically
/// inconsistent inertias are findings (`Model.physical_problems`), not errors, unless
/// `strict=True`.
#[pyfunction]
#[pyo3(signature = (path_or_builtin, *, strict = false))]
pub fn load(path_or_builtin: &Bound<'_, PyAny>, strict: bool) -> PyResult<PyModel> {
    guard(|| {
        let path: String = match path_or_builtin.extract::<String>() {
            Ok(s) => s,
            Err(_) => path_or_builtin
                .extract::<PathBuf>()
                .map_err(|_| {
                    PyTypeError::new_err(
                        "load takes a path (str or os.PathLike) or 'builtin:<name>'",
                    )
                })?
                .to_string_lossy()
                .into_owned(),
        };
        if let Some(name) = path.strip_prefix("builtin:") {
            return PyModel::rebuild(Source::Builtin(name.to_string()), strict, None, None);
        }
        let opts = options(strict);
        let model =
            screwdyn::io::load_model_with(&path, &opts).map_err(|e| load_err(e, Some(&path)))?;
        // The text the model was parsed from, kept for pickling (the library has no exact
        // serialiser: a pickled model is parsed again from the same text).
        let text = std::fs::read_to_string(&path).map_err(|e| {
            load_err(
                screwdyn::Error::Io(format!("{path}: cannot be read ({e})")),
                Some(&path),
            )
        })?;
        Ok(PyModel {
            model,
            source: Source::Text { text, file: path },
            strict,
            gravity: None,
            joint_friction: None,
            scratch: Mutex::new(None),
        })
    })
}

/// Loads a model from the text of a description. `format` is `"urdf"` or `"toml"` (a TOML
/// description says which of dh, modified-dh, poe or screwdyn it is with its `format` key);
/// `None` guesses from the text (URDF starts with `<`). `name` names the text in messages.
#[pyfunction]
#[pyo3(signature = (text, format = None, *, name = "<string>", strict = false))]
pub fn load_string(
    text: &str,
    format: Option<&str>,
    name: &str,
    strict: bool,
) -> PyResult<PyModel> {
    guard(|| {
        let urdf = match format.map(|f| f.to_ascii_lowercase()) {
            None => text.trim_start().starts_with('<'),
            Some(f) if f == "urdf" || f == "xml" => true,
            Some(f) if ["toml", "dh", "modified-dh", "poe", "screwdyn"].contains(&f.as_str()) => false,
            Some(f) => {
                return Err(PyValueError::new_err(format!(
                    "unknown format '{f}' (use urdf or toml; a TOML text names dh, modified-dh, poe or screwdyn in its format key)"
                )))
            }
        };
        let ext = if urdf { ".urdf" } else { ".toml" };
        let lower = name.to_ascii_lowercase();
        let file = if lower.ends_with(ext) || (urdf && lower.ends_with(".xml")) {
            name.to_string()
        } else {
            format!("{name}{ext}")
        };
        PyModel::rebuild(
            Source::Text {
                text: text.to_string(),
                file,
            },
            strict,
            None,
            None,
        )
    })
}

/// The names accepted as `builtin:<name>`.
#[pyfunction]
pub fn builtin_names() -> Vec<&'static str> {
    screwdyn::builtin::NAMES.to_vec()
}

/// Rebuilds a pickled model (see `Model.__reduce__`).
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn _unpickle_model(
    kind: &str,
    text: String,
    file: String,
    strict: bool,
    gravity: Option<[f64; 3]>,
    joint_friction: Option<(Vec<f64>, Vec<f64>)>,
) -> PyResult<PyModel> {
    guard(|| {
        let source = match kind {
            "builtin" => Source::Builtin(text),
            "text" => Source::Text { text, file },
            _ => {
                return Err(ModelError::new_err(format!(
                    "unknown pickled model kind '{kind}'"
                )))
            }
        };
        PyModel::rebuild(source, strict, gravity, joint_friction)
    })
}

#[pymethods]
impl PyModel {
    // ---------------------------------------------------------------- properties

    /// The robot's name.
    #[getter]
    fn name(&self) -> String {
        self.model.name().to_string()
    }

    /// Number of joint coordinates.
    #[getter]
    fn nq(&self) -> usize {
        self.model.nq()
    }

    /// Number of joint velocities (equal to `nq`).
    #[getter]
    fn nv(&self) -> usize {
        self.model.nv()
    }

    /// Number of moving links (one per joint).
    #[getter]
    fn nbodies(&self) -> usize {
        self.model.nbodies()
    }

    /// Joint names, in the order of every joint-space array.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.model
            .joint_names()
            .into_iter()
            .map(String::from)
            .collect()
    }

    /// Joint kinds: revolute, continuous, prismatic or helical.
    #[getter]
    fn joint_types(&self) -> Vec<&'static str> {
        self.model.joints().iter().map(|j| j.kind.name()).collect()
    }

    /// Names of the moving links (link `i` is moved by joint `i`).
    #[getter]
    fn link_names(&self) -> Vec<String> {
        self.model.bodies().iter().map(|b| b.name.clone()).collect()
    }

    /// Names of every frame: the base, the links, merged fixed links and extra frames.
    #[getter]
    fn frame_names(&self) -> Vec<String> {
        self.model.frames().iter().map(|f| f.name.clone()).collect()
    }

    /// The parent link of each link (`None` for a link attached to the base): the seeds' `λ(i)`.
    #[getter]
    fn parents(&self) -> Vec<Option<usize>> {
        self.model.parents().to_vec()
    }

    /// Lower position limits (rad or m; `-inf` when unlimited).
    #[getter]
    fn lower_limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self.model.joints().iter().map(|j| j.limits.lower).collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// Upper position limits (rad or m; `inf` when unlimited).
    #[getter]
    fn upper_limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self.model.joints().iter().map(|j| j.limits.upper).collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// Velocity limits (rad/s or m/s; `inf` when unlimited).
    #[getter]
    fn velocity_limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self
            .model
            .joints()
            .iter()
            .map(|j| j.limits.velocity)
            .collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// Effort limits (N·m or N; `inf` when unlimited).
    #[getter]
    fn effort_limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self
            .model
            .joints()
            .iter()
            .map(|j| j.limits.effort)
            .collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// Viscous damping coefficients (N·m·s/rad).
    #[getter]
    fn damping<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self.model.joints().iter().map(|j| j.damping).collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// Coulomb friction torques (N·m).
    #[getter]
    fn friction<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self.model.joints().iter().map(|j| j.friction).collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// Joint screw axes `S_i^{i,λ(i)}` in the link frames, angular first, shape `(nq, 6)`.
    #[getter]
    fn screw_axes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let rows: Vec<Vec<f64>> = self
            .model
            .joints()
            .iter()
            .map(|j| j.screw.as_slice().to_vec())
            .collect();
        convert::frozen(convert::rows_array(py, &rows, 6)?)
    }

    /// Spatial inertias `𝔍^{i,i}` of the links in their own frames, angular first, `(nq, 6, 6)`.
    #[getter]
    fn spatial_inertias<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.model.nbodies();
        let mut out = vec![0.0; n * 36];
        for (b, o) in self.model.bodies().iter().zip(out.chunks_mut(36)) {
            convert::write_rows(&b.inertia.matrix(), o);
        }
        convert::frozen(convert::array(py, out, &[n, 6, 6])?)
    }

    /// Gravity in the base frame (m/s²), default `(0, 0, -9.81)`. Settable: the model is
    /// replaced by the library's `with_gravity` copy (pickles keep the new value).
    #[getter]
    fn get_gravity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::frozen(convert::vector(py, self.model.gravity().as_slice())?)
    }

    #[setter]
    fn set_gravity(&mut self, g: ArrayIn<'_>) -> PyResult<()> {
        let s = fixed_states(&g, "gravity", 3, false)?;
        let g = [s.row(0)[0], s.row(0)[1], s.row(0)[2]];
        if let Some(i) = g.iter().position(|x| !x.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "gravity contains a non-finite value ({}) at position {i}",
                g[i]
            )));
        }
        self.model = self
            .model
            .with_gravity(Vector3::from(g))
            .map_err(call_err)?;
        self.gravity = Some(g);
        Ok(())
    }

    /// Physical-consistency findings of the description (inertias not positive semi-definite or
    /// breaking the triangle inequality, massless moving leaves), one sentence each; empty for a
    /// consistent model. `load(..., strict=True)` makes them load errors.
    #[getter]
    fn physical_problems(&self) -> Vec<String> {
        self.model
            .physical_problems()
            .iter()
            .map(|f| f.to_string())
            .collect()
    }

    /// Total mass of the moving links (kg).
    #[getter]
    fn total_mass(&self) -> f64 {
        self.model.total_mass()
    }

    /// A copy of the model with the given viscous damping and Coulomb friction per joint.
    fn with_joint_friction(
        &self,
        damping: ArrayIn<'_>,
        friction: ArrayIn<'_>,
    ) -> PyResult<PyModel> {
        let d = joint_states(&self.model, &damping, "damping")?;
        let f = joint_states(&self.model, &friction, "friction")?;
        let (d, f) = (
            d.single("with_joint_friction")?.to_vec(),
            f.single("with_joint_friction")?.to_vec(),
        );
        PyModel::rebuild(self.source.clone(), self.strict, self.gravity, Some((d, f)))
    }

    /// The model as URDF text (the library's exporter; gravity is not part of URDF).
    fn to_urdf(&self) -> PyResult<String> {
        screwdyn::io::urdf::to_urdf_string(&self.model).map_err(call_err)
    }

    fn __repr__(&self) -> String {
        let g = self.model.gravity();
        format!(
            "Model('{}', nq={}, joints=[{}], gravity=[{}, {}, {}])",
            self.model.name(),
            self.model.nq(),
            self.model
                .joint_names()
                .iter()
                .map(|n| format!("'{n}'"))
                .collect::<Vec<_>>()
                .join(", "),
            g.x,
            g.y,
            g.z
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.extract::<PyRef<'_, PyModel>>() {
            Ok(o) => o.model == self.model,
            Err(_) => false,
        }
    }

    /// Pickling: the model is rebuilt by parsing the same description again (built-in name or
    /// file text), then applying the gravity and joint friction set since.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let this = slf.borrow();
        let f = py
            .import("screwdyn._screwdyn")?
            .getattr("_unpickle_model")?;
        let (kind, text, file) = match &this.source {
            Source::Builtin(n) => ("builtin", n.clone(), String::new()),
            Source::Text { text, file } => ("text", text.clone(), file.clone()),
        };
        let args = (
            kind,
            text,
            file,
            this.strict,
            this.gravity,
            this.joint_friction.clone(),
        )
            .into_pyobject(py)?;
        PyTuple::new(py, [f, args.into_any()])
    }

    // ---------------------------------------------------------------- kinematics

    /// Pose `H_f^0(q)` of a frame (name or index) in the base frame: a `(4, 4)` homogeneous
    /// matrix, `(N, 4, 4)` for stacked `q`.
    #[pyo3(signature = (q, frame, *, threads = None, out = None))]
    fn frame_pose<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        frame: &Bound<'py, PyAny>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let f = self.frame(frame)?;
            let q = joint_states(&self.model, &q, "q")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[4, 4],
                Batch { threads, out },
                |m, s, r, o| {
                    kinematics::forward_kinematics(m, &mut s.ws, r[0])?;
                    convert::write_pose(&kinematics::frame_pose(m, &s.ws, f)?, o);
                    Ok(())
                },
            )
        })
    }

    /// Poses of every frame: a dict frame name → `(4, 4)` (or `(N, 4, 4)`) array.
    #[pyo3(signature = (q, *, threads = None))]
    fn frame_poses<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let nf = self.model.frames().len();
            let all = run(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[nf, 4, 4],
                Batch::threads(threads),
                |m, s, r, o| {
                    kinematics::forward_kinematics(m, &mut s.ws, r[0])?;
                    for (f, of) in o.chunks_mut(16).enumerate() {
                        convert::write_pose(&kinematics::frame_pose(m, &s.ws, f)?, of);
                    }
                    Ok(())
                },
            )?;
            let d = PyDict::new(py);
            for (f, frame) in self.model.frames().iter().enumerate() {
                let item = if q.n.is_some() {
                    all.get_item((PySlice::full(py), f))?
                } else {
                    all.get_item(f)?
                };
                d.set_item(&frame.name, item)?;
            }
            Ok(d)
        })
    }

    /// Geometric Jacobian of a frame, `(6, nq)` angular rows first (`(N, 6, nq)` stacked):
    /// `reference="world"` (the space Jacobian `J^{0,0}`, Pinocchio's WORLD), `"local"` (the body
    /// Jacobian `J_f^{f,0}`) or `"world-aligned"` (the frame origin's velocity in base axes,
    /// Pinocchio's LOCAL_WORLD_ALIGNED).
    #[pyo3(signature = (q, frame, reference = "world", *, threads = None, out = None))]
    fn frame_jacobian<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        frame: &Bound<'py, PyAny>,
        reference: &str,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let f = self.frame(frame)?;
            let rf = self::reference(reference)?;
            let q = joint_states(&self.model, &q, "q")?;
            let nq = self.model.nq();
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[6, nq],
                Batch { threads, out },
                |m, s, r, o| {
                    kinematics::compute_joint_jacobians(m, &mut s.ws, r[0])?;
                    kinematics::frame_jacobian(m, &s.ws, f, rf, &mut s.jac)?;
                    convert::write_rows(&s.jac, o);
                    Ok(())
                },
            )
        })
    }

    /// Seed 001's body Jacobian `J_i^{i,0}(q)` of a link (name or index), `(6, nq)`: block row `i`
    /// of the closed form's `J = L S`.
    #[pyo3(signature = (q, link, *, threads = None, out = None))]
    fn link_jacobian<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        link: &Bound<'py, PyAny>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let b = self.link(link)?;
            let q = joint_states(&self.model, &q, "q")?;
            let nq = self.model.nq();
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[6, nq],
                Batch { threads, out },
                |m, s, r, o| {
                    kinematics::compute_joint_jacobians(m, &mut s.ws, r[0])?;
                    kinematics::link_jacobian(m, &s.ws, b, &mut s.jac)?;
                    convert::write_rows(&s.jac, o);
                    Ok(())
                },
            )
        })
    }

    /// Twist `(ω, v)` of a frame at `(q, v)` in `reference` (world, local or world-aligned),
    /// shape `(6,)` or `(N, 6)`.
    #[pyo3(signature = (q, v, frame, reference = "world", *, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn frame_twist<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        frame: &Bound<'py, PyAny>,
        reference: &str,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let f = self.frame(frame)?;
            let rf = self::reference(reference)?;
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v],
                &[6],
                Batch { threads, out },
                |m, s, r, o| {
                    kinematics::forward_velocity(m, &mut s.ws, r[0], r[1])?;
                    o.copy_from_slice(kinematics::frame_twist(m, &s.ws, f, rf)?.as_slice());
                    Ok(())
                },
            )
        })
    }

    /// Acceleration of a frame at `(q, v, a)`: the derivative of `frame_twist`'s components in
    /// `reference` (world-aligned: the classical acceleration of the frame origin), `(6,)`.
    #[pyo3(signature = (q, v, a, frame, reference = "world", *, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn frame_acceleration<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        a: StateIn<'py>,
        frame: &Bound<'py, PyAny>,
        reference: &str,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let f = self.frame(frame)?;
            let rf = self::reference(reference)?;
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            let a = joint_states(&self.model, &a, "a")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v, &a],
                &[6],
                Batch { threads, out },
                |m, s, r, o| {
                    kinematics::forward_acceleration(m, &mut s.ws, r[0], r[1], r[2])?;
                    o.copy_from_slice(kinematics::frame_acceleration(m, &s.ws, f, rf)?.as_slice());
                    Ok(())
                },
            )
        })
    }

    /// `J̇(q, v) v` of a frame in `reference`: the frame acceleration at zero joint acceleration
    /// (the drift term of `ẍ = J q̈ + J̇ q̇`), `(6,)`.
    #[pyo3(signature = (q, v, frame, reference = "world", *, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn frame_jdot_qdot<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        frame: &Bound<'py, PyAny>,
        reference: &str,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let f = self.frame(frame)?;
            let rf = self::reference(reference)?;
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v],
                &[6],
                Batch { threads, out },
                |m, s, r, o| {
                    let x = kinematics::frame_jdot_qdot(m, &mut s.ws, r[0], r[1], f, rf)?;
                    o.copy_from_slice(x.as_slice());
                    Ok(())
                },
            )
        })
    }

    // ---------------------------------------------------------------- dynamics

    /// Inverse dynamics `τ = M(q) a + C(q, v) v + g(q) − Σ J_iᵀ W_ext,i (+ J_eᵀ W_tip)` by the
    /// recursive Newton–Euler algorithm (seeds 000–002). `v` and `a` default to zero.
    ///
    /// External wrenches (applied to every state): `fext={link: (6,)}` — the wrench of the
    /// environment on the link, in the link frame; `fext_world={link: (6,)}` — the same in the
    /// base frame (moment about the base origin); `tip_wrenches={frame: (6,)}` — the wrench the
    /// frame applies to the environment, in that frame. Wrenches are `(m, f)`, moment first.
    #[pyo3(signature = (q, v = None, a = None, *, fext = None, fext_world = None, tip_wrenches = None, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn rnea<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
        a: Option<StateIn<'py>>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let ext = self.wrenches(fext, fext_world, tip_wrenches)?;
            let q = joint_states(&self.model, &q, "q")?;
            let v = self.opt(&v, "v")?;
            let a = self.opt(&a, "a")?;
            let nq = self.model.nq();
            if ext.is_none() {
                // Without wrenches, the library's batch RNEA (eight states side by side).
                return run_lanes(
                    py,
                    &self.model,
                    &self.scratch,
                    &[&q, &v, &a],
                    &[nq],
                    Batch { threads, out },
                    |m, ws, r, o| screwdyn::batch::rnea(m, ws, r[0], r[1], r[2], o),
                    |m, s, r, o| {
                        put(o, dynamics::rnea(m, &mut s.ws, r[0], r[1], r[2])?);
                        Ok(())
                    },
                );
            }
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v, &a],
                &[nq],
                Batch { threads, out },
                |m, s, r: &Rows<'_>, o| {
                    put(
                        o,
                        dynamics::inverse_dynamics(m, &mut s.ws, r[0], r[1], r[2], ext.as_ref())?,
                    );
                    Ok(())
                },
            )
        })
    }

    /// Joint-space mass matrix `M(q)` by the composite-rigid-body algorithm, `(nq, nq)`.
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn crba<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let nq = self.model.nq();
            run_lanes(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[nq, nq],
                Batch { threads, out },
                |m, ws, r, o| screwdyn::batch::crba(m, ws, r[0], o),
                |m, s, r, o| {
                    convert::write_rows(dynamics::crba(m, &mut s.ws, r[0])?, o);
                    Ok(())
                },
            )
        })
    }

    /// `M(q)⁻¹` (CRBA and a Cholesky factorisation), `(nq, nq)`.
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn mass_matrix_inverse<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let nq = self.model.nq();
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[nq, nq],
                Batch { threads, out },
                |m, s, r, o| {
                    convert::write_rows(dynamics::mass_matrix_inverse(m, &mut s.ws, r[0])?, o);
                    Ok(())
                },
            )
        })
    }

    /// The Coriolis matrix `C(q, v)` whose `Ṁ − 2C` is skew-symmetric (Christoffel symbols of
    /// the first kind), `(nq, nq)`.
    #[pyo3(signature = (q, v, *, threads = None, out = None))]
    fn coriolis_matrix<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            let nq = self.model.nq();
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v],
                &[nq, nq],
                Batch { threads, out },
                |m, s, r, o| {
                    convert::write_rows(dynamics::coriolis_matrix(m, &mut s.ws, r[0], r[1])?, o);
                    Ok(())
                },
            )
        })
    }

    /// Gravity torques `g(q)` (N·m / N), `(nq,)`.
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn gravity_torque<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let nq = self.model.nq();
            run_lanes(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[nq],
                Batch { threads, out },
                |m, ws, r, o| screwdyn::batch::gravity_torque(m, ws, r[0], o),
                |m, s, r, o| {
                    put(o, dynamics::gravity_torque(m, &mut s.ws, r[0])?);
                    Ok(())
                },
            )
        })
    }

    /// Nonlinear effects `C(q, v) v + g(q)`, `(nq,)`.
    #[pyo3(signature = (q, v, *, threads = None, out = None))]
    fn nonlinear_effects<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            let nq = self.model.nq();
            run_lanes(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v],
                &[nq],
                Batch { threads, out },
                |m, ws, r, o| screwdyn::batch::nonlinear_effects(m, ws, r[0], r[1], o),
                |m, s, r, o| {
                    put(o, dynamics::nonlinear_effects(m, &mut s.ws, r[0], r[1])?);
                    Ok(())
                },
            )
        })
    }

    /// Forward dynamics `a = M⁻¹ (τ − C v − g + Σ J_iᵀ W_ext,i)`: `method="aba"` (Featherstone's
    /// articulated-body algorithm), `"crba"` (CRBA + Cholesky) or `"walker-orin"` (seed 004 §6.4).
    /// External wrenches as in `rnea`. A singular mass matrix raises ValueError naming the joint.
    #[pyo3(signature = (q, v, tau, *, method = "aba", fext = None, fext_world = None, tip_wrenches = None, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn forward_dynamics<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        tau: StateIn<'py>,
        method: &str,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let how = self::method(method)?;
        let batch = Batch { threads, out };
        self.forward(py, q, v, tau, how, fext, fext_world, tip_wrenches, batch)
    }

    /// Forward dynamics by the articulated-body algorithm (Featherstone): `forward_dynamics(…,
    /// method="aba")`, q̈ (rad/s²) of shape `(nq,)` or `(N, nq)`. External wrenches as in `rnea`.
    #[pyo3(signature = (q, v, tau, *, fext = None, fext_world = None, tip_wrenches = None, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn aba<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        tau: StateIn<'py>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (how, batch) = (dynamics::ForwardMethod::Aba, Batch { threads, out });
        self.forward(py, q, v, tau, how, fext, fext_world, tip_wrenches, batch)
    }

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
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v],
                &[],
                Batch { threads, out },
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
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[],
                Batch { threads, out },
                |m, s, r, o| {
                    o[0] = dynamics::potential_energy(m, &mut s.ws, r[0])?;
                    Ok(())
                },
            )
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
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let v = joint_states(&self.model, &v, "v")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q, &v],
                &[],
                Batch { threads, out },
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
        guard(|| {
            let tau = joint_states(&self.model, &tau, "tau")?;
            let v = joint_states(&self.model, &v, "v")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&tau, &v],
                &[],
                Batch { threads, out },
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
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            run(
                py,
                &self.model,
                &self.scratch,
                &[&q],
                &[3],
                Batch { threads, out },
                |m, s, r, o| {
                    o.copy_from_slice(dynamics::center_of_mass(m, &mut s.ws, r[0])?.as_slice());
                    Ok(())
                },
            )
        })
    }

    // ---------------------------------------------------------------- seeds' closed form etc.

    /// The seeds' closed form at `(q, v)` (seeds 000/001): a dict of arrays `A`, `L`, `S`,
    /// `inertia` (𝔍), `ad_S_qdot`, `V`, `ad_V`, `J`, `J_dot`, `Vdot_base`, `M`, `C`,
    /// `C_christoffel`, `g` (the Python `screwdyn.closed_form` wraps it in a `ClosedForm`).
    #[pyo3(signature = (q, v = None))]
    fn _closed_form<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let v = self.opt(&v, "v")?;
            analysis::closed_form(
                py,
                &self.model,
                q.single("closed_form")?,
                v.single("closed_form")?,
            )
        })
    }

    /// Lagrangian coefficients `D_ij`, `D_ijk`, `D_i` (seed 004) as a dict of arrays.
    fn _lagrange<'py>(&self, py: Python<'py>, q: StateIn<'py>) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            analysis::lagrange(py, &self.model, q.single("lagrange_coefficients")?)
        })
    }

    /// `∂M/∂q_k` for every `k`, shape `(nq, nq, nq)` with `[k, i, j] = ∂M_ij/∂q_k`.
    fn mass_matrix_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let q = joint_states(&self.model, &q, "q")?;
            let dm = dynamics::mass_matrix_derivatives(
                &self.model,
                q.single("mass_matrix_derivatives")?,
            )
            .map_err(call_err)?;
            let n = self.model.nq();
            let mut out = vec![0.0; n * n * n];
            for (k, o) in out.chunks_mut(n * n).enumerate() {
                convert::write_rows(&dm[k], o);
            }
            convert::array(py, out, &[n, n, n])
        })
    }

    /// Effective inertia of `joint` at `q` (seed 004): with every other joint locked
    /// (`free=None`, the diagonal `M_ii`), every other joint free (`free="all"`: the inertia felt
    /// through the free joints, `M_ii − M_if M_ff⁻¹ M_fi`), or the joints named in a list free.
    #[pyo3(signature = (q, joint, free = None))]
    fn effective_inertia(
        &self,
        q: ArrayIn<'_>,
        joint: &Bound<'_, PyAny>,
        free: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<f64> {
        guard(|| {
            let j = self.joint(joint)?;
            let q = joint_states(&self.model, &q, "q")?;
            let q = q.single("effective_inertia")?;
            let n = self.model.nq();
            let mask: Vec<bool> =
                match free {
                    None => vec![false; n],
                    Some(f) if f.extract::<String>().map(|s| s == "all").unwrap_or(false) => {
                        vec![true; n]
                    }
                    Some(f) if f.extract::<String>().is_ok() => return Err(PyValueError::new_err(
                        "free is None (others locked), \"all\" or a list of joint names or indices",
                    )),
                    Some(f) => {
                        let mut m = vec![false; n];
                        for item in f.try_iter()? {
                            m[self.joint(&item?)?] = true;
                        }
                        m
                    }
                };
            let mut ws = screwdyn::Workspace::new(&self.model);
            dynamics::effective_inertia(&self.model, &mut ws, q, j, &mask).map_err(call_err)
        })
    }

    /// The step-by-step RNEA of seeds 000/002 at one state as a dict of arrays (the Python
    /// `screwdyn.rnea_trace` wraps it in an `RneaTrace` that displays like the lecture).
    #[pyo3(signature = (q, v = None, a = None, *, fext = None, fext_world = None, tip_wrenches = None))]
    #[allow(clippy::too_many_arguments)]
    fn _rnea_trace<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
        a: Option<StateIn<'py>>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let ext = self.wrenches(fext, fext_world, tip_wrenches)?;
            let q = joint_states(&self.model, &q, "q")?;
            let v = self.opt(&v, "v")?;
            let a = self.opt(&a, "a")?;
            analysis::rnea_trace(
                py,
                &self.model,
                q.single("rnea_trace")?,
                v.single("rnea_trace")?,
                a.single("rnea_trace")?,
                ext.as_ref(),
            )
        })
    }

    // ---------------------------------------------------------------- simulation

    /// Simulation; see `screwdyn.Model.simulate` in the Python layer for the arguments.
    #[pyo3(signature = (q0, v0, controller, disturbances, duration, dt, integrator, rtol, atol, method, effects, record_every, frames, progress))]
    #[allow(clippy::too_many_arguments)]
    fn _simulate<'py>(
        &self,
        py: Python<'py>,
        q0: StateIn<'py>,
        v0: StateIn<'py>,
        controller: &Bound<'py, PyAny>,
        disturbances: &Bound<'py, PyList>,
        duration: f64,
        dt: f64,
        integrator: &str,
        rtol: f64,
        atol: f64,
        method: &str,
        effects: &Bound<'py, PyAny>,
        record_every: usize,
        frames: &Bound<'py, PyList>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let q0 = joint_states(&self.model, &q0, "q0")?;
            let v0 = joint_states(&self.model, &v0, "v0")?;
            sim::simulate(
                py,
                self,
                sim::SimArgs {
                    q0: q0.single("simulate")?,
                    v0: v0.single("simulate")?,
                    controller,
                    disturbances,
                    duration,
                    dt,
                    integrator,
                    rtol,
                    atol,
                    method,
                    effects,
                    record_every,
                    frames,
                    progress,
                },
            )
        })
    }

    /// Inverse dynamics along a trajectory every `dt` seconds (end included): a dict with the
    /// samples, peak and RMS torque per joint, effort limits and limit violations.
    fn _torque_profile<'py>(
        &self,
        py: Python<'py>,
        trajectory: &Bound<'py, sim::PyTrajectory>,
        dt: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        guard(|| sim::torque_profile(py, &self.model, &trajectory.borrow(), dt))
    }
}

/// An item of the model given by its name (looked up by `by_name`) or by its index below `n`;
/// `kind` ("frame") and `plural` ("frames") word the messages.
fn name_or_index(
    x: &Bound<'_, PyAny>,
    kind: &str,
    n: usize,
    plural: &str,
    by_name: impl FnOnce(&str) -> screwdyn::Result<usize>,
) -> PyResult<usize> {
    if let Ok(name) = x.extract::<String>() {
        return by_name(&name).map_err(call_err);
    }
    if let Ok(i) = x.extract::<i64>() {
        return usize::try_from(i).ok().filter(|&i| i < n).ok_or_else(|| {
            PyValueError::new_err(format!(
                "{kind} index {i} is out of range: the model has {n} {plural} (0…{})",
                n.saturating_sub(1)
            ))
        });
    }
    Err(PyTypeError::new_err(format!(
        "a {kind} is given by its name (str) or its index (int)"
    )))
}
