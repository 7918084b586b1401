//! √3 subdivision of triangle meshes (Kobbelt 2000), with CGAL's rules
//! (`Subdivision_method_3::Sqrt3_subdivision`, `Sqrt3_mask_3`), boundaries included.
//!
//! One level puts a new vertex in every triangle, joins it to the triangle's corners and
//! flips every old interior edge, so that it joins the two new vertices on either side:
//! three triangles per triangle, rotated by 30° against the old ones. Two levels split every
//! edge into three (hence the name). The child's vertices are, in this order:
//! - the parent's vertices, same index: interior, valence `n`, neighbours `qᵢ`:
//!   `(1 − α)·p + α/n·Σqᵢ` with `α(n) = (4 − 2cos(2π/n))/9`; on a boundary see below; a
//!   vertex without faces stays;
//! - one **face point** per parent triangle: its centroid (but see below);
//! - on boundary levels only, a second boundary point per boundary triangle (below).
//!
//! **Boundaries**, as CGAL, which follows Kobbelt: the boundary is refined only on every
//! second level (levels 2, 4, … of one call), where a ternary rule splits each boundary
//! edge into three. On the other levels (1, 3, …) boundary vertices stay where they are and
//! boundary edges are not flipped: a boundary triangle `(u, w, x)` with the boundary edge
//! `u → w` keeps the child `(u, w, m)` (`m` its face point). On a boundary level, such a
//! triangle (after a first level it has exactly one boundary edge) gets no centroid but two
//! points on that edge, with `u₋`, `w₊` the boundary neighbours of `u` and `w` beyond the
//! edge: `(u₋ + 16u + 10w)/27` next to `u` (the triangle's face point) and
//! `(10u + 16w + w₊)/27` next to `w` (numbered after all face points, in triangle order), and
//! each boundary vertex `p` with boundary neighbours `a`, `b` moves to `(4a + 19p + 4b)/27`.
//! The triangle becomes `(u, n₁, x)`, `(n₁, n₂, x)`, `(n₂, w, x)`, and the flips of its edges
//! `w → x` and `x → u` join `n₂` and `n₁` to the points across them. Interior vertices are
//! smoothed on every level. A closed mesh is never a boundary case: every level maps
//! `(V, F)` to `(V + F, 3F)`; with `B` boundary edges a boundary level gives `V + F + B`.
//!
//! Child triangle `c` comes from corner `c` of the parent (its half-edge `a → b` in triangle
//! `f`): across an interior edge, `(b, m_f, m_g)` with `m_f`, `m_g` the points on this and the
//! other side (the face points, or `n₂`, `n₁` of a boundary triangle, for its edges `w → x`,
//! `x → u`); on a boundary edge `(a, b, m_f)` or, on a boundary level, `(n₁, n₂, x)`. All are
//! counter-clockwise like the parent: orientation is kept.
//!
//! **Attributes.** Colours (per vertex) follow the position weights; with
//! [`Sqrt3Options::color_by_level`] new vertices are coloured by their level instead
//! ([`LEVEL_COLORS`](super::LEVEL_COLORS)). UVs are carried the same way where every vertex has one UV (no seams);
//! UVs with seams, and normals, are dropped (a subdivided surface's normals are computed from
//! it).
//!
//! The mesh must be manifold and consistently oriented; the error names the first edge or
//! vertex that is not, or the first face that is not a triangle.

use rayon::prelude::*;

use super::attribute::Attribute;
use super::counts;
use super::error::SubdivError;
use super::rings::Rings;
use super::topology::{MIN_LEN, MIN_RINGS};
use super::triangles::{TriangleLevel, triangle_level, triangle_levels};
use crate::mesh::{NONE, PolyMesh};

/// Options of √3 subdivision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Sqrt3Options {
    /// Colour the vertices by the level they were born at ([`LEVEL_COLORS`](super::LEVEL_COLORS)), replacing any
    /// input colours.
    pub color_by_level: bool,
}

/// Subdivides the triangle mesh `mesh` `levels` times with √3 subdivision (see the [module
/// docs](self)): levels 2, 4, … refine the boundary, as in one call of CGAL's
/// `Sqrt3_subdivision`. Positions, colours and seamless UVs are carried; normals are dropped.
///
/// # Errors
///
/// [`SubdivError::NotTriangles`] for a face that is not a triangle, [`SubdivError::Topology`]
/// for an edge used by more than two faces or twice in the same direction, or a vertex whose
/// faces form several fans; [`SubdivError::TooLarge`] if the result would not fit `u32`
/// indices (checked before any level is made).
pub fn sqrt3_subdivide(mesh: &PolyMesh, levels: usize, options: &Sqrt3Options) -> Result<PolyMesh, SubdivError> {
    let check = |base| counts::sqrt3_levels(base, levels).map(|_| ());
    triangle_levels(mesh, levels, "√3", check, |rings, depth| step(rings, depth, options))
}

/// Level `depth` of the subdivision from level `depth − 1`, the mesh of `rings` (all
/// triangles); the boundary is refined when `depth` is even.
fn step(rings: &Rings<'_>, depth: usize, options: &Sqrt3Options) -> PolyMesh {
    let plan = Plan::new(rings, depth.is_multiple_of(2));
    triangle_level(rings.mesh, depth, options.color_by_level, &plan)
}

/// One level's numbering: which triangles have a boundary edge refined, and where their
/// second boundary points go.
struct Plan<'r, 'a> {
    rings: &'r Rings<'a>,
    /// Whether this level refines the boundary.
    border: bool,
    /// On a boundary level, per triangle: its boundary corner (half-edge), or [`NONE`].
    border_corner: Vec<u32>,
    /// Per triangle with a boundary corner: the index of its second boundary point.
    second: Vec<u32>,
    /// The triangles with a boundary corner, in order.
    boundary_faces: Vec<u32>,
}

