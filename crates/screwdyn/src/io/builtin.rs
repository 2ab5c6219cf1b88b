//! Built-in robots, available as `builtin:<name>` wherever a model path is accepted.
//!
//! - `planar2`: the classic two-link planar arm — point masses `m1 = m2 = 1` kg at
//!   the link ends, `L1 = L2 = 1` m, both joints about `z`, gravity `(0, −9.81, 0)` (along −y of
//!   the base, as in the example). Link frames sit at the link ends (the CoMs).
//! - `pendulum`: a simple pendulum, point mass 1 kg on a 1 m massless rod, joint about `z`,
//!   gravity `(0, −9.81, 0)`; at `q = 0` the mass hangs straight down.
//! - `ur5`: Universal Robots UR5 from its published standard-DH table, masses and CoMs
//!   (rotational inertias approximated as cylinders), `models/ur5.toml`.
//! - `panda`: Franka Emika Panda from its published modified-DH table and Gaz et al. (2019)'s
//!   inertial parameters, `models/panda.toml`.
//! - `branched`: a torso turning about `z` with a fixed head and two 3-DoF arms,
//!   `models/branched.toml`.
//!
//! The last three are the files in `models/`, compiled in with `include_str!`, so a built-in
//! and its file are the same robot.

use super::options::LoadOptions;
use super::toml_format::load_toml_str;
use crate::error::{Error, Result};
use crate::model::{JointSpec, Model, ModelBuilder};
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::{Vector3, Vector6};

/// The names accepted by [`load`].
pub const NAMES: &[&str] = &["planar2", "pendulum", "ur5", "panda", "branched"];

/// The shipped description files: (built-in name, file name in `models/`, text).
pub const FILES: &[(&str, &str, &str)] = &[
    (
        "planar2",
        "planar2.toml",
        include_str!("../../../../models/planar2.toml"),
    ),
    (
        "ur5",
        "ur5.toml",
        include_str!("../../../../models/ur5.toml"),
    ),
    (
        "panda",
        "panda.toml",
        include_str!("../../../../models/panda.toml"),
    ),
    (
        "branched",
        "branched.toml",
        include_str!("../../../../models/branched.toml"),
    ),
];

/// The shipped description a built-in robot is parsed from: `(file name in models/, text)`;
/// `None` for the robots built in code (`planar2`, `pendulum`) and unknown names.
fn shipped(name: &str) -> Option<(&'static str, &'static str)> {
    if matches!(name, "planar2" | "pendulum") {
        return None;
    }
    FILES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, file, text)| (*file, *text))
}

/// The text of the description the built-in robot `name` is parsed from (its file in
/// `models/`); `None` for the robots built in code (`planar2`, `pendulum`) and unknown names.
///
/// ```
/// assert!(screwdyn::builtin::description("ur5").unwrap().contains("format"));
/// assert_eq!(screwdyn::builtin::description("pendulum"), None);
/// ```
pub fn description(name: &str) -> Option<&'static str> {
    shipped(name).map(|(_, text)| text)
}

/// The built-in robot called `name` (without the `builtin:` prefix).
///
/// # Errors
/// [`Error::UnknownName`] for a name that is not a built-in robot.
///
/// ```
/// assert_eq!(screwdyn::builtin::load("pendulum").unwrap().nq(), 1);
/// assert_eq!(screwdyn::builtin::load("ur5").unwrap().nq(), 6);
/// assert_eq!(screwdyn::builtin::load("panda").unwrap().nq(), 7);
/// assert!(screwdyn::builtin::load("r2d2").unwrap_err().to_string().contains("planar2"));
/// ```
pub fn load(name: &str) -> Result<Model> {
    match name {
        "planar2" => Ok(planar2()),
        "pendulum" => Ok(pendulum()),
        _ => match shipped(name) {
            Some((file, text)) => load_toml_str(
                text,
                &format!("builtin:{name} (models/{file})"),
                &LoadOptions::default(),
            ),
            None => Err(Error::UnknownName {
                kind: "built-in robot",
                name: name.into(),
                known: NAMES.join(", "),
            }),
        },
    }
}

/// The two-link planar arm with given lengths and point masses.
///
/// ```
/// let m = screwdyn::builtin::planar2_with(0.5, 0.3, 2.0, 1.0);
/// assert!((m.total_mass() - 3.0).abs() < 1e-15);
/// ```
pub fn planar2_with(l1: f64, l2: f64, m1: f64, m2: f64) -> Model {
    let h_0_1_home = Se3::from_translation(Vector3::new(l1, 0.0, 0.0));
    let h_1_2_home = Se3::from_translation(Vector3::new(l2, 0.0, 0.0));
    let s_0_0_1 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let s_1_1_2 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let i_1 = SpatialInertia::point_mass(m1, Vector3::zeros());
    let i_2 = SpatialInertia::point_mass(m2, Vector3::zeros());
    let mut b = ModelBuilder::new("planar2");
    b.gravity(Vector3::new(0.0, -9.81, 0.0))
        .link(
            "link1",
            "base",
            JointSpec::revolute("joint1").screw_in_parent(s_0_0_1),
            h_0_1_home,
            i_1,
        )
        .link(
            "link2",
            "link1",
            JointSpec::revolute("joint2").screw_in_parent(s_1_1_2),
            h_1_2_home,
            i_2,
        );
    b.build().expect("planar2 is a valid model")
}

/// `planar2` with `L1 = L2 = 1` m and `m1 = m2 = 1` kg.
pub fn planar2() -> Model {
    planar2_with(1.0, 1.0, 1.0, 1.0)
}

/// A simple pendulum of length `l` and point mass `m`, hanging along −y at `q = 0`.
pub fn pendulum_with(l: f64, m: f64) -> Model {
    let mut b = ModelBuilder::new("pendulum");
    b.gravity(Vector3::new(0.0, -9.81, 0.0)).link(
        "bob",
        "base",
        JointSpec::continuous("pivot").screw_in_parent(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0)),
        Se3::from_translation(Vector3::new(0.0, -l, 0.0)),
        SpatialInertia::point_mass(m, Vector3::zeros()),
    );
    b.build().expect("pendulum is a valid model")
}

/// The 1 m, 1 kg pendulum.
pub fn pendulum() -> Model {
    pendulum_with(1.0, 1.0)
}
