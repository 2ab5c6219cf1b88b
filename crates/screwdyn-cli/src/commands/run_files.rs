//! What `simulate` and `torque-profile` share: the kinds of their output and plot files, the
//! run writer (CSV or JSON), outputs refused when they are inputs, plot series, and the flag
//! wording of the library's option errors.

use crate::args::Format;
use crate::plot::Series;
use crate::write::{self};
use crate::CliError;
use screwdyn::sim::{self, Recording, SampleSink};
use std::path::Path;

/// Whether `path` is a run file (`.csv` / `.json`): checked before any work is done.
pub(super) fn run_file_kind(path: &Path, flag: &str) -> Result<Format, CliError> {
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

pub(super) fn plot_kind(path: &Path) -> Result<(), CliError> {
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

/// A streaming writer of a run.
pub(super) enum RunWriter {
    Csv(sim::CsvSampleWriter<Box<dyn std::io::Write>>),
    Json(sim::JsonSampleWriter<Box<dyn std::io::Write>>),
}

impl RunWriter {
    pub(super) fn new(kind: Format, out: Box<dyn std::io::Write>) -> Self {
        match kind {
            Format::Json => RunWriter::Json(sim::JsonSampleWriter::new(out)),
            _ => RunWriter::Csv(sim::CsvSampleWriter::new(out)),
        }
    }
    pub(super) fn sink(&mut self) -> &mut dyn SampleSink {
        match self {
            RunWriter::Csv(w) => w,
            RunWriter::Json(w) => w,
        }
    }
    /// Completes the file (flushes the CSV, assembles the JSON object).
    pub(super) fn finish(self) -> screwdyn::Result<()> {
        match self {
            RunWriter::Csv(mut w) => w.flush(),
            RunWriter::Json(w) => w.finish().map(|_| ()),
        }
    }
}

/// Refuses `--output` / `--plot` onto an input of the command (the model file, `extra`).
pub(super) fn refuse_onto_inputs(
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

pub(super) fn joint_series(rec: &Recording, x: &[Vec<f64>]) -> Vec<Series> {
    rec.joints
        .iter()
        .enumerate()
        .map(|(i, name)| Series {
            name: name.clone(),
            points: rec.t.iter().zip(x).map(|(t, r)| (*t, r[i])).collect(),
        })
        .collect()
}

pub(super) fn scalar_series(rec: &Recording, name: &str, x: &[f64]) -> Series {
    Series {
        name: name.into(),
        points: rec.t.iter().copied().zip(x.iter().copied()).collect(),
    }
}

/// A library error about a setting (`dt must be positive (got 0); …`) worded with the flag
/// that sets it (`--dt must be positive (got 0); …`); other errors as they are.
pub(super) fn in_flag_words(e: screwdyn::Error) -> CliError {
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
