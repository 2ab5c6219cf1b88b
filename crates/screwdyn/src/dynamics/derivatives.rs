//! Analytical first-order derivatives of inverse and forward dynamics, written with the
//! operators in the base frame {0} (twists angular first, `ad`, `ad*`).
//!
//! # Notation
//!
//! Every spatial quantity is written in the base frame {0} (moments about the base origin):
//!
//! - `s_i = Ad_{H_i^0} S_i^{i,λ(i)}`: joint `i`'s screw axis (a column of the space Jacobian);
//! - `V_i = V_{λ(i)} + s_i q̇_i`: body `i`'s twist `Ad_{H_i^0} V_i^{i,0}`;
//! - `ṡ_i = ad_{V_i} s_i = ad_{V_{λ(i)}} s_i`: the time derivative of `s_i`;
//! - `A_i = A_{λ(i)} + s_i q̈_i + ṡ_i q̇_i` with `A_base = (0, −g)` (the base
//!   acceleration): `d/dt V_i + gravity`, equal to `Ad_{H_i^0} V̇_i^{i,0}`;
//! - `𝔍_i = Ad_{H_0^i}ᵀ 𝔍^{i,i} Ad_{H_0^i}`: body `i`'s spatial inertia;
//! - `W_i = 𝔍_i A_i − ad_{V_i}ᵀ 𝔍_i V_i − W_ext,i`: the Newton–Euler wrench of Lynch & Park's *Modern Robotics*
//!   backward pass, written in {0}, and `F_i = Σ_{k ⪰ i} W_k` (the subtree of `i`), so that
//!   `τ_i = s_iᵀ F_i`.
//!
//! # Derivatives of the kinematic quantities
//!
//! A body-fixed twist moves with `q_j` (`j ⪯ k`, i.e. `j` supports `k`) as
//! `∂(Ad_{H_k^0} X)/∂q_j = ad_{s_j} Ad_{H_k^0} X`, because `∂H_k^0/∂q_j = [s_j] H_k^0`. Hence,
//! for `j ⪯ k` (all other derivatives are zero):
//!
//! ```text
//! ∂s_k/∂q_j  = ad_{s_j} s_k
//! ∂V_k/∂q_j  = ad_{s_j} (V_k − V_{λ(j)})  = ad_{s_j} V_k + ṡ_j
//! ∂V_k/∂q̇_j = s_j
//! ∂A_k/∂q_j  = ad_{s_j} A_k + α_j − ad_{V_k} ṡ_j,   α_j = ad_{A_{λ(j)}} s_j + ad_{V_{λ(j)}} ṡ_j
//! ∂A_k/∂q̇_j = ad_{s_j} V_k + 2 ṡ_j
//! ∂𝔍_k/∂q_j  = −ad_{s_j}ᵀ 𝔍_k − 𝔍_k ad_{s_j}
//! ```
//!
//! (the first three are the derivatives of frame poses and twists: the space-Jacobian column
//! `s_j` moves the pose, `ad_{s_j} V_k + ṡ_j` is the derivative of the twist of any frame on
//! body `k`).
//!
//! # Derivatives of the wrenches
//!
//! With `D_k = (𝔍_k V_k)⊼ − ad_{V_k}ᵀ 𝔍_k − 𝔍_k ad_{V_k}` (`(h)⊼ X = −ad_Xᵀ h`; `D_k` is twice
//! the Coriolis factor `B(𝔍, V)` of [`coriolis_matrix`](super::coriolis_matrix), and only its
//! left half is non-zero: `D = [[D₁₁, 0], [−2[f], 0]]` with `f` the linear momentum), the
//! rigid motion of body `k` with joint `j` turns `W_k` as a wrench, `−ad_{s_j}ᵀ W_k`, and the
//! rest is linear in the subtree:
//!
//! ```text
//! ∂W_k/∂q_j  = −ad_{s_j}ᵀ (W_k + E_k) + 𝔍_k α_j + D_k ṡ_j
//! ∂W_k/∂q̇_j = 2 𝔍_k ṡ_j + D_k s_j
//! ```
//!
//! where `E_k` is the part of the external wrench fixed in the base frame (wrenches given in
//! the body frame move with the body and are covered by the first term). With the subtree sums
//! `𝔍ᶜ_j = Σ_{k⪰j} 𝔍_k`, `Dᶜ_j = Σ_{k⪰j} D_k`, `Eᶜ_j = Σ_{k⪰j} E_k` and `F'_j = F_j + Eᶜ_j`:
//!
//! ```text
//! i ⪯ j:  ∂τ_i/∂q_j  = s_iᵀ φ_j,  φ_j = −ad_{s_j}ᵀ F'_j + 𝔍ᶜ_j α_j + Dᶜ_j ṡ_j
//!         ∂τ_i/∂q̇_j = s_iᵀ ψ_j,  ψ_j = 2 𝔍ᶜ_j ṡ_j + Dᶜ_j s_j
//! j ⪯ i:  ∂τ_i/∂q_j  = (𝔍ᶜ_i s_i)ᵀ α_j + (Dᶜ_iᵀ s_i)ᵀ ṡ_j + (ad_{s_i}ᵀ Eᶜ_i)ᵀ s_j
//!         ∂τ_i/∂q̇_j = 2 (𝔍ᶜ_i s_i)ᵀ ṡ_j + (Dᶜ_iᵀ s_i)ᵀ s_j
//! ```
//!
//! (both forms agree on the diagonal), and `∂τ/∂q̈ = M` with `M_ij = s_iᵀ 𝔍ᶜ_j s_j`. Joints
//! on different branches do not couple. `∂τ/∂q̇ = 2 C` for the Christoffel-consistent Coriolis
//! matrix `C` when there is no friction (checked in the tests).
//!
//! Forward dynamics `q̈ = FD(q, q̇, τ)` satisfies `ID(q, q̇, FD(q, q̇, τ)) = τ`, so
//! `∂q̈/∂q = −M⁻¹ ∂τ/∂q|_{q̈ = FD}`, `∂q̈/∂q̇ = −M⁻¹ ∂τ/∂q̇|_{q̈ = FD}` and `∂q̈/∂τ = M⁻¹`.
//! `M⁻¹` and the two products come from articulated-body sweeps over the articulated inertias
//! of the ABA that gave `q̈` (`articulated_inverse.rs`: O(n²) each instead of the O(n³) of a
//! dense inverse and dense products) on larger models, and from a Cholesky inverse and dense
//! products on small ones, where they take fewer instructions.
//!
//! The derivative passes are one forward and one backward pass, O(n d) with `d` the depth of
//! the tree (O(n²) on a chain), and allocate nothing.

