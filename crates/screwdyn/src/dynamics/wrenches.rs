//! External wrenches on the links and a tip wrench at any frame (Lynch & Park, *Modern Robotics*, "Adding External
//! Wrenches" and "Adding End-effector wrench").

use crate::error::{Error, Result};
use crate::model::{FrameKind, Model};
use crate::scalar::Real;
use crate::spatial::{Se3, Wrench};
use crate::workspace::Workspace;

/// External wrenches acting on the bodies, collected before an algorithm call.
///
/// Lynch & Park, *Modern Robotics* adds `W_ext^{i,i}` (the wrench of the environment **on** link `i`, in frame `i`) to
/// the backward pass, `W = Lᵀ 𝔍 V̇ − Lᵀ ad_Vᵀ 𝔍 V − Lᵀ W_ext`, so that
/// `τ = M q̈ + C q̇ + g − Σ_i J_i^{i,0ᵀ} W_ext^{i,i}`. A wrench may also be given in the base
/// frame (moment about the base origin), and a **tip wrench** `W_tip^{e,e}` — the wrench that
/// frame `e` applies **to** the environment, in frame `e` — enters as `τ = … + J_eᵀ W_tip`.
///
/// Setting wrenches may allocate nothing after [`ExternalWrenches::new`]; algorithms read it
/// without allocating.
///
/// ```
/// use nalgebra::Vector6;
/// use screwdyn::{builtin, dynamics::{inverse_dynamics, ExternalWrenches}, Workspace};
/// let m = builtin::planar2().with_gravity(nalgebra::Vector3::zeros()).unwrap();
/// let mut ws = Workspace::new(&m);
/// // The tip pushes on the environment with 1 N along its local y axis (the link-2 frame).
/// let mut ext = ExternalWrenches::new(&m);
/// ext.add_tip(&m, m.frame_id("link2").unwrap(), Vector6::new(0.0, 0.0, 0.0, 0.0, 1.0, 0.0)).unwrap();
/// let tau = inverse_dynamics(&m, &mut ws, &[0.0, 0.0], &[0.0, 0.0], &[0.0, 0.0], Some(&ext)).unwrap();
/// // Statics: τ = J_eᵀ W_tip = (L1 + L2, L2) · 1 N.
/// assert!((tau[0] - 2.0).abs() < 1e-12 && (tau[1] - 1.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ExternalWrenches<T: Real = f64> {
    /// Per body: wrench on the body, in the body frame (tip wrenches folded in).
    local: Vec<Wrench<T>>,
    /// Per body: wrench on the body, in the base frame.
    world: Vec<Wrench<T>>,
    any_world: bool,
}

fn check_wrench<T: Real>(w: &Wrench<T>, what: &str) -> Result<()> {
    if let Some((i, v)) = w.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(Error::NonFinite {
            what: what.into(),
            index: i,
            value: format!("{v:?}"),
        });
    }
    Ok(())
}

/// The moving body a wrench on the link whose frame is `frame` acts on, and the wrench as that
/// body takes it: unchanged when written in the base frame (`in_world`: the same wrench on the
/// same rigid body), else moved from the link frame `f` to the body frame `b`,
/// `W^{b} = Ad_{H_b^f}ᵀ W^{f}`. The link may be a moving body or a link attached by a fixed joint
/// (merged into the body it hangs from). The one rule behind [`ExternalWrenches::add_on_link`]
/// and the front-ends' simulation disturbances.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no frame
/// `frame`, the frame is not a link (an extra frame) or the link is fixed to the base;
/// [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞ in `w`.
///
/// ```
/// use nalgebra::Vector6;
/// use screwdyn::{builtin, dynamics::link_wrench_on_body};
/// let m = builtin::planar2();
/// let w = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
/// let (body, on_body) = link_wrench_on_body(&m, m.link_frame_id("link2").unwrap(), w, false).unwrap();
/// assert_eq!((body, on_body), (1, w));
/// ```
pub fn link_wrench_on_body<T: Real>(
    model: &Model<T>,
    frame: usize,
    w: Wrench<T>,
    in_world: bool,
) -> Result<(usize, Wrench<T>)> {
    let f = model.frame(frame)?;
    if f.kind == FrameKind::Extra {
        return Err(Error::InvalidArgument(format!(
            "an external wrench on '{}', which is a frame, not a link: name a link",
            f.name
        )));
    }
    let Some(body) = f.body else {
        return Err(Error::InvalidArgument(format!(
            "an external wrench on link '{}', which is fixed to the base and cannot act on the robot",
            f.name
        )));
    };
    check_wrench(&w, "the external wrench")?;
    if in_world {
        Ok((body, w))
    } else {
        // W^{b} = Ad_{H_b^f}ᵀ W^{f} = Ad_{(H_f^b)⁻¹}ᵀ W^{f}.
        Ok((body, f.placement.inv_act_transpose_wrench(&w)))
    }
}

