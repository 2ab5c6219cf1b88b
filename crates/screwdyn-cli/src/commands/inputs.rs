//! What every command reads: the model (with its warnings), vectors and per-joint values given
//! as flags, external and tip wrenches, and the joint names its reports are labelled with.

use crate::args::ModelArgs;
use crate::output::{self};
use crate::CliError;
use nalgebra::{Vector3, Vector6};
use screwdyn::dynamics::ExternalWrenches;
use screwdyn::io::{LoadOptions, Loaded};
use screwdyn::Model;

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
    Ok(load_source(path, strict)?.model)
}

/// As [`load_model`], with the text and path the model was read from.
pub fn load_source(path: &str, strict: bool) -> Result<Loaded, CliError> {
    let loaded = screwdyn::io::load_source(path, &LoadOptions { strict })?;
    for f in loaded.model.physical_problems() {
        eprintln!("screwdyn: warning: {f}");
    }
    Ok(loaded)
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
    // `--q key:NAME` (and --q0, --qf): a named configuration of the model (an MJCF <key>).
    if let (Some(key), "q" | "q0" | "qf") = (text.strip_prefix("key:"), name) {
        return Ok(model.keyframe(key.trim())?.to_vec());
    }
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
        // Any link, one merged into its parent by a fixed joint included (the library moves
        // the wrench to the body that carries it).
        let (link, w, world) = parse_wrench(w, "--wrench")?;
        let frame = m.link_frame_id(&link)?;
        ext.add_on_link(m, frame, w, world)?;
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

/// The joint names, as labels shared by every report of the command.
pub fn names(m: &Model) -> output::Labels {
    output::labels(&m.joint_names())
}
