//! `screwdyn.Trajectory` (the library's `sim` trajectories): trapezoidal velocity profiles,
//! quintics and waypoints, sampled at given times.

use crate::convert::{self, joint_count, per_joint, values_1d, vector, ArrayIn};
use crate::errors::{call_err, guard};
use crate::model::PyModel;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use screwdyn::kinematics::ik::target_from_matrix;
use screwdyn::motion::{
    cartesian_move, time_optimal, CartesianOptions, CubicSpline, JerkLimited, TimeOptimal,
    TimeOptimalOptions, TimingLimits,
};
use screwdyn::sim::{Quintic, Trajectory, Trapezoid, Waypoints};

/// The library trajectory a `Trajectory` holds.
#[derive(Clone, Debug)]
pub(crate) enum Traj {
    Trapezoid(Trapezoid),
    Quintic(Quintic),
    Waypoints(Waypoints),
    TimeOptimal(Box<TimeOptimal<CubicSpline>>),
    JerkLimited(JerkLimited),
}

impl Traj {
    /// The trajectory (`Sync`, for a call with the GIL released).
    pub(crate) fn get(&self) -> &(dyn Trajectory + Sync) {
        match self {
            Traj::Trapezoid(t) => t,
            Traj::Quintic(t) => t,
            Traj::Waypoints(t) => t,
            Traj::TimeOptimal(t) => t.as_ref(),
            Traj::JerkLimited(t) => t,
        }
    }

    /// The trajectory as a box, for a controller that tracks it.
    pub(crate) fn boxed(self) -> Box<dyn Trajectory + Send> {
        match self {
            Traj::Trapezoid(t) => Box::new(t),
            Traj::Quintic(t) => Box::new(t),
            Traj::Waypoints(t) => Box::new(t),
            Traj::TimeOptimal(t) => t,
            Traj::JerkLimited(t) => Box::new(t),
        }
    }
}

/// A joint-space trajectory (from rest to constant velocity, and then back to stop, through
/// waypoints, or timed to the limits): make one with `Trajectory.trapezoid`,
/// `Trajectory.quintic`, `Trajectory.waypoints`, `Trajectory.time_optimal` or
/// `Trajectory.jerk_limited`; sample it with `sample(t)`.
#[pyclass(name = "Trajectory", module = "screwdyn._screwdyn", frozen)]
pub(crate) struct PyTrajectory {
    pub(crate) traj: Traj,
    kind: &'static str,
}

