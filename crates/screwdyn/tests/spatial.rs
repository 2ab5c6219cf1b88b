//! Spatial algebra against independent sources: matrix exponential series, group identities,
//! power invariance, and the seed 003 box-inertia example.

use nalgebra::{Matrix3, Matrix4, Vector3, Vector6};
use rand::{rngs::StdRng, Rng, SeedableRng};
use screwdyn::spatial::*;
use std::f64::consts::PI;

fn rand_vec6(rng: &mut StdRng, s: f64) -> Vector6<f64> {
    Vector6::from_fn(|_, _| rng.gen_range(-s..s))
}

fn rand_unit(rng: &mut StdRng) -> Vector3<f64> {
    loop {
        let v = Vector3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
        if v.norm() > 0.1 {
            return v.normalize();
        }
    }
}

fn rand_pose(rng: &mut StdRng) -> Se3 {
    Se3::exp(&rand_vec6(rng, 2.0))
}

/// The matrix exponential by its power series, an implementation independent of Rodrigues.
fn expm_series(a: &Matrix4<f64>) -> Matrix4<f64> {
    let mut sum = Matrix4::identity();
    let mut term = Matrix4::identity();
    for k in 1..60 {
        term = term * a / k as f64;
        sum += term;
    }
    sum
}

#[test]
fn se3_exp_equals_matrix_exponential_series() {
    let mut rng = StdRng::seed_from_u64(1);
    for _ in 0..200 {
        let xi = rand_vec6(&mut rng, 3.0);
        let h = Se3::exp(&xi).to_matrix();
        assert!((h - expm_series(&hat6(&xi))).amax() < 1e-11, "{xi}");
    }
    // Tiny twists, where the closed form switches to its series.
    for k in 1..12 {
        let xi = rand_vec6(&mut rng, 1.0) * 10f64.powi(-k);
        assert!((Se3::exp(&xi).to_matrix() - expm_series(&hat6(&xi))).amax() < 1e-15);
    }
}

#[test]
fn so3_log_exp_round_trip_including_near_zero_and_pi() {
    let mut rng = StdRng::seed_from_u64(2);
    let mut angles = vec![0.0, 1e-12, 1e-8, 1e-4, 0.05, 0.1, 0.5, 1.0, 2.0, 3.0];
    angles.extend([PI - 1e-3, PI - 1e-6, PI - 1e-9, PI]);
    for &t in &angles {
        for _ in 0..50 {
            let n = rand_unit(&mut rng);
            let w = n * t;
            let r = exp_so3(&w);
            let back = log_so3(&r);
            // At exactly π the axis sign is ambiguous: compare rotations, and the angle.
            assert!((exp_so3(&back) - r).amax() < 1e-12, "t = {t}");
            assert!((back.norm() - t).abs() < 1e-9, "t = {t}: {}", back.norm());
            if t < PI - 1e-6 {
                assert!((back - w).norm() < 1e-9 * t.max(1e-3), "t = {t}");
            }
        }
    }
}

#[test]
fn se3_log_exp_round_trip_random_screws_near_zero_and_pi() {
    let mut rng = StdRng::seed_from_u64(3);
    for &t in &[0.0, 1e-10, 1e-5, 0.01, 0.7, 2.5, PI - 1e-4, PI - 1e-8] {
        for _ in 0..50 {
            let s = twist(
                rand_unit(&mut rng),
                Vector3::from_fn(|_, _| rng.gen_range(-2.0..2.0)),
            );
            let xi = s * t;
            let h = Se3::exp(&xi);
            let back = h.log();
            assert!(
                (Se3::exp(&back).to_matrix() - h.to_matrix()).amax() < 1e-10,
                "t = {t}"
            );
            assert!(
                (back - xi).norm() < 1e-7 * (1.0 + xi.norm()),
                "t = {t}: {back} vs {xi}"
            );
        }
    }
    // Pure translations (ω = 0).
    let xi = Vector6::new(0.0, 0.0, 0.0, 1.0, -2.0, 3.0);
    assert!((Se3::exp(&xi).log() - xi).norm() < 1e-15);
}

