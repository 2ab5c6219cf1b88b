//! Formatting of results: human tables, JSON and CSV (keys and columns as in docs/cli.md).
//!
//! Every command produces a [`Report`]: an ordered list of `(key, value)` where a value is a
//! scalar, a labelled vector, a labelled matrix, a map of further values, or text. The same
//! report is printed as a table, a JSON object or one CSV row (columns `<key>.<label>` for
//! vectors, `<key>.<row>.<col>` for matrices, `<key>.<sub key>...` for maps), and a batch of
//! reports (one per input state) as a JSON array or a CSV file with one row per state.

use crate::args::Format;
use crate::CliError;
use comfy_table::{presets, Table};
use nalgebra::DMatrix;
use screwdyn::format::{csv_field, json_number, NumberText};
use serde_json::{Map, Value as Json};
use std::borrow::Cow;
use std::io::{IsTerminal, Write};
use std::rc::Rc;

/// The format asked for, or `table` on a terminal and `json` otherwise.
pub fn resolve(format: Option<Format>) -> Format {
    format.unwrap_or_else(|| {
        if std::io::stdout().is_terminal() {
            Format::Table
        } else {
            Format::Json
        }
    })
}

/// Labels of a vector's entries or a matrix's rows/columns, shared between the values of a
/// batch (one allocation per command, not per row).
pub type Labels = Rc<[String]>;

/// Labels from names.
pub fn labels<S: AsRef<str>>(names: &[S]) -> Labels {
    names.iter().map(|s| s.as_ref().to_string()).collect()
}

/// One value of a result.
#[derive(Clone, Debug)]
pub enum Value {
    /// A number.
    Scalar(f64),
    /// A count (written as an integer: `10001`, not `10001.0`).
    Count(usize),
    /// A yes/no answer (`true` or `false` in every format).
    Flag(bool),
    /// A vector whose entries carry labels (joint names, `wx`…`vz`, ...).
    Vector(Labels, Vec<f64>),
    /// A matrix with row and column labels.
    Matrix(Labels, Labels, DMatrix<f64>),
    /// Nested values (a frame → pose map, per-body quantities, ...).
    Map(Vec<(String, Value)>),
    /// A word (a frame name, a method).
    Text(String),
    /// A list of names (the joint names); omitted from CSV, whose columns carry them.
    Names(Labels),
    /// A list of values of any length (a run's events); omitted from CSV, whose columns are
    /// fixed.
    List(Vec<Value>),
}

impl Value {
    /// Where this value holds a NaN or an infinity (`""` for a scalar, `.<label>` for a vector
    /// entry, `.<row>.<column>` for a matrix entry, nested for maps), if anywhere.
    pub fn non_finite(&self) -> Option<String> {
        match self {
            Value::Scalar(x) => (!x.is_finite()).then(String::new),
            Value::Vector(labels, x) => x
                .iter()
                .position(|v| !v.is_finite())
                .map(|i| format!(".{}", labels.get(i).map_or("?", |s| s.as_str()))),
            Value::Matrix(rows, cols, m) => m.iter().position(|v| !v.is_finite()).map(|k| {
                let (r, c) = (k % m.nrows(), k / m.nrows());
                let name = |l: &Labels, i: usize| l.get(i).map_or("?".to_string(), |s| s.clone());
                format!(".{}.{}", name(rows, r), name(cols, c))
            }),
            Value::Map(items) => items
                .iter()
                .find_map(|(k, v)| v.non_finite().map(|at| format!(".{k}{at}"))),
            Value::List(items) => items
                .iter()
                .enumerate()
                .find_map(|(k, v)| v.non_finite().map(|at| format!(".{k}{at}"))),
            Value::Count(_) | Value::Flag(_) | Value::Text(_) | Value::Names(_) => None,
        }
    }

    /// A joint-space vector.
    pub fn joints(names: &Labels, x: &[f64]) -> Value {
        Value::Vector(names.clone(), x.to_vec())
    }

