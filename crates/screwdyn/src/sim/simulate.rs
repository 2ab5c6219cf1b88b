//! The dynamic simulator: forward dynamics (ABA by default, or CRBA, or
//! Walker–Orin) integrated in time, under a controller, joint effects and disturbances.

use super::controller::Controller;
use super::effects::{EffectGains, JointEffects};
use super::integrate::{all_finite, non_finite_flag, Stepper};
use super::limit_events::LimitWatch;
use super::options::SimOptions;
use super::record::{Recording, Sample, SampleSink};
use crate::dynamics::energy::{kinetic_energy_given_twists, potential_energy_given_poses};
use crate::dynamics::{
    forward_dynamics, forward_dynamics_for_stepper, ExternalWrenches, ForwardMethod,
};
use crate::error::{Error, Result};
use crate::kinematics::{forward_velocity, frame_pose};
use crate::model::{first_non_finite, Model};
use crate::spatial::{Se3, Wrench};
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

/// The plant: controller + effects + disturbances → applied torque → forward dynamics.
struct Plant<'a> {
    model: &'a Model,
    ws: Workspace,
    controller: &'a mut dyn Controller,
    disturbances: &'a [Disturbance],
    fext: ExternalWrenches,
    /// The controller's torque, when joint effects change it before it is applied.
    cmd: Vec<f64>,
    /// The applied torque of the last evaluation.
    tau: Vec<f64>,
    method: ForwardMethod,
    effects: JointEffects,
    /// Every joint effect is off: the controller writes the applied torque into `tau` itself.
    commanded_only: bool,
    /// The controller is [`Controller::is_zero`]: its torque, all zeros, is in `cmd` and `tau`
    /// from the start and it is not called.
    zero_controller: bool,
    gains: EffectGains,
    /// The recorder's evaluation `(t, q, q̇) ↦ q̈` (its `τ` is still in `tau`): a sample is
    /// recorded at the state the next step starts from, so the integrator's first stage there
    /// takes it instead of repeating the forward dynamics.
    recorded: RecordedEvaluation,
}

/// The inputs and result of the recorder's last evaluation, and whether the next call of
/// [`Plant::accel`] (the first stage of the next step) may still take it.
struct RecordedEvaluation {
    pending: bool,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    qdd: Vec<f64>,
}

impl RecordedEvaluation {
    fn new(n: usize) -> Self {
        RecordedEvaluation {
            pending: false,
            t: f64::NAN,
            q: vec![0.0; n],
            v: vec![0.0; n],
            qdd: vec![0.0; n],
        }
    }
}

