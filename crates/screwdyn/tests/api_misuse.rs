//! The public API walked as a careless user would call it: wrong lengths, NaN and infinity,
//! workspaces made for another model, ids out of range. Every call must return `Err` (no panic:
//! a panic fails the test, nothing here catches it), and the message must say what is wrong.

use nalgebra::{Matrix3, Matrix6xX, Vector3, Vector6};
use screwdyn::dynamics::{
    self, closed_form, coriolis_matrix, crba, forward_dynamics, gravity_torque, inverse_dynamics,
    lagrange_coefficients, mass_matrix_inverse, nonlinear_effects, rnea, ExternalWrenches,
    ForwardMethod,
};
use screwdyn::kinematics::{
    compute_joint_jacobians, forward_acceleration, forward_kinematics, forward_velocity,
    frame_acceleration, frame_jacobian, frame_jdot_qdot, frame_pose, frame_twist, link_jacobian,
    Reference,
};
use screwdyn::model::{JointLimits, JointSpec, ModelBuilder};
use screwdyn::sim::{
    self, ConstantTorque, Controller, EffectGains, Integrator, JointEffects, Quintic, Recording,
    Sample, SampleSink, SimOptions, Stepper, TorqueSeries, Trajectory, ZeroTorque,
};
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::{builtin, Error, Model, Workspace};

fn ur5() -> Model {
    builtin::load("ur5").unwrap()
}

/// `Err` whose message contains every word.
fn says<T: std::fmt::Debug>(r: Result<T, Error>, words: &[&str]) {
    let e = r.expect_err("expected an error").to_string();
    for w in words {
        assert!(e.contains(w), "expected '{w}' in: {e}");
    }
    assert!(!e.contains('\n'), "one sentence: {e}");
}

#[test]
fn a_workspace_made_for_another_model_is_refused_by_every_algorithm() {
    let (small, big) = (builtin::planar2(), ur5());
    let z2 = [0.0; 2];
    let z6 = [0.0; 6];
    for (m, ws_model, z) in [(&small, &big, &z2[..]), (&big, &small, &z6[..])] {
        let mut ws = Workspace::new(ws_model);
        let w = ["workspace"];
        says(forward_kinematics(m, &mut ws, z), &w);
        says(forward_velocity(m, &mut ws, z, z), &w);
        says(forward_acceleration(m, &mut ws, z, z, z), &w);
        says(compute_joint_jacobians(m, &mut ws, z), &w);
        says(rnea(m, &mut ws, z, z, z).cloned(), &w);
        says(inverse_dynamics(m, &mut ws, z, z, z, None).cloned(), &w);
        says(gravity_torque(m, &mut ws, z).cloned(), &w);
        says(nonlinear_effects(m, &mut ws, z, z).cloned(), &w);
        says(crba(m, &mut ws, z).cloned(), &w);
        says(mass_matrix_inverse(m, &mut ws, z).cloned(), &w);
        says(coriolis_matrix(m, &mut ws, z, z).cloned(), &w);
        says(dynamics::aba(m, &mut ws, z, z, z).cloned(), &w);
        for method in [
            ForwardMethod::Aba,
            ForwardMethod::Crba,
            ForwardMethod::WalkerOrin,
        ] {
            says(
                forward_dynamics(m, &mut ws, z, z, z, None, method).cloned(),
                &w,
            );
        }
        says(dynamics::kinetic_energy(m, &mut ws, z, z), &w);
        says(dynamics::potential_energy(m, &mut ws, z), &w);
        says(frame_pose(m, &ws, 0), &w);
        says(frame_twist(m, &ws, 0, Reference::World), &w);
        says(frame_acceleration(m, &ws, 0, Reference::World), &w);
        let mut j = Matrix6xX::zeros(m.nq());
        says(frame_jacobian(m, &ws, 0, Reference::World, &mut j), &w);
        says(frame_jdot_qdot(m, &mut ws, z, z, 0, Reference::World), &w);
    }
    // External wrenches made for another model.
    let ext = ExternalWrenches::new(&big);
    let mut ws = Workspace::new(&small);
    says(
        inverse_dynamics(&small, &mut ws, &z2, &z2, &z2, Some(&ext)).cloned(),
        &["external wrenches", "6 bodies"],
    );
    says(ext.on_body(&ws, 0), &["workspace"]);
}

