//! Torque profiles: inverse dynamics along a trajectory, peak and RMS torque per joint and
//! every sample over the joint's effort limit — seed 003's question "how much torque is needed
//! to accelerate the manipulator from rest to constant velocity, and then back to stop?".

use super::record::Recording;
use super::trajectory::Trajectory;
use crate::dynamics::{inverse_dynamics, kinetic_energy, potential_energy};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;

/// One sample over an effort limit.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// Joint index.
    pub joint: usize,
    /// Time (s).
    pub t: f64,
    /// The required torque.
    pub tau: f64,
    /// The joint's effort limit.
    pub limit: f64,
}

/// The result of [`torque_profile`].
#[derive(Clone, Debug, PartialEq)]
pub struct TorqueProfile {
    /// The sampled motion and the required torques (`tau`), energies included.
    pub samples: Recording,
    /// `max |τ_i|` per joint.
    pub peak: Vec<f64>,
    /// `√(mean τ_i²)` per joint.
    pub rms: Vec<f64>,
    /// Effort limit per joint (∞ if none).
    pub effort_limit: Vec<f64>,
    /// Every sample whose `|τ_i|` exceeds the limit.
    pub violations: Vec<Violation>,
}

/// Inverse dynamics (RNEA with gravity) at every `dt` along `trajectory`, end included.
///
/// ```
/// use screwdyn::sim::{torque_profile, Trapezoid};
/// let m = screwdyn::builtin::planar2();
/// let traj = Trapezoid::new(&[0.0, 0.0], &[1.0, 0.5], &[1.0, 1.0], &[2.0, 2.0], true).unwrap();
/// let p = torque_profile(&m, &traj, 0.01).unwrap();
/// assert!(p.peak[0] >= p.rms[0] && p.violations.is_empty());
/// ```
pub fn torque_profile(
    model: &Model,
    trajectory: &dyn Trajectory,
    dt: f64,
) -> Result<TorqueProfile> {
    if trajectory.nq() != model.nq() {
        return Err(Error::InvalidModel(format!(
            "the trajectory has {} joints, the model has {}",
            trajectory.nq(),
            model.nq()
        )));
    }
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(Error::InvalidModel(format!(
            "the sampling step must be positive (got {dt})"
        )));
    }
    let n = model.nq();
    let mut ws = Workspace::new(model);
    let (mut q, mut v, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut rec = Recording::new(
        model.joint_names().into_iter().map(String::from).collect(),
        vec![],
    );
    let steps = (trajectory.duration() / dt).ceil() as usize;
    let effort_limit: Vec<f64> = model.joints().iter().map(|j| j.limits.effort).collect();
    let (mut peak, mut sumsq) = (vec![0.0_f64; n], vec![0.0; n]);
    let mut violations = Vec::new();
    for k in 0..=steps {
        let t = (k as f64 * dt).min(trajectory.duration());
        trajectory.sample(t, &mut q, &mut v, &mut a);
        let tau = inverse_dynamics(model, &mut ws, &q, &v, &a, None)?
            .as_slice()
            .to_vec();
        for i in 0..n {
            peak[i] = peak[i].max(tau[i].abs());
            sumsq[i] += tau[i] * tau[i];
            if tau[i].abs() > effort_limit[i] {
                violations.push(Violation {
                    joint: i,
                    t,
                    tau: tau[i],
                    limit: effort_limit[i],
                });
            }
        }
        let ke = kinetic_energy(model, &mut ws, &q, &v)?;
        let pe = potential_energy(model, &mut ws, &q)?;
        rec.push(t, &q, &v, &a, &tau, (ke, pe), vec![]);
    }
    let count = (steps + 1) as f64;
    Ok(TorqueProfile {
        samples: rec,
        peak,
        rms: sumsq.iter().map(|s| (s / count).sqrt()).collect(),
        effort_limit,
        violations,
    })
}
