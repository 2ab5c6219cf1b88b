//! The batch kernels (`screwdyn::batch`, eight states side by side): against Pinocchio's values,
//! against the per-call algorithms on random trees with every kind of joint, the same bits
//! whatever the grouping, and errors that name the state. (No allocation per call:
//! `zero_alloc.rs`.)

mod common;
#[path = "common/pinocchio.rs"]
mod pinocchio;

use common::{assert_close, random_tree, random_vec};
use pinocchio::{dmatrix, load_fixture, rel, ROBOTS};
use rand::rngs::StdRng;
use rand::SeedableRng;
use screwdyn::batch::{self, BatchWorkspace, Rows};
use screwdyn::{builtin, dynamics, Error, Model, Workspace};

/// The batch results of the five functions for stacked `q`, `v`, `a` (ABA takes `a` as τ).
struct Results {
    tau: Vec<f64>,
    gravity: Vec<f64>,
    nle: Vec<f64>,
    mass: Vec<f64>,
    qdd: Vec<f64>,
}

fn all(m: &Model, q: &[f64], v: &[f64], a: &[f64]) -> Results {
    all_with(m, BatchWorkspace::new(m), q, v, a)
}

fn all_with(m: &Model, mut ws: BatchWorkspace, q: &[f64], v: &[f64], a: &[f64]) -> Results {
    let nq = m.nq();
    let states = q.len() / nq;
    let (q, v, a) = (Rows::Stacked(q), Rows::Stacked(v), Rows::Stacked(a));
    let mut r = Results {
        tau: vec![0.0; states * nq],
        gravity: vec![0.0; states * nq],
        nle: vec![0.0; states * nq],
        mass: vec![0.0; states * nq * nq],
        qdd: vec![0.0; states * nq],
    };
    batch::rnea(m, &mut ws, q, v, a, &mut r.tau).unwrap();
    batch::gravity_torque(m, &mut ws, q, &mut r.gravity).unwrap();
    batch::nonlinear_effects(m, &mut ws, q, v, &mut r.nle).unwrap();
    batch::crba(m, &mut ws, q, &mut r.mass).unwrap();
    batch::aba(m, &mut ws, q, v, a, &mut r.qdd).unwrap();
    r
}

#[test]
fn batches_match_pinocchio() {
    // 20 states: two groups of eight and four states alone.
    for robot in ROBOTS {
        let (m, fx) = load_fixture(robot);
        let nq = m.nq();
        let cat = |f: &dyn Fn(&pinocchio::State) -> Vec<f64>| -> Vec<f64> {
            fx.states.iter().flat_map(f).collect()
        };
        let q = cat(&|s| s.q.clone());
        let v = cat(&|s| s.v.clone());
        let a = cat(&|s| s.a.clone());
        let r = all(&m, &q, &v, &a);
        // ABA of Pinocchio's τ_in, against its q̈.
        let tau_ref = cat(&|s| s.tau_in.clone());
        let mut qdd = vec![0.0; q.len()];
        let mut ws = BatchWorkspace::new(&m);
        let rows = (
            Rows::Stacked(&q),
            Rows::Stacked(&v),
            Rows::Stacked(&tau_ref),
        );
        batch::aba(&m, &mut ws, rows.0, rows.1, rows.2, &mut qdd).unwrap();
        for (k, s) in fx.states.iter().enumerate() {
            let row = k * nq..(k + 1) * nq;
            let tol = 1e-9;
            assert!(rel(&r.tau[row.clone()], &s.tau) < tol, "{robot} {k}: τ");
            assert!(
                rel(&r.gravity[row.clone()], &s.gravity) < tol,
                "{robot} {k}: g"
            );
            assert!(
                rel(&r.nle[row.clone()], &s.nonlinear_effects) < tol,
                "{robot} {k}: h"
            );
            assert!(rel(&qdd[row.clone()], &s.qdd) < tol, "{robot} {k}: q̈");
            let want = dmatrix(&s.mass_matrix);
            let got = &r.mass[k * nq * nq..(k + 1) * nq * nq];
            // Row-major out, column-major nalgebra: M is symmetric, so both read alike.
            assert!(rel(got, want.as_slice()) < tol, "{robot} {k}: M");
        }
    }
}

