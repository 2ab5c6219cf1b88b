//! Jerk-limited point-to-point motion from rest to rest: per joint, the time-optimal
//! seven-segment profile under velocity, acceleration and jerk limits; all joints synchronised
//! to finish with the slowest.

use crate::error::{Error, Result};
use crate::sim::Trajectory;

/// The durations `(t_j, t_a, t_v)` of the fastest rest-to-rest profile over `d ≥ 0`: jerk
/// `+j` for `t_j`, constant acceleration for `t_a`, jerk `−j` for `t_j` (reaching the peak
/// speed), cruise for `t_v`, and the mirror image; total `T = 4 t_j + 2 t_a + t_v`.
///
/// - The speed limit is reached when `d ≥ v (2 t_j + t_a)` with `t_j = min(a/j, √(v/j))`,
///   `t_a = v/a − t_j` (zero when `v j < a²`): `t_v = d/v − (2 t_j + t_a)`.
/// - Otherwise the acceleration limit is reached when `d ≥ 2 a³/j²`: `t_j = a/j` and `t_a`
///   solves `a (t_j + t_a)(2 t_j + t_a) = d`.
/// - Otherwise neither: `t_a = 0`, `d = 2 j t_j³`.
pub(crate) fn fastest(d: f64, v: f64, a: f64, j: f64) -> (f64, f64, f64) {
    if d <= 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let (tj, ta) = if v * j >= a * a {
        (a / j, v / a - a / j)
    } else {
        ((v / j).sqrt(), 0.0)
    };
    if d >= v * (2.0 * tj + ta) {
        return (tj, ta, d / v - (2.0 * tj + ta));
    }
    if d >= 2.0 * a * a * a / (j * j) {
        let tj = a / j;
        // t_a² + 3 t_j t_a + 2 t_j² − d/a = 0
        let ta = 0.5 * (-3.0 * tj + (tj * tj + 4.0 * d / a).sqrt());
        return (tj, ta.max(0.0), 0.0);
    }
    ((0.5 * d / j).cbrt(), 0.0, 0.0)
}

/// One joint's profile: seven segments of constant jerk, the state at each boundary.
#[derive(Clone, Debug, PartialEq)]
struct Profile {
    q0: f64,
    qf: f64,
    /// Segment start times (8 entries, the last the end).
    start: [f64; 8],
    /// Jerk on each segment (signed, the direction of motion included).
    jerk: [f64; 7],
    /// `(q, q̇, q̈)` at each segment start.
    state: [(f64, f64, f64); 8],
}

impl Profile {
    /// The profile of durations `(t_j, t_a, t_v)` stretched by `k ≥ 1` (every duration × k,
    /// jerk ÷ k³: the same shape, slower).
    fn new(q0: f64, qf: f64, durations: (f64, f64, f64), jmax: f64, k: f64) -> Self {
        let (tj, ta, tv) = (durations.0 * k, durations.1 * k, durations.2 * k);
        let j = (qf - q0).signum() * jmax / (k * k * k);
        let lengths = [tj, ta, tj, tv, tj, ta, tj];
        let jerk = [j, 0.0, -j, 0.0, -j, 0.0, j];
        let mut start = [0.0; 8];
        let mut state = [(q0, 0.0, 0.0); 8];
        for s in 0..7 {
            start[s + 1] = start[s] + lengths[s];
            state[s + 1] = advance(state[s], jerk[s], lengths[s]);
        }
        Profile {
            q0,
            qf,
            start,
            jerk,
            state,
        }
    }

    fn sample(&self, t: f64) -> (f64, f64, f64) {
        if t >= self.start[7] || self.q0 == self.qf {
            return (self.qf, 0.0, 0.0);
        }
        let t = t.max(0.0);
        let s = (self.start.partition_point(|&x| x <= t).max(1) - 1).min(6);
        advance(self.state[s], self.jerk[s], t - self.start[s])
    }
}

/// `(q, q̇, q̈)` after `τ` at constant jerk `j`:
/// `q + q̇ τ + q̈ τ²/2 + j τ³/6`, `q̇ + q̈ τ + j τ²/2`, `q̈ + j τ`.
fn advance((q, v, a): (f64, f64, f64), j: f64, tau: f64) -> (f64, f64, f64) {
    (
        q + tau * (v + tau * (a / 2.0 + tau * j / 6.0)),
        v + tau * (a + tau * j / 2.0),
        a + j * tau,
    )
}

/// Jerk-limited motion from rest at `q0` to rest at `qf`, every joint within its velocity,
/// acceleration and jerk limits, all finishing together in the least time.
///
/// Each joint's fastest profile is the seven-segment one (jerk `+j, 0, −j, 0, −j, 0, +j`; see
/// the durations in `docs/motion.md`); the duration is that of the slowest joint,
/// `T = max_i T_i`, the same as Ruckig's for rest-to-rest motion. Every other joint keeps the
/// shape of its own fastest profile stretched in time by `k_i = T / T_i ≥ 1`: `q_i(t) =
/// q_i*(t / k_i)`, so its speed, acceleration and jerk peaks drop by `k_i`, `k_i²` and `k_i³`
/// and stay within the limits, and every joint starts and stops at the same instants.
///
/// ```
/// use screwdyn::motion::JerkLimited;
/// use screwdyn::sim::Trajectory;
/// // 10 rad at up to 2 rad/s, 1 rad/s², 1 rad/s³: jerk 1 s, accelerate 1 s, jerk 1 s
/// // (6 rad on the way up and down), cruise 2 s: 8 s.
/// let m = JerkLimited::new(&[0.0, 0.0], &[10.0, 1.0], &[2.0; 2], &[1.0; 2], &[1.0; 2]).unwrap();
/// assert!((m.duration() - 8.0).abs() < 1e-12);
/// let (mut q, mut v, mut a) = ([0.0; 2], [0.0; 2], [0.0; 2]);
/// m.sample(4.0, &mut q, &mut v, &mut a).unwrap();
/// assert!((q[0] - 5.0).abs() < 1e-12 && (q[1] - 0.5).abs() < 1e-12); // halfway, both
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct JerkLimited {
    profiles: Vec<Profile>,
    fastest: Vec<f64>,
    duration: f64,
}

