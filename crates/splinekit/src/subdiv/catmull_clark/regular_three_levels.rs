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
//! the values of levels 1 and 2 are never made. Nor are their tables: the vertex and face
//! numbers are those of the level-by-level path (see [`quads`](super::quads)), computed in
//! closed form from the base level's twins ([`Numbers`]), so the mesh is the same as
//! [`subdivide`](super::quads::subdivide)'s but for rounding: the tensor weights sum the same
//! values in another order (the difference is a few ulps of the coordinates).

use glam::DVec3;
use rayon::prelude::*;

use super::quad_levels::{FACES, QuadLevel, counts_before, next, prev, quad_mesh, quad_twins};
use crate::mesh::{NONE, PolyMesh};
use crate::subdiv::level_colors::LEVEL_COLORS;
use crate::subdiv::topology::MIN_RINGS;

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
const GRID: [u8; 256] = {
    /// Child `k` of a quad with corners `p`: its corner, the middle of its next edge, the
    /// centre, the middle of its previous edge.
    const fn children(p: [(u32, u32); 4], k: usize) -> [(u32, u32); 4] {
        const fn mid(a: (u32, u32), b: (u32, u32)) -> (u32, u32) {
            ((a.0 + b.0) / 2, (a.1 + b.1) / 2)
        }
        let centre = mid(mid(p[0], p[1]), mid(p[2], p[3]));
        [p[k], mid(p[k], p[(k + 1) % 4]), centre, mid(p[(k + 3) % 4], p[k])]
    }
    let base = [(0, 0), (8, 0), (8, 8), (0, 8)];
    let mut out = [0u8; 256];
    let mut k = 0;
    while k < 4 {
        let s = children(base, k);
        let mut k1 = 0;
        while k1 < 4 {
            let m = children(s, k1);
            let mut k2 = 0;
            while k2 < 4 {
                let f = children(m, k2);
                let mut i = 0;
                while i < 4 {
                    out[4 * (16 * k + 4 * k1 + k2) + i] = (f[i].0 + 9 * f[i].1) as u8;
                    i += 1;
                }
                k2 += 1;
            }
            k1 += 1;
        }
        k += 1;
    }
    out
};

/// The grid points of the `N` values `slot(j)` of [`GRID`].
const fn grid_points<const N: usize>(first: usize, stride: usize) -> [u8; N] {
    let mut g = [0u8; N];
    let mut j = 0;
    while j < N {
        g[j] = GRID[first + stride * j];
        j += 1;
    }
    g
}

// Where each part of the output ([`Layout`]) finds its values in a base face's grid, read off
// the corners of its level-3 quads (`[mv[x], e2[x], face, e2[prev x]]` of `M` corner `x`, see
// [`Numbers::quads_of`]). Vertices on edges are listed per owner corner, those on faces per face.

/// Part 0, the vertices on base edges: base corner `k`'s edge is `S` corner `4k + 1`'s vertex,
/// `M` corner `16k + 4`'s, the corner of quad `16k + 4`.
const BASE_EDGE_GRID: [u8; 4] = grid_points(16, 64);
/// Part 1, the base face's vertex: `S` corner `2`'s, `M` corner `8`'s.
const FACE_GRID: u8 = GRID[32];
/// Part 2, the vertices on `S` edges: `S` corner `i`'s edge is `M` corner `4i + 1`'s vertex.
const S_EDGE_GRID: [u8; 16] = grid_points(4, 16);
/// Part 3, the vertices on `S` faces: `S` face `k`'s is `M` corner `16k + 2`'s vertex.
const S_FACE_GRID: [u8; 4] = grid_points(8, 64);
/// Part 4, the vertices on `M` edges: `M` corner `x`'s edge is slot 1 of quad `x`.
const M_EDGE_GRID: [u8; 64] = grid_points(1, 4);
/// Part 5, the vertices on `M` faces: `M` face `j`'s is slot 2 of quad `4j`.
const M_FACE_GRID: [u8; 16] = grid_points(2, 16);

/// The 4 × 4 control points of regular base face `f`, `[x][y]`: its corners at `[1][1]`,
/// `[2][1]`, `[2][2]`, `[1][2]` (corners `4f … 4f + 3`), the x axis along its first edge.
#[inline(always)]
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

