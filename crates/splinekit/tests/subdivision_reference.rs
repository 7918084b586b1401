//! Subdivision against independent implementations.
//!
//! - Loop (issue #4): OpenSubdiv 3.5 (Loop's β, boundary crease rules with one-face corners
//!   smoothed or, with `VTX_BOUNDARY_EDGE_AND_CORNER`, fixed) and libigl 2.6.3 (Warren's β,
//!   the same crease rules), on the reference meshes in `tests/data/loop/` (made by
//!   `bench/make_loop_references.sh`; its README says how).
//! - Catmull-Clark (issue #7): OpenSubdiv 3.5's `SCHEME_CATMARK` (the same two boundary
//!   options) on a cube, a quad torus, a prism of pentagons, quads and triangles and an open
//!   quad grid, in `tests/data/catmark/` (made by `bench/make_catmark_references.sh` with
//!   `bench/drivers/osd_catmark.cpp`).
//! - √3 and Doo-Sabin (issue #7): CGAL 5.5's `Sqrt3_subdivision` (levels 1 to 3: the boundary
//!   is refined on level 2 only) on a tetrahedron, an icosahedron, an open triangle grid and an
//!   icosahedron with a hole, and `DooSabin_subdivision` on a cube, the prism, the icosahedron,
//!   an open quad grid and the open triangle grid, in `tests/data/cgal/` (made by
//!   `bench/make_cgal_references.sh` with `bench/drivers/cgal_sqrt3_doosabin.cpp`; the cube,
//!   prism and quad grid are Catmull-Clark's inputs, in `tests/data/catmark/`).
//! - OpenSubdiv's options (issue #39): Catmull-Clark with `TRI_SUB_SMOOTH` on meshes with
//!   triangles (also creased, with fixed corners, non-manifold) and the bilinear scheme, in
//!   `tests/data/options/` (made by `bench/make_options_references.sh`).
//! - Modified butterfly (issue #7): OpenMesh 9's `ModifiedButterflyT` on closed meshes of
//!   valences 3 to 7, two open meshes and the bunny's base mesh, in `tests/data/openmesh/`
//!   (made by `bench/make_butterfly_references.sh` with `bench/drivers/openmesh_loop.cpp`).
//!
//! Our vertex numbering differs from the peers', so meshes are compared as point sets plus
//! topology: every vertex of ours is matched to the reference vertex nearest to it, the
//! matching must be a bijection within [`MATCH_TOL`], and our faces renumbered through it
//! must be exactly the reference's faces, with the same orientation (up to rotation of the
//! corners). The Loop counts V+E, 2E+3F, 4F are checked on the inputs and on the reference files.

use std::collections::HashSet;
use std::fmt::Write as _;

use glam::DVec3;
use splinekit::PolyMesh;
use splinekit::subdiv::{
    BilinearOptions, BoundaryRule, ButterflyOptions, CatmullClarkOptions, Creases, CreasingMethod, DooSabinOptions,
    EdgeCrease, HoleSplit, LoopOptions, LoopWeights, Sqrt3Options, TriangleSubdivision, VertexCrease,
    bilinear_subdivide, boundary_holes, butterfly_subdivide, catmull_clark_limit_creased, catmull_clark_limit_normals,
    catmull_clark_limit_positions, catmull_clark_step, catmull_clark_subdivide, catmull_clark_subdivide_creased,
    doo_sabin_subdivide, loop_limit_creased, loop_limit_normals, loop_limit_positions, loop_subdivide,
    loop_subdivide_creased, remove_holes, sqrt3_subdivide,
};

/// Largest distance allowed between a vertex of ours and its match in the reference, as a
/// fraction of the diagonal of the reference's bounding box (the meshes are 0.15 to 3 units
/// across). The peers agree with each other to 3e-16 of it, and any two reference vertices are
/// more than 1e-3 of it apart.
const MATCH_TOL: f64 = 1e-12;

/// Largest distance allowed between our unit limit normal and OpenSubdiv's at a matched
/// vertex (about the angle between them, in radians).
const NORMAL_TOL: f64 = 1e-12;

/// The reference meshes and the finest level stored for each (the bunny base only at level 1,
/// to keep the data small).
const MESHES: [(&str, u32); 5] =
    [("icosahedron20", 2), ("icosphere80", 2), ("torus96", 2), ("grid32", 2), ("bunnybase883", 1)];

/// A polygon mesh as read from an OBJ file.
struct Obj {
    positions: Vec<DVec3>,
    /// The `vn` lines (the limit references' unit limit normals, one per vertex).
    normals: Vec<DVec3>,
    faces: Vec<Vec<u32>>,
    /// The faces as triangles, when they all are.
    triangles: Vec<[u32; 3]>,
    /// The `t crease` and `t corner` tags.
    creases: Creases,
}

impl Obj {
    fn to_poly(&self) -> PolyMesh {
        let mut face_offsets = vec![0];
        for f in &self.faces {
            face_offsets.push(face_offsets.last().unwrap() + f.len() as u32);
        }
        PolyMesh {
            positions: self.positions.clone(),
            face_offsets,
            face_vertices: self.faces.concat(),
            ..PolyMesh::default()
        }
    }
}

