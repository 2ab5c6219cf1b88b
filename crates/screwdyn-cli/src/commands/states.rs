//! The states of the numeric commands: one from `--q/--v/--a` flags, or many streamed from
//! `--input states.csv` in chunks, each computed and its report written before the next is read.

use super::inputs::parse_vector;
use crate::args::Common;
use crate::output::{self, Report};
use crate::CliError;
use screwdyn::Model;
use std::path::Path;

/// One state of the robot; the vectors a command does not use stay zero.
#[derive(Clone, Debug)]
pub struct State {
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
    pub tau: Vec<f64>,
}

impl State {
    /// All zeros for a model with `n` coordinates.
    pub fn zeros(n: usize) -> Self {
        State {
            q: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
            tau: vec![0.0; n],
        }
    }

    fn slot(&mut self, k: usize) -> &mut [f64] {
        match k {
            0 => &mut self.q,
            1 => &mut self.v,
            2 => &mut self.a,
            _ => &mut self.tau,
        }
    }
}

/// The one state given by the vector flags (`(name, value)`; an absent vector is zero).
fn flag_state(m: &Model, flags: &[(&str, Option<&str>)]) -> Result<State, CliError> {
    let mut s = State::zeros(m.nq());
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
    Ok(s)
}

/// The longest line accepted in a CSV file of states (8 MiB, a state of ~80,000 joints): a
/// binary file or `/dev/zero` given as input is an error, not an unbounded read.
pub const MAX_LINE_BYTES: usize = 8 << 20;

/// A reader that refuses what cannot be a text CSV file before it reaches the CSV parser: a NUL
/// byte, or a line longer than [`MAX_LINE_BYTES`]. It counts lines for the message.
pub(super) struct TextOnly<R> {
    inner: R,
    /// The number of the line being read (1-based).
    line: u64,
    /// Bytes since the last newline.
    run: usize,
}

impl<R: std::io::Read> std::io::Read for TextOnly<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        let chunk = &buf[..n];
        let lines_in = |c: &[u8]| memchr::memchr_iter(b'\n', c).count() as u64;
        if let Some(nul) = memchr::memchr(0, chunk) {
            let line = self.line + lines_in(&chunk[..nul]);
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("line {line} contains a NUL byte: this is binary data, not a CSV file of states"),
            ));
        }
        // A chunk is at most the CSV reader's buffer (kilobytes), so only the line running
        // across chunk boundaries can exceed the limit.
        match memchr::memrchr(b'\n', chunk) {
            Some(last) => {
                let first = memchr::memchr(b'\n', chunk).unwrap_or(last);
                if self.run + first > MAX_LINE_BYTES {
                    return Err(self.too_long());
                }
                self.line += lines_in(chunk);
                self.run = n - last - 1;
            }
            None => self.run += n,
        }
        if self.run > MAX_LINE_BYTES {
            return Err(self.too_long());
        }
        Ok(n)
    }
}

impl<R> TextOnly<R> {
    fn too_long(&self) -> std::io::Error {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "line {} is longer than {} MiB: this is not a CSV file of states",
                self.line,
                MAX_LINE_BYTES >> 20
            ),
        )
    }
}

/// Reads the states of `--input` one row at a time into a reused [`State`]: columns
/// `q.<joint>`, `v.<joint>`, `a.<joint>`, `tau.<joint>`; a missing column is zero.
///
/// A row of numbers is one line split at its commas (the common case, without the general CSV
/// parser's per-byte state machine); a line with a quote goes through the `csv` crate, so
/// quoted cells (`"0.5"`, a quoted joint name in the header) read as CSV says. Empty lines are
/// skipped, `\r\n` line ends accepted, spaces around cells ignored.
struct StateReader {
    file: String,
    input: std::io::BufReader<TextOnly<InputSource>>,
    /// The current line, without its line end.
    line: Vec<u8>,
    /// Its number in the file (1-based).
    line_no: u64,
    headers: Vec<String>,
    /// (vector 0..4 = q, v, a, tau; joint index) per column.
    slots: Vec<(usize, usize)>,
    rows: usize,
}

