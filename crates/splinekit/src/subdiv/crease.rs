//! Sharp and semi-sharp creases on edges and vertices, with OpenSubdiv's rules, for Loop and
//! Catmull-Clark subdivision.
//!
//! A crease gives an edge or a vertex a **sharpness** `s`: `0` is smooth, `s ≥ 10` is
//! infinitely sharp, anything between is semi-sharp — sharp for the first `⌊s⌋` levels, then
//! blended towards smooth by the fraction left, then smooth. Boundary edges are always
//! infinitely sharp; with [`BoundaryRule::Corners`] a boundary vertex of one face is an
//! infinitely sharp vertex (OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER`). Sharpness values are
//! `f32` and are computed with the same single-precision arithmetic as OpenSubdiv (`Sdc::Crease`),
//! so the rules picked and the weights blended are the same to the bit.
//!
//! Each level, every vertex gets a **rule** from its own sharpness and the number of sharp
//! edges around it: a sharp vertex or three or more sharp edges make a *corner* (the vertex
//! stays: `P`), two make a *crease* (`3/4·P + 1/8·(a + b)`, `a` and `b` the far ends of the two
//! sharp edges), fewer are *smooth* (the scheme's smooth rule; one sharp edge is a dart, which
//! is smooth too). An edge point on a sharp edge is the edge's midpoint. The same rules are
//! determined again from the child level's sharpness (see below); where the parent's and the
//! child's rule differ, the vertex is the blend `w·parent + (1 − w)·child` with `w` the average
//! sharpness of the edges (and the vertex) whose sharpness decays to zero, at most 1; an edge
//! point on a sharp edge whose child halves are not both sharp is `s·midpoint + (1 − s)·smooth`.
//!
//! Sharpness is **carried to the child level**: a vertex's child has sharpness `s − 1` (`0`
//! once `s ≤ 1`, `10` stays `10`); the two halves of an edge of sharpness `s` get, with
//! [`CreasingMethod::Uniform`], `s − 1` each; with [`CreasingMethod::Chaikin`] (the default),
//! the half at end vertex `v` gets `3/4·s + 1/4·(average of the other semi-sharp edges at v) − 1`
//! when `v` has other semi-sharp edges, else `s − 1` — so a crease whose sharpness varies
//! along it tapers smoothly. Edges inside a face are smooth. The subdivision functions return
//! the child's [`Creases`], so that refining level by level gives the same result as refining
//! several levels at once (on a manifold mesh: the tags a non-manifold mesh's levels inherit
//! are not in their creases, see [`catmull_clark_step`](super::catmull_clark_step)).

use glam::DVec3;

use super::error::SubdivError;
use super::level_colors::{child_colors, parent_colors};
use super::matrix::{Builder, SubdivisionMatrix};
use super::options::{BoundaryRule, CreasingMethod, Rules};
use super::rings::Rings;
use super::topology::{Table, next, prev};
use crate::mesh::{NONE, PolyMesh};

/// Sharpness at which an edge or vertex is infinitely sharp.
pub const INFINITELY_SHARP: f32 = 10.0;

/// A sharp or semi-sharp edge: the edge between vertices `a` and `b` (either order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeCrease {
    /// One end.
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// Sharpness: 0 smooth, ≥ 10 infinitely sharp.
    pub sharpness: f32,
}

/// A sharp or semi-sharp vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexCrease {
    /// The vertex.
    pub vertex: u32,
    /// Sharpness: 0 smooth, ≥ 10 infinitely sharp.
    pub sharpness: f32,
}

/// The sharp and semi-sharp edges and vertices of a mesh (see the [module docs](self)). An edge
/// or vertex listed twice takes the last sharpness given.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Creases {
    /// Edges.
    pub edges: Vec<EdgeCrease>,
    /// Vertices.
    pub vertices: Vec<VertexCrease>,
}

impl Creases {
    /// No edge and no vertex with a positive sharpness.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.edges.iter().all(|e| e.sharpness <= 0.0) && self.vertices.iter().all(|v| v.sharpness <= 0.0)
    }
}

/// What a vertex does in one level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Rule {
    /// The scheme's smooth rule (also a dart: one sharp edge).
    Smooth,
    /// `3/4·P + 1/8·(a + b)` with `a`, `b` the far ends of the two sharp edges.
    Crease(u32, u32),
    /// `P`.
    Corner,
}

