//! The equations of motion along a path: with `q = q(s)`, `q̇ = q' ṡ` and
//! `q̈ = q' s̈ + q'' ṡ²`, the joint torque `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` becomes
//! `τ = a(s) s̈ + b(s) ṡ² + c(s)`, linear in `(s̈, ṡ²)`.

use super::spline::Path;
use crate::dynamics::base_acceleration;
use crate::error::{Error, Result};
use crate::kinematics::poses_in_parent;
use crate::model::Model;
use crate::spatial::{ad_transpose, Twist, Wrench};
use crate::workspace::Workspace;

/// The path and its dynamics at one `s`: `q`, `q'`, `q''` and the coefficients `a`, `b`, `c`
/// of `τ = a s̈ + b ṡ² + c` (one entry per joint).
#[derive(Clone, Debug, PartialEq)]
pub struct PathPoint {
    /// `q(s)`.
    pub q: Vec<f64>,
    /// `q'(s) = dq/ds`.
    pub dq: Vec<f64>,
    /// `q''(s) = d²q/ds²`.
    pub ddq: Vec<f64>,
    /// `a(s) = M(q) q'`.
    pub a: Vec<f64>,
    /// `b(s) = M(q) q'' + C(q, q') q'`.
    pub b: Vec<f64>,
    /// `c(s) = g(q) + k ∘ (q − q_spring) + f ∘ sign(q')`: gravity plus the model's joint
    /// springs and Coulomb friction (moving forward along the path, `ṡ > 0`).
    pub c: Vec<f64>,
}

/// Evaluates [`PathPoint`]s of one model along paths, allocating nothing per call: the poses
/// of the bodies in their parents (forward kinematics without the world poses) and three
/// passes of the recursive Newton–Euler algorithm per point, run side by side,
///
/// ```text
/// c = RNEA_g(q, 0, 0) + f ∘ sign(q'),   a = RNEA_0(q, 0, q'),   b = RNEA_0(q, q', q''),
/// ```
///
/// where `RNEA_g` has the base accelerating at `−g` (gravity) and `RNEA_0` is at rest (no
/// gravity), since `RNEA_0(q, q̇, q̈) = M q̈ + C(q, q̇) q̇` and `C(q, q') q'` is quadratic in `q'`.
/// Whatever the model's inverse dynamics includes (joint armature in `M`) is included here.
/// Viscous damping (`−b_i q̇_i`, linear in `ṡ`, not in `ṡ²`) is not part of this form.
///
/// ```
/// use screwdyn::motion::{CubicSpline, PathDynamics};
/// let m = screwdyn::builtin::pendulum(); // 1 kg at 1 m: M = 1, g(q) = 9.81 sin q
/// let path = CubicSpline::new(&[0.0, 1.0], &[vec![0.0], vec![0.5]]).unwrap();
/// let mut pd = PathDynamics::new(&m, 1).unwrap();
/// let p = pd.at(&m, &path, 1.0).unwrap();
/// assert!((p.a[0] - 0.5).abs() < 1e-12 && p.b[0].abs() < 1e-12);
/// assert!((p.c[0] - 9.81 * 0.5_f64.sin()).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct PathDynamics {
    ws: Workspace,
    extra: ExtraPasses,
    point: PathPoint,
}

impl PathDynamics {
    /// A workspace for `model` and paths of `nq` joints.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when `nq` is not the model's number of joints.
    pub fn new(model: &Model, nq: usize) -> Result<Self> {
        if nq != model.nq() {
            return Err(Error::InvalidArgument(format!(
                "the path has {nq} joints, the model has {}",
                model.nq()
            )));
        }
        let z = vec![0.0; nq];
        Ok(PathDynamics {
            ws: Workspace::new(model),
            extra: ExtraPasses {
                accel_a: vec![Twist::zeros(); model.nbodies()],
                accel_c: vec![Twist::zeros(); model.nbodies()],
                wrench_a: vec![Wrench::zeros(); model.nbodies()],
                wrench_c: vec![Wrench::zeros(); model.nbodies()],
            },
            point: PathPoint {
                q: z.clone(),
                dq: z.clone(),
                ddq: z.clone(),
                a: z.clone(),
                b: z.clone(),
                c: z,
            },
        })
    }

    /// The path and its dynamics at `s`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a model other than the one this was made for;
    /// [`Error::NonFinite`] when the path gives NaN or ∞ at `s`.
    pub fn at(&mut self, model: &Model, path: &dyn Path, s: f64) -> Result<&PathPoint> {
        let p = &mut self.point;
        path.eval(s, &mut p.q, &mut p.dq, &mut p.ddq);
        model.check_vector(&p.dq, "q'")?;
        model.check_vector(&p.ddq, "q''")?;
        // The passes use the poses in the parents only: no world poses.
        poses_in_parent(model, &mut self.ws, &p.q)?;
        three_passes(model, &mut self.ws, &mut self.extra, p);
        // c += k ∘ (q − q_spring) + f ∘ sign(q'): springs, and Coulomb friction moving forward
        // along the path (ṡ > 0, so sign(q̇) = sign(q')).
        model.add_spring_and_friction_torques(&p.q, &p.dq, &mut p.c);
        Ok(&self.point)
    }
}

/// The accelerations and wrenches of the passes for `a` and `c`, per body (those for `b` are
/// the workspace's).
#[derive(Clone, Debug)]
struct ExtraPasses {
    accel_a: Vec<Twist>,
    accel_c: Vec<Twist>,
    wrench_a: Vec<Wrench>,
    wrench_c: Vec<Wrench>,
}

