//! The Coriolis matrix `C(q, q̇)` by an O(n²) recursion, with `Ṁ − 2C` skew-symmetric.

use super::closed_form::bar_matrix;
use crate::error::Result;
use crate::kinematics::forward_velocity;
use crate::model::Model;
use crate::scalar::{real, Real};
use crate::spatial::{ad, ad_matrix};
use crate::workspace::Workspace;
use nalgebra::DMatrix;

/// The Coriolis matrix `C(q, q̇)` with `C q̇` the velocity-product torques of RNEA and
/// `C_ij = Σ_k Γ_ijk q̇_k` (Christoffel symbols of the first kind, the `D_ijk`), so that
/// `Ṁ − 2C` is skew-symmetric. Returns `ws.coriolis_matrix`.
///
/// The stacked closed form `C = Jᵀ 𝔍 J̇ − Jᵀ ad_Vᵀ 𝔍 J` (Lynch & Park, *Modern Robotics*) has the right product `C q̇`
/// but in general **not** a skew-symmetric `Ṁ − 2C` (the tests show it on random trees). With
/// `Ψ = J̇ + ad_V J` (the base-frame rate of the Jacobian columns, written in the link frames) it
/// reads `C = Jᵀ 𝔍 Ψ + Jᵀ(−𝔍 ad_V − ad_Vᵀ 𝔍) J`; this function replaces the per-body term by
/// `B(𝔍, V) = ½(−ad_Vᵀ 𝔍 − 𝔍 ad_V + (𝔍V)⊼)`, `(h)⊼ X = −ad_Xᵀ h` (the factorisation of
/// Echeandia & Wensing), which has the same product with `V` (because `ad_V V = 0`) and makes
/// `C` Christoffel-consistent
/// (see [`ClosedForm::c_christoffel`](super::ClosedForm)). Computed in the base frame, where
/// column `j` of every link Jacobian is the same screw `s_j = Ad_{H_j^0} S_j` with
/// `ṡ_j = ad_{V_j} s_j`, and subtree sums of `𝔍` and `B` (composite bodies) give
/// `C_kj = s_kᵀ(𝔍ᶜ_j ṡ_j + Bᶜ_j s_j)` for `k` supporting `j` and
/// `C_jk = (𝔍ᶜ_j s_j)ᵀ ṡ_k + (Bᶜ_jᵀ s_j)ᵀ s_k`: O(n²) on a tree.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::coriolis_matrix, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let (q2, qd1, qd2) = (0.7_f64, 0.3, -1.2);
/// let c = coriolis_matrix(&m, &mut ws, &[0.1, q2], &[qd1, qd2]).unwrap();
/// let cv = c * nalgebra::DVector::from_vec(vec![qd1, qd2]);
/// // Craig, *Introduction to Robotics*: [−m2L1L2 s2 θ̇2² − 2 m2L1L2 s2 θ̇1θ̇2, m2L1L2 s2 θ̇1²].
/// assert!((cv[0] - (-q2.sin() * qd2 * qd2 - 2.0 * q2.sin() * qd1 * qd2)).abs() < 1e-12);
/// assert!((cv[1] - q2.sin() * qd1 * qd1).abs() < 1e-12);
/// ```
pub fn coriolis_matrix<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
) -> Result<&'w DMatrix<T>> {
    forward_velocity(model, ws, q, v)?;
    ws.ensure_square()?;
    let n = model.nbodies();
    let half: T = real(0.5);
    for i in 0..n {
        let x = &ws.pose_in_world[i];
        let s = x.act_twist(&model.joints()[i].screw);
        let vs = x.act_twist(&ws.twist[i]);
        ws.screw_in_world[i] = s;
        ws.screw_rate_in_world[i] = ad(&vs, &s);
        let inertia = model.bodies()[i].inertia.transformed(x);
        let im = inertia.matrix();
        let adv = ad_matrix(&vs);
        ws.composite_coriolis_factor[i] =
            (bar_matrix(&inertia.apply(&vs)) - im * adv - adv.transpose() * im) * half;
        ws.composite_inertia_matrix[i] = im;
    }
    for i in (0..n).rev() {
        if let Some(p) = model.parents()[i] {
            let (ci, bi) = (
                ws.composite_inertia_matrix[i],
                ws.composite_coriolis_factor[i],
            );
            ws.composite_inertia_matrix[p] += ci;
            ws.composite_coriolis_factor[p] += bi;
        }
    }
    ws.coriolis_matrix.fill(T::zero());
    for j in 0..n {
        let (sj, sdj) = (ws.screw_in_world[j], ws.screw_rate_in_world[j]);
        let f = ws.composite_inertia_matrix[j] * sdj + ws.composite_coriolis_factor[j] * sj;
        let g = ws.composite_inertia_matrix[j] * sj;
        let h = ws.composite_coriolis_factor[j].tr_mul(&sj);
        ws.coriolis_matrix[(j, j)] = sj.dot(&f);
        let mut k = j;
        while let Some(p) = model.parents()[k] {
            k = p;
            ws.coriolis_matrix[(k, j)] = ws.screw_in_world[k].dot(&f);
            ws.coriolis_matrix[(j, k)] =
                g.dot(&ws.screw_rate_in_world[k]) + h.dot(&ws.screw_in_world[k]);
        }
    }
    Ok(&ws.coriolis_matrix)
}
