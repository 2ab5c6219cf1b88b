//! # screwdyn-view
//!
//! See the robot: one self-contained HTML page (no server, no network, no external file) that
//! draws a [`screwdyn::Model`] in 3-D with WebGL — orbit, zoom, pan, a floor grid and the base
//! frame — and, given a [`Run`], animates it with a time slider, a speed control and a small
//! synchronised plot of `q`, `τ` and the energies, highlighting the joints past a position
//! limit or an effort limit at the times they are.
//!
//! Geometry comes from the model's visuals, a format-neutral list the library reads
//! ([`screwdyn::io::visual::visuals_of`]): a URDF's `<visual>` elements or an MJCF's visual
//! geoms (boxes, spheres, cylinders, capsules, ellipsoids and STL, OBJ and Collada meshes, with
//! their colours; see [`visual`] and [`mesh`]); a model without visuals (DH, PoE, TOML,
//! built-ins) is drawn as a skeleton built from its screw axes (see [`scene`]). Every pose
//! on the page is computed here, by the library's forward kinematics
//! `H_i^0 = H_{λ(i)}^0 H_i^{λ(i)}(0) e^{[S_i] q_i}` (Lynch & Park, *Modern Robotics*); the page's JavaScript only
//! multiplies matrices it is given.
//!
//! The page embeds its data as base64 little-endian `float32` arrays. Two caps keep it small:
//! [`DEFAULT_MAX_TRIANGLES`] for the meshes (decimated to fit, with a warning) and
//! [`DEFAULT_MAX_SAMPLES`] for the run (evenly strided; violations of dropped samples are kept).
//!
//! ```
//! use screwdyn_view::{render_html, ViewOptions};
//! let model = screwdyn::builtin::planar2();
//! let page = render_html(&model, &ViewOptions::default()).unwrap();
//! assert!(page.html.starts_with("<!DOCTYPE html>"));
//! assert!(page.html.contains("joint2"));
//! assert!(page.warnings.is_empty());
//! ```

mod html;
pub mod mesh;
pub mod run;
pub mod scene;
pub mod visual;

pub use html::render_html;
pub use run::{read_run, Run};

use std::path::{Path, PathBuf};

/// Default cap on the triangles embedded in a page (all meshes together). The UR5's and the
/// Panda's visual meshes fit under it; larger meshes are decimated to fit.
pub const DEFAULT_MAX_TRIANGLES: usize = 200_000;

/// Default cap on the samples of a run embedded in a page (a 10 s run at 1 kHz is strided to
/// 1000 samples, 100 per second).
pub const DEFAULT_MAX_SAMPLES: usize = 1000;

/// What to draw besides the model.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    /// The configuration shown when there is no run (zeros when `None`).
    pub q: Option<Vec<f64>>,
    /// A run to animate (see [`read_run`] and [`Run::from_recording`]).
    pub run: Option<Run>,
    /// The URDF or MJCF file the model was loaded from: its visuals (a URDF's `<visual>`
    /// elements, an MJCF's visual geoms, see [`screwdyn::io::visual::visuals_of`]) are drawn.
    /// `None` (DH, PoE, TOML, built-ins) draws the skeleton.
    pub description: Option<PathBuf>,
    /// The text of `description` when the caller has already read it (see
    /// [`screwdyn::io::Loaded::description`]); `None` reads the file.
    pub description_text: Option<String>,
    /// Folders searched for `package://` mesh paths, before `ROS_PACKAGE_PATH`.
    pub package_paths: Vec<PathBuf>,
    /// Cap on the embedded triangles ([`DEFAULT_MAX_TRIANGLES`]).
    pub max_triangles: usize,
    /// The page title (the model's name when `None`).
    pub title: Option<String>,
}

impl Default for ViewOptions {
    fn default() -> Self {
        ViewOptions {
            q: None,
            run: None,
            description: None,
            description_text: None,
            package_paths: Vec::new(),
            max_triangles: DEFAULT_MAX_TRIANGLES,
            title: None,
        }
    }
}

/// What kind of problem a [`Warning`] reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WarningKind {
    /// A mesh file was not found (a stand-in box is drawn).
    MeshMissing,
    /// A mesh file could not be read or parsed (a stand-in box is drawn).
    MeshUnreadable,
    /// The meshes were simplified to fit the triangle cap.
    Decimated,
}

/// A problem that did not stop the page from being written.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    /// What kind of problem.
    pub kind: WarningKind,
    /// One sentence for a person.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// A generated page.
#[derive(Clone, Debug)]
pub struct Page {
    /// The HTML text (one self-contained file).
    pub html: String,
    /// Missing or unreadable meshes, decimation.
    pub warnings: Vec<Warning>,
    /// Triangles embedded.
    pub triangles: usize,
    /// Run samples embedded (0 without a run).
    pub samples: usize,
}

impl Page {
    /// Writes the page to `path`, as [`write_atomically`] does.
    ///
    /// # Errors
    /// As [`write_atomically`].
    pub fn save(&self, path: &Path) -> screwdyn::Result<()> {
        write_atomically(path, self.html.as_bytes())
    }
}

/// Writes `bytes` to `path` by the library's one output rule
/// ([`screwdyn::io::output::write_file`]): a regular file (or a new one) is written to a
/// temporary file beside it, flushed to disk and renamed over it, so a browser (or a reader of
/// a run file) never sees a half-written file and a failed write leaves no temporary behind; a
/// device or FIFO (`/dev/null`, `/dev/stdout` on a pipe) is written directly, never replaced.
///
/// # Errors
/// [`screwdyn::Error::Io`] naming `path` when the folder does not exist or cannot be written,
/// or the device reports an error.
///
/// ```
/// let dir = std::env::temp_dir().join(format!("screwdyn-view-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let page = dir.join("robot.html");
/// screwdyn_view::write_atomically(&page, b"<!DOCTYPE html>").unwrap();
/// assert_eq!(std::fs::read(&page).unwrap(), b"<!DOCTYPE html>");
/// let e = screwdyn_view::write_atomically(&dir.join("no/such/dir.html"), b"x").unwrap_err();
/// assert!(e.to_string().starts_with("cannot write"));
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn write_atomically(path: &Path, bytes: &[u8]) -> screwdyn::Result<()> {
    screwdyn::io::output::write_file(path, bytes)
}