/// Reads the `v` and `f` lines of `tests/data/loop/<file>` (`tests/data/<dir>/<file>` for a
/// path `dir/file`; 1-based indices; `a/b/c` corners use `a`); every other line is ignored.
/// The core crate has no I/O of its own.
fn read_obj(file: &str) -> Obj {
    let file = if file.contains('/') { file.to_owned() } else { format!("loop/{file}") };
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {path}: {e}"));
    let mut obj = Obj {
        positions: Vec::new(),
        normals: Vec::new(),
        faces: Vec::new(),
        triangles: Vec::new(),
        creases: Creases::default(),
    };
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let bad = || -> ! { panic!("{path}:{}: cannot read {line:?}", n + 1) };
        match words.next() {
            Some(kind @ ("v" | "vn")) => {
                let mut c = [0.0; 3];
                for x in &mut c {
                    *x = words.next().and_then(|w| w.parse().ok()).unwrap_or_else(|| bad());
                }
                if kind == "v" { &mut obj.positions } else { &mut obj.normals }.push(DVec3::from_array(c));
            }
            Some("f") => {
                let corners: Vec<u32> = words
                    .map(|w| {
                        w.split('/')
                            .next()
                            .and_then(|k| k.parse::<u32>().ok())
                            .filter(|&k| k >= 1)
                            .unwrap_or_else(|| bad())
                            - 1
                    })
                    .collect();
                if corners.len() < 3 {
                    bad();
                }
                obj.faces.push(corners);
            }
            // `t crease N/M v0 .. s ..` (a chain of edges) and `t corner N/M v .. s ..`, 0-based
            Some("t") => {
                let name = words.next().unwrap_or_else(|| bad());
                if matches!(name, "interpolateboundary" | "creasemethod" | "smoothtriangles") {
                    continue; // the options of `tests/data/options/`, given to the tests in code
                }
                let (ni, nf) = words.next().and_then(|w| w.split_once('/')).unwrap_or_else(|| bad());
                let (ni, nf): (usize, usize) =
                    (ni.parse().unwrap_or_else(|_| bad()), nf.parse().unwrap_or_else(|_| bad()));
                let args: Vec<&str> = words.collect();
                let ints: Vec<u32> = args[..ni].iter().map(|w| w.parse().unwrap_or_else(|_| bad())).collect();
                let floats: Vec<f32> = args[ni..ni + nf].iter().map(|w| w.parse().unwrap_or_else(|_| bad())).collect();
                let sharpness = |k: usize| if floats.len() == 1 { floats[0] } else { floats[k] };
                match name {
                    "crease" => obj.creases.edges.extend(ints.windows(2).enumerate().map(|(k, w)| EdgeCrease {
                        a: w[0],
                        b: w[1],
                        sharpness: sharpness(k),
                    })),
                    "corner" => obj.creases.vertices.extend(
                        ints.iter().enumerate().map(|(k, &vertex)| VertexCrease { vertex, sharpness: sharpness(k) }),
                    ),
                    _ => bad(),
                }
            }
            _ => {}
        }
    }
    let n = obj.positions.len() as u32;
    assert!(obj.faces.iter().flatten().all(|&v| v < n), "{path}: a face refers to a missing vertex");
    if obj.faces.iter().all(|f| f.len() == 3) {
        obj.triangles = obj.faces.iter().map(|f| [f[0], f[1], f[2]]).collect();
    }
    obj
}

/// The input mesh `<name>.in.obj`.
fn input(name: &str) -> PolyMesh {
    let obj = read_obj(&format!("{name}.in.obj"));
    PolyMesh::from_triangles(obj.positions, &obj.triangles)
}

fn options(weights: LoopWeights, boundary: BoundaryRule) -> LoopOptions {
    LoopOptions { weights, boundary, ..LoopOptions::default() }
}

/// The face rotated so that its smallest index comes first (orientation kept).
fn canonical(face: &[u32]) -> Vec<u32> {
    let k = (0..face.len()).min_by_key(|&k| face[k]).unwrap_or(0);
    face[k..].iter().chain(&face[..k]).copied().collect()
}

/// Number of distinct undirected edges.
fn count_edges(triangles: &[[u32; 3]]) -> usize {
    let edges: HashSet<(u32, u32)> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect();
    edges.len()
}

fn diagonal(points: &[DVec3]) -> f64 {
    let lo = points.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    lo.distance(hi)
}

/// Exact nearest-neighbour queries: the points sorted by x, scanned outwards from the query's
/// x until the x gap alone exceeds the best distance found.
struct NearestByX<'a> {
    points: &'a [DVec3],
    order: Vec<usize>,
    xs: Vec<f64>,
}

impl<'a> NearestByX<'a> {
    fn new(points: &'a [DVec3]) -> Self {
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&i, &j| points[i].x.total_cmp(&points[j].x));
        let xs = order.iter().map(|&i| points[i].x).collect();
        Self { points, order, xs }
    }

    /// The index of the point nearest to `q`, and its distance.
    fn nearest(&self, q: DVec3) -> (usize, f64) {
        let start = self.xs.partition_point(|&x| x < q.x);
        let mut best = (usize::MAX, f64::INFINITY);
        for k in start..self.xs.len() {
            if self.xs[k] - q.x > best.1 {
                break;
            }
            let d = self.points[self.order[k]].distance(q);
            if d < best.1 {
                best = (self.order[k], d);
            }
        }
        for k in (0..start).rev() {
            if q.x - self.xs[k] > best.1 {
                break;
            }
            let d = self.points[self.order[k]].distance(q);
            if d < best.1 {
                best = (self.order[k], d);
            }
        }
        best
    }
}

