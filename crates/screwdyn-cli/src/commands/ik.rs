//! `ik`: the joint positions that put a frame at a target pose, for one target given by flags or
//! for every row of `--input targets.csv`, streamed in chunks solved on `--threads` threads.

use super::inputs::{load, names, parse_fixed, parse_vector};
use super::states::{open_text, shorten, split_cells, InputSource, TextOnly};
use crate::args::{Format, IkArgs};
use crate::output::{self, Labels, Report, ReportWriter, Value};
use crate::CliError;
use nalgebra::{DMatrix, Vector3};
use screwdyn::kinematics::ik::{
    default_start, target_from_quaternion, IkOptions, IkResult, IkSolver, IkTask, IkWorkspace,
};
use screwdyn::spatial::Se3;
use screwdyn::Model;
use std::io::{BufRead, Write};
use std::path::Path;

/// Rows read, solved and written at a time: the memory of a batch is bounded by one chunk.
const CHUNK_ROWS: usize = 512;

/// `screwdyn ik MODEL --frame NAME (--target … | --position … | --input …)`.
pub fn ik(a: &IkArgs) -> Result<(), CliError> {
    let m = load(&a.model, None)?;
    let frame = m.frame_id(&a.frame)?;
    let q0 = match &a.q0 {
        Some(_) => parse_vector(a.q0.as_deref(), "q0", &m)?,
        None => default_start(&m),
    };
    let defaults = IkOptions::default();
    let options = IkOptions {
        seed: a.seed,
        position_tolerance: a.position_tolerance.unwrap_or(defaults.position_tolerance),
        orientation_tolerance: a
            .orientation_tolerance
            .unwrap_or(defaults.orientation_tolerance),
        max_restarts: a.max_restarts.unwrap_or(defaults.max_restarts),
        ..defaults
    };
    let given = [
        ("--target", a.target.is_some()),
        ("--position", a.position.is_some()),
        ("--input", a.input.is_some()),
    ];
    let chosen: Vec<&str> = given.iter().filter(|g| g.1).map(|g| g.0).collect();
    if chosen.len() != 1 {
        return Err(CliError::input(format!(
            "ik needs exactly one of --target x,y,z,qw,qx,qy,qz, --position x,y,z or --input TARGETS.CSV{}",
            if chosen.is_empty() {
                String::new()
            } else {
                format!(" (got {})", chosen.join(" and "))
            }
        )));
    }
    if a.threads == Some(0) {
        return Err(CliError::input("--threads must be at least 1"));
    }
    if let Some(path) = &a.input {
        if a.all {
            return Err(CliError::input(
                "--all (every closed-form solution) takes one --target, not --input",
            ));
        }
        return batch(a, &m, frame, &q0, options, path);
    }
    if a.output.is_some() {
        return Err(CliError::input(
            "--output is for --input batches; one target is printed to stdout",
        ));
    }
    let (target, task) = match (&a.target, &a.position) {
        (Some(text), _) => {
            let v = parse_fixed(text, "--target", 7, "x,y,z,qw,qx,qy,qz")?;
            let pose =
                target_from_quaternion([v[0], v[1], v[2]], [v[3], v[4], v[5], v[6]], "--target")?;
            (pose, IkTask::pose(frame))
        }
        (None, Some(text)) => {
            let v = parse_fixed(text, "--position", 3, "x,y,z")?;
            let pose = Se3::from_translation(Vector3::new(v[0], v[1], v[2]));
            (pose, IkTask::position(frame))
        }
        (None, None) => unreachable!("one of --target, --position and --input was checked"),
    };
    if a.all {
        if a.position.is_some() {
            return Err(CliError::input(
                "--all (every closed-form solution) needs a full pose: give --target, not --position",
            ));
        }
        return all_solutions(&m, frame, &target, &q0, options, a.model.format);
    }
    let solver = IkSolver::new(&m, &[task], options)?;
    let mut ws = IkWorkspace::new(&solver);
    let mut q = vec![0.0; m.nq()];
    let result = solver.solve(&mut ws, &[target], &q0, &mut q)?;
    let mut r = Report::new();
    r.add("joints", Value::Names(names(&m)));
    add_result(&mut r, &names(&m), &q, &result);
    output::print(&[r], output::resolve(a.model.format), false)
}

