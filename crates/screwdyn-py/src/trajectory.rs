//! `screwdyn.Trajectory` (the library's `sim` trajectories): trapezoidal velocity profiles,
//! quintics and waypoints, sampled at given times.

use crate::convert::{self, joint_count, per_joint, values_1d, vector, ArrayIn};
use crate::errors::{call_err, guard};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use screwdyn::sim::{Quintic, Trajectory, Trapezoid, Waypoints};

/// The library trajectory a `Trajectory` holds.
#[derive(Clone, Debug)]
pub(crate) enum Traj {
    Trapezoid(Trapezoid),
    Quintic(Quintic),
    Waypoints(Waypoints),
}

impl Traj {
    /// The trajectory (`Sync`, for a call with the GIL released).
    pub(crate) fn get(&self) -> &(dyn Trajectory + Sync) {
        match self {
            Traj::Trapezoid(t) => t,
            Traj::Quintic(t) => t,
            Traj::Waypoints(t) => t,
        }
    }

    /// The trajectory as a box, for a controller that tracks it.
    pub(crate) fn boxed(self) -> Box<dyn Trajectory + Send> {
        match self {
            Traj::Trapezoid(t) => Box::new(t),
            Traj::Quintic(t) => Box::new(t),
            Traj::Waypoints(t) => Box::new(t),
        }
    }
}

/// A joint-space trajectory (from rest to constant velocity, and then back to stop, or through
/// waypoints): make one with `Trajectory.trapezoid`, `Trajectory.quintic` or
/// `Trajectory.waypoints`; sample it with `sample(t)`.
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
