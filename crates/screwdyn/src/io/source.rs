//! Loading a model from where a user names it: `builtin:<name>` or a `.urdf`/`.toml` file, read
//! once; [`load_source`] also returns the text and the path.

use super::builtin;
use super::mjcf;
use super::options::LoadOptions;
use super::toml_format::load_toml_str;
use super::urdf;
use crate::error::{Error, Result};
use crate::model::Model;
use std::io::ErrorKind;
use std::path::PathBuf;

/// A model together with what it was loaded from.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The model.
    pub model: Model,
    /// The text of the description, as read: the file's contents, or the shipped description
    /// of a built-in robot made from one (`ur5`, `panda`, `branched`); `None` for the built-ins
    /// built in code (`planar2`, `pendulum`).
    pub text: Option<String>,
    /// The file it was read from (as given); `None` for a built-in robot.
    pub path: Option<PathBuf>,
}

/// Loads a model from `builtin:<name>`, a `.urdf` file or a `.toml` file, with default options.
///
/// # Errors
/// As [`load_source`].
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
/// As [`load_source`].
pub fn load_model_with(path_or_builtin: &str, options: &LoadOptions) -> Result<Model> {
    load_source(path_or_builtin, options).map(|loaded| loaded.model)
}

/// Loads a model from `builtin:<name>`, a `.urdf` file or a `.toml` file, and returns it with
/// the text it was parsed from and the file's path, reading the file once (for a front-end
/// that keeps the text, e.g. to rebuild the model or to draw a URDF's visuals).
///
/// # Errors
/// [`Error::UnknownName`] for an unknown built-in; [`Error::Parse`] for a path that is neither
/// a `.urdf`/`.xml` nor a `.toml` file, and for malformed text; [`Error::Io`] when the file
/// cannot be read (its [`kind`](Error::io_kind) says why: `NotFound`, `PermissionDenied`...,
/// `InvalidInput` for a path that is not a regular file); [`Error::InvalidModel`] for an
/// inconsistent model. Each names the file and, where known, the line (and, with `strict`,
/// the first physical-consistency problem).
///
/// ```
/// use screwdyn::io::{load_source, LoadOptions};
/// let path = std::env::temp_dir().join(format!("screwdyn-doc-{}.toml", std::process::id()));
/// let text = "format = \"dh\"\n[[row]]\ntype = \"R\"\na = 1.0\nmass = 1.0\n";
/// std::fs::write(&path, text).unwrap();
/// let loaded = load_source(path.to_str().unwrap(), &LoadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(loaded.model.nq(), 1);
/// assert_eq!(loaded.text.as_deref(), Some(text));
/// assert_eq!(loaded.path.as_deref(), Some(path.as_path()));
///
/// let ur5 = load_source("builtin:ur5", &LoadOptions::default()).unwrap();
/// assert!(ur5.text.unwrap().contains("format") && ur5.path.is_none());
/// ```
pub fn load_source(path_or_builtin: &str, options: &LoadOptions) -> Result<Loaded> {
    if let Some(name) = path_or_builtin.strip_prefix("builtin:") {
        return Ok(Loaded {
            model: builtin::load(name)?,
            text: builtin::description(name).map(str::to_string),
            path: None,
        });
    }
    if Format::of_file(path_or_builtin).is_none() {
        return Err(Error::parse(
            path_or_builtin,
            format!(
                "unknown model format, expected a .urdf, .xml (MJCF) or .toml file or builtin:<name> ({})",
                builtin::NAMES.join(", ")
            ),
        ));
    }
    // Regular files only: a FIFO or a device given as a model would block or never end.
    let meta =
        std::fs::metadata(path_or_builtin).map_err(|e| Error::unreadable(path_or_builtin, &e))?;
    if !meta.is_file() {
        return Err(Error::io(
            Some(PathBuf::from(path_or_builtin)),
            ErrorKind::InvalidInput,
            format!(
                "{path_or_builtin}: is not a regular file (a model must be a .urdf, .xml or .toml file)"
            ),
        ));
    }
    let text = std::fs::read_to_string(path_or_builtin)
        .map_err(|e| Error::unreadable(path_or_builtin, &e))?;
    let model = load_str(&text, path_or_builtin, options)?;
    Ok(Loaded {
        model,
        text: Some(text),
        path: Some(PathBuf::from(path_or_builtin)),
    })
}

/// Loads a model from the text of a description; `file` names it in messages and chooses the
/// format by its extension (`.urdf`/`.xml` or `.toml`).
///
/// # Errors
/// [`Error::Parse`] for malformed text and [`Error::InvalidModel`] for an inconsistent model,
/// each naming the file and, where known, the line (and, with `strict`, the first
/// physical-consistency problem).
pub fn load_str(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    match Format::of_file(file) {
        Some(Format::Urdf) => urdf::parse_urdf(text, file, options),
        // A `.xml` file whose root element is <robot> is URDF.
        Some(Format::Mjcf) if Format::of_text(text) == Format::Urdf => {
            urdf::parse_urdf(text, file, options)
        }
        Some(Format::Mjcf) => mjcf::parse_mjcf(text, file, options),
        _ => load_toml_str(text, file, options),
    }
}

/// The kind of description a file holds, told by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// URDF (`.urdf`; a `.xml` file whose root element is `<robot>`).
    Urdf,
    /// MJCF, MuJoCo's format (`.xml`).
    Mjcf,
    /// TOML: DH, modified DH, product of exponentials or screwdyn's own (`.toml`).
    Toml,
}

