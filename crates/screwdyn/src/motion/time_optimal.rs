//! The fastest timing `s(t)` of a path from rest to rest within joint velocity, acceleration
//! and torque limits: TOPP-RA (reachability analysis, Pham & Pham 2018) on a grid refined until
//! the duration converges, checked afterwards by inverse dynamics along the result.

use super::check::{check_limits, CheckWorkspace};
use super::grid_coefficients::{GridCoefficients, PointView, POINTS_PER_CALL};
use super::reachability::{interval_times, parameterize, Constraints, LimitKind, Parameterization};
use super::spline::Path;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::sim::{ProfileSummary, Trajectory};

/// Per-joint limits of a timing; `f64::INFINITY` where a joint has none.
#[derive(Clone, Debug, PartialEq)]
pub struct TimingLimits {
    /// `|q̇_j| ≤ velocity_j` (rad/s or m/s).
    pub velocity: Vec<f64>,
    /// `|q̈_j| ≤ acceleration_j` (rad/s² or m/s²).
    pub acceleration: Vec<f64>,
    /// `|τ_j| ≤ effort_j` (N·m or N).
    pub effort: Vec<f64>,
}

impl TimingLimits {
    /// The model's velocity and effort limits, no acceleration limit.
    ///
    /// ```
    /// let m = screwdyn::builtin::load("ur5").unwrap();
    /// let l = screwdyn::motion::TimingLimits::from_model(&m);
    /// assert_eq!((l.effort[0], l.effort[5], l.velocity[0]), (150.0, 28.0, 3.15));
    /// assert!(l.acceleration[0].is_infinite());
    /// ```
    pub fn from_model(model: &Model) -> Self {
        let j = model.joints();
        TimingLimits {
            velocity: j.iter().map(|j| j.limits.velocity).collect(),
            acceleration: vec![f64::INFINITY; j.len()],
            effort: j.iter().map(|j| j.limits.effort).collect(),
        }
    }

    /// Checks lengths and values: every limit positive (`+∞` allowed), none NaN.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] for a vector of the wrong length; [`Error::InvalidArgument`]
    /// for a zero, negative or NaN limit, naming the joint.
    pub fn check(&self, model: &Model) -> Result<()> {
        let names = model.joint_names();
        for (what, v) in [
            ("the velocity limits", &self.velocity),
            ("the acceleration limits", &self.acceleration),
            ("the effort limits", &self.effort),
        ] {
            if v.len() != model.nq() {
                return Err(Error::DimensionMismatch {
                    what: what.into(),
                    got: v.len(),
                    expected: model.nq(),
                    names: names.join(", "),
                });
            }
            if let Some(j) = v.iter().position(|x| x.is_nan() || *x <= 0.0) {
                return Err(Error::InvalidArgument(format!(
                    "{what} must be positive (or infinite for none), but joint {} has {}",
                    names[j], v[j]
                )));
            }
        }
        Ok(())
    }
}

/// How near each kind of limit a state is: `max_j |q̇_j| / vmax_j`, `max_j |q̈_j| / amax_j` and
/// `max_j |τ_j| / τmax_j` (1 on the limit), in the order velocity, acceleration, torque. Along a
/// time-optimal motion one of them is 1 at almost every instant: the limiting constraint.
///
/// ```
/// use screwdyn::motion::{limit_fractions, TimingLimits};
/// let l = TimingLimits { velocity: vec![2.0, 1.0], acceleration: vec![f64::INFINITY; 2], effort: vec![10.0, 5.0] };
/// let f = limit_fractions(&l, &[1.0, -1.0], &[3.0, 0.0], &[2.0, -4.0]);
/// assert_eq!(f, [1.0, 0.0, 0.8]);
/// ```
pub fn limit_fractions(limits: &TimingLimits, qd: &[f64], qdd: &[f64], tau: &[f64]) -> [f64; 3] {
    let most = |x: &[f64], l: &[f64]| {
        x.iter()
            .zip(l)
            .map(|(x, l)| x.abs() / l)
            .fold(0.0, f64::max)
    };
    [
        most(qd, &limits.velocity),
        most(qdd, &limits.acceleration),
        most(tau, &limits.effort),
    ]
}

