//! The sizes of subdivided meshes, checked before anything is made.
//!
//! Vertices, faces and face corners are numbered with `u32` indices (and edges and half-edges
//! in the adjacency tables), so every entry point works out the exact counts of each level it
//! is asked for, from the base mesh's counts, and refuses a level that would not fit with
//! [`SubdivError::TooLarge`] instead of wrapping indices, overflowing or running out of memory
//! part way. The counts per level (`V` vertices, `E` edges, `F` faces, `C` corners):
//! - Loop and butterfly: `V + E`, `2E + 3F`, `4F`, `12F`;
//! - Catmull-Clark: `V + E + F`, `2E + C`, `C`, `4C`;
//! - √3, with `B = 2E − 3F` boundary edges: `V + F` (`+ B` on a boundary level), `(9F + B′)/2`,
//!   `3F`, `9F`, where `B′ = 3B` on a boundary level and `B` otherwise;
//! - Doo-Sabin: see [`DooSabin`].
//!
//! Every count that enters a level is at most `u32::MAX` and every formula is a small sum, so
//! no `u64` arithmetic here can overflow (it saturates all the same).

use rayon::prelude::*;

use super::error::SubdivError;
use super::rings::Rings;
use super::scheme::Scheme;
use super::topology::Topology;
use crate::mesh::{NONE, PolyMesh};

/// The largest count `u32` indices can number.
const MAX: u64 = u32::MAX as u64;

/// The sizes of one level of a subdivision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Counts {
    pub(super) vertices: u64,
    pub(super) edges: u64,
    pub(super) faces: u64,
    /// Face corners: the length of the face index buffer (and the number of half-edges).
    pub(super) corners: u64,
}

/// `Σ kᵢ·xᵢ`, saturating.
fn sum<const N: usize>(terms: [(u64, u64); N]) -> u64 {
    terms.iter().fold(0, |s, &(k, x)| s.saturating_add(k.saturating_mul(x)))
}

impl Counts {
    /// The counts of the mesh of `rings`.
    pub(super) fn of_rings(rings: &Rings<'_>) -> Self {
        let mesh = rings.mesh;
        Self {
            vertices: mesh.num_vertices() as u64,
            edges: rings.adj.num_edges() as u64,
            faces: mesh.num_faces() as u64,
            corners: mesh.face_vertices.len() as u64,
        }
    }

    /// The counts of `mesh`, its edges the distinct pairs of vertices that the sides of its
    /// faces join.
    pub(super) fn of_mesh(mesh: &PolyMesh) -> Self {
        let mut sides: Vec<u64> = mesh
            .faces()
            .flat_map(|f| {
                (0..f.len()).map(move |k| {
                    let (a, b) = (f[k], f[(k + 1) % f.len()]);
                    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
                })
            })
            .collect();
        sides.par_sort_unstable();
        sides.dedup();
        Self {
            vertices: mesh.num_vertices() as u64,
            edges: sides.len() as u64,
            faces: mesh.num_faces() as u64,
            corners: mesh.face_vertices.len() as u64,
        }
    }

    /// The counts of `triangles` triangles with the tables `topology`.
    pub(super) fn of_triangles(topology: &Topology, triangles: usize) -> Self {
        let faces = triangles as u64;
        Self { vertices: topology.num_vertices() as u64, edges: topology.num_edges() as u64, faces, corners: 3 * faces }
    }

    /// One level of Loop's (or butterfly's) split of every triangle into four.
    fn loop_child(self) -> Self {
        let Self { vertices: v, edges: e, faces: f, .. } = self;
        Self {
            vertices: sum([(1, v), (1, e)]),
            edges: sum([(2, e), (3, f)]),
            faces: sum([(4, f)]),
            corners: sum([(12, f)]),
        }
    }

    /// One level of Catmull-Clark: a quad per corner.
    fn catmull_clark_child(self) -> Self {
        let Self { vertices: v, edges: e, faces: f, corners: c } = self;
        Self { vertices: sum([(1, v), (1, e), (1, f)]), edges: sum([(2, e), (1, c)]), faces: c, corners: sum([(4, c)]) }
    }

