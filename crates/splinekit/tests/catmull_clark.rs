//! Catmull-Clark subdivision: closed forms on the cube, counts and topology, a second naive
//! implementation (hash maps, the textbook `(F + 2R + (n − 3)P)/n` form), affine invariance,
//! boundary and corner rules, colours, and errors.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;
use splinekit::PolyMesh;
use splinekit::mesh::Adjacency;
use splinekit::subdiv::{BoundaryRule, CatmullClarkOptions, SubdivError, catmull_clark_subdivide};

mod common;
use common::{cube, poly, prism};

/// An open `n × n` grid of quads over `[0, 1]²`, bumped in z.
fn grid(n: u32) -> PolyMesh {
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            p.push(DVec3::new(x, y, 0.2 * (2.0 * x + 1.0).sin() * (3.0 * y).cos()));
        }
    }
    let faces: Vec<[u32; 4]> =
        (0..n).flat_map(|j| (0..n).map(move |i| [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])).collect();
    let refs: Vec<&[u32]> = faces.iter().map(|f| &f[..]).collect();
    poly(p, &refs)
}

/// One level of Catmull-Clark, written independently: hash maps from undirected edges to
/// faces, vertex points as `(F + 2R + (n − 3)·P)/n` (R: the average of the edge midpoints),
/// and the same vertex numbering as the library (vertices, edges in order of first use by
/// the corners, faces).
fn naive(mesh: &PolyMesh, corners_fixed: bool) -> PolyMesh {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut edge_faces: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    let mut edge_index: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for (f, face) in mesh.faces().enumerate() {
        for k in 0..face.len() {
            let e = key(face[k], face[(k + 1) % face.len()]);
            edge_faces.entry(e).or_default().push(f);
            edge_index.entry(e).or_insert_with(|| {
                edges.push(e);
                edges.len() - 1
            });
        }
    }
    let p = &mesh.positions;
    let centre: Vec<DVec3> =
        mesh.faces().map(|f| f.iter().map(|&v| p[v as usize]).sum::<DVec3>() / f.len() as f64).collect();
    let edge_point: Vec<DVec3> = edges
        .iter()
        .map(|&(a, b)| {
            let fs = &edge_faces[&(a, b)];
            if fs.len() == 1 {
                (p[a as usize] + p[b as usize]) / 2.0
            } else {
                (p[a as usize] + p[b as usize] + centre[fs[0]] + centre[fs[1]]) / 4.0
            }
        })
        .collect();
    let mut vertex_faces: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); p.len()];
    let mut vertex_edges: Vec<BTreeSet<(u32, u32)>> = vec![BTreeSet::new(); p.len()];
    for (f, face) in mesh.faces().enumerate() {
        for k in 0..face.len() {
            vertex_faces[face[k] as usize].insert(f);
            let e = key(face[k], face[(k + 1) % face.len()]);
            vertex_edges[e.0 as usize].insert(e);
            vertex_edges[e.1 as usize].insert(e);
        }
    }
    let mut positions = Vec::new();
    for v in 0..p.len() {
        let boundary: Vec<(u32, u32)> = vertex_edges[v].iter().copied().filter(|e| edge_faces[e].len() == 1).collect();
        let pv = p[v];
        positions.push(if vertex_faces[v].is_empty() {
            pv
        } else if !boundary.is_empty() {
            if corners_fixed && vertex_faces[v].len() == 1 {
                pv
            } else {
                let other = |e: (u32, u32)| p[(if e.0 as usize == v { e.1 } else { e.0 }) as usize];
                0.75 * pv + 0.125 * (other(boundary[0]) + other(boundary[1]))
            }
        } else {
            let n = vertex_faces[v].len() as f64;
            let f = vertex_faces[v].iter().map(|&f| centre[f]).sum::<DVec3>() / n;
            let r = vertex_edges[v].iter().map(|&(a, b)| (p[a as usize] + p[b as usize]) / 2.0).sum::<DVec3>() / n;
            (f + 2.0 * r + (n - 3.0) * pv) / n
        });
    }
    positions.extend_from_slice(&edge_point);
    positions.extend_from_slice(&centre);
    let (nv, ne) = (p.len() as u32, edges.len() as u32);
    let mut quads: Vec<[u32; 4]> = Vec::new();
    for (f, face) in mesh.faces().enumerate() {
        let m = face.len();
        for k in 0..m {
            let (prev, v, next) = (face[(k + m - 1) % m], face[k], face[(k + 1) % m]);
            quads.push([
                v,
                nv + edge_index[&key(v, next)] as u32,
                nv + ne + f as u32,
                nv + edge_index[&key(prev, v)] as u32,
            ]);
        }
    }
    let refs: Vec<&[u32]> = quads.iter().map(|q| &q[..]).collect();
    poly(positions, &refs)
}

