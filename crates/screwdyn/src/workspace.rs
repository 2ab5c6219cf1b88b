//! [`Workspace`]: everything an algorithm writes, allocated once per model (Pinocchio's `Data`).

use crate::error::{Error, Result};
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::CompositeInertia;
use crate::spatial::{Se3, Twist, Wrench};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, Vector3};

/// Preallocated per-model buffers. Algorithms read a [`Model`] and write here; after
/// `Workspace::new` no algorithm call allocates. Every field but the scratch of the
/// ABA-derivative sweeps is public and documented with the quantity it holds after the
/// algorithm that writes it (results such as `tau` or `mass_matrix`, and the intermediate
/// quantities of ABA, CRBA and the Coriolis matrix).
///
/// Field names follow the notation of docs/notation.md: `pose_in_parent[i] = H_i^{λ(i)}(q)`,
/// `pose_in_world[i] = H_i^0(q)`, `twist[i] = V_i^{i,0}`, `twist_dot[i] = V̇_i^{i,0}`,
/// `wrench[i] = W_{λ(i)}^{i,i}`.
///
/// ```
/// let model = screwdyn::builtin::planar2();
/// let mut ws = screwdyn::Workspace::new(&model);
/// screwdyn::kinematics::forward_kinematics(&model, &mut ws, &[0.0, 0.0]).unwrap();
/// assert_eq!(ws.pose_in_world[1].translation.x, 2.0);
/// ```
#[derive(Clone, Debug)]
pub struct Workspace<T: Real = f64> {
    /// `H_i^{λ(i)}(q)`.
    pub pose_in_parent: Vec<Se3<T>>,
    /// `H_i^0(q)`.
    pub pose_in_world: Vec<Se3<T>>,
    /// `Ad_{H_i^0} S_i`: joint `i`'s screw axis in the base frame (a column of the space Jacobian).
    pub screw_in_world: Vec<Twist<T>>,
    /// CRBA (base frame): the same screws coordinate by coordinate, entry `r n + i` holding
    /// coordinate `r` of `Ad_{H_i^0} S_i` (`n` bodies), so that the products `s_kᵀ F` of
    /// consecutive joints `k` are formed side by side.
    pub screw_in_world_by_coordinate: Vec<T>,
    /// `V_i^{i,0}`: body twist of body `i` in its own frame (forward velocity and acceleration,
    /// the local-frame RNEA of [`rnea_trace`](crate::dynamics::rnea_trace); [`rnea`](crate::dynamics::rnea)
    /// writes `twist_in_world` instead).
    pub twist: Vec<Twist<T>>,
    /// `V̇_i^{i,0}`: its time derivative.
    pub twist_dot: Vec<Twist<T>>,
    /// `W_{λ(i)}^{i,i}`: wrench of the parent on body `i`, in frame `i` (the local-frame RNEA;
    /// [`rnea`](crate::dynamics::rnea) writes `wrench_in_world` instead).
    pub wrench: Vec<Wrench<T>>,

    /// `τ`: joint torques from inverse dynamics ([`rnea`](crate::dynamics::rnea)).
    pub tau: DVector<T>,
    /// `M(q)`: the joint-space mass matrix (full, symmetric) from
    /// [`crba`](crate::dynamics::crba).
    pub mass_matrix: DMatrix<T>,
    /// `M(q)⁻¹` from [`mass_matrix_inverse`](crate::dynamics::mass_matrix_inverse).
    pub mass_matrix_inverse: DMatrix<T>,
    /// `C(q, q̇)` from [`coriolis_matrix`](crate::dynamics::coriolis_matrix).
    pub coriolis_matrix: DMatrix<T>,
    /// `g(q)` from [`gravity_torque`](crate::dynamics::gravity_torque).
    pub gravity_torque: DVector<T>,
    /// `C(q, q̇) q̇ + g(q)` from [`nonlinear_effects`](crate::dynamics::nonlinear_effects).
    pub nonlinear_effects: DVector<T>,
    /// `q̈`: joint accelerations from forward dynamics.
    pub qdd: DVector<T>,