    /// A joint × joint matrix.
    pub fn joint_matrix(names: &Labels, m: &DMatrix<f64>) -> Value {
        Value::Matrix(names.clone(), names.clone(), m.clone())
    }

    /// A matrix labelled `1, 2, ...` on both sides (a 4×4 pose).
    pub fn numbered(m: &DMatrix<f64>) -> Value {
        thread_local! {
            static ONE_TO_FOUR: Labels = (1..=4).map(|k| k.to_string()).collect();
        }
        let numbers = |k: usize| -> Labels {
            if k == 4 {
                ONE_TO_FOUR.with(Rc::clone)
            } else {
                (1..=k).map(|i| i.to_string()).collect()
            }
        };
        let (r, c) = (numbers(m.nrows()), numbers(m.ncols()));
        Value::Matrix(r, c, m.clone())
    }

    /// A twist or wrench (angular first).
    pub fn six(labels: [&str; 6], x: &[f64]) -> Value {
        Value::Vector(labels.iter().map(|s| s.to_string()).collect(), x.to_vec())
    }

    fn to_json(&self) -> Json {
        match self {
            Value::Scalar(x) => json_number(*x),
            Value::Count(n) => Json::from(*n),
            Value::Flag(b) => Json::Bool(*b),
            Value::Vector(_, x) => Json::Array(x.iter().map(|v| json_number(*v)).collect()),
            Value::Matrix(_, _, m) => Json::Array(
                (0..m.nrows())
                    .map(|r| Json::Array((0..m.ncols()).map(|c| json_number(m[(r, c)])).collect()))
                    .collect(),
            ),
            Value::Map(items) => Json::Object(
                items
                    .iter()
                    .map(|(k, v)| (k.clone(), v.to_json()))
                    .collect::<Map<_, _>>(),
            ),
            Value::Text(s) => Json::String(s.clone()),
            Value::Names(n) => Json::Array(n.iter().map(|s| Json::String(s.clone())).collect()),
            Value::List(items) => Json::Array(items.iter().map(Value::to_json).collect()),
        }
    }

    /// The CSV column names of this value under `key`.
    fn columns(&self, key: &str, out: &mut Vec<String>) {
        match self {
            Value::Scalar(_) | Value::Count(_) | Value::Flag(_) | Value::Text(_) => {
                out.push(key.into())
            }
            Value::Vector(l, _) => out.extend(l.iter().map(|l| format!("{key}.{l}"))),
            Value::Matrix(rl, cl, _) => {
                for rn in rl.iter() {
                    out.extend(cl.iter().map(|cn| format!("{key}.{rn}.{cn}")));
                }
            }
            Value::Map(items) => {
                for (k, v) in items {
                    v.columns(&format!("{key}.{k}"), out);
                }
            }
            Value::Names(_) | Value::List(_) => {}
        }
    }

    /// Writes the CSV cells of this value (in [`Value::flatten`]'s order); counts them.
    fn write_csv(
        &self,
        w: &mut impl Write,
        num: &mut NumberText,
        cells: &mut usize,
    ) -> std::io::Result<()> {
        match self {
            Value::Scalar(x) => csv_cell(w, cells, num.csv(*x)),
            Value::Count(n) => csv_cell(w, cells, &n.to_string()),
            Value::Flag(b) => csv_cell(w, cells, if *b { "true" } else { "false" }),
            Value::Vector(_, x) => x.iter().try_for_each(|x| csv_cell(w, cells, num.csv(*x))),
            Value::Matrix(_, _, m) => {
                for r in 0..m.nrows() {
                    for c in 0..m.ncols() {
                        csv_cell(w, cells, num.csv(m[(r, c)]))?;
                    }
                }
                Ok(())
            }
            Value::Map(items) => items
                .iter()
                .try_for_each(|(_, v)| v.write_csv(w, num, cells)),
            Value::Text(s) => csv_cell(w, cells, &csv_field(s)),
            Value::Names(_) | Value::List(_) => Ok(()),
        }
    }

