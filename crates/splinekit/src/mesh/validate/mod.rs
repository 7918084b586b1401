//! Topology validation of a [`PolyMesh`]: counts, boundary loops, components, Euler
//! characteristic and genus, and every problem by vertex and face index
//! ([`TopologyReport`]); and a repair that splits non-manifold edges and vertices
//! ([`split_nonmanifold`]).
//!
//! The definitions (which faces take part, edges, fans, components, χ, genus) are in the docs
//! of [`TopologyReport`].
//!
//! Cost: `O(corners · valence)` time (the [`Adjacency`]), plus a sort for duplicate faces.

mod faces;
mod repair;
mod report;
mod scan;
#[cfg(test)]
mod tests;

pub use repair::{SplitReport, split_nonmanifold};
pub use report::{
    BoundaryLoop, Component, DEFAULT_DEGENERATE_TOLERANCE, DEFAULT_LISTED, Degeneracy, DegenerateFace, DuplicateFace,
    InvalidIndex, ShortFace, TopologyReport,
};
