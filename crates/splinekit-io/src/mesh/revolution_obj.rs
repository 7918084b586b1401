//! The spline-annotated OBJ files of the CS 4620 (Cornell, Fall 2015) spline tools.
//!
//! Those tools save a mesh as plain OBJ whose leading `#` comments describe the spline(s) that
//! generated it, so that the tool can load the spline again. There are two kinds.
//!
//! **Surface of revolution** (the interactive revolution tool):
//!
//! ```text
//! # This mesh is a Surface of Revolution: the comments below describe a Spline (cross-section) swept along
//! # an axis that generated this mesh.
//! #
//! # Configs: closed, epsilon, isBSpline, Scale, sliceTolerance
//! # true 0.1 false 0.5 0.3
//! #
//! # Cross-section Spline control points:
//! # 0.5 -1.0
//! # 1.0 0.0
//! # 0.5 1.0
//! v ...
//! ```
//!
//! **Sweep spline** (the older sweep tool; the meshes bundled in `data/obj/cs4620-splines/`):
//!
//! ```text
//! # This mesh is a "Sweep Spline": the comments below describe a Spline (cross-section) swept along
//! # another spline (swept-along) that generated this mesh.
//! #
//! # Cross-section: closed, epsilon >>+<< Swept-along: closed, epsilon >>+<< Scale of Cross-section
//! # true, 0.0558213 >>+<< true, 0.050699063 >>+<< 0.38264847
//! #
//! # Cross-section Spline control points:
//! # -1.0 -1.2246469E-16
//! # ...
//! #
//! # Swept-along Spline control points:
//! # -1.0 -1.2246469E-16
//! # ...
//! v ...
//! ```
//!
//! # Reading rules
//!
//! - Only the leading comment block is read: the lines before the first line that is neither
//!   blank nor a comment (`#`, possibly after spaces). A UTF-8 byte order mark at the start is
//!   skipped; LF and CRLF line ends both work. The mesh itself is left to an OBJ reader.
//! - The kind is recognised by a comment starting with `Configs:` (revolution) or with
//!   `Cross-section:` (sweep). A block with neither is not a spline header
//!   ([`SplineHeader::parse`] returns `None`). Other comment lines, like the two introductory
//!   sentences, are ignored.
//! - The values line is the comment after the `Configs:` / `Cross-section:` line. Its values are
//!   separated by whitespace (and, in the sweep kind, by commas and the `>>+<<` separators).
//!   Booleans are exactly `true` or `false`; numbers are decimal (`0.5`, `1.0E-4`, `-3`), finite,
//!   and the tolerances and the scale must be positive. No value may be missing or extra.
//! - Control points follow a `Cross-section Spline control points:` (or `Swept-along Spline
//!   control points:`) comment, one `# x y` per line, up to an empty comment line or the end
//!   of the block.
//! - Any violation is an error naming the file, the 1-based line and column, what was found and
//!   what was expected — unlike the original tool, which printed a message and kept whatever it
//!   had parsed.
//!
//! The header records the settings; [`SplineHeader::rebuild`] (module
//! [`rebuild`](super::rebuild)) turns them back into the mesh.

use std::io::{BufRead, BufReader, Write};
use std::path::Path;

use glam::DVec2;
use splinekit::TriMesh;

use super::{MeshIoError, MeshIoErrorKind, atomic, write_obj};
use crate::swp::SourcePos;

/// The introduction the revolution tool writes, before the `Configs:` line.
const REVOLUTION_INTRO: &str = "# This mesh is a Surface of Revolution: the comments below describe a Spline \
                                (cross-section) swept along\n# an axis that generated this mesh.\n#\n";
/// The line that starts the revolution kind.
const CONFIGS: &str = "Configs:";
/// The line that starts the sweep kind.
const SWEEP_SETTINGS: &str = "Cross-section:";
/// The heading of the cross-section control points.
const CROSS_SECTION_POINTS: &str = "Cross-section Spline control points";
/// The heading of the swept-along control points.
const SWEPT_ALONG_POINTS: &str = "Swept-along Spline control points";
/// The separator of the sweep kind's values line.
const SEPARATOR: &str = ">>+<<";

