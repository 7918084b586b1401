//! Swept surfaces: surfaces of revolution about +y (`srev`) and generalized
//! cylinders (`gcyl`), from tessellated curves with frames.
//!
//! # Layouts
//! - [`MeshLayout::Compat`]: the course program's vertex layout and counts:
//!   one vertex per (copy, profile point), seams of generalized cylinders duplicated, poles
//!   of revolutions repeated in every copy.
//! - [`MeshLayout::Welded`] (the default): every point of the surface one vertex (seams,
//!   poles, creases, cap rims and joints at path corners shared), zero-area triangles left
//!   out, normals and UVs per face corner, so a closed sweep is a closed 2-manifold
//!   ([`generalized_cylinder_poly`], [`revolve_poly`]). The meshes for drawing
//!   ([`generalized_cylinder`], [`revolve`]) have a vertex per side where normals or UVs
//!   differ (a crease, a UV seam where `u` jumps from 1 to 0).
//!
//! # Orientation
//! Triangles are counter-clockwise seen from outside, and vertex normals point outside,
//! whatever the side or direction of the profile: after building, the flux of the face
//! normals through the surface's "outward" direction (away from the axis of revolution, or
//! from the sweep curve) is checked, and the whole mesh is flipped if it is negative. The
//! course files (profiles at x < 0) come out with outward normals and counter-clockwise front
//! faces; a profile on the x > 0 side, or traversed the other way, still gives an outward
//! surface.

pub mod adaptive;
pub mod surface;
pub mod welded;

use glam::{DVec2, DVec3};

pub use self::welded::{CornerFit, Join};
use crate::frame::Frame;
use crate::mesh::{FaceVarying, PolyMesh, TriMesh};

/// The default of [`SweepOptions::mitre_limit`]: SVG's default `stroke-miterlimit`, a mitre
/// at most 4 times the profile's offset (corners of up to about 151°).
pub const DEFAULT_MITRE_LIMIT: f64 = 4.0;

/// The default of [`SweepOptions::round_step`]: 10° per step of a round joint's arc.
pub const DEFAULT_ROUND_STEP: f64 = std::f64::consts::PI / 18.0;

/// How seams and poles are laid out; see the module docs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MeshLayout {
    /// The course program's layout and counts (seams duplicated, poles repeated).
    Compat,
    /// Seams and poles shared; a closed sweep is a closed 2-manifold.
    #[default]
    Welded,
}

/// Options shared by the sweeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepOptions {
    /// Vertex layout.
    pub layout: MeshLayout,
    /// Emit arc-length UVs: `u` along the sweep (or around the axis), `v` along the profile,
    /// both normalized to `[0, 1]`.
    pub uvs: bool,
    /// Close an open generalized cylinder whose profile is a closed loop with flat end caps
    /// (on the end copies' vertices, with normals of their own, so the rim is a sharp edge).
    /// Ignored by revolutions. On by
    /// default, as `splinekit sweep` does: a closed profile swept along an open path then
    /// encloses a solid.
    pub caps: bool,
    /// How the walls meet at a sharp corner of the path (welded layout; see [`welded`]).
    pub join: Join,
    /// The longest mitre, as a multiple of the profile's offset from the path, before a
    /// [`Join::Mitre`] falls back to a bevel (`1/cos(α/2)` at a corner of angle `α`).
    pub mitre_limit: f64,
    /// The largest angle (radians) of one step of a [`Join::Round`] arc.
    pub round_step: f64,
}

impl Default for SweepOptions {
    /// The welded layout with caps and mitre joins, without UVs: what `splinekit sweep`, `render`,
    /// `gallery` and the editor all sweep with unless told otherwise.
    fn default() -> Self {
        Self {
            layout: MeshLayout::Welded,
            uvs: false,
            caps: true,
            join: Join::Mitre,
            mitre_limit: DEFAULT_MITRE_LIMIT,
            round_step: DEFAULT_ROUND_STEP,
        }
    }
}

/// The size of a mesh a sweep would build, known before building it (see [`revolve_counts`]
/// and [`generalized_cylinder_counts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshCounts {
    /// Vertices.
    pub vertices: u64,
    /// Triangles.
    pub triangles: u64,
}

/// Why a sweep could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// Too few points to make a surface.
    #[error("{what} has {found} points; at least {needed} are needed")]
    TooFewPoints {
        /// `profile` or `sweep`.
        what: &'static str,
        /// Number of points given.
        found: usize,
        /// Minimum.
        needed: usize,
    },
    /// Point and normal (or frame) arrays differ in length.
    #[error("{what}: {points} points but {attributes} normals or frames")]
    LengthMismatch {
        /// `profile` or `sweep`.
        what: &'static str,
        /// Number of points.
        points: usize,
        /// Number of normals or frames.
        attributes: usize,
    },
    /// `steps` of a revolution is zero.
    #[error("a surface of revolution needs at least 1 step, got 0")]
    ZeroSteps,
    /// A point, normal or frame is NaN or infinite.
    #[error("{what} point {index} is not finite")]
    NonFinite {
        /// `profile` or `sweep`.
        what: &'static str,
        /// Index of the point.
        index: usize,
    },
    /// The mesh would have more vertices than 32-bit indices can address.
    #[error("about {vertices:e} vertices do not fit 32-bit indices")]
    TooLarge {
        /// The vertex count the mesh would have (at most; as `f64`, as it may not fit `usize`).
        vertices: f64,
    },
}

