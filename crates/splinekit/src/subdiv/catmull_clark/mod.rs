//! Catmull-Clark subdivision of polygon meshes, with OpenSubdiv's `catmark`
//! weights and boundary rules.
//!
//! One level turns every `n`-gon into `n` quads. The child's vertices are, in this order:
//! - one **vertex point** per parent vertex `P` (the evens, same index):
//!   interior, valence `n`: `((n − 2)·P + (Σ neighbours)/n + (Σ face points)/n) / n`;
//!   boundary: `3/4·P + 1/8·(a + b)` with `a`, `b` its neighbours along the boundary (a
//!   crease), or `P` itself for a corner with [`BoundaryRule::Corners`] (a boundary vertex
//!   of one face: OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER`); a vertex without faces stays;
//! - one **edge point** per parent edge (numbered as [`Adjacency::edge_of`](crate::mesh::Adjacency::edge_of)):
//!   `(v₀ + v₁ + f₀ + f₁)/4` with the two face points `f`, the midpoint on a boundary;
//! - one **face point** per parent face: the average of its corners.
//!
//! Child face `k` of parent face `f` (its corners `c₀ … cₙ₋₁` counter-clockwise) is the quad
//! `(vertex point cₖ, edge point cₖcₖ₊₁, face point f, edge point cₖ₋₁cₖ)`, counter-clockwise
//! like its parent; the children of face 0 come first. Colours follow the same weights.
//!
//! **Speed.** [`catmull_clark_subdivide`] builds the general adjacency once, for the base mesh;
//! every level below is all quads, whose adjacency follows from its parent's in closed form
//! (`quads`), and the finest level is made straight from the tables two levels above it, so
//! for three levels only the base level and level 1 (or, for a base that is not all quads,
//! level 1 alone) get tables. Every pass is a parallel map (rayon) writing its own output
//! slots; the results are the same to the bit as level by level with [`catmull_clark_step`],
//! on any number of threads. One exception: three levels of a *regular* quad mesh (closed,
//! every vertex of valence 4, such as a torus of quads) are made a base face at a time from
//! the bicubic B-spline's weights (`regular`), with no values of levels 1 and 2; the same
//! mesh, with positions and colours equal to rounding (a few ulps), and the same on any
//! number of threads.
//!
//! **Non-manifold and degenerate meshes** (an edge of more than two faces or of two faces
//! running the same way, a vertex whose faces form several fans, a face that repeats a vertex)
//! are subdivided with OpenSubdiv's rules: their non-manifold edges are infinitely sharp
//! creases and their non-manifold vertices corners (see [`nonmanifold`](super::nonmanifold)), level by
//! level through the subdivision matrices, so more slowly; [`crate::mesh::split_nonmanifold`]
//! splits such a mesh apart instead, which gives another surface. Face-varying normals and UVs
//! are not carried (a subdivided surface's normals are computed from it).

use rayon::prelude::*;

mod quad_levels;
mod regular_three_levels;

use quad_levels::QuadLevel;

use super::attribute::Attribute;
use super::counts::{self, Counts};
use super::crease::Creases;
use super::error::{SubdivError, polygons_only};
use super::level_colors::{child_colors, parent_colors};
use super::nonmanifold::General;
use super::options::{BoundaryRule, CatmullClarkOptions, CreasingMethod};
use super::rings::Rings;
use super::topology::MIN_LEN;
use crate::mesh::{NONE, PolyMesh};

