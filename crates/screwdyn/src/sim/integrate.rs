//! Time integration of `q̈ = f(t, q, q̇)`: semi-implicit (symplectic) Euler, classic
//! Runge–Kutta 4 (by hand: "Integrating q̈ to find q̇ and q (Runge-Kutta)"), and adaptive
//! Dormand–Prince 5(4).

use crate::error::{Error, Result};

/// The integration scheme.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Integrator {
    /// `q̇ ← q̇ + h q̈(q, q̇)`, then `q ← q + h q̇`: first order, symplectic (bounded energy error).
    SymplecticEuler,
    /// Classic fourth-order Runge–Kutta with a fixed step.
    Rk4,
    /// Dormand–Prince 5(4) with error control: steps adapt so that each step's local error
    /// stays below `atol + rtol·|x|` (per component); output is still reported every `dt`.
    DormandPrince {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
}

impl std::str::FromStr for Integrator {
    type Err = crate::Error;
    fn from_str(s: &str) -> std::result::Result<Self, crate::Error> {
        match crate::error::choice_key(s).as_str() {
            "euler" | "symplectic-euler" => Ok(Integrator::SymplecticEuler),
            "rk4" => Ok(Integrator::Rk4),
            "dopri5" | "dormand-prince" => Ok(Integrator::DormandPrince {
                rtol: 1e-8,
                atol: 1e-10,
            }),
            _ => Err(crate::Error::UnknownChoice {
                what: "integrator",
                got: s.into(),
                expected: "euler, rk4 or dopri5",
            }),
        }
    }
}

/// The acceleration function: writes `q̈` for time `t`, position `q`, velocity `v`.
pub type AccelFn<'a> = dyn FnMut(f64, &[f64], &[f64], &mut [f64]) -> Result<()> + 'a;

/// Buffers for one integrator, allocated once for `n` coordinates.
#[derive(Clone, Debug)]
pub struct Stepper {
    integrator: Integrator,
    k: Vec<Vec<f64>>,
    qs: Vec<f64>,
    vs: Vec<f64>,
    q5: Vec<f64>,
    v5: Vec<f64>,
    /// Dormand–Prince's current internal step (adapted).
    h_adaptive: f64,
    /// Number of accepted and rejected internal steps so far.
    pub steps: (usize, usize),
}

// Dormand–Prince 5(4) tableau (published coefficients).
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
const B5: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
const B4: [f64; 7] = [
    5179.0 / 57600.0,
    0.0,
    7571.0 / 16695.0,
    393.0 / 640.0,
    -92097.0 / 339200.0,
    187.0 / 2100.0,
    1.0 / 40.0,
];

impl Integrator {
    /// Checks the scheme's settings: Dormand–Prince tolerances finite, non-negative and not
    /// both zero (the fixed-step schemes have none).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `rtol` and `atol`.
    ///
    /// ```
    /// use screwdyn::sim::Integrator;
    /// assert!(Integrator::DormandPrince { rtol: 1e-8, atol: 0.0 }.validate().is_ok());
    /// assert!(Integrator::DormandPrince { rtol: 0.0, atol: 0.0 }.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        if let Integrator::DormandPrince { rtol, atol } = *self {
            let ok = |x: f64| x.is_finite() && x >= 0.0;
            if !(ok(rtol) && ok(atol) && rtol + atol > 0.0) {
                return Err(Error::InvalidArgument(format!(
                    "Dormand–Prince tolerances must be finite, non-negative and not both zero (got rtol = {rtol}, atol = {atol})"
                )));
            }
        }
        Ok(())
    }
}