/// Fails when `vertices` (a product of counts, computed in `f64` so that it cannot wrap)
/// would not fit 32-bit indices.
fn check_vertex_count(vertices: f64) -> Result<(), SweepError> {
    if vertices <= f64::from(u32::MAX) { Ok(()) } else { Err(SweepError::TooLarge { vertices }) }
}

/// A tessellated planar profile: points `(x, y)` and unit normals, in order along the curve.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profile {
    /// Points along the profile.
    pub points: Vec<DVec2>,
    /// Unit normal at each point (the curve's frame normal `N`, as the course program uses it).
    pub normals: Vec<DVec2>,
}

impl Profile {
    fn check(&self) -> Result<(), SweepError> {
        if self.points.len() < 2 {
            return Err(SweepError::TooFewPoints { what: "profile", found: self.points.len(), needed: 2 });
        }
        if self.normals.len() != self.points.len() {
            return Err(SweepError::LengthMismatch {
                what: "profile",
                points: self.points.len(),
                attributes: self.normals.len(),
            });
        }
        if let Some(index) =
            (0..self.points.len()).find(|&i| !self.points[i].is_finite() || !self.normals[i].is_finite())
        {
            return Err(SweepError::NonFinite { what: "profile", index });
        }
        Ok(())
    }

    /// Cumulative chord length, normalized to `[0, 1]` (all zero for a degenerate profile).
    fn normalized_lengths(&self) -> Vec<f64> {
        normalized_lengths(self.points.iter().zip(self.points.iter().skip(1)).map(|(a, b)| a.distance(*b)))
    }

    /// True when the first and last points coincide (within `1e-9` of the profile's size).
    fn is_closed(&self) -> bool {
        let size = extent(self.points.iter().map(|p| p.extend(0.0)));
        self.points.len() > 2 && self.points[0].distance(self.points[self.points.len() - 1]) <= 1e-9 * size.max(1e-300)
    }
}

/// A tessellated sweep curve: positions with their frames, and optionally a scale per point.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweepPath {
    /// Points along the sweep curve.
    pub positions: Vec<DVec3>,
    /// Frame at each point (a twist is applied by rotating these about `T`).
    pub frames: Vec<Frame>,
    /// Empty, or one `(sx, sy)` per point: the profile's `x` is scaled by `sx` and its `y`
    /// by `sy` at that point. With scales, vertex normals are the area-weighted normals of
    /// the faces around each vertex (the profile's normals no longer describe a tapering tube).
    pub scales: Vec<DVec2>,
}

impl SweepPath {
    fn check(&self) -> Result<(), SweepError> {
        if self.positions.len() < 2 {
            return Err(SweepError::TooFewPoints { what: "sweep", found: self.positions.len(), needed: 2 });
        }
        if self.frames.len() != self.positions.len() {
            return Err(SweepError::LengthMismatch {
                what: "sweep",
                points: self.positions.len(),
                attributes: self.frames.len(),
            });
        }
        if !self.scales.is_empty() && self.scales.len() != self.positions.len() {
            return Err(SweepError::LengthMismatch {
                what: "sweep scale",
                points: self.positions.len(),
                attributes: self.scales.len(),
            });
        }
        let bad = |f: &Frame| !(f.t.is_finite() && f.n.is_finite() && f.b.is_finite());
        if let Some(index) = (0..self.positions.len()).find(|&i| !self.positions[i].is_finite() || bad(&self.frames[i]))
        {
            return Err(SweepError::NonFinite { what: "sweep", index });
        }
        if let Some(index) = self.scales.iter().position(|s| !s.is_finite()) {
            return Err(SweepError::NonFinite { what: "sweep scale", index });
        }
        Ok(())
    }

    /// True when the first and last points coincide (within `1e-9` of the path's size).
    fn is_closed(&self) -> bool {
        let size = extent(self.positions.iter().copied());
        let n = self.positions.len();
        n > 2 && self.positions[0].distance(self.positions[n - 1]) <= 1e-9 * size.max(1e-300)
    }
}

fn extent(points: impl Iterator<Item = DVec3>) -> f64 {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for p in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    if lo.x <= hi.x { (hi - lo).max_element() } else { 0.0 }
}

fn normalized_lengths(steps: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut acc = vec![0.0];
    for d in steps {
        let last = *acc.last().unwrap_or(&0.0);
        acc.push(last + d);
    }
    let total = *acc.last().unwrap_or(&0.0);
    if total > 0.0 {
        for v in &mut acc {
            *v /= total;
        }
    }
    acc
}

