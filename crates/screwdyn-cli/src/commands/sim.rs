//! `simulate` and `torque-profile`: runs over time, written as CSV/JSON (docs/cli.md) and plotted.

use super::{load, names, parse_numbers, parse_per_joint, parse_vector, parse_wrench};
use crate::args::{ControllerArg, Format, SimulateArgs, TorqueProfileArgs, TrajectoryArg};
use crate::output::{fmt, resolve, table, Report, Value};
use crate::plot::{plot_panels, Panel, Series};
use crate::write::{self, OutputFile};
use crate::CliError;
use screwdyn::dynamics::ForwardMethod;
use screwdyn::sim::{
    self, Controller, ControllerSpec, Disturbance, Integrator, JointEffects, Quintic, Recording,
    Sample, SampleSink, SimOptions, Trajectory, Trapezoid,
};
use screwdyn::Model;
use std::io::IsTerminal;
use std::path::Path;

/// Whether `path` is a run file (`.csv` / `.json`): checked before any work is done.
fn run_file_kind(path: &Path, flag: &str) -> Result<Format, CliError> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("csv") => Ok(Format::Csv),
        Some("json") => Ok(Format::Json),
        _ => Err(CliError::input(format!(
            "{flag} {}: the file name must end in .csv or .json",
            path.display()
        ))),
    }
}

fn plot_kind(path: &Path) -> Result<(), CliError> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("png") | Some("svg") => Ok(()),
        _ => Err(CliError::input(format!(
            "--plot {}: the file name must end in .png or .svg",
            path.display()
        ))),
    }
}

/// Where a run's samples go as they are recorded: a CSV or JSON file (or stdout), a bounded
/// copy for the plot, and the first and last samples for the summary.
struct RunSinks {
    file: Option<RunWriter>,
    plot: Option<Decimated>,
    first: Option<Recording>,
    last: Recording,
    joints: Vec<String>,
}

/// A streaming writer of a run.
enum RunWriter {
    Csv(sim::CsvSampleWriter<Box<dyn std::io::Write>>),
    Json(sim::JsonSampleWriter<Box<dyn std::io::Write>>),
}

impl RunWriter {
    fn new(kind: Format, out: Box<dyn std::io::Write>) -> Self {
        match kind {
            Format::Json => RunWriter::Json(sim::JsonSampleWriter::new(out)),
            _ => RunWriter::Csv(sim::CsvSampleWriter::new(out)),
        }
    }
    fn sink(&mut self) -> &mut dyn SampleSink {
        match self {
            RunWriter::Csv(w) => w,
            RunWriter::Json(w) => w,
        }
    }
    /// Completes the file (flushes the CSV, assembles the JSON object).
    fn finish(self) -> screwdyn::Result<()> {
        match self {
            RunWriter::Csv(mut w) => w.flush(),
            RunWriter::Json(w) => w.finish().map(|_| ()),
        }
    }
}

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
        self.last = Recording::new(self.joints.clone(), vec![]);
        self.last.push(&Sample { poses: &[], ..*s })
    }
}

/// Refuses `--output` / `--plot` onto an input of the command (the model file, `extra`).
fn refuse_onto_inputs(
    model: &str,
    extra: Option<&Path>,
    output: Option<&Path>,
    plot: Option<&Path>,
) -> Result<(), CliError> {
    let mut inputs = vec![Path::new(model)];
    inputs.extend(extra);
    for (flag, path) in [("--output", output), ("--plot", plot)] {
        if let Some(p) = path {
            write::refuse_inputs(flag, p, &inputs)?;
        }
    }
    Ok(())
}

fn joint_series(rec: &Recording, x: &[Vec<f64>]) -> Vec<Series> {
    rec.joints
        .iter()
        .enumerate()
        .map(|(i, name)| Series {
            name: name.clone(),
            points: rec.t.iter().zip(x).map(|(t, r)| (*t, r[i])).collect(),
        })
        .collect()
}

fn scalar_series(rec: &Recording, name: &str, x: &[f64]) -> Series {
    Series {
        name: name.into(),
        points: rec.t.iter().copied().zip(x.iter().copied()).collect(),
    }
}

