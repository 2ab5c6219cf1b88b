//! Deterministic random restarts: a SplitMix64 generator and the range each joint is drawn
//! from.

/// SplitMix64 (Steele, Lea & Flood 2014): 64 bits of state, the same stream for the same seed
/// on every machine.
#[derive(Clone, Copy, Debug)]
pub(super) struct SplitMix(u64);

impl SplitMix {
    /// The generator of `seed`, mixed with `stream` (a batch's target index), so that nearby
    /// seeds and streams give unrelated sequences.
    pub(super) fn new(seed: u64, stream: u64) -> SplitMix {
        let mut g = SplitMix(seed ^ stream.wrapping_mul(0xD1B5_4A32_D192_ED03));
        g.next();
        g
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub(super) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
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
