//! Forward kinematics: the recursion `H_i^0 = H_{λ(i)}^0 H_i^{λ(i)}(q_i)` and the spatial
//! product-of-exponentials formula (Lynch & Park, *Modern Robotics*).

use crate::error::Result;
use crate::model::{Frame, Model};
use crate::scalar::{sin_cos, sin_cos_lanes, Real};
use crate::spatial::Se3;
use crate::workspace::Workspace;

/// Poses of all bodies by the recursion `H_i^{λ(i)}(q_i) = H_i^{λ(i)}(0) e^{[S_i^{i,λ(i)}] q_i}`,
/// `H_i^0 = H_{λ(i)}^0 H_i^{λ(i)}` (Lynch & Park, *Modern Robotics*, forward iterations). Writes `ws.pose_in_parent`
/// and `ws.pose_in_world`.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `ws` was made for another
/// model; [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or
/// [`Error::NonFinite`](crate::Error::NonFinite) for a bad `q`.
///
/// ```
/// use screwdyn::{builtin, kinematics::forward_kinematics, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// let (q1, q2) = (0.3_f64, 0.5_f64);
/// forward_kinematics(&m, &mut ws, &[q1, q2]).unwrap();
/// let p = ws.pose_in_world[1].translation;
/// assert!((p.x - (q1.cos() + (q1 + q2).cos())).abs() < 1e-15);
/// assert!((p.y - (q1.sin() + (q1 + q2).sin())).abs() < 1e-15);
/// ```
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
pub fn forward_kinematics<T: Real>(model: &Model<T>, ws: &mut Workspace<T>, q: &[T]) -> Result<()> {
    // With fused multiply–adds, the sines and cosines of a block's joint angles side by side
    // in vector registers before the joints that use them, and the turned home columns and
    // the compositions fused; without (a portable build's baseline clone, where `mul_add` is
    // a library call) one scalar `sin_cos` per joint and unfused products.
    let lanes = multiversion::target::target_cfg_f!(target_feature = "fma");
    poses::<T, true>(model, ws, q, lanes)
}

/// The poses of all bodies in their parents' frames only, `H_i^{λ(i)}(q_i) = H_i^{λ(i)}(0)
/// e^{[S_i^{i,λ(i)}] q_i}`: [`forward_kinematics`] without the compositions `H_i^0 = H_{λ(i)}^0
/// H_i^{λ(i)}`, for the algorithms that work in the body frames (the recursive Newton–Euler
/// passes). Writes `ws.pose_in_parent` and leaves `ws.pose_in_world` as it was.
///
/// # Errors
/// As [`forward_kinematics`].
///
/// ```
/// use screwdyn::{builtin, kinematics::{forward_kinematics, poses_in_parent}, Workspace};
/// let m = builtin::load("ur5").unwrap();
/// let q = [0.1, -0.7, 1.2, 0.4, -0.3, 2.0];
/// let (mut full, mut local) = (Workspace::new(&m), Workspace::new(&m));
/// forward_kinematics(&m, &mut full, &q).unwrap();
/// poses_in_parent(&m, &mut local, &q).unwrap();
/// assert_eq!(local.pose_in_parent, full.pose_in_parent);
/// assert_eq!(local.pose_in_world[5], screwdyn::spatial::Se3::identity()); // not written
/// ```
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
pub fn poses_in_parent<T: Real>(model: &Model<T>, ws: &mut Workspace<T>, q: &[T]) -> Result<()> {
    let lanes = multiversion::target::target_cfg_f!(target_feature = "fma");
    poses::<T, false>(model, ws, q, lanes)
}

/// [`forward_kinematics`]' poses in {0} for the simulator's stepper, which has checked that
/// `q` has one finite entry per joint and that `ws` was made for `model` (RK4's stage states,
/// checked as they are formed): no checks, and only `ws.pose_in_world` is written
/// (articulated-body dynamics reads nothing else; `ws.pose_in_parent` is left as it was).
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
pub(crate) fn world_poses_of_checked<T: Real>(model: &Model<T>, ws: &mut Workspace<T>, q: &[T]) {
    let lanes = multiversion::target::target_cfg_f!(target_feature = "fma");
    pose_pass::<T, false, true>(model, ws, q, lanes);
}

/// The body poses in the parents' frames, and in the world frame when `WORLD`, after checking
/// `ws` and `q` against `model`.
#[inline(always)]
fn poses<T: Real, const WORLD: bool>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    lanes: bool,
) -> Result<()> {
    ws.check(model)?;
    model.check_vector(q, "q")?;
    pose_pass::<T, true, WORLD>(model, ws, q, lanes);
    Ok(())
}

/// The body poses in the parents' frames when `PARENT` (`ws.pose_in_parent`), in the world
/// frame when `WORLD` (`ws.pose_in_world`); the sines and cosines by lanes when `lanes` (see
/// [`sin_cos_packed`]). For `q` with `nq` entries and `ws` made for `model` (checked by the
/// callers).
#[inline(always)]
fn pose_pass<T: Real, const PARENT: bool, const WORLD: bool>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    q: &[T],
    lanes: bool,
) {
    let n = model.nq();
    // Everything as slices of length n, so that the loop's bounds checks go.
    let (joints, motions, parents) = (
        &model.joints()[..n],
        &model.motions()[..n],
        &model.parents()[..n],
    );
    let q = &q[..n];
    let (pip, piw) = (&mut ws.pose_in_parent[..n], &mut ws.pose_in_world[..n]);
    for start in (0..n).step_by(BLOCK) {
        let end = n.min(start + BLOCK);
        // The angles θ = ±q of the block's turning joints, packed.
        let mut angle = [T::zero(); BLOCK];
        let mut turning = 0;
        for (m, &q) in motions[start..end].iter().zip(&q[start..end]) {
            if m.turns() {
                angle[turning] = m.angle(q);
                turning += 1;
            }
        }
        let (sin, cos) = sin_cos_packed(angle, turning, lanes);
        let mut k = 0;
        for i in start..end {
            let sc = if motions[i].turns() {
                k += 1;
                (sin[k - 1], cos[k - 1])
            } else {
                (T::zero(), T::one())
            };
            // H_i^λ = H_i^λ(0) e^{[S_i] q_i},  H_i^0 = H_λ^0 H_i^λ.
            let h = if lanes {
                motions[i].pose_in_parent_given_fused(&joints[i].home, q[i], sc)
            } else {
                motions[i].pose_in_parent_given(&joints[i].home, q[i], sc)
            };
            if PARENT {
                pip[i] = h;
            }
            if WORLD {
                piw[i] = match parents[i] {
                    Some(p) if lanes => piw[p].compose_fused(&h),
                    Some(p) => piw[p].compose(&h),
                    None => h,
                };
            }
        }
    }
}