/// Reads a torque series: columns `t` and `tau.<joint>` (a missing joint is zero); the times
/// are checked when the controller is built.
fn read_torque_csv(m: &Model, path: &Path) -> Result<ControllerSpec, CliError> {
    let file = path.display().to_string();
    let err =
        |e: csv::Error| CliError::input(format!("{file}: {}", e.to_string().replace('\n', " ")));
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| match e.kind() {
            csv::ErrorKind::Io(io) => CliError::input(format!("{file}: cannot be read ({io})")),
            _ => err(e),
        })?;
    let names = m.joint_names();
    let headers = reader.headers().map_err(err)?.clone();
    let mut cols = Vec::new(); // None = t, Some(j) = tau of joint j
    for h in headers.iter() {
        if h == "t" {
            cols.push(None);
        } else if let Some(j) = h
            .strip_prefix("tau.")
            .and_then(|n| names.iter().position(|x| *x == n))
        {
            cols.push(Some(j));
        } else {
            return Err(CliError::input(format!(
                "{file}: unknown column '{h}' (expected t and tau.<joint>, joints: {})",
                names.join(", ")
            )));
        }
    }
    if !cols.contains(&None) {
        return Err(CliError::input(format!(
            "{file}: the column 't' is missing"
        )));
    }
    let (mut times, mut values) = (Vec::new(), Vec::new());
    for record in reader.records() {
        let record = record.map_err(err)?;
        let line = record.position().map(|p| p.line()).unwrap_or(0);
        let mut tau = vec![0.0; m.nq()];
        let mut t = 0.0;
        for ((c, cell), h) in cols.iter().zip(record.iter()).zip(headers.iter()) {
            let x: f64 = cell
                .parse()
                .ok()
                .filter(|x: &f64| x.is_finite())
                .ok_or_else(|| {
                    CliError::input(format!(
                        "{file}:{line}: column '{h}': '{cell}' is not a finite number"
                    ))
                })?;
            match c {
                None => t = x,
                Some(j) => tau[*j] = x,
            }
        }
        times.push(t);
        values.push(tau);
    }
    Ok(ControllerSpec::Series { times, values })
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
        a.torque_csv.as_deref(),
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
    let q0 = parse_vector(a.q0.as_deref(), "q0", &m)?;
    let v0 = parse_vector(a.v0.as_deref(), "v0", &m)?;
    let (name, mut controller) = controller(a, &m, &q0)?;
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

/// A library error about a setting (`dt must be positive (got 0); …`) worded with the flag
/// that sets it (`--dt must be positive (got 0); …`); other errors as they are.
fn in_flag_words(e: screwdyn::Error) -> CliError {
    if let screwdyn::Error::InvalidArgument(message) = &e {
        if let Some((field, rest)) = message.split_once(" must be ") {
            let is_field = |c: char| c.is_ascii_lowercase() || c == '_' || c == '.';
            if !field.is_empty() && field.chars().all(is_field) {
                // `effects.limit_time_constant` is set by `--limit-time-constant`.
                let name = field.rsplit('.').next().unwrap_or(field);
                return CliError::input(format!("--{} must be {rest}", name.replace('_', "-")));
            }
        }
    }
    e.into()
}

/// The controller chosen by `--controller` (and its name), with its gains and reference.
fn controller(
    a: &SimulateArgs,
    m: &Model,
    q0: &[f64],
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
            let reference = Quintic::rest_to_rest(q0, &target, a.duration).map_err(|e| {
                in_flag_words(e).with_suffix(
                    " (--controller computed-torque tracks a quintic from --q0 to --target over --duration)",
                )
            })?;
            ControllerSpec::ComputedTorque {
                reference: Box::new(reference),
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

/// The summary of a run: first and last state, energies, what was written.
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
        .add("total_energy_end", Value::Scalar(energy(&last)));
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
        if let Some(p) = &a.output {
            text.push_str(&format!("run written to {}\n", p.display()));
        }
        if let Some(p) = &a.plot {
            text.push_str(&format!("plot written to {}\n", p.display()));
        }
        r.table = Some(text);
    }
    crate::output::print(&[r], format, false)
}