/// The spline settings of a surface of revolution, as the CS 4620 revolution tool stores
/// them in an OBJ's leading comments (see the [module docs](self) for the layout).
///
/// The profile (cross-section) is a 2D spline in the xy-plane; the tool revolves it about +z
/// ("second convention"): a profile point `(x, y)` goes to `(s·x·cos φ, s·x·sin φ, s·y)` with
/// scale `s > 0`, in `ceil(2π / slice_tolerance)` slices.
#[derive(Clone, Debug, PartialEq)]
pub struct RevolutionHeader {
    /// Whether the cross-section spline is closed.
    pub closed: bool,
    /// The tool's `epsilon`: the tolerance it tessellated the cross-section with (> 0).
    pub epsilon: f64,
    /// `true` for a uniform cubic B-spline, `false` for a Catmull-Rom spline.
    pub is_bspline: bool,
    /// The scale `s` applied to the profile (> 0).
    pub scale: f64,
    /// The largest angle between adjacent slices, in radians (> 0); the tool uses
    /// `ceil(2π / slice_tolerance)` slices.
    pub slice_tolerance: f64,
    /// The cross-section's control points.
    pub control_points: Vec<DVec2>,
}

/// One spline of a [`SweepHeader`].
#[derive(Clone, Debug, PartialEq)]
pub struct HeaderSpline {
    /// Whether the spline is closed.
    pub closed: bool,
    /// The tool's `epsilon`: the tolerance it tessellated the spline with (> 0).
    pub epsilon: f64,
    /// The control points.
    pub control_points: Vec<DVec2>,
}

/// The settings of a "Sweep Spline" mesh of the older CS 4620 sweep tool: a cross-section
/// swept along a second spline (see the [module docs](self) for the layout). The header does
/// not record the spline kind ([`SweepHeader::write`] writes it back).
#[derive(Clone, Debug, PartialEq)]
pub struct SweepHeader {
    /// The cross-section (profile).
    pub cross_section: HeaderSpline,
    /// The spline the cross-section is swept along.
    pub swept_along: HeaderSpline,
    /// The scale of the cross-section (> 0).
    pub scale: f64,
}

/// The spline description in the leading comments of a spline-annotated OBJ file.
#[derive(Clone, Debug, PartialEq)]
pub enum SplineHeader {
    /// A surface of revolution (`# Configs: …`).
    Revolution(RevolutionHeader),
    /// A cross-section swept along a spline (`# Cross-section: closed, epsilon >>+<< …`).
    Sweep(SweepHeader),
}

impl SplineHeader {
    /// Reads the spline header from the leading comments of OBJ text; `origin` names the text
    /// in errors (usually the file name).
    ///
    /// Returns `Ok(None)` when the leading comments hold no spline header (a plain OBJ file).
    ///
    /// # Errors
    ///
    /// A header that is recognised but malformed: a bad boolean or number, a missing or extra
    /// value, a missing section. The error names `origin`, the line and the column.
    ///
    /// # Example
    ///
    /// ```
    /// use splinekit_io::mesh::SplineHeader;
    ///
    /// let text = [
    ///     "# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance",
    ///     "# false 0.1 true 0.5 0.3",
    ///     "#",
    ///     "# Cross-section Spline control points: ",
    ///     "# 0.5 -1.0",
    ///     "# 1.0 0.0",
    ///     "v 0 0 0",
    /// ]
    /// .join("\n");
    /// let Some(SplineHeader::Revolution(h)) = SplineHeader::parse(&text, "vase.obj")? else { panic!() };
    /// assert!(!h.closed && h.is_bspline);
    /// assert_eq!((h.epsilon, h.scale, h.slice_tolerance), (0.1, 0.5, 0.3));
    /// assert_eq!(h.control_points.len(), 2);
    ///
    /// let bad = text.replace("0.5 -1.0", "0.5 -1,0");
    /// let err = SplineHeader::parse(&bad, "vase.obj").unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     r#"vase.obj:5:7: found "-1,0", expected a number (y coordinate of cross-section control point 1)"#
    /// );
    /// assert_eq!(SplineHeader::parse("# just a comment\nv 0 0 0\n", "plain.obj")?, None);
    /// # Ok::<(), splinekit_io::mesh::MeshIoError>(())
    /// ```
    pub fn parse(text: &str, origin: &str) -> Result<Option<Self>, MeshIoError> {
        let block = Block::new(text);
        let p = Parser { origin, block: &block };
        if let Some(i) = block.find(0, CONFIGS) {
            p.revolution(i).map(|h| Some(Self::Revolution(h)))
        } else if let Some(i) = block.find(0, SWEEP_SETTINGS) {
            p.sweep(i).map(|h| Some(Self::Sweep(h)))
        } else {
            Ok(None)
        }
    }

