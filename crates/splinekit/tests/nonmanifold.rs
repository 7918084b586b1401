//! Non-manifold and degenerate topology against OpenSubdiv 3.5 (issue #39): Loop and
//! Catmull-Clark subdivision of edges of 3, 4 and 100 faces, vertices with several fans,
//! back-to-back faces, interior vertices of valence 2, a fold-over, faces that repeat a vertex
//! (degenerate triangles, quad poles) and triangles and quads mixed, at levels 1 to 3 and at the
//! limit of levels 1 and 2 (and three of them with one-face corners fixed), in
//! `tests/data/nonmanifold/` (made by `bench/make_nonmanifold_references.sh` from
//! `bench/meshgen.py nonmanifold`).
//!
//! OpenSubdiv keeps the two halves of an edge that a face uses twice as two edges, so some of
//! its vertices coincide (the middles of such halves; the face points of back-to-back faces).
//! So vertices are matched by position to *classes* of coinciding reference vertices: every
//! vertex of ours must lie within [`MATCH_TOL`] of a reference vertex, each class must get as
//! many of ours as it has, and our faces, written in classes, must be the reference's faces as
//! a multiset (orientation kept, corners rotated).

mod common;

use std::collections::HashMap;
use std::fmt::Write as _;

use glam::DVec3;
use splinekit::PolyMesh;
use splinekit::subdiv::{
    BoundaryRule, CatmullClarkOptions, Creases, CreasingMethod, LoopOptions, catmull_clark_subdivide,
    catmull_clark_subdivide_limit, is_nonmanifold, loop_subdivide, loop_subdivide_limit,
};

/// Largest distance between a vertex of ours and its reference vertex, relative to the
/// diagonal of the reference's bounding box.
const MATCH_TOL: f64 = 1e-12;

/// The Loop meshes (all triangles) and the Catmull-Clark ones; the edge of 100 faces has no
/// level 3.
const LOOP: [&str; 8] = ["fins3", "fins4", "edge100", "cones", "backtoback", "pillow", "foldgrid", "degenerate"];
const CATMARK: [&str; 11] = [
    "fins3",
    "fins4",
    "edge100",
    "cones",
    "backtoback",
    "pillow",
    "foldgrid",
    "degenerate",
    "poles",
    "valence2",
    "cubes",
];

/// The `v` and `f` lines of `tests/data/nonmanifold/<file>`.
fn read(file: &str) -> PolyMesh {
    common::read_obj(&format!("nonmanifold/{file}"))
}

fn levels(name: &str) -> u32 {
    if name == "edge100" { 2 } else { 3 }
}

fn diagonal(points: &[DVec3]) -> f64 {
    let lo = points.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    lo.distance(hi)
}

/// Per point, its class: the smallest index of the points within `tol` of it (the references'
/// distinct vertices are far apart, coinciding ones equal).
fn classes(points: &[DVec3], tol: f64) -> Vec<usize> {
    let mut class: Vec<usize> = (0..points.len()).collect();
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&i, &j| points[i].x.total_cmp(&points[j].x));
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if points[j].x - points[i].x > tol {
                break;
            }
            if points[i].distance(points[j]) <= tol {
                let c = class[i].min(class[j]);
                class[i] = c;
                class[j] = c;
            }
        }
    }
    // settle chains to their smallest member
    for i in 0..points.len() {
        class[i] = class[class[i]];
    }
    class
}

