//! The Wavefront OBJ writer.

use std::io::{BufWriter, Write};

use glam::{DVec2, DVec3};
use splinekit::mesh::FaceVarying;
use splinekit::{PolyMesh, TriMesh};

use super::{MeshIoError, MeshIoErrorKind};

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
/// colour per vertex), then a `vn` line per normal value and a `vt` line per UV value, and one
/// `f` line per face with its corners (1-based, `v/t/n` forms as needed), numbers as
/// [`write_obj`].
///
/// Normals and UVs are face-varying ([`FaceVarying`]): each corner names its own value, so a
/// vertex on a UV seam or at a sharp edge of flat shading stays one `v` with several `vt` or
/// `vn` values, and the file keeps the mesh's topology (a closed mesh stays closed, and
/// reading the file back gives the same vertices, faces and attribute indices). A channel
/// given per vertex (its indices are the corners' vertices) writes the same bytes as
/// [`write_obj`] would.
///
/// # Errors
///
/// [`InvalidMesh`](super::MeshIoErrorKind::InvalidMesh) if the fan triangulation fails
/// [`TriMesh::validate`], or an attribute's indices do not match the corners or its values
/// (nothing is written then); [`Unrepresentable`](super::MeshIoErrorKind::Unrepresentable)
/// for a face without corners; or an [`Io`](super::MeshIoErrorKind::Io) error from `out`.
pub fn write_obj_poly<W: Write + ?Sized>(mesh: &PolyMesh, out: &mut W) -> Result<(), MeshIoError> {
    // the checks of a triangle mesh, on the fan triangulation (same vertices and indices)
    super::check(&mesh.to_tri_mesh())?;
    // a bare `f` line is no face to a reader (a PLY face list may be empty)
    if let Some(face) = mesh.faces().position(<[u32]>::is_empty) {
        let what = format!("face {face}, with no corners,");
        return Err(MeshIoError::new(MeshIoErrorKind::Unrepresentable { format: "OBJ", what }));
    }
    let normals = channel(mesh, mesh.normals.as_ref(), "normals")?;
    let uvs = channel(mesh, mesh.uvs.as_ref(), "UVs")?;
    let n = mesh.positions.len();
    let mut w = BufWriter::with_capacity(super::BUFFER_SIZE, out);
    let colors = mesh.colors.len() == n;
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
        for range in mesh.face_offsets.windows(2) {
            w.write_all(b"f")?;
            for c in range[0] as usize..range[1] as usize {
                let (t, n) = (uvs.map(|a| a.indices[c]), normals.map(|a| a.indices[c]));
                write_face_corner(w, mesh.face_vertices[c], t, n)?;
            }
            w.write_all(b"\n")?;
        }
        Ok(())
    };
    body(&mut w).map_err(MeshIoError::write)?;
    w.flush().map_err(MeshIoError::write)
}

/// `attribute` checked against the corners of `mesh`: one index per corner, each naming one
/// of its values, and every value finite.
pub(super) fn channel<'m, T: FiniteValue>(
    mesh: &PolyMesh,
    attribute: Option<&'m FaceVarying<T>>,
    what: &'static str,
) -> Result<Option<&'m FaceVarying<T>>, MeshIoError> {
    let Some(a) = attribute else { return Ok(None) };
    let corners = mesh.face_vertices.len();
    let problem = if a.indices.len() == corners {
        let out_of_range = a.indices.iter().position(|&i| i as usize >= a.values.len());
        let not_finite = || a.values.iter().position(|v| !v.finite());
        match (out_of_range, not_finite()) {
            (Some(c), _) => Some(format!("corner {c} names value {} of {}", a.indices[c], a.values.len())),
            (None, Some(v)) => Some(format!("value {v} is not finite")),
            (None, None) => None,
        }
    } else {
        Some(format!("{} indices for {corners} face corners", a.indices.len()))
    };
    match problem {
        Some(problem) => Err(MeshIoError::new(MeshIoErrorKind::InvalidAttribute { attribute: what, problem })),
        None => Ok(Some(a)),
    }
}

/// A normal or UV value, finite or not.
pub(super) trait FiniteValue {
    fn finite(&self) -> bool;
}

impl FiniteValue for DVec3 {
    fn finite(&self) -> bool {
        self.is_finite()
    }
}

impl FiniteValue for DVec2 {
    fn finite(&self) -> bool {
        self.is_finite()
    }
}

/// Writes a face corner as ` v`, ` v/t`, ` v//n` or ` v/t/n` (1-based) from 0-based indices.
fn write_face_corner<W: Write + ?Sized>(w: &mut W, v: u32, t: Option<u32>, n: Option<u32>) -> std::io::Result<()> {
    let one = |i: u32| u64::from(i) + 1;
    match (t, n) {
        (Some(t), Some(n)) => write!(w, " {}/{}/{}", one(v), one(t), one(n)),
        (Some(t), None) => write!(w, " {}/{}", one(v), one(t)),
        (None, Some(n)) => write!(w, " {}//{}", one(v), one(n)),
        (None, None) => write!(w, " {}", one(v)),
    }
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

/// Writes face corner `v` (0-based) as ` i`, ` i/i`, ` i//i` or ` i/i/i` (1-based), the vertex
/// also indexing its UV and normal.
fn write_corner<W: Write + ?Sized>(w: &mut W, v: u32, has_uv: bool, has_normal: bool) -> std::io::Result<()> {
    write_face_corner(w, v, has_uv.then_some(v), has_normal.then_some(v))
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
