//! The error type of the mesh writers and of the spline-annotated OBJ header reader.

use splinekit::mesh::MeshError;

use super::atomic::WriteFileError;
use crate::location::{Location, Position, Prefix, SourcePos};

/// Longest token text (in characters) quoted in a message before it is shortened with `…`.
const MAX_QUOTED_CHARS: usize = 40;

/// An error from writing a mesh file or from reading a spline-annotated OBJ header.
///
/// It carries the origin (the path written or read, or the name given to a parser; empty when
/// a writer was called on a plain [`Write`](std::io::Write) stream), the 1-based line and
/// column for parse errors, and a structured [`MeshIoErrorKind`].
///
/// It displays as `ORIGIN:LINE:COL: <message>` for parse errors, `ORIGIN: <message>`
/// otherwise, and just `<message>` without an origin, for example
/// `lathe.obj:5:9: found "ture", expected true or false (closed, 1st value of the configs line)`
/// or `out/vase.glb: cannot create temporary file: No such file or directory (os error 2)`.
#[derive(Debug, thiserror::Error)]
#[error("{}{kind}", Prefix(location))]
pub struct MeshIoError {
    location: Location,
    kind: MeshIoErrorKind,
}

impl MeshIoError {
    /// An error without origin or position (the origin is filled in by path-level functions).
    pub(crate) fn new(kind: MeshIoErrorKind) -> Self {
        Self { location: Location::default(), kind }
    }

    /// An error at a position in `origin`.
    pub(crate) fn at(origin: &str, pos: SourcePos, kind: MeshIoErrorKind) -> Self {
        Self { location: Location::new(origin, Some(Position::Text(pos))), kind }
    }

    /// An error at a place in the structure of the binary file `origin` (see
    /// [`Position::Structure`]).
    pub(crate) fn in_structure(origin: &str, path: String, kind: MeshIoErrorKind) -> Self {
        Self { location: Location::new(origin, Some(Position::Structure(path))), kind }
    }

    /// An I/O error while writing to a stream.
    pub(crate) fn write(error: std::io::Error) -> Self {
        Self::new(MeshIoErrorKind::Io { action: "write", error })
    }

    /// Moves the position through `map` (for statements joined from several lines).
    pub(crate) fn map_pos(mut self, map: impl Fn(SourcePos) -> SourcePos) -> Self {
        if let Some(Position::Text(pos)) = &mut self.location.position {
            *pos = map(*pos);
        }
        self
    }

    /// Sets the origin if the error has none yet.
    pub(crate) fn with_origin(mut self, origin: &std::path::Path) -> Self {
        if self.location.origin.is_empty() {
            self.location.origin = origin.display().to_string();
        }
        self
    }

    /// The path or name the error is about; empty for errors of a stream writer.
    #[must_use]
    pub fn origin(&self) -> &str {
        &self.location.origin
    }

    /// The file and the place in it.
    #[must_use]
    pub fn location(&self) -> &Location {
        &self.location
    }

    /// The 1-based line of a parse error, or 0 if the error has no position.
    #[must_use]
    pub fn line(&self) -> usize {
        self.location.pos().map_or(0, |p| p.line)
    }

    /// The 1-based column (in characters) of a parse error, or 0 if the error has no position.
    #[must_use]
    pub fn column(&self) -> usize {
        self.location.pos().map_or(0, |p| p.column)
    }

    /// The position of a parse error, or `None`.
    #[must_use]
    pub fn pos(&self) -> Option<SourcePos> {
        self.location.pos()
    }

    /// What went wrong.
    #[must_use]
    pub fn kind(&self) -> &MeshIoErrorKind {
        &self.kind
    }
}

impl From<WriteFileError> for MeshIoError {
    fn from(e: WriteFileError) -> Self {
        let location = Location::new(e.path().display().to_string(), None);
        let (action, error) = e.into_parts();
        Self { location, kind: MeshIoErrorKind::Io { action, error } }
    }
}

impl From<std::io::Error> for MeshIoError {
    /// An I/O error of a writer: [`Io`](MeshIoErrorKind::Io) with the action `write` and no
    /// origin (path-level functions fill it in). Lets `?` work on `Write` calls inside an
    /// [`atomic::write_file`](super::atomic::write_file) callback that returns `MeshIoError`.
    fn from(error: std::io::Error) -> Self {
        Self::write(error)
    }
}

