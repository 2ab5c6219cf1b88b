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
    /// Whether the rows of each point come in pairs `(α, β, γ)`, `(−α, −β, γ')` (the two signs
    /// of one limit), which share `1 / α` ([`split_rows`], [`largest_u`]).
    pub paired: bool,
    /// `x_max` per grid point.
    pub x_max: Vec<f64>,
}

impl Constraints {
    /// The rows of grid point `i`.
    pub(crate) fn at(&self, i: usize) -> &[[f64; 3]] {
        &self.rows[i * self.rows_per_point..(i + 1) * self.rows_per_point]
    }
}

/// Lines `m(x) = c0 + c1 x`, stored as two columns so that [`max_line`] runs down them in
/// independent lanes; the first `len` entries are in use.
#[derive(Default)]
struct Lines {
    c0: Vec<f64>,
    c1: Vec<f64>,
    len: usize,
}

impl Lines {
    /// Room for `n` lines, none in use.
    fn clear(&mut self, n: usize) {
        if self.c0.len() < n {
            self.c0.resize(n, 0.0);
            self.c1.resize(n, 0.0);
        }
        self.len = 0;
    }
    /// The lines in use: `(c0, c1)`.
    fn columns(&self) -> (&[f64], &[f64]) {
        (&self.c0[..self.len], &self.c1[..self.len])
    }
    fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// Scratch space of the projections, reused from interval to interval: the bounds on `u` as
/// lines in `x`, the upper ones negated (`u ≤ −m(x)`) and the lower ones as they are
/// (`u ≥ m(x)`), so that both envelopes are maxima.
#[derive(Default)]
struct Scratch {
    upper: Lines,
    lower: Lines,
}

/// The constraints of interval `i` (from `s_i` to `s_{i+1}`, step `Δ`), on `(u, x_i)`: the rows
/// of point `i` as they are, and the rows of point `i+1` at `x_{i+1} = x_i + 2 Δ u`
/// (`α u + β (x + 2Δu) ≤ γ`, TOPP-RA's first-order interpolation, which keeps the constant
/// `u` of the interval within the limits at both of its ends), and
/// `lo ≤ x + 2Δu ≤ hi` for the next controllable set. Sorted into upper bounds on `u`
/// (`α > 0`: `u ≤ γ/α − (β/α) x`, kept negated), lower bounds (`α < 0`:
/// `u ≥ γ/α − (β/α) x`); rows free of `u` narrow `[x_lo, x_hi]` directly.
fn split_rows(
    c: &Constraints,
    i: usize,
    delta: f64,
    next: (f64, f64),
    scratch: &mut Scratch,
) -> (f64, f64) {
    let room = 2 * c.rows_per_point + 2;
    scratch.upper.clear(room);
    scratch.lower.clear(room);
    let mut split = Split {
        upper: &mut scratch.upper,
        lower: &mut scratch.lower,
        n_upper: 0,
        n_lower: 0,
        x_lo: 0.0,
        x_hi: c.x_max[i],
    };
    // Plain loops rather than chained iterators: each compiles to a tight loop.
    if c.paired {
        for r in c.at(i).chunks_exact(2) {
            split.pair(r[0], r[1][2]);
        }
        for r in c.at(i + 1).chunks_exact(2) {
            let r0 = r[0];
            split.pair([r0[0] + 2.0 * delta * r0[1], r0[1], r0[2]], r[1][2]);
        }
    } else {
        for &r in c.at(i) {
            split.row(r);
        }
        for r in c.at(i + 1) {
            split.row([r[0] + 2.0 * delta * r[1], r[1], r[2]]);
        }
    }
    split.row([2.0 * delta, 1.0, next.1]);
    split.row([-2.0 * delta, -1.0, -next.0]);
    let (n_upper, n_lower, x_lo, x_hi) = (split.n_upper, split.n_lower, split.x_lo, split.x_hi);
    (scratch.upper.len, scratch.lower.len) = (n_upper, n_lower);
    (x_lo, x_hi)
}

/// The lines and the bounds on `x` of [`split_rows`] as they are collected.
struct Split<'a> {
    upper: &'a mut Lines,
    lower: &'a mut Lines,
    n_upper: usize,
    n_lower: usize,
    x_lo: f64,
    x_hi: f64,
}

