//! Numerical inverse kinematics (`kinematics::ik::IkSolver`), checked by forward kinematics:
//! targets are the poses of random configurations within the limits, and every answer the
//! solver calls a success is confirmed here by the product-of-exponentials formula
//! (`forward_kinematics_poe`, a code path the solver does not use) and the limits. Also
//! analytic cases (the planar arm's reach), agreement with the closed form, singular targets,
//! limits, held joints, redundancy, and bad input.

#[path = "common/counting.rs"]
mod counting;

use nalgebra::Vector3;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::io::{load_model, load_str, LoadOptions};
use screwdyn::kinematics::ik::{
    ClosedForm, IkFailure, IkOptions, IkResult, IkSolver, IkTask, IkWorkspace,
};
use screwdyn::kinematics::{forward_kinematics_poe, frame_pose};
use screwdyn::spatial::{log_so3, Se3};
use screwdyn::{builtin, Error, Model};
use std::f64::consts::PI;

const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../models/");
const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/");

/// A configuration drawn uniformly within the limits (`[−π, π]` where unbounded).
fn random_q(model: &Model, rng: &mut StdRng) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|j| {
            let lo = if j.limits.lower.is_finite() {
                j.limits.lower
            } else {
                -PI
            };
            let hi = if j.limits.upper.is_finite() {
                j.limits.upper
            } else {
                PI
            };
            rng.gen_range(lo..=hi)
        })
        .collect()
}

/// The middle of the limits (0 where unbounded).
fn middle(model: &Model) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|j| {
            let (lo, hi) = (j.limits.lower, j.limits.upper);
            if lo.is_finite() && hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                0.0
            }
        })
        .collect()
}

/// The pose of `frame` at `q` by the product-of-exponentials formula.
fn poe_pose(model: &Model, frame: usize, q: &[f64]) -> Se3 {
    let f = &model.frames()[frame];
    match f.body {
        Some(b) => forward_kinematics_poe(model, q).unwrap()[b].compose(&f.placement),
        None => f.placement,
    }
}

/// Position (m) and rotation (rad) distance between two poses.
fn distance(a: &Se3, b: &Se3) -> (f64, f64) {
    (
        (a.translation - b.translation).norm(),
        log_so3(&(a.rotation.transpose() * b.rotation)).norm(),
    )
}

fn within_limits(model: &Model, q: &[f64]) -> bool {
    q.iter()
        .zip(model.joints())
        .all(|(v, j)| j.limits.lower <= *v && *v <= j.limits.upper)
}

/// Confirms a success independently: every task's frame within 1e-6 m / 1e-6 rad of its
/// target on the weighed parts (position and/or orientation), every joint within its limits.
fn confirm(model: &Model, tasks: &[IkTask], targets: &[Se3], q: &[f64]) {
    assert!(within_limits(model, q), "outside the limits: {q:?}");
    for (task, target) in tasks.iter().zip(targets) {
        let pose = poe_pose(model, task.frame, q);
        let (p, r) = distance(&pose, target);
        if task.weights[3..].iter().all(|&w| w != 0.0) {
            assert!(p <= 1e-6, "position error {p} at {q:?}");
        }
        if task.weights[..3].iter().all(|&w| w != 0.0) {
            assert!(r <= 1e-6, "orientation error {r} at {q:?}");
        }
    }
}

/// Solves `count` targets made by forward kinematics of random configurations from the middle
/// of the limits; confirms each success and returns the success rate.
fn round_trip(model: &Model, tasks: &[IkTask], options: IkOptions, count: usize, seed: u64) -> f64 {
    let solver = IkSolver::new(model, tasks, options).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(seed);
    let q0 = middle(model);
    let mut q = vec![0.0; model.nq()];
    let mut successes = 0;
    for _ in 0..count {
        let truth = random_q(model, &mut rng);
        let targets: Vec<Se3> = tasks
            .iter()
            .map(|t| poe_pose(model, t.frame, &truth))
            .collect();
        let result = solver.solve(&mut ws, &targets, &q0, &mut q).unwrap();
        if result.success {
            confirm(model, tasks, &targets, &q);
            assert!(result.position_error <= 1e-6 && result.orientation_error <= 1e-6);
            assert_eq!(result.failure, None);
            successes += 1;
        } else {
            assert!(result.failure.is_some());
        }
    }
    successes as f64 / count as f64
}

