//! Topology validation of a [`PolyMesh`]: counts, boundary loops, components, Euler
//! characteristic and genus, and every problem by vertex and face index
//! ([`TopologyReport`]); and a repair that splits non-manifold edges and vertices
//! ([`split_nonmanifold`]).
//!
//! The definitions (which faces take part, edges, fans, components, χ, genus) are in the docs
//! of [`TopologyReport`].
//!
//! Cost: `O(corners · valence)` time (the [`Adjacency`]), plus a sort for duplicate faces.

use std::collections::VecDeque;
use std::fmt;
use std::hash::{DefaultHasher, Hash, Hasher};

use glam::DVec3;

use super::{Adjacency, EdgeProblem, FaceVarying, NONE, PolyMesh};

/// The default `tolerance` of [`TopologyReport::new`]: only faces of exactly zero area are
/// degenerate.
pub const DEFAULT_DEGENERATE_TOLERANCE: f64 = 0.0;

/// How many entries of each problem list [`TopologyReport`]'s `Display` prints before
/// `… and N more`.
pub const DEFAULT_LISTED: usize = 10;

/// An edge used by more than two face sides.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NonManifoldEdge {
    /// Smaller vertex index.
    pub a: u32,
    /// Larger vertex index.
    pub b: u32,
    /// The faces along the edge, ascending.
    pub faces: Vec<u32>,
}

/// A vertex whose faces form several fans (see [`TopologyReport`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NonManifoldVertex {
    /// The vertex.
    pub vertex: u32,
    /// Number of fans (at least 2).
    pub fans: u32,
}

/// A two-sided edge whose two faces both run `a → b`: their orientations disagree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InconsistentEdge {
    /// Start vertex (in both faces).
    pub a: u32,
    /// End vertex.
    pub b: u32,
    /// The two faces, ascending.
    pub faces: [u32; 2],
}

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
/// assert_eq!(report.inconsistent_edges.len(), 3);
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
    /// Per mesh face, its component, or [`NONE`] for a face left out of the analysis.
    pub face_component: Vec<u32>,
    /// χ = V − E + F.
    pub euler_characteristic: i64,
    /// Edges with more than two face sides.
    pub nonmanifold_edges: Vec<NonManifoldEdge>,
    /// Pinch vertices (several fans, not on a non-manifold edge).
    pub nonmanifold_vertices: Vec<NonManifoldVertex>,
    /// Two-sided edges used twice in the same direction.
    pub inconsistent_edges: Vec<InconsistentEdge>,
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
    /// Analyses `mesh` (it builds its own [`Adjacency`]).
    ///
    /// `tolerance` (a distance, ≥ 0) decides which faces are degenerate by area: a face is
    /// [`ZeroArea`](Degeneracy::ZeroArea) when `2·A / L ≤ tolerance`, where `A` is the length
    /// of its vector area (Newell's formula, half the norm of `Σ (pᵢ − p₀) × (pᵢ₊₁ − p₀)`)
    /// and `L` its longest edge, or when all its corners coincide. For a triangle, `2A/L` is
    /// its smallest height: the face is degenerate when it lies within `tolerance` of a line.
    /// [`DEFAULT_DEGENERATE_TOLERANCE`] (0) flags only exactly zero areas. Faces with a
    /// non-finite corner are not measured.
    ///
    /// Never panics, whatever the indices.
    #[must_use]
    pub fn new(mesh: &PolyMesh, tolerance: f64) -> Self {
        let scan = Scan::new(mesh, tolerance, true);
        let kept = Kept::new(mesh, &scan.keep);
        let adj = Adjacency::from_faces(&kept.offsets, &kept.verts, mesh.num_vertices());
        Self::analyse(mesh, &kept, &adj, scan)
    }

    /// [`Self::new`] reusing the mesh's adjacency (`Adjacency::build(mesh)`). If some faces
    /// are left out of the analysis (see [`TopologyReport`]), the adjacency of the others is
    /// built anew.
    #[must_use]
    pub fn with_adjacency(mesh: &PolyMesh, adjacency: &Adjacency, tolerance: f64) -> Self {
        let scan = Scan::new(mesh, tolerance, true);
        let kept = Kept::new(mesh, &scan.keep);
        if kept.face_map.is_none() && adjacency.face_of.len() == mesh.face_vertices.len() {
            return Self::analyse(mesh, &kept, adjacency, scan);
        }
        let adj = Adjacency::from_faces(&kept.offsets, &kept.verts, mesh.num_vertices());
        Self::analyse(mesh, &kept, &adj, scan)
    }

    fn analyse(mesh: &PolyMesh, kept: &Kept<'_>, adj: &Adjacency, scan: Scan) -> Self {
        let nv = mesh.num_vertices();
        let nf = kept.num_faces();
        let edges = Edges::new(kept, adj);
        let mesh_face = |f: u32| kept.mesh_face(f);

        // Problems found while pairing half-edges.
        let mut nonmanifold_edges = Vec::new();
        let mut inconsistent_edges = Vec::new();
        let mut on_nonmanifold_edge = vec![false; nv];
        for p in &adj.problems {
            match p {
                EdgeProblem::NonManifold { a, b, corners } => {
                    let mut faces: Vec<u32> = corners.iter().map(|&c| mesh_face(adj.face_of[c as usize])).collect();
                    faces.sort_unstable();
                    faces.dedup();
                    on_nonmanifold_edge[*a as usize] = true;
                    on_nonmanifold_edge[*b as usize] = true;
                    nonmanifold_edges.push(NonManifoldEdge { a: *a, b: *b, faces });
                }
                EdgeProblem::Inconsistent { a, b, corners } => {
                    let mut faces = corners.map(|c| mesh_face(adj.face_of[c as usize]));
                    faces.sort_unstable();
                    inconsistent_edges.push(InconsistentEdge { a: *a, b: *b, faces });
                }
            }
        }
        nonmanifold_edges.sort_by_key(|e| (e.a, e.b));
        inconsistent_edges.sort_by_key(|e| (e.a.min(e.b), e.a.max(e.b)));

        // Fans, orientation-agnostic: corners at a vertex joined across two-sided edges.
        let mut fans = UnionFind::new(kept.verts.len());
        for (c, &m) in edges.mate.iter().enumerate() {
            if m != NONE && (c as u32) < m {
                join_across(kept, &mut fans, c as u32, m);
            }
        }
        let mut nonmanifold_vertices = Vec::new();
        let mut roots = Vec::new();
        for v in 0..nv as u32 {
            if on_nonmanifold_edge[v as usize] {
                continue;
            }
            roots.clear();
            roots.extend(adj.corners_of(v).iter().map(|&c| fans.find(c)));
            roots.sort_unstable();
            roots.dedup();
            if roots.len() > 1 {
                nonmanifold_vertices.push(NonManifoldVertex { vertex: v, fans: roots.len() as u32 });
            }
        }

        // Components: faces sharing vertices.
        let mut vertex_sets = UnionFind::new(nv);
        for f in 0..nf {
            let face = kept.face(f);
            for w in face.windows(2) {
                vertex_sets.union(w[0], w[1]);
            }
        }
        let mut component_of_root = vec![NONE; nv];
        let mut face_component = vec![NONE; mesh.num_faces()];
        let mut num_components = 0u32;
        for f in 0..nf {
            let r = vertex_sets.find(kept.face(f)[0]) as usize;
            if component_of_root[r] == NONE {
                component_of_root[r] = num_components;
                num_components += 1;
            }
            face_component[mesh_face(f as u32) as usize] = component_of_root[r];
        }
        let vertex_component = |v: u32, sets: &mut UnionFind| component_of_root[sets.find(v) as usize];
        let mut components: Vec<Component> = (0..num_components)
            .map(|_| Component {
                first_face: NONE,
                num_vertices: 0,
                num_edges: 0,
                num_faces: 0,
                num_boundary_edges: 0,
                num_boundary_loops: 0,
                euler_characteristic: 0,
                manifold: true,
                orientable: true,
                consistently_oriented: true,
                genus: None,
            })
            .collect();
        for f in 0..nf {
            let k = vertex_component(kept.face(f)[0], &mut vertex_sets) as usize;
            let comp = &mut components[k];
            comp.num_faces += 1;
            comp.first_face = comp.first_face.min(mesh_face(f as u32));
        }
        let mut num_vertices = 0;
        for v in 0..nv as u32 {
            if !adj.corners_of(v).is_empty() {
                num_vertices += 1;
                components[vertex_component(v, &mut vertex_sets) as usize].num_vertices += 1;
            }
        }
        for &c in &edges.first_side {
            let k = vertex_component(kept.verts[c as usize], &mut vertex_sets) as usize;
            components[k].num_edges += 1;
            if edges.is_boundary(c) {
                components[k].num_boundary_edges += 1;
            }
        }
        for e in &nonmanifold_edges {
            components[vertex_component(e.a, &mut vertex_sets) as usize].manifold = false;
        }
        for v in &nonmanifold_vertices {
            components[vertex_component(v.vertex, &mut vertex_sets) as usize].manifold = false;
        }
        for e in &inconsistent_edges {
            components[vertex_component(e.a, &mut vertex_sets) as usize].consistently_oriented = false;
        }

        // Orientation.
        let orientation = Orientation::new(kept, adj, &edges);
        let mut misoriented_faces = Vec::new();
        for f in 0..nf {
            let group = orientation.group[f] as usize;
            if orientation.conflict[group] {
                let k = vertex_component(kept.face(f)[0], &mut vertex_sets) as usize;
                components[k].orientable = false;
            } else if orientation.flip(f) {
                misoriented_faces.push(mesh_face(f as u32));
            }
        }
        misoriented_faces.sort_unstable();

        // Boundary loops.
        let boundary_loops = boundary_loops(kept, adj, &edges);
        for l in &boundary_loops {
            components[vertex_component(l.vertices[0], &mut vertex_sets) as usize].num_boundary_loops += 1;
        }
        for comp in &mut components {
            comp.euler_characteristic = comp.num_vertices as i64 - comp.num_edges as i64 + comp.num_faces as i64;
            if comp.manifold && comp.orientable {
                let twice = 2 - comp.euler_characteristic - comp.num_boundary_loops as i64;
                if twice >= 0 && twice % 2 == 0 {
                    comp.genus = u32::try_from(twice / 2).ok();
                }
            }
        }

        let num_edges = edges.first_side.len();
        let duplicate_faces = duplicate_faces(mesh, &scan.valid);
        Self {
            num_vertices,
            num_edges,
            num_faces: nf,
            num_boundary_edges: edges.num_boundary,
            boundary_loops,
            components,
            face_component,
            euler_characteristic: num_vertices as i64 - num_edges as i64 + nf as i64,
            nonmanifold_edges,
            nonmanifold_vertices,
            inconsistent_edges,
            misoriented_faces,
            degenerate_faces: scan.degenerate_faces,
            duplicate_faces,
            unreferenced_vertices: scan.unreferenced_vertices,
            short_faces: scan.short_faces,
            invalid_indices: scan.invalid_indices,
            nonfinite_vertices: scan.nonfinite_vertices,
        }
    }

    /// Whether no problem was found (every problem list is empty).
    #[must_use]
    pub fn is_clean(&self) -> bool {
        self.num_problems() == 0
    }

    /// Total number of entries in the problem lists.
    #[must_use]
    pub fn num_problems(&self) -> usize {
        self.nonmanifold_edges.len()
            + self.nonmanifold_vertices.len()
            + self.inconsistent_edges.len()
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
        self.nonmanifold_edges.is_empty() && self.nonmanifold_vertices.is_empty()
    }

    /// Whether every component is orientable.
    #[must_use]
    pub fn is_orientable(&self) -> bool {
        self.components.iter().all(|c| c.orientable)
    }

    /// Whether every two-sided edge is used in opposite directions.
    #[must_use]
    pub fn is_consistently_oriented(&self) -> bool {
        self.inconsistent_edges.is_empty()
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
        section(f, "non-manifold edges", &r.nonmanifold_edges, n, |e| {
            format!("edge {}–{}: faces {}", e.a, e.b, join(&e.faces))
        })?;
        section(f, "non-manifold vertices", &r.nonmanifold_vertices, n, |v| {
            format!("vertex {}: {} fans", v.vertex, v.fans)
        })?;
        section(f, "inconsistently oriented edges", &r.inconsistent_edges, n, |e| {
            format!("edge {}→{}: faces {} and {} both run this way", e.a, e.b, e.faces[0], e.faces[1])
        })?;
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

fn join(v: &[u32]) -> String {
    v.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
}

// ---------------------------------------------------------------------------------------
// Repair

/// What [`split_nonmanifold`] changed.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SplitReport {
    /// Input faces naming a vertex that does not exist, removed (input face numbering,
    /// ascending). The other face indices here are output face indices; they equal the
    /// input's when nothing was removed.
    pub removed_faces: Vec<u32>,
    /// Faces whose corner order was reversed (keeping their first corner) to orient their
    /// component consistently, ascending.
    pub flipped_faces: Vec<u32>,
    /// Input vertices that were split into several, ascending.
    pub split_vertices: Vec<u32>,
    /// Per output vertex, the input vertex it copies: `i` for the first `n` vertices, then
    /// the origin of each new vertex.
    pub vertex_origin: Vec<u32>,
}

