//! Times the time-optimal timing of the paths of `bench/motion_compare.py` (the 5-waypoint
//! UR5 path with speed and torque limits, the 5-waypoint Panda path with acceleration and torque
//! limits) on a grid of 1000 intervals, `CALLS` times in a row, for instruction counts:
//!
//! ```text
//! RUSTFLAGS="-C target-cpu=x86-64-v3" CARGO_TARGET_DIR=target/bench-v3 \
//!     cargo build --release -p screwdyn --example topp_bench
//! valgrind --tool=callgrind target/bench-v3/release/examples/topp_bench panda 2000
//! ```
//!
//! (the difference between two call counts, divided by the difference, is the cost of a call).

use screwdyn::motion::{time_optimal, CubicSpline, TimeOptimalOptions, TimingLimits};
use screwdyn::sim::Trajectory;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let robot = args.get(1).map(String::as_str).unwrap_or("panda");
    let calls: usize = args.get(2).and_then(|c| c.parse().ok()).unwrap_or(10);
    let model = screwdyn::builtin::load(robot).expect("a builtin model");
    let mut limits = TimingLimits::from_model(&model);
    let points: Vec<Vec<f64>> = match robot {
        "ur5" => vec![
            vec![-1.0, -2.0, 2.0, -1.5, -1.5, 0.0],
            vec![-0.3, -1.5, 1.2, -1.0, -1.2, 0.6],
            vec![0.4, -1.0, 0.6, -0.8, -1.6, 1.2],
            vec![1.0, -1.4, 1.5, -1.6, -2.0, 0.4],
            vec![1.8, -0.8, 0.8, -1.2, -1.4, -0.4],
        ],
        _ => {
            limits.velocity = vec![f64::INFINITY; 7];
            limits.acceleration = vec![15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0];
            vec![
                vec![-1.0, -0.3, 0.2, -2.2, 0.1, 1.6, 0.0],
                vec![-0.4, 0.3, -0.2, -1.6, 0.5, 2.2, 0.6],
                vec![0.2, 0.0, 0.3, -2.0, -0.2, 1.4, 1.2],
                vec![0.8, -0.4, -0.1, -2.6, 0.3, 1.9, 0.4],
                vec![1.4, 0.2, 0.2, -1.8, -0.4, 2.4, -0.3],
            ]
        }
    };
    let options = TimeOptimalOptions {
        grid: Some(1000),
        ..TimeOptimalOptions::default()
    };
    let mut duration = 0.0;
    for _ in 0..calls {
        let path = CubicSpline::chord_length(&points).expect("a path");
        let timed = time_optimal(&model, path, &limits, &options).expect("a timing");
        duration += timed.duration();
    }
    println!(
        "{robot}: {calls} calls, duration {}",
        duration / calls as f64
    );
}
