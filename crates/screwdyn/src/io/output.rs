//! Writing an output file so that nothing is lost and nothing is clobbered: the one rule of
//! every file the CLI, the viewer and the Python package write.
//!
//! - A **regular file**, or a path that does not exist yet, is *replaced*: the content goes to a
//!   hidden temporary file in the same directory (`.NAME.XXXXXX.EXT`, permissions of a new
//!   file), which is flushed to disk and renamed over the target only when complete. A failure
//!   part-way removes the temporary file and leaves the previous target as it was. A symbolic
//!   link to a regular file is followed: the file it points to is replaced, the link stays.
//! - Anything else that exists — a character or block device (`/dev/null`, `/dev/full`), a
//!   FIFO, a socket, also behind a symbolic link such as `/dev/stdout` — is written
//!   *directly*: opened for writing (not truncated, not replaced, not synced), so a device
//!   keeps being a device and a reader of a FIFO receives the data; every write error is
//!   reported (`/dev/full` gives "No space left on device").
//!
//! Errors are [`Error::Io`] with the sentence `cannot write PATH (reason)`.
//!
//! ```
//! use screwdyn::io::output::{write_file, OutputFile};
//! use std::io::Write;
//! let dir = std::env::temp_dir().join(format!("screwdyn-output-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let path = dir.join("run.csv");
//! std::fs::write(&path, "an older and longer file").unwrap();
//! write_file(&path, b"t\n0\n").unwrap();
//! assert_eq!(std::fs::read(&path).unwrap(), b"t\n0\n");
//!
//! // A stream: written through a buffer, then committed (renamed over the target).
//! let out = OutputFile::create(&path).unwrap();
//! assert!(!out.is_direct());
//! let mut w = out.writer().unwrap();
//! w.write_all(b"t\n1\n").unwrap();
//! w.flush().unwrap();
//! out.commit().unwrap();
//! assert_eq!(std::fs::read(&path).unwrap(), b"t\n1\n");
//!
//! // A device is written, never replaced.
//! #[cfg(unix)]
//! {
//!     assert!(OutputFile::create(std::path::Path::new("/dev/null")).unwrap().is_direct());
//!     write_file(std::path::Path::new("/dev/null"), b"gone").unwrap();
//! }
//! let e = write_file(&dir.join("no/such/dir.csv"), b"x").unwrap_err();
//! assert!(e.to_string().starts_with("cannot write "));
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

use crate::{Error, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use tempfile::NamedTempFile;

/// How `path` is written: `Some(target)` when it is replaced (a regular file, reached through
/// any symbolic links, or a path that does not exist yet: `target` is what the rename goes
/// over), `None` when it exists and is not a regular file (a device, FIFO or socket), so it is
/// written directly.
///
/// ```
/// use screwdyn::io::output::replaced_path;
/// use std::path::Path;
/// let new = std::env::temp_dir().join("screwdyn-not-there-yet.csv");
/// assert_eq!(replaced_path(&new), Some(new.clone()));
/// #[cfg(unix)]
/// assert_eq!(replaced_path(Path::new("/dev/null")), None);
/// ```
pub fn replaced_path(path: &Path) -> Option<PathBuf> {
    match std::fs::metadata(path) {
        // A directory is "replaced" too: the rename fails and reports it.
        Ok(m) if m.is_file() || m.is_dir() => {
            let through_link = std::fs::symlink_metadata(path)
                .map(|l| l.file_type().is_symlink())
                .unwrap_or(false);
            if m.is_file() && through_link {
                Some(std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()))
            } else {
                Some(path.to_path_buf())
            }
        }
        Ok(_) => None,
        // Does not exist (or a dangling link): a new file.
        Err(_) => Some(path.to_path_buf()),
    }
}

/// An output file being written: a temporary file renamed over the target by
/// [`OutputFile::commit`] (dropped without a commit, it is removed and the target untouched),
/// or a device or FIFO opened for writing directly (see the [module](self) documentation).
pub struct OutputFile {
    /// The path as given, for messages.
    path: PathBuf,
    dest: Destination,
}

