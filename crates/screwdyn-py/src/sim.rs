//! Simulation, trajectories and torque profiles. Built-in controllers run with the GIL
//! released; a Python callable as controller is called with the GIL held, and an exception it
//! raises ends the simulation and propagates unchanged.

use crate::convert::{self, fixed_states, joint_states, rows_array, vector, ArrayIn};
use crate::errors::{call_err, guard};
use crate::model::{method, PyModel};
use nalgebra::Vector6;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use screwdyn::sim::{
    self, ComputedTorque, ConstantTorque, Controller, Disturbance, Integrator, JointEffects,
    PdGravity, Quintic, Recording, SimOptions, TorqueSeries, Trajectory, Trapezoid, Waypoints,
    ZeroTorque,
};
use screwdyn::Model;
use std::cell::RefCell;

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyTrajectory>()
}

#[derive(Clone, Debug)]
enum Traj {
    Trapezoid(Trapezoid),
    Quintic(Quintic),
    Waypoints(Waypoints),
}

impl Traj {
    fn get(&self) -> &dyn Trajectory {
        match self {
            Traj::Trapezoid(t) => t,
            Traj::Quintic(t) => t,
            Traj::Waypoints(t) => t,
        }
    }

    fn boxed(self) -> Box<dyn Trajectory> {
        match self {
            Traj::Trapezoid(t) => Box::new(t),
            Traj::Quintic(t) => Box::new(t),
            Traj::Waypoints(t) => Box::new(t),
        }
    }
}

fn vec1(a: &ArrayIn<'_>, name: &'static str) -> PyResult<Vec<f64>> {
    use numpy::PyUntypedArrayMethods;
    if a.ndim() != 1 {
        return Err(PyValueError::new_err(format!(
            "{name} must be a 1-D array (one value per joint), got {} dimensions",
            a.ndim()
        )));
    }
    Ok(a.as_array().iter().copied().collect())
}

/// A joint-space trajectory (seed 003's "from rest to constant velocity, and then back to
/// stop"): make one with `Trajectory.trapezoid`, `Trajectory.quintic` or
/// `Trajectory.waypoints`; sample it with `sample(t)`.
#[pyclass(name = "Trajectory", module = "screwdyn._screwdyn", frozen)]
pub struct PyTrajectory {
    traj: Traj,
    kind: &'static str,
}

#[pymethods]
impl PyTrajectory {
    /// Trapezoidal velocity profiles from `q0` to `qf` under per-joint velocity and
    /// acceleration limits (positive); `synchronised=True` makes every joint arrive together.
    #[staticmethod]
    #[pyo3(signature = (q0, qf, vmax, amax, synchronised = true))]
    fn trapezoid(
        q0: ArrayIn<'_>,
        qf: ArrayIn<'_>,
        vmax: ArrayIn<'_>,
        amax: ArrayIn<'_>,
        synchronised: bool,
    ) -> PyResult<Self> {
        guard(|| {
            let t = Trapezoid::new(
                &vec1(&q0, "q0")?,
                &vec1(&qf, "qf")?,
                &vec1(&vmax, "vmax")?,
                &vec1(&amax, "amax")?,
                synchronised,
            )
            .map_err(call_err)?;
            Ok(PyTrajectory {
                traj: Traj::Trapezoid(t),
                kind: "trapezoid",
            })
        })
    }

