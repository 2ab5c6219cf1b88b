//! Cartesian moves: a frame carried on a straight segment or a circular arc through a via point,
//! its orientation slerped, solved point by point by the inverse kinematics and timed by
//! [`time_optimal`] under the joint limits and a tool speed limit.

use super::spline::CubicSpline;
use super::time_optimal::{time_optimal, TimeOptimal, TimeOptimalOptions, TimingLimits};
use crate::error::{Error, Result};
use crate::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
use crate::kinematics::{forward_kinematics, frame_pose};
use crate::model::Model;
use crate::sim::Trajectory;
use crate::spatial::{exp_so3, log_so3, Se3};
use crate::workspace::Workspace;
use nalgebra::{Matrix3, Vector3};

/// The circle through three points: centre `c`, radius `r`, in-plane unit vectors `e1`
/// (towards the start) and `e2`, and the angle swept from the start to the end through the via.
#[derive(Clone, Debug, PartialEq)]
struct Arc {
    center: Vector3<f64>,
    radius: f64,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    sweep: f64,
}

/// The poses a Cartesian move passes through, as a function of the fraction `σ ∈ [0, 1]` of the
/// path: the origin on a straight segment or a circular arc at constant speed in `σ`, the
/// rotation by slerp `R(σ) = R_0 exp(σ log(R_0ᵀ R_1))`.
#[derive(Clone, Debug, PartialEq)]
pub struct CartesianPath {
    start: Se3,
    target: Se3,
    arc: Option<Arc>,
    /// `log(R_0ᵀ R_1)`: the rotation from start to target in the start frame.
    turn: Vector3<f64>,
}

impl CartesianPath {
    /// The straight segment from `start` to `target` (poses in the world frame).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use screwdyn::motion::CartesianPath;
    /// use screwdyn::spatial::Se3;
    /// let line = CartesianPath::linear(Se3::identity(), Se3::from_translation(Vector3::new(0.3, 0.4, 0.0)));
    /// assert!((line.length() - 0.5).abs() < 1e-15);
    /// assert!((line.pose_at(0.5).translation.y - 0.2).abs() < 1e-15);
    /// ```
    pub fn linear(start: Se3, target: Se3) -> CartesianPath {
        let turn = log_so3(&(start.rotation.transpose() * target.rotation));
        CartesianPath {
            start,
            target,
            arc: None,
            turn,
        }
    }

