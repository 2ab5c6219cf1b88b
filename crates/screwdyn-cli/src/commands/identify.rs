//! `identify`: inertial parameters from a log of states and torques, and exciting logs to record
//! (issue 15). The library does the work; this reads the log, calls and prints.

use super::inputs::{load, names};
use crate::args::IdentifyArgs;
use crate::output::{self, Report, Value};
use crate::plot::{plot_panels, Panel, Series};
use crate::CliError;
use screwdyn::identification::{
    excitation_log, BaseParameters, FourierTrajectory, LeastSquares, Residuals,
    VelocityDifferentiator,
};
use screwdyn::Model;
use std::io::Write;
use std::path::Path;

/// Column indices of a log.
struct LogColumns {
    t: Option<usize>,
    q: Vec<usize>,
    v: Vec<usize>,
    a: Option<Vec<usize>>,
    tau: Vec<usize>,
}

fn open_log(path: &Path) -> Result<csv::Reader<std::fs::File>, CliError> {
    csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| CliError::input(format!("{}: cannot be read ({e})", path.display())))
}

fn log_columns(
    m: &Model,
    path: &Path,
    headers: &csv::StringRecord,
) -> Result<LogColumns, CliError> {
    let file = path.display();
    let find = |name: &str| headers.iter().position(|h| h == name);
    let joints = m.joint_names();
    let need = |key: &str| -> Result<Vec<usize>, CliError> {
        joints
            .iter()
            .map(|j| {
                find(&format!("{key}.{j}")).ok_or_else(|| {
                    CliError::input(format!(
                        "{file}: the log has no column '{key}.{j}' (it needs t, q.<joint>, \
                         v.<joint>, tau.<joint> and optionally a.<joint> for joints {})",
                        joints.join(", ")
                    ))
                })
            })
            .collect()
    };
    let any_a = joints.iter().any(|j| find(&format!("a.{j}")).is_some());
    let cols = LogColumns {
        t: find("t"),
        q: need("q")?,
        v: need("v")?,
        a: if any_a { Some(need("a")?) } else { None },
        tau: need("tau")?,
    };
    if cols.a.is_none() && cols.t.is_none() {
        return Err(CliError::input(format!(
            "{file}: without a.<joint> columns the accelerations are differentiated from the \
             velocities, which needs a time column 't'"
        )));
    }
    Ok(cols)
}

