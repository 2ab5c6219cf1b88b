//! Cartesian moves: forward kinematics of the timed trajectory stays on the line or the circle
//! with the slerped orientation, the tool speed stays within its limit (by finite differences
//! of the forward kinematics), and a singularity or the end of the reach is reported where it is.

use nalgebra::{Matrix3, Vector3};
use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::motion::{cartesian_move, CartesianOptions, TimingLimits};
use screwdyn::sim::Trajectory;
use screwdyn::spatial::{exp_so3, log_so3, Se3};
use screwdyn::{builtin, Model, Workspace};

const Q0: [f64; 6] = [0.3, -1.2, 1.5, -1.9, -1.57, 0.2];

fn ur5() -> (Model, usize) {
    let m = builtin::load("ur5").unwrap();
    let tool = m.frame_id("tool0").unwrap();
    (m, tool)
}

fn pose(m: &Model, frame: usize, q: &[f64]) -> Se3 {
    let mut ws = Workspace::new(m);
    forward_kinematics(m, &mut ws, q).unwrap();
    frame_pose(m, &ws, frame).unwrap()
}

/// The poses of the frame along the timed move, every millisecond.
fn sampled_poses(m: &Model, frame: usize, motion: &dyn Trajectory) -> Vec<Se3> {
    let n = m.nq();
    let (mut q, mut qd, mut qdd) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let samples = (motion.duration() / 1e-3).ceil() as usize;
    (0..=samples)
        .map(|k| {
            motion.eval(
                (k as f64 * 1e-3).min(motion.duration()),
                &mut q,
                &mut qd,
                &mut qdd,
            );
            pose(m, frame, &q)
        })
        .collect()
}

fn angle_between(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    log_so3(&(a.transpose() * b)).norm()
}

#[test]
fn a_linear_move_stays_on_the_segment_with_the_slerped_orientation() {
    let (m, tool) = ur5();
    let start = pose(&m, tool, &Q0);
    let shift = Vector3::new(0.05, 0.12, -0.08);
    let turn = Vector3::new(0.2, -0.1, 0.25);
    let target = Se3::new(start.rotation * exp_so3(&turn), start.translation + shift);
    let limits = TimingLimits::from_model(&m);
    let motion =
        cartesian_move(&m, tool, &Q0, &target, None, &limits, &Default::default()).unwrap();
    let poses = sampled_poses(&m, tool, &motion);
    let (mut worst_off_line, mut worst_angle) = (0.0_f64, 0.0_f64);
    for p in &poses {
        // The fraction along the segment, from the position alone.
        let d = p.translation - start.translation;
        let sigma = d.dot(&shift) / shift.norm_squared();
        assert!((-1e-9..=1.0 + 1e-9).contains(&sigma), "σ = {sigma}");
        worst_off_line = worst_off_line.max((d - sigma * shift).norm());
        // The slerp at that fraction: R_0 exp(σ ω).
        let slerped = start.rotation * exp_so3(&(sigma * turn));
        worst_angle = worst_angle.max(angle_between(&slerped, &p.rotation));
    }
    assert!(worst_off_line < 2e-6, "{worst_off_line} m off the line");
    assert!(worst_angle < 2e-6, "{worst_angle} rad off the slerp");
    let end = poses.last().unwrap();
    assert!((end.translation - target.translation).norm() < 1e-6);
    assert!(angle_between(&end.rotation, &target.rotation) < 1e-6);
}

#[test]
fn a_circular_move_stays_on_the_circle_through_the_via_point() {
    let (m, tool) = ur5();
    let start = pose(&m, tool, &Q0);
    // A circle of radius 0.08 m in the horizontal plane, centred 0.08 m along −x from the start:
    // via a quarter turn on, target half a turn on.
    let r = 0.08;
    let center = start.translation - Vector3::new(r, 0.0, 0.0);
    let via = center + Vector3::new(0.0, r, 0.0);
    let target = Se3::new(start.rotation, center + Vector3::new(-r, 0.0, 0.0));
    let limits = TimingLimits::from_model(&m);
    let options = CartesianOptions {
        tool_speed: 0.3,
        ..Default::default()
    };
    let motion = cartesian_move(&m, tool, &Q0, &target, Some(via), &limits, &options).unwrap();
    assert!((motion.path().length() - std::f64::consts::PI * r).abs() < 1e-12);
    let poses = sampled_poses(&m, tool, &motion);
    let mut passed_via = f64::INFINITY;
    for p in &poses {
        let d = p.translation - center;
        assert!(
            (d.norm() - r).abs() < 2e-6,
            "{} m off the circle",
            d.norm() - r
        );
        assert!(d.z.abs() < 2e-6, "{} m off the plane", d.z);
        assert!(d.y > -2e-6, "on the other half of the circle: {d:?}");
        assert!(angle_between(&start.rotation, &p.rotation) < 2e-6);
        passed_via = passed_via.min((p.translation - via).norm());
    }
    assert!(passed_via < 0.3 * 1e-3, "{passed_via}");
    // A half circle at no more than 0.3 m/s takes at least π r / 0.3.
    assert!(motion.duration() > std::f64::consts::PI * r / 0.3);
}