    /// Reads the spline header of the OBJ file at `path`; see [`parse`](Self::parse). Only the
    /// leading comment block is read from the file, not the whole mesh.
    ///
    /// # Errors
    ///
    /// As [`parse`](Self::parse), with the path as the origin; also an
    /// [`Io`](MeshIoErrorKind::Io) error if the file cannot be read, and
    /// [`InvalidUtf8`](MeshIoErrorKind::InvalidUtf8) for a comment that is not UTF-8.
    pub fn read(path: impl AsRef<Path>) -> Result<Option<Self>, MeshIoError> {
        let path = path.as_ref();
        let origin = path.display().to_string();
        let io = |error| MeshIoError::new(MeshIoErrorKind::Io { action: "read file", error }).with_origin(path);
        let mut reader = BufReader::new(std::fs::File::open(path).map_err(io)?);
        let mut text = String::new();
        let mut line = Vec::new();
        for number in 1.. {
            line.clear();
            if reader.read_until(b'\n', &mut line).map_err(io)? == 0 {
                break;
            }
            let mut bytes = line.as_slice();
            if number == 1 {
                bytes = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
            }
            let trimmed = bytes.trim_ascii_start();
            let ends_block = !trimmed.is_empty() && trimmed[0] != b'#';
            match std::str::from_utf8(bytes) {
                Ok(s) => text.push_str(s),
                // The line that ends the block may be anything (binary junk is the OBJ reader's
                // problem); a stand-in non-comment line ends the block at the same place.
                Err(_) if ends_block => text.push_str("x\n"),
                Err(e) => {
                    let valid = std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or_default();
                    let pos = SourcePos::new(number, valid.chars().count() + 1);
                    return Err(MeshIoError::at(&origin, pos, MeshIoErrorKind::InvalidUtf8));
                }
            }
            if ends_block {
                break;
            }
        }
        Self::parse(&text, &origin)
    }
}

impl RevolutionHeader {
    /// Writes the header as the revolution tool did: the introduction, the `Configs:` line and
    /// its values, and the control points, every line starting with `# ` and ending with `\n`.
    /// Numbers are written in the shortest form that reads back as the same `f64`.
    ///
    /// The original tool can load the result, and so can [`SplineHeader::parse`].
    ///
    /// # Errors
    ///
    /// [`InvalidHeaderValue`](MeshIoErrorKind::InvalidHeaderValue) for a non-finite number or a
    /// tolerance or scale that is not positive (nothing is written then), or an
    /// [`Io`](MeshIoErrorKind::Io) error from `out`.
    ///
    /// # Example
    ///
    /// ```
    /// use glam::DVec2;
    /// use splinekit_io::mesh::RevolutionHeader;
    ///
    /// let header = RevolutionHeader {
    ///     closed: false,
    ///     epsilon: 0.1,
    ///     is_bspline: true,
    ///     scale: 1.0,
    ///     slice_tolerance: 0.25,
    ///     control_points: vec![DVec2::new(0.5, -1.0), DVec2::new(1.0, 0.0)],
    /// };
    /// let mut out = Vec::new();
    /// header.write(&mut out)?;
    /// let text = String::from_utf8(out).unwrap();
    /// let lines: Vec<&str> = text.lines().collect();
    /// assert_eq!(
    ///     lines[3..],
    ///     [
    ///         "# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance",
    ///         "# false 0.1 true 1.0 0.25",
    ///         "#",
    ///         "# Cross-section Spline control points: ",
    ///         "# 0.5 -1.0",
    ///         "# 1.0 0.0",
    ///     ]
    /// );
    /// # Ok::<(), splinekit_io::mesh::MeshIoError>(())
    /// ```
    pub fn write<W: Write + ?Sized>(&self, out: &mut W) -> Result<(), MeshIoError> {
        self.check()?;
        let mut text = String::from(REVOLUTION_INTRO);
        text += "# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance\n";
        text += &format!(
            "# {} {:?} {} {:?} {:?}\n",
            self.closed, self.epsilon, self.is_bspline, self.scale, self.slice_tolerance
        );
        // The original writes a space after the colon; kept for byte-compatibility.
        text += "#\n# Cross-section Spline control points: \n";
        for p in &self.control_points {
            text += &format!("# {:?} {:?}\n", p.x, p.y);
        }
        out.write_all(text.as_bytes()).map_err(MeshIoError::write)
    }

