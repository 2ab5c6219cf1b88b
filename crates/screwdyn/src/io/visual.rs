//! What a model looks like, in one list whatever the format: the shapes attached to its links
//! ([`Visual`], from a URDF's `<visual>` elements or an MJCF's visual geoms, see
//! [`visuals_of`]) and the one reader of the mesh files they name ([`read_mesh`], also used by
//! the MJCF loader for the inertia of mesh geoms).

use crate::error::{Error, Result};
use crate::io::options::LoadOptions;
use crate::io::Format;
use crate::spatial::Se3;
use std::path::Path;

/// The shape of a visual, centred at (and aligned with) its origin.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A box of full edge lengths `size` along `x`, `y`, `z`.
    Box { size: [f64; 3] },
    /// A sphere.
    Sphere { radius: f64 },
    /// A cylinder along `z` of full `length`.
    Cylinder { radius: f64, length: f64 },
    /// A cylinder of full `length` along `z` with a hemisphere of `radius` on each end.
    Capsule { radius: f64, length: f64 },
    /// An ellipsoid of semi-axes `radii` along `x`, `y`, `z`.
    Ellipsoid { radii: [f64; 3] },
    /// A mesh file scaled by `scale` along each axis. `file` is as the description writes it
    /// (URDF: a `package://`, `file://`, absolute or relative name, relative to the URDF's
    /// folder) or, for MJCF, the path resolved through `<compiler meshdir>`, absolute.
    Mesh { file: String, scale: [f64; 3] },
}

/// One shape attached to a link.
#[derive(Clone, Debug, PartialEq)]
pub struct Visual {
    /// The link (or fixed frame) it moves with.
    pub link: String,
    /// Its pose in the link frame.
    pub origin: Se3,
    /// Its shape.
    pub shape: Shape,
    /// Its RGBA colour, when the description gives one.
    pub color: Option<[f32; 4]>,
}

/// The visuals of a URDF or MJCF description (`text`, read from `file`; the format is taken
/// from the text): a URDF's `<visual>` elements, an MJCF's geoms in the groups MuJoCo's viewer
/// shows by default (0, 1 and 2: Menagerie puts its visual meshes in group 2 and its collision
/// shapes in group 3). Other formats have none.
///
/// # Errors
/// [`Error::Parse`] at `file:line` for malformed XML, a shape without its sizes, or a value
/// that is not a number; for MJCF, as [`crate::io::mjcf::parse_mjcf`].
///
/// ```
/// use screwdyn::io::{visual::{visuals_of, Shape}, LoadOptions};
/// let xml = r#"<mujoco><worldbody><body name="b"><joint/>
///   <geom type="capsule" size="0.1 0.5" rgba="1 0 0 1"/></body></worldbody></mujoco>"#;
/// let v = visuals_of(xml, "m.xml", &LoadOptions::default()).unwrap();
/// assert_eq!(v[0].shape, Shape::Capsule { radius: 0.1, length: 1.0 });
/// assert_eq!(v[0].color, Some([1.0, 0.0, 0.0, 1.0]));
/// ```
pub fn visuals_of(text: &str, file: &str, options: &LoadOptions) -> Result<Vec<Visual>> {
    match Format::of_text(text) {
        Format::Urdf => crate::io::urdf::parse_visuals(text, file),
        Format::Mjcf => crate::io::mjcf::parse_mjcf_visuals(text, file, options),
        _ => Ok(Vec::new()),
    }
}

/// A triangle mesh as read from a file: vertex positions in the file's units and three vertex
/// indices per triangle, counter-clockwise seen from outside.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Three indices into `positions` per triangle.
    pub indices: Vec<u32>,
}

/// Reads an STL (binary or ASCII) or Wavefront OBJ file (by its extension, any case) with the
/// `mesh-loader` crate: one [`TriangleMesh`] per mesh of the file (an OBJ file may hold
/// several objects).
///
/// # Errors
/// [`Error::Io`] naming `path` when it cannot be read; [`Error::Parse`] naming it when it is
/// malformed, a face names a vertex that does not exist, or the extension is neither `.stl`
/// nor `.obj`.
///
/// ```
/// let path = std::env::temp_dir().join(format!("screwdyn-doc-{}.stl", std::process::id()));
/// std::fs::write(&path, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n\
///   vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n").unwrap();
/// let m = screwdyn::io::visual::read_mesh(&path).unwrap();
/// assert_eq!(m[0].indices.len(), 3);
/// assert_eq!(m[0].positions[m[0].indices[1] as usize], [1.0, 0.0, 0.0]);
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn read_mesh(path: &Path) -> Result<Vec<TriangleMesh>> {
    let file = path.display().to_string();
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let bytes = std::fs::read(path).map_err(|e| Error::unreadable(path, &e))?;
    let loader = mesh_loader::Loader::default();
    let scene = match ext.as_str() {
        "stl" => loader.load_stl_from_slice(&bytes, path),
        "obj" => loader.load_obj_from_slice(&bytes, path),
        _ => {
            return Err(Error::parse(
                file,
                format!("unknown mesh format '.{ext}' (expected .stl or .obj)"),
            ))
        }
    }
    .map_err(|e| Error::parse(&file, format!("is not a readable mesh ({e})")))?;
    let mut out = Vec::with_capacity(scene.meshes.len());
    for m in &scene.meshes {
        let n = m.vertices.len();
        if m.faces.iter().flatten().any(|&k| k as usize >= n) {
            return Err(Error::parse(
                &file,
                format!(
                    "mesh '{}' has a face that names a vertex that does not exist",
                    m.name
                ),
            ));
        }
        out.push(TriangleMesh {
            positions: m.vertices.clone(),
            indices: m.faces.iter().flatten().copied().collect(),
        });
    }
    Ok(out)
}
