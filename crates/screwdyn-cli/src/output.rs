//! Formatting of results: human tables, JSON (DESIGN §5 keys) and CSV.

use crate::args::Format;
use std::io::IsTerminal;

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

/// A number for tables: fixed width, 6 significant decimals.
pub fn num(x: f64) -> String {
    format!("{x:>12.6}")
}

/// A matrix as rows of fixed-width numbers.
pub fn matrix_rows(m: &nalgebra::DMatrix<f64>) -> String {
    (0..m.nrows())
        .map(|r| (0..m.ncols()).map(|c| num(m[(r, c)])).collect::<String>())
        .collect::<Vec<_>>()
        .join("\n")
}

/// A matrix as a JSON list of rows.
pub fn matrix_json(m: &nalgebra::DMatrix<f64>) -> serde_json::Value {
    serde_json::Value::Array(
        (0..m.nrows())
            .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect::<Vec<_>>().into())
            .collect(),
    )
}
