//! Dynamics against the seeds' closed-form two-link results (seeds 003/004) and Modern Robotics'
//! published `InverseDynamics` example.

mod common;

use common::assert_close;
use nalgebra::{DVector, Matrix3, Matrix4, Vector3, Vector6};
use screwdyn::dynamics::{
    aba, closed_form, coriolis_matrix, crba, effective_inertia_free, effective_inertia_locked,
    forward_dynamics, gravity_torque, inverse_dynamics, lagrange_coefficients, nonlinear_effects,
    rnea, ExternalWrenches, ForwardMethod,
};
use screwdyn::model::{JointSpec, ModelBuilder};
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{builtin, Error, Workspace};

const G: f64 = 9.81;

/// Seed 003's closed forms for the point-mass two-link arm.
struct Planar2 {
    l1: f64,
    l2: f64,
    m1: f64,
    m2: f64,
}

impl Planar2 {
    fn mass(&self, q2: f64) -> [[f64; 2]; 2] {
        let (l1, l2, m1, m2) = (self.l1, self.l2, self.m1, self.m2);
        let c2 = q2.cos();
        let m11 = (m1 + m2) * l1 * l1 + m2 * l2 * l2 + 2.0 * m2 * l1 * l2 * c2;
        let m12 = m2 * l2 * l2 + m2 * l1 * l2 * c2;
        [[m11, m12], [m12, m2 * l2 * l2]]
    }
    fn coriolis(&self, q2: f64, qd: [f64; 2]) -> [f64; 2] {
        let k = self.m2 * self.l1 * self.l2 * q2.sin();
        [
            -k * qd[1] * qd[1] - 2.0 * k * qd[0] * qd[1],
            k * qd[0] * qd[0],
        ]
    }
    fn gravity(&self, q: [f64; 2]) -> [f64; 2] {
        let c12 = (q[0] + q[1]).cos();
        [
            self.m2 * G * self.l2 * c12 + (self.m1 + self.m2) * G * self.l1 * q[0].cos(),
            self.m2 * G * self.l2 * c12,
        ]
    }
}

#[test]
fn planar2_mass_coriolis_gravity_match_seed_003() {
    let arm = Planar2 {
        l1: 0.7,
        l2: 0.4,
        m1: 1.3,
        m2: 0.8,
    };
    let model = builtin::planar2_with(arm.l1, arm.l2, arm.m1, arm.m2);
    let mut ws = Workspace::new(&model);
    for &(q, qd, qdd) in &[
        ([0.3, -0.8], [1.2, 0.7], [0.5, -2.0]),
        ([-1.1, 2.3], [-0.4, 1.9], [0.0, 1.0]),
        ([2.0, 0.0], [0.0, 0.0], [0.0, 0.0]),
    ] {
        let mm = arm.mass(q[1]);
        let m = crba(&model, &mut ws, &q).unwrap().clone();
        assert_close(
            m.as_slice(),
            &[mm[0][0], mm[1][0], mm[0][1], mm[1][1]],
            1e-12,
            "M",
        );
        let cv = arm.coriolis(q[1], qd);
        let g = arm.gravity(q);
        assert_close(
            gravity_torque(&model, &mut ws, &q).unwrap().as_slice(),
            &g,
            1e-12,
            "g",
        );
        let h = nonlinear_effects(&model, &mut ws, &q, &qd).unwrap().clone();
        assert_close(
            h.as_slice(),
            &[cv[0] + g[0], cv[1] + g[1]],
            1e-12,
            "C q̇ + g",
        );
        let c = coriolis_matrix(&model, &mut ws, &q, &qd).unwrap().clone();
        let cq = c * DVector::from_column_slice(&qd);
        assert_close(cq.as_slice(), &cv, 1e-12, "C(q, q̇) q̇");
        // Seed 003's full τ.
        let tau: Vec<f64> = (0..2)
            .map(|i| mm[i][0] * qdd[0] + mm[i][1] * qdd[1] + cv[i] + g[i])
            .collect();
        assert_close(
            rnea(&model, &mut ws, &q, &qd, &qdd).unwrap().as_slice(),
            &tau,
            1e-12,
            "τ",
        );
        // The closed form of seeds 000/001 too.
        let cf = closed_form(&model, &q, &qd).unwrap();
        assert_close(
            cf.inverse_dynamics(&qdd, None).unwrap().as_slice(),
            &tau,
            1e-12,
            "closed-form τ",
        );
        assert_close(cf.g.as_slice(), &g, 1e-12, "closed-form g");
    }
}