#[test]
fn batches_agree_with_the_per_call_algorithms_on_every_kind_of_joint() {
    let mut rng = StdRng::seed_from_u64(11);
    let mut models: Vec<Model> = ["planar2", "pendulum", "ur5", "panda", "branched"]
        .iter()
        .map(|n| builtin::load(n).unwrap())
        .collect();
    // Random trees: revolute, prismatic and helical joints about tilted axes (the general
    // screw path of the kernels), branching.
    for n in [1, 3, 7, 12] {
        models.push(random_tree(&mut rng, n, true));
    }
    for m in &models {
        let nq = m.nq();
        let states = 19;
        let q = random_vec(&mut rng, states * nq, 4.0);
        let v = random_vec(&mut rng, states * nq, 2.0);
        let a = random_vec(&mut rng, states * nq, 2.0);
        let r = all(m, &q, &v, &a);
        let mut ws = Workspace::new(m);
        for k in 0..states {
            let row = k * nq..(k + 1) * nq;
            let (qk, vk, ak) = (&q[row.clone()], &v[row.clone()], &a[row.clone()]);
            let what = format!("{} state {k}", m.name());
            let tol = 1e-11;
            let tau = dynamics::rnea(m, &mut ws, qk, vk, ak).unwrap().clone();
            assert_close(
                &r.tau[row.clone()],
                tau.as_slice(),
                tol,
                &format!("{what}: τ"),
            );
            let g = dynamics::gravity_torque(m, &mut ws, qk).unwrap().clone();
            assert_close(
                &r.gravity[row.clone()],
                g.as_slice(),
                tol,
                &format!("{what}: g"),
            );
            let h = dynamics::nonlinear_effects(m, &mut ws, qk, vk)
                .unwrap()
                .clone();
            assert_close(
                &r.nle[row.clone()],
                h.as_slice(),
                tol,
                &format!("{what}: h"),
            );
            let mm = dynamics::crba(m, &mut ws, qk).unwrap().transpose();
            let got = &r.mass[k * nq * nq..(k + 1) * nq * nq];
            assert_close(got, mm.as_slice(), tol, &format!("{what}: M"));
            let qdd = dynamics::aba(m, &mut ws, qk, vk, ak).unwrap().clone();
            assert_close(
                &r.qdd[row.clone()],
                qdd.as_slice(),
                1e-9,
                &format!("{what}: q̈"),
            );
        }
    }
}

