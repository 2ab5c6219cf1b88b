//! The intermediate quantities a student checks a hand derivation against, at one state (the
//! library's `dynamics::closed_form`, `lagrange_coefficients` and `rnea_trace`):
//! `Model.closed_form`, `lagrange_coefficients` and `rnea_trace`, dicts of arrays wrapped in the
//! display classes of `screwdyn._results`.

use crate::compute::{arg, optional};
use crate::convert::{self, array, matrix, python_class, vector, StateIn};
use crate::errors::call_err;
use crate::model::PyModel;
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use screwdyn::dynamics::{self, ExternalWrenches};
use screwdyn::spatial::Se3;
use screwdyn::Model;

#[pymethods]
impl PyModel {
    /// The stacked closed form of docs/notation.md at one state ``(q, v)``: ``A(θ)``, ``L = (I − A)⁻¹``, ``S``, ``𝔍``,
    /// ``J = L S``, ``M = Sᵀ Lᵀ 𝔍 L S``, ``C``, ``g`` as arrays (a :class:`ClosedForm`).
    #[pyo3(signature = (q, v = None))]
    fn closed_form<'py>(
        slf: &Bound<'py, Self>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (py, this) = (slf.py(), slf.borrow());
        let data = this.compute(py, |c| {
            c.one("closed_form", [arg(&q, "q"), optional(&v, "v")], |[q, v]| {
                closed_form(py, &this.model, q, v)
            })
        })?;
        python_class(py, "screwdyn._results", "ClosedForm")?.call1((slf, data))
    }

    /// The Lagrangian coefficients at one state: ``D_ij`` (inertias), ``D_ijk``
    /// (Coriolis/centrifugal) and ``D_i`` (gravity), as a :class:`LagrangeCoefficients`.
    fn lagrange_coefficients<'py>(
        slf: &Bound<'py, Self>,
        q: StateIn<'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (py, this) = (slf.py(), slf.borrow());
        let data = this.compute(py, |c| {
            c.one("lagrange_coefficients", [arg(&q, "q")], |[q]| {
                lagrange(py, &this.model, q)
            })
        })?;
        python_class(py, "screwdyn._results", "LagrangeCoefficients")?.call1((slf, data))
    }

    /// The recursive Newton–Euler algorithm step by step at one state, in the notation of
    /// docs/notation.md: the
    /// forward iterations (poses, twists, accelerations) and the backward ones (wrenches,
    /// torques), as an :class:`RneaTrace` that displays typeset in a notebook.
    #[pyo3(signature = (q, v = None, a = None, *, fext = None, fext_world = None, tip_wrenches = None))]
    #[allow(clippy::too_many_arguments)]
    fn rnea_trace<'py>(
        &self,
        py: Python<'py>,
        q: StateIn<'py>,
        v: Option<StateIn<'py>>,
        a: Option<StateIn<'py>>,
        fext: Option<&Bound<'py, PyDict>>,
        fext_world: Option<&Bound<'py, PyDict>>,
        tip_wrenches: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let data = self.compute(py, |c| {
            let ext = self.wrenches([fext, fext_world, tip_wrenches])?;
            let joints = [arg(&q, "q"), optional(&v, "v"), optional(&a, "a")];
            c.one("rnea_trace", joints, |[q, v, a]| {
                rnea_trace(py, &self.model, q, v, a, ext.as_ref())
            })
        })?;
        python_class(py, "screwdyn._results", "RneaTrace")?.call1((data,))
    }
}

/// The library's `dynamics::closed_form` as a dict of arrays `A`, `L`, `S`,
/// `inertia` (𝔍), `ad_S_qdot`, `V`, `ad_V`, `J`, `J_dot`, `Vdot_base`, `M`, `C`,
/// `C_christoffel`, `g`.
fn closed_form<'py>(
    py: Python<'py>,
    model: &Model,
    q: &[f64],
    v: &[f64],
) -> PyResult<Bound<'py, PyDict>> {
    let cf = dynamics::closed_form(model, q, v).map_err(call_err)?;
    let d = PyDict::new(py);
    d.set_item("q", vector(py, q)?)?;
    d.set_item("qdot", vector(py, cf.qdot.as_slice())?)?;
    d.set_item("A", matrix(py, &cf.a)?)?;
    d.set_item("L", matrix(py, &cf.l)?)?;
    d.set_item("S", matrix(py, &cf.s)?)?;
    d.set_item("inertia", matrix(py, &cf.inertia)?)?;
    d.set_item("ad_S_qdot", matrix(py, &cf.ad_s_qdot)?)?;
    d.set_item("V", vector(py, cf.v.as_slice())?)?;
    d.set_item("ad_V", matrix(py, &cf.ad_v)?)?;
    d.set_item("J", matrix(py, &cf.j)?)?;
    d.set_item("J_dot", matrix(py, &cf.j_dot)?)?;
    d.set_item("Vdot_base", vector(py, cf.vdot_base.as_slice())?)?;
    d.set_item("M", matrix(py, &cf.m)?)?;
    d.set_item("C", matrix(py, &cf.c)?)?;
    d.set_item("C_christoffel", matrix(py, &cf.c_christoffel)?)?;
    d.set_item("g", vector(py, cf.g.as_slice())?)?;
    Ok(d)
}

