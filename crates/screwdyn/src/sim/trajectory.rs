//! Joint-space trajectories: trapezoidal velocity profiles (the "from rest to constant
//! velocity, and then back to stop"), quintic polynomials, and piecewise quintics through
//! waypoints.

use super::setting::{check, Range};
use crate::error::{Error, Result};

/// A joint-space reference `q_d(t)`, `q̇_d(t)`, `q̈_d(t)` on `[0, duration]` (held constant
/// after the end).
pub trait Trajectory {
    /// Number of joints.
    fn nq(&self) -> usize;
    /// Duration in seconds.
    fn duration(&self) -> f64;
    /// Writes position, velocity and acceleration at time `t` (clamped to `[0, duration]`)
    /// into slices of length [`nq`](Trajectory::nq), which the caller guarantees; implement
    /// this and call [`sample`](Trajectory::sample).
    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]);
    /// Position, velocity and acceleration at time `t` (clamped to `[0, duration]`).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when a slice does not have [`nq`](Trajectory::nq) entries or
    /// `t` is NaN.
    ///
    /// ```
    /// use screwdyn::sim::{Quintic, Trajectory};
    /// let t = Quintic::rest_to_rest(&[0.0, 0.0], &[1.0, 2.0], 1.0).unwrap();
    /// let (mut q, mut qd, mut qdd) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    /// t.sample(1.0, &mut q, &mut qd, &mut qdd).unwrap();
    /// assert_eq!(q, [1.0, 2.0]);
    /// assert!(t.sample(0.5, &mut [0.0], &mut qd, &mut qdd).is_err());
    /// ```
    fn sample(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) -> Result<()> {
        let n = self.nq();
        if q.len() != n || qd.len() != n || qdd.len() != n {
            return Err(Error::InvalidArgument(format!(
                "a trajectory of {n} joints was sampled into buffers of {}, {} and {} values",
                q.len(),
                qd.len(),
                qdd.len()
            )));
        }
        if t.is_nan() {
            return Err(Error::InvalidArgument(
                "a trajectory was sampled at t = NaN".into(),
            ));
        }
        self.eval(t, q, qd, qdd);
        Ok(())
    }
}

fn check_same_len(what: &str, a: &[f64], n: usize) -> Result<()> {
    if a.len() != n {
        return Err(Error::InvalidArgument(format!(
            "{what} has {} values, expected {n}",
            a.len()
        )));
    }
    if let Some((i, x)) = a.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(Error::NonFinite {
            what: what.into(),
            index: i,
            value: format!("{x:?}"),
        });
    }
    Ok(())
}

#[derive(Clone, Debug, PartialEq)]
struct Ramp {
    q0: f64,
    qf: f64,
    sign: f64,
    accel: f64,
    cruise: f64,
    t_accel: f64,
    t_cruise: f64,
}

impl Ramp {
    /// Time-optimal profile for `distance ≥ 0` under `vmax`, `amax`.
    fn fastest(distance: f64, vmax: f64, amax: f64) -> (f64, f64) {
        let ta = vmax / amax;
        if amax * ta * ta >= distance {
            ((distance / amax).sqrt(), 0.0)
        } else {
            (ta, (distance - amax * ta * ta) / vmax)
        }
    }

    fn sample(&self, t: f64) -> (f64, f64, f64) {
        let (a, ta, tc) = (self.accel, self.t_accel, self.t_cruise);
        let total = 2.0 * ta + tc;
        let t = t.clamp(0.0, total);
        let (p, v, acc) = if t < ta {
            (0.5 * a * t * t, a * t, a)
        } else if t < ta + tc {
            (0.5 * a * ta * ta + self.cruise * (t - ta), self.cruise, 0.0)
        } else if t < total {
            let r = total - t;
            let d = a * ta * ta + self.cruise * tc;
            (d - 0.5 * a * r * r, a * r, -a)
        } else {
            return (self.qf, 0.0, 0.0);
        };
        (self.q0 + self.sign * p, self.sign * v, self.sign * acc)
    }
}

/// Trapezoidal velocity profiles: each joint accelerates at its `amax` from rest, cruises at
/// most at `vmax`, and decelerates to rest at the target. Synchronised profiles all last as long
/// as the slowest joint (each joint keeps its `amax` and lowers its cruise speed).
///
/// ```
/// use screwdyn::sim::{Trajectory, Trapezoid};
/// // 1 rad at up to 1 rad/s and 2 rad/s²: 0.5 s ramp, 0.5 s cruise, 0.5 s ramp.
/// let t = Trapezoid::new(&[0.0], &[1.0], &[1.0], &[2.0], true).unwrap();
/// assert!((t.duration() - 1.5).abs() < 1e-12);
/// let (mut q, mut qd, mut qdd) = ([0.0], [0.0], [0.0]);
/// t.sample(0.75, &mut q, &mut qd, &mut qdd);
/// assert_eq!((q[0], qd[0], qdd[0]), (0.5, 1.0, 0.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Trapezoid {
    ramps: Vec<Ramp>,
    duration: f64,
}

