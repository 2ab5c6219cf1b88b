//! Forward dynamics by Featherstone's articulated-body algorithm (O(n)), in the seeds' notation.

use super::rnea::base_acceleration;
use super::wrenches::ExternalWrenches;
use crate::error::{Error, Result};
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::{real, Real};
use crate::spatial::{ad, ad_transpose, Se3, SpatialInertia, Twist};
use crate::workspace::Workspace;
use nalgebra::{DVector, Matrix3, Matrix6};

/// Writes the 6×6 matrix of `𝔍^0 = Ad_{H_0^i}ᵀ 𝔍^i Ad_{H_0^i}`, body `i`'s spatial inertia
/// in the base frame, into `out`, given `H_i^0 = (R, p)` and the body-frame parameters: the
/// centre of mass moves to `c⁰ = R c + p`, the rotational inertia about it turns to
/// `I_c⁰ = R I_c Rᵀ` (symmetric, six entries formed), and the matrix is
/// `[I_c⁰ − m[c⁰][c⁰]  m[c⁰]; −m[c⁰]  m·1]` (the parallel-axis theorem of seed 003).
/// Returns the same inertia by its parameters `(m, c⁰, I_c⁰)`, for the momentum `𝔍^0 V`.
#[inline(always)]
fn world_inertia<T: Real>(
    h: &Se3<T>,
    body: &SpatialInertia<T>,
    out: &mut Matrix6<T>,
) -> SpatialInertia<T> {
    let r = &h.rotation;
    let m = body.mass;
    let c = r * body.com + h.translation;
    let a = r * body.inertia_com;
    // I_c⁰ = A Rᵀ: entry (i, j) is row i of A dotted with row j of R.
    let dot =
        |i: usize, j: usize| a[(i, 0)] * r[(j, 0)] + a[(i, 1)] * r[(j, 1)] + a[(i, 2)] * r[(j, 2)];
    let (i00, i01, i02, i11, i12, i22) = (
        dot(0, 0),
        dot(0, 1),
        dot(0, 2),
        dot(1, 1),
        dot(1, 2),
        dot(2, 2),
    );
    let ic = Matrix3::new(i00, i01, i02, i01, i11, i12, i02, i12, i22);
    let (mx, my, mz) = (m * c.x, m * c.y, m * c.z);
    // −m[c][c] = m (cᵀc 1 − c cᵀ).
    let (xx, yy, zz) = (mx * c.x, my * c.y, mz * c.z);
    let (xy, xz, yz) = (mx * c.y, mx * c.z, my * c.z);
    let zero = T::zero();
    #[rustfmt::skip]
    let matrix = Matrix6::new(
        i00 + yy + zz, i01 - xy,      i02 - xz,      zero, -mz,  my,
        i01 - xy,      i11 + xx + zz, i12 - yz,      mz,   zero, -mx,
        i02 - xz,      i12 - yz,      i22 + xx + yy, -my,  mx,   zero,
        zero,          mz,            -my,           m,    zero, zero,
        -mz,           zero,          mx,            zero, m,    zero,
        my,            -mx,           zero,          zero, zero, m,
    );
    *out = matrix;
    SpatialInertia::new(m, c, ic)
}

/// Forward dynamics `q̈ = M⁻¹(τ − C q̇ − g)` by the articulated-body algorithm (Featherstone),
/// written with the seeds' operators and every spatial quantity in the base frame {0}
/// (`s_i = Ad_{H_i^0} S_i`, `𝔍_i^0 = Ad_{H_0^i}ᵀ 𝔍_i Ad_{H_0^i}`, twists `V_i^0 = Ad_{H_i^0} V_i`),
/// so that nothing is carried from child to parent frame:
///
/// 1. forward: `V_i = V_λ + s_i q̇_i`, `c_i = ad_{V_λ}(s_i q̇_i)` (the `ṡ_i q̇_i` of
///    `V̇_i = V̇_λ + s_i q̈_i + ṡ_i q̇_i`), `𝔍ᴬ_i = 𝔍_i^0`, `pᴬ_i = −ad_{V_i}ᵀ 𝔍_i^0 V_i − W_ext,i`;
/// 2. backward: `U_i = 𝔍ᴬ_i s_i`, `D_i = s_iᵀ U_i`, `u_i = τ_i − s_iᵀ pᴬ_i`; the parent
///    receives `𝔍ᴬ_i − U_i U_iᵀ / D_i` and `pᴬ_i + 𝔍ᵃ_i c_i + U_i u_i / D_i`;
/// 3. forward: `V̇'_i = V̇_λ + c_i`, `q̈_i = (u_i − U_iᵀ V̇'_i) / D_i`,
///    `V̇_i = V̇'_i + s_i q̈_i`, with `V̇_base = (0, −g)` (seed 000).
///
/// Writes `ws.qdd`, and `ws.screw_in_world`, `ws.twist_in_world`, `ws.twist_dot_in_world`
/// (`V̇_i^0`, the base-frame spatial acceleration) and the articulated quantities, all in the
/// base frame. Returns `ws.qdd`; `Error::Numerical` when an articulated inertia `D_i` is not
/// positive (a massless subtree).
///
/// ```
/// use screwdyn::{builtin, dynamics::aba, Workspace};
/// let m = builtin::pendulum();
/// let mut ws = Workspace::new(&m);
/// // A free pendulum at angle q: m l² q̈ = −m g l sin q.
/// let qdd = aba(&m, &mut ws, &[0.5], &[0.0], &[0.0]).unwrap();
/// assert!((qdd[0] + 9.81 * 0.5_f64.sin()).abs() < 1e-12);
/// ```
pub fn aba<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
) -> Result<&'w DVector<T>> {
    aba_with(model, ws, q, v, tau, None)
}