impl SplitReport {
    /// Number of vertices added.
    #[must_use]
    pub fn num_new_vertices(&self) -> usize {
        self.vertex_origin.iter().enumerate().filter(|&(i, &o)| i as u32 != o).count()
    }

    /// Whether the mesh came back unchanged.
    #[must_use]
    pub fn is_unchanged(&self) -> bool {
        self.removed_faces.is_empty() && self.flipped_faces.is_empty() && self.split_vertices.is_empty()
    }
}

/// Makes a mesh manifold: orients each component consistently where it can, then splits
/// non-manifold edges and vertices by duplicating vertices.
///
/// 1. **Orientation.** In each set of faces joined through two-sided edges, a breadth-first
///    walk from its first face gives every face an orientation; the faces that disagree with
///    the majority (on a tie, with the first face) are flipped (corners reversed, keeping
///    the first corner; normal and UV indices are reversed with them). An orientable set
///    comes out consistently oriented. In a non-orientable one (a Möbius strip) the same
///    flips are made only if they leave fewer inconsistent edges than the input has; the
///    remaining inconsistent edges are where step 2 cuts it open.
/// 2. **Splitting.** Along a non-manifold edge, half-edges running opposite ways are paired
///    in corner order (`a → b` with the first unpaired `b → a`); the remaining sides, and
///    the sides of inconsistent edges, become boundary. Then every vertex whose corners form
///    several fans through paired edges keeps its index for the fan of its smallest corner
///    and gets a new vertex (same position and colour, appended in vertex order) for each
///    other fan. Repeated until the mesh is clean; in the rare case where a split does not
///    separate a problem edge (a single fan that reaches the edge twice), the faces of its
///    unpaired sides are detached at the edge's ends.
///
/// The result has no non-manifold edge or vertex and no inconsistent edge
/// ([`TopologyReport::new`] on it lists none). Faces naming a vertex that does not exist are
/// removed first (they could otherwise come to name one of the new vertices); the other
/// faces keep their order, and face-varying normal and UV values and indices are kept (only
/// reordered with flipped faces), so only `face_vertices`, `positions` and `colors` change.
/// Faces with fewer than three corners or a repeated vertex are left as they are.
///
/// ```
/// use glam::DVec3;
/// use splinekit::mesh::{PolyMesh, TopologyReport, split_nonmanifold};
///
/// // A bowtie: two triangles sharing only vertex 0.
/// let mesh = PolyMesh::from_triangles(vec![DVec3::ZERO; 5], &[[0, 1, 2], [0, 3, 4]]);
/// assert_eq!(TopologyReport::new(&mesh, 0.0).nonmanifold_vertices.len(), 1);
/// let (fixed, what) = split_nonmanifold(&mesh);
/// assert_eq!(fixed.face(1), &[5, 3, 4]);
/// assert_eq!((what.split_vertices, what.vertex_origin[5]), (vec![0], 0));
/// assert!(TopologyReport::new(&fixed, 0.0).is_manifold());
/// ```
#[must_use]
pub fn split_nonmanifold(mesh: &PolyMesh) -> (PolyMesh, SplitReport) {
    let scan = Scan::new(mesh, 0.0, false);
    let mut removed_faces: Vec<u32> = scan.invalid_indices.iter().map(|i| i.face).collect();
    removed_faces.dedup();
    if removed_faces.is_empty() {
        return split_valid(mesh, scan, removed_faces);
    }
    let valid = without_faces(mesh, &removed_faces);
    let scan = Scan::new(&valid, 0.0, false);
    split_valid(&valid, scan, removed_faces)
}

