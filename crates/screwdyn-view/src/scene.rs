//! The drawable scene: triangle meshes attached to bodies, from the model's visuals or, for a
//! model without visuals, a skeleton built from the joints' screw axes and the bodies' inertias.

use crate::mesh::{self, Mesh};
use crate::visual::{self, Shape, Visual};
use crate::{ViewOptions, Warning, WarningKind};
use nalgebra::{Matrix4, Vector3};
use screwdyn::model::FrameKind;
use screwdyn::spatial::Se3;
use screwdyn::{kinematics, Model, Result, Workspace};
use std::collections::HashMap;
use std::path::Path;

/// What a part shows; the page can hide each group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// The robot's own geometry (visuals, or the skeleton's links and joint markers).
    Robot,
    /// A sphere at a body's centre of mass, its volume proportional to the mass.
    Com,
}

/// One mesh placed on a body.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// The body it moves with (`None`: the base).
    pub body: Option<usize>,
    /// Index into [`Scene::meshes`].
    pub mesh: usize,
    /// Mesh coordinates → body frame (may include the URDF `scale`).
    pub transform: Matrix4<f64>,
    /// RGBA colour.
    pub color: [f32; 4],
    /// What it shows.
    pub group: Group,
}

/// The scene of a model: shared meshes, the parts that place them, and what went wrong.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Meshes, each stored once however many parts use it.
    pub meshes: Vec<Mesh>,
    /// Placed meshes.
    pub parts: Vec<Part>,
    /// Whether the robot is drawn as a skeleton (the model has no visuals).
    pub skeleton: bool,
    /// A length scale of the robot (m): the largest distance of a frame from the base at
    /// home, at least 0.1.
    pub size: f64,
    /// Missing or unreadable meshes, decimation.
    pub warnings: Vec<Warning>,
}

const GREY: [f32; 4] = [0.72, 0.74, 0.78, 1.0];
const LINK: [f32; 4] = [0.55, 0.62, 0.75, 1.0];
const JOINT: [f32; 4] = [0.95, 0.6, 0.15, 1.0];
const COM: [f32; 4] = [0.2, 0.7, 0.3, 1.0];
const STAND_IN: [f32; 4] = [1.0, 0.3, 0.8, 0.6];

/// `r` of joint `i` in body `i`'s frame: the point of the screw axis `S = (ω, v)` nearest the
/// body origin, `r = ω × v / |ω|²` (Lynch & Park, *Modern Robotics*, `v = −ω × r + h ω`); the body origin for a
/// prismatic joint.
///
/// ```
/// let m = screwdyn::builtin::planar2();
/// // Joint 2 turns about z one link length behind frame 2.
/// assert_eq!(screwdyn_view::scene::joint_anchor(&m, 1).x, -1.0);
/// ```
pub fn joint_anchor(model: &Model, i: usize) -> Vector3<f64> {
    let s = &model.joints()[i].screw;
    let w = Vector3::new(s[0], s[1], s[2]);
    let v = Vector3::new(s[3], s[4], s[5]);
    let n2 = w.norm_squared();
    if n2 < 1e-24 {
        Vector3::zeros()
    } else {
        w.cross(&v) / n2
    }
}

/// The unit direction of joint `i`'s axis in body `i`'s frame (`ω`, or `v` for a prismatic
/// joint).
pub fn joint_direction(model: &Model, i: usize) -> Vector3<f64> {
    let s = &model.joints()[i].screw;
    let w = Vector3::new(s[0], s[1], s[2]);
    let d = if w.norm() > 1e-12 {
        w
    } else {
        Vector3::new(s[3], s[4], s[5])
    };
    d.normalize()
}

/// A skeleton segment `(body, a, b)`: end points `a`, `b` in the frame of `body` (`None`: the
/// base frame).
pub type Segment = (Option<usize>, Vector3<f64>, Vector3<f64>);

