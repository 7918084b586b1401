//! The oracle's checks on successful results: every number finite, every index in range.

use glam::{DVec2, DVec3};
use splinekit::frame::Frame;
use splinekit::{PolyMesh, TriMesh};

use crate::{Finding, FindingKind};

/// Numbers at most this large (in magnitude) cannot overflow in the computations fed here
/// (their squares, sums of squares and products with the library's constants stay far below
/// `f64::MAX`). An input with a larger number may give results that overflow to infinity;
/// the commands refuse those (`splinekit curve` and `arclen` say the curve overflows, the mesh
/// writers refuse a non-finite vertex), and the oracle counts them as refusals.
pub const LARGE: f64 = 1e100;

/// Whether `x` counts as large (see [`LARGE`]).
pub fn is_large(x: f64) -> bool {
    !(x.abs() <= LARGE)
}

/// The largest magnitude among `values`.
pub fn max_abs(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, |m: f64, x| if x.is_nan() { f64::INFINITY } else { m.max(x.abs()) })
}

/// A [`FindingKind::NonFinite`] finding.
pub fn non_finite(what: impl Into<String>) -> Finding {
    Finding::new(FindingKind::NonFinite, what)
}

/// Fails unless `x` is finite.
pub fn scalar(x: f64, what: &str) -> Result<(), Finding> {
    if x.is_finite() { Ok(()) } else { Err(non_finite(format!("{what} is {x}"))) }
}

/// Fails unless every point is finite.
pub fn points(points: &[DVec3], what: &str) -> Result<(), Finding> {
    match points.iter().position(|p| !p.is_finite()) {
        Some(i) => Err(non_finite(format!("{what} {i} is {}", points[i]))),
        None => Ok(()),
    }
}

/// Fails unless every 2D point is finite.
pub fn points_2d(points: &[DVec2], what: &str) -> Result<(), Finding> {
    match points.iter().position(|p| !p.is_finite()) {
        Some(i) => Err(non_finite(format!("{what} {i} is {}", points[i]))),
        None => Ok(()),
    }
}

/// Fails unless every frame is finite.
pub fn frames(frames: &[Frame], what: &str) -> Result<(), Finding> {
    match frames.iter().position(|f| !f.is_finite()) {
        Some(i) => {
            let f = frames[i];
            Err(non_finite(format!("{what} frame {i} is T {} N {} B {}", f.t, f.n, f.b)))
        }
        None => Ok(()),
    }
}

/// Fails unless the triangle mesh is valid: indices in range, attribute lengths right,
/// everything finite ([`TriMesh::validate`], which every writer applies).
pub fn tri_mesh(mesh: &TriMesh, what: &str) -> Result<(), Finding> {
    mesh.validate().map_err(|e| {
        let kind = if e.to_string().contains("finite") { FindingKind::NonFinite } else { FindingKind::Invalid };
        Finding::new(kind, format!("{what}: {e}"))
    })
}

/// Fails unless the polygon mesh's indices are in range and its values finite.
pub fn poly_mesh(mesh: &PolyMesh, what: &str) -> Result<(), Finding> {
    let n = mesh.num_vertices();
    let offsets_ok = mesh.face_offsets.first() == Some(&0)
        && mesh.face_offsets.windows(2).all(|w| w[0] <= w[1])
        && mesh.face_offsets.last().map(|&o| o as usize) == Some(mesh.face_vertices.len());
    if !offsets_ok {
        return Err(Finding::new(FindingKind::Invalid, format!("{what}: face offsets out of order")));
    }
    if let Some(v) = mesh.face_vertices.iter().find(|&&v| v as usize >= n) {
        return Err(Finding::new(FindingKind::Invalid, format!("{what}: vertex index {v} of {n} vertices")));
    }
    points(&mesh.positions, &format!("{what}: position"))?;
    points(&mesh.colors, &format!("{what}: colour"))?;
    if let Some(normals) = &mesh.normals {
        points(&normals.values, &format!("{what}: normal"))?;
    }
    if let Some(uvs) = &mesh.uvs {
        points_2d(&uvs.values, &format!("{what}: texture coordinate"))?;
    }
    Ok(())
}
