//! The binary glTF 2.0 (`.glb`) reader: the triangles of every mesh of the default scene,
//! with the node transforms applied, as one mesh.
//!
//! The JSON document is parsed by `gltf-json` (the `gltf` crate's document model); the binary
//! container ([`container`]), the accessors ([`accessor`]) and the scene walk ([`scene`]) are
//! this module's own rather than the `gltf` crate's reader, for a measured reason. On 20 000
//! generated and mutated `.glb` files of the fuzz harness (`cargo run --release -p
//! splinekit-fuzz --example gltf_probe`), `gltf` 1.4's reader panicked on 8 (an index out of
//! bounds), read 1 947 files that are invalid without a word (indices beyond the vertex
//! count, which it hands on, and triangles that all repeat a vertex), and its errors do not
//! say where the problem is ("could not completely read the object", "unknown chunk type")
//! where this reader names the JSON path (`meshes[0].primitives[1].indices (accessors[4])`)
//! or the byte. It also refuses 2 443 files this reader reads, mostly for a `POSITION`
//! accessor without `min` and `max`, which exporters leave out and which nothing here needs.

mod accessor;
mod container;
mod scene;
#[cfg(test)]
mod tests;

use std::io::Read;

use std::collections::{HashMap, HashSet};

use super::load::{self, LoadedMesh, Warnings};
use super::{MeshIoError, MeshIoErrorKind};
use accessor::Doc;
use container::{Chunks, chunks, parse_json, resolve_buffer};
use scene::{Builder, Reader};

/// Required extensions that move the geometry out of the plain accessors.
const COMPRESSION_EXTENSIONS: [&str; 3] =
    ["KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"];

/// Reads a binary glTF 2.0 (`.glb`) file from `reader`; `origin` names it in errors.
///
/// # What is read
///
/// - The 12-byte header (`glTF`, version 2, the total length; bytes after that length are
///   ignored with a [`TrailingBytes`](crate::mesh::ReadWarningKind::TrailingBytes) warning), the JSON chunk
///   and an optional `BIN` chunk; chunks of other types are skipped.
/// - The nodes of the default scene (`scene`, else the first of `scenes`), depth first with
///   their children, each node's transform (`matrix`, or `translation`, `rotation`, `scale`)
///   composed with its parents'. A file without scenes gives every mesh once, untransformed.
/// - Every primitive of every node's mesh, all combined into one triangle mesh: modes
///   `TRIANGLES` (the default), `TRIANGLE_STRIP` and `TRIANGLE_FAN` (strips and fans become
///   triangles; their degenerate triangles, which stitch strips, are left out). Points and
///   lines are skipped with a [`SkippedPrimitive`](crate::mesh::ReadWarningKind::SkippedPrimitive) warning,
///   as is a primitive without `POSITION`.
/// - Attributes: `POSITION` (`f32` VEC3, transformed as points); `NORMAL` (`f32` or
///   normalized `i8`/`i16` VEC3, transformed by the inverse transpose and renormalised);
///   `TEXCOORD_0` (`f32` or normalized integer VEC2), read back as `(u, 1 − v)`, the OBJ and
///   PLY convention ([`write_glb`](super::write_glb) writes `(u, 1 − v)`); `COLOR_0` (`f32`
///   or normalized `u8`/`u16`, VEC3 or VEC4, alpha dropped) as vertex colours. Normals and
///   texture coordinates become face-varying attributes with per-vertex indices. An
///   attribute that some primitives have and others lack is dropped with a
///   [`PrimitiveAttributeDropped`](crate::mesh::ReadWarningKind::PrimitiveAttributeDropped) warning.
/// - Indices: `u8`, `u16` or `u32` SCALAR; a primitive without indices uses its vertices in
///   order. Accessors may have a `byteOffset` and their buffer views a `byteStride`.
/// - Buffers: the `BIN` chunk, and base64 `data:` URIs.
///
/// Vertices are kept as the file has them: each node gets its own copy of its mesh's
/// vertices (primitives of one node that share their attribute accessors share vertices),
/// and a vertex split in the file (at a UV seam, say) stays split. A transform with a
/// negative determinant (a mirror) has its triangles reversed, so that they stay
/// counter-clockwise from the front, as glTF specifies. Materials, textures, cameras, skins,
/// morph targets and animations are ignored.
///
/// # Errors
///
/// A [`MeshIoError`] naming `origin` and, for problems in the glTF document, where: a JSON
/// path like `meshes[0].primitives[1].indices (accessors[4])`. A wrong magic number or
/// version, a truncated file or chunk, invalid JSON (with its line and column in the JSON
/// chunk), an index out of range, an accessor beyond its buffer view or a view beyond its
/// buffer, positions that are not `f32` VEC3, a primitive whose vertex count does not make
/// whole triangles, primitives of triangles of which not one triangle is read (all without
/// `POSITION`, or degenerate: [`NoFacesRead`](MeshIoErrorKind::NoFacesRead); a file of
/// points or lines only is read, with its warnings). Refused with a clear error: sparse
/// accessors, accessors without a buffer view, external buffer files (`"uri": "x.bin"`;
/// only `.glb` with embedded buffers is read) and compressed geometry (Draco, meshopt).
/// Nothing is returned on error.
///
/// ```
/// use glam::{DVec2, DVec3};
/// use splinekit::TriMesh;
/// use splinekit_io::mesh::{read_glb, write_glb};
///
/// let mesh = TriMesh {
///     positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
///     uvs: vec![DVec2::ZERO, DVec2::X, DVec2::new(0.0, 0.25)],
///     triangles: vec![[0, 1, 2]],
///     ..TriMesh::default()
/// };
/// let mut bytes = Vec::new();
/// write_glb(&mesh, &mut bytes)?;
/// let read = read_glb(bytes.as_slice(), "tri.glb")?.mesh;
/// assert_eq!(read.positions, mesh.positions);
/// assert_eq!(read.face(0), &[0, 1, 2]);
/// assert_eq!(read.uvs.unwrap().values[2], DVec2::new(0.0, 0.25));
///
/// let err = read_glb(&bytes[..30], "tri.glb").unwrap_err();
/// assert!(err.to_string().starts_with("tri.glb: found end of file, expected "), "{err}");
/// # Ok::<(), splinekit_io::MeshIoError>(())
/// ```
pub fn read_glb<R: Read>(reader: R, origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let bytes = load::read_all(reader, origin)?;
    parse_glb(&bytes, origin)
}