/// The skeleton's link segments `(body, a, b)`, end points in the body's frame (`None`: the
/// base frame): from each body's joint anchor (see [`joint_anchor`]) to its own origin, to
/// its children's joint anchors and to its fixed frames; from the base origin to the anchors
/// of the root joints. Zero-length segments are dropped.
///
/// ```
/// let m = screwdyn::builtin::planar2();
/// let s = screwdyn_view::scene::skeleton_segments(&m).unwrap();
/// assert_eq!(s.len(), 2); // joint 1 → link 1's end, joint 2 → link 2's end
/// ```
///
/// # Errors
/// None for a valid model (the body ids it asks the model about are its own).
pub fn skeleton_segments(model: &Model) -> Result<Vec<Segment>> {
    let mut out = Vec::new();
    let mut push = |b: Option<usize>, a: Vector3<f64>, c: Vector3<f64>| {
        if (a - c).norm() > 1e-9
            && !out.iter().any(|(ob, oa, oc): &Segment| {
                *ob == b
                    && (((oa - a).norm() < 1e-9 && (oc - c).norm() < 1e-9)
                        || ((oa - c).norm() < 1e-9 && (oc - a).norm() < 1e-9))
            })
        {
            out.push((b, a, c));
        }
    };
    // The start of the links of body b (None: base origin).
    let start = |b: Option<usize>| match b {
        Some(i) => joint_anchor(model, i),
        None => Vector3::zeros(),
    };
    for i in 0..model.nbodies() {
        let b = Some(i);
        let a = start(b);
        push(b, a, Vector3::zeros());
        for &c in model.children(i)? {
            let tip = model.joints()[c].home.act_point(&joint_anchor(model, c));
            push(b, a, tip);
        }
    }
    for (c, p) in model.parents().iter().enumerate() {
        if p.is_none() {
            let tip = model.joints()[c].home.act_point(&joint_anchor(model, c));
            push(None, Vector3::zeros(), tip);
        }
    }
    for f in model.frames() {
        if matches!(f.kind, FrameKind::FixedLink | FrameKind::Extra) {
            push(f.body, start(f.body), f.placement.translation);
        }
    }
    Ok(out)
}

/// The robot's length scale: the largest distance of a frame from the base at home.
fn robot_size(model: &Model) -> Result<f64> {
    let mut ws = Workspace::new(model);
    kinematics::forward_kinematics(model, &mut ws, &vec![0.0; model.nq()])?;
    let mut size: f64 = 0.1;
    for f in 0..model.frames().len() {
        size = size.max(kinematics::frame_pose(model, &ws, f)?.translation.norm());
    }
    for i in 0..model.nbodies() {
        let p = ws.pose_in_world[i].act_point(&joint_anchor(model, i));
        size = size.max(p.norm());
    }
    Ok(size)
}

fn se3_matrix(h: &Se3) -> Matrix4<f64> {
    h.to_matrix()
}

/// A transform taking `z` to the unit vector `d` and the origin to `a`.
fn along(a: &Vector3<f64>, d: &Vector3<f64>) -> Matrix4<f64> {
    let z = d.normalize();
    let helper = if z.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let x = helper.cross(&z).normalize();
    let y = z.cross(&x);
    let mut m = Matrix4::identity();
    for r in 0..3 {
        m[(r, 0)] = x[r];
        m[(r, 1)] = y[r];
        m[(r, 2)] = z[r];
        m[(r, 3)] = a[r];
    }
    m
}

