//! The geoms drawn by a viewer, as [`Visual`]s: those in the groups MuJoCo's viewer shows by
//! default (0, 1, 2; Menagerie's visual meshes are in group 2, its collision shapes in group 3),
//! planes and height fields left out. Colour: the geom's `rgba` when it (or its class) sets
//! one, else its `material`'s `rgba`, else MuJoCo's default grey.

use super::bodies::Walk;
use super::defaults::Styled;
use super::geoms::{geom_type, placement_and_size};
use super::values::Values;
use crate::error::Result;
use crate::io::visual::{Shape, Visual};
use nalgebra::Vector3;
use std::collections::HashMap;

/// MuJoCo's default geom colour.
const GREY: [f32; 4] = [0.5, 0.5, 0.5, 1.0];

fn rgba(v: &Values) -> Result<Option<[f32; 4]>> {
    Ok(v.numbers("rgba", 4)?
        .map(|c| [c[0] as f32, c[1] as f32, c[2] as f32, c[3] as f32]))
}

/// The visual geoms the walk met, in file order.
pub(crate) fn visuals(walk: &Walk) -> Result<Vec<Visual>> {
    let (tree, defaults) = (walk.tree, walk.defaults);
    let values = |element, class| Values {
        tree,
        styled: Styled {
            element,
            class,
            defaults,
        },
    };
    // Material colours by name (a material without rgba is white, as in MuJoCo).
    let mut materials: HashMap<&str, [f32; 4]> = HashMap::new();
    for a in tree.root.children_named("asset") {
        for m in a.children_named("material") {
            let v = values(m, defaults.class_of(tree, m, defaults.main())?);
            if let Some(name) = v.text("name") {
                materials.insert(name, rgba(&v)?.unwrap_or([1.0; 4]));
            }
        }
    }
    let mut out = Vec::new();
    for ((g, at, inherited), link) in walk.geoms.iter().zip(&walk.geom_links) {
        let v = values(g, defaults.class_of(tree, g, *inherited)?);
        let group = v.number("group")?.unwrap_or(0.0);
        let kind = geom_type(&v)?;
        if !(0.0..=2.0).contains(&group) || matches!(kind, "plane" | "hfield" | "sdf") {
            continue;
        }
        let (placement, s) = placement_and_size(&v, walk.compiler, kind)?;
        let shape = match kind {
            "sphere" => Shape::Sphere { radius: s[0] },
            "capsule" => Shape::Capsule {
                radius: s[0],
                length: 2.0 * s[1],
            },
            "cylinder" => Shape::Cylinder {
                radius: s[0],
                length: 2.0 * s[1],
            },
            "ellipsoid" => Shape::Ellipsoid {
                radii: [s[0], s[1], s[2]],
            },
            "box" => Shape::Box {
                size: [2.0 * s[0], 2.0 * s[1], 2.0 * s[2]],
            },
            _ => {
                let name = v
                    .text("mesh")
                    .ok_or_else(|| v.error("<geom type=\"mesh\"> names no mesh"))?;
                let (file, scale): (_, Vector3<f64>) = walk.meshes.file_of(&v, name)?;
                let file = std::path::absolute(file).unwrap_or_else(|_| file.to_path_buf());
                Shape::Mesh {
                    file: file.display().to_string(),
                    scale: [scale.x, scale.y, scale.z],
                }
            }
        };
        let material = v.text("material").and_then(|m| materials.get(m).copied());
        let color = rgba(&v)?.or(material).unwrap_or(GREY);
        out.push(Visual {
            link: link.clone(),
            origin: at.compose(&placement),
            shape,
            color: Some(color),
        });
    }
    Ok(out)
}
