//! The inverse-kinematics benchmark's protocol in Rust, for one robot file: verified success
//! rate, time per solve on one thread, the failures, and a batch on 1 and 2 threads.
//!
//! ```sh
//! cargo run --release -p screwdyn --example ik_protocol -- ROBOT FRAME [POSES] [--failures]
//! ```
//!
//! `POSES` (default 2000) configurations are drawn uniformly within the limits (clipped to
//! ±π) of the joints that move `FRAME`, the other joints at 0 clamped into their limits; their
//! frame poses are the targets, each solved from that start. A solve counts as verified only
//! when an independent forward kinematics of the answer here is within 1e-6 m and 1e-6 rad and
//! every joint within its limits; a success the library reports that this check refuses
//! stops the program. `--failures` lists each failed target (its index, the library's reason,
//! the errors and the true configuration).

use screwdyn::kinematics::ik::{default_start, IkOptions, IkSolver, IkTask, IkWorkspace};
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::model::SplitMix64;
use screwdyn::spatial::{log_so3, Se3};
use screwdyn::Workspace;
use std::time::Instant;

/// The median of `rounds` timings of `f`, in seconds.
fn median_of(rounds: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..rounds)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[rounds / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let failures = args.iter().any(|a| a == "--failures");
    let plain: Vec<&String> = args.iter().filter(|a| !a.starts_with("--")).collect();
    let (Some(robot), Some(frame_name)) = (plain.first(), plain.get(1)) else {
        eprintln!("usage: ik_protocol ROBOT FRAME [POSES] [--failures]");
        std::process::exit(2);
    };
    let poses: usize = plain
        .get(2)
        .map_or(2000, |s| s.parse().expect("POSES must be a whole number"));
    let model = screwdyn::io::load_model(robot).expect("a robot file or builtin:NAME");
    let frame = model.frame_id(frame_name).expect("a frame of the robot");
    let solver = IkSolver::new(&model, &[IkTask::pose(frame)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut kin = Workspace::new(&model);
    let n = model.nq();
    let limits: Vec<(f64, f64)> = model
        .joints()
        .iter()
        .map(|j| (j.limits.lower, j.limits.upper))
        .collect();
    let q0 = default_start(&model);
    let mut rng = SplitMix64::new(2026);
    let mut truths = Vec::with_capacity(poses);
    let targets: Vec<Se3> = (0..poses)
        .map(|_| {
            let mut truth = q0.clone();
            for &j in solver.moving_joints() {
                let (lo, hi) = limits[j];
                truth[j] = rng.uniform(lo.max(-std::f64::consts::PI), hi.min(std::f64::consts::PI));
            }
            forward_kinematics(&model, &mut kin, &truth).unwrap();
            truths.push(truth);
            frame_pose(&model, &kin, frame).unwrap()
        })
        .collect();
    let mut q = vec![0.0; n];
    let mut times = Vec::with_capacity(poses);
    let (mut verified, mut iterations, mut restarts) = (0, 0, 0);
    for (k, target) in targets.iter().enumerate() {
        let start = Instant::now();
        let result = solver.solve(&mut ws, &[*target], &q0, &mut q).unwrap();
        times.push(start.elapsed().as_secs_f64() * 1e6);
        iterations += result.iterations;
        restarts += result.restarts;
        forward_kinematics(&model, &mut kin, &q).unwrap();
        let pose = frame_pose(&model, &kin, frame).unwrap();
        let position = (pose.translation - target.translation).norm();
        let angle = log_so3(&(pose.rotation.transpose() * target.rotation)).norm();
        let within = q
            .iter()
            .zip(&limits)
            .all(|(v, (lo, hi))| lo <= v && v <= hi);
        let confirmed = position <= 1e-6 && angle <= 1e-6 && within;
        assert!(
            !result.success || confirmed,
            "a false success on target {k}"
        );
        verified += usize::from(confirmed);
        if failures && !confirmed {
            println!(
                "target {k}: {:?}, {:.2e} m, {:.2e} rad, {} restarts; true q {:.3?}; found {:.3?}",
                result.failure, position, angle, result.restarts, truths[k], q
            );
        }
    }
    times.sort_by(f64::total_cmp);
    let mean = times.iter().sum::<f64>() / poses as f64;
    println!(
        "{frame_name}: {:.2} % verified, mean {mean:.1} µs, median {:.1}, p99 {:.1}; {:.2} iterations, {:.3} restarts per solve",
        100.0 * verified as f64 / poses as f64,
        times[poses / 2],
        times[(poses * 99) / 100],
        iterations as f64 / poses as f64,
        restarts as f64 / poses as f64,
    );
    let mut out = vec![0.0; poses * n];
    let mut batch = |threads: usize| {
        median_of(5, || {
            solver
                .solve_batch(&targets, &q0, &mut out, threads)
                .unwrap();
        })
    };
    let (one, two) = (batch(1), batch(2));
    println!(
        "batch: {:.2} µs per target on 1 thread, {:.2} on 2 ({:.2}×)",
        one * 1e6 / poses as f64,
        two * 1e6 / poses as f64,
        one / two
    );
    if solver.closed_form().is_some() {
        let all = median_of(5, || {
            for target in &targets {
                std::hint::black_box(solver.solve_all(&mut ws, target, &q0).unwrap());
            }
        });
        println!(
            "every closed-form solution (refined, checked): {:.2} µs per target",
            all * 1e6 / poses as f64
        );
    }
}
