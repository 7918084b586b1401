//! Three Catmull-Clark levels of a regular quad mesh, made a base face at a time.
//!
//! Over a quad whose four corners are interior vertices of valence 4 (all their faces quads),
//! Catmull-Clark's rules are the uniform bicubic B-spline's refinement of the face's 4 × 4
//! control points (its own corners and the 12 around them): the face point is the
//! tensor product of the 1D edge rule `(½, ½)`, the edge point of the edge and vertex rules,
//! the valence-4 vertex point `P/2 + (Σ ring + Σ face points)/16` of the vertex rule
//! `(⅛, ¾, ⅛)` with itself. Three levels over the face are therefore the 9 × 9 grid
//! `Σ A[x][a]·A[y][b]·P[a][b]` with `A` the 9 × 4 weights of three halvings of the cubic
//! B-spline (dyadic fractions, exact in `f64`).
//!
//! [`subdivide3`] makes three levels of a mesh where every face is such a quad (closed, every
//! vertex on four corners) that way: one pass over the base faces writes each face's level-3
//! quads and the level-3 vertices it owns, one pass over the base vertices writes theirs, and
//! the values of levels 1 and 2 are never made. The vertex and face numbers are those of the
//! level-by-level path (level 1's tables and the grandchild numbering give them; see
//! [`quads`](super::quads)), so the mesh is the same as [`subdivide`](super::quads::subdivide)'s
//! but for rounding: the tensor weights sum the same values in another order (the
//! difference is a few ulps of the coordinates).

use glam::DVec3;
use rayon::prelude::*;

use super::quads::{FACES, Grandchild, QuadLevel, next, prev, quad_mesh};
use super::topology::MIN_RINGS;
use crate::mesh::{NONE, PolyMesh};

/// Grid points a side of one base face after three levels.
const SIDE: usize = 9;

/// Whether every face of `level` is regular: no boundary, every vertex on exactly four
/// corners (with the manifold check of `Rings`, its four faces form one closed fan).
pub(super) fn is_regular(level: &QuadLevel) -> bool {
    if level.twin.contains(&NONE) {
        return false;
    }
    let mut corners = vec![0u8; level.num_vertices()];
    for &v in &level.corners {
        let c = &mut corners[v as usize];
        *c = c.saturating_add(1);
    }
    corners.iter().all(|&c| c == 4)
}

/// `A[i]`: the weights of the 4 control points `P0 … P3` of a uniform cubic B-spline in
/// the control point of three halvings at `1 + i/8` (the span from `P1` to `P2`).
fn weights() -> [[f64; 4]; SIDE] {
    // the 1D rules: edge points (a + b)/2, vertex points (a + 6b + c)/8, on the points that
    // keep both neighbours (4 → 5 → 7 → 11; the 9 in the middle span are 1 ..= 9)
    fn halve(p: &[f64]) -> Vec<f64> {
        let n = p.len();
        (0..2 * n - 3)
            .map(|i| {
                if i % 2 == 0 {
                    (p[i / 2] + p[i / 2 + 1]) * 0.5
                } else {
                    (p[i / 2] + 6.0 * p[i / 2 + 1] + p[i / 2 + 2]) * 0.125
                }
            })
            .collect()
    }
    let mut a = [[0.0; 4]; SIDE];
    for j in 0..4 {
        let unit: Vec<f64> = (0..4).map(|k| f64::from(u8::from(k == j))).collect();
        let fine = halve(&halve(&halve(&unit)));
        for (i, row) in a.iter_mut().enumerate() {
            row[j] = fine[i + 1];
        }
    }
    a
}

/// Per level-3 quad of a base face (`16k + 4k₁ + k₂`: the child of corner `k₂` of the child
/// of corner `k₁` of the child of base corner `k`) and corner, its point of the face's 9 × 9
/// grid, `x + 9y`: base corner `k` at `(0,0)`, `(8,0)`, `(8,8)`, `(0,8)` for `k = 0 … 3`, and
/// each child `(Pₖ, mid(Pₖ, Pₖ₊₁), centre, mid(Pₖ₋₁, Pₖ))` of its parent's corners `P`.
fn grid_of_corners() -> [u8; 256] {
    let children = |p: [(u32, u32); 4], k: usize| {
        let mid = |a: (u32, u32), b: (u32, u32)| ((a.0 + b.0) / 2, (a.1 + b.1) / 2);
        let centre = mid(mid(p[0], p[1]), mid(p[2], p[3]));
        [p[k], mid(p[k], p[(k + 1) % 4]), centre, mid(p[(k + 3) % 4], p[k])]
    };
    let base = [(0, 0), (8, 0), (8, 8), (0, 8)];
    let mut out = [0u8; 256];
    for k in 0..4 {
        let s = children(base, k);
        for k1 in 0..4 {
            let m = children(s, k1);
            for k2 in 0..4 {
                let f = children(m, k2);
                for (i, &(x, y)) in f.iter().enumerate() {
                    out[4 * (16 * k + 4 * k1 + k2) + i] = (x + 9 * y) as u8;
                }
            }
        }
    }
    out
}

