//! Reading mesh files: [`load_mesh`] picks the reader by extension; [`read_mesh`] reads a
//! stream. The readers themselves are [`read_obj`](super::read_obj),
//! [`read_glb`](super::read_glb), [`read_ply`](super::read_ply) and
//! [`read_stl`](super::read_stl).

use std::borrow::Cow;
use std::fmt;
use std::io::Read;
use std::path::Path;

use splinekit::PolyMesh;
use splinekit::subdiv::Creases;

use super::{MeshFormat, MeshIoError, MeshIoErrorKind};
use crate::swp::SourcePos;

/// At most this many warnings of one kind are kept; the rest are counted in one
/// [`ReadWarningKind::More`] warning.
pub const MAX_WARNINGS: usize = 100;

/// Longest statement text (in characters) quoted in a warning.
const MAX_WARNING_CHARS: usize = 60;

/// A mesh read from a file, with what the reader skipped or dropped.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedMesh {
    /// The mesh. Face indices are in range (readers check them); the topology is not
    /// checked (see [`TopologyReport`](splinekit::mesh::TopologyReport)).
    pub mesh: PolyMesh,
    /// What was skipped or dropped, in file order.
    pub warnings: Vec<ReadWarning>,
    /// Sharp and semi-sharp edges and vertices: an OBJ file's crease tags (see
    /// [`read_creases`](super::read_creases)); none for the other formats.
    pub creases: Creases,
    /// The subdivision options an OBJ file's tags ask for (see [`SubdivTags`](super::SubdivTags));
    /// none for the other formats.
    pub subdiv_tags: super::SubdivTags,
}

/// Something a reader skipped or dropped without failing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadWarning {
    /// The 1-based line it is about, or 0 (binary data, or the whole file).
    pub line: usize,
    /// What happened.
    pub kind: ReadWarningKind,
}

/// What a reader skipped or dropped. New variants may be added.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ReadWarningKind {
    /// A statement the reader does not know (OBJ), skipped. `text` is the line, shortened.
    UnknownStatement {
        /// The line's text (at most 60 characters, then `…`).
        text: String,
    },
    /// An OBJ tag line (`t NAME …`) other than `crease`, `corner`, `interpolateboundary`,
    /// `creasemethod` and `smoothtriangles`, skipped.
    SkippedTag {
        /// The tag's name.
        name: String,
    },
    /// More warnings than [`MAX_WARNINGS`] of the previous kind were found; they are only
    /// counted.
    More {
        /// How many were not kept.
        count: usize,
    },
    /// A face-varying attribute (texture coordinates or normals) was dropped because some
    /// faces have it and others do not.
    AttributeDropped {
        /// `texture coordinates` or `normals`.
        attribute: &'static str,
        /// Faces with the attribute at every corner.
        faces_with: usize,
        /// Faces without it at some corner.
        faces_without: usize,
        /// Line of the first face without it.
        first_without: usize,
    },
    /// Vertex colours were dropped because some vertices have them and others do not.
    ColorsDropped {
        /// Vertices with a colour.
        vertices_with: usize,
        /// Vertices without.
        vertices_without: usize,
        /// Line of the first vertex without one.
        first_without: usize,
    },
    /// Bytes after the end of the data (binary PLY or STL, or after the length in a `.glb`
    /// header), ignored.
    TrailingBytes {
        /// How many.
        count: usize,
    },
    /// A binary glTF mesh primitive that is not made of triangles (points or lines), or has no
    /// positions, skipped.
    SkippedPrimitive {
        /// Which, like `meshes[0].primitives[1] (mesh "Cube")`.
        primitive: String,
        /// Why, like `its mode is LINES, not triangles`.
        reason: String,
    },
    /// OBJ statements with geometry the reader does not read (points, lines, free-form curves
    /// and surfaces), skipped: one warning for each keyword, on the line of its first statement.
    SkippedStatements {
        /// The keyword, like `l` or `surf`.
        keyword: &'static str,
        /// How many statements.
        count: usize,
        /// What is not read, like `lines are not read`.
        reason: &'static str,
    },
    /// A PLY element other than `vertex`, `face` and `tristrips` (or a second one of those),
    /// skipped with all its data.
    SkippedElement {
        /// The element's name, like `edge`.
        name: String,
        /// How many the file has.
        count: usize,
    },
    /// A property of a PLY element that is read, skipped: for `vertex` anything but the
    /// position, normal, colour and texture coordinates; for `face` and `tristrips` anything
    /// but the vertex indices.
    SkippedProperty {
        /// The element's name.
        element: String,
        /// The property's name.
        name: String,
    },
    /// A binary glTF vertex attribute was dropped because some mesh primitives have it and
    /// others do not.
    PrimitiveAttributeDropped {
        /// `normals`, `texture coordinates` or `vertex colours`.
        attribute: &'static str,
        /// Primitives with the attribute (a mesh used by several nodes counts once per node).
        primitives_with: usize,
        /// Primitives without it.
        primitives_without: usize,
        /// The first primitive without it, like `meshes[1].primitives[0]`.
        first_without: String,
    },
}

