//! The coefficients of the equations of motion along a path on `Lanes`: the three passes of
//! the recursive Newton–Euler algorithm of `motion::PathDynamics`, line for line, for `L` path
//! points at once.

use super::buffers::Buffers;
use super::joint::{sin_cos_all, LaneJoint};
use super::spatial::{ad_transpose, add6, apply_body_inertia, gravity_twist, sub6, zero6};
use crate::model::Model;

/// With `q`, `q'`, `q''` of the points in `b.q`, `b.v`, `b.a`, writes `a = M(q) q'` to
/// `b.out[..n]`, `b = M(q) q'' + C(q, q') q'` to `b.out[n..2n]` and `c = g(q)` to
/// `b.out[2n..3n]` (Lynch & Park, *Modern Robotics*): the poses in the parents once, then three
/// passes side by side, the velocity terms only in the one that has a velocity,
///
/// ```text
/// V_i   = Ad_{H_λ^i} V_λ + S_i q'_i                                       (b only)
/// V̇b_i = Ad_{H_λ^i} V̇b_λ − ad_{S_i q'_i}(Ad_{H_λ^i} V_λ) + S_i q''_i,   W_b = 𝔍_i V̇b_i − ad_{V_i}ᵀ 𝔍_i V_i
/// V̇a_i = Ad_{H_λ^i} V̇a_λ + S_i q'_i,                                     W_a = 𝔍_i V̇a_i
/// V̇c_i = Ad_{H_λ^i} V̇c_λ  (V̇c_base = (0, −g)),                           W_c = 𝔍_i V̇c_i
/// W_λ += Ad_{H_λ^i}ᵀ W_i,   τ_i = S_iᵀ W_i + I_a,i q̈_i   (q̈ = q' for a, q'' for b, 0 for c)
/// ```
#[inline(always)]
pub(super) fn path_coefficients<const L: usize>(
    model: &Model,
    joints: &[LaneJoint],
    b: &mut Buffers<L>,
) {
    let n = model.nbodies();
    let (parents, bodies, joints) = (&model.parents()[..n], &model.bodies()[..n], &joints[..n]);
    let (q, dq, ddq) = (&b.q[..n], &b.v[..n], &b.a[..n]);
    let sc = sin_cos_all(joints, q, &mut b.sin_cos);
    let (pip, twist, accel_b, wrench_b) = (
        &mut b.pose_in_parent[..n],
        &mut b.twist[..n],
        &mut b.accel[..n],
        &mut b.wrench[..n],
    );
    let (accel_a, accel_c, wrench_a, wrench_c) = (
        &mut b.accel_a[..n],
        &mut b.accel_c[..n],
        &mut b.wrench_a[..n],
        &mut b.wrench_c[..n],
    );
    let base = gravity_twist(model);
    for i in 0..n {
        let j = &joints[i];
        let h = j.pose_in_parent(q[i], sc[i]);
        // Ad_{H_λ^i} of the parent's twist and the three accelerations.
        let (mut vi, mut vd_b, mut vd_a, vd_c) = match parents[i] {
            Some(p) => (
                h.inv_act_twist(&twist[p]),
                h.inv_act_twist(&accel_b[p]),
                h.inv_act_twist(&accel_a[p]),
                h.inv_act_twist(&accel_c[p]),
            ),
            None => (zero6(), zero6(), zero6(), h.inv_act_twist(&base)),
        };
        // ad_{S q'}(Ad V_λ) is taken before S q' is added.
        vd_b = sub6(&vd_b, &j.ad_scaled(dq[i], &vi));
        j.add_scaled(&mut vi, dq[i]);
        j.add_scaled(&mut vd_b, ddq[i]);
        j.add_scaled(&mut vd_a, dq[i]);
        // W = 𝔍 V̇ (− ad_Vᵀ 𝔍 V for b).
        let inertia = &bodies[i].inertia;
        let momentum = apply_body_inertia(inertia, &vi);
        wrench_b[i] = sub6(
            &apply_body_inertia(inertia, &vd_b),
            &ad_transpose(&vi, &momentum),
        );
        wrench_a[i] = apply_body_inertia(inertia, &vd_a);
        wrench_c[i] = apply_body_inertia(inertia, &vd_c);
        pip[i] = h;
        twist[i] = vi;
        accel_b[i] = vd_b;
        accel_a[i] = vd_a;
        accel_c[i] = vd_c;
    }
    let out = &mut b.out[..3 * n];
    let model_joints = &model.joints()[..n];
    for i in (0..n).rev() {
        // τ_i = S_iᵀ W_i + I_a,i q̈_i
        let (j, armature) = (&joints[i], model_joints[i].armature);
        out[i] = dq[i].mul_add(armature, j.dot(&wrench_a[i]));
        out[n + i] = ddq[i].mul_add(armature, j.dot(&wrench_b[i]));
        out[2 * n + i] = j.dot(&wrench_c[i]);
        // W_λ += Ad_{H_λ^i}ᵀ W_i
        if let Some(p) = parents[i] {
            let h = &pip[i];
            wrench_b[p] = add6(&wrench_b[p], &h.inv_act_transpose_wrench(&wrench_b[i]));
            wrench_a[p] = add6(&wrench_a[p], &h.inv_act_transpose_wrench(&wrench_a[i]));
            wrench_c[p] = add6(&wrench_c[p], &h.inv_act_transpose_wrench(&wrench_c[i]));
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::batch::{self, BatchWorkspace, Rows};
    use crate::motion::{CubicSpline, Path, PathDynamics};

    #[test]
    fn lanes_agree_with_path_dynamics_point_by_point() {
        // Every built-in model (screw joints in `branched`), as it is and with joint armature,
        // 19 points (two groups of eight lanes, three alone): [a, b, c] against
        // PathDynamics::at (its springs and friction taken out of c), in lanes and state by
        // state (three per-call RNEAs), to 10⁻¹² relative.
        let models = crate::io::builtin::NAMES.iter().flat_map(|name| {
            let m = crate::builtin::load(name).unwrap();
            let armature: Vec<f64> = (0..m.nq()).map(|j| 0.1 * (j + 1) as f64).collect();
            let with_armature = m.with_armature(&armature).unwrap();
            [m, with_armature]
        });
        for m in models {
            let (n, name) = (m.nq(), m.name().to_string());
            let points: Vec<Vec<f64>> = (0..3)
                .map(|k| {
                    (0..n)
                        .map(|j| (0.7 * k as f64 + 0.3 * j as f64).sin())
                        .collect()
                })
                .collect();
            let path = CubicSpline::chord_length(&points).unwrap();
            let (s0, s1) = path.s_range();
            let s: Vec<f64> = (0..19).map(|i| s0 + (s1 - s0) * i as f64 / 18.0).collect();
            let (mut q, mut dq, mut ddq) =
                (vec![0.0; 19 * n], vec![0.0; 19 * n], vec![0.0; 19 * n]);
            for (i, &si) in s.iter().enumerate() {
                let at = i * n..(i + 1) * n;
                path.eval(si, &mut q[at.clone()], &mut dq[at.clone()], &mut ddq[at]);
            }
            let mut pd = PathDynamics::new(&m, n).unwrap();
            for mut ws in [BatchWorkspace::new(&m), BatchWorkspace::state_by_state(&m)] {
                let mut abc = vec![0.0; 19 * 3 * n];
                let (q, dq, ddq) = (Rows::Stacked(&q), Rows::Stacked(&dq), Rows::Stacked(&ddq));
                batch::path_coefficients(&m, &mut ws, q, dq, ddq, &mut abc).unwrap();
                for (i, &si) in s.iter().enumerate() {
                    let p = pd.at(&m, &path, si).unwrap();
                    let row = &abc[3 * n * i..3 * n * (i + 1)];
                    for j in 0..n {
                        let effects = m.joints()[j].spring_and_friction_torque(p.q[j], p.dq[j]);
                        for (ours, theirs) in [
                            (row[j], p.a[j]),
                            (row[n + j], p.b[j]),
                            (row[2 * n + j], p.c[j] - effects),
                        ] {
                            let scale = ours.abs().max(theirs.abs()).max(1.0);
                            assert!(
                                (ours - theirs).abs() <= 1e-12 * scale,
                                "{name}, point {i}, joint {j}: {ours} vs {theirs}"
                            );
                        }
                    }
                }
            }
        }
    }
}
