//! Joint-space paths `q(s)`: the [`Path`] trait that time-optimal timing needs (position and
//! its first two derivatives in the path parameter `s`) and the cubic spline through waypoints
//! with not-a-knot ends.

use crate::error::{Error, Result};
use crate::model::Model;

/// A joint-space path `q(s)` on `[s_start, s_end]` with its derivatives `q'(s) = dq/ds` and
/// `q''(s) = d²q/ds²`: anything the library can evaluate this way can be timed by
/// [`time_optimal`](super::time_optimal).
pub trait Path {
    /// Number of joints.
    fn nq(&self) -> usize;
    /// The range `(s_start, s_end)` of the path parameter, `s_start < s_end`.
    fn s_range(&self) -> (f64, f64);
    /// Writes `q(s)`, `q'(s)` and `q''(s)` into slices of length [`nq`](Path::nq) (which the
    /// caller guarantees); `s` is clamped to [`s_range`](Path::s_range).
    fn eval(&self, s: f64, q: &mut [f64], dq: &mut [f64], ddq: &mut [f64]);
}

/// The interpolating cubic spline through waypoints `q_k` at path parameters `s_k`, one cubic
/// per joint and segment, twice continuously differentiable, with **not-a-knot** ends (the
/// third derivative is also continuous at `s_1` and `s_{m−1}`, so the first two segments are one
/// cubic, and so are the last two: the ends carry no arbitrary condition). Two waypoints give a
/// straight line, three a parabola.
///
/// On segment `k`, with `t = s − s_k` and the second derivatives `M_k` at the knots,
/// `q(s) = q_k + β_k t + (M_k / 2) t² + (M_{k+1} − M_k)/(6 h_k) t³`, where
/// `h_k = s_{k+1} − s_k` and `β_k = (q_{k+1} − q_k)/h_k − h_k (2 M_k + M_{k+1})/6`; the `M_k`
/// solve the tridiagonal continuity equations
/// `h_{k−1} M_{k−1} + 2 (h_{k−1} + h_k) M_k + h_k M_{k+1} = 6 (δ_k − δ_{k−1})` (`δ_k` the slope
/// of segment `k`) with `M_0`, `M_m` eliminated by the not-a-knot conditions.
///
/// ```
/// use screwdyn::motion::{CubicSpline, Path};
/// // A cubic is reproduced exactly: q(s) = s³ through four points.
/// let s = [0.0, 1.0, 2.5, 3.0];
/// let points: Vec<Vec<f64>> = s.iter().map(|&x: &f64| vec![x.powi(3)]).collect();
/// let spline = CubicSpline::new(&s, &points).unwrap();
/// let (mut q, mut dq, mut ddq) = ([0.0], [0.0], [0.0]);
/// spline.eval(2.0, &mut q, &mut dq, &mut ddq);
/// assert!((q[0] - 8.0).abs() < 1e-12 && (dq[0] - 12.0).abs() < 1e-12 && (ddq[0] - 12.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CubicSpline {
    knots: Vec<f64>,
    /// `coefficients[k * nq + j] = [q, β, M/2, (ΔM)/(6h)]` of joint `j` on segment `k`.
    coefficients: Vec<[f64; 4]>,
    nq: usize,
}

impl CubicSpline {
    /// The spline through `points[k]` at `s[k]` (strictly increasing; at least two points).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for fewer than two points, a count of `s` values different
    /// from the number of points, waypoints of different lengths, or `s` not strictly
    /// increasing; [`Error::NonFinite`] for NaN or ∞.
    pub fn new(s: &[f64], points: &[Vec<f64>]) -> Result<Self> {
        check_waypoints(s, points)?;
        let nq = points[0].len();
        let m = s.len() - 1;
        let h: Vec<f64> = s.windows(2).map(|w| w[1] - w[0]).collect();
        let mut coefficients = Vec::with_capacity(m * nq);
        let mut second = vec![vec![0.0; m + 1]; nq];
        for (j, mj) in second.iter_mut().enumerate() {
            let y: Vec<f64> = points.iter().map(|p| p[j]).collect();
            not_a_knot_second_derivatives(&h, &y, mj);
        }
        for k in 0..m {
            for (j, mj) in second.iter().enumerate() {
                let (y0, y1) = (points[k][j], points[k + 1][j]);
                let (m0, m1) = (mj[k], mj[k + 1]);
                let hk = h[k];
                coefficients.push([
                    y0,
                    (y1 - y0) / hk - hk * (2.0 * m0 + m1) / 6.0,
                    0.5 * m0,
                    (m1 - m0) / (6.0 * hk),
                ]);
            }
        }
        Ok(CubicSpline {
            knots: s.to_vec(),
            coefficients,
            nq,
        })
    }

