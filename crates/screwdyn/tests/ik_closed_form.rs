//! Closed-form inverse kinematics (`kinematics::ik::ClosedForm`), checked by forward
//! kinematics: random configurations within the limits → the frame's pose → every solution
//! must reproduce that pose (by the library's forward-kinematics recursion, a code path the
//! closed form does not use), and the configuration we started from must be among them.
//!
//! Arms: the built-in UR5 (TOML and URDF), a Puma 560, an ortho-parallel arm with a shoulder
//! offset (KUKA-like), an arm whose first two axes meet but whose second and third are skew,
//! and arms with those geometries read from the tip.

#[path = "common/counting.rs"]
mod counting;

use nalgebra::{Matrix6, Matrix6xX};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::io::{load_model, load_str, LoadOptions};
use screwdyn::kinematics::ik::{ClosedForm, ClosedFormFamily};
use screwdyn::kinematics::{
    compute_joint_jacobians, forward_kinematics, frame_jacobian, frame_pose, Reference,
};
use screwdyn::spatial::Se3;
use screwdyn::{builtin, Model, Workspace};
use std::f64::consts::{FRAC_PI_2, PI};

const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../models/");

/// One standard-DH row: `a`, `α`, `d`, the `θ` offset, and the joint limits (rad).
struct Row {
    a: f64,
    alpha: f64,
    d: f64,
    theta: f64,
    limits: (f64, f64),
}

fn row(a: f64, alpha: f64, d: f64, limits: (f64, f64)) -> Row {
    Row {
        a,
        alpha,
        d,
        theta: 0.0,
        limits,
    }
}

const FULL: (f64, f64) = (-PI, PI);

/// A standard-DH model of the rows, with a tool frame `tool` on the last link (an offset and a
/// rotation, so that `M` is not the flange). `extra_first` adds a joint on another branch
/// before the arm (it must be ignored).
fn dh_model(name: &str, rows: &[Row], extra_first: bool) -> Model {
    let mut text = format!("format = \"dh\"\nname = \"{name}\"\n");
    if extra_first {
        text += "[[row]]\nname = \"other\"\nlink = \"other_link\"\nparent = \"base\"\ntype = \"R\"\na = 0.3\nmass = 1.0\n";
    }
    for (i, r) in rows.iter().enumerate() {
        let parent = if i == 0 {
            "base".to_string()
        } else {
            format!("link{i}")
        };
        text += &format!(
            "[[row]]\nname = \"joint{}\"\nlink = \"link{}\"\nparent = \"{parent}\"\ntype = \"R\"\n\
             a = {:?}\nalpha = {:?}\nd = {:?}\ntheta = {:?}\n\
             limits = {{ lower = {:?}, upper = {:?} }}\nmass = 1.0\n",
            i + 1,
            i + 1,
            r.a,
            r.alpha,
            r.d,
            r.theta,
            r.limits.0,
            r.limits.1
        );
    }
    text += &format!(
        "[[frame]]\nname = \"tool\"\nlink = \"link{}\"\npose = {{ xyz = [0.01, -0.02, 0.1], rpy = [0.1, 0.2, 0.3] }}\n",
        rows.len()
    );
    load_str(&text, &format!("{name}.toml"), &LoadOptions::default()).unwrap()
}

/// Puma 560, standard DH, from Corke's Robotics Toolbox `mdl_puma560` (kinematics and joint
/// limits: −160…160, −45…225, −225…45, −110…170, −100…100, −266…266 degrees).
fn puma560() -> Model {
    let deg = PI / 180.0;
    let lim = |a: f64, b: f64| (a * deg, b * deg);
    dh_model(
        "puma560",
        &[
            row(0.0, FRAC_PI_2, 0.0, lim(-160.0, 160.0)),
            row(0.4318, 0.0, 0.0, lim(-45.0, 225.0)),
            row(0.0203, -FRAC_PI_2, 0.15005, lim(-225.0, 45.0)),
            row(0.0, FRAC_PI_2, 0.4318, lim(-110.0, 170.0)),
            row(0.0, -FRAC_PI_2, 0.0, lim(-100.0, 100.0)),
            row(0.0, 0.0, 0.0, lim(-266.0, 266.0)),
        ],
        false,
    )
}