impl Plant<'_> {
    /// The energy stored in the joint springs, `Σ ½ k_i (q_i − q_spring,i)²`, when they act
    /// (MuJoCo counts it in its potential energy too): with undamped springs the recorded total
    /// energy is conserved.
    fn spring_energy(&self, q: &[f64]) -> f64 {
        if !self.effects.springs {
            return 0.0;
        }
        self.model
            .joints()
            .iter()
            .zip(q)
            .map(|(j, qi)| 0.5 * j.stiffness * (qi - j.springref).powi(2))
            .sum()
    }

    /// `q̈ = FD(q, q̇, τ(t, q, q̇))`, the state equation the integrator steps. The first call
    /// after [`Plant::accel_for_sample`], when it has the same `(t, q, q̇)` (the first stage of
    /// the step that starts at the sample), returns the recorder's result: the controller, a
    /// function of the state, is not asked twice. Every other call evaluates, with nothing to
    /// compare or copy.
    ///
    /// `checked` says that the stepper has checked `(q, q̇)` finite (RK4's stage states): then
    /// forward kinematics does not check `q` again. Unchecked states go through the checks of
    /// [`forward_dynamics`], which report a non-finite `q` as they always have.
    #[inline]
    fn accel(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        qdd: &mut [f64],
        checked: bool,
    ) -> Result<()> {
        let r = &mut self.recorded;
        if r.pending {
            r.pending = false;
            if r.t == t && r.q == q && r.v == v {
                qdd.copy_from_slice(&r.qdd);
                return Ok(());
            }
        }
        self.evaluate(t, q, v, qdd, checked)
    }

    /// [`Plant::accel`] for a recorded sample, kept for the next step's first stage.
    fn accel_for_sample(&mut self, t: f64, q: &[f64], v: &[f64], qdd: &mut [f64]) -> Result<()> {
        self.accel(t, q, v, qdd, false)?;
        let r = &mut self.recorded;
        r.pending = true;
        r.t = t;
        r.q.copy_from_slice(q);
        r.v.copy_from_slice(v);
        r.qdd.copy_from_slice(qdd);
        Ok(())
    }

    fn evaluate(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        qdd: &mut [f64],
        checked: bool,
    ) -> Result<()> {
        if !self.zero_controller {
            let torque = if self.commanded_only {
                &mut self.tau
            } else {
                &mut self.cmd
            };
            self.controller.torque(t, q, v, torque)?;
            if let Some(i) = first_non_finite(torque) {
                let x = torque[i];
                return Err(Error::Numerical(format!(
                    "the controller returned a non-finite torque {x} for joint '{}' at t = {t:.6} s",
                    self.model.joints()[i].name
                )));
            }
        }
        if !self.commanded_only {
            if self.effects.position_limits && EffectGains::any_in_stop(self.model, q) {
                self.gains.refresh_stops(self.model, &mut self.ws, q)?;
            }
            self.effects
                .apply(self.model, &self.gains, q, v, &self.cmd, &mut self.tau)?;
        }
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
        let a = if self.commanded_only {
            // The torque is the controller's, checked above, and the stepper only hands over
            // states it has checked (`q` too when `checked`): ABA need not check them again.
            forward_dynamics_for_stepper(
                self.model,
                &mut self.ws,
                (q, checked),
                v,
                &self.tau,
                fext,
                self.method,
            )?
        } else {
            forward_dynamics(self.model, &mut self.ws, q, v, &self.tau, fext, self.method)?
        };
        // q̈ copied into the stage's buffer and checked finite in one loop.
        let mut flags = 0;
        for (out, &x) in qdd.iter_mut().zip(a.as_slice()) {
            *out = x;
            flags |= non_finite_flag(x);
        }
        if let Some(i) = (!all_finite(flags))
            .then(|| first_non_finite(qdd))
            .flatten()
        {
            let cause = if self.effects.total_torque_is_commanded() {
                "a fixed step too large for the robot's fastest motion, or a controller with \
                 gains too high for the step, does this"
            } else {
                "a fixed step too large for stiff joint effects — limit stops, damping, \
                 stiff springs or smoothed Coulomb friction on a light link — does this"
            };
            return Err(Error::Numerical(format!(
                "the acceleration of joint '{}' became non-finite at t = {t:.6} s: the \
                 simulation diverged ({cause}; try a smaller step or the adaptive \
                 Dormand–Prince integrator)",
                self.model.joints()[i].name
            )));
        }
        Ok(())
    }
}

/// Simulates `model` from `(q0, v0)` for `opts.duration` seconds under `controller` and
/// `disturbances`, and returns the whole run in memory (see [`simulate_into`] to stream the
/// samples instead); `progress` is called with the completed fraction (0…1) now and then.
///
/// # Errors
/// As [`simulate_into`].
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
    let mut rec = Recording::default();
    simulate_into(
        model,
        q0,
        v0,
        controller,
        disturbances,
        opts,
        &mut rec,
        progress,
    )?;
    Ok(rec)
}

/// What a run did: the number of integration steps, of recorded samples, and the final time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunSummary {
    /// Integration steps taken (the last one may be shorter than `dt`).
    pub steps: usize,
    /// Samples sent to the sink.
    pub samples: usize,
    /// The time reached (s): `duration` exactly.
    pub end_time: f64,
    /// Events sent to the sink's [`SampleSink::event`]: joints that start outside their
    /// limits, and contacts with a limit stop.
    pub limit_events: usize,
}

