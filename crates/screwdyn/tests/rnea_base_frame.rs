//! The recursive Newton–Euler algorithm in the base frame ([`rnea`], [`inverse_dynamics`],
//! [`gravity_torque`], [`nonlinear_effects`]) against two independent computations of the same
//! torques: the local-frame recursion of Lynch & Park's *Modern Robotics* (each quantity in its
//! body's own frame, carried by `Ad_{H_λ^i}`; [`rnea_trace`] runs it) and `M q̈ + C q̇ + g` with
//! `M` from CRBA and `C` from the Coriolis matrix; with external wrenches, against the stacked
//! closed form `τ = M q̈ + C q̇ + g − Jᵀ W_ext`. On random branched trees with revolute,
//! prismatic and helical joints, the built-in arms and a 200-joint chain, all with armatures.
mod common;

use common::{assert_close, random_chain, random_external, random_tree, random_vec};
use nalgebra::DVector;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::dynamics::{
    closed_form, coriolis_matrix, crba, gravity_torque, inverse_dynamics, nonlinear_effects, rnea,
    rnea_trace, MAX_CLOSED_FORM_JOINTS,
};
use screwdyn::{builtin, Model, Workspace};

const TOL: f64 = 1e-10;

fn with_armature(model: &Model, rng: &mut StdRng) -> Model {
    let a: Vec<f64> = (0..model.nq()).map(|_| rng.gen_range(0.0..0.5)).collect();
    model.with_armature(&a).unwrap()
}

fn models() -> Vec<(String, Model)> {
    let mut rng = StdRng::seed_from_u64(31);
    let mut out = Vec::new();
    for name in ["ur5", "panda", "branched"] {
        let m = builtin::load(name).unwrap();
        out.push((name.to_string(), with_armature(&m, &mut rng)));
    }
    for t in 0..8 {
        let n = rng.gen_range(1..14);
        let m = random_tree(&mut rng, n, t % 2 == 0);
        out.push((format!("tree {t} ({n})"), with_armature(&m, &mut rng)));
    }
    for n in [7, 200] {
        let m = random_chain(&mut rng, n);
        out.push((format!("chain ({n})"), with_armature(&m, &mut rng)));
    }
    out
}

#[test]
fn base_frame_rnea_equals_the_local_form_and_m_qdd_plus_c_qd_plus_g() {
    let mut rng = StdRng::seed_from_u64(310);
    for (name, model) in models() {
        let n = model.nq();
        let mut ws = Workspace::new(&model);
        let (q, v, a) = (
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 2.0),
        );
        let zero = vec![0.0; n];
        let tau = rnea(&model, &mut ws, &q, &v, &a).unwrap().clone();
        // The local-frame recursion.
        let local = rnea_trace(&model, &q, &v, &a, None).unwrap().tau;
        assert_close(
            tau.as_slice(),
            &local,
            TOL,
            &format!("{name}: τ vs local form"),
        );
        // M q̈ + C q̇ + g: M by CRBA (with the armatures), C by the Coriolis matrix, g by the
        // local-frame recursion at rest.
        let g = DVector::from_vec(rnea_trace(&model, &q, &zero, &zero, None).unwrap().tau);
        let mq = crba(&model, &mut ws, &q).unwrap() * DVector::from_column_slice(&a);
        let cv = coriolis_matrix(&model, &mut ws, &q, &v).unwrap() * DVector::from_column_slice(&v);
        let lagrangian = &mq + &cv + &g;
        assert_close(
            tau.as_slice(),
            lagrangian.as_slice(),
            TOL,
            &format!("{name}: τ vs M q̈ + C q̇ + g"),
        );
        // q̇ = q̈ = 0 and q̈ = 0.
        assert_close(
            gravity_torque(&model, &mut ws, &q).unwrap().as_slice(),
            g.as_slice(),
            TOL,
            &format!("{name}: g"),
        );
        assert_close(
            nonlinear_effects(&model, &mut ws, &q, &v)
                .unwrap()
                .as_slice(),
            (&cv + &g).as_slice(),
            TOL,
            &format!("{name}: C q̇ + g"),
        );
        // External wrenches: the local form, and the closed form where it is defined.
        let ext = random_external(&model, &mut rng);
        let tau_ext = inverse_dynamics(&model, &mut ws, &q, &v, &a, Some(&ext))
            .unwrap()
            .clone();
        let local_ext = rnea_trace(&model, &q, &v, &a, Some(&ext)).unwrap().tau;
        assert_close(
            tau_ext.as_slice(),
            &local_ext,
            TOL,
            &format!("{name}: τ with W_ext vs local form"),
        );
        if n <= MAX_CLOSED_FORM_JOINTS {
            let cf = closed_form(&model, &q, &v).unwrap();
            assert_close(
                tau_ext.as_slice(),
                cf.inverse_dynamics(&a, Some(&ext)).unwrap().as_slice(),
                TOL,
                &format!("{name}: τ with W_ext vs closed form"),
            );
        }
    }
}

/// What the base-frame passes leave in the workspace is the local form's twists, accelerations
/// and wrenches written in {0}: `V_i^0 = Ad_{H_i^0} V_i`, `V̇_i^0 = Ad_{H_i^0} V̇_i` (as
/// `ad_{V_i} V_i = 0`), `W_i^0 = Ad_{H_0^i}ᵀ W_i`.
#[test]
fn base_frame_quantities_are_the_body_frame_ones_moved_to_the_base() {
    let mut rng = StdRng::seed_from_u64(311);
    for (name, model) in models() {
        let n = model.nq();
        let mut ws = Workspace::new(&model);
        let (q, v, a) = (
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 2.0),
            random_vec(&mut rng, n, 2.0),
        );
        let ext = random_external(&model, &mut rng);
        inverse_dynamics(&model, &mut ws, &q, &v, &a, Some(&ext)).unwrap();
        let trace = rnea_trace(&model, &q, &v, &a, Some(&ext)).unwrap();
        for i in 0..n {
            let h = &ws.pose_in_world[i];
            let what = |x: &str| format!("{name}: {x}_{i}");
            assert_close(
                ws.twist_in_world[i].as_slice(),
                h.act_twist(&trace.forward[i].twist).as_slice(),
                TOL,
                &what("V"),
            );
            assert_close(
                ws.twist_dot_in_world[i].as_slice(),
                h.act_twist(&trace.forward[i].twist_dot).as_slice(),
                TOL,
                &what("V̇"),
            );
            assert_close(
                ws.wrench_in_world[i].as_slice(),
                h.inverse()
                    .act_transpose_wrench(&trace.backward[i].wrench)
                    .as_slice(),
                TOL,
                &what("W"),
            );
        }
    }
}
