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

use crate::mesh::{NONE, PolyMesh};
use crate::subdiv::attribute::Attribute;
use crate::subdiv::level_colors::child_colors;
use crate::subdiv::options::{BoundaryRule, CatmullClarkOptions};
use crate::subdiv::rings::Rings;
use crate::subdiv::topology::{MIN_LEN, MIN_RINGS};

/// Faces per parallel task in the per-face passes.
pub(super) const FACES: usize = MIN_LEN / 4;

/// The next corner of a quad.
#[inline]
pub(super) fn next(c: u32) -> u32 {
    (c & !3) | ((c + 1) & 3)
}

/// The previous corner of a quad.
#[inline]
pub(super) fn prev(c: u32) -> u32 {
    (c & !3) | ((c + 3) & 3)
}

/// A level's corners seen from its child: twins and the corners around a face.
pub(super) trait Corners: Sync {
    /// The twin of corner `c`, or [`NONE`].
    fn twin(&self, c: u32) -> u32;
    /// The next corner in `c`'s face (by default, of a level of quads).
    #[inline]
    fn next(&self, c: u32) -> u32 {
        next(c)
    }
    /// The previous corner in `c`'s face (by default, of a level of quads).
    #[inline]
    fn prev(&self, c: u32) -> u32 {
        prev(c)
    }

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
        owner_bits(c, self.child_twins(c)).count_ones()
    }
}

/// The owner bits of quad `q` whose corners' twins are `t`: bit `k` when corner `4q + k` owns
/// its edge (it has no twin, or comes before it).
#[inline]
pub(super) fn owner_bits(q: u32, t: [u32; 4]) -> u32 {
    (0..4).fold(0, |m, k| m | u32::from(4 * q + k < t[k as usize]) << k)
}

/// The twins of the corners of quad `q`.
#[inline(always)]
pub(super) fn quad_twins(twin: &[u32], q: u32) -> [u32; 4] {
    // one bounds check for the four
    let i = 4 * q as usize;
    twin[i..i + 4].try_into().expect("four corners a quad")
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

/// The values around a vertex, by the corners of a quad level: `to(c)` across the edge of
/// corner `c` leaving the vertex, `from(c)` at the start of corner `c` arriving at it, `face(c)`
/// the face point of `c`'s face.
struct Ring<A, B, C> {
    to: A,
    from: B,
    face: C,
}

/// The tables of an all-quad level (see the module docs).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct QuadLevel {
    /// Per corner: its vertex (the level's `face_vertices`).
    pub(super) corners: Vec<u32>,
    /// Per corner: its twin, or [`NONE`].
    pub(super) twin: Vec<u32>,
    /// Per face, and one more: the edges owned by the corners of the faces before it.
    pub(super) edge_base: Vec<u32>,
    /// Per corner: its edge (looked up far more often than made).
    edge_of: Vec<u32>,
    /// Per vertex: a corner leaving it (the boundary one on a boundary), or [`NONE`].
    pub(super) vertex_start: Vec<u32>,
}

impl Corners for QuadLevel {
    #[inline]
    fn twin(&self, c: u32) -> u32 {
        self.twin[c as usize]
    }
}

impl QuadLevel {
    /// Number of vertices.
    pub(super) fn num_vertices(&self) -> usize {
        self.vertex_start.len()
    }

    /// Number of edges.
    pub(super) fn num_edges(&self) -> usize {
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
        Self::with_edges(corners, bytemuck::cast_vec(twin), edge_base, vertex_start)
    }

    /// The tables, with each corner's edge from the twins and the counts per face.
    fn with_edges(corners: Vec<u32>, twin: Vec<u32>, edge_base: Vec<u32>, vertex_start: Vec<u32>) -> Self {
        let mut level = Self { corners, twin, edge_base, edge_of: Vec::new(), vertex_start };
        let mut edge_of: Vec<[u32; 4]> = Vec::new();
        // per face: its own owner bits once, a neighbour's for each edge the neighbour owns
        let edge = |q: u32, owners: u32, k: u32| level.edge_base[q as usize] + (owners & ((1 << k) - 1)).count_ones();
        (0..level.num_faces() as u32)
            .into_par_iter()
            .with_min_len(FACES)
            .map(|q| {
                let owners = level.owners(q);
                core::array::from_fn(|k| {
                    let t = level.twin[4 * q as usize + k];
                    if owners & (1 << k) != 0 {
                        edge(q, owners, k as u32)
                    } else {
                        edge(t / 4, level.owners(t / 4), t % 4)
                    }
                })
            })
            .collect_into_vec(&mut edge_of);
        level.edge_of = bytemuck::cast_vec(edge_of);
        level
    }