/// `q`, `success`, `iterations`, `restarts`, `position_error`, `orientation_error` and
/// `failure` (`none` on success).
fn add_result(r: &mut Report, joints: &Labels, q: &[f64], result: &IkResult) {
    r.add("q", Value::joints(joints, q))
        .add("success", Value::Flag(result.success))
        .add("iterations", Value::Count(result.iterations))
        .add("restarts", Value::Count(result.restarts))
        .add("position_error", Value::Scalar(result.position_error))
        .add("orientation_error", Value::Scalar(result.orientation_error))
        .add(
            "failure",
            Value::Text(result.failure.map_or("none", |f| f.name()).into()),
        );
}

/// `--all`: every closed-form solution within the joint limits (the one numerical answer for
/// an arm without a closed form), nearest `q0` first.
fn all_solutions(
    m: &Model,
    frame: usize,
    target: &Se3,
    q0: &[f64],
    options: IkOptions,
    format: Option<Format>,
) -> Result<(), CliError> {
    let solver = IkSolver::new(m, &[IkTask::pose(frame)], options)?;
    let mut ws = IkWorkspace::new(&solver);
    let all = solver.solve_all(&mut ws, target, q0)?;
    let joints = names(m);
    let family = solver.closed_form().map_or("none", |cf| cf.family().name());
    let rows: Labels = (1..=all.len()).map(|k| k.to_string()).collect();
    let q = DMatrix::from_fn(all.len(), joints.len(), |r, c| all[r].q[c]);
    let worst = |f: fn(&IkResult) -> f64| all.iter().map(|s| f(&s.result)).fold(0.0, f64::max);
    let mut r = Report::new();
    r.add("joints", Value::Names(joints.clone()))
        .add("closed_form", Value::Text(family.into()))
        .add("count", Value::Count(all.len()))
        .add("solutions", Value::Matrix(rows, joints, q))
        .add("position_error", Value::Scalar(worst(|r| r.position_error)))
        .add(
            "orientation_error",
            Value::Scalar(worst(|r| r.orientation_error)),
        );
    output::print(&[r], output::resolve(format), false)
}

/// One row of `--input`: its line, the target and the start (or why the row is bad).
struct Row {
    line: u64,
    target: Se3,
    q0: Vec<f64>,
    bad: Option<String>,
}

/// The columns of a targets file: `x,y,z`, then `qw,qx,qy,qz` (all or none) and `q0.<joint>`.
struct Columns {
    /// Per column: 0–2 position, 3–6 quaternion, 7 + j the start of joint j.
    slots: Vec<usize>,
    headers: Vec<String>,
    /// Whether the quaternion columns are there (else the targets are positions only).
    oriented: bool,
}

impl Columns {
    fn parse(file: &str, text: &str, m: &Model) -> Result<Columns, CliError> {
        const POSE: [&str; 7] = ["x", "y", "z", "qw", "qx", "qy", "qz"];
        let joints = m.joint_names();
        let raw = split_cells(text, 1, file)?;
        let mut slots = Vec::new();
        let mut headers = Vec::new();
        for h in raw.iter().map(|h| h.trim()) {
            let slot = POSE.iter().position(|p| *p == h).or_else(|| {
                let joint = h.strip_prefix("q0.")?;
                joints.iter().position(|n| *n == joint).map(|j| 7 + j)
            });
            let Some(slot) = slot else {
                return Err(CliError::input(format!(
                    "{file}: unknown column '{}' (expected x, y, z, qw, qx, qy, qz and q0.<joint>, joints: {})",
                    shorten(h),
                    joints.join(", ")
                )));
            };
            if slots.contains(&slot) {
                return Err(CliError::input(format!(
                    "{file}: column '{h}' appears twice"
                )));
            }
            slots.push(slot);
            headers.push(h.to_string());
        }
        let has = |k: usize| slots.contains(&k);
        if let Some(k) = (0..3).find(|&k| !has(k)) {
            return Err(CliError::input(format!(
                "{file}: the header has no column '{}' (targets need x, y, z, and qw, qx, qy, qz for a full pose)",
                POSE[k]
            )));
        }
        let quaternion = (3..7).filter(|&k| has(k)).count();
        if quaternion != 0 && quaternion != 4 {
            return Err(CliError::input(format!(
                "{file}: the header has {quaternion} of the quaternion columns qw, qx, qy, qz: give all four (a pose) or none (a position)"
            )));
        }
        Ok(Columns {
            slots,
            headers,
            oriented: quaternion == 4,
        })
    }

    /// Parses one line into `row` (its start preset to the default); a bad row keeps the reason.
    fn read(&self, text: &str, line: u64, file: &str, row: &mut Row) {
        row.line = line;
        row.bad = self.parse_row(text, line, file, row).err();
    }

