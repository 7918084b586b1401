//! Creases beyond the OpenSubdiv comparison (in subdivision_reference.rs): an infinitely sharp
//! cube stays a cube; sharpness `k` is `k` sharp levels then smooth ones; a fraction blends
//! the two; creases carry through the subdivision matrix; no creases changes nothing; bad
//! creases are errors naming them.

use glam::DVec3;
use splinekit::PolyMesh;
use splinekit::subdiv::{
    CatmullClarkOptions, Creases, CreasingMethod, EdgeCrease, LoopOptions, SubdivError, SubdivisionMatrix,
    VertexCrease, catmull_clark_subdivide, catmull_clark_subdivide_creased, loop_subdivide, loop_subdivide_creased,
};

mod common;

/// Every edge of `mesh` with sharpness `s`.
fn all_edges(mesh: &PolyMesh, s: f32) -> Creases {
    let mut edges = Vec::new();
    for f in mesh.faces() {
        for (k, &a) in f.iter().enumerate() {
            let b = f[(k + 1) % f.len()];
            if a < b {
                edges.push(EdgeCrease { a, b, sharpness: s });
            }
        }
    }
    Creases { edges, vertices: Vec::new() }
}

fn cc(mesh: &PolyMesh, levels: usize, creases: &Creases, method: CreasingMethod) -> (PolyMesh, Creases) {
    catmull_clark_subdivide_creased(mesh, levels, &CatmullClarkOptions::default(), creases, method).unwrap()
}

fn max_distance(a: &[DVec3], b: &[DVec3]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max)
}

#[test]
fn an_infinitely_sharp_cube_stays_a_cube() {
    let cube = common::cube(); // [-1, 1]^3
    let creases = all_edges(&cube, 10.0);
    let (fine, child) = cc(&cube, 3, &creases, CreasingMethod::Chaikin);
    // every vertex on the cube's surface, the corners where they were, edges straight
    for p in &fine.positions {
        assert!((p.abs().max_element() - 1.0).abs() < 1e-14, "{p} is off the cube");
    }
    assert_eq!(&fine.positions[..8], &cube.positions[..]);
    // the sharp edges are carried: 12 edges split three times, all still infinitely sharp
    assert_eq!(child.edges.len(), 12 * 8);
    assert!(child.edges.iter().all(|e| e.sharpness == 10.0));
    for e in &child.edges {
        let (a, b) = (fine.positions[e.a as usize], fine.positions[e.b as usize]);
        let on_cube_edge = |p: DVec3| p.abs().to_array().iter().filter(|&&x| (x - 1.0).abs() < 1e-14).count() >= 2;
        assert!(on_cube_edge(a) && on_cube_edge(b), "child crease {e:?} leaves the cube's edges");
    }
}

#[test]
fn sharpness_k_is_k_sharp_levels_then_smooth_ones() {
    let cube = common::cube();
    for method in [CreasingMethod::Uniform, CreasingMethod::Chaikin] {
        // sharpness 2 on every edge: two levels as if infinitely sharp, then plain levels
        let (creased, _) = cc(&cube, 4, &all_edges(&cube, 2.0), method);
        let (sharp, _) = cc(&cube, 2, &all_edges(&cube, 10.0), method);
        let smooth = catmull_clark_subdivide(&sharp, 2, &CatmullClarkOptions::default()).unwrap();
        assert!(max_distance(&creased.positions, &smooth.positions) < 1e-14, "{method:?}");
        // sharpness 1.5: one sharp level, then a level blended half way, then smooth
        let (creased, _) = cc(&cube, 2, &all_edges(&cube, 1.5), method);
        let (sharp, _) = cc(&cube, 1, &all_edges(&cube, 10.0), method);
        let (half, _) = cc(&sharp, 1, &all_edges(&sharp, 0.5), method);
        assert!(max_distance(&creased.positions, &half.positions) < 1e-14, "{method:?}");
    }
}

#[test]
fn a_fractional_sharpness_blends_the_sharp_and_smooth_rules() {
    // Uniform sharpness s < 1 on every edge: one level is (1 − s)·smooth + s·sharp per vertex
    // (every vertex's rule and every edge's rule blend with weight s; face points do not move)
    let cube = common::cube();
    let smooth = catmull_clark_subdivide(&cube, 1, &CatmullClarkOptions::default()).unwrap();
    let (sharp, _) = cc(&cube, 1, &all_edges(&cube, 10.0), CreasingMethod::Uniform);
    for s in [0.25f32, 0.5, 0.75] {
        let (blend, child) = cc(&cube, 1, &all_edges(&cube, s), CreasingMethod::Uniform);
        assert!(child.is_empty());
        let w = f64::from(s);
        let expected: Vec<DVec3> =
            smooth.positions.iter().zip(&sharp.positions).map(|(a, b)| *a * (1.0 - w) + *b * w).collect();
        assert!(max_distance(&blend.positions, &expected) < 1e-14, "s = {s}");
    }
}