/// The weights of [`weights`] split by the mirror symmetry `A[8 − i][b] = A[i][3 − b]`:
/// `(A[i][b] ± A[i][3 − b]) / 2` for `b = 0, 1` and `i = 0 … 4` (exact: dyadic fractions), so
/// that with `sᵦ = Pᵦ + P₃₋ᵦ` and `dᵦ = Pᵦ − P₃₋ᵦ` the points `i` and `8 − i` of a line are
/// `S ± D`, `S = Σ w⁺·s`, `D = Σ w⁻·d` (`D = 0` at `i = 4`): about half the operations of
/// `Σ A·P`, with the same value in exact arithmetic.
#[derive(Clone, Copy)]
struct Halves {
    plus: [[f64; 2]; 5],
    minus: [[f64; 2]; 5],
}

impl Halves {
    fn new(a: &[[f64; 4]; SIDE]) -> Self {
        let half = |i: usize, b: usize, sign: f64| (a[i][b] + sign * a[i][3 - b]) * 0.5;
        Self {
            plus: core::array::from_fn(|i| [half(i, 0, 1.0), half(i, 1, 1.0)]),
            minus: core::array::from_fn(|i| [half(i, 0, -1.0), half(i, 1, -1.0)]),
        }
    }

    /// The 9 points of a line from its 4 control points `p`, each `N` values wide, into `out`
    /// (`out[i]`, `i = 0 … 8`).
    #[inline(always)]
    fn line<const N: usize>(&self, p: [&[f64; N]; 4], out: &mut [[f64; N]; SIDE]) {
        let mut s = [[0.0; N]; 2];
        let mut d = [[0.0; N]; 2];
        for b in 0..2 {
            for k in 0..N {
                s[b][k] = p[b][k] + p[3 - b][k];
                d[b][k] = p[b][k] - p[3 - b][k];
            }
        }
        for i in 0..4 {
            let (wp, wm) = (self.plus[i], self.minus[i]);
            let (lo, hi) = out.split_at_mut(SIDE - 1 - i);
            for k in 0..N {
                let sum = wp[0] * s[0][k] + wp[1] * s[1][k];
                let diff = wm[0] * d[0][k] + wm[1] * d[1][k];
                lo[i][k] = sum + diff;
                hi[0][k] = sum - diff;
            }
        }
        let wp = self.plus[4];
        for k in 0..N {
            out[4][k] = wp[0] * s[0][k] + wp[1] * s[1][k];
        }
    }
}

/// The 9 × 9 level-3 grid over a face with control points `n` (see the module docs),
/// into `out`, grid point `x + 9y` at `out[y][3x .. 3x + 3]`: first the 9 points along x of
/// each of the 4 rows of `n` (`n[·][b]`, 3 values wide), then those 4 × 9 points along y (27
/// values wide, so the second pass works on whole rows of points). Written in place and read
/// through reference casts (returning the 81 points by value costs two copies of them);
/// `rows` is scratch room for the first pass. (Both are the caller's, made once for many
/// faces: a fresh zeroed array per face is a `memset` per face.)
#[inline(always)]
fn grid(h: &Halves, n: &[[DVec3; 4]; 4], rows: &mut [[[f64; 3]; SIDE]; 4], out: &mut [[f64; 3 * SIDE]; SIDE]) {
    for (b, row) in rows.iter_mut().enumerate() {
        let p = [0, 1, 2, 3].map(|a| n[a][b].to_array());
        h.line::<3>([&p[0], &p[1], &p[2], &p[3]], row);
    }
    let flat: &[[f64; 3 * SIDE]; 4] = bytemuck::cast_ref(rows);
    h.line::<{ 3 * SIDE }>([&flat[0], &flat[1], &flat[2], &flat[3]], out);
}

/// A block of base faces `f0 .. f1` with its share of the six parts and, if they are to be
/// made, of the level-3 corners.
type Block<'a> = (u32, u32, [&'a mut [DVec3]; 6], Option<&'a mut [u32]>);

/// The fixed weights: of a base vertex's level-3 point, and the split weights of the grid.
struct Tables {
    vertex: [f64; 3],
    halves: Halves,
}

impl Tables {
    fn new() -> Self {
        let a = weights();
        // a base vertex's point: the tensor weights A[0] x A[0], A[0] = (a0, a1, a0, 0)
        // (the vertex rule is symmetric and does not reach P3)
        debug_assert!(a[0][0] == a[0][2] && a[0][3] == 0.0);
        let vertex = [a[0][1] * a[0][1], a[0][0] * a[0][1], a[0][0] * a[0][0]];
        Self { vertex, halves: Halves::new(&a) }
    }
}

