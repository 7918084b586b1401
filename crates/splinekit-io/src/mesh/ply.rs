//! The PLY writer (binary little endian).

use std::io::{BufWriter, Write};

use glam::DVec2;
use splinekit::mesh::FaceVarying;
use splinekit::{PolyMesh, TriMesh};

use super::{MeshIoError, MeshIoErrorKind, to_f32};

/// The format name used in messages.
const FORMAT: &str = "binary PLY";

/// Writes `mesh` as a binary little-endian PLY file.
///
/// The header is ASCII:
///
/// ```text
/// ply
/// format binary_little_endian 1.0
/// comment written by splinekit-io
/// element vertex N
/// property float x
/// property float y
/// property float z
/// property float nx        (nx, ny, nz only if the mesh has normals)
/// property float ny
/// property float nz
/// property float u         (u, v only if the mesh has UVs)
/// property float v
/// property uchar red       (red, green, blue only if the mesh has colours: round(255·c),
/// property uchar green      clamped to 0 … 255)
/// property uchar blue
/// element face M
/// property list uchar int vertex_indices
/// end_header
/// ```
///
/// followed by N vertex records of little-endian `f32`s in that order, and M face records
/// `3 a b c` (a `u8` count and three little-endian `i32` indices, counter-clockwise from the
/// front). Coordinates are rounded to the nearest `f32`. The same mesh always gives the same
/// bytes.
///
/// Output is buffered internally; `out` need not be buffered.
///
/// # Errors
///
/// [`InvalidMesh`](MeshIoErrorKind::InvalidMesh) if the mesh fails [`TriMesh::validate`],
/// [`Unrepresentable`](MeshIoErrorKind::Unrepresentable) if a coordinate is beyond the `f32`
/// range or the mesh has more vertices than an `int` index can address (2³¹); nothing is
/// written in these cases. An [`Io`](MeshIoErrorKind::Io) error from `out`.
pub fn write_ply<W: Write + ?Sized>(mesh: &TriMesh, out: &mut W) -> Result<(), MeshIoError> {
    super::check(mesh)?;
    if i32::try_from(mesh.positions.len()).is_err() {
        return Err(MeshIoError::new(MeshIoErrorKind::Unrepresentable {
            format: FORMAT,
            what: format!("vertex count {} (indices are 32-bit signed `int`)", mesh.positions.len()),
        }));
    }
    super::check_f32_range(mesh, FORMAT, true)?;

    let mut w = BufWriter::with_capacity(super::BUFFER_SIZE, out);
    write_body(mesh, &mut w).map_err(MeshIoError::write)?;
    w.flush().map_err(MeshIoError::write)
}

/// Writes a polygon mesh as a binary little-endian PLY file that keeps its vertices and
/// faces: the header of [`write_ply`] with polygons in the face lists, and
///
/// - normals as vertex properties `nx ny nz` when every vertex has one normal (the same value
///   at all its corners); face-varying normals that differ at a vertex cannot be held by PLY
///   and are left out (the returned flag says so);
/// - UVs as vertex properties `u v` when every vertex has one UV, else as MeshLab's per-corner
///   `property list uchar float texcoord` on the faces (two numbers a corner), so a vertex on a
///   UV seam stays one vertex.
///
/// Returns whether normals were left out.
///
/// # Errors
///
/// As [`write_ply`] (checked on the mesh's fan triangulation), a face of more than 255
/// corners, or an attribute whose indices do not match the corners or its values; nothing is
/// written then.
pub fn write_ply_poly<W: Write + ?Sized>(mesh: &PolyMesh, out: &mut W) -> Result<bool, MeshIoError> {
    let corners = mesh.face_vertices.len();
    let normals = super::obj::channel(mesh, mesh.normals.as_ref(), "normals")?;
    let uvs = super::obj::channel(mesh, mesh.uvs.as_ref(), "UVs")?;
    let vertex_normals = normals.and_then(|a| one_per_vertex(mesh, a));
    let normals_left_out = normals.is_some() && vertex_normals.is_none();
    let vertex_uvs = uvs.and_then(|a| one_per_vertex(mesh, a));
    let corner_uvs = if vertex_uvs.is_none() { uvs } else { None };
    // the per-vertex parts as a triangle mesh: the checks and the vertex records of `write_ply`
    let mut tri = mesh.to_tri_mesh();
    tri.normals = vertex_normals.unwrap_or_default();
    tri.uvs = vertex_uvs.unwrap_or_default();
    super::check(&tri)?;
    if i32::try_from(mesh.positions.len()).is_err() || u32::try_from(corners).is_err() {
        return Err(MeshIoError::new(MeshIoErrorKind::Unrepresentable {
            format: FORMAT,
            what: format!("vertex count {} (indices are 32-bit signed `int`)", mesh.positions.len()),
        }));
    }
    // a `uchar` counts a face's corners, and its texcoord list's two numbers a corner
    let most = if corner_uvs.is_some() { usize::from(u8::MAX) / 2 } else { usize::from(u8::MAX) };
    if let Some(f) = mesh.faces().position(|f| f.len() > most) {
        return Err(MeshIoError::new(MeshIoErrorKind::Unrepresentable {
            format: FORMAT,
            what: format!("face {f} of {} corners (at most {most}: list lengths are a `uchar`)", mesh.face(f).len()),
        }));
    }
    super::check_f32_range(&tri, FORMAT, true)?;
    if let Some(c) =
        corner_uvs.and_then(|a| a.values.iter().position(|t| !to_f32(t.x).is_finite() || !to_f32(t.y).is_finite()))
    {
        return Err(MeshIoError::new(MeshIoErrorKind::Unrepresentable { format: FORMAT, what: format!("UV {c}") }));
    }
    let mut w = BufWriter::with_capacity(super::BUFFER_SIZE, out);
    let body = |w: &mut BufWriter<&mut W>| -> std::io::Result<()> {
        let faces = Faces { corners: &mesh.face_vertices, offsets: Some(&mesh.face_offsets), uvs: corner_uvs };
        write_records(&tri, &faces, w)
    };
    body(&mut w).map_err(MeshIoError::write)?;
    w.flush().map_err(MeshIoError::write)?;
    Ok(normals_left_out)
}