/// How [`time_optimal`] chooses its grid and checks its result.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeOptimalOptions {
    /// A fixed number of grid intervals (uniform in `s`): no refinement. `None` (default):
    /// start at `initial_grid` and double until the duration converges.
    pub grid: Option<usize>,
    /// The first grid of the refinement (default 100 intervals).
    pub initial_grid: usize,
    /// The finest grid tried (default 2¹⁶ intervals).
    pub max_grid: usize,
    /// The duration has converged when doubling the grid changes it by less than this fraction
    /// (default `10⁻³`). The duration converges to first order in the grid step (it is
    /// overestimated by about as much as the last doubling changed it).
    pub duration_tolerance: f64,
    /// The step (s) at which the result is sampled and checked (default `10⁻³`).
    pub check_step: f64,
    /// The safety margin (a fraction of each limit, default `10⁻⁴`): the timing is planned
    /// within `(1 − margin)` of every velocity, acceleration and torque limit, where it holds at
    /// the grid points; between them it can exceed that by second order in the grid step, so
    /// the margin keeps every sample of the check within the limits themselves. A sample over a
    /// limit refines the grid further.
    pub limit_margin: f64,
    /// A bound on the path speed, `ṡ ≤ max_path_speed` (default `+∞`: none), kept within the
    /// same margin as the joint limits. A Cartesian move uses it for its tool speed limit.
    pub max_path_speed: f64,
}

impl Default for TimeOptimalOptions {
    fn default() -> Self {
        TimeOptimalOptions {
            grid: None,
            initial_grid: 100,
            max_grid: 1 << 16,
            duration_tolerance: 1e-3,
            check_step: 1e-3,
            limit_margin: 1e-4,
            max_path_speed: f64::INFINITY,
        }
    }
}

/// What the timing found out on the way.
#[derive(Clone, Debug, PartialEq)]
pub struct TimingReport {
    /// `(grid intervals, duration)` of each grid tried, coarsest first.
    pub durations: Vec<(usize, f64)>,
    /// Grids added after the duration had converged because the check found a limit exceeded.
    pub refined_for_limits: usize,
    /// The largest excess over a limit found by the final check, as a fraction of the limit
    /// (`max(|value| / limit) − 1`: negative when every sample stays inside, about
    /// `−limit_margin` when the motion is limited somewhere).
    pub max_excess: f64,
    /// The limit nearest to (or furthest over) its bound in the final check: kind, joint and
    /// time.
    pub worst: (LimitKind, usize, f64),
    /// Number of samples checked.
    pub samples_checked: usize,
    /// The torques of the final check's samples summarised against the model's effort limits:
    /// what [`torque_profile_into`](crate::sim::torque_profile_into) reports for this timing
    /// every `check_step` seconds, the same samples and the same inverse dynamics (to round-off:
    /// the check evaluates it for eight samples side by side, see [`crate::batch`]), so a
    /// profile at that step need not compute them again.
    pub profile: ProfileSummary,
}

/// The timing on one grid: `s_i`, `x_i = ṡ_i²`, `u_i` and the times `t_i`.
#[derive(Clone, Debug)]
pub(super) struct Timing {
    s: Vec<f64>,
    x: Vec<f64>,
    u: Vec<f64>,
    t: Vec<f64>,
}

impl Timing {
    /// `(s, ṡ, s̈)` at time `t`: on interval `k`, `s = s_k + ṡ_k τ + u_k τ²/2` with `τ = t − t_k`.
    fn state(&self, t: f64) -> (f64, f64, f64) {
        let n = self.s.len() - 1;
        let k = (self.t.partition_point(|&x| x <= t).max(1) - 1).min(n - 1);
        self.state_on(t, k)
    }