impl<'r, 'a> Plan<'r, 'a> {
    fn new(rings: &'r Rings<'a>, border: bool) -> Self {
        let (nv, nf) = (rings.mesh.num_vertices() as u32, rings.mesh.num_faces() as u32);
        let (mut border_corner, mut second, mut boundary_faces) = (Vec::new(), Vec::new(), Vec::new());
        if border {
            // after a first level a triangle has at most one boundary edge (as CGAL assumes)
            (0..nf)
                .into_par_iter()
                .with_min_len(MIN_LEN)
                .map(|f| (3 * f..3 * f + 3).find(|&c| rings.adj.twin[c as usize] == NONE).unwrap_or(NONE))
                .collect_into_vec(&mut border_corner);
            second = vec![NONE; nf as usize];
            for (f, &c) in border_corner.iter().enumerate() {
                if c != NONE {
                    second[f] = nv + nf + boundary_faces.len() as u32;
                    boundary_faces.push(f as u32);
                }
            }
        }
        Self { rings, border, border_corner, second, boundary_faces }
    }

    /// The boundary corner of triangle `f` on a boundary level, or [`NONE`].
    #[inline]
    fn boundary_corner(&self, f: usize) -> u32 {
        if self.border { self.border_corner[f] } else { NONE }
    }

    /// The new value of parent vertex `v`.
    fn vertex_point<T: Attribute>(&self, p: &[T], v: usize) -> T {
        let pv = p[v];
        let corners = self.rings.adj.corners_of(v as u32);
        if corners.is_empty() {
            return pv;
        }
        if let Some((a, b)) = self.rings.boundary_neighbours(v as u32) {
            if !self.border {
                return pv;
            }
            return (p[a as usize] * 4.0 + pv * 19.0 + p[b as usize] * 4.0) * (1.0 / 27.0);
        }
        let n = corners.len() as f64;
        let alpha = (4.0 - 2.0 * (core::f64::consts::TAU / n).cos()) / 9.0;
        let ring = corners.iter().fold(T::default(), |s, &c| s + p[self.rings.adj.to[c as usize] as usize]);
        pv * (1.0 - alpha) + ring * (alpha / n)
    }

    /// The child vertex on the side of corner `c`'s triangle across `c`'s edge: the face
    /// point, or on a boundary level one of a boundary triangle's two boundary points.
    #[inline]
    fn apex(&self, c: u32) -> u32 {
        let f = c / 3;
        let point = self.rings.mesh.num_vertices() as u32 + f;
        let b = self.boundary_corner(f as usize);
        if b != NONE && c == next(b) { self.second[f as usize] } else { point }
    }
}

impl TriangleLevel for Plan<'_, '_> {
    /// The child values: the parent's vertices, the face points, the second boundary points.
    fn refine<T: Attribute>(&self, p: &[T]) -> Vec<T> {
        let (nv, nf) = (self.rings.mesh.num_vertices(), self.rings.mesh.num_faces());
        let (fv, to) = (&self.rings.mesh.face_vertices, &self.rings.adj.to);
        let at = |v: u32| p[v as usize];
        let third = 1.0 / 27.0;
        let vertices = (0..nv).into_par_iter().with_min_len(MIN_RINGS).map(|v| self.vertex_point(p, v));
        let faces = (0..nf).into_par_iter().with_min_len(MIN_LEN).map(|f| {
            let c = self.boundary_corner(f);
            if c == NONE {
                let t = &fv[3 * f..3 * f + 3];
                return (at(t[0]) + at(t[1]) + at(t[2])) * (1.0 / 3.0);
            }
            // n₁, next to u on the boundary edge u → w
            let (u, w) = (fv[c as usize], to[c as usize]);
            let (_, before) = self.rings.boundary_neighbours(u).expect("a boundary vertex");
            (at(before) + at(u) * 16.0 + at(w) * 10.0) * third
        });
        let seconds = self.boundary_faces.par_iter().with_min_len(MIN_RINGS).map(|&f| {
            // n₂, next to w
            let c = self.border_corner[f as usize];
            let (u, w) = (fv[c as usize], to[c as usize]);
            let (after, _) = self.rings.boundary_neighbours(w).expect("a boundary vertex");
            (at(u) * 10.0 + at(w) * 16.0 + at(after)) * third
        });
        let mut out = Vec::new();
        vertices.chain(faces).chain(seconds).collect_into_vec(&mut out);
        out
    }

    /// The child triangles, one per parent corner (see the module docs).
    fn child_triangles(&self) -> Vec<u32> {
        let nv = self.rings.mesh.num_vertices() as u32;
        let (fv, to, twin) = (&self.rings.mesh.face_vertices, &self.rings.adj.to, &self.rings.adj.twin);
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        (0..fv.len() as u32)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|c| {
                let t = twin[c as usize];
                if t != NONE {
                    [to[c as usize], self.apex(c), self.apex(t)]
                } else if self.border {
                    let f = c / 3;
                    [nv + f, self.second[f as usize], to[next(c) as usize]]
                } else {
                    [fv[c as usize], to[c as usize], nv + c / 3]
                }
            })
            .collect_into_vec(&mut triangles);
        bytemuck::cast_vec(triangles)
    }
}

/// The next corner of the same triangle.
#[inline]
fn next(c: u32) -> u32 {
    if c % 3 == 2 { c - 2 } else { c + 1 }
}