    /// The spline through `points` with `s` the cumulative chord length
    /// `s_k = Σ_{l<k} ‖q_{l+1} − q_l‖` (joint-space Euclidean distance), the usual choice when
    /// the waypoints carry no parameter.
    ///
    /// # Errors
    /// As [`CubicSpline::new`]; two consecutive equal waypoints make `s` non-increasing.
    ///
    /// ```
    /// use screwdyn::motion::{CubicSpline, Path};
    /// let p = CubicSpline::chord_length(&[vec![0.0, 0.0], vec![3.0, 4.0], vec![3.0, 5.0]]).unwrap();
    /// assert_eq!(p.s_range(), (0.0, 6.0));
    /// assert_eq!(p.knots(), &[0.0, 5.0, 6.0]);
    /// ```
    pub fn chord_length(points: &[Vec<f64>]) -> Result<Self> {
        let mut s = Vec::with_capacity(points.len());
        let mut total = 0.0;
        for (k, p) in points.iter().enumerate() {
            if k > 0 {
                let prev = &points[k - 1];
                if prev.len() == p.len() {
                    total += p
                        .iter()
                        .zip(prev)
                        .map(|(a, b)| (a - b) * (a - b))
                        .sum::<f64>()
                        .sqrt();
                }
            }
            s.push(total);
        }
        if let Some(k) = (1..s.len()).find(|&k| s[k] <= s[k - 1]) {
            return Err(Error::InvalidArgument(format!(
                "waypoints {} and {k} are equal, so the chord length does not increase between them (remove one)",
                k - 1
            )));
        }
        CubicSpline::new(&s, points)
    }

    /// The spline through joint-space waypoints of `model`: at `s` when given, else at the
    /// chord length ([`CubicSpline::chord_length`]); every waypoint must have one value per
    /// joint and lie within the joint position limits.
    ///
    /// # Errors
    /// As [`CubicSpline::new`]; [`Error::InvalidArgument`] for a waypoint of the wrong length or
    /// outside a joint's position limits (naming the waypoint and the joint).
    ///
    /// ```
    /// use screwdyn::motion::CubicSpline;
    /// let panda = screwdyn::builtin::load("panda").unwrap();
    /// let e = CubicSpline::for_model(&panda, None, &[vec![0.0; 7], vec![0.1; 7]]).unwrap_err();
    /// assert!(e.to_string().starts_with("waypoint 0: joint panda_joint4 = 0 is outside its position limits"));
    /// ```
    pub fn for_model(model: &Model, s: Option<&[f64]>, points: &[Vec<f64>]) -> Result<Self> {
        let names = model.joint_names();
        for (k, p) in points.iter().enumerate() {
            if p.len() != model.nq() {
                return Err(Error::InvalidArgument(format!(
                    "waypoint {k} has {} values, the model has {} joints: {}",
                    p.len(),
                    model.nq(),
                    names.join(", ")
                )));
            }
            for (j, joint) in model.joints().iter().enumerate() {
                let (lo, hi) = (joint.limits.lower, joint.limits.upper);
                if p[j] < lo || p[j] > hi {
                    return Err(Error::InvalidArgument(format!(
                        "waypoint {k}: joint {} = {} is outside its position limits [{lo}, {hi}]",
                        names[j], p[j]
                    )));
                }
            }
        }
        match s {
            Some(s) => CubicSpline::new(s, points),
            None => CubicSpline::chord_length(points),
        }
    }

    /// The path parameters `s_k` of the waypoints.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }
}

