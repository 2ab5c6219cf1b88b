//! Integrators and trajectories against exact solutions, convergence orders, finite
//! differences and boundary conditions.

use screwdyn::sim::*;
use std::f64::consts::PI;

fn oscillator(_t: f64, q: &[f64], _v: &[f64], a: &mut [f64]) -> screwdyn::Result<()> {
    a[0] = -q[0];
    Ok(())
}

/// Integrates q̈ = −q from (1, 0) to t = T; returns the final error against cos t.
fn error_after(integrator: Integrator, h: f64, t_end: f64) -> f64 {
    let mut s = Stepper::new(integrator, 1).unwrap();
    let (mut q, mut v) = ([1.0], [0.0]);
    let n = (t_end / h).round() as usize;
    for k in 0..n {
        s.advance(&mut oscillator, k as f64 * h, h, &mut q, &mut v)
            .unwrap();
    }
    let t = n as f64 * h;
    ((q[0] - t.cos()).powi(2) + (v[0] + t.sin()).powi(2)).sqrt()
}

#[test]
fn rk4_is_fourth_order_and_euler_first_order() {
    let (e1, e2) = (
        error_after(Integrator::Rk4, 0.02, 5.0),
        error_after(Integrator::Rk4, 0.01, 5.0),
    );
    let order = (e1 / e2).log2();
    assert!((order - 4.0).abs() < 0.1, "RK4 order {order}");
    let (e1, e2) = (
        error_after(Integrator::SymplecticEuler, 0.002, 5.0),
        error_after(Integrator::SymplecticEuler, 0.001, 5.0),
    );
    let order = (e1 / e2).log2();
    assert!((order - 1.0).abs() < 0.1, "Euler order {order}");
}

#[test]
fn symplectic_euler_energy_stays_bounded() {
    // Energy ½(q² + v²) of the oscillator over 1000 periods: no secular drift.
    let mut s = Stepper::new(Integrator::SymplecticEuler, 1).unwrap();
    let (mut q, mut v) = ([1.0], [0.0]);
    let h = 0.01;
    let mut worst: f64 = 0.0;
    for k in 0..(1000.0 * 2.0 * PI / h) as usize {
        s.advance(&mut oscillator, k as f64 * h, h, &mut q, &mut v)
            .unwrap();
        worst = worst.max((0.5 * (q[0] * q[0] + v[0] * v[0]) - 0.5).abs());
    }
    assert!(worst < 0.01, "energy error {worst}");
}

#[test]
fn dormand_prince_meets_its_tolerance() {
    for tol in [1e-6, 1e-9] {
        let e = error_after(
            Integrator::DormandPrince {
                rtol: tol,
                atol: tol,
            },
            0.5,
            10.0,
        );
        // Global error stays within a modest multiple of the local tolerance.
        assert!(e < 50.0 * tol, "tol {tol}: error {e}");
    }
}

fn fd_check(traj: &dyn Trajectory) {
    let n = traj.nq();
    let (mut q, mut qd, mut qdd) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut qp, mut qm, mut d1, mut d2) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let h = 1e-6;
    for k in 1..100 {
        let t = traj.duration() * k as f64 / 100.0 + 1e-4;
        traj.sample(t, &mut q, &mut qd, &mut qdd).unwrap();
        traj.sample(t + h, &mut qp, &mut d1, &mut d2).unwrap();
        traj.sample(t - h, &mut qm, &mut d2, &mut d1).unwrap();
        for i in 0..n {
            assert!(
                ((qp[i] - qm[i]) / (2.0 * h) - qd[i]).abs() < 1e-6,
                "velocity at t = {t}"
            );
        }
    }
}

