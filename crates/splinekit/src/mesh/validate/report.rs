//! What a topology check finds: [`TopologyReport`] and its parts (boundary loops,
//! components, the problem records), and the human-readable listing its `Display` prints.

use std::fmt;

use crate::mesh::NonManifold;

/// The default `tolerance` of [`TopologyReport::new`]: only faces of exactly zero area are
/// degenerate.
pub const DEFAULT_DEGENERATE_TOLERANCE: f64 = 0.0;

/// How many entries of each problem list [`TopologyReport`]'s `Display` prints before
/// `… and N more`.
pub const DEFAULT_LISTED: usize = 10;

/// Why a face is degenerate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degeneracy {
    /// The face names `vertex` at more than one corner (the first repeated one is given). Such
    /// faces are left out of the topology.
    RepeatedVertex {
        /// The repeated vertex.
        vertex: u32,
    },
    /// The face has (nearly) zero area: see [`TopologyReport::new`] for the tolerance.
    ZeroArea,
}

/// A degenerate face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DegenerateFace {
    /// The face.
    pub face: u32,
    /// What is wrong with it.
    pub kind: Degeneracy,
}

/// A face with the same vertex set as an earlier face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DuplicateFace {
    /// The face.
    pub face: u32,
    /// The first face (smallest index) with the same vertex set.
    pub first: u32,
}

/// A face with fewer than three corners.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShortFace {
    /// The face.
    pub face: u32,
    /// Its number of corners (0, 1 or 2).
    pub len: u32,
}

/// A face corner that names a vertex that does not exist.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InvalidIndex {
    /// The face.
    pub face: u32,
    /// The vertex index it names.
    pub vertex: u32,
}

/// A boundary loop: the vertices along a chain of boundary edges.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BoundaryLoop {
    /// The vertices in order, the first not repeated at the end. The walk follows the
    /// faces' direction where it can (the faces are then on the left, seen from the front).
    pub vertices: Vec<u32>,
    /// Whether the chain closes. It always does on a manifold; where the boundary meets a
    /// non-manifold edge it can end open.
    pub closed: bool,
}

impl BoundaryLoop {
    /// Number of edges: the vertex count if closed, one less if open.
    #[must_use]
    pub fn num_edges(&self) -> usize {
        if self.closed { self.vertices.len() } else { self.vertices.len().saturating_sub(1) }
    }
}

/// One connected component (faces sharing vertices) of the analysed faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Component {
    /// Its smallest face index.
    pub first_face: u32,
    /// Vertices of its faces.
    pub num_vertices: usize,
    /// Its edges.
    pub num_edges: usize,
    /// Its faces.
    pub num_faces: usize,
    /// Its boundary edges.
    pub num_boundary_edges: usize,
    /// Its boundary loops.
    pub num_boundary_loops: usize,
    /// V − E + F of the component.
    pub euler_characteristic: i64,
    /// No non-manifold edge or vertex.
    pub manifold: bool,
    /// Its faces can be oriented consistently.
    pub orientable: bool,
    /// Its faces are oriented consistently (no inconsistent edge).
    pub consistently_oriented: bool,
    /// `(2 − χ − b)/2` for a manifold, orientable component; `None` otherwise.
    pub genus: Option<u32>,
}

