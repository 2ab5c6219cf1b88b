//! URDF `<visual>` elements (read again from the URDF text: the library's loader keeps only
//! the dynamics) and the resolution of their mesh file names.

use nalgebra::{Matrix3, Vector3};
use screwdyn::spatial::Se3;
use screwdyn::{Error, Result};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The shape of a `<visual>`.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// `<box size="x y z"/>`, centred at the visual origin.
    Box([f64; 3]),
    /// `<cylinder radius length/>`, along `z`, centred.
    Cylinder { radius: f64, length: f64 },
    /// `<sphere radius/>`.
    Sphere(f64),
    /// `<mesh filename scale/>`.
    Mesh { filename: String, scale: [f64; 3] },
}

/// One `<visual>` of a link.
#[derive(Clone, Debug, PartialEq)]
pub struct Visual {
    /// The link it belongs to.
    pub link: String,
    /// `<origin>`: its pose in the link frame.
    pub origin: Se3,
    /// Its shape.
    pub geometry: Geometry,
    /// `<material>` colour (inline, or by name from a top-level `<material>`), RGBA.
    pub color: Option<[f32; 4]>,
}

fn numbers(text: &str, n: usize, what: &str, file: &str, line: u32) -> Result<Vec<f64>> {
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|s| s.parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| {
            Error::parse_at(
                file,
                line as usize,
                format!("{what} '{text}' is not a list of numbers"),
            )
        })?;
    if v.len() != n || v.iter().any(|x| !x.is_finite()) {
        return Err(Error::parse_at(
            file,
            line as usize,
            format!("{what} '{text}' must be {n} finite numbers"),
        ));
    }
    Ok(v)
}

fn color_of(node: roxmltree::Node, file: &str, line: u32) -> Result<Option<[f32; 4]>> {
    match node
        .children()
        .find(|c| c.has_tag_name("color"))
        .and_then(|c| c.attribute("rgba"))
    {
        Some(t) => {
            let v = numbers(t, 4, "rgba", file, line)?;
            Ok(Some([v[0] as f32, v[1] as f32, v[2] as f32, v[3] as f32]))
        }
        None => Ok(None),
    }
}

/// The `<visual>` elements of a URDF text, in file order.
///
/// # Errors
/// [`Error::Parse`] with `file:line` for broken XML, a geometry without a shape, or numbers
/// that are not numbers.
///
/// ```
/// let urdf = r#"<robot name="r"><material name="blue"><color rgba="0 0 1 1"/></material>
///   <link name="a"><visual><origin xyz="0 0 0.5"/><geometry><box size="1 2 3"/></geometry>
///   <material name="blue"/></visual></link></robot>"#;
/// let v = screwdyn_view::visual::parse_visuals(urdf, "r.urdf").unwrap();
/// assert_eq!(v[0].link, "a");
/// assert_eq!(v[0].color, Some([0.0, 0.0, 1.0, 1.0]));
/// assert_eq!(v[0].origin.translation.z, 0.5);
/// ```
pub fn parse_visuals(text: &str, file: &str) -> Result<Vec<Visual>> {
    let doc = roxmltree::Document::parse(text)
        .map_err(|e| Error::parse(file, format!("is not valid XML ({e})")))?;
    let line = |n: roxmltree::Node| doc.text_pos_at(n.range().start).row;
    let robot = doc.root_element();
    let mut named: HashMap<&str, [f32; 4]> = HashMap::new();
    for m in robot.children().filter(|n| n.has_tag_name("material")) {
        if let (Some(name), Some(c)) = (m.attribute("name"), color_of(m, file, line(m))?) {
            named.insert(name, c);
        }
    }
    let mut out = Vec::new();
    for link in robot.children().filter(|n| n.has_tag_name("link")) {
        let name = link.attribute("name").unwrap_or("");
        for v in link.children().filter(|n| n.has_tag_name("visual")) {
            let l = line(v);
            let origin = match v.children().find(|n| n.has_tag_name("origin")) {
                Some(o) => {
                    let xyz = o
                        .attribute("xyz")
                        .map(|t| numbers(t, 3, "xyz", file, l))
                        .transpose()?
                        .unwrap_or(vec![0.0; 3]);
                    let rpy = o
                        .attribute("rpy")
                        .map(|t| numbers(t, 3, "rpy", file, l))
                        .transpose()?
                        .unwrap_or(vec![0.0; 3]);
                    Se3::from_rpy(rpy[0], rpy[1], rpy[2])
                        .with_translation(Vector3::new(xyz[0], xyz[1], xyz[2]))
                }
                None => Se3::identity(),
            };
            let shape = v
                .children()
                .find(|n| n.has_tag_name("geometry"))
                .and_then(|g| g.children().find(|n| n.is_element()))
                .ok_or_else(|| {
                    Error::parse_at(
                        file,
                        l as usize,
                        format!("a <visual> of link '{name}' has no <geometry> shape"),
                    )
                })?;
            let attr = |a: &str| {
                shape.attribute(a).ok_or_else(|| {
                    Error::parse_at(
                        file,
                        line(shape) as usize,
                        format!(
                            "<{}> of link '{name}' has no '{a}' attribute",
                            shape.tag_name().name()
                        ),
                    )
                })
            };
            let one =
                |a: &str| -> Result<f64> { Ok(numbers(attr(a)?, 1, a, file, line(shape))?[0]) };
            let geometry = match shape.tag_name().name() {
                "box" => {
                    let s = numbers(attr("size")?, 3, "size", file, line(shape))?;
                    Geometry::Box([s[0], s[1], s[2]])
                }
                "cylinder" => Geometry::Cylinder {
                    radius: one("radius")?,
                    length: one("length")?,
                },
                "sphere" => Geometry::Sphere(one("radius")?),
                "mesh" => {
                    let scale = match shape.attribute("scale") {
                        Some(t) => {
                            let s = numbers(t, 3, "scale", file, line(shape))?;
                            [s[0], s[1], s[2]]
                        }
                        None => [1.0; 3],
                    };
                    Geometry::Mesh {
                        filename: attr("filename")?.to_string(),
                        scale,
                    }
                }
                other => {
                    return Err(Error::parse_at(
                        file,
                        line(shape) as usize,
                        format!("unknown geometry <{other}> in link '{name}' (expected box, cylinder, sphere or mesh)"),
                    ))
                }
            };
            let color = match v.children().find(|n| n.has_tag_name("material")) {
                Some(m) => match color_of(m, file, line(m))? {
                    Some(c) => Some(c),
                    None => m.attribute("name").and_then(|n| named.get(n).copied()),
                },
                None => None,
            };
            out.push(Visual {
                link: name.to_string(),
                origin,
                geometry,
                color,
            });
        }
    }
    Ok(out)
}

