//! `simulate`: a run over time, streamed as CSV/JSON (docs/cli.md) and plotted.

use super::inputs::{load, names, parse_numbers, parse_per_joint, parse_vector, parse_wrench};
use super::joint_csv::{read_joint_rows, read_motion, Columns};
use super::run_files::{
    in_flag_words, joint_series, plot_kind, refuse_onto_inputs, run_file_kind, scalar_series,
    RunWriter,
};
use crate::args::{ControllerArg, Format, SimulateArgs};
use crate::output::{fmt, resolve, table, Report, Value};
use crate::plot::{plot_panels, Panel};
use crate::write::OutputFile;
use crate::CliError;
use screwdyn::dynamics::ForwardMethod;
use screwdyn::motion::SampledTrajectory;
use screwdyn::sim::{
    self, Controller, ControllerSpec, Disturbance, Integrator, JointEffects, LimitEvent, Quintic,
    Recording, Sample, SampleSink, SimOptions,
};
use screwdyn::Model;
use std::io::IsTerminal;
use std::path::Path;

/// Where a run's samples go as they are recorded: a CSV or JSON file (or stdout), a bounded
/// copy for the plot, and the first and last samples for the summary.
struct RunSinks {
    file: Option<RunWriter>,
    plot: Option<Decimated>,
    first: Option<Recording>,
    last: Recording,
    joints: Vec<String>,
    /// The first [`MAX_EVENT_LINES`] events at the limits, for stderr and the summary, and
    /// how many there were in all.
    events: Vec<LimitEvent>,
    event_count: usize,
}

/// Events at the limits printed on stderr (the rest are counted).
const MAX_EVENT_LINES: usize = 20;

/// At most `2 · MAX_PLOT_SAMPLES` samples of a run for its plot: every `stride`-th sample,
/// the stride doubling (and every other kept sample dropped) whenever the buffer is full.
struct Decimated {
    rec: Recording,
    stride: usize,
    seen: usize,
}

const MAX_PLOT_SAMPLES: usize = 5000;

impl Decimated {
    fn push(&mut self, s: &Sample) -> screwdyn::Result<()> {
        if self.seen % self.stride == 0 {
            self.rec.push(s)?;
            if self.rec.len() >= 2 * MAX_PLOT_SAMPLES {
                let old = std::mem::take(&mut self.rec);
                self.rec = Recording::new(old.joints.clone(), old.frames.clone());
                for k in (0..old.len()).step_by(2) {
                    self.rec.push(&old.sample(k)?)?;
                }
                self.stride *= 2;
            }
        }
        self.seen += 1;
        Ok(())
    }
}

impl SampleSink for RunSinks {
    fn begin(&mut self, joints: &[String], frames: &[String]) -> screwdyn::Result<()> {
        self.joints = joints.to_vec();
        if let Some(w) = &mut self.file {
            w.sink().begin(joints, frames)?;
        }
        if let Some(p) = &mut self.plot {
            p.rec.begin(joints, frames)?;
        }
        self.last.begin(joints, frames)
    }
    fn push(&mut self, s: &Sample) -> screwdyn::Result<()> {
        if let Some(w) = &mut self.file {
            w.sink().push(s)?;
        }
        if let Some(p) = &mut self.plot {
            p.push(s)?;
        }
        if self.first.is_none() {
            let mut first = Recording::default();
            first.begin(&self.joints, &[])?;
            first.push(&Sample { poses: &[], ..*s })?;
            self.first = Some(first);
        }
        keep_only(&mut self.last, &self.joints, s)
    }
    fn event(&mut self, e: &LimitEvent) -> screwdyn::Result<()> {
        if let Some(w) = &mut self.file {
            w.sink().event(e)?;
        }
        if self.events.len() < MAX_EVENT_LINES {
            self.events.push(e.clone());
        }
        self.event_count += 1;
        Ok(())
    }
}

