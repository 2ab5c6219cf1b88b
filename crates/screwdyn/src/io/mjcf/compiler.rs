//! `<compiler>`: the settings that change how the rest of the file reads (angle unit, Euler
//! sequence, limits, mesh directory, where inertias come from), with MuJoCo's defaults.

use super::defaults::{Defaults, Styled};
use super::tree::Tree;
use super::values::Values;
use crate::error::Result;
use std::path::PathBuf;

/// `inertiafromgeom`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FromGeom {
    /// Always from the geoms (an `<inertial>` is ignored).
    Always,
    /// Never (a body without `<inertial>` is massless).
    Never,
    /// From the geoms when the body has no `<inertial>` (MuJoCo's default).
    Auto,
}

/// The compiler settings.
#[derive(Clone, Debug)]
pub(crate) struct Compiler {
    /// Angles in degrees (MuJoCo's default) rather than radians.
    pub degrees: bool,
    /// Three of `xyzXYZ`: lower case rotates about the moving axes, upper case about fixed ones.
    pub eulerseq: [u8; 3],
    /// A `range` alone makes a joint limited (`limited="auto"`).
    pub autolimits: bool,
    /// Where mesh files are looked up (relative to the main file's directory).
    pub meshdir: PathBuf,
    pub inertia_from_geom: FromGeom,
    /// Geoms whose `group` lies in this range contribute to inertias.
    pub inertia_group_range: (i64, i64),
    pub bound_mass: f64,
    pub bound_inertia: f64,
    /// Every body's mass (and inertia) scaled so that the total is this, when positive.
    pub set_total_mass: f64,
}

impl Compiler {
    /// Reads every `<compiler>` element in file order (later ones override earlier ones).
    pub fn read(tree: &Tree, defaults: &Defaults, main_file: &str) -> Result<Compiler> {
        let main_dir = std::path::Path::new(main_file)
            .parent()
            .map(PathBuf::from)
            .unwrap_or_default();
        let mut c = Compiler {
            degrees: true,
            eulerseq: *b"xyz",
            autolimits: true,
            meshdir: main_dir.clone(),
            inertia_from_geom: FromGeom::Auto,
            inertia_group_range: (0, 5),
            bound_mass: 0.0,
            bound_inertia: 0.0,
            set_total_mass: -1.0,
        };
        let mut assetdir: Option<String> = None;
        let mut meshdir: Option<String> = None;
        for e in tree.root.children_named("compiler") {
            e.take();
            let v = Values {
                tree,
                styled: Styled {
                    element: e,
                    class: defaults.main(),
                    defaults,
                },
            };
            if let Some(a) = v.keyword("angle", &["degree", "radian"])? {
                c.degrees = a == "degree";
            }
            if let Some(s) = v.text("eulerseq") {
                let b = s.as_bytes();
                if b.len() != 3 || !b.iter().all(|x| b"xyzXYZ".contains(x)) {
                    return Err(v.error(format!(
                        "<compiler eulerseq=\"{s}\"> must be three of x, y, z, X, Y, Z"
                    )));
                }
                c.eulerseq = [b[0], b[1], b[2]];
            }
            if let Some(a) = v.keyword("autolimits", &["true", "false"])? {
                c.autolimits = a == "true";
            }
            if let Some(s) = v.text("assetdir") {
                assetdir = Some(s.to_string());
            }
            if let Some(s) = v.text("meshdir") {
                meshdir = Some(s.to_string());
            }
            if let Some(a) = v.tristate("inertiafromgeom")? {
                c.inertia_from_geom = match a {
                    "true" => FromGeom::Always,
                    "false" => FromGeom::Never,
                    _ => FromGeom::Auto,
                };
            }
            if let Some(r) = v.numbers("inertiagrouprange", 2)? {
                if r.iter().any(|x| x.fract() != 0.0) || r[0] > r[1] {
                    return Err(v.error(format!(
                        "<compiler inertiagrouprange=\"{} {}\"> must be two integers, the first not above the second",
                        r[0], r[1]
                    )));
                }
                c.inertia_group_range = (r[0] as i64, r[1] as i64);
            }
            if let Some(m) = v.non_negative("boundmass")? {
                c.bound_mass = m;
            }
            if let Some(i) = v.non_negative("boundinertia")? {
                c.bound_inertia = i;
            }
            if let Some(m) = v.number("settotalmass")? {
                c.set_total_mass = m;
            }
            if let Some(s) = v.keyword("coordinate", &["local", "global"])? {
                if s == "global" {
                    return Err(v.error(
                        "<compiler coordinate=\"global\"> is not supported (MuJoCo itself dropped it); use local coordinates",
                    ));
                }
            }
        }
        // meshdir wins over assetdir; both are relative to the main file.
        if let Some(d) = meshdir.or(assetdir) {
            c.meshdir = main_dir.join(d);
        }
        Ok(c)
    }

    /// An angle attribute in radians.
    pub fn angle(&self, x: f64) -> f64 {
        if self.degrees {
            x.to_radians()
        } else {
            x
        }
    }
}
