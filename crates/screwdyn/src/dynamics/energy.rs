//! Kinetic, potential and total energy, mechanical power and the centre of mass (Lynch & Park, *Modern Robotics*).

use super::crba::crba;
use crate::error::{Error, Result};
use crate::kinematics::{forward_kinematics, forward_velocity};
use crate::model::Model;
use crate::scalar::{real, Real};
use crate::workspace::Workspace;
use nalgebra::Vector3;

/// Kinetic energy as the sum over links, `E_kin = ½ Σ_i V_iᵀ 𝔍^{i,i} V_i` (Lynch & Park, *Modern Robotics*), plus the
/// rotors' `½ Σ_i I_a,i q̇_i²` (each joint's armature, [`Joint::armature`](crate::model::Joint::armature)),
/// so that it equals `½ q̇ᵀ M(q) q̇`.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::kinetic_energy, Workspace};
/// let m = builtin::pendulum();
/// let mut ws = Workspace::new(&m);
/// // ½ m l² q̇² for the 1 kg, 1 m pendulum.
/// assert!((kinetic_energy(&m, &mut ws, &[0.3], &[2.0]).unwrap() - 2.0).abs() < 1e-12);
/// ```
pub fn kinetic_energy<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
) -> Result<T> {
    forward_velocity(model, ws, q, v)?;
    Ok(kinetic_energy_given_twists(model, ws, v))
}

/// `Σ_i ½ V_iᵀ 𝔍_i V_i + ½ I_a,i q̇_i²` from the body twists `ws.twist` of the last
/// [`forward_velocity`](crate::kinematics::forward_velocity) call at velocity `v` (the RNEA
/// leaves its twists in `ws.twist_in_world`, not here).
pub(crate) fn kinetic_energy_given_twists<T: Real>(
    model: &Model<T>,
    ws: &Workspace<T>,
    v: &[T],
) -> T {
    let half: T = real(0.5);
    model
        .bodies()
        .iter()
        .zip(&ws.twist)
        .zip(model.joints().iter().zip(v))
        .fold(T::zero(), |e, ((b, vi), (j, qd))| {
            e + b.inertia.kinetic_energy(vi) + half * j.armature * *qd * *qd
        })
}

/// Kinetic energy from the mass matrix, `½ q̇ᵀ M(q) q̇` (Lynch & Park, *Modern Robotics*, Craig, *Introduction to Robotics*).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::{kinetic_energy, kinetic_energy_mass_matrix}, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let a = kinetic_energy_mass_matrix(&m, &mut ws, &[0.2, 0.4], &[1.0, -2.0]).unwrap();
/// let b = kinetic_energy(&m, &mut ws, &[0.2, 0.4], &[1.0, -2.0]).unwrap();
/// assert!((a - b).abs() < 1e-12);
/// ```
pub fn kinetic_energy_mass_matrix<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
) -> Result<T> {
    model.check_vector(v, "v")?;
    let m = crba(model, ws, q)?;
    let mut e = T::zero();
    for i in 0..v.len() {
        for j in 0..v.len() {
            e += v[i] * m[(i, j)] * v[j];
        }
    }
    Ok(e * real(0.5))
}

/// Potential energy of gravity, `P = −Σ_i m_i g⁰ · p_{c,i}⁰` (by hand: `P = m g l sin θ` terms),
/// zero with every centre of mass at the base origin.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::potential_energy, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let (q1, q2) = (0.4_f64, 0.5_f64);
/// // By hand: P = (m1 + m2) g l1 sin θ1 + m2 g l2 sin(θ1 + θ2).
/// let p = potential_energy(&m, &mut ws, &[q1, q2]).unwrap();
/// assert!((p - 9.81 * (2.0 * q1.sin() + (q1 + q2).sin())).abs() < 1e-12);
/// ```
pub fn potential_energy<T: Real>(model: &Model<T>, ws: &mut Workspace<T>, q: &[T]) -> Result<T> {
    forward_kinematics(model, ws, q)?;
    Ok(potential_energy_given_poses(model, ws))
}

/// `−Σ_i m_i g⁰ · p_{c,i}⁰` from the body poses `ws.pose_in_world` of the last
/// [`forward_kinematics`] call.
pub(crate) fn potential_energy_given_poses<T: Real>(model: &Model<T>, ws: &Workspace<T>) -> T {
    let g = model.gravity();
    model
        .bodies()
        .iter()
        .zip(&ws.pose_in_world)
        .fold(T::zero(), |e, (b, h)| {
            e - g.dot(&h.act_point(&b.inertia.com)) * b.inertia.mass
        })
}

/// Total mechanical energy `E_kin + P`.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
pub fn total_energy<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
) -> Result<T> {
    let k = kinetic_energy(model, ws, q, v)?;
    let p = potential_energy(model, ws, q)?;
    Ok(k + p)
}

/// Mechanical power delivered by the joints, `τ · q̇` (Lynch & Park, *Modern Robotics*: `Wᵀ V = τ q̇`); with no gravity
/// it equals `dE_kin/dt`.
///
/// # Errors
/// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a bad `tau` or `v`.
pub fn power<T: Real>(model: &Model<T>, tau: &[T], v: &[T]) -> Result<T> {
    model.check_vector(tau, "tau")?;
    model.check_vector(v, "v")?;
    Ok(tau.iter().zip(v).fold(T::zero(), |s, (t, w)| s + *t * *w))
}

/// The centre of mass of the moving bodies in the base frame, `Σ m_i p_{c,i}⁰ / Σ m_i`;
/// `Error::Numerical` when the robot has no mass.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::center_of_mass, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let c = center_of_mass(&m, &mut ws, &[0.0, 0.0]).unwrap();
/// assert!((c.x - 1.5).abs() < 1e-15); // masses at x = 1 and x = 2
/// ```
pub fn center_of_mass<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
) -> Result<Vector3<T>> {
    forward_kinematics(model, ws, q)?;
    let mut m = T::zero();
    let mut c = Vector3::zeros();
    for (b, h) in model.bodies().iter().zip(&ws.pose_in_world) {
        m += b.inertia.mass;
        c += h.act_point(&b.inertia.com) * b.inertia.mass;
    }
    if m.partial_cmp(&T::zero()) != Some(std::cmp::Ordering::Greater) {
        return Err(Error::Numerical(
            "the centre of mass is undefined: the moving bodies have no mass".into(),
        ));
    }
    Ok(c / m)
}
