//! Times a passive simulation: 10 s at 1 kHz with RK4 and ABA, no joint effects, recording
//! only the end state (or, with `--record-every K --csv PATH`, every K-th step streamed to a CSV
//! file as `screwdyn simulate --output` does); prints JSON
//! `{"model", "steps", "seconds": [..], "median_s", "final_q"}`. Optionally writes the model as
//! URDF (for the MuJoCo side of `bench/sim_vs_mujoco.sh`).
//!
//! ```text
//! cargo run --release -p screwdyn --example sim_bench -- builtin:ur5 [--repeat 5] [--duration 10] \
//!     [--urdf out.urdf] [--record-every K --csv run.csv]
//! ```

use screwdyn::sim::{
    simulate_into, CsvSampleWriter, Integrator, JointEffects, Sample, SampleSink, SimOptions,
    ZeroTorque,
};
use std::io::Write;
use std::time::Instant;

/// Streams the samples to a CSV writer and keeps the last `q`.
struct Csv<W: Write> {
    csv: CsvSampleWriter<W>,
    last_q: Vec<f64>,
}

impl<W: Write> SampleSink for Csv<W> {
    fn begin(&mut self, joints: &[String], frames: &[String]) -> screwdyn::Result<()> {
        self.csv.begin(joints, frames)
    }
    fn push(&mut self, sample: &Sample) -> screwdyn::Result<()> {
        self.last_q.clear();
        self.last_q.extend_from_slice(sample.q);
        self.csv.push(sample)
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let spec = args.get(1).map(String::as_str).unwrap_or("builtin:ur5");
    let flag = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let repeat: usize = flag("--repeat").and_then(|s| s.parse().ok()).unwrap_or(5);
    let duration: f64 = flag("--duration")
        .and_then(|s| s.parse().ok())
        .unwrap_or(10.0);
    let model = match screwdyn::io::load_model(spec) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("sim_bench: {e}");
            std::process::exit(2);
        }
    };
    if let Some(path) = flag("--urdf") {
        let text = screwdyn::io::urdf::to_urdf_string(&model).unwrap_or_else(|e| {
            eprintln!("sim_bench: {e}");
            std::process::exit(2)
        });
        std::fs::write(&path, text).expect("write the URDF");
    }
    let n = model.nq();
    // The same start for both simulators: a bent arm at rest, released under gravity.
    let q0: Vec<f64> = (0..n).map(|i| 0.3 * ((i as f64) + 1.0).sin()).collect();
    let v0 = vec![0.0; n];
    let opts = SimOptions {
        duration,
        dt: 1e-3,
        integrator: Integrator::Rk4,
        effects: JointEffects::none(),
        record_every: flag("--record-every")
            .and_then(|s| s.parse().ok())
            .unwrap_or(1_000_000),
        ..Default::default()
    };
    let mut seconds = Vec::new();
    let mut final_q = Vec::new();
    for _ in 0..repeat {
        let out: Box<dyn Write> = match flag("--csv") {
            Some(path) => Box::new(std::io::BufWriter::new(
                std::fs::File::create(path).expect("create the CSV file"),
            )),
            None => Box::new(std::io::sink()),
        };
        let mut sink = Csv {
            csv: CsvSampleWriter::new(out),
            last_q: Vec::new(),
        };
        let start = Instant::now();
        simulate_into(
            &model,
            &q0,
            &v0,
            &mut ZeroTorque,
            &[],
            &opts,
            &mut sink,
            &mut |_| {},
        )
        .expect("simulate");
        sink.csv.flush().expect("flush the CSV file");
        seconds.push(start.elapsed().as_secs_f64());
        final_q = sink.last_q;
    }
    let mut sorted = seconds.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    println!(
        "{{\"model\": \"{}\", \"steps\": {}, \"q0\": {:?}, \"seconds\": {:?}, \"median_s\": {median}, \"final_q\": {:?}}}",
        model.name(),
        (duration / 1e-3).round(),
        q0,
        seconds,
        final_q
    );
}