/// Where a mesh file name of a URDF points to on disk.
///
/// - `package://PKG/REST` (and `model://PKG/REST`): `DIR/PKG/REST` or, when `DIR` is itself
///   called `PKG`, `DIR/REST`, for each `DIR` of `package_paths`, then of the
///   `ROS_PACKAGE_PATH` environment variable (`:`-separated), then each ancestor folder of the
///   URDF (a URDF usually sits in `PKG/urdf/`);
/// - `file:///abs/path` and absolute paths: as written;
/// - anything else: relative to the URDF's folder.
///
/// # Errors
/// [`Error::Io`] naming the file name and the folders searched, when no candidate exists.
///
/// ```
/// use screwdyn_view::visual::resolve_mesh;
/// let dir = std::env::temp_dir().join("screwdyn_view_doc_resolve/pkg/meshes");
/// std::fs::create_dir_all(&dir).unwrap();
/// std::fs::write(dir.join("a.stl"), b"solid a\nendsolid a\n").unwrap();
/// let root = dir.parent().unwrap().parent().unwrap();
/// let p = resolve_mesh("package://pkg/meshes/a.stl", root, &[root.to_path_buf()]).unwrap();
/// assert!(p.ends_with("pkg/meshes/a.stl"));
/// ```
pub fn resolve_mesh(uri: &str, urdf_dir: &Path, package_paths: &[PathBuf]) -> Result<PathBuf> {
    let package = uri
        .strip_prefix("package://")
        .or_else(|| uri.strip_prefix("model://"));
    if let Some(rest) = package {
        let (pkg, tail) = rest.split_once('/').unwrap_or((rest, ""));
        let mut dirs: Vec<PathBuf> = package_paths.to_vec();
        if let Some(env) = std::env::var_os("ROS_PACKAGE_PATH") {
            dirs.extend(std::env::split_paths(&env));
        }
        let searched = dirs.len();
        dirs.extend(urdf_dir.ancestors().map(Path::to_path_buf));
        for d in &dirs {
            let mut candidates = vec![d.join(pkg).join(tail)];
            if d.file_name().is_some_and(|n| n == pkg) {
                candidates.push(d.join(tail));
            }
            if let Some(c) = candidates.into_iter().find(|c| c.is_file()) {
                return Ok(c);
            }
        }
        let hint = if searched == 0 {
            " (give the folder that holds it with --package-path or ROS_PACKAGE_PATH)".to_string()
        } else {
            format!(
                " in {}",
                dirs[..searched]
                    .iter()
                    .map(|d| d.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        return Err(Error::io(
            None,
            std::io::ErrorKind::NotFound,
            format!("mesh '{uri}': package '{pkg}' not found{hint} or above the URDF's folder"),
        ));
    }
    let path = match uri.strip_prefix("file://") {
        Some(p) => PathBuf::from(p),
        None => {
            let p = PathBuf::from(uri);
            if p.is_absolute() {
                p
            } else {
                urdf_dir.join(p)
            }
        }
    };
    if path.is_file() {
        Ok(path)
    } else {
        Err(Error::io(
            Some(path.clone()),
            std::io::ErrorKind::NotFound,
            format!("mesh '{uri}': {} does not exist", path.display()),
        ))
    }
}

/// Reads the mesh file at `path` by its extension (`.stl`, `.obj`, `.dae`, any case).
///
/// # Errors
/// [`Error::Io`] when the file cannot be read, [`Error::Parse`] when it is malformed or of an
/// unknown kind.
pub fn read_mesh_file(path: &Path) -> Result<Vec<crate::mesh::Mesh>> {
    let file = path.display().to_string();
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let bytes = std::fs::read(path).map_err(|e| Error::unreadable(path, &e))?;
    let text =
        || String::from_utf8(bytes.clone()).map_err(|_| Error::parse(&file, "is not UTF-8 text"));
    match ext.as_str() {
        "stl" => Ok(vec![crate::mesh::read_stl(&bytes, &file)?]),
        "obj" => Ok(vec![crate::mesh::read_obj(&text()?, &file)?]),
        "dae" => crate::mesh::read_dae(&text()?, &file),
        _ => Err(Error::parse(
            file,
            format!("unknown mesh format '.{ext}' (expected .stl, .obj or .dae)"),
        )),
    }
}

/// The 3×3 scaling matrix of a mesh `scale` attribute.
pub(crate) fn scaling(s: [f64; 3]) -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(s[0], s[1], s[2]))
}
