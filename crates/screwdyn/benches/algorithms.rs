//! Criterion benchmarks of the core algorithms on the built-in robots (`planar2`, and the UR5
//! and Franka Panda of `models/`). The side-by-side comparison with Pinocchio on the
//! example-robot-data URDFs is `bench/compare.sh` (see BENCHMARKS.md).
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use screwdyn::dynamics::{aba, coriolis_matrix, crba, forward_dynamics, rnea, ForwardMethod};
use screwdyn::kinematics::{compute_joint_jacobians, forward_kinematics};
use screwdyn::{Model, Workspace};
use std::hint::black_box;
use std::time::Duration;

fn models() -> Vec<Model> {
    vec![
        screwdyn::builtin::planar2(),
        screwdyn::builtin::load("ur5").expect("built-in ur5"),
        screwdyn::builtin::load("panda").expect("built-in panda"),
    ]
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
                forward_dynamics(
                    &model,
                    &mut ws,
                    black_box(&q),
                    &v,
                    &a,
                    None,
                    ForwardMethod::Crba,
                )
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