/// The step times of a run of `duration` seconds with step `dt`: `ceil(duration / dt)` steps,
/// all of length `dt` but the last, which ends exactly at `duration`.
///
/// ```
/// let (n, last) = screwdyn::sim::step_plan(1.0, 0.3);
/// assert_eq!(n, 4);
/// assert!((last - 0.1).abs() < 1e-12);
/// assert_eq!(screwdyn::sim::step_plan(1.0, 5.0), (1, 1.0));
/// assert_eq!(screwdyn::sim::step_plan(0.0, 1e-3), (0, 0.0));
/// ```
pub fn step_plan(duration: f64, dt: f64) -> (usize, f64) {
    if duration <= 0.0 {
        return (0, 0.0);
    }
    let ratio = duration / dt;
    // A ratio within round-off of an integer takes that many full steps.
    let n = (ratio - 1e-9 * ratio.max(1.0)).ceil().max(1.0) as usize;
    (n, duration - (n - 1) as f64 * dt)
}

/// Simulates `model` and sends each recorded sample to `sink` as soon as it is
/// recorded, so a run of any length needs constant memory: the state at `t = 0`, then every
/// `opts.record_every` steps and at the end. The run ends exactly at `opts.duration` (a last,
/// shorter step where `dt` does not divide it, see [`step_plan`]). When the run fails part-way
/// (divergence, a sink that cannot write), every sample before the failure has already reached
/// the sink.
///
/// # Errors
/// [`Error::DimensionMismatch`]/[`Error::NonFinite`] for bad `q0`, `v0`;
/// [`Error::InvalidArgument`] for options that break [`SimOptions::validate`], a bad
/// disturbance body or time; [`Error::Numerical`] when the run diverges; any error of the
/// controller or the sink.
///
/// ```
/// use screwdyn::sim::{simulate_into, CsvSampleWriter, SimOptions, ZeroTorque};
/// let m = screwdyn::builtin::pendulum();
/// let opts = SimOptions { duration: 0.25, dt: 0.1, ..Default::default() };
/// let mut csv = CsvSampleWriter::new(Vec::new());
/// let run = simulate_into(&m, &[0.1], &[0.0], &mut ZeroTorque, &[], &opts, &mut csv, &mut |_| {}).unwrap();
/// assert_eq!((run.steps, run.samples, run.end_time), (3, 4, 0.25));
/// let text = String::from_utf8(csv.into_inner()).unwrap();
/// assert!(text.lines().last().unwrap().starts_with("0.25,"));
/// ```
#[allow(clippy::too_many_arguments)]
pub fn simulate_into(
    model: &Model,
    q0: &[f64],
    v0: &[f64],
    controller: &mut dyn Controller,
    disturbances: &[Disturbance],
    opts: &SimOptions,
    sink: &mut dyn SampleSink,
    progress: &mut dyn FnMut(f64),
) -> Result<RunSummary> {
    check_inputs(model, q0, v0, disturbances, opts)?;
    let n = model.nq();
    let zero_controller = controller.is_zero();
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
        commanded_only: opts.effects.total_torque_is_commanded(),
        zero_controller,
        gains: EffectGains::new(&opts.effects, model, q0, opts.dt)?,
        recorded: RecordedEvaluation::new(n),
    };
    let mut stepper = Stepper::new(opts.integrator, n)?;
    let mut recorder = Recorder::new(model, &opts.frames)?;
    let joints: Vec<String> = model.joint_names().into_iter().map(String::from).collect();
    sink.begin(&joints, &recorder.frame_names)?;
    let (mut q, mut v, mut a) = (q0.to_vec(), v0.to_vec(), vec![0.0; n]);
    // The state before the step, for the limit watch's crossing times.
    let (mut q_before, mut v_before) = (q0.to_vec(), v0.to_vec());
    let watching = opts.effects.position_limits;
    let mut watch = LimitWatch::new(model, watching);
    let mut limit_events = watch.start(model, q0, v0, &mut |e| sink.event(e))?;
    let (steps, last_dt) = step_plan(opts.duration, opts.dt);
    let every = opts.record_every;
    recorder.record(0.0, &q, &v, &mut plant, &mut a, sink)?;
    let report = (steps / 200).max(1);
    // Countdowns instead of `k % every` and `k % report`: two integer divisions a step.
    let (mut to_record, mut to_report) = (every, 1);
    let mut t = 0.0;
    // Whether `(q, q̇)` is known finite: `(q0, v0)` was checked, later states by the stepper.
    let mut state_checked = true;
    for k in 0..steps {
        let h = if k + 1 == steps { last_dt } else { opts.dt };
        if watching {
            q_before.copy_from_slice(&q);
            v_before.copy_from_slice(&v);
        }
        state_checked = stepper.advance_checked(
            &mut |t, q, v, qdd, checked| plant.accel(t, q, v, qdd, checked),
            t,
            h,
            (&mut q, &mut v),
            state_checked,
        )?;
        if watching {
            limit_events += watch.step(model, t, h, (&q_before, &v_before), &q, &mut |e| {
                sink.event(e)
            })?;
        }
        t = if k + 1 == steps {
            opts.duration
        } else {
            (k + 1) as f64 * opts.dt
        };
        to_record -= 1;
        if to_record == 0 || k + 1 == steps {
            recorder.record(t, &q, &v, &mut plant, &mut a, sink)?;
            to_record = every;
        }
        to_report -= 1;
        if to_report == 0 {
            progress(k as f64 / steps as f64);
            to_report = report;
        }
    }
    progress(1.0);
    Ok(RunSummary {
        steps,
        samples: recorder.samples,
        end_time: t,
        limit_events,
    })
}

