//! `fk` and `jacobian`.

use super::inputs::{load, names};
use super::states::run_states;
use crate::args::{FkArgs, JacobianArgs, ReferenceArg};
use crate::output::{Report, Value};
use crate::CliError;
use nalgebra::{DMatrix, Matrix6xX};
use screwdyn::kinematics::{
    compute_joint_jacobians, forward_kinematics, frame_jacobian, frame_pose, Reference,
};
use screwdyn::Workspace;

/// Row labels of a twist Jacobian: angular rows first.
pub const TWIST_ROWS: [&str; 6] = ["wx", "wy", "wz", "vx", "vy", "vz"];

/// `screwdyn fk MODEL --q ... [--frame NAME]`: `poses` maps frame → 4×4 `H_f^0`.
pub fn fk(a: &FkArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let frames: Vec<usize> = match &a.frame {
        Some(name) => vec![m.frame_id(name)?],
        None => (0..m.frames().len()).collect(),
    };
    let joints = names(&m);
    let mut ws = Workspace::new(&m);
    run_states(&m, &a.common, &[("q", a.q.as_deref())], |s| {
        forward_kinematics(&m, &mut ws, &s.q)?;
        let poses = frames
            .iter()
            .map(|&f| {
                let h = frame_pose(&m, &ws, f)?.to_matrix();
                let h = DMatrix::from_iterator(4, 4, h.iter().copied());
                Ok((m.frames()[f].name.clone(), Value::numbered(&h)))
            })
            .collect::<Result<Vec<_>, CliError>>()?;
        let mut r = Report::new();
        r.add("joints", Value::Names(joints.clone()))
            .add("poses", Value::Map(poses));
        Ok(r)
    })
}

/// `screwdyn jacobian MODEL --frame NAME --q ... [--reference ...]`.
pub fn jacobian(a: &JacobianArgs) -> Result<(), CliError> {
    let m = load(&a.common.model, a.common.gravity.as_deref())?;
    let f = match &a.frame {
        Some(name) => m.frame_id(name)?,
        None => m.frames().len() - 1,
    };
    let (reference, ref_name) = match a.reference {
        ReferenceArg::World => (Reference::World, "world"),
        ReferenceArg::Local => (Reference::Local, "local"),
        ReferenceArg::WorldAligned => (Reference::LocalWorldAligned, "world-aligned"),
    };
    let joints = names(&m);
    let name = m.frames()[f].name.clone();
    let rows = crate::output::labels(&TWIST_ROWS);
    let mut ws = Workspace::new(&m);
    run_states(&m, &a.common, &[("q", a.q.as_deref())], |s| {
        compute_joint_jacobians(&m, &mut ws, &s.q)?;
        let mut j = Matrix6xX::zeros(m.nq());
        frame_jacobian(&m, &ws, f, reference, &mut j)?;
        let j = DMatrix::from_iterator(6, m.nq(), j.iter().copied());
        let mut r = Report::new();
        r.add("joints", Value::Names(joints.clone()))
            .add("frame", Value::Text(name.clone()))
            .add("reference", Value::Text(ref_name.into()))
            .add("jacobian", Value::Matrix(rows.clone(), joints.clone(), j));
        Ok(r)
    })
}
