//! The mechanics written once over any [`Ring`]: joint transforms
//! `H_i^{λ(i)}(θ_i) = H_i^{λ(i)}(0) e^{[S_i] θ_i}`, body Jacobians `J = L S`, `M = Jᵀ 𝔍 J`, the
//! literal closed-form `C` of Lynch & Park's *Modern Robotics*, the RNEA of Lynch & Park's *Modern Robotics* (`τ`, `g`), energies, frame
//! poses and Jacobians.

use super::params::{clean, ParamKind, ParamTable};
use super::ring::{Inertia, Pose, Ring, Tw, M3, V3};
use crate::kinematics::Reference;
use crate::model::{JointKind, Model};

/// The joint variables and parameters as ring values.
#[derive(Clone, Debug)]
pub struct Vars<R> {
    /// `cos θ_i`.
    pub c: Vec<R>,
    /// `sin θ_i`.
    pub s: Vec<R>,
    /// `θ_i`.
    pub q: Vec<R>,
    /// `θ̇_i`.
    pub qd: Vec<R>,
    /// `θ̈_i`.
    pub qdd: Vec<R>,
    /// Every parameter of the table (a symbol or its numeric value).
    pub p: Vec<R>,
}

/// A model with every entry a ring value.
#[derive(Clone, Debug)]
pub struct SymRobot<R> {
    /// Number of joints.
    pub n: usize,
    /// `λ(i)`.
    pub parents: Vec<Option<usize>>,
    /// `S_i^{i,λ(i)}`.
    pub screw: Vec<Tw<R>>,
    /// `H_i^{λ(i)}(θ_i)`.
    pub joint_pose: Vec<Pose<R>>,
    /// `𝔍^{i,i}` by its ten parameters.
    pub inertia: Vec<Inertia<R>>,
    /// `g⁰`.
    pub gravity: V3<R>,
    /// `I_a,i`: each joint's armature (rotor inertia reflected to the joint).
    pub armature: Vec<R>,
}

fn numeric_pose<R: Ring>(h: &crate::spatial::Se3) -> Pose<R> {
    let r = h.rotation;
    Pose {
        r: M3::constant([0, 1, 2].map(|i| [0, 1, 2].map(|j| clean(r[(i, j)])))),
        p: V3::constant([0, 1, 2].map(|i| clean(h.translation[i]))),
    }
}

