//! Runs a kernel over the states of a batch: checks the inputs, gathers groups of [`LANES`]
//! states into lanes, runs the kernel, scatters the results; the remaining states (and a
//! group with a singular mass matrix) one at a time, or every state through the per-call
//! functions on a CPU without fused multiply–add.

use super::buffers::Buffers;
use super::joint::LaneJoint;
use super::lanes::Lanes;
use super::workspace::{BatchWorkspace, LANES};
use super::{aba, crba, path, rnea};
use crate::error::Error;
use crate::model::Model;

/// Joint vectors of a batch of states.
#[derive(Clone, Copy, Debug)]
pub enum Rows<'a> {
    /// `N` vectors of `nq` values, one after the other (a row-major `(N, nq)` array).
    Stacked(&'a [f64]),
    /// One vector of `nq` values for every state.
    Same(&'a [f64]),
}

/// Which algorithm a batch call runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Algorithm {
    Rnea,
    Crba,
    Aba,
    /// `a`, `b`, `c` of `τ = a s̈ + b ṡ² + c` from `q`, `q'`, `q''` (gravity in `c`).
    PathCoefficients,
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
        Algorithm::PathCoefficients => {
            path::path_coefficients(model, joints, b);
            Ok(())
        }
    }
}

/// What stops a group: a non-finite input, or a singular mass matrix (ABA).
enum Fault {
    Input(Error),
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
fn check_inputs(model: &Model, inputs: &Inputs<'_>, states: usize) -> Result<(), Error> {
    let nq = model.nq();
    for (rows, what) in inputs {
        match rows {
            Some(Rows::Same(x)) => model.check_vector(x, what)?,
            Some(Rows::Stacked(x)) if x.len() != states * nq => {
                return Err(Error::InvalidArgument(format!(
                    "{what} holds {} values, expected {states} states of {nq} joints ({})",
                    x.len(),
                    states * nq
                )))
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
) -> Result<(), Error> {
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
            return Err(model
                .check_vector(&block[k * nq..(k + 1) * nq], what)
                .unwrap_err()
                .in_state(first + k));
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
pub(super) fn run(
    algorithm: Algorithm,
    model: &Model,
    ws: &mut BatchWorkspace,
    inputs: Inputs<'_>,
    width: usize,
    out: &mut [f64],
) -> Result<(), Error> {
    ws.check(model)?;
    if width == 0 {
        return Ok(());
    }
    if out.len() % width != 0 {
        return Err(Error::InvalidArgument(format!(
            "the output holds {} values, not a whole number of results of {width}",
            out.len()
        )));
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
) -> Result<(), Error> {
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
            Algorithm::PathCoefficients => {
                path_coefficients_by_rnea(model, ws, [q, v, a], zeros, o)
                    .map_err(|e| e.in_state(k))?;
                continue;
            }
        };
        o.copy_from_slice(result.map_err(|e| e.in_state(k))?);
    }
    Ok(())
}

/// The path coefficients of one point from three per-call inverse dynamics, `c = g(q)`,
/// `a = RNEA(q, 0, q') − c`, `b = RNEA(q, q', q'') − c`, into `out = [a, b, c]`.
fn path_coefficients_by_rnea(
    model: &Model,
    ws: &mut crate::Workspace,
    [q, dq, ddq]: [&[f64]; 3],
    zeros: &[f64],
    out: &mut [f64],
) -> Result<(), Error> {
    let n = model.nq();
    let (a, rest) = out.split_at_mut(n);
    let (b, c) = rest.split_at_mut(n);
    c.copy_from_slice(crate::dynamics::rnea(model, ws, q, zeros, zeros)?.as_slice());
    a.copy_from_slice(crate::dynamics::rnea(model, ws, q, zeros, dq)?.as_slice());
    b.copy_from_slice(crate::dynamics::rnea(model, ws, q, dq, ddq)?.as_slice());
    for ((a, b), c) in a.iter_mut().zip(b.iter_mut()).zip(c.iter()) {
        *a -= c;
        *b -= c;
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
) -> Result<(), Error> {
    match step_single(algorithm, model, joints, inputs, k, b, width, out) {
        Ok(()) => Ok(()),
        Err(Fault::Input(e)) => Err(e),
        Err(Fault::Singular(i, d)) => {
            Err(crate::dynamics::singular_articulated_inertia(model, i, d).in_state(k))
        }
    }
}
