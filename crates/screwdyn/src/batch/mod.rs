//! Many states at once: inverse dynamics, the mass matrix and forward dynamics of `N` robot
//! states, eight at a time side by side in SIMD registers.
//!
//! Logs of robot motion, datasets for learning and sampling-based planners ask for the same
//! algorithm on thousands to millions of states. The per-call functions of [`crate::dynamics`]
//! run one state through the recursions; the functions here run eight: every quantity of the
//! algorithms (poses, twists, wrenches, inertias) holds one value per state in a [`Lanes`], and
//! each addition or multiplication acts on all eight (one AVX-512 instruction, two AVX2 ones).
//! The recursions are those of [`crate::dynamics`], line for line.
//!
//! **Same numbers, whatever the grouping.** Every state's result depends on that state alone:
//! a state computed in a group of eight, alone (the last states of a batch, or
//! `N = 1`), on any thread or CPU gives the same bits. The results agree with the per-call
//! functions of [`crate::dynamics`] to round-off (a few units in the last place), not bit for
//! bit: the lanes fuse the multiply–adds of dot products ([`Lanes::mul_add`]), use their own
//! `sin`/`cos` ([`Lanes::sin_cos`]) and, for the few joints that are not a plain rotation about
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

/// `[e(0), e(1), …]`: an array of `3` or `6` entries, written out (no loop, no closure), so
/// that the compiler sees straight-line lane arithmetic. A loop of three here would be
/// vectorised across its iterations (gathering one lane at a time) instead of across the lanes.
macro_rules! each {
    (3, |$k:ident| $e:expr) => {
        [
            {
                let $k = 0;
                $e
            },
            {
                let $k = 1;
                $e
            },
            {
                let $k = 2;
                $e
            },
        ]
    };
    (6, |$k:ident| $e:expr) => {
        [
            {
                let $k = 0;
                $e
            },
            {
                let $k = 1;
                $e
            },
            {
                let $k = 2;
                $e
            },
            {
                let $k = 3;
                $e
            },
            {
                let $k = 4;
                $e
            },
            {
                let $k = 5;
                $e
            },
        ]
    };
}

/// A 3×3 array of entries `e(i, j)`, written out.
macro_rules! each33 {
    (|$i:ident, $j:ident| $e:expr) => {
        [
            each!(3, |$j| {
                let $i = 0;
                $e
            }),
            each!(3, |$j| {
                let $i = 1;
                $e
            }),
            each!(3, |$j| {
                let $i = 2;
                $e
            }),
        ]
    };
}

/// `Σ_k a(k) b(k)` over `3` or `6` terms in index order, each product added with one rounding
/// ([`Lanes::mul_add`]); `dot!(n, |k| a, b; c)` starts the sum from `c` instead of the first
/// product. `a(k)` must be lanes, `b(k)` lanes or a number.
macro_rules! dot {
    (3, |$k:ident| $a:expr, $b:expr $(; $c:expr)?) => {{
        let acc = dot!(@first $k, $a, $b $(; $c)?);
        let acc = { let $k = 1; ($a).mul_add($b, acc) };
        { let $k = 2; ($a).mul_add($b, acc) }
    }};
    (6, |$k:ident| $a:expr, $b:expr $(; $c:expr)?) => {{
        let acc = dot!(@first $k, $a, $b $(; $c)?);
        let acc = { let $k = 1; ($a).mul_add($b, acc) };
        let acc = { let $k = 2; ($a).mul_add($b, acc) };
        let acc = { let $k = 3; ($a).mul_add($b, acc) };
        let acc = { let $k = 4; ($a).mul_add($b, acc) };
        { let $k = 5; ($a).mul_add($b, acc) }
    }};
    (@first $k:ident, $a:expr, $b:expr) => {{ let $k = 0; $a * $b }};
    (@first $k:ident, $a:expr, $b:expr; $c:expr) => {{ let $k = 0; ($a).mul_add($b, $c) }};
}

mod aba;
mod crba;
mod joint;
mod lanes;
mod rnea;
pub mod spatial;

pub use joint::LaneJoint;
pub use lanes::Lanes;

use crate::error::Error;
use crate::model::{JointMotion, Model};
use crate::spatial::Se3;
use spatial::{Composite, Pose, M6, V6};