enum Destination {
    /// The temporary file, the path it is renamed to, and its entry in the list of files being
    /// written (left when the file is committed or dropped).
    Replace(NamedTempFile, PathBuf, Listed),
    /// The device, FIFO or socket itself.
    Direct(File),
}

impl OutputFile {
    /// Opens `path` for writing: creates the temporary file beside it, or opens the device or
    /// FIFO (which waits for a reader of a FIFO).
    ///
    /// # Errors
    /// [`Error::Io`] naming `path` when the directory does not exist or is not writable, or the
    /// device cannot be opened.
    pub fn create(path: &Path) -> Result<Self> {
        let dest = match replaced_path(path) {
            Some(target) => {
                let tmp = temp_file(path, &target)?;
                let listed = Listed::new(tmp.path());
                Destination::Replace(tmp, target, listed)
            }
            None => Destination::Direct(
                std::fs::OpenOptions::new()
                    .write(true)
                    .open(path)
                    .map_err(|e| Error::unwritable(path, &e))?,
            ),
        };
        Ok(OutputFile {
            path: path.to_path_buf(),
            dest,
        })
    }

    /// Whether the target is written directly (a device, FIFO or socket), not replaced.
    pub fn is_direct(&self) -> bool {
        matches!(self.dest, Destination::Direct(_))
    }

    /// The path as given.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The temporary file being written, when the target is replaced (`None` when direct): for
    /// a writer that opens a path itself.
    pub fn temp_path(&self) -> Option<&Path> {
        match &self.dest {
            Destination::Replace(tmp, ..) => Some(tmp.path()),
            Destination::Direct(_) => None,
        }
    }

    /// The open file (the temporary file or the device).
    pub fn file(&self) -> &File {
        match &self.dest {
            Destination::Replace(tmp, ..) => tmp.as_file(),
            Destination::Direct(f) => f,
        }
    }

    /// A buffered writer onto [`OutputFile::file`] (flush it before [`OutputFile::commit`]).
    ///
    /// # Errors
    /// [`Error::Io`] naming the path when the file handle cannot be duplicated.
    pub fn writer(&self) -> Result<BufWriter<File>> {
        let f = self
            .file()
            .try_clone()
            .map_err(|e| Error::unwritable(&self.path, &e))?;
        Ok(BufWriter::new(f))
    }

    /// Completes the output: the temporary file is flushed to disk and renamed over the target
    /// (on failure it is removed); a direct target has already received everything.
    ///
    /// # Errors
    /// [`Error::Io`] naming the path when the file cannot be synced or renamed.
    pub fn commit(self) -> Result<()> {
        match self.dest {
            Destination::Replace(tmp, target, _listed) => tmp
                .as_file()
                .sync_all()
                .map_err(|e| Error::unwritable(&self.path, &e))
                .and_then(|()| {
                    tmp.persist(&target)
                        .map(drop)
                        .map_err(|e| Error::unwritable(&self.path, &e.error))
                }),
            Destination::Direct(_) => Ok(()),
        }
    }
}

/// Writes `bytes` to `path` by the rule of the [module](self): replaced whole when a regular
/// file (or new), written directly when a device or FIFO.
///
/// # Errors
/// [`Error::Io`] naming `path` (`cannot write PATH (reason)`); a replaced target is then left as
/// it was and no temporary file remains.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    let out = OutputFile::create(path)?;
    let mut file = out.file();
    file.write_all(bytes)
        .and_then(|()| file.flush())
        .map_err(|e| Error::unwritable(path, &e))?;
    out.commit()
}

