//! Inertia tensors of common shapes, the parallel-axis theorem both ways, rotation and
//! combination of inertias (Craig, *Introduction to Robotics*). The physical-consistency check of
//! an inertia is [`SpatialInertia::check_physical`].
//!
//! Tensors are 3×3 rotational inertias `ᴬI = [Ixx −Ixy −Ixz; −Ixy Iyy −Iyz; −Ixz −Iyz Izz]`
//! (the sign convention: products of inertia enter negated), in kg·m².
//!
//! ```
//! use nalgebra::Vector3;
//! use screwdyn::inertia;
//! // Craig, *Introduction to Robotics*: a box of mass m and sides w (x), l (y), h (z) about its corner …
//! let (m, w, l, h) = (2.0, 0.3, 0.2, 0.1);
//! let corner = inertia::box_about_corner(m, w, l, h).unwrap();
//! // … and about its centre of mass, by the parallel-axis theorem backwards.
//! let com = inertia::parallel_axis_to_com(&corner, m, &Vector3::new(w / 2.0, l / 2.0, h / 2.0));
//! assert!((com - inertia::cuboid(m, w, l, h).unwrap()).amax() < 1e-15);
//! ```

use crate::error::{Error, Result};
use crate::scalar::{real, Real};
use crate::spatial::{parallel_axis_term, SpatialInertia};
use nalgebra::{Matrix3, Vector3};

fn check<T: Real>(what: &str, values: &[(&str, T)]) -> Result<()> {
    for (name, v) in values {
        if !v.is_finite() || *v < T::zero() {
            return Err(Error::InvalidArgument(format!(
                "the {name} of the {what} must be a finite non-negative number, got {v:?}"
            )));
        }
    }
    Ok(())
}

/// A solid box of mass `m` and sides `w` (along x), `l` (y), `h` (z), about its centre of mass:
/// `diag(m(l² + h²)/12, m(w² + h²)/12, m(w² + l²)/12)` (Craig, *Introduction to Robotics*).
///
/// # Errors
/// [`Error::InvalidArgument`] when a dimension or the mass is negative or not finite.
pub fn cuboid<T: Real>(m: T, w: T, l: T, h: T) -> Result<Matrix3<T>> {
    check(
        "box",
        &[("mass", m), ("width", w), ("length", l), ("height", h)],
    )?;
    let k = m / real(12.0);
    Ok(Matrix3::from_diagonal(&Vector3::new(
        k * (l * l + h * h),
        k * (w * w + h * h),
        k * (w * w + l * l),
    )))
}

/// The same box about the corner at the origin, the body filling `[0,w]×[0,l]×[0,h]`
/// (the worked example): `Ixx = m(l² + h²)/3`, `Ixy = m w l / 4` (entered negated), ….
///
/// # Errors
/// [`Error::InvalidArgument`] when a dimension or the mass is negative or not finite.
///
/// ```
/// let i = screwdyn::inertia::box_about_corner(12.0, 1.0, 2.0, 3.0).unwrap();
/// assert_eq!(i[(0, 0)], 4.0 * (4.0 + 9.0)); // m/3 (l² + h²)
/// assert_eq!(i[(0, 1)], -3.0 * 2.0);        // −m/4 w l
/// ```
pub fn box_about_corner<T: Real>(m: T, w: T, l: T, h: T) -> Result<Matrix3<T>> {
    check(
        "box",
        &[("mass", m), ("width", w), ("length", l), ("height", h)],
    )?;
    let (t, q) = (m / real(3.0), m / real(4.0));
    Ok(Matrix3::new(
        t * (l * l + h * h),
        -q * w * l,
        -q * h * w,
        -q * w * l,
        t * (w * w + h * h),
        -q * h * l,
        -q * h * w,
        -q * h * l,
        t * (w * w + l * l),
    ))
}

/// A solid cylinder of mass `m`, radius `r` and height `h`, axis along z, about its centre of
/// mass: `Ixx = Iyy = m(3r² + h²)/12`, `Izz = m r²/2` (Craig, *Introduction to Robotics*, tutorial question 1).
///
/// # Errors
/// [`Error::InvalidArgument`] when a dimension or the mass is negative or not finite.
pub fn solid_cylinder<T: Real>(m: T, r: T, h: T) -> Result<Matrix3<T>> {
    hollow_cylinder(m, T::zero(), r, h)
}

/// A thick-walled tube of mass `m`, radii `r_in ≤ r_out` and height `h`, axis along z, about its
/// centre of mass: `Ixx = Iyy = m(3(r_in² + r_out²) + h²)/12`, `Izz = m(r_in² + r_out²)/2`
/// (`r_in = r_out` is a thin shell).
///
/// # Errors
/// [`Error::InvalidArgument`] when a dimension or the mass is negative or not finite.
pub fn hollow_cylinder<T: Real>(m: T, r_in: T, r_out: T, h: T) -> Result<Matrix3<T>> {
    check(
        "cylinder",
        &[
            ("mass", m),
            ("inner radius", r_in),
            ("outer radius", r_out),
            ("height", h),
        ],
    )?;
    if r_in > r_out {
        return Err(Error::InvalidArgument(format!(
            "the inner radius of the cylinder ({r_in:?}) exceeds its outer radius ({r_out:?})"
        )));
    }
    let s = r_in * r_in + r_out * r_out;
    let a = m * (s * real(3.0) + h * h) / real(12.0);
    Ok(Matrix3::from_diagonal(&Vector3::new(
        a,
        a,
        m * s / real(2.0),
    )))
}