/// States per group: one AVX-512 register of doubles.
pub const LANES: usize = 8;

/// Joint vectors of a batch of states.
#[derive(Clone, Copy, Debug)]
pub enum Rows<'a> {
    /// `N` vectors of `nq` values, one after the other (a row-major `(N, nq)` array).
    Stacked(&'a [f64]),
    /// One vector of `nq` values for every state.
    Same(&'a [f64]),
}

/// An error of a batch call: the library's [`Error`] and, when it belongs to one state, that
/// state's index.
///
/// ```
/// use screwdyn::batch::{self, BatchWorkspace, Rows};
/// let m = screwdyn::builtin::load("ur5").unwrap();
/// let mut ws = BatchWorkspace::new(&m);
/// let mut q = vec![0.0; 18];
/// q[13] = f64::NAN;
/// let mut out = vec![0.0; 108];
/// let e = batch::crba(&m, &mut ws, Rows::Stacked(&q), &mut out).unwrap_err();
/// assert_eq!(e.state, Some(2));
/// assert_eq!(e.to_string(), "state 2: q contains a non-finite value (NaN) at position 1");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BatchError {
    /// The state the error belongs to (`None`: the call itself, e.g. a buffer of the wrong size).
    pub state: Option<usize>,
    /// What is wrong.
    pub error: Error,
}

impl std::fmt::Display for BatchError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.state {
            Some(k) => write!(f, "state {k}: {}", self.error),
            None => write!(f, "{}", self.error),
        }
    }
}

impl std::error::Error for BatchError {}

impl From<Error> for BatchError {
    fn from(error: Error) -> Self {
        BatchError { state: None, error }
    }
}

/// The buffers of the kernels for `L` lanes: inputs gathered by joint, and every per-body
/// quantity of the three algorithms.
#[derive(Clone, Debug)]
struct Buffers<const L: usize> {
    q: Vec<Lanes<L>>,
    v: Vec<Lanes<L>>,
    /// `q̈` for RNEA, `τ` for ABA.
    a: Vec<Lanes<L>>,
    /// The joints' `(sin, cos)` ([`joint::sin_cos_all`]).
    sin_cos: Vec<(Lanes<L>, Lanes<L>)>,
    pose_in_parent: Vec<Pose<L>>,
    pose_in_world: Vec<Pose<L>>,
    twist: Vec<V6<L>>,
    accel: Vec<V6<L>>,
    /// RNEA's body wrenches, ABA's bias wrenches `pᴬ`.
    wrench: Vec<V6<L>>,
    screw: Vec<V6<L>>,
    composite: Vec<Composite<L>>,
    bias_acceleration: Vec<V6<L>>,
    articulated_inertia: Vec<M6<L>>,
    articulated_force: Vec<V6<L>>,
    articulated_joint_force: Vec<Lanes<L>>,
    /// The result: `n` values, or `n²` for the mass matrix.
    out: Vec<Lanes<L>>,
}

impl<const L: usize> Buffers<L> {
    fn new(n: usize) -> Self {
        Buffers {
            q: vec![Lanes::zero(); n],
            v: vec![Lanes::zero(); n],
            a: vec![Lanes::zero(); n],
            sin_cos: vec![(Lanes::zero(), Lanes::zero()); n],
            pose_in_parent: vec![Pose::default(); n],
            pose_in_world: vec![Pose::default(); n],
            twist: vec![[Lanes::zero(); 6]; n],
            accel: vec![[Lanes::zero(); 6]; n],
            wrench: vec![[Lanes::zero(); 6]; n],
            screw: vec![[Lanes::zero(); 6]; n],
            composite: vec![Composite::default(); n],
            bias_acceleration: vec![[Lanes::zero(); 6]; n],
            articulated_inertia: vec![[[Lanes::zero(); 6]; 6]; n],
            articulated_force: vec![[Lanes::zero(); 6]; n],
            articulated_joint_force: vec![Lanes::zero(); n],
            out: vec![Lanes::zero(); n * n],
        }
    }
}

