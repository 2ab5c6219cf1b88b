//! Runs to animate: the files `screwdyn simulate --output` and `screwdyn torque-profile
//! --output` write (CSV with columns `t`, `q.<joint>`, `v.<joint>`, `a.<joint>`,
//! `tau.<joint>`, `kinetic_energy`, `potential_energy`, `total_energy`, optionally
//! `pose.<frame>.x|y|z`; or JSON with the same names holding arrays), reduced to at most
//! `max_samples` evenly strided samples, with the joint-limit and effort-limit violations of
//! every sample (also of the samples dropped) kept.

use screwdyn::model::JointKind;
use screwdyn::sim::Recording;
use screwdyn::{Error, Model, Result};
use std::path::Path;

/// Bit of [`Run::flags`]: the joint is past a position limit.
pub const PAST_LIMIT: u8 = 1;
/// Bit of [`Run::flags`]: the joint's torque is past its effort limit.
pub const PAST_EFFORT: u8 = 2;

/// One kind of violation of one joint over a whole run.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// Joint index (model order).
    pub joint: usize,
    /// [`PAST_LIMIT`] or [`PAST_EFFORT`].
    pub kind: u8,
    /// Samples (of all those read) where it happens.
    pub count: usize,
    /// Time of the first.
    pub first_time: f64,
    /// The worst value: the position (for a limit) or the torque (for effort) furthest out.
    pub worst: f64,
}

/// A run ready to animate: at most `max_samples` samples in model joint order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Run {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// Joint positions per sample.
    pub q: Vec<Vec<f64>>,
    /// Joint torques per sample, when the run has them.
    pub tau: Option<Vec<Vec<f64>>>,
    /// Energy series present in the run: (name, values per sample).
    pub energy: Vec<(String, Vec<f64>)>,
    /// Per kept sample and joint: [`PAST_LIMIT`] | [`PAST_EFFORT`] bits, or-ed over the samples
    /// the decimation dropped since the previous kept one (a short violation is not lost).
    pub flags: Vec<Vec<u8>>,
    /// Violations summed over every sample read.
    pub violations: Vec<Violation>,
    /// Number of samples read (before decimation).
    pub samples_read: usize,
}

impl Run {
    /// The run's duration: last time minus first.
    pub fn duration(&self) -> f64 {
        match (self.t.first(), self.t.last()) {
            (Some(a), Some(b)) => b - a,
            _ => 0.0,
        }
    }

    /// A run from a library [`Recording`] (what `simulate` and `torque_profile` return).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the recording's joints are not the model's, it is empty,
    /// or its times decrease.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// let mut rec = screwdyn::sim::Recording::new(vec!["joint1".into(), "joint2".into()], vec![]);
    /// for k in 0..5 {
    ///     rec.t.push(k as f64);
    ///     rec.q.push(vec![0.1 * k as f64, 0.0]);
    ///     rec.tau.push(vec![0.0; 2]);
    ///     rec.kinetic_energy.push(0.0);
    ///     rec.potential_energy.push(0.0);
    ///     rec.total_energy.push(0.0);
    /// }
    /// let run = screwdyn_view::Run::from_recording(&rec, &m, 3).unwrap();
    /// assert_eq!(run.t, vec![0.0, 2.0, 4.0]);
    /// assert_eq!(run.duration(), 4.0);
    /// ```
    pub fn from_recording(rec: &Recording, model: &Model, max_samples: usize) -> Result<Run> {
        let names = model.joint_names();
        if rec.joints.iter().map(String::as_str).collect::<Vec<_>>() != names {
            return Err(Error::InvalidArgument(format!(
                "the run's joints ({}) are not the model's ({})",
                rec.joints.join(", "),
                names.join(", ")
            )));
        }
        let mut b = Builder::new(model, rec.len(), max_samples, true, "the recording")?;
        for k in 0..rec.len() {
            let e = [
                rec.kinetic_energy[k],
                rec.potential_energy[k],
                rec.total_energy[k],
            ];
            b.push(rec.t[k], &rec.q[k], Some(&rec.tau[k]), &e, k + 1)?;
        }
        b.energy_names = ENERGIES.iter().map(|s| s.to_string()).collect();
        b.finish()
    }
}

const ENERGIES: [&str; 3] = ["kinetic_energy", "potential_energy", "total_energy"];