/// Compares our output with a reference mesh as described in the module docs.
fn compare(ours: &PolyMesh, reference: &Obj) -> Result<(), String> {
    let counts = (ours.num_vertices(), ours.num_faces());
    let expected = (reference.positions.len(), reference.faces.len());
    if counts != expected {
        return Err(format!("(vertices, faces) = {counts:?}, the reference has {expected:?}"));
    }
    if let Some(i) = ours.positions.iter().position(|p| !p.is_finite()) {
        return Err(format!("our vertex {i} is at {}", ours.positions[i]));
    }

    // Vertices: nearest reference vertex, within the tolerance, one to one.
    let tol = MATCH_TOL * diagonal(&reference.positions);
    let index = NearestByX::new(&reference.positions);
    let mut map = Vec::with_capacity(ours.num_vertices());
    let mut worst = (0, 0, 0.0);
    for (i, &p) in ours.positions.iter().enumerate() {
        let (j, d) = index.nearest(p);
        if d > worst.2 {
            worst = (i, j, d);
        }
        map.push(j as u32);
    }
    let (i, j, d) = worst;
    if d > tol {
        let far = ours.positions.iter().zip(&map).filter(|&(&p, &j)| p.distance(reference.positions[j as usize]) > tol);
        return Err(format!(
            "{} vertices are farther than {tol:.1e} from every reference vertex; the worst, our vertex {i} at {}, is \
             {d:.3e} from reference vertex {j} at {}",
            far.count(),
            ours.positions[i],
            reference.positions[j]
        ));
    }
    let mut owner = vec![usize::MAX; reference.positions.len()];
    for (i, &j) in map.iter().enumerate() {
        if owner[j as usize] != usize::MAX {
            return Err(format!("our vertices {} and {i} both match reference vertex {j}", owner[j as usize]));
        }
        owner[j as usize] = i;
    }

    // Faces, renumbered into the reference's vertex numbers.
    let theirs: HashSet<Vec<u32>> = reference.faces.iter().map(|f| canonical(f)).collect();
    if theirs.len() != reference.faces.len() {
        return Err("the reference has duplicate faces".into());
    }
    let renumbered = |f: &[u32]| f.iter().map(|&v| map[v as usize]).collect::<Vec<u32>>();
    let mine: HashSet<Vec<u32>> = ours.faces().map(|f| canonical(&renumbered(f))).collect();
    if mine.len() != ours.num_faces() {
        return Err("our output has duplicate faces".into());
    }
    if mine != theirs {
        let extra: Vec<_> = mine.difference(&theirs).collect();
        let missing: Vec<_> = theirs.difference(&mine).collect();
        let reversed = |f: &Vec<u32>| canonical(&f.iter().rev().copied().collect::<Vec<u32>>());
        let flipped = extra.iter().filter(|f| theirs.contains(&reversed(f))).count();
        return Err(format!(
            "{} of our faces are not in the reference ({flipped} of them reversed), {} reference faces are \
             missing; in reference numbering, first extra {:?}, first missing {:?}",
            extra.len(),
            missing.len(),
            &extra[..extra.len().min(4)],
            &missing[..missing.len().min(4)]
        ));
    }
    Ok(())
}

/// Subdivides `<name>.in.obj` and compares with `<name>.<peer>.l<level>.obj` for each level up
/// to `max_level`, collecting every failure.
fn check(cases: &[(&str, u32)], peer: &str, opts: &LoopOptions, failures: &mut String) {
    for &(name, max_level) in cases {
        let mesh = input(name);
        for level in 1..=max_level {
            let what = format!("{name}.{peer}.l{level}");
            let result = loop_subdivide(&mesh, level, opts)
                .map_err(|e| format!("loop_subdivide failed: {e}"))
                .and_then(|ours| compare(&ours, &read_obj(&format!("{what}.obj"))));
            if let Err(e) = result {
                writeln!(failures, "{what}: {e}").unwrap();
            }
        }
    }
}

#[test]
fn loop_weights_match_opensubdiv() {
    let mut failures = String::new();
    check(&MESHES, "osd", &options(LoopWeights::Loop, BoundaryRule::Smooth), &mut failures);
    assert!(failures.is_empty(), "against OpenSubdiv (Loop's β, boundary EDGE_ONLY):\n{failures}");
}

#[test]
fn warren_weights_match_libigl() {
    let mut failures = String::new();
    check(&MESHES, "igl", &options(LoopWeights::Warren, BoundaryRule::Smooth), &mut failures);
    assert!(failures.is_empty(), "against libigl (Warren's β):\n{failures}");
}

/// The grid has two one-face corners, at (1, 0) and (0, 1); OpenSubdiv's
/// `VTX_BOUNDARY_EDGE_AND_CORNER` keeps them where they are.
#[test]
fn fixed_corners_match_opensubdiv_edge_and_corner() {
    let mut failures = String::new();
    check(&[("grid32", 2)], "osd-corners", &options(LoopWeights::Loop, BoundaryRule::Corners), &mut failures);
    assert!(failures.is_empty(), "against OpenSubdiv (Loop's β, boundary EDGE_AND_CORNER):\n{failures}");
}

/// Each level maps (V, E, F) to (V+E, 2E+3F, 4F), closed or not, so V−E+F is kept. Checked for
/// our output (levels 1 to 3) and for every reference file.
#[test]
fn counts_follow_v_plus_e_2e_plus_3f_4f() {
    for (name, max_level) in MESHES {
        let obj = read_obj(&format!("{name}.in.obj"));
        let mesh = PolyMesh::from_triangles(obj.positions.clone(), &obj.triangles);
        let mut expected = (obj.positions.len(), count_edges(&obj.triangles), obj.triangles.len());
        for level in 1..=3 {
            let (v, e, f) = expected;
            expected = (v + e, 2 * e + 3 * f, 4 * f);
            let ours = loop_subdivide(&mesh, level, &LoopOptions::default()).unwrap();
            let triangles = ours.triangles().expect("triangles");
            let counts = (ours.num_vertices(), count_edges(&triangles), triangles.len());
            assert_eq!(counts, expected, "{name} level {level}: (V, E, F) of our output");
            if level <= max_level {
                for peer in ["osd", "igl"] {
                    let r = read_obj(&format!("{name}.{peer}.l{level}.obj"));
                    let counts = (r.positions.len(), count_edges(&r.triangles), r.triangles.len());
                    assert_eq!(counts, expected, "{name}.{peer}.l{level}.obj: (V, E, F)");
                }
            }
        }
    }
    // SPEC §3.2: icosahedron level 1 has 42 vertices and 80 faces.
    let ours = loop_subdivide(&input("icosahedron20"), 1, &LoopOptions::default()).unwrap();
    assert_eq!((ours.num_vertices(), ours.num_faces()), (42, 80));
}

