//! `--waypoints PATH.CSV`: joint-space waypoints with an optional path parameter `s`.

use crate::CliError;
use screwdyn::Model;
use std::path::Path;

/// Waypoints read from a file: the path parameter of each (when the file has `s`), the points.
pub type Waypoints = (Option<Vec<f64>>, Vec<Vec<f64>>);

/// The waypoints of a CSV file with columns `q.<joint>` for every joint and optionally `s`:
/// `(s if given, points)`. Cells must be finite numbers; the library checks the rest.
pub fn read_waypoints(m: &Model, path: &Path) -> Result<Waypoints, CliError> {
    let file = path.display().to_string();
    let err =
        |e: csv::Error| CliError::input(format!("{file}: {}", e.to_string().replace('\n', " ")));
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| match e.kind() {
            csv::ErrorKind::Io(io) => CliError::input(format!("{file}: cannot be read ({io})")),
            _ => err(e),
        })?;
    let names = m.joint_names();
    let headers = reader.headers().map_err(err)?.clone();
    let mut cols = Vec::new(); // None = s, Some(j) = q of joint j
    for h in headers.iter() {
        let col = if h == "s" {
            None
        } else if let Some(j) = h
            .strip_prefix("q.")
            .and_then(|n| names.iter().position(|x| *x == n))
        {
            Some(j)
        } else {
            return Err(CliError::input(format!(
                "{file}: unknown column '{h}' (expected s and q.<joint>, joints: {})",
                names.join(", ")
            )));
        };
        if cols.contains(&col) {
            return Err(CliError::input(format!(
                "{file}: column '{h}' appears twice"
            )));
        }
        cols.push(col);
    }
    if let Some(missing) = (0..m.nq()).find(|j| !cols.contains(&Some(*j))) {
        return Err(CliError::input(format!(
            "{file}: the column 'q.{}' is missing (every joint needs one)",
            names[missing]
        )));
    }
    let has_s = cols.contains(&None);
    let (mut s, mut points) = (Vec::new(), Vec::new());
    for record in reader.records() {
        let record = record.map_err(err)?;
        let line = record.position().map(|p| p.line()).unwrap_or(0);
        let mut q = vec![0.0; m.nq()];
        for ((c, cell), h) in cols.iter().zip(record.iter()).zip(headers.iter()) {
            let x: f64 = cell
                .parse()
                .ok()
                .filter(|x: &f64| x.is_finite())
                .ok_or_else(|| {
                    CliError::input(format!(
                        "{file}:{line}: column '{h}': '{cell}' is not a finite number"
                    ))
                })?;
            match c {
                None => s.push(x),
                Some(j) => q[*j] = x,
            }
        }
        points.push(q);
    }
    Ok((has_s.then_some(s), points))
}
