//! The recursive Newton–Euler iterations of Lynch & Park's *Modern Robotics* written out step by step, for a
//! student who checks a homework line by line: every intermediate quantity of one
//! [`inverse_dynamics`] call, in the notation of docs/notation.md.

use super::inputs::checked_poses;
use super::rnea::{base_acceleration, rnea_passes};
use super::wrenches::ExternalWrenches;
use crate::error::Result;
use crate::model::Model;
use crate::spatial::{ad_transpose, Se3, Twist, Wrench};
use crate::workspace::Workspace;

/// Forward iteration `i` (Lynch & Park, *Modern Robotics*): the joint transform and the twist recursion.
#[derive(Clone, Debug, PartialEq)]
pub struct ForwardStep {
    /// `θ_i`, `θ̇_i`, `θ̈_i`.
    pub q: f64,
    /// `θ̇_i`.
    pub v: f64,
    /// `θ̈_i`.
    pub a: f64,
    /// `H_i^{λ(i)}(θ_i) = H_i^{λ(i)}(0) e^{S̃_i θ_i}`.
    pub pose_in_parent: Se3,
    /// `Ad_{H_{λ(i)}^i} V_{λ(i)}`: the parent's twist seen in frame `i` (zero for the base).
    pub parent_twist: Twist,
    /// `Ad_{H_{λ(i)}^i} V̇_{λ(i)}` (the base acceleration `(0, −g)` for a root body).
    pub parent_twist_dot: Twist,
    /// `V_i^{i,0} = Ad_{H_{λ(i)}^i} V_{λ(i)} + S_i θ̇_i`.
    pub twist: Twist,
    /// `V̇_i^{i,0} = Ad V̇_{λ(i)} − ad_{S_i θ̇_i}(Ad V_{λ(i)}) + S_i θ̈_i`.
    pub twist_dot: Twist,
}

/// Backward iteration `i` (Lynch & Park, *Modern Robotics*): the wrench balance of body `i` and its joint torque.
#[derive(Clone, Debug, PartialEq)]
pub struct BackwardStep {
    /// `𝔍^{i,i} V̇_i − ad_{V_i}ᵀ(𝔍^{i,i} V_i)`: the body's own Newton–Euler wrench.
    pub inertial: Wrench,
    /// `W_ext^{i,i}`: the environment's wrench on the body, in its frame (zero if none).
    pub external: Wrench,
    /// `(c, Ad_{H_i^c}ᵀ W_i^{c,c})` for every child body `c`.
    pub from_children: Vec<(usize, Wrench)>,
    /// `W_{λ(i)}^{i,i} = 𝔍 V̇ − ad_Vᵀ 𝔍 V − W_ext + Σ_c Ad_{H_i^c}ᵀ W_c`.
    pub wrench: Wrench,
    /// `τ_i = (S_i^{i,λ(i)})ᵀ W_{λ(i)}^{i,i} + I_a,i θ̈_i` (the last term the joint's armature).
    pub tau: f64,
}

/// Every intermediate quantity of one RNEA run (see [`rnea_trace`]); body indices are 0-based
/// (the body `i` is index `i − 1`, the base is `None` in [`Model::parents`]).
#[derive(Clone, Debug, PartialEq)]
pub struct RneaTrace {
    /// `V̇_0^{0,0} = (0, −g)`: gravity as a base acceleration.
    pub base_acceleration: Twist,
    /// Forward iterations `i = 1 … n`, by body index.
    pub forward: Vec<ForwardStep>,
    /// Backward iterations, by body index (run from `n` down to 1).
    pub backward: Vec<BackwardStep>,
    /// The joint torques `τ`.
    pub tau: Vec<f64>,
}

