//! The path coefficients `a(s)`, `b(s)`, `c(s)` of [`PathDynamics`] at many grid points at once:
//! [`POINTS_PER_CALL`] points per call of the batch kernel, eight side by side in SIMD lanes.

use super::path_dynamics::{PathDynamics, PathPoint};
use super::spline::Path;
use crate::batch::{self, BatchWorkspace, Rows};
use crate::error::Result;
use crate::model::Model;

/// Points per call of the batch kernel: four groups of eight lanes.
pub(super) const POINTS_PER_CALL: usize = 4 * batch::LANES;

/// One point's `q`, `q'`, `q''` and coefficients `a`, `b`, `c` (springs and friction in `c`),
/// as [`PathPoint`] holds them.
pub(super) struct PointView<'a> {
    pub q: &'a [f64],
    pub dq: &'a [f64],
    pub ddq: &'a [f64],
    pub a: &'a [f64],
    pub b: &'a [f64],
    pub c: &'a [f64],
}

impl<'a> From<&'a PathPoint> for PointView<'a> {
    fn from(p: &'a PathPoint) -> Self {
        PointView {
            q: &p.q,
            dq: &p.dq,
            ddq: &p.ddq,
            a: &p.a,
            b: &p.b,
            c: &p.c,
        }
    }
}

/// The buffers of [`GridCoefficients::eval`], made once per timing: the batch workspace (which
/// the timing's check borrows too), the points' `q`, `q'`, `q''` and `[a, b, c]` (row-major, one point after the other), and a
/// [`PathDynamics`] for points taken one at a time.
pub(super) struct GridCoefficients {
    pub(super) batch: BatchWorkspace,
    q: Vec<f64>,
    dq: Vec<f64>,
    ddq: Vec<f64>,
    abc: Vec<f64>,
    points: usize,
    /// One point at a time: the points of a call the batch refuses (a non-finite value), so
    /// that the first refused point is named as [`PathDynamics::at`] names it.
    pub(super) one: PathDynamics,
}

impl GridCoefficients {
    /// The buffers for `model` and paths of `nq` joints.
    ///
    /// # Errors
    /// As [`PathDynamics::new`].
    pub(super) fn new(model: &Model, nq: usize) -> Result<Self> {
        let one = PathDynamics::new(model, nq)?;
        let rows = POINTS_PER_CALL * nq;
        Ok(GridCoefficients {
            batch: BatchWorkspace::new(model),
            q: vec![0.0; rows],
            dq: vec![0.0; rows],
            ddq: vec![0.0; rows],
            abc: vec![0.0; 3 * rows],
            points: 0,
            one,
        })
    }

    /// The path and its coefficients at the points `s` (at most [`POINTS_PER_CALL`]), read with
    /// [`point`](Self::point): `c = RNEA_g(q, 0, 0) + k ∘ (q − q_spring) + f ∘ sign(q')`,
    /// `a = RNEA_0(q, 0, q')`, `b = RNEA_0(q, q', q'')` as [`PathDynamics`] has them. `false`
    /// when the batch refuses a point (a non-finite value): take the points one at a time
    /// with [`PathDynamics::at`] then.
    pub(super) fn eval(&mut self, model: &Model, path: &dyn Path, s: &[f64]) -> bool {
        let n = model.nq();
        let rows = s.len() * n;
        // q(s), q'(s), q''(s) of every point.
        for (i, &si) in s.iter().enumerate() {
            let at = i * n..(i + 1) * n;
            path.eval(
                si,
                &mut self.q[at.clone()],
                &mut self.dq[at.clone()],
                &mut self.ddq[at],
            );
        }
        // [a, b, g(q)] of every point, eight side by side.
        let (q, dq) = (&self.q[..rows], &self.dq[..rows]);
        let abc = &mut self.abc[..3 * rows];
        if batch::path_coefficients(
            model,
            &mut self.batch,
            Rows::Stacked(q),
            Rows::Stacked(dq),
            Rows::Stacked(&self.ddq[..rows]),
            abc,
        )
        .is_err()
        {
            return false;
        }
        // c += k ∘ (q − q_spring) + f ∘ sign(q'): springs, and Coulomb friction moving forward
        // along the path (ṡ > 0, so sign(q̇) = sign(q')).
        for ((row, q), dq) in abc
            .chunks_exact_mut(3 * n)
            .zip(q.chunks_exact(n))
            .zip(dq.chunks_exact(n))
        {
            model.add_spring_and_friction_torques(q, dq, &mut row[2 * n..]);
        }
        self.points = s.len();
        true
    }

    /// Point `i` of the last [`eval`](Self::eval).
    pub(super) fn point(&self, i: usize) -> PointView<'_> {
        debug_assert!(i < self.points);
        let n = self.q.len() / POINTS_PER_CALL;
        let at = i * n..(i + 1) * n;
        let abc = &self.abc[3 * n * i..3 * n * (i + 1)];
        PointView {
            q: &self.q[at.clone()],
            dq: &self.dq[at.clone()],
            ddq: &self.ddq[at],
            a: &abc[..n],
            b: &abc[n..2 * n],
            c: &abc[2 * n..],
        }
    }
}
