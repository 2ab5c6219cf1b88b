//! The per-body buffers of the batch kernels for `L` lanes.

use super::lanes::Lanes;
use super::spatial::{Composite, Pose, M6, V6};

/// The buffers of the kernels for `L` lanes: inputs gathered by joint, and every per-body
/// quantity of the three algorithms.
#[derive(Clone, Debug)]
pub(super) struct Buffers<const L: usize> {
    pub(super) q: Vec<Lanes<L>>,
    pub(super) v: Vec<Lanes<L>>,
    /// `q̈` for RNEA, `τ` for ABA.
    pub(super) a: Vec<Lanes<L>>,
    /// The joints' `(sin, cos)` ([`sin_cos_all`](super::joint::sin_cos_all)).
    pub(super) sin_cos: Vec<(Lanes<L>, Lanes<L>)>,
    pub(super) pose_in_parent: Vec<Pose<L>>,
    pub(super) pose_in_world: Vec<Pose<L>>,
    pub(super) twist: Vec<V6<L>>,
    pub(super) accel: Vec<V6<L>>,
    /// RNEA's body wrenches, ABA's bias wrenches `pᴬ`.
    pub(super) wrench: Vec<V6<L>>,
    pub(super) screw: Vec<V6<L>>,
    pub(super) composite: Vec<Composite<L>>,
    pub(super) bias_acceleration: Vec<V6<L>>,
    pub(super) articulated_inertia: Vec<M6<L>>,
    pub(super) articulated_force: Vec<V6<L>>,
    pub(super) articulated_joint_force: Vec<Lanes<L>>,
    /// The accelerations `V̇a`, `V̇c` and wrenches `W_a`, `W_c` of the passes for the path
    /// coefficients `a` and `c` (those for `b` are `accel` and `wrench`).
    pub(super) accel_a: Vec<V6<L>>,
    pub(super) accel_c: Vec<V6<L>>,
    pub(super) wrench_a: Vec<V6<L>>,
    pub(super) wrench_c: Vec<V6<L>>,
    /// The result: `n` values, `n²` for the mass matrix, `3n` for the path coefficients.
    pub(super) out: Vec<Lanes<L>>,
}

impl<const L: usize> Buffers<L> {
    pub(super) fn new(n: usize) -> Self {
        Buffers {
            q: vec![Lanes::zero(); n],
            v: vec![Lanes::zero(); n],
            a: vec![Lanes::zero(); n],
            sin_cos: vec![(Lanes::zero(), Lanes::zero()); n],
            pose_in_parent: vec![Pose::default(); n],
            pose_in_world: vec![Pose::default(); n],
            twist: vec![[Lanes::zero(); 6]; n],
            accel: vec![[Lanes::zero(); 6]; n],
            wrench: vec![[Lanes::zero(); 6]; n],
            screw: vec![[Lanes::zero(); 6]; n],
            composite: vec![Composite::default(); n],
            bias_acceleration: vec![[Lanes::zero(); 6]; n],
            articulated_inertia: vec![[[Lanes::zero(); 6]; 6]; n],
            articulated_force: vec![[Lanes::zero(); 6]; n],
            articulated_joint_force: vec![Lanes::zero(); n],
            accel_a: vec![[Lanes::zero(); 6]; n],
            accel_c: vec![[Lanes::zero(); 6]; n],
            wrench_a: vec![[Lanes::zero(); 6]; n],
            wrench_c: vec![[Lanes::zero(); 6]; n],
            out: vec![Lanes::zero(); (n * n).max(3 * n)],
        }
    }
}
