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
//!
//! **Limit normals** ([`loop_limit_normals`], [`catmull_clark_limit_normals`]) are the unit
//! cross products `t₁ × t₂` of two limit tangents from closed-form masks over the vertex's
//! ring `q₀ … ` (its neighbours counter-clockwise, from the boundary edge it leaves along for a
//! boundary vertex) — OpenSubdiv's masks (`Sdc::Scheme::assign*LimitTangentMasks`), so they
//! point to the side the faces' corners turn counter-clockwise around:
//! - Loop, interior vertex of valence `n`: `t₁ = Σ cos(2πi/n)·qᵢ`, `t₂ = Σ sin(2πi/n)·qᵢ`
//!   (the subdominant left eigenvectors of the subdivision matrix, the same for both
//!   [`LoopWeights`](super::LoopWeights)).
//! - Catmull-Clark, interior vertex of valence `n` with quads around it, edge neighbours `eᵢ`
//!   and diagonal neighbours `fᵢ` (in the face between `eᵢ` and `eᵢ₊₁`):
//!   `t₁ = Σ 4cos(iθ)·eᵢ + (cos(iθ) + cos((i+1)θ))/(4λ − 1)·fᵢ` with `θ = 2π/n` and the
//!   subdominant eigenvalue `λ = 5/16 + (cos θ + cos(θ/2)·√(2(9 + cos θ)))/16`, and `t₂` the same
//!   mask turned by one place.
//! - Boundary vertex with `k` faces, `q₀` and `q_k` its boundary neighbours: `t₁ = q₀ − q_k`
//!   along the boundary, and across the surface Loop's `3(q₀ + q₁) − 6p` (k = 1), `q₁ − p`
//!   (k = 2), `−√3·p − √3/2·(q₀ + q₃) + √3·(q₁ + q₂)` (k = 3), else with `θ = π/k`
//!   `−sin θ·(q₀ + q_k) + 2(1 − cos θ)·Σ sin(iθ)·qᵢ`; Catmull-Clark's likewise from
//!   Biermann, Levin and Zorin's boundary masks.
//! - A one-face corner kept fixed ([`BoundaryRule::Corners`]): the two edges, `q₀ − p` and
//!   `q₁ − p` (the face's normal). A vertex without faces gets the zero vector.

use core::f64::consts::{PI, TAU};

use glam::DVec3;
use rayon::prelude::*;

use super::catmull_clark::{CatmullClarkOptions, Rings};
use super::loop_scheme::{BoundaryRule, LoopOptions, Rules, SubdivError, triangles_only};
use super::topology::MIN_LEN;
use crate::mesh::{NONE, PolyMesh};

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
    triangles_only(mesh, "Loop")?;
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

/// Vertex `v`'s corners (half-edges leaving it), counter-clockwise: from the one along the
/// boundary for a boundary vertex (then also the neighbour it arrives from along the
/// boundary), from any for an interior one; `None` for a vertex without faces.
fn ccw_ring<'r>(rings: &'r Rings<'_>, v: u32) -> Option<(impl Iterator<Item = u32> + 'r, Option<u32>)> {
    let corners = rings.adj.corners_of(v);
    let first = *corners.first()?;
    let start = corners.iter().copied().find(|&c| rings.adj.twin[c as usize] == NONE);
    let arriving = start.map(|_| rings.boundary_neighbours(v).map_or(v, |(_, arriving)| arriving));
    Some((rings.fan(start.unwrap_or(first)), arriving))
}

/// The unit Loop limit normals of the vertices of the triangle mesh `mesh` (see the [module
/// docs](self)): the normal of the limit surface at each vertex's limit position, on the side
/// the triangles turn counter-clockwise around.
///
/// # Errors
///
/// As [`loop_limit_positions`].
pub fn loop_limit_normals(mesh: &PolyMesh, options: &LoopOptions) -> Result<Vec<DVec3>, SubdivError> {
    triangles_only(mesh, "Loop")?;
    let rings = Rings::new(mesh)?;
    let p = &mesh.positions;
    Ok((0..p.len() as u32)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| {
            let Some((ring, arriving)) = ccw_ring(&rings, v) else { return DVec3::ZERO };
            let pv = p[v as usize];
            let k = rings.adj.corners_of(v).len();
            let to = |c: u32| p[rings.adj.to[c as usize] as usize];
            let (t1, t2) = match arriving {
                None => {
                    let a = TAU / k as f64;
                    ring.enumerate().fold((DVec3::ZERO, DVec3::ZERO), |(t1, t2), (i, c)| {
                        let (sin, cos) = (a * i as f64).sin_cos();
                        (t1 + to(c) * cos, t2 + to(c) * sin)
                    })
                }
                Some(last) => {
                    let last = p[last as usize];
                    let mut ring = ring.map(to);
                    let first = ring.next().unwrap_or(pv);
                    if options.boundary == BoundaryRule::Corners && k == 1 {
                        (first - pv, last - pv)
                    } else {
                        let across = match k {
                            1 => (first + last) * 3.0 - pv * 6.0,
                            2 => ring.next().unwrap_or(pv) - pv,
                            3 => {
                                let r3 = 3f64.sqrt();
                                let inner: DVec3 = ring.sum();
                                inner * r3 - (first + last) * (0.5 * r3) - pv * r3
                            }
                            _ => {
                                let theta = PI / k as f64;
                                let inner = ring
                                    .enumerate()
                                    .fold(DVec3::ZERO, |s, (i, q)| s + q * ((i + 1) as f64 * theta).sin());
                                inner * (2.0 * (1.0 - theta.cos())) - (first + last) * theta.sin()
                            }
                        };
                        (first - last, across)
                    }
                }
            };
            t1.cross(t2).normalize_or_zero()
        })
        .collect())
}

