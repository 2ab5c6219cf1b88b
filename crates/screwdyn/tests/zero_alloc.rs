//! Per-call algorithms allocate nothing once the workspace exists, checked with a
//! counting global allocator that counts allocations made on the test's own thread.

mod common;
#[path = "common/counting.rs"]
mod counting;

use counting::allocations;

use nalgebra::{Matrix6xX, Vector6};
use rand::rngs::StdRng;
use rand::SeedableRng;
use screwdyn::dynamics::*;
use screwdyn::kinematics::*;
use screwdyn::{builtin, Model, Workspace};

fn check(model: &Model) {
    let n = model.nq();
    let mut ws = Workspace::new(model);
    let q: Vec<f64> = (0..n).map(|i| 0.1 + 0.2 * i as f64).collect();
    let v: Vec<f64> = (0..n).map(|i| 0.3 - 0.1 * i as f64).collect();
    let a: Vec<f64> = (0..n).map(|i| -0.2 + 0.05 * i as f64).collect();
    let mut ext = ExternalWrenches::new(model);
    ext.add_local(0, Vector6::repeat(0.5)).unwrap();
    ext.add_world(n - 1, Vector6::repeat(-0.25)).unwrap();
    let mut jac = Matrix6xX::zeros(n);
    let mut jac2 = Matrix6xX::zeros(n);
    let tip = model.body_frame(n - 1).unwrap();
    // Warm up once (nothing lazily allocated should remain), then count.
    let mut run = |ws: &mut Workspace| {
        forward_kinematics(model, ws, &q).unwrap();
        compute_joint_jacobians(model, ws, &q).unwrap();
        frame_jacobian(model, ws, tip, Reference::World, &mut jac).unwrap();
        forward_velocity(model, ws, &q, &v).unwrap();
        forward_acceleration(model, ws, &q, &v, &a).unwrap();
        rnea(model, ws, &q, &v, &a).unwrap();
        inverse_dynamics(model, ws, &q, &v, &a, Some(&ext)).unwrap();
        crba(model, ws, &q).unwrap();
        mass_matrix_inverse(model, ws, &q).unwrap();
        coriolis_matrix(model, ws, &q, &v).unwrap();
        gravity_torque(model, ws, &q).unwrap();
        nonlinear_effects(model, ws, &q, &v).unwrap();
        aba(model, ws, &q, &v, &a).unwrap();
        forward_dynamics(model, ws, &q, &v, &a, Some(&ext), ForwardMethod::Aba).unwrap();
        for m in [
            ForwardMethod::Aba,
            ForwardMethod::Crba,
            ForwardMethod::WalkerOrin,
        ] {
            forward_dynamics(model, ws, &q, &v, &a, None, m).unwrap();
            forward_dynamics(model, ws, &q, &v, &a, Some(&ext), m).unwrap();
        }
        kinetic_energy(model, ws, &q, &v).unwrap();
        kinetic_energy_mass_matrix(model, ws, &q, &v).unwrap();
        potential_energy(model, ws, &q).unwrap();
        total_energy(model, ws, &q, &v).unwrap();
        center_of_mass(model, ws, &q).unwrap();
        power(model, &a, &v).unwrap();
        rnea_derivatives(model, ws, &q, &v, &a, None).unwrap();
        rnea_derivatives(model, ws, &q, &v, &a, Some(&ext)).unwrap();
        aba_derivatives(model, ws, &q, &v, &a, None).unwrap();
        aba_derivatives(model, ws, &q, &v, &a, Some(&ext)).unwrap();
        regressor(model, ws, &q, &v, &a).unwrap();
        frame_velocity_derivatives(
            model,
            ws,
            tip,
            Reference::Local,
            &q,
            &v,
            &mut jac,
            &mut jac2,
        )
        .unwrap();
    };
    run(&mut ws);
    let count = allocations(|| run(&mut ws));
    assert_eq!(count, 0, "{} allocated {count} times", model.name());
}

/// The batch functions, on a batch of 11 states (a group of eight and three alone).
fn check_batch(model: &Model) {
    use screwdyn::batch::{self, BatchWorkspace, Rows};
    let n = model.nq();
    let mut ws = BatchWorkspace::new(model);
    let q: Vec<f64> = (0..11 * n).map(|i| 0.1 * i as f64).collect();
    let v: Vec<f64> = (0..11 * n).map(|i| 0.3 - 0.01 * i as f64).collect();
    let mut out = vec![0.0; 11 * n * n];
    let mut run = |ws: &mut BatchWorkspace| {
        let (q, v) = (Rows::Stacked(&q), Rows::Stacked(&v));
        batch::rnea(model, ws, q, v, v, &mut out[..11 * n]).unwrap();
        batch::gravity_torque(model, ws, q, &mut out[..11 * n]).unwrap();
        batch::nonlinear_effects(model, ws, q, v, &mut out[..11 * n]).unwrap();
        batch::crba(model, ws, q, &mut out).unwrap();
        batch::aba(model, ws, q, v, v, &mut out[..11 * n]).unwrap();
    };
    run(&mut ws);
    let count = allocations(|| run(&mut ws));
    assert_eq!(
        count,
        0,
        "batches on {} allocated {count} times",
        model.name()
    );
}

#[test]
fn batch_functions_do_not_allocate() {
    check_batch(&builtin::planar2());
    let mut rng = StdRng::seed_from_u64(42);
    check_batch(&common::random_tree(&mut rng, 7, true));
}

#[test]
fn per_call_algorithms_do_not_allocate() {
    // The counter must see allocations at all (guards against a vacuous pass).
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 16]))) > 0);
    check(&builtin::planar2());
    let mut rng = StdRng::seed_from_u64(42);
    check(&common::random_tree(&mut rng, 7, true));
}
