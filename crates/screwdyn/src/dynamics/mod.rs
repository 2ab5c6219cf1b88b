//! Dynamics: inverse dynamics (RNEA), the seeds' closed form, mass matrix, Coriolis, gravity,
//! forward dynamics, energies and Lagrangian coefficients.