/// What the batch functions need besides the model: the joints in the kernels' form (made
/// once), and buffers for a group of [`LANES`] states and for one state. Make one per thread
/// with [`BatchWorkspace::new`]; no call allocates after that.
///
/// ```
/// let m = screwdyn::builtin::load("panda").unwrap();
/// let ws = screwdyn::batch::BatchWorkspace::new(&m);
/// assert_eq!(ws.nbodies(), 7);
/// ```
#[derive(Clone, Debug)]
pub struct BatchWorkspace {
    joints: Vec<LaneJoint>,
    /// What `joints` was made from, to check the model of each call against.
    made_from: Vec<(JointMotion<f64>, Se3<f64>)>,
    group: Box<Buffers<LANES>>,
    single: Box<Buffers<1>>,
    /// On a CPU without fused multiply–add instructions, the per-call functions' workspace
    /// (state by state) and a vector of zeros for the inputs a call leaves out.
    per_state: Option<(Box<crate::Workspace>, Vec<f64>)>,
}

impl BatchWorkspace {
    /// The workspace for `model`.
    pub fn new(model: &Model) -> Self {
        BatchWorkspace::made(model, !fma_in_hardware())
    }

    /// A workspace that runs every state through the per-call functions of
    /// [`crate::dynamics`], as [`BatchWorkspace::new`] does on a CPU without fused
    /// multiply–add instructions (where the lanes' `mul_add` would be a library call): the
    /// results are the per-call functions', bit for bit.
    ///
    /// ```
    /// use screwdyn::batch::{self, BatchWorkspace, Rows};
    /// use screwdyn::{dynamics, Workspace};
    /// let m = screwdyn::builtin::load("ur5").unwrap();
    /// let mut ws = BatchWorkspace::state_by_state(&m);
    /// let q = [0.1, -0.4, 0.7, 0.2, 1.1, -0.3];
    /// let mut mm = [0.0; 36];
    /// batch::crba(&m, &mut ws, Rows::Stacked(&q), &mut mm).unwrap();
    /// assert_eq!(mm[..], dynamics::crba(&m, &mut Workspace::new(&m), &q).unwrap().as_slice()[..]);
    /// ```
    pub fn state_by_state(model: &Model) -> Self {
        BatchWorkspace::made(model, true)
    }

    fn made(model: &Model, state_by_state: bool) -> Self {
        let n = model.nbodies();
        BatchWorkspace {
            joints: LaneJoint::of(model),
            made_from: made_from(model),
            group: Box::new(Buffers::new(n)),
            single: Box::new(Buffers::new(n)),
            per_state: state_by_state.then(|| {
                (
                    Box::new(crate::Workspace::new(model)),
                    vec![0.0; model.nq()],
                )
            }),
        }
    }

    /// The number of bodies of the model it was made for.
    pub fn nbodies(&self) -> usize {
        self.joints.len()
    }

    /// `Err` unless the workspace was made for a model with `model`'s joints.
    fn check(&self, model: &Model) -> Result<(), Error> {
        let n = model.nbodies();
        let same = self.made_from.len() == n
            && model
                .motions()
                .iter()
                .zip(model.joints())
                .zip(&self.made_from)
                .all(|((m, j), (m0, h0))| m == m0 && j.home == *h0);
        if same {
            Ok(())
        } else {
            Err(Error::InvalidArgument(format!(
                "the batch workspace was made for another model than '{}' (make one with \
                 BatchWorkspace::new)",
                model.name()
            )))
        }
    }
}

fn made_from(model: &Model) -> Vec<(JointMotion<f64>, Se3<f64>)> {
    model
        .motions()
        .iter()
        .zip(model.joints())
        .map(|(m, j)| (*m, j.home))
        .collect()
}

/// Whether `f64::mul_add` is one instruction here: checked at run time on x86 (FMA came with
/// AVX2, 2013), known for the architectures that always have it.
fn fma_in_hardware() -> bool {
    #[cfg(any(target_arch = "x86_64", target_arch = "x86"))]
    {
        std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(any(target_arch = "x86_64", target_arch = "x86")))]
    {
        cfg!(any(
            target_arch = "aarch64",
            target_arch = "riscv64",
            target_arch = "powerpc64",
            target_arch = "s390x",
            target_arch = "loongarch64"
        ))
    }
}

/// Which algorithm a batch call runs.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Algorithm {
    Rnea,
    Crba,
    Aba,
}

