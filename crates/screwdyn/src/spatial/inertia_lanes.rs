//! The bodies' inertias moved to the base frame {0}, [`LANES`] bodies side by side: the
//! parameters `(m, h, I_o)` of [`CompositeInertia::rigid_in_world`] for every body at once after
//! forward kinematics, coordinate by coordinate (one vector register, or two, per coordinate in
//! the CPU-specific clones of the callers), instead of one body at a time.
//!
//! For body `i` at `H_i^0 = (R_i, p_i)`, with its mass `m_i`, centre of mass `c_i` and
//! rotational inertia `I_{c,i}` in its own frame:
//! `c_i⁰ = R_i c_i + p_i`, `h_i = m_i c_i⁰`,
//! `I_{o,i} = R_i I_{c,i} R_iᵀ + m_i(|c_i⁰|² 1 − c_i⁰ c_i⁰ᵀ)` (about the origin of {0}).
//! The products are fused in the same order as [`CompositeInertia::rigid_in_world`], so the
//! results are the same to the last bit.

use super::composite_inertia::CompositeInertia;
use super::inertia::SpatialInertia;
use super::se3::Se3;
use crate::scalar::Real;
use nalgebra::{Matrix3, Vector3};

/// How many bodies are moved to {0} side by side: one AVX-512 register of `f64`, two AVX2 ones.
pub(crate) const LANES: usize = 4;

/// [`LANES`] bodies' inertias in their own frames, coordinate by coordinate: lane `l` of chunk
/// `k` is body `k L + l` (the lanes past the last body are zero).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct BodyLanes<T: Real> {
    /// `m`.
    mass: [T; LANES],
    /// `c` (centre of mass in the body frame), by coordinate.
    com: [[T; LANES]; 3],
    /// `I_c` (about the centre of mass, body axes), column-major (`I_c,ab` at `3b + a`): all
    /// nine entries, as [`CompositeInertia::rigid_in_world`] reads them.
    inertia_com: [[T; LANES]; 9],
}

/// [`LANES`] bodies' inertias in {0} by the parameters [`CompositeInertia`] holds,
/// coordinate by coordinate.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct InertiaLanes<T: Real> {
    /// `m`.
    pub(crate) mass: [T; LANES],
    /// `h = m c⁰`, by coordinate.
    pub(crate) first_moment: [[T; LANES]; 3],
    /// `I_o` about the origin of {0}, its symmetric entries `(00, 11, 22, 01, 02, 12)`.
    pub(crate) inertia_origin: [[T; LANES]; 6],
}

impl<T: Real> InertiaLanes<T> {
    /// All zero.
    pub(crate) fn zero() -> Self {
        InertiaLanes {
            mass: [T::zero(); LANES],
            first_moment: [[T::zero(); LANES]; 3],
            inertia_origin: [[T::zero(); LANES]; 6],
        }
    }

    /// The chunks for `n` bodies.
    pub(crate) fn for_bodies(n: usize) -> Vec<Self> {
        vec![Self::zero(); n.div_ceil(LANES)]
    }

    /// Lane `l` as a [`CompositeInertia`].
    #[inline(always)]
    pub(crate) fn get(&self, l: usize) -> CompositeInertia<T> {
        let io = &self.inertia_origin;
        let (i00, i11, i22, i01, i02, i12) =
            (io[0][l], io[1][l], io[2][l], io[3][l], io[4][l], io[5][l]);
        #[rustfmt::skip]
        let inertia_origin = Matrix3::new(
            i00, i01, i02,
            i01, i11, i12,
            i02, i12, i22,
        );
        CompositeInertia {
            mass: self.mass[l],
            first_moment: Vector3::new(
                self.first_moment[0][l],
                self.first_moment[1][l],
                self.first_moment[2][l],
            ),
            inertia_origin,
        }
    }
}