/// What a mesh's topology is, and everything wrong with it, by vertex and face index.
///
/// # Which faces take part
///
/// The topology (edges, boundaries, components, χ, genus, non-manifold and orientation
/// checks) is computed over the *analysed* faces: faces with at least three corners, every
/// vertex index in range, and no vertex twice. The other faces are reported
/// ([`TopologyReport::short_faces`], [`TopologyReport::invalid_indices`], a
/// [`Degeneracy::RepeatedVertex`]) and otherwise left out, so that one broken face cannot
/// make the rest of the report wrong. Faces of zero area are analysed (they are valid
/// topology) and reported as [`Degeneracy::ZeroArea`].
///
/// # Definitions
///
/// - An *edge* is an unordered vertex pair `{a, b}` joined by a side of some analysed face.
///   Its *sides* are the face corners whose half-edge runs along it (corner `c` runs from its
///   vertex to the next corner's vertex of the same face). A *boundary* edge has one side,
///   a manifold interior edge two, a *non-manifold* edge three or more. A two-sided edge whose
///   sides run the same way (`a → b` twice) is *inconsistently oriented*.
/// - A *fan* of a vertex is a maximal set of its face corners joined through two-sided edges
///   at the vertex (in either direction). A vertex with more than one fan, that is not on a
///   non-manifold edge, is a *non-manifold vertex* (a pinch: a bowtie, two cones touching at
///   their tips). Vertices on non-manifold edges are named by the edge report instead.
/// - *Components* are the classes of analysed faces that share vertices (so two cones touching
///   at their tips are one component, and each vertex, edge and face is in exactly one
///   component; χ is then the sum of the components' χ).
/// - χ = V − E + F, where V counts the vertices referenced by analysed faces (unreferenced
///   vertices and vertices used only by left-out faces do not count), E the edges and F the
///   analysed faces.
/// - A component is *orientable* if its faces can be given orientations that make every
///   two-sided edge consistent (found by a breadth-first walk across two-sided edges;
///   non-manifold edges do not propagate orientation). It is *manifold* if it has no
///   non-manifold edge and no non-manifold vertex.
/// - The *genus* of a manifold, orientable component with χ_c and `b` boundary loops is
///   `g = (2 − χ_c − b) / 2` (for a closed surface `(2 − χ_c)/2`; a sphere or disk has 0, a
///   torus 1, the bunny with four holes 0). Other components have no genus (for a
///   non-orientable manifold, `2 − χ_c − b` is its number of cross-caps).
///
/// # The report
///
/// Every list is sorted by its first index. [`is_clean`](Self::is_clean) says whether all
/// problem lists are empty. `Display` prints a human-readable report, listing at most
/// [`DEFAULT_LISTED`] entries per problem (see [`display_listing`](Self::display_listing)).
///
/// ```
/// use glam::DVec3;
/// use splinekit::mesh::{PolyMesh, TopologyReport};
///
/// // A tetrahedron with one face flipped.
/// let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
/// let mesh = PolyMesh::from_triangles(positions, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]]);
/// let report = TopologyReport::new(&mesh, 0.0);
/// assert_eq!((report.num_vertices, report.num_edges, report.num_faces), (4, 6, 4));
/// assert_eq!((report.euler_characteristic, report.genus()), (2, Some(0)));
/// assert_eq!(report.nonmanifold.iter().filter(|p| p.is_inconsistent()).count(), 3);
/// assert_eq!(report.misoriented_faces, vec![3]);
/// assert!(!report.is_clean());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TopologyReport {
    /// Vertices referenced by analysed faces (V of χ).
    pub num_vertices: usize,
    /// Edges of the analysed faces (E of χ).
    pub num_edges: usize,
    /// Analysed faces (F of χ).
    pub num_faces: usize,
    /// Edges with one face side.
    pub num_boundary_edges: usize,
    /// The boundary loops, in order of their first boundary edge.
    pub boundary_loops: Vec<BoundaryLoop>,
    /// The connected components, in order of their first face.
    pub components: Vec<Component>,
    /// Per mesh face, its component, or [`NONE`](crate::mesh::NONE) for a face left out of the analysis.
    pub face_component: Vec<u32>,
    /// χ = V − E + F.
    pub euler_characteristic: i64,
    /// Where the mesh is not a manifold, consistently oriented surface: first the edges with
    /// more than two face sides ([`NonManifold::Edge`]), then the pinch vertices (several
    /// fans, not on a non-manifold edge: [`NonManifold::Vertex`]), then the two-sided edges
    /// used twice in the same direction ([`NonManifold::Inconsistent`]); each kind sorted by
    /// its vertices.
    pub nonmanifold: Vec<NonManifold>,
    /// In each orientable component that is not consistently oriented, the faces to flip
    /// for a consistent orientation: those that disagree with the majority of their
    /// component (on a tie, those that disagree with its first face). Ascending.
    pub misoriented_faces: Vec<u32>,
    /// Faces with a repeated vertex or (nearly) zero area.
    pub degenerate_faces: Vec<DegenerateFace>,
    /// Faces with the same vertex set as an earlier face (faces with at least three corners
    /// and valid indices are compared).
    pub duplicate_faces: Vec<DuplicateFace>,
    /// Vertices that no face names.
    pub unreferenced_vertices: Vec<u32>,
    /// Faces with fewer than three corners.
    pub short_faces: Vec<ShortFace>,
    /// Face corners naming a vertex that does not exist.
    pub invalid_indices: Vec<InvalidIndex>,
    /// Vertices with a NaN or infinite coordinate.
    pub nonfinite_vertices: Vec<u32>,
}

