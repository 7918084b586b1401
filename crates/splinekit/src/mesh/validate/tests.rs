//! Tests of the topology report and the repair on small meshes built in code.

use glam::DVec3;

use super::*;
use crate::mesh::{Adjacency, FaceVarying, NONE, NonManifold, PolyMesh};

fn mesh(n: usize, tris: &[[u32; 3]]) -> PolyMesh {
    // Distinct, non-collinear positions so that no face has zero area by accident.
    let positions = (0..n).map(|i| DVec3::new(i as f64, (i * i) as f64, (i * i * i % 7) as f64)).collect();
    PolyMesh::from_triangles(positions, tris)
}

fn report(m: &PolyMesh) -> TopologyReport {
    TopologyReport::new(m, DEFAULT_DEGENERATE_TOLERANCE)
}

const TETRA: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

fn tetra() -> PolyMesh {
    PolyMesh::from_triangles(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z], &TETRA)
}

/// An `n × m` torus of triangles (vertex (i, j) = i·m + j).
fn torus(n: u32, m: u32) -> PolyMesh {
    let mut positions = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (i as f64 / n as f64 * std::f64::consts::TAU, j as f64 / m as f64 * std::f64::consts::TAU);
            let r = 2.0 + 0.5 * v.cos();
            positions.push(DVec3::new(r * u.cos(), r * u.sin(), 0.5 * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..m {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    PolyMesh::from_triangles(positions, &tris)
}

/// An open `n × n`-vertex grid of triangles in the xy-plane, facing +z.
fn grid(n: u32) -> PolyMesh {
    let positions = (0..n * n).map(|k| DVec3::new((k % n) as f64, (k / n) as f64, 0.0)).collect();
    let id = |x: u32, y: u32| y * n + x;
    let mut tris = Vec::new();
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            tris.push([id(x, y), id(x + 1, y), id(x + 1, y + 1)]);
            tris.push([id(x, y), id(x + 1, y + 1), id(x, y + 1)]);
        }
    }
    PolyMesh::from_triangles(positions, &tris)
}

/// A Möbius strip of `n` quads: bottom vertices `0..n`, top `n..2n`; the last quad joins
/// the ends with a half twist.
fn mobius(n: u32) -> PolyMesh {
    let mut m = PolyMesh::default();
    for i in 0..n {
        let a = i as f64 / n as f64 * std::f64::consts::PI;
        let (c, s) = (2.0 * a).sin_cos();
        m.positions.push(DVec3::new(c, s, -0.3 + 0.01 * i as f64));
    }
    for i in 0..n {
        let a = i as f64 / n as f64 * std::f64::consts::PI;
        let (c, s) = (2.0 * a).sin_cos();
        m.positions.push(DVec3::new(1.3 * c, 1.3 * s, 0.3 + 0.01 * i as f64));
    }
    let (b, t) = (|i: u32| i, |i: u32| n + i);
    for i in 0..n - 1 {
        m.face_vertices.extend([b(i), b(i + 1), t(i + 1), t(i)]);
        m.face_offsets.push(m.face_vertices.len() as u32);
    }
    m.face_vertices.extend([b(n - 1), t(0), b(0), t(n - 1)]);
    m.face_offsets.push(m.face_vertices.len() as u32);
    m
}

#[track_caller]
fn assert_clean_manifold(r: &TopologyReport) {
    assert!(r.is_clean(), "expected a clean report:\n{r}");
    assert!(r.components.iter().all(|c| c.manifold && c.orientable && c.consistently_oriented), "{r}");
}

#[test]
fn tetrahedron_is_a_sphere() {
    let r = report(&tetra());
    assert_clean_manifold(&r);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (4, 6, 4));
    assert_eq!((r.euler_characteristic, r.genus()), (2, Some(0)));
    assert!(r.is_closed() && r.boundary_loops.is_empty());
    assert_eq!(r.components.len(), 1);
    assert_eq!(r.face_component, vec![0; 4]);
    assert!(r.to_string().contains("problems: none"), "{r}");
}

#[test]
fn torus_has_genus_one() {
    let r = report(&torus(8, 5));
    assert_clean_manifold(&r);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (40, 120, 80));
    assert_eq!((r.euler_characteristic, r.genus()), (0, Some(1)));
    assert!(r.is_closed());
}