use super::aba::articulated_body;
use super::articulated_inverse::articulated_inverse_and_products;
use super::cholesky::with_small_size;
use super::crba::invert_mass_matrix;
use super::inputs::checked_poses;
use super::rnea::base_acceleration;
use super::wrenches::ExternalWrenches;
use crate::error::Result;
use crate::kinematics::forward_kinematics;
use crate::model::Model;
use crate::scalar::{real, Real};
use crate::spatial::CompositeInertia;
use crate::spatial::{ad, ad_transpose, ang, hat, lin, twist, Twist, Wrench};
use crate::workspace::Workspace;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// The partial derivatives `∂τ/∂q` and `∂τ/∂q̇` of inverse dynamics
/// `τ = M(q) q̈ + C(q, q̇) q̇ + g(q) − Σ_i J_iᵀ W_ext,i` (the RNEA with gravity and
/// external wrenches), analytically (module docs give the equations). Writes `ws.dtau_dq`,
/// `ws.dtau_dv`, `ws.mass_matrix` (`= ∂τ/∂q̈`, both triangles) and `ws.tau` (`τ` itself), and
/// leaves `ws.screw_in_world`, `ws.twist_in_world` (`V_i` in {0}), `ws.twist_dot_in_world`
/// (`A_i` in {0}, gravity included) and `ws.composite_inertia` (`𝔍ᶜ_i`) set. Entry `(i, j)` of each matrix is `∂τ_i/∂x_j`, rows and
/// columns in model joint order.
///
/// External wrenches given in a body frame ([`ExternalWrenches::add_local`], tip wrenches) move
/// with their body; those given in the base frame ([`ExternalWrenches::add_world`]) stay fixed
/// in space (the convention of Pinocchio's `computeRNEADerivatives`, whose external forces are
/// body-fixed, for the former).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) for a workspace or external-wrench
/// set made for another model; `DimensionMismatch` / `NonFinite` for `q`, `v` or `a` of the
/// wrong length or with a NaN.
///
/// ```
/// use screwdyn::{builtin, dynamics::rnea_derivatives, Workspace};
/// let m = builtin::pendulum(); // m = l = 1, hanging along −y
/// let mut ws = Workspace::new(&m);
/// let q = 0.4_f64;
/// rnea_derivatives(&m, &mut ws, &[q], &[0.7], &[0.0], None).unwrap();
/// // τ = m l² q̈ + m g l sin q: ∂τ/∂q = m g l cos q, ∂τ/∂q̇ = 0.
/// assert!((ws.dtau_dq[(0, 0)] - 9.81 * q.cos()).abs() < 1e-12);
/// assert!(ws.dtau_dv[(0, 0)].abs() < 1e-12);
/// assert!((ws.mass_matrix[(0, 0)] - 1.0).abs() < 1e-12);
/// ```
pub fn rnea_derivatives<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
    a: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<()> {
    ws.check(model)?;
    ws.ensure_derivatives()?;
    checked_poses(model, ws, q, &[(v, "v"), (a, "a")], fext)?;
    derivative_passes(model, ws, v, a, fext, Kinematics::Form);
    Ok(())
}

