//! One module per family of commands; `run` dispatches. Shared here: model loading, vectors,
//! wrenches and the states of numeric commands (from flags or `--input states.csv`).

mod bench;
mod dynamics;
mod explain;
mod kinematics;
mod model;
mod sim;
mod view;

use crate::args::{Cli, Command, Common, ModelArgs};
use crate::output::{self, Report};
use crate::CliError;
use nalgebra::{Vector3, Vector6};
use screwdyn::dynamics::ExternalWrenches;
use screwdyn::io::LoadOptions;
use screwdyn::Model;
use std::path::Path;

/// Runs one command.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Info(a) => model::info(&a),
        Command::Check(a) => model::check(&a),
        Command::Export(a) => model::export(&a),
        Command::Fk(a) => kinematics::fk(&a),
        Command::Jacobian(a) => kinematics::jacobian(&a),
        Command::InverseDynamics(a) => dynamics::inverse_dynamics(&a),
        Command::MassMatrix(a) => dynamics::mass_matrix(&a),
        Command::Coriolis(a) => dynamics::coriolis(&a),
        Command::Gravity(a) => dynamics::gravity(&a),
        Command::NonlinearEffects(a) => dynamics::nonlinear_effects(&a),
        Command::Energy(a) => dynamics::energy(&a),
        Command::ForwardDynamics(a) => dynamics::forward_dynamics(&a),
        Command::ClosedForm(a) => dynamics::closed_form(&a),
        Command::Lagrange(a) => dynamics::lagrange(&a),
        Command::Explain(a) => explain::explain(&a),
        Command::Simulate(a) => sim::simulate(&a),
        Command::TorqueProfile(a) => sim::torque_profile(&a),
        Command::Bench(a) => bench::bench(&a),
        Command::View(a) => view::view(&a),
    }
}

/// Loads the model of `args` with `--gravity` applied; its physical-consistency problems are
/// warnings on stderr, one line each (errors with `--strict`).
pub fn load(args: &ModelArgs, gravity: Option<&str>) -> Result<Model, CliError> {
    let m = load_model(&args.model, args.strict)?;
    match gravity {
        None => Ok(m),
        Some(text) => {
            let g = parse_fixed(text, "--gravity", 3, "x,y,z")?;
            Ok(m.with_gravity(Vector3::new(g[0], g[1], g[2]))?)
        }
    }
}

/// Loads `path` (strict: findings are errors) and warns about each physical-consistency
/// finding on stderr.
pub fn load_model(path: &str, strict: bool) -> Result<Model, CliError> {
    let m = screwdyn::io::load_model_with(path, &LoadOptions { strict })?;
    for f in m.physical_problems() {
        eprintln!("screwdyn: warning: {f}");
    }
    Ok(m)
}

/// Comma-separated numbers given as `flag`, all finite.
pub fn parse_numbers(text: &str, flag: &str) -> Result<Vec<f64>, CliError> {
    let values = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| CliError::input(format!("{flag}: '{}' is not a number", s.trim())))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if let Some((i, x)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(CliError::input(format!(
            "{flag} contains a non-finite value ({x}) at position {i}"
        )));
    }
    Ok(values)
}

/// Exactly `n` comma-separated numbers (`what` names them for the message).
pub fn parse_fixed(text: &str, flag: &str, n: usize, what: &str) -> Result<Vec<f64>, CliError> {
    let v = parse_numbers(text, flag)?;
    if v.len() != n {
        return Err(CliError::input(format!(
            "{flag} needs {n} numbers {what}, got {} in '{text}'",
            v.len()
        )));
    }
    Ok(v)
}

/// A joint-space vector given as `--name`; `None` means all zeros.
pub fn parse_vector(text: Option<&str>, name: &str, model: &Model) -> Result<Vec<f64>, CliError> {
    let Some(text) = text else {
        return Ok(vec![0.0; model.nq()]);
    };
    let flag = format!("--{name}");
    let values = parse_numbers(text, &flag)?;
    model.check_vector(&values, &flag)?;
    Ok(values)
}

