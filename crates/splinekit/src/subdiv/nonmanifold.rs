//! Loop and Catmull-Clark subdivision of non-manifold and degenerate meshes, with
//! OpenSubdiv's rules (its `Far::TopologyRefinerFactory` and `Vtr` refinement): edges of more
//! than two faces, edges whose two faces run the same way (a fold-over), vertices whose faces
//! form several fans (a bowtie, two cones touching at their tips), faces that name a vertex
//! more than once (a quad pole `a b a c`, a triangle `a a b`).
//!
//! **Topology.** Edges are made face by face, corner by corner, from the half-edge of each
//! corner to the next one, as OpenSubdiv does: a half-edge joins the first edge made between
//! its two vertices, except that a half-edge whose two ends are one vertex, or that runs along
//! an edge the same face already uses, gets an edge of its own. An edge is *non-manifold* when
//! it has more than two faces, two faces running the same way along it, both ends at one
//! vertex, or a face that uses it twice; so is a vertex at either end of one, and a vertex
//! whose faces do not form a single fan.
//!
//! **Rules.** Non-manifold edges are infinitely sharp (as boundary edges are), and so is every
//! non-manifold vertex (a corner: it stays where it is), except one in the middle of an
//! interior non-manifold crease — two non-manifold edges, no boundary edge, more faces than
//! edges, such as a vertex where three sheets meet along a curve — whose rule comes from its
//! sharp edges: a crease. Everything else follows the creases' rules of [`crease`](super::crease)
//! and the scheme's smooth rules, the same for a vertex of valence 2 as for any other.
//!
//! **Refinement.** Each level is made from the one above as OpenSubdiv's refinement makes it,
//! not rebuilt from the child faces: every edge is split in two halves that keep its tags, so
//! the two halves of an edge that a face uses twice stay two edges (and the vertices at their
//! middles two vertices, at the same place). Numbering: the parent's vertices, one vertex per
//! edge, then (Catmull-Clark) one per face; the child faces as the manifold schemes number
//! them.
//!
//! This path builds a sparse matrix per level, so it is slower than the manifold one; meshes
//! that are manifold never take it.

use glam::DVec3;

use super::counts::{self, Counts};
use super::crease::{CreasedLevel, Creases, INFINITELY_SHARP, Level, Rule, Values, creased_level, rule, sharpness};
use super::error::{SubdivError, indices_in_range, triangles_only};
use super::matrix::{Builder, SubdivisionMatrix};
use super::options::{BoundaryRule, CatmullClarkOptions, CreasingMethod, LoopOptions, Rules, TriangleSubdivision};
use super::rings::Rings;
use crate::mesh::{NONE, PolyMesh};

/// How faces are split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Split {
    /// Loop: every triangle into four.
    Triangles,
    /// Catmull-Clark: every n-gon into n quads.
    Quads,
}

/// Whether Loop and Catmull-Clark subdivision take `mesh` through OpenSubdiv's rules for
/// non-manifold topology (see [`loop_subdivide`](super::loop_subdivide)): a face names a vertex
/// twice, an edge has more than two faces or two faces running the same way, or a vertex's
/// faces form several fans. `false` for a mesh with a vertex index out of range or a face of
/// fewer than three corners, which no scheme takes.
#[must_use]
pub fn is_nonmanifold(mesh: &PolyMesh) -> bool {
    if mesh.faces().any(|f| f.len() < 3) || indices_in_range(mesh).is_err() {
        return false;
    }
    matches!(Rings::new(mesh), Err(SubdivError::Topology(e)) if e.is_nonmanifold())
}

