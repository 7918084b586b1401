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
//!
//! **With creases** ([`loop_limit_creased`], [`catmull_clark_limit_creased`]; see
//! [`crease`](super::crease)) each vertex takes OpenSubdiv's limit rule from the sharpness left
//! at this level (`Sdc::Scheme::ComputeVertexLimitMask`): a sharp vertex, or three or more sharp
//! edges (boundary edges count as infinitely sharp), is a *corner* — it stays, and its normal
//! is that of its first two edges; exactly two sharp edges make a *crease* — the limit is
//! `(a + 4·P + b)/6` with `a`, `b` the far ends of the sharp edges (the cubic B-spline of the
//! crease), and the normal uses the boundary masks above over the faces between the two sharp
//! edges, counter-clockwise from the leading one; fewer sharp edges are smooth (a dart too).
//! A boundary vertex is the crease of its two boundary edges, as above. At an interior crease
//! the surface has two normals, one per side: the side taken is the one counter-clockwise
//! from the first sharp edge met turning counter-clockwise from the vertex's first corner
//! (the corner of its lowest-numbered face), and the first two edges of a corner are counted
//! from that corner too (OpenSubdiv makes the same choice from its own ordering of a vertex's
//! edges, so the other side can come out there).

use core::f64::consts::{PI, TAU};

use glam::DVec3;
use rayon::prelude::*;

use super::crease::{Creases, Sharpness, sharpness};
use super::creased::{catmull_clark_subdivide_creased, loop_subdivide_creased};
use super::error::{SubdivError, triangles_only};
use super::nonmanifold::{General, is_nonmanifold};
use super::options::{BoundaryRule, CatmullClarkOptions, CreasingMethod, LoopOptions, Rules};
use super::rings::Rings;
use super::topology::MIN_LEN;
use crate::mesh::{NONE, PolyMesh};

/// The limit rule of a vertex, with the part of its ring the masks use (see the [module
/// docs](self)).
#[derive(Clone, Copy, Debug)]
enum Feature {
    /// No faces: the vertex stays, without a normal.
    Isolated,
    /// The scheme's smooth masks over the whole ring, counter-clockwise from corner `start`.
    Smooth { start: u32 },
    /// The crease masks over the `faces` faces counter-clockwise from corner `start` (the
    /// leading sharp edge); `last` is the far end of the trailing sharp edge.
    Crease { start: u32, faces: usize, last: u32 },
    /// The vertex stays; `e0` and `e1` are the far ends of its first two edges.
    Corner { e0: u32, e1: u32 },
}

/// The limit rule of vertex `v` of `rings` with edge and vertex sharpness `sharp` (boundary
/// edges infinitely sharp).
fn feature(rings: &Rings<'_>, sharp: &Sharpness, boundary: BoundaryRule, v: u32) -> Feature {
    let adj = &rings.adj;
    let corners = adj.corners_of(v);
    let Some(&first) = corners.first() else { return Feature::Isolated };
    let to = |c: u32| adj.to[c as usize];
    let is_sharp = |c: u32| sharp.edge[adj.edge_of[c as usize] as usize] > 0.0;
    let vertex_sharp = sharp.vertex[v as usize] > 0.0;
    let k = corners.len();
    if let Some(start) = corners.iter().copied().find(|&c| adj.twin[c as usize] == NONE) {
        // the two boundary edges are sharp; a third sharp edge, a sharp vertex or a fixed
        // one-face corner make a corner
        let arriving = rings.boundary_neighbours(v).map_or(v, |(_, arriving)| arriving);
        let third = rings.fan(start).skip(1).any(is_sharp);
        if vertex_sharp || third || (boundary == BoundaryRule::Corners && k == 1) {
            let e1 = rings.fan(start).nth(1).map_or(arriving, to);
            return Feature::Corner { e0: to(start), e1 };
        }
        return Feature::Crease { start, faces: k, last: arriving };
    }
    let count = corners.iter().filter(|&&c| is_sharp(c)).count();
    if vertex_sharp || count >= 3 {
        let e1 = rings.fan(first).nth(1).unwrap_or(first);
        return Feature::Corner { e0: to(first), e1: to(e1) };
    }
    if count < 2 {
        return Feature::Smooth { start: first };
    }
    let mut sharp_at = rings.fan(first).enumerate().filter(|&(_, c)| is_sharp(c));
    let (Some((i0, lead)), Some((i1, trail))) = (sharp_at.next(), sharp_at.next()) else {
        return Feature::Smooth { start: first };
    };
    Feature::Crease { start: lead, faces: i1 - i0, last: to(trail) }
}