impl Trapezoid {
    /// Profiles from `q0` to `qf` under per-joint limits `vmax`, `amax` (positive).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) for vectors of different lengths, non-positive limits or duration; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞.
    pub fn new(
        q0: &[f64],
        qf: &[f64],
        vmax: &[f64],
        amax: &[f64],
        synchronised: bool,
    ) -> Result<Self> {
        let n = q0.len();
        check_same_len("the target", qf, n)?;
        check_same_len("the velocity limits", vmax, n)?;
        check_same_len("the acceleration limits", amax, n)?;
        check_same_len("the start", q0, n)?;
        for i in 0..n {
            if vmax[i] <= 0.0 || amax[i] <= 0.0 {
                return Err(Error::InvalidArgument(format!(
                    "joint {i}: velocity and acceleration limits must be positive (got {} and {})",
                    vmax[i], amax[i]
                )));
            }
        }
        let times: Vec<(f64, f64)> = (0..n)
            .map(|i| Ramp::fastest((qf[i] - q0[i]).abs(), vmax[i], amax[i]))
            .collect();
        let longest = times
            .iter()
            .map(|(ta, tc)| 2.0 * ta + tc)
            .fold(0.0, f64::max);
        let ramps = (0..n)
            .map(|i| {
                let d = (qf[i] - q0[i]).abs();
                let a = amax[i];
                let (ta, tc) = if synchronised && d > 0.0 {
                    // Cruise speed v with d = v (T − v/a): the smaller root.
                    let t = longest;
                    let disc = (a * a * t * t - 4.0 * a * d).max(0.0);
                    let v = 0.5 * (a * t - disc.sqrt());
                    let ta = v / a;
                    (ta, (t - 2.0 * ta).max(0.0))
                } else {
                    times[i]
                };
                Ramp {
                    q0: q0[i],
                    qf: qf[i],
                    sign: if qf[i] >= q0[i] { 1.0 } else { -1.0 },
                    accel: a,
                    cruise: a * ta,
                    t_accel: ta,
                    t_cruise: tc,
                }
            })
            .collect();
        Ok(Trapezoid {
            ramps,
            duration: longest,
        })
    }

    /// The cruise speed reached by each joint.
    pub fn cruise_speeds(&self) -> Vec<f64> {
        self.ramps.iter().map(|r| r.cruise).collect()
    }
}

impl Trajectory for Trapezoid {
    fn nq(&self) -> usize {
        self.ramps.len()
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        for (i, r) in self.ramps.iter().enumerate() {
            (q[i], qd[i], qdd[i]) = r.sample(t);
        }
    }
}

/// A quintic polynomial per joint from `(q0, v0, a0)` at `t = 0` to `(qf, vf, af)` at
/// `t = T`: the minimum-jerk family used for smooth point-to-point motion.
///
/// ```
/// use screwdyn::sim::{Quintic, Trajectory};
/// let t = Quintic::rest_to_rest(&[0.0], &[1.0], 2.0).unwrap();
/// let (mut q, mut qd, mut qdd) = ([0.0], [0.0], [0.0]);
/// t.sample(1.0, &mut q, &mut qd, &mut qdd).unwrap();
/// assert!((q[0] - 0.5).abs() < 1e-15); // symmetric about the midpoint
/// assert!((qd[0] - 15.0 / 16.0).abs() < 1e-14); // peak speed 15/8 · Δq/T
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Quintic {
    coeffs: Vec<[f64; 6]>,
    duration: f64,
}

impl Quintic {
    /// The general boundary-value quintic.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) for vectors of different lengths, non-positive limits or duration; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞.
    pub fn new(
        start: (&[f64], &[f64], &[f64]),
        end: (&[f64], &[f64], &[f64]),
        duration: f64,
    ) -> Result<Self> {
        let n = start.0.len();
        for (what, v) in [
            ("q0", start.0),
            ("v0", start.1),
            ("a0", start.2),
            ("qf", end.0),
            ("vf", end.1),
            ("af", end.2),
        ] {
            check_same_len(what, v, n)?;
        }
        check(
            "duration",
            duration,
            Range::Positive,
            "the length of the quintic in seconds",
        )?;
        let t = duration;
        let coeffs = (0..n)
            .map(|i| {
                let (q0, v0, a0) = (start.0[i], start.1[i], start.2[i]);
                let (qf, vf, af) = (end.0[i], end.1[i], end.2[i]);
                let h = qf - q0;
                [
                    q0,
                    v0,
                    a0 / 2.0,
                    (20.0 * h - (8.0 * vf + 12.0 * v0) * t - (3.0 * a0 - af) * t * t)
                        / (2.0 * t.powi(3)),
                    (-30.0 * h + (14.0 * vf + 16.0 * v0) * t + (3.0 * a0 - 2.0 * af) * t * t)
                        / (2.0 * t.powi(4)),
                    (12.0 * h - 6.0 * (vf + v0) * t - (a0 - af) * t * t) / (2.0 * t.powi(5)),
                ]
            })
            .collect();
        Ok(Quintic { coeffs, duration })
    }