/// Checks the waypoints: at least two, as many `s` as points, equal lengths, finite, `s`
/// strictly increasing.
pub(crate) fn check_waypoints(s: &[f64], points: &[Vec<f64>]) -> Result<()> {
    if points.len() < 2 || s.len() != points.len() {
        return Err(Error::InvalidArgument(format!(
            "a path needs at least two waypoints with one s value each (got {} waypoints and {} s values)",
            points.len(),
            s.len()
        )));
    }
    let nq = points[0].len();
    if nq == 0 {
        return Err(Error::InvalidArgument(
            "the waypoints have no joint values".into(),
        ));
    }
    for (k, p) in points.iter().enumerate() {
        if p.len() != nq {
            return Err(Error::InvalidArgument(format!(
                "waypoint {k} has {} values, waypoint 0 has {nq}",
                p.len()
            )));
        }
        if let Some((j, x)) = p.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(Error::NonFinite {
                what: format!("waypoint {k}"),
                index: j,
                value: format!("{x:?}"),
            });
        }
    }
    if let Some((k, x)) = s.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(Error::NonFinite {
            what: "the path parameter s".into(),
            index: k,
            value: format!("{x:?}"),
        });
    }
    if let Some(k) = (1..s.len()).find(|&k| s[k] <= s[k - 1]) {
        return Err(Error::InvalidArgument(format!(
            "the path parameter s must increase strictly, but s = {} at waypoint {k} follows s = {} at waypoint {}",
            s[k],
            s[k - 1],
            k - 1
        )));
    }
    Ok(())
}

/// The second derivatives `M_0 … M_m` of the not-a-knot spline through `y` with knot spacings
/// `h` (written into `out`, length `m + 1`).
fn not_a_knot_second_derivatives(h: &[f64], y: &[f64], out: &mut [f64]) {
    let m = h.len();
    let slope = |k: usize| (y[k + 1] - y[k]) / h[k];
    match m {
        1 => out.fill(0.0),
        2 => {
            // One parabola through three points: M = 2 × the second divided difference.
            let c = 2.0 * (slope(1) - slope(0)) / (h[0] + h[1]);
            out.fill(c);
        }
        _ => {
            // Unknowns M_1 … M_{m−1}; rows k = 1 … m−1 of
            // h_{k−1} M_{k−1} + 2 (h_{k−1} + h_k) M_k + h_k M_{k+1} = 6 (δ_k − δ_{k−1}),
            // with M_0 = (1 + h_0/h_1) M_1 − (h_0/h_1) M_2 and the mirror image for M_m
            // substituted (third derivative continuous at s_1 and s_{m−1}).
            let rows = m - 1;
            let (mut sub, mut diag, mut sup, mut rhs) = (
                vec![0.0; rows],
                vec![0.0; rows],
                vec![0.0; rows],
                vec![0.0; rows],
            );
            for r in 0..rows {
                let k = r + 1;
                sub[r] = h[k - 1];
                diag[r] = 2.0 * (h[k - 1] + h[k]);
                sup[r] = h[k];
                rhs[r] = 6.0 * (slope(k) - slope(k - 1));
            }
            let (h0, h1) = (h[0], h[1]);
            diag[0] += h0 * (1.0 + h0 / h1);
            sup[0] -= h0 * h0 / h1;
            let (ha, hb) = (h[m - 2], h[m - 1]);
            diag[rows - 1] += hb * (1.0 + hb / ha);
            sub[rows - 1] -= hb * hb / ha;
            // Thomas algorithm (rows ≥ 2; the matrix is diagonally dominant).
            for r in 1..rows {
                let w = sub[r] / diag[r - 1];
                diag[r] -= w * sup[r - 1];
                rhs[r] -= w * rhs[r - 1];
            }
            out[rows] = rhs[rows - 1] / diag[rows - 1];
            for r in (0..rows - 1).rev() {
                out[r + 1] = (rhs[r] - sup[r] * out[r + 2]) / diag[r];
            }
            out[0] = (1.0 + h0 / h1) * out[1] - (h0 / h1) * out[2];
            out[m] = (1.0 + hb / ha) * out[m - 1] - (hb / ha) * out[m - 2];
        }
    }
}