/// `D x` for `D = [[D₁₁, 0], [−2[f], 0]]` (see [`velocity_coupling`]).
#[inline]
fn coupling_apply<T: Real>(d11: &Matrix3<T>, f: &Vector3<T>, x: &Twist<T>) -> Wrench<T> {
    let xa = Vector3::new(x[0], x[1], x[2]);
    let top = d11 * xa;
    let bottom = f.cross(&xa) * real::<T>(-2.0);
    twist(top, bottom)
}

/// The angular part of `Dᵀ y = (D₁₁ᵀ y_a + 2 f × y_l, 0)` (its linear part is zero).
#[inline]
fn coupling_transpose_apply<T: Real>(d11: &Matrix3<T>, f: &Vector3<T>, y: &Twist<T>) -> Vector3<T> {
    d11.tr_mul(&ang(y)) + f.cross(&lin(y)) * real::<T>(2.0)
}

/// `D = (𝔍 V)⊼ − ad_Vᵀ 𝔍 − 𝔍 ad_V` of one body, which has only two non-zero blocks: with
/// `𝔍 = [I [h]; [h]ᵀ m1]` (in {0}), `V = (ω, v)`, `𝔍 V = (μ, f)`,
/// `D = [[D₁₁, 0], [−2[f], 0]]`, `D₁₁ = −[μ] − (I[ω] + (I[ω])ᵀ) − (v hᵀ + h vᵀ) + 2 (h·v) 1`.
/// Returns `(D₁₁, f)`; both add over a subtree.
#[inline]
fn velocity_coupling<T: Real>(
    inertia: &CompositeInertia<T>,
    v: &Twist<T>,
) -> (Matrix3<T>, Vector3<T>) {
    let w = Vector3::new(v[0], v[1], v[2]);
    let l = Vector3::new(v[3], v[4], v[5]);
    let (i, h, m) = (&inertia.inertia_origin, &inertia.first_moment, inertia.mass);
    let mu = i * w + h.cross(&l);
    let f = l * m - h.cross(&w);
    let k = i * hat(&w);
    let hv = h.dot(&l) * real::<T>(2.0);
    let mut d = -hat(&mu);
    for r in 0..3 {
        for c in 0..3 {
            d[(r, c)] -= k[(r, c)] + k[(c, r)] + l[r] * h[c] + h[r] * l[c];
        }
        d[(r, r)] += hv;
    }
    (d, f)
}