#[test]
fn seed_004_effective_inertia_table() {
    let model = builtin::planar2();
    let mut ws = Workspace::new(&model);
    // θ2, D11, D21, D22, ① I1 (joint 2 locked), ② I1 (joint 2 free)
    let table = [
        (0.0, 5.0, 2.0, 1.0, 5.0, 1.0),
        (90.0, 3.0, 1.0, 1.0, 3.0, 2.0),
        (180.0, 1.0, 0.0, 1.0, 1.0, 1.0),
        (270.0, 3.0, 1.0, 1.0, 3.0, 2.0),
    ];
    for (deg, d11, d21, d22, locked, free) in table {
        let q = [0.4, f64::to_radians(deg)];
        let m = crba(&model, &mut ws, &q).unwrap().clone();
        assert_close(
            &[m[(0, 0)], m[(1, 0)], m[(1, 1)]],
            &[d11, d21, d22],
            1e-12,
            "D",
        );
        let l = effective_inertia_locked(&model, &mut ws, &q, 0).unwrap();
        let f = effective_inertia_free(&model, &mut ws, &q, 0).unwrap();
        assert_close(&[l, f], &[locked, free], 1e-12, "effective inertia");
    }
}

#[test]
fn seed_004_christoffel_coefficients() {
    let (l1, l2, m1, m2) = (0.9, 0.6, 1.7, 1.1);
    let model = builtin::planar2_with(l1, l2, m1, m2);
    for &q in &[[0.2, 0.7], [-1.0, 2.5], [0.5, -1.2]] {
        let d = lagrange_coefficients(&model, &q).unwrap();
        let k = m2 * l1 * l2 * q[1].sin();
        // D111 = D222 = 0, D122 = D112 = D121 = −m2 l1 l2 s2, D211 = m2 l1 l2 s2, D212 = D221 = 0.
        let got = [
            d.d(0, 0, 0).unwrap(),
            d.d(1, 1, 1).unwrap(),
            d.d(0, 1, 1).unwrap(),
            d.d(0, 0, 1).unwrap(),
            d.d(0, 1, 0).unwrap(),
            d.d(1, 0, 0).unwrap(),
            d.d(1, 0, 1).unwrap(),
            d.d(1, 1, 0).unwrap(),
        ];
        assert_close(&got, &[0.0, 0.0, -k, -k, -k, k, 0.0, 0.0], 1e-12, "D_ijk");
        // D_i: seed 004's gravity terms.
        let c12 = (q[0] + q[1]).cos();
        let d1 = (m1 + m2) * G * l1 * q[0].cos() + m2 * G * l2 * c12;
        assert_close(d.d_i.as_slice(), &[d1, m2 * G * l2 * c12], 1e-12, "D_i");
    }
}