/// One level of a mesh with OpenSubdiv's topology (see the [module docs](self)).
#[derive(Clone, Debug)]
pub(super) struct GeneralLevel {
    num_vertices: usize,
    face_offsets: Vec<u32>,
    face_vertices: Vec<u32>,
    /// Per corner: its face.
    face_of: Vec<u32>,
    /// Per corner: the edge of its half-edge (to the next corner).
    face_edges: Vec<u32>,
    /// Per edge: its two ends.
    edge_vertices: Vec<[u32; 2]>,
    /// Per edge: the corners along it (CSR).
    edge_offsets: Vec<u32>,
    edge_corners: Vec<u32>,
    /// Per vertex: its corners (CSR).
    vertex_offsets: Vec<u32>,
    vertex_corners: Vec<u32>,
    /// Per vertex: its edges (an edge from a vertex to itself twice), with the end of the edge
    /// the vertex is (CSR).
    vertex_edge_offsets: Vec<u32>,
    vertex_edges: Vec<(u32, u8)>,
    /// Per edge: infinitely sharp by topology (a boundary or non-manifold edge).
    edge_sharp: Vec<bool>,
    /// Per vertex: infinitely sharp by topology (a non-manifold vertex made a corner).
    vertex_sharp: Vec<bool>,
}

/// CSR lists of `items` grouped by `key(item)` over `n` keys, in item order.
fn group(n: usize, items: impl Iterator<Item = (u32, u32)> + Clone) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; n + 1];
    for (k, _) in items.clone() {
        offsets[k as usize + 1] += 1;
    }
    for k in 0..n {
        offsets[k + 1] += offsets[k];
    }
    let mut fill = offsets.clone();
    let mut out = vec![0u32; offsets[n] as usize];
    for (k, x) in items {
        out[fill[k as usize] as usize] = x;
        fill[k as usize] += 1;
    }
    (offsets, out)
}

impl GeneralLevel {
    /// The base level of `mesh`, tagged as OpenSubdiv's factory tags it.
    pub(super) fn base(mesh: &PolyMesh) -> Result<Self, SubdivError> {
        indices_in_range(mesh)?;
        let nv = mesh.num_vertices();
        let nc = mesh.face_vertices.len();
        let mut face_edges = Vec::with_capacity(nc);
        let mut edge_vertices: Vec<[u32; 2]> = Vec::new();
        let mut last_face: Vec<u32> = Vec::new();
        let mut face_count: Vec<u32> = Vec::new();
        let mut at: Vec<Vec<u32>> = vec![Vec::new(); nv];
        let mut nonmanifold: Vec<u32> = Vec::new();
        for (f, w) in mesh.face_offsets.windows(2).enumerate() {
            let (s, e) = (w[0] as usize, w[1] as usize);
            for c in s..e {
                let v0 = mesh.face_vertices[c];
                let v1 = mesh.face_vertices[if c + 1 == e { s } else { c + 1 }];
                let mut edge = None;
                if v0 == v1 {
                    nonmanifold.push(edge_vertices.len() as u32);
                } else {
                    edge = at[v0 as usize].iter().copied().find(|&x| edge_vertices[x as usize].contains(&v1));
                }
                if let Some(x) = edge {
                    if last_face[x as usize] == f as u32 {
                        // the face uses this edge already: a new edge for this side
                        nonmanifold.extend([x, edge_vertices.len() as u32]);
                        edge = None;
                    } else if face_count[x as usize] > 1 || edge_vertices[x as usize][0] == v0 {
                        nonmanifold.push(x);
                    }
                }
                let x = edge.unwrap_or_else(|| {
                    let x = edge_vertices.len() as u32;
                    edge_vertices.push([v0, v1]);
                    last_face.push(NONE);
                    face_count.push(0);
                    at[v0 as usize].push(x);
                    at[v1 as usize].push(x);
                    x
                });
                face_count[x as usize] += 1;
                last_face[x as usize] = f as u32;
                face_edges.push(x);
            }
        }
        let mut level = Self::from_faces(
            nv,
            mesh.face_offsets.clone(),
            mesh.face_vertices.clone(),
            face_edges,
            edge_vertices,
            Some(&at),
        );
        let ne = level.edge_vertices.len();
        let mut edge_nonmanifold = vec![false; ne];
        let mut vertex_nonmanifold = vec![false; nv];
        for &x in &nonmanifold {
            edge_nonmanifold[x as usize] = true;
            for v in level.edge_vertices[x as usize] {
                vertex_nonmanifold[v as usize] = true;
            }
        }
        for v in 0..nv as u32 {
            if !vertex_nonmanifold[v as usize] && !level.is_one_fan(v) {
                vertex_nonmanifold[v as usize] = true;
            }
        }
        level.edge_sharp = (0..ne).map(|x| level.edge_len(x as u32) < 2 || edge_nonmanifold[x]).collect();
        level.vertex_sharp = (0..nv as u32)
            .map(|v| {
                if !vertex_nonmanifold[v as usize] {
                    return false;
                }
                let edges = level.edges_of(v);
                let count = |p: &dyn Fn(u32) -> bool| edges.iter().filter(|&&(x, _)| p(x)).count();
                let nm = count(&|x| edge_nonmanifold[x as usize]);
                let boundary = count(&|x| level.edge_len(x) < 2);
                // an interior non-manifold crease keeps its rule; every other non-manifold vertex
                // is a corner
                !(nm == 2 && boundary == 0 && level.corners_of(v).len() > edges.len())
            })
            .collect();
        Ok(level)
    }

