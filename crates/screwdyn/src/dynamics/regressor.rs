//! The joint-torque regressor: inverse dynamics written linearly in the inertial parameters,
//! `τ = Y(q, q̇, q̈) π`.

use super::inputs::checked_poses;
use super::rnea::{base_acceleration, rnea_passes};
use crate::error::Result;
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::{hat, SpatialInertia};
use nalgebra::{DMatrix, Matrix3, Vector3};

/// Number of standard inertial parameters per body.
pub const PARAMETERS_PER_BODY: usize = 10;

/// Names of the ten standard parameters of a body, in the order of [`body_parameters`]:
/// `m, mx, my, mz` (mass and first moment `m c`), then the rotational inertia about the body
/// frame origin `Ixx, Ixy, Iyy, Ixz, Iyz, Izz` (the order of Pinocchio's dynamic parameters).
pub const PARAMETER_NAMES: [&str; PARAMETERS_PER_BODY] = [
    "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

/// The ten standard inertial parameters of one body, all in the body frame:
/// `π = (m, m c_x, m c_y, m c_z, I_xx, I_xy, I_yy, I_xz, I_yz, I_zz)` with `I = I_c − m [c]²`
/// the rotational inertia about the body frame origin (the parallel-axis theorem). The
/// spatial inertia `𝔍 = [I  m[c]; −m[c]  m 1]` is linear in them.
///
/// ```
/// use nalgebra::{Matrix3, Vector3};
/// use screwdyn::{dynamics::body_parameters, spatial::SpatialInertia};
/// let i = SpatialInertia::new(2.0_f64, Vector3::new(0.0, 0.0, 0.5), Matrix3::identity() * 0.1);
/// let p = body_parameters(&i);
/// assert_eq!(p[0], 2.0);            // m
/// assert_eq!(p[3], 1.0);            // m c_z
/// assert!((p[4] - 0.6).abs() < 1e-15); // I_xx = 0.1 + m c_z²
/// ```
pub fn body_parameters<T: Real>(inertia: &SpatialInertia<T>) -> [T; PARAMETERS_PER_BODY] {
    let h = inertia.com * inertia.mass;
    pack_parameters(inertia.mass, &h, &inertia.inertia_about_origin())
}

/// `(m, h, I)` (mass, first moment, rotational inertia about the frame origin) in the order of
/// [`body_parameters`]: `m, h_x, h_y, h_z, I_xx, I_xy, I_yy, I_xz, I_yz, I_zz`.
pub(crate) fn pack_parameters<T: Real>(
    m: T,
    h: &Vector3<T>,
    i: &Matrix3<T>,
) -> [T; PARAMETERS_PER_BODY] {
    [
        m,
        h.x,
        h.y,
        h.z,
        i[(0, 0)],
        i[(0, 1)],
        i[(1, 1)],
        i[(0, 2)],
        i[(1, 2)],
        i[(2, 2)],
    ]
}

/// The inverse of [`body_parameters`]: the spatial inertia with these ten parameters.
/// A zero mass gives a zero first moment (the centre of mass is then set to the origin).
///
/// ```
/// use nalgebra::{Matrix3, Vector3};
/// use screwdyn::{dynamics::{body_parameters, inertia_from_parameters}, spatial::SpatialInertia};
/// let i = SpatialInertia::new(2.0, Vector3::new(0.1, -0.2, 0.5), Matrix3::identity() * 0.1);
/// let back = inertia_from_parameters(&body_parameters(&i));
/// assert!((back.matrix() - i.matrix()).amax() < 1e-14);
/// ```
pub fn inertia_from_parameters<T: Real>(p: &[T; PARAMETERS_PER_BODY]) -> SpatialInertia<T> {
    let m = p[0];
    let com = if m != T::zero() {
        Vector3::new(p[1], p[2], p[3]) / m
    } else {
        Vector3::zeros()
    };
    let io = Matrix3::new(p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9]);
    SpatialInertia::from_inertia_about_origin(m, com, io)
}