/// Modern Robotics, `InverseDynamics` documentation example (3-link arm, UR5-like geometry).
///
/// The published example (MR's MATLAB/Python documentation) uses the space screw
/// `S1 = (1, 0, 1, 0, 1, 0)`, which is `√2` times the unit revolute screw
/// `Ŝ1 = S1/√2`. A scaled screw is a rescaled coordinate: with `q̂1 = √2 q1` (and the same for
/// `q̇1`, `q̈1`) the motion is identical and `τ1 = √2 τ̂1`. The model uses the unit screw and the
/// test applies that change of coordinate.
#[test]
fn modern_robotics_inverse_dynamics_example() {
    let m01 = Matrix4::new(
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0.089159, 0., 0., 0., 1.,
    );
    let m12 = Matrix4::new(
        0., 0., 1., 0.28, 0., 1., 0., 0.13585, -1., 0., 0., 0., 0., 0., 0., 1.,
    );
    let m23 = Matrix4::new(
        1., 0., 0., 0., 0., 1., 0., -0.1197, 0., 0., 1., 0.395, 0., 0., 0., 1.,
    );
    let m34 = Matrix4::new(
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0.14225, 0., 0., 0., 1.,
    );
    let homes = [m01, m12, m23].map(|m| Se3::from_matrix(&m));
    let glist = [
        (0.010267, 0.010267, 0.00666, 3.7),
        (0.22689, 0.22689, 0.0151074, 8.393),
        (0.0494433, 0.0494433, 0.004095, 2.275),
    ];
    let k = 2f64.sqrt();
    let slist = [
        Vector6::new(1., 0., 1., 0., 1., 0.) / k,
        Vector6::new(0., 1., 0., -0.089, 0., 0.),
        Vector6::new(0., 1., 0., -0.089, 0., 0.425),
    ];
    let mut b = ModelBuilder::new("mr-3link");
    b.gravity(Vector3::new(0.0, 0.0, -9.8));
    let mut m_i = Se3::identity();
    let mut parent = "base".to_string();
    for i in 0..3 {
        m_i = m_i.compose(&homes[i]);
        let (ixx, iyy, izz, mass) = glist[i];
        let inertia = SpatialInertia::new(
            mass,
            Vector3::zeros(),
            Matrix3::from_diagonal(&Vector3::new(ixx, iyy, izz)),
        );
        let name = format!("link{}", i + 1);
        b.link(
            &name,
            &parent,
            JointSpec::revolute(&format!("joint{}", i + 1))
                .screw_in_child(m_i.inverse().act_twist(&slist[i])),
            homes[i],
            inertia,
        );
        parent = name;
    }
    b.frame("ee", "link3", Se3::from_matrix(&m34));
    let model = b.build().unwrap();
    let mut ws = Workspace::new(&model);
    let (q, v, a) = (
        [0.1 * k, 0.1, 0.1],
        [0.1 * k, 0.2, 0.3],
        [2.0 * k, 1.5, 1.0],
    );
    let mut ext = ExternalWrenches::new(&model);
    ext.add_tip(&model, model.frame_id("ee").unwrap(), Vector6::repeat(1.0))
        .unwrap();
    let mut tau = inverse_dynamics(&model, &mut ws, &q, &v, &a, Some(&ext))
        .unwrap()
        .clone();
    tau[0] *= k;
    let expected: [f64; 3] = [74.69616155, -33.06766016, -3.23057314];
    for i in 0..3 {
        assert!(
            (tau[i] - expected[i]).abs() < 1e-6,
            "τ{i} = {} vs {}",
            tau[i],
            expected[i]
        );
    }
    // The closed form with the same tip wrench agrees.
    let cf = closed_form(&model, &q, &v).unwrap();
    let mut tau_cf = cf.inverse_dynamics(&a, Some(&ext)).unwrap();
    tau_cf[0] *= k;
    assert_close(tau_cf.as_slice(), &expected, 1e-8, "closed form");
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let model = builtin::planar2();
    let mut ws = Workspace::new(&model);
    let e = rnea(&model, &mut ws, &[0.0], &[0.0, 0.0], &[0.0, 0.0]).unwrap_err();
    assert!(matches!(e, Error::DimensionMismatch { .. }), "{e}");
    let e = aba(&model, &mut ws, &[0.0, 0.0], &[f64::NAN, 0.0], &[0.0, 0.0]).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    let e = forward_dynamics(
        &model,
        &mut ws,
        &[0.0, 0.0],
        &[0.0, 0.0],
        &[0.0],
        None,
        ForwardMethod::Crba,
    )
    .unwrap_err();
    assert!(e.to_string().contains("tau has 1 values"), "{e}");
    let mut ext = ExternalWrenches::new(&model);
    assert!(ext.add_local(5, Vector6::zeros()).is_err());
    assert!(ext
        .add_tip(&model, model.frame_id("base").unwrap(), Vector6::zeros())
        .is_err());
    let other = builtin::pendulum();
    let ext1 = ExternalWrenches::new(&other);
    assert!(inverse_dynamics(
        &model,
        &mut ws,
        &[0.0; 2],
        &[0.0; 2],
        &[0.0; 2],
        Some(&ext1)
    )
    .is_err());
}

#[test]
fn massless_chain_is_a_numerical_error() {
    let model = common::massless_tip();
    let mut ws = Workspace::new(&model);
    for method in [
        ForwardMethod::Aba,
        ForwardMethod::Crba,
        ForwardMethod::WalkerOrin,
    ] {
        let e = forward_dynamics(
            &model,
            &mut ws,
            &[0.1, 0.2],
            &[0.0, 0.0],
            &[1.0, 1.0],
            None,
            method,
        )
        .unwrap_err();
        assert!(matches!(e, Error::Numerical(_)), "{method:?}: {e}");
        assert!(e.to_string().contains("singular"), "{method:?}: {e}");
    }
}

#[test]
fn f32_smoke() {
    let m64 = builtin::planar2();
    let m32: screwdyn::Model<f32> = m64.cast();
    let mut w64 = Workspace::new(&m64);
    let mut w32 = Workspace::new(&m32);
    let t64 = rnea(&m64, &mut w64, &[0.3, 0.4], &[1.0, -1.0], &[0.5, 0.2])
        .unwrap()
        .clone();
    let t32 = rnea(&m32, &mut w32, &[0.3, 0.4], &[1.0, -1.0], &[0.5, 0.2])
        .unwrap()
        .clone();
    for i in 0..2 {
        assert!((t32[i] as f64 - t64[i]).abs() < 1e-4);
    }
    let a32 = aba(&m32, &mut w32, &[0.3, 0.4], &[1.0, -1.0], t32.as_slice()).unwrap();
    assert!((a32[0] - 0.5).abs() < 1e-3 && (a32[1] - 0.2).abs() < 1e-3);
}
