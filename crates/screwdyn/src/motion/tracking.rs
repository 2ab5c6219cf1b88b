//! A motion given by its samples `(t_k, q_k, q̇_k, q̈_k)` — a run file written by
//! `torque-profile --output` — as a [`Trajectory`] again, so that a controller can track it:
//! between two samples each joint follows the quintic that matches position, velocity and
//! acceleration at both ends, so `q̇` and `q̈` are the derivatives of `q` everywhere.

use crate::error::{Error, Result};
use crate::sim::Trajectory;

/// A trajectory through samples `(t_k, q_k, q̇_k, q̈_k)`, `t_0 = 0` and increasing, interpolated
/// by quintic Hermite polynomials: on `[t_k, t_{k+1}]`, `h = t_{k+1} − t_k`, `τ = (t − t_k)/h`,
///
/// ```text
/// q(τ) = q_k + V_k τ + A_k τ²/2 + c₃ τ³ + c₄ τ⁴ + c₅ τ⁵,   V = h q̇,  A = h² q̈,
/// c₃ = 10 Δ − 6 V_k − 4 V_{k+1} − (3 A_k − A_{k+1})/2,
/// c₄ = −15 Δ + 8 V_k + 7 V_{k+1} + (3 A_k − 2 A_{k+1})/2,
/// c₅ = 6 Δ − 3 V_k − 3 V_{k+1} − (A_k − A_{k+1})/2,   Δ = q_{k+1} − q_k,
/// ```
///
/// which passes every sample with its velocity and acceleration. Times before `0` and after the
/// last sample give the first and the last sample.
///
/// ```
/// use screwdyn::motion::SampledTrajectory;
/// use screwdyn::sim::{Quintic, Trajectory};
/// // Samples of a quintic rest-to-rest motion every 0.1 s give that quintic back in between.
/// let exact = Quintic::rest_to_rest(&[0.0], &[1.0], 1.0).unwrap();
/// let (mut t, mut q, mut v, mut a) = (vec![], vec![], vec![], vec![]);
/// for k in 0..=10 {
///     let (mut x, mut xd, mut xdd) = ([0.0], [0.0], [0.0]);
///     exact.sample(k as f64 / 10.0, &mut x, &mut xd, &mut xdd).unwrap();
///     t.push(k as f64 / 10.0); q.push(x.to_vec()); v.push(xd.to_vec()); a.push(xdd.to_vec());
/// }
/// let again = SampledTrajectory::new(t, q, v, a).unwrap();
/// let (mut x, mut xd, mut xdd) = ([0.0], [0.0], [0.0]);
/// again.sample(0.55, &mut x, &mut xd, &mut xdd).unwrap();
/// let (mut y, mut yd, mut ydd) = ([0.0], [0.0], [0.0]);
/// exact.sample(0.55, &mut y, &mut yd, &mut ydd).unwrap();
/// assert!((x[0] - y[0]).abs() < 1e-12 && (xd[0] - yd[0]).abs() < 1e-12);
/// assert!(SampledTrajectory::new(vec![0.0, 0.0], vec![vec![0.0]; 2], vec![vec![0.0]; 2], vec![vec![0.0]; 2]).is_err());
/// ```
#[derive(Clone, Debug)]
pub struct SampledTrajectory {
    t: Vec<f64>,
    q: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    a: Vec<Vec<f64>>,
}

impl SampledTrajectory {
    /// The trajectory through the samples `t[k]`, `q[k]`, `v[k]` (`q̇`), `a[k]` (`q̈`).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for fewer than two samples, rows of different lengths, a
    /// first time other than 0, times that do not increase, or a value that is not finite —
    /// each naming the sample.
    pub fn new(t: Vec<f64>, q: Vec<Vec<f64>>, v: Vec<Vec<f64>>, a: Vec<Vec<f64>>) -> Result<Self> {
        let bad = |why: String| Err(Error::InvalidArgument(why));
        if t.len() < 2 {
            return bad(format!(
                "a sampled trajectory needs two samples at least, got {}",
                t.len()
            ));
        }
        let n = q[0].len();
        if q.len() != t.len() || v.len() != t.len() || a.len() != t.len() {
            return bad(format!(
                "a sampled trajectory has {} times but {} positions, {} velocities and {} accelerations",
                t.len(),
                q.len(),
                v.len(),
                a.len()
            ));
        }
        if t[0] != 0.0 {
            return bad(format!(
                "a sampled trajectory starts at t = 0, not at t = {}",
                t[0]
            ));
        }
        for k in 0..t.len() {
            if [&q[k], &v[k], &a[k]].iter().any(|r| r.len() != n) {
                return bad(format!(
                    "sample {} of the trajectory does not have {n} positions, velocities and accelerations",
                    k + 1
                ));
            }
            let finite = t[k].is_finite()
                && [&q[k], &v[k], &a[k]]
                    .iter()
                    .all(|r| r.iter().all(|x| x.is_finite()));
            if !finite {
                return bad(format!(
                    "sample {} of the trajectory has a value that is not finite",
                    k + 1
                ));
            }
            if k > 0 && t[k] <= t[k - 1] {
                return bad(format!(
                    "the trajectory's times must increase, but sample {} is at t = {} after t = {}",
                    k + 1,
                    t[k],
                    t[k - 1]
                ));
            }
        }
        Ok(SampledTrajectory { t, q, v, a })
    }

    /// The sample times.
    pub fn times(&self) -> &[f64] {
        &self.t
    }

    /// Sample `k`'s `(q, q̇, q̈)`.
    ///
    /// # Panics
    /// When `k` is not below the number of samples.
    pub fn sample_at(&self, k: usize) -> (&[f64], &[f64], &[f64]) {
        (&self.q[k], &self.v[k], &self.a[k])
    }
}

impl Trajectory for SampledTrajectory {
    fn nq(&self) -> usize {
        self.q[0].len()
    }

    fn duration(&self) -> f64 {
        self.t[self.t.len() - 1]
    }

    fn eval(&self, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        let last = self.t.len() - 1;
        let t = t.clamp(0.0, self.t[last]);
        // The interval [t_k, t_k+1] holding t.
        let k = (self.t.partition_point(|&x| x <= t).max(1) - 1).min(last - 1);
        let h = self.t[k + 1] - self.t[k];
        let s = (t - self.t[k]) / h;
        for j in 0..q.len() {
            let (p0, p1) = (self.q[k][j], self.q[k + 1][j]);
            let (v0, v1) = (h * self.v[k][j], h * self.v[k + 1][j]);
            let (a0, a1) = (h * h * self.a[k][j], h * h * self.a[k + 1][j]);
            let d = p1 - p0;
            let c3 = 10.0 * d - 6.0 * v0 - 4.0 * v1 - 0.5 * (3.0 * a0 - a1);
            let c4 = -15.0 * d + 8.0 * v0 + 7.0 * v1 + 0.5 * (3.0 * a0 - 2.0 * a1);
            let c5 = 6.0 * d - 3.0 * v0 - 3.0 * v1 - 0.5 * (a0 - a1);
            q[j] = p0 + s * (v0 + s * (0.5 * a0 + s * (c3 + s * (c4 + s * c5))));
            let dq = v0 + s * (a0 + s * (3.0 * c3 + s * (4.0 * c4 + s * 5.0 * c5)));
            let ddq = a0 + s * (6.0 * c3 + s * (12.0 * c4 + s * 20.0 * c5));
            qd[j] = dq / h;
            qdd[j] = ddq / (h * h);
        }
    }
}