#[test]
fn ur5_round_trips_from_the_closed_form_and_numerically() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    assert_eq!(
        round_trip(&ur5, &[IkTask::pose(tool)], IkOptions::default(), 300, 1),
        1.0
    );
    let numerical = IkOptions {
        closed_form: false,
        ..IkOptions::default()
    };
    assert_eq!(
        round_trip(&ur5, &[IkTask::pose(tool)], numerical, 300, 2),
        1.0
    );
}

#[test]
fn ur5_urdf_round_trips() {
    let ur5 = load_model(&format!("{MODELS}ur5.urdf")).unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    assert_eq!(
        round_trip(&ur5, &[IkTask::pose(tool)], IkOptions::default(), 200, 3),
        1.0
    );
}

#[test]
fn panda_round_trips() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let rate = round_trip(&panda, &[IkTask::pose(hand)], IkOptions::default(), 300, 4);
    assert!(rate >= 0.99, "{rate}");
}

#[test]
fn planar2_position_round_trips() {
    for model in [
        builtin::planar2(),
        load_model(&format!("{DATA}planar2.urdf")).unwrap(),
    ] {
        let tip = model.body_frame(1).unwrap();
        let rate = round_trip(
            &model,
            &[IkTask::position(tip)],
            IkOptions::default(),
            200,
            5,
        );
        assert_eq!(rate, 1.0, "{}", model.name());
    }
}

#[test]
fn arm3_urdf_position_round_trips() {
    let arm = load_model(&format!("{DATA}arm3.urdf")).unwrap();
    let tip = arm.body_frame(arm.nbodies() - 1).unwrap();
    let rate = round_trip(&arm, &[IkTask::position(tip)], IkOptions::default(), 200, 6);
    assert_eq!(rate, 1.0);
}

#[test]
fn branched_both_hands_and_torso_at_once() {
    let robot = builtin::load("branched").unwrap();
    let left = robot.frame_id("left_hand").unwrap();
    let right = robot.frame_id("right_hand").unwrap();
    // Two 3-DoF arms on a turning torso: seven joints for the two hands' positions (six).
    let tasks = [IkTask::position(left), IkTask::position(right)];
    let rate = round_trip(&robot, &tasks, IkOptions::default(), 200, 7);
    assert!(rate >= 0.99, "{rate}");
    // One hand's full pose is out of reach of 4 joints in general, its position is not.
    let rate = round_trip(
        &robot,
        &[IkTask::position(left)],
        IkOptions::default(),
        200,
        8,
    );
    assert_eq!(rate, 1.0);
}

/// Every numerical answer on the UR5 is one of the closed-form solutions (modulo 2π).
#[test]
fn numerical_solutions_are_closed_form_solutions() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    let cf = ClosedForm::detect(&ur5, tool).unwrap().unwrap();
    let options = IkOptions {
        closed_form: false,
        ..IkOptions::default()
    };
    let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], options).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(9);
    let mut q = [0.0; 6];
    let mut out = [[0.0; 6]; 8];
    for _ in 0..100 {
        let truth = random_q(&ur5, &mut rng);
        let target = poe_pose(&ur5, tool, &truth);
        let q0 = random_q(&ur5, &mut rng);
        assert!(
            solver
                .solve(&mut ws, &[target], &q0, &mut q)
                .unwrap()
                .success
        );
        let count = cf.solve(&target, &mut out);
        let angle = |a: f64| (a + PI).rem_euclid(2.0 * PI) - PI;
        let nearest = out[..count]
            .iter()
            .map(|s| (0..6).map(|k| angle(s[k] - q[k]).abs()).fold(0.0, f64::max))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 1e-5, "{nearest}");
    }
}

