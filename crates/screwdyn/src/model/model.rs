//! The immutable [`Model`].

use super::findings::PhysicalFinding;
use super::joint::Joint;
use super::motion::JointMotion;
use super::spine::Spine;
use crate::error::{Error, Result};
use crate::scalar::Real;
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::Vector3;
use std::collections::HashMap;

/// A rigid body (a link, with any fixed children merged in).
#[derive(Clone, Debug, PartialEq)]
pub struct Body<T: Real = f64> {
    /// The link name.
    pub name: String,
    /// `𝔍^{i,i}`: spatial inertia in the body frame (fixed children included).
    pub inertia: SpatialInertia<T>,
}

/// What a frame marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    /// The base frame {0} (the root link).
    Base,
    /// The frame of a moving body.
    Body,
    /// A link attached by a fixed joint, merged into its parent body.
    FixedLink,
    /// An extra named frame (a tool point, a sensor...).
    Extra,
}

/// A named frame rigidly attached to a body (or to the base).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame<T: Real = f64> {
    /// Unique frame name.
    pub name: String,
    /// The body it moves with; `None` for the base.
    pub body: Option<usize>,
    /// `H_f^b`: pose of the frame in its body's frame (in the base frame if `body` is `None`).
    pub placement: Se3<T>,
    /// What the frame marks.
    pub kind: FrameKind,
}

/// A fixed-base kinematic tree with inertias: the input of every algorithm.
///
/// Built by [`ModelBuilder`](super::ModelBuilder), a description loader or
/// [`builtin`](crate::builtin); read-only afterwards. Per-call results live in a
/// [`Workspace`](crate::Workspace).
#[derive(Clone, Debug, PartialEq)]
pub struct Model<T: Real = f64> {
    pub(crate) name: String,
    pub(crate) joints: Vec<Joint<T>>,
    pub(crate) bodies: Vec<Body<T>>,
    pub(crate) parents: Vec<Option<usize>>,
    pub(crate) children: Vec<Vec<usize>>,
    pub(crate) frames: Vec<Frame<T>>,
    pub(crate) gravity: Vector3<T>,
    pub(crate) base: Body<T>,
    pub(crate) meshes: Vec<(String, String)>,
    /// Derived from `joints` at build time (see [`Model::motions`]).
    pub(crate) motions: Vec<JointMotion<T>>,
    /// Derived: the largest entry of any body's 6×6 spatial inertia (ABA's singularity scale).
    pub(crate) inertia_scale: T,
    /// Derived: the shape of each body's `I_c` ([`InertiaForm`](crate::spatial::inertia_in_world::InertiaForm)),
    /// which decides how `R I_c Rᵀ` is formed in {0}.
    pub(crate) body_inertia_form: Vec<crate::spatial::inertia_in_world::InertiaForm<T>>,
    /// Derived: the tree is a single chain (`λ(i) = i − 1`).
    pub(crate) is_chain: bool,
    /// Derived: for each body `k`, the first body `j ≤ k` of the unbranched run ending at `k`
    /// (`λ(t) = t − 1` for every `t` in `j + 1..=k`): the ancestors of a body are a few runs of
    /// consecutive indices (CRBA's base-frame form walks them run by run).
    pub(crate) run_start: Vec<usize>,
    /// Derived: the chain and the leaf bodies on it, when the tree is one (see [`Spine`];
    /// CRBA's pass for such trees).
    pub(crate) spine: Option<Spine>,
    /// Derived: the index of each body's frame in `frames`.
    pub(crate) body_frames: Vec<usize>,
    /// Frame name → index in `frames`.
    pub(crate) frame_index: HashMap<String, usize>,
    /// Physical-consistency problems found when the model was built.
    pub(crate) findings: Vec<PhysicalFinding>,
    /// Named configurations (MJCF `<keyframe>`s), each `q` in joint order.
    pub(crate) keyframes: Vec<(String, Vec<T>)>,
}