#[test]
fn open_grid_has_one_boundary_loop() {
    let r = report(&grid(5));
    assert_clean_manifold(&r);
    assert_eq!(r.euler_characteristic, 1);
    assert_eq!(r.genus(), Some(0));
    assert_eq!(r.num_boundary_edges, 16);
    assert_eq!(r.boundary_loops.len(), 1);
    let l = &r.boundary_loops[0];
    assert!(l.closed);
    assert_eq!(l.num_edges(), 16);
    // Counter-clockwise seen from +z (faces on the left): 0 → 1 → … along y = 0.
    assert_eq!(&l.vertices[..5], &[0, 1, 2, 3, 4]);
    assert_eq!(&l.vertices[5..8], &[9, 14, 19]);
    assert_eq!(r.components[0].num_boundary_loops, 1);
}

#[test]
fn quads_and_polygons_count() {
    // A cube of quads: V 8, E 12, F 6.
    let mut m = PolyMesh {
        positions: (0..8).map(|k| DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64)).collect(),
        ..PolyMesh::default()
    };
    for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        m.face_vertices.extend(q);
        m.face_offsets.push(m.face_vertices.len() as u32);
    }
    let r = report(&m);
    assert_clean_manifold(&r);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces, r.euler_characteristic), (8, 12, 6, 2));
    assert_eq!(r.genus(), Some(0));
}

#[test]
fn three_faces_on_an_edge() {
    let m = mesh(5, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    let r = report(&m);
    // Its ends are named by the edge, not as pinch vertices.
    assert_eq!(r.nonmanifold, vec![NonManifold::Edge { a: 0, b: 1, faces: vec![0, 1, 2] }]);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (5, 7, 3));
    assert!(!r.is_manifold() && !r.components[0].manifold && r.genus().is_none());
    let text = r.to_string();
    assert!(text.contains("non-manifold edges (1):\n    edge 0–1: faces 0, 1, 2\n"), "{text}");

    let (s, what) = split_nonmanifold(&m);
    let r = report(&s);
    assert_clean_manifold(&r);
    // Faces 0 and 1 stay joined along 0–1 (opposite directions); face 2 is detached.
    assert_eq!(s.face(0), &[0, 1, 2]);
    assert_eq!(s.face(1), &[1, 0, 3]);
    assert_eq!(s.face(2), &[5, 6, 4]);
    assert_eq!(what.split_vertices, vec![0, 1]);
    assert_eq!(what.vertex_origin, vec![0, 1, 2, 3, 4, 0, 1]);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (7, 8, 3));
    assert_eq!((r.components.len(), r.euler_characteristic, r.genus()), (2, 2, Some(0)));
    assert_eq!(r.boundary_loops.len(), 2);
    assert_eq!(s.positions[5], m.positions[0]);
}

#[test]
fn bowtie_vertex() {
    let mut m = mesh(5, &[[0, 1, 2], [0, 3, 4]]);
    m.colors = (0..5).map(|i| DVec3::splat(i as f64 / 4.0)).collect();
    let r = report(&m);
    assert_eq!(r.nonmanifold, vec![NonManifold::Vertex { vertex: 0, fans: 2 }]);
    assert_eq!(r.components.len(), 1);
    // Two triangles sharing a vertex: the boundary is two loops of 3.
    assert_eq!(r.boundary_loops.iter().map(BoundaryLoop::num_edges).collect::<Vec<_>>(), vec![3, 3]);
    assert!(r.to_string().contains("vertex 0: 2 fans"));

    let (s, what) = split_nonmanifold(&m);
    assert_eq!(s.face(1), &[5, 3, 4]);
    assert_eq!(s.colors.len(), 6);
    assert_eq!(s.colors[5], m.colors[0]);
    assert_eq!(what.num_new_vertices(), 1);
    let r = report(&s);
    assert_clean_manifold(&r);
    assert_eq!((r.components.len(), r.euler_characteristic, r.genus()), (2, 2, Some(0)));
}