/// The surface of revolution (`srev`): `steps` copies of the profile, copy `j`
/// rotated by the right-handed angle `2πj/steps` about +y, no duplicate copy at 2π.
///
/// Compat layout: vertex `j·P + i` for profile point `i` of copy `j`; triangles
/// `(a, a+1, a+P)` and `(a+1, a+P+1, a+P)` with `a = j·P + i` (indices mod the vertex count);
/// normals are the profile normals rotated and flipped. Welded layout: profile points on the
/// axis become single pole vertices, and the triangles that would collapse there are left out.
///
/// # Errors
/// Fewer than two profile points, mismatched normals, non-finite input, `steps == 0`, more
/// vertices than 32-bit indices can address.
pub fn revolve(profile: &Profile, steps: usize, options: SweepOptions) -> Result<TriMesh, SweepError> {
    let RevolveLayout { on_axis, twin, copies, welded } = RevolveLayout::new(profile, steps, options)?;
    let p = profile.points.len();
    let vs = profile.normalized_lengths();

    let mut mesh = TriMesh::default();
    mesh.positions.reserve(copies * p);
    mesh.normals.reserve(copies * p);
    mesh.triangles.reserve(2 * steps * p);
    // index[j][i]: vertex of profile point i in copy j
    let mut index = vec![0u32; copies * p];
    let mut pole = vec![u32::MAX; p];
    for j in 0..copies {
        let phi = std::f64::consts::TAU * j as f64 / steps as f64;
        let (s, c) = phi.sin_cos();
        let rot = |v: DVec2| DVec3::new(v.x * c, v.y, -v.x * s);
        for i in 0..p {
            if on_axis[i] && pole[i] != u32::MAX {
                index[j * p + i] = pole[i];
                continue;
            }
            let id = mesh.positions.len() as u32;
            let q = profile.points[i];
            mesh.positions.push(if on_axis[i] { DVec3::new(0.0, q.y, 0.0) } else { rot(q) });
            mesh.normals.push(-rot(profile.normals[i]));
            if options.uvs {
                mesh.uvs.push(DVec2::new(if on_axis[i] { 0.5 } else { j as f64 / steps as f64 }, vs[i]));
            }
            if on_axis[i] {
                pole[i] = id;
            }
            index[j * p + i] = id;
        }
    }
    for j in 0..steps {
        let next = if options.uvs { j + 1 } else { (j + 1) % steps };
        for i in (0..p - 1).filter(|&i| !twin[i]) {
            let (a, b) = (index[j * p + i], index[j * p + i + 1]);
            let (c, d) = (index[next * p + i], index[next * p + i + 1]);
            push_quad(&mut mesh, [a, b, c, d], welded);
        }
    }
    // outward: away from the y axis
    orient(&mut mesh, |q, _| DVec3::new(q.x, 0.0, q.z));
    if welded {
        fix_pole_normals(&mut mesh, &pole);
    }
    Ok(mesh)
}

/// [`revolve`]'s surface with every point one vertex (welded layout): a crease of the
/// profile, the closing point of a closed profile and the UV seam are shared, and the
/// normals and UVs are face-varying. In the compat layout, the same mesh as [`revolve`].
///
/// # Errors
/// As [`revolve`].
pub fn revolve_poly(profile: &Profile, steps: usize, options: SweepOptions) -> Result<PolyMesh, SweepError> {
    let split = revolve(profile, steps, options)?;
    if options.layout == MeshLayout::Compat {
        return Ok(PolyMesh::from(&split));
    }
    let RevolveLayout { on_axis, copies, .. } = RevolveLayout::new(profile, steps, options)?;
    let slots = welded::Slots::new(profile);
    let (p, np) = (profile.points.len(), slots.first_slot.len());
    // the split vertices in the order `revolve` makes them: copy by copy, a pole once
    let mut pid = Vec::with_capacity(split.positions.len());
    let mut pole_seen = vec![false; p];
    for j in 0..copies {
        for i in 0..p {
            if on_axis[i] {
                if pole_seen[i] {
                    continue;
                }
                pole_seen[i] = true;
                pid.push((steps * np + slots.point[i]) as u32);
            } else {
                pid.push(((j % steps) * np + slots.point[i]) as u32);
            }
        }
    }
    let mut positions = vec![DVec3::ZERO; (steps + 1) * np];
    for (v, &id) in pid.iter().enumerate() {
        positions[id as usize] = split.positions[v];
    }
    // one value where the sides agree (the UV seam's copy without UVs, a smooth closed profile)
    let twin = attribute_twins(&split, &pid, |_| true);
    let mut split = split;
    for t in &mut split.triangles {
        *t = t.map(|v| twin[v as usize]);
    }
    Ok(weld(&split, &pid, &positions))
}

