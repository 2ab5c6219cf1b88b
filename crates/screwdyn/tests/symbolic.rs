//! The symbolic engine against the seeds' closed forms (symbolic equality, seeds 000/003/004) and
//! against the numeric library at random states (planar2, UR5, Panda, branched, random trees).

mod common;

use common::{assert_close, random_tree, random_vec};
use nalgebra::{Matrix3, Matrix6xX, Vector3, Vector6};
use rand::{rngs::StdRng, SeedableRng};
use screwdyn::dynamics::{
    closed_form, coriolis_matrix, crba, gravity_torque, kinetic_energy, potential_energy, rnea,
};
use screwdyn::kinematics::{compute_joint_jacobians, frame_jacobian, frame_pose, Reference};
use screwdyn::model::{JointSpec, ModelBuilder};
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::symbolic::{
    derive, generate, Collect, CoriolisForm, Derivation, Options, Poly, Printer, Quantity, Style,
    Var,
};
use screwdyn::{builtin, Model, Workspace};

fn all() -> Options {
    Options {
        symbols: "all".into(),
        ..Options::default()
    }
}

/// A symbol of the derivation's parameter table as a polynomial.
fn sym(d: &Derivation, name: &str) -> Poly {
    let k = d
        .params
        .params
        .iter()
        .position(|p| p.name == name)
        .unwrap_or_else(|| panic!("no parameter {name}"));
    assert!(d.params.params[k].symbolic, "{name} is not a symbol");
    Poly::var(Var::Param(k as u16))
}
fn c(i: usize) -> Poly {
    Poly::var(Var::Cos(1 << (i - 1)))
}
fn s(i: usize) -> Poly {
    Poly::var(Var::Sin(1 << (i - 1)))
}
fn qd(i: usize) -> Poly {
    Poly::var(Var::Qd((i - 1) as u16))
}
fn qdd(i: usize) -> Poly {
    Poly::var(Var::Qdd((i - 1) as u16))
}
fn prod(f: &[&Poly]) -> Poly {
    f.iter().fold(Poly::constant(1.0), |p, x| p.mul(x))
}
/// cos(θ1 + θ2) and sin(θ1 + θ2) by the angle-sum formulas.
fn c12() -> Poly {
    c(1).mul(&c(2)).sub(&s(1).mul(&s(2)))
}
fn s12() -> Poly {
    s(1).mul(&c(2)).add(&c(1).mul(&s(2)))
}

fn entry(d: &Derivation, k: usize, r: usize, col: usize) -> &Poly {
    let m = &d.matrices[k];
    &m.entries[r * m.cols + col]
}

/// Seed 003 (and seed 000's MATLAB model): the two-link arm with point masses at the link ends.
#[test]
fn planar2_mass_matrix_is_seed_003_term_by_term() {
    let d = derive(&builtin::planar2(), Quantity::MassMatrix, &all()).unwrap();
    let (m1, m2, l1, l2) = (sym(&d, "m1"), sym(&d, "m2"), sym(&d, "L1"), sym(&d, "L2"));
    // M11 = (m1 + m2) L1² + m2 L2² + 2 m2 L1 L2 c2
    let m11 = prod(&[&m1.add(&m2), &l1, &l1])
        .add(&prod(&[&m2, &l2, &l2]))
        .add(&prod(&[&m2, &l1, &l2, &c(2)]).scale(2.0));
    // M12 = M21 = m2 L2² + m2 L1 L2 c2, M22 = m2 L2²
    let m12 = prod(&[&m2, &l2, &l2]).add(&prod(&[&m2, &l1, &l2, &c(2)]));
    let m22 = prod(&[&m2, &l2, &l2]);
    assert_eq!(entry(&d, 0, 0, 0), &m11);
    assert_eq!(entry(&d, 0, 0, 1), &m12);
    assert_eq!(entry(&d, 0, 1, 0), &m12);
    assert_eq!(entry(&d, 0, 1, 1), &m22);
    // Printed as the issue writes it (collected on the masses) and as seed 003 lays it out.
    assert_eq!(
        d.entry_text(0, 0, 0),
        "m1 L1² + m2 (L1² + 2 L1 L2 c₂ + L2²)"
    );
    let p = Printer::new(&d.params, Style::Text { abbrev: true }, Collect::Config);
    assert_eq!(p.poly(&m11), "(m1 + m2) L1² + 2 m2 L1 L2 c₂ + m2 L2²");
    assert_eq!(p.poly(&m12), "m2 L1 L2 c₂ + m2 L2²");
}