/// The standard parameters of every moving body, stacked in body (= joint) order:
/// `π = (π_1, …, π_n)`, `10 n` entries (see [`body_parameters`]). Allocates.
///
/// ```
/// let m = screwdyn::builtin::planar2();
/// let pi = screwdyn::dynamics::model_parameters(&m);
/// assert_eq!(pi.len(), 20);
/// ```
pub fn model_parameters<T: Real>(model: &Model<T>) -> nalgebra::DVector<T> {
    let mut pi = nalgebra::DVector::zeros(PARAMETERS_PER_BODY * model.nbodies());
    for (k, b) in model.bodies().iter().enumerate() {
        let p = body_parameters(&b.inertia);
        pi.rows_mut(PARAMETERS_PER_BODY * k, PARAMETERS_PER_BODY)
            .copy_from_slice(&p);
    }
    pi
}

/// The armatures' torque `I_a q̈` (`I_a,i q̈_i` per joint), the part of inverse dynamics the
/// regressor leaves out: `τ = Y π + I_a q̈`. Written into `out`.
///
/// # Errors
/// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for an `a` or `out` of the wrong length or an `a` with NaN/∞.
///
/// ```
/// use screwdyn::{builtin, dynamics::{armature_torque, model_parameters, regressor, rnea}, Workspace};
/// let m = builtin::planar2().with_armature(&[0.3, 0.1]).unwrap();
/// let mut ws = Workspace::new(&m);
/// let (q, v, a) = ([0.3, -0.5], [1.0, 0.2], [0.4, -0.1]);
/// let tau = rnea(&m, &mut ws, &q, &v, &a).unwrap().clone();
/// let mut known = [0.0; 2];
/// armature_torque(&m, &a, &mut known).unwrap();
/// assert_eq!(known, [0.3 * 0.4, 0.1 * -0.1]);
/// let y = regressor(&m, &mut ws, &q, &v, &a).unwrap();
/// let t = y * model_parameters(&m) + nalgebra::DVector::from_column_slice(&known);
/// assert!((t - tau).amax() < 1e-12);
/// ```
pub fn armature_torque<T: Real>(model: &Model<T>, a: &[T], out: &mut [T]) -> Result<()> {
    model.check_vector(a, "a")?;
    if out.len() != a.len() {
        return Err(crate::Error::DimensionMismatch {
            what: "the armature torque's output".into(),
            got: out.len(),
            expected: a.len(),
            names: format!("{} joints", a.len()),
        });
    }
    // (I_a q̈)_i = I_a,i q̈_i
    for ((o, j), &ai) in out.iter_mut().zip(model.joints()).zip(a) {
        *o = j.armature * ai;
    }
    Ok(())
}

/// `L(w)`: the 3×6 matrix with `I w = L(w) (I_xx, I_xy, I_yy, I_xz, I_yz, I_zz)`.
#[inline]
fn inertia_action<T: Real>(w: &Vector3<T>) -> nalgebra::Matrix3x6<T> {
    let z = T::zero();
    nalgebra::Matrix3x6::new(
        w.x, w.y, z, w.z, z, z, //
        z, w.x, w.y, z, w.z, z, //
        z, z, z, w.x, w.y, w.z,
    )
}

