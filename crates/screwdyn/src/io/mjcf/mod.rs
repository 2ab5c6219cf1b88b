//! MJCF, MuJoCo's XML format: loading ([`parse_mjcf`]) into the same [`Model`] as every other
//! format, and the conformance report of what the loader left out ([`parse_mjcf_report`]).
//!
//! Mapping (docs/formats.md, "MJCF"): every body in `<worldbody>` is a link, `world` the base;
//! hinge and slide joints move it about or along `axis` through `pos`, both in the body frame,
//! several joints in one body become a chain of massless links named `body/joint`, a body
//! without joints is welded to its parent. `q` is MuJoCo's `qpos` (each joint's `ref` is folded
//! into its home pose). `<compiler>` (angle unit — MuJoCo's default is degrees —, `eulerseq`,
//! `autolimits`, `meshdir`, `inertiafromgeom`, `inertiagrouprange`, `boundmass`,
//! `boundinertia`, `settotalmass`), `<default>` classes with `class` and `childclass`, and
//! `<include>` (relative to the including file, a cycle is an error) are read as MuJoCo reads
//! them; a body without `<inertial>` gets the mass and inertia of its geoms (primitives and
//! STL/OBJ meshes). Sites are frames of the same name, `<key>`s named configurations
//! ([`Model::keyframe`](crate::Model::keyframe)), effort limits come from `actuatorfrcrange`
//! and the actuators' `forcerange`/`ctrlrange` × `gear`. Free and ball joints are errors.
//!
//! ```
//! use screwdyn::io::{mjcf::parse_mjcf_report, LoadOptions};
//! let text = r#"<mujoco model="arm">
//!   <compiler angle="radian"/>
//!   <worldbody>
//!     <body name="link" pos="0 0 1">
//!       <joint name="j" axis="0 0 1" range="-1 1" damping="0.5"/>
//!       <geom type="box" size="0.1 0.2 0.3" mass="2" rgba="1 0 0 1"/>
//!       <site name="tip" pos="0.5 0 0"/>
//!     </body>
//!   </worldbody>
//!   <tendon/>
//! </mujoco>"#;
//! let (m, ignored) = parse_mjcf_report(text, "arm.xml", &LoadOptions::default()).unwrap();
//! assert_eq!(m.joint_names(), vec!["j"]);
//! // A box of half-sizes (0.1, 0.2, 0.3): I_zz = m (a² + b²)/3.
//! let izz = m.bodies()[0].inertia.inertia_com[(2, 2)];
//! assert!((izz - 2.0 * (0.01 + 0.04) / 3.0).abs() < 1e-15);
//! assert!(m.frame_id("tip").is_ok());
//! let lines: Vec<String> = ignored.iter().map(|i| i.to_string()).collect();
//! assert_eq!(lines, vec!["arm.xml:6: <geom>: ignored rgba", "arm.xml:10: <tendon> ignored"]);
//! ```

mod actuators;
mod bodies;
mod compiler;
mod defaults;
mod geoms;
mod hull;
mod mesh;
mod orientation;
mod report;
mod tree;
mod values;
mod visuals;

pub use report::Ignored;

use crate::error::Result;
use crate::io::common::{build, default_name};
use crate::io::options::LoadOptions;
use crate::io::visual::Visual;
use crate::model::{JointSpec, Model, ModelBuilder};

/// The name of the base (MuJoCo's world body).
const WORLD: &str = "world";

/// Parses MJCF text into a [`Model`]; `file` names it in messages and locates `<include>`d
/// files and meshes (relative to its directory).
///
/// # Errors
/// [`Error::Parse`](crate::Error::Parse) for malformed XML, a missing or cyclic include, an
/// unknown default class, a value that is not a number or out of range;
/// [`Error::InvalidModel`](crate::Error::InvalidModel) for a free or ball joint, a zero axis, a
/// non-positive mass or a non-positive-definite inertia; each at `file:line`.
pub fn parse_mjcf(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    parse_mjcf_report(text, file, options).map(|(m, _)| m)
}

/// As [`parse_mjcf`], with the conformance report: every element and attribute the loader did
/// not use (tendons, equality constraints, contacts, actuator dynamics, visual settings…),
/// element by element, in file order.
///
/// # Errors
/// As [`parse_mjcf`].
pub fn parse_mjcf_report(
    text: &str,
    file: &str,
    options: &LoadOptions,
) -> Result<(Model, Vec<Ignored>)> {
    load(text, file, options, false).map(|(m, r, _)| (m, r))
}

