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
//! the interior edge between `c_i` and `c_3` is `2E + 3f + i`. At every level an edge is
//! owned by its first half-edge (`h` owns its edge iff it has no twin or `h < twin(h)`), which
//! the passes use instead of looking the owner up. So no hashing or searching
//! happens after the base level, and every pass is a parallel map over faces, edges or
//! vertices.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use rayon::prelude::*;

use crate::mesh::{Adjacency, NONE, NonManifold};

/// Work items per rayon task, at least. A pass ends when its last task does, so the thread
/// that finishes first waits for at most one task: small tasks keep two threads together
/// (on a 20k-triangle icosphere, 2¹³ items per task lost 4–5 % on two threads to that wait
/// against 2¹⁰), and 2¹⁰ items still dwarf a task's cost of about a microsecond. One thread
/// runs a pass as one or two tasks whatever this is.
pub(crate) const MIN_LEN: usize = 1 << 10;

/// Vertices per rayon task in passes that walk vertex rings: each costs several items' worth,
/// and smaller tasks balance two threads on small meshes.
pub(crate) const MIN_RINGS: usize = MIN_LEN / 8;

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
    /// An edge used by more than two faces or twice in the same direction, or a vertex whose
    /// faces form several fans (two cones touching at their tips): the mesh's own
    /// [`NonManifold`] report of it.
    #[error("{}", nonmanifold_message(.0))]
    NonManifold(NonManifold),
    /// A face names a vertex at more than one corner (a degenerate face such as `a a b`, or a
    /// quad pole `a b a c`).
    #[error("face {face} repeats vertex {vertex}")]
    RepeatedVertex {
        /// The face.
        face: u32,
        /// The vertex it names twice.
        vertex: u32,
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

impl TopologyError {
    /// Whether this is non-manifold or degenerate topology, which Loop and Catmull-Clark
    /// subdivision take (with OpenSubdiv's rules) and the other schemes refuse: a non-manifold
    /// or inconsistently oriented edge, a non-manifold vertex, a face that repeats a vertex.
    #[must_use]
    pub fn is_nonmanifold(&self) -> bool {
        matches!(self, Self::NonManifold(_) | Self::RepeatedVertex { .. })
    }
}

/// The message of [`TopologyError::NonManifold`]: what subdivision cannot take, in the words
/// `splinekit subdivide` has always used.
fn nonmanifold_message(problem: &NonManifold) -> String {
    match problem {
        NonManifold::Edge { a, b, faces } => {
            format!("edge {a}–{b} is used by {faces:?}: not a manifold, consistently oriented edge")
        }
        NonManifold::Inconsistent { a, b, faces } => {
            format!("edge {a}–{b} is used by {faces:?}: not a manifold, consistently oriented edge")
        }
        NonManifold::Vertex { vertex, fans } => {
            format!("vertex {vertex} is non-manifold: its faces form {fans} separate fans")
        }
    }
}

/// The next corner of a triangle.
#[inline]
pub(super) fn next(i: u32) -> u32 {
    if i == 2 { 0 } else { i + 1 }
}

/// The previous corner of a triangle.
#[inline]
pub(super) fn prev(i: u32) -> u32 {
    if i == 0 { 2 } else { i - 1 }
}

/// `[f(0), f(1), f(2)]`: like `[0, 1, 2].map(f)`, which is not always inlined in the passes.
#[inline(always)]
pub(super) fn three<T>(f: impl Fn(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
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
    /// The first triangle that repeats a vertex, else the first non-manifold or inconsistently
    /// oriented edge, or non-manifold vertex.
    pub fn build(triangles: &[[u32; 3]], num_vertices: usize) -> Result<Self, TopologyError> {
        match Self::build_manifold(triangles, num_vertices) {
            Some(topo) => Ok(topo),
            None => {
                let repeated =
                    |t: &[u32; 3]| [t[0], t[1]].into_iter().find(|&v| v == t[2]).or((t[0] == t[1]).then_some(t[0]));
                if let Some((face, vertex)) =
                    triangles.iter().enumerate().find_map(|(f, t)| repeated(t).map(|v| (f, v)))
                {
                    return Err(TopologyError::RepeatedVertex { face: face as u32, vertex });
                }
                Self::build_checked(triangles, num_vertices)
            }
        }
    }

    /// [`Self::build`] for meshes without problems: `None` at the first sign of one (a
    /// vertex out of range, a degenerate, non-manifold or inconsistently oriented edge, a
    /// vertex whose corners are not one fan), so that [`Self::build_checked`] names it. The
    /// tables are the same as `build_checked`'s: edges numbered in half-edge order and owned by
    /// their first half-edge, starts on the last boundary half-edge leaving the vertex, else
    /// its first half-edge. Every step is a parallel pass ([`leaving_lists`],
    /// [`number_edges`]): everything else is, so serial steps here would take a growing share
    /// of the time as threads are added.
    fn build_manifold(triangles: &[[u32; 3]], nv: usize) -> Option<Self> {
        let nh = 3 * triangles.len();
        if nh >= NONE as usize || nv >= NONE as usize {
            return None;
        }
        let problem = AtomicBool::new(false);
        let fail = || {
            problem.store(true, Ordering::Relaxed);
            NONE
        };
        let (offsets, leaving) = leaving_lists(triangles, nv)?;
        // (half-edge, its head) pairs.
        let out = |v: u32| leaving_from(&offsets, &leaving, v);
        let mut twin = Vec::new();
        (0..nh as u32)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|h| {
                let t = &triangles[(h / 3) as usize];
                let (a, b) = (t[(h % 3) as usize], t[next(h % 3) as usize]);
                // The twin is the one half-edge back from b to a. Two half-edges from a to b
                // are caught from the other side (the search of a half-edge back finds both)
                // or, with none back, by the fan check of a below (neither can be reached
                // from the other by rotating, which crosses an edge only to its twin).
                let mut found = out(b).filter(|&[_, hc]| hc == a);
                match (found.next(), found.next()) {
                    _ if a == b => fail(),
                    (None, _) => NONE,
                    (Some([c, _]), None) => c,
                    (Some(_), Some(_)) => fail(),
                }
            })
            .collect_into_vec(&mut twin);
        if problem.load(Ordering::Relaxed) {
            return None;
        }
        // The starts and the edge numbers only read the twins: side by side, so that on several
        // threads neither waits at the end of its passes. The leaving lists go with the starts,
        // freed before the edges are numbered when there is one thread.
        let tw = &twin;
        let starts = move || {
            let out = |v: u32| leaving_from(&offsets, &leaving, v);
            let mut vertex_start = Vec::new();
            (0..nv as u32)
                .into_par_iter()
                .with_min_len(MIN_RINGS)
                .map(|v| {
                    let corners = offsets[v as usize + 1] - offsets[v as usize];
                    let Some([first, _]) = out(v).next() else { return NONE };
                    let start = out(v).map(|[h, _]| h).filter(|&h| tw[h as usize] == NONE).last().unwrap_or(first);
                    // Every corner must be reached by rotating from the start.
                    let mut h = start;
                    let mut n = 1;
                    loop {
                        let t = tw[(h - h % 3 + prev(h % 3)) as usize];
                        if t == NONE || t == start {
                            break;
                        }
                        h = t;
                        n += 1;
                        if n > corners {
                            return fail();
                        }
                    }
                    if n == corners { start } else { fail() }
                })
                .collect_into_vec(&mut vertex_start);
            vertex_start
        };
        let (vertex_start, (edge_of, edge_owner)) = rayon::join(starts, || number_edges(tw));
        if problem.load(Ordering::Relaxed) {
            return None;
        }
        Some(Self { twin, edge_of, edge_owner, vertex_start })
    }

    /// [`Self::build`] through the mesh [`Adjacency`], which names every problem.
    fn build_checked(triangles: &[[u32; 3]], num_vertices: usize) -> Result<Self, TopologyError> {
        let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
        if let Some(c) = flat.iter().position(|&v| v as usize >= num_vertices) {
            return Err(TopologyError::Index { face: (c / 3) as u32, vertex: flat[c], count: num_vertices });
        }
        let offsets: Vec<u32> = (0..=triangles.len() as u32).map(|f| 3 * f).collect();
        let mut adj = Adjacency::from_faces(&offsets, &flat, num_vertices);
        if let Some(problem) = adj.nonmanifold.first() {
            return Err(TopologyError::NonManifold(problem.clone()));
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
                let fans = adj.fans(&mesh, v as u32).len() as u32;
                return Err(TopologyError::NonManifold(NonManifold::Vertex { vertex: v as u32, fans }));
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
        let level = Table { triangles, topology: self };
        if with_topology {
            let (child, topology) = child_level(&level);
            (child, Some(topology))
        } else {
            (child_triangles(&level), None)
        }
    }
}

/// The half-edges leaving vertex `v` and their heads, `[h, head]`, from [`leaving_lists`].
#[inline]
fn leaving_from<'a>(offsets: &[u32], leaving: &'a [AtomicU64], v: u32) -> impl Iterator<Item = [u32; 2]> + 'a {
    leaving[offsets[v as usize] as usize..offsets[v as usize + 1] as usize]
        .iter()
        .map(|c| c.load(Ordering::Relaxed))
        .map(|c| [c as u32, (c >> 32) as u32])
}

