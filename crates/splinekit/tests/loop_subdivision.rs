//! Loop subdivision against a second, naive implementation (hash maps and neighbour sets,
//! written from SPEC §3.2 alone), and against invariants: counts, Euler characteristic,
//! closed and consistently oriented output, affine invariance, thread independence, seams.

use std::collections::{BTreeSet, HashMap};

use glam::{DMat3, DVec2, DVec3};
use splinekit::subdiv::{BoundaryRule, LoopOptions, LoopPyramid, LoopWeights, loop_subdivide};
use splinekit::{FaceVarying, PolyMesh};

mod common;
use common::icosahedron;

/// An `n × m` grid of squares over [0,1]², two triangles each, with a wavy height; `wrap`
/// makes it a torus (positions on a torus of radii 2 and 0.7).
fn grid(n: u32, m: u32, wrap: bool) -> PolyMesh {
    let (cols, rows) = if wrap { (n, m) } else { (n + 1, m + 1) };
    let id = |i: u32, j: u32| (j % rows) * cols + (i % cols);
    let mut positions = Vec::new();
    for j in 0..rows {
        for i in 0..cols {
            let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(m));
            positions.push(if wrap {
                let (a, b) = (u * std::f64::consts::TAU, v * std::f64::consts::TAU);
                DVec3::new((2.0 + 0.7 * b.cos()) * a.cos(), (2.0 + 0.7 * b.cos()) * a.sin(), 0.7 * b.sin())
            } else {
                DVec3::new(u, v, 0.1 * (7.0 * u).sin() * (5.0 * v).cos())
            });
        }
    }
    let mut tris = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    PolyMesh::from_triangles(positions, &tris)
}

fn tris(m: &PolyMesh) -> Vec<[u32; 3]> {
    m.triangles().unwrap()
}

/// One Loop step, the obvious way.
fn naive_step(pos: &[DVec3], t: &[[u32; 3]], warren: bool, corners: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut edge_id: HashMap<(u32, u32), usize> = HashMap::new();
    let mut opposite: Vec<Vec<u32>> = Vec::new();
    let mut ends: Vec<(u32, u32)> = Vec::new();
    let mut neighbours = vec![BTreeSet::new(); pos.len()];
    let mut faces_at = vec![0usize; pos.len()];
    for tri in t {
        for k in 0..3 {
            let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let key = (a.min(b), a.max(b));
            let e = *edge_id.entry(key).or_insert_with(|| {
                opposite.push(Vec::new());
                ends.push(key);
                ends.len() - 1
            });
            opposite[e].push(c);
            neighbours[a as usize].insert(b);
            neighbours[b as usize].insert(a);
            faces_at[a as usize] += 1;
        }
    }
    let mut boundary_nb = vec![Vec::new(); pos.len()];
    for (e, &(a, b)) in ends.iter().enumerate() {
        if opposite[e].len() == 1 {
            boundary_nb[a as usize].push(b);
            boundary_nb[b as usize].push(a);
        }
    }
    let mut out = Vec::with_capacity(pos.len() + ends.len());
    for v in 0..pos.len() {
        let p = pos[v];
        let nb = &neighbours[v];
        out.push(if nb.is_empty() || (corners && faces_at[v] == 1) {
            p
        } else if !boundary_nb[v].is_empty() {
            assert_eq!(boundary_nb[v].len(), 2);
            p * 0.75 + (pos[boundary_nb[v][0] as usize] + pos[boundary_nb[v][1] as usize]) * 0.125
        } else {
            let n = nb.len() as f64;
            let beta = if warren {
                if nb.len() == 3 { 3.0 / 16.0 } else { 3.0 / (8.0 * n) }
            } else {
                (5.0 / 8.0 - (3.0 / 8.0 + 0.25 * (2.0 * std::f64::consts::PI / n).cos()).powi(2)) / n
            };
            p * (1.0 - n * beta) + nb.iter().map(|&q| pos[q as usize]).sum::<DVec3>() * beta
        });
    }
    for (e, &(a, b)) in ends.iter().enumerate() {
        let (pa, pb) = (pos[a as usize], pos[b as usize]);
        out.push(match opposite[e][..] {
            [c, d] => (pa + pb) * 0.375 + (pos[c as usize] + pos[d as usize]) * 0.125,
            _ => (pa + pb) * 0.5,
        });
    }
    let nv = pos.len() as u32;
    let m = |a: u32, b: u32| nv + edge_id[&(a.min(b), a.max(b))] as u32;
    let mut child = Vec::new();
    for &[i0, i1, i2] in t {
        let (m01, m12, m20) = (m(i0, i1), m(i1, i2), m(i2, i0));
        child.extend([[i0, m01, m20], [i1, m12, m01], [i2, m20, m12], [m01, m12, m20]]);
    }
    (out, child)
}