/// Collects samples one at a time, keeping every `stride`-th (and the last).
struct Builder<'m> {
    model: &'m Model,
    stride: usize,
    rows: usize,
    seen: usize,
    run: Run,
    pending: Vec<u8>,
    has_tau: bool,
    energy_names: Vec<String>,
    what: String,
}

impl<'m> Builder<'m> {
    fn new(
        model: &'m Model,
        rows: usize,
        max_samples: usize,
        has_tau: bool,
        what: &str,
    ) -> Result<Self> {
        if rows == 0 {
            return Err(Error::InvalidArgument(format!("{what} has no samples")));
        }
        if max_samples < 2 {
            return Err(Error::InvalidArgument(format!(
                "the sample cap must be at least 2 (got {max_samples})"
            )));
        }
        // Keep rows 0, s, 2s, … and the last: at most max_samples.
        let stride = (rows - 1).div_ceil(max_samples - 1).max(1);
        Ok(Builder {
            model,
            stride,
            rows,
            seen: 0,
            run: Run {
                tau: has_tau.then(Vec::new),
                ..Default::default()
            },
            pending: vec![0; model.nq()],
            has_tau,
            energy_names: Vec::new(),
            what: what.into(),
        })
    }

    fn violate(&mut self, joint: usize, kind: u8, t: f64, value: f64) {
        self.pending[joint] |= kind;
        match self
            .run
            .violations
            .iter_mut()
            .find(|v| v.joint == joint && v.kind == kind)
        {
            Some(v) => {
                v.count += 1;
                if value.abs() > v.worst.abs() {
                    v.worst = value;
                }
            }
            None => self.run.violations.push(Violation {
                joint,
                kind,
                count: 1,
                first_time: t,
                worst: value,
            }),
        }
    }

    fn push(
        &mut self,
        t: f64,
        q: &[f64],
        tau: Option<&[f64]>,
        energy: &[f64],
        row: usize,
    ) -> Result<()> {
        if let Some(&last) = self.run.t.last() {
            if t < last {
                return Err(Error::InvalidArgument(format!(
                    "{} sample {row}: time {t} is before the previous sample's {last}",
                    self.what
                )));
            }
        }
        for (i, j) in self.model.joints().iter().enumerate() {
            let limited = !matches!(j.kind, JointKind::Continuous);
            if limited && (q[i] < j.limits.lower - 1e-9 || q[i] > j.limits.upper + 1e-9) {
                self.violate(i, PAST_LIMIT, t, q[i]);
            }
            if let Some(tau) = tau {
                if tau[i].abs() > j.limits.effort * (1.0 + 1e-9) {
                    self.violate(i, PAST_EFFORT, t, tau[i]);
                }
            }
        }
        let k = self.seen;
        self.seen += 1;
        if k % self.stride == 0 || k + 1 == self.rows {
            self.run.t.push(t);
            self.run.q.push(q.to_vec());
            if let (Some(all), Some(tau)) = (self.run.tau.as_mut(), tau) {
                all.push(tau.to_vec());
            }
            if self.run.energy.is_empty() {
                self.run.energy = vec![(String::new(), Vec::new()); energy.len()];
            }
            for (s, e) in self.run.energy.iter_mut().zip(energy) {
                s.1.push(*e);
            }
            self.run
                .flags
                .push(std::mem::replace(&mut self.pending, vec![0; q.len()]));
        }
        Ok(())
    }

    fn finish(mut self) -> Result<Run> {
        if self.seen == 0 {
            return Err(Error::InvalidArgument(format!(
                "{} has no samples",
                self.what
            )));
        }
        for (s, n) in self.run.energy.iter_mut().zip(&self.energy_names) {
            s.0 = n.clone();
        }
        if !self.has_tau {
            self.run.tau = None;
        }
        self.run.samples_read = self.seen;
        Ok(self.run)
    }
}

/// What a column of a run file holds.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Col {
    T,
    Q(usize),
    Tau(usize),
    Energy(usize),
    Other,
}

