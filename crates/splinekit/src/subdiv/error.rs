//! Why a mesh cannot be subdivided: [`SubdivError`], and the checks of faces and indices the
//! schemes make first.

use super::scheme::Scheme;
use super::topology::TopologyError;
use crate::mesh::PolyMesh;

/// Why a mesh cannot be subdivided.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SubdivError {
    /// Loop, √3 and butterfly subdivision need triangles.
    #[error("face {face} has {corners} corners; {scheme} subdivision needs triangles (triangulate the mesh first)")]
    NotTriangles {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
        /// The scheme: `Loop`, `√3` or `butterfly`.
        scheme: &'static str,
    },
    /// A face of fewer than three corners (a PLY face list of length 0, 1 or 2, an OBJ
    /// `f 1 2`): no scheme takes it.
    #[error("face {face} has {corners} corner{}; every face needs at least 3 (remove it from the file)", plural(.corners))]
    TooFewCorners {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// Catmull-Clark's limit mask needs quads around an interior vertex.
    #[error(
        "vertex {vertex} lies on face {face} with {corners} corners; Catmull-Clark limit positions need quads \
         around each vertex (subdivide once first)"
    )]
    NotQuads {
        /// The vertex.
        vertex: usize,
        /// A face around it that is not a quad.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// The triangles are not a manifold, consistently oriented surface.
    #[error(transparent)]
    Topology(#[from] TopologyError),
    /// A crease names an edge or vertex the mesh does not have, or has a negative sharpness.
    #[error("{what}: {problem}")]
    Crease {
        /// The crease, e.g. `crease on edge 3–7`.
        what: String,
        /// What is wrong.
        problem: String,
    },
    /// A face-varying attribute is malformed.
    #[error("{attribute}: {problem}")]
    Attribute {
        /// `normals`, `uvs` or `colors`.
        attribute: &'static str,
        /// What is wrong.
        problem: String,
    },
    /// Limit positions were asked of a scheme that has none computed (see
    /// [`Scheme::has_limit_positions`]).
    #[error("limit positions are computed for Loop and Catmull-Clark only, not {scheme} subdivision")]
    NoLimit {
        /// The scheme.
        scheme: Scheme,
    },
    /// The subdivided mesh would have more vertices, edges, faces or face corners than `u32`
    /// indices can number. Checked before anything is made.
    #[error(
        "{levels} level{} of {scheme} subdivision would make {count} {what}; at most {} fit in u32 indices",
        plural(.levels),
        u32::MAX
    )]
    TooLarge {
        /// The scheme: `Loop`, `Catmull-Clark`, `√3`, `Doo-Sabin` or `butterfly`.
        scheme: &'static str,
        /// The first number of levels (from the base mesh) that would not fit: at most the
        /// number asked for.
        levels: usize,
        /// What there would be too many of: `vertices`, `edges`, `faces`, `face corners`,
        /// `normal values` or `UV values`.
        what: &'static str,
        /// How many there would be.
        count: u64,
    },
}

/// `s` unless `n` is 1.
fn plural(n: &usize) -> &'static str {
    if *n == 1 { "" } else { "s" }
}

/// [`SubdivError::TooFewCorners`] for the first face of `mesh` with fewer than three corners.
pub(super) fn polygons_only(mesh: &PolyMesh) -> Result<(), SubdivError> {
    match mesh.faces().enumerate().find(|(_, f)| f.len() < 3) {
        Some((face, f)) => Err(SubdivError::TooFewCorners { face, corners: f.len() }),
        None => Ok(()),
    }
}

/// [`SubdivError::NotTriangles`] for the first face of `mesh` that is not a triangle, naming
/// `scheme`.
pub(super) fn triangles_only(mesh: &PolyMesh, scheme: &'static str) -> Result<(), SubdivError> {
    match mesh.faces().enumerate().find(|(_, f)| f.len() != 3) {
        Some((face, f)) => Err(SubdivError::NotTriangles { face, corners: f.len(), scheme }),
        None => Ok(()),
    }
}

/// [`TopologyError::Index`] for the first corner of `mesh` that names no vertex.
pub(super) fn indices_in_range(mesh: &PolyMesh) -> Result<(), TopologyError> {
    let count = mesh.num_vertices();
    for (face, f) in mesh.faces().enumerate() {
        if let Some(&vertex) = f.iter().find(|&&v| v as usize >= count) {
            return Err(TopologyError::Index { face: face as u32, vertex, count });
        }
    }
    Ok(())
}

/// The first face that names a vertex twice, and that vertex.
pub(super) fn repeated_vertex(mesh: &PolyMesh) -> Option<(usize, u32)> {
    mesh.faces()
        .enumerate()
        .find_map(|(f, face)| face.iter().enumerate().find_map(|(i, &v)| face[i + 1..].contains(&v).then_some((f, v))))
}
