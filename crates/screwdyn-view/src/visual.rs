//! The visuals drawn (the library's format-neutral [`Visual`]s, from a URDF's `<visual>`
//! elements or an MJCF's visual geoms, see [`screwdyn::io::visual::visuals_of`]), the
//! resolution of their mesh file names and the reading of the files.

use nalgebra::{Matrix3, Vector3};
pub use screwdyn::io::visual::{Shape, Visual};
use screwdyn::{Error, Result};
use std::path::{Path, PathBuf};

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

/// Reads the mesh file at `path` by its extension (any case): `.stl` and `.obj` by the
/// library's [`screwdyn::io::visual::read_mesh`] (the reader the MJCF loader uses for mesh
/// inertias), `.dae` by [`crate::mesh::read_dae`]; shared vertices are merged.
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
    match ext.as_str() {
        "stl" | "obj" => Ok(screwdyn::io::visual::read_mesh(path)?
            .into_iter()
            .map(|m| {
                let mut mesh = crate::mesh::Mesh {
                    positions: m.positions,
                    indices: m.indices,
                    color: None,
                };
                mesh.dedup();
                mesh
            })
            .collect()),
        "dae" => {
            let bytes = std::fs::read(path).map_err(|e| Error::unreadable(path, &e))?;
            let text =
                String::from_utf8(bytes).map_err(|_| Error::parse(&file, "is not UTF-8 text"))?;
            crate::mesh::read_dae(&text, &file)
        }
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
