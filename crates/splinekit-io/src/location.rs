//! Where in a file a problem is: the one location type of SWP and mesh errors
//! ([`SwpError`](crate::SwpError), [`MeshIoError`](crate::MeshIoError)).

use std::fmt;

/// A 1-based position in a source text: line, and column counted in characters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SourcePos {
    /// Line number, starting at 1. Lines end at LF (a CRLF counts as one line end).
    pub line: usize,
    /// Column number, starting at 1, counted in Unicode scalar values (`char`s).
    pub column: usize,
}

impl SourcePos {
    /// Creates a position from a 1-based line and column.
    #[must_use]
    pub const fn new(line: usize, column: usize) -> Self {
        Self { line, column }
    }
}

impl Default for SourcePos {
    /// Line 1, column 1: the start of a text.
    fn default() -> Self {
        Self::new(1, 1)
    }
}

impl fmt::Display for SourcePos {
    /// Formats as `LINE:COL`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// Where in a file's content a problem is.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Position {
    /// A line and column of a text file (SWP, OBJ, ASCII PLY and STL, annotated OBJ headers).
    Text(SourcePos),
    /// A place in the structure of a binary file, which has no lines: a glTF JSON path such
    /// as `meshes[0].primitives[1].indices (accessors[4])`, or a place in the binary layout
    /// such as `chunk 1 at byte 1020`.
    Structure(String),
}

impl fmt::Display for Position {
    /// Formats as `LINE:COL`, or the structure path as it is.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Text(pos) => pos.fmt(f),
            Self::Structure(path) => f.write_str(path),
        }
    }
}

/// The file an error is about and, if known, the place in it.
///
/// It displays as `FILE:LINE:COL` for a text position, `FILE: PATH` for a place in a binary
/// file's structure, and `FILE` without a position; without a file (a writer called on a
/// plain stream, a text parsed under an empty name) just the position, or nothing.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub struct Location {
    /// The path read or written, or the name given to a parser; may be empty.
    pub origin: String,
    /// Where in the file, if the problem has a place.
    pub position: Option<Position>,
}

impl Location {
    /// A location in `origin` at `position`.
    #[must_use]
    pub fn new(origin: impl Into<String>, position: Option<Position>) -> Self {
        Self { origin: origin.into(), position }
    }

    /// The text position, if the location is a line and column.
    #[must_use]
    pub fn pos(&self) -> Option<SourcePos> {
        match self.position {
            Some(Position::Text(pos)) => Some(pos),
            _ => None,
        }
    }

    /// Whether the location says nothing (no file, no position).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.origin.is_empty() && self.position.is_none()
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.origin)?;
        match &self.position {
            None => Ok(()),
            Some(Position::Text(pos)) if self.origin.is_empty() => write!(f, "{pos}"),
            Some(Position::Text(pos)) => write!(f, ":{pos}"),
            Some(Position::Structure(path)) if self.origin.is_empty() => f.write_str(path),
            Some(Position::Structure(path)) => write!(f, ": {path}"),
        }
    }
}

/// `LOCATION: ` before a message, or nothing for an empty location.
pub(crate) struct Prefix<'a>(pub(crate) &'a Location);

impl fmt::Display for Prefix<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() { Ok(()) } else { write!(f, "{}: ", self.0) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_combination_displays_as_documented() {
        let text = Some(Position::Text(SourcePos::new(3, 4)));
        let path = Some(Position::Structure("meshes[0]".to_owned()));
        let show = |origin: &str, position: &Option<Position>| Location::new(origin, position.clone()).to_string();
        assert_eq!(show("a.obj", &text), "a.obj:3:4");
        assert_eq!(show("a.glb", &path), "a.glb: meshes[0]");
        assert_eq!(show("a.obj", &None), "a.obj");
        assert_eq!(show("", &text), "3:4");
        assert_eq!(show("", &path), "meshes[0]");
        assert_eq!(show("", &None), "");
        assert_eq!(Prefix(&Location::default()).to_string(), "");
        assert_eq!(Prefix(&Location::new("a.obj", text)).to_string(), "a.obj:3:4: ");
    }
}