/// Without FMA instructions the batch runs state by state through the per-call functions:
/// their results to the bit, errors included.
#[test]
fn state_by_state_gives_the_per_call_bits() {
    let mut rng = StdRng::seed_from_u64(5);
    let mut models: Vec<Model> = ["ur5", "branched"]
        .iter()
        .map(|n| builtin::load(n).unwrap())
        .collect();
    models.push(random_tree(&mut rng, 5, true));
    for m in &models {
        let (nq, states) = (m.nq(), 11);
        let q = random_vec(&mut rng, states * nq, 4.0);
        let v = random_vec(&mut rng, states * nq, 2.0);
        let a = random_vec(&mut rng, states * nq, 2.0);
        let r = all_with(m, BatchWorkspace::state_by_state(m), &q, &v, &a);
        let mut ws = Workspace::new(m);
        let zeros = vec![0.0; nq];
        for k in 0..states {
            let row = k * nq..(k + 1) * nq;
            let (qk, vk, ak) = (&q[row.clone()], &v[row.clone()], &a[row.clone()]);
            let tau = dynamics::rnea(m, &mut ws, qk, vk, ak).unwrap().clone();
            assert_eq!(r.tau[row.clone()], tau.as_slice()[..]);
            let g = dynamics::rnea(m, &mut ws, qk, &zeros, &zeros)
                .unwrap()
                .clone();
            assert_eq!(r.gravity[row.clone()], g.as_slice()[..]);
            let h = dynamics::rnea(m, &mut ws, qk, vk, &zeros).unwrap().clone();
            assert_eq!(r.nle[row.clone()], h.as_slice()[..]);
            let mm = dynamics::crba(m, &mut ws, qk).unwrap().transpose();
            assert_eq!(r.mass[k * nq * nq..(k + 1) * nq * nq], mm.as_slice()[..]);
            let qdd = dynamics::aba(m, &mut ws, qk, vk, ak).unwrap().clone();
            assert_eq!(r.qdd[row], qdd.as_slice()[..]);
        }
        let mut bad = q.clone();
        bad[3 * nq + 1] = f64::NAN;
        let mut out = vec![0.0; states * nq];
        let e = batch::rnea(
            m,
            &mut BatchWorkspace::state_by_state(m),
            Rows::Stacked(&bad),
            Rows::Stacked(&v),
            Rows::Stacked(&a),
            &mut out,
        )
        .unwrap_err();
        assert_eq!(e.state(), Some(3), "{e}");
        assert!(e.to_string().contains("q"), "{e}");
    }
}

#[test]
fn a_state_gives_the_same_bits_in_a_group_alone_or_anywhere_in_a_batch() {
    let mut rng = StdRng::seed_from_u64(5);
    for m in [
        builtin::load("ur5").unwrap(),
        random_tree(&mut rng, 6, true),
    ] {
        let nq = m.nq();
        let states = 21; // two groups of eight, five alone
        let q = random_vec(&mut rng, states * nq, 3.0);
        let v = random_vec(&mut rng, states * nq, 1.0);
        let a = random_vec(&mut rng, states * nq, 1.0);
        let whole = all(&m, &q, &v, &a);
        // The same states shifted by three: each now sits in another lane, group or the tail.
        let shift = |x: &[f64]| [&x[3 * nq..], &x[..3 * nq]].concat();
        let moved = all(&m, &shift(&q), &shift(&v), &shift(&a));
        let bits = |x: &[f64]| x.iter().map(|y| y.to_bits()).collect::<Vec<_>>();
        for (w, s, width) in [
            (&whole.tau, &moved.tau, nq),
            (&whole.gravity, &moved.gravity, nq),
            (&whole.nle, &moved.nle, nq),
            (&whole.mass, &moved.mass, nq * nq),
            (&whole.qdd, &moved.qdd, nq),
        ] {
            assert_eq!(bits(&shift_rows(w, width)), bits(s));
        }
        // One state alone.
        for k in [0, 9, 20] {
            let row = k * nq..(k + 1) * nq;
            let one = all(&m, &q[row.clone()], &v[row.clone()], &a[row.clone()]);
            assert_eq!(bits(&one.tau), bits(&whole.tau[row.clone()]));
            assert_eq!(bits(&one.qdd), bits(&whole.qdd[row.clone()]));
            assert_eq!(
                bits(&one.mass),
                bits(&whole.mass[k * nq * nq..(k + 1) * nq * nq])
            );
        }
        // g(q) and C(q, q̇) q̇ + g(q) are RNEA with zeros, to the bit.
        let mut ws = BatchWorkspace::new(&m);
        let zero = vec![0.0; q.len()];
        let mut tau = vec![0.0; q.len()];
        let (qr, z) = (Rows::Stacked(&q), Rows::Same(&zero[..nq]));
        batch::rnea(&m, &mut ws, qr, z, z, &mut tau).unwrap();
        assert_eq!(bits(&tau), bits(&whole.gravity));
        batch::rnea(
            &m,
            &mut ws,
            qr,
            Rows::Stacked(&v),
            Rows::Stacked(&zero),
            &mut tau,
        )
        .unwrap();
        assert_eq!(bits(&tau), bits(&whole.nle));
    }
}

