//! Subdivision matrices: `S · P` equals the subdivided positions (Loop with both weights and
//! both boundary rules, Catmull-Clark with both boundary rules, 0–3 levels, closed and open
//! meshes); edited base positions re-applied equal a fresh subdivision; rows are affine and
//! nonnegative; colours go through the same matrix; wrong lengths and bad meshes are errors.

use glam::DVec3;
use splinekit::PolyMesh;
use splinekit::subdiv::{
    BoundaryRule, CatmullClarkOptions, LoopOptions, LoopWeights, SubdivError, SubdivisionMatrix,
    catmull_clark_subdivide, loop_subdivide,
};

mod common;
use common::poly;

/// A deterministic pseudo-random offset in [−0.1, 0.1]³ (so no symmetry hides a wrong weight).
fn jitter(k: u32) -> DVec3 {
    let h = |s: u32| {
        let x = u64::from(k)
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .wrapping_add(u64::from(s).wrapping_mul(0xBF58_476D_1CE4_E5B9));
        ((x >> 40) as f64 / (1u64 << 24) as f64 - 0.5) * 0.2
    };
    DVec3::new(h(1), h(2), h(3))
}

/// The icosahedron, jittered.
fn icosahedron() -> PolyMesh {
    let mut mesh = common::icosahedron();
    for (k, p) in mesh.positions.iter_mut().enumerate() {
        *p += jitter(k as u32);
    }
    mesh
}

/// An open `n × n` grid; `triangles` splits each quad in two.
fn grid(n: u32, triangles: bool) -> PolyMesh {
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            p.push(DVec3::new(f64::from(i), f64::from(j), 0.0) + jitter(id(i, j)));
        }
    }
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if triangles {
                faces.push(vec![a, b, c]);
                faces.push(vec![a, c, d]);
            } else {
                faces.push(vec![a, b, c, d]);
            }
        }
    }
    let faces: Vec<&[u32]> = faces.iter().map(Vec::as_slice).collect();
    poly(p, &faces)
}

/// The prism of triangles, quads and pentagons, jittered.
fn prism() -> PolyMesh {
    let mut mesh = common::prism();
    for (k, p) in mesh.positions.iter_mut().enumerate() {
        *p += jitter(k as u32);
    }
    mesh
}

fn max_diff(a: &[DVec3], b: &[DVec3]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0, f64::max)
}

/// Rows: weights sum to 1 and are nonnegative; columns ascending and distinct.
fn check_rows(s: &SubdivisionMatrix) {
    for i in 0..s.num_rows() {
        let row = s.row(i);
        let sum: f64 = row.iter().map(|e| e.1).sum();
        assert!((sum - 1.0).abs() < 1e-13, "row {i} sums to {sum}");
        assert!(row.iter().all(|e| e.1 >= 0.0), "row {i} has a negative weight: {row:?}");
        assert!(row.windows(2).all(|w| w[0].0 < w[1].0), "row {i}: columns not ascending");
    }
}

#[test]
fn loop_matrix_reproduces_loop_subdivision() {
    let meshes = [("icosahedron", icosahedron()), ("open grid", grid(4, true))];
    for (name, mesh) in &meshes {
        for weights in [LoopWeights::Loop, LoopWeights::Warren] {
            for boundary in [BoundaryRule::Smooth, BoundaryRule::Corners] {
                let options = LoopOptions { weights, boundary, ..LoopOptions::default() };
                for levels in 0..=3 {
                    let s = SubdivisionMatrix::loop_scheme(mesh, levels, &options).unwrap();
                    let direct = loop_subdivide(mesh, levels, &options).unwrap();
                    assert_eq!((s.num_rows(), s.num_cols()), (direct.num_vertices(), mesh.num_vertices()));
                    let via = s.apply(&mesh.positions).unwrap();
                    let d = max_diff(&via, &direct.positions);
                    assert!(d < 1e-12, "{name} {weights:?} {boundary:?} level {levels}: {d:e}");
                    check_rows(&s);
                }
            }
        }
    }
}

#[test]
fn catmull_clark_matrix_reproduces_catmull_clark_subdivision() {
    let meshes = [("prism", prism()), ("open quad grid", grid(3, false)), ("triangle grid", grid(2, true))];
    for (name, mesh) in &meshes {
        for boundary in [BoundaryRule::Smooth, BoundaryRule::Corners] {
            let options = CatmullClarkOptions { boundary, ..CatmullClarkOptions::default() };
            for levels in 0..=3 {
                let s = SubdivisionMatrix::catmull_clark(mesh, levels, &options).unwrap();
                let direct = catmull_clark_subdivide(mesh, levels, &options).unwrap();
                assert_eq!((s.num_rows(), s.num_cols()), (direct.num_vertices(), mesh.num_vertices()));
                let d = max_diff(&s.apply(&mesh.positions).unwrap(), &direct.positions);
                assert!(d < 1e-12, "{name} {boundary:?} level {levels}: {d:e}");
                check_rows(&s);
            }
        }
    }
}