/// The library's `dynamics::lagrange_coefficients`: `D_ij`, `D_ijk`, `D_i` as a dict
/// of arrays.
fn lagrange<'py>(py: Python<'py>, model: &Model, q: &[f64]) -> PyResult<Bound<'py, PyDict>> {
    let c = dynamics::lagrange_coefficients(model, q).map_err(call_err)?;
    let n = model.nq();
    let mut dijk = vec![0.0; n * n * n];
    for (i, o) in dijk.chunks_mut(n * n).enumerate() {
        convert::write_rows(&c.d_ijk[i], o);
    }
    let d = PyDict::new(py);
    d.set_item("q", vector(py, q)?)?;
    d.set_item("D_ij", matrix(py, &c.d_ij)?)?;
    d.set_item("D_ijk", array(py, dijk, &[n, n, n])?)?;
    d.set_item("D_i", vector(py, c.d_i.as_slice())?)?;
    Ok(d)
}

/// The library's `dynamics::rnea_trace` (forward and backward iterations) as a
/// dict of arrays, plus the model quantities written next to them (`S_i`,
/// `H_i^{λ(i)}(0)`, `𝔍^{i,i}`).
fn rnea_trace<'py>(
    py: Python<'py>,
    model: &Model,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    ext: Option<&ExternalWrenches>,
) -> PyResult<Bound<'py, PyDict>> {
    let tr = dynamics::rnea_trace(model, q, v, a, ext).map_err(call_err)?;
    let n = model.nbodies();
    let poses = |hs: &mut dyn Iterator<Item = Se3>| {
        let mut out = vec![0.0; n * 16];
        for (h, o) in hs.zip(out.chunks_mut(16)) {
            convert::write_pose(&h, o);
        }
        array(py, out, &[n, 4, 4])
    };
    let sixes = |xs: &mut dyn Iterator<Item = Vector6<f64>>| {
        let mut out = Vec::with_capacity(n * 6);
        for x in xs {
            out.extend_from_slice(x.as_slice());
        }
        array(py, out, &[n, 6])
    };
    let mut inertia = vec![0.0; n * 36];
    for (b, o) in model.bodies().iter().zip(inertia.chunks_mut(36)) {
        convert::write_rows(&b.inertia.matrix(), o);
    }
    let (fw, bw) = (&tr.forward, &tr.backward);
    let d = PyDict::new(py);
    d.set_item("joint_names", model.joint_names())?;
    d.set_item(
        "link_names",
        model
            .bodies()
            .iter()
            .map(|b| b.name.as_str())
            .collect::<Vec<_>>(),
    )?;
    d.set_item("parents", model.parents().to_vec())?;
    d.set_item("q", vector(py, q)?)?;
    d.set_item("v", vector(py, v)?)?;
    d.set_item("a", vector(py, a)?)?;
    d.set_item("gravity", vector(py, model.gravity().as_slice())?)?;
    d.set_item(
        "base_acceleration",
        vector(py, tr.base_acceleration.as_slice())?,
    )?;
    d.set_item("screw", sixes(&mut model.joints().iter().map(|j| j.screw))?)?;
    d.set_item("home", poses(&mut model.joints().iter().map(|j| j.home))?)?;
    d.set_item("inertia", array(py, inertia, &[n, 6, 6])?)?;
    d.set_item(
        "pose_in_parent",
        poses(&mut fw.iter().map(|f| f.pose_in_parent))?,
    )?;
    d.set_item(
        "parent_twist",
        sixes(&mut fw.iter().map(|f| f.parent_twist))?,
    )?;
    d.set_item(
        "parent_twist_dot",
        sixes(&mut fw.iter().map(|f| f.parent_twist_dot))?,
    )?;
    d.set_item("twist", sixes(&mut fw.iter().map(|f| f.twist))?)?;
    d.set_item("twist_dot", sixes(&mut fw.iter().map(|f| f.twist_dot))?)?;
    d.set_item("inertial", sixes(&mut bw.iter().map(|b| b.inertial))?)?;
    d.set_item("external", sixes(&mut bw.iter().map(|b| b.external))?)?;
    let children = PyList::empty(py);
    for b in bw {
        let c = PyDict::new(py);
        for (k, w) in &b.from_children {
            c.set_item(*k, vector(py, w.as_slice())?)?;
        }
        children.append(c)?;
    }
    d.set_item("from_children", children)?;
    d.set_item("wrench", sixes(&mut bw.iter().map(|b| b.wrench))?)?;
    d.set_item("tau", vector(py, &tr.tau)?)?;
    Ok(d)
}
