//! Reading URDF: links, joints and their `file:line`, checked as a tree, into a [`Model`].

use crate::error::{Error, Result};
use crate::io::common::{build, default_name};
use crate::io::options::LoadOptions;
use crate::model::{JointSpec, Mimic, Model, ModelBuilder};
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::{Matrix3, Vector3, Vector6};
use roxmltree::{Document, Node};
use std::collections::HashMap;

struct ULink {
    name: String,
    line: u32,
    inertia: SpatialInertia,
    inertial_line: u32,
}

struct UJoint {
    name: String,
    line: u32,
    kind: String,
    parent: String,
    child: String,
    origin: Se3,
    axis: Vector3<f64>,
    lower: f64,
    upper: f64,
    velocity: f64,
    effort: f64,
    damping: f64,
    friction: f64,
    mimic: Option<Mimic>,
}

struct Ctx<'a> {
    file: &'a str,
    /// Byte offset of the start of every line, for line numbers in O(log n).
    line_starts: Vec<usize>,
}

impl Ctx<'_> {
    fn line(&self, n: Node) -> u32 {
        let at = n.range().start;
        self.line_starts.partition_point(|&s| s <= at) as u32
    }
    fn parse_err(&self, n: Node, msg: String) -> Error {
        Error::parse_at(self.file, self.line(n) as usize, msg)
    }
    fn model_err(&self, line: u32, msg: String) -> Error {
        Error::InvalidModel(format!("{}:{line}: {msg}", self.file))
    }
    fn attr<'n>(&self, n: Node<'n, 'n>, name: &str, owner: &str) -> Result<&'n str> {
        n.attribute(name).ok_or_else(|| {
            self.parse_err(
                n,
                format!(
                    "<{}> of {owner} has no '{name}' attribute",
                    n.tag_name().name()
                ),
            )
        })
    }
    fn numbers(&self, n: Node, name: &str, owner: &str, count: usize) -> Result<Option<Vec<f64>>> {
        let Some(s) = n.attribute(name) else {
            return Ok(None);
        };
        let tag = n.tag_name().name();
        let mut v = Vec::new();
        for w in s.split_whitespace() {
            match w.parse::<f64>() {
                Ok(x) if x.is_finite() => v.push(x),
                _ => {
                    return Err(self.parse_err(
                        n,
                        format!("<{tag} {name}=\"{s}\"> of {owner}: '{w}' is not a finite number"),
                    ))
                }
            }
        }
        if v.len() != count {
            return Err(self.parse_err(
                n,
                format!(
                    "<{tag} {name}=\"{s}\"> of {owner} has {} numbers, expected {count}",
                    v.len()
                ),
            ));
        }
        Ok(Some(v))
    }
    fn number(&self, n: Node, name: &str, owner: &str) -> Result<Option<f64>> {
        Ok(self.numbers(n, name, owner, 1)?.map(|v| v[0]))
    }
    /// A finite number that must not be negative (an effort, speed, damping or friction).
    fn non_negative(&self, n: Node, name: &str, owner: &str) -> Result<Option<f64>> {
        let x = self.number(n, name, owner)?;
        if let Some(x) = x.filter(|x| *x < 0.0) {
            return Err(self.parse_err(
                n,
                format!(
                    "<{} {name}=\"{x}\"> of {owner} is negative; it must be zero or more",
                    n.tag_name().name()
                ),
            ));
        }
        Ok(x)
    }
    /// A name attribute: present, not empty, without control characters.
    fn name(&self, n: Node, owner: &str) -> Result<String> {
        let name = self.attr(n, "name", owner)?;
        if name.trim().is_empty() || name.chars().any(char::is_control) {
            return Err(self.parse_err(
                n,
                format!(
                    "<{}> has the name {name:?}; names must be non-empty, without control characters",
                    n.tag_name().name()
                ),
            ));
        }
        Ok(name.to_string())
    }
    fn vec3(&self, n: Node, name: &str, owner: &str) -> Result<Option<Vector3<f64>>> {
        Ok(self
            .numbers(n, name, owner, 3)?
            .map(|v| Vector3::new(v[0], v[1], v[2])))
    }
    fn origin(&self, parent: Node, owner: &str) -> Result<Se3> {
        let Some(o) = child(parent, "origin") else {
            return Ok(Se3::identity());
        };
        let xyz = self.vec3(o, "xyz", owner)?.unwrap_or_else(Vector3::zeros);
        let rpy = self.vec3(o, "rpy", owner)?.unwrap_or_else(Vector3::zeros);
        Ok(Se3::from_rpy(rpy.x, rpy.y, rpy.z).with_translation(xyz))
    }
}

fn child<'a, 'i>(n: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.is_element() && c.has_tag_name(tag))
}