#[test]
fn ids_out_of_range_are_errors() {
    let m = builtin::planar2();
    let mut ws = Workspace::new(&m);
    compute_joint_jacobians(&m, &mut ws, &[0.1, 0.2]).unwrap();
    let nf = m.frames().len();
    says(frame_pose(&m, &ws, nf), &["frame 3", "3 frames"]);
    says(frame_twist(&m, &ws, nf, Reference::Local), &["frame"]);
    says(
        frame_acceleration(&m, &ws, nf, Reference::LocalWorldAligned),
        &["frame"],
    );
    let mut j = Matrix6xX::zeros(2);
    says(
        frame_jacobian(&m, &ws, nf, Reference::World, &mut j),
        &["frame"],
    );
    let mut wrong = Matrix6xX::zeros(3);
    says(
        frame_jacobian(&m, &ws, 1, Reference::World, &mut wrong),
        &["3 columns", "2 joints"],
    );
    says(link_jacobian(&m, &ws, 2, &mut j), &["body 2"]);
    says(
        frame_jdot_qdot(&m, &mut ws, &[0.0; 2], &[0.0; 2], 9, Reference::World),
        &["frame 9"],
    );
    says(m.parent(2), &["body 2", "2 moving bodies"]);
    says(m.children(7), &["body 7"]);
    says(m.support(2), &["body 2"]);
    says(m.supports(0, 5), &["body 5"]);
    says(m.body_frame(2), &["body 2"]);
    says(m.body(3), &["body 3"]);
    says(m.frame(usize::MAX), &["frame"]);
    let mut ext = ExternalWrenches::new(&m);
    says(ext.add_local(2, Vector6::zeros()), &["body 2"]);
    says(ext.add_world(5, Vector6::zeros()), &["body 5"]);
    says(ext.add_tip(&m, 17, Vector6::zeros()), &["frame 17"]);
    says(ext.add_tip(&m, 0, Vector6::zeros()), &["fixed to the base"]);
    says(ext.on_body(&ws, 2), &["body 2"]);
    let d = lagrange_coefficients(&m, &[0.0, 0.3]).unwrap();
    says(d.d(0, 2, 0), &["out of range"]);
}

#[test]
fn wrong_lengths_and_non_finite_values_are_errors() {
    let m = builtin::planar2();
    let mut ws = Workspace::new(&m);
    says(
        rnea(&m, &mut ws, &[0.0], &[0.0; 2], &[0.0; 2]).cloned(),
        &["q has 1 values"],
    );
    says(
        rnea(&m, &mut ws, &[0.0; 2], &[f64::NAN, 0.0], &[0.0; 2]).cloned(),
        &["v", "non-finite"],
    );
    says(
        dynamics::aba(&m, &mut ws, &[0.0; 2], &[0.0; 2], &[f64::INFINITY, 0.0]).cloned(),
        &["tau", "non-finite"],
    );
    let cf = closed_form(&m, &[0.1, 0.2], &[0.0, 1.0]).unwrap();
    says(
        cf.inverse_dynamics(&[0.0; 3], None),
        &["3 values", "2 joints"],
    );
    says(cf.inverse_dynamics(&[f64::NAN, 0.0], None), &["non-finite"]);
    let mut ext = ExternalWrenches::new(&m);
    says(
        ext.add_local(0, Vector6::new(f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0)),
        &["non-finite"],
    );
    says(
        m.with_gravity(Vector3::new(0.0, f64::NAN, 0.0)),
        &["gravity", "non-finite"],
    );
    says(
        m.with_gravity(Vector3::new(f64::INFINITY, 0.0, 0.0)),
        &["gravity"],
    );
    says(m.with_joint_friction(&[0.1], &[0.0, 0.0]), &["1 values"]);
    says(
        m.with_joint_friction(&[-0.1, 0.0], &[0.0, 0.0]),
        &["non-negative"],
    );
}