    /// The tables of a manifold all-quad level (its adjacency numbers edges as quad levels do),
    /// taking over the adjacency's twins and edges.
    pub(super) fn from_quad_rings(rings: Rings<'_>) -> Self {
        let Rings { mesh, mut adj, .. } = rings;
        let edge_base = counts_before(mesh.num_faces(), |q| owner_bits(q, quad_twins(&adj.twin, q)).count_ones());
        let mut vertex_start = Vec::new();
        (0..mesh.num_vertices() as u32)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|v| {
                let corners = adj.corners_of(v);
                let boundary = corners.iter().copied().find(|&c| adj.twin[c as usize] == NONE);
                boundary.or_else(|| corners.first().copied()).unwrap_or(NONE)
            })
            .collect_into_vec(&mut vertex_start);
        Self {
            corners: mesh.face_vertices.clone(),
            twin: core::mem::take(&mut adj.twin),
            edge_base,
            edge_of: core::mem::take(&mut adj.edge_of),
            vertex_start,
        }
    }

    /// The owner bits of the corners of face `q` (bit `k` for corner `4q + k`).
    #[inline(always)]
    pub(super) fn owners(&self, q: u32) -> u32 {
        owner_bits(q, quad_twins(&self.twin, q))
    }

    /// The edge of corner `c`.
    #[inline]
    fn edge(&self, c: u32) -> u32 {
        self.edge_of[c as usize]
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
        let ring = Ring {
            to: |c: u32| p[self.corners[next(c) as usize] as usize],
            from: |c: u32| p[self.corners[c as usize] as usize],
            face: |c: u32| faces[(c / 4) as usize],
        };
        self.ring_point(p[v], self.vertex_start[v], boundary, &ring)
    }

    /// The vertex point of the vertex whose value is `pv` and whose start corner is `start`,
    /// walking its ring in this level: `ring` gives the values across its corners (which are
    /// those of this level's vertices, or, in the grandchild passes, of the child's vertices
    /// on this level's edges).
    #[inline]
    fn ring_point<T: Attribute>(
        &self,
        pv: T,
        start: u32,
        boundary: BoundaryRule,
        ring: &Ring<impl Fn(u32) -> T, impl Fn(u32) -> T, impl Fn(u32) -> T>,
    ) -> T {
        if start == NONE {
            return pv;
        }
        let mut corners = [0u32; 8];
        let mut n = 0;
        let mut c = start;
        loop {
            if let Some(r) = corners.get_mut(n) {
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
                return pv * 0.75 + ((ring.to)(start) + (ring.from)(pc)) * 0.125;
            }
            if t == start {
                break;
            }
            c = t;
        }
        // interior: the ring and face points summed in ascending corner order
        let (mut sum_ring, mut centres) = (T::default(), T::default());
        let mut add = |c: u32| {
            sum_ring = sum_ring + (ring.to)(c);
            centres = centres + (ring.face)(c);
        };
        if n <= corners.len() {
            let corners = &mut corners[..n];
            corners.sort_unstable();
            corners.iter().for_each(|&c| add(c));
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
            .map(|q| self.child_corners_of(q, nv, nv + ne))
            .collect_into_vec(&mut out);
        bytemuck::cast_vec(out)
    }

    /// The corners of the child faces of face `q` ([`Self::child_corners`]), the child's
    /// vertices on edges numbered from `on_edges`, those on faces from `on_faces`.
    #[inline(always)]
    pub(super) fn child_corners_of(&self, q: u32, on_edges: u32, on_faces: u32) -> [u32; 16] {
        let mut quads = [0u32; 16];
        let e = [4 * q, 4 * q + 1, 4 * q + 2, 4 * q + 3].map(|c| on_edges + self.edge(c));
        for k in 0..4 {
            let c = (4 * q) as usize + k;
            quads[4 * k..4 * k + 4].copy_from_slice(&[self.corners[c], e[k], on_faces + q, e[(k + 3) % 4]]);
        }
        quads
    }

    /// The child's tables, given its corners ([`Self::child_corners`]).
    pub(super) fn child(&self, corners: Vec<u32>) -> Self {
        let (nv, ne, nf) = (self.num_vertices(), self.num_edges(), self.num_faces());
        // the twins of each child face, and how many edges its corners own
        let (mut twin, mut counts): (Vec<[u32; 4]>, _) = (Vec::new(), Vec::with_capacity(4 * nf + 1));
        (0..4 * nf as u32)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|c| {
                let t = self.child_twins(c);
                (t, owner_bits(c, t).count_ones())
            })
            .unzip_into_vecs(&mut twin, &mut counts);
        let edge_base = prefix_sums(counts);
        let mut vertex_start = vec![0u32; nv + ne + nf];
        let (old, rest) = vertex_start.split_at_mut(nv);
        let (edges, faces) = rest.split_at_mut(ne);
        old.par_iter_mut().zip(&self.vertex_start).with_min_len(MIN_LEN).for_each(|(o, &s)| {
            *o = if s == NONE { NONE } else { 4 * s };
        });
        self.for_owners(edges, |o| edge_start(self, o));
        faces.par_iter_mut().enumerate().with_min_len(MIN_LEN).for_each(|(q, o)| *o = 16 * q as u32 + 2);
        Self::with_edges(corners, bytemuck::cast_vec(twin), edge_base, vertex_start)
    }
}

