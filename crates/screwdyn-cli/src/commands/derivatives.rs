//! `derivatives`: the partial derivatives of inverse and forward dynamics at a state (issue 15).
//! The library does the work; this parses, calls and prints.

use super::inputs::{external_wrenches, load, names};
use super::states::run_states;
use crate::args::DerivativesArgs;
use crate::output::{Report, Value};
use crate::CliError;
use screwdyn::dynamics;
use screwdyn::Workspace;

/// `derivatives`: `dtau_dq`, `dtau_dv`, `dqdd_dq`, `dqdd_dv`, `minv` (rows: the differentiated
/// quantity, columns: the variable, both in joint order).
pub fn derivatives(a: &DerivativesArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let ext = external_wrenches(&m, &a.wrenches.wrench, &a.wrenches.tip_wrench)?;
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    let flags = [
        ("q", a.q.as_deref()),
        ("v", a.v.as_deref()),
        ("a", a.a.as_deref()),
    ];
    run_states(&m, &a.common, &flags, |s| {
        dynamics::rnea_derivatives(&m, &mut ws, &s.q, &s.v, &s.a, ext.as_ref())?;
        let (dq, dv) = (ws.dtau_dq.clone(), ws.dtau_dv.clone());
        // Forward dynamics at the torque that produces q̈ = a.
        let tau = ws.tau.as_slice().to_vec();
        dynamics::aba_derivatives(&m, &mut ws, &s.q, &s.v, &tau, ext.as_ref())?;
        let mut r = Report::new();
        r.add("joints", Value::Names(j.clone()))
            .add("tau", Value::joints(&j, &tau))
            .add("dtau_dq", Value::joint_matrix(&j, &dq))
            .add("dtau_dv", Value::joint_matrix(&j, &dv))
            .add("dqdd_dq", Value::joint_matrix(&j, &ws.dqdd_dq))
            .add("dqdd_dv", Value::joint_matrix(&j, &ws.dqdd_dv))
            .add("minv", Value::joint_matrix(&j, &ws.mass_matrix_inverse));
        Ok(r)
    })
}
