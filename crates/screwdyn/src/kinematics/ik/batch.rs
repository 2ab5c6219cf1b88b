//! Many targets at once on several threads, and paths solved point by point.

use super::numerical::IkSolver;
use super::result::IkResult;
use super::workspace::IkWorkspace;
use crate::error::{Error, Result};
use crate::spatial::Se3;
use std::sync::{Arc, Mutex, OnceLock};

/// The most problems a thread takes at a time from a batch.
const BLOCK: usize = 16;
/// Batches of fewer problems are solved on the calling thread.
const SPAWN_MIN: usize = 8;

/// The pool of `threads` threads batches run on: made on first use and kept for later calls;
/// `None` when the threads cannot be started.
fn pool(threads: usize) -> Option<Arc<rayon::ThreadPool>> {
    static POOLS: OnceLock<Mutex<Vec<Arc<rayon::ThreadPool>>>> = OnceLock::new();
    let mut pools = POOLS
        .get_or_init(|| Mutex::new(Vec::new()))
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(p) = pools.iter().find(|p| p.current_num_threads() == threads) {
        return Some(Arc::clone(p));
    }
    let made = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("screwdyn-ik-{i}"))
        .build()
        .ok()
        .map(Arc::new)?;
    pools.push(Arc::clone(&made));
    Some(made)
}

/// A joint that moved more than the threshold between two consecutive points of a path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkJump {
    /// The point (index into the path) the joint jumped to.
    pub point: usize,
    /// The joint.
    pub joint: usize,
    /// `q[point][joint] − q[point − 1][joint]` (rad or m).
    pub change: f64,
}

/// What [`IkSolver::solve_path`] reports: one result per point and the jumps.
#[derive(Clone, Debug, PartialEq)]
pub struct IkPath {
    /// One per point.
    pub results: Vec<IkResult>,
    /// Every joint change larger than the threshold between consecutive points.
    pub jumps: Vec<IkJump>,
}

impl IkSolver {
    /// Solves `k` independent problems on `threads` threads (`0`: as many as the machine has):
    /// `targets` holds `k × tasks` poses (problem `i`'s targets at `i × tasks …`), `q0`
    /// either one start for all (`nq` values) or one per problem (`k × nq`), `q_out`
    /// receives `k × nq` values. Problem `i` draws its restarts from its own stream `i` of the
    /// seed, so each answer is the same whatever the number of threads.
    ///
    /// Returns one entry per problem: its result, or the error of its own input (a target
    /// that is not a rotation, NaN, a `q0` outside the limits) as
    /// [`Error::Batch`] naming the problem; the other problems are solved all the same.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the lengths do not fit together.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask};
    /// use screwdyn::kinematics::forward_kinematics_poe;
    /// let ur5 = screwdyn::builtin::load("ur5").unwrap();
    /// let tool = ur5.frame_id("tool0").unwrap();
    /// let solver = IkSolver::new(&ur5, &[IkTask::pose(tool)], IkOptions::default()).unwrap();
    /// let placement = ur5.frames()[tool].placement;
    /// let targets: Vec<_> = (0..10)
    ///     .map(|i| forward_kinematics_poe(&ur5, &[0.1 * i as f64, -1.0, 1.0, 0.2, 0.5, 0.0]).unwrap()[5].compose(&placement))
    ///     .collect();
    /// let mut q = vec![0.0; 10 * 6];
    /// let results = solver.solve_batch(&targets, &[0.0; 6], &mut q, 2).unwrap();
    /// assert!(results.iter().all(|r| r.as_ref().unwrap().success));
    /// ```
    pub fn solve_batch(
        &self,
        targets: &[Se3],
        q0: &[f64],
        q_out: &mut [f64],
        threads: usize,
    ) -> Result<Vec<Result<IkResult>>> {
        let k = targets.len() / self.tasks.len();
        let mut results: Vec<Result<IkResult>> = Vec::with_capacity(k);
        results.resize_with(k, || Ok(empty()));
        self.solve_batch_into(targets, q0, q_out, threads, 0, &mut results)?;
        Ok(results)
    }