/// What an `--input` is read from: a file, or standard input for `-`.
pub(super) type InputSource = Box<dyn std::io::Read + Send>;

/// A buffered reader of `path` (standard input for `-`, as in most Unix programs) that refuses
/// binary data and overlong lines ([`TextOnly`]), and the path as text for messages.
pub(super) fn open_text(
    path: &Path,
) -> Result<(String, std::io::BufReader<TextOnly<InputSource>>), CliError> {
    let (file, f): (String, InputSource) = if path == Path::new("-") {
        ("standard input".into(), Box::new(std::io::stdin()))
    } else {
        let file = path.display().to_string();
        let f = std::fs::File::open(path)
            .map_err(|e| CliError::input(format!("{file}: cannot be read ({e})")))?;
        (file, Box::new(f))
    };
    let input = std::io::BufReader::with_capacity(
        1 << 16,
        TextOnly {
            inner: f,
            line: 1,
            run: 0,
        },
    );
    Ok((file, input))
}

impl StateReader {
    fn open(m: &Model, path: &Path) -> Result<Self, CliError> {
        let (file, input) = open_text(path)?;
        let mut r = StateReader {
            file,
            input,
            line: Vec::new(),
            line_no: 0,
            headers: Vec::new(),
            slots: Vec::new(),
            rows: 0,
        };
        if !r.next_line()? {
            return Err(CliError::input(format!(
                "{}: has no rows of states",
                r.file
            )));
        }
        let Ok(text) = std::str::from_utf8(&r.line) else {
            return Err(CliError::input(format!(
                "{}: line {} is not UTF-8 text: this is not a CSV file of states",
                r.file, r.line_no
            )));
        };
        let raw = split_cells(text, r.line_no, &r.file)?;
        let names = m.joint_names();
        let mut seen = std::collections::HashSet::new();
        for h in raw.iter().map(|h| h.trim()) {
            let slot = h.split_once('.').and_then(|(key, joint)| {
                let k = ["q", "v", "a", "tau"].iter().position(|x| *x == key)?;
                let j = names.iter().position(|n| *n == joint)?;
                Some((k, j))
            });
            let Some(slot) = slot else {
                return Err(CliError::input(format!(
                    "{}: unknown column '{}' (expected q.<joint>, v.<joint>, a.<joint> or tau.<joint>, joints: {})",
                    r.file,
                    shorten(h),
                    names.join(", ")
                )));
            };
            if !seen.insert(slot) {
                return Err(CliError::input(format!(
                    "{}: column '{h}' appears twice",
                    r.file
                )));
            }
            r.slots.push(slot);
            r.headers.push(h.to_string());
        }
        Ok(r)
    }

    /// Reads the next non-empty line into `self.line` (line end removed); `false` at the end.
    fn next_line(&mut self) -> Result<bool, CliError> {
        use std::io::BufRead;
        loop {
            self.line.clear();
            let n = self
                .input
                .read_until(b'\n', &mut self.line)
                .map_err(|e| match e.kind() {
                    std::io::ErrorKind::InvalidData => {
                        CliError::input(format!("{}: {e}", self.file))
                    }
                    _ => CliError::input(format!("{}: cannot be read ({e})", self.file)),
                })?;
            if n == 0 {
                return Ok(false);
            }
            self.line_no += 1;
            while matches!(self.line.last(), Some(b'\n' | b'\r')) {
                self.line.pop();
            }
            if !self.line.iter().all(u8::is_ascii_whitespace) {
                return Ok(true);
            }
        }
    }

