//! The PLY reader (ASCII, binary little endian and binary big endian).

use std::io::Read;

use glam::{DVec2, DVec3};
use splinekit::mesh::{FaceVarying, PolyMesh};
use splinekit::subdiv::Creases;

use super::load::{self, LoadedMesh, ReadWarningKind, Warnings};
use super::{MeshIoError, MeshIoErrorKind, SubdivTags};
use crate::swp::SourcePos;

/// Reads a PLY mesh from `reader`; `origin` names it in errors (usually the path).
///
/// # What is read
///
/// - The header: `ply`, `format ascii 1.0` / `binary_little_endian 1.0` /
///   `binary_big_endian 1.0`, `comment` and `obj_info` lines, `element NAME COUNT`,
///   `property TYPE NAME` and `property list COUNT_TYPE ITEM_TYPE NAME`, `end_header`. Types
///   are `char uchar short ushort int uint float double` and their sized names (`int8` …
///   `float64`). Header lines may end with CRLF. An ASCII file may start with a UTF-8
///   byte-order mark, or be UTF-16 with a byte-order mark (decoded).
/// - Element `vertex`: `x y z` (required, any numeric type); `nx ny nz` (normals, if all
///   three are present); `red green blue` or `diffuse_red diffuse_green diffuse_blue`
///   (colours: integer types are divided by their maximum, so `uchar` 255 is 1.0; float
///   types are kept as given); texture coordinates from `u v`, `s t`, `texture_u texture_v`
///   or `texture_s texture_t`. Normals and texture coordinates become face-varying
///   attributes with per-vertex indices.
/// - Element `face`: the list `vertex_indices` (or `vertex_index`) of any integer types;
///   polygons of any size are kept as they are (faces with fewer than three corners too, for
///   [`TopologyReport`](splinekit::mesh::TopologyReport) to report). A list `texcoord` (two
///   numbers a corner, as MeshLab writes per-corner texture coordinates) gives face-varying
///   UVs, in place of the vertices' own: the corners of a vertex with equal UVs share one
///   value, so a UV seam is where a vertex's corners differ.
/// - Element `tristrips` (triangle strips, as old scanners' files and some MeshLab files
///   have them: usually `element tristrips 1` and `property list int int vertex_indices`):
///   the list `vertex_indices` (or `vertex_index`) holds strips separated by `-1`. Triangle k
///   of a strip (k from 0 at the strip's start), of the corners a, b, c at k, k + 1, k + 2,
///   is (a, b, c) for even k and (a, c, b) for odd k, so that all face the way the first
///   does. Triangles with a repeated vertex (which stitch strips together) are left out, as
///   MeshLab leaves them out. Faces and strip triangles are numbered in the order of their
///   elements in the file.
///
/// Nothing is dropped silently: other elements (edges, materials, range grids, …) are read
/// past with a [`SkippedElement`](ReadWarningKind::SkippedElement) warning, and the other
/// properties of `vertex`, `face` and `tristrips` with a
/// [`SkippedProperty`](ReadWarningKind::SkippedProperty) warning, one per name, on its
/// header line (none when the element's count is 0). Elements may come in any order.
///
/// In ASCII files values are separated by any whitespace (a record need not be one line).
/// Bytes after the last element are ignored with a
/// [`TrailingBytes`](ReadWarningKind::TrailingBytes) warning.
///
/// # Errors
///
/// A [`MeshIoError`] naming the element, record and property: in the header and in ASCII
/// data with `origin:LINE:COL` (for example `found "1.5x", expected a float (property y of
/// vertex 3)`); in binary data with the origin only (`found end of file, expected a float
/// (property z of vertex 99 of 100)`). Also: a missing `x`, `y` or `z` property or face
/// index list, a list length that is negative or not an integer, a vertex index out of
/// range (for strips, other than `-1`), an integer outside its type's range, a file that
/// looks like UTF-16 without a byte-order mark, and strips that make not one triangle
/// ([`NoFacesRead`](MeshIoErrorKind::NoFacesRead)).
///
/// ```
/// use splinekit_io::mesh::read_ply;
///
/// let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
///             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
///             end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
/// let loaded = read_ply(text.as_bytes(), "tri.ply")?;
/// assert_eq!(loaded.mesh.face(0), &[0, 1, 2]);
///
/// let err = read_ply(text.replace("3 0 1 2", "3 0 1 3").as_bytes(), "tri.ply").unwrap_err();
/// assert_eq!(err.to_string(), "tri.ply:13:7: found \"3\", expected a vertex index below 3 (corner 2 of face 0)");
/// # Ok::<(), splinekit_io::MeshIoError>(())
/// ```
pub fn read_ply<R: Read>(reader: R, origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let bytes = load::read_all(reader, origin)?;
    parse_ply(&bytes, origin)
}