#[test]
fn adjoint_is_a_homomorphism_and_operators_match_matrices() {
    let mut rng = StdRng::seed_from_u64(4);
    for _ in 0..100 {
        let (h1, h2) = (rand_pose(&mut rng), rand_pose(&mut rng));
        let lhs = (h1 * h2).adjoint_matrix();
        let rhs = h1.adjoint_matrix() * h2.adjoint_matrix();
        assert!((lhs - rhs).amax() < 1e-12);
        assert!(
            (h1.inverse().adjoint_matrix() - h1.adjoint_matrix().try_inverse().unwrap()).amax()
                < 1e-10
        );
        let v = rand_vec6(&mut rng, 1.0);
        let ad = h1.adjoint_matrix();
        assert!((h1.act_twist(&v) - ad * v).norm() < 1e-12);
        assert!((h1.inv_act_twist(&v) - h1.inverse().adjoint_matrix() * v).norm() < 1e-12);
        assert!((h1.act_transpose_wrench(&v) - ad.transpose() * v).norm() < 1e-12);
        assert!(
            (h1.inv_act_transpose_wrench(&v) - h1.inverse().adjoint_matrix().transpose() * v)
                .norm()
                < 1e-12
        );
        // Ad_H [ξ] = H [ξ] H⁻¹ (the definition of the adjoint map).
        let conj = h1.to_matrix() * hat6(&v) * h1.inverse().to_matrix();
        assert!((vee6(&conj) - h1.act_twist(&v)).norm() < 1e-12);
    }
}

#[test]
fn power_is_invariant_under_change_of_frame() {
    let mut rng = StdRng::seed_from_u64(5);
    for _ in 0..100 {
        let h = rand_pose(&mut rng);
        let (v, w) = (rand_vec6(&mut rng, 1.0), rand_vec6(&mut rng, 1.0));
        // (Ad_Hᵀ W)ᵀ V = Wᵀ (Ad_H V)
        assert!((h.act_transpose_wrench(&w).dot(&v) - w.dot(&h.act_twist(&v))).abs() < 1e-12);
        assert!(
            (h.inv_act_transpose_wrench(&w).dot(&v) - w.dot(&h.inv_act_twist(&v))).abs() < 1e-12
        );
    }
}

#[test]
fn ad_properties() {
    let mut rng = StdRng::seed_from_u64(6);
    for _ in 0..100 {
        let (v, x, y) = (
            rand_vec6(&mut rng, 1.0),
            rand_vec6(&mut rng, 1.0),
            rand_vec6(&mut rng, 1.0),
        );
        assert!(ad(&v, &v).norm() < 1e-15);
        // ad_V X is the matrix commutator [V̂, X̂] of se(3).
        let comm = hat6(&v) * hat6(&x) - hat6(&x) * hat6(&v);
        assert!((vee6(&comm) - ad(&v, &x)).norm() < 1e-13);
        assert!((ad_matrix(&v) * x - ad(&v, &x)).norm() < 1e-13);
        assert!((ad_matrix(&v).transpose() * y - ad_transpose(&v, &y)).norm() < 1e-13);
        // d/dt Ad_{exp(tV)} X at t = 0 is ad_V X.
        let h = 1e-6;
        let fd = (Se3::exp(&(v * h)).act_twist(&x) - Se3::exp(&(v * -h)).act_twist(&x)) / (2.0 * h);
        assert!((fd - ad(&v, &x)).norm() < 1e-8);
    }
}

#[test]
fn rpy_round_trip_and_urdf_convention() {
    let h = Se3::from_rpy(0.1_f64, 0.2, 0.3);
    let (r, p, y) = h.rpy();
    assert!((r - 0.1).abs() < 1e-14 && (p - 0.2).abs() < 1e-14 && (y - 0.3).abs() < 1e-14);
    // URDF: yaw about z applied last: Rz(π/2) maps x to y.
    let h = Se3::from_rpy(0.0, 0.0, PI / 2.0);
    assert!((h.rotation * Vector3::x() - Vector3::y()).norm() < 1e-15);
}

