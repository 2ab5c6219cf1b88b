//! Formatting of results: human tables, JSON (DESIGN §5 keys) and CSV.
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
use serde_json::{Map, Value as Json};
use std::io::{IsTerminal, Write};

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

/// One value of a result.
#[derive(Clone, Debug)]
pub enum Value {
    /// A number.
    Scalar(f64),
    /// A count (written as an integer: `10001`, not `10001.0`).
    Count(usize),
    /// A vector whose entries carry labels (joint names, `wx`…`vz`, ...).
    Vector(Vec<String>, Vec<f64>),
    /// A matrix with row and column labels.
    Matrix(Vec<String>, Vec<String>, DMatrix<f64>),
    /// Nested values (a frame → pose map, per-body quantities, ...).
    Map(Vec<(String, Value)>),
    /// A word (a frame name, a method).
    Text(String),
    /// A list of names (the joint names); omitted from CSV, whose columns carry them.
    Names(Vec<String>),
}

impl Value {
    /// A joint-space vector.
    pub fn joints(names: &[String], x: &[f64]) -> Value {
        Value::Vector(names.to_vec(), x.to_vec())
    }

    /// A joint × joint matrix.
    pub fn joint_matrix(names: &[String], m: &DMatrix<f64>) -> Value {
        Value::Matrix(names.to_vec(), names.to_vec(), m.clone())
    }

    /// A matrix labelled `1, 2, ...` on both sides (a 4×4 pose).
    pub fn numbered(m: &DMatrix<f64>) -> Value {
        let r = (1..=m.nrows()).map(|k| k.to_string()).collect();
        let c = (1..=m.ncols()).map(|k| k.to_string()).collect();
        Value::Matrix(r, c, m.clone())
    }

    /// A twist or wrench (angular first).
    pub fn six(labels: [&str; 6], x: &[f64]) -> Value {
        Value::Vector(labels.iter().map(|s| s.to_string()).collect(), x.to_vec())
    }

    fn to_json(&self) -> Json {
        match self {
            Value::Scalar(x) => num_json(*x),
            Value::Count(n) => Json::from(*n),
            Value::Vector(_, x) => Json::Array(x.iter().map(|v| num_json(*v)).collect()),
            Value::Matrix(_, _, m) => Json::Array(
                (0..m.nrows())
                    .map(|r| Json::Array((0..m.ncols()).map(|c| num_json(m[(r, c)])).collect()))
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
        }
    }

    fn flatten(&self, key: &str, out: &mut Vec<(String, String)>) {
        match self {
            Value::Scalar(x) => out.push((key.into(), format!("{x:?}"))),
            Value::Count(n) => out.push((key.into(), n.to_string())),
            Value::Vector(l, x) => {
                for (l, x) in l.iter().zip(x) {
                    out.push((format!("{key}.{l}"), format!("{x:?}")));
                }
            }
            Value::Matrix(rl, cl, m) => {
                for (r, rn) in rl.iter().enumerate() {
                    for (c, cn) in cl.iter().enumerate() {
                        out.push((format!("{key}.{rn}.{cn}"), format!("{:?}", m[(r, c)])));
                    }
                }
            }
            Value::Map(items) => {
                for (k, v) in items {
                    v.flatten(&format!("{key}.{k}"), out);
                }
            }
            Value::Text(s) => out.push((key.into(), s.clone())),
            Value::Names(_) => {}
        }
    }

    fn table(&self, key: &str, out: &mut String) {
        match self {
            Value::Scalar(x) => out.push_str(&format!("{key} = {}\n", fmt(*x))),
            Value::Count(n) => out.push_str(&format!("{key} = {n}\n")),
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
        }
    }
}

fn num_json(x: f64) -> Json {
    serde_json::Number::from_f64(x)
        .map(Json::Number)
        .unwrap_or(Json::Null)
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
    pub items: Vec<(String, Value)>,
    /// A hand-written table replacing the generic one (e.g. `explain`'s narrative).
    pub table: Option<String>,
}

impl Report {
    /// An empty report.
    pub fn new() -> Self {
        Report::default()
    }

    /// Appends `key = value`.
    pub fn add(&mut self, key: &str, value: Value) -> &mut Self {
        self.items.push((key.into(), value));
        self
    }

    /// The report as a JSON object.
    pub fn to_json(&self) -> Json {
        Json::Object(
            self.items
                .iter()
                .map(|(k, v)| (k.clone(), v.to_json()))
                .collect(),
        )
    }

    /// `(column, cell)` pairs of the CSV row.
    pub fn to_csv_cells(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        for (k, v) in &self.items {
            v.flatten(k, &mut out);
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
    let mut text = String::new();
    match format {
        Format::Json => {
            let v = if batch {
                Json::Array(reports.iter().map(Report::to_json).collect())
            } else {
                reports.first().map(Report::to_json).unwrap_or(Json::Null)
            };
            text = serde_json::to_string_pretty(&v).expect("JSON of numbers and strings");
            text.push('\n');
        }
        Format::Csv => {
            let mut header: Option<Vec<String>> = None;
            for r in reports {
                let cells = r.to_csv_cells();
                let names: Vec<String> = cells.iter().map(|(n, _)| n.clone()).collect();
                match &header {
                    None => {
                        text.push_str(&csv_line(&names));
                        header = Some(names);
                    }
                    Some(h) if *h != names => {
                        return Err(CliError::internal(
                            "the rows of a batch produced different CSV columns",
                        ))
                    }
                    _ => {}
                }
                let values: Vec<String> = cells.into_iter().map(|(_, c)| c).collect();
                text.push_str(&csv_line(&values));
            }
        }
        Format::Table => {
            for (k, r) in reports.iter().enumerate() {
                if batch {
                    text.push_str(&format!("── state {} ──\n", k + 1));
                }
                text.push_str(&r.to_table());
            }
        }
    }
    write_stdout(&text)
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

fn csv_line(cells: &[String]) -> String {
    let quoted: Vec<String> = cells
        .iter()
        .map(|c| {
            if c.contains([',', '"', '\n']) {
                format!("\"{}\"", c.replace('"', "\"\""))
            } else {
                c.clone()
            }
        })
        .collect();
    format!("{}\n", quoted.join(","))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_columns_follow_design() {
        let j = vec!["a".to_string(), "b".to_string()];
        let mut r = Report::new();
        r.add("joints", Value::Names(j.clone()))
            .add("tau", Value::joints(&j, &[1.0, 2.0]))
            .add(
                "mass_matrix",
                Value::joint_matrix(&j, &DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0])),
            )
            .add("kinetic_energy", Value::Scalar(0.5));
        let names: Vec<String> = r.to_csv_cells().into_iter().map(|(n, _)| n).collect();
        assert_eq!(
            names,
            [
                "tau.a",
                "tau.b",
                "mass_matrix.a.a",
                "mass_matrix.a.b",
                "mass_matrix.b.a",
                "mass_matrix.b.b",
                "kinetic_energy"
            ]
        );
        let j = r.to_json();
        assert_eq!(j["mass_matrix"][1][0], 3.0);
        assert_eq!(j["joints"][1], "b");
    }
}
