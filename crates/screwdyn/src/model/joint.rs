//! Joints: kind, screw axis `S_i^{i,λ(i)}`, home pose `H_i^{λ(i)}(0)`, limits, damping, friction.

use crate::scalar::Real;
use crate::spatial::{Se3, Twist};

/// The kind of a moving joint. Every joint moves by its screw axis (Lynch & Park, *Modern Robotics*, "Modeling Ideal
/// Joints"); the kind says how to read it and which limits apply.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind<T: Real = f64> {
    /// Rotation about a line: `S = (n̂, −n̂ × r)`, with position limits.
    Revolute,
    /// A revolute joint without position limits.
    Continuous,
    /// Translation along `n̂`: `S = (0, n̂)`.
    Prismatic,
    /// A screw motion with `pitch` metres of travel per radian: `S = (n̂, −n̂ × r + h n̂)`.
    Helical {
        /// Translation per radian of rotation (m/rad).
        pitch: T,
    },
}

impl<T: Real> JointKind<T> {
    /// A short lowercase name: `revolute`, `continuous`, `prismatic` or `helical`.
    pub fn name(&self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
            JointKind::Helical { .. } => "helical",
        }
    }
}

/// Position, velocity and effort limits of a joint; `±∞` where there is none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits<T: Real = f64> {
    /// Lowest position (rad or m).
    pub lower: T,
    /// Highest position (rad or m).
    pub upper: T,
    /// Largest speed magnitude (rad/s or m/s).
    pub velocity: T,
    /// Largest torque or force magnitude (N·m or N).
    pub effort: T,
}

impl<T: Real> Default for JointLimits<T> {
    fn default() -> Self {
        let inf: T = crate::scalar::real(f64::INFINITY);
        JointLimits {
            lower: -inf,
            upper: inf,
            velocity: inf,
            effort: inf,
        }
    }
}

/// A URDF `<mimic>` tag, kept for information: screwdyn loads mimic joints as independent
/// coordinates, as Pinocchio does.
#[derive(Clone, Debug, PartialEq)]
pub struct Mimic {
    /// The joint this one copies.
    pub joint: String,
    /// `q = multiplier · q_joint + offset`.
    pub multiplier: f64,
    /// See `multiplier`.
    pub offset: f64,
}

/// A moving joint of a [`Model`](super::Model). Joint `i` connects body `λ(i)` to body `i`.
///
/// ```
/// let m = screwdyn::builtin::planar2();
/// let j = &m.joints()[1];
/// assert_eq!(j.name, "joint2");
/// // S_2^{2,1}: rotation about z through the joint, one link length behind frame 2.
/// assert_eq!(j.screw, nalgebra::Vector6::new(0.0, 0.0, 1.0, 0.0, 1.0, 0.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Joint<T: Real = f64> {
    /// Joint name (unique in the model).
    pub name: String,
    /// Revolute, continuous, prismatic or helical.
    pub kind: JointKind<T>,
    /// `S_i^{i,λ(i)}`: the unit screw axis in the child (body `i`) frame.
    pub screw: Twist<T>,
    /// `H_i^{λ(i)}(0)`: pose of body `i` in its parent at `q_i = 0`.
    pub home: Se3<T>,
    /// Position, velocity and effort limits.
    pub limits: JointLimits<T>,
    /// Viscous damping coefficient (N·m·s/rad or N·s/m).
    pub damping: T,
    /// Coulomb friction magnitude (N·m or N).
    pub friction: T,
    /// Armature: the rotor inertia reflected to the joint (kg·m² or kg), added to `M(q)`'s
    /// diagonal entry of this joint (MuJoCo's `armature`). Zero unless the model gives one.
    pub armature: T,
    /// Joint spring stiffness `k` (N·m/rad or N/m, MuJoCo's `stiffness`): a passive torque
    /// `τ = −k (q − q_spring)` acts in simulation, beside the damping. Zero unless given.
    pub stiffness: T,
    /// The spring's rest position `q_spring` (rad or m, MuJoCo's `springref`).
    pub springref: T,
    /// The URDF mimic tag, if any (information only).
    pub mimic: Option<Mimic>,
}

impl<T: Real> Joint<T> {
    /// `H_i^{λ(i)}(q) = H_i^{λ(i)}(0) e^{[S_i^{i,λ(i)}] q}` (Lynch & Park, *Modern Robotics*, forward iterations).
    #[inline]
    pub fn pose_in_parent(&self, q: T) -> Se3<T> {
        self.home.compose(&Se3::exp_screw(&self.screw, q))
    }
}

impl Joint<f64> {
    /// The torque the joint's spring and Coulomb friction take from its motor at position `q`
    /// moving with speed `qd`: `k (q − q_spring) + f sign(q̇)`, with `sign(0) = 0` (no friction
    /// at rest). Torque profiles, the time-optimal timing and its check add it to inverse
    /// dynamics; viscous damping `d q̇` is left to simulation (it is linear in the path speed
    /// `ṡ`, the timing's constraints are linear in `ṡ²`).
    ///
    /// ```
    /// let m = screwdyn::builtin::pendulum().with_joint_friction(&[0.0], &[0.5]).unwrap();
    /// let m = m.with_springs(&[2.0], &[0.1]).unwrap();
    /// let j = &m.joints()[0];
    /// assert_eq!(j.spring_and_friction_torque(0.6, -3.0), 2.0 * 0.5 - 0.5);
    /// assert_eq!(j.spring_and_friction_torque(0.1, 0.0), 0.0);
    /// ```
    pub fn spring_and_friction_torque(&self, q: f64, qd: f64) -> f64 {
        let sign = if qd == 0.0 { 0.0 } else { qd.signum() };
        self.stiffness * (q - self.springref) + self.friction * sign
    }
}
