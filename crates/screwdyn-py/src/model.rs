//! `screwdyn.Model`: the class, loading (`load`, `load_string`), its properties and pickling.
//! The methods that compute are in the topic modules (`kinematics`, `dynamics`, `energy`…),
//! each with its own `#[pymethods]` block.

use crate::batch::Scratch;
use crate::convert::{self, fixed_states, ArrayIn};
use crate::errors::{call_err, guard, load_err, ModelError};
use nalgebra::Vector3;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use screwdyn::io::{Format, LoadOptions};
use screwdyn::Model;
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
pub(crate) struct PyModel {
    pub(crate) model: Model,
    source: Source,
    strict: bool,
    gravity: Option<[f64; 3]>,
    joint_friction: Option<(Vec<f64>, Vec<f64>)>,
    /// A workspace reused by single-state calls (batches make one per thread).
    pub(crate) scratch: Mutex<Option<Scratch>>,
    /// The last inverse-kinematics solver and its workspace, reused while the frame and the
    /// options stay the same (building one copies the model and looks for a closed form).
    pub(crate) ik_cache: Mutex<Option<crate::ik::CachedSolver>>,
}

/// Adds the class and the loading functions to the native module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyModel>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(load_string, m)?)?;
    m.add_function(wrap_pyfunction!(builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(_unpickle_model, m)?)?;
    Ok(())
}

fn options(strict: bool) -> LoadOptions {
    LoadOptions { strict }
}

impl PyModel {
    /// A model parsed from `source`, then given the gravity and joint friction set since it was
    /// loaded (the path of `load_string` and of unpickling).
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
                    .map_err(load_err)?
            }
            Source::Text { text, file } => {
                screwdyn::io::load_str(text, file, &opts).map_err(load_err)?
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
            ik_cache: Mutex::new(None),
        })
    }

    /// The URDF or MJCF file the model was loaded from and its text, when it was loaded from
    /// one that still exists (its visuals are drawn by `view`, meshes found beside it).
    pub(crate) fn description_source(&self) -> Option<(PathBuf, String)> {
        match &self.source {
            Source::Text { file, text } => {
                use screwdyn::io::Format;
                let drawn = matches!(Format::of_file(file), Some(Format::Urdf | Format::Mjcf));
                let p = PathBuf::from(file);
                (drawn && p.is_file()).then(|| (p, text.clone()))
            }
            Source::Builtin(_) => None,
        }
    }
}

/// Loads a model from a `.urdf` file, a `.xml` file (MuJoCo's MJCF), a `.toml` file (DH, modified
/// DH, product of exponentials or the native format, chosen by its `format` key) or
/// `builtin:<name>`.
///
/// Raises FileNotFoundError for a missing file and screwdyn.ModelError (a ValueError) for a
/// description that cannot be loaded; the message names the file and line. Physically
/// inconsistent inertias are findings (`Model.physical_problems`), not errors, unless
/// `strict=True`.
#[pyfunction]
#[pyo3(signature = (path_or_builtin, *, strict = false))]
fn load(path_or_builtin: &Bound<'_, PyAny>, strict: bool) -> PyResult<PyModel> {
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
        // The text the model was parsed from, read once and kept for pickling (the library has
        // no exact serialiser: a pickled model is parsed again from the same text).
        let loaded = screwdyn::io::load_source(&path, &options(strict)).map_err(load_err)?;
        Ok(PyModel {
            model: loaded.model,
            source: Source::Text {
                text: loaded.text.unwrap_or_default(),
                file: path,
            },
            strict,
            gravity: None,
            joint_friction: None,
            scratch: Mutex::new(None),
            ik_cache: Mutex::new(None),
        })
    })
}