    /// CRBA: composite spatial inertia of the subtree rooted at body `i`, in the base frame.
    pub composite_inertia: Vec<CompositeInertia<T>>,
    /// ABA and RNEA: `V_i^0 = Ad_{H_i^0} V_i^{i,0}`, body `i`'s twist written in the base frame.
    pub twist_in_world: Vec<Twist<T>>,
    /// ABA and RNEA: `V̇_i^0`, its time derivative (the base-frame spatial acceleration).
    pub twist_dot_in_world: Vec<Twist<T>>,
    /// RNEA: `W_i^0 = Ad_{H_0^i}ᵀ W_{λ(i)}^{i,i}`, the wrench of the parent on body `i` written
    /// in the base frame (moment about the base origin).
    pub wrench_in_world: Vec<Wrench<T>>,
    /// ABA: articulated-body inertia `𝔍ᴬ_i`, in the base frame, for the bodies that have a
    /// parent (a root body's is left at its rigid inertia `𝔍_i^0`: no pass reads it).
    pub articulated_inertia: Vec<Matrix6<T>>,
    /// ABA: articulated bias wrench `pᴬ_i`, in the base frame.
    pub articulated_bias: Vec<Wrench<T>>,
    /// ABA: velocity-product acceleration `c_i = ad_{V_{λ(i)}^0}(s_i q̇_i)`, in the base frame.
    pub bias_acceleration: Vec<Twist<T>>,
    /// ABA: `U_i / D_i`, the articulated inertia times the joint screw (`U_i = 𝔍ᴬ_i s_i`)
    /// divided by the joint's articulated inertia, so that `q̈_i = u_i / D_i − (U_i / D_i)ᵀ V̇'_i`.
    pub articulated_force: Vec<Wrench<T>>,
    /// ABA: `D_i = s_iᵀ U_i`, the inertia joint `i` feels through its articulated body.
    pub articulated_joint_inertia: DVector<T>,
    /// ABA: `u_i / D_i`, where `u_i = τ_i − s_iᵀ pᴬ_i` is the joint torque left for
    /// accelerating it.
    pub articulated_joint_force: DVector<T>,
    /// ABA: `V̇'_i = V̇_{λ(i)} + c_i`, body `i`'s acceleration before its own joint's `s_i q̈_i`,
    /// in the base frame (pass 3 keeps it so that a child's `q̈` waits on one product only).
    pub(crate) acceleration_before_joint: Vec<Twist<T>>,
    /// ABA: `(U_i / D_i)ᵀ s_{λ(i)}`, how much of the parent's `q̈_λ` joint `i`'s `q̈_i` loses.
    pub(crate) articulated_parent_coupling: DVector<T>,
    /// Forward dynamics by CRBA: the Cholesky factor of `M` (lower triangle).
    pub cholesky: DMatrix<T>,
    /// Forward dynamics: the bias `b = C q̇ + g − Σ Jᵀ W_ext`.
    pub bias: DVector<T>,

    /// Coriolis matrix: the time derivative `ṡ_j = ad_{V_j^{0,0}} s_j` of each joint's screw in
    /// the base frame.
    pub screw_rate_in_world: Vec<Twist<T>>,
    /// Coriolis matrix: composite base-frame inertia `𝔍ᶜ_j` (6×6) of the subtree of `j`.
    pub composite_inertia_matrix: Vec<Matrix6<T>>,
    /// Coriolis matrix: composite base-frame factor `Bᶜ_j = Σ B(𝔍_i, V_i)` of the subtree of `j`.
    pub composite_coriolis_factor: Vec<Matrix6<T>>,

    /// `∂τ/∂q` from [`rnea_derivatives`](crate::dynamics::rnea_derivatives): entry `(i, j)` is
    /// `∂τ_i/∂q_j`.
    pub dtau_dq: DMatrix<T>,
    /// `∂τ/∂q̇` from [`rnea_derivatives`](crate::dynamics::rnea_derivatives).
    pub dtau_dv: DMatrix<T>,
    /// `∂q̈/∂q` from [`aba_derivatives`](crate::dynamics::aba_derivatives).
    pub dqdd_dq: DMatrix<T>,
    /// `∂q̈/∂q̇` from [`aba_derivatives`](crate::dynamics::aba_derivatives).
    pub dqdd_dv: DMatrix<T>,
    /// `Y(q, q̇, q̈)` (n × 10n) from [`regressor`](crate::dynamics::regressor): `τ = Y π`
    /// (empty until the first call).
    pub regressor: DMatrix<T>,
    /// Derivatives: `α_i = ad_{A_{λ(i)}} s_i + ad_{V_{λ(i)}} ṡ_i`, the part of `∂A_k/∂q_i` shared
    /// by the subtree of `i` (base frame).
    pub acceleration_derivative_in_world: Vec<Twist<T>>,
    /// Derivatives: `Dᶜ₁₁`, the angular block of `Σ (𝔍V)⊼ − ad_Vᵀ 𝔍 − 𝔍 ad_V` over the subtree
    /// of `i` (base frame; the other non-zero block is `−2[f]`, `f` the linear momentum).
    pub subtree_velocity_coupling: Vec<Matrix3<T>>,
    /// Derivatives: the subtree's linear momentum `f` in the base frame.
    pub subtree_linear_momentum: Vec<Vector3<T>>,
    /// Derivatives: `F'_i`, the subtree's Newton–Euler wrench without the wrenches fixed in
    /// space (base frame).
    pub subtree_wrench_in_world: Vec<Wrench<T>>,
    /// Derivatives: `Eᶜ_i`, the subtree's external wrenches given in the base frame.
    pub subtree_fixed_external_wrench: Vec<Wrench<T>>,
    /// ABA derivatives: scratch of the articulated-body sweeps that form `M⁻¹` and `M⁻¹ X`
    /// (`1 / D_i`, one block of rows, the slots of the blocks `F_i` and `A_i`; empty until the
    /// first call).
    pub(crate) articulated_sweep: crate::dynamics::ArticulatedSweep<T>,
    /// The number of bodies of the model this workspace was made for.
    nbodies: usize,
}

