//! `<worldbody>`: every body becomes a link of the tree. A body's `pos`/orientation is its home
//! pose in its parent; each `<joint>` moves it about (hinge) or along (slide) `axis` through `pos`,
//! both in the body frame, so a body with joints `1…n` is at
//! `H = H_body e^{[S_1](q_1 − ref_1)} ⋯ e^{[S_n](q_n − ref_n)}` with `S_k = (a_k, pos_k × a_k)`
//! (hinge) or `(0, a_k)` (slide): a chain of `n` links, the first `n − 1` massless and named
//! `body/joint`, the last one the body. `ref` is folded into the home pose,
//! `H_k(0) = H_k e^{−[S_k] ref_k}`, so that `q` is MuJoCo's `qpos`. A body without joints is
//! welded to its parent. `<frame>` elements place what they hold (bodies, geoms, sites,
//! inertials and joints: a joint's `axis` and `pos` are written in its frame).

use super::compiler::{Compiler, FromGeom};
use super::defaults::{ClassId, Defaults, Styled};
use super::geoms::geom_inertia;
use super::mesh::MeshTable;
use super::orientation::{pose, rotation};
use super::tree::{Element, Tree};
use super::values::Values;
use crate::error::Result;
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::{Matrix3, SymmetricEigen, Vector3, Vector6};
use std::f64::consts::TAU;

/// A hinge or slide joint as read.
pub(crate) struct MJoint {
    pub name: String,
    pub slide: bool,
    /// `S_k` in the body frame.
    pub screw: Vector6<f64>,
    pub limits: Option<(f64, f64)>,
    pub reference: f64,
    pub damping: f64,
    pub friction: f64,
    pub armature: f64,
    /// The spring: stiffness `k` and rest position `q_spring` (`springref`, in radians or
    /// metres).
    pub stiffness: f64,
    pub springref: f64,
    pub effort: f64,
}

/// One link of the tree: a body, or a massless link between two joints of one body.
pub(crate) struct Link {
    pub name: String,
    pub parent: String,
    /// Index into [`Walk::joints`]; `None` for a welded body.
    pub joint: Option<usize>,
    pub home: Se3,
    pub inertia: SpatialInertia,
    pub at: String,
}

/// What the walk over `<worldbody>` collects.
pub(crate) struct Walk<'t> {
    pub tree: &'t Tree,
    pub defaults: &'t Defaults<'t>,
    pub compiler: &'t Compiler,
    pub meshes: &'t MeshTable<'t>,
    pub links: Vec<Link>,
    /// In MuJoCo's order (bodies depth first, joints of a body in file order).
    pub joints: Vec<MJoint>,
    /// Sites: (name, link, placement in the link).
    pub sites: Vec<(String, String, Se3)>,
    /// Geoms: (link, element, placement of what holds it in the link, class).
    pub geoms: Vec<Held<'t>>,
    /// The link of each geom of [`Walk::geoms`].
    pub geom_links: Vec<String>,
    /// Warnings: (`file:line`, message).
    pub warnings: Vec<(String, String)>,
    unnamed: usize,
}

/// What a body holds directly or through `<frame>`s: the element, its placement in the body
/// and its class.
pub(crate) type Held<'t> = (&'t Element, Se3, ClassId);

impl<'t> Walk<'t> {
    pub fn new(
        tree: &'t Tree,
        defaults: &'t Defaults<'t>,
        compiler: &'t Compiler,
        meshes: &'t MeshTable<'t>,
    ) -> Self {
        Walk {
            tree,
            defaults,
            compiler,
            meshes,
            links: Vec::new(),
            joints: Vec::new(),
            sites: Vec::new(),
            geoms: Vec::new(),
            geom_links: Vec::new(),
            warnings: Vec::new(),
            unnamed: 0,
        }
    }