impl<R: Ring> SymRobot<R> {
    /// Builds the ring model from `model`, reading every parameter from `vars.p` (indexed like
    /// `table`).
    pub fn new(model: &Model, table: &ParamTable, vars: &Vars<R>) -> Self {
        let par = |k: ParamKind| vars.p[table.index(k)].clone();
        let n = model.nq();
        let mut screw = Vec::with_capacity(n);
        let mut joint_pose = Vec::with_capacity(n);
        for (i, j) in model.joints().iter().enumerate() {
            let home = numeric_pose::<R>(&j.home);
            let p = V3([0, 1, 2].map(|a| par(ParamKind::Length(i, a))));
            let w = [0, 1, 2].map(|a| clean(j.screw[a]));
            let v = [3, 4, 5].map(|a| clean(j.screw[a]));
            match j.kind {
                JointKind::Prismatic => {
                    let s = Tw {
                        w: V3::zero(),
                        v: V3::constant(v),
                    };
                    let t = home.r.mul_v(&s.v).times(&vars.q[i]).add(&p);
                    screw.push(s);
                    joint_pose.push(Pose { r: home.r, p: t });
                }
                _ => {
                    let h = match j.kind {
                        JointKind::Helical { pitch } => pitch,
                        _ => 0.0,
                    };
                    // Axis point in the child frame: r_c = ω × v (foot of the perpendicular).
                    let rc_num = [
                        w[1] * v[2] - w[2] * v[1],
                        w[2] * v[0] - w[0] * v[2],
                        w[0] * v[1] - w[1] * v[0],
                    ];
                    let scale = 1.0 + j.home.translation.norm();
                    let through_child = rc_num.iter().all(|x| x.abs() < 1e-12 * scale);
                    let rc_vec = nalgebra::Vector3::from(rc_num);
                    let rp = j.home.rotation * rc_vec + j.home.translation;
                    let wp = j.home.rotation * nalgebra::Vector3::from(w);
                    let foot = rp - wp * wp.dot(&rp);
                    // Where the axis passes: through the child origin (r_c = 0), through the
                    // parent origin (r_c = −R0ᵀ p, so the offset turns with the joint:
                    // t = R0 Rot R0ᵀ p), or through a point fixed in the parent.
                    enum Axis {
                        Child,
                        Parent,
                        Fixed,
                    }
                    let axis = if through_child {
                        Axis::Child
                    } else if foot.norm() < 1e-12 * scale {
                        Axis::Parent
                    } else {
                        Axis::Fixed
                    };
                    let rc: V3<R> = match axis {
                        Axis::Child => V3::zero(),
                        Axis::Parent => home.r.tr_mul_v(&p.neg()),
                        Axis::Fixed => home
                            .r
                            .tr_mul_v(&V3::constant([0, 1, 2].map(|a| rp[a])).sub(&p)),
                    };
                    let wv = V3::<R>::constant(w);
                    let s = Tw {
                        w: wv.clone(),
                        v: wv.cross(&rc).neg().add(&wv.times(&R::constant(h))),
                    };
                    // e^{[ω]θ} = c (1 − ωωᵀ) + s [ω] + ωωᵀ
                    let hat = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
                    let rot = M3([0, 1, 2].map(|a| {
                        [0, 1, 2].map(|b| {
                            let ww = w[a] * w[b];
                            let id = if a == b { 1.0 } else { 0.0 };
                            vars.c[i]
                                .scale(clean(id - ww))
                                .add(&vars.s[i].scale(hat[a][b]))
                                .add(&R::constant(clean(ww)))
                        })
                    }));
                    let r = home.r.mul_m(&rot);
                    // t = p + R0 (r_c − Rot r_c) + R0 ω h θ
                    let mut t = match axis {
                        Axis::Child => p.clone(),
                        Axis::Parent => home.r.mul_v(&rot.mul_v(&home.r.tr_mul_v(&p))),
                        Axis::Fixed => p.add(&home.r.mul_v(&rc.sub(&rot.mul_v(&rc)))),
                    };
                    if h != 0.0 {
                        t = t.add(&home.r.mul_v(&wv.times(&vars.q[i].scale(h))));
                    }
                    screw.push(s);
                    joint_pose.push(Pose { r, p: t });
                }
            }
        }
        let inertia = (0..n)
            .map(|i| {
                let m = par(ParamKind::Mass(i));
                let c = V3([0, 1, 2].map(|a| par(ParamKind::Com(i, a))));
                let e = |r: usize, c: usize| {
                    let k = match (r.min(c), r.max(c)) {
                        (0, 0) => 0,
                        (0, 1) => 1,
                        (0, 2) => 2,
                        (1, 1) => 3,
                        (1, 2) => 4,
                        _ => 5,
                    };
                    par(ParamKind::Inertia(i, k))
                };
                let ic = M3([0, 1, 2].map(|r| [0, 1, 2].map(|c| e(r, c))));
                Inertia::from_com(m, &c, &ic)
            })
            .collect();
        let g0 = model.gravity();
        let gn = g0.norm();
        let gpar = par(ParamKind::Gravity);
        let gravity = if gn == 0.0 {
            V3::zero()
        } else {
            V3([0, 1, 2].map(|a| gpar.scale(clean(g0[a] / gn))))
        };
        let armature = (0..n).map(|i| par(ParamKind::Armature(i))).collect();
        SymRobot {
            n,
            parents: model.parents().to_vec(),
            screw,
            joint_pose,
            inertia,
            gravity,
            armature,
        }
    }