    /// Reads the next row into `s` (its columns only: the others stay as they are, zero);
    /// `false` at the end of the file.
    fn next(&mut self, s: &mut State) -> Result<bool, CliError> {
        if !self.next_line()? {
            return Ok(false);
        }
        self.rows += 1;
        let (file, line) = (&self.file, self.line_no);
        let Ok(text) = std::str::from_utf8(&self.line) else {
            return Err(CliError::input(format!(
                "{file}:{line}: the row is not UTF-8 text"
            )));
        };
        if memchr::memchr(b'"', &self.line).is_some() {
            let cells = split_cells(text, line, file)?;
            if cells.len() != self.slots.len() {
                return Err(ragged(file, line, cells.len(), self.slots.len()));
            }
            for (k, cell) in cells.iter().enumerate() {
                self.store(k, cell, s)?;
            }
        } else {
            let fields = || memchr::memchr_iter(b',', &self.line).count() + 1;
            let ends = memchr::memchr_iter(b',', &self.line).chain(std::iter::once(text.len()));
            let (mut start, mut count) = (0, 0);
            for (k, end) in ends.enumerate() {
                if k >= self.slots.len() {
                    return Err(ragged(file, line, fields(), self.slots.len()));
                }
                // Commas are ASCII, so these are character boundaries.
                self.store(k, &text[start..end], s)?;
                start = end + 1;
                count = k + 1;
            }
            if count != self.slots.len() {
                return Err(ragged(file, line, count, self.slots.len()));
            }
        }
        Ok(true)
    }

    /// Parses `cell` of column `k` into its place in `s`.
    fn store(&self, k: usize, cell: &str, s: &mut State) -> Result<(), CliError> {
        let (file, line) = (&self.file, self.line_no);
        let cell = cell.trim_ascii();
        let x: f64 = cell.parse().map_err(|_| {
            CliError::input(format!(
                "{file}:{line}: column '{}': '{}' is not a number",
                self.headers[k],
                shorten(cell)
            ))
        })?;
        if !x.is_finite() {
            return Err(CliError::input(format!(
                "{file}:{line}: column '{}' is not finite ({x})",
                self.headers[k]
            )));
        }
        let (slot, j) = self.slots[k];
        s.slot(slot)[j] = x;
        Ok(())
    }

    /// Where the last row read is: (line in the file, row number).
    fn place(&self) -> (u64, usize) {
        (self.line_no, self.rows)
    }
}

/// `e` placed at a row of `file`: "FILE:LINE (row K): ...".
fn locate(file: &Path, (line, row): (u64, usize), e: CliError) -> CliError {
    CliError {
        code: e.code,
        message: format!("{}:{line} (row {row}): {}", file.display(), e.message),
    }
}

/// Rows per message from the reading thread of a batch to the computing one.
const CHUNK_ROWS: usize = 256;
/// Chunks in circulation: the memory of a batch is bounded by this many chunks of rows.
const CHUNKS: usize = 4;

/// Up to [`CHUNK_ROWS`] states read from `--input`, with the place of each in the file.
struct Chunk {
    states: Vec<State>,
    places: Vec<(u64, usize)>,
    len: usize,
}

impl Chunk {
    fn new(nq: usize) -> Self {
        Chunk {
            states: (0..CHUNK_ROWS).map(|_| State::zeros(nq)).collect(),
            places: vec![(0, 0); CHUNK_ROWS],
            len: 0,
        }
    }
}

/// Reads rows into the chunks that come back through `empty` and sends them on through `full`
/// until the file ends, a row is bad (the rows before it are sent, then the error) or the
/// computing side hangs up.
fn read_chunks(
    mut rows: StateReader,
    empty: std::sync::mpsc::Receiver<Chunk>,
    full: std::sync::mpsc::SyncSender<Result<Chunk, CliError>>,
) {
    while let Ok(mut chunk) = empty.recv() {
        chunk.len = 0;
        let mut ended = false;
        while chunk.len < CHUNK_ROWS {
            match rows.next(&mut chunk.states[chunk.len]) {
                Ok(true) => {
                    chunk.places[chunk.len] = rows.place();
                    chunk.len += 1;
                }
                Ok(false) => {
                    ended = true;
                    break;
                }
                Err(e) => {
                    // The rows before the bad one are computed and written first.
                    if chunk.len > 0 && full.send(Ok(chunk)).is_err() {
                        return;
                    }
                    let _ = full.send(Err(e));
                    return;
                }
            }
        }
        if chunk.len > 0 && full.send(Ok(chunk)).is_err() || ended {
            return;
        }
    }
}