/// The numbers of the level-1 (`S`) and level-2 (`M`) edges of a regular base level, in closed
/// form from the base twins, with no tables of `S` or `M`.
///
/// The child of base corner `c` is `S` face `c` with corners `4c .. 4c + 4`, so base face `f`
/// holds the `S` corners `16f .. 16f + 16` and the `M` corners `64f .. 64f + 64`. Their twins are
/// those of [`Corners::child_twins`](super::quads) applied twice: inside the face they are
/// fixed (tables [`S_OWNER`], [`M_OWNER`]), and along each base edge they are the corners along
/// the same edge of the face across it, the other way ([`S_ALONG`], [`M_ALONG`]). Edges are
/// numbered in the order of their owners (the corner before its twin), as the level-by-level
/// path numbers them, so an edge's number is the count of owners in the base faces before its
/// owner's (a prefix sum over base faces of the owner bits, kept per base face), plus the
/// owners before it in that face ([`edge_numbers`]).
struct Numbers<'a> {
    base: &'a QuadLevel,
    /// Per base face: bit `i` for `S` corner `16f + i` owning its edge.
    s_masks: Vec<u16>,
    /// Per base face: bit `i` for `M` corner `64f + i` owning its edge.
    m_masks: Vec<u64>,
    /// Per base face, and one more: the `S` edges owned by the faces before it.
    s_base: Vec<u32>,
    /// Per base face, and one more: the `M` edges owned by the faces before it.
    m_base: Vec<u32>,
}

/// The index of the previous corner in a quad among corners numbered from a multiple of 4.
#[inline(always)]
const fn prev_index(i: usize) -> usize {
    (i & !3) | ((i + 3) & 3)
}

/// The index of the next corner in a quad among corners numbered from a multiple of 4.
const fn next_index(i: usize) -> usize {
    (i & !3) | ((i + 1) & 3)
}

/// A base face's `S` corners along its base edge `k`, from corner `k` to corner `k + 1`: `S`
/// corner `16f + S_ALONG[k][p]` covers the `p`-th half. (The child of base corner `k` leaves
/// along the edge, the last child of corner `k + 1` arrives; see `Corners::child_twins`.)
const S_ALONG: [[u8; 2]; 4] = {
    let mut a = [[0; 2]; 4];
    let mut k = 0;
    while k < 4 {
        a[k] = [4 * k as u8, 4 * ((k as u8 + 1) % 4) + 3];
        k += 1;
    }
    a
};

/// A base face's `M` corners along its base edge `k`, by quarters from corner `k` (each `S`
/// corner's edge along it split in two: the halves of `S` corner `s` are `M` corners `4s` and
/// `4·next(s) + 3`).
const M_ALONG: [[u8; 4]; 4] = {
    let mut a = [[0; 4]; 4];
    let mut k = 0;
    while k < 4 {
        let (s0, s1) = (S_ALONG[k][0] as usize, S_ALONG[k][1] as usize);
        a[k] = [(4 * s0) as u8, (4 * next_index(s0) + 3) as u8, (4 * s1) as u8, (4 * next_index(s1) + 3) as u8];
        k += 1;
    }
    a
};

/// Per `S` corner of a base face (`16f + i`): the corner in the face that owns its edge, for the
/// edges inside the face (their twins are fixed: `4c + 1 ↔ 4·next(c) + 2`); itself for those on
/// the base edges ([`S_ALONG`]), whose twins are in the neighbours.
const S_OWNER: [u8; 16] = {
    let mut o = [0u8; 16];
    let mut i = 0;
    while i < 16 {
        o[i] = match s_inner_twin(i) {
            Some(t) if t < i => t as u8,
            _ => i as u8,
        };
        i += 1;
    }
    o
};

/// The twin of `S` corner `16f + i` if it is in the same base face (`16f + twin`).
const fn s_inner_twin(i: usize) -> Option<usize> {
    let (k, l) = (i / 4, i % 4);
    match l {
        1 => Some(4 * ((k + 1) % 4) + 2),
        2 => Some(4 * ((k + 3) % 4) + 1),
        _ => None,
    }
}

/// Per `M` corner of a base face (`64f + x`, the child `x % 4` of `S` corner `x / 4`): the corner
/// in the face that owns its edge, as [`S_OWNER`]. The twins inside the face follow from
/// `Corners::child_twins` and the `S` twins inside it.
const M_OWNER: [u8; 64] = {
    let mut o = [0u8; 64];
    let mut x = 0;
    while x < 64 {
        let (i, l) = (x / 4, x % 4);
        let twin = match l {
            0 => match s_inner_twin(i) {
                Some(t) => Some(4 * next_index(t) + 3),
                None => None,
            },
            1 => Some(4 * next_index(i) + 2),
            2 => Some(4 * prev_index(i) + 1),
            _ => match s_inner_twin(prev_index(i)) {
                Some(t) => Some(4 * t),
                None => None,
            },
        };
        o[x] = match twin {
            Some(t) if t < x => t as u8,
            _ => x as u8,
        };
        x += 1;
    }
    o
};