    /// A quintic polynomial per joint from `(q0, v0, a0)` to `(qf, vf, af)` in `duration`
    /// seconds (velocities and accelerations default to zero: rest to rest).
    #[staticmethod]
    #[pyo3(signature = (q0, qf, duration, v0 = None, vf = None, a0 = None, af = None))]
    #[allow(clippy::too_many_arguments)]
    fn quintic(
        q0: ArrayIn<'_>,
        qf: ArrayIn<'_>,
        duration: f64,
        v0: Option<ArrayIn<'_>>,
        vf: Option<ArrayIn<'_>>,
        a0: Option<ArrayIn<'_>>,
        af: Option<ArrayIn<'_>>,
    ) -> PyResult<Self> {
        guard(|| {
            let q0 = vec1(&q0, "q0")?;
            let qf = vec1(&qf, "qf")?;
            let zero = vec![0.0; q0.len()];
            let opt = |x: &Option<ArrayIn<'_>>, name| match x {
                Some(a) => vec1(a, name),
                None => Ok(zero.clone()),
            };
            let (v0, vf, a0, af) = (
                opt(&v0, "v0")?,
                opt(&vf, "vf")?,
                opt(&a0, "a0")?,
                opt(&af, "af")?,
            );
            let t = Quintic::new((&q0, &v0, &a0), (&qf, &vf, &af), duration).map_err(call_err)?;
            Ok(PyTrajectory {
                traj: Traj::Quintic(t),
                kind: "quintic",
            })
        })
    }

    /// Piecewise quintics through `points` (shape `(K, nq)`) at `times` (strictly increasing).
    #[staticmethod]
    fn waypoints(times: ArrayIn<'_>, points: ArrayIn<'_>) -> PyResult<Self> {
        use numpy::PyUntypedArrayMethods;
        guard(|| {
            let times = vec1(&times, "times")?;
            if points.ndim() != 2 {
                return Err(PyValueError::new_err(
                    "points must have shape (K, nq): one row per waypoint",
                ));
            }
            let p = points.as_array();
            let rows: Vec<Vec<f64>> = p
                .outer_iter()
                .map(|r| r.iter().copied().collect())
                .collect();
            let t = Waypoints::new(&times, &rows).map_err(call_err)?;
            Ok(PyTrajectory {
                traj: Traj::Waypoints(t),
                kind: "waypoints",
            })
        })
    }

    /// Duration (s).
    #[getter]
    fn duration(&self) -> f64 {
        self.traj.get().duration()
    }

    /// Number of joints.
    #[getter]
    fn nq(&self) -> usize {
        self.traj.get().nq()
    }

    /// Position, velocity and acceleration at time(s) `t` (clamped to `[0, duration]`): three
    /// arrays `(nq,)` for a scalar `t`, `(N, nq)` for an array of `N` times.
    fn sample<'py>(&self, py: Python<'py>, t: ArrayIn<'py>) -> PyResult<Bound<'py, PyTuple>> {
        use numpy::PyUntypedArrayMethods;
        guard(|| {
            let tr = self.traj.get();
            let n = tr.nq();
            let times: Vec<f64> = t.as_array().iter().copied().collect();
            let (mut q, mut v, mut a) = (
                vec![0.0; n * times.len()],
                vec![0.0; n * times.len()],
                vec![0.0; n * times.len()],
            );
            for (k, &tk) in times.iter().enumerate() {
                let r = k * n..(k + 1) * n;
                tr.sample(tk, &mut q[r.clone()], &mut v[r.clone()], &mut a[r])
                    .map_err(call_err)?;
            }
            let shape: Vec<usize> = if t.ndim() == 0 {
                vec![n]
            } else {
                vec![times.len(), n]
            };
            PyTuple::new(
                py,
                [
                    convert::array(py, q, &shape)?,
                    convert::array(py, v, &shape)?,
                    convert::array(py, a, &shape)?,
                ],
            )
        })
    }

    /// The cruise speed each joint reaches (trapezoids only).
    fn cruise_speeds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match &self.traj {
            Traj::Trapezoid(t) => vector(py, &t.cruise_speeds()),
            _ => Err(PyTypeError::new_err(format!(
                "cruise_speeds is defined for trapezoids, this is a {} trajectory",
                self.kind
            ))),
        }
    }

    fn __repr__(&self) -> String {
        let t = self.traj.get();
        format!(
            "Trajectory.{}(nq={}, duration={})",
            self.kind,
            t.nq(),
            t.duration()
        )
    }
}

/// The controller argument, parsed from the Python layer's specification.
enum Ctl {
    Zero,
    Constant(Vec<f64>),
    Pd(Vec<f64>, Vec<f64>, Vec<f64>),
    Computed(Traj, Vec<f64>, Vec<f64>),
    Series(Vec<f64>, Vec<Vec<f64>>),
}

