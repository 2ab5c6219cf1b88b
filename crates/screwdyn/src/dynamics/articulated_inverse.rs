//! `M⁻¹` and products `M⁻¹ X` by articulated-body sweeps (Carpentier's `computeMinverse` idea,
//! Carpentier & Mansard, *Analytical derivatives of rigid body dynamics algorithms*, RSS 2018),
//! written in the base-frame form of [`aba`](super::aba) and reusing the articulated quantities
//! its pass 2 has just computed for the configuration `q`.
//!
//! # Equations
//!
//! With `q̇ = 0` and no gravity the articulated-body algorithm maps joint torques `τ` to
//! `q̈ = M⁻¹ τ`, and every step of it is linear in `τ`. In the base frame {0}, with
//! `s_i = Ad_{H_i^0} S_i`, the articulated inertia `𝔍ᴬ_i`, `U_i = 𝔍ᴬ_i s_i` and
//! `D_i = s_iᵀ U_i + I_a,i` of ABA's pass 2 (they depend on `q` only):
//!
//! ```text
//! backward (leaves to root):  u_i = τ_i − s_iᵀ pᴬ_i,   pᴬ_λ(i) += pᴬ_i + (U_i / D_i) u_i
//! forward  (root to leaves):  q̈_i = u_i / D_i − (U_i / D_i)ᵀ A_λ(i),   A_i = A_λ(i) + s_i q̈_i
//! ```
//!
//! with `pᴬ_i = 0` before its children add to it and `A_base = 0` (ABA's `c_i`, `pᴬ` of the body
//! itself and `V̇_base = (0, −g)` vanish with the velocity and gravity). For `k` right-hand
//! sides at once (the columns of an `n × k` matrix `X`) the wrench `pᴬ_i` becomes a 6 × k block
//! `F_i`, the acceleration `A_i` a 6 × k block, and `u_i`, `q̈_i` rows of k entries: the sweep
//! costs about 24 multiply–adds per body and column, `24 n k` in all, where the dense product
//! `M⁻¹ X` costs `n² k`.
//!
//! For `M⁻¹` itself (`X = 1`), column `j` is `τ = e_j`: `F_i` has a non-zero column `j` only when
//! `j` is a strict descendant of `i` (`j > i` in the depth-first order), so the backward sweep of
//! columns `j₀ … j₁ − 1` starts at body `j₁ − 1`; and `M⁻¹` is symmetric, so the forward sweep
//! only forms the rows `i < j₁` and the rest is mirrored: about `12 n²` multiply–adds.
//!
//! # Storage
//!
//! Columns are taken [`LANES`] at a time. The blocks `F_i` and `A_i` are kept in a stack of
//! 6 × [`LANES`] slots: a body's last child (highest index) works in its parent's slot in place,
//! any other child in the next slot up, so that a chain needs one slot and a tree one per
//! nesting of branches (the subtree of a child is contiguous in the depth-first order and done
//! before its earlier siblings are, in the backward sweep, or its later ones, in the forward
//! sweep). The backward slots are left zero by every sweep: a non-last child adds to its
//! parent's slot and clears its own. Nothing is allocated per call.

use crate::model::Model;
use crate::scalar::Real;
use crate::spatial::{Twist, Wrench};
use crate::workspace::Workspace;
use nalgebra::DMatrix;

/// The number of columns one sweep carries (the width of the blocks `F_i`, `A_i`).
pub(crate) const LANES: usize = 8;

/// One 6 × [`LANES`] block: row `r` of `F_i` or `A_i` for the lanes' columns.
type Block<T> = [[T; LANES]; 6];

/// `slot_of[i]`: flag of a body with children.
const HAS_CHILDREN: usize = 1;
/// `slot_of[i]`: flag of a body that is its parent's last child (or the last root).
const LAST_CHILD: usize = 2;
/// `slot_of[i]`: flag of a body with more than one child.
const BRANCHES: usize = 4;
/// `slot_of[i] >> SLOT`: the body's slot.
const SLOT: u32 = 3;

/// The scratch of the sweeps, kept in the [`Workspace`] (made on the first call of
/// [`aba_derivatives`](super::aba_derivatives)).
#[derive(Clone, Debug)]
pub(crate) struct ArticulatedSweep<T: Real> {
    /// `1 / D_i`.
    inv_d: Vec<T>,
    /// Each body's slot and flags, `slot << SLOT | BRANCHES | LAST_CHILD | HAS_CHILDREN`.
    slot_of: Vec<usize>,
    /// The rows `u_i / D_i`, then `q̈_i`, of one sweep.
    rows: Vec<[T; LANES]>,
    /// The slots of the blocks `F_i` (backward) and `A_i` (forward).
    back: Vec<Block<T>>,
    fwd: Vec<Block<T>>,
}

