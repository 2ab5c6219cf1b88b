//! `regressor`: the regressor `Y` of `τ = Y π` at a state, or with `--base` the model's base
//! parameters (issue 15). The library does the work; this parses, calls and prints.

use super::inputs::{load, names};
use super::states::run_states;
use crate::args::RegressorArgs;
use crate::output::{self, Report, Value};
use crate::CliError;
use nalgebra::DMatrix;
use screwdyn::identification::{
    full_regressor, parameter_names, standard_parameters, BaseParameters, DEFAULT_SEED,
};
use screwdyn::Workspace;

/// `regressor`: `regressor` (n × p, columns named by parameter) and `parameters` (the model's
/// standard parameters); with `--base`, the base parameters.
pub fn regressor(a: &RegressorArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    if a.base {
        if a.q.is_some() || a.v.is_some() || a.a.is_some() || a.common.input.is_some() {
            return Err(CliError::input(
                "--base describes the model, not a state: drop --q, --v, --a and --input",
            ));
        }
        let b = BaseParameters::new(&m, a.friction, a.states, DEFAULT_SEED)?;
        let values = b.base_values(&standard_parameters(&m, a.friction));
        let exprs = b.expressions();
        let mut r = Report::new();
        r.add("rank", Value::Count(b.rank()))
            .add("standard_parameters", Value::Count(b.standard_names.len()));
        r.add(
            "base_parameters",
            Value::Map(
                exprs
                    .iter()
                    .zip(values.iter())
                    .map(|(e, v)| (e.clone(), Value::Scalar(*v)))
                    .collect(),
            ),
        );
        let mut t = format!(
            "{} base parameters of {} standard ones ({}), value in the model:\n",
            b.rank(),
            b.standard_names.len(),
            m.name()
        );
        for (e, v) in exprs.iter().zip(values.iter()) {
            t.push_str(&format!("  {:>14}  {e}\n", output::fmt(*v)));
        }
        r.table = Some(t);
        return output::print(&[r], output::resolve(a.common.model.format), false);
    }
    let mut ws = Workspace::new(&m);
    let j = names(&m);
    let pnames = output::labels(&parameter_names(&m, a.friction));
    let pi = standard_parameters(&m, a.friction);
    let mut y = DMatrix::zeros(m.nv(), pnames.len());
    let flags = [
        ("q", a.q.as_deref()),
        ("v", a.v.as_deref()),
        ("a", a.a.as_deref()),
    ];
    run_states(&m, &a.common, &flags, |s| {
        full_regressor(&m, &mut ws, &s.q, &s.v, &s.a, a.friction, &mut y)?;
        let mut r = Report::new();
        r.add("joints", Value::Names(j.clone()))
            .add(
                "regressor",
                Value::Matrix(j.clone(), pnames.clone(), y.clone()),
            )
            .add(
                "parameters",
                Value::Vector(pnames.clone(), pi.as_slice().to_vec()),
            );
        Ok(r)
    })
}
