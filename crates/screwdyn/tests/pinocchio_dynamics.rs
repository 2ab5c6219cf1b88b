//! Dynamics against Pinocchio (issue 4): τ (RNEA), M (CRBA), g, C q̇, the nonlinear effects,
//! the Coriolis matrix and q̈ (ABA, and the other two forward-dynamics methods) at 20 random
//! states of the UR5, the Panda and a random tree with prismatic joints; 1e-9 relative.
//! Reference values: `scripts/gen_reference.py`.

#[path = "common/pinocchio.rs"]
mod pinocchio;

use nalgebra::{DMatrix, DVector};
use pinocchio::{dmatrix, load_fixture, rel, ROBOTS};
use screwdyn::dynamics::*;
use screwdyn::Workspace;

const TOL: f64 = 1e-9;

#[test]
fn rnea_crba_gravity_and_nonlinear_effects_match_pinocchio() {
    for robot in ROBOTS {
        let (m, fx) = load_fixture(robot);
        let mut ws = Workspace::new(&m);
        for (k, s) in fx.states.iter().enumerate() {
            let tau = rnea(&m, &mut ws, &s.q, &s.v, &s.a)
                .unwrap()
                .as_slice()
                .to_vec();
            assert!(
                rel(&tau, &s.tau) < TOL,
                "{robot} state {k}: tau {}",
                rel(&tau, &s.tau)
            );
            let mm = crba(&m, &mut ws, &s.q).unwrap().clone();
            let want = dmatrix(&s.mass_matrix);
            assert!(
                rel(mm.as_slice(), want.as_slice()) < TOL,
                "{robot} state {k}: M"
            );
            let g = gravity_torque(&m, &mut ws, &s.q)
                .unwrap()
                .as_slice()
                .to_vec();
            assert!(rel(&g, &s.gravity) < TOL, "{robot} state {k}: g");
            let h = nonlinear_effects(&m, &mut ws, &s.q, &s.v)
                .unwrap()
                .as_slice()
                .to_vec();
            assert!(
                rel(&h, &s.nonlinear_effects) < TOL,
                "{robot} state {k}: nle"
            );
            let c = coriolis_matrix(&m, &mut ws, &s.q, &s.v).unwrap().clone();
            let cv = &c * DVector::from_column_slice(&s.v);
            assert!(
                rel(cv.as_slice(), &s.coriolis_times_v) < TOL,
                "{robot} state {k}: C q̇"
            );
        }
    }
}

#[test]
fn coriolis_matrix_matches_pinocchio() {
    for robot in ROBOTS {
        let (m, fx) = load_fixture(robot);
        let mut ws = Workspace::new(&m);
        for (k, s) in fx.states.iter().enumerate() {
            let c: DMatrix<f64> = coriolis_matrix(&m, &mut ws, &s.q, &s.v).unwrap().clone();
            let want = dmatrix(&s.coriolis_matrix);
            assert!(
                rel(c.as_slice(), want.as_slice()) < TOL,
                "{robot} state {k}: C {}",
                rel(c.as_slice(), want.as_slice())
            );
        }
    }
}

#[test]
fn forward_dynamics_matches_pinocchio_aba_with_all_three_methods() {
    for robot in ROBOTS {
        let (m, fx) = load_fixture(robot);
        let mut ws = Workspace::new(&m);
        for (k, s) in fx.states.iter().enumerate() {
            for method in [
                ForwardMethod::Aba,
                ForwardMethod::Crba,
                ForwardMethod::WalkerOrin,
            ] {
                let qdd = forward_dynamics(&m, &mut ws, &s.q, &s.v, &s.tau_in, None, method)
                    .unwrap()
                    .as_slice()
                    .to_vec();
                assert!(
                    rel(&qdd, &s.qdd) < TOL,
                    "{robot} state {k} {method:?}: {}",
                    rel(&qdd, &s.qdd)
                );
            }
        }
    }
}
