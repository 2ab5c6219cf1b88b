//! Every file the CLI writes goes through here, by the library's one output rule
//! ([`screwdyn::io::output`]): a regular file (or a new one) is written to a temporary file in
//! the target's directory and renamed over the target only when complete; a device, FIFO or
//! socket (`/dev/null`, `/dev/full`, `/dev/stdout` on a pipe) is written directly and never
//! replaced. An output is never one of the command's inputs.
//!
//! A failure part-way (disk full, `ulimit -f`, a plot that cannot be drawn) removes the
//! temporary file and leaves the previous target as it was; two processes writing the same
//! target each rename a complete file of their own, so the result is one of them, whole.

use crate::CliError;
pub use screwdyn::io::output::OutputFile;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes `path` (atomically when it is a regular file): `f` writes the whole content into a
/// buffered writer, which is then committed.
///
/// # Errors
/// The error of `f`, or a one-sentence error naming `path` when the file cannot be created,
/// written, flushed or renamed; a replaced target is then left untouched.
pub fn atomic<F>(path: &Path, f: F) -> Result<(), CliError>
where
    F: FnOnce(&mut BufWriter<&File>) -> Result<(), CliError>,
{
    let out = OutputFile::create(path)?;
    {
        let mut w = BufWriter::new(out.file());
        f(&mut w)?;
        w.flush().map_err(|e| cannot_write(path, &e))?;
    }
    Ok(out.commit()?)
}

/// Like [`atomic`] for a writer that opens a path itself (the plotting backends): `f` gets the
/// path of a temporary file, which keeps the target's extension. For a device or FIFO target
/// the temporary file is a scratch file, copied to the target once complete.
///
/// # Errors
/// As [`atomic`].
pub fn atomic_path<F>(path: &Path, f: F) -> Result<(), CliError>
where
    F: FnOnce(&Path) -> Result<(), CliError>,
{
    let out = OutputFile::create(path)?;
    if let Some(tmp) = out.temp_path() {
        f(tmp)?;
        return Ok(out.commit()?);
    }
    let suffix = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    let scratch = tempfile::Builder::new()
        .prefix(".screwdyn.")
        .suffix(&suffix)
        .tempfile()
        .map_err(|e| cannot_write(path, &e))?;
    f(scratch.path())?;
    let bytes = std::fs::read(scratch.path()).map_err(|e| cannot_write(path, &e))?;
    let mut w = out.file();
    w.write_all(&bytes)
        .and_then(|()| w.flush())
        .map_err(|e| cannot_write(path, &e))?;
    Ok(out.commit()?)
}

/// Says on stderr that `path` was written ("wrote run.csv"), when stderr is a terminal: a
/// person at the terminal learns where the file went, a script's stderr stays free of it.
/// Every command calls it once a file is complete (`view` and `identify --excite`, whose
/// result is the file, say so on stdout instead).
pub fn announce(path: &Path) {
    use std::io::IsTerminal;
    if std::io::stderr().is_terminal() {
        eprintln!("wrote {}", path.display());
    }
}

/// Refuses an output `path` (given as `flag`) that names one of the command's `inputs` (files
/// only: a `builtin:` model is not a path), comparing canonical paths so that `./m.urdf`,
/// `dir/../m.urdf` and a symbolic link to the model are all recognised.
///
/// # Errors
/// One sentence naming the flag and the input, for the exit status 2.
pub fn refuse_inputs(flag: &str, path: &Path, inputs: &[&Path]) -> Result<(), CliError> {
    let Some(out) = canonical_target(path) else {
        return Ok(());
    };
    for input in inputs {
        if let Ok(i) = std::fs::canonicalize(input) {
            if i == out {
                return Err(CliError::input(format!(
                    "{flag} {} is an input of this command ({}); write the result to another file",
                    path.display(),
                    input.display()
                )));
            }
        }
    }
    Ok(())
}

/// The canonical path `path` would be written at: the file itself when it exists (following a
/// symbolic link), else its canonical directory joined with its name.
fn canonical_target(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = std::fs::canonicalize(path) {
        return Some(p);
    }
    let name = path.file_name()?;
    let dir = std::fs::canonicalize(directory(path)).ok()?;
    Some(dir.join(name))
}

/// The directory `path` is in (`.` for a bare file name).
fn directory(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

fn cannot_write(path: &Path, e: &std::io::Error) -> CliError {
    CliError::input(format!("cannot write {} ({e})", path.display()))
}