#[test]
fn two_cones_touching_at_their_tips() {
    // Two closed tetrahedra sharing vertex 0.
    let mut tris = TETRA.to_vec();
    let map = [0, 4, 5, 6];
    tris.extend(TETRA.iter().map(|t| t.map(|v| map[v as usize])));
    let m = mesh(7, &tris);
    let r = report(&m);
    assert_eq!(r.nonmanifold, vec![NonManifold::Vertex { vertex: 0, fans: 2 }]);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces, r.euler_characteristic), (7, 12, 8, 3));
    assert_eq!(r.components.len(), 1);
    assert!(r.is_closed());
    assert_eq!(r.genus(), None);

    let (s, what) = split_nonmanifold(&m);
    assert_eq!(what.split_vertices, vec![0]);
    assert!(what.flipped_faces.is_empty());
    let r = report(&s);
    assert_clean_manifold(&r);
    assert_eq!((r.num_vertices, r.euler_characteristic, r.components.len(), r.genus()), (8, 4, 2, Some(0)));
    assert!(r.components.iter().all(|c| c.euler_characteristic == 2 && c.genus == Some(0)));
}

#[test]
fn mobius_strip_is_not_orientable() {
    let n = 6;
    let m = mobius(n);
    let r = report(&m);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (12, 18, 6));
    assert_eq!(r.euler_characteristic, 0);
    // The twist: bottom 0 and top 6 are joined by quad 0 and quad 5 in the same direction.
    assert_eq!(r.nonmanifold, vec![NonManifold::Inconsistent { a: 6, b: 0, faces: [0, 5] }]);
    assert!(!r.components[0].orientable && r.components[0].manifold);
    assert!(r.misoriented_faces.is_empty());
    assert_eq!(r.genus(), None);
    // One boundary curve, twice as long as the strip.
    assert_eq!(r.boundary_loops.len(), 1);
    assert_eq!(r.boundary_loops[0].num_edges(), 12);
    assert!(r.to_string().contains("non-orientable (1 cross-caps)"), "{r}");

    // Split: cut open along the twist edge into a disk.
    let (s, what) = split_nonmanifold(&m);
    assert_eq!(what.split_vertices, vec![0, 6]);
    let r = report(&s);
    assert_clean_manifold(&r);
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces), (14, 19, 6));
    assert_eq!((r.euler_characteristic, r.genus()), (1, Some(0)));
    assert_eq!(r.boundary_loops.len(), 1);
    assert_eq!(r.boundary_loops[0].num_edges(), 14);
}

#[test]
fn tetrahedron_with_a_flipped_face() {
    let mut m = tetra();
    m.face_vertices[9..12].copy_from_slice(&[1, 3, 2]);
    let r = report(&m);
    assert_eq!(
        r.nonmanifold,
        vec![
            NonManifold::Inconsistent { a: 2, b: 1, faces: [0, 3] },
            NonManifold::Inconsistent { a: 1, b: 3, faces: [1, 3] },
            NonManifold::Inconsistent { a: 3, b: 2, faces: [2, 3] },
        ]
    );
    assert_eq!(r.misoriented_faces, vec![3]);
    assert!(r.is_manifold() && !r.is_consistently_oriented());
    assert!(r.components[0].orientable && !r.components[0].consistently_oriented);
    // Topologically still a sphere: closed, χ 2, genus 0.
    assert!(r.is_closed());
    assert_eq!((r.euler_characteristic, r.genus()), (2, Some(0)));
    let text = r.to_string();
    assert!(text.contains("edge 1→3: faces 1 and 3 both run this way"), "{text}");
    assert!(text.contains("faces to flip for a consistent orientation (1): 3"), "{text}");

    let (s, what) = split_nonmanifold(&m);
    assert_eq!(what.flipped_faces, vec![3]);
    assert!(what.split_vertices.is_empty());
    assert_eq!(s.face(3), &[1, 2, 3]);
    assert_clean_manifold(&report(&s));
}

#[test]
fn flips_carry_face_varying_indices() {
    let mut m = tetra();
    m.face_vertices[9..12].copy_from_slice(&[1, 3, 2]);
    let indices: Vec<u32> = (0..12).collect();
    m.uvs = Some(FaceVarying { values: vec![glam::DVec2::ZERO; 12], indices: indices.clone() });
    m.normals = Some(FaceVarying { values: vec![DVec3::Z; 12], indices });
    let (s, _) = split_nonmanifold(&m);
    assert_eq!(&s.uvs.as_ref().unwrap().indices[9..], &[9, 11, 10]);
    assert_eq!(&s.normals.as_ref().unwrap().indices[9..], &[9, 11, 10]);
}