/// The bits of the corners in `owner` that own an edge inside the face.
const fn inner_owners(owner: &[u8]) -> u64 {
    let mut bits = 0u64;
    let mut i = 0;
    while i < owner.len() {
        if owner[i] as usize == i {
            bits |= 1 << i;
        }
        i += 1;
    }
    bits
}

/// The twins of the child corners along base edge `k` of a base face whose base corners have
/// twins `tb`: the base face across the edge, `tb[k] / 4`, and there its corners along its
/// edge `tb[k] % 4` (the same edge, the other way), reversed so that place `p` is the twin of
/// `along[k][p]`.
#[inline(always)]
fn across<const P: usize>(tb: &[u32; 4], along: &[[u8; P]; 4], k: usize) -> (u32, [u8; P]) {
    let theirs = &along[(tb[k] % 4) as usize];
    (tb[k] / 4, core::array::from_fn(|p| theirs[P - 1 - p]))
}

/// The owner bits of the `N` child corners (`S`: 16, `M`: 64) of base face `f` whose base corners
/// have twins `tb`: the fixed ones inside the face, and along each base edge `k` the corners that
/// come before their twins, which are in the face across it (`g = tb[k] / 4`, along its edge
/// `tb[k] % 4` the other way).
#[inline(always)]
fn owner_mask<const N: usize, const P: usize>(f: u32, tb: &[u32; 4], along: &[[u8; P]; 4], owner: &[u8; N]) -> u64 {
    let mut bits = inner_owners(owner) & !along.iter().flatten().fold(0, |m, &i| m | 1u64 << i);
    for (k, ours) in along.iter().enumerate() {
        let (g, theirs) = across(tb, along, k);
        for (&i, &j) in ours.iter().zip(&theirs) {
            let own = N as u32 * f + u32::from(i) < N as u32 * g + u32::from(j);
            bits |= u64::from(own) << i;
        }
    }
    bits
}

/// The edge numbers of the `N` child corners of base face `f` (as [`owner_mask`]): an owner's
/// is `base[f]` plus the owners before it in the face; a corner inside the face has its
/// owner's; one along a base edge that does not own has its twin's in the face across.
#[inline(always)]
fn edge_numbers<const N: usize, const P: usize>(
    f: u32,
    tb: &[u32; 4],
    along: &[[u8; P]; 4],
    owner: &[u8; N],
    mask: impl Fn(usize) -> u64,
    base: &[u32],
) -> [u32; N] {
    let rank = |g: usize, i: u8| base[g] + (mask(g) & ((1u64 << i) - 1)).count_ones();
    let own: [u32; N] = core::array::from_fn(|i| rank(f as usize, i as u8));
    let mut e: [u32; N] = core::array::from_fn(|i| own[owner[i] as usize]);
    let m = mask(f as usize);
    for (k, ours) in along.iter().enumerate() {
        let (g, theirs) = across(tb, along, k);
        for (&i, &j) in ours.iter().zip(&theirs) {
            let twin = rank(g as usize, j);
            e[i as usize] = if m >> i & 1 != 0 { e[i as usize] } else { twin };
        }
    }
    e
}

impl<'a> Numbers<'a> {
    fn new(base: &'a QuadLevel) -> Self {
        let (mut s_masks, mut m_masks) = (Vec::new(), Vec::new());
        (0..base.num_faces() as u32)
            .into_par_iter()
            .with_min_len(FACES)
            .map(|f| {
                let tb = quad_twins(&base.twin, f);
                (owner_mask(f, &tb, &S_ALONG, &S_OWNER) as u16, owner_mask(f, &tb, &M_ALONG, &M_OWNER))
            })
            .unzip_into_vecs(&mut s_masks, &mut m_masks);
        let s_base = counts_before(s_masks.len(), |f| s_masks[f as usize].count_ones());
        let m_base = counts_before(m_masks.len(), |f| m_masks[f as usize].count_ones());
        Self { base, s_masks, m_masks, s_base, m_base }
    }

    /// Number of `S` edges.
    fn num_s_edges(&self) -> u32 {
        *self.s_base.last().expect("one more count than faces")
    }

