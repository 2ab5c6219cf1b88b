//! `simulate` and `torque-profile`: runs over time, written as CSV/JSON and plotted.

use super::{load, names, parse_numbers, parse_per_joint, parse_vector, parse_wrench};
use crate::args::{ControllerArg, Format, SimulateArgs, TorqueProfileArgs, TrajectoryArg};
use crate::output::{fmt, resolve, table, write_stdout, Report, Value};
use crate::plot::{plot_panels, Panel, Series};
use crate::write;
use crate::CliError;
use screwdyn::dynamics::{crba, ForwardMethod};
use screwdyn::sim::{
    self, ComputedTorque, ConstantTorque, Controller, Disturbance, Integrator, JointEffects,
    PdGravity, Quintic, Recording, SimOptions, TorqueSeries, Trajectory, Trapezoid, ZeroTorque,
};
use screwdyn::{Model, Workspace};
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

/// Writes a recording as CSV or JSON (the run file's columns) to `path`, atomically.
fn write_recording(rec: &Recording, path: &Path, kind: Format) -> Result<(), CliError> {
    let fail =
        |e: std::io::Error| CliError::input(format!("cannot write {} ({e})", path.display()));
    write::atomic(path, |file| match kind {
        Format::Json => serde_json::to_writer(file, &rec.to_json())
            .map_err(|e| CliError::input(format!("cannot write {} ({e})", path.display()))),
        _ => write_run_csv(rec, file).map_err(fail),
    })
}