/// Where the forward pass of [`derivative_passes`] takes `s_i`, `V_i` and `A_i` from.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kinematics {
    /// Formed here from `ws.pose_in_world`, `q̇` and `q̈` (inverse-dynamics derivatives).
    Form,
    /// Read from `ws.screw_in_world`, `ws.twist_in_world` and `ws.twist_dot_in_world`, left
    /// there by the ABA of the same call (the `q̈` passed in is that ABA's), which forms
    /// `s_i` and `V_i` by the same operations and `A_i = A_{λ(i)} + ṡ_i q̇_i + s_i q̈_i`.
    FromAba,
}

/// Both passes of [`rnea_derivatives`] given `ws.pose_in_world` (one copy, shared with
/// [`aba_derivatives`]). Each body's inertia `𝔍_i` in {0} is formed from its ten parameters
/// ([`CompositeInertia::rigid_in_world`] with the body's inertia form: `m`, `h = m c⁰`, `I_o`).
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
fn derivative_passes<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    v: &[T],
    a: &[T],
    fext: Option<&ExternalWrenches<T>>,
    kinematics: Kinematics,
) {
    let n = model.nbodies();
    let (motions, parents, bodies, joints) = (
        &model.motions()[..n],
        &model.parents()[..n],
        &model.bodies()[..n],
        &model.joints()[..n],
    );
    let forms = &model.body_inertia_form[..n];
    let (v, a) = (&v[..n], &a[..n]);
    let base = base_acceleration(model);
    let two: T = real(2.0);
    let fixed = fext.is_some_and(|f| f.has_world());
    // The workspace's buffers borrowed once, as slices of length n (the n×n matrices column
    // by column, entry (r, c) at r + c n): their addresses stay in registers across the stores.
    let Workspace {
        pose_in_world,
        screw_in_world,
        screw_rate_in_world,
        twist_in_world,
        twist_dot_in_world,
        acceleration_derivative_in_world,
        composite_inertia,
        subtree_velocity_coupling,
        subtree_linear_momentum,
        subtree_wrench_in_world,
        subtree_fixed_external_wrench,
        tau,
        dtau_dq,
        dtau_dv,
        mass_matrix,
        ..
    } = ws;
    let poses = &pose_in_world[..n];
    let screws = &mut screw_in_world[..n];
    let screw_rates = &mut screw_rate_in_world[..n];
    let twists = &mut twist_in_world[..n];
    let accels = &mut twist_dot_in_world[..n];
    let alphas = &mut acceleration_derivative_in_world[..n];
    let inertias = &mut composite_inertia[..n];
    let couplings = &mut subtree_velocity_coupling[..n];
    let momenta = &mut subtree_linear_momentum[..n];
    let wrenches = &mut subtree_wrench_in_world[..n];
    let fixed_wrenches = &mut subtree_fixed_external_wrench[..n];
    let tau = &mut tau.as_mut_slice()[..n];
    let dtau_dq = &mut dtau_dq.as_mut_slice()[..n * n];
    let dtau_dv = &mut dtau_dv.as_mut_slice()[..n * n];
    let mass_matrix = &mut mass_matrix.as_mut_slice()[..n * n];
    // Forward pass: s_i, ṡ_i, V_i, A_i, α_i, 𝔍_i, D_i and W_i (+ E_i), all in {0}.
    for i in 0..n {
        let h = &poses[i];
        let (vp, ap) = match parents[i] {
            Some(p) => (twists[p], accels[p]),
            None => (Twist::zeros(), base),
        };
        // s_i, V_i = V_λ + s_i q̇_i, ṡ_i = ad_{V_λ} s_i, A_i = A_λ + s_i q̈_i + ṡ_i q̇_i.
        let (s, vi, sdot, ai) = match kinematics {
            Kinematics::Form => {
                let s = motions[i].act(h);
                let sdot = ad(&vp, &s);
                (s, vp + s * v[i], sdot, ap + s * a[i] + sdot * v[i])
            }
            Kinematics::FromAba => {
                let s = screws[i];
                (s, twists[i], ad(&vp, &s), accels[i])
            }
        };
        let alpha = ad(&ap, &s) + ad(&vp, &sdot);
        let inertia = CompositeInertia::rigid_in_world_with_form(&bodies[i].inertia, &forms[i], h);
        let momentum = inertia.apply(&vi);
        let mut w = inertia.apply(&ai) - ad_transpose(&vi, &momentum);
        let mut fixed_in_space = Wrench::zeros();
        if let Some(f) = fext {
            w -= f.in_world_at(h, i);
            if let Some(e) = f.world_part(i) {
                fixed_in_space = *e;
            }
        }
        let (d11, lin_momentum) = velocity_coupling(&inertia, &vi);
        screws[i] = s;
        screw_rates[i] = sdot;
        twists[i] = vi;
        accels[i] = ai;
        alphas[i] = alpha;
        inertias[i] = inertia;
        couplings[i] = d11;
        momenta[i] = lin_momentum;
        wrenches[i] = w + fixed_in_space;
        fixed_wrenches[i] = fixed_in_space;
    }
    if !model.is_chain {
        dtau_dq.fill(T::zero());
        dtau_dv.fill(T::zero());
        mass_matrix.fill(T::zero());
    }
    // Backward pass: subtree sums, then the row and column of every joint with its ancestors.
    for j in (0..n).rev() {
        let (s, sdot, alpha) = (screws[j], screw_rates[j], alphas[j]);
        let ic = inertias[j];
        let (d11, lm) = (couplings[j], momenta[j]);
        let (fc, ec) = (wrenches[j], fixed_wrenches[j]);
        // τ_j = s_jᵀ W_j + I_a,j q̈_j; the armature adds I_a,j to M_jj = ∂τ_j/∂q̈_j and nothing
        // to ∂τ/∂q or ∂τ/∂q̇ (it is constant).
        let armature = joints[j].armature;
        tau[j] = s.dot(&(fc - ec)) + armature * a[j];
        let ic_sdot = ic.apply(&sdot);
        let phi = ic.apply(&alpha) + coupling_apply(&d11, &lm, &sdot) - ad_transpose(&s, &fc);
        let psi = ic_sdot * two + coupling_apply(&d11, &lm, &s);
        let g = ic.apply(&s);
        let g2 = g * two;
        let hh = coupling_transpose_apply(&d11, &lm, &s);
        let e = ad_transpose(&s, &ec);
        let jj = j + j * n;
        dtau_dq[jj] = g.dot(&alpha) + hh.dot(&ang(&sdot));
        dtau_dv[jj] = g2.dot(&sdot) + hh.dot(&ang(&s));
        mass_matrix[jj] = g.dot(&s) + armature;
        let mut k = j;
        while let Some(p) = parents[k] {
            k = p;
            let (sk, sdk, ak) = (&screws[k], &screw_rates[k], &alphas[k]);
            let mut dq_jk = g.dot(ak) + hh.dot(&ang(sdk));
            if fixed {
                dq_jk += e.dot(sk);
            }
            let (dq_kj, dv_kj) = (sk.dot(&phi), sk.dot(&psi));
            let dv_jk = g2.dot(sdk) + hh.dot(&ang(sk));
            let mkj = sk.dot(&g);
            // Entry (k, j) of column j, and (j, k) of column k.
            let (kj, jk) = (k + j * n, j + k * n);
            dtau_dq[kj] = dq_kj;
            dtau_dv[kj] = dv_kj;
            dtau_dq[jk] = dq_jk;
            dtau_dv[jk] = dv_jk;
            mass_matrix[kj] = mkj;
            mass_matrix[jk] = mkj;
        }
        if let Some(p) = parents[j] {
            inertias[p].add(&ic);
            couplings[p] += d11;
            momenta[p] += lm;
            wrenches[p] += fc;
            if fixed {
                fixed_wrenches[p] += ec;
            }
        }
    }
}

