//! [`ModelBuilder`]: declare links by name the way the MATLAB does
//! (`H_0_1_home`, `S_0_0_1`, `I_1`), then `build()` an immutable [`Model`].

use super::findings::{PhysicalFinding, Problem};
use super::joint::{Joint, JointKind, JointLimits, Mimic};
use super::model::{Body, Frame, FrameKind, Model};
use crate::error::{Error, Result};
use crate::scalar::{real, Real};
use crate::spatial::{ang, lin, Se3, SpatialInertia, Twist};
use nalgebra::Vector3;
use std::collections::HashMap;

#[derive(Clone, Copy, Debug, PartialEq)]
enum SpecKind<T: Real> {
    Moving(JointKind<T>),
    Fixed,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum AxisFrame {
    Parent,
    Child,
}

/// A joint declaration: kind, screw axis (in the parent or child frame at home), limits,
/// damping and friction.
///
/// ```
/// use nalgebra::Vector6;
/// use screwdyn::model::JointSpec;
/// let s_0_0_1 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
/// let j = JointSpec::revolute("joint1").screw_in_parent(s_0_0_1).limits(-3.0, 3.0).effort_limit(50.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct JointSpec<T: Real = f64> {
    name: String,
    kind: SpecKind<T>,
    screw: Option<(Twist<T>, AxisFrame)>,
    limits: JointLimits<T>,
    damping: T,
    friction: T,
    armature: T,
    stiffness: T,
    springref: T,
    mimic: Option<Mimic>,
}

impl<T: Real> JointSpec<T> {
    fn new(name: &str, kind: SpecKind<T>) -> Self {
        JointSpec {
            name: name.into(),
            kind,
            screw: None,
            limits: JointLimits::default(),
            damping: T::zero(),
            friction: T::zero(),
            armature: T::zero(),
            stiffness: T::zero(),
            springref: T::zero(),
            mimic: None,
        }
    }
    /// A revolute joint (set its screw with `screw_in_parent` or `screw_in_child`).
    pub fn revolute(name: &str) -> Self {
        Self::new(name, SpecKind::Moving(JointKind::Revolute))
    }
    /// A continuous (unlimited revolute) joint.
    pub fn continuous(name: &str) -> Self {
        Self::new(name, SpecKind::Moving(JointKind::Continuous))
    }
    /// A prismatic joint.
    pub fn prismatic(name: &str) -> Self {
        Self::new(name, SpecKind::Moving(JointKind::Prismatic))
    }
    /// A helical joint with `pitch` metres per radian.
    pub fn helical(name: &str, pitch: T) -> Self {
        Self::new(name, SpecKind::Moving(JointKind::Helical { pitch }))
    }
    /// A fixed joint: the child link is merged into its parent body and kept as a named frame.
    pub fn fixed(name: &str) -> Self {
        Self::new(name, SpecKind::Fixed)
    }
    /// The screw axis written in the parent frame at home, `S_c^{p,p}` (the `S_0_0_1`);
    /// converted to the child frame as `S_c^{c,p} = Ad_{H_c^p(0)⁻¹} S_c^{p,p}`.
    pub fn screw_in_parent(mut self, s: Twist<T>) -> Self {
        self.screw = Some((s, AxisFrame::Parent));
        self
    }
    /// The screw axis written in the child frame, `S_c^{c,p}` (URDF's `<axis>`).
    pub fn screw_in_child(mut self, s: Twist<T>) -> Self {
        self.screw = Some((s, AxisFrame::Child));
        self
    }
    /// Position limits.
    pub fn limits(mut self, lower: T, upper: T) -> Self {
        self.limits.lower = lower;
        self.limits.upper = upper;
        self
    }
    /// Speed limit.
    pub fn velocity_limit(mut self, v: T) -> Self {
        self.limits.velocity = v;
        self
    }
    /// Torque or force limit.
    pub fn effort_limit(mut self, e: T) -> Self {
        self.limits.effort = e;
        self
    }
    /// Viscous damping coefficient.
    pub fn damping(mut self, d: T) -> Self {
        self.damping = d;
        self
    }
    /// Coulomb friction magnitude.
    pub fn friction(mut self, f: T) -> Self {
        self.friction = f;
        self
    }
    /// Armature: rotor inertia reflected to the joint, added to the joint's diagonal of `M(q)`.
    pub fn armature(mut self, a: T) -> Self {
        self.armature = a;
        self
    }
    /// A joint spring: stiffness `k` and rest position `q_spring`, so that simulation applies
    /// `τ = −k (q − q_spring)` (MuJoCo's `stiffness` and `springref`).
    pub fn spring(mut self, stiffness: T, springref: T) -> Self {
        self.stiffness = stiffness;
        self.springref = springref;
        self
    }
    /// Records a URDF mimic tag (information only: the joint stays independent).
    pub fn mimic(mut self, m: Mimic) -> Self {
        self.mimic = Some(m);
        self
    }
    /// The joint name.
    pub fn name(&self) -> &str {
        &self.name
    }
}