/// A scalar type of a PLY property.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Self> {
        Some(match name {
            b"char" | b"int8" => Self::I8,
            b"uchar" | b"uint8" => Self::U8,
            b"short" | b"int16" => Self::I16,
            b"ushort" | b"uint16" => Self::U16,
            b"int" | b"int32" => Self::I32,
            b"uint" | b"uint32" => Self::U32,
            b"float" | b"float32" => Self::F32,
            b"double" | b"float64" => Self::F64,
            _ => return None,
        })
    }

    /// The type name with its article, for messages: `a float`, `an int`.
    fn described(self) -> String {
        let name = self.name();
        format!("{} {name}", if name.starts_with('i') { "an" } else { "a" })
    }

    fn name(self) -> &'static str {
        match self {
            Self::I8 => "char",
            Self::U8 => "uchar",
            Self::I16 => "short",
            Self::U16 => "ushort",
            Self::I32 => "int",
            Self::U32 => "uint",
            Self::F32 => "float",
            Self::F64 => "double",
        }
    }

    fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }

    /// The integer range, or `None` for float types.
    fn range(self) -> Option<(i64, i64)> {
        Some(match self {
            Self::I8 => (i8::MIN.into(), i8::MAX.into()),
            Self::U8 => (0, u8::MAX.into()),
            Self::I16 => (i16::MIN.into(), i16::MAX.into()),
            Self::U16 => (0, u16::MAX.into()),
            Self::I32 => (i32::MIN.into(), i32::MAX.into()),
            Self::U32 => (0, u32::MAX.into()),
            Self::F32 | Self::F64 => return None,
        })
    }

    /// Decodes a value from exactly `size()` bytes.
    fn decode(self, b: &[u8], big: bool) -> f64 {
        macro_rules! get {
            ($t:ty, $n:literal) => {{
                let mut a = [0u8; $n];
                a.copy_from_slice(&b[..$n]);
                if big { <$t>::from_be_bytes(a) } else { <$t>::from_le_bytes(a) }
            }};
        }
        match self {
            Self::I8 => f64::from(b[0] as i8),
            Self::U8 => f64::from(b[0]),
            Self::I16 => f64::from(get!(i16, 2)),
            Self::U16 => f64::from(get!(u16, 2)),
            Self::I32 => f64::from(get!(i32, 4)),
            Self::U32 => f64::from(get!(u32, 4)),
            Self::F32 => f64::from(get!(f32, 4)),
            Self::F64 => get!(f64, 8),
        }
    }
}

#[derive(Clone, Copy, Debug)]
enum PropType {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: String,
    ty: PropType,
    /// Its line in the header, for warnings.
    line: usize,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    props: Vec<Property>,
    /// Where its name is in the header, for errors about the element as a whole.
    pos: SourcePos,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

/// The parsed header and where the data starts.
struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the data.
    data: usize,
    /// Line number of the first data line (ASCII).
    data_line: usize,
}

