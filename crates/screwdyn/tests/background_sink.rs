//! `BackgroundSink`: the samples and events a run sends through the worker thread reach the
//! inner sink unchanged and in order; the inner sink's errors stop the run.

use nalgebra::{Vector3, Vector6};
use screwdyn::model::JointSpec;
use screwdyn::sim::*;
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{builtin, ModelBuilder};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

#[test]
fn a_csv_file_written_in_the_background_is_the_same_file() {
    // planar2 recording the frame at the second link's origin, every step for 2 s.
    let m = builtin::planar2();
    let opts = SimOptions {
        duration: 2.0,
        dt: 1e-3,
        frames: vec![m.frame_id("link2").unwrap()],
        ..Default::default()
    };
    let (q0, v0) = ([0.4, -0.7], [0.0, 1.5]);
    let mut direct = CsvSampleWriter::new(Vec::new());
    simulate_into(
        &m,
        &q0,
        &v0,
        &mut ZeroTorque,
        &[],
        &opts,
        &mut direct,
        &mut |_| {},
    )
    .unwrap();
    let mut background = BackgroundSink::new(CsvSampleWriter::new(Vec::new()));
    let run = simulate_into(
        &m,
        &q0,
        &v0,
        &mut ZeroTorque,
        &[],
        &opts,
        &mut background,
        &mut |_| {},
    )
    .unwrap();
    let text = background.finish().unwrap().into_inner();
    assert_eq!(run.samples, 2001);
    assert!(text == direct.into_inner(), "the two files differ");
    // The last row's frame position is the planar arm's closed form, x = cos q1 + cos(q1 + q2).
    let text = String::from_utf8(text).unwrap();
    let row: Vec<f64> = text
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|c| c.parse().unwrap())
        .collect();
    assert_eq!(row.len(), 1 + 4 * 2 + 3 + 3);
    let (q1, q2) = (row[1], row[2]);
    assert!((row[12] - (q1.cos() + (q1 + q2).cos())).abs() < 1e-12);
    assert!((row[13] - (q1.sin() + (q1 + q2).sin())).abs() < 1e-12);
}

#[test]
fn limit_events_arrive_among_the_samples_in_order() {
    // The 1 m pendulum from 0.02 rad against a stop at −0.016 rad: one contact, at
    // ωt = acos(−0.8) of the small-angle solution.
    let mut b = ModelBuilder::new("pendulum");
    b.gravity(Vector3::new(0.0, -9.81, 0.0)).link(
        "bob",
        "base",
        JointSpec::revolute("pivot")
            .limits(-0.016, 1.0)
            .screw_in_parent(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0)),
        Se3::from_translation(Vector3::new(0.0, -1.0, 0.0)),
        SpatialInertia::point_mass(1.0, Vector3::zeros()),
    );
    let m = b.build().unwrap();
    let opts = SimOptions {
        duration: 1.0,
        ..Default::default()
    };
    let direct = simulate(
        &m,
        &[0.02],
        &[0.0],
        &mut ZeroTorque,
        &[],
        &opts,
        &mut |_| {},
    )
    .unwrap();
    let mut sink = BackgroundSink::new(Recording::default());
    simulate_into(
        &m,
        &[0.02],
        &[0.0],
        &mut ZeroTorque,
        &[],
        &opts,
        &mut sink,
        &mut |_| {},
    )
    .unwrap();
    let rec = sink.finish().unwrap();
    assert_eq!(rec, direct);
    assert_eq!(rec.events.len(), 1);
    let t = (-0.8_f64).acos() / 9.81_f64.sqrt();
    assert!(
        (rec.events[0].t - t).abs() < 1e-4,
        "{} vs {t}",
        rec.events[0].t
    );
}

/// Fails at its `fail_at`-th sample; counts the samples it saw.
struct FailingSink {
    seen: Arc<AtomicUsize>,
    fail_at: usize,
}

impl SampleSink for FailingSink {
    fn begin(&mut self, _: &[String], _: &[String]) -> screwdyn::Result<()> {
        Ok(())
    }
    fn push(&mut self, _: &Sample) -> screwdyn::Result<()> {
        let k = self.seen.fetch_add(1, Ordering::SeqCst) + 1;
        if k == self.fail_at {
            return Err(screwdyn::Error::InvalidArgument(
                "disk full at sample 100".into(),
            ));
        }
        Ok(())
    }
}

#[test]
fn the_inner_sinks_error_stops_the_run() {
    let m = builtin::pendulum();
    let seen = Arc::new(AtomicUsize::new(0));
    let mut sink = BackgroundSink::new(FailingSink {
        seen: seen.clone(),
        fail_at: 100,
    });
    // 100 000 samples would be sent; the run stops within a few batches of the 100th.
    let opts = SimOptions {
        duration: 100.0,
        dt: 1e-3,
        ..Default::default()
    };
    let e = simulate_into(
        &m,
        &[0.1],
        &[0.0],
        &mut ZeroTorque,
        &[],
        &opts,
        &mut sink,
        &mut |_| {},
    )
    .unwrap_err();
    assert!(e.to_string().contains("disk full at sample 100"), "{e}");
    assert_eq!(seen.load(Ordering::SeqCst), 100);
    // The sink is spent: finishing it reports that its worker is gone, without a panic.
    assert!(sink.finish().is_err());
}

#[test]
fn a_sample_of_the_wrong_size_is_refused() {
    let mut sink = BackgroundSink::new(Recording::default());
    sink.begin(&["j1".into()], &[]).unwrap();
    let e = sink
        .push(&Sample {
            t: 0.0,
            q: &[1.0, 2.0],
            v: &[0.0],
            a: &[0.0],
            tau: &[0.0],
            kinetic_energy: 0.0,
            potential_energy: 0.0,
            poses: &[],
        })
        .unwrap_err();
    assert!(
        e.to_string().contains("does not fit a run of 1 joints"),
        "{e}"
    );
    assert_eq!(sink.finish().unwrap().len(), 0);
}
