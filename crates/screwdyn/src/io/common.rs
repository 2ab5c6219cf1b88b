//! Pieces shared by the TOML formats: error positions, poses, inertias, extra frames, limits.

use super::options::LoadOptions;
use crate::error::{Error, Result};
use crate::model::{JointSpec, Model, ModelBuilder};
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::{Matrix3, Matrix6, Quaternion, UnitQuaternion, Vector3};
use serde::de::DeserializeOwned;
use serde::Deserialize;

/// Line and column (1-based) of byte offset `at` in `text`.
pub(crate) fn line_col(text: &str, at: usize) -> (usize, usize) {
    let at = at.min(text.len());
    let before = &text[..at];
    // Bytes, not chars: a newline byte is always a newline (UTF-8), and the count vectorises.
    let line = before.bytes().filter(|&b| b == b'\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |s| s.chars().count()) + 1;
    (line, col)
}

/// Where an element of a description starts: its file and line.
pub(crate) struct At<'f> {
    pub file: &'f str,
    pub line: usize,
}

impl At<'_> {
    /// A parse error at this place.
    pub fn error(&self, message: impl Into<String>) -> Error {
        Error::parse_at(self.file, self.line, message)
    }
}

/// `file:line`, the form the model builder's messages take.
impl std::fmt::Display for At<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.file, self.line)
    }
}

/// The place of an element of a TOML file, from its span (the start of its table).
pub(crate) fn at_line<'f, T>(file: &'f str, text: &str, element: &toml::Spanned<T>) -> At<'f> {
    Lines::new(text).at(file, element)
}

/// Line numbers of the elements of one text, each counted on from the previous element's
/// line (the tables of a file come in file order), not from the text's start for every one.
pub(crate) struct Lines<'t> {
    text: &'t str,
    /// The byte offset counted up to, and its line (1-based).
    offset: usize,
    line: usize,
}

impl<'t> Lines<'t> {
    pub fn new(text: &'t str) -> Self {
        Lines {
            text,
            offset: 0,
            line: 1,
        }
    }

    /// The place of `element` (as [`at_line`]).
    pub fn at<'f, T>(&mut self, file: &'f str, element: &toml::Spanned<T>) -> At<'f> {
        let at = element.span().start.min(self.text.len());
        if at < self.offset {
            (self.offset, self.line) = (0, 1);
        }
        let between = &self.text.as_bytes()[self.offset..at];
        self.line += between.iter().filter(|&&b| b == b'\n').count();
        self.offset = at;
        At {
            file,
            line: self.line,
        }
    }
}

/// Deserializes TOML, turning an error into `file:line:col: message`.
pub(crate) fn from_toml<T: DeserializeOwned>(text: &str, file: &str) -> Result<T> {
    toml::from_str(text).map_err(|e| {
        let msg = e.message().trim().trim_end_matches('.').replace('\n', " ");
        match e.span() {
            Some(span) => {
                let (line, column) = line_col(text, span.start);
                Error::Parse {
                    file: file.into(),
                    line: Some(line),
                    column: Some(column),
                    message: msg,
                }
            }
            None => Error::parse(file, msg),
        }
    })
}

/// The robot name used when a file gives none: the file name without directory and extension.
pub(crate) fn default_name(file: &str) -> String {
    let base = file.rsplit(['/', '\\']).next().unwrap_or(file);
    base.split('.').next().unwrap_or(base).to_string()
}

/// Prefixes a builder error with the file name.
pub(crate) fn build(b: &ModelBuilder, file: &str) -> Result<Model> {
    b.build().map_err(|e| match e {
        Error::InvalidModel(m) => Error::InvalidModel(format!("{file}: {m}")),
        other => other,
    })
}

/// A rigid placement in a TOML file: `xyz` plus at most one of `rpy` (URDF convention
/// `Rz·Ry·Rx`), `quaternion` (`[w, x, y, z]`, normalised) or `rotation` (3×3, rows).
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct PoseSpec {
    #[serde(default)]
    pub xyz: Option<[f64; 3]>,
    #[serde(default)]
    pub rpy: Option<[f64; 3]>,
    #[serde(default)]
    pub quaternion: Option<[f64; 4]>,
    #[serde(default)]
    pub rotation: Option<[[f64; 3]; 3]>,
}