fn parse_header(bytes: &[u8], origin: &str) -> Result<Header, MeshIoError> {
    let mut pos = 0;
    let mut no = 0;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        no += 1;
        let Some(len) = bytes[pos..].iter().position(|&b| b == b'\n') else {
            let line = &bytes[pos..];
            let end = line.len();
            return Err(load::error_at(
                origin,
                no,
                line,
                end,
                MeshIoErrorKind::UnexpectedEnd {
                    found: "end of file",
                    expected: String::from(if no == 1 { "a PLY header" } else { "end_header" }),
                },
            ));
        };
        let raw = &bytes[pos..pos + len];
        let line = raw.strip_suffix(b"\r").unwrap_or(raw);
        pos += len + 1;
        let unexpected =
            |offset: usize, token: &[u8], expected: &str| load::unexpected(origin, no, line, offset, token, expected);
        let mut cursor = 0;
        let mut next = || {
            let mut i = cursor;
            while i < line.len() && line[i].is_ascii_whitespace() {
                i += 1;
            }
            let start = i;
            while i < line.len() && !line[i].is_ascii_whitespace() {
                i += 1;
            }
            cursor = i;
            (start, &line[start..i])
        };
        let (k0, keyword) = next();
        if no == 1 {
            if keyword != b"ply" {
                if load::looks_like_utf16(bytes) {
                    return Err(load::error_in(origin, MeshIoErrorKind::Utf16WithoutBom));
                }
                return Err(unexpected(k0, keyword, "ply (the first line of a PLY file)"));
            }
            continue;
        }
        match keyword {
            b"format" => {
                let (k, name) = next();
                encoding = Some(match name {
                    b"ascii" => Encoding::Ascii,
                    b"binary_little_endian" => Encoding::Little,
                    b"binary_big_endian" => Encoding::Big,
                    _ => return Err(unexpected(k, name, "ascii, binary_little_endian or binary_big_endian")),
                });
            }
            b"comment" | b"obj_info" => {}
            b"element" => {
                if encoding.is_none() {
                    return Err(unexpected(k0, keyword, "a format line before the first element"));
                }
                let (k, name) = next();
                if name.is_empty() {
                    return Err(unexpected(k, name, "an element name"));
                }
                let (kc, count) = next();
                let count = load::parse_i64(count)
                    .and_then(|c| usize::try_from(c).ok())
                    .ok_or_else(|| unexpected(kc, count, "a non-negative element count"))?;
                elements.push(Element {
                    name: String::from_utf8_lossy(name).into_owned(),
                    count,
                    props: Vec::new(),
                    pos: SourcePos::new(no, load::column(line, k)),
                });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(unexpected(k0, keyword, "an element line before the first property"));
                };
                let scalar = |k: usize, t: &[u8]| {
                    Scalar::parse(t).ok_or_else(|| {
                        unexpected(k, t, "a type: char, uchar, short, ushort, int, uint, float or double")
                    })
                };
                let (kt, t) = next();
                let ty = if t == b"list" {
                    let (kc, c) = next();
                    let count = scalar(kc, c)?;
                    if count.range().is_none() {
                        return Err(unexpected(kc, c, "an integer type for the list length"));
                    }
                    let (ki, i) = next();
                    PropType::List { count, item: scalar(ki, i)? }
                } else {
                    PropType::Scalar(scalar(kt, t)?)
                };
                let (kn, name) = next();
                if name.is_empty() {
                    return Err(unexpected(kn, name, "a property name"));
                }
                element.props.push(Property { name: String::from_utf8_lossy(name).into_owned(), ty, line: no });
            }
            b"end_header" => break,
            _ => {
                return Err(unexpected(k0, keyword, "format, element, property, comment or end_header"));
            }
        }
        let (k, extra) = next();
        if !extra.is_empty() && !matches!(keyword, b"comment" | b"obj_info" | b"format") {
            return Err(unexpected(k, extra, "end of line"));
        }
    }
    let Some(encoding) = encoding else {
        return Err(load::error_at(
            origin,
            no,
            b"end_header",
            0,
            MeshIoErrorKind::UnexpectedToken {
                found: String::from("end_header"),
                expected: String::from("a format line"),
            },
        ));
    };
    Ok(Header { encoding, elements, data: pos, data_line: no + 1 })
}

/// The data after the header: ASCII tokens or binary values.
struct Data<'a> {
    bytes: &'a [u8],
    pos: usize,
    encoding: Encoding,
    origin: &'a str,
    /// ASCII: the current line number and the byte offset where it starts.
    line: usize,
    line_start: usize,
    /// Where the last token started (ASCII), for errors about its value.
    token_start: usize,
    token_line: usize,
    token_line_start: usize,
}

