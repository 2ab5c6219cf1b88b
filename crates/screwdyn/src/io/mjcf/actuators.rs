//! What `<actuator>`, `<option>` and `<keyframe>` give the model: effort limits, gravity and
//! named configurations.

use super::bodies::MJoint;
use super::defaults::{default_key, Defaults, Styled};
use super::tree::Tree;
use super::values::Values;
use crate::error::Result;
use nalgebra::Vector3;
use std::collections::HashMap;

/// Effort limits from the actuators that drive a joint directly: an actuator's largest joint
/// torque is `|gear| · max|forcerange|` when its force is limited, else, for a `motor` (force =
/// control), `|gear| · max|ctrlrange|` when its control is limited; several actuators on one
/// joint add up, and the joint's own `actuatorfrcrange` caps the sum.
pub(crate) fn effort_limits(
    tree: &Tree,
    defaults: &Defaults,
    autolimits: bool,
    joints: &mut [MJoint],
) -> Result<()> {
    let at: HashMap<String, usize> = joints
        .iter()
        .enumerate()
        .map(|(k, j)| (j.name.clone(), k))
        .collect();
    let mut sum = vec![0.0_f64; joints.len()];
    let mut driven = vec![false; joints.len()];
    for block in tree.root.children_named("actuator") {
        block.take();
        for a in &block.children {
            if default_key(&a.tag) != "actuator" || a.tag == "plugin" {
                continue;
            }
            // Only joint transmissions set a joint's effort; others stay in the report.
            let Some(joint) = a.attr("joint") else {
                continue;
            };
            a.take();
            a.attr("name");
            let class = defaults.class_of(tree, a, defaults.main())?;
            let v = Values {
                tree,
                styled: Styled {
                    element: a,
                    class,
                    defaults,
                },
            };
            let &k = at.get(joint).ok_or_else(|| {
                tree.model_error(
                    a,
                    format!("<{}> drives joint '{joint}', which does not exist", a.tag),
                )
            })?;
            let gear = v.numbers_between("gear", 1, 6)?.map_or(1.0, |g| g[0].abs());
            let limited = |flag: &str, range: &Option<Vec<f64>>| -> Result<bool> {
                Ok(match v.tristate(flag)? {
                    Some("true") => true,
                    Some("false") => false,
                    _ => autolimits && range.is_some(),
                })
            };
            let force = v.numbers("forcerange", 2)?;
            let ctrl = v.numbers("ctrlrange", 2)?;
            let bound = |r: &[f64]| r[0].abs().max(r[1].abs());
            let effort = if limited("forcelimited", &force)? && force.is_some() {
                gear * bound(force.as_deref().unwrap_or(&[0.0, 0.0]))
            } else if a.tag == "motor" && limited("ctrllimited", &ctrl)? && ctrl.is_some() {
                gear * bound(ctrl.as_deref().unwrap_or(&[0.0, 0.0]))
            } else {
                f64::INFINITY
            };
            sum[k] += effort;
            driven[k] = true;
        }
    }
    for (k, j) in joints.iter_mut().enumerate() {
        if driven[k] {
            j.effort = j.effort.min(sum[k]);
        }
    }
    Ok(())
}

/// `<option gravity>` (MuJoCo's default `(0, 0, −9.81)`).
pub(crate) fn gravity(tree: &Tree, defaults: &Defaults) -> Result<Vector3<f64>> {
    let mut g = Vector3::new(0.0, 0.0, -9.81);
    for o in tree.root.children_named("option") {
        o.take();
        let v = Values {
            tree,
            styled: Styled {
                element: o,
                class: defaults.main(),
                defaults,
            },
        };
        if let Some(x) = v.vec3("gravity")? {
            g = x;
        }
    }
    Ok(g)
}

/// `<keyframe><key name qpos>`: `qpos` in MuJoCo's joint order (all `nq` values), mapped to
/// joint names; a key without `qpos` is the reference configuration (each joint's `ref`).
/// Unnamed keys are called by their index (`0`, `1`, …).
pub(crate) fn keyframes(
    tree: &Tree,
    defaults: &Defaults,
    joints: &[MJoint],
) -> Result<Vec<(String, HashMap<String, f64>)>> {
    let mut out = Vec::new();
    let mut index = 0;
    for block in tree.root.children_named("keyframe") {
        block.take();
        for key in block.children_named("key") {
            key.take();
            let v = Values {
                tree,
                styled: Styled {
                    element: key,
                    class: defaults.main(),
                    defaults,
                },
            };
            let name = key
                .attr("name")
                .map_or_else(|| index.to_string(), str::to_string);
            index += 1;
            let qpos = match key.attr("qpos") {
                None => joints.iter().map(|j| j.reference).collect(),
                Some(s) => {
                    let q = super::values::numbers(tree, key, "qpos", s, 0, usize::MAX)?;
                    if q.len() != joints.len() {
                        return Err(v.error(format!(
                            "<key name=\"{name}\"> has {} qpos values, but the model has {} joints",
                            q.len(),
                            joints.len()
                        )));
                    }
                    q
                }
            };
            let q = joints
                .iter()
                .zip(qpos)
                .map(|(j, x)| (j.name.clone(), x))
                .collect();
            out.push((name, q));
        }
    }
    Ok(out)
}