impl TopologyReport {
    /// Whether no problem was found (every problem list is empty).
    #[must_use]
    pub fn is_clean(&self) -> bool {
        self.num_problems() == 0
    }

    /// Total number of entries in the problem lists.
    #[must_use]
    pub fn num_problems(&self) -> usize {
        self.nonmanifold.len()
            + self.misoriented_faces.len()
            + self.degenerate_faces.len()
            + self.duplicate_faces.len()
            + self.unreferenced_vertices.len()
            + self.short_faces.len()
            + self.invalid_indices.len()
            + self.nonfinite_vertices.len()
    }

    /// Whether there is at least one analysed face and no boundary edge.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.num_faces > 0 && self.num_boundary_edges == 0
    }

    /// Whether there is no non-manifold edge or vertex.
    #[must_use]
    pub fn is_manifold(&self) -> bool {
        !self.nonmanifold.iter().any(|p| p.is_edge() || p.is_vertex())
    }

    /// Whether every component is orientable.
    #[must_use]
    pub fn is_orientable(&self) -> bool {
        self.components.iter().all(|c| c.orientable)
    }

    /// Whether every two-sided edge is used in opposite directions.
    #[must_use]
    pub fn is_consistently_oriented(&self) -> bool {
        !self.nonmanifold.iter().any(NonManifold::is_inconsistent)
    }

    /// The sum of the components' genera, if every component has one (see [`Component::genus`]).
    #[must_use]
    pub fn genus(&self) -> Option<u32> {
        self.components.iter().map(|c| c.genus).sum()
    }

    /// A `Display` of the report listing at most `limit` entries per problem list (then
    /// `… and N more`).
    #[must_use]
    pub fn display_listing(&self, limit: usize) -> impl fmt::Display + '_ {
        Listing { report: self, limit }
    }
}

impl fmt::Display for TopologyReport {
    /// The report in lines of text, at most [`DEFAULT_LISTED`] entries per problem list.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.display_listing(DEFAULT_LISTED).fmt(f)
    }
}

struct Listing<'a> {
    report: &'a TopologyReport,
    limit: usize,
}

