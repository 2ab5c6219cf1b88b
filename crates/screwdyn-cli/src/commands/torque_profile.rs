//! `torque-profile`: the torques a trajectory needs against the effort limits, written as
//! CSV/JSON (docs/cli.md) and plotted.

use super::inputs::{load, names, parse_fixed, parse_per_joint, parse_vector};
use super::joint_csv::read_waypoints;
use super::run_files::{
    in_flag_words, joint_series, plot_kind, refuse_onto_inputs, run_file_kind, RunWriter,
};
use crate::args::{Format, TorqueProfileArgs, TrajectoryArg};
use crate::output::{fmt, resolve, table, Report, Value};
use crate::plot::{plot_panels, Panel, Series};
use crate::write::OutputFile;
use crate::CliError;
use screwdyn::kinematics::ik::target_from_quaternion;
use screwdyn::motion::{
    cartesian_move, limit_fractions, time_optimal, CartesianOptions, CubicSpline, JerkLimited,
    TimeOptimalOptions, TimingLimits,
};
use screwdyn::sim::{self, Quintic, Trajectory, Trapezoid};
use screwdyn::Model;
use std::path::Path;

/// The motion of `--trajectory`, a phrase describing it, and for time-optimal timings the
/// limits it was timed within, with the grid and check results.
struct Motion {
    trajectory: Box<dyn Trajectory>,
    what: String,
    timing: Option<(TimingLimits, screwdyn::motion::TimingReport)>,
    /// The torque statistics of a time-optimal timing's check, sampled every `--dt` as the
    /// profile would be (`None` when its step is another).
    checked: Option<sim::ProfileSummary>,
}

/// `screwdyn torque-profile MODEL --trajectory trapezoid|quintic|time-optimal|jerk-limited ...`.
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
    let motion = trajectory(a, &m)?;
    let traj = &motion.trajectory;
    let format = resolve(a.model.format);
    // Without a plot nothing needs the samples in memory: they are streamed to --output, or
    // to stdout with --format csv (and no --output), as they are computed.
    let to_stdout = a.output.is_none() && format == Format::Csv;
    if a.plot.is_none() && (a.output.is_some() || to_stdout) {
        let summary = match (&a.output, output_kind) {
            (Some(path), Some(kind)) => stream_to_file(a, &m, traj.as_ref(), path, kind)?,
            _ => return stream_to_stdout(a, &m, traj.as_ref()),
        };
        let r = profile_report(a, &m, &summary, &motion);
        return crate::output::print(&[r], format, false);
    }
    // A report alone, of a timing whose check sampled the torques every --dt already: its
    // statistics are the profile's.
    if let Some(summary) = &motion.checked {
        if a.plot.is_none() && a.output.is_none() && summary.samples <= a.max_samples {
            let r = profile_report(a, &m, summary, &motion);
            return crate::output::print(&[r], format, false);
        }
    }
    // A plot needs every sample: the profile is held, or refused up front with the memory it
    // would need.
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
        whole.map_err(|e| cannot_write(e, path))?;
        file.commit()?;
        crate::write::announce(path);
    }
    let summary = sim::ProfileSummary {
        samples: rec.len(),
        peak: p.peak.clone(),
        peak_time: p.peak_time.clone(),
        rms: p.rms.clone(),
        effort_limit: p.effort_limit.clone(),
        violation_summary: p.violation_summary.clone(),
    };
    let r = profile_report(a, &m, &summary, &motion);
    if let Some(path) = &a.plot {
        plot_profile(a, &m, &p, &motion, path)?;
    }
    crate::output::print(&[r], format, false)
}

/// A write error of the run file as the CLI's sentence naming it.
fn cannot_write(e: screwdyn::Error, path: &Path) -> CliError {
    match e {
        screwdyn::Error::Io { message: why, .. } => {
            CliError::input(format!("cannot write {} ({why})", path.display()))
        }
        e => e.into(),
    }
}

/// Streams the profile's samples into `path` (atomically: a temporary file renamed over it
/// once complete); returns the statistics.
fn stream_to_file(
    a: &TorqueProfileArgs,
    m: &Model,
    traj: &dyn Trajectory,
    path: &Path,
    kind: Format,
) -> Result<sim::ProfileSummary, CliError> {
    let file = OutputFile::create(path)?;
    let mut w = RunWriter::new(kind, Box::new(file.writer()?));
    let summary =
        sim::torque_profile_into(m, traj, a.dt, a.max_samples, w.sink()).map_err(|e| match e {
            screwdyn::Error::Io { .. } => cannot_write(e, path),
            // A setting's error is worded with its flag (`--dt must be positive …`).
            e => in_flag_words(e),
        })?;
    w.finish().map_err(|e| cannot_write(e, path))?;
    file.commit()?;
    crate::write::announce(path);
    Ok(summary)
}