impl<'a> Data<'a> {
    /// The next ASCII token, or `None` at the end of the data.
    fn token(&mut self) -> Option<&'a [u8]> {
        let b = self.bytes;
        let mut i = self.pos;
        while i < b.len() && b[i].is_ascii_whitespace() {
            if b[i] == b'\n' {
                self.line += 1;
                self.line_start = i + 1;
            }
            i += 1;
        }
        if i == b.len() {
            self.pos = i;
            return None;
        }
        let start = i;
        while i < b.len() && !b[i].is_ascii_whitespace() {
            i += 1;
        }
        self.pos = i;
        self.token_start = start;
        self.token_line = self.line;
        self.token_line_start = self.line_start;
        Some(&b[start..i])
    }

    /// An error about the last ASCII token (`token`; empty: the end of the data).
    fn ascii_error(&self, token: &[u8], expected: String) -> MeshIoError {
        let (line_start, offset, line) = if token.is_empty() {
            (self.line_start, self.pos, self.line)
        } else {
            (self.token_line_start, self.token_start, self.token_line)
        };
        let end =
            self.bytes[line_start..].iter().position(|&b| b == b'\n').map_or(self.bytes.len(), |e| line_start + e);
        let text = &self.bytes[line_start..end];
        if token.is_empty() {
            let kind = MeshIoErrorKind::UnexpectedEnd { found: "end of file", expected };
            return MeshIoError::at(self.origin, SourcePos::new(line, load::column(text, offset - line_start)), kind);
        }
        load::unexpected(self.origin, line, text, offset - line_start, token, expected)
    }

    /// An error about the last value read: at its token (ASCII) or without position.
    fn value_error(&self, token: &[u8], expected: String) -> MeshIoError {
        if self.encoding == Encoding::Ascii {
            self.ascii_error(token, expected)
        } else {
            load::error_in(
                self.origin,
                MeshIoErrorKind::UnexpectedToken { found: String::from_utf8_lossy(token).into_owned(), expected },
            )
        }
    }

    /// Reads one value of type `t`; `what` describes it for errors.
    fn value(&mut self, t: Scalar, what: &dyn Fn() -> String) -> Result<f64, MeshIoError> {
        if self.encoding == Encoding::Ascii {
            let Some(token) = self.token() else {
                return Err(self.ascii_error(b"", format!("{} ({})", t.described(), what())));
            };
            let value = match t.range() {
                Some((lo, hi)) => load::parse_i64(token).filter(|v| (lo..=hi).contains(v)).map(|v| v as f64),
                None => load::parse_f64(token),
            };
            return value.ok_or_else(|| self.ascii_error(token, format!("{} ({})", t.described(), what())));
        }
        let n = t.size();
        if self.bytes.len() - self.pos < n {
            return Err(load::truncated(self.origin, format!("{} ({})", t.described(), what())));
        }
        let v = t.decode(&self.bytes[self.pos..self.pos + n], self.encoding == Encoding::Big);
        self.pos += n;
        Ok(v)
    }

    /// The text of the last value read, for an error about it.
    fn last_text(&self, value: f64) -> Vec<u8> {
        if self.encoding == Encoding::Ascii {
            self.bytes[self.token_start..self.pos].to_vec()
        } else {
            value.to_string().into_bytes()
        }
    }
}

/// What a vertex property is used for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Position(usize),
    Normal(usize),
    Color(usize),
    Tex(usize),
    Ignored,
}

/// The roles of a vertex element's properties.
fn vertex_roles(element: &Element) -> (Vec<Role>, bool, bool, bool, [bool; 3]) {
    let find = |names: &[&str]| element.props.iter().position(|p| names.contains(&p.name.as_str()));
    let mut roles = vec![Role::Ignored; element.props.len()];
    let scalar = |i: usize| matches!(element.props[i].ty, PropType::Scalar(_));
    let mut have_pos = [false; 3];
    for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
        if let Some(i) = find(&[axis]).filter(|&i| scalar(i)) {
            roles[i] = Role::Position(k);
            have_pos[k] = true;
        }
    }
    let mut set = |names: [&[&str]; 3], n: usize, role: fn(usize) -> Role| -> bool {
        let found: Vec<Option<usize>> = names[..n].iter().map(|k| find(k)).collect();
        if found.iter().all(|f| f.is_some_and(scalar)) {
            for (k, f) in found.into_iter().enumerate() {
                roles[f.unwrap_or_default()] = role(k);
            }
            true
        } else {
            false
        }
    };
    let normals = set([&["nx"], &["ny"], &["nz"]], 3, Role::Normal);
    let colors = set([&["red", "diffuse_red"], &["green", "diffuse_green"], &["blue", "diffuse_blue"]], 3, Role::Color);
    let tex = set([&["u", "s", "texture_u", "texture_s"], &["v", "t", "texture_v", "texture_t"], &[]], 2, Role::Tex);
    (roles, normals, colors, tex, have_pos)
}