/// `Err(NonFinite)` naming `what` and the position of the first NaN or infinite value.
#[inline]
pub(crate) fn check_finite<T: Real>(x: &[T], what: &str) -> Result<()> {
    match first_non_finite(x) {
        None => Ok(()),
        Some(i) => Err(non_finite_error(x, i, what)),
    }
}

/// The rule every front-end applies to what it returns: a result computed from finite inputs
/// that is NaN or infinite (say RNEA at `q̇ = 10²⁰⁰`) is an [`Error::Overflow`] naming the entry
/// by `name(index)`, never a NaN handed back as a number.
///
/// # Errors
/// [`Error::Overflow`] for the first non-finite entry.
///
/// ```
/// let e = screwdyn::check_result(&[1.0, f64::INFINITY], |i| format!("tau[{i}]")).unwrap_err();
/// assert_eq!(
///     e.to_string(),
///     "the result tau[1] is not finite (NaN or infinite): the inputs are too large for double precision"
/// );
/// assert!(screwdyn::check_result(&[1.0, 2.0], |i| i.to_string()).is_ok());
/// ```
#[inline]
pub fn check_result<T: Real>(values: &[T], name: impl FnOnce(usize) -> String) -> Result<()> {
    match first_non_finite(values) {
        None => Ok(()),
        Some(i) => Err(Error::Overflow { what: name(i) }),
    }
}

/// The index of the first NaN or infinite entry, `None` when all are finite. A branch-free pass
/// first (every call of every algorithm makes it): `0 · v` is ±0 for a finite `v` and NaN for
/// ±∞ or NaN, and a NaN anywhere makes the sum NaN; the position only when something is wrong.
/// The sums are kept in four independent lanes, so the loop vectorises instead of adding one
/// entry after another.
#[inline]
pub(crate) fn first_non_finite<T: Real>(x: &[T]) -> Option<usize> {
    let mut lanes = [T::zero(); 4];
    let mut chunks = x.chunks_exact(4);
    for chunk in &mut chunks {
        for (lane, &v) in lanes.iter_mut().zip(chunk) {
            *lane += v * T::zero();
        }
    }
    for (lane, &v) in lanes.iter_mut().zip(chunks.remainder()) {
        *lane += v * T::zero();
    }
    if (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) == T::zero() {
        return None;
    }
    position_of_non_finite(x)
}

#[cold]
fn position_of_non_finite<T: Real>(x: &[T]) -> Option<usize> {
    x.iter().position(|v| !v.is_finite())
}

#[cold]
fn non_finite_error<T: Real>(x: &[T], i: usize, what: &str) -> Error {
    Error::NonFinite {
        what: what.into(),
        index: i,
        value: format!("{:?}", x[i]),
    }
}

fn list(names: impl Iterator<Item = String>) -> String {
    let v: Vec<String> = names.collect();
    if v.len() > 12 {
        format!("{}, … ({} in all)", v[..12].join(", "), v.len())
    } else {
        v.join(", ")
    }
}

