//! The Lagrangian coefficients: `D_ij` (inertia), `D_ijk` (centripetal and Coriolis,
//! Christoffel symbols of the first kind) and `D_i` (gravity), and effective inertias.

use super::crba::crba;
use super::rnea::gravity_torque;
use crate::error::{Error, Result};
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::{real, Real};
use crate::spatial::{ad, ad_matrix, Twist};
use crate::workspace::Workspace;
use nalgebra::{DMatrix, DVector, Matrix6};

/// The coefficients of the Lagrangian form
/// `τ_i = Σ_j D_ij q̈_j + Σ_j Σ_k D_ijk q̇_j q̇_k + D_i`.
#[derive(Clone, Debug)]
pub struct LagrangeCoefficients<T: Real = f64> {
    /// `D_ij = M_ij`: effective (`i = j`) and coupling inertias.
    pub d_ij: DMatrix<T>,
    /// `d_ijk[i][(j, k)] = D_ijk = ½(∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i)` (0-based indices).
    pub d_ijk: Vec<DMatrix<T>>,
    /// `D_i = g_i(q)`: gravity torques.
    pub d_i: DVector<T>,
}

impl<T: Real> LagrangeCoefficients<T> {
    /// `D_ijk` with 0-based `i, j, k`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when an index is not below `n`.
    ///
    /// ```
    /// use screwdyn::{builtin, dynamics::lagrange_coefficients};
    /// let c = lagrange_coefficients(&builtin::planar2(), &[0.0, 0.5]).unwrap();
    /// // By hand: D_112 = −m2 L1 L2 s2 (all ones here).
    /// assert!((c.d(0, 0, 1).unwrap() + 0.5_f64.sin()).abs() < 1e-12);
    /// assert!(c.d(0, 0, 2).is_err());
    /// ```
    pub fn d(&self, i: usize, j: usize, k: usize) -> Result<T> {
        let n = self.d_ijk.len();
        if i >= n || j >= n || k >= n {
            return Err(Error::InvalidArgument(format!(
                "D_ijk index ({i}, {j}, {k}) is out of range for {n} joints"
            )));
        }
        Ok(self.d_ijk[i][(j, k)])
    }
}

/// The largest model (in joints) for [`mass_matrix_derivatives`] and
/// [`lagrange_coefficients`]: they hold `n` dense `n × n` matrices and cost O(n⁴), teaching
/// quantities for small arms; a larger model is refused before anything is allocated.
pub const MAX_LAGRANGE_JOINTS: usize = 60;

/// `Err(InvalidArgument)` when `model` has more than `limit` joints for `what`.
pub(crate) fn check_size<T: Real>(model: &Model<T>, limit: usize, what: &str) -> Result<()> {
    if model.nq() > limit {
        return Err(Error::InvalidArgument(format!(
            "'{}' has {} joints, more than the limit of {limit} for {what}: use the recursive algorithms (crba, coriolis_matrix, rnea) on large models",
            model.name(),
            model.nq()
        )));
    }
    Ok(())
}

/// `∂M/∂q_k` for every `k`, analytically: in the base frame column `j` of every link Jacobian is
/// `s_j = Ad_{H_j^0} S_j`, with `∂s_j/∂q_k = ad_{s_k} s_j` when joint `k` strictly supports
/// joint `j` (zero otherwise), and the base-frame inertia of body `i` has
/// `∂𝔍_i/∂q_k = −(ad_{s_k}ᵀ 𝔍_i + 𝔍_i ad_{s_k})` when `k` supports `i`; differentiate
/// `M = Σ_i J_iᵀ 𝔍_i J_i` (Lynch & Park, *Modern Robotics*) term by term. O(n⁴); allocates.
///
/// # Errors
/// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a bad `q`.
///
/// ```
/// use screwdyn::{builtin, dynamics::mass_matrix_derivatives};
/// let m = builtin::planar2();
/// let q2 = 0.6_f64;
/// let dm = mass_matrix_derivatives(&m, &[0.2, q2]).unwrap();
/// // ∂M11/∂θ2 = −2 m2 l1 l2 sin θ2 (by hand: D11 = … + 2 m2 l1 l2 cos θ2).
/// assert!((dm[1][(0, 0)] + 2.0 * q2.sin()).abs() < 1e-12);
/// ```
pub fn mass_matrix_derivatives<T: Real>(model: &Model<T>, q: &[T]) -> Result<Vec<DMatrix<T>>> {
    check_size(
        model,
        MAX_LAGRANGE_JOINTS,
        "∂M/∂q and the Lagrangian coefficients (O(n⁴))",
    )?;
    let mut ws = Workspace::new(model);
    forward_kinematics(model, &mut ws, q)?;
    let n = model.nbodies();
    let s: Vec<Twist<T>> = (0..n)
        .map(|j| ws.pose_in_world[j].act_twist(&model.joints()[j].screw))
        .collect();
    let inertia: Vec<Matrix6<T>> = (0..n)
        .map(|i| {
            model.bodies()[i]
                .inertia
                .transformed(&ws.pose_in_world[i])
                .matrix()
        })
        .collect();
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let adk = ad_matrix(&s[k]);
        let mut dm = DMatrix::zeros(n, n);
        for (i, inertia_i) in inertia.iter().enumerate() {
            if !model.supports_unchecked(k, i) {
                continue;
            }
            let mut j_i = DMatrix::zeros(6, n);
            let mut dj_i = DMatrix::zeros(6, n);
            for j in 0..n {
                if model.supports_unchecked(j, i) {
                    j_i.set_column(j, &s[j]);
                    if j != k && model.supports_unchecked(k, j) {
                        dj_i.set_column(j, &ad(&s[k], &s[j]));
                    }
                }
            }
            let im = DMatrix::from_column_slice(6, 6, inertia_i.as_slice());
            let d_im_f = -(adk.transpose() * inertia_i + inertia_i * adk);
            let d_im = DMatrix::from_column_slice(6, 6, d_im_f.as_slice());
            let a = dj_i.transpose() * &im * &j_i;
            dm += &a + a.transpose() + j_i.transpose() * d_im * &j_i;
        }
        out.push(dm);
    }
    Ok(out)
}