    /// Checks that every value reads back: finite numbers, positive tolerances and scale.
    fn check(&self) -> Result<(), MeshIoError> {
        let invalid = |what: String, value: f64, expected| {
            Err(MeshIoError::new(MeshIoErrorKind::InvalidHeaderValue { what, value, expected }))
        };
        for (what, value) in
            [("epsilon", self.epsilon), ("scale", self.scale), ("slice tolerance", self.slice_tolerance)]
        {
            if !(value.is_finite() && value > 0.0) {
                return invalid(what.to_owned(), value, "a positive finite number");
            }
        }
        for (i, p) in self.control_points.iter().enumerate() {
            for (axis, value) in [("x", p.x), ("y", p.y)] {
                if !value.is_finite() {
                    return invalid(format!("{axis} coordinate of control point {}", i + 1), value, "a finite number");
                }
            }
        }
        Ok(())
    }
}

impl SweepHeader {
    /// Writes the header as the sweep tool did (the layout of the bundled files): the two
    /// introductory lines, the settings line `# true, 0.05 >>+<< false, 0.1 >>+<< 0.5`, the
    /// cross-section's points (after `# Cross-section Spline control points: `), a `# ` line,
    /// and the swept-along points. Numbers use Rust's shortest round-trip form with at least
    /// one decimal, so the header reads back to the same values.
    ///
    /// # Errors
    /// A value that is not finite, a tolerance or scale that is not positive, or an I/O error.
    pub fn write<W: Write + ?Sized>(&self, out: &mut W) -> Result<(), MeshIoError> {
        self.check()?;
        let mut text = String::from(
            "# This mesh is a \"Sweep Spline\": the comments below describe a Spline (cross-section) swept along\n\
             # another spline (swept-along) that generated this mesh.\n#\n",
        );
        text += "# Cross-section: closed, epsilon >>+<< Swept-along: closed, epsilon >>+<< Scale of Cross-section\n";
        let (c, a) = (&self.cross_section, &self.swept_along);
        text +=
            &format!("# {}, {:?} >>+<< {}, {:?} >>+<< {:?}\n", c.closed, c.epsilon, a.closed, a.epsilon, self.scale);
        text += "#\n# Cross-section Spline control points: \n";
        for p in &c.control_points {
            text += &format!("# {:?} {:?}\n", p.x, p.y);
        }
        text += "# \n# Swept-along Spline control points:\n";
        for p in &a.control_points {
            text += &format!("# {:?} {:?}\n", p.x, p.y);
        }
        out.write_all(text.as_bytes()).map_err(MeshIoError::write)
    }

    /// Checks that every value reads back: finite numbers, positive tolerances and scale.
    fn check(&self) -> Result<(), MeshIoError> {
        let invalid = |what: String, value: f64, expected| {
            Err(MeshIoError::new(MeshIoErrorKind::InvalidHeaderValue { what, value, expected }))
        };
        let values = [
            ("cross-section epsilon", self.cross_section.epsilon),
            ("swept-along epsilon", self.swept_along.epsilon),
            ("scale", self.scale),
        ];
        for (what, value) in values {
            if !(value.is_finite() && value > 0.0) {
                return invalid(what.to_owned(), value, "a positive finite number");
            }
        }
        for (name, spline) in [("cross-section", &self.cross_section), ("swept-along", &self.swept_along)] {
            for (i, p) in spline.control_points.iter().enumerate() {
                for (axis, value) in [("x", p.x), ("y", p.y)] {
                    if !value.is_finite() {
                        return invalid(
                            format!("{axis} coordinate of {name} control point {}", i + 1),
                            value,
                            "a finite number",
                        );
                    }
                }
            }
        }
        Ok(())
    }
}

impl SplineHeader {
    /// Writes the header (see [`RevolutionHeader::write`] and [`SweepHeader::write`]).
    ///
    /// # Errors
    /// As those.
    pub fn write<W: Write + ?Sized>(&self, out: &mut W) -> Result<(), MeshIoError> {
        match self {
            Self::Revolution(h) => h.write(out),
            Self::Sweep(h) => h.write(out),
        }
    }

    fn check(&self) -> Result<(), MeshIoError> {
        match self {
            Self::Revolution(h) => h.check(),
            Self::Sweep(h) => h.check(),
        }
    }
}

/// Writes `path` atomically as an annotated OBJ of either tool: `header`, then `mesh`
/// ([`write_obj`]); everything is checked first and nothing is left behind on an error.
///
/// # Errors
/// A [`MeshIoError`] whose origin is `path`: an invalid header value or mesh, or an I/O error.
pub fn save_annotated_obj(header: &SplineHeader, mesh: &TriMesh, path: impl AsRef<Path>) -> Result<(), MeshIoError> {
    let path = path.as_ref();
    stage_annotated_obj(header, mesh, path)?.commit().map_err(|e| MeshIoError::from(e).with_origin(path))
}

