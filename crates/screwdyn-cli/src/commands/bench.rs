//! `screwdyn bench MODEL`: per-call time of the core algorithms (JSON keys in docs/cli.md).
//!
//! Protocol (the same as `bench/pinocchio_bench.cpp`, so the two can be compared row by row):
//! 1000 random states are drawn once — `q` uniform within the position limits (an infinite
//! limit is clamped to ±π), `q̇`, `q̈` and `τ` uniform in [−1, 1]; one batch is `--calls` calls
//! cycling through the states, timed as a whole; the figure reported is the median over
//! `--batches` batches (after one untimed warm-up batch), in nanoseconds per call.

use crate::args::{BenchArgs, Format};
use crate::output::resolve;
use crate::CliError;
use screwdyn::dynamics::{aba, coriolis_matrix, crba, forward_dynamics, gravity_torque};
use screwdyn::dynamics::{aba_derivatives, rnea_derivatives};
use screwdyn::dynamics::{mass_matrix_inverse, nonlinear_effects, rnea, ForwardMethod};
use screwdyn::kinematics::{compute_joint_jacobians, forward_kinematics};
use screwdyn::model::SplitMix64;
use screwdyn::{Model, Workspace};
use std::hint::black_box;
use std::time::Instant;

/// Every algorithm `bench` knows, in output order.
const ALGORITHMS: &[&str] = &[
    "fk",
    "jacobians",
    "rnea",
    "crba",
    "aba",
    "gravity",
    "nle",
    "coriolis",
    "minv",
    "forward_crba",
    "rnea_derivatives",
    "aba_derivatives",
];

const STATES: usize = 1000;

struct States {
    q: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    a: Vec<Vec<f64>>,
    tau: Vec<Vec<f64>>,
}

fn random_states(model: &Model) -> States {
    let pi = std::f64::consts::PI;
    // The library's SplitMix64: the same states every run.
    let mut rng = SplitMix64::new(12345);
    let mut s = States {
        q: Vec::new(),
        v: Vec::new(),
        a: Vec::new(),
        tau: Vec::new(),
    };
    for _ in 0..STATES {
        let mut row = |f: &mut dyn FnMut(&mut SplitMix64, usize) -> f64| {
            (0..model.nq()).map(|i| f(&mut rng, i)).collect::<Vec<_>>()
        };
        s.q.push(row(&mut |r, i| {
            let l = &model.joints()[i].limits;
            r.uniform(l.lower.max(-pi), l.upper.min(pi))
        }));
        s.v.push(row(&mut |r, _| r.uniform(-1.0, 1.0)));
        s.a.push(row(&mut |r, _| r.uniform(-1.0, 1.0)));
        s.tau.push(row(&mut |r, _| r.uniform(-1.0, 1.0)));
    }
    s
}

/// Median ns per call of `call(k)` over `batches` batches of `calls` calls.
fn time_it(batches: usize, calls: usize, mut call: impl FnMut(usize)) -> f64 {
    let mut per_call = Vec::with_capacity(batches);
    for b in 0..=batches {
        let t0 = Instant::now();
        for c in 0..calls {
            call(c % STATES);
        }
        let ns = t0.elapsed().as_secs_f64() * 1e9 / calls as f64;
        if b > 0 {
            per_call.push(ns);
        }
    }
    per_call.sort_by(f64::total_cmp);
    let n = per_call.len();
    if n % 2 == 1 {
        per_call[n / 2]
    } else {
        0.5 * (per_call[n / 2 - 1] + per_call[n / 2])
    }
}