/// What went wrong while writing a mesh or reading a spline-annotated OBJ header.
///
/// Messages are lowercase and say what was found and what was expected. New variants may be
/// added.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MeshIoErrorKind {
    /// A file or stream could not be read or written.
    #[error("cannot {action}: {error}")]
    Io {
        /// What was being done, like `write` or `create temporary file`.
        action: &'static str,
        /// The operating system's error.
        error: std::io::Error,
    },
    /// The mesh fails [`TriMesh::validate`](splinekit::mesh::TriMesh::validate); nothing is
    /// written.
    #[error("invalid mesh: {0}")]
    InvalidMesh(MeshError),
    /// A face-varying attribute to be written does not match the faces or holds a value that
    /// is not finite; nothing is written.
    #[error("invalid {attribute}: {problem}")]
    InvalidAttribute {
        /// `normals` or `UVs`.
        attribute: &'static str,
        /// What is wrong, naming the corner or value.
        problem: String,
    },
    /// A value or count does not fit the file format (a coordinate beyond the `f32` range, more
    /// than 2³² bytes in a `.glb`, more vertices than a PLY `int` index can address).
    #[error("{what} does not fit in {format}")]
    Unrepresentable {
        /// The format, like `binary STL`.
        format: &'static str,
        /// The value or count, like `x coordinate of vertex 7 (1e300)`.
        what: String,
    },
    /// A header value to be written would not read back (a non-finite number, or a tolerance
    /// or scale that is not positive).
    #[error("cannot write {what} = {value}, expected {expected}")]
    InvalidHeaderValue {
        /// The value, like `x coordinate of control point 2` or `scale`.
        what: String,
        /// The value.
        value: f64,
        /// What is allowed, like `a positive finite number`.
        expected: &'static str,
    },
    /// A token is not what the header grammar allows here (a malformed number or boolean, a
    /// missing `>>+<<` separator, an extra value).
    #[error("found {}, expected {expected}", quote(found))]
    UnexpectedToken {
        /// The token found.
        found: String,
        /// What was expected, with context (which value of which line).
        expected: String,
    },
    /// A line or the header ended where more was expected. The position is just after the
    /// last character of the line (or at the start of the line that ended the header).
    #[error("found {found}, expected {expected}")]
    UnexpectedEnd {
        /// `end of line` or `end of the comment header`.
        found: &'static str,
        /// What was expected.
        expected: String,
    },
    /// A vertex read from a file has a coordinate, normal, texture coordinate or colour that
    /// is NaN or infinite (binary files; text files report the token with its line and
    /// column instead).
    #[error("vertex {} has {axis} = {value}, expected a finite number", vertex + 1)]
    NonFiniteVertex {
        /// The vertex, from 0 (messages count from 1); for normals and texture coordinates,
        /// the index of the value (one per vertex in PLY and glb files).
        vertex: usize,
        /// `x`, `y` or `z`; `normal x`, `normal y` or `normal z`; `u` or `v`; `red`, `green`
        /// or `blue`.
        axis: &'static str,
        /// The value read.
        value: f64,
    },
    /// The header is not valid UTF-8. Points at the line.
    #[error("found invalid UTF-8, expected UTF-8 text")]
    InvalidUtf8,
    /// The file has NUL bytes in every other byte, as UTF-16 text has, but no byte-order mark
    /// to say which byte order (text files with a UTF-16 byte-order mark are decoded).
    #[error(
        "found text that looks like UTF-16 without a byte-order mark, expected UTF-8 (or UTF-16 with a byte-order mark)"
    )]
    Utf16WithoutBom,
    /// The file has face records but not one face came of them: every one was skipped or
    /// made only degenerate triangles.
    #[error("read no faces from {records}: {reason}")]
    NoFacesRead {
        /// The face records, like `element tristrips (2 strips)` or `3 free-form surfaces (surf)`.
        records: String,
        /// Why none gave a face, like `every triangle of the strips repeats a vertex`.
        reason: String,
    },
    /// A binary glTF file is malformed, or uses something the reader does not support (see
    /// [`read_glb`](super::read_glb)). Binary files have no lines: the error's
    /// [`Location`] holds a [`Position::Structure`] instead, such as the JSON path
    /// `meshes[0].primitives[1].indices (accessors[4])`, `chunk 1 at byte 1020`, or `JSON
    /// chunk line 1, column 57 (byte 76)`.
    #[error("{message}")]
    InvalidGltf {
        /// What is wrong, such as `found index 7 at element 5, expected an index below 4 (the
        /// count of POSITION)`.
        message: String,
    },
}

/// Quotes token text for a message, shortening long tokens.
fn quote(text: &str) -> String {
    if text.chars().count() > MAX_QUOTED_CHARS {
        let short: String = text.chars().take(MAX_QUOTED_CHARS).collect();
        format!("{short:?}…")
    } else {
        format!("{text:?}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_with_and_without_origin_and_position() {
        let kind = || MeshIoErrorKind::UnexpectedToken { found: "x".into(), expected: "a number".into() };
        assert_eq!(MeshIoError::new(kind()).to_string(), r#"found "x", expected a number"#);
        let e = MeshIoError::at("a.obj", SourcePos::new(3, 4), kind());
        assert_eq!(e.to_string(), r#"a.obj:3:4: found "x", expected a number"#);
        assert_eq!((e.line(), e.column(), e.origin()), (3, 4, "a.obj"));
        let e = MeshIoError::new(kind()).with_origin(std::path::Path::new("b.obj"));
        assert_eq!(e.to_string(), r#"b.obj: found "x", expected a number"#);
        assert_eq!(e.pos(), None);
    }
}