/// Sharpness of a vertex or edge one level down, uniformly: `s − 1`, or 0, or infinite.
fn decrement(s: f32) -> f32 {
    if s <= 0.0 {
        0.0
    } else if s >= INFINITELY_SHARP {
        INFINITELY_SHARP
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// The rule of a vertex of sharpness `vertex` whose edges (far end, sharpness) are `edges`.
pub(super) fn rule(vertex: f32, edges: impl Iterator<Item = (u32, f32)>) -> Rule {
    if vertex > 0.0 {
        return Rule::Corner;
    }
    let mut ends = [NONE; 2];
    let mut count = 0;
    for (end, s) in edges {
        if s > 0.0 {
            if count < 2 {
                ends[count] = end;
            }
            count += 1;
        }
    }
    match count {
        0 | 1 => Rule::Smooth,
        2 => Rule::Crease(ends[0], ends[1]),
        _ => Rule::Corner,
    }
}

/// The sharpness of the child halves of `parent` (the edges around one vertex), at that vertex
/// (OpenSubdiv's `SubdivideEdgeSharpnessesAroundVertex`).
fn child_sharpness_around(parent: &[f32], method: CreasingMethod, child: &mut Vec<f32>) {
    child.clear();
    if method == CreasingMethod::Uniform || parent.len() < 2 {
        child.extend(parent.iter().map(|&s| decrement(s)));
        return;
    }
    let semi_sharp = |s: f32| s > 0.0 && s < INFINITELY_SHARP;
    let (mut sum, mut count) = (0.0f32, 0u32);
    for &s in parent.iter().filter(|&&s| semi_sharp(s)) {
        sum += s;
        count += 1;
    }
    child.extend(parent.iter().map(|&s| {
        if s <= 0.0 {
            0.0
        } else if s >= INFINITELY_SHARP {
            INFINITELY_SHARP
        } else if count == 1 {
            decrement(s)
        } else {
            let others = (sum - s) / (count - 1) as f32;
            let c = (0.75 * s + 0.25 * others) - 1.0;
            if c > 0.0 { c } else { 0.0 }
        }
    }));
}

/// The weight of the parent's rule where a vertex's rule changes from parent to child
/// (OpenSubdiv's `ComputeFractionalWeightAtVertex`).
fn fractional_weight(vertex: f32, child_vertex: f32, parent: &[f32], child: &[f32], method: CreasingMethod) -> f32 {
    let (mut sum, mut count) = (0.0f32, 0u32);
    if vertex > 0.0 && child_vertex <= 0.0 {
        (sum, count) = (vertex, 1);
    }
    for (&p, &c) in parent.iter().zip(child) {
        let decays = match method {
            CreasingMethod::Uniform => p <= 1.0,
            CreasingMethod::Chaikin => c <= 0.0,
        };
        if p > 0.0 && decays {
            sum += p;
            count += 1;
        }
    }
    if count == 0 { 0.0 } else { (sum / count as f32).min(1.0) }
}

/// One level's topology as the crease rules read it, and the scheme's smooth rules.
pub(super) trait Level {
    /// Number of vertices.
    fn num_vertices(&self) -> usize;
    /// Number of edges (edge points are numbered after the vertex points in this order).
    fn num_edges(&self) -> usize;
    /// The two ends of edge `e`.
    fn edge_ends(&self, e: u32) -> [u32; 2];
    /// Whether edge `e` has a single face.
    fn is_boundary(&self, e: u32) -> bool;
    /// The edges at vertex `v` as (edge, far end), into `out` (cleared first); returns the
    /// number of faces at `v`.
    fn edges_at(&self, v: u32, out: &mut Vec<(u32, u32)>) -> usize;
    /// `scale ×` the smooth rule of the interior vertex `v`.
    fn smooth_vertex(&self, v: u32, scale: f64, b: &mut Builder);
    /// `scale ×` the smooth rule of the interior edge `e`.
    fn smooth_edge(&self, e: u32, scale: f64, b: &mut Builder);
    /// The rows after the edge points (Catmull-Clark's face points).
    fn more_rows(&self, b: &mut Builder);
    /// Whether vertex `v` is infinitely sharp by its topology (a non-manifold vertex made a
    /// corner: see [`general`](super::general)).
    fn is_corner(&self, _v: u32) -> bool {
        false
    }
}

/// Loop's level: a triangle table and the weights.
pub(super) struct LoopLevelRules<'a> {
    pub(super) table: Table<'a>,
    pub(super) rules: &'a Rules,
}

impl Level for LoopLevelRules<'_> {
    fn num_vertices(&self) -> usize {
        self.table.num_vertices()
    }

    fn num_edges(&self) -> usize {
        self.table.num_edges()
    }

    fn edge_ends(&self, e: u32) -> [u32; 2] {
        let h = self.table.edge_owner(e);
        let t = self.table.tri(h / 3);
        [t[(h % 3) as usize], t[next(h % 3) as usize]]
    }

    fn is_boundary(&self, e: u32) -> bool {
        self.table.twin(self.table.edge_owner(e)) == NONE
    }

    fn edges_at(&self, v: u32, out: &mut Vec<(u32, u32)>) -> usize {
        out.clear();
        let topo = &self.table;
        let start = topo.vertex_start(v);
        if start == NONE {
            return 0;
        }
        let (mut h, mut faces) = (start, 0);
        loop {
            out.push((topo.edge_of(h), topo.tri(h / 3)[next(h % 3) as usize]));
            faces += 1;
            let arriving = h - h % 3 + prev(h % 3);
            let t = topo.twin(arriving);
            if t == NONE {
                out.push((topo.edge_of(arriving), topo.tri(arriving / 3)[(arriving % 3) as usize]));
                return faces;
            }
            if t == start {
                return faces;
            }
            h = t;
        }
    }

    fn smooth_vertex(&self, v: u32, scale: f64, b: &mut Builder) {
        let topo = &self.table;
        let start = topo.vertex_start(v);
        let mut n = 0;
        let mut h = start;
        loop {
            n += 1;
            h = topo.twin(h - h % 3 + prev(h % 3));
            if h == start || h == NONE {
                break;
            }
        }
        let beta = self.rules.beta(n);
        b.add(v, scale * (1.0 - f64::from(n) * beta));
        let mut h = start;
        loop {
            b.add(topo.tri(h / 3)[next(h % 3) as usize], scale * beta);
            h = topo.twin(h - h % 3 + prev(h % 3));
            if h == start || h == NONE {
                break;
            }
        }
    }

    fn smooth_edge(&self, e: u32, scale: f64, b: &mut Builder) {
        let topo = &self.table;
        let h = topo.edge_owner(e);
        let (i, t, tw) = (h % 3, topo.tri(h / 3), topo.twin(h));
        b.add(t[i as usize], scale * 0.375);
        b.add(t[next(i) as usize], scale * 0.375);
        b.add(t[prev(i) as usize], scale * 0.125);
        b.add(topo.tri(tw / 3)[prev(tw % 3) as usize], scale * 0.125);
    }

    fn more_rows(&self, _: &mut Builder) {}
}

