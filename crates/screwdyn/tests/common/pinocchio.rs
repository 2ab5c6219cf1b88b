//! Loader for the Pinocchio reference fixtures in `tests/fixtures/pinocchio/*.json`, written by
//! `scripts/gen_reference.py` (schema: `tests/fixtures/pinocchio/README.md`). Everything in the
//! files is already angular first (twists `(ω, v)`, Jacobian rows angular then linear).
//!
//! [`load_fixture`] parses a file and rebuilds the same robot through screwdyn's own
//! [`ModelBuilder`], so no third-party URDF is needed. Include it from a test with
//! `#[path = "common/pinocchio.rs"] mod pinocchio;`.
#![allow(dead_code)]

use nalgebra::{DMatrix, Matrix3, Matrix4, Matrix6xX, Vector3, Vector6};
use screwdyn::model::JointSpec;
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{Model, ModelBuilder};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The name the rebuilt model gives its root link: Pinocchio's universe frame.
pub const BASE: &str = "universe";

/// The three robots with fixtures.
pub const ROBOTS: [&str; 3] = ["ur5", "panda", "tree"];

/// A rigid transform as written in the fixtures.
#[derive(Clone, Debug, Deserialize)]
pub struct Placement {
    /// Rows of the 3×3 rotation matrix.
    pub rotation: [[f64; 3]; 3],
    /// The translation.
    pub translation: [f64; 3],
}

impl Placement {
    /// As an [`Se3`].
    pub fn se3(&self) -> Se3 {
        Se3::new(
            Matrix3::from_fn(|r, c| self.rotation[r][c]),
            Vector3::from(self.translation),
        )
    }
}

/// Mass, centre of mass and rotational inertia about the CoM, in the joint (body) frame.
#[derive(Clone, Debug, Deserialize)]
pub struct InertiaData {
    pub mass: f64,
    pub com: [f64; 3],
    pub inertia_com: [[f64; 3]; 3],
}

impl InertiaData {
    /// As a [`SpatialInertia`].
    pub fn spatial(&self) -> SpatialInertia {
        SpatialInertia::new(
            self.mass,
            Vector3::from(self.com),
            Matrix3::from_fn(|r, c| self.inertia_com[r][c]),
        )
    }
}

/// Position, velocity and effort limits (Pinocchio's model limits).
#[derive(Clone, Debug, Deserialize)]
pub struct Limits {
    pub lower: f64,
    pub upper: f64,
    pub velocity: f64,
    pub effort: f64,
}

/// One moving joint, in Pinocchio order (the universe joint skipped).
#[derive(Clone, Debug, Deserialize)]
pub struct JointData {
    pub name: String,
    /// Index of the parent joint in the fixture's joint list; `None` for the base.
    pub parent: Option<usize>,
    /// `revolute` or `prismatic`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Unit axis in the joint (child) frame; the axis passes through the joint frame origin.
    pub axis: [f64; 3],
    /// `H_c^p(0)`: the joint frame in the parent joint frame at `q = 0`.
    pub placement: Placement,
    /// The child link (Pinocchio BODY frame placed at the joint frame).
    pub body_name: String,
    /// Inertia of the child link with fixed descendants merged.
    pub inertia: InertiaData,
    pub limits: Limits,
}

impl JointData {
    /// The screw axis `S_c^{c,p}`, angular first.
    pub fn screw(&self) -> Vector6<f64> {
        let [x, y, z] = self.axis;
        match self.kind.as_str() {
            "revolute" => Vector6::new(x, y, z, 0.0, 0.0, 0.0),
            "prismatic" => Vector6::new(0.0, 0.0, 0.0, x, y, z),
            k => panic!("joint '{}' has unsupported type '{k}'", self.name),
        }
    }
}

/// A named frame (Pinocchio BODY or OP_FRAME).
#[derive(Clone, Debug, Deserialize)]
pub struct FrameData {
    pub name: String,
    /// Index of the joint it moves with; `None` for the base.
    pub joint: Option<usize>,
    /// `body` or `op`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Pose in the joint frame (in the base frame when `joint` is `None`).
    pub placement: Placement,
}

/// One random state and everything Pinocchio computed at it. Matrices are lists of rows.
#[derive(Clone, Debug, Deserialize)]
pub struct State {
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
    /// The torque given to ABA.
    pub tau_in: Vec<f64>,
    /// `rnea(q, v, a)`.
    pub tau: Vec<f64>,
    /// `M(q)` (crba, symmetrised).
    pub mass_matrix: Vec<Vec<f64>>,
    /// `g(q)` (computeGeneralizedGravity).
    pub gravity: Vec<f64>,
    /// `C(q, v) v + g(q)` (nonLinearEffects).
    pub nonlinear_effects: Vec<f64>,
    /// `C(q, v) v`.
    pub coriolis_times_v: Vec<f64>,
    /// `C(q, v)` (computeCoriolisMatrix).
    pub coriolis_matrix: Vec<Vec<f64>>,
    /// `aba(q, v, tau_in)`.
    pub qdd: Vec<f64>,
    /// `H_f^0` (4×4 rows) of every frame on a moving body.
    pub frame_poses: BTreeMap<String, Vec<Vec<f64>>>,
    /// 6×n Jacobians (angular rows first) of the `jacobian_frames`.
    pub jacobians_world: BTreeMap<String, Vec<Vec<f64>>>,
    pub jacobians_local: BTreeMap<String, Vec<Vec<f64>>>,
    pub jacobians_local_world_aligned: BTreeMap<String, Vec<Vec<f64>>>,
    /// `computeRNEADerivatives` / `computeABADerivatives` with external wrenches.
    pub derivatives: DerivativeData,
}