fn assert_close(a: &PolyMesh, b: &PolyMesh, tol: f64, what: &str) {
    assert_eq!(a.face_offsets, b.face_offsets, "{what}: faces");
    assert_eq!(a.face_vertices, b.face_vertices, "{what}: face corners");
    assert_eq!(a.positions.len(), b.positions.len(), "{what}: vertices");
    for (i, (p, q)) in a.positions.iter().zip(&b.positions).enumerate() {
        assert!((*p - *q).length() <= tol, "{what}: vertex {i}: {p} vs {q}");
    }
}

fn euler(mesh: &PolyMesh) -> i64 {
    let adj = Adjacency::build(mesh);
    mesh.num_vertices() as i64 - adj.num_edges() as i64 + mesh.num_faces() as i64
}

#[test]
fn the_cube_by_hand() {
    let fine = catmull_clark_subdivide(&cube(), 1, &CatmullClarkOptions::default()).unwrap();
    assert_eq!((fine.num_vertices(), fine.num_faces()), (8 + 12 + 6, 24));
    // a corner (valence 3): F = (1/3, 1/3, 1/3)·s, R = (2/3, 2/3, 2/3)·s → (F + 2R)/3 = 5/9·s
    for (v, p) in cube().positions.iter().enumerate() {
        assert!((fine.positions[v] - *p * (5.0 / 9.0)).length() < 1e-15, "corner {v}");
    }
    // an edge between corners p and q: (p + q + two face centres)/4 = 3/4 of the midpoint
    let adj = Adjacency::build(&cube());
    for e in 0..12 {
        let c = adj.edge_corner[e] as usize;
        let (p, q) = (cube().positions[cube().face_vertices[c] as usize], cube().positions[adj.to[c] as usize]);
        assert!((fine.positions[8 + e] - 0.375 * (p + q)).length() < 1e-15, "edge {e}");
    }
    // face points: the face centres (±1 on one axis)
    for f in 0..6 {
        let p = fine.positions[20 + f];
        assert!((p.abs().max_element() - 1.0).abs() < 1e-15 && (p.length() - 1.0).abs() < 1e-15, "face {f}: {p}");
    }
}

#[test]
fn agrees_with_the_naive_implementation() {
    let meshes = [("cube", cube()), ("prism", prism()), ("grid", grid(4))];
    for (name, mesh) in meshes {
        for corners in [false, true] {
            let options = CatmullClarkOptions {
                boundary: if corners { BoundaryRule::Corners } else { BoundaryRule::Smooth },
                ..CatmullClarkOptions::default()
            };
            let mut reference = mesh.clone();
            for level in 1..=3 {
                reference = naive(&reference, corners);
                let ours = catmull_clark_subdivide(&mesh, level, &options).unwrap();
                assert_close(&ours, &reference, 1e-13, &format!("{name}, level {level}, corners {corners}"));
            }
        }
    }
}

#[test]
fn counts_topology_and_orientation() {
    for (name, mesh, boundary) in [("cube", cube(), false), ("prism", prism(), false), ("grid", grid(5), true)] {
        let chi = euler(&mesh);
        let mut level = mesh.clone();
        for _ in 0..3 {
            let adj = Adjacency::build(&level);
            let (v, e, f, corners) =
                (level.num_vertices(), adj.num_edges(), level.num_faces(), level.face_vertices.len());
            let fine = catmull_clark_subdivide(&level, 1, &CatmullClarkOptions::default()).unwrap();
            let fine_adj = Adjacency::build(&fine);
            assert_eq!(fine.num_vertices(), v + e + f, "{name}: V + E + F");
            assert_eq!(fine.num_faces(), corners, "{name}: one quad per corner");
            assert!(fine.faces().all(|q| q.len() == 4), "{name}: all quads");
            assert_eq!(fine_adj.num_edges(), 2 * e + corners, "{name}: 2E + corners");
            assert!(fine_adj.nonmanifold.is_empty(), "{name}: consistently oriented and manifold");
            assert_eq!(fine_adj.num_boundary_edges(), 2 * adj.num_boundary_edges(), "{name}: boundary");
            assert_eq!(euler(&fine), chi, "{name}: Euler characteristic");
            assert_eq!(fine_adj.num_boundary_edges() > 0, boundary);
            level = fine;
        }
    }
}

