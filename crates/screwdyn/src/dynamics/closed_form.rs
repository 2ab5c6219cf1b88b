//! The stacked closed form of the manipulator dynamics (Lynch & Park, *Modern Robotics*), built from stacked block
//! matrices exactly as the lecture writes them. A teaching and reference implementation: it
//! allocates and costs O(n³); the recursive algorithms are tested against it.

use super::rnea::base_acceleration;
use super::wrenches::ExternalWrenches;
use crate::error::{Error, Result};
use crate::kinematics::forward_kinematics_poe;
use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::{ad_matrix, hat, Se3, Twist};
use nalgebra::{DMatrix, DVector, Matrix6};

/// Every matrix of the stacked closed form at one state `(θ, θ̇)`; see [`closed_form`].
///
/// Blocks are 6×6 and indexed by body: block `(i, j)` occupies rows `6i..6i+6` and columns
/// `6j..6j+6`.
#[derive(Clone, Debug)]
pub struct ClosedForm<T: Real = f64> {
    /// `A(θ)`: block `(i, λ(i)) = Ad_{H_{λ(i)}^i(θ_i)}` (parent blocks, so trees work).
    pub a: DMatrix<T>,
    /// `L(θ) = (I − A)⁻¹`, in closed form: block `(i, j) = Ad_{H_j^i(θ)}` when `j` supports `i`.
    pub l: DMatrix<T>,
    /// `S = blkdiag(S_1^{1,0}, …, S_n^{n,λ(n)})`, 6n×n.
    pub s: DMatrix<T>,
    /// `𝔍 = blkdiag(𝔍^{1,1}, …, 𝔍^{n,n})`.
    pub inertia: DMatrix<T>,
    /// `ad_{S θ̇} = blkdiag(ad_{S_i θ̇_i})`.
    pub ad_s_qdot: DMatrix<T>,
    /// `V = L S θ̇`: the stacked body twists.
    pub v: DVector<T>,
    /// `ad_V = blkdiag(ad_{V_i})`.
    pub ad_v: DMatrix<T>,
    /// `J = L S`: block row `i` is the body Jacobian `J_i^{i,0}` of link `i` (Lynch & Park, *Modern Robotics*).
    pub j: DMatrix<T>,
    /// `J̇ = −L ad_{Sθ̇} A J` (the derivative of `J` along the motion; the `L Ȧ J`).
    pub j_dot: DMatrix<T>,
    /// `V̇_base`: block `i` is `Ad_{H_0^i} V̇_g` for the bodies attached to the base, with
    /// `V̇_g = (0, −g⁰)` (Lynch & Park, *Modern Robotics*, gravity by the equivalence principle).
    pub vdot_base: DVector<T>,
    /// `I_a = diag(I_a,1, …, I_a,n)`: the joints' armatures (rotor inertias reflected to the
    /// joints, [`Joint::armature`](crate::model::Joint::armature)).
    pub armature: DMatrix<T>,
    /// `M = Jᵀ 𝔍 J + I_a = Sᵀ Lᵀ 𝔍 L S + I_a`.
    pub m: DMatrix<T>,
    /// The `C = Sᵀ Lᵀ [−𝔍 L ad_{Sθ̇} A − ad_{L S θ̇}ᵀ 𝔍] L S`, literally.
    pub c: DMatrix<T>,
    /// The Christoffel-consistent factorisation of the same `C θ̇`:
    /// `C♯ = Jᵀ 𝔍 (J̇ + ad_V J) + ½ Jᵀ [−ad_Vᵀ 𝔍 − 𝔍 ad_V + (𝔍V)⊼] J`, where `(h)⊼ X = −ad_Xᵀ h`.
    /// `C♯ θ̇ = C θ̇`, `Ṁ − 2C♯` is skew-symmetric and `C♯_ij = Σ_k Γ_ijk θ̇_k`; this is what
    /// [`coriolis_matrix`](super::coriolis_matrix) computes.
    pub c_christoffel: DMatrix<T>,
    /// `g = Sᵀ Lᵀ 𝔍 L V̇_base`.
    pub g: DVector<T>,
    /// `θ̇`, the velocity the form was built at.
    pub qdot: DVector<T>,
    /// `H_i^0(θ)` (to convert world-frame wrenches).
    pub pose_in_world: Vec<Se3<T>>,
}

