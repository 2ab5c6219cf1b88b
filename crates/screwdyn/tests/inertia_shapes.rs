//! Shape primitives (issue 14): seed 003's box about its corner and cylinder about its end, and
//! shapes in the native TOML format.

use nalgebra::{Matrix3, Vector3};
use screwdyn::inertia::{box_about_corner, solid_cylinder, Shape};
use screwdyn::spatial::Se3;

#[test]
fn seed_003_box_about_its_corner() {
    let (m, w, l, h) = (2.0, 0.3, 0.2, 0.1);
    let i = Shape::parse("box", &[w, l, h])
        .unwrap()
        .inertia_about(
            m,
            &Vector3::new(-w / 2.0, -l / 2.0, -h / 2.0),
            &Matrix3::identity(),
        )
        .unwrap();
    // Seed 003: [m/3 (l² + h²), −m/4 w l, −m/4 h w; …; …, m/3 (w² + l²)].
    let seed = Matrix3::new(
        m / 3.0 * (l * l + h * h),
        -m / 4.0 * w * l,
        -m / 4.0 * h * w,
        -m / 4.0 * w * l,
        m / 3.0 * (w * w + h * h),
        -m / 4.0 * h * l,
        -m / 4.0 * h * w,
        -m / 4.0 * h * l,
        m / 3.0 * (w * w + l * l),
    );
    assert!((i - seed).amax() < 1e-15);
    assert!((i - box_about_corner(m, w, l, h).unwrap()).amax() < 1e-15);
}

#[test]
fn seed_003_cylinder_about_its_end() {
    // Tutorial question 1: about the CoM Ixx = Iyy = m(3r² + h²)/12, Izz = m r²/2; about one end
    // (along the axis) Ixx = Iyy = m(3r² + 4h²)/12 = m r²/4 + m h²/3.
    let (m, r, h) = (3.0, 0.2, 1.5);
    let c = Shape::Cylinder { r, h };
    let com = c.inertia_com(m).unwrap();
    assert!((com[(0, 0)] - m * (3.0 * r * r + h * h) / 12.0).abs() < 1e-15);
    assert!((com[(2, 2)] - m * r * r / 2.0).abs() < 1e-15);
    let end = c
        .inertia_about(m, &Vector3::new(0.0, 0.0, -h / 2.0), &Matrix3::identity())
        .unwrap();
    assert!((end[(0, 0)] - (m * r * r / 4.0 + m * h * h / 3.0)).abs() < 1e-14);
    assert!((end[(1, 1)] - end[(0, 0)]).abs() < 1e-15 && (end[(2, 2)] - com[(2, 2)]).abs() < 1e-15);
    // Turned a quarter turn about x, the axis lies along y: Iyy becomes the axial m r²/2.
    let rot = Se3::from_rpy(std::f64::consts::FRAC_PI_2, 0.0, 0.0).rotation;
    let turned = c.inertia_about(m, &Vector3::zeros(), &rot).unwrap();
    assert!((turned[(1, 1)] - m * r * r / 2.0).abs() < 1e-15);
}

#[test]
fn shapes_in_native_toml() {
    let text = r#"
format = "screwdyn"
name = "shaped"
[[body]]
name = "link1"
parent = "base"
joint = "j1"
type = "revolute"
home = { xyz = [0.0, 0.0, 0.1] }
screw_in_parent = [0, 0, 1, 0, 0, 0]
mass = 2.0
com = [0.0, 0.0, 0.25]
shape = { type = "cylinder", size = [0.05, 0.5] }
"#;
    let m = screwdyn::io::load_str(text, "shaped.toml", &Default::default()).unwrap();
    let i = m.bodies()[0].inertia.inertia_com;
    assert!((i - solid_cylinder(2.0, 0.05, 0.5).unwrap()).amax() < 1e-15);
    let both = text.replace("mass = 2.0", "mass = 2.0\ninertia = [1, 0, 0, 1, 0, 1]");
    let e = screwdyn::io::load_str(&both, "shaped.toml", &Default::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("both a shape and an inertia") && e.contains("shaped.toml"),
        "{e}"
    );
    let bad = text.replace("size = [0.05, 0.5]", "size = [0.05]");
    let e = screwdyn::io::load_str(&bad, "shaped.toml", &Default::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("cylinder takes 2 sizes"), "{e}");
}
