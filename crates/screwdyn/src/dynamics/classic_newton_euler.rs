//! The classic vector Newton–Euler recursion (Craig's "iterative Newton–Euler" of *Introduction to Robotics*, Luh,
//! Walker & Paul's recursive algorithm): angular velocity `ω`, angular acceleration
//! `ω̇`, the classical linear acceleration `v̇` of the frame origin and `v̇_C` of the centre of
//! mass, Newton's `F = m v̇_C` and Euler's `N = ᶜI ω̇ + ω × ᶜI ω`, then the inward forces `f`,
//! moments `n` and the joint torque `τ` — every vector in the link's own frame.
//!
//! How it differs from the Lie-group recursion of Lynch & Park's *Modern Robotics* ([`rnea`](super::rnea)): the
//! twist derivative `V̇ = (ω̇, v̇_body)` is the derivative of the *body* twist, whose linear part
//! is not the acceleration of any material point: the classical acceleration of the frame origin
//! is `v̇ = v̇_body + ω × v` (`v` the origin's velocity in the frame). The forces agree:
//! `(n_i, f_i)` is the RNEA wrench `W_i` (moment about the frame origin), and `τ_i = S_iᵀ W_i`.

use crate::error::Result;
use crate::model::Model;
use nalgebra::Vector3;

/// One link's row of the classic Newton–Euler table, all in the link frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ClassicLink {
    /// `ω_i`: angular velocity.
    pub omega: Vector3<f64>,
    /// `ω̇_i`: angular acceleration.
    pub omega_dot: Vector3<f64>,
    /// `v_i`: velocity of the frame origin.
    pub v: Vector3<f64>,
    /// `v̇_i`: classical acceleration of the frame origin (gravity included as the base
    /// accelerating upwards).
    pub v_dot: Vector3<f64>,
    /// `v̇_{C_i}`: acceleration of the centre of mass.
    pub v_dot_com: Vector3<f64>,
    /// `F_i = m_i v̇_{C_i}`.
    pub force: Vector3<f64>,
    /// `N_i = ᶜI ω̇_i + ω_i × ᶜI ω_i`.
    pub moment: Vector3<f64>,
    /// `f_i`: force exerted on link `i` by its parent.
    pub f: Vector3<f64>,
    /// `n_i`: moment exerted on link `i` by its parent, about the frame origin.
    pub n: Vector3<f64>,
    /// `τ_i`: the joint torque (or force), `n_i · ŝ_i + f_i · v_{s,i} + I_a,i θ̈_i` (the last
    /// term the joint's armature, zero unless the model has one).
    pub tau: f64,
}