/// The 4 × 4 control points of regular base face `f`, `[x][y]`: its corners at `[1][1]`,
/// `[2][1]`, `[2][2]`, `[1][2]` (corners `4f … 4f + 3`), the x axis along its first edge.
#[inline]
fn net(level: &QuadLevel, p: &[DVec3], f: u32) -> [[DVec3; 4]; 4] {
    let at = |c: u32| p[level.corners[c as usize] as usize];
    let tw = |c: u32| level.twin[c as usize];
    let mut n = [[DVec3::ZERO; 4]; 4];
    // (x, y) of corner k, of the far points across its edge next to it and next to the
    // following corner, and of the diagonal point at it
    const AT: [[(usize, usize); 4]; 4] = [
        [(1, 1), (1, 0), (2, 0), (0, 0)],
        [(2, 1), (3, 1), (3, 2), (3, 0)],
        [(2, 2), (2, 3), (1, 3), (3, 3)],
        [(1, 2), (0, 2), (0, 1), (0, 3)],
    ];
    for (k, [own, near, far, diagonal]) in AT.into_iter().enumerate() {
        let c = 4 * f + k as u32;
        // the quad across c's edge: t runs back along it, next(t) leaves c's vertex
        let t = tw(c);
        n[own.0][own.1] = at(c);
        n[near.0][near.1] = at(next(next(t)));
        n[far.0][far.1] = at(prev(t));
        n[diagonal.0][diagonal.1] = at(prev(tw(next(t))));
    }
    n
}

/// The 9 × 9 level-3 grid over a face with control points `n` (see the module docs), per
/// coordinate, `[c][x + 9y]`: `at[a]` is column `a` of `A` (`at[a][i] = A[i][a]`). Rows of 9
/// values throughout, so that the sums vectorize: first `Σ_b n[x][b]·A[y][b]` per `x`, then
/// those against `A` along x.
#[inline]
fn grid(at: &[[f64; SIDE]; 4], n: &[[DVec3; 4]; 4]) -> [[f64; SIDE * SIDE]; 3] {
    let mut out = [[0.0; SIDE * SIDE]; 3];
    for (c, out) in out.iter_mut().enumerate() {
        // rows[x][y] = Σ_b n[x][b]·A[y][b]
        let mut rows = [[0.0; SIDE]; 4];
        for (x, row) in rows.iter_mut().enumerate() {
            for b in 0..4 {
                let w = n[x][b][c];
                for (r, &t) in row.iter_mut().zip(&at[b]) {
                    *r += w * t;
                }
            }
        }
        for y in 0..SIDE {
            let line = &mut out[SIDE * y..SIDE * (y + 1)];
            for (a, row) in rows.iter().enumerate() {
                let w = row[y];
                for (o, &t) in line.iter_mut().zip(&at[a]) {
                    *o += w * t;
                }
            }
        }
    }
    out
}

/// Per grid point `x + 9y` of a base face: the part of the output its level-3 vertex is in
/// (see [`Layout`]; [`CORNER`] for the base corners, which the vertex pass writes), and one
/// slot of the face's 256 level-3 corners that holds it.
fn parts_and_slots(slots: &[u8; 256]) -> ([u8; SIDE * SIDE], [u8; SIDE * SIDE]) {
    let mut part = [0u8; SIDE * SIDE];
    let mut slot = [u8::MAX; SIDE * SIDE];
    for (i, &g) in slots.iter().enumerate() {
        if slot[g as usize] == u8::MAX {
            slot[g as usize] = i as u8;
        }
    }
    for (g, p) in part.iter_mut().enumerate() {
        let (x, y) = (g % SIDE, g / SIDE);
        let edge = |u: usize| u == 0 || u == 8;
        // on a base edge, `along` is the coordinate along it; inside, the spokes are x or y = 4
        let (on_edge, along) = if edge(x) {
            (true, y)
        } else if edge(y) {
            (true, x)
        } else {
            (false, 0)
        };
        *p = if edge(x) && edge(y) {
            CORNER
        } else if on_edge {
            // level 1 at 4, level 2 at 2 and 6 (halves of the base edge), level 3 between
            match along {
                4 => 0,
                2 | 6 => 2,
                _ => 4,
            }
        } else if x == 4 && y == 4 {
            1
        } else if x % 2 == 1 && y % 2 == 1 {
            5
        } else if x % 2 == 0 && y % 2 == 0 && x != 4 && y != 4 {
            3
        } else if (x == 4 && y % 2 == 0) || (y == 4 && x % 2 == 0) {
            2
        } else {
            4
        };
    }
    (part, slot)
}

