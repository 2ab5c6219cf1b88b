//! Exciting trajectories (finite Fourier series) and the logs an identification experiment
//! along one would record.

use super::parameters::sign;
use super::random::{joint_range, SplitMix};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;

/// A finite Fourier series per joint, the exciting trajectory of Swevers et al. (1997):
/// `q_i(t) = q0_i + Σ_{l=1}^{L} (a_il / (l ω_f)) sin(l ω_f t) − (b_il / (l ω_f)) cos(l ω_f t)`,
/// periodic with period `2π/ω_f`, with `q̇` and `q̈` in closed form.
#[derive(Clone, Debug)]
pub struct FourierTrajectory {
    /// `ω_f` (rad/s).
    pub base_frequency: f64,
    /// `q0_i`.
    pub offset: Vec<f64>,
    /// `a_il`, joint-major (`L` per joint).
    pub sine: Vec<Vec<f64>>,
    /// `b_il`.
    pub cosine: Vec<Vec<f64>>,
}

impl FourierTrajectory {
    /// A random exciting trajectory for `model`: `harmonics` terms per joint at base frequency
    /// `base_frequency` (rad/s), coefficients drawn uniformly from `seed`, then scaled per joint
    /// so that the motion stays within 80 % of the joint's range (limits clamped to ±π) around
    /// its middle and within 80 % of its velocity limit when it has one.
    ///
    /// # Errors
    /// `InvalidArgument` for zero harmonics or a non-positive or non-finite frequency.
    ///
    /// ```
    /// use screwdyn::identification::FourierTrajectory;
    /// let m = screwdyn::builtin::planar2();
    /// let f = FourierTrajectory::random(&m, 5, 0.6, 3).unwrap();
    /// let (q, v, a) = f.sample(1.0);
    /// let (q2, _, _) = f.sample(1.0 + 2.0 * std::f64::consts::PI / 0.6);
    /// assert!((q[0] - q2[0]).abs() < 1e-9 && v.len() == 2 && a.len() == 2);
    /// ```
    pub fn random(model: &Model, harmonics: usize, base_frequency: f64, seed: u64) -> Result<Self> {
        if harmonics == 0 {
            return Err(Error::InvalidArgument(
                "an exciting trajectory needs at least one harmonic".into(),
            ));
        }
        if !(base_frequency > 0.0 && base_frequency.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "the base frequency must be positive and finite, not {base_frequency}"
            )));
        }
        let mut rng = SplitMix::new(seed.wrapping_mul(0x2545_F491_4F6C_DD1D) ^ 0xF0_0F);
        let n = model.nv();
        let mut f = FourierTrajectory {
            base_frequency,
            offset: vec![0.0; n],
            sine: vec![vec![0.0; harmonics]; n],
            cosine: vec![vec![0.0; harmonics]; n],
        };
        for i in 0..n {
            let (lo, hi) = joint_range(model, i);
            let amp_limit = 0.4 * (hi - lo);
            f.offset[i] = 0.5 * (lo + hi);
            for l in 0..harmonics {
                f.sine[i][l] = rng.uniform(-1.0, 1.0);
                f.cosine[i][l] = rng.uniform(-1.0, 1.0);
            }
            // Bounds of |q − q0| and |q̇| over all t from the coefficients.
            let (mut qb, mut vb) = (0.0, 0.0);
            for l in 0..harmonics {
                let w = (l + 1) as f64 * base_frequency;
                let c = f.sine[i][l].hypot(f.cosine[i][l]);
                qb += c / w;
                vb += c;
            }
            let mut s = amp_limit / qb;
            let vlim = model.joints()[i].limits.velocity;
            if vlim.is_finite() && vlim > 0.0 {
                s = s.min(0.8 * vlim / vb);
            }
            for l in 0..harmonics {
                f.sine[i][l] *= s;
                f.cosine[i][l] *= s;
            }
        }
        Ok(f)
    }

    /// `(q, q̇, q̈)` at time `t`.
    pub fn sample(&self, t: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = self.offset.len();
        let (mut q, mut v, mut a) = (self.offset.clone(), vec![0.0; n], vec![0.0; n]);
        for i in 0..n {
            for (l, (&sa, &cb)) in self.sine[i].iter().zip(&self.cosine[i]).enumerate() {
                let w = (l + 1) as f64 * self.base_frequency;
                let (s, c) = (w * t).sin_cos();
                q[i] += sa / w * s - cb / w * c;
                v[i] += sa * c + cb * s;
                a[i] += -sa * w * s + cb * w * c;
            }
        }
        (q, v, a)
    }

    /// The period `2π / ω_f` (s).
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.base_frequency
    }
}