#[test]
fn planar2_velocity_and_gravity_terms_are_seed_003() {
    let d = derive(&builtin::planar2(), Quantity::Coriolis, &all()).unwrap();
    let (m2, l1, l2) = (sym(&d, "m2"), sym(&d, "L1"), sym(&d, "L2"));
    let k = prod(&[&m2, &l1, &l2, &s(2)]);
    // Seed 003: C q̇ = [−m2 L1 L2 s2 θ̇2² − 2 m2 L1 L2 s2 θ̇1 θ̇2, m2 L1 L2 s2 θ̇1²]
    let cv1 = prod(&[&k, &qd(2), &qd(2)])
        .neg()
        .sub(&prod(&[&k, &qd(1), &qd(2)]).scale(2.0));
    let cv2 = prod(&[&k, &qd(1), &qd(1)]);
    assert_eq!(entry(&d, 1, 0, 0), &cv1);
    assert_eq!(entry(&d, 1, 1, 0), &cv2);
    let p = Printer::new(&d.params, Style::Text { abbrev: true }, Collect::Config);
    assert_eq!(p.poly(&cv1), "−2 m2 L1 L2 s₂ θ̇₁ θ̇₂ − m2 L1 L2 s₂ θ̇₂²");
    // Seed 004's Christoffel coefficients: D112 = D121 = −m2 l1 l2 s2, D122 = −m2 l1 l2 s2,
    // D211 = m2 l1 l2 s2, so C = [D112 θ̇2, D121 θ̇1 + D122 θ̇2; D211 θ̇1, 0].
    let o = Options {
        coriolis: CoriolisForm::Christoffel,
        ..all()
    };
    let dc = derive(&builtin::planar2(), Quantity::Coriolis, &o).unwrap();
    let kk = prod(&[&sym(&dc, "m2"), &sym(&dc, "L1"), &sym(&dc, "L2"), &s(2)]);
    assert_eq!(entry(&dc, 0, 0, 0), &kk.mul(&qd(2)).neg());
    assert_eq!(entry(&dc, 0, 0, 1), &kk.mul(&qd(1).add(&qd(2))).neg());
    assert_eq!(entry(&dc, 0, 1, 0), &kk.mul(&qd(1)));
    assert!(entry(&dc, 0, 1, 1).is_zero());
    assert_eq!(entry(&dc, 1, 0, 0), &cv1);

    let g = derive(&builtin::planar2(), Quantity::Gravity, &all()).unwrap();
    let (m1, m2, l1, l2, gg) = (
        sym(&g, "m1"),
        sym(&g, "m2"),
        sym(&g, "L1"),
        sym(&g, "L2"),
        sym(&g, "g"),
    );
    // Seed 003: G = [m2 g L2 c12 + (m1 + m2) g L1 c1, m2 g L2 c12]
    let g2 = prod(&[&m2, &gg, &l2, &c12()]);
    let g1 = g2.add(&prod(&[&m1.add(&m2), &gg, &l1, &c(1)]));
    assert_eq!(entry(&g, 0, 0, 0), &g1);
    assert_eq!(entry(&g, 0, 1, 0), &g2);
    assert_eq!(g.entry_text(0, 1, 0), "m2 g L2 c₁₂");
    let p = Printer::new(&g.params, Style::Text { abbrev: true }, Collect::Config);
    assert_eq!(p.poly(&g1), "(m1 + m2) g L1 c₁ + m2 g L2 c₁₂");
    let p = Printer::new(&g.params, Style::Text { abbrev: false }, Collect::Config);
    assert_eq!(p.poly(&g2), "m2 g L2 cos(θ1 + θ2)");
}