/// One CSV row per sample under [`Recording::columns`]; names quoted as CSV needs (a joint
/// named `j"2,x`), numbers in their shortest round-trip form.
fn write_run_csv(rec: &Recording, w: &mut impl std::io::Write) -> std::io::Result<()> {
    let mut csv = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(w);
    let io = |e: csv::Error| match e.into_kind() {
        csv::ErrorKind::Io(e) => e,
        k => std::io::Error::other(format!("{k:?}")),
    };
    csv.write_record(rec.columns()).map_err(io)?;
    let mut num = ryu::Buffer::new();
    let mut cell = |csv: &mut csv::Writer<_>, x: f64| {
        let text = if x.is_finite() {
            num.format_finite(x)
        } else if x.is_nan() {
            "NaN"
        } else if x > 0.0 {
            "inf"
        } else {
            "-inf"
        };
        csv.write_field(text)
    };
    for k in 0..rec.len() {
        cell(&mut csv, rec.t[k]).map_err(io)?;
        for x in [&rec.q, &rec.v, &rec.a, &rec.tau] {
            for v in &x[k] {
                cell(&mut csv, *v).map_err(io)?;
            }
        }
        for e in [
            rec.kinetic_energy[k],
            rec.potential_energy[k],
            rec.total_energy[k],
        ] {
            cell(&mut csv, e).map_err(io)?;
        }
        if let Some(p) = rec.poses.get(k) {
            for h in p {
                for x in h.translation.iter() {
                    cell(&mut csv, *x).map_err(io)?;
                }
            }
        }
        csv.write_record(None::<&[u8]>).map_err(io)?;
    }
    csv.flush()
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

/// Reads a torque series: columns `t` and `tau.<joint>` (a missing joint is zero).
fn read_torque_csv(m: &Model, path: &Path) -> Result<TorqueSeries, CliError> {
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
    TorqueSeries::new(times, values).map_err(|e| CliError::input(format!("{file}: {e}")))
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

/// `screwdyn simulate MODEL ...`.
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
    let integrator: Integrator = a
        .integrator
        .parse()
        .map_err(|e: String| CliError::input(format!("--integrator: {e}")))?;
    let method: ForwardMethod = a
        .method
        .parse()
        .map_err(|e: String| CliError::input(format!("--method: {e}")))?;
    if !(a.dt > 0.0 && a.dt.is_finite()) {
        return Err(CliError::input(format!(
            "--dt must be positive (got {})",
            a.dt
        )));
    }
    let t = a.limit_time_constant;
    if !(t > 0.0 && t.is_finite()) {
        return Err(CliError::input(format!(
            "--limit-time-constant must be positive (got {t})"
        )));
    }
    let zeta = a.limit_damping_ratio;
    if !(zeta >= 0.0 && zeta.is_finite()) {
        return Err(CliError::input(format!(
            "--limit-damping-ratio must be non-negative (got {zeta})"
        )));
    }
    if !(a.duration >= 0.0 && a.duration.is_finite()) {
        return Err(CliError::input(format!(
            "--duration must be a non-negative number (got {})",
            a.duration
        )));
    }
    if a.record_every == 0 {
        return Err(CliError::input("--record-every must be at least 1"));
    }
    let q0 = parse_vector(a.q0.as_deref(), "q0", &m)?;
    let v0 = parse_vector(a.v0.as_deref(), "v0", &m)?;
    let target = match &a.target {
        Some(t) => parse_vector(Some(t), "target", &m)?,
        None => q0.clone(),
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
    let gains = |text: &Option<String>, flag: &str, default: Vec<f64>| match text {
        Some(t) => parse_per_joint(t, flag, &m),
        None => Ok(default),
    };
    let mut controller: Box<dyn Controller> = match c {
        ControllerArg::Zero => Box::new(ZeroTorque),
        ControllerArg::Constant => {
            let Some(t) = &a.tau else {
                return Err(CliError::input("--controller constant needs --tau"));
            };
            Box::new(ConstantTorque(parse_vector(Some(t), "tau", &m)?))
        }
        ControllerArg::Pd => {
            // Critically damped at 10 rad/s on each joint's own inertia M_ii(target).
            let mut ws = Workspace::new(&m);
            let mm = crba(&m, &mut ws, &target)?;
            let diag: Vec<f64> = (0..m.nq()).map(|i| mm[(i, i)]).collect();
            let kp = gains(&a.kp, "kp", diag.iter().map(|d| 100.0 * d).collect())?;
            let kd = gains(&a.kd, "kd", diag.iter().map(|d| 20.0 * d).collect())?;
            Box::new(PdGravity::new(m.clone(), target.clone(), kp, kd)?)
        }
        ControllerArg::ComputedTorque => {
            if a.duration <= 0.0 {
                return Err(CliError::input(
                    "--controller computed-torque needs a positive --duration",
                ));
            }
            let traj = Quintic::rest_to_rest(&q0, &target, a.duration)?;
            let kp = gains(&a.kp, "kp", vec![100.0; m.nq()])?;
            let kd = gains(&a.kd, "kd", vec![20.0; m.nq()])?;
            Box::new(ComputedTorque::new(m.clone(), Box::new(traj), kp, kd)?)
        }
        ControllerArg::Series => {
            let Some(p) = &a.torque_csv else {
                return Err(CliError::input(
                    "--controller series needs --torque-csv FILE",
                ));
            };
            Box::new(read_torque_csv(&m, p)?)
        }
    };
    let disturbances = a
        .disturbance
        .iter()
        .map(|d| parse_disturbance(&m, d))
        .collect::<Result<Vec<_>, _>>()?;
    let opts = SimOptions {
        duration: a.duration,
        dt: a.dt,
        integrator,
        method,
        effects: if a.no_effects {
            JointEffects::none()
        } else {
            JointEffects {
                limit_time_constant: a.limit_time_constant,
                limit_damping_ratio: a.limit_damping_ratio,
                ..JointEffects::default()
            }
        },
        record_every: a.record_every,
        frames: a
            .frames
            .iter()
            .map(|f| m.frame_id(f))
            .collect::<Result<Vec<_>, _>>()?,
    };
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
    let result = sim::simulate(
        &m,
        &q0,
        &v0,
        controller.as_mut(),
        &disturbances,
        &opts,
        &mut progress,
    );
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let rec = result?;
    if let (Some(p), Some(kind)) = (&a.output, output_kind) {
        write_recording(&rec, p, kind)?;
    }
    if let Some(p) = &a.plot {
        let panels = vec![
            Panel {
                title: "Joint positions".into(),
                y_label: "q (rad)".into(),
                series: joint_series(&rec, &rec.q),
                lines: vec![],
            },
            Panel {
                title: "Joint velocities".into(),
                y_label: "dq/dt (rad/s)".into(),
                series: joint_series(&rec, &rec.v),
                lines: vec![],
            },
            Panel {
                title: "Applied joint torques".into(),
                y_label: "τ (N·m)".into(),
                series: joint_series(&rec, &rec.tau),
                lines: vec![],
            },
            Panel {
                title: "Energy".into(),
                y_label: "E (J)".into(),
                series: vec![
                    scalar_series(&rec, "kinetic", &rec.kinetic_energy),
                    scalar_series(&rec, "potential", &rec.potential_energy),
                    scalar_series(&rec, "total", &rec.total_energy),
                ],
                lines: vec![],
            },
        ];
        let title = format!("{}: simulate, controller {name}", m.name());
        plot_panels(p, &title, "t (s)", &panels)?;
    }
    let format = resolve(a.model.format);
    if a.output.is_none() && format != Format::Table {
        let mut text = Vec::new();
        if format == Format::Csv {
            write_run_csv(&rec, &mut text)
                .map_err(|e| CliError::internal(format!("cannot format the run ({e})")))?;
        } else {
            text = serde_json::to_vec(&rec.to_json()).expect("JSON of numbers");
            text.push(b'\n');
        }
        return write_stdout(&String::from_utf8_lossy(&text));
    }
    // A summary of the run.
    let j = names(&m);
    let last = rec.len() - 1;
    let mut r = Report::new();
    r.add("joints", Value::Names(j.clone()))
        .add("samples", Value::Count(rec.len()))
        .add("t", Value::Scalar(rec.t[last]))
        .add("q", Value::joints(&j, &rec.q[last]))
        .add("v", Value::joints(&j, &rec.v[last]))
        .add("total_energy_start", Value::Scalar(rec.total_energy[0]))
        .add("total_energy_end", Value::Scalar(rec.total_energy[last]));
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
                fmt(rec.q[0][i]),
                fmt(rec.q[last][i]),
                fmt(rec.v[last][i]),
                fmt(rec.tau[last][i]),
            ]);
        }
        let mut text = format!(
            "simulated {} s of {} ({} integrator, {} steps of {} s), {} samples recorded\n{t}\n",
            fmt(rec.t[last]),
            m.name(),
            a.integrator,
            (a.duration / a.dt).round(),
            a.dt,
            rec.len()
        );
        text.push_str(&format!(
            "total energy: {} J at t = 0, {} J at the end\n",
            fmt(rec.total_energy[0]),
            fmt(rec.total_energy[last])
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
    if !(a.dt > 0.0 && a.dt.is_finite()) {
        return Err(CliError::input(format!(
            "--dt must be positive (got {})",
            a.dt
        )));
    }
    let (traj, what): (Box<dyn Trajectory>, String) = match a.trajectory {
        TrajectoryArg::Trapezoid => {
            let vmax = parse_per_joint(&a.vmax, "vmax", &m)?;
            let amax = parse_per_joint(&a.amax, "amax", &m)?;
            if let Some(x) = vmax.iter().chain(&amax).find(|x| **x <= 0.0) {
                return Err(CliError::input(format!(
                    "--vmax and --amax must be positive (got {x})"
                )));
            }
            let t = Trapezoid::new(&q0, &qf, &vmax, &amax, !a.unsynchronised)?;
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
        TrajectoryArg::Quintic => {
            if !(a.duration > 0.0 && a.duration.is_finite()) {
                return Err(CliError::input(format!(
                    "--duration must be positive (got {})",
                    a.duration
                )));
            }
            (
                Box::new(Quintic::rest_to_rest(&q0, &qf, a.duration)?),
                "quintic rest-to-rest".to_string(),
            )
        }
    };
    let p = sim::torque_profile(&m, traj.as_ref(), a.dt)?;
    let rec = &p.samples;
    if let (Some(path), Some(kind)) = (&a.output, output_kind) {
        write_recording(rec, path, kind)?;
    }
    let j = names(&m);
    let n = m.nq();
    let peak_time: Vec<f64> = (0..n)
        .map(|i| {
            let k = (0..rec.len())
                .max_by(|&x, &y| rec.tau[x][i].abs().total_cmp(&rec.tau[y][i].abs()))
                .unwrap_or(0);
            rec.t[k]
        })
        .collect();
    let mut viol = Vec::new();
    for (i, name) in j.iter().enumerate() {
        let mine: Vec<_> = p.violations.iter().filter(|v| v.joint == i).collect();
        let first = mine.first().map(|v| v.t).unwrap_or(f64::NAN);
        let worst = mine
            .iter()
            .map(|v| v.tau.abs())
            .fold(f64::NAN, |w: f64, x| if w.is_nan() { x } else { w.max(x) });
        viol.push((
            name.clone(),
            Value::Map(vec![
                ("count".into(), Value::Count(mine.len())),
                ("first_time".into(), Value::Scalar(first)),
                ("worst".into(), Value::Scalar(worst)),
            ]),
        ));
    }
    let mut r = Report::new();
    r.add("joints", Value::Names(j.clone()))
        .add("duration", Value::Scalar(traj.duration()))
        .add("peak", Value::joints(&j, &p.peak))
        .add("peak_time", Value::joints(&j, &peak_time))
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
    for i in 0..n {
        let mine: Vec<_> = p.violations.iter().filter(|v| v.joint == i).collect();
        let (first, worst) = if mine.is_empty() {
            ("-".to_string(), "-".to_string())
        } else {
            (
                fmt(mine[0].t),
                fmt(mine.iter().map(|v| v.tau.abs()).fold(0.0, f64::max)),
            )
        };
        t.add_row(vec![
            j[i].clone(),
            fmt(p.peak[i]),
            format!("{:.3}", peak_time[i]),
            fmt(p.rms[i]),
            fmt(p.effort_limit[i]),
            mine.len().to_string(),
            first,
            worst,
        ]);
    }
    let over: Vec<&str> = (0..n)
        .filter(|&i| p.violations.iter().any(|v| v.joint == i))
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
        fmt(traj.duration()),
        rec.len(),
        a.dt
    ));
    if let Some(path) = &a.plot {
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
            fmt_short(traj.duration())
        );
        plot_panels(path, &title, "t (s)", &panels)?;
    }
    crate::output::print(&[r], resolve(a.model.format), false)
}

fn fmt_short(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