/// An ortho-parallel arm with a shoulder offset (axis 1 does not meet axis 2) and an elbow
/// offset, with the lengths of the KUKA KR 6 R700 sixx's OPW parameters (Brandstötter, Angerer
/// & Hofbaur 2014: a₁ = 0.025, a₂ = −0.035, c₁ = 0.4, c₂ = 0.315, c₃ = 0.365, c₄ = 0.08). The
/// zero pose and signs are the DH table's, not KUKA's.
fn kuka_like() -> Model {
    let mut rows = [
        row(0.025, -FRAC_PI_2, 0.4, FULL),
        row(0.315, 0.0, 0.0, FULL),
        row(0.035, -FRAC_PI_2, 0.0, FULL),
        row(0.0, FRAC_PI_2, 0.365, FULL),
        row(0.0, -FRAC_PI_2, 0.0, FULL),
        row(0.0, 0.0, 0.08, FULL),
    ];
    rows[1].theta = -FRAC_PI_2;
    dh_model("kuka_like", &rows, false)
}

/// An ABB IRB 120 as a standard-DH table from the dimensions of its product specification
/// (0.29, 0.27, 0.07, 0.302 and 0.072 m); axes 1 and 2 meet, so the wrist centre can reach
/// axis 1.
fn irb120() -> Model {
    let mut rows = [
        row(0.0, -FRAC_PI_2, 0.29, FULL),
        row(0.27, 0.0, 0.0, FULL),
        row(0.07, -FRAC_PI_2, 0.0, FULL),
        row(0.0, FRAC_PI_2, 0.302, FULL),
        row(0.0, -FRAC_PI_2, 0.0, FULL),
        row(0.0, 0.0, 0.072, FULL),
    ];
    rows[1].theta = -FRAC_PI_2;
    dh_model("irb120", &rows, false)
}

/// A spherical wrist whose first two axes meet while axes 2 and 3 are skew (60°).
fn skew_elbow() -> Model {
    dh_model(
        "skew_elbow",
        &[
            row(0.0, FRAC_PI_2, 0.3, FULL),
            row(0.4, PI / 3.0, 0.0, FULL),
            row(0.05, -FRAC_PI_2, 0.1, FULL),
            row(0.0, FRAC_PI_2, 0.4, FULL),
            row(0.0, -FRAC_PI_2, 0.0, FULL),
            row(0.0, 0.0, 0.1, FULL),
        ],
        false,
    )
}

/// The UR5's standard-DH table (models/ur5.toml), `π/2` given as `alpha`, with another joint
/// on a branch of its own first when `extra_first`.
fn ur5_dh(alpha: f64, extra_first: bool) -> Model {
    let l = (-2.0 * PI, 2.0 * PI);
    dh_model(
        "ur5",
        &[
            row(0.0, alpha, 0.089159, l),
            row(-0.425, 0.0, 0.0, l),
            row(-0.39225, 0.0, 0.0, l),
            row(0.0, alpha, 0.10915, l),
            row(0.0, -alpha, 0.09465, l),
            row(0.0, 0.0, 0.0823, l),
        ],
        extra_first,
    )
}

/// Three parallel axes read from the tip: axes 1 and 2 meet, 3 ∥ 4 ∥ 5.
fn reversed_parallel() -> Model {
    dh_model(
        "reversed_parallel",
        &[
            row(0.0, FRAC_PI_2, 0.1, FULL),
            row(0.0, -FRAC_PI_2, 0.12, FULL),
            row(0.4, 0.0, 0.0, FULL),
            row(0.35, 0.0, 0.0, FULL),
            row(0.0, FRAC_PI_2, 0.1, FULL),
            row(0.0, 0.0, 0.08, FULL),
        ],
        false,
    )
}