    /// Writes this value as compact JSON (the same document as [`Value::to_json`]).
    fn write_json(&self, w: &mut impl Write, num: &mut NumberText) -> std::io::Result<()> {
        match self {
            Value::Scalar(x) => json_num(w, num, *x),
            Value::Count(n) => write!(w, "{n}"),
            Value::Flag(b) => write!(w, "{b}"),
            Value::Vector(_, x) => {
                w.write_all(b"[")?;
                for (k, x) in x.iter().enumerate() {
                    if k > 0 {
                        w.write_all(b",")?;
                    }
                    json_num(w, num, *x)?;
                }
                w.write_all(b"]")
            }
            Value::Matrix(_, _, m) => {
                w.write_all(b"[")?;
                for r in 0..m.nrows() {
                    w.write_all(if r > 0 { b",[" } else { b"[" })?;
                    for c in 0..m.ncols() {
                        if c > 0 {
                            w.write_all(b",")?;
                        }
                        json_num(w, num, m[(r, c)])?;
                    }
                    w.write_all(b"]")?;
                }
                w.write_all(b"]")
            }
            Value::Map(items) => write_json_object(w, num, items),
            Value::Text(s) => json_str(w, s),
            Value::Names(n) => {
                w.write_all(b"[")?;
                for (k, s) in n.iter().enumerate() {
                    if k > 0 {
                        w.write_all(b",")?;
                    }
                    json_str(w, s)?;
                }
                w.write_all(b"]")
            }
            Value::List(items) => {
                w.write_all(b"[")?;
                for (k, v) in items.iter().enumerate() {
                    if k > 0 {
                        w.write_all(b",")?;
                    }
                    v.write_json(w, num)?;
                }
                w.write_all(b"]")
            }
        }
    }

    fn table(&self, key: &str, out: &mut String) {
        match self {
            Value::Scalar(x) => out.push_str(&format!("{key} = {}\n", fmt(*x))),
            Value::Count(n) => out.push_str(&format!("{key} = {n}\n")),
            Value::Flag(b) => out.push_str(&format!("{key}: {b}\n")),
            Value::Text(s) => out.push_str(&format!("{key}: {s}\n")),
            Value::Names(n) => out.push_str(&format!("{key}: {}\n", n.join(", "))),
            Value::Vector(l, x) => {
                let mut t = table();
                t.set_header(vec!["", key]);
                for (l, x) in l.iter().zip(x) {
                    t.add_row(vec![l.clone(), fmt(*x)]);
                }
                out.push_str(&format!("{t}\n"));
            }
            Value::Matrix(rl, cl, m) => {
                out.push_str(&format!("{key}:\n"));
                out.push_str(&matrix_table(rl, cl, m));
                out.push('\n');
            }
            Value::Map(items) => {
                for (k, v) in items {
                    v.table(&format!("{key} {k}"), out);
                }
            }
            Value::List(items) => {
                for (k, v) in items.iter().enumerate() {
                    v.table(&format!("{key} {k}"), out);
                }
            }
        }
    }
}

fn write_json_object<K: AsRef<str>>(
    w: &mut impl Write,
    num: &mut NumberText,
    items: &[(K, Value)],
) -> std::io::Result<()> {
    w.write_all(b"{")?;
    for (k, (key, v)) in items.iter().enumerate() {
        if k > 0 {
            w.write_all(b",")?;
        }
        json_str(w, key.as_ref())?;
        w.write_all(b":")?;
        v.write_json(w, num)?;
    }
    w.write_all(b"}")
}

/// A number for tables: 6 decimals, or scientific when very large or small.
pub fn fmt(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if !x.is_finite() {
        if x.is_nan() {
            "NaN".into()
        } else if x > 0.0 {
            "∞".into()
        } else {
            "-∞".into()
        }
    } else if x.abs() >= 1e6 || x.abs() < 1e-4 {
        format!("{x:.4e}")
    } else {
        format!("{x:.6}")
    }
}

