//! One Levenberg–Marquardt step with a secondary objective in the null space:
//! `Δθ = d + (Jᵀ J + λ I)⁻¹ Jᵀ (e − J d)`, on the weighted stacked Jacobian `J` and error `e`,
//! over the joints that are not locked (a locked joint's column of `J` is left out and its
//! step is zero).

/// Solves for the step: `normal` receives `Jᵀ J + λ I` and then its Cholesky factor, `step`
/// the step. `stacked` is `J` (`rows × cols`, row-major, `cols` the length of `step`), `error` is `e`, `secondary` is `d`
/// (all zeros for none), `locked[c]` leaves column `c` out (its step is 0). Returns `false` when `Jᵀ J + λ I` is not positive definite (only
/// possible with `λ = 0`).
///
/// With `d = 0` this is the damped least-squares step minimising `‖J Δθ − e‖² + λ ‖Δθ‖²`.
/// With `d ≠ 0` it is that step for the residual `e − J d`, plus `d`: the part of `d` in the
/// null space of `J` passes unchanged (it does not disturb the tasks), the rest is traded
/// against the tasks' error.
pub(super) fn step(
    stacked: &[f64],
    error: &[f64],
    lambda: f64,
    secondary: &[f64],
    locked: &[bool],
    normal: &mut [f64],
    step: &mut [f64],
) -> bool {
    let (rows, cols) = (error.len(), step.len());
    // normal = Jᵀ J + λ I (lower triangle), step = Jᵀ (e − J d), over the free columns; a
    // locked column's row and column are those of the identity, its right-hand side 0.
    for a in 0..cols {
        for b in 0..=a {
            let mut s = 0.0;
            if !(locked[a] || locked[b]) {
                for r in 0..rows {
                    s += stacked[r * cols + a] * stacked[r * cols + b];
                }
            }
            normal[a * cols + b] = s;
        }
        normal[a * cols + a] += if locked[a] { 1.0 } else { lambda };
        step[a] = 0.0;
    }
    for r in 0..rows {
        let row = &stacked[r * cols..(r + 1) * cols];
        let mut jd = 0.0;
        for c in 0..cols {
            if !locked[c] {
                jd += row[c] * secondary[c];
            }
        }
        let residual = error[r] - jd;
        for c in 0..cols {
            if !locked[c] {
                step[c] += row[c] * residual;
            }
        }
    }
    if !cholesky(normal, cols) {
        return false;
    }
    solve(normal, cols, step);
    for c in 0..cols {
        if !locked[c] {
            step[c] += secondary[c];
        }
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
        assert!(step(
            &j,
            &e,
            0.5,
            &[0.0; 2],
            &[false; 2],
            &mut normal,
            &mut x
        ));
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
            1e-3,
            &[1.0, -1.0],
            &[false; 2],
            &mut normal,
            &mut x
        ));
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] + 1.0).abs() < 1e-14);
    }

    /// A locked column does not move, and the others take the least-squares step of the
    /// system without it: J = [[1, 2], [0, 1], [3, 0]] with column 1 locked is the column
    /// (1, 0, 3), so Δθ₀ = (1·1 + 3·3) / (1 + 9 + λ).
    #[test]
    fn locked_column_is_left_out() {
        let j = [1.0, 2.0, 0.0, 1.0, 3.0, 0.0];
        let e = [1.0, 2.0, 3.0];
        let mut normal = [0.0; 4];
        let mut x = [0.0; 2];
        let d = [0.0, 0.7];
        assert!(step(&j, &e, 0.5, &d, &[false, true], &mut normal, &mut x));
        assert!((x[0] - 10.0 / 10.5).abs() < 1e-14, "{x:?}");
        assert_eq!(x[1], 0.0);
    }
}
