//! Geometric Jacobians (Lynch & Park, *Modern Robotics*): the space Jacobian `J_e^{0,0}`, body Jacobians `J_i^{i,0}`,
//! and frame Jacobians in the world, local and world-aligned conventions.

use super::forward::{forward_kinematics, frame_pose_unchecked};
use crate::error::{Error, Result};
use crate::model::{Frame, Model};
use crate::scalar::Real;
use crate::spatial::{ang, lin, twist, Twist};
use crate::workspace::Workspace;
use nalgebra::Matrix6xX;

/// In which frame a frame's twist (and so its Jacobian) is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Reference {
    /// The spatial twist `V_f^{0,0}` in the base frame {0} (the space Jacobian
    /// `J^{0,0}`; Pinocchio's `WORLD`).
    #[default]
    World,
    /// The body twist `V_f^{f,0}` in the frame itself (body Jacobian `J_f^{f,0}`; `LOCAL`).
    Local,
    /// The frame origin's angular and linear velocity written with base-frame axes
    /// (Pinocchio's `LOCAL_WORLD_ALIGNED`).
    LocalWorldAligned,
}

impl std::str::FromStr for Reference {
    type Err = crate::Error;
    fn from_str(s: &str) -> std::result::Result<Self, crate::Error> {
        match crate::error::choice_key(s).as_str() {
            "world" => Ok(Reference::World),
            "local" => Ok(Reference::Local),
            "world-aligned" | "local-world-aligned" => Ok(Reference::LocalWorldAligned),
            _ => Err(crate::Error::UnknownChoice {
                what: "reference",
                got: s.into(),
                expected: "world, local, world-aligned, WORLD, LOCAL or LOCAL_WORLD_ALIGNED",
            }),
        }
    }
}

/// Forward kinematics plus every joint's screw axis in the base frame,
/// `ws.screw_in_world[j] = Ad_{H_j^0} S_j^{j,λ(j)}` — the columns of the space Jacobian
/// (Lynch & Park, *Modern Robotics*: `J_i^0 = Ad_{e^{[S_1]q_1}⋯e^{[S_{i-1}]q_{i-1}}} S_i^0`).
///
/// # Errors
/// As [`forward_kinematics`].
pub fn compute_joint_jacobians<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
) -> Result<()> {
    forward_kinematics(model, ws, q)?;
    for (j, motion) in model.motions().iter().enumerate() {
        ws.screw_in_world[j] = motion.act(&ws.pose_in_world[j]);
    }
    Ok(())
}

/// Writes the 6×n Jacobian of frame `frame` in `reference` into `out`, from the last
/// [`compute_joint_jacobians`] call: column `j` is non-zero only when joint `j` supports the
/// frame's body. `out` must have `nq` columns.
///
/// # Errors
/// [`Error::InvalidArgument`] when the model has no frame `frame`, `out` does not have `nq`
/// columns, or `ws` was made for another model.
///
/// ```
/// use nalgebra::Matrix6xX;
/// use screwdyn::{builtin, Workspace};
/// use screwdyn::kinematics::{compute_joint_jacobians, frame_jacobian, Reference};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let (q1, q2) = (0.3_f64, 0.5_f64);
/// compute_joint_jacobians(&m, &mut ws, &[q1, q2]).unwrap();
/// let mut j = Matrix6xX::zeros(2);
/// frame_jacobian(&m, &ws, m.frame_id("link2").unwrap(), Reference::LocalWorldAligned, &mut j).unwrap();
/// // The classic planar Jacobian of the tip: ẋ = −L1 s1 q̇1 − L2 s12 (q̇1 + q̇2), ...
/// assert!((j[(3, 0)] - (-q1.sin() - (q1 + q2).sin())).abs() < 1e-15);
/// assert!((j[(4, 1)] - (q1 + q2).cos()).abs() < 1e-15);
/// ```
pub fn frame_jacobian<T: Real>(
    model: &Model<T>,
    ws: &Workspace<T>,
    frame: usize,
    reference: Reference,
    out: &mut Matrix6xX<T>,
) -> Result<()> {
    ws.check(model)?;
    let f = model.frame(frame)?;
    if out.ncols() != model.nq() {
        return Err(Error::InvalidArgument(format!(
            "the Jacobian buffer has {} columns, the model has {} joints",
            out.ncols(),
            model.nq()
        )));
    }
    out.fill(T::zero());
    let Some(body) = f.body else {
        return Ok(());
    };
    let h = frame_pose_unchecked(ws, f);
    let mut k = Some(body);
    while let Some(j) = k {
        let s = &ws.screw_in_world[j];
        let col = match reference {
            Reference::World => *s,
            Reference::Local => h.inv_act_twist(s),
            Reference::LocalWorldAligned => {
                let w = ang(s);
                twist(w, lin(s) - h.translation.cross(&w))
            }
        };
        out.set_column(j, &col);
        k = model.parents()[j];
    }
    Ok(())
}