/// Models with at most this many bodies get their four `n × n` buffers (`mass_matrix`,
/// `mass_matrix_inverse`, `coriolis_matrix`, `cholesky`) when the workspace is made; larger ones
/// get them on the first call of an algorithm that needs them (CRBA, `M⁻¹`, the Coriolis
/// matrix, forward dynamics by CRBA or Walker–Orin), so that O(n) work on a long chain (forward
/// kinematics, RNEA, ABA) needs O(n) memory.
pub const EAGER_SQUARE_BUFFERS: usize = 256;

/// A zero `n × n` matrix, or an error when its memory cannot be had.
fn try_square<T: Real>(n: usize) -> Result<DMatrix<T>> {
    let too_big = || {
        Error::InvalidArgument(format!(
            "a {n} × {n} matrix ({:.1} GB) cannot be allocated for a model of {n} joints",
            (n as f64).powi(2) * std::mem::size_of::<T>() as f64 / 1e9
        ))
    };
    let len = n.checked_mul(n).ok_or_else(too_big)?;
    let mut data: Vec<T> = Vec::new();
    data.try_reserve_exact(len).map_err(|_| too_big())?;
    data.resize(len, T::zero());
    Ok(DMatrix::from_vec(n, n, data))
}

impl<T: Real> Workspace<T> {
    /// Allocates the buffers for `model` (the `n × n` ones only up to
    /// [`EAGER_SQUARE_BUFFERS`] bodies).
    pub fn new(model: &Model<T>) -> Self {
        let n = model.nbodies();
        let sq = if n <= EAGER_SQUARE_BUFFERS { n } else { 0 };
        Workspace {
            pose_in_parent: vec![Se3::identity(); n],
            pose_in_world: vec![Se3::identity(); n],
            screw_in_world: vec![Twist::zeros(); n],
            screw_in_world_by_coordinate: vec![T::zero(); 6 * n],
            twist: vec![Twist::zeros(); n],
            twist_dot: vec![Twist::zeros(); n],
            wrench: vec![Wrench::zeros(); n],
            tau: DVector::zeros(n),
            mass_matrix: DMatrix::zeros(sq, sq),
            mass_matrix_inverse: DMatrix::zeros(sq, sq),
            coriolis_matrix: DMatrix::zeros(sq, sq),
            gravity_torque: DVector::zeros(n),
            nonlinear_effects: DVector::zeros(n),
            qdd: DVector::zeros(n),
            composite_inertia: vec![CompositeInertia::zero(); n],
            twist_in_world: vec![Twist::zeros(); n],
            twist_dot_in_world: vec![Twist::zeros(); n],
            wrench_in_world: vec![Wrench::zeros(); n],
            articulated_inertia: vec![Matrix6::zeros(); n],
            articulated_bias: vec![Wrench::zeros(); n],
            bias_acceleration: vec![Twist::zeros(); n],
            articulated_force: vec![Wrench::zeros(); n],
            articulated_joint_inertia: DVector::zeros(n),
            articulated_joint_force: DVector::zeros(n),
            acceleration_before_joint: vec![Twist::zeros(); n],
            articulated_parent_coupling: DVector::zeros(n),
            cholesky: DMatrix::zeros(sq, sq),
            bias: DVector::zeros(n),
            screw_rate_in_world: vec![Twist::zeros(); n],
            composite_inertia_matrix: vec![Matrix6::zeros(); n],
            composite_coriolis_factor: vec![Matrix6::zeros(); n],
            dtau_dq: DMatrix::zeros(sq, sq),
            dtau_dv: DMatrix::zeros(sq, sq),
            dqdd_dq: DMatrix::zeros(sq, sq),
            dqdd_dv: DMatrix::zeros(sq, sq),
            regressor: DMatrix::zeros(0, 0),
            acceleration_derivative_in_world: vec![Twist::zeros(); n],
            subtree_velocity_coupling: vec![Matrix3::zeros(); n],
            subtree_linear_momentum: vec![Vector3::zeros(); n],
            subtree_wrench_in_world: vec![Wrench::zeros(); n],
            subtree_fixed_external_wrench: vec![Wrench::zeros(); n],
            articulated_sweep: crate::dynamics::ArticulatedSweep::empty(),
            nbodies: n,
        }
    }

