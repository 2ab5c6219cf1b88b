//! Robot description formats, all producing the same [`Model`] (DESIGN §4):
//!
//! - **URDF** (`.urdf`): [`urdf::parse_urdf`], and the export [`urdf::to_urdf_string`];
//! - **DH tables** (`.toml` with `format = "dh"` or `format = "modified-dh"`): [`dh`];
//! - **product of exponentials**, Modern Robotics style (`format = "poe"`): [`poe`], also as
//!   the API [`poe::from_poe`];
//! - **native TOML** (`format = "screwdyn"`), the seeds' `H_i^{λ(i)}(0)`, `S_i`, `𝔍^{i,i}`
//!   written directly: [`native`];
//! - **built-in robots**: `builtin:<name>` (see [`crate::builtin`]).
//!
//! Every loader reports a broken file as an [`Error::Parse`] (syntax, unknown keys, non-numbers)
//! or [`Error::InvalidModel`] (bad tree, bad axis, non-physical inertia) whose message is one
//! sentence starting with the file name and, where known, the line.
//!
//! ```
//! use screwdyn::io::{load_model, load_str, LoadOptions};
//! let m = load_model("builtin:planar2").unwrap();
//! assert_eq!(m.joint_names(), vec!["joint1", "joint2"]);
//!
//! let text = r#"
//! format = "dh"
//! [[row]]
//! type = "R"
//! a = 1.0
//! mass = 1.0
//! "#;
//! let one = load_str(text, "one.toml", &LoadOptions::default()).unwrap();
//! assert_eq!(one.nq(), 1);
//! let err = load_str("format = \"dh\"\nrows = 3\n", "bad.toml", &LoadOptions::default()).unwrap_err();
//! assert!(err.to_string().starts_with("bad.toml:2:"));
//! ```

pub mod dh;
pub mod native;
pub mod poe;
pub mod urdf;

mod common;

use crate::error::{Error, Result};
use crate::model::Model;
use serde::Deserialize;

/// Options shared by every loader.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Make physical-consistency problems (inertias not positive semi-definite or breaking
    /// the triangle inequality, massless moving leaves) errors. Off by default: such a file
    /// loads, and [`Model::physical_problems`] lists its problems, as Pinocchio would load it.
    pub strict: bool,
}

/// Loads a model from `builtin:<name>`, a `.urdf` file or a `.toml` file, with default options.
///
/// # Errors
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] for malformed text and [`Error::InvalidModel`] for an inconsistent model, each naming the file and, where known, the line (and, with `strict`, the first physical-consistency problem).
///
/// ```
/// let e = screwdyn::io::load_model("robot.xyz").unwrap_err().to_string();
/// assert!(e.contains("robot.xyz"));
/// ```
pub fn load_model(path_or_builtin: &str) -> Result<Model> {
    load_model_with(path_or_builtin, &LoadOptions::default())
}

/// Loads a model from `builtin:<name>`, a `.urdf` file or a `.toml` file.
///
/// # Errors
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] for malformed text and [`Error::InvalidModel`] for an inconsistent model, each naming the file and, where known, the line (and, with `strict`, the first physical-consistency problem).
pub fn load_model_with(path_or_builtin: &str, options: &LoadOptions) -> Result<Model> {
    if let Some(name) = path_or_builtin.strip_prefix("builtin:") {
        return crate::builtin::load(name);
    }
    let lower = path_or_builtin.to_ascii_lowercase();
    if !(lower.ends_with(".urdf") || lower.ends_with(".toml") || lower.ends_with(".xml")) {
        return Err(Error::Parse(format!(
            "{path_or_builtin}: unknown model format, expected a .urdf or .toml file or builtin:<name> ({})",
            crate::builtin::NAMES.join(", ")
        )));
    }
    // Regular files only: a FIFO or a device given as a model would block or never end.
    let meta = std::fs::metadata(path_or_builtin)
        .map_err(|e| Error::Io(format!("{path_or_builtin}: cannot be read ({e})")))?;
    if !meta.is_file() {
        return Err(Error::Io(format!(
            "{path_or_builtin}: is not a regular file (a model must be a .urdf or .toml file)"
        )));
    }
    let text = std::fs::read_to_string(path_or_builtin)
        .map_err(|e| Error::Io(format!("{path_or_builtin}: cannot be read ({e})")))?;
    load_str(&text, path_or_builtin, options)
}

/// Loads a model from the text of a description; `file` names it in messages and chooses the
/// format by its extension (`.urdf`/`.xml` or `.toml`).
///
/// # Errors
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] for malformed text and [`Error::InvalidModel`] for an inconsistent model, each naming the file and, where known, the line (and, with `strict`, the first physical-consistency problem).
pub fn load_str(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    let lower = file.to_ascii_lowercase();
    if lower.ends_with(".urdf") || lower.ends_with(".xml") {
        urdf::parse_urdf(text, file, options)
    } else {
        load_toml_str(text, file, options)
    }
}

/// Loads a TOML description (any of the formats `dh`, `modified-dh`, `poe`, `screwdyn`, chosen by
/// its top-level `format` key).
///
/// # Errors
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] for malformed text and [`Error::InvalidModel`] for an inconsistent model, each naming the file and, where known, the line (and, with `strict`, the first physical-consistency problem).
pub fn load_toml_str(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    #[derive(Deserialize)]
    struct Head {
        format: Option<String>,
    }
    let head: Head = common::from_toml(text, file)?;
    match head.format.as_deref() {
        Some("dh") | Some("modified-dh") => dh::parse_dh(text, file, options),
        Some("poe") => poe::parse_poe(text, file, options),
        Some("screwdyn") => native::parse_native(text, file, options),
        Some(other) => Err(Error::Parse(format!(
            "{file}: unknown format '{other}', expected one of dh, modified-dh, poe, screwdyn"
        ))),
        None => Err(Error::Parse(format!(
            "{file}: the top-level key 'format' is missing (one of dh, modified-dh, poe, screwdyn)"
        ))),
    }
}
