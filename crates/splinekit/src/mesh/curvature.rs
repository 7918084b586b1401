//! Discrete curvature of a triangle mesh at its vertices: [`vertex_curvature`].
//!
//! # Method
//!
//! The operators of Meyer, Desbrun, Schröder and Barr, *Discrete Differential-Geometry
//! Operators for Triangulated 2-Manifolds* (Visualization and Mathematics III, 2003,
//! <https://doi.org/10.1007/978-3-662-05105-4_2>), each an average over the vertex's *mixed
//! area* `A`:
//!
//! - **Mixed area.** Per triangle: a triangle with no obtuse angle gives each corner its
//!   Voronoi part, `(|xᵢ − xⱼ|²·cot θₖ + |xᵢ − xₖ|²·cot θⱼ)/8`; an obtuse one gives half its
//!   area to the obtuse corner and a quarter to each other. The areas of all vertices sum to
//!   the mesh's area.
//! - **Mean curvature** `H`, from the mean-curvature normal (the cotangent Laplacian)
//!   `K(xᵢ) = 1/(2A) · Σⱼ (cot αᵢⱼ + cot βᵢⱼ)·(xᵢ − xⱼ) = 2H·n`, with `αᵢⱼ`, `βᵢⱼ` the angles
//!   opposite the edge `i–j`. `H = ½·K(xᵢ)·n̂` with `n̂` the unit area-weighted vertex normal:
//!   the sign is taken against the vertex normal, so a sphere of radius `r` whose triangles are
//!   counter-clockwise seen from outside has `H = +1/r` (and `−1/r` turned inside out). The
//!   projection also drops the tangential part that `K(xᵢ)` picks up on an irregular mesh.
//! - **Gaussian curvature** `K = (2π − Σθ)/A`, the angle defect over the mixed area. Summed
//!   with the areas over a closed mesh, `Σ K·A = 2π·χ` exactly (Gauss–Bonnet), up to rounding.
//!
//! # Seams, boundaries and degenerate triangles
//!
//! - **Seams.** Vertices at the same position — within [`WELD_TOLERANCE`] times the diagonal
//!   of the mesh's bounding box, as a seam computed twice is (the copy at 2π of a revolution
//!   swept with UVs lies some 1e-16 off the copy at 0) — are taken as one vertex, and every
//!   copy gets its values: a UV seam or a crease kept as two rows of vertices (see
//!   [`sweep`](crate::sweep)), or poles repeated in every copy, are measured across, not as
//!   a boundary.
//! - **Boundary vertices** (on an edge that only one triangle uses, after welding) have
//!   neither an angle sum nor a Laplacian that means anything, and so do vertices with no
//!   area (all their triangles degenerate, or none): each gets the average of the values of
//!   its neighbours (along edges) that are interior vertices with area, or 0 if it has none.
//!   A flat piece of plane is then 0 everywhere (to rounding, inside).
//! - **Degenerate triangles**, with twice their area at most `f64::EPSILON` times their
//!   longest edge squared, add no area and no Laplacian weight (their cotangents are
//!   infinite), but their angles (0 and π) still count in the angle sums, which keeps
//!   Gauss–Bonnet. Triangles with two corners at one position, or a corner out of range or
//!   not finite, are left out. No value is ever NaN or infinite.
//!
//! Cost: linear in the triangles, plus a sort of the edges (`O(F log F)`); no adjacency
//! structure is needed.

use std::collections::HashMap;
use std::f64::consts::TAU;

use glam::DVec3;
use rayon::slice::ParallelSliceMut;

use super::TriMesh;

/// Vertices closer than this times the diagonal of the mesh's bounding box are one vertex
/// for [`vertex_curvature`] (the sweeps' pole tolerance,
/// [`DEFAULT_POLE_TOLERANCE`](crate::sweep::surface::DEFAULT_POLE_TOLERANCE), is the same).
pub const WELD_TOLERANCE: f64 = 1e-9;

