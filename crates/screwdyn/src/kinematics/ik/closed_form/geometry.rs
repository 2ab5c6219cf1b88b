//! What the families are recognised by: lines that are parallel and lines that meet.

use super::super::subproblems::Axis;
use nalgebra::{Matrix3, Vector3};

/// Two axes are parallel when the sine of the angle between them is at most this (rad); axes
/// that must cross do so by more. URDF files round `π/2` to about 10 digits, which tilts axes
/// by ~10⁻⁹ rad: well inside.
pub(crate) const ANGLE_TOL: f64 = 1e-6;

/// Lines meet when they pass within this distance (m) of one point; parallel lines, or a point
/// and a line, are distinct when farther apart than this.
pub(crate) const DISTANCE_TOL: f64 = 1e-6;

/// `|ω̂_a × ω̂_b|`, the sine of the angle between two axes.
pub(crate) fn sine(a: &Axis, b: &Axis) -> f64 {
    a.w.cross(&b.w).norm()
}

/// Whether two axes are parallel (within [`ANGLE_TOL`]).
pub(crate) fn parallel(a: &Axis, b: &Axis) -> bool {
    sine(a, b) <= ANGLE_TOL
}

/// The distance from the point `x` to the line of `a`.
pub(crate) fn distance_to_line(x: &Vector3<f64>, a: &Axis) -> f64 {
    let u = x - a.r;
    (u - a.w * a.w.dot(&u)).norm()
}

/// The same line along `±n` (the sign of `ω̂·n` kept): an axis made exactly parallel to `n`.
pub(crate) fn along(a: &Axis, n: &Vector3<f64>) -> Axis {
    Axis {
        w: if a.w.dot(n) >= 0.0 { *n } else { -n },
        r: a.r,
    }
}

/// The point `x` minimising the sum of squared distances to the given (not all parallel)
/// lines, and the largest of those distances: `Σ (I − ω̂ω̂ᵀ)(x − r) = 0`.
pub(crate) fn meeting_point(axes: &[&Axis]) -> Option<(Vector3<f64>, f64)> {
    let mut a = Matrix3::zeros();
    let mut b = Vector3::zeros();
    for axis in axes {
        let projector = Matrix3::identity() - axis.w * axis.w.transpose();
        a += projector;
        b += projector * axis.r;
    }
    let x = a.try_inverse()? * b;
    let worst = axes
        .iter()
        .map(|axis| distance_to_line(&x, axis))
        .fold(0.0, f64::max);
    Some((x, worst))
}

/// Where two crossing lines meet (the midpoint of their closest points, when within
/// [`DISTANCE_TOL`]); `None` for lines parallel or passing farther apart.
pub(crate) fn meet(a: &Axis, b: &Axis) -> Option<Vector3<f64>> {
    if sine(a, b) <= ANGLE_TOL {
        return None;
    }
    let (x, half_distance) = meeting_point(&[a, b])?;
    (2.0 * half_distance <= DISTANCE_TOL).then_some(x)
}

/// A unit vector perpendicular to `a`'s direction: `hint` with its part along `ω̂` removed,
/// or, when `hint` is (nearly) along `ω̂`, the coordinate axis farthest from `ω̂` treated so.
pub(crate) fn perpendicular_unit(a: &Axis, hint: &Vector3<f64>) -> Vector3<f64> {
    let across = |v: Vector3<f64>| v - a.w * a.w.dot(&v);
    let from_hint = across(*hint);
    if from_hint.norm() > 0.1 * hint.norm() {
        return from_hint.normalize();
    }
    let w = a.w.abs();
    let axis = if w.x <= w.y && w.x <= w.z {
        Vector3::x()
    } else if w.y <= w.z {
        Vector3::y()
    } else {
        Vector3::z()
    };
    across(axis).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_meet_where_they_cross() {
        let a = Axis::through(Vector3::new(1.0, 0.0, 0.0), Vector3::z());
        let b = Axis::through(Vector3::new(0.0, 0.0, 2.0), Vector3::x());
        let x = meet(&a, &b).unwrap();
        assert!((x - Vector3::new(1.0, 0.0, 2.0)).norm() < 1e-15);
        let c = Axis::through(Vector3::new(0.0, 0.1, 2.0), Vector3::x());
        assert!(meet(&a, &c).is_none());
        assert!(meet(&a, &along(&b, &Vector3::z())).is_none());
        for hint in [Vector3::z(), Vector3::new(0.3, -0.2, 1.0)] {
            let p = perpendicular_unit(&a, &hint);
            assert!(p.dot(&a.w).abs() < 1e-15 && (p.norm() - 1.0).abs() < 1e-15);
        }
    }
}