/// Every level of the pyramid equals the naive step applied to the level before it: the
/// triangles correspond one to one (same order), and so do their vertices and positions.
fn check_against_naive(mesh: &PolyMesh, levels: usize, options: LoopOptions) {
    let mut pyramid = LoopPyramid::new(mesh, options).unwrap();
    pyramid.refine_to(levels, |_| {}).unwrap();
    let warren = options.weights == LoopWeights::Warren;
    let corners = options.boundary == BoundaryRule::Corners;
    for k in 0..levels {
        let (coarse, fine) = (pyramid.level(k), pyramid.level(k + 1));
        let (pos, child) = naive_step(&coarse.positions, &coarse.triangles, warren, corners);
        assert_eq!(fine.triangles.len(), child.len());
        assert_eq!(fine.positions.len(), pos.len());
        let mut map = vec![u32::MAX; pos.len()];
        for (ours, theirs) in fine.triangles.iter().zip(&child) {
            for (&a, &b) in ours.iter().zip(theirs) {
                assert!(map[a as usize] == u32::MAX || map[a as usize] == b, "level {k}: vertex {a} maps twice");
                map[a as usize] = b;
            }
        }
        let scale = pos.iter().map(|p| p.abs().max_element()).fold(1.0, f64::max);
        for (v, &w) in map.iter().enumerate() {
            let d = (fine.positions[v] - pos[w as usize]).abs().max_element();
            assert!(
                d <= 4e-16 * scale,
                "level {}: vertex {v}: {} vs {} ({d:e})",
                k + 1,
                fine.positions[v],
                pos[w as usize]
            );
        }
        assert_eq!(map.iter().collect::<BTreeSet<_>>().len(), map.len(), "level {}: not a bijection", k + 1);
    }
}

fn options(weights: LoopWeights, boundary: BoundaryRule) -> LoopOptions {
    LoopOptions { weights, boundary, ..LoopOptions::default() }
}

#[test]
fn agrees_with_the_naive_implementation() {
    for weights in [LoopWeights::Loop, LoopWeights::Warren] {
        for boundary in [BoundaryRule::Smooth, BoundaryRule::Corners] {
            let o = options(weights, boundary);
            check_against_naive(&icosahedron(), 3, o);
            check_against_naive(&grid(6, 5, true), 2, o);
            check_against_naive(&grid(5, 4, false), 3, o);
        }
    }
}

fn euler(m: &PolyMesh) -> i64 {
    let t = tris(m);
    let edges: BTreeSet<(u32, u32)> =
        t.iter().flat_map(|t| (0..3).map(|k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])))).collect();
    m.num_vertices() as i64 - edges.len() as i64 + t.len() as i64
}