#[test]
fn degenerate_duplicate_and_broken_faces() {
    let mut m = tetra();
    m.positions.push(DVec3::new(2.0, 0.0, 0.0)); // 4: on the line of 0 and 1
    m.positions.push(DVec3::new(f64::NAN, 0.0, 0.0)); // 5: unreferenced, non-finite
    m.positions.push(DVec3::ONE); // 6: unreferenced
    let mut add = |face: &[u32]| {
        m.face_vertices.extend_from_slice(face);
        m.face_offsets.push(m.face_vertices.len() as u32);
    };
    add(&[0, 1, 4]); // 4: zero area
    add(&[0, 0, 2]); // 5: repeated vertex
    add(&[2, 1, 0]); // 6: same set as face 0
    add(&[1, 2]); // 7: short
    add(&[0, 1, 9]); // 8: index out of range
    add(&[3, 2, 1]); // 9: same set as face 3
    let r = report(&m);
    assert_eq!(
        r.degenerate_faces,
        vec![
            DegenerateFace { face: 4, kind: Degeneracy::ZeroArea },
            DegenerateFace { face: 5, kind: Degeneracy::RepeatedVertex { vertex: 0 } },
        ]
    );
    assert_eq!(r.duplicate_faces, vec![DuplicateFace { face: 6, first: 0 }, DuplicateFace { face: 9, first: 3 }]);
    assert_eq!(r.short_faces, vec![ShortFace { face: 7, len: 2 }]);
    assert_eq!(r.invalid_indices, vec![InvalidIndex { face: 8, vertex: 9 }]);
    assert_eq!(r.unreferenced_vertices, vec![5, 6]);
    assert_eq!(r.nonfinite_vertices, vec![5]);
    // Left out: faces 5, 7, 8.
    assert_eq!(r.num_faces, 7);
    assert_eq!(r.face_component[5], NONE);
    assert_eq!(r.face_component[4], 0);
    // Split removes the face with a bad index (which would otherwise come to name a new
    // vertex), and leaves the other left-out faces as they are.
    let (s, what) = split_nonmanifold(&m);
    assert_eq!(what.removed_faces, vec![8]);
    assert_eq!(s.num_faces(), 9);
    assert_eq!(s.face(7), &[1, 2]);
    assert_eq!(s.face(5), &[0, 0, 2]);
    let r = report(&s);
    assert!(r.is_manifold() && r.is_consistently_oriented() && r.invalid_indices.is_empty(), "{r}");
    let text = report(&m).to_string();
    for needle in [
        "face 4: zero area",
        "face 5: vertex 0 repeated",
        "face 6: same vertices as face 0",
        "face 7: 2 vertices",
        "face 8: vertex 9",
        "unreferenced vertices (2): 5, 6",
        "vertices with a non-finite coordinate (1): 5",
    ] {
        assert!(text.contains(needle), "{needle:?} missing in\n{text}");
    }
}

#[test]
fn zero_area_tolerance_is_a_distance() {
    // A sliver of height 1e-3 over a longest edge of length 2.
    let m = PolyMesh::from_triangles(
        vec![DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(1.0, 1e-3, 0.0)],
        &[[0, 1, 2]],
    );
    assert!(TopologyReport::new(&m, 0.0).degenerate_faces.is_empty());
    assert!(TopologyReport::new(&m, 0.9e-3).degenerate_faces.is_empty());
    assert_eq!(TopologyReport::new(&m, 1.1e-3).degenerate_faces.len(), 1);
    // Coincident corners are degenerate at any tolerance.
    let m = PolyMesh::from_triangles(vec![DVec3::ONE; 3], &[[0, 1, 2]]);
    assert_eq!(TopologyReport::new(&m, 0.0).degenerate_faces.len(), 1);
}

#[test]
fn listing_caps_long_lists() {
    // 30 separate triangles sharing vertex 0: one pinch vertex, 29 unreferenced vertices.
    let mut tris = Vec::new();
    for k in 0..30 {
        tris.push([0, 1 + 2 * k, 2 + 2 * k]);
    }
    let mut m = mesh(61 + 29, &tris);
    m.positions.truncate(61 + 29);
    let r = report(&m);
    assert_eq!(r.unreferenced_vertices.len(), 29);
    let text = r.to_string();
    assert!(
        text.contains("unreferenced vertices (29): 61, 62, 63, 64, 65, 66, 67, 68, 69, 70, … and 19 more"),
        "{text}"
    );
    assert!(r.display_listing(100).to_string().contains(", 89\n"));
}

