//! The composite-rigid-body algorithm on `Lanes`: [`dynamics::crba`] for `L`
//! states at once, everything in the base frame as there.
//!
//! [`dynamics::crba`]: crate::dynamics::crba

use super::buffers::Buffers;
use super::joint::sin_cos_all;
use super::joint::LaneJoint;
use super::lanes::Lanes;
use super::spatial::{dot6, Composite};
use crate::model::Model;

/// `M(q)` for the states in `b.q`; writes `b.out[..n²]` (symmetric, so row- and column-major
/// alike).
///
/// Forward: kinematics `H_i^0 = H_λ^0 H_i^λ(q_i)`, base-frame screws `s_i = Ad_{H_i^0} S_i`
/// and body inertias `Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}` (by the shape of each `I_c`). Backward, from the leaves: the composite
/// `𝔍ᶜ_i` (its body's inertia plus its children's composites) is whole when body `i` is
/// reached, so `M_ki = s_kᵀ 𝔍ᶜ_i s_i` for every `k` supporting `i` (Lynch & Park, *Modern Robotics*
/// `M = Sᵀ Lᵀ 𝔍 L S`), plus the armature `I_a,i` on the diagonal, then `𝔍ᶜ_i` is added to
/// its parent's.
#[inline(always)]
pub(super) fn crba<const L: usize>(model: &Model, joints: &[LaneJoint], b: &mut Buffers<L>) {
    let n = model.nbodies();
    let (parents, bodies, forms, joints) = (
        &model.parents()[..n],
        &model.bodies()[..n],
        &model.body_inertia_form[..n],
        &joints[..n],
    );
    let q = &b.q[..n];
    let sc = sin_cos_all(joints, q, &mut b.sin_cos);
    let (piw, ci, s) = (
        &mut b.pose_in_world[..n],
        &mut b.composite[..n],
        &mut b.screw[..n],
    );
    for i in 0..n {
        let h = joints[i].pose_in_parent(q[i], sc[i]);
        piw[i] = match parents[i] {
            Some(p) => piw[p].compose(&h),
            None => h,
        };
        ci[i] = Composite::rigid_in_world_with_form(&bodies[i].inertia, &forms[i], &piw[i]);
        s[i] = joints[i].act(&piw[i]);
    }
    let m = &mut b.out[..n * n];
    if !model.is_chain {
        // Bodies on different branches do not couple.
        m.fill(Lanes::zero());
    }
    // From the leaves: 𝔍ᶜ_i is whole once its children (higher indices) have been added to it.
    let armature = |i: usize| model.joints()[i].armature;
    for i in (0..n).rev() {
        let f = ci[i].apply(&s[i]);
        // M_ii = s_iᵀ 𝔍ᶜ_i s_i + I_a,i
        m[i * n + i] = dot6(&s[i], &f) + armature(i);
        let mut k = i;
        while let Some(p) = parents[k] {
            k = p;
            let mki = dot6(&s[k], &f);
            m[i * n + k] = mki;
            m[k * n + i] = mki;
        }
        if let Some(p) = parents[i] {
            let c = ci[i];
            ci[p].add(&c);
        }
    }
}
