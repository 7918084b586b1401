//! Finding what is wrong: [`TopologyReport::new`] checks each face and vertex on its own
//! (the scan), then analyses the faces that qualify through their [`Adjacency`]: edges, fans,
//! components, orientation and boundary loops.

use std::hash::{DefaultHasher, Hash, Hasher};

use glam::DVec3;

use super::faces::{Edges, Kept, Orientation, UnionFind, join_across};
use super::report::{
    BoundaryLoop, Component, Degeneracy, DegenerateFace, DuplicateFace, InvalidIndex, ShortFace, TopologyReport,
};
use crate::mesh::{Adjacency, NONE, NonManifold, PolyMesh};

impl TopologyReport {
    /// Analyses `mesh` (it builds its own [`Adjacency`]).
    ///
    /// `tolerance` (a distance, ≥ 0) decides which faces are degenerate by area: a face is
    /// [`ZeroArea`](Degeneracy::ZeroArea) when `2·A / L ≤ tolerance`, where `A` is the length
    /// of its vector area (Newell's formula, half the norm of `Σ (pᵢ − p₀) × (pᵢ₊₁ − p₀)`)
    /// and `L` its longest edge, or when all its corners coincide. For a triangle, `2A/L` is
    /// its smallest height: the face is degenerate when it lies within `tolerance` of a line.
    /// [`DEFAULT_DEGENERATE_TOLERANCE`](super::DEFAULT_DEGENERATE_TOLERANCE) (0) flags only
    /// exactly zero areas. Faces with a non-finite corner are not measured.
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

        // Problems found while pairing half-edges, with the adjacency's faces renumbered as
        // the mesh's.
        let mut nonmanifold_edges = Vec::new();
        let mut inconsistent_edges = Vec::new();
        let mut on_nonmanifold_edge = vec![false; nv];
        for p in &adj.nonmanifold {
            match *p {
                NonManifold::Edge { a, b, ref faces } => {
                    let mut faces: Vec<u32> = faces.iter().map(|&f| mesh_face(f)).collect();
                    faces.sort_unstable();
                    faces.dedup();
                    on_nonmanifold_edge[a as usize] = true;
                    on_nonmanifold_edge[b as usize] = true;
                    nonmanifold_edges.push(((a, b), NonManifold::Edge { a, b, faces }));
                }
                NonManifold::Inconsistent { a, b, faces } => {
                    let mut faces = faces.map(mesh_face);
                    faces.sort_unstable();
                    inconsistent_edges.push(((a.min(b), a.max(b)), NonManifold::Inconsistent { a, b, faces }));
                }
                NonManifold::Vertex { .. } => {}
            }
        }
        nonmanifold_edges.sort_by_key(|e| e.0);
        inconsistent_edges.sort_by_key(|e| e.0);

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
                nonmanifold_vertices.push(NonManifold::Vertex { vertex: v, fans: roots.len() as u32 });
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
        let nonmanifold: Vec<NonManifold> = nonmanifold_edges
            .into_iter()
            .map(|e| e.1)
            .chain(nonmanifold_vertices)
            .chain(inconsistent_edges.into_iter().map(|e| e.1))
            .collect();
        for p in &nonmanifold {
            let (v, manifold) = match p {
                NonManifold::Edge { a, .. } => (*a, true),
                NonManifold::Vertex { vertex, .. } => (*vertex, true),
                NonManifold::Inconsistent { a, .. } => (*a, false),
            };
            let comp = &mut components[vertex_component(v, &mut vertex_sets) as usize];
            if manifold {
                comp.manifold = false;
            } else {
                comp.consistently_oriented = false;
            }
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
            nonmanifold,
            misoriented_faces,
            degenerate_faces: scan.degenerate_faces,
            duplicate_faces,
            unreferenced_vertices: scan.unreferenced_vertices,
            short_faces: scan.short_faces,
            invalid_indices: scan.invalid_indices,
            nonfinite_vertices: scan.nonfinite_vertices,
        }
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
pub(super) struct Scan {
    /// Per face: analysed (≥ 3 corners, indices in range, no repeated vertex).
    pub(super) keep: Vec<bool>,
    /// Per face: ≥ 3 corners and indices in range (compared for duplicates).
    pub(super) valid: Vec<bool>,
    pub(super) short_faces: Vec<ShortFace>,
    pub(super) invalid_indices: Vec<InvalidIndex>,
    pub(super) degenerate_faces: Vec<DegenerateFace>,
    pub(super) nonfinite_vertices: Vec<u32>,
    pub(super) unreferenced_vertices: Vec<u32>,
}

impl Scan {
    pub(super) fn new(mesh: &PolyMesh, tolerance: f64, measure: bool) -> Self {
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
