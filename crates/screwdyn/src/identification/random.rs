//! Deterministic random numbers for the identification experiments: random states for the base
//! parameters, Fourier coefficients, torque noise ([`SplitMix64`](crate::model::SplitMix64)).

use crate::model::Model;

/// The generator every experiment draws from (shared with random configurations).
pub(super) use crate::model::SplitMix64 as SplitMix;

/// Position range of a joint for random states: its limits, clamped to `[−π, π]` when wider.
pub(super) fn joint_range(model: &Model, i: usize) -> (f64, f64) {
    let l = &model.joints()[i].limits;
    let pi = std::f64::consts::PI;
    let lo = if l.lower.is_finite() {
        l.lower.max(-pi)
    } else {
        -pi
    };
    let hi = if l.upper.is_finite() {
        l.upper.min(pi)
    } else {
        pi
    };
    if hi > lo {
        (lo, hi)
    } else {
        (-pi, pi)
    }
}
