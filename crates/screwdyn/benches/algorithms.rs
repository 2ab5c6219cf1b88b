//! Criterion benchmarks of the core algorithms (filled in by the dynamics work).
use criterion::{criterion_group, criterion_main, Criterion};

fn fk(c: &mut Criterion) {
    let m = screwdyn::builtin::planar2();
    let mut ws = screwdyn::Workspace::new(&m);
    c.bench_function("fk/planar2", |b| {
        b.iter(|| screwdyn::kinematics::forward_kinematics(&m, &mut ws, &[0.1, 0.2]).unwrap())
    });
}

criterion_group!(benches, fk);
criterion_main!(benches);
