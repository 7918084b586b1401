//! The level three Loop steps below a level with stored tables, from the values of the level
//! two steps below, without the tables (or the triangles) of the two levels in between.
//!
//! With `B` the stored level, `S` its child, `M` the child of `S` (whose values are given) and
//! `F` the child of `M`: [`grandchild`](super::grandchild) makes `F` from `S`'s tables, and
//! `S`'s tables are closed-form functions of `B`'s ([`topology`](super::topology)). Spelled
//! out, every stencil of `F` is a fixed pattern over one `B` triangle (the stencils inside
//! its four `S` triangles), over the two `B` triangles along one `B` edge (around the two
//! halves of the edge and the `S` vertex on it) or over the ring of one `B` vertex. This
//! module evaluates those patterns from `B`'s tables, which are 16 times smaller than `M`'s,
//! in the same order of operations as `grandchild`, so the results are the same to the bit.
//!
//! Notation (see `topology`): `B` triangle `f = [v0, v1, v2]` with half-edges `h_i = 3f + i`
//! on edges `e_i`, `m_i = |V_B| + e_i` the `S` vertex on `e_i`, `S` triangles
//! `c_i = [v_i, m_i, m_{i−1}]` and `c_3 = [m0, m1, m2]` at `4f + k`. The `S` edges are
//! `2e_i + 1 − own_i` (the first half of `h_i`, from `v_i`), `2e_i + own_i` (its second
//! half), where `own_i` is whether `h_i` owns `e_i`, and `2|E_B| + 3f + i` (between `c_i`
//! and `c_3`, from `m_i` to `m_{i−1}`). `M`'s values are `|V_S|` values on `S` vertices, then
//! one per `S` edge.

use bytemuck::Zeroable;
use rayon::prelude::*;

use super::stencils::even_ring;
use super::two_steps::{in_groups, sixteen};
use crate::mesh::NONE;
use crate::subdiv::attribute::Attribute;
use crate::subdiv::options::Rules;
use crate::subdiv::topology::{MIN_LEN, MIN_RINGS, Table, next, prev, three};

/// Whether half-edge `h`, whose twin is `tw`, owns its edge (0 or 1).
#[inline]
fn own(h: u32, tw: u32) -> u32 {
    u32::from(tw == NONE || h < tw)
}