/// [`save_annotated_obj`] to a temporary file, not yet renamed into place (see
/// [`atomic::Staged`]).
///
/// # Errors
/// As [`save_annotated_obj`].
pub fn stage_annotated_obj(
    header: &SplineHeader,
    mesh: &TriMesh,
    path: impl AsRef<Path>,
) -> Result<atomic::Staged, MeshIoError> {
    let path = path.as_ref();
    header.check().and_then(|()| super::check(mesh)).map_err(|e| e.with_origin(path))?;
    atomic::stage_file(path, |w| header.write(w).and_then(|()| write_obj(mesh, w)).map_err(|e| e.with_origin(path)))
        .map(|(staged, ())| staged)
}

/// Writes an OBJ file as the revolution tool did: `header` ([`RevolutionHeader::write`])
/// followed by `mesh` ([`write_obj`]).
///
/// # Errors
///
/// An invalid header value or mesh (nothing is written then), or an I/O error.
pub fn write_revolution_obj<W: Write + ?Sized>(
    header: &RevolutionHeader,
    mesh: &TriMesh,
    out: &mut W,
) -> Result<(), MeshIoError> {
    header.check()?;
    super::check(mesh)?;
    header.write(out)?;
    write_obj(mesh, out)
}

/// Writes [`write_revolution_obj`]'s output to the file at `path`, atomically (see
/// [`atomic::write_file`]): the header and mesh are checked first, and on any error no file is
/// left behind.
///
/// # Errors
///
/// A [`MeshIoError`] whose origin is `path`: an invalid header value or mesh, or an I/O error.
pub fn save_revolution_obj(
    header: &RevolutionHeader,
    mesh: &TriMesh,
    path: impl AsRef<Path>,
) -> Result<(), MeshIoError> {
    let path = path.as_ref();
    header.check().and_then(|()| super::check(mesh)).map_err(|e| e.with_origin(path))?;
    atomic::write_file(path, |w| write_revolution_obj(header, mesh, w).map_err(|e| e.with_origin(path)))
}

// ---------------------------------------------------------------------------------------
// Parsing

/// A comment line of the leading block.
struct Comment<'a> {
    /// 1-based line number.
    line: usize,
    /// The text after `#`.
    body: &'a str,
    /// 1-based column of the first character of `body`.
    body_column: usize,
}

impl Comment<'_> {
    /// Whether the comment, without leading spaces, starts with `prefix`.
    fn starts_with(&self, prefix: &str) -> bool {
        self.body.trim_start().starts_with(prefix)
    }

    /// Whether the comment is empty (a bare `#`, perhaps with spaces).
    fn is_empty(&self) -> bool {
        self.body.trim().is_empty()
    }

    /// The column just after the last character.
    fn end_column(&self) -> usize {
        self.body_column + self.body.chars().count()
    }

    /// The whitespace-separated tokens (also comma-separated, with `commas`).
    fn tokens(&self, commas: bool) -> Vec<Token<'_>> {
        let mut tokens = Vec::new();
        let mut start: Option<(usize, usize)> = None; // (byte offset, column)
        for (column, (offset, c)) in (self.body_column..).zip(self.body.char_indices()) {
            let separator = c.is_whitespace() || (commas && c == ',');
            match (separator, start) {
                (true, Some((s, col))) => {
                    tokens.push(Token { text: &self.body[s..offset], column: col });
                    start = None;
                }
                (false, None) => start = Some((offset, column)),
                _ => {}
            }
        }
        if let Some((s, col)) = start {
            tokens.push(Token { text: &self.body[s..], column: col });
        }
        tokens
    }
}

/// A token of a comment line, with its 1-based column.
struct Token<'a> {
    text: &'a str,
    column: usize,
}

/// The leading comment block of a text.
struct Block<'a> {
    comments: Vec<Comment<'a>>,
    /// Where the block ends: the start of the first other line, or just after the text.
    end: SourcePos,
}

impl<'a> Block<'a> {
    fn new(text: &'a str) -> Self {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut comments = Vec::new();
        let mut end = SourcePos::default();
        for (i, raw) in text.split('\n').enumerate() {
            let line = raw.strip_suffix('\r').unwrap_or(raw);
            let trimmed = line.trim_start();
            end = SourcePos::new(i + 1, line.chars().count() + 1);
            if let Some(body) = trimmed.strip_prefix('#') {
                let body_column = line.chars().count() - trimmed.chars().count() + 2;
                comments.push(Comment { line: i + 1, body, body_column });
            } else if !trimmed.is_empty() {
                end = SourcePos::new(i + 1, 1);
                break;
            }
        }
        Self { comments, end }
    }

