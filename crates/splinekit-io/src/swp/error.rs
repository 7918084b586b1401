//! The SWP error type.

use std::path::{Path, PathBuf};

use super::{SourcePos, SwpClause};
use crate::location::{Location, Position, Prefix};

/// The keywords listed in "unknown keyword" messages, in the order they are documented.
pub(crate) const KEYWORD_LIST: &str = "bez2, bsp2, bez3, bsp3, cr2, cr3, her2, her3, tcb2, tcb3, bo2, bo3, bezn2, bezn3, nurbs2, nurbs3, circ, helix, trefoil, srev or gcyl";

/// Longest token text (in characters) quoted in a message before it is shortened with `…`.
const MAX_QUOTED_CHARS: usize = 40;

/// An error from reading or parsing an SWP file.
///
/// It carries the origin (the file name given to [`parse`](super::SwpDocument::parse) or the
/// path given to [`read`](super::SwpDocument::read)), the 1-based line and column where the
/// problem is, and a structured [`SwpErrorKind`].
///
/// It displays as `FILE:LINE:COL: found <what was found>, expected <what>`, for example
/// `core.swp:3:7: found "1.2.3", expected a number (x coordinate of point 2 of bsp2 curve "profile")`.
/// Errors without a position (I/O errors) display as `FILE: <message>`.
#[derive(Debug, thiserror::Error)]
#[error("{}{kind}", Prefix(location))]
pub struct SwpError {
    location: Location,
    kind: SwpErrorKind,
}

impl SwpError {
    /// An error at a position in `origin`.
    pub(crate) fn at(origin: &str, pos: SourcePos, kind: SwpErrorKind) -> Self {
        Self { location: Location::new(origin, Some(Position::Text(pos))), kind }
    }

    /// A file could not be read.
    pub(crate) fn io(path: &Path, error: std::io::Error) -> Self {
        let location = Location::new(path.display().to_string(), None);
        Self { location, kind: SwpErrorKind::Io { path: path.to_owned(), error } }
    }

    /// `bytes[valid_up_to]` starts an invalid UTF-8 sequence.
    pub(crate) fn invalid_utf8(origin: &str, bytes: &[u8], valid_up_to: usize) -> Self {
        let valid = bytes.get(..valid_up_to).unwrap_or_default();
        // `valid` is valid UTF-8 by construction; fall back to the start if it is not.
        let text = std::str::from_utf8(valid).unwrap_or_default();
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let line = 1 + text.matches('\n').count();
        let last_line = text.rsplit('\n').next().unwrap_or_default();
        let column = 1 + last_line.chars().count();
        Self::at(
            origin,
            SourcePos::new(line, column),
            SwpErrorKind::InvalidUtf8 { byte: bytes.get(valid_up_to).copied().unwrap_or_default() },
        )
    }

    /// The name of the file (or other text) the error is about.
    #[must_use]
    pub fn origin(&self) -> &str {
        &self.location.origin
    }

    /// The file and the place in it.
    #[must_use]
    pub fn location(&self) -> &Location {
        &self.location
    }

    /// The 1-based line of the error, or 0 if the error has no position (I/O errors).
    #[must_use]
    pub fn line(&self) -> usize {
        self.location.pos().map_or(0, |p| p.line)
    }

    /// The 1-based column of the error, counted in characters, or 0 if the error has no
    /// position (I/O errors).
    #[must_use]
    pub fn column(&self) -> usize {
        self.location.pos().map_or(0, |p| p.column)
    }

    /// The position of the error, or `None` for I/O errors.
    #[must_use]
    pub fn pos(&self) -> Option<SourcePos> {
        self.location.pos()
    }

    /// What went wrong.
    #[must_use]
    pub fn kind(&self) -> &SwpErrorKind {
        &self.kind
    }
}