impl<T: Real> ArticulatedSweep<T> {
    /// The scratch for `n` bodies.
    pub(crate) fn new(n: usize) -> Self {
        ArticulatedSweep {
            inv_d: vec![T::zero(); n],
            slot_of: vec![0; n],
            rows: vec![[T::zero(); LANES]; n],
            back: vec![[[T::zero(); LANES]; 6]; n + 1],
            fwd: vec![[[T::zero(); LANES]; 6]; n + 1],
        }
    }

    /// No scratch (until the first call).
    pub(crate) fn empty() -> Self {
        Self::new(0)
    }

    /// The number of bodies it was made for.
    pub(crate) fn len(&self) -> usize {
        self.inv_d.len()
    }
}

/// The per-body slot of the sweeps and its flags (`slot << SLOT | BRANCHES | LAST_CHILD |
/// HAS_CHILDREN`) in `slot_of`; returns the number of slots used.
fn assign_slots(parents: &[Option<usize>], slot_of: &mut [usize]) -> usize {
    slot_of.fill(0);
    // Leaves to root: the first child met of each parent is its last one.
    let mut root_seen = false;
    for i in (0..parents.len()).rev() {
        let seen = match parents[i] {
            Some(p) => {
                let seen = slot_of[p] & HAS_CHILDREN != 0;
                slot_of[p] |= if seen { BRANCHES } else { HAS_CHILDREN };
                seen
            }
            None => std::mem::replace(&mut root_seen, true),
        };
        if !seen {
            slot_of[i] |= LAST_CHILD;
        }
    }
    // Root to leaves: the last child shares its parent's slot, any other takes the next one.
    let mut used = 1;
    for i in 0..parents.len() {
        let parent_slot = parents[i].map_or(0, |p| slot_of[p] >> SLOT);
        let slot = parent_slot + usize::from(slot_of[i] & LAST_CHILD == 0);
        used = used.max(slot + 1);
        slot_of[i] |= slot << SLOT;
    }
    used
}

/// The articulated quantities of one sweep, all of length `n`.
struct Articulated<'a, T: Real> {
    screws: &'a [Twist<T>],
    u_over_d: &'a [Wrench<T>],
    inv_d: &'a [T],
    parents: &'a [Option<usize>],
    slot_of: &'a [usize],
}

/// If `inverse`, `M⁻¹` into `ws.mass_matrix_inverse` (both triangles); if `products`,
/// `−M⁻¹ ∂τ/∂q`, `−M⁻¹ ∂τ/∂q̇` into `ws.dqdd_dq`, `ws.dqdd_dv`: from the screws
/// `ws.screw_in_world` and the articulated quantities `ws.articulated_force` (`U_i / D_i`) and
/// `ws.articulated_joint_inertia` (`D_i`) that ABA's pass 2 left for the present `q` (module
/// docs give the equations).
pub(crate) fn articulated_inverse_and_products<T: Real>(
    model: &Model<T>,
    ws: &mut Workspace<T>,
    inverse: bool,
    products: bool,
) {
    if !inverse && !products {
        return;
    }
    let n = model.nbodies();
    let Workspace {
        screw_in_world,
        articulated_force,
        articulated_joint_inertia,
        articulated_sweep,
        mass_matrix_inverse,
        dtau_dq,
        dtau_dv,
        dqdd_dq,
        dqdd_dv,
        ..
    } = ws;
    let ArticulatedSweep {
        inv_d,
        slot_of,
        rows,
        back,
        fwd,
    } = articulated_sweep;
    let slot_of = &mut slot_of[..n];
    let nslots = assign_slots(&model.parents()[..n], slot_of);
    let inv_d = &mut inv_d[..n];
    for (x, d) in inv_d.iter_mut().zip(articulated_joint_inertia.iter()) {
        *x = T::one() / *d;
    }
    let rows = &mut rows[..n];
    let back = &mut back[..nslots];
    let fwd = &mut fwd[..nslots];
    for b in back.iter_mut() {
        *b = [[T::zero(); LANES]; 6];
    }
    let bodies = Articulated {
        screws: &screw_in_world[..n],
        u_over_d: &articulated_force[..n],
        inv_d,
        parents: &model.parents()[..n],
        slot_of,
    };
    // M⁻¹: columns j₀ … j₁ − 1 of the identity, rows i < j₁ stored as column i's rows j₀ … j₁ − 1
    // (symmetry), then the strict upper triangle mirrored from the lower one.
    let minv = &mut mass_matrix_inverse.as_mut_slice()[..n * n];
    for j0 in (0..n).step_by(LANES).filter(|_| inverse) {
        let j1 = (j0 + LANES).min(n);
        for row in rows[..j1].iter_mut() {
            *row = [T::zero(); LANES];
        }
        for j in j0..j1 {
            rows[j][j - j0] = T::one();
        }
        sweep(&bodies, rows, back, fwd, j1);
        for (i, row) in rows[..j1].iter().enumerate() {
            minv[i * n + j0..i * n + j1].copy_from_slice(&row[..j1 - j0]);
        }
    }
    for j in (1..n).filter(|_| inverse) {
        for i in 0..j {
            minv[j * n + i] = minv[i * n + j];
        }
    }
    // ∂q̈/∂x = M⁻¹ (−∂τ/∂x), LANES columns at a time.
    if !products {
        return;
    }
    for (x, out) in [(&*dtau_dq, dqdd_dq), (&*dtau_dv, dqdd_dv)] {
        negated_solve(&bodies, x, out, rows, back, fwd, n);
    }
}