/// Writes the joint-torque regressor `Y(q, q̇, q̈)` (n × 10n) into `ws.regressor`, so that
/// `τ = Y π` for the stacked standard parameters `π` of [`model_parameters`] (inverse dynamics
/// with gravity, without external wrenches, joint friction or armature). Column `10 k + c` belongs to
/// parameter `c` of body `k` (order [`PARAMETER_NAMES`], body frame, inertia about the body
/// frame origin); entries of bodies that joint `i` does not support are zero.
///
/// Body `k`'s wrench in its frame is `W_k = Φ(V_k, V̇_k) π_k` (twists and accelerations of
/// the forward pass, gravity as the base acceleration of Lynch & Park's *Modern Robotics*), and
/// `τ_i = Σ_{k ⪰ i} (Ad_{H_k^0}⁻¹ s_i)ᵀ W_k` (the backward pass), so
/// `Y_{i, k} = (Ad_{H_k^0}⁻¹ s_i)ᵀ Φ(V_k, V̇_k)` with `s_i = Ad_{H_i^0} S_i`.
///
/// The joints' armatures are a known term, not parameters: inverse dynamics is
/// `τ = Y π + I_a q̈` with `I_a = diag(I_a,i)` taken from the model
/// ([`Joint::armature`](crate::model::Joint::armature)); identification subtracts `I_a q̈` from
/// the measured torques before fitting `π` (see [`armature_torque`]).
///
/// # Errors
/// As [`rnea`](super::rnea): a workspace made for another model, or `q`, `v`, `a` of the wrong
/// length or not finite.
///
/// ```
/// use screwdyn::{builtin, dynamics::{model_parameters, regressor, rnea}, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let (q, v, a) = ([0.3, -0.5], [1.0, 0.2], [0.4, -0.1]);
/// let tau = rnea(&m, &mut ws, &q, &v, &a).unwrap().clone();
/// let y = regressor(&m, &mut ws, &q, &v, &a).unwrap();
/// let t = y * model_parameters(&m);
/// assert!((t - tau).amax() < 1e-12);
/// ```
pub fn regressor<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut crate::Workspace<T>,
    q: &[T],
    v: &[T],
    a: &[T],
) -> Result<&'w DMatrix<T>> {
    ws.check(model)?;
    ws.ensure_regressor()?;
    checked_poses(model, ws, q, &[(v, "v"), (a, "a")], None)?;
    rnea_passes(
        model,
        ws,
        Some(v),
        |i| a[i],
        &base_acceleration(model),
        None,
    );
    let n = model.nbodies();
    let (motions, parents) = (model.motions(), model.parents());
    for (i, m) in motions.iter().enumerate() {
        ws.screw_in_world[i] = m.act(&ws.pose_in_world[i]);
    }
    let y = &mut ws.regressor;
    y.fill(T::zero());
    // Φ(V_k, V̇_k) by blocks, with V = (ω, v) and a = v̇ + ω × v (the acceleration of the frame
    // origin): mass column (0, a); first moment (−[a], [ω̇] + [ω]²); rotational inertia about
    // the origin (L(ω̇) + [ω] L(ω), 0), L(w) the 3×6 matrix with I w = L(w) (I_xx, …, I_zz).
    for k in 0..n {
        let (vk, vdk) = (&ws.twist[k], &ws.twist_dot[k]);
        let w = Vector3::new(vk[0], vk[1], vk[2]);
        let lv = Vector3::new(vk[3], vk[4], vk[5]);
        let wd = Vector3::new(vdk[0], vdk[1], vdk[2]);
        let acc = Vector3::new(vdk[3], vdk[4], vdk[5]) + w.cross(&lv);
        let (hw, hwd) = (hat(&w), hat(&wd));
        let first_moment_force = hwd + hw * hw;
        let first_moment_moment = -hat(&acc);
        let inertia_moment = inertia_action(&wd) + hw * inertia_action(&w);
        let col = PARAMETERS_PER_BODY * k;
        let mut i = k;
        loop {
            // Joint i's screw written in frame k.
            let s = ws.pose_in_world[k].inv_act_twist(&ws.screw_in_world[i]);
            let (sw, sl) = (
                Vector3::new(s[0], s[1], s[2]),
                Vector3::new(s[3], s[4], s[5]),
            );
            y[(i, col)] = sl.dot(&acc);
            let h = first_moment_moment.tr_mul(&sw) + first_moment_force.tr_mul(&sl);
            for c in 0..3 {
                y[(i, col + 1 + c)] = h[c];
            }
            let r = inertia_moment.tr_mul(&sw);
            for c in 0..6 {
                y[(i, col + 4 + c)] = r[c];
            }
            match parents[i] {
                Some(p) => i = p,
                None => break,
            }
        }
    }
    Ok(&ws.regressor)
}
