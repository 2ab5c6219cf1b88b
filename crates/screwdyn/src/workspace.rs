//! [`Workspace`]: everything an algorithm writes, allocated once per model (Pinocchio's `Data`).

use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::{Se3, Twist, Wrench};

/// Preallocated per-model buffers. Algorithms read a [`Model`] and write here; after
/// `Workspace::new` no algorithm call allocates.
///
/// Field names follow DESIGN §3: `pose_in_parent[i] = H_i^{λ(i)}(q)`,
/// `pose_in_world[i] = H_i^0(q)`, `twist[i] = V_i^{i,0}`, `twist_dot[i] = V̇_i^{i,0}`,
/// `wrench[i] = W_{λ(i)}^{i,i}`.
///
/// ```
/// let model = screwdyn::builtin::planar2();
/// let mut ws = screwdyn::Workspace::new(&model);
/// screwdyn::kinematics::forward_kinematics(&model, &mut ws, &[0.0, 0.0]).unwrap();
/// assert_eq!(ws.pose_in_world[1].translation.x, 2.0);
/// ```
#[derive(Clone, Debug)]
pub struct Workspace<T: Real = f64> {
    /// `H_i^{λ(i)}(q)`.
    pub pose_in_parent: Vec<Se3<T>>,
    /// `H_i^0(q)`.
    pub pose_in_world: Vec<Se3<T>>,
    /// `Ad_{H_i^0} S_i`: joint `i`'s screw axis in the base frame (a column of the space Jacobian).
    pub screw_in_world: Vec<Twist<T>>,
    /// `V_i^{i,0}`: body twist of body `i` in its own frame.
    pub twist: Vec<Twist<T>>,
    /// `V̇_i^{i,0}`: its time derivative.
    pub twist_dot: Vec<Twist<T>>,
    /// `W_{λ(i)}^{i,i}`: wrench of the parent on body `i`, in frame `i`.
    pub wrench: Vec<Wrench<T>>,
}

impl<T: Real> Workspace<T> {
    /// Allocates the buffers for `model`.
    pub fn new(model: &Model<T>) -> Self {
        let n = model.nbodies();
        Workspace {
            pose_in_parent: vec![Se3::identity(); n],
            pose_in_world: vec![Se3::identity(); n],
            screw_in_world: vec![Twist::zeros(); n],
            twist: vec![Twist::zeros(); n],
            twist_dot: vec![Twist::zeros(); n],
            wrench: vec![Wrench::zeros(); n],
        }
    }
}
