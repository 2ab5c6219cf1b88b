//! Physical-consistency findings: what is wrong with a model's inertias that a published robot
//! file may still contain (round-off, sensor mounts, massless leaves). They are reported, not
//! refused: [`Model::physical_problems`](super::Model::physical_problems) lists them, the CLI
//! warns, `check` and strict loading make them errors.

use crate::spatial::InertiaProblem;

/// What is wrong.
#[derive(Clone, Debug, PartialEq)]
pub enum Problem {
    /// The link's own inertia is not physically consistent.
    Inertia(InertiaProblem),
    /// A moving body at a leaf of the tree has no mass: its joint moves nothing (forward
    /// dynamics fails on it unless rotational inertia alone carries a revolute joint).
    MasslessLeaf {
        /// The joint that moves it.
        joint: String,
    },
    /// A joint's mimic tag names a joint the model does not have (the mimic is information
    /// only: the joint is an independent coordinate either way).
    MissingMimicTarget {
        /// The joint it names.
        target: String,
    },
    /// A loader's warning about the description itself (e.g. MJCF joint ranges that look like
    /// degrees in a file whose angles are radians).
    Warning(String),
}

/// One problem of one link.
///
/// ```
/// use screwdyn::io::{load_str, LoadOptions};
/// let text = r#"<robot name="r"><link name="base"/>
///   <link name="a"><inertial><mass value="1"/>
///     <inertia ixx="0.001" iyy="0.001" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
///   <joint name="j" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint>
/// </robot>"#;
/// let m = load_str(text, "mount.urdf", &LoadOptions::default()).unwrap();
/// let f = &m.physical_problems()[0];
/// assert_eq!(f.link, "a");
/// assert!(f.to_string().starts_with("mount.urdf:2: link 'a': its inertia breaks the triangle inequality"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PhysicalFinding {
    /// The link (as named in the description); the joint, for a mimic problem.
    pub link: String,
    /// Where it was declared (`file:line`), when known.
    pub location: Option<String>,
    /// What is wrong.
    pub problem: Problem,
}

impl std::fmt::Display for PhysicalFinding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some(at) = &self.location {
            write!(f, "{at}: ")?;
        }
        match &self.problem {
            Problem::Inertia(p) => write!(f, "link '{}': its inertia {p}", self.link),
            Problem::MissingMimicTarget { target } => write!(
                f,
                "joint '{}' mimics joint '{target}', which does not exist",
                self.link
            ),
            Problem::Warning(message) => write!(f, "{message}"),
            Problem::MasslessLeaf { joint } => write!(
                f,
                "link '{}' is a moving leaf body with no mass: joint '{joint}' moves nothing",
                self.link
            ),
        }
    }
}