/// The half-edges leaving each vertex, in half-edge order, each as `h | head << 32` (the
/// half-edge and the vertex it points to), and where each vertex's list starts (`nv + 1`
/// offsets); `None` if a triangle refers to a vertex `≥ nv`.
///
/// A counting sort in one chunk of triangles per thread: each chunk counts its corners per
/// vertex, the counts become each chunk's places (a vertex's corners from chunk 0, then those
/// from chunk 1, …: half-edge order), and each chunk writes its corners to its places. The
/// chunks write to places scattered over one table, which safe code can share only as
/// atomics; relaxed atomic stores and loads are plain ones.
fn leaving_lists(triangles: &[[u32; 3]], nv: usize) -> Option<(Vec<u32>, Vec<AtomicU64>)> {
    let per = triangles.len().div_ceil(rayon::current_num_threads()).max(MIN_LEN);
    let mut places: Vec<Vec<u32>> = triangles
        .par_chunks(per)
        .map(|chunk| {
            let mut count = vec![0u32; nv];
            for t in chunk {
                for &v in t {
                    *count.get_mut(v as usize)? += 1;
                }
            }
            Some(count)
        })
        .collect::<Option<_>>()?;
    let mut offsets = Vec::with_capacity(nv + 1);
    let mut at = 0;
    for v in 0..nv {
        offsets.push(at);
        for place in &mut places {
            (place[v], at) = (at, at + place[v]);
        }
    }
    offsets.push(at);
    // Zeroed in parallel: the first touch of fresh pages is the costly part of filling them.
    let mut leaving = Vec::new();
    (0..3 * triangles.len())
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|_| AtomicU64::new(0))
        .collect_into_vec(&mut leaving);
    triangles.par_chunks(per).zip(places.par_iter_mut()).enumerate().for_each(|(c, (chunk, place))| {
        for (f, t) in (c * per..).zip(chunk) {
            for i in 0..3 {
                let k = &mut place[t[i] as usize];
                let h = (3 * f + i) as u64;
                leaving[*k as usize].store(h | u64::from(t[next(i as u32) as usize]) << 32, Ordering::Relaxed);
                *k += 1;
            }
        }
    });
    Some((offsets, leaving))
}

