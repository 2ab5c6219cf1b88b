//! Reachability analysis on a grid in `s` (Pham & Pham 2018, TOPP-RA): with `u = s̈` and
//! `x = ṡ²`, every limit at a grid point is a linear inequality in `(u, x)`; the controllable
//! sets `K_i` (the `x_i` from which the end can still be reached at rest) are computed backward,
//! then the greedy forward pass takes the largest `u_i` that keeps `x_{i+1}` in `K_{i+1}`.

/// Which limit a constraint row comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitKind {
    /// `|q̇_j| ≤ vmax_j`.
    Velocity,
    /// `|q̈_j| ≤ amax_j`.
    Acceleration,
    /// `|τ_j| ≤ τmax_j`.
    Torque,
}

/// The linear constraints `α u + β x ≤ γ` at each grid point, and the speed bound
/// `x ≤ x_max` from the velocity limits.
#[derive(Clone, Debug, Default)]
pub(crate) struct Constraints {
    /// Rows `[α, β, γ]`, `rows_per_point` for each grid point (rows with `γ = ∞` are unused).
    pub rows: Vec<[f64; 3]>,
    pub rows_per_point: usize,
    /// `x_max` per grid point.
    pub x_max: Vec<f64>,
}

impl Constraints {
    fn at(&self, i: usize) -> &[[f64; 3]] {
        &self.rows[i * self.rows_per_point..(i + 1) * self.rows_per_point]
    }
}

/// Scratch space of the projections, reused from interval to interval.
#[derive(Default)]
struct Scratch {
    upper: Vec<[f64; 3]>,
    lower: Vec<[f64; 3]>,
}

/// The constraints of interval `i` (from `s_i` to `s_{i+1}`, step `Δ`), on `(u, x_i)`: the rows
/// of point `i` as they are, and the rows of point `i+1` at `x_{i+1} = x_i + 2 Δ u`
/// (`α u + β (x + 2Δu) ≤ γ`, TOPP-RA's first-order interpolation, which keeps the constant
/// `u` of the interval within the limits at both of its ends), and
/// `lo ≤ x + 2Δu ≤ hi` for the next controllable set. Sorted into upper bounds on `u`
/// (`α > 0`), lower bounds (`α < 0`); rows free of `u` narrow `[x_lo, x_hi]` directly.
fn split_rows(
    c: &Constraints,
    i: usize,
    delta: f64,
    next: (f64, f64),
    scratch: &mut Scratch,
) -> (f64, f64) {
    scratch.upper.clear();
    scratch.lower.clear();
    let (mut x_lo, mut x_hi) = (0.0_f64, c.x_max[i]);
    let here = c.at(i).iter().copied();
    let there = c
        .at(i + 1)
        .iter()
        .map(|r| [r[0] + 2.0 * delta * r[1], r[1], r[2]]);
    let ahead = [[2.0 * delta, 1.0, next.1], [-2.0 * delta, -1.0, -next.0]];
    for r in here.chain(there).chain(ahead) {
        if !r[2].is_finite() {
            continue;
        }
        if r[0] > 0.0 {
            scratch.upper.push(r);
        } else if r[0] < 0.0 {
            scratch.lower.push(r);
        } else if r[1] > 0.0 {
            x_hi = x_hi.min(r[2] / r[1]);
        } else if r[1] < 0.0 {
            x_lo = x_lo.max(r[2] / r[1]);
        } else if r[2] < 0.0 {
            x_lo = f64::INFINITY;
        }
    }
    (x_lo, x_hi)
}

/// The projection onto `x` of the polygon of interval `i` (Fourier–Motzkin elimination of `u`:
/// each upper bound `p` and lower bound `n` on `u` combine into
/// `(α_n β_p − α_p β_n) x ≥ α_n γ_p − α_p γ_n`), or `None` when it is empty.
fn project(
    c: &Constraints,
    i: usize,
    delta: f64,
    next: (f64, f64),
    scratch: &mut Scratch,
) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = split_rows(c, i, delta, next, scratch);
    for p in &scratch.upper {
        for n in &scratch.lower {
            let k = n[0] * p[1] - p[0] * n[1];
            let r = n[0] * p[2] - p[0] * n[2];
            if k > 0.0 {
                lo = lo.max(r / k);
            } else if k < 0.0 {
                hi = hi.min(r / k);
            } else if r > 0.0 {
                return None;
            }
        }
    }
    close_enough(lo, hi)
}

