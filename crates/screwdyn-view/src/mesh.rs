//! Triangle meshes: the Collada `.dae` reader (STL and OBJ files are read by the library's
//! [`screwdyn::io::visual::read_mesh`], see [`crate::visual::read_mesh_file`]), the primitive
//! shapes (box, cylinder, sphere, capsule) and the size controls (vertex deduplication,
//! vertex-clustering decimation).
//!
//! Meshes are in the file's own units with the file's transforms applied (Collada node
//! matrices and `<unit meter=…>`); the visual's `scale` is applied later, by its transform.
//!
//! Why Collada is read here and not by `mesh-loader`: its Collada loader keeps one material
//! per geometry (the first primitive's) and one transform per instanced geometry, and the
//! published arms' meshes colour their parts by several materials within one geometry.
//! Checked against `mesh-loader` 0.1.13, the newest release on crates.io in November 2026.

use nalgebra::{Matrix4, Vector3, Vector4};
use screwdyn::{Error, Result};
use std::collections::HashMap;

/// An indexed triangle mesh (positions in metres once placed) with an optional colour from
/// the mesh file itself (Collada materials).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
    /// RGBA colour given by the file (a Collada material's diffuse colour), if any.
    pub color: Option<[f32; 4]>,
}

impl Mesh {
    /// Number of triangles.
    pub fn triangles(&self) -> usize {
        self.indices.len() / 3
    }

    /// Merges vertices with bit-identical positions (STL repeats every corner for every
    /// triangle; merging makes the embedded data about six times smaller) and drops unused
    /// ones.
    ///
    /// ```
    /// use screwdyn_view::mesh::Mesh;
    /// let mut m = Mesh { positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3]],
    ///     indices: vec![0, 1, 2, 3, 1, 2], color: None };
    /// m.dedup();
    /// assert_eq!(m.positions.len(), 3);
    /// assert_eq!(m.indices, vec![0, 1, 2, 0, 1, 2]);
    /// ```
    pub fn dedup(&mut self) {
        let mut map: HashMap<[u32; 3], u32> = HashMap::new();
        let mut out = Vec::new();
        let mut remap = vec![u32::MAX; self.positions.len()];
        for i in self.indices.iter_mut() {
            let p = self.positions[*i as usize];
            if remap[*i as usize] == u32::MAX {
                let key = p.map(f32::to_bits);
                let k = *map.entry(key).or_insert_with(|| {
                    out.push(p);
                    (out.len() - 1) as u32
                });
                remap[*i as usize] = k;
            }
            *i = remap[*i as usize];
        }
        self.positions = out;
    }

    /// Reduces the mesh to at most `max_triangles` triangles by vertex clustering: vertices
    /// are snapped to a cubic grid, each cell's vertices merged at their mean, and triangles
    /// that collapse are dropped; the cell grows until the count fits. Coarse but robust, and
    /// linear in the mesh size per pass. Returns whether the mesh changed.
    ///
    /// ```
    /// use screwdyn_view::mesh::{sphere, Mesh};
    /// let mut s = sphere(1.0, 32, 16);
    /// let before = s.triangles();
    /// assert!(s.decimate(100));
    /// assert!(s.triangles() <= 100 && s.triangles() > 0 && before > 100);
    /// ```
    pub fn decimate(&mut self, max_triangles: usize) -> bool {
        if self.triangles() <= max_triangles {
            return false;
        }
        let (lo, hi) = self.bounds();
        let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0_f32, f32::max);
        if extent <= 0.0 || max_triangles == 0 {
            self.indices.clear();
            return true;
        }
        // A grid of n cells along the longest side keeps of the order of n² surface
        // triangles: start a little finer than that and coarsen by 15 % until it fits.
        let mut cells = (1.5 * (max_triangles as f32).sqrt()).max(1.0);
        loop {
            let h = extent / cells;
            let reduced = self.clustered(h, lo);
            if reduced.triangles() <= max_triangles || cells <= 1.0 {
                let color = self.color;
                *self = reduced;
                self.color = color;
                return true;
            }
            cells *= 0.85;
        }
    }

    fn clustered(&self, h: f32, lo: [f32; 3]) -> Mesh {
        let mut cell_of: HashMap<[i32; 3], u32> = HashMap::new();
        let mut sums: Vec<([f64; 3], u32)> = Vec::new();
        let vmap: Vec<u32> = self
            .positions
            .iter()
            .map(|p| {
                let key = [0, 1, 2].map(|k| ((p[k] - lo[k]) / h).floor() as i32);
                let c = *cell_of.entry(key).or_insert_with(|| {
                    sums.push(([0.0; 3], 0));
                    (sums.len() - 1) as u32
                });
                let s = &mut sums[c as usize];
                for (acc, x) in s.0.iter_mut().zip(p) {
                    *acc += *x as f64;
                }
                s.1 += 1;
                c
            })
            .collect();
        let positions = sums
            .iter()
            .map(|(s, n)| s.map(|x| (x / *n as f64) as f32))
            .collect();
        let mut seen = std::collections::HashSet::new();
        let mut indices = Vec::new();
        for t in self.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| vmap[i as usize]);
            if a == b || b == c || a == c {
                continue;
            }
            let mut key = [a, b, c];
            key.sort_unstable();
            if seen.insert(key) {
                indices.extend([a, b, c]);
            }
        }
        let mut m = Mesh {
            positions,
            indices,
            color: None,
        };
        m.dedup();
        m
    }

    /// The axis-aligned bounding box `(min, max)` (zeros for an empty mesh).
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        if self.positions.is_empty() {
            return ([0.0; 3], [0.0; 3]);
        }
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &self.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }

    /// Appends `other`'s triangles.
    pub fn append(&mut self, other: &Mesh) {
        let k = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.indices.extend(other.indices.iter().map(|i| i + k));
    }
}