#[test]
fn counts_and_topology() {
    let ico = icosahedron();
    let one = loop_subdivide(&ico, 1, &LoopOptions::default()).unwrap();
    assert_eq!((one.num_vertices(), one.num_faces()), (42, 80));
    for (mesh, closed) in [(icosahedron(), true), (grid(7, 5, true), true), (grid(4, 6, false), false)] {
        let (mut v, mut f) = (mesh.num_vertices(), mesh.num_faces());
        let chi = euler(&mesh);
        for levels in 1..=3 {
            let e = 3 * f / 2;
            let fine = loop_subdivide(&mesh, levels, &LoopOptions::default()).unwrap();
            if closed {
                assert_eq!(fine.num_vertices(), v + e, "V + E");
                assert_eq!(3 * fine.num_faces() / 2, 2 * e + 3 * f, "2E + 3F");
                assert!(fine.to_tri_mesh().is_closed_oriented());
            }
            assert_eq!(fine.num_faces(), 4 * f);
            assert_eq!(euler(&fine), chi, "Euler characteristic");
            (v, f) = (fine.num_vertices(), fine.num_faces());
        }
    }
}

#[test]
fn affine_invariance_and_flat_stays_flat() {
    let a = DMat3::from_cols(DVec3::new(1.0, 0.2, -0.3), DVec3::new(0.5, 2.0, 0.1), DVec3::new(0.0, -0.4, 0.7));
    let shift = DVec3::new(3.0, -1.0, 2.0);
    for mesh in [icosahedron(), grid(5, 4, false), grid(6, 5, true)] {
        let mut moved = mesh.clone();
        for p in &mut moved.positions {
            *p = a * *p + shift;
        }
        let o = options(LoopWeights::Loop, BoundaryRule::Corners);
        let (f1, f2) = (loop_subdivide(&mesh, 2, &o).unwrap(), loop_subdivide(&moved, 2, &o).unwrap());
        for (p, q) in f1.positions.iter().zip(&f2.positions) {
            assert!((a * *p + shift - *q).length() < 1e-13);
        }
    }
    // A plane stays that plane, boundary included.
    let mut flat = grid(5, 4, false);
    for p in &mut flat.positions {
        p.z = 0.3 * p.x - 0.2 * p.y + 1.0;
    }
    let fine = loop_subdivide(&flat, 3, &LoopOptions::default()).unwrap();
    assert!(fine.positions.iter().all(|p| (p.z - (0.3 * p.x - 0.2 * p.y + 1.0)).abs() < 1e-14));
}

#[test]
fn weights_and_corner_rules_differ_where_they_should() {
    let ico = icosahedron();
    let l = loop_subdivide(&ico, 1, &options(LoopWeights::Loop, BoundaryRule::Smooth)).unwrap();
    let w = loop_subdivide(&ico, 1, &options(LoopWeights::Warren, BoundaryRule::Smooth)).unwrap();
    // Valence-5 even vertices move differently; odd vertices are the same.
    assert!((l.positions[0] - w.positions[0]).length() > 1e-3);
    assert_eq!(l.positions[12..], w.positions[12..]);
    // The open grid's corner (0,0) has a single face only in the [a, c, d] split's other corner;
    // vertex n (the (1,0) corner) belongs to one triangle.
    let g = grid(4, 4, false);
    let smooth = loop_subdivide(&g, 1, &options(LoopWeights::Loop, BoundaryRule::Smooth)).unwrap();
    let fixed = loop_subdivide(&g, 1, &options(LoopWeights::Loop, BoundaryRule::Corners)).unwrap();
    assert_eq!(fixed.positions[4], g.positions[4]);
    assert_ne!(smooth.positions[4], g.positions[4]);
}

#[test]
fn threads_do_not_change_a_bit() {
    let mesh = grid(40, 30, true);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| loop_subdivide(&mesh, 3, &LoopOptions::default()).unwrap())
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn pyramid_refines_coarsens_and_follows_edits() {
    let mesh = grid(5, 5, true);
    let mut p = LoopPyramid::new(&mesh, LoopOptions::default()).unwrap();
    p.refine().unwrap();
    p.refine().unwrap();
    assert_eq!(p.num_levels(), 3);
    assert!(p.coarsen());
    p.refine().unwrap();
    let direct = loop_subdivide(&mesh, 2, &LoopOptions::default()).unwrap();
    assert_eq!(p.finest().to_mesh(), direct);
    let mut moved = mesh.positions.clone();
    moved[7] += DVec3::new(0.1, -0.2, 0.3);
    p.set_base_positions(moved.clone()).unwrap();
    let edited = PolyMesh { positions: moved, ..mesh.clone() };
    assert_eq!(p.finest().to_mesh(), loop_subdivide(&edited, 2, &LoopOptions::default()).unwrap());
    assert!(p.set_base_positions(vec![DVec3::ZERO]).is_err());
    while p.coarsen() {}
    assert_eq!(p.num_levels(), 1);
}

