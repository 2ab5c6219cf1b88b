//! Derivatives of the dynamics against Pinocchio (issue 15): `computeRNEADerivatives`
//! (`∂τ/∂q`, `∂τ/∂q̇`, `∂τ/∂q̈ = M`) and `computeABADerivatives` (`∂q̈/∂q`, `∂q̈/∂q̇`, `M⁻¹`)
//! with body-fixed external wrenches, at 20 random states of the UR5, the Panda and a random
//! tree with prismatic joints; 1e-9 relative. Reference values: `scripts/gen_reference.py`.

#[path = "common/pinocchio.rs"]
mod pinocchio;

use nalgebra::{DMatrix, Vector6};
use pinocchio::{dmatrix, load_fixture, ROBOTS};
use screwdyn::dynamics::*;
use screwdyn::Workspace;

const TOL: f64 = 1e-9;

/// Largest `|got − want| / max(1, |want|)` over the entries.
fn rel(got: &DMatrix<f64>, want: &DMatrix<f64>) -> f64 {
    assert_eq!(got.shape(), want.shape());
    got.iter()
        .zip(want.iter())
        .map(|(g, w)| (g - w).abs() / w.abs().max(1.0))
        .fold(0.0, f64::max)
}

#[test]
fn rnea_and_aba_derivatives_match_pinocchio() {
    let mut with_wrenches = 0;
    for robot in ROBOTS {
        let (m, fx) = load_fixture(robot);
        let mut ws = Workspace::new(&m);
        for (k, s) in fx.states.iter().enumerate() {
            let d = &s.derivatives;
            let mut ext = ExternalWrenches::new(&m);
            for (i, w) in d.fext.iter().enumerate() {
                ext.add_local(i, Vector6::from_column_slice(w)).unwrap();
            }
            if d.fext.iter().flatten().any(|x| *x != 0.0) {
                with_wrenches += 1;
            }
            rnea_derivatives(&m, &mut ws, &s.q, &s.v, &s.a, Some(&ext)).unwrap();
            let tau = DMatrix::from_column_slice(m.nv(), 1, ws.tau.as_slice());
            let want_tau = DMatrix::from_column_slice(m.nv(), 1, &d.tau_fext);
            for (name, got, want) in [
                ("tau", &tau, &want_tau),
                ("dtau_dq", &ws.dtau_dq, &dmatrix(&d.dtau_dq)),
                ("dtau_dv", &ws.dtau_dv, &dmatrix(&d.dtau_dv)),
                ("dtau_da", &ws.mass_matrix, &dmatrix(&d.dtau_da)),
            ] {
                let e = rel(got, want);
                assert!(e < TOL, "{robot} state {k}: {name} off by {e:e}");
            }
            aba_derivatives(&m, &mut ws, &s.q, &s.v, &s.tau_in, Some(&ext)).unwrap();
            let qdd = DMatrix::from_column_slice(m.nv(), 1, ws.qdd.as_slice());
            let want_qdd = DMatrix::from_column_slice(m.nv(), 1, &d.qdd_fext);
            for (name, got, want) in [
                ("qdd", &qdd, &want_qdd),
                ("dqdd_dq", &ws.dqdd_dq, &dmatrix(&d.dqdd_dq)),
                ("dqdd_dv", &ws.dqdd_dv, &dmatrix(&d.dqdd_dv)),
                ("minv", &ws.mass_matrix_inverse, &dmatrix(&d.minv)),
            ] {
                let e = rel(got, want);
                assert!(e < TOL, "{robot} state {k}: {name} off by {e:e}");
            }
        }
    }
    assert_eq!(
        with_wrenches, 30,
        "half of the 60 states carry external wrenches"
    );
}