/// The values of the great-grandchild `F` of `b`, from the values `pm` of its grandchild `M`:
/// the `M` vertices moved, then one odd value per `M` edge (the layout of
/// [`grandchild_values`](super::grandchild::grandchild_values) over `b`'s child).
///
/// One fork-join of three parallel passes, each writing its own parts of the (zeroed)
/// output: over `B` vertices (the `M` vertices on them), over `B` edges (the `M` vertex on
/// the `S` vertex of the edge, and the values of the two `S` edges that halve it), and over
/// `B` triangles (the values of their three interior `S` edges and of their four `S`
/// triangles).
pub(crate) fn great_grandchild_values<T: Attribute + Zeroable>(b: &Table<'_>, pm: &[T], rules: &Rules) -> Vec<T> {
    let nvb = b.num_vertices() as u32;
    let neb = b.num_edges() as u32;
    let nfb = b.num_faces() as u32;
    let (nvs, nes, nfs) = (nvb + neb, 2 * neb + 3 * nfb, 4 * nfb);
    let total = nvs + nes + 2 * nes + 3 * nfs;
    debug_assert_eq!(pm.len(), (nvs + nes) as usize);
    // M values: on S vertex x, and on S edge y.
    let at = |x: u32| pm[x as usize];
    let on = |y: u32| pm[(nvs + y) as usize];
    // S edges: the halves of h (with edge e and ownership o), and the interior ones.
    let first = |e: u32, o: u32| 2 * e + 1 - o;
    let second = |e: u32, o: u32| 2 * e + o;
    let inside = |f: u32, i: u32| 2 * neb + 3 * f + i;
    let beta6 = rules.beta(6);
    let even6 = |p: T, sum: T| p * (1.0 - 6.0 * beta6) + sum * beta6;

    let mut out: Vec<T> = bytemuck::zeroed_vec(total as usize);
    // The M vertices on S vertices: those of B vertices, then those of B edges.
    let (old_v, rest) = out.split_at_mut(nvb as usize);
    let (old_e, rest) = rest.split_at_mut(neb as usize);
    // The M vertices on S edges: the halves of B edges, then the interior ones.
    let (new_e, rest) = rest.split_at_mut(2 * neb as usize);
    let (new_f, rest) = rest.split_at_mut(3 * nfb as usize);
    // The odd vertices of the two halves of each M edge, in the same order.
    let (halves_e, rest) = rest.split_at_mut(4 * neb as usize);
    let (halves_f, inner) = rest.split_at_mut(6 * nfb as usize);

    // B vertex v: its S ring is its B ring, each B half-edge h standing for its first half
    // (leaving v) and, coming into v, its second half.
    let vertex_pass = || {
        old_v.par_iter_mut().enumerate().with_min_len(MIN_RINGS).for_each(|(v, o)| {
            let out = |h: u32| on(first(b.edge_of(h), own(h, b.twin(h))));
            let inc = |h: u32| on(second(b.edge_of(h), own(h, b.twin(h))));
            *o = even_ring(b, at(v as u32), v as u32, rules, out, inc);
        });
    };

    // B edge e, owned by h_i of triangle f, twin h_j of triangle g. Its S vertex m = m_i has
    // the ring (from its start, the second half of h_i): second half of h_i, interior i + 1
    // and i of f, second half of h_j (the first half of e), interior j + 1 and j of g. Its
    // halves: S edge 2e (the first half of h_i, in c_i) and 2e + 1 (its second half, in
    // c_{i+1}), whose twins are the second half of h_j (in g's c_{j+1}) and its first half
    // (in g's c_j).
    let edge_pass = || {
        old_e
            .par_iter_mut()
            .zip(new_e.par_chunks_mut(2))
            .zip(halves_e.par_chunks_mut(4))
            .enumerate()
            .with_min_len(MIN_LEN / 4)
            .for_each(|(e, ((o, new), halves))| {
                let e = e as u32;
                let h = b.edge_owner(e);
                let (f, i) = (h / 3, h % 3);
                let (ni, pi) = (next(i), prev(i));
                let t = b.tri(f);
                let (ef, tf) = (b.face_edges(f), b.face_twins(f));
                let (vi, vn, m) = (at(t[i as usize]), at(t[ni as usize]), at(nvb + e));
                let (lo, hi) = (on(2 * e), on(2 * e + 1));
                let (fi, fni) = (on(inside(f, i)), on(inside(f, ni)));
                let tw = tf[i as usize];
                if tw == NONE {
                    *o = m * 0.75 + (hi + lo) * 0.125;
                    new[0] = lo * 0.75 + (m + vi) * 0.125;
                    new[1] = hi * 0.75 + (vn + m) * 0.125;
                    halves[0] = (vi + lo) * 0.5;
                    halves[1] = (lo + m) * 0.5;
                    halves[2] = (m + hi) * 0.5;
                    halves[3] = (hi + vn) * 0.5;
                    return;
                }
                let (pi, ni) = (pi as usize, ni as usize);
                // c_i's second half of h_{i−1}, c_{i+1}'s first half of h_{i+1}.
                let fp = on(second(ef[pi], own(3 * f + pi as u32, tf[pi])));
                let fn_ = on(first(ef[ni], own(3 * f + ni as u32, tf[ni])));
                let (g, j) = (tw / 3, tw % 3);
                let (nj, pj) = (next(j), prev(j));
                let (eg, tg) = (b.face_edges(g), b.face_twins(g));
                let (gj, gnj) = (on(inside(g, j)), on(inside(g, nj)));
                let (nj, pj) = (nj as usize, pj as usize);
                let gn = on(first(eg[nj], own(3 * g + nj as u32, tg[nj])));
                let gp = on(second(eg[pj], own(3 * g + pj as u32, tg[pj])));
                *o = even6(m, T::default() + hi + fni + fi + lo + gnj + gj);
                // S edge 2e: from v_i to m_i, in c_i.
                new[0] = even6(lo, T::default() + m + fi + fp + vi + gn + gnj);
                halves[0] = (vi + lo) * 0.375 + (fp + gn) * 0.125;
                halves[1] = (lo + m) * 0.375 + (fi + gnj) * 0.125;
                // S edge 2e + 1: from m_i to v_{i+1}, in c_{i+1}.
                new[1] = even6(hi, T::default() + vn + fn_ + fni + m + gj + gp);
                halves[2] = (m + hi) * 0.375 + (fni + gj) * 0.125;
                halves[3] = (hi + vn) * 0.375 + (fn_ + gp) * 0.125;
            });
    };

    // B triangle f: its interior S edge i runs from m_i to m_{i−1} in c_i (whose other edges
    // are the first half of h_i and the second half of h_{i−1}) and back in c_3 (whose other
    // edges are the interior edges i + 1 and i − 1); then the inner values of c_0 .. c_3.
    let face_pass = || {
        new_f
            .par_chunks_mut(3)
            .zip(halves_f.par_chunks_mut(6))
            .zip(inner.par_chunks_mut(12))
            .enumerate()
            .with_min_len(MIN_LEN / 4)
            .for_each(|(f, ((new, halves), inner))| {
                let f = f as u32;
                let t = b.tri(f);
                let (ef, tf) = (b.face_edges(f), b.face_twins(f));
                let o = three(|i| own(3 * f + i as u32, tf[i]));
                let vt = three(|i| at(t[i]));
                let vm = three(|i| at(nvb + ef[i]));
                let pf = three(|i| on(first(ef[i], o[i])));
                let ps = three(|i| on(second(ef[i], o[i])));
                let pint = three(|i| on(inside(f, i as u32)));
                for i in 0..3 {
                    let (ni, pi) = (next(i as u32) as usize, prev(i as u32) as usize);
                    let (mi, a, bv) = (pint[i], vm[i], vm[pi]);
                    let (fn_, fp, gn, gp) = (ps[pi], pf[i], pint[ni], pint[pi]);
                    new[i] = even6(mi, T::default() + bv + fn_ + fp + a + gn + gp);
                    halves[2 * i] = (a + mi) * 0.375 + (fp + gn) * 0.125;
                    halves[2 * i + 1] = (mi + bv) * 0.375 + (fn_ + gp) * 0.125;
                }
                // The S triangles' corners and the M values on their edges.
                for k in 0..4 {
                    let (v, mv) = if k < 3 {
                        let pk = prev(k as u32) as usize;
                        ([vt[k], vm[k], vm[pk]], [pf[k], pint[k], ps[pk]])
                    } else {
                        (vm, [pint[1], pint[2], pint[0]])
                    };
                    for i in 0..3 {
                        let (ni, pi) = (next(i as u32) as usize, prev(i as u32) as usize);
                        inner[3 * k + i] = (mv[i] + mv[pi]) * 0.375 + (v[i] + mv[ni]) * 0.125;
                    }
                }
            });
    };
    rayon::join(vertex_pass, || rayon::join(edge_pass, face_pass));
    out
}