/// `limit(rings, v, feature)` for every vertex `v` of `mesh` with its limit rule under
/// `creases` (boundary edges infinitely sharp, one-face corners by `boundary`), in parallel.
fn each_vertex<T: Send>(
    mesh: &PolyMesh,
    boundary: BoundaryRule,
    creases: &Creases,
    limit: impl Fn(&Rings<'_>, u32, Feature) -> Result<T, SubdivError> + Sync,
) -> Result<Vec<T>, SubdivError> {
    let rings = Rings::new(mesh)?;
    let sharp = sharpness(&rings, creases)?;
    (0..mesh.num_vertices() as u32)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| limit(&rings, v, feature(&rings, &sharp, boundary, v)))
        .collect()
}

/// The limit position of vertex `v` for a crease or corner `feature`, `None` for a smooth one.
fn sharp_position(rings: &Rings<'_>, p: &[DVec3], v: usize, feature: Feature) -> Option<DVec3> {
    match feature {
        Feature::Smooth { .. } => None,
        Feature::Isolated | Feature::Corner { .. } => Some(p[v]),
        Feature::Crease { start, last, .. } => {
            let a = p[rings.adj.to[start as usize] as usize];
            Some((a + p[v] * 4.0 + p[last as usize]) * (1.0 / 6.0))
        }
    }
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
    let rules = Rules::new(options);
    let manifold =
        each_vertex(mesh, options.boundary, &Creases::default(), |rings, v, f| Ok(loop_position(rings, &rules, v, f)));
    or_general(manifold, || loop_general(mesh, options, &Creases::default()).map(|(p, _)| p))
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
    let manifold = each_vertex(mesh, options.boundary, &Creases::default(), |rings, v, f| Ok(loop_normal(rings, v, f)));
    or_general(manifold, || loop_general(mesh, options, &Creases::default()).map(|(_, n)| n))
}

/// The Loop limit positions and unit limit normals of the vertices of the triangle mesh
/// `mesh` with `creases` (on its vertices, as returned by
/// [`loop_subdivide_creased`] for its finest level); see the
/// [module docs](self).
///
/// # Errors
///
/// As [`loop_limit_positions`], and [`SubdivError::Crease`] for a crease on an edge the mesh
/// does not have, a vertex it does not have, or a sharpness that is not a number ≥ 0.
pub fn loop_limit_creased(
    mesh: &PolyMesh,
    options: &LoopOptions,
    creases: &Creases,
) -> Result<(Vec<DVec3>, Vec<DVec3>), SubdivError> {
    triangles_only(mesh, "Loop")?;
    let rules = Rules::new(options);
    let limits = each_vertex(mesh, options.boundary, creases, |rings, v, f| {
        Ok((loop_position(rings, &rules, v, f), loop_normal(rings, v, f)))
    });
    or_general(limits.map(|l| l.into_iter().unzip()), || loop_general(mesh, options, creases))
}

/// The Loop limit position of vertex `v` (see the [module docs](self)).
fn loop_position(rings: &Rings<'_>, rules: &Rules, v: u32, feature: Feature) -> DVec3 {
    let p = &rings.mesh.positions;
    if let Some(position) = sharp_position(rings, p, v as usize, feature) {
        return position;
    }
    let corners = rings.adj.corners_of(v);
    let n = corners.len() as f64;
    let chi = 1.0 / (n + 3.0 / (8.0 * rules.beta(corners.len() as u32)));
    let ring: DVec3 = corners.iter().map(|&c| p[rings.adj.to[c as usize] as usize]).sum();
    p[v as usize] * (1.0 - n * chi) + ring * chi
}