    /// [`state`](Self::state) for times that only increase from call to call: the interval is
    /// found by stepping on from the previous one (`k`, 0 at first) instead of a binary search.
    pub(super) fn state_after(&self, t: f64, k: &mut usize) -> (f64, f64, f64) {
        let last = self.s.len() - 2;
        while *k < last && self.t[*k + 1] <= t {
            *k += 1;
        }
        self.state_on(t, *k)
    }

    /// The state at `t` on interval `k` (which holds `t` unless `t` is outside the motion).
    fn state_on(&self, t: f64, k: usize) -> (f64, f64, f64) {
        let n = self.s.len() - 1;
        if t >= self.t[n] {
            return (self.s[n], 0.0, 0.0);
        }
        let t = t.max(0.0);
        let tau = t - self.t[k];
        let (u, v0) = (self.u[k], self.x[k].sqrt());
        let s = (self.s[k] + v0 * tau + 0.5 * u * tau * tau).clamp(self.s[k], self.s[k + 1]);
        (s, (v0 + u * tau).max(0.0), u)
    }

    /// `q`, `q̇ = q' ṡ`, `q̈ = q' s̈ + q'' ṡ²` at time `t`.
    fn eval(&self, path: &dyn Path, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        let state = self.state(t);
        Self::to_joints(path, state, q, qd, qdd);
    }

    /// `q(s)`, `q'(s) ṡ` and `q'(s) s̈ + q''(s) ṡ²` from the path state `(s, ṡ, s̈)`.
    pub(super) fn to_joints(
        path: &dyn Path,
        (s, sd, sdd): (f64, f64, f64),
        q: &mut [f64],
        qd: &mut [f64],
        qdd: &mut [f64],
    ) {
        path.eval(s, q, qd, qdd);
        for j in 0..q.len() {
            let d = qd[j];
            qd[j] = d * sd;
            qdd[j] = d * sdd + qdd[j] * sd * sd;
        }
    }

    pub(super) fn duration(&self) -> f64 {
        self.t[self.t.len() - 1]
    }
}

/// A time-optimal timing of a path: `s(t)` with constant `s̈ = u_i` between the grid points
/// `s_i`, which it passes at `ṡ_i = √x_i` and times `t_i`. A [`Trajectory`], so
/// [`torque_profile`](crate::sim::torque_profile) and simulation use it like any other.
#[derive(Clone, Debug)]
pub struct TimeOptimal<P: Path> {
    path: P,
    timing: Timing,
    report: TimingReport,
}

impl<P: Path> TimeOptimal<P> {
    /// The path timed.
    pub fn path(&self) -> &P {
        &self.path
    }
    /// The grid `s_i`.
    pub fn grid(&self) -> &[f64] {
        &self.timing.s
    }
    /// `ṡ²` at the grid points: the phase-plane curve.
    pub fn speed_squared(&self) -> &[f64] {
        &self.timing.x
    }
    /// The times `t_i` at which the grid points are passed.
    pub fn times(&self) -> &[f64] {
        &self.timing.t
    }
    /// What the refinement and the check found.
    pub fn report(&self) -> &TimingReport {
        &self.report
    }
    /// The timing itself, for the tests of its check.
    #[cfg(test)]
    pub(super) fn timing(&self) -> &Timing {
        &self.timing
    }
    /// `(s, ṡ, s̈)` at time `t` (clamped to `[0, duration]`).
    pub fn path_state(&self, t: f64) -> (f64, f64, f64) {
        self.timing.state(t)
    }
}

impl<P: Path> Trajectory for TimeOptimal<P> {
    fn nq(&self) -> usize {
        self.path.nq()
    }
    fn duration(&self) -> f64 {
        self.timing.duration()
    }
    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        self.timing.eval(&self.path, t, q, qd, qdd);
    }
}