/// Makes `s` (without poses) the one sample of `rec`: after the first sample its vectors are
/// overwritten in place, so a run recorded every step allocates nothing per sample here.
fn keep_only(rec: &mut Recording, joints: &[String], s: &Sample) -> screwdyn::Result<()> {
    let n = joints.len();
    let fits = |x: &[Vec<f64>], y: &[f64]| x.len() == 1 && x[0].len() == n && y.len() == n;
    let reusable = rec.len() == 1
        && rec.frames.is_empty()
        && fits(&rec.q, s.q)
        && fits(&rec.v, s.v)
        && fits(&rec.a, s.a)
        && fits(&rec.tau, s.tau);
    if !reusable {
        *rec = Recording::new(joints.to_vec(), vec![]);
        return rec.push(&Sample { poses: &[], ..*s });
    }
    rec.t[0] = s.t;
    rec.q[0].copy_from_slice(s.q);
    rec.v[0].copy_from_slice(s.v);
    rec.a[0].copy_from_slice(s.a);
    rec.tau[0].copy_from_slice(s.tau);
    rec.kinetic_energy[0] = s.kinetic_energy;
    rec.potential_energy[0] = s.potential_energy;
    rec.total_energy[0] = s.kinetic_energy + s.potential_energy;
    Ok(())
}

impl RunSinks {
    /// Prints the events at the limits on stderr, one line each, after the run (the progress
    /// bar is gone by then).
    fn print_events(&self, m: &Model) {
        for e in &self.events {
            eprintln!("screwdyn: warning: {}", e.message(e.unit(m)));
        }
        if self.event_count > self.events.len() {
            eprintln!(
                "screwdyn: warning: {} more contacts with the limit stops",
                self.event_count - self.events.len()
            );
        }
    }
}

/// Reads a torque series: columns `t` and `tau.<joint>` (a missing joint is zero); the times
/// are checked when the controller is built.
fn read_torque_csv(m: &Model, path: &Path) -> Result<ControllerSpec, CliError> {
    let columns = Columns {
        key: "t",
        prefix: "tau.",
        every_joint: false,
    };
    match read_joint_rows(m, path, &columns)? {
        (Some(times), values) => Ok(ControllerSpec::Series { times, values }),
        (None, _) => Err(CliError::input(format!(
            "{}: the column 't' is missing",
            path.display()
        ))),
    }
}

/// The motion of `--target-trajectory`, read from its run file.
fn target_trajectory(a: &SimulateArgs, m: &Model) -> Result<Option<SampledTrajectory>, CliError> {
    let Some(path) = &a.target_trajectory else {
        return Ok(None);
    };
    let (t, q, v, acc) = read_motion(m, path)?;
    SampledTrajectory::new(t, q, v, acc)
        .map(Some)
        .map_err(|e| CliError::input(format!("{}: {e}", path.display())))
}

/// Parses `BODY:mx,my,mz,fx,fy,fz[@world]@T0-T1`.
fn parse_disturbance(m: &Model, text: &str) -> Result<Disturbance, CliError> {
    let bad = || {
        CliError::input(format!(
            "--disturbance '{text}' must look like BODY:mx,my,mz,fx,fy,fz[@world]@T0-T1"
        ))
    };
    let (head, window) = text.rsplit_once('@').ok_or_else(bad)?;
    // The window is "t0-t1": split at a '-' that is not an exponent sign.
    let b = window.as_bytes();
    let dash = (1..b.len())
        .find(|&k| b[k] == b'-' && !matches!(b[k - 1], b'e' | b'E'))
        .ok_or_else(bad)?;
    let t = parse_numbers(
        &format!("{},{}", &window[..dash], &window[dash + 1..]),
        "--disturbance",
    )?;
    if t[1] < t[0] {
        return Err(CliError::input(format!(
            "--disturbance '{text}': the window ends before it starts"
        )));
    }
    let (body, wrench, in_world) = parse_wrench(head, "--disturbance")?;
    Ok(Disturbance {
        body: m.body_id(&body)?,
        wrench,
        in_world,
        start: t[0],
        end: t[1],
    })
}