impl fmt::Display for ReadWarning {
    /// `line N: message`, or just the message when there is no line.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line > 0 {
            write!(f, "line {}: ", self.line)?;
        }
        match &self.kind {
            ReadWarningKind::UnknownStatement { text } => write!(f, "skipped unknown statement {text:?}"),
            ReadWarningKind::SkippedTag { name } => {
                write!(
                    f,
                    "skipped tag {name:?} (only crease, corner, interpolateboundary, creasemethod and smoothtriangles are read)"
                )
            }
            ReadWarningKind::More { count } => write!(f, "… and {count} more warnings like the previous one"),
            ReadWarningKind::AttributeDropped { attribute, faces_with, faces_without, first_without } => write!(
                f,
                "dropped the {attribute}: {faces_with} faces have them, {faces_without} do not (the first at line {first_without})"
            ),
            ReadWarningKind::ColorsDropped { vertices_with, vertices_without, first_without } => write!(
                f,
                "dropped the vertex colours: {vertices_with} vertices have one, {vertices_without} do not (the first at line {first_without})"
            ),
            ReadWarningKind::TrailingBytes { count } => write!(f, "ignored {count} bytes after the end of the data"),
            ReadWarningKind::SkippedPrimitive { primitive, reason } => write!(f, "skipped {primitive}: {reason}"),
            ReadWarningKind::SkippedStatements { keyword, count, reason } => {
                let (s, first) = if *count == 1 { ("", "") } else { ("s", ", the first on this line") };
                write!(f, "skipped {count} {keyword:?} statement{s}{first} ({reason})")
            }
            ReadWarningKind::SkippedElement { name, count } => write!(
                f,
                "skipped element {name:?} ({count} in the file; the elements read are vertex, face and tristrips)"
            ),
            ReadWarningKind::SkippedProperty { element, name } => {
                write!(f, "skipped property {name:?} of element {element:?}")
            }
            ReadWarningKind::PrimitiveAttributeDropped {
                attribute,
                primitives_with,
                primitives_without,
                first_without,
            } => write!(
                f,
                "dropped the {attribute}: {primitives_with} mesh primitives have them, {primitives_without} do not (the first is {first_without})"
            ),
        }
    }
}

/// Collects warnings, keeping at most [`MAX_WARNINGS`] unknown statements.
#[derive(Default)]
pub(crate) struct Warnings {
    list: Vec<ReadWarning>,
    unknown: usize,
}

impl Warnings {
    /// An unknown statement on `line` (its raw bytes).
    pub(crate) fn unknown(&mut self, line: usize, text: &[u8]) {
        self.unknown += 1;
        if self.unknown <= MAX_WARNINGS {
            self.list.push(ReadWarning { line, kind: ReadWarningKind::UnknownStatement { text: shorten(text) } });
        }
    }

    pub(crate) fn push(&mut self, line: usize, kind: ReadWarningKind) {
        self.list.push(ReadWarning { line, kind });
    }

    /// A warning about `line`, before the warnings about later lines.
    pub(crate) fn insert(&mut self, line: usize, kind: ReadWarningKind) {
        let at = self.list.iter().position(|w| w.line > line).unwrap_or(self.list.len());
        self.list.insert(at, ReadWarning { line, kind });
    }

    pub(crate) fn finish(mut self) -> Vec<ReadWarning> {
        if self.unknown > MAX_WARNINGS {
            let count = self.unknown - MAX_WARNINGS;
            // After the last kept unknown-statement warning.
            let at = self
                .list
                .iter()
                .rposition(|w| matches!(w.kind, ReadWarningKind::UnknownStatement { .. }))
                .map_or(self.list.len(), |i| i + 1);
            self.list.insert(at, ReadWarning { line: 0, kind: ReadWarningKind::More { count } });
        }
        self.list
    }
}

/// The trimmed text of a line for a message, lossily decoded and shortened.
fn shorten(text: &[u8]) -> String {
    let text = String::from_utf8_lossy(text);
    let text = text.trim();
    if text.chars().count() > MAX_WARNING_CHARS {
        let mut s: String = text.chars().take(MAX_WARNING_CHARS).collect();
        s.push('…');
        s
    } else {
        text.to_owned()
    }
}

