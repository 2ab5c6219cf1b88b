//! `Model.simulate` and `Model.torque_profile` (the library's `sim`): the controller, the
//! disturbances and the joint effects from their Python forms, the run, and the recording as the
//! dict `screwdyn.SimResult` wraps. Built-in controllers run with the GIL released; a Python
//! callable as controller is called with the GIL held, and an exception it raises ends the
//! simulation and propagates unchanged.

use crate::args::method;
use crate::compute::{arg, optional};
use crate::convert::{self, fixed_states, python_class, rows_array, values_1d};
use crate::convert::{as_float, as_int, empty_tuple, vector, ArrayIn, StateIn};
use crate::errors::call_err;
use crate::model::PyModel;
use crate::trajectory::PyTrajectory;
use nalgebra::Vector6;
use numpy::PyUntypedArrayMethods;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use screwdyn::dynamics::link_wrench_on_body;
use screwdyn::sim::{
    self, Controller, ControllerSpec, Disturbance, Integrator, JointEffects, Recording, SimOptions,
};
use screwdyn::Model;
use std::cell::RefCell;

/// What `controller` may be, for the message that refuses anything else.
const CONTROLLERS: &str = "controller is None, an array of constant torques, screwdyn.PD, screwdyn.ComputedTorque, screwdyn.TorqueSeries or a callable f(t, q, v) -> tau";

#[pymethods]
impl PyModel {
    /// Simulates the robot from ``(q0, v0)`` for ``duration`` seconds: forward dynamics
    /// integrated in time.
    ///
    /// controller: ``None`` (zero torque), an array (constant torque), :class:`PD`,
    ///     :class:`ComputedTorque`, :class:`TorqueSeries`, or a callable ``f(t, q, v) -> tau``
    ///     (called with the GIL held; an exception it raises stops the run and propagates).
    /// integrator: ``"euler"`` (semi-implicit), ``"rk4"`` or ``"dopri5"`` (adaptive, ``rtol``,
    ///     ``atol``; ``dt`` is then the output interval).
    /// method: forward dynamics ``"aba"``, ``"crba"`` or ``"walker-orin"``.
    /// effects: joint effects added to the commanded torque: ``None``/``True`` for the library's
    ///     defaults (effort saturation, viscous damping, joint springs, smoothed Coulomb friction, position limits
    ///     as stiff spring–dampers), ``False`` for none, or a dict of fields (``saturate``,
    ///     ``damping``, ``springs``, ``friction``, ``position_limits``, ``friction_smoothing``,
    ///     ``limit_time_constant``, ``limit_damping_ratio``).
    /// disturbances: :class:`Disturbance` wrenches on links during time windows.
    /// record_every: keep every k-th step; frames: frames whose poses are recorded.
    /// Returns a :class:`SimResult` (arrays ``t``, ``q``, ``v``, ``a``, ``tau``, energies, poses).
    // The text signature shows the defaults `()` of the two sequences, which are no literals in
    // Rust.
    #[pyo3(
        signature = (q0, v0 = None, *, duration = 1.0, dt = 1e-3, controller = None, integrator = "rk4", rtol = 1e-8, atol = 1e-10, method = "aba", effects = None, disturbances = empty_tuple(), record_every = 1, frames = empty_tuple(), progress = None),
        text_signature = "($self, q0, v0=None, *, duration=1.0, dt=0.001, controller=None, integrator='rk4', rtol=1e-08, atol=1e-10, method='aba', effects=None, disturbances=(), record_every=1, frames=(), progress=None)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        q0: StateIn<'py>,
        v0: Option<StateIn<'py>>,
        #[pyo3(from_py_with = as_float)] duration: f64,
        #[pyo3(from_py_with = as_float)] dt: f64,
        controller: Option<&Bound<'py, PyAny>>,
        integrator: &str,
        #[pyo3(from_py_with = as_float)] rtol: f64,
        #[pyo3(from_py_with = as_float)] atol: f64,
        method: &str,
        effects: Option<&Bound<'py, PyAny>>,
        disturbances: Py<PyAny>,
        #[pyo3(from_py_with = as_int)] record_every: usize,
        frames: Py<PyAny>,
        progress: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let rec = self.compute(py, |c| {
            // The controller, disturbances and frames are read before the initial state (as
            // when this method was written in Python: the same error comes first).
            let run = Run {
                controller: ControllerArg::of(controller)?,
                disturbances: disturbance_specs(disturbances.bind(py))?,
                frames: frames.bind(py).try_iter()?.collect::<PyResult<_>>()?,
                duration,
                dt,
                integrator,
                rtol,
                atol,
                method,
                effects,
                record_every,
                progress,
            };
            let joints = [arg(&q0, "q0"), optional(&v0, "v0")];
            c.one("simulate", joints, |[q0, v0]| {
                self.simulate_from(py, q0, v0, run)
            })
        })?;
        python_class(py, "screwdyn._results", "SimResult")?.call1((rec,))
    }

    /// Inverse dynamics along ``trajectory`` every ``dt`` seconds (end included) — how much
    /// torque it takes to accelerate from rest to a constant velocity and stop again — with
    /// peak and RMS torque per joint against the effort limits (a :class:`TorqueProfile`).
    #[pyo3(signature = (trajectory, dt = 0.01))]
    fn torque_profile<'py>(
        &self,
        py: Python<'py>,
        trajectory: &Bound<'py, PyTrajectory>,
        #[pyo3(from_py_with = as_float)] dt: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let data = self.compute(py, |_| {
            torque_profile(py, &self.model, &trajectory.borrow(), dt)
        })?;
        python_class(py, "screwdyn._results", "TorqueProfile")?.call1((data,))
    }
}