/// A copy of `mesh` without the faces `remove` (ascending), with their attribute indices.
fn without_faces(mesh: &PolyMesh, remove: &[u32]) -> PolyMesh {
    let mut out = PolyMesh { positions: mesh.positions.clone(), colors: mesh.colors.clone(), ..PolyMesh::default() };
    let mut corners = Vec::new();
    for f in 0..mesh.num_faces() {
        if remove.binary_search(&(f as u32)).is_err() {
            let range = mesh.face_offsets[f] as usize..mesh.face_offsets[f + 1] as usize;
            out.face_vertices.extend_from_slice(&mesh.face_vertices[range.clone()]);
            out.face_offsets.push(out.face_vertices.len() as u32);
            corners.extend(range);
        }
    }
    let pick = |indices: &[u32]| corners.iter().map(|&c| indices[c]).collect();
    out.normals = mesh.normals.as_ref().map(|a| FaceVarying { values: a.values.clone(), indices: pick(&a.indices) });
    out.uvs = mesh.uvs.as_ref().map(|a| FaceVarying { values: a.values.clone(), indices: pick(&a.indices) });
    out
}

/// [`split_nonmanifold`] of a mesh whose indices are all in range.
fn split_valid(mesh: &PolyMesh, scan: Scan, removed_faces: Vec<u32>) -> (PolyMesh, SplitReport) {
    let mut out = mesh.clone();
    let nv0 = mesh.num_vertices();
    let mut report = SplitReport { removed_faces, vertex_origin: (0..nv0 as u32).collect(), ..SplitReport::default() };
    let kept = Kept::new(mesh, &scan.keep);
    // Kept corner → mesh corner.
    let corner_map: Vec<u32> = match &kept.face_map {
        None => (0..mesh.face_vertices.len() as u32).collect(),
        Some(map) => {
            map.iter().flat_map(|&f| mesh.face_offsets[f as usize]..mesh.face_offsets[f as usize + 1]).collect()
        }
    };
    let mut work = kept;

    // 1. Orientation.
    {
        let adj = Adjacency::from_faces(&work.offsets, &work.verts, nv0);
        let edges = Edges::new(&work, &adj);
        let orientation = Orientation::new(&work, &adj, &edges);
        let verts = work.verts.to_mut();
        for f in 0..work.offsets.len() - 1 {
            if !orientation.flip(f) {
                continue;
            }
            let (s, e) = (work.offsets[f] as usize, work.offsets[f + 1] as usize);
            verts[s + 1..e].reverse();
            let (ms, me) = (corner_map[s] as usize, corner_map[e - 1] as usize + 1);
            out.face_vertices[ms + 1..me].reverse();
            if let Some(n) = &mut out.normals {
                n.indices[ms + 1..me].reverse();
            }
            if let Some(t) = &mut out.uvs {
                t.indices[ms + 1..me].reverse();
            }
            report.flipped_faces.push(work.face_map.as_ref().map_or(f as u32, |m| m[f]));
        }
        report.flipped_faces.sort_unstable();
    }

    // 2. Splitting, until clean. Every round adds a vertex or stops, and a vertex used by a
    // single corner is never split, so this ends (at the latest with every corner its own
    // vertex).
    let mut split = vec![false; nv0];
    loop {
        let nv = out.positions.len();
        let adj = Adjacency::from_faces(&work.offsets, &work.verts, nv);
        let pairs = pair_opposite(&work, &adj);
        let mut fans = UnionFind::new(work.verts.len());
        for (c, &m) in pairs.iter().enumerate() {
            if m != NONE && (c as u32) < m {
                join_across(&work, &mut fans, c as u32, m);
            }
        }
        let mut renames: Vec<(u32, u32)> = Vec::new(); // (kept corner, new vertex)
        let mut groups: Vec<(u32, u32)> = Vec::new(); // (root, new vertex or v)
        for v in 0..nv as u32 {
            let corners = adj.corners_of(v);
            if corners.len() < 2 {
                continue;
            }
            groups.clear();
            for &c in corners {
                let root = fans.find(c);
                let target = match groups.iter().find(|g| g.0 == root) {
                    Some(g) => g.1,
                    None => {
                        let target = if groups.is_empty() { v } else { add_copy(&mut out, &mut report, v) };
                        groups.push((root, target));
                        target
                    }
                };
                if target != v {
                    renames.push((c, target));
                }
            }
        }
        if renames.is_empty() {
            // Nothing splits: done if clean, else detach the unpaired sides of problem edges.
            if adj.problems.is_empty() {
                break;
            }
            for p in &adj.problems {
                let corners: &[u32] = match p {
                    EdgeProblem::NonManifold { corners, .. } => corners,
                    EdgeProblem::Inconsistent { corners, .. } => corners,
                };
                let anchor = corners.iter().copied().find(|&c| pairs[c as usize] != NONE).unwrap_or(corners[0]);
                for &d in corners {
                    if d == anchor || pairs[d as usize] == anchor {
                        continue;
                    }
                    for corner in [d, work.next(d)] {
                        let v = work.verts[corner as usize];
                        if adj.corners_of(v).len() > 1 && !renames.iter().any(|r| r.0 == corner) {
                            renames.push((corner, add_copy(&mut out, &mut report, v)));
                        }
                    }
                }
            }
            if renames.is_empty() {
                break; // cannot happen: a problem edge's ends are shared
            }
        }
        let verts = work.verts.to_mut();
        for &(c, v) in &renames {
            let old = verts[c as usize];
            split[report.vertex_origin[old as usize] as usize] = true;
            verts[c as usize] = v;
            out.face_vertices[corner_map[c as usize] as usize] = v;
        }
    }
    report.split_vertices = (0..nv0 as u32).filter(|&v| split[v as usize]).collect();
    (out, report)
}

/// Appends a copy of vertex `v` (position, colour) and returns its index.
fn add_copy(out: &mut PolyMesh, report: &mut SplitReport, v: u32) -> u32 {
    let new = out.positions.len() as u32;
    out.positions.push(out.positions[v as usize]);
    if !out.colors.is_empty() {
        out.colors.push(out.colors[v as usize]);
    }
    report.vertex_origin.push(report.vertex_origin[v as usize]);
    new
}