/// A spherical wrist read from the tip: the first three axes meet, the last three place the
/// tool like an elbow arm.
fn spherical_shoulder() -> Model {
    dh_model(
        "spherical_shoulder",
        &[
            row(0.0, FRAC_PI_2, 0.3, FULL),
            row(0.0, -FRAC_PI_2, 0.0, FULL),
            row(0.1, FRAC_PI_2, 0.4, FULL),
            row(0.35, 0.0, 0.0, FULL),
            row(0.3, FRAC_PI_2, 0.05, FULL),
            row(0.0, 0.0, 0.1, FULL),
        ],
        false,
    )
}

fn tool(model: &Model) -> usize {
    model
        .frame_id("tool")
        .or_else(|_| model.frame_id("tool0"))
        .unwrap()
}

/// The pose of `frame` at `q`, by the library's forward-kinematics recursion.
fn pose(model: &Model, frame: usize, q: &[f64]) -> Se3 {
    let mut ws = Workspace::new(model);
    forward_kinematics(model, &mut ws, q).unwrap();
    frame_pose(model, &ws, frame).unwrap()
}

fn random_q(model: &Model, rng: &mut StdRng) -> Vec<f64> {
    model
        .joints()
        .iter()
        .map(|j| rng.gen_range(j.limits.lower.max(-2.0 * PI)..j.limits.upper.min(2.0 * PI)))
        .collect()
}

/// The full joint vector of a solution, other joints as in `q`.
fn full_q(ik: &ClosedForm, theta: &[f64; 6], q: &[f64]) -> Vec<f64> {
    let mut full = q.to_vec();
    for (k, &j) in ik.joints().iter().enumerate() {
        full[j] = theta[k];
    }
    full
}

fn same_angle(a: f64, b: f64, tol: f64) -> bool {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d) <= tol
}

/// The largest entry of `T(θ) − T_d` over the solutions (4×4 matrices).
fn check_solutions(
    model: &Model,
    ik: &ClosedForm,
    q: &[f64],
    solutions: &[[f64; 6]],
    tol: f64,
) -> f64 {
    let frame = tool(model);
    let target = pose(model, frame, q);
    let mut worst = 0.0_f64;
    for theta in solutions {
        assert!(theta.iter().all(|t| t.is_finite() && t.abs() <= PI));
        let reached = pose(model, frame, &full_q(ik, theta, q));
        let err = (reached.to_matrix() - target.to_matrix()).amax();
        assert!(
            err < tol,
            "{}: solution {theta:?} misses by {err:e}",
            model.name()
        );
        worst = worst.max(err);
    }
    worst
}

/// Whether some solution equals `q`'s arm joints (mod 2π) within `tol`.
fn contains(ik: &ClosedForm, solutions: &[[f64; 6]], q: &[f64], tol: f64) -> bool {
    solutions.iter().any(|theta| {
        ik.joints()
            .iter()
            .enumerate()
            .all(|(k, &j)| same_angle(theta[k], q[j], tol))
    })
}

/// Random configurations within the limits: every solution reproduces the pose to 1e-10, the
/// configuration is among them; returns how many poses had all eight solutions.
fn round_trips(model: &Model, family: ClosedFormFamily, seed: u64, poses: usize) -> usize {
    let frame = tool(model);
    let ik = ClosedForm::detect(model, frame).unwrap().unwrap();
    assert_eq!(ik.family(), family, "{}", model.name());
    let mut rng = StdRng::seed_from_u64(seed);
    let mut out = [[0.0; 6]; 8];
    let mut eight = 0;
    for _ in 0..poses {
        let q = random_q(model, &mut rng);
        let count = ik.solve(&pose(model, frame, &q), &mut out);
        check_solutions(model, &ik, &q, &out[..count], 1e-10);
        assert!(
            contains(&ik, &out[..count], &q, 1e-7),
            "{}: q = {q:?} not among {:?}",
            model.name(),
            &out[..count]
        );
        // All distinct.
        for i in 0..count {
            for k in 0..i {
                assert!((0..6).any(|j| !same_angle(out[i][j], out[k][j], 1e-6)));
            }
        }
        eight += usize::from(count == 8);
    }
    eight
}