/// `screwdyn torque-profile MODEL --trajectory trapezoid|quintic --q0 --qf ...`.
pub fn torque_profile(a: &TorqueProfileArgs) -> Result<(), CliError> {
    let output_kind = a
        .output
        .as_deref()
        .map(|p| run_file_kind(p, "--output"))
        .transpose()?;
    if let Some(p) = &a.plot {
        plot_kind(p)?;
    }
    refuse_onto_inputs(&a.model.model, None, a.output.as_deref(), a.plot.as_deref())?;
    let m = load(&a.model, a.gravity.as_deref())?;
    let q0 = parse_vector(a.q0.as_deref(), "q0", &m)?;
    let qf = parse_vector(Some(&a.qf), "qf", &m)?;
    let (traj, what) = trajectory(a, &m, &q0, &qf)?;
    let p = sim::torque_profile_limited(&m, traj.as_ref(), a.dt, a.max_samples)
        .map_err(in_flag_words)?;
    let rec = &p.samples;
    if let (Some(path), Some(kind)) = (&a.output, output_kind) {
        let file = OutputFile::create(path)?;
        let mut w = RunWriter::new(kind, Box::new(file.writer()?));
        let whole = (|| {
            w.sink().begin(&rec.joints, &rec.frames)?;
            for k in 0..rec.len() {
                w.sink().push(&rec.sample(k)?)?;
            }
            w.finish()
        })();
        whole.map_err(|e| match e {
            screwdyn::Error::Io { message: why, .. } => {
                CliError::input(format!("cannot write {} ({why})", path.display()))
            }
            e => e.into(),
        })?;
        file.commit()?;
    }
    let r = profile_report(a, &m, &p, traj.duration(), &what);
    if let Some(path) = &a.plot {
        plot_profile(a, &m, &p, traj.duration(), path)?;
    }
    crate::output::print(&[r], resolve(a.model.format), false)
}

/// The trajectory of `--trajectory` and a phrase describing it.
fn trajectory(
    a: &TorqueProfileArgs,
    m: &Model,
    q0: &[f64],
    qf: &[f64],
) -> Result<(Box<dyn Trajectory>, String), CliError> {
    Ok(match a.trajectory {
        TrajectoryArg::Trapezoid => {
            let vmax = parse_per_joint(&a.vmax, "vmax", m)?;
            let amax = parse_per_joint(&a.amax, "amax", m)?;
            if let Some(x) = vmax.iter().chain(&amax).find(|x| **x <= 0.0) {
                return Err(CliError::input(format!(
                    "--vmax and --amax must be positive (got {x})"
                )));
            }
            let t = Trapezoid::new(q0, qf, &vmax, &amax, !a.unsynchronised)?;
            let cruise: Vec<String> = t
                .cruise_speeds()
                .iter()
                .map(|v| format!("{v:.3}"))
                .collect();
            let what = format!(
                "trapezoid: accelerate from rest, cruise at ({}) rad/s, stop",
                cruise.join(", ")
            );
            (Box::new(t), what)
        }
        TrajectoryArg::Quintic => (
            Box::new(Quintic::rest_to_rest(q0, qf, a.duration).map_err(in_flag_words)?),
            "quintic rest-to-rest".to_string(),
        ),
    })
}