    /// From rest at `q0` to rest at `qf` in `duration` seconds.
    ///
    /// # Errors
    /// As [`Quintic::new`].
    pub fn rest_to_rest(q0: &[f64], qf: &[f64], duration: f64) -> Result<Self> {
        let z = vec![0.0; q0.len()];
        Quintic::new((q0, &z, &z), (qf, &z, &z), duration)
    }
}

fn eval_quintic(c: &[f64; 6], t: f64) -> (f64, f64, f64) {
    let q = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
    let v = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])));
    let a = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]));
    (q, v, a)
}

impl Trajectory for Quintic {
    fn nq(&self) -> usize {
        self.coeffs.len()
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        let tc = t.clamp(0.0, self.duration);
        for (i, c) in self.coeffs.iter().enumerate() {
            (q[i], qd[i], qdd[i]) = eval_quintic(c, tc);
            if t > self.duration {
                // Held at rest at the final position.
                (qd[i], qdd[i]) = (0.0, 0.0);
            }
        }
    }
}

/// Piecewise quintics through waypoints `q_k` at times `t_k`, starting and ending at rest;
/// interior velocities are the average of the neighbouring segment slopes, interior
/// accelerations zero, so position, velocity and acceleration are continuous.
///
/// ```
/// use screwdyn::sim::{Trajectory, Waypoints};
/// let w = Waypoints::new(&[0.0, 1.0, 3.0], &[vec![0.0], vec![1.0], vec![0.0]]).unwrap();
/// let (mut q, mut qd, mut qdd) = ([0.0], [0.0], [0.0]);
/// w.sample(1.0, &mut q, &mut qd, &mut qdd).unwrap();
/// assert!((q[0] - 1.0).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Waypoints {
    times: Vec<f64>,
    segments: Vec<Quintic>,
}

impl Waypoints {
    /// Through `points[k]` at `times[k]` (strictly increasing, starting anywhere).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) for vectors of different lengths, non-positive limits or duration; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞.
    pub fn new(times: &[f64], points: &[Vec<f64>]) -> Result<Self> {
        if times.len() != points.len() || times.len() < 2 {
            return Err(Error::InvalidArgument(format!(
                "waypoints need at least two points with one time each (got {} times, {} points)",
                times.len(),
                points.len()
            )));
        }
        let n = points[0].len();
        for (k, p) in points.iter().enumerate() {
            check_same_len(&format!("waypoint {k}"), p, n)?;
        }
        if times.windows(2).any(|w| w[1] <= w[0]) {
            return Err(Error::InvalidArgument(
                "waypoint times must increase strictly".into(),
            ));
        }
        let m = times.len();
        let slope =
            |k: usize, i: usize| (points[k + 1][i] - points[k][i]) / (times[k + 1] - times[k]);
        let vel: Vec<Vec<f64>> = (0..m)
            .map(|k| {
                (0..n)
                    .map(|i| {
                        if k == 0 || k == m - 1 {
                            0.0
                        } else {
                            0.5 * (slope(k - 1, i) + slope(k, i))
                        }
                    })
                    .collect()
            })
            .collect();
        let z = vec![0.0; n];
        let segments = (0..m - 1)
            .map(|k| {
                Quintic::new(
                    (&points[k], &vel[k], &z),
                    (&points[k + 1], &vel[k + 1], &z),
                    times[k + 1] - times[k],
                )
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Waypoints {
            times: times.to_vec(),
            segments,
        })
    }
}

impl Trajectory for Waypoints {
    fn nq(&self) -> usize {
        self.segments[0].nq()
    }
    fn duration(&self) -> f64 {
        self.times[self.times.len() - 1] - self.times[0]
    }
    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        let abs = self.times[0] + t;
        let k = self.times[1..]
            .iter()
            .position(|&tk| abs < tk)
            .unwrap_or(self.segments.len() - 1);
        let local = abs - self.times[k];
        self.segments[k].eval(local, q, qd, qdd);
    }
}