impl Path for CubicSpline {
    fn nq(&self) -> usize {
        self.nq
    }
    fn s_range(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }
    fn eval(&self, s: f64, q: &mut [f64], dq: &mut [f64], ddq: &mut [f64]) {
        let (s0, s1) = self.s_range();
        let s = s.clamp(s0, s1);
        let segments = self.knots.len() - 1;
        // The segment k with s_k ≤ s (the last one for s = s_end).
        let k = (self.knots.partition_point(|&x| x <= s).max(1) - 1).min(segments - 1);
        let t = s - self.knots[k];
        let row = &self.coefficients[k * self.nq..(k + 1) * self.nq];
        for (j, c) in row.iter().enumerate() {
            q[j] = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
            dq[j] = c[1] + t * (2.0 * c[2] + t * 3.0 * c[3]);
            ddq[j] = 2.0 * c[2] + t * 6.0 * c[3];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval1(p: &CubicSpline, s: f64) -> (f64, f64, f64) {
        let (mut q, mut dq, mut ddq) = ([0.0], [0.0], [0.0]);
        p.eval(s, &mut q, &mut dq, &mut ddq);
        (q[0], dq[0], ddq[0])
    }

    #[test]
    fn not_a_knot_reproduces_every_cubic_on_uneven_knots() {
        // Not-a-knot interpolation is exact for cubics: f(s) = 2 − s + 0.5 s² − 0.3 s³.
        let f = |s: f64| {
            (
                2.0 - s + 0.5 * s * s - 0.3 * s * s * s,
                -1.0 + s - 0.9 * s * s,
                1.0 - 1.8 * s,
            )
        };
        for n in [4, 5, 9] {
            let s: Vec<f64> = (0..n).map(|k| (k as f64).powf(1.3) * 0.7 - 0.4).collect();
            let pts: Vec<Vec<f64>> = s.iter().map(|&x| vec![f(x).0]).collect();
            let p = CubicSpline::new(&s, &pts).unwrap();
            for i in 0..=50 {
                let x = s[0] + (s[n - 1] - s[0]) * i as f64 / 50.0;
                let (q, dq, ddq) = eval1(&p, x);
                let (fq, fd, fdd) = f(x);
                assert!((q - fq).abs() < 1e-11, "n = {n}, s = {x}: {q} vs {fq}");
                assert!((dq - fd).abs() < 1e-10 && (ddq - fdd).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn three_points_give_the_parabola_and_two_the_line() {
        let p = CubicSpline::new(&[0.0, 1.0, 3.0], &[vec![1.0], vec![2.0], vec![10.0]]).unwrap();
        // q = 1 + s² passes through (0, 1), (1, 2), (3, 10).
        let (q, dq, ddq) = eval1(&p, 2.0);
        assert!((q - 5.0).abs() < 1e-12 && (dq - 4.0).abs() < 1e-12 && (ddq - 2.0).abs() < 1e-12);
        let l = CubicSpline::new(&[1.0, 3.0], &[vec![1.0], vec![5.0]]).unwrap();
        assert_eq!(eval1(&l, 2.0), (3.0, 2.0, 0.0));
    }

    #[test]
    fn the_spline_is_twice_continuously_differentiable_at_knots() {
        let s = [0.0, 0.5, 1.7, 2.0, 3.1, 4.0];
        let pts: Vec<Vec<f64>> = [0.0, 1.0, -0.5, 0.2, 2.0, 1.0]
            .iter()
            .map(|&x| vec![x])
            .collect();
        let p = CubicSpline::new(&s, &pts).unwrap();
        for (k, &sk) in s.iter().enumerate() {
            assert!((eval1(&p, sk).0 - pts[k][0]).abs() < 1e-14);
        }
        for &sk in &s[1..5] {
            let (a, b) = (eval1(&p, sk - 1e-9), eval1(&p, sk + 1e-9));
            assert!(
                (a.1 - b.1).abs() < 1e-6 && (a.2 - b.2).abs() < 1e-6,
                "at {sk}: {a:?} {b:?}"
            );
        }
        // Not-a-knot: the third derivative (finite differences of q'') agrees across s_1.
        let third = |x: f64| (eval1(&p, x + 1e-4).2 - eval1(&p, x - 1e-4).2) / 2e-4;
        assert!((third(0.3) - third(0.9)).abs() < 1e-6);
    }

    #[test]
    fn bad_waypoints_are_refused_with_where() {
        let e = |s: &[f64], p: &[Vec<f64>]| CubicSpline::new(s, p).unwrap_err().to_string();
        assert!(e(&[0.0, 0.0], &[vec![0.0], vec![1.0]]).contains("increase strictly"));
        assert!(e(&[0.0], &[vec![0.0]]).contains("at least two"));
        assert!(e(&[0.0, 1.0], &[vec![0.0], vec![f64::NAN]]).contains("waypoint 1"));
        assert!(e(&[0.0, f64::NAN], &[vec![0.0], vec![1.0]]).contains("path parameter"));
        assert!(e(&[0.0, 1.0], &[vec![0.0], vec![1.0, 2.0]]).contains("waypoint 1 has 2"));
        let c = CubicSpline::chord_length(&[vec![0.0], vec![0.0]]).unwrap_err();
        assert!(c.to_string().contains("waypoints 0 and 1 are equal"));
    }
}