fn parse_link(ctx: &Ctx, n: Node, b: &mut ModelBuilder) -> Result<ULink> {
    let name = ctx.name(n, "a link")?;
    let owner = format!("link '{name}'");
    let mut link = ULink {
        name: name.clone(),
        line: ctx.line(n),
        inertia: SpatialInertia::zero(),
        inertial_line: ctx.line(n),
    };
    if let Some(inl) = child(n, "inertial") {
        link.inertial_line = ctx.line(inl);
        let origin = ctx.origin(inl, &owner)?;
        let mass = match child(inl, "mass") {
            Some(m) => ctx.number(m, "value", &owner)?.ok_or_else(|| {
                ctx.parse_err(m, format!("<mass> of {owner} has no 'value' attribute"))
            })?,
            None => return Err(ctx.parse_err(inl, format!("<inertial> of {owner} has no <mass>"))),
        };
        let mut i = Matrix3::zeros();
        if let Some(t) = child(inl, "inertia") {
            let g = |a: &str| -> Result<f64> { Ok(ctx.number(t, a, &owner)?.unwrap_or(0.0)) };
            let (xx, xy, xz, yy, yz, zz) = (
                g("ixx")?,
                g("ixy")?,
                g("ixz")?,
                g("iyy")?,
                g("iyz")?,
                g("izz")?,
            );
            i = Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
        }
        let r = origin.rotation;
        link.inertia = SpatialInertia::new(mass, origin.translation, r * i * r.transpose());
    }
    for tag in ["visual", "collision"] {
        for v in n
            .children()
            .filter(|c| c.is_element() && c.has_tag_name(tag))
        {
            if let Some(mesh) = child(v, "geometry").and_then(|g| child(g, "mesh")) {
                if let Some(f) = mesh.attribute("filename") {
                    b.mesh(&name, f);
                }
            }
        }
    }
    Ok(link)
}

fn parse_joint(ctx: &Ctx, n: Node) -> Result<UJoint> {
    let name = ctx.name(n, "a joint")?;
    let owner = format!("joint '{name}'");
    let kind = ctx.attr(n, "type", &owner)?.to_string();
    match kind.as_str() {
        "revolute" | "continuous" | "prismatic" | "fixed" => {}
        "floating" | "planar" => {
            return Err(ctx.model_err(
                ctx.line(n),
                format!("{owner} is {kind}, which screwdyn does not support (fixed-base trees of revolute, continuous, prismatic and fixed joints only)"),
            ))
        }
        other => {
            return Err(ctx.parse_err(
                n,
                format!("{owner} has unknown type '{other}' (expected revolute, continuous, prismatic or fixed)"),
            ))
        }
    }
    let link_of = |tag: &str| -> Result<String> {
        let c = child(n, tag)
            .ok_or_else(|| ctx.parse_err(n, format!("{owner} has no <{tag}> element")))?;
        Ok(ctx.attr(c, "link", &owner)?.to_string())
    };
    let (parent, child_link) = (link_of("parent")?, link_of("child")?);
    let origin = ctx.origin(n, &owner)?;
    let mut axis = Vector3::x();
    if let Some(a) = child(n, "axis") {
        if let Some(v) = ctx.vec3(a, "xyz", &owner)? {
            // Scaled first, so that a huge axis such as 1e308 1e308 0 normalises too.
            let scale = v.amax();
            if scale <= 0.0 || (v / scale).norm() * scale < 1e-12 {
                if kind != "fixed" {
                    return Err(ctx.model_err(
                        ctx.line(a),
                        format!("{owner} has a zero axis; the axis must be a nonzero direction"),
                    ));
                }
            } else if kind != "fixed" {
                let u = v / scale;
                axis = u / u.norm();
            }
        }
    }
    // "No limit" is the model's default limit value.
    let inf = crate::model::JointLimits::<f64>::default().upper;
    let mut j = UJoint {
        name,
        line: ctx.line(n),
        kind,
        parent,
        child: child_link,
        origin,
        axis,
        lower: -inf,
        upper: inf,
        velocity: inf,
        effort: inf,
        damping: 0.0,
        friction: 0.0,
        mimic: None,
    };
    if let Some(l) = child(n, "limit") {
        if j.kind != "continuous" {
            j.lower = ctx.number(l, "lower", &owner)?.unwrap_or(-inf);
            j.upper = ctx.number(l, "upper", &owner)?.unwrap_or(inf);
            if j.lower > j.upper {
                return Err(ctx.parse_err(
                    l,
                    format!(
                        "<limit> of {owner} has lower = {} above upper = {}",
                        j.lower, j.upper
                    ),
                ));
            }
        }
        j.velocity = ctx.non_negative(l, "velocity", &owner)?.unwrap_or(inf);
        j.effort = ctx.non_negative(l, "effort", &owner)?.unwrap_or(inf);
    }
    if let Some(d) = child(n, "dynamics") {
        j.damping = ctx.non_negative(d, "damping", &owner)?.unwrap_or(0.0);
        j.friction = ctx.non_negative(d, "friction", &owner)?.unwrap_or(0.0);
    }
    if let Some(m) = child(n, "mimic") {
        j.mimic = Some(Mimic {
            joint: ctx.attr(m, "joint", &owner)?.to_string(),
            multiplier: ctx.number(m, "multiplier", &owner)?.unwrap_or(1.0),
            offset: ctx.number(m, "offset", &owner)?.unwrap_or(0.0),
        });
    }
    Ok(j)
}