/// Runs `algorithm` on the gathered lanes of `b`; `Err((joint, D))` from ABA.
#[inline(always)]
fn kernel<const L: usize>(
    algorithm: Algorithm,
    model: &Model,
    joints: &[LaneJoint],
    b: &mut Buffers<L>,
) -> Result<(), (usize, f64)> {
    match algorithm {
        Algorithm::Rnea => {
            rnea::rnea(model, joints, b);
            Ok(())
        }
        Algorithm::Crba => {
            crba::crba(model, joints, b);
            Ok(())
        }
        Algorithm::Aba => aba::aba(model, joints, b),
    }
}

/// What stops a group: a non-finite input, or a singular mass matrix (ABA).
enum Fault {
    Input(BatchError),
    Singular(usize, f64),
}

/// The states `first..first + L`: gathers their inputs into lanes, runs `algorithm`, writes each
/// lane's result to its row of `out` (`L × width` values, or fewer for a check-only pass).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn step<const L: usize>(
    algorithm: Algorithm,
    model: &Model,
    joints: &[LaneJoint],
    inputs: &Inputs<'_>,
    first: usize,
    b: &mut Buffers<L>,
    width: usize,
    out: &mut [f64],
) -> Result<(), Fault> {
    gather(model, inputs, first, b).map_err(Fault::Input)?;
    kernel(algorithm, model, joints, b).map_err(|(i, d)| Fault::Singular(i, d))?;
    scatter(b, width, out);
    Ok(())
}

/// [`step`] on a group of [`LANES`] states, compiled for AVX-512, AVX2 + FMA and the
/// baseline, chosen at run time (as `forward_kinematics`).
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
#[allow(clippy::too_many_arguments)]
fn step_group<'a>(
    algorithm: Algorithm,
    model: &Model,
    joints: &[LaneJoint],
    inputs: &Inputs<'a>,
    first: usize,
    b: &mut Buffers<LANES>,
    width: usize,
    out: &mut [f64],
) -> Result<(), Fault> {
    step(algorithm, model, joints, inputs, first, b, width, out)
}

/// [`step`] on one state.
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
#[allow(clippy::too_many_arguments)]
fn step_single<'a>(
    algorithm: Algorithm,
    model: &Model,
    joints: &[LaneJoint],
    inputs: &Inputs<'a>,
    first: usize,
    b: &mut Buffers<1>,
    width: usize,
    out: &mut [f64],
) -> Result<(), Fault> {
    step(algorithm, model, joints, inputs, first, b, width, out)
}

/// The inputs of a call, by name, `None` for zeros.
type Inputs<'a> = [(Option<Rows<'a>>, &'static str); 3];

/// Checks the inputs' sizes against `states` and the model.
fn check_inputs(model: &Model, inputs: &Inputs<'_>, states: usize) -> Result<(), BatchError> {
    let nq = model.nq();
    for (rows, what) in inputs {
        match rows {
            Some(Rows::Same(x)) => model.check_vector(x, what)?,
            Some(Rows::Stacked(x)) if x.len() != states * nq => {
                return Err(Error::InvalidArgument(format!(
                    "{what} holds {} values, expected {states} states of {nq} joints ({})",
                    x.len(),
                    states * nq
                ))
                .into())
            }
            _ => {}
        }
    }
    Ok(())
}

/// Fills the lanes of `b` for the inputs that are the same in every state (zeros for a
/// missing input), once per call.
fn fill_same<const L: usize>(model: &Model, inputs: &Inputs<'_>, b: &mut Buffers<L>) {
    let nq = model.nq();
    for (slot, (rows, _)) in inputs.iter().enumerate() {
        let dst = slot_of(b, slot, nq);
        match rows {
            None => dst.fill(Lanes::zero()),
            Some(Rows::Same(x)) => {
                for (d, &s) in dst.iter_mut().zip(x.iter()) {
                    *d = Lanes::splat(s);
                }
            }
            Some(Rows::Stacked(_)) => {}
        }
    }
}

/// The lanes of input `slot` (0: `q`, 1: `v`, 2: `a` or `τ`).
#[inline(always)]
fn slot_of<const L: usize>(b: &mut Buffers<L>, slot: usize, nq: usize) -> &mut [Lanes<L>] {
    match slot {
        0 => &mut b.q[..nq],
        1 => &mut b.v[..nq],
        _ => &mut b.a[..nq],
    }
}

