//! Writing any [`Model`] as MJCF, MuJoCo's XML format ([`to_mjcf_string`]).
//!
//! Mapping: the base is `<worldbody>`; moving body `i` is a `<body>` nested in its parent's,
//! placed at `H_i^{λ(i)}(0)` (`pos`, `quat` w first), with one joint whose screw
//! `S_i^{i,λ(i)} = (ω, v)` becomes a `hinge` with `axis = ω` through the point `ω × v` (the
//! point of the axis closest to the body origin, since `v = −ω × p`) or a `slide` with
//! `axis = v`. MuJoCo's joint coordinate is then screwdyn's `q_i` (`ref = 0`). The inertia is
//! an `<inertial>` at the centre of mass with `fullinertia` about it in MuJoCo's order
//! `xx yy zz xy xz yz` (`diaginertia` when the body axes are principal; a singular inertia in
//! its principal axes, with `boundmass`/`boundinertia`, see [`mjcf_export_warnings`]). Position limits become `range`, damping `damping`, Coulomb friction
//! `frictionloss`, the armature `armature`, a joint spring `stiffness` and `springref`, and a finite effort limit a `<motor>` with
//! `forcerange` (and `ctrlrange`) `±effort`. Every frame that is not a body frame (merged fixed
//! links, tool points) becomes a `<site>` of the same name; gravity goes to
//! `<option gravity>`. Velocity limits (MuJoCo has none) are left out.

use crate::error::{Error, Result};
use crate::io::xml_text::{xml_comment, xml_escape};
use crate::model::{FrameKind, Joint, JointKind, Model};
use crate::spatial::{ang, lin, Se3, SpatialInertia};
use nalgebra::{Rotation3, UnitQuaternion, Vector3};
use std::fmt::Write;

/// Whether a limit value is an actual bound (not infinite, not the "no limit" default).
fn limited(x: f64) -> bool {
    x.is_finite() && x.abs() < f64::MAX
}

/// Shortest round-trip text of a number (`0` for ±0).
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

/// `pos="…" quat="w x y z"` of a pose (the quaternion left out for the identity).
fn placement(h: &Se3) -> String {
    let mut s = format!("pos=\"{}\"", v3(&h.translation));
    if h.rotation != nalgebra::Matrix3::identity() {
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(h.rotation));
        let _ = write!(
            s,
            " quat=\"{} {} {} {}\"",
            num(q.w),
            num(q.i),
            num(q.j),
            num(q.k)
        );
    }
    s
}

/// The `<joint …/>` element of `j`.
fn joint_element(j: &Joint) -> Result<String> {
    let (w, v) = (ang(&j.screw), lin(&j.screw));
    let bad = |what: &str| {
        Err(Error::InvalidModel(format!(
            "joint '{}' {what}, which MJCF cannot describe",
            j.name
        )))
    };
    let mut s = format!("<joint name=\"{}\"", xml_escape(&j.name));
    match j.kind {
        JointKind::Helical { .. } => return bad("is helical"),
        JointKind::Prismatic => {
            if (v.norm() - 1.0).abs() > 1e-9 {
                return bad("has a screw axis that is not a unit translation");
            }
            let _ = write!(s, " type=\"slide\" axis=\"{}\"", v3(&v));
        }
        JointKind::Revolute | JointKind::Continuous => {
            if (w.norm() - 1.0).abs() > 1e-9 {
                return bad("has a screw axis that is not a unit rotation");
            }
            // v = −ω × p for a point p on the axis: ω × v is the point closest to the origin.
            let _ = write!(
                s,
                " type=\"hinge\" pos=\"{}\" axis=\"{}\"",
                v3(&w.cross(&v)),
                v3(&w)
            );
        }
    }
    let (lo, hi) = (j.limits.lower, j.limits.upper);
    if !matches!(j.kind, JointKind::Continuous) && limited(lo) && limited(hi) {
        let _ = write!(s, " range=\"{} {}\"", num(lo), num(hi));
    }
    for (key, x) in [
        ("damping", j.damping),
        ("frictionloss", j.friction),
        ("armature", j.armature),
        ("stiffness", j.stiffness),
    ] {
        if x != 0.0 {
            let _ = write!(s, " {key}=\"{}\"", num(x));
        }
    }
    if j.stiffness != 0.0 && j.springref != 0.0 {
        let _ = write!(s, " springref=\"{}\"", num(j.springref));
    }
    s += "/>";
    Ok(s)
}