/// Per corner, its partner across the edge when the two run opposite ways: the adjacency's
/// twin, and on non-manifold edges each `a → b` side paired with the first unpaired `b → a`
/// side in corner order. [`NONE`] otherwise.
fn pair_opposite(kept: &Kept<'_>, adj: &Adjacency) -> Vec<u32> {
    let mut pairs = adj.twin.clone();
    for p in &adj.problems {
        if let EdgeProblem::NonManifold { corners, .. } = p {
            for (i, &c) in corners.iter().enumerate() {
                if pairs[c as usize] != NONE {
                    continue;
                }
                let start = kept.verts[c as usize];
                let partner = corners[i + 1..]
                    .iter()
                    .copied()
                    .find(|&d| pairs[d as usize] == NONE && kept.verts[d as usize] != start);
                if let Some(d) = partner {
                    pairs[c as usize] = d;
                    pairs[d as usize] = c;
                }
            }
        }
    }
    pairs
}

// ---------------------------------------------------------------------------------------
// Shared machinery

/// The analysed faces (all faces when every one qualifies, borrowed then).
struct Kept<'a> {
    offsets: std::borrow::Cow<'a, [u32]>,
    verts: std::borrow::Cow<'a, [u32]>,
    /// Kept face → mesh face; `None` when all faces are kept.
    face_map: Option<Vec<u32>>,
}

impl<'a> Kept<'a> {
    fn new(mesh: &'a PolyMesh, keep: &[bool]) -> Self {
        if keep.iter().all(|&k| k) {
            return Self {
                offsets: (&mesh.face_offsets[..]).into(),
                verts: (&mesh.face_vertices[..]).into(),
                face_map: None,
            };
        }
        let mut offsets = vec![0u32];
        let mut verts = Vec::new();
        let mut map = Vec::new();
        for (f, face) in mesh.faces().enumerate() {
            if keep[f] {
                verts.extend_from_slice(face);
                offsets.push(verts.len() as u32);
                map.push(f as u32);
            }
        }
        Self { offsets: offsets.into(), verts: verts.into(), face_map: Some(map) }
    }

    fn num_faces(&self) -> usize {
        self.offsets.len() - 1
    }