/// The part of a base corner's grid point: written by the vertex pass.
const CORNER: u8 = 6;

/// The level-3 corners: made by the pass (into room for them), or made already.
enum Quads<'a> {
    Make(&'a mut [u32]),
    Made(&'a [u32]),
}

/// A block of base faces `f0 .. f1` with its share of the six parts and of the corners.
type Block<'a> = (u32, u32, [&'a mut [DVec3]; 6], Quads<'a>);

/// The fixed tables of a face: `A`, its columns, and per grid point its part and a slot.
struct Tables {
    a: [[f64; 4]; SIDE],
    at: [[f64; SIDE]; 4],
    part: [u8; SIDE * SIDE],
    rep: [u8; SIDE * SIDE],
}

/// Where the level-3 vertices go: the output's parts (see [`QuadLevel`]'s and
/// [`Grandchild`]'s layouts) and, per base face, the ones it writes.
struct Layout<'a> {
    base: &'a QuadLevel,
    s: &'a QuadLevel,
    g: &'a Grandchild<'a>,
    /// The starts of the parts: base edges, base faces (the level-1 vertices on them), `S`
    /// edges, `S` faces, `M` edges, `M` faces, and the end.
    starts: [u32; 7],
}

impl<'a> Layout<'a> {
    fn new(base: &'a QuadLevel, s: &'a QuadLevel, g: &'a Grandchild<'a>) -> Self {
        let (nv, ne, nf) = (base.num_vertices() as u32, base.num_edges() as u32, base.num_faces() as u32);
        let (nvs, nes, nfs) = (s.num_vertices() as u32, s.num_edges() as u32, s.num_faces() as u32);
        let (nvm, nem) = (g.num_m_vertices(), g.num_m_edges());
        debug_assert_eq!(nvs, nv + ne + nf);
        let starts = [nv, nv + ne, nvs, nvs + nes, nvm, nvm + nem, nvm + nem + 4 * nfs];
        Self { base, s, g, starts }
    }

    /// The ranges of the parts that base faces `f0 .. f1` write (empty for the base vertices).
    fn ranges(&self, f0: u32, f1: u32) -> [(u32, u32); 6] {
        let st = &self.starts;
        let (b, s, g) = (&self.base.edge_base, &self.s.edge_base, &self.g.base);
        let (f0, f1) = (f0 as usize, f1 as usize);
        [
            (st[0] + b[f0], st[0] + b[f1]),
            (st[1] + f0 as u32, st[1] + f1 as u32),
            (st[2] + s[4 * f0], st[2] + s[4 * f1]),
            (st[3] + 4 * f0 as u32, st[3] + 4 * f1 as u32),
            (st[4] + g[4 * f0], st[4] + g[4 * f1]),
            (st[5] + 16 * f0 as u32, st[5] + 16 * f1 as u32),
        ]
    }
}

/// Three Catmull-Clark levels of the regular quad mesh with tables `base` (see
/// [`is_regular`]) and `positions`; `colors` carried with the same weights, or, with
/// `color_by_level`, the vertices coloured by the level they were born at.
pub(super) fn subdivide3(base: QuadLevel, positions: &[DVec3], colors: &[DVec3], color_by_level: bool) -> PolyMesh {
    debug_assert!(is_regular(&base));
    let s = base.child(base.child_corners());
    let g = s.grandchild();
    let layout = Layout::new(&base, &s, &g);
    let (a, slots) = (weights(), grid_of_corners());
    let at: [[f64; SIDE]; 4] = core::array::from_fn(|b| core::array::from_fn(|i| a[i][b]));
    let (part, rep) = parts_and_slots(&slots);
    let tables = Tables { a, at, part, rep };
    let mut corners: Vec<u32> = bytemuck::zeroed_vec(256 * base.num_faces());
    let fine = values(&layout, &tables, positions, Quads::Make(&mut corners));
    let colors = if color_by_level {
        let ends = [layout.starts[0], layout.starts[2], layout.g.num_m_vertices(), layout.starts[6]];
        let mut c = Vec::with_capacity(ends[3] as usize);
        for (level, &end) in ends.iter().enumerate() {
            c.resize(end as usize, super::LEVEL_COLORS[level % super::LEVEL_COLORS.len()]);
        }
        c
    } else if colors.is_empty() {
        Vec::new()
    } else {
        values(&layout, &tables, colors, Quads::Made(&corners))
    };
    drop(g);
    drop(s);
    drop(base);
    quad_mesh(fine, colors, corners)
}