/// Subdivides `mesh` `levels` times with Catmull-Clark's rules (see the [module
/// docs](self)). Positions and per-vertex colours are carried; face-varying normals and UVs
/// are dropped.
///
/// # Errors
///
/// [`SubdivError::Topology`] for a vertex index out of range; [`SubdivError::TooLarge`] if the
/// result would not fit `u32` indices (checked before any level is made).
pub fn catmull_clark_subdivide(
    mesh: &PolyMesh,
    levels: usize,
    options: &CatmullClarkOptions,
) -> Result<PolyMesh, SubdivError> {
    if levels == 0 {
        polygons_only(mesh)?;
        return Ok(PolyMesh { normals: None, uvs: None, ..mesh.clone() });
    }
    let mut rings = match Rings::new(mesh) {
        Err(SubdivError::Topology(e)) if e.is_nonmanifold() => return general(mesh, levels, options),
        rings => rings?,
    };
    rings.triangles = options.triangles;
    counts::catmull_clark_levels(Counts::of_rings(&rings), 0, levels)?;
    let all_quads = mesh.face_vertices.len() == 4 * mesh.num_faces()
        && mesh.face_offsets.iter().enumerate().all(|(f, &o)| o as usize == 4 * f);
    if all_quads && levels > 1 {
        // Quads from the start: the base level's tables are the adjacency's.
        let level = QuadLevel::from_quad_rings(rings);
        if levels == 3 && regular_three_levels::is_regular(&level) {
            // every face a regular quad: three levels a base face at a time
            let carried: &[_] = if mesh.colors.len() == mesh.positions.len() { &mesh.colors } else { &[] };
            return Ok(regular_three_levels::subdivide3(level, &mesh.positions, carried, options.color_by_level));
        }
        let colors = parent_colors(mesh, options.color_by_level, 1).into_owned();
        return Ok(quad_levels::subdivide(level, mesh.positions.clone(), colors, 0, levels, options));
    }
    let positions = rings.refine(&mesh.positions, options.boundary);
    let parent = parent_colors(mesh, options.color_by_level, 1);
    let colors =
        child_colors(options.color_by_level, &parent, positions.len(), 1, |c| rings.refine(c, options.boundary));
    if levels == 1 {
        let (face_offsets, face_vertices) = rings.child_faces();
        return Ok(PolyMesh { positions, colors, face_offsets, face_vertices, normals: None, uvs: None });
    }
    // Every level below the first is all quads: closed-form tables from here on.
    let level = QuadLevel::from_rings(&rings);
    Ok(quad_levels::subdivide(level, positions, colors, 1, levels, options))
}

/// One level of [`catmull_clark_subdivide`]: the child of `mesh`, which is level `depth − 1`
/// of the subdivision (`depth` picks the colour of the new vertices with
/// [`CatmullClarkOptions::color_by_level`]; at depth 1 the mesh's own vertices get
/// [`LEVEL_COLORS`](super::LEVEL_COLORS)`[0]`). Refining level by level gives the same meshes as one call,
/// except on a non-manifold mesh whose levels have faces that repeat a vertex or edges whose
/// faces run the same way: each call takes its mesh as a base mesh, and OpenSubdiv's tags of
/// the levels below (which edge halves stay apart, which vertices stay creases) are not in a
/// mesh.
///
/// # Errors
///
/// As [`catmull_clark_subdivide`].
pub fn catmull_clark_step(
    mesh: &PolyMesh,
    depth: usize,
    options: &CatmullClarkOptions,
) -> Result<PolyMesh, SubdivError> {
    let mut rings = match Rings::new(mesh) {
        Err(SubdivError::Topology(e)) if e.is_nonmanifold() => {
            // the colours of this level are made from the parent's, by level or not
            return general(mesh, 1, &CatmullClarkOptions { color_by_level: false, ..*options }).map(|mut fine| {
                if options.color_by_level {
                    let parent = parent_colors(mesh, true, depth);
                    fine.colors = child_colors(true, &parent, fine.positions.len(), depth, |c| c.to_vec());
                }
                fine
            });
        }
        rings => rings?,
    };
    rings.triangles = options.triangles;
    let parent_depth = depth.saturating_sub(1);
    counts::catmull_clark_levels(Counts::of_rings(&rings), parent_depth, parent_depth + 1)?;
    let positions = rings.refine(&mesh.positions, options.boundary);
    let parent = parent_colors(mesh, options.color_by_level, depth);
    let colors =
        child_colors(options.color_by_level, &parent, positions.len(), depth, |c| rings.refine(c, options.boundary));
    let (face_offsets, face_vertices) = rings.child_faces();
    Ok(PolyMesh { positions, colors, face_offsets, face_vertices, normals: None, uvs: None })
}