/// Per half-edge its edge, and per edge its owner, from the twins: edges numbered in
/// half-edge order, each owned by its first half-edge (the one without a twin or before it).
///
/// In parallel through a bitmask of the owners, one bit per half-edge: the edge of owner `h`
/// is the number of owners before it — those before its word of 64 bits, counted once, plus
/// the bits below it in its word — and the edge of another half-edge is its twin's, found the
/// same way. Then runs of words number their owners side by side, each from its own start.
fn number_edges(twin: &[u32]) -> (Vec<u32>, Vec<u32>) {
    /// Words per run.
    const RUN: usize = MIN_LEN / 64;
    let nh = twin.len();
    let owns = |h: usize, t: u32| t == NONE || h < t as usize;
    let mut mask = Vec::new();
    twin.par_chunks(64)
        .with_min_len(RUN)
        .enumerate()
        .map(|(w, twins)| {
            // Eight bits at a time, whose shifts are then constants: several times faster.
            // (`NONE` is larger than any half-edge.)
            let h0 = 64 * w as u32;
            let mut eights = twins.chunks_exact(8);
            let (mut m, mut k) = (0u64, 0);
            for t in &mut eights {
                m |= (0..8).fold(0u64, |b, i| b | u64::from(h0 + k + (i as u32) < t[i]) << i) << k;
                k += 8;
            }
            for (i, &t) in (k..).zip(eights.remainder()) {
                m |= u64::from(h0 + i < t) << i;
            }
            m
        })
        .collect_into_vec(&mut mask);
    let mut before = Vec::with_capacity(mask.len() + 1);
    let mut ne = 0;
    for m in &mask {
        before.push(ne);
        ne += m.count_ones();
    }
    before.push(ne);
    let rank = |h: u32| {
        let w = (h / 64) as usize;
        before[w] + (mask[w] & ((1u64 << (h % 64)) - 1)).count_ones()
    };
    // Each run's edges, and the half-edges of each run.
    let mut edge_owner = vec![0u32; ne as usize];
    let mut runs = Vec::with_capacity(mask.len().div_ceil(RUN));
    let mut rest = edge_owner.as_mut_slice();
    for w in (0..mask.len()).step_by(RUN) {
        let end = mask.len().min(w + RUN);
        let (run, tail) = core::mem::take(&mut rest).split_at_mut((before[end] - before[w]) as usize);
        runs.push(run);
        rest = tail;
    }
    let mut edge_of = vec![0u32; nh];
    edge_of.par_chunks_mut(64 * RUN).zip(runs).enumerate().for_each(|(r, (edges, owners))| {
        let h0 = 64 * RUN * r;
        let first = before[RUN * r];
        let mut e = first;
        for (h, (edge, &t)) in (h0..).zip(edges.iter_mut().zip(&twin[h0..])) {
            *edge = if owns(h, t) {
                owners[(e - first) as usize] = h as u32;
                e += 1;
                e - 1
            } else {
                rank(t)
            };
        }
    });
    (edge_of, edge_owner)
}

