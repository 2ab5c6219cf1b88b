//! Forward dynamics by Featherstone's articulated-body algorithm (O(n)), in the seeds' notation.

use super::rnea::base_acceleration;
use super::wrenches::ExternalWrenches;
use crate::error::{Error, Result};
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::{real, Real};
use crate::spatial::{ad, ad_transpose, Twist};
use crate::workspace::Workspace;
use nalgebra::{DVector, Matrix6};

/// `Ad_{H_λ^i}ᵀ 𝔍 Ad_{H_λ^i}`: a 6×6 inertia in child frame `i` written in the parent frame, with
/// `h = H_i^λ`.
#[inline]
fn to_parent<T: Real>(h: &crate::spatial::Se3<T>, m: &Matrix6<T>) -> Matrix6<T> {
    let x = h.inverse().adjoint_matrix();
    x.transpose() * m * x
}

/// Forward dynamics `q̈ = M⁻¹(τ − C q̇ − g)` by the articulated-body algorithm (Featherstone),
/// written with the seeds' operators:
///
/// 1. forward: `V_i = Ad_{H_λ^i} V_λ + S_i q̇_i`, `c_i = −ad_{S_i q̇_i}(Ad_{H_λ^i} V_λ)`,
///    `𝔍ᴬ_i = 𝔍_i`, `pᴬ_i = −ad_{V_i}ᵀ 𝔍_i V_i − W_ext,i`;
/// 2. backward: `U_i = 𝔍ᴬ_i S_i`, `D_i = S_iᵀ U_i`, `u_i = τ_i − S_iᵀ pᴬ_i`, and the parent
///    receives `Ad_{H_λ^i}ᵀ (𝔍ᴬ_i − U_i U_iᵀ / D_i) Ad_{H_λ^i}` and
///    `Ad_{H_λ^i}ᵀ (pᴬ_i + 𝔍ᵃ_i c_i + U_i u_i / D_i)`;
/// 3. forward: `V̇'_i = Ad_{H_λ^i} V̇_λ + c_i`, `q̈_i = (u_i − U_iᵀ V̇'_i) / D_i`,
///    `V̇_i = V̇'_i + S_i q̈_i`, with `V̇_base = (0, −g)` (seed 000).
///
/// Returns `ws.qdd`; `Error::Numerical` when an articulated inertia `D_i` is not positive (a
/// massless subtree).
///
/// ```
/// use screwdyn::{builtin, dynamics::aba, Workspace};
/// let m = builtin::pendulum();
/// let mut ws = Workspace::new(&m);
/// // A free pendulum at angle q: m l² q̈ = −m g l sin q.
/// let qdd = aba(&m, &mut ws, &[0.5], &[0.0], &[0.0]).unwrap();
/// assert!((qdd[0] + 9.81 * 0.5_f64.sin()).abs() < 1e-12);
/// ```
pub fn aba<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
) -> Result<&'w DVector<T>> {
    aba_with(model, ws, q, v, tau, None)
}

/// [`aba`] with external wrenches on the bodies (and tip wrenches).
pub fn aba_with<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<&'w DVector<T>> {
    model.check_vector(v, "v")?;
    model.check_vector(tau, "tau")?;
    if let Some(f) = fext {
        f.check(model)?;
    }
    forward_kinematics(model, ws, q)?;
    let n = model.nbodies();
    // Pass 1: twists, velocity-product accelerations, rigid-body inertias and bias wrenches.
    for (i, joint) in model.joints().iter().enumerate() {
        let v_par = match model.parent(i) {
            Some(p) => ws.pose_in_parent[i].inv_act_twist(&ws.twist[p]),
            None => Twist::zeros(),
        };
        let s_qd = joint.screw * v[i];
        let vi = v_par + s_qd;
        ws.twist[i] = vi;
        ws.bias_acceleration[i] = -ad(&s_qd, &v_par);
        let inertia = &model.bodies()[i].inertia;
        ws.articulated_inertia[i] = inertia.matrix();
        let mut p = -ad_transpose(&vi, &inertia.apply(&vi));
        if let Some(f) = fext {
            p -= f.on_body(ws, i);
        }
        ws.articulated_bias[i] = p;
    }
    // Pass 2: articulated inertias, from the leaves to the root.
    let scale = ws
        .articulated_inertia
        .iter()
        .fold(T::zero(), |s, m| s.max(m.amax()));
    let tiny = scale * T::default_epsilon() * real(64.0);
    for i in (0..n).rev() {
        let s = &model.joints()[i].screw;
        let u = ws.articulated_inertia[i] * s;
        let d = s.dot(&u);
        // Written to also catch NaN.
        if d.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err(Error::Numerical(format!(
                "forward dynamics failed: the articulated inertia seen by joint '{}' is {:?}, so \
                 the mass matrix is singular (is the chain beyond it massless?)",
                model.joints()[i].name,
                d
            )));
        }
        let small_u = tau[i] - s.dot(&ws.articulated_bias[i]);
        ws.aba_u[i] = u;
        ws.aba_d[i] = d;
        ws.aba_small_u[i] = small_u;
        if let Some(p) = model.parent(i) {
            let ia = ws.articulated_inertia[i] - u * u.transpose() / d;
            let pa = ws.articulated_bias[i] + ia * ws.bias_acceleration[i] + u * (small_u / d);
            let h = &ws.pose_in_parent[i];
            let ia_par = to_parent(h, &ia);
            ws.articulated_inertia[p] += ia_par;
            let pa_par = h.inv_act_transpose_wrench(&pa);
            ws.articulated_bias[p] += pa_par;
        }
    }
    // Pass 3: accelerations, from the root to the leaves.
    let base = base_acceleration(model);
    for i in 0..n {
        let h = &ws.pose_in_parent[i];
        let a_par = match model.parent(i) {
            Some(p) => h.inv_act_twist(&ws.twist_dot[p]),
            None => h.inv_act_twist(&base),
        } + ws.bias_acceleration[i];
        let qdd = (ws.aba_small_u[i] - ws.aba_u[i].dot(&a_par)) / ws.aba_d[i];
        ws.qdd[i] = qdd;
        ws.twist_dot[i] = a_par + model.joints()[i].screw * qdd;
    }
    Ok(&ws.qdd)
}