/// The three passes of the recursive Newton–Euler algorithm (Lynch & Park, *Modern Robotics*)
/// side by side on the poses in the parents at `q`, the velocity terms only in the one
/// that has a velocity:
///
/// ```text
/// V_i   = Ad V_λ + S_i q'_i                                  (b only)
/// V̇b_i = Ad V̇b_λ − ad_{S_i q'_i}(Ad V_λ) + S_i q''_i,   W_b = 𝔍 V̇b − ad_Vᵀ 𝔍 V
/// V̇a_i = Ad V̇a_λ + S_i q'_i,                             W_a = 𝔍 V̇a
/// V̇c_i = Ad V̇c_λ  (V̇c_base = (0, −g)),                   W_c = 𝔍 V̇c
/// W_λ += Ad_{H_λ^i}ᵀ W_i,   τ_i = S_iᵀ W_i + I_a,i q̈_i   (q̈ = q'' for b, q' for a, 0 for c)
/// ```
fn three_passes(model: &Model, ws: &mut Workspace, x: &mut ExtraPasses, p: &mut PathPoint) {
    let n = model.nbodies();
    let (motions, parents, bodies) = (model.motions(), model.parents(), model.bodies());
    let base_c = base_acceleration(model);
    for i in 0..n {
        let h = &ws.pose_in_parent[i];
        let m = &motions[i];
        let (mut v, mut vd_b, mut vd_a, vd_c) = match parents[i] {
            Some(l) => (
                h.inv_act_twist(&ws.twist[l]),
                h.inv_act_twist(&ws.twist_dot[l]),
                h.inv_act_twist(&x.accel_a[l]),
                h.inv_act_twist(&x.accel_c[l]),
            ),
            None => (
                Twist::zeros(),
                Twist::zeros(),
                Twist::zeros(),
                h.inv_act_twist(&base_c),
            ),
        };
        vd_b -= m.ad_scaled(p.dq[i], &v);
        m.add_scaled(&mut v, p.dq[i]);
        m.add_scaled(&mut vd_b, p.ddq[i]);
        m.add_scaled(&mut vd_a, p.dq[i]);
        let inertia = &bodies[i].inertia;
        ws.wrench[i] = inertia.apply(&vd_b) - ad_transpose(&v, &inertia.apply(&v));
        x.wrench_a[i] = inertia.apply(&vd_a);
        x.wrench_c[i] = inertia.apply(&vd_c);
        ws.twist[i] = v;
        ws.twist_dot[i] = vd_b;
        x.accel_a[i] = vd_a;
        x.accel_c[i] = vd_c;
    }
    let joints = model.joints();
    for i in (0..n).rev() {
        let (m, armature) = (&motions[i], joints[i].armature);
        p.b[i] = m.dot(&ws.wrench[i]) + armature * p.ddq[i];
        p.a[i] = m.dot(&x.wrench_a[i]) + armature * p.dq[i];
        p.c[i] = m.dot(&x.wrench_c[i]);
        if let Some(l) = parents[i] {
            let h = &ws.pose_in_parent[i];
            let back = [
                h.inv_act_transpose_wrench(&ws.wrench[i]),
                h.inv_act_transpose_wrench(&x.wrench_a[i]),
                h.inv_act_transpose_wrench(&x.wrench_c[i]),
            ];
            ws.wrench[l] += back[0];
            x.wrench_a[l] += back[1];
            x.wrench_c[l] += back[2];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::{coriolis_matrix, mass_matrix};
    use crate::motion::CubicSpline;

    #[test]
    fn coefficients_match_the_mass_and_coriolis_matrices() {
        // a = M q', b = M q'' + C(q, q') q' from CRBA and the Coriolis matrix.
        let m = crate::builtin::load("ur5").unwrap();
        let pts = vec![
            vec![0.0, -1.0, 1.0, 0.0, 0.5, 0.0],
            vec![0.5, -0.5, 1.5, 0.3, 0.2, 0.1],
            vec![1.0, -1.2, 0.8, -0.2, 0.6, 0.4],
        ];
        let path = CubicSpline::chord_length(&pts).unwrap();
        let mut pd = PathDynamics::new(&m, 6).unwrap();
        let s = 0.7;
        let p = pd.at(&m, &path, s).unwrap().clone();
        let mut ws = Workspace::new(&m);
        let mm = mass_matrix(&m, &mut ws, &p.q).unwrap().clone();
        let cc = coriolis_matrix(&m, &mut ws, &p.q, &p.dq).unwrap().clone();
        let dq = nalgebra::DVector::from_column_slice(&p.dq);
        let ddq = nalgebra::DVector::from_column_slice(&p.ddq);
        let a = &mm * &dq;
        let b = &mm * &ddq + &cc * &dq;
        let g = crate::dynamics::gravity_torque(&m, &mut ws, &p.q)
            .unwrap()
            .clone();
        for j in 0..6 {
            assert!((p.a[j] - a[j]).abs() < 1e-10, "a[{j}]");
            assert!((p.b[j] - b[j]).abs() < 1e-10, "b[{j}]");
            let friction = m.joints()[j].friction * p.dq[j].signum();
            assert!((p.c[j] - g[j] - friction).abs() < 1e-10, "c[{j}]");
        }
        assert!(PathDynamics::new(&m, 2).is_err());
    }
}