/// `[lo, hi]`, or `None` if empty beyond round-off (a sliver of `10⁻⁹` relative is closed).
fn close_enough(lo: f64, hi: f64) -> Option<(f64, f64)> {
    if lo <= hi {
        Some((lo, hi))
    } else if lo - hi <= 1e-9 * hi.abs().max(1e-9) {
        Some((hi, hi))
    } else {
        None
    }
}

/// The result of the two passes on one grid.
#[derive(Clone, Debug, Default)]
pub(crate) struct Parameterization {
    /// `x_i = ṡ²` at each grid point.
    pub x: Vec<f64>,
    /// `u_i = s̈` on each interval.
    pub u: Vec<f64>,
}

/// Where the two passes fail: the grid point whose controllable set is empty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Infeasible {
    pub point: usize,
}

/// Controllable sets backward from `K_N = {0}` (rest at the end), then the greedy forward pass
/// from `x_0 = 0` (rest at the start): `u_i = max { u : (u, x_i) feasible on interval i,
/// x_i + 2Δ_i u ∈ K_{i+1} }`, `x_{i+1} = x_i + 2Δ_i u_i`.
pub(crate) fn parameterize(
    s: &[f64],
    c: &Constraints,
    out: &mut Parameterization,
) -> Result<(), Infeasible> {
    let n = s.len() - 1;
    let mut scratch = Scratch::default();
    let mut sets = vec![(0.0, 0.0); n + 1];
    if c.x_max[n] < 0.0 {
        return Err(Infeasible { point: n });
    }
    for i in (0..n).rev() {
        let delta = s[i + 1] - s[i];
        sets[i] = project(c, i, delta, sets[i + 1], &mut scratch).ok_or(Infeasible { point: i })?;
    }
    if sets[0].0 > 0.0 {
        return Err(Infeasible { point: 0 });
    }
    out.x.clear();
    out.u.clear();
    out.x.push(0.0);
    let mut x = 0.0;
    for i in 0..n {
        let delta = s[i + 1] - s[i];
        let next = sets[i + 1];
        let (_, _) = split_rows(c, i, delta, next, &mut scratch);
        let u_hi = scratch
            .upper
            .iter()
            .map(|r| (r[2] - r[1] * x) / r[0])
            .fold(f64::INFINITY, f64::min);
        let x_next = (x + 2.0 * delta * u_hi).clamp(next.0, next.1).max(0.0);
        out.u.push((x_next - x) / (2.0 * delta));
        out.x.push(x_next);
        x = x_next;
    }
    Ok(())
}

/// The time on each interval, `Δt_i = 2 Δ_i / (√x_i + √x_{i+1})` (constant `s̈`), summed.
pub(crate) fn interval_times(s: &[f64], x: &[f64], times: &mut Vec<f64>) -> f64 {
    times.clear();
    times.push(0.0);
    let mut t = 0.0;
    for i in 0..s.len() - 1 {
        t += 2.0 * (s[i + 1] - s[i]) / (x[i].sqrt() + x[i + 1].sqrt());
        times.push(t);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pure_acceleration_limit_gives_the_bang_bang_parabola() {
        // |s̈| ≤ 1 on s ∈ [0, 1]: x = 2s up to the middle, then 2(1 − s); duration 2.
        let n = 100;
        let s: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
        let c = Constraints {
            rows: (0..=n)
                .flat_map(|_| [[1.0, 0.0, 1.0], [-1.0, 0.0, 1.0]])
                .collect(),
            rows_per_point: 2,
            x_max: vec![f64::INFINITY; n + 1],
        };
        let mut p = Parameterization::default();
        parameterize(&s, &c, &mut p).unwrap();
        for (i, &x) in p.x.iter().enumerate() {
            let expect = 2.0 * s[i].min(1.0 - s[i]);
            assert!(
                (x - expect).abs() < 1e-12,
                "x[{i}] = {x}, expected {expect}"
            );
        }
        let mut times = vec![];
        assert!((interval_times(&s, &p.x, &mut times) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn an_empty_set_names_its_grid_point() {
        // x ≤ −1 at point 3 (an impossible speed bound) empties K_3.
        let s: Vec<f64> = (0..=5).map(f64::from).collect();
        let mut x_max = vec![f64::INFINITY; 6];
        x_max[3] = -1.0;
        let c = Constraints {
            rows: vec![[1.0, 0.0, 1.0]; 6],
            rows_per_point: 1,
            x_max,
        };
        let mut p = Parameterization::default();
        assert_eq!(
            parameterize(&s, &c, &mut p).unwrap_err(),
            Infeasible { point: 3 }
        );
    }
}
