//! Forward dynamics three ways: ABA, CRBA + Cholesky, and the Walker–Orin simulator method
//! (Walker & Orin, 1982)

use super::aba::{articulated_body, articulated_body_for_stepper};
use super::cholesky::{cholesky_in_place, cholesky_solve_in_place, singular_error};
use super::crba::crba_given_poses;
use super::inputs::checked_poses;
use super::rnea::rnea_passes;
use super::rnea_in_world::rnea_in_world_passes;
use super::wrenches::ExternalWrenches;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::Twist;
use crate::workspace::Workspace;
use nalgebra::DVector;

/// How [`forward_dynamics`] solves `M q̈ = τ − b`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ForwardMethod {
    /// Featherstone's articulated-body algorithm, O(n).
    #[default]
    Aba,
    /// `M` by CRBA, `b` by RNEA, then a Cholesky solve, O(n³).
    Crba,
    /// Walker & Orin's method: `b` by RNEA with `q̈ = 0`, `M` column by column by RNEA with
    /// `q̈ = e_j` and no velocity, gravity or external wrench, then solve `M q̈ = τ − b`.
    WalkerOrin,
}

impl std::str::FromStr for ForwardMethod {
    type Err = crate::Error;
    fn from_str(s: &str) -> std::result::Result<Self, crate::Error> {
        match crate::error::choice_key(s).as_str() {
            "aba" => Ok(ForwardMethod::Aba),
            "crba" => Ok(ForwardMethod::Crba),
            "walker-orin" => Ok(ForwardMethod::WalkerOrin),
            _ => Err(crate::Error::UnknownChoice {
                what: "forward-dynamics method",
                got: s.into(),
                expected: "aba, crba or walker-orin",
            }),
        }
    }
}

/// Forward dynamics `q̈ = M(q)⁻¹ (τ − C(q, q̇) q̇ − g(q) + Σ J_iᵀ W_ext,i)` by the chosen method
/// (all three agree to round-off), with optional external wrenches (Walker–Orin's
/// `b = C q̇ + G + Kᵀ f_ext`). Returns `ws.qdd`.
///
/// Naming rule of the library: the functions named after the quantity
/// ([`inverse_dynamics`](super::inverse_dynamics), `forward_dynamics`) take the external
/// wrenches; the algorithms' acronyms ([`rnea`](super::rnea), [`aba`](super::aba),
/// [`crba`](super::crba)) are the wrench-free short forms.
///
/// # Errors
/// [`Error::DimensionMismatch`]/[`Error::NonFinite`] for bad `q`, `v`, `tau`;
/// [`Error::InvalidArgument`] for a workspace or wrenches made for another model;
/// [`Error::Numerical`] when the mass matrix is singular, naming the joint.
///
/// ```
/// use screwdyn::{builtin, dynamics::{forward_dynamics, ForwardMethod}, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let (q, v, tau) = ([0.3, 0.9], [0.5, -1.0], [2.0, 1.0]);
/// let a = forward_dynamics(&m, &mut ws, &q, &v, &tau, None, ForwardMethod::Aba).unwrap().clone();
/// let b = forward_dynamics(&m, &mut ws, &q, &v, &tau, None, ForwardMethod::WalkerOrin).unwrap().clone();
/// assert!((a - b).amax() < 1e-12);
/// ```
pub fn forward_dynamics<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
    method: ForwardMethod,
) -> Result<&'w DVector<T>> {
    match method {
        ForwardMethod::Aba => articulated_body(model, ws, q, v, tau, fext),
        ForwardMethod::Crba => forward_dynamics_crba(model, ws, q, v, tau, fext),
        ForwardMethod::WalkerOrin => forward_dynamics_walker_orin(model, ws, q, v, tau, fext),
    }
}

/// [`forward_dynamics`] for the simulator's plant, which guarantees that `v` and `tau` have one
/// finite entry per joint, and `q` too when `q_checked` (see [`articulated_body_for_stepper`]):
/// ABA skips checking them again. The other methods check everything.
pub(crate) fn forward_dynamics_for_stepper<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    (q, q_checked): (&[T], bool),
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
    method: ForwardMethod,
) -> Result<&'w DVector<T>> {
    match method {
        ForwardMethod::Aba => articulated_body_for_stepper(model, ws, (q, q_checked), v, tau, fext),
        _ => forward_dynamics(model, ws, q, v, tau, fext, method),
    }
}

fn prepare<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<()> {
    checked_poses(model, ws, q, &[(v, "v"), (tau, "tau")], fext)?;
    // b = C q̇ + g − Σ Jᵀ W_ext: RNEA (in {0}) with q̈ = 0.
    rnea_in_world_passes(model, ws, Some(v), None, fext);
    ws.bias.copy_from(&ws.tau);
    Ok(())
}

fn solve<T: Real>(model: &Model<T>, ws: &mut Workspace<T>, tau: &[T]) -> Result<()> {
    ws.cholesky.copy_from(&ws.mass_matrix);
    cholesky_in_place(&mut ws.cholesky).map_err(|j| singular_error(model, j))?;
    for (i, t) in tau.iter().enumerate() {
        ws.qdd[i] = *t - ws.bias[i];
    }
    cholesky_solve_in_place(&ws.cholesky, ws.qdd.column_mut(0));
    if ws.qdd.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::Numerical(
            "forward dynamics produced a non-finite acceleration (the mass matrix is nearly singular)"
                .into(),
        ))
    }
}

/// Forward dynamics by CRBA (`M`), RNEA with `q̈ = 0` (`b`) and a Cholesky solve of
/// `M q̈ = τ − b`. Returns `ws.qdd`.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞. [`Error::Numerical`](crate::Error::Numerical) when `M` is singular, naming the joint.
pub fn forward_dynamics_crba<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<&'w DVector<T>> {
    prepare(model, ws, q, v, tau, fext)?;
    ws.ensure_square()?;
    crba_given_poses(model, ws);
    solve(model, ws, tau)?;
    Ok(&ws.qdd)
}

/// Walker & Orin's simulator: ① `b` = SUB1(q, q̇, q̈ = 0, f_ext) (RNEA);
/// ② column `j` of `H(q)` = SUB2(q, q̈ = e_j) (RNEA without velocity, gravity or external
/// wrenches); ③ solve `H q̈ = τ − b`. Returns `ws.qdd` (and leaves `M` in `ws.mass_matrix`).
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a joint vector of the wrong length or with NaN/∞. [`Error::Numerical`](crate::Error::Numerical) when `M` is singular, naming the joint.
pub fn forward_dynamics_walker_orin<'w, T: Real>(
    model: &Model<T>,
    ws: &'w mut Workspace<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    fext: Option<&ExternalWrenches<T>>,
) -> Result<&'w DVector<T>> {
    prepare(model, ws, q, v, tau, fext)?;
    ws.ensure_square()?;
    let zero = Twist::zeros();
    for j in 0..model.nv() {
        rnea_passes(
            model,
            ws,
            None,
            |i| if i == j { T::one() } else { T::zero() },
            &zero,
            None,
        );
        ws.mass_matrix.set_column(j, &ws.tau);
    }
    solve(model, ws, tau)?;
    Ok(&ws.qdd)
}