/// The arguments of `simulate` but the initial state.
struct Run<'a, 'py> {
    controller: ControllerArg<'a, 'py>,
    /// `(link, wrench, start, end, in_world)` each.
    disturbances: Vec<Bound<'py, PyAny>>,
    frames: Vec<Bound<'py, PyAny>>,
    duration: f64,
    dt: f64,
    integrator: &'a str,
    rtol: f64,
    atol: f64,
    method: &'a str,
    effects: Option<&'a Bound<'py, PyAny>>,
    record_every: usize,
    progress: Option<&'a Bound<'py, PyAny>>,
}

impl PyModel {
    /// Simulates from `(q0, v0)` as `a` says, and returns the recording as a dict.
    fn simulate_from<'py>(
        &self,
        py: Python<'py>,
        q0: &[f64],
        v0: &[f64],
        a: Run<'_, 'py>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let model = &self.model;
        let frames = a
            .frames
            .iter()
            .map(|f| self.frame(f))
            .collect::<PyResult<_>>()?;
        let dist = self.disturbances(&a.disturbances)?;
        let opts = SimOptions {
            duration: a.duration,
            dt: a.dt,
            integrator: integrator(a.integrator, a.rtol, a.atol)?,
            method: method(a.method)?,
            effects: effects(a.effects)?,
            record_every: a.record_every,
            frames,
        };
        let (q0, v0) = (q0.to_vec(), v0.to_vec());
        let rec = match self.controller(a.controller)? {
            Control::Library(ctl) if a.progress.is_none() => py
                .detach(|| {
                    let mut c = ctl.build(model)?;
                    sim::simulate(model, &q0, &v0, c.as_mut(), &dist, &opts, &mut |_| {})
                })
                .map_err(call_err)?,
            Control::Library(ctl) => {
                let mut c = ctl.build(model).map_err(call_err)?;
                let progress = a.progress;
                let perr: RefCell<Option<PyErr>> = RefCell::new(None);
                let r = sim::simulate(model, &q0, &v0, c.as_mut(), &dist, &opts, &mut |x| {
                    if let Some(p) = progress {
                        if perr.borrow().is_none() {
                            if let Err(e) = p.call1((x,)) {
                                *perr.borrow_mut() = Some(e);
                            }
                        }
                    }
                });
                if let Some(e) = perr.into_inner() {
                    return Err(e);
                }
                r.map_err(call_err)?
            }
            Control::Callable(f) => {
                let mut cb = PyCallback {
                    f,
                    error: RefCell::new(None),
                };
                let progress = a.progress;
                let r = sim::simulate(model, &q0, &v0, &mut cb, &dist, &opts, &mut |x| {
                    if let Some(p) = progress {
                        let _ = p.call1((x,));
                    }
                });
                if let Some(e) = cb.error.into_inner() {
                    return Err(e);
                }
                r.map_err(call_err)?
            }
        };
        recording(py, &rec)
    }

    /// The disturbances from their `(link, wrench, start, end, in_world)` descriptions.
    fn disturbances(&self, specs: &[Bound<'_, PyAny>]) -> PyResult<Vec<Disturbance>> {
        let mut out = Vec::new();
        for spec in specs {
            let t = spec.cast::<PyTuple>().map_err(|_| {
                PyTypeError::new_err("disturbances is a list of screwdyn.Disturbance")
            })?;
            let w: ArrayIn<'_> = t.get_item(1)?.extract()?;
            let w = fixed_states(&w, "a disturbance wrench", 6, false)?;
            let in_world: bool = t.get_item(4)?.extract()?;
            let link = self.link_frame(&t.get_item(0)?)?;
            let w = Vector6::from_column_slice(w.row(0));
            let (body, wrench) =
                link_wrench_on_body(&self.model, link, w, in_world).map_err(call_err)?;
            out.push(Disturbance {
                body,
                wrench,
                start: t.get_item(2)?.extract()?,
                end: t.get_item(3)?.extract()?,
                in_world,
            });
        }
        Ok(out)
    }

    /// The controller of a run from its argument.
    fn controller<'a, 'py>(&self, c: ControllerArg<'a, 'py>) -> PyResult<Control<'a, 'py>> {
        Ok(match c {
            ControllerArg::Zero => Control::Library(ControllerSpec::Zero),
            ControllerArg::Spec(spec) => Control::Library(self.library_controller(&spec)?),
            ControllerArg::Callable(f) => Control::Callable(f),
            ControllerArg::Constant(torque) => {
                let torque = joint_vector(&self.model, &torque, "the constant torque")?;
                Control::Library(ControllerSpec::Constant(torque))
            }
        })
    }

    /// A controller of the library from its `(kind, arguments…)` description.
    fn library_controller(&self, spec: &Bound<'_, PyTuple>) -> PyResult<ControllerSpec> {
        let kind: String = spec.get_item(0)?.extract()?;
        let m = &self.model;
        let jv = |i: usize, name: &'static str| -> PyResult<Vec<f64>> {
            let a: ArrayIn<'_> = spec.get_item(i)?.extract()?;
            joint_vector(m, &a, name)
        };
        // Optional gains: `None` takes the library's defaults.
        let gain = |i: usize, name: &'static str| -> PyResult<Option<Vec<f64>>> {
            let g = spec.get_item(i)?;
            (!g.is_none()).then(|| jv(i, name)).transpose()
        };
        Ok(match kind.as_str() {
            "constant" => ControllerSpec::Constant(jv(1, "the constant torque")?),
            "pd" => ControllerSpec::PdGravity {
                target: jv(1, "the PD target")?,
                kp: gain(2, "kp")?,
                kd: gain(3, "kd")?,
            },
            "computed_torque" => {
                let t = spec.get_item(1)?;
                let t = t.cast::<PyTrajectory>().map_err(|_| {
                    PyTypeError::new_err(
                        "computed-torque control needs a screwdyn.Trajectory as reference",
                    )
                })?;
                ControllerSpec::ComputedTorque {
                    reference: t.get().traj.clone().boxed(),
                    kp: gain(2, "kp")?,
                    kd: gain(3, "kd")?,
                }
            }
            "series" => {
                let t: ArrayIn<'_> = spec.get_item(1)?.extract()?;
                let times = values_1d(&t, "times")?;
                let v: ArrayIn<'_> = spec.get_item(2)?.extract()?;
                if v.ndim() != 2 {
                    return Err(PyValueError::new_err(
                        "torque series values must have shape (K, nq): one torque row per time",
                    ));
                }
                let rows = convert::rows_of(&v);
                ControllerSpec::Series {
                    times,
                    values: rows,
                }
            }
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown controller kind '{other}'"
                )))
            }
        })
    }
}