/// An empty terminal table in the house style.
pub fn table() -> Table {
    let mut t = Table::new();
    t.load_preset(presets::UTF8_FULL_CONDENSED);
    t
}

/// A labelled matrix as a terminal table.
pub fn matrix_table(rows: &[String], cols: &[String], m: &DMatrix<f64>) -> String {
    let mut t = table();
    let mut header = vec![String::new()];
    header.extend(cols.iter().cloned());
    t.set_header(header);
    for (r, rn) in rows.iter().enumerate() {
        let mut row = vec![rn.clone()];
        row.extend((0..m.ncols()).map(|c| fmt(m[(r, c)])));
        t.add_row(row);
    }
    format!("{t}\n")
}

/// The result of one command on one state.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// `(key, value)` in output order.
    pub items: Vec<(Cow<'static, str>, Value)>,
    /// A hand-written table replacing the generic one (e.g. `explain`'s narrative).
    pub table: Option<String>,
}

impl Report {
    /// An empty report.
    pub fn new() -> Self {
        Report::default()
    }

    /// Appends `key = value`.
    pub fn add(&mut self, key: impl Into<Cow<'static, str>>, value: Value) -> &mut Self {
        self.items.push((key.into(), value));
        self
    }

    /// The report as a JSON object.
    pub fn to_json(&self) -> Json {
        Json::Object(
            self.items
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_json()))
                .collect(),
        )
    }

    /// Writes the report as one compact JSON object (the document of [`Report::to_json`]).
    pub fn write_json(&self, w: &mut impl Write, num: &mut NumberText) -> std::io::Result<()> {
        write_json_object(w, num, &self.items)
    }

    /// The CSV column names: `<key>.<label>` for vectors, `<key>.<row>.<col>` for matrices,
    /// `<key>.<sub key>...` for maps; the names list is left out.
    pub fn csv_columns(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (k, v) in &self.items {
            v.columns(k, &mut out);
        }
        out
    }

    /// The report as a terminal table.
    pub fn to_table(&self) -> String {
        if let Some(t) = &self.table {
            return t.clone();
        }
        let mut out = String::new();
        for (k, v) in &self.items {
            v.table(k, &mut out);
        }
        out
    }
}

/// Prints `reports` (one per input state) in `format`; `batch` says whether the states came
/// from `--input` (JSON array) or from flags (a single JSON object).
pub fn print(reports: &[Report], format: Format, batch: bool) -> Result<(), CliError> {
    let stdout = std::io::stdout();
    let mut out = ReportWriter::new(std::io::BufWriter::new(stdout.lock()), format, batch);
    for r in reports {
        out.write(r)?;
    }
    out.finish()
}

/// Writes reports one at a time (one per state of a batch) as they are computed: a JSON array
/// is opened at the first report and closed by [`ReportWriter::finish`], a CSV file gets its
/// header from the first report and one row per report, a table one block per state. Nothing
/// is kept between reports but the number formatter, so memory does not grow with the batch.
pub struct ReportWriter<W: Write> {
    format: Format,
    batch: bool,
    count: usize,
    /// CSV: the number of columns of the header (every row must match it).
    columns: usize,
    out: Sink<W>,
    num: NumberText,
}

enum Sink<W: Write> {
    Csv(W),
    Text(W),
}

impl<W: Write> ReportWriter<W> {
    /// A writer of `format` onto `w`; `batch` as for [`print`].
    pub fn new(w: W, format: Format, batch: bool) -> Self {
        let out = match format {
            Format::Csv => Sink::Csv(w),
            _ => Sink::Text(w),
        };
        ReportWriter {
            format,
            batch,
            count: 0,
            columns: 0,
            out,
            num: NumberText::new(),
        }
    }