/// One value for every joint, or one per joint.
pub fn parse_per_joint(text: &str, name: &str, model: &Model) -> Result<Vec<f64>, CliError> {
    let flag = format!("--{name}");
    let v = parse_numbers(text, &flag)?;
    if v.len() == 1 {
        return Ok(vec![v[0]; model.nq()]);
    }
    model.check_vector(&v, &flag)?;
    Ok(v)
}

/// One state of the robot; the vectors a command does not use stay zero.
#[derive(Clone, Debug)]
pub struct State {
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
    pub tau: Vec<f64>,
}

/// The states to evaluate: one from the flags, or one per row of `--input`.
pub struct States {
    pub rows: Vec<State>,
    /// Where each state came from, for messages ("states.csv row 3").
    pub origin: Vec<String>,
    pub batch: bool,
}

/// Collects the states of a numeric command: `flags` are `(name, value)` of its vector flags.
pub fn states(
    m: &Model,
    common: &Common,
    flags: &[(&str, Option<&str>)],
) -> Result<States, CliError> {
    if let Some(path) = &common.input {
        if let Some((name, _)) = flags.iter().find(|(_, v)| v.is_some()) {
            return Err(CliError::input(format!(
                "--{name} cannot be combined with --input (give {name}.<joint> columns in {})",
                path.display()
            )));
        }
        let rows = read_states(m, path)?;
        let origin = (0..rows.len())
            .map(|k| format!("{} row {}", path.display(), k + 1))
            .collect();
        return Ok(States {
            rows,
            origin,
            batch: true,
        });
    }
    let mut s = State {
        q: vec![0.0; m.nq()],
        v: vec![0.0; m.nq()],
        a: vec![0.0; m.nq()],
        tau: vec![0.0; m.nq()],
    };
    for (name, text) in flags {
        let x = parse_vector(*text, name, m)?;
        match *name {
            "q" => s.q = x,
            "v" => s.v = x,
            "a" => s.a = x,
            "tau" => s.tau = x,
            _ => unreachable!("vector flags are q, v, a, tau"),
        }
    }
    Ok(States {
        rows: vec![s],
        origin: vec!["the command line".into()],
        batch: false,
    })
}

/// Reads `q.<joint>`, `v.<joint>`, `a.<joint>`, `tau.<joint>` columns; a missing column is zero.
fn read_states(m: &Model, path: &Path) -> Result<Vec<State>, CliError> {
    let file = path.display().to_string();
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| CliError::input(format!("{file}: cannot be read ({})", io_reason(&e))))?;
    let names = m.joint_names();
    let headers = reader
        .headers()
        .map_err(|e| CliError::input(format!("{file}: {}", io_reason(&e))))?
        .clone();
    // (slot 0..4 = q, v, a, tau; joint index) per column.
    let mut slots = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for h in headers.iter() {
        let slot = h.split_once('.').and_then(|(key, joint)| {
            let k = ["q", "v", "a", "tau"].iter().position(|x| *x == key)?;
            let j = names.iter().position(|n| *n == joint)?;
            Some((k, j))
        });
        let Some(slot) = slot else {
            return Err(CliError::input(format!(
                "{file}: unknown column '{h}' (expected q.<joint>, v.<joint>, a.<joint> or tau.<joint>, joints: {})",
                names.join(", ")
            )));
        };
        if !seen.insert(slot) {
            return Err(CliError::input(format!(
                "{file}: column '{h}' appears twice"
            )));
        }
        slots.push(slot);
    }
    let n = m.nq();
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| CliError::input(format!("{file}: {}", io_reason(&e))))?;
        let line = record.position().map(|p| p.line()).unwrap_or(0);
        let mut x = [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        for ((k, j), (cell, h)) in slots.iter().zip(record.iter().zip(headers.iter())) {
            let v: f64 = cell.parse().map_err(|_| {
                CliError::input(format!(
                    "{file}:{line}: column '{h}': '{cell}' is not a number"
                ))
            })?;
            if !v.is_finite() {
                return Err(CliError::input(format!(
                    "{file}:{line}: column '{h}' is not finite ({v})"
                )));
            }
            x[*k][*j] = v;
        }
        let [q, v, a, tau] = x;
        rows.push(State { q, v, a, tau });
    }
    if rows.is_empty() {
        return Err(CliError::input(format!("{file}: has no rows of states")));
    }
    Ok(rows)
}