#[test]
fn edited_base_positions_reapply_without_topology() {
    let mut tri = icosahedron();
    let mut quads = prism();
    let s_loop = SubdivisionMatrix::loop_scheme(&tri, 3, &LoopOptions::default()).unwrap();
    let s_cc = SubdivisionMatrix::catmull_clark(&quads, 3, &CatmullClarkOptions::default()).unwrap();
    for k in 0..5u32 {
        let v = (7 * k as usize) % tri.num_vertices();
        tri.positions[v] += DVec3::new(0.3, -0.2, 0.5) * f64::from(k + 1);
        let w = (3 * k as usize) % quads.num_vertices();
        quads.positions[w] -= DVec3::new(0.1, 0.4, -0.2) * f64::from(k + 1);
        let fresh = loop_subdivide(&tri, 3, &LoopOptions::default()).unwrap();
        assert!(max_diff(&s_loop.apply(&tri.positions).unwrap(), &fresh.positions) < 1e-12);
        let fresh = catmull_clark_subdivide(&quads, 3, &CatmullClarkOptions::default()).unwrap();
        assert!(max_diff(&s_cc.apply(&quads.positions).unwrap(), &fresh.positions) < 1e-12);
    }
}

#[test]
fn colours_go_through_the_same_matrix() {
    let mut mesh = icosahedron();
    mesh.colors = (0..mesh.num_vertices() as u32).map(|k| jitter(k) * 5.0 + DVec3::splat(0.5)).collect();
    let s = SubdivisionMatrix::loop_scheme(&mesh, 2, &LoopOptions::default()).unwrap();
    let direct = loop_subdivide(&mesh, 2, &LoopOptions::default()).unwrap();
    assert!(max_diff(&s.apply(&mesh.colors).unwrap(), &direct.colors) < 1e-12);
}

#[test]
fn stencils_stay_local() {
    // One Loop level: an even vertex of valence n has n + 1 weights, an odd one 4 (2 on the
    // boundary). Three levels of a 642-vertex icosphere reach a few rings around each vertex,
    // not the whole mesh.
    let mesh = icosahedron();
    let one = SubdivisionMatrix::loop_scheme(&mesh, 1, &LoopOptions::default()).unwrap();
    for v in 0..12 {
        assert_eq!(one.row(v).len(), 6, "even vertex {v} (valence 5)");
    }
    for e in 12..one.num_rows() {
        assert_eq!(one.row(e).len(), 4, "odd vertex {e}");
    }
    let fine = loop_subdivide(&mesh, 3, &LoopOptions::default()).unwrap();
    let big = SubdivisionMatrix::loop_scheme(&fine, 3, &LoopOptions::default()).unwrap();
    let widest = (0..big.num_rows()).map(|i| big.row(i).len()).max().unwrap();
    assert!(widest < 60, "a row of {widest} weights");
    assert_eq!(SubdivisionMatrix::identity(3).row(2), &[(2, 1.0)]);
}

#[test]
fn errors() {
    let mesh = icosahedron();
    let s = SubdivisionMatrix::loop_scheme(&mesh, 1, &LoopOptions::default()).unwrap();
    let err = s.apply(&mesh.positions[..11]).unwrap_err();
    assert!(err.to_string().contains("11 values for a matrix of 12 columns"), "{err}");
    let quads = grid(2, false);
    let err = SubdivisionMatrix::loop_scheme(&quads, 1, &LoopOptions::default()).unwrap_err();
    assert!(matches!(err, SubdivError::NotTriangles { face: 0, corners: 4, .. }), "{err}");
}

/// Issue #39: three faces on one edge are taken with OpenSubdiv's rules; the matrix gives the
/// subdivision's vertices.
#[test]
fn non_manifold_matrices_give_the_subdivision() {
    let fin = poly(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE], &[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4]]);
    // (the product of the level matrices rounds differently from level by level)
    let same =
        |a: Vec<DVec3>, b: Vec<DVec3>| a.len() == b.len() && a.iter().zip(&b).all(|(p, q)| p.distance(*q) < 1e-14);
    for levels in 1..=2 {
        let s = SubdivisionMatrix::loop_scheme(&fin, levels, &LoopOptions::default()).unwrap();
        let direct = loop_subdivide(&fin, levels, &LoopOptions::default()).unwrap();
        assert!(same(s.apply(&fin.positions).unwrap(), direct.positions), "Loop, {levels} levels");
        let s = SubdivisionMatrix::catmull_clark(&fin, levels as usize, &CatmullClarkOptions::default()).unwrap();
        let direct = catmull_clark_subdivide(&fin, levels as usize, &CatmullClarkOptions::default()).unwrap();
        assert!(same(s.apply(&fin.positions).unwrap(), direct.positions), "Catmull-Clark, {levels} levels");
    }
}
