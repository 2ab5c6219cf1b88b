//! Mass and inertia of a body from its geoms, as MuJoCo computes them when the body has no
//! `<inertial>`: each geom a solid of uniform `density` (1000 kg/m³ unless given) or of the given
//! `mass`, placed by `pos`/orientation or `fromto`, and the geoms' inertias summed in the body
//! frame. Only geoms whose `group` lies in the compiler's `inertiagrouprange` count.

use super::compiler::Compiler;
use super::mesh::MeshTable;
use super::orientation::{pose, z_to};
use super::values::Values;
use crate::error::Result;
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::{Matrix3, Unit, Vector3};
use std::f64::consts::PI;

/// The geom's spatial inertia in the body frame; `None` for a geom outside the inertia group
/// range or one that has no volume of its own (a plane or height field).
pub(crate) fn geom_inertia(
    v: &Values,
    compiler: &Compiler,
    meshes: &MeshTable<'_>,
) -> Result<Option<SpatialInertia>> {
    let group = v.number("group")?.unwrap_or(0.0);
    let (lo, hi) = compiler.inertia_group_range;
    if group < lo as f64 || group > hi as f64 {
        return Ok(None);
    }
    let kind = geom_type(v)?;
    if matches!(kind, "plane" | "hfield") {
        return Ok(None);
    }
    if kind == "sdf" {
        return Err(v.error(
            "<geom type=\"sdf\"> has no inertia screwdyn can compute; give the body an <inertial>",
        ));
    }
    let (placement, size) = placement_and_size(v, compiler, kind)?;
    let (volume, unit_inertia, centre) = match kind {
        "mesh" => {
            let name = v
                .text("mesh")
                .ok_or_else(|| v.error("<geom type=\"mesh\"> names no mesh"))?;
            let m = meshes.get(v, name)?;
            (m.volume, m.inertia_per_volume, m.centre)
        }
        _ => {
            let (vol, i) = solid(kind, &size);
            (vol, i, Vector3::zeros())
        }
    };
    let mass = match v.number("mass")? {
        Some(m) if m < 0.0 => return Err(v.error(format!("<geom mass=\"{m}\"> is negative"))),
        Some(m) => m,
        None => {
            let density = v.number("density")?.unwrap_or(1000.0);
            if density < 0.0 {
                return Err(v.error(format!("<geom density=\"{density}\"> is negative")));
            }
            density * volume
        }
    };
    // Inertia about the centre in the geom frame, scaled to the mass: I = m Î / V.
    let i_geom = unit_inertia * (mass / volume);
    let r = placement.rotation;
    Ok(Some(SpatialInertia::new(
        mass,
        placement.act_point(&centre),
        r * i_geom * r.transpose(),
    )))
}

/// The geom's `type` (MuJoCo's default: a sphere).
pub(crate) fn geom_type(v: &Values) -> Result<&'static str> {
    let types = [
        "plane",
        "hfield",
        "sphere",
        "capsule",
        "ellipsoid",
        "cylinder",
        "box",
        "mesh",
        "sdf",
    ];
    Ok(v.keyword("type", &types)?.unwrap_or("sphere"))
}