#[test]
fn trapezoid_reaches_cruise_is_continuous_and_stops_at_target() {
    let (q0, qf) = ([0.0, 1.0, -0.5], [2.0, 0.5, -0.5]);
    let t = Trapezoid::new(&q0, &qf, &[1.0, 1.0, 1.0], &[2.0, 1.0, 1.0], false).unwrap();
    // Joint 0: ramp 0.5 s to 1 rad/s, cruise (2 − 0.5)/1 = 1.5 s: 2.5 s in all.
    assert!((t.duration() - 2.5).abs() < 1e-12);
    // Joint 1 is short (0.5 rad < v²/a = 1 rad): a triangle peaking at a·√(d/a) = √0.5 rad/s.
    assert!((t.cruise_speeds()[1] - 0.5f64.sqrt()).abs() < 1e-12);
    let (mut q, mut qd, mut qdd) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    t.sample(1.0, &mut q, &mut qd, &mut qdd).unwrap();
    assert_eq!(qd[0], 1.0);
    t.sample(t.duration(), &mut q, &mut qd, &mut qdd).unwrap();
    assert_eq!(q, qf);
    assert_eq!(qd, [0.0; 3]);
    // Velocity continuity: no jumps between samples 1 ms apart larger than amax·dt.
    let (mut prev, mut cur) = ([0.0; 3], [0.0; 3]);
    for k in 0..=2500 {
        t.sample(k as f64 * 1e-3, &mut q, &mut cur, &mut qdd)
            .unwrap();
        if k > 0 {
            for i in 0..3 {
                assert!((cur[i] - prev[i]).abs() <= 4.0 * 1e-3 + 1e-12);
            }
        }
        prev = cur;
    }
    fd_check(&t);
}

#[test]
fn synchronised_trapezoids_end_together() {
    let t = Trapezoid::new(&[0.0, 0.0], &[2.0, 0.3], &[1.0, 1.0], &[2.0, 2.0], true).unwrap();
    let (mut q, mut qd, mut qdd) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    // Joint 1 ends exactly when joint 0 does, and not before.
    t.sample(t.duration() - 0.05, &mut q, &mut qd, &mut qdd)
        .unwrap();
    assert!(qd[1] > 0.0 && q[1] < 0.3);
    t.sample(t.duration(), &mut q, &mut qd, &mut qdd).unwrap();
    assert!((q[1] - 0.3).abs() < 1e-12 && qd[1].abs() < 1e-12);
    fd_check(&t);
}

#[test]
fn quintic_meets_its_boundary_conditions() {
    let (q0, v0, a0) = ([0.1, -1.0], [0.5, 0.0], [0.0, 2.0]);
    let (qf, vf, af) = ([1.0, 1.0], [0.0, -0.3], [1.0, 0.0]);
    let t = Quintic::new((&q0, &v0, &a0), (&qf, &vf, &af), 1.7).unwrap();
    let (mut q, mut qd, mut qdd) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    t.sample(0.0, &mut q, &mut qd, &mut qdd).unwrap();
    assert_eq!((q, qd, qdd), (q0, v0, a0));
    t.sample(1.7, &mut q, &mut qd, &mut qdd).unwrap();
    for i in 0..2 {
        assert!(
            (q[i] - qf[i]).abs() < 1e-12
                && (qd[i] - vf[i]).abs() < 1e-12
                && (qdd[i] - af[i]).abs() < 1e-11
        );
    }
    fd_check(&t);
    assert!(Quintic::rest_to_rest(&[0.0], &[1.0], 0.0).is_err());
}

#[test]
fn waypoints_pass_through_every_point() {
    let times = [0.0, 0.5, 1.5, 2.0];
    let pts = vec![
        vec![0.0, 1.0],
        vec![1.0, 0.0],
        vec![-1.0, 2.0],
        vec![0.5, 0.5],
    ];
    let w = Waypoints::new(&times, &pts).unwrap();
    let (mut q, mut qd, mut qdd) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    for (k, tk) in times.iter().enumerate() {
        w.sample(*tk, &mut q, &mut qd, &mut qdd).unwrap();
        assert!((q[0] - pts[k][0]).abs() < 1e-12 && (q[1] - pts[k][1]).abs() < 1e-12);
    }
    fd_check(&w);
    assert!(Waypoints::new(&[0.0, 0.0], &pts[..2]).is_err());
}