/// The UR5 with its wrist singular (θ₅ = 0: axes 4 and 6 aligned) and stretched out (θ₃ = 0),
/// solved numerically from a nearby and a far start.
#[test]
fn singular_targets() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    for closed_form in [false, true] {
        let options = IkOptions {
            closed_form,
            ..IkOptions::default()
        };
        let tasks = [IkTask::pose(tool)];
        let solver = IkSolver::new(&ur5, &tasks, options).unwrap();
        let mut ws = IkWorkspace::new(&solver);
        let mut q = [0.0; 6];
        for truth in [
            [0.3, -1.0, 1.2, -0.5, 0.0, 0.4],
            [0.3, -1.0, 0.0, -0.5, 0.8, 0.4],
            [0.0, -PI / 2.0, 0.0, -PI / 2.0, 0.0, 0.0],
        ] {
            let target = poe_pose(&ur5, tool, &truth);
            for q0 in [[0.0; 6], truth.map(|v| v + 0.05)] {
                let r = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
                assert!(r.success, "{truth:?} from {q0:?}: {r:?}");
                confirm(&ur5, &tasks, &[target], &q);
            }
        }
    }
}

/// The planar arm (L1 = L2 = 1) cannot reach (3, 0, 0): the nearest point is the stretched arm
/// at (2, 0, 0), 1 m away.
#[test]
fn unreachable_target_returns_the_nearest_pose() {
    let arm = builtin::planar2();
    let tip = arm.body_frame(1).unwrap();
    let solver = IkSolver::new(&arm, &[IkTask::position(tip)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q = [0.0; 2];
    let target = Se3::from_translation(Vector3::new(3.0, 0.0, 0.0));
    let r = solver
        .solve(&mut ws, &[target], &[0.3, 0.4], &mut q)
        .unwrap();
    assert!(!r.success);
    assert_eq!(r.failure, Some(IkFailure::Unreachable));
    assert!((r.position_error - 1.0).abs() < 1e-6, "{r:?}");
    let reached = poe_pose(&arm, tip, &q).translation;
    assert!(
        (reached - Vector3::new(2.0, 0.0, 0.0)).norm() < 1e-3,
        "{reached}"
    );
    // The UR5 3 m away.
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q = [0.0; 6];
    let far = Se3::from_translation(Vector3::new(3.0, 0.0, 0.0));
    let r = solver.solve(&mut ws, &[far], &[0.0; 6], &mut q).unwrap();
    assert!(!r.success && r.failure.is_some());
    assert_eq!(r.restarts, IkOptions::default().max_restarts);
    // The errors reported are those of the returned q.
    let (p, _) = distance(&poe_pose(&ur5, tool, &q), &far);
    assert!((p - r.position_error).abs() < 1e-9);
    assert!(p > 1.9, "the UR5 reaches about 1 m: {p}");
}

/// A two-link planar arm (L1 = L2 = 1 m, both joints about z) with the given joint types and
/// limits (`None`: no `limits` key).
fn planar(joints: [(&str, Option<(f64, f64)>); 2]) -> Model {
    let mut text = String::from("format = \"screwdyn\"\nname = \"planar\"\n");
    for (i, (kind, limits)) in joints.iter().enumerate() {
        let parent = if i == 0 { "base" } else { "link1" };
        text += &format!(
            "[[body]]\nname = \"link{}\"\nparent = \"{parent}\"\njoint = \"joint{}\"\ntype = \"{kind}\"\n\
             home = {{ xyz = [1.0, 0.0, 0.0] }}\nscrew_in_parent = [0, 0, 1, 0, 0, 0]\nmass = 1.0\n",
            i + 1,
            i + 1
        );
        if let Some((lo, hi)) = limits {
            text += &format!("limits = {{ lower = {lo:?}, upper = {hi:?} }}\n");
        }
    }
    load_str(&text, "planar.toml", &LoadOptions::default()).unwrap()
}

/// A target reachable only beyond a joint's limit: with the elbow limited to `[0, 0.5]` the
/// arm cannot fold enough to reach a point 0.5 m from the base; the nearest it gets is the
/// elbow at its limit, the tip `2 cos(0.25)` m from the base.
#[test]
fn target_beyond_the_limits_fails_within_the_limits() {
    let arm = planar([
        ("revolute", Some((-3.0, 3.0))),
        ("revolute", Some((0.0, 0.5))),
    ]);
    let tip = arm.body_frame(1).unwrap();
    let solver = IkSolver::new(&arm, &[IkTask::position(tip)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q = [0.0; 2];
    let target = Se3::from_translation(Vector3::new(0.5, 0.0, 0.0));
    let r = solver
        .solve(&mut ws, &[target], &[0.0, 0.2], &mut q)
        .unwrap();
    assert!(!r.success, "{r:?} {q:?}");
    assert!(within_limits(&arm, &q));
    assert_eq!(
        q[1], 0.5,
        "the elbow ends folded as far as its limit lets it"
    );
    assert_eq!(r.failure, Some(IkFailure::Limits));
    let nearest = 2.0 * 0.25_f64.cos() - 0.5;
    assert!((r.position_error - nearest).abs() < 1e-6, "{r:?}");
}

/// Limits at ±π and a continuous joint: targets that need angles near ±π are reached, the
/// bounded joint stays within `[−π, π]`, the continuous one within π of `q0`.
#[test]
fn limits_at_pi_and_continuous_joints() {
    let arm = planar([("revolute", Some((-PI, PI))), ("continuous", None)]);
    let tip = arm.body_frame(1).unwrap();
    let solver = IkSolver::new(&arm, &[IkTask::position(tip)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q = [0.0; 2];
    let mut rng = StdRng::seed_from_u64(11);
    for k in 0..100 {
        // Angles within 0.05 rad of ±π for joint 1, anywhere for joint 2.
        let near_pi = PI - rng.gen_range(0.0..0.05);
        let truth = [
            if k % 2 == 0 { near_pi } else { -near_pi },
            rng.gen_range(-3.0..3.0),
        ];
        let target = poe_pose(&arm, tip, &truth);
        let q0 = [0.0, 20.0]; // the continuous joint several turns away
        let r = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
        assert!(r.success, "{truth:?}: {r:?}");
        confirm(&arm, &[IkTask::position(tip)], &[target], &q);
        assert!(q[0].abs() <= PI);
        assert!((q[1] - q0[1]).abs() <= PI, "{q:?}");
    }
}

/// Held joints keep their `q0` exactly; the others still reach the target.
#[test]
fn held_joints_stay() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let options = IkOptions {
        held_joints: vec![0, 6],
        ..IkOptions::default()
    };
    let tasks = [IkTask::position(hand)];
    let solver = IkSolver::new(&panda, &tasks, options).unwrap();
    assert_eq!(solver.moving_joints(), [1, 2, 3, 4, 5]);
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(12);
    let mut q = [0.0; 7];
    for _ in 0..50 {
        let mut truth = random_q(&panda, &mut rng);
        let q0 = middle(&panda);
        truth[0] = q0[0];
        truth[6] = q0[6];
        let target = poe_pose(&panda, hand, &truth);
        let r = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
        assert!(r.success, "{r:?}");
        confirm(&panda, &tasks, &[target], &q);
        assert_eq!((q[0], q[6]), (q0[0], q0[6]));
    }
}

/// A 5-axis task: the tool's rotation about its own z axis is free. The tool's z axis and
/// origin match the target; its rotation about z generally does not.
#[test]
fn five_axis_task() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    let task = IkTask::weighted(tool, [1.0, 1.0, 0.0, 1.0, 1.0, 1.0]);
    let solver = IkSolver::new(&ur5, &[task], IkOptions::default()).unwrap();
    assert!(
        solver.closed_form().is_none(),
        "a 5-axis task is not the closed form's"
    );
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(13);
    let mut q = [0.0; 6];
    for _ in 0..50 {
        let target = poe_pose(&ur5, tool, &random_q(&ur5, &mut rng));
        let r = solver.solve(&mut ws, &[target], &[0.0; 6], &mut q).unwrap();
        assert!(r.success, "{r:?}");
        let pose = poe_pose(&ur5, tool, &q);
        assert!((pose.translation - target.translation).norm() < 1e-6);
        let z = pose.rotation.column(2);
        assert!(z.angle(&target.rotation.column(2)) < 1e-6);
    }
}

/// Redundancy: the Panda has one joint more than a pose needs. With the posture objective
/// toward a known solution `θ*` of the target (the posture), the answer moves along the
/// self-motion to `θ*` itself; without it, it stops wherever the iteration met the target.
#[test]
fn panda_posture_objective_moves_along_the_self_motion() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let tasks = [IkTask::pose(hand)];
    let q0 = middle(&panda);
    let mut mean_distance = [0.0; 2];
    for (k, gain) in [0.0, 0.5].into_iter().enumerate() {
        let mut rng = StdRng::seed_from_u64(14);
        let mut q = [0.0; 7];
        for _ in 0..50 {
            let truth: Vec<f64> = q0.iter().map(|v| v + rng.gen_range(-0.5..0.5)).collect();
            let options = IkOptions {
                posture_gain: gain,
                posture: Some(truth.clone()),
                ..IkOptions::default()
            };
            let solver = IkSolver::new(&panda, &tasks, options).unwrap();
            let mut ws = IkWorkspace::new(&solver);
            let target = poe_pose(&panda, hand, &truth);
            let r = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
            assert!(r.success, "{r:?}");
            confirm(&panda, &tasks, &[target], &q);
            let d: f64 = q.iter().zip(&truth).map(|(a, b)| (a - b) * (a - b)).sum();
            mean_distance[k] += d.sqrt() / 50.0;
        }
    }
    assert!(
        mean_distance[1] < 0.1 * mean_distance[0],
        "distance to the posture: objective off {}, on {}",
        mean_distance[0],
        mean_distance[1]
    );
}

/// The same seed gives the same answer; restarts differ with the seed.
#[test]
fn deterministic() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let solver = IkSolver::new(&panda, &[IkTask::pose(hand)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(15);
    let targets: Vec<Se3> = (0..20)
        .map(|_| poe_pose(&panda, hand, &random_q(&panda, &mut rng)))
        .collect();
    let solve_all = |ws: &mut IkWorkspace| -> Vec<(Vec<f64>, IkResult)> {
        targets
            .iter()
            .map(|t| {
                let mut q = vec![0.0; 7];
                let r = solver.solve(ws, &[*t], &middle(&panda), &mut q).unwrap();
                (q, r)
            })
            .collect()
    };
    let first = solve_all(&mut ws);
    let mut fresh = IkWorkspace::new(&solver);
    assert_eq!(first, solve_all(&mut fresh));
}

fn error_of(r: Result<IkResult, Error>) -> String {
    r.unwrap_err().to_string()
}

#[test]
fn bad_input_is_an_error_naming_it() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    assert!(matches!(
        ur5.frame_id("flange_tip").unwrap_err(),
        Error::UnknownName { kind: "frame", .. }
    ));
    let e = IkSolver::new(&ur5, &[IkTask::pose(999)], IkOptions::default()).unwrap_err();
    assert!(e.to_string().contains("999"), "{e}");
    assert!(IkSolver::new(&ur5, &[], IkOptions::default()).is_err());
    let e = IkSolver::new(
        &ur5,
        &[IkTask::weighted(tool, [0.0; 6])],
        IkOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("every weight zero"), "{e}");
    let held = IkOptions {
        held_joints: vec![6],
        ..IkOptions::default()
    };
    assert!(IkSolver::new(&ur5, &[IkTask::pose(tool)], held).is_err());

    let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q = [0.0; 6];
    let good = poe_pose(&ur5, tool, &[0.1; 6]);
    // A rotation that is not orthonormal: the message names the tolerance.
    let mut skew = good;
    skew.rotation[(0, 1)] += 1e-3;
    let e = error_of(solver.solve(&mut ws, &[skew], &[0.0; 6], &mut q));
    assert!(e.contains("not orthonormal") && e.contains("1e-9"), "{e}");
    // NaN in a target.
    let mut nan = good;
    nan.translation.y = f64::NAN;
    let e = solver
        .solve(&mut ws, &[nan], &[0.0; 6], &mut q)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    // q0 outside the limits names the joint.
    let e = error_of(solver.solve(&mut ws, &[good], &[0.0, 0.0, 7.0, 0.0, 0.0, 0.0], &mut q));
    assert!(
        e.contains("elbow_joint") && e.contains("outside its limits"),
        "{e}"
    );
    // Wrong lengths: q0, q_out, the number of targets.
    let e = solver
        .solve(&mut ws, &[good], &[0.0; 5], &mut q)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::DimensionMismatch {
                got: 5,
                expected: 6,
                ..
            }
        ),
        "{e}"
    );
    let e = error_of(solver.solve(&mut ws, &[good], &[0.0; 6], &mut [0.0; 7]));
    assert!(e.contains("7 values"), "{e}");
    let e = error_of(solver.solve(&mut ws, &[good, good], &[0.0; 6], &mut q));
    assert!(e.contains("2 IK targets"), "{e}");
    // NaN in q0.
    let e = solver
        .solve(&mut ws, &[good], &[f64::NAN; 6], &mut q)
        .unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    // A workspace made for another solver.
    let panda = builtin::load("panda").unwrap();
    let other = IkSolver::new(
        &panda,
        &[IkTask::pose(panda.frame_id("panda_link8").unwrap())],
        IkOptions::default(),
    )
    .unwrap();
    let mut wrong = IkWorkspace::new(&other);
    assert!(solver
        .solve(&mut wrong, &[good], &[0.0; 6], &mut q)
        .is_err());
    // Options out of range.
    let bad = IkOptions {
        orientation_tolerance: f64::NAN,
        ..IkOptions::default()
    };
    assert!(IkSolver::new(&ur5, &[IkTask::pose(tool)], bad).is_err());
}

/// Once the workspace exists, solving allocates nothing (restarts and failures included).
#[test]
fn solve_allocates_nothing() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    for (model, frame) in [(panda, hand), (ur5, tool)] {
        let options = IkOptions {
            posture_gain: 0.1,
            limit_gain: 0.1,
            ..IkOptions::default()
        };
        let solver = IkSolver::new(&model, &[IkTask::pose(frame)], options).unwrap();
        let mut ws = IkWorkspace::new(&solver);
        let mut rng = StdRng::seed_from_u64(16);
        let mut targets: Vec<Se3> = (0..10)
            .map(|_| poe_pose(&model, frame, &random_q(&model, &mut rng)))
            .collect();
        targets.push(Se3::from_translation(Vector3::new(3.0, 0.0, 0.0)));
        let q0 = middle(&model);
        let mut q = vec![0.0; model.nq()];
        let mut successes = 0;
        let allocs = counting::allocations(|| {
            for target in &targets {
                successes += solver
                    .solve(&mut ws, &[*target], &q0, &mut q)
                    .unwrap()
                    .success as usize;
            }
        });
        assert_eq!(allocs, 0, "{}", model.name());
        assert!(successes >= 10);
        let _ = frame_pose(&model, ws.kinematics(), frame).unwrap();
    }
}

