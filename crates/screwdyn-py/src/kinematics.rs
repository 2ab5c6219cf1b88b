//! `Model`'s kinematics (the library's `kinematics`): frame poses, Jacobians, twists and
//! accelerations, single or batched.

use crate::args::reference;
use crate::batch::Batch;
use crate::compute::arg;
use crate::convert::{self, StateIn, Values};
use crate::model::PyModel;
use crate::single::plain;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PySlice};
use screwdyn::kinematics;

#[pymethods]
impl PyModel {
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
        if plain(threads, out) {
            let f = self.frame(frame)?;
            if let Some(r) = self.single_state(py, [Some(&q)], [4, 4], |m, s, [q], o| {
                kinematics::forward_kinematics(m, &mut s.ws, q)?;
                convert::write_pose(&kinematics::frame_pose(m, &s.ws, f)?, o);
                Ok(())
            }) {
                return r;
            }
        }
        self.compute(py, |c| {
            let f = self.frame(frame)?;
            c.each(
                Batch { threads, out },
                [arg(&q, "q")],
                &[4, 4],
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
        let frames = self.model.frames();
        self.compute(py, |c| {
            let all = c.each(
                Batch::threads(threads),
                [arg(&q, "q")],
                &[frames.len(), 4, 4],
                |m, s, r, o| {
                    kinematics::forward_kinematics(m, &mut s.ws, r[0])?;
                    for (f, of) in o.chunks_mut(16).enumerate() {
                        convert::write_pose(&kinematics::frame_pose(m, &s.ws, f)?, of);
                    }
                    Ok(())
                },
            )?;
            // One entry per frame: a view of the frame's poses.
            let stacked = q.shape().len() == 2;
            let d = PyDict::new(py);
            for (f, frame) in frames.iter().enumerate() {
                let item = if stacked {
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
    /// Jacobian `J_f^{f,0}`, Pinocchio's LOCAL, the Robotics Toolbox's `jacobe`) or
    /// `"world-aligned"` (the frame origin's velocity in base axes, Pinocchio's
    /// LOCAL_WORLD_ALIGNED, the Robotics Toolbox's `jacob0`); Pinocchio's names are accepted as
    /// they are. The frame by name or index.
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
        let nq = self.model.nq();
        if plain(threads, out) {
            let (f, rf) = (self.frame(frame)?, self::reference(reference)?);
            if let Some(r) = self.single_state(py, [Some(&q)], [6, nq], |m, s, [q], o| {
                kinematics::compute_joint_jacobians(m, &mut s.ws, q)?;
                kinematics::frame_jacobian(m, &s.ws, f, rf, &mut s.jac)?;
                convert::write_rows(&s.jac, o);
                Ok(())
            }) {
                return r;
            }
        }
        self.compute(py, |c| {
            let (f, rf) = (self.frame(frame)?, self::reference(reference)?);
            c.each(
                Batch { threads, out },
                [arg(&q, "q")],
                &[6, nq],
                |m, s, r, o| {
                    kinematics::compute_joint_jacobians(m, &mut s.ws, r[0])?;
                    kinematics::frame_jacobian(m, &s.ws, f, rf, &mut s.jac)?;
                    convert::write_rows(&s.jac, o);
                    Ok(())
                },
            )
        })
    }

    /// The body Jacobian `J_i^{i,0}(q)` of a link (name or index), `(6, nq)`: block row `i`
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
        let nq = self.model.nq();
        self.compute(py, |c| {
            let b = self.link(link)?;
            c.each(
                Batch { threads, out },
                [arg(&q, "q")],
                &[6, nq],
                |m, s, r, o| {
                    kinematics::compute_joint_jacobians(m, &mut s.ws, r[0])?;
                    kinematics::link_jacobian(m, &s.ws, b, &mut s.jac)?;
                    convert::write_rows(&s.jac, o);
                    Ok(())
                },
            )
        })
    }

    /// Twist `(ω, v)` of a frame at `(q, v)` in `reference` (world, local or world-aligned; or
    /// Pinocchio's WORLD, LOCAL, LOCAL_WORLD_ALIGNED), shape `(6,)` or `(N, 6)`.
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
        self.compute(py, |c| {
            let (f, rf) = (self.frame(frame)?, self::reference(reference)?);
            c.each(
                Batch { threads, out },
                [arg(&q, "q"), arg(&v, "v")],
                &[6],
                |m, s, r, o| {
                    kinematics::forward_velocity(m, &mut s.ws, r[0], r[1])?;
                    o.copy_from_slice(kinematics::frame_twist(m, &s.ws, f, rf)?.as_slice());
                    Ok(())
                },
            )
        })
    }

    /// Acceleration of a frame at `(q, v, a)`: the derivative of `frame_twist`'s components in
    /// `reference` (as in `frame_twist`; world-aligned: the classical acceleration of the frame
    /// origin), `(6,)`.
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
        self.compute(py, |c| {
            let (f, rf) = (self.frame(frame)?, self::reference(reference)?);
            c.each(
                Batch { threads, out },
                [arg(&q, "q"), arg(&v, "v"), arg(&a, "a")],
                &[6],
                |m, s, r, o| {
                    kinematics::forward_acceleration(m, &mut s.ws, r[0], r[1], r[2])?;
                    o.copy_from_slice(kinematics::frame_acceleration(m, &s.ws, f, rf)?.as_slice());
                    Ok(())
                },
            )
        })
    }

    /// `J̇(q, v) v` of a frame in `reference` (as in `frame_twist`): the frame acceleration at zero joint acceleration
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
        self.compute(py, |c| {
            let (f, rf) = (self.frame(frame)?, self::reference(reference)?);
            c.each(
                Batch { threads, out },
                [arg(&q, "q"), arg(&v, "v")],
                &[6],
                |m, s, r, o| {
                    let x = kinematics::frame_jdot_qdot(m, &mut s.ws, r[0], r[1], f, rf)?;
                    o.copy_from_slice(x.as_slice());
                    Ok(())
                },
            )
        })
    }
}