fn unused(flag: &str, given: bool, controller: &str) -> Result<(), CliError> {
    if given {
        return Err(CliError::input(format!(
            "{flag} is not used by --controller {controller}"
        )));
    }
    Ok(())
}

/// `screwdyn simulate MODEL ...`: parse, run with the samples streamed to the output, plot,
/// summarise.
pub fn simulate(a: &SimulateArgs) -> Result<(), CliError> {
    let output_kind = a
        .output
        .as_deref()
        .map(|p| run_file_kind(p, "--output"))
        .transpose()?;
    if let Some(p) = &a.plot {
        plot_kind(p)?;
    }
    refuse_onto_inputs(
        &a.model.model,
        a.torque_csv.as_deref().or(a.target_trajectory.as_deref()),
        a.output.as_deref(),
        a.plot.as_deref(),
    )?;
    let mut m = load(&a.model, a.gravity.as_deref())?;
    if let Some(d) = &a.damping {
        let b = parse_per_joint(d, "damping", &m)?;
        let f: Vec<f64> = m.joints().iter().map(|j| j.friction).collect();
        m = m.with_joint_friction(&b, &f)?;
    }
    let opts = sim_options(a, &m)?;
    let reference = target_trajectory(a, &m)?;
    // Without --q0/--v0 a tracked motion starts where the reference does.
    let (q0, v0) = match &reference {
        Some(r) => (
            a.q0.as_ref().map_or(Ok(r.sample_at(0).0.to_vec()), |t| {
                parse_vector(Some(t), "q0", &m)
            })?,
            a.v0.as_ref().map_or(Ok(r.sample_at(0).1.to_vec()), |t| {
                parse_vector(Some(t), "v0", &m)
            })?,
        ),
        None => (
            parse_vector(a.q0.as_deref(), "q0", &m)?,
            parse_vector(a.v0.as_deref(), "v0", &m)?,
        ),
    };
    let (name, mut controller) = controller(a, &m, &q0, reference)?;
    let disturbances = a
        .disturbance
        .iter()
        .map(|d| parse_disturbance(&m, d))
        .collect::<Result<Vec<_>, _>>()?;
    let format = resolve(a.model.format);
    let (summary, sinks) = run_streamed(
        a,
        &m,
        &q0,
        &v0,
        controller.as_mut(),
        &disturbances,
        &opts,
        output_kind.unwrap_or(format),
    )?;
    if let (Some(p), Some(d)) = (&a.plot, &sinks.plot) {
        plot_run(&m, &d.rec, &name, p)?;
    }
    if a.output.is_none() && format != Format::Table {
        return Ok(());
    }
    report_run(a, &m, &summary, &sinks, format)
}

/// The integrator, method, joint effects and recorded frames of `simulate`, checked.
fn sim_options(a: &SimulateArgs, m: &Model) -> Result<SimOptions, CliError> {
    let integrator: Integrator = a
        .integrator
        .parse()
        .map_err(|e: screwdyn::Error| CliError::input(format!("--integrator: {e}")))?;
    let method: ForwardMethod = a
        .method
        .parse()
        .map_err(|e: screwdyn::Error| CliError::input(format!("--method: {e}")))?;
    let opts = SimOptions {
        duration: a.duration,
        dt: a.dt,
        integrator,
        method,
        effects: JointEffects {
            limit_time_constant: a.limit_time_constant,
            limit_damping_ratio: a.limit_damping_ratio,
            ..if a.no_effects {
                JointEffects::none()
            } else {
                JointEffects::default()
            }
        },
        record_every: a.record_every,
        frames: a
            .frames
            .iter()
            .map(|f| m.frame_id(f))
            .collect::<Result<Vec<_>, _>>()?,
    };
    opts.validate(m).map_err(in_flag_words)?;
    Ok(opts)
}