/// Classifies the column names of a run against the model's joints.
fn columns(names: &[&str], model: &Model, file: &str) -> Result<(Vec<Col>, bool, Vec<String>)> {
    let joints = model.joint_names();
    let mut cols = Vec::new();
    for h in names {
        let col = if *h == "t" {
            Col::T
        } else if let Some(e) = ENERGIES.iter().position(|e| e == h) {
            Col::Energy(e)
        } else if let Some((key, joint)) = h.split_once('.') {
            if ["q", "v", "a", "tau"].contains(&key) {
                let j = joints.iter().position(|n| *n == joint).ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "{file}: the run's column '{h}' names joint '{joint}', which the model does not have (model joints: {})",
                        joints.join(", ")
                    ))
                })?;
                match key {
                    "q" => Col::Q(j),
                    "tau" => Col::Tau(j),
                    _ => Col::Other,
                }
            } else {
                Col::Other
            }
        } else {
            Col::Other
        };
        cols.push(col);
    }
    if !cols.contains(&Col::T) {
        return Err(Error::InvalidArgument(format!(
            "{file}: the run has no column 't'"
        )));
    }
    let missing: Vec<&str> = (0..model.nq())
        .filter(|j| !cols.contains(&Col::Q(*j)))
        .map(|j| joints[j])
        .collect();
    if !missing.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "{file}: the run has no position column for joint(s) {} of the model (expected q.<joint> columns for {})",
            missing.join(", "),
            joints.join(", ")
        )));
    }
    let has_tau = cols.iter().any(|c| matches!(c, Col::Tau(_)));
    let energy: Vec<String> = ENERGIES
        .iter()
        .enumerate()
        .filter(|(e, _)| cols.contains(&Col::Energy(*e)))
        .map(|(_, n)| n.to_string())
        .collect();
    // Energy columns numbered by their slot in `energy` (the order of ENERGIES).
    for c in cols.iter_mut() {
        if let Col::Energy(e) = *c {
            *c = Col::Energy(energy.iter().position(|n| n == ENERGIES[e]).unwrap_or(0));
        }
    }
    Ok((cols, has_tau, energy))
}

/// Reads a run file (`.csv` or `.json`, see the module documentation) for `model`, keeping at
/// most `max_samples` samples. A CSV file is streamed twice (count, then read), so memory does
/// not grow with its length; a JSON file is read whole.
///
/// # Errors
/// [`Error::Io`] when the file cannot be read; [`Error::InvalidArgument`] (one sentence naming
/// the file) when its joints do not match the model's, a column is missing, a value is not a
/// finite number, times decrease or there are no samples.
pub fn read_run(path: &Path, model: &Model, max_samples: usize) -> Result<Run> {
    let file = path.display().to_string();
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "csv" => read_csv(path, &file, model, max_samples),
        "json" => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| Error::unreadable(path, &e))?;
            read_json(&text, &file, model, max_samples)
        }
        _ => Err(Error::InvalidArgument(format!(
            "{file}: a run must be a .csv or .json file (as written by simulate --output or torque-profile --output)"
        ))),
    }
}

fn csv_error(file: &str, e: csv::Error) -> Error {
    match e.kind() {
        csv::ErrorKind::Io(io) => Error::unreadable(file, io),
        _ => Error::InvalidArgument(format!("{file}: {}", e.to_string().replace('\n', " "))),
    }
}

fn read_csv(path: &Path, file: &str, model: &Model, max_samples: usize) -> Result<Run> {
    let open = || {
        csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_path(path)
            .map_err(|e| csv_error(file, e))
    };
    let mut reader = open()?;
    let headers = reader.headers().map_err(|e| csv_error(file, e))?.clone();
    let names: Vec<&str> = headers.iter().collect();
    let (cols, has_tau, energy_names) = columns(&names, model, file)?;
    let mut record = csv::StringRecord::new();
    let mut rows = 0;
    while reader
        .read_record(&mut record)
        .map_err(|e| csv_error(file, e))?
    {
        rows += 1;
    }
    let mut b = Builder::new(model, rows, max_samples, has_tau, file)?;
    b.energy_names = energy_names.clone();
    let mut reader = open()?;
    let n = model.nq();
    let (mut q, mut tau) = (vec![0.0; n], vec![0.0; n]);
    let mut energy = vec![0.0; energy_names.len()];
    let mut row = 0;
    while reader
        .read_record(&mut record)
        .map_err(|e| csv_error(file, e))?
    {
        row += 1;
        let line = record.position().map_or(row + 1, |p| p.line() as usize);
        let mut t = 0.0;
        for ((c, cell), h) in cols.iter().zip(record.iter()).zip(&names) {
            if *c == Col::Other {
                continue;
            }
            let x: f64 = cell
                .parse()
                .ok()
                .filter(|x: &f64| x.is_finite())
                .ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "{file}:{line}: column '{h}': '{cell}' is not a finite number"
                    ))
                })?;
            match *c {
                Col::T => t = x,
                Col::Q(j) => q[j] = x,
                Col::Tau(j) => tau[j] = x,
                Col::Energy(e) => energy[e] = x,
                Col::Other => {}
            }
        }
        b.push(t, &q, has_tau.then_some(&tau[..]), &energy, line)?;
    }
    b.finish()
}