/// Curvature per vertex of a [`TriMesh`] (see [`vertex_curvature`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VertexCurvature {
    /// Mean curvature `H` (1/length) per vertex: the mean of the principal curvatures,
    /// positive where the surface bends away from its normal (`1/r` on a sphere of radius `r`
    /// with outward normals).
    pub mean: Vec<f64>,
    /// Gaussian curvature `K` (1/length²) per vertex: the product of the principal
    /// curvatures (`1/r²` on a sphere, negative at saddles).
    pub gauss: Vec<f64>,
    /// The mixed area of each vertex, shared by copies at one position (so that summing it
    /// over the distinct positions gives the mesh's area, without degenerate triangles).
    pub area: Vec<f64>,
}

/// Mean and Gaussian curvature at every vertex of `mesh`, by the cotangent Laplacian and the
/// angle defect over mixed Voronoi areas. See the [module docs](self) for the method and
/// what seams, boundaries and degenerate triangles get.
///
/// Accuracy: on a mesh sampled from a smooth surface with near-regular triangles of size `h`,
/// both converge to the surface's values as `h → 0` (on the test spheres and tori the error
/// falls about as `h²`); on irregular meshes the mean curvature converges only on average.
///
/// # Usage
/// ```
/// use glam::DVec3;
/// use splinekit::TriMesh;
/// use splinekit::mesh::vertex_curvature;
/// // An octahedron of radius 1: each corner has four 60° angles, a defect of 2π/3.
/// let positions = vec![DVec3::X, DVec3::Y, DVec3::Z, -DVec3::X, -DVec3::Y, -DVec3::Z];
/// let triangles = vec![[0, 1, 2], [1, 3, 2], [3, 4, 2], [4, 0, 2], [1, 0, 5], [3, 1, 5], [4, 3, 5], [0, 4, 5]];
/// let c = vertex_curvature(&TriMesh { positions, triangles, ..TriMesh::default() });
/// let total: f64 = c.gauss.iter().zip(&c.area).map(|(k, a)| k * a).sum();
/// assert!((total - 4.0 * std::f64::consts::PI).abs() < 1e-12); // Gauss–Bonnet, χ = 2
/// assert!(c.mean.iter().all(|&h| h > 0.0)); // convex, outward
/// ```
#[must_use]
pub fn vertex_curvature(mesh: &TriMesh) -> VertexCurvature {
    let (weld, points) = weld_by_position(&mesh.positions);
    let m = points.len();
    let n = mesh.positions.len();
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter(|t| t.iter().all(|&i| (i as usize) < n))
        .map(|t| t.map(|i| weld[i as usize]))
        .filter(|w| w[0] != w[1] && w[1] != w[2] && w[2] != w[0] && w.iter().all(|&i| points[i as usize].is_finite()))
        .collect();

    let mut angles = vec![0.0; m];
    let mut area = vec![0.0; m];
    let mut laplacian = vec![DVec3::ZERO; m];
    let mut normal = vec![DVec3::ZERO; m];
    for t in &triangles {
        let p = t.map(|i| points[i as usize]);
        let cross = (p[1] - p[0]).cross(p[2] - p[0]);
        let twice_area = cross.length();
        let mut cot = [0.0; 3];
        let mut longest2: f64 = 0.0;
        for k in 0..3 {
            let (u, v) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            let d = u.dot(v);
            // |u × v| is twice the area at every corner.
            angles[t[k] as usize] += twice_area.atan2(d);
            cot[k] = d / twice_area;
            longest2 = longest2.max(u.length_squared());
        }
        if !(twice_area > f64::EPSILON * longest2) {
            continue;
        }
        for &v in t {
            normal[v as usize] += cross;
        }
        let half = 0.5 * twice_area;
        let obtuse = (0..3).find(|&k| cot[k] < 0.0);
        for k in 0..3 {
            // The edge i–j opposite corner k.
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let d = p[i] - p[j];
            laplacian[t[i] as usize] += cot[k] * d;
            laplacian[t[j] as usize] -= cot[k] * d;
            match obtuse {
                None => {
                    let voronoi = d.length_squared() * cot[k] / 8.0;
                    area[t[i] as usize] += voronoi;
                    area[t[j] as usize] += voronoi;
                }
                Some(o) => area[t[k] as usize] += if o == k { half / 2.0 } else { half / 4.0 },
            }
        }
    }

    // Undirected edges, sorted: an edge that appears once is on the boundary.
    let mut edges: Vec<u64> =
        triangles.iter().flat_map(|t| (0..3).map(move |k| edge_key(t[k], t[(k + 1) % 3]))).collect();
    edges.par_sort_unstable();
    let mut boundary = vec![false; m];
    let mut unique = Vec::with_capacity(edges.len() / 2 + 1);
    for run in edges.chunk_by(|a, b| a == b) {
        let (a, b) = split_key(run[0]);
        if run.len() == 1 {
            boundary[a] = true;
            boundary[b] = true;
        }
        unique.push((a, b));
    }

    let own: Vec<bool> = (0..m).map(|v| !boundary[v] && area[v] > 0.0).collect();
    let mut mean = vec![0.0; m];
    let mut gauss = vec![0.0; m];
    for v in (0..m).filter(|&v| own[v]) {
        let h = 0.5 * laplacian[v].dot(normal[v].normalize_or_zero()) / (2.0 * area[v]);
        let k = (TAU - angles[v]) / area[v];
        // (Finite by construction; kept total should an area be subnormal.)
        mean[v] = if h.is_finite() { h } else { 0.0 };
        gauss[v] = if k.is_finite() { k } else { 0.0 };
    }
    // The others: the average of their own-valued neighbours, in edge order.
    let mut sums = vec![(0.0, 0.0, 0u32); m];
    for &(a, b) in &unique {
        for (to, from) in [(a, b), (b, a)] {
            if !own[to] && own[from] {
                let s = &mut sums[to];
                s.0 += mean[from];
                s.1 += gauss[from];
                s.2 += 1;
            }
        }
    }
    for v in (0..m).filter(|&v| !own[v]) {
        let (h, k, count) = sums[v];
        if count > 0 {
            mean[v] = h / f64::from(count);
            gauss[v] = k / f64::from(count);
        }
    }

    VertexCurvature {
        mean: weld.iter().map(|&w| mean[w as usize]).collect(),
        gauss: weld.iter().map(|&w| gauss[w as usize]).collect(),
        area: weld.iter().map(|&w| area[w as usize]).collect(),
    }
}