#[test]
fn planar2_torque_is_seed_003_tau() {
    let d = derive(&builtin::planar2(), Quantity::Torque, &all()).unwrap();
    let (m1, m2, l1, l2, g) = (
        sym(&d, "m1"),
        sym(&d, "m2"),
        sym(&d, "L1"),
        sym(&d, "L2"),
        sym(&d, "g"),
    );
    let a12 = qdd(1).add(&qdd(2));
    let k = prod(&[&m2, &l1, &l2]);
    // τ1 = m2 L2² (θ̈1 + θ̈2) + m2 L1 L2 c2 (2θ̈1 + θ̈2) + (m1 + m2) L1² θ̈1 − m2 L1 L2 s2 θ̇2²
    //      − 2 m2 L1 L2 s2 θ̇1 θ̇2 + m2 g L2 c12 + (m1 + m2) g L1 c1
    let tau1 = prod(&[&m2, &l2, &l2, &a12])
        .add(&prod(&[&k, &c(2), &qdd(1).scale(2.0).add(&qdd(2))]))
        .add(&prod(&[&m1.add(&m2), &l1, &l1, &qdd(1)]))
        .sub(&prod(&[&k, &s(2), &qd(2), &qd(2)]))
        .sub(&prod(&[&k, &s(2), &qd(1), &qd(2)]).scale(2.0))
        .add(&prod(&[&m2, &g, &l2, &c12()]))
        .add(&prod(&[&m1.add(&m2), &g, &l1, &c(1)]));
    // τ2 = m2 L1 L2 s2 θ̇1² + m2 L1 L2 c2 θ̈1 + m2 g L2 c12 + m2 L2² (θ̈1 + θ̈2)
    let tau2 = prod(&[&k, &s(2), &qd(1), &qd(1)])
        .add(&prod(&[&k, &c(2), &qdd(1)]))
        .add(&prod(&[&m2, &g, &l2, &c12()]))
        .add(&prod(&[&m2, &l2, &l2, &a12]));
    assert_eq!(entry(&d, 0, 0, 0), &tau1);
    assert_eq!(entry(&d, 0, 1, 0), &tau2);
}

#[test]
fn planar2_energies_are_seed_004() {
    let d = derive(&builtin::planar2(), Quantity::Energy, &all()).unwrap();
    let (m1, m2, l1, l2, g) = (
        sym(&d, "m1"),
        sym(&d, "m2"),
        sym(&d, "L1"),
        sym(&d, "L2"),
        sym(&d, "g"),
    );
    // K = ½(m1 + m2) l1² θ̇1² + ½ m2 l2² (θ̇1² + 2θ̇1θ̇2 + θ̇2²) + m2 l1 l2 c2 (θ̇1² + θ̇1θ̇2)
    let sq = qd(1).add(&qd(2));
    let k = prod(&[&m1.add(&m2), &l1, &l1, &qd(1), &qd(1)])
        .scale(0.5)
        .add(&prod(&[&m2, &l2, &l2, &sq, &sq]).scale(0.5))
        .add(&prod(&[
            &m2,
            &l1,
            &l2,
            &c(2),
            &qd(1).mul(&qd(1)).add(&qd(1).mul(&qd(2))),
        ]));
    // P = (m1 + m2) g l1 s1 + m2 g l2 s12
    let p = prod(&[&m1.add(&m2), &g, &l1, &s(1)]).add(&prod(&[&m2, &g, &l2, &s12()]));
    assert_eq!(entry(&d, 0, 0, 0), &k);
    assert_eq!(entry(&d, 1, 0, 0), &p);
}

