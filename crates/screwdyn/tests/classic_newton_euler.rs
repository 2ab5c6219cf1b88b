//! The classic vector Newton–Euler table (seeds 003/004) against the Lie-group RNEA.

mod common;

use common::{assert_close, random_tree, random_vec};
use rand::{rngs::StdRng, SeedableRng};
use screwdyn::dynamics::{classic_newton_euler, rnea};
use screwdyn::{builtin, Model, Workspace};

fn check(model: &Model, rng: &mut StdRng) {
    let n = model.nq();
    let (q, v, a) = (
        random_vec(rng, n, 3.0),
        random_vec(rng, n, 2.0),
        random_vec(rng, n, 2.0),
    );
    let table = classic_newton_euler(model, &q, &v, &a).unwrap();
    let mut ws = Workspace::new(model);
    let tau: Vec<f64> = rnea(model, &mut ws, &q, &v, &a)
        .unwrap()
        .iter()
        .copied()
        .collect();
    let classic: Vec<f64> = table.iter().map(|l| l.tau).collect();
    assert_close(&classic, &tau, 1e-12, "τ classic vs RNEA");
    for (i, link) in table.iter().enumerate() {
        // The RNEA runs in {0}: its twist, acceleration and wrench moved to body i's frame.
        let h = &ws.pose_in_world[i];
        let (tw, twd, w) = (
            h.inv_act_twist(&ws.twist_in_world[i]),
            h.inv_act_twist(&ws.twist_dot_in_world[i]),
            h.act_transpose_wrench(&ws.wrench_in_world[i]),
        );
        let omega = tw.fixed_rows::<3>(0).into_owned();
        let vel = tw.fixed_rows::<3>(3).into_owned();
        // ω, ω̇ and v agree; the classical v̇ is the twist derivative's linear part + ω × v.
        assert_close(link.omega.as_slice(), omega.as_slice(), 1e-12, "ω");
        assert_close(link.v.as_slice(), vel.as_slice(), 1e-12, "v");
        assert_close(
            link.omega_dot.as_slice(),
            twd.fixed_rows::<3>(0).into_owned().as_slice(),
            1e-12,
            "ω̇",
        );
        let classical = twd.fixed_rows::<3>(3).into_owned() + omega.cross(&vel);
        assert_close(
            link.v_dot.as_slice(),
            classical.as_slice(),
            1e-12,
            "v̇ = v̇_body + ω × v",
        );
        // (n, f) is the RNEA wrench W (moment about the frame origin).
        assert_close(
            link.n.as_slice(),
            w.fixed_rows::<3>(0).into_owned().as_slice(),
            1e-11,
            "n",
        );
        assert_close(
            link.f.as_slice(),
            w.fixed_rows::<3>(3).into_owned().as_slice(),
            1e-11,
            "f",
        );
    }
}

#[test]
fn classic_table_matches_the_lie_group_rnea() {
    let mut rng = StdRng::seed_from_u64(11);
    for name in ["planar2", "ur5", "panda", "branched"] {
        check(&builtin::load(name).unwrap(), &mut rng);
    }
    for _ in 0..4 {
        let m = random_tree(&mut rng, 5, true);
        check(&m, &mut rng);
    }
}

/// Seed 003's worked two-link example: ¹v̇_C1 = (−L1 θ̇1² + g s1, L1 θ̈1 + g c1, 0), ¹F1 = m1 ¹v̇_C1
/// and τ2 = m2 L1 L2 s2 θ̇1² + m2 L1 L2 c2 θ̈1 + m2 g L2 c12 + m2 L2² (θ̈1 + θ̈2). (Seed 003's
/// frames put gravity along +y₀ as the base acceleration, as builtin:planar2 does.)
#[test]
fn seed_003_two_link_rows() {
    let (l1, l2, m1, m2, g) = (0.7, 0.4, 1.5, 0.8, 9.81);
    let m = builtin::planar2_with(l1, l2, m1, m2);
    let (q1, q2, qd1, qd2, qdd1, qdd2) = (0.3_f64, -0.8_f64, 1.1, -0.6, 0.4, 0.9);
    let t = classic_newton_euler(&m, &[q1, q2], &[qd1, qd2], &[qdd1, qdd2]).unwrap();
    // Our link frames sit at the link ends (the CoMs): the seed's frame-1 acceleration of the
    // CoM rotated… the CoM of link 1 is the origin of frame 1, whose axes are the seed's frame-1
    // axes: ¹v̇_C1 is the same vector.
    let vc1 = [
        -l1 * qd1 * qd1 + g * q1.sin(),
        l1 * qdd1 + g * q1.cos(),
        0.0,
    ];
    assert_close(t[0].v_dot_com.as_slice(), &vc1, 1e-12, "¹v̇_C1");
    assert_close(t[0].force.as_slice(), &vc1.map(|x| m1 * x), 1e-12, "¹F1");
    let tau2 = m2 * l1 * l2 * q2.sin() * qd1 * qd1
        + m2 * l1 * l2 * q2.cos() * qdd1
        + m2 * g * l2 * (q1 + q2).cos()
        + m2 * l2 * l2 * (qdd1 + qdd2);
    assert!((t[1].tau - tau2).abs() < 1e-12);
}

#[test]
fn bad_vectors_are_errors() {
    let e = classic_newton_euler(&builtin::planar2(), &[0.0], &[0.0, 0.0], &[0.0, 0.0])
        .unwrap_err()
        .to_string();
    assert!(e.contains("q has 1 values"), "{e}");
}