impl Stepper {
    /// Buffers for `n` coordinates.
    ///
    /// # Errors
    /// As [`Integrator::validate`].
    ///
    /// ```
    /// use screwdyn::sim::{Integrator, Stepper};
    /// assert!(Stepper::new(Integrator::Rk4, 2).is_ok());
    /// assert!(Stepper::new(Integrator::DormandPrince { rtol: f64::NAN, atol: 1e-9 }, 2).is_err());
    /// ```
    pub fn new(integrator: Integrator, n: usize) -> Result<Self> {
        integrator.validate()?;
        Ok(Stepper {
            integrator,
            // Stage derivatives: for the first-order system x = (q, v), ẋ = (v, q̈):
            // k[s] holds q̇ (first n) and q̈ (last n) of stage s.
            k: vec![vec![0.0; 2 * n]; 7],
            qs: vec![0.0; n],
            vs: vec![0.0; n],
            q5: vec![0.0; n],
            v5: vec![0.0; n],
            h_adaptive: 0.0,
            steps: (0, 0),
        })
    }

    /// Advances `(q, v)` from `t` to `t + dt` (one step, or adaptive sub-steps for
    /// Dormand–Prince).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `q` or `v` do not have the stepper's length, or `t`, `dt`
    /// are not finite (`dt` positive); any error of `f`.
    pub fn advance(
        &mut self,
        f: &mut AccelFn,
        t: f64,
        dt: f64,
        q: &mut [f64],
        v: &mut [f64],
    ) -> Result<()> {
        self.check_step(t, dt, q, v)?;
        self.advance_after_checks(f, t, dt, q, v)
    }

    /// [`Stepper::advance`] for the simulator's plant, whose `f` takes a fifth argument:
    /// whether the stepper has checked that the state `(q, v)` it hands over is finite (RK4
    /// forms each stage's state and checks it in one loop; the other schemes pass `false`).
    /// `checked` says whether the caller's `(q, v)` is known finite; returns whether the new
    /// state is (known) finite, for the next step's `checked`.
    ///
    /// # Errors
    /// As [`Stepper::advance`].
    pub(crate) fn advance_checked<F>(
        &mut self,
        f: &mut F,
        t: f64,
        dt: f64,
        (q, v): (&mut [f64], &mut [f64]),
        checked: bool,
    ) -> Result<bool>
    where
        F: FnMut(f64, &[f64], &[f64], &mut [f64], bool) -> Result<()>,
    {
        self.check_step(t, dt, q, v)?;
        match self.integrator {
            Integrator::Rk4 => {
                let finite = self.rk4(f, t, dt, q, v, checked)?;
                self.steps.0 += 1;
                Ok(finite)
            }
            _ => {
                let mut f = |t, q: &[f64], v: &[f64], qdd: &mut [f64]| f(t, q, v, qdd, false);
                self.advance_after_checks(&mut f, t, dt, q, v)?;
                Ok(false)
            }
        }
    }