#[test]
fn ur5_every_solution_of_random_poses() {
    let ur5 = builtin::load("ur5").unwrap();
    let eight = round_trips(&ur5, ClosedFormFamily::ThreeParallel, 1, 1000);
    // Shoulder, wrist and elbow each two ways; for about a quarter of the poses some of the
    // eight branches fall out of reach (`no_solution_is_missed` checks that those poses have
    // no further solution).
    assert!(eight >= 500, "{eight} of 1000 poses had 8 solutions");
}

/// Newton's method on the body twist `V_b = log(T(q)⁻¹ T_d)` with the body Jacobian, from
/// `q`: the converged joint vector, or `None`.
fn newton(model: &Model, frame: usize, target: &Se3, mut q: Vec<f64>) -> Option<Vec<f64>> {
    let mut ws = Workspace::new(model);
    let mut j = Matrix6xX::zeros(model.nq());
    for _ in 0..60 {
        compute_joint_jacobians(model, &mut ws, &q).unwrap();
        let error = frame_pose(model, &ws, frame)
            .unwrap()
            .inverse()
            .compose(target)
            .log();
        if error.norm() < 1e-13 {
            return Some(q);
        }
        frame_jacobian(model, &ws, frame, Reference::Local, &mut j).unwrap();
        // Damped least squares: Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ V_b.
        let jjt = &j * j.transpose() + Matrix6::identity() * 1e-10;
        let step = j.transpose() * jjt.try_inverse()? * error;
        let scale = (0.5 / step.amax()).min(1.0);
        for (qi, s) in q.iter_mut().zip(step.iter()) {
            *qi += scale * s;
        }
    }
    None
}

#[test]
fn no_solution_is_missed() {
    // Many-start Newton iterations find solutions independently of the subproblems: every
    // one they converge to must be among the closed form's. Checked on the first poses with
    // fewer than eight solutions and on a few with eight.
    for (model, seed) in [(builtin::load("ur5").unwrap(), 10), (puma560(), 11)] {
        let frame = tool(&model);
        let ik = ClosedForm::detect(&model, frame).unwrap().unwrap();
        let mut rng = StdRng::seed_from_u64(seed);
        let mut out = [[0.0; 6]; 8];
        let (mut short, mut full) = (0, 0);
        for _ in 0..300 {
            let q = random_q(&model, &mut rng);
            let target = pose(&model, frame, &q);
            let count = ik.solve(&target, &mut out);
            let pick = if count < 8 { &mut short } else { &mut full };
            if *pick >= 5 {
                continue;
            }
            *pick += 1;
            // Which of the closed-form solutions Newton reached.
            let mut reached = [false; 8];
            for _ in 0..40 {
                let start: Vec<f64> = (0..6).map(|_| rng.gen_range(-PI..PI)).collect();
                if let Some(found) = newton(&model, frame, &target, start) {
                    let index = out[..count]
                        .iter()
                        .position(|theta| (0..6).all(|k| same_angle(theta[k], found[k], 1e-6)));
                    assert!(
                        index.is_some(),
                        "{}: Newton found {found:?}, not among the {count} closed-form solutions {:?}",
                        model.name(),
                        &out[..count]
                    );
                    reached[index.unwrap()] = true;
                }
            }
            assert!(reached.iter().any(|r| *r));
        }
        assert_eq!(full, 5);
    }
}

#[test]
fn ur5_urdf_and_extra_branch() {
    let urdf = load_model(&format!("{MODELS}ur5.urdf")).unwrap();
    round_trips(&urdf, ClosedFormFamily::ThreeParallel, 2, 200);
    // A joint on another branch is ignored: the arm's joints are 1…6 of q.
    let branched = ur5_dh(FRAC_PI_2, true);
    let ik = ClosedForm::detect(&branched, tool(&branched))
        .unwrap()
        .unwrap();
    assert_eq!(ik.joints(), [1, 2, 3, 4, 5, 6]);
    round_trips(&branched, ClosedFormFamily::ThreeParallel, 3, 200);
}