/// The `disturbances` argument: `screwdyn.Disturbance`s (described by their `_spec()`), or
/// their descriptions.
fn disturbance_specs<'py>(ds: &Bound<'py, PyAny>) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let class = python_class(ds.py(), "screwdyn", "Disturbance")?;
    ds.try_iter()?
        .map(|d| {
            let d = d?;
            if d.is_instance(&class)? {
                d.call_method0("_spec")
            } else {
                Ok(d)
            }
        })
        .collect()
}

/// The `controller` argument as given: `None` (zero torque), one of the package's controller
/// classes (`PD`, `ComputedTorque`, `TorqueSeries`, `ConstantTorque`: each describes itself by
/// `_spec()` as `(kind, arguments…)`), a callable `f(t, q, v) -> tau`, or an array of constant
/// torques.
enum ControllerArg<'a, 'py> {
    Zero,
    Spec(Bound<'py, PyTuple>),
    Callable(&'a Bound<'py, PyAny>),
    Constant(ArrayIn<'py>),
}

impl<'a, 'py> ControllerArg<'a, 'py> {
    fn of(c: Option<&'a Bound<'py, PyAny>>) -> PyResult<Self> {
        let Some(c) = c.filter(|c| !c.is_none()) else {
            return Ok(ControllerArg::Zero);
        };
        if c.hasattr("_spec")? {
            let spec = c.call_method0("_spec")?;
            let spec = spec
                .cast_into::<PyTuple>()
                .map_err(|_| PyTypeError::new_err(CONTROLLERS))?;
            return Ok(ControllerArg::Spec(spec));
        }
        if c.is_callable() {
            return Ok(ControllerArg::Callable(c));
        }
        Ok(ControllerArg::Constant(c.extract()?))
    }
}

/// A joint vector of a controller: one value per joint or one number for all of them.
fn joint_vector(m: &Model, a: &ArrayIn<'_>, name: &'static str) -> PyResult<Vec<f64>> {
    convert::model_per_joint(m, a, name)
}

/// The controller of a run: one the library builds (and runs with the GIL released), or a
/// Python callable.
enum Control<'a, 'py> {
    Library(ControllerSpec),
    Callable(&'a Bound<'py, PyAny>),
}

/// A Python callable `f(t, q, v) -> tau` as a controller.
struct PyCallback<'a, 'py> {
    f: &'a Bound<'py, PyAny>,
    error: RefCell<Option<PyErr>>,
}

impl Controller for PyCallback<'_, '_> {
    fn torque(&mut self, t: f64, q: &[f64], v: &[f64], tau: &mut [f64]) -> screwdyn::Result<()> {
        let py = self.f.py();
        let out = (|| -> PyResult<()> {
            let r = self.f.call1((t, vector(py, q)?, vector(py, v)?))?;
            let arr: ArrayIn<'_> = r.extract().map_err(|_| {
                PyTypeError::new_err("the controller must return an array of joint torques")
            })?;
            let s = fixed_states(&arr, "the controller's torque", tau.len(), false)?;
            tau.copy_from_slice(s.row(0));
            Ok(())
        })();
        out.map_err(|e| {
            *self.error.borrow_mut() = Some(e);
            screwdyn::Error::InvalidArgument("the Python controller raised an exception".into())
        })
    }
}