#[pymethods]
impl PyTrajectory {
    /// Trapezoidal velocity profiles from `q0` to `qf` under per-joint velocity and
    /// acceleration limits (positive); `synchronised=True` makes every joint arrive together.
    /// Each argument is one value per joint or one number for all of them.
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
            let n = joint_count(&[&q0, &qf]);
            let t = Trapezoid::new(
                &per_joint(&q0, "q0", n)?,
                &per_joint(&qf, "qf", n)?,
                &per_joint(&vmax, "vmax", n)?,
                &per_joint(&amax, "amax", n)?,
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
    /// seconds (velocities and accelerations default to zero: rest to rest). Each argument is one
    /// value per joint or one number for all of them.
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
            let n = joint_count(&[&q0, &qf]);
            let q0 = per_joint(&q0, "q0", n)?;
            let qf = per_joint(&qf, "qf", n)?;
            let opt = |x: &Option<ArrayIn<'_>>, name| match x {
                Some(a) => per_joint(a, name, n),
                None => Ok(vec![0.0; n]),
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
            let times = values_1d(&times, "times")?;
            if points.ndim() != 2 {
                return Err(PyValueError::new_err(
                    "points must have shape (K, nq): one row per waypoint",
                ));
            }
            let rows = convert::rows_of(&points);
            let t = Waypoints::new(&times, &rows).map_err(call_err)?;
            Ok(PyTrajectory {
                traj: Traj::Waypoints(t),
                kind: "waypoints",
            })
        })
    }

    /// The fastest timing of the cubic spline (not-a-knot) through `waypoints` (shape
    /// `(K, nq)`) at path parameters `s` (default: the chord length), from rest to rest within
    /// the joint velocity limits `vmax` (default: the model's), acceleration limits `amax`
    /// (default: none) and effort limits `effort` (default: the model's); `inf` means no
    /// limit. TOPP-RA on a grid refined until the duration converges (or `grid` intervals).
    #[staticmethod]
    #[pyo3(signature = (model, waypoints, s = None, vmax = None, amax = None, effort = None, grid = None))]
    #[allow(clippy::too_many_arguments)]
    fn time_optimal(
        model: &PyModel,
        waypoints: ArrayIn<'_>,
        s: Option<ArrayIn<'_>>,
        vmax: Option<ArrayIn<'_>>,
        amax: Option<ArrayIn<'_>>,
        effort: Option<ArrayIn<'_>>,
        grid: Option<usize>,
    ) -> PyResult<Self> {
        use numpy::PyUntypedArrayMethods;
        guard(|| {
            let m = &model.model;
            if waypoints.ndim() != 2 {
                return Err(PyValueError::new_err(
                    "waypoints must have shape (K, nq): one row per waypoint",
                ));
            }
            let rows = convert::rows_of(&waypoints);
            let s = s.map(|s| values_1d(&s, "s")).transpose()?;
            let mut limits = TimingLimits::from_model(m);
            for (x, name, slot) in [
                (&vmax, "vmax", &mut limits.velocity),
                (&amax, "amax", &mut limits.acceleration),
                (&effort, "effort", &mut limits.effort),
            ] {
                if let Some(x) = x {
                    *slot = values_1d(x, name)?;
                }
            }
            let options = TimeOptimalOptions {
                grid,
                ..Default::default()
            };
            let path = CubicSpline::for_model(m, s.as_deref(), &rows).map_err(call_err)?;
            let timed = time_optimal(m, path, &limits, &options).map_err(call_err)?;
            Ok(PyTrajectory {
                traj: Traj::TimeOptimal(Box::new(timed)),
                kind: "time_optimal",
            })
        })
    }

    /// Jerk-limited motion from rest at `q0` to rest at `qf`: per joint the fastest
    /// seven-segment profile within `vmax`, `amax` and `jmax` (positive), every joint
    /// stretched in time to finish with the slowest.
    #[staticmethod]
    fn jerk_limited(
        q0: ArrayIn<'_>,
        qf: ArrayIn<'_>,
        vmax: ArrayIn<'_>,
        amax: ArrayIn<'_>,
        jmax: ArrayIn<'_>,
    ) -> PyResult<Self> {
        guard(|| {
            let t = JerkLimited::new(
                &values_1d(&q0, "q0")?,
                &values_1d(&qf, "qf")?,
                &values_1d(&vmax, "vmax")?,
                &values_1d(&amax, "amax")?,
                &values_1d(&jmax, "jmax")?,
            )
            .map_err(call_err)?;
            Ok(PyTrajectory {
                traj: Traj::JerkLimited(t),
                kind: "jerk_limited",
            })
        })
    }

    /// `frame` (name or index) in a straight line from its pose at `q0` to the pose `target`
    /// (a `(4, 4)` array, world frame), orientation by slerp, solved by the inverse kinematics
    /// every 1 mm / 0.01 rad and timed as fast as the model's velocity and effort limits and
    /// the tool speed limit `speed` (m/s, default none) allow. A point out of reach, a joint
    /// limit or a singularity on the way raises `ValueError` naming the position on the path.
    #[staticmethod]
    #[pyo3(signature = (model, frame, q0, target, speed = None))]
    fn linear(
        model: &PyModel,
        frame: &Bound<'_, PyAny>,
        q0: ArrayIn<'_>,
        target: ArrayIn<'_>,
        speed: Option<f64>,
    ) -> PyResult<Self> {
        cartesian(model, frame, q0, target, None, speed)
    }

    /// As `linear`, on the circular arc through the point `via` (3 values, m, world frame).
    #[staticmethod]
    #[pyo3(signature = (model, frame, q0, via, target, speed = None))]
    fn circular(
        model: &PyModel,
        frame: &Bound<'_, PyAny>,
        q0: ArrayIn<'_>,
        via: ArrayIn<'_>,
        target: ArrayIn<'_>,
        speed: Option<f64>,
    ) -> PyResult<Self> {
        cartesian(model, frame, q0, target, Some(via), speed)
    }

    /// Time-optimal timings only: the phase-plane curve `(s_i, ṡ_i)` at the grid points, and
    /// the times `t_i` at which they are passed, three arrays `(N + 1,)`.
    fn phase_plane<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        match &self.traj {
            Traj::TimeOptimal(t) => {
                let sd: Vec<f64> = t.speed_squared().iter().map(|x| x.sqrt()).collect();
                PyTuple::new(
                    py,
                    [
                        vector(py, t.grid())?,
                        vector(py, &sd)?,
                        vector(py, t.times())?,
                    ],
                )
            }
            _ => Err(PyTypeError::new_err(format!(
                "phase_plane is defined for time-optimal timings, this is a {} trajectory",
                self.kind
            ))),
        }
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
            let times = convert::contiguous(&t).into_owned();
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

/// `Trajectory.linear` and `Trajectory.circular`: the library's `cartesian_move`.
fn cartesian(
    model: &PyModel,
    frame: &Bound<'_, PyAny>,
    q0: ArrayIn<'_>,
    target: ArrayIn<'_>,
    via: Option<ArrayIn<'_>>,
    speed: Option<f64>,
) -> PyResult<PyTrajectory> {
    guard(|| {
        let m = &model.model;
        let frame = model.frame(frame)?;
        let q0 = values_1d(&q0, "q0")?;
        let t = convert::contiguous(&target).into_owned();
        if t.len() != 16 {
            return Err(PyValueError::new_err(format!(
                "target must be a (4, 4) pose, it has {} values",
                t.len()
            )));
        }
        let target = target_from_matrix(&nalgebra::Matrix4::from_row_slice(&t), "target")
            .map_err(call_err)?;
        let via = match via {
            Some(v) => {
                let v = values_1d(&v, "via")?;
                if v.len() != 3 {
                    return Err(PyValueError::new_err(format!(
                        "via must be a point x, y, z, it has {} values",
                        v.len()
                    )));
                }
                Some(nalgebra::Vector3::new(v[0], v[1], v[2]))
            }
            None => None,
        };
        let options = CartesianOptions {
            tool_speed: speed.unwrap_or(f64::INFINITY),
            ..Default::default()
        };
        let limits = TimingLimits::from_model(m);
        let motion =
            cartesian_move(m, frame, &q0, &target, via, &limits, &options).map_err(call_err)?;
        Ok(PyTrajectory {
            traj: Traj::TimeOptimal(Box::new(motion.timing().clone())),
            kind: if via.is_some() { "circular" } else { "linear" },
        })
    })
}
