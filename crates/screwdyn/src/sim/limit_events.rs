//! What a simulation reports about the joints' position limits: a start outside them, and each
//! contact with a limit stop (the spring–damper of [`JointEffects`](super::JointEffects)).

use crate::error::Result;
use crate::model::{JointKind, Model};

/// Which of a joint's two position limits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitSide {
    /// The lower limit: the joint went below it.
    Lower,
    /// The upper limit: the joint went above it.
    Upper,
}

impl LimitSide {
    /// `"lower"` or `"upper"`.
    pub fn name(self) -> &'static str {
        match self {
            LimitSide::Lower => "lower",
            LimitSide::Upper => "upper",
        }
    }
}

/// What happened at a position limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitEventKind {
    /// The run starts with the joint beyond the limit: the stop pushes it back from the first
    /// step (nothing moves it inside before the run).
    StartOutside,
    /// The joint crossed the limit into its stop during the run.
    Contact,
}

impl LimitEventKind {
    /// `"start_outside"` or `"contact"`.
    pub fn name(self) -> &'static str {
        match self {
            LimitEventKind::StartOutside => "start_outside",
            LimitEventKind::Contact => "contact",
        }
    }
}

/// One event at a joint's position limit. A contact is reported once, when the joint crosses
/// into its stop; the next contact of the same joint needs it to come back inside its limits
/// first (by more than [`LimitWatch::HYSTERESIS`]).
///
/// ```
/// use nalgebra::{Vector3, Vector6};
/// use screwdyn::model::JointSpec;
/// use screwdyn::sim::{simulate, LimitEventKind, LimitSide, SimOptions, ZeroTorque};
/// use screwdyn::spatial::{Se3, SpatialInertia};
/// // A 1 m, 1 kg pendulum with limits −0.2 … 0.3 rad, released at rest from 0.25 rad: it
/// // swings as θ = 0.25 cos(√(g/l) t) (small angles) and hits −0.2 rad when the cosine is −0.8.
/// let mut b = screwdyn::ModelBuilder::new("pendulum");
/// b.gravity(Vector3::new(0.0, -9.81, 0.0)).link(
///     "bob", "base",
///     JointSpec::revolute("pivot").limits(-0.2, 0.3)
///         .screw_in_parent(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0)),
///     Se3::from_translation(Vector3::new(0.0, -1.0, 0.0)),
///     SpatialInertia::point_mass(1.0, Vector3::zeros()),
/// );
/// let m = b.build().unwrap();
/// let opts = SimOptions { duration: 1.0, ..Default::default() };
/// let run = simulate(&m, &[0.25], &[0.0], &mut ZeroTorque, &[], &opts, &mut |_| {}).unwrap();
/// assert_eq!(run.events.len(), 1);
/// let hit = &run.events[0];
/// assert_eq!((hit.kind, hit.side, hit.joint), (LimitEventKind::Contact, LimitSide::Lower, 0));
/// let expected = (-0.8_f64).acos() / 9.81_f64.sqrt();
/// assert!((hit.t - expected).abs() < 0.01 && hit.velocity < 0.0, "{hit:?}");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct LimitEvent {
    /// A start outside the limits or a contact.
    pub kind: LimitEventKind,
    /// Time (s): 0 for a start outside; for a contact, the crossing time interpolated linearly
    /// within the step that crossed.
    pub t: f64,
    /// The joint's index.
    pub joint: usize,
    /// The joint's name.
    pub joint_name: String,
    /// Which limit.
    pub side: LimitSide,
    /// The limit's value (rad or m).
    pub bound: f64,
    /// The joint's position: at the start for a start outside, the bound for a contact.
    pub position: f64,
    /// The joint's velocity (rad/s or m/s): at the start for a start outside; for a contact,
    /// at the start of the step that crossed (before the stop acts on it).
    pub velocity: f64,
}

impl LimitEvent {
    /// One sentence saying what happened (and, for a start outside, what the simulator does
    /// about it).
    ///
    /// ```
    /// use screwdyn::sim::{LimitEvent, LimitEventKind, LimitSide};
    /// let e = LimitEvent { kind: LimitEventKind::Contact, t: 0.51, joint: 2,
    ///     joint_name: "elbow_joint".into(), side: LimitSide::Upper, bound: 3.14,
    ///     position: 3.14, velocity: 2.5 };
    /// assert_eq!(e.message("rad"), "joint 'elbow_joint' hit its upper limit stop (3.14 rad) at t = 0.51 s, moving at 2.5 rad/s");
    /// ```
    pub fn message(&self, unit: &str) -> String {
        let (name, side, bound) = (&self.joint_name, self.side.name(), self.bound);
        match self.kind {
            LimitEventKind::Contact => format!(
                "joint '{name}' hit its {side} limit stop ({} {unit}) at t = {} s, moving at {} {unit}/s",
                round(bound),
                round(self.t),
                round(self.velocity)
            ),
            LimitEventKind::StartOutside => format!(
                "joint '{name}' starts at {} {unit}, {} its {side} limit {} {unit}: it is not \
                 moved inside before the run, the limit stop pushes it back from the first step",
                round(self.position),
                if self.side == LimitSide::Upper { "above" } else { "below" },
                round(bound),
            ),
        }
    }