#[test]
fn uv_seams_never_blend() {
    // The torus grid with UVs from the unwrapped grid: the seams at u = 0 ≡ 1 and
    // v = 0 ≡ 1 carry two UVs per vertex.
    let (n, m) = (6u32, 4u32);
    let mut mesh = grid(n, m, true);
    let uv_id = |i: u32, j: u32| j * (n + 1) + i;
    let mut values = Vec::new();
    for j in 0..=m {
        for i in 0..=n {
            values.push(DVec2::new(f64::from(i) / f64::from(n), f64::from(j) / f64::from(m)));
        }
    }
    let mut indices = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b, c, d) = (uv_id(i, j), uv_id(i + 1, j), uv_id(i + 1, j + 1), uv_id(i, j + 1));
            indices.extend([a, b, c, a, c, d]);
        }
    }
    // The unwrapped UV grid as a mesh of its own (an open grid: the seams are its boundary).
    let flat = PolyMesh::from_triangles(
        values.iter().map(|p| p.extend(0.0)).collect(),
        &indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect::<Vec<_>>(),
    );
    mesh.uvs = Some(FaceVarying { values, indices });
    let fine = loop_subdivide(&mesh, 2, &LoopOptions::default()).unwrap();
    let flat_fine = loop_subdivide(&flat, 2, &LoopOptions::default()).unwrap();
    let uvs = fine.uvs.clone().unwrap();
    assert_eq!(uvs.indices.len(), 3 * fine.num_faces());
    // Corner by corner, the UV channel is Loop of the unwrapped grid: nothing blends across
    // a seam, and the two sides of a seam keep their own values.
    for (c, &i) in uvs.indices.iter().enumerate() {
        let expected = flat_fine.positions[flat_fine.face_vertices[c] as usize];
        assert_eq!(uvs.values[i as usize], expected.truncate(), "corner {c}");
    }
    // The positions themselves see no seam (the torus is closed).
    assert!(fine.to_tri_mesh().is_closed_oriented());
}

#[test]
fn bad_input_is_an_error() {
    let mut quad = PolyMesh::from_triangles(vec![DVec3::ZERO; 4], &[]);
    quad.face_vertices = vec![0, 1, 2, 3];
    quad.face_offsets = vec![0, 4];
    let e = loop_subdivide(&quad, 1, &LoopOptions::default()).unwrap_err();
    assert_eq!(e.to_string(), "face 0 has 4 corners; Loop subdivision needs triangles (triangulate the mesh first)");
}

