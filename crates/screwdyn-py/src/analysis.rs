//! The seeds' quantities for a student: the closed form, the Lagrangian coefficients and the
//! RNEA iterations, as dicts of arrays (wrapped in display classes by the Python layer).

use crate::convert::{self, array, matrix, vector};
use crate::errors::call_err;
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use screwdyn::dynamics::{self, ExternalWrenches};
use screwdyn::spatial::Se3;
use screwdyn::Model;

pub fn closed_form<'py>(
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

pub fn lagrange<'py>(py: Python<'py>, model: &Model, q: &[f64]) -> PyResult<Bound<'py, PyDict>> {
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

/// The library's `dynamics::rnea_trace` (seeds 000/002, forward and backward iterations) as a
/// dict of arrays, plus the model quantities the lecture writes next to them (`S_i`,
/// `H_i^{λ(i)}(0)`, `𝔍^{i,i}`).
pub fn rnea_trace<'py>(
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
