//! Doo-Sabin subdivision of polygon meshes, with CGAL's weights and boundary handling
//! (`Subdivision_method_3::DooSabin_subdivision`, `DooSabin_mask_3`).
//!
//! A dual scheme: one level makes a new vertex for every **corner** of every face (child
//! vertex `c` for corner `c`), from the corners of its own face only. For corner `c` of an
//! `n`-gon whose corners, from `c` on, are `p₀ = c, p₁, …, pₙ₋₁`:
//! `Σₖ wₖ·pₖ` with `w₀ = (n + 5)/(4n)` and `wₖ = (3 + 2cos(2πk/n))/(4n)` (Doo and Sabin's
//! weights; for quads `9/16, 3/16, 1/16, 3/16`, and for triangles `2/3, 1/6, 1/6`). No old
//! vertex is kept. The child's faces are, in this order:
//! - an **F-face** per parent face: its corners' points, in the same order (the face shrunk);
//! - an **E-face** per interior parent edge `a → b` (corner `c` of face `f`, twin corner `t`
//!   of face `g`): the quad `(c + 1, c, t + 1, t)` of the points of `b` and `a` in `f` and of
//!   `a` and `b` in `g`, in parent edge order;
//! - a **V-face** per interior parent vertex: the points of its corners, counter-clockwise
//!   around it (the ring of faces), in vertex order.
//!
//! Every face keeps the parent's orientation. A closed mesh with `V` vertices, `E` edges and
//! `F` faces becomes `Σ(face sizes) = 2E` vertices and `F + E + V` faces.
//!
//! **Boundaries**, as CGAL: boundary edges and boundary vertices get no face, so the
//! surface shrinks away from its boundary, which becomes the outer edges of the F- and
//! E-faces along it (`F + E_interior + V_interior` faces). The corner weights are the same
//! everywhere: the boundary is not interpolated.
//!
//! **Attributes.** Colours (per vertex) and UVs (face-varying, so seams are kept: each new
//! vertex belongs to one face corner) are carried with the position weights; the output's
//! UVs are per vertex. Normals are dropped (a subdivided surface's normals are computed from
//! it). There is no colouring by level: every vertex is new at every level.
//!
//! The mesh must be manifold and consistently oriented; the error names the first edge or
//! vertex that is not. A vertex without faces disappears.

use rayon::prelude::*;

use super::attribute::Attribute;
use super::counts::{self, DooSabin};
use super::error::{SubdivError, polygons_only};
use super::rings::Rings;
use super::topology::{MIN_LEN, MIN_RINGS};
use crate::mesh::{FaceVarying, NONE, PolyMesh};

/// Options of Doo-Sabin subdivision (none yet: CGAL's rules are the only ones).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct DooSabinOptions {}

/// Subdivides the polygon mesh `mesh` `levels` times with Doo-Sabin's rules (see the [module
/// docs](self)). Positions, per-vertex colours and UVs are carried; normals are dropped.
///
/// # Errors
///
/// [`SubdivError::Topology`] for an edge used by more than two faces or twice in the same
/// direction, or a vertex whose faces form several fans; [`SubdivError::TooLarge`] if the
/// result would not fit `u32` indices (checked before any level is made).
pub fn doo_sabin_subdivide(mesh: &PolyMesh, levels: usize, options: &DooSabinOptions) -> Result<PolyMesh, SubdivError> {
    let _ = options;
    if levels == 0 {
        polygons_only(mesh)?;
        return Ok(PolyMesh { normals: None, ..mesh.clone() });
    }
    let rings = Rings::new(mesh)?;
    counts::doo_sabin_levels(DooSabin::of_rings(&rings), levels)?;
    let mut level = step(&rings);
    for _ in 1..levels {
        let fine = step(&Rings::new(&level)?);
        level = fine;
    }
    Ok(level)
}

/// Largest face size whose weights are tabulated.
const TABLE: usize = 16;

/// The corner weights `wₖ` of `n`-gons, `n < TABLE`, row `n` (CGAL's form: `(5/n + 1)/4` and
/// `(3 + 2cos(2kπ/n))/n/4`).
struct Weights([[f64; TABLE]; TABLE]);

impl Weights {
    fn new() -> Self {
        let mut w = [[0.0; TABLE]; TABLE];
        for (n, row) in w.iter_mut().enumerate().skip(1) {
            for (k, x) in row.iter_mut().enumerate().take(n) {
                *x = Self::compute(n, k);
            }
        }
        Self(w)
    }