/// The grandchild `F` of a quad level `S`, made from the values of its child `M` and the
/// tables of `S`, without `M`'s tables or faces: `M` face `4q + k` is
/// `(a_k, e_k, m_q, e_{k−1})` with `a_k` the vertex of `S` corner `4q + k`, `e_k` the `M`
/// vertex on its edge and `m_q` the one on face `q`, `M`'s twins follow from `S`'s
/// ([`Corners::child_twins`]), and every stencil of `F` is a fixed pattern over one `S` face,
/// the two along one `S` edge, or the ring of one `S` vertex. The `M` edges are numbered as
/// `Adjacency` numbers them: per `S` face, the owner bits of its 16 `M` corners and how many
/// `M` edges the faces before it own.
pub(super) struct Grandchild<'a> {
    s: &'a QuadLevel,
    /// Per `S` face: bit `i` for `M` corner `16q + i` owning its edge.
    masks: Vec<u32>,
    /// Per `S` face, and one more: the `M` edges owned by the faces before it.
    pub(super) base: Vec<u32>,
    /// The numbers of `S` vertices and `S` edges.
    nvs: u32,
    nes: u32,
}

impl QuadLevel {
    /// What [`Grandchild`] needs of this level.
    pub(super) fn grandchild(&self) -> Grandchild<'_> {
        let mut masks = Vec::new();
        (0..self.num_faces() as u32)
            .into_par_iter()
            .with_min_len(FACES)
            .map(|q| {
                let mut m = 0;
                for k in 0..4 {
                    let c = 4 * q + k;
                    m |= owner_bits(c, self.child_twins(c)) << (4 * k);
                }
                m
            })
            .collect_into_vec(&mut masks);
        let base = counts_before(self.num_faces(), |q| masks[q as usize].count_ones());
        Grandchild { s: self, masks, base, nvs: self.num_vertices() as u32, nes: self.num_edges() as u32 }
    }
}