/// The unit Catmull-Clark limit normals of the vertices of `mesh` (see the [module
/// docs](self)): the normal of the limit surface at each vertex's limit position, on the side
/// the faces turn counter-clockwise around.
///
/// # Errors
///
/// [`SubdivError::NotQuads`] for a vertex with a face around it that is not a quad (except a
/// boundary vertex with one face), [`SubdivError::Topology`] for a non-manifold or
/// inconsistently oriented edge or vertex.
pub fn catmull_clark_limit_normals(mesh: &PolyMesh, options: &CatmullClarkOptions) -> Result<Vec<DVec3>, SubdivError> {
    let rings = Rings::new(mesh)?;
    let p = &mesh.positions;
    (0..p.len() as u32)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| {
            let Some((ring, arriving)) = ccw_ring(&rings, v) else { return Ok(DVec3::ZERO) };
            let pv = p[v as usize];
            let k = rings.adj.corners_of(v).len();
            // corner c's edge neighbour, and the vertex across its quad
            let edge = |c: u32| p[rings.adj.to[c as usize] as usize];
            let diagonal = |c: u32| {
                let f = rings.adj.face_of[c as usize] as usize;
                let face = mesh.face(f);
                if face.len() != 4 {
                    return Err(SubdivError::NotQuads { vertex: v as usize, face: f, corners: face.len() });
                }
                let i = c as usize - mesh.face_offsets[f] as usize;
                Ok(p[face[(i + 2) % 4] as usize])
            };
            let (t1, t2) = match arriving {
                None if k == 2 => {
                    let mut ring = ring.map(edge);
                    let (e0, e1) = (ring.next().unwrap_or(pv), ring.next().unwrap_or(pv));
                    (e0 - pv, e1 - pv)
                }
                None => {
                    let theta = TAU / k as f64;
                    let lambda =
                        5.0 / 16.0 + (theta.cos() + (0.5 * theta).cos() * (2.0 * (9.0 + theta.cos())).sqrt()) / 16.0;
                    let face_scale = 1.0 / (4.0 * lambda - 1.0);
                    let mut t = (DVec3::ZERO, DVec3::ZERO);
                    for (i, c) in ring.enumerate() {
                        let (e, f) = (edge(c), diagonal(c)?);
                        let cos = |j: f64| (j * theta).cos();
                        let i = i as f64;
                        t.0 += e * (4.0 * cos(i)) + f * (face_scale * (cos(i) + cos(i + 1.0)));
                        t.1 += e * (4.0 * cos(i - 1.0)) + f * (face_scale * (cos(i - 1.0) + cos(i)));
                    }
                    t
                }
                Some(last) => {
                    let last = p[last as usize];
                    let mut ring = ring.peekable();
                    let c0 = *ring.peek().expect("a vertex with faces has a corner");
                    let first = edge(c0);
                    if options.boundary == BoundaryRule::Corners && k == 1 {
                        (first - pv, last - pv)
                    } else {
                        let across = match k {
                            1 => (first + last) * 3.0 - pv * 6.0,
                            2 => {
                                let c1 = ring.nth(1).unwrap_or(c0);
                                let (f0, f1) = (diagonal(c0)?, diagonal(c1)?);
                                (edge(c1) * 4.0 - pv * 4.0 - first - last + f0 + f1) * (1.0 / 6.0)
                            }
                            _ => {
                                let theta = PI / k as f64;
                                let (sin, cos) = theta.sin_cos();
                                let r = (cos + 1.0) / sin;
                                let mut inner = pv * (4.0 * r * (cos - 1.0)) - (first + last) * (r * (1.0 + 2.0 * cos));
                                for (i, c) in ring.enumerate() {
                                    let (si, sj) = ((i as f64 * theta).sin(), ((i + 1) as f64 * theta).sin());
                                    if i > 0 {
                                        inner += edge(c) * (4.0 * si);
                                    }
                                    inner += diagonal(c)? * (si + sj);
                                }
                                inner * (1.0 / (k as f64 * (3.0 + cos)))
                            }
                        };
                        (first - last, across)
                    }
                }
            };
            Ok(t1.cross(t2).normalize_or_zero())
        })
        .collect()
}