/// The geometric body Jacobian of link `i`, `J_i^{i,0}(q) = Ad_{H_0^i} J_i^{0,0}(q)`: the
/// `i`-th block row of the `J(θ) = L(θ) S`. Needs [`compute_joint_jacobians`] first.
///
/// # Errors
/// [`Error::InvalidArgument`] when the model has no body `body`, `out` does not have `nq`
/// columns, or `ws` was made for another model.
///
/// ```
/// use nalgebra::Matrix6xX;
/// use screwdyn::{builtin, Workspace, kinematics::{compute_joint_jacobians, link_jacobian}};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// compute_joint_jacobians(&m, &mut ws, &[0.2, 0.4]).unwrap();
/// let mut j = Matrix6xX::zeros(2);
/// link_jacobian(&m, &ws, 0, &mut j).unwrap();
/// // J_1^{1,0} = (S_1^{1,0}, 0)
/// assert_eq!(j.column(0).into_owned(), m.joints()[0].screw);
/// assert_eq!(j.column(1).norm(), 0.0);
/// ```
pub fn link_jacobian<T: Real>(
    model: &Model<T>,
    ws: &Workspace<T>,
    body: usize,
    out: &mut Matrix6xX<T>,
) -> Result<()> {
    frame_jacobian(model, ws, model.body_frame(body)?, Reference::Local, out)
}

/// The twist of frame `f` in `reference`, from the body twists of the last
/// [`forward_velocity`](super::forward_velocity) or
/// [`forward_acceleration`](super::forward_acceleration) call.
///
/// # Errors
/// [`Error::InvalidArgument`] when the model has no frame `frame` or `ws` was made for another
/// model.
///
/// ```
/// use screwdyn::{builtin, Workspace, kinematics::{forward_velocity, frame_twist, Reference}};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// forward_velocity(&m, &mut ws, &[0.0, 0.0], &[1.0, 0.0]).unwrap();
/// // The tip at (2, 0, 0) turning about z at 1 rad/s moves at 2 m/s along y.
/// let v = frame_twist(&m, &ws, m.frame_id("link2").unwrap(), Reference::LocalWorldAligned).unwrap();
/// assert!((v[4] - 2.0).abs() < 1e-15);
/// ```
pub fn frame_twist<T: Real>(
    model: &Model<T>,
    ws: &Workspace<T>,
    frame: usize,
    reference: Reference,
) -> Result<Twist<T>> {
    ws.check(model)?;
    let f = model.frame(frame)?;
    let Some(b) = f.body else {
        return Ok(Twist::zeros());
    };
    let local = f.placement.inv_act_twist(&ws.twist[b]);
    Ok(express(ws, f, reference, &local))
}

/// The time derivative of [`frame_twist`]'s components in `reference`, from the last
/// [`forward_acceleration`](super::forward_acceleration) call: `V̇^{f}` (local), `Ad_{H_f^0} V̇^{f}`
/// (world), and `(R ω̇, R(v̇ + ω × v))` (world-aligned: the classical acceleration of the
/// frame origin).
///
/// # Errors
/// [`Error::InvalidArgument`] when the model has no frame `frame` or `ws` was made for another
/// model.
///
/// ```
/// use screwdyn::{builtin, Workspace, kinematics::{forward_acceleration, frame_acceleration, Reference}};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// forward_acceleration(&m, &mut ws, &[0.0, 0.0], &[0.0, 0.0], &[1.0, 0.0]).unwrap();
/// // Angular acceleration 1 rad/s² about z at radius 2 m: 2 m/s² along y.
/// let a = frame_acceleration(&m, &ws, m.frame_id("link2").unwrap(), Reference::LocalWorldAligned).unwrap();
/// assert!((a[4] - 2.0).abs() < 1e-15);
/// ```
pub fn frame_acceleration<T: Real>(
    model: &Model<T>,
    ws: &Workspace<T>,
    frame: usize,
    reference: Reference,
) -> Result<Twist<T>> {
    ws.check(model)?;
    let f = model.frame(frame)?;
    let Some(b) = f.body else {
        return Ok(Twist::zeros());
    };
    let local_dot = f.placement.inv_act_twist(&ws.twist_dot[b]);
    Ok(match reference {
        Reference::LocalWorldAligned => {
            let local = f.placement.inv_act_twist(&ws.twist[b]);
            let r = frame_pose_unchecked(ws, f).rotation;
            let a = lin(&local_dot) + ang(&local).cross(&lin(&local));
            twist(r * ang(&local_dot), r * a)
        }
        _ => express(ws, f, reference, &local_dot),
    })
}

/// A twist given in frame `f` (`local`) written in `reference`.
fn express<T: Real>(
    ws: &Workspace<T>,
    f: &Frame<T>,
    reference: Reference,
    local: &Twist<T>,
) -> Twist<T> {
    match reference {
        Reference::Local => *local,
        Reference::World => frame_pose_unchecked(ws, f).act_twist(local),
        Reference::LocalWorldAligned => {
            let r = frame_pose_unchecked(ws, f).rotation;
            twist(r * ang(local), r * lin(local))
        }
    }
}
