//! Helpers shared by the integration tests and the benches (which include this file with
//! `#[path]`): a fixed random stream of cubics, and a measured two-sided Hausdorff distance.
#![allow(dead_code)]

use glam::{DVec2, DVec3};
use splinekit::{CubicBezier, PolyMesh};

/// splitmix64 in `[0, scale)`: a fixed, dependency-free random stream, so every run sees the
/// same curves.
pub fn splitmix(state: &mut u64, scale: f64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 * scale
}

/// The next random 2D cubic of the stream, control points in `[0, scale)²`.
pub fn random_cubic(state: &mut u64, scale: f64) -> CubicBezier<DVec2> {
    let mut p = || DVec2::new(splitmix(state, scale), splitmix(state, scale));
    CubicBezier::new(p(), p(), p(), p())
}

/// `n` random cubics in `[0, 100]²` from `seed` (the benches use seed `0x5EED`).
pub fn random_cubics(seed: u64, n: usize) -> Vec<CubicBezier<DVec2>> {
    let mut state = seed;
    (0..n).map(|_| random_cubic(&mut state, 100.0)).collect()
}

fn seg_dist_sq(x: DVec3, a: DVec3, b: DVec3) -> f64 {
    let e = b - a;
    let l2 = e.length_squared();
    let s = if l2 > 0.0 { ((x - a).dot(e) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (a + e * s).distance_squared(x)
}

const BLOCK: usize = 32;

/// A polyline cut into blocks of segments with bounding boxes, for exact nearest-distance
/// queries that skip blocks farther away than the best distance found so far.
pub struct Blocked<'a> {
    points: &'a [DVec3],
    boxes: Vec<(usize, DVec3, DVec3)>,
}

impl<'a> Blocked<'a> {
    /// Blocks of the polyline through `points`.
    pub fn new(points: &'a [DVec3]) -> Self {
        let boxes = (0..points.len().saturating_sub(1))
            .step_by(BLOCK)
            .map(|start| {
                let pts = &points[start..=(start + BLOCK).min(points.len() - 1)];
                let lo = pts.iter().fold(pts[0], |a, &b| a.min(b));
                let hi = pts.iter().fold(pts[0], |a, &b| a.max(b));
                (start, lo, hi)
            })
            .collect();
        Self { points, boxes }
    }

    /// Exact distance from `x` to the polyline.
    pub fn dist(&self, x: DVec3) -> f64 {
        let mut order: Vec<(f64, usize)> =
            self.boxes.iter().map(|&(start, lo, hi)| ((x - x.clamp(lo, hi)).length_squared(), start)).collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best = f64::INFINITY;
        for (box_d2, start) in order {
            if box_d2 >= best {
                break;
            }
            for i in start..(start + BLOCK).min(self.points.len() - 1) {
                best = best.min(seg_dist_sq(x, self.points[i], self.points[i + 1]));
            }
        }
        best.sqrt()
    }
}

/// A lower bound of the two-sided Hausdorff distance between a curve, sampled densely as
/// `dense` (consecutive samples within `sagitta` of the curve between them), and the
/// polyline `poly`: curve → polyline exactly at the samples, and polyline → curve at
/// `divisions − 1` interior points of every chord, less `sagitta`.
pub fn hausdorff_lower_bound(dense: &[DVec3], poly: &[DVec3], sagitta: f64, divisions: usize) -> f64 {
    let blocked_poly = Blocked::new(poly);
    let mut h = dense.iter().map(|&p| blocked_poly.dist(p)).fold(0.0, f64::max);
    let blocked_dense = Blocked::new(dense);
    for w in poly.windows(2) {
        for j in 1..divisions {
            let x = w[0].lerp(w[1], j as f64 / divisions as f64);
            h = h.max(blocked_dense.dist(x) - sagitta);
        }
    }
    h
}

/// The icosahedron of the course's `icosahedron.obj` (J. Burkardt), outward.
pub fn icosahedron() -> PolyMesh {
    let phi = f64::midpoint(1.0, 5f64.sqrt());
    let p = [
        (-1.0, phi, 0.0),
        (1.0, phi, 0.0),
        (-1.0, -phi, 0.0),
        (1.0, -phi, 0.0),
        (0.0, -1.0, phi),
        (0.0, 1.0, phi),
        (0.0, -1.0, -phi),
        (0.0, 1.0, -phi),
        (phi, 0.0, -1.0),
        (phi, 0.0, 1.0),
        (-phi, 0.0, -1.0),
        (-phi, 0.0, 1.0),
    ];
    let t = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    PolyMesh::from_triangles(p.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect(), &t)
}

/// A polygon mesh from positions and faces (lists of vertex indices).
pub fn poly(positions: Vec<DVec3>, faces: &[&[u32]]) -> PolyMesh {
    let mut face_offsets = vec![0];
    let mut face_vertices = Vec::new();
    for f in faces {
        face_vertices.extend_from_slice(f);
        face_offsets.push(face_vertices.len() as u32);
    }
    PolyMesh { positions, face_offsets, face_vertices, ..PolyMesh::default() }
}

/// The cube `[−1, 1]³`, faces counter-clockwise from outside.
pub fn cube() -> PolyMesh {
    let p = (0..8).map(|i| {
        DVec3::new(f64::from(i & 1) * 2.0 - 1.0, f64::from((i >> 1) & 1) * 2.0 - 1.0, f64::from(i >> 2) * 2.0 - 1.0)
    });
    poly(p.collect(), &[&[0, 2, 3, 1], &[4, 5, 7, 6], &[0, 1, 5, 4], &[2, 6, 7, 3], &[0, 4, 6, 2], &[1, 3, 7, 5]])
}

/// A closed mesh of triangles, quads and pentagons: a pentagonal prism with one side quad
/// split into two triangles.
pub fn prism() -> PolyMesh {
    let mut p = Vec::new();
    for z in [0.0, 1.3] {
        for k in 0..5 {
            let a = std::f64::consts::TAU * f64::from(k) / 5.0 + 0.1;
            p.push(DVec3::new(a.cos(), a.sin(), z + 0.1 * f64::from(k)));
        }
    }
    poly(
        p,
        &[
            &[4, 3, 2, 1, 0],
            &[5, 6, 7, 8, 9],
            &[0, 1, 6, 5],
            &[1, 2, 7],
            &[1, 7, 6],
            &[2, 3, 8, 7],
            &[3, 4, 9, 8],
            &[4, 0, 5, 9],
        ],
    )
}

/// The positions and faces of `tests/data/{file}` (an OBJ file: `v x y z` and `f a b c …`
/// lines, 1-based; everything else skipped).
pub fn read_obj(file: &str) -> PolyMesh {
    let path = format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {path}: {e}"));
    let mut mesh = PolyMesh::default();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words.map(|w| w.parse().unwrap()).collect();
                mesh.positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                mesh.face_vertices.extend(words.map(|w| w.parse::<u32>().unwrap() - 1));
                mesh.face_offsets.push(mesh.face_vertices.len() as u32);
            }
            _ => {}
        }
    }
    mesh
}