/// Catmull-Clark against OpenSubdiv's catmark scheme: each reference mesh at levels 1 and 2,
/// boundary `EDGE_ONLY` (crease rules everywhere) and, on the grid, `EDGE_AND_CORNER`.
#[test]
fn catmull_clark_matches_opensubdiv_catmark() {
    let mut failures = String::new();
    let cases = [
        ("cube6", "osd", BoundaryRule::Smooth),
        ("torus48", "osd", BoundaryRule::Smooth),
        ("prism8", "osd", BoundaryRule::Smooth),
        ("grid16", "osd", BoundaryRule::Smooth),
        ("grid16", "osd-corners", BoundaryRule::Corners),
    ];
    for (name, peer, boundary) in cases {
        let mesh = read_obj(&format!("catmark/{name}.in.obj")).to_poly();
        let options = CatmullClarkOptions { boundary, ..CatmullClarkOptions::default() };
        for level in 1..=2 {
            let what = format!("{name}.{peer}.l{level}");
            let result = catmull_clark_subdivide(&mesh, level, &options)
                .map_err(|e| format!("catmull_clark_subdivide failed: {e}"))
                .and_then(|ours| compare(&ours, &read_obj(&format!("catmark/{what}.obj"))));
            if let Err(e) = result {
                writeln!(failures, "{what}: {e}").unwrap();
            }
        }
    }
    assert!(failures.is_empty(), "against OpenSubdiv (catmark):\n{failures}");
}

/// Sharp and semi-sharp creases against OpenSubdiv (catmark and loop schemes): levels 1 to 3 of
/// each creased input (`tests/data/crease/`, from `bench/make_crease_references.sh`) with
/// Chaikin's creasing, two also with Uniform, two grids also with fixed corners, two tori with
/// four and five semi-sharp edges of different sharpness at one vertex; and the
/// creases the subdivision returns carry on: one level at a time gives the same mesh.
#[test]
fn creases_match_opensubdiv() {
    let mut failures = String::new();
    let (chaikin, uniform) = (CreasingMethod::Chaikin, CreasingMethod::Uniform);
    let (smooth, corners) = (BoundaryRule::Smooth, BoundaryRule::Corners);
    let cases = [
        ("cube6", "osd", chaikin, smooth, true),
        ("cube6", "osd-uniform", uniform, smooth, true),
        ("torus48", "osd", chaikin, smooth, true),
        ("prism8", "osd", chaikin, smooth, true),
        ("grid16", "osd", chaikin, smooth, true),
        ("grid16", "osd-corners", chaikin, corners, true),
        ("icosahedron20", "osd", chaikin, smooth, false),
        ("icosahedron20", "osd-uniform", uniform, smooth, false),
        ("grid32", "osd", chaikin, smooth, false),
        ("grid32", "osd-corners", chaikin, corners, false),
        ("torus96", "osd", chaikin, smooth, false),
        // issue #39: several semi-sharp edges of different sharpness at one vertex, whose
        // single-precision Chaikin sums follow OpenSubdiv's order of the vertex's edges
        ("torus48c4", "osd", chaikin, smooth, true),
        ("torus96c5", "osd", chaikin, smooth, false),
    ];
    for (name, peer, method, boundary, catmark) in cases {
        let obj = read_obj(&format!("crease/{name}.in.obj"));
        assert!(!obj.creases.is_empty(), "{name}: no creases read");
        let mesh = obj.to_poly();
        let subdivide = |m: &PolyMesh, levels: u32, creases: &Creases| {
            if catmark {
                let options = CatmullClarkOptions { boundary, ..CatmullClarkOptions::default() };
                catmull_clark_subdivide_creased(m, levels as usize, &options, creases, method)
            } else {
                let options = LoopOptions { boundary, ..LoopOptions::default() };
                loop_subdivide_creased(m, levels, &options, creases, method)
            }
        };
        let (mut stepped, mut creases) = (mesh.clone(), obj.creases.clone());
        for level in 1..=3 {
            let what = format!("{name}.{peer}.l{level}");
            let reference = read_obj(&format!("crease/{what}.obj"));
            let result = subdivide(&mesh, level, &obj.creases)
                .map_err(|e| format!("subdivision failed: {e}"))
                .and_then(|(ours, _)| compare(&ours, &reference).map(|()| relative_error(&ours, &reference)));
            match result {
                Ok(error) => println!("{what}: {error:.1e}"),
                Err(e) => writeln!(failures, "{what}: {e}").unwrap(),
            }
            // (Loop numbers a refined level's edges differently from a mesh read afresh: compare
            // as meshes, not vertex by vertex)
            let (next, next_creases) = subdivide(&stepped, 1, &creases).unwrap();
            if let Err(e) = compare(&next, &reference) {
                writeln!(failures, "{what}, one level at a time: {e}").unwrap();
            }
            (stepped, creases) = (next, next_creases);
        }
    }
    assert!(failures.is_empty(), "creases against OpenSubdiv:\n{failures}");
}