    fn parse_row(&self, text: &str, line: u64, file: &str, row: &mut Row) -> Result<(), String> {
        let cells = split_cells(text, line, file).map_err(|e| {
            let place = format!("{file}:{line}: ");
            e.message
                .strip_prefix(&place)
                .unwrap_or(&e.message)
                .to_string()
        })?;
        if cells.len() != self.slots.len() {
            return Err(format!(
                "the row has {} fields, the header has {}",
                cells.len(),
                self.slots.len()
            ));
        }
        let mut pose = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];
        for (k, cell) in cells.iter().enumerate() {
            let cell = cell.trim();
            let x: f64 = cell.parse().map_err(|_| {
                format!(
                    "column '{}': '{}' is not a number",
                    self.headers[k],
                    shorten(cell)
                )
            })?;
            if !x.is_finite() {
                return Err(format!("column '{}' is not finite ({x})", self.headers[k]));
            }
            match self.slots[k] {
                s if s < 7 => pose[s] = x,
                s => row.q0[s - 7] = x,
            }
        }
        let position = [pose[0], pose[1], pose[2]];
        row.target = if self.oriented {
            target_from_quaternion(position, [pose[3], pose[4], pose[5], pose[6]], "target")
                .map_err(|e| e.to_string())?
        } else {
            Se3::from_translation(Vector3::from(position))
        };
        Ok(())
    }
}

/// The lines of a targets file, without line ends; empty lines skipped.
struct Lines {
    file: String,
    input: std::io::BufReader<TextOnly<InputSource>>,
    buffer: Vec<u8>,
    line_no: u64,
}

impl Lines {
    /// The next non-empty line and its number, `None` at the end. A line that is not UTF-8
    /// comes back as the replacement text of its bytes (the row is then bad by its numbers).
    fn next(&mut self) -> Result<Option<(String, u64)>, CliError> {
        loop {
            self.buffer.clear();
            let n = self
                .input
                .read_until(b'\n', &mut self.buffer)
                .map_err(|e| CliError::input(format!("{}: {e}", self.file)))?;
            if n == 0 {
                return Ok(None);
            }
            self.line_no += 1;
            while matches!(self.buffer.last(), Some(b'\n' | b'\r')) {
                self.buffer.pop();
            }
            if !self.buffer.iter().all(u8::is_ascii_whitespace) {
                let text = String::from_utf8_lossy(&self.buffer).into_owned();
                return Ok(Some((text, self.line_no)));
            }
        }
    }
}

/// `--input`: every row solved (the bad ones reported on stderr and written with
/// `success = false`), written to `--output` or stdout; exit status 2 when a row was bad.
fn batch(
    a: &IkArgs,
    m: &Model,
    frame: usize,
    q0: &[f64],
    options: IkOptions,
    path: &Path,
) -> Result<(), CliError> {
    let (file, input) = open_text(path)?;
    let mut lines = Lines {
        file: file.clone(),
        input,
        buffer: Vec::new(),
        line_no: 0,
    };
    let Some((header, _)) = lines.next()? else {
        return Err(CliError::input(format!("{file}: has no rows of targets")));
    };
    let columns = Columns::parse(&file, &header, m)?;
    let task = if columns.oriented {
        IkTask::pose(frame)
    } else {
        IkTask::position(frame)
    };
    let solver = IkSolver::new(m, &[task], options)?;
    let threads = a.threads.unwrap_or_else(|| {
        std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
    });
    let format = match &a.output {
        Some(out) => {
            crate::write::refuse_inputs("--output", out, &[path])?;
            output_format(out, a.model.format)?
        }
        None => output::resolve(a.model.format),
    };
    let mut job = Batch {
        file,
        lines,
        columns,
        solver,
        joints: names(m),
        q0: q0.to_vec(),
        threads,
        bad: Vec::new(),
        rows: 0,
    };
    match &a.output {
        Some(out) => crate::write::atomic(out, |w| job.run(w, format))?,
        None => {
            let stdout = std::io::stdout();
            let sink = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
            job.run(sink, format)?;
        }
    }
    job.outcome()
}

/// The format of `--output`: from its extension (`.csv`, `.json`), else `--format` (table
/// refused: a file of rows is CSV or JSON).
fn output_format(path: &Path, format: Option<Format>) -> Result<Format, CliError> {
    let by_extension = match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("csv") => Some(Format::Csv),
        Some(e) if e.eq_ignore_ascii_case("json") => Some(Format::Json),
        _ => None,
    };
    match by_extension.or(format) {
        Some(Format::Table) | None => Err(CliError::input(format!(
            "--output {}: name a .csv or .json file, or give --format csv|json",
            path.display()
        ))),
        Some(f) => Ok(f),
    }
}

