//! The binary glTF 2.0 (`.glb`) reader: the triangles of every mesh of the default scene,
//! with the node transforms applied, as one mesh.

use std::borrow::Cow;
use std::collections::{HashMap, HashSet};
use std::io::Read;

use glam::{DMat3, DMat4, DQuat, DVec2, DVec3, DVec4};
use gltf_json as json;
use json::accessor::{ComponentType, Type};
use json::mesh::{Mode, Semantic};
use json::validation::Checked::{Invalid, Valid};
use splinekit::mesh::{FaceVarying, PolyMesh};
use splinekit::subdiv::Creases;

use super::load::{self, LoadedMesh, MAX_WARNINGS, ReadWarningKind, Warnings};
use super::{MeshIoError, MeshIoErrorKind, SubdivTags};

/// `glTF`, the magic number at the start of a `.glb`.
const MAGIC: &[u8; 4] = b"glTF";
/// The chunk type of the JSON chunk.
const CHUNK_JSON: &[u8; 4] = b"JSON";
/// The chunk type of the binary buffer chunk.
const CHUNK_BIN: &[u8; 4] = b"BIN\0";
/// Size of the file header (magic, version, length).
const HEADER: usize = 12;
/// Size of a chunk header (length, type).
const CHUNK_HEADER: usize = 8;
/// Required extensions that move the geometry out of the plain accessors.
const COMPRESSION_EXTENSIONS: [&str; 3] =
    ["KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"];

/// Reads a binary glTF 2.0 (`.glb`) file from `reader`; `origin` names it in errors.
///
/// # What is read
///
/// - The 12-byte header (`glTF`, version 2, the total length; bytes after that length are
///   ignored with a [`TrailingBytes`](ReadWarningKind::TrailingBytes) warning), the JSON chunk
///   and an optional `BIN` chunk; chunks of other types are skipped.
/// - The nodes of the default scene (`scene`, else the first of `scenes`), depth first with
///   their children, each node's transform (`matrix`, or `translation`, `rotation`, `scale`)
///   composed with its parents'. A file without scenes gives every mesh once, untransformed.
/// - Every primitive of every node's mesh, all combined into one triangle mesh: modes
///   `TRIANGLES` (the default), `TRIANGLE_STRIP` and `TRIANGLE_FAN` (strips and fans become
///   triangles; their degenerate triangles, which stitch strips, are left out). Points and
///   lines are skipped with a [`SkippedPrimitive`](ReadWarningKind::SkippedPrimitive) warning,
///   as is a primitive without `POSITION`.
/// - Attributes: `POSITION` (`f32` VEC3, transformed as points); `NORMAL` (`f32` or
///   normalized `i8`/`i16` VEC3, transformed by the inverse transpose and renormalised);
///   `TEXCOORD_0` (`f32` or normalized integer VEC2), read back as `(u, 1 − v)`, the OBJ and
///   PLY convention ([`write_glb`](super::write_glb) writes `(u, 1 − v)`); `COLOR_0` (`f32`
///   or normalized `u8`/`u16`, VEC3 or VEC4, alpha dropped) as vertex colours. Normals and
///   texture coordinates become face-varying attributes with per-vertex indices. An
///   attribute that some primitives have and others lack is dropped with a
///   [`PrimitiveAttributeDropped`](ReadWarningKind::PrimitiveAttributeDropped) warning.
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
    load::error_in(origin, MeshIoErrorKind::InvalidGltf { at: at.into(), message: message.into() })
}

/// The little-endian `u32` at `at` (which is in bounds).
fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

/// The chunks of a `.glb`.
struct Chunks<'a> {
    /// Where the JSON chunk's data starts in the file.
    json_at: usize,
    json: &'a [u8],
    bin: Option<&'a [u8]>,
}

/// Checks the header and splits the chunks.
fn chunks<'a>(bytes: &'a [u8], origin: &str, warnings: &mut Warnings) -> Result<Chunks<'a>, MeshIoError> {
    let size = bytes.len();
    if size < HEADER {
        if bytes.first() == Some(&b'{') {
            return Err(not_binary(origin));
        }
        return Err(load::truncated(origin, format!("a 12-byte binary glTF header (the file has {size} bytes)")));
    }
    if &bytes[..4] != MAGIC {
        let text = bytes.trim_ascii_start();
        if text.first() == Some(&b'{') {
            return Err(not_binary(origin));
        }
        return Err(invalid(
            origin,
            "byte 0",
            format!("found \"{}\", expected glTF (the magic number of binary glTF)", bytes[..4].escape_ascii()),
        ));
    }
    let version = u32_at(bytes, 4);
    if version != 2 {
        return Err(invalid(origin, "byte 4", format!("found version {version}, expected version 2 (glTF 2.0)")));
    }
    let length = u32_at(bytes, 8) as usize;
    if length < HEADER + CHUNK_HEADER {
        return Err(invalid(
            origin,
            "byte 8",
            format!("found a total length of {length} bytes, expected at least 20 (the header and a JSON chunk)"),
        ));
    }
    if length > size {
        return Err(load::truncated(
            origin,
            format!("{length} bytes (the length in the binary glTF header), found {size}"),
        ));
    }
    if length < size {
        warnings.push(0, ReadWarningKind::TrailingBytes { count: size - length });
    }
    let bytes = &bytes[..length];
    let mut at = HEADER;
    let mut json = None;
    let mut bin = None;
    let mut index = 0;
    while at < length {
        if length - at < CHUNK_HEADER {
            return Err(load::truncated(
                origin,
                format!("the 8-byte header of chunk {index} at byte {at} (the file has {length} bytes)"),
            ));
        }
        let chunk_length = u32_at(bytes, at) as usize;
        let kind = &bytes[at + 4..at + 8];
        let start = at + CHUNK_HEADER;
        if chunk_length > length - start {
            return Err(load::truncated(
                origin,
                format!(
                    "the {chunk_length} bytes of chunk {index} (\"{}\") at byte {start}, found {}",
                    kind.escape_ascii(),
                    length - start
                ),
            ));
        }
        let data = &bytes[start..start + chunk_length];
        if index == 0 {
            if kind != CHUNK_JSON {
                return Err(invalid(
                    origin,
                    format!("chunk 0 at byte {at}"),
                    format!("found chunk type \"{}\", expected JSON (the first chunk)", kind.escape_ascii()),
                ));
            }
            json = Some((start, data));
        } else if kind == CHUNK_BIN && bin.is_none() {
            if index != 1 {
                return Err(invalid(
                    origin,
                    format!("chunk {index} at byte {at}"),
                    "found a BIN chunk, expected it to be the second chunk",
                ));
            }
            bin = Some(data);
        }
        // Other chunk types are skipped, as the specification asks.
        at = start + chunk_length;
        index += 1;
    }
    // `length >= 20`, so the loop saw chunk 0.
    let (json_at, json) = json.unwrap_or((HEADER, &[]));
    Ok(Chunks { json_at, json, bin })
}

/// The error for a text `.gltf` file read as binary.
fn not_binary(origin: &str) -> MeshIoError {
    invalid(
        origin,
        "byte 0",
        "found JSON text, expected binary glTF starting with glTF (text .gltf files are not supported)",
    )
}