/// What went wrong while reading an SWP file.
///
/// Each variant displays as `found <…>, expected <…>` (I/O errors as `cannot read file: <OS
/// message>`). Fields holding token text keep it unquoted and unshortened; the message quotes
/// it and shortens long tokens. New variants may be added.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SwpErrorKind {
    /// A token that is not a keyword stood where an object must start.
    #[error("found {}, expected a keyword ({}){}", quote(found), KEYWORD_LIST, case_hint(found))]
    UnknownKeyword {
        /// The token found.
        found: String,
    },
    /// A token is not a valid number or integer, or its value is out of range (a negative
    /// radius, a negative point count).
    #[error("found {}, expected {expected}", quote(found))]
    InvalidNumber {
        /// The token found.
        found: String,
        /// What was expected, with context (which coordinate of which point of which curve).
        expected: String,
    },
    /// STEPS is not in `1..=MAX_STEPS`.
    #[error("found {}, expected a step count from 1 to {} for {object}", quote(found), super::MAX_STEPS)]
    StepsOutOfRange {
        /// The token found.
        found: String,
        /// The object whose steps these are, like `bez2 curve #0`.
        object: String,
    },
    /// A token that the grammar does not allow here, such as a missing `]` or `[`, or `[` as
    /// a name.
    #[error("found {}, expected {expected}", quote(found))]
    UnexpectedToken {
        /// The token found.
        found: String,
        /// What was expected.
        expected: String,
    },
    /// The file ended in the middle of an object (but not between points: see
    /// [`MissingPoints`](Self::MissingPoints)). The position is just after the last token.
    #[error("found end of file, expected {expected}")]
    UnexpectedEnd {
        /// What was expected.
        expected: String,
    },
    /// The file ended before all NPOINTS points (or Hermite pairs) were given. The position is
    /// just after the last token.
    #[error(
        "found end of file after {found} {}, expected {expected} {} for {curve}",
        unit(*.pairs, *.found), unit(*.pairs, *.expected)
    )]
    MissingPoints {
        /// The curve, like `bez2 curve "profile"`.
        curve: String,
        /// NPOINTS as written.
        expected: u64,
        /// How many complete points (or pairs) were read.
        found: u64,
        /// Whether the counts are Hermite point-tangent pairs.
        pairs: bool,
    },
    /// NPOINTS breaks the kind's point-count rule. Points at the NPOINTS token.
    #[error("found {found} {}, expected {} for {curve}", unit(.keyword.starts_with("her"), *.found), count_rule(.keyword, *.closed))]
    PointCount {
        /// The curve, like `bez2 curve "profile"`.
        curve: String,
        /// The curve's keyword, like `bez2`.
        keyword: &'static str,
        /// Whether the curve has the `closed` option.
        closed: bool,
        /// NPOINTS as written.
        found: u64,
    },
    /// NPOINTS breaks a point-count rule that depends on more than the keyword: a Bézier curve
    /// of any degree's 2 to 65 points, or a NURBS's degree + 1 and more. Points at the NPOINTS
    /// token.
    #[error("found {found} {}, expected {rule} for {curve}", unit(false, *.found))]
    PointRange {
        /// The curve, like `nurbs2 curve "arc"`.
        curve: String,
        /// The rule, like `at least 4 points (degree + 1) and at most 1048576 of degree 3`.
        rule: String,
        /// NPOINTS as written.
        found: u64,
    },
    /// A surface refers to a name that is not a curve defined earlier in the file (or to `.`).
    #[error("found {}, expected {expected}", quote(name))]
    UndefinedName {
        /// The name used.
        name: String,
        /// What was expected, with the reason.
        expected: String,
    },
    /// A name is used a second time. Points at the second use.
    #[error(
        "found {} again, expected a new name ({} is already the name of the {what} at line {}, column {})",
        quote(name), quote(name), first.line, first.column
    )]
    DuplicateName {
        /// The name.
        name: String,
        /// The object that already has the name, like `bsp2 curve`.
        what: String,
        /// Where the object that first used the name starts.
        first: SourcePos,
    },
    /// A surface's profile is a 3D curve.
    #[error(
        "found 3D curve {} ({keyword}), expected a 2D curve (bez2, bsp2, cr2, her2, tcb2, bo2, bezn2, nurbs2 or circ) as the profile of {surface}",
        quote(name)
    )]
    ProfileNot2D {
        /// The profile's name.
        name: String,
        /// The profile's keyword, like `bsp3`.
        keyword: &'static str,
        /// The surface, like `gcyl surface "weird"`.
        surface: String,
    },
    /// A gcyl's scale or twist curve is a 3D curve.
    #[error(
        "found 3D curve {} ({keyword}), expected a 2D curve (bez2, bsp2, cr2, her2, tcb2, bo2, bezn2, nurbs2 or circ) as the {role} curve of {surface}",
        quote(name)
    )]
    CurveNot2D {
        /// The curve's name.
        name: String,
        /// The curve's keyword, like `bsp3`.
        keyword: &'static str,
        /// The clause that names the curve.
        role: SwpClause,
        /// The surface, like `gcyl surface "spring"`.
        surface: String,
    },
    /// A lathe's radius or height curve is a 3D curve.
    #[error(
        "found 3D curve {} ({keyword}), expected a 2D curve (bez2, bsp2, cr2, her2, tcb2 or bo2) as the {} curve of {surface}",
        quote(name), role.word()
    )]
    LatheCurveNot2D {
        /// The curve's name.
        name: String,
        /// The curve's keyword, like `bsp3`.
        keyword: &'static str,
        /// [`SwpCurveRole::Radius`](super::SwpCurveRole::Radius) or
        /// [`SwpCurveRole::Height`](super::SwpCurveRole::Height).
        role: super::SwpCurveRole,
        /// The surface, like `lathe surface "vase"`.
        surface: String,
    },
    /// An unknown curve option, an option on a kind it does not apply to, an option given
    /// twice, a bad `alpha` value, or a gcyl `scale` or `twist` clause given twice.
    #[error("found {}, expected {expected}", quote(found))]
    BadOption {
        /// The token found.
        found: String,
        /// What was expected.
        expected: String,
    },
    /// The file is not valid UTF-8. Points at the first bad byte.
    #[error("found invalid UTF-8 (byte 0x{byte:02x}), expected UTF-8 text")]
    InvalidUtf8 {
        /// The first byte of the invalid sequence.
        byte: u8,
    },
    /// The file could not be read.
    #[error("cannot read file: {error}")]
    Io {
        /// The path that could not be read.
        path: PathBuf,
        /// The operating system's error.
        error: std::io::Error,
    },
}

