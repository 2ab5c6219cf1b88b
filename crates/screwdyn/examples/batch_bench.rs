//! Per-state time of the batch kernels against a loop over the per-call functions, one thread:
//! `cargo run --release --example batch_bench -- [robot] [states] [rnea|crba|aba] [batch]`
//! (BENCHMARKS.md, "Batches"); `batch` times the batch alone, for profiling.

use screwdyn::batch::{self, BatchWorkspace, Rows};
use screwdyn::{dynamics, Workspace};
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let robot = args.next().unwrap_or_else(|| "ur5".into());
    let states: usize = args
        .next()
        .map_or(100_000, |s| s.parse().expect("a number of states"));
    let m = screwdyn::io::load_model(&if robot.contains('.') {
        robot.clone()
    } else {
        format!("builtin:{robot}")
    })
    .expect("a built-in robot");
    let nq = m.nq();
    // Deterministic pseudo-random states (a Weyl sequence) in ±3 rad, ±1 rad/s, ±1 rad/s².
    let mut x = 0.0_f64;
    let mut next = |scale: f64| {
        x = (x + 0.618_033_988_749_894_9) % 1.0;
        (2.0 * x - 1.0) * scale
    };
    let q: Vec<f64> = (0..states * nq).map(|_| next(3.0)).collect();
    let v: Vec<f64> = (0..states * nq).map(|_| next(1.0)).collect();
    let a: Vec<f64> = (0..states * nq).map(|_| next(1.0)).collect();
    let mut out = vec![0.0; states * nq * nq];
    let mut bws = BatchWorkspace::new(&m);
    let mut ws = Workspace::new(&m);
    println!("{robot}, {states} states, ns per state (median of 5), one thread");
    println!("| algorithm | per-call loop | batch | ratio |");
    println!("| --- | ---: | ---: | ---: |");
    let only = args.next();
    // A fourth argument `batch` times the batch alone (for profiling it).
    let batch_only = args.next().as_deref() == Some("batch");
    for name in ["rnea", "crba", "aba"] {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let (mut t_loop, mut t_batch) = (Vec::new(), Vec::new());
        for _ in 0..5 {
            let t0 = Instant::now();
            for k in (0..states).take(if batch_only { 0 } else { states }) {
                let r = k * nq..(k + 1) * nq;
                match name {
                    "rnea" => {
                        let t = dynamics::rnea(
                            &m,
                            &mut ws,
                            &q[r.clone()],
                            &v[r.clone()],
                            &a[r.clone()],
                        )
                        .unwrap();
                        out[r].copy_from_slice(t.as_slice());
                    }
                    "crba" => {
                        let mm = dynamics::crba(&m, &mut ws, &q[r]).unwrap();
                        out[k * nq * nq..(k + 1) * nq * nq].copy_from_slice(mm.as_slice());
                    }
                    _ => {
                        let t =
                            dynamics::aba(&m, &mut ws, &q[r.clone()], &v[r.clone()], &a[r.clone()])
                                .unwrap();
                        out[r].copy_from_slice(t.as_slice());
                    }
                }
            }
            t_loop.push(t0.elapsed().as_secs_f64());
            let t0 = Instant::now();
            let (qs, vs, as_) = (Rows::Stacked(&q), Rows::Stacked(&v), Rows::Stacked(&a));
            match name {
                "rnea" => batch::rnea(&m, &mut bws, qs, vs, as_, &mut out[..states * nq]),
                "crba" => batch::crba(&m, &mut bws, qs, &mut out),
                _ => batch::aba(&m, &mut bws, qs, vs, as_, &mut out[..states * nq]),
            }
            .unwrap();
            t_batch.push(t0.elapsed().as_secs_f64());
        }
        let med = |t: &mut Vec<f64>| {
            t.sort_by(f64::total_cmp);
            t[t.len() / 2] * 1e9 / states as f64
        };
        let (l, b) = (med(&mut t_loop), med(&mut t_batch));
        if batch_only {
            println!("| {name} | – | {b:.0} | – |");
        } else {
            println!("| {name} | {l:.0} | {b:.0} | {:.2}× |", l / b);
        }
    }
}
