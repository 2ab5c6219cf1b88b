//! The native half of `screwdyn.se3`: pose helpers over plain NumPy arrays (4×4 homogeneous
//! matrices, twists angular first), each a call of the library's `spatial` module. Inputs are
//! checked there (`Se3::checked_from_matrix`, `check_rotation`, `Se3::from_quaternion`); this
//! file only checks shapes and converts.

use crate::convert::{self, contiguous, ArrayIn};
use crate::errors::{call_err, guard};
use nalgebra::{Matrix3, Matrix4, Vector3, Vector6};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use screwdyn::spatial::{self, check_rotation, Se3};

/// Adds the pose helpers to the native module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_se3_exp, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_log, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_adjoint, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_ad, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_inverse, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_from_quaternion, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_to_quaternion, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_from_rpy, m)?)?;
    m.add_function(wrap_pyfunction!(_se3_to_rpy, m)?)?;
    Ok(())
}

/// `(a, b)` as NumPy writes a shape.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        s => format!(
            "({})",
            s.iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The values of `a` when its shape is one of `shapes`, else a ValueError naming `name`.
fn values_of_shape(a: &ArrayIn<'_>, name: &str, shapes: &[&[usize]]) -> PyResult<Vec<f64>> {
    use numpy::PyUntypedArrayMethods;
    if !shapes.iter().any(|s| a.shape() == *s) {
        let expected: Vec<String> = shapes.iter().map(|s| shape_text(s)).collect();
        return Err(PyValueError::new_err(format!(
            "{name} has shape {}, expected {}",
            shape_text(a.shape()),
            expected.join(" or ")
        )));
    }
    Ok(contiguous(a).into_owned())
}

/// A finite vector of `n` values.
fn finite_vector(a: &ArrayIn<'_>, name: &str, n: usize) -> PyResult<Vec<f64>> {
    let v = values_of_shape(a, name, &[&[n]])?;
    if let Some(k) = v.iter().position(|x| !x.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{name} has a non-finite entry ({:?}) at index {k}",
            v[k]
        )));
    }
    Ok(v)
}

/// A checked pose from a `(4, 4)` array.
fn pose(a: &ArrayIn<'_>, name: &str) -> PyResult<Se3> {
    let v = values_of_shape(a, name, &[&[4, 4]])?;
    Se3::checked_from_matrix(&Matrix4::from_row_slice(&v), name).map_err(call_err)
}

/// A checked rotation from a `(3, 3)` rotation matrix or the rotation part of a `(4, 4)` pose.
fn rotation(a: &ArrayIn<'_>, name: &str) -> PyResult<Se3> {
    let v = values_of_shape(a, name, &[&[4, 4], &[3, 3]])?;
    if v.len() == 16 {
        return Se3::checked_from_matrix(&Matrix4::from_row_slice(&v), name).map_err(call_err);
    }
    let r = Matrix3::from_row_slice(&v);
    check_rotation(&r, name).map_err(call_err)?;
    Ok(Se3::new(r, Vector3::zeros()))
}

/// `translation` (default zero) set into `h`, returned as a `(4, 4)` array.
fn with_translation<'py>(
    py: Python<'py>,
    mut h: Se3,
    translation: Option<ArrayIn<'_>>,
) -> PyResult<Bound<'py, PyAny>> {
    if let Some(p) = translation {
        h.translation = Vector3::from_column_slice(&finite_vector(&p, "translation", 3)?);
    }
    pose_array(py, &h)
}

fn pose_array<'py>(py: Python<'py>, h: &Se3) -> PyResult<Bound<'py, PyAny>> {
    let mut out = vec![0.0; 16];
    convert::write_pose(h, &mut out);
    convert::array(py, out, &[4, 4])
}

fn matrix6<'py>(py: Python<'py>, m: &nalgebra::Matrix6<f64>) -> PyResult<Bound<'py, PyAny>> {
    let mut out = vec![0.0; 36];
    convert::write_rows(m, &mut out);
    convert::array(py, out, &[6, 6])
}

