//! Body twists and accelerations by the forward recursion of Lynch & Park's *Modern Robotics*, and `J̇ q̇`.

use super::forward::forward_kinematics;
use super::jacobian::{frame_acceleration, Reference};
use crate::error::Result;
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::Twist;
use crate::workspace::Workspace;

/// Forward kinematics and body twists: `V_i^{i,0} = Ad_{H_{λ(i)}^i} V_{λ(i)} + S_i q̇_i`
/// (Lynch & Park, *Modern Robotics*, parent-child twist relation). Writes `ws.twist`.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, Workspace, kinematics::forward_velocity};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// forward_velocity(&m, &mut ws, &[0.0, 0.0], &[1.0, 2.0]).unwrap();
/// assert_eq!(ws.twist[1][2], 3.0); // ω_z of link 2 = q̇1 + q̇2
/// ```
pub fn forward_velocity<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
) -> Result<()> {
    forward_kinematics(model, ws, q)?;
    model.check_vector(v, "v")?;
    for (i, m) in model.motions().iter().enumerate() {
        let mut vi = match model.parents()[i] {
            Some(p) => ws.pose_in_parent[i].inv_act_twist(&ws.twist[p]),
            None => Twist::zeros(),
        };
        m.add_scaled(&mut vi, v[i]);
        ws.twist[i] = vi;
    }
    Ok(())
}

/// Forward kinematics, twists and accelerations of every body with the base at rest:
/// `V̇_i = Ad_{H_{λ(i)}^i} V̇_{λ(i)} − ad_{S_i q̇_i}(Ad_{H_{λ(i)}^i} V_{λ(i)}) + S_i q̈_i`
/// (Lynch & Park, *Modern Robotics*). Writes `ws.twist` and `ws.twist_dot`.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, Workspace, kinematics::forward_acceleration};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// forward_acceleration(&m, &mut ws, &[0.0, 0.0], &[1.0, 0.0], &[0.0, 0.0]).unwrap();
/// // Link 1's point mass whirls at 1 rad/s on a 1 m radius: v̇ + ω × v = −1 m/s² along x.
/// let (w, v, vd) = (ws.twist[0].fixed_rows::<3>(0).into_owned(), ws.twist[0].fixed_rows::<3>(3).into_owned(),
///                   ws.twist_dot[0].fixed_rows::<3>(3).into_owned());
/// assert!(((vd + w.cross(&v)).x + 1.0).abs() < 1e-15);
/// ```
pub fn forward_acceleration<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
    a: &[T],
) -> Result<()> {
    forward_velocity(model, ws, q, v)?;
    model.check_vector(a, "a")?;
    propagate_acceleration(model, ws, v, Some(a));
    Ok(())
}

/// The acceleration half of the forward pass, given `ws.pose_in_parent` and `ws.twist`, with
/// the base at rest; `a = None` means `q̈ = 0`.
fn propagate_acceleration<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    v: &[T],
    a: Option<&[T]>,
) {
    for (i, m) in model.motions().iter().enumerate() {
        let h = &ws.pose_in_parent[i];
        let (v_par, vd_par) = match model.parents()[i] {
            Some(p) => (
                h.inv_act_twist(&ws.twist[p]),
                h.inv_act_twist(&ws.twist_dot[p]),
            ),
            None => (Twist::zeros(), Twist::zeros()),
        };
        let mut vdi = vd_par - m.ad_scaled(v[i], &v_par);
        if let Some(a) = a {
            m.add_scaled(&mut vdi, a[i]);
        }
        ws.twist_dot[i] = vdi;
    }
}

/// `J̇(q, q̇) q̇` of frame `f` in `reference`: the frame's acceleration when `q̈ = 0`
/// (overwrites the workspace's twists and accelerations).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞. [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no frame `frame`.
///
/// ```
/// use screwdyn::{builtin, Workspace, kinematics::{frame_jdot_qdot, Reference}};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let f = m.frame_id("link1").unwrap();
/// // Uniform rotation: the tip of link 1 has centripetal acceleration −ω² r.
/// let a = frame_jdot_qdot(&m, &mut ws, &[0.0, 0.0], &[2.0, 0.0], f, Reference::LocalWorldAligned).unwrap();
/// assert!((a[3] + 4.0).abs() < 1e-14);
/// ```
pub fn frame_jdot_qdot<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
    frame: usize,
    reference: Reference,
) -> Result<Twist<T>> {
    model.frame(frame)?;
    forward_velocity(model, ws, q, v)?;
    propagate_acceleration(model, ws, v, None);
    frame_acceleration(model, ws, frame, reference)
}