impl Grandchild<'_> {
    /// Number of `M` vertices.
    pub(super) fn num_m_vertices(&self) -> u32 {
        (self.s.num_vertices() + self.s.num_edges() + self.s.num_faces()) as u32
    }

    /// Number of `M` edges.
    pub(super) fn num_m_edges(&self) -> u32 {
        *self.base.last().expect("one more count than faces")
    }

    /// The `M` edge of `M` corner `x`.
    #[inline]
    fn m_edge(&self, x: u32) -> u32 {
        let o = x.min(self.s.child_twins(x / 4)[(x % 4) as usize]);
        let q = (o / 16) as usize;
        self.base[q] + (self.masks[q] & ((1 << (o % 16)) - 1)).count_ones()
    }

    /// The `M` edges of the `M` corners `16q .. 16q + 16` (as [`Self::m_edge`], the twins of
    /// `S` face `q` read once): the halves of `S` edges may be owned across them, the `M`
    /// edges inside are owned inside.
    #[inline]
    fn m_edges(&self, q: u32) -> [u32; 16] {
        let i = q as usize;
        let tw = &self.s.twin[4 * i..4 * i + 4];
        let (mask, base) = (self.masks[i], self.base[i]);
        let local = |b: u32| base + (mask & ((1 << b) - 1)).count_ones();
        let far = |o: u32| {
            let g = (o / 16) as usize;
            self.base[g] + (self.masks[g] & ((1 << (o % 16)) - 1)).count_ones()
        };
        let mut e = [0u32; 16];
        for k in 0..4u32 {
            let x = 16 * q + 4 * k;
            let (t, tp) = (tw[k as usize], tw[((k + 3) % 4) as usize]);
            let first = if t == NONE { NONE } else { 4 * next(t) + 3 };
            let second = if tp == NONE { NONE } else { 4 * tp };
            let e4 = &mut e[4 * k as usize..4 * k as usize + 4];
            e4[0] = if x < first { local(4 * k) } else { far(first) };
            e4[1] = local(if k < 3 { 4 * k + 1 } else { 2 });
            e4[2] = local(if k > 0 { 4 * k - 3 } else { 2 });
            e4[3] = if x + 3 < second { local(4 * k + 3) } else { far(second) };
        }
        debug_assert!((0..16).all(|j| e[j as usize] == self.m_edge(16 * q + j)));
        e
    }

    /// The `M` vertices of the corners of `M` faces `4q .. 4q + 4`.
    #[inline]
    fn m_faces(&self, q: u32) -> [[u32; 4]; 4] {
        let s = self.s;
        let i = 4 * q as usize;
        let (a, eo) = (&s.corners[i..i + 4], &s.edge_of[i..i + 4]);
        let e = [self.nvs + eo[0], self.nvs + eo[1], self.nvs + eo[2], self.nvs + eo[3]];
        let m = self.nvs + self.nes + q;
        [[a[0], e[0], m, e[3]], [a[1], e[1], m, e[0]], [a[2], e[2], m, e[1]], [a[3], e[3], m, e[2]]]
    }

    /// The values of `F` from those of `M`, `pm` (the layout of [`QuadLevel::refine`] on `M`).
    ///
    /// One pass over `S` faces for the face points of `M` faces, then, side by side, one over
    /// `S` vertices (the `M` vertices on them) and one over `S` faces (the `M` vertex on each,
    /// those on the `S` edges it owns, and the `M` edges it owns).
    pub(super) fn values<T: Attribute + Zeroable>(&self, pm: &[T], boundary: BoundaryRule) -> Vec<T> {
        let s = self.s;
        let (nvs, nes, nfs) = (s.num_vertices(), s.num_edges(), s.num_faces());
        let (nvm, nem) = (self.num_m_vertices() as usize, self.num_m_edges() as usize);
        debug_assert_eq!(pm.len(), nvm);
        let mut out: Vec<T> = bytemuck::zeroed_vec(nvm + nem + 4 * nfs);
        let (old, rest) = out.split_at_mut(nvs);
        let (on_edges, rest) = rest.split_at_mut(nes);
        let (on_faces, rest) = rest.split_at_mut(nfs);
        let (edges, faces) = rest.split_at_mut(nem);
        faces.par_chunks_mut(4).enumerate().with_min_len(FACES).for_each(|(q, o)| {
            for (o, v) in o.iter_mut().zip(self.m_faces(q as u32)) {
                *o = (T::default() + pm[v[0] as usize] + pm[v[1] as usize] + pm[v[2] as usize] + pm[v[3] as usize])
                    * 0.25;
            }
        });
        let faces = &*faces;
        let fp = |x: u32| faces[x as usize];
        // S vertex v: its M ring is its S ring, the M vertices on the S edges standing for
        // the S neighbours, the M faces of its S corners for its S faces.
        let old_pass = || {
            old.par_iter_mut().enumerate().with_min_len(MIN_RINGS).for_each(|(v, o)| {
                let on = |c: u32| pm[nvs + s.edge(c) as usize];
                let ring = Ring { to: on, from: on, face: fp };
                *o = s.ring_point(pm[v], s.vertex_start[v], boundary, &ring);
            });
        };
        let face_pass = || {
            let mut parts = Vec::with_capacity(nfs.div_ceil(FACES));
            let (mut on_edges, mut on_faces, mut edges) = (on_edges, on_faces, edges);
            for q in (0..nfs).step_by(FACES) {
                let end = nfs.min(q + FACES);
                let e;
                (e, on_edges) = on_edges.split_at_mut((s.edge_base[end] - s.edge_base[q]) as usize);
                let f;
                (f, on_faces) = on_faces.split_at_mut(end - q);
                let m;
                (m, edges) = edges.split_at_mut((self.base[end] - self.base[q]) as usize);
                parts.push((q as u32, e, f, m));
            }
            parts.into_par_iter().for_each(|(q0, on_edges, on_faces, edges)| {
                let (mut on_edges, mut edges) = (on_edges.iter_mut(), edges.iter_mut());
                for (q, on_face) in (q0..).zip(on_faces) {
                    let mv = self.m_faces(q);
                    let at = |k: usize, j: usize| pm[mv[k][j] as usize];
                    let tw = quad_twins(&s.twin, q);
                    // The M vertex on S face q: valence 4, its corners 16q + 4k + 2 ascending.
                    let ring = (0..4).fold(T::default(), |r, k| r + at(k, 3));
                    let centres = (0..4).fold(T::default(), |r, k| r + fp(4 * q + k as u32));
                    *on_face = at(0, 2) * 0.5 + (ring + centres) * 0.0625;
                    // The M vertices on the S edges q owns.
                    let mut owners = owner_bits(q, tw);
                    while owners != 0 {
                        let o = 4 * q + owners.trailing_zeros();
                        owners &= owners - 1;
                        let k = (o % 4) as usize;
                        let value =
                            self.on_edge(pm, faces, o, tw[k], [at(k, 1), at(k, 0), at((k + 1) % 4, 0), at(k, 2)]);
                        if let Some(slot) = on_edges.next() {
                            *slot = value;
                        }
                    }
                    // The M edges q owns: M corner 16q + 4k + j, in M face 4q + k, whose twin
                    // is in M face `across[j]` (see `Corners::child_twins`).
                    let mut owners = self.masks[q as usize];
                    while owners != 0 {
                        let x = owners.trailing_zeros();
                        owners &= owners - 1;
                        let (k, j) = ((x / 4) as usize, (x % 4) as usize);
                        let (a, b) = (at(k, j), at(k, (j + 1) % 4));
                        let across = match j {
                            0 if tw[k] == NONE => NONE,
                            0 => next(tw[k]),
                            1 => 4 * q + ((k as u32 + 1) % 4),
                            2 => 4 * q + ((k as u32 + 3) % 4),
                            _ => tw[(k + 3) % 4],
                        };
                        let value = if across == NONE {
                            (a + b) * 0.5
                        } else {
                            (a + b + fp(4 * q + k as u32) + fp(across)) * 0.25
                        };
                        if let Some(slot) = edges.next() {
                            *slot = value;
                        }
                    }
                }
            });
        };
        rayon::join(old_pass, face_pass);
        out
    }

    /// The new value of the `M` vertex on the `S` edge owned by corner `o`, whose twin is `t`,
    /// from the values `pv` of that vertex, `a` and `b` of the edge's ends (from `o`'s vertex)
    /// and `m` of the `M` vertex on `o`'s face: on a boundary the crease rule between the
    /// ends, else valence 4 with the `M` corners `4o + 1`, `4·next(o) + 3`, `4t + 1`,
    /// `4·next(t) + 3`, summed in ascending order.
    #[inline]
    fn on_edge<T: Attribute>(&self, pm: &[T], faces: &[T], o: u32, t: u32, [pv, a, b, m]: [T; 4]) -> T {
        if t == NONE {
            return pv * 0.75 + (b + a) * 0.125;
        }
        let (no, nt) = (next(o), next(t));
        let ring = [m, b, pm[(self.nvs + self.nes + t / 4) as usize], a];
        let centres = [o, no, t, nt];
        let order = ascending([4 * o + 1, 4 * no + 3, 4 * t + 1, 4 * nt + 3]);
        let sum = order.iter().fold(T::default(), |r, &i| r + ring[i]);
        let centres = order.iter().fold(T::default(), |r, &i| r + faces[centres[i] as usize]);
        pv * 0.5 + (sum + centres) * 0.0625
    }

    /// The faces of `F`: `S` face `q` gives `F` faces `16q .. 16q + 16` ([`Self::quads_of`]).
    pub(super) fn corners(&self) -> Vec<u32> {
        let mut out: Vec<[u32; 64]> = Vec::new();
        (0..self.s.num_faces() as u32)
            .into_par_iter()
            .with_min_len(FACES / 4)
            .map(|q| self.quads_of(q))
            .collect_into_vec(&mut out);
        bytemuck::cast_vec(out)
    }

    /// The corners of `F` faces `16q .. 16q + 16`: per `M` corner `x = 16q + 4k + j`,
    /// `(v_x, e(x), face of x, e(prev x))` as `F` vertices.
    #[inline]
    pub(super) fn quads_of(&self, q: u32) -> [u32; 64] {
        let (nvm, nem) = (self.num_m_vertices(), self.num_m_edges());
        let mv = self.m_faces(q);
        let e = self.m_edges(q).map(|e| nvm + e);
        let mut quads = [0u32; 64];
        for k in 0..4 {
            for j in 0..4 {
                let x = 4 * k + j;
                let quad = [mv[k][j], e[x], nvm + nem + 4 * q + k as u32, e[4 * k + (j + 3) % 4]];
                quads[4 * x..4 * x + 4].copy_from_slice(&quad);
            }
        }
        quads
    }
}