/// The controller chosen by `--controller` (and its name), with its gains and reference.
fn controller(
    a: &SimulateArgs,
    m: &Model,
    q0: &[f64],
    reference: Option<SampledTrajectory>,
) -> Result<(String, Box<dyn Controller>), CliError> {
    let target = match &a.target {
        Some(t) => parse_vector(Some(t), "target", m)?,
        None => q0.to_vec(),
    };
    let name = clap::ValueEnum::to_possible_value(&a.controller)
        .map(|v| v.get_name().to_string())
        .unwrap_or_default();
    let c = a.controller;
    if c != ControllerArg::Constant {
        unused("--tau", a.tau.is_some(), &name)?;
    }
    if !matches!(c, ControllerArg::Pd | ControllerArg::ComputedTorque) {
        unused("--target", a.target.is_some(), &name)?;
        unused("--kp", a.kp.is_some(), &name)?;
        unused("--kd", a.kd.is_some(), &name)?;
    }
    if c != ControllerArg::Series {
        unused("--torque-csv", a.torque_csv.is_some(), &name)?;
    }
    if c != ControllerArg::ComputedTorque {
        unused("--target-trajectory", reference.is_some(), &name)?;
    } else if reference.is_some() && a.target.is_some() {
        return Err(CliError::input(
            "--target and --target-trajectory are alternatives: computed torque tracks either a quintic to --target or the motion of --target-trajectory",
        ));
    }
    let gains = |text: &Option<String>, flag: &str| {
        text.as_deref()
            .map(|t| parse_per_joint(t, flag, m))
            .transpose()
    };
    let spec = match c {
        ControllerArg::Zero => ControllerSpec::Zero,
        ControllerArg::Constant => {
            let Some(t) = &a.tau else {
                return Err(CliError::input("--controller constant needs --tau"));
            };
            ControllerSpec::Constant(parse_vector(Some(t), "tau", m)?)
        }
        ControllerArg::Pd => ControllerSpec::PdGravity {
            target,
            kp: gains(&a.kp, "kp")?,
            kd: gains(&a.kd, "kd")?,
        },
        ControllerArg::ComputedTorque => {
            let reference: Box<dyn sim::Trajectory + Send> = match reference {
                Some(r) => Box::new(r),
                None => Box::new(Quintic::rest_to_rest(q0, &target, a.duration).map_err(|e| {
                    in_flag_words(e).with_suffix(
                        " (--controller computed-torque tracks a quintic from --q0 to --target over --duration)",
                    )
                })?),
            };
            ControllerSpec::ComputedTorque {
                reference,
                kp: gains(&a.kp, "kp")?,
                kd: gains(&a.kd, "kd")?,
            }
        }
        ControllerArg::Series => {
            let Some(p) = &a.torque_csv else {
                return Err(CliError::input(
                    "--controller series needs --torque-csv FILE",
                ));
            };
            read_torque_csv(m, p)?
        }
    };
    // A bad series (times not increasing) is reported against its file.
    let controller = spec.build(m).map_err(|e| match (c, &a.torque_csv) {
        (ControllerArg::Series, Some(p)) => CliError::input(format!("{}: {e}", p.display())),
        _ => e.into(),
    })?;
    Ok((name, controller))
}