/// The unit Loop limit normal of vertex `v` (see the [module docs](self)).
fn loop_normal(rings: &Rings<'_>, v: u32, feature: Feature) -> DVec3 {
    let p = &rings.mesh.positions;
    let pv = p[v as usize];
    let to = |c: u32| p[rings.adj.to[c as usize] as usize];
    let (t1, t2) = match feature {
        Feature::Isolated => return DVec3::ZERO,
        Feature::Corner { e0, e1 } => (p[e0 as usize] - pv, p[e1 as usize] - pv),
        Feature::Smooth { start } => {
            let a = TAU / rings.adj.corners_of(v).len() as f64;
            rings.fan(start).enumerate().fold((DVec3::ZERO, DVec3::ZERO), |(t1, t2), (i, c)| {
                let (sin, cos) = (a * i as f64).sin_cos();
                (t1 + to(c) * cos, t2 + to(c) * sin)
            })
        }
        Feature::Crease { start, faces: k, last } => {
            let last = p[last as usize];
            let first = to(start);
            // the edges strictly inside the span
            let mut inner = rings.fan(start).skip(1).take(k - 1).map(to);
            let across = match k {
                1 => (first + last) * 3.0 - pv * 6.0,
                2 => inner.next().unwrap_or(pv) - pv,
                3 => {
                    let r3 = 3f64.sqrt();
                    let inner: DVec3 = inner.sum();
                    inner * r3 - (first + last) * (0.5 * r3) - pv * r3
                }
                _ => {
                    let theta = PI / k as f64;
                    let inner = inner.enumerate().fold(DVec3::ZERO, |s, (i, q)| s + q * ((i + 1) as f64 * theta).sin());
                    inner * (2.0 * (1.0 - theta.cos())) - (first + last) * theta.sin()
                }
            };
            (first - last, across)
        }
    };
    t1.cross(t2).normalize_or_zero()
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
    let manifold = each_vertex(mesh, options.boundary, &Creases::default(), catmull_clark_position);
    or_general(manifold, || catmark_general(mesh, options, &Creases::default()).map(|(p, _)| p))
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
    let manifold = each_vertex(mesh, options.boundary, &Creases::default(), catmull_clark_normal);
    or_general(manifold, || catmark_general(mesh, options, &Creases::default()).map(|(_, n)| n))
}

/// The Catmull-Clark limit positions and unit limit normals of the vertices of `mesh` with
/// `creases` (on its vertices, as returned by
/// [`catmull_clark_subdivide_creased`] for its finest
/// level); see the [module docs](self).
///
/// # Errors
///
/// As [`catmull_clark_limit_normals`], and [`SubdivError::Crease`] for a crease on an edge the
/// mesh does not have, a vertex it does not have, or a sharpness that is not a number ≥ 0.
pub fn catmull_clark_limit_creased(
    mesh: &PolyMesh,
    options: &CatmullClarkOptions,
    creases: &Creases,
) -> Result<(Vec<DVec3>, Vec<DVec3>), SubdivError> {
    let limits = each_vertex(mesh, options.boundary, creases, |rings, v, f| {
        Ok((catmull_clark_position(rings, v, f)?, catmull_clark_normal(rings, v, f)?))
    });
    or_general(limits.map(|l| l.into_iter().unzip()), || catmark_general(mesh, options, creases))
}

/// `manifold`, or `general()` where `manifold` failed on a non-manifold or degenerate mesh.
fn or_general<T>(
    manifold: Result<T, SubdivError>,
    general: impl FnOnce() -> Result<T, SubdivError>,
) -> Result<T, SubdivError> {
    match manifold {
        Err(SubdivError::Topology(e)) if e.is_nonmanifold() => general(),
        result => result,
    }
}

/// The Loop limit positions and normals of the non-manifold `mesh` as a base level, with
/// OpenSubdiv's rules (see [`general`](super::general)).
fn loop_general(
    mesh: &PolyMesh,
    options: &LoopOptions,
    creases: &Creases,
) -> Result<(Vec<DVec3>, Vec<DVec3>), SubdivError> {
    General::loop_scheme(options, creases, CreasingMethod::default())
        .subdivide_limit(mesh, 0, false)
        .map(|(_, p, n)| (p, n))
}

