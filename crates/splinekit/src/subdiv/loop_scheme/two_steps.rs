//! The level two Loop steps below a level with stored tables, without the tables (or the
//! triangles) of the level in between.
//!
//! With `S` the stored level (triangles `[v0, v1, v2]`, edges `e`, `m_i = |V_S| + edge(h_i)`),
//! its child `M` has the triangles `c_i = [v_i, m_i, m_{i−1}]` and `c_3 = [m0, m1, m2]` at
//! `4f + k`, the edges `2e`, `2e + 1` (the halves of `e`, the owner's first half first) and
//! `2|E_S| + 3f + i` (between `c_i` and `c_3`), as [`topology`](super::topology) sets out.
//! Every stencil of the grandchild `F` — the ring of an `M` vertex, the four vertices around
//! an `M` edge, the triangles of `F` — is therefore a fixed pattern over one `S` triangle or
//! the two along one `S` edge. This module evaluates those patterns directly from `S`'s
//! tables and `M`'s values, in the same order of operations as the general passes over `M`
//! (see `loop_scheme`), so the results are the same to the bit; but it reads tables four
//! times smaller, and never writes `M`'s. ([`great`](super::great) goes one level further.)

use bytemuck::{Pod, Zeroable};
use rayon::prelude::*;

use super::stencils::even_ring;
use crate::mesh::NONE;
use crate::subdiv::attribute::Attribute;
use crate::subdiv::options::Rules;
use crate::subdiv::topology::{MIN_LEN, MIN_RINGS, Table, next, prev, three};

/// The values of the grandchild `F` of `s`, from the values `pm` of its child `M`: the `M`
/// vertices moved (`|V_M|` values), then one odd value per `M` edge.
///
/// One fork-join of three parallel passes, each writing its own part of the (zeroed) output:
/// over `S` vertices, over `S` edges (the `M` vertex on the edge and the odd vertices of its
/// two halves, which read the same stencil), and over `S` triangles.
pub(crate) fn grandchild_values<T: Attribute + Zeroable>(s: &Table<'_>, pm: &[T], rules: &Rules) -> Vec<T> {
    let nv = s.num_vertices() as u32;
    let ne = s.num_edges() as u32;
    let nf = s.num_faces() as u32;
    let nvm = nv + ne;
    let total = nvm + 2 * ne + 3 * nf;
    debug_assert_eq!(pm.len(), nvm as usize);
    let m = |h: u32| nv + s.edge_of(h);
    let beta6 = rules.beta(6);
    let mut out: Vec<T> = bytemuck::zeroed_vec(total as usize);
    let (old, rest) = out.split_at_mut(nv as usize);
    let (new, rest) = rest.split_at_mut(ne as usize);
    let (halves, inner) = rest.split_at_mut(2 * ne as usize);
    // The M vertices of S vertices: their M rings are their S rings, through the odd vertices.
    let old_pass = || {
        old.par_iter_mut().enumerate().with_min_len(MIN_RINGS).for_each(|(v, o)| {
            let v = v as u32;
            let mid = |h: u32| pm[m(h) as usize];
            *o = even_ring(s, pm[v as usize], v, rules, mid, mid);
        });
    };
    // Per S edge: the M vertex on it (valence 6 inside, 4 on the boundary), then the odd
    // vertices of its two halves.
    let edge_pass = || {
        new.par_iter_mut().zip(halves.par_chunks_mut(2)).enumerate().with_min_len(MIN_LEN / 4).for_each(
            |(e, (o, halves))| {
                let h = s.edge_owner(e as u32);
                let (f, i) = (h / 3, h % 3);
                let t = s.tri(f);
                let mi = pm[(nv + e as u32) as usize];
                let (a, b) = (pm[t[i as usize] as usize], pm[t[next(i) as usize] as usize]);
                let tw = s.twin(h);
                if tw == NONE {
                    *o = mi * 0.75 + (b + a) * 0.125;
                    halves[0] = (a + mi) * 0.5;
                    halves[1] = (mi + b) * 0.5;
                    return;
                }
                let (g, j) = (tw / 3, tw % 3);
                let (fn_, fp) = (pm[m(3 * f + next(i)) as usize], pm[m(3 * f + prev(i)) as usize]);
                let (gn, gp) = (pm[m(3 * g + next(j)) as usize], pm[m(3 * g + prev(j)) as usize]);
                let sum = T::default() + b + fn_ + fp + a + gn + gp;
                *o = mi * (1.0 - 6.0 * beta6) + sum * beta6;
                halves[0] = (a + mi) * 0.375 + (fp + gn) * 0.125;
                halves[1] = (mi + b) * 0.375 + (fn_ + gp) * 0.125;
            },
        );
    };
    // The odd vertices of the edges between c_i and c_3 of each S triangle.
    let face_pass = || {
        inner.par_chunks_mut(3).enumerate().with_min_len(MIN_LEN / 3).for_each(|(f, o)| {
            let f = f as u32;
            let t = s.tri(f);
            let mv = [pm[m(3 * f) as usize], pm[m(3 * f + 1) as usize], pm[m(3 * f + 2) as usize]];
            let v = [pm[t[0] as usize], pm[t[1] as usize], pm[t[2] as usize]];
            for i in 0..3 {
                let (p, n) = (prev(i as u32) as usize, next(i as u32) as usize);
                o[i] = (mv[i] + mv[p]) * 0.375 + (v[i] + mv[n]) * 0.125;
            }
        });
    };
    rayon::join(old_pass, || rayon::join(edge_pass, face_pass));
    out
}

