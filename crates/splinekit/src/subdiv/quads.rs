//! Catmull-Clark levels below the first, where every face is a quad: the child's adjacency
//! follows from the parent's in closed form, so no level after the first is searched or
//! hashed, and every pass is a parallel map over faces or vertices.
//!
//! A quad level stores, per corner `c = 4q + k` of quad `q` (the half-edge from its vertex to
//! the next corner's), the corner's vertex and its twin (or [`NONE`]); per face, how many
//! edges the corners of the faces before it own; per vertex, a *start* corner leaving it (on
//! a boundary, the boundary one). An edge is owned by its first half-edge in corner order,
//! the one without a twin or before its twin, and edges are numbered in the order of their
//! owners — exactly [`Adjacency`](crate::mesh::Adjacency)'s numbering, so the vertices come
//! out in [`catmull_clark_step`](super::catmull_clark_step)'s order. The edge of an owner is
//! its face's count plus the owners before it in its face; another half-edge's is its twin's.
//!
//! Child face `c` (of parent corner `c`, in a face of any size) is `(v_c, e(c), f, e(prev c))`
//! with corners `4c .. 4c + 4`, so the child's twins are, with `t = twin(c)`:
//! `4c → 4·next(t) + 3` (the halves of an edge swap), `4c + 1 → 4·next(c) + 2`,
//! `4c + 2 → 4·prev(c) + 1` (the edges to the face point), `4c + 3 → 4·twin(prev c)`;
//! edge counts per face are a prefix sum of the child's owner bits; and the starts are
//! `4·start(v)` for a parent vertex, `4·next(o) + 3` (boundary) or `4o + 1` for the point on
//! the edge owned by `o`, and `4·first(f) + 2` for the point of face `f`.
//!
//! The values are computed with the operations of `Rings::refine`, in the same order (a
//! vertex's ring summed in ascending corner order), so they are the same to the bit.

use bytemuck::Zeroable;
use rayon::prelude::*;

use glam::DVec3;

use super::catmull_clark::{CatmullClarkOptions, Rings};
use super::loop_scheme::{Attribute, BoundaryRule, LEVEL_COLORS};
use super::topology::{MIN_LEN, MIN_RINGS};
use crate::mesh::{NONE, PolyMesh};

/// Faces per parallel task in the per-face passes.
const FACES: usize = MIN_LEN / 4;

/// The next corner of a quad.
#[inline]
fn next(c: u32) -> u32 {
    (c & !3) | ((c + 1) & 3)
}

/// The previous corner of a quad.
#[inline]
fn prev(c: u32) -> u32 {
    (c & !3) | ((c + 3) & 3)
}

/// A level's corners seen from its child: twins and the corners around a face.
trait Corners: Sync {
    /// The twin of corner `c`, or [`NONE`].
    fn twin(&self, c: u32) -> u32;
    /// The next corner in `c`'s face.
    fn next(&self, c: u32) -> u32;
    /// The previous corner in `c`'s face.
    fn prev(&self, c: u32) -> u32;

    /// The twins of the four corners of child face `c`.
    #[inline]
    fn child_twins(&self, c: u32) -> [u32; 4] {
        let (t, tp) = (self.twin(c), self.twin(self.prev(c)));
        [
            if t == NONE { NONE } else { 4 * self.next(t) + 3 },
            4 * self.next(c) + 2,
            4 * self.prev(c) + 1,
            if tp == NONE { NONE } else { 4 * tp },
        ]
    }

    /// How many edges the corners of child face `c` own.
    #[inline]
    fn child_owners(&self, c: u32) -> u32 {
        let t = self.child_twins(c);
        (0..4).map(|j| u32::from(4 * c + j < t[j as usize])).sum()
    }
}

impl Corners for Rings<'_> {
    #[inline]
    fn twin(&self, c: u32) -> u32 {
        self.adj.twin[c as usize]
    }
    #[inline]
    fn next(&self, c: u32) -> u32 {
        let f = self.adj.face_of[c as usize] as usize;
        if c + 1 == self.mesh.face_offsets[f + 1] { self.mesh.face_offsets[f] } else { c + 1 }
    }
    #[inline]
    fn prev(&self, c: u32) -> u32 {
        Rings::prev(self, c)
    }
}