fn io_reason(e: &csv::Error) -> String {
    match e.kind() {
        csv::ErrorKind::Io(io) => io.to_string(),
        csv::ErrorKind::UnequalLengths {
            pos,
            expected_len,
            len,
        } => format!(
            "line {} has {len} fields, the header has {expected_len}",
            pos.as_ref().map(|p| p.line()).unwrap_or(0)
        ),
        _ => e.to_string().replace('\n', " "),
    }
}

/// Evaluates `f` on every state and prints the reports in the chosen format.
pub fn run_states(
    m: &Model,
    common: &Common,
    flags: &[(&str, Option<&str>)],
    mut f: impl FnMut(&State) -> Result<Report, CliError>,
) -> Result<(), CliError> {
    let states = states(m, common, flags)?;
    let format = output::resolve(common.model.format);
    let mut reports = Vec::with_capacity(states.rows.len());
    for (s, origin) in states.rows.iter().zip(&states.origin) {
        let r = f(s).map_err(|e| {
            if states.batch {
                CliError {
                    code: e.code,
                    message: format!("{origin}: {}", e.message),
                }
            } else {
                e
            }
        })?;
        reports.push(r);
    }
    output::print(&reports, format, states.batch)
}

/// Parses `NAME:mx,my,mz,fx,fy,fz[@world]` into (name, wrench, in world).
pub fn parse_wrench(text: &str, flag: &str) -> Result<(String, Vector6<f64>, bool), CliError> {
    let Some((name, rest)) = text.rsplit_once(':') else {
        return Err(CliError::input(format!(
            "{flag} '{text}' must look like NAME:mx,my,mz,fx,fy,fz"
        )));
    };
    let (numbers, world) = match rest.strip_suffix("@world") {
        Some(r) => (r, true),
        None => (rest, false),
    };
    let w = parse_fixed(numbers, flag, 6, "mx,my,mz,fx,fy,fz (moment first)")?;
    Ok((
        name.trim().to_string(),
        Vector6::from_column_slice(&w),
        world,
    ))
}

/// The external wrenches of `--wrench` and `--tip-wrench`, or `None` when there are none.
pub fn external_wrenches(
    m: &Model,
    wrenches: &[String],
    tips: &[String],
) -> Result<Option<ExternalWrenches>, CliError> {
    if wrenches.is_empty() && tips.is_empty() {
        return Ok(None);
    }
    let mut ext = ExternalWrenches::new(m);
    for w in wrenches {
        let (body, w, world) = parse_wrench(w, "--wrench")?;
        let b = m.body_id(&body)?;
        if world {
            ext.add_world(b, w)?;
        } else {
            ext.add_local(b, w)?;
        }
    }
    for t in tips {
        let (frame, w, world) = parse_wrench(t, "--tip-wrench")?;
        if world {
            return Err(CliError::input(format!(
                "--tip-wrench '{t}': a tip wrench is written in its own frame, @world is not accepted"
            )));
        }
        let f = m.frame_id(&frame)?;
        ext.add_tip(m, f, w)?;
    }
    Ok(Some(ext))
}

/// The joint names as owned strings.
pub fn names(m: &Model) -> Vec<String> {
    m.joint_names().into_iter().map(String::from).collect()
}