/// The largest distance from our vertices to the reference's, or why the meshes differ.
fn compare(ours: &[DVec3], faces: &PolyMesh, reference: &PolyMesh) -> Result<f64, String> {
    if ours.len() != reference.positions.len() || faces.num_faces() != reference.num_faces() {
        return Err(format!(
            "(vertices, faces) = ({}, {}), the reference has ({}, {})",
            ours.len(),
            faces.num_faces(),
            reference.positions.len(),
            reference.num_faces()
        ));
    }
    let tol = MATCH_TOL * diagonal(&reference.positions);
    let class = classes(&reference.positions, tol);
    let mut map = Vec::with_capacity(ours.len());
    let mut worst = 0.0f64;
    for (i, &p) in ours.iter().enumerate() {
        let (j, d) = reference
            .positions
            .iter()
            .enumerate()
            .map(|(j, q)| (j, p.distance(*q)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        if d > tol {
            return Err(format!("our vertex {i} at {p} is {d:.3e} from the nearest reference vertex {j}"));
        }
        worst = worst.max(d);
        map.push(class[j]);
    }
    let count = |it: &mut dyn Iterator<Item = usize>| {
        let mut m = HashMap::new();
        for c in it {
            *m.entry(c).or_insert(0usize) += 1;
        }
        m
    };
    if count(&mut map.iter().copied()) != count(&mut class.iter().copied()) {
        return Err("our vertices fall into the reference's coinciding vertices in other numbers".into());
    }
    // the smallest rotation (a face's classes can repeat)
    let canonical = |f: Vec<usize>| {
        (0..f.len()).map(|k| f[k..].iter().chain(&f[..k]).copied().collect::<Vec<usize>>()).min().unwrap()
    };
    let multiset = |faces: Vec<Vec<usize>>| {
        let mut m = HashMap::new();
        for f in faces {
            *m.entry(canonical(f)).or_insert(0usize) += 1;
        }
        m
    };
    let mine = multiset(faces.faces().map(|f| f.iter().map(|&v| map[v as usize]).collect()).collect());
    let theirs = multiset(reference.faces().map(|f| f.iter().map(|&v| class[v as usize]).collect()).collect());
    if mine != theirs {
        let extra = mine.keys().filter(|f| mine.get(*f) != theirs.get(*f)).take(3).collect::<Vec<_>>();
        return Err(format!("the faces differ, e.g. (in reference classes) {extra:?}"));
    }
    Ok(worst)
}

/// Runs `case` on every (mesh, scheme, level) and collects the failures and the table of the
/// largest differences.
fn sweep(scheme: &str, meshes: &[&str], case: impl Fn(&PolyMesh, u32, bool) -> Result<(Vec<DVec3>, PolyMesh), String>) {
    let mut failures = String::new();
    let mut table = String::new();
    for &name in meshes {
        let input = read(&format!("{name}.in.obj"));
        // (two are manifold: valence-2 vertices on the manifold path, and a pillow whose levels
        // have two edges between the same two vertices, whose limit needs the subdivision's edges)
        assert_eq!(is_nonmanifold(&input), !["valence2", "pillow"].contains(&name), "{name}");
        for limit in [false, true] {
            let top = if limit { 2 } else { levels(name) };
            for level in 1..=top {
                let kind = if limit { ".limit" } else { "" };
                let file = format!("{name}.osd-{scheme}{kind}.l{level}.obj");
                let result = case(&input, level, limit).and_then(|(p, faces)| compare(&p, &faces, &read(&file)));
                match result {
                    Ok(d) => writeln!(
                        table,
                        "| {name} | {scheme} | {level}{} | {d:.1e} |",
                        if limit { " limit" } else { "" }
                    )
                    .unwrap(),
                    Err(e) => writeln!(failures, "{file}: {e}").unwrap(),
                }
            }
        }
    }
    println!("{table}");
    assert!(failures.is_empty(), "against OpenSubdiv ({scheme}):\n{failures}");
}

#[test]
fn loop_matches_opensubdiv_on_nonmanifold_meshes() {
    let options = LoopOptions::default();
    sweep("loop", &LOOP, |input, level, limit| {
        let fine = loop_subdivide(input, level, &options).map_err(|e| e.to_string())?;
        if limit {
            let no = (&Creases::default(), CreasingMethod::default());
            let (mesh, p, _) = loop_subdivide_limit(input, level, &options, no.0, no.1).map_err(|e| e.to_string())?;
            return Ok((p, mesh));
        }
        Ok((fine.positions.clone(), fine))
    });
}

#[test]
fn catmull_clark_matches_opensubdiv_on_nonmanifold_meshes() {
    let options = CatmullClarkOptions::default();
    sweep("catmark", &CATMARK, |input, level, limit| {
        let fine = catmull_clark_subdivide(input, level as usize, &options).map_err(|e| e.to_string())?;
        if limit {
            let c = (&Creases::default(), CreasingMethod::default());
            let (mesh, p, _) =
                catmull_clark_subdivide_limit(input, level as usize, &options, c.0, c.1).map_err(|e| e.to_string())?;
            return Ok((p, mesh));
        }
        Ok((fine.positions.clone(), fine))
    });
}

/// Invariants of the non-manifold path: moving the mesh moves the subdivision (the rules are
/// affine), colours that are an affine image of the positions stay one, and each level has
/// `V + E` (Loop) or `V + E + F` (Catmull-Clark) vertices.
#[test]
fn nonmanifold_subdivision_is_affine_and_counts_follow() {
    let shift = |p: DVec3| DVec3::new(0.3 * p.y - 2.0 * p.x + 1.0, p.z + 0.5 * p.x, -p.y + 3.0);
    for name in CATMARK {
        let mut mesh = read(&format!("{name}.in.obj"));
        mesh.colors = mesh.positions.iter().map(|&p| shift(p)).collect();
        let mut moved = mesh.clone();
        moved.positions = mesh.colors.clone();
        let triangles = mesh.is_triangle_mesh();
        for level in 1..=2u32 {
            let runs: Vec<(PolyMesh, PolyMesh)> = if triangles {
                let o = LoopOptions::default();
                vec![(loop_subdivide(&mesh, level, &o).unwrap(), loop_subdivide(&moved, level, &o).unwrap())]
            } else {
                vec![]
            }
            .into_iter()
            .chain([(
                catmull_clark_subdivide(&mesh, level as usize, &CatmullClarkOptions::default()).unwrap(),
                catmull_clark_subdivide(&moved, level as usize, &CatmullClarkOptions::default()).unwrap(),
            )])
            .collect();
            for (fine, fine_moved) in runs {
                assert_eq!(fine.face_vertices, fine_moved.face_vertices, "{name} level {level}");
                for (k, ((&p, &q), &c)) in
                    fine.positions.iter().zip(&fine_moved.positions).zip(&fine.colors).enumerate()
                {
                    assert!(shift(p).distance(q) < 1e-12, "{name} level {level} vertex {k}: {p} moved is not {q}");
                    assert!(c.distance(q) < 1e-12, "{name} level {level} vertex {k}: colour {c}, position {q}");
                }
            }
        }
    }
}

/// One level's counts: Loop `V + E` vertices and `4F` triangles, Catmull-Clark `V + E + F` and
/// one quad per corner, where `E` counts OpenSubdiv's edges: the degenerate triangle `a a b` of
/// `degenerate` has three (`a–a`, `a–b` and `b–a` apart), so its level has two vertices at `a`.
#[test]
fn counts_count_opensubdivs_edges() {
    let mesh = read("degenerate.in.obj");
    // a 4 x 4 grid: 25 vertices, 56 edges, 32 triangles; then (0-based) 12 12 13 (12–12, and the
    // grid's edge 12–13 gets a third face and an edge 13–12 of its own), 16 16 16 (three edges
    // 16–16) and 18 24 18 (18–24 on the grid, 24–18 of its own, 18–18): 7 more edges
    let fine = loop_subdivide(&mesh, 1, &LoopOptions::default()).unwrap();
    assert_eq!((fine.num_vertices(), fine.num_faces()), (25 + 63, 4 * 35));
    let fine = catmull_clark_subdivide(&mesh, 1, &CatmullClarkOptions::default()).unwrap();
    assert_eq!((fine.num_vertices(), fine.num_faces()), (25 + 63 + 35, 3 * 35));
}

/// One-face corners kept fixed (`BoundaryRule::Corners`, OpenSubdiv's
/// `VTX_BOUNDARY_EDGE_AND_CORNER`) next to non-manifold features: a bowtie, a fold-over and
/// degenerate triangles on a grid with two one-face corners, levels 1 and 2.
#[test]
fn fixed_corners_match_opensubdiv_on_nonmanifold_meshes() {
    let mut failures = String::new();
    for name in ["cones", "foldgrid", "degenerate"] {
        let input = read(&format!("{name}.in.obj"));
        for level in 1..=2u32 {
            let loop_options = LoopOptions { boundary: BoundaryRule::Corners, ..LoopOptions::default() };
            let catmark_options =
                CatmullClarkOptions { boundary: BoundaryRule::Corners, ..CatmullClarkOptions::default() };
            let runs = [
                ("loop", loop_subdivide(&input, level, &loop_options)),
                ("catmark", catmull_clark_subdivide(&input, level as usize, &catmark_options)),
            ];
            for (scheme, fine) in runs {
                let file = format!("{name}.osd-{scheme}-corners.l{level}.obj");
                let result = fine.map_err(|e| e.to_string()).and_then(|f| compare(&f.positions, &f, &read(&file)));
                if let Err(e) = result {
                    writeln!(failures, "{file}: {e}").unwrap();
                }
            }
        }
    }
    assert!(failures.is_empty(), "against OpenSubdiv (EDGE_AND_CORNER):\n{failures}");
}

/// #38: a face of fewer than three corners (a PLY face list of length 0, 1 or 2, an OBJ
/// `f 1 2`) is refused by name by every polygon scheme, at every number of levels, with and
/// without creases and limits; Catmull-Clark gave a face point of 0/0 for an empty face.
#[test]
fn faces_of_fewer_than_three_corners_are_refused() {
    use splinekit::subdiv::{
        DooSabinOptions, SubdivError, catmull_clark_limit_positions, catmull_clark_step,
        catmull_clark_subdivide_creased, doo_sabin_subdivide,
    };
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
    for short in [vec![], vec![3], vec![1, 3]] {
        let mut faces = vec![vec![0u32, 1, 2], vec![2, 1, 3]];
        faces.insert(1, short.clone());
        let mut mesh = PolyMesh { positions: positions.clone(), ..PolyMesh::default() };
        mesh.face_offsets = vec![0];
        for f in &faces {
            mesh.face_vertices.extend(f);
            mesh.face_offsets.push(mesh.face_vertices.len() as u32);
        }
        let expected = SubdivError::TooFewCorners { face: 1, corners: short.len() };
        let cc = CatmullClarkOptions::default();
        for levels in 0..3 {
            assert_eq!(catmull_clark_subdivide(&mesh, levels, &cc).unwrap_err(), expected, "{levels} levels");
            assert_eq!(doo_sabin_subdivide(&mesh, levels, &DooSabinOptions::default()).unwrap_err(), expected);
            let bilinear = splinekit::subdiv::bilinear_subdivide(&mesh, levels, &Default::default());
            assert_eq!(bilinear.unwrap_err(), expected);
            let creased =
                catmull_clark_subdivide_creased(&mesh, levels, &cc, &Creases::default(), CreasingMethod::Chaikin);
            assert_eq!(creased.unwrap_err(), expected);
        }
        assert_eq!(catmull_clark_step(&mesh, 1, &cc).unwrap_err(), expected);
        assert_eq!(catmull_clark_limit_positions(&mesh, &cc).unwrap_err(), expected);
        let limit = catmull_clark_subdivide_limit(&mesh, 1, &cc, &Creases::default(), CreasingMethod::Uniform);
        assert_eq!(limit.unwrap_err(), expected);
        assert!(!is_nonmanifold(&mesh));
        assert_eq!(
            expected.to_string(),
            format!(
                "face 1 has {} corner{}; every face needs at least 3 (remove it from the file)",
                short.len(),
                if short.len() == 1 { "" } else { "s" }
            )
        );
    }
}
