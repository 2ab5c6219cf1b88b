//! The one error type of the library: every message is one sentence naming what is wrong and where.

use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Everything that can go wrong when building a model or calling an algorithm on bad input.
///
/// The `Display` text is a single sentence meant for a person: it names the offending item
/// (file and line, joint, frame, argument) and what is wrong with it. The variants carry what a
/// program needs to react (the I/O error's kind, the file and line of a parse error, the state
/// of a batch), so a front-end never parses the sentence.
///
/// ```
/// let e = screwdyn::Error::DimensionMismatch { what: "q".into(), got: 3, expected: 2, names: "j1, j2".into() };
/// assert_eq!(e.to_string(), "q has 3 values, the model has 2 joints: j1, j2");
/// ```
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// A joint-space vector has the wrong length.
    #[error("{what} has {got} values, the model has {expected} joints: {names}")]
    DimensionMismatch {
        /// The vector (an argument or flag name).
        what: String,
        /// Its length.
        got: usize,
        /// The number of joints.
        expected: usize,
        /// The joint names, for the message.
        names: String,
    },
    /// A number is NaN or infinite where a finite value is required.
    #[error("{what} contains a non-finite value ({value}) at position {index}")]
    NonFinite {
        /// The vector or quantity.
        what: String,
        /// Position of the first bad value.
        index: usize,
        /// The value, as text.
        value: String,
    },
    /// A result computed from finite inputs is NaN or infinite: the inputs are too large for
    /// double precision (see [`check_result`](crate::check_result)).
    #[error("the result {what} is not finite (NaN or infinite): the inputs are too large for double precision")]
    Overflow {
        /// The entry of the result (`tau.shoulder_pan_joint`, `(entry 3)`…).
        what: String,
    },
    /// A frame, body or joint name that the model does not have.
    #[error("the model has no {kind} named '{name}' (known: {known})")]
    UnknownName {
        /// `frame`, `joint`, `moving body`…
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// The names the model has (abbreviated when many).
        known: String,
    },
    /// A word naming one of a fixed set of choices (an integrator, a forward-dynamics method,
    /// a reference frame...) that is not one of them: the error of the library's `FromStr`
    /// implementations.
    ///
    /// ```
    /// use screwdyn::sim::Integrator;
    /// let e = "leapfrog".parse::<Integrator>().unwrap_err();
    /// assert!(matches!(e, screwdyn::Error::UnknownChoice { what: "integrator", .. }));
    /// assert_eq!(e.to_string(), "unknown integrator 'leapfrog' (use euler, rk4 or dopri5)");
    /// ```
    #[error("unknown {what} '{got}' (use {expected})")]
    UnknownChoice {
        /// What was being chosen (`integrator`, `reference`...).
        what: &'static str,
        /// The word given.
        got: String,
        /// The accepted words, as a phrase (`euler, rk4 or dopri5`).
        expected: &'static str,
    },
    /// A model description is inconsistent (bad tree, bad joint, bad inertia...).
    #[error("{0}")]
    InvalidModel(String),
    /// A description file could not be parsed: `file:line:column: message`, with the line and
    /// column when known. Made with [`Error::parse`] and [`Error::parse_at`].
    #[error("{}", located(file, *line, *column, message))]
    Parse {
        /// The file (or the name given to a text).
        file: String,
        /// The line (1-based), when known.
        line: Option<usize>,
        /// The column (1-based), when known (only with a line).
        column: Option<usize>,
        /// What is wrong, without the location.
        message: String,
    },
    /// A function argument is out of range or malformed (an id the model does not have, a
    /// buffer of the wrong size, a NaN option, a workspace made for another model...).
    #[error("{0}")]
    InvalidArgument(String),
    /// A numerical failure, e.g. a singular mass matrix in forward dynamics.
    #[error("{0}")]
    Numerical(String),
    /// Reading or writing a file failed. `message` is the whole sentence; `kind` says why
    /// (a missing file is [`ErrorKind::NotFound`], a forbidden one
    /// [`ErrorKind::PermissionDenied`]), so a front-end can choose its own error class.
    /// Made with [`Error::unreadable`], [`Error::unwritable`] or [`Error::io`].
    #[error("{message}")]
    Io {
        /// The file, when the error belongs to one.
        path: Option<PathBuf>,
        /// The operating system's reason (or [`ErrorKind::InvalidInput`] for a path that is
        /// not a regular file, [`ErrorKind::Other`] for a failure of a serialiser).
        kind: ErrorKind,
        /// The sentence for a person.
        message: String,
    },
    /// An error of one state of a batch call (see [`crate::batch`]): `state k: <error>`.
    /// Errors of the call itself (a buffer of the wrong size) carry no state.
    #[error("state {state}: {source}")]
    Batch {
        /// The index of the state.
        state: usize,
        /// What is wrong with it.
        source: Box<Error>,
    },
}

/// `file:line:column: message`, leaving out what is unknown.
fn located(file: &str, line: Option<usize>, column: Option<usize>, message: &str) -> String {
    match (line, column) {
        (Some(l), Some(c)) => format!("{file}:{l}:{c}: {message}"),
        (Some(l), None) => format!("{file}:{l}: {message}"),
        _ => format!("{file}: {message}"),
    }
}