/// Limit positions and normals with creases against OpenSubdiv's `PrimvarRefinerReal::Limit`
/// of the finest level, after 1 and 2 levels of each creased input (so semi-sharp edges meet
/// the limit both still sharp and decayed): our finest level with its child creases, moved to
/// our limit positions, must be OpenSubdiv's; the normals must match too, except that at a
/// vertex inside the surface with a crease or corner OpenSubdiv may pick the other side (its
/// own ordering of the vertex's edges decides): there its normal must still be a normal of
/// the limit surface at that point — for a crease, at right angles to the crease, for a corner,
/// the normal of one of the faces around it.
#[test]
fn creased_limit_matches_opensubdiv() {
    let mut failures = String::new();
    let (smooth, corners) = (BoundaryRule::Smooth, BoundaryRule::Corners);
    let cases = [
        ("cube6", "osd", smooth, true),
        ("torus48", "osd", smooth, true),
        ("prism8", "osd", smooth, true),
        ("grid16", "osd", smooth, true),
        ("grid16", "osd-corners", corners, true),
        ("icosahedron20", "osd", smooth, false),
        ("grid32", "osd", smooth, false),
        ("grid32", "osd-corners", corners, false),
        ("torus96", "osd", smooth, false),
    ];
    let (mut exact, mut other_side) = (0usize, 0usize);
    for (name, peer, boundary, catmark) in cases {
        let obj = read_obj(&format!("crease/{name}.in.obj"));
        let mesh = obj.to_poly();
        for level in 1..=2 {
            let what = format!("{name}.{peer}.limit.l{level}");
            let reference = read_obj(&format!("crease/{what}.obj"));
            let method = CreasingMethod::Chaikin;
            let (mut fine, creases) = if catmark {
                let options = CatmullClarkOptions { boundary, ..CatmullClarkOptions::default() };
                catmull_clark_subdivide_creased(&mesh, level, &options, &obj.creases, method).unwrap()
            } else {
                let options = LoopOptions { boundary, ..LoopOptions::default() };
                loop_subdivide_creased(&mesh, level as u32, &options, &obj.creases, method).unwrap()
            };
            let (positions, normals) = if catmark {
                let options = CatmullClarkOptions { boundary, ..CatmullClarkOptions::default() };
                catmull_clark_limit_creased(&fine, &options, &creases).unwrap()
            } else {
                let options = LoopOptions { boundary, ..LoopOptions::default() };
                loop_limit_creased(&fine, &options, &creases).unwrap()
            };
            let unmoved = fine.positions.clone();
            fine.positions = positions;
            if let Err(e) = compare(&fine, &reference) {
                writeln!(failures, "{what}: {e}").unwrap();
                continue;
            }
            assert_eq!(reference.normals.len(), reference.positions.len(), "{what}: one vn per v");
            let near = NearestByX::new(&reference.positions);
            // the edges and faces around each vertex, and which edges are sharp
            let sharp: HashSet<(u32, u32)> =
                creases.edges.iter().filter(|e| e.sharpness > 0.0).map(|e| (e.a.min(e.b), e.a.max(e.b))).collect();
            let mut around: Vec<Vec<(u32, u32)>> = vec![Vec::new(); fine.num_vertices()];
            let mut edge_faces = std::collections::HashMap::<(u32, u32), usize>::new();
            for f in 0..fine.num_faces() {
                let face = fine.face(f);
                for (j, &v) in face.iter().enumerate() {
                    let (prev, next) = (face[(j + face.len() - 1) % face.len()], face[(j + 1) % face.len()]);
                    around[v as usize].push((next, prev));
                    *edge_faces.entry((v.min(next), v.max(next))).or_default() += 1;
                }
            }
            for (v, (p, n)) in fine.positions.iter().zip(&normals).enumerate() {
                let r = reference.normals[near.nearest(*p).0];
                if n.distance(r) <= NORMAL_TOL {
                    exact += 1;
                    continue;
                }
                let boundary_vertex = around[v]
                    .iter()
                    .any(|&(next, _)| edge_faces[&(v.min(next as usize) as u32, v.max(next as usize) as u32)] == 1);
                let ends: Vec<u32> = around[v]
                    .iter()
                    .map(|&(next, _)| next)
                    .filter(|&q| sharp.contains(&((v as u32).min(q), (v as u32).max(q))))
                    .collect();
                let vertex_sharp = creases.vertices.iter().any(|c| c.vertex as usize == v && c.sharpness > 0.0);
                let at = unmoved[v];
                let ok = if boundary_vertex {
                    false
                } else if vertex_sharp || ends.len() >= 3 {
                    around[v].iter().any(|&(next, prev)| {
                        let face = (unmoved[next as usize] - at).cross(unmoved[prev as usize] - at).normalize();
                        face.distance(r) <= 1e-9
                    })
                } else if ends.len() == 2 {
                    let along = (unmoved[ends[0] as usize] - unmoved[ends[1] as usize]).normalize();
                    (r.length() - 1.0).abs() <= 1e-9 && r.dot(along).abs() <= 1e-9
                } else {
                    false
                };
                if ok {
                    other_side += 1;
                } else {
                    writeln!(failures, "{what}: our limit normal at vertex {v} is {n}, OpenSubdiv's {r}").unwrap();
                    break;
                }
            }
        }
    }
    println!("creased limit normals: {exact} as OpenSubdiv's, {other_side} on the other side of a crease or corner");
    assert!(failures.is_empty(), "creased limit against OpenSubdiv:\n{failures}");
}