/// One level's triangles and tables, read by the passes that make the next levels.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Table<'a> {
    /// The triangles.
    pub triangles: &'a [[u32; 3]],
    /// The tables.
    pub topology: &'a Topology,
}

impl Table<'_> {
    /// Number of vertices.
    #[inline]
    pub(crate) fn num_vertices(&self) -> usize {
        self.topology.vertex_start.len()
    }
    /// Number of edges.
    #[inline]
    pub(crate) fn num_edges(&self) -> usize {
        self.topology.edge_owner.len()
    }
    /// Number of triangles.
    #[inline]
    pub(crate) fn num_faces(&self) -> usize {
        self.triangles.len()
    }
    /// Triangle `f`.
    #[inline]
    pub(crate) fn tri(&self, f: u32) -> [u32; 3] {
        self.triangles[f as usize]
    }
    /// The twin of half-edge `h`, or [`NONE`].
    #[inline]
    pub(crate) fn twin(&self, h: u32) -> u32 {
        self.topology.twin[h as usize]
    }
    /// The edge of half-edge `h`.
    #[inline]
    pub(crate) fn edge_of(&self, h: u32) -> u32 {
        self.topology.edge_of[h as usize]
    }
    /// The owner half-edge of edge `e` (its first half-edge).
    #[inline]
    pub(crate) fn edge_owner(&self, e: u32) -> u32 {
        self.topology.edge_owner[e as usize]
    }
    /// The start half-edge of vertex `v`, or [`NONE`].
    #[inline]
    pub(crate) fn vertex_start(&self, v: u32) -> u32 {
        self.topology.vertex_start[v as usize]
    }
    /// The edges of the half-edges of triangle `f`.
    #[inline]
    pub(crate) fn face_edges(&self, f: u32) -> [u32; 3] {
        let e = &self.topology.edge_of[3 * f as usize..3 * f as usize + 3];
        [e[0], e[1], e[2]]
    }
    /// The twins of the half-edges of triangle `f`.
    #[inline]
    pub(crate) fn face_twins(&self, f: u32) -> [u32; 3] {
        let t = &self.topology.twin[3 * f as usize..3 * f as usize + 3];
        [t[0], t[1], t[2]]
    }
}

