//! Every file the CLI writes goes through here: written to a temporary file in the target's
//! directory and renamed over the target only when complete, and never onto an input.
//!
//! A failure part-way (disk full, `ulimit -f`, a plot that cannot be drawn) removes the
//! temporary file and leaves the previous target as it was; two processes writing the same
//! target each rename a complete file of their own, so the result is one of them, whole.

use crate::CliError;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use tempfile::NamedTempFile;

/// Writes `path` atomically: `f` writes the whole content into a buffered temporary file in the
/// same directory, which then replaces `path` (a rename, on the same file system).
///
/// # Errors
/// The error of `f`, or a one-sentence error naming `path` when the temporary file cannot be
/// created, written, flushed or renamed; in every case the target is left untouched.
pub fn atomic<F>(path: &Path, f: F) -> Result<(), CliError>
where
    F: FnOnce(&mut BufWriter<&File>) -> Result<(), CliError>,
{
    let tmp = temp_file(path)?;
    {
        let mut w = BufWriter::new(tmp.as_file());
        f(&mut w)?;
        w.flush().map_err(|e| cannot_write(path, &e))?;
    }
    finish(tmp, path)
}

/// Like [`atomic`] for a writer that opens a path itself (the plotting backends): `f` gets the
/// temporary file's path, which keeps the target's extension.
///
/// # Errors
/// As [`atomic`].
pub fn atomic_path<F>(path: &Path, f: F) -> Result<(), CliError>
where
    F: FnOnce(&Path) -> Result<(), CliError>,
{
    let tmp = temp_file(path)?;
    f(tmp.path())?;
    finish(tmp, path)
}

/// A file being written in a stream (a simulation run): a temporary file beside the target,
/// renamed over it by [`AtomicFile::commit`]; dropped without a commit, it is removed and the
/// target is untouched.
pub struct AtomicFile {
    tmp: NamedTempFile,
    path: PathBuf,
}

impl AtomicFile {
    /// Creates the temporary file for `path`.
    ///
    /// # Errors
    /// One sentence naming `path` when the directory does not exist or is not writable.
    pub fn create(path: &Path) -> Result<Self, CliError> {
        Ok(AtomicFile {
            tmp: temp_file(path)?,
            path: path.to_path_buf(),
        })
    }

    /// A buffered writer onto the temporary file (flush it before [`AtomicFile::commit`]).
    ///
    /// # Errors
    /// When the file handle cannot be duplicated.
    pub fn writer(&self) -> Result<BufWriter<File>, CliError> {
        let f = self
            .tmp
            .as_file()
            .try_clone()
            .map_err(|e| cannot_write(&self.path, &e))?;
        Ok(BufWriter::new(f))
    }

    /// Renames the complete file over the target.
    ///
    /// # Errors
    /// When it cannot be synced or renamed (the temporary file is then removed).
    pub fn commit(self) -> Result<(), CliError> {
        finish(self.tmp, &self.path)
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

/// A hidden temporary file next to `path`, `.NAME.XXXXXX.EXT`, with the permissions a new file
/// gets (0666 less the umask), not `tempfile`'s private 0600.
fn temp_file(path: &Path) -> Result<NamedTempFile, CliError> {
    let name = path
        .file_name()
        .ok_or_else(|| {
            CliError::input(format!("cannot write {}: not a file name", path.display()))
        })?
        .to_string_lossy();
    let suffix = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    let mut b = tempfile::Builder::new();
    let prefix = format!(".{name}.");
    b.prefix(&prefix).suffix(&suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    b.tempfile_in(directory(path))
        .map_err(|e| cannot_write(path, &e))
}

/// Flushes the temporary file to disk and renames it onto `path`; on failure it is removed
/// (dropping a `NamedTempFile` deletes it).
fn finish(tmp: NamedTempFile, path: &Path) -> Result<(), CliError> {
    tmp.as_file()
        .sync_all()
        .map_err(|e| cannot_write(path, &e))?;
    tmp.persist(path)
        .map_err(|e| cannot_write(path, &e.error))?;
    Ok(())
}

fn cannot_write(path: &Path, e: &std::io::Error) -> CliError {
    CliError::input(format!("cannot write {} ({e})", path.display()))
}