#[test]
fn affine_maps_commute_with_subdivision_and_flat_stays_flat() {
    let mesh = prism();
    let map =
        |p: DVec3| DVec3::new(2.0 * p.x - 0.5 * p.y + 3.0, 0.3 * p.x + 1.5 * p.y - p.z, 0.7 * p.z + 0.2 * p.x - 4.0);
    let mut moved = mesh.clone();
    moved.positions = mesh.positions.iter().map(|&p| map(p)).collect();
    let a = catmull_clark_subdivide(&mesh, 2, &CatmullClarkOptions::default()).unwrap();
    let b = catmull_clark_subdivide(&moved, 2, &CatmullClarkOptions::default()).unwrap();
    for (p, q) in a.positions.iter().zip(&b.positions) {
        assert!((map(*p) - *q).length() < 1e-12, "{p} → {q}");
    }
    let mut flat = grid(4);
    for p in &mut flat.positions {
        p.z = 0.25 * p.x - 0.5 * p.y + 1.0;
    }
    let fine = catmull_clark_subdivide(&flat, 3, &CatmullClarkOptions::default()).unwrap();
    for p in &fine.positions {
        assert!((p.z - (0.25 * p.x - 0.5 * p.y + 1.0)).abs() < 1e-14, "{p} left the plane");
    }
}

#[test]
fn corners_stay_fixed_only_when_asked() {
    let mesh = grid(3);
    let corner = 0; // (0, 0): one face
    let smooth = catmull_clark_subdivide(&mesh, 2, &CatmullClarkOptions::default()).unwrap();
    let fixed = catmull_clark_subdivide(
        &mesh,
        2,
        &CatmullClarkOptions { boundary: BoundaryRule::Corners, ..Default::default() },
    )
    .unwrap();
    assert_eq!(fixed.positions[corner], mesh.positions[corner]);
    assert!((smooth.positions[corner] - mesh.positions[corner]).length() > 1e-3);
    // boundary curves are the cubic B-spline of the boundary polygon: the straight edge
    // y = 0, z = 0.2·sin(2x + 1) stays in the plane y = 0
    for (p, q) in smooth.positions.iter().zip(&fixed.positions) {
        if p.y.abs() < 1e-15 {
            assert!(q.y.abs() < 1e-15);
        }
    }
}

#[test]
fn colours_follow_the_weights_or_mark_the_levels() {
    let mut mesh = cube();
    mesh.colors = mesh.positions.iter().map(|p| (*p + DVec3::ONE) * 0.5).collect();
    let fine = catmull_clark_subdivide(&mesh, 2, &CatmullClarkOptions::default()).unwrap();
    // the colours are an affine image of the positions, so they subdivide the same way
    for (p, c) in fine.positions.iter().zip(&fine.colors) {
        assert!(((*p + DVec3::ONE) * 0.5 - *c).length() < 1e-14);
    }
    let options = CatmullClarkOptions { color_by_level: true, ..CatmullClarkOptions::default() };
    let marked = catmull_clark_subdivide(&mesh, 2, &options).unwrap();
    let lc = splinekit::subdiv::LEVEL_COLORS;
    assert_eq!(marked.colors.len(), marked.num_vertices());
    assert!(marked.colors[..8].iter().all(|&c| c == lc[0]));
    assert!(marked.colors[8..26].iter().all(|&c| c == lc[1]));
    assert!(marked.colors[26..].iter().all(|&c| c == lc[2]));
}

