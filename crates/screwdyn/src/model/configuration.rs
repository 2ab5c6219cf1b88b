//! Configurations to start from: the neutral configuration and random configurations within the
//! joint limits, drawn from a seeded deterministic generator.
//!
//! **Ranges.** Joint `i` is drawn uniformly from `[lo_i, hi_i]`: its position limits where they
//! are finite; an infinite bound is replaced by the default one, `∓π` for a revolute, continuous
//! or helical joint and `∓1 m` for a prismatic joint; when the finite bound lies beyond that
//! default (a lower limit of 5 rad and no upper one), the range is the finite bound and the
//! default width beyond it (`[5, 5 + 2π]`).
//!
//! **Neutral.** `q_i = 0`, or the point of `[lower_i, upper_i]` nearest zero when zero is
//! outside the limits (a joint whose limits are `[0.5, 2]` starts at `0.5`).

use super::joint::JointKind;
use super::model::Model;
use crate::error::{Error, Result};
use crate::scalar::{real, Real};

/// SplitMix64 (Steele, Lea and Flood 2014): a small deterministic generator, the same numbers
/// on every machine for a given seed. Random configurations and the identification
/// experiments draw from it.
///
/// ```
/// let mut a = screwdyn::model::SplitMix64::new(7);
/// let mut b = screwdyn::model::SplitMix64::new(7);
/// let x = a.uniform(-1.0, 1.0);
/// assert!((-1.0..1.0).contains(&x));
/// assert_eq!(x, b.uniform(-1.0, 1.0));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// The generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number drawn uniformly from `[lo, hi)` (53 random bits).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }
}

impl<T: Real> Model<T> {
    /// The neutral configuration: zero for every joint, or the point of the joint's position
    /// range nearest zero when zero is outside its limits (module docs).
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert_eq!(m.neutral(), vec![0.0, 0.0]);
    /// ```
    pub fn neutral(&self) -> Vec<T> {
        self.joints
            .iter()
            .map(|j| {
                // q_i = min(max(0, lower_i), upper_i)
                let zero = T::zero();
                let lo = if j.limits.lower > zero {
                    j.limits.lower
                } else {
                    zero
                };
                if lo > j.limits.upper {
                    j.limits.upper
                } else {
                    lo
                }
            })
            .collect()
    }

    /// The finite range `[lo_i, hi_i]` random configurations draw joint `i` from: its limits,
    /// with an infinite bound replaced by `∓π` (revolute, continuous, helical) or `∓1 m`
    /// (prismatic) (module docs).
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2(); // two revolute joints without limits
    /// let pi = std::f64::consts::PI;
    /// assert_eq!(m.configuration_ranges(), vec![(-pi, pi), (-pi, pi)]);
    /// ```
    pub fn configuration_ranges(&self) -> Vec<(T, T)> {
        self.joints
            .iter()
            .map(|j| {
                let half = match j.kind {
                    JointKind::Prismatic => T::one(),
                    _ => T::pi(),
                };
                let (lower, upper) = (j.limits.lower, j.limits.upper);
                match (lower.is_finite(), upper.is_finite()) {
                    (true, true) => (lower, upper),
                    (false, false) => (-half, half),
                    // [lower, max(half, lower + 2 half)]
                    (true, false) => (lower, upper_default(lower, half)),
                    (false, true) => (-upper_default(-upper, half), upper),
                }
            })
            .collect()
    }

    /// The configuration at the unit coordinates `u` (each in `[0, 1]`):
    /// `q_i = lo_i + u_i (hi_i − lo_i)` over [`configuration_ranges`](Self::configuration_ranges).
    /// Uniform `u` give a uniform random configuration, from any generator.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`] when `u` does not have one value per joint;
    /// [`Error::InvalidArgument`] for a value outside `[0, 1]` (or NaN), naming its position.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// let q = m.configuration_at(&[0.5, 1.0]).unwrap();
    /// assert_eq!(q, vec![0.0, std::f64::consts::PI]);
    /// assert!(m.configuration_at(&[0.5, 1.5]).is_err());
    /// ```
    pub fn configuration_at(&self, u: &[T]) -> Result<Vec<T>> {
        self.check_vector(u, "u")?;
        self.configurations_at(u)
    }

