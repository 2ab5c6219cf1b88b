//! The first guess from the closed form: each solution's angles shifted by whole turns into
//! the joint limits, and the solution nearest `q0`.

use super::closed_form::ClosedForm;
use super::subproblems::wrap;
use std::f64::consts::TAU;

/// The angle `θ + 2π m` within `[lower, upper]` nearest `reference`, if any.
pub(super) fn shift_into_limits(theta: f64, reference: f64, lower: f64, upper: f64) -> Option<f64> {
    let near = reference + wrap(theta - reference);
    [near, near - TAU, near + TAU]
        .into_iter()
        .filter(|v| lower <= *v && *v <= upper)
        .min_by(|a, b| (a - reference).abs().total_cmp(&(b - reference).abs()))
}

/// Writes into `q` (which holds `q0`) the closed-form solution nearest `q0` among those that
/// fit the limits after whole-turn shifts; leaves `q` as it is when none fits.
pub(super) fn nearest_closed_form(
    cf: &ClosedForm,
    solutions: &[[f64; 6]],
    q0: &[f64],
    lower: &[f64],
    upper: &[f64],
    q: &mut [f64],
) {
    let joints = cf.joints();
    let mut best = f64::INFINITY;
    for theta in solutions {
        let mut shifted = [0.0; 6];
        let mut distance = 0.0;
        let mut fits = true;
        for k in 0..6 {
            let j = joints[k];
            match shift_into_limits(theta[k], q0[j], lower[j], upper[j]) {
                Some(v) => {
                    shifted[k] = v;
                    distance += (v - q0[j]) * (v - q0[j]);
                }
                None => fits = false,
            }
        }
        if fits && distance < best {
            best = distance;
            for k in 0..6 {
                q[joints[k]] = shifted[k];
            }
        }
    }
}
