//! [`BatchWorkspace`]: the joints in the kernels' form and the buffers of a batch call.

use super::buffers::Buffers;
use super::joint::LaneJoint;
use crate::error::Error;
use crate::model::{JointMotion, Model};
use crate::spatial::Se3;

/// States per group: one AVX-512 register of doubles.
pub const LANES: usize = 8;

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
    pub(super) joints: Vec<LaneJoint>,
    /// What `joints` was made from, to check the model of each call against.
    made_from: Vec<(JointMotion<f64>, Se3<f64>)>,
    pub(super) group: Box<Buffers<LANES>>,
    pub(super) single: Box<Buffers<1>>,
    /// On a CPU without fused multiply–add instructions, the per-call functions' workspace
    /// (state by state) and a vector of zeros for the inputs a call leaves out.
    pub(super) per_state: Option<(Box<crate::Workspace>, Vec<f64>)>,
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
    pub(super) fn check(&self, model: &Model) -> Result<(), Error> {
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