/// Seed 003's tutorial question 2: the two-link arm with link inertias `diag(Ixx, Iyy, Izz)` about
/// each CoM (at the link ends): the planar motion adds `Izz1 + Izz2`, `Izz2`, `Izz2` to `M`.
#[test]
fn planar2_with_link_inertias() {
    let mut b = ModelBuilder::new("planar2");
    let z = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let inertia = |m: f64, i: [f64; 3]| {
        SpatialInertia::new(
            m,
            Vector3::zeros(),
            Matrix3::from_diagonal(&Vector3::from(i)),
        )
    };
    b.gravity(Vector3::new(0.0, -9.81, 0.0))
        .link(
            "link1",
            "base",
            JointSpec::revolute("joint1").screw_in_parent(z),
            Se3::from_translation(Vector3::new(0.7, 0.0, 0.0)),
            inertia(1.5, [0.01, 0.02, 0.03]),
        )
        .link(
            "link2",
            "link1",
            JointSpec::revolute("joint2").screw_in_parent(z),
            Se3::from_translation(Vector3::new(0.4, 0.0, 0.0)),
            inertia(0.8, [0.004, 0.005, 0.006]),
        );
    let model = b.build().unwrap();
    let d = derive(&model, Quantity::MassMatrix, &all()).unwrap();
    let (m1, m2, l1, l2) = (sym(&d, "m1"), sym(&d, "m2"), sym(&d, "L1"), sym(&d, "L2"));
    let (i1, i2) = (sym(&d, "Izz1"), sym(&d, "Izz2"));
    let m22 = prod(&[&m2, &l2, &l2]).add(&i2);
    let m12 = m22.add(&prod(&[&m2, &l1, &l2, &c(2)]));
    let m11 = prod(&[&m1.add(&m2), &l1, &l1])
        .add(&prod(&[&m2, &l2, &l2]))
        .add(&prod(&[&m2, &l1, &l2, &c(2)]).scale(2.0))
        .add(&i1)
        .add(&i2);
    assert_eq!(entry(&d, 0, 0, 0), &m11);
    assert_eq!(entry(&d, 0, 0, 1), &m12);
    assert_eq!(entry(&d, 0, 1, 1), &m22);
    check_numeric(&model, 3, true);
}

/// Seed 000's MATLAB example is the two-link arm above (H_0_1_home = (I, [L1; 0; 0]),
/// S = ẑ, point masses m1, m2): its `M_th` is seed 003's M (tested above) and its literal
/// `C_th` is the closed form computed by the library's stacked matrices.
#[test]
fn seed_000_literal_c_matches_the_stacked_closed_form() {
    let model = builtin::planar2_with(0.7, 0.4, 1.5, 0.8);
    let d = derive(&model, Quantity::Coriolis, &all()).unwrap();
    let mut rng = StdRng::seed_from_u64(0);
    for _ in 0..5 {
        let q = random_vec(&mut rng, 2, 3.0);
        let v = random_vec(&mut rng, 2, 2.0);
        let cf = closed_form(&model, &q, &v).unwrap();
        let c: Vec<f64> = cf.c.transpose().iter().copied().collect();
        assert_close(&d.eval(0, &q, &v, &[0.0; 2]), &c, 1e-12, "C_th");
    }
}