fn bad(file: &str, what: impl std::fmt::Display) -> Error {
    Error::parse(file, what.to_string())
}

/// Reads a Collada (`.dae`) file: the geometries (`<triangles>`, `<polylist>`, `<polygons>`)
/// instanced by the nodes of the visual scene, each vertex moved by its node's transforms
/// (`<matrix>`, `<translate>`, `<rotate>`, `<scale>`, nested) and scaled by
/// `<asset><unit meter=…>`. Returns one mesh per material (with its diffuse colour when the
/// file gives one). `<up_axis>` is ignored (as URDF viewers do: the node transforms are
/// taken as written).
///
/// # Errors
/// [`Error::Parse`] naming `file` when the XML or a referenced array is broken.
///
/// ```
/// let dae = r##"<COLLADA><asset><unit meter="0.5"/></asset>
/// <library_geometries><geometry id="g"><mesh>
///  <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array></source>
///  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
///  <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
/// </mesh></geometry></library_geometries>
/// <library_visual_scenes><visual_scene id="s"><node><translate>0 0 2</translate>
///  <instance_geometry url="#g"/></node></visual_scene></library_visual_scenes></COLLADA>"##;
/// let m = screwdyn_view::mesh::read_dae(dae, "t.dae").unwrap();
/// assert_eq!(m[0].positions[1], [0.5, 0.0, 1.0]);
/// ```
pub fn read_dae(text: &str, file: &str) -> Result<Vec<Mesh>> {
    let doc = roxmltree::Document::parse(text)
        .map_err(|e| bad(file, format!("is not valid XML ({e})")))?;
    let root = doc.root_element();
    let by_id: HashMap<&str, roxmltree::Node> = root
        .descendants()
        .filter_map(|n| n.attribute("id").map(|id| (id, n)))
        .collect();
    let unit = root
        .children()
        .find(|n| n.has_tag_name("asset"))
        .and_then(|a| a.children().find(|n| n.has_tag_name("unit")))
        .and_then(|u| u.attribute("meter"))
        .map(|m| m.trim().parse::<f32>())
        .transpose()
        .map_err(|_| bad(file, "<unit meter> is not a number"))?
        .unwrap_or(1.0);
    let scale = Matrix4::new_scaling(unit);
    let ctx = Dae { file, by_id };
    let mut out: Vec<(String, Mesh)> = Vec::new();
    // The scene to draw: <scene><instance_visual_scene url>, else the first visual scene.
    let scene = root
        .descendants()
        .find(|n| n.has_tag_name("instance_visual_scene"))
        .and_then(|n| n.attribute("url"))
        .and_then(|u| ctx.by_id.get(u.trim_start_matches('#')).copied())
        .or_else(|| root.descendants().find(|n| n.has_tag_name("visual_scene")));
    match scene {
        Some(s) => {
            for node in s.children().filter(|n| n.has_tag_name("node")) {
                ctx.node(node, &scale, &mut out, 0)?;
            }
        }
        None => {
            // No scene: every geometry once, untransformed.
            for g in root.descendants().filter(|n| n.has_tag_name("geometry")) {
                ctx.geometry(g, &scale, None, &mut out)?;
            }
        }
    }
    Ok(out.into_iter().map(|(_, m)| m).collect())
}