#[derive(Clone, Debug)]
struct LinkDecl<T: Real> {
    name: String,
    parent: String,
    joint: JointSpec<T>,
    home: Se3<T>,
    inertia: SpatialInertia<T>,
}

#[derive(Clone, Debug)]
struct FrameDecl<T: Real> {
    name: String,
    link: String,
    placement: Se3<T>,
}

/// Builds a [`Model`] from links declared by name, in any order that names existing parents
/// or not (the tree is resolved at `build`).
///
/// The two-link arm, line by line:
/// ```
/// use nalgebra::{Matrix3, Vector3, Vector6};
/// use screwdyn::model::{JointSpec, ModelBuilder};
/// use screwdyn::spatial::{Se3, SpatialInertia};
/// let (l1, l2, m1, m2) = (1.0, 1.0, 1.0, 1.0);
/// let h_0_1_home = Se3::from_translation(Vector3::new(l1, 0.0, 0.0));
/// let h_1_2_home = Se3::from_translation(Vector3::new(l2, 0.0, 0.0));
/// let s_0_0_1 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
/// let s_1_1_2 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
/// let i_1 = SpatialInertia::point_mass(m1, Vector3::zeros());
/// let i_2 = SpatialInertia::point_mass(m2, Vector3::zeros());
///
/// let mut robot = ModelBuilder::new("two-link");
/// robot.link("link1", "base", JointSpec::revolute("joint1").screw_in_parent(s_0_0_1), h_0_1_home, i_1);
/// robot.link("link2", "link1", JointSpec::revolute("joint2").screw_in_parent(s_1_1_2), h_1_2_home, i_2);
/// let model = robot.build().unwrap();
/// // S_1^{1,0} = Ad_{H_0_1_home⁻¹} S_0_0_1 = (0,0,1, 0,L1,0)
/// assert_eq!(model.joints()[0].screw, Vector6::new(0.0, 0.0, 1.0, 0.0, l1, 0.0));
/// ```
#[derive(Clone, Debug)]
pub struct ModelBuilder<T: Real = f64> {
    name: String,
    base: String,
    base_inertia: SpatialInertia<T>,
    links: Vec<LinkDecl<T>>,
    frames: Vec<FrameDecl<T>>,
    gravity: Vector3<T>,
    strict: bool,
    meshes: Vec<(String, String)>,
    locations: HashMap<String, String>,
    keyframes: Vec<(String, HashMap<String, T>)>,
    warnings: Vec<PhysicalFinding>,
}