/// Pinocchio's first-order derivatives at one state, with body-fixed external wrenches `fext`
/// (random on even states, zero on odd ones). Matrices are lists of rows, entry `(i, j)` is
/// `∂y_i/∂x_j`.
#[derive(Clone, Debug, Deserialize)]
pub struct DerivativeData {
    /// One wrench per joint, angular first, in the joint (body) frame: on the body.
    pub fext: Vec<[f64; 6]>,
    /// `rnea(q, v, a, fext)`.
    pub tau_fext: Vec<f64>,
    /// `aba(q, v, tau_in, fext)`.
    pub qdd_fext: Vec<f64>,
    /// `computeRNEADerivatives(q, v, a, fext)`.
    pub dtau_dq: Vec<Vec<f64>>,
    pub dtau_dv: Vec<Vec<f64>>,
    pub dtau_da: Vec<Vec<f64>>,
    /// `computeABADerivatives(q, v, tau_in, fext)`.
    pub dqdd_dq: Vec<Vec<f64>>,
    pub dqdd_dv: Vec<Vec<f64>>,
    pub minv: Vec<Vec<f64>>,
}

/// A whole fixture file.
#[derive(Clone, Debug, Deserialize)]
pub struct Fixture {
    pub robot: String,
    pub source: String,
    pub pinocchio_version: String,
    pub example_robot_data_version: String,
    /// Where the URDF was on the generating machine (information only), `None` for `tree`.
    pub urdf_path: Option<String>,
    pub gravity: [f64; 3],
    pub joints: Vec<JointData>,
    pub frames: Vec<FrameData>,
    /// Frames that have Jacobians in every state.
    pub jacobian_frames: Vec<String>,
    pub states: Vec<State>,
}

impl Fixture {
    /// Joint names in order.
    pub fn joint_names(&self) -> Vec<&str> {
        self.joints.iter().map(|j| j.name.as_str()).collect()
    }
}

/// Rows of a fixture matrix as a dense matrix.
pub fn dmatrix(rows: &[Vec<f64>]) -> DMatrix<f64> {
    let (r, c) = (rows.len(), rows.first().map_or(0, Vec::len));
    assert!(rows.iter().all(|row| row.len() == c), "ragged matrix");
    DMatrix::from_fn(r, c, |i, j| rows[i][j])
}

/// A fixture 4×4 pose.
pub fn matrix4(rows: &[Vec<f64>]) -> Matrix4<f64> {
    assert!(
        rows.len() == 4 && rows.iter().all(|r| r.len() == 4),
        "not 4×4"
    );
    Matrix4::from_fn(|i, j| rows[i][j])
}

/// A fixture 6×n Jacobian.
pub fn jacobian(rows: &[Vec<f64>]) -> Matrix6xX<f64> {
    assert_eq!(rows.len(), 6, "a Jacobian has 6 rows");
    let n = rows[0].len();
    Matrix6xX::from_fn(n, |i, j| rows[i][j])
}

/// Path of a fixture file.
pub fn fixture_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/pinocchio")
        .join(format!("{name}.json"))
}

/// Parses `tests/fixtures/pinocchio/<name>.json`.
pub fn read_fixture(name: &str) -> Fixture {
    let path = fixture_path(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("cannot parse {}: {e}", path.display()))
}

/// Rebuilds the fixture's robot with [`ModelBuilder`]: the root link is [`BASE`], link `j`
/// is `body_name` attached by joint `j` at `placement` with screw axis `axis` in the child
/// frame; frames that are not a joint's child link become extra frames.
pub fn build_model(fx: &Fixture) -> Model {
    let mut b = ModelBuilder::new(&fx.robot);
    b.base_name(BASE)
        .gravity(Vector3::from(fx.gravity))
        .strict(false);
    let link_of = |joint: Option<usize>| joint.map_or(BASE, |p| fx.joints[p].body_name.as_str());
    for j in &fx.joints {
        let spec = match j.kind.as_str() {
            "revolute" => JointSpec::revolute(&j.name),
            "prismatic" => JointSpec::prismatic(&j.name),
            k => panic!("joint '{}' has unsupported type '{k}'", j.name),
        }
        .screw_in_child(j.screw())
        .limits(j.limits.lower, j.limits.upper)
        .velocity_limit(j.limits.velocity)
        .effort_limit(j.limits.effort);
        b.link(
            &j.body_name,
            link_of(j.parent),
            spec,
            j.placement.se3(),
            j.inertia.spatial(),
        );
    }
    for f in &fx.frames {
        if fx.joints.iter().any(|j| j.body_name == f.name) {
            continue; // a body frame, created with its link
        }
        b.frame(&f.name, link_of(f.joint), f.placement.se3());
    }
    b.build()
        .unwrap_or_else(|e| panic!("fixture '{}' does not build: {e}", fx.robot))
}

/// Reads fixture `name` (`ur5`, `panda` or `tree`) and rebuilds its robot.
pub fn load_fixture(name: &str) -> (Model, Fixture) {
    let fx = read_fixture(name);
    let model = build_model(&fx);
    (model, fx)
}

/// `max |got − want| / max(1, |want|)` over the entries: the relative error the fixture tests
/// bound.
pub fn rel(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len());
    got.iter()
        .zip(want)
        .map(|(g, w)| (g - w).abs() / w.abs().max(1.0))
        .fold(0.0, f64::max)
}