/// The fastest timing of `path` from rest to rest within `limits` (TOPP-RA).
///
/// With `u = s̈`, `x = ṡ²`, each limit is linear in `(u, x)` at every `s`:
/// `x ≤ (vmax_j / |q'_j|)²`, `|q'_j u + q''_j x| ≤ amax_j`, `|a_j u + b_j x + c_j| ≤ τmax_j`
/// (the coefficients of [`PathDynamics`](super::PathDynamics)). On a uniform grid `s_0 … s_N` with
/// `x_{i+1} = x_i + 2 Δ u_i`, the controllable sets `K_i` are computed backward from
/// `K_N = {0}` and the greedy forward pass from `x_0 = 0` takes the largest `u_i` keeping
/// `x_{i+1} ∈ K_{i+1}`. The grid is doubled until the duration changes by less than
/// `duration_tolerance`. The limits used are `(1 − limit_margin)` of those given; the result is
/// then sampled every `check_step` seconds and its velocities, accelerations and torques
/// (inverse dynamics plus springs and Coulomb friction) compared with the limits given; while one exceeds
/// its limit the grid is doubled again.
///
/// # Errors
/// [`Error::InvalidArgument`] for limits that are not positive, a path whose joints do not
/// match the model, a path point outside the joint position limits or where gravity (and
/// friction) alone needs more than an effort limit (each naming `s` and the joint), a path that
/// no timing can follow (naming the first `s` where it fails), bad options;
/// [`Error::Numerical`] when the check still fails on the finest grid.
///
/// ```
/// use screwdyn::motion::{time_optimal, CubicSpline, TimeOptimalOptions, TimingLimits};
/// use screwdyn::sim::Trajectory;
/// // A pendulum swung from −0.5 to 0.5 rad; only its 5 N·m motor limits it.
/// let m = screwdyn::builtin::pendulum();
/// let path = CubicSpline::new(&[0.0, 1.0], &[vec![-0.5], vec![0.5]]).unwrap();
/// let mut limits = TimingLimits::from_model(&m);
/// limits.effort = vec![5.0];
/// let timed = time_optimal(&m, path, &limits, &TimeOptimalOptions::default()).unwrap();
/// assert!(timed.duration() > 0.5 && timed.duration() < 1.5);
/// assert!(timed.report().max_excess <= 0.0); // every sample within the limits
/// ```
pub fn time_optimal<P: Path>(
    model: &Model,
    path: P,
    limits: &TimingLimits,
    options: &TimeOptimalOptions,
) -> Result<TimeOptimal<P>> {
    limits.check(model)?;
    check_options(options)?;
    let keep = 1.0 - options.limit_margin;
    let mut dynamics = GridCoefficients::new(model, path.nq())?;
    let mut check_ws = CheckWorkspace::new(model, limits);
    // The rows of the grid being timed, and of the one before (half as fine).
    let (mut constraints, mut coarse) = (Constraints::default(), Constraints::default());
    let mut durations: Vec<(usize, f64)> = Vec::new();
    let mut grid = options.grid.unwrap_or(options.initial_grid);
    let mut refined_for_limits = 0;
    let mut converged = options.grid.is_some();
    loop {
        std::mem::swap(&mut constraints, &mut coarse);
        let timing = time_on_grid(
            model,
            &path,
            grid,
            (limits, keep, options.max_path_speed),
            &mut dynamics,
            (&coarse, &mut constraints),
        )?;
        let duration = timing.duration();
        if let Some(&(_, previous)) = durations.last() {
            converged |= (previous - duration).abs() <= options.duration_tolerance * duration;
        }
        durations.push((grid, duration));
        let finest = options.grid.is_some() || 2 * grid > options.max_grid;
        if converged || finest {
            let check = check_limits(
                model,
                &mut dynamics.batch,
                &mut check_ws,
                &path,
                &timing,
                options.check_step,
            );
            if check.0 <= 0.0 || finest {
                if check.0 > 0.0 && options.grid.is_none() {
                    let (kind, j, at) = check.1;
                    return Err(Error::Numerical(format!(
                        "the timing on the finest grid ({grid} intervals) still exceeds the {} limit of joint {} by {:.3} % at t = {at:.4} s",
                        kind_word(kind),
                        model.joint_names()[j],
                        100.0 * check.0
                    )));
                }
                return Ok(TimeOptimal {
                    path,
                    timing,
                    report: TimingReport {
                        durations,
                        refined_for_limits,
                        max_excess: check.0,
                        worst: check.1,
                        samples_checked: check.2,
                        profile: check.3,
                    },
                });
            }
            refined_for_limits += 1;
        }
        grid *= 2;
    }
}