/// One level with creases: its matrix (rows: the child's vertices) and the child's creases.
pub(super) struct CreasedLevel {
    pub(super) matrix: SubdivisionMatrix,
    pub(super) child: Creases,
}

/// Per-level sharpness of every edge and vertex.
pub(super) struct Sharpness {
    pub(super) edge: Vec<f32>,
    pub(super) vertex: Vec<f32>,
}

/// The sharpness of every edge and vertex of `level` given by `creases`, boundary edges
/// infinitely sharp (one-face corners are made sharp by [`creased_level`]'s vertex pass).
pub(super) fn sharpness(level: &impl Level, creases: &Creases) -> Result<Sharpness, SubdivError> {
    let (nv, ne) = (level.num_vertices(), level.num_edges());
    let mut edge: Vec<f32> =
        (0..ne as u32).map(|e| if level.is_boundary(e) { INFINITELY_SHARP } else { 0.0 }).collect();
    let mut vertex = vec![0.0f32; nv];
    let bad = |what: String, problem: &str| SubdivError::Crease { what, problem: problem.to_owned() };
    let check = |what: &dyn Fn() -> String, s: f32| {
        if s.is_nan() || s < 0.0 { Err(bad(what(), &format!("sharpness {s} is not a number ≥ 0"))) } else { Ok(()) }
    };
    let mut around = Vec::new();
    for c in &creases.edges {
        let what = || format!("crease on edge {}–{}", c.a, c.b);
        check(&what, c.sharpness)?;
        if c.a as usize >= nv || c.b as usize >= nv {
            return Err(bad(what(), &format!("the mesh has {nv} vertices")));
        }
        level.edges_at(c.a, &mut around);
        let Some(&(e, _)) = around.iter().find(|&&(_, far)| far == c.b) else {
            return Err(bad(what(), "no face has this edge"));
        };
        if !level.is_boundary(e) {
            edge[e as usize] = c.sharpness;
        }
    }
    for c in &creases.vertices {
        let what = || format!("crease on vertex {}", c.vertex);
        check(&what, c.sharpness)?;
        if c.vertex as usize >= nv {
            return Err(bad(what(), &format!("the mesh has {nv} vertices")));
        }
        vertex[c.vertex as usize] = c.sharpness;
    }
    Ok(Sharpness { edge, vertex })
}