#[test]
fn simulation_pieces_refuse_wrong_lengths() {
    let m = builtin::planar2();
    // Joint effects.
    let gains = EffectGains::new(&JointEffects::default(), &m, &[0.0; 2], 1e-3).unwrap();
    let mut tau = [0.0; 2];
    says(
        JointEffects::default().apply(&m, &gains, &[0.0; 3], &[0.0; 2], &[0.0; 2], &mut tau),
        &["joint effects on 2 joints"],
    );
    // Stepper.
    let mut s = Stepper::new(Integrator::Rk4, 2).unwrap();
    let mut rest = |_: f64, _: &[f64], _: &[f64], a: &mut [f64]| {
        a.fill(0.0);
        Ok(())
    };
    let (mut q, mut v) = (vec![0.0; 3], vec![0.0; 2]);
    says(
        s.advance(&mut rest, 0.0, 1e-3, &mut q, &mut v),
        &["2 joints", "q has 3"],
    );
    let mut q = vec![0.0; 2];
    says(
        s.advance(&mut rest, 0.0, f64::NAN, &mut q, &mut v),
        &["positive finite step"],
    );
    says(
        Stepper::new(
            Integrator::DormandPrince {
                rtol: f64::NAN,
                atol: 1e-9,
            },
            2,
        ),
        &["tolerances"],
    );
    // Trajectories.
    let t = Quintic::rest_to_rest(&[0.0; 2], &[1.0; 2], 1.0).unwrap();
    let (mut a, mut b, mut c) = ([0.0; 3], [0.0; 2], [0.0; 2]);
    says(t.sample(0.5, &mut a, &mut b, &mut c), &["2 joints"]);
    let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
    says(t.sample(f64::NAN, &mut a, &mut b, &mut c), &["NaN"]);
    // Recording.
    let mut r = Recording::new(vec!["j1".into(), "j2".into()], vec![]);
    says(
        r.push(&Sample {
            t: 0.0,
            q: &[0.0],
            v: &[0.0; 2],
            a: &[0.0; 2],
            tau: &[0.0; 2],
            kinetic_energy: 0.0,
            potential_energy: 0.0,
            poses: &[],
        }),
        &["does not fit"],
    );
    says(r.sample(0), &["sample 0"]);
    // Controllers with the wrong number of torques.
    let mut out = [0.0; 2];
    says(
        ConstantTorque(vec![1.0; 3]).torque(0.0, &[0.0; 2], &[0.0; 2], &mut out),
        &["3 values", "2 joints"],
    );
    says(
        TorqueSeries::new(vec![0.0, 1.0], vec![vec![0.0; 2], vec![0.0; 3]]),
        &["row 2 has 3 values"],
    );
    says(
        TorqueSeries::new(vec![0.0, f64::NAN], vec![vec![0.0; 2], vec![0.0; 2]]),
        &["non-finite"],
    );
    let mut series = TorqueSeries::new(vec![0.0], vec![vec![0.0; 3]]).unwrap();
    says(
        series.torque(0.0, &[0.0; 2], &[0.0; 2], &mut out),
        &["3 values"],
    );
    // Whole simulations.
    let opts = SimOptions {
        duration: 0.01,
        ..Default::default()
    };
    let run = |c: &mut dyn Controller, o: &SimOptions| {
        sim::simulate(&m, &[0.0; 2], &[0.0; 2], c, &[], o, &mut |_| {})
    };
    says(run(&mut ConstantTorque(vec![1.0; 3]), &opts), &["3 values"]);
    says(run(&mut series, &opts), &["3 values"]);
    let bad_frame = SimOptions {
        frames: vec![99],
        ..opts.clone()
    };
    says(run(&mut ZeroTorque, &bad_frame), &["frame 99"]);
    let bad_dt = SimOptions {
        dt: f64::NAN,
        ..opts.clone()
    };
    says(run(&mut ZeroTorque, &bad_dt), &["step"]);
    let bad_disturbance = sim::Disturbance {
        body: 4,
        wrench: Vector6::zeros(),
        in_world: false,
        start: 0.0,
        end: 1.0,
    };
    says(
        sim::simulate(
            &m,
            &[0.0; 2],
            &[0.0; 2],
            &mut ZeroTorque,
            &[bad_disturbance],
            &opts,
            &mut |_| {},
        ),
        &["body 4"],
    );
}