/// Parses the JSON chunk, which starts at byte `json_at` of the file.
fn parse_json(bytes: &[u8], json_at: usize, origin: &str) -> Result<json::Root, MeshIoError> {
    // Padding is spaces; some writers pad with NULs.
    let end = bytes.iter().rposition(|&b| b != 0 && !b.is_ascii_whitespace()).map_or(0, |e| e + 1);
    let bytes = &bytes[..end];
    json::Root::from_slice(bytes).map_err(|e| {
        let message = e.to_string();
        let suffix = format!(" at line {} column {}", e.line(), e.column());
        let message = message.strip_suffix(&suffix).unwrap_or(&message);
        let at = if e.line() == 0 {
            String::from("JSON chunk")
        } else {
            let byte = json_at + byte_offset(bytes, e.line(), e.column());
            format!("JSON chunk line {}, column {} (byte {byte})", e.line(), e.column())
        };
        invalid(origin, at, format!("invalid glTF JSON: {message}"))
    })
}

/// The byte offset of 1-based `line` and `column` (serde_json's: the column counts bytes,
/// and is 0 before the first byte of a line).
fn byte_offset(text: &[u8], line: usize, column: usize) -> usize {
    let line_start = if line <= 1 {
        0
    } else {
        text.iter().enumerate().filter(|&(_, &b)| b == b'\n').nth(line - 2).map_or(text.len(), |(i, _)| i + 1)
    };
    (line_start + column.saturating_sub(1)).min(text.len())
}

/// A resolved buffer, or where and why it cannot be read (reported if an accessor uses it).
type Buffer<'a> = Result<Cow<'a, [u8]>, (String, String)>;

/// The bytes of buffer `i`: the `BIN` chunk for the first buffer without `uri`, or a base64
/// `data:` URI.
fn resolve_buffer<'a>(i: usize, buffer: &json::Buffer, bin: Option<&'a [u8]>) -> Buffer<'a> {
    let length = buffer.byte_length.0;
    let data: Cow<'a, [u8]> = match (&buffer.uri, bin) {
        (None, Some(bin)) if i == 0 => Cow::Borrowed(bin),
        (None, None) if i == 0 => {
            return Err((
                String::from("buffers[0]"),
                String::from("found a buffer without uri and no BIN chunk, expected a BIN chunk holding it"),
            ));
        }
        (None, _) => {
            return Err((
                format!("buffers[{i}]"),
                String::from("found a buffer without uri, expected a uri (only the first buffer is the BIN chunk)"),
            ));
        }
        (Some(uri), _) => match uri.strip_prefix("data:") {
            Some(rest) => {
                let Some((media, text)) = rest.split_once(',') else {
                    return Err((format!("buffers[{i}].uri"), String::from("found a data URI without a comma")));
                };
                if !media.ends_with(";base64") {
                    return Err((
                        format!("buffers[{i}].uri"),
                        format!("found a data URI \"data:{media},…\", expected a base64 one (data:…;base64,…)"),
                    ));
                }
                match decode_base64(text.as_bytes()) {
                    Some(bytes) => Cow::Owned(bytes),
                    None => {
                        return Err((
                            format!("buffers[{i}].uri"),
                            String::from("found invalid base64 in the data URI, expected base64 text"),
                        ));
                    }
                }
            }
            None => {
                let shown: String = uri.chars().take(60).collect();
                return Err((
                    format!("buffers[{i}].uri"),
                    format!(
                        "external buffer {shown:?} is not supported: only .glb with embedded buffers (the BIN chunk or base64 data: URIs)"
                    ),
                ));
            }
        },
    };
    if length > data.len() as u64 {
        let source = if buffer.uri.is_none() { "the BIN chunk" } else { "the data URI" };
        return Err((
            format!("buffers[{i}].byteLength"),
            format!("found {length} bytes, expected at most {} (the size of {source})", data.len()),
        ));
    }
    // `length <= data.len()`, so it fits in usize.
    Ok(match data {
        Cow::Borrowed(b) => Cow::Borrowed(&b[..length as usize]),
        Cow::Owned(mut b) => {
            b.truncate(length as usize);
            Cow::Owned(b)
        }
    })
}

/// Decodes standard or URL-safe base64 (padding optional, whitespace ignored).
fn decode_base64(text: &[u8]) -> Option<Vec<u8>> {
    let text = text.trim_ascii_end();
    let text = text.strip_suffix(b"==").or_else(|| text.strip_suffix(b"=")).unwrap_or(text);
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 2);
    let (mut acc, mut bits, mut digits) = (0u32, 0u32, 0usize);
    for &c in text {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            c if c.is_ascii_whitespace() => continue,
            _ => return None,
        };
        digits += 1;
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    (digits % 4 != 1).then_some(out)
}

/// The elements of an accessor, checked to lie within their buffer.
struct Elements<'a> {
    /// From the first byte of the first element to the end of the buffer view.
    data: &'a [u8],
    stride: usize,
    count: usize,
    component: ComponentType,
    normalized: bool,
}

impl Elements<'_> {
    /// Component `k` of element `i` as a number (normalized integers mapped to `[0, 1]` or
    /// `[-1, 1]`).
    fn get(&self, i: usize, k: usize) -> f64 {
        let size = self.component.size();
        let at = i * self.stride + k * size;
        let Some(b) = self.data.get(at..at + size) else { return 0.0 };
        let n = self.normalized;
        match self.component {
            ComponentType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            ComponentType::U8 => f64::from(b[0]) / if n { 255.0 } else { 1.0 },
            ComponentType::I8 => {
                let v = f64::from(b[0] as i8);
                if n { (v / 127.0).max(-1.0) } else { v }
            }
            ComponentType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])) / if n { 65535.0 } else { 1.0 },
            ComponentType::I16 => {
                let v = f64::from(i16::from_le_bytes([b[0], b[1]]));
                if n { (v / 32767.0).max(-1.0) } else { v }
            }
            ComponentType::U32 => {
                f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])) / if n { f64::from(u32::MAX) } else { 1.0 }
            }
        }
    }

    /// Element `i` of an unsigned integer accessor.
    fn index(&self, i: usize) -> u32 {
        let size = self.component.size();
        let at = i * self.stride;
        let Some(b) = self.data.get(at..at + size) else { return u32::MAX };
        match self.component {
            ComponentType::U8 | ComponentType::I8 => u32::from(b[0]),
            ComponentType::U16 | ComponentType::I16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
            ComponentType::U32 | ComponentType::F32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        }
    }

    fn vec3(&self, i: usize) -> DVec3 {
        DVec3::new(self.get(i, 0), self.get(i, 1), self.get(i, 2))
    }
}

/// The name of a component type, like `f32`.
fn component_name(c: ComponentType) -> &'static str {
    match c {
        ComponentType::I8 => "i8",
        ComponentType::U8 => "u8",
        ComponentType::I16 => "i16",
        ComponentType::U16 => "u16",
        ComponentType::U32 => "u32",
        ComponentType::F32 => "f32",
    }
}

/// The name of an accessor type, like `VEC3`, and its number of components.
fn type_info(t: Type) -> (&'static str, usize) {
    match t {
        Type::Scalar => ("SCALAR", 1),
        Type::Vec2 => ("VEC2", 2),
        Type::Vec3 => ("VEC3", 3),
        Type::Vec4 => ("VEC4", 4),
        Type::Mat2 => ("MAT2", 4),
        Type::Mat3 => ("MAT3", 9),
        Type::Mat4 => ("MAT4", 16),
    }
}

/// What an attribute accepts: a description for errors and the test.
struct Accepts {
    expected: &'static str,
    ok: fn(ComponentType, Type, bool) -> bool,
}