impl PoseSpec {
    /// The pose, or a phrase saying what is wrong.
    ///
    /// # Errors
    /// A phrase saying which value is malformed (the loader adds file and line).
    pub fn to_se3(&self) -> std::result::Result<Se3, String> {
        let n = self.rpy.is_some() as u8
            + self.quaternion.is_some() as u8
            + self.rotation.is_some() as u8;
        if n > 1 {
            return Err("gives more than one of rpy, quaternion and rotation".into());
        }
        let mut h = if let Some([r, p, y]) = self.rpy {
            Se3::from_rpy(r, p, y)
        } else if let Some([w, x, y, z]) = self.quaternion {
            // Scaled first, so that a huge quaternion normalises instead of overflowing.
            let scale = [w, x, y, z].iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            if !(scale.is_finite() && scale > 0.0) {
                return Err("has a zero quaternion (or a non-finite one)".into());
            }
            let q = Quaternion::new(w / scale, x / scale, y / scale, z / scale);
            if q.norm() * scale <= 1e-9 {
                return Err("has a zero quaternion".into());
            }
            Se3::new(
                UnitQuaternion::from_quaternion(q)
                    .to_rotation_matrix()
                    .into_inner(),
                Vector3::zeros(),
            )
        } else if let Some(rows) = self.rotation {
            let r = Matrix3::from_fn(|i, j| rows[i][j]);
            if (r.transpose() * r - Matrix3::identity()).amax() > 1e-6 || r.determinant() < 0.0 {
                return Err(
                    "has a rotation matrix that is not orthonormal with determinant +1".into(),
                );
            }
            Se3::new(r, Vector3::zeros())
        } else {
            Se3::identity()
        };
        if let Some(p) = self.xyz {
            h.translation = Vector3::from(p);
        }
        if !h
            .rotation
            .iter()
            .chain(h.translation.iter())
            .all(|x| x.is_finite())
        {
            return Err("has a non-finite number".into());
        }
        Ok(h)
    }
}

/// Inertia of a link: `mass` + `com` + `inertia` (about the CoM, link-frame axes, in URDF order
/// `[ixx, ixy, ixz, iyy, iyz, izz]`), or a full 6×6 `spatial_inertia` (angular first, about the
/// link frame origin).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct InertiaSpec {
    #[serde(default)]
    pub mass: Option<f64>,
    #[serde(default)]
    pub com: Option<[f64; 3]>,
    #[serde(default)]
    pub inertia: Option<[f64; 6]>,
    #[serde(default)]
    pub spatial_inertia: Option<[[f64; 6]; 6]>,
}

/// `[ixx, ixy, ixz, iyy, iyz, izz]` → symmetric 3×3.
pub(crate) fn inertia_matrix(i: [f64; 6]) -> Matrix3<f64> {
    let [xx, xy, xz, yy, yz, zz] = i;
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

impl InertiaSpec {
    ///
    /// # Errors
    /// A phrase saying which value is malformed (the loader adds file and line).
    pub fn to_inertia(&self) -> std::result::Result<SpatialInertia, String> {
        if let Some(rows) = self.spatial_inertia {
            if self.mass.is_some() || self.com.is_some() || self.inertia.is_some() {
                return Err("gives both spatial_inertia and mass/com/inertia".into());
            }
            let j = Matrix6::from_fn(|i, k| rows[i][k]);
            return SpatialInertia::from_matrix(&j).map_err(|why| {
                format!("has a spatial_inertia that is not a spatial inertia: {why}")
            });
        }
        if self.mass.is_none() && (self.com.is_some() || self.inertia.is_some()) {
            return Err("gives com or inertia without mass".into());
        }
        let m = self.mass.unwrap_or(0.0);
        let c = Vector3::from(self.com.unwrap_or([0.0; 3]));
        let i = inertia_matrix(self.inertia.unwrap_or([0.0; 6]));
        Ok(SpatialInertia::new(m, c, i))
    }
}

/// An extra named frame: `name`, `link`, and its `pose` in the link frame.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct FrameSpec {
    pub name: String,
    pub link: String,
    #[serde(default)]
    pub pose: PoseSpec,
}

/// Adds the extra frames (`text` is the file's contents, for the line of a bad frame).
pub(crate) fn add_frames(
    b: &mut ModelBuilder,
    frames: &[toml::Spanned<FrameSpec>],
    file: &str,
    text: &str,
) -> Result<()> {
    for spanned in frames {
        let f = spanned.get_ref();
        let h = f.pose.to_se3().map_err(|why| {
            at_line(file, text, spanned).error(format!("the pose of frame '{}' {why}", f.name))
        })?;
        b.frame(&f.name, &f.link, h);
    }
    Ok(())
}

