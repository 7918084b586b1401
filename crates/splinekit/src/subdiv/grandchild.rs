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
//! times smaller, and never writes `M`'s.

use rayon::prelude::*;

use super::groups::groups;
use super::loop_scheme::{Attribute, Rules, even_ring};
use super::topology::{MIN_LEN, Table, next, prev};
use crate::mesh::NONE;

/// The values of the grandchild `F` of `s`, from the values `pm` of its child `M`: the `M`
/// vertices moved (`|V_M|` values), then one odd value per `M` edge.
pub(crate) fn grandchild_values<T: Attribute>(s: &Table<'_>, pm: &[T], rules: &Rules) -> Vec<T> {
    let nv = s.num_vertices() as u32;
    let ne = s.num_edges() as u32;
    let nf = s.num_faces() as u32;
    let nvm = nv + ne;
    let total = nvm + 2 * ne + 3 * nf;
    debug_assert_eq!(pm.len(), nvm as usize);
    let m = |h: u32| nv + s.edge_of(h);
    let beta6 = rules.beta(6);
    let mut out = Vec::with_capacity(total as usize);
    // The M vertices of S vertices: their M rings are their S rings, through the odd vertices.
    let old = (0..nv).into_par_iter().with_min_len(MIN_LEN).map(|v| {
        let mid = |h: u32| pm[m(h) as usize];
        even_ring(s, pm[v as usize], v, rules, mid, mid)
    });
    // The M vertices of S edges: valence 6 inside, 4 on the boundary.
    let new = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        let pv = pm[(nv + e) as usize];
        let h = s.edge_owner(e);
        let (f, i) = (h / 3, h % 3);
        let t = s.tri(f);
        let a = pm[t[i as usize] as usize];
        let b = pm[t[next(i) as usize] as usize];
        let tw = s.twin(h);
        if tw == NONE {
            return pv * 0.75 + (b + a) * 0.125;
        }
        let (g, j) = (tw / 3, tw % 3);
        let mut sum = T::default() + b;
        sum = sum + pm[m(3 * f + next(i)) as usize];
        sum = sum + pm[m(3 * f + prev(i)) as usize];
        sum = sum + a;
        sum = sum + pm[m(3 * g + next(j)) as usize];
        sum = sum + pm[m(3 * g + prev(j)) as usize];
        pv * (1.0 - 6.0 * beta6) + sum * beta6
    });
    // The odd vertices of the two halves of each S edge.
    let halves = groups(ne as usize, |e| {
        let h = s.edge_owner(e);
        let (f, i) = (h / 3, h % 3);
        let tw = s.twin(h);
        let t = s.tri(f);
        let mi = pm[m(h) as usize];
        let (va, vb) = (pm[t[i as usize] as usize], pm[t[next(i) as usize] as usize]);
        if tw == NONE {
            return [(va + mi) * 0.5, (mi + vb) * 0.5];
        }
        let (g, j) = (tw / 3, tw % 3);
        let (fn_, fp) = (pm[m(3 * f + next(i)) as usize], pm[m(3 * f + prev(i)) as usize]);
        let (gn, gp) = (pm[m(3 * g + next(j)) as usize], pm[m(3 * g + prev(j)) as usize]);
        [(va + mi) * 0.375 + (fp + gn) * 0.125, (mi + vb) * 0.375 + (fn_ + gp) * 0.125]
    })
    .with_min_len(MIN_LEN);
    // The odd vertices of the edges between c_i and c_3 of each S triangle.
    let inner = groups(nf as usize, |f| {
        let t = s.tri(f);
        let mv = [pm[m(3 * f) as usize], pm[m(3 * f + 1) as usize], pm[m(3 * f + 2) as usize]];
        let v = [pm[t[0] as usize], pm[t[1] as usize], pm[t[2] as usize]];
        [0, 1, 2].map(|i| (mv[i] + mv[prev(i as u32) as usize]) * 0.375 + (v[i] + mv[next(i as u32) as usize]) * 0.125)
    })
    .with_min_len(MIN_LEN);
    old.chain(new).chain(halves).chain(inner).collect_into_vec(&mut out);
    debug_assert_eq!(out.len(), total as usize);
    out
}

/// The triangles of the grandchild `F` of `s`: S triangle `f` becomes `16f .. 16f + 16`.
pub(crate) fn grandchild_triangles(s: &Table<'_>) -> Vec<[u32; 3]> {
    let nv = s.num_vertices() as u32;
    let ne = s.num_edges() as u32;
    let nf = s.num_faces() as u32;
    let nvm = nv + ne;
    let mut out = Vec::new();
    groups(nf as usize, |f| {
        let t = s.tri(f);
        let (ef, tw) = (s.face_edges(f), s.face_twins(f));
        let mut mv = [0u32; 3];
        let mut first = [0u32; 3];
        let mut second = [0u32; 3];
        for i in 0..3 {
            let h = 3 * f + i;
            let e = ef[i as usize];
            let t = tw[i as usize];
            let own = u32::from(t == NONE || h < t);
            mv[i as usize] = nv + e;
            // M edges of the two halves of h_i, as vertices of F.
            first[i as usize] = nvm + 2 * e + 1 - own;
            second[i as usize] = nvm + 2 * e + own;
        }
        let interior = nvm + 2 * ne + 3 * f;
        let mut out = [[0u32; 3]; 16];
        for k in 0..4u32 {
            // M triangle c_k and the F vertices of its edges.
            let (x, y) = if k < 3 {
                let i = k as usize;
                let p = prev(k) as usize;
                ([t[i], mv[i], mv[p]], [first[i], interior + k, second[p]])
            } else {
                (mv, [interior + 1, interior + 2, interior])
            };
            let o = &mut out[4 * k as usize..4 * k as usize + 4];
            o[0] = [x[0], y[0], y[2]];
            o[1] = [x[1], y[1], y[0]];
            o[2] = [x[2], y[2], y[1]];
            o[3] = y;
        }
        out
    })
    .with_min_len(MIN_LEN)
    .collect_into_vec(&mut out);
    out
}