/// Targets whose configurations put joints on their limits: the Panda with its 2nd, 4th and
/// 6th joints each at a limit (drawn at random which). A joint on its limit whose step points
/// out of it is held there and the others make up for it, so one attempt from the middle of
/// the limits (no restarts) reaches most of them (141 of these 200; clamping each step into
/// the limits without holding reached 96), each confirmed by the product-of-exponentials
/// formula.
#[test]
fn targets_with_joints_on_their_limits() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.body_frame(6).unwrap();
    let tasks = [IkTask::pose(hand)];
    let options = IkOptions {
        max_restarts: 0,
        ..IkOptions::default()
    };
    let solver = IkSolver::new(&panda, &tasks, options).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(11);
    let q0 = middle(&panda);
    let mut q = vec![0.0; panda.nq()];
    let (count, mut successes, mut iterations) = (200, 0, 0_usize);
    for _ in 0..count {
        let mut truth = random_q(&panda, &mut rng);
        for j in [1, 3, 5] {
            let limits = panda.joints()[j].limits;
            truth[j] = if rng.gen_bool(0.5) {
                limits.lower
            } else {
                limits.upper
            };
        }
        let target = poe_pose(&panda, hand, &truth);
        let result = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
        iterations += result.iterations;
        if result.success {
            confirm(&panda, &tasks, &[target], &q);
            successes += 1;
        }
    }
    assert!(
        successes >= 130,
        "{successes} of {count} reached in one attempt ({iterations} iterations)"
    );
}

