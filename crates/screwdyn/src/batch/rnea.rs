//! The recursive Newton–Euler algorithm on `Lanes`, in the bodies' own frames (the local form
//! of Lynch & Park's *Modern Robotics*; [`dynamics::rnea`] computes the same `τ` in the base
//! frame), for `L` states at once.
//!
//! [`dynamics::rnea`]: crate::dynamics::rnea

use super::buffers::Buffers;
use super::joint::sin_cos_all;
use super::joint::LaneJoint;
use super::spatial::{ad_transpose, add6, apply_body_inertia, gravity_twist, sub6, zero6};
use crate::model::Model;

/// `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` for the states in `b.q`, `b.v`, `b.a`; writes `b.out[..n]`.
///
/// Forward pass (Lynch & Park, *Modern Robotics*): `V_i = Ad_{H_λ^i} V_λ + S_i q̇_i`,
/// `V̇_i = Ad_{H_λ^i} V̇_λ − ad_{S_i q̇_i}(Ad_{H_λ^i} V_λ) + S_i q̈_i`, and
/// `W_i = 𝔍_i V̇_i − ad_{V_i}ᵀ 𝔍_i V_i`, with gravity as the base acceleration `(0, −g)` (Lynch & Park, *Modern Robotics*).
/// Backward pass (Lynch & Park, *Modern Robotics*): `W_λ += Ad_{H_λ^i}ᵀ W_i`, `τ_i = S_iᵀ W_i + I_a,i q̈_i` (armature).
#[inline(always)]
pub(super) fn rnea<const L: usize>(model: &Model, joints: &[LaneJoint], b: &mut Buffers<L>) {
    let n = model.nbodies();
    let (parents, bodies, joints) = (&model.parents()[..n], &model.bodies()[..n], &joints[..n]);
    let (q, v, a) = (&b.q[..n], &b.v[..n], &b.a[..n]);
    let sc = sin_cos_all(joints, q, &mut b.sin_cos);
    let (pip, twist, accel, wrench) = (
        &mut b.pose_in_parent[..n],
        &mut b.twist[..n],
        &mut b.accel[..n],
        &mut b.wrench[..n],
    );
    let base = gravity_twist(model);
    for i in 0..n {
        let j = &joints[i];
        let h = j.pose_in_parent(q[i], sc[i]);
        let (mut vi, mut vdi) = match parents[i] {
            Some(p) => (h.inv_act_twist(&twist[p]), h.inv_act_twist(&accel[p])),
            None => (zero6(), h.inv_act_twist(&base)),
        };
        // ad_{S q̇}(Ad V_λ) is taken before S q̇ is added.
        vdi = sub6(&vdi, &j.ad_scaled(v[i], &vi));
        j.add_scaled(&mut vi, v[i]);
        j.add_scaled(&mut vdi, a[i]);
        let inertia = &bodies[i].inertia;
        let momentum = apply_body_inertia(inertia, &vi);
        wrench[i] = sub6(
            &apply_body_inertia(inertia, &vdi),
            &ad_transpose(&vi, &momentum),
        );
        pip[i] = h;
        twist[i] = vi;
        accel[i] = vdi;
    }
    let out = &mut b.out[..n];
    let model_joints = &model.joints()[..n];
    for i in (0..n).rev() {
        // τ_i = S_iᵀ W_i + I_a,i q̈_i
        out[i] = a[i].mul_add(model_joints[i].armature, joints[i].dot(&wrench[i]));
        if let Some(p) = parents[i] {
            let back = pip[i].inv_act_transpose_wrench(&wrench[i]);
            wrench[p] = add6(&wrench[p], &back);
        }
    }
}
