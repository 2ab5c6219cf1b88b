//! Forward dynamics by Featherstone's articulated-body algorithm (O(n)), in the notation of docs/notation.md.

use super::cholesky::singular_threshold;
use super::inputs::checked_poses;
use super::rnea::base_acceleration;
use super::wrenches::ExternalWrenches;
use crate::error::{Error, Result};
use crate::kinematics::world_poses_of_checked;
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::fused::{ad_fused, dot6, mat6_vec};
use crate::spatial::inertia_in_world::InertiaInWorld;
use crate::spatial::Twist;
use crate::workspace::Workspace;
use nalgebra::DVector;

/// Forward dynamics `q̈ = M⁻¹(τ − C q̇ − g)` by the articulated-body algorithm (Featherstone),
/// written with the operators and every spatial quantity in the base frame {0}
/// (`s_i = Ad_{H_i^0} S_i`, `𝔍_i^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}`, twists `V_i^0 = Ad_{H_i^0} V_i`),
/// so that nothing is carried from child to parent frame:
///
/// 1. forward: `V_i = V_λ + s_i q̇_i`, `c_i = ad_{V_λ}(s_i q̇_i)` (the `ṡ_i q̇_i` of
///    `V̇_i = V̇_λ + s_i q̈_i + ṡ_i q̇_i`), `𝔍ᴬ_i = 𝔍_i^0`, `pᴬ_i = −ad_{V_i}ᵀ 𝔍_i^0 V_i − W_ext,i`;
/// 2. backward: `U_i = 𝔍ᴬ_i s_i`, `D_i = s_iᵀ U_i + I_a,i` (with the joint's armature
///    [`Joint::armature`](crate::model::Joint::armature)), `u_i = τ_i − s_iᵀ pᴬ_i`; the parent
///    receives `𝔍ᵃ_i = 𝔍ᴬ_i − U_i U_iᵀ / D_i` and `pᴬ_i + 𝔍ᵃ_i c_i + U_i u_i / D_i`, and
///    `U_λ`, `D_λ` are summed as the children are reached: `U_λ = 𝔍_λ^0 s_λ + Σ_i 𝔍ᵃ_i s_λ`
///    with `𝔍ᵃ_i s_λ = 𝔍ᴬ_i s_λ − U_i (U_iᵀ s_λ) / D_i`, and
///    `D_λ = s_λᵀ 𝔍_λ^0 s_λ + I_a,λ + Σ_i (s_λᵀ 𝔍ᴬ_i s_λ − (U_iᵀ s_λ)² / D_i)`;
/// 3. forward: `V̇'_i = V̇_λ + c_i`, `q̈_i = u_i / D_i − (U_i / D_i)ᵀ V̇'_i`,
///    `V̇_i = V̇'_i + s_i q̈_i`, with `V̇_base = (0, −g)` (Lynch & Park, *Modern Robotics*);
///    as `V̇'_i = V̇'_λ + c_i + s_λ q̈_λ`, `q̈_i` is formed as
///    `u_i / D_i − (U_i / D_i)ᵀ (V̇'_λ + c_i) − ((U_i / D_i)ᵀ s_λ) q̈_λ`.
///
/// Writes `ws.qdd`, and `ws.screw_in_world`, `ws.twist_in_world`, `ws.twist_dot_in_world`
/// (`V̇_i^0`, the base-frame spatial acceleration) and the articulated quantities, all in the
/// base frame (a root's `𝔍ᴬ` is left at its rigid `𝔍^0`: nothing reads it). Returns `ws.qdd`.
///
/// # Errors
/// [`Error::DimensionMismatch`]/[`Error::NonFinite`] for bad `q`, `v`, `tau`;
/// [`Error::InvalidArgument`] for a workspace made for another model; [`Error::Numerical`] when
/// an articulated inertia `D_i` is not positive (a massless subtree), naming the joint.
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
    articulated_body(model, ws, q, v, tau, None)
}

/// The error of an articulated inertia `d` at joint `i` that is not positive.
#[cold]
pub(crate) fn singular<T: Real>(model: &Model<T>, i: usize, d: T) -> Error {
    Error::Numerical(format!(
        "forward dynamics failed: the articulated inertia seen by joint '{}' is {:?}, so the \
         mass matrix is singular (is the chain beyond it massless?)",
        model.joints()[i].name,
        d
    ))
}

/// [`aba`] with external wrenches on the bodies (and tip wrenches); public as
/// [`forward_dynamics`](super::forward_dynamics) with [`ForwardMethod::Aba`](super::ForwardMethod::Aba).
pub(crate) fn articulated_body<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<&'w DVector<T>> {
    checked_poses(model, ws, q, &[(v, "v"), (tau, "tau")], fext)?;
    aba_passes(model, ws, v, tau, fext)?;
    Ok(&ws.qdd)
}

