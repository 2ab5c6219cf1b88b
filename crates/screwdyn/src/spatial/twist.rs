//! Twists, wrenches and screws as angular-first 6-vectors, and the Lie bracket `ad`.
//!
//! Lynch & Park, *Modern Robotics*: a twist is `V = (ω, v) ∈ R⁶`, a wrench `W = (m, f) ∈ (R⁶)*`, and `Wᵀ V` is power.
//! A joint's screw axis `S` is a unit twist: revolute `S = (n̂, −n̂ × r)`, prismatic `S = (0, n̂)`,
//! helical `S = (n̂, −n̂ × r + h n̂)` with pitch `h`.

use super::so3::hat;
use crate::scalar::Real;
use nalgebra::{Matrix6, Vector3, Vector6};

/// A twist `V = (ω, v)`, angular part first.
pub type Twist<T = f64> = Vector6<T>;
/// A wrench `W = (m, f)`, moment first.
pub type Wrench<T = f64> = Vector6<T>;

/// The angular part `ω` (or moment `m`) of a 6-vector.
#[inline(always)]
pub fn ang<T: Real>(v: &Vector6<T>) -> Vector3<T> {
    Vector3::new(v[0], v[1], v[2])
}

/// The linear part `v` (or force `f`) of a 6-vector.
#[inline(always)]
pub fn lin<T: Real>(v: &Vector6<T>) -> Vector3<T> {
    Vector3::new(v[3], v[4], v[5])
}

/// Assembles `(a, l)` into a 6-vector.
///
/// ```
/// use nalgebra::Vector3;
/// let v = screwdyn::spatial::twist(Vector3::new(1.0, 2.0, 3.0), Vector3::new(4.0, 5.0, 6.0));
/// assert_eq!(v[2], 3.0);
/// assert_eq!(screwdyn::spatial::lin(&v), Vector3::new(4.0, 5.0, 6.0));
/// ```
#[inline(always)]
pub fn twist<T: Real>(a: Vector3<T>, l: Vector3<T>) -> Vector6<T> {
    Vector6::new(a.x, a.y, a.z, l.x, l.y, l.z)
}

/// The screw axis of a revolute joint about unit axis `n` through the point `r`:
/// `S = (n̂, −n̂ × r)` (Lynch & Park, *Modern Robotics*).
///
/// ```
/// use nalgebra::Vector3;
/// let s = screwdyn::spatial::revolute_screw(Vector3::z(), Vector3::new(-1.0, 0.0, 0.0));
/// assert_eq!(s, nalgebra::Vector6::new(0.0, 0.0, 1.0, 0.0, 1.0, 0.0));
/// ```
pub fn revolute_screw<T: Real>(n: Vector3<T>, r: Vector3<T>) -> Twist<T> {
    twist(n, -n.cross(&r))
}

/// The screw axis of a prismatic joint along the unit axis `n`: `S = (0, n̂)`.
pub fn prismatic_screw<T: Real>(n: Vector3<T>) -> Twist<T> {
    twist(Vector3::zeros(), n)
}

/// The screw axis of a helical joint about unit axis `n` through `r` with pitch `h`
/// (translation per radian): `S = (n̂, −n̂ × r + h n̂)`.
pub fn helical_screw<T: Real>(n: Vector3<T>, r: Vector3<T>, pitch: T) -> Twist<T> {
    twist(n, -n.cross(&r) + n * pitch)
}

/// `ad_V X = (ω × ω_x, v × ω_x + ω × v_x)`: the Lie bracket `[V, X]` of se(3) applied to a
/// twist (Lynch & Park, *Modern Robotics*: `V̇_c = Ad V̇_p − ad_{S q̇}(Ad V_p) + S q̈`).
///
/// ```
/// use nalgebra::Vector6;
/// let v = Vector6::new(0.1, -0.2, 0.3, 1.0, 2.0, 3.0);
/// assert!(screwdyn::spatial::ad(&v, &v).norm() < 1e-15); // ad_V V = 0
/// ```
#[inline]
pub fn ad<T: Real>(v: &Twist<T>, x: &Twist<T>) -> Twist<T> {
    let w = ang(v);
    let wx = ang(x);
    twist(w.cross(&wx), lin(v).cross(&wx) + w.cross(&lin(x)))
}

/// `ad_Vᵀ W = (−ω × m − v × f, −ω × f)`, the transpose of `ad_V` applied to a wrench
/// (Lynch & Park, *Modern Robotics* backward pass: `W = 𝔍 V̇ − ad_Vᵀ 𝔍 V`).
///
/// ```
/// use nalgebra::Vector6;
/// use screwdyn::spatial::{ad, ad_transpose};
/// let (v, x, w) = (Vector6::new(0.1_f64, -0.2, 0.3, 1.0, 2.0, 3.0),
///                  Vector6::new(0.5, 0.1, -0.7, 0.2, 0.0, 1.0),
///                  Vector6::new(1.0, 2.0, 3.0, -1.0, 0.5, 0.2));
/// let r: f64 = ad_transpose(&v, &w).dot(&x) - w.dot(&ad(&v, &x));
/// assert!(r.abs() < 1e-14);
/// ```
#[inline]
pub fn ad_transpose<T: Real>(v: &Twist<T>, w: &Wrench<T>) -> Wrench<T> {
    let om = ang(v);
    let f = lin(w);
    twist(-om.cross(&ang(w)) - lin(v).cross(&f), -om.cross(&f))
}

/// The 6×6 matrix `ad_V = [[ω] 0; [v] [ω]]` (for teaching and the closed form).
///
/// ```
/// use nalgebra::Vector6;
/// let v = Vector6::new(0.1, -0.2, 0.3, 1.0, 2.0, 3.0);
/// let x = Vector6::new(0.5, 0.1, -0.7, 0.2, 0.0, 1.0);
/// assert!((screwdyn::spatial::ad_matrix(&v) * x - screwdyn::spatial::ad(&v, &x)).norm() < 1e-15);
/// ```
pub fn ad_matrix<T: Real>(v: &Twist<T>) -> Matrix6<T> {
    let mut m = Matrix6::zeros();
    let w = hat(&ang(v));
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&w);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&w);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&hat(&lin(v)));
    m
}

/// The 4×4 matrix `[ξ] = [[ω] v; 0 0] ∈ se(3)` (the hat map of se(3)).
pub fn hat6<T: Real>(xi: &Twist<T>) -> nalgebra::Matrix4<T> {
    let mut m = nalgebra::Matrix4::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&hat(&ang(xi)));
    m.fixed_view_mut::<3, 1>(0, 3).copy_from(&lin(xi));
    m
}

/// The vee map of se(3): `(ω, v)` from `[[ω] v; 0 0]`.
///
/// ```
/// use nalgebra::Vector6;
/// let xi = Vector6::new(0.1, -0.2, 0.3, 1.0, 2.0, 3.0);
/// assert_eq!(screwdyn::spatial::vee6(&screwdyn::spatial::hat6(&xi)), xi);
/// ```
pub fn vee6<T: Real>(m: &nalgebra::Matrix4<T>) -> Twist<T> {
    let w = super::so3::vee(&m.fixed_view::<3, 3>(0, 0).into_owned());
    twist(w, m.fixed_view::<3, 1>(0, 3).into_owned())
}
