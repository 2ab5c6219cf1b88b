//! The standard parameters `π` of a model (inertial, optionally friction), their names, and the
//! full regressor `Y` with friction columns: `τ = Y π`.

use crate::dynamics::{model_parameters, regressor, PARAMETERS_PER_BODY, PARAMETER_NAMES};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::workspace::Workspace;
use nalgebra::{DMatrix, DVector};

/// Names of the standard parameters, `<parameter>_<body>` (e.g. `m_upper_arm_link`,
/// `Izz_shoulder_link`), then `fv_<joint>`, `fc_<joint>` per joint when `friction`.
///
/// ```
/// let m = screwdyn::builtin::planar2();
/// let names = screwdyn::identification::parameter_names(&m, true);
/// assert_eq!(names.len(), 24);
/// assert_eq!(names[0], "m_link1");
/// assert_eq!(names[21], "fc_joint1");
/// ```
pub fn parameter_names(model: &Model, friction: bool) -> Vec<String> {
    let mut out = Vec::new();
    for b in model.bodies() {
        for p in PARAMETER_NAMES {
            out.push(format!("{p}_{}", b.name));
        }
    }
    if friction {
        for j in model.joints() {
            out.push(format!("fv_{}", j.name));
            out.push(format!("fc_{}", j.name));
        }
    }
    out
}

/// The model's standard parameters `π` (see the module docs), with the joints' `damping` and
/// `friction` coefficients as `fv`, `fc` when `friction`.
pub fn standard_parameters(model: &Model, friction: bool) -> DVector<f64> {
    let pi = model_parameters(model);
    if !friction {
        return pi;
    }
    let n = model.nv();
    let mut out = DVector::zeros(pi.len() + 2 * n);
    out.rows_mut(0, pi.len()).copy_from(&pi);
    for (i, j) in model.joints().iter().enumerate() {
        out[pi.len() + 2 * i] = j.damping;
        out[pi.len() + 2 * i + 1] = j.friction;
    }
    out
}

/// Number of standard parameters: `10 n`, plus `2 n` with friction.
pub fn parameter_count(model: &Model, friction: bool) -> usize {
    PARAMETERS_PER_BODY * model.nbodies() + if friction { 2 * model.nv() } else { 0 }
}

/// `sign(q̇)` as used by the Coulomb friction column (0 at rest).
pub(super) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The full regressor (n × [`parameter_count`]) at one state: [`regressor`] followed by the
/// friction columns (`q̇_i` and `sign(q̇_i)` in row `i`) when `friction`.
///
/// # Errors
/// As [`regressor`]; `out` of the wrong shape is an `InvalidArgument`.
pub fn full_regressor(
    model: &Model,
    ws: &mut Workspace,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    friction: bool,
    out: &mut DMatrix<f64>,
) -> Result<()> {
    let n = model.nv();
    let p = parameter_count(model, friction);
    if out.shape() != (n, p) {
        return Err(Error::InvalidArgument(format!(
            "the regressor buffer is {}×{}, it must be {n}×{p}",
            out.nrows(),
            out.ncols()
        )));
    }
    let y = regressor(model, ws, q, v, a)?;
    let inertial = PARAMETERS_PER_BODY * n;
    out.columns_mut(0, inertial).copy_from(y);
    if friction {
        out.columns_mut(inertial, 2 * n).fill(0.0);
        for i in 0..n {
            out[(i, inertial + 2 * i)] = v[i];
            out[(i, inertial + 2 * i + 1)] = sign(v[i]);
        }
    }
    Ok(())
}