    /// [`solve_batch`](IkSolver::solve_batch) for the problems `first`, `first + 1`, … of a
    /// longer batch, writing their results into `results` (one per problem): problem `i` of
    /// this call draws from stream `first + i`, so a batch solved block by block (as the CLI
    /// streams a file) gives the same answers as in one call, and the same as `solve_batch`.
    /// Errors in `results` name the problem by its index in the longer batch.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the lengths do not fit together.
    ///
    /// ```
    /// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkResult};
    /// use nalgebra::Vector3;
    /// use screwdyn::spatial::Se3;
    /// let arm = screwdyn::builtin::planar2();
    /// let tip = arm.body_frame(1).unwrap();
    /// let solver = IkSolver::new(&arm, &[IkTask::position(tip)], IkOptions::default()).unwrap();
    /// // Out of reach: every restart is taken, so the answers depend on the seed streams.
    /// let targets: Vec<Se3> = (0..6)
    ///     .map(|i| Se3::from_translation(Vector3::new(2.5, 0.1 * i as f64, 0.0)))
    ///     .collect();
    /// let mut whole = vec![0.0; 12];
    /// solver.solve_batch(&targets, &[0.3, 0.4], &mut whole, 1).unwrap();
    /// let mut blocks = vec![0.0; 12];
    /// let mut results: Vec<screwdyn::Result<IkResult>> = Vec::new();
    /// for first in [0, 4] {
    ///     let end = (first + 4).min(6);
    ///     results.resize_with(end - first, || Err(screwdyn::Error::InvalidArgument(String::new())));
    ///     solver
    ///         .solve_batch_into(&targets[first..end], &[0.3, 0.4], &mut blocks[2 * first..2 * end], 2, first, &mut results)
    ///         .unwrap();
    /// }
    /// assert_eq!(whole, blocks);
    /// ```
    pub fn solve_batch_into(
        &self,
        targets: &[Se3],
        q0: &[f64],
        q_out: &mut [f64],
        threads: usize,
        first: usize,
        results: &mut [Result<IkResult>],
    ) -> Result<()> {
        let n = self.model.nq();
        let t = self.tasks.len();
        if targets.len() % t != 0 {
            return Err(Error::InvalidArgument(format!(
                "{} IK targets are not a whole number of problems of {t} tasks",
                targets.len()
            )));
        }
        let k = targets.len() / t;
        if q_out.len() != k * n || results.len() != k {
            return Err(Error::InvalidArgument(format!(
                "the IK output has {} values and {} results, {k} problems of {n} joints need {} and {k}",
                q_out.len(),
                results.len(),
                k * n
            )));
        }
        if q0.len() != n && q0.len() != k * n {
            return Err(Error::InvalidArgument(format!(
                "q0 has {} values: give {n} (one start for all) or {} ({k} problems of {n} joints)",
                q0.len(),
                k * n
            )));
        }
        let threads = if threads == 0 {
            std::thread::available_parallelism().map_or(1, |p| p.get())
        } else {
            threads
        };
        // Problems `offset …` of this call, into their slices of the output.
        let solve_range = |ws: &mut IkWorkspace,
                           offset: usize,
                           q_out: &mut [f64],
                           results: &mut [Result<IkResult>]| {
            for (i, (q, r)) in q_out.chunks_mut(n).zip(results.iter_mut()).enumerate() {
                let p = offset + i;
                let start = if q0.len() == n {
                    q0
                } else {
                    &q0[p * n..(p + 1) * n]
                };
                let stream = (first + p) as u64;
                *r = self
                    .solve_from(ws, &targets[p * t..(p + 1) * t], start, q, stream, None)
                    .map_err(|e| Error::Batch {
                        state: first + p,
                        source: Box::new(e),
                    });
            }
        };
        let threads = threads.min(k);
        let pool = if threads <= 1 || k < SPAWN_MIN {
            // Handing out the problems would cost more than they do.
            None
        } else {
            pool(threads)
        };
        let Some(pool) = pool else {
            let mut ws = IkWorkspace::new(self);
            solve_range(&mut ws, 0, q_out, results);
            return Ok(());
        };
        // Guided scheduling: each free thread takes a share of what is left, at most BLOCK
        // problems and fewer toward the end, so that a problem that needs many restarts (it
        // costs hundreds of ordinary ones) does not leave the other threads idle while the
        // last block finishes. Each problem draws from its own seed stream, so the answers
        // do not depend on which thread solves it.
        // The workers run on a pool whose threads outlive the call (starting threads and their
        // allocator arenas took a sizeable part of a batch of a few milliseconds).
        let rest = Mutex::new((0, q_out, results));
        pool.scope(|scope| {
            for _ in 0..threads {
                let (solve_range, rest) = (&solve_range, &rest);
                scope.spawn(move |_| {
                    let mut ws = IkWorkspace::new(self);
                    loop {
                        let (offset, q, r) = {
                            // A poisoned lock only means another thread panicked; what is left
                            // is still valid to hand out.
                            let mut left = rest.lock().unwrap_or_else(|e| e.into_inner());
                            let (offset, q, r) = &mut *left;
                            let take = (r.len() / (2 * threads)).clamp(1, BLOCK).min(r.len());
                            if take == 0 {
                                break;
                            }
                            let (q_head, q_tail) = std::mem::take(q).split_at_mut(take * n);
                            let (r_head, r_tail) = std::mem::take(r).split_at_mut(take);
                            (*q, *r) = (q_tail, r_tail);
                            let at = *offset;
                            *offset += take;
                            (at, q_head, r_head)
                        };
                        solve_range(&mut ws, offset, q, r);
                    }
                });
            }
        });
        Ok(())
    }