/// [`loop_general`] for Catmull-Clark.
fn catmark_general(
    mesh: &PolyMesh,
    options: &CatmullClarkOptions,
    creases: &Creases,
) -> Result<(Vec<DVec3>, Vec<DVec3>), SubdivError> {
    General::catmark(options, creases, CreasingMethod::default())
        .subdivide_limit(mesh, 0, false)
        .map(|(_, p, n)| (p, n))
}

/// A subdivided mesh with the limit positions and unit limit normals of its vertices.
pub type LimitMesh = (PolyMesh, Vec<DVec3>, Vec<DVec3>);

/// `levels` levels of Loop subdivision of `mesh` with `creases` carried by `method`, as
/// [`loop_subdivide_creased`], and the limit positions and unit
/// limit normals of the subdivided mesh's vertices, as [`loop_limit_creased`] gives them for
/// its creases — with the vertex rules and the edges the vertices have at that level of the
/// subdivision, as OpenSubdiv's limit after refining has them. They differ from the rules of
/// the subdivided mesh taken alone where a level's faces, written as a list, join what the
/// subdivision keeps apart: on a non-manifold mesh (see [`is_nonmanifold`];
/// a vertex born on a non-manifold edge keeps that edge's crease), and on meshes whose levels
/// have two edges between the same two vertices (back-to-back triangles: two triangles on the
/// same three vertices). The subdivided mesh is then made by OpenSubdiv's rules for such meshes
/// (as [`loop_subdivide`](super::loop_subdivide) makes a non-manifold one: the same positions,
/// no normals or UVs) and its normals are the area-weighted normals of the faces around each
/// vertex at the limit positions.
///
/// # Errors
///
/// As [`loop_subdivide_creased`].
pub fn loop_subdivide_limit(
    mesh: &PolyMesh,
    levels: u32,
    options: &LoopOptions,
    creases: &Creases,
    method: CreasingMethod,
) -> Result<LimitMesh, SubdivError> {
    triangles_only(mesh, "Loop")?;
    let general = General::loop_scheme(options, creases, method);
    if !is_nonmanifold(mesh) {
        let (fine, child) = loop_subdivide_creased(mesh, levels, options, creases, method)?;
        let rules = Rules::new(options);
        let limits = each_vertex(&fine, options.boundary, &child, |rings, v, f| {
            Ok((loop_position(rings, &rules, v, f), loop_normal(rings, v, f)))
        });
        match limits {
            Err(SubdivError::Topology(e)) if e.is_nonmanifold() => {}
            limits => {
                let (positions, normals) = limits?.into_iter().unzip();
                return Ok((fine, positions, normals));
            }
        }
    }
    general.subdivide_limit(mesh, levels as usize, options.color_by_level)
}

/// `levels` levels of Catmull-Clark subdivision of `mesh` and the limit positions and unit
/// limit normals of the subdivided mesh's vertices, as [`loop_subdivide_limit`] for Loop (two
/// back-to-back quads make levels with two edges between the same two vertices).
///
/// # Errors
///
/// As [`catmull_clark_subdivide_creased`], and
/// [`SubdivError::NotQuads`] without levels for a mesh that is not all quads.
pub fn catmull_clark_subdivide_limit(
    mesh: &PolyMesh,
    levels: usize,
    options: &CatmullClarkOptions,
    creases: &Creases,
    method: CreasingMethod,
) -> Result<LimitMesh, SubdivError> {
    let general = General::catmark(options, creases, method);
    if !is_nonmanifold(mesh) {
        let (fine, child) = catmull_clark_subdivide_creased(mesh, levels, options, creases, method)?;
        let limits = each_vertex(&fine, options.boundary, &child, |rings, v, f| {
            Ok((catmull_clark_position(rings, v, f)?, catmull_clark_normal(rings, v, f)?))
        });
        match limits {
            Err(SubdivError::Topology(e)) if e.is_nonmanifold() => {}
            limits => {
                let (positions, normals) = limits?.into_iter().unzip();
                return Ok((fine, positions, normals));
            }
        }
    }
    general.subdivide_limit(mesh, levels, options.color_by_level)
}