fn block<T: Real>(m: &mut DMatrix<T>, i: usize, j: usize, b: &Matrix6<T>) {
    m.view_mut((6 * i, 6 * j), (6, 6)).copy_from(b);
}

fn get_block<T: Real>(m: &DMatrix<T>, i: usize, j: usize) -> Matrix6<T> {
    m.fixed_view::<6, 6>(6 * i, 6 * j).into_owned()
}

/// The largest model (in joints) for [`closed_form`]: its stacked matrices are `6n × 6n` and
/// their products cost O(n³), a teaching form for small arms; a larger model is refused before
/// anything is allocated.
pub const MAX_CLOSED_FORM_JOINTS: usize = 100;

/// `(h)⊼`: the matrix of `X ↦ −ad_Xᵀ h` (skew-symmetric).
pub(crate) fn bar_matrix<T: Real>(h: &Twist<T>) -> Matrix6<T> {
    let ha = -hat(&h.fixed_rows::<3>(0).into_owned());
    let hl = -hat(&h.fixed_rows::<3>(3).into_owned());
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&ha);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(&hl);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&hl);
    m
}

/// Builds the stacked closed form at `(θ, θ̇)`: `A`, `L`, `S`, `𝔍`, `ad_{Sθ̇}`, `V`, `ad_V`, `J`,
/// `M`, `C`, `g` (Lynch & Park, *Modern Robotics*, "General n-link manipulator dynamics" and "Adding Gravity";
/// Lynch & Park, *Modern Robotics*, "Dynamic Equations in Closed Form"). `τ = M θ̈ + C θ̇ + g − Jᵀ W_ext`.
///
/// # Errors
/// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or [`Error::NonFinite`](crate::Error::NonFinite) for a bad `q` or `v`.
///
/// ```
/// use screwdyn::{builtin, dynamics::closed_form};
/// let m = builtin::planar2();
/// let cf = closed_form(&m, &[0.0, std::f64::consts::FRAC_PI_2], &[0.0, 0.0]).unwrap();
/// // The table at θ2 = 90°: D11 = 3, D21 = 1, D22 = 1.
/// assert!((cf.m[(0, 0)] - 3.0).abs() < 1e-12 && (cf.m[(1, 0)] - 1.0).abs() < 1e-12);
/// // L(θ) has identity diagonal blocks and Ad_{H_1^2} below (print it with `println!("{}", cf.l)`).
/// assert_eq!(cf.l[(0, 0)], 1.0);
/// ```
pub fn closed_form<T: Real>(model: &Model<T>, q: &[T], v: &[T]) -> Result<ClosedForm<T>> {
    super::lagrange::check_size(
        model,
        MAX_CLOSED_FORM_JOINTS,
        "the stacked closed form (6n × 6n matrices, O(n³))",
    )?;
    model.check_vector(v, "v")?;
    let pose_in_world = forward_kinematics_poe(model, q)?;
    let n = model.nbodies();
    let mut a = DMatrix::zeros(6 * n, 6 * n);
    let mut l = DMatrix::zeros(6 * n, 6 * n);
    let mut s = DMatrix::zeros(6 * n, n);
    let mut inertia = DMatrix::zeros(6 * n, 6 * n);
    let mut ad_s_qdot = DMatrix::zeros(6 * n, 6 * n);
    let mut vdot_base = DVector::zeros(6 * n);
    let g0 = base_acceleration(model);
    for (i, joint) in model.joints().iter().enumerate() {
        let h = joint.pose_in_parent(q[i]); // H_i^{λ(i)}
        let ad_parent = h.inverse().adjoint_matrix(); // Ad_{H_{λ(i)}^i}
        block(&mut l, i, i, &Matrix6::identity());
        match model.parents()[i] {
            Some(p) => {
                block(&mut a, i, p, &ad_parent);
                // L_ij = Ad_{H_λ^i} L_{λ j} for every j supporting λ(i): Ad_{H_j^i}.
                for jj in 0..=p {
                    if model.supports_unchecked(jj, p) {
                        let b = ad_parent * get_block(&l, p, jj);
                        block(&mut l, i, jj, &b);
                    }
                }
            }
            None => {
                vdot_base
                    .fixed_rows_mut::<6>(6 * i)
                    .copy_from(&pose_in_world[i].inv_act_twist(&g0));
            }
        }
        s.view_mut((6 * i, i), (6, 1)).copy_from(&joint.screw);
        block(&mut inertia, i, i, &model.bodies()[i].inertia.matrix());
        block(&mut ad_s_qdot, i, i, &ad_matrix(&(joint.screw * v[i])));
    }
    let qd = DVector::from_column_slice(v);
    let j = &l * &s;
    let vel = &j * &qd;
    let mut ad_v = DMatrix::zeros(6 * n, 6 * n);
    let mut bar = DMatrix::zeros(6 * n, 6 * n);
    for i in 0..n {
        let vi: Twist<T> = vel.fixed_rows::<6>(6 * i).into_owned();
        block(&mut ad_v, i, i, &ad_matrix(&vi));
        let h = model.bodies()[i].inertia.apply(&vi);
        block(&mut bar, i, i, &bar_matrix(&h));
    }
    let jt = j.transpose();
    // M = Jᵀ 𝔍 J + I_a
    let armature = DMatrix::from_fn(n, n, |r, c| {
        if r == c {
            model.joints()[r].armature
        } else {
            T::zero()
        }
    });
    let m = &jt * &inertia * &j + &armature;
    let inner = -(&inertia * &l * &ad_s_qdot * &a) - ad_v.transpose() * &inertia;
    let c = &jt * inner * &j;
    let j_dot = -(&l * &ad_s_qdot * &a * &j);
    let psi = &j_dot + &ad_v * &j;
    let half: T = crate::scalar::real(0.5);
    let sym = (bar - &inertia * &ad_v - ad_v.transpose() * &inertia) * half;
    let c_christoffel = &jt * &inertia * psi + &jt * sym * &j;
    let g = &jt * &inertia * &l * &vdot_base;
    Ok(ClosedForm {
        a,
        l,
        s,
        inertia,
        ad_s_qdot,
        v: vel,
        ad_v,
        j,
        j_dot,
        vdot_base,
        armature,
        m,
        c,
        c_christoffel,
        g,
        qdot: qd,
        pose_in_world,
    })
}

