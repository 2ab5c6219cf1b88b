//! [`HomeRotation`]: the rotation `R_i^{λ(i)}(0)` of a joint's home pose, classified once at
//! model build time so that forward kinematics can skip a 3×3 product.
//!
//! The joint frames of most arms differ from their parents' by no rotation at all or by quarter
//! turns (URDF `rpy` of `±π/2`, DH twists `α = ±π/2`): then every column of `R_i^{λ(i)}(0)` is a
//! signed unit vector `±ê_k` (a signed permutation matrix). The product `R_{λ(i)}^0 R_i^{λ(i)}(0)`
//! that forward kinematics forms at every joint is then a choice of columns of `R_{λ(i)}^0` with
//! signs, exactly (no rounding), instead of 27 multiplications.

use crate::scalar::Real;
use nalgebra::Matrix3;

/// A home rotation `R = R_i^{λ(i)}(0)`, specialised by shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HomeRotation<T: Real = f64> {
    /// Column `c` of `R` is `signs[c] ê_{columns[c]}` (identity and quarter turns).
    SignedPermutation {
        /// Which unit vector each column is (0, 1, 2 for x, y, z).
        columns: [usize; 3],
        /// `±1` for each column.
        signs: [T; 3],
    },
    /// Any other rotation.
    General,
}

impl<T: Real> HomeRotation<T> {
    /// Classifies a rotation matrix (exact comparisons: only entries that are exactly `0` or
    /// `±1` make a signed permutation).
    ///
    /// ```
    /// use nalgebra::Matrix3;
    /// use screwdyn::model::HomeRotation;
    /// // A quarter turn about x: columns (ê_x, ê_z, −ê_y).
    /// let r = Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
    /// assert_eq!(
    ///     HomeRotation::classify(&r),
    ///     HomeRotation::SignedPermutation { columns: [0, 2, 1], signs: [1.0, 1.0, -1.0] }
    /// );
    /// assert_eq!(HomeRotation::classify(&(r * 0.5)), HomeRotation::General);
    /// ```
    pub fn classify(r: &Matrix3<T>) -> Self {
        let mut columns = [0; 3];
        let mut signs = [T::one(); 3];
        let mut used = [false; 3];
        for c in 0..3 {
            let nz: Vec<usize> = (0..3).filter(|&k| r[(k, c)] != T::zero()).collect();
            match nz.as_slice() {
                [k] if !used[*k] && (r[(*k, c)] == T::one() || r[(*k, c)] == -T::one()) => {
                    used[*k] = true;
                    columns[c] = *k;
                    signs[c] = r[(*k, c)];
                }
                _ => return HomeRotation::General,
            }
        }
        HomeRotation::SignedPermutation { columns, signs }
    }

    /// `A R` given `R` itself (the rotation this was classified from): for a signed permutation,
    /// column `c` of the product is `signs[c]` times column `columns[c]` of `A` (exact);
    /// otherwise the 3×3 product.
    ///
    /// ```
    /// use nalgebra::Matrix3;
    /// use screwdyn::model::HomeRotation;
    /// let r = Matrix3::new(0.0, 0.0, 1.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0); // quarter turn about y
    /// let a = Matrix3::new(0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9);
    /// assert_eq!(HomeRotation::classify(&r).right_multiply(&a, &r), a * r);
    /// ```
    #[inline(always)]
    pub fn right_multiply(&self, a: &Matrix3<T>, r: &Matrix3<T>) -> Matrix3<T> {
        match *self {
            HomeRotation::SignedPermutation { columns, signs } => {
                let mut out = Matrix3::zeros();
                for c in 0..3 {
                    let (k, s) = (columns[c], signs[c]);
                    out[(0, c)] = a[(0, k)] * s;
                    out[(1, c)] = a[(1, k)] * s;
                    out[(2, c)] = a[(2, k)] * s;
                }
                out
            }
            HomeRotation::General => a * r,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::Se3;

    /// Every product of quarter turns about the axes (the 24 rotations of the cube) is a signed
    /// permutation, and the column choice gives the matrix product exactly.
    #[test]
    fn quarter_turns_are_signed_permutations_and_multiply_exactly() {
        let half_pi = std::f64::consts::FRAC_PI_2;
        let a = Se3::from_rpy(0.3, -1.1, 2.5).rotation;
        let mut seen = 0;
        for i in 0..4 {
            for j in 0..4 {
                for k in 0..4 {
                    let r = Se3::from_rpy(
                        f64::from(i) * half_pi,
                        f64::from(j) * half_pi,
                        f64::from(k) * half_pi,
                    )
                    .rotation;
                    let kind = HomeRotation::classify(&r);
                    assert!(
                        matches!(kind, HomeRotation::SignedPermutation { .. }),
                        "{r}"
                    );
                    // The matrix product with entries 0 and ±1 is exact too.
                    assert_eq!(kind.right_multiply(&a, &r), a * r);
                    seen += 1;
                }
            }
        }
        assert_eq!(seen, 64);
    }

    #[test]
    fn other_rotations_and_repeated_columns_are_general() {
        // The UR5 URDF's quarter turns are written 1.57079632679, 4.9e-12 short of π/2.
        let r = Se3::from_rpy(0.0, std::f64::consts::FRAC_PI_2 - 4.9e-12, 0.0).rotation;
        assert_eq!(HomeRotation::classify(&r), HomeRotation::General);
        let a = Se3::from_rpy(0.3, -1.1, 2.5).rotation;
        assert_eq!(HomeRotation::General.right_multiply(&a, &r), a * r);
        // Two columns on the same axis: not a rotation, not a permutation.
        let bad = Matrix3::new(1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
        assert_eq!(HomeRotation::classify(&bad), HomeRotation::General);
    }
}