/// The vertex across corner `c`'s quad from its vertex, or an error naming vertex `v` if the
/// face is not a quad.
fn diagonal(rings: &Rings<'_>, v: u32, c: u32) -> Result<u32, SubdivError> {
    let mesh = rings.mesh;
    let f = rings.adj.face_of[c as usize] as usize;
    let face = mesh.face(f);
    if face.len() != 4 {
        return Err(SubdivError::NotQuads { vertex: v as usize, face: f, corners: face.len() });
    }
    let i = c as usize - mesh.face_offsets[f] as usize;
    Ok(face[(i + 2) % 4])
}

/// The Catmull-Clark limit position of vertex `v` (see the [module docs](self)).
fn catmull_clark_position(rings: &Rings<'_>, v: u32, feature: Feature) -> Result<DVec3, SubdivError> {
    let p = &rings.mesh.positions;
    if let Some(position) = sharp_position(rings, p, v as usize, feature) {
        return Ok(position);
    }
    let corners = rings.adj.corners_of(v);
    if corners.len() == 2 {
        // valence 2: OpenSubdiv's limit mask keeps the vertex where it is, as a corner's
        return Ok(p[v as usize]);
    }
    let (mut edges, mut diagonals) = (DVec3::ZERO, DVec3::ZERO);
    for &c in corners {
        edges += p[rings.adj.to[c as usize] as usize];
        diagonals += p[diagonal(rings, v, c)? as usize];
    }
    let n = corners.len() as f64;
    Ok((p[v as usize] * (n * n) + edges * 4.0 + diagonals) * (1.0 / (n * (n + 5.0))))
}

/// The unit Catmull-Clark limit normal of vertex `v` (see the [module docs](self)).
fn catmull_clark_normal(rings: &Rings<'_>, v: u32, feature: Feature) -> Result<DVec3, SubdivError> {
    let p = &rings.mesh.positions;
    let pv = p[v as usize];
    let edge = |c: u32| p[rings.adj.to[c as usize] as usize];
    let diagonal = |c: u32| diagonal(rings, v, c).map(|d| p[d as usize]);
    let (t1, t2) = match feature {
        Feature::Isolated => return Ok(DVec3::ZERO),
        Feature::Corner { e0, e1 } => (p[e0 as usize] - pv, p[e1 as usize] - pv),
        Feature::Smooth { start } if rings.adj.corners_of(v).len() == 2 => {
            let mut ring = rings.fan(start).map(edge);
            let (e0, e1) = (ring.next().unwrap_or(pv), ring.next().unwrap_or(pv));
            (e0 - pv, e1 - pv)
        }
        Feature::Smooth { start } => {
            let theta = TAU / rings.adj.corners_of(v).len() as f64;
            let lambda = 5.0 / 16.0 + (theta.cos() + (0.5 * theta).cos() * (2.0 * (9.0 + theta.cos())).sqrt()) / 16.0;
            let face_scale = 1.0 / (4.0 * lambda - 1.0);
            let mut t = (DVec3::ZERO, DVec3::ZERO);
            for (i, c) in rings.fan(start).enumerate() {
                let (e, f) = (edge(c), diagonal(c)?);
                let cos = |j: f64| (j * theta).cos();
                let i = i as f64;
                t.0 += e * (4.0 * cos(i)) + f * (face_scale * (cos(i) + cos(i + 1.0)));
                t.1 += e * (4.0 * cos(i - 1.0)) + f * (face_scale * (cos(i - 1.0) + cos(i)));
            }
            t
        }
        Feature::Crease { start, faces: k, last } => {
            let last = p[last as usize];
            let first = edge(start);
            let across = match k {
                1 => (first + last) * 3.0 - pv * 6.0,
                2 => {
                    let c1 = rings.fan(start).nth(1).unwrap_or(start);
                    let (f0, f1) = (diagonal(start)?, diagonal(c1)?);
                    (edge(c1) * 4.0 - pv * 4.0 - first - last + f0 + f1) * (1.0 / 6.0)
                }
                _ => {
                    let theta = PI / k as f64;
                    let (sin, cos) = theta.sin_cos();
                    let r = (cos + 1.0) / sin;
                    let mut inner = pv * (4.0 * r * (cos - 1.0)) - (first + last) * (r * (1.0 + 2.0 * cos));
                    for (i, c) in rings.fan(start).take(k).enumerate() {
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
    };
    Ok(t1.cross(t2).normalize_or_zero())
}