#[test]
fn puma560_every_solution_of_random_poses() {
    // Left or right shoulder, elbow up or down, wrist flipped or not: a Puma reaches every
    // pose inside its workspace, away from singularities, in 8 ways (Craig, *Introduction to
    // Robotics*, ch. 4).
    let eight = round_trips(&puma560(), ClosedFormFamily::SphericalWrist, 4, 1000);
    assert_eq!(eight, 1000);
}

#[test]
fn other_spherical_wrists() {
    round_trips(&kuka_like(), ClosedFormFamily::SphericalWrist, 5, 300);
    round_trips(&irb120(), ClosedFormFamily::SphericalWrist, 12, 300);
    round_trips(&skew_elbow(), ClosedFormFamily::SphericalWrist, 6, 300);
}

#[test]
fn geometries_read_from_the_tip() {
    round_trips(
        &reversed_parallel(),
        ClosedFormFamily::ThreeParallel,
        7,
        300,
    );
    round_trips(
        &spherical_shoulder(),
        ClosedFormFamily::SphericalWrist,
        8,
        300,
    );
}

#[test]
fn arms_without_a_closed_form() {
    let none = |m: &Model, frame: usize| ClosedForm::detect(m, frame).unwrap().is_none();
    let panda = builtin::load("panda").unwrap();
    assert!(none(&panda, panda.body_frame(6).unwrap()));
    let planar = builtin::planar2();
    assert!(none(&planar, planar.frame_id("link2").unwrap()));
    // Three of the UR5's joints.
    let ur5 = builtin::load("ur5").unwrap();
    assert!(none(&ur5, ur5.body_frame(2).unwrap()));
    // A frame on the base.
    let base = ur5.frames().iter().position(|f| f.body.is_none()).unwrap();
    assert!(none(&ur5, base));
    // The branched robot's arms have four joints.
    let branched = builtin::load("branched").unwrap();
    for f in 0..branched.frames().len() {
        assert!(none(&branched, f));
    }
    // A 6R arm with no parallel or meeting axes (a UR5 with axis 3 tilted).
    let mut rows = [
        row(0.0, FRAC_PI_2, 0.089159, FULL),
        row(-0.425, 0.3, 0.0, FULL),
        row(-0.39225, 0.0, 0.0, FULL),
        row(0.0, FRAC_PI_2, 0.10915, FULL),
        row(0.0, -FRAC_PI_2, 0.09465, FULL),
        row(0.0, 0.0, 0.0823, FULL),
    ];
    let tilted = dh_model("tilted", &rows, false);
    assert!(none(&tilted, tool(&tilted)));
    // A prismatic joint among the six.
    rows[1].alpha = 0.0;
    let mut text = String::from("format = \"dh\"\n");
    for (i, r) in rows.iter().enumerate() {
        let kind = if i == 2 { "P" } else { "R" };
        text += &format!(
            "[[row]]\ntype = \"{kind}\"\na = {:?}\nalpha = {:?}\nd = {:?}\nmass = 1.0\n",
            r.a, r.alpha, r.d
        );
    }
    let prismatic = load_str(&text, "p.toml", &LoadOptions::default()).unwrap();
    assert!(none(&prismatic, prismatic.body_frame(5).unwrap()));
    // An unknown frame is an error.
    let err = ClosedForm::detect(&ur5, 999).unwrap_err();
    assert!(err.to_string().contains("999"), "{err}");
}

