//! `Model`'s derivatives of the dynamics (the library's `dynamics::rnea_derivatives` and
//! `aba_derivatives`), single or batched: three `(nq, nq)` matrices per state, returned as
//! views into one stacked array.

use crate::args::WrenchDicts;
use crate::batch::Batch;
use crate::compute::{arg, Joint};
use crate::convert::{self, StateIn};
use crate::model::PyModel;
use nalgebra::DMatrix;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyEllipsis, PySlice, PyTuple};
use screwdyn::dynamics::{self, ExternalWrenches};
use screwdyn::{Model, Workspace};

/// The library's derivative function (`dynamics::rnea_derivatives` or `aba_derivatives`) at
/// one state, leaving its results in the workspace.
type Derivatives = fn(
    &Model,
    &mut Workspace,
    &[f64],
    &[f64],
    &[f64],
    Option<&ExternalWrenches>,
) -> screwdyn::Result<()>;

impl PyModel {
    /// Runs `derivatives` at each of the (stacked) states `joints` under the external wrenches
    /// `wrenches` and returns the three `nq × nq` matrices `pick` takes from the workspace: a
    /// tuple of three `(nq, nq)` (or `(N, nq, nq)`) views into one `(3, nq, nq)`
    /// (`(N, 3, nq, nq)`) array.
    fn three_matrices<'py>(
        &self,
        py: Python<'py>,
        joints: [Joint<'_, 'py>; 3],
        wrenches: WrenchDicts<'_, 'py>,
        threads: Option<usize>,
        derivatives: Derivatives,
        pick: fn(&Workspace) -> [&DMatrix<f64>; 3],
    ) -> PyResult<Bound<'py, PyTuple>> {
        let n = self.model.nq();
        let all = self.compute(py, |c| {
            let ext = self.wrenches(wrenches)?;
            c.each(Batch::threads(threads), joints, &[3, n, n], |m, s, r, o| {
                derivatives(m, &mut s.ws, r[0], r[1], r[2], ext.as_ref())?;
                for (matrix, out) in pick(&s.ws).into_iter().zip(o.chunks_exact_mut(n * n)) {
                    convert::write_rows(matrix, out);
                }
                Ok(())
            })
        })?;
        let (dots, all_rows) = (PyEllipsis::get(py).to_owned(), PySlice::full(py));
        let view = |k: usize| all.get_item((&dots, k, &all_rows, &all_rows));
        PyTuple::new(py, [view(0)?, view(1)?, view(2)?])
    }
}

#[pymethods]
impl PyModel {
    /// First-order derivatives of the inverse dynamics ``τ = RNEA(q, v, a)`` (docs/derivatives.md):
    /// ``(dtau_dq, dtau_dv, M)`` with ``dtau_dq[i, j] = ∂τ_i/∂q_j``, ``dtau_dv = ∂τ/∂q̇`` and
    /// ``M = ∂τ/∂q̈``, each ``(nq, nq)`` — ``(N, nq, nq)`` for stacked states (views into one
    /// ``(N, 3, nq, nq)`` array). Computed analytically in one forward and one backward pass in the
    /// base frame (Lie brackets with the joint screws). External wrenches as in :meth:`rnea`:
    /// ``fext`` and ``tip_wrenches`` move with their link, ``fext_world`` stays fixed in space.
    #[pyo3(signature = (q, v, a, *, fext = None, fext_world = None, tip_wrenches = None, threads = None))]
    #[allow(clippy::too_many_arguments)]
    fn rnea_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        a: StateIn<'py>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        self.three_matrices(
            py,
            [arg(&q, "q"), arg(&v, "v"), arg(&a, "a")],
            [fext, fext_world, tip_wrenches],
            threads,
            |m, ws, q, v, a, ext| dynamics::rnea_derivatives(m, ws, q, v, a, ext).map(|_| ()),
            |ws| [&ws.dtau_dq, &ws.dtau_dv, &ws.mass_matrix],
        )
    }

    /// First-order derivatives of the forward dynamics ``q̈ = ABA(q, v, τ)``:
    /// ``(dqdd_dq, dqdd_dv, Minv)`` with ``∂q̈/∂q = −M⁻¹ ∂τ/∂q``, ``∂q̈/∂q̇ = −M⁻¹ ∂τ/∂q̇`` (at
    /// ``q̈ = ABA(q, v, τ)``) and ``Minv = M⁻¹ = ∂q̈/∂τ``, each ``(nq, nq)`` or ``(N, nq, nq)``.
    /// External wrenches as in :meth:`rnea`. A singular mass matrix raises ValueError.
    #[pyo3(signature = (q, v, tau, *, fext = None, fext_world = None, tip_wrenches = None, threads = None))]
    #[allow(clippy::too_many_arguments)]
    fn aba_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        tau: StateIn<'py>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        self.three_matrices(
            py,
            [arg(&q, "q"), arg(&v, "v"), arg(&tau, "tau")],
            [fext, fext_world, tip_wrenches],
            threads,
            |m, ws, q, v, tau, ext| dynamics::aba_derivatives(m, ws, q, v, tau, ext).map(|_| ()),
            |ws| [&ws.dqdd_dq, &ws.dqdd_dv, &ws.mass_matrix_inverse],
        )
    }
}
