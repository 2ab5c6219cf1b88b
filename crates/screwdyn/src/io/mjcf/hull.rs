//! The convex hull of a mesh, for `<mesh inertia="convex">`: MuJoCo computes such a mesh's
//! volume and inertia on its convex hull (it builds the hull with qhull), so a non-convex part
//! weighs as the solid that shrink-wraps it.
//!
//! The hull comes from the `quickhull` crate (Quickhull, Barber et al. 1996, as adapted from
//! parry3d by the author of the Avian physics engine, MIT/Apache-2.0). It was chosen over
//! `parry3d` (a whole collision library for one function), `chull` (unmaintained since 2022,
//! on an old `num-bigint`) and `qhull` (bindings that compile qhull's C sources) because it is
//! small, pure Rust, maintained, and most of its dependencies (`glam`, `hashbrown`,
//! `foldhash`, `approx`) were in the workspace's lock file already. It works in single
//! precision, the precision of the vertices in the mesh file (and in MuJoCo): the hull's
//! vertices are input points, unchanged, and the mass properties are then integrated in
//! double precision over its triangles.

use glam::Vec3A;
use nalgebra::Vector3;
use quickhull::ConvexTriangleMesh;

/// The triangles of the convex hull of the vertices of `triangles` (single-precision numbers
/// read from a mesh file, so exact as `f32`), or a sentence saying why there is none.
pub(crate) fn convex_hull(
    triangles: &[[Vector3<f64>; 3]],
) -> std::result::Result<Vec<[Vector3<f64>; 3]>, String> {
    let mut points: Vec<[f32; 3]> = triangles
        .iter()
        .flatten()
        .map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect();
    if points.iter().flatten().any(|x| !x.is_finite()) {
        return Err("it has a vertex that is not a finite number".into());
    }
    // STL repeats each vertex in every triangle that uses it: one copy of each is enough.
    points.sort_by(|a, b| a.map(f32::to_bits).cmp(&b.map(f32::to_bits)));
    points.dedup();
    let points: Vec<Vec3A> = points.iter().map(|&p| Vec3A::from_array(p)).collect();
    // The crate's debug builds check their own invariants with assertions: a failed one is
    // reported as this mesh's error rather than a panic of the loader.
    let hull = std::panic::catch_unwind(|| ConvexTriangleMesh::try_from_points(&points, None))
        .map_err(|_| "the convex hull could not be built (an internal check failed)".to_string())?
        .map_err(|e| format!("the convex hull could not be built ({e})"))?;
    let v = hull.vertices();
    let at = |k: u32| {
        let p = v[k as usize];
        Vector3::new(p.x as f64, p.y as f64, p.z as f64)
    };
    Ok(hull
        .indices()
        .iter()
        .map(|t| [at(t[0]), at(t[1]), at(t[2])])
        .collect())
}