/// Levels `from + 1` to `levels` (at least `from + 1`) of a Catmull-Clark subdivision, from
/// level `from`: its tables `level`, positions and colours (empty, carried, or coloured by
/// level as `options` says). The last level is made from the tables two levels above it
/// ([`Grandchild`]), so for three levels of a quad mesh only the base level and level 1 get
/// tables.
pub(super) fn subdivide(
    mut level: QuadLevel,
    mut positions: Vec<DVec3>,
    mut colors: Vec<DVec3>,
    from: usize,
    levels: usize,
    options: &CatmullClarkOptions,
) -> PolyMesh {
    let b = options.boundary;
    let colours = |colors: &[DVec3], n: usize, depth: usize, refine: &dyn Fn(&[DVec3]) -> Vec<DVec3>| {
        child_colors(options.color_by_level, colors, n, depth, refine)
    };
    // `level` holds the tables of level `depth − 1`, `positions` and `colors` its values.
    for depth in from + 1..levels {
        let fine = level.refine(&positions, b);
        colors = colours(&colors, fine.len(), depth, &|c| level.refine(c, b));
        positions = fine;
        if depth + 1 == levels {
            let g = level.grandchild();
            let fine = g.values(&positions, b);
            drop(positions);
            colors = colours(&colors, fine.len(), levels, &|c| g.values(c, b));
            let corners = g.corners();
            // the tables are done with: their memory can serve the face offsets
            drop(g);
            drop(level);
            return quad_mesh(fine, colors, corners);
        }
        let corners = level.child_corners();
        level = level.child(corners);
    }
    // one level: from `level`'s tables
    let fine = level.refine(&positions, b);
    drop(positions);
    colors = colours(&colors, fine.len(), levels, &|c| level.refine(c, b));
    quad_mesh(fine, colors, level.child_corners())
}

