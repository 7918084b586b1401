//! The STL reader (ASCII and binary), welding equal positions into shared vertices.

use std::collections::HashMap;
use std::io::Read;

use glam::DVec3;
use splinekit::mesh::PolyMesh;
use splinekit::subdiv::Creases;

use super::load::{self, LoadedMesh, ReadWarningKind, Warnings, parse_f64};
use super::{MeshIoError, MeshIoErrorKind, SubdivTags};

/// Size of the binary header and of one binary triangle record.
const HEADER: usize = 84;
const RECORD: usize = 50;

/// Reads an STL mesh (ASCII or binary) from `reader`; `origin` names it in errors.
///
/// # Which kind
///
/// A file is binary when its size is exactly `84 + 50·n`, `n` being the little-endian
/// `u32` at byte 80, even if it starts with `solid` (many binary exporters write that into
/// the 80-byte header). Otherwise it is ASCII if it starts with `solid` (after optional
/// whitespace) and has no NUL byte in its first kilobyte; else binary, where a file longer
/// than `84 + 50·n` is read with a [`TrailingBytes`](ReadWarningKind::TrailingBytes) warning
/// and a shorter one is an error. ASCII may start with a UTF-8 byte-order mark, or be UTF-16
/// with a byte-order mark (decoded first); UTF-16 without one is refused with a clear error.
///
/// # Welding
///
/// STL stores every triangle's three corners separately. The reader makes corners with equal
/// positions one shared vertex, so that edges and adjacency work: positions are compared
/// exactly, coordinate by coordinate (as `f64` values converted from the file's `f32` or
/// decimal text; `0.0` and `-0.0` are equal, NaN only to a bitwise-identical NaN). Vertices are
/// numbered in order of first appearance. Nearby but unequal positions stay separate; weld
/// those with a tolerance afterwards if needed.
///
/// Facet normals and the binary attribute bytes are ignored: the corner order gives the
/// orientation (counter-clockwise seen from the front). ASCII `outer loop`s with more than
/// three vertices become polygons. Keywords are matched in any case; several `solid … endsolid`
/// blocks in one file are read in order.
///
/// # Errors
///
/// ASCII: `origin:LINE:COL: found …, expected …` (a misspelt keyword, a malformed number, a
/// loop with fewer than three vertices, a missing `endsolid`). Binary: `origin: found end of
/// file, expected …` for a truncated file. Nothing is returned on error.
///
/// ```
/// use splinekit_io::mesh::read_stl;
///
/// let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n\
///             endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\n\
///             vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
/// let mesh = read_stl(text.as_bytes(), "quad.stl")?.mesh;
/// assert_eq!(mesh.num_vertices(), 4); // the shared corners are welded
/// assert_eq!(mesh.face(1), &[1, 3, 2]);
/// # Ok::<(), splinekit_io::MeshIoError>(())
/// ```
pub fn read_stl<R: Read>(reader: R, origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let bytes = load::read_all(reader, origin)?;
    parse_stl(&bytes, origin)
}

/// Parses STL bytes (see [`read_stl`]).
pub(crate) fn parse_stl(bytes: &[u8], origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let declared = (bytes.len() >= HEADER).then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]));
    let binary_size = declared.map(|n| HEADER as u64 + RECORD as u64 * u64::from(n));
    if binary_size == Some(bytes.len() as u64) {
        return parse_binary(bytes, origin);
    }
    if let Some(text) = load::utf16_decoded(bytes).filter(|t| starts_with_solid(t)) {
        return parse_ascii(&text, origin);
    }
    let solid = starts_with_solid(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes));
    let has_nul = bytes[..bytes.len().min(1024)].contains(&0);
    if solid && !has_nul {
        return parse_ascii(bytes, origin);
    }
    // `solid` in UTF-16 without a byte-order mark (binary data hardly looks so)
    let head: Vec<u8> = bytes.iter().take(64).filter(|&&b| b != 0).copied().collect();
    if !solid && starts_with_solid(&head) && load::looks_like_utf16(bytes) {
        return Err(load::error_in(origin, MeshIoErrorKind::Utf16WithoutBom));
    }
    if declared.is_some() {
        return parse_binary(bytes, origin);
    }
    Err(load::error_in(
        origin,
        MeshIoErrorKind::UnexpectedEnd {
            found: "end of file",
            expected: format!(
                "an STL file: ASCII starting with solid, or binary with an 84-byte header (the file has {} bytes)",
                bytes.len()
            ),
        },
    ))
}

/// Whether `text` starts with `solid` (in any case) after optional whitespace.
fn starts_with_solid(text: &[u8]) -> bool {
    let start = text.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(text.len());
    text[start..].get(..5).is_some_and(|k| k.eq_ignore_ascii_case(b"solid"))
}

/// Welds equal positions into shared vertices.
#[derive(Default)]
struct Welder {
    map: HashMap<[u64; 3], u32>,
    positions: Vec<DVec3>,
}