const POSITIONS: Accepts = Accepts {
    expected: "f32 VEC3 (quantized positions are not supported)",
    ok: |c, t, _| c == ComponentType::F32 && t == Type::Vec3,
};
const NORMALS: Accepts = Accepts {
    expected: "f32, or normalized i8 or i16, VEC3",
    ok: |c, t, n| {
        t == Type::Vec3 && (c == ComponentType::F32 || n && matches!(c, ComponentType::I8 | ComponentType::I16))
    },
};
const TEXCOORDS: Accepts = Accepts {
    expected: "f32, or normalized u8, u16, i8 or i16, VEC2",
    ok: |c, t, n| t == Type::Vec2 && (c == ComponentType::F32 || n && c != ComponentType::U32),
};
const COLORS: Accepts = Accepts {
    expected: "f32, or normalized u8 or u16, VEC3 or VEC4",
    ok: |c, t, n| {
        matches!(t, Type::Vec3 | Type::Vec4)
            && (c == ComponentType::F32 || n && matches!(c, ComponentType::U8 | ComponentType::U16))
    },
};
const INDICES: Accepts = Accepts {
    expected: "u8, u16 or u32 SCALAR",
    ok: |c, t, n| t == Type::Scalar && !n && matches!(c, ComponentType::U8 | ComponentType::U16 | ComponentType::U32),
};

/// The optional attributes, in the order of [`Builder::attributes`].
const ATTRIBUTES: [&str; 3] = ["normals", "texture coordinates", "vertex colours"];

/// The combined mesh being built.
#[derive(Default)]
struct Builder {
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    uvs: Vec<DVec2>,
    colors: Vec<DVec3>,
    face_vertices: Vec<u32>,
    /// Per optional attribute: primitives with it, without it, and the first without it.
    attributes: [(usize, usize, Option<String>); 3],
}

/// A parsed document with its buffers.
struct Doc<'a> {
    origin: &'a str,
    root: &'a json::Root,
    buffers: Vec<Buffer<'a>>,
}

/// Reads the meshes of a parsed document.
struct Reader<'a> {
    doc: Doc<'a>,
    builder: Builder,
    /// Where the vertices of (instance, POSITION, NORMAL, TEXCOORD_0, COLOR_0) start.
    blocks: HashMap<(usize, [Option<usize>; 4]), u32>,
    /// Primitives skipped, as (mesh, primitive); the first [`MAX_WARNINGS`] have a warning.
    skipped: HashSet<(usize, usize)>,
    warnings: Warnings,
    /// Primitives of triangles (modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) met, once per
    /// node, and how many of them were skipped for having no POSITION.
    triangle_primitives: usize,
    without_position: usize,
}

/// The transforms of one node instance.
struct Placement {
    /// The node's world matrix.
    matrix: DMat4,
    /// Whether it is the identity (positions and normals are kept as read).
    identity: bool,
    /// The inverse transpose of the upper 3×3 block, up to a positive factor.
    normal_matrix: DMat3,
    /// Whether the determinant is negative (triangles are reversed).
    mirror: bool,
}

impl Placement {
    fn new(matrix: DMat4) -> Self {
        let m = DMat3::from_mat4(matrix);
        let det = m.determinant();
        // The cofactor matrix is det · M⁻ᵀ; it exists even when M is singular.
        let cofactor = DMat3::from_cols(m.y_axis.cross(m.z_axis), m.z_axis.cross(m.x_axis), m.x_axis.cross(m.y_axis));
        let normal_matrix = if det < 0.0 { -cofactor } else { cofactor };
        Self { matrix, identity: matrix == DMat4::IDENTITY, normal_matrix, mirror: det < 0.0 }
    }
}

impl Doc<'_> {
    fn error(&self, at: impl Into<String>, message: impl Into<String>) -> MeshIoError {
        invalid(self.origin, at, message)
    }

    /// Accessor `index`, referenced at `at`, checked against `accepts` and its buffer view.
    fn accessor(&self, index: usize, at: &str, accepts: &Accepts) -> Result<Elements<'_>, MeshIoError> {
        let root = self.root;
        let Some(accessor) = root.accessors.get(index) else {
            return Err(self.error(at, format!("found accessor {index}, {}", below(root.accessors.len(), "accessors"))));
        };
        let here = format!("{at} (accessors[{index}])");
        if accessor.sparse.is_some() {
            return Err(
                self.error(here, "found a sparse accessor, expected a plain one (sparse accessors are not supported)")
            );
        }
        let Valid(json::accessor::GenericComponentType(component)) = accessor.component_type else {
            return Err(
                self.error(here, "found an invalid componentType, expected 5120, 5121, 5122, 5123, 5125 or 5126")
            );
        };
        let Valid(type_) = accessor.type_ else {
            return Err(self.error(here, "found an invalid type, expected SCALAR, VEC2, VEC3, VEC4 or a matrix"));
        };
        let normalized = accessor.normalized;
        let (type_name, components) = type_info(type_);
        if !(accepts.ok)(component, type_, normalized) {
            let norm = if normalized { "normalized " } else { "" };
            return Err(self.error(
                here,
                format!("found {norm}{} {type_name}, expected {}", component_name(component), accepts.expected),
            ));
        }
        let Some(v) = accessor.buffer_view.map(|v| v.value()) else {
            return Err(self.error(here, "found no bufferView, expected one (accessors of zeros are not supported)"));
        };
        let Some(view) = root.buffer_views.get(v) else {
            return Err(self.error(
                format!("{here}.bufferView"),
                format!("found buffer view {v}, {}", below(root.buffer_views.len(), "buffer views")),
            ));
        };
        let b = view.buffer.value();
        let buffer = match self.buffers.get(b) {
            Some(Ok(buffer)) => buffer,
            Some(Err((at, message))) => return Err(self.error(at.clone(), message.clone())),
            None => {
                return Err(self.error(
                    format!("bufferViews[{v}].buffer"),
                    format!("found buffer {b}, {}", below(root.buffers.len(), "buffers")),
                ));
            }
        };
        let view_start = view.byte_offset.map_or(0, |o| o.0);
        let view_length = view.byte_length.0;
        let view_end = view_start.saturating_add(view_length);
        if view_end > buffer.len() as u64 {
            return Err(self.error(
                format!("bufferViews[{v}]"),
                format!(
                    "found bytes {view_start}..{view_end} of buffers[{b}], which has {} bytes, expected a view within its buffer",
                    buffer.len()
                ),
            ));
        }
        let element = (component.size() * components) as u64;
        let stride = view.byte_stride.map_or(element, |s| s.0 as u64);
        if stride < element {
            return Err(self.error(
                format!("bufferViews[{v}].byteStride"),
                format!("found {stride}, expected at least {element} (the size of an element of accessors[{index}])"),
            ));
        }
        let offset = accessor.byte_offset.map_or(0, |o| o.0);
        let count = accessor.count.0;
        if count > 0 {
            let end = (count - 1)
                .checked_mul(stride)
                .and_then(|e| e.checked_add(offset))
                .and_then(|e| e.checked_add(element));
            if end.is_none_or(|end| end > view_length) {
                let end = end.map_or_else(|| String::from("beyond 2⁶⁴"), |e| e.to_string());
                return Err(self.error(
                    here,
                    format!(
                        "found {count} elements of {element} bytes every {stride} bytes from byte {offset} (up to byte {end}), expected them within bufferViews[{v}] of {view_length} bytes"
                    ),
                ));
            }
        }
        // In bounds: view_end <= buffer.len(), and offset <= view_length when count > 0.
        let start = (view_start + offset.min(view_length)) as usize;
        let data = &buffer[start..view_end as usize];
        Ok(Elements { data, stride: stride as usize, count: count as usize, component, normalized })
    }
}

