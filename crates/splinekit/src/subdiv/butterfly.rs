//! Modified butterfly subdivision of triangle meshes (Zorin, Schröder and Sweldens 1996), an
//! interpolating scheme, with OpenMesh's rules and boundary handling
//! (`Subdivider::Uniform::ModifiedButterflyT`).
//!
//! One level splits every triangle into four as Loop's scheme does (the parent's
//! vertices keep their indices, then one new vertex per edge in edge order, triangles
//! `(v₀, m₀₁, m₂₀)`, `(v₁, m₁₂, m₀₁)`, `(v₂, m₂₀, m₁₂)`, `(m₀₁, m₁₂, m₂₀)` for each parent
//! triangle in order; orientation kept), but **old vertices do not move**: the surface passes
//! through every vertex of every level. The new vertex on edge `a–b`:
//! - **boundary edge**: the four-point rule along the boundary,
//!   `9/16·(a + b) − 1/16·(a₋ + b₊)` with `a₋`, `b₊` the boundary neighbours beyond `a` and `b`;
//! - **interior edge whose ends are each regular (valence 6) or on the boundary**: the
//!   eight-point butterfly
//!   `1/2·(a + b) + 1/8·(c + d) − 1/16·(w₁ + w₂ + w₃ + w₄)`, with `c`, `d` the vertices opposite
//!   the edge in its two triangles and `wᵢ` the vertices opposite the four other edges of those
//!   triangles, across them; a wing missing because that edge is on the boundary is
//!   reflected: for the edge `x–y` of the triangle `x, y, z`, `x + y − z`;
//! - **otherwise**, for each end that is an interior vertex of valence `K ≠ 6`, Zorin's mask
//!   over its ring `q₀ = ` the other end, `q₁, …, q_{K−1}` around it: `Σ sⱼ·qⱼ + (1 − Σ sⱼ)·p`
//!   with `s = 5/12, −1/12, −1/12` for `K = 3`, `3/8, 0, −1/8, 0` for `K = 4`, and
//!   `sⱼ = (1/4 + cos(2πj/K) + 1/2·cos(4πj/K))/K` otherwise (the centre weight is then 3/4);
//!   the average of the two when both ends are such vertices.
//!
//! Valence counts edges (a boundary vertex with `k` triangles has valence `k + 1`). An interior
//! vertex of valence 2 (two triangles glued along two edges) takes the general formula.
//!
//! A closed mesh `V, E, F` becomes `V + E, 2E + 3F, 4F`, as with Loop.
//!
//! **Attributes.** Colours (per vertex) follow the position weights; with
//! [`ButterflyOptions::color_by_level`] new vertices are coloured by their level instead
//! ([`LEVEL_COLORS`](super::LEVEL_COLORS)). UVs are carried the same way where every vertex has one UV (no seams);
//! UVs with seams, and normals, are dropped (a subdivided surface's normals are computed from
//! it).
//!
//! The mesh must be manifold and consistently oriented; the error names the first edge or
//! vertex that is not, or the first face that is not a triangle.

use rayon::prelude::*;

use super::attribute::Attribute;
use super::counts::{self, Counts};
use super::error::{SubdivError, triangles_only};
use super::rings::Rings;
use super::topology::{MIN_LEN, MIN_RINGS};
use super::triangles::{TriangleLevel, triangle_level, triangle_levels};
use crate::mesh::{NONE, PolyMesh};

/// Options of modified butterfly subdivision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ButterflyOptions {
    /// Colour the vertices by the level they were born at ([`LEVEL_COLORS`](super::LEVEL_COLORS)), replacing any
    /// input colours.
    pub color_by_level: bool,
}

/// Subdivides the triangle mesh `mesh` `levels` times with the modified butterfly scheme (see
/// the [module docs](self)). Positions, colours and seamless UVs are carried; normals are
/// dropped.
///
/// # Errors
///
/// [`SubdivError::NotTriangles`] for a face that is not a triangle, [`SubdivError::Topology`]
/// for an edge used by more than two faces or twice in the same direction, or a vertex whose
/// faces form several fans; [`SubdivError::TooLarge`] if the result would not fit `u32`
/// indices (checked before any level is made).
pub fn butterfly_subdivide(
    mesh: &PolyMesh,
    levels: usize,
    options: &ButterflyOptions,
) -> Result<PolyMesh, SubdivError> {
    let check = |base| counts::loop_levels("butterfly", "vertices", base, 0, levels).map(|_| ());
    triangle_levels(mesh, levels, "butterfly", check, |rings, depth| step(rings, depth, options))
}