#[test]
fn ur5_wrist_singularity() {
    // θ₅ = 0: axis 6 is parallel to axes 2, 3, 4, a continuum of solutions.
    let ur5 = builtin::load("ur5").unwrap();
    let frame = tool(&ur5);
    let ik = ClosedForm::detect(&ur5, frame).unwrap().unwrap();
    let mut out = [[0.0; 6]; 8];
    for q in [
        [0.3, -1.0, 1.2, 0.4, 0.0, 0.5],
        [-2.0, -0.5, -1.4, 2.0, 0.0, -1.0],
        [0.3, -1.0, 1.2, 0.4, PI, 0.5],
    ] {
        let count = ik.solve(&pose(&ur5, frame, &q), &mut out);
        assert!(count >= 2, "{count}");
        check_solutions(&ur5, &ik, &q, &out[..count], 1e-10);
        // The shoulder and the wrist angle of q are among them.
        assert!(out[..count]
            .iter()
            .any(|t| same_angle(t[0], q[0], 1e-7) && same_angle(t[4], q[4], 1e-7)));
    }
}

#[test]
fn ur5_stretched_elbow() {
    // θ₃ = 0: upper arm and forearm in line, the two elbow branches merge.
    let ur5 = builtin::load("ur5").unwrap();
    let frame = tool(&ur5);
    let ik = ClosedForm::detect(&ur5, frame).unwrap().unwrap();
    let mut out = [[0.0; 6]; 8];
    let q = [0.3, -1.0, 0.0, 0.4, 1.0, 0.5];
    let count = ik.solve(&pose(&ur5, frame, &q), &mut out);
    assert!(count >= 1);
    check_solutions(&ur5, &ik, &q, &out[..count], 1e-10);
    assert!(contains(&ik, &out[..count], &q, 1e-6));
}

