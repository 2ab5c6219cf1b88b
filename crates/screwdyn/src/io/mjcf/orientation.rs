//! Placement of a body, geom, site or inertial frame in its parent: `pos` and one of MuJoCo's
//! orientation forms, `quat` (w first, normalised), `axisangle`, `euler` (the compiler's
//! `eulerseq`), `xyaxes` and `zaxis`, all giving `R` of `H = (R, pos)`.

use super::compiler::Compiler;
use super::values::Values;
use crate::error::Result;
use crate::spatial::Se3;
use nalgebra::{Matrix3, Quaternion, Unit, UnitQuaternion, Vector3};

/// `R` of the element's orientation (identity when it gives none). Two forms at once are an
/// error, as in MuJoCo.
pub(crate) fn rotation(v: &Values, compiler: &Compiler) -> Result<Matrix3<f64>> {
    let forms = ["quat", "axisangle", "euler", "xyaxes", "zaxis"];
    let given: Vec<&str> = forms
        .iter()
        .copied()
        .filter(|f| v.element().attrs.iter().any(|a| a.name == *f))
        .collect();
    if given.len() > 1 {
        return Err(v.error(format!(
            "<{}> gives its orientation twice ({}); give one of quat, axisangle, euler, xyaxes, zaxis",
            v.element().tag,
            given.join(" and ")
        )));
    }
    let tag = &v.element().tag;
    if let Some(q) = v.numbers("quat", 4)? {
        // q = (w, x, y, z), any nonzero length: R of q/|q|.
        let q = Quaternion::new(q[0], q[1], q[2], q[3]);
        if q.norm() < 1e-12 {
            return Err(v.error(format!(
                "<{tag} quat> is zero; a rotation needs a nonzero quaternion"
            )));
        }
        return Ok(*UnitQuaternion::from_quaternion(q)
            .to_rotation_matrix()
            .matrix());
    }
    if let Some(a) = v.numbers("axisangle", 4)? {
        // R = exp([n̂] θ), n̂ = axis/|axis|.
        let axis = unit(v, "axisangle", Vector3::new(a[0], a[1], a[2]))?;
        return Ok(
            *UnitQuaternion::from_axis_angle(&axis, compiler.angle(a[3]))
                .to_rotation_matrix()
                .matrix(),
        );
    }
    if let Some(e) = v.numbers("euler", 3)? {
        return Ok(euler(&e, compiler));
    }
    if let Some(a) = v.numbers("xyaxes", 6)? {
        // x̂ = x/|x|, ŷ = (y − (y·x̂) x̂)/|…|, ẑ = x̂ × ŷ: the columns of R.
        let x = unit(v, "xyaxes", Vector3::new(a[0], a[1], a[2]))?;
        let y = Vector3::new(a[3], a[4], a[5]);
        let y = unit(v, "xyaxes", y - x.into_inner() * y.dot(&x))?;
        let z = x.cross(&y);
        return Ok(Matrix3::from_columns(&[x.into_inner(), y.into_inner(), z]));
    }
    if let Some(z) = v.vec3("zaxis")? {
        let z = unit(v, "zaxis", z)?;
        return Ok(z_to(&z));
    }
    Ok(Matrix3::identity())
}

/// `H = (R, pos)` of the element.
pub(crate) fn pose(v: &Values, compiler: &Compiler) -> Result<Se3> {
    let p = v.vec3("pos")?.unwrap_or_else(Vector3::zeros);
    Ok(Se3::new(rotation(v, compiler)?, p))
}

/// `R = R_1 R_2 R_3` for the moving axes of lower-case letters, `R = R_3 R_2 R_1` for the fixed
/// axes of upper-case ones (mixed sequences compose each rotation on its side).
pub(crate) fn euler(angles: &[f64], compiler: &Compiler) -> Matrix3<f64> {
    let mut q = UnitQuaternion::identity();
    for (k, &letter) in compiler.eulerseq.iter().enumerate() {
        let axis = match letter.to_ascii_lowercase() {
            b'x' => Vector3::x_axis(),
            b'y' => Vector3::y_axis(),
            _ => Vector3::z_axis(),
        };
        let r = UnitQuaternion::from_axis_angle(&axis, compiler.angle(angles[k]));
        q = if letter.is_ascii_lowercase() {
            q * r
        } else {
            r * q
        };
    }
    *q.to_rotation_matrix().matrix()
}

/// The smallest rotation taking `ẑ` to `z` (a half turn about `x̂` when `z = −ẑ`), MuJoCo's
/// reading of `zaxis` and of `fromto`.
pub(crate) fn z_to(z: &Unit<Vector3<f64>>) -> Matrix3<f64> {
    let e = Vector3::z();
    let c = e.cross(z);
    let s = c.norm();
    if s < 1e-14 {
        return if z.z < 0.0 {
            Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0))
        } else {
            Matrix3::identity()
        };
    }
    let angle = s.atan2(e.dot(z));
    *UnitQuaternion::from_axis_angle(&Unit::new_normalize(c), angle)
        .to_rotation_matrix()
        .matrix()
}

/// `a/|a|`; a zero vector is an error naming the attribute.
fn unit(v: &Values, name: &str, a: Vector3<f64>) -> Result<Unit<Vector3<f64>>> {
    let scale = a.amax();
    if scale <= 0.0 || (a / scale).norm() < 1e-12 {
        return Err(v.error(format!(
            "<{} {name}> has a zero direction; it must be nonzero",
            v.element().tag
        )));
    }
    Ok(Unit::new_normalize(a / scale))
}
