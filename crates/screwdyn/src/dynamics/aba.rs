//! Forward dynamics by Featherstone's articulated-body algorithm (O(n)), in the seeds' notation.

use super::rnea::base_acceleration;
use super::wrenches::ExternalWrenches;
use crate::error::{Error, Result};
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::{real, Real};
use crate::spatial::{ad_transpose, Twist};
use crate::workspace::Workspace;
use nalgebra::{DVector, Matrix3, Matrix6, Vector3};

/// `𝔍_λ += Ad_{H_λ^i}ᵀ 𝔍 Ad_{H_λ^i}`: adds a symmetric 6×6 inertia given in child frame `i`,
/// written in the parent frame, with `h = H_i^λ = (R, p)`. By blocks, with `𝔍 = [A B; Bᵀ C]`
/// rotated to `A' = R A Rᵀ`, `B' = R B Rᵀ`, `C' = R C Rᵀ` and then shifted by `p`:
/// `C_λ = C'`, `B_λ = B' + [p] C'`, `A_λ = A' + [p] B'ᵀ − B' [p] − [p] C' [p]`
/// (no 6×6 product; only the upper triangles of the symmetric blocks are formed).
#[inline]
fn add_to_parent<T: Real>(h: &crate::spatial::Se3<T>, m: &Matrix6<T>, out: &mut Matrix6<T>) {
    let r = &h.rotation;
    let p = &h.translation;
    let a: Matrix3<T> = m.fixed_view::<3, 3>(0, 0).into_owned();
    let b: Matrix3<T> = m.fixed_view::<3, 3>(0, 3).into_owned();
    let c: Matrix3<T> = m.fixed_view::<3, 3>(3, 3).into_owned();
    let rt = r.transpose();
    let a1 = r * a * rt;
    let b1 = r * b * rt;
    let c1 = r * c * rt;
    // [p] X column by column is p × X_col; X [p] = −([p] Xᵀ)ᵀ.
    let pc = cross_cols(p, &c1); // [p] C'
    let b2 = b1 + pc;
    let pbt = cross_cols(p, &b1.transpose()); // [p] B'ᵀ
                                              // −B'[p] = ([p] B'ᵀ)ᵀ and −[p] C' [p] = [p] ([p] C')ᵀ (C' symmetric).
    let pcp = cross_cols(p, &pc.transpose());
    let a2 = a1 + pbt + pbt.transpose() + pcp;
    for i in 0..3 {
        for j in 0..3 {
            out[(i, j)] += a2[(i, j)];
            out[(i, j + 3)] += b2[(i, j)];
            out[(j + 3, i)] += b2[(i, j)];
            out[(i + 3, j + 3)] += c1[(i, j)];
        }
    }
}

/// `[p] X`: `p ×` each column of `X`.
#[inline(always)]
fn cross_cols<T: Real>(p: &Vector3<T>, x: &Matrix3<T>) -> Matrix3<T> {
    let mut out = Matrix3::zeros();
    for k in 0..3 {
        let (x0, x1, x2) = (x[(0, k)], x[(1, k)], x[(2, k)]);
        out[(0, k)] = p.y * x2 - p.z * x1;
        out[(1, k)] = p.z * x0 - p.x * x2;
        out[(2, k)] = p.x * x1 - p.y * x0;
    }
    out
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
    let (motions, parents, bodies) = (model.motions(), model.parents(), model.bodies());
    // Pass 1: twists, velocity-product accelerations, rigid-body inertias and bias wrenches.
    for i in 0..n {
        let m = &motions[i];
        let mut vi = match parents[i] {
            Some(p) => ws.pose_in_parent[i].inv_act_twist(&ws.twist[p]),
            None => Twist::zeros(),
        };
        ws.bias_acceleration[i] = -m.ad_scaled(v[i], &vi);
        m.add_scaled(&mut vi, v[i]);
        ws.twist[i] = vi;
        let inertia = &bodies[i].inertia;
        ws.articulated_inertia[i] = inertia.matrix();
        let mut p = -ad_transpose(&vi, &inertia.apply(&vi));
        if let Some(f) = fext {
            p -= f.on_body(ws, i);
        }
        ws.articulated_bias[i] = p;
    }
    // Pass 2: articulated inertias, from the leaves to the root.
    let tiny = model.inertia_scale() * T::default_epsilon() * real(64.0);
    for i in (0..n).rev() {
        let m = &motions[i];
        let u = m.inertia_column(&ws.articulated_inertia[i]);
        let d = m.dot(&u);
        // Written to also catch NaN.
        if d.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err(Error::Numerical(format!(
                "forward dynamics failed: the articulated inertia seen by joint '{}' is {:?}, so \
                 the mass matrix is singular (is the chain beyond it massless?)",
                model.joints()[i].name,
                d
            )));
        }
        let small_u = tau[i] - m.dot(&ws.articulated_bias[i]);
        ws.aba_u[i] = u;
        ws.aba_d[i] = d;
        ws.aba_small_u[i] = small_u;
        if let Some(p) = parents[i] {
            // 𝔍ᵃ = 𝔍ᴬ − U Uᵀ / D, symmetric.
            let mut ia = ws.articulated_inertia[i];
            let ud = u / d;
            for c in 0..6 {
                for r in 0..6 {
                    ia[(r, c)] -= ud[r] * u[c];
                }
            }
            let pa = ws.articulated_bias[i] + ia * ws.bias_acceleration[i] + ud * small_u;
            let h = ws.pose_in_parent[i];
            add_to_parent(&h, &ia, &mut ws.articulated_inertia[p]);
            let pa_par = h.inv_act_transpose_wrench(&pa);
            ws.articulated_bias[p] += pa_par;
        }
    }
    // Pass 3: accelerations, from the root to the leaves.
    let base = base_acceleration(model);
    for i in 0..n {
        let h = &ws.pose_in_parent[i];
        let a_par = match parents[i] {
            Some(p) => h.inv_act_twist(&ws.twist_dot[p]),
            None => h.inv_act_twist(&base),
        } + ws.bias_acceleration[i];
        let qdd = (ws.aba_small_u[i] - ws.aba_u[i].dot(&a_par)) / ws.aba_d[i];
        ws.qdd[i] = qdd;
        let mut vd = a_par;
        motions[i].add_scaled(&mut vd, qdd);
        ws.twist_dot[i] = vd;
    }
    Ok(&ws.qdd)
}