    fn face(&self, f: usize) -> &[u32] {
        &self.verts[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    fn mesh_face(&self, f: u32) -> u32 {
        self.face_map.as_ref().map_or(f, |m| m[f as usize])
    }

    /// The face of corner `c` (binary search over the offsets).
    fn face_of(&self, c: u32) -> usize {
        self.offsets.partition_point(|&o| o <= c) - 1
    }

    /// The corner after `c` in its face.
    fn next(&self, c: u32) -> u32 {
        let f = self.face_of(c);
        if c + 1 == self.offsets[f + 1] { self.offsets[f] } else { c + 1 }
    }

    /// The corner before `c` in its face.
    fn prev(&self, c: u32) -> u32 {
        let f = self.face_of(c);
        if c == self.offsets[f] { self.offsets[f + 1] - 1 } else { c - 1 }
    }
}

/// Joins, at both ends of the edge of corners `c` and `m`, the two faces' corners at that
/// vertex.
fn join_across(kept: &Kept<'_>, sets: &mut UnionFind, c: u32, m: u32) {
    let (u, nc, nm) = (kept.verts[c as usize], kept.next(c), kept.next(m));
    if kept.verts[m as usize] == u {
        // Same direction: corners at u are c and m, at the far end their successors.
        sets.union(c, m);
        sets.union(nc, nm);
    } else {
        sets.union(c, nm);
        sets.union(nc, m);
    }
}

/// The undirected edges of the analysed faces.
struct Edges {
    /// Per corner, the other side of a two-sided edge (opposite or same direction), or [`NONE`].
    mate: Vec<u32>,
    /// Per corner, whether it lies on a non-manifold edge.
    nonmanifold: Vec<bool>,
    /// One corner per edge (its first side in corner order).
    first_side: Vec<u32>,
    /// Number of one-sided edges.
    num_boundary: usize,
}

impl Edges {
    fn new(kept: &Kept<'_>, adj: &Adjacency) -> Self {
        let nc = kept.verts.len();
        let mut mate = adj.twin.clone();
        let mut nonmanifold = vec![false; nc];
        let mut names_edge = vec![false; nc];
        for p in &adj.problems {
            match p {
                EdgeProblem::NonManifold { corners, .. } => {
                    for &c in corners {
                        nonmanifold[c as usize] = true;
                    }
                    names_edge[corners[0] as usize] = true;
                }
                EdgeProblem::Inconsistent { corners: [c, d], .. } => {
                    mate[*c as usize] = *d;
                    mate[*d as usize] = *c;
                }
            }
        }
        let mut first_side = Vec::with_capacity(nc / 2 + 1);
        let mut num_boundary = 0;
        for c in 0..nc as u32 {
            let m = mate[c as usize];
            if nonmanifold[c as usize] {
                // The smallest side of a non-manifold edge names it.
                if names_edge[c as usize] {
                    first_side.push(c);
                }
            } else if m == NONE || c < m {
                first_side.push(c);
                num_boundary += usize::from(m == NONE);
            }
        }
        Self { mate, nonmanifold, first_side, num_boundary }
    }

    fn is_boundary(&self, c: u32) -> bool {
        self.mate[c as usize] == NONE && !self.nonmanifold[c as usize]
    }
}

/// Face orientations found by a breadth-first walk across two-sided edges.
struct Orientation {
    /// Per kept face: whether it is flipped relative to the first face of its group.
    flipped: Vec<bool>,
    /// Per kept face: its group (faces joined through two-sided edges).
    group: Vec<u32>,
    /// Per group: whether the walk met a contradiction (non-orientable).
    conflict: Vec<bool>,
    /// Per group: whether the flipped faces are the majority (then the others are to flip),
    /// on a tie not.
    majority_flipped: Vec<bool>,
    /// Per group: whether to leave its faces as they are. True for a non-orientable group
    /// where flipping the minority would not leave fewer inconsistent edges than the input
    /// has (a well-made Möbius strip keeps its one seam where it is).
    keep: Vec<bool>,
}

impl Orientation {
    fn new(kept: &Kept<'_>, adj: &Adjacency, edges: &Edges) -> Self {
        let nf = kept.num_faces();
        let mut flipped = vec![false; nf];
        let mut group = vec![NONE; nf];
        let mut conflict = Vec::new();
        let mut majority_flipped = Vec::new();
        let mut queue = VecDeque::new();
        for root in 0..nf {
            if group[root] != NONE {
                continue;
            }
            let g = conflict.len() as u32;
            conflict.push(false);
            group[root] = g;
            queue.push_back(root);
            let (mut total, mut nflipped) = (0usize, 0usize);
            while let Some(f) = queue.pop_front() {
                total += 1;
                nflipped += usize::from(flipped[f]);
                for c in kept.offsets[f]..kept.offsets[f + 1] {
                    let m = edges.mate[c as usize];
                    if m == NONE {
                        continue;
                    }
                    let h = adj.face_of[m as usize] as usize;
                    let same_direction = kept.verts[m as usize] == kept.verts[c as usize];
                    let want = flipped[f] ^ same_direction;
                    if group[h] == NONE {
                        group[h] = g;
                        flipped[h] = want;
                        queue.push_back(h);
                    } else if flipped[h] != want {
                        conflict[g as usize] = true;
                    }
                }
            }
            majority_flipped.push(2 * nflipped > total);
        }
        let mut this = Self { flipped, group, conflict, majority_flipped, keep: Vec::new() };
        // Inconsistent edges per group as given and after the flips.
        let groups = this.conflict.len();
        let (mut before, mut after) = (vec![0usize; groups], vec![0usize; groups]);
        for (c, &m) in edges.mate.iter().enumerate() {
            if m == NONE || (c as u32) > m {
                continue;
            }
            let (f, h) = (adj.face_of[c] as usize, adj.face_of[m as usize] as usize);
            let same = kept.verts[m as usize] == kept.verts[c];
            let g = this.group[f] as usize;
            before[g] += usize::from(same);
            after[g] += usize::from(same ^ this.flip_majority(f) ^ this.flip_majority(h));
        }
        this.keep = (0..groups).map(|g| this.conflict[g] && after[g] >= before[g]).collect();
        this
    }

    /// Whether kept face `f` disagrees with the majority of its group.
    fn flip_majority(&self, f: usize) -> bool {
        self.flipped[f] != self.majority_flipped[self.group[f] as usize]
    }

    /// Whether kept face `f` is to be flipped: it disagrees with the majority of its group,
    /// and the group is orientable or flipping helps (see [`Self::keep`]).
    fn flip(&self, f: usize) -> bool {
        self.flip_majority(f) && !self.keep[self.group[f] as usize]
    }
}

/// Traces the boundary loops (see [`BoundaryLoop`]).
fn boundary_loops(kept: &Kept<'_>, adj: &Adjacency, edges: &Edges) -> Vec<BoundaryLoop> {
    let nc = kept.verts.len();
    let mut used = vec![false; nc];
    let mut loops = Vec::new();
    for start in 0..nc as u32 {
        if used[start as usize] || !edges.is_boundary(start) {
            continue;
        }
        used[start as usize] = true;
        let first = kept.verts[start as usize];
        let mut vertices = vec![first];
        let closed = walk(kept, adj, edges, &mut used, start, true, first, &mut vertices);
        if !closed {
            // Extend the open chain backwards from its start edge: walking `start` backwards
            // arrives at `first` again, which `back` then holds last.
            let mut back = Vec::new();
            walk(kept, adj, edges, &mut used, start, false, NONE, &mut back);
            back.reverse();
            back.pop();
            back.extend(vertices);
            vertices = back;
        }
        loops.push(BoundaryLoop { vertices, closed });
    }
    loops
}

/// Walks boundary edges from half-edge `h`, forward (to its end) or backward (to its
/// start), pushing each vertex reached, until `stop` is reached (returns true) or no unused
/// boundary edge continues (returns false).
fn walk(
    kept: &Kept<'_>,
    adj: &Adjacency,
    edges: &Edges,
    used: &mut [bool],
    mut h: u32,
    mut forward: bool,
    stop: u32,
    vertices: &mut Vec<u32>,
) -> bool {
    loop {
        let at = if forward { adj.to[h as usize] } else { kept.verts[h as usize] };
        if at == stop {
            return true;
        }
        vertices.push(at);
        // Preferred: rotate around `at` through paired edges, within the face fan.
        let limit = adj.corners_of(at).len() + 1;
        let mut r = if forward { kept.next(h) } else { kept.prev(h) };
        for _ in 0..limit {
            let t = adj.twin[r as usize];
            if t == NONE {
                break;
            }
            r = if forward { kept.next(t) } else { kept.prev(t) };
        }
        let candidate = if adj.twin[r as usize] == NONE && edges.is_boundary(r) && !used[r as usize] {
            Some((r, forward))
        } else {
            // Otherwise any unused boundary edge at `at`: leaving it, then entering it.
            let corners = adj.corners_of(at);
            corners.iter().copied().find(|&c| edges.is_boundary(c) && !used[c as usize]).map(|c| (c, true)).or_else(
                || {
                    corners
                        .iter()
                        .map(|&c| kept.prev(c))
                        .find(|&p| edges.is_boundary(p) && !used[p as usize])
                        .map(|p| (p, false))
                },
            )
        };
        let Some((next, dir)) = candidate else { return false };
        used[next as usize] = true;
        h = next;
        forward = dir;
    }
}

/// Per-face and per-vertex checks that need no adjacency.
struct Scan {
    /// Per face: analysed (≥ 3 corners, indices in range, no repeated vertex).
    keep: Vec<bool>,
    /// Per face: ≥ 3 corners and indices in range (compared for duplicates).
    valid: Vec<bool>,
    short_faces: Vec<ShortFace>,
    invalid_indices: Vec<InvalidIndex>,
    degenerate_faces: Vec<DegenerateFace>,
    nonfinite_vertices: Vec<u32>,
    unreferenced_vertices: Vec<u32>,
}

impl Scan {
    fn new(mesh: &PolyMesh, tolerance: f64, measure: bool) -> Self {
        debug_assert!(!(tolerance < 0.0), "tolerance must be ≥ 0");
        let nv = mesh.num_vertices();
        let nf = mesh.num_faces();
        let mut scan = Self {
            keep: vec![true; nf],
            valid: vec![true; nf],
            short_faces: Vec::new(),
            invalid_indices: Vec::new(),
            degenerate_faces: Vec::new(),
            nonfinite_vertices: (0..nv as u32).filter(|&v| !mesh.positions[v as usize].is_finite()).collect(),
            unreferenced_vertices: Vec::new(),
        };
        let mut referenced = vec![false; nv];
        let mut sorted = Vec::new();
        for (f, face) in mesh.faces().enumerate() {
            let fu = f as u32;
            if face.len() < 3 {
                scan.short_faces.push(ShortFace { face: fu, len: face.len() as u32 });
                scan.keep[f] = false;
                scan.valid[f] = false;
            }
            let mut in_range = true;
            for &v in face {
                if (v as usize) < nv {
                    referenced[v as usize] = true;
                } else {
                    scan.invalid_indices.push(InvalidIndex { face: fu, vertex: v });
                    in_range = false;
                }
            }
            if !in_range {
                scan.keep[f] = false;
                scan.valid[f] = false;
                continue;
            }
            if let Some(vertex) = repeated(face, &mut sorted) {
                scan.degenerate_faces.push(DegenerateFace { face: fu, kind: Degeneracy::RepeatedVertex { vertex } });
                scan.keep[f] = false;
                continue;
            }
            if measure && face.len() >= 3 && zero_area(&mesh.positions, face, tolerance) {
                scan.degenerate_faces.push(DegenerateFace { face: fu, kind: Degeneracy::ZeroArea });
            }
        }
        scan.unreferenced_vertices = (0..nv as u32).filter(|&v| !referenced[v as usize]).collect();
        scan
    }
}

/// The first vertex (in corner order) that occurs twice in `face`.
fn repeated(face: &[u32], scratch: &mut Vec<u32>) -> Option<u32> {
    if face.len() <= 16 {
        return face.iter().enumerate().find(|&(i, v)| face[..i].contains(v)).map(|(_, &v)| v);
    }
    scratch.clear();
    scratch.extend_from_slice(face);
    scratch.sort_unstable();
    if scratch.windows(2).all(|w| w[0] != w[1]) {
        return None;
    }
    face.iter().enumerate().find(|&(i, v)| face[..i].contains(v)).map(|(_, &v)| v)
}

/// Whether the face is degenerate by area (see [`TopologyReport::new`]).
fn zero_area(positions: &[DVec3], face: &[u32], tolerance: f64) -> bool {
    let p0 = positions[face[0] as usize];
    let mut twice_area = DVec3::ZERO;
    let mut longest2 = 0.0f64;
    for (i, &v) in face.iter().enumerate() {
        let p = positions[v as usize];
        let q = positions[face[(i + 1) % face.len()] as usize];
        if !p.is_finite() {
            return false;
        }
        twice_area += (p - p0).cross(q - p0);
        longest2 = longest2.max(p.distance_squared(q));
    }
    if longest2 == 0.0 {
        return true;
    }
    twice_area.length() <= tolerance * longest2.sqrt()
}

/// Faces with the same vertex set as an earlier face (among `valid` faces).
fn duplicate_faces(mesh: &PolyMesh, valid: &[bool]) -> Vec<DuplicateFace> {
    let mut scratch = Vec::new();
    let key = |face: &[u32], out: &mut Vec<u32>| {
        out.clear();
        out.extend_from_slice(face);
        out.sort_unstable();
        out.dedup();
    };
    let mut hashed: Vec<(u64, u32)> = Vec::with_capacity(mesh.num_faces());
    for (f, face) in mesh.faces().enumerate() {
        if valid[f] {
            key(face, &mut scratch);
            let mut h = DefaultHasher::new();
            scratch.hash(&mut h);
            hashed.push((h.finish(), f as u32));
        }
    }
    hashed.sort_unstable();
    let mut out = Vec::new();
    let mut run: Vec<(Vec<u32>, u32)> = Vec::new();
    for group in hashed.chunk_by(|x, y| x.0 == y.0).filter(|g| g.len() > 1) {
        // Equal hashes: compare the vertex sets exactly, grouping equal ones (by face order
        // within a set, so each set's first face comes first).
        run.clear();
        for &(_, f) in group {
            key(mesh.face(f as usize), &mut scratch);
            run.push((scratch.clone(), f));
        }
        run.sort_unstable();
        for same in run.chunk_by(|x, y| x.0 == y.0) {
            out.extend(same[1..].iter().map(|&(_, face)| DuplicateFace { face, first: same[0].1 }));
        }
    }
    out.sort_unstable_by_key(|d| d.face);
    out
}

/// Union-find over `0..n` with path halving and union by index (smaller root wins, so
/// roots are deterministic).
struct UnionFind(Vec<u32>);

impl UnionFind {
    fn new(n: usize) -> Self {
        Self((0..n as u32).collect())
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let up = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = up;
            x = up;
        }
        x
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.0[hi as usize] = lo;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(n: usize, tris: &[[u32; 3]]) -> PolyMesh {
        // Distinct, non-collinear positions so that no face has zero area by accident.
        let positions = (0..n).map(|i| DVec3::new(i as f64, (i * i) as f64, (i * i * i % 7) as f64)).collect();
        PolyMesh::from_triangles(positions, tris)
    }

    fn report(m: &PolyMesh) -> TopologyReport {
        TopologyReport::new(m, DEFAULT_DEGENERATE_TOLERANCE)
    }

    const TETRA: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

    fn tetra() -> PolyMesh {
        PolyMesh::from_triangles(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], &TETRA)
    }

    /// An `n × m` torus of triangles (vertex (i, j) = i·m + j).
    fn torus(n: u32, m: u32) -> PolyMesh {
        let mut positions = Vec::new();
        for i in 0..n {
            for j in 0..m {
                let (u, v) = (i as f64 / n as f64 * std::f64::consts::TAU, j as f64 / m as f64 * std::f64::consts::TAU);
                let r = 2.0 + 0.5 * v.cos();
                positions.push(DVec3::new(r * u.cos(), r * u.sin(), 0.5 * v.sin()));
            }
        }
        let id = |i: u32, j: u32| (i % n) * m + (j % m);
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..m {
                tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        PolyMesh::from_triangles(positions, &tris)
    }

    /// An open `n × n`-vertex grid of triangles in the xy-plane, facing +z.
    fn grid(n: u32) -> PolyMesh {
        let positions = (0..n * n).map(|k| DVec3::new((k % n) as f64, (k / n) as f64, 0.0)).collect();
        let id = |x: u32, y: u32| y * n + x;
        let mut tris = Vec::new();
        for y in 0..n - 1 {
            for x in 0..n - 1 {
                tris.push([id(x, y), id(x + 1, y), id(x + 1, y + 1)]);
                tris.push([id(x, y), id(x + 1, y + 1), id(x, y + 1)]);
            }
        }
        PolyMesh::from_triangles(positions, &tris)
    }

    /// A Möbius strip of `n` quads: bottom vertices `0..n`, top `n..2n`; the last quad joins
    /// the ends with a half twist.
    fn mobius(n: u32) -> PolyMesh {
        let mut m = PolyMesh::default();
        for i in 0..n {
            let a = i as f64 / n as f64 * std::f64::consts::PI;
            let (c, s) = (2.0 * a).sin_cos();
            m.positions.push(DVec3::new(c, s, -0.3 + 0.01 * i as f64));
        }
        for i in 0..n {
            let a = i as f64 / n as f64 * std::f64::consts::PI;
            let (c, s) = (2.0 * a).sin_cos();
            m.positions.push(DVec3::new(1.3 * c, 1.3 * s, 0.3 + 0.01 * i as f64));
        }
        let (b, t) = (|i: u32| i, |i: u32| n + i);
        for i in 0..n - 1 {
            m.face_vertices.extend([b(i), b(i + 1), t(i + 1), t(i)]);
            m.face_offsets.push(m.face_vertices.len() as u32);
        }
        m.face_vertices.extend([b(n - 1), t(0), b(0), t(n - 1)]);
        m.face_offsets.push(m.face_vertices.len() as u32);
        m
    }

    #[track_caller]
    fn assert_clean_manifold(r: &TopologyReport) {
        assert!(r.is_clean(), "expected a clean report:\n{r}");
        assert!(r.components.iter().all(|c| c.manifold && c.orientable && c.consistently_oriented), "{r}");
    }

    #[test]
    fn tetrahedron_is_a_sphere() {
        let r = report(&tetra());
        assert_clean_manifold(&r);
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (4, 6, 4));
        assert_eq!((r.euler_characteristic, r.genus()), (2, Some(0)));
        assert!(r.is_closed() && r.boundary_loops.is_empty());
        assert_eq!(r.components.len(), 1);
        assert_eq!(r.face_component, vec![0; 4]);
        assert!(r.to_string().contains("problems: none"), "{r}");
    }

    #[test]
    fn torus_has_genus_one() {
        let r = report(&torus(8, 5));
        assert_clean_manifold(&r);
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (40, 120, 80));
        assert_eq!((r.euler_characteristic, r.genus()), (0, Some(1)));
        assert!(r.is_closed());
    }