/// Runs the simulation with its samples streamed to `--output` (or stdout for JSON/CSV), a
/// bounded copy kept for the plot; on a failure part-way the message says what was kept.
#[allow(clippy::too_many_arguments)]
fn run_streamed(
    a: &SimulateArgs,
    m: &Model,
    q0: &[f64],
    v0: &[f64],
    controller: &mut dyn Controller,
    disturbances: &[Disturbance],
    opts: &SimOptions,
    kind: Format,
) -> Result<(sim::RunSummary, RunSinks), CliError> {
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = indicatif::ProgressBar::new(1000);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "simulating {bar:40} {percent:>3}% {elapsed_precise} (eta {eta})",
        ) {
            b.set_style(style);
        }
        b
    });
    let mut progress = |f: f64| {
        if let Some(b) = &bar {
            b.set_position((f * 1000.0) as u64);
        }
    };
    let format = resolve(a.model.format);
    // The run file is streamed into a temporary file, renamed over --output once complete (a
    // device or FIFO is written directly).
    let target = a.output.as_deref().map(OutputFile::create).transpose()?;
    let direct = target.as_ref().is_some_and(OutputFile::is_direct);
    let file: Option<Box<dyn std::io::Write>> = match &target {
        Some(f) => Some(Box::new(f.writer()?)),
        None if format != Format::Table => {
            Some(Box::new(std::io::BufWriter::new(std::io::stdout())))
        }
        None => None,
    };
    let mut sinks = RunSinks {
        file: file.map(|out| RunWriter::new(kind, out)),
        plot: a.plot.as_ref().map(|_| Decimated {
            rec: Recording::default(),
            stride: 1,
            seen: 0,
        }),
        first: None,
        last: Recording::default(),
        joints: Vec::new(),
        events: Vec::new(),
        event_count: 0,
    };
    let result = sim::simulate_into(
        m,
        q0,
        v0,
        controller,
        disturbances,
        opts,
        &mut sinks,
        &mut progress,
    );
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    sinks.print_events(m);
    // A run that failed part-way keeps the samples written so far (complete rows); a file that
    // could not be written leaves the previous --output as it was. The reader of stdout going
    // away (`| head`) ends the command quietly.
    let written = sinks.file.take().map(|w| {
        w.finish()
            .and_then(|()| target.map_or(Ok(()), OutputFile::commit))
    });
    let unwritten = |why: &str, p: &Path| {
        let kept = if direct {
            ""
        } else {
            "; the previous file, if any, is unchanged"
        };
        CliError::input(format!("cannot write {} ({why}){kept}", p.display()))
    };
    let summary = match (result, &a.output) {
        (Ok(s), _) => s,
        (Err(e), None) if e.io_kind() == Some(std::io::ErrorKind::BrokenPipe) => {
            return Err(CliError::stop())
        }
        // Writing the file failed (disk full, file-size limit): nothing replaced --output.
        (Err(screwdyn::Error::Io { message: why, .. }), Some(p)) => return Err(unwritten(&why, p)),
        (Err(e), Some(p)) if sinks.first.is_some() => {
            let kept = match written {
                Some(Ok(())) => format!(
                    "; the run up to t = {} s is in {}",
                    fmt(sinks.last.t[0]),
                    p.display()
                ),
                _ => String::new(),
            };
            return Err(CliError::from(e).with_suffix(&kept));
        }
        (Err(e), _) => return Err(e.into()),
    };
    match (written, &a.output) {
        (Some(Err(e)), None) if e.io_kind() == Some(std::io::ErrorKind::BrokenPipe) => {
            return Err(CliError::stop())
        }
        (Some(Err(screwdyn::Error::Io { message: why, .. })), Some(p)) => {
            // The commit's own error already names the file.
            return Err(if why.starts_with("cannot write ") {
                CliError::input(why)
            } else {
                unwritten(&why, p)
            });
        }
        (Some(Err(e)), _) => return Err(e.into()),
        _ => {}
    }
    if let Some(p) = &a.output {
        crate::write::announce(p);
    }
    Ok((summary, sinks))
}