/// The bodies' inertias in chunks of [`LANES`], the tail chunk padded with zero bodies.
pub(crate) fn body_lanes<'a, T: Real>(
    bodies: impl ExactSizeIterator<Item = &'a SpatialInertia<T>>,
) -> Vec<BodyLanes<T>> {
    let mut chunks = vec![
        BodyLanes {
            mass: [T::zero(); LANES],
            com: [[T::zero(); LANES]; 3],
            inertia_com: [[T::zero(); LANES]; 9],
        };
        bodies.len().div_ceil(LANES)
    ];
    for (i, body) in bodies.enumerate() {
        let (chunk, l) = (&mut chunks[i / LANES], i % LANES);
        chunk.mass[l] = body.mass;
        for r in 0..3 {
            chunk.com[r][l] = body.com[r];
        }
        for (k, x) in body.inertia_com.as_slice().iter().enumerate() {
            chunk.inertia_com[k][l] = *x;
        }
    }
    chunks
}

/// Every body's inertia in {0} (`out[k]` lane `l` for body `k L + l`), from the bodies in their
/// own frames (`bodies`, as [`body_lanes`] made them) at the world poses `poses`
/// (`H_i^0`, one per body): the equations of the module, lane by lane. The lanes past the last
/// body hold zero inertias.
#[inline(always)]
pub(crate) fn inertias_in_world<T: Real>(
    bodies: &[BodyLanes<T>],
    poses: &[Se3<T>],
    out: &mut [InertiaLanes<T>],
) {
    let n = poses.len();
    for (k, (body, out)) in bodies.iter().zip(out.iter_mut()).enumerate() {
        let start = k * LANES;
        let (r, p) = if start + LANES <= n {
            gather(|l| &poses[start + l])
        } else {
            // The tail chunk: its lanes past the last body repeat the last pose (their bodies
            // are zero, so are their inertias).
            gather(|l| &poses[(start + l).min(n - 1)])
        };
        chunk_in_world(body, &r, &p, out);
    }
}

/// `(R, p)` of the [`LANES`] poses `pose(l)`, coordinate by coordinate (`R` column-major:
/// `R_rc` at `3c + r`).
#[inline(always)]
fn gather<'a, T: Real>(pose: impl Fn(usize) -> &'a Se3<T>) -> ([[T; LANES]; 9], [[T; LANES]; 3]) {
    let mut r = [[T::zero(); LANES]; 9];
    let mut p = [[T::zero(); LANES]; 3];
    for l in 0..LANES {
        let pose = pose(l);
        for (k, x) in pose.rotation.as_slice().iter().enumerate() {
            r[k][l] = *x;
        }
        for (p, x) in p.iter_mut().zip(pose.translation.iter()) {
            p[l] = *x;
        }
    }
    (r, p)
}

