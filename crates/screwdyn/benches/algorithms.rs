//! Criterion benchmarks of the core algorithms on a list of models.
//!
//! `ur5-like` and `panda-like` are built here from the published DH parameters of the UR5
//! (standard DH) and the Franka Panda (modified DH) with approximate link masses; the lead swaps
//! in `screwdyn::builtin::load("ur5")` / `"panda"` once they exist.
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{Matrix3, Vector3, Vector6};
use screwdyn::dynamics::{aba, coriolis_matrix, crba, forward_dynamics, rnea, ForwardMethod};
use screwdyn::kinematics::{compute_joint_jacobians, forward_kinematics};
use screwdyn::model::{JointSpec, ModelBuilder};
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{Model, Workspace};
use std::hint::black_box;
use std::time::Duration;

const Z: Vector6<f64> = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);

fn rx(a: f64) -> Se3 {
    Se3::from_rpy(a, 0.0, 0.0)
}

fn body(m: f64, com: [f64; 3]) -> SpatialInertia {
    let r = 0.05 + 0.02 * m.sqrt();
    SpatialInertia::new(
        m,
        Vector3::from(com),
        Matrix3::identity() * (0.4 * m * r * r),
    )
}

/// UR5, standard DH `(d, a, α)` and link masses from the published parameter table.
fn ur5_like() -> Model {
    let pi2 = std::f64::consts::FRAC_PI_2;
    let dh = [
        (0.089159, 0.0, pi2, 3.7, [0.0, -0.02561, 0.00193]),
        (0.0, -0.425, 0.0, 8.393, [0.2125, 0.0, 0.11336]),
        (0.0, -0.39225, 0.0, 2.33, [0.15, 0.0, 0.0265]),
        (0.10915, 0.0, pi2, 1.219, [0.0, -0.0018, 0.01634]),
        (0.09465, 0.0, -pi2, 1.219, [0.0, 0.0018, 0.01634]),
        (0.0823, 0.0, 0.0, 0.1879, [0.0, 0.0, -0.001159]),
    ];
    let mut b = ModelBuilder::new("ur5-like");
    let mut parent = "base".to_string();
    for (i, (d, a, alpha, m, c)) in dh.iter().enumerate() {
        let home = Se3::from_translation(Vector3::new(0.0, 0.0, *d))
            .compose(&Se3::from_translation(Vector3::new(*a, 0.0, 0.0)))
            .compose(&rx(*alpha));
        let name = format!("link{}", i + 1);
        b.link(
            &name,
            &parent,
            JointSpec::revolute(&format!("j{}", i + 1)).screw_in_parent(Z),
            home,
            body(*m, *c),
        );
        parent = name;
    }
    b.build().unwrap()
}

/// Franka Panda, modified DH `(a, d, α)` and approximate link masses.
fn panda_like() -> Model {
    let pi2 = std::f64::consts::FRAC_PI_2;
    let dh = [
        (0.0, 0.333, 0.0, 4.97),
        (0.0, 0.0, -pi2, 0.646),
        (0.0, 0.316, pi2, 3.228),
        (0.0825, 0.0, pi2, 3.587),
        (-0.0825, 0.384, -pi2, 1.225),
        (0.0, 0.0, pi2, 1.666),
        (0.088, 0.0, pi2, 0.735),
    ];
    let mut b = ModelBuilder::new("panda-like");
    let mut parent = "base".to_string();
    for (i, (a, d, alpha, m)) in dh.iter().enumerate() {
        let home = rx(*alpha)
            .compose(&Se3::from_translation(Vector3::new(*a, 0.0, 0.0)))
            .compose(&Se3::from_translation(Vector3::new(0.0, 0.0, *d)));
        let name = format!("link{}", i + 1);
        b.link(
            &name,
            &parent,
            JointSpec::revolute(&format!("j{}", i + 1)).screw_in_child(Z),
            home,
            body(*m, [0.01, -0.02, 0.03]),
        );
        parent = name;
    }
    b.build().unwrap()
}

fn models() -> Vec<Model> {
    vec![screwdyn::builtin::planar2(), ur5_like(), panda_like()]
}

fn bench_all(c: &mut Criterion) {
    for model in models() {
        let n = model.nq();
        let name = model.name().to_string();
        let mut ws = Workspace::new(&model);
        let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * i as f64).collect();
        let v: Vec<f64> = (0..n).map(|i| 0.5 - 0.2 * i as f64).collect();
        let a: Vec<f64> = (0..n).map(|i| -0.4 + 0.15 * i as f64).collect();
        let mut g = c.benchmark_group("algorithms");
        g.bench_function(BenchmarkId::new("fk", &name), |b| {
            b.iter(|| forward_kinematics(&model, &mut ws, black_box(&q)).unwrap())
        });
        g.bench_function(BenchmarkId::new("jacobians", &name), |b| {
            b.iter(|| compute_joint_jacobians(&model, &mut ws, black_box(&q)).unwrap())
        });
        g.bench_function(BenchmarkId::new("rnea", &name), |b| {
            b.iter(|| {
                rnea(&model, &mut ws, black_box(&q), &v, &a).unwrap();
            })
        });
        g.bench_function(BenchmarkId::new("crba", &name), |b| {
            b.iter(|| {
                crba(&model, &mut ws, black_box(&q)).unwrap();
            })
        });
        g.bench_function(BenchmarkId::new("aba", &name), |b| {
            b.iter(|| {
                aba(&model, &mut ws, black_box(&q), &v, &a).unwrap();
            })
        });
        g.bench_function(BenchmarkId::new("coriolis", &name), |b| {
            b.iter(|| {
                coriolis_matrix(&model, &mut ws, black_box(&q), &v).unwrap();
            })
        });
        g.bench_function(BenchmarkId::new("forward_crba", &name), |b| {
            b.iter(|| {
                forward_dynamics(&model, &mut ws, black_box(&q), &v, &a, ForwardMethod::Crba)
                    .unwrap();
            })
        });
        g.finish();
    }
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(100))
        .measurement_time(Duration::from_millis(300))
}

criterion_group! {
    name = benches;
    config = config();
    targets = bench_all
}
criterion_main!(benches);
