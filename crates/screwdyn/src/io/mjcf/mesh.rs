//! Mesh assets (`<asset><mesh name file scale>`) and their mass properties by exact volume
//! integration over the closed triangle surface: each triangle `(a, b, c)` and the origin span a
//! tetrahedron of signed volume `V_t = a·(b × c)/6`, centroid `(a + b + c)/4` and second
//! moments `∫ x xᵀ dV = V_t/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ)` with `s = a + b + c`; summed, they
//! give the volume, the centre and `I = tr(C) 1 − C` about the origin, moved to the centre.
//!
//! Files are read by the `mesh-loader` crate (STL binary and ASCII, Wavefront OBJ): pure Rust,
//! no dependency of its own for these two formats, single-precision vertices as MuJoCo stores
//! them.

use super::compiler::Compiler;
use super::defaults::Defaults;
use super::tree::Tree;
use super::values::Values;
use crate::error::Result;
use nalgebra::{Matrix3, Vector3};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Mass properties of a mesh of unit density, in the geom frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MeshProps {
    pub volume: f64,
    pub centre: Vector3<f64>,
    /// Inertia about `centre` for density 1 (mass = volume).
    pub inertia_per_volume: Matrix3<f64>,
}

struct Asset {
    file: PathBuf,
    scale: Vector3<f64>,
    at: String,
}

/// The mesh assets by name, each read the first time a geom needs its inertia.
pub(crate) struct MeshTable {
    assets: HashMap<String, Asset>,
    cache: RefCell<HashMap<String, MeshProps>>,
}

impl MeshTable {
    /// The `<mesh>` elements of every `<asset>` (name: the `name` attribute, else the file name
    /// without its extension).
    pub fn read(tree: &Tree, defaults: &Defaults, compiler: &Compiler) -> Result<MeshTable> {
        let mut assets = HashMap::new();
        for a in tree.root.children_named("asset") {
            for m in a.children_named("mesh") {
                let class = defaults.class_of(tree, m, defaults.main())?;
                let v = Values {
                    tree,
                    styled: super::defaults::Styled {
                        element: m,
                        class,
                        defaults,
                    },
                };
                let Some(file) = v.text("file") else {
                    // Meshes given by vertex lists in the file are not read.
                    continue;
                };
                let name = v.text("name").map(str::to_string).unwrap_or_else(|| {
                    let base = Path::new(file).file_stem().unwrap_or_default();
                    base.to_string_lossy().into_owned()
                });
                let scale = v
                    .vec3("scale")?
                    .unwrap_or_else(|| Vector3::new(1.0, 1.0, 1.0));
                assets.insert(
                    name,
                    Asset {
                        file: compiler.meshdir.join(file),
                        scale,
                        at: tree.at(m),
                    },
                );
            }
        }
        Ok(MeshTable {
            assets,
            cache: RefCell::new(HashMap::new()),
        })
    }

    /// The mass properties of mesh `name`, named by the geom `v`.
    pub fn get(&self, v: &Values, name: &str) -> Result<MeshProps> {
        if let Some(p) = self.cache.borrow().get(name) {
            return Ok(*p);
        }
        let asset = self.assets.get(name).ok_or_else(|| {
            v.error(format!(
                "<geom mesh=\"{name}\"> names no <mesh> asset with a file"
            ))
        })?;
        let triangles = read_triangles(&asset.file).map_err(|e| {
            v.error(format!(
                "mesh '{name}' (declared at {}): {} cannot be read: {e}",
                asset.at,
                asset.file.display()
            ))
        })?;
        let s = asset.scale;
        let scaled = triangles
            .iter()
            .map(|t| t.map(|p| p.component_mul(&s)))
            .collect::<Vec<_>>();
        let p = integrate(&scaled);
        if p.volume.abs() < 1e-18 {
            return Err(v.error(format!(
                "mesh '{name}' ({}) encloses no volume, so its inertia cannot be computed; give the body an <inertial>",
                asset.file.display()
            )));
        }
        self.cache.borrow_mut().insert(name.to_string(), p);
        Ok(p)
    }
}

/// The triangles of an STL or OBJ file.
fn read_triangles(path: &Path) -> std::io::Result<Vec<[Vector3<f64>; 3]>> {
    let loader = mesh_loader::Loader::default();
    let lower = path.to_string_lossy().to_ascii_lowercase();
    let scene = if lower.ends_with(".stl") {
        loader.load_stl(path)?
    } else if lower.ends_with(".obj") {
        loader.load_obj(path)?
    } else {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "only STL and OBJ meshes are read",
        ));
    };
    let mut out = Vec::new();
    for m in &scene.meshes {
        let p = |k: u32| {
            let v = m.vertices[k as usize];
            Vector3::new(v[0] as f64, v[1] as f64, v[2] as f64)
        };
        for f in &m.faces {
            if f.iter().any(|&k| k as usize >= m.vertices.len()) {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    "a face names a vertex that does not exist",
                ));
            }
            out.push([p(f[0]), p(f[1]), p(f[2])]);
        }
    }
    Ok(out)
}

/// Volume, centre and inertia about the centre (density 1) of a closed triangle surface.
pub(crate) fn integrate(triangles: &[[Vector3<f64>; 3]]) -> MeshProps {
    let mut volume = 0.0;
    let mut first = Vector3::zeros();
    let mut second = Matrix3::zeros();
    for [a, b, c] in triangles {
        // V_t = a·(b × c)/6
        let vt = a.dot(&b.cross(c)) / 6.0;
        let s = a + b + c;
        volume += vt;
        first += s * (vt / 4.0);
        // ∫ x xᵀ dV = V_t/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ)
        second += (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose())
            * (vt / 20.0);
    }
    // A surface wound inward gives a negative volume: the same solid.
    if volume < 0.0 {
        volume = -volume;
        first = -first;
        second = -second;
    }
    let centre = if volume > 0.0 {
        first / volume
    } else {
        Vector3::zeros()
    };
    // I_o = tr(C) 1 − C; I_c = I_o − V (|c|² 1 − c cᵀ)
    let i_origin = Matrix3::identity() * second.trace() - second;
    let shift =
        (Matrix3::identity() * centre.norm_squared() - centre * centre.transpose()) * volume;
    MeshProps {
        volume,
        centre,
        inertia_per_volume: i_origin - shift,
    }
}
