//! Triangle-mesh topology for subdivision, and its refinement in closed form.
//!
//! Half-edge `h = 3f + i` of triangle `f = [v0, v1, v2]` runs from `v_i` to `v_{i+1}`. A
//! level stores, per half-edge, its twin (or [`NONE`]) and its edge; per edge, an *owner*
//! half-edge; per vertex, a *start* half-edge leaving it — on a boundary, the boundary
//! half-edge leaving it, so that rotating `h → twin(prev(h))` visits the whole fan.
//!
//! One Loop step splits triangle `f` into `4f + k` (`c_i = [v_i, m_i, m_{i+2}]`,
//! `c_3 = [m0, m1, m2]`, `m_i` on the edge of `h_i`), and every table of the child level is
//! a closed-form function of the parent's tables at the same index: half-edge `h_i`'s two
//! halves are edge 0 of `c_i` and edge 2 of `c_{i+1}`; their twins are the other halves of
//! `twin(h_i)`; parent edge `e` becomes child edges `2e` (the owner's first half) and `2e + 1`;
//! the interior edge between `c_i` and `c_3` is `2E + 3f + i`. So no hashing or searching
//! happens after the base level, and every pass is a parallel map over faces, edges or
//! vertices.

use rayon::prelude::*;

use crate::mesh::{Adjacency, NONE};

/// Work items per rayon task (large, so that one thread runs at full speed).
pub(crate) const MIN_LEN: usize = 1 << 13;

/// The adjacency tables of one level (see the module docs).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Topology {
    /// Per half-edge: the twin half-edge, or [`NONE`] on a boundary.
    pub twin: Vec<u32>,
    /// Per half-edge: its edge.
    pub edge_of: Vec<u32>,
    /// Per edge: its owner half-edge (the one the edge's odd vertex is computed from).
    pub edge_owner: Vec<u32>,
    /// Per vertex: a half-edge leaving it (the boundary one on a boundary), or [`NONE`].
    pub vertex_start: Vec<u32>,
}

/// Why a triangle list cannot be given a manifold topology.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TopologyError {
    /// An edge is used by more than two triangles, or twice in the same direction.
    #[error("edge {a}–{b} is used by {faces:?}: not a manifold, consistently oriented edge")]
    Edge {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
        /// The faces along it.
        faces: Vec<u32>,
    },
    /// A vertex's triangles form several fans (e.g. two cones touching at their tips).
    #[error("vertex {vertex} is non-manifold: its faces form {fans} separate fans")]
    Vertex {
        /// The vertex.
        vertex: u32,
        /// Number of fans.
        fans: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {face} refers to vertex {vertex}, but there are {count} vertices")]
    Index {
        /// The triangle.
        face: u32,
        /// The vertex index.
        vertex: u32,
        /// Number of vertices.
        count: usize,
    },
}

#[inline]
fn next(i: u32) -> u32 {
    if i == 2 { 0 } else { i + 1 }
}

#[inline]
fn prev(i: u32) -> u32 {
    if i == 0 { 2 } else { i - 1 }
}