impl Split<'_> {
    /// One row `α u + β x ≤ γ`.
    #[inline(always)]
    fn row(&mut self, r: [f64; 3]) {
        if !r[2].is_finite() {
            return;
        }
        if r[0] != 0.0 {
            // Written to both columns, kept by the one its sign picks: no branch to mispredict.
            let per_alpha = 1.0 / r[0];
            let (c0, c1) = (r[2] * per_alpha, -r[1] * per_alpha);
            (self.upper.c0[self.n_upper], self.upper.c1[self.n_upper]) = (-c0, -c1);
            (self.lower.c0[self.n_lower], self.lower.c1[self.n_lower]) = (c0, c1);
            let is_upper = r[0] > 0.0;
            self.n_upper += usize::from(is_upper);
            self.n_lower += usize::from(!is_upper);
        } else if r[1] > 0.0 {
            self.x_hi = self.x_hi.min(r[2] / r[1]);
        } else if r[1] < 0.0 {
            self.x_lo = self.x_lo.max(r[2] / r[1]);
        } else if r[2] < 0.0 {
            self.x_lo = f64::INFINITY;
        }
    }

    /// The rows `(α, β, γ)` and `(−α, −β, γ')`: one bound on `u` each way, from one division.
    /// With `g = γ / α`, `g' = γ' / α` and `d = β / α`, the upper bound (negated) is
    /// `(−g, d)` and the lower `(−g', −d)` for `α > 0`; `(g', d)` and `(g, −d)` for `α < 0`:
    /// the lines [`row`](Self::row) writes for the two rows, to the bit (negation is exact).
    #[inline(always)]
    fn pair(&mut self, r: [f64; 3], gamma_other: f64) {
        if r[0] == 0.0 || !r[2].is_finite() || !gamma_other.is_finite() {
            self.row(r);
            self.row([-r[0], -r[1], gamma_other]);
            return;
        }
        let per_alpha = 1.0 / r[0];
        let (g, g_other, d) = (r[2] * per_alpha, gamma_other * per_alpha, r[1] * per_alpha);
        let (upper, lower) = if r[0] > 0.0 {
            (-g, -g_other)
        } else {
            (g_other, g)
        };
        (self.upper.c0[self.n_upper], self.upper.c1[self.n_upper]) = (upper, d);
        (self.lower.c0[self.n_lower], self.lower.c1[self.n_lower]) = (lower, -d);
        self.n_upper += 1;
        self.n_lower += 1;
    }
}

/// The projection onto `x` of the polygon of interval `i`, or `None` when it is empty.
///
/// For a given `x`, `u` ranges over `[L(x), U(x)]` with `U(x) = min_p (γ_p − β_p x) / α_p`
/// over the upper bounds and `L(x) = max_n (γ_n − β_n x) / α_n` over the lower ones, so the
/// projection is `{x : F(x) ≤ 0}` for `F = L − U`, convex and piecewise linear: an interval,
/// whose ends are found by Newton's method on `F` (exact after as many steps as `F` has pieces
/// on the way, usually two or three), falling back to [`project_pairwise`] when it does not
/// settle.
fn project(
    c: &Constraints,
    i: usize,
    delta: f64,
    next: (f64, f64),
    scratch: &mut Scratch,
) -> Option<(f64, f64)> {
    let (x_lo, x_hi) = split_rows(c, i, delta, next, scratch);
    if scratch.upper.is_empty() || scratch.lower.is_empty() {
        return close_enough(x_lo, x_hi);
    }
    // F at the last point evaluated is kept: the upper end starts where the lower one settled.
    let last = std::cell::Cell::new((f64::NAN, (0.0, 0.0, 0.0)));
    let f = |x: f64| {
        let (at, value) = last.get();
        if at == x {
            return value;
        }
        let value = gap(&scratch.upper, &scratch.lower, x);
        last.set((x, value));
        value
    };
    // The lower end: Newton rightwards from x_lo while F > 0 there.
    let lo = match newton(f, x_lo, Direction::Right) {
        Settled::At(x) => x,
        // Empty (rare: the path is infeasible there) is left to the exact elimination, with
        // its round-off tolerance.
        _ => return project_pairwise(scratch, (x_lo, x_hi)),
    };
    // The upper end is near the next set's (neighbouring grid points): Newton starts there.
    match upper_end(f, lo, next.1, x_hi) {
        Settled::At(hi) => close_enough(lo, hi),
        _ => project_pairwise(scratch, (x_lo, x_hi)),
    }
}