/// The `integrator` argument, with the tolerances of the adaptive one.
fn integrator(s: &str, rtol: f64, atol: f64) -> PyResult<Integrator> {
    let i = s.parse::<Integrator>().map_err(call_err)?;
    Ok(match i {
        Integrator::DormandPrince { .. } => Integrator::DormandPrince { rtol, atol },
        other => other,
    })
}

/// The `effects` argument: `None`/`True` (the library's defaults), `False` (none) or a dict of
/// `JointEffects` fields.
fn effects(e: Option<&Bound<'_, PyAny>>) -> PyResult<JointEffects> {
    let Some(e) = e.filter(|e| !e.is_none()) else {
        return Ok(JointEffects::default());
    };
    if let Ok(b) = e.extract::<bool>() {
        let mut x = JointEffects::default();
        if !b {
            x.saturate = false;
            x.damping = false;
            x.springs = false;
            x.friction = false;
            x.position_limits = false;
        }
        return Ok(x);
    }
    let d = e.cast::<PyDict>().map_err(|_| {
        PyTypeError::new_err("effects is True (all), False (none) or a dict of JointEffects fields")
    })?;
    let mut x = JointEffects::default();
    for (k, v) in d.iter() {
        let key: String = k.extract()?;
        match key.as_str() {
            "saturate" => x.saturate = v.extract()?,
            "damping" => x.damping = v.extract()?,
            "springs" => x.springs = v.extract()?,
            "friction" => x.friction = v.extract()?,
            "position_limits" => x.position_limits = v.extract()?,
            "friction_smoothing" => x.friction_smoothing = v.extract()?,
            "limit_time_constant" => x.limit_time_constant = v.extract()?,
            "limit_damping_ratio" => x.limit_damping_ratio = v.extract()?,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown joint effect '{other}' (known: saturate, damping, springs, friction, position_limits, friction_smoothing, limit_time_constant, limit_damping_ratio)"
                )))
            }
        }
    }
    Ok(x)
}

