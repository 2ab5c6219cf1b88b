//! Many states at once: inverse dynamics, the mass matrix and forward dynamics of `N` robot
//! states, eight at a time side by side in SIMD registers.
//!
//! Logs of robot motion, datasets for learning and sampling-based planners ask for the same
//! algorithm on thousands to millions of states. The per-call functions of [`crate::dynamics`]
//! run one state through the recursions; the functions here run eight: every quantity of the
//! algorithms (poses, twists, wrenches, inertias) holds one value per state in a `Lanes` (eight
//! doubles), and each addition or multiplication acts on all eight (one AVX-512 instruction,
//! two AVX2 ones).
//! The recursions are those of [`crate::dynamics`], line for line.
//!
//! **Same numbers, whatever the grouping.** Every state's result depends on that state alone:
//! a state computed in a group of eight, alone (the last states of a batch, or
//! `N = 1`), on any thread or CPU gives the same bits. The results agree with the per-call
//! functions of [`crate::dynamics`] to round-off (a few units in the last place), not bit for
//! bit: the lanes fuse the multiply–adds of dot products (`Lanes::mul_add`), use their own
//! `sin`/`cos` (`Lanes::sin_cos`) and, for the few joints that are not a plain rotation about
//! a frame axis, another but equivalent form of `e^{[S]q}`. On a CPU without fused
//! multiply–add instructions the states go one by one through the per-call functions
//! ([`BatchWorkspace::state_by_state`]).
//!
//! **Inputs** are [`Rows`]: `N` joint vectors stored one after the other (a row-major
//! `(N, nq)` array), or one vector for every state. **Outputs** are row-major too: `(N, nq)`
//! for torques and accelerations, `(N, nq, nq)` for mass matrices. `N` is the output's length
//! divided by the width of one result. External wrenches are not taken here: use the per-call
//! functions for those.
//!
//! ```
//! use screwdyn::batch::{self, BatchWorkspace, Rows};
//! use screwdyn::{builtin, dynamics, Workspace};
//! let m = builtin::load("ur5").unwrap();
//! let mut ws = BatchWorkspace::new(&m);
//! // Ten states of six joints each, one after the other.
//! let q: Vec<f64> = (0..60).map(|k| (k as f64 * 0.37).sin()).collect();
//! let v = vec![0.5; 6];
//! let mut tau = vec![0.0; 60];
//! batch::rnea(&m, &mut ws, Rows::Stacked(&q), Rows::Same(&v), Rows::Same(&[0.0; 6]), &mut tau)
//!     .unwrap();
//! // Row k is the torque of state k, as one call of the per-state RNEA gives it.
//! let mut one = Workspace::new(&m);
//! let tau3 = dynamics::rnea(&m, &mut one, &q[18..24], &v, &[0.0; 6]).unwrap();
//! for j in 0..6 {
//!     assert!((tau[18 + j] - tau3[j]).abs() < 1e-12);
//! }
//! ```
//!
//! **Errors** that belong to one state are an [`Error::Batch`] naming it (`state k: …`, see
//! [`Error::state`]); errors of the call itself (a buffer of the wrong size, a workspace made for
//! another model) carry no state.
//!
//! ```
//! use screwdyn::batch::{self, BatchWorkspace, Rows};
//! let m = screwdyn::builtin::load("ur5").unwrap();
//! let mut ws = BatchWorkspace::new(&m);
//! let mut q = vec![0.0; 18];
//! q[13] = f64::NAN;
//! let mut out = vec![0.0; 108];
//! let e = batch::crba(&m, &mut ws, Rows::Stacked(&q), &mut out).unwrap_err();
//! assert_eq!(e.state(), Some(2));
//! assert_eq!(e.to_string(), "state 2: q contains a non-finite value (NaN) at position 1");
//! ```

#[macro_use]
mod macros;

mod aba;
mod buffers;
mod crba;
mod driver;
mod joint;
mod lanes;
mod path;
mod rnea;
mod spatial;
mod workspace;

pub use driver::Rows;
pub use workspace::{BatchWorkspace, LANES};

use crate::error::Error;
use crate::model::Model;
use driver::{run, Algorithm};

/// Inverse dynamics `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` of every state by the recursive
/// Newton–Euler algorithm (as [`dynamics::rnea`](crate::dynamics::rnea), Lynch & Park, *Modern Robotics*):
/// `tau` is `(N, nq)`, row-major.
///
/// # Errors
/// An [`Error::Batch`] naming the state for a non-finite input; for inputs or output of the
/// wrong size, or a workspace made for another model, the error itself (without a state).
///
/// ```
/// use screwdyn::batch::{self, BatchWorkspace, Rows};
/// let m = screwdyn::builtin::planar2(); // point masses, gravity −9.81 ŷ
/// let mut ws = BatchWorkspace::new(&m);
/// let mut tau = [0.0; 4];
/// let zero = [0.0; 2];
/// batch::rnea(&m, &mut ws, Rows::Stacked(&[0.0; 4]), Rows::Same(&zero), Rows::Same(&zero), &mut tau)
///     .unwrap();
/// // Craig, *Introduction to Robotics*: g = [3g, g] at q = 0, for both states.
/// assert!((tau[2] - 3.0 * 9.81).abs() < 1e-12 && (tau[3] - 9.81).abs() < 1e-12);
/// ```
pub fn rnea(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    v: Rows<'_>,
    a: Rows<'_>,
    tau: &mut [f64],
) -> Result<(), Error> {
    let inputs = [(Some(q), "q"), (Some(v), "v"), (Some(a), "a")];
    run(Algorithm::Rnea, model, ws, inputs, model.nq(), tau)
}

