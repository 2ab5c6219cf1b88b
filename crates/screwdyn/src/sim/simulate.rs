//! The dynamic simulator of seed 004 §6.4: forward dynamics (ABA by default, or CRBA, or
//! Walker–Orin) integrated in time, under a controller, joint effects and disturbances.

use super::controller::Controller;
use super::effects::{EffectGains, JointEffects};
use super::integrate::{Integrator, Stepper};
use super::record::Recording;
use crate::dynamics::energy::{kinetic_energy_given_twists, potential_energy_given_poses};
use crate::dynamics::{forward_dynamics_with, ExternalWrenches, ForwardMethod};
use crate::error::{Error, Result};
use crate::kinematics::{forward_velocity, frame_pose};
use crate::model::Model;
use crate::spatial::Wrench;
use crate::workspace::Workspace;

/// An external wrench on a body during `[start, end)` (seconds), in the body frame or the
/// world frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Disturbance {
    /// The body it acts on.
    pub body: usize,
    /// `W = (m, f)` acting on the body.
    pub wrench: Wrench,
    /// Whether `wrench` is written in the world frame (else in the body frame).
    pub in_world: bool,
    /// Start time (s).
    pub start: f64,
    /// End time (s).
    pub end: f64,
}

/// How to simulate.
#[derive(Clone, Debug, PartialEq)]
pub struct SimOptions {
    /// Simulated time (s).
    pub duration: f64,
    /// Step (s): the fixed step of Euler and RK4, the output interval of Dormand–Prince.
    pub dt: f64,
    /// Integration scheme.
    pub integrator: Integrator,
    /// Forward-dynamics algorithm.
    pub method: ForwardMethod,
    /// Joint effects.
    pub effects: JointEffects,
    /// Record every k-th step (1 = every step).
    pub record_every: usize,
    /// Frames whose poses are recorded.
    pub frames: Vec<usize>,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            duration: 1.0,
            dt: 1e-3,
            integrator: Integrator::Rk4,
            method: ForwardMethod::Aba,
            effects: JointEffects::default(),
            record_every: 1,
            frames: Vec::new(),
        }
    }
}

/// The plant: controller + effects + disturbances → applied torque → forward dynamics.
struct Plant<'a> {
    model: &'a Model,
    ws: Workspace,
    controller: &'a mut dyn Controller,
    disturbances: &'a [Disturbance],
    fext: ExternalWrenches,
    cmd: Vec<f64>,
    tau: Vec<f64>,
    method: ForwardMethod,
    effects: JointEffects,
    gains: EffectGains,
}

impl Plant<'_> {
    fn accel(&mut self, t: f64, q: &[f64], v: &[f64], qdd: &mut [f64]) -> Result<()> {
        self.controller.torque(t, q, v, &mut self.cmd)?;
        if let Some((i, x)) = self.cmd.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(Error::Numerical(format!(
                "the controller returned a non-finite torque {x} for joint '{}' at t = {t:.6} s",
                self.model.joints()[i].name
            )));
        }
        self.effects
            .apply(self.model, &self.gains, q, v, &self.cmd, &mut self.tau);
        let active = |d: &&Disturbance| t >= d.start && t < d.end;
        let fext = if self.disturbances.iter().any(|d| active(&d)) {
            self.fext.clear();
            for d in self.disturbances.iter().filter(active) {
                if d.in_world {
                    self.fext.add_world(d.body, d.wrench)?;
                } else {
                    self.fext.add_local(d.body, d.wrench)?;
                }
            }
            Some(&self.fext)
        } else {
            None
        };
        let a =
            forward_dynamics_with(self.model, &mut self.ws, q, v, &self.tau, fext, self.method)?;
        qdd.copy_from_slice(a.as_slice());
        if let Some(i) = qdd.iter().position(|x| !x.is_finite()) {
            return Err(Error::Numerical(format!(
                "the acceleration of joint '{}' became non-finite at t = {t:.6} s: the \
                 simulation diverged (a fixed step too large for stiff joint effects — limit \
                 stops, damping or smoothed Coulomb friction on a light link — does this; try a \
                 smaller step or the adaptive Dormand–Prince integrator)",
                self.model.joints()[i].name
            )));
        }
        Ok(())
    }
}

