//! Time per closed-form inverse-kinematics solve (all solutions), one thread:
//! `cargo run --release --example ik_closed_form_timing -- [robot-or-file] [frame] [poses]`
//! (default: the built-in UR5's `tool0`, 2000 poses). The targets are forward kinematics of
//! configurations spread over ±π; the time includes checking every solution by forward
//! kinematics.

use screwdyn::kinematics::ik::ClosedForm;
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::spatial::Se3;
use screwdyn::Workspace;
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let robot = args.next().unwrap_or_else(|| "ur5".into());
    let frame_name = args.next().unwrap_or_else(|| "tool0".into());
    let poses: usize = args
        .next()
        .map_or(2000, |s| s.parse().expect("a number of poses"));
    let model = screwdyn::io::load_model(&if robot.contains('.') {
        robot.clone()
    } else {
        format!("builtin:{robot}")
    })
    .expect("a robot");
    let frame = model.frame_id(&frame_name).expect("a frame of the robot");
    let ik = ClosedForm::detect(&model, frame)
        .expect("a frame")
        .expect("an arm with a closed form");
    // Deterministic configurations (a Weyl sequence) in ±π, their poses the targets.
    let mut x = 0.0_f64;
    let mut ws = Workspace::new(&model);
    let targets: Vec<Se3> = (0..poses)
        .map(|_| {
            let q: Vec<f64> = (0..model.nq())
                .map(|_| {
                    x = (x + 0.618_033_988_749_894_9) % 1.0;
                    (2.0 * x - 1.0) * std::f64::consts::PI
                })
                .collect();
            forward_kinematics(&model, &mut ws, &q).unwrap();
            frame_pose(&model, &ws, frame).unwrap()
        })
        .collect();
    let mut out = [[0.0; 6]; 8];
    let mut rounds = Vec::new();
    let mut solutions = 0;
    for _ in 0..7 {
        solutions = 0;
        let start = Instant::now();
        for target in &targets {
            solutions += ik.solve(std::hint::black_box(target), &mut out);
        }
        rounds.push(start.elapsed().as_secs_f64() * 1e6 / poses as f64);
    }
    rounds.sort_by(f64::total_cmp);
    println!(
        "{robot} {frame_name} ({:?}): {:.3} µs per solve (median of 7 rounds of {poses} poses), {:.2} solutions per pose",
        ik.family(),
        rounds[3],
        solutions as f64 / poses as f64
    );
}
