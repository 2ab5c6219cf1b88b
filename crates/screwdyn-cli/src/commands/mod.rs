//! One module per family of commands; `run` dispatches. What they share is in `inputs` (model
//! loading, vectors, wrenches, labels) and `states` (the states of numeric commands, from flags
//! or `--input states.csv`).

mod bench;
mod classic;
mod derivatives;
mod dynamics;
mod explain;
mod identify;
mod ik;
mod inertia;
mod inputs;
mod joint_csv;
mod kinematics;
mod model;
mod regressor;
mod run_files;
mod simulate;
mod states;
mod symbolic;
mod torque_profile;
mod view;

use crate::args::{Cli, Command};
use crate::CliError;

/// Runs one command.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Info(a) => model::info(&a),
        Command::Check(a) => model::check(&a),
        Command::Export(a) => model::export(&a),
        Command::Fk(a) => kinematics::fk(&a),
        Command::Jacobian(a) => kinematics::jacobian(&a),
        Command::Ik(a) => ik::ik(&a),
        Command::InverseDynamics(a) => dynamics::inverse_dynamics(&a),
        Command::MassMatrix(a) => dynamics::mass_matrix(&a),
        Command::Coriolis(a) => dynamics::coriolis(&a),
        Command::Gravity(a) => dynamics::gravity(&a),
        Command::NonlinearEffects(a) => dynamics::nonlinear_effects(&a),
        Command::Energy(a) => dynamics::energy(&a),
        Command::ForwardDynamics(a) => dynamics::forward_dynamics(&a),
        Command::ClosedForm(a) => dynamics::closed_form(&a),
        Command::Lagrange(a) => dynamics::lagrange(&a),
        Command::Explain(a) => explain::explain(&a),
        Command::Simulate(a) => simulate::simulate(&a),
        Command::TorqueProfile(a) => torque_profile::torque_profile(&a),
        Command::Bench(a) => bench::bench(&a),
        Command::Symbolic(a) => symbolic::symbolic(&a),
        Command::Inertia(a) => inertia::inertia(&a),
        Command::Derivatives(a) => derivatives::derivatives(&a),
        Command::Regressor(a) => regressor::regressor(&a),
        Command::Identify(a) => identify::identify(&a),
        Command::View(a) => view::view(&a),
    }
}
