//! One module per family of commands; `run` dispatches.

mod bench;
mod kinematics;
mod model;

use crate::args::{Cli, Command};
use crate::CliError;

pub use model::load;

/// Runs one command.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Info(a) => model::info(&a),
        Command::Fk(a) => kinematics::fk(&a),
        Command::Jacobian(a) => kinematics::jacobian(&a),
        Command::Bench(a) => bench::bench(&a),
    }
}

/// Parses a comma-separated joint-space vector given as `--name`; `None` means all zeros.
pub fn parse_vector(
    text: Option<&str>,
    name: &str,
    model: &screwdyn::Model,
) -> Result<Vec<f64>, CliError> {
    let Some(text) = text else {
        return Ok(vec![0.0; model.nq()]);
    };
    let values = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| CliError::input(format!("--{name}: '{}' is not a number", s.trim())))
        })
        .collect::<Result<Vec<_>, _>>()?;
    model.check_vector(&values, &format!("--{name}"))?;
    Ok(values)
}