/// The classic vector Newton–Euler recursion (the outward and inward iterations of
/// Luh, Walker and Paul's algorithm, as in Craig's *Introduction to Robotics*) on any model, in the links' frames. For joint `i` with screw
/// axis `S_i = (ŝ, v_s)` in frame `i` (`ŝ = ẑ`, `v_s = 0` for Craig's revolute joint; `ŝ = 0`,
/// `v_s = ẑ` for a prismatic one), `R = R_i^{λ}`, `p` the origin of `i` in `λ`:
///
/// - outward: `ω_i = Rᵀ ω_λ + ŝ θ̇`, `ω̇_i = Rᵀ ω̇_λ + Rᵀω_λ × ŝ θ̇ + ŝ θ̈`,
///   `v̇_i = Rᵀ(v̇_λ + ω̇_λ × p + ω_λ × (ω_λ × p)) + 2 Rᵀω_λ × v_s θ̇ + ŝθ̇ × v_s θ̇ + v_s θ̈`
///   from `v̇_0 = −g`; `v̇_C = v̇_i + ω̇_i × c + ω_i × (ω_i × c)`; `F = m v̇_C`,
///   `N = ᶜI ω̇ + ω × ᶜI ω`;
/// - inward: `f_i = F_i + Σ_c R_c f_c`, `n_i = N_i + c × F_i + Σ_c (R_c n_c + p_c × R_c f_c)`,
///   `τ_i = n_i · ŝ + f_i · v_s + I_a,i θ̈_i` (`I_a,i` the joint's armature, the rotor inertia
///   reflected to it).
///
/// Allocates (a teaching function).
///
/// ```
/// use screwdyn::{builtin, dynamics::classic_newton_euler};
/// // The two-link arm at rest, horizontal: τ = [(m1 + m2) g L1 + m2 g L2, m2 g L2].
/// let t = classic_newton_euler(&builtin::planar2(), &[0.0, 0.0], &[0.0, 0.0], &[0.0, 0.0]).unwrap();
/// assert!((t[0].tau - 3.0 * 9.81).abs() < 1e-12 && (t[1].tau - 9.81).abs() < 1e-12);
/// // ¹v̇_C1 = (g s1, g c1, 0) at θ1 = 0 (Craig, *Introduction to Robotics*).
/// assert!((t[0].v_dot_com.y - 9.81).abs() < 1e-12);
/// ```
///
/// # Errors
/// [`Error::DimensionMismatch`](crate::Error::DimensionMismatch) or
/// [`Error::NonFinite`](crate::Error::NonFinite) for a bad `q`, `v` or `a`.
pub fn classic_newton_euler(
    model: &Model,
    q: &[f64],
    v: &[f64],
    a: &[f64],
) -> Result<Vec<ClassicLink>> {
    model.check_vector(q, "q")?;
    model.check_vector(v, "v")?;
    model.check_vector(a, "a")?;
    let n = model.nq();
    let zero = Vector3::zeros();
    let mut out: Vec<ClassicLink> = Vec::with_capacity(n);
    let mut poses = Vec::with_capacity(n);
    for (i, joint) in model.joints().iter().enumerate() {
        let h = joint.pose_in_parent(q[i]);
        let (r, p) = (h.rotation, h.translation);
        let s = Vector3::new(joint.screw[0], joint.screw[1], joint.screw[2]);
        let vs = Vector3::new(joint.screw[3], joint.screw[4], joint.screw[5]);
        let (w0, wd0, v0, vd0) = match model.parents()[i] {
            Some(k) => (out[k].omega, out[k].omega_dot, out[k].v, out[k].v_dot),
            None => (zero, zero, zero, -model.gravity()),
        };
        let w_in = r.transpose() * w0;
        let omega = w_in + s * v[i];
        let omega_dot = r.transpose() * wd0 + w_in.cross(&(s * v[i])) + s * a[i];
        let vel = r.transpose() * (v0 + w0.cross(&p)) + vs * v[i];
        let v_dot = r.transpose() * (vd0 + wd0.cross(&p) + w0.cross(&w0.cross(&p)))
            + (w_in * 2.0).cross(&(vs * v[i]))
            + (s * v[i]).cross(&(vs * v[i]))
            + vs * a[i];
        let inertia = &model.bodies()[i].inertia;
        let c = inertia.com;
        let v_dot_com = v_dot + omega_dot.cross(&c) + omega.cross(&omega.cross(&c));
        let force = v_dot_com * inertia.mass;
        let ic = inertia.inertia_com;
        let moment = ic * omega_dot + omega.cross(&(ic * omega));
        out.push(ClassicLink {
            omega,
            omega_dot,
            v: vel,
            v_dot,
            v_dot_com,
            force,
            moment,
            f: force,
            n: moment + c.cross(&force),
            tau: 0.0,
        });
        poses.push((r, p, s, vs));
    }
    for i in (0..n).rev() {
        let (r, p, s, vs) = poses[i];
        // τ_i = n_i · ŝ + f_i · v_s + I_a,i θ̈_i
        out[i].tau = out[i].n.dot(&s) + out[i].f.dot(&vs) + model.joints()[i].armature * a[i];
        if let Some(k) = model.parents()[i] {
            let f = r * out[i].f;
            let moment = r * out[i].n + p.cross(&f);
            out[k].f += f;
            out[k].n += moment;
        }
    }
    Ok(out)
}