impl Error {
    /// A parse error in `file` at no particular line.
    ///
    /// ```
    /// let e = screwdyn::Error::parse("arm.toml", "the DH table has no [[row]]");
    /// assert_eq!(e.to_string(), "arm.toml: the DH table has no [[row]]");
    /// ```
    pub fn parse(file: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Parse {
            file: file.into(),
            line: None,
            column: None,
            message: message.into(),
        }
    }

    /// A parse error at line `line` (1-based) of `file`.
    ///
    /// ```
    /// let e = screwdyn::Error::parse_at("arm.urdf", 12, "joint 'j' has no <child>");
    /// assert_eq!(e.to_string(), "arm.urdf:12: joint 'j' has no <child>");
    /// assert!(matches!(e, screwdyn::Error::Parse { line: Some(12), .. }));
    /// ```
    pub fn parse_at(file: impl Into<String>, line: usize, message: impl Into<String>) -> Self {
        Error::Parse {
            file: file.into(),
            line: Some(line),
            column: None,
            message: message.into(),
        }
    }

    /// An I/O error whose sentence is `message`.
    pub fn io(path: Option<PathBuf>, kind: ErrorKind, message: impl Into<String>) -> Self {
        Error::Io {
            path,
            kind,
            message: message.into(),
        }
    }

    /// `path` could not be read: `<path>: cannot be read (<reason>)`, with the reason's kind.
    ///
    /// ```
    /// use std::io::ErrorKind;
    /// let why = std::io::Error::from(ErrorKind::NotFound);
    /// let e = screwdyn::Error::unreadable("arm.urdf", &why);
    /// assert!(e.to_string().starts_with("arm.urdf: cannot be read ("));
    /// assert_eq!(e.io_kind(), Some(ErrorKind::NotFound));
    /// ```
    pub fn unreadable(path: impl AsRef<Path>, why: &std::io::Error) -> Self {
        let path = path.as_ref();
        Error::io(
            Some(path.to_path_buf()),
            why.kind(),
            format!("{}: cannot be read ({why})", path.display()),
        )
    }

    /// `path` could not be written: `cannot write <path> (<reason>)`, with the reason's kind.
    pub fn unwritable(path: impl AsRef<Path>, why: &std::io::Error) -> Self {
        let path = path.as_ref();
        Error::io(
            Some(path.to_path_buf()),
            why.kind(),
            format!("cannot write {} ({why})", path.display()),
        )
    }

    /// The kind of an [`Error::Io`] (also inside an [`Error::Batch`]); `None` for the others.
    pub fn io_kind(&self) -> Option<ErrorKind> {
        match self {
            Error::Io { kind, .. } => Some(*kind),
            Error::Batch { source, .. } => source.io_kind(),
            _ => None,
        }
    }

    /// This error as the error of state `state` of a batch ([`Error::Batch`]); an error that
    /// already names its state is returned as it is.
    ///
    /// ```
    /// let e = screwdyn::Error::Numerical("the mass matrix is singular".into()).in_state(4);
    /// assert_eq!(e.state(), Some(4));
    /// assert_eq!(e.to_string(), "state 4: the mass matrix is singular");
    /// ```
    pub fn in_state(self, state: usize) -> Self {
        match self {
            Error::Batch { .. } => self,
            other => Error::Batch {
                state,
                source: Box::new(other),
            },
        }
    }

    /// The same error with its state (if any) moved on by `offset`: a batch function called on
    /// the states `offset..` of a larger batch numbers them from 0.
    ///
    /// ```
    /// let e = screwdyn::Error::Numerical("singular".into()).in_state(2).offset_state(100);
    /// assert_eq!(e.state(), Some(102));
    /// ```
    pub fn offset_state(self, offset: usize) -> Self {
        match self {
            Error::Batch { state, source } => Error::Batch {
                state: state + offset,
                source,
            },
            other => other,
        }
    }

    /// The batch state this error belongs to (`None`: not a state's error).
    pub fn state(&self) -> Option<usize> {
        match self {
            Error::Batch { state, .. } => Some(*state),
            _ => None,
        }
    }

    /// The error itself, without the batch state around it (for a batch of one state, whose
    /// errors need no state number).
    ///
    /// ```
    /// let e = screwdyn::Error::Numerical("singular".into());
    /// assert_eq!(e.clone().in_state(0).without_state(), e);
    /// ```
    pub fn without_state(self) -> Error {
        match self {
            Error::Batch { source, .. } => *source,
            other => other,
        }
    }
}

/// Shorthand for `std::result::Result<T, screwdyn::Error>`.
pub type Result<T> = std::result::Result<T, Error>;

/// The spelling every named choice (`FromStr`) is matched in: trimmed, lower case, `_` read as
/// `-`, so that `LOCAL_WORLD_ALIGNED` (Pinocchio's name), `local_world_aligned` and
/// `local-world-aligned` are one choice. Error messages quote what the user wrote.
pub(crate) fn choice_key(s: &str) -> String {
    s.trim().to_ascii_lowercase().replace('_', "-")
}
