//! Exact limit positions: where each vertex of a mesh ends up after infinitely many levels
//! of Loop or Catmull-Clark subdivision, from closed-form masks over its one-ring (the left
//! eigenvector of the subdivision matrix for the dominant eigenvalue 1), matching the weights
//! and boundary rules chosen.
//!
//! - Loop, interior vertex of valence `n`: `(1 − n·χ)·P + χ·Σ neighbours`, with
//!   `χ = 1 / (n + 3/(8β))` and `β` the even weight of [`LoopWeights`](super::LoopWeights).
//! - Catmull-Clark, interior vertex of valence `n` with quads around it:
//!   `(n²·P + 4·Σ edge neighbours + Σ diagonal neighbours) / (n·(n + 5))`.
//! - Boundary vertices of both: the cubic B-spline limit of the boundary polygon,
//!   `(a + 4·P + b)/6`; a one-face corner with [`BoundaryRule::Corners`] stays where it is, and
//!   so does a vertex without faces.
//!
//! Catmull-Clark's mask needs quads around the vertex; subdivide once first (after one level
//! every face is a quad).

use glam::DVec3;
use rayon::prelude::*;

use super::catmull_clark::{CatmullClarkOptions, Rings};
use super::loop_scheme::{BoundaryRule, LoopOptions, Rules, SubdivError};
use super::topology::MIN_LEN;
use crate::mesh::PolyMesh;

/// The limit of a boundary vertex `p` between boundary neighbours `a` and `b`, or `p` itself
/// for a fixed corner.
fn boundary_limit(rings: &Rings<'_>, p: &[DVec3], v: usize, (a, b): (u32, u32), boundary: BoundaryRule) -> DVec3 {
    if boundary == BoundaryRule::Corners && rings.adj.corners_of(v as u32).len() == 1 {
        return p[v];
    }
    (p[a as usize] + p[v] * 4.0 + p[b as usize]) * (1.0 / 6.0)
}

/// The Loop limit positions of the vertices of the triangle mesh `mesh` (see the [module
/// docs](self)).
///
/// # Errors
///
/// [`SubdivError::NotTriangles`] for a face that is not a triangle, [`SubdivError::Topology`]
/// for a non-manifold or inconsistently oriented edge or vertex.
pub fn loop_limit_positions(mesh: &PolyMesh, options: &LoopOptions) -> Result<Vec<DVec3>, SubdivError> {
    if let Some((face, f)) = mesh.faces().enumerate().find(|(_, f)| f.len() != 3) {
        return Err(SubdivError::NotTriangles { face, corners: f.len(), scheme: "Loop" });
    }
    let rings = Rings::new(mesh)?;
    let rules = Rules::new(options);
    let p = &mesh.positions;
    Ok((0..p.len())
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| {
            let corners = rings.adj.corners_of(v as u32);
            if corners.is_empty() {
                return p[v];
            }
            if let Some(ends) = rings.boundary_neighbours(v as u32) {
                return boundary_limit(&rings, p, v, ends, options.boundary);
            }
            let n = corners.len() as f64;
            let chi = 1.0 / (n + 3.0 / (8.0 * rules.beta(corners.len() as u32)));
            let ring: DVec3 = corners.iter().map(|&c| p[rings.adj.to[c as usize] as usize]).sum();
            p[v] * (1.0 - n * chi) + ring * chi
        })
        .collect())
}

/// The Catmull-Clark limit positions of the vertices of `mesh` (see the [module
/// docs](self)).
///
/// # Errors
///
/// [`SubdivError::NotQuads`] for an interior vertex with a face around it that is not a quad,
/// [`SubdivError::Topology`] for a non-manifold or inconsistently oriented edge or vertex.
pub fn catmull_clark_limit_positions(
    mesh: &PolyMesh,
    options: &CatmullClarkOptions,
) -> Result<Vec<DVec3>, SubdivError> {
    let rings = Rings::new(mesh)?;
    let p = &mesh.positions;
    (0..p.len())
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| {
            let corners = rings.adj.corners_of(v as u32);
            if corners.is_empty() {
                return Ok(p[v]);
            }
            if let Some(ends) = rings.boundary_neighbours(v as u32) {
                return Ok(boundary_limit(&rings, p, v, ends, options.boundary));
            }
            let mut edges = DVec3::ZERO;
            let mut diagonals = DVec3::ZERO;
            for &c in corners {
                let f = rings.adj.face_of[c as usize] as usize;
                let face = mesh.face(f);
                if face.len() != 4 {
                    return Err(SubdivError::NotQuads { vertex: v, face: f, corners: face.len() });
                }
                let k = c as usize - mesh.face_offsets[f] as usize;
                edges += p[rings.adj.to[c as usize] as usize];
                diagonals += p[face[(k + 2) % 4] as usize];
            }
            let n = corners.len() as f64;
            Ok((p[v] * (n * n) + edges * 4.0 + diagonals) * (1.0 / (n * (n + 5.0))))
        })
        .collect()
}
