//! The one error type of the library: every message is one sentence naming what is wrong and where.

use thiserror::Error;

/// Everything that can go wrong when building a model or calling an algorithm on bad input.
///
/// The `Display` text is a single sentence meant for a person: it names the offending item
/// (file and line, joint, frame, argument) and what is wrong with it.
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
    /// A model description is inconsistent (bad tree, bad joint, bad inertia...).
    #[error("{0}")]
    InvalidModel(String),
    /// A description file could not be read or parsed; the message names file and line.
    #[error("{0}")]
    Parse(String),
    /// A function argument is out of range or malformed (an id the model does not have, a
    /// buffer of the wrong size, a NaN option, a workspace made for another model...).
    #[error("{0}")]
    InvalidArgument(String),
    /// A numerical failure, e.g. a singular mass matrix in forward dynamics.
    #[error("{0}")]
    Numerical(String),
    /// Reading or writing a file failed.
    #[error("{0}")]
    Io(String),
}

/// Shorthand for `std::result::Result<T, screwdyn::Error>`.
pub type Result<T> = std::result::Result<T, Error>;
