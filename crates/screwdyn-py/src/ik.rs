//! `Model.inverse_kinematics` and `Model.inverse_kinematics_all`: the library's
//! `kinematics::ik` solver on one `(4, 4)` target or `(N, 4, 4)` stacked ones.

use crate::convert::{self, python_class, ArrayIn, Values};
use crate::errors::{call_err, guard};
use crate::model::PyModel;
use nalgebra::Matrix4;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use screwdyn::kinematics::ik::{
    default_start, target_from_matrix, IkOptions, IkResult, IkSolver, IkTask, IkWorkspace,
};
use screwdyn::spatial::Se3;

/// The targets of an `(4, 4)` or `(N, 4, 4)` array, and whether they were stacked.
fn targets(target: &ArrayIn<'_>) -> PyResult<(Vec<Se3>, bool)> {
    let shape = target.shape().to_vec();
    let stacked = match shape.as_slice() {
        [4, 4] => false,
        [_, 4, 4] => true,
        _ => {
            return Err(PyValueError::new_err(format!(
                "target must be a (4, 4) homogeneous matrix or an (N, 4, 4) array of them, got shape {shape:?}"
            )))
        }
    };
    let values = target.values();
    let poses = values
        .chunks(16)
        .enumerate()
        .map(|(k, m)| {
            let what = if stacked {
                format!("target {k}")
            } else {
                "target".to_string()
            };
            target_from_matrix(&Matrix4::from_row_slice(m), &what).map_err(call_err)
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((poses, stacked))
}

/// The results as the dict `screwdyn._results.IkResult` is made from: NumPy arrays made from
/// the columns without a copy (a batch's per-target Python objects would cost as much as a
/// closed-form solve each), `failure` a list.
fn fill<'py>(d: &Bound<'py, PyDict>, results: &[IkResult]) -> PyResult<()> {
    let py = d.py();
    let floats = |f: fn(&IkResult) -> f64| {
        numpy::PyArray1::from_vec(py, results.iter().map(f).collect::<Vec<_>>())
    };
    let counts = |f: fn(&IkResult) -> usize| {
        numpy::PyArray1::from_vec(py, results.iter().map(|r| f(r) as i64).collect::<Vec<_>>())
    };
    d.set_item(
        "success",
        numpy::PyArray1::from_vec(py, results.iter().map(|r| r.success).collect::<Vec<_>>()),
    )?;
    d.set_item("iterations", counts(|r| r.iterations))?;
    d.set_item("restarts", counts(|r| r.restarts))?;
    d.set_item("position_error", floats(|r| r.position_error))?;
    d.set_item("orientation_error", floats(|r| r.orientation_error))?;
    let failure: Vec<Option<&str>> = results
        .iter()
        .map(|r| r.failure.map(|f| f.name()))
        .collect();
    d.set_item("failure", failure)?;
    Ok(())
}

/// What makes two solvers the same: the frame, the task and every option the Python call sets.
#[derive(Clone, Copy, PartialEq)]
struct SolverKey {
    frame: usize,
    position_only: bool,
    seed: u64,
    position_tolerance: f64,
    orientation_tolerance: f64,
    max_iterations: usize,
    max_restarts: usize,
}

/// A solver kept by the model between calls, with its workspace.
pub(crate) struct CachedSolver {
    key: SolverKey,
    solver: IkSolver,
    ws: IkWorkspace,
}

impl PyModel {
    /// Runs `f` with the solver of `frame` (full pose, or position only) and the keyword
    /// options, and a workspace: the model's cached one when the frame and options match the
    /// last call's (and no other thread holds it), else a new one, kept for the next call.
    #[allow(clippy::too_many_arguments)]
    fn with_ik_solver<R>(
        &self,
        frame: &Bound<'_, PyAny>,
        position_only: bool,
        seed: u64,
        position_tolerance: Option<f64>,
        orientation_tolerance: Option<f64>,
        max_iterations: Option<usize>,
        max_restarts: Option<usize>,
        f: impl FnOnce(&IkSolver, &mut IkWorkspace) -> PyResult<R>,
    ) -> PyResult<R> {
        let d = IkOptions::default();
        let key = SolverKey {
            frame: self.frame(frame)?,
            position_only,
            seed,
            position_tolerance: position_tolerance.unwrap_or(d.position_tolerance),
            orientation_tolerance: orientation_tolerance.unwrap_or(d.orientation_tolerance),
            max_iterations: max_iterations.unwrap_or(d.max_iterations),
            max_restarts: max_restarts.unwrap_or(d.max_restarts),
        };
        let build = || -> PyResult<CachedSolver> {
            let task = if key.position_only {
                IkTask::position(key.frame)
            } else {
                IkTask::pose(key.frame)
            };
            let options = IkOptions {
                seed: key.seed,
                position_tolerance: key.position_tolerance,
                orientation_tolerance: key.orientation_tolerance,
                max_iterations: key.max_iterations,
                max_restarts: key.max_restarts,
                ..IkOptions::default()
            };
            let solver = IkSolver::new(&self.model, &[task], options).map_err(call_err)?;
            let ws = IkWorkspace::new(&solver);
            Ok(CachedSolver { key, solver, ws })
        };
        match self.ik_cache.try_lock() {
            Ok(mut cache) => {
                if !cache.as_ref().is_some_and(|c| c.key == key) {
                    *cache = Some(build()?);
                }
                let c = cache.as_mut().expect("filled above");
                f(&c.solver, &mut c.ws)
            }
            // Another thread is solving with the cached solver: a fresh one for this call.
            Err(_) => {
                let mut c = build()?;
                f(&c.solver, &mut c.ws)
            }
        }
    }

    /// `q0` as given (`(nq,)`, or `(N, nq)` for `count` stacked targets), or the default start.
    fn ik_start(&self, q0: Option<&ArrayIn<'_>>, count: Option<usize>) -> PyResult<Vec<f64>> {
        let n = self.model.nq();
        let Some(q0) = q0 else {
            return Ok(default_start(&self.model));
        };
        let shape = q0.shape().to_vec();
        let fits = match (shape.as_slice(), count) {
            ([m], _) => *m == n,
            ([k, m], Some(c)) => *k == c && *m == n,
            _ => false,
        };
        if !fits {
            let expected = match count {
                Some(c) => format!("({n},) or ({c}, {n})"),
                None => format!("({n},)"),
            };
            return Err(PyValueError::new_err(format!(
                "q0 has shape {shape:?}, expected {expected} for the model's {n} joints"
            )));
        }
        Ok(q0.values().into_owned())
    }
}

#[pymethods]
impl PyModel {
    /// Inverse kinematics: joint positions that put `frame` (name or index) at `target`, a
    /// `(4, 4)` homogeneous matrix in the world frame, or at each of `(N, 4, 4)` stacked ones.
    ///
    /// Levenberg–Marquardt with error-scaled damping on the body-frame pose error, joint
    /// limits kept at every step, seeded random restarts, started from the closed-form
    /// solution nearest `q0` on arms that have one (docs/ik.md). `q0`: `(nq,)` for all, or
    /// `(N, nq)` one per target; default each joint at 0, or at the nearer limit when 0 lies
    /// outside them. `position_only=True` places the frame's origin only. `seed` makes the
    /// restarts repeatable; a batch runs on `threads` threads (default: all cores) with the
    /// GIL released, each answer the same whatever the thread count.
    ///
    /// Returns an `IkResult`: `q` (`(nq,)` or `(N, nq)`), `success`, `iterations`,
    /// `restarts`, `position_error` (m), `orientation_error` (rad) and `failure` (`None`, or
    /// `"unreachable"`, `"limits"`, `"budget"`), scalars for one target and arrays for a
    /// batch. `success` is true only when forward kinematics of `q` is within both
    /// tolerances and every joint within its limits; an unreachable target is not an error.
    ///
    /// Raises `ValueError` for a rotation that is not orthonormal, a bottom row that is not
    /// `(0, 0, 0, 1)`, NaN, a `q0` outside the limits or of the wrong shape, an unknown frame.
    #[pyo3(signature = (frame, target, q0 = None, *, seed = 0, threads = None,
        position_only = false, position_tolerance = None, orientation_tolerance = None,
        max_iterations = None, max_restarts = None))]
    #[allow(clippy::too_many_arguments)]
    fn inverse_kinematics<'py>(
        &self,
        py: Python<'py>,
        frame: &Bound<'py, PyAny>,
        target: ArrayIn<'py>,
        q0: Option<ArrayIn<'py>>,
        seed: u64,
        threads: Option<usize>,
        position_only: bool,
        position_tolerance: Option<f64>,
        orientation_tolerance: Option<f64>,
        max_iterations: Option<usize>,
        max_restarts: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let (poses, stacked) = targets(&target)?;
            let n = self.model.nq();
            let d = PyDict::new(py);
            let solve = |solver: &IkSolver, ws: &mut IkWorkspace| -> PyResult<()> {
                if !stacked {
                    let start = self.ik_start(q0.as_ref(), None)?;
                    let mut q = vec![0.0; n];
                    let result = py
                        .detach(|| solver.solve(ws, &poses, &start, &mut q))
                        .map_err(call_err)?;
                    d.set_item("q", convert::vector(py, &q)?)?;
                    fill(&d, &[result])?;
                    d.set_item("batch", false)?;
                } else {
                    let k = poses.len();
                    let start = self.ik_start(q0.as_ref(), Some(k))?;
                    let mut q = vec![0.0; k * n];
                    let results = py
                        .detach(|| solver.solve_batch(&poses, &start, &mut q, threads.unwrap_or(0)))
                        .map_err(call_err)?
                        .into_iter()
                        .collect::<screwdyn::Result<Vec<_>>>()
                        .map_err(call_err)?;
                    d.set_item("q", convert::array(py, q, &[k, n])?)?;
                    fill(&d, &results)?;
                    d.set_item("batch", true)?;
                }
                Ok(())
            };
            self.with_ik_solver(
                frame,
                position_only,
                seed,
                position_tolerance,
                orientation_tolerance,
                max_iterations,
                max_restarts,
                solve,
            )?;
            python_class(py, "screwdyn._results", "IkResult")?.call1((d,))
        })
    }

    /// Every solution for one `(4, 4)` target: on a 6R arm with a closed form (a spherical
    /// wrist or three consecutive parallel axes, e.g. the UR5: up to 8), each closed-form
    /// branch shifted by whole turns into the joint limits, refined and checked by forward
    /// kinematics; on any other arm the one numerical answer if it succeeds. An `(M, nq)`
    /// array, nearest `q0` first (`M = 0` when the target is out of reach).
    #[pyo3(signature = (frame, target, q0 = None))]
    fn inverse_kinematics_all<'py>(
        &self,
        py: Python<'py>,
        frame: &Bound<'py, PyAny>,
        target: ArrayIn<'py>,
        q0: Option<ArrayIn<'py>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let (poses, stacked) = targets(&target)?;
            if stacked {
                return Err(PyValueError::new_err(
                    "inverse_kinematics_all takes one (4, 4) target; loop over a batch",
                ));
            }
            let start = self.ik_start(q0.as_ref(), None)?;
            let all =
                self.with_ik_solver(frame, false, 0, None, None, None, None, |solver, ws| {
                    py.detach(|| solver.solve_all(ws, &poses[0], &start))
                        .map_err(call_err)
                })?;
            let n = self.model.nq();
            let flat: Vec<f64> = all.iter().flat_map(|s| s.q.iter().copied()).collect();
            convert::array(py, flat, &[all.len(), n])
        })
    }
}