impl Welder {
    fn with_capacity(n: usize) -> Self {
        Self { map: HashMap::with_capacity(n), positions: Vec::with_capacity(n) }
    }

    fn index(&mut self, p: DVec3) -> u32 {
        // `+ 0.0` turns -0.0 into 0.0, so the two weld.
        let key = [(p.x + 0.0).to_bits(), (p.y + 0.0).to_bits(), (p.z + 0.0).to_bits()];
        let next = self.positions.len() as u32;
        let index = *self.map.entry(key).or_insert(next);
        if index == next {
            self.positions.push(p);
        }
        index
    }
}

fn parse_binary(bytes: &[u8], origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let available = (bytes.len() - HEADER) / RECORD;
    if available < n {
        return Err(load::truncated(
            origin,
            format!(
                "{n} triangles of binary STL ({} bytes), found {available} complete triangles ({} bytes)",
                HEADER as u64 + RECORD as u64 * n as u64,
                bytes.len()
            ),
        ));
    }
    let mut warnings = Warnings::default();
    let extra = bytes.len() - HEADER - RECORD * n;
    if extra > 0 {
        warnings.push(0, ReadWarningKind::TrailingBytes { count: extra });
    }
    let mut welder = Welder::with_capacity(n / 2 + 3);
    let mut face_vertices = Vec::with_capacity(3 * n);
    for record in bytes[HEADER..HEADER + RECORD * n].chunks_exact(RECORD) {
        for corner in 0..3 {
            let at = 12 + 12 * corner;
            let f = |k: usize| {
                let b = &record[at + 4 * k..at + 4 * k + 4];
                f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            };
            face_vertices.push(welder.index(DVec3::new(f(0), f(1), f(2))));
        }
    }
    Ok(finish(welder, face_vertices, (0..=n as u32).map(|f| 3 * f).collect(), warnings))
}

fn finish(welder: Welder, face_vertices: Vec<u32>, face_offsets: Vec<u32>, warnings: Warnings) -> LoadedMesh {
    let mesh = PolyMesh { positions: welder.positions, face_offsets, face_vertices, ..PolyMesh::default() };
    LoadedMesh { mesh, warnings: warnings.finish(), creases: Creases::default(), subdiv_tags: SubdivTags::default() }
}

/// Whitespace-separated tokens across lines, with their positions.
struct Tokens<'a> {
    lines: Box<dyn Iterator<Item = (usize, &'a [u8])> + 'a>,
    no: usize,
    line: &'a [u8],
    pos: usize,
    /// The last token's start offset.
    at: usize,
    origin: &'a str,
}

impl<'a> Tokens<'a> {
    fn next(&mut self) -> Option<&'a [u8]> {
        loop {
            let line = self.line;
            let mut i = self.pos;
            while i < line.len() && line[i].is_ascii_whitespace() {
                i += 1;
            }
            if i < line.len() {
                let start = i;
                while i < line.len() && !line[i].is_ascii_whitespace() {
                    i += 1;
                }
                self.pos = i;
                self.at = start;
                return Some(&line[start..i]);
            }
            let (no, next) = self.lines.next()?;
            (self.no, self.line, self.pos) = (no, next, 0);
        }
    }

    fn skip_line(&mut self) {
        self.pos = self.line.len();
    }

    /// "found TOKEN (or end of file), expected WHAT" at the last token (or the end).
    fn error(&self, token: Option<&[u8]>, expected: impl Into<String>) -> MeshIoError {
        match token {
            Some(t) => load::unexpected(self.origin, self.no, self.line, self.at, t, expected),
            None => load::error_at(
                self.origin,
                self.no,
                self.line,
                self.line.len(),
                MeshIoErrorKind::UnexpectedEnd { found: "end of file", expected: expected.into() },
            ),
        }
    }

    fn keyword(&mut self, word: &str) -> Result<(), MeshIoError> {
        let t = self.next();
        if t.is_some_and(|t| t.eq_ignore_ascii_case(word.as_bytes())) { Ok(()) } else { Err(self.error(t, word)) }
    }

    fn number(&mut self, what: &str) -> Result<f64, MeshIoError> {
        let t = self.next();
        t.and_then(parse_f64).ok_or_else(|| self.error(t, format!("a number ({what})")))
    }
}

fn is(t: Option<&[u8]>, word: &str) -> bool {
    t.is_some_and(|t| t.eq_ignore_ascii_case(word.as_bytes()))
}