/// Seed 003: a uniform box w × l × h (x, y, z) with a frame at one corner has
/// I_xx = m/3 (l² + h²), I_xy = −m/4 w l ...; about the CoM, m/12 (l² + h²), ... and no products.
#[test]
fn seed003_box_inertia_about_corner_and_com_by_change_of_point() {
    let (m, w, l, h): (f64, f64, f64, f64) = (2.5, 0.3, 0.5, 0.7);
    let corner = Matrix3::new(
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
    let com_tensor = Matrix3::from_diagonal(&Vector3::new(
        m / 12.0 * (l * l + h * h),
        m / 12.0 * (w * w + h * h),
        m / 12.0 * (w * w + l * l),
    ));
    let pc = Vector3::new(w / 2.0, l / 2.0, h / 2.0);
    // Spatial inertia at a CoM frame is diag(I_c, m·1); the corner frame sees the CoM frame at pc:
    // 𝔍^{corner} = Ad_{H_corner^com}ᵀ 𝔍^{com} Ad_{H_corner^com}.
    let j_com = SpatialInertia::new(m, Vector3::zeros(), com_tensor).matrix();
    let h_com_in_corner = Se3::from_translation(pc);
    let ad = h_com_in_corner.inverse().adjoint_matrix();
    let j_corner = ad.transpose() * j_com * ad;
    let about_corner = j_corner.fixed_view::<3, 3>(0, 0).into_owned();
    assert!(
        (about_corner - corner).amax() < 1e-14,
        "{about_corner} vs {corner}"
    );
    // Backwards (seed 003: ᶜI = ᴬI − m[...]) through the structured form.
    let back = SpatialInertia::from_inertia_about_origin(m, pc, corner);
    assert!((back.inertia_com - com_tensor).amax() < 1e-14);
    // And the structured change of frame agrees with the matrix one.
    let moved = SpatialInertia::new(m, Vector3::zeros(), com_tensor).transformed(&h_com_in_corner);
    assert!((moved.matrix() - j_corner).amax() < 1e-14);
}

#[test]
fn spatial_inertia_apply_and_energy_match_matrix() {
    let mut rng = StdRng::seed_from_u64(7);
    for _ in 0..50 {
        // Rotational inertia of four point masses about their centre: physical by construction.
        let mut ic = Matrix3::zeros();
        for _ in 0..4 {
            let r = Vector3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            ic += parallel_axis_term(rng.gen_range(0.1..2.0), &r);
        }
        let i = SpatialInertia::new(
            rng.gen_range(0.1..5.0),
            Vector3::from_fn(|_, _| rng.gen_range(-1.0..1.0)),
            ic,
        );
        let v = rand_vec6(&mut rng, 2.0);
        assert!((i.apply(&v) - i.matrix() * v).norm() < 1e-12);
        assert!(i.check_physical().is_ok());
        let back = SpatialInertia::from_matrix(&i.matrix()).unwrap();
        assert!((back.matrix() - i.matrix()).amax() < 1e-12);
        // Combining with itself doubles the matrix.
        assert!((i.combined(&i).matrix() - i.matrix() * 2.0).amax() < 1e-12);
    }
    // Non-physical inertias are caught: triangle inequality and negative moments.
    let bad = SpatialInertia::new(
        1.0,
        Vector3::zeros(),
        Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 3.0)),
    );
    assert!(bad
        .check_physical()
        .unwrap_err()
        .to_string()
        .contains("triangle"));
    let neg = SpatialInertia::new(
        1.0,
        Vector3::zeros(),
        Matrix3::from_diagonal(&Vector3::new(-1.0, 1.0, 1.0)),
    );
    assert!(neg
        .check_physical()
        .unwrap_err()
        .to_string()
        .contains("positive"));
}