impl Scene {
    /// Builds the scene of `model`: its visuals (URDF or MJCF, see [`Visual`]) when `visuals` is
    /// not empty (with `urdf_dir`, the description's folder, to resolve relative mesh paths), a
    /// skeleton otherwise; CoM spheres in both cases.
    /// Meshes that cannot be found or read become warnings and stand-in boxes; when the meshes
    /// hold more than `options.max_triangles` triangles they are decimated to fit (a warning).
    ///
    /// # Errors
    /// [`screwdyn::Error::UnknownName`] when a visual belongs to a link the model does not have.
    pub fn build(
        model: &Model,
        visuals: &[Visual],
        urdf_dir: &Path,
        options: &ViewOptions,
    ) -> Result<Scene> {
        let size = robot_size(model)?;
        let mut scene = Scene {
            size,
            skeleton: visuals.is_empty(),
            ..Default::default()
        };
        if visuals.is_empty() {
            scene.add_skeleton(model)?;
        } else {
            scene.add_visuals(model, visuals, urdf_dir, options)?;
        }
        scene.add_coms(model);
        scene.cap(options.max_triangles);
        Ok(scene)
    }

    fn add(&mut self, mesh: Mesh) -> usize {
        self.meshes.push(mesh);
        self.meshes.len() - 1
    }

    fn add_skeleton(&mut self, model: &Model) -> Result<()> {
        let r = (0.03 * self.size) as f32;
        for (body, a, b) in skeleton_segments(model)? {
            let len = (b - a).norm() as f32;
            let m = self.add(mesh::capsule(r, len, 16));
            self.parts.push(Part {
                body,
                mesh: m,
                transform: along(&a, &(b - a)),
                color: LINK,
                group: Group::Robot,
            });
        }
        // Joint markers: a short cylinder along each joint axis, centred on its anchor.
        let marker = self.add(mesh::cylinder(1.6 * r, 5.0 * r, 20));
        for i in 0..model.nq() {
            self.parts.push(Part {
                body: Some(i),
                mesh: marker,
                transform: along(&joint_anchor(model, i), &joint_direction(model, i)),
                color: JOINT,
                group: Group::Robot,
            });
        }
        Ok(())
    }

    fn add_coms(&mut self, model: &Model) {
        let mmax = model
            .bodies()
            .iter()
            .map(|b| b.inertia.mass)
            .fold(0.0, f64::max);
        if mmax <= 0.0 {
            return;
        }
        let unit = self.add(mesh::sphere(1.0, 20, 12));
        for (i, b) in model.bodies().iter().enumerate() {
            if b.inertia.mass <= 0.0 {
                continue;
            }
            // Volume proportional to mass: radius ∝ ∛m.
            let r = 0.07 * self.size * (b.inertia.mass / mmax).cbrt();
            let mut t = Matrix4::new_scaling(r);
            t.fixed_view_mut::<3, 1>(0, 3).copy_from(&b.inertia.com);
            self.parts.push(Part {
                body: Some(i),
                mesh: unit,
                transform: t,
                color: COM,
                group: Group::Com,
            });
        }
    }