/// A batch being solved: the reader, the solver and what went wrong so far.
struct Batch {
    file: String,
    lines: Lines,
    columns: Columns,
    solver: IkSolver,
    joints: Labels,
    q0: Vec<f64>,
    threads: usize,
    /// The lines of the bad rows.
    bad: Vec<u64>,
    rows: usize,
}

impl Batch {
    /// Reads, solves and writes every row, one chunk at a time. Each chunk is solved by the
    /// library's [`IkSolver::solve_batch_into`] as problems `rows so far …` of one long batch,
    /// so every row gets the answer `solve_batch` (and Python's batch) gives it, whatever the
    /// chunking and the thread count. A bad row is handed over with a NaN target (the
    /// library refuses it at once) and reported with its own reason.
    fn run<W: Write>(&mut self, w: W, format: Format) -> Result<(), CliError> {
        let nq = self.q0.len();
        let mut rows: Vec<Row> = (0..CHUNK_ROWS)
            .map(|_| Row {
                line: 0,
                target: Se3::identity(),
                q0: Vec::with_capacity(nq),
                bad: None,
            })
            .collect();
        let mut targets = vec![Se3::identity(); CHUNK_ROWS];
        let mut starts = vec![0.0; CHUNK_ROWS * nq];
        let mut q = vec![0.0; CHUNK_ROWS * nq];
        let mut results: Vec<screwdyn::Result<IkResult>> = Vec::with_capacity(CHUNK_ROWS);
        let refused = Se3::from_translation(Vector3::from_element(f64::NAN));
        let mut out = ReportWriter::new(w, format, true);
        loop {
            let mut len = 0;
            while len < CHUNK_ROWS {
                let Some((text, line)) = self.lines.next()? else {
                    break;
                };
                let row = &mut rows[len];
                row.q0.clear();
                row.q0.extend_from_slice(&self.q0);
                self.columns.read(&text, line, &self.file, row);
                targets[len] = if row.bad.is_some() {
                    refused
                } else {
                    row.target
                };
                starts[len * nq..(len + 1) * nq].copy_from_slice(&row.q0);
                len += 1;
            }
            if len == 0 {
                break;
            }
            results.clear();
            results.resize_with(len, || Err(screwdyn::Error::InvalidArgument(String::new())));
            self.solver.solve_batch_into(
                &targets[..len],
                &starts[..len * nq],
                &mut q[..len * nq],
                self.threads,
                self.rows,
                &mut results,
            )?;
            for (k, (row, result)) in rows.iter().zip(&results).take(len).enumerate() {
                self.rows += 1;
                let mut r = Report::new();
                r.add("joints", Value::Names(self.joints.clone()));
                let failed = match (&row.bad, result) {
                    (None, Ok(result)) => {
                        add_result(&mut r, &self.joints, &q[k * nq..(k + 1) * nq], result);
                        None
                    }
                    (Some(message), _) => Some(message.clone()),
                    // The row's own input refused by the solver (e.g. q0 outside the limits).
                    (None, Err(screwdyn::Error::Batch { source, .. })) => Some(source.to_string()),
                    (None, Err(e)) => Some(e.to_string()),
                };
                if let Some(message) = failed {
                    eprintln!("screwdyn: {}:{}: {message}", self.file, row.line);
                    self.bad.push(row.line);
                    let nan = vec![f64::NAN; nq];
                    r.add("q", Value::joints(&self.joints, &nan))
                        .add("success", Value::Flag(false))
                        .add("iterations", Value::Count(0))
                        .add("restarts", Value::Count(0))
                        .add("position_error", Value::Scalar(f64::NAN))
                        .add("orientation_error", Value::Scalar(f64::NAN))
                        .add("failure", Value::Text("bad input".into()));
                }
                out.write(&r)?;
            }
            if len < CHUNK_ROWS {
                break;
            }
        }
        out.finish()
    }

    /// Exit status 2 with a summary when some row was bad.
    fn outcome(&self) -> Result<(), CliError> {
        if self.rows == 0 {
            return Err(CliError::input(format!(
                "{}: has no rows of targets",
                self.file
            )));
        }
        if self.bad.is_empty() {
            return Ok(());
        }
        let shown: Vec<String> = self.bad.iter().take(10).map(u64::to_string).collect();
        let more = if self.bad.len() > 10 { ", …" } else { "" };
        Err(CliError::input(format!(
            "{}: {} of {} rows had bad input (line{} {}{more}); the others were solved",
            self.file,
            self.bad.len(),
            self.rows,
            if self.bad.len() > 1 { "s" } else { "" },
            shown.join(", ")
        )))
    }
}