    /// `self`, or [`SubdivError::TooLarge`] for its first count above `u32::MAX` (`vertices`
    /// names the vertices, e.g. `normal values` for a normal channel's).
    fn fit(self, scheme: &'static str, levels: usize, vertices: &'static str) -> Result<Self, SubdivError> {
        let counts =
            [(vertices, self.vertices), ("edges", self.edges), ("faces", self.faces), ("face corners", self.corners)];
        match counts.into_iter().find(|&(_, count)| count > MAX) {
            Some((what, count)) => Err(SubdivError::TooLarge { scheme, levels, what, count }),
            None => Ok(self),
        }
    }
}

/// Level `to` from level `from`, `base`: `step(level, depth)` makes level `depth` from level
/// `depth − 1`, and `fit` checks it. Stops early at a fixed point (a mesh without faces, or a
/// Doo-Sabin face alone), so that any number of levels is checked at once: otherwise some count
/// at least doubles per level and overflows within some 70 levels.
fn walk<S: Copy + PartialEq>(
    base: S,
    from: usize,
    to: usize,
    step: impl Fn(S, usize) -> S,
    fit: impl Fn(S, usize) -> Result<S, SubdivError>,
) -> Result<S, SubdivError> {
    let mut level = base;
    for depth in from + 1..=to {
        let child = fit(step(level, depth), depth)?;
        if child == level {
            break;
        }
        level = child;
    }
    Ok(level)
}

/// The counts of level `to` of Loop's or butterfly's scheme (`scheme`) from level `from`,
/// `base`; `vertices` names the vertices (`normal values` for a channel of normals).
pub(super) fn loop_levels(
    scheme: &'static str,
    vertices: &'static str,
    base: Counts,
    from: usize,
    to: usize,
) -> Result<Counts, SubdivError> {
    walk(base, from, to, |c, _| c.loop_child(), |c, depth| c.fit(scheme, depth, vertices))
}

/// The counts of level `to` of Catmull-Clark subdivision from level `from`, `base`.
pub(super) fn catmull_clark_levels(base: Counts, from: usize, to: usize) -> Result<Counts, SubdivError> {
    walk(base, from, to, |c, _| c.catmull_clark_child(), |c, depth| c.fit("Catmull-Clark", depth, "vertices"))
}

/// The counts of level `to` of bilinear subdivision (Catmull-Clark's split) from level `from`, `base`.
pub(super) fn bilinear_levels(base: Counts, from: usize, to: usize) -> Result<Counts, SubdivError> {
    walk(base, from, to, |c, _| c.catmull_clark_child(), |c, depth| c.fit("bilinear", depth, "vertices"))
}

/// The counts of level `levels` of √3 subdivision of the triangle mesh `base` (level 0;
/// boundary levels are the even ones).
pub(super) fn sqrt3_levels(base: Counts, levels: usize) -> Result<Counts, SubdivError> {
    // a manifold triangle mesh: 2E = 3F + B
    let boundary = sum([(2, base.edges)]).saturating_sub(sum([(3, base.faces)]));
    let step = |(c, b): (Counts, u64), depth: usize| sqrt3_child(c, b, depth.is_multiple_of(2));
    let fit = |(c, b): (Counts, u64), depth| Ok((c.fit("√3", depth, "vertices")?, b));
    Ok(walk((base, boundary), 0, levels, step, fit)?.0)
}

/// One level of √3 from `c` with `b` boundary edges, refining the boundary on a `border`
/// level: the child's counts and boundary edges.
fn sqrt3_child(c: Counts, b: u64, border: bool) -> (Counts, u64) {
    let child_b = if border { sum([(3, b)]) } else { b };
    let child = Counts {
        vertices: sum([(1, c.vertices), (1, c.faces), (u64::from(border), b)]),
        edges: sum([(9, c.faces), (1, child_b)]) / 2,
        faces: sum([(3, c.faces)]),
        corners: sum([(9, c.faces)]),
    };
    (child, child_b)
}