/// The 1-based column (in characters) of byte `offset` of `line`.
pub(crate) fn column(line: &[u8], offset: usize) -> usize {
    let head = &line[..offset.min(line.len())];
    if head.is_ascii() { head.len() + 1 } else { String::from_utf8_lossy(head).chars().count() + 1 }
}

/// An error at byte `offset` of `line` (number `line_no`).
pub(crate) fn error_at(origin: &str, line_no: usize, line: &[u8], offset: usize, kind: MeshIoErrorKind) -> MeshIoError {
    MeshIoError::at(origin, SourcePos::new(line_no, column(line, offset)), kind)
}

/// "found TOKEN, expected WHAT" at byte `offset` of `line`.
pub(crate) fn unexpected(
    origin: &str,
    line_no: usize,
    line: &[u8],
    offset: usize,
    token: &[u8],
    expected: impl Into<String>,
) -> MeshIoError {
    let kind = if token.is_empty() {
        MeshIoErrorKind::UnexpectedEnd { found: "end of line", expected: expected.into() }
    } else {
        MeshIoErrorKind::UnexpectedToken {
            found: String::from_utf8_lossy(token).into_owned(),
            expected: expected.into(),
        }
    };
    error_at(origin, line_no, line, offset, kind)
}

/// An error about the file as a whole or its binary data (no position).
pub(crate) fn error_in(origin: &str, kind: MeshIoErrorKind) -> MeshIoError {
    MeshIoError::new(kind).with_origin(Path::new(origin))
}

/// "found end of file, expected WHAT" for binary data.
pub(crate) fn truncated(origin: &str, expected: String) -> MeshIoError {
    error_in(origin, MeshIoErrorKind::UnexpectedEnd { found: "end of file", expected })
}

/// Reads all of `reader`.
pub(crate) fn read_all<R: Read>(mut reader: R, origin: &str) -> Result<Vec<u8>, MeshIoError> {
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes).map_err(|error| error_in(origin, MeshIoErrorKind::Io { action: "read", error }))?;
    Ok(bytes)
}

/// The next whitespace-separated token of `line` at or after `*pos`, with its byte offset;
/// `None` at the end of the line or at a `#` that starts a token (a comment).
pub(crate) fn next_token<'a>(line: &'a [u8], pos: &mut usize) -> Option<(usize, &'a [u8])> {
    let mut i = *pos;
    while i < line.len() && line[i].is_ascii_whitespace() {
        i += 1;
    }
    if i == line.len() || line[i] == b'#' {
        *pos = line.len();
        return None;
    }
    let start = i;
    while i < line.len() && !line[i].is_ascii_whitespace() {
        i += 1;
    }
    *pos = i;
    Some((start, &line[start..i]))
}

/// Parses a decimal number (anything `f64::from_str` accepts, including `inf` and `nan`).
pub(crate) fn parse_f64(token: &[u8]) -> Option<f64> {
    // `nan`, `inf` and numbers that overflow are not coordinates
    std::str::from_utf8(token).ok()?.parse().ok().filter(|v: &f64| v.is_finite())
}

/// Parses an optionally signed decimal integer.
pub(crate) fn parse_i64(token: &[u8]) -> Option<i64> {
    let (negative, digits) = match token.first()? {
        b'-' => (true, &token[1..]),
        b'+' => (false, &token[1..]),
        _ => (false, token),
    };
    if digits.is_empty() || digits.len() > 18 {
        return std::str::from_utf8(token).ok()?.parse().ok();
    }
    let mut n: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        n = n * 10 + i64::from(d - b'0');
    }
    Some(if negative { -n } else { n })
}

/// Text with a UTF-16 byte-order mark (little or big endian), decoded to UTF-8 (unpaired
/// surrogates and an odd last byte become U+FFFD); `None` without that mark.
pub(crate) fn utf16_decoded(bytes: &[u8]) -> Option<Vec<u8>> {
    let big = match bytes.get(..2)? {
        [0xFF, 0xFE] => false,
        [0xFE, 0xFF] => true,
        _ => return None,
    };
    let units = bytes[2..].chunks(2).map(|c| match *c {
        [a, b] if big => u16::from_be_bytes([a, b]),
        [a, b] => u16::from_le_bytes([a, b]),
        _ => 0xFFFD,
    });
    let text: String = char::decode_utf16(units).map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER)).collect();
    Some(text.into_bytes())
}

