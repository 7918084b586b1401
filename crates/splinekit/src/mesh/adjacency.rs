//! Edge adjacency of a polygon mesh: for every edge of every face, the neighbouring face's
//! edge across it, or "boundary" (the neighbour-face / neighbour-edge tables, in
//! half-edge form).
//!
//! Half-edges are *corners*: corner `c` of [`PolyMesh::face_vertices`] is the half-edge from
//! its vertex to the next corner's vertex of the same face. [`Adjacency::twin`] gives, per
//! corner, the corner of the neighbouring face that runs along the same edge the other way
//! (so `face_of(twin[c])` is the neighbour face and the twin's position in that face is the
//! neighbour's edge), or [`NONE`] on a boundary.
//!
//! Only *manifold, consistently oriented* edges are paired: an edge used by exactly two
//! faces in opposite directions. Every other edge is left unpaired in [`Adjacency::twin`] and
//! reported in [`Adjacency::nonmanifold`]: an edge used by more than two faces
//! ([`NonManifold::Edge`]), or by two faces in the same direction (inconsistent orientation,
//! [`NonManifold::Inconsistent`]); [`Adjacency::sides`] gives its half-edges.
//!
//! Cost: `O(corners · valence)` time, no hashing; deterministic.

use super::{NonManifold, PolyMesh};

/// "No such corner": a boundary half-edge's twin, an isolated vertex's first corner.
pub const NONE: u32 = u32::MAX;

/// Half-edge adjacency of a [`PolyMesh`] (see the module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Adjacency {
    /// Per corner: the face the corner belongs to.
    pub face_of: Vec<u32>,
    /// Per corner: the twin half-edge (a corner of the neighbouring face), or [`NONE`].
    pub twin: Vec<u32>,
    /// Per corner: the end vertex of its half-edge.
    pub to: Vec<u32>,
    /// Per corner: the edge it lies on, `0 .. num_edges`, numbered in corner order; a
    /// half-edge and its twin share an edge; unpaired half-edges get an edge each.
    pub edge_of: Vec<u32>,
    /// Per edge: the first corner (in corner order) along it.
    pub edge_corner: Vec<u32>,
    /// Per vertex: the corners whose half-edge starts there (CSR offsets into
    /// [`Self::vertex_corners`]).
    pub vertex_offsets: Vec<u32>,
    /// Corners grouped by start vertex, ascending within each vertex.
    pub vertex_corners: Vec<u32>,
    /// Edges that could not be paired, in corner order of their first half-edge:
    /// [`NonManifold::Edge`] and [`NonManifold::Inconsistent`], their faces numbered as here
    /// (ascending; [`Self::sides`] gives the half-edges).
    pub nonmanifold: Vec<NonManifold>,
}

impl Adjacency {
    /// Pairs the half-edges of `mesh`. Vertex indices must be in range (a reader checks them).
    #[must_use]
    pub fn build(mesh: &PolyMesh) -> Self {
        Self::from_faces(&mesh.face_offsets, &mesh.face_vertices, mesh.num_vertices())
    }