/// One sample of a log: (t, q, v, a, tau).
type Sample = (f64, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// Streams the samples of a log (differentiating velocities when it has no accelerations) into
/// `f`; returns the number of samples passed.
fn for_each_sample(
    m: &Model,
    path: &Path,
    window: usize,
    mut f: impl FnMut(Sample) -> Result<(), CliError>,
) -> Result<usize, CliError> {
    let file = path.display().to_string();
    let mut reader = open_log(path)?;
    let headers = reader
        .headers()
        .map_err(|e| CliError::input(format!("{file}: {e}")))?
        .clone();
    let cols = log_columns(m, path, &headers)?;
    let mut diff = match cols.a {
        None => Some(VelocityDifferentiator::new(window)?),
        Some(_) => None,
    };
    let mut count = 0;
    for record in reader.records() {
        let record = record.map_err(|e| CliError::input(format!("{file}: {e}")))?;
        let line = record.position().map(|p| p.line()).unwrap_or(0);
        let cell = |c: usize| -> Result<f64, CliError> {
            let text = record.get(c).unwrap_or("");
            let x: f64 = text.parse().map_err(|_| {
                CliError::input(format!(
                    "{file}:{line}: column '{}': '{text}' is not a number",
                    &headers[c]
                ))
            })?;
            if !x.is_finite() {
                return Err(CliError::input(format!(
                    "{file}:{line}: column '{}' is not finite ({x})",
                    &headers[c]
                )));
            }
            Ok(x)
        };
        let pick = |cs: &[usize]| cs.iter().map(|&c| cell(c)).collect::<Result<Vec<_>, _>>();
        let t = match cols.t {
            Some(c) => cell(c)?,
            None => count as f64,
        };
        let (q, v, tau) = (pick(&cols.q)?, pick(&cols.v)?, pick(&cols.tau)?);
        match (&cols.a, diff.as_mut()) {
            (Some(ac), _) => {
                let a = pick(ac)?;
                f((t, q, v, a, tau))?;
                count += 1;
            }
            (None, Some(d)) => {
                let out = d
                    .push(t, &q, &v, &tau)
                    .map_err(|e| CliError::input(format!("{file}:{line}: {e}")))?;
                if let Some(s) = out {
                    f((s.t, s.q, s.v, s.a, s.tau))?;
                    count += 1;
                }
            }
            (None, None) => unreachable!("a differentiator exists when a.* is absent"),
        }
    }
    Ok(count)
}

/// `identify --excite --output log.csv`: writes an exciting trajectory log.
fn excite(m: &Model, a: &IdentifyArgs) -> Result<(), CliError> {
    let Some(path) = &a.output else {
        return Err(CliError::input(
            "--excite writes a log: give --output LOG.csv",
        ));
    };
    if path.extension().and_then(|e| e.to_str()) != Some("csv") {
        return Err(CliError::input(format!(
            "--output {}: the file name must end in .csv",
            path.display()
        )));
    }
    if !(a.frequency > 0.0 && a.frequency.is_finite()) {
        return Err(CliError::input(format!(
            "--frequency must be a positive number of Hz, not {}",
            a.frequency
        )));
    }
    let traj = FourierTrajectory::random(
        m,
        a.harmonics,
        2.0 * std::f64::consts::PI * a.frequency,
        a.seed,
    )?;
    let fail =
        |e: std::io::Error| CliError::input(format!("cannot write {} ({e})", path.display()));
    let j = m.joint_names();
    let mut header = vec!["t".to_string()];
    for key in ["q", "v", "a", "tau"] {
        header.extend(j.iter().map(|n| format!("{key}.{n}")));
    }
    let mut rows = 0usize;
    crate::write::atomic(path, |out| {
        writeln!(out, "{}", header.join(",")).map_err(fail)?;
        excitation_log(
            m,
            &traj,
            a.duration,
            a.rate,
            a.noise,
            a.seed,
            |t, q, v, acc, tau| {
                let mut line = format!("{t:?}");
                for x in q.iter().chain(v).chain(acc).chain(tau) {
                    line.push_str(&format!(",{x:?}"));
                }
                rows += 1;
                writeln!(out, "{line}").map_err(fail)
            },
        )
    })?;
    output::write_stdout(&format!(
        "wrote {rows} samples of a {}-harmonic Fourier trajectory ({} Hz base frequency) to {}\n",
        a.harmonics,
        a.frequency,
        path.display()
    ))
}

/// `identify MODEL --input log.csv`: base parameters by least squares.
pub fn identify(a: &IdentifyArgs) -> Result<(), CliError> {
    let m = load(&a.model, a.gravity.as_deref())?;
    if a.excite {
        if a.input.is_some() {
            return Err(CliError::input(
                "--excite writes a new log and --input reads one: give only one of them",
            ));
        }
        return excite(&m, a);
    }
    let Some(path) = &a.input else {
        return Err(CliError::input(
            "identify needs a log: --input LOG.csv (or --excite --output LOG.csv to make one)",
        ));
    };
    if path == Path::new("-") {
        // The log is read twice (the estimate, then the residuals of every sample).
        return Err(CliError::input(
            "identify reads its log twice, so --input must name a file, not standard input ('-')",
        ));
    }
    if let Some(p) = &a.plot {
        let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
        if ext != "png" && ext != "svg" {
            return Err(CliError::input(format!(
                "--plot {}: the file name must end in .png or .svg",
                p.display()
            )));
        }
    }
    let base = BaseParameters::with_defaults(&m, a.friction)?;
    let mut ls = LeastSquares::new(&m, base.clone());
    let file = path.display().to_string();
    let samples = for_each_sample(&m, path, a.window, |(_, q, v, acc, tau)| {
        ls.add(&m, &q, &v, &acc, &tau)?;
        Ok(())
    })?;
    if samples == 0 {
        return Err(CliError::input(format!(
            "{file}: the log has no usable samples"
        )));
    }
    let est = ls
        .solve()
        .map_err(|e| CliError::input(format!("{file}: {e}")))?;
    let physical = if a.physical {
        Some(ls.physical_estimate(&m)?)
    } else {
        None
    };
    let values = physical
        .as_ref()
        .map_or(&est.values, |p| &p.base_values)
        .clone();
    // Second pass: residuals per joint (and the plot data).
    let mut res = Residuals::new(&m, &base);
    let mut pred = vec![0.0; m.nv()];
    let mut plot_data: Vec<(f64, Vec<f64>)> = Vec::new();
    let want_plot = a.plot.is_some();
    for_each_sample(&m, path, a.window, |(t, q, v, acc, tau)| {
        res.add(&m, &base, &values, &q, &v, &acc, &tau, &mut pred)?;
        if want_plot {
            plot_data.push((t, tau.iter().zip(&pred).map(|(x, p)| x - p).collect()));
        }
        Ok(())
    })?;
    let j = names(&m);
    let rms = res.rms();
    if let Some(p) = &a.plot {
        let series = j
            .iter()
            .enumerate()
            .map(|(i, n)| Series {
                name: n.clone(),
                points: plot_data.iter().map(|(t, e)| (*t, e[i])).collect(),
            })
            .collect();
        let panels = [Panel {
            title: "Torque residual τ − Y_b π̂_b".into(),
            y_label: "residual (N·m or N)".into(),
            series,
            lines: vec![],
        }];
        plot_panels(
            p,
            &format!("identify {}: {file}", m.name()),
            "t (s)",
            &panels,
        )?;
    }
    let exprs = base.expressions();
    let mut items = Vec::new();
    for (k, e) in exprs.iter().enumerate() {
        let mut entry = vec![
            ("value".to_string(), Value::Scalar(values[k])),
            ("std_dev".to_string(), Value::Scalar(est.std_dev[k])),
        ];
        if physical.is_some() {
            entry.push(("unconstrained".to_string(), Value::Scalar(est.values[k])));
        }
        items.push((e.clone(), Value::Map(entry)));
    }
    let mut r = Report::new();
    r.add("joints", Value::Names(j.clone()))
        .add("samples", Value::Count(samples))
        .add("condition_number", Value::Scalar(est.condition_number))
        .add("sigma", Value::Scalar(est.sigma))
        .add("residual_rms", Value::joints(&j, &rms))
        .add(
            "physical",
            Value::Text(if a.physical { "yes" } else { "no" }.into()),
        )
        .add("base_parameters", Value::Map(items));
    let mut t = format!(
        "{} base parameters from {samples} samples of {file}{}\n\
         condition number of the regressor: {}\n\
         σ (RMS torque residual, all joints): {}\n\n",
        base.rank(),
        if a.physical {
            " (physically consistent estimate)"
        } else {
            ""
        },
        output::fmt(est.condition_number),
        output::fmt(est.sigma)
    );
    t.push_str(&format!(
        "{:>14} {:>12}  base parameter\n",
        "estimate", "std dev"
    ));
    for (k, e) in exprs.iter().enumerate() {
        t.push_str(&format!(
            "{:>14} {:>12}  {e}\n",
            output::fmt(values[k]),
            output::fmt(est.std_dev[k])
        ));
    }
    t.push_str("\ntorque residual per joint (RMS):\n");
    for (n, x) in j.iter().zip(&rms) {
        t.push_str(&format!("  {n:<24} {}\n", output::fmt(*x)));
    }
    r.table = Some(t);
    output::print(&[r], output::resolve(a.model.format), false)
}