fn parse_ascii(bytes: &[u8], origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let mut tokens = Tokens { lines: Box::new(load::lines(bytes)), no: 0, line: b"", pos: 0, at: 0, origin };
    let mut welder = Welder::with_capacity(bytes.len() / 200 + 3);
    let mut face_offsets = vec![0u32];
    let mut face_vertices = Vec::with_capacity(bytes.len() / 80);
    tokens.keyword("solid")?;
    tokens.skip_line(); // the name
    loop {
        let t = tokens.next();
        if is(t, "endsolid") {
            tokens.skip_line();
            let t = tokens.next();
            if t.is_none() {
                break;
            }
            if !is(t, "solid") {
                return Err(tokens.error(t, "solid or end of file"));
            }
            tokens.skip_line();
            continue;
        }
        if !is(t, "facet") {
            return Err(tokens.error(t, "facet or endsolid"));
        }
        tokens.keyword("normal")?;
        for axis in ["x", "y", "z"] {
            tokens.number(&format!("{axis} component of the facet normal"))?;
        }
        tokens.keyword("outer")?;
        tokens.keyword("loop")?;
        let start = face_vertices.len();
        loop {
            let t = tokens.next();
            if is(t, "endloop") && face_vertices.len() - start >= 3 {
                break;
            }
            if !is(t, "vertex") {
                let expected = if face_vertices.len() - start >= 3 { "vertex or endloop" } else { "vertex" };
                return Err(tokens.error(t, expected));
            }
            let corner = face_vertices.len() - start + 1;
            let mut p = DVec3::ZERO;
            for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
                p[k] = tokens.number(&format!("{axis} coordinate of vertex {corner}"))?;
            }
            face_vertices.push(welder.index(p));
        }
        tokens.keyword("endfacet")?;
        let end = u32::try_from(face_vertices.len()).map_err(|_| {
            tokens.error(
                None,
                "at most 2³² face corners", // practically unreachable: a file of hundreds of GB
            )
        })?;
        face_offsets.push(end);
    }
    Ok(finish(welder, face_vertices, face_offsets, Warnings::default()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binary(header: &[u8; 80], tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut b = header.to_vec();
        b.extend((tris.len() as u32).to_le_bytes());
        for t in tris {
            b.extend([0u8; 12]);
            for p in t {
                for x in p {
                    b.extend(x.to_le_bytes());
                }
            }
            b.extend([0u8; 2]);
        }
        b
    }

    const QUAD: [[[f32; 3]; 3]; 2] =
        [[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [-0.0, 1.0, 0.0]]];

    fn err(bytes: &[u8]) -> String {
        parse_stl(bytes, "t.stl").unwrap_err().to_string()
    }

    #[test]
    fn binary_with_solid_header_and_welding() {
        let mut header = [b' '; 80];
        header[..11].copy_from_slice(b"solid quad ");
        let b = binary(&header, &QUAD);
        let m = parse_stl(&b, "t.stl").unwrap();
        assert!(m.warnings.is_empty());
        assert_eq!(m.mesh.num_vertices(), 4);
        assert_eq!(m.mesh.face_vertices, vec![0, 1, 2, 1, 3, 2]);
        // Trailing bytes: a warning. Truncated: an error.
        let mut longer = b.clone();
        longer.extend([0; 7]);
        assert_eq!(
            parse_stl(&longer, "t.stl").unwrap().warnings[0].to_string(),
            "ignored 7 bytes after the end of the data"
        );
        assert_eq!(
            err(&b[..b.len() - 1]),
            "t.stl: found end of file, expected 2 triangles of binary STL (184 bytes), found 1 complete triangles (183 bytes)"
        );
    }

    #[test]
    fn ascii_polygons_case_and_several_solids() {
        let text = "SOLID a\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n\
                    vertex 0 1 0\n  endloop\n endfacet\nENDSOLID a\nsolid b\nfacet normal 0 0 0 outer loop vertex 0 0 0 \
                    vertex 1 1 0 vertex 0 0 1 endloop endfacet endsolid\n";
        let m = parse_stl(text.as_bytes(), "t.stl").unwrap().mesh;
        assert_eq!(m.face_offsets, vec![0, 4, 7]);
        assert_eq!(m.face_vertices, vec![0, 1, 2, 3, 0, 2, 4]);
    }

    #[test]
    fn ascii_errors() {
        let head = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
        assert_eq!(
            err(format!("{head}vertex 0 1,0 0\nendloop\nendfacet\nendsolid\n").as_bytes()),
            r#"t.stl:6:10: found "1,0", expected a number (y coordinate of vertex 3)"#
        );
        assert_eq!(
            err(format!("{head}endloop\nendfacet\nendsolid\n").as_bytes()),
            r#"t.stl:6:1: found "endloop", expected vertex"#
        );
        assert_eq!(
            err(format!("{head}vertex 0 1 0\nendloop\nendfacet\n").as_bytes()),
            "t.stl:8:9: found end of file, expected facet or endsolid"
        );
        assert_eq!(
            err(format!("{head}vertex 0 1 0\nendlop\n").as_bytes()),
            r#"t.stl:7:1: found "endlop", expected vertex or endloop"#
        );
        assert_eq!(err(b"solid"), "t.stl:1:6: found end of file, expected facet or endsolid");
        assert_eq!(
            err(b"hello"),
            "t.stl: found end of file, expected an STL file: ASCII starting with solid, or binary with an 84-byte header (the file has 5 bytes)"
        );
    }
}
