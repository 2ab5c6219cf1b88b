//! Small CSV files with one value column per joint and one key column: `--waypoints PATH.CSV`
//! (`s`, `q.<joint>`) and `--torque-csv PATH.CSV` (`t`, `tau.<joint>`); and the motion of a
//! run file (`t`, `q.<joint>`, `v.<joint>`, `a.<joint>`) for `--target-trajectory`.

use crate::CliError;
use screwdyn::Model;
use std::path::Path;

/// The rows of a joint-column file: the key column's values (when the file has it) and one
/// vector per row.
pub type JointRows = (Option<Vec<f64>>, Vec<Vec<f64>>);

/// What a file's columns must be: the key column's name, the prefix of the joint columns, and
/// whether every joint needs a column (else a missing one is zero).
pub struct Columns<'a> {
    pub key: &'a str,
    pub prefix: &'a str,
    pub every_joint: bool,
}

/// The waypoints of a CSV file with columns `q.<joint>` for every joint and optionally `s`:
/// `(s if given, points)`. Cells must be finite numbers; the library checks the rest.
pub fn read_waypoints(m: &Model, path: &Path) -> Result<JointRows, CliError> {
    let columns = Columns {
        key: "s",
        prefix: "q.",
        every_joint: true,
    };
    read_joint_rows(m, path, &columns)
}

/// Reads `path` with the columns `c` describes; every cell a finite number, an error naming
/// the file, line and column otherwise.
pub fn read_joint_rows(m: &Model, path: &Path, c: &Columns) -> Result<JointRows, CliError> {
    let file = path.display().to_string();
    let err = |e: csv::Error| csv_error(&file, e);
    let mut reader = open_csv(path, &file)?;
    let names = m.joint_names();
    let headers = reader.headers().map_err(err)?.clone();
    let mut cols = Vec::new(); // None = the key, Some(j) = joint j
    for h in headers.iter() {
        let col = if h == c.key {
            None
        } else if let Some(j) = h
            .strip_prefix(c.prefix)
            .and_then(|n| names.iter().position(|x| *x == n))
        {
            Some(j)
        } else {
            return Err(CliError::input(format!(
                "{file}: unknown column '{h}' (expected {} and {}<joint>, joints: {})",
                c.key,
                c.prefix,
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
    if c.every_joint {
        if let Some(missing) = (0..m.nq()).find(|j| !cols.contains(&Some(*j))) {
            return Err(CliError::input(format!(
                "{file}: the column '{}{}' is missing (every joint needs one)",
                c.prefix, names[missing]
            )));
        }
    }
    let has_key = cols.contains(&None);
    let (mut keys, mut rows) = (Vec::new(), Vec::new());
    for record in reader.records() {
        let record = record.map_err(err)?;
        let line = record.position().map(|p| p.line()).unwrap_or(0);
        let mut row = vec![0.0; m.nq()];
        for ((col, cell), h) in cols.iter().zip(record.iter()).zip(headers.iter()) {
            let x: f64 = cell
                .parse()
                .ok()
                .filter(|x: &f64| x.is_finite())
                .ok_or_else(|| {
                    CliError::input(format!(
                        "{file}:{line}: column '{h}': '{cell}' is not a finite number"
                    ))
                })?;
            match col {
                None => keys.push(x),
                Some(j) => row[*j] = x,
            }
        }
        rows.push(row);
    }
    Ok((has_key.then_some(keys), rows))
}

/// The samples of a motion: times, and `q`, `q̇`, `q̈` per sample.
pub type MotionRows = (Vec<f64>, Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<Vec<f64>>);

/// The motion in a run file (`torque-profile --output` or `simulate --output`, CSV): the
/// columns `t`, `q.<joint>`, `v.<joint>` and `a.<joint>` of every joint, each cell a finite
/// number; other columns (torques, energies, poses) are ignored.
pub fn read_motion(m: &Model, path: &Path) -> Result<MotionRows, CliError> {
    let file = path.display().to_string();
    let err = |e: csv::Error| csv_error(&file, e);
    let mut reader = open_csv(path, &file)?;
    let headers = reader.headers().map_err(err)?.clone();
    let find = |name: &str| {
        headers.iter().position(|h| h == name).ok_or_else(|| {
            CliError::input(format!(
                "{file}: the column '{name}' is missing (a run file has t, q.<joint>, v.<joint> and a.<joint> for every joint)"
            ))
        })
    };
    let t_col = find("t")?;
    let mut cols = [vec![], vec![], vec![]];
    for name in m.joint_names() {
        for (prefix, c) in ["q.", "v.", "a."].iter().zip(cols.iter_mut()) {
            c.push(find(&format!("{prefix}{name}"))?);
        }
    }
    let (mut t, mut q, mut v, mut a) = (vec![], vec![], vec![], vec![]);
    for record in reader.records() {
        let record = record.map_err(err)?;
        let line = record.position().map(|p| p.line()).unwrap_or(0);
        let cell = |k: usize| -> Result<f64, CliError> {
            let text = record.get(k).unwrap_or("");
            text.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    CliError::input(format!(
                        "{file}:{line}: column '{}': '{text}' is not a finite number",
                        &headers[k]
                    ))
                })
        };
        t.push(cell(t_col)?);
        for (c, rows) in cols.iter().zip([&mut q, &mut v, &mut a]) {
            rows.push(c.iter().map(|&k| cell(k)).collect::<Result<Vec<_>, _>>()?);
        }
    }
    Ok((t, q, v, a))
}

/// A CSV error as one sentence naming the file (the csv crate's message names line and field).
fn csv_error(file: &str, e: csv::Error) -> CliError {
    CliError::input(format!("{file}: {}", e.to_string().replace('\n', " ")))
}

/// `path` opened as CSV with a header row, cells trimmed.
fn open_csv(path: &Path, file: &str) -> Result<csv::Reader<std::fs::File>, CliError> {
    csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| match e.kind() {
            csv::ErrorKind::Io(io) => CliError::input(format!("{file}: cannot be read ({io})")),
            _ => csv_error(file, e),
        })
}
