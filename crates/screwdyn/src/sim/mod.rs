//! Simulation: integrators, trajectories, controllers, joint effects and recording.
//!
//! ```
//! use screwdyn::sim::{Integrator, Stepper};
//! // A unit harmonic oscillator q̈ = −q over one period with RK4 returns to its start.
//! let mut f = |_t: f64, q: &[f64], _v: &[f64], a: &mut [f64]| { a[0] = -q[0]; Ok(()) };
//! let mut s = Stepper::new(Integrator::Rk4, 1);
//! let (mut q, mut v) = ([1.0], [0.0]);
//! let n = 1000;
//! let h = 2.0 * std::f64::consts::PI / n as f64;
//! for k in 0..n { s.advance(&mut f, k as f64 * h, h, &mut q, &mut v).unwrap(); }
//! assert!((q[0] - 1.0).abs() < 1e-10 && v[0].abs() < 1e-10);
//! ```

mod integrate;
mod trajectory;

pub use integrate::{AccelFn, Integrator, Stepper};
pub use trajectory::{Quintic, Trajectory, Trapezoid, Waypoints};
