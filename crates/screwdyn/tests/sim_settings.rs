//! The rules the simulator's settings obey, in one place: every bad option is refused before
//! the run, naming its field; nothing is silently adjusted.

use screwdyn::builtin;
use screwdyn::sim::*;

/// The message of `simulate` with `opts` on the pendulum (which must fail).
fn refused(opts: &SimOptions) -> String {
    let m = builtin::pendulum();
    simulate(&m, &[0.1], &[0.0], &mut ZeroTorque, &[], opts, &mut |_| {})
        .unwrap_err()
        .to_string()
}

#[test]
fn every_bad_option_is_refused_naming_its_field() {
    let ok = SimOptions {
        duration: 0.01,
        ..Default::default()
    };
    let cases: Vec<(SimOptions, &str)> = vec![
        (
            SimOptions {
                dt: 0.0,
                ..ok.clone()
            },
            "dt must be positive (got 0)",
        ),
        (
            SimOptions {
                dt: f64::NAN,
                ..ok.clone()
            },
            "dt must be positive (got NaN)",
        ),
        (
            SimOptions {
                dt: f64::INFINITY,
                ..ok.clone()
            },
            "dt must be finite (got inf)",
        ),
        (
            SimOptions {
                duration: -1.0,
                ..ok.clone()
            },
            "duration must be non-negative (got -1)",
        ),
        (
            SimOptions {
                duration: f64::INFINITY,
                ..ok.clone()
            },
            "duration must be finite (got inf)",
        ),
        (
            SimOptions {
                record_every: 0,
                ..ok.clone()
            },
            "record_every must be at least 1 (got 0)",
        ),
        (
            SimOptions {
                integrator: Integrator::DormandPrince {
                    rtol: -1.0,
                    atol: 1e-9,
                },
                ..ok.clone()
            },
            "Dormand–Prince tolerances",
        ),
        (
            SimOptions {
                frames: vec![7],
                ..ok.clone()
            },
            "frame 7 is out of range",
        ),
    ];
    let m = builtin::pendulum();
    for (opts, says) in cases {
        let e = refused(&opts);
        assert!(e.starts_with(says), "{e}");
        // `validate` is the check the simulator makes: the same sentence.
        assert_eq!(opts.validate(&m).unwrap_err().to_string(), e);
    }
    assert!(ok.validate(&m).is_ok());
    // A zero duration is a valid (empty) run.
    assert!(SimOptions {
        duration: 0.0,
        ..ok
    }
    .validate(&m)
    .is_ok());
}

#[test]
fn joint_effect_settings_are_checked_even_when_switched_off() {
    let off = JointEffects::none();
    let cases = [
        (
            JointEffects {
                limit_time_constant: -1.0,
                ..off
            },
            "effects.limit_time_constant must be positive (got -1)",
        ),
        (
            JointEffects {
                limit_damping_ratio: f64::NAN,
                ..off
            },
            "effects.limit_damping_ratio must be non-negative (got NaN)",
        ),
        (
            JointEffects {
                friction_smoothing: 0.0,
                ..off
            },
            "effects.friction_smoothing must be positive (got 0)",
        ),
    ];
    let m = builtin::pendulum();
    for (effects, says) in cases {
        let opts = SimOptions {
            duration: 0.01,
            effects,
            ..Default::default()
        };
        assert!(refused(&opts).starts_with(says), "{}", refused(&opts));
        let gains = EffectGains::new(&effects, &m, &[0.0], 1e-3).unwrap_err();
        assert!(gains.to_string().starts_with(says), "{gains}");
    }
    // An undamped stop (ζ = 0: the joint bounces out at the speed it came in) is allowed.
    assert!(JointEffects {
        limit_damping_ratio: 0.0,
        ..off
    }
    .validate()
    .is_ok());
}

#[test]
fn record_every_keeps_every_kth_step_and_the_last() {
    // 10 steps of 0.1 s recorded every 3rd: t = 0, 0.3, 0.6, 0.9 and the end, 1.0.
    let m = builtin::pendulum();
    let opts = SimOptions {
        duration: 1.0,
        dt: 0.1,
        record_every: 3,
        ..Default::default()
    };
    let run = simulate(&m, &[0.1], &[0.0], &mut ZeroTorque, &[], &opts, &mut |_| {}).unwrap();
    let expected = [0.0, 0.3, 0.6, 0.9, 1.0];
    assert_eq!(run.t.len(), expected.len());
    for (t, e) in run.t.iter().zip(expected) {
        assert!((t - e).abs() < 1e-12, "{t} vs {e}");
    }
}

#[test]
fn torque_profiles_and_quintics_name_their_step_and_duration() {
    let m = builtin::planar2();
    let q = Quintic::rest_to_rest(&[0.0; 2], &[1.0; 2], 1.0).unwrap();
    let e = torque_profile(&m, &q, -0.5).unwrap_err().to_string();
    assert!(e.starts_with("dt must be positive (got -0.5)"), "{e}");
    let e = Quintic::rest_to_rest(&[0.0; 2], &[1.0; 2], 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("duration must be positive (got 0)"), "{e}");
}