/// The tables of an all-quad level (see the module docs).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct QuadLevel {
    /// Per corner: its vertex (the level's `face_vertices`).
    pub(super) corners: Vec<u32>,
    /// Per corner: its twin, or [`NONE`].
    twin: Vec<u32>,
    /// Per face, and one more: the edges owned by the corners of the faces before it.
    edge_base: Vec<u32>,
    /// Per vertex: a corner leaving it (the boundary one on a boundary), or [`NONE`].
    vertex_start: Vec<u32>,
}

impl Corners for QuadLevel {
    #[inline]
    fn twin(&self, c: u32) -> u32 {
        self.twin[c as usize]
    }
    #[inline]
    fn next(&self, c: u32) -> u32 {
        next(c)
    }
    #[inline]
    fn prev(&self, c: u32) -> u32 {
        prev(c)
    }
}

impl QuadLevel {
    /// Number of vertices.
    pub(super) fn num_vertices(&self) -> usize {
        self.vertex_start.len()
    }

    /// Number of edges.
    fn num_edges(&self) -> usize {
        *self.edge_base.last().expect("one more count than faces") as usize
    }

    /// Number of faces.
    pub(super) fn num_faces(&self) -> usize {
        self.twin.len() / 4
    }

    /// The tables of the child of a manifold polygon level.
    pub(super) fn from_rings(rings: &Rings<'_>) -> Self {
        let (_, corners) = rings.child_faces();
        let nc = rings.mesh.face_vertices.len();
        let mut twin: Vec<[u32; 4]> = Vec::new();
        (0..nc as u32).into_par_iter().with_min_len(MIN_LEN).map(|c| rings.child_twins(c)).collect_into_vec(&mut twin);
        let edge_base = counts_before(nc, |c| rings.child_owners(c));
        let adj = &rings.adj;
        let (nv, ne, nf) = (rings.mesh.num_vertices(), adj.num_edges(), rings.mesh.num_faces());
        let mut vertex_start = Vec::new();
        (0..(nv + ne + nf) as u32)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|x| {
                let x = x as usize;
                if x < nv {
                    let corners = adj.corners_of(x as u32);
                    let boundary = corners.iter().copied().find(|&c| adj.twin[c as usize] == NONE);
                    boundary.or_else(|| corners.first().copied()).map_or(NONE, |s| 4 * s)
                } else if x < nv + ne {
                    edge_start(rings, adj.edge_corner[x - nv])
                } else {
                    4 * rings.mesh.face_offsets[x - nv - ne] + 2
                }
            })
            .collect_into_vec(&mut vertex_start);
        Self { corners, twin: bytemuck::cast_vec(twin), edge_base, vertex_start }
    }

    /// The owner bits of the corners of face `q` (bit `k` for corner `4q + k`).
    #[inline]
    fn owners(&self, q: u32) -> u32 {
        let t = &self.twin[4 * q as usize..4 * q as usize + 4];
        (0..4).fold(0, |m, k| m | u32::from(4 * q + k < t[k as usize]) << k)
    }

    /// The edge of corner `c`.
    #[inline]
    fn edge(&self, c: u32) -> u32 {
        let o = c.min(self.twin[c as usize]);
        let q = o / 4;
        self.edge_base[q as usize] + (self.owners(q) & ((1 << (o % 4)) - 1)).count_ones()
    }

    /// Writes `fill(o)` for every owner corner `o`, in edge order, into `edges` (one slot per
    /// edge).
    fn for_owners<X: Send>(&self, edges: &mut [X], fill: impl Fn(u32) -> X + Sync) {
        let nf = self.num_faces();
        let mut parts = Vec::with_capacity(nf.div_ceil(FACES));
        let mut rest = edges;
        for q in (0..nf).step_by(FACES) {
            let end = nf.min(q + FACES);
            let (part, tail) = rest.split_at_mut((self.edge_base[end] - self.edge_base[q]) as usize);
            parts.push((q as u32, end as u32, part));
            rest = tail;
        }
        parts.into_par_iter().for_each(|(q0, q1, part)| {
            let mut slots = part.iter_mut();
            for q in q0..q1 {
                let mut m = self.owners(q);
                while m != 0 {
                    let k = m.trailing_zeros();
                    m &= m - 1;
                    if let Some(s) = slots.next() {
                        *s = fill(4 * q + k);
                    }
                }
            }
        });
    }

    /// The child's values: vertex points, edge points, face points (see
    /// [`catmull_clark`](super::catmull_clark)).
    pub(super) fn refine<T: Attribute + Zeroable>(&self, p: &[T], boundary: BoundaryRule) -> Vec<T> {
        let (nv, ne) = (self.num_vertices(), self.num_edges());
        let mut out: Vec<T> = bytemuck::zeroed_vec(nv + ne + self.num_faces());
        let (vertices, rest) = out.split_at_mut(nv);
        let (edges, faces) = rest.split_at_mut(ne);
        let at = |c: u32| p[self.corners[c as usize] as usize];
        faces.par_iter_mut().enumerate().with_min_len(MIN_LEN).for_each(|(q, o)| {
            let c = 4 * q as u32;
            *o = (T::default() + at(c) + at(c + 1) + at(c + 2) + at(c + 3)) * 0.25;
        });
        let faces = &*faces;
        let edge_pass = || {
            self.for_owners(edges, |c| {
                let (a, b) = (at(c), at(next(c)));
                let t = self.twin[c as usize];
                if t == NONE {
                    (a + b) * 0.5
                } else {
                    (a + b + faces[(c / 4) as usize] + faces[(t / 4) as usize]) * 0.25
                }
            });
        };
        let vertex_pass = || {
            vertices.par_iter_mut().enumerate().with_min_len(MIN_RINGS).for_each(|(v, o)| {
                *o = self.vertex_point(p, faces, v, boundary);
            });
        };
        rayon::join(edge_pass, vertex_pass);
        out
    }

    /// The vertex point of vertex `v`, from the values `p` and the face points `faces`.
    #[inline]
    fn vertex_point<T: Attribute>(&self, p: &[T], faces: &[T], v: usize, boundary: BoundaryRule) -> T {
        let pv = p[v];
        let start = self.vertex_start[v];
        if start == NONE {
            return pv;
        }
        let to = |c: u32| p[self.corners[next(c) as usize] as usize];
        let mut ring = [0u32; 8];
        let mut n = 0;
        let mut c = start;
        loop {
            if let Some(r) = ring.get_mut(n) {
                *r = c;
            }
            n += 1;
            let pc = prev(c);
            let t = self.twin[pc as usize];
            if t == NONE {
                // on the boundary (the start is its boundary corner)
                if boundary == BoundaryRule::Corners && n == 1 {
                    return pv;
                }
                let b = p[self.corners[pc as usize] as usize];
                return pv * 0.75 + (to(start) + b) * 0.125;
            }
            if t == start {
                break;
            }
            c = t;
        }
        // interior: the ring and face points summed in ascending corner order
        let (mut sum_ring, mut centres) = (T::default(), T::default());
        let mut add = |c: u32| {
            sum_ring = sum_ring + to(c);
            centres = centres + faces[(c / 4) as usize];
        };
        if n <= ring.len() {
            let ring = &mut ring[..n];
            ring.sort_unstable();
            ring.iter().for_each(|&c| add(c));
        } else {
            // high valence: the next larger corner, found by walking the ring again
            let mut last = None;
            for _ in 0..n {
                let mut best = NONE;
                let mut c = start;
                loop {
                    if last.is_none_or(|l| c > l) && c < best {
                        best = c;
                    }
                    c = self.twin[prev(c) as usize];
                    if c == start {
                        break;
                    }
                }
                add(best);
                last = Some(best);
            }
        }
        let n = n as f64;
        pv * ((n - 2.0) / n) + (sum_ring + centres) * (1.0 / (n * n))
    }

    /// The child's faces: per corner `c`, `(v_c, e(c), f, e(prev c))` as child vertices.
    pub(super) fn child_corners(&self) -> Vec<u32> {
        let (nv, ne) = (self.num_vertices() as u32, self.num_edges() as u32);
        let mut out: Vec<[u32; 16]> = Vec::new();
        (0..self.num_faces() as u32)
            .into_par_iter()
            .with_min_len(FACES)
            .map(|q| {
                let mut quads = [0u32; 16];
                let e = [4 * q, 4 * q + 1, 4 * q + 2, 4 * q + 3].map(|c| nv + self.edge(c));
                for k in 0..4 {
                    let c = (4 * q) as usize + k;
                    quads[4 * k..4 * k + 4].copy_from_slice(&[self.corners[c], e[k], nv + ne + q, e[(k + 3) % 4]]);
                }
                quads
            })
            .collect_into_vec(&mut out);
        bytemuck::cast_vec(out)
    }

    /// The child's tables, given its corners ([`Self::child_corners`]).
    pub(super) fn child(&self, corners: Vec<u32>) -> Self {
        let (nv, ne, nf) = (self.num_vertices(), self.num_edges(), self.num_faces());
        let mut twin: Vec<[u32; 4]> = Vec::new();
        (0..4 * nf as u32)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|c| self.child_twins(c))
            .collect_into_vec(&mut twin);
        let edge_base = counts_before(4 * nf, |c| self.child_owners(c));
        let mut vertex_start = vec![0u32; nv + ne + nf];
        let (old, rest) = vertex_start.split_at_mut(nv);
        let (edges, faces) = rest.split_at_mut(ne);
        old.par_iter_mut().zip(&self.vertex_start).with_min_len(MIN_LEN).for_each(|(o, &s)| {
            *o = if s == NONE { NONE } else { 4 * s };
        });
        self.for_owners(edges, |o| edge_start(self, o));
        faces.par_iter_mut().enumerate().with_min_len(MIN_LEN).for_each(|(q, o)| *o = 16 * q as u32 + 2);
        Self { corners, twin: bytemuck::cast_vec(twin), edge_base, vertex_start }
    }
}