#[test]
fn puma_singularities() {
    let puma = puma560();
    let frame = tool(&puma);
    let ik = ClosedForm::detect(&puma, frame).unwrap().unwrap();
    let mut out = [[0.0; 6]; 8];
    // Wrist: θ₅ = 0 puts axes 4 and 6 on one line; only θ₄ + θ₆ counts.
    let q = [0.3, 0.5, -0.8, 0.7, 0.0, 0.4];
    let count = ik.solve(&pose(&puma, frame, &q), &mut out);
    assert!(count >= 1);
    check_solutions(&puma, &ik, &q, &out[..count], 1e-10);
    assert!(out[..count]
        .iter()
        .any(|t| (0..3).all(|k| same_angle(t[k], q[k], 1e-7))
            && same_angle(t[4], 0.0, 1e-7)
            && same_angle(t[3] + t[5], q[3] + q[5], 1e-7)));
    // Elbow: the θ₃ that puts the wrist centre (the origin of link 4) farthest from the
    // shoulder (the world origin), found by golden-section search on forward kinematics.
    let reach = |t3: f64| {
        let mut ws = Workspace::new(&puma);
        forward_kinematics(&puma, &mut ws, &[0.0, 0.0, t3, 0.0, 0.0, 0.0]).unwrap();
        ws.pose_in_world[3].translation.norm()
    };
    let (mut lo, mut hi) = (-PI, 0.0);
    let ratio = (5.0_f64.sqrt() - 1.0) / 2.0;
    for _ in 0..200 {
        let (a, b) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
        if reach(a) > reach(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    let stretched = 0.5 * (lo + hi);
    assert!(
        reach(stretched) > reach(stretched + 0.01) && reach(stretched) > reach(stretched - 0.01)
    );
    let q = [0.3, 0.5, stretched, 0.7, 0.6, 0.4];
    let count = ik.solve(&pose(&puma, frame, &q), &mut out);
    assert!(count >= 1);
    check_solutions(&puma, &ik, &q, &out[..count], 1e-10);
    assert!(contains(&ik, &out[..count], &q, 1e-6));
}

#[test]
fn shoulder_singularity() {
    // The IRB 120's wrist centre (the origin of link 4) on axis 1 (the world z axis): θ₁ is
    // free, the solver takes θ₁ = 0 and the wrist takes up the turn.
    let irb = irb120();
    let frame = tool(&irb);
    let ik = ClosedForm::detect(&irb, frame).unwrap().unwrap();
    let wrist_x = |t2: f64| {
        let mut ws = Workspace::new(&irb);
        forward_kinematics(&irb, &mut ws, &[0.0, t2, 0.3, 0.0, 0.0, 0.0]).unwrap();
        ws.pose_in_world[3].translation.x
    };
    // Bisection for wrist_x(θ₂) = 0 on a bracket found by scanning.
    let grid: Vec<f64> = (0..=64).map(|k| -PI + 2.0 * PI * k as f64 / 64.0).collect();
    let k = (0..64)
        .find(|&k| wrist_x(grid[k]) * wrist_x(grid[k + 1]) < 0.0)
        .unwrap();
    let (mut lo, mut hi) = (grid[k], grid[k + 1]);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if wrist_x(lo) * wrist_x(mid) <= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let q = [0.4, 0.5 * (lo + hi), 0.3, 0.7, 0.6, -0.5];
    let mut out = [[0.0; 6]; 8];
    let count = ik.solve(&pose(&irb, frame, &q), &mut out);
    assert!(count >= 1);
    check_solutions(&irb, &ik, &q, &out[..count], 1e-10);
    assert!(out[..count]
        .iter()
        .any(|t| t[0] == 0.0 && same_angle(t[1], q[1], 1e-7) && same_angle(t[2], q[2], 1e-7)));
}

#[test]
fn unreachable_and_non_finite_targets_have_no_solution() {
    let mut out = [[0.0; 6]; 8];
    for model in [builtin::load("ur5").unwrap(), puma560(), kuka_like()] {
        let frame = tool(&model);
        let ik = ClosedForm::detect(&model, frame).unwrap().unwrap();
        let far = pose(&model, frame, &[0.0; 6]).with_translation([3.0, 0.5, 0.2].into());
        assert_eq!(ik.solve(&far, &mut out), 0, "{}", model.name());
        let mut nan = pose(&model, frame, &[0.1; 6]);
        nan.translation.x = f64::NAN;
        assert_eq!(ik.solve(&nan, &mut out), 0);
        nan.translation.x = 0.1;
        nan.rotation[(0, 0)] = f64::INFINITY;
        assert_eq!(ik.solve(&nan, &mut out), 0);
    }
}

#[test]
fn near_ideal_geometry_gives_near_solutions() {
    // π/2 rounded to ten digits, as URDF files write it: the axes are 1.8e-9 rad off parallel.
    let ur5 = ur5_dh(1.570796325, false);
    let frame = tool(&ur5);
    let ik = ClosedForm::detect(&ur5, frame).unwrap().unwrap();
    assert_eq!(ik.family(), ClosedFormFamily::ThreeParallel);
    let mut rng = StdRng::seed_from_u64(9);
    let mut out = [[0.0; 6]; 8];
    for _ in 0..200 {
        let q = random_q(&ur5, &mut rng);
        let count = ik.solve(&pose(&ur5, frame, &q), &mut out);
        assert!(count >= 1);
        // The error is of the order of the defect times the arm's size.
        check_solutions(&ur5, &ik, &q, &out[..count], 1e-7);
        assert!(contains(&ik, &out[..count], &q, 1e-6));
    }
}

#[test]
fn solve_allocates_nothing() {
    for model in [
        builtin::load("ur5").unwrap(),
        puma560(),
        reversed_parallel(),
    ] {
        let frame = tool(&model);
        let ik = ClosedForm::detect(&model, frame).unwrap().unwrap();
        let targets: Vec<Se3> = (0..20)
            .map(|i| pose(&model, frame, &[0.1 * i as f64 - 0.7; 6]))
            .collect();
        let mut out = [[0.0; 6]; 8];
        let mut found = 0;
        let allocs = counting::allocations(|| {
            for target in &targets {
                found += ik.solve(target, &mut out);
            }
        });
        assert!(found > 0);
        assert_eq!(allocs, 0, "{}", model.name());
    }
}