/// Per vertex, its welded index, and the welded positions: a vertex within
/// [`WELD_TOLERANCE`] times the bounding box's diagonal of an earlier welded vertex takes the
/// lowest such index, the others a new one, in order of first appearance (non-finite
/// positions are never welded).
///
/// The welded points are hashed into cubic cells four tolerances wide, so that a point
/// within the tolerance of another lies in one of the (at most eight, usually one) cells its
/// tolerance box touches.
fn weld_by_position(positions: &[DVec3]) -> (Vec<u32>, Vec<DVec3>) {
    let finite = || positions.iter().filter(|p| p.is_finite());
    let lo = finite().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let hi = finite().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    let tolerance = if lo.x <= hi.x { WELD_TOLERANCE * (hi - lo).length() } else { 0.0 };
    let cell = 4.0 * tolerance;
    // The first welded point of each cell, and the next one in the same cell.
    let mut first: HashMap<[i64; 3], u32> = HashMap::with_capacity(positions.len());
    let mut next: Vec<u32> = Vec::with_capacity(positions.len());
    let mut points: Vec<DVec3> = Vec::with_capacity(positions.len());
    let key = |p: DVec3, d: DVec3| -> [i64; 3] {
        if cell > 0.0 {
            ((p + d - lo) / cell).floor().to_array().map(|x| x as i64)
        } else {
            // All finite points coincide (or there are none): exact positions.
            (p + DVec3::ZERO).to_array().map(|x| x.to_bits() as i64)
        }
    };
    let weld = positions
        .iter()
        .map(|&p| {
            let mut found = u32::MAX;
            if p.is_finite() {
                let (a, b) = (key(p, DVec3::splat(-tolerance)), key(p, DVec3::splat(tolerance)));
                for x in a[0]..=b[0] {
                    for y in a[1]..=b[1] {
                        for z in a[2]..=b[2] {
                            let mut at = first.get(&[x, y, z]).copied().unwrap_or(u32::MAX);
                            while at != u32::MAX {
                                if at < found && points[at as usize].distance(p) <= tolerance {
                                    found = at;
                                }
                                at = next[at as usize];
                            }
                        }
                    }
                }
            }
            if found == u32::MAX {
                found = points.len() as u32;
                points.push(p);
                next.push(u32::MAX);
                if p.is_finite() {
                    // Push onto its cell's list.
                    let home = first.entry(key(p, DVec3::ZERO)).or_insert(u32::MAX);
                    next[found as usize] = *home;
                    *home = found;
                }
            }
            found
        })
        .collect();
    (weld, points)
}