    fn compute(n: usize, k: usize) -> f64 {
        let nf = n as f64;
        if k == 0 {
            (5.0 / nf + 1.0) / 4.0
        } else {
            (3.0 + 2.0 * (2.0 * k as f64 * core::f64::consts::PI / nf).cos()) / nf / 4.0
        }
    }

    #[inline]
    fn get(&self, n: usize, k: usize) -> f64 {
        if n < TABLE { self.0[n][k] } else { Self::compute(n, k) }
    }
}

/// The point of every corner: the weighted corners of its face. `value(c)` is corner `c`'s
/// value.
fn corner_points<T: Attribute>(mesh: &PolyMesh, weights: &Weights, value: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let mut out = Vec::new();
    (0..mesh.face_vertices.len())
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|c| {
            let f = face_containing(mesh, c);
            let (s, e) = (mesh.face_offsets[f] as usize, mesh.face_offsets[f + 1] as usize);
            let n = e - s;
            let at = |k: usize| value(s + (c - s + k) % n);
            if n == 4 {
                return (at(0) * 9.0 + at(1) * 3.0 + at(2) + at(3) * 3.0) * (1.0 / 16.0);
            }
            (0..n).fold(T::default(), |sum, k| sum + at(k) * weights.get(n, k))
        })
        .collect_into_vec(&mut out);
    out
}

/// The face of corner `c` (binary search in the offsets).
#[inline]
fn face_containing(mesh: &PolyMesh, c: usize) -> usize {
    mesh.face_offsets.partition_point(|&o| o as usize <= c) - 1
}

/// One level, from the adjacency of the parent.
fn step(rings: &Rings<'_>) -> PolyMesh {
    let mesh = rings.mesh;
    let weights = Weights::new();
    let fv = &mesh.face_vertices;
    let positions = corner_points(mesh, &weights, |c| mesh.positions[fv[c] as usize]);
    let colors = if mesh.colors.len() == mesh.positions.len() {
        corner_points(mesh, &weights, |c| mesh.colors[fv[c] as usize])
    } else {
        Vec::new()
    };
    let uv_values = mesh
        .uvs
        .as_ref()
        .filter(|uv| uv.indices.len() == fv.len() && uv.indices.iter().all(|&i| (i as usize) < uv.values.len()))
        .map(|uv| corner_points(mesh, &weights, |c| uv.values[uv.indices[c] as usize]));
    let (face_offsets, face_vertices) = child_faces(rings);
    let uvs = uv_values.map(|values| FaceVarying { values, indices: face_vertices.clone() });
    PolyMesh { positions, colors, face_offsets, face_vertices, normals: None, uvs }
}

/// The child faces: F-faces, E-faces, V-faces (see the module docs).
fn child_faces(rings: &Rings<'_>) -> (Vec<u32>, Vec<u32>) {
    let (mesh, adj) = (rings.mesh, &rings.adj);
    let nc = mesh.face_vertices.len() as u32;
    let next = |c: u32| {
        let f = adj.face_of[c as usize] as usize;
        if c + 1 == mesh.face_offsets[f + 1] { mesh.face_offsets[f] } else { c + 1 }
    };
    // E-faces: the interior edges, by their first corner
    let mut quads: Vec<[u32; 4]> = (0..adj.num_edges())
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .filter_map(|e| {
            let c = adj.edge_corner[e];
            let t = adj.twin[c as usize];
            (t != NONE).then(|| [next(c), c, next(t), t])
        })
        .collect();
    let interior = |v: u32| {
        let corners = adj.corners_of(v);
        !corners.is_empty() && corners.iter().all(|&c| adj.twin[c as usize] != NONE)
    };
    // V-faces: each interior vertex's corners, counter-clockwise (a closed fan)
    let rings_out: Vec<u32> = (0..mesh.num_vertices() as u32)
        .into_par_iter()
        .with_min_len(MIN_RINGS)
        .filter(|&v| interior(v))
        .flat_map_iter(|v| rings.fan(adj.corners_of(v)[0]))
        .collect();
    let mut offsets = mesh.face_offsets.clone();
    let mut end = nc;
    offsets.extend(quads.iter().map(|_| {
        end += 4;
        end
    }));
    offsets.extend((0..mesh.num_vertices() as u32).filter(|&v| interior(v)).map(|v| {
        end += adj.corners_of(v).len() as u32;
        end
    }));
    let mut vertices: Vec<u32> = Vec::with_capacity(end as usize);
    vertices.extend(0..nc);
    vertices.extend(quads.drain(..).flatten());
    vertices.extend(rings_out);
    debug_assert_eq!(vertices.len(), end as usize);
    (offsets, vertices)
}