    /// [`configuration_at`](Self::configuration_at) for stacked rows: `u` holds `N` rows of
    /// `nq` unit coordinates one after the other; so do the configurations returned.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `u`'s length is not a multiple of `nq`, or for a value
    /// outside `[0, 1]` (or NaN), naming its row and joint.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// let q = m.configurations_at(&[0.5, 0.5, 0.0, 1.0]).unwrap();
    /// let pi = std::f64::consts::PI;
    /// assert_eq!(q, vec![0.0, 0.0, -pi, pi]);
    /// ```
    pub fn configurations_at(&self, u: &[T]) -> Result<Vec<T>> {
        let nq = self.nq();
        if nq == 0 || u.len() % nq != 0 {
            if u.is_empty() {
                return Ok(Vec::new());
            }
            return Err(Error::InvalidArgument(format!(
                "{} unit coordinates do not make rows of {nq} (one per joint)",
                u.len()
            )));
        }
        if let Some(k) = u.iter().position(|&x| !(x >= T::zero() && x <= T::one())) {
            return Err(Error::InvalidArgument(format!(
                "the unit coordinate of joint {} ('{}') in row {} is {:?}, outside [0, 1]",
                k % nq,
                self.joints[k % nq].name,
                k / nq,
                u[k]
            )));
        }
        let ranges = self.configuration_ranges();
        // q_i = lo_i + u_i (hi_i − lo_i)
        Ok(u.iter()
            .enumerate()
            .map(|(k, &x)| {
                let (lo, hi) = ranges[k % nq];
                lo + x * (hi - lo)
            })
            .collect())
    }

    /// A random configuration, uniform over [`configuration_ranges`](Self::configuration_ranges),
    /// drawn from `rng` (the same configurations for the same seed).
    ///
    /// ```
    /// use screwdyn::model::SplitMix64;
    /// let m = screwdyn::builtin::load("ur5").unwrap();
    /// let q = m.random_configuration(&mut SplitMix64::new(1));
    /// assert_eq!(q, m.random_configuration(&mut SplitMix64::new(1)));
    /// let ranges = m.configuration_ranges();
    /// assert!(q.iter().zip(&ranges).all(|(x, (lo, hi))| lo <= x && x <= hi));
    /// ```
    pub fn random_configuration(&self, rng: &mut SplitMix64) -> Vec<T> {
        self.random_configurations(rng, 1)
    }

    /// `n` random configurations stacked row after row (`n · nq` values), the rows the same as
    /// `n` calls of [`random_configuration`](Self::random_configuration).
    ///
    /// ```
    /// use screwdyn::model::SplitMix64;
    /// let m = screwdyn::builtin::planar2();
    /// let mut rng = SplitMix64::new(3);
    /// let rows = m.random_configurations(&mut SplitMix64::new(3), 2);
    /// assert_eq!(rows[..2], m.random_configuration(&mut rng)[..]);
    /// assert_eq!(rows[2..], m.random_configuration(&mut rng)[..]);
    /// ```
    pub fn random_configurations(&self, rng: &mut SplitMix64, n: usize) -> Vec<T> {
        let ranges = self.configuration_ranges();
        let mut q = Vec::with_capacity(n * ranges.len());
        for _ in 0..n {
            // q_i = lo_i + u (hi_i − lo_i), u uniform in [0, 1)
            q.extend(
                ranges
                    .iter()
                    .map(|&(lo, hi)| lo + real::<T>(rng.uniform(0.0, 1.0)) * (hi - lo)),
            );
        }
        q
    }
}

/// The default upper end above a finite `lower`: `half` (π or 1 m), or `lower + 2 half` when
/// `lower` is above `half`.
fn upper_default<T: Real>(lower: T, half: T) -> T {
    if lower < half {
        half
    } else {
        lower + half + half
    }
}
