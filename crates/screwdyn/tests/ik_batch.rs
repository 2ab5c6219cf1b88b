//! Every closed-form solution refined and checked (`IkSolver::solve_all`), batches on several
//! threads (`solve_batch`) and paths (`solve_path`); every answer confirmed by the
//! product-of-exponentials formula and the limits.

use nalgebra::Vector3;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::kinematics::forward_kinematics_poe;
use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
use screwdyn::spatial::{log_so3, Se3};
use screwdyn::{builtin, Error, Model};
use std::f64::consts::PI;

fn random_q(model: &Model, rng: &mut StdRng) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|j| rng.gen_range(j.limits.lower..=j.limits.upper))
        .collect()
}

fn poe_pose(model: &Model, frame: usize, q: &[f64]) -> Se3 {
    let f = &model.frames()[frame];
    forward_kinematics_poe(model, q).unwrap()[f.body.unwrap()].compose(&f.placement)
}

/// FK of `q` within 1e-6 m and rad of `target`, `q` within the limits.
fn confirm(model: &Model, frame: usize, target: &Se3, q: &[f64]) {
    let pose = poe_pose(model, frame, q);
    assert!((pose.translation - target.translation).norm() <= 1e-6);
    assert!(log_so3(&(pose.rotation.transpose() * target.rotation)).norm() <= 1e-6);
    for (v, j) in q.iter().zip(model.joints()) {
        assert!(j.limits.lower <= *v && *v <= j.limits.upper);
    }
}

/// The UR5 (limits ±2π) has up to 8 solutions, all kept; each returned one is confirmed by forward
/// kinematics, they differ from each other, and the configuration the target was made from
/// is among them (modulo 2π).
#[test]
fn ur5_every_solution() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(21);
    let cf = solver.closed_form().unwrap();
    let mut out = [[0.0; 6]; 8];
    for _ in 0..100 {
        let truth = random_q(&ur5, &mut rng);
        let target = poe_pose(&ur5, tool, &truth);
        let all = solver.solve_all(&mut ws, &target, &[0.0; 6]).unwrap();
        // Limits of ±2π fit every branch: as many as the closed form's exact branches.
        assert_eq!(all.len(), cf.solve(&target, &mut out));
        for (i, s) in all.iter().enumerate() {
            // Each branch confirmed as the closed form gave it, without refinement.
            assert!(s.result.success && s.result.iterations == 0);
            confirm(&ur5, tool, &target, &s.q);
            for other in &all[..i] {
                assert!(other.q.iter().zip(&s.q).any(|(a, b)| (a - b).abs() > 1e-6));
            }
        }
        let angle = |a: f64| (a + PI).rem_euclid(2.0 * PI) - PI;
        assert!(
            all.iter().any(|s| s
                .q
                .iter()
                .zip(&truth)
                .all(|(a, b)| angle(a - b).abs() < 1e-6)),
            "{truth:?} not among {all:?}"
        );
    }
}

/// The numerical solver starts from the closed-form solution nearest q0 on the UR5: exact to
/// round-off, it is confirmed by forward kinematics as it is and taken without an iteration
/// (confirmed here again by the product-of-exponentials formula).
#[test]
fn ur5_closed_form_first_guess_needs_no_iteration() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    assert!(solver.closed_form().is_some());
    let mut ws = IkWorkspace::new(&solver);
    let mut rng = StdRng::seed_from_u64(22);
    let mut q = [0.0; 6];
    for _ in 0..200 {
        let truth = random_q(&ur5, &mut rng);
        let target = poe_pose(&ur5, tool, &truth);
        // Started next to the truth, the answer is the truth (the nearest branch).
        let q0: Vec<f64> = truth.iter().map(|v| (v + 0.01).min(2.0 * PI)).collect();
        let r = solver.solve(&mut ws, &[target], &q0, &mut q).unwrap();
        assert!(r.success && r.iterations == 0 && r.restarts == 0, "{r:?}");
        confirm(&ur5, tool, &target, &q);
        assert!(q.iter().zip(&truth).all(|(a, b)| (a - b).abs() < 1e-6));
    }
}

/// Without a closed form (the Panda), the one numerical answer.
#[test]
fn panda_solve_all_is_the_numerical_answer() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let solver = IkSolver::new(&panda, &[IkTask::pose(hand)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let truth = [0.3, -0.4, 0.2, -2.0, 0.3, 1.7, 0.4];
    let target = poe_pose(&panda, hand, &truth);
    let q0 = [0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0];
    let all = solver.solve_all(&mut ws, &target, &q0).unwrap();
    assert_eq!(all.len(), 1);
    confirm(&panda, hand, &target, &all[0].q);
}

/// A batch gives the same answers on 1, 2 and 3 threads; each success is confirmed; a bad
/// problem is reported by its index and the others are solved.
#[test]
fn batches_do_not_depend_on_the_thread_count() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let solver = IkSolver::new(&panda, &[IkTask::pose(hand)], IkOptions::default()).unwrap();
    let mut rng = StdRng::seed_from_u64(23);
    let mut targets: Vec<Se3> = (0..40)
        .map(|_| poe_pose(&panda, hand, &random_q(&panda, &mut rng)))
        .collect();
    targets[3].translation.x = f64::NAN;
    let q0 = [0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0];
    let mut answers = Vec::new();
    for threads in [1, 2, 3] {
        let mut q = vec![0.0; 40 * 7];
        let results = solver.solve_batch(&targets, &q0, &mut q, threads).unwrap();
        assert!(matches!(&results[3], Err(Error::Batch { state: 3, .. })));
        for (i, r) in results.iter().enumerate() {
            if i != 3 {
                let r = r.as_ref().unwrap();
                assert!(r.success, "{i}: {r:?}");
                confirm(&panda, hand, &targets[i], &q[i * 7..(i + 1) * 7]);
            }
        }
        answers.push((q, results));
    }
    assert_eq!(answers[0], answers[1]);
    assert_eq!(answers[0], answers[2]);
    // The lengths must fit.
    assert!(solver.solve_batch(&targets, &q0, &mut [0.0; 7], 1).is_err());
    assert!(solver
        .solve_batch(&targets, &q0[..6], &mut vec![0.0; 280], 1)
        .is_err());
}

