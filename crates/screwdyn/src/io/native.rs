//! The native TOML format (`format = "screwdyn"`): the quantities written directly.
//!
//! Per body: its `parent`, the home pose `H_i^{λ(i)}(0)` (`home`), the screw axis
//! `S_i` (`screw_in_parent = S_i^{λ(i),λ(i)}`, the `S_0_0_1`, or
//! `screw_in_child = S_i^{i,λ(i)}`), the joint kind and limits, and the inertia `𝔍^{i,i}`.
//!
//! | key | meaning |
//! | --- | --- |
//! | `format = "screwdyn"` | required |
//! | `name` | robot name (default: the file name) |
//! | `base` | root link name (default `base`) |
//! | `gravity = [gx, gy, gz]` | base-frame gravity, default `[0, 0, -9.81]` |
//! | `[[body]]` | one per link, in any order; joints are ordered depth-first from the root, children in file order |
//! | `body.name`, `body.parent` | link names (required) |
//! | `body.joint` | joint name (default `<name>_joint`) |
//! | `body.type` | `revolute`, `continuous`, `prismatic`, `helical` (with `pitch`, m/rad) or `fixed` |
//! | `body.home = { xyz, rpy \| quaternion \| rotation }` | `H_i^{λ(i)}(0)`; `quaternion = [w, x, y, z]`, `rotation` = 3 rows |
//! | `body.screw_in_parent` / `body.screw_in_child` | `[ωx, ωy, ωz, vx, vy, vz]` (one of them; not for `fixed`) |
//! | `body.limits = { lower, upper, velocity, effort }` | each optional, infinite when absent |
//! | `body.damping`, `body.friction` | viscous and Coulomb coefficients |
//! | `body.armature` | rotor inertia reflected to the joint (kg·m² or kg), added to `M(q)`'s diagonal |
//! | `body.stiffness`, `body.springref` | a joint spring: stiffness `k` (N·m/rad or N/m) and rest position `q_spring` (rad or m, default 0); simulation applies `τ = −k (q − q_spring)` |
//! | `body.mass`, `body.com`, `body.inertia` | mass, CoM in the link frame, inertia about the CoM `[ixx, ixy, ixz, iyy, iyz, izz]` |
//! | `body.shape` | or a uniform shape centred at `com`: `{ type = "box", size = [w, l, h] }`, `cylinder` `[r, h]` (axis z), `sphere` `[r]`, `rod` `[length]` (along z), `point`; optional `rpy` turns its axes |
//! | `body.spatial_inertia` | or the full 6×6 `𝔍^{i,i}` (6 rows, angular first, about the link origin) |
//! | `[[frame]]` `name`, `link`, `pose = { xyz, rpy \| … }` | extra frames (tool points...) |
//!
//! Unknown keys are errors.
//!
//! ```
//! use screwdyn::io::{native::parse_native, LoadOptions};
//! // The two-link arm: H_0_1_home, S_0_0_1, I_1 = point mass...
//! let text = r#"
//! format = "screwdyn"
//! gravity = [0, -9.81, 0]
//! [[body]]
//! name = "link1"
//! parent = "base"
//! joint = "joint1"
//! type = "revolute"
//! home = { xyz = [1, 0, 0] }
//! screw_in_parent = [0, 0, 1, 0, 0, 0]
//! mass = 1.0
//! [[body]]
//! name = "link2"
//! parent = "link1"
//! joint = "joint2"
//! type = "revolute"
//! home = { xyz = [1, 0, 0] }
//! screw_in_parent = [0, 0, 1, 0, 0, 0]
//! mass = 1.0
//! [[frame]]
//! name = "tip"
//! link = "link2"
//! "#;
//! let m = parse_native(text, "planar2.toml", &LoadOptions::default()).unwrap();
//! // S_1^{1,0} = Ad_{H_0_1_home⁻¹} S_0_0_1 = (0, 0, 1, 0, L1, 0)
//! assert_eq!(m.joints()[0].screw.as_slice(), &[0.0, 0.0, 1.0, 0.0, 1.0, 0.0]);
//! ```

use super::common::{self, FrameSpec, InertiaSpec, LimitSpec, PoseSpec};
use super::options::LoadOptions;
use crate::error::Result;
use crate::model::{JointSpec, Model};
use nalgebra::Vector6;
use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NativeFile {
    #[allow(dead_code)]
    format: String,
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    base: Option<String>,
    #[serde(default)]
    gravity: Option<[f64; 3]>,
    #[serde(default)]
    body: Vec<toml::Spanned<BodySpec>>,
    #[serde(default)]
    frame: Vec<toml::Spanned<FrameSpec>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BodySpec {
    name: String,
    parent: String,
    #[serde(default)]
    joint: Option<String>,
    #[serde(rename = "type")]
    kind: String,
    #[serde(default)]
    pitch: Option<f64>,
    #[serde(default)]
    home: PoseSpec,
    #[serde(default)]
    screw_in_parent: Option<[f64; 6]>,
    #[serde(default)]
    screw_in_child: Option<[f64; 6]>,
    #[serde(default)]
    limits: LimitSpec,
    #[serde(default)]
    damping: Option<f64>,
    #[serde(default)]
    friction: Option<f64>,
    #[serde(default)]
    armature: Option<f64>,
    #[serde(default)]
    stiffness: Option<f64>,
    #[serde(default)]
    springref: Option<f64>,
    #[serde(default)]
    mass: Option<f64>,
    #[serde(default)]
    com: Option<[f64; 3]>,
    #[serde(default)]
    inertia: Option<[f64; 6]>,
    #[serde(default)]
    spatial_inertia: Option<[[f64; 6]; 6]>,
    /// A shape primitive centred at `com` giving the inertia (issue 14).
    #[serde(default)]
    shape: Option<ShapeSpec>,
}

/// `shape = { type = "cylinder", size = [r, h], rpy = [..] }`: uniform density, centred at the
/// body's `com`, axes turned by `rpy` in the link frame; replaces `inertia`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ShapeSpec {
    #[serde(rename = "type")]
    kind: String,
    #[serde(default)]
    size: Vec<f64>,
    #[serde(default)]
    rpy: Option<[f64; 3]>,
}