impl Ctl {
    fn build(self, model: &Model) -> screwdyn::Result<Box<dyn Controller>> {
        Ok(match self {
            Ctl::Zero => Box::new(ZeroTorque),
            Ctl::Constant(t) => {
                model.check_vector(&t, "the constant torque")?;
                Box::new(ConstantTorque(t))
            }
            Ctl::Pd(target, kp, kd) => Box::new(PdGravity::new(model.clone(), target, kp, kd)?),
            Ctl::Computed(tr, kp, kd) => {
                Box::new(ComputedTorque::new(model.clone(), tr.boxed(), kp, kd)?)
            }
            Ctl::Series(times, values) => {
                for v in &values {
                    model.check_vector(v, "a torque of the series")?;
                }
                Box::new(TorqueSeries::new(times, values)?)
            }
        })
    }
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

pub struct SimArgs<'a, 'py> {
    pub q0: &'a [f64],
    pub v0: &'a [f64],
    pub controller: &'a Bound<'py, PyAny>,
    pub disturbances: &'a Bound<'py, PyList>,
    pub duration: f64,
    pub dt: f64,
    pub integrator: &'a str,
    pub rtol: f64,
    pub atol: f64,
    pub method: &'a str,
    pub effects: &'a Bound<'py, PyAny>,
    pub record_every: usize,
    pub frames: &'a Bound<'py, PyList>,
    pub progress: Option<Bound<'py, PyAny>>,
}

fn integrator(s: &str, rtol: f64, atol: f64) -> PyResult<Integrator> {
    let i = s
        .replace('_', "-")
        .parse::<Integrator>()
        .map_err(PyValueError::new_err)?;
    Ok(match i {
        Integrator::DormandPrince { .. } => Integrator::DormandPrince { rtol, atol },
        other => other,
    })
}

fn effects(e: &Bound<'_, PyAny>) -> PyResult<JointEffects> {
    if e.is_none() {
        return Ok(JointEffects::default());
    }
    if let Ok(b) = e.extract::<bool>() {
        let mut x = JointEffects::default();
        if !b {
            x.saturate = false;
            x.damping = false;
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
            "friction" => x.friction = v.extract()?,
            "position_limits" => x.position_limits = v.extract()?,
            "friction_smoothing" => x.friction_smoothing = v.extract()?,
            "limit_time_constant" => x.limit_time_constant = v.extract()?,
            "limit_damping_ratio" => x.limit_damping_ratio = v.extract()?,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown joint effect '{other}' (known: saturate, damping, friction, position_limits, friction_smoothing, limit_time_constant, limit_damping_ratio)"
                )))
            }
        }
    }
    Ok(x)
}

fn controller(pm: &PyModel, c: &Bound<'_, PyAny>) -> PyResult<Option<Ctl>> {
    if c.is_none() {
        return Ok(Some(Ctl::Zero));
    }
    let Ok(spec) = c.cast::<PyTuple>() else {
        return Ok(None);
    };
    let kind: String = spec.get_item(0)?.extract()?;
    let m = &pm.model;
    let jv = |i: usize, name: &'static str| -> PyResult<Vec<f64>> {
        let a: ArrayIn<'_> = spec.get_item(i)?.extract()?;
        let s = joint_states(m, &a, name)?;
        Ok(s.single("the controller")?.to_vec())
    };
    // Optional gains: `None` takes the library's defaults.
    let gains = |i: usize,
                 default: &dyn Fn() -> PyResult<(Vec<f64>, Vec<f64>)>|
     -> PyResult<(Vec<f64>, Vec<f64>)> {
        let (kp, kd) = (spec.get_item(i)?, spec.get_item(i + 1)?);
        let d = if kp.is_none() || kd.is_none() {
            Some(default()?)
        } else {
            None
        };
        let kp = if kp.is_none() {
            d.as_ref().map(|d| d.0.clone()).unwrap_or_default()
        } else {
            jv(i, "kp")?
        };
        let kd = if kd.is_none() {
            d.map(|d| d.1).unwrap_or_default()
        } else {
            jv(i + 1, "kd")?
        };
        Ok((kp, kd))
    };
    Ok(Some(match kind.as_str() {
        "constant" => Ctl::Constant(jv(1, "the constant torque")?),
        "pd" => {
            let target = jv(1, "the PD target")?;
            let (kp, kd) = gains(2, &|| {
                PdGravity::default_gains(m, &target).map_err(call_err)
            })?;
            Ctl::Pd(target, kp, kd)
        }
        "computed_torque" => {
            let t = spec.get_item(1)?;
            let t = t.cast::<PyTrajectory>().map_err(|_| {
                PyTypeError::new_err(
                    "computed-torque control needs a screwdyn.Trajectory as reference",
                )
            })?;
            let (kp, kd) = gains(2, &|| Ok(ComputedTorque::default_gains(m.nq())))?;
            Ctl::Computed(t.get().traj.clone(), kp, kd)
        }
        "series" => {
            use numpy::PyUntypedArrayMethods;
            let t: ArrayIn<'_> = spec.get_item(1)?.extract()?;
            let times = vec1(&t, "times")?;
            let v: ArrayIn<'_> = spec.get_item(2)?.extract()?;
            if v.ndim() != 2 {
                return Err(PyValueError::new_err(
                    "torque series values must have shape (K, nq): one torque row per time",
                ));
            }
            let rows = v
                .as_array()
                .outer_iter()
                .map(|r| r.iter().copied().collect())
                .collect();
            Ctl::Series(times, rows)
        }
        other => {
            return Err(PyValueError::new_err(format!(
                "unknown controller kind '{other}'"
            )))
        }
    }))
}