/// The vertex counts of levels `0 .. levels` of `scheme` (not Doo-Sabin, whose vertices are
/// all new at every level) from level 0, `base`, given to `visit` in order: where the vertices
/// of levels `1 ..= levels` start. Saturating and unchecked (the subdivision checks its own).
pub(super) fn level_vertices(scheme: Scheme, base: Counts, levels: usize, mut visit: impl FnMut(u64)) {
    // √3's boundary edges (a manifold triangle mesh: 2E = 3F + B)
    let boundary = sum([(2, base.edges)]).saturating_sub(sum([(3, base.faces)]));
    let mut level = (base, boundary);
    for depth in 1..=levels {
        visit(level.0.vertices);
        level = match scheme {
            Scheme::Loop | Scheme::Butterfly => (level.0.loop_child(), level.1),
            Scheme::Sqrt3 => sqrt3_child(level.0, level.1, depth.is_multiple_of(2)),
            _ => (level.0.catmull_clark_child(), level.1),
        };
    }
}

/// What the counts of a Doo-Sabin level follow from: its [`Counts`], and
/// - `B` boundary edges (half-edges without a twin);
/// - `Vᵢ` interior vertices (with faces, none of their edges on the boundary), with `Cᵢ`
///   corners between them;
/// - `X`: the boundary ends of the interior edges, summed.
///
/// With `Eᵢ = E − B` interior edges, the child has a vertex per corner (`C`), the parent's
/// faces' edges and two across each interior edge (`C + 2Eᵢ`), an F-face per face, an E-face
/// per interior edge and a V-face per interior vertex (`F + Eᵢ + Vᵢ`, with `C + 4Eᵢ + Cᵢ`
/// corners); its boundary is the parent's boundary edges and an edge across each interior edge
/// at each boundary end (`B + X`); its interior vertices are the corners at the parent's (`Cᵢ`),
/// each of four corners (`4Cᵢ`); and `X` doubles (each interior edge's two halves).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct DooSabin {
    pub(super) counts: Counts,
    boundary_edges: u64,
    interior_vertices: u64,
    interior_corners: u64,
    boundary_ends: u64,
}

impl DooSabin {
    /// The counts of the mesh of `rings`.
    pub(super) fn of_rings(rings: &Rings<'_>) -> Self {
        let adj = &rings.adj;
        let interior = |v: u32| adj.corners_of(v).iter().all(|&c| adj.twin[c as usize] != NONE);
        let (mut interior_vertices, mut interior_corners, mut boundary_ends) = (0, 0, 0);
        for v in 0..rings.mesh.num_vertices() as u32 {
            let corners = adj.corners_of(v);
            if corners.is_empty() {
                continue;
            }
            if interior(v) {
                interior_vertices += 1;
                interior_corners += corners.len() as u64;
            } else {
                // each interior half-edge leaving a boundary vertex: one boundary end
                boundary_ends += corners.iter().filter(|&&c| adj.twin[c as usize] != NONE).count() as u64;
            }
        }
        Self {
            counts: Counts::of_rings(rings),
            boundary_edges: adj.num_boundary_edges() as u64,
            interior_vertices,
            interior_corners,
            boundary_ends,
        }
    }

    fn child(self) -> Self {
        let Counts { vertices: _, edges: e, faces: f, corners: c } = self.counts;
        let e_int = e.saturating_sub(self.boundary_edges);
        Self {
            counts: Counts {
                vertices: c,
                edges: sum([(1, c), (2, e_int)]),
                faces: sum([(1, f), (1, e_int), (1, self.interior_vertices)]),
                corners: sum([(1, c), (4, e_int), (1, self.interior_corners)]),
            },
            boundary_edges: sum([(1, self.boundary_edges), (1, self.boundary_ends)]),
            interior_vertices: self.interior_corners,
            interior_corners: sum([(4, self.interior_corners)]),
            boundary_ends: sum([(2, self.boundary_ends)]),
        }
    }
}