impl<T: Real> ModelBuilder<T> {
    /// A new robot whose root link (base frame {0}) is called `base`; gravity `(0, 0, −9.81)`.
    pub fn new(name: &str) -> Self {
        ModelBuilder {
            name: name.into(),
            base: "base".into(),
            base_inertia: SpatialInertia::zero(),
            links: Vec::new(),
            frames: Vec::new(),
            gravity: Vector3::new(T::zero(), T::zero(), real(-9.81)),
            strict: false,
            meshes: Vec::new(),
            locations: HashMap::new(),
            keyframes: Vec::new(),
            warnings: Vec::new(),
        }
    }
    /// Renames the root link (default `base`).
    pub fn base_name(&mut self, name: &str) -> &mut Self {
        self.base = name.into();
        self
    }
    /// The root link's inertia (kept for information; a fixed base does not move).
    pub fn base_inertia(&mut self, i: SpatialInertia<T>) -> &mut Self {
        self.base_inertia = i;
        self
    }
    /// Gravity `g⁰` in the base frame.
    pub fn gravity(&mut self, g: Vector3<T>) -> &mut Self {
        self.gravity = g;
        self
    }
    /// Makes physical-consistency problems (see [`Model::physical_problems`]) errors of
    /// [`build`](ModelBuilder::build) instead of findings.
    pub fn strict(&mut self, strict: bool) -> &mut Self {
        self.strict = strict;
        self
    }
    /// Records where link `link` was declared (e.g. `robot.urdf:42`), for messages.
    pub fn locate(&mut self, link: &str, location: String) -> &mut Self {
        self.locations.insert(link.into(), location);
        self
    }
    /// Declares link `name`, attached to link `parent` by `joint`, with home pose
    /// `home = H_c^p(0)` and spatial inertia `inertia` (in the link frame).
    pub fn link(
        &mut self,
        name: &str,
        parent: &str,
        joint: JointSpec<T>,
        home: Se3<T>,
        inertia: SpatialInertia<T>,
    ) -> &mut Self {
        self.links.push(LinkDecl {
            name: name.into(),
            parent: parent.into(),
            joint,
            home,
            inertia,
        });
        self
    }
    /// Declares an extra named frame rigidly attached to `link` at `placement` (in the link frame).
    pub fn frame(&mut self, name: &str, link: &str, placement: Se3<T>) -> &mut Self {
        self.frames.push(FrameDecl {
            name: name.into(),
            link: link.into(),
            placement,
        });
        self
    }
    /// Declares the named configuration `name`: each joint's value by joint name (every moving
    /// joint must be given; see [`Model::keyframe`]).
    pub fn keyframe(&mut self, name: &str, q: HashMap<String, T>) -> &mut Self {
        self.keyframes.push((name.into(), q));
        self
    }
    /// Records a loader's warning about the description of `what` (a link or joint) declared at
    /// `location`: it joins the model's findings (an error when strict).
    pub fn warn(&mut self, what: &str, location: Option<String>, message: String) -> &mut Self {
        self.warnings.push(PhysicalFinding {
            link: what.into(),
            location,
            problem: Problem::Warning(message),
        });
        self
    }
    /// Records a mesh path of `link` for viewers.
    pub fn mesh(&mut self, link: &str, path: &str) -> &mut Self {
        self.meshes.push((link.into(), path.into()));
        self
    }

    /// Resolves the tree (depth-first order from the root, children in declaration order),
    /// merges fixed joints, converts screw axes to the child frame and checks everything.
    /// Physical-consistency problems of the inertias are not errors: they are listed by
    /// [`Model::physical_problems`] (unless [`ModelBuilder::strict`] is set).
    ///
    /// # Errors
    /// [`Error::InvalidModel`] for a malformed declaration (empty or duplicate names, a missing
    /// parent, a cycle, a NaN or infinite number, limits with lower > upper, a negative
    /// effort, velocity, damping or friction, a screw axis that does not fit the joint kind),
    /// and in strict mode for the first physical-consistency problem.
    pub fn build(&self) -> Result<Model<T>> {
        self.check_declarations()?;
        let order = self.depth_first_order()?;
        let mut model = self.assemble(&order)?;
        self.attach_frames(&mut model)?;
        model.children = vec![Vec::new(); model.bodies.len()];
        for (i, p) in model.parents.iter().enumerate() {
            if let Some(p) = p {
                model.children[*p].push(i);
            }
        }
        model.findings = self.findings(&model);
        model.findings.extend(self.warnings.iter().cloned());
        model.keyframes = self.resolve_keyframes(&model)?;
        if self.strict && !model.findings.is_empty() {
            let all: Vec<String> = model.findings.iter().map(|f| f.to_string()).collect();
            return Err(Error::InvalidModel(format!(
                "the model is not physically consistent: {}",
                all.join("; ")
            )));
        }
        Ok(model.with_motions())
    }