/// Why a UR5 solve fails. Its tool is at most `Σ (|a_i| + |d_i|)` of its Denavit–Hartenberg
/// parameters from the base origin (the tool's position is a sum of those vectors):
/// 0.089159 + 0.425 + 0.39225 + 0.10915 + 0.09465 + 0.0823 = 1.192709 m. Targets farther than
/// that are `Unreachable`, whatever the limits. A target made by forward kinematics (so within
/// reach) whose every closed-form solution puts the base joint outside narrowed limits
/// `[−0.1, 0.1]` is `Limits`.
#[test]
fn out_of_reach_is_unreachable_and_out_of_the_limits_is_limits() {
    let ur5 = load_model(&format!("{MODELS}ur5.urdf")).unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    let options = IkOptions {
        max_restarts: 5,
        ..IkOptions::default()
    };
    let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], options.clone()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q = [0.0; 6];
    let dh_sum = 0.089159 + 0.425 + 0.39225 + 0.10915 + 0.09465 + 0.0823;
    for (distance, direction) in [
        (1.25, Vector3::new(1.0, 0.0, 0.0)),
        (1.25, Vector3::new(0.0, -0.6, 0.8)),
        (3.0, Vector3::new(0.0, 0.0, 1.0)),
    ] {
        assert!(distance > dh_sum);
        let far = Se3::from_translation(direction * distance);
        let r = solver.solve(&mut ws, &[far], &[0.0; 6], &mut q).unwrap();
        assert!(!r.success);
        assert_eq!(
            r.failure,
            Some(IkFailure::Unreachable),
            "{distance} m: {r:?}"
        );
        // The errors are those of the returned q, which stays within the limits.
        let (p, _) = distance_of(&ur5, tool, &q, &far);
        assert!((p - r.position_error).abs() < 1e-9 && within_limits(&ur5, &q));
    }
    // The base joint narrowed to [−0.1, 0.1].
    let text = std::fs::read_to_string(format!("{MODELS}ur5.urdf")).unwrap();
    let narrowed = text.replacen(
        r#"<limit lower="-6.283185307179586" upper="6.283185307179586""#,
        r#"<limit lower="-0.1" upper="0.1""#,
        1,
    );
    assert_ne!(narrowed, text);
    let tight = load_str(&narrowed, "ur5_tight.urdf", &LoadOptions::default()).unwrap();
    assert_eq!(tight.joints()[0].limits.upper, 0.1);
    let truth = [1.0, -1.2, 1.4, -0.5, 1.1, 0.3];
    let target = poe_pose(&ur5, tool, &truth);
    assert!(target.translation.norm() < dh_sum);
    let cf = ClosedForm::detect(&ur5, tool).unwrap().unwrap();
    let mut all = [[0.0; 6]; 8];
    let count = cf.solve(&target, &mut all);
    assert!(count > 0);
    for theta in &all[..count] {
        let base = (theta[0] + PI).rem_euclid(2.0 * PI) - PI;
        assert!(
            base.abs() > 0.1,
            "a solution within the narrowed limits: {theta:?}"
        );
    }
    let solver = IkSolver::new(&tight, &[IkTask::pose(tool)], options).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let r = solver.solve(&mut ws, &[target], &[0.0; 6], &mut q).unwrap();
    assert!(!r.success && within_limits(&tight, &q), "{r:?} {q:?}");
    assert_eq!(r.failure, Some(IkFailure::Limits), "{r:?} {q:?}");
}

/// The position error (m) and rotation angle (rad) of `frame` at `q` from `target`.
fn distance_of(model: &Model, frame: usize, q: &[f64], target: &Se3) -> (f64, f64) {
    distance(&poe_pose(model, frame, q), target)
}