/// The triangles of the child level of `level`: triangle `f` becomes `4f .. 4f + 4`.
pub(crate) fn child_triangles(level: &Table<'_>) -> Vec<[u32; 3]> {
    let nv = level.num_vertices() as u32;
    let mut child = vec![[0u32; 3]; 4 * level.num_faces()];
    child.par_chunks_mut(4).with_min_len(MIN_LEN).enumerate().for_each(|(f, out)| {
        let f = f as u32;
        let t = level.tri(f);
        let m = [nv + level.edge_of(3 * f), nv + level.edge_of(3 * f + 1), nv + level.edge_of(3 * f + 2)];
        out[0] = [t[0], m[0], m[2]];
        out[1] = [t[1], m[1], m[0]];
        out[2] = [t[2], m[2], m[1]];
        out[3] = m;
    });
    child
}

/// The triangles and stored tables of the child level of `level` (three parallel passes: over
/// faces, edges and vertices).
pub(crate) fn child_level(level: &Table<'_>) -> (Vec<[u32; 3]>, Topology) {
    let nv = level.num_vertices();
    let ne = level.num_edges();
    let nh = 3 * level.num_faces();
    let mut triangles = vec![[0u32; 3]; 4 * level.num_faces()];
    let mut twin = vec![0u32; 4 * nh];
    let mut edge_of = vec![0u32; 4 * nh];
    triangles
        .par_chunks_mut(4)
        .zip(twin.par_chunks_mut(12))
        .zip(edge_of.par_chunks_mut(12))
        .with_min_len(MIN_LEN)
        .enumerate()
        .for_each(|(f, ((out, tw), eo))| {
            let t = level.tri(f as u32);
            let ef = level.face_edges(f as u32);
            let m = ef.map(|e| nv as u32 + e);
            out[0] = [t[0], m[0], m[2]];
            out[1] = [t[1], m[1], m[0]];
            out[2] = [t[2], m[2], m[1]];
            out[3] = m;
            let base = 4 * 3 * f as u32;
            let hh = |c: u32, k: u32| base + 3 * c + k;
            for i in 0..3u32 {
                let h = 3 * f as u32 + i;
                let (first, second) = ((3 * i) as usize, (3 * next(i) + 2) as usize);
                let t = level.twin(h);
                if t == NONE {
                    tw[first] = NONE;
                    tw[second] = NONE;
                } else {
                    let (g, j) = (t / 3, t % 3);
                    tw[first] = 12 * g + 3 * next(j) + 2;
                    tw[second] = 12 * g + 3 * j;
                }
                let e = 2 * ef[i as usize];
                let own = u32::from(t == NONE || h < t);
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
        });
    // Split edges 2e, 2e + 1 (the owner's halves), then the interior edges 3f + i.
    let mut edge_owner = Vec::new();
    (0..(2 * ne + nh) as u32)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|e| {
            if e < 2 * ne as u32 {
                let h = level.edge_owner(e / 2);
                let (f, i) = (h / 3, h % 3);
                if e % 2 == 0 { 12 * f + 3 * i } else { 12 * f + 3 * next(i) + 2 }
            } else {
                let r = e - 2 * ne as u32;
                12 * (r / 3) + 3 * (r % 3) + 1
            }
        })
        .collect_into_vec(&mut edge_owner);
    // Even vertices start on the first half of their start; odd ones on the second half of
    // their edge's owner (a boundary half-edge on a boundary edge).
    let mut vertex_start = Vec::new();
    (0..(nv + ne) as u32)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| {
            if v < nv as u32 {
                let h = level.vertex_start(v);
                if h == NONE { NONE } else { 12 * (h / 3) + 3 * (h % 3) }
            } else {
                let h = level.edge_owner(v - nv as u32);
                12 * (h / 3) + 3 * next(h % 3) + 2
            }
        })
        .collect_into_vec(&mut vertex_start);
    (triangles, Topology { twin, edge_of, edge_owner, vertex_start })
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
            // The fast build gives the tables the checked one does.
            assert_eq!(Some(&rebuilt), Topology::build_manifold(&child, t.num_vertices()).as_ref());
            assert_eq!(rebuilt, Topology::build_checked(&child, t.num_vertices()).unwrap());
            assert_eq!(t.twin, rebuilt.twin);
            assert_eq!(t.num_edges(), rebuilt.num_edges());
            for h in 0..t.twin.len() {
                let e = t.edge_of[h] as usize;
                let o = t.edge_owner[e] as usize;
                assert!(o == h || t.twin[h] as usize == o, "owner of the edge of {h}");
                assert_eq!(o == h, t.twin[h] == NONE || h < t.twin[h] as usize, "first half-edge owns {e}");
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

    /// Large enough for several chunks and runs in [`leaving_lists`] and [`number_edges`], on
    /// any number of threads the same tables as the checked build's.
    #[test]
    fn parallel_build_matches_checked() {
        let mut tris = octahedron();
        let mut topo = Topology::build(&tris, 6).unwrap();
        for _ in 0..6 {
            let (child, t) = topo.refine(&tris, true);
            (tris, topo) = (child, t.unwrap());
        }
        let nv = topo.num_vertices();
        // Scatter the vertex numbers, and open the surface: drop what became of base triangle
        // 5 (some vertices are then on no triangle).
        let perm: Vec<u32> = (0..nv as u32).map(|v| (v * 7919) % nv as u32).collect();
        assert_eq!(perm.iter().collect::<std::collections::HashSet<_>>().len(), nv);
        let n = tris.len() / 8;
        let scattered: Vec<[u32; 3]> =
            tris[..5 * n].iter().chain(&tris[6 * n..]).map(|t| t.map(|v| perm[v as usize])).collect();
        for (mesh, label) in [(&tris, "closed"), (&scattered, "open, scattered")] {
            let checked = Topology::build_checked(mesh, nv).unwrap();
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let fast = pool.install(|| Topology::build_manifold(mesh, nv));
                assert_eq!(fast.as_ref(), Some(&checked), "{label}, {threads} threads");
            }
        }
        // A vertex out of range in the last chunk.
        let mut bad = tris.clone();
        bad.last_mut().unwrap()[1] = nv as u32;
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        assert_eq!(pool.install(|| Topology::build_manifold(&bad, nv)), None);
    }

    #[test]
    fn problems_are_errors() {
        let err = Topology::build(&[[0, 1, 2], [0, 3, 4]], 5).unwrap_err();
        assert_eq!(err, TopologyError::NonManifold(NonManifold::Vertex { vertex: 0, fans: 2 }));
        let err = Topology::build(&[[0, 1, 2], [0, 1, 3]], 4).unwrap_err();
        // both triangles run 0 → 1
        assert!(matches!(err, TopologyError::NonManifold(NonManifold::Inconsistent { a: 0, b: 1, faces: [0, 1] })));
        assert_eq!(err.to_string(), "edge 0–1 is used by [0, 1]: not a manifold, consistently oriented edge");
        let err = Topology::build(&[[0, 1, 2], [1, 0, 3], [0, 1, 4]], 5).unwrap_err();
        assert!(matches!(err, TopologyError::NonManifold(NonManifold::Edge { a: 0, b: 1, .. })));
        let err = Topology::build(&[[0, 1, 7]], 3).unwrap_err();
        assert_eq!(err, TopologyError::Index { face: 0, vertex: 7, count: 3 });
    }
}