/// One level of [`butterfly_subdivide`]: the child of `mesh`, which is level `depth − 1` of
/// the subdivision (`depth` picks the colour of the new vertices with
/// [`ButterflyOptions::color_by_level`]; at depth 1 the mesh's own vertices get
/// [`LEVEL_COLORS`](super::LEVEL_COLORS)`[0]`). Refining level by level gives the same meshes as one call.
///
/// # Errors
///
/// As [`butterfly_subdivide`].
pub fn butterfly_step(mesh: &PolyMesh, depth: usize, options: &ButterflyOptions) -> Result<PolyMesh, SubdivError> {
    triangles_only(mesh, "butterfly")?;
    let rings = Rings::new(mesh)?;
    let parent_depth = depth.saturating_sub(1);
    counts::loop_levels("butterfly", "vertices", Counts::of_rings(&rings), parent_depth, parent_depth + 1)?;
    Ok(step(&rings, depth, options))
}

/// [`butterfly_step`] of a mesh known to be all triangles, from its adjacency `rings`.
fn step(rings: &Rings<'_>, depth: usize, options: &ButterflyOptions) -> PolyMesh {
    let plan = Plan::new(rings);
    triangle_level(rings.mesh, depth, options.color_by_level, &plan)
}

/// What one level needs besides the adjacency: each vertex's valence and whether it is on
/// the boundary, and Zorin's masks for the valences present.
struct Plan<'r, 'a> {
    rings: &'r Rings<'a>,
    /// Per vertex: its valence (edges), and the top bit set when it is on the boundary.
    kind: Vec<u32>,
    /// Per valence `K`: the ring weights `s₀ … s_{K−1}`, then the centre weight.
    masks: Vec<Vec<f64>>,
}

/// The bit of [`Plan::kind`] marking a boundary vertex.
const BOUNDARY: u32 = 1 << 31;

impl<'r, 'a> Plan<'r, 'a> {
    fn new(rings: &'r Rings<'a>) -> Self {
        let nv = rings.mesh.num_vertices() as u32;
        let mut kind = Vec::new();
        (0..nv)
            .into_par_iter()
            .with_min_len(MIN_RINGS)
            .map(|v| {
                let corners = rings.adj.corners_of(v).len() as u32;
                if rings.boundary_neighbours(v).is_some() { (corners + 1) | BOUNDARY } else { corners }
            })
            .collect_into_vec(&mut kind);
        let max = kind.iter().map(|k| k & !BOUNDARY).max().unwrap_or(0) as usize;
        let masks = (0..=max).map(zorin_mask).collect();
        Self { rings, kind, masks }
    }

    /// The new value on edge `e` (see the module docs).
    fn edge_point<T: Attribute>(&self, p: &[T], e: u32) -> T {
        let (adj, fv) = (&self.rings.adj, &self.rings.mesh.face_vertices);
        let at = |v: u32| p[v as usize];
        let c = adj.edge_corner[e as usize];
        let (a, b) = (fv[c as usize], adj.to[c as usize]);
        let t = adj.twin[c as usize];
        if t == NONE {
            let beyond_a = self.rings.boundary_neighbours(a).map_or(b, |(_, arriving)| arriving);
            let beyond_b = self.rings.boundary_neighbours(b).map_or(a, |(leaving, _)| leaving);
            return (at(a) + at(b)) * (9.0 / 16.0) + (at(beyond_a) + at(beyond_b)) * (-1.0 / 16.0);
        }
        let (ka, kb) = (self.kind[a as usize], self.kind[b as usize]);
        let (va, vb) = (ka & !BOUNDARY, kb & !BOUNDARY);
        let (ba, bb) = (ka & BOUNDARY != 0, kb & BOUNDARY != 0);
        if (va == 6 || ba) && (vb == 6 || bb) {
            // The apexes of the two triangles, and the wings across their other edges.
            let wing = |x: u32, third: u32| {
                let tw = adj.twin[x as usize];
                if tw == NONE {
                    at(fv[x as usize]) + at(adj.to[x as usize]) + at(third) * -1.0
                } else {
                    at(adj.to[next(tw) as usize])
                }
            };
            let (apex_c, apex_t) = (adj.to[next(c) as usize], adj.to[next(t) as usize]);
            let wings = wing(next(c), a) + wing(prev(c), b) + wing(next(t), b) + wing(prev(t), a);
            return (at(a) + at(b)) * 0.5 + (at(apex_c) + at(apex_t)) * 0.125 + wings * (-1.0 / 16.0);
        }
        let mut sum = T::default();
        let mut count = 0.0;
        for (end, corner, valence, boundary) in [(a, c, va, ba), (b, t, vb, bb)] {
            if valence != 6 && !boundary {
                let mask = &self.masks[valence as usize];
                let ring =
                    self.rings.fan(corner).zip(mask).fold(T::default(), |s, (q, &w)| s + at(adj.to[q as usize]) * w);
                sum = sum + ring + at(end) * mask[valence as usize];
                count += 1.0;
            }
        }
        sum * (1.0 / count)
    }
}