pub fn simulate<'py>(
    py: Python<'py>,
    pm: &PyModel,
    a: SimArgs<'_, 'py>,
) -> PyResult<Bound<'py, PyDict>> {
    let model = &pm.model;
    let mut frames = Vec::new();
    for f in a.frames.iter() {
        frames.push(pm.frame(&f)?);
    }
    let mut dist = Vec::new();
    for d in a.disturbances.iter() {
        // (link, wrench, start, end, in_world) from screwdyn.Disturbance.
        let t = d
            .cast::<PyTuple>()
            .map_err(|_| PyTypeError::new_err("disturbances is a list of screwdyn.Disturbance"))?;
        let w: ArrayIn<'_> = t.get_item(1)?.extract()?;
        let w = fixed_states(&w, "a disturbance wrench", 6, false)?;
        dist.push(Disturbance {
            body: pm.link(&t.get_item(0)?)?,
            wrench: Vector6::from_column_slice(w.row(0)),
            start: t.get_item(2)?.extract()?,
            end: t.get_item(3)?.extract()?,
            in_world: t.get_item(4)?.extract()?,
        });
    }
    if a.record_every == 0 {
        return Err(PyValueError::new_err("record_every must be at least 1"));
    }
    let opts = SimOptions {
        duration: a.duration,
        dt: a.dt,
        integrator: integrator(a.integrator, a.rtol, a.atol)?,
        method: method(a.method)?,
        effects: effects(a.effects)?,
        record_every: a.record_every,
        frames,
    };
    let (q0, v0) = (a.q0.to_vec(), a.v0.to_vec());
    let rec = match controller(pm, a.controller)? {
        Some(ctl) if a.progress.is_none() => py
            .detach(|| {
                let mut c = ctl.build(model)?;
                sim::simulate(model, &q0, &v0, c.as_mut(), &dist, &opts, &mut |_| {})
            })
            .map_err(call_err)?,
        Some(ctl) => {
            let mut c = ctl.build(model).map_err(call_err)?;
            let progress = a.progress.as_ref();
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
        None => {
            if !a.controller.is_callable() {
                return Err(PyTypeError::new_err(
                    "controller is None, an array of constant torques, screwdyn.PD, screwdyn.ComputedTorque, screwdyn.TorqueSeries or a callable f(t, q, v) -> tau",
                ));
            }
            let mut cb = PyCallback {
                f: a.controller,
                error: RefCell::new(None),
            };
            let progress = a.progress.as_ref();
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

pub fn recording<'py>(py: Python<'py>, r: &Recording) -> PyResult<Bound<'py, PyDict>> {
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
    Ok(d)
}

pub fn torque_profile<'py>(
    py: Python<'py>,
    model: &Model,
    t: &PyTrajectory,
    dt: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let p = py
        .detach(|| sim::torque_profile(model, t.traj.get_send(), dt))
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

impl Traj {
    /// The trajectory as a `Send` reference for a call with the GIL released.
    fn get_send(&self) -> &(dyn Trajectory + Sync) {
        match self {
            Traj::Trapezoid(t) => t,
            Traj::Quintic(t) => t,
            Traj::Waypoints(t) => t,
        }
    }
}