/// Copies the stacked inputs of states `first..first + L` into the lanes of `b` (one lane per
/// state), checking that they are finite.
#[inline(always)]
fn gather<const L: usize>(
    model: &Model,
    inputs: &Inputs<'_>,
    first: usize,
    b: &mut Buffers<L>,
) -> Result<(), BatchError> {
    let nq = model.nq();
    for (slot, (rows, what)) in inputs.iter().enumerate() {
        let Some(Rows::Stacked(x)) = rows else {
            continue;
        };
        let block = &x[first * nq..(first + L) * nq];
        let dst = slot_of(b, slot, nq);
        // Lane by lane: 0 · x is ±0 for a finite x and NaN otherwise (see first_non_finite).
        let mut bad = Lanes::<L>::zero();
        for (j, d) in dst.iter_mut().enumerate() {
            for l in 0..L {
                d.0[l] = block[l * nq + j];
            }
            bad += *d * 0.0;
        }
        if let Some(k) = bad.0.iter().position(|&x| x != 0.0) {
            return Err(BatchError {
                state: Some(first + k),
                error: model
                    .check_vector(&block[k * nq..(k + 1) * nq], what)
                    .unwrap_err(),
            });
        }
    }
    Ok(())
}

/// Writes result `m` of lane `l` to `out[l width + m]`, for the lanes `out` has room for. Not
/// inlined: a scalar copy is as fast as what the clones would make of it (gathers), and as
/// fast as an AVX-512 8×8 transpose with vector stores (measured: the stores straddle cache
/// lines, rows being 36 doubles long for a 6-joint mass matrix).
#[inline(never)]
fn scatter<const L: usize>(b: &Buffers<L>, width: usize, out: &mut [f64]) {
    let results = &b.out[..width];
    for (l, row) in out.chunks_exact_mut(width).take(L).enumerate() {
        for (o, x) in row.iter_mut().zip(results) {
            *o = x.0[l];
        }
    }
}

/// Runs `algorithm` for every state: groups of [`LANES`], then the remaining states one by one.
fn run(
    algorithm: Algorithm,
    model: &Model,
    ws: &mut BatchWorkspace,
    inputs: Inputs<'_>,
    width: usize,
    out: &mut [f64],
) -> Result<(), BatchError> {
    ws.check(model)?;
    if width == 0 {
        return Ok(());
    }
    if out.len() % width != 0 {
        return Err(Error::InvalidArgument(format!(
            "the output holds {} values, not a whole number of results of {width}",
            out.len()
        ))
        .into());
    }
    let states = out.len() / width;
    check_inputs(model, &inputs, states)?;
    let BatchWorkspace {
        joints,
        group,
        single,
        per_state,
        ..
    } = ws;
    if let Some((one_ws, zeros)) = per_state {
        return state_by_state(algorithm, model, one_ws, zeros, &inputs, width, out);
    }
    if states >= LANES {
        fill_same(model, &inputs, group);
    }
    if states % LANES != 0 {
        fill_same(model, &inputs, single);
    }
    let mut chunks = out.chunks_exact_mut(LANES * width);
    let mut first = 0;
    for block in &mut chunks {
        match step_group(
            algorithm, model, joints, &inputs, first, group, width, block,
        ) {
            Ok(()) => {}
            Err(Fault::Input(e)) => return Err(e),
            Err(Fault::Singular(..)) => {
                // Some state's mass matrix is singular: find the first, one state at a time.
                fill_same(model, &inputs, single);
                for k in first..first + LANES {
                    one(algorithm, model, joints, single, &inputs, k, width, &mut [])?;
                }
            }
        }
        first += LANES;
    }
    for o in chunks.into_remainder().chunks_exact_mut(width) {
        one(algorithm, model, joints, single, &inputs, first, width, o)?;
        first += 1;
    }
    Ok(())
}