    /// The index of the first comment at or after `from` that starts with `prefix`.
    fn find(&self, from: usize, prefix: &str) -> Option<usize> {
        (from..self.comments.len()).find(|&i| self.comments[i].starts_with(prefix))
    }
}

/// Reads the values of one comment line, left to right.
struct Values<'a, 'o> {
    origin: &'o str,
    line: usize,
    end_column: usize,
    tokens: std::vec::IntoIter<Token<'a>>,
}

impl<'a> Values<'a, '_> {
    /// The next token, or an error saying that `expected` is missing.
    fn next(&mut self, expected: impl FnOnce() -> String) -> Result<Token<'a>, MeshIoError> {
        self.tokens.next().ok_or_else(|| {
            let kind = MeshIoErrorKind::UnexpectedEnd { found: "end of line", expected: expected() };
            MeshIoError::at(self.origin, SourcePos::new(self.line, self.end_column), kind)
        })
    }

    fn error(&self, token: &Token<'_>, expected: String) -> MeshIoError {
        let kind = MeshIoErrorKind::UnexpectedToken { found: token.text.to_owned(), expected };
        MeshIoError::at(self.origin, SourcePos::new(self.line, token.column), kind)
    }

    /// `true` or `false`.
    fn boolean(&mut self, context: &str) -> Result<bool, MeshIoError> {
        let expected = || format!("true or false ({context})");
        let token = self.next(expected)?;
        match token.text {
            "true" => Ok(true),
            "false" => Ok(false),
            _ => Err(self.error(&token, expected())),
        }
    }

    /// A finite number.
    fn number(&mut self, context: &str) -> Result<f64, MeshIoError> {
        let token = self.next(|| format!("a number ({context})"))?;
        match token.text.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            Ok(_) => Err(self.error(&token, format!("a finite number ({context})"))),
            Err(_) => Err(self.error(&token, format!("a number ({context})"))),
        }
    }

    /// A positive finite number.
    fn positive(&mut self, context: &str) -> Result<f64, MeshIoError> {
        let token = self.next(|| format!("a positive number ({context})"))?;
        match token.text.parse::<f64>() {
            Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
            _ => Err(self.error(&token, format!("a positive number ({context})"))),
        }
    }

    /// The `>>+<<` separator.
    fn separator(&mut self, context: &str) -> Result<(), MeshIoError> {
        let expected = || format!("\"{SEPARATOR}\" ({context})");
        let token = self.next(expected)?;
        if token.text == SEPARATOR { Ok(()) } else { Err(self.error(&token, expected())) }
    }

    /// No more tokens.
    fn finish(&mut self, what: &str) -> Result<(), MeshIoError> {
        match self.tokens.next() {
            None => Ok(()),
            Some(token) => Err(self.error(&token, format!("end of line ({what})"))),
        }
    }
}

/// Parses a recognised header.
struct Parser<'a, 'o> {
    origin: &'o str,
    block: &'a Block<'a>,
}