/// A mesh of quads from its positions, colours and corners.
pub(super) fn quad_mesh(positions: Vec<DVec3>, colors: Vec<DVec3>, corners: Vec<u32>) -> PolyMesh {
    let mut face_offsets = Vec::new();
    (0..(corners.len() / 4 + 1) as u32)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|q| 4 * q)
        .collect_into_vec(&mut face_offsets);
    PolyMesh { positions, colors, face_offsets, face_vertices: corners, normals: None, uvs: None }
}

/// The start of the child vertex on the edge owned by corner `o`: the boundary half leaving
/// it on a boundary edge, else the half-edge to the face point of `o`'s face.
#[inline]
fn edge_start(level: &impl Corners, o: u32) -> u32 {
    if level.twin(o) == NONE { 4 * level.next(o) + 3 } else { 4 * o + 1 }
}

/// The indices of `keys` (all different) in ascending order of the keys, without moving
/// anything: each key's rank is how many keys are smaller.
#[inline]
fn ascending(keys: [u32; 4]) -> [usize; 4] {
    let mut rank = [0; 4];
    for i in 0..4 {
        for j in i + 1..4 {
            let below = usize::from(keys[i] < keys[j]);
            rank[j] += below;
            rank[i] += 1 - below;
        }
    }
    let mut order = [0; 4];
    for (i, r) in rank.into_iter().enumerate() {
        order[r] = i;
    }
    order
}

/// The exclusive prefix sums of `count(0), …, count(n − 1)`, and the total: `n + 1` values.
pub(super) fn counts_before(n: usize, count: impl Fn(u32) -> u32 + Sync) -> Vec<u32> {
    // room for the total: pushing it onto a full vector would copy the whole
    let mut out = Vec::with_capacity(n + 1);
    (0..n as u32).into_par_iter().with_min_len(MIN_LEN).map(&count).collect_into_vec(&mut out);
    prefix_sums(out)
}

/// The exclusive prefix sums of `out` in place, and the total pushed.
fn prefix_sums(mut out: Vec<u32>) -> Vec<u32> {
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