/// The largest `x ≤ x_hi` with `F(x) ≤ 0`, given `F(lo) ≤ 0`: from `guess` (when it lies
/// between `lo` and `x_hi` and `F(guess) > 0`, the end is to its left: Newton leftwards from
/// there, usually one step), else rightwards from `lo` or the guess to the zero of the tangent
/// (at or beyond the end, since the tangent lies below `F`), or doubling where `F` does not
/// rise, until `F > 0`; then Newton leftwards.
fn upper_end(f: impl Fn(f64) -> (f64, f64, f64), lo: f64, guess: f64, x_hi: f64) -> Settled {
    let mut x = lo;
    if guess > lo && guess < x_hi {
        let (fx, _, scale) = f(guess);
        if fx > ROUND_OFF * scale {
            return newton(f, guess, Direction::Left);
        }
        x = guess;
    }
    for _ in 0..64 {
        let (fx, slope, scale) = f(x);
        if fx > ROUND_OFF * scale {
            return newton(f, x, Direction::Left);
        }
        if x >= x_hi {
            return Settled::At(x_hi);
        }
        let next = if slope > 0.0 {
            x - fx / slope
        } else {
            2.0 * x + 1.0
        };
        if next <= x + 4.0 * f64::EPSILON * x.abs() {
            return Settled::At(x);
        }
        x = next.min(x_hi);
    }
    Settled::Unsettled
}

/// `F(x) ≤ ROUND_OFF · max(|L|, |U|)` counts as `F(x) ≤ 0`: where `L = U` along a segment
/// (`K_N = {0}` pins `u = −x / 2Δ` on the last interval) their difference is round-off.
const ROUND_OFF: f64 = 1e-12;

/// `F(x) = L(x) − U(x)`, its slope on the active pieces, and `max(|L|, |U|)`: with the upper
/// bounds negated, `L = max m_lower(x)` and `U = −max m_upper(x)`.
fn gap(upper: &Lines, lower: &Lines, x: f64) -> (f64, f64, f64) {
    let (l, dl) = max_line(lower, x);
    let (minus_u, minus_du) = max_line(upper, x);
    (l + minus_u, dl + minus_du, l.abs().max(minus_u.abs()))
}

/// `max_k (c0_k + c1_k x)` and the slope `c1_k` of a line attaining it, in four independent
/// lanes (the lines are many and each step is short: one chain would wait on every compare),
/// compiled for AVX-512, AVX2 and the baseline, chosen at run time (the same operations, so the
/// same bits, in each).
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
fn max_line(lines: &Lines, x: f64) -> (f64, f64) {
    let (c0, c1) = lines.columns();
    let (mut best, mut slope) = ([f64::NEG_INFINITY; 4], [0.0; 4]);
    let (c0_4, c1_4) = (c0.chunks_exact(4), c1.chunks_exact(4));
    let tail = c0_4.remainder().iter().zip(c1_4.remainder());
    for (a, b) in c0_4.zip(c1_4) {
        // Whole four-lane arrays at each step, selects rather than branches: one vector
        // multiply, add, compare and two blends.
        let (a, b): (&[f64; 4], &[f64; 4]) = (a.try_into().unwrap(), b.try_into().unwrap());
        let v: [f64; 4] = std::array::from_fn(|l| a[l] + b[l] * x);
        let above: [bool; 4] = std::array::from_fn(|l| v[l] > best[l]);
        best = std::array::from_fn(|l| if above[l] { v[l] } else { best[l] });
        slope = std::array::from_fn(|l| if above[l] { b[l] } else { slope[l] });
    }
    for (a, b) in tail {
        let v = a + b * x;
        if v > best[0] {
            (best[0], slope[0]) = (v, *b);
        }
    }
    let mut top = 0;
    for lane in 1..4 {
        if best[lane] > best[top] {
            top = lane;
        }
    }
    (best[top], slope[top])
}