/// `--format csv` without `--output`: the samples to stdout as they are computed; a reader
/// that goes away (`| head`) ends the command quietly.
fn stream_to_stdout(
    a: &TorqueProfileArgs,
    m: &Model,
    traj: &dyn Trajectory,
) -> Result<(), CliError> {
    let mut w = sim::CsvSampleWriter::new(std::io::BufWriter::new(std::io::stdout()));
    let result =
        sim::torque_profile_into(m, traj, a.dt, a.max_samples, &mut w).and_then(|_| w.flush());
    match result {
        Ok(()) => Ok(()),
        Err(e) if e.io_kind() == Some(std::io::ErrorKind::BrokenPipe) => Err(CliError::stop()),
        Err(e) => Err(in_flag_words(e)),
    }
}

/// `--name`, required by `--trajectory kind`.
fn required<'a>(x: &'a Option<String>, name: &str, kind: &str) -> Result<&'a str, CliError> {
    x.as_deref()
        .ok_or_else(|| CliError::input(format!("--{name} is required with --trajectory {kind}")))
}

/// A time-optimal limit flag: one value for all joints or one per joint, `inf` for none (the
/// library refuses zero, negative and NaN limits naming the joint).
fn parse_limit(text: &str, name: &str, m: &Model) -> Result<Vec<f64>, CliError> {
    let flag = format!("--{name}");
    let v = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| CliError::input(format!("{flag}: '{}' is not a number", s.trim())))
        })
        .collect::<Result<Vec<_>, _>>()?;
    match v.len() {
        1 => Ok(vec![v[0]; m.nq()]),
        n if n == m.nq() => Ok(v),
        n => Err(CliError::input(format!(
            "{flag} has {n} values: give one for all joints or one per joint ({})",
            m.nq()
        ))),
    }
}

/// Flags that `--trajectory kind` does not use are refused.
fn unused(flags: &[(&str, bool)], kind: &str) -> Result<(), CliError> {
    match flags.iter().find(|(_, given)| *given) {
        Some((name, _)) => Err(CliError::input(format!(
            "--{name} is not used by --trajectory {kind}"
        ))),
        None => Ok(()),
    }
}