/// The values of `attribute`, one per vertex, when every vertex's corners name one value (a
/// vertex of no face gets the zero value).
fn one_per_vertex<T: Copy + Default + PartialEq>(mesh: &PolyMesh, attribute: &FaceVarying<T>) -> Option<Vec<T>> {
    let mut out: Vec<Option<T>> = vec![None; mesh.positions.len()];
    for (&v, &i) in mesh.face_vertices.iter().zip(&attribute.indices) {
        let value = attribute.values[i as usize];
        match &mut out[v as usize] {
            Some(seen) if *seen != value => return None,
            slot => *slot = Some(value),
        }
    }
    Some(out.into_iter().map(Option::unwrap_or_default).collect())
}

/// The faces to write: every corner's vertex, where each face starts (`None`: triangles),
/// and UVs per corner if any.
struct Faces<'m> {
    corners: &'m [u32],
    offsets: Option<&'m [u32]>,
    uvs: Option<&'m FaceVarying<DVec2>>,
}

impl Faces<'_> {
    fn count(&self) -> usize {
        self.offsets.map_or(self.corners.len() / 3, |o| o.len() - 1)
    }

    /// The corners of face `f`.
    fn range(&self, f: usize) -> std::ops::Range<usize> {
        match self.offsets {
            Some(o) => o[f] as usize..o[f + 1] as usize,
            None => 3 * f..3 * f + 3,
        }
    }
}

/// Writes the header and the records.
fn write_body<W: Write>(mesh: &TriMesh, w: &mut W) -> std::io::Result<()> {
    write_records(mesh, &Faces { corners: mesh.triangles.as_flattened(), offsets: None, uvs: None }, w)
}

/// Writes the header, the vertex records of `mesh` (positions and its per-vertex normals, UVs
/// and colours) and the face records of `faces`.
fn write_records<W: Write>(mesh: &TriMesh, faces: &Faces<'_>, w: &mut W) -> std::io::Result<()> {
    let (has_normals, has_uvs, has_colors) = (!mesh.normals.is_empty(), !mesh.uvs.is_empty(), !mesh.colors.is_empty());
    let mut header = String::from("ply\nformat binary_little_endian 1.0\ncomment written by splinekit-io\n");
    header += &format!("element vertex {}\n", mesh.positions.len());
    header += "property float x\nproperty float y\nproperty float z\n";
    if has_normals {
        header += "property float nx\nproperty float ny\nproperty float nz\n";
    }
    if has_uvs {
        header += "property float u\nproperty float v\n";
    }
    if has_colors {
        header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    }
    header += &format!("element face {}\n", faces.count());
    header += "property list uchar int vertex_indices\n";
    if faces.uvs.is_some() {
        header += "property list uchar float texcoord\n";
    }
    header += "end_header\n";
    w.write_all(header.as_bytes())?;

    for (i, p) in mesh.positions.iter().enumerate() {
        for x in p.to_array() {
            w.write_all(&to_f32(x).to_le_bytes())?;
        }
        if has_normals {
            for x in mesh.normals[i].to_array() {
                w.write_all(&to_f32(x).to_le_bytes())?;
            }
        }
        if has_uvs {
            for x in mesh.uvs[i].to_array() {
                w.write_all(&to_f32(x).to_le_bytes())?;
            }
        }
        if has_colors {
            // Clamped and rounded: the cast cannot truncate.
            w.write_all(&mesh.colors[i].to_array().map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8))?;
        }
    }
    let mut record = Vec::new();
    for f in 0..faces.count() {
        let corners = faces.range(f);
        record.clear();
        // Checked by the callers: at most 255 corners, every index fits an i32.
        record.push(u8::try_from(corners.len()).unwrap_or(u8::MAX));
        for &v in &faces.corners[corners.clone()] {
            record.extend_from_slice(&i32::try_from(v).unwrap_or(i32::MAX).to_le_bytes());
        }
        if let Some(uvs) = faces.uvs {
            // two numbers a corner (checked by the caller: at most 127 corners)
            record.push(u8::try_from(2 * corners.len()).unwrap_or(u8::MAX));
            for &i in &uvs.indices[corners] {
                for x in uvs.values[i as usize].to_array() {
                    record.extend_from_slice(&to_f32(x).to_le_bytes());
                }
            }
        }
        w.write_all(&record)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn header_and_record_sizes() {
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 2]],
            ..TriMesh::default()
        };
        let mut out = Vec::new();
        write_ply(&mesh, &mut out).unwrap();
        let end = out.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        let header = std::str::from_utf8(&out[..end]).unwrap();
        assert!(header.contains("element vertex 3\n") && !header.contains("nx") && !header.contains(" u\n"));
        assert_eq!(out.len() - end, 3 * 12 + 13);
        assert_eq!(&out[end + 36..], &[3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0]);
    }

    #[test]
    fn coordinate_beyond_f32_is_refused() {
        let mesh = TriMesh { positions: vec![DVec3::new(0.0, 1e300, 0.0)], ..TriMesh::default() };
        let mut out = Vec::new();
        let e = write_ply(&mesh, &mut out).unwrap_err();
        assert!(out.is_empty());
        assert_eq!(e.to_string(), "y coordinate of vertex 0 (1e300) does not fit in binary PLY");
    }
}
