//! Denavit–Hartenberg tables in TOML: standard DH (`format = "dh"`) and modified DH
//! (`format = "modified-dh"`, Craig, Craig, *Introduction to Robotics*).
//!
//! **Standard DH**: link frame `{i}` in `{i−1}` is
//! `A_i^{i−1} = Rot_z(θ_i) Trans_z(d_i) Trans_x(a_i) Rot_x(α_i)`; joint `i` turns `θ_i` (R) or
//! slides `d_i` (P) about/along `z_{i−1}`. In the notation of docs/notation.md the screw is written in the
//! parent frame at home, `S = (ẑ, 0)` (R) or `(0, ẑ)` (P), and the home pose is
//! `H_i^{i−1}(0) = Rot_z(θ_offset) Trans_z(d) Trans_x(a) Rot_x(α)`.
//!
//! **Modified DH** (Craig): `H_i^{i−1} = Rot_x(α_{i−1}) Trans_x(a_{i−1}) Rot_z(θ_i) Trans_z(d_i)`;
//! the joint axis is `z_i` of the child frame: `S_i^{i,i−1} = (ẑ, 0)` (R) or `(0, ẑ)` (P). On row
//! `i`, `a` and `alpha` are Craig's `a_{i−1}` and `α_{i−1}` (the values printed on row `i` of his
//! tables).
//!
//! | key | meaning |
//! | --- | --- |
//! | `format` | `"dh"` or `"modified-dh"` |
//! | `name`, `base`, `gravity` | robot name, root link name (default `base`), gravity (default `[0, 0, -9.81]`) |
//! | `[[row]]` | one per joint, in chain order |
//! | `row.type` | `"R"` (revolute), `"P"` (prismatic) or `"C"` (continuous revolute) |
//! | `row.a`, `row.alpha`, `row.d`, `row.theta` | DH parameters (m, rad); the joint's own variable (`θ` for R, `d` for P) is `q + offset`, its value here the offset; all default 0 |
//! | `row.name`, `row.link` | joint and link names (default `joint<i>`, `link<i>`) |
//! | `row.parent` | parent link (default: the previous row's link, or the base) — allows trees |
//! | `row.limits = { lower, upper, velocity, effort }`, `row.damping`, `row.friction` | joint limits, viscous and Coulomb coefficients |
//! | `row.armature` | rotor inertia reflected to the joint (kg·m² or kg), added to `M(q)`'s diagonal |
//! | `row.stiffness`, `row.springref` | a joint spring: stiffness `k` (N·m/rad or N/m) and rest position `q_spring` (rad or m, default 0); simulation applies `τ = −k (q − q_spring)` |
//! | `row.mass`, `row.com`, `row.inertia` | link mass, CoM in link frame `{i}`, inertia about the CoM `[ixx, ixy, ixz, iyy, iyz, izz]` |
//! | `[[frame]]` `name`, `link`, `pose = { xyz, rpy }` | extra frames (a flange, a tool) |
//!
//! ```
//! use screwdyn::io::{dh::parse_dh, LoadOptions};
//! use screwdyn::{kinematics::forward_kinematics, Workspace};
//! // The two-link planar arm as a standard DH table: a1 = a2 = 1.
//! let text = r#"
//! format = "dh"
//! [[row]]
//! type = "R"
//! a = 1.0
//! mass = 1.0
//! [[row]]
//! type = "R"
//! a = 1.0
//! mass = 1.0
//! "#;
//! let m = parse_dh(text, "planar.toml", &LoadOptions::default()).unwrap();
//! let mut ws = Workspace::new(&m);
//! let (q1, q2) = (0.3_f64, 0.4_f64);
//! forward_kinematics(&m, &mut ws, &[q1, q2]).unwrap();
//! let p = ws.pose_in_world[1].translation;
//! assert!((p.x - (q1.cos() + (q1 + q2).cos())).abs() < 1e-15);
//! ```

use super::common::{self, FrameSpec, LimitSpec};
use super::options::LoadOptions;
use crate::error::{Error, Result};
use crate::model::{JointSpec, Model};
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::{Vector3, Vector6};
use serde::Deserialize;

/// A DH file's keys as read from its TOML text (the built-in tables of `builtin_tables.rs` are
/// values of this type, written out from `models/`).
#[derive(Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct DhFile {
    pub format: String,
    #[serde(default)]
    pub name: Option<String>,
    #[serde(default)]
    pub base: Option<String>,
    #[serde(default)]
    pub gravity: Option<[f64; 3]>,
    #[serde(default)]
    pub row: Vec<toml::Spanned<Row>>,
    #[serde(default)]
    pub frame: Vec<toml::Spanned<FrameSpec>>,
}

/// One `[[row]]` of a DH table.
#[derive(Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct Row {
    #[serde(rename = "type")]
    pub kind: String,
    #[serde(default)]
    pub a: f64,
    #[serde(default)]
    pub alpha: f64,
    #[serde(default)]
    pub d: f64,
    #[serde(default)]
    pub theta: f64,
    #[serde(default)]
    pub name: Option<String>,
    #[serde(default)]
    pub link: Option<String>,
    #[serde(default)]
    pub parent: Option<String>,
    #[serde(default)]
    pub limits: LimitSpec,
    #[serde(default)]
    pub damping: Option<f64>,
    #[serde(default)]
    pub friction: Option<f64>,
    #[serde(default)]
    pub armature: Option<f64>,
    #[serde(default)]
    pub stiffness: Option<f64>,
    #[serde(default)]
    pub springref: Option<f64>,
    #[serde(default)]
    pub mass: Option<f64>,
    #[serde(default)]
    pub com: Option<[f64; 3]>,
    #[serde(default)]
    pub inertia: Option<[f64; 6]>,
}

