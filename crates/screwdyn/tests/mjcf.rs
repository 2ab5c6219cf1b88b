//! The MJCF loader on small files: geom inertias against the solids' formulas, each orientation
//! form against a rotation written by hand, default-class precedence, includes, several joints
//! in one body, keyframes, effort limits, and every kind of bad input (one sentence at
//! `file:line`, no panic). Agreement with MuJoCo itself is checked in the Python suite
//! (crates/screwdyn-py/tests/test_mjcf.py).

use nalgebra::{Matrix3, Rotation3, Vector3};
use screwdyn::io::{load_model, load_str, mjcf::parse_mjcf_report, LoadOptions};
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::{Model, Workspace};
use std::f64::consts::{FRAC_PI_2, PI};

fn load(text: &str) -> Model {
    load_str(text, "t.xml", &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn err(text: &str) -> String {
    match load_str(text, "bad.xml", &LoadOptions::default()) {
        Ok(_) => panic!("loaded but should not:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn check(msg: &str, place: &str, words: &[&str]) {
    assert!(
        msg.starts_with(place),
        "expected '{place}' at the start of: {msg}"
    );
    for w in words {
        assert!(msg.contains(w), "expected '{w}' in: {msg}");
    }
    assert!(!msg.contains('\n'), "one line: {msg}");
}

fn close(a: &Matrix3<f64>, b: &Matrix3<f64>, tol: f64) {
    assert!((a - b).amax() <= tol, "\n{a}\n!=\n{b}");
}

/// One moving body holding `geoms`, angles in radians.
fn one_body(geoms: &str) -> Model {
    load(&format!(
        "<mujoco><compiler angle=\"radian\"/><worldbody><body name=\"b\"><joint name=\"j\"/>{geoms}</body></worldbody></mujoco>"
    ))
}

fn diag(x: f64, y: f64, z: f64) -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(x, y, z))
}

#[test]
fn primitive_geoms_have_the_solids_inertias() {
    let m = 2.0;
    // Box of half-sizes a, b, c: I_xx = m (b² + c²)/3 (full sides 2a, 2b, 2c).
    let i = one_body("<geom type=\"box\" size=\"0.1 0.2 0.3\" mass=\"2\"/>").bodies()[0].inertia;
    close(
        &i.inertia_com,
        &diag(m * 0.13 / 3.0, m * 0.10 / 3.0, m * 0.05 / 3.0),
        1e-15,
    );
    // Sphere: 2/5 m r²; from density: m = ρ 4/3 π r³.
    let i = one_body("<geom size=\"0.1\"/>").bodies()[0].inertia;
    let ms = 1000.0 * 4.0 / 3.0 * PI * 1e-3;
    assert!((i.mass - ms).abs() < 1e-12);
    close(
        &i.inertia_com,
        &(Matrix3::identity() * 0.4 * ms * 0.01),
        1e-15,
    );
    // Cylinder of radius r and half-height h: m (3r² + (2h)²)/12, m r²/2.
    let i = one_body("<geom type=\"cylinder\" size=\"0.1 0.3\" mass=\"2\"/>").bodies()[0].inertia;
    let ixx = m * (3.0 * 0.01 + 0.36) / 12.0;
    close(&i.inertia_com, &diag(ixx, ixx, m * 0.01 / 2.0), 1e-15);
    // Ellipsoid: m (b² + c²)/5.
    let i =
        one_body("<geom type=\"ellipsoid\" size=\"0.1 0.2 0.3\" mass=\"2\"/>").bodies()[0].inertia;
    close(
        &i.inertia_com,
        &diag(m * 0.13 / 5.0, m * 0.10 / 5.0, m * 0.05 / 5.0),
        1e-15,
    );
}

#[test]
fn capsule_is_a_cylinder_and_a_sphere_split_at_its_ends() {
    // Independent: the capsule of density ρ is the cylinder plus the two hemispheres; each
    // hemisphere (mass m_s/2) has its centre 3r/8 from its face, I about its own centre
    // 2/5 (m_s/2) r² − (m_s/2)(3r/8)², moved by h + 3r/8 (parallel axes).
    let (r, h, rho) = (0.05_f64, 0.2_f64, 700.0);
    let i = one_body(&format!(
        "<geom type=\"capsule\" size=\"{r} {h}\" density=\"{rho}\"/>"
    ))
    .bodies()[0]
        .inertia;
    let mc = rho * PI * r * r * 2.0 * h;
    let mh = rho * 2.0 / 3.0 * PI * r.powi(3);
    let d = h + 3.0 * r / 8.0;
    let hemi_own = 0.4 * mh * r * r - mh * (3.0 * r / 8.0).powi(2);
    let ixx = mc * (3.0 * r * r + 4.0 * h * h) / 12.0 + 2.0 * (hemi_own + mh * d * d);
    let izz = mc * r * r / 2.0 + 2.0 * 0.4 * mh * r * r;
    assert!((i.mass - (mc + 2.0 * mh)).abs() < 1e-12);
    close(&i.inertia_com, &diag(ixx, ixx, izz), 1e-14);
}

#[test]
fn fromto_places_the_geom_between_its_points() {
    // A cylinder from (0,0,0) to (0.4,0,0): along x, centred at (0.2,0,0), half-length 0.2.
    let i = one_body("<geom type=\"cylinder\" fromto=\"0 0 0 0.4 0 0\" size=\"0.1\" mass=\"2\"/>")
        .bodies()[0]
        .inertia;
    assert!((i.com - Vector3::new(0.2, 0.0, 0.0)).norm() < 1e-15);
    let axial = 2.0 * 0.01 / 2.0;
    let across = 2.0 * (3.0 * 0.01 + 0.16) / 12.0;
    close(&i.inertia_com, &diag(axial, across, across), 1e-15);
}

#[test]
fn geoms_outside_the_inertia_group_range_and_planes_do_not_count() {
    let i = one_body(
        "<geom size=\"0.1\" mass=\"1\"/><geom size=\"1\" mass=\"5\" group=\"6\"/><geom type=\"plane\" size=\"1 1 1\"/>",
    )
    .bodies()[0]
    .inertia;
    assert_eq!(i.mass, 1.0);
}

#[test]
fn a_closed_mesh_cube_has_the_box_inertia() {
    let dir = tempfile::tempdir().unwrap();
    // The cube [0, 0.25]³ as 12 outward-wound triangles, in an OBJ file (0.25 is exact in the
    // single precision mesh files are read in).
    let v = (0..8)
        .map(|k| {
            format!(
                "v {} {} {}\n",
                0.25 * (k & 1) as f64,
                0.25 * ((k >> 1) & 1) as f64,
                0.25 * ((k >> 2) & 1) as f64
            )
        })
        .collect::<String>();
    let faces = "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
    std::fs::write(dir.path().join("cube.obj"), format!("{v}{faces}")).unwrap();
    let main = dir.path().join("m.xml");
    let text = "<mujoco><asset><mesh file=\"cube.obj\"/></asset><worldbody><body name=\"b\"><joint name=\"j\"/><geom type=\"mesh\" mesh=\"cube\" pos=\"1 0 0\"/></body></worldbody></mujoco>";
    std::fs::write(&main, text).unwrap();
    let m = load_model(main.to_str().unwrap()).unwrap();
    let i = m.bodies()[0].inertia;
    let mass = 1000.0 * 0.25_f64.powi(3);
    assert!((i.mass - mass).abs() < 1e-12 * mass, "{}", i.mass);
    assert!((i.com - Vector3::new(1.125, 0.125, 0.125)).norm() < 1e-15);
    let s = mass * (0.0625 + 0.0625) / 12.0;
    close(&i.inertia_com, &(Matrix3::identity() * s), 1e-12 * s);
}

#[test]
fn a_convex_mesh_weighs_its_hull() {
    // Two cubes of side 0.25, a gap of 0.25 between them along x: the hull is the box
    // 0.75 × 0.25 × 0.25.
    let dir = tempfile::tempdir().unwrap();
    let mut obj = String::new();
    for x0 in [0.0, 0.5] {
        for k in 0..8 {
            obj += &format!(
                "v {} {} {}\n",
                x0 + 0.25 * (k & 1) as f64,
                0.25 * ((k >> 1) & 1) as f64,
                0.25 * ((k >> 2) & 1) as f64
            );
        }
    }
    for o in [0, 8] {
        for f in [
            [1, 3, 4],
            [1, 4, 2],
            [5, 6, 8],
            [5, 8, 7],
            [1, 2, 6],
            [1, 6, 5],
            [3, 7, 8],
            [3, 8, 4],
            [1, 5, 7],
            [1, 7, 3],
            [2, 4, 8],
            [2, 8, 6],
        ] {
            obj += &format!("f {} {} {}\n", f[0] + o, f[1] + o, f[2] + o);
        }
    }
    std::fs::write(dir.path().join("pair.obj"), obj).unwrap();
    let load_as = |inertia: &str| {
        let main = dir.path().join(format!("{inertia}.xml"));
        std::fs::write(&main, format!("<mujoco><asset><mesh file=\"pair.obj\" {inertia}/></asset><worldbody><body name=\"b\"><joint name=\"j\"/><geom type=\"mesh\" mesh=\"pair\"/></body></worldbody></mujoco>")).unwrap();
        load_model(main.to_str().unwrap()).unwrap().bodies()[0].inertia
    };
    let hull = load_as("inertia=\"convex\"");
    let (a, b, c) = (0.75, 0.25, 0.25);
    let mass = 1000.0 * a * b * c;
    assert!((hull.mass - mass).abs() < 1e-12 * mass, "{}", hull.mass);
    assert!((hull.com - Vector3::new(0.375, 0.125, 0.125)).norm() < 1e-15);
    let box_inertia = diag(b * b + c * c, a * a + c * c, a * a + b * b) * (mass / 12.0);
    close(&hull.inertia_com, &box_inertia, 1e-12 * mass);
    // Exact counts the two cubes; the default is legacy (MuJoCo's), whose pyramids from a centre
    // between the cubes count more than the solid (the Python suite compares it with MuJoCo).
    let two_cubes = 2.0 * 1000.0 * 0.25_f64.powi(3);
    assert!((load_as("inertia=\"exact\"").mass - two_cubes).abs() < 1e-12);
    let legacy = load_as("inertia=\"legacy\"").mass;
    assert_eq!(load_as("").mass, legacy);
    assert!(legacy > two_cubes * (1.0 + 1e-6), "{legacy}");
    // A hull cut to fewer vertices is refused, naming the attribute.
    let main = dir.path().join("cut.xml");
    std::fs::write(&main, "<mujoco><asset><mesh file=\"pair.obj\" inertia=\"convex\" maxhullvert=\"6\"/></asset><worldbody><body><joint/><geom type=\"mesh\" mesh=\"pair\"/></body></worldbody></mujoco>").unwrap();
    let e = load_model(main.to_str().unwrap()).unwrap_err().to_string();
    assert!(e.contains("maxhullvert") && !e.contains('\n'), "{e}");
}

#[test]
fn a_joint_in_a_frame_has_its_axis_and_pos_in_the_frame() {
    // The frame at (0, 0, 1) turned 90° about y: the joint's x axis is the body's −z, through
    // (0, 0, 1). A quarter turn takes the site (1, 0, 1) to (0, −1, 1).
    let m = load(
        r#"<mujoco><worldbody><body name="b"><geom size="0.1"/>
  <frame pos="0 0 1" euler="0 90 0"><joint name="j" axis="1 0 0"/></frame>
  <site name="s" pos="1 0 1"/></body></worldbody></mujoco>"#,
    );
    let mut ws = Workspace::new(&m);
    forward_kinematics(&m, &mut ws, &[FRAC_PI_2]).unwrap();
    let s = frame_pose(&m, &ws, m.frame_id("s").unwrap()).unwrap();
    assert!(
        (s.translation - Vector3::new(0.0, -1.0, 1.0)).norm() < 1e-12,
        "{}",
        s.translation
    );
    // A joint in a frame of <worldbody> moves nothing: refused, as MuJoCo does.
    check(
        &err("<mujoco><worldbody><frame pos=\"0 0 1\">\n<joint name=\"j\"/></frame></worldbody></mujoco>"),
        "bad.xml:2:",
        &["<worldbody>", "<frame>", "<body>"],
    );
}

fn rot(axis: Vector3<f64>, angle: f64) -> Matrix3<f64> {
    *Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix()
}

/// The placement of site `s` on the world body of a file with `compiler` and `attrs`.
fn site_rotation(compiler: &str, attrs: &str) -> Matrix3<f64> {
    let m = load(&format!(
        "<mujoco><compiler {compiler}/><worldbody><site name=\"s\" {attrs}/></worldbody></mujoco>"
    ));
    m.frames()[m.frame_id("s").unwrap()].placement.rotation
}

#[test]
fn every_orientation_form_matches_a_rotation_written_by_hand() {
    let z90 = rot(Vector3::z(), FRAC_PI_2);
    // quat: w first, not normalised.
    close(&site_rotation("", "quat=\"2 0 0 2\""), &z90, 1e-15);
    // axisangle: degrees by default, radians when the compiler says so.
    close(&site_rotation("", "axisangle=\"0 0 3 90\""), &z90, 1e-15);
    close(
        &site_rotation("angle=\"radian\"", "axisangle=\"0 0 1 1.5707963267948966\""),
        &z90,
        1e-15,
    );
    // xyaxes: x̂ = ŷ₀, ŷ = −x̂₀ (made orthogonal first).
    close(&site_rotation("", "xyaxes=\"0 2 0 -1 0.5 0\""), &z90, 1e-15);
    // zaxis: the smallest rotation taking ẑ to x̂ is +90° about ŷ.
    close(
        &site_rotation("", "zaxis=\"1 0 0\""),
        &rot(Vector3::y(), FRAC_PI_2),
        1e-15,
    );
    close(
        &site_rotation("", "zaxis=\"0 0 -1\""),
        &diag(1.0, -1.0, -1.0),
        1e-15,
    );
    // euler: intrinsic (moving axes) R = Rx(a) Ry(b) Rz(c); extrinsic (fixed axes) Rz Ry Rx.
    let (a, b, c) = (0.3_f64, -0.5_f64, 1.1_f64);
    let (rx, ry, rz) = (
        rot(Vector3::x(), a),
        rot(Vector3::y(), b),
        rot(Vector3::z(), c),
    );
    let e = format!("euler=\"{a} {b} {c}\"");
    close(
        &site_rotation("angle=\"radian\"", &e),
        &(rx * ry * rz),
        1e-15,
    );
    close(
        &site_rotation("angle=\"radian\" eulerseq=\"XYZ\"", &e),
        &(rz * ry * rx),
        1e-15,
    );
    let (d1, d2, d3) = (a.to_degrees(), b.to_degrees(), c.to_degrees());
    let zyx = rot(Vector3::z(), a) * rot(Vector3::y(), b) * rot(Vector3::x(), c);
    close(
        &site_rotation("eulerseq=\"zyx\"", &format!("euler=\"{d1} {d2} {d3}\"")),
        &zyx,
        1e-14,
    );
}

#[test]
fn defaults_follow_mujocos_precedence() {
    let m = load(
        r#"<mujoco>
  <default>
    <joint damping="1" armature="0.5"/>
    <default class="outer">
      <joint damping="2"/>
      <default class="inner"><joint frictionloss="3"/></default>
    </default>
  </default>
  <worldbody>
    <body name="a" childclass="inner"><geom size="0.1"/>
      <joint name="by_childclass"/>
      <joint name="own_attribute" damping="7"/>
      <joint name="own_class" class="outer"/>
      <body name="b"><geom size="0.1"/><joint name="inherited_childclass"/></body>
    </body>
    <body name="c"><geom size="0.1"/><joint name="main"/></body>
  </worldbody>
</mujoco>"#,
    );
    let got: Vec<(f64, f64, f64)> = m
        .joints()
        .iter()
        .map(|j| (j.damping, j.friction, j.armature))
        .collect();
    assert_eq!(
        got,
        vec![
            (2.0, 3.0, 0.5),
            (7.0, 3.0, 0.5),
            (2.0, 0.0, 0.5),
            (2.0, 3.0, 0.5),
            (1.0, 0.0, 0.5)
        ]
    );
    check(
        &err("<mujoco><worldbody>\n<body><joint class=\"nope\"/></body></worldbody></mujoco>"),
        "bad.xml:2:",
        &["class 'nope'", "not defined"],
    );
}

#[test]
fn several_joints_in_one_body_make_a_chain_and_ref_is_qpos() {
    // Two hinges in one body; at q = ref the body is where the file puts it.
    let m = load(
        r#"<mujoco><compiler angle="radian"/><worldbody>
  <body name="b" pos="1 0 0"><geom size="0.1" mass="1"/>
    <joint name="j1" axis="0 0 1" ref="0.4"/>
    <joint name="j2" axis="0 1 0" pos="0 0 0.5" ref="-0.2"/>
    <site name="s" pos="0 0 1"/>
  </body></worldbody></mujoco>"#,
    );
    assert_eq!(m.joint_names(), vec!["j1", "j2"]);
    assert_eq!(m.bodies()[0].name, "b/j1");
    assert_eq!(m.bodies()[0].inertia.mass, 0.0);
    assert_eq!(m.bodies()[1].inertia.mass, 1.0);
    let mut ws = Workspace::new(&m);
    forward_kinematics(&m, &mut ws, &[0.4, -0.2]).unwrap();
    let s = frame_pose(&m, &ws, m.frame_id("s").unwrap()).unwrap();
    assert!((s.translation - Vector3::new(1.0, 0.0, 1.0)).norm() < 1e-15);
    // At q = ref + (π/2, 0): the site turns about ẑ through the body origin.
    forward_kinematics(&m, &mut ws, &[0.4 + FRAC_PI_2, -0.2]).unwrap();
    let s = frame_pose(&m, &ws, m.frame_id("s").unwrap()).unwrap();
    assert!((s.translation - Vector3::new(1.0, 0.0, 1.0)).norm() < 1e-15);
    // At q = ref + (0, π/2): about ŷ through (1, 0, 0.5): the site goes to (1.5, 0, 0.5).
    forward_kinematics(&m, &mut ws, &[0.4, -0.2 + FRAC_PI_2]).unwrap();
    let s = frame_pose(&m, &ws, m.frame_id("s").unwrap()).unwrap();
    assert!(
        (s.translation - Vector3::new(1.5, 0.0, 0.5)).norm() < 1e-15,
        "{}",
        s.translation
    );
}

#[test]
fn welded_bodies_merge_and_keep_their_frames() {
    let m = load(
        r#"<mujoco><worldbody><body name="a"><joint name="j"/><geom size="0.1" mass="1"/>
  <body name="welded" pos="0 0 1"><geom size="0.1" mass="2"/></body></body>
  <body name="fixed_to_world" pos="3 0 0"/></worldbody></mujoco>"#,
    );
    assert_eq!(m.nq(), 1);
    assert_eq!(m.bodies()[0].inertia.mass, 3.0);
    assert!(m.frame_id("welded").is_ok() && m.frame_id("fixed_to_world").is_ok());
}

#[test]
fn keyframes_effort_limits_and_limits() {
    let m = load(
        r#"<mujoco><worldbody><body name="a"><geom size="0.1"/>
  <joint name="h" range="-90 45" actuatorfrcrange="-30 20"/>
  <body name="b"><geom size="0.1"/><joint name="s" type="slide" range="-0.5 0.5"/>
  <body name="c"><geom size="0.1"/><joint name="free_spin"/></body></body></body></worldbody>
  <actuator>
    <motor joint="h" gear="100" ctrlrange="-1 1"/>
    <general joint="s" gear="2" forcerange="-7 7"/>
    <motor joint="free_spin" ctrlrange="-1 1" ctrllimited="false"/>
  </actuator>
  <keyframe><key name="home" qpos="0.1 0.2 0.3"/><key qpos="1 2 3"/></keyframe>
</mujoco>"#,
    );
    let l: Vec<_> = m.joints().iter().map(|j| j.limits).collect();
    assert!((l[0].lower + FRAC_PI_2).abs() < 1e-15 && (l[0].upper - PI / 4.0).abs() < 1e-15);
    assert_eq!((l[1].lower, l[1].upper), (-0.5, 0.5));
    assert!(l[2].lower.is_infinite());
    // min(actuatorfrcrange 30, motor 100 · 1); 2 · 7; an unlimited motor.
    assert_eq!([l[0].effort, l[1].effort], [30.0, 14.0]);
    assert!(l[2].effort.is_infinite());
    assert_eq!(m.keyframe("home").unwrap(), &[0.1, 0.2, 0.3]);
    assert_eq!(m.keyframe("1").unwrap(), &[1.0, 2.0, 3.0]);
    check(
        &err("<mujoco><worldbody><body><geom size=\"1\"/><joint/></body></worldbody>\n<keyframe><key qpos=\"1 2\"/></keyframe></mujoco>"),
        "bad.xml:2:",
        &["2 qpos values", "1 joints"],
    );
}

#[test]
fn includes_are_relative_to_the_including_file_and_cycles_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    std::fs::create_dir(p.join("sub")).unwrap();
    std::fs::write(
        p.join("main.xml"),
        "<mujoco><worldbody>\n<include file=\"sub/arm.xml\"/></worldbody></mujoco>",
    )
    .unwrap();
    std::fs::write(p.join("sub/arm.xml"), "<mujoco><body name=\"a\"><joint name=\"j\"/><geom size=\"0.1\"/><include file=\"hand.xml\"/></body></mujoco>").unwrap();
    std::fs::write(
        p.join("sub/hand.xml"),
        "<mujoco><body name=\"h\"><joint name=\"k\"/><geom size=\"0.1\"/></body></mujoco>",
    )
    .unwrap();
    let m = load_model(p.join("main.xml").to_str().unwrap()).unwrap();
    assert_eq!(m.joint_names(), vec!["j", "k"]);

    std::fs::write(
        p.join("sub/hand.xml"),
        "<mujoco>\n<include file=\"arm.xml\"/></mujoco>",
    )
    .unwrap();
    let e = load_model(p.join("main.xml").to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(e.contains("hand.xml:2:") && e.contains("cycle"), "{e}");

    std::fs::write(
        p.join("sub/hand.xml"),
        "<mujoco>\n\n<include file=\"gone.xml\"/></mujoco>",
    )
    .unwrap();
    let e = load_model(p.join("main.xml").to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("hand.xml:3:") && e.contains("gone.xml") && e.contains("does not exist"),
        "{e}"
    );
}

#[test]
fn bad_input_is_one_sentence_at_file_and_line() {
    let body = |inner: &str| {
        format!("<mujoco><worldbody>\n<body name=\"b\">\n{inner}\n</body></worldbody></mujoco>")
    };
    check(
        &err("<mujoco><worldbody>\n<body>\n</worldbody>"),
        "bad.xml:",
        &["XML syntax error"],
    );
    check(
        &err(&body("<joint name=\"f\" type=\"free\"/>")),
        "bad.xml:3:",
        &["joint 'f'", "free", "not support"],
    );
    check(
        &err(&body("<joint name=\"f\" type=\"ball\"/>")),
        "bad.xml:3:",
        &["joint 'f'", "ball"],
    );
    check(
        &err(&body("<freejoint name=\"f\"/>")),
        "bad.xml:3:",
        &["freejoint", "floating"],
    );
    check(
        &err(&body("<joint name=\"z\" axis=\"0 0 0\"/>")),
        "bad.xml:3:",
        &["joint 'z'", "zero axis"],
    );
    check(
        &err(&body("<inertial mass=\"0\" diaginertia=\"1 1 1\"/>")),
        "bad.xml:3:",
        &["mass 0", "positive"],
    );
    check(
        &err(&body("<inertial mass=\"-1\" diaginertia=\"1 1 1\"/>")),
        "bad.xml:3:",
        &["mass -1"],
    );
    check(
        &err(&body("<inertial mass=\"1\" diaginertia=\"1 -1 1\"/>")),
        "bad.xml:3:",
        &["not positive definite"],
    );
    check(
        &err(&body("<inertial mass=\"1\" fullinertia=\"1 1 1 2 0 0\"/>")),
        "bad.xml:3:",
        &["not positive definite"],
    );
    check(
        &err(&body(
            "<geom size=\"0.1\" quat=\"1 0 0 0\" euler=\"0 0 1\"/>",
        )),
        "bad.xml:3:",
        &["orientation twice"],
    );
    check(
        &err(&body("<geom size=\"0.1\" quat=\"0 0 0 0\"/>")),
        "bad.xml:3:",
        &["quat", "zero"],
    );
    check(
        &err(&body("<geom type=\"box\" size=\"0.1\"/>")),
        "bad.xml:3:",
        &["needs 3 positive size values"],
    );
    check(
        &err(&body("<joint range=\"1 x\"/>")),
        "bad.xml:3:",
        &["'x' is not a finite number"],
    );
    check(&err("<robotx/>"), "bad.xml:1:", &["<robotx>"]);
}

#[test]
fn ranges_in_the_wrong_unit_are_warnings() {
    let text = "<mujoco><compiler angle=\"radian\"/><worldbody><body>\n<joint name=\"j\" range=\"-180 180\"/><geom size=\"0.1\"/></body></worldbody></mujoco>";
    let m = load(text);
    let f: Vec<String> = m
        .physical_problems()
        .iter()
        .map(|f| f.to_string())
        .collect();
    assert_eq!(f.len(), 1);
    check(&f[0], "t.xml:2:", &["joint 'j'", "looks like degrees"]);
    assert!(load_str(text, "t.xml", &LoadOptions { strict: true }).is_err());
    // MuJoCo's default unit is degrees: ±1.57 looks like radians.
    let m = load("<mujoco><worldbody><body>\n<joint name=\"j\" range=\"-1.57 1.57\"/><geom size=\"0.1\"/></body></worldbody></mujoco>");
    assert!(m.physical_problems()[0]
        .to_string()
        .contains("looks like radians"));
}

#[test]
fn deep_and_long_files_fail_fast_without_overflowing_the_stack() {
    let n = 100_000;
    let text = format!(
        "<mujoco><worldbody>{}{}</worldbody></mujoco>",
        "<body>".repeat(n),
        "</body>".repeat(n)
    );
    let t = std::time::Instant::now();
    let e = err(&text);
    assert!(e.contains("nested more than"), "{e}");
    assert!(t.elapsed().as_secs() < 10);
}

#[test]
fn the_report_lists_what_the_loader_ignored() {
    let text = r#"<mujoco>
  <visual><global offwidth="100"/></visual>
  <worldbody><body name="b"><joint name="j" margin="0.01" damping="1"/><geom size="0.1" rgba="1 0 0 1" friction="1 0 0"/></body></worldbody>
  <tendon><fixed name="t"><joint joint="j" coef="1"/></fixed></tendon>
  <equality><joint joint1="j"/></equality>
  <contact><exclude body1="b" body2="b"/></contact>
  <actuator><position joint="j" kp="10"/></actuator>
</mujoco>"#;
    let (_, r) = parse_mjcf_report(text, "r.xml", &LoadOptions::default()).unwrap();
    let lines: Vec<String> = r.iter().map(|i| i.to_string()).collect();
    assert_eq!(
        lines,
        vec![
            "r.xml:2: <visual> ignored",
            "r.xml:3: <joint name=\"j\">: ignored margin",
            "r.xml:3: <geom>: ignored rgba, friction",
            "r.xml:4: <tendon> ignored",
            "r.xml:5: <equality> ignored",
            "r.xml:6: <contact> ignored",
            "r.xml:7: <position>: ignored kp",
        ]
    );
}

#[test]
fn xml_files_are_mjcf_unless_their_root_is_robot() {
    use screwdyn::io::Format;
    assert_eq!(Format::of_file("arm.XML"), Some(Format::Mjcf));
    let urdf = "<?xml version=\"1.0\"?>\n<robot name=\"r\"><link name=\"a\"/></robot>";
    let m = load_str(urdf, "r.xml", &LoadOptions::default()).unwrap();
    assert_eq!(m.nq(), 0);
}
