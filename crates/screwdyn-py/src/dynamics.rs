//! `Model`'s dynamics (the library's `dynamics`): inverse dynamics, the mass matrix and its
//! inverse, Coriolis and gravity terms, forward dynamics, single or batched; and the one-state
//! Lagrangian quantities (`∂M/∂q`, effective inertia).

use crate::args::{method, WrenchDicts};
use crate::batch::Batch;
use crate::compute::{arg, optional};
use crate::convert::{self, StateIn};
use crate::errors::call_err;
use crate::model::PyModel;
use crate::single::plain;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use screwdyn::dynamics::{self, ForwardMethod};

/// The docstring of `rnea` and of its alias `inverse_dynamics`.
macro_rules! rnea_doc {
    () => {
        concat!(
            "Inverse dynamics `τ = M(q) a + C(q, v) v + g(q) − Σ J_iᵀ W_ext,i (+ J_eᵀ W_tip)` by the\n",
            "recursive Newton–Euler algorithm (docs/notation.md). `v` and `a` default to zero.\n",
            "\n",
            "External wrenches (applied to every state): `fext={link: (6,)}` — the wrench of the\n",
            "environment on the link, in the link frame; `fext_world={link: (6,)}` — the same in the\n",
            "base frame (moment about the base origin); `tip_wrenches={frame: (6,)}` — the wrench the\n",
            "frame applies to the environment, in that frame. Wrenches are `(m, f)`, moment first.\n",
            "A link is named (any link, one attached by a fixed joint included: its wrench is moved\n",
            "to the body it is merged into, `W^b = Ad_{H_b^f}ᵀ W^f`) or given by its index in\n",
            "`link_names`."
        )
    };
}

/// The docstring of `crba` and of its alias `mass_matrix`.
macro_rules! crba_doc {
    () => {
        "Joint-space mass matrix `M(q)` by the composite-rigid-body algorithm, `(nq, nq)`."
    };
}

/// Copies a library vector into the output row.
#[inline]
fn put(o: &mut [f64], x: &nalgebra::DVector<f64>) {
    o.copy_from_slice(x.as_slice());
}

impl PyModel {
    /// The body of `forward_dynamics` and `aba`: `q̈` by `method`; ABA without external wrenches
    /// runs stacked states through the library's batch ABA (eight states side by side).
    fn forward<'py>(
        &self,
        py: Python<'py>,
        [q, v, tau]: [&StateIn<'py>; 3],
        method: &str,
        wrenches: WrenchDicts<'_, 'py>,
        batch: Batch<'_, 'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nq = self.model.nq();
        self.compute(py, |c| {
            let how = self::method(method)?;
            let joints = [arg(q, "q"), arg(v, "v"), arg(tau, "tau")];
            match self.wrenches(wrenches)? {
                None if how == ForwardMethod::Aba => c.lanes(
                    batch,
                    joints,
                    &[nq],
                    |m, ws, r, o| screwdyn::batch::aba(m, ws, r[0], r[1], r[2], o),
                    |m, s, r, o| {
                        put(o, dynamics::aba(m, &mut s.ws, r[0], r[1], r[2])?);
                        Ok(())
                    },
                ),
                ext => c.each(batch, joints, &[nq], move |m, s, r, o| {
                    let (ws, ext) = (&mut s.ws, ext.as_ref());
                    put(
                        o,
                        dynamics::forward_dynamics(m, ws, r[0], r[1], r[2], ext, how)?,
                    );
                    Ok(())
                }),
            }
        })
    }
}