#[test]
fn model_builder_refuses_nan_and_out_of_range_values() {
    let rz = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let one = SpatialInertia::new(1.0, Vector3::zeros(), Matrix3::identity() * 0.1);
    let build = |spec: JointSpec, home: Se3| {
        let mut b = ModelBuilder::new("x");
        b.link("a", "base", spec.screw_in_child(rz), home, one);
        b.build().map(|_| ())
    };
    let id = Se3::identity();
    let nan_home = Se3::from_translation(Vector3::new(f64::NAN, 0.0, 0.0));
    says(
        build(JointSpec::revolute("j"), nan_home),
        &["joint 'j'", "home pose"],
    );
    says(
        build(JointSpec::revolute("j").effort_limit(-1.0), id),
        &["joint 'j'", "effort limit", "non-negative"],
    );
    says(
        build(JointSpec::revolute("j").effort_limit(f64::NAN), id),
        &["effort limit"],
    );
    says(
        build(JointSpec::revolute("j").velocity_limit(-2.0), id),
        &["velocity limit"],
    );
    says(
        build(JointSpec::revolute("j").damping(f64::NAN), id),
        &["damping"],
    );
    says(
        build(JointSpec::revolute("j").friction(-0.1), id),
        &["friction"],
    );
    says(
        build(JointSpec::revolute("j").limits(1.0, -1.0), id),
        &["lower position limit", "above"],
    );
    says(
        build(JointSpec::revolute("j").limits(f64::NAN, 1.0), id),
        &["NaN"],
    );
    says(build(JointSpec::helical("j", f64::NAN), id), &["pitch"]);
    says(build(JointSpec::revolute(""), id), &["empty name"]);
    says(
        build(JointSpec::revolute("a\nb"), id),
        &["control character"],
    );
    let mut b = ModelBuilder::new("x");
    b.link(
        "a",
        "base",
        JointSpec::revolute("j").screw_in_child(rz),
        id,
        one,
    )
    .frame("tool", "a", nan_home);
    says(b.build(), &["frame 'tool'", "non-finite placement"]);
    let mut b = ModelBuilder::new("x");
    b.gravity(Vector3::new(0.0, 0.0, f64::NAN)).link(
        "a",
        "base",
        JointSpec::revolute("j").screw_in_child(rz),
        id,
        one,
    );
    says(b.build(), &["gravity"]);
    // Limits in range still build, with JointLimits' ±∞ defaults.
    assert_eq!(JointLimits::<f64>::default().effort, f64::INFINITY);
    assert!(build(
        JointSpec::revolute("j").limits(-1.0, 1.0).effort_limit(5.0),
        id
    )
    .is_ok());
}

