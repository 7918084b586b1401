//! The vertex data of the mesh shown, made on the CPU (also off the UI thread,
//! [`PreparedMesh`]), and the bounds the view frames ([`bounds`], [`point_bounds`]).

use glam::{DVec3, Vec3};
use splinekit::TriMesh;

/// Bytes per triangle corner: position (3 × f32), normal (3 × f32), sRGB colour (4 × u8).
pub(super) const SURFACE_STRIDE: u64 = 28;
/// Bytes per normal-line end: position (3 × f32).
pub(super) const LINE_STRIDE: u64 = 12;

/// The vertex data of the current mesh, ready to upload.
#[derive(Default)]
pub(super) struct MeshData {
    /// Three corners per drawn triangle, [`SURFACE_STRIDE`] bytes each.
    pub(super) surface: Vec<u8>,
    /// Two ends per normal line, [`LINE_STRIDE`] bytes each.
    pub(super) lines: Vec<u8>,
    /// Subtracted from positions before they go to f32 (the bounding-box centre).
    pub(super) origin: DVec3,
    /// Largest distance of a finite position from `origin`.
    pub(super) radius: f64,
    pub(super) has_colours: bool,
    /// Bumped whenever the data changes.
    pub(super) generation: u64,
}

impl MeshData {
    /// Centre and radius of the bounding sphere (radius 1 when there is no extent).
    pub(super) fn centre_radius(&self) -> (DVec3, f64) {
        let r = self.radius;
        (self.origin, if r > 0.0 && r.is_finite() { r } else { 1.0 })
    }
}

/// Scratch space of [`View3d::set_mesh`](super::View3d::set_mesh), kept to avoid reallocating every frame.
#[derive(Default)]
pub(super) struct Scratch {
    normals: Vec<Vec3>,
    normal_sums: Vec<DVec3>,
    records: Vec<[u8; SURFACE_STRIDE as usize]>,
    pub(super) surface: Vec<u8>,
    pub(super) lines: Vec<u8>,
}

/// A mesh's vertex data for the 3D view, made where it takes no time from the UI thread (a
/// few hundred milliseconds for millions of triangles); [`View3d::set_prepared`](super::View3d::set_prepared) shows it.
pub struct PreparedMesh {
    pub(super) surface: Vec<u8>,
    pub(super) lines: Vec<u8>,
    pub(super) origin: DVec3,
    pub(super) radius: f64,
    pub(super) colours: bool,
}

impl PreparedMesh {
    /// The vertex data of `mesh` (as [`View3d::set_mesh`](super::View3d::set_mesh) makes it).
    #[must_use]
    pub fn new(mesh: &TriMesh) -> Self {
        let mut scratch = Scratch::default();
        let (origin, radius, colours) = prepare(mesh, &mut scratch);
        Self { surface: scratch.surface, lines: scratch.lines, origin, radius, colours }
    }

    /// The number of triangles it draws.
    #[must_use]
    pub fn num_triangles(&self) -> usize {
        self.surface.len() / (3 * SURFACE_STRIDE as usize)
    }
}

/// Fills `scratch.surface` and `scratch.lines` with the vertex data of `mesh`; returns its
/// origin, radius and whether it has colours.
///
/// Triangles with an index out of range or a non-finite corner are left out. Normals
/// come from the mesh when it has one per vertex, otherwise they are area-weighted;
/// colours likewise, read as sRGB in `[0, 1]`.
pub(super) fn prepare(mesh: &TriMesh, scratch: &mut Scratch) -> (DVec3, f64, bool) {
    let n = mesh.positions.len();
    let (origin, radius) = bounds(mesh);
    let valid = |t: &[u32; 3]| t.iter().all(|&v| (v as usize) < n && mesh.positions[v as usize].is_finite());

    // Unit vertex normals.
    let normals = &mut scratch.normals;
    normals.clear();
    if mesh.normals.len() == n {
        normals.extend(mesh.normals.iter().map(|v| v.normalize_or_zero().as_vec3()));
    } else {
        let sums = &mut scratch.normal_sums;
        sums.clear();
        sums.resize(n, DVec3::ZERO);
        for t in mesh.triangles.iter().filter(|t| valid(t)) {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            let face = (b - a).cross(c - a);
            for &v in t {
                sums[v as usize] += face;
            }
        }
        normals.extend(sums.iter().map(|v| v.normalize_or_zero().as_vec3()));
    }
    let colours = mesh.colors.len() == n;
    let srgb8 = |c: DVec3| c.clamp(DVec3::ZERO, DVec3::ONE).to_array().map(|x| (x * 255.0).round() as u8);

    // One record per vertex, then three copied per triangle.
    let records = &mut scratch.records;
    records.clear();
    records.extend(mesh.positions.iter().zip(normals.iter()).enumerate().map(|(v, (p, nv))| {
        let mut r = [0u8; SURFACE_STRIDE as usize];
        let p = (*p - origin).as_vec3();
        for (k, x) in [p.x, p.y, p.z, nv.x, nv.y, nv.z].into_iter().enumerate() {
            r[4 * k..4 * k + 4].copy_from_slice(&x.to_le_bytes());
        }
        let [red, green, blue] = if colours { srgb8(mesh.colors[v]) } else { [255; 3] };
        r[24..].copy_from_slice(&[red, green, blue, 255]);
        r
    }));
    let surface = &mut scratch.surface;
    surface.clear();
    surface.reserve(mesh.triangles.len() * 3 * SURFACE_STRIDE as usize);
    let mut edge_sum = 0.0;
    let mut edges = 0usize;
    for t in mesh.triangles.iter().filter(|t| valid(t)) {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        edge_sum += a.distance(b) + b.distance(c) + c.distance(a);
        edges += 3;
        for &v in t {
            surface.extend_from_slice(&records[v as usize]);
        }
    }

    // Normal lines: half the mean edge length, at most a tenth of the radius.
    let length = if edges > 0 { 0.5 * edge_sum / edges as f64 } else { 0.05 * radius }.min(0.1 * radius);
    let lines = &mut scratch.lines;
    lines.clear();
    for (p, nv) in mesh.positions.iter().zip(normals.iter()) {
        if p.is_finite() && *nv != Vec3::ZERO {
            push_vec3(lines, (*p - origin).as_vec3());
            push_vec3(lines, (*p - origin + length * nv.as_dvec3()).as_vec3());
        }
    }

    (origin, radius, colours)
}

/// The centre of the bounding box of `mesh`'s finite positions (the origin if there are
/// none), and the largest distance of one from it: the bounding sphere the view frames.
#[must_use]
pub fn bounds(mesh: &TriMesh) -> (DVec3, f64) {
    point_bounds(|| mesh.positions.iter().copied())
}

/// [`bounds`] of the points `points()` gives (called twice: box, then sphere).
pub fn point_bounds<I: Iterator<Item = DVec3>>(points: impl Fn() -> I) -> (DVec3, f64) {
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    for p in points().filter(|p| p.is_finite()) {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let origin = if lo.x <= hi.x { 0.5 * (lo + hi) } else { DVec3::ZERO };
    // Bounding sphere about the box centre, tighter than the box's.
    let radius = points().filter(|p| p.is_finite()).map(|p| p.distance_squared(origin)).fold(0.0, f64::max).sqrt();
    (origin, radius)
}

pub(super) fn push_vec3(out: &mut Vec<u8>, v: Vec3) {
    for x in v.to_array() {
        out.extend_from_slice(&x.to_le_bytes());
    }
}