/// One chunk of [`inertias_in_world`]: plain elementwise loops over the lanes, nothing indexed
/// across them, so that each statement is one vector instruction per register.
#[inline(always)]
fn chunk_in_world<T: Real>(
    body: &BodyLanes<T>,
    r: &[[T; LANES]; 9],
    p: &[[T; LANES]; 3],
    out: &mut InertiaLanes<T>,
) {
    let rot = |row: usize, col: usize| &r[3 * col + row];
    let ic = |a: usize, b: usize| &body.inertia_com[3 * b + a];
    // c⁰ = R c + p and h = m c⁰.
    let mut c0 = [[T::zero(); LANES]; 3];
    for row in 0..3 {
        let (r0, r1, r2) = (rot(row, 0), rot(row, 1), rot(row, 2));
        let (c, m) = (&body.com, &body.mass);
        for l in 0..LANES {
            let x = r2[l].mul_add(
                c[2][l],
                r1[l].mul_add(c[1][l], r0[l].mul_add(c[0][l], p[row][l])),
            );
            c0[row][l] = x;
            out.first_moment[row][l] = x * m[l];
        }
    }
    out.mass = body.mass;
    // I_o = R I_c Rᵀ + m(|c⁰|² 1 − c⁰ c⁰ᵀ), row j at a time: a = row j of R I_c, then
    // (R I_c Rᵀ)_{jk} = a · row k of R for k ≥ j; the shift's diagonal is h_y c⁰_y + h_z c⁰_z,
    // …, the rest −h_j c⁰_k.
    let h = &out.first_moment;
    for j in 0..3 {
        let (r0, r1, r2) = (rot(j, 0), rot(j, 1), rot(j, 2));
        let mut a = [[T::zero(); LANES]; 3];
        for (k, a) in a.iter_mut().enumerate() {
            let (i0, i1, i2) = (ic(0, k), ic(1, k), ic(2, k));
            for l in 0..LANES {
                a[l] = r2[l].mul_add(i2[l], r1[l].mul_add(i1[l], r0[l] * i0[l]));
            }
        }
        for k in j..3 {
            let (q0, q1, q2) = (rot(k, 0), rot(k, 1), rot(k, 2));
            let mut io = [T::zero(); LANES];
            for l in 0..LANES {
                let arr = a[2][l].mul_add(q2[l], a[1][l].mul_add(q1[l], a[0][l] * q0[l]));
                io[l] = if j == k {
                    let (u, v) = ((j + 1) % 3, (j + 2) % 3);
                    let (hu, hv) = (h[u][l] * c0[u][l], h[v][l] * c0[v][l]);
                    // The order of rigid_in_world: the lower coordinate's term first.
                    let (first, second) = if u < v { (hu, hv) } else { (hv, hu) };
                    arr + (first + second)
                } else {
                    arr - h[j][l] * c0[k][l]
                };
            }
            out.inertia_origin[SYMMETRIC_INDEX[j][k]] = io;
        }
    }
}

/// Where entry `(j, k)` of a symmetric 3×3 matrix is in the order `(00, 11, 22, 01, 02, 12)`.
const SYMMETRIC_INDEX: [[usize; 3]; 3] = [[0, 3, 4], [3, 1, 5], [4, 5, 2]];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::exp_so3;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    fn vec3(rng: &mut StdRng, r: f64) -> Vector3<f64> {
        Vector3::from_fn(|_, _| rng.gen_range(-r..r))
    }

    /// A box of random size and mass, rotated, its centre of mass off the origin.
    fn body(rng: &mut StdRng) -> SpatialInertia<f64> {
        let m = rng.gen_range(0.5..3.0);
        let s = Vector3::from_fn(|_, _| rng.gen_range(0.05..0.6_f64));
        let d = Matrix3::from_diagonal(&Vector3::new(
            m / 12.0 * (s.y * s.y + s.z * s.z),
            m / 12.0 * (s.x * s.x + s.z * s.z),
            m / 12.0 * (s.x * s.x + s.y * s.y),
        ));
        let r = exp_so3(&vec3(rng, 2.0));
        SpatialInertia::new(m, vec3(rng, 0.3), r * d * r.transpose())
    }

    /// Bit for bit [`CompositeInertia::rigid_in_world`], body by body, for 1 to 20 bodies (full
    /// and padded tail chunks); the padded lanes stay zero.
    #[test]
    fn lanes_equal_rigid_in_world_body_by_body() {
        let mut rng = StdRng::seed_from_u64(31);
        for n in 1..=20 {
            let bodies: Vec<_> = (0..n).map(|_| body(&mut rng)).collect();
            let poses: Vec<_> = (0..n)
                .map(|_| Se3::new(exp_so3(&vec3(&mut rng, 3.0)), vec3(&mut rng, 2.0)))
                .collect();
            let lanes = body_lanes(bodies.iter());
            let mut out = InertiaLanes::for_bodies(n);
            inertias_in_world(&lanes, &poses, &mut out);
            for i in 0..n {
                let expected = CompositeInertia::rigid_in_world(&bodies[i], &poses[i]);
                assert_eq!(
                    out[i / LANES].get(i % LANES),
                    expected,
                    "{n} bodies, body {i}"
                );
            }
            for l in n % LANES..if n % LANES == 0 { 0 } else { LANES } {
                assert_eq!(out[n / LANES].get(l), CompositeInertia::zero());
            }
        }
    }
}