/// The triangles of the great-grandchild `F` of `b`: B triangle `f` becomes `64f .. 64f + 64`
/// (its S triangles `4f + k` each split as in
/// [`grandchild_triangles`](super::grandchild::grandchild_triangles)).
pub(crate) fn great_grandchild_triangles(b: &Table<'_>) -> Vec<[u32; 3]> {
    let nvb = b.num_vertices() as u32;
    let neb = b.num_edges() as u32;
    let (nvs, nes) = (nvb + neb, 2 * neb + 3 * b.num_faces() as u32);
    in_groups::<_, 16>(b.num_faces(), |f| {
        let t = b.tri(f);
        let (ef, tf) = (b.face_edges(f), b.face_twins(f));
        let o = three(|i| own(3 * f + i as u32, tf[i]));
        let m = three(|i| nvb + ef[i]);
        let inside = |i: u32| 2 * neb + 3 * f + i;
        // c_k: the first half of h_k, the interior edge k, the second half of h_{k−1}.
        let c = |k: usize| {
            let p = prev(k as u32) as usize;
            let es = [2 * ef[k] + 1 - o[k], inside(k as u32), 2 * ef[p] + o[p]];
            sixteen(nvs, nes, 4 * f + k as u32, [t[k], m[k], m[p]], es, [o[k], 1, o[p]])
        };
        // c_3: edge i is the interior edge i + 1, owned by c_{i+1}.
        [c(0), c(1), c(2), sixteen(nvs, nes, 4 * f + 3, m, [inside(1), inside(2), inside(0)], [0, 0, 0])]
    })
}