    /// The checks of [`Stepper::advance`]: the lengths of `q`, `v`, and finite `t`, `dt > 0`.
    fn check_step(&self, t: f64, dt: f64, q: &[f64], v: &[f64]) -> Result<()> {
        let n = self.qs.len();
        if q.len() != n || v.len() != n {
            return Err(Error::InvalidArgument(format!(
                "the stepper was made for {n} joints, but q has {} and q̇ {} values",
                q.len(),
                v.len()
            )));
        }
        if !(dt > 0.0 && dt.is_finite() && t.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "a step needs a finite time and a positive finite step (got t = {t}, dt = {dt})"
            )));
        }
        Ok(())
    }

    /// [`Stepper::advance`] after [`Stepper::check_step`].
    fn advance_after_checks(
        &mut self,
        f: &mut AccelFn,
        t: f64,
        dt: f64,
        q: &mut [f64],
        v: &mut [f64],
    ) -> Result<()> {
        match self.integrator {
            Integrator::SymplecticEuler => {
                let n = q.len();
                let acc = &mut self.k[0][n..];
                f(t, q, v, acc)?;
                for i in 0..n {
                    v[i] += dt * acc[i];
                    q[i] += dt * v[i];
                }
                self.steps.0 += 1;
                Ok(())
            }
            Integrator::Rk4 => {
                self.rk4(&mut |t, q, v, qdd, _| f(t, q, v, qdd), t, dt, q, v, false)?;
                self.steps.0 += 1;
                Ok(())
            }
            Integrator::DormandPrince { rtol, atol } => self.dopri(f, t, dt, q, v, rtol, atol),
        }
    }

    /// Evaluates stage `s` at `(t, qs, vs)`.
    fn stage(&mut self, f: &mut AccelFn, s: usize, t: f64) -> Result<()> {
        let n = self.qs.len();
        let (qd, qdd) = self.k[s].split_at_mut(n);
        qd.copy_from_slice(&self.vs);
        f(t, &self.qs, &self.vs, qdd)
    }

    /// Sets `(qs, vs) = (q, v) + h Σ_j a_j k_j`.
    fn combine(&mut self, q: &[f64], v: &[f64], h: f64, a: &[f64]) {
        let n = q.len();
        for i in 0..n {
            let (mut dq, mut dv) = (0.0, 0.0);
            for (j, &aj) in a.iter().enumerate() {
                if aj != 0.0 {
                    dq += aj * self.k[j][i];
                    dv += aj * self.k[j][n + i];
                }
            }
            self.qs[i] = q[i] + h * dq;
            self.vs[i] = v[i] + h * dv;
        }
    }

    /// The classic Runge–Kutta step on `ẋ = (q̇, q̈)`: `k_1 = f(t, x)`,
    /// `k_2 = f(t + h/2, x + h/2 k_1)`, `k_3 = f(t + h/2, x + h/2 k_2)`, `k_4 = f(t + h, x + h k_3)`,
    /// `x ← x + h/6 (k_1 + 2k_2 + 2k_3 + k_4)`. Each stage needs only the one before it, so the
    /// stage states are formed directly rather than by the general tableau sum of `combine`.
    /// The `q̇` half of stage `s`'s derivative is the stage's own velocity, so it is written once,
    /// into `k[s][..n]`, and `f` reads it there (the first stage reads `(q, v)` in place).
    ///
    /// `f`'s fifth argument says whether the stage state is known finite: `checked` for the
    /// first stage (the caller's state), and for the later ones whether the loop that formed
    /// them found every entry finite. Returns whether the new `(q, v)` is finite (checked in the
    /// loop that sums it).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn rk4<F>(
        &mut self,
        f: &mut F,
        t: f64,
        h: f64,
        q: &mut [f64],
        v: &mut [f64],
        checked: bool,
    ) -> Result<bool>
    where
        F: FnMut(f64, &[f64], &[f64], &mut [f64], bool) -> Result<()>,
    {
        let n = q.len();
        let Stepper { k, qs, .. } = self;
        let qs = &mut qs[..n];
        let [k0, k1, k2, k3, ..] = &mut k[..] else {
            unreachable!("Stepper::new makes seven stages")
        };
        // Stage 1 at (q, v) itself: its q̇ is `v`, read in place.
        f(t, q, v, &mut k0[n..2 * n], checked)?;
        rk4_stage(f, t, h, 0.5, (q, v), (v, &k0[n..2 * n]), qs, k1)?;
        let (qd, qdd) = k1.split_at(n);
        rk4_stage(f, t, h, 0.5, (q, v), (qd, qdd), qs, k2)?;
        let (qd, qdd) = k2.split_at(n);
        rk4_stage(f, t, h, 1.0, (q, v), (qd, qdd), qs, k3)?;
        let (k1, k2, k3) = (&k1[..2 * n], &k2[..2 * n], &k3[..2 * n]);
        let (k0, v) = (&k0[n..2 * n], &mut v[..n]);
        let mut flags = 0;
        for i in 0..n {
            q[i] += h / 6.0 * (v[i] + 2.0 * k1[i] + 2.0 * k2[i] + k3[i]);
            v[i] += h / 6.0 * (k0[i] + 2.0 * k1[n + i] + 2.0 * k2[n + i] + k3[n + i]);
            flags |= non_finite_flag(q[i]) | non_finite_flag(v[i]);
        }
        Ok(all_finite(flags))
    }

    #[allow(clippy::too_many_arguments)]
    fn dopri(
        &mut self,
        f: &mut AccelFn,
        t0: f64,
        dt: f64,
        q: &mut [f64],
        v: &mut [f64],
        rtol: f64,
        atol: f64,
    ) -> Result<()> {
        let n = q.len();
        let t_end = t0 + dt;
        let mut t = t0;
        if self.h_adaptive <= 0.0 {
            self.h_adaptive = dt;
        }
        let mut guard = 0usize;
        while t < t_end - 1e-15 * t_end.abs().max(1.0) {
            guard += 1;
            if guard > 1_000_000 {
                return Err(Error::Numerical(format!(
                    "Dormand-Prince could not meet its tolerance near t = {t:.6} s (step size {:.3e} s)",
                    self.h_adaptive
                )));
            }
            let h = self.h_adaptive.min(t_end - t);
            for s in 0..7 {
                let a = A[s];
                self.combine(q, v, h, &a[..s.min(6)]);
                self.stage(f, s, t + C[s] * h)?;
            }
            // Fifth-order solution and the embedded fourth-order error estimate.
            let mut err: f64 = 0.0;
            for i in 0..2 * n {
                let (mut x5, mut x4) = (0.0, 0.0);
                for s in 0..7 {
                    x5 += B5[s] * self.k[s][i];
                    x4 += B4[s] * self.k[s][i];
                }
                let x0 = if i < n { q[i] } else { v[i - n] };
                let new = x0 + h * x5;
                let scale = atol + rtol * x0.abs().max(new.abs());
                err = err.max((h * (x5 - x4) / scale).abs());
                if i < n {
                    self.q5[i] = new;
                } else {
                    self.v5[i - n] = new;
                }
            }
            if !err.is_finite() {
                return Err(Error::Numerical(format!(
                    "the state became non-finite at t = {t:.6} s"
                )));
            }
            if err <= 1.0 {
                q.copy_from_slice(&self.q5);
                v.copy_from_slice(&self.v5);
                t += h;
                self.steps.0 += 1;
            } else {
                self.steps.1 += 1;
            }
            let factor = if err == 0.0 {
                5.0
            } else {
                (0.9 * err.powf(-0.2)).clamp(0.2, 5.0)
            };
            self.h_adaptive = h * factor;
        }
        Ok(())
    }
}

