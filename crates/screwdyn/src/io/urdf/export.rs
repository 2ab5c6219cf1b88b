//! Writing any [`Model`] as URDF.

use crate::error::{Error, Result};
use crate::io::xml_text::{xml_comment, xml_escape};
use crate::model::{FrameKind, JointKind, Model};
use crate::spatial::{ang, lin, Se3, SpatialInertia};
use nalgebra::Vector3;
use std::collections::{HashMap, HashSet};
use std::fmt::Write;

/// URDF's joint type for `j`, its axis, and the offset from the child frame to a point on the
/// axis (non-zero when the screw axis misses the child origin, which URDF cannot say directly).
fn urdf_joint_kind(j: &crate::model::Joint) -> Result<(&'static str, Vector3<f64>, Vector3<f64>)> {
    let (w, v) = (ang(&j.screw), lin(&j.screw));
    Ok(match j.kind {
        JointKind::Helical { .. } => {
            return Err(Error::InvalidModel(format!(
                "joint '{}' is helical, which URDF cannot describe",
                j.name
            )))
        }
        JointKind::Prismatic => ("prismatic", v, Vector3::zeros()),
        JointKind::Continuous => ("continuous", w, w.cross(&v)),
        JointKind::Revolute => {
            let unlimited = !limited(j.limits.lower) && !limited(j.limits.upper);
            (
                if unlimited { "continuous" } else { "revolute" },
                w,
                w.cross(&v),
            )
        }
    })
}

/// The `<joint>` element of a moving joint: parent, child, origin, axis, limits, dynamics and
/// mimic.
fn joint_element(
    j: &crate::model::Joint,
    kind: &str,
    parent: &str,
    child: &str,
    home: &Se3,
    axis: &Vector3<f64>,
) -> String {
    let mut limit = String::new();
    for (key, x, on) in [
        ("lower", j.limits.lower, kind != "continuous"),
        ("upper", j.limits.upper, kind != "continuous"),
        ("effort", j.limits.effort, true),
        ("velocity", j.limits.velocity, true),
    ] {
        if on && limited(x) {
            let _ = write!(limit, " {key}=\"{}\"", num(x));
        }
    }
    let mut s = format!(
        "  <joint name=\"{}\" type=\"{kind}\">\n    <parent link=\"{}\"/>\n    <child link=\"{}\"/>\n    {}\n    <axis xyz=\"{}\"/>\n",
        xml_escape(&j.name),
        xml_escape(parent),
        xml_escape(child),
        origin_tag(home),
        v3(axis)
    );
    if !limit.is_empty() {
        let _ = writeln!(s, "    <limit{limit}/>");
    }
    if j.damping != 0.0 || j.friction != 0.0 {
        let _ = writeln!(
            s,
            "    <dynamics damping=\"{}\" friction=\"{}\"/>",
            num(j.damping),
            num(j.friction)
        );
    }
    if let Some(m) = &j.mimic {
        let _ = writeln!(
            s,
            "    <mimic joint=\"{}\" multiplier=\"{}\" offset=\"{}\"/>",
            xml_escape(&m.joint),
            num(m.multiplier),
            num(m.offset)
        );
    }
    s += "  </joint>\n";
    s
}

/// Whether a limit value is an actual bound (not infinite, not the "no limit" default).
fn limited(x: f64) -> bool {
    x.is_finite() && x.abs() < f64::MAX
}

fn num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x}")
    }
}

fn v3(v: &Vector3<f64>) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

fn origin_tag(h: &Se3) -> String {
    let (r, p, y) = h.rpy();
    format!(
        "<origin xyz=\"{}\" rpy=\"{}\"/>",
        v3(&h.translation),
        v3(&Vector3::new(r, p, y))
    )
}

fn inertial_tag(i: &SpatialInertia) -> String {
    let c = &i.inertia_com;
    format!(
        "\n    <inertial>\n      <origin xyz=\"{}\" rpy=\"0 0 0\"/>\n      <mass value=\"{}\"/>\n      <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>\n    </inertial>\n  ",
        v3(&i.com),
        num(i.mass),
        num(c[(0, 0)]),
        num(c[(0, 1)]),
        num(c[(0, 2)]),
        num(c[(1, 1)]),
        num(c[(1, 2)]),
        num(c[(2, 2)])
    )
}

/// What an export to URDF leaves out, one sentence each: URDF has no armature (rotor inertia
/// reflected to a joint) and no joint spring, so a joint with one loses it. Empty when nothing
/// is lost.
///
/// ```
/// use screwdyn::io::urdf::urdf_export_warnings;
/// let m = screwdyn::builtin::planar2().with_armature(&[0.0, 0.2]).unwrap();
/// let w = urdf_export_warnings(&m);
/// assert_eq!(w.len(), 1);
/// assert!(w[0].contains("joint2") && w[0].contains("armature"));
/// let m = screwdyn::builtin::planar2().with_springs(&[3.0, 0.0], &[0.5, 0.0]).unwrap();
/// let w = urdf_export_warnings(&m);
/// assert!(w.len() == 1 && w[0].contains("joint1") && w[0].contains("spring"));
/// assert!(urdf_export_warnings(&screwdyn::builtin::planar2()).is_empty());
/// ```
pub fn urdf_export_warnings(model: &Model) -> Vec<String> {
    let mut out = Vec::new();
    for j in model.joints() {
        if j.armature != 0.0 {
            out.push(format!(
                "joint '{}' has an armature of {}, which URDF cannot hold: it is left out \
                 (export to MJCF keeps it)",
                j.name,
                num(j.armature)
            ));
        }
        if j.stiffness != 0.0 {
            out.push(format!(
                "joint '{}' has a spring (stiffness {}, rest position {}), which URDF cannot \
                 hold: it is left out (export to MJCF keeps it)",
                j.name,
                num(j.stiffness),
                num(j.springref)
            ));
        }
    }
    out
}