impl Reader<'_> {
    fn error(&self, at: impl Into<String>, message: impl Into<String>) -> MeshIoError {
        self.doc.error(at, message)
    }

    /// Reads the default scene (or every mesh, if there is no scene).
    fn read_scene(&mut self) -> Result<(), MeshIoError> {
        let root = self.doc.root;
        let scene = match root.scene {
            Some(s) => Some((s.value(), "scene")),
            None if !root.scenes.is_empty() => Some((0, "scenes[0]")),
            None => None,
        };
        let Some((s, at)) = scene else {
            for m in 0..root.meshes.len() {
                self.add_mesh(m, root.nodes.len() + m, &Placement::new(DMat4::IDENTITY))?;
            }
            return Ok(());
        };
        let Some(scene) = root.scenes.get(s) else {
            return Err(self.error(at, format!("found scene {s}, {}", below(root.scenes.len(), "scenes"))));
        };
        let mut visited = vec![false; root.nodes.len()];
        for (k, &node) in scene.nodes.iter().enumerate() {
            let at = format!("scenes[{s}].nodes[{k}]");
            self.add_node(node.value(), &at, DMat4::IDENTITY, &mut visited)?;
        }
        Ok(())
    }

    /// Adds node `n` and its descendants, depth first, under the transform `parent`.
    fn add_node(&mut self, n: usize, at: &str, parent: DMat4, visited: &mut [bool]) -> Result<(), MeshIoError> {
        let root = self.doc.root;
        // (node, where it is referenced, the parent's world matrix)
        let mut stack = vec![(n, at.to_owned(), parent)];
        while let Some((n, at, parent)) = stack.pop() {
            let Some(node) = root.nodes.get(n) else {
                return Err(self.error(at, format!("found node {n}, {}", below(root.nodes.len(), "nodes"))));
            };
            if std::mem::replace(&mut visited[n], true) {
                return Err(self.error(
                    at,
                    format!("found node {n} a second time, expected every node at most once (nodes form trees)"),
                ));
            }
            let world = parent * local_matrix(node);
            if let Some(m) = node.mesh {
                let m = m.value();
                if m >= root.meshes.len() {
                    let message = format!("found mesh {m}, {}", below(root.meshes.len(), "meshes"));
                    return Err(self.error(format!("nodes[{n}].mesh"), message));
                }
                self.add_mesh(m, n, &Placement::new(world))?;
            }
            for (k, child) in node.children.as_deref().unwrap_or_default().iter().enumerate().rev() {
                stack.push((child.value(), format!("nodes[{n}].children[{k}]"), world));
            }
        }
        Ok(())
    }

    /// A warning that primitive `p` of mesh `m` is skipped (once per primitive).
    fn skip(&mut self, m: usize, p: usize, reason: String) {
        if self.skipped.insert((m, p)) && self.skipped.len() <= MAX_WARNINGS {
            let primitive = match &self.doc.root.meshes[m].name {
                Some(name) => format!("meshes[{m}].primitives[{p}] (mesh {name:?})"),
                None => format!("meshes[{m}].primitives[{p}]"),
            };
            self.warnings.push(0, ReadWarningKind::SkippedPrimitive { primitive, reason });
        }
    }

    /// Adds the primitives of mesh `m`, placed by `placement`; `instance` identifies the node.
    fn add_mesh(&mut self, m: usize, instance: usize, placement: &Placement) -> Result<(), MeshIoError> {
        let root = self.doc.root;
        let mesh = &root.meshes[m];
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let at = format!("meshes[{m}].primitives[{p}]");
            let mode = match primitive.mode {
                Valid(mode @ (Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan)) => mode,
                Valid(other) => {
                    let name = match other {
                        Mode::Points => "POINTS",
                        Mode::Lines => "LINES",
                        Mode::LineLoop => "LINE_LOOP",
                        _ => "LINE_STRIP",
                    };
                    self.skip(m, p, format!("its mode is {name}, not triangles"));
                    continue;
                }
                Invalid => {
                    self.skip(m, p, String::from("its mode is unknown"));
                    continue;
                }
            };
            self.triangle_primitives += 1;
            let attribute = |s: Semantic| primitive.attributes.get(&Valid(s)).map(|a| a.value());
            let Some(position) = attribute(Semantic::Positions) else {
                self.without_position += 1;
                self.skip(m, p, String::from("it has no POSITION attribute"));
                continue;
            };
            let optional =
                [attribute(Semantic::Normals), attribute(Semantic::TexCoords(0)), attribute(Semantic::Colors(0))];
            let key = (instance, [Some(position), optional[0], optional[1], optional[2]]);
            let (base, count) = match self.blocks.get(&key) {
                Some(&base) => (base, self.count_of(position)),
                None => {
                    let base = self.builder.positions.len() as u32;
                    let count = self.add_vertices(&at, position, optional, placement)?;
                    self.blocks.insert(key, base);
                    (base, count)
                }
            };
            for (k, a) in optional.iter().enumerate() {
                let stats = &mut self.builder.attributes[k];
                if a.is_some() {
                    stats.0 += 1;
                } else {
                    stats.1 += 1;
                    stats.2.get_or_insert_with(|| at.clone());
                }
            }
            self.add_triangles(&at, primitive.indices.map(|i| i.value()), mode, base, count, placement.mirror)?;
        }
        Ok(())
    }

    /// The count of an accessor already read.
    fn count_of(&self, accessor: usize) -> usize {
        self.doc.root.accessors.get(accessor).map_or(0, |a| a.count.0 as usize)
    }

    /// Appends the vertices of a primitive; returns their number.
    fn add_vertices(
        &mut self,
        at: &str,
        position: usize,
        optional: [Option<usize>; 3],
        placement: &Placement,
    ) -> Result<usize, MeshIoError> {
        let positions = self.doc.accessor(position, &format!("{at}.attributes.POSITION"), &POSITIONS)?;
        let n = positions.count;
        let names = ["NORMAL", "TEXCOORD_0", "COLOR_0"];
        let accepts = [&NORMALS, &TEXCOORDS, &COLORS];
        let mut read = [None, None, None];
        for k in 0..3 {
            if let Some(a) = optional[k] {
                let here = format!("{at}.attributes.{}", names[k]);
                let elements = self.doc.accessor(a, &here, accepts[k])?;
                if elements.count != n {
                    return Err(self.error(
                        format!("{here} (accessors[{a}])"),
                        format!("found {} elements, expected {n} (the count of POSITION)", elements.count),
                    ));
                }
                read[k] = Some(elements);
            }
        }
        if self.builder.positions.len() + n > u32::MAX as usize {
            return Err(load::error_in(
                self.doc.origin,
                MeshIoErrorKind::Unrepresentable {
                    format: "32-bit indices",
                    what: String::from("more than 2³² vertices"),
                },
            ));
        }
        let b = &mut self.builder;
        b.positions.extend((0..n).map(|i| {
            let p = positions.vec3(i);
            if placement.identity { p } else { placement.matrix.transform_point3(p) }
        }));
        match &read[0] {
            Some(e) => b.normals.extend((0..n).map(|i| {
                let v = e.vec3(i);
                if placement.identity { v } else { (placement.normal_matrix * v).normalize_or_zero() }
            })),
            None => b.normals.resize(b.positions.len(), DVec3::ZERO),
        }
        match &read[1] {
            Some(e) => b.uvs.extend((0..n).map(|i| DVec2::new(e.get(i, 0), 1.0 - e.get(i, 1)))),
            None => b.uvs.resize(b.positions.len(), DVec2::ZERO),
        }
        match &read[2] {
            Some(e) => b.colors.extend((0..n).map(|i| e.vec3(i))),
            None => b.colors.resize(b.positions.len(), DVec3::ZERO),
        }
        Ok(n)
    }

    /// Appends the triangles of a primitive whose `count` vertices start at `base`.
    fn add_triangles(
        &mut self,
        at: &str,
        indices: Option<usize>,
        mode: Mode,
        base: u32,
        count: usize,
        mirror: bool,
    ) -> Result<(), MeshIoError> {
        let corners: Vec<u32> = match indices {
            Some(a) => {
                let here = format!("{at}.indices");
                let elements = self.doc.accessor(a, &here, &INDICES)?;
                let mut corners = Vec::with_capacity(elements.count);
                for i in 0..elements.count {
                    let v = elements.index(i);
                    if v as usize >= count {
                        return Err(self.error(
                            format!("{here} (accessors[{a}])"),
                            format!("found index {v} at element {i}, expected an index below {count} (the count of POSITION)"),
                        ));
                    }
                    corners.push(v);
                }
                corners
            }
            None => (0..count as u32).collect(),
        };
        let what = if indices.is_some() { "indices" } else { "vertices (no indices)" };
        let mut triangles = Vec::new();
        match mode {
            Mode::TriangleStrip => load::strip_triangles(&corners, |t| triangles.push(t)),
            Mode::TriangleFan => {
                for w in corners.get(1..).unwrap_or_default().windows(2) {
                    let t = [w[0], w[1], corners[0]];
                    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                        triangles.push(t);
                    }
                }
            }
            _ => {
                if !corners.len().is_multiple_of(3) {
                    return Err(self.error(
                        at,
                        format!("found {} {what} with mode TRIANGLES, expected a multiple of 3", corners.len()),
                    ));
                }
                triangles.extend(corners.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
            }
        }
        let b = &mut self.builder;
        if b.face_vertices.len() + 3 * triangles.len() > u32::MAX as usize {
            return Err(load::error_in(
                self.doc.origin,
                MeshIoErrorKind::Unrepresentable {
                    format: "32-bit indices",
                    what: String::from("more than 2³² face corners"),
                },
            ));
        }
        for [a, c, d] in triangles {
            let t = if mirror { [a, d, c] } else { [a, c, d] };
            b.face_vertices.extend(t.map(|v| base + v));
        }
        Ok(())
    }

    /// The mesh and the warnings; an error if there were primitives of triangles but not one
    /// triangle came of them.
    fn finish(mut self) -> Result<LoadedMesh, MeshIoError> {
        if self.builder.face_vertices.is_empty() && self.triangle_primitives > 0 {
            let (n, without) = (self.triangle_primitives, self.without_position);
            let no_triangle = "no triangle with three different vertices";
            let they = if n == 1 { "it has" } else { "they have" };
            let reason = match without {
                0 => format!("{they} {no_triangle}"),
                _ if without == n => format!("{they} no POSITION attribute"),
                _ => format!("{without} have no POSITION attribute, the others {no_triangle}"),
            };
            let records = format!("{n} mesh primitive{} of triangles", if n == 1 { "" } else { "s" });
            return Err(load::error_in(self.doc.origin, MeshIoErrorKind::NoFacesRead { records, reason }));
        }
        if self.skipped.len() > MAX_WARNINGS {
            let count = self.skipped.len() - MAX_WARNINGS;
            self.warnings.push(0, ReadWarningKind::More { count });
        }
        let mut b = self.builder;
        let mut keep = [true; 3];
        for (k, (with, without, first)) in b.attributes.iter_mut().enumerate() {
            keep[k] = *with > 0 && *without == 0;
            if *with > 0 && *without > 0 {
                self.warnings.push(
                    0,
                    ReadWarningKind::PrimitiveAttributeDropped {
                        attribute: ATTRIBUTES[k],
                        primitives_with: *with,
                        primitives_without: *without,
                        first_without: first.take().unwrap_or_default(),
                    },
                );
            }
        }
        let faces = b.face_vertices.len() / 3;
        let face_offsets = (0..=faces).map(|f| (3 * f) as u32).collect();
        let normals = keep[0].then(|| FaceVarying { values: b.normals, indices: b.face_vertices.clone() });
        let uvs = keep[1].then(|| FaceVarying { values: b.uvs, indices: b.face_vertices.clone() });
        if !keep[2] {
            b.colors.clear();
        }
        let mesh = PolyMesh {
            positions: b.positions,
            colors: b.colors,
            face_offsets,
            face_vertices: b.face_vertices,
            normals,
            uvs,
        };
        Ok(LoadedMesh {
            mesh,
            warnings: self.warnings.finish(),
            creases: Creases::default(),
            subdiv_tags: SubdivTags::default(),
        })
    }
}