/// Parses URDF text into a [`Model`]; `file` names the source in messages (`file:line: …`).
///
/// # Errors
/// [`Error::Parse`] for malformed XML, a missing attribute or a value out of range (a NaN or
/// infinite number, limits with lower > upper, a negative effort, velocity, damping or
/// friction, an empty name, a mimic of a missing joint), and [`Error::InvalidModel`] for a
/// tree that is not one (two parents, a cycle, no or several roots), each at `file:line`; with
/// `strict`, the first physical-consistency problem.
pub fn parse_urdf(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    let doc = Document::parse(text).map_err(|e| {
        let p = e.pos();
        Error::Parse {
            file: file.into(),
            line: Some(p.row as usize),
            column: Some(p.col as usize),
            message: format!("XML syntax error: {e}"),
        }
    })?;
    let ctx = Ctx {
        file,
        line_starts: std::iter::once(0)
            .chain(text.match_indices('\n').map(|(k, _)| k + 1))
            .collect(),
    };
    let root = doc.root_element();
    if !root.has_tag_name("robot") {
        return Err(ctx.parse_err(
            root,
            format!(
                "the root element is <{}>, expected <robot>",
                root.tag_name().name()
            ),
        ));
    }
    let robot_name = root
        .attribute("name")
        .map(str::to_string)
        .unwrap_or_else(|| default_name(file));
    let mut b = ModelBuilder::new(&robot_name);
    b.strict(options.strict);
    let e = read_elements(&ctx, root, &mut b)?;
    let root_link = check_tree(&ctx, root, &e)?;
    // Findings name the <inertial> element of a link and the <joint> element of a mimic.
    for l in &e.links {
        b.locate(&l.name, format!("{}:{}", ctx.file, l.inertial_line));
    }
    for j in e.joints.iter().filter(|j| j.mimic.is_some()) {
        b.locate(&j.name, format!("{}:{}", ctx.file, j.line));
    }
    b.base_name(&root_link.name).base_inertia(root_link.inertia);
    for j in &e.joints {
        let inertia = e.links[e.link_at[j.child.as_str()]].inertia;
        b.link(&j.child, &j.parent, joint_spec(j), j.origin, inertia);
    }
    build(&b, file)
}

/// The `<link>` and `<joint>` elements in file order, names unique, mimics resolved.
struct Elements {
    links: Vec<ULink>,
    joints: Vec<UJoint>,
    link_at: HashMap<String, usize>,
}

fn read_elements(ctx: &Ctx, root: Node, b: &mut ModelBuilder) -> Result<Elements> {
    let mut e = Elements {
        links: Vec::new(),
        joints: Vec::new(),
        link_at: HashMap::new(),
    };
    // A mimic naming a missing joint is a finding of the builder (Pinocchio loads such files).
    let mut joint_at: HashMap<String, usize> = HashMap::new();
    let twice = |what: &str, name: &str, line: u32, first: u32| {
        ctx.model_err(
            line,
            format!("{what} '{name}' is declared twice (first at line {first})"),
        )
    };
    for n in root.children().filter(|c| c.is_element()) {
        if n.has_tag_name("link") {
            let l = parse_link(ctx, n, b)?;
            if let Some(&k) = e.link_at.get(&l.name) {
                return Err(twice("link", &l.name, l.line, e.links[k].line));
            }
            e.link_at.insert(l.name.clone(), e.links.len());
            e.links.push(l);
        } else if n.has_tag_name("joint") {
            let j = parse_joint(ctx, n)?;
            if let Some(&k) = joint_at.get(&j.name) {
                return Err(twice("joint", &j.name, j.line, e.joints[k].line));
            }
            joint_at.insert(j.name.clone(), e.joints.len());
            e.joints.push(j);
        }
    }
    Ok(e)
}

