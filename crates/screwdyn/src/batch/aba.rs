//! The articulated-body algorithm on `Lanes`: [`dynamics::aba`]'s three passes
//! for `L` states at once, everything in the base frame as there.
//!
//! [`dynamics::aba`]: crate::dynamics::aba

use super::buffers::Buffers;
use super::joint::sin_cos_all;
use super::joint::LaneJoint;
use super::lanes::Lanes;
use super::spatial::{
    ad, ad_transpose, add6, body_inertia_in, dot6, gravity_twist, mul6, scale6, zero6,
};
use crate::model::Model;

/// `q̈ = M⁻¹(τ − C q̇ − g)` for the states in `b.q`, `b.v`, `b.a` (`a` holds `τ`); writes
/// `b.out[..n]`. `Err((i, D))` when some lane's articulated inertia `D_i` is not positive (or
/// NaN), with the smallest `D_i`, for the caller to find the state and report it as
/// [`dynamics::aba`] would.
///
/// 1. forward: `V_i = V_λ + s_i q̇_i`, `c_i = ad_{V_λ}(s_i q̇_i)`, `𝔍ᴬ_i = 𝔍_i^0`,
///    `pᴬ_i = −ad_{V_i}ᵀ 𝔍_i^0 V_i`;
/// 2. backward: `U_i = 𝔍ᴬ_i s_i`, `D_i = s_iᵀ U_i + I_a,i` (armature), `u_i = τ_i − s_iᵀ pᴬ_i`; the parent
///    receives `𝔍ᴬ_i − U_i U_iᵀ / D_i` and `pᴬ_i + 𝔍ᴬ_i c_i + (U_i / D_i)(u_i − U_iᵀ c_i)`;
/// 3. forward: `V̇'_i = V̇_λ + c_i`, `q̈_i = u_i / D_i − (U_i / D_i)ᵀ V̇'_i`,
///    `V̇_i = V̇'_i + s_i q̈_i`, with `V̇_base = (0, −g)` (Lynch & Park, *Modern Robotics*).
///
/// [`dynamics::aba`]: crate::dynamics::aba
#[inline(always)]
pub(super) fn aba<const L: usize>(
    model: &Model,
    joints: &[LaneJoint],
    b: &mut Buffers<L>,
) -> Result<(), (usize, f64)> {
    let n = model.nbodies();
    let (parents, bodies, joints) = (&model.parents()[..n], &model.bodies()[..n], &joints[..n]);
    let (q, v, tau) = (&b.q[..n], &b.v[..n], &b.a[..n]);
    let sc = sin_cos_all(joints, q, &mut b.sin_cos);
    let piw = &mut b.pose_in_world[..n];
    let screws = &mut b.screw[..n];
    let twists = &mut b.twist[..n];
    let accels = &mut b.accel[..n];
    let bias_acc = &mut b.bias_acceleration[..n];
    let inertias = &mut b.articulated_inertia[..n];
    let biases = &mut b.wrench[..n];
    let u_over_d = &mut b.articulated_force[..n];
    let small_u_over_d = &mut b.articulated_joint_force[..n];
    // Pass 1: poses, twists, velocity-product accelerations, inertias and bias wrenches.
    for i in 0..n {
        let h = joints[i].pose_in_parent(q[i], sc[i]);
        piw[i] = match parents[i] {
            Some(p) => piw[p].compose(&h),
            None => h,
        };
        let s = joints[i].act(&piw[i]);
        let sv = scale6(&s, v[i]);
        let (vi, ci) = match parents[i] {
            Some(p) => (add6(&twists[p], &sv), ad(&twists[p], &sv)),
            None => (sv, zero6()),
        };
        let momentum = body_inertia_in(&bodies[i].inertia, &piw[i], &vi, &mut inertias[i]);
        let pa = ad_transpose(&vi, &momentum);
        biases[i] = each!(6, |k| -pa[k]);
        screws[i] = s;
        twists[i] = vi;
        bias_acc[i] = ci;
    }
    // Pass 2: articulated inertias, from the leaves to the root.
    let tiny = crate::dynamics::singular_threshold(model.inertia_scale());
    for i in (0..n).rev() {
        let s = screws[i];
        let (before, from_i) = inertias.split_at_mut(i);
        let ia = &from_i[0];
        let u = mul6(ia, &s);
        // D_i = s_iᵀ 𝔍ᴬ_i s_i + I_a,i (armature)
        let d = dot6(&s, &u) + model.joints()[i].armature;
        // Not greater than `tiny`, or NaN, in some lane.
        let smallest = d.min_or_nan();
        if smallest.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err((i, smallest));
        }
        let small_u = tau[i] - dot6(&s, &biases[i]);
        let inv_d = Lanes::splat(1.0) / d;
        let ud = scale6(&u, inv_d);
        u_over_d[i] = ud;
        small_u_over_d[i] = small_u * inv_d;
        if let Some(p) = parents[i] {
            let parent = &mut before[p];
            *parent = each!(6, |r| each!(6, |c| parent[r][c]
                + (-ud[r]).mul_add(u[c], ia[r][c])));
            let ci = bias_acc[i];
            let pa = add6(&biases[i], &mul6(ia, &ci));
            let k = small_u - dot6(&u, &ci);
            biases[p] = each!(6, |r| biases[p][r] + ud[r].mul_add(k, pa[r]));
        }
    }
    // Pass 3: accelerations, from the root to the leaves.
    let base = gravity_twist(model);
    let out = &mut b.out[..n];
    for i in 0..n {
        let a_par = add6(
            match parents[i] {
                Some(p) => &accels[p],
                None => &base,
            },
            &bias_acc[i],
        );
        let qdd = small_u_over_d[i] - dot6(&u_over_d[i], &a_par);
        out[i] = qdd;
        accels[i] = each!(6, |k| screws[i][k].mul_add(qdd, a_par[k]));
    }
    Ok(())
}