    /// Names, numbers and limits of every declaration, before the tree is resolved.
    fn check_declarations(&self) -> Result<()> {
        let bad = |s: String| Err(Error::InvalidModel(s));
        check_name("root link", &self.base)?;
        if !self.gravity.iter().all(|g| g.is_finite()) {
            return bad("gravity has a non-finite component".into());
        }
        let mut links: HashMap<&str, usize> = HashMap::new();
        let mut joint_names: HashMap<&str, ()> = HashMap::new();
        for (k, l) in self.links.iter().enumerate() {
            check_name("link", &l.name)?;
            check_name("joint", &l.joint.name)?;
            if l.name == self.base {
                return bad(format!(
                    "link '{}' is declared with a parent joint '{}' but is the root link",
                    l.name, l.joint.name
                ));
            }
            if let Some(&prev) = links.get(l.name.as_str()) {
                let a = &self.links[prev];
                return bad(if a.parent != l.parent {
                    format!(
                        "link '{}' has two parents: '{}' (joint '{}') and '{}' (joint '{}')",
                        l.name, a.parent, a.joint.name, l.parent, l.joint.name
                    )
                } else {
                    format!("two links are named '{}'", l.name)
                });
            }
            links.insert(&l.name, k);
            if joint_names.insert(&l.joint.name, ()).is_some() {
                return bad(format!("two joints are named '{}'", l.joint.name));
            }
            if !is_finite_pose(&l.home) {
                return bad(format!(
                    "joint '{}' has a non-finite home pose H_c^p(0)",
                    l.joint.name
                ));
            }
            if l.inertia.physical_problem() == Some(crate::spatial::InertiaProblem::NonFinite) {
                return bad(format!("link '{}' has a non-finite inertia", l.name));
            }
            l.joint.check_values()?;
        }
        for l in &self.links {
            if l.parent != self.base && !links.contains_key(l.parent.as_str()) {
                return bad(format!(
                    "joint '{}' names parent link '{}', which does not exist",
                    l.joint.name, l.parent
                ));
            }
        }
        for f in &self.frames {
            check_name("frame", &f.name)?;
            if !is_finite_pose(&f.placement) {
                return bad(format!("frame '{}' has a non-finite placement", f.name));
            }
        }
        Ok(())
    }

    /// Link indices in depth-first order from the root, children in declaration order.
    fn depth_first_order(&self) -> Result<Vec<usize>> {
        let mut kids: HashMap<&str, Vec<usize>> = HashMap::new();
        for (k, l) in self.links.iter().enumerate() {
            kids.entry(l.parent.as_str()).or_default().push(k);
        }
        let mut order = Vec::with_capacity(self.links.len());
        let mut stack: Vec<usize> = kids
            .get(self.base.as_str())
            .map(|v| v.iter().rev().copied().collect())
            .unwrap_or_default();
        while let Some(k) = stack.pop() {
            order.push(k);
            if let Some(v) = kids.get(self.links[k].name.as_str()) {
                stack.extend(v.iter().rev());
            }
        }
        if order.len() != self.links.len() {
            let mut seen = vec![false; self.links.len()];
            for &k in &order {
                seen[k] = true;
            }
            let lost: Vec<&str> = (0..self.links.len())
                .filter(|&k| !seen[k])
                .map(|k| self.links[k].name.as_str())
                .collect();
            return Err(Error::InvalidModel(format!(
                "links {} form a cycle and are not connected to the root link '{}'",
                lost.join(", "),
                self.base
            )));
        }
        Ok(order)
    }

    /// Joints, bodies and link frames in `order`: a moving joint makes a body, a fixed joint
    /// merges its link into the body it hangs from (inertias combined, the frame kept).
    fn assemble(&self, order: &[usize]) -> Result<Model<T>> {
        let mut m = Model {
            name: self.name.clone(),
            joints: Vec::new(),
            bodies: Vec::new(),
            parents: Vec::new(),
            children: Vec::new(),
            frames: vec![Frame {
                name: self.base.clone(),
                body: None,
                placement: Se3::identity(),
                kind: FrameKind::Base,
            }],
            gravity: self.gravity,
            base: Body {
                name: self.base.clone(),
                inertia: self.base_inertia,
            },
            meshes: self.meshes.clone(),
            motions: Vec::new(),
            inertia_scale: T::zero(),
            body_inertia_form: Vec::new(),
            is_chain: false,
            run_start: Vec::new(),
            spine: None,
            body_frames: Vec::new(),
            findings: Vec::new(),
            frame_index: HashMap::new(),
            keyframes: Vec::new(),
        };
        // Where each link lives: (moving body or base, placement of the link frame in it).
        let mut attach: HashMap<&str, (Option<usize>, Se3<T>)> = HashMap::new();
        attach.insert(&self.base, (None, Se3::identity()));
        for &k in order {
            let l = &self.links[k];
            let (anc, parent_placement) = attach[l.parent.as_str()];
            let home = parent_placement.compose(&l.home);
            let kind = match l.joint.kind {
                SpecKind::Fixed => {
                    let inertia = l.inertia.transformed(&home);
                    let into = match anc {
                        Some(b) => &mut m.bodies[b].inertia,
                        None => &mut m.base.inertia,
                    };
                    *into = into.combined(&inertia);
                    attach.insert(&l.name, (anc, home));
                    FrameKind::FixedLink
                }
                SpecKind::Moving(kind) => {
                    m.joints.push(Joint {
                        name: l.joint.name.clone(),
                        kind,
                        screw: self.child_screw(l, kind)?,
                        home,
                        limits: l.joint.limits,
                        damping: l.joint.damping,
                        friction: l.joint.friction,
                        armature: l.joint.armature,
                        stiffness: l.joint.stiffness,
                        springref: l.joint.springref,
                        mimic: l.joint.mimic.clone(),
                    });
                    m.bodies.push(Body {
                        name: l.name.clone(),
                        inertia: l.inertia,
                    });
                    m.parents.push(anc);
                    attach.insert(&l.name, (Some(m.bodies.len() - 1), Se3::identity()));
                    FrameKind::Body
                }
            };
            let (body, placement) = attach[l.name.as_str()];
            m.frames.push(Frame {
                name: l.name.clone(),
                body,
                placement,
                kind,
            });
        }
        Ok(m)
    }

