//! [`Rings`]: a polygon mesh with its adjacency, checked to be manifold: what one level of
//! Catmull-Clark, √3, Doo-Sabin, butterfly or the crease rules reads.

use rayon::prelude::*;

use super::error::{SubdivError, polygons_only, repeated_vertex};
use super::options::TriangleSubdivision;
use super::topology::{MIN_RINGS, TopologyError};
use crate::mesh::{Adjacency, NONE, NonManifold, PolyMesh};

/// What one level needs: the mesh's faces and their adjacency, checked to be manifold.
pub(super) struct Rings<'a> {
    pub(super) mesh: &'a PolyMesh,
    pub(super) adj: Adjacency,
    /// The edge points next to triangles ([`TriangleSubdivision::Catmark`] unless set).
    pub(super) triangles: TriangleSubdivision,
}

impl<'a> Rings<'a> {
    /// The adjacency of `mesh`; an error for the first face of fewer than three corners, else
    /// the first face that repeats a vertex, else the first non-manifold or inconsistently
    /// oriented edge or vertex.
    pub(super) fn new(mesh: &'a PolyMesh) -> Result<Self, SubdivError> {
        polygons_only(mesh)?;
        if let Some((face, vertex)) = repeated_vertex(mesh) {
            return Err(TopologyError::RepeatedVertex { face: face as u32, vertex }.into());
        }
        let adj = Adjacency::build(mesh);
        if let Some(problem) = adj.nonmanifold.first() {
            return Err(TopologyError::NonManifold(problem.clone()).into());
        }
        // a manifold vertex's corners form one fan: rotating from its boundary half-edge (or
        // any corner) reaches them all
        let rings = Self { mesh, adj, triangles: TriangleSubdivision::Catmark };
        let bad = (0..mesh.num_vertices() as u32).into_par_iter().with_min_len(MIN_RINGS).find_first(|&v| {
            let corners = rings.adj.corners_of(v);
            let Some(&first) = corners.first() else { return false };
            let start = corners.iter().copied().find(|&c| rings.adj.twin[c as usize] == NONE).unwrap_or(first);
            rings.fan(start).take(corners.len() + 1).count() != corners.len()
        });
        if let Some(v) = bad {
            let fans = rings.adj.fans(mesh, v).len() as u32;
            return Err(TopologyError::NonManifold(NonManifold::Vertex { vertex: v, fans }).into());
        }
        Ok(rings)
    }

    /// The corners leaving the vertex of corner `start`, rotating counter-clockwise
    /// (`c → twin(prev(c))`) until a boundary or back at `start`.
    pub(super) fn fan(&self, start: u32) -> impl Iterator<Item = u32> + '_ {
        let mut next = Some(start);
        core::iter::from_fn(move || {
            let c = next?;
            let t = self.adj.twin[self.prev(c) as usize];
            next = (t != NONE && t != start).then_some(t);
            Some(c)
        })
    }

    /// The corner before `c` in its face.
    #[inline]
    pub(super) fn prev(&self, c: u32) -> u32 {
        let f = self.adj.face_of[c as usize] as usize;
        let start = self.mesh.face_offsets[f];
        if c == start { self.mesh.face_offsets[f + 1] - 1 } else { c - 1 }
    }

    /// The neighbours of vertex `v` along the boundary (leaving, arriving), if it is on one.
    pub(super) fn boundary_neighbours(&self, v: u32) -> Option<(u32, u32)> {
        let mut ends = [None, None];
        for &c in self.adj.corners_of(v) {
            if self.adj.twin[c as usize] == NONE {
                ends[0] = Some(self.adj.to[c as usize]);
            }
            let pc = self.prev(c);
            if self.adj.twin[pc as usize] == NONE {
                ends[1] = Some(self.mesh.face_vertices[pc as usize]);
            }
        }
        match ends {
            [Some(a), Some(b)] => Some((a, b)),
            _ => None,
        }
    }
}