fn rot_z(t: f64) -> Se3 {
    Se3::from_rpy(0.0, 0.0, t)
}
fn rot_x(t: f64) -> Se3 {
    Se3::from_rpy(t, 0.0, 0.0)
}
fn trans(x: f64, y: f64, z: f64) -> Se3 {
    Se3::from_translation(Vector3::new(x, y, z))
}

/// `A_i^{i−1} = Rot_z(θ) Trans_z(d) Trans_x(a) Rot_x(α)` (standard DH).
pub fn standard_dh_transform(a: f64, alpha: f64, d: f64, theta: f64) -> Se3 {
    rot_z(theta)
        .compose(&trans(a, 0.0, d))
        .compose(&rot_x(alpha))
}

/// `Rot_x(α_{i−1}) Trans_x(a_{i−1}) Rot_z(θ_i) Trans_z(d_i)` (modified DH, Craig, Craig, *Introduction to Robotics*).
pub fn modified_dh_transform(a_prev: f64, alpha_prev: f64, d: f64, theta: f64) -> Se3 {
    rot_x(alpha_prev)
        .compose(&trans(a_prev, 0.0, 0.0))
        .compose(&rot_z(theta))
        .compose(&trans(0.0, 0.0, d))
}

/// Parses a standard or modified DH table (see the module documentation for the keys).
///
/// # Errors
/// [`Error::Parse`] for malformed text and [`Error::InvalidModel`] for an inconsistent model,
/// each naming the file and, where known, the line (and, with `strict`, the first
/// physical-consistency problem).
pub fn parse_dh(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    let f: DhFile = common::from_toml(text, file)?;
    dh_model(&f, text, file, options)
}

/// The model of a DH table already read from `text` (the spans of its rows and frames are
/// byte offsets in `text`, for the line an error names).
pub(crate) fn dh_model(f: &DhFile, text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    let modified = match f.format.as_str() {
        "dh" => false,
        "modified-dh" => true,
        other => {
            return Err(Error::parse(
                file,
                format!("format '{other}' is not a DH table (expected dh or modified-dh)"),
            ))
        }
    };
    let header = common::Header {
        name: f.name.as_deref(),
        base: f.base.as_deref(),
        gravity: f.gravity,
        frames: &f.frame,
    };
    let mut b = header.builder(file, options);
    let base = header.base().to_string();
    if f.row.is_empty() {
        return Err(Error::parse(file, "the DH table has no [[row]]"));
    }
    let mut previous = base.clone();
    let z = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let z_lin = Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
    let mut lines = common::Lines::new(text);
    for (k, spanned) in f.row.iter().enumerate() {
        let row = spanned.get_ref();
        let at = lines.at(file, spanned);
        let i = k + 1;
        let jname = row.name.clone().unwrap_or_else(|| format!("joint{i}"));
        let lname = row.link.clone().unwrap_or_else(|| format!("link{i}"));
        let bad = |why: String| at.error(format!("DH row {i} (joint '{jname}') {why}"));
        let nums = [row.a, row.alpha, row.d, row.theta];
        if !nums.iter().all(|x| x.is_finite()) {
            return Err(bad("has a non-finite DH parameter".into()));
        }
        let home = if modified {
            modified_dh_transform(row.a, row.alpha, row.d, row.theta)
        } else {
            standard_dh_transform(row.a, row.alpha, row.d, row.theta)
        };
        let prismatic = match row.kind.as_str() {
            "R" | "r" | "C" | "c" => false,
            "P" | "p" => true,
            other => {
                return Err(bad(format!(
                "has joint type '{other}', expected R (revolute), P (prismatic) or C (continuous)"
            )))
            }
        };
        let mut j = match row.kind.as_str() {
            "P" | "p" => JointSpec::prismatic(&jname),
            "C" | "c" => JointSpec::continuous(&jname),
            _ => JointSpec::revolute(&jname),
        };
        let s = if prismatic { z_lin } else { z };
        j = if modified {
            j.screw_in_child(s)
        } else {
            j.screw_in_parent(s)
        };
        j = row.limits.apply(j, row.damping, row.friction, row.armature);
        j = common::spring(j, row.stiffness, row.springref);
        if row.mass.is_none() && (row.com.is_some() || row.inertia.is_some()) {
            return Err(bad("gives com or inertia without mass".into()));
        }
        let inertia = SpatialInertia::new(
            row.mass.unwrap_or(0.0),
            Vector3::from(row.com.unwrap_or([0.0; 3])),
            common::inertia_matrix(row.inertia.unwrap_or([0.0; 6])),
        );
        b.locate(&lname, at.to_string());
        let parent = row.parent.clone().unwrap_or(previous);
        b.link(&lname, &parent, j, home, inertia);
        previous = lname;
    }
    header.finish(b, file, text)
}