/// Quotes token text for a message, shortening long tokens.
pub(crate) fn quote(text: &str) -> String {
    if text.chars().count() > MAX_QUOTED_CHARS {
        let short: String = text.chars().take(MAX_QUOTED_CHARS).collect();
        format!("{short:?}…")
    } else {
        format!("{text:?}")
    }
}

/// A hint for keywords written in the wrong case.
fn case_hint(found: &str) -> &'static str {
    let lower = found.to_ascii_lowercase();
    if lower != found && super::parser::is_keyword(&lower) { " (keywords are lowercase)" } else { "" }
}

/// `point`/`points` or `point pair`/`point pairs`.
fn unit(pairs: bool, count: u64) -> &'static str {
    match (pairs, count == 1) {
        (false, true) => "point",
        (false, false) => "points",
        (true, true) => "point pair",
        (true, false) => "point pairs",
    }
}

/// The point-count rule of a keyword, as words.
fn count_rule(keyword: &str, closed: bool) -> &'static str {
    match (keyword.get(..3), closed) {
        (Some("bez"), false) => "3m+1 points with m ≥ 1 (4, 7, 10, …)",
        (Some("bez"), true) => "3m points with m ≥ 1 (3, 6, 9, …)",
        (Some("her"), _) => "at least 2 point pairs",
        (_, false) => "at least 4 points",
        (_, true) => "at least 3 points",
    }
}
