//! √3 and Doo-Sabin subdivision without a peer (`subdivision_reference.rs` compares both with
//! CGAL): counts, Euler characteristic, orientation, valences, closed forms, affine invariance,
//! planes, attributes and errors.

use glam::{DMat3, DVec2, DVec3};
use splinekit::PolyMesh;
use splinekit::mesh::{Adjacency, FaceVarying};
mod common;
use common::{cube, poly, prism};

use splinekit::subdiv::{
    DooSabinOptions, LEVEL_COLORS, Sqrt3Options, SubdivError, catmull_clark_subdivide, doo_sabin_subdivide,
    sqrt3_subdivide,
};

/// An irregular tetrahedron, outward.
fn tetra() -> PolyMesh {
    PolyMesh::from_triangles(
        vec![DVec3::ZERO, DVec3::new(1.0, 0.1, 0.0), DVec3::new(0.2, 1.0, 0.1), DVec3::new(0.1, 0.3, 1.2)],
        &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
}

/// The octahedron, outward.
fn octahedron() -> PolyMesh {
    PolyMesh::from_triangles(
        vec![DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y, DVec3::Z, -DVec3::Z],
        &[[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
    )
}

/// An open `n × n` grid over `[0, 1]²` at height `z(x, y)`, of quads or of triangles (each
/// square split along its diagonal).
fn grid(n: u32, triangles: bool, z: impl Fn(f64, f64) -> f64) -> PolyMesh {
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            p.push(DVec3::new(x, y, z(x, y)));
        }
    }
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if triangles {
                faces.push(vec![q[0], q[1], q[2]]);
                faces.push(vec![q[0], q[2], q[3]]);
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    let refs: Vec<&[u32]> = faces.iter().map(Vec::as_slice).collect();
    poly(p, &refs)
}

fn bump(x: f64, y: f64) -> f64 {
    0.2 * (2.0 * x + 1.0).sin() * (3.0 * y).cos()
}

/// (V, E, F, boundary edges), checking that the mesh is manifold and consistently oriented.
fn counts(mesh: &PolyMesh) -> (usize, usize, usize, usize) {
    let adj = Adjacency::build(mesh);
    assert!(adj.nonmanifold.is_empty(), "{:?}", adj.nonmanifold);
    assert!(adj.nonmanifold_vertices(mesh).is_empty());
    (mesh.num_vertices(), adj.num_edges(), mesh.num_faces(), adj.num_boundary_edges())
}

fn euler(mesh: &PolyMesh) -> i64 {
    let (v, e, f, _) = counts(mesh);
    v as i64 - e as i64 + f as i64
}

fn valences(mesh: &PolyMesh) -> Vec<usize> {
    let adj = Adjacency::build(mesh);
    (0..mesh.num_vertices() as u32).map(|v| adj.corners_of(v).len()).collect()
}

fn sqrt3(mesh: &PolyMesh, levels: usize) -> PolyMesh {
    sqrt3_subdivide(mesh, levels, &Sqrt3Options::default()).unwrap()
}

fn doo_sabin(mesh: &PolyMesh, levels: usize) -> PolyMesh {
    doo_sabin_subdivide(mesh, levels, &DooSabinOptions::default()).unwrap()
}

/// √3: `(V, F)` → `(V + F, 3F)` on closed meshes; with `B` boundary edges, odd levels keep the
/// boundary (`V + F`, `B` edges) and even levels split every boundary edge into three
/// (`V + F + B`, `3B`). The Euler characteristic and a consistent orientation are kept.
#[test]
fn sqrt3_counts_euler_and_orientation() {
    for (name, mesh) in [
        ("tetra", tetra()),
        ("octahedron", octahedron()),
        ("grid", grid(3, true, bump)),
        ("single triangle", PolyMesh::from_triangles(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[[0, 1, 2]])),
    ] {
        let (mut v, _, mut f, mut b) = counts(&mesh);
        let chi = euler(&mesh);
        for level in 1..=4 {
            let fine = sqrt3(&mesh, level);
            let border = level.is_multiple_of(2);
            (v, f, b) = (v + f + if border { b } else { 0 }, 3 * f, if border { 3 * b } else { b });
            let (fv, _, ff, fb) = counts(&fine);
            assert_eq!((fv, ff, fb), (v, f, b), "{name} level {level}: (V, F, B)");
            assert_eq!(euler(&fine), chi, "{name} level {level}");
            assert!(fine.is_triangle_mesh());
        }
    }
}

/// On a closed mesh one level keeps every old vertex's valence (its edges to old neighbours are
/// flipped into edges to face points) and gives every face point valence 6.
#[test]
fn sqrt3_valences_and_closed_form() {
    let mesh = octahedron();
    let fine = sqrt3(&mesh, 1);
    let val = valences(&fine);
    assert!(val[..6].iter().all(|&n| n == 4), "{val:?}");
    assert!(val[6..].iter().all(|&n| n == 6), "{val:?}");
    // α(4) = (4 − 2cos(π/2))/9 = 4/9: the vertex at x moves to 5/9·x (its neighbours sum to 0
    // in x); face points are the centroids (±1/3, ±1/3, ±1/3)
    for (v, p) in fine.positions[..6].iter().enumerate() {
        assert!((p.length() - 5.0 / 9.0).abs() < 1e-15, "vertex {v} at {p}");
    }
    for p in &fine.positions[6..] {
        assert!((p.abs() - DVec3::splat(1.0 / 3.0)).abs().max_element() < 1e-15, "{p}");
    }
    // the tetrahedron: α(3) = 5/9 pulls a vertex 5/9 of the way to its neighbours' centroid
    let t = tetra();
    let fine = sqrt3(&t, 1);
    let centroid = (t.positions[1] + t.positions[2] + t.positions[3]) / 3.0;
    assert!(fine.positions[0].distance(t.positions[0] * (4.0 / 9.0) + centroid * (5.0 / 9.0)) < 1e-15);
}

/// Kobbelt's boundary rule on a flat grid (spacing h = 1/3): level 1 keeps the boundary;
/// level 2 moves boundary vertex `p` with boundary neighbours `a`, `b` to `(4a + 19p + 4b)/27`
/// and splits boundary edge `u → w` at `(u₋ + 16u + 10w)/27`, `(10u + 16w + w₊)/27`. Along the
/// bottom edge that is a ternary refinement: the points left on y = 0 are 2h/3, h, 4h/3, …,
/// 7h/3, evenly spaced; the corner (0, 0) moves inside to (4h/27, 4h/27).
#[test]
fn sqrt3_boundary_rule() {
    let mesh = grid(3, true, |_, _| 0.0);
    let one = sqrt3(&mesh, 1);
    for v in (0..16).filter(|v| ![5, 6, 9, 10].contains(v)) {
        assert_eq!(one.positions[v], mesh.positions[v], "level 1 keeps boundary vertex {v}");
    }
    let two = sqrt3(&mesh, 2);
    let h = 1.0 / 3.0;
    let mut bottom: Vec<f64> = two.positions.iter().filter(|p| p.y == 0.0).map(|p| p.x).collect();
    bottom.sort_by(f64::total_cmp);
    assert_eq!(bottom.len(), 6, "{bottom:?}");
    for (k, x) in bottom.iter().enumerate() {
        assert!((x - (k + 2) as f64 * h / 3.0).abs() < 1e-15, "{bottom:?}");
    }
    let corner = two.positions[0];
    assert!(corner.distance(DVec3::new(4.0 * h / 27.0, 4.0 * h / 27.0, 0.0)) < 1e-15, "{corner}");
    assert!(two.positions.iter().all(|p| p.z == 0.0), "a flat mesh stays flat");
}

/// Doo-Sabin: one vertex per parent corner; closed meshes get `F + E + V` faces, open ones `F +
/// E_interior + V_interior`; every vertex of a closed result has valence 4; Euler characteristic
/// and orientation kept.
#[test]
fn doo_sabin_counts_euler_and_orientation() {
    for (name, mesh) in [
        ("cube", cube()),
        ("prism", prism()),
        ("octahedron", octahedron()),
        ("quad grid", grid(4, false, bump)),
        ("triangle grid", grid(3, true, bump)),
    ] {
        let chi = euler(&mesh);
        let mut level_mesh = mesh.clone();
        for level in 1..=3 {
            let fine = doo_sabin(&mesh, level);
            let adj = Adjacency::build(&level_mesh);
            let (v, e, f, b) = counts(&level_mesh);
            let boundary_vertices = (0..v as u32)
                .filter(|&x| adj.corners_of(x).iter().any(|&c| adj.twin[c as usize] == splinekit::mesh::NONE))
                .count();
            let expected = (level_mesh.face_vertices.len(), f + (e - b) + (v - boundary_vertices));
            assert_eq!((fine.num_vertices(), fine.num_faces()), expected, "{name} level {level}: (V, F)");
            assert_eq!(euler(&fine), chi, "{name} level {level}");
            if b == 0 {
                assert_eq!(fine.num_vertices(), 2 * e, "{name} level {level}: V' = 2E");
                assert!(valences(&fine).iter().all(|&n| n == 4), "{name} level {level}");
            }
            level_mesh = doo_sabin(&level_mesh, 1);
            assert_eq!(level_mesh, fine, "{name}: level by level = all at once");
        }
    }
}

/// The cube's corner points: 9/16, 3/16, 1/16, 3/16 of the face's corners, so (±1/2, ±1/2) in
/// the face's plane.
#[test]
fn doo_sabin_closed_form_on_the_cube() {
    let fine = doo_sabin(&cube(), 1);
    for p in &fine.positions {
        let mut a = p.abs().to_array();
        a.sort_by(f64::total_cmp);
        assert_eq!(a, [0.5, 0.5, 1.0], "{p}");
    }
    // triangle weights 2/3, 1/6, 1/6 (n = 3: (n + 5)/4n and (3 + 2cos(2π/3))/4n)
    let t = PolyMesh::from_triangles(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[[0, 1, 2]]);
    let fine = doo_sabin(&t, 1);
    assert_eq!((fine.num_vertices(), fine.num_faces()), (3, 1));
    assert!(fine.positions[1].distance(DVec3::new(2.0 / 3.0, 1.0 / 6.0, 0.0)) < 1e-15);
}

/// Both schemes commute with affine maps (their weights sum to 1), and a planar mesh stays in
/// its plane.
#[test]
fn affine_invariance_and_planes() {
    let a = DMat3::from_cols(DVec3::new(1.2, 0.3, -0.2), DVec3::new(-0.4, 0.9, 0.5), DVec3::new(0.1, -0.3, 1.4));
    let t = DVec3::new(3.0, -1.0, 2.0);
    let map = |m: &PolyMesh| PolyMesh { positions: m.positions.iter().map(|&p| a * p + t).collect(), ..m.clone() };
    let close = |x: &PolyMesh, y: &PolyMesh| {
        assert_eq!(x.face_vertices, y.face_vertices);
        for (p, q) in x.positions.iter().zip(&y.positions) {
            assert!(p.distance(*q) < 1e-12, "{p} vs {q}");
        }
    };
    for mesh in [octahedron(), grid(3, true, bump)] {
        close(&sqrt3(&map(&mesh), 3), &map(&sqrt3(&mesh, 3)));
    }
    for mesh in [prism(), grid(4, false, bump)] {
        close(&doo_sabin(&map(&mesh), 2), &map(&doo_sabin(&mesh, 2)));
    }
    // the plane z = 0.3x − 0.2y + 0.1
    let plane = |x: f64, y: f64| 0.3 * x - 0.2 * y + 0.1;
    let off = |m: &PolyMesh| m.positions.iter().map(|p| (p.z - plane(p.x, p.y)).abs()).fold(0.0, f64::max);
    assert!(off(&sqrt3(&grid(3, true, plane), 4)) < 1e-15);
    assert!(off(&doo_sabin(&grid(3, false, plane), 3)) < 1e-15);
    assert!(off(&doo_sabin(&grid(3, true, plane), 3)) < 1e-15);
}

/// Colours and UVs follow the position weights: colours equal to the positions stay equal to
/// them, and so do UVs equal to (x, y). Doo-Sabin keeps UV seams apart (each new vertex belongs
/// to one face corner); √3 drops UVs with seams. Normals are dropped.
#[test]
fn attributes_are_carried() {
    let with_attributes = |mut m: PolyMesh| {
        m.colors = m.positions.clone();
        let values: Vec<DVec2> = m.positions.iter().map(|p| p.truncate()).collect();
        m.uvs = Some(FaceVarying { values, indices: m.face_vertices.clone() });
        m.normals = Some(FaceVarying { values: vec![DVec3::Z], indices: vec![0; m.face_vertices.len()] });
        m
    };
    let check = |fine: &PolyMesh| {
        assert_eq!(fine.colors, fine.positions);
        let uvs = fine.uvs.as_ref().expect("UVs carried");
        assert_eq!(uvs.indices, fine.face_vertices);
        for (uv, p) in uvs.values.iter().zip(&fine.positions) {
            assert!(uv.distance(p.truncate()) < 1e-15);
        }
        assert!(fine.normals.is_none());
    };
    check(&sqrt3(&with_attributes(grid(3, true, bump)), 3));
    check(&doo_sabin(&with_attributes(grid(3, false, bump)), 2));

    // UVs per face corner of the cube: every face (0,0), (1,0), (1,1), (0,1), a seam on every
    // edge; Doo-Sabin's F-face points land at (¼ or ¾, ¼ or ¾)
    let mut c = cube();
    c.uvs = Some(FaceVarying {
        values: vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y],
        indices: (0..24).map(|k| k % 4).collect(),
    });
    let fine = doo_sabin(&c, 1);
    let uvs = fine.uvs.unwrap();
    for uv in &uvs.values {
        assert!([0.25, 0.75].contains(&uv.x) && [0.25, 0.75].contains(&uv.y), "{uv}");
    }
    // √3 cannot carry seams: the octahedron with a UV index per corner
    let mut o = octahedron();
    o.uvs = Some(FaceVarying { values: vec![DVec2::ZERO; 24], indices: (0..24).collect() });
    o.uvs.as_mut().unwrap().values[5] = DVec2::ONE;
    assert!(sqrt3(&o, 1).uvs.is_none());
}

/// Colour by level (√3): base vertices grey, each level's new vertices its colour.
#[test]
fn sqrt3_color_by_level() {
    let mesh = octahedron();
    let fine = sqrt3_subdivide(&mesh, 2, &Sqrt3Options { color_by_level: true }).unwrap();
    assert_eq!(fine.colors.len(), 6 + 8 + 24);
    assert!(fine.colors[..6].iter().all(|&c| c == LEVEL_COLORS[0]));
    assert!(fine.colors[6..14].iter().all(|&c| c == LEVEL_COLORS[1]));
    assert!(fine.colors[14..].iter().all(|&c| c == LEVEL_COLORS[2]));
}

/// Zero levels give the mesh back (normals dropped).
#[test]
fn zero_levels() {
    let mesh = prism();
    assert_eq!(doo_sabin(&mesh, 0), mesh);
    assert_eq!(sqrt3(&octahedron(), 0), octahedron());
}

/// Errors name the face, edge or vertex; two closed fans at one vertex (two tetrahedra sharing
/// a tip) are caught too, by Catmull-Clark as well.
#[test]
fn errors_name_the_problem() {
    let quad = poly(vec![DVec3::ZERO, DVec3::X, DVec3::ONE, DVec3::Y], &[&[0, 1, 2, 3]]);
    let err = sqrt3_subdivide(&quad, 1, &Sqrt3Options::default()).unwrap_err();
    assert_eq!(err.to_string(), "face 0 has 4 corners; √3 subdivision needs triangles (triangulate the mesh first)");
    assert!(matches!(err, SubdivError::NotTriangles { face: 0, corners: 4, .. }));

    let fin = PolyMesh::from_triangles(vec![DVec3::ZERO; 5], &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    let err = sqrt3_subdivide(&fin, 1, &Sqrt3Options::default()).unwrap_err();
    assert!(err.to_string().contains("edge 0–1"), "{err}");
    let err = doo_sabin_subdivide(&fin, 1, &DooSabinOptions::default()).unwrap_err();
    assert!(err.to_string().contains("edge 0–1"), "{err}");

    let bowtie = PolyMesh::from_triangles(vec![DVec3::ZERO; 5], &[[0, 1, 2], [0, 3, 4]]);
    let err = doo_sabin_subdivide(&bowtie, 1, &DooSabinOptions::default()).unwrap_err();
    assert!(err.to_string().contains("vertex 0 is non-manifold"), "{err}");

    // two tetrahedra touching at vertex 0: no boundary, two closed fans
    let mut p = tetra().positions;
    p.extend([DVec3::new(-1.0, 0.0, 0.0), DVec3::new(0.0, -1.0, 0.1), DVec3::new(0.0, 0.0, -1.0)]);
    let twin = PolyMesh::from_triangles(
        p,
        &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 5, 4], [0, 4, 6], [0, 6, 5], [4, 5, 6]],
    );
    let expected = "vertex 0 is non-manifold: its faces form 2 separate fans";
    let err = sqrt3_subdivide(&twin, 1, &Sqrt3Options::default()).unwrap_err();
    assert_eq!(err.to_string(), expected);
    let err = doo_sabin_subdivide(&twin, 1, &DooSabinOptions::default()).unwrap_err();
    assert_eq!(err.to_string(), expected);
    // Catmull-Clark takes it (issue #39): the vertex is a corner, it stays
    let fine = catmull_clark_subdivide(&twin, 1, &Default::default()).unwrap();
    assert_eq!(fine.positions[0], twin.positions[0]);
}