/// Simulates `model` from `(q0, v0)` for `opts.duration` seconds under `controller` and
/// `disturbances`; `progress` is called with the completed fraction (0…1) now and then.
///
/// ```
/// use screwdyn::sim::{simulate, SimOptions, ZeroTorque};
/// // The pendulum released at rest from 0.1 rad swings through zero.
/// let m = screwdyn::builtin::pendulum();
/// // A quarter period is π/2 · √(l/g) ≈ 0.50 s.
/// let opts = SimOptions { duration: 0.6, dt: 1e-3, ..Default::default() };
/// let run = simulate(&m, &[0.1], &[0.0], &mut ZeroTorque, &[], &opts, &mut |_| {}).unwrap();
/// assert!(run.q.last().unwrap()[0] < 0.0);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn simulate(
    model: &Model,
    q0: &[f64],
    v0: &[f64],
    controller: &mut dyn Controller,
    disturbances: &[Disturbance],
    opts: &SimOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<Recording> {
    model.check_vector(q0, "q0")?;
    model.check_vector(v0, "v0")?;
    let valid =
        opts.dt > 0.0 && opts.dt.is_finite() && opts.duration >= 0.0 && opts.duration.is_finite();
    if !valid {
        return Err(Error::InvalidModel(format!(
            "the step must be positive and the duration non-negative (got dt = {}, duration = {})",
            opts.dt, opts.duration
        )));
    }
    for d in disturbances {
        if d.body >= model.nbodies() {
            return Err(Error::InvalidModel(format!(
                "a disturbance names body {} of {}",
                d.body,
                model.nbodies()
            )));
        }
    }
    let n = model.nq();
    let mut plant = Plant {
        model,
        ws: Workspace::new(model),
        controller,
        disturbances,
        fext: ExternalWrenches::new(model),
        cmd: vec![0.0; n],
        tau: vec![0.0; n],
        method: opts.method,
        effects: opts.effects,
        gains: EffectGains::new(&opts.effects, model, q0, opts.dt)?,
    };
    let mut stepper = Stepper::new(opts.integrator, n);
    let mut rec_ws = Workspace::new(model);
    let joints = model.joint_names().into_iter().map(String::from).collect();
    let frames = opts
        .frames
        .iter()
        .map(|&f| model.frames()[f].name.clone())
        .collect();
    let mut rec = Recording::new(joints, frames);
    let (mut q, mut v, mut a) = (q0.to_vec(), v0.to_vec(), vec![0.0; n]);
    let steps = (opts.duration / opts.dt).round() as usize;
    let every = opts.record_every.max(1);
    let mut record = |t: f64,
                      q: &[f64],
                      v: &[f64],
                      plant: &mut Plant,
                      a: &mut [f64],
                      rec: &mut Recording|
     -> Result<()> {
        plant.accel(t, q, v, a)?;
        // One kinematic pass gives the energies and the frame poses.
        forward_velocity(model, &mut rec_ws, q, v)?;
        let ke = kinetic_energy_given_twists(model, &rec_ws);
        let pe = potential_energy_given_poses(model, &rec_ws);
        let poses = opts
            .frames
            .iter()
            .map(|&f| frame_pose(model, &rec_ws, f))
            .collect();
        rec.push(t, q, v, a, &plant.tau, (ke, pe), poses);
        Ok(())
    };
    record(0.0, &q, &v, &mut plant, &mut a, &mut rec)?;
    let report = (steps / 200).max(1);
    for k in 0..steps {
        let t = k as f64 * opts.dt;
        stepper.advance(
            &mut |t, q, v, qdd| plant.accel(t, q, v, qdd),
            t,
            opts.dt,
            &mut q,
            &mut v,
        )?;
        if (k + 1) % every == 0 || k + 1 == steps {
            record(
                (k + 1) as f64 * opts.dt,
                &q,
                &v,
                &mut plant,
                &mut a,
                &mut rec,
            )?;
        }
        if k % report == 0 {
            progress(k as f64 / steps as f64);
        }
    }
    progress(1.0);
    Ok(rec)
}