    /// `H_i^0(θ)` for every body.
    pub fn world_poses(&self) -> Vec<Pose<R>> {
        let mut out: Vec<Pose<R>> = Vec::with_capacity(self.n);
        for i in 0..self.n {
            let h = match self.parents[i] {
                Some(p) => out[p].compose(&self.joint_pose[i]),
                None => self.joint_pose[i].clone(),
            };
            out.push(h);
        }
        out
    }

    /// The body Jacobians `J_k^{k,0}` (block rows of the `J = L S`): column `j` is
    /// `Ad_{H_j^k} S_j` when joint `j` supports body `k`, `None` otherwise.
    pub fn body_jacobians(&self) -> Vec<Vec<Option<Tw<R>>>> {
        let mut out: Vec<Vec<Option<Tw<R>>>> = Vec::with_capacity(self.n);
        for k in 0..self.n {
            let mut cols: Vec<Option<Tw<R>>> = match self.parents[k] {
                Some(p) => out[p]
                    .iter()
                    .map(|c| c.as_ref().map(|s| self.joint_pose[k].inv_act_twist(s)))
                    .collect(),
                None => vec![None; self.n],
            };
            cols[k] = Some(self.screw[k].clone());
            out.push(cols);
        }
        out
    }

    /// `M(θ) = Sᵀ Lᵀ 𝔍 L S + I_a = Σ_k J_kᵀ 𝔍_k J_k + diag(I_a,i)` (Lynch & Park, *Modern
    /// Robotics*, and the joints' armatures), row-major.
    pub fn mass_matrix(&self) -> Vec<R> {
        let n = self.n;
        let jac = self.body_jacobians();
        let mut m = vec![R::zero(); n * n];
        for (k, jk) in jac.iter().enumerate() {
            for j in 0..n {
                let Some(cj) = &jk[j] else { continue };
                let f = self.inertia[k].apply(cj);
                for i in 0..=j {
                    if let Some(ci) = &jk[i] {
                        m[i * n + j] = m[i * n + j].add(&ci.dot(&f));
                    }
                }
            }
        }
        // + diag(I_a,i)
        for (i, a) in self.armature.iter().enumerate() {
            m[i * n + i] = m[i * n + i].add(a);
        }
        for i in 0..n {
            for j in 0..i {
                m[i * n + j] = m[j * n + i].clone();
            }
        }
        m
    }

    /// The literal `C(θ, θ̇) = Sᵀ Lᵀ [−𝔍 L ad_{Sθ̇} A − ad_Vᵀ 𝔍] L S` (Lynch & Park, *Modern Robotics*), row-major:
    /// with `J = L S`, `Y = L ad_{Sθ̇} A J` (block `k`: `Y_k = Ad_{H_λ^k} Y_λ + ad_{S_k θ̇_k}
    /// Ad_{H_λ^k} J_λ`) and `V_k = J_k θ̇`, `C = −Σ_k J_kᵀ (𝔍_k Y_k + ad_{V_k}ᵀ 𝔍_k J_k)`.
    pub fn coriolis_seed(&self, qd: &[R]) -> Vec<R> {
        let n = self.n;
        let jac = self.body_jacobians();
        let mut y: Vec<Vec<Option<Tw<R>>>> = Vec::with_capacity(n);
        let mut c = vec![R::zero(); n * n];
        for k in 0..n {
            let yk: Vec<Option<Tw<R>>> = match self.parents[k] {
                Some(p) => (0..n)
                    .map(|j| {
                        let from_parent = y[p][j]
                            .as_ref()
                            .map(|t| self.joint_pose[k].inv_act_twist(t));
                        let x = jac[p][j].as_ref().map(|t| {
                            self.screw[k]
                                .times(&qd[k])
                                .ad(&self.joint_pose[k].inv_act_twist(t))
                        });
                        match (from_parent, x) {
                            (Some(a), Some(b)) => Some(a.add(&b)),
                            (a, b) => a.or(b),
                        }
                    })
                    .collect(),
                None => vec![None; n],
            };
            let mut vk = Tw::zero();
            for (j, col) in jac[k].iter().enumerate() {
                if let Some(col) = col {
                    vk = vk.add(&col.times(&qd[j]));
                }
            }
            for j in 0..n {
                let mut w = match &yk[j] {
                    Some(t) => self.inertia[k].apply(t),
                    None => Tw::zero(),
                };
                if let Some(cj) = &jac[k][j] {
                    w = w.add(&vk.ad_transpose(&self.inertia[k].apply(cj)));
                }
                for i in 0..n {
                    if let Some(ci) = &jac[k][i] {
                        c[i * n + j] = c[i * n + j].sub(&ci.dot(&w));
                    }
                }
            }
            y.push(yk);
        }
        c
    }