/// Where Newton's method on a convex `F` stops.
enum Settled {
    At(f64),
    Empty,
    Unsettled,
}

/// Which way [`newton`] searches.
#[derive(Clone, Copy, PartialEq)]
enum Direction {
    Left,
    Right,
}

/// Newton's method `x ← x − F(x) / F'(x)` from `x` towards the nearest point with `F ≤ 0` in
/// `direction`. The tangent of a convex `F` lies below it, so each step lands at or before that
/// point: none is skipped, and a tangent that does not lead towards 0 that way means there is
/// none (`Empty`).
fn newton(f: impl Fn(f64) -> (f64, f64, f64), mut x: f64, direction: Direction) -> Settled {
    for _ in 0..64 {
        let (fx, slope, scale) = f(x);
        if fx <= ROUND_OFF * scale {
            return Settled::At(x);
        }
        let towards = match direction {
            Direction::Right => slope < 0.0,
            Direction::Left => slope > 0.0,
        };
        if !fx.is_finite() || !slope.is_finite() {
            return Settled::Unsettled;
        }
        if !towards {
            return Settled::Empty;
        }
        let step = fx / slope;
        if step.abs() <= 4.0 * f64::EPSILON * x.abs() {
            return Settled::At(x);
        }
        x -= step;
    }
    Settled::Unsettled
}