    /// The circular arc from `start` through the point `via` (world frame, m) to `target`.
    ///
    /// The centre of the circle through `p_0`, `p_v`, `p_1`, with `u = p_v − p_0`,
    /// `w = p_1 − p_0` and `n = u × w`, is `c = p_0 + (|u|² w − |w|² u) × n / (2 |n|²)`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the three points are (nearly) on one line, or
    /// [`Error::NonFinite`] for NaN in `via`.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use screwdyn::motion::CartesianPath;
    /// use screwdyn::spatial::Se3;
    /// // A half circle of radius 1 from (1, 0, 0) through (0, 1, 0) to (−1, 0, 0).
    /// let at = |x, y| Se3::from_translation(Vector3::new(x, y, 0.0));
    /// let arc = CartesianPath::circular(at(1.0, 0.0), Vector3::new(0.0, 1.0, 0.0), at(-1.0, 0.0)).unwrap();
    /// assert!((arc.length() - std::f64::consts::PI).abs() < 1e-12);
    /// assert!((arc.pose_at(0.5).translation - Vector3::new(0.0, 1.0, 0.0)).norm() < 1e-12);
    /// assert!(CartesianPath::circular(at(0.0, 0.0), Vector3::new(1.0, 0.0, 0.0), at(2.0, 0.0)).is_err());
    /// ```
    pub fn circular(start: Se3, via: Vector3<f64>, target: Se3) -> Result<CartesianPath> {
        if let Some(k) = via.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                what: "the via point".into(),
                index: k,
                value: via[k].to_string(),
            });
        }
        let p0 = start.translation;
        let u = via - p0;
        let w = target.translation - p0;
        let n = u.cross(&w);
        if n.norm() <= 1e-9 * u.norm() * w.norm() || n.norm() == 0.0 {
            return Err(Error::InvalidArgument(format!(
                "the circular move's start ({:.4}, {:.4}, {:.4}), via ({:.4}, {:.4}, {:.4}) and target ({:.4}, {:.4}, {:.4}) lie on one line (or coincide): they define no circle",
                p0.x, p0.y, p0.z, via.x, via.y, via.z, target.translation.x, target.translation.y, target.translation.z
            )));
        }
        // c = p0 + (|u|² w − |w|² u) × n / (2 |n|²)
        let center =
            p0 + (u.norm_squared() * w - w.norm_squared() * u).cross(&n) / (2.0 * n.norm_squared());
        let radius = (p0 - center).norm();
        let e1 = (p0 - center) / radius;
        let e2 = n.normalize().cross(&e1);
        // p0 → via → p1 runs counter-clockwise about n, so the sweep is the angle of p1 in (0, 2π).
        let d = target.translation - center;
        let mut sweep = d.dot(&e2).atan2(d.dot(&e1));
        if sweep <= 0.0 {
            sweep += 2.0 * std::f64::consts::PI;
        }
        let mut path = CartesianPath::linear(start, target);
        path.arc = Some(Arc {
            center,
            radius,
            e1,
            e2,
            sweep,
        });
        Ok(path)
    }

    /// The length (m) of the path of the frame's origin.
    pub fn length(&self) -> f64 {
        match &self.arc {
            Some(a) => a.radius * a.sweep,
            None => (self.target.translation - self.start.translation).norm(),
        }
    }

    /// The angle (rad) the frame turns through from start to target.
    pub fn angle(&self) -> f64 {
        self.turn.norm()
    }

    /// The pose at the fraction `sigma` of the path (clamped to `[0, 1]`), in the world frame:
    /// origin `p_0 + σ (p_1 − p_0)` on a segment, `c + r (cos(σφ) e_1 + sin(σφ) e_2)` on an arc
    /// sweeping `φ`; rotation `R_0 exp(σ log(R_0ᵀ R_1))`.
    pub fn pose_at(&self, sigma: f64) -> Se3 {
        let sigma = sigma.clamp(0.0, 1.0);
        let position = match &self.arc {
            Some(a) => {
                let phi = sigma * a.sweep;
                a.center + a.radius * (phi.cos() * a.e1 + phi.sin() * a.e2)
            }
            None => {
                self.start.translation + sigma * (self.target.translation - self.start.translation)
            }
        };
        let rotation: Matrix3<f64> = self.start.rotation * exp_so3(&(sigma * self.turn));
        Se3::new(rotation, position)
    }

    fn kind(&self) -> &'static str {
        if self.arc.is_some() {
            "circular"
        } else {
            "linear"
        }
    }
}

/// How a Cartesian move is sampled, solved and timed.
#[derive(Clone, Debug, PartialEq)]
pub struct CartesianOptions {
    /// The largest distance (m) the frame's origin moves between two IK points. Default `1e-3`.
    pub step_length: f64,
    /// The largest angle (rad) the frame turns between two IK points. Default `1e-2`.
    pub step_angle: f64,
    /// A joint moving more than this (rad or m) between two consecutive IK points is a
    /// singularity (or a change of branch) and stops the move. Default `0.1`.
    pub jump_threshold: f64,
    /// The tool speed limit `|ṗ| ≤ tool_speed` (m/s) on the frame's origin. Default `+∞`.
    pub tool_speed: f64,
    /// Options of the inverse kinematics (tolerances, budget).
    pub ik: IkOptions,
    /// Options of the timing.
    pub timing: TimeOptimalOptions,
}

impl Default for CartesianOptions {
    fn default() -> Self {
        CartesianOptions {
            step_length: 1e-3,
            step_angle: 1e-2,
            jump_threshold: 0.1,
            tool_speed: f64::INFINITY,
            ik: IkOptions::default(),
            timing: TimeOptimalOptions::default(),
        }
    }
}

