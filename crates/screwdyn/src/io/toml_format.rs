//! TOML descriptions: the top-level `format` key chooses the reader (DH, PoE or native).

use super::options::LoadOptions;
use super::{common, dh, native, poe};
use crate::error::{Error, Result};
use crate::model::Model;
use serde::Deserialize;

/// Loads a TOML description (any of the formats `dh`, `modified-dh`, `poe`, `screwdyn`, chosen by
/// its top-level `format` key).
///
/// # Errors
/// [`Error::Parse`] for malformed text (naming the file and, where known, the line) and
/// [`Error::InvalidModel`] for an inconsistent model (and, with `strict`, the first
/// physical-consistency problem).
///
/// ```
/// use screwdyn::io::{load_toml_str, LoadOptions};
/// let e = load_toml_str("name = 'x'\n", "x.toml", &LoadOptions::default()).unwrap_err();
/// assert!(e.to_string().starts_with("x.toml: the top-level key 'format' is missing"));
/// ```
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
        Some(other) => Err(Error::parse(
            file,
            format!("unknown format '{other}', expected one of dh, modified-dh, poe, screwdyn"),
        )),
        None => Err(Error::parse(
            file,
            "the top-level key 'format' is missing (one of dh, modified-dh, poe, screwdyn)",
        )),
    }
}