/// The projection by Fourier–Motzkin elimination of `u`: each upper bound `u ≤ p0 + p1 x` and
/// lower bound `u ≥ n0 + n1 x` combine into `(n1 − p1) x ≤ p0 − n0`; `O(m²)` for `m` rows.
fn project_pairwise(scratch: &Scratch, (mut lo, mut hi): (f64, f64)) -> Option<(f64, f64)> {
    let ((u0, u1), (l0, l1)) = (scratch.upper.columns(), scratch.lower.columns());
    for (p0, p1) in u0.iter().zip(u1) {
        for (n0, n1) in l0.iter().zip(l1) {
            // The upper bound is u ≤ −p0 − p1 x (stored negated).
            let k = n1 + p1;
            let r = -p0 - n0;
            if k > 0.0 {
                hi = hi.min(r / k);
            } else if k < 0.0 {
                lo = lo.max(r / k);
            } else if r < 0.0 {
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
        let u_hi = largest_u(c, i, delta, next, x);
        let x_next = (x + 2.0 * delta * u_hi).clamp(next.0, next.1).max(0.0);
        out.u.push((x_next - x) / (2.0 * delta));
        out.x.push(x_next);
        x = x_next;
    }
    Ok(())
}

/// The largest `u` allowed on interval `i` at `x_i = x`: `min (γ − β x) / α` over the rows of
/// [`split_rows`] with `α > 0` (the same rows, without collecting them).
fn largest_u(c: &Constraints, i: usize, delta: f64, next: (f64, f64), x: f64) -> f64 {
    let mut u_hi = f64::INFINITY;
    let mut bound = |r: [f64; 3]| {
        let u = (r[2] - r[1] * x) / r[0];
        if r[0] > 0.0 && r[2].is_finite() && u < u_hi {
            u_hi = u;
        }
    };
    if c.paired {
        // Of the rows (α, β, γ) and (−α, −β, γ') only the one with a positive α bounds u
        // from above: one division per pair.
        let mut pair = |r: [f64; 3], gamma_other: f64| {
            if r[0] > 0.0 {
                bound(r);
            } else {
                bound([-r[0], -r[1], gamma_other]);
            }
        };
        for r in c.at(i).chunks_exact(2) {
            pair(r[0], r[1][2]);
        }
        for r in c.at(i + 1).chunks_exact(2) {
            let r0 = r[0];
            pair([r0[0] + 2.0 * delta * r0[1], r0[1], r0[2]], r[1][2]);
        }
    } else {
        for &r in c.at(i) {
            bound(r);
        }
        for r in c.at(i + 1) {
            bound([r[0] + 2.0 * delta * r[1], r[1], r[2]]);
        }
    }
    bound([2.0 * delta, 1.0, next.1]);
    bound([-2.0 * delta, -1.0, -next.0]);
    u_hi
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
            paired: false,
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
    fn newton_projection_matches_the_pairwise_elimination() {
        // Random intervals in the shape of TOPP-RA's (rows α u + β x ≤ γ of two grid points,
        // torque-like rows with γ > 0, a speed bound, the next controllable set): the ends
        // found by Newton's method equal the minimum and maximum over all pairs of rows.
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(27);
        let (mut nonempty, mut empty) = (0, 0);
        for case in 0..2000 {
            let k = rng.gen_range(1..12);
            let rows = (0..2 * k)
                .map(|_| {
                    [
                        rng.gen_range(-2.0..2.0),
                        rng.gen_range(-1.0..1.0),
                        rng.gen_range(-0.2..3.0),
                    ]
                })
                .collect();
            let x_max = if case % 3 == 0 {
                vec![f64::INFINITY; 2]
            } else {
                vec![rng.gen_range(0.5..20.0); 2]
            };
            let c = Constraints {
                rows,
                rows_per_point: k,
                paired: false,
                x_max,
            };
            let next = match case % 4 {
                0 => (0.0, 0.0),
                _ => (rng.gen_range(0.0..1.0), rng.gen_range(1.0..10.0)),
            };
            let delta = rng.gen_range(0.001..0.1);
            let mut scratch = Scratch::default();
            let newton = project(&c, 0, delta, next, &mut scratch);
            let (x_lo, x_hi) = split_rows(&c, 0, delta, next, &mut scratch);
            let pairwise = project_pairwise(&scratch, (x_lo, x_hi));
            match (newton, pairwise) {
                (Some(a), Some(b)) => {
                    nonempty += 1;
                    for (x, y) in [(a.0, b.0), (a.1, b.1)] {
                        assert!(
                            (x - y).abs() <= 1e-9 * y.abs().max(1.0) || x == y,
                            "case {case}: {a:?} against {b:?}"
                        );
                    }
                }
                (None, None) => empty += 1,
                (a, b) => panic!("case {case}: {a:?} against {b:?}"),
            }
        }
        assert!(
            nonempty > 500 && empty > 50,
            "{nonempty} sets, {empty} empty"
        );
    }

    #[test]
    fn paired_rows_give_the_lines_and_bounds_of_single_rows_to_the_bit() {
        // Rows (α, β, γ), (−α, −β, γ') as fill_constraints writes them, some with α = 0: the
        // paired split (one division per pair) and the row-by-row one give the same lines in
        // the same order, the same bounds on x and the same largest u.
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(26);
        for case in 0..500 {
            let k = rng.gen_range(1..8);
            let mut rows = Vec::new();
            for _ in 0..2 * k {
                let alpha = if rng.gen_range(0..6) == 0 {
                    0.0
                } else {
                    rng.gen_range(-2.0..2.0)
                };
                let beta = rng.gen_range(-1.0..1.0);
                rows.push([alpha, beta, rng.gen_range(0.1..3.0)]);
                rows.push([-alpha, -beta, rng.gen_range(0.1..3.0)]);
            }
            let x_max = vec![rng.gen_range(0.5..20.0); 2];
            let next = (rng.gen_range(0.0..1.0), rng.gen_range(1.0..10.0));
            let delta = rng.gen_range(0.001..0.1);
            let x = rng.gen_range(0.0..2.0);
            let [paired, single] = [true, false].map(|paired| Constraints {
                rows: rows.clone(),
                rows_per_point: 2 * k,
                paired,
                x_max: x_max.clone(),
            });
            let (mut a, mut b) = (Scratch::default(), Scratch::default());
            let bounds = split_rows(&paired, 0, delta, next, &mut a);
            assert_eq!(
                bounds,
                split_rows(&single, 0, delta, next, &mut b),
                "case {case}"
            );
            assert_eq!(a.upper.columns(), b.upper.columns(), "case {case}");
            assert_eq!(a.lower.columns(), b.lower.columns(), "case {case}");
            assert_eq!(
                largest_u(&paired, 0, delta, next, x).to_bits(),
                largest_u(&single, 0, delta, next, x).to_bits(),
                "case {case}"
            );
        }
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
            paired: false,
            x_max,
        };
        let mut p = Parameterization::default();
        assert_eq!(
            parameterize(&s, &c, &mut p).unwrap_err(),
            Infeasible { point: 3 }
        );
    }
}