    /// Solves a path point by point, each point started from the previous point's answer
    /// (the first from `q0`), so consecutive answers stay on one branch; reports every joint
    /// that moves more than `jump_threshold` between consecutive points (a restart or a branch
    /// change). `targets` holds `points × tasks` poses; `q_out` receives `points × nq` values.
    ///
    /// # Errors
    /// As [`solve`](IkSolver::solve), naming the point as [`Error::Batch`];
    /// [`Error::InvalidArgument`] when the lengths do not fit together or `jump_threshold` is
    /// not positive.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use screwdyn::kinematics::ik::{IkOptions, IkSolver, IkTask, IkWorkspace};
    /// use screwdyn::spatial::Se3;
    /// let arm = screwdyn::builtin::planar2();
    /// let tip = arm.body_frame(1).unwrap();
    /// let solver = IkSolver::new(&arm, &[IkTask::position(tip)], IkOptions::default()).unwrap();
    /// let mut ws = IkWorkspace::new(&solver);
    /// // A straight line from (1.5, 0.5) to (0.5, 1.5).
    /// let line: Vec<Se3> = (0..=20)
    ///     .map(|i| Se3::from_translation(Vector3::new(1.5 - 0.05 * i as f64, 0.5 + 0.05 * i as f64, 0.0)))
    ///     .collect();
    /// let mut q = vec![0.0; 21 * 2];
    /// let path = solver.solve_path(&mut ws, &line, &[0.0, 1.0], 0.3, &mut q).unwrap();
    /// assert!(path.results.iter().all(|r| r.success));
    /// assert!(path.jumps.is_empty());
    /// ```
    pub fn solve_path(
        &self,
        ws: &mut IkWorkspace,
        targets: &[Se3],
        q0: &[f64],
        jump_threshold: f64,
        q_out: &mut [f64],
    ) -> Result<IkPath> {
        let n = self.model.nq();
        let t = self.tasks.len();
        if jump_threshold.is_nan() || jump_threshold <= 0.0 {
            return Err(Error::InvalidArgument(format!(
                "the jump threshold is {jump_threshold}, it must be positive"
            )));
        }
        if targets.len() % t != 0 || q_out.len() != (targets.len() / t) * n {
            return Err(Error::InvalidArgument(format!(
                "{} IK targets and an output of {} values do not fit {t} tasks and {n} joints",
                targets.len(),
                q_out.len()
            )));
        }
        let points = targets.len() / t;
        let mut results = Vec::with_capacity(points);
        let mut jumps = Vec::new();
        for p in 0..points {
            let (done, rest) = q_out.split_at_mut(p * n);
            let start = if p == 0 { q0 } else { &done[(p - 1) * n..] };
            let result = self
                .solve_from(
                    ws,
                    &targets[p * t..(p + 1) * t],
                    start,
                    &mut rest[..n],
                    0,
                    None,
                )
                .map_err(|e| Error::Batch {
                    state: p,
                    source: Box::new(e),
                })?;
            if p > 0 {
                for j in 0..n {
                    let change = rest[j] - start[j];
                    if change.abs() > jump_threshold {
                        jumps.push(IkJump {
                            point: p,
                            joint: j,
                            change,
                        });
                    }
                }
            }
            results.push(result);
        }
        Ok(IkPath { results, jumps })
    }
}

/// A placeholder result, overwritten by every problem.
fn empty() -> IkResult {
    IkResult {
        success: false,
        iterations: 0,
        restarts: 0,
        position_error: f64::NAN,
        orientation_error: f64::NAN,
        failure: None,
    }
}