/// Issue #39: non-manifold input follows OpenSubdiv's rules (its edges infinitely sharp, its
/// vertices corners) instead of being refused; `tests/nonmanifold.rs` compares many more cases
/// with OpenSubdiv itself.
#[test]
fn non_manifold_input_is_subdivided_with_sharp_edges_and_corners() {
    // three quads on the edge 0–1: its edge point is its midpoint, its ends stay
    let p: Vec<DVec3> = (0..8).map(|i| DVec3::new(f64::from(i), f64::from(i * i % 5), 0.0)).collect();
    let mesh = poly(p.clone(), &[&[0, 1, 2, 3], &[1, 0, 4, 5], &[0, 1, 6, 7]]);
    let fine = catmull_clark_subdivide(&mesh, 1, &CatmullClarkOptions::default()).unwrap();
    assert_eq!(fine.num_faces(), 12);
    assert_eq!(&fine.positions[..2], &p[..2]);
    assert!(fine.positions.contains(&((p[0] + p[1]) * 0.5)));
    // two squares touching at vertex 0 only: it stays
    let p: Vec<DVec3> = (0..7).map(|i| DVec3::new(f64::from(i), 0.0, f64::from(i % 2))).collect();
    let bowtie = poly(p.clone(), &[&[0, 1, 2, 3], &[0, 4, 5, 6]]);
    let fine = catmull_clark_subdivide(&bowtie, 1, &CatmullClarkOptions::default()).unwrap();
    assert_eq!(fine.positions[0], p[0]);
    // zero levels: the mesh itself
    let same = catmull_clark_subdivide(&cube(), 0, &CatmullClarkOptions::default()).unwrap();
    assert_eq!(same.positions, cube().positions);
}

#[test]
fn limit_positions_need_quads_and_are_fixed_points_of_subdivision() {
    use splinekit::subdiv::catmull_clark_limit_positions;
    let options = CatmullClarkOptions::default();
    match catmull_clark_limit_positions(&prism(), &options) {
        Err(SubdivError::NotQuads { corners, .. }) => assert_ne!(corners, 4),
        other => panic!("expected NotQuads, got {other:?}"),
    }
    // the limit of a vertex does not depend on the level it is computed at
    let one = catmull_clark_subdivide(&prism(), 1, &options).unwrap();
    let two = catmull_clark_subdivide(&prism(), 2, &options).unwrap();
    let (l1, l2) = (
        catmull_clark_limit_positions(&one, &options).unwrap(),
        catmull_clark_limit_positions(&two, &options).unwrap(),
    );
    for v in 0..one.num_vertices() {
        assert!((l1[v] - l2[v]).length() < 1e-14, "vertex {v}: {} vs {}", l1[v], l2[v]);
    }
}

#[test]
fn level_by_level_equals_one_call() {
    use splinekit::subdiv::catmull_clark_step;
    for color_by_level in [false, true] {
        let options = CatmullClarkOptions { color_by_level, ..CatmullClarkOptions::default() };
        let mut level = prism();
        for depth in 1..=3 {
            level = catmull_clark_step(&level, depth, &options).unwrap();
            let once = catmull_clark_subdivide(&prism(), depth, &options).unwrap();
            assert_eq!(level, once, "depth {depth}, colour by level {color_by_level}");
        }
    }
}

/// Scattered positions, so that every rounding shows.
fn jitter(k: u32) -> DVec3 {
    let f = |a: u32| f64::from((k.wrapping_mul(a).wrapping_add(12345)) % 1000) / 997.0;
    DVec3::new(f(7919), f(104_729), f(1_299_709))
}

/// A torus of `n × m` quads, or with `open` its first `m − 1` rows (a band with two
/// boundary loops) plus an isolated vertex.
fn torus(n: u32, m: u32, open: bool) -> PolyMesh {
    let id = |i: u32, j: u32| (j % m) * n + (i % n);
    let rows = if open { m - 1 } else { m };
    let quads: Vec<[u32; 4]> =
        (0..rows).flat_map(|j| (0..n).map(move |i| [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])).collect();
    let faces: Vec<&[u32]> = quads.iter().map(|q| &q[..]).collect();
    let extra = u32::from(open);
    poly((0..n * m + extra).map(jitter).collect(), &faces)
}

/// A cone of `n` triangles over an `n`-gon (apex of valence `n`), and an open fan of
/// pentagons and triangles around a boundary vertex.
fn cone_and_fan(n: u32) -> PolyMesh {
    let apex = n;
    let tris: Vec<[u32; 3]> = (0..n).map(|i| [i, (i + 1) % n, apex]).collect();
    let base: Vec<u32> = (0..n).rev().collect();
    let mut faces: Vec<&[u32]> = tris.iter().map(|t| &t[..]).collect();
    faces.push(&base);
    let c = n + 1;
    let fan: [&[u32]; 3] = [&[c, c + 1, c + 2, c + 3, c + 4], &[c, c + 4, c + 5], &[c, c + 5, c + 6, c + 7]];
    faces.extend(fan);
    poly((0..c + 8).map(jitter).collect(), &faces)
}