    /// The tables from the faces and their edges; `at` lists each vertex's edges in order
    /// (else they are collected from the edges, each at its two ends).
    fn from_faces(
        num_vertices: usize,
        face_offsets: Vec<u32>,
        face_vertices: Vec<u32>,
        face_edges: Vec<u32>,
        edge_vertices: Vec<[u32; 2]>,
        at: Option<&[Vec<u32>]>,
    ) -> Self {
        let ne = edge_vertices.len();
        let mut face_of = vec![0u32; face_vertices.len()];
        for (f, w) in face_offsets.windows(2).enumerate() {
            face_of[w[0] as usize..w[1] as usize].fill(f as u32);
        }
        let corners = || (0..face_vertices.len() as u32).map(|c| (face_edges[c as usize], c));
        let (edge_offsets, edge_corners) = group(ne, corners());
        let (vertex_offsets, vertex_corners) =
            group(num_vertices, (0..face_vertices.len() as u32).map(|c| (face_vertices[c as usize], c)));
        let mut vertex_edge_offsets = vec![0u32];
        let mut vertex_edges = Vec::new();
        match at {
            Some(at) => {
                for (v, list) in at.iter().enumerate() {
                    let mut seen = Vec::new();
                    for &x in list {
                        let [a, b] = edge_vertices[x as usize];
                        // an edge from the vertex to itself is listed twice: ends 0, then 1
                        let end = if a == b { u8::from(seen.contains(&x)) } else { u8::from(b == v as u32) };
                        seen.push(x);
                        vertex_edges.push((x, end));
                    }
                    vertex_edge_offsets.push(vertex_edges.len() as u32);
                }
            }
            None => {
                let ends = (0..ne as u32)
                    .flat_map(|x| [0u8, 1].map(|k| (edge_vertices[x as usize][k as usize], 2 * x + u32::from(k))));
                let (offsets, items) = group(num_vertices, ends);
                vertex_edge_offsets = offsets;
                vertex_edges = items.into_iter().map(|h| (h / 2, (h % 2) as u8)).collect();
            }
        }
        Self {
            num_vertices,
            face_offsets,
            face_vertices,
            face_of,
            face_edges,
            edge_vertices,
            edge_offsets,
            edge_corners,
            vertex_offsets,
            vertex_corners,
            vertex_edge_offsets,
            vertex_edges,
            edge_sharp: vec![false; ne],
            vertex_sharp: vec![false; num_vertices],
        }
    }

    fn num_faces(&self) -> usize {
        self.face_offsets.len() - 1
    }

    /// The number of corners of face `f`.
    fn face_len(&self, f: u32) -> usize {
        (self.face_offsets[f as usize + 1] - self.face_offsets[f as usize]) as usize
    }

    /// Number of vertices.
    pub(super) fn num_vertices(&self) -> usize {
        self.num_vertices
    }

    /// The counts of this level.
    fn counts(&self) -> Counts {
        Counts {
            vertices: self.num_vertices as u64,
            edges: self.edge_vertices.len() as u64,
            faces: self.num_faces() as u64,
            corners: self.face_vertices.len() as u64,
        }
    }

    /// The faces along edge `x` (counted with repeats).
    fn edge_len(&self, x: u32) -> usize {
        (self.edge_offsets[x as usize + 1] - self.edge_offsets[x as usize]) as usize
    }

    fn edge_corners_of(&self, x: u32) -> &[u32] {
        &self.edge_corners[self.edge_offsets[x as usize] as usize..self.edge_offsets[x as usize + 1] as usize]
    }