/// Writes `model` as URDF. Each moving body becomes a link named after it; when its screw axis
/// does not pass through its frame origin (e.g. a standard-DH joint, which turns about
/// `z_{i−1}`), a link `<body>_axis` on the axis carries the joint and the body's own frame
/// follows as a fixed link `<body>` (so every frame keeps its name and pose). Merged fixed
/// links and extra frames become massless links on fixed joints named `<frame>_fixed`. A
/// revolute joint without position limits is written as `continuous`; infinite limits are
/// left out. Gravity is not part of URDF and is not written. Helical joints cannot be written
/// (URDF has none): that is an error.
///
/// # Errors
/// [`Error::InvalidModel`] for a joint URDF cannot express (a helical joint, or an axis that does not pass through the child origin).
pub fn to_urdf_string(model: &Model) -> Result<String> {
    let mut out = String::new();
    let mut links = String::new();
    let mut joints = String::new();
    let mut meshes: HashMap<&str, Vec<&str>> = HashMap::new();
    for (l, p) in model.meshes() {
        meshes.entry(l.as_str()).or_default().push(p.as_str());
    }
    let mut used: HashSet<String> = model.joints().iter().map(|j| j.name.clone()).collect();
    let mut fresh = |base: String| {
        let mut name = base.clone();
        let mut k = 1;
        while used.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        used.insert(name.clone());
        name
    };
    let mut link_names: HashSet<String> = model.frames().iter().map(|f| f.name.clone()).collect();
    let mut link = |name: &str, inertia: Option<&SpatialInertia>| {
        let mut s = format!("  <link name=\"{}\">", xml_escape(name));
        if let Some(i) = inertia.filter(|i| i.mass > 0.0 || i.inertia_com.amax() > 0.0) {
            s += &inertial_tag(i);
        }
        for m in meshes.get(name).into_iter().flatten() {
            let _ = write!(
                s,
                "\n    <visual><geometry><mesh filename=\"{}\"/></geometry></visual>\n  ",
                xml_escape(m)
            );
        }
        s += "</link>\n";
        links += &s;
    };
    let _ = writeln!(out, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        out,
        "<!-- Written by screwdyn from model '{}'. -->",
        xml_comment(model.name())
    );
    let _ = writeln!(out, "<robot name=\"{}\">", xml_escape(model.name()));
    let base = model.base();
    link(&base.name, Some(&base.inertia));
    let body_link = |b: Option<usize>| match b {
        Some(i) => model.bodies()[i].name.clone(),
        None => base.name.clone(),
    };
    for (i, (j, body)) in model.joints().iter().zip(model.bodies()).enumerate() {
        let parent = body_link(model.parents()[i]);
        let (kind, axis, offset) = urdf_joint_kind(j)?;
        let split = offset.norm() > 1e-12;
        let moving = if split {
            let mut name = format!("{}_axis", body.name);
            while link_names.contains(&name) {
                name += "_";
            }
            link_names.insert(name.clone());
            name
        } else {
            body.name.clone()
        };
        let home = j.home.compose(&Se3::from_translation(offset));
        joints += &joint_element(j, kind, &parent, &moving, &home, &axis);
        if split {
            link(&moving, None);
            link(&body.name, Some(&body.inertia));
            let _ = write!(
                joints,
                "  <joint name=\"{}\" type=\"fixed\">\n    <parent link=\"{}\"/>\n    <child link=\"{}\"/>\n    {}\n  </joint>\n",
                xml_escape(&fresh(format!("{}_offset", body.name))),
                xml_escape(&moving),
                xml_escape(&body.name),
                origin_tag(&Se3::from_translation(-offset))
            );
        } else {
            link(&body.name, Some(&body.inertia));
        }
    }
    for f in model.frames() {
        if !matches!(f.kind, FrameKind::FixedLink | FrameKind::Extra) {
            continue;
        }
        link(&f.name, None);
        let _ = write!(
            joints,
            "  <joint name=\"{}\" type=\"fixed\">\n    <parent link=\"{}\"/>\n    <child link=\"{}\"/>\n    {}\n  </joint>\n",
            xml_escape(&fresh(format!("{}_fixed", f.name))),
            xml_escape(&body_link(f.body)),
            xml_escape(&f.name),
            origin_tag(&f.placement)
        );
    }
    out += &links;
    out += &joints;
    out += "</robot>\n";
    Ok(out)
}