/// The partial derivatives of forward dynamics `q̈ = M⁻¹(τ − C q̇ − g + Σ_i J_iᵀ W_ext,i)`:
/// `∂q̈/∂q = −M⁻¹ ∂τ/∂q`, `∂q̈/∂q̇ = −M⁻¹ ∂τ/∂q̇` (the inverse-dynamics derivatives of
/// [`rnea_derivatives`] taken at `q̈ = FD(q, q̇, τ)`) and `∂q̈/∂τ = M⁻¹`. Writes `ws.qdd`
/// (forward dynamics by the articulated-body algorithm, [`aba`](super::aba)), `ws.dqdd_dq`, `ws.dqdd_dv`, `ws.mass_matrix_inverse`,
/// and everything [`rnea_derivatives`] writes. Entry `(i, j)` is `∂q̈_i/∂x_j`. From 10 joints
/// on `M⁻¹` is formed by an articulated-body sweep over ABA's articulated inertias, and from
/// 20 joints on the products too (O(n²) each instead of O(n³)).
///
/// # Errors
/// As [`rnea_derivatives`] (with `tau` for `a`), and
/// [`Error::Numerical`](crate::Error::Numerical) when the mass matrix is singular.
///
/// ```
/// use screwdyn::{builtin, dynamics::aba_derivatives, Workspace};
/// let m = builtin::pendulum(); // m = l = 1: q̈ = τ − g sin q
/// let mut ws = Workspace::new(&m);
/// let q = 0.4_f64;
/// aba_derivatives(&m, &mut ws, &[q], &[0.7], &[0.3], None).unwrap();
/// assert!((ws.dqdd_dq[(0, 0)] + 9.81 * q.cos()).abs() < 1e-12);
/// assert!(ws.dqdd_dv[(0, 0)].abs() < 1e-12);
/// assert!((ws.mass_matrix_inverse[(0, 0)] - 1.0).abs() < 1e-12);
/// ```
pub fn aba_derivatives<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<()> {
    ws.check(model)?;
    ws.ensure_derivatives()?;
    // ABA checks q, q̇, τ and the wrenches.
    articulated_body(model, ws, q, v, tau, fext)?;
    // Poses are those of `q` (set by ABA); q̈ is read from a moved-out buffer (no allocation).
    let qdd = std::mem::replace(&mut ws.qdd, DVector::zeros(0));
    derivative_passes(model, ws, v, qdd.as_slice(), fext, Kinematics::FromAba);
    ws.qdd = qdd;
    // M⁻¹ and ∂q̈/∂x = −M⁻¹ ∂τ/∂x: by articulated-body sweeps on larger models, by a Cholesky
    // inverse and dense products (fewer instructions there) on small ones.
    let n = model.nv();
    let (inverse, products) = (n >= INVERSE_SWEEP_FROM, n >= PRODUCT_SWEEP_FROM);
    if !inverse {
        invert_mass_matrix(model, ws)?;
    }
    articulated_inverse_and_products(model, ws, inverse, products);
    if !products {
        negated_product(&ws.mass_matrix_inverse, &ws.dtau_dq, &mut ws.dqdd_dq, n);
        negated_product(&ws.mass_matrix_inverse, &ws.dtau_dv, &mut ws.dqdd_dv, n);
    }
    Ok(())
}