/// The checks [`simulate_into`] makes before it starts.
fn check_inputs(
    model: &Model,
    q0: &[f64],
    v0: &[f64],
    disturbances: &[Disturbance],
    opts: &SimOptions,
) -> Result<()> {
    opts.validate(model)?;
    model.check_vector(q0, "q0")?;
    model.check_vector(v0, "v0")?;
    for d in disturbances {
        model.check_body(d.body)?;
        crate::model::check_finite(d.wrench.as_slice(), "a disturbance wrench")?;
        if d.start.is_nan() || d.end.is_nan() {
            return Err(Error::InvalidArgument(
                "a disturbance has a NaN start or end time".into(),
            ));
        }
    }
    Ok(())
}

/// Turns the state at a sample time into a [`Sample`]: `q̈` and `τ` from the plant, the
/// energies and the recorded frames' poses from one kinematic pass.
struct Recorder<'m> {
    model: &'m Model,
    ws: Workspace,
    frames: Vec<usize>,
    frame_names: Vec<String>,
    poses: Vec<Se3>,
    samples: usize,
}

impl<'m> Recorder<'m> {
    fn new(model: &'m Model, frames: &[usize]) -> Result<Self> {
        let frame_names = frames
            .iter()
            .map(|&f| Ok(model.frame(f)?.name.clone()))
            .collect::<Result<Vec<_>>>()?;
        Ok(Recorder {
            model,
            ws: Workspace::new(model),
            frames: frames.to_vec(),
            frame_names,
            poses: vec![Se3::identity(); frames.len()],
            samples: 0,
        })
    }

    fn record(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        plant: &mut Plant,
        a: &mut [f64],
        sink: &mut dyn SampleSink,
    ) -> Result<()> {
        plant.accel_for_sample(t, q, v, a)?;
        forward_velocity(self.model, &mut self.ws, q, v)?;
        for (p, &f) in self.poses.iter_mut().zip(&self.frames) {
            *p = frame_pose(self.model, &self.ws, f)?;
        }
        sink.push(&Sample {
            t,
            q,
            v,
            a,
            tau: &plant.tau,
            kinetic_energy: kinetic_energy_given_twists(self.model, &self.ws, v),
            potential_energy: potential_energy_given_poses(self.model, &self.ws)
                + plant.spring_energy(q),
            poses: &self.poses,
        })?;
        self.samples += 1;
        Ok(())
    }
}
