//! The checks every dynamics algorithm makes before it writes: the workspace is the model's,
//! each joint vector has `nq` finite entries, external wrenches were made for the model; then
//! forward kinematics, which all of them start with.

use super::wrenches::ExternalWrenches;
use crate::error::Result;
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::Real;
use crate::workspace::Workspace;

/// Checks `ws`, `q`, the named joint vectors and `fext` against `model`, then runs forward
/// kinematics (`ws.pose_in_parent`, `ws.pose_in_world`).
pub(crate) fn checked_poses<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    vectors: &[(&[T], &str)],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<()> {
    checked_vectors(model, vectors)?;
    if let Some(f) = fext {
        f.check(model)?;
    }
    forward_kinematics(model, ws, q)
}

/// Checks that each named joint vector has `nq` finite entries.
fn checked_vectors<T: Real>(model: &Model<T>, vectors: &[(&[T], &str)]) -> Result<()> {
    for (x, what) in vectors {
        model.check_vector(x, what)?;
    }
    Ok(())
}