struct Dae<'a, 'input> {
    file: &'a str,
    by_id: HashMap<&'a str, roxmltree::Node<'a, 'input>>,
}

fn numbers(text: Option<&str>) -> Vec<f32> {
    text.unwrap_or("")
        .split_whitespace()
        .filter_map(|s| s.parse().ok())
        .collect()
}

impl<'a, 'input> Dae<'a, 'input> {
    fn node(
        &self,
        node: roxmltree::Node<'a, 'input>,
        parent: &Matrix4<f32>,
        out: &mut Vec<(String, Mesh)>,
        depth: usize,
    ) -> Result<()> {
        if depth > 64 {
            return Err(bad(
                self.file,
                "nodes are nested more than 64 deep (a cycle?)",
            ));
        }
        let mut m = *parent;
        for c in node.children().filter(|c| c.is_element()) {
            let x = numbers(c.text());
            let t = match c.tag_name().name() {
                "matrix" if x.len() == 16 => Matrix4::from_row_slice(&x),
                "translate" if x.len() == 3 => {
                    Matrix4::new_translation(&Vector3::new(x[0], x[1], x[2]))
                }
                "scale" if x.len() == 3 => {
                    Matrix4::new_nonuniform_scaling(&Vector3::new(x[0], x[1], x[2]))
                }
                "rotate" if x.len() == 4 => {
                    let axis = Vector3::new(x[0], x[1], x[2]);
                    if axis.norm() == 0.0 {
                        Matrix4::identity()
                    } else {
                        nalgebra::Rotation3::from_axis_angle(
                            &nalgebra::Unit::new_normalize(axis),
                            x[3].to_radians(),
                        )
                        .to_homogeneous()
                    }
                }
                "matrix" | "translate" | "scale" | "rotate" => {
                    return Err(bad(
                        self.file,
                        format!("<{}> has {} numbers", c.tag_name().name(), x.len()),
                    ))
                }
                _ => continue,
            };
            m *= t;
        }
        for c in node.children().filter(|c| c.is_element()) {
            match c.tag_name().name() {
                "instance_geometry" => {
                    let url = c.attribute("url").unwrap_or("").trim_start_matches('#');
                    let g = self.by_id.get(url).ok_or_else(|| {
                        bad(
                            self.file,
                            format!("<instance_geometry url='#{url}'> names no geometry"),
                        )
                    })?;
                    self.geometry(*g, &m, Some(c), out)?;
                }
                "instance_node" => {
                    let url = c.attribute("url").unwrap_or("").trim_start_matches('#');
                    if let Some(n) = self.by_id.get(url) {
                        self.node(*n, &m, out, depth + 1)?;
                    }
                }
                "node" => self.node(c, &m, out, depth + 1)?,
                _ => {}
            }
        }
        Ok(())
    }

    /// The diffuse colour of the material bound to `symbol` by an `<instance_geometry>`.
    fn material_color(&self, inst: Option<roxmltree::Node>, symbol: &str) -> Option<[f32; 4]> {
        let target = inst?
            .descendants()
            .find(|n| n.has_tag_name("instance_material") && n.attribute("symbol") == Some(symbol))?
            .attribute("target")?
            .trim_start_matches('#');
        let mat = self.by_id.get(target)?;
        let eff_url = mat
            .descendants()
            .find(|n| n.has_tag_name("instance_effect"))?
            .attribute("url")?
            .trim_start_matches('#');
        let eff = self.by_id.get(eff_url)?;
        let color = eff
            .descendants()
            .find(|n| n.has_tag_name("diffuse"))?
            .children()
            .find(|n| n.has_tag_name("color"))?;
        let c = numbers(color.text());
        (c.len() >= 3).then(|| [c[0], c[1], c[2], c.get(3).copied().unwrap_or(1.0)])
    }