    fn corners_of(&self, v: u32) -> &[u32] {
        &self.vertex_corners[self.vertex_offsets[v as usize] as usize..self.vertex_offsets[v as usize + 1] as usize]
    }

    fn edges_of(&self, v: u32) -> &[(u32, u8)] {
        &self.vertex_edges
            [self.vertex_edge_offsets[v as usize] as usize..self.vertex_edge_offsets[v as usize + 1] as usize]
    }

    /// The far end of edge `x` from its end `end`.
    fn far(&self, x: u32, end: u8) -> u32 {
        self.edge_vertices[x as usize][1 - end as usize]
    }

    /// The corner before `c` in its face.
    fn prev(&self, c: u32) -> u32 {
        let f = self.face_of[c as usize] as usize;
        if c == self.face_offsets[f] { self.face_offsets[f + 1] - 1 } else { c - 1 }
    }

    /// Whether the corners of vertex `v` (on no non-manifold edge) form one fan through edges
    /// of two faces, as OpenSubdiv's ordering of a vertex's faces and edges checks.
    fn is_one_fan(&self, v: u32) -> bool {
        let corners = self.corners_of(v);
        let edges = self.edges_of(v).len();
        if corners.is_empty() || edges < 2 || edges > corners.len() + 1 {
            return false;
        }
        let across = |c: u32| {
            let arriving = self.face_edges[self.prev(c) as usize];
            let pair = self.edge_corners_of(arriving);
            pair.iter().copied().find(|&d| d != self.prev(c)).filter(|_| pair.len() == 2)
        };
        let start = corners.iter().copied().find(|&c| self.edge_len(self.face_edges[c as usize]) == 1);
        let start = start.unwrap_or(corners[0]);
        let (mut c, mut n) = (start, 1);
        while let Some(d) = across(c) {
            if d == start || n > corners.len() {
                break;
            }
            c = d;
            n += 1;
        }
        n == corners.len()
    }

    /// `w ×` the centre of face `f`.
    fn face_point(&self, f: u32, w: f64, b: &mut Builder) {
        let (s, e) = (self.face_offsets[f as usize], self.face_offsets[f as usize + 1]);
        let share = w / f64::from(e - s);
        for c in s..e {
            b.add(self.face_vertices[c as usize], share);
        }
    }

    /// The half of edge `x` at the end where corner `c`'s vertex is: leaving along it when
    /// `leaving`, else arriving (the two halves of an edge from a vertex to itself).
    fn half(&self, x: u32, c: u32, leaving: bool) -> u32 {
        let [a, b] = self.edge_vertices[x as usize];
        let v = self.face_vertices[c as usize];
        let first = if a == b { leaving } else { a == v };
        2 * x + u32::from(!first)
    }