/// The `limits = { lower, upper, velocity, effort }` table of a TOML joint (each optional,
/// infinite when absent).
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct LimitSpec {
    #[serde(default)]
    pub lower: Option<f64>,
    #[serde(default)]
    pub upper: Option<f64>,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub effort: Option<f64>,
}

impl LimitSpec {
    /// The limits, and the joint's `damping`, `friction` and `armature` keys when present.
    pub fn apply(
        &self,
        mut j: JointSpec,
        damping: Option<f64>,
        friction: Option<f64>,
        armature: Option<f64>,
    ) -> JointSpec {
        let d = crate::model::JointLimits::<f64>::default();
        j = j.limits(self.lower.unwrap_or(d.lower), self.upper.unwrap_or(d.upper));
        if let Some(v) = self.velocity {
            j = j.velocity_limit(v);
        }
        if let Some(e) = self.effort {
            j = j.effort_limit(e);
        }
        if let Some(x) = damping {
            j = j.damping(x);
        }
        if let Some(x) = friction {
            j = j.friction(x);
        }
        if let Some(x) = armature {
            j = j.armature(x);
        }
        j
    }
}

/// The joint spring of the TOML keys `stiffness` (`k`, default 0) and `springref`
/// (`q_spring`, default 0): simulation applies `τ = −k (q − q_spring)`.
pub(crate) fn spring(j: JointSpec, stiffness: Option<f64>, springref: Option<f64>) -> JointSpec {
    if stiffness.is_none() && springref.is_none() {
        return j;
    }
    j.spring(stiffness.unwrap_or(0.0), springref.unwrap_or(0.0))
}

/// The keys every TOML description shares — `name`, `base`, `gravity` and the `[[frame]]`
/// tables — read from any of the three formats (DH, PoE, native), and what they do to the
/// builder.
pub(crate) struct Header<'f> {
    /// `name`: the robot's name (default: the file name without its extension).
    pub name: Option<&'f str>,
    /// `base`: the root link's name (default `base`).
    pub base: Option<&'f str>,
    /// `gravity = [gx, gy, gz]` in the base frame (default `(0, 0, −9.81)`).
    pub gravity: Option<[f64; 3]>,
    /// `[[frame]]`: extra named frames.
    pub frames: &'f [toml::Spanned<FrameSpec>],
}

impl Header<'_> {
    /// The robot's name.
    pub fn model_name(&self, file: &str) -> String {
        self.name
            .map(str::to_string)
            .unwrap_or_else(|| default_name(file))
    }
    /// The root link's name.
    pub fn base(&self) -> &str {
        self.base.unwrap_or("base")
    }
    /// A builder with the name, root link, gravity and strictness set.
    pub fn builder(&self, file: &str, options: &LoadOptions) -> ModelBuilder {
        let mut b = ModelBuilder::new(&self.model_name(file));
        b.base_name(self.base())
            .gravity(gravity(self.gravity))
            .strict(options.strict);
        b
    }
    /// Adds the `[[frame]]` tables and builds the model.
    pub fn finish(&self, mut b: ModelBuilder, file: &str, text: &str) -> Result<Model> {
        add_frames(&mut b, self.frames, file, text)?;
        build(&b, file)
    }
}

/// Gravity from an optional `[gx, gy, gz]`, default `(0, 0, −9.81)`.
pub(crate) fn gravity(g: Option<[f64; 3]>) -> Vector3<f64> {
    g.map(Vector3::from)
        .unwrap_or_else(|| Vector3::new(0.0, 0.0, -9.81))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The counted-on line of each table, in file order and out of it, is the line that
    /// [`line_col`] counts from the text's start.
    #[test]
    fn lines_counted_on_are_the_lines_from_the_start() {
        #[derive(Deserialize)]
        struct File {
            row: Vec<toml::Spanned<toml::Table>>,
        }
        let text = "name = \"x\"\n\n[[row]]\na = 1\n\n\n[[row]]\na = 2\n[[row]] # é\na = 3\n";
        let f: File = toml::from_str(text).unwrap();
        let mut lines = Lines::new(text);
        let order = [0, 1, 2, 1, 0, 2];
        let counted: Vec<usize> = order
            .iter()
            .map(|&k| lines.at("f", &f.row[k]).line)
            .collect();
        let from_start: Vec<usize> = order
            .iter()
            .map(|&k| line_col(text, f.row[k].span().start).0)
            .collect();
        assert_eq!(counted, from_start);
        assert_eq!(from_start[..3], [3, 7, 9]);
    }
}
