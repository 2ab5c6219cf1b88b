//! Jerk-limited point-to-point motion: synchronised joints, limits checked by sampling and
//! finite differences.

use screwdyn::motion::JerkLimited;
use screwdyn::sim::Trajectory;

#[test]
fn joints_finish_together_within_every_limit() {
    let q0 = [0.0, 1.0, -0.5, 0.2, 0.0, 0.0];
    let qf = [2.0, -0.5, 0.5, 0.2, 0.05, 3.0];
    let (v, a, j) = ([3.15; 6], [5.0, 5.0, 5.0, 8.0, 8.0, 8.0], [40.0; 6]);
    let m = JerkLimited::new(&q0, &qf, &v, &a, &j).unwrap();
    // The duration is the slowest joint's: the sixth (3 rad) here.
    let fastest = m.fastest_durations();
    let slowest = fastest.iter().copied().fold(0.0, f64::max);
    assert_eq!(m.duration(), slowest);
    assert_eq!(fastest[3], 0.0);
    let dt = 1e-4;
    let steps = (m.duration() / dt).ceil() as usize + 1;
    let (mut q, mut qd, mut qdd) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    let mut previous_acc = [0.0; 6];
    for k in 0..=steps {
        let t = k as f64 * dt;
        m.sample(t, &mut q, &mut qd, &mut qdd).unwrap();
        for i in 0..6 {
            assert!(
                qd[i].abs() <= v[i] * (1.0 + 1e-12),
                "t = {t}: q̇{i} = {}",
                qd[i]
            );
            assert!(
                qdd[i].abs() <= a[i] * (1.0 + 1e-12),
                "t = {t}: q̈{i} = {}",
                qdd[i]
            );
            // Jerk by finite differences of the acceleration (continuous, piecewise linear).
            if k > 0 {
                let jerk = (qdd[i] - previous_acc[i]) / dt;
                assert!(
                    jerk.abs() <= j[i] * (1.0 + 1e-6),
                    "t = {t}: jerk{i} = {jerk}"
                );
            }
            // Every moving joint is still moving until the common end, and at rest after it.
            if t < m.duration() - 1e-3 && t > 1e-3 && q0[i] != qf[i] {
                assert!(qd[i].abs() > 0.0);
            }
        }
        previous_acc = qdd;
    }
    m.sample(m.duration(), &mut q, &mut qd, &mut qdd).unwrap();
    assert_eq!(q, qf);
    assert_eq!((qd, qdd), ([0.0; 6], [0.0; 6]));
    // Position by integrating the sampled velocity (trapezoid rule) lands on the target.
    let mut pos = q0;
    let mut last = [0.0; 6];
    for k in 1..=steps {
        m.sample(k as f64 * dt, &mut q, &mut qd, &mut qdd).unwrap();
        for i in 0..6 {
            pos[i] += 0.5 * dt * (last[i] + qd[i]);
        }
        last = qd;
    }
    for i in 0..6 {
        assert!(
            (pos[i] - qf[i]).abs() < 1e-6,
            "joint {i}: {} vs {}",
            pos[i],
            qf[i]
        );
    }
}

#[test]
fn bad_limits_and_values_are_named() {
    let e = |v: f64, q: f64| {
        JerkLimited::new(&[0.0, 0.0], &[1.0, q], &[1.0, v], &[1.0; 2], &[1.0; 2])
            .unwrap_err()
            .to_string()
    };
    assert_eq!(e(0.0, 1.0), "vmax must be positive, but joint 1 has 0");
    assert_eq!(e(-2.0, 1.0), "vmax must be positive, but joint 1 has -2");
    assert!(e(f64::NAN, 1.0).contains("vmax contains a non-finite value"));
    assert!(e(1.0, f64::NAN).contains("qf contains a non-finite value (NaN) at position 1"));
    let short = JerkLimited::new(&[0.0, 0.0], &[1.0], &[1.0; 2], &[1.0; 2], &[1.0; 2]);
    assert!(short.unwrap_err().to_string().contains("qf has 1 values"));
}