/// The largest distance from a vertex of `ours` to the nearest vertex of `reference`, as a
/// fraction of the reference's bounding-box diagonal (what [`compare`] bounds by [`MATCH_TOL`]).
fn relative_error(ours: &PolyMesh, reference: &Obj) -> f64 {
    let index = NearestByX::new(&reference.positions);
    let worst = ours.positions.iter().map(|&p| index.nearest(p).1).fold(0.0, f64::max);
    worst / diagonal(&reference.positions)
}

/// Catmull-Clark with OpenSubdiv's `TRI_SUB_SMOOTH` (issue #39): levels 1 to 3 of meshes with
/// triangles among quads and pentagons (a closed prism, an open grid, also with fixed corners),
/// of all triangles (the icosahedron), with creases (Chaikin and Uniform) and non-manifold
/// (cubes with a triangle fin), in one call and one level at a time; and the plain rule is
/// far from these references, so the comparison would notice a missing option.
#[test]
fn smooth_triangles_match_opensubdiv() {
    let smooth = CatmullClarkOptions { triangles: TriangleSubdivision::Smooth, ..CatmullClarkOptions::default() };
    let corners = CatmullClarkOptions { boundary: BoundaryRule::Corners, ..smooth };
    let (chaikin, uniform) = (CreasingMethod::Chaikin, CreasingMethod::Uniform);
    let cases = [
        ("prism8", "osd-smooth", smooth, chaikin),
        ("gridmix", "osd-smooth", smooth, chaikin),
        ("gridmix", "osd-smooth-corners", corners, chaikin),
        ("icosahedron20", "osd-smooth", smooth, chaikin),
        ("prism8creased", "osd-smooth", smooth, chaikin),
        ("prism8creased", "osd-smooth-uniform", smooth, uniform),
        ("fins3", "osd-smooth", smooth, chaikin),
    ];
    let mut failures = String::new();
    for (name, tag, options, method) in cases {
        let obj = read_obj(&format!("options/{name}.in.obj"));
        let mesh = obj.to_poly();
        let subdivide = |m: &PolyMesh, levels: usize, creases: &Creases| {
            catmull_clark_subdivide_creased(m, levels, &options, creases, method).map_err(|e| e.to_string())
        };
        let (mut stepped, mut creases) = (mesh.clone(), obj.creases.clone());
        for level in 1..=3 {
            let what = format!("{name}.{tag}.l{level}");
            let reference = read_obj(&format!("options/{what}.obj"));
            let plain = catmull_clark_subdivide(&mesh, level, &options).map_err(|e| e.to_string());
            let creased = subdivide(&mesh, level, &obj.creases).map(|(m, _)| m);
            for (how, ours) in
                [("", if obj.creases.is_empty() { plain } else { creased.clone() }), (" creased", creased)]
            {
                match ours.and_then(|ours| compare(&ours, &reference).map(|()| relative_error(&ours, &reference))) {
                    Ok(error) => println!("{what}{how}: {error:.1e}"),
                    Err(e) => writeln!(failures, "{what}{how}: {e}").unwrap(),
                }
            }
            let (next, next_creases) = subdivide(&stepped, 1, &creases).unwrap();
            if let Err(e) = compare(&next, &reference) {
                writeln!(failures, "{what}, one level at a time: {e}").unwrap();
            }
            (stepped, creases) = (next, next_creases);
        }
        if obj.creases.is_empty() {
            let step = catmull_clark_step(&mesh, 1, &options).unwrap();
            if let Err(e) = compare(&step, &read_obj(&format!("options/{name}.{tag}.l1.obj"))) {
                writeln!(failures, "{name}.{tag}.l1, catmull_clark_step: {e}").unwrap();
            }
        }
        let catmark = CatmullClarkOptions { triangles: TriangleSubdivision::Catmark, ..options };
        let plain = catmull_clark_subdivide_creased(&mesh, 1, &catmark, &obj.creases, method).unwrap().0;
        let error = relative_error(&plain, &read_obj(&format!("options/{name}.{tag}.l1.obj")));
        assert!(error > 1e-3, "{name}: Catmull-Clark's own rule is within {error:.1e} of TRI_SUB_SMOOTH's");
    }
    assert!(failures.is_empty(), "TRI_SUB_SMOOTH against OpenSubdiv:\n{failures}");
}

/// Bilinear subdivision against OpenSubdiv's `SCHEME_BILINEAR` (issue #39): levels 1 to 3 of
/// the cube, the prism of triangles, quads and pentagons, the open grid of triangles, quads and
/// a pentagon, and cubes sharing an edge and a vertex with a triangle fin (non-manifold).
#[test]
fn bilinear_matches_opensubdiv() {
    let mut failures = String::new();
    for name in ["cube6", "prism8", "gridmix", "cubes"] {
        let mesh = read_obj(&format!("options/{name}.in.obj")).to_poly();
        for level in 1..=3 {
            let what = format!("{name}.osd-bilinear.l{level}");
            let reference = read_obj(&format!("options/{what}.obj"));
            let ours = bilinear_subdivide(&mesh, level, &BilinearOptions::default()).map_err(|e| e.to_string());
            match ours.and_then(|ours| compare(&ours, &reference).map(|()| relative_error(&ours, &reference))) {
                Ok(error) => println!("{what}: {error:.1e}"),
                Err(e) => writeln!(failures, "{what}: {e}").unwrap(),
            }
        }
    }
    assert!(failures.is_empty(), "bilinear against OpenSubdiv:\n{failures}");
}