/// What the reader does with an element.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Use {
    Vertices,
    Faces,
    Strips,
    Skipped,
}

/// The index of the vertex index list of a `face` or `tristrips` element.
fn index_list(element: &Element, origin: &str) -> Result<Option<usize>, MeshIoError> {
    let found = element.props.iter().position(|p| {
        matches!(p.ty, PropType::List { .. }) && (p.name == "vertex_indices" || p.name == "vertex_index")
    });
    if found.is_none() && element.count > 0 {
        let kind = MeshIoErrorKind::UnexpectedToken {
            found: element.name.clone(),
            expected: String::from("an element with a list property vertex_indices or vertex_index"),
        };
        return Err(MeshIoError::at(origin, element.pos, kind));
    }
    Ok(found)
}

/// The faces read so far: a CSR list, and a reused buffer for the strip being read.
#[derive(Default)]
struct Faces {
    offsets: Vec<u32>,
    vertices: Vec<u32>,
    strip: Vec<u32>,
}

impl Faces {
    /// Closes the face whose corners were pushed last.
    fn close(&mut self, origin: &str) -> Result<(), MeshIoError> {
        let end = u32::try_from(self.vertices.len()).map_err(|_| too_many_corners(origin))?;
        self.offsets.push(end);
        Ok(())
    }

    /// Adds the triangles of the strip gathered so far, and starts a new one.
    fn end_strip(&mut self, origin: &str) -> Result<(), MeshIoError> {
        let (vertices, offsets) = (&mut self.vertices, &mut self.offsets);
        let mut fits = true;
        load::strip_triangles(&self.strip, |t| {
            vertices.extend(t);
            match u32::try_from(vertices.len()) {
                Ok(end) => offsets.push(end),
                Err(_) => fits = false,
            }
        });
        self.strip.clear();
        if fits { Ok(()) } else { Err(too_many_corners(origin)) }
    }
}

/// The `texcoord` lists of the faces as read: two numbers a corner.
#[derive(Default)]
struct FaceUvs {
    /// Each face's list length.
    lengths: Vec<usize>,
    values: Vec<f64>,
}

impl FaceUvs {
    /// The UVs as a face-varying attribute: the corners of one vertex with the same UV share
    /// its value (so the UV mesh is joined across edges and split only at seams).
    fn into_face_varying(
        self,
        offsets: &[u32],
        vertices: &[u32],
        origin: &str,
    ) -> Result<FaceVarying<DVec2>, MeshIoError> {
        let mut ids: std::collections::HashMap<(u32, u64, u64), u32> = std::collections::HashMap::new();
        let mut uvs = FaceVarying { values: Vec::new(), indices: Vec::with_capacity(vertices.len()) };
        let mut at = 0;
        for (f, (w, &len)) in offsets.windows(2).zip(&self.lengths).enumerate() {
            let corners = (w[1] - w[0]) as usize;
            if len != 2 * corners {
                let kind = MeshIoErrorKind::UnexpectedToken {
                    found: format!("{len} numbers"),
                    expected: format!(
                        "two texture coordinates for each of the {corners} corners of face {f} (texcoord)"
                    ),
                };
                return Err(load::error_in(origin, kind));
            }
            for (c, &v) in vertices[w[0] as usize..w[1] as usize].iter().enumerate() {
                let uv = DVec2::new(self.values[at + 2 * c], self.values[at + 2 * c + 1]);
                let next = uvs.values.len() as u32;
                let id = *ids.entry((v, uv.x.to_bits(), uv.y.to_bits())).or_insert(next);
                if id == next {
                    uvs.values.push(uv);
                }
                uvs.indices.push(id);
            }
            at += len;
        }
        Ok(uvs)
    }
}

fn too_many_corners(origin: &str) -> MeshIoError {
    load::error_in(
        origin,
        MeshIoErrorKind::Unrepresentable {
            format: "32-bit indices", what: String::from("more than 2³² face corners")
        },
    )
}