/// Times one algorithm by name; `None` for an unknown name.
fn run(model: &Model, s: &States, name: &str, batches: usize, calls: usize) -> Option<f64> {
    let m = model;
    let mut ws = Workspace::new(m);
    let w = &mut ws;
    let (b, c) = (batches, calls);
    // Results are checked once outside the timing (all states are valid), then ignored.
    Some(match name {
        "fk" => time_it(b, c, |k| {
            let _ = black_box(forward_kinematics(m, w, black_box(&s.q[k])));
        }),
        "jacobians" => time_it(b, c, |k| {
            let _ = black_box(compute_joint_jacobians(m, w, black_box(&s.q[k])));
        }),
        "rnea" => time_it(b, c, |k| {
            let _ = black_box(rnea(m, w, black_box(&s.q[k]), &s.v[k], &s.a[k]).is_ok());
        }),
        "crba" => time_it(b, c, |k| {
            let _ = black_box(crba(m, w, black_box(&s.q[k])).is_ok());
        }),
        "aba" => time_it(b, c, |k| {
            let _ = black_box(aba(m, w, black_box(&s.q[k]), &s.v[k], &s.tau[k]).is_ok());
        }),
        "gravity" => time_it(b, c, |k| {
            let _ = black_box(gravity_torque(m, w, black_box(&s.q[k])).is_ok());
        }),
        "nle" => time_it(b, c, |k| {
            let _ = black_box(nonlinear_effects(m, w, black_box(&s.q[k]), &s.v[k]).is_ok());
        }),
        "coriolis" => time_it(b, c, |k| {
            let _ = black_box(coriolis_matrix(m, w, black_box(&s.q[k]), &s.v[k]).is_ok());
        }),
        "minv" => time_it(b, c, |k| {
            let _ = black_box(mass_matrix_inverse(m, w, black_box(&s.q[k])).is_ok());
        }),
        "forward_crba" => time_it(b, c, |k| {
            let r = forward_dynamics(
                m,
                w,
                black_box(&s.q[k]),
                &s.v[k],
                &s.tau[k],
                None,
                ForwardMethod::Crba,
            );
            let _ = black_box(r.is_ok());
        }),
        "rnea_derivatives" => time_it(b, c, |k| {
            let r = rnea_derivatives(m, w, black_box(&s.q[k]), &s.v[k], &s.a[k], None);
            let _ = black_box(r.is_ok());
        }),
        "aba_derivatives" => time_it(b, c, |k| {
            let r = aba_derivatives(m, w, black_box(&s.q[k]), &s.v[k], &s.tau[k], None);
            let _ = black_box(r.is_ok());
        }),
        _ => return None,
    })
}

/// `screwdyn bench MODEL [--algorithms …] [--batches N] [--calls N] [--format json|table]`.
pub fn bench(args: &BenchArgs) -> Result<(), CliError> {
    let model = screwdyn::io::load_model(&args.model)?;
    if args.batches == 0 || args.calls == 0 {
        return Err(CliError::input("--batches and --calls must be at least 1"));
    }
    let names: Vec<&str> = args
        .algorithms
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect();
    if let Some(bad) = names.iter().find(|n| !ALGORITHMS.contains(n)) {
        return Err(CliError::input(format!(
            "--algorithms: unknown algorithm '{bad}' (known: {})",
            ALGORITHMS.join(", ")
        )));
    }
    let states = random_states(&model);
    // One untimed call per algorithm on the first state, to report a bad model cleanly.
    {
        let mut ws = Workspace::new(&model);
        aba(&model, &mut ws, &states.q[0], &states.v[0], &states.tau[0])?;
    }
    let mut results = Vec::new();
    for name in ALGORITHMS.iter().filter(|a| names.contains(a)) {
        let ns = run(&model, &states, name, args.batches, args.calls).expect("known algorithm");
        results.push((*name, ns));
    }
    match resolve(args.format) {
        Format::Json => {
            let ns: serde_json::Map<String, serde_json::Value> = results
                .iter()
                .map(|(n, t)| {
                    (
                        n.to_string(),
                        serde_json::json!((t * 100.0).round() / 100.0),
                    )
                })
                .collect();
            let v = serde_json::json!({"model": model.name(), "nq": model.nq(), "ns_per_call": ns});
            println!("{v}");
        }
        Format::Csv => {
            println!("algorithm,ns_per_call");
            for (n, t) in &results {
                println!("{n},{t:.2}");
            }
        }
        Format::Table => {
            println!(
                "model {} (nq = {}): median of {} batches × {} calls",
                model.name(),
                model.nq(),
                args.batches,
                args.calls
            );
            println!("{:<14} {:>12}", "algorithm", "ns/call");
            for (n, t) in &results {
                println!("{n:<14} {t:>12.1}");
            }
        }
    }
    Ok(())
}
