//! Mesh readers, path resolution, the skeleton and run reading, on small files written here.
//! Expected values come from the files' own contents (corners, stored normals, transforms
//! written by hand) and from seed 003's two-link forward kinematics.

use nalgebra::Vector3;
use screwdyn::kinematics::forward_kinematics;
use screwdyn::{builtin, Workspace};
use screwdyn_view::mesh::{read_dae, Mesh};
use screwdyn_view::run::{read_run, PAST_EFFORT, PAST_LIMIT};
use screwdyn_view::scene::skeleton_segments;
use screwdyn_view::visual::{read_mesh_file, resolve_mesh};
use screwdyn_view::{render_html, ViewOptions, WarningKind};
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("screwdyn_view_tests_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1): four facets with the normals of
/// their corners' order (outward for the first three), corners listed as written to the file.
fn tetrahedron() -> Vec<([f32; 3], [[f32; 3]; 3])> {
    let (o, x, y, z) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    let s = 1.0 / 3f32.sqrt();
    vec![
        ([0.0, 0.0, -1.0], [o, y, x]),
        ([0.0, -1.0, 0.0], [o, x, z]),
        ([-1.0, 0.0, 0.0], [o, z, y]),
        // Written clockwise seen from outside: kept as written (MuJoCo reads STL corners in
        // their order too; the page lights both faces).
        ([-s, -s, -s], [x, z, y]),
    ]
}

fn stl_binary(facets: &[([f32; 3], [[f32; 3]; 3])]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend((facets.len() as u32).to_le_bytes());
    for (n, c) in facets {
        for v in std::iter::once(n).chain(c.iter()) {
            for x in v {
                b.extend(x.to_le_bytes());
            }
        }
        b.extend([0, 0]);
    }
    b
}

fn stl_ascii(facets: &[([f32; 3], [[f32; 3]; 3])]) -> String {
    let mut s = "solid tet\n".to_string();
    for (n, c) in facets {
        s += &format!(
            "  facet normal {} {} {}\n    outer loop\n",
            n[0], n[1], n[2]
        );
        for v in c {
            s += &format!("      vertex {} {} {}\n", v[0], v[1], v[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s + "endsolid tet\n"
}

fn v(p: [f32; 3]) -> Vector3<f32> {
    Vector3::new(p[0], p[1], p[2])
}

/// Every triangle's right-hand normal is the normal of one of the facets as written.
fn check_outward(m: &Mesh, facets: &[([f32; 3], [[f32; 3]; 3])]) {
    for t in m.indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| v(m.positions[i as usize]));
        let n = (b - a).cross(&(c - a)).normalize();
        assert!(
            facets.iter().any(|(s, _)| (n - v(*s)).norm() < 1e-5),
            "triangle normal {n:?} is not the normal of a facet as written"
        );
    }
}

#[test]
fn stl_binary_and_ascii_give_the_tetrahedron_as_written() {
    let f = tetrahedron();
    let dir = tmp("stl");
    let (bin, asc, bad) = (dir.join("bin.stl"), dir.join("asc.STL"), dir.join("x.stl"));
    std::fs::write(&bin, stl_binary(&f)).unwrap();
    std::fs::write(&asc, stl_ascii(&f)).unwrap();
    std::fs::write(&bad, b"not a mesh").unwrap();
    for path in [&bin, &asc] {
        let meshes = read_mesh_file(path).unwrap();
        assert_eq!(meshes.len(), 1);
        let m = &meshes[0];
        assert_eq!(m.triangles(), 4);
        assert_eq!(m.positions.len(), 4, "corners shared by facets are merged");
        check_outward(m, &f);
    }
    let err = read_mesh_file(&bad).unwrap_err().to_string();
    assert!(err.starts_with(&format!("{}: ", bad.display())), "{err}");
}

#[test]
fn obj_quads_and_negative_indices() {
    // A unit cube: 8 vertices, 6 quads written with v/vt/vn and negative references.
    let mut s = String::new();
    for k in 0..8 {
        s += &format!("v {} {} {}\n", k & 1, (k >> 1) & 1, (k >> 2) & 1);
    }
    s += "vt 0 0\nvn 0 0 1\n";
    for q in [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [3, 7, 8, 4],
        [1, 5, 7, 3],
    ] {
        s += &format!("f {}/1/1 {}/1/1 {}/1/1 {}/1/1\n", q[0], q[1], q[2], q[3]);
    }
    // The last face (x = 1: vertices 2, 4, 8, 6) by negative indices (−8 is vertex 1; the
    // texture coordinate −1 is the only one). `mesh-loader` wants the same attributes on every
    // face of an object, as real files have them.
    s += "f -7/-1/1 -5/-1/1 -1/-1/1 -3/-1/1\n";
    let dir = tmp("obj");
    let (cube, bad) = (dir.join("cube.obj"), dir.join("bad.obj"));
    std::fs::write(&cube, &s).unwrap();
    std::fs::write(&bad, "v 0 0 0\nf 1 2 3\n").unwrap();
    let meshes = read_mesh_file(&cube).unwrap();
    assert_eq!(meshes.len(), 1);
    let m = &meshes[0];
    assert_eq!(m.triangles(), 12);
    assert_eq!(m.bounds(), ([0.0; 3], [1.0; 3]));
    // The x = 1 face's two triangles use exactly the vertices with x = 1.
    for t in m.indices[30..36].iter() {
        assert_eq!(m.positions[*t as usize][0], 1.0);
    }
    let err = read_mesh_file(&bad).unwrap_err().to_string();
    assert!(err.starts_with(&format!("{}: ", bad.display())), "{err}");
}

#[test]
fn dae_node_transforms_unit_and_materials() {
    // One quad (polylist) at z = 0 with corners (0,0)…(10,20) in millimetres; the outer node
    // turns 90° about z and moves 100 mm along x; the inner node scales x by 2. A red
    // material. Expected: p_world = unit · (T_outer · S_inner · p).
    let dae = r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <asset><unit name="millimeter" meter="0.001"/><up_axis>Z_UP</up_axis></asset>
 <library_effects><effect id="red-fx"><profile_COMMON><technique sid="c"><phong>
   <diffuse><color>1 0 0 1</color></diffuse></phong></technique></profile_COMMON></effect></library_effects>
 <library_materials><material id="red"><instance_effect url="#red-fx"/></material></library_materials>
 <library_geometries><geometry id="quad"><mesh>
   <source id="pos"><float_array id="pa" count="12">0 0 0 10 0 0 10 20 0 0 20 0</float_array>
     <technique_common><accessor source="#pa" count="4" stride="3"/></technique_common></source>
   <source id="nrm"><float_array id="na" count="3">0 0 1</float_array></source>
   <vertices id="verts"><input semantic="POSITION" source="#pos"/></vertices>
   <polylist count="1" material="m"><input semantic="VERTEX" source="#verts" offset="0"/>
     <input semantic="NORMAL" source="#nrm" offset="1"/><vcount>4</vcount><p>0 0 1 0 2 0 3 0</p></polylist>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="scene">
   <node id="outer"><translate>100 0 0</translate><rotate>0 0 1 90</rotate>
     <node id="inner"><scale>2 1 1</scale>
       <instance_geometry url="#quad"><bind_material><technique_common>
         <instance_material symbol="m" target="#red"/></technique_common></bind_material></instance_geometry>
     </node></node>
 </visual_scene></library_visual_scenes>
 <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>"##;
    let meshes = read_dae(dae, "q.dae").unwrap();
    assert_eq!(meshes.len(), 1);
    let m = &meshes[0];
    assert_eq!(m.triangles(), 2);
    assert_eq!(m.color, Some([1.0, 0.0, 0.0, 1.0]));
    // Corner (10, 20, 0): scaled (20, 20, 0), turned (−20, 20, 0), moved (80, 20, 0) mm.
    let expected = [
        [0.1, 0.0, 0.0],
        [0.1, 0.02, 0.0],
        [0.08, 0.02, 0.0],
        [0.08, 0.0, 0.0],
    ];
    for (p, e) in m.positions.iter().zip(expected) {
        for k in 0..3 {
            assert!((p[k] - e[k]).abs() < 1e-6, "{p:?} vs {e:?}");
        }
    }
    assert!(read_dae("<COLLADA>", "broken.dae")
        .unwrap_err()
        .to_string()
        .starts_with("broken.dae:"));
}

#[test]
fn package_relative_and_env_paths_resolve() {
    let root = tmp("resolve");
    let pkg = root.join("share/my_robot");
    std::fs::create_dir_all(pkg.join("meshes")).unwrap();
    std::fs::create_dir_all(pkg.join("urdf")).unwrap();
    std::fs::write(pkg.join("meshes/a.stl"), b"solid a\nendsolid a\n").unwrap();
    let elsewhere = root.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let uri = "package://my_robot/meshes/a.stl";
    let want = pkg.join("meshes/a.stl");
    // --package-path: the folder holding the package, or the package folder itself.
    for dir in [root.join("share"), pkg.clone()] {
        assert_eq!(resolve_mesh(uri, &elsewhere, &[dir]).unwrap(), want);
    }
    // Above the URDF's folder.
    assert_eq!(resolve_mesh(uri, &pkg.join("urdf"), &[]).unwrap(), want);
    // Relative to the URDF's folder, and absolute / file://.
    assert_eq!(
        resolve_mesh("../meshes/a.stl", &pkg.join("urdf"), &[]).unwrap(),
        pkg.join("urdf/../meshes/a.stl")
    );
    let abs = format!("file://{}", want.display());
    assert_eq!(resolve_mesh(&abs, &elsewhere, &[]).unwrap(), want);
    // ROS_PACKAGE_PATH (this is the only test of this binary that sets it).
    std::env::set_var("ROS_PACKAGE_PATH", root.join("share"));
    let found = resolve_mesh(uri, &elsewhere, &[]);
    std::env::remove_var("ROS_PACKAGE_PATH");
    assert_eq!(found.unwrap(), want);
    let err = resolve_mesh("package://nope/x.stl", &elsewhere, &[])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("package 'nope' not found") && err.contains("--package-path"),
        "{err}"
    );
}

#[test]
fn planar2_skeleton_runs_through_the_joints() {
    // Seed 003: joint 1 at the origin, joint 2 at L1 (cos q1, sin q1), the tip at
    // L1 (cos q1, sin q1) + L2 (cos(q1+q2), sin(q1+q2)), L1 = L2 = 1.
    let m = builtin::planar2();
    let mut ws = Workspace::new(&m);
    for (q1, q2) in [(0.0, 0.0), (0.7, -1.2), (-2.0, 2.5)] {
        forward_kinematics(&m, &mut ws, &[q1, q2]).unwrap();
        let mut got: Vec<[Vector3<f64>; 2]> = skeleton_segments(&m)
            .unwrap()
            .iter()
            .map(|(b, a, c)| {
                let h = ws.pose_in_world[b.unwrap()];
                [h.act_point(a), h.act_point(c)]
            })
            .collect();
        got.sort_by(|x, y| x[0].norm().total_cmp(&y[0].norm()));
        let j2 = Vector3::new(q1.cos(), q1.sin(), 0.0);
        let tip = j2 + Vector3::new((q1 + q2).cos(), (q1 + q2).sin(), 0.0);
        let want = [[Vector3::zeros(), j2], [j2, tip]];
        assert_eq!(got.len(), 2);
        for (g, w) in got.iter().zip(&want) {
            assert!(
                (g[0] - w[0]).norm() < 1e-12 && (g[1] - w[1]).norm() < 1e-12,
                "{g:?} vs {w:?}"
            );
        }
    }
}

fn write_run(path: &Path, rows: &[(f64, [f64; 2], [f64; 2])]) {
    let mut s =
        "t,q.joint1,q.joint2,v.joint1,v.joint2,tau.joint1,tau.joint2,total_energy\n".to_string();
    for (t, q, tau) in rows {
        s += &format!("{t},{},{},0,0,{},{},1\n", q[0], q[1], tau[0], tau[1]);
    }
    std::fs::write(path, s).unwrap();
}

#[test]
fn runs_are_strided_and_keep_violations_of_dropped_samples() {
    // A model with limits: joint 1 within ±1 rad, effort 5 N·m.
    let text = r#"<robot name="r"><link name="base"/>
      <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="b"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="joint1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
      <joint name="joint2" type="continuous"><parent link="a"/><child link="b"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint>
    </robot>"#;
    let m = screwdyn::io::load_str(text, "r.urdf", &Default::default()).unwrap();
    let dir = tmp("runs");
    let path = dir.join("run.csv");
    // 101 samples at 10 ms; sample 37 past the position limit, 55 past the effort limit;
    // joint 2 (continuous) far out but never a violation.
    let rows: Vec<_> = (0..=100)
        .map(|k| {
            let q1 = if k == 37 { 1.5 } else { 0.0 };
            let tau1 = if k == 55 { -7.0 } else { 1.0 };
            (k as f64 * 0.01, [q1, 10.0], [tau1, 100.0])
        })
        .collect();
    write_run(&path, &rows);
    let run = read_run(&path, &m, 11).unwrap();
    assert_eq!(run.samples_read, 101);
    assert_eq!(run.t.len(), 11, "rows 0, 10, …, 100");
    assert!((run.t[3] - 0.3).abs() < 1e-12);
    assert!((run.duration() - 1.0).abs() < 1e-12);
    // Row 37 was dropped; its violation is carried by the next kept row (40), row 55's by 60.
    assert_eq!(run.flags[4][0], PAST_LIMIT);
    assert_eq!(run.flags[6][0], PAST_EFFORT);
    assert!(run
        .flags
        .iter()
        .enumerate()
        .all(|(k, f)| f[1] == 0 && (k == 4 || k == 6 || f[0] == 0)));
    assert_eq!(run.violations.len(), 2);
    let v = &run.violations;
    assert!((v[0].first_time - 0.37).abs() < 1e-12 && v[0].worst == 1.5 && v[0].count == 1);
    assert!((v[1].first_time - 0.55).abs() < 1e-12 && v[1].worst == -7.0 && v[1].count == 1);
    assert_eq!(run.energy[0].0, "total_energy");

    // A run of another robot: one sentence naming the column and the model's joints.
    std::fs::write(dir.join("other.csv"), "t,q.shoulder,q.joint2\n0,0,0\n").unwrap();
    let e = read_run(&dir.join("other.csv"), &m, 100)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("'q.shoulder'") && e.contains("joint1, joint2"),
        "{e}"
    );
    std::fs::write(dir.join("short.csv"), "t,q.joint1\n0,0\n").unwrap();
    let e = read_run(&dir.join("short.csv"), &m, 100)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no position column for joint(s) joint2"), "{e}");
}

#[test]
fn missing_meshes_warn_and_huge_meshes_are_capped() {
    let dir = tmp("cap");
    // A sphere-like STL of 20 000 triangles (a fine lathe), and a missing mesh.
    let mut fine = screwdyn_view::mesh::sphere(0.1, 200, 51);
    fine.dedup();
    let tris = fine.triangles();
    assert!(tris > 19_000);
    let mut facets = Vec::new();
    for t in fine.indices.chunks_exact(3) {
        let c = [t[0], t[1], t[2]].map(|i| fine.positions[i as usize]);
        let n = (v(c[1]) - v(c[0])).cross(&(v(c[2]) - v(c[0])));
        facets.push(([n.x, n.y, n.z], c));
    }
    std::fs::write(dir.join("ball.stl"), stl_binary(&facets)).unwrap();
    let urdf = dir.join("r.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="r"><link name="base"><visual><geometry><mesh filename="ball.stl"/></geometry></visual></link>
      <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
        <visual><geometry><mesh filename="package://gone/arm.dae"/></geometry></visual></link>
      <joint name="j" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint></robot>"#,
    )
    .unwrap();
    let m = screwdyn::io::load_model(urdf.to_str().unwrap()).unwrap();
    let page = render_html(
        &m,
        &ViewOptions {
            description: Some(urdf.clone()),
            max_triangles: 5000,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(
        page.triangles <= 5000 + 12 * 3,
        "{} triangles",
        page.triangles
    );
    let kinds: Vec<_> = page.warnings.iter().map(|w| w.kind).collect();
    assert!(
        kinds.contains(&WarningKind::MeshMissing) && kinds.contains(&WarningKind::Decimated),
        "{kinds:?}"
    );
    assert!(page
        .warnings
        .iter()
        .any(|w| w.message.contains("package://gone/arm.dae")));
    // Without the cap the sphere is kept whole.
    let full = render_html(
        &m,
        &ViewOptions {
            description: Some(urdf),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(full.triangles >= tris);
}
