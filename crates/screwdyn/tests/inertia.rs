//! Inertia helpers against seed 003's formulas and direct numerical integration of
//! `I = ∫ (|r|² 1 − r rᵀ) ρ dV` (midpoint rule).

use nalgebra::{Matrix3, Vector3};
use screwdyn::inertia::*;
use screwdyn::spatial::{exp_so3, SpatialInertia};

/// Midpoint-rule integral of the inertia tensor of the points of `[lo, hi]` where `inside`,
/// about the origin, for total mass `m`.
fn integrate(
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    inside: impl Fn(&Vector3<f64>) -> bool,
    m: f64,
) -> Matrix3<f64> {
    let n = 60;
    let d = (hi - lo) / n as f64;
    let (mut sum, mut count) = (Matrix3::zeros(), 0usize);
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let p = lo
                    + Vector3::new(
                        (i as f64 + 0.5) * d.x,
                        (j as f64 + 0.5) * d.y,
                        (k as f64 + 0.5) * d.z,
                    );
                if inside(&p) {
                    sum += Matrix3::identity() * p.dot(&p) - p * p.transpose();
                    count += 1;
                }
            }
        }
    }
    sum * (m / count as f64)
}

#[test]
fn box_about_corner_and_com_match_integration_and_seed_003() {
    let (m, w, l, h): (f64, f64, f64, f64) = (3.0, 0.4, 0.3, 0.2);
    let corner = box_about_corner(m, w, l, h).unwrap();
    let num = integrate(Vector3::zeros(), Vector3::new(w, l, h), |_| true, m);
    assert!(
        (corner - num).amax() < 1e-4 * corner.amax(),
        "{corner} vs {num}"
    );
    let com = cuboid(m, w, l, h).unwrap();
    let half = Vector3::new(w, l, h) / 2.0;
    let num = integrate(-half, half, |_| true, m);
    assert!((com - num).amax() < 1e-3 * com.amax());
    // Parallel-axis theorem both ways (seed 003).
    assert!((parallel_axis(&com, m, &half) - corner).amax() < 1e-15);
    assert!((parallel_axis_to_com(&corner, m, &half) - com).amax() < 1e-15);
}

#[test]
fn cylinders_spheres_and_rods_match_integration() {
    let (m, r, h): (f64, f64, f64) = (2.0, 0.3, 0.5);
    let cyl = solid_cylinder(m, r, h).unwrap();
    let num = integrate(
        Vector3::new(-r, -r, -h / 2.0),
        Vector3::new(r, r, h / 2.0),
        |p| p.x * p.x + p.y * p.y <= r * r,
        m,
    );
    assert!((cyl - num).amax() < 3e-3 * cyl.amax(), "{cyl} vs {num}");
    let ri = 0.2;
    let tube = hollow_cylinder(m, ri, r, h).unwrap();
    let num = integrate(
        Vector3::new(-r, -r, -h / 2.0),
        Vector3::new(r, r, h / 2.0),
        |p| {
            let q = p.x * p.x + p.y * p.y;
            q <= r * r && q >= ri * ri
        },
        m,
    );
    assert!((tube - num).amax() < 3e-3 * tube.amax(), "{tube} vs {num}");
    // Seed 003 tutorial: the cylinder about one far end (parallel axis by h/2 along z).
    let end = parallel_axis(&cyl, m, &Vector3::new(0.0, 0.0, h / 2.0));
    assert!((end[(0, 0)] - (m * r * r / 4.0 + m * h * h / 3.0)).abs() < 1e-15);
    let s = solid_sphere(m, r).unwrap();
    let num = integrate(
        Vector3::repeat(-r),
        Vector3::repeat(r),
        |p| p.norm() <= r,
        m,
    );
    assert!((s - num).amax() < 3e-3 * s.amax());
    // A thin shell is the derivative of the solid ball's r⁵ scaling: I = 2/3 m r².
    assert!((hollow_sphere(m, r).unwrap()[(2, 2)] - 2.0 / 3.0 * m * r * r).abs() < 1e-15);
    // A thin rod is the limit of a cylinder of vanishing radius.
    let rod = thin_rod(m, h).unwrap();
    assert!((rod - solid_cylinder(m, 0.0, h).unwrap()).amax() < 1e-15);
}

#[test]
fn rotation_combination_and_consistency() {
    let (m, w, l, h): (f64, f64, f64, f64) = (1.5, 0.4, 0.3, 0.2);
    let i = cuboid(m, w, l, h).unwrap();
    let r = exp_so3(&Vector3::new(0.3, -0.4, 0.8));
    let j = rotate(&i, &r);
    // Same principal moments, and the integral of the rotated box agrees.
    let mut a: Vec<f64> = i.symmetric_eigenvalues().as_slice().to_vec();
    let mut b: Vec<f64> = j.symmetric_eigenvalues().as_slice().to_vec();
    a.sort_by(|x, y| x.partial_cmp(y).unwrap());
    b.sort_by(|x, y| x.partial_cmp(y).unwrap());
    for k in 0..3 {
        assert!((a[k] - b[k]).abs() < 1e-14);
    }
    let half = Vector3::new(w, l, h) / 2.0;
    let ext = half.norm();
    let num = integrate(
        Vector3::repeat(-ext),
        Vector3::repeat(ext),
        |p| {
            let q = r.transpose() * p;
            q.x.abs() <= half.x && q.y.abs() <= half.y && q.z.abs() <= half.z
        },
        m,
    );
    assert!((j - num).amax() < 5e-3 * j.amax(), "{j} vs {num}");
    // Two half boxes side by side make the whole box.
    let left = SpatialInertia::new(
        m / 2.0,
        Vector3::new(-w / 4.0, 0.0, 0.0),
        cuboid(m / 2.0, w / 2.0, l, h).unwrap(),
    );
    let right = SpatialInertia::new(
        m / 2.0,
        Vector3::new(w / 4.0, 0.0, 0.0),
        cuboid(m / 2.0, w / 2.0, l, h).unwrap(),
    );
    let whole = combine(&[left, right]);
    assert!((whole.inertia_com - i).amax() < 1e-15 && whole.com.norm() < 1e-15 && whole.mass == m);
    assert!(whole.check_physical().is_ok());
    let bad = SpatialInertia::new(-1.0, Vector3::zeros(), Matrix3::identity());
    assert!(bad
        .check_physical()
        .unwrap_err()
        .to_string()
        .contains("negative mass"));
    assert!(cuboid(1.0, -1.0, 1.0, 1.0)
        .unwrap_err()
        .to_string()
        .contains("width of the box"));
    assert!(hollow_cylinder(1.0, 0.5, 0.2, 1.0).is_err());
}