/// The rows of `x` (each `width` long) rotated as `shift` in the test above rotates states.
fn shift_rows(x: &[f64], width: usize) -> Vec<f64> {
    [&x[3 * width..], &x[..3 * width]].concat()
}

#[test]
fn errors_name_the_state_and_say_what_is_wrong() {
    let m = builtin::load("ur5").unwrap();
    let mut ws = BatchWorkspace::new(&m);
    let mut q = vec![0.1; 12 * 6];
    q[10 * 6 + 4] = f64::INFINITY; // state 10 (the tail) …
    let mut out = vec![0.0; 12 * 36];
    let e = batch::gravity_torque(&m, &mut ws, Rows::Stacked(&q), &mut out[..72]).unwrap_err();
    assert_eq!(e.state(), Some(10));
    assert_eq!(
        e.to_string(),
        "state 10: q contains a non-finite value (inf) at position 4"
    );
    q[3 * 6] = f64::NAN; // … and state 3, in the first group, comes first.
    let e = batch::gravity_torque(&m, &mut ws, Rows::Stacked(&q), &mut out[..72]).unwrap_err();
    assert_eq!(e.state(), Some(3));
    // Wrong lengths: a shared vector, stacked rows, the output.
    let q = vec![0.0; 12];
    let e = batch::rnea(
        &m,
        &mut ws,
        Rows::Stacked(&q),
        Rows::Same(&[0.0; 5]),
        Rows::Same(&[0.0; 6]),
        &mut out[..12],
    )
    .unwrap_err();
    assert_eq!(e.state(), None);
    assert!(matches!(e, Error::DimensionMismatch { got: 5, .. }), "{e}");
    let e = batch::crba(&m, &mut ws, Rows::Stacked(&q), &mut out[..36 * 3]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "q holds 12 values, expected 3 states of 6 joints (18)"
    );
    let e = batch::crba(&m, &mut ws, Rows::Stacked(&q), &mut out[..40]).unwrap_err();
    assert!(
        e.to_string()
            .contains("not a whole number of results of 36"),
        "{e}"
    );
    // A workspace made for another model, even one with as many joints.
    let mut rng = StdRng::seed_from_u64(1);
    let other = random_tree(&mut rng, 6, false);
    let e = batch::crba(&other, &mut ws, Rows::Stacked(&q), &mut out[..72]).unwrap_err();
    assert!(e.to_string().contains("made for another model"), "{e}");
    // No states at all is fine.
    batch::rnea(
        &m,
        &mut ws,
        Rows::Stacked(&[]),
        Rows::Same(&[0.0; 6]),
        Rows::Same(&[0.0; 6]),
        &mut [],
    )
    .unwrap();
}

#[test]
fn a_singular_mass_matrix_names_the_state_and_the_joint_as_the_per_call_aba_does() {
    let m = common::massless_tip();
    let mut ws = BatchWorkspace::new(&m);
    for states in [1, 8, 11] {
        let q: Vec<f64> = (0..2 * states).map(|k| 0.1 * k as f64).collect();
        let mut out = vec![0.0; 2 * states];
        let e = batch::aba(
            &m,
            &mut ws,
            Rows::Stacked(&q),
            Rows::Same(&[0.0; 2]),
            Rows::Same(&[1.0; 2]),
            &mut out,
        )
        .unwrap_err();
        let per_call =
            dynamics::aba(&m, &mut Workspace::new(&m), &q[..2], &[0.0; 2], &[1.0; 2]).unwrap_err();
        assert_eq!(e.state(), Some(0));
        assert_eq!(e.clone().without_state(), per_call);
        assert!(
            e.to_string()
                .starts_with("state 0: forward dynamics failed"),
            "{e}"
        );
    }
}
