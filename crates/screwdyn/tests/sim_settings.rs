//! The rules the simulator's settings obey, in one place: every bad option or controller
//! specification is refused before the run, naming its field; nothing is silently adjusted;
//! default gains follow their documented formulas.

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

/// Planar two-link arm, unit point masses at the ends of unit links (seed 004): the diagonal
/// of `M(q)` and the gravity torque `g(q)` in closed form.
fn planar2_m_diag_and_g(q: &[f64]) -> ([f64; 2], [f64; 2]) {
    let g = 9.81;
    let (c1, c12) = (q[0].cos(), (q[0] + q[1]).cos());
    (
        [3.0 + 2.0 * q[1].cos(), 1.0],
        [g * (2.0 * c1 + c12), g * c12],
    )
}

#[test]
fn default_pd_gains_are_omega_squared_and_two_omega_times_the_joint_inertia() {
    let m = builtin::planar2();
    let target = vec![0.4, 0.9];
    let (q, v) = ([0.1, -0.3], [0.7, -1.1]);
    let (m_ii, _) = planar2_m_diag_and_g(&target);
    let (_, g) = planar2_m_diag_and_g(&q);
    let w = DEFAULT_NATURAL_FREQUENCY;
    // Only kp given: kd takes its default; and the other way round.
    for (kp, kd) in [
        (None, None),
        (Some(vec![7.0, 3.0]), None),
        (None, Some(vec![2.0, 5.0])),
    ] {
        let spec = ControllerSpec::PdGravity {
            target: target.clone(),
            kp: kp.clone(),
            kd: kd.clone(),
        };
        let kp = kp.unwrap_or_else(|| m_ii.iter().map(|i| w * w * i).collect());
        let kd = kd.unwrap_or_else(|| m_ii.iter().map(|i| 2.0 * w * i).collect());
        let mut tau = [0.0; 2];
        spec.build(&m)
            .unwrap()
            .torque(0.0, &q, &v, &mut tau)
            .unwrap();
        for i in 0..2 {
            let expected = kp[i] * (target[i] - q[i]) - kd[i] * v[i] + g[i];
            assert!(
                (tau[i] - expected).abs() < 1e-9,
                "joint {i}: {} vs {expected}",
                tau[i]
            );
        }
    }
}

#[test]
fn default_computed_torque_gains_make_the_error_critically_damped_at_omega() {
    use screwdyn::dynamics::inverse_dynamics;
    let m = builtin::planar2();
    let reference = Quintic::rest_to_rest(&[0.0, 0.0], &[1.0, -0.5], 2.0).unwrap();
    let (t, q, v) = (0.7, [0.2, 0.1], [0.3, -0.4]);
    let (mut qd, mut vd, mut ad) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    reference.sample(t, &mut qd, &mut vd, &mut ad).unwrap();
    let spec = ControllerSpec::ComputedTorque {
        reference: Box::new(reference),
        kp: None,
        kd: None,
    };
    let mut tau = [0.0; 2];
    spec.build(&m).unwrap().torque(t, &q, &v, &mut tau).unwrap();
    // ë + 2ω ė + ω² e = 0 with ω = 10: the commanded acceleration q̈_d + 20 ė + 100 e.
    let w = DEFAULT_NATURAL_FREQUENCY;
    let a: Vec<f64> = (0..2)
        .map(|i| ad[i] + 2.0 * w * (vd[i] - v[i]) + w * w * (qd[i] - q[i]))
        .collect();
    let mut ws = screwdyn::Workspace::new(&m);
    let expected = inverse_dynamics(&m, &mut ws, &q, &v, &a, None).unwrap();
    for i in 0..2 {
        assert!((tau[i] - expected[i]).abs() < 1e-9, "joint {i}");
    }
}

#[test]
fn simple_specs_build_the_controllers_they_describe() {
    let m = builtin::planar2();
    let mut tau = [9.0; 2];
    let mut torque = |spec: ControllerSpec, t: f64| {
        spec.build(&m)
            .unwrap()
            .torque(t, &[0.0; 2], &[0.0; 2], &mut tau)
            .unwrap();
        tau
    };
    assert_eq!(torque(ControllerSpec::Zero, 0.0), [0.0, 0.0]);
    assert_eq!(
        torque(ControllerSpec::Constant(vec![1.5, -2.0]), 3.0),
        [1.5, -2.0]
    );
    let series = ControllerSpec::Series {
        times: vec![0.0, 2.0],
        values: vec![vec![0.0, 4.0], vec![2.0, 0.0]],
    };
    // Halfway between the two samples.
    assert_eq!(torque(series, 1.0), [1.0, 2.0]);
}

#[test]
fn bad_specs_are_refused_naming_the_vector() {
    let m = builtin::planar2();
    let pd = |target: Vec<f64>, kp: Option<Vec<f64>>, kd: Option<Vec<f64>>| {
        ControllerSpec::PdGravity { target, kp, kd }
    };
    let quintic =
        |n: usize| Box::new(Quintic::rest_to_rest(&vec![0.0; n], &vec![1.0; n], 1.0).unwrap());
    let cases: Vec<(ControllerSpec, &str)> = vec![
        (pd(vec![0.0; 3], None, None), "the PD target has 3 values"),
        (
            pd(vec![0.0; 2], Some(vec![1.0; 3]), None),
            "kp has 3 values",
        ),
        (
            pd(vec![0.0; 2], None, Some(vec![1.0, f64::NAN])),
            "kd contains a non-finite value",
        ),
        (
            pd(vec![f64::INFINITY, 0.0], None, None),
            "the PD target contains a non-finite value",
        ),
        (
            ControllerSpec::ComputedTorque {
                reference: quintic(2),
                kp: None,
                kd: Some(vec![1.0]),
            },
            "kd has 1 values",
        ),
        (
            ControllerSpec::ComputedTorque {
                reference: quintic(3),
                kp: None,
                kd: None,
            },
            "the reference trajectory has 3 joints",
        ),
        (
            ControllerSpec::Constant(vec![1.0; 3]),
            "the constant torque has 3 values",
        ),
        (
            ControllerSpec::Series {
                times: vec![0.0, 1.0],
                values: vec![vec![0.0; 2], vec![0.0; 3]],
            },
            "torque series row 2 has 3 values",
        ),
        (
            ControllerSpec::Series {
                times: vec![1.0, 0.0],
                values: vec![vec![0.0; 2]; 2],
            },
            "torque series times must increase strictly",
        ),
    ];
    for (spec, says) in cases {
        let what = format!("{spec:?}");
        let e = spec
            .build(&m)
            .err()
            .unwrap_or_else(|| panic!("{what} was accepted"))
            .to_string();
        assert!(e.starts_with(says), "{what}: {e}");
    }
}

#[test]
fn a_profile_too_large_to_hold_is_refused_before_it_starts() {
    // 10^12 samples of the two-link arm need hundreds of TB: an error naming the memory, not an
    // allocation failure after gigabytes (which aborts the process).
    let m = builtin::planar2();
    let traj = Quintic::rest_to_rest(&[0.0, 0.0], &[1.0, 1.0], 1.0).unwrap();
    let e = torque_profile_limited(&m, &traj, 1e-12, usize::MAX)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("samples needs about") && e.contains("GB of memory"),
        "{e}"
    );
    // an ordinary profile is unaffected
    assert!(torque_profile_limited(&m, &traj, 1e-3, usize::MAX).is_ok());
}
