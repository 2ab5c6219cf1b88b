//! Robot description formats, all producing the same [`Model`](crate::Model) (every key in
//! docs/formats.md):
//!
//! - **URDF** (`.urdf`): [`urdf::parse_urdf`], and the export [`urdf::to_urdf_string`];
//! - **MJCF**, MuJoCo's format (`.xml`): [`mjcf::parse_mjcf`], and the list of what it leaves
//!   out, [`mjcf::parse_mjcf_report`];
//! - **DH tables** (`.toml` with `format = "dh"` or `format = "modified-dh"`): [`dh`];
//! - **product of exponentials**, Modern Robotics style (`format = "poe"`): [`poe`], also as
//!   the API [`poe::from_poe`];
//! - **native TOML** (`format = "screwdyn"`), the `H_i^{λ(i)}(0)`, `S_i`, `𝔍^{i,i}`
//!   written directly: [`native`];
//! - **built-in robots**: `builtin:<name>` (see [`builtin`]).
//!
//! Any model is written as URDF ([`urdf::to_urdf_string`]) or as MJCF, MuJoCo's format
//! ([`mjcf_export::to_mjcf_string`]).
//!
//! Output files are written by the one rule of [`output`]: a regular file is replaced atomically,
//! a device or FIFO is written directly.
//!
//! [`load_model`] takes any of them by path; [`load_source`] also returns the text it read.
//! Every loader reports a broken file as an [`Error::Parse`](crate::Error::Parse) (syntax,
//! unknown keys, non-numbers) or [`Error::InvalidModel`](crate::Error::InvalidModel) (bad tree,
//! bad axis, non-physical inertia) whose message is one sentence starting with the file name
//! and, where known, the line.
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

pub mod builtin;
pub mod dh;
pub mod mjcf;
pub mod mjcf_export;
pub mod native;
pub mod output;
pub mod poe;
pub mod urdf;
pub mod visual;
mod xml_text;

// Written out from models/ by a test (builtin.rs), in the layout the test writes.
#[rustfmt::skip]
mod builtin_tables;
mod common;
mod options;
mod source;
mod toml_format;

pub use options::LoadOptions;
pub use source::{load_model, load_model_with, load_source, load_str, Format, Loaded};
pub use toml_format::load_toml_str;