/// One level of subdivision of `level` with `creases` (on `level`'s vertices): the matrix of
/// the child's vertices (vertex points, edge points, then [`Level::more_rows`]) and the
/// child's creases. Without creases this is the scheme's plain level with its boundary rules.
pub(super) fn creased_level(
    level: &impl Level,
    creases: &Creases,
    boundary: BoundaryRule,
    method: CreasingMethod,
) -> Result<CreasedLevel, SubdivError> {
    let sharp = sharpness(level, creases)?;
    let corners = boundary == BoundaryRule::Corners;
    let (nv, ne) = (level.num_vertices(), level.num_edges());
    // the sharpness of each edge's two halves, at its first and second end
    let mut halves = vec![[0.0f32; 2]; ne];
    let mut rows = Builder::new(nv);
    let (mut around, mut parent, mut child) = (Vec::new(), Vec::new(), Vec::new());
    for v in 0..nv as u32 {
        let faces = level.edges_at(v, &mut around);
        if faces == 0 {
            rows.add(v, 1.0);
            rows.end_row();
            continue;
        }
        parent.clear();
        parent.extend(around.iter().map(|&(e, _)| sharp.edge[e as usize]));
        child_sharpness_around(&parent, method, &mut child);
        for (k, (&(e, _), &c)) in around.iter().zip(&child).enumerate() {
            let [a, b] = level.edge_ends(e);
            // an edge from `v` to itself is listed twice: its first half, then its second
            let end = if a == b { usize::from(around[..k].iter().any(|&(x, _)| x == e)) } else { usize::from(a != v) };
            halves[e as usize][end] = c;
        }
        // with fixed corners, a vertex of one face (on the boundary) is infinitely sharp
        // (and a non-manifold vertex made a corner)
        let pv =
            if (corners && faces == 1) || level.is_corner(v) { INFINITELY_SHARP } else { sharp.vertex[v as usize] };
        let cv = decrement(pv);
        let ends = || around.iter().map(|&(_, far)| far);
        let p_rule = rule(pv, ends().zip(parent.iter().copied()));
        let add = |r: Rule, w: f64, rows: &mut Builder| match r {
            Rule::Smooth => level.smooth_vertex(v, w, rows),
            Rule::Crease(a, b) => {
                rows.add(v, 0.75 * w);
                rows.add(a, 0.125 * w);
                rows.add(b, 0.125 * w);
            }
            Rule::Corner => rows.add(v, w),
        };
        if p_rule == Rule::Smooth {
            add(Rule::Smooth, 1.0, &mut rows);
        } else {
            let c_rule = rule(cv, ends().zip(child.iter().copied()));
            if c_rule == p_rule {
                add(p_rule, 1.0, &mut rows);
            } else {
                let w = f64::from(fractional_weight(pv, cv, &parent, &child, method));
                add(p_rule, w, &mut rows);
                add(c_rule, 1.0 - w, &mut rows);
            }
        }
        rows.end_row();
    }
    for e in 0..ne as u32 {
        let s = sharp.edge[e as usize];
        let [a, b] = level.edge_ends(e);
        let [ha, hb] = halves[e as usize];
        if s <= 0.0 {
            level.smooth_edge(e, 1.0, &mut rows);
        } else {
            // sharp in the child too: the midpoint; else the blend by the parent's sharpness
            let w = if ha > 0.0 && hb > 0.0 { 1.0 } else { f64::from(s) };
            rows.add(a, 0.5 * w);
            rows.add(b, 0.5 * w);
            if w != 1.0 {
                level.smooth_edge(e, 1.0 - w, &mut rows);
            }
        }
        rows.end_row();
    }
    level.more_rows(&mut rows);

    let mut out = Creases::default();
    for e in 0..ne as u32 {
        if level.is_boundary(e) || sharp.edge[e as usize] <= 0.0 {
            continue;
        }
        let [a, b] = level.edge_ends(e);
        let m = nv as u32 + e;
        let [ha, hb] = halves[e as usize];
        if ha > 0.0 {
            out.edges.push(EdgeCrease { a, b: m, sharpness: ha });
        }
        if hb > 0.0 {
            out.edges.push(EdgeCrease { a: m, b, sharpness: hb });
        }
    }
    out.vertices.extend(
        sharp
            .vertex
            .iter()
            .enumerate()
            .map(|(v, &s)| VertexCrease { vertex: v as u32, sharpness: decrement(s) })
            .filter(|c| c.sharpness > 0.0),
    );
    Ok(CreasedLevel { matrix: rows.finish(), child: out })
}