/// The level-3 values of `p` (and the level-3 corners, if not made yet): the base vertices in
/// one pass, everything else per base face, each base face writing the vertices in its
/// ranges of the output ([`Layout::ranges`]).
fn values(layout: &Layout<'_>, tables: &Tables, p: &[DVec3], mut corners: Quads<'_>) -> Vec<DVec3> {
    let a = &tables.a;
    let base = layout.base;
    let st = layout.starts;
    let mut out: Vec<DVec3> = bytemuck::zeroed_vec(st[6] as usize);
    let (old, mut rest) = out.split_at_mut(st[0] as usize);
    // the base vertices: the grid point of the corner of their start corner
    let vertex_pass = || {
        old.par_iter_mut().enumerate().with_min_len(MIN_RINGS).for_each(|(v, o)| {
            let c = base.vertex_start[v];
            let n = net(base, p, c / 4);
            let (x, y) = [(0, 0), (8, 0), (8, 8), (0, 8)][(c % 4) as usize];
            let mut sum = DVec3::ZERO;
            for i in 0..4 {
                for j in 0..4 {
                    sum += n[i][j] * (a[x][i] * a[y][j]);
                }
            }
            *o = sum;
        });
    };
    // the six parts, cut into blocks of base faces
    let nf = base.num_faces();
    let mut parts: Vec<Block<'_>> = Vec::with_capacity(nf.div_ceil(FACES));
    let mut part_rest: [&mut [DVec3]; 6] = Default::default();
    for (i, slot) in part_rest.iter_mut().enumerate() {
        let (head, tail) = core::mem::take(&mut rest).split_at_mut((st[i + 1] - st[i]) as usize);
        *slot = head;
        rest = tail;
    }
    for f0 in (0..nf).step_by(FACES) {
        let f1 = nf.min(f0 + FACES);
        let ranges = layout.ranges(f0 as u32, f1 as u32);
        let block: [&mut [DVec3]; 6] = core::array::from_fn(|i| {
            let (head, tail) = core::mem::take(&mut part_rest[i]).split_at_mut((ranges[i].1 - ranges[i].0) as usize);
            part_rest[i] = tail;
            head
        });
        let n = 256 * (f1 - f0);
        let quads = match core::mem::replace(&mut corners, Quads::Made(&[])) {
            Quads::Make(c) => {
                let (head, tail) = c.split_at_mut(n);
                corners = Quads::Make(tail);
                Quads::Make(head)
            }
            Quads::Made(c) => {
                let (head, tail) = c.split_at(n);
                corners = Quads::Made(tail);
                Quads::Made(head)
            }
        };
        parts.push((f0 as u32, f1 as u32, block, quads));
    }
    let face_pass = || {
        parts.into_par_iter().for_each(|(f0, f1, block, mut quads)| {
            let lo = layout.ranges(f0, f1).map(|r| r.0);
            for f in f0..f1 {
                let own = layout.ranges(f, f + 1);
                // the face's 64 quads are those of its S faces 4f .. 4f + 3
                let at = 256 * (f - f0) as usize;
                let quads: &[u32] = match &mut quads {
                    Quads::Make(out) => {
                        let out = &mut out[at..at + 256];
                        for (k, part) in out.chunks_exact_mut(64).enumerate() {
                            part.copy_from_slice(&layout.g.quads_of(4 * f + k as u32));
                        }
                        out
                    }
                    Quads::Made(made) => &made[at..at + 256],
                };
                let values = grid(&tables.at, &net(base, p, f));
                for (g, (&part, &slot)) in tables.part.iter().zip(&tables.rep).enumerate() {
                    let part = part as usize;
                    let i = quads[slot as usize];
                    // this face's vertex (all inside it; on its edges, those it owns)
                    if part < 6 && i >= own[part].0 && i < own[part].1 {
                        debug_assert!(i >= st[part] && i < st[part + 1]);
                        block[part][(i - lo[part]) as usize] = DVec3::new(values[0][g], values[1][g], values[2][g]);
                    }
                }
            }
        });
    };
    rayon::join(vertex_pass, face_pass);
    out
}