/// [`catmull_clark_subdivide`] of a non-manifold or degenerate mesh, with OpenSubdiv's rules
/// (see [`nonmanifold`](super::nonmanifold)).
fn general(mesh: &PolyMesh, levels: usize, options: &CatmullClarkOptions) -> Result<PolyMesh, SubdivError> {
    let no = Creases::default();
    let general = General::catmark(options, &no, CreasingMethod::default());
    general.subdivide(mesh, levels, options.color_by_level).map(|(m, ..)| m)
}

/// Catmull-Clark's values and faces of the child level.
impl Rings<'_> {
    /// The child values: vertex points, edge points, face points.
    fn refine<T: Attribute>(&self, p: &[T], boundary: BoundaryRule) -> Vec<T> {
        let (nv, ne, nf) = (self.mesh.num_vertices(), self.adj.num_edges(), self.mesh.num_faces());
        let face_point = |f: usize| {
            let corners = self.mesh.face(f);
            let sum = corners.iter().fold(T::default(), |s, &v| s + p[v as usize]);
            sum * (1.0 / corners.len() as f64)
        };
        let faces: Vec<T> = (0..nf).into_par_iter().with_min_len(MIN_LEN).map(face_point).collect();
        let mut out = Vec::new();
        let vertices = (0..nv).into_par_iter().with_min_len(MIN_LEN).map(|v| self.vertex_point(p, &faces, v, boundary));
        let edges = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
            let c = self.adj.edge_corner[e];
            let (a, b) = (p[self.mesh.face_vertices[c as usize] as usize], p[self.adj.to[c as usize] as usize]);
            let t = self.adj.twin[c as usize];
            if t == NONE {
                return (a + b) * 0.5;
            }
            let (g0, g1) = (self.adj.face_of[c as usize] as usize, self.adj.face_of[t as usize] as usize);
            let (f0, f1) = (faces[g0], faces[g1]);
            match self.triangles.edge_weights(self.mesh.face(g0).len(), self.mesh.face(g1).len()) {
                None => (a + b + f0 + f1) * 0.25,
                Some((end, face)) => (a + b) * end + (f0 + f1) * face,
            }
        });
        vertices.chain(edges).chain(faces.par_iter().copied()).collect_into_vec(&mut out);
        out
    }

    /// The vertex point of vertex `v`.
    fn vertex_point<T: Attribute>(&self, p: &[T], faces: &[T], v: usize, boundary: BoundaryRule) -> T {
        let pv = p[v];
        let corners = self.adj.corners_of(v as u32);
        if corners.is_empty() {
            return pv;
        }
        // boundary: the half-edge leaving along the boundary, and the one arriving
        if let Some((a, b)) = self.boundary_neighbours(v as u32) {
            if boundary == BoundaryRule::Corners && corners.len() == 1 {
                return pv;
            }
            return pv * 0.75 + (p[a as usize] + p[b as usize]) * 0.125;
        }
        // interior: one leaving half-edge per edge and per face
        let n = corners.len() as f64;
        let mut ring = T::default();
        let mut centres = T::default();
        for &c in corners {
            ring = ring + p[self.adj.to[c as usize] as usize];
            centres = centres + faces[self.adj.face_of[c as usize] as usize];
        }
        pv * ((n - 2.0) / n) + (ring + centres) * (1.0 / (n * n))
    }

    /// The child faces (all quads): face offsets and corners.
    pub(super) fn child_faces(&self) -> (Vec<u32>, Vec<u32>) {
        let (nv, ne) = (self.mesh.num_vertices() as u32, self.adj.num_edges() as u32);
        let corners = self.mesh.face_vertices.len();
        let offsets: Vec<u32> = (0..=corners as u32).map(|k| 4 * k).collect();
        let mut quads: Vec<[u32; 4]> = Vec::with_capacity(corners);
        (0..corners as u32)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|c| {
                [
                    self.mesh.face_vertices[c as usize],
                    nv + self.adj.edge_of[c as usize],
                    nv + ne + self.adj.face_of[c as usize],
                    nv + self.adj.edge_of[self.prev(c) as usize],
                ]
            })
            .collect_into_vec(&mut quads);
        let quads: Vec<u32> = bytemuck::cast_vec(quads);
        (offsets, quads)
    }
}