/// Whether `bytes` look like UTF-16 text without a byte-order mark: in the first kilobyte,
/// NUL in at least half of the bytes at even (or odd) offsets, as in the high bytes of ASCII
/// characters, and in at most an eighth as many at the others.
pub(crate) fn looks_like_utf16(bytes: &[u8]) -> bool {
    let sample = &bytes[..bytes.len().min(1024) & !1];
    let mut zeros = [0usize; 2];
    for (i, &b) in sample.iter().enumerate() {
        zeros[i % 2] += usize::from(b == 0);
    }
    let (most, least) = (zeros[0].max(zeros[1]), zeros[0].min(zeros[1]));
    most > 0 && 4 * most >= sample.len() && 8 * least <= most
}

/// The bytes of a text file, ready for [`lines`]: UTF-16 with a byte-order mark decoded to
/// UTF-8, anything else as it is (a UTF-8 byte-order mark is skipped by [`lines`]).
///
/// # Errors
///
/// [`Utf16WithoutBom`](MeshIoErrorKind::Utf16WithoutBom) for text that looks like UTF-16 but
/// has no byte-order mark.
pub(crate) fn text<'a>(bytes: &'a [u8], origin: &str) -> Result<Cow<'a, [u8]>, MeshIoError> {
    if let Some(decoded) = utf16_decoded(bytes) {
        return Ok(Cow::Owned(decoded));
    }
    if looks_like_utf16(bytes) {
        return Err(error_in(origin, MeshIoErrorKind::Utf16WithoutBom));
    }
    Ok(Cow::Borrowed(bytes))
}

/// The triangles of the triangle strip `strip`, to `emit`: triangle k, of the corners a, b, c
/// at k, k + 1, k + 2, is (a, b, c) for even k and (a, c, b) for odd k, so that all face the
/// way the first does. Triangles with a repeated vertex (which stitch strips together) are
/// left out.
pub(crate) fn strip_triangles(strip: &[u32], mut emit: impl FnMut([u32; 3])) {
    for (k, w) in strip.windows(3).enumerate() {
        let t = if k % 2 == 0 { [w[0], w[1], w[2]] } else { [w[0], w[2], w[1]] };
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            emit(t);
        }
    }
}

/// The lines of `bytes` (split at LF, a trailing CR removed), numbered from 1; a UTF-8 byte
/// order mark at the start is skipped.
pub(crate) fn lines(bytes: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let end_newline = bytes.last() == Some(&b'\n');
    let n = bytes.len() - usize::from(end_newline);
    bytes[..n].split(|&b| b == b'\n').map(|l| l.strip_suffix(b"\r").unwrap_or(l)).enumerate().map(|(i, l)| (i + 1, l))
}

/// Reads the mesh file at `path`, choosing the reader by its extension: `.obj`
/// ([`read_obj`](super::read_obj)), `.glb` ([`read_glb`](super::read_glb)), `.ply`
/// ([`read_ply`](super::read_ply)) or `.stl` ([`read_stl`](super::read_stl)), in any case.
///
/// # Errors
///
/// A [`MeshIoError`] naming the path: an unknown extension, a file that cannot be read, or
/// the reader's error with line and column (text formats) or what is wrong where (binary
/// formats; for `.glb` a JSON path such as `meshes[0].primitives[1].indices`).
///
/// ```
/// # let dir = std::env::temp_dir().join(format!("splinekit-load-doc-{}", std::process::id()));
/// # std::fs::create_dir_all(&dir)?;
/// let path = dir.join("quad.obj");
/// std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")?;
/// let loaded = splinekit_io::mesh::load_mesh(&path)?;
/// assert_eq!((loaded.mesh.num_vertices(), loaded.mesh.num_faces()), (4, 1));
///
/// std::fs::write(&path, "v 0 0 0\nf 1 2 3\n")?;
/// let err = splinekit_io::mesh::load_mesh(&path).unwrap_err();
/// assert!(err.to_string().ends_with(
///     "quad.obj:2:5: found \"2\", expected a vertex index from 1 to 1 or from -1 to -1"
/// ));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn load_mesh(path: impl AsRef<Path>) -> Result<LoadedMesh, MeshIoError> {
    let path = path.as_ref();
    let origin = path.display().to_string();
    let format = readable_format(path).map_err(|kind| error_in(&origin, kind))?;
    let bytes =
        std::fs::read(path).map_err(|error| error_in(&origin, MeshIoErrorKind::Io { action: "read", error }))?;
    parse_mesh(&bytes, format, &origin)
}

