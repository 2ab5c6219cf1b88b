//! Issue 25 item 4: a simulation says when a joint reaches a limit stop (time and joint, once
//! per contact) and when it starts outside its limits. The crossing times are checked against
//! the small-angle pendulum and against the same run with the stops switched off.

use nalgebra::{Vector3, Vector6};
use screwdyn::model::JointSpec;
use screwdyn::sim::*;
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{builtin, Model, ModelBuilder};

/// The 1 m, 1 kg pendulum with position limits `[lower, upper]`.
fn limited_pendulum(lower: f64, upper: f64) -> Model {
    let mut b = ModelBuilder::new("pendulum");
    b.gravity(Vector3::new(0.0, -9.81, 0.0)).link(
        "bob",
        "base",
        JointSpec::revolute("pivot")
            .limits(lower, upper)
            .screw_in_parent(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0)),
        Se3::from_translation(Vector3::new(0.0, -1.0, 0.0)),
        SpatialInertia::point_mass(1.0, Vector3::zeros()),
    );
    b.build().unwrap()
}

fn run(m: &Model, q0: &[f64], opts: &SimOptions) -> Recording {
    let v0 = vec![0.0; m.nq()];
    simulate(m, q0, &v0, &mut ZeroTorque, &[], opts, &mut |_| {}).unwrap()
}

#[test]
fn a_pendulum_meets_its_lower_stop_when_the_small_angle_solution_says() {
    // θ(t) = θ0 cos(ωt), ω = √(g/l): θ = −0.8 θ0 at ωt = acos(−0.8).
    let amplitude = 0.02;
    let m = limited_pendulum(-0.8 * amplitude, 1.0);
    let opts = SimOptions {
        duration: 1.0,
        ..Default::default()
    };
    let rec = run(&m, &[amplitude], &opts);
    assert_eq!(rec.events.len(), 1, "{:?}", rec.events);
    let e = &rec.events[0];
    assert_eq!(
        (e.kind, e.side, e.joint_name.as_str()),
        (LimitEventKind::Contact, LimitSide::Lower, "pivot")
    );
    let omega = 9.81_f64.sqrt();
    let t = (-0.8_f64).acos() / omega;
    assert!((e.t - t).abs() < 1e-4, "{} vs {t}", e.t);
    // θ̇ = −θ0 ω sin(ωt) there, reported at the start of the 1 ms step that crossed: within
    // |θ̈| h = ω² |θ| h.
    let v = -amplitude * omega * (t * omega).sin();
    let within = omega * omega * 0.8 * amplitude * 1e-3;
    assert!((e.velocity - v).abs() < within, "{} vs {v}", e.velocity);
    assert_eq!((e.bound, e.position), (-0.016, -0.016));
}

#[test]
fn a_joint_resting_on_its_stop_makes_one_contact_not_one_a_step() {
    // Gravity pulls the pendulum towards 0, beyond its upper limit −0.1: it comes to rest in
    // the stop, where k (θ − bound) balances g sin θ, and stays there.
    let m = limited_pendulum(-1.0, -0.1);
    let opts = SimOptions {
        duration: 3.0,
        ..Default::default()
    };
    let rec = run(&m, &[-0.1 + 1e-6], &opts);
    assert_eq!(rec.events.len(), 1, "{:?}", rec.events);
    assert_eq!(rec.events[0].side, LimitSide::Upper);
    assert!(rec.q.last().unwrap()[0] > -0.1, "at rest in the stop");
}

#[test]
fn a_start_outside_the_limits_is_reported_and_not_moved() {
    // The Panda's fourth joint has limits [−3.0718, −0.0698] rad (Franka's data sheet and the
    // published URDF): q = 0 is above them.
    let m = builtin::load("panda").unwrap();
    let opts = SimOptions {
        duration: 0.01,
        ..Default::default()
    };
    let rec = run(&m, &[0.0; 7], &opts);
    let starts: Vec<_> = rec
        .events
        .iter()
        .filter(|e| e.kind == LimitEventKind::StartOutside)
        .collect();
    assert_eq!(starts.len(), 1, "{:?}", rec.events);
    let e = starts[0];
    assert_eq!(
        (e.joint_name.as_str(), e.side, e.t),
        ("panda_joint4", LimitSide::Upper, 0.0)
    );
    assert!((e.bound + 0.0698).abs() < 1e-4 && e.position == 0.0);
    // The run starts where it was told to: the first sample is q = 0.
    assert_eq!(rec.q[0][3], 0.0);
    assert!(
        e.message("rad").contains("not moved inside"),
        "{}",
        e.message("rad")
    );
}

/// The first time a recorded run is beyond a joint's limits, interpolated linearly between
/// samples, with the joint: computed from the positions alone.
fn first_crossing(m: &Model, rec: &Recording) -> Option<(f64, usize)> {
    for k in 1..rec.len() {
        for (i, j) in m.joints().iter().enumerate() {
            let (a, b) = (rec.q[k - 1][i], rec.q[k][i]);
            for bound in [j.limits.lower, j.limits.upper] {
                let crossed = (a - bound) * (b - bound) < 0.0;
                if crossed {
                    let s = (bound - a) / (b - a);
                    return Some((rec.t[k - 1] + s * (rec.t[k] - rec.t[k - 1]), i));
                }
            }
        }
    }
    None
}

#[test]
fn the_ur5s_passive_run_reports_the_stop_it_reaches() {
    // Issue 25: `screwdyn simulate builtin:ur5 --duration 1` lost 95 % of its energy and a joint
    // reached its stop at 0.51 s without a word. Until the first contact the stops exert no
    // torque, so the run without them crosses the limit at the same time.
    let m = builtin::load("ur5").unwrap();
    let opts = SimOptions {
        duration: 1.0,
        ..Default::default()
    };
    let with_stops = run(&m, &[0.0; 6], &opts);
    let free = run(
        &m,
        &[0.0; 6],
        &SimOptions {
            effects: JointEffects {
                position_limits: false,
                ..JointEffects::default()
            },
            ..opts.clone()
        },
    );
    assert!(free.events.is_empty());
    let (t, joint) = first_crossing(&m, &free).expect("the free run leaves the limits");
    let e = &with_stops.events[0];
    assert_eq!((e.kind, e.joint), (LimitEventKind::Contact, joint));
    assert!((e.t - t).abs() < 1e-6, "{} vs {t}", e.t);
    assert!((e.t - 0.51).abs() < 0.01, "{}", e.t);
}

#[test]
fn json_and_in_memory_runs_carry_the_events() {
    let m = limited_pendulum(-0.1, 0.1);
    let opts = SimOptions {
        duration: 0.5,
        record_every: 10,
        ..Default::default()
    };
    let mut json = JsonSampleWriter::new(Vec::new());
    let summary = simulate_into(
        &m,
        &[0.2],
        &[0.0],
        &mut ZeroTorque,
        &[],
        &opts,
        &mut json,
        &mut |_| {},
    )
    .unwrap();
    let value: serde_json::Value = serde_json::from_slice(&json.finish().unwrap()).unwrap();
    let rec = run(&m, &[0.2], &opts);
    assert_eq!(summary.limit_events, rec.events.len());
    assert_eq!(value["events"], rec.to_json()["events"]);
    let first = &value["events"][0];
    assert_eq!(first["kind"], "start_outside");
    assert_eq!(first["joint"], "pivot");
    assert_eq!(first["side"], "upper");
}