/// The vertex and triangle counts of [`revolve_poly`]`(profile, steps, options)` (the file's
/// mesh), from the profile alone: the work is linear in the profile's length, whatever `steps` is.
///
/// # Errors
/// As [`revolve`].
pub fn revolve_counts(profile: &Profile, steps: usize, options: SweepOptions) -> Result<MeshCounts, SweepError> {
    let RevolveLayout { on_axis, twin, copies, welded } = RevolveLayout::new(profile, steps, options)?;
    let p = on_axis.len();
    // welded with one copy: every quad collapses onto itself (in the file, the UV copy is
    // the first one again)
    let collapsed = welded && steps == 1;
    let strip_triangles = |i: usize| -> u64 {
        if collapsed || twin[i] {
            0
        } else if welded {
            u64::from(!on_axis[i]) + u64::from(!on_axis[i + 1])
        } else {
            2
        }
    };
    let vertices = if welded {
        // the distinct profile points a triangle uses: once per copy (no UV copy), a pole once
        let slots = welded::Slots::new(profile);
        let mut used = vec![false; slots.first_slot.len()];
        for i in (0..p - 1).filter(|&i| strip_triangles(i) > 0) {
            used[slots.point[i]] = true;
            used[slots.point[i + 1]] = true;
        }
        (0..used.len()).filter(|&d| used[d]).map(|d| if on_axis[slots.first_slot[d]] { 1 } else { steps as u64 }).sum()
    } else {
        let poles = on_axis.iter().filter(|&&a| a).count();
        // a pole is one vertex; every other point has one per copy
        (copies * (p - poles) + poles) as u64
    };
    let per_turn: u64 = (0..p - 1).map(strip_triangles).sum();
    Ok(MeshCounts { vertices, triangles: per_turn * steps as u64 })
}

/// Which profile points of a revolution are poles and which strips are left out.
struct RevolveLayout {
    /// Profile points on the axis (welded layout): one vertex for every copy.
    on_axis: Vec<bool>,
    /// See [`twins`].
    twin: Vec<bool>,
    /// Copies of the profile: `steps`, and one more (the UV seam at 2π) with UVs.
    copies: usize,
    welded: bool,
}

impl RevolveLayout {
    fn new(profile: &Profile, steps: usize, options: SweepOptions) -> Result<Self, SweepError> {
        profile.check()?;
        if steps == 0 {
            return Err(SweepError::ZeroSteps);
        }
        check_vertex_count((steps as f64 + 1.0) * profile.points.len() as f64)?;
        let size = extent(profile.points.iter().map(|q| q.extend(0.0)));
        let welded = options.layout == MeshLayout::Welded;
        let on_axis = profile.points.iter().map(|q| welded && q.x.abs() <= 1e-12 * size).collect();
        // UV seam: with UVs, the copy at 2π is emitted again (u = 1)
        let copies = if options.uvs { steps + 1 } else { steps };
        Ok(Self { on_axis, twin: twins(&profile.points, welded), copies, welded })
    }
}