    /// The extra named frames, placed on the body their link was merged into.
    fn attach_frames(&self, m: &mut Model<T>) -> Result<()> {
        let mut index: HashMap<String, usize> = m
            .frames
            .iter()
            .enumerate()
            .map(|(k, f)| (f.name.clone(), k))
            .collect();
        for f in &self.frames {
            let Some(&link) = index.get(f.link.as_str()) else {
                return Err(Error::InvalidModel(format!(
                    "frame '{}' is attached to link '{}', which does not exist",
                    f.name, f.link
                )));
            };
            if index.contains_key(f.name.as_str()) {
                return Err(Error::InvalidModel(format!(
                    "two frames are named '{}'",
                    f.name
                )));
            }
            let at = &m.frames[link];
            let frame = Frame {
                name: f.name.clone(),
                body: at.body,
                placement: at.placement.compose(&f.placement),
                kind: FrameKind::Extra,
            };
            index.insert(f.name.clone(), m.frames.len());
            m.frames.push(frame);
        }
        m.frame_index = index;
        Ok(())
    }

    /// The physical-consistency problems: every declared link's own inertia (the root link's
    /// is ignored: a fixed base never moves), and moving leaf bodies without mass.
    fn findings(&self, m: &Model<T>) -> Vec<PhysicalFinding> {
        let mut out = Vec::new();
        let location = |link: &str| self.locations.get(link).cloned();
        for l in &self.links {
            if let Some(problem) = l.inertia.physical_problem() {
                out.push(PhysicalFinding {
                    link: l.name.clone(),
                    location: location(&l.name),
                    problem: Problem::Inertia(problem),
                });
            }
        }
        for j in &m.joints {
            if let Some(mimic) = &j.mimic {
                if !m.joints.iter().any(|k| k.name == mimic.joint) {
                    out.push(PhysicalFinding {
                        link: j.name.clone(),
                        location: location(&j.name),
                        problem: Problem::MissingMimicTarget {
                            target: mimic.joint.clone(),
                        },
                    });
                }
            }
        }
        for (i, b) in m.bodies.iter().enumerate() {
            if m.children[i].is_empty() && b.inertia.mass == T::zero() {
                out.push(PhysicalFinding {
                    link: b.name.clone(),
                    location: location(&b.name),
                    problem: Problem::MasslessLeaf {
                        joint: m.joints[i].name.clone(),
                    },
                });
            }
        }
        out
    }

    /// Each keyframe's `q` in joint order: every joint given, no other name, values finite.
    fn resolve_keyframes(&self, m: &Model<T>) -> Result<Vec<(String, Vec<T>)>> {
        let mut out: Vec<(String, Vec<T>)> = Vec::with_capacity(self.keyframes.len());
        for (name, values) in &self.keyframes {
            check_name("keyframe", name)?;
            if out.iter().any(|(n, _)| n == name) {
                return Err(Error::InvalidModel(format!(
                    "two keyframes are named '{name}'"
                )));
            }
            let mut q = Vec::with_capacity(m.joints.len());
            for j in &m.joints {
                match values.get(&j.name) {
                    Some(x) if x.is_finite() => q.push(*x),
                    Some(x) => {
                        return Err(Error::InvalidModel(format!(
                            "keyframe '{name}' gives joint '{}' the non-finite value {x:?}",
                            j.name
                        )))
                    }
                    None => {
                        return Err(Error::InvalidModel(format!(
                            "keyframe '{name}' gives no value for joint '{}'",
                            j.name
                        )))
                    }
                }
            }
            if let Some(extra) = values
                .keys()
                .find(|k| !m.joints.iter().any(|j| &j.name == *k))
            {
                return Err(Error::InvalidModel(format!(
                    "keyframe '{name}' names joint '{extra}', which the model does not have"
                )));
            }
            out.push((name.clone(), q));
        }
        Ok(out)
    }