#[pymethods]
impl PyModel {
    #[doc = rnea_doc!()]
    #[pyo3(signature = (q, v = None, a = None, *, fext = None, fext_world = None, tip_wrenches = None, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn rnea<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
        a: Option<StateIn<'py>>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (nq, batch) = (self.model.nq(), Batch { threads, out });
        if fext.is_none() && fext_world.is_none() && tip_wrenches.is_none() && plain(threads, out) {
            let joints = [Some(&q), v.as_ref(), a.as_ref()];
            if let Some(r) = self.single_state(py, joints, [1, nq], |m, s, [q, v, a], o| {
                put(o, dynamics::rnea(m, &mut s.ws, q, v, a)?);
                Ok(())
            }) {
                return r;
            }
        }
        self.compute(py, |c| {
            let ext = self.wrenches([fext, fext_world, tip_wrenches])?;
            let joints = [arg(&q, "q"), optional(&v, "v"), optional(&a, "a")];
            match ext {
                // Without wrenches, the library's batch RNEA (eight states side by side).
                None => c.lanes(
                    batch,
                    joints,
                    &[nq],
                    |m, ws, r, o| screwdyn::batch::rnea(m, ws, r[0], r[1], r[2], o),
                    |m, s, r, o| {
                        put(o, dynamics::rnea(m, &mut s.ws, r[0], r[1], r[2])?);
                        Ok(())
                    },
                ),
                Some(ext) => c.each(batch, joints, &[nq], move |m, s, r, o| {
                    let tau =
                        dynamics::inverse_dynamics(m, &mut s.ws, r[0], r[1], r[2], Some(&ext))?;
                    put(o, tau);
                    Ok(())
                }),
            }
        })
    }

    #[doc = rnea_doc!()]
    #[pyo3(signature = (q, v = None, a = None, *, fext = None, fext_world = None, tip_wrenches = None, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn inverse_dynamics<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
        a: Option<StateIn<'py>>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.rnea(py, q, v, a, fext, fext_world, tip_wrenches, threads, out)
    }

    #[doc = crba_doc!()]
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn crba<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nq = self.model.nq();
        if plain(threads, out) {
            if let Some(r) = self.single_state(py, [Some(&q)], [nq, nq], |m, s, [q], o| {
                convert::write_rows(dynamics::crba(m, &mut s.ws, q)?, o);
                Ok(())
            }) {
                return r;
            }
        }
        self.compute(py, |c| {
            c.lanes(
                Batch { threads, out },
                [arg(&q, "q")],
                &[nq, nq],
                |m, ws, r, o| screwdyn::batch::crba(m, ws, r[0], o),
                |m, s, r, o| {
                    convert::write_rows(dynamics::crba(m, &mut s.ws, r[0])?, o);
                    Ok(())
                },
            )
        })
    }

    #[doc = crba_doc!()]
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn mass_matrix<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.crba(py, q, threads, out)
    }

    /// `M(q)⁻¹` (CRBA and a Cholesky factorisation), `(nq, nq)`.
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn mass_matrix_inverse<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nq = self.model.nq();
        self.compute(py, |c| {
            c.each(
                Batch { threads, out },
                [arg(&q, "q")],
                &[nq, nq],
                |m, s, r, o| {
                    convert::write_rows(dynamics::mass_matrix_inverse(m, &mut s.ws, r[0])?, o);
                    Ok(())
                },
            )
        })
    }

    /// The Coriolis matrix `C(q, v)` whose `Ṁ − 2C` is skew-symmetric (Christoffel symbols of
    /// the first kind), `(nq, nq)`.
    #[pyo3(signature = (q, v, *, threads = None, out = None))]
    fn coriolis_matrix<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nq = self.model.nq();
        self.compute(py, |c| {
            c.each(
                Batch { threads, out },
                [arg(&q, "q"), arg(&v, "v")],
                &[nq, nq],
                |m, s, r, o| {
                    convert::write_rows(dynamics::coriolis_matrix(m, &mut s.ws, r[0], r[1])?, o);
                    Ok(())
                },
            )
        })
    }

    /// Gravity torques `g(q)` (N·m / N), `(nq,)`.
    #[pyo3(signature = (q, *, threads = None, out = None))]
    fn gravity_torque<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nq = self.model.nq();
        self.compute(py, |c| {
            c.lanes(
                Batch { threads, out },
                [arg(&q, "q")],
                &[nq],
                |m, ws, r, o| screwdyn::batch::gravity_torque(m, ws, r[0], o),
                |m, s, r, o| {
                    put(o, dynamics::gravity_torque(m, &mut s.ws, r[0])?);
                    Ok(())
                },
            )
        })
    }

    /// Nonlinear effects `C(q, v) v + g(q)`, `(nq,)`.
    #[pyo3(signature = (q, v, *, threads = None, out = None))]
    fn nonlinear_effects<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nq = self.model.nq();
        self.compute(py, |c| {
            c.lanes(
                Batch { threads, out },
                [arg(&q, "q"), arg(&v, "v")],
                &[nq],
                |m, ws, r, o| screwdyn::batch::nonlinear_effects(m, ws, r[0], r[1], o),
                |m, s, r, o| {
                    put(o, dynamics::nonlinear_effects(m, &mut s.ws, r[0], r[1])?);
                    Ok(())
                },
            )
        })
    }

    /// Forward dynamics `a = M⁻¹ (τ − C v − g + Σ J_iᵀ W_ext,i)`: `method="aba"` (Featherstone's
    /// articulated-body algorithm), `"crba"` (CRBA + Cholesky) or `"walker-orin"` (Walker and Orin's
    /// method: `M` column by column from RNEA).
    /// External wrenches as in `rnea`. A singular mass matrix raises ValueError naming the joint.
    #[pyo3(signature = (q, v, tau, *, method = "aba", fext = None, fext_world = None, tip_wrenches = None, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn forward_dynamics<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        tau: StateIn<'py>,
        method: &str,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let wrenches = [fext, fext_world, tip_wrenches];
        let batch = Batch { threads, out };
        self.forward(py, [&q, &v, &tau], method, wrenches, batch)
    }

    /// Forward dynamics by the articulated-body algorithm (Featherstone): `forward_dynamics(…,
    /// method="aba")`, q̈ (rad/s²) of shape `(nq,)` or `(N, nq)`. External wrenches as in `rnea`.
    #[pyo3(signature = (q, v, tau, *, fext = None, fext_world = None, tip_wrenches = None, threads = None, out = None))]
    #[allow(clippy::too_many_arguments)]
    fn aba<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: StateIn<'py>,
        tau: StateIn<'py>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
        threads: Option<usize>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let wrenches = [fext, fext_world, tip_wrenches];
        if wrenches.iter().all(Option::is_none) && plain(threads, out) {
            let nq = self.model.nq();
            let joints = [Some(&q), Some(&v), Some(&tau)];
            if let Some(r) = self.single_state(py, joints, [1, nq], |m, s, [q, v, tau], o| {
                put(o, dynamics::aba(m, &mut s.ws, q, v, tau)?);
                Ok(())
            }) {
                return r;
            }
        }
        let batch = Batch { threads, out };
        self.forward(py, [&q, &v, &tau], "aba", wrenches, batch)
    }

    /// `∂M/∂q_k` for every `k`, shape `(nq, nq, nq)` with `[k, i, j] = ∂M_ij/∂q_k`.
    fn mass_matrix_derivatives<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.compute(py, |c| {
            c.one("mass_matrix_derivatives", [arg(&q, "q")], |[q]| {
                let dm = dynamics::mass_matrix_derivatives(&self.model, q).map_err(call_err)?;
                let n = self.model.nq();
                let mut out = vec![0.0; n * n * n];
                for (k, o) in out.chunks_mut(n * n).enumerate() {
                    convert::write_rows(&dm[k], o);
                }
                convert::array(py, out, &[n, n, n])
            })
        })
    }

    /// Effective inertia of `joint` at `q` (from the Lagrangian form): with every other joint locked
    /// (`free=None`, the diagonal `M_ii`), every other joint free (`free="all"`: the inertia felt
    /// through the free joints, `M_ii − M_if M_ff⁻¹ M_fi`), or the joints named in a list free.
    #[pyo3(signature = (q, joint, free = None))]
    fn effective_inertia(
        &self,
        py: Python<'_>,
        q: StateIn<'_>,
        joint: &Bound<'_, PyAny>,
        free: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<f64> {
        self.compute(py, |c| {
            let j = self.joint(joint)?;
            c.one("effective_inertia", [arg(&q, "q")], |[q]| {
                let n = self.model.nq();
                let is_str = |f: &Bound<'_, PyAny>| f.extract::<String>().ok();
                let mask: Vec<bool> = match free {
                    None => vec![false; n],
                    Some(f) => match is_str(f).as_deref() {
                        Some("all") => vec![true; n],
                        Some(_) => return Err(PyValueError::new_err(
                            "free is None (others locked), \"all\" or a list of joint names or indices",
                        )),
                        None => {
                            let mut m = vec![false; n];
                            for item in f.try_iter()? {
                                m[self.joint(&item?)?] = true;
                            }
                            m
                        }
                    },
                };
                let mut ws = screwdyn::Workspace::new(&self.model);
                dynamics::effective_inertia(&self.model, &mut ws, q, j, &mask).map_err(call_err)
            })
        })
    }
}