/// Parses PLY bytes (see [`read_ply`]).
pub(crate) fn parse_ply(bytes: &[u8], origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let decoded;
    let bytes = match load::utf16_decoded(bytes) {
        Some(text) => {
            decoded = text;
            &decoded[..]
        }
        None => bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes),
    };
    let header = parse_header(bytes, origin)?;
    let first = |name: &str| header.elements.iter().position(|e| e.name == name);
    let (vertex_element, face_element, strip_element) = (first("vertex"), first("face"), first("tristrips"));
    let num_vertices = vertex_element.map_or(0, |i| header.elements[i].count);
    if u32::try_from(num_vertices).is_err() {
        return Err(load::error_in(
            origin,
            MeshIoErrorKind::Unrepresentable { format: "32-bit indices", what: format!("{num_vertices} vertices") },
        ));
    }
    let mut data = Data {
        bytes,
        pos: header.data,
        encoding: header.encoding,
        origin,
        line: header.data_line,
        line_start: header.data,
        token_start: header.data,
        token_line: header.data_line,
        token_line_start: header.data,
    };
    // Preallocate no more than the data could hold (at least a byte per value).
    let room = bytes.len() - header.data;
    let mut positions = Vec::with_capacity(num_vertices.min(room));
    let mut normals = Vec::new();
    let mut colors = Vec::new();
    let mut tex = Vec::new();
    let mut faces = Faces { offsets: vec![0], ..Faces::default() };
    let mut face_uvs = FaceUvs::default();
    let mut warnings = Warnings::default();

    for (e, element) in header.elements.iter().enumerate() {
        let role = match Some(e) {
            i if i == vertex_element => Use::Vertices,
            i if i == face_element => Use::Faces,
            i if i == strip_element => Use::Strips,
            _ => Use::Skipped,
        };
        let (roles, has_normals, has_colors, has_tex) = if role == Use::Vertices {
            let (roles, n, c, t, have) = vertex_roles(element);
            if let Some(k) = have.iter().position(|&h| !h) {
                let expected =
                    format!("an element with scalar properties x, y and z ({} is missing)", ["x", "y", "z"][k]);
                let kind = MeshIoErrorKind::UnexpectedToken { found: element.name.clone(), expected };
                return Err(MeshIoError::at(origin, element.pos, kind));
            }
            (roles, n, c, t)
        } else {
            (vec![Role::Ignored; element.props.len()], false, false, false)
        };
        let indices = match role {
            Use::Faces | Use::Strips => index_list(element, origin)?,
            Use::Vertices | Use::Skipped => None,
        };
        // a face's UVs, corner by corner (MeshLab's per-wedge texture coordinates)
        let texcoord = (role == Use::Faces)
            .then(|| element.props.iter().position(|p| p.name == "texcoord" && matches!(p.ty, PropType::List { .. })))
            .flatten();
        if element.count > 0 {
            if role == Use::Skipped {
                warnings.push(
                    element.pos.line,
                    ReadWarningKind::SkippedElement { name: element.name.clone(), count: element.count },
                );
            } else {
                for (k, prop) in element.props.iter().enumerate() {
                    if roles[k] == Role::Ignored && Some(k) != indices && Some(k) != texcoord {
                        let (element, name) = (element.name.clone(), prop.name.clone());
                        warnings.push(prop.line, ReadWarningKind::SkippedProperty { element, name });
                    }
                }
            }
        }
        for r in 0..element.count {
            let (mut p, mut n, mut c, mut t) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec2::ZERO);
            for (k, prop) in element.props.iter().enumerate() {
                let what = || format!("property {} of {} {r} of {}", prop.name, element.name, element.count);
                match prop.ty {
                    PropType::Scalar(s) => {
                        let v = data.value(s, &what)?;
                        match roles[k] {
                            Role::Position(i) => p[i] = v,
                            Role::Normal(i) => n[i] = v,
                            Role::Color(i) => c[i] = s.range().map_or(v, |(_, hi)| v / hi as f64),
                            Role::Tex(i) => t[i] = v,
                            Role::Ignored => {}
                        }
                    }
                    PropType::List { count, item } => {
                        let len_what = || format!("the length of list {} of {} {r}", prop.name, element.name);
                        let len = data.value(count, &len_what)?;
                        if len < 0.0 {
                            let text = data.last_text(len);
                            return Err(data.value_error(&text, format!("a non-negative length ({})", len_what())));
                        }
                        let list = if Some(k) == indices { role } else { Use::Skipped };
                        let uv_list = Some(k) == texcoord;
                        if uv_list {
                            face_uvs.lengths.push(len as usize);
                        }
                        for i in 0..len as usize {
                            let item_what = || format!("item {i} of list {} of {} {r}", prop.name, element.name);
                            let v = data.value(item, &item_what)?;
                            if uv_list {
                                face_uvs.values.push(v);
                            }
                            if list == Use::Skipped {
                                continue;
                            }
                            let restart = list == Use::Strips && v == -1.0;
                            if !restart && (v.fract() != 0.0 || !(0.0..num_vertices as f64).contains(&v)) {
                                let text = data.last_text(v);
                                let expected = if list == Use::Faces {
                                    format!("a vertex index below {num_vertices} (corner {i} of face {r})")
                                } else {
                                    format!(
                                        "a vertex index below {num_vertices}, or -1 to restart the strip (item {i} of tristrips {r})"
                                    )
                                };
                                return Err(data.value_error(&text, expected));
                            }
                            match list {
                                Use::Faces => faces.vertices.push(v as u32),
                                _ if restart => faces.end_strip(origin)?,
                                _ => faces.strip.push(v as u32),
                            }
                        }
                        match list {
                            Use::Faces => faces.close(origin)?,
                            Use::Strips => faces.end_strip(origin)?,
                            _ => {}
                        }
                    }
                }
            }
            if role == Use::Vertices {
                positions.push(p);
                if has_normals {
                    normals.push(n);
                }
                if has_colors {
                    colors.push(c);
                }
                if has_tex {
                    tex.push(t);
                }
            }
        }
    }

    if faces.offsets.len() == 1
        && let Some(e) = strip_element.map(|i| &header.elements[i]).filter(|e| e.count > 0)
    {
        let records = format!("element {:?} ({} strip{})", e.name, e.count, if e.count == 1 { "" } else { "s" });
        let reason = String::from("no strip has a triangle of three different vertices");
        return Err(load::error_in(origin, MeshIoErrorKind::NoFacesRead { records, reason }));
    }
    let rest = &bytes[data.pos..];
    let trailing = if header.encoding == Encoding::Ascii {
        rest.iter().filter(|b| !b.is_ascii_whitespace()).count()
    } else {
        rest.len()
    };
    if trailing > 0 {
        warnings.push(0, ReadWarningKind::TrailingBytes { count: rest.len() });
    }
    let Faces { offsets: face_offsets, vertices: face_vertices, .. } = faces;
    let normals = (!normals.is_empty()).then(|| FaceVarying { values: normals, indices: face_vertices.clone() });
    let uvs = if face_uvs.lengths.is_empty() {
        (!tex.is_empty()).then(|| FaceVarying { values: tex, indices: face_vertices.clone() })
    } else {
        Some(face_uvs.into_face_varying(&face_offsets, &face_vertices, origin)?)
    };
    let mesh = PolyMesh { positions, colors, face_offsets, face_vertices, normals, uvs };
    Ok(LoadedMesh {
        mesh,
        warnings: warnings.finish(),
        creases: Creases::default(),
        subdiv_tags: SubdivTags::default(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "ply\nformat ascii 1.0\ncomment c\nelement vertex 3\nproperty float x\nproperty float y\n\
                        property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

    fn err(bytes: &[u8]) -> String {
        parse_ply(bytes, "t.ply").unwrap_err().to_string()
    }

    #[test]
    fn ascii_with_attributes_and_other_elements() {
        let text = "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty double x\r\nproperty double y\r\n\
                    property double z\r\nproperty float nx\r\nproperty float ny\r\nproperty float nz\r\n\
                    property uchar red\r\nproperty uchar green\r\nproperty uchar blue\r\nproperty float s\r\n\
                    property float t\r\nproperty int flags\r\nelement edge 1\r\nproperty int a\r\nproperty int b\r\n\
                    element face 1\r\nproperty uchar intensity\r\nproperty list uchar uint vertex_index\r\nend_header\r\n\
                    0 0 0 0 0 1 255 0 0 0 0 7\r\n1 0 0 0 0 1 0 255 0 1 0 7\r\n0 1 0 0 0 1 0 0 255 0 1 7\r\n0 1\r\n9 3 0 1 2\r\n";
        let m = parse_ply(text.as_bytes(), "t.ply").unwrap();
        // What is skipped is said, once per property or element, at its header line (#39).
        let w: Vec<String> = m.warnings.iter().map(ToString::to_string).collect();
        assert_eq!(
            w,
            [
                r#"line 15: skipped property "flags" of element "vertex""#,
                r#"line 16: skipped element "edge" (1 in the file; the elements read are vertex, face and tristrips)"#,
                r#"line 20: skipped property "intensity" of element "face""#,
            ]
        );
        let m = m.mesh;
        assert_eq!(m.positions, vec![DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert_eq!(m.colors, vec![DVec3::X, DVec3::Y, DVec3::Z]);
        assert_eq!(m.normals.as_ref().unwrap().values, vec![DVec3::Z; 3]);
        assert_eq!(m.uvs.as_ref().unwrap().values[2], DVec2::Y);
        assert_eq!(m.face(0), &[0, 1, 2]);
    }

    #[test]
    fn binary_both_endians() {
        for (format, big) in [("binary_little_endian", false), ("binary_big_endian", true)] {
            let mut b = HEAD.replace("ascii", format).replace("float z", "double z").into_bytes();
            for p in [[0.0f32, 0.0], [1.0, 0.0], [0.0, 1.0]] {
                for x in p {
                    b.extend(if big { x.to_be_bytes() } else { x.to_le_bytes() });
                }
                b.extend(if big { 0.5f64.to_be_bytes() } else { 0.5f64.to_le_bytes() });
            }
            b.push(3);
            for i in [0i32, 1, 2] {
                b.extend(if big { i.to_be_bytes() } else { i.to_le_bytes() });
            }
            let m = parse_ply(&b, "t.ply").unwrap();
            assert_eq!(m.mesh.positions[1], DVec3::new(1.0, 0.0, 0.5), "{format}");
            assert_eq!(m.mesh.face(0), &[0, 1, 2]);
            b.extend([0, 0]);
            let m = parse_ply(&b, "t.ply").unwrap();
            assert_eq!(m.warnings[0].to_string(), "ignored 2 bytes after the end of the data");
            b.truncate(b.len() - 5);
            assert_eq!(err(&b), "t.ply: found end of file, expected an int (item 2 of list vertex_indices of face 0)");
        }
    }

    #[test]
    fn errors_name_the_element_and_position() {
        let body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert_eq!(
            err(format!("{HEAD}{}", body.replace("1 0 0", "1 x 0")).as_bytes()),
            r#"t.ply:12:3: found "x", expected a float (property y of vertex 1 of 3)"#
        );
        assert_eq!(
            err(format!("{HEAD}{}", body.replace("3 0 1 2", "3 0 1 -1")).as_bytes()),
            r#"t.ply:14:7: found "-1", expected a vertex index below 3 (corner 2 of face 0)"#
        );
        assert_eq!(
            err(format!("{HEAD}{}", body.replace("3 0 1 2", "300 0")).as_bytes()),
            r#"t.ply:14:1: found "300", expected a uchar (the length of list vertex_indices of face 0)"#
        );
        assert_eq!(
            err(format!("{HEAD}0 0 0\n1 0 0\n0 1").as_bytes()),
            "t.ply:13:4: found end of file, expected a float (property z of vertex 2 of 3)"
        );
        assert_eq!(err(b"plx\n"), r#"t.ply:1:1: found "plx", expected ply (the first line of a PLY file)"#);
        assert_eq!(err(b"ply\nformat ascii 1.0\n"), "t.ply:3:1: found end of file, expected end_header");
        assert_eq!(
            err(b"ply\nformat text 1.0\nend_header\n"),
            r#"t.ply:2:8: found "text", expected ascii, binary_little_endian or binary_big_endian"#
        );
        assert_eq!(
            err(HEAD.replace("property float y", "property flot y").as_bytes()),
            r#"t.ply:6:10: found "flot", expected a type: char, uchar, short, ushort, int, uint, float or double"#
        );
        assert_eq!(
            err(HEAD.replace("property float z\n", "").as_bytes()),
            r#"t.ply:4:9: found "vertex", expected an element with scalar properties x, y and z (z is missing)"#
        );
        assert_eq!(
            err(HEAD.replace("element vertex 3", "element vertex many").as_bytes()),
            r#"t.ply:4:16: found "many", expected a non-negative element count"#
        );
    }

    #[test]
    fn huge_counts_do_not_allocate() {
        let text = HEAD.replace("element vertex 3", "element vertex 4000000000").replace("list uchar", "list uint");
        let text = text.replace("ascii", "binary_little_endian");
        assert_eq!(
            err(text.as_bytes()),
            "t.ply: found end of file, expected a float (property x of vertex 0 of 4000000000)"
        );
    }
}
