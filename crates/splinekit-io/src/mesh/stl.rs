//! The STL writer (binary).

use std::io::{BufWriter, Write};

use splinekit::TriMesh;

use super::{MeshIoError, MeshIoErrorKind, to_f32};

/// The format name used in messages.
const FORMAT: &str = "binary STL";

/// The 80-byte header text (zero-padded). It must not start with `solid`, or readers may take
/// the file for ASCII STL.
const HEADER_TEXT: &[u8] = b"binary STL written by splinekit-io";

/// Writes `mesh` as a binary STL file.
///
/// Layout: an 80-byte header (`binary STL written by splinekit-io`, zero-padded), the
/// triangle count as a little-endian `u32`, then per triangle the unit face normal and the
/// three corners (counter-clockwise from the front) as little-endian `f32`s, and a zero `u16`
/// attribute word. The face normal is computed in `f64` from the corners, `(b − a) × (c − a)`
/// normalised; a degenerate triangle gets `0 0 0` (which readers take as "compute it
/// yourself"). Vertex normals and UVs are not stored: STL has no place for them. The same mesh
/// always gives the same bytes.
///
/// Output is buffered internally; `out` need not be buffered.
///
/// # Errors
///
/// [`InvalidMesh`](MeshIoErrorKind::InvalidMesh) if the mesh fails [`TriMesh::validate`],
/// [`Unrepresentable`](MeshIoErrorKind::Unrepresentable) if a position is beyond the `f32`
/// range or there are 2³² triangles or more; nothing is written in these cases. An
/// [`Io`](MeshIoErrorKind::Io) error from `out`.
pub fn write_stl<W: Write + ?Sized>(mesh: &TriMesh, out: &mut W) -> Result<(), MeshIoError> {
    super::check(mesh)?;
    let Ok(count) = u32::try_from(mesh.triangles.len()) else {
        return Err(MeshIoError::new(MeshIoErrorKind::Unrepresentable {
            format: FORMAT,
            what: format!("triangle count {}", mesh.triangles.len()),
        }));
    };
    super::check_f32_range(mesh, FORMAT, false)?;

    let mut w = BufWriter::with_capacity(super::BUFFER_SIZE, out);
    write_body(mesh, count, &mut w).map_err(MeshIoError::write)?;
    w.flush().map_err(MeshIoError::write)
}

/// Writes the header and the triangle records.
fn write_body<W: Write>(mesh: &TriMesh, count: u32, w: &mut W) -> std::io::Result<()> {
    let mut header = [0u8; 80];
    header[..HEADER_TEXT.len()].copy_from_slice(HEADER_TEXT);
    w.write_all(&header)?;
    w.write_all(&count.to_le_bytes())?;
    for i in 0..mesh.triangles.len() {
        let normal = mesh.face_normal(i).normalize_or_zero();
        let mut record = [0u8; 50];
        let values = std::iter::once(normal).chain(mesh.corners(i)).flat_map(|v| v.to_array());
        for (k, x) in values.enumerate() {
            record[4 * k..4 * k + 4].copy_from_slice(&to_f32(x).to_le_bytes());
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
    fn layout_and_degenerate_normal() {
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X],
            triangles: vec![[0, 1, 2], [0, 1, 3]],
            ..TriMesh::default()
        };
        let mut out = Vec::new();
        write_stl(&mesh, &mut out).unwrap();
        assert_eq!(out.len(), 84 + 2 * 50);
        assert!(out.starts_with(HEADER_TEXT) && !out.starts_with(b"solid"));
        assert_eq!(&out[80..84], &2u32.to_le_bytes());
        let f = |at: usize| f32::from_le_bytes(out[at..at + 4].try_into().unwrap());
        assert_eq!([f(84), f(88), f(92)], [0.0, 0.0, 1.0]);
        assert_eq!([f(134), f(138), f(142)], [0.0, 0.0, 0.0]);
        assert_eq!(&out[132..134], &[0, 0]);
    }
}