/// Subdividing in one call (levels below the first from closed-form quad tables) gives, to the
/// bit, what level after level gives (the general adjacency rebuilt each time): tori, open
/// bands, an isolated vertex, a valence above eight, n-gons, no faces at all, both boundary
/// rules, colours, on one thread and three.
#[test]
fn closed_form_levels_equal_level_by_level() {
    use splinekit::subdiv::catmull_clark_step;
    let meshes = [
        ("closed torus", torus(7, 5, false)),
        ("open band", torus(6, 4, true)),
        ("cones", cone_and_fan(11)),
        ("large torus", torus(40, 30, false)),
        ("no faces", poly((0..3).map(jitter).collect(), &[])),
    ];
    for (name, mut mesh) in meshes {
        for (colors, color_by_level) in [(false, false), (true, false), (false, true)] {
            mesh.colors = if colors {
                mesh.positions.iter().map(|p| DVec3::new(p.z, p.x, p.y) * 2.0).collect()
            } else {
                Vec::new()
            };
            for boundary in [BoundaryRule::Smooth, BoundaryRule::Corners] {
                let options = CatmullClarkOptions { boundary, color_by_level, ..CatmullClarkOptions::default() };
                let mut level = mesh.clone();
                let deepest = if name == "large torus" { 3 } else { 4 };
                for depth in 1..=deepest {
                    level = catmull_clark_step(&level, depth, &options).unwrap();
                    for threads in [1, 3] {
                        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                        let once = pool.install(|| catmull_clark_subdivide(&mesh, depth, &options)).unwrap();
                        let what = format!("{name}, {options:?}, level {depth}, {threads} threads");
                        if name.ends_with("torus") && depth == 3 {
                            // three levels of a regular mesh: a face at a time, equal to rounding
                            same_to_rounding(&once, &level, &what);
                        } else {
                            assert!(once == level, "{what}");
                        }
                    }
                }
            }
        }
    }
}

/// `a` and `b` are the same mesh but for rounding: the same faces and level colours, positions
/// and carried colours (of size about 1) within a few ulps.
fn same_to_rounding(a: &PolyMesh, b: &PolyMesh, what: &str) {
    assert_eq!(a.face_offsets, b.face_offsets, "{what}");
    assert_eq!(a.face_vertices, b.face_vertices, "{what}");
    let worst = |x: &[DVec3], y: &[DVec3]| {
        assert_eq!(x.len(), y.len(), "{what}");
        x.iter().zip(y).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f64::max)
    };
    let d = worst(&a.positions, &b.positions);
    assert!(d < 1e-15, "{what}: positions differ by {d:e}");
    let d = worst(&a.colors, &b.colors);
    assert!(d < 4e-15, "{what}: colours differ by {d:e}");
}

/// Regular quad meshes (closed, every vertex of valence 4) take three levels a base face at
/// a time from tensor-product weights: the same mesh as level by level, the positions and
/// carried colours equal to rounding, the level colours exactly.
#[test]
fn regular_meshes_in_one_pass_equal_level_by_level() {
    use splinekit::subdiv::catmull_clark_step;
    for (n, m) in [(3, 3), (4, 3), (7, 5), (40, 30)] {
        let mut mesh = torus(n, m, false);
        for (colors, color_by_level) in [(false, false), (true, false), (false, true)] {
            mesh.colors = if colors {
                mesh.positions.iter().map(|p| DVec3::new(p.z, p.x, p.y) * 2.0).collect()
            } else {
                Vec::new()
            };
            let options = CatmullClarkOptions { color_by_level, ..CatmullClarkOptions::default() };
            let mut level = mesh.clone();
            for depth in 1..=3 {
                level = catmull_clark_step(&level, depth, &options).unwrap();
            }
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let once = pool.install(|| catmull_clark_subdivide(&mesh, 3, &options)).unwrap();
                let what = format!("{n} x {m} torus, colours {colors}, by level {color_by_level}, {threads} threads");
                same_to_rounding(&once, &level, &what);
                if color_by_level {
                    assert_eq!(once.colors, level.colors, "{what}");
                }
            }
        }
    }
}