/// The geom's pose in its body (or frame) and its half-sizes (MuJoCo's `size`), from
/// `pos`/orientation or from `fromto` (centre at the midpoint, `ẑ` along the segment,
/// half-length `|to − from|/2`); the sizes the type needs are checked to be positive.
pub(crate) fn placement_and_size(
    v: &Values,
    compiler: &Compiler,
    kind: &str,
) -> Result<(Se3, Vec<f64>)> {
    let mut placement = pose(v, compiler)?;
    let mut size = v.numbers_between("size", 0, 3)?.unwrap_or_default();
    if let Some(ft) = v.numbers("fromto", 6)? {
        if !matches!(kind, "capsule" | "cylinder" | "box" | "ellipsoid") {
            return Err(v.error(format!("<geom type=\"{kind}\" fromto> is only defined for capsules, cylinders, boxes and ellipsoids")));
        }
        let (from, to) = (
            Vector3::new(ft[0], ft[1], ft[2]),
            Vector3::new(ft[3], ft[4], ft[5]),
        );
        let d = to - from;
        if d.norm() < 1e-12 {
            return Err(v.error("<geom fromto> has the same start and end point"));
        }
        placement = Se3::new(z_to(&Unit::new_normalize(d)), (from + to) / 2.0);
        let half = d.norm() / 2.0;
        match kind {
            "capsule" | "cylinder" => {
                size.resize(1, 0.0);
                size.push(half);
            }
            _ => {
                size.resize(2, 0.0);
                size.push(half);
            }
        }
    }
    let need = match kind {
        "sphere" => 1,
        "capsule" | "cylinder" => 2,
        "mesh" | "plane" | "hfield" | "sdf" => 0,
        _ => 3,
    };
    if size.len() < need || size[..need].iter().any(|s| *s <= 0.0) {
        return Err(v.error(format!(
            "<geom type=\"{kind}\"> needs {need} positive size value{} (got \"{}\")",
            if need == 1 { "" } else { "s" },
            v.text("size").unwrap_or("")
        )));
    }
    Ok((placement, size))
}

/// Volume `V` and inertia about the centre in the geom frame for unit mass times `V` (so that
/// `I = m Î / V`) of a primitive with MuJoCo's half-sizes.
fn solid(kind: &str, s: &[f64]) -> (f64, Matrix3<f64>) {
    let diag =
        |a: f64, b: f64, c: f64, v: f64| (v, Matrix3::from_diagonal(&Vector3::new(a, b, c)) * v);
    match kind {
        // V = 4/3 π r³, I = 2/5 m r².
        "sphere" => {
            let r = s[0];
            let i = 0.4 * r * r;
            diag(i, i, i, 4.0 / 3.0 * PI * r.powi(3))
        }
        // V = 4/3 π a b c, I_xx = m (b² + c²)/5, …
        "ellipsoid" => {
            let (a, b, c) = (s[0], s[1], s[2]);
            diag(
                (b * b + c * c) / 5.0,
                (a * a + c * c) / 5.0,
                (a * a + b * b) / 5.0,
                4.0 / 3.0 * PI * a * b * c,
            )
        }
        // V = 8 a b c, I_xx = m (b² + c²)/3, …
        "box" => {
            let (a, b, c) = (s[0], s[1], s[2]);
            diag(
                (b * b + c * c) / 3.0,
                (a * a + c * c) / 3.0,
                (a * a + b * b) / 3.0,
                8.0 * a * b * c,
            )
        }
        // V = π r² H with H = 2h, I_xx = m (r²/4 + H²/12), I_zz = m r²/2.
        "cylinder" => {
            let (r, hh) = (s[0], 2.0 * s[1]);
            let ixx = r * r / 4.0 + hh * hh / 12.0;
            diag(ixx, ixx, r * r / 2.0, PI * r * r * hh)
        }
        // A cylinder of height H = 2h and two hemispheres, each part's mass in proportion to
        // its volume; a hemisphere's centre of mass is 3r/8 from its flat face, so about the
        // capsule's centre I_xx = m_c (r²/4 + H²/12) + m_s (2r²/5 + H²/4 + 3Hr/8),
        // I_zz = (m_c/2 + 2 m_s/5) r².
        _ => {
            let (r, hh) = (s[0], 2.0 * s[1]);
            let (vc, vs) = (PI * r * r * hh, 4.0 / 3.0 * PI * r.powi(3));
            let v = vc + vs;
            let (mc, ms) = (vc / v, vs / v);
            let ixx = mc * (r * r / 4.0 + hh * hh / 12.0)
                + ms * (0.4 * r * r + hh * hh / 4.0 + 3.0 * hh * r / 8.0);
            let izz = (mc / 2.0 + 0.4 * ms) * r * r;
            diag(ixx, ixx, izz, v)
        }
    }
}