impl<T: Real> ExternalWrenches<T> {
    /// No wrenches, sized for `model`.
    pub fn new(model: &Model<T>) -> Self {
        let n = model.nbodies();
        ExternalWrenches {
            local: vec![Wrench::zeros(); n],
            world: vec![Wrench::zeros(); n],
            any_world: false,
        }
    }

    /// The number of bodies this set was made for.
    pub fn len(&self) -> usize {
        self.local.len()
    }

    /// Whether it was made for a model without moving bodies.
    pub fn is_empty(&self) -> bool {
        self.local.is_empty()
    }

    /// Removes every wrench (keeps the storage).
    pub fn clear(&mut self) {
        self.local.iter_mut().for_each(|w| w.fill(T::zero()));
        self.world.iter_mut().for_each(|w| w.fill(T::zero()));
        self.any_world = false;
    }

    fn check_body(&self, body: usize) -> Result<()> {
        if body >= self.local.len() {
            return Err(Error::InvalidArgument(format!(
                "external wrench on body {body}, but the model has {} moving bodies",
                self.local.len()
            )));
        }
        Ok(())
    }

    /// Adds `W_ext^{i,i}`: a wrench of the environment on body `body`, in the body frame.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no body `body`; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞ in `w`.
    pub fn add_local(&mut self, body: usize, w: Wrench<T>) -> Result<()> {
        self.check_body(body)?;
        check_wrench(&w, "the external wrench")?;
        self.local[body] += w;
        Ok(())
    }

    /// Adds a wrench of the environment on body `body`, in the base frame {0} (moment about the
    /// base origin); converted at call time with `Ad_{H_i^0}ᵀ`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no body `body`; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞ in `w`.
    pub fn add_world(&mut self, body: usize, w: Wrench<T>) -> Result<()> {
        self.check_body(body)?;
        check_wrench(&w, "the external wrench")?;
        self.world[body] += w;
        self.any_world = true;
        Ok(())
    }

    /// Adds a wrench of the environment on the link whose frame is `frame`: a moving body's
    /// frame or a link attached by a fixed joint (merged into the body it hangs from), given in
    /// that link's frame, or in the base frame {0} when `in_world`. A fixed-joint link's wrench
    /// is moved to its body, `W^{b} = Ad_{H_f^b}^{-ᵀ} W^{f}` (a wrench in the base frame needs no
    /// move: it is the same wrench on the same rigid body).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no frame
    /// `frame`, the frame is not a link (an extra frame), the link is fixed to the base, or the
    /// set was made for another model; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞
    /// in `w`.
    ///
    /// ```
    /// use nalgebra::Vector6;
    /// use screwdyn::{builtin, dynamics::ExternalWrenches};
    /// let m = builtin::planar2();
    /// let mut ext = ExternalWrenches::new(&m);
    /// let link2 = m.link_frame_id("link2").unwrap();
    /// ext.add_on_link(&m, link2, Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0), false).unwrap();
    /// assert_eq!(ext.len(), 2);
    /// ```
    pub fn add_on_link(
        &mut self,
        model: &Model<T>,
        frame: usize,
        w: Wrench<T>,
        in_world: bool,
    ) -> Result<()> {
        self.check(model)?;
        let (body, w) = link_wrench_on_body(model, frame, w, in_world)?;
        if in_world {
            self.add_world(body, w)
        } else {
            self.add_local(body, w)
        }
    }