impl ShapeSpec {
    /// The `[ixx, ixy, ixz, iyy, iyz, izz]` of mass `m` in this shape about its centre.
    fn inertia(&self, m: Option<f64>) -> std::result::Result<[f64; 6], String> {
        let m = m.ok_or("gives a shape without mass")?;
        let shape =
            crate::inertia::Shape::parse(&self.kind, &self.size).map_err(|e| e.to_string())?;
        let [r, p, y] = self.rpy.unwrap_or([0.0; 3]);
        let rot = crate::spatial::Se3::from_rpy(r, p, y).rotation;
        let i = crate::inertia::rotate(&shape.inertia_com(m).map_err(|e| e.to_string())?, &rot);
        Ok([
            i[(0, 0)],
            i[(0, 1)],
            i[(0, 2)],
            i[(1, 1)],
            i[(1, 2)],
            i[(2, 2)],
        ])
    }
}

/// Parses a native screwdyn TOML description (see the module documentation for the keys).
///
/// # Errors
/// [`Error::Parse`](crate::Error::Parse) for malformed text and
/// [`Error::InvalidModel`](crate::Error::InvalidModel) for an inconsistent model, each naming the
/// file and, where known, the line (and, with `strict`, the first physical-consistency
/// problem).
pub fn parse_native(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    let f: NativeFile = common::from_toml(text, file)?;
    let header = common::Header {
        name: f.name.as_deref(),
        base: f.base.as_deref(),
        gravity: f.gravity,
        frames: &f.frame,
    };
    let mut b = header.builder(file, options);
    let mut lines = common::Lines::new(text);
    for spanned in &f.body {
        let body = spanned.get_ref();
        let at = lines.at(file, spanned);
        let what = format!("body '{}'", body.name);
        let bad = |why: String| at.error(format!("{what} {why}"));
        let home = body
            .home
            .to_se3()
            .map_err(|w| bad(format!("home pose {w}")))?;
        let shape_inertia = match &body.shape {
            Some(_) if body.inertia.is_some() || body.spatial_inertia.is_some() => {
                return Err(bad("gives both a shape and an inertia".into()))
            }
            Some(shape) => Some(shape.inertia(body.mass).map_err(&bad)?),
            None => body.inertia,
        };
        let inertia = InertiaSpec {
            mass: body.mass,
            com: body.com,
            inertia: shape_inertia,
            spatial_inertia: body.spatial_inertia,
        }
        .to_inertia()
        .map_err(bad)?;
        b.locate(&body.name, at.to_string());
        let jname = body
            .joint
            .clone()
            .unwrap_or_else(|| format!("{}_joint", body.name));
        let mut j = match body.kind.as_str() {
            "revolute" => JointSpec::revolute(&jname),
            "continuous" => JointSpec::continuous(&jname),
            "prismatic" => JointSpec::prismatic(&jname),
            "helical" => match body.pitch {
                Some(p) => JointSpec::helical(&jname, p),
                None => return Err(bad("is helical but gives no pitch".into())),
            },
            "fixed" => JointSpec::fixed(&jname),
            "floating" | "planar" => {
                return Err(bad(format!(
                    "has a {} joint, which screwdyn does not support (fixed-base trees of 1-DoF joints only)",
                    body.kind
                )))
            }
            other => {
                return Err(bad(format!(
                    "has unknown joint type '{other}' (expected revolute, continuous, prismatic, helical or fixed)"
                )))
            }
        };
        if body.pitch.is_some() && body.kind != "helical" {
            return Err(bad("gives a pitch but is not helical".into()));
        }
        match (
            body.screw_in_parent,
            body.screw_in_child,
            body.kind.as_str(),
        ) {
            (None, None, "fixed") => {}
            (_, _, "fixed") => return Err(bad("is fixed but gives a screw axis".into())),
            (Some(s), None, _) => j = j.screw_in_parent(Vector6::from(s)),
            (None, Some(s), _) => j = j.screw_in_child(Vector6::from(s)),
            (Some(_), Some(_), _) => {
                return Err(bad("gives both screw_in_parent and screw_in_child".into()))
            }
            (None, None, _) => {
                return Err(bad(
                    "gives no screw axis (screw_in_parent or screw_in_child)".into(),
                ))
            }
        }
        j = body
            .limits
            .apply(j, body.damping, body.friction, body.armature);
        j = common::spring(j, body.stiffness, body.springref);
        b.link(&body.name, &body.parent, j, home, inertia);
    }
    header.finish(b, file, text)
}