impl Topology {
    /// Number of vertices.
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.vertex_start.len()
    }

    /// Number of edges.
    #[must_use]
    pub fn num_edges(&self) -> usize {
        self.edge_owner.len()
    }

    /// The base level's topology of `triangles` over `num_vertices` vertices.
    ///
    /// # Errors
    /// The first non-manifold or inconsistently oriented edge, or non-manifold vertex.
    pub fn build(triangles: &[[u32; 3]], num_vertices: usize) -> Result<Self, TopologyError> {
        let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
        if let Some(c) = flat.iter().position(|&v| v as usize >= num_vertices) {
            return Err(TopologyError::Index { face: (c / 3) as u32, vertex: flat[c], count: num_vertices });
        }
        let offsets: Vec<u32> = (0..=triangles.len() as u32).map(|f| 3 * f).collect();
        let mut adj = Adjacency::from_faces(&offsets, &flat, num_vertices);
        if let Some(p) = adj.problems.first() {
            let (a, b, corners) = match p {
                crate::mesh::EdgeProblem::NonManifold { a, b, corners } => (*a, *b, corners.clone()),
                crate::mesh::EdgeProblem::Inconsistent { a, b, corners } => (*a, *b, corners.to_vec()),
            };
            return Err(TopologyError::Edge { a, b, faces: corners.iter().map(|c| c / 3).collect() });
        }
        // Adjacency numbers edges as `from_twins` does (in half-edge order, owned by their
        // first half-edge): take its tables instead of numbering again.
        let (edge_of, edge_owner) = (std::mem::take(&mut adj.edge_of), std::mem::take(&mut adj.edge_corner));
        let topo = Self::with_starts(triangles, adj.twin.clone(), edge_of, edge_owner, num_vertices);
        // Every corner of a vertex must be reached by rotating from its start.
        for (v, &h) in topo.vertex_start.iter().enumerate() {
            let reached = if h == NONE { 0 } else { topo.fan(h).count() as u32 };
            if reached != adj.vertex_offsets[v + 1] - adj.vertex_offsets[v] {
                let mesh = crate::mesh::PolyMesh {
                    face_offsets: offsets,
                    face_vertices: flat,
                    positions: vec![glam::DVec3::ZERO; num_vertices],
                    ..crate::mesh::PolyMesh::default()
                };
                return Err(TopologyError::Vertex { vertex: v as u32, fans: adj.fans(&mesh, v as u32).len() });
            }
        }
        Ok(topo)
    }

    /// Tables from a (manifold) twin table: edges numbered in half-edge order, each owned by
    /// its first half-edge; starts prefer boundary half-edges.
    pub(crate) fn from_twins(triangles: &[[u32; 3]], twin: Vec<u32>, num_vertices: usize) -> Self {
        let mut edge_of = vec![NONE; twin.len()];
        let mut edge_owner = Vec::with_capacity(twin.len() / 2 + 1);
        for h in 0..twin.len() {
            if edge_of[h] == NONE {
                let e = edge_owner.len() as u32;
                edge_owner.push(h as u32);
                edge_of[h] = e;
                if twin[h] != NONE {
                    edge_of[twin[h] as usize] = e;
                }
            }
        }
        Self::with_starts(triangles, twin, edge_of, edge_owner, num_vertices)
    }

    /// Tables from manifold twin and edge tables: starts prefer boundary half-edges.
    fn with_starts(
        triangles: &[[u32; 3]],
        twin: Vec<u32>,
        edge_of: Vec<u32>,
        edge_owner: Vec<u32>,
        num_vertices: usize,
    ) -> Self {
        let mut vertex_start = vec![NONE; num_vertices];
        for (f, t) in triangles.iter().enumerate() {
            for i in 0..3 {
                let h = 3 * f as u32 + i;
                let s = &mut vertex_start[t[i as usize] as usize];
                if *s == NONE || twin[h as usize] == NONE {
                    *s = h;
                }
            }
        }
        Self { twin, edge_of, edge_owner, vertex_start }
    }

    /// The half-edges leaving the start vertex of `h`, rotating `h → twin(prev(h))` until a
    /// boundary or back at `h`.
    pub(crate) fn fan(&self, start: u32) -> impl Iterator<Item = u32> + '_ {
        let mut h = start;
        let mut done = false;
        core::iter::from_fn(move || {
            if done {
                return None;
            }
            let out = h;
            let t = self.twin[(3 * (h / 3) + prev(h % 3)) as usize];
            if t == NONE || t == start {
                done = true;
            } else {
                h = t;
            }
            Some(out)
        })
    }

    /// The child level's triangles, and its tables when `with_topology` (they are needed only
    /// to refine further).
    pub(crate) fn refine(&self, triangles: &[[u32; 3]], with_topology: bool) -> (Vec<[u32; 3]>, Option<Self>) {
        let nv = self.num_vertices() as u32;
        let ne = self.num_edges();
        let mut child = vec![[0u32; 3]; 4 * triangles.len()];
        child.par_chunks_mut(4).with_min_len(MIN_LEN).zip(triangles.par_iter()).enumerate().for_each(
            |(f, (out, t))| {
                let e = &self.edge_of[3 * f..3 * f + 3];
                let m = [nv + e[0], nv + e[1], nv + e[2]];
                out[0] = [t[0], m[0], m[2]];
                out[1] = [t[1], m[1], m[0]];
                out[2] = [t[2], m[2], m[1]];
                out[3] = m;
            },
        );
        if !with_topology {
            return (child, None);
        }
        let nh = 3 * triangles.len();
        let mut twin = vec![0u32; 4 * nh];
        let mut edge_of = vec![0u32; 4 * nh];
        let owner_of = |h: usize| self.edge_owner[self.edge_of[h] as usize] == h as u32;
        twin.par_chunks_mut(12).zip(edge_of.par_chunks_mut(12)).with_min_len(MIN_LEN).enumerate().for_each(
            |(f, (tw, eo))| {
                let base = 4 * 3 * f as u32;
                let hh = |c: u32, k: u32| base + 3 * c + k;
                for i in 0..3u32 {
                    let h = 3 * f + i as usize;
                    let (first, second) = ((3 * i) as usize, (3 * next(i) + 2) as usize);
                    let t = self.twin[h];
                    if t == NONE {
                        tw[first] = NONE;
                        tw[second] = NONE;
                    } else {
                        let (g, j) = (t / 3, t % 3);
                        tw[first] = 12 * g + 3 * next(j) + 2;
                        tw[second] = 12 * g + 3 * j;
                    }
                    let e = 2 * self.edge_of[h];
                    let own = owner_of(h) as u32;
                    eo[first] = e + 1 - own;
                    eo[second] = e + own;
                    // Interior edge between c_i (edge 1) and c_3 (edge i + 2).
                    let (a, b) = ((3 * i + 1) as usize, (9 + prev(i)) as usize);
                    tw[a] = hh(3, prev(i));
                    tw[b] = hh(i, 1);
                    let interior = (2 * ne + 3 * f) as u32 + i;
                    eo[a] = interior;
                    eo[b] = interior;
                }
            },
        );
        let mut edge_owner = vec![0u32; 2 * ne + nh];
        let (split, interior) = edge_owner.split_at_mut(2 * ne);
        split.par_chunks_mut(2).with_min_len(MIN_LEN).zip(self.edge_owner.par_iter()).for_each(|(o, &h)| {
            let (f, i) = (h / 3, h % 3);
            o[0] = 12 * f + 3 * i;
            o[1] = 12 * f + 3 * next(i) + 2;
        });
        interior.par_chunks_mut(3).with_min_len(MIN_LEN).enumerate().for_each(|(f, o)| {
            for i in 0..3u32 {
                o[i as usize] = 12 * f as u32 + 3 * i + 1;
            }
        });
        let mut vertex_start = vec![0u32; nv as usize + ne];
        let (even, odd) = vertex_start.split_at_mut(nv as usize);
        even.par_iter_mut().with_min_len(MIN_LEN).zip(self.vertex_start.par_iter()).for_each(|(s, &h)| {
            *s = if h == NONE { NONE } else { 12 * (h / 3) + 3 * (h % 3) };
        });
        odd.par_iter_mut().with_min_len(MIN_LEN).zip(self.edge_owner.par_iter()).for_each(|(s, &h)| {
            *s = 12 * (h / 3) + 3 * next(h % 3) + 2;
        });
        (child, Some(Self { twin, edge_of, edge_owner, vertex_start }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn octahedron() -> Vec<[u32; 3]> {
        vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    }

    /// The refined tables equal the tables built from scratch on the refined triangles, up to
    /// the numbering of edges (checked through twins and the edge partition).
    fn check_against_rebuild(tris: &[[u32; 3]], nv: usize, levels: usize) {
        let mut tris = tris.to_vec();
        let mut topo = Topology::build(&tris, nv).unwrap();
        for _ in 0..levels {
            let (child, t) = topo.refine(&tris, true);
            let t = t.unwrap();
            let rebuilt = Topology::build(&child, t.num_vertices()).unwrap();
            assert_eq!(t.twin, rebuilt.twin);
            assert_eq!(t.num_edges(), rebuilt.num_edges());
            for h in 0..t.twin.len() {
                let e = t.edge_of[h] as usize;
                let o = t.edge_owner[e] as usize;
                assert!(o == h || t.twin[h] as usize == o, "owner of the edge of {h}");
            }
            for (v, &s) in t.vertex_start.iter().enumerate() {
                assert_eq!(child[(s / 3) as usize][(s % 3) as usize] as usize, v);
                assert_eq!(t.fan(s).count(), t.fan(rebuilt.vertex_start[v]).count());
                if rebuilt.twin[rebuilt.vertex_start[v] as usize] == NONE {
                    assert_eq!(t.twin[s as usize], NONE, "boundary start of {v}");
                }
            }
            tris = child;
            topo = t;
        }
    }

    #[test]
    fn closed_refinement_matches_rebuild() {
        check_against_rebuild(&octahedron(), 6, 3);
    }

    #[test]
    fn open_refinement_matches_rebuild() {
        let mut tris = octahedron();
        tris.truncate(5);
        check_against_rebuild(&tris, 6, 3);
    }

    #[test]
    fn problems_are_errors() {
        let err = Topology::build(&[[0, 1, 2], [0, 3, 4]], 5).unwrap_err();
        assert_eq!(err, TopologyError::Vertex { vertex: 0, fans: 2 });
        let err = Topology::build(&[[0, 1, 2], [0, 1, 3]], 4).unwrap_err();
        assert!(matches!(err, TopologyError::Edge { a: 0, b: 1, .. }));
        let err = Topology::build(&[[0, 1, 7]], 3).unwrap_err();
        assert_eq!(err, TopologyError::Index { face: 0, vertex: 7, count: 3 });
    }
}