#[test]
fn creases_go_through_the_subdivision_matrix() {
    let cube = common::cube();
    let mut creases = all_edges(&cube, 1.75);
    creases.edges.truncate(7);
    creases.vertices.push(VertexCrease { vertex: 6, sharpness: 2.5 });
    for method in [CreasingMethod::Uniform, CreasingMethod::Chaikin] {
        let options = CatmullClarkOptions::default();
        let s = SubdivisionMatrix::catmull_clark_creased(&cube, 3, &options, &creases, method).unwrap();
        let (fine, _) = cc(&cube, 3, &creases, method);
        assert!(max_distance(&s.apply(&cube.positions).unwrap(), &fine.positions) < 1e-14);
    }
    let ico = common::icosahedron();
    let mut creases = all_edges(&ico, 2.25);
    creases.edges.truncate(9);
    let options = LoopOptions::default();
    let s = SubdivisionMatrix::loop_creased(&ico, 3, &options, &creases, CreasingMethod::Chaikin).unwrap();
    let (fine, _) = loop_subdivide_creased(&ico, 3, &options, &creases, CreasingMethod::Chaikin).unwrap();
    assert!(max_distance(&s.apply(&ico.positions).unwrap(), &fine.positions) < 1e-14);
}

#[test]
fn no_creases_change_nothing() {
    let none = Creases::default();
    let cube = common::cube();
    let plain = catmull_clark_subdivide(&cube, 3, &CatmullClarkOptions::default()).unwrap();
    let (creased, child) = cc(&cube, 3, &none, CreasingMethod::Chaikin);
    assert!(max_distance(&plain.positions, &creased.positions) < 1e-14);
    assert_eq!(plain.face_vertices, creased.face_vertices);
    assert!(child.is_empty());
    // colours carried by the weights, and by level, as the plain subdivision gives them
    let mut colored = cube.clone();
    colored.colors = cube.positions.iter().map(|p| (*p + DVec3::ONE) * 0.5).collect();
    for color_by_level in [false, true] {
        let options = CatmullClarkOptions { color_by_level, ..CatmullClarkOptions::default() };
        for levels in 0..3 {
            let plain = catmull_clark_subdivide(&colored, levels, &options).unwrap();
            let (creased, _) =
                catmull_clark_subdivide_creased(&colored, levels, &options, &none, CreasingMethod::Chaikin).unwrap();
            assert!(max_distance(&plain.colors, &creased.colors) < 1e-14, "{levels} levels, {color_by_level}");
            assert_eq!((&plain.face_offsets, &plain.face_vertices), (&creased.face_offsets, &creased.face_vertices));
        }
    }
    let ico = common::icosahedron();
    let plain = loop_subdivide(&ico, 3, &LoopOptions::default()).unwrap();
    let (creased, _) =
        loop_subdivide_creased(&ico, 3, &LoopOptions::default(), &none, CreasingMethod::Chaikin).unwrap();
    assert!(max_distance(&plain.positions, &creased.positions) < 1e-14);
}

#[test]
fn bad_creases_are_errors_naming_them() {
    let cube = common::cube();
    let edge = |a, b, sharpness| Creases { edges: vec![EdgeCrease { a, b, sharpness }], vertices: Vec::new() };
    let vertex = |vertex, sharpness| Creases { edges: Vec::new(), vertices: vec![VertexCrease { vertex, sharpness }] };
    let run = |c: &Creases| {
        catmull_clark_subdivide_creased(&cube, 1, &CatmullClarkOptions::default(), c, CreasingMethod::Chaikin)
            .unwrap_err()
            .to_string()
    };
    // 0 and 7 are opposite corners of the cube
    assert_eq!(run(&edge(0, 7, 1.0)), "crease on edge 0–7: no face has this edge");
    assert_eq!(run(&edge(0, 8, 1.0)), "crease on edge 0–8: the mesh has 8 vertices");
    assert_eq!(run(&edge(0, 1, -1.0)), "crease on edge 0–1: sharpness -1 is not a number ≥ 0");
    assert!(run(&edge(0, 1, f32::NAN)).starts_with("crease on edge 0–1: sharpness NaN"));
    assert_eq!(run(&vertex(9, 1.0)), "crease on vertex 9: the mesh has 8 vertices");
    let err = loop_subdivide_creased(
        &common::icosahedron(),
        1,
        &LoopOptions::default(),
        &edge(0, 0, 1.0),
        CreasingMethod::Uniform,
    );
    assert!(matches!(err, Err(SubdivError::Crease { .. })), "{err:?}");
}