    fn values(&self, e: &'t Element, class: ClassId) -> Values<'t> {
        Values {
            tree: self.tree,
            styled: Styled {
                element: e,
                class,
                defaults: self.defaults,
            },
        }
    }

    /// Every `<worldbody>`: its bodies hang from `base`; its sites are frames of `base`.
    pub fn world(&mut self, base: &str) -> Result<()> {
        for w in self.tree.root.children_named("worldbody") {
            w.take();
            let held = self.held(w, Se3::identity(), self.defaults.main())?;
            for (e, at, class) in held {
                match e.tag.as_str() {
                    "body" => self.body(e, base, at, class)?,
                    "site" => self.site(e, base, at, class)?,
                    "geom" => {
                        self.geoms.push((e, at, class));
                        self.geom_links.push(base.to_string());
                    }
                    "joint" | "freejoint" => {
                        return Err(self.tree.model_error(
                            e,
                            "a joint in <worldbody> (or in a <frame> of it) moves nothing, as in MuJoCo; put it in a <body>",
                        ))
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// The bodies, joints, geoms, sites and inertials of `e`, through nested `<frame>`s.
    fn held(&self, e: &'t Element, offset: Se3, class: ClassId) -> Result<Vec<Held<'t>>> {
        let mut out = Vec::new();
        for c in &e.children {
            match c.tag.as_str() {
                "frame" => {
                    c.take();
                    let v = self.values(c, class);
                    let inner = match c.attr("childclass") {
                        Some(name) => self.defaults.class(self.tree, c, name)?,
                        None => class,
                    };
                    let at = offset.compose(&pose(&v, self.compiler)?);
                    out.extend(self.held(c, at, inner)?);
                }
                "body" | "joint" | "freejoint" | "geom" | "site" | "inertial" => {
                    out.push((c, offset, class))
                }
                _ => {}
            }
        }
        Ok(out)
    }

    fn body(
        &mut self,
        e: &'t Element,
        parent: &str,
        offset: Se3,
        inherited: ClassId,
    ) -> Result<()> {
        e.take();
        let class = match e.attr("childclass") {
            Some(name) => self.defaults.class(self.tree, e, name)?,
            None => inherited,
        };
        let name = match e.attr("name") {
            Some(n) => n.to_string(),
            None => {
                self.unnamed += 1;
                format!("body{}", self.unnamed)
            }
        };
        // The body's own placement never reads defaults.
        let own = self.values(e, self.defaults.main());
        let placement = offset.compose(&pose(&own, self.compiler)?);
        let held = self.held(e, Se3::identity(), class)?;
        let inertia = self.body_inertia(&name, &held)?;
        let mut joint_elements = Vec::new();
        for (c, at, cls) in &held {
            match c.tag.as_str() {
                "freejoint" => {
                    return Err(self.tree.model_error(
                        c,
                        format!("body '{name}' has a <freejoint>; floating bases are not supported yet (fixed-base trees of hinge and slide joints only)"),
                    ))
                }
                "joint" => joint_elements.push((*c, *at, *cls)),
                _ => {}
            }
        }
        // The chain of links: intermediate ones massless, the last one the body.
        let mut link_parent = parent.to_string();
        let mut home = placement;
        let n = joint_elements.len();
        for (k, (c, at, cls)) in joint_elements.into_iter().enumerate() {
            let j = self.joint(c, &at, cls, &name)?;
            let link = if k + 1 == n {
                name.clone()
            } else {
                format!("{name}/{}", j.name)
            };
            // H_k(0) = H_k e^{−[S_k] ref_k}
            let h = home.compose(&Se3::exp_screw(&j.screw, -j.reference));
            self.links.push(Link {
                name: link.clone(),
                parent: link_parent,
                joint: Some(self.joints.len()),
                home: h,
                inertia: if k + 1 == n {
                    inertia
                } else {
                    SpatialInertia::zero()
                },
                at: self.tree.at(e),
            });
            self.joints.push(j);
            link_parent = link;
            home = Se3::identity();
        }
        if n == 0 {
            self.links.push(Link {
                name: name.clone(),
                parent: parent.to_string(),
                joint: None,
                home: placement,
                inertia,
                at: self.tree.at(e),
            });
        }
        for (c, at, cls) in held {
            match c.tag.as_str() {
                "body" => self.body(c, &name, at, cls)?,
                "site" => self.site(c, &name, at, cls)?,
                "geom" => {
                    self.geoms.push((c, at, cls));
                    self.geom_links.push(name.clone());
                }
                _ => {}
            }
        }
        Ok(())
    }

    fn site(&mut self, e: &'t Element, link: &str, offset: Se3, inherited: ClassId) -> Result<()> {
        let class = self.defaults.class_of(self.tree, e, inherited)?;
        let v = self.values(e, class);
        let Some(name) = e.attr("name") else {
            // An unnamed site cannot be asked for; nothing to keep.
            return Ok(());
        };
        e.take();
        let placement = offset.compose(&pose(&v, self.compiler)?);
        self.sites
            .push((name.to_string(), link.to_string(), placement));
        Ok(())
    }

    /// A `<joint>` of `body`, held through `<frame>`s placed at `frame` in the body (identity
    /// for a joint directly in the body).
    fn joint(
        &mut self,
        e: &'t Element,
        frame: &Se3,
        inherited: ClassId,
        body: &str,
    ) -> Result<MJoint> {
        e.take();
        let class = self.defaults.class_of(self.tree, e, inherited)?;
        let v = self.values(e, class);
        let name = match e.attr("name") {
            Some(n) => n.to_string(),
            None => format!("{body}_joint{}", self.joints.len()),
        };
        let kind = v
            .keyword("type", &["hinge", "slide", "ball", "free"])?
            .unwrap_or("hinge");
        if matches!(kind, "ball" | "free") {
            return Err(self.tree.model_error(
                e,
                format!("joint '{name}' of body '{body}' is a {kind} joint, which screwdyn does not support yet (hinge and slide joints only)"),
            ));
        }
        let slide = kind == "slide";
        let axis = v.vec3("axis")?.unwrap_or_else(Vector3::z);
        let scale = axis.amax();
        if scale <= 0.0 || (axis / scale).norm() < 1e-12 {
            return Err(self.tree.model_error(
                e,
                format!("joint '{name}' has a zero axis; the axis must be a nonzero direction"),
            ));
        }
        // The axis and its point, written in the frame, in the body: a = R a_f, p = R p_f + t.
        let a = frame.rotation * (axis / scale).normalize();
        let p = frame.rotation * v.vec3("pos")?.unwrap_or_else(Vector3::zeros) + frame.translation;
        // Hinge: S = (a, p × a); slide: S = (0, a).
        let screw = if slide {
            Vector6::new(0.0, 0.0, 0.0, a.x, a.y, a.z)
        } else {
            let m = p.cross(&a);
            Vector6::new(a.x, a.y, a.z, m.x, m.y, m.z)
        };
        let angle = |x: f64| if slide { x } else { self.compiler.angle(x) };
        let range = v.numbers("range", 2)?;
        let limited = match v.tristate("limited")? {
            Some("true") => true,
            Some("false") => false,
            _ if self.compiler.autolimits => range.is_some(),
            _ => {
                if range.is_some() {
                    self.warnings.push((
                        self.tree.at(e),
                        format!("joint '{name}' has a range but no limited=\"true\" and the compiler sets autolimits=\"false\": the range is ignored, as in MuJoCo"),
                    ));
                }
                false
            }
        };
        let mut limits = None;
        if limited {
            let r = range
                .ok_or_else(|| v.error(format!("joint '{name}' is limited but has no range")))?;
            if r[0] > r[1] {
                return Err(v.error(format!(
                    "joint '{name}' has range=\"{} {}\" with the lower end above the upper",
                    r[0], r[1]
                )));
            }
            if !slide {
                self.angle_unit_warning(e, &name, &r);
            }
            limits = Some((angle(r[0]), angle(r[1])));
        }
        let mut effort = f64::INFINITY;
        if let Some(r) = v.numbers("actuatorfrcrange", 2)? {
            let on = match v.tristate("actuatorfrclimited")? {
                Some("true") => true,
                Some("false") => false,
                _ => self.compiler.autolimits,
            };
            if on {
                effort = r[0].abs().max(r[1].abs());
            }
        }
        Ok(MJoint {
            name,
            slide,
            screw,
            limits,
            reference: angle(v.number("ref")?.unwrap_or(0.0)),
            damping: v.non_negative("damping")?.unwrap_or(0.0),
            friction: v.non_negative("frictionloss")?.unwrap_or(0.0),
            armature: v.non_negative("armature")?.unwrap_or(0.0),
            stiffness: v.non_negative("stiffness")?.unwrap_or(0.0),
            springref: angle(v.number("springref")?.unwrap_or(0.0)),
            effort,
        })
    }

    /// A hinge range that looks like degrees in a radian file, or like radians in a degree
    /// file, is a warning.
    fn angle_unit_warning(&mut self, e: &Element, name: &str, r: &[f64]) {
        let big = r[0].abs().max(r[1].abs());
        let message = if !self.compiler.degrees && big > TAU * 1.01 {
            format!(
                "joint '{name}' has range=\"{} {}\", which looks like degrees, but the file sets <compiler angle=\"radian\">",
                r[0], r[1]
            )
        } else if self.compiler.degrees
            && big > 0.0
            && big <= TAU
            && r.iter().any(|x| x.fract() != 0.0)
        {
            format!(
                "joint '{name}' has range=\"{} {}\", which looks like radians, but angles are in degrees (MuJoCo's default; set <compiler angle=\"radian\">)",
                r[0], r[1]
            )
        } else {
            return;
        };
        self.warnings.push((self.tree.at(e), message));
    }

    /// The body's spatial inertia in its frame: its `<inertial>`, or its geoms (compiler's
    /// `inertiafromgeom`), then the compiler's bounds.
    fn body_inertia(&mut self, name: &str, held: &[Held<'t>]) -> Result<SpatialInertia> {
        let inertial: Vec<&Held> = held.iter().filter(|h| h.0.tag == "inertial").collect();
        if inertial.len() > 1 {
            return Err(self.tree.error(
                inertial[1].0,
                format!("body '{name}' has two <inertial> elements"),
            ));
        }
        let from_geoms = match self.compiler.inertia_from_geom {
            FromGeom::Always => true,
            FromGeom::Never => false,
            FromGeom::Auto => inertial.is_empty(),
        };
        let mut i = if from_geoms {
            let mut sum = SpatialInertia::zero();
            for (g, at, class) in held.iter().filter(|h| h.0.tag == "geom") {
                let class = self.defaults.class_of(self.tree, g, *class)?;
                let v = self.values(g, class);
                if let Some(gi) = geom_inertia(&v, self.compiler, self.meshes)? {
                    g.take();
                    sum = sum.combined(&gi.transformed(at));
                }
            }
            sum
        } else if let Some((el, at, _)) = inertial.first() {
            self.inertial(el, name)?.transformed(at)
        } else {
            SpatialInertia::zero()
        };
        if self.compiler.bound_mass > 0.0 || self.compiler.bound_inertia > 0.0 {
            i = bounded(&i, self.compiler.bound_mass, self.compiler.bound_inertia);
        }
        Ok(i)
    }

    /// `<inertial mass pos (orientation) diaginertia|fullinertia>`: `I_c = R diag(I) Rᵀ`.
    fn inertial(&self, e: &'t Element, body: &str) -> Result<SpatialInertia> {
        e.take();
        let v = self.values(e, self.defaults.main());
        let mass = v
            .number("mass")?
            .ok_or_else(|| v.error(format!("<inertial> of body '{body}' has no mass")))?;
        if mass <= 0.0 {
            return Err(self.tree.model_error(
                e,
                format!("<inertial> of body '{body}' has mass {mass}; it must be positive"),
            ));
        }
        let com = v.vec3("pos")?.unwrap_or_else(Vector3::zeros);
        let i = match (v.numbers("diaginertia", 3)?, v.numbers("fullinertia", 6)?) {
            (Some(d), None) => {
                let r = rotation(&v, self.compiler)?;
                r * Matrix3::from_diagonal(&Vector3::new(d[0], d[1], d[2])) * r.transpose()
            }
            // MuJoCo's order: xx yy zz xy xz yz.
            (None, Some(f)) => {
                if ["quat", "axisangle", "euler", "xyaxes", "zaxis"]
                    .iter()
                    .any(|o| e.attrs.iter().any(|a| a.name == *o))
                {
                    return Err(v.error(format!("<inertial> of body '{body}' has fullinertia and an orientation; fullinertia is already in the body frame")));
                }
                Matrix3::new(f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2])
            }
            (Some(_), Some(_)) => {
                return Err(v.error(format!(
                    "<inertial> of body '{body}' has both diaginertia and fullinertia"
                )))
            }
            (None, None) => {
                return Err(v.error(format!(
                    "<inertial> of body '{body}' has neither diaginertia nor fullinertia"
                )))
            }
        };
        let eig = SymmetricEigen::new(i).eigenvalues;
        if eig.iter().any(|x| *x < -1e-12 * eig.amax().max(1e-300)) {
            return Err(self.tree.model_error(
                e,
                format!(
                    "<inertial> of body '{body}' is not positive definite (principal moments {:.6e}, {:.6e}, {:.6e})",
                    eig[0], eig[1], eig[2]
                ),
            ));
        }
        Ok(SpatialInertia::new(mass, com, i))
    }
}

/// `boundmass`/`boundinertia`: the mass at least `m_min`, each principal moment at least
/// `i_min` (in the principal frame, as MuJoCo applies them).
fn bounded(i: &SpatialInertia, m_min: f64, i_min: f64) -> SpatialInertia {
    let mass = i.mass.max(m_min);
    let eig = SymmetricEigen::new(i.inertia_com);
    let d = eig.eigenvalues.map(|x| x.max(i_min));
    let q = eig.eigenvectors;
    SpatialInertia::new(mass, i.com, q * Matrix3::from_diagonal(&d) * q.transpose())
}