/// "expected an index below N (the number of WHAT)", or "expected none (there are no WHAT)".
fn below(n: usize, what: &str) -> String {
    if n == 0 {
        format!("expected none (there are no {what})")
    } else {
        format!("expected an index below {n} (the number of {what})")
    }
}

/// A node's local transform: `matrix` (column-major), or translation · rotation · scale.
fn local_matrix(node: &json::Node) -> DMat4 {
    if let Some(m) = node.matrix {
        return DMat4::from_cols_array(&m.map(f64::from));
    }
    let translation = node.translation.map_or(DVec3::ZERO, |t| DVec3::from_array(t.map(f64::from)));
    let scale = node.scale.map_or(DVec3::ONE, |s| DVec3::from_array(s.map(f64::from)));
    let rotation = node.rotation.map_or(DQuat::IDENTITY, |q| {
        // glTF requires a unit quaternion; normalise what rounding left.
        DQuat::from_vec4(DVec4::from_array(q.0.map(f64::from)).try_normalize().unwrap_or(DVec4::W))
    });
    DMat4::from_scale_rotation_translation(scale, rotation, translation)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `.glb` of `json` and, if not empty, the binary chunk `bin` (both padded).
    fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
        let mut j = json.as_bytes().to_vec();
        j.resize(j.len().next_multiple_of(4), b' ');
        let mut b = bin.to_vec();
        b.resize(b.len().next_multiple_of(4), 0);
        let total = 12 + 8 + j.len() + if b.is_empty() { 0 } else { 8 + b.len() };
        let mut out = Vec::new();
        out.extend(MAGIC);
        out.extend(2u32.to_le_bytes());
        out.extend((total as u32).to_le_bytes());
        out.extend((j.len() as u32).to_le_bytes());
        out.extend(CHUNK_JSON);
        out.extend(j);
        if !b.is_empty() {
            out.extend((b.len() as u32).to_le_bytes());
            out.extend(CHUNK_BIN);
            out.extend(b);
        }
        out
    }

    fn f32s(values: &[f32]) -> Vec<u8> {
        values.iter().flat_map(|x| x.to_le_bytes()).collect()
    }

    /// A unit quad in z = 0 as a triangle strip: positions and normals interleaved (stride
    /// 24), normalized u16 UVs, u8 indices; its node is moved by x + 10.
    fn strip_quad() -> (String, Vec<u8>) {
        let json = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"translation":[10,0,0]}],
