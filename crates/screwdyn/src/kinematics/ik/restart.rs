//! Deterministic random restarts: a SplitMix64 generator and the range each joint is drawn
//! from.

use crate::model::SplitMix64;

/// The model's SplitMix64 generator ([`SplitMix64`]), started from a seed mixed with a stream:
/// the same draws for the same seed and stream on every machine.
#[derive(Clone, Debug)]
pub(super) struct SplitMix(SplitMix64);

impl SplitMix {
    /// The generator of `seed`, mixed with `stream` (a batch's target index), so that nearby
    /// seeds and streams give unrelated sequences.
    pub(super) fn new(seed: u64, stream: u64) -> SplitMix {
        let mut g = SplitMix64::new(seed ^ stream.wrapping_mul(0xD1B5_4A32_D192_ED03));
        g.next_u64();
        SplitMix(g)
    }

    /// Uniform in `[lo, hi)`.
    pub(super) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0.uniform(lo, hi)
    }
}

/// The range a restart draws a joint from: its limits where finite, else `[−π, π]` for a
/// rotation and `[−1, 1]` m for a translation, on the unbounded side(s).
pub(super) fn sample_range(lower: f64, upper: f64, rotates: bool) -> (f64, f64) {
    let span = if rotates { std::f64::consts::PI } else { 1.0 };
    match (lower.is_finite(), upper.is_finite()) {
        (true, true) => (lower, upper),
        (true, false) => (lower, lower + 2.0 * span),
        (false, true) => (upper - 2.0 * span, upper),
        (false, false) => (-span, span),
    }
}