/// The four panels of a run: positions, velocities, torques and energy.
fn plot_run(m: &Model, rec: &Recording, controller: &str, p: &Path) -> Result<(), CliError> {
    let panels = vec![
        Panel {
            title: "Joint positions".into(),
            y_label: "q (rad)".into(),
            series: joint_series(rec, &rec.q),
            lines: vec![],
        },
        Panel {
            title: "Joint velocities".into(),
            y_label: "dq/dt (rad/s)".into(),
            series: joint_series(rec, &rec.v),
            lines: vec![],
        },
        Panel {
            title: "Applied joint torques".into(),
            y_label: "τ (N·m)".into(),
            series: joint_series(rec, &rec.tau),
            lines: vec![],
        },
        Panel {
            title: "Energy".into(),
            y_label: "E (J)".into(),
            series: vec![
                scalar_series(rec, "kinetic", &rec.kinetic_energy),
                scalar_series(rec, "potential", &rec.potential_energy),
                scalar_series(rec, "total", &rec.total_energy),
            ],
            lines: vec![],
        },
    ];
    let title = format!("{}: simulate, controller {controller}", m.name());
    plot_panels(p, &title, "t (s)", &panels).map(|_| ())
}

/// An event at a limit as the summary's JSON object (see [`LimitEvent::to_json`]).
fn event_value(e: &LimitEvent) -> Value {
    Value::Map(vec![
        ("kind".into(), Value::Text(e.kind.name().into())),
        ("t".into(), Value::Scalar(e.t)),
        ("joint".into(), Value::Text(e.joint_name.clone())),
        ("side".into(), Value::Text(e.side.name().into())),
        ("bound".into(), Value::Scalar(e.bound)),
        ("position".into(), Value::Scalar(e.position)),
        ("velocity".into(), Value::Scalar(e.velocity)),
    ])
}

/// The summary of a run: first and last state, energies, events at the limits, what was
/// written.
fn report_run(
    a: &SimulateArgs,
    m: &Model,
    summary: &sim::RunSummary,
    sinks: &RunSinks,
    format: Format,
) -> Result<(), CliError> {
    let (first, last) = match (&sinks.first, &sinks.last) {
        (Some(f), l) if !l.is_empty() => (f.sample(0)?, l.sample(0)?),
        _ => return Err(CliError::internal("the run recorded no sample")),
    };
    // A summary of the run.
    let j = names(m);
    let energy = |s: &Sample| s.kinetic_energy + s.potential_energy;
    let mut r = Report::new();
    r.add("joints", Value::Names(j.clone()))
        .add("samples", Value::Count(summary.samples))
        .add("t", Value::Scalar(last.t))
        .add("q", Value::joints(&j, last.q))
        .add("v", Value::joints(&j, last.v))
        .add("total_energy_start", Value::Scalar(energy(&first)))
        .add("total_energy_end", Value::Scalar(energy(&last)))
        .add(
            "events",
            Value::List(sinks.events.iter().map(event_value).collect()),
        );
    if format == Format::Table {
        let mut t = table();
        t.set_header(vec![
            "joint",
            "q(0) (rad)",
            "q(T) (rad)",
            "q̇(T) (rad/s)",
            "τ(T) (N·m)",
        ]);
        for (i, n) in j.iter().enumerate() {
            t.add_row(vec![
                n.clone(),
                fmt(first.q[i]),
                fmt(last.q[i]),
                fmt(last.v[i]),
                fmt(last.tau[i]),
            ]);
        }
        let mut text = format!(
            "simulated {} s of {} ({} integrator, {} steps of {} s), {} samples recorded\n{t}\n",
            fmt(last.t),
            m.name(),
            a.integrator,
            summary.steps,
            a.dt,
            summary.samples
        );
        text.push_str(&format!(
            "total energy: {} J at t = 0, {} J at the end\n",
            fmt(energy(&first)),
            fmt(energy(&last))
        ));
        if sinks.event_count > 0 {
            text.push_str(&format!(
                "limit events: {} (listed on stderr)\n",
                sinks.event_count
            ));
        }
        r.table = Some(text);
    }
    crate::output::print(&[r], format, false)
}