    /// Adds a tip wrench `W_tip^{e,e}`: the wrench that frame `frame` applies to the environment,
    /// written in that frame (Lynch & Park, *Modern Robotics*: `τ = M q̈ + C q̇ + J_eᵀ W_tip`). A frame on the fixed base
    /// is rejected.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no frame `frame`, the frame is fixed to the base, or the set was made for another model; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞ in `w`.
    pub fn add_tip(&mut self, model: &Model<T>, frame: usize, w: Wrench<T>) -> Result<()> {
        self.check(model)?;
        let f = model.frame(frame)?;
        let Some(body) = f.body else {
            return Err(Error::InvalidArgument(format!(
                "tip wrench at frame '{}', which is fixed to the base and cannot act on the robot",
                f.name
            )));
        };
        check_wrench(&w, "the tip wrench")?;
        // The environment pushes back on the body with −W_tip, written in the body frame:
        // Ad_{H_b^e}ᵀ W = Ad_{(H_e^b)⁻¹}ᵀ W.
        self.add_local(body, -f.placement.inv_act_transpose_wrench(&w))
    }

    /// Checks that this set was made for a model with `model.nbodies()` bodies.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming both sizes.
    pub fn check(&self, model: &Model<T>) -> Result<()> {
        if self.local.len() != model.nbodies() {
            return Err(Error::InvalidArgument(format!(
                "the external wrenches were made for a model with {} bodies, this one has {}",
                self.local.len(),
                model.nbodies()
            )));
        }
        Ok(())
    }

    /// `W_ext^{i,i}`: the total wrench on body `i` in its frame, given `ws.pose_in_world` (from
    /// the last forward-kinematics call).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when there is no body `i` or `ws` was made for another model.
    ///
    /// ```
    /// use nalgebra::Vector6;
    /// use screwdyn::{builtin, dynamics::ExternalWrenches, Workspace};
    /// let m = builtin::planar2();
    /// let ws = Workspace::new(&m);
    /// let mut ext = ExternalWrenches::new(&m);
    /// ext.add_local(1, Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0)).unwrap();
    /// assert_eq!(ext.on_body(&ws, 1).unwrap()[2], 1.0);
    /// assert!(ext.on_body(&ws, 2).is_err());
    /// ```
    pub fn on_body(&self, ws: &Workspace<T>, i: usize) -> Result<Wrench<T>> {
        self.check_body(i)?;
        if ws.pose_in_world.len() != self.local.len() {
            return Err(Error::InvalidArgument(format!(
                "the workspace has {} bodies, the external wrenches {}",
                ws.pose_in_world.len(),
                self.local.len()
            )));
        }
        Ok(self.on_body_at(&ws.pose_in_world[i], i))
    }

    /// `W_ext^{0,i}`: the total wrench on body `i` written in the base frame (moment about the
    /// base origin), given the pose `H_i^0` of body `i`; `Ad_{H_0^i}ᵀ W_ext^{i,i}`.
    #[inline]
    pub(crate) fn in_world_at(&self, pose_in_world: &Se3<T>, i: usize) -> Wrench<T> {
        let local = pose_in_world.inv_act_transpose_wrench(&self.local[i]);
        if self.any_world {
            local + self.world[i]
        } else {
            local
        }
    }

    /// Whether any wrench was given in the base frame.
    #[inline]
    pub(crate) fn has_world(&self) -> bool {
        self.any_world
    }

    /// The part of the wrench on body `i` that was given in the base frame (fixed in space),
    /// `None` when no wrench was given in the base frame.
    #[inline]
    pub(crate) fn world_part(&self, i: usize) -> Option<&Wrench<T>> {
        if self.any_world {
            Some(&self.world[i])
        } else {
            None
        }
    }

    /// `W_ext^{i,i}` given the pose `H_i^0` of body `i`.
    #[inline]
    pub(crate) fn on_body_at(&self, pose_in_world: &Se3<T>, i: usize) -> Wrench<T> {
        if self.any_world {
            self.local[i] + pose_in_world.act_transpose_wrench(&self.world[i])
        } else {
            self.local[i]
        }
    }
}