/// From this many joints on, `M⁻¹` is formed by an articulated-body sweep
/// ([`articulated_inverse_and_products`]), below by a Cholesky inverse (measured by instruction
/// counts: BENCHMARKS.md, "ABA derivatives: `M⁻¹` by an articulated-body sweep").
const INVERSE_SWEEP_FROM: usize = 10;

/// From this many joints on, `−M⁻¹ ∂τ/∂x` is formed by articulated-body sweeps, below by dense
/// products with `M⁻¹`.
const PRODUCT_SWEEP_FROM: usize = 20;

/// `out = −a b` for n×n matrices, column by column as sums of columns of `a` (a plain loop:
/// `gemm` may allocate packing buffers), compiled for the size at hand ([`with_small_size`]).
fn negated_product<T: Real>(a: &DMatrix<T>, b: &DMatrix<T>, out: &mut DMatrix<T>, n: usize) {
    let (a, b) = (a.as_slice(), b.as_slice());
    let out = out.as_mut_slice();
    if n > SMALL_SIZES {
        negated_product_four_columns(a, b, out, n);
    } else {
        with_small_size!(n, |m| negated_product_columns(a, b, out, m));
    }
}

/// The sizes [`with_small_size`] compiles separately (1–12).
const SMALL_SIZES: usize = 12;

