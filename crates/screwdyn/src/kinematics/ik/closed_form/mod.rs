//! Every inverse-kinematics solution of the 6R arms that have a closed form, from the
//! Paden–Kahan subproblems.
//!
//! The frame's pose is the product of exponentials (*Modern Robotics* §4.1)
//! `T(θ) = e^{[S₁]θ₁} ⋯ e^{[S₆]θ₆} M`, with `S_i` the joints' unit screw axes in the world frame
//! at `q = 0` and `M` the frame's pose there. The target `T_d` is folded into
//! `G = T_d M⁻¹ = e^{[S₁]θ₁} ⋯ e^{[S₆]θ₆}`, and the families split `G` into subproblems:
//! [`ClosedFormFamily::SphericalWrist`] (`spherical_wrist.rs`) and
//! [`ClosedFormFamily::ThreeParallel`] (`three_parallel.rs`). An arm whose geometry reads the
//! same from the tip (the first three axes meet, or axes 3 ∥ 4 ∥ 5 with axes 1 and 2 meeting)
//! is solved through `G⁻¹ = e^{[−S₆]θ₆} ⋯ e^{[−S₁]θ₁}`, the chain reversed.

mod geometry;
mod spherical_wrist;
mod three_parallel;

use super::subproblems::{wrap, Axis};
use crate::error::Result;
use crate::model::{JointKind, Model};
use crate::spatial::Se3;
use nalgebra::Vector3;
use spherical_wrist::SphericalWrist;
use three_parallel::ThreeParallel;

/// Solutions whose angles all agree within this (rad, modulo 2π) are one solution: they only
/// arise as the two halves of a branch that meet at a singularity.
const SAME_SOLUTION: f64 = 1e-6;

/// A branch is kept when each of its subproblems is exact within `1e-9` (m per metre of the
/// arm's size for points, rad for directions).
const ACCURACY: f64 = 1e-9;

/// How far a subproblem may miss for its branch to count as exact.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Tolerance {
    /// For points (m).
    position: f64,
    /// For directions (rad).
    orientation: f64,
}

/// The kinematic families with a closed-form inverse.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ClosedFormFamily {
    /// The last three axes meet in one point (the wrist centre), and the first three place it
    /// by subproblems: axes 2 ∥ 3 with axis 1 not parallel to them, or axes 1 and 2 meeting
    /// (Puma 560, ABB IRB, KUKA KR, Stäubli, Fanuc). Also the same geometry read from the tip.
    SphericalWrist,
    /// Axes 2 ∥ 3 ∥ 4, and axes 5 and 6 meet (Universal Robots UR3/5/10/16 and e-series).
    /// Also the same geometry read from the tip.
    ThreeParallel,
}

impl ClosedFormFamily {
    /// A short lowercase name: `spherical wrist` or `three parallel axes`.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::ClosedFormFamily;
    /// assert_eq!(ClosedFormFamily::ThreeParallel.name(), "three parallel axes");
    /// ```
    pub fn name(&self) -> &'static str {
        match self {
            ClosedFormFamily::SphericalWrist => "spherical wrist",
            ClosedFormFamily::ThreeParallel => "three parallel axes",
        }
    }
}

/// The subproblem sequence of a family.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Plan {
    Wrist(SphericalWrist),
    Parallel(ThreeParallel),
}

impl Plan {
    fn detect(axes: &[Axis; 6]) -> Option<Plan> {
        SphericalWrist::detect(axes)
            .map(Plan::Wrist)
            .or_else(|| ThreeParallel::detect(axes).map(Plan::Parallel))
    }
}