/// Parses `.glb` bytes (see [`read_glb`]).
pub(crate) fn parse_glb(bytes: &[u8], origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let mut warnings = Warnings::default();
    let Chunks { json_at, json, bin } = chunks(bytes, origin, &mut warnings)?;
    let root = parse_json(json, json_at, origin)?;
    for (k, name) in root.extensions_required.iter().enumerate() {
        if COMPRESSION_EXTENSIONS.contains(&name.as_str()) {
            return Err(invalid(
                origin,
                format!("extensionsRequired[{k}]"),
                format!("found {name:?}, expected uncompressed geometry (compressed meshes are not supported)"),
            ));
        }
    }
    let buffers = root.buffers.iter().enumerate().map(|(i, b)| resolve_buffer(i, b, bin)).collect();
    let mut reader = Reader {
        doc: Doc { origin, root: &root, buffers },
        builder: Builder::default(),
        blocks: HashMap::new(),
        skipped: HashSet::new(),
        warnings,
        triangle_primitives: 0,
        without_position: 0,
    };
    reader.read_scene()?;
    reader.finish()
}

/// An error in the glTF document or the binary layout: `at` says where, `message` what.
fn invalid(origin: &str, at: impl Into<String>, message: impl Into<String>) -> MeshIoError {
    MeshIoError::in_structure(origin, at.into(), MeshIoErrorKind::InvalidGltf { message: message.into() })
}

/// "expected an index below N (the number of WHAT)", or "expected none (there are no WHAT)".
fn below(n: usize, what: &str) -> String {
    if n == 0 {
        format!("expected none (there are no {what})")
    } else {
        format!("expected an index below {n} (the number of {what})")
    }
}
