//! Inverse dynamics by the recursive Newton–Euler algorithm in the Lie-group form
//! (Lynch & Park, *Modern Robotics*), with gravity as a base acceleration and external wrenches.

use super::inputs::checked_poses;
use super::rnea_in_world::rnea_in_world_passes;
use super::wrenches::ExternalWrenches;
use crate::error::Result;
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::{ad_transpose, twist, Twist};
use crate::workspace::Workspace;
use nalgebra::{DVector, Vector3};

/// `V̇_base = (0, −g⁰)`: the base frame accelerating upwards stands in for gravity (Lynch & Park, *Modern Robotics*,
/// "Einstein's equivalence principle").
#[inline]
pub fn base_acceleration<T: Real>(model: &Model<T>) -> Twist<T> {
    twist(Vector3::zeros(), -model.gravity())
}

/// Both passes of the RNEA in the bodies' own frames (the local form, Lynch & Park's *Modern
/// Robotics*) given `ws.pose_in_parent` (and `ws.pose_in_world` when there are external
/// wrenches); `v = None` means `q̇ = 0`, `qdd(i)` gives `q̈_i`. Writes `ws.twist`,
/// `ws.twist_dot`, `ws.wrench` and `ws.tau`: the body-frame quantities that
/// [`rnea_trace`](crate::dynamics::rnea_trace), the regressor and Walker–Orin's columns read
/// ([`rnea`] itself runs the base-frame passes).
pub(crate) fn rnea_passes<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    v: Option<&[T]>,
    qdd: impl Fn(usize) -> T,
    base: &Twist<T>,
    fext: Option<&ExternalWrenches<T>>,
) {
    // Forward pass (Lynch & Park, *Modern Robotics*):
    //   V_i = Ad_{H_λ^i} V_λ + S_i q̇_i,  V̇_i = Ad_{H_λ^i} V̇_λ − ad_{S_i q̇_i}(Ad_{H_λ^i} V_λ) + S_i q̈_i
    // and the Newton–Euler equation of each body W_i = 𝔍_i V̇_i − ad_{V_i}ᵀ 𝔍_i V_i − W_ext,i.
    let n = model.nbodies();
    // Everything as slices of length n, so that the loops' bounds checks go (parents come
    // before their children, so `p < i` for the parent `p` of `i`).
    let (motions, parents, bodies, joints) = (
        &model.motions()[..n],
        &model.parents()[..n],
        &model.bodies()[..n],
        &model.joints()[..n],
    );
    let pip = &ws.pose_in_parent[..n];
    let piw = &ws.pose_in_world[..n];
    let (twist, twist_dot, wrench, tau) = (
        &mut ws.twist[..n],
        &mut ws.twist_dot[..n],
        &mut ws.wrench[..n],
        &mut ws.tau.as_mut_slice()[..n],
    );
    let v = v.map(|v| &v[..n]);
    for i in 0..n {
        let h = &pip[i];
        let m = &motions[i];
        let (mut vi, mut vdi) = match parents[i] {
            Some(p) => (h.inv_act_twist(&twist[p]), h.inv_act_twist(&twist_dot[p])),
            None => (Twist::zeros(), h.inv_act_twist(base)),
        };
        if let Some(v) = v {
            // ad_{S q̇}(Ad V_λ) is taken before S q̇ is added (ad_{S q̇} S q̇ = 0 anyway).
            vdi -= m.ad_scaled(v[i], &vi);
            m.add_scaled(&mut vi, v[i]);
        }
        m.add_scaled(&mut vdi, qdd(i));
        let inertia = &bodies[i].inertia;
        let mut w = inertia.apply(&vdi) - ad_transpose(&vi, &inertia.apply(&vi));
        if let Some(f) = fext {
            w -= f.on_body_at(&piw[i], i);
        }
        twist[i] = vi;
        twist_dot[i] = vdi;
        wrench[i] = w;
    }
    // Backward pass (Lynch & Park, *Modern Robotics*): W_λ += Ad_{H_λ^i}ᵀ W_i, τ_i = S_iᵀ W_i + I_a,i q̈_i (the
    // armature, the rotor inertia reflected to joint i, accelerates with the joint alone).
    for i in (0..n).rev() {
        let w = wrench[i];
        tau[i] = motions[i].dot(&w) + joints[i].armature * qdd(i);
        if let Some(p) = parents[i] {
            let back = pip[i].inv_act_transpose_wrench(&w);
            wrench[p] += back;
        }
    }
}

