//! `inertia`: the inertia tensor of a shape about a point, in turned axes (the box about
//! its corner, the cylinder about its end). The formulas are the library's
//! [`screwdyn::inertia::Shape`].

use super::inputs::{parse_fixed, parse_numbers};
use crate::args::InertiaArgs;
use crate::output::{self, Report, Value};
use crate::CliError;
use nalgebra::{DMatrix, Vector3};
use screwdyn::inertia::Shape;
use screwdyn::spatial::Se3;

/// `screwdyn inertia SHAPE --mass M --size … [--about] [--rotate]`.
pub fn inertia(a: &InertiaArgs) -> Result<(), CliError> {
    let size = match &a.size {
        Some(s) => parse_numbers(s, "--size")?,
        None => Vec::new(),
    };
    let shape = Shape::parse(&a.shape, &size)?;
    let about = match &a.about {
        Some(s) => Vector3::from_column_slice(&parse_fixed(s, "--about", 3, "x,y,z")?),
        None => Vector3::zeros(),
    };
    let rot = match &a.rotate {
        Some(s) => {
            let r = parse_fixed(s, "--rotate", 3, "roll,pitch,yaw")?;
            Se3::from_rpy(r[0], r[1], r[2]).rotation
        }
        None => nalgebra::Matrix3::identity(),
    };
    let i = shape.inertia_about(a.mass, &about, &rot)?;
    let com = rot.transpose() * (-about);
    let xyz = crate::output::labels(&["x", "y", "z"]);
    let mut r = Report::new();
    r.add("mass", Value::Scalar(a.mass))
        .add(
            "com",
            Value::Vector(xyz.clone(), com.iter().copied().collect()),
        )
        .add(
            "inertia",
            Value::Matrix(xyz.clone(), xyz, DMatrix::from_fn(3, 3, |r, c| i[(r, c)])),
        );
    output::print(&[r], output::resolve(a.format), false)
}