/// [`aba`] with external wrenches on the bodies (and tip wrenches).
pub fn aba_with<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<&'w DVector<T>> {
    model.check_vector(v, "v")?;
    model.check_vector(tau, "tau")?;
    if let Some(f) = fext {
        f.check(model)?;
    }
    forward_kinematics(model, ws, q)?;
    let n = model.nbodies();
    let (motions, parents, bodies) = (model.motions(), model.parents(), model.bodies());
    // Pass 1: twists, velocity-product accelerations, rigid-body inertias and bias wrenches.
    for i in 0..n {
        let h = &ws.pose_in_world[i];
        let s = motions[i].act(h);
        let sv = s * v[i];
        let (vi, ci) = match parents[i] {
            Some(p) => {
                let vp = ws.twist_in_world[p];
                (vp + sv, ad(&vp, &sv))
            }
            None => (sv, Twist::zeros()),
        };
        let inertia = world_inertia(h, &bodies[i].inertia, &mut ws.articulated_inertia[i]);
        let mut p = -ad_transpose(&vi, &inertia.apply(&vi));
        if let Some(f) = fext {
            p -= f.in_world_at(h, i);
        }
        ws.screw_in_world[i] = s;
        ws.twist_in_world[i] = vi;
        ws.bias_acceleration[i] = ci;
        ws.articulated_bias[i] = p;
    }
    // Pass 2: articulated inertias, from the leaves to the root.
    let tiny = model.inertia_scale() * T::default_epsilon() * real(64.0);
    for i in (0..n).rev() {
        let s = ws.screw_in_world[i];
        let ia = ws.articulated_inertia[i];
        let u = ia * s;
        let d = s.dot(&u);
        // Written to also catch NaN.
        if d.partial_cmp(&tiny) != Some(std::cmp::Ordering::Greater) {
            return Err(Error::Numerical(format!(
                "forward dynamics failed: the articulated inertia seen by joint '{}' is {:?}, so \
                 the mass matrix is singular (is the chain beyond it massless?)",
                model.joints()[i].name,
                d
            )));
        }
        let small_u = tau[i] - s.dot(&ws.articulated_bias[i]);
        ws.aba_u[i] = u;
        ws.aba_d[i] = d;
        ws.aba_small_u[i] = small_u;
        if let Some(p) = parents[i] {
            let ud = u / d;
            // 𝔍ᵃ = 𝔍ᴬ − U Uᵀ / D (symmetric), added to the parent's as it is formed.
            let parent = &mut ws.articulated_inertia[p];
            for c in 0..6 {
                for r in 0..6 {
                    parent[(r, c)] += ia[(r, c)] - ud[r] * u[c];
                }
            }
            // pᵃ = pᴬ + 𝔍ᵃ c + U u / D = pᴬ + 𝔍ᴬ c + (U / D)(u − Uᵀ c).
            let ci = ws.bias_acceleration[i];
            let pa = ws.articulated_bias[i] + ia * ci + ud * (small_u - u.dot(&ci));
            ws.articulated_bias[p] += pa;
        }
    }
    // Pass 3: accelerations, from the root to the leaves.
    let base = base_acceleration(model);
    for (i, parent) in parents.iter().enumerate() {
        let a_par = match *parent {
            Some(p) => ws.twist_dot_in_world[p],
            None => base,
        } + ws.bias_acceleration[i];
        let qdd = (ws.aba_small_u[i] - ws.aba_u[i].dot(&a_par)) / ws.aba_d[i];
        ws.qdd[i] = qdd;
        ws.twist_dot_in_world[i] = a_par + ws.screw_in_world[i] * qdd;
    }
    Ok(&ws.qdd)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    /// The base-frame inertia equals the change of frame `Ad_{H⁻¹}ᵀ 𝔍 Ad_{H⁻¹}` done with 6×6
    /// adjoint matrices (seed 001), for a body with an off-diagonal inertia and offset CoM.
    #[test]
    fn world_inertia_is_the_adjoint_change_of_frame() {
        let body = SpatialInertia::new(
            2.5,
            Vector3::new(0.1, -0.2, 0.3),
            Matrix3::new(0.3, 0.01, -0.02, 0.01, 0.2, 0.03, -0.02, 0.03, 0.25),
        );
        let h = Se3::from_rpy(0.4, -0.7, 1.9).with_translation(Vector3::new(0.5, -1.2, 0.8));
        let ad = h.inverse().adjoint_matrix();
        let expected = ad.transpose() * body.matrix() * ad;
        let mut out = Matrix6::zeros();
        let params = world_inertia(&h, &body, &mut out);
        assert!((out - expected).amax() < 1e-12);
        assert!((params.matrix() - expected).amax() < 1e-12);
    }
}