/// OpenSubdiv's `VTX_BOUNDARY_NONE` (issue #39): the surface of edge-only boundaries with the
/// faces at the boundary left out — Catmull-Clark on the open grid of quads, triangles and a
/// pentagon with an infinitely sharp crease along one side (its faces stay), Loop on an open
/// grid — levels 1 to 3.
#[test]
fn boundary_none_leaves_the_same_holes_as_opensubdiv() {
    let mut failures = String::new();
    for (name, reference, split) in
        [("holes", "holes.osd", HoleSplit::Quads), ("grid32", "grid32.osd-none", HoleSplit::Triangles)]
    {
        let obj = read_obj(&format!("options/{name}.in.obj"));
        let mesh = obj.to_poly();
        let holes = boundary_holes(&mesh, &obj.creases);
        assert!(holes.iter().any(|&h| h) && !holes.iter().all(|&h| h), "{name}: {holes:?}");
        for level in 1..=3 {
            let what = format!("{reference}.l{level}");
            let mut fine = match split {
                HoleSplit::Quads => {
                    let options = CatmullClarkOptions::default();
                    catmull_clark_subdivide_creased(&mesh, level, &options, &obj.creases, CreasingMethod::Chaikin)
                        .unwrap()
                        .0
                }
                HoleSplit::Triangles => loop_subdivide(&mesh, level as u32, &LoopOptions::default()).unwrap(),
            };
            remove_holes(&mut fine, &mesh, level, split, &holes);
            let reference = read_obj(&format!("options/{what}.obj"));
            // the vertices of the holes stay: compare them as a point set, and the faces left
            let kept = PolyMesh { face_offsets: vec![0], face_vertices: Vec::new(), ..fine.clone() };
            let result = compare(&kept, &Obj { faces: Vec::new(), ..read_obj(&format!("options/{what}.obj")) })
                .and_then(|()| faces_match(&fine, &reference));
            match result {
                Ok(()) => println!("{what}: {:.1e}", relative_error(&fine, &reference)),
                Err(e) => writeln!(failures, "{what}: {e}").unwrap(),
            }
        }
    }
    assert!(failures.is_empty(), "VTX_BOUNDARY_NONE against OpenSubdiv:\n{failures}");
}

/// Whether the faces of `ours`, its vertices matched to the nearest of `reference`'s, are
/// `reference`'s faces (same orientation, up to rotation).
fn faces_match(ours: &PolyMesh, reference: &Obj) -> Result<(), String> {
    let index = NearestByX::new(&reference.positions);
    let map: Vec<u32> = ours.positions.iter().map(|&p| index.nearest(p).0 as u32).collect();
    let mine: HashSet<Vec<u32>> =
        ours.faces().map(|f| canonical(&f.iter().map(|&v| map[v as usize]).collect::<Vec<u32>>())).collect();
    let theirs: HashSet<Vec<u32>> = reference.faces.iter().map(|f| canonical(f)).collect();
    if mine == theirs && mine.len() == ours.num_faces() {
        Ok(())
    } else {
        Err(format!(
            "{} faces, the reference has {}; {} in common",
            ours.num_faces(),
            theirs.len(),
            mine.intersection(&theirs).count()
        ))
    }
}

/// Levels 1 to `max` of each `(input, max)` case (`tests/data/{input}.in.obj`) made by
/// `subdivide`, each compared with `{peer}/{name}.{tag}.l{level}.obj`: the failures, a line each.
fn check_levels(
    cases: &[(&str, usize)],
    peer: &str,
    tag: &str,
    subdivide: impl Fn(&PolyMesh, usize) -> Result<PolyMesh, String>,
) -> String {
    let mut failures = String::new();
    for &(input, max_level) in cases {
        let mesh = read_obj(&format!("{input}.in.obj")).to_poly();
        let name = input.rsplit('/').next().unwrap();
        for level in 1..=max_level {
            let what = format!("{name}.{tag}.l{level}");
            let result =
                subdivide(&mesh, level).and_then(|ours| compare(&ours, &read_obj(&format!("{peer}/{what}.obj"))));
            if let Err(e) = result {
                writeln!(failures, "{what}: {e}").unwrap();
            }
        }
    }
    failures
}

/// √3 against CGAL's `Sqrt3_subdivision`: levels 1 to 3 of one call, so the boundary meshes
/// meet the boundary rule of level 2 and the level after it.
#[test]
fn sqrt3_matches_cgal() {
    let cases = [("cgal/tetra4", 3), ("cgal/icosahedron20", 3), ("cgal/trigrid18", 3), ("cgal/icoopen15", 3)];
    let failures = check_levels(&cases, "cgal", "cgal-sqrt3", |mesh, level| {
        sqrt3_subdivide(mesh, level, &Sqrt3Options::default()).map_err(|e| format!("sqrt3_subdivide failed: {e}"))
    });
    assert!(failures.is_empty(), "against CGAL (Sqrt3_subdivision):\n{failures}");
}

/// Doo-Sabin against CGAL's `DooSabin_subdivision`, closed and open meshes of triangles, quads
/// and pentagons.
#[test]
fn doo_sabin_matches_cgal() {
    let cases = [
        ("catmark/cube6", 3),
        ("catmark/prism8", 2),
        ("cgal/icosahedron20", 2),
        ("catmark/grid16", 2),
        ("cgal/trigrid18", 2),
    ];
    let failures = check_levels(&cases, "cgal", "cgal-doosabin", |mesh, level| {
        doo_sabin_subdivide(mesh, level, &DooSabinOptions::default())
            .map_err(|e| format!("doo_sabin_subdivide failed: {e}"))
    });
    assert!(failures.is_empty(), "against CGAL (DooSabin_subdivision):\n{failures}");
}