    fn add_visuals(
        &mut self,
        model: &Model,
        visuals: &[Visual],
        urdf_dir: &Path,
        options: &ViewOptions,
    ) -> Result<()> {
        // Meshes read so far, by file name: (first mesh index, count) or the failure.
        let mut cache: HashMap<String, Option<(usize, usize)>> = HashMap::new();
        for v in visuals {
            let frame = &model.frames()[model.frame_id(&v.link)?];
            let placed = se3_matrix(&frame.placement.compose(&v.origin));
            let color = v.color.unwrap_or(GREY);
            let (meshes, transform, file_colors) = match &v.shape {
                Shape::Box { size } => {
                    let m = self.add(mesh::cuboid(size.map(|x| x as f32)));
                    ((m, 1), placed, false)
                }
                Shape::Cylinder { radius, length } => {
                    let m = self.add(mesh::cylinder(*radius as f32, *length as f32, 32));
                    ((m, 1), placed, false)
                }
                Shape::Sphere { radius } => {
                    let m = self.add(mesh::sphere(*radius as f32, 24, 12));
                    ((m, 1), placed, false)
                }
                // The capsule mesh runs from z = 0 to z = length: shift it back by half.
                Shape::Capsule { radius, length } => {
                    let m = self.add(mesh::capsule(*radius as f32, *length as f32, 24));
                    let shift = Matrix4::new_translation(&Vector3::new(0.0, 0.0, -length / 2.0));
                    ((m, 1), placed * shift, false)
                }
                // A unit sphere scaled by the semi-axes.
                Shape::Ellipsoid { radii } => {
                    let m = self.add(mesh::sphere(1.0, 24, 12));
                    let scale = Matrix4::new_nonuniform_scaling(&Vector3::from(*radii));
                    ((m, 1), placed * scale, false)
                }
                Shape::Mesh {
                    file: filename,
                    scale,
                } => {
                    let scaled = placed * visual::scaling(*scale).to_homogeneous();
                    let entry = match cache.get(filename) {
                        Some(e) => *e,
                        None => {
                            let e = self.load_mesh(filename, &v.link, urdf_dir, options);
                            cache.insert(filename.clone(), e);
                            e
                        }
                    };
                    match entry {
                        Some(e) => (e, scaled, true),
                        None => {
                            // Stand-in: a translucent box of a tenth of the robot's size.
                            let s = (0.1 * self.size) as f32;
                            let m = self.add(mesh::cuboid([s, s, s]));
                            self.parts.push(Part {
                                body: frame.body,
                                mesh: m,
                                transform: placed,
                                color: STAND_IN,
                                group: Group::Robot,
                            });
                            continue;
                        }
                    }
                }
            };
            for k in meshes.0..meshes.0 + meshes.1 {
                let c = match (v.color, file_colors, self.meshes[k].color) {
                    (None, true, Some(c)) => c,
                    _ => color,
                };
                self.parts.push(Part {
                    body: frame.body,
                    mesh: k,
                    transform,
                    color: c,
                    group: Group::Robot,
                });
            }
        }
        Ok(())
    }

    /// Resolves and reads a mesh file; a failure is a warning and `None`.
    fn load_mesh(
        &mut self,
        filename: &str,
        link: &str,
        urdf_dir: &Path,
        options: &ViewOptions,
    ) -> Option<(usize, usize)> {
        let read = visual::resolve_mesh(filename, urdf_dir, &options.package_paths)
            .map_err(|e| (WarningKind::MeshMissing, e))
            .and_then(|p| visual::read_mesh_file(&p).map_err(|e| (WarningKind::MeshUnreadable, e)));
        match read {
            Ok(meshes) if meshes.iter().any(|m| m.triangles() > 0) => {
                let first = self.meshes.len();
                let n = meshes.len();
                self.meshes.extend(meshes);
                Some((first, n))
            }
            Ok(_) => {
                self.warnings.push(Warning {
                    kind: WarningKind::MeshUnreadable,
                    message: format!("link '{link}': mesh '{filename}' has no triangles; a stand-in box is drawn"),
                });
                None
            }
            Err((kind, e)) => {
                self.warnings.push(Warning {
                    kind,
                    message: format!("link '{link}': {e}; a stand-in box is drawn"),
                });
                None
            }
        }
    }

    /// Total triangles of the meshes in use.
    pub fn triangles(&self) -> usize {
        self.meshes.iter().map(Mesh::triangles).sum()
    }

    /// Decimates every mesh in proportion so the total fits `max_triangles`.
    fn cap(&mut self, max_triangles: usize) {
        let total = self.triangles();
        if total <= max_triangles {
            return;
        }
        for m in &mut self.meshes {
            let share =
                (m.triangles() as f64 * max_triangles as f64 / total as f64).floor() as usize;
            m.decimate(share.max(12).min(m.triangles()));
        }
        self.warnings.push(Warning {
            kind: WarningKind::Decimated,
            message: format!(
                "the meshes have {total} triangles, more than the cap of {max_triangles}; they were simplified to {} (raise the cap with --max-triangles)",
                self.triangles()
            ),
        });
    }
}