    /// The child level (see the [module docs](self)).
    pub(super) fn refine(&self, split: Split) -> Self {
        let (nv, ne, nf) = (self.num_vertices as u32, self.edge_vertices.len() as u32, self.num_faces() as u32);
        let nc = self.face_vertices.len();
        let m = |x: u32| nv + x;
        let mut edge_vertices = Vec::with_capacity(2 * ne as usize + nc);
        for (x, &[a, b]) in self.edge_vertices.iter().enumerate() {
            edge_vertices.push([a, m(x as u32)]);
            edge_vertices.push([m(x as u32), b]);
        }
        let mut face_vertices = Vec::new();
        let mut face_edges = Vec::new();
        let interior = |c: u32| 2 * ne + c;
        match split {
            Split::Quads => {
                let fp = |f: u32| nv + ne + f;
                for c in 0..nc as u32 {
                    let (f, p) = (self.face_of[c as usize], self.prev(c));
                    let (e, ep) = (self.face_edges[c as usize], self.face_edges[p as usize]);
                    edge_vertices.push([m(e), fp(f)]);
                    face_vertices.extend([self.face_vertices[c as usize], m(e), fp(f), m(ep)]);
                    face_edges.extend([self.half(e, c, true), interior(c), interior(p), self.half(ep, c, false)]);
                }
            }
            Split::Triangles => {
                for f in 0..nf {
                    let c0 = 3 * f;
                    let e = [0, 1, 2].map(|i| self.face_edges[(c0 + i) as usize]);
                    let v = [0, 1, 2].map(|i| self.face_vertices[(c0 + i) as usize]);
                    for i in 0..3 {
                        let p = (i + 2) % 3;
                        edge_vertices.push([m(e[i]), m(e[p])]);
                        face_vertices.extend([v[i], m(e[i]), m(e[p])]);
                        let c = c0 + i as u32;
                        face_edges.extend([self.half(e[i], c, true), interior(c), self.half(e[p], c, false)]);
                    }
                    face_vertices.extend([m(e[0]), m(e[1]), m(e[2])]);
                    face_edges.extend([interior(c0 + 1), interior(c0 + 2), interior(c0)]);
                }
            }
        }
        let corners = face_vertices.len() as u32;
        let size = if split == Split::Quads { 4 } else { 3 };
        let face_offsets = (0..=corners / size).map(|f| size * f).collect();
        let num_vertices = (nv + ne + if split == Split::Quads { nf } else { 0 }) as usize;
        let mut child = Self::from_faces(num_vertices, face_offsets, face_vertices, face_edges, edge_vertices, None);
        for x in 0..ne as usize {
            child.edge_sharp[2 * x] = self.edge_sharp[x];
            child.edge_sharp[2 * x + 1] = self.edge_sharp[x];
        }
        child.vertex_sharp[..nv as usize].copy_from_slice(&self.vertex_sharp);
        child
    }

    /// The faces as a mesh with `positions`.
    pub(super) fn to_mesh(&self, positions: Vec<DVec3>, colors: Vec<DVec3>) -> PolyMesh {
        PolyMesh {
            positions,
            colors,
            face_offsets: self.face_offsets.clone(),
            face_vertices: self.face_vertices.clone(),
            normals: None,
            uvs: None,
        }
    }
}

/// A level with its scheme's smooth rules, as the crease rules read it.
struct Scheme<'a> {
    level: &'a GeneralLevel,
    split: Split,
    rules: &'a Rules,
    triangles: TriangleSubdivision,
}

impl Level for Scheme<'_> {
    fn num_vertices(&self) -> usize {
        self.level.num_vertices
    }

    fn num_edges(&self) -> usize {
        self.level.edge_vertices.len()
    }

    fn edge_ends(&self, e: u32) -> [u32; 2] {
        self.level.edge_vertices[e as usize]
    }

    fn is_boundary(&self, e: u32) -> bool {
        self.level.edge_sharp[e as usize]
    }

    fn is_corner(&self, v: u32) -> bool {
        self.level.vertex_sharp[v as usize]
    }

    fn edges_at(&self, v: u32, out: &mut Vec<(u32, u32)>) -> usize {
        out.clear();
        out.extend(self.level.edges_of(v).iter().map(|&(x, end)| (x, self.level.far(x, end))));
        self.level.corners_of(v).len()
    }

    fn smooth_vertex(&self, v: u32, scale: f64, b: &mut Builder) {
        let level = self.level;
        let n = level.corners_of(v).len();
        match self.split {
            Split::Triangles => {
                let beta = self.rules.beta(n as u32);
                b.add(v, scale * (1.0 - n as f64 * beta));
                for &(x, end) in level.edges_of(v) {
                    b.add(level.far(x, end), scale * beta);
                }
            }
            Split::Quads => {
                let nf = n as f64;
                b.add(v, scale * (nf - 2.0) / nf);
                let w = scale / (nf * nf);
                for &(x, end) in level.edges_of(v) {
                    b.add(level.far(x, end), w);
                }
                for &c in level.corners_of(v) {
                    level.face_point(level.face_of[c as usize], w, b);
                }
            }
        }
    }

    fn smooth_edge(&self, e: u32, scale: f64, b: &mut Builder) {
        let level = self.level;
        let [v0, v1] = level.edge_vertices[e as usize];
        let corners = level.edge_corners_of(e);
        let size = |c: u32| level.face_len(level.face_of[c as usize]);
        let (ends, faces) = match (self.split, corners) {
            (Split::Triangles, _) => (0.375, 0.125),
            (Split::Quads, &[c0, c1]) => self.triangles.edge_weights(size(c0), size(c1)).unwrap_or((0.25, 0.25)),
            (Split::Quads, _) => (0.25, 0.25),
        };
        b.add(v0, scale * ends);
        b.add(v1, scale * ends);
        for &c in level.edge_corners_of(e) {
            match self.split {
                Split::Triangles => b.add(level.face_vertices[level.prev(c) as usize], scale * faces),
                Split::Quads => level.face_point(level.face_of[c as usize], scale * faces, b),
            }
        }
    }

    fn more_rows(&self, b: &mut Builder) {
        if self.split == Split::Quads {
            for f in 0..self.level.num_faces() as u32 {
                self.level.face_point(f, 1.0, b);
                b.end_row();
            }
        }
    }
}