    fn child_screw(&self, l: &LinkDecl<T>, kind: JointKind<T>) -> Result<Twist<T>> {
        let j = &l.joint;
        let Some((s, frame)) = j.screw else {
            return Err(Error::InvalidModel(format!(
                "joint '{}' has no screw axis",
                j.name
            )));
        };
        if !s.iter().all(|x| x.is_finite()) {
            return Err(Error::InvalidModel(format!(
                "joint '{}' has a non-finite screw axis",
                j.name
            )));
        }
        let s = match frame {
            AxisFrame::Child => s,
            AxisFrame::Parent => l.home.inv_act_twist(&s),
        };
        let (w, v) = (ang(&s), lin(&s));
        let tol: T = real(1e-6);
        let fail = |what: &str| {
            Err(Error::InvalidModel(format!(
                "joint '{}' ({}) has screw axis {:?}: {}",
                j.name,
                kind.name(),
                s.as_slice(),
                what
            )))
        };
        match kind {
            JointKind::Prismatic => {
                if w.norm() > tol {
                    return fail("a prismatic axis must have zero angular part");
                }
                if (v.norm() - T::one()).abs() > tol {
                    return fail("its direction must be a unit vector");
                }
            }
            JointKind::Revolute | JointKind::Continuous | JointKind::Helical { .. } => {
                if (w.norm() - T::one()).abs() > tol {
                    return fail("its rotation axis must be a unit vector");
                }
                let pitch = w.dot(&v);
                let want = match kind {
                    JointKind::Helical { pitch } => pitch,
                    _ => T::zero(),
                };
                if (pitch - want).abs() > tol * (T::one() + v.norm()) {
                    return fail("its pitch ω·v does not match the joint kind");
                }
            }
        }
        Ok(s)
    }
}

/// A name is non-empty and has no control characters (line breaks, tabs…).
fn check_name(what: &str, name: &str) -> Result<()> {
    if name.trim().is_empty() {
        return Err(Error::InvalidModel(format!("a {what} has an empty name")));
    }
    if name.chars().any(char::is_control) {
        return Err(Error::InvalidModel(format!(
            "the {what} name {name:?} contains a control character"
        )));
    }
    Ok(())
}

fn is_finite_pose<T: Real>(h: &Se3<T>) -> bool {
    h.rotation
        .iter()
        .chain(h.translation.iter())
        .all(|x| x.is_finite())
}

impl<T: Real> JointSpec<T> {
    /// Limits, damping, friction, armature, spring and pitch are numbers in range.
    fn check_values(&self) -> Result<()> {
        let bad = |what: String| {
            Err(Error::InvalidModel(format!(
                "joint '{}': {what}",
                self.name
            )))
        };
        let l = &self.limits;
        let nan = |x: T| x.partial_cmp(&x).is_none();
        if nan(l.lower) || nan(l.upper) {
            return bad("a position limit is NaN".into());
        }
        if l.lower > l.upper {
            return bad(format!(
                "the lower position limit {:?} is above the upper limit {:?}",
                l.lower, l.upper
            ));
        }
        for (what, x) in [
            ("velocity limit", l.velocity),
            ("effort limit", l.effort),
            ("damping", self.damping),
            ("friction", self.friction),
            ("armature", self.armature),
            ("spring stiffness", self.stiffness),
        ] {
            if nan(x) || x < T::zero() {
                return bad(format!("the {what} must be non-negative, got {x:?}"));
            }
        }
        for (what, x) in [
            ("damping", self.damping),
            ("friction", self.friction),
            ("armature", self.armature),
            ("spring stiffness", self.stiffness),
            ("spring reference position", self.springref),
        ] {
            if !x.is_finite() {
                return bad(format!("the {what} must be finite, got {x:?}"));
            }
        }
        if let SpecKind::Moving(JointKind::Helical { pitch }) = self.kind {
            if !pitch.is_finite() {
                return bad(format!("the helical pitch must be finite, got {pitch:?}"));
            }
        }
        Ok(())
    }
}
