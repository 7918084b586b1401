//! What both the scan and the repair build on the analysed faces: the faces themselves
//! ([`Kept`]), their undirected edges ([`Edges`]), a consistent orientation found by walking
//! across edges ([`Orientation`]), and the union-find that groups corners into fans.

use std::collections::VecDeque;

use crate::mesh::{Adjacency, NONE, NonManifold, PolyMesh};

/// The analysed faces (all faces when every one qualifies, borrowed then).
pub(super) struct Kept<'a> {
    pub(super) offsets: std::borrow::Cow<'a, [u32]>,
    pub(super) verts: std::borrow::Cow<'a, [u32]>,
    /// Kept face → mesh face; `None` when all faces are kept.
    pub(super) face_map: Option<Vec<u32>>,
}

impl<'a> Kept<'a> {
    pub(super) fn new(mesh: &'a PolyMesh, keep: &[bool]) -> Self {
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

    pub(super) fn num_faces(&self) -> usize {
        self.offsets.len() - 1
    }

    pub(super) fn face(&self, f: usize) -> &[u32] {
        &self.verts[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    pub(super) fn mesh_face(&self, f: u32) -> u32 {
        self.face_map.as_ref().map_or(f, |m| m[f as usize])
    }

    /// The face of corner `c` (binary search over the offsets).
    pub(super) fn face_of(&self, c: u32) -> usize {
        self.offsets.partition_point(|&o| o <= c) - 1
    }

    /// The corner after `c` in its face.
    pub(super) fn next(&self, c: u32) -> u32 {
        let f = self.face_of(c);
        if c + 1 == self.offsets[f + 1] { self.offsets[f] } else { c + 1 }
    }

    /// The corner before `c` in its face.
    pub(super) fn prev(&self, c: u32) -> u32 {
        let f = self.face_of(c);
        if c == self.offsets[f] { self.offsets[f + 1] - 1 } else { c - 1 }
    }
}

/// Joins, at both ends of the edge of corners `c` and `m`, the two faces' corners at that
/// vertex.
pub(super) fn join_across(kept: &Kept<'_>, sets: &mut UnionFind, c: u32, m: u32) {
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
pub(super) struct Edges {
    /// Per corner, the other side of a two-sided edge (opposite or same direction), or [`NONE`].
    pub(super) mate: Vec<u32>,
    /// Per corner, whether it lies on a non-manifold edge.
    pub(super) nonmanifold: Vec<bool>,
    /// One corner per edge (its first side in corner order).
    pub(super) first_side: Vec<u32>,
    /// Number of one-sided edges.
    pub(super) num_boundary: usize,
}

impl Edges {
    pub(super) fn new(kept: &Kept<'_>, adj: &Adjacency) -> Self {
        let nc = kept.verts.len();
        let mut mate = adj.twin.clone();
        let mut nonmanifold = vec![false; nc];
        let mut names_edge = vec![false; nc];
        for p in &adj.nonmanifold {
            match *p {
                NonManifold::Edge { a, b, .. } => {
                    let corners = adj.sides(a, b);
                    for &c in &corners {
                        nonmanifold[c as usize] = true;
                    }
                    names_edge[corners[0] as usize] = true;
                }
                NonManifold::Inconsistent { a, b, .. } => {
                    let sides = adj.sides(a, b);
                    let (c, d) = (sides[0], sides[1]);
                    mate[c as usize] = d;
                    mate[d as usize] = c;
                }
                NonManifold::Vertex { .. } => {}
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

    pub(super) fn is_boundary(&self, c: u32) -> bool {
        self.mate[c as usize] == NONE && !self.nonmanifold[c as usize]
    }
}

/// Face orientations found by a breadth-first walk across two-sided edges.
pub(super) struct Orientation {
    /// Per kept face: whether it is flipped relative to the first face of its group.
    pub(super) flipped: Vec<bool>,
    /// Per kept face: its group (faces joined through two-sided edges).
    pub(super) group: Vec<u32>,
    /// Per group: whether the walk met a contradiction (non-orientable).
    pub(super) conflict: Vec<bool>,
    /// Per group: whether the flipped faces are the majority (then the others are to flip),
    /// on a tie not.
    pub(super) majority_flipped: Vec<bool>,
    /// Per group: whether to leave its faces as they are. True for a non-orientable group
    /// where flipping the minority would not leave fewer inconsistent edges than the input
    /// has (a well-made Möbius strip keeps its one seam where it is).
    pub(super) keep: Vec<bool>,
}

impl Orientation {
    pub(super) fn new(kept: &Kept<'_>, adj: &Adjacency, edges: &Edges) -> Self {
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
    pub(super) fn flip_majority(&self, f: usize) -> bool {
        self.flipped[f] != self.majority_flipped[self.group[f] as usize]
    }

    /// Whether kept face `f` is to be flipped: it disagrees with the majority of its group,
    /// and the group is orientable or flipping helps (see [`Self::keep`]).
    pub(super) fn flip(&self, f: usize) -> bool {
        self.flip_majority(f) && !self.keep[self.group[f] as usize]
    }
}

/// Union-find over `0..n` with path halving and union by index (smaller root wins, so
/// roots are deterministic).
pub(super) struct UnionFind(Vec<u32>);

impl UnionFind {
    pub(super) fn new(n: usize) -> Self {
        Self((0..n as u32).collect())
    }

    pub(super) fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let up = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = up;
            x = up;
        }
        x
    }

    pub(super) fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.0[hi as usize] = lo;
        }
    }
}
