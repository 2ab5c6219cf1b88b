//! The page: a template (`assets/view.html`), the renderer (`assets/view.js`) and the data,
//! embedded as JSON whose large arrays are base64 little-endian `float32`/`uint32`/`uint8`.

use crate::run::{PAST_EFFORT, PAST_LIMIT};
use crate::scene::{joint_anchor, joint_direction, Group, Scene};
use crate::{Page, ViewOptions};
use base64::Engine;
use nalgebra::Matrix4;
use screwdyn::io::visual::visuals_of;
use screwdyn::model::FrameKind;
use screwdyn::spatial::Se3;
use screwdyn::{kinematics, Error, Model, Result, Workspace};
use serde_json::{json, Value};
use std::path::Path;

const TEMPLATE: &str = include_str!("../assets/view.html");
const SCRIPT: &str = include_str!("../assets/view.js");

fn b64(bytes: &[u8]) -> String {
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

fn f32s(x: impl IntoIterator<Item = f64>) -> String {
    let bytes: Vec<u8> = x
        .into_iter()
        .flat_map(|v| (v as f32).to_le_bytes())
        .collect();
    b64(&bytes)
}

/// The 3×4 row-major top of a 4×4 transform.
fn rows34(m: &Matrix4<f64>) -> Vec<f64> {
    (0..3)
        .flat_map(|r| (0..4).map(move |c| m[(r, c)]))
        .collect()
}

fn pose34(h: &Se3) -> Vec<f64> {
    rows34(&h.to_matrix())
}

fn finite(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The frames whose path a run draws: for each leaf body, its last fixed or extra frame (a
/// tool point), else its own frame.
fn end_effectors(model: &Model) -> Result<Vec<usize>> {
    let mut out = Vec::new();
    for i in 0..model.nbodies() {
        if !model.children(i)?.is_empty() {
            continue;
        }
        let tool = model
            .frames()
            .iter()
            .enumerate()
            .filter(|(_, f)| f.body == Some(i) && f.kind != FrameKind::Body)
            .map(|(k, _)| k)
            .next_back();
        out.push(match tool {
            Some(k) => k,
            None => model.body_frame(i)?,
        });
    }
    Ok(out)
}

/// Writes the page of `model` with `options` (see [`ViewOptions`]): the scene (visuals
/// or skeleton), the overlays (frames `{i}` of every link, joint screw axes, centres of mass,
/// the end-effector path of the run) and the run's animation and plots.
///
/// # Errors
/// [`Error::DimensionMismatch`]/[`Error::NonFinite`] for a bad `options.q`; [`Error::Io`] or
/// [`Error::Parse`] when the URDF or MJCF file cannot be read again for its visuals;
/// [`Error::InvalidArgument`] when the run's samples do not have one position per joint or
/// `max_triangles` is 0. Missing or unreadable meshes are not errors: they are in
/// [`Page::warnings`] and drawn as stand-in boxes.
pub fn render_html(model: &Model, options: &ViewOptions) -> Result<Page> {
    if options.max_triangles == 0 {
        return Err(Error::InvalidArgument(
            "the triangle cap must be at least 1".into(),
        ));
    }
    let q0 = options.q.clone().unwrap_or_else(|| vec![0.0; model.nq()]);
    model.check_vector(&q0, "q")?;
    let (visuals, dir) = match &options.description {
        Some(path) => {
            let file = path.display().to_string();
            let text = match &options.description_text {
                Some(text) => text.clone(),
                None => std::fs::read_to_string(path).map_err(|e| Error::unreadable(path, &e))?,
            };
            let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
            let load = screwdyn::io::LoadOptions::default();
            (visuals_of(&text, &file, &load)?, dir)
        }
        None => (Vec::new(), Default::default()),
    };
    let scene = Scene::build(model, &visuals, &dir, options)?;
    let mut ws = Workspace::new(model);
    let pose0 = body_poses(model, &mut ws, &q0)?;
    let mut data = scene_json(model, &scene);
    let names = model.joint_names();
    let (run_json, samples) = match &options.run {
        None => (Value::Null, 0),
        Some(run) => (run_json(model, run, &mut ws)?, run.t.len()),
    };
    let title = options
        .title
        .clone()
        .unwrap_or_else(|| format!("{} — screwdyn view", model.name()));
    let extra = json!({
        "title": title,
        "joints": names,
        "bodies": model.bodies().iter().map(|b| b.name.as_str()).collect::<Vec<_>>(),
        "q0": q0,
        "pose0": f32s(pose0),
        "run": run_json,
        "warnings": scene.warnings.iter().map(|w| w.message.clone()).collect::<Vec<_>>(),
    });
    if let (Some(d), Value::Object(e)) = (data.as_object_mut(), extra) {
        d.extend(e);
    }
    // `</` inside a <script> would end it: JSON allows the escape `<\/`.
    let data = data.to_string().replace("</", "<\\/");
    let joints_html: String = names
        .iter()
        .enumerate()
        .map(|(i, n)| format!("<li data-joint=\"{i}\">{}</li>", escape(n)))
        .collect();
    let duration = options.run.as_ref().map_or(String::new(), |r| {
        format!("{}", (r.duration() * 1e6).round() / 1e6)
    });
    let html = TEMPLATE
        .replace("{{TITLE}}", &escape(&title))
        .replace("{{JOINTS}}", &joints_html)
        .replace("{{DURATION}}", &duration)
        .replace("{{SCRIPT}}", &SCRIPT.replace("</", "<\\/"))
        .replace("{{DATA}}", &data);
    Ok(Page {
        html,
        triangles: scene.triangles(),
        warnings: scene.warnings,
        samples,
    })
}

/// The scene's data: meshes, parts, frames, screw axes, limits and the "up" direction.
fn scene_json(model: &Model, scene: &Scene) -> Value {
    let meshes: Vec<Value> = scene
        .meshes
        .iter()
        .map(|m| {
            let idx: Vec<u8> = m.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
            json!({
                "p": f32s(m.positions.iter().flatten().map(|x| *x as f64)),
                "i": b64(&idx),
            })
        })
        .collect();
    let parts: Vec<Value> = scene
        .parts
        .iter()
        .map(|p| {
            json!({
                "b": p.body.map_or(-1, |b| b as i64),
                "m": p.mesh,
                "t": rows34(&p.transform),
                "c": p.color,
                "g": match p.group { Group::Robot => "robot", Group::Com => "com" },
            })
        })
        .collect();
    let frames: Vec<Value> = model
        .frames()
        .iter()
        .map(|f| {
            json!({
                "name": f.name,
                "b": f.body.map_or(-1, |b| b as i64),
                "t": pose34(&f.placement),
            })
        })
        .collect();
    let axes: Vec<Value> = (0..model.nq())
        .map(|i| {
            json!({
                "b": i,
                "p": joint_anchor(model, i).as_slice(),
                "d": joint_direction(model, i).as_slice(),
                "kind": model.joints()[i].kind.name(),
            })
        })
        .collect();
    let limits: Vec<Value> = model
        .joints()
        .iter()
        .map(|j| {
            json!({
                "lower": finite(j.limits.lower),
                "upper": finite(j.limits.upper),
                "effort": finite(j.limits.effort),
            })
        })
        .collect();
    let g = model.gravity();
    let up = if g.norm() > 0.0 {
        (-g / g.norm()).as_slice().to_vec()
    } else {
        vec![0.0, 0.0, 1.0]
    };
    json!({
        "up": up,
        "size": scene.size,
        "skeleton": scene.skeleton,
        "meshes": meshes,
        "parts": parts,
        "frames": frames,
        "axes": axes,
        "limits": limits,
    })
}

/// The body poses `H_i^0` at `q`, as 3×4 row-major blocks.
fn body_poses(model: &Model, ws: &mut Workspace, q: &[f64]) -> Result<Vec<f64>> {
    kinematics::forward_kinematics(model, ws, q)?;
    Ok(ws.pose_in_world[..model.nbodies()]
        .iter()
        .flat_map(pose34)
        .collect())
}

/// The run's data: per-sample body poses and end-effector paths (computed here), series and
/// violation flags.
fn run_json(model: &Model, run: &crate::Run, ws: &mut Workspace) -> Result<Value> {
    let names = model.joint_names();
    let nb = model.nbodies();
    let n = run.t.len();
    if run.q.iter().any(|q| q.len() != model.nq()) {
        return Err(Error::InvalidArgument(format!(
            "the run's samples do not have {} positions (the model's joints: {})",
            model.nq(),
            names.join(", ")
        )));
    }
    let ee = end_effectors(model)?;
    let mut all_poses = Vec::with_capacity(n * nb * 12);
    let mut paths = vec![Vec::with_capacity(3 * n); ee.len()];
    for q in &run.q {
        all_poses.extend(body_poses(model, ws, q)?);
        for (k, f) in ee.iter().enumerate() {
            paths[k].extend(kinematics::frame_pose(model, ws, *f)?.translation.iter());
        }
    }
    let flags: Vec<u8> = run.flags.iter().flatten().copied().collect();
    let violations: Vec<Value> = run
        .violations
        .iter()
        .map(|v| {
            json!({
                "joint": v.joint,
                "kind": if v.kind == PAST_LIMIT { "limit" } else if v.kind == PAST_EFFORT { "effort" } else { "?" },
                "count": v.count,
                "first_time": v.first_time,
                "worst": v.worst,
            })
        })
        .collect();
    Ok(json!({
        "n": n,
        "t": f32s(run.t.iter().map(|t| t - run.t[0])),
        "t0": run.t[0],
        "duration": run.duration(),
        "poses": f32s(all_poses),
        "q": f32s(run.q.iter().flatten().copied()),
        "tau": run.tau.as_ref().map(|tau| f32s(tau.iter().flatten().copied())),
        "energy": run.energy.iter().map(|(name, v)| json!({"name": name, "v": f32s(v.iter().copied())})).collect::<Vec<_>>(),
        "flags": b64(&flags),
        "paths": ee.iter().zip(&paths).map(|(f, p)| json!({"frame": model.frames()[*f].name, "p": f32s(p.iter().copied())})).collect::<Vec<_>>(),
        "violations": violations,
        "samples_read": run.samples_read,
    }))
}