/// Loads a model from the text of a description. `format` is `"urdf"`, `"mjcf"` or `"toml"` (a
/// TOML description says which of dh, modified-dh, poe or screwdyn it is with its `format`
/// key); `None` guesses from the text (MJCF's root element is `<mujoco>`, URDF's `<robot>`). `name` names the text in messages.
#[pyfunction]
#[pyo3(signature = (text, format = None, *, name = "<string>", strict = false))]
fn load_string(text: &str, format: Option<&str>, name: &str, strict: bool) -> PyResult<PyModel> {
    guard(|| {
        let format = match format {
            None => Format::of_text(text),
            Some(f) => f.parse::<Format>().map_err(call_err)?,
        };
        let file = format.file_name(name);
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
fn builtin_names() -> Vec<&'static str> {
    screwdyn::builtin::NAMES.to_vec()
}

/// Rebuilds a pickled model (see `Model.__reduce__`).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn _unpickle_model(
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

    /// The index of a frame (its position in :attr:`frame_names`) from its name, or from its
    /// index (checked); Pinocchio's ``model.getFrameId(name)``. Every method taking a frame takes
    /// either.
    fn frame_id(&self, frame: &Bound<'_, PyAny>) -> PyResult<usize> {
        self.frame(frame)
    }

    /// The name of a frame from its index (or its name, checked); ``frame_names[i]``.
    fn frame_name(&self, frame: &Bound<'_, PyAny>) -> PyResult<String> {
        let f = self.frame(frame)?;
        Ok(self.model.frames()[f].name.clone())
    }

    /// The index of a joint (its position in :attr:`joint_names`, the coordinate it moves in
    /// ``q``) from its name, or from its index (checked); Pinocchio's ``getJointId`` minus one
    /// (Pinocchio's joint 0 is the universe).
    fn joint_id(&self, joint: &Bound<'_, PyAny>) -> PyResult<usize> {
        self.joint(joint)
    }

    /// Names of the model's keyframes (named configurations, an MJCF file's `<key>`s).
    #[getter]
    fn keyframe_names(&self) -> Vec<String> {
        self.model
            .keyframe_names()
            .into_iter()
            .map(String::from)
            .collect()
    }

    /// The named configuration `name` (an MJCF `<key>`): `q`, `(nq,)`. Raises
    /// screwdyn.ModelError for a name the model does not have.
    fn keyframe<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let q = self.model.keyframe(name).map_err(call_err)?;
        convert::vector(py, q)
    }

    /// The parent link of each link (`None` for a link attached to the base): `λ(i)` of docs/notation.md.
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

    /// Armatures: the rotor inertias reflected to the joints (kg·m² or kg), added to the
    /// mass matrix's diagonal.
    #[getter]
    fn armature<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self.model.joints().iter().map(|j| j.armature).collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// Joint spring stiffnesses `k` (N·m/rad or N/m; MuJoCo's `stiffness`): simulation applies
    /// `τ = −k (q − q_spring)`.
    #[getter]
    fn stiffness<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self.model.joints().iter().map(|j| j.stiffness).collect();
        convert::frozen(convert::vector(py, &v)?)
    }

    /// The joint springs' rest positions `q_spring` (rad or m; MuJoCo's `springref`).
    #[getter]
    fn springref<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self.model.joints().iter().map(|j| j.springref).collect();
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

    /// A copy of the model with the given viscous damping and Coulomb friction per joint (each
    /// one value per joint or one number for all of them).
    fn with_joint_friction(
        &self,
        damping: ArrayIn<'_>,
        friction: ArrayIn<'_>,
    ) -> PyResult<PyModel> {
        let d = convert::model_per_joint(&self.model, &damping, "damping")?;
        let f = convert::model_per_joint(&self.model, &friction, "friction")?;
        PyModel::rebuild(self.source.clone(), self.strict, self.gravity, Some((d, f)))
    }

    /// The model as URDF text (the library's exporter; gravity is not part of URDF).
    fn to_urdf(&self) -> PyResult<String> {
        screwdyn::io::urdf::to_urdf_string(&self.model).map_err(call_err)
    }

    /// The model as MJCF text, MuJoCo's format (the library's exporter: armature, limits,
    /// damping, friction, springs, effort limits as motors, frames as sites, gravity).
    fn to_mjcf(&self) -> PyResult<String> {
        screwdyn::io::mjcf_export::to_mjcf_string(&self.model).map_err(call_err)
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
}