/// The vertex counts of levels `0 .. levels` of `split` on the non-manifold `mesh`, given to
/// `visit` in order: where the vertices of levels `1 ..= levels` start (the levels' tables
/// only, no values).
///
/// # Errors
/// As [`GeneralLevel::base`].
pub(super) fn level_vertices(
    mesh: &PolyMesh,
    split: Split,
    levels: usize,
    mut visit: impl FnMut(usize),
) -> Result<(), SubdivError> {
    let mut level = GeneralLevel::base(mesh)?;
    for depth in 1..=levels {
        visit(level.num_vertices());
        if depth < levels {
            level = level.refine(split);
        }
    }
    Ok(())
}

/// The settings of one subdivision of a non-manifold mesh: the split, the weights (Loop's β,
/// unused by Catmull-Clark), the boundary rule, the creases of the base mesh and how their
/// sharpness is carried.
pub(super) struct General<'a> {
    pub(super) split: Split,
    pub(super) rules: Rules,
    pub(super) boundary: BoundaryRule,
    /// Catmull-Clark's edge points next to triangles.
    pub(super) triangles: TriangleSubdivision,
    pub(super) creases: &'a Creases,
    pub(super) method: CreasingMethod,
}

impl<'a> General<'a> {
    /// Loop subdivision with `options` (its weights and boundary rule).
    pub(super) fn loop_scheme(options: &LoopOptions, creases: &'a Creases, method: CreasingMethod) -> Self {
        let (rules, boundary) = (Rules::new(options), options.boundary);
        Self { split: Split::Triangles, rules, boundary, triangles: TriangleSubdivision::Catmark, creases, method }
    }

    /// Catmull-Clark subdivision with `options` (its boundary rule and triangle rule).
    pub(super) fn catmark(options: &CatmullClarkOptions, creases: &'a Creases, method: CreasingMethod) -> Self {
        let rules = Rules::new(&LoopOptions::default());
        let (boundary, triangles) = (options.boundary, options.triangles);
        Self { split: Split::Quads, rules, boundary, triangles, creases, method }
    }

    /// Walks `levels` levels of subdivision of `mesh`, giving each level's matrix to `visit`;
    /// returns the finest level's creases and tables.
    pub(super) fn levels(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        mut visit: impl FnMut(SubdivisionMatrix),
    ) -> Result<(Creases, GeneralLevel), SubdivError> {
        if self.split == Split::Triangles {
            triangles_only(mesh, "Loop")?;
        }
        let mut level = GeneralLevel::base(mesh)?;
        match self.split {
            Split::Triangles => counts::loop_levels("Loop", "vertices", level.counts(), 0, levels)?,
            Split::Quads => counts::catmull_clark_levels(level.counts(), 0, levels)?,
        };
        let mut creases = self.creases.clone();
        for _ in 0..levels {
            let scheme = Scheme { level: &level, split: self.split, rules: &self.rules, triangles: self.triangles };
            let CreasedLevel { matrix, child } = creased_level(&scheme, &creases, self.boundary, self.method)?;
            visit(matrix);
            creases = child;
            level = level.refine(self.split);
        }
        Ok((creases, level))
    }

    /// `levels` levels of subdivision of `mesh` (positions and colours, by level with
    /// `color_by_level`; normals and UVs are not carried): the subdivided mesh, its creases and
    /// its tables.
    pub(super) fn subdivide(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        color_by_level: bool,
    ) -> Result<(PolyMesh, Creases, GeneralLevel), SubdivError> {
        let mut values = Values::new(mesh, color_by_level);
        let (child, level) = self.levels(mesh, levels, |m| values.step(&m))?;
        let (positions, colors) = values.finish();
        Ok((level.to_mesh(positions, colors), child, level))
    }