/// [`negated_product`] for larger `n`: four columns of `out` at a time, so that each column of
/// `a` is read once per four output columns (on a 200-joint chain `a` no longer fits the first
/// cache level and the one-column loop read it `n` times). Every entry sums the same terms in
/// the same order as [`negated_product_columns`]: `out_rj = Σ_k a_rk (−b_kj)`, `k` ascending.
fn negated_product_four_columns<T: Real>(a: &[T], b: &[T], out: &mut [T], n: usize) {
    let (a, b, out) = (&a[..n * n], &b[..n * n], &mut out[..n * n]);
    let mut groups = out.chunks_exact_mut(4 * n);
    for (g, group) in groups.by_ref().enumerate() {
        group.fill(T::zero());
        let (c0, rest) = group.split_at_mut(n);
        let (c1, rest) = rest.split_at_mut(n);
        let (c2, c3) = rest.split_at_mut(n);
        let j = 4 * g;
        for (k, ak) in a.chunks_exact(n).enumerate() {
            let (x0, x1, x2, x3) = (
                -b[j * n + k],
                -b[(j + 1) * n + k],
                -b[(j + 2) * n + k],
                -b[(j + 3) * n + k],
            );
            for ((((y, o0), o1), o2), o3) in ak
                .iter()
                .zip(c0.iter_mut())
                .zip(c1.iter_mut())
                .zip(c2.iter_mut())
                .zip(c3.iter_mut())
            {
                *o0 += *y * x0;
                *o1 += *y * x1;
                *o2 += *y * x2;
                *o3 += *y * x3;
            }
        }
    }
    // The last n mod 4 columns one by one.
    let done = n - n % 4;
    for (c, col) in groups.into_remainder().chunks_exact_mut(n).enumerate() {
        let j = done + c;
        col.fill(T::zero());
        for (k, ak) in a.chunks_exact(n).enumerate() {
            let x = -b[j * n + k];
            for (o, y) in col.iter_mut().zip(ak) {
                *o += *y * x;
            }
        }
    }
}

/// [`negated_product`] on column-major slices.
#[inline(always)]
fn negated_product_columns<T: Real>(a: &[T], b: &[T], out: &mut [T], n: usize) {
    let (a, b, out) = (&a[..n * n], &b[..n * n], &mut out[..n * n]);
    for (j, col) in out.chunks_exact_mut(n).enumerate() {
        col.fill(T::zero());
        for (k, ak) in a.chunks_exact(n).enumerate() {
            let x = -b[j * n + k];
            for (o, y) in col.iter_mut().zip(ak) {
                *o += *y * x;
            }
        }
    }
}