/// A straight line of the UR5's tool (fixed orientation) solved point by point stays on one
/// branch: consecutive answers differ little, and no jump is reported; with a tiny threshold
/// every reported jump is the actual change of the answers.
#[test]
fn paths_stay_on_one_branch_and_report_jumps() {
    let ur5 = builtin::load("ur5").unwrap();
    let tool = ur5.frame_id("tool0").unwrap();
    let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let q0 = [0.3, -1.2, 1.5, -0.4, 1.1, 0.7];
    let start = poe_pose(&ur5, tool, &q0);
    let line: Vec<Se3> = (0..=50)
        .map(|i| {
            start.with_translation(
                start.translation + Vector3::new(0.0, 0.004 * i as f64, -0.002 * i as f64),
            )
        })
        .collect();
    let mut q = vec![0.0; 51 * 6];
    let path = solver.solve_path(&mut ws, &line, &q0, 0.2, &mut q).unwrap();
    assert!(path.jumps.is_empty(), "{:?}", path.jumps);
    for (p, r) in path.results.iter().enumerate() {
        assert!(r.success);
        confirm(&ur5, tool, &line[p], &q[p * 6..(p + 1) * 6]);
        if p > 0 {
            let step = (0..6)
                .map(|j| (q[p * 6 + j] - q[(p - 1) * 6 + j]).abs())
                .fold(0.0, f64::max);
            assert!(step < 0.05, "point {p}: {step}");
        }
    }
    let fine = solver
        .solve_path(&mut ws, &line, &q0, 1e-3, &mut q)
        .unwrap();
    assert!(!fine.jumps.is_empty());
    for jump in &fine.jumps {
        let change = q[jump.point * 6 + jump.joint] - q[(jump.point - 1) * 6 + jump.joint];
        assert_eq!(jump.change, change);
        assert!(change.abs() > 1e-3);
    }
    assert!(solver.solve_path(&mut ws, &line, &q0, 0.0, &mut q).is_err());
}

/// A batch solved block by block with `solve_batch_into` (as the CLI streams a file) gives
/// exactly the answers of one `solve_batch` call, bad problems named by their index in the
/// whole batch. Out-of-reach targets take every restart, so their answers depend on the seed
/// stream: solving a later block as if it were the first gives other answers.
#[test]
fn blocks_give_the_answers_of_one_batch() {
    let panda = builtin::load("panda").unwrap();
    let hand = panda.frame_id("panda_link8").unwrap();
    let options = IkOptions {
        max_restarts: 3,
        ..IkOptions::default()
    };
    let solver = IkSolver::new(&panda, &[IkTask::pose(hand)], options).unwrap();
    let mut rng = StdRng::seed_from_u64(29);
    let mut targets: Vec<Se3> = (0..45)
        .map(|i| {
            let pose = poe_pose(&panda, hand, &random_q(&panda, &mut rng));
            if i % 5 == 4 {
                // 2 m out: beyond the Panda's reach (about 1.2 m).
                pose.with_translation(pose.translation + Vector3::new(2.0, 0.0, 0.0))
            } else {
                pose
            }
        })
        .collect();
    targets[20].translation.y = f64::INFINITY;
    let q0 = [0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0];
    let mut whole = vec![0.0; 45 * 7];
    let expected = solver.solve_batch(&targets, &q0, &mut whole, 2).unwrap();
    assert!(matches!(&expected[20], Err(Error::Batch { state: 20, .. })));
    let mut blocks = vec![0.0; 45 * 7];
    let mut results = Vec::new();
    for first in (0..45).step_by(16) {
        let end = (first + 16).min(45);
        let mut block = Vec::new();
        block.resize_with(end - first, || Ok(expected[0].clone().unwrap()));
        solver
            .solve_batch_into(
                &targets[first..end],
                &q0,
                &mut blocks[first * 7..end * 7],
                3,
                first,
                &mut block,
            )
            .unwrap();
        results.extend(block);
    }
    assert_eq!(whole, blocks);
    assert_eq!(format!("{expected:?}"), format!("{results:?}"));
    // The block from 32 solved as if it were the first block of a batch.
    let mut wrong = vec![0.0; 13 * 7];
    solver
        .solve_batch(&targets[32..], &q0, &mut wrong, 1)
        .unwrap();
    assert_ne!(wrong, whole[32 * 7..]);
}