    /// Number of `M` edges.
    fn num_m_edges(&self) -> u32 {
        *self.m_base.last().expect("one more count than faces")
    }

    /// Writes the corners of the 64 level-3 quads of base face `f` into `out` (256 values; `F`
    /// faces `64f .. 64f + 64`, the children of its `M` corners): per `M` corner `x`,
    /// `(v_x, e(x), face of x, e(prev x))` as level-3 vertices, the `M` corners themselves the
    /// children's of its `S` corners, and those of its base corners.
    #[inline(always)]
    fn quads_of(&self, f: u32, starts: &[u32; 7], out: &mut [u32]) {
        let tb = quad_twins(&self.base.twin, f);
        let (s0, m0) = (16 * f, 64 * f);
        // the S vertices of the S corners (children of the base corners)
        let sv = self.base.child_corners_of(f, starts[0], starts[1]);
        // the S edges of the S corners, as M vertices
        let e1 =
            edge_numbers(f, &tb, &S_ALONG, &S_OWNER, |g| self.s_masks[g].into(), &self.s_base).map(|e| starts[2] + e);
        // the M vertices of the M corners
        let mut mv = [0u32; 64];
        for i in 0..16 {
            let quad = [sv[i], e1[i], starts[3] + (s0 + i as u32) / 4, e1[prev_index(i)]];
            mv[4 * i..4 * i + 4].copy_from_slice(&quad);
        }
        // the M edges of the M corners, as F vertices
        let e2 = edge_numbers(f, &tb, &M_ALONG, &M_OWNER, |g| self.m_masks[g], &self.m_base).map(|e| starts[4] + e);
        for (x, quad) in out.chunks_exact_mut(4).enumerate() {
            quad.copy_from_slice(&[mv[x], e2[x], starts[5] + (m0 + x as u32) / 4, e2[prev_index(x)]]);
        }
    }
}

/// Where the level-3 vertices go: the output's parts (the level-by-level layout: base
/// vertices, then the vertices on base edges, base faces, `S` edges, `S` faces, `M` edges, `M`
/// faces) and, per base face, the ones it writes.
struct Layout<'a> {
    numbers: Numbers<'a>,
    /// The starts of the parts: base edges, base faces (the level-1 vertices on them), `S`
    /// edges, `S` faces, `M` edges, `M` faces, and the end.
    starts: [u32; 7],
}

impl<'a> Layout<'a> {
    fn new(base: &'a QuadLevel) -> Self {
        let numbers = Numbers::new(base);
        let (nv, ne, nf) = (base.num_vertices() as u32, base.num_edges() as u32, base.num_faces() as u32);
        let (nvs, nes) = (nv + ne + nf, numbers.num_s_edges());
        let (nvm, nem) = (nvs + nes + 4 * nf, numbers.num_m_edges());
        let starts = [nv, nv + ne, nvs, nvs + nes, nvm, nvm + nem, nvm + nem + 16 * nf];
        Self { numbers, starts }
    }

    /// The ranges of the parts that base faces `f0 .. f1` write (empty for the base vertices).
    #[inline(always)]
    fn ranges(&self, f0: u32, f1: u32) -> [(u32, u32); 6] {
        let st = &self.starts;
        let n = &self.numbers;
        let (b, s, m) = (&n.base.edge_base, &n.s_base, &n.m_base);
        let (f0, f1) = (f0 as usize, f1 as usize);
        [
            (st[0] + b[f0], st[0] + b[f1]),
            (st[1] + f0 as u32, st[1] + f1 as u32),
            (st[2] + s[f0], st[2] + s[f1]),
            (st[3] + 4 * f0 as u32, st[3] + 4 * f1 as u32),
            (st[4] + m[f0], st[4] + m[f1]),
            (st[5] + 16 * f0 as u32, st[5] + 16 * f1 as u32),
        ]
    }
}

/// Three Catmull-Clark levels of the regular quad mesh with tables `base` (see
/// [`is_regular`]) and `positions`; `colors` carried with the same weights, or, with
/// `color_by_level`, the vertices coloured by the level they were born at.
pub(super) fn subdivide3(base: QuadLevel, positions: &[DVec3], colors: &[DVec3], color_by_level: bool) -> PolyMesh {
    debug_assert!(is_regular(&base));
    let layout = Layout::new(&base);
    let tables = Tables::new();
    let mut corners: Vec<u32> = bytemuck::zeroed_vec(256 * base.num_faces());
    let fine = values(&layout, &tables, positions, Some(&mut corners));
    let colors = if color_by_level {
        let ends = [layout.starts[0], layout.starts[2], layout.starts[4], layout.starts[6]];
        let mut c = Vec::with_capacity(ends[3] as usize);
        for (level, &end) in ends.iter().enumerate() {
            c.resize(end as usize, LEVEL_COLORS[level % LEVEL_COLORS.len()]);
        }
        c
    } else if colors.is_empty() {
        Vec::new()
    } else {
        values(&layout, &tables, colors, None)
    };
    drop(layout);
    drop(base);
    quad_mesh(fine, colors, corners)
}