    /// [`Self::build`] from the raw face arrays.
    #[must_use]
    pub fn from_faces(face_offsets: &[u32], face_vertices: &[u32], num_vertices: usize) -> Self {
        let nc = face_vertices.len();
        let mut face_of = vec![0u32; nc];
        let mut to = vec![0u32; nc];
        for (f, w) in face_offsets.windows(2).enumerate() {
            let (s, e) = (w[0] as usize, w[1] as usize);
            for c in s..e {
                face_of[c] = f as u32;
                to[c] = face_vertices[if c + 1 == e { s } else { c + 1 }];
            }
        }
        // Corners grouped by start vertex (counting sort: stable, so ascending).
        let mut vertex_offsets = vec![0u32; num_vertices + 1];
        for &v in face_vertices {
            vertex_offsets[v as usize + 1] += 1;
        }
        for v in 0..num_vertices {
            vertex_offsets[v + 1] += vertex_offsets[v];
        }
        let mut fill = vertex_offsets.clone();
        let mut vertex_corners = vec![0u32; nc];
        for (c, &v) in face_vertices.iter().enumerate() {
            vertex_corners[fill[v as usize] as usize] = c as u32;
            fill[v as usize] += 1;
        }
        let out =
            |v: u32| &vertex_corners[vertex_offsets[v as usize] as usize..vertex_offsets[v as usize + 1] as usize];

        let mut twin = vec![NONE; nc];
        let mut edge_of = vec![NONE; nc];
        let mut edge_corner = Vec::with_capacity(nc / 2 + 1);
        let mut nonmanifold = Vec::new();
        for c in 0..nc {
            if edge_of[c] != NONE {
                continue;
            }
            let (a, b) = (face_vertices[c], to[c]);
            let e = edge_corner.len() as u32;
            edge_corner.push(c as u32);
            let same = out(a).iter().filter(|&&d| to[d as usize] == b);
            let reverse = out(b).iter().filter(|&&d| to[d as usize] == a);
            // one walk over each fan: how many half-edges run a -> b and b -> a, and the first
            // of the latter
            let n_same = same.clone().count();
            let (mut n_rev, mut first_rev) = (0, NONE);
            for &d in reverse.clone() {
                if n_rev == 0 {
                    first_rev = d;
                }
                n_rev += 1;
            }
            if n_same == 1 && n_rev <= 1 {
                edge_of[c] = e;
                if first_rev != NONE {
                    let d = first_rev;
                    twin[c] = d;
                    twin[d as usize] = c as u32;
                    edge_of[d as usize] = e;
                }
                continue;
            }
            // A problem edge: every half-edge along it stays unpaired, each its own edge.
            let mut corners: Vec<u32> = same.chain(reverse).copied().collect();
            corners.sort_unstable();
            let faces: Vec<u32> = corners.iter().map(|&d| face_of[d as usize]).collect();
            if n_same == 2 && n_rev == 0 {
                nonmanifold.push(NonManifold::Inconsistent { a, b, faces: [faces[0], faces[1]] });
            } else {
                nonmanifold.push(NonManifold::Edge { a: a.min(b), b: a.max(b), faces });
            }
            edge_of[c] = e;
            for &d in &corners[1..] {
                edge_of[d as usize] = edge_corner.len() as u32;
                edge_corner.push(d);
            }
        }
        // Renumber edges in corner order of their first corner (they already are: an edge is
        // created at its smallest corner, except the extra edges of problem edges).
        Self { face_of, twin, to, edge_of, edge_corner, vertex_offsets, vertex_corners, nonmanifold }
    }

    /// Number of edges.
    #[must_use]
    pub fn num_edges(&self) -> usize {
        self.edge_corner.len()
    }

    /// Number of boundary half-edges (edges used by one face side).
    #[must_use]
    pub fn num_boundary_edges(&self) -> usize {
        self.twin.iter().filter(|&&t| t == NONE).count()
    }

    /// The corners starting at vertex `v`.
    #[must_use]
    pub fn corners_of(&self, v: u32) -> &[u32] {
        &self.vertex_corners[self.vertex_offsets[v as usize] as usize..self.vertex_offsets[v as usize + 1] as usize]
    }

    /// The half-edges along the undirected edge `{a, b}` (the corners running `a → b` or
    /// `b → a`), ascending: the sides of a [`NonManifold::Edge`] or
    /// [`NonManifold::Inconsistent`] edge of [`Self::nonmanifold`].
    #[must_use]
    pub fn sides(&self, a: u32, b: u32) -> Vec<u32> {
        let along =
            |from: u32, to: u32| self.corners_of(from).iter().copied().filter(move |&c| self.to[c as usize] == to);
        let mut sides: Vec<u32> = along(a, b).chain(along(b, a)).collect();
        sides.sort_unstable();
        sides
    }

    /// The corner before `c` in its face (its half-edge ends where `c`'s starts).
    #[must_use]
    pub fn prev(&self, mesh: &PolyMesh, c: u32) -> u32 {
        let f = self.face_of[c as usize] as usize;
        if c == mesh.face_offsets[f] { mesh.face_offsets[f + 1] - 1 } else { c - 1 }
    }