/// [`articulated_body`] for a caller that guarantees that `v` and `tau` have one finite entry
/// per joint: the simulator, whose plant checks every torque it passes and whose stepper
/// integrates a state it has already checked (a non-finite acceleration stops the run before it
/// reaches the state). `q` is checked by forward kinematics, unless `q_checked`: then the caller
/// also guarantees that `q` has one finite entry per joint and that `ws` was made for `model`
/// (RK4's stage states, checked as they are formed, in the plant's own workspace), and only the
/// poses in {0} that the passes read are written (`ws.pose_in_parent` is left as it was).
/// The wrenches, when given, are always checked.
pub(crate) fn articulated_body_for_stepper<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    (q, q_checked): (&[T], bool),
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<&'w DVector<T>> {
    debug_assert!(v.len() == model.nq() && tau.len() == model.nq());
    debug_assert!(v.iter().chain(tau).all(|x| x.is_finite()));
    if q_checked {
        debug_assert!(ws.check(model).is_ok() && model.check_vector(q, "q").is_ok());
        if let Some(f) = fext {
            f.check(model)?;
        }
        world_poses_of_checked(model, ws, q);
    } else {
        checked_poses(model, ws, q, &[], fext)?;
    }
    aba_passes(model, ws, v, tau, fext)?;
    Ok(&ws.qdd)
}