/// Compares every quantity (polynomial form when `poly`, and the expression graph always) with
/// the numeric library at random states.
fn check_numeric(model: &Model, states: usize, poly: bool) {
    let n = model.nq();
    let mut rng = StdRng::seed_from_u64(n as u64 + 17);
    let mut ws = Workspace::new(model);
    let tool = model.body_frame(n - 1).unwrap();
    let opts = Options {
        max_terms: 200_000,
        ..Options::default()
    };
    let christoffel = Options {
        coriolis: CoriolisForm::Christoffel,
        ..opts.clone()
    };
    let quantities = [
        (Quantity::MassMatrix, &opts),
        (Quantity::Coriolis, &opts),
        (Quantity::Coriolis, &christoffel),
        (Quantity::Gravity, &opts),
        (Quantity::Torque, &opts),
        (Quantity::Energy, &opts),
        (Quantity::Fk, &opts),
        (Quantity::Jacobian, &opts),
        (Quantity::Regressor, &opts),
    ];
    for (quantity, o) in quantities {
        let polys = if poly && (quantity != Quantity::Regressor || n <= 3) {
            Some(derive(model, quantity, o).unwrap())
        } else {
            None
        };
        let unit = generate(model, quantity, o).unwrap();
        for _ in 0..states {
            let q = random_vec(&mut rng, n, 3.0);
            let v = random_vec(&mut rng, n, 2.0);
            let a = random_vec(&mut rng, n, 2.0);
            let expect: Vec<f64> = match quantity {
                Quantity::MassMatrix => crba(model, &mut ws, &q).unwrap().iter().copied().collect(),
                Quantity::Coriolis => {
                    if o.coriolis == CoriolisForm::Seed {
                        let cf = closed_form(model, &q, &v).unwrap();
                        cf.c.transpose().iter().copied().collect()
                    } else {
                        let c = coriolis_matrix(model, &mut ws, &q, &v).unwrap();
                        c.transpose().iter().copied().collect()
                    }
                }
                Quantity::Gravity => gravity_torque(model, &mut ws, &q)
                    .unwrap()
                    .iter()
                    .copied()
                    .collect(),
                Quantity::Torque => rnea(model, &mut ws, &q, &v, &a)
                    .unwrap()
                    .iter()
                    .copied()
                    .collect(),
                Quantity::Energy => vec![
                    kinetic_energy(model, &mut ws, &q, &v).unwrap(),
                    potential_energy(model, &mut ws, &q).unwrap(),
                ],
                Quantity::Fk => {
                    screwdyn::kinematics::forward_kinematics(model, &mut ws, &q).unwrap();
                    let h = frame_pose(model, &ws, tool).unwrap().to_matrix();
                    h.transpose().iter().copied().collect()
                }
                Quantity::Jacobian => {
                    compute_joint_jacobians(model, &mut ws, &q).unwrap();
                    let mut j = Matrix6xX::zeros(n);
                    frame_jacobian(model, &ws, tool, Reference::Local, &mut j).unwrap();
                    j.transpose().iter().copied().collect()
                }
                Quantity::Regressor => {
                    // τ = Y π with π from the model's inertias (an independent RNEA run).
                    rnea(model, &mut ws, &q, &v, &a)
                        .unwrap()
                        .iter()
                        .copied()
                        .collect()
                }
            };
            let mut from_graph = unit.eval(&q, &v, &a, &unit.param_values());
            let mut from_poly = polys.as_ref().map(|d| {
                d.matrices
                    .iter()
                    .enumerate()
                    .flat_map(|(k, _)| d.eval(k, &q, &v, &a))
                    .collect::<Vec<f64>>()
            });
            if quantity == Quantity::Coriolis {
                from_poly = from_poly.map(|x| x[..n * n].to_vec());
            }
            if quantity == Quantity::Regressor {
                let pi = inertial_parameters(model);
                let y_pi = |y: &[f64]| -> Vec<f64> {
                    (0..n)
                        .map(|i| (0..10 * n).map(|k| y[i * 10 * n + k] * pi[k]).sum())
                        .collect()
                };
                // τ = Y π + I_a q̈: the armature is a known term outside the regressor.
                let with_armature = |t: Vec<f64>| -> Vec<f64> {
                    t.iter()
                        .zip(model.joints())
                        .zip(&a)
                        .map(|((t, j), a)| t + j.armature * a)
                        .collect()
                };
                from_graph = with_armature(y_pi(&from_graph));
                from_poly = from_poly.map(|y| with_armature(y_pi(&y)));
            }
            let what = format!("{} {:?} {:?}", model.name(), quantity, o.coriolis);
            assert_close(&from_graph, &expect, 1e-12, &format!("graph {what}"));
            if let Some(p) = from_poly {
                assert_close(&p, &expect, 1e-12, &format!("poly {what}"));
            }
        }
    }
}

/// `π` per body: `(m, m c, I_o)` about the body-frame origin.
fn inertial_parameters(model: &Model) -> Vec<f64> {
    model
        .bodies()
        .iter()
        .flat_map(|b| {
            let i = &b.inertia;
            let io = i.inertia_about_origin();
            let h = i.com * i.mass;
            [
                i.mass,
                h.x,
                h.y,
                h.z,
                io[(0, 0)],
                io[(0, 1)],
                io[(0, 2)],
                io[(1, 1)],
                io[(1, 2)],
                io[(2, 2)],
            ]
        })
        .collect()
}

#[test]
fn planar2_numeric() {
    check_numeric(&builtin::planar2_with(0.7, 0.4, 1.5, 0.8), 4, true);
}

#[test]
fn ur5_numeric() {
    check_numeric(&builtin::load("ur5").unwrap(), 3, true);
}

