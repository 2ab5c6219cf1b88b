//! The recursive Newton–Euler passes in the base frame {0} (Featherstone, *Rigid Body Dynamics
//! Algorithms*, the algorithm in ground coordinates; Lynch & Park, *Modern Robotics*, in the
//! notation of docs/notation.md), the form [`rnea`](crate::dynamics::rnea()) and its variants
//! run: every twist, wrench and inertia is written in {0}, so nothing is carried from one
//! body's frame to another's.

use super::rnea::base_acceleration;
use super::wrenches::ExternalWrenches;
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::fused::{ad_fused, cross, dot6};
use crate::spatial::inertia_in_world::{com_in_world, InertiaInWorld};
use crate::spatial::{lin, twist, Twist};
use crate::workspace::Workspace;

/// Both passes of the RNEA in {0} on the world poses of the last forward kinematics
/// (`ws.pose_in_world`), for `v` and `a` of the model's length (checked by the callers);
/// `v = None` means `q̇ = 0` and `a = None` means `q̈ = 0`. With `s_i = Ad_{H_i^0} S_i`,
/// `𝔍_i^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}` and `V̇_base = (0, −g)`:
///
/// 1. forward: `V_i = V_λ + s_i q̇_i`, `V̇_i = V̇_λ + s_i q̈_i + ad_{V_λ}(s_i q̇_i)`, and the
///    body's Newton–Euler wrench `W_i = 𝔍_i^0 V̇_i − ad_{V_i}ᵀ 𝔍_i^0 V_i − W_ext,i`;
/// 2. backward: `W_λ += W_i` (same frame, so no `Adᵀ`), `τ_i = s_iᵀ W_i + I_a,i q̈_i` (the
///    armature [`Joint::armature`](crate::model::Joint::armature) accelerates with the joint alone).
///
/// Writes `ws.screw_in_world` (`s_i`), `ws.twist_in_world` (`V_i^0`), `ws.twist_dot_in_world`
/// (`V̇_i^0`), `ws.wrench_in_world` (`W_i^0`, the parent's wrench on body `i` in {0}) and `ws.tau`.
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
pub(crate) fn rnea_in_world_passes<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    v: Option<&[T]>,
    a: Option<&[T]>,
    fext: Option<&ExternalWrenches<T>>,
) {
    let n = model.nbodies();
    // Everything as slices of length n, so that the loops' bounds checks go (parents come
    // before their children, so `p < i` for the parent `p` of `i`).
    let (motions, parents, bodies, joints) = (
        &model.motions()[..n],
        &model.parents()[..n],
        &model.bodies()[..n],
        &model.joints()[..n],
    );
    let (v, a) = (v.map(|v| &v[..n]), a.map(|a| &a[..n]));
    let Workspace {
        pose_in_world,
        screw_in_world,
        twist_in_world,
        twist_dot_in_world,
        wrench_in_world,
        tau,
        ..
    } = ws;
    let poses = &pose_in_world[..n];
    let screws = &mut screw_in_world[..n];
    let twists = &mut twist_in_world[..n];
    let accels = &mut twist_dot_in_world[..n];
    let wrenches = &mut wrench_in_world[..n];
    let tau = &mut tau.as_mut_slice()[..n];
    let base = base_acceleration(model);
    // Forward pass, root to leaves: s_i, V_i and V̇_i (a short chain from parent to child) ...
    for i in 0..n {
        let s = motions[i].act(&poses[i]);
        let (vp, ap) = match parents[i] {
            Some(p) => (twists[p], accels[p]),
            None => (Twist::zeros(), base),
        };
        // V̇_i = V̇_λ + s_i q̈_i + ad_{V_λ}(s_i q̇_i).
        let mut ai = match a {
            Some(a) => Twist::from_fn(|r, _| s[r].mul_add(a[i], ap[r])),
            None => ap,
        };
        let vi = match v {
            Some(v) => {
                let sv = s * v[i];
                ai += ad_fused(&vp, &sv);
                vp + sv
            }
            None => Twist::zeros(),
        };
        screws[i] = s;
        twists[i] = vi;
        accels[i] = ai;
    }
    // ... then, body by body (each on its own), W_i = 𝔍_i^0 V̇_i − ad_{V_i}ᵀ 𝔍_i^0 V_i − W_ext,i,
    // the velocity product only when the bodies move.
    let at_rest = v.is_none() && a.is_none();
    let forms = &model.body_inertia_form[..n];
    for i in 0..n {
        let h = &poses[i];
        let body = &bodies[i].inertia;
        let mut w = if at_rest {
            // g(q): W_i = 𝔍_i^0 (0, −g) = (c^0 × f, f) with f = −m g, the weight at the centre
            // of mass; the rotational inertia plays no part.
            let f = lin(&base) * body.mass;
            twist(cross(&com_in_world(body, h), &f), f)
        } else {
            let inertia = InertiaInWorld::with_form(body, &forms[i], h);
            let mut w = inertia.momentum(&accels[i]);
            if v.is_some() {
                w += inertia.velocity_product_wrench(&twists[i]);
            }
            w
        };
        if let Some(f) = fext {
            w -= f.in_world_at(h, i);
        }
        wrenches[i] = w;
    }
    // Backward pass, leaves to root: τ_i = s_iᵀ W_i + I_a,i q̈_i, then W_λ += W_i.
    for i in (0..n).rev() {
        let w = wrenches[i];
        let t = dot6(&screws[i], &w);
        tau[i] = match a {
            Some(a) => joints[i].armature.mul_add(a[i], t),
            None => t,
        };
        if let Some(p) = parents[i] {
            wrenches[p] += w;
        }
    }
}
