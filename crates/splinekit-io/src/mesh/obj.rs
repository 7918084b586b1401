//! The Wavefront OBJ writer.

use std::io::{BufWriter, Write};

use glam::{DVec2, DVec3};
use splinekit::mesh::FaceVarying;
use splinekit::{PolyMesh, TriMesh};

use super::MeshIoError;

/// Writes `mesh` as Wavefront OBJ text.
///
/// The output holds, in this order, one line per vertex for each attribute the mesh has —
/// `v x y z` (`v x y z r g b` with colours), then `vn x y z`, then `vt u v` — and one `f` line per triangle with 1-based
/// indices. The face form depends on the attributes: `f a/a/a` (UVs and normals), `f a/a`
/// (UVs only), `f a//a` (normals only) or `f a` (positions only); vertex `i` of the mesh is
/// index `i + 1` of every attribute. No comments, groups or materials are written, so the
/// output can follow a comment header (see
/// [`write_revolution_obj`](super::write_revolution_obj)). An empty mesh writes nothing.
///
/// Numbers are written in the shortest form that reads back as the same `f64` (Rust's `{:?}`:
/// `0.5`, `1.0`, `-2.5e-17`), independent of locale, so the same mesh always gives the same
/// bytes. Lines end with `\n`.
///
/// Output is buffered internally; `out` need not be buffered.
///
/// # Errors
///
/// [`InvalidMesh`](super::MeshIoErrorKind::InvalidMesh) if the mesh fails
/// [`TriMesh::validate`] (nothing is written then), or an
/// [`Io`](super::MeshIoErrorKind::Io) error from `out`.
///
/// # Example
///
/// ```
/// use glam::DVec3;
/// use splinekit::{PolyMesh, TriMesh};
///
/// let mesh = TriMesh {
///     positions: vec![DVec3::ZERO, DVec3::X, DVec3::new(0.0, 0.5, 0.0)],
///     triangles: vec![[0, 1, 2]],
///     ..TriMesh::default()
/// };
/// let mut out = Vec::new();
/// splinekit_io::mesh::write_obj(&mesh, &mut out)?;
/// assert_eq!(String::from_utf8(out)?, "v 0.0 0.0 0.0\nv 1.0 0.0 0.0\nv 0.0 0.5 0.0\nf 1 2 3\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_obj<W: Write + ?Sized>(mesh: &TriMesh, out: &mut W) -> Result<(), MeshIoError> {
    super::check(mesh)?;
    let mut w = BufWriter::with_capacity(super::BUFFER_SIZE, out);
    write_body(mesh, &mut w).map_err(MeshIoError::write)?;
    w.flush().map_err(MeshIoError::write)
}

/// Writes a polygon mesh as Wavefront OBJ text: `v x y z` lines (`v x y z r g b` with one
/// colour per vertex), `vn` and `vt` lines for normals and UVs given per vertex (a channel
/// whose indices are the face corners' vertices), and one `f` line per face with its corners
/// (1-based, `v/t/n` forms as needed), numbers as [`write_obj`]. Face-varying normals and UVs
/// (with seams) are not written.
///
/// # Errors
///
/// [`InvalidMesh`](super::MeshIoErrorKind::InvalidMesh) if the fan triangulation fails
/// [`TriMesh::validate`] (nothing is written then), or an
/// [`Io`](super::MeshIoErrorKind::Io) error from `out`.
pub fn write_obj_poly<W: Write + ?Sized>(mesh: &PolyMesh, out: &mut W) -> Result<(), MeshIoError> {
    // the checks of a triangle mesh, on the fan triangulation (same vertices and indices)
    super::check(&mesh.to_tri_mesh())?;
    let n = mesh.positions.len();
    let mut w = BufWriter::with_capacity(super::BUFFER_SIZE, out);
    let colors = mesh.colors.len() == n;
    let (normals, uvs) = (per_vertex(mesh, mesh.normals.as_ref()), per_vertex(mesh, mesh.uvs.as_ref()));
    let body = |w: &mut BufWriter<&mut W>| -> std::io::Result<()> {
        for (i, p) in mesh.positions.iter().enumerate() {
            if colors {
                let c = mesh.colors[i];
                writeln!(w, "v {:?} {:?} {:?} {:?} {:?} {:?}", p.x, p.y, p.z, c.x, c.y, c.z)?;
            } else {
                write_vec3(w, "v", *p)?;
            }
        }
        for &n in normals.iter().flat_map(|c| &c.values) {
            write_vec3(w, "vn", n)?;
        }
        for &t in uvs.iter().flat_map(|c| &c.values) {
            write_vec2(w, "vt", t)?;
        }
        for face in mesh.faces() {
            w.write_all(b"f")?;
            for &v in face {
                write_corner(w, v, uvs.is_some(), normals.is_some())?;
            }
            w.write_all(b"\n")?;
        }
        Ok(())
    };
    body(&mut w).map_err(MeshIoError::write)?;
    w.flush().map_err(MeshIoError::write)
}