    /// Writes one report.
    ///
    /// # Errors
    /// A write error (a closed pipe becomes [`CliError::stop`]), or an internal error when a
    /// CSV row has other columns than the first one.
    pub fn write(&mut self, r: &Report) -> Result<(), CliError> {
        let first = self.count == 0;
        self.count += 1;
        match &mut self.out {
            Sink::Csv(w) => {
                if first {
                    // The header through the csv crate's writer (names quoted as needed).
                    let names = r.csv_columns();
                    self.columns = names.len();
                    let mut h = csv::WriterBuilder::new()
                        .terminator(csv::Terminator::Any(b'\n'))
                        .from_writer(Vec::new());
                    h.write_record(&names)
                        .map_err(|e| CliError::internal(format!("CSV header ({e})")))?;
                    let bytes = h
                        .into_inner()
                        .map_err(|e| CliError::internal(format!("CSV header ({e})")))?;
                    w.write_all(&bytes).map_err(io_error)?;
                }
                let mut cells = 0;
                for (_, v) in &r.items {
                    v.write_csv(w, &mut self.num, &mut cells)
                        .map_err(io_error)?;
                }
                if cells != self.columns {
                    return Err(CliError::internal(
                        "the rows of a batch produced different CSV columns",
                    ));
                }
                w.write_all(b"\n").map_err(io_error)?;
            }
            Sink::Text(w) => match self.format {
                Format::Json if self.batch => {
                    w.write_all(if first { b"[\n" } else { b",\n" })
                        .map_err(io_error)?;
                    r.write_json(w, &mut self.num).map_err(io_error)?;
                }
                Format::Json => {
                    serde_json::to_writer_pretty(&mut *w, &r.to_json())
                        .map_err(|e| io_error(e.into()))?;
                    w.write_all(b"\n").map_err(io_error)?;
                }
                _ => {
                    if self.batch {
                        writeln!(w, "── state {} ──", self.count).map_err(io_error)?;
                    }
                    w.write_all(r.to_table().as_bytes()).map_err(io_error)?;
                }
            },
        }
        Ok(())
    }

    /// The number of reports written.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Closes the JSON array of a batch and flushes.
    ///
    /// # Errors
    /// A write error (a closed pipe becomes [`CliError::stop`]).
    pub fn finish(self) -> Result<(), CliError> {
        match self.out {
            Sink::Csv(mut w) => w.flush().map_err(io_error),
            Sink::Text(mut w) => {
                if self.batch && self.format == Format::Json {
                    let end: &[u8] = if self.count == 0 { b"[]\n" } else { b"\n]\n" };
                    w.write_all(end).map_err(io_error)?;
                }
                w.flush().map_err(io_error)
            }
        }
    }
}

/// A write error: a closed pipe (`| head`) ends the command quietly with status 0.
fn io_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::stop()
    } else {
        CliError::internal(format!("cannot write the output ({e})"))
    }
}

/// Writes one CSV cell (already quoted if needed), preceded by a comma unless it is the first
/// of its row. Numbers never need quotes, so rows are written without the CSV writer's
/// per-byte scan; names (the header, words) go through [`csv_field`].
fn csv_cell(w: &mut impl Write, cells: &mut usize, text: &str) -> std::io::Result<()> {
    if *cells > 0 {
        w.write_all(b",")?;
    }
    *cells += 1;
    w.write_all(text.as_bytes())
}

fn json_num(w: &mut impl Write, num: &mut NumberText, x: f64) -> std::io::Result<()> {
    w.write_all(num.json(x).as_bytes())
}

fn json_str(w: &mut impl Write, s: &str) -> std::io::Result<()> {
    serde_json::to_writer(w, s).map_err(std::io::Error::from)
}

/// Writes to stdout; a closed pipe (`| head`) is not an error.
pub fn write_stdout(text: &str) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(CliError::internal(format!("cannot write to stdout ({e})"))),
    }
}