/// A timed Cartesian move: the joint-space cubic spline through the IK points at `s = σ` (the
/// fraction of the path), timed by [`time_optimal`]. A [`Trajectory`].
#[derive(Clone, Debug)]
pub struct CartesianMove {
    path: CartesianPath,
    timed: TimeOptimal<CubicSpline>,
    points: usize,
}

impl CartesianMove {
    /// The Cartesian path followed.
    pub fn path(&self) -> &CartesianPath {
        &self.path
    }
    /// The time-optimal timing of the joint-space path (`s` is the fraction of the path).
    pub fn timing(&self) -> &TimeOptimal<CubicSpline> {
        &self.timed
    }
    /// The number of IK points (the spline's knots).
    pub fn points(&self) -> usize {
        self.points
    }
}

impl Trajectory for CartesianMove {
    fn nq(&self) -> usize {
        self.timed.nq()
    }
    fn duration(&self) -> f64 {
        self.timed.duration()
    }
    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        self.timed.eval(t, q, qd, qdd);
    }
}

/// Moves frame `frame` from its pose at `q0` along `path` (which must start there, see
/// [`cartesian_move`]) — the general form, for a path built by hand.
///
/// The path is cut into `N = max(⌈L / step_length⌉, ⌈θ / step_angle⌉, 1)` equal steps of `σ`
/// (`L` its length, `θ` its turn); the IK solves each point from the previous answer. The
/// joint points become a cubic spline in `s = σ`, timed by [`time_optimal`] under `limits`.
/// The origin moves at `|ṗ| = L ṡ` (constant speed in `σ` on a segment and on an arc), so the
/// tool speed limit is the path speed bound `ṡ ≤ v_tool / L`.
///
/// # Errors
/// [`Error::InvalidArgument`] for bad options, when the IK finds no pose at some point (out of
/// reach, or a joint limit in the way) or a joint jumps more than `jump_threshold` between two
/// points (a singularity), each naming the position on the path (fraction, metres, radians);
/// the errors of [`time_optimal`] (where `s` is the fraction of the path).
pub fn cartesian_move_along(
    model: &Model,
    frame: usize,
    q0: &[f64],
    path: CartesianPath,
    limits: &TimingLimits,
    options: &CartesianOptions,
) -> Result<CartesianMove> {
    for (what, x) in [
        ("step_length", options.step_length),
        ("step_angle", options.step_angle),
        ("jump_threshold", options.jump_threshold),
        ("tool_speed", options.tool_speed),
    ] {
        if x.is_nan() || x <= 0.0 {
            return Err(Error::InvalidArgument(format!(
                "the Cartesian move option {what} is {x}, it must be positive"
            )));
        }
    }
    let solver = IkSolver::new(model, &[IkTask::pose(frame)], options.ik.clone())?;
    let mut ws = IkWorkspace::new(&solver);
    let (length, angle) = (path.length(), path.angle());
    let steps = ((length / options.step_length).ceil())
        .max((angle / options.step_angle).ceil())
        .max(1.0);
    if steps > 1e7 {
        return Err(Error::InvalidArgument(format!(
            "the {} move would need {steps} IK points (length {length:.4} m, turn {angle:.4} rad): make the steps larger",
            path.kind()
        )));
    }
    let steps = steps as usize;
    let n = model.nq();
    let mut qs: Vec<Vec<f64>> = vec![q0.to_vec()];
    let mut q = vec![0.0; n];
    let names = model.joint_names();
    // "43.0 % of the path (0.2150 m of 0.5000 m, 0.1200 rad of 0.3000 rad)", each part only
    // when the path moves that way.
    let where_ = |sigma: f64| {
        let mut parts = Vec::new();
        if length > 0.0 {
            parts.push(format!("{:.4} m of {length:.4} m", sigma * length));
        }
        if angle > 0.0 {
            parts.push(format!("{:.4} rad of {angle:.4} rad", sigma * angle));
        }
        format!("{:.1} % of the path ({})", 100.0 * sigma, parts.join(", "))
    };
    for i in 1..=steps {
        let sigma = i as f64 / steps as f64;
        let previous = &qs[i - 1];
        let result = solver.solve(&mut ws, &[path.pose_at(sigma)], previous, &mut q)?;
        if !result.success {
            let why = match result.failure {
                Some(crate::kinematics::ik::IkFailure::Limits) => "a joint limit is in the way",
                _ => "the pose is out of reach",
            };
            return Err(Error::InvalidArgument(format!(
                "the {} move of frame {} stops at {}: the inverse kinematics finds no pose there ({why})",
                path.kind(),
                model.frames()[frame].name,
                where_(sigma)
            )));
        }
        if let Some(j) = (0..n).find(|&j| (q[j] - previous[j]).abs() > options.jump_threshold) {
            return Err(Error::InvalidArgument(format!(
                "the {} move of frame {} meets a singularity at {}: joint {} jumps by {:.3} between two points {:.4} m apart (more than the threshold {})",
                path.kind(),
                model.frames()[frame].name,
                where_(sigma),
                names[j],
                q[j] - previous[j],
                length / steps as f64,
                options.jump_threshold
            )));
        }
        qs.push(q.clone());
    }
    let s: Vec<f64> = (0..=steps).map(|i| i as f64 / steps as f64).collect();
    let spline = CubicSpline::new(&s, &qs)?;
    let mut timing = options.timing.clone();
    // |ṗ| = |dp/dσ| ṡ = L ṡ ≤ v_tool
    if length > 0.0 {
        timing.max_path_speed = timing.max_path_speed.min(options.tool_speed / length);
    }
    let timed = time_optimal(model, spline, limits, &timing).map_err(|e| match e {
        Error::InvalidArgument(m) => Error::InvalidArgument(format!(
            "{m} (s is the fraction of the {} move, {length:.4} m long)",
            path.kind()
        )),
        other => other,
    })?;
    Ok(CartesianMove {
        path,
        timed,
        points: steps + 1,
    })
}