/// The cells of one line that holds quotes, by the `csv` crate's rules.
pub(super) fn split_cells(text: &str, line: u64, file: &str) -> Result<Vec<String>, CliError> {
    if !text.contains('"') {
        return Ok(text.split(',').map(String::from).collect());
    }
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(text.as_bytes());
    let mut record = csv::StringRecord::new();
    match r.read_record(&mut record) {
        Ok(_) => Ok(record.iter().map(String::from).collect()),
        Err(e) => Err(CliError::input(format!(
            "{file}:{line}: {}",
            e.to_string().replace('\n', " ")
        ))),
    }
}

fn ragged(file: &str, line: u64, fields: usize, expected: usize) -> CliError {
    CliError::input(format!(
        "{file}: line {line} has {fields} fields, the header has {expected}"
    ))
}

/// At most 60 characters of a cell or column name, for messages.
pub(super) fn shorten(s: &str) -> String {
    match s.char_indices().nth(60) {
        Some((i, _)) => format!("{}…", &s[..i]),
        None => s.to_string(),
    }
}

/// Evaluates `f` on the state of the flags, or on every row of `--input` as it is read, and
/// writes each report as soon as it is computed (stdout, in the chosen format): memory does
/// not grow with the number of rows.
pub fn run_states(
    m: &Model,
    common: &Common,
    flags: &[(&str, Option<&str>)],
    mut f: impl FnMut(&State) -> Result<Report, CliError>,
) -> Result<(), CliError> {
    let format = output::resolve(common.model.format);
    let stdout = std::io::stdout();
    let sink = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
    let Some(path) = &common.input else {
        let s = flag_state(m, flags)?;
        let mut out = output::ReportWriter::new(sink, format, false);
        out.write(&finite(f(&s)?)?)?;
        return out.finish();
    };
    if let Some((name, _)) = flags.iter().find(|(_, v)| v.is_some()) {
        return Err(CliError::input(format!(
            "--{name} cannot be combined with --input (give {name}.<joint> columns in {})",
            path.display()
        )));
    }
    let rows = StateReader::open(m, path)?;
    let mut out = output::ReportWriter::new(sink, format, true);
    // Two stages on two threads: one reads and parses the rows, this one computes and writes,
    // with a few chunks of rows in circulation between them (memory stays bounded, and the
    // order of the rows is kept). Parsing costs about as much as the computation, so the two
    // overlap instead of adding up.
    std::thread::scope(|scope| -> Result<(), CliError> {
        let (full_tx, full_rx) = std::sync::mpsc::sync_channel(CHUNKS);
        let (empty_tx, empty_rx) = std::sync::mpsc::channel();
        for _ in 0..CHUNKS {
            let _ = empty_tx.send(Chunk::new(m.nq()));
        }
        scope.spawn(move || read_chunks(rows, empty_rx, full_tx));
        for message in full_rx {
            let chunk: Chunk = message?;
            for (s, &place) in chunk.states.iter().zip(&chunk.places).take(chunk.len) {
                let r = f(s).and_then(finite).map_err(|e| locate(path, place, e))?;
                out.write(&r)?;
            }
            let _ = empty_tx.send(chunk);
        }
        Ok(())
    })?;
    if out.count() == 0 {
        return Err(CliError::input(format!(
            "{}: has no rows of states",
            path.display()
        )));
    }
    out.finish()
}

/// A report of a numeric command whose numbers are all finite: a NaN or ∞ (inputs too large for
/// double precision, e.g. `--v 1e200`) is an error naming the quantity, never printed.
fn finite(r: Report) -> Result<Report, CliError> {
    match r
        .items
        .iter()
        .find_map(|(k, v)| v.non_finite().map(|at| (k, at)))
    {
        None => Ok(r),
        Some((key, at)) => Err(screwdyn::Error::Overflow {
            what: format!("{key}{at}"),
        }
        .into()),
    }
}