/// The bound MuJoCo's compiler gives masses and principal moments of inertia
/// (`boundmass`, `boundinertia`) when some moving body has none: MuJoCo refuses a moving body
/// whose mass or any principal moment is below `mjMINVAL` (1e-15).
pub const MUJOCO_INERTIA_BOUND: f64 = 1e-14;

/// Whether MuJoCo would refuse body `b` as it is: no mass, or a principal moment of inertia
/// (about the centre of mass) below the bound (a point mass, a thin rod).
fn needs_bound(i: &SpatialInertia) -> bool {
    let smallest = i.inertia_com.symmetric_eigenvalues().min();
    i.mass < MUJOCO_INERTIA_BOUND || smallest < MUJOCO_INERTIA_BOUND
}

/// The `<inertial …/>` element: centre of mass, mass, and the inertia about the centre of mass
/// as `fullinertia="xx yy zz xy xz yz"` (MuJoCo's order); `diaginertia` when the body axes are
/// principal, and in the principal axes (`quat`) when the inertia is singular, which
/// `fullinertia` cannot hold.
fn inertial_element(i: &SpatialInertia) -> String {
    let c = &i.inertia_com;
    let head = format!("<inertial pos=\"{}\" mass=\"{}\"", v3(&i.com), num(i.mass));
    if c[(0, 1)] == 0.0 && c[(0, 2)] == 0.0 && c[(1, 2)] == 0.0 {
        return format!(
            "{head} diaginertia=\"{} {} {}\"/>",
            num(c[(0, 0)]),
            num(c[(1, 1)]),
            num(c[(2, 2)])
        );
    }
    let eig = c.symmetric_eigen();
    if eig.eigenvalues.min() <= MUJOCO_INERTIA_BOUND {
        // I_c = R diag(λ) Rᵀ with R the eigenvectors, made a rotation (det = +1).
        let mut r = eig.eigenvectors;
        if r.determinant() < 0.0 {
            r.column_mut(2).neg_mut();
        }
        let principal = Se3::new(r, i.com);
        let l = eig.eigenvalues.map(|x| x.max(0.0));
        return format!(
            "<inertial {} mass=\"{}\" diaginertia=\"{}\"/>",
            placement(&principal),
            num(i.mass),
            v3(&l)
        );
    }
    format!(
        "{head} fullinertia=\"{} {} {} {} {} {}\"/>",
        num(c[(0, 0)]),
        num(c[(1, 1)]),
        num(c[(2, 2)]),
        num(c[(0, 1)]),
        num(c[(0, 2)]),
        num(c[(1, 2)])
    )
}

/// What an export to MJCF changes, one sentence each: a moving body without mass or with a
/// singular rotational inertia (a point mass, a thin rod) is refused by MuJoCo, so the file
/// raises masses and principal moments to [`MUJOCO_INERTIA_BOUND`] (`boundmass`,
/// `boundinertia`), which changes `M(q)` by about that much. Empty when nothing changes.
///
/// ```
/// use screwdyn::io::mjcf_export::mjcf_export_warnings;
/// let w = mjcf_export_warnings(&screwdyn::builtin::planar2()); // point masses
/// assert_eq!(w.len(), 2);
/// assert!(w[0].contains("link1"));
/// assert!(mjcf_export_warnings(&screwdyn::builtin::load("ur5").unwrap()).is_empty());
/// ```
pub fn mjcf_export_warnings(model: &Model) -> Vec<String> {
    model
        .bodies()
        .iter()
        .filter(|b| needs_bound(&b.inertia))
        .map(|b| {
            format!(
                "link '{}' has no mass or a singular rotational inertia (a point mass or a thin \
                 rod), which MuJoCo refuses for a moving body: the MJCF file raises them to {} \
                 (boundmass, boundinertia), changing M by about as much",
                b.name, MUJOCO_INERTIA_BOUND
            )
        })
        .collect()
}