/// The closed-form inverse kinematics of one frame of a 6R arm: detected once from the screw
/// axes, then [`solve`](ClosedForm::solve) returns every solution for a target pose.
///
/// ```
/// use screwdyn::kinematics::{forward_kinematics, frame_pose};
/// use screwdyn::kinematics::ik::{ClosedForm, ClosedFormFamily};
/// use screwdyn::{builtin, Workspace};
/// let ur5 = builtin::load("ur5").unwrap();
/// let tool = ur5.frame_id("tool0").unwrap();
/// let ik = ClosedForm::detect(&ur5, tool).unwrap().unwrap();
/// assert_eq!(ik.family(), ClosedFormFamily::ThreeParallel);
/// // A target made by forward kinematics.
/// let mut ws = Workspace::new(&ur5);
/// forward_kinematics(&ur5, &mut ws, &[0.3, -1.2, 1.5, -0.4, 1.1, 0.7]).unwrap();
/// let target = frame_pose(&ur5, &ws, tool).unwrap();
/// let mut solutions = [[0.0; 6]; 8];
/// let count = ik.solve(&target, &mut solutions);
/// assert_eq!(count, 8);
/// for theta in &solutions[..count] {
///     let mut q = [0.0; 6];
///     for (k, &j) in ik.joints().iter().enumerate() {
///         q[j] = theta[k];
///     }
///     forward_kinematics(&ur5, &mut ws, &q).unwrap();
///     let pose = frame_pose(&ur5, &ws, tool).unwrap();
///     assert!((pose.to_matrix() - target.to_matrix()).amax() < 1e-10);
/// }
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedForm {
    family: ClosedFormFamily,
    joints: [usize; 6],
    plan: Plan,
    /// Whether the plan reads the chain from the tip (`G⁻¹`, axes `−S₆ … −S₁`).
    reversed: bool,
    /// `M`, the frame's pose at `q = 0`.
    home: Se3,
    /// `M⁻¹`.
    home_inverse: Se3,
    tolerance: Tolerance,
}

impl ClosedForm {
    /// The closed form of `frame`'s inverse kinematics, or `None` when the frame's chain is not
    /// a 6R arm with a spherical wrist or three consecutive parallel axes.
    ///
    /// The frame must be moved by exactly six joints, all revolute or continuous (joints on
    /// other branches are ignored; a prismatic or helical one gives `None`). Their screw axes in
    /// the world frame at `q = 0` decide the family, within tolerances: axes count as parallel
    /// when the angle between them is below `1e-6` rad, lines as meeting when they pass within
    /// `1e-6` m of one point, and axes that must cross or lines that must be distinct differ by
    /// more. The subproblems solve the ideal geometry (the parallel axes made exactly parallel,
    /// the meeting ones made to meet); a model within the tolerances but not exactly ideal (a
    /// URDF's `π/2` rounded to ten digits) gets solutions that miss the target by about that
    /// deviation times the arm's size, for a numerical solver to polish.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no frame
    /// `frame`.
    ///
    /// ```
    /// use screwdyn::builtin;
    /// use screwdyn::kinematics::ik::ClosedForm;
    /// let panda = builtin::load("panda").unwrap(); // seven joints
    /// assert!(ClosedForm::detect(&panda, panda.body_frame(6).unwrap()).unwrap().is_none());
    /// assert!(ClosedForm::detect(&panda, 999).is_err());
    /// ```
    pub fn detect(model: &Model, frame: usize) -> Result<Option<ClosedForm>> {
        let f = model.frame(frame)?;
        let Some(body) = f.body else {
            return Ok(None);
        };
        let support = model.support(body)?;
        if support.len() != 6 {
            return Ok(None);
        }
        // Home poses H_i^0(0) down the chain and the world axes S_i^0 = Ad_{H_i^0(0)} S_i.
        let mut pose = Se3::identity();
        let mut axes = [Axis::through(Vector3::zeros(), Vector3::z()); 6];
        let mut joints = [0; 6];
        let mut origins = [Vector3::zeros(); 6];
        for (k, &j) in support.iter().enumerate() {
            let joint = &model.joints()[j];
            if !matches!(joint.kind, JointKind::Revolute | JointKind::Continuous) {
                return Ok(None);
            }
            pose = pose.compose(&joint.home);
            let screw = pose.act_twist(&joint.screw);
            axes[k] = Axis::from_screw(&screw).anchored_near(&pose.translation);
            joints[k] = j;
            origins[k] = pose.translation;
        }
        let home = pose.compose(&f.placement);
        // The family, read from the base or else from the tip.
        let reversed_axes = [5, 4, 3, 2, 1, 0].map(|k| axes[k].reversed());
        let (plan, reversed) = match Plan::detect(&axes) {
            Some(plan) => (plan, false),
            None => match Plan::detect(&reversed_axes) {
                Some(plan) => (plan, true),
                None => return Ok(None),
            },
        };
        let family = match plan {
            Plan::Wrist(_) => ClosedFormFamily::SphericalWrist,
            Plan::Parallel(_) => ClosedFormFamily::ThreeParallel,
        };
        // The arm's size: the farthest joint origin from the frame or from the first joint.
        let size = origins
            .iter()
            .map(|o| (o - home.translation).norm().max((o - origins[0]).norm()))
            .fold(1.0, f64::max);
        Ok(Some(ClosedForm {
            family,
            joints,
            plan,
            reversed,
            home,
            home_inverse: home.inverse(),
            tolerance: Tolerance {
                position: ACCURACY * size,
                orientation: ACCURACY,
            },
        }))
    }

