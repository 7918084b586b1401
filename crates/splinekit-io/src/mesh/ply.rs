//! The PLY writer (binary little endian).

use std::io::{BufWriter, Write};

use splinekit::TriMesh;

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

/// Writes the header and the records.
fn write_body<W: Write>(mesh: &TriMesh, w: &mut W) -> std::io::Result<()> {
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
    header += &format!("element face {}\n", mesh.triangles.len());
    header += "property list uchar int vertex_indices\nend_header\n";
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
    for tri in &mesh.triangles {
        let mut record = [0u8; 13];
        record[0] = 3;
        for (k, &v) in tri.iter().enumerate() {
            // Checked by the caller: every index is below the vertex count, which fits an i32.
            let v = i32::try_from(v).unwrap_or(i32::MAX);
            record[1 + 4 * k..5 + 4 * k].copy_from_slice(&v.to_le_bytes());
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
