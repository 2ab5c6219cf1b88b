//! Physical consistency of body parameters (the pseudo-inertia) and the physically consistent
//! estimate (Levenberg–Marquardt over log-Cholesky coordinates).

use super::base_parameters::BaseParameters;
use super::least_squares::LeastSquares;
use super::parameters::standard_parameters;
use crate::dynamics::pack_parameters;
use crate::error::{Error, Result};
use crate::model::Model;
use nalgebra::{DMatrix, DVector, Matrix4};

/// Pseudo-inertia `J = [½tr(I)1 − I, h; hᵀ, m]` of ten body parameters (`I` about the origin);
/// the body is physically consistent exactly when `J` is positive (semi)definite.
fn pseudo_inertia(p: &[f64]) -> Matrix4<f64> {
    let i = nalgebra::Matrix3::new(p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9]);
    let s = nalgebra::Matrix3::identity() * (0.5 * i.trace()) - i;
    let mut j = Matrix4::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&s);
    j[(0, 3)] = p[1];
    j[(1, 3)] = p[2];
    j[(2, 3)] = p[3];
    j[(3, 0)] = p[1];
    j[(3, 1)] = p[2];
    j[(3, 2)] = p[3];
    j[(3, 3)] = p[0];
    j
}

/// Ten body parameters of a pseudo-inertia (inverse of [`pseudo_inertia`]).
fn parameters_of_pseudo_inertia(j: &Matrix4<f64>) -> [f64; 10] {
    let s = j.fixed_view::<3, 3>(0, 0);
    // I = tr(Σ) 1 − Σ.
    let i = nalgebra::Matrix3::identity() * s.trace() - s;
    let h = nalgebra::Vector3::new(j[(0, 3)], j[(1, 3)], j[(2, 3)]);
    pack_parameters(j[(3, 3)], &h, &i)
}

/// Log-Cholesky coordinates (10 numbers) → pseudo-inertia `J = U Uᵀ`, `U` upper triangular
/// with diagonal `e^{θ}` (Rucker & Wensing 2022): every coordinate vector is a physically
/// consistent body, and every body with a positive-definite `J` has coordinates.
fn pseudo_inertia_of_log_cholesky(t: &[f64]) -> Matrix4<f64> {
    let u = Matrix4::new(
        t[0].exp(),
        t[4],
        t[5],
        t[6],
        0.0,
        t[1].exp(),
        t[7],
        t[8],
        0.0,
        0.0,
        t[2].exp(),
        t[9],
        0.0,
        0.0,
        0.0,
        t[3].exp(),
    );
    u * u.transpose()
}

/// Log-Cholesky coordinates of a positive-definite pseudo-inertia (its `U Uᵀ` factorisation).
fn log_cholesky_of_pseudo_inertia(j: &Matrix4<f64>) -> Option<[f64; 10]> {
    // U Uᵀ with U upper triangular: Cholesky of the row/column-reversed matrix.
    let rev = Matrix4::from_fn(|r, c| j[(3 - r, 3 - c)]);
    let l = rev.cholesky()?.l();
    let u = Matrix4::from_fn(|r, c| l[(3 - r, 3 - c)]);
    Some([
        u[(0, 0)].ln(),
        u[(1, 1)].ln(),
        u[(2, 2)].ln(),
        u[(3, 3)].ln(),
        u[(0, 1)],
        u[(0, 2)],
        u[(0, 3)],
        u[(1, 2)],
        u[(1, 3)],
        u[(2, 3)],
    ])
}

/// Whether ten body parameters describe a physically consistent body: positive mass and a
/// positive-semidefinite pseudo-inertia (to `1e-12` of its trace), which is the mass
/// distribution of a real body (Wensing, Kim & Slotine 2017); it implies the triangle
/// inequalities of the rotational inertia about the centre of mass.
pub fn is_physically_consistent(p: &[f64]) -> bool {
    let j = pseudo_inertia(p);
    let eig = j.symmetric_eigenvalues();
    let scale = j.trace().abs().max(f64::MIN_POSITIVE);
    p[0] > 0.0 && eig.iter().all(|e| *e >= -1e-12 * scale)
}