/// Writes the `v`, `vn`, `vt` and `f` lines.
fn write_body<W: Write>(mesh: &TriMesh, w: &mut W) -> std::io::Result<()> {
    for (i, p) in mesh.positions.iter().enumerate() {
        match mesh.colors.get(i) {
            Some(c) => writeln!(w, "v {:?} {:?} {:?} {:?} {:?} {:?}", p.x, p.y, p.z, c.x, c.y, c.z)?,
            None => write_vec3(w, "v", *p)?,
        }
    }
    for n in &mesh.normals {
        write_vec3(w, "vn", *n)?;
    }
    for t in &mesh.uvs {
        write_vec2(w, "vt", *t)?;
    }
    let (has_uv, has_normal) = (!mesh.uvs.is_empty(), !mesh.normals.is_empty());
    for tri in &mesh.triangles {
        w.write_all(b"f")?;
        for &v in tri {
            write_corner(w, v, has_uv, has_normal)?;
        }
        w.write_all(b"\n")?;
    }
    Ok(())
}

/// `channel` if it has one value per vertex of `mesh`, indexed by the face corners' vertices.
fn per_vertex<'m, T>(mesh: &PolyMesh, channel: Option<&'m FaceVarying<T>>) -> Option<&'m FaceVarying<T>> {
    channel.filter(|c| c.indices == mesh.face_vertices && c.values.len() == mesh.positions.len())
}

/// Writes face corner `v` (0-based) as ` i`, ` i/i`, ` i//i` or ` i/i/i` (1-based), the vertex
/// also indexing its UV and normal.
fn write_corner<W: Write + ?Sized>(w: &mut W, v: u32, has_uv: bool, has_normal: bool) -> std::io::Result<()> {
    let i = u64::from(v) + 1;
    match (has_uv, has_normal) {
        (true, true) => write!(w, " {i}/{i}/{i}"),
        (true, false) => write!(w, " {i}/{i}"),
        (false, true) => write!(w, " {i}//{i}"),
        (false, false) => write!(w, " {i}"),
    }
}

/// Writes `KEY x y z`.
fn write_vec3<W: Write>(w: &mut W, key: &str, p: DVec3) -> std::io::Result<()> {
    writeln!(w, "{key} {:?} {:?} {:?}", p.x, p.y, p.z)
}

/// Writes `KEY u v`.
fn write_vec2<W: Write>(w: &mut W, key: &str, p: DVec2) -> std::io::Result<()> {
    writeln!(w, "{key} {:?} {:?}", p.x, p.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(mesh: &TriMesh) -> String {
        let mut out = Vec::new();
        write_obj(mesh, &mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    fn triangle() -> TriMesh {
        TriMesh {
            positions: vec![DVec3::ZERO, DVec3::new(1e-20, 2.5, -3.0), DVec3::new(0.1, 1e20, 7.0)],
            triangles: vec![[0, 1, 2]],
            ..TriMesh::default()
        }
    }

    #[test]
    fn face_forms_follow_the_attributes() {
        let mut mesh = triangle();
        assert!(text(&mesh).ends_with("\nf 1 2 3\n"));
        mesh.normals = vec![DVec3::Z; 3];
        assert!(text(&mesh).ends_with("\nvn 0.0 0.0 1.0\nf 1//1 2//2 3//3\n"));
        mesh.uvs = vec![DVec2::new(0.25, 1.0); 3];
        assert!(text(&mesh).ends_with("\nvt 0.25 1.0\nf 1/1/1 2/2/2 3/3/3\n"));
        mesh.normals.clear();
        assert!(text(&mesh).ends_with("\nf 1/1 2/2 3/3\n"));
    }

    #[test]
    fn numbers_are_shortest_round_trip() {
        let t = text(&triangle());
        assert!(t.starts_with("v 0.0 0.0 0.0\nv 1e-20 2.5 -3.0\nv 0.1 1e20 7.0\n"), "{t}");
        for line in t.lines().filter(|l| l.starts_with("v ")) {
            for (k, word) in line.split(' ').skip(1).enumerate() {
                let x: f64 = word.parse().unwrap();
                let i = t.lines().position(|l| l == line).unwrap();
                assert_eq!(x, triangle().positions[i].to_array()[k]);
            }
        }
    }

    #[test]
    fn invalid_mesh_writes_nothing() {
        let mut mesh = triangle();
        mesh.triangles.push([0, 1, 3]);
        let mut out = Vec::new();
        let e = write_obj(&mesh, &mut out).unwrap_err();
        assert!(out.is_empty());
        assert_eq!(e.to_string(), "invalid mesh: triangle 1 refers to vertex 3, but the mesh has 3 vertices");
    }
}
