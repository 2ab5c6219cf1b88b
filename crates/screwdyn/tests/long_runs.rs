//! Issue 12.4: the default simulation of every shipped robot (what `screwdyn simulate
//! builtin:<name> --duration 100` does: zero torque from rest at q = 0, RK4 at 1 ms, ABA, every
//! joint effect on) runs 100 s without diverging. A passive robot with damping, friction and
//! limit stops can only lose energy: the total energy at the end is checked against the start.

use screwdyn::builtin;
use screwdyn::sim::{simulate_into, Sample, SampleSink, SimOptions, ZeroTorque};

/// Keeps the first and last total energy and the largest speed, nothing else.
#[derive(Default)]
struct Watch {
    first: Option<f64>,
    last: f64,
    fastest: f64,
    samples: usize,
}

impl SampleSink for Watch {
    fn begin(&mut self, _: &[String], _: &[String]) -> screwdyn::Result<()> {
        Ok(())
    }
    fn push(&mut self, s: &Sample) -> screwdyn::Result<()> {
        let e = s.kinetic_energy + s.potential_energy;
        self.first.get_or_insert(e);
        self.last = e;
        self.fastest = s.v.iter().fold(self.fastest, |m, v| m.max(v.abs()));
        self.samples += 1;
        Ok(())
    }
}

#[test]
fn every_builtin_simulates_100_s_with_default_options() {
    for name in builtin::NAMES {
        let m = builtin::load(name).unwrap();
        let n = m.nq();
        let opts = SimOptions {
            duration: 100.0,
            record_every: 100,
            ..Default::default()
        };
        let mut w = Watch::default();
        let run = simulate_into(
            &m,
            &vec![0.0; n],
            &vec![0.0; n],
            &mut ZeroTorque,
            &[],
            &opts,
            &mut w,
            &mut |_| {},
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(run.end_time, 100.0, "{name}");
        assert_eq!(w.samples, 1001, "{name}");
        let (start, end) = (w.first.unwrap(), w.last);
        // Passive effects dissipate; the integrator's own drift at 1 ms is far below 1 mJ.
        assert!(
            end <= start + 1e-3 * (1.0 + start.abs()),
            "{name}: energy {start} J → {end} J"
        );
        assert!(
            w.fastest.is_finite() && w.fastest < 1e3,
            "{name}: {}",
            w.fastest
        );
    }
}