    /// Subdivides `mesh` `levels` times ([`Self::subdivide`]) and gives the limit positions and
    /// normals of the finest level's vertices ([`Self::limit`]).
    pub(super) fn subdivide_limit(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        color_by_level: bool,
    ) -> Result<(PolyMesh, Vec<DVec3>, Vec<DVec3>), SubdivError> {
        let (fine, child, level) = self.subdivide(mesh, levels, color_by_level)?;
        let (positions, normals) = self.limit(&level, &fine.positions, &child)?;
        Ok((fine, positions, normals))
    }

    /// The limit positions of the vertices of `level` at `positions` with `creases` (on its
    /// vertices), and unit normals: OpenSubdiv's limit masks for each vertex's rule (a smooth
    /// vertex of valence 2 of Catmull-Clark stays where it is, as a corner); the normals are the
    /// area-weighted normals of the faces around each vertex at the limit positions.
    pub(super) fn limit(
        &self,
        level: &GeneralLevel,
        positions: &[DVec3],
        creases: &Creases,
    ) -> Result<(Vec<DVec3>, Vec<DVec3>), SubdivError> {
        let (split, rules, boundary) = (self.split, &self.rules, self.boundary);
        let scheme = Scheme { level, split, rules, triangles: self.triangles };
        let sharp = sharpness(&scheme, creases)?;
        let mut around = Vec::new();
        let mut limit = Vec::with_capacity(level.num_vertices);
        for v in 0..level.num_vertices as u32 {
            let p = positions[v as usize];
            let faces = scheme.edges_at(v, &mut around);
            if around.is_empty() {
                limit.push(p);
                continue;
            }
            let corner = scheme.is_corner(v) || (boundary == BoundaryRule::Corners && faces == 1);
            let vertex = if corner { INFINITELY_SHARP } else { sharp.vertex[v as usize] };
            let ends = around.iter().map(|&(x, far)| (far, sharp.edge[x as usize]));
            limit.push(match rule(vertex, ends) {
                Rule::Corner => p,
                Rule::Crease(a, b) => (positions[a as usize] + p * 4.0 + positions[b as usize]) * (1.0 / 6.0),
                Rule::Smooth => {
                    let n = faces as f64;
                    let ring: DVec3 = around.iter().map(|&(_, far)| positions[far as usize]).sum();
                    match split {
                        Split::Triangles => {
                            let chi = 1.0 / (n + 3.0 / (8.0 * rules.beta(faces as u32)));
                            p * (1.0 - n * chi) + ring * chi
                        }
                        Split::Quads if faces == 2 => p,
                        Split::Quads => {
                            let mut diagonals = DVec3::ZERO;
                            for &c in level.corners_of(v) {
                                let f = level.face_of[c as usize] as usize;
                                let (s, e) = (level.face_offsets[f], level.face_offsets[f + 1]);
                                if e - s != 4 {
                                    return Err(SubdivError::NotQuads {
                                        vertex: v as usize,
                                        face: f,
                                        corners: (e - s) as usize,
                                    });
                                }
                                diagonals += positions[level.face_vertices[(s + (c - s + 2) % 4) as usize] as usize];
                            }
                            (p * (n * n) + ring * 4.0 + diagonals) * (1.0 / (n * (n + 5.0)))
                        }
                    }
                }
            });
        }
        let mut normals = vec![DVec3::ZERO; level.num_vertices];
        for w in level.face_offsets.windows(2) {
            let face = &level.face_vertices[w[0] as usize..w[1] as usize];
            let p0 = limit[face[0] as usize];
            let mut area = DVec3::ZERO;
            for k in 1..face.len().saturating_sub(1) {
                area += (limit[face[k] as usize] - p0).cross(limit[face[k + 1] as usize] - p0);
            }
            for &v in face {
                normals[v as usize] += area;
            }
        }
        Ok((limit, normals.into_iter().map(DVec3::normalize_or_zero).collect()))
    }
}