/// The triangles of the grandchild `F` of `s`: S triangle `f` becomes `16f .. 16f + 16`.
pub(crate) fn grandchild_triangles(s: &Table<'_>) -> Vec<[u32; 3]> {
    let nv = s.num_vertices() as u32;
    let ne = s.num_edges() as u32;
    in_groups::<_, 64>(s.num_faces(), |f| {
        let tw = s.face_twins(f);
        let own = three(|i| u32::from(tw[i] == NONE || 3 * f + (i as u32) < tw[i]));
        sixteen(nv, ne, f, s.tri(f), s.face_edges(f), own)
    })
}

/// The triangles `make(0), make(1), …, make(n − 1)` (each a fixed number of triangles, as
/// arrays), collected `G` results at a time: large items (12 KiB for the callers' `G`) are
/// copied into the output as whole blocks, much faster than many small ones; then the bytes
/// are reinterpreted as triangles.
pub(super) fn in_groups<T: Pod + Send, const G: usize>(n: usize, make: impl Fn(u32) -> T + Sync) -> Vec<[u32; 3]> {
    let mut out: Vec<[T; G]> = Vec::new();
    (0..n.div_ceil(G))
        .into_par_iter()
        .with_min_len((MIN_LEN * size_of::<[u32; 3]>() / size_of::<[T; G]>()).max(1))
        .map(|g| {
            core::array::from_fn(|k| {
                let f = g * G + k;
                if f < n { make(f as u32) } else { T::zeroed() }
            })
        })
        .collect_into_vec(&mut out);
    let mut out: Vec<[u32; 3]> = bytemuck::cast_vec(out);
    // The last item's places past the end.
    out.truncate(n * size_of::<T>() / size_of::<[u32; 3]>());
    out
}

/// The 16 triangles of the grandchild `F` in triangle `f` of a level `S` with `nv` vertices
/// and `ne` edges, whose corners are `t`, whose half-edges have the edges `ef`, and own them
/// where `own` is 1.
#[inline]
pub(super) fn sixteen(nv: u32, ne: u32, f: u32, t: [u32; 3], ef: [u32; 3], own: [u32; 3]) -> [[u32; 3]; 16] {
    let nvm = nv + ne;
    // M vertices on the S edges, and the M edges of the two halves of each, as F vertices.
    let mv = three(|i| nv + ef[i]);
    let first = three(|i| nvm + 2 * ef[i] + 1 - own[i]);
    let second = three(|i| nvm + 2 * ef[i] + own[i]);
    let interior = nvm + 2 * ne + 3 * f;
    // M triangle c_k and the F vertices of its edges, split in four.
    let split = |x: [u32; 3], y: [u32; 3]| [[x[0], y[0], y[2]], [x[1], y[1], y[0]], [x[2], y[2], y[1]], y];
    let c = |k: usize| {
        let p = prev(k as u32) as usize;
        split([t[k], mv[k], mv[p]], [first[k], interior + k as u32, second[p]])
    };
    let [a, b, c, d] = [c(0), c(1), c(2), split(mv, [interior + 1, interior + 2, interior])];
    [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3], c[0], c[1], c[2], c[3], d[0], d[1], d[2], d[3]]
}