    /// The RNEA of Lynch & Park's *Modern Robotics* with the given inertias: forward pass
    /// `V_i = Ad V_λ + S_i θ̇_i`, `V̇_i = Ad V̇_λ − ad_{S_i θ̇_i}(Ad V_λ) + S_i θ̈_i` from
    /// `V̇_0 = (0, −g⁰)` (or `0` without gravity), backward pass
    /// `W_i = 𝔍_i V̇_i − ad_{V_i}ᵀ 𝔍_i V_i + Σ Ad_{H_i^c}ᵀ W_c`, `τ_i = S_iᵀ W_i`.
    pub fn rnea_with(
        &self,
        inertia: &[Inertia<R>],
        qd: Option<&[R]>,
        qdd: Option<&[R]>,
        gravity: bool,
    ) -> Vec<R> {
        let n = self.n;
        let base = Tw {
            w: V3::zero(),
            v: if gravity {
                self.gravity.neg()
            } else {
                V3::zero()
            },
        };
        let mut v: Vec<Tw<R>> = Vec::with_capacity(n);
        let mut vd: Vec<Tw<R>> = Vec::with_capacity(n);
        let mut w: Vec<Tw<R>> = Vec::with_capacity(n);
        for i in 0..n {
            let x = &self.joint_pose[i];
            let (mut vi, mut vdi) = match self.parents[i] {
                Some(p) => (x.inv_act_twist(&v[p]), x.inv_act_twist(&vd[p])),
                None => (Tw::zero(), x.inv_act_twist(&base)),
            };
            if let Some(qd) = qd {
                let sq = self.screw[i].times(&qd[i]);
                vdi = vdi.sub(&sq.ad(&vi));
                vi = vi.add(&sq);
            }
            if let Some(qdd) = qdd {
                vdi = vdi.add(&self.screw[i].times(&qdd[i]));
            }
            let j = &inertia[i];
            let wi = j.apply(&vdi).sub(&vi.ad_transpose(&j.apply(&vi)));
            v.push(vi);
            vd.push(vdi);
            w.push(wi);
        }
        let mut tau = vec![R::zero(); n];
        for i in (0..n).rev() {
            tau[i] = self.screw[i].dot(&w[i]);
            if let Some(p) = self.parents[i] {
                let back = self.joint_pose[i].inv_act_transpose_wrench(&w[i]);
                w[p] = w[p].add(&back);
            }
        }
        tau
    }

    /// `τ(θ, θ̇, θ̈) = M θ̈ + C θ̇ + g` by the RNEA, plus the armatures' `I_a,i θ̈_i`.
    pub fn inverse_dynamics(&self, qd: &[R], qdd: &[R]) -> Vec<R> {
        let mut tau = self.rnea_with(&self.inertia, Some(qd), Some(qdd), true);
        // τ_i += I_a,i θ̈_i
        for ((t, a), qddi) in tau.iter_mut().zip(&self.armature).zip(qdd) {
            *t = t.add(&a.mul(qddi));
        }
        tau
    }

    /// `g(θ)`: the RNEA at rest (the `Sᵀ Lᵀ 𝔍 L V̇_base`).
    pub fn gravity_torque(&self) -> Vec<R> {
        self.rnea_with(&self.inertia, None, None, true)
    }

    /// `C(θ, θ̇) θ̇`: the RNEA without gravity and acceleration.
    pub fn velocity_torque(&self, qd: &[R]) -> Vec<R> {
        self.rnea_with(&self.inertia, Some(qd), None, false)
    }