impl fmt::Display for Listing<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = self.report;
        let plural = |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        let left_out = r.face_component.len() - r.num_faces;
        writeln!(
            f,
            "{}, {}, {}{}",
            plural(r.num_vertices, "vertex", "vertices"),
            plural(r.num_edges, "edge", "edges"),
            plural(r.num_faces, "face", "faces"),
            if left_out > 0 {
                format!(" ({} left out, see the problems)", plural(left_out, "face", "faces"))
            } else {
                String::new()
            }
        )?;
        if r.num_boundary_edges == 0 {
            writeln!(f, "boundary: none (closed)")?;
        } else {
            let lengths: Vec<String> = r
                .boundary_loops
                .iter()
                .map(|l| if l.closed { l.num_edges().to_string() } else { format!("{} (open)", l.num_edges()) })
                .collect();
            writeln!(
                f,
                "boundary: {} in {} ({})",
                plural(r.num_boundary_edges, "edge", "edges"),
                plural(r.boundary_loops.len(), "loop", "loops"),
                list(&lengths, self.limit, ", ")
            )?;
        }
        writeln!(f, "components: {}", r.components.len())?;
        writeln!(f, "Euler characteristic: {}", r.euler_characteristic)?;
        match r.genus() {
            Some(g) => writeln!(f, "genus: {g}")?,
            None => writeln!(f, "genus: undefined (a component is non-manifold or non-orientable)")?,
        }
        if r.components.len() > 1 {
            for (k, c) in r.components.iter().enumerate().take(self.limit) {
                let genus = c.genus.map_or_else(|| String::from("-"), |g| g.to_string());
                writeln!(
                    f,
                    "  component {k}: {} from face {}, {}, χ {}, genus {genus}{}{}",
                    plural(c.num_faces, "face", "faces"),
                    c.first_face,
                    plural(c.num_boundary_loops, "boundary loop", "boundary loops"),
                    c.euler_characteristic,
                    if c.manifold { "" } else { ", non-manifold" },
                    if c.orientable { "" } else { ", non-orientable" },
                )?;
            }
            if r.components.len() > self.limit {
                writeln!(f, "  … and {} more components", r.components.len() - self.limit)?;
            }
        } else if let Some(c) = r.components.first().filter(|c| !c.orientable) {
            writeln!(f, "non-orientable ({} cross-caps)", 2 - c.euler_characteristic - c.num_boundary_loops as i64)?;
        }
        if r.is_clean() {
            return writeln!(f, "problems: none");
        }
        writeln!(f, "problems: {}", r.num_problems())?;
        let n = self.limit;
        let kind = |is: fn(&NonManifold) -> bool| r.nonmanifold.iter().filter(|p| is(p)).collect::<Vec<_>>();
        section(f, "non-manifold edges", &kind(NonManifold::is_edge), n, ToString::to_string)?;
        section(f, "non-manifold vertices", &kind(NonManifold::is_vertex), n, ToString::to_string)?;
        section(f, "inconsistently oriented edges", &kind(NonManifold::is_inconsistent), n, ToString::to_string)?;
        if !r.misoriented_faces.is_empty() {
            let items: Vec<String> = r.misoriented_faces.iter().map(u32::to_string).collect();
            writeln!(f, "  faces to flip for a consistent orientation ({}): {}", items.len(), list(&items, n, ", "))?;
        }
        section(f, "degenerate faces", &r.degenerate_faces, n, |d| match d.kind {
            Degeneracy::RepeatedVertex { vertex } => format!("face {}: vertex {vertex} repeated", d.face),
            Degeneracy::ZeroArea => format!("face {}: zero area", d.face),
        })?;
        section(f, "duplicate faces", &r.duplicate_faces, n, |d| {
            format!("face {}: same vertices as face {}", d.face, d.first)
        })?;
        section(f, "faces with fewer than 3 vertices", &r.short_faces, n, |s| {
            format!("face {}: {}", s.face, plural(s.len as usize, "vertex", "vertices"))
        })?;
        section(f, "indices out of range", &r.invalid_indices, n, |i| format!("face {}: vertex {}", i.face, i.vertex))?;
        if !r.unreferenced_vertices.is_empty() {
            let items: Vec<String> = r.unreferenced_vertices.iter().map(u32::to_string).collect();
            writeln!(f, "  unreferenced vertices ({}): {}", items.len(), list(&items, n, ", "))?;
        }
        if !r.nonfinite_vertices.is_empty() {
            let items: Vec<String> = r.nonfinite_vertices.iter().map(u32::to_string).collect();
            writeln!(f, "  vertices with a non-finite coordinate ({}): {}", items.len(), list(&items, n, ", "))?;
        }
        Ok(())
    }
}

/// Writes `  title (N):` and one indented line per item, at most `limit`.
fn section<T>(
    f: &mut fmt::Formatter<'_>,
    title: &str,
    items: &[T],
    limit: usize,
    line: impl Fn(&T) -> String,
) -> fmt::Result {
    if items.is_empty() {
        return Ok(());
    }
    writeln!(f, "  {title} ({}):", items.len())?;
    for item in items.iter().take(limit) {
        writeln!(f, "    {}", line(item))?;
    }
    if items.len() > limit {
        writeln!(f, "    … and {} more", items.len() - limit)?;
    }
    Ok(())
}

/// The first `limit` items joined by `sep`, then `… and N more`.
fn list(items: &[String], limit: usize, sep: &str) -> String {
    let mut s = items.iter().take(limit).cloned().collect::<Vec<_>>().join(sep);
    if items.len() > limit {
        s += &format!("{sep}… and {} more", items.len() - limit);
    }
    s
}