/// Levels 2 to `levels` of a Catmull-Clark subdivision, from level 1: its tables `level`,
/// positions and colours (empty, carried, or coloured by level as `options` says).
pub(super) fn subdivide(
    mut level: QuadLevel,
    mut positions: Vec<DVec3>,
    mut colors: Vec<DVec3>,
    levels: usize,
    options: &CatmullClarkOptions,
) -> PolyMesh {
    for depth in 2..=levels {
        let fine = level.refine(&positions, options.boundary);
        drop(positions);
        colors = if options.color_by_level {
            let mut c = colors;
            c.resize(fine.len(), LEVEL_COLORS[depth % LEVEL_COLORS.len()]);
            c
        } else if colors.is_empty() {
            colors
        } else {
            level.refine(&colors, options.boundary)
        };
        positions = fine;
        let corners = level.child_corners();
        if depth < levels {
            level = level.child(corners);
        } else {
            let mut face_offsets = Vec::new();
            (0..(corners.len() / 4 + 1) as u32)
                .into_par_iter()
                .with_min_len(MIN_LEN)
                .map(|q| 4 * q)
                .collect_into_vec(&mut face_offsets);
            return PolyMesh { positions, colors, face_offsets, face_vertices: corners, normals: None, uvs: None };
        }
    }
    unreachable!("the loop returns at depth = levels ≥ 2")
}

/// The start of the child vertex on the edge owned by corner `o`: the boundary half leaving
/// it on a boundary edge, else the half-edge to the face point of `o`'s face.
#[inline]
fn edge_start(level: &impl Corners, o: u32) -> u32 {
    if level.twin(o) == NONE { 4 * level.next(o) + 3 } else { 4 * o + 1 }
}

/// The exclusive prefix sums of `count(0), …, count(n − 1)`, and the total: `n + 1` values.
fn counts_before(n: usize, count: impl Fn(u32) -> u32 + Sync) -> Vec<u32> {
    let mut out = Vec::new();
    (0..n as u32).into_par_iter().with_min_len(MIN_LEN).map(&count).collect_into_vec(&mut out);
    let mut sums: Vec<u32> = out.par_chunks(MIN_LEN).map(|c| c.iter().sum()).collect();
    let mut at = 0;
    for s in &mut sums {
        (*s, at) = (at, at + *s);
    }
    out.par_chunks_mut(MIN_LEN).zip(sums).for_each(|(chunk, mut at)| {
        for x in chunk {
            (*x, at) = (at, at + *x);
        }
    });
    out.push(at);
    out
}
