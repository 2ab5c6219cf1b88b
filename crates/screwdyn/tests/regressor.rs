//! The joint-torque regressor (issue 15): `Y(q, q̇, q̈) π = RNEA(q, q̇, q̈)` to 1e-12 on every
//! shipped model (the built-in robots and the files in `models/`) and on random trees with
//! revolute, prismatic and helical joints; the parameter map round-trips.

mod common;

use common::{random_tree, random_vec};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use screwdyn::dynamics::{
    body_parameters, inertia_from_parameters, model_parameters, regressor, rnea,
};
use screwdyn::{Model, Workspace};

fn shipped_models() -> Vec<(String, Model)> {
    let mut out = Vec::new();
    for name in ["planar2", "pendulum", "ur5", "panda", "branched"] {
        let path = format!("builtin:{name}");
        out.push((path.clone(), screwdyn::io::load_model(&path).unwrap()));
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../models");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml" || x == "urdf"))
        .collect();
    files.sort();
    assert!(files.len() >= 5, "models/ has the shipped robot files");
    for f in files {
        let p = f.to_string_lossy().to_string();
        out.push((p.clone(), screwdyn::io::load_model(&p).unwrap()));
    }
    out
}

fn check(label: &str, m: &Model, rng: &mut StdRng) {
    let n = m.nv();
    let pi = model_parameters(m);
    assert_eq!(pi.len(), 10 * n);
    let mut ws = Workspace::new(m);
    for _ in 0..5 {
        let (q, v, a) = (
            random_vec(rng, n, 3.0),
            random_vec(rng, n, 3.0),
            random_vec(rng, n, 3.0),
        );
        let tau = rnea(m, &mut ws, &q, &v, &a).unwrap().clone();
        let y = regressor(m, &mut ws, &q, &v, &a).unwrap();
        assert_eq!(y.shape(), (n, 10 * n));
        let t = y * &pi;
        for i in 0..n {
            let err = (t[i] - tau[i]).abs();
            assert!(
                err <= 1e-12 * tau[i].abs().max(1.0),
                "{label}: joint {i}: Yπ = {} vs RNEA {} ({err:e})",
                t[i],
                tau[i]
            );
        }
    }
}

#[test]
fn regressor_times_parameters_is_inverse_dynamics_on_shipped_models() {
    let mut rng = StdRng::seed_from_u64(7);
    let models = shipped_models();
    for (label, m) in &models {
        check(label, m, &mut rng);
    }
}

#[test]
fn regressor_times_parameters_is_inverse_dynamics_on_random_trees() {
    let mut rng = StdRng::seed_from_u64(8);
    for t in 0..12 {
        let n = rng.gen_range(1..9);
        let m = random_tree(&mut rng, n, t % 3 != 0);
        check(&format!("tree {t}"), &m, &mut rng);
    }
}

#[test]
fn parameters_round_trip_and_bad_input_is_an_error() {
    let m = screwdyn::builtin::load("panda").unwrap();
    for b in m.bodies() {
        let back = inertia_from_parameters(&body_parameters(&b.inertia));
        assert!((back.matrix() - b.inertia.matrix()).amax() < 1e-12);
    }
    let mut ws = Workspace::new(&m);
    let z = vec![0.0; m.nv()];
    let e = regressor(&m, &mut ws, &z, &z[1..], &z).unwrap_err();
    assert!(e.to_string().starts_with("v has 6 values"), "{e}");
}