    fn geometry(
        &self,
        g: roxmltree::Node,
        m: &Matrix4<f32>,
        inst: Option<roxmltree::Node>,
        out: &mut Vec<(String, Mesh)>,
    ) -> Result<()> {
        let Some(mesh) = g.children().find(|n| n.has_tag_name("mesh")) else {
            return Ok(()); // splines, convex meshes: nothing to draw
        };
        for prim in mesh.children().filter(|n| {
            n.has_tag_name("triangles") || n.has_tag_name("polylist") || n.has_tag_name("polygons")
        }) {
            let inputs: Vec<_> = prim
                .children()
                .filter(|n| n.has_tag_name("input"))
                .collect();
            let stride = inputs
                .iter()
                .filter_map(|i| i.attribute("offset")?.parse::<usize>().ok())
                .max()
                .map_or(1, |m| m + 1);
            let Some(vin) = inputs
                .iter()
                .find(|i| i.attribute("semantic") == Some("VERTEX"))
            else {
                continue;
            };
            let offset: usize = vin
                .attribute("offset")
                .and_then(|o| o.parse().ok())
                .unwrap_or(0);
            let positions = self.positions(vin.attribute("source").unwrap_or(""))?;
            let placed: Vec<[f32; 3]> = positions
                .iter()
                .map(|p| {
                    let v = m * Vector4::new(p[0], p[1], p[2], 1.0);
                    [v.x, v.y, v.z]
                })
                .collect();
            // Polygons: (vertex counts, index lists) per <p>.
            let mut polys: Vec<Vec<u32>> = Vec::new();
            let ps: Vec<Vec<f32>> = prim
                .children()
                .filter(|n| n.has_tag_name("p"))
                .map(|p| numbers(p.text()))
                .collect();
            let vertex = |list: &[f32], k: usize| -> Result<u32> {
                let i = *list.get(k * stride + offset).ok_or_else(|| {
                    bad(self.file, "a <p> list is shorter than its primitive says")
                })? as usize;
                if i >= placed.len() {
                    return Err(bad(
                        self.file,
                        format!(
                            "vertex index {i} is out of range ({} positions)",
                            placed.len()
                        ),
                    ));
                }
                Ok(i as u32)
            };
            match prim.tag_name().name() {
                "triangles" => {
                    for list in &ps {
                        for t in 0..list.len() / stride / 3 {
                            polys.push(
                                (0..3)
                                    .map(|c| vertex(list, 3 * t + c))
                                    .collect::<Result<_>>()?,
                            );
                        }
                    }
                }
                "polylist" => {
                    let counts = numbers(
                        prim.children()
                            .find(|n| n.has_tag_name("vcount"))
                            .and_then(|n| n.text()),
                    );
                    let list = ps.first().cloned().unwrap_or_default();
                    let mut k = 0;
                    for c in counts {
                        let c = c as usize;
                        polys.push(
                            (k..k + c)
                                .map(|j| vertex(&list, j))
                                .collect::<Result<_>>()?,
                        );
                        k += c;
                    }
                }
                _ => {
                    for list in &ps {
                        polys.push(
                            (0..list.len() / stride)
                                .map(|j| vertex(list, j))
                                .collect::<Result<_>>()?,
                        );
                    }
                }
            }
            let symbol = prim.attribute("material").unwrap_or("");
            let color = self.material_color(inst, symbol);
            let key = format!("{color:?}");
            let slot = match out.iter().position(|(k, _)| *k == key) {
                Some(s) => s,
                None => {
                    out.push((
                        key,
                        Mesh {
                            color,
                            ..Default::default()
                        },
                    ));
                    out.len() - 1
                }
            };
            let dst = &mut out[slot].1;
            let base = dst.positions.len() as u32;
            dst.positions.extend_from_slice(&placed);
            for p in polys {
                for k in 1..p.len().saturating_sub(1) {
                    dst.indices
                        .extend([base + p[0], base + p[k], base + p[k + 1]]);
                }
            }
        }
        Ok(())
    }

    /// The POSITION array of a `<vertices>` (or a `<source>` named directly).
    fn positions(&self, url: &str) -> Result<Vec<[f32; 3]>> {
        let id = url.trim_start_matches('#');
        let node = self
            .by_id
            .get(id)
            .ok_or_else(|| bad(self.file, format!("the source '#{id}' does not exist")))?;
        let source = if node.has_tag_name("vertices") {
            let url = node
                .children()
                .find(|n| n.has_tag_name("input") && n.attribute("semantic") == Some("POSITION"))
                .and_then(|n| n.attribute("source"))
                .ok_or_else(|| {
                    bad(
                        self.file,
                        format!("<vertices id='{id}'> has no POSITION input"),
                    )
                })?;
            *self
                .by_id
                .get(url.trim_start_matches('#'))
                .ok_or_else(|| bad(self.file, format!("the source '{url}' does not exist")))?
        } else {
            *node
        };
        let array = source
            .children()
            .find(|n| n.has_tag_name("float_array"))
            .ok_or_else(|| bad(self.file, format!("the source '{id}' has no <float_array>")))?;
        let x = numbers(array.text());
        let stride = source
            .descendants()
            .find(|n| n.has_tag_name("accessor"))
            .and_then(|a| a.attribute("stride"))
            .and_then(|s| s.parse::<usize>().ok())
            .unwrap_or(3)
            .max(3);
        Ok(x.chunks_exact(stride).map(|c| [c[0], c[1], c[2]]).collect())
    }
}