impl<T: Real> ClosedForm<T> {
    /// `W_ext`: the external wrenches stacked in body frames (Lynch & Park, *Modern Robotics*).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `fext` was made for another model.
    pub fn stacked_wrenches(&self, fext: &ExternalWrenches<T>) -> Result<DVector<T>> {
        let n = self.pose_in_world.len();
        if fext.len() != n {
            return Err(Error::InvalidArgument(format!(
                "the external wrenches were made for {} bodies, the closed form for {n}",
                fext.len()
            )));
        }
        let mut w = DVector::zeros(6 * n);
        for i in 0..n {
            w.fixed_rows_mut::<6>(6 * i)
                .copy_from(&fext.on_body_at(&self.pose_in_world[i], i));
        }
        Ok(w)
    }

    /// `τ = M θ̈ + C θ̇ + g − Jᵀ W_ext` (Lynch & Park, *Modern Robotics*; `M` includes the armatures), with the velocity `θ̇` the form was built at.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`](crate::Error::InvalidArgument) when `qdd` does not have one value per joint or `fext` was made for another model; [`Error::NonFinite`](crate::Error::NonFinite) for NaN/∞ in `qdd`.
    ///
    /// ```
    /// use screwdyn::{builtin, dynamics::{closed_form, rnea}, Workspace};
    /// let m = builtin::planar2();
    /// let (q, v, a) = ([0.3, -0.7], [1.0, 2.0], [0.5, -0.25]);
    /// let tau = closed_form(&m, &q, &v).unwrap().inverse_dynamics(&a, None).unwrap();
    /// let mut ws = Workspace::new(&m);
    /// assert!((rnea(&m, &mut ws, &q, &v, &a).unwrap() - tau).amax() < 1e-12);
    /// ```
    pub fn inverse_dynamics(
        &self,
        qdd: &[T],
        fext: Option<&ExternalWrenches<T>>,
    ) -> Result<DVector<T>> {
        let n = self.qdot.len();
        if qdd.len() != n {
            return Err(Error::InvalidArgument(format!(
                "qdd has {} values, the closed form was built for {n} joints",
                qdd.len()
            )));
        }
        crate::model::check_finite(qdd, "qdd")?;
        let a = DVector::from_column_slice(qdd);
        let mut tau = &self.m * a + &self.c * &self.qdot + &self.g;
        if let Some(f) = fext {
            tau -= self.j.transpose() * self.stacked_wrenches(f)?;
        }
        Ok(tau)
    }