/// `velocity`, `acceleration` or `torque`.
pub(crate) fn kind_word(kind: LimitKind) -> &'static str {
    match kind {
        LimitKind::Velocity => "velocity",
        LimitKind::Acceleration => "acceleration",
        LimitKind::Torque => "torque",
    }
}

fn check_options(o: &TimeOptimalOptions) -> Result<()> {
    let bad = |what: &str, why: &str| Err(Error::InvalidArgument(format!("{what} {why}")));
    if o.grid == Some(0) || o.initial_grid == 0 {
        return bad("the grid", "needs at least one interval");
    }
    if o.max_grid < o.initial_grid {
        return bad("the finest grid", "must not be smaller than the first grid");
    }
    for (what, x) in [
        ("the duration tolerance", o.duration_tolerance),
        ("the check step", o.check_step),
    ] {
        if !(x.is_finite() && x > 0.0) {
            return bad(what, &format!("must be positive and finite (got {x})"));
        }
    }
    if o.max_path_speed.is_nan() || o.max_path_speed <= 0.0 {
        return bad(
            "the path speed bound",
            &format!("must be positive (got {})", o.max_path_speed),
        );
    }
    if !(0.0..1.0).contains(&o.limit_margin) {
        return bad(
            "the limit margin",
            &format!("must be at least 0 and below 1 (got {})", o.limit_margin),
        );
    }
    Ok(())
}

/// `N + 1` points evenly spaced over the path's range.
fn uniform_grid(path: &dyn Path, n: usize) -> Vec<f64> {
    let (a, b) = path.s_range();
    (0..=n)
        .map(|i| {
            if i == n {
                b
            } else {
                a + (b - a) * i as f64 / n as f64
            }
        })
        .collect()
}

/// The timing on a uniform grid of `n` intervals within `keep` times the limits; `coarse` holds
/// the rows of the previous grid (or none).
fn time_on_grid(
    model: &Model,
    path: &dyn Path,
    n: usize,
    limits: (&TimingLimits, f64, f64),
    dynamics: &mut GridCoefficients,
    (coarse, constraints): (&Constraints, &mut Constraints),
) -> Result<Timing> {
    let s = uniform_grid(path, n);
    fill_constraints(model, path, &s, limits, dynamics, coarse, constraints)?;
    let mut p = Parameterization::default();
    if let Err(e) = parameterize(&s, constraints, &mut p) {
        return Err(Error::InvalidArgument(format!(
            "no timing can follow the path at s = {}: from there the end cannot be reached at rest within the limits",
            fmt_s(s[e.point])
        )));
    }
    let mut t = Vec::with_capacity(s.len());
    let duration = interval_times(&s, &p.x, &mut t);
    if !duration.is_finite() {
        return Err(Error::InvalidArgument(
            "the path does not move the joints (q' = 0 everywhere), so it has no timing".into(),
        ));
    }
    Ok(Timing {
        s,
        x: p.x,
        u: p.u,
        t,
    })
}

fn fmt_s(s: f64) -> String {
    format!("{}", (s * 1e6).round() / 1e6)
}