impl<T: Real> Model<T> {
    /// The names of the model's keyframes (named configurations), in file order.
    pub fn keyframe_names(&self) -> Vec<&str> {
        self.keyframes.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The named configuration `name` (an MJCF `<key>`), `q` in joint order.
    ///
    /// # Errors
    /// [`Error::UnknownName`] when the model has no keyframe of that name.
    ///
    /// ```
    /// use screwdyn::io::{load_str, LoadOptions};
    /// let text = r#"<mujoco><worldbody><body name="a"><joint name="j" axis="0 0 1"/>
    ///   <geom size="0.1"/></body></worldbody>
    ///   <keyframe><key name="up" qpos="0.5"/></keyframe></mujoco>"#;
    /// let m = load_str(text, "one.xml", &LoadOptions::default()).unwrap();
    /// assert_eq!(m.keyframe("up").unwrap(), &[0.5]);
    /// assert_eq!(m.keyframe_names(), vec!["up"]);
    /// assert!(m.keyframe("down").is_err());
    /// ```
    pub fn keyframe(&self, name: &str) -> Result<&[T]> {
        self.keyframes
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, q)| q.as_slice())
            .ok_or_else(|| Error::UnknownName {
                kind: "keyframe",
                name: name.into(),
                known: self.keyframe_names().join(", "),
            })
    }

    /// The physical-consistency problems found when the model was built (an empty list for a
    /// consistent model): each names the link, where it was declared and what is wrong. They
    /// do not stop any algorithm; forward dynamics refuses only a mass matrix that is really
    /// singular.
    pub fn physical_problems(&self) -> &[PhysicalFinding] {
        &self.findings
    }
    /// The robot's name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Number of joint coordinates (`nq == nv`, one per moving joint).
    pub fn nq(&self) -> usize {
        self.joints.len()
    }
    /// Number of joint velocities (equal to [`Model::nq`]).
    pub fn nv(&self) -> usize {
        self.joints.len()
    }
    /// Number of moving bodies (equal to [`Model::nq`]).
    pub fn nbodies(&self) -> usize {
        self.bodies.len()
    }
    /// The moving joints in coordinate order.
    pub fn joints(&self) -> &[Joint<T>] {
        &self.joints
    }
    /// The joints' screw axes classified for the per-call algorithms (axis-aligned revolute
    /// and prismatic joints get cheap special cases), in coordinate order.
    #[inline]
    pub fn motions(&self) -> &[JointMotion<T>] {
        &self.motions
    }
    /// Fills `motions` from the joints' screw axes.
    pub(crate) fn with_motions(mut self) -> Self {
        self.motions = self
            .joints
            .iter()
            .map(|j| JointMotion::classify(&j.screw))
            .collect();
        self.body_inertia_form = self
            .bodies
            .iter()
            .map(|b| crate::spatial::inertia_in_world::InertiaForm::of(&b.inertia.inertia_com))
            .collect();
        self.is_chain = self
            .parents
            .iter()
            .enumerate()
            .all(|(i, p)| *p == i.checked_sub(1));
        self.run_start = Vec::with_capacity(self.parents.len());
        for (k, p) in self.parents.iter().enumerate() {
            let start = match *p {
                Some(p) if p + 1 == k => self.run_start[p],
                _ => k,
            };
            self.run_start.push(start);
        }
        self.spine = Spine::find(&self.parents);
        self.body_frames = vec![0; self.bodies.len()];
        for (k, f) in self.frames.iter().enumerate() {
            if let (FrameKind::Body, Some(b)) = (f.kind, f.body) {
                self.body_frames[b] = k;
            }
        }
        self.inertia_scale = self
            .bodies
            .iter()
            .fold(T::zero(), |s, b| s.max(b.inertia.matrix().amax()));
        self
    }
    /// The largest entry of any moving body's 6×6 spatial inertia (a scale for singularity
    /// tests).
    #[inline]
    pub fn inertia_scale(&self) -> T {
        self.inertia_scale
    }
    /// The moving bodies; body `i` is moved by joint `i`.
    pub fn bodies(&self) -> &[Body<T>] {
        &self.bodies
    }
    /// `λ(i)`: the parent body of body `i` (`None` for the base).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the model has no body `i`.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert_eq!(m.parent(1).unwrap(), Some(0));
    /// assert!(m.parent(2).is_err());
    /// ```
    pub fn parent(&self, i: usize) -> Result<Option<usize>> {
        self.check_body(i)?;
        Ok(self.parents[i])
    }
    /// The parent array `λ`.
    pub fn parents(&self) -> &[Option<usize>] {
        &self.parents
    }
    /// The child bodies of body `i`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the model has no body `i`.
    pub fn children(&self, i: usize) -> Result<&[usize]> {
        self.check_body(i)?;
        Ok(&self.children[i])
    }
    /// Body `i`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the model has no body `i`.
    pub fn body(&self, i: usize) -> Result<&Body<T>> {
        self.check_body(i)?;
        Ok(&self.bodies[i])
    }
    /// Frame `f`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the model has no frame `f`.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert_eq!(m.frame(m.frame_id("link1").unwrap()).unwrap().name, "link1");
    /// assert!(m.frame(100).unwrap_err().to_string().contains("frame 100"));
    /// ```
    pub fn frame(&self, f: usize) -> Result<&Frame<T>> {
        self.frames.get(f).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "frame {f} is out of range: the model '{}' has {} frames",
                self.name,
                self.frames.len()
            ))
        })
    }
    /// Checks that `i` is a body index of this model.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the index and the number of bodies.
    pub fn check_body(&self, i: usize) -> Result<()> {
        if i >= self.bodies.len() {
            return Err(Error::InvalidArgument(format!(
                "body {i} is out of range: the model '{}' has {} moving bodies",
                self.name,
                self.bodies.len()
            )));
        }
        Ok(())
    }
    /// Every named frame: the base, each body, merged fixed links and extra frames.
    pub fn frames(&self) -> &[Frame<T>] {
        &self.frames
    }
    /// Gravity `g⁰` in the base frame (m/s²).
    pub fn gravity(&self) -> Vector3<T> {
        self.gravity
    }
    /// The root link (fixed; its inertia does not enter the dynamics).
    pub fn base(&self) -> &Body<T> {
        &self.base
    }
    /// `(link, mesh path)` pairs from URDF `<visual>`/`<collision>` tags, kept for viewers.
    pub fn meshes(&self) -> &[(String, String)] {
        &self.meshes
    }
    /// A copy of the model with another gravity vector `g⁰` (m/s², base frame).
    ///
    /// # Errors
    /// [`Error::NonFinite`] when a component is NaN or infinite.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// let m = screwdyn::builtin::planar2().with_gravity(Vector3::zeros()).unwrap();
    /// assert_eq!(m.gravity(), Vector3::zeros());
    /// assert!(m.with_gravity(Vector3::new(0.0, f64::NAN, 0.0)).is_err());
    /// ```
    pub fn with_gravity(&self, g: Vector3<T>) -> Result<Self> {
        check_finite(g.as_slice(), "gravity")?;
        let mut m = self.clone();
        m.gravity = g;
        Ok(m)
    }
    /// A copy of the model with these viscous damping and Coulomb friction coefficients, one
    /// per joint (non-negative and finite).
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch)/[`Error::NonFinite`](crate::Error::NonFinite) for a vector of the wrong length or with NaN/∞; [`Error::InvalidArgument`](crate::Error::InvalidArgument) for a negative value.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2().with_joint_friction(&[0.5, 0.2], &[0.0, 0.1]).unwrap();
    /// assert_eq!(m.joints()[1].damping, 0.2);
    /// assert!(screwdyn::builtin::planar2().with_joint_friction(&[-1.0, 0.0], &[0.0, 0.0]).is_err());
    /// ```
    pub fn with_joint_friction(&self, damping: &[T], friction: &[T]) -> Result<Self> {
        self.check_vector(damping, "damping")?;
        self.check_vector(friction, "friction")?;
        let mut m = self.clone();
        for (i, j) in m.joints.iter_mut().enumerate() {
            if damping[i] < T::zero() || friction[i] < T::zero() {
                return Err(Error::InvalidArgument(format!(
                    "joint '{}': damping and friction must be non-negative (got {:?} and {:?})",
                    j.name, damping[i], friction[i]
                )));
            }
            j.damping = damping[i];
            j.friction = friction[i];
        }
        Ok(m)
    }
    /// A copy with every joint's armature `I_a,i` (the rotor inertia reflected to the joint,
    /// kg·m² or kg) set from `armature`, one value per joint; it is added to `M(q)`'s diagonal
    /// and so enters every dynamics algorithm.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch)/[`Error::NonFinite`](crate::Error::NonFinite) for a vector of the wrong length or with NaN/∞; [`Error::InvalidArgument`](crate::Error::InvalidArgument) for a negative value.
    ///
    /// ```
    /// use screwdyn::{builtin, dynamics::crba, Workspace};
    /// let m = builtin::pendulum().with_armature(&[0.25]).unwrap();
    /// let mut ws = Workspace::new(&m);
    /// // M = m l² + I_a for the 1 kg, 1 m point-mass pendulum.
    /// assert!((crba(&m, &mut ws, &[0.3]).unwrap()[(0, 0)] - 1.25).abs() < 1e-12);
    /// assert!(builtin::pendulum().with_armature(&[-1.0]).is_err());
    /// ```
    pub fn with_armature(&self, armature: &[T]) -> Result<Self> {
        self.check_vector(armature, "armature")?;
        let mut m = self.clone();
        for (j, &a) in m.joints.iter_mut().zip(armature) {
            if a < T::zero() {
                return Err(Error::InvalidArgument(format!(
                    "joint '{}': the armature must be non-negative (got {a:?})",
                    j.name
                )));
            }
            j.armature = a;
        }
        Ok(m)
    }
    /// A copy with every joint's spring set: stiffness `k_i` (N·m/rad or N/m, non-negative)
    /// and rest position `q_spring,i` (rad or m), one value per joint. Simulation then applies
    /// the passive torque `τ_i = −k_i (q_i − q_spring,i)` (MuJoCo's `stiffness` and `springref`);
    /// the equations of motion (`M`, `C q̇ + g`) do not change.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch)/[`Error::NonFinite`](crate::Error::NonFinite) for a vector of the wrong length or with NaN/∞; [`Error::InvalidArgument`](crate::Error::InvalidArgument) for a negative stiffness.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2().with_springs(&[2.0, 0.0], &[0.5, 0.0]).unwrap();
    /// assert_eq!((m.joints()[0].stiffness, m.joints()[0].springref), (2.0, 0.5));
    /// assert!(screwdyn::builtin::planar2().with_springs(&[-1.0, 0.0], &[0.0, 0.0]).is_err());
    /// ```
    pub fn with_springs(&self, stiffness: &[T], springref: &[T]) -> Result<Self> {
        self.check_vector(stiffness, "stiffness")?;
        self.check_vector(springref, "springref")?;
        let mut m = self.clone();
        for (i, j) in m.joints.iter_mut().enumerate() {
            if stiffness[i] < T::zero() {
                return Err(Error::InvalidArgument(format!(
                    "joint '{}': the spring stiffness must be non-negative (got {:?})",
                    j.name, stiffness[i]
                )));
            }
            j.stiffness = stiffness[i];
            j.springref = springref[i];
        }
        Ok(m)
    }
    /// Joint names in coordinate order.
    pub fn joint_names(&self) -> Vec<&str> {
        self.joints.iter().map(|j| j.name.as_str()).collect()
    }
    /// The bodies from the root down to `i` (the support of body `i`, `i` last).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the model has no body `i`.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert_eq!(m.support(1).unwrap(), vec![0, 1]);
    /// ```
    pub fn support(&self, i: usize) -> Result<Vec<usize>> {
        self.check_body(i)?;
        let mut s = vec![i];
        let mut k = i;
        while let Some(p) = self.parents[k] {
            s.push(p);
            k = p;
        }
        s.reverse();
        Ok(s)
    }
    /// Whether body `j` is body `i` or one of its ancestors.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the model has no body `i` or `j`.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert!(m.supports(0, 1).unwrap() && !m.supports(1, 0).unwrap());
    /// ```
    pub fn supports(&self, j: usize, i: usize) -> Result<bool> {
        self.check_body(i)?;
        self.check_body(j)?;
        Ok(self.supports_unchecked(j, i))
    }
    /// [`Model::supports`] for indices known to be in range.
    #[inline]
    pub(crate) fn supports_unchecked(&self, j: usize, i: usize) -> bool {
        let mut k = Some(i);
        while let Some(b) = k {
            if b == j {
                return true;
            }
            if b < j {
                return false;
            }
            k = self.parents[b];
        }
        false
    }
    /// Total mass of the moving bodies (the base excluded).
    pub fn total_mass(&self) -> T {
        self.bodies
            .iter()
            .fold(T::zero(), |s, b| s + b.inertia.mass)
    }

    /// The index of the frame called `name`.
    ///
    /// # Errors
    /// [`Error::UnknownName`](crate::Error::UnknownName) listing the known names.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert!(m.frame_id("link2").is_ok());
    /// let e = m.frame_id("hand").unwrap_err().to_string();
    /// assert!(e.contains("no frame named 'hand'"));
    /// ```
    pub fn frame_id(&self, name: &str) -> Result<usize> {
        self.frame_index
            .get(name)
            .copied()
            .ok_or_else(|| Error::UnknownName {
                kind: "frame",
                name: name.into(),
                known: list(self.frames.iter().map(|f| f.name.clone())),
            })
    }
    /// The index of the frame of the link called `name`: a moving body or a link attached by a
    /// fixed joint (merged into the body it hangs from), the base included; extra frames (a
    /// tool point, a sensor) are not links.
    ///
    /// # Errors
    /// [`Error::UnknownName`](crate::Error::UnknownName) listing the links.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert_eq!(m.link_frame_id("link2").unwrap(), m.frame_id("link2").unwrap());
    /// let e = m.link_frame_id("hand").unwrap_err().to_string();
    /// assert!(e.contains("no link named 'hand'"));
    /// ```
    pub fn link_frame_id(&self, name: &str) -> Result<usize> {
        let is_link = |f: &Frame<T>| f.kind != FrameKind::Extra;
        match self.frame_index.get(name) {
            Some(&k) if is_link(&self.frames[k]) => Ok(k),
            _ => Err(Error::UnknownName {
                kind: "link",
                name: name.into(),
                known: list(
                    self.frames
                        .iter()
                        .filter(|f| is_link(f))
                        .map(|f| f.name.clone()),
                ),
            }),
        }
    }
    /// The index of the moving body (link) called `name`.
    ///
    /// # Errors
    /// [`Error::UnknownName`](crate::Error::UnknownName) listing the known names.
    pub fn body_id(&self, name: &str) -> Result<usize> {
        self.bodies
            .iter()
            .position(|b| b.name == name)
            .ok_or_else(|| Error::UnknownName {
                kind: "moving body",
                name: name.into(),
                known: list(self.bodies.iter().map(|b| b.name.clone())),
            })
    }
    /// The index of the joint called `name`.
    ///
    /// # Errors
    /// [`Error::UnknownName`](crate::Error::UnknownName) listing the known names.
    pub fn joint_id(&self, name: &str) -> Result<usize> {
        self.joints
            .iter()
            .position(|j| j.name == name)
            .ok_or_else(|| Error::UnknownName {
                kind: "joint",
                name: name.into(),
                known: list(self.joints.iter().map(|j| j.name.clone())),
            })
    }
    /// The frame of body `i` (every body has one, named after its link).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the model has no body `i`.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// assert_eq!(m.frames()[m.body_frame(1).unwrap()].name, "link2");
    /// ```
    pub fn body_frame(&self, i: usize) -> Result<usize> {
        self.check_body(i)?;
        Ok(self.body_frames[i])
    }

    /// Checks that a joint-space vector has `nq` finite entries; `what` names it in the error.
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) naming the joints, or [`Error::NonFinite`](crate::Error::NonFinite) naming the position.
    ///
    /// ```
    /// let m = screwdyn::builtin::planar2();
    /// let e = m.check_vector(&[0.1, 0.2, 0.3], "--q").unwrap_err();
    /// assert_eq!(e.to_string(), "--q has 3 values, the model has 2 joints: joint1, joint2");
    /// ```
    #[inline]
    pub fn check_vector(&self, x: &[T], what: &str) -> Result<()> {
        if x.len() != self.nq() {
            return Err(self.length_error(x.len(), what));
        }
        check_finite(x, what)
    }

    #[cold]
    fn length_error(&self, got: usize, what: &str) -> Error {
        Error::DimensionMismatch {
            what: what.into(),
            got,
            expected: self.nq(),
            names: self.joint_names().join(", "),
        }
    }
}