/// The geoms of an MJCF text a viewer draws, as [`Visual`]s of the model's links: those in the
/// groups MuJoCo's viewer shows by default (0, 1 and 2; Menagerie puts its visual meshes in
/// group 2 and its collision shapes in group 3), with the geom's `rgba`, else its material's.
/// Mesh files are given by their path through `<compiler meshdir>`, made absolute.
///
/// # Errors
/// As [`parse_mjcf`] (the model is loaded to place the geoms).
///
/// ```
/// use screwdyn::io::{mjcf::parse_mjcf_visuals, visual::Shape, LoadOptions};
/// let text = r#"<mujoco><asset><material name="red" rgba="1 0 0 1"/></asset>
///   <worldbody><body name="b"><joint/>
///     <geom type="box" size="0.1 0.2 0.3" material="red"/>
///     <geom type="sphere" size="0.5" group="3"/>
///   </body></worldbody></mujoco>"#;
/// let v = parse_mjcf_visuals(text, "m.xml", &LoadOptions::default()).unwrap();
/// assert_eq!(v.len(), 1); // group 3 (collision) is not drawn
/// assert_eq!(v[0].shape, Shape::Box { size: [0.2, 0.4, 0.6] });
/// assert_eq!(v[0].color, Some([1.0, 0.0, 0.0, 1.0]));
/// ```
pub fn parse_mjcf_visuals(text: &str, file: &str, options: &LoadOptions) -> Result<Vec<Visual>> {
    load(text, file, options, true).map(|(_, _, v)| v)
}

/// The model, the conformance report and (when `want_visuals`) the visual geoms.
fn load(
    text: &str,
    file: &str,
    options: &LoadOptions,
    want_visuals: bool,
) -> Result<(Model, Vec<Ignored>, Vec<Visual>)> {
    let tree = tree::read(text, file)?;
    tree.root.take();
    let name = tree
        .root
        .attr("model")
        .map_or_else(|| default_name(file), str::to_string);
    let defaults = defaults::Defaults::read(&tree)?;
    let compiler = compiler::Compiler::read(&tree, &defaults, file)?;
    let meshes = mesh::MeshTable::read(&tree, &defaults, &compiler)?;
    let mut walk = bodies::Walk::new(&tree, &defaults, &compiler, &meshes);
    walk.world(WORLD)?;
    actuators::effort_limits(&tree, &defaults, compiler.autolimits, &mut walk.joints)?;
    let keys = actuators::keyframes(&tree, &defaults, &walk.joints)?;

    let mut b = ModelBuilder::new(&name);
    b.strict(options.strict)
        .base_name(WORLD)
        .gravity(actuators::gravity(&tree, &defaults)?);
    let scale = total_mass_scale(&walk.links, compiler.set_total_mass);
    for l in &walk.links {
        b.locate(&l.name, l.at.clone());
        let mut inertia = l.inertia;
        inertia.mass *= scale;
        inertia.inertia_com *= scale;
        let spec = match l.joint {
            None => JointSpec::fixed(&format!("{}/weld", l.name)),
            Some(k) => joint_spec(&walk.joints[k]),
        };
        b.link(&l.name, &l.parent, spec, l.home, inertia);
    }
    for (site, link, placement) in &walk.sites {
        b.frame(site, link, *placement);
    }
    for (key, q) in keys {
        b.keyframe(&key, q);
    }
    for (at, message) in &walk.warnings {
        b.warn(&name, Some(at.clone()), message.clone());
    }
    let model = build(&b, file)?;
    // The report first: reading the geoms' colours marks them as used.
    let report = report::ignored(&tree);
    let visuals = if want_visuals {
        visuals::visuals(&walk)?
    } else {
        Vec::new()
    };
    Ok((model, report, visuals))
}

/// The conformance report of the MJCF file at `path` ([`parse_mjcf_report`] of its text);
/// `None` when `path` is not an MJCF file (another extension, or a `.xml` URDF).
///
/// # Errors
/// [`Error::Io`](crate::Error::Io) when the file cannot be read; else as [`parse_mjcf`].
pub fn report_of_file(path: &str, options: &LoadOptions) -> Result<Option<Vec<Ignored>>> {
    use crate::io::Format;
    if Format::of_file(path) != Some(Format::Mjcf) {
        return Ok(None);
    }
    let text = std::fs::read_to_string(path).map_err(|e| crate::Error::unreadable(path, &e))?;
    if Format::of_text(&text) != Format::Mjcf {
        return Ok(None);
    }
    parse_mjcf_report(&text, path, options).map(|(_, r)| Some(r))
}

/// `settotalmass`: the factor that makes the bodies' masses add up to it (1 when unset).
fn total_mass_scale(links: &[bodies::Link], total: f64) -> f64 {
    let sum: f64 = links.iter().map(|l| l.inertia.mass).sum();
    if total > 0.0 && sum > 0.0 {
        total / sum
    } else {
        1.0
    }
}

/// The builder's joint: screw in the child (body) frame, limits, damping, friction, armature,
/// spring.
fn joint_spec(j: &bodies::MJoint) -> JointSpec {
    let spec = match (j.slide, j.limits) {
        (true, _) => JointSpec::prismatic(&j.name),
        (false, Some(_)) => JointSpec::revolute(&j.name),
        (false, None) => JointSpec::continuous(&j.name),
    };
    let (lower, upper) = j.limits.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    spec.screw_in_child(j.screw)
        .limits(lower, upper)
        .effort_limit(j.effort)
        .damping(j.damping)
        .friction(j.friction)
        .armature(j.armature)
        .spring(j.stiffness, j.springref)
}