    /// The regressor `Y(θ, θ̇, θ̈)` with `τ = Y π`, `π` = for each body `(m, m cx, m cy, m cz,
    /// Ixx, Ixy, Ixz, Iyy, Iyz, Izz)` (inertia about the body-frame origin): column `k` is the
    /// RNEA with `π = e_k` (τ is linear in `π`). Row-major, `n × 10n`. The armatures are a known
    /// term outside it, as in [`crate::dynamics::regressor`]: `τ = Y π + I_a θ̈`.
    pub fn regressor(&self, qd: &[R], qdd: &[R]) -> Vec<R> {
        let n = self.n;
        let zero_inertia = || Inertia {
            m: R::zero(),
            h: V3::zero(),
            io: M3([0, 1, 2].map(|_| [0, 1, 2].map(|_| R::zero()))),
        };
        let mut y = vec![R::zero(); n * 10 * n];
        for b in 0..n {
            for k in 0..10 {
                let mut list: Vec<Inertia<R>> = (0..n).map(|_| zero_inertia()).collect();
                let one = R::constant(1.0);
                let e = &mut list[b];
                match k {
                    0 => e.m = one,
                    1..=3 => e.h.0[k - 1] = one,
                    _ => {
                        let (r, c) = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)][k - 4];
                        e.io.0[r][c] = one.clone();
                        e.io.0[c][r] = one;
                    }
                }
                let col = self.rnea_with(&list, Some(qd), Some(qdd), true);
                for (i, t) in col.into_iter().enumerate() {
                    y[i * 10 * n + 10 * b + k] = t;
                }
            }
        }
        y
    }

    /// Kinetic energy `½ Σ_k V_kᵀ 𝔍_k V_k + ½ Σ_i I_a,i θ̇_i²` (Lynch & Park, *Modern Robotics*,
    /// and the rotors).
    pub fn kinetic_energy(&self, qd: &[R]) -> R {
        let mut v: Vec<Tw<R>> = Vec::with_capacity(self.n);
        let mut e = R::zero();
        for (i, qdi) in qd.iter().enumerate().take(self.n) {
            let mut vi = match self.parents[i] {
                Some(p) => self.joint_pose[i].inv_act_twist(&v[p]),
                None => Tw::zero(),
            };
            vi = vi.add(&self.screw[i].times(qdi));
            e = e.add(&vi.dot(&self.inertia[i].apply(&vi)));
            // + I_a,i θ̇_i²
            e = e.add(&self.armature[i].mul(qdi).mul(qdi));
            v.push(vi);
        }
        e.scale(0.5)
    }

    /// Potential energy `P = −Σ_k m_k g⁰ · p_{c,k}⁰ = −Σ_k g⁰ · (R_k h_k + m_k p_k)`.
    pub fn potential_energy(&self) -> R {
        let poses = self.world_poses();
        let mut e = R::zero();
        for (k, h) in poses.iter().enumerate() {
            let j = &self.inertia[k];
            let mc = h.r.mul_v(&j.h).add(&h.p.times(&j.m));
            e = e.sub(&self.gravity.dot(&mc));
        }
        e
    }

    /// The Jacobian (6×n, row-major, angular rows first) of a frame on `body` placed at
    /// `placement` in it, in `reference`.
    pub fn frame_jacobian(&self, body: usize, placement: &Pose<R>, reference: Reference) -> Vec<R> {
        let n = self.n;
        let jac = self.body_jacobians();
        let world = self.world_poses()[body].compose(placement);
        let mut out = vec![R::zero(); 6 * n];
        for (j, col) in jac[body].iter().enumerate() {
            let Some(col) = col else { continue };
            let local = placement.inv_act_twist(col);
            let t = match reference {
                Reference::Local => local,
                Reference::World => world.act_twist(&local),
                Reference::LocalWorldAligned => Tw {
                    w: world.r.mul_v(&local.w),
                    v: world.r.mul_v(&local.v),
                },
            };
            for (r, e) in t.entries().into_iter().enumerate() {
                out[r * n + j] = e;
            }
        }
        out
    }
}