    /// Checks that this workspace was made for `model` (the same number of bodies): every
    /// algorithm calls it once before it writes.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming both sizes when the workspace was made for another
    /// model.
    ///
    /// ```
    /// use screwdyn::{builtin, Workspace};
    /// let ws = Workspace::new(&builtin::load("ur5").unwrap());
    /// assert!(ws.check(&builtin::load("ur5").unwrap()).is_ok());
    /// let e = ws.check(&builtin::planar2()).unwrap_err().to_string();
    /// assert!(e.contains("6 bodies"));
    /// ```
    pub fn check(&self, model: &Model<T>) -> Result<()> {
        if self.nbodies != model.nbodies() {
            return Err(Error::InvalidArgument(format!(
                "the workspace was made for a model with {} bodies, not for '{}' with {} bodies (make one with Workspace::new)",
                self.nbodies,
                model.name(),
                model.nbodies()
            )));
        }
        Ok(())
    }

    /// Makes sure the `n × n` buffers exist (see [`EAGER_SQUARE_BUFFERS`]); allocates only the
    /// first time, for a large model.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the memory cannot be had.
    pub(crate) fn ensure_square(&mut self) -> Result<()> {
        let n = self.nbodies;
        if self.mass_matrix.nrows() != n {
            self.mass_matrix = try_square(n)?;
            self.mass_matrix_inverse = try_square(n)?;
            self.coriolis_matrix = try_square(n)?;
            self.cholesky = try_square(n)?;
        }
        Ok(())
    }

    /// [`Workspace::ensure_square`] and the four `n × n` derivative matrices (`dtau_dq`,
    /// `dtau_dv`, `dqdd_dq`, `dqdd_dv`, made with the workspace up to
    /// [`EAGER_SQUARE_BUFFERS`] bodies).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the memory cannot be had.
    pub(crate) fn ensure_derivatives(&mut self) -> Result<()> {
        self.ensure_square()?;
        let n = self.nbodies;
        if self.dtau_dq.nrows() != n {
            self.dtau_dq = try_square(n)?;
            self.dtau_dv = try_square(n)?;
            self.dqdd_dq = try_square(n)?;
            self.dqdd_dv = try_square(n)?;
        }
        if self.articulated_sweep.len() != n {
            self.articulated_sweep = crate::dynamics::ArticulatedSweep::new(n);
        }
        Ok(())
    }

    /// The `n × 10n` regressor buffer, made on the first call of
    /// [`regressor`](crate::dynamics::regressor) (it is ten times a mass matrix).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the memory cannot be had.
    pub(crate) fn ensure_regressor(&mut self) -> Result<()> {
        let n = self.nbodies;
        if self.regressor.shape() != (n, 10 * n) {
            let cols = n.checked_mul(10).ok_or_else(|| {
                Error::InvalidArgument(format!("a regressor for {n} joints is too large"))
            })?;
            let len = n.checked_mul(cols).ok_or_else(|| {
                Error::InvalidArgument(format!("a regressor for {n} joints is too large"))
            })?;
            let mut data: Vec<T> = Vec::new();
            data.try_reserve_exact(len).map_err(|_| {
                Error::InvalidArgument(format!(
                    "the {n} × {cols} regressor cannot be allocated for a model of {n} joints"
                ))
            })?;
            data.resize(len, T::zero());
            self.regressor = DMatrix::from_vec(n, cols, data);
        }
        Ok(())
    }
}
