//! Mesh assets (`<asset><mesh name file scale inertia>`) and their mass properties by volume
//! integration over the triangle surface, as MuJoCo computes them (see [`integrate`]); for
//! `inertia="convex"` over the surface of the mesh's convex hull ([`super::hull`]).
//!
//! Files are read by [`crate::io::visual::read_mesh`] (the `mesh-loader` crate: STL binary and
//! ASCII, Wavefront OBJ), the reader the viewer uses too; single-precision vertices as MuJoCo
//! stores them.

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

struct Asset<'t> {
    file: PathBuf,
    scale: Vector3<f64>,
    mode: MeshInertia,
    element: &'t super::tree::Element,
    at: String,
}

/// The mesh assets by name, each read the first time a geom needs its inertia.
pub(crate) struct MeshTable<'t> {
    assets: HashMap<String, Asset<'t>>,
    cache: RefCell<HashMap<String, MeshProps>>,
}

impl<'t> MeshTable<'t> {
    /// The `<mesh>` elements of every `<asset>` (name: the `name` attribute, else the file name
    /// without its extension).
    pub fn read(tree: &'t Tree, defaults: &Defaults<'t>, compiler: &Compiler) -> Result<Self> {
        let mut assets = HashMap::new();
        for a in tree.root.children_named("asset") {
            a.take();
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
                // MuJoCo's default is "legacy" (3.x and 4.x; its documentation recommends
                // "convex" but keeps the default for old models).
                let mode = match v.keyword("inertia", &["legacy", "exact", "shell", "convex"])? {
                    None | Some("legacy") => MeshInertia::Legacy,
                    Some("exact") => MeshInertia::Exact,
                    Some("shell") => MeshInertia::Shell,
                    Some(_) => MeshInertia::Convex,
                };
                if mode == MeshInertia::Convex
                    && v.number("maxhullvert")?.is_some_and(|n| n != -1.0)
                {
                    return Err(v.error(
                        "<mesh inertia=\"convex\" maxhullvert> (a hull cut to fewer vertices) is not supported; remove maxhullvert or give the body an <inertial>",
                    ));
                }
                assets.insert(
                    name,
                    Asset {
                        file: compiler.meshdir.join(file),
                        scale,
                        mode,
                        element: m,
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

    /// The file and scale of mesh `name`, named by the geom `v`.
    pub fn file_of(&self, v: &Values, name: &str) -> Result<(&Path, Vector3<f64>)> {
        let asset = self.assets.get(name).ok_or_else(|| {
            v.error(format!(
                "<geom mesh=\"{name}\"> names no <mesh> asset with a file"
            ))
        })?;
        Ok((&asset.file, asset.scale))
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
        let triangles = read_triangles(&asset.file)
            .map_err(|e| v.error(format!("mesh '{name}' (declared at {}): {e}", asset.at)))?;
        let s = asset.scale;
        // The hull of the scaled vertices is the scaled hull of the file's vertices (a scale
        // is linear), which are single-precision numbers, so the hull sees them exactly.
        let triangles = if asset.mode == MeshInertia::Convex {
            super::hull::convex_hull(&triangles)
                .map_err(|e| v.error(format!("mesh '{name}' (declared at {}): {e}", asset.at)))?
        } else {
            triangles
        };
        let scaled = triangles
            .iter()
            .map(|t| t.map(|p| p.component_mul(&s)))
            .collect::<Vec<_>>();
        asset.element.take();
        let p = integrate(&scaled, asset.mode);
        if p.volume < 1e-15 {
            return Err(v.error(format!(
                "mesh '{name}' ({}) encloses no volume (or a negative one: its triangles are wound inward), so its inertia cannot be computed; give the body an <inertial>",
                asset.file.display()
            )));
        }
        self.cache.borrow_mut().insert(name.to_string(), p);
        Ok(p)
    }
}

/// The triangles of an STL or OBJ file, read by [`crate::io::visual::read_mesh`].
fn read_triangles(path: &Path) -> Result<Vec<[Vector3<f64>; 3]>> {
    let mut out = Vec::new();
    for m in crate::io::visual::read_mesh(path)? {
        let p = |k: u32| {
            let v = m.positions[k as usize];
            Vector3::new(v[0] as f64, v[1] as f64, v[2] as f64)
        };
        for f in m.indices.chunks_exact(3) {
            out.push([p(f[0]), p(f[1]), p(f[2])]);
        }
    }
    Ok(out)
}

/// How a mesh's mass is spread (`<mesh inertia>`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MeshInertia {
    /// MuJoCo's default: every pyramid's volume counted positive (exact for closed convex
    /// meshes, more than the solid for others).
    Legacy,
    /// Signed volumes: exact for any closed, consistently wound mesh.
    Exact,
    /// Mass on the surface.
    Shell,
    /// The solid convex hull of the vertices (integrated as `Legacy`, which is exact on a
    /// convex surface whatever the winding of its triangles).
    Convex,
}

/// Volume (area for a shell), centre and inertia about the centre (density 1) of a triangle
/// surface, in MuJoCo's two passes. With `f̄` the area-weighted centroid of the faces and, for
/// each triangle `(a, b, c)` of centroid `t` and area `A`, the pyramid from `f̄` of volume
/// `V_t = (a − f̄)·((b − f̄) × (c − f̄))/6`: the centre `c = Σ V_t (3t/4 + f̄/4) / Σ V_t`; then,
/// with `a, b, c` relative to the centre and `V_t` recomputed from it, the volume `Σ V_t` and
/// `∫ x xᵀ dV = Σ V_t/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ)` (`s = a + b + c`), `I = tr(C) 1 − C`.
/// Legacy takes `|V_t|`; a shell puts `A` for `V_t`, `f̄` for the centre and `/12` for `/20`.
pub(crate) fn integrate(triangles: &[[Vector3<f64>; 3]], mode: MeshInertia) -> MeshProps {
    let area_of = |[a, b, c]: &[Vector3<f64>; 3]| (b - a).cross(&(c - a)).norm() / 2.0;
    let mut total_area = 0.0;
    let mut facecen = Vector3::zeros();
    for t in triangles {
        let area = area_of(t);
        total_area += area;
        facecen += (t[0] + t[1] + t[2]) / 3.0 * area;
    }
    if total_area > 0.0 {
        facecen /= total_area;
    }
    let pyramid = |[a, b, c]: &[Vector3<f64>; 3], o: &Vector3<f64>| {
        let v = (a - o).dot(&(b - o).cross(&(c - o))) / 6.0;
        if matches!(mode, MeshInertia::Legacy | MeshInertia::Convex) {
            v.abs()
        } else {
            v
        }
    };
    let centre = if mode == MeshInertia::Shell {
        facecen
    } else {
        let mut volume = 0.0;
        let mut moment = Vector3::zeros();
        for t in triangles {
            let v = pyramid(t, &facecen);
            volume += v;
            moment += ((t[0] + t[1] + t[2]) / 4.0 + facecen / 4.0) * v;
        }
        if volume > 0.0 {
            moment / volume
        } else {
            facecen
        }
    };
    let mut volume = 0.0;
    let mut second = Matrix3::zeros();
    for t in triangles {
        let w = match mode {
            MeshInertia::Shell => area_of(t) / 12.0,
            _ => pyramid(t, &centre) / 20.0,
        };
        volume += if mode == MeshInertia::Shell {
            area_of(t)
        } else {
            pyramid(t, &centre)
        };
        let [a, b, c] = t.map(|p| p - centre);
        let s = a + b + c;
        second +=
            (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose()) * w;
    }
    MeshProps {
        volume,
        centre,
        // I = tr(C) 1 − C
        inertia_per_volume: Matrix3::identity() * second.trace() - second,
    }
}