/// The level-3 values of `p` (and the level-3 corners, into `corners` if given): the base
/// vertices in one pass, everything else per base face, each base face writing the vertices in
/// its ranges of the output ([`Layout::ranges`]).
fn values(layout: &Layout<'_>, tables: &Tables, p: &[DVec3], mut corners: Option<&mut [u32]>) -> Vec<DVec3> {
    let base = layout.numbers.base;
    let st = layout.starts;
    let mut out: Vec<DVec3> = bytemuck::zeroed_vec(st[6] as usize);
    let (old, mut rest) = out.split_at_mut(st[0] as usize);
    // the base vertices: the grid point at a corner, from the vertex, its four neighbours
    // along edges and its four diagonal neighbours (corner c's next two corners, c running
    // around the vertex from its start corner)
    let [wv, we, wd] = tables.vertex;
    let vertex_pass = || {
        old.par_iter_mut().enumerate().with_min_len(MIN_RINGS).for_each(|(v, o)| {
            let at = |c: u32| p[base.corners[c as usize] as usize];
            let (mut edges, mut diagonals) = (DVec3::ZERO, DVec3::ZERO);
            let mut c = base.vertex_start[v];
            for _ in 0..4 {
                edges += at(next(c));
                diagonals += at(next(next(c)));
                c = base.twin[prev(c) as usize];
            }
            *o = p[v] * wv + edges * we + diagonals * wd;
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
        let quads = corners.take().map(|c| {
            let (head, tail) = c.split_at_mut(n);
            corners = Some(tail);
            head
        });
        parts.push((f0 as u32, f1 as u32, block, quads));
    }
    let face_pass = || {
        parts.into_par_iter().for_each(|(f0, f1, block, quads)| {
            crate::wide::wide(
                #[inline(always)]
                || face_block(layout, tables, p, f0, f1, block, quads),
            );
        });
    };
    rayon::join(vertex_pass, face_pass);
    out
}

/// Base faces `f0 .. f1` of the face pass of [`values`]: their level-3 corners (if wanted) and
/// the level-3 vertices they own, into their `block` of the output: the vertices on faces at
/// fixed places, those on edges in the order of their owner corners (the edges a base face
/// owns are numbered one after the other in that order, [`Numbers`]).
#[inline(always)]
fn face_block(
    layout: &Layout<'_>,
    tables: &Tables,
    p: &[DVec3],
    f0: u32,
    f1: u32,
    block: [&mut [DVec3]; 6],
    mut quads: Option<&mut [u32]>,
) {
    let (numbers, st) = (&layout.numbers, &layout.starts);
    let base = numbers.base;
    let [base_edges, faces, s_edges, s_faces, m_edges, m_faces] = block;
    let first = |counts: &[u32], f: u32| (counts[f as usize] - counts[f0 as usize]) as usize;
    let (mut rows, mut points) = ([[[0.0; 3]; SIDE]; 4], [[0.0; 3 * SIDE]; SIDE]);
    for f in f0..f1 {
        let r = (f - f0) as usize;
        if let Some(out) = &mut quads {
            numbers.quads_of(f, st, &mut out[256 * r..256 * (r + 1)]);
        }
        grid(&tables.halves, &net(base, p, f), &mut rows, &mut points);
        let values: &[DVec3; SIDE * SIDE] = bytemuck::cast_ref(&points);
        let copy = |out: &mut [DVec3], grid: &[u8]| {
            for (o, &g) in out.iter_mut().zip(grid) {
                *o = values[g as usize];
            }
        };
        // the owned edges' vertices: the owners by their bits, in order
        let owned = |out: &mut [DVec3], start: usize, mut bits: u64, grid: &[u8]| {
            for o in &mut out[start..start + bits.count_ones() as usize] {
                *o = values[grid[bits.trailing_zeros() as usize] as usize];
                bits &= bits - 1;
            }
        };
        faces[r] = values[FACE_GRID as usize];
        copy(&mut s_faces[4 * r..4 * r + 4], &S_FACE_GRID);
        copy(&mut m_faces[16 * r..16 * r + 16], &M_FACE_GRID);
        owned(base_edges, first(&base.edge_base, f), base.owners(f).into(), &BASE_EDGE_GRID);
        owned(s_edges, first(&numbers.s_base, f), numbers.s_masks[f as usize].into(), &S_EDGE_GRID);
        owned(m_edges, first(&numbers.m_base, f), numbers.m_masks[f as usize], &M_EDGE_GRID);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::subdiv::catmull_clark::quad_levels::Corners;

    /// A `rows` x `cols` quad torus, bumped so that no two coordinates are alike, each face's
    /// corners rotated by a pseudo-random amount (so that neighbours meet along any pair of
    /// their edges).
    fn torus(rows: u32, cols: u32, rotate: bool) -> PolyMesh {
        let mut mesh = PolyMesh::default();
        for i in 0..rows {
            for j in 0..cols {
                let tau = std::f64::consts::TAU;
                let (u, v) = (f64::from(i) / f64::from(rows) * tau, f64::from(j) / f64::from(cols) * tau);
                let r = 3.0 + (1.0 + 0.1 * f64::from((i * 7 + j * 3) % 5)) * v.cos();
                mesh.positions.push(DVec3::new(r * u.cos(), r * u.sin(), v.sin() + 0.01 * f64::from(i)));
            }
        }
        let at = |i: u32, j: u32| (i % rows) * cols + j % cols;
        for i in 0..rows {
            for j in 0..cols {
                let mut quad = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                if rotate {
                    quad.rotate_left(((i * 5 + j * 3 + i * j) % 4) as usize);
                }
                mesh.face_vertices.extend(quad);
                mesh.face_offsets.push(mesh.face_vertices.len() as u32);
            }
        }
        mesh
    }

    /// A level given by its twins alone.
    struct Twins(Vec<u32>);

    impl Corners for Twins {
        fn twin(&self, c: u32) -> u32 {
            self.0[c as usize]
        }
    }

    /// The owner masks and edge numbers of the fixed tables ([`owner_mask`], [`edge_numbers`])
    /// equal those of the level-by-level rules: the `S` and `M` twins from
    /// [`Corners::child_twins`] applied to the whole base level and then to its child, an owner
    /// being a corner before its twin, edges numbered in the order of their owners.
    #[test]
    fn tables_agree_with_the_child_twins_of_whole_levels() {
        use crate::subdiv::rings::Rings;
        for (rows, cols, rotate) in [(3, 3, false), (3, 4, true), (12, 7, false), (12, 7, true), (5, 9, true)] {
            let mesh = torus(rows, cols, rotate);
            let base = QuadLevel::from_quad_rings(Rings::new(&mesh).expect("a closed quad torus"));
            assert!(is_regular(&base));
            let nf = base.num_faces() as u32;
            let base_twins = Twins(base.twin.clone());
            let s = Twins((0..4 * nf).flat_map(|c| base_twins.child_twins(c)).collect());
            let m = Twins((0..16 * nf).flat_map(|c| s.child_twins(c)).collect());
            // edge numbers in the order of their owners
            let numbered = |level: &Twins| {
                let mut number = vec![0u32; level.0.len()];
                let mut next = 0;
                for c in 0..level.0.len() as u32 {
                    let t = level.twin(c);
                    if c < t {
                        number[c as usize] = next;
                        next += 1;
                    } else {
                        number[c as usize] = number[t as usize];
                    }
                }
                number
            };
            let (s_numbers, m_numbers) = (numbered(&s), numbered(&m));
            let numbers = Numbers::new(&base);
            for f in 0..nf {
                let tb = quad_twins(&base.twin, f);
                let bits = |level: &Twins, n: u32| {
                    (0..n).fold(0u64, |b, i| b | u64::from(n * f + i < level.twin(n * f + i)) << i)
                };
                assert_eq!(owner_mask(f, &tb, &S_ALONG, &S_OWNER), bits(&s, 16), "S owners of face {f}");
                assert_eq!(owner_mask(f, &tb, &M_ALONG, &M_OWNER), bits(&m, 64), "M owners of face {f}");
                let e1 = edge_numbers(f, &tb, &S_ALONG, &S_OWNER, |g| numbers.s_masks[g].into(), &numbers.s_base);
                let e2 = edge_numbers(f, &tb, &M_ALONG, &M_OWNER, |g| numbers.m_masks[g], &numbers.m_base);
                assert_eq!(e1[..], s_numbers[16 * f as usize..16 * (f + 1) as usize], "S edges of face {f}");
                assert_eq!(e2[..], m_numbers[64 * f as usize..64 * (f + 1) as usize], "M edges of face {f}");
            }
        }
    }

    /// The grid points of the parts: with the four base corners they cover the 9 x 9 grid, no
    /// point in two parts; the corners of one edge inside a face (a corner and its owner) find
    /// the same point; vertices on base edges lie on the grid's border, the others inside.
    #[test]
    fn part_tables_cover_the_grid_once() {
        let parts: [&[u8]; 6] = [&BASE_EDGE_GRID, &[FACE_GRID], &S_EDGE_GRID, &S_FACE_GRID, &M_EDGE_GRID, &M_FACE_GRID];
        let mut part_of = [None; SIDE * SIDE];
        for g in [0, 8, 80, 72] {
            part_of[g] = Some(usize::MAX);
        }
        for (k, grid) in parts.iter().enumerate() {
            for &g in *grid {
                assert!(part_of[g as usize].is_none_or(|p| p == k), "grid point {g} in parts {part_of:?} and {k}");
                part_of[g as usize] = Some(k);
            }
        }
        assert!(part_of.iter().all(Option::is_some), "{part_of:?}");
        for i in 0..16 {
            assert_eq!(S_EDGE_GRID[i], S_EDGE_GRID[S_OWNER[i] as usize], "S corner {i}");
        }
        for x in 0..64 {
            assert_eq!(M_EDGE_GRID[x], M_EDGE_GRID[M_OWNER[x] as usize], "M corner {x}");
        }
        let border = |g: u8| matches!(g % 9, 0 | 8) || matches!(g / 9, 0 | 8);
        for k in 0..4 {
            for (p, &i) in S_ALONG[k].iter().enumerate() {
                assert!(border(S_EDGE_GRID[i as usize]), "S corner {i} along edge {k} ({p})");
            }
            for &x in &M_ALONG[k] {
                assert!(border(M_EDGE_GRID[x as usize]), "M corner {x} along edge {k}");
            }
            assert!(border(BASE_EDGE_GRID[k]));
        }
        let on_border = parts.iter().flat_map(|grid| grid.iter()).filter(|&&g| border(g)).count();
        assert_eq!(on_border, 4 + 8 + 16, "base edges' middles, S and M halves along them");
    }

    /// Colours carried on a regular mesh follow the weights of the positions: an affine image
    /// of the positions stays that image of the subdivided positions.
    #[test]
    fn carried_colours_follow_the_positions() {
        use crate::subdiv::{CatmullClarkOptions, catmull_clark_subdivide};
        let mut mesh = torus(5, 9, true);
        let image = |p: DVec3| DVec3::new(0.5 * p.x + 0.25, 0.1 * p.y - p.z, 0.3 * p.z + 0.2 * p.x);
        mesh.colors = mesh.positions.iter().map(|&p| image(p)).collect();
        let fine = catmull_clark_subdivide(&mesh, 3, &CatmullClarkOptions::default()).expect("a closed quad torus");
        assert_eq!(fine.colors.len(), fine.positions.len());
        for (k, (&p, &c)) in fine.positions.iter().zip(&fine.colors).enumerate() {
            assert!((image(p) - c).length() < 1e-13, "vertex {k}: {c} against {}", image(p));
        }
    }

    /// The AVX2 build of the face pass ([`crate::wide`]) gives the same mesh, bit for bit, as
    /// the baseline build (on a processor without AVX2 both runs take the baseline path).
    #[test]
    fn wide_and_baseline_paths_give_the_same_bits() {
        use crate::subdiv::{CatmullClarkOptions, catmull_clark_subdivide};
        use std::sync::atomic::Ordering;
        let mesh = torus(12, 7, true);
        let options = CatmullClarkOptions::default();
        let wide = catmull_clark_subdivide(&mesh, 3, &options).expect("a closed quad torus");
        crate::wide::BASELINE.store(true, Ordering::Relaxed);
        let baseline = catmull_clark_subdivide(&mesh, 3, &options);
        crate::wide::BASELINE.store(false, Ordering::Relaxed);
        let baseline = baseline.expect("a closed quad torus");
        assert_eq!(wide.face_vertices, baseline.face_vertices);
        assert_eq!(wide.positions.len(), baseline.positions.len());
        for (k, (a, b)) in wide.positions.iter().zip(&baseline.positions).enumerate() {
            assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits), "vertex {k}");
        }
    }
}