/// The three passes of [`aba`] on the poses of the last forward kinematics, for `v` and `tau`
/// of the model's length (checked by the callers). Writes `ws.qdd`.
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
fn aba_passes<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<()> {
    let n = model.nbodies();
    let (motions, parents, bodies, joints) = (
        &model.motions()[..n],
        &model.parents()[..n],
        &model.bodies()[..n],
        &model.joints()[..n],
    );
    let forms = &model.body_inertia_form[..n];
    let (v, tau) = (&v[..n], &tau[..n]);
    // The workspace's buffers borrowed once, as slices of length n: their addresses and lengths
    // stay in registers instead of being reloaded after every store (and most bounds checks go).
    let Workspace {
        pose_in_world,
        screw_in_world,
        twist_in_world,
        twist_dot_in_world,
        bias_acceleration,
        articulated_inertia,
        articulated_bias,
        articulated_force,
        articulated_joint_inertia,
        articulated_joint_force,
        acceleration_before_joint,
        articulated_parent_coupling,
        qdd,
        ..
    } = ws;
    let poses = &pose_in_world[..n];
    let screws = &mut screw_in_world[..n];
    let twists = &mut twist_in_world[..n];
    let accels = &mut twist_dot_in_world[..n];
    let bias_acc = &mut bias_acceleration[..n];
    let inertias = &mut articulated_inertia[..n];
    let biases = &mut articulated_bias[..n];
    let u_over_d = &mut articulated_force[..n];
    let d_joint = &mut articulated_joint_inertia.as_mut_slice()[..n];
    let small_u_over_d = &mut articulated_joint_force.as_mut_slice()[..n];
    let qdd_out = &mut qdd.as_mut_slice()[..n];
    let a_pre = &mut acceleration_before_joint[..n];
    let coupling = &mut articulated_parent_coupling.as_mut_slice()[..n];
    // Pass 1: joint screws, twists and velocity-product accelerations (root to leaves)...
    for i in 0..n {
        let s = motions[i].act(&poses[i]);
        let sv = s * v[i];
        let (vi, ci) = match parents[i] {
            Some(p) => {
                let vp = twists[p];
                (vp + sv, ad_fused(&vp, &sv))
            }
            None => (sv, Twist::zeros()),
        };
        screws[i] = s;
        twists[i] = vi;
        bias_acc[i] = ci;
    }
    // ... then, body by body (each on its own), 𝔍_i^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i} written into
    // 𝔍ᴬ_i, pᴬ_i = −ad_{V_i}ᵀ 𝔍_i^0 V_i − W_ext,i, and the body's own shares 𝔍_i^0 s_i of U_i
    // (kept in `u_over_d` until pass 2 divides it) and s_iᵀ 𝔍_i^0 s_i + I_a,i of D_i.
    for i in 0..n {
        let h = &poses[i];
        let inertia = InertiaInWorld::with_form(&bodies[i].inertia, &forms[i], h);
        inertia.write_matrix(&mut inertias[i]);
        let vi = &twists[i];
        let mut p = inertia.velocity_product_wrench(vi);
        if let Some(f) = fext {
            p -= f.in_world_at(h, i);
        }
        biases[i] = p;
        let s = &screws[i];
        let own = inertia.momentum(s);
        u_over_d[i] = own;
        d_joint[i] = dot6(s, &own) + joints[i].armature;
    }
    // Pass 2: articulated inertias, from the leaves to the root. U_i and D_i are complete when
    // body i is reached: every child (index above i) has added its share.
    let tiny = singular_threshold(model.inertia_scale());
    for i in (0..n).rev() {
        let s = screws[i];
        let u = u_over_d[i];
        let d = d_joint[i];
        // Written to also catch NaN.
        if d.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err(singular(model, i, d));
        }
        let small_u = tau[i] - dot6(&s, &biases[i]);
        // One division per joint: U / D and u / D are what pass 3 and the parent need.
        let inv_d = T::one() / d;
        let ud = u * inv_d;
        u_over_d[i] = ud;
        small_u_over_d[i] = small_u * inv_d;
        if let Some(p) = parents[i] {
            // 𝔍ᴬ_i read in place, next to its parent's (whose index is below i) being written.
            let (before, from_i) = inertias.split_at_mut(i);
            let ia = &from_i[0];
            // The parent's U_λ and D_λ receive 𝔍ᵃ_i s_λ = 𝔍ᴬ_i s_λ − U_i (U_iᵀ s_λ) / D_i and
            // s_λᵀ 𝔍ᵃ_i s_λ = s_λᵀ 𝔍ᴬ_i s_λ − (U_iᵀ s_λ)² / D_i: the products with 𝔍ᴬ_i do not
            // wait for 1/D_i, only the last fused product does (so the chain through the
            // parents is a division and two products per body, not a 6×6 update and 𝔍ᴬ s).
            let sp = screws[p];
            let ia_sp = mat6_vec(ia, &sp);
            let u_sp = dot6(&u, &sp);
            coupling[i] = u_sp * inv_d;
            let up = &mut u_over_d[p];
            for r in 0..6 {
                up[r] = ud[r].mul_add(-u_sp, ia_sp[r] + up[r]);
            }
            d_joint[p] = (u_sp * u_sp).mul_add(-inv_d, dot6(&sp, &ia_sp) + d_joint[p]);
            // 𝔍ᵃ = 𝔍ᴬ − U Uᵀ / D (symmetric), added to the parent's as it is formed, unless the
            // parent is a root.
            if parents[p].is_some() {
                let parent = &mut before[p];
                for c in 0..6 {
                    let uc = -u[c];
                    for r in 0..6 {
                        parent[(r, c)] += ud[r].mul_add(uc, ia[(r, c)]);
                    }
                }
            }
            // pᵃ = pᴬ + 𝔍ᵃ c + U u / D = pᴬ + 𝔍ᴬ c + (U / D)(u − Uᵀ c).
            let ci = bias_acc[i];
            let k = small_u - dot6(&u, &ci);
            let ia_c = mat6_vec(ia, &ci);
            let (bi, bp) = (biases[i], &mut biases[p]);
            for r in 0..6 {
                bp[r] += ud[r].mul_add(k, bi[r] + ia_c[r]);
            }
        }
    }
    // Pass 3: accelerations, from the root to the leaves, with V̇'_i = V̇_λ + c_i kept per body.
    let base = base_acceleration(model);
    for i in 0..n {
        let ud = &u_over_d[i];
        let (a_before, qdd_i) = match parents[i] {
            Some(p) => {
                // V̇'_i = V̇'_λ + c_i + s_λ q̈_λ, so q̈_i = u_i/D_i − (U_i/D_i)ᵀ(V̇'_λ + c_i)
                // − ((U_i/D_i)ᵀ s_λ) q̈_λ: only the last product waits for q̈_λ.
                let (sp, qdd_p) = (&screws[p], qdd_out[p]);
                let known = a_pre[p] + bias_acc[i];
                let rest = small_u_over_d[i] - dot6(ud, &known);
                let qdd_i = (-coupling[i]).mul_add(qdd_p, rest);
                (Twist::from_fn(|r, _| sp[r].mul_add(qdd_p, known[r])), qdd_i)
            }
            None => {
                let a_before = base + bias_acc[i];
                (a_before, small_u_over_d[i] - dot6(ud, &a_before))
            }
        };
        a_pre[i] = a_before;
        qdd_out[i] = qdd_i;
        let s = &screws[i];
        accels[i] = Twist::from_fn(|r, _| s[r].mul_add(qdd_i, a_before[r]));
    }
    Ok(())
}