/// The `D_ij`, `D_ijk` and `D_i` at `q`, with `D_ijk` the Christoffel symbols of the
/// first kind from the analytic `∂M/∂q` of [`mass_matrix_derivatives`].
///
/// # Errors
/// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a bad `q`.
///
/// ```
/// use screwdyn::{builtin, dynamics::lagrange_coefficients};
/// let m = builtin::planar2(); // m1 = m2 = l1 = l2 = 1
/// let q2 = 0.8_f64;
/// let d = lagrange_coefficients(&m, &[0.3, q2]).unwrap();
/// // By hand: D122 = D112 = −m2 l1 l2 sin θ2, D211 = m2 l1 l2 sin θ2, D111 = D222 = 0.
/// assert!((d.d(0, 1, 1).unwrap() + q2.sin()).abs() < 1e-12);
/// assert!((d.d(0, 0, 1).unwrap() + q2.sin()).abs() < 1e-12);
/// assert!((d.d(1, 0, 0).unwrap() - q2.sin()).abs() < 1e-12);
/// ```
pub fn lagrange_coefficients<T: Real>(
    model: &Model<T>,
    q: &[T],
) -> Result<LagrangeCoefficients<T>> {
    let dm = mass_matrix_derivatives(model, q)?;
    let n = model.nbodies();
    let half: T = real(0.5);
    let d_ijk = (0..n)
        .map(|i| {
            DMatrix::from_fn(n, n, |j, k| {
                (dm[k][(i, j)] + dm[j][(i, k)] - dm[i][(j, k)]) * half
            })
        })
        .collect();
    let mut ws = Workspace::new(model);
    let d_ij = crba(model, &mut ws, q)?.clone();
    let d_i = gravity_torque(model, &mut ws, q)?.clone();
    Ok(LagrangeCoefficients { d_ij, d_ijk, d_i })
}

/// The inertia felt at joint `joint` when the joints marked `free` are free (`τ = 0`) and the
/// others are locked (`q̈ = 0`), at rest without gravity: the Schur complement
/// `M_ii − M_iF M_FF⁻¹ M_Fi` (by hand: `D11 − D12²/D22` for the two-joint arm). `free[joint]`
/// is ignored. Allocates.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) for a joint index out of range or a set that does not include it; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch)/[`Error::NonFinite`](crate::Error::NonFinite) for a bad `q`; [`Error::Numerical`](crate::Error::Numerical) for a singular block of `M`.
///
/// ```
/// use screwdyn::{builtin, dynamics::effective_inertia, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let q = [0.0, std::f64::consts::FRAC_PI_2];
/// // The table at θ2 = 90°: 3 with joint 2 locked, 2 with joint 2 free.
/// assert!((effective_inertia(&m, &mut ws, &q, 0, &[false, false]).unwrap() - 3.0).abs() < 1e-12);
/// assert!((effective_inertia(&m, &mut ws, &q, 0, &[false, true]).unwrap() - 2.0).abs() < 1e-12);
/// ```
pub fn effective_inertia<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    joint: usize,
    free: &[bool],
) -> Result<T> {
    let n = model.nv();
    if joint >= n {
        return Err(Error::InvalidArgument(format!(
            "effective inertia of joint {joint}, but the model has {n} joints"
        )));
    }
    if free.len() != n {
        return Err(Error::DimensionMismatch {
            what: "the free-joint mask".into(),
            got: free.len(),
            expected: n,
            names: model.joint_names().join(", "),
        });
    }
    let m = crba(model, ws, q)?;
    let f: Vec<usize> = (0..n).filter(|&k| k != joint && free[k]).collect();
    let mii = m[(joint, joint)];
    if f.is_empty() {
        return Ok(mii);
    }
    let mff = DMatrix::from_fn(f.len(), f.len(), |a, b| m[(f[a], f[b])]);
    let mfi = DVector::from_fn(f.len(), |a, _| m[(f[a], joint)]);
    let chol = mff
        .cholesky()
        .ok_or_else(|| Error::Numerical("the mass matrix of the free joints is singular".into()))?;
    let x = chol.solve(&mfi);
    Ok(mii - mfi.dot(&x))
}

/// Effective inertia at `joint` with every other joint locked: `D_ii` (case ①).
///
/// # Errors
/// As [`effective_inertia`].
pub fn effective_inertia_locked<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    joint: usize,
) -> Result<T> {
    let none = vec![false; model.nv()];
    effective_inertia(model, ws, q, joint, &none)
}

/// Effective inertia at `joint` with every other joint free: `1 / (M⁻¹)_ii`, the Schur
/// complement of the case ② (`D11 − D12²/D22` for two joints).
///
/// # Errors
/// As [`effective_inertia`].
pub fn effective_inertia_free<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    joint: usize,
) -> Result<T> {
    let all = vec![true; model.nv()];
    effective_inertia(model, ws, q, joint, &all)
}