impl Format {
    /// The format of the file named `file` (case-insensitive extension); `None` for another
    /// extension.
    ///
    /// ```
    /// use screwdyn::io::Format;
    /// assert_eq!(Format::of_file("robots/UR5.URDF"), Some(Format::Urdf));
    /// assert_eq!(Format::of_file("arm.toml"), Some(Format::Toml));
    /// assert_eq!(Format::of_file("ur5e.xml"), Some(Format::Mjcf));
    /// assert_eq!(Format::of_file("arm.json"), None);
    /// ```
    pub fn of_file(file: &str) -> Option<Format> {
        let lower = file.to_ascii_lowercase();
        if lower.ends_with(".urdf") {
            Some(Format::Urdf)
        } else if lower.ends_with(".xml") {
            Some(Format::Mjcf)
        } else if lower.ends_with(".toml") {
            Some(Format::Toml)
        } else {
            None
        }
    }
}

impl Format {
    /// The format of a description given as text alone: MJCF when its root element is
    /// `<mujoco>`, URDF for any other XML, else TOML.
    ///
    /// ```
    /// use screwdyn::io::Format;
    /// assert_eq!(Format::of_text("  <robot name='r'/>"), Format::Urdf);
    /// assert_eq!(Format::of_text("<?xml version='1.0'?>\n<!-- arm -->\n<mujoco model='a'/>"), Format::Mjcf);
    /// assert_eq!(Format::of_text("format = \"dh\""), Format::Toml);
    /// ```
    pub fn of_text(text: &str) -> Format {
        let t = text.trim_start();
        if !t.starts_with('<') {
            return Format::Toml;
        }
        // The first element's tag, past the XML declaration, comments and doctype.
        let mut rest = t;
        while let Some(i) = rest.find('<') {
            rest = &rest[i + 1..];
            if rest.starts_with('?') || rest.starts_with('!') {
                continue;
            }
            return if rest.starts_with("mujoco") {
                Format::Mjcf
            } else {
                Format::Urdf
            };
        }
        Format::Urdf
    }

    /// A file name for a text in this format called `name`: `name` itself when it already ends
    /// in one of the format's extensions, else `name` with `.urdf`, `.xml` or `.toml` appended (the
    /// loaders choose the format by the extension).
    ///
    /// ```
    /// use screwdyn::io::Format;
    /// assert_eq!(Format::Toml.file_name("arm"), "arm.toml");
    /// assert_eq!(Format::Urdf.file_name("arm.xml"), "arm.xml");
    /// ```
    pub fn file_name(self, name: &str) -> String {
        // A `.xml` name suits URDF too: a `.xml` text whose root is <robot> loads as URDF.
        let xml_urdf = self == Format::Urdf && Format::of_file(name) == Some(Format::Mjcf);
        if Format::of_file(name) == Some(self) || xml_urdf {
            name.to_string()
        } else {
            match self {
                Format::Urdf => format!("{name}.urdf"),
                Format::Mjcf => format!("{name}.xml"),
                Format::Toml => format!("{name}.toml"),
            }
        }
    }
}

/// A format by name: `urdf`, `mjcf` (or `xml`), `toml`, or a TOML description's kind (`dh`,
/// `modified-dh`, `poe`, `screwdyn`), any case.
impl std::str::FromStr for Format {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match crate::error::choice_key(s).as_str() {
            "urdf" => Ok(Format::Urdf),
            "mjcf" | "xml" => Ok(Format::Mjcf),
            "toml" | "dh" | "modified-dh" | "poe" | "screwdyn" => Ok(Format::Toml),
            _ => Err(Error::UnknownChoice {
                what: "format",
                got: s.into(),
                expected: "urdf, mjcf, xml, toml, dh, modified-dh, poe or screwdyn",
            }),
        }
    }
}

impl Loaded {
    /// The URDF file and its text when the model was read from one (its `<visual>` elements
    /// can then be drawn); `None` for a TOML or MJCF description or a built-in robot.
    ///
    /// ```
    /// use screwdyn::io::{load_source, LoadOptions};
    /// let ur5 = load_source("builtin:ur5", &LoadOptions::default()).unwrap();
    /// assert!(ur5.urdf().is_none());
    /// ```
    pub fn urdf(&self) -> Option<(&std::path::Path, &str)> {
        let path = self.path.as_deref()?;
        let text = self.text.as_deref()?;
        let urdf = match Format::of_file(&path.to_string_lossy()) {
            Some(Format::Urdf) => true,
            Some(Format::Mjcf) => Format::of_text(text) == Format::Urdf,
            _ => false,
        };
        urdf.then_some((path, text))
    }

    /// The URDF or MJCF file and its text when the model was read from one (its visuals can
    /// then be drawn, see [`crate::io::visual::visuals_of`]); `None` for a TOML description
    /// or a built-in robot.
    ///
    /// ```
    /// use screwdyn::io::{load_source, LoadOptions};
    /// let planar = load_source("builtin:planar2", &LoadOptions::default()).unwrap();
    /// assert!(planar.description().is_none());
    /// ```
    pub fn description(&self) -> Option<(&std::path::Path, &str)> {
        let path = self.path.as_deref()?;
        let text = self.text.as_deref()?;
        matches!(
            Format::of_file(&path.to_string_lossy()),
            Some(Format::Urdf | Format::Mjcf)
        )
        .then_some((path, text))
    }
}
