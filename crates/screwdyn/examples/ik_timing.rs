//! Numerical inverse kinematics on random reachable poses: verified success rate and time per
//! solve, one thread.
//!
//! ```sh
//! cargo run --release -p screwdyn --example ik_timing [-- POSES]
//! ```
//!
//! For each arm, `POSES` (default 2000) configurations are drawn uniformly within the joint
//! limits, their tool pose computed by forward kinematics, and each pose solved from the
//! middle of the limits. A solve counts as a success only when the library's final check says
//! so *and* an independent forward kinematics of the answer here is within 1e-6 m and 1e-6 rad
//! with every joint within its limits.

use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::spatial::log_so3;
use screwdyn::{builtin, Workspace};
use std::time::Instant;

/// SplitMix64, for the random configurations.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

fn main() {
    let poses: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("POSES must be a whole number"))
        .unwrap_or(2000);
    println!(
        "arm     frame         poses  verified   mean µs  median µs  p99 µs  iterations  restarts"
    );
    for (name, frame) in [("ur5", "tool0"), ("panda", "panda_link8")] {
        let model = builtin::load(name).unwrap();
        let frame_id = model
            .frame_id(frame)
            .unwrap_or_else(|_| model.body_frame(model.nbodies() - 1).unwrap());
        let solver =
            IkSolver::new(&model, &[IkTask::pose(frame_id)], IkOptions::default()).unwrap();
        let mut ws = IkWorkspace::new(&solver);
        let mut kin = Workspace::new(&model);
        let mut rng = Rng(7);
        let n = model.nq();
        let limits: Vec<(f64, f64)> = model
            .joints()
            .iter()
            .map(|j| (j.limits.lower, j.limits.upper))
            .collect();
        let q0: Vec<f64> = limits.iter().map(|(lo, hi)| 0.5 * (lo + hi)).collect();
        let mut q = vec![0.0; n];
        let mut truth = vec![0.0; n];
        let mut times = Vec::with_capacity(poses);
        let (mut verified, mut iterations, mut restarts) = (0, 0, 0);
        for _ in 0..poses {
            for (t, (lo, hi)) in truth.iter_mut().zip(&limits) {
                *t = rng.uniform(*lo, *hi);
            }
            forward_kinematics(&model, &mut kin, &truth).unwrap();
            let target = frame_pose(&model, &kin, frame_id).unwrap();
            let start = Instant::now();
            let result = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
            times.push(start.elapsed().as_secs_f64() * 1e6);
            iterations += result.iterations;
            restarts += result.restarts;
            forward_kinematics(&model, &mut kin, &q).unwrap();
            let pose = frame_pose(&model, &kin, frame_id).unwrap();
            let position = (pose.translation - target.translation).norm();
            let angle = log_so3(&(pose.rotation.transpose() * target.rotation)).norm();
            let within = q
                .iter()
                .zip(&limits)
                .all(|(v, (lo, hi))| lo <= v && v <= hi);
            let confirmed = position <= 1e-6 && angle <= 1e-6 && within;
            assert!(!result.success || confirmed, "a false success on {name}");
            if result.success {
                verified += 1;
            }
        }
        times.sort_by(f64::total_cmp);
        let mean = times.iter().sum::<f64>() / poses as f64;
        println!(
            "{name:<7} {frame:<12} {poses:>6}  {:>7.2} %  {mean:>8.1}  {:>9.1}  {:>6.1}  {:>10.2}  {:>8.3}",
            100.0 * verified as f64 / poses as f64,
            times[poses / 2],
            times[(poses * 99) / 100],
            iterations as f64 / poses as f64,
            restarts as f64 / poses as f64,
        );
    }
}