/// The readable format named by the extension of `path`.
fn readable_format(path: &Path) -> Result<MeshFormat, MeshIoErrorKind> {
    let expected = "a mesh file ending in .obj, .glb, .ply or .stl";
    match MeshFormat::from_path(path) {
        Some(format) => Ok(format),
        None => Err(MeshIoErrorKind::UnexpectedToken {
            found: path
                .extension()
                .map_or_else(|| String::from("no extension"), |e| format!(".{}", e.to_string_lossy())),
            expected: expected.into(),
        }),
    }
}

/// Reads a mesh in `format` from `reader`; `origin` names it in errors.
///
/// # Errors
///
/// As [`load_mesh`].
pub fn read_mesh<R: Read>(reader: R, format: MeshFormat, origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let bytes = read_all(reader, origin)?;
    parse_mesh(&bytes, format, origin)
}

/// Parses `bytes` in `format`.
fn parse_mesh(bytes: &[u8], format: MeshFormat, origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let loaded = match format {
        MeshFormat::Obj => super::obj_read::parse_obj(bytes, origin),
        MeshFormat::Ply => super::ply_read::parse_ply(bytes, origin),
        MeshFormat::Stl => super::stl_read::parse_stl(bytes, origin),
        MeshFormat::Glb => super::glb_read::parse_glb(bytes, origin),
    }?;
    // binary floats can be NaN or infinite; nothing downstream can use such a vertex, nor
    // such a normal, texture coordinate or colour (the writers refuse them: issue #38)
    fn first_bad<const N: usize>(
        values: impl Iterator<Item = [f64; N]>,
        names: [&'static str; N],
    ) -> Option<MeshIoErrorKind> {
        values.enumerate().find_map(|(vertex, v)| {
            let k = (0..N).find(|&k| !v[k].is_finite())?;
            Some(MeshIoErrorKind::NonFiniteVertex { vertex, axis: names[k], value: v[k] })
        })
    }
    let m = &loaded.mesh;
    let normals = m.normals.iter().flat_map(|n| &n.values);
    let uvs = m.uvs.iter().flat_map(|t| &t.values);
    let bad = first_bad(m.positions.iter().map(|p| p.to_array()), ["x", "y", "z"])
        .or_else(|| first_bad(normals.map(|n| n.to_array()), ["normal x", "normal y", "normal z"]))
        .or_else(|| first_bad(uvs.map(|t| t.to_array()), ["u", "v"]))
        .or_else(|| first_bad(m.colors.iter().map(|c| c.to_array()), ["red", "green", "blue"]));
    match bad {
        Some(kind) => Err(error_in(origin, kind)),
        None => Ok(loaded),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_and_lines() {
        let line = b"  v 1.5\t-2 # c";
        let mut pos = 0;
        assert_eq!(next_token(line, &mut pos), Some((2, &b"v"[..])));
        assert_eq!(next_token(line, &mut pos), Some((4, &b"1.5"[..])));
        assert_eq!(next_token(line, &mut pos), Some((8, &b"-2"[..])));
        assert_eq!(next_token(line, &mut pos), None);
        let l: Vec<_> = lines(b"\xEF\xBB\xBFa\r\n\r\nb").collect();
        assert_eq!(l, vec![(1, &b"a"[..]), (2, &b""[..]), (3, &b"b"[..])]);
        assert_eq!(lines(b"a\n").count(), 1);
        assert_eq!(lines(b"").count(), 1);
        assert_eq!(lines(b"\n").count(), 1);
        assert_eq!(column("aé b".as_bytes(), 4), 4);
    }

    #[test]
    fn integers() {
        assert_eq!(parse_i64(b"-12"), Some(-12));
        assert_eq!(parse_i64(b"+7"), Some(7));
        assert_eq!(parse_i64(b"1x"), None);
        assert_eq!(parse_i64(b"-"), None);
        assert_eq!(parse_i64(b"123456789012345678901"), None);
        assert_eq!(parse_i64(b"1234567890123456789"), Some(1_234_567_890_123_456_789));
    }

    #[test]
    fn warnings_are_capped() {
        let mut w = Warnings::default();
        for i in 0..MAX_WARNINGS + 5 {
            w.unknown(i + 1, b"<html>");
        }
        w.push(7, ReadWarningKind::TrailingBytes { count: 3 });
        let list = w.finish();
        assert_eq!(list.len(), MAX_WARNINGS + 2);
        assert_eq!(list[MAX_WARNINGS].kind, ReadWarningKind::More { count: 5 });
        assert_eq!(list[0].to_string(), "line 1: skipped unknown statement \"<html>\"");
    }
}
