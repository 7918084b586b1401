//! Meshes. [`TriMesh`] is the indexed triangle mesh that sweeps produce and the mesh
//! writers consume; [`PolyMesh`] is the polygon mesh that readers produce and subdivision
//! works on, with its half-edge [`Adjacency`]. [`vertex_curvature`] measures the mean and
//! Gaussian curvature of a triangle mesh at its vertices.

use std::collections::HashMap;

mod adjacency;
pub mod curvature;
mod nonmanifold;
mod poly;
mod validate;

#[doc(hidden)]
pub use adjacency::{Adjacency, NONE};
pub use curvature::{VertexCurvature, WELD_TOLERANCE, vertex_curvature};
pub use nonmanifold::NonManifold;
pub use poly::{FaceVarying, PolyMesh};
pub use validate::{
    BoundaryLoop, Component, DEFAULT_DEGENERATE_TOLERANCE, DEFAULT_LISTED, Degeneracy, DegenerateFace, DuplicateFace,
    InvalidIndex, ShortFace, SplitReport, TopologyReport, split_nonmanifold,
};

use glam::{DVec2, DVec3};

/// What is wrong with a [`TriMesh`], naming the triangle or vertex.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {vertex}, but the mesh has {count} vertices")]
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
        /// The offending vertex index.
        vertex: u32,
        /// Number of vertices.
        count: usize,
    },
    /// An attribute array has the wrong length.
    #[error("{attribute}: {found} values for {expected} vertices")]
    AttributeLength {
        /// `normals`, `uvs` or `colors`.
        attribute: &'static str,
        /// Its length.
        found: usize,
        /// Number of vertices.
        expected: usize,
    },
    /// A position, normal or UV is NaN or infinite.
    #[error("vertex {vertex}: non-finite {attribute}")]
    NonFinite {
        /// Vertex index.
        vertex: usize,
        /// `position`, `normal`, `uv` or `color`.
        attribute: &'static str,
    },
}