/// Peak, RMS, limits and violations per joint (JSON keys and the table).
fn profile_report(
    a: &TorqueProfileArgs,
    m: &Model,
    p: &sim::TorqueProfile,
    duration: f64,
    what: &str,
) -> Report {
    let rec = &p.samples;
    let j = names(m);
    let viol: Vec<(String, Value)> = j
        .iter()
        .zip(&p.violation_summary)
        .map(|(name, s)| {
            let (count, first, worst) = s.map_or((0, f64::NAN, f64::NAN), |s| {
                (s.count, s.first_time, s.worst)
            });
            (
                name.clone(),
                Value::Map(vec![
                    ("count".into(), Value::Count(count)),
                    ("first_time".into(), Value::Scalar(first)),
                    ("worst".into(), Value::Scalar(worst)),
                ]),
            )
        })
        .collect();
    let mut r = Report::new();
    r.add("joints", Value::Names(j.clone()))
        .add("duration", Value::Scalar(duration))
        .add("peak", Value::joints(&j, &p.peak))
        .add("peak_time", Value::joints(&j, &p.peak_time))
        .add("rms", Value::joints(&j, &p.rms))
        .add("effort_limit", Value::joints(&j, &p.effort_limit))
        .add("violations", Value::Map(viol));
    let mut t = table();
    t.set_header(vec![
        "joint",
        "peak |τ| (N·m)",
        "at t (s)",
        "RMS τ (N·m)",
        "limit (N·m)",
        "samples over",
        "first over (s)",
        "worst |τ| (N·m)",
    ]);
    for (i, name) in j.iter().enumerate() {
        let (count, first, worst) = match p.violation_summary[i] {
            None => (0, "-".to_string(), "-".to_string()),
            Some(s) => (s.count, fmt(s.first_time), fmt(s.worst)),
        };
        t.add_row(vec![
            name.clone(),
            fmt(p.peak[i]),
            format!("{:.3}", p.peak_time[i]),
            fmt(p.rms[i]),
            fmt(p.effort_limit[i]),
            count.to_string(),
            first,
            worst,
        ]);
    }
    let over: Vec<&str> = p
        .joints_over_limit()
        .into_iter()
        .map(|i| j[i].as_str())
        .collect();
    let verdict = if over.is_empty() {
        "every joint stays within its effort limit".to_string()
    } else {
        format!("over the effort limit: {}", over.join(", "))
    };
    r.table = Some(format!(
        "{} on {}: {what}, {} s, {} samples every {} s\n{t}\n{verdict}\n",
        match a.trajectory {
            TrajectoryArg::Trapezoid => "torque profile (trapezoid)",
            TrajectoryArg::Quintic => "torque profile (quintic)",
        },
        m.name(),
        fmt(duration),
        rec.len(),
        a.dt
    ));
    r
}

/// Required torques against the effort limits, velocities and positions.
fn plot_profile(
    a: &TorqueProfileArgs,
    m: &Model,
    p: &sim::TorqueProfile,
    duration: f64,
    path: &Path,
) -> Result<(), CliError> {
    let rec = &p.samples;
    let mut lines = Vec::new();
    let mut limits: Vec<(f64, Vec<String>)> = Vec::new();
    for (i, l) in p.effort_limit.iter().enumerate() {
        if !l.is_finite() {
            continue;
        }
        match limits.iter_mut().find(|(x, _)| x == l) {
            Some((_, js)) => js.push((i + 1).to_string()),
            None => limits.push((*l, vec![(i + 1).to_string()])),
        }
    }
    for (l, js) in &limits {
        let which = if js.len() == 1 { "joint" } else { "joints" };
        let label = format!(
            "effort limit ±{} N·m ({which} {})",
            fmt_short(*l),
            js.join(", ")
        );
        lines.push((label.clone(), *l));
        lines.push((label, -*l));
    }
    let panels = vec![
        Panel {
            title: "Required joint torques (inverse dynamics)".into(),
            y_label: "τ (N·m)".into(),
            series: joint_series(rec, &rec.tau),
            lines,
        },
        Panel {
            title: "Joint velocities".into(),
            y_label: "dq/dt (rad/s)".into(),
            series: joint_series(rec, &rec.v),
            lines: vec![],
        },
        Panel {
            title: "Joint positions".into(),
            y_label: "q (rad)".into(),
            series: joint_series(rec, &rec.q),
            lines: vec![],
        },
    ];
    let kind = match a.trajectory {
        TrajectoryArg::Trapezoid => "trapezoid",
        TrajectoryArg::Quintic => "quintic",
    };
    let title = format!(
        "{}: torques for a {kind} motion of {} s",
        m.name(),
        fmt_short(duration)
    );
    plot_panels(path, &title, "t (s)", &panels).map(|_| ())
}

fn fmt_short(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
