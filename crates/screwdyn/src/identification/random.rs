//! Deterministic random numbers for the identification experiments: random states for the base
//! parameters, Fourier coefficients, torque noise.

use crate::model::Model;

/// SplitMix64: a small deterministic generator for the random states.
pub(super) struct SplitMix(pub(super) u64);

impl SplitMix {
    pub(super) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

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