/// One later Runge–Kutta stage: `(q_s, q̇_s) = (q, q̇) + c h (q̇_prev, q̈_prev)`, then
/// `q̈_s = f(t + c h, q_s, q̇_s, finite)` with `finite` whether every entry of `(q_s, q̇_s)` is
/// finite (checked in the loop that forms them); `q̇_s` and `q̈_s` are written into `next` (its
/// two halves).
#[allow(clippy::too_many_arguments)]
#[inline]
fn rk4_stage<F>(
    f: &mut F,
    t: f64,
    h: f64,
    c: f64,
    (q, v): (&[f64], &[f64]),
    (qd_prev, qdd_prev): (&[f64], &[f64]),
    qs: &mut [f64],
    next: &mut [f64],
) -> Result<()>
where
    F: FnMut(f64, &[f64], &[f64], &mut [f64], bool) -> Result<()>,
{
    let n = q.len();
    let (vs, qdd) = next[..2 * n].split_at_mut(n);
    let (v, qd_prev, qdd_prev, qs) = (&v[..n], &qd_prev[..n], &qdd_prev[..n], &mut qs[..n]);
    let mut flags = 0;
    for i in 0..n {
        qs[i] = q[i] + h * (c * qd_prev[i]);
        vs[i] = v[i] + h * (c * qdd_prev[i]);
        flags |= non_finite_flag(qs[i]) | non_finite_flag(vs[i]);
    }
    f(t + c * h, qs, vs, qdd, all_finite(flags))
}

/// The exponent bits of `x` plus one unit of the exponent: the sign bit of the sum is set
/// exactly when the exponent is all ones (`x` is ±∞ or NaN). OR-ed over a vector (integer
/// operations, which the compiler vectorises with the loop that forms the values) and read by
/// [`all_finite`].
#[inline(always)]
pub(super) fn non_finite_flag(x: f64) -> u64 {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    (x.to_bits() & EXPONENT) + (1 << 52)
}