/// A solid sphere of mass `m` and radius `r`: `2/5 m r²` about every axis through the centre.
///
/// # Errors
/// [`Error::InvalidArgument`] when a dimension or the mass is negative or not finite.
pub fn solid_sphere<T: Real>(m: T, r: T) -> Result<Matrix3<T>> {
    check("sphere", &[("mass", m), ("radius", r)])?;
    Ok(Matrix3::identity() * (m * r * r * real(0.4)))
}

/// A thin spherical shell: `2/3 m r²`.
///
/// # Errors
/// [`Error::InvalidArgument`] when a dimension or the mass is negative or not finite.
pub fn hollow_sphere<T: Real>(m: T, r: T) -> Result<Matrix3<T>> {
    check("sphere", &[("mass", m), ("radius", r)])?;
    Ok(Matrix3::identity() * (m * r * r * real(2.0 / 3.0)))
}

/// A thin rod of mass `m` and length `length` along z, about its centre:
/// `Ixx = Iyy = m L²/12`, `Izz = 0`.
///
/// # Errors
/// [`Error::InvalidArgument`] when a dimension or the mass is negative or not finite.
pub fn thin_rod<T: Real>(m: T, length: T) -> Result<Matrix3<T>> {
    check("rod", &[("mass", m), ("length", length)])?;
    let a = m * length * length / real(12.0);
    Ok(Matrix3::from_diagonal(&Vector3::new(a, a, T::zero())))
}

/// Parallel-axis theorem (Craig, *Introduction to Robotics*): `ᴬI = ᶜI + m(P_Cᵀ P_C 1 − P_C P_Cᵀ)`, the inertia about a
/// frame `{A}` in which the centre of mass sits at `p_c` (axes parallel to the CoM frame's).
///
/// ```
/// use nalgebra::Vector3;
/// use screwdyn::inertia::{parallel_axis, thin_rod};
/// // A rod about its end: m L²/3.
/// let end = parallel_axis(&thin_rod(3.0, 2.0).unwrap(), 3.0, &Vector3::new(0.0, 0.0, 1.0));
/// assert!((end[(0, 0)] - 4.0_f64).abs() < 1e-15);
/// ```
pub fn parallel_axis<T: Real>(i_com: &Matrix3<T>, m: T, p_c: &Vector3<T>) -> Matrix3<T> {
    i_com + parallel_axis_term(m, p_c)
}

/// The parallel-axis theorem backwards (Craig, *Introduction to Robotics*): `ᶜI = ᴬI − m(P_Cᵀ P_C 1 − P_C P_Cᵀ)`.
pub fn parallel_axis_to_com<T: Real>(i_a: &Matrix3<T>, m: T, p_c: &Vector3<T>) -> Matrix3<T> {
    i_a - parallel_axis_term(m, p_c)
}

/// The inertia written in a rotated frame: `ᴮI = R ᴬI Rᵀ` with `R = R_A^B`, the orientation of
/// frame `{A}` in frame `{B}`.
///
/// ```
/// use nalgebra::{Matrix3, Vector3};
/// use screwdyn::{inertia::{cuboid, rotate}, spatial::exp_so3};
/// let i = cuboid(1.0, 1.0, 2.0, 3.0).unwrap();
/// // Turning the box a quarter turn about z swaps Ixx and Iyy.
/// let r = exp_so3(&Vector3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
/// let j = rotate(&i, &r);
/// assert!((j[(0, 0)] - i[(1, 1)]).abs() < 1e-15);
/// ```
pub fn rotate<T: Real>(i: &Matrix3<T>, r: &Matrix3<T>) -> Matrix3<T> {
    r * i * r.transpose()
}

/// The spatial inertia of several rigid bodies joined together, all given in the same frame
/// (masses add, the CoM is mass-weighted, inertias about the origin add).
///
/// ```
/// use nalgebra::Vector3;
/// use screwdyn::{inertia::combine, spatial::SpatialInertia};
/// let a = SpatialInertia::point_mass(1.0, Vector3::new(1.0, 0.0, 0.0));
/// let b = SpatialInertia::point_mass(1.0, Vector3::new(-1.0, 0.0, 0.0));
/// let c = combine(&[a, b]);
/// assert_eq!(c.mass, 2.0);
/// assert_eq!(c.com, Vector3::zeros());
/// assert!((c.inertia_com[(1, 1)] - 2.0_f64).abs() < 1e-15); // two unit masses at 1 m
/// ```
pub fn combine<T: Real>(bodies: &[SpatialInertia<T>]) -> SpatialInertia<T> {
    bodies
        .iter()
        .fold(SpatialInertia::zero(), |acc, b| acc.combined(b))
}