/// Writes `model` as MJCF (see the module documentation for the mapping): loading the text in
/// MuJoCo gives the same `M(q)` (armature included), bias forces `C q̇ + g` and frame poses
/// (as sites) as screwdyn.
///
/// # Errors
/// [`Error::InvalidModel`] for a joint MJCF cannot describe (a helical joint).
///
/// ```
/// use screwdyn::io::mjcf_export::to_mjcf_string;
/// let m = screwdyn::builtin::planar2().with_armature(&[0.1, 0.0]).unwrap();
/// let xml = to_mjcf_string(&m).unwrap();
/// assert!(xml.contains("<compiler angle=\"radian\" autolimits=\"true\""));
/// assert!(xml.contains("type=\"hinge\"") && xml.contains("armature=\"0.1\""));
/// ```
pub fn to_mjcf_string(model: &Model) -> Result<String> {
    let n = model.nbodies();
    let mut elements = Vec::with_capacity(n);
    for j in model.joints() {
        elements.push(joint_element(j)?);
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<!-- Written by screwdyn from model '{}'. -->",
        xml_comment(model.name())
    );
    let _ = writeln!(out, "<mujoco model=\"{}\">", xml_escape(model.name()));
    if model.bodies().iter().any(|b| needs_bound(&b.inertia)) {
        // See mjcf_export_warnings.
        let b = num(MUJOCO_INERTIA_BOUND);
        let _ = writeln!(
            out,
            "  <!-- MuJoCo refuses moving bodies without mass or rotational inertia: raised to {b}. -->"
        );
        let _ = writeln!(
            out,
            "  <compiler angle=\"radian\" autolimits=\"true\" boundmass=\"{b}\" boundinertia=\"{b}\"/>"
        );
    } else {
        let _ = writeln!(out, "  <compiler angle=\"radian\" autolimits=\"true\"/>");
    }
    let _ = writeln!(out, "  <option gravity=\"{}\"/>", v3(&model.gravity()));
    let _ = writeln!(out, "  <worldbody>");
    let sites = |body: Option<usize>, indent: &str, out: &mut String| {
        for f in model.frames() {
            if f.body == body && matches!(f.kind, FrameKind::FixedLink | FrameKind::Extra) {
                let _ = writeln!(
                    out,
                    "{indent}<site name=\"{}\" {}/>",
                    xml_escape(&f.name),
                    placement(&f.placement)
                );
            }
        }
    };
    sites(None, "    ", &mut out);
    // Depth-first, children in coordinate order; a stack of (body, depth, opening?) so deep
    // chains need no recursion.
    let roots: Vec<usize> = (0..n).filter(|&i| model.parents()[i].is_none()).collect();
    let mut stack: Vec<(usize, usize, bool)> = roots.iter().rev().map(|&i| (i, 0, true)).collect();
    while let Some((i, depth, open)) = stack.pop() {
        let indent = "  ".repeat(depth + 2);
        if !open {
            let _ = writeln!(out, "{indent}</body>");
            continue;
        }
        let (j, b) = (&model.joints()[i], &model.bodies()[i]);
        let _ = writeln!(
            out,
            "{indent}<body name=\"{}\" {}>",
            xml_escape(&b.name),
            placement(&j.home)
        );
        let inner = format!("{indent}  ");
        let _ = writeln!(out, "{inner}{}", elements[i]);
        let _ = writeln!(out, "{inner}{}", inertial_element(&b.inertia));
        sites(Some(i), &inner, &mut out);
        stack.push((i, depth, false));
        let children = model.children(i).unwrap_or(&[]);
        stack.extend(children.iter().rev().map(|&c| (c, depth + 1, true)));
    }
    let _ = writeln!(out, "  </worldbody>");
    let motors: Vec<&Joint> = model
        .joints()
        .iter()
        .filter(|j| limited(j.limits.effort) && j.limits.effort > 0.0)
        .collect();
    if !motors.is_empty() {
        let _ = writeln!(out, "  <actuator>");
        for j in motors {
            let e = num(j.limits.effort);
            let _ = writeln!(
                out,
                "    <motor name=\"{}\" joint=\"{}\" gear=\"1\" ctrlrange=\"-{e} {e}\" forcerange=\"-{e} {e}\"/>",
                xml_escape(&j.name),
                xml_escape(&j.name)
            );
        }
        let _ = writeln!(out, "  </actuator>");
    }
    let _ = writeln!(out, "</mujoco>");
    Ok(out)
}