/// Inverse dynamics `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` by the recursive Newton–Euler algorithm
/// (Lynch & Park, *Modern Robotics*; Featherstone, *Rigid Body Dynamics Algorithms*), with
/// gravity as the base acceleration `V̇_base = (0, −g)`. Trees are handled: the backward pass
/// sums the children's wrenches. Returns `ws.tau`.
///
/// The passes run in the base frame {0}, with `s_i = Ad_{H_i^0} S_i` and
/// `𝔍_i^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}` (formed from the body's ten inertial parameters):
///
/// Forward pass: `V_i = V_{λ(i)} + s_i q̇_i`, `V̇_i = V̇_{λ(i)} + s_i q̈_i + ad_{V_{λ(i)}}(s_i q̇_i)`.
/// Backward pass: `W_i = 𝔍_i^0 V̇_i − ad_{V_i}ᵀ 𝔍_i^0 V_i + Σ_children W_c`,
/// `τ_i = s_iᵀ W_i + I_a,i q̈_i` (the joint's armature `I_a,i`, [`Joint::armature`](crate::model::Joint::armature)).
///
/// Writes the poses (`ws.pose_in_parent`, `ws.pose_in_world`), `ws.screw_in_world`,
/// `ws.twist_in_world`, `ws.twist_dot_in_world` and `ws.wrench_in_world` (all in {0}), not the
/// body-frame `ws.twist`, `ws.twist_dot`, `ws.wrench` (those are
/// [`rnea_trace`](crate::dynamics::rnea_trace)'s, in the bodies' own frames).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::rnea, Workspace};
/// let m = builtin::planar2(); // point masses, gravity −9.81 ŷ
/// let mut ws = Workspace::new(&m);
/// let tau = rnea(&m, &mut ws, &[0.0, 0.0], &[0.0, 0.0], &[0.0, 0.0]).unwrap();
/// // Craig, *Introduction to Robotics*: g = [m2 g L2 c12 + (m1 + m2) g L1 c1, m2 g L2 c12] = [3g, g] at q = 0.
/// assert!((tau[0] - 3.0 * 9.81).abs() < 1e-12 && (tau[1] - 9.81).abs() < 1e-12);
/// ```
pub fn rnea<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    a: &[T],
) -> Result<&'w DVector<T>> {
    inverse_dynamics(model, ws, q, v, a, None)
}

/// [`rnea`] with external wrenches: `τ = M q̈ + C q̇ + g − Σ_i J_iᵀ W_ext,i (+ J_eᵀ W_tip)`
/// (Lynch & Park, *Modern Robotics*), each `W_ext,i` moved to {0} and taken from body `i`'s
/// wrench in the forward pass. Returns `ws.tau`; writes what [`rnea`] writes.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use nalgebra::Vector6;
/// use screwdyn::{builtin, dynamics::{inverse_dynamics, ExternalWrenches}, Workspace};
/// let m = builtin::pendulum();
/// let mut ws = Workspace::new(&m);
/// // Hold the bob up against gravity from outside: the motor then needs no torque anywhere.
/// let mut ext = ExternalWrenches::new(&m);
/// ext.add_world(0, Vector6::new(0.0, 0.0, 0.0, 0.0, 9.81, 0.0)
///     + Vector6::new(0.0, 0.0, 0.3_f64.sin() * 9.81, 0.0, 0.0, 0.0)).unwrap(); // f = m g ŷ at r = (sin q, −cos q, 0)
/// let tau = inverse_dynamics(&m, &mut ws, &[0.3], &[0.0], &[0.0], Some(&ext)).unwrap();
/// assert!(tau[0].abs() < 1e-12);
/// ```
pub fn inverse_dynamics<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    a: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<&'w DVector<T>> {
    checked_poses(model, ws, q, &[(v, "v"), (a, "a")], fext)?;
    rnea_in_world_passes(model, ws, Some(v), Some(a), fext);
    Ok(&ws.tau)
}

/// Gravity torques `g(q)`: RNEA with `q̇ = q̈ = 0` (Lynch & Park, *Modern Robotics*,
/// `g(θ) = Sᵀ Lᵀ 𝔍 L V̇_base`), in {0} as [`rnea`]: `W_i = 𝔍_i^0 V̇_base + Σ_children W_c`,
/// `τ_i = s_iᵀ W_i`. Returns `ws.gravity_torque`; writes what [`rnea`] writes (and `ws.tau`).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::gravity_torque, Workspace};
/// let m = builtin::pendulum();
/// let mut ws = Workspace::new(&m);
/// // m g l sin q for a pendulum hanging along −y at q = 0.
/// let g = gravity_torque(&m, &mut ws, &[0.5]).unwrap();
/// assert!((g[0] - 9.81 * 0.5_f64.sin()).abs() < 1e-12);
/// ```
pub fn gravity_torque<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
) -> Result<&'w DVector<T>> {
    forward_kinematics(model, ws, q)?;
    rnea_in_world_passes(model, ws, None, None, None);
    ws.gravity_torque.copy_from(&ws.tau);
    Ok(&ws.gravity_torque)
}

/// Nonlinear effects `C(q, q̇) q̇ + g(q)`: [`rnea`] (in {0}) with `q̈ = 0`. Returns
/// `ws.nonlinear_effects`; writes what [`rnea`] writes (and `ws.tau`).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::nonlinear_effects, Workspace};
/// let m = builtin::planar2().with_gravity(nalgebra::Vector3::zeros()).unwrap();
/// let mut ws = Workspace::new(&m);
/// let (q2, qd1) = (0.4_f64, 1.5_f64);
/// let h = nonlinear_effects(&m, &mut ws, &[0.0, q2], &[qd1, 0.0]).unwrap();
/// // Craig, *Introduction to Robotics*: the centrifugal torque at joint 2 is m2 L1 L2 s2 θ̇1².
/// assert!((h[1] - q2.sin() * qd1 * qd1).abs() < 1e-12);
/// ```
pub fn nonlinear_effects<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
) -> Result<&'w DVector<T>> {
    checked_poses(model, ws, q, &[(v, "v")], None)?;
    rnea_in_world_passes(model, ws, Some(v), None, None);
    ws.nonlinear_effects.copy_from(&ws.tau);
    Ok(&ws.nonlinear_effects)
}