/// The physically consistent estimate: standard parameters `π` with every body's
/// pseudo-inertia positive definite (and friction coefficients non-negative) minimising
/// `‖R K π − z‖² + λ ‖D (π − π₀)‖²` — the torque least-squares cost of the log (`R`, `z` from
/// [`LeastSquares::factor`]) plus a small pull (`λ = 1e-6` relative) towards the model's own
/// parameters `π₀` that fixes the directions the log cannot see (`D` scales each parameter by
/// its body's mass and size). Solved by Levenberg–Marquardt over the log-Cholesky coordinates
/// of Rucker & Wensing (2022), 10 per body, and `fv = e^{θ}`, `fc = e^{θ}` per joint.
/// Returns the standard parameters; their base parameters are `K π`.
///
/// # Errors
/// `Numerical` when the iteration does not produce a finite cost.
pub fn physical_estimate(
    model: &Model,
    base: &BaseParameters,
    r: &DMatrix<f64>,
    z: &DVector<f64>,
) -> Result<DVector<f64>> {
    let nb = model.nbodies();
    let nj = model.nv();
    let friction = base.friction;
    let p = base.standard_names.len();
    let k = base.combination_matrix();
    let rk = r * &k;
    // Starting point and prior: the model's parameters, made strictly consistent.
    let pi0 = standard_parameters(model, friction);
    let mut theta = Vec::with_capacity(p);
    let mut scale = DVector::zeros(p);
    for b in 0..nb {
        let pb: Vec<f64> = pi0.rows(10 * b, 10).iter().copied().collect();
        let m = pb[0].abs().max(1e-3);
        let size = {
            let tr = pb[4] + pb[6] + pb[9];
            (tr / m).abs().sqrt().max(0.05)
        };
        let mut j = pseudo_inertia(&pb);
        j += Matrix4::identity() * (1e-6 * m * size * size);
        j[(3, 3)] += 1e-6 * m;
        let t = log_cholesky_of_pseudo_inertia(&j).unwrap_or_else(|| {
            let mut t = [0.0; 10];
            t[0] = (0.1 * size * m.sqrt()).ln();
            t[1] = t[0];
            t[2] = t[0];
            t[3] = m.sqrt().ln();
            t
        });
        theta.extend_from_slice(&t);
        scale[10 * b] = 1.0 / m;
        for c in 1..4 {
            scale[10 * b + c] = 1.0 / (m * size);
        }
        for c in 4..10 {
            scale[10 * b + c] = 1.0 / (m * size * size);
        }
    }
    if friction {
        for i in 0..nj {
            theta.push(pi0[10 * nb + 2 * i].max(1e-6).ln());
            theta.push(pi0[10 * nb + 2 * i + 1].max(1e-6).ln());
            scale[10 * nb + 2 * i] = 1.0;
            scale[10 * nb + 2 * i + 1] = 1.0;
        }
    }
    let to_standard = |t: &[f64]| -> DVector<f64> {
        let mut pi = DVector::zeros(p);
        for b in 0..nb {
            let j = pseudo_inertia_of_log_cholesky(&t[10 * b..10 * b + 10]);
            pi.rows_mut(10 * b, 10)
                .copy_from_slice(&parameters_of_pseudo_inertia(&j));
        }
        if friction {
            for c in 0..2 * nj {
                pi[10 * nb + c] = t[10 * nb + c].exp();
            }
        }
        pi
    };
    let data_scale = z.norm().max(1e-12);
    let lambda = 1e-6 * data_scale;
    let residual = |t: &[f64]| -> DVector<f64> {
        let pi = to_standard(t);
        let mut res = DVector::zeros(rk.nrows() + p);
        res.rows_mut(0, rk.nrows()).copy_from(&(&rk * &pi - z));
        let prior = (&pi - &pi0).component_mul(&scale) * lambda;
        res.rows_mut(rk.nrows(), p).copy_from(&prior);
        res
    };
    // Jacobian = [R K; λ D] ∂π/∂θ, with ∂π/∂θ block diagonal (10 × 10 per body by central
    // differences of the log-Cholesky map, e^θ on the friction diagonal).
    let mut lin = DMatrix::zeros(rk.nrows() + p, p);
    lin.rows_mut(0, rk.nrows()).copy_from(&rk);
    for c in 0..p {
        lin[(rk.nrows() + c, c)] = lambda * scale[c];
    }
    let dpi = |t: &[f64]| -> DMatrix<f64> {
        let mut d = DMatrix::zeros(p, p);
        for b in 0..nb {
            for c in 0..10 {
                let mut tp = [0.0; 10];
                tp.copy_from_slice(&t[10 * b..10 * b + 10]);
                let mut tm = tp;
                let h = 1e-6 * tp[c].abs().max(1.0);
                tp[c] += h;
                tm[c] -= h;
                let fp = parameters_of_pseudo_inertia(&pseudo_inertia_of_log_cholesky(&tp));
                let fm = parameters_of_pseudo_inertia(&pseudo_inertia_of_log_cholesky(&tm));
                for r in 0..10 {
                    d[(10 * b + r, 10 * b + c)] = (fp[r] - fm[r]) / (2.0 * h);
                }
            }
        }
        if friction {
            for c in 0..2 * nj {
                d[(10 * nb + c, 10 * nb + c)] = t[10 * nb + c].exp();
            }
        }
        d
    };
    let mut res = residual(&theta);
    let mut cost = res.norm_squared();
    let mut mu = 1e-3;
    for _ in 0..100 {
        let jac = &lin * dpi(&theta);
        let g = jac.tr_mul(&res);
        let h = jac.tr_mul(&jac);
        let mut improved = false;
        for _ in 0..20 {
            let mut a = h.clone();
            for i in 0..p {
                a[(i, i)] += mu * h[(i, i)].max(1e-12);
            }
            let Some(ch) = a.cholesky() else {
                mu *= 10.0;
                continue;
            };
            let step = ch.solve(&(-&g));
            let cand: Vec<f64> = theta.iter().zip(step.iter()).map(|(t, s)| t + s).collect();
            let r2 = residual(&cand);
            let c2 = r2.norm_squared();
            if c2.is_finite() && c2 < cost {
                let done = (cost - c2) <= 1e-10 * cost;
                theta = cand;
                res = r2;
                cost = c2;
                mu = (mu / 3.0).max(1e-12);
                improved = !done;
                break;
            }
            mu *= 10.0;
        }
        if !improved {
            break;
        }
    }
    if !cost.is_finite() {
        return Err(Error::Numerical(
            "the physically consistent estimate did not converge".into(),
        ));
    }
    Ok(to_standard(&theta))
}