/// [`run`] without lanes: every state through the per-call function.
fn state_by_state(
    algorithm: Algorithm,
    model: &Model,
    ws: &mut crate::Workspace,
    zeros: &[f64],
    inputs: &Inputs<'_>,
    width: usize,
    out: &mut [f64],
) -> Result<(), BatchError> {
    let nq = model.nq();
    for (k, o) in out.chunks_exact_mut(width).enumerate() {
        let [q, v, a] = inputs.map(|(rows, _)| match rows {
            Some(Rows::Stacked(x)) => &x[k * nq..(k + 1) * nq],
            Some(Rows::Same(x)) => x,
            None => zeros,
        });
        let result = match algorithm {
            Algorithm::Rnea => crate::dynamics::rnea(model, ws, q, v, a).map(|t| t.as_slice()),
            // Symmetric: column-major is row-major.
            Algorithm::Crba => crate::dynamics::crba(model, ws, q).map(|m| m.as_slice()),
            Algorithm::Aba => crate::dynamics::aba(model, ws, q, v, a).map(|t| t.as_slice()),
        };
        o.copy_from_slice(result.map_err(|error| BatchError {
            state: Some(k),
            error,
        })?);
    }
    Ok(())
}

/// State `k` alone; writes its result to `out` (nothing if `out` is empty).
#[allow(clippy::too_many_arguments)]
fn one(
    algorithm: Algorithm,
    model: &Model,
    joints: &[LaneJoint],
    b: &mut Buffers<1>,
    inputs: &Inputs<'_>,
    k: usize,
    width: usize,
    out: &mut [f64],
) -> Result<(), BatchError> {
    match step_single(algorithm, model, joints, inputs, k, b, width, out) {
        Ok(()) => Ok(()),
        Err(Fault::Input(e)) => Err(e),
        Err(Fault::Singular(i, d)) => Err(BatchError {
            state: Some(k),
            error: crate::dynamics::singular_articulated_inertia(model, i, d),
        }),
    }
}

/// Inverse dynamics `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` of every state by the recursive
/// Newton–Euler algorithm (as [`dynamics::rnea`](crate::dynamics::rnea), seeds 000–002):
/// `tau` is `(N, nq)`, row-major.
///
/// # Errors
/// A [`BatchError`] naming the state for a non-finite input; for inputs or output of the wrong
/// size, or a workspace made for another model, without a state.
///
/// ```
/// use screwdyn::batch::{self, BatchWorkspace, Rows};
/// let m = screwdyn::builtin::planar2(); // point masses, gravity −9.81 ŷ
/// let mut ws = BatchWorkspace::new(&m);
/// let mut tau = [0.0; 4];
/// let zero = [0.0; 2];
/// batch::rnea(&m, &mut ws, Rows::Stacked(&[0.0; 4]), Rows::Same(&zero), Rows::Same(&zero), &mut tau)
///     .unwrap();
/// // Seed 003: g = [3g, g] at q = 0, for both states.
/// assert!((tau[2] - 3.0 * 9.81).abs() < 1e-12 && (tau[3] - 9.81).abs() < 1e-12);
/// ```
pub fn rnea(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    v: Rows<'_>,
    a: Rows<'_>,
    tau: &mut [f64],
) -> Result<(), BatchError> {
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
) -> Result<(), BatchError> {
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
/// // Seed 003: the centrifugal torque at joint 2 is m2 L1 L2 s2 θ̇1².
/// assert!((h[1] - 0.4_f64.sin() * 1.5 * 1.5).abs() < 1e-12);
/// ```
pub fn nonlinear_effects(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    v: Rows<'_>,
    out: &mut [f64],
) -> Result<(), BatchError> {
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
/// // Seed 004: D11 = 5, D12 = D21 = 2, D22 = 1 at θ2 = 0 (all masses and lengths 1).
/// assert!((mm[0] - 5.0).abs() < 1e-12 && (mm[1] - 2.0).abs() < 1e-12 && (mm[3] - 1.0).abs() < 1e-12);
/// ```
pub fn crba(
    model: &Model,
    ws: &mut BatchWorkspace,
    q: Rows<'_>,
    out: &mut [f64],
) -> Result<(), BatchError> {
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
) -> Result<(), BatchError> {
    let inputs = [(Some(q), "q"), (Some(v), "v"), (Some(tau), "tau")];
    run(Algorithm::Aba, model, ws, inputs, model.nq(), qdd)
}