/// The defect of issue 11: a massless moving link with rotational inertia merged with a fixed
/// child lost all its inertia. About the joint axis z the three parts add by the parallel-axis
/// theorem (seed 003): `M₀₀ = I_zz(link) + I_zz(fixed child) + m r² = 0.1 + 0.1 + 1 · 1² = 1.2`.
#[test]
fn merging_massless_links_keeps_their_rotational_inertia() {
    let rz = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let rotor = SpatialInertia::new(0.0, Vector3::zeros(), Matrix3::identity() * 0.1);
    let mut b = ModelBuilder::<f64>::new("rotor");
    b.link(
        "a",
        "base",
        JointSpec::revolute("j1").screw_in_child(rz),
        Se3::identity(),
        rotor,
    )
    .link(
        "a_cover",
        "a",
        JointSpec::fixed("f"),
        Se3::identity(),
        rotor,
    )
    .link(
        "b",
        "a",
        JointSpec::revolute("j2").screw_in_child(rz),
        Se3::from_translation(Vector3::new(1.0, 0.0, 0.0)),
        SpatialInertia::point_mass(1.0, Vector3::zeros()),
    );
    let m = b.build().unwrap();
    let mut ws = Workspace::new(&m);
    let mm = crba(&m, &mut ws, &[0.0, 0.0]).unwrap();
    assert!((mm[(0, 0)] - 1.2).abs() < 1e-12, "M00 = {}", mm[(0, 0)]);
    assert!((mm[(1, 1)] - 0.0).abs() < 1e-12);
}

/// A `FromStr` of the library: an unknown word is an [`Error::UnknownChoice`] naming it, and
/// every word its message offers is accepted.
fn offers_only_words_it_accepts<T>(what: &str)
where
    T: std::str::FromStr<Err = Error> + std::fmt::Debug,
{
    let e = "no-such-word".parse::<T>().unwrap_err();
    let Error::UnknownChoice {
        what: w,
        got,
        expected,
    } = &e
    else {
        panic!("{what}: {e:?}")
    };
    assert_eq!((*w, got.as_str()), (what, "no-such-word"));
    assert_eq!(
        e.to_string(),
        format!("unknown {what} 'no-such-word' (use {expected})")
    );
    let words: Vec<&str> = expected
        .split([',', ' '])
        .filter(|w| !w.is_empty() && *w != "or")
        .collect();
    assert!(words.len() >= 2, "{what}: {expected}");
    for word in words {
        if let Err(e) = word.parse::<T>() {
            panic!("{what}: '{word}' is offered but refused: {e}");
        }
    }
}

#[test]
fn every_from_str_refuses_an_unknown_word_with_the_choices() {
    use screwdyn::symbolic::{Collect, CoriolisForm, Quantity};
    offers_only_words_it_accepts::<ForwardMethod>("forward-dynamics method");
    offers_only_words_it_accepts::<Reference>("reference");
    offers_only_words_it_accepts::<Integrator>("integrator");
    offers_only_words_it_accepts::<Quantity>("quantity");
    offers_only_words_it_accepts::<CoriolisForm>("Coriolis form");
    offers_only_words_it_accepts::<Collect>("collect mode");
    offers_only_words_it_accepts::<screwdyn::io::Format>("format");
}

#[test]
fn named_choices_take_any_case_and_underscores_and_quote_what_was_written() {
    // Pinocchio's reference names are what its users type.
    for (word, expected) in [
        ("WORLD", Reference::World),
        ("LOCAL", Reference::Local),
        ("LOCAL_WORLD_ALIGNED", Reference::LocalWorldAligned),
        (" world_aligned ", Reference::LocalWorldAligned),
    ] {
        assert_eq!(word.parse::<Reference>().unwrap(), expected, "{word}");
    }
    assert!(matches!(
        "Walker_Orin".parse::<ForwardMethod>(),
        Ok(ForwardMethod::WalkerOrin)
    ));
    let e = "LOCAL_WORLD_ALIGNEDX"
        .parse::<Reference>()
        .unwrap_err()
        .to_string();
    assert!(e.contains("'LOCAL_WORLD_ALIGNEDX'"), "{e}");
}