    /// The vertices whose corners do not form a single fan (a disc or half-disc) through
    /// paired edges, as [`NonManifold::Vertex`] with their number of [`Self::fans`],
    /// ascending. Vertices with no faces are not included.
    #[must_use]
    pub fn nonmanifold_vertices(&self, mesh: &PolyMesh) -> Vec<NonManifold> {
        (0..mesh.num_vertices() as u32)
            .filter_map(|vertex| {
                let fans = self.fans(mesh, vertex).len();
                (fans > 1).then_some(NonManifold::Vertex { vertex, fans: fans as u32 })
            })
            .collect()
    }

    /// The fans around vertex `v`: maximal runs of its corners joined through paired edges,
    /// each listed in rotation order from a boundary (or, for a closed fan, from its smallest
    /// corner). A manifold vertex has at most one.
    #[must_use]
    pub fn fans(&self, mesh: &PolyMesh, v: u32) -> Vec<Vec<u32>> {
        let corners = self.corners_of(v);
        let mut seen = vec![false; corners.len()];
        let index = |c: u32| corners.binary_search(&c).ok();
        let mut fans = Vec::new();
        // Start from corners that begin a fan (their own half-edge is unpaired), then closed
        // fans from the smallest unseen corner.
        let starts: Vec<u32> =
            corners.iter().copied().filter(|&c| self.twin[c as usize] == NONE).chain(corners.iter().copied()).collect();
        for start in starts {
            let Some(k) = index(start) else { continue };
            if seen[k] {
                continue;
            }
            let mut fan = Vec::new();
            let mut c = start;
            while let Some(k) = index(c) {
                if seen[k] {
                    break;
                }
                seen[k] = true;
                fan.push(c);
                let t = self.twin[self.prev(mesh, c) as usize];
                if t == NONE {
                    break;
                }
                c = t;
            }
            fans.push(fan);
        }
        fans
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    fn mesh(n: usize, tris: &[[u32; 3]]) -> PolyMesh {
        PolyMesh::from_triangles(vec![DVec3::ZERO; n], tris)
    }

    #[test]
    fn tetrahedron_is_closed() {
        let m = mesh(4, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]);
        let a = Adjacency::build(&m);
        assert!(a.nonmanifold.is_empty());
        assert_eq!(a.num_edges(), 6);
        assert_eq!(a.num_boundary_edges(), 0);
        for c in 0..12u32 {
            let t = a.twin[c as usize];
            assert_eq!(a.twin[t as usize], c);
            assert_eq!(a.to[c as usize], m.face_vertices[t as usize]);
            assert_eq!(a.edge_of[c as usize], a.edge_of[t as usize]);
        }
        assert!(a.nonmanifold_vertices(&m).is_empty());
    }

    #[test]
    fn problems_are_reported() {
        // Three triangles on edge {0,1}: non-manifold.
        let m = mesh(5, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
        let a = Adjacency::build(&m);
        assert_eq!(a.nonmanifold, vec![NonManifold::Edge { a: 0, b: 1, faces: vec![0, 1, 2] }]);
        assert_eq!(a.sides(0, 1), vec![0, 3, 6]);
        assert_eq!(a.sides(1, 0), vec![0, 3, 6]);
        // Two triangles using 0→1 in the same direction.
        let m = mesh(4, &[[0, 1, 2], [0, 1, 3]]);
        let a = Adjacency::build(&m);
        assert_eq!(a.nonmanifold, vec![NonManifold::Inconsistent { a: 0, b: 1, faces: [0, 1] }]);
        assert_eq!(a.sides(0, 1), vec![0, 3]);
        assert_eq!(a.num_boundary_edges(), 6);
    }

    #[test]
    fn bowtie_vertex_has_two_fans() {
        let m = mesh(5, &[[0, 1, 2], [0, 3, 4]]);
        let a = Adjacency::build(&m);
        assert_eq!(a.nonmanifold_vertices(&m), vec![NonManifold::Vertex { vertex: 0, fans: 2 }]);
        assert_eq!(a.fans(&m, 0).len(), 2);
        // A quad and a triangle sharing an edge.
        let mut q = PolyMesh::from_triangles(vec![DVec3::ZERO; 5], &[[1, 4, 2]]);
        q.face_vertices.splice(0..0, [0, 1, 2, 3]);
        q.face_offsets = vec![0, 4, 7];
        let a = Adjacency::build(&q);
        assert_eq!(a.num_edges(), 6);
        assert_eq!(a.twin[1], 6);
        assert_eq!(a.face_of[6], 1);
    }
}