#[test]
fn the_tool_speed_never_exceeds_its_limit() {
    let (m, tool) = ur5();
    let start = pose(&m, tool, &Q0);
    let target = Se3::new(
        start.rotation,
        start.translation + Vector3::new(0.0, 0.25, 0.0),
    );
    let v_tool = 0.2;
    let options = CartesianOptions {
        tool_speed: v_tool,
        ..Default::default()
    };
    let limits = TimingLimits::from_model(&m);
    let motion = cartesian_move(&m, tool, &Q0, &target, None, &limits, &options).unwrap();
    let n = m.nq();
    let (mut q, mut qd, mut qdd) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut at = |t: f64| {
        motion.eval(t, &mut q, &mut qd, &mut qdd);
        pose(&m, tool, &q).translation
    };
    // |ṗ| by central differences of the forward kinematics.
    let h = 1e-6;
    let mut fastest = 0.0_f64;
    let samples = (motion.duration() / 1e-3) as usize;
    for k in 1..samples {
        let t = k as f64 * 1e-3;
        let speed = (at(t + h) - at(t - h)).norm() / (2.0 * h);
        fastest = fastest.max(speed);
    }
    assert!(fastest <= v_tool * (1.0 + 1e-6), "{fastest} m/s");
    // The limit is what bounds this move: it cruises at it.
    assert!(fastest > 0.999 * v_tool, "{fastest} m/s");
    // Cruising at v_tool most of the way: just over 0.25 / 0.2 s.
    assert!(motion.duration() > 0.25 / v_tool && motion.duration() < 1.5 * 0.25 / v_tool);
}

/// The fraction of the path an error message names (`… at 43.0 % of the path …`).
fn fraction_in(message: &str) -> f64 {
    let before = message.split(" % of the path").next().unwrap();
    before.rsplit(' ').next().unwrap().parse::<f64>().unwrap() / 100.0
}

/// The world-frame rotation axis of joint `j` at `q`, from the forward kinematics of the frame:
/// `log(R(q + h e_j) R(q)ᵀ) / h`.
fn joint_axis(m: &Model, frame: usize, q: &[f64], j: usize) -> Vector3<f64> {
    let h = 1e-7;
    let mut moved = q.to_vec();
    moved[j] += h;
    let (r, r_moved) = (pose(m, frame, q).rotation, pose(m, frame, &moved).rotation);
    (log_so3(&(r_moved * r.transpose())) / h).normalize()
}

#[test]
fn a_turn_past_the_wrist_singularity_reports_where() {
    let (m, tool) = ur5();
    // The wrist is singular at q5 = 0: joints 4 and 6 aligned, and no wrist joint turns the tool
    // about w = z5 × z4. The tool turns about z5 from −δ to +δ (through q5 = 0), tilted by a
    // small ε about w: half-way, joints 4 and 6 must swing by about π within a turn of a few ε.
    let mut q_singular = Q0;
    q_singular[4] = 0.0;
    let middle = pose(&m, tool, &q_singular);
    let z4 = joint_axis(&m, tool, &q_singular, 3);
    let z5 = joint_axis(&m, tool, &q_singular, 4);
    let w = z5.cross(&z4).normalize();
    let (delta, epsilon) = (0.1, 2e-3);
    let turned = |angle: f64| {
        Se3::new(
            exp_so3(&(epsilon * w)) * exp_so3(&(angle * z5)) * middle.rotation,
            middle.translation,
        )
    };
    let (start_pose, target) = (turned(-delta), turned(delta));
    // The start: the IK of the start pose from the singular configuration turned by −δ.
    let solver = IkSolver::new(&m, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q0 = vec![0.0; 6];
    let mut seed = q_singular;
    seed[4] = -delta;
    assert!(
        solver
            .solve(&mut ws, &[start_pose], &seed, &mut q0)
            .unwrap()
            .success
    );
    let limits = TimingLimits::from_model(&m);
    let e = cartesian_move(&m, tool, &q0, &target, None, &limits, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("singularity") || e.contains("finds no pose"),
        "{e}"
    );
    // The turn passes nearest the singular pose half-way.
    let at = fraction_in(&e);
    assert!((at - 0.5).abs() < 0.06, "{e}");
    assert!(e.contains("rad of 0.2000 rad"), "{e}");
}

#[test]
fn a_line_out_of_reach_reports_where_the_reach_ends() {
    let (m, tool) = ur5();
    let start = pose(&m, tool, &Q0);
    // Straight out, 1 m further from the base axis: the arm (about 0.95 m long) runs out.
    let outward = Vector3::new(start.translation.x, start.translation.y, 0.0).normalize();
    let target = Se3::new(start.rotation, start.translation + outward);
    let limits = TimingLimits::from_model(&m);
    let e = cartesian_move(&m, tool, &Q0, &target, None, &limits, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("out of reach"), "{e}");
    let at = fraction_in(&e);
    // Independent bracket: a fresh IK (with restarts) reaches the pose 5 mm before the point
    // reported, and none reaches 5 mm after it.
    let solver = IkSolver::new(&m, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    let mut ws = IkWorkspace::new(&solver);
    let mut q = vec![0.0; 6];
    let on_line = |sigma: f64| Se3::new(start.rotation, start.translation + sigma * outward);
    assert!(
        solver
            .solve(&mut ws, &[on_line(at - 5e-3)], &Q0, &mut q)
            .unwrap()
            .success,
        "{e}"
    );
    assert!(
        !solver
            .solve(&mut ws, &[on_line(at + 5e-3)], &Q0, &mut q)
            .unwrap()
            .success,
        "{e}"
    );
}

#[test]
fn bad_options_are_refused() {
    let (m, tool) = ur5();
    let start = pose(&m, tool, &Q0);
    let limits = TimingLimits::from_model(&m);
    let options = CartesianOptions {
        tool_speed: 0.0,
        ..Default::default()
    };
    let e = cartesian_move(&m, tool, &Q0, &start, None, &limits, &options).unwrap_err();
    assert!(e.to_string().contains("tool_speed is 0"), "{e}");
    let e = cartesian_move(
        &m,
        tool,
        &Q0[..5],
        &start,
        None,
        &limits,
        &Default::default(),
    );
    assert!(e.is_err());
}