impl<'a> Parser<'a, '_> {
    /// An error at the end of the block.
    fn missing(&self, expected: String) -> MeshIoError {
        let kind = MeshIoErrorKind::UnexpectedEnd { found: "end of the comment header", expected };
        MeshIoError::at(self.origin, self.block.end, kind)
    }

    fn values(&self, comment: &'a Comment<'a>, commas: bool) -> Values<'a, '_> {
        Values {
            origin: self.origin,
            line: comment.line,
            end_column: comment.end_column(),
            tokens: comment.tokens(commas).into_iter(),
        }
    }

    /// The values line after comment `i`.
    fn values_line(&self, i: usize, what: &str) -> Result<&'a Comment<'a>, MeshIoError> {
        self.block.comments.get(i + 1).ok_or_else(|| self.missing(what.to_owned()))
    }

    /// The control points after the heading `heading` searched from comment `from`; returns
    /// them and the index of the comment after them.
    fn points(&self, from: usize, heading: &str, name: &str) -> Result<(Vec<DVec2>, usize), MeshIoError> {
        let Some(start) = self.block.find(from, heading) else {
            return Err(self.missing(format!("a \"# {heading}:\" line")));
        };
        let mut points = Vec::new();
        let mut i = start + 1;
        while let Some(comment) = self.block.comments.get(i).filter(|c| !c.is_empty()) {
            let k = points.len() + 1;
            let mut values = self.values(comment, false);
            let x = values.number(&format!("x coordinate of {name} control point {k}"))?;
            let y = values.number(&format!("y coordinate of {name} control point {k}"))?;
            values.finish("a control point has 2 coordinates")?;
            points.push(DVec2::new(x, y));
            i += 1;
        }
        Ok((points, i))
    }

    /// The revolution kind; comment `i` is the `Configs:` line.
    fn revolution(&self, i: usize) -> Result<RevolutionHeader, MeshIoError> {
        let line = self
            .values_line(i, "the configs values line \"# <closed> <epsilon> <isBSpline> <Scale> <sliceTolerance>\"")?;
        let mut v = self.values(line, false);
        let ctx = |name: &str, k: usize| format!("{name}, value {k} of 5 of the configs line");
        let closed = v.boolean(&ctx("closed", 1))?;
        let epsilon = v.positive(&ctx("epsilon", 2))?;
        let is_bspline = v.boolean(&ctx("isBSpline", 3))?;
        let scale = v.positive(&ctx("Scale", 4))?;
        let slice_tolerance = v.positive(&ctx("sliceTolerance", 5))?;
        v.finish("the configs line has 5 values")?;
        let (control_points, _) = self.points(i + 2, CROSS_SECTION_POINTS, "cross-section")?;
        Ok(RevolutionHeader { closed, epsilon, is_bspline, scale, slice_tolerance, control_points })
    }

    /// The sweep kind; comment `i` is the `Cross-section: closed, epsilon >>+<< …` line.
    fn sweep(&self, i: usize) -> Result<SweepHeader, MeshIoError> {
        let line = self.values_line(
            i,
            "the settings values line \"# <closed>, <epsilon> >>+<< <closed>, <epsilon> >>+<< <scale>\"",
        )?;
        let mut v = self.values(line, true);
        let ctx = |name: &str, k: usize| format!("{name}, value {k} of 5 of the settings line");
        let cross_closed = v.boolean(&ctx("cross-section closed", 1))?;
        let cross_epsilon = v.positive(&ctx("cross-section epsilon", 2))?;
        v.separator("after the cross-section settings")?;
        let along_closed = v.boolean(&ctx("swept-along closed", 3))?;
        let along_epsilon = v.positive(&ctx("swept-along epsilon", 4))?;
        v.separator("after the swept-along settings")?;
        let scale = v.positive(&ctx("scale of cross-section", 5))?;
        v.finish("the settings line has 5 values")?;
        let (cross_points, next) = self.points(i + 2, CROSS_SECTION_POINTS, "cross-section")?;
        let (along_points, _) = self.points(next, SWEPT_ALONG_POINTS, "swept-along")?;
        Ok(SweepHeader {
            cross_section: HeaderSpline { closed: cross_closed, epsilon: cross_epsilon, control_points: cross_points },
            swept_along: HeaderSpline { closed: along_closed, epsilon: along_epsilon, control_points: along_points },
            scale,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const REVOLUTION: &str = "# This mesh is a Surface of Revolution: the comments below describe a Spline (cross-section) swept along\n\
        # an axis that generated this mesh.\n\
        #\n\
        # Configs: closed, epsilon, isBSpline, Scale, sliceTolerance\n\
        # true 0.5623413 false 1.0E-4 0.31622776\n\
        #\n\
        # Cross-section Spline control points: \n\
        # 0.25 -1.0\n\
        # 1.0 2.5E-17\n\
        v 0.0 0.0 0.0\n";

    fn parse(text: &str) -> Result<Option<SplineHeader>, MeshIoError> {
        SplineHeader::parse(text, "t.obj")
    }

    fn err(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn revolution_header_as_the_tool_writes_it() {
        let Some(SplineHeader::Revolution(h)) = parse(REVOLUTION).unwrap() else { panic!() };
        assert_eq!(
            h,
            RevolutionHeader {
                closed: true,
                epsilon: 0.5623413,
                is_bspline: false,
                scale: 1.0e-4,
                slice_tolerance: 0.31622776,
                control_points: vec![DVec2::new(0.25, -1.0), DVec2::new(1.0, 2.5e-17)],
            }
        );
        // CRLF, a byte order mark and indentation do not matter.
        let crlf = format!("\u{feff}{}", REVOLUTION.replace('\n', "\r\n").replace("# 0.25", "  # 0.25"));
        assert_eq!(parse(&crlf).unwrap(), Some(SplineHeader::Revolution(h)));
    }

    #[test]
    fn written_header_reads_back_and_matches_the_original_layout() {
        let Some(SplineHeader::Revolution(h)) = parse(REVOLUTION).unwrap() else { panic!() };
        let mut out = Vec::new();
        h.write(&mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(text.lines().count(), 9);
        assert!(REVOLUTION.replace("1.0E-4", "0.0001").replace("2.5E-17", "2.5e-17").starts_with(&text), "{text}");
        assert_eq!(parse(&text).unwrap(), Some(SplineHeader::Revolution(h)));
    }

    #[test]
    fn writing_refuses_values_that_would_not_read_back() {
        let Some(SplineHeader::Revolution(mut h)) = parse(REVOLUTION).unwrap() else { panic!() };
        h.scale = 0.0;
        let mut out = Vec::new();
        let e = h.write(&mut out).unwrap_err();
        assert!(out.is_empty());
        assert_eq!(e.to_string(), "cannot write scale = 0, expected a positive finite number");
        h.scale = 1.0;
        h.control_points[1].y = f64::NAN;
        let e = h.write(&mut out).unwrap_err();
        assert_eq!(e.to_string(), "cannot write y coordinate of control point 2 = NaN, expected a finite number");
    }

    #[test]
    fn errors_name_line_and_column() {
        let e = |from: &str, to: &str| err(&REVOLUTION.replacen(from, to, 1));
        assert_eq!(
            e("# true 0.56", "# ture 0.56"),
            r#"t.obj:5:3: found "ture", expected true or false (closed, value 1 of 5 of the configs line)"#
        );
        assert_eq!(
            e("0.5623413", "0.56.23413"),
            r#"t.obj:5:8: found "0.56.23413", expected a positive number (epsilon, value 2 of 5 of the configs line)"#
        );
        assert_eq!(
            e("1.0E-4", "-1.0E-4"),
            r#"t.obj:5:24: found "-1.0E-4", expected a positive number (Scale, value 4 of 5 of the configs line)"#
        );
        assert_eq!(
            e(" 0.31622776", ""),
            "t.obj:5:30: found end of line, expected a positive number (sliceTolerance, value 5 of 5 of the configs line)"
        );
        assert_eq!(
            e("0.31622776", "0.31622776 7"),
            r#"t.obj:5:42: found "7", expected end of line (the configs line has 5 values)"#
        );
        assert_eq!(
            e("# 1.0 2.5E-17", "# 1.0 inf"),
            r#"t.obj:9:7: found "inf", expected a finite number (y coordinate of cross-section control point 2)"#
        );
        assert_eq!(
            e("# 1.0 2.5E-17", "# 1.0"),
            "t.obj:9:6: found end of line, expected a number (y coordinate of cross-section control point 2)"
        );
        assert_eq!(
            e("# Cross-section Spline", "# Spline"),
            r##"t.obj:10:1: found end of the comment header, expected a "# Cross-section Spline control points:" line"##
        );
        let cut = &REVOLUTION[..REVOLUTION.find("# true").unwrap()];
        assert_eq!(
            err(cut),
            "t.obj:5:1: found end of the comment header, expected the configs values line \
             \"# <closed> <epsilon> <isBSpline> <Scale> <sliceTolerance>\""
        );
    }

    #[test]
    fn sweep_header() {
        let text = "# Cross-section: closed, epsilon >>+<< Swept-along: closed, epsilon >>+<< Scale of Cross-section\n\
                    # false, 0.15 >>+<< true, 0.25 >>+<< 0.5\n#\n\
                    # Cross-section Spline control points: \n# 1.0 2.0\n# 3.0 4.0\n# \n\
                    # Swept-along Spline control points:\n# 5.0 6.0\nv 1 2 3\n";
        let Some(SplineHeader::Sweep(h)) = parse(text).unwrap() else { panic!() };
        assert_eq!(h.scale, 0.5);
        assert_eq!(
            h.cross_section,
            HeaderSpline {
                closed: false,
                epsilon: 0.15,
                control_points: vec![DVec2::new(1.0, 2.0), DVec2::new(3.0, 4.0)]
            }
        );
        assert_eq!(
            h.swept_along,
            HeaderSpline { closed: true, epsilon: 0.25, control_points: vec![DVec2::new(5.0, 6.0)] }
        );
        assert_eq!(
            err(&text.replacen(" >>+<< true", " true", 1)),
            r#"t.obj:2:15: found "true", expected ">>+<<" (after the cross-section settings)"#
        );
        assert_eq!(
            err(&text.replace("# Swept-along Spline control points:\n", "")),
            r##"t.obj:9:1: found end of the comment header, expected a "# Swept-along Spline control points:" line"##
        );
    }

    #[test]
    fn no_header() {
        assert_eq!(parse("").unwrap(), None);
        assert_eq!(parse("v 0 0 0\n# Configs: late\n").unwrap(), None);
        assert_eq!(parse("# exported by something\n#\nv 0 0 0\n").unwrap(), None);
    }
}