/// Runs the recursive Newton–Euler algorithm in the bodies' own frames (the form written
/// below; [`inverse_dynamics`](super::inverse_dynamics) computes the same `τ` in the base
/// frame) and reads out every step of the recursion:
///
/// - forward, `i = 1 … n`: `H_i^{λ(i)}(θ_i) = H_i^{λ(i)}(0) e^{S̃_i θ_i}`,
///   `V_i = Ad_{H_{λ(i)}^i} V_{λ(i)} + S_i θ̇_i`,
///   `V̇_i = Ad_{H_{λ(i)}^i} V̇_{λ(i)} − ad_{S_i θ̇_i}(Ad_{H_{λ(i)}^i} V_{λ(i)}) + S_i θ̈_i`,
///   with `V_0 = 0`, `V̇_0 = (0, −g)`;
/// - backward, `i = n … 1`: `W_{λ(i)}^{i,i} = 𝔍^{i,i} V̇_i − ad_{V_i}ᵀ(𝔍^{i,i} V_i) − W_ext^{i,i}
///   + Σ_c Ad_{H_i^c}ᵀ W_i^{c,c}`, `τ_i = (S_i^{i,λ(i)})ᵀ W_{λ(i)}^{i,i} + I_a,i θ̈_i` (the
///   joint's armature `I_a,i`, zero unless the model has one).
///
/// Teaching code: it allocates the trace.
///
/// # Errors
/// As [`inverse_dynamics`](super::inverse_dynamics).
///
/// ```
/// use screwdyn::{builtin, dynamics::rnea_trace};
/// let m = builtin::planar2();
/// let t = rnea_trace(&m, &[0.3, 0.5], &[1.0, -1.0], &[0.5, 0.2], None).unwrap();
/// // Link 1's twist is S_1 θ̇_1 (the base is at rest); τ_2 is S_2ᵀ W_1^{2,2}.
/// assert_eq!(t.forward[0].twist, m.joints()[0].screw * 1.0);
/// assert!((t.backward[1].tau - m.joints()[1].screw.dot(&t.backward[1].wrench)).abs() < 1e-15);
/// assert!((t.tau[0] - 28.810919).abs() < 1e-6);
/// ```
pub fn rnea_trace(
    model: &Model,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    fext: Option<&ExternalWrenches>,
) -> Result<RneaTrace> {
    let mut ws = Workspace::new(model);
    checked_poses(model, &mut ws, q, &[(v, "v"), (a, "a")], fext)?;
    let base = base_acceleration(model);
    rnea_passes(model, &mut ws, Some(v), |i| a[i], &base, fext);
    let tau = ws.tau.as_slice().to_vec();
    let parents = model.parents();
    let forward = (0..model.nq())
        .map(|i| {
            let h = ws.pose_in_parent[i];
            let (parent_twist, parent_twist_dot) = match parents[i] {
                Some(p) => (
                    h.inv_act_twist(&ws.twist[p]),
                    h.inv_act_twist(&ws.twist_dot[p]),
                ),
                None => (Twist::zeros(), h.inv_act_twist(&base)),
            };
            ForwardStep {
                q: q[i],
                v: v[i],
                a: a[i],
                pose_in_parent: h,
                parent_twist,
                parent_twist_dot,
                twist: ws.twist[i],
                twist_dot: ws.twist_dot[i],
            }
        })
        .collect();
    let backward = (0..model.nq())
        .map(|i| {
            let inertia = &model.bodies()[i].inertia;
            let (vi, vdi) = (ws.twist[i], ws.twist_dot[i]);
            let external = fext.map_or(Wrench::zeros(), |f| f.on_body_at(&ws.pose_in_world[i], i));
            BackwardStep {
                inertial: inertia.apply(&vdi) - ad_transpose(&vi, &inertia.apply(&vi)),
                external,
                from_children: model.children[i]
                    .iter()
                    .map(|&c| {
                        let back = ws.pose_in_parent[c].inv_act_transpose_wrench(&ws.wrench[c]);
                        (c, back)
                    })
                    .collect(),
                wrench: ws.wrench[i],
                tau: tau[i],
            }
        })
        .collect();
    Ok(RneaTrace {
        base_acceleration: base,
        forward,
        backward,
        tau,
    })
}