/// Gravity torques `g(q)` of every state: [`rnea`] with `q̇ = q̈ = 0` (the same numbers, bit
/// for bit).
///
/// # Errors
/// As [`rnea`].
///
/// ```
/// use screwdyn::batch::{self, BatchWorkspace, Rows};
/// let m = screwdyn::builtin::pendulum();
/// let mut ws = BatchWorkspace::new(&m);
/// let mut g = [0.0; 3];
/// batch::gravity_torque(&m, &mut ws, Rows::Stacked(&[0.1, 0.2, 0.3]), &mut g).unwrap();
/// assert!((g[2] - 9.81 * 0.3_f64.sin()).abs() < 1e-12);
/// ```
pub fn gravity_torque(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    out: &mut [f64],
) -> Result<(), Error> {
    let inputs = [(Some(q), "q"), (None, "v"), (None, "a")];
    run(Algorithm::Rnea, model, ws, inputs, model.nq(), out)
}

/// Nonlinear effects `C(q, q̇) q̇ + g(q)` of every state: [`rnea`] with `q̈ = 0` (the same
/// numbers, bit for bit).
///
/// # Errors
/// As [`rnea`].
///
/// ```
/// use screwdyn::batch::{self, BatchWorkspace, Rows};
/// let m = screwdyn::builtin::planar2().with_gravity(nalgebra::Vector3::zeros()).unwrap();
/// let mut ws = BatchWorkspace::new(&m);
/// let mut h = [0.0; 2];
/// batch::nonlinear_effects(&m, &mut ws, Rows::Same(&[0.0, 0.4]), Rows::Same(&[1.5, 0.0]), &mut h)
///     .unwrap();
/// // Craig, *Introduction to Robotics*: the centrifugal torque at joint 2 is m2 L1 L2 s2 θ̇1².
/// assert!((h[1] - 0.4_f64.sin() * 1.5 * 1.5).abs() < 1e-12);
/// ```
pub fn nonlinear_effects(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    v: Rows<'_>,
    out: &mut [f64],
) -> Result<(), Error> {
    let inputs = [(Some(q), "q"), (Some(v), "v"), (None, "a")];
    run(Algorithm::Rnea, model, ws, inputs, model.nq(), out)
}

/// The mass matrix `M(q)` of every state by the composite-rigid-body algorithm (as
/// [`dynamics::crba`](crate::dynamics::crba)): `out` is `(N, nq, nq)`, row-major, both
/// triangles filled.
///
/// # Errors
/// As [`rnea`].
///
/// ```
/// use screwdyn::batch::{self, BatchWorkspace, Rows};
/// let m = screwdyn::builtin::planar2();
/// let mut ws = BatchWorkspace::new(&m);
/// let mut mm = [0.0; 4];
/// batch::crba(&m, &mut ws, Rows::Same(&[0.0, 0.0]), &mut mm).unwrap();
/// // By hand: D11 = 5, D12 = D21 = 2, D22 = 1 at θ2 = 0 (all masses and lengths 1).
/// assert!((mm[0] - 5.0).abs() < 1e-12 && (mm[1] - 2.0).abs() < 1e-12 && (mm[3] - 1.0).abs() < 1e-12);
/// ```
pub fn crba(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    out: &mut [f64],
) -> Result<(), Error> {
    let inputs = [(Some(q), "q"), (None, "v"), (None, "a")];
    let nq = model.nq();
    run(Algorithm::Crba, model, ws, inputs, nq * nq, out)
}

/// Forward dynamics `q̈ = M⁻¹(τ − C q̇ − g)` of every state by the articulated-body algorithm
/// (as [`dynamics::aba`](crate::dynamics::aba)): `qdd` is `(N, nq)`, row-major.
///
/// # Errors
/// As [`rnea`]; and, naming the state and the joint, an [`Error::Numerical`] when a state's
/// mass matrix is singular.
///
/// ```
/// use screwdyn::batch::{self, BatchWorkspace, Rows};
/// let m = screwdyn::builtin::pendulum();
/// let mut ws = BatchWorkspace::new(&m);
/// let mut qdd = [0.0; 2];
/// batch::aba(&m, &mut ws, Rows::Stacked(&[0.5, -1.0]), Rows::Same(&[0.0]), Rows::Same(&[0.0]), &mut qdd)
///     .unwrap();
/// // A free pendulum: m l² q̈ = −m g l sin q.
/// assert!((qdd[1] - 9.81 * 1.0_f64.sin()).abs() < 1e-12);
/// ```
pub fn aba(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    v: Rows<'_>,
    tau: Rows<'_>,
    qdd: &mut [f64],
) -> Result<(), Error> {
    let inputs = [(Some(q), "q"), (Some(v), "v"), (Some(tau), "tau")];
    run(Algorithm::Aba, model, ws, inputs, model.nq(), qdd)
}

/// The coefficients of the equations of motion along a path, `τ = a s̈ + b ṡ² + c` with
/// `a = M(q) q'`, `b = M(q) q'' + C(q, q') q'`, `c = g(q)`, at every point `(q, q', q'')`:
/// `out` is `(N, 3 nq)`, row-major, each row `[a, b, c]` (what `motion::PathDynamics` computes
/// point by point, without its springs and friction).
///
/// # Errors
/// As [`rnea`], the inputs named `q`, `q'` and `q''`.
pub(crate) fn path_coefficients(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    dq: Rows<'_>,
    ddq: Rows<'_>,
    out: &mut [f64],
) -> Result<(), Error> {
    let inputs = [(Some(q), "q"), (Some(dq), "q'"), (Some(ddq), "q''")];
    run(
        Algorithm::PathCoefficients,
        model,
        ws,
        inputs,
        3 * model.nq(),
        out,
    )
}