    /// The unit of the joint's position, `"rad"` or `"m"`.
    pub fn unit(&self, model: &Model) -> &'static str {
        match model.joints().get(self.joint).map(|j| &j.kind) {
            Some(JointKind::Prismatic) => "m",
            _ => "rad",
        }
    }

    /// The event as a JSON object: `kind`, `t`, `joint`, `side`, `bound`, `position`,
    /// `velocity`.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "kind": self.kind.name(),
            "t": self.t,
            "joint": self.joint_name,
            "side": self.side.name(),
            "bound": self.bound,
            "position": self.position,
            "velocity": self.velocity,
        })
    }
}

/// Six significant digits, enough for a message.
fn round(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(5 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// Watches the joints against their limits step by step and reports each contact once.
#[derive(Clone, Debug)]
pub struct LimitWatch {
    /// The stop each joint is in (`None` when inside its limits).
    in_stop: Vec<Option<LimitSide>>,
    /// Whether the stops act (the position-limit effect is on).
    enabled: bool,
}

impl LimitWatch {
    /// How far back inside its limits (rad or m) a joint must come before its next crossing
    /// counts as a new contact: a joint resting on its stop, where round-off moves it back and
    /// forth across the bound, makes one contact, not one a step.
    pub const HYSTERESIS: f64 = 1e-9;

    /// A watch over `model`'s joints; `enabled` is false when the stops do not act (then
    /// nothing is reported).
    pub fn new(model: &Model, enabled: bool) -> Self {
        LimitWatch {
            in_stop: vec![None; model.nq()],
            enabled,
        }
    }

    /// Reports each joint that starts beyond a limit (as [`LimitEventKind::StartOutside`]
    /// at `t = 0`) to `emit`, and counts it as in its stop.
    ///
    /// # Errors
    /// Whatever `emit` returns.
    pub fn start(
        &mut self,
        model: &Model,
        q0: &[f64],
        v0: &[f64],
        emit: &mut dyn FnMut(&LimitEvent) -> Result<()>,
    ) -> Result<usize> {
        let mut count = 0;
        if !self.enabled {
            return Ok(0);
        }
        for (i, j) in model.joints().iter().enumerate() {
            let (side, bound) = match beyond(q0[i], j.limits.lower, j.limits.upper) {
                Some(s) => s,
                None => continue,
            };
            self.in_stop[i] = Some(side);
            count += 1;
            emit(&LimitEvent {
                kind: LimitEventKind::StartOutside,
                t: 0.0,
                joint: i,
                joint_name: j.name.clone(),
                side,
                bound,
                position: q0[i],
                velocity: v0[i],
            })?;
        }
        Ok(count)
    }

    /// Checks the step from `(t0, q0, v0)` to `(t0 + h, q1)`: each joint that crossed into a
    /// stop it was not in is reported to `emit`, at the crossing time
    /// `t0 + h (bound − q0) / (q1 − q0)`, with the velocity `v0` the joint had before the
    /// stop acted. Returns the number of contacts reported. Allocates only for an event.
    ///
    /// # Errors
    /// Whatever `emit` returns.
    pub fn step(
        &mut self,
        model: &Model,
        t0: f64,
        h: f64,
        (q0, v0): (&[f64], &[f64]),
        q1: &[f64],
        emit: &mut dyn FnMut(&LimitEvent) -> Result<()>,
    ) -> Result<usize> {
        let mut count = 0;
        if !self.enabled {
            return Ok(0);
        }
        for (i, j) in model.joints().iter().enumerate() {
            let (lower, upper) = (j.limits.lower, j.limits.upper);
            match (beyond(q1[i], lower, upper), self.in_stop[i]) {
                (Some((side, _)), Some(now)) if side == now => {}
                (Some((side, bound)), _) => {
                    self.in_stop[i] = Some(side);
                    let dq = q1[i] - q0[i];
                    let s = if dq != 0.0 {
                        ((bound - q0[i]) / dq).clamp(0.0, 1.0)
                    } else {
                        1.0
                    };
                    count += 1;
                    emit(&LimitEvent {
                        kind: LimitEventKind::Contact,
                        t: t0 + s * h,
                        joint: i,
                        joint_name: j.name.clone(),
                        side,
                        bound,
                        position: bound,
                        velocity: v0[i],
                    })?;
                }
                (None, Some(_)) => {
                    let inside =
                        q1[i] - lower > Self::HYSTERESIS && upper - q1[i] > Self::HYSTERESIS;
                    if inside {
                        self.in_stop[i] = None;
                    }
                }
                (None, None) => {}
            }
        }
        Ok(count)
    }
}

/// The limit `x` is beyond, and its value.
fn beyond(x: f64, lower: f64, upper: f64) -> Option<(LimitSide, f64)> {
    if x > upper {
        Some((LimitSide::Upper, upper))
    } else if x < lower {
        Some((LimitSide::Lower, lower))
    } else {
        None
    }
}