/// The rows `α u + β x ≤ γ` of every grid point (acceleration and torque, both signs) and the
/// speed bounds `x ≤ min_j (vmax_j / |q'_j|)²`, within `keep` times the limits; refuses points
/// outside the position limits or where `|c_j(s)| > keep τmax_j` (the robot could not be held
/// there). On a doubled grid (`coarse` has the rows of `s_0, s_2, s_4, …`, which
/// [`uniform_grid`] computes to the same bits) the even points' rows are copied, not recomputed.
/// The coefficients of the others are computed [`POINTS_PER_CALL`] at a time
/// ([`GridCoefficients`]), the rows then written point by point in grid order.
fn fill_constraints(
    model: &Model,
    path: &dyn Path,
    s: &[f64],
    limits: (&TimingLimits, f64, f64),
    dynamics: &mut GridCoefficients,
    coarse: &Constraints,
    c: &mut Constraints,
) -> Result<()> {
    // Only the rows of finite limits are kept (the others never bind), two per limit.
    let finite = |l: &[f64]| l.iter().filter(|x| x.is_finite()).count();
    c.rows_per_point = 2 * (finite(&limits.0.acceleration) + finite(&limits.0.effort));
    // point_rows writes each limit's two rows one after the other.
    c.paired = true;
    c.rows.clear();
    c.x_max.clear();
    c.rows.reserve(s.len() * c.rows_per_point);
    c.x_max.reserve(s.len());
    let doubled = s.len() % 2 == 1
        && coarse.x_max.len() == s.len() / 2 + 1
        && coarse.rows_per_point == c.rows_per_point;
    let copied = |k: usize| doubled && k % 2 == 0;
    let mut wanted = [0.0; POINTS_PER_CALL];
    let mut first = 0;
    while first < s.len() {
        // The next grid points up to POINTS_PER_CALL computed ones, and their coefficients.
        let (mut end, mut count) = (first, 0);
        while end < s.len() && (count < POINTS_PER_CALL || copied(end)) {
            if !copied(end) {
                wanted[count] = s[end];
                count += 1;
            }
            end += 1;
        }
        let batched = dynamics.eval(model, path, &wanted[..count]);
        let mut next = 0;
        for (k, &si) in s.iter().enumerate().take(end).skip(first) {
            if copied(k) {
                c.rows.extend_from_slice(coarse.at(k / 2));
                c.x_max.push(coarse.x_max[k / 2]);
                continue;
            }
            if batched {
                point_rows(model, si, dynamics.point(next), limits, c)?;
            } else {
                let p = dynamics.one.at(model, path, si)?;
                point_rows(model, si, p.into(), limits, c)?;
            }
            next += 1;
        }
        first = end;
    }
    Ok(())
}

/// The rows and the speed bound of the grid point `si` (see [`fill_constraints`]).
fn point_rows(
    model: &Model,
    si: f64,
    p: PointView<'_>,
    (limits, keep, path_speed): (&TimingLimits, f64, f64),
    c: &mut Constraints,
) -> Result<()> {
    // x = ṡ² ≤ (keep · max_path_speed)²
    let mut x_max = (keep * path_speed).powi(2);
    for (j, joint) in model.joints().iter().enumerate() {
        let (lo, hi) = (joint.limits.lower, joint.limits.upper);
        if p.q[j] < lo || p.q[j] > hi {
            return Err(Error::InvalidArgument(format!(
                "the path leaves the position limits of joint {} at s = {}: q = {} outside [{lo}, {hi}]",
                model.joint_names()[j],
                fmt_s(si),
                p.q[j]
            )));
        }
        let effort = limits.effort[j] * keep;
        if p.c[j].abs() > effort {
            return Err(Error::InvalidArgument(format!(
                "gravity alone needs {:.3} at joint {} at s = {}, more than its effort limit {} allows: the robot cannot be held there",
                p.c[j].abs(),
                model.joint_names()[j],
                fmt_s(si),
                limits.effort[j]
            )));
        }
        // x ≤ (vmax / |q'|)²
        if p.dq[j] != 0.0 {
            x_max = x_max.min((keep * limits.velocity[j] / p.dq[j]).powi(2));
        }
        // ±(q' u + q'' x) ≤ amax,  ±(a u + b x + c) ≤ τmax
        let amax = keep * limits.acceleration[j];
        if amax.is_finite() {
            c.rows.push([p.dq[j], p.ddq[j], amax]);
            c.rows.push([-p.dq[j], -p.ddq[j], amax]);
        }
        if effort.is_finite() {
            c.rows.push([p.a[j], p.b[j], effort - p.c[j]]);
            c.rows.push([-p.a[j], -p.b[j], effort + p.c[j]]);
        }
    }
    c.x_max.push(x_max);
    Ok(())
}