/// Modified butterfly against OpenMesh's `ModifiedButterflyT`: levels 1 to 3 on closed meshes
/// whose vertices have valence 3, 4, 5 and 7 (Zorin's irregular masks, then the regular
/// butterfly next to them), on two open meshes (the four-point rule, reflected wings, boundary
/// ends), and level 1 of the bunny's base mesh (four holes, valences 3 to 11).
#[test]
fn butterfly_matches_openmesh() {
    let cases = [
        ("cgal/tetra4", 3),
        ("openmesh/octahedron8", 3),
        ("openmesh/bipyramid14", 3),
        ("cgal/icosahedron20", 3),
        ("cgal/trigrid18", 3),
        ("cgal/icoopen15", 3),
        ("loop/bunnybase883", 1),
    ];
    let failures = check_levels(&cases, "openmesh", "openmesh-butterfly", |mesh, level| {
        butterfly_subdivide(mesh, level, &ButterflyOptions::default())
            .map_err(|e| format!("butterfly_subdivide failed: {e}"))
    });
    assert!(failures.is_empty(), "against OpenMesh (ModifiedButterflyT):\n{failures}");
}

/// Limit positions against OpenSubdiv's `PrimvarRefinerReal::Limit` after one level of Loop
/// or Catmull-Clark (both boundary options), compared like the refined meshes: our level-1
/// faces carrying our limit positions.
#[test]
fn limit_positions_and_normals_match_opensubdiv() {
    let mut failures = String::new();
    // ours: the level-1 mesh carrying our limit positions, and our limit normals
    let mut check = |what: String, result: Result<(PolyMesh, Vec<DVec3>), String>| {
        let reference = read_obj(&format!("limit/{what}.obj"));
        let result = result.and_then(|(ours, normals)| {
            compare(&ours, &reference)?;
            // the positions matched one to one: compare the normals of matched vertices
            assert_eq!(reference.normals.len(), reference.positions.len(), "{what}: one vn per v");
            let near = NearestByX::new(&reference.positions);
            let (mut worst, mut at) = (0.0f64, 0);
            for (i, (p, n)) in ours.positions.iter().zip(&normals).enumerate() {
                let err = n.distance(reference.normals[near.nearest(*p).0]);
                if !(err <= worst) {
                    (worst, at) = (err, i);
                }
            }
            if worst > NORMAL_TOL {
                let r = reference.normals[near.nearest(ours.positions[at]).0];
                return Err(format!(
                    "our limit normal at vertex {at} is {}, OpenSubdiv's {r} ({worst:.1e} apart)",
                    normals[at]
                ));
            }
            Ok(())
        });
        if let Err(e) = result {
            writeln!(failures, "{what}: {e}").unwrap();
        }
    };
    for (name, peer, boundary) in [
        ("icosahedron20", "osd-loop", BoundaryRule::Smooth),
        ("torus96", "osd-loop", BoundaryRule::Smooth),
        ("grid32", "osd-loop", BoundaryRule::Smooth),
        ("grid32", "osd-loop-corners", BoundaryRule::Corners),
        ("bunnybase883", "osd-loop", BoundaryRule::Smooth),
    ] {
        let options = LoopOptions { boundary, ..LoopOptions::default() };
        let result = loop_subdivide(&input(name), 1, &options).map_err(|e| e.to_string()).and_then(|mut fine| {
            let normals = loop_limit_normals(&fine, &options).map_err(|e| e.to_string())?;
            fine.positions = loop_limit_positions(&fine, &options).map_err(|e| e.to_string())?;
            Ok((fine, normals))
        });
        check(format!("{name}.{peer}.l1"), result);
    }
    for (input, peer, boundary) in [
        ("catmark/cube6", "osd-catmark", BoundaryRule::Smooth),
        ("catmark/torus48", "osd-catmark", BoundaryRule::Smooth),
        ("catmark/prism8", "osd-catmark", BoundaryRule::Smooth),
        ("catmark/grid16", "osd-catmark", BoundaryRule::Smooth),
        ("catmark/grid16", "osd-catmark-corners", BoundaryRule::Corners),
        ("cgal/icoopen15", "osd-catmark", BoundaryRule::Smooth),
    ] {
        let options = CatmullClarkOptions { boundary, ..CatmullClarkOptions::default() };
        let mesh = read_obj(&format!("{input}.in.obj")).to_poly();
        let result = catmull_clark_subdivide(&mesh, 1, &options).map_err(|e| e.to_string()).and_then(|mut fine| {
            let normals = catmull_clark_limit_normals(&fine, &options).map_err(|e| e.to_string())?;
            fine.positions = catmull_clark_limit_positions(&fine, &options).map_err(|e| e.to_string())?;
            Ok((fine, normals))
        });
        let name = input.rsplit('/').next().unwrap();
        check(format!("{name}.{peer}.l1"), result);
    }
    assert!(failures.is_empty(), "limit positions and normals against OpenSubdiv:\n{failures}");
}

/// The comparison itself must notice a moved vertex and a reversed triangle.
#[test]
fn the_comparison_notices_a_moved_vertex_and_a_reversed_triangle() {
    let reference = read_obj("torus96.osd.l1.obj");
    let exact = PolyMesh::from_triangles(reference.positions.clone(), &reference.triangles);
    assert_eq!(compare(&exact, &reference), Ok(()));

    let mut moved = reference.positions.clone();
    moved[7].z += 1e-9;
    let err = compare(&PolyMesh::from_triangles(moved, &reference.triangles), &reference).unwrap_err();
    assert!(err.contains("1 vertices are farther"), "{err}");

    let mut triangles = reference.triangles.clone();
    triangles[5].swap(1, 2);
    let err = compare(&PolyMesh::from_triangles(reference.positions.clone(), &triangles), &reference).unwrap_err();
    assert!(err.contains("(1 of them reversed)"), "{err}");
}