/// The derivatives of frame `frame`'s twist with respect to `q` and `q̇` (6 × n each, angular
/// rows first): with `b` the frame's body, `s_j = Ad_{H_j^0} S_j` and `ṡ_j = ad_{V_λ(j)} s_j`,
/// for every joint `j` supporting `b` (other columns zero)
///
/// - `Reference::World` (spatial twist `V_f^{0,0}` in {0}): `∂V/∂q_j = ad_{s_j} V_b + ṡ_j`,
///   `∂V/∂q̇_j = s_j` (the space Jacobian);
/// - `Reference::Local` (body twist `V_f^{f,0}`): `∂V/∂q_j = Ad_{H_f^0}⁻¹ ṡ_j`,
///   `∂V/∂q̇_j = Ad_{H_f^0}⁻¹ s_j` (the body Jacobian),
///
/// because `∂H_f^0/∂q_j = [s_j] H_f^0` (the pose derivative: the space-Jacobian column). Writes
/// `ws.pose_in_world`, `ws.screw_in_world`, `ws.twist_in_world` and `ws.screw_rate_in_world`.
///
/// # Errors
/// `InvalidArgument` for an unknown frame, a workspace made for another model, output
/// matrices that are not 6 × n, or `Reference::LocalWorldAligned` (not provided);
/// `DimensionMismatch` / `NonFinite` for bad `q` or `v`.
///
/// ```
/// use nalgebra::Matrix6xX;
/// use screwdyn::{builtin, dynamics::frame_velocity_derivatives, kinematics::Reference, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let (mut dq, mut dv) = (Matrix6xX::zeros(2), Matrix6xX::zeros(2));
/// let tip = m.frame_id("link2").unwrap();
/// frame_velocity_derivatives(&m, &mut ws, tip, Reference::Local, &[0.0, 0.0], &[1.0, 0.0],
///                            &mut dq, &mut dv).unwrap();
/// // At q1 = 0 with q̇ = (1, 0) the tip's velocity in its own frame is (sin q2, 1 + cos q2):
/// // ∂v/∂q̇1 = (0, 2) at q2 = 0 (body Jacobian), and ∂v_x/∂q2 = cos q2 = 1.
/// assert!((dv[(4, 0)] - 2.0).abs() < 1e-12 && (dq[(3, 1)] - 1.0).abs() < 1e-12);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn frame_velocity_derivatives<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    frame: usize,
    reference: crate::kinematics::Reference,
    q: &[T],
    v: &[T],
    dv_dq: &mut nalgebra::Matrix6xX<T>,
    dv_dv: &mut nalgebra::Matrix6xX<T>,
) -> Result<()> {
    use crate::kinematics::Reference;
    ws.check(model)?;
    model.check_vector(v, "v")?;
    let n = model.nv();
    if dv_dq.ncols() != n || dv_dv.ncols() != n {
        return Err(crate::Error::InvalidArgument(format!(
            "the derivative matrices have {} and {} columns, the model has {n} joints",
            dv_dq.ncols(),
            dv_dv.ncols()
        )));
    }
    if reference == Reference::LocalWorldAligned {
        return Err(crate::Error::InvalidArgument(
            "frame velocity derivatives are given in the world or the local frame, not \
             local-world-aligned"
                .into(),
        ));
    }
    let (body, placement) = {
        let f = model.frame(frame)?;
        (f.body, f.placement)
    };
    forward_kinematics(model, ws, q)?;
    let (motions, parents) = (model.motions(), model.parents());
    for i in 0..n {
        let s = motions[i].act(&ws.pose_in_world[i]);
        let vp = parents[i].map_or(Twist::zeros(), |p| ws.twist_in_world[p]);
        ws.screw_in_world[i] = s;
        ws.screw_rate_in_world[i] = ad(&vp, &s);
        ws.twist_in_world[i] = vp + s * v[i];
    }
    dv_dq.fill(T::zero());
    dv_dv.fill(T::zero());
    let Some(b) = body else {
        return Ok(());
    };
    let pose = ws.pose_in_world[b].compose(&placement);
    let vb = ws.twist_in_world[b];
    let mut j = b;
    loop {
        let (s, sdot) = (ws.screw_in_world[j], ws.screw_rate_in_world[j]);
        let (dq, dv) = match reference {
            Reference::World => (ad(&s, &vb) + sdot, s),
            _ => (pose.inv_act_twist(&sdot), pose.inv_act_twist(&s)),
        };
        dv_dq.set_column(j, &dq);
        dv_dv.set_column(j, &dv);
        match parents[j] {
            Some(p) => j = p,
            None => break,
        }
    }
    Ok(())
}