    #[test]
    fn open_grid_has_one_boundary_loop() {
        let r = report(&grid(5));
        assert_clean_manifold(&r);
        assert_eq!(r.euler_characteristic, 1);
        assert_eq!(r.genus(), Some(0));
        assert_eq!(r.num_boundary_edges, 16);
        assert_eq!(r.boundary_loops.len(), 1);
        let l = &r.boundary_loops[0];
        assert!(l.closed);
        assert_eq!(l.num_edges(), 16);
        // Counter-clockwise seen from +z (faces on the left): 0 → 1 → … along y = 0.
        assert_eq!(&l.vertices[..5], &[0, 1, 2, 3, 4]);
        assert_eq!(&l.vertices[5..8], &[9, 14, 19]);
        assert_eq!(r.components[0].num_boundary_loops, 1);
    }

    #[test]
    fn quads_and_polygons_count() {
        // A cube of quads: V 8, E 12, F 6.
        let mut m = PolyMesh {
            positions: (0..8).map(|k| DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64)).collect(),
            ..PolyMesh::default()
        };
        for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
            m.face_vertices.extend(q);
            m.face_offsets.push(m.face_vertices.len() as u32);
        }
        let r = report(&m);
        assert_clean_manifold(&r);
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces, r.euler_characteristic), (8, 12, 6, 2));
        assert_eq!(r.genus(), Some(0));
    }

    #[test]
    fn three_faces_on_an_edge() {
        let m = mesh(5, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
        let r = report(&m);
        assert_eq!(r.nonmanifold_edges, vec![NonManifoldEdge { a: 0, b: 1, faces: vec![0, 1, 2] }]);
        // Its ends are named by the edge, not as pinch vertices.
        assert!(r.nonmanifold_vertices.is_empty());
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (5, 7, 3));
        assert!(!r.is_manifold() && !r.components[0].manifold && r.genus().is_none());
        let text = r.to_string();
        assert!(text.contains("non-manifold edges (1):\n    edge 0–1: faces 0, 1, 2\n"), "{text}");

        let (s, what) = split_nonmanifold(&m);
        let r = report(&s);
        assert_clean_manifold(&r);
        // Faces 0 and 1 stay joined along 0–1 (opposite directions); face 2 is detached.
        assert_eq!(s.face(0), &[0, 1, 2]);
        assert_eq!(s.face(1), &[1, 0, 3]);
        assert_eq!(s.face(2), &[5, 6, 4]);
        assert_eq!(what.split_vertices, vec![0, 1]);
        assert_eq!(what.vertex_origin, vec![0, 1, 2, 3, 4, 0, 1]);
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (7, 8, 3));
        assert_eq!((r.components.len(), r.euler_characteristic, r.genus()), (2, 2, Some(0)));
        assert_eq!(r.boundary_loops.len(), 2);
        assert_eq!(s.positions[5], m.positions[0]);
    }

    #[test]
    fn bowtie_vertex() {
        let mut m = mesh(5, &[[0, 1, 2], [0, 3, 4]]);
        m.colors = (0..5).map(|i| DVec3::splat(i as f64 / 4.0)).collect();
        let r = report(&m);
        assert_eq!(r.nonmanifold_vertices, vec![NonManifoldVertex { vertex: 0, fans: 2 }]);
        assert!(r.nonmanifold_edges.is_empty());
        assert_eq!(r.components.len(), 1);
        // Two triangles sharing a vertex: the boundary is two loops of 3.
        assert_eq!(r.boundary_loops.iter().map(BoundaryLoop::num_edges).collect::<Vec<_>>(), vec![3, 3]);
        assert!(r.to_string().contains("vertex 0: 2 fans"));

        let (s, what) = split_nonmanifold(&m);
        assert_eq!(s.face(1), &[5, 3, 4]);
        assert_eq!(s.colors.len(), 6);
        assert_eq!(s.colors[5], m.colors[0]);
        assert_eq!(what.num_new_vertices(), 1);
        let r = report(&s);
        assert_clean_manifold(&r);
        assert_eq!((r.components.len(), r.euler_characteristic, r.genus()), (2, 2, Some(0)));
    }

    #[test]
    fn two_cones_touching_at_their_tips() {
        // Two closed tetrahedra sharing vertex 0.
        let mut tris = TETRA.to_vec();
        let map = [0, 4, 5, 6];
        tris.extend(TETRA.iter().map(|t| t.map(|v| map[v as usize])));
        let m = mesh(7, &tris);
        let r = report(&m);
        assert_eq!(r.nonmanifold_vertices, vec![NonManifoldVertex { vertex: 0, fans: 2 }]);
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces, r.euler_characteristic), (7, 12, 8, 3));
        assert_eq!(r.components.len(), 1);
        assert!(r.is_closed());
        assert_eq!(r.genus(), None);

        let (s, what) = split_nonmanifold(&m);
        assert_eq!(what.split_vertices, vec![0]);
        assert!(what.flipped_faces.is_empty());
        let r = report(&s);
        assert_clean_manifold(&r);
        assert_eq!((r.num_vertices, r.euler_characteristic, r.components.len(), r.genus()), (8, 4, 2, Some(0)));
        assert!(r.components.iter().all(|c| c.euler_characteristic == 2 && c.genus == Some(0)));
    }

    #[test]
    fn mobius_strip_is_not_orientable() {
        let n = 6;
        let m = mobius(n);
        let r = report(&m);
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (12, 18, 6));
        assert_eq!(r.euler_characteristic, 0);
        // The twist: bottom 0 and top 6 are joined by quad 0 and quad 5 in the same direction.
        assert_eq!(r.inconsistent_edges, vec![InconsistentEdge { a: 6, b: 0, faces: [0, 5] }]);
        assert!(!r.components[0].orientable && r.components[0].manifold);
        assert!(r.misoriented_faces.is_empty());
        assert_eq!(r.genus(), None);
        // One boundary curve, twice as long as the strip.
        assert_eq!(r.boundary_loops.len(), 1);
        assert_eq!(r.boundary_loops[0].num_edges(), 12);
        assert!(r.to_string().contains("non-orientable (1 cross-caps)"), "{r}");

        // Split: cut open along the twist edge into a disk.
        let (s, what) = split_nonmanifold(&m);
        assert_eq!(what.split_vertices, vec![0, 6]);
        let r = report(&s);
        assert_clean_manifold(&r);
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (14, 19, 6));
        assert_eq!((r.euler_characteristic, r.genus()), (1, Some(0)));
        assert_eq!(r.boundary_loops.len(), 1);
        assert_eq!(r.boundary_loops[0].num_edges(), 14);
    }

    #[test]
    fn tetrahedron_with_a_flipped_face() {
        let mut m = tetra();
        m.face_vertices[9..12].copy_from_slice(&[1, 3, 2]);
        let r = report(&m);
        assert_eq!(
            r.inconsistent_edges,
            vec![
                InconsistentEdge { a: 2, b: 1, faces: [0, 3] },
                InconsistentEdge { a: 1, b: 3, faces: [1, 3] },
                InconsistentEdge { a: 3, b: 2, faces: [2, 3] },
            ]
        );
        assert_eq!(r.misoriented_faces, vec![3]);
        assert!(r.nonmanifold_vertices.is_empty() && r.nonmanifold_edges.is_empty());
        assert!(r.components[0].orientable && !r.components[0].consistently_oriented);
        // Topologically still a sphere: closed, χ 2, genus 0.
        assert!(r.is_closed());
        assert_eq!((r.euler_characteristic, r.genus()), (2, Some(0)));
        let text = r.to_string();
        assert!(text.contains("edge 1→3: faces 1 and 3 both run this way"), "{text}");
        assert!(text.contains("faces to flip for a consistent orientation (1): 3"), "{text}");

        let (s, what) = split_nonmanifold(&m);
        assert_eq!(what.flipped_faces, vec![3]);
        assert!(what.split_vertices.is_empty());
        assert_eq!(s.face(3), &[1, 2, 3]);
        assert_clean_manifold(&report(&s));
    }

    #[test]
    fn flips_carry_face_varying_indices() {
        let mut m = tetra();
        m.face_vertices[9..12].copy_from_slice(&[1, 3, 2]);
        let indices: Vec<u32> = (0..12).collect();
        m.uvs = Some(FaceVarying { values: vec![glam::DVec2::ZERO; 12], indices: indices.clone() });
        m.normals = Some(FaceVarying { values: vec![DVec3::Z; 12], indices });
        let (s, _) = split_nonmanifold(&m);
        assert_eq!(&s.uvs.as_ref().unwrap().indices[9..], &[9, 11, 10]);
        assert_eq!(&s.normals.as_ref().unwrap().indices[9..], &[9, 11, 10]);
    }

    #[test]
    fn degenerate_duplicate_and_broken_faces() {
        let mut m = tetra();
        m.positions.push(DVec3::new(2.0, 0.0, 0.0)); // 4: on the line of 0 and 1
        m.positions.push(DVec3::new(f64::NAN, 0.0, 0.0)); // 5: unreferenced, non-finite
        m.positions.push(DVec3::ONE); // 6: unreferenced
        let mut add = |face: &[u32]| {
            m.face_vertices.extend_from_slice(face);
            m.face_offsets.push(m.face_vertices.len() as u32);
        };
        add(&[0, 1, 4]); // 4: zero area
        add(&[0, 0, 2]); // 5: repeated vertex
        add(&[2, 1, 0]); // 6: same set as face 0
        add(&[1, 2]); // 7: short
        add(&[0, 1, 9]); // 8: index out of range
        add(&[3, 2, 1]); // 9: same set as face 3
        let r = report(&m);
        assert_eq!(
            r.degenerate_faces,
            vec![
                DegenerateFace { face: 4, kind: Degeneracy::ZeroArea },
                DegenerateFace { face: 5, kind: Degeneracy::RepeatedVertex { vertex: 0 } },
            ]
        );
        assert_eq!(r.duplicate_faces, vec![DuplicateFace { face: 6, first: 0 }, DuplicateFace { face: 9, first: 3 }]);
        assert_eq!(r.short_faces, vec![ShortFace { face: 7, len: 2 }]);
        assert_eq!(r.invalid_indices, vec![InvalidIndex { face: 8, vertex: 9 }]);
        assert_eq!(r.unreferenced_vertices, vec![5, 6]);
        assert_eq!(r.nonfinite_vertices, vec![5]);
        // Left out: faces 5, 7, 8.
        assert_eq!(r.num_faces, 7);
        assert_eq!(r.face_component[5], NONE);
        assert_eq!(r.face_component[4], 0);
        // Split removes the face with a bad index (which would otherwise come to name a new
        // vertex), and leaves the other left-out faces as they are.
        let (s, what) = split_nonmanifold(&m);
        assert_eq!(what.removed_faces, vec![8]);
        assert_eq!(s.num_faces(), 9);
        assert_eq!(s.face(7), &[1, 2]);
        assert_eq!(s.face(5), &[0, 0, 2]);
        let r = report(&s);
        assert!(r.is_manifold() && r.is_consistently_oriented() && r.invalid_indices.is_empty(), "{r}");
        let text = report(&m).to_string();
        for needle in [
            "face 4: zero area",
            "face 5: vertex 0 repeated",
            "face 6: same vertices as face 0",
            "face 7: 2 vertices",
            "face 8: vertex 9",
            "unreferenced vertices (2): 5, 6",
            "vertices with a non-finite coordinate (1): 5",
        ] {
            assert!(text.contains(needle), "{needle:?} missing in\n{text}");
        }
    }

    #[test]
    fn zero_area_tolerance_is_a_distance() {
        // A sliver of height 1e-3 over a longest edge of length 2.
        let m = PolyMesh::from_triangles(
            vec![DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(1.0, 1e-3, 0.0)],
            &[[0, 1, 2]],
        );
        assert!(TopologyReport::new(&m, 0.0).degenerate_faces.is_empty());
        assert!(TopologyReport::new(&m, 0.9e-3).degenerate_faces.is_empty());
        assert_eq!(TopologyReport::new(&m, 1.1e-3).degenerate_faces.len(), 1);
        // Coincident corners are degenerate at any tolerance.
        let m = PolyMesh::from_triangles(vec![DVec3::ONE; 3], &[[0, 1, 2]]);
        assert_eq!(TopologyReport::new(&m, 0.0).degenerate_faces.len(), 1);
    }

    #[test]
    fn listing_caps_long_lists() {
        // 30 separate triangles sharing vertex 0: one pinch vertex, 29 unreferenced vertices.
        let mut tris = Vec::new();
        for k in 0..30 {
            tris.push([0, 1 + 2 * k, 2 + 2 * k]);
        }
        let mut m = mesh(61 + 29, &tris);
        m.positions.truncate(61 + 29);
        let r = report(&m);
        assert_eq!(r.unreferenced_vertices.len(), 29);
        let text = r.to_string();
        assert!(
            text.contains("unreferenced vertices (29): 61, 62, 63, 64, 65, 66, 67, 68, 69, 70, … and 19 more"),
            "{text}"
        );
        assert!(r.display_listing(100).to_string().contains(", 89\n"));
    }

    #[test]
    fn reuses_an_adjacency() {
        let m = torus(4, 3);
        let adj = Adjacency::build(&m);
        assert_eq!(TopologyReport::with_adjacency(&m, &adj, 0.0), report(&m));
    }

    #[test]
    fn empty_mesh() {
        let r = report(&PolyMesh::default());
        assert!(r.is_clean() && !r.is_closed());
        assert_eq!((r.num_vertices, r.num_edges, r.num_faces, r.euler_characteristic), (0, 0, 0, 0));
        assert_eq!(r.genus(), Some(0));
        let (s, what) = split_nonmanifold(&PolyMesh::default());
        assert!(what.is_unchanged() && s.num_faces() == 0);
    }

    #[test]
    fn four_faces_on_an_edge_pair_up() {
        // Two "books" of two pages each along edge 0–1, opposite directions paired.
        let m = mesh(6, &[[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 0, 5]]);
        let r = report(&m);
        assert_eq!(r.nonmanifold_edges[0].faces, vec![0, 1, 2, 3]);
        let (s, what) = split_nonmanifold(&m);
        let r = report(&s);
        assert_clean_manifold(&r);
        assert_eq!(what.num_new_vertices(), 2);
        assert_eq!(s.face(0), &[0, 1, 2]);
        assert_eq!(s.face(1), &[1, 0, 3]);
        assert_eq!(s.face(2), &[6, 7, 4]);
        assert_eq!(s.face(3), &[7, 6, 5]);
    }

    mod properties {
        use proptest::prelude::*;

        use super::*;

        /// Triangles with distinct corners over `n` vertices.
        fn soup() -> impl Strategy<Value = (usize, Vec<[u32; 3]>)> {
            (3..9usize).prop_flat_map(|n| {
                let tri = Just((0..n as u32).collect::<Vec<_>>()).prop_shuffle().prop_map(|v| [v[0], v[1], v[2]]);
                (Just(n), proptest::collection::vec(tri, 1..24))
            })
        }

        proptest! {
            #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

            /// Whatever the soup, the split is manifold and consistently oriented, keeps the
            /// faces and copies positions from the recorded origins; the report's counts add up.
            #[test]
            fn split_is_always_clean((n, tris) in soup()) {
                let m = mesh(n, &tris);
                let r = report(&m);
                prop_assert_eq!(r.components.iter().map(|c| c.euler_characteristic).sum::<i64>(), r.euler_characteristic);
                prop_assert_eq!(r.components.iter().map(|c| c.num_faces).sum::<usize>(), r.num_faces);
                prop_assert_eq!(r.boundary_loops.iter().map(BoundaryLoop::num_edges).sum::<usize>(), r.num_boundary_edges);
                let (s, what) = split_nonmanifold(&m);
                let after = report(&s);
                prop_assert!(after.is_manifold() && after.is_consistently_oriented(), "{}\n{:?}", after, tris);
                prop_assert!(after.boundary_loops.iter().all(|l| l.closed), "{}", after);
                prop_assert!(after.components.iter().all(|c| c.genus.is_some()), "{}", after);
                prop_assert_eq!(s.num_faces(), m.num_faces());
                prop_assert_eq!(what.vertex_origin.len(), s.num_vertices());
                for (v, &o) in what.vertex_origin.iter().enumerate() {
                    prop_assert_eq!(s.positions[v], m.positions[o as usize]);
                }
                // Each output face is an input face (up to flipping) through the origins.
                for f in 0..m.num_faces() {
                    let mut a: Vec<u32> = s.face(f).iter().map(|&v| what.vertex_origin[v as usize]).collect();
                    let mut b = m.face(f).to_vec();
                    a.sort_unstable();
                    b.sort_unstable();
                    prop_assert_eq!(a, b);
                }
                // A clean mesh is a fixed point.
                let (again, what2) = split_nonmanifold(&s);
                prop_assert!(what2.is_unchanged());
                prop_assert_eq!(again, s);
            }
        }
    }
}