"meshes":[{"name":"quad","primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"mode":5}]}],
"buffers":[{"byteLength":116}],
"bufferViews":[{"buffer":0,"byteLength":96,"byteStride":24},{"buffer":0,"byteOffset":96,"byteLength":16},
{"buffer":0,"byteOffset":112,"byteLength":4}],
"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
{"bufferView":0,"byteOffset":12,"componentType":5126,"count":4,"type":"VEC3"},
{"bufferView":1,"componentType":5123,"normalized":true,"count":4,"type":"VEC2"},
{"bufferView":2,"componentType":5121,"count":4,"type":"SCALAR"}]}"#;
        let mut bin = Vec::new();
        for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0f32]] {
            bin.extend(f32s(&p));
            bin.extend(f32s(&[0.0, 0.0, 1.0]));
        }
        for uv in [[0u16, 65535], [65535, 65535], [0, 0], [65535, 0]] {
            bin.extend(uv.iter().flat_map(|x| x.to_le_bytes()));
        }
        bin.extend([0u8, 1, 2, 3]);
        (json.replace('\n', ""), bin)
    }

    fn read(bytes: &[u8]) -> LoadedMesh {
        parse_glb(bytes, "t.glb").unwrap_or_else(|e| panic!("{e}"))
    }

    fn err(bytes: &[u8]) -> String {
        parse_glb(bytes, "t.glb").unwrap_err().to_string()
    }

    /// The error for the strip quad with `from` replaced by `to` in its JSON.
    fn json_err(from: &str, to: &str) -> String {
        let (json, bin) = strip_quad();
        assert!(json.contains(from), "{from}");
        err(&glb(&json.replacen(from, to, 1), &bin))
    }

    #[test]
    fn strip_with_stride_normalized_uvs_and_translation() {
        let (json, bin) = strip_quad();
        let m = read(&glb(&json, &bin));
        assert!(m.warnings.is_empty(), "{:?}", m.warnings);
        let m = m.mesh;
        let x = DVec3::X * 10.0;
        assert_eq!(m.positions, vec![x, x + DVec3::X, x + DVec3::Y, x + DVec3::new(1.0, 1.0, 0.0)]);
        assert_eq!(m.face_vertices, vec![0, 1, 2, 1, 3, 2]);
        assert_eq!(m.face_offsets, vec![0, 3, 6]);
        let normals = m.normals.unwrap();
        assert_eq!(normals.values, vec![DVec3::Z; 4]);
        assert_eq!(normals.indices, m.face_vertices);
        assert_eq!(m.uvs.unwrap().values, vec![DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::ONE]);
        assert!(m.colors.is_empty());
    }

    #[test]
    fn fans_lists_and_no_indices() {
        let (json, bin) = strip_quad();
        // Fan 0 1 3 2: triangles (1 3 0) and (3 2 0).
        let mut fan = bin.clone();
        fan[112..116].copy_from_slice(&[0, 1, 3, 2]);
        let m = read(&glb(&json.replace(r#""mode":5"#, r#""mode":6"#), &fan)).mesh;
        assert_eq!(m.face_vertices, vec![1, 3, 0, 3, 2, 0]);
        // A strip without indices: the vertices in order.
        let m = read(&glb(&json.replace(r#","indices":3"#, ""), &bin)).mesh;
        assert_eq!(m.face_vertices, vec![0, 1, 2, 1, 3, 2]);
        // A list (the default mode) of 4 indices does not make whole triangles.
        assert_eq!(
            err(&glb(&json.replace(r#","mode":5"#, ""), &bin)),
            "t.glb: meshes[0].primitives[0]: found 4 indices with mode TRIANGLES, expected a multiple of 3"
        );
        // A strip with a repeated index: the degenerate triangles are left out; none left is
        // an error (#39), a file of points is not.
        let mut degenerate = bin.clone();
        degenerate[112..116].copy_from_slice(&[0, 1, 1, 2]);
        assert_eq!(
            err(&glb(&json, &degenerate)),
            "t.glb: read no faces from 1 mesh primitive of triangles: it has no triangle with three different vertices"
        );
        let no_position = json.replace(r#""POSITION":0,"#, "");
        assert_eq!(
            err(&glb(&no_position.replace("}]}]", "},{\"attributes\":{},\"mode\":4}]}]"), &bin)),
            "t.glb: read no faces from 2 mesh primitives of triangles: they have no POSITION attribute"
        );
        let points = read(&glb(&json.replace(r#""mode":5"#, r#""mode":0"#), &bin));
        assert_eq!((points.mesh.num_vertices(), points.mesh.num_faces(), points.warnings.len()), (0, 0, 1));
    }

    #[test]
    fn transforms_matrix_trs_hierarchy_and_mirror() {
        let (json, bin) = strip_quad();
        let positions = |node: &str| {
            let j = json.replace(r#"{"mesh":0,"translation":[10,0,0]}"#, node);
            read(&glb(&j, &bin)).mesh
        };
        // A quarter turn about z, then x + 1: as TRS and as a column-major matrix.
        let s = std::f32::consts::FRAC_1_SQRT_2;
        let trs = positions(&format!(r#"{{"mesh":0,"rotation":[0,0,{s},{s}],"translation":[1,0,0]}}"#));
        let matrix = positions(r#"{"mesh":0,"matrix":[0,1,0,0, -1,0,0,0, 0,0,1,0, 1,0,0,1]}"#);
        for (a, b) in trs.positions.iter().zip(&matrix.positions) {
            assert!(a.distance(*b) < 1e-7, "{a} {b}");
        }
        assert!(matrix.positions[1].distance(DVec3::new(1.0, 1.0, 0.0)) < 1e-12);
        // Parent x + 10, child scaled by 2 (normals stay unit).
        let j = json.replace(
            r#""nodes":[{"mesh":0,"translation":[10,0,0]}]"#,
            r#""nodes":[{"children":[1],"translation":[10,0,0]},{"mesh":0,"scale":[2,2,2]}]"#,
        );
        let m = read(&glb(&j, &bin)).mesh;
        assert_eq!(m.positions[3], DVec3::new(12.0, 2.0, 0.0));
        assert_eq!(m.normals.unwrap().values[0], DVec3::Z);
        // A mirror in x: triangles reversed to stay counter-clockwise; the normals keep +z.
        let m = positions(r#"{"mesh":0,"scale":[-1,1,1]}"#);
        assert_eq!(m.positions[1], DVec3::new(-1.0, 0.0, 0.0));
        assert_eq!(m.face_vertices, vec![0, 2, 1, 1, 2, 3]);
        assert_eq!(m.normals.unwrap().values[0], DVec3::Z);
        // A shear: the normal is transformed by the inverse transpose (it stays
        // perpendicular to the transformed quad).
        let m = positions(r#"{"mesh":0,"matrix":[1,0,0,0, 0,1,0,0, 1,0,1,0, 0,0,0,1]}"#);
        assert_eq!(m.normals.as_ref().unwrap().values[0], DVec3::Z);
        let m = positions(r#"{"mesh":0,"matrix":[1,0,1,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}"#);
        let n = m.normals.as_ref().unwrap().values[0];
        let edge = m.positions[1] - m.positions[0];
        assert!(n.dot(edge).abs() < 1e-12 && (n.length() - 1.0).abs() < 1e-12, "{n} {edge}");
    }

    #[test]
    fn several_nodes_primitives_and_no_scene() {
        let (json, bin) = strip_quad();
        // Two nodes share the mesh: each gets its own vertices.
        let j = json.replace(
            r#""scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[10,0,0]}]"#,
            r#""scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0,"translation":[10,0,0]},{"mesh":0}]"#,
        );
        let m = read(&glb(&j, &bin)).mesh;
        assert_eq!(m.num_vertices(), 8);
        assert_eq!(m.face_vertices[6..], [4, 5, 6, 5, 7, 6]);
        assert_eq!(m.positions[4], DVec3::ZERO);
        // Without scenes, every mesh once, untransformed.
        let j = json.replace(r#""scene":0,"scenes":[{"nodes":[0]}],"#, "");
        let m = read(&glb(&j, &bin)).mesh;
        assert_eq!(m.positions[0], DVec3::ZERO);
        // Without `scene`, the first of `scenes`.
        let m = read(&glb(&json.replace(r#""scene":0,"#, ""), &bin)).mesh;
        assert_eq!(m.positions[0], DVec3::X * 10.0);
        // Two primitives on the same accessors share vertices; one of lines is skipped, once
        // even though two nodes use the mesh; one without normals or UVs drops them.
        let prim = r#"{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"mode":5}"#;
        let j = json.replace(
            prim,
            &format!(
                r#"{prim},{prim},{{"attributes":{{"POSITION":0}},"mode":1}},{{"attributes":{{"POSITION":0}},"indices":3,"mode":5}},{{"attributes":{{}}}}"#
            ),
        );
        let j = j.replace(r#""nodes":[{"mesh":0,"translation":[10,0,0]}]"#, r#""nodes":[{"mesh":0},{"mesh":0}]"#);
        let j = j.replace(r#""nodes":[0]"#, r#""nodes":[0,1]"#);
        let m = read(&glb(&j, &bin));
        let text: Vec<String> = m.warnings.iter().map(ToString::to_string).collect();
        assert_eq!(
            text,
            [
                r#"skipped meshes[0].primitives[2] (mesh "quad"): its mode is LINES, not triangles"#,
                r#"skipped meshes[0].primitives[4] (mesh "quad"): it has no POSITION attribute"#,
                "dropped the normals: 4 mesh primitives have them, 2 do not (the first is meshes[0].primitives[3])",
                "dropped the texture coordinates: 4 mesh primitives have them, 2 do not (the first is meshes[0].primitives[3])",
            ]
        );
        let m = m.mesh;
        // Per node: 4 vertices for primitives 0 and 1, 4 more for primitive 3.
        assert_eq!((m.num_vertices(), m.num_faces()), (16, 12));
        assert_eq!(m.face_vertices[..12], [0, 1, 2, 1, 3, 2, 0, 1, 2, 1, 3, 2]);
        assert!(m.normals.is_none() && m.uvs.is_none());
        // Many skipped primitives: the warnings are capped.
        let points = r#"{"attributes":{"POSITION":0},"mode":0}"#;
        let many = vec![points; MAX_WARNINGS + 3].join(",");
        let m = read(&glb(&json.replace(prim, &format!("{prim},{many}")), &bin));
        assert_eq!(m.warnings.len(), MAX_WARNINGS + 1);
        assert_eq!(m.warnings[MAX_WARNINGS].to_string(), "… and 3 more warnings like the previous one");
        assert_eq!(m.mesh.num_faces(), 2);
    }

    #[test]
    fn colors_and_data_uris() {
        let (json, bin) = strip_quad();
        // Vertex colours: normalized u8 VEC4 appended to the buffer (alpha dropped).
        let mut b = bin.clone();
        b.extend([255u8, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 0]);
        let j = json
            .replace(r#""TEXCOORD_0":2"#, r#""TEXCOORD_0":2,"COLOR_0":4"#)
            .replace(r#""byteLength":116}]"#, r#""byteLength":132}]"#)
            .replace(
                r#"{"buffer":0,"byteOffset":112,"byteLength":4}"#,
                r#"{"buffer":0,"byteOffset":112,"byteLength":4},{"buffer":0,"byteOffset":116,"byteLength":16}"#,
            )
            .replace(
                r#""type":"SCALAR"}"#,
                r#""type":"SCALAR"},{"bufferView":3,"componentType":5121,"normalized":true,"count":4,"type":"VEC4"}"#,
            );
        let m = read(&glb(&j, &b)).mesh;
        assert_eq!(m.colors, vec![DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE]);
        // The same buffer as a base64 data URI, and no BIN chunk.
        let encoded = base64(&bin);
        let j = json.replace(
            r#""buffers":[{"byteLength":116}]"#,
            &format!(r#""buffers":[{{"byteLength":116,"uri":"data:application/octet-stream;base64,{encoded}"}}]"#),
        );
        let m = read(&glb(&j, &[])).mesh;
        assert_eq!(m.positions[3], DVec3::new(11.0, 1.0, 0.0));
        assert_eq!(decode_base64(b"TWFu"), Some(b"Man".to_vec()));
        assert_eq!(decode_base64(b"TWE="), Some(b"Ma".to_vec()));
        assert_eq!(decode_base64(b"TQ"), Some(b"M".to_vec()));
        assert_eq!(decode_base64(b"T"), None);
        assert_eq!(decode_base64(b"T*=="), None);
    }

    /// Standard base64 with padding, for the tests.
    fn base64(bytes: &[u8]) -> String {
        const DIGITS: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut out = String::new();
        for chunk in bytes.chunks(3) {
            let n = chunk.iter().enumerate().fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
            for k in 0..4 {
                if k <= chunk.len() {
                    out.push(DIGITS[(n >> (18 - 6 * k) & 63) as usize] as char);
                } else {
                    out.push('=');
                }
            }
        }
        out
    }

    #[test]
    fn header_and_chunk_errors() {
        let (json, bin) = strip_quad();
        let good = glb(&json, &bin);
        assert_eq!(
            err(b"glTF"),
            "t.glb: found end of file, expected a 12-byte binary glTF header (the file has 4 bytes)"
        );
        let mut b = good.clone();
        b[0] = b'g';
        b[3] = 0xFF;
        assert_eq!(err(&b), r#"t.glb: byte 0: found "glT\xff", expected glTF (the magic number of binary glTF)"#);
        assert_eq!(
            err(b" {\"asset\":{\"version\":\"2.0\"}}"),
            "t.glb: byte 0: found JSON text, expected binary glTF starting with glTF (text .gltf files are not supported)"
        );
        let mut b = good.clone();
        b[4] = 1;
        assert_eq!(err(&b), "t.glb: byte 4: found version 1, expected version 2 (glTF 2.0)");
        let n = good.len();
        assert_eq!(
            err(&good[..n - 1]),
            format!(
                "t.glb: found end of file, expected {n} bytes (the length in the binary glTF header), found {}",
                n - 1
            )
        );
        let mut b = good.clone();
        b[8..12].copy_from_slice(&16u32.to_le_bytes());
        assert_eq!(
            err(&b),
            "t.glb: byte 8: found a total length of 16 bytes, expected at least 20 (the header and a JSON chunk)"
        );
        // A shorter total length: the BIN chunk is cut off.
        let mut b = good.clone();
        b[8..12].copy_from_slice(&((n - 4) as u32).to_le_bytes());
        let json_len = u32_at(&good, 12) as usize;
        let bin_at = 20 + json_len + 8;
        assert_eq!(
            err(&b),
            format!(
                "t.glb: found end of file, expected the 116 bytes of chunk 1 (\"BIN\\x00\") at byte {bin_at}, found 112"
            )
        );
        // A chunk longer than the file.
        let mut b = good.clone();
        b[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(err(&b).starts_with(
            "t.glb: found end of file, expected the 4294967295 bytes of chunk 0 (\"JSON\") at byte 20, found "
        ));
        // Only part of a chunk header.
        let mut b = good[..20 + json_len + 4].to_vec();
        let len = b.len() as u32;
        b[8..12].copy_from_slice(&len.to_le_bytes());
        assert_eq!(
            err(&b),
            format!(
                "t.glb: found end of file, expected the 8-byte header of chunk 1 at byte {} (the file has {} bytes)",
                20 + json_len,
                b.len()
            )
        );
        let mut b = good.clone();
        b[16..20].copy_from_slice(b"JSOX");
        assert_eq!(err(&b), r#"t.glb: chunk 0 at byte 12: found chunk type "JSOX", expected JSON (the first chunk)"#);
        // Trailing bytes after the declared length: a warning.
        let mut b = good.clone();
        b.extend([0; 5]);
        assert_eq!(read(&b).warnings[0].to_string(), "ignored 5 bytes after the end of the data");
        // Unknown chunks are skipped.
        let mut b = good;
        b.extend(4u32.to_le_bytes());
        b.extend(b"XTRA");
        b.extend([1, 2, 3, 4]);
        let total = b.len() as u32;
        b[8..12].copy_from_slice(&total.to_le_bytes());
        assert!(read(&b).warnings.is_empty());
    }

    #[test]
    fn json_errors_have_line_column_and_byte() {
        let (_, bin) = strip_quad();
        let b = glb("{\"asset\":{\"version\":\"2.0\"},\n\"meshes\":[{}]}", &bin);
        assert_eq!(
            err(&b),
            "t.glb: JSON chunk line 2, column 12 (byte 59): invalid glTF JSON: missing field `primitives`"
        );
        assert_eq!(b[59], b'}');
        let e = err(&glb("{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"mesh\":\"a\"}]}", &bin));
        assert_eq!(
            e,
            r#"t.glb: JSON chunk line 1, column 47 (byte 66): invalid glTF JSON: invalid type: string "a", expected index into child of root"#
        );
        assert_eq!(&glb("{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"mesh\":\"a\"}]}", &bin)[66..67], b"\"");
        let e = err(&glb("{\"asset\":", &bin));
        assert_eq!(e, "t.glb: JSON chunk line 1, column 9 (byte 28): invalid glTF JSON: EOF while parsing a value");
    }

    #[test]
    fn document_errors_name_the_json_path() {
        assert_eq!(
            json_err(r#""indices":3"#, r#""indices":9"#),
            "t.glb: meshes[0].primitives[0].indices: found accessor 9, expected an index below 4 (the number of accessors)"
        );
        assert_eq!(
            json_err(r#"{"bufferView":0,"componentType":5126"#, r#"{"bufferView":0,"componentType":5123"#),
            "t.glb: meshes[0].primitives[0].attributes.POSITION (accessors[0]): found u16 VEC3, expected f32 VEC3 (quantized positions are not supported)"
        );
        assert_eq!(
            json_err(r#""type":"SCALAR""#, r#""type":"SCALAR","normalized":true"#),
            "t.glb: meshes[0].primitives[0].indices (accessors[3]): found normalized u8 SCALAR, expected u8, u16 or u32 SCALAR"
        );
        assert_eq!(
            json_err(r#""componentType":5121"#, r#""componentType":5124"#),
            "t.glb: meshes[0].primitives[0].indices (accessors[3]): found an invalid componentType, expected 5120, 5121, 5122, 5123, 5125 or 5126"
        );
        assert_eq!(
            json_err(
                r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":4"#,
                r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":5"#
            ),
            "t.glb: meshes[0].primitives[0].attributes.NORMAL (accessors[1]): found 5 elements of 12 bytes every 24 bytes from byte 12 (up to byte 120), expected them within bufferViews[0] of 96 bytes"
        );
        assert_eq!(
            json_err(
                r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":4"#,
                r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":18446744073709551615"#
            ),
            "t.glb: meshes[0].primitives[0].attributes.NORMAL (accessors[1]): found 18446744073709551615 elements of 12 bytes every 24 bytes from byte 12 (up to byte beyond 2⁶⁴), expected them within bufferViews[0] of 96 bytes"
        );
        assert_eq!(
            json_err(r#""byteOffset":112,"byteLength":4"#, r#""byteOffset":114,"byteLength":4"#),
            "t.glb: bufferViews[2]: found bytes 114..118 of buffers[0], which has 116 bytes, expected a view within its buffer"
        );
        assert_eq!(
            json_err(r#""byteStride":24"#, r#""byteStride":8"#),
            "t.glb: bufferViews[0].byteStride: found 8, expected at least 12 (the size of an element of accessors[0])"
        );
        assert_eq!(
            json_err(r#""byteLength":116}"#, r#""byteLength":120}"#),
            "t.glb: buffers[0].byteLength: found 120 bytes, expected at most 116 (the size of the BIN chunk)"
        );
        assert_eq!(
            json_err(r#""byteLength":116}"#, r#""byteLength":116,"uri":"quad.bin"}"#),
            r#"t.glb: buffers[0].uri: external buffer "quad.bin" is not supported: only .glb with embedded buffers (the BIN chunk or base64 data: URIs)"#
        );
        assert_eq!(
            json_err(r#""byteLength":116}"#, r#""byteLength":116,"uri":"data:,abc"}"#),
            r#"t.glb: buffers[0].uri: found a data URI "data:,…", expected a base64 one (data:…;base64,…)"#
        );
        assert_eq!(
            json_err(
                r#""type":"SCALAR"}"#,
                r#""type":"SCALAR","sparse":{"count":1,"indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":2}}}"#
            ),
            "t.glb: meshes[0].primitives[0].indices (accessors[3]): found a sparse accessor, expected a plain one (sparse accessors are not supported)"
        );
        assert_eq!(
            json_err(r#"{"bufferView":2,"#, "{"),
            "t.glb: meshes[0].primitives[0].indices (accessors[3]): found no bufferView, expected one (accessors of zeros are not supported)"
        );
        assert_eq!(
            json_err(r#""count":4,"type":"VEC2""#, r#""count":3,"type":"VEC2""#),
            "t.glb: meshes[0].primitives[0].attributes.TEXCOORD_0 (accessors[2]): found 3 elements, expected 4 (the count of POSITION)"
        );
        assert_eq!(
            json_err(r#""nodes":[0]"#, r#""nodes":[1]"#),
            "t.glb: scenes[0].nodes[0]: found node 1, expected an index below 1 (the number of nodes)"
        );
        assert_eq!(
            json_err(r#"{"mesh":0,"translation":[10,0,0]}"#, r#"{"mesh":0,"children":[0]}"#),
            "t.glb: nodes[0].children[0]: found node 0 a second time, expected every node at most once (nodes form trees)"
        );
        assert_eq!(
            json_err(r#"{"mesh":0,"#, r#"{"mesh":3,"#),
            "t.glb: nodes[0].mesh: found mesh 3, expected an index below 1 (the number of meshes)"
        );
        assert_eq!(
            json_err(r#""scene":0"#, r#""scene":2"#),
            "t.glb: scene: found scene 2, expected an index below 1 (the number of scenes)"
        );
        assert_eq!(
            json_err(
                r#""asset":{"version":"2.0"}"#,
                r#""asset":{"version":"2.0"},"extensionsRequired":["KHR_draco_mesh_compression"]"#
            ),
            r#"t.glb: extensionsRequired[0]: found "KHR_draco_mesh_compression", expected uncompressed geometry (compressed meshes are not supported)"#
        );
        // No BIN chunk for the buffer without uri.
        let (json, _) = strip_quad();
        assert_eq!(
            err(&glb(&json, &[])),
            "t.glb: buffers[0]: found a buffer without uri and no BIN chunk, expected a BIN chunk holding it"
        );
    }

    #[test]
    fn index_out_of_range_names_primitive_and_index() {
        let (json, mut bin) = strip_quad();
        bin[114] = 7;
        assert_eq!(
            err(&glb(&json, &bin)),
            "t.glb: meshes[0].primitives[0].indices (accessors[3]): found index 7 at element 2, expected an index below 4 (the count of POSITION)"
        );
    }

    #[test]
    fn truncations_and_bit_flips_never_panic() {
        let (json, bin) = strip_quad();
        let good = glb(&json, &bin);
        for n in 0..good.len() {
            let _ = parse_glb(&good[..n], "t.glb");
            // Truncated, with the header's length fixed up: chunk errors, not header errors.
            let mut b = good[..n].to_vec();
            if n >= 12 {
                b[8..12].copy_from_slice(&(n as u32).to_le_bytes());
                let _ = parse_glb(&b, "t.glb");
            }
        }
        let mut ok = 0;
        for i in 0..good.len() * 8 {
            let mut b = good.clone();
            b[i / 8] ^= 1 << (i % 8);
            ok += usize::from(parse_glb(&b, "t.glb").is_ok());
        }
        // Flips in vertex data and JSON whitespace still read.
        assert!(ok > 0);
    }
}
