//! The body every computing method of `Model` shares, written once: the panic guard, the
//! conversion of the joint-space arguments (`q`, `v`, `a`, `tau`…), the choice between one state
//! and `N` stacked states, and the run (over rayon's threads with the GIL released). A method
//! states only what it computes:
//!
//! ```ignore
//! self.compute(py, |c| {
//!     let f = self.frame(frame)?; // the method's other arguments, resolved first
//!     c.each(Batch { threads, out }, [arg(&q, "q")], &[4, 4], move |m, s, r, o| {
//!         kinematics::forward_kinematics(m, &mut s.ws, r[0])?;
//!         convert::write_pose(&kinematics::frame_pose(m, &s.ws, f)?, o);
//!         Ok(())
//!     })
//! })
//! ```

use crate::batch::{run, run_lanes, Batch, Rows, Scratch};
use crate::convert::{joint_states, StateIn, States};
use crate::errors::guard;
use crate::model::PyModel;
use pyo3::prelude::*;
use screwdyn::batch::{BatchWorkspace, Rows as LaneRows};
use screwdyn::Model;
use std::borrow::Cow;

/// A joint-space argument of a method, with the name its messages use; an optional argument
/// left out (`v=None`) is the zero vector.
pub(crate) struct Joint<'a, 'py> {
    value: Option<&'a StateIn<'py>>,
    name: &'static str,
}

/// A joint-space argument the caller must give.
pub(crate) fn arg<'a, 'py>(value: &'a StateIn<'py>, name: &'static str) -> Joint<'a, 'py> {
    Joint {
        value: Some(value),
        name,
    }
}

/// A joint-space argument that defaults to zero.
pub(crate) fn optional<'a, 'py>(
    value: &'a Option<StateIn<'py>>,
    name: &'static str,
) -> Joint<'a, 'py> {
    Joint {
        value: value.as_ref(),
        name,
    }
}

/// What a method's body computes through: the model (its workspace for single states) and the
/// interpreter the results go to.
pub(crate) struct Compute<'m, 'py> {
    py: Python<'py>,
    model: &'m PyModel,
}

impl PyModel {
    /// Runs a method's body under the panic guard. The body resolves the method's other
    /// arguments (frames, wrenches…) first, then computes through `Compute` (which converts the
    /// joint-space arguments in order), so an error names the first bad argument.
    pub(crate) fn compute<'py, T>(
        &self,
        py: Python<'py>,
        body: impl FnOnce(Compute<'_, 'py>) -> PyResult<T>,
    ) -> PyResult<T> {
        guard(|| body(Compute { py, model: self }))
    }
}

impl<'py> Compute<'_, 'py> {
    /// `kernel(model, scratch, rows, out)` at every state of `joints` (one, or `N` stacked, a
    /// single argument broadcast against stacked ones): a result of `out_shape` per state,
    /// stacked as `(N, *out_shape)`, into a fresh array or `batch.out`.
    pub(crate) fn each<F, const K: usize>(
        &self,
        batch: Batch<'_, 'py>,
        joints: [Joint<'_, 'py>; K],
        out_shape: &[usize],
        kernel: F,
    ) -> PyResult<Bound<'py, PyAny>>
    where
        F: Fn(&Model, &mut Scratch, &Rows<'_>, &mut [f64]) -> screwdyn::Result<()> + Sync,
    {
        let states = self.joints(joints)?;
        let m = self.model;
        run(
            self.py,
            &m.model,
            &m.scratch,
            &states.each_ref(),
            out_shape,
            batch,
            kernel,
        )
    }

    /// As [`Compute::each`], but stacked states go through `lanes`, one of the library's batch
    /// functions ([`screwdyn::batch`]: eight states side by side), and a single state through
    /// `one`.
    pub(crate) fn lanes<F, G, const K: usize>(
        &self,
        batch: Batch<'_, 'py>,
        joints: [Joint<'_, 'py>; K],
        out_shape: &[usize],
        lanes: F,
        one: G,
    ) -> PyResult<Bound<'py, PyAny>>
    where
        F: Fn(&Model, &mut BatchWorkspace, &[LaneRows<'_>], &mut [f64]) -> screwdyn::Result<()>
            + Sync,
        G: Fn(&Model, &mut Scratch, &Rows<'_>, &mut [f64]) -> screwdyn::Result<()> + Sync,
    {
        let states = self.joints(joints)?;
        let m = self.model;
        run_lanes(
            self.py,
            &m.model,
            &m.scratch,
            &states.each_ref(),
            out_shape,
            batch,
            lanes,
            one,
        )
    }

    /// `body` at the one state of `joints` (the methods that take no stacked states; a stacked
    /// argument is refused with a sentence naming `method`).
    pub(crate) fn one<T, const K: usize>(
        &self,
        method: &str,
        joints: [Joint<'_, 'py>; K],
        body: impl FnOnce([&[f64]; K]) -> PyResult<T>,
    ) -> PyResult<T> {
        let states = self.joints(joints)?;
        let mut rows: [&[f64]; K] = [&[]; K];
        for (row, s) in rows.iter_mut().zip(&states) {
            *row = s.single(method)?;
        }
        body(rows)
    }

    /// The joint-space arguments converted in order (the first bad one raises), for a method
    /// that does its own loop over the states.
    pub(crate) fn joints<'a, const K: usize>(
        &self,
        joints: [Joint<'a, 'py>; K],
    ) -> PyResult<[States<'a>; K]> {
        let model = &self.model.model;
        let mut states = [States::EMPTY; K];
        for (state, j) in states.iter_mut().zip(joints) {
            *state = match j.value {
                Some(v) => joint_states(model, v, j.name)?,
                None => States {
                    name: j.name,
                    data: Cow::Owned(vec![0.0; model.nq()]),
                    n: None,
                    width: model.nq(),
                },
            };
        }
        Ok(states)
    }
}