/// Issue #39: a bowtie vertex and an edge of three faces are subdivided with OpenSubdiv's
/// rules (the vertex a corner, the edge infinitely sharp), no longer refused.
#[test]
fn non_manifold_input_is_subdivided_with_sharp_edges_and_corners() {
    let p: Vec<DVec3> = (0..5).map(|i| DVec3::new(f64::from(i), f64::from(i * i % 3), f64::from(i % 2))).collect();
    let bowtie = PolyMesh::from_triangles(p.clone(), &[[0, 1, 2], [0, 3, 4]]);
    let fine = loop_subdivide(&bowtie, 1, &LoopOptions::default()).unwrap();
    assert_eq!((fine.num_vertices(), fine.num_faces(), fine.positions[0]), (11, 8, p[0]));
    let fin = PolyMesh::from_triangles(p.clone(), &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    let fine = loop_subdivide(&fin, 1, &LoopOptions::default()).unwrap();
    // edge 0–1 is the first edge: its odd vertex is its midpoint, and its ends stay
    assert_eq!(&fine.positions[..2], &p[..2]);
    assert_eq!(fine.positions[5], (p[0] + p[1]) * 0.5);
}

#[test]
fn colour_by_level_marks_where_vertices_were_born() {
    use splinekit::subdiv::LEVEL_COLORS;
    let mesh = icosahedron();
    let o = LoopOptions { color_by_level: true, ..LoopOptions::default() };
    let fine = LoopPyramid::new(&mesh, o).unwrap().into_refined(2, |_| {}).unwrap();
    assert_eq!(fine.depth(), 2);
    // 12 base vertices, 30 born at level 1, 120 at level 2.
    assert!(fine.colors[..12].iter().all(|&c| c == LEVEL_COLORS[0]));
    assert!(fine.colors[12..42].iter().all(|&c| c == LEVEL_COLORS[1]));
    assert!(fine.colors[42..].iter().all(|&c| c == LEVEL_COLORS[2]));
    assert_eq!(fine.colors.len(), 162);
    // The one-shot path and the pyramid agree.
    let mut p = LoopPyramid::new(&mesh, o).unwrap();
    p.refine_to(2, |_| {}).unwrap();
    assert_eq!(p.finest().to_mesh(), fine.to_mesh());
    let tri = fine.into_tri_mesh();
    assert_eq!(tri.colors.len(), tri.positions.len());
}

/// The one-shot path (`into_refined`, which makes each level from the tables two levels up
/// and stores tables only every other level) equals the pyramid, level by level, to the bit:
/// positions, colours and triangles, closed and open, every weight and boundary rule.
#[test]
fn one_shot_equals_the_pyramid_to_the_bit() {
    let mut meshes = vec![icosahedron(), grid(6, 5, true), grid(5, 4, false)];
    // Corners: a single-face corner vertex at each end of a strip.
    meshes.push(PolyMesh::from_triangles(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(0.2, 1.0, 0.1), DVec3::new(1.3, 0.9, -0.2), DVec3::new(2.0, 0.1, 0.3)],
        &[[0, 1, 2], [1, 3, 2], [1, 4, 3]],
    ));
    for mut mesh in meshes {
        mesh.colors = mesh.positions.iter().map(|p| DVec3::new(p.x.sin(), p.y.cos(), p.z * p.x)).collect();
        for weights in [LoopWeights::Loop, LoopWeights::Warren] {
            for boundary in [BoundaryRule::Smooth, BoundaryRule::Corners] {
                for color_by_level in [false, true] {
                    let o = LoopOptions { weights, boundary, color_by_level };
                    let mut pyramid = LoopPyramid::new(&mesh, o).unwrap();
                    pyramid.refine_to(5, |_| {}).unwrap();
                    for levels in 0..=5 {
                        let mut seen = Vec::new();
                        let fine = LoopPyramid::new(&mesh, o).unwrap().into_refined(levels, |k| seen.push(k)).unwrap();
                        assert_eq!(seen, (1..=levels).collect::<Vec<_>>());
                        let want = pyramid.level(levels);
                        assert_eq!(fine.depth(), levels);
                        assert_eq!(fine.triangles, want.triangles, "{o:?}, {levels} levels");
                        assert_eq!(fine.positions, want.positions, "{o:?}, {levels} levels");
                        assert_eq!(fine.colors, want.colors, "{o:?}, {levels} levels");
                    }
                }
            }
        }
    }
    // From a pyramid that already has levels, into_refined goes on from its finest.
    let mesh = grid(5, 4, false);
    let mut p = LoopPyramid::new(&mesh, LoopOptions::default()).unwrap();
    p.refine().unwrap();
    let fine = p.clone().into_refined(3, |_| {}).unwrap();
    p.refine_to(4, |_| {}).unwrap();
    assert_eq!((fine.depth(), &fine.positions, &fine.triangles), (4, &p.finest().positions, &p.finest().triangles));
}