/// The joint torques a log of `model` would record at `(q, q̇, q̈)`: inverse dynamics plus the
/// joints' viscous and Coulomb friction, `τ = RNEA(q, q̇, q̈) + fv q̇ + fc sign(q̇)`. Written into
/// `tau`.
///
/// # Errors
/// As [`rnea`](crate::dynamics::rnea).
fn logged_torque(
    model: &Model,
    ws: &mut Workspace,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    tau: &mut [f64],
) -> Result<()> {
    let t = crate::dynamics::rnea(model, ws, q, v, a)?;
    for (i, j) in model.joints().iter().enumerate() {
        tau[i] = t[i] + j.damping * v[i] + j.friction * sign(v[i]);
    }
    Ok(())
}

/// Samples `traj` every `1 / rate` seconds over `[0, duration]` and calls `sink(t, q, q̇, q̈, τ)`
/// with the torques the robot would need (inverse dynamics plus the joints' viscous and
/// Coulomb friction, `τ = RNEA(q, q̇, q̈) + fv q̇ + fc sign(q̇)`) plus Gaussian noise of
/// standard deviation `noise` (Box–Muller from a deterministic generator seeded with `seed`):
/// the log an identification experiment along an exciting trajectory would record. Streams:
/// nothing is stored.
///
/// # Errors
/// `InvalidArgument` for a non-positive or non-finite duration or rate, or a negative noise;
/// errors of `sink` are passed on.
///
/// ```
/// use screwdyn::identification::{excitation_log, FourierTrajectory};
/// let m = screwdyn::builtin::planar2();
/// let traj = FourierTrajectory::random(&m, 3, 1.0, 7).unwrap();
/// let mut rows = 0;
/// excitation_log(&m, &traj, 1.0, 100.0, 0.0, 1, |_, _, _, _, _| {
///     rows += 1;
///     Ok::<(), screwdyn::Error>(())
/// })
/// .unwrap();
/// assert_eq!(rows, 101);
/// ```
#[allow(clippy::type_complexity)]
pub fn excitation_log<E: From<Error>>(
    model: &Model,
    traj: &FourierTrajectory,
    duration: f64,
    rate: f64,
    noise: f64,
    seed: u64,
    mut sink: impl FnMut(f64, &[f64], &[f64], &[f64], &[f64]) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    if !(duration > 0.0 && duration.is_finite() && rate > 0.0 && rate.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "the duration and the sampling rate must be positive and finite (got {duration} s \
             and {rate} Hz)"
        ))
        .into());
    }
    if !(noise >= 0.0 && noise.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "the torque noise must be a non-negative standard deviation, not {noise}"
        ))
        .into());
    }
    let mut ws = Workspace::new(model);
    let mut rng = SplitMix::new(seed ^ 0xA5A5_5A5A_1234_5678);
    let mut tau = vec![0.0; model.nv()];
    let samples = (duration * rate).floor() as usize;
    for k in 0..=samples {
        let t = k as f64 / rate;
        let (q, v, a) = traj.sample(t);
        logged_torque(model, &mut ws, &q, &v, &a, &mut tau)?;
        if noise > 0.0 {
            for x in tau.iter_mut() {
                let u1 = rng.uniform(f64::MIN_POSITIVE, 1.0);
                let u2 = rng.uniform(0.0, 1.0);
                *x += noise * (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
            }
        }
        sink(t, &q, &v, &a, &tau)?;
    }
    Ok(())
}