impl Model<f64> {
    /// `τ += k ∘ (q − q_spring) + f ∘ sign(q̇)`: every joint's spring and Coulomb friction
    /// ([`Joint::spring_and_friction_torque`]) added to the torques `tau` at positions `q` moving
    /// with speeds `qd` (all of the model's length), as torque profiles and the time-optimal
    /// timing add them to inverse dynamics.
    pub(crate) fn add_spring_and_friction_torques(&self, q: &[f64], qd: &[f64], tau: &mut [f64]) {
        for ((t, j), (q, qd)) in tau.iter_mut().zip(&self.joints).zip(q.iter().zip(qd)) {
            *t += j.spring_and_friction_torque(*q, *qd);
        }
    }

    /// The same model in another scalar type (e.g. `f32`).
    ///
    /// ```
    /// let m32: screwdyn::Model<f32> = screwdyn::builtin::planar2().cast();
    /// assert_eq!(m32.nq(), 2);
    /// ```
    pub fn cast<U: Real>(&self) -> Model<U> {
        let c = |x: &f64| -> U { crate::scalar::real(*x) };
        Model {
            name: self.name.clone(),
            joints: self
                .joints
                .iter()
                .map(|j| Joint {
                    name: j.name.clone(),
                    kind: match j.kind {
                        super::JointKind::Revolute => super::JointKind::Revolute,
                        super::JointKind::Continuous => super::JointKind::Continuous,
                        super::JointKind::Prismatic => super::JointKind::Prismatic,
                        super::JointKind::Helical { pitch } => {
                            super::JointKind::Helical { pitch: c(&pitch) }
                        }
                    },
                    screw: j.screw.map(|x| c(&x)),
                    home: j.home.cast(),
                    limits: super::JointLimits {
                        lower: c(&j.limits.lower),
                        upper: c(&j.limits.upper),
                        velocity: c(&j.limits.velocity),
                        effort: c(&j.limits.effort),
                    },
                    damping: c(&j.damping),
                    friction: c(&j.friction),
                    armature: c(&j.armature),
                    stiffness: c(&j.stiffness),
                    springref: c(&j.springref),
                    mimic: j.mimic.clone(),
                })
                .collect(),
            bodies: self
                .bodies
                .iter()
                .map(|b| Body {
                    name: b.name.clone(),
                    inertia: b.inertia.cast(),
                })
                .collect(),
            parents: self.parents.clone(),
            children: self.children.clone(),
            frames: self
                .frames
                .iter()
                .map(|f| Frame {
                    name: f.name.clone(),
                    body: f.body,
                    placement: f.placement.cast(),
                    kind: f.kind,
                })
                .collect(),
            gravity: self.gravity.map(|x| c(&x)),
            base: Body {
                name: self.base.name.clone(),
                inertia: self.base.inertia.cast(),
            },
            meshes: self.meshes.clone(),
            motions: Vec::new(),
            inertia_scale: U::zero(),
            body_inertia_form: Vec::new(),
            is_chain: false,
            run_start: Vec::new(),
            spine: None,
            body_frames: Vec::new(),
            frame_index: self.frame_index.clone(),
            findings: self.findings.clone(),
            keyframes: self
                .keyframes
                .iter()
                .map(|(n, q)| (n.clone(), q.iter().map(c).collect()))
                .collect(),
        }
        .with_motions()
    }
}