impl TriangleLevel for Plan<'_, '_> {
    /// The child values: the parent's vertices, then one per edge.
    fn refine<T: Attribute>(&self, p: &[T]) -> Vec<T> {
        let ne = self.rings.adj.num_edges();
        let edges = (0..ne as u32).into_par_iter().with_min_len(MIN_LEN / 4).map(|e| self.edge_point(p, e));
        let mut out = Vec::new();
        p.par_iter().copied().chain(edges).collect_into_vec(&mut out);
        out
    }

    /// The child triangles, four per parent triangle (see the module docs).
    fn child_triangles(&self) -> Vec<u32> {
        let nv = self.rings.mesh.num_vertices() as u32;
        let (fv, edge_of) = (&self.rings.mesh.face_vertices, &self.rings.adj.edge_of);
        let mut triangles: Vec<[[u32; 3]; 4]> = Vec::new();
        (0..self.rings.mesh.num_faces())
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|f| {
                let v = [fv[3 * f], fv[3 * f + 1], fv[3 * f + 2]];
                let m = [nv + edge_of[3 * f], nv + edge_of[3 * f + 1], nv + edge_of[3 * f + 2]];
                [[v[0], m[0], m[2]], [v[1], m[1], m[0]], [v[2], m[2], m[1]], m]
            })
            .collect_into_vec(&mut triangles);
        bytemuck::cast_vec(triangles)
    }
}

/// Zorin's weights for an interior vertex of valence `k`: the ring's `s₀ … s_{k−1}` (`s₀` for
/// the other end of the edge), then the centre's `1 − Σ sⱼ`.
fn zorin_mask(k: usize) -> Vec<f64> {
    match k {
        3 => vec![5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0, 0.75],
        4 => vec![3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0, 0.75],
        _ => {
            let inv = 1.0 / k as f64;
            let mut w: Vec<f64> = (0..k)
                .map(|j| {
                    let angle = core::f64::consts::TAU * j as f64 * inv;
                    (0.25 + angle.cos() + 0.5 * (2.0 * angle).cos()) * inv
                })
                .collect();
            let sum: f64 = w.iter().sum();
            w.push(1.0 - sum);
            w
        }
    }
}

/// The next corner of the same triangle.
#[inline]
fn next(c: u32) -> u32 {
    if c % 3 == 2 { c - 2 } else { c + 1 }
}

/// The previous corner of the same triangle.
#[inline]
fn prev(c: u32) -> u32 {
    if c.is_multiple_of(3) { c + 2 } else { c - 1 }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    /// An open grid of `n × n` squares, each split into two triangles, in the plane
    /// `z = 0.3x − 0.2y + 1`.
    fn planar_grid(n: u32) -> PolyMesh {
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (f64::from(i), f64::from(j))))
            .map(|(x, y)| DVec3::new(x, y, 0.3 * x - 0.2 * y + 1.0))
            .collect();
        let g = |i: u32, j: u32| j * (n + 1) + i;
        let triangles: Vec<[u32; 3]> = (0..n)
            .flat_map(|j| {
                (0..n).flat_map(move |i| {
                    [[g(i, j), g(i + 1, j), g(i + 1, j + 1)], [g(i, j), g(i + 1, j + 1), g(i, j + 1)]]
                })
            })
            .collect();
        PolyMesh::from_triangles(positions, &triangles)
    }

    #[test]
    fn old_vertices_stay_and_a_plane_stays_a_plane() {
        let mesh = planar_grid(4);
        let fine = butterfly_subdivide(&mesh, 2, &ButterflyOptions::default()).unwrap();
        // V + E, 2E + 3F, 4F per level: (25, 56, 32) → (81, 208, 128) → (289, ·, 512)
        assert_eq!((fine.num_vertices(), fine.num_faces()), (289, 512));
        assert_eq!(&fine.positions[..mesh.num_vertices()], &mesh.positions[..], "interpolating");
        for p in &fine.positions {
            assert!((p.z - (0.3 * p.x - 0.2 * p.y + 1.0)).abs() < 1e-12, "{p} left the plane");
        }
    }

    #[test]
    fn non_triangles_are_refused() {
        let quad = PolyMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::ONE, DVec3::Y],
            face_offsets: vec![0, 4],
            face_vertices: vec![0, 1, 2, 3],
            ..PolyMesh::default()
        };
        let err = butterfly_subdivide(&quad, 1, &ButterflyOptions::default()).unwrap_err();
        assert!(err.to_string().contains("butterfly"), "{err}");
    }

    #[test]
    fn masks_sum_to_one_and_are_symmetric() {
        for k in 2..40 {
            let m = zorin_mask(k);
            assert_eq!(m.len(), k + 1);
            assert!((m.iter().sum::<f64>() - 1.0).abs() < 1e-15, "valence {k}");
            for j in 1..k {
                assert!((m[j] - m[k - j]).abs() < 1e-15, "valence {k}, weight {j}");
            }
            if k >= 3 {
                assert!((m[k] - 0.75).abs() < 1e-15, "valence {k}: centre {}", m[k]);
            }
        }
    }
}