    /// The family the arm was recognised as.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::{ClosedForm, ClosedFormFamily};
    /// let ur5 = screwdyn::builtin::load("ur5").unwrap();
    /// let ik = ClosedForm::detect(&ur5, ur5.frame_id("tool0").unwrap()).unwrap().unwrap();
    /// assert_eq!(ik.family(), ClosedFormFamily::ThreeParallel);
    /// ```
    pub fn family(&self) -> ClosedFormFamily {
        self.family
    }

    /// The six joints moving the frame, base to tip, as indices into `q`: solution `θ` of
    /// [`solve`](ClosedForm::solve) sets `q[joints()[k]] = θ[k]`.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::ClosedForm;
    /// let ur5 = screwdyn::builtin::load("ur5").unwrap();
    /// let ik = ClosedForm::detect(&ur5, ur5.frame_id("tool0").unwrap()).unwrap().unwrap();
    /// assert_eq!(ik.joints(), [0, 1, 2, 3, 4, 5]);
    /// ```
    pub fn joints(&self) -> [usize; 6] {
        self.joints
    }

    /// Every joint-angle solution `θ` (in the order of [`joints`](ClosedForm::joints)) that puts
    /// the frame at `target_in_world`: up to 8, written to the first entries of `out`; returns
    /// how many. Allocates nothing.
    ///
    /// Each of the up to 2 × 2 × 2 branches is kept only when every subproblem on it is exact
    /// (misses by less than `1e-9` m per metre of the arm's size for points, `1e-9` rad for
    /// directions), that is when `e^{[S₁]θ₁} ⋯ e^{[S₆]θ₆} M` of the ideal geometry (see
    /// [`detect`](ClosedForm::detect)) is the target. So an unreachable target, or one with
    /// NaN, gives 0 solutions, and a target reached by fewer branches (at a stretched elbow, or
    /// out of reach of one shoulder side) gives fewer. Angles are in `(−π, π]`, not wrapped
    /// into the joint limits. At a singularity where a continuum of solutions exists, one
    /// member is returned: with two wrist axes aligned, one of the aligned joints is set to 0
    /// (`θ₄` of a spherical wrist, `θ₆` of a three-parallel arm) and the others take the whole
    /// turn; with the wrist centre on axis 1 (a spherical wrist's shoulder singularity),
    /// `θ₁ = 0`.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use screwdyn::kinematics::ik::ClosedForm;
    /// use screwdyn::spatial::Se3;
    /// let ur5 = screwdyn::builtin::load("ur5").unwrap();
    /// let ik = ClosedForm::detect(&ur5, ur5.frame_id("tool0").unwrap()).unwrap().unwrap();
    /// let mut out = [[0.0; 6]; 8];
    /// // 3 m away: out of reach.
    /// assert_eq!(ik.solve(&Se3::from_translation(Vector3::new(3.0, 0.0, 0.0)), &mut out), 0);
    /// // In front of the base, the tool pointing down: reachable.
    /// let up = Se3::from_rpy(std::f64::consts::PI, 0.0, 0.0).with_translation(Vector3::new(0.3, 0.2, 0.5));
    /// assert!(ik.solve(&up, &mut out) > 0);
    /// ```
    pub fn solve(&self, target_in_world: &Se3, out: &mut [[f64; 6]; 8]) -> usize {
        // G = T_d M⁻¹ = e^{[S₁]θ₁} ⋯ e^{[S₆]θ₆}; read from the tip, G⁻¹.
        let mut g = target_in_world.compose(&self.home_inverse);
        if self.reversed {
            g = g.inverse();
        }
        let mut count = 0;
        let mut keep = |theta: [f64; 6]| {
            let theta = if self.reversed {
                [5, 4, 3, 2, 1, 0].map(|k| theta[k])
            } else {
                theta
            };
            let known = out[..count]
                .iter()
                .any(|other| (0..6).all(|k| wrap(other[k] - theta[k]).abs() < SAME_SOLUTION));
            if count < out.len() && !known {
                out[count] = theta;
                count += 1;
            }
        };
        match &self.plan {
            Plan::Wrist(wrist) => wrist.solve(&g, &self.tolerance, &mut keep),
            Plan::Parallel(parallel) => parallel.solve(&g, &self.tolerance, &mut keep),
        }
        count
    }
}