impl JerkLimited {
    /// From rest at `q0` to rest at `qf` under per-joint limits `vmax`, `amax`, `jmax`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for vectors of different lengths or a limit that is not
    /// positive and finite (naming the joint); [`Error::NonFinite`] for NaN or ∞ in `q0`, `qf`.
    pub fn new(q0: &[f64], qf: &[f64], vmax: &[f64], amax: &[f64], jmax: &[f64]) -> Result<Self> {
        let n = q0.len();
        for (what, x) in [
            ("q0", q0),
            ("qf", qf),
            ("vmax", vmax),
            ("amax", amax),
            ("jmax", jmax),
        ] {
            if x.len() != n {
                return Err(Error::InvalidArgument(format!(
                    "{what} has {} values, q0 has {n}",
                    x.len()
                )));
            }
            if let Some((i, v)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(Error::NonFinite {
                    what: what.into(),
                    index: i,
                    value: format!("{v:?}"),
                });
            }
        }
        for (what, x) in [("vmax", vmax), ("amax", amax), ("jmax", jmax)] {
            if let Some(i) = x.iter().position(|&v| v <= 0.0) {
                return Err(Error::InvalidArgument(format!(
                    "{what} must be positive, but joint {i} has {}",
                    x[i]
                )));
            }
        }
        let durations: Vec<(f64, f64, f64)> = (0..n)
            .map(|i| fastest((qf[i] - q0[i]).abs(), vmax[i], amax[i], jmax[i]))
            .collect();
        let fastest: Vec<f64> = durations
            .iter()
            .map(|(tj, ta, tv)| 4.0 * tj + 2.0 * ta + tv)
            .collect();
        let duration = fastest.iter().copied().fold(0.0, f64::max);
        let profiles = (0..n)
            .map(|i| {
                let k = if fastest[i] > 0.0 {
                    duration / fastest[i]
                } else {
                    1.0
                };
                Profile::new(q0[i], qf[i], durations[i], jmax[i], k)
            })
            .collect();
        Ok(JerkLimited {
            profiles,
            fastest,
            duration,
        })
    }

    /// Each joint's own shortest duration `T_i` (before synchronisation).
    pub fn fastest_durations(&self) -> &[f64] {
        &self.fastest
    }
}

impl Trajectory for JerkLimited {
    fn nq(&self) -> usize {
        self.profiles.len()
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        for (i, p) in self.profiles.iter().enumerate() {
            (q[i], qd[i], qdd[i]) = p.sample(t);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn total(d: f64, v: f64, a: f64, j: f64) -> f64 {
        let (tj, ta, tv) = fastest(d, v, a, j);
        4.0 * tj + 2.0 * ta + tv
    }

    #[test]
    fn the_three_cases_have_their_closed_form_durations() {
        // Every limit reached: 1 + 1 + 1 s up (6 rad up and down), 2 s cruise.
        assert!((total(10.0, 2.0, 1.0, 1.0) - 8.0).abs() < 1e-14);
        // Speed never reached: t_j = 1, t_a from (1 + t_a)(2 + t_a) = 10, T = 2 (2 + t_a).
        let ta = (-3.0 + 41f64.sqrt()) / 2.0;
        assert!((total(10.0, 10.0, 1.0, 1.0) - 2.0 * (2.0 + ta)).abs() < 1e-14);
        // Jerk only: d = 2 j t_j³, T = 4 t_j.
        assert!((total(1.0, 10.0, 10.0, 1.0) - 4.0 * 0.5f64.cbrt()).abs() < 1e-14);
        // Speed reached without the acceleration limit (v j < a²): t_j = √(v/j).
        assert!((total(10.0, 1.0, 5.0, 1.0) - (10.0 + 2.0)).abs() < 1e-14);
    }

    #[test]
    fn each_profile_ends_at_rest_on_target_within_its_limits() {
        let (v, a, j) = (1.5, 2.0, 7.0);
        for d in [0.01, 0.2, 0.5, 1.0, 3.0, -2.0] {
            let m = JerkLimited::new(&[0.3], &[0.3 + d], &[v], &[a], &[j]).unwrap();
            let p = &m.profiles[0];
            let end = p.state[7];
            assert!(
                (end.0 - (0.3 + d)).abs() < 1e-12 && end.1.abs() < 1e-12 && end.2.abs() < 1e-12,
                "{d}: {end:?}"
            );
            for s in &p.state {
                assert!(s.1.abs() <= v * (1.0 + 1e-12) && s.2.abs() <= a * (1.0 + 1e-12));
            }
        }
    }
}
