//! The options every loader takes.

/// Options shared by every loader.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Make physical-consistency problems (inertias not positive semi-definite or breaking
    /// the triangle inequality, massless moving leaves) errors. Off by default: such a file
    /// loads, and [`Model::physical_problems`](crate::Model::physical_problems) lists its
    /// problems, as Pinocchio would load it.
    pub strict: bool,
}