/// A library recording as the dict `screwdyn.SimResult` wraps.
fn recording<'py>(py: Python<'py>, r: &Recording) -> PyResult<Bound<'py, PyDict>> {
    let n = r.joints.len();
    let d = PyDict::new(py);
    d.set_item("joints", &r.joints)?;
    d.set_item("t", vector(py, &r.t)?)?;
    d.set_item("q", rows_array(py, &r.q, n)?)?;
    d.set_item("v", rows_array(py, &r.v, n)?)?;
    d.set_item("a", rows_array(py, &r.a, n)?)?;
    d.set_item("tau", rows_array(py, &r.tau, n)?)?;
    d.set_item("kinetic_energy", vector(py, &r.kinetic_energy)?)?;
    d.set_item("potential_energy", vector(py, &r.potential_energy)?)?;
    d.set_item("total_energy", vector(py, &r.total_energy)?)?;
    let poses = PyDict::new(py);
    for (f, name) in r.frames.iter().enumerate() {
        let mut out = vec![0.0; r.poses.len() * 16];
        for (k, o) in out.chunks_mut(16).enumerate() {
            convert::write_pose(&r.poses[k][f], o);
        }
        poses.set_item(name, convert::array(py, out, &[r.poses.len(), 4, 4])?)?;
    }
    d.set_item("poses", poses)?;
    // What happened at the position limits (a start outside them, each limit-stop contact).
    let events = PyList::empty(py);
    for e in &r.events {
        let x = PyDict::new(py);
        x.set_item("kind", e.kind.name())?;
        x.set_item("t", e.t)?;
        x.set_item("joint", &e.joint_name)?;
        x.set_item("side", e.side.name())?;
        x.set_item("bound", e.bound)?;
        x.set_item("position", e.position)?;
        x.set_item("velocity", e.velocity)?;
        events.append(x)?;
    }
    d.set_item("events", events)?;
    Ok(d)
}

/// The library's torque profile along `t` as the dict `screwdyn.TorqueProfile` wraps.
fn torque_profile<'py>(
    py: Python<'py>,
    model: &Model,
    t: &PyTrajectory,
    dt: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let p = py
        .detach(|| sim::torque_profile(model, t.traj.get(), dt))
        .map_err(call_err)?;
    let d = PyDict::new(py);
    d.set_item("samples", recording(py, &p.samples)?)?;
    d.set_item("peak", vector(py, &p.peak)?)?;
    d.set_item("peak_time", vector(py, &p.peak_time)?)?;
    let summary = PyDict::new(py);
    for (j, v) in p.violation_summary.iter().enumerate() {
        if let Some(v) = v {
            let e = PyDict::new(py);
            e.set_item("count", v.count)?;
            e.set_item("first_time", v.first_time)?;
            e.set_item("worst", v.worst)?;
            summary.set_item(model.joint_names()[j], e)?;
        }
    }
    d.set_item("violation_summary", summary)?;
    d.set_item("rms", vector(py, &p.rms)?)?;
    d.set_item("effort_limit", vector(py, &p.effort_limit)?)?;
    let names = model.joint_names();
    let v = PyList::empty(py);
    for x in &p.violations {
        let e = PyDict::new(py);
        e.set_item("joint", names[x.joint])?;
        e.set_item("t", x.t)?;
        e.set_item("tau", x.tau)?;
        e.set_item("limit", x.limit)?;
        v.append(e)?;
    }
    d.set_item("violations", v)?;
    Ok(d)
}