/// The generalized cylinder (`gcyl`): a copy of the profile at every sweep
/// point, `vertex = N·p.x + B·p.y + V`, `normal = −(N·n.x + B·n.y)` with the sweep frame
/// `(T, N, B)` at `V` and the profile normal `n`.
///
/// This is the mesh a renderer draws: normals and UVs are per vertex, so a vertex where they
/// differ (a crease, a cap's rim, a UV seam, a joint) is repeated once per side at the same
/// position. [`generalized_cylinder_poly`] gives the same surface with those vertices
/// shared, as files get it.
///
/// Compat layout: vertex `k·P + i` for profile point `i` of copy `k`, triangles
/// `(a, a+1, a+P)` and `(a+1, a+P+1, a+P)`, seams duplicated. Welded layout: built as the
/// [`welded`] module describes (joints at the path's sharp corners, walls cut at them, caps
/// on the end copies' points).
///
/// # Errors
/// Fewer than two points in either curve, mismatched arrays, non-finite input, more vertices
/// than 32-bit indices can address.
pub fn generalized_cylinder(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<TriMesh, SweepError> {
    if options.layout == MeshLayout::Welded {
        return Ok(generalized_cylinder_poly(profile, path, options)?.mesh.to_tri_mesh_with_seams());
    }
    compat_cylinder(profile, path, options)
}

/// A sweep as a file holds it: a [`PolyMesh`] of triangles whose vertices are the distinct
/// points of the surface, with face-varying normals (and UVs) that keep its sharp edges sharp.
#[derive(Clone, Debug, PartialEq)]
pub struct SweptMesh {
    /// The mesh.
    pub mesh: PolyMesh,
    /// Corners of the path whose joints may fold over or intersect themselves (the profile
    /// does not fit inside the turn; see [`welded`]).
    pub unfit_corners: Vec<CornerFit>,
}

/// [`generalized_cylinder`]'s surface with every point one vertex (welded layout): walls,
/// creases, joints and caps share their vertices, and the normals and UVs are face-varying.
/// A closed profile swept along a closed path, or capped, is one closed, consistently
/// oriented 2-manifold. In the compat layout, the same mesh as [`generalized_cylinder`].
///
/// # Errors
/// As [`generalized_cylinder`].
pub fn generalized_cylinder_poly(
    profile: &Profile,
    path: &SweepPath,
    options: SweepOptions,
) -> Result<SweptMesh, SweepError> {
    if options.layout == MeshLayout::Compat {
        let mesh = compat_cylinder(profile, path, options)?;
        return Ok(SweptMesh { mesh: PolyMesh::from(&mesh), unfit_corners: Vec::new() });
    }
    CylinderLayout::new(profile, path, options)?;
    let built = welded::build(profile, path, options)?;
    Ok(SweptMesh { mesh: weld(&built.split, &built.pid, &built.positions), unfit_corners: built.unfit })
}

/// The polygon mesh of a split mesh whose vertex `v` is at the position with id `pid[v]` in
/// `positions`: a vertex per position a triangle uses (in order of id), and the split
/// vertices' normals and UVs, the ones triangles use, as face-varying attributes (in order of
/// first use: the callers point the triangles at one split vertex where the sides agree, see
/// [`attribute_twins`]). Triangles with a repeated position are left out.
fn weld(split: &TriMesh, pid: &[u32], positions: &[DVec3]) -> PolyMesh {
    let mut used = vec![false; positions.len()];
    let triangles: Vec<[u32; 3]> = split
        .triangles
        .iter()
        .filter(|t| {
            let [a, b, c] = t.map(|v| pid[v as usize]);
            a != b && b != c && a != c
        })
        .copied()
        .collect();
    for t in &triangles {
        t.iter().for_each(|&v| used[pid[v as usize] as usize] = true);
    }
    let mut new_id = vec![u32::MAX; positions.len()];
    let mut kept = Vec::new();
    for (id, p) in positions.iter().enumerate().filter(|&(id, _)| used[id]) {
        new_id[id] = kept.len() as u32;
        kept.push(*p);
    }
    let corners: Vec<u32> = triangles.iter().flatten().copied().collect();
    let mut mesh = PolyMesh::from_triangles(kept, &[]);
    mesh.face_vertices = corners.iter().map(|&v| new_id[pid[v as usize] as usize]).collect();
    mesh.face_offsets = (0..=triangles.len()).map(|f| (3 * f) as u32).collect();
    // the attributes: one value per split vertex used, numbered in order of first use
    let mut value_id = vec![u32::MAX; split.positions.len()];
    let mut order = Vec::new();
    let indices: Vec<u32> = corners
        .iter()
        .map(|&v| {
            if value_id[v as usize] == u32::MAX {
                value_id[v as usize] = order.len() as u32;
                order.push(v as usize);
            }
            value_id[v as usize]
        })
        .collect();
    if !split.normals.is_empty() {
        mesh.normals =
            Some(FaceVarying { values: order.iter().map(|&v| split.normals[v]).collect(), indices: indices.clone() });
    }
    if !split.uvs.is_empty() {
        mesh.uvs = Some(FaceVarying { values: order.iter().map(|&v| split.uvs[v]).collect(), indices });
    }
    mesh
}

/// How many earlier vertices at one position [`attribute_twins`] compares a vertex with.
const TWIN_CANDIDATES: usize = 8;

/// Each split vertex's first twin: the first vertex at the same position id with the same UV,
/// the same `smooth` (whether its normal is known yet) and, if known, a normal within `1e-9`.
fn attribute_twins(split: &TriMesh, pid: &[u32], smooth: impl Fn(usize) -> bool) -> Vec<u32> {
    let mut twin: Vec<u32> = (0..split.positions.len() as u32).collect();
    let mut at: std::collections::HashMap<u32, Vec<u32>> = std::collections::HashMap::new();
    for v in 0..split.positions.len() {
        let seen = at.entry(pid[v]).or_default();
        let same = |w: &u32| {
            let w = *w as usize;
            let normals = split.normals.get(w).zip(split.normals.get(v));
            smooth(w) == smooth(v)
                && (!smooth(v) || normals.is_none_or(|(a, b)| a.dot(*b) > 1.0 - 1e-9))
                && split.uvs.get(w) == split.uvs.get(v)
        };
        // a point has a few sides (a crease, a seam, a cap's rim); a point many copies share
        // (a pole where the path stays put) keeps its first few as candidates, so the search
        // stays linear
        match seen.iter().take(TWIN_CANDIDATES).find(|w| same(w)) {
            Some(&w) => twin[v] = w,
            None => seen.push(v as u32),
        }
    }
    twin
}

/// The course layout of [`generalized_cylinder`].
fn compat_cylinder(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<TriMesh, SweepError> {
    let CylinderLayout { p, s, wrap_p, wrap_s, twin, cap_ring } = CylinderLayout::new(profile, path, options)?;
    let vs = profile.normalized_lengths();
    let us = normalized_lengths(path.positions.iter().zip(path.positions.iter().skip(1)).map(|(a, b)| a.distance(*b)));

    let mut mesh = TriMesh::default();
    mesh.positions.reserve(p * s);
    mesh.normals.reserve(p * s);
    mesh.triangles.reserve(2 * p * s);
    let scaled = !path.scales.is_empty();
    for (k, ((f, v), u)) in path.frames.iter().zip(&path.positions).zip(&us).take(s).enumerate() {
        let sc = if scaled { path.scales[k] } else { DVec2::ONE };
        for ((q, n), w) in profile.points.iter().zip(&profile.normals).zip(&vs).take(p) {
            mesh.positions.push(f.n * (q.x * sc.x) + f.b * (q.y * sc.y) + *v);
            mesh.normals.push(-(f.n * n.x + f.b * n.y));
            if options.uvs {
                mesh.uvs.push(DVec2::new(*u, *w));
            }
        }
    }
    let id = |k: usize, i: usize| ((k % s) * p + (i % p)) as u32;
    let quads_s = if wrap_s { s } else { s - 1 };
    let quads_p = if wrap_p { p } else { p - 1 };
    for k in 0..quads_s {
        for i in (0..quads_p).filter(|&i| !twin[i]) {
            push_quad(&mut mesh, [id(k, i), id(k, i + 1), id(k + 1, i), id(k + 1, i + 1)], false);
        }
    }
    // outward: away from the sweep curve, per copy (vertex v belongs to copy v / p)
    orient(&mut mesh, |q, v| q - path.positions[v / p]);
    if scaled {
        face_average_normals(&mut mesh);
    }
    if let Some(ring) = cap_ring {
        let sc = |k: usize| if scaled { path.scales[k] } else { DVec2::ONE };
        add_cap(&mut mesh, &ring, path.frames[0], path.positions[0], sc(0), -path.frames[0].t);
        let last = path.positions.len() - 1;
        add_cap(&mut mesh, &ring, path.frames[last], path.positions[last], sc(last), path.frames[last].t);
    }
    Ok(mesh)
}

/// The vertex and triangle counts of [`generalized_cylinder_poly`]`(profile, path, options)`
/// (the file's mesh), without building it: the work is linear in the lengths of the profile
/// and the path, except for a welded sweep along a path with sharp corners, whose joints are
/// built to be counted.
///
/// # Errors
/// As [`generalized_cylinder`].
pub fn generalized_cylinder_counts(
    profile: &Profile,
    path: &SweepPath,
    options: SweepOptions,
) -> Result<MeshCounts, SweepError> {
    let CylinderLayout { p, s, wrap_p, wrap_s, twin, cap_ring } = CylinderLayout::new(profile, path, options)?;
    if options.layout == MeshLayout::Welded {
        let n = path.positions.len();
        let size = extent(path.positions.iter().copied()).max(1e-300);
        let repeats = (1..n).any(|k| path.positions[k - 1].distance(path.positions[k]) <= 1e-12 * size);
        let pinched = path.scales.iter().any(|s| s.x == 0.0 || s.y == 0.0);
        let seam_corner = path.is_closed() && path.frames[0].t.dot(path.frames[n - 1].t) < 1.0 - 1e-12;
        if repeats || pinched || seam_corner {
            let m = generalized_cylinder_poly(profile, path, options)?.mesh;
            return Ok(MeshCounts { vertices: m.num_vertices() as u64, triangles: m.num_faces() as u64 });
        }
        // a vertex per distinct profile point and path point; the closing copy of a
        // closed path is the first one
        let slots = welded::Slots::new(profile);
        let rings = if path.is_closed() { n - 1 } else { n };
        let strips = slots.strips.len() as u64;
        // (a profile of one distinct point makes no triangle, and has no vertex in the file)
        let used = if strips == 0 { 0 } else { slots.first_slot.len() };
        let mut counts = MeshCounts { vertices: (used * rings) as u64, triangles: 2 * strips * (n as u64 - 1) };
        if cap_ring.is_some() {
            counts.triangles += 2 * slots.first_slot.len().saturating_sub(2) as u64;
        }
        return Ok(counts);
    }
    let quads_s = if wrap_s { s } else { s - 1 };
    let quads_p = if wrap_p { p } else { p - 1 };
    // no quad has a repeated corner: p, s ≥ 2, and a wrapped curve has at least 2 distinct samples
    let strips = (0..quads_p).filter(|&i| !twin[i]).count() as u64;
    let mut counts = MeshCounts { vertices: (p * s) as u64, triangles: 2 * strips * quads_s as u64 };
    if let Some(ring) = cap_ring {
        // each cap: its ring's vertices, and an (n − 2)-triangle polygon triangulation
        counts.vertices += 2 * ring.len() as u64;
        counts.triangles += 2 * ring.len().saturating_sub(2) as u64;
    }
    Ok(counts)
}

/// How a generalized cylinder's copies of the profile are laid out.
struct CylinderLayout {
    /// Profile points and path points with vertices of their own.
    p: usize,
    s: usize,
    /// The profile (path) wraps around: its last sample is its first, shared (welded layout).
    wrap_p: bool,
    wrap_s: bool,
    /// See [`twins`].
    twin: Vec<bool>,
    /// The profile ring each end cap triangulates, when the sweep is capped.
    cap_ring: Option<Vec<DVec2>>,
}

impl CylinderLayout {
    fn new(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<Self, SweepError> {
        profile.check()?;
        path.check()?;
        // the copies of the profile and two caps
        check_vertex_count((path.positions.len() as f64 + 2.0) * profile.points.len() as f64)?;
        let welded = options.layout == MeshLayout::Welded;
        let p_all = profile.points.len();
        let s_all = path.positions.len();
        // welded: drop the repeated seam point / copy and wrap instead (unless UVs need it)
        // (a closed curve whose ends meet at a corner keeps both end samples: a crease)
        let n_last = profile.normals[p_all - 1];
        let wrap_p = welded && !options.uvs && profile.is_closed() && profile.normals[0].dot(n_last) > 1.0 - 1e-9;
        let t_last = path.frames[s_all - 1].t;
        let wrap_s = welded && !options.uvs && path.is_closed() && path.frames[0].t.dot(t_last) > 1.0 - 1e-9;
        let capped = options.caps && !path.is_closed() && profile.is_closed();
        Ok(Self {
            p: if wrap_p { p_all - 1 } else { p_all },
            s: if wrap_s { s_all - 1 } else { s_all },
            wrap_p,
            wrap_s,
            twin: twins(&profile.points, welded),
            cap_ring: capped.then(|| cap_ring(&profile.points[..p_all - 1])),
        })
    }
}

/// The points of a closed profile (without its repeated last point) a cap is made of: a
/// crease samples its corner twice (one point per side), and the cap needs it once, or its
/// triangulation gets zero-area triangles.
fn cap_ring(ring: &[DVec2]) -> Vec<DVec2> {
    let mut ring: Vec<DVec2> = ring.to_vec();
    ring.dedup();
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    ring
}

/// A flat cap: the profile ring (from [`cap_ring`]) placed with `frame` at `centre`,
/// triangulated, facing `outward`.
fn add_cap(mesh: &mut TriMesh, ring: &[DVec2], frame: Frame, centre: DVec3, scale: DVec2, outward: DVec3) {
    let base = mesh.positions.len() as u32;
    let uv = !mesh.uvs.is_empty();
    for q in ring {
        mesh.positions.push(frame.n * (q.x * scale.x) + frame.b * (q.y * scale.y) + centre);
        mesh.normals.push(outward.normalize_or_zero());
        if uv {
            mesh.uvs.push(*q);
        }
    }
    let tris = triangulate_polygon(ring);
    let first = mesh.triangles.len();
    mesh.triangles.extend(tris.iter().map(|t| t.map(|i| base + i as u32)));
    let facing: f64 = (first..mesh.triangles.len()).map(|i| mesh.face_normal(i).dot(outward)).sum();
    if facing < 0.0 {
        for t in &mut mesh.triangles[first..] {
            t.swap(1, 2);
        }
    }
}

/// Ear-clipping triangulation of a simple polygon (either orientation); indices into
/// `points`. A polygon that is not simple falls back to a fan over what is left when no ear
/// is found in a whole turn.
///
/// The ring is a linked list, and only reflex (or flat) corners can lie in an ear of a simple
/// polygon, so each ear test looks at those in a grid of cells over the triangle's box
/// (a cap of 20 000 points took minutes when every clip started over and tested every point).
#[must_use]
pub fn triangulate_polygon(points: &[DVec2]) -> Vec<[usize; 3]> {
    let n = points.len();
    if n < 3 {
        return Vec::new();
    }
    let area: f64 = (0..n).map(|i| points[i].perp_dot(points[(i + 1) % n])).sum();
    let sign = if area < 0.0 { -1.0 } else { 1.0 };
    let cross = |a: usize, b: usize, c: usize| sign * (points[b] - points[a]).perp_dot(points[c] - points[a]);
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    // reflex or flat corners (never clipped; a corner only turns convex as ears go)
    let mut reflex: Vec<bool> = (0..n).map(|i| cross(prev[i], i, next[i]) <= 0.0).collect();
    let grid = ReflexGrid::new(points, &reflex);
    let mut alive = vec![true; n];
    let mut out = Vec::with_capacity(n - 2);
    let (mut remaining, mut i, mut tried) = (n, 0, 0);
    while remaining > 3 && tried < remaining {
        let (a, c) = (prev[i], next[i]);
        let ear = !reflex[i]
            && !grid.any_in([points[a], points[i], points[c]], |j| {
                alive[j] && reflex[j] && j != a && j != i && j != c && {
                    cross(a, i, j) >= 0.0 && cross(i, c, j) >= 0.0 && cross(c, a, j) >= 0.0
                }
            });
        if !ear {
            (i, tried) = (c, tried + 1);
            continue;
        }
        out.push([a, i, c]);
        alive[i] = false;
        (next[a], prev[c]) = (c, a);
        remaining -= 1;
        reflex[a] = cross(prev[a], a, c) <= 0.0;
        reflex[c] = cross(a, c, next[c]) <= 0.0;
        // the corner before the ear changed: try it first
        (i, tried) = (a, 0);
    }
    // three left, or not simple: a fan over what is left
    let ring: Vec<usize> = core::iter::successors(Some(i), |&v| Some(next[v])).take(remaining).collect();
    for w in 1..ring.len() - 1 {
        out.push([ring[0], ring[w], ring[w + 1]]);
    }
    out
}

/// The reflex corners of a polygon in a uniform grid of about one corner per cell, for ear
/// tests.
struct ReflexGrid {
    lo: DVec2,
    /// Cells per unit length.
    inv: DVec2,
    side: usize,
    cells: Vec<Vec<usize>>,
}

impl ReflexGrid {
    fn new(points: &[DVec2], reflex: &[bool]) -> Self {
        let corners: Vec<usize> = (0..points.len()).filter(|&i| reflex[i] && points[i].is_finite()).collect();
        let (lo, hi) = corners
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &i| (lo.min(points[i]), hi.max(points[i])));
        let side = ((corners.len() as f64).sqrt().ceil() as usize).clamp(1, 1024);
        let span = hi - lo;
        let inv = DVec2::new(
            if span.x > 0.0 && span.x.is_finite() { side as f64 / span.x } else { 0.0 },
            if span.y > 0.0 && span.y.is_finite() { side as f64 / span.y } else { 0.0 },
        );
        let mut grid = Self { lo, inv, side, cells: vec![Vec::new(); side * side] };
        for i in corners {
            let [x, y] = grid.cell(points[i]);
            grid.cells[y * side + x].push(i);
        }
        grid
    }

    /// The cell of `p`, clamped to the grid.
    fn cell(&self, p: DVec2) -> [usize; 2] {
        let q = (p - self.lo) * self.inv;
        let at = |v: f64| if v > 0.0 { (v as usize).min(self.side - 1) } else { 0 };
        [at(q.x), at(q.y)]
    }

    /// Whether `hit` holds for a corner in a cell over the box of `tri`.
    fn any_in(&self, tri: [DVec2; 3], hit: impl Fn(usize) -> bool) -> bool {
        let lo = tri[0].min(tri[1]).min(tri[2]);
        let hi = tri[0].max(tri[1]).max(tri[2]);
        let ([x0, y0], [x1, y1]) = (self.cell(lo), self.cell(hi));
        (y0..=y1).any(|y| (x0..=x1).any(|x| self.cells[y * self.side + x].iter().any(|&j| hit(j))))
    }
}

/// Vertex normals from the area-weighted normals of the faces around each vertex.
fn face_average_normals(mesh: &mut TriMesh) {
    let sums = mesh.vertex_normal_sums();
    for (n, s) in mesh.normals.iter_mut().zip(sums) {
        if let Some(u) = s.try_normalize() {
            *n = u;
        }
    }
}

/// `twin[i]`: profile points `i` and `i + 1` coincide (a crease sampled twice) and, in the
/// welded layout, the zero-width strip between them is left out.
fn twins(points: &[DVec2], welded: bool) -> Vec<bool> {
    let size = extent(points.iter().map(|q| q.extend(0.0)));
    let mut twin: Vec<bool> = points.windows(2).map(|w| welded && w[0].distance(w[1]) <= 1e-12 * size).collect();
    // the closing pair (last, first) of a wrapped profile
    twin.push(false);
    twin
}

/// Two triangles `(a, b, c)` and `(b, d, c)` of the quad `a b / c d`; in welded layout,
/// triangles with a repeated vertex are left out.
fn push_quad(mesh: &mut TriMesh, [a, b, c, d]: [u32; 4], welded: bool) {
    for t in [[a, b, c], [b, d, c]] {
        if !(welded && (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])) {
            mesh.triangles.push(t);
        }
    }
}

/// Flips the mesh if its face normals point, on balance, against `outward(position, index)`
/// summed over each triangle's corners, then aligns the vertex normals with the faces.
///
/// One pass: the agreement of vertex and face normals is summed with the faces as they are,
/// and a flip of the faces negates every term exactly (swapping two corners negates the cross
/// product bit for bit), so it is the same sum, negated, as after the flip.
fn orient(mesh: &mut TriMesh, outward: impl Fn(DVec3, usize) -> DVec3) {
    orient_where(mesh, outward, |_| true);
}

/// [`orient`], with the vertex normals' agreement summed over the vertices `counted` says.
fn orient_where(mesh: &mut TriMesh, outward: impl Fn(DVec3, usize) -> DVec3, counted: impl Fn(usize) -> bool) {
    let mut flux = 0.0;
    let mut agreement = 0.0;
    for (i, t) in mesh.triangles.iter().enumerate() {
        let face = mesh.face_normal(i);
        let out: DVec3 = t.iter().map(|&v| outward(mesh.positions[v as usize], v as usize)).sum();
        flux += face.dot(out);
        for &v in t.iter().filter(|&&v| counted(v as usize)) {
            agreement += face.dot(mesh.normals[v as usize]);
        }
    }
    if flux < 0.0 {
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
        agreement = -agreement;
    }
    // the vertex normals disagree, on balance, with the faces around them
    if agreement < 0.0 {
        for n in &mut mesh.normals {
            *n = -*n;
        }
    }
}

/// Pole vertices get the area-weighted normal of their faces (along the axis).
fn fix_pole_normals(mesh: &mut TriMesh, pole: &[u32]) {
    // the face normals summed at the poles only, in triangle order (as `vertex_normal_sums`)
    let mut sums = vec![None; mesh.positions.len()];
    for &v in pole.iter().filter(|&&v| v != u32::MAX) {
        sums[v as usize] = Some(DVec3::ZERO);
    }
    for (i, t) in mesh.triangles.iter().enumerate() {
        if t.iter().any(|&v| sums[v as usize].is_some()) {
            let face = mesh.face_normal(i);
            for &v in t {
                if let Some(sum) = &mut sums[v as usize] {
                    *sum += face;
                }
            }
        }
    }
    for &v in pole.iter().filter(|&&v| v != u32::MAX) {
        if let Some(n) = sums[v as usize].and_then(DVec3::try_normalize) {
            mesh.normals[v as usize] = n;
        }
    }
}
