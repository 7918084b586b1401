//! [`NonManifold`]: a place where a polygon mesh is not a manifold, consistently oriented
//! surface (an edge of more than two face sides, a pinch vertex, an edge whose two faces run
//! the same way), named by vertex and face index. [`Adjacency`](super::Adjacency) and
//! [`TopologyReport`](super::TopologyReport) report them.

/// A place where a mesh is not a manifold, consistently oriented surface.
///
/// `Display` gives one line naming the vertices and faces, as [`TopologyReport`] lists them:
///
/// ```
/// use splinekit::mesh::NonManifold;
///
/// let edge = NonManifold::Edge { a: 0, b: 1, faces: vec![0, 1, 2] };
/// assert_eq!(edge.to_string(), "edge 0–1: faces 0, 1, 2");
/// let pinch = NonManifold::Vertex { vertex: 4, fans: 2 };
/// assert_eq!(pinch.to_string(), "vertex 4: 2 fans");
/// let flipped = NonManifold::Inconsistent { a: 2, b: 3, faces: [1, 5] };
/// assert_eq!(flipped.to_string(), "edge 2→3: faces 1 and 5 both run this way");
/// ```
///
/// [`TopologyReport`]: super::TopologyReport
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NonManifold {
    /// The undirected edge `{a, b}` has more than two face sides.
    #[error("edge {a}–{b}: faces {}", join(faces))]
    Edge {
        /// Smaller vertex index.
        a: u32,
        /// Larger vertex index.
        b: u32,
        /// The faces of its sides, ascending.
        faces: Vec<u32>,
    },
    /// A vertex whose faces form several fans (a pinch: a bowtie, two cones touching at their
    /// tips), see [`TopologyReport`](super::TopologyReport) for the definition.
    #[error("vertex {vertex}: {fans} fans")]
    Vertex {
        /// The vertex.
        vertex: u32,
        /// Number of fans (at least 2).
        fans: u32,
    },
    /// A two-sided edge whose two faces both run `a → b`: their orientations disagree.
    #[error("edge {a}→{b}: faces {} and {} both run this way", faces[0], faces[1])]
    Inconsistent {
        /// Start vertex (in both faces).
        a: u32,
        /// End vertex.
        b: u32,
        /// The two faces, ascending.
        faces: [u32; 2],
    },
}

impl NonManifold {
    /// Whether this is a [`NonManifold::Edge`].
    #[must_use]
    pub fn is_edge(&self) -> bool {
        matches!(self, Self::Edge { .. })
    }

    /// Whether this is a [`NonManifold::Vertex`].
    #[must_use]
    pub fn is_vertex(&self) -> bool {
        matches!(self, Self::Vertex { .. })
    }

    /// Whether this is a [`NonManifold::Inconsistent`] edge.
    #[must_use]
    pub fn is_inconsistent(&self) -> bool {
        matches!(self, Self::Inconsistent { .. })
    }
}

/// The indices joined by `, `.
fn join(v: &[u32]) -> String {
    v.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
}