/// The physically consistent estimate of a log: the standard parameters and their base
/// parameters (see [`LeastSquares::physical_estimate`]).
#[derive(Clone, Debug)]
pub struct PhysicalEstimate {
    /// Standard parameters `π` (every body physically consistent, friction non-negative).
    pub standard: DVector<f64>,
    /// Their base parameters `K π`, in the order of [`BaseParameters::expressions`].
    pub base_values: DVector<f64>,
}

impl LeastSquares {
    /// The physically consistent estimate of the samples added so far: [`physical_estimate`]
    /// on this problem's information factor ([`LeastSquares::factor`]), with the base
    /// parameters of the result.
    ///
    /// # Errors
    /// As [`physical_estimate`].
    ///
    /// ```
    /// use screwdyn::identification::*;
    /// let m = screwdyn::builtin::planar2();
    /// let base = BaseParameters::with_defaults(&m, false).unwrap();
    /// let mut ls = LeastSquares::new(&m, base.clone());
    /// let traj = FourierTrajectory::random(&m, 3, 1.0, 7).unwrap();
    /// excitation_log(&m, &traj, 10.0, 50.0, 0.0, 1, |_, q, v, a, tau| ls.add(&m, q, v, a, tau))
    ///     .unwrap();
    /// let est = ls.physical_estimate(&m).unwrap();
    /// // A noise-free log of a real robot: its own base parameters, every body consistent.
    /// let truth = base.base_values(&standard_parameters(&m, false));
    /// assert!((&est.base_values - &truth).amax() < 1e-3 * truth.amax());
    /// for b in 0..m.nbodies() {
    ///     assert!(is_physically_consistent(&est.standard.as_slice()[10 * b..10 * b + 10]));
    /// }
    /// ```
    pub fn physical_estimate(&mut self, model: &Model) -> Result<PhysicalEstimate> {
        let (r, z) = self.factor();
        let base = self.base();
        let standard = physical_estimate(model, base, &r, &z)?;
        Ok(PhysicalEstimate {
            base_values: base.base_values(&standard),
            standard,
        })
    }
}
