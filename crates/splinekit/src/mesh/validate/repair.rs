//! The repair: [`split_nonmanifold`] orients each component consistently where it can and
//! splits non-manifold edges and vertices, and [`SplitReport`] says what it changed.

use super::faces::{Edges, Kept, Orientation, UnionFind, join_across};
use super::scan::Scan;
use crate::mesh::{Adjacency, FaceVarying, NONE, NonManifold, PolyMesh};

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
/// ([`TopologyReport::new`](super::TopologyReport::new) on it lists none). Faces naming a
/// vertex that does not exist are removed first (they could otherwise come to name one of
/// the new vertices); the other faces keep their order, and face-varying normal and UV values
/// and indices are kept (only reordered with flipped faces), so only `face_vertices`,
/// `positions` and `colors` change.
/// Faces with fewer than three corners or a repeated vertex are left as they are.
///
/// ```
/// use glam::DVec3;
/// use splinekit::mesh::{NonManifold, PolyMesh, TopologyReport, split_nonmanifold};
///
/// // A bowtie: two triangles sharing only vertex 0.
/// let mesh = PolyMesh::from_triangles(vec![DVec3::ZERO; 5], &[[0, 1, 2], [0, 3, 4]]);
/// assert_eq!(TopologyReport::new(&mesh, 0.0).nonmanifold, vec![NonManifold::Vertex { vertex: 0, fans: 2 }]);
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
            if adj.nonmanifold.is_empty() {
                break;
            }
            for p in &adj.nonmanifold {
                let corners = match *p {
                    NonManifold::Edge { a, b, .. } | NonManifold::Inconsistent { a, b, .. } => adj.sides(a, b),
                    NonManifold::Vertex { .. } => continue,
                };
                let anchor = corners.iter().copied().find(|&c| pairs[c as usize] != NONE).unwrap_or(corners[0]);
                for &d in &corners {
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
    for p in &adj.nonmanifold {
        if let NonManifold::Edge { a, b, .. } = *p {
            let corners = adj.sides(a, b);
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