/// A hidden temporary file beside `target`, `.NAME.XXXXXX.EXT` (NAME and EXT those of `path`),
/// with the permissions a new file gets (0666 less the umask), not `tempfile`'s private 0600.
fn temp_file(path: &Path, target: &Path) -> Result<NamedTempFile> {
    let name = path
        .file_name()
        .ok_or_else(|| {
            Error::io(
                Some(path.to_path_buf()),
                std::io::ErrorKind::InvalidInput,
                format!("cannot write {}: not a file name", path.display()),
            )
        })?
        .to_string_lossy();
    let suffix = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    // The process id in the name tells a later write whether the writer is still alive.
    let prefix = format!(".{name}.{}.", std::process::id());
    let mut b = tempfile::Builder::new();
    b.prefix(&prefix).suffix(&suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    remove_stale(dir, &format!(".{name}."), &suffix);
    let tmp = b
        .tempfile_in(dir)
        .map_err(|e| Error::unwritable(path, &e))?;
    Ok(tmp)
}

/// The temporary files this process is writing (removed from the list when committed or
/// dropped), for [`remove_pending`].
fn pending() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    static PENDING: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// A temporary file's entry in [`pending`]: listed when made, off the list when dropped (after
/// the file is renamed, or removed with its dropped `NamedTempFile`).
struct Listed(PathBuf);

impl Listed {
    fn new(tmp: &Path) -> Self {
        pending().push(tmp.to_path_buf());
        Listed(tmp.to_path_buf())
    }
}

impl Drop for Listed {
    fn drop(&mut self) {
        pending().retain(|p| p != &self.0);
    }
}

/// Removes the temporary files this process is writing and returns them: what a program calls
/// when a signal (`SIGTERM`, `SIGINT`) ends it before its outputs are complete, so that no
/// partial file is left behind (the targets stay as they were).
pub fn remove_pending() -> Vec<PathBuf> {
    let files = std::mem::take(&mut *pending());
    for f in &files {
        let _ = std::fs::remove_file(f);
    }
    files
}

/// Removes temporary files of ours for the same target, `PREFIX<pid>.XXXXXX<suffix>`, whose
/// process no longer runs (a writer killed by `SIGKILL` or a power cut). Only where the
/// process table can be read (`/proc`); elsewhere they stay.
fn remove_stale(dir: &Path, prefix: &str, suffix: &str) {
    let proc_root = Path::new("/proc/self");
    if !proc_root.exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(rest) = name.to_str().and_then(|n| n.strip_prefix(prefix)) else {
            continue;
        };
        let Some((pid, random)) = rest.split_once('.') else {
            continue;
        };
        let ours = pid.parse::<u32>().is_ok() && random.ends_with(suffix);
        if ours && !Path::new("/proc").join(pid).exists() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("screwdyn-output-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// A file being written is on the list a signal handler empties until it is committed or
    /// dropped (the list is read, not emptied: other tests write files at the same time).
    #[test]
    fn only_unfinished_files_are_listed() {
        let dir = scratch("listed");
        let temp = |o: &OutputFile| o.temp_path().unwrap().to_path_buf();
        let committed = OutputFile::create(&dir.join("a.csv")).unwrap();
        let dropped = OutputFile::create(&dir.join("b.csv")).unwrap();
        let unfinished = OutputFile::create(&dir.join("c.csv")).unwrap();
        let (a, b, c) = (temp(&committed), temp(&dropped), temp(&unfinished));
        assert!([&a, &b, &c].iter().all(|p| pending().contains(p)));
        committed.commit().unwrap();
        drop(dropped);
        let listed = pending().clone();
        assert!(listed.contains(&c), "{listed:?}");
        assert!(!listed.contains(&a) && !listed.contains(&b), "{listed:?}");
        drop(unfinished);
        assert!(!pending().contains(&c));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_stream_leaves_the_target_and_no_temporary() {
        let dir = scratch("drop");
        let path = dir.join("keep.csv");
        std::fs::write(&path, "previous").unwrap();
        let out = OutputFile::create(&path).unwrap();
        out.writer().unwrap().write_all(b"half").unwrap();
        drop(out);
        assert_eq!(std::fs::read(&path).unwrap(), b"previous");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_link_to_a_file_stays_a_link() {
        let dir = scratch("link");
        let real = dir.join("real.csv");
        let link = dir.join("link.csv");
        std::fs::write(&real, "old").unwrap();
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_file(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_full_device_reports_the_full_disk() {
        let e = write_file(Path::new("/dev/full"), b"x").unwrap_err();
        let msg = e.to_string();
        assert!(msg.starts_with("cannot write /dev/full ("), "{msg}");
        assert!(msg.contains("No space left on device"), "{msg}");
        assert!(!Path::new("/dev/full").metadata().unwrap().is_file());
    }
}