/// The trajectory of `--trajectory` and a phrase describing it.
fn trajectory(a: &TorqueProfileArgs, m: &Model) -> Result<Motion, CliError> {
    let plain = |trajectory: Box<dyn Trajectory>, what: String| Motion {
        trajectory,
        what,
        timing: None,
        checked: None,
    };
    let q0 = || parse_vector(a.q0.as_deref(), "q0", m);
    let kind = a.trajectory.name();
    let cartesian = matches!(
        a.trajectory,
        TrajectoryArg::Linear | TrajectoryArg::Circular
    );
    if a.trajectory != TrajectoryArg::TimeOptimal {
        unused(&[("waypoints", a.waypoints.is_some())], kind)?;
        if !cartesian {
            unused(&[("grid", a.grid.is_some())], kind)?;
        }
    }
    if a.trajectory != TrajectoryArg::JerkLimited {
        unused(&[("jmax", a.jmax.is_some())], kind)?;
    }
    if !cartesian {
        unused(
            &[
                ("frame", a.frame.is_some()),
                ("target", a.target.is_some()),
                ("speed", a.speed.is_some()),
            ],
            kind,
        )?;
    }
    if a.trajectory != TrajectoryArg::Circular {
        unused(&[("via", a.via.is_some())], kind)?;
    }
    Ok(match a.trajectory {
        TrajectoryArg::Linear | TrajectoryArg::Circular => cartesian_motion(a, m)?,
        TrajectoryArg::Trapezoid => {
            let qf = parse_vector(Some(required(&a.qf, "qf", kind)?), "qf", m)?;
            let vmax = parse_per_joint(a.vmax.as_deref().unwrap_or("1"), "vmax", m)?;
            let amax = parse_per_joint(a.amax.as_deref().unwrap_or("2"), "amax", m)?;
            let t = Trapezoid::new(&q0()?, &qf, &vmax, &amax, !a.unsynchronised)?;
            let cruise: Vec<String> = t
                .cruise_speeds()
                .iter()
                .map(|v| format!("{v:.3}"))
                .collect();
            let what = format!(
                "trapezoid: accelerate from rest, cruise at ({}) rad/s, stop",
                cruise.join(", ")
            );
            plain(Box::new(t), what)
        }
        TrajectoryArg::Quintic => {
            let qf = parse_vector(Some(required(&a.qf, "qf", kind)?), "qf", m)?;
            plain(
                Box::new(Quintic::rest_to_rest(&q0()?, &qf, a.duration).map_err(in_flag_words)?),
                "quintic rest-to-rest".to_string(),
            )
        }
        TrajectoryArg::JerkLimited => {
            let qf = parse_vector(Some(required(&a.qf, "qf", kind)?), "qf", m)?;
            let vmax = match &a.vmax {
                Some(v) => parse_per_joint(v, "vmax", m)?,
                None => TimingLimits::from_model(m).velocity,
            };
            if let Some(j) = vmax.iter().position(|v| v.is_infinite()) {
                return Err(CliError::input(format!(
                    "--vmax is required: joint {} has no velocity limit in the model",
                    m.joint_names()[j]
                )));
            }
            let amax = parse_per_joint(required(&a.amax, "amax", kind)?, "amax", m)?;
            let jmax = parse_per_joint(required(&a.jmax, "jmax", kind)?, "jmax", m)?;
            let t = JerkLimited::new(&q0()?, &qf, &vmax, &amax, &jmax).map_err(in_flag_words)?;
            plain(
                Box::new(t),
                "jerk-limited rest-to-rest, all joints finishing together".to_string(),
            )
        }
        TrajectoryArg::TimeOptimal => {
            unused(
                &[
                    ("q0", a.q0.is_some()),
                    ("qf", a.qf.is_some()),
                    ("unsynchronised", a.unsynchronised),
                ],
                kind,
            )?;
            let Some(file) = &a.waypoints else {
                return Err(CliError::input(
                    "--waypoints is required with --trajectory time-optimal",
                ));
            };
            let (s, points) = read_waypoints(m, file)?;
            let path = CubicSpline::for_model(m, s.as_deref(), &points)
                .map_err(|e| CliError::input(format!("{}: {e}", file.display())))?;
            let mut limits = TimingLimits::from_model(m);
            if let Some(v) = &a.vmax {
                limits.velocity = parse_limit(v, "vmax", m)?;
            }
            if let Some(v) = &a.amax {
                limits.acceleration = parse_limit(v, "amax", m)?;
            }
            let options = TimeOptimalOptions {
                grid: a.grid,
                ..Default::default()
            };
            let timed = time_optimal(m, path, &limits, &options)?;
            let report = timed.report().clone();
            let checked = (a.dt == options.check_step).then(|| report.profile.clone());
            let &(grid, _) = report.durations.last().expect("one grid at least");
            let check = if report.max_excess <= 0.0 {
                "every checked sample within the limits".to_string()
            } else {
                format!(
                    "a checked sample over a limit by {:.2e} of it",
                    report.max_excess
                )
            };
            let what = format!(
                "time-optimal through {} waypoints: grid of {grid} intervals, {check}",
                points.len()
            );
            Motion {
                trajectory: Box::new(timed),
                what,
                timing: Some((limits, report)),
                checked,
            }
        }
    })
}