/// Reads a JSON run (an object of arrays, as `simulate --output run.json` writes).
///
/// # Errors
/// As [`read_run`].
///
/// ```
/// let m = screwdyn::builtin::planar2();
/// let text = r#"{"t": [0, 1], "q.joint1": [0, 1], "q.joint2": [0, 0]}"#;
/// let run = screwdyn_view::run::read_json(text, "r.json", &m, 1000).unwrap();
/// assert_eq!(run.q[1], vec![1.0, 0.0]);
/// let bad = r#"{"t": [0], "q.elbow": [0]}"#;
/// assert!(screwdyn_view::run::read_json(bad, "r.json", &m, 1000).unwrap_err().to_string().contains("'elbow'"));
/// ```
pub fn read_json(text: &str, file: &str, model: &Model, max_samples: usize) -> Result<Run> {
    let v: serde_json::Value = serde_json::from_str(text)
        .map_err(|e| Error::InvalidArgument(format!("{file}: is not valid JSON ({e})")))?;
    let obj = v.as_object().ok_or_else(|| {
        Error::InvalidArgument(format!(
            "{file}: a JSON run must be an object of arrays (t, q.<joint>, …)"
        ))
    })?;
    if let Some(j) = obj.get("joints").and_then(|j| j.as_array()) {
        let theirs: Vec<&str> = j.iter().filter_map(|x| x.as_str()).collect();
        let mut a = theirs.clone();
        let mut b = model.joint_names();
        a.sort_unstable();
        b.sort_unstable();
        if a != b {
            return Err(Error::InvalidArgument(format!(
                "{file}: the run's joints ({}) are not the model's ({})",
                theirs.join(", "),
                model.joint_names().join(", ")
            )));
        }
    }
    let names: Vec<&str> = obj
        .iter()
        .filter(|(_, v)| {
            v.as_array()
                .is_some_and(|a| a.iter().all(|x| x.is_number()))
                && !v.as_array().unwrap().is_empty()
        })
        .map(|(k, _)| k.as_str())
        .filter(|k| *k != "joints")
        .collect();
    let (cols, has_tau, energy_names) = columns(&names, model, file)?;
    let series: Vec<Vec<f64>> = names
        .iter()
        .map(|k| {
            obj[*k]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    let rows = series[cols.iter().position(|c| *c == Col::T).unwrap()].len();
    if let Some((k, _)) = series
        .iter()
        .enumerate()
        .find(|(k, s)| s.len() != rows && cols[*k] != Col::Other)
    {
        return Err(Error::InvalidArgument(format!(
            "{file}: the array '{}' has {} values, 't' has {rows}",
            names[k],
            series[k].len()
        )));
    }
    let mut b = Builder::new(model, rows, max_samples, has_tau, file)?;
    b.energy_names = energy_names.clone();
    let n = model.nq();
    let (mut q, mut tau) = (vec![0.0; n], vec![0.0; n]);
    let mut energy = vec![0.0; energy_names.len()];
    #[allow(clippy::needless_range_loop)] // r indexes every column of `series`
    for r in 0..rows {
        let mut t = 0.0;
        for (k, c) in cols.iter().enumerate() {
            if *c == Col::Other {
                continue;
            }
            let x = series[k][r];
            if !x.is_finite() {
                return Err(Error::InvalidArgument(format!(
                    "{file}: '{}'[{r}] is not a finite number",
                    names[k]
                )));
            }
            match *c {
                Col::T => t = x,
                Col::Q(j) => q[j] = x,
                Col::Tau(j) => tau[j] = x,
                Col::Energy(e) => energy[e] = x,
                Col::Other => {}
            }
        }
        b.push(t, &q, has_tau.then_some(&tau[..]), &energy, r + 1)?;
    }
    b.finish()
}