fn edge_key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}

fn split_key(key: u64) -> (usize, usize) {
    ((key >> 32) as usize, (key & u64::from(u32::MAX)) as usize)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use glam::DVec2;

    use super::*;
    use crate::sweep::surface::{SurfaceOptions, UvMode, mesh_surface};
    use crate::sweep::{MeshLayout, Profile, SweepOptions, revolve};

    /// Rounding-level agreement.
    const EXACT: f64 = 1e-12;

    /// An icosahedron of circumradius `r` refined `levels` times by splitting every triangle
    /// in four at its edge midpoints, pushed out to the sphere. Counter-clockwise outward.
    fn icosphere(r: f64, levels: usize) -> TriMesh {
        let phi = (1.0 + 5f64.sqrt()) / 2.0;
        let mut positions = Vec::new();
        for (a, b) in [(1.0, phi), (1.0, -phi), (-1.0, phi), (-1.0, -phi)] {
            positions.extend([DVec3::new(0.0, a, b), DVec3::new(a, b, 0.0), DVec3::new(b, 0.0, a)]);
        }
        // The faces: the triples of vertices two apart from each other, turned outward.
        let mut triangles = Vec::new();
        let near = |i: usize, j: usize| (positions[i] - positions[j]).length() < 2.0 + 1e-9;
        for i in 0..12 {
            for j in i + 1..12 {
                for k in j + 1..12 {
                    if near(i, j) && near(j, k) && near(k, i) {
                        let (a, b, c) = (positions[i], positions[j], positions[k]);
                        let outward = (b - a).cross(c - a).dot(a + b + c) > 0.0;
                        let (i, j, k) = (i as u32, j as u32, k as u32);
                        triangles.push(if outward { [i, j, k] } else { [i, k, j] });
                    }
                }
            }
        }
        assert_eq!(triangles.len(), 20);
        for _ in 0..levels {
            let mut mid = HashMap::new();
            let mut finer = Vec::with_capacity(4 * triangles.len());
            for t in &triangles {
                let mut m = [0u32; 3];
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    m[k] = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                        positions.push(0.5 * (positions[a as usize] + positions[b as usize]));
                        (positions.len() - 1) as u32
                    });
                }
                finer.extend([[t[0], m[0], m[2]], [t[1], m[1], m[0]], [t[2], m[2], m[1]], m]);
            }
            triangles = finer;
        }
        let positions = positions.into_iter().map(|p| r * p.normalize()).collect();
        TriMesh { positions, triangles, ..TriMesh::default() }
    }

    /// A torus about z, tube radius `r` about a circle of radius `big`, on an `nu × nv` grid:
    /// `(u, v) ↦ ((R + r cos φ) cos θ, (R + r cos φ) sin θ, r sin φ)`, θ = 2πu, φ = 2πv.
    fn torus(big: f64, r: f64, nu: usize, nv: usize, uvs: UvMode) -> TriMesh {
        let f = move |u: f64, v: f64| {
            let (theta, phi) = (TAU * u, TAU * v);
            let rho = big + r * phi.cos();
            DVec3::new(rho * theta.cos(), rho * theta.sin(), r * phi.sin())
        };
        mesh_surface(f, &SurfaceOptions::new(nu, nv).with_wrap(true, true).with_uvs(uvs)).unwrap()
    }

    /// The closed forms on the torus at `p`: (H, K).
    fn torus_curvature(big: f64, r: f64, p: DVec3) -> (f64, f64) {
        let cos_phi = ((p.x.hypot(p.y) - big) / r).clamp(-1.0, 1.0);
        let rho = big + r * cos_phi;
        ((big + 2.0 * r * cos_phi) / (2.0 * r * rho), cos_phi / (r * rho))
    }

    fn max_error(values: &[f64], expected: impl Fn(usize) -> f64) -> f64 {
        values.iter().enumerate().map(|(i, &v)| (v - expected(i)).abs()).fold(0.0, f64::max)
    }

    fn euler(mesh: &TriMesh) -> i64 {
        let mut edges: Vec<u64> =
            mesh.triangles.iter().flat_map(|t| (0..3).map(|k| edge_key(t[k], t[(k + 1) % 3]))).collect();
        edges.sort_unstable();
        edges.dedup();
        mesh.num_vertices() as i64 - edges.len() as i64 + mesh.num_triangles() as i64
    }

    fn total_gauss(c: &VertexCurvature) -> f64 {
        c.gauss.iter().zip(&c.area).map(|(k, a)| k * a).sum()
    }

    #[test]
    fn icosphere_converges_to_the_sphere() {
        let r = 2.0;
        let mut last = (f64::INFINITY, f64::INFINITY);
        for levels in 2..=5 {
            let mesh = icosphere(r, levels);
            let c = vertex_curvature(&mesh);
            let (eh, ek) = (max_error(&c.mean, |_| 1.0 / r), max_error(&c.gauss, |_| 1.0 / (r * r)));
            // Mixed areas tile the surface; Gauss–Bonnet with χ = 2.
            assert!((c.area.iter().sum::<f64>() - mesh.area()).abs() < 1e-12 * mesh.area(), "level {levels}");
            assert!((total_gauss(&c) - 4.0 * PI).abs() < 1e-10, "level {levels}: {}", total_gauss(&c));
            // The error shrinks with every refinement (by about 4: second order).
            assert!(
                eh < 0.5 * last.0 && ek < 0.5 * last.1,
                "level {levels}: H error {eh}, K error {ek}, before {last:?}"
            );
            last = (eh, ek);
        }
        // 10242 vertices, edges about 0.03·r (measured: H within 2.2e-7, K within 8.9e-5).
        assert!(last.0 < 1e-6 / r && last.1 < 1e-3 / (r * r), "{last:?}");
    }

    #[test]
    fn inside_out_sphere_has_negative_mean_curvature() {
        let mut mesh = icosphere(0.5, 3);
        let outward = vertex_curvature(&mesh);
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
        let inward = vertex_curvature(&mesh);
        for i in 0..mesh.num_vertices() {
            assert!((inward.mean[i] + outward.mean[i]).abs() < EXACT, "vertex {i}");
            assert!((inward.gauss[i] - outward.gauss[i]).abs() < EXACT, "vertex {i}");
        }
        assert!(inward.mean.iter().all(|&h| (h + 2.0).abs() < 0.05));
    }

    #[test]
    fn torus_matches_its_closed_forms() {
        let (big, r) = (2.0, 0.5);
        let mut last = (f64::INFINITY, f64::INFINITY);
        for (nu, nv) in [(48, 24), (96, 48), (192, 96)] {
            let mesh = torus(big, r, nu, nv, UvMode::Omit);
            assert!(mesh.is_closed_oriented());
            let c = vertex_curvature(&mesh);
            let exact = |i: usize| torus_curvature(big, r, mesh.positions[i]);
            let (eh, ek) = (max_error(&c.mean, |i| exact(i).0), max_error(&c.gauss, |i| exact(i).1));
            assert!(total_gauss(&c).abs() < 1e-9, "{nu}×{nv}: Gauss–Bonnet, χ = 0: {}", total_gauss(&c));
            assert_eq!(euler(&mesh), 0);
            assert!(eh < 0.5 * last.0 && ek < 0.5 * last.1, "{nu}×{nv}: H error {eh}, K error {ek}, before {last:?}");
            last = (eh, ek);
        }
        // Values range over H ∈ [0.67, 1.17], K ∈ [−1.33, 0.4]; measured within 1.7e-4 and 5.1e-4.
        assert!(last.0 < 1e-3 && last.1 < 1e-3, "{last:?}");
        // Negative inside, positive outside.
        let mesh = torus(big, r, 96, 48, UvMode::Omit);
        let c = vertex_curvature(&mesh);
        for (i, p) in mesh.positions.iter().enumerate() {
            let rho = p.x.hypot(p.y);
            if rho < big - 0.1 {
                assert!(c.gauss[i] < 0.0, "inner vertex {i}: {}", c.gauss[i]);
            } else if rho > big + 0.1 {
                assert!(c.gauss[i] > 0.0, "outer vertex {i}: {}", c.gauss[i]);
            }
        }
    }

    #[test]
    fn seams_are_measured_across() {
        // The same torus with its seams split (UVs): every copy gets the welded value.
        let (big, r) = (2.0, 0.5);
        let welded = torus(big, r, 48, 24, UvMode::Omit);
        let split = torus(big, r, 48, 24, UvMode::SplitSeams);
        assert!(split.num_vertices() > welded.num_vertices());
        assert!(!split.boundary_edges().is_empty(), "by index the seams are boundaries");
        let (cw, cs) = (vertex_curvature(&welded), vertex_curvature(&split));
        let at: HashMap<[u64; 3], usize> =
            welded.positions.iter().enumerate().map(|(i, p)| (p.to_array().map(f64::to_bits), i)).collect();
        for (i, p) in split.positions.iter().enumerate() {
            let w = at[&p.to_array().map(f64::to_bits)];
            assert!((cs.mean[i] - cw.mean[w]).abs() < EXACT && (cs.gauss[i] - cw.gauss[w]).abs() < EXACT, "{i}");
            let (h, k) = torus_curvature(big, r, *p);
            assert!((cs.mean[i] - h).abs() < 0.05 && (cs.gauss[i] - k).abs() < 0.05, "{i}: {} {}", cs.mean[i], h);
        }
        // A UV sphere with its seam split and its poles as fans.
        let sphere = |u: f64, v: f64| {
            let (theta, phi) = (TAU * u, PI * (v - 0.5));
            3.0 * DVec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin())
        };
        let o = SurfaceOptions::new(64, 32).with_wrap(true, false).with_uvs(UvMode::SplitSeams);
        let s = mesh_surface(sphere, &o).unwrap();
        assert_eq!(s.uvs[1], DVec2::new(0.0, 1.0 / 32.0));
        let c = vertex_curvature(&s);
        assert!(max_error(&c.mean, |_| 1.0 / 3.0) < 0.01 / 3.0, "{}", max_error(&c.mean, |_| 1.0 / 3.0));
        assert!(max_error(&c.gauss, |_| 1.0 / 9.0) < 0.02 / 9.0, "{}", max_error(&c.gauss, |_| 1.0 / 9.0));
        let welded_total: f64 = {
            // Each position once.
            let mut seen = std::collections::HashSet::new();
            (0..s.num_vertices())
                .filter(|&i| seen.insert(s.positions[i].to_array().map(f64::to_bits)))
                .map(|i| c.gauss[i] * c.area[i])
                .sum()
        };
        assert!((welded_total - 4.0 * PI).abs() < 1e-10, "{welded_total}");
    }

    #[test]
    fn a_swept_sphere_is_measured_across_its_seam_and_poles() {
        // A half circle of radius 1.5 revolved about +y: with UVs the sweep doubles its seam
        // (u = 0 and 1), the course's layout repeats the poles in every copy; both give the
        // welded sphere's values at every position.
        let r = 1.5;
        let n = 40;
        let t = |i: usize| PI * i as f64 / n as f64;
        let profile = Profile {
            points: (0..=n).map(|i| r * DVec2::new(-t(i).sin(), -t(i).cos())).collect(),
            normals: (0..=n).map(|i| DVec2::new(-t(i).sin(), -t(i).cos())).collect(),
        };
        let welded = SweepOptions::default();
        let sweep = |o: SweepOptions| revolve(&profile, 64, o).unwrap();
        let reference = sweep(welded);
        assert!(reference.is_closed_oriented());
        let c = vertex_curvature(&reference);
        assert!(max_error(&c.mean, |_| 1.0 / r) < 0.01 / r, "H {}", max_error(&c.mean, |_| 1.0 / r));
        assert!(
            max_error(&c.gauss, |_| 1.0 / (r * r)) < 0.02 / (r * r),
            "K {}",
            max_error(&c.gauss, |_| 1.0 / (r * r))
        );
        // The reference vertex at the same place (the seam copy at 2π is some 1e-16 off).
        let at = |p: DVec3| reference.positions.iter().position(|q| q.distance(p) < 1e-12).unwrap();
        for options in [SweepOptions { uvs: true, ..welded }, SweepOptions { layout: MeshLayout::Compat, ..welded }] {
            let mesh = sweep(options);
            assert!(mesh.num_vertices() > reference.num_vertices(), "{options:?}");
            let d = vertex_curvature(&mesh);
            for (i, p) in mesh.positions.iter().enumerate() {
                let w = at(*p);
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
                assert!(close(d.mean[i], c.mean[w]) && close(d.gauss[i], c.gauss[w]), "{options:?}, vertex {i}");
            }
        }
    }

    #[test]
    fn a_plane_is_flat_everywhere() {
        // A grid in a tilted plane, its inner vertices moved about within the plane (obtuse
        // and non-Delaunay triangles): the cotangent Laplacian of a plane is zero at any
        // interior vertex, the angles sum to 2π, and the boundary takes the average.
        let (a, b) = (DVec3::new(1.0, 0.3, -0.2), DVec3::new(-0.1, 0.8, 0.6));
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut mesh =
            mesh_surface(|u, v| DVec3::new(3.0, -1.0, 2.0) + 4.0 * u * a + 3.0 * v * b, &SurfaceOptions::new(12, 9))
                .unwrap();
        for (i, p) in mesh.positions.iter_mut().enumerate() {
            let (col, row) = (i % 13, i / 13);
            if col > 0 && col < 12 && row > 0 && row < 9 {
                *p += 0.12 * rnd() * a + 0.12 * rnd() * b;
            }
        }
        let c = vertex_curvature(&mesh);
        assert!(c.mean.iter().chain(&c.gauss).all(|v| v.abs() < EXACT), "{:?}", max_error(&c.mean, |_| 0.0));
        // An axis-aligned grid is exact.
        let grid = mesh_surface(|u, v| DVec3::new(2.0 * u, v, 0.0), &SurfaceOptions::new(8, 6)).unwrap();
        let c = vertex_curvature(&grid);
        assert!(c.mean.iter().chain(&c.gauss).all(|v| v.abs() < EXACT));
    }

    #[test]
    fn degenerate_triangles_give_no_nan() {
        // A tetrahedron with one face split at a point on its edge: the sliver (a, m, b) has
        // no area. And a vertex used only by a zero-area triangle, and a vertex of no triangle.
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::new(0.5, 0.5, 0.0)],
            // (0, 2, 1) split at m = 4 on the edge 1–2.
            triangles: vec![[0, 2, 4], [0, 4, 1], [2, 1, 4], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            ..TriMesh::default()
        };
        let whole = TriMesh {
            positions: mesh.positions[..4].to_vec(),
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            ..TriMesh::default()
        };
        let c = vertex_curvature(&mesh);
        assert!(c.mean.iter().chain(&c.gauss).chain(&c.area).all(|v| v.is_finite()));
        // Gauss–Bonnet still holds: m's angles sum to 2π with its π in the sliver.
        assert!((total_gauss(&c) - 4.0 * PI).abs() < 1e-12, "{}", total_gauss(&c));
        assert!(c.gauss[4].abs() < EXACT, "{}", c.gauss[4]);
        let w = vertex_curvature(&whole);
        assert!((total_gauss(&w) - 4.0 * PI).abs() < 1e-12);

        // A vertex whose every triangle has no area (two slivers glued along the edge 0–1,
        // through its midpoint 4) takes its neighbours' average; a vertex of no triangle, or
        // only of triangles left out (a corner not finite, or out of range), gets 0.
        let mut mesh = whole;
        mesh.positions.extend([DVec3::new(0.5, 0.0, 0.0), DVec3::new(9.0, 9.0, 9.0), DVec3::new(f64::NAN, 0.0, 0.0)]);
        mesh.triangles.extend([[0, 4, 1], [1, 4, 0], [3, 6, 1], [5, 99, 1]]);
        let c = vertex_curvature(&mesh);
        assert!(c.mean.iter().chain(&c.gauss).chain(&c.area).all(|v| v.is_finite()));
        assert_eq!(c.area[4], 0.0);
        assert!((c.gauss[4] - 0.5 * (c.gauss[0] + c.gauss[1])).abs() < EXACT, "{:?}", c.gauss);
        assert!((c.mean[4] - 0.5 * (c.mean[0] + c.mean[1])).abs() < EXACT, "{:?}", c.mean);
        assert!(c.gauss[0] > 0.0 && c.mean[0] > 0.0);
        for v in [5, 6] {
            assert_eq!((c.mean[v], c.gauss[v], c.area[v]), (0.0, 0.0, 0.0));
        }
    }

    #[test]
    fn rigid_motions_change_nothing() {
        let mesh = torus(1.5, 0.4, 24, 12, UvMode::Omit);
        let c = vertex_curvature(&mesh);
        let q = glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let moved =
            TriMesh { positions: mesh.positions.iter().map(|&p| q * p + DVec3::new(5.0, -2.0, 1.0)).collect(), ..mesh };
        let d = vertex_curvature(&moved);
        for i in 0..moved.num_vertices() {
            assert!((c.mean[i] - d.mean[i]).abs() < 1e-9 && (c.gauss[i] - d.gauss[i]).abs() < 1e-9, "vertex {i}");
        }
    }

    #[test]
    fn welding_joins_only_near_copies() {
        // Diagonal 2: the tolerance is 2e-9.
        let positions = vec![
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 1e-9, -1e-9),   // 1.4e-9 from 1: welded
            DVec3::new(-0.0, 0.0, 3e-9),    // 3e-9 from 0: not
            DVec3::new(f64::NAN, 0.0, 0.0), // never
            DVec3::new(f64::NAN, 0.0, 0.0),
            DVec3::new(0.0, -0.0, 0.0), // −0 = +0
            DVec3::new(2.0, 0.0, 1e-9), // 1e-9 from 1 and 1.4e-9 from 2: the lower index
        ];
        let (weld, points) = weld_by_position(&positions);
        assert_eq!(weld, vec![0, 1, 1, 2, 3, 4, 0, 1]);
        assert_eq!(points.len(), 5);
        assert_eq!(weld_by_position(&[DVec3::ONE, DVec3::ONE]).0, vec![0, 0]);
    }

    #[test]
    fn empty_mesh() {
        assert_eq!(vertex_curvature(&TriMesh::default()), VertexCurvature::default());
    }
}