/// `--trajectory linear|circular`: `--frame` from its pose at `--q0` to `--target` (through
/// `--via`), timed within the joint limits and `--speed`.
fn cartesian_motion(a: &TorqueProfileArgs, m: &Model) -> Result<Motion, CliError> {
    let kind = a.trajectory.name();
    unused(
        &[("qf", a.qf.is_some()), ("unsynchronised", a.unsynchronised)],
        kind,
    )?;
    let frame = m.frame_id(required(&a.frame, "frame", kind)?)?;
    let q0 = parse_vector(Some(required(&a.q0, "q0", kind)?), "q0", m)?;
    let v = parse_fixed(
        required(&a.target, "target", kind)?,
        "--target",
        7,
        "x,y,z,qw,qx,qy,qz",
    )?;
    let target = target_from_quaternion([v[0], v[1], v[2]], [v[3], v[4], v[5], v[6]], "--target")?;
    let via = match a.trajectory {
        TrajectoryArg::Circular => {
            let v = parse_fixed(required(&a.via, "via", kind)?, "--via", 3, "x,y,z")?;
            Some(nalgebra::Vector3::new(v[0], v[1], v[2]))
        }
        _ => None,
    };
    let mut limits = TimingLimits::from_model(m);
    if let Some(v) = &a.vmax {
        limits.velocity = parse_limit(v, "vmax", m)?;
    }
    if let Some(v) = &a.amax {
        limits.acceleration = parse_limit(v, "amax", m)?;
    }
    if let Some(speed) = a.speed {
        if speed.is_nan() || speed <= 0.0 {
            return Err(CliError::input(format!(
                "--speed is {speed}, the tool speed limit must be positive"
            )));
        }
    }
    let options = CartesianOptions {
        tool_speed: a.speed.unwrap_or(f64::INFINITY),
        timing: TimeOptimalOptions {
            grid: a.grid,
            ..Default::default()
        },
        ..Default::default()
    };
    let motion = cartesian_move(m, frame, &q0, &target, via, &limits, &options)?;
    let report = motion.timing().report().clone();
    let speed = a.speed.map_or("no tool speed limit".to_string(), |v| {
        format!("tool speed ≤ {v} m/s")
    });
    let what = format!(
        "{kind} move of {}: {:.4} m and {:.4} rad, {} IK points, {speed}",
        m.frames()[frame].name,
        motion.path().length(),
        motion.path().angle(),
        motion.points()
    );
    Ok(Motion {
        trajectory: Box::new(motion),
        what,
        timing: Some((limits, report)),
        checked: None,
    })
}

/// Peak, RMS, limits and violations per joint (JSON keys and the table).
fn profile_report(
    a: &TorqueProfileArgs,
    m: &Model,
    p: &sim::ProfileSummary,
    motion: &Motion,
) -> Report {
    let (duration, what) = (motion.trajectory.duration(), &motion.what);
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
    if let Some((_, report)) = &motion.timing {
        let durations = report
            .durations
            .iter()
            .map(|(g, d)| (g.to_string(), Value::Scalar(*d)))
            .collect();
        let &(grid, _) = report.durations.last().expect("one grid at least");
        r.add("grid_intervals", Value::Count(grid))
            .add("grid_durations", Value::Map(durations))
            .add("max_limit_excess", Value::Scalar(report.max_excess));
    }
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
    let over: Vec<&str> = (0..j.len())
        .filter(|&i| p.violation_summary[i].is_some())
        .map(|i| j[i].as_str())
        .collect();
    let verdict = if over.is_empty() {
        "every joint stays within its effort limit".to_string()
    } else {
        format!("over the effort limit: {}", over.join(", "))
    };
    r.table = Some(format!(
        "torque profile ({}) on {}: {what}, {} s, {} samples every {} s\n{t}\n{verdict}\n",
        a.trajectory.name(),
        m.name(),
        fmt(duration),
        p.samples,
        a.dt
    ));
    r
}

/// Required torques against the effort limits, velocities and positions.
fn plot_profile(
    a: &TorqueProfileArgs,
    m: &Model,
    p: &sim::TorqueProfile,
    motion: &Motion,
    path: &Path,
) -> Result<(), CliError> {
    let duration = motion.trajectory.duration();
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
    let mut panels = vec![
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
    if let Some((limits, _)) = &motion.timing {
        // The limiting constraint along the motion: each kind's nearest joint, 1 = on the limit.
        let kinds = ["velocity", "acceleration", "torque"];
        let mut series: Vec<Series> = kinds
            .iter()
            .map(|k| Series {
                name: format!("{k} (max over joints of |value| / limit)"),
                points: Vec::with_capacity(rec.len()),
            })
            .collect();
        for k in 0..rec.len() {
            let f = limit_fractions(limits, &rec.v[k], &rec.a[k], &rec.tau[k]);
            for (s, x) in series.iter_mut().zip(f) {
                if x.is_finite() {
                    s.points.push((rec.t[k], x));
                }
            }
        }
        series.retain(|s| s.points.iter().any(|p| p.1 > 0.0));
        panels.insert(
            1,
            Panel {
                title: "Limiting constraint: fraction of each limit used".into(),
                y_label: "|value| / limit".into(),
                series,
                lines: vec![("limit".into(), 1.0)],
            },
        );
    }
    let kind = a.trajectory.name();
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