/// Catmull-Clark's level: a polygon mesh's adjacency.
impl Level for Rings<'_> {
    fn num_vertices(&self) -> usize {
        self.mesh.num_vertices()
    }

    fn num_edges(&self) -> usize {
        self.adj.num_edges()
    }

    fn edge_ends(&self, e: u32) -> [u32; 2] {
        let c = self.adj.edge_corner[e as usize];
        [self.mesh.face_vertices[c as usize], self.adj.to[c as usize]]
    }

    fn is_boundary(&self, e: u32) -> bool {
        self.adj.twin[self.adj.edge_corner[e as usize] as usize] == NONE
    }

    /// In OpenSubdiv's order (`Vtr::Level::orderVertexFacesAndEdges`), which its single-precision
    /// Chaikin sums follow: from the edge leaving `v` in its first face (or the boundary edge
    /// leaving `v`), counter-clockwise, then the boundary edge arriving at `v`. The children of
    /// a vertex keep the order: their first face is the child of the parent's first face.
    fn edges_at(&self, v: u32, out: &mut Vec<(u32, u32)>) -> usize {
        out.clear();
        let corners = self.adj.corners_of(v);
        let Some(&first) = corners.first() else { return 0 };
        let start = corners.iter().copied().find(|&c| self.adj.twin[c as usize] == NONE).unwrap_or(first);
        let mut last = start;
        for c in self.fan(start) {
            out.push((self.adj.edge_of[c as usize], self.adj.to[c as usize]));
            last = c;
        }
        let arriving = self.prev(last);
        if self.adj.twin[arriving as usize] == NONE {
            out.push((self.adj.edge_of[arriving as usize], self.mesh.face_vertices[arriving as usize]));
        }
        corners.len()
    }

    fn smooth_vertex(&self, v: u32, scale: f64, b: &mut Builder) {
        let corners = self.adj.corners_of(v);
        let n = corners.len() as f64;
        b.add(v, scale * (n - 2.0) / n);
        let w = scale / (n * n);
        for &c in corners {
            b.add(self.adj.to[c as usize], w);
            self.face_point(self.adj.face_of[c as usize], w, b);
        }
    }

    fn smooth_edge(&self, e: u32, scale: f64, b: &mut Builder) {
        let c = self.adj.edge_corner[e as usize];
        let t = self.adj.twin[c as usize];
        let (f0, f1) = (self.adj.face_of[c as usize], self.adj.face_of[t as usize]);
        let sizes = (self.mesh.face(f0 as usize).len(), self.mesh.face(f1 as usize).len());
        let (end, face) = self.triangles.edge_weights(sizes.0, sizes.1).unwrap_or((0.25, 0.25));
        b.add(self.mesh.face_vertices[c as usize], end * scale);
        b.add(self.adj.to[c as usize], end * scale);
        self.face_point(f0, face * scale, b);
        self.face_point(f1, face * scale, b);
    }

    fn more_rows(&self, b: &mut Builder) {
        for f in 0..self.mesh.num_faces() as u32 {
            self.face_point(f, 1.0, b);
            b.end_row();
        }
    }
}

impl Rings<'_> {
    /// `w ×` the face point of face `f`.
    fn face_point(&self, f: u32, w: f64, b: &mut Builder) {
        let corners = self.mesh.face(f as usize);
        let share = w / corners.len() as f64;
        for &v in corners {
            b.add(v, share);
        }
    }
}

/// Carries positions and colours (by the level matrices, or by level) through the levels.
pub(super) struct Values {
    pub(super) positions: Vec<DVec3>,
    pub(super) colors: Vec<DVec3>,
    color_by_level: bool,
    depth: usize,
}

impl Values {
    pub(super) fn new(mesh: &PolyMesh, color_by_level: bool) -> Self {
        let colors = parent_colors(mesh, color_by_level, 1).into_owned();
        Self { positions: mesh.positions.clone(), colors, color_by_level, depth: 0 }
    }

    /// The positions and colours.
    pub(super) fn finish(self) -> (Vec<DVec3>, Vec<DVec3>) {
        (self.positions, self.colors)
    }

    pub(super) fn step(&mut self, matrix: &SubdivisionMatrix) {
        self.depth += 1;
        self.positions = matrix.apply(&self.positions).expect("one value per column");
        let apply = |c: &[DVec3]| matrix.apply(c).expect("one value per column");
        self.colors = child_colors(self.color_by_level, &self.colors, self.positions.len(), self.depth, apply);
    }
}