/// Whether no value whose [`non_finite_flag`] went into `flags` was ±∞ or NaN.
#[inline(always)]
pub(super) fn all_finite(flags: u64) -> bool {
    flags >> 63 == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flag_of_each_stage_state_says_whether_it_is_finite() {
        // RK4 hands `f` a flag with each stage state; it must be true exactly when every entry
        // of (q, q̇) is finite, as `f64::is_finite` says. Huge finite states whose stage sums
        // overflow to ±∞ (q + c h q̇ beyond f64::MAX), NaN and ±∞ entries, and ordinary ones.
        let big = f64::MAX / 1.5;
        let cases: [(&[f64], &[f64], f64); 6] = [
            (&[0.3, -1.2, 2.0], &[0.5, 0.0, -4.0], 1e-3),
            (&[big, 0.0, 0.0], &[big, 0.0, 0.0], 1.0),
            (&[0.0, -big, 1.0], &[0.0, -big, 0.0], 2.0),
            (&[0.0, 1.0, 2.0], &[f64::NAN, 0.0, 0.0], 1e-3),
            (&[f64::INFINITY, 1.0, 2.0], &[0.0; 3], 1e-3),
            (&[1.0, 2.0, 3.0], &[0.0, f64::NEG_INFINITY, 0.0], 1e-3),
        ];
        let mut overflowed = 0;
        for (q0, v0, h) in cases {
            let mut s = Stepper::new(Integrator::Rk4, 3).unwrap();
            let (mut q, mut v) = (q0.to_vec(), v0.to_vec());
            let start_finite = q0.iter().chain(v0).all(|x| x.is_finite());
            let mut seen = Vec::new();
            let mut f = |_t: f64, q: &[f64], v: &[f64], qdd: &mut [f64], checked: bool| {
                let finite = q.iter().chain(v).all(|x| x.is_finite());
                seen.push((checked, finite));
                // A constant acceleration, large enough to overflow the huge states' velocity.
                qdd.fill(big);
                Ok(())
            };
            let end = s
                .advance_checked(&mut f, 0.0, h, (&mut q, &mut v), start_finite)
                .unwrap();
            assert_eq!(seen.len(), 4);
            for (stage, &(checked, finite)) in seen.iter().enumerate() {
                assert_eq!(checked, finite, "stage {stage} of {q0:?}, {v0:?}");
            }
            assert_eq!(end, q.iter().chain(&v).all(|x| x.is_finite()));
            overflowed += usize::from(start_finite && seen.iter().any(|&(_, finite)| !finite));
        }
        // The two huge cases start finite and leave the finite numbers in a later stage.
        assert_eq!(overflowed, 2);
    }

    #[test]
    fn the_checked_step_is_the_step() {
        // `advance_checked` and `advance` take the same RK4 step, to the bit.
        let mut f = |_t: f64, q: &[f64], v: &[f64], qdd: &mut [f64]| {
            for i in 0..q.len() {
                qdd[i] = -9.81 * q[i].sin() - 0.1 * v[i];
            }
            Ok(())
        };
        let (mut a, mut b) = (
            Stepper::new(Integrator::Rk4, 2).unwrap(),
            Stepper::new(Integrator::Rk4, 2).unwrap(),
        );
        let (mut qa, mut va) = (vec![0.4, -1.0], vec![0.0, 2.0]);
        let (mut qb, mut vb) = (qa.clone(), va.clone());
        for k in 0..100 {
            let t = k as f64 * 1e-2;
            a.advance(&mut f, t, 1e-2, &mut qa, &mut va).unwrap();
            let mut g = |t, q: &[f64], v: &[f64], qdd: &mut [f64], _| f(t, q, v, qdd);
            assert!(b
                .advance_checked(&mut g, t, 1e-2, (&mut qb, &mut vb), true)
                .unwrap());
        }
        assert_eq!((qa, va), (qb, vb));
    }
}