/// An indexed triangle mesh with optional per-vertex normals, UVs and colours.
///
/// Triangles are counter-clockwise seen from the front (outside) of the surface.
/// `normals`, `uvs` and `colors` are either empty or hold one value per vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Unit vertex normals (empty, or one per vertex).
    pub normals: Vec<DVec3>,
    /// Texture coordinates (empty, or one per vertex).
    pub uvs: Vec<DVec2>,
    /// RGB colours in `[0, 1]` (empty, or one per vertex).
    pub colors: Vec<DVec3>,
    /// Vertex indices of each triangle, counter-clockwise from the front.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// Number of vertices.
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[must_use]
    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// Checks indices, attribute lengths and finiteness.
    ///
    /// # Errors
    /// The first problem found, naming the triangle or vertex.
    pub fn validate(&self) -> Result<(), MeshError> {
        let n = self.positions.len();
        for (attribute, found) in
            [("normals", self.normals.len()), ("uvs", self.uvs.len()), ("colors", self.colors.len())]
        {
            if found != 0 && found != n {
                return Err(MeshError::AttributeLength { attribute, found, expected: n });
            }
        }
        for (triangle, t) in self.triangles.iter().enumerate() {
            if let Some(&vertex) = t.iter().find(|&&v| v as usize >= n) {
                return Err(MeshError::IndexOutOfRange { triangle, vertex, count: n });
            }
        }
        for (vertex, p) in self.positions.iter().enumerate() {
            if !p.is_finite() {
                return Err(MeshError::NonFinite { vertex, attribute: "position" });
            }
        }
        for (vertex, p) in self.normals.iter().enumerate() {
            if !p.is_finite() {
                return Err(MeshError::NonFinite { vertex, attribute: "normal" });
            }
        }
        for (vertex, p) in self.uvs.iter().enumerate() {
            if !p.is_finite() {
                return Err(MeshError::NonFinite { vertex, attribute: "uv" });
            }
        }
        for (vertex, p) in self.colors.iter().enumerate() {
            if !p.is_finite() {
                return Err(MeshError::NonFinite { vertex, attribute: "color" });
            }
        }
        Ok(())
    }

    /// The three corner positions of triangle `i`.
    #[must_use]
    pub fn corners(&self, i: usize) -> [DVec3; 3] {
        self.triangles[i].map(|v| self.positions[v as usize])
    }

    /// Area-weighted normal of triangle `i` (length = twice its area).
    #[must_use]
    pub fn face_normal(&self, i: usize) -> DVec3 {
        let [a, b, c] = self.corners(i);
        (b - a).cross(c - a)
    }

    /// Signed volume enclosed (divergence theorem); positive for a closed, outward mesh.
    #[must_use]
    pub fn signed_volume(&self) -> f64 {
        (0..self.triangles.len())
            .map(|i| {
                let [a, b, c] = self.corners(i);
                a.dot(b.cross(c))
            })
            .sum::<f64>()
            / 6.0
    }

    /// Per vertex, the sum of the area-weighted normals of its triangles ([`normal_sums`]).
    #[must_use]
    pub fn vertex_normal_sums(&self) -> Vec<DVec3> {
        normal_sums(&self.positions, &self.triangles)
    }

    /// Total surface area.
    #[must_use]
    pub fn area(&self) -> f64 {
        (0..self.triangles.len()).map(|i| 0.5 * self.face_normal(i).length()).sum()
    }

    /// Edges used by exactly one triangle, directed as in that triangle, sorted.
    #[must_use]
    pub fn boundary_edges(&self) -> Vec<[u32; 2]> {
        let counts = self.directed_edge_counts();
        let mut out: Vec<[u32; 2]> = counts
            .iter()
            .filter(|&(&(a, b), &n)| n == 1 && !counts.contains_key(&(b, a)))
            .map(|(&(a, b), _)| [a, b])
            .collect();
        out.sort_unstable();
        out
    }

    /// True when the mesh is a closed, consistently oriented 2-manifold with respect to
    /// edges: every directed edge appears exactly once and its reverse exactly once.
    #[must_use]
    pub fn is_closed_oriented(&self) -> bool {
        let counts = self.directed_edge_counts();
        !self.triangles.is_empty() && counts.iter().all(|(&(a, b), &n)| n == 1 && counts.get(&(b, a)) == Some(&1))
    }

    fn directed_edge_counts(&self) -> HashMap<(u32, u32), usize> {
        let mut counts = HashMap::with_capacity(self.triangles.len() * 3);
        for t in &self.triangles {
            for k in 0..3 {
                *counts.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        counts
    }
}

/// Per vertex, the sum of `(b − a) × (c − a)` over the triangles `(a, b, c)` that use it:
/// normalized, the area-weighted vertex normal (zero where no triangle has area).
#[must_use]
pub fn normal_sums(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|k| positions[k as usize]);
        let n = (b - a).cross(c - a);
        for &k in t {
            sums[k as usize] += n;
        }
    }
    sums
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit tetrahedron, outward.
    fn tetra() -> TriMesh {
        TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            ..TriMesh::default()
        }
    }

    #[test]
    fn tetrahedron_invariants() {
        let m = tetra();
        m.validate().unwrap();
        assert!((m.signed_volume() - 1.0 / 6.0).abs() < 1e-15);
        assert!(m.is_closed_oriented());
        assert!(m.boundary_edges().is_empty());
        let mut open = m.clone();
        open.triangles.pop();
        assert!(!open.is_closed_oriented());
        assert_eq!(open.boundary_edges(), vec![[1, 3], [2, 1], [3, 2]]);
        let mut flipped = m;
        flipped.triangles[3] = [1, 3, 2];
        assert!(!flipped.is_closed_oriented());
    }

    #[test]
    fn validation_names_the_problem() {
        let mut m = tetra();
        m.triangles.push([0, 1, 9]);
        assert_eq!(m.validate(), Err(MeshError::IndexOutOfRange { triangle: 4, vertex: 9, count: 4 }));
        let mut m = tetra();
        m.normals = vec![DVec3::Z; 3];
        assert!(matches!(m.validate(), Err(MeshError::AttributeLength { attribute: "normals", .. })));
    }
}