/// A shape primitive of uniform density (the CLI's `screwdyn inertia` and the native TOML
/// format's `shape = { type = "box", size = [w, l, h] }`). Axes: a box's sides along x, y, z; a
/// cylinder's and a rod's axis along z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A solid box with sides `w` (x), `l` (y), `h` (z).
    Box {
        /// Side along x.
        w: f64,
        /// Side along y.
        l: f64,
        /// Side along z.
        h: f64,
    },
    /// A solid cylinder of radius `r` and length `h` along z.
    Cylinder {
        /// Radius.
        r: f64,
        /// Length along z.
        h: f64,
    },
    /// A solid sphere of radius `r`.
    Sphere {
        /// Radius.
        r: f64,
    },
    /// A thin rod of length `length` along z.
    Rod {
        /// Length along z.
        length: f64,
    },
    /// A point mass.
    Point,
}

impl Shape {
    /// The shape called `kind` (`box`, `cylinder`, `sphere`, `rod`, `point`) with its sizes
    /// (`w,l,h`; `r,h`; `r`; `length`; none).
    ///
    /// ```
    /// use screwdyn::inertia::Shape;
    /// assert_eq!(Shape::parse("cylinder", &[0.1, 0.5]).unwrap(), Shape::Cylinder { r: 0.1, h: 0.5 });
    /// assert!(Shape::parse("box", &[1.0]).unwrap_err().to_string().contains("3 sizes"));
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown kind or a wrong number of sizes.
    pub fn parse(kind: &str, size: &[f64]) -> Result<Shape> {
        let want = match kind {
            "box" | "cuboid" => 3,
            "cylinder" => 2,
            "sphere" | "rod" => 1,
            "point" => 0,
            _ => {
                return Err(Error::InvalidArgument(format!(
                    "unknown shape '{kind}' (use box, cylinder, sphere, rod or point)"
                )))
            }
        };
        if size.len() != want {
            let what = match want {
                3 => "w, l, h",
                2 => "radius, length",
                1 if kind == "rod" => "length",
                1 => "radius",
                _ => "nothing",
            };
            return Err(Error::InvalidArgument(format!(
                "a {kind} takes {want} sizes ({what}), got {}",
                size.len()
            )));
        }
        Ok(match kind {
            "box" | "cuboid" => Shape::Box {
                w: size[0],
                l: size[1],
                h: size[2],
            },
            "cylinder" => Shape::Cylinder {
                r: size[0],
                h: size[1],
            },
            "sphere" => Shape::Sphere { r: size[0] },
            "rod" => Shape::Rod { length: size[0] },
            _ => Shape::Point,
        })
    }

    /// The rotational inertia of mass `m` in this shape about its centre of mass, shape axes.
    ///
    /// # Errors
    /// [`Error::InvalidModel`] for a negative or non-finite mass or size.
    pub fn inertia_com(&self, m: f64) -> Result<Matrix3<f64>> {
        match *self {
            Shape::Box { w, l, h } => cuboid(m, w, l, h),
            Shape::Cylinder { r, h } => solid_cylinder(m, r, h),
            Shape::Sphere { r } => solid_sphere(m, r),
            Shape::Rod { length } => thin_rod(m, length),
            Shape::Point => {
                check("point mass", &[("mass", m)])?;
                Ok(Matrix3::zeros())
            }
        }
    }

    /// The inertia about a point and in turned axes: the output frame has its origin at
    /// `about` (in the shape's frame, whose origin is the centre of mass) and axes
    /// `R = rotation` relative to the shape's, so `I = Rᵀ (ᶜI + m(pᵀp 1 − p pᵀ)) R` with `p = −about`
    /// the centre of mass seen from the new origin (the parallel-axis theorem).
    ///
    /// ```
    /// use nalgebra::{Matrix3, Vector3};
    /// use screwdyn::inertia::{box_about_corner, Shape};
    /// // Craig, *Introduction to Robotics*: the box about its corner.
    /// let b = Shape::Box { w: 1.0, l: 2.0, h: 3.0 };
    /// let i = b.inertia_about(12.0, &Vector3::new(-0.5, -1.0, -1.5), &Matrix3::identity()).unwrap();
    /// assert!((i - box_about_corner(12.0, 1.0, 2.0, 3.0).unwrap()).amax() < 1e-12);
    /// ```
    ///
    /// # Errors
    /// As [`Shape::inertia_com`].
    pub fn inertia_about(
        &self,
        m: f64,
        about: &Vector3<f64>,
        rotation: &Matrix3<f64>,
    ) -> Result<Matrix3<f64>> {
        let i = parallel_axis(&self.inertia_com(m)?, m, &(-about));
        Ok(rotation.transpose() * i * rotation)
    }
}