/// Joints per block of forward kinematics: the sines and cosines of a block's angles are
/// computed together, into arrays on the stack.
const BLOCK: usize = 8;

/// `(sin θ_k, cos θ_k)` of the first `len` angles of `angle` (the rest are zeros): five to
/// eight by [`sin_cos_lanes`] on eight lanes, two to four on four, a single one by
/// [`sin_cos`]; each by [`sin_cos`] when `!lanes`.
#[inline(always)]
fn sin_cos_packed<T: Real>(angle: [T; BLOCK], len: usize, lanes: bool) -> ([T; BLOCK], [T; BLOCK]) {
    if lanes && len > 4 {
        return sin_cos_lanes(angle);
    }
    let (mut sin, mut cos) = ([T::zero(); BLOCK], [T::one(); BLOCK]);
    if lanes && len > 1 {
        let (s, c) = sin_cos_lanes::<T, 4>([angle[0], angle[1], angle[2], angle[3]]);
        sin[..4].copy_from_slice(&s);
        cos[..4].copy_from_slice(&c);
    } else {
        for k in 0..len {
            (sin[k], cos[k]) = sin_cos(angle[k]);
        }
    }
    (sin, cos)
}

/// The pose `H_f^0 = H_b^0 H_f^b` of frame `f` on body `b`, from the body poses of the last
/// [`forward_kinematics`] call.
///
/// # Errors
/// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when the model has no frame
/// `frame` or `ws` was made for another model.
///
/// ```
/// use screwdyn::{builtin, kinematics::{forward_kinematics, frame_pose}, Workspace};
/// let m = builtin::planar2();
/// let mut ws = Workspace::new(&m);
/// forward_kinematics(&m, &mut ws, &[0.0, 0.0]).unwrap();
/// assert_eq!(frame_pose(&m, &ws, m.frame_id("link2").unwrap()).unwrap().translation.x, 2.0);
/// assert!(frame_pose(&m, &ws, 99).is_err());
/// ```
pub fn frame_pose<T: Real>(model: &Model<T>, ws: &Workspace<T>, frame: usize) -> Result<Se3<T>> {
    ws.check(model)?;
    let f = model.frame(frame)?;
    Ok(frame_pose_unchecked(ws, f))
}

/// [`frame_pose`] for a frame of the model `ws` was checked against.
#[inline]
pub(crate) fn frame_pose_unchecked<T: Real>(ws: &Workspace<T>, f: &Frame<T>) -> Se3<T> {
    match f.body {
        Some(b) => ws.pose_in_world[b].compose(&f.placement),
        None => f.placement,
    }
}

/// Poses of all bodies by the spatial product-of-exponentials formula (Lynch & Park, *Modern Robotics*):
/// `H_i^0(q) = e^{[S_1^{0}] q_1} ⋯ e^{[S_i^{0}] q_i} H_i^0(0)`, the product running over the
/// joints supporting body `i`, with `S_j^0 = Ad_{H_j^0(0)} S_j^{j,λ(j)}` the screw axes in the
/// base frame at home. An independent formula, used to check the recursion; it allocates.
///
/// # Errors
/// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a bad `q`.
///
/// ```
/// use screwdyn::{builtin, kinematics::{forward_kinematics, forward_kinematics_poe}, Workspace};
/// let m = builtin::planar2();
/// let q = [0.7, -1.1];
/// let mut ws = Workspace::new(&m);
/// forward_kinematics(&m, &mut ws, &q).unwrap();
/// let poe = forward_kinematics_poe(&m, &q).unwrap();
/// assert!((poe[1].to_matrix() - ws.pose_in_world[1].to_matrix()).amax() < 1e-12);
/// ```
pub fn forward_kinematics_poe<T: Real>(model: &Model<T>, q: &[T]) -> Result<Vec<Se3<T>>> {
    model.check_vector(q, "q")?;
    let n = model.nq();
    // Home poses H_i^0(0) and space-frame screws S_i^0.
    let mut home = vec![Se3::identity(); n];
    for i in 0..n {
        let h = model.joints()[i].home;
        home[i] = match model.parents()[i] {
            Some(p) => home[p].compose(&h),
            None => h,
        };
    }
    let space_screw: Vec<_> = (0..n)
        .map(|i| home[i].act_twist(&model.joints()[i].screw))
        .collect();
    let mut poses = Vec::with_capacity(n);
    for (i, home_i) in home.iter().enumerate() {
        let mut h = Se3::identity();
        for j in model.support(i)? {
            h = h.compose(&Se3::exp_screw(&space_screw[j], q[j]));
        }
        poses.push(h.compose(home_i));
    }
    Ok(poses)
}