#[test]
fn reuses_an_adjacency() {
    let m = torus(4, 3);
    let adj = Adjacency::build(&m);
    assert_eq!(TopologyReport::with_adjacency(&m, &adj, 0.0), report(&m));
}

#[test]
fn empty_mesh() {
    let r = report(&PolyMesh::default());
    assert!(r.is_clean() && !r.is_closed());
    assert_eq!((r.num_vertices, r.num_edges, r.num_faces, r.euler_characteristic), (0, 0, 0, 0));
    assert_eq!(r.genus(), Some(0));
    let (s, what) = split_nonmanifold(&PolyMesh::default());
    assert!(what.is_unchanged() && s.num_faces() == 0);
}

#[test]
fn four_faces_on_an_edge_pair_up() {
    // Two "books" of two pages each along edge 0–1, opposite directions paired.
    let m = mesh(6, &[[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 0, 5]]);
    let r = report(&m);
    assert_eq!(r.nonmanifold, vec![NonManifold::Edge { a: 0, b: 1, faces: vec![0, 1, 2, 3] }]);
    let (s, what) = split_nonmanifold(&m);
    let r = report(&s);
    assert_clean_manifold(&r);
    assert_eq!(what.num_new_vertices(), 2);
    assert_eq!(s.face(0), &[0, 1, 2]);
    assert_eq!(s.face(1), &[1, 0, 3]);
    assert_eq!(s.face(2), &[6, 7, 4]);
    assert_eq!(s.face(3), &[7, 6, 5]);
}

mod properties {
    use proptest::prelude::*;

    use super::*;

    /// Triangles with distinct corners over `n` vertices.
    fn soup() -> impl Strategy<Value = (usize, Vec<[u32; 3]>)> {
        (3..9usize).prop_flat_map(|n| {
            let tri = Just((0..n as u32).collect::<Vec<_>>()).prop_shuffle().prop_map(|v| [v[0], v[1], v[2]]);
            (Just(n), proptest::collection::vec(tri, 1..24))
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

        /// Whatever the soup, the split is manifold and consistently oriented, keeps the
        /// faces and copies positions from the recorded origins; the report's counts add up.
        #[test]
        fn split_is_always_clean((n, tris) in soup()) {
            let m = mesh(n, &tris);
            let r = report(&m);
            prop_assert_eq!(r.components.iter().map(|c| c.euler_characteristic).sum::<i64>(), r.euler_characteristic);
            prop_assert_eq!(r.components.iter().map(|c| c.num_faces).sum::<usize>(), r.num_faces);
            prop_assert_eq!(r.boundary_loops.iter().map(BoundaryLoop::num_edges).sum::<usize>(), r.num_boundary_edges);
            let (s, what) = split_nonmanifold(&m);
            let after = report(&s);
            prop_assert!(after.is_manifold() && after.is_consistently_oriented(), "{}\n{:?}", after, tris);
            prop_assert!(after.boundary_loops.iter().all(|l| l.closed), "{}", after);
            prop_assert!(after.components.iter().all(|c| c.genus.is_some()), "{}", after);
            prop_assert_eq!(s.num_faces(), m.num_faces());
            prop_assert_eq!(what.vertex_origin.len(), s.num_vertices());
            for (v, &o) in what.vertex_origin.iter().enumerate() {
                prop_assert_eq!(s.positions[v], m.positions[o as usize]);
            }
            // Each output face is an input face (up to flipping) through the origins.
            for f in 0..m.num_faces() {
                let mut a: Vec<u32> = s.face(f).iter().map(|&v| what.vertex_origin[v as usize]).collect();
                let mut b = m.face(f).to_vec();
                a.sort_unstable();
                b.sort_unstable();
                prop_assert_eq!(a, b);
            }
            // A clean mesh is a fixed point.
            let (again, what2) = split_nonmanifold(&s);
            prop_assert!(what2.is_unchanged());
            prop_assert_eq!(again, s);
        }
    }
}