/// The counts of level `levels` of Doo-Sabin subdivision of `base` (level 0).
pub(super) fn doo_sabin_levels(base: DooSabin, levels: usize) -> Result<DooSabin, SubdivError> {
    let fit = |d: DooSabin, depth| Ok(DooSabin { counts: d.counts.fit("Doo-Sabin", depth, "vertices")?, ..d });
    walk(base, 0, levels, |d, _| d.child(), fit)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::PolyMesh;
    use crate::subdiv::{
        ButterflyOptions, CatmullClarkOptions, Creases, CreasingMethod, DooSabinOptions, EdgeCrease, LoopOptions,
        LoopPyramid, Sqrt3Options, SubdivisionMatrix, butterfly_step, butterfly_subdivide, catmull_clark_step,
        catmull_clark_subdivide, catmull_clark_subdivide_creased, doo_sabin_subdivide, loop_subdivide,
        loop_subdivide_creased, sqrt3_subdivide,
    };

    /// A polygon mesh from its faces.
    fn mesh(positions: usize, faces: &[&[u32]]) -> PolyMesh {
        let mut face_offsets = vec![0];
        let mut face_vertices = Vec::new();
        for f in faces {
            face_vertices.extend_from_slice(f);
            face_offsets.push(face_vertices.len() as u32);
        }
        let positions = (0..positions).map(|i| DVec3::new(i as f64, (i * i % 7) as f64, (i % 3) as f64)).collect();
        PolyMesh { positions, face_offsets, face_vertices, ..PolyMesh::default() }
    }

    /// A cube of six quads.
    fn cube() -> PolyMesh {
        let faces: [&[u32]; 6] =
            [&[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7]];
        mesh(8, &faces)
    }

    /// A tetrahedron.
    fn tetrahedron() -> PolyMesh {
        mesh(4, &[&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]])
    }

    /// An open `n × n` grid of quads (`triangles`: each split in two), with a vertex of no face.
    fn grid(n: u32, triangles: bool) -> PolyMesh {
        let g = |i: u32, j: u32| j * (n + 1) + i;
        let mut faces: Vec<Vec<u32>> = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1));
                if triangles {
                    faces.extend([vec![a, b, c], vec![a, c, d]]);
                } else {
                    faces.push(vec![a, b, c, d]);
                }
            }
        }
        let faces: Vec<&[u32]> = faces.iter().map(Vec::as_slice).collect();
        mesh(((n + 1) * (n + 1) + 1) as usize, &faces)
    }

    /// A pyramid with an open square base (a pentagon beside it): triangles, a quad missing, a pentagon.
    fn mixed() -> PolyMesh {
        mesh(8, &[&[0, 1, 4], &[1, 2, 4], &[2, 3, 4], &[3, 0, 4], &[1, 0, 5, 6, 7]])
    }

    /// The counts of `mesh`, its edges counted from its adjacency.
    fn counts_of(mesh: &PolyMesh) -> Counts {
        Counts::of_rings(&Rings::new(mesh).unwrap())
    }

    /// Asserts that `err` is [`SubdivError::TooLarge`] for `scheme` at some level up to `levels`.
    #[track_caller]
    fn assert_too_large(err: SubdivError, scheme: &str, levels: usize) {
        let SubdivError::TooLarge { scheme: s, levels: at, what: _, count } = &err else {
            panic!("expected TooLarge, got {err:?}");
        };
        assert_eq!(*s, scheme, "{err}");
        assert!(*at <= levels && *count > u64::from(u32::MAX), "{err}");
        assert!(err.to_string().contains("at most 4294967295 fit in u32 indices"), "{err}");
    }

    #[test]
    fn predicted_counts_are_the_counts_made() {
        let triangles = [tetrahedron(), grid(3, true)];
        let polygons = [cube(), grid(3, false), mixed(), tetrahedron()];
        for levels in 1..=3 {
            for m in &triangles {
                let base = counts_of(m);
                let fine = loop_subdivide(m, levels as u32, &LoopOptions::default()).unwrap();
                assert_eq!(loop_levels("Loop", "vertices", base, 0, levels), Ok(counts_of(&fine)), "Loop {levels}");
                let fine = butterfly_subdivide(m, levels, &ButterflyOptions::default()).unwrap();
                assert_eq!(loop_levels("butterfly", "vertices", base, 0, levels), Ok(counts_of(&fine)));
                let fine = sqrt3_subdivide(m, levels, &Sqrt3Options::default()).unwrap();
                assert_eq!(sqrt3_levels(base, levels), Ok(counts_of(&fine)), "√3 {levels}");
            }
            for m in &polygons {
                let base = counts_of(m);
                let fine = catmull_clark_subdivide(m, levels, &CatmullClarkOptions::default()).unwrap();
                assert_eq!(catmull_clark_levels(base, 0, levels), Ok(counts_of(&fine)), "Catmull-Clark {levels}");
                let fine = doo_sabin_subdivide(m, levels, &DooSabinOptions::default()).unwrap();
                let ds = DooSabin::of_rings(&Rings::new(m).unwrap());
                assert_eq!(doo_sabin_levels(ds, levels).map(|d| d.counts), Ok(counts_of(&fine)), "Doo-Sabin {levels}");
            }
        }
        // the regular path (three levels of a closed quad mesh of valence 4): a 4 × 4 torus
        let n = 4;
        let at = |i: u32, j: u32| (j % n) * n + i % n;
        let quads: Vec<Vec<u32>> = (0..n)
            .flat_map(|j| (0..n).map(move |i| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]))
            .collect();
        let torus = mesh((n * n) as usize, &quads.iter().map(Vec::as_slice).collect::<Vec<_>>());
        let fine = catmull_clark_subdivide(&torus, 3, &CatmullClarkOptions::default()).unwrap();
        assert_eq!(catmull_clark_levels(counts_of(&torus), 0, 3), Ok(counts_of(&fine)));
    }

    #[test]
    fn the_largest_levels_that_fit_pass() {
        // a cube's level k has 6·4ᵏ quads, 24·4ᵏ corners: 13 levels fit (1 610 612 736 corners),
        // 14 do not (6 442 450 944)
        let cube = counts_of(&cube());
        let fine = catmull_clark_levels(cube, 0, 13).unwrap();
        assert_eq!((fine.faces, fine.corners), (6 << 26, 24 << 26));
        assert_eq!(
            catmull_clark_levels(cube, 0, 14),
            Err(SubdivError::TooLarge { scheme: "Catmull-Clark", levels: 14, what: "face corners", count: 24 << 28 })
        );
        // a tetrahedron's level k has 6·4ᵏ edges, 4·4ᵏ triangles, 12·4ᵏ corners: 14 levels fit,
        // and at 15 the edges are the first count too many
        let tetra = counts_of(&tetrahedron());
        assert_eq!(loop_levels("Loop", "vertices", tetra, 0, 14).unwrap().corners, 12 << 28);
        assert_eq!(
            loop_levels("Loop", "vertices", tetra, 0, 15),
            Err(SubdivError::TooLarge { scheme: "Loop", levels: 15, what: "edges", count: 6 << 30 })
        );
        // √3: 4·3ᵏ triangles, 12·3ᵏ corners: 17 levels fit, 18 do not
        assert_eq!(sqrt3_levels(tetra, 17).unwrap().corners, 12 * 3u64.pow(17));
        assert!(matches!(sqrt3_levels(tetra, 18), Err(SubdivError::TooLarge { levels: 18, .. })));
        // no faces, no growth: any number of levels fits (and is checked at once)
        let dots = Counts { vertices: 3, ..Counts::default() };
        assert_eq!(loop_levels("Loop", "vertices", dots, 0, usize::MAX), Ok(dots));
        assert_eq!(catmull_clark_levels(dots, 0, usize::MAX), Ok(dots));
        // a lone Doo-Sabin face stays a lone face
        let quad = mesh(4, &[&[0, 1, 2, 3]]);
        let ds = DooSabin::of_rings(&Rings::new(&quad).unwrap());
        assert_eq!(doo_sabin_levels(ds, usize::MAX).map(|d| d.counts), Ok(counts_of(&quad)));
    }

    #[test]
    fn the_message_names_the_levels_and_the_count() {
        let err = SubdivError::TooLarge { scheme: "Catmull-Clark", levels: 4, what: "vertices", count: 5_368_709_120 };
        assert_eq!(
            err.to_string(),
            "4 levels of Catmull-Clark subdivision would make 5368709120 vertices; at most 4294967295 fit in u32 indices"
        );
    }

    #[test]
    fn every_entry_point_refuses_too_many_levels() {
        let (cube, tetra) = (cube(), tetrahedron());
        let cc = CatmullClarkOptions::default();
        let lo = LoopOptions::default();
        let creases = Creases { edges: vec![EdgeCrease { a: 0, b: 1, sharpness: 2.0 }], ..Creases::default() };
        let method = CreasingMethod::default();
        let n = 20;
        assert_too_large(catmull_clark_subdivide(&cube, n, &cc).unwrap_err(), "Catmull-Clark", n);
        assert_too_large(catmull_clark_subdivide(&tetra, usize::MAX, &cc).unwrap_err(), "Catmull-Clark", usize::MAX);
        assert_too_large(
            catmull_clark_subdivide_creased(&cube, n, &cc, &creases, method).unwrap_err(),
            "Catmull-Clark",
            n,
        );
        assert_too_large(SubdivisionMatrix::catmull_clark(&cube, n, &cc).unwrap_err(), "Catmull-Clark", n);
        assert_too_large(doo_sabin_subdivide(&cube, n, &DooSabinOptions::default()).unwrap_err(), "Doo-Sabin", n);
        assert_too_large(loop_subdivide(&tetra, n as u32, &lo).unwrap_err(), "Loop", n);
        assert_too_large(loop_subdivide(&tetra, u32::MAX, &lo).unwrap_err(), "Loop", u32::MAX as usize);
        assert_too_large(loop_subdivide_creased(&tetra, n as u32, &lo, &creases, method).unwrap_err(), "Loop", n);
        assert_too_large(SubdivisionMatrix::loop_scheme(&tetra, n as u32, &lo).unwrap_err(), "Loop", n);
        assert_too_large(sqrt3_subdivide(&tetra, 2 * n, &Sqrt3Options::default()).unwrap_err(), "√3", 2 * n);
        assert_too_large(butterfly_subdivide(&tetra, n, &ButterflyOptions::default()).unwrap_err(), "butterfly", n);
        // the level-by-level pyramid: one shot, to a level, and one more level
        let pyramid = LoopPyramid::new(&tetra, lo).unwrap();
        assert_too_large(pyramid.clone().into_refined(n, |_| {}).unwrap_err(), "Loop", n);
        let mut p = pyramid.clone();
        assert_too_large(p.refine_to(n, |_| {}).unwrap_err(), "Loop", n);
        assert_eq!(p.num_levels(), 1, "nothing refined");
        // one step of a mesh whose child would not fit: a level-15 tetrahedron is too big to
        // make here, so the check is called as the steps call it, on a level's counts
        let big = Counts { vertices: 1 << 31, edges: 3 << 30, faces: 1 << 31, corners: 3 << 31 };
        assert_too_large(loop_levels("butterfly", "vertices", big, 14, 15).unwrap_err(), "butterfly", 15);
        assert_too_large(catmull_clark_levels(big, 14, 15).unwrap_err(), "Catmull-Clark", 15);
        // a step of a small mesh passes
        assert!(
            catmull_clark_step(&cube, 1, &cc).is_ok()
                && butterfly_step(&tetra, 1, &ButterflyOptions::default()).is_ok()
        );
    }
}