/// Checks that the joints make a tree (every link named exists, one parent each, no cycle)
/// and returns its one root link; each problem is reported at the offending element. Linear in
/// the number of joints.
fn check_tree<'e>(ctx: &Ctx, root: Node, e: &'e Elements) -> Result<&'e ULink> {
    let mut parent_joint: HashMap<&str, usize> = HashMap::new();
    for (k, j) in e.joints.iter().enumerate() {
        for (role, l) in [("parent", &j.parent), ("child", &j.child)] {
            if !e.link_at.contains_key(l) {
                return Err(ctx.model_err(
                    j.line,
                    format!(
                        "joint '{}' names {role} link '{l}', which does not exist",
                        j.name
                    ),
                ));
            }
        }
        if let Some(&p) = parent_joint.get(j.child.as_str()) {
            let first = &e.joints[p];
            return Err(ctx.model_err(
                j.line,
                format!(
                    "link '{}' has two parents: '{}' (joint '{}', line {}) and '{}' (joint '{}')",
                    j.child, first.parent, first.name, first.line, j.parent, j.name
                ),
            ));
        }
        parent_joint.insert(&j.child, k);
    }
    let roots: Vec<&ULink> = e
        .links
        .iter()
        .filter(|l| !parent_joint.contains_key(l.name.as_str()))
        .collect();
    let root_link = match roots.as_slice() {
        [r] => *r,
        [_, second, ..] => {
            let names: Vec<&str> = roots.iter().map(|l| l.name.as_str()).collect();
            return Err(ctx.model_err(
                second.line,
                format!(
                    "the robot has several root links ({}), but every link except one must be the child of a joint",
                    names.join(", ")
                ),
            ));
        }
        [] if e.joints.is_empty() => {
            return Err(ctx.model_err(
                ctx.line(root),
                "the robot has no root link: every link is the child of a joint".into(),
            ))
        }
        [] => return Err(cycle_error(ctx, e, &parent_joint, 0)),
    };
    // With one parent per link, a link that the root does not reach lies on a cycle.
    let mut children: HashMap<&str, Vec<&str>> = HashMap::new();
    for j in &e.joints {
        children
            .entry(j.parent.as_str())
            .or_default()
            .push(&j.child);
    }
    let mut seen: std::collections::HashSet<&str> = std::collections::HashSet::new();
    let mut stack = vec![root_link.name.as_str()];
    while let Some(l) = stack.pop() {
        seen.insert(l);
        stack.extend(children.get(l).into_iter().flatten());
    }
    if seen.len() != e.links.len() {
        let k = e
            .joints
            .iter()
            .position(|j| !seen.contains(j.child.as_str()))
            .unwrap_or(0);
        return Err(cycle_error(ctx, e, &parent_joint, k));
    }
    Ok(root_link)
}

/// The cycle through joint `k`'s child, found by walking parents until a link repeats.
fn cycle_error(ctx: &Ctx, e: &Elements, parent_joint: &HashMap<&str, usize>, k: usize) -> Error {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    let mut path: Vec<usize> = Vec::new();
    let mut at = e.joints[k].child.as_str();
    while let Some(&p) = parent_joint.get(at) {
        if let Some(&start) = seen.get(at) {
            let mut names: Vec<&str> = path[start..]
                .iter()
                .map(|&j| e.joints[j].name.as_str())
                .collect();
            names.reverse();
            let last = path[path.len() - 1];
            return ctx.model_err(
                e.joints[last].line,
                format!("joints {} form a cycle", names.join(", ")),
            );
        }
        seen.insert(at, path.len());
        path.push(p);
        at = &e.joints[p].parent;
    }
    ctx.model_err(
        e.joints[k].line,
        format!("joint '{}' closes a cycle", e.joints[k].name),
    )
}

/// The builder's joint declaration of a URDF joint: axis in the child frame (URDF's axis is
/// given in the joint frame, which is the child frame at `q = 0`).
fn joint_spec(j: &UJoint) -> JointSpec {
    let a = j.axis;
    let (spec, s) = match j.kind.as_str() {
        "fixed" => return JointSpec::fixed(&j.name),
        "prismatic" => (
            JointSpec::prismatic(&j.name),
            Vector6::new(0.0, 0.0, 0.0, a.x, a.y, a.z),
        ),
        "continuous" => (
            JointSpec::continuous(&j.name),
            Vector6::new(a.x, a.y, a.z, 0.0, 0.0, 0.0),
        ),
        _ => (
            JointSpec::revolute(&j.name),
            Vector6::new(a.x, a.y, a.z, 0.0, 0.0, 0.0),
        ),
    };
    let spec = spec
        .screw_in_child(s)
        .limits(j.lower, j.upper)
        .velocity_limit(j.velocity)
        .effort_limit(j.effort)
        .damping(j.damping)
        .friction(j.friction);
    match &j.mimic {
        Some(m) => spec.mimic(m.clone()),
        None => spec,
    }
}