    /// The stacked recursion of Lynch & Park's *Modern Robotics* at acceleration `θ̈`:
    /// `V̇ = L S θ̈ − L ad_{Sθ̇} A V + L V̇_base` (gravity through `V̇_base`),
    /// `W = Lᵀ 𝔍 V̇ − Lᵀ ad_Vᵀ 𝔍 V` and `τ = Sᵀ W + I_a θ̈` (the armatures'
    /// torque, which no body's wrench carries). Returns `(V̇, W, τ)`.
    ///
    /// ```
    /// use screwdyn::{builtin, dynamics::{closed_form, rnea}, Workspace};
    /// let m = builtin::planar2();
    /// let (q, v, a) = ([0.3, -0.7], [1.0, 2.0], [0.5, -0.25]);
    /// let (vdot, w, tau) = closed_form(&m, &q, &v).unwrap().stacked_dynamics(&a).unwrap();
    /// let mut ws = Workspace::new(&m);
    /// assert!((rnea(&m, &mut ws, &q, &v, &a).unwrap() - &tau).amax() < 1e-12);
    /// // RNEA's V̇_2 and W_1, which it forms in {0}, in the bodies' own frames.
    /// let (h1, h2) = (&ws.pose_in_world[0], &ws.pose_in_world[1]);
    /// assert!((vdot.fixed_rows::<6>(6) - h2.inv_act_twist(&ws.twist_dot_in_world[1])).amax() < 1e-12);
    /// assert!((w.fixed_rows::<6>(0) - h1.act_transpose_wrench(&ws.wrench_in_world[0])).amax() < 1e-12);
    /// ```
    ///
    /// # Errors
    /// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) when `qdd` does not have
    /// one entry per joint.
    pub fn stacked_dynamics(&self, qdd: &[T]) -> Result<(DVector<T>, DVector<T>, DVector<T>)> {
        let n = self.s.ncols();
        if qdd.len() != n {
            return Err(crate::Error::DimensionMismatch {
                what: "a".into(),
                got: qdd.len(),
                expected: n,
                names: format!("{n} joints"),
            });
        }
        let a = DVector::from_column_slice(qdd);
        let vdot = &self.j * &a + &self.j_dot * &self.qdot + &self.l * &self.vdot_base;
        let w = self.l.transpose()
            * (&self.inertia * &vdot - self.ad_v.transpose() * (&self.inertia * &self.v));
        // τ = Sᵀ W + I_a θ̈
        let tau = self.s.transpose() * &w + &self.armature * a;
        Ok((vdot, w, tau))
    }
}