/// `out = M⁻¹ (−x)` for `n × n` column-major `x`, [`LANES`] columns per sweep.
fn negated_solve<T: Real>(
    bodies: &Articulated<'_, T>,
    x: &DMatrix<T>,
    out: &mut DMatrix<T>,
    rows: &mut [[T; LANES]],
    back: &mut [Block<T>],
    fwd: &mut [Block<T>],
    n: usize,
) {
    let (x, out) = (&x.as_slice()[..n * n], &mut out.as_mut_slice()[..n * n]);
    let rows = &mut rows[..n];
    for j0 in (0..n).step_by(LANES) {
        let j1 = (j0 + LANES).min(n);
        if j1 - j0 < LANES {
            for row in rows.iter_mut() {
                *row = [T::zero(); LANES];
            }
        }
        for j in j0..j1 {
            for (row, xij) in rows.iter_mut().zip(&x[j * n..(j + 1) * n]) {
                row[j - j0] = -*xij;
            }
        }
        sweep(bodies, rows, back, fwd, n);
        for j in j0..j1 {
            for (o, row) in out[j * n..(j + 1) * n].iter_mut().zip(rows.iter()) {
                *o = row[j - j0];
            }
        }
    }
}

/// One backward and one forward sweep over bodies `0 … last − 1` for [`LANES`] right-hand sides:
/// `rows[i]` holds `τ_i` in and `q̈_i` out (bodies from `last` on must have zero right-hand
/// sides, and their rows are left alone). The block of the body just done stays in registers
/// when the next body is its only child (backward) or its first child (forward); the slots
/// in memory are read and written only at branches.
#[multiversion::multiversion(targets(
    "x86_64+avx512f+avx512vl+avx512dq+avx512bw+avx2+fma",
    "x86_64+avx2+fma"
))]
fn sweep<T: Real>(
    bodies: &Articulated<'_, T>,
    rows: &mut [[T; LANES]],
    back: &mut [Block<T>],
    fwd: &mut [Block<T>],
    last: usize,
) {
    let (screws, u_over_d, inv_d, parents, slot_of) = (
        &bodies.screws[..last],
        &bodies.u_over_d[..last],
        &bodies.inv_d[..last],
        &bodies.parents[..last],
        &bodies.slot_of[..last],
    );
    let rows = &mut rows[..last];
    let zero: Block<T> = [[T::zero(); LANES]; 6];
    // Backward: u_i = τ_i − s_iᵀ F_i, row u_i / D_i kept, F_λ += F_i + (U_i / D_i) u_i.
    // `carried` is F_i when body i + 1 was the only child of i (zero for a first body whose
    // children are all beyond `last`).
    let (mut carried, mut is_carried) = (zero, true);
    for i in (0..last).rev() {
        let (s, ud) = (&screws[i], &u_over_d[i]);
        let flags = slot_of[i];
        let slot = flags >> SLOT;
        let from_memory = !is_carried && flags & HAS_CHILDREN != 0;
        let f = if is_carried {
            carried
        } else if from_memory {
            back[slot]
        } else {
            zero
        };
        // Each line runs across the lanes (one vector operation per row of the block).
        let row = &mut rows[i];
        let mut u = *row;
        for r in 0..6 {
            let sr = -s[r];
            for w in 0..LANES {
                u[w] = sr.mul_add(f[r][w], u[w]);
            }
        }
        for w in 0..LANES {
            row[w] = u[w] * inv_d[i];
        }
        let mut passed = f;
        for r in 0..6 {
            for w in 0..LANES {
                passed[r][w] = ud[r].mul_add(u[w], passed[r][w]);
            }
        }
        is_carried = false;
        match parents[i] {
            None => {
                if from_memory {
                    back[slot] = zero;
                }
            }
            Some(p) if flags & LAST_CHILD != 0 => {
                if p + 1 == i {
                    // The only child: F_λ stays in registers (and its slot is left zero).
                    (carried, is_carried) = (passed, true);
                    if from_memory {
                        back[slot] = zero;
                    }
                } else {
                    back[slot] = passed;
                }
            }
            Some(_) => {
                let to = &mut back[slot - 1];
                for r in 0..6 {
                    for w in 0..LANES {
                        to[r][w] += passed[r][w];
                    }
                }
                if from_memory {
                    back[slot] = zero;
                }
            }
        }
    }
    // Forward: q̈_i = u_i / D_i − (U_i / D_i)ᵀ A_λ, A_i = A_λ + s_i q̈_i; `a` is A_{i−1}, kept in
    // memory too when body i − 1 branches (for its later children).
    let mut a = zero;
    for i in 0..last {
        let (s, ud) = (&screws[i], &u_over_d[i]);
        let flags = slot_of[i];
        let slot = flags >> SLOT;
        let a_parent = match parents[i] {
            Some(p) if p + 1 == i => a,
            Some(_) => fwd[slot - usize::from(flags & LAST_CHILD == 0)],
            None => zero,
        };
        let row = &mut rows[i];
        let mut q = *row;
        for r in 0..6 {
            let ur = -ud[r];
            for w in 0..LANES {
                q[w] = ur.mul_add(a_parent[r][w], q[w]);
            }
        }
        *row = q;
        // Formed for leaves too (unused there): a conditional update of `a` made the compiler
        // shuffle its lanes at every body.
        a = a_parent;
        for r in 0..6 {
            for w in 0..LANES {
                a[r][w] = s[r].mul_add(q[w], a[r][w]);
            }
        }
        if flags & BRANCHES != 0 {
            fwd[slot] = a;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::articulated_inverse_and_products;
    use crate::dynamics::aba_derivatives;
    use crate::model::{JointSpec, ModelBuilder, SplitMix64};
    use crate::spatial::{Se3, SpatialInertia};
    use crate::Workspace;
    use nalgebra::{Matrix3, Vector3, Vector6};

    /// A tree of `n` revolute joints about varied offset axes whose parents `parent(i)` picks.
    fn tree(
        n: usize,
        rng: &mut SplitMix64,
        parent: impl Fn(usize, &mut SplitMix64) -> Option<usize>,
    ) -> crate::Model {
        let mut b = ModelBuilder::new("tree");
        for i in 0..n {
            let p = parent(i, rng).map_or("base".to_string(), |p| format!("l{p}"));
            let axis =
                Vector3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 1.0).normalize();
            let l = -axis.cross(&Vector3::new(
                rng.uniform(-0.1, 0.1),
                0.0,
                rng.uniform(-0.1, 0.1),
            ));
            let home = Se3::from_rpy(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.3)
                .with_translation(Vector3::new(0.1, rng.uniform(-0.1, 0.1), 0.2));
            let inertia = SpatialInertia::new(
                rng.uniform(0.5, 2.0),
                Vector3::new(0.05, rng.uniform(-0.1, 0.1), 0.1),
                Matrix3::from_diagonal(&Vector3::new(0.02, 0.03, rng.uniform(0.01, 0.05))),
            );
            b.link(
                &format!("l{i}"),
                &p,
                JointSpec::revolute(&format!("j{i}"))
                    .screw_in_child(Vector6::new(axis.x, axis.y, axis.z, l.x, l.y, l.z)),
                home,
                inertia,
            );
        }
        b.build().unwrap()
    }

    /// The sweeps at every size (also below the sizes where `aba_derivatives` uses them) agree
    /// with the Cholesky inverse and the dense products that `aba_derivatives` forms there, on
    /// chains and on trees with roots and forks anywhere.
    #[test]
    fn sweeps_match_the_dense_inverse_and_products_at_every_size() {
        let mut rng = SplitMix64::new(5);
        for n in 1..=12 {
            for shape in 0..6 {
                let m = tree(n, &mut rng, |i, rng| match (i, shape) {
                    (0, _) => None,
                    (_, 0) => Some(i - 1),
                    _ => {
                        let k = (rng.uniform(0.0, 1.0) * (i + 1) as f64) as usize;
                        k.checked_sub(1)
                    }
                });
                let x: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
                let mut ws = Workspace::new(&m);
                aba_derivatives(&m, &mut ws, &x, &x, &x, None).unwrap();
                let (minv, dq, dv) = (
                    ws.mass_matrix_inverse.clone(),
                    ws.dqdd_dq.clone(),
                    ws.dqdd_dv.clone(),
                );
                articulated_inverse_and_products(&m, &mut ws, true, true);
                for (got, want, what) in [
                    (&ws.mass_matrix_inverse, &minv, "M⁻¹"),
                    (&ws.dqdd_dq, &dq, "∂q̈/∂q"),
                    (&ws.dqdd_dv, &dv, "∂q̈/∂q̇"),
                ] {
                    let rel = (got - want).amax() / want.amax();
                    assert!(
                        rel < 1e-10,
                        "{what}, parents {:?}: off by {rel:e}",
                        m.parents()
                    );
                }
            }
        }
    }
}
