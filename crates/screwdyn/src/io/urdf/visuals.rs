//! A URDF's `<visual>` elements as [`Visual`]s (the loader keeps only the dynamics; this reads
//! the text again for what the model looks like).

use crate::error::{Error, Result};
use crate::io::visual::{Shape, Visual};
use crate::spatial::Se3;
use nalgebra::Vector3;
use std::collections::HashMap;

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
/// let v = screwdyn::io::urdf::parse_visuals(urdf, "r.urdf").unwrap();
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
            let element = v
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
                element.attribute(a).ok_or_else(|| {
                    Error::parse_at(
                        file,
                        line(element) as usize,
                        format!(
                            "<{}> of link '{name}' has no '{a}' attribute",
                            element.tag_name().name()
                        ),
                    )
                })
            };
            let one =
                |a: &str| -> Result<f64> { Ok(numbers(attr(a)?, 1, a, file, line(element))?[0]) };
            let shape = match element.tag_name().name() {
                "box" => {
                    let s = numbers(attr("size")?, 3, "size", file, line(element))?;
                    Shape::Box {
                        size: [s[0], s[1], s[2]],
                    }
                }
                "cylinder" => Shape::Cylinder {
                    radius: one("radius")?,
                    length: one("length")?,
                },
                "sphere" => Shape::Sphere {
                    radius: one("radius")?,
                },
                "mesh" => {
                    let scale = match element.attribute("scale") {
                        Some(t) => {
                            let s = numbers(t, 3, "scale", file, line(element))?;
                            [s[0], s[1], s[2]]
                        }
                        None => [1.0; 3],
                    };
                    Shape::Mesh {
                        file: attr("filename")?.to_string(),
                        scale,
                    }
                }
                other => {
                    return Err(Error::parse_at(
                        file,
                        line(element) as usize,
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
                shape,
                color,
            });
        }
    }
    Ok(out)
}
