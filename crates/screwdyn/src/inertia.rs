//! Inertia tensors of common shapes, the parallel-axis theorem and consistency checks (seed 003).