/// `e^{[ξ]}`: the `(4, 4)` pose of the twist `ξ = (ω, v)` `(6,)`, angular first.
#[pyfunction]
fn _se3_exp<'py>(py: Python<'py>, twist: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
    guard(|| {
        let xi = Vector6::from_column_slice(&finite_vector(&twist, "the twist", 6)?);
        pose_array(py, &Se3::exp(&xi))
    })
}

/// The twist `ξ = (ω, v)` `(6,)` with `e^{[ξ]} = H` and `|ω| ≤ π`.
#[pyfunction]
fn _se3_log<'py>(py: Python<'py>, h: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
    guard(|| convert::vector(py, pose(&h, "H")?.log().as_slice()))
}

/// `Ad_H` `(6, 6)`: maps a twist written in the moving frame to the same twist in the
/// reference frame, `[[R, 0], [[p]R, R]]`.
#[pyfunction]
fn _se3_adjoint<'py>(py: Python<'py>, h: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
    guard(|| matrix6(py, &pose(&h, "H")?.adjoint_matrix()))
}

/// `ad_V` `(6, 6)` of a twist `V = (ω, v)`: `[[[ω], 0], [[v], [ω]]]`, the Lie bracket
/// `ad_V X = [V, X]`.
#[pyfunction]
fn _se3_ad<'py>(py: Python<'py>, twist: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
    guard(|| {
        let v = Vector6::from_column_slice(&finite_vector(&twist, "the twist", 6)?);
        matrix6(py, &spatial::ad_matrix(&v))
    })
}

/// `H⁻¹ = [Rᵀ, −Rᵀp; 0, 1]`.
#[pyfunction]
fn _se3_inverse<'py>(py: Python<'py>, h: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
    guard(|| pose_array(py, &pose(&h, "H")?.inverse()))
}

/// The `(4, 4)` pose of the quaternion `(w, x, y, z)` (scalar first, normalised) and the
/// optional `translation` `(3,)`.
#[pyfunction]
#[pyo3(signature = (q, translation = None))]
fn _se3_from_quaternion<'py>(
    py: Python<'py>,
    q: ArrayIn<'py>,
    translation: Option<ArrayIn<'py>>,
) -> PyResult<Bound<'py, PyAny>> {
    guard(|| {
        let v = values_of_shape(&q, "the quaternion", &[&[4]])?;
        let h = Se3::from_quaternion([v[0], v[1], v[2], v[3]]).map_err(call_err)?;
        with_translation(py, h, translation)
    })
}

/// The unit quaternion `(w, x, y, z)` (scalar first, `w ≥ 0`) of a `(4, 4)` pose's or a
/// `(3, 3)` rotation's rotation.
#[pyfunction]
fn _se3_to_quaternion<'py>(py: Python<'py>, h: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
    guard(|| convert::vector(py, &rotation(&h, "H")?.quaternion()))
}

/// The `(4, 4)` pose of the URDF angles `rpy = (roll, pitch, yaw)`,
/// `R = Rz(yaw) Ry(pitch) Rx(roll)`, and the optional `translation` `(3,)`.
#[pyfunction]
#[pyo3(signature = (rpy, translation = None))]
fn _se3_from_rpy<'py>(
    py: Python<'py>,
    rpy: ArrayIn<'py>,
    translation: Option<ArrayIn<'py>>,
) -> PyResult<Bound<'py, PyAny>> {
    guard(|| {
        let a = finite_vector(&rpy, "rpy", 3)?;
        with_translation(py, Se3::from_rpy(a[0], a[1], a[2]), translation)
    })
}

/// The URDF angles `(roll, pitch, yaw)` of a `(4, 4)` pose's or a `(3, 3)` rotation's rotation
/// (pitch in `[−π/2, π/2]`; at `|pitch| = π/2` roll is 0 and yaw takes the whole turn).
#[pyfunction]
fn _se3_to_rpy<'py>(py: Python<'py>, h: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
    guard(|| {
        let (r, p, y) = rotation(&h, "H")?.rpy();
        convert::vector(py, &[r, p, y])
    })
}