/// Moves frame `frame` in a straight line (`via: None`) or on the circular arc through `via`
/// from its pose at `q0` to `target` (world frame), orientation by slerp, as fast as `limits`
/// and `options.tool_speed` allow; see [`cartesian_move_along`].
///
/// # Errors
/// As [`cartesian_move_along`] and [`CartesianPath::circular`]; [`Error::InvalidArgument`] for a
/// frame the model does not have or a `q0` of the wrong length or outside the joint limits.
///
/// ```
/// use nalgebra::Vector3;
/// use screwdyn::kinematics::{forward_kinematics, frame_pose};
/// use screwdyn::motion::{cartesian_move, CartesianOptions, TimingLimits};
/// use screwdyn::sim::Trajectory;
/// use screwdyn::spatial::Se3;
/// use screwdyn::Workspace;
/// let ur5 = screwdyn::builtin::load("ur5").unwrap();
/// let tool = ur5.frame_id("tool0").unwrap();
/// let q0 = [0.0, -1.2, 1.5, -1.9, -1.57, 0.0];
/// let mut ws = Workspace::new(&ur5);
/// forward_kinematics(&ur5, &mut ws, &q0).unwrap();
/// let start = frame_pose(&ur5, &ws, tool).unwrap();
/// // 10 cm along y at no more than 0.25 m/s.
/// let target = Se3::new(start.rotation, start.translation + Vector3::new(0.0, 0.1, 0.0));
/// let options = CartesianOptions { tool_speed: 0.25, ..Default::default() };
/// let motion = cartesian_move(&ur5, tool, &q0, &target, None, &TimingLimits::from_model(&ur5), &options).unwrap();
/// assert!(motion.duration() > 0.1 / 0.25);
/// ```
pub fn cartesian_move(
    model: &Model,
    frame: usize,
    q0: &[f64],
    target: &Se3,
    via: Option<Vector3<f64>>,
    limits: &TimingLimits,
    options: &CartesianOptions,
) -> Result<CartesianMove> {
    model.check_vector(q0, "q0")?;
    let mut ws = Workspace::new(model);
    forward_kinematics(model, &mut ws, q0)?;
    let start = frame_pose(model, &ws, frame)?;
    let path = match via {
        Some(v) => CartesianPath::circular(start, v, *target)?,
        None => CartesianPath::linear(start, *target),
    };
    cartesian_move_along(model, frame, q0, path, limits, options)
}