#[test]
fn panda_numeric() {
    // The expanded τ/C of the Panda are large: the graph form is checked for everything, the
    // polynomial form through M, g, energy, FK and Jacobian.
    let m = builtin::load("panda").unwrap();
    check_numeric(&m, 2, false);
    let mut rng = StdRng::seed_from_u64(3);
    let mut ws = Workspace::new(&m);
    for q in [Quantity::MassMatrix, Quantity::Gravity] {
        let d = derive(&m, q, &Options::default()).unwrap();
        let x = random_vec(&mut rng, 7, 3.0);
        let expect: Vec<f64> = match q {
            Quantity::MassMatrix => crba(&m, &mut ws, &x).unwrap().iter().copied().collect(),
            _ => gravity_torque(&m, &mut ws, &x)
                .unwrap()
                .iter()
                .copied()
                .collect(),
        };
        assert_close(
            &d.eval(0, &x, &[0.0; 7], &[0.0; 7]),
            &expect,
            1e-12,
            "panda poly",
        );
    }
}

#[test]
fn branched_numeric() {
    check_numeric(&builtin::load("branched").unwrap(), 3, true);
}

#[test]
fn random_trees_with_prismatic_and_helical_joints() {
    let mut rng = StdRng::seed_from_u64(42);
    for n in [3, 4] {
        let m = random_tree(&mut rng, n, true);
        check_numeric(&m, 2, true);
    }
}

#[test]
fn symbolic_lengths_and_inertias_evaluate_like_the_numbers() {
    // Every parameter a symbol: evaluating at the model's values reproduces the library.
    for name in ["ur5", "branched"] {
        let m = builtin::load(name).unwrap();
        let o = Options {
            symbols: "all".into(),
            max_terms: 400_000,
            ..Options::default()
        };
        let mut rng = StdRng::seed_from_u64(5);
        let mut ws = Workspace::new(&m);
        let n = m.nq();
        for q in [Quantity::MassMatrix, Quantity::Gravity, Quantity::Torque] {
            let unit = generate(&m, q, &o).unwrap();
            let x = random_vec(&mut rng, n, 3.0);
            let v = random_vec(&mut rng, n, 2.0);
            let a = random_vec(&mut rng, n, 2.0);
            let expect: Vec<f64> = match q {
                Quantity::MassMatrix => crba(&m, &mut ws, &x).unwrap().iter().copied().collect(),
                Quantity::Gravity => gravity_torque(&m, &mut ws, &x)
                    .unwrap()
                    .iter()
                    .copied()
                    .collect(),
                _ => rnea(&m, &mut ws, &x, &v, &a)
                    .unwrap()
                    .iter()
                    .copied()
                    .collect(),
            };
            let got = unit.eval(&x, &v, &a, &unit.param_values());
            assert_close(&got, &expect, 1e-12, &format!("{name} {q:?} all symbols"));
        }
        let g = derive(&m, Quantity::Gravity, &o).unwrap();
        let x = random_vec(&mut rng, n, 3.0);
        let expect: Vec<f64> = gravity_torque(&m, &mut ws, &x)
            .unwrap()
            .iter()
            .copied()
            .collect();
        assert_close(
            &g.eval(0, &x, &[0.0; 8][..n], &[0.0; 8][..n]),
            &expect,
            1e-12,
            "poly g",
        );
    }
}