/// A box centred at the origin with edge lengths `size`.
///
/// ```
/// let b = screwdyn_view::mesh::cuboid([1.0, 2.0, 3.0]);
/// assert_eq!(b.triangles(), 12);
/// assert_eq!(b.bounds(), ([-0.5, -1.0, -1.5], [0.5, 1.0, 1.5]));
/// ```
pub fn cuboid(size: [f32; 3]) -> Mesh {
    let h = size.map(|s| s / 2.0);
    let positions: Vec<[f32; 3]> = (0..8)
        .map(|k| {
            [
                if k & 1 != 0 { h[0] } else { -h[0] },
                if k & 2 != 0 { h[1] } else { -h[1] },
                if k & 4 != 0 { h[2] } else { -h[2] },
            ]
        })
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut indices = Vec::new();
    for q in quads {
        indices.extend([q[0], q[1], q[2], q[0], q[2], q[3]]);
    }
    Mesh {
        positions,
        indices,
        color: None,
    }
}

/// A surface of revolution about `z`: `profile` is a list of `(radius, z)` from bottom to top;
/// `segments` around. Ends with radius 0 close the surface.
fn lathe(profile: &[(f32, f32)], segments: usize) -> Mesh {
    let mut m = Mesh::default();
    let ring = |r: f32, z: f32, m: &mut Mesh| {
        for s in 0..segments {
            let a = std::f32::consts::TAU * s as f32 / segments as f32;
            // `+ 0.0` turns −0 into +0, so the pole vertices merge in `dedup`.
            m.positions.push([r * a.cos() + 0.0, r * a.sin() + 0.0, z]);
        }
    };
    for &(r, z) in profile {
        ring(r, z, &mut m);
    }
    for k in 0..profile.len() - 1 {
        for s in 0..segments {
            let a = (k * segments + s) as u32;
            let b = (k * segments + (s + 1) % segments) as u32;
            let (c, d) = (a + segments as u32, b + segments as u32);
            m.indices.extend([a, b, d, a, d, c]);
        }
    }
    m.dedup();
    // Drop the triangles that collapsed at the poles.
    let idx: Vec<u32> = m
        .indices
        .chunks_exact(3)
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .flatten()
        .copied()
        .collect();
    m.indices = idx;
    m
}

/// A closed cylinder of `radius` and `length` along `z`, centred at the origin (URDF's
/// `<cylinder>`).
///
/// ```
/// let c = screwdyn_view::mesh::cylinder(0.5, 2.0, 16);
/// assert_eq!(c.bounds().1[2], 1.0);
/// ```
pub fn cylinder(radius: f32, length: f32, segments: usize) -> Mesh {
    let h = length / 2.0;
    lathe(&[(0.0, -h), (radius, -h), (radius, h), (0.0, h)], segments)
}

/// A sphere of `radius` at the origin.
pub fn sphere(radius: f32, segments: usize, rings: usize) -> Mesh {
    let profile: Vec<(f32, f32)> = (0..=rings)
        .map(|k| {
            let a = std::f32::consts::PI * (k as f32 / rings as f32 - 0.5);
            (radius * a.cos(), radius * a.sin())
        })
        .collect();
    lathe(&profile, segments)
}

/// A capsule of `radius` from `z = 0` to `z = length` (hemispherical ends).
pub fn capsule(radius: f32, length: f32, segments: usize) -> Mesh {
    let rings = 6;
    let mut profile = Vec::new();
    for k in 0..=rings {
        let a = std::f32::consts::FRAC_PI_2 * (k as f32 / rings as f32 - 1.0);
        profile.push((radius * a.cos(), radius * a.sin()));
    }
    for k in 0..=rings {
        let a = std::f32::consts::FRAC_PI_2 * (k as f32 / rings as f32);
        profile.push((radius * a.cos(), length + radius * a.sin()));
    }
    lathe(&profile, segments)
}
