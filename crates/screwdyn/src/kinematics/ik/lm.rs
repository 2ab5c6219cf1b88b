//! One Levenberg–Marquardt step with a secondary objective in the null space:
//! `Δθ = d + (Jᵀ J + λ I)⁻¹ Jᵀ (e − J d)`, on the weighted stacked Jacobian `J` and error `e`.

/// Solves for the step: `normal` receives `Jᵀ J + λ I` and then its Cholesky factor, `step`
/// the step. `stacked` is `J` (`rows × cols`, row-major), `error` is `e`, `secondary` is `d`
/// (all zeros for none). Returns `false` when `Jᵀ J + λ I` is not positive definite (only
/// possible with `λ = 0`).
///
/// With `d = 0` this is the damped least-squares step minimising `‖J Δθ − e‖² + λ ‖Δθ‖²`.
/// With `d ≠ 0` it is that step for the residual `e − J d`, plus `d`: the part of `d` in the
/// null space of `J` passes unchanged (it does not disturb the tasks), the rest is traded
/// against the tasks' error.
pub(super) fn step(
    stacked: &[f64],
    error: &[f64],
    cols: usize,
    lambda: f64,
    secondary: &[f64],
    normal: &mut [f64],
    step: &mut [f64],
) -> bool {
    let rows = error.len();
    // normal = Jᵀ J + λ I (lower triangle), step = Jᵀ (e − J d).
    for a in 0..cols {
        for b in 0..=a {
            let mut s = 0.0;
            for r in 0..rows {
                s += stacked[r * cols + a] * stacked[r * cols + b];
            }
            normal[a * cols + b] = s;
        }
        normal[a * cols + a] += lambda;
        step[a] = 0.0;
    }
    for r in 0..rows {
        let row = &stacked[r * cols..(r + 1) * cols];
        let jd: f64 = row.iter().zip(secondary).map(|(j, d)| j * d).sum();
        let residual = error[r] - jd;
        for (s, j) in step.iter_mut().zip(row) {
            *s += j * residual;
        }
    }
    if !cholesky(normal, cols) {
        return false;
    }
    solve(normal, cols, step);
    for (s, d) in step.iter_mut().zip(secondary) {
        *s += d;
    }
    true
}

/// `A = L Lᵀ` in place on the lower triangle of `a` (`n × n`, row-major).
fn cholesky(a: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    true
}

/// Solves `L Lᵀ x = b` in place, `L` from [`cholesky`].
fn solve(l: &[f64], n: usize, b: &mut [f64]) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * n + k] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The step solves the normal equations: checked against the 2×2 inverse written out.
    #[test]
    fn damped_least_squares_of_a_small_system() {
        // J = [[1, 2], [0, 1], [3, 0]], e = (1, 2, 3), λ = 0.5.
        let j = [1.0, 2.0, 0.0, 1.0, 3.0, 0.0];
        let e = [1.0, 2.0, 3.0];
        let mut normal = [0.0; 4];
        let mut x = [0.0; 2];
        assert!(step(&j, &e, 2, 0.5, &[0.0; 2], &mut normal, &mut x));
        // JᵀJ + λI = [[10.5, 2], [2, 5.5]], Jᵀe = (10, 4).
        let det = 10.5 * 5.5 - 4.0;
        let expected = [
            (5.5 * 10.0 - 2.0 * 4.0) / det,
            (10.5 * 4.0 - 2.0 * 10.0) / det,
        ];
        assert!((x[0] - expected[0]).abs() < 1e-14 && (x[1] - expected[1]).abs() < 1e-14);
    }

    /// A secondary step in the null space of `J` passes through unchanged.
    #[test]
    fn null_space_step_passes_through() {
        // J = [1, 1] (one row), e = 0, d = (1, −1) ∈ null(J).
        let mut normal = [0.0; 4];
        let mut x = [0.0; 2];
        assert!(step(
            &[1.0, 1.0],
            &[0.0],
            2,
            1e-3,
            &[1.0, -1.0],
            &mut normal,
            &mut x
        ));
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] + 1.0).abs() < 1e-14);
    }
}