#[test]
fn bad_input_gives_clear_errors() {
    let m = builtin::planar2();
    let e = derive(
        &m,
        Quantity::MassMatrix,
        &Options {
            symbols: "m7".into(),
            ..Options::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("unknown symbol 'm7'") && e.contains("m1"), "{e}");
    let panda = builtin::load("panda").unwrap();
    let e = derive(
        &panda,
        Quantity::Torque,
        &Options {
            max_terms: 1000,
            ..Options::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("more than 1000 terms") && e.contains("--max-terms"),
        "{e}"
    );
    let e = derive(
        &m,
        Quantity::Fk,
        &Options {
            frame: Some("hand".into()),
            ..Options::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("no frame named 'hand'"), "{e}");
}

/// The armature is a symbol of its own, `Ia_<i>`: `M = M_bodies + diag(Ia_1, Ia_2)` term by
/// term, in the kinetic energy as `½ Ia_i θ̇_i²`, and the Euler–Lagrange τ (from the energies)
/// equals the Newton–Euler τ symbol for symbol.
#[test]
fn armature_is_a_symbol_of_its_own() {
    let m = builtin::planar2().with_armature(&[0.2, 0.1]).unwrap();
    let d = derive(&m, Quantity::MassMatrix, &all()).unwrap();
    let (m1, m2, l1, l2) = (sym(&d, "m1"), sym(&d, "m2"), sym(&d, "L1"), sym(&d, "L2"));
    let (ia1, ia2) = (sym(&d, "Ia_1"), sym(&d, "Ia_2"));
    let m11 = prod(&[&m1.add(&m2), &l1, &l1])
        .add(&prod(&[&m2, &l2, &l2]))
        .add(&prod(&[&m2, &l1, &l2, &c(2)]).scale(2.0))
        .add(&ia1);
    let m12 = prod(&[&m2, &l2, &l2]).add(&prod(&[&m2, &l1, &l2, &c(2)]));
    let m22 = prod(&[&m2, &l2, &l2]).add(&ia2);
    assert_eq!(entry(&d, 0, 0, 0), &m11);
    assert_eq!(entry(&d, 0, 0, 1), &m12);
    assert_eq!(entry(&d, 0, 1, 1), &m22);
    assert!(
        d.entry_text(0, 1, 1).contains("Ia_2"),
        "{}",
        d.entry_text(0, 1, 1)
    );
    let e = derive(&m, Quantity::Energy, &all()).unwrap();
    let k = &e.matrices[0].entries[0];
    // ∂²K/∂θ̇1² = M11
    assert_eq!(k.diff_var(Var::Qd(0)).diff_var(Var::Qd(0)), m11);
    let steps = screwdyn::symbolic::lagrange_steps(&m, &all()).unwrap();
    let t = derive(&m, Quantity::Torque, &all()).unwrap();
    assert_eq!(steps.tau[0], t.matrices[0].entries[0]);
    assert_eq!(steps.tau[1], t.matrices[0].entries[1]);
    // Generated code takes it as an argument.
    let unit = generate(&m, Quantity::MassMatrix, &all()).unwrap();
    assert!(unit.param_names().iter().any(|n| n == "Ia_1"));
    // A zero armature stays a zero under `all`, but can be named.
    let bare = derive(&builtin::planar2(), Quantity::MassMatrix, &all()).unwrap();
    assert!(!bare.entry_text(0, 0, 0).contains("Ia_"));
    let named = derive(
        &builtin::planar2(),
        Quantity::MassMatrix,
        &Options {
            symbols: "armature,Ia_1".into(),
            ..Options::default()
        },
    )
    .unwrap();
    assert!(named.entry_text(0, 0, 0).contains("Ia_1"));
}

#[test]
fn armature_numeric() {
    check_numeric(
        &builtin::planar2().with_armature(&[0.3, 0.7]).unwrap(),
        3,
        true,
    );
    let mut rng = StdRng::seed_from_u64(43);
    let m = random_tree(&mut rng, 3, true)
        .with_armature(&[0.2, 0.05, 0.4])
        .unwrap();
    check_numeric(&m, 2, true);
}

#[test]
fn dh_models_name_lengths_a_and_d() {
    let m = builtin::load("ur5").unwrap();
    let d = derive(
        &m,
        Quantity::Gravity,
        &Options {
            symbols: "a_2,d_1,m_upper_arm_link".into(),
            ..Options::default()
        },
    )
    .unwrap();
    let names: Vec<&str> = d
        .params
        .symbols()
        .iter()
        .map(|(_, p)| p.name.as_str())
        .collect();
    assert_eq!(names, ["m_upper_arm_link", "d_1", "a_2"]);
    // g2 has the term m_upper_arm_link · g · (a_2/2 + …) c2: both symbols appear, d_1 does not
    // (it only lifts the whole arm).
    let g2 = d.entry_text(0, 1, 0);
    assert!(
        g2.contains("m_upper_arm_link") && g2.contains("a_2") && !g2.contains("d_1"),
        "{g2}"
    );
}

/// Seed 004's Lagrangian steps for the two-link arm, symbol for symbol.
#[test]
fn lagrange_steps_are_seed_004() {
    let st = screwdyn::symbolic::lagrange_steps(&builtin::planar2(), &all()).unwrap();
    let d = derive(&builtin::planar2(), Quantity::MassMatrix, &all()).unwrap();
    let (m1, m2, l1, l2) = (sym(&d, "m1"), sym(&d, "m2"), sym(&d, "L1"), sym(&d, "L2"));
    let gd = derive(&builtin::planar2(), Quantity::Gravity, &all()).unwrap();
    let g = sym(&gd, "g");
    let k = prod(&[&m2, &l1, &l2]);
    // ∂L/∂θ̇1 = (m1 + m2) l1² θ̇1 + m2 l2² θ̇1 + m2 l2² θ̇2 + 2 m2 l1 l2 c2 θ̇1 + m2 l1 l2 c2 θ̇2
    let dl1 = prod(&[&m1.add(&m2), &l1, &l1, &qd(1)])
        .add(&prod(&[&m2, &l2, &l2, &qd(1)]))
        .add(&prod(&[&m2, &l2, &l2, &qd(2)]))
        .add(&prod(&[&k, &c(2), &qd(1)]).scale(2.0))
        .add(&prod(&[&k, &c(2), &qd(2)]));
    assert_eq!(st.dl_dqd[0], dl1);
    // d/dt ∂L/∂θ̇2 = m2 l2² θ̈1 + m2 l2² θ̈2 + m2 l1 l2 c2 θ̈1 − m2 l1 l2 s2 θ̇1 θ̇2
    let ddt2 = prod(&[&m2, &l2, &l2, &qdd(1)])
        .add(&prod(&[&m2, &l2, &l2, &qdd(2)]))
        .add(&prod(&[&k, &c(2), &qdd(1)]))
        .sub(&prod(&[&k, &s(2), &qd(1), &qd(2)]));
    assert_eq!(st.ddt_dl_dqd[1], ddt2);
    // d/dt ∂L/∂θ̇1 = [...] θ̈1 + (m2 l2² + m2 l1 l2 c2) θ̈2 − 2 m2 l1 l2 s2 θ̇1 θ̇2 − m2 l1 l2 s2 θ̇2²
    let ddt1 = prod(&[
        &prod(&[&m1.add(&m2), &l1, &l1])
            .add(&prod(&[&m2, &l2, &l2]))
            .add(&prod(&[&k, &c(2)]).scale(2.0)),
        &qdd(1),
    ])
    .add(&prod(&[
        &prod(&[&m2, &l2, &l2]).add(&prod(&[&k, &c(2)])),
        &qdd(2),
    ]))
    .sub(&prod(&[&k, &s(2), &qd(1), &qd(2)]).scale(2.0))
    .sub(&prod(&[&k, &s(2), &qd(2), &qd(2)]));
    assert_eq!(st.ddt_dl_dqd[0], ddt1);
    // ∂L/∂θ1 = −(m1 + m2) g l1 c1 − m2 g l2 c12
    let dq1 = prod(&[&m1.add(&m2), &g, &l1, &c(1)])
        .add(&prod(&[&m2, &g, &l2, &c12()]))
        .neg();
    assert_eq!(st.dl_dq[0], dq1);
    // ∂L/∂θ2 = −m2 l1 l2 s2 (θ̇1² + θ̇1 θ̇2) − m2 g l2 c12
    let dq2 = prod(&[&k, &s(2), &qd(1).mul(&qd(1)).add(&qd(1).mul(&qd(2)))])
        .add(&prod(&[&m2, &g, &l2, &c12()]))
        .neg();
    assert_eq!(st.dl_dq[1], dq2);
    // And τ from Lagrange is τ from Newton–Euler.
    let t = derive(&builtin::planar2(), Quantity::Torque, &all()).unwrap();
    assert_eq!(st.tau[0], t.matrices[0].entries[0]);
    assert_eq!(st.tau[1], t.matrices[0].entries[1]);
}
