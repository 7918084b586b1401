//! The Wavefront OBJ reader.

use std::io::Read;

use glam::{DVec2, DVec3};
use splinekit::mesh::{FaceVarying, PolyMesh};

use super::load::{self, LoadedMesh, ReadWarningKind, Warnings, next_token, parse_f64, parse_i64};
use super::tags::Tags;
use super::{MeshIoError, MeshIoErrorKind};
use crate::swp::SourcePos;

/// "No value" in the per-corner index arrays while reading.
const ABSENT: u32 = u32::MAX;

/// What the values of a `v` line are, by position.
const VERTEX_VALUES: [&str; 6] =
    ["x coordinate", "y coordinate", "z coordinate", "w weight or red component", "green component", "blue component"];

/// Reads a Wavefront OBJ mesh from `reader`; `origin` names it in errors (usually the path).
///
/// # What is read
///
/// - `v x y z`, `v x y z w` (the weight is ignored: it only matters for rational curves and
///   surfaces) and `v x y z r g b` (a vertex colour, kept as given, usually in `[0, 1]`).
///   Colours are kept only if every vertex has one; otherwise they are dropped with a
///   [`ColorsDropped`](ReadWarningKind::ColorsDropped) warning.
/// - `vt u [v [w]]` (`v` defaults to 0, `w` is ignored) and `vn x y z`.
/// - `f` with one reference per corner, in any of the forms `v`, `v/vt`, `v//vn`, `v/vt/vn`
///   (forms may be mixed within a face), with 1-based indices or negative ones relative to
///   the end of the list so far (`-1` is the last vertex defined). Polygons of any size are
///   kept as they are; faces with one or two corners are kept too (for
///   [`TopologyReport`](splinekit::mesh::TopologyReport) to report). A positive index may
///   refer to a vertex defined later in the file.
/// - Texture coordinates and normals become face-varying attributes
///   ([`FaceVarying`]): `vt`/`vn` values as written, and per corner the index given. An
///   attribute is kept only if every corner of every face gives it; if some faces have it
///   and some do not, it is dropped with an
///   [`AttributeDropped`](ReadWarningKind::AttributeDropped) warning naming the first face
///   line without it.
/// - `t crease …` and `t corner …`: sharp and semi-sharp edges and vertices (OpenSubdiv's tags,
///   0-based vertices; see [`read_creases`](super::read_creases)) into
///   [`LoadedMesh::creases`]; `t interpolateboundary …`, `t creasemethod …` and
///   `t smoothtriangles …`, the subdivision options (see [`SubdivTags`](super::SubdivTags)), into
///   [`LoadedMesh::subdiv_tags`]; other `t` tags are skipped with a
///   [`SkippedTag`](ReadWarningKind::SkippedTag) warning.
/// - Grouping, material and display statements (`o`, `g`, `s`, `mg`, `usemtl`, `mtllib`,
///   `maplib`, `usemap`, `bevel`, `c_interp`, `d_interp`, `lod`, `shadow_obj`, `trace_obj`,
///   `ctech`, `stech`) are ignored, as are comments (`#` to the end of the line, also after a
///   statement) and empty lines.
/// - Statements with geometry the reader does not read — points `p`, lines `l`, free-form
///   curves and surfaces (`curv`, `curv2`, `surf`) and the statements that describe them
///   (`vp`, `cstype`, `deg`, `bmat`, `step`, `parm`, `trim`, `hole`, `scrv`, `sp`, `end`,
///   `con`) — are skipped with one
///   [`SkippedStatements`](ReadWarningKind::SkippedStatements) warning per keyword, giving
///   the count and the line of the first.
/// - Any other statement — such as the HTML lines around the course's `icosahedron.obj` and
///   `bunny.obj` — is skipped with an [`UnknownStatement`](ReadWarningKind::UnknownStatement)
///   warning naming the line (at most [`MAX_WARNINGS`](super::MAX_WARNINGS) of them, then a
///   count).
///
/// Lines end at LF; a CR before it is ignored. A line whose last character (other than
/// whitespace, and not in a comment) is `\` continues on the next line: the `\` separates
/// tokens like a space, and errors still give the line and column where the token is. The
/// text is UTF-8 (a byte-order mark is skipped), or UTF-16 little or big endian with a
/// byte-order mark (decoded first). The file is read in one pass without allocating per line.
///
/// # Errors
///
/// A [`MeshIoError`] at `origin:LINE:COL` (1-based, the column counted in characters) naming
/// what was found and what was expected: a malformed number, a missing or extra value, a
/// malformed face reference, index 0, or an index out of range (checked against the
/// vertices, texture coordinates or normals defined so far for negative indices, and in the
/// whole file for positive ones). Also a file that looks like UTF-16 without a byte-order
/// mark, and a file whose only surfaces are free-form ones (`surf` but no `f`:
/// [`NoFacesRead`](MeshIoErrorKind::NoFacesRead)). Nothing is returned on error.
///
/// ```
/// use splinekit_io::mesh::read_obj;
///
/// let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 -2/1/1 -1/1/1\n";
/// let loaded = read_obj(text.as_bytes(), "quad.obj")?;
/// assert_eq!(loaded.mesh.face(0), &[0, 1, 2, 3]);
/// assert_eq!(loaded.mesh.uvs.unwrap().indices, vec![0; 4]);
///
/// let err = read_obj("v 0 0 0\nv 1 0 0\nv 1 1,5 0\n".as_bytes(), "bad.obj").unwrap_err();
/// assert_eq!(err.to_string(), r#"bad.obj:3:5: found "1,5", expected a number (y coordinate)"#);
/// # Ok::<(), splinekit_io::MeshIoError>(())
/// ```
pub fn read_obj<R: Read>(reader: R, origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let bytes = load::read_all(reader, origin)?;
    parse_obj(&bytes, origin)
}

/// Which list a face index refers to.
#[derive(Clone, Copy)]
enum List {
    Vertex,
    TexCoord,
    Normal,
}

impl List {
    fn name(self) -> &'static str {
        match self {
            Self::Vertex => "vertex",
            Self::TexCoord => "texture coordinate",
            Self::Normal => "normal",
        }
    }
}

/// A positive index beyond the list so far, checked at the end of the file.
struct Forward {
    list: List,
    index: u32,
    token: Vec<u8>,
    pos: SourcePos,
}

/// Per-face bookkeeping of one attribute.
#[derive(Default)]
struct Presence {
    any_corner: bool,
    faces_with: usize,
    faces_without: usize,
    first_without: usize,
}

impl Presence {
    fn face(&mut self, line: usize, with: usize, corners: usize) {
        self.any_corner |= with > 0;
        if with == corners {
            self.faces_with += 1;
        } else {
            self.faces_without += 1;
            if self.first_without == 0 {
                self.first_without = line;
            }
        }
    }

    /// Whether to keep the attribute; warns when dropping it.
    fn keep(&self, attribute: &'static str, warnings: &mut Warnings) -> bool {
        if !self.any_corner {
            return false;
        }
        if self.faces_without == 0 {
            return true;
        }
        warnings.push(
            0,
            ReadWarningKind::AttributeDropped {
                attribute,
                faces_with: self.faces_with,
                faces_without: self.faces_without,
                first_without: self.first_without,
            },
        );
        false
    }
}

/// Statements with geometry that is not read: keyword, and what is not read. Each kind is
/// skipped with one [`SkippedStatements`](ReadWarningKind::SkippedStatements) warning.
const SKIPPED_GEOMETRY: [(&str, &str); 17] = [
    ("p", "points are not read"),
    ("l", "lines are not read"),
    ("curv", "free-form curves are not read"),
    ("curv2", "free-form curves are not read"),
    ("surf", "free-form surfaces are not read"),
    ("vp", "free-form geometry is not read"),
    ("cstype", "free-form geometry is not read"),
    ("deg", "free-form geometry is not read"),
    ("bmat", "free-form geometry is not read"),
    ("step", "free-form geometry is not read"),
    ("parm", "free-form geometry is not read"),
    ("trim", "free-form geometry is not read"),
    ("hole", "free-form geometry is not read"),
    ("scrv", "free-form geometry is not read"),
    ("sp", "free-form geometry is not read"),
    ("end", "free-form geometry is not read"),
    ("con", "free-form geometry is not read"),
];

/// Statements without geometry, ignored without a warning: grouping, materials and display
/// attributes.
const IGNORED: [&[u8]; 16] = [
    b"o",
    b"g",
    b"s",
    b"mg",
    b"usemtl",
    b"mtllib",
    b"maplib",
    b"usemap",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"lod",
    b"shadow_obj",
    b"trace_obj",
    b"ctech",
    b"stech",
];

/// Where the lines after the first of a statement continued with `\` start: for each, its
/// 1-based column in the joined text and its line number.
#[derive(Default)]
struct Joins(Vec<(usize, usize)>);

impl Joins {
    /// The position in the file of `pos`, a position in the joined text (whose line is the
    /// statement's first).
    fn physical(&self, pos: SourcePos) -> SourcePos {
        match self.0.iter().rev().find(|&&(column, _)| column <= pos.column) {
            Some(&(column, line)) => SourcePos::new(line, pos.column - column + 1),
            None => pos,
        }
    }
}

/// The byte offset of the `\` that continues `line` on the next line, if it does: the last
/// character other than whitespace, outside a comment.
fn continuation(line: &[u8]) -> Option<usize> {
    let last = line.iter().rposition(|b| !b.is_ascii_whitespace()).filter(|&i| line[i] == b'\\')?;
    let comment = (0..last).find(|&i| line[i] == b'#' && (i == 0 || line[i - 1].is_ascii_whitespace()));
    comment.is_none().then_some(last)
}

/// The state of one read.
#[derive(Default)]
struct Reader {
    positions: Vec<DVec3>,
    colors: Vec<DVec3>,
    colored: usize,
    first_uncolored: usize,
    tex: Vec<DVec2>,
    normals: Vec<DVec3>,
    face_offsets: Vec<u32>,
    face_vertices: Vec<u32>,
    face_tex: Vec<u32>,
    face_normals: Vec<u32>,
    tex_presence: Presence,
    normal_presence: Presence,
    forward: Vec<Forward>,
    warnings: Warnings,
    tags: Tags,
    /// Per entry of [`SKIPPED_GEOMETRY`]: how many, and the line of the first.
    skipped: [(usize, usize); SKIPPED_GEOMETRY.len()],
}

/// Parses OBJ text (see [`read_obj`]).
pub(crate) fn parse_obj(bytes: &[u8], origin: &str) -> Result<LoadedMesh, MeshIoError> {
    let text = load::text(bytes, origin)?;
    let mut r = Reader { face_offsets: vec![0], ..Reader::default() };
    let mut lines = load::lines(&text);
    // A statement continued over several lines, joined, and where its lines start.
    let mut joined = Vec::new();
    let mut joins = Joins::default();
    while let Some((no, first)) = lines.next() {
        let Some(cut) = continuation(first) else {
            r.statement(origin, no, first)?;
            continue;
        };
        // The `\` and what follows it become a space.
        joined.clear();
        joins.0.clear();
        joined.extend_from_slice(&first[..cut]);
        joined.push(b' ');
        for (next_no, next) in lines.by_ref() {
            joins.0.push((load::column(&joined, joined.len()), next_no));
            let Some(cut) = continuation(next) else {
                joined.extend_from_slice(next);
                break;
            };
            joined.extend_from_slice(&next[..cut]);
            joined.push(b' ');
        }
        // Positions in the joined text move to the lines they are on.
        let (forward, tags) = (r.forward.len(), r.tags.num_refs());
        r.statement(origin, no, &joined).map_err(|e| e.map_pos(|p| joins.physical(p)))?;
        for f in &mut r.forward[forward..] {
            f.pos = joins.physical(f.pos);
        }
        r.tags.map_refs(tags, |p| joins.physical(p));
    }
    r.finish(origin)
}

impl Reader {
    /// Reads the statement `line`, which starts on line `no`.
    fn statement(&mut self, origin: &str, no: usize, line: &[u8]) -> Result<(), MeshIoError> {
        let mut pos = 0;
        let Some((_, key)) = next_token(line, &mut pos) else { return Ok(()) };
        let unexpected =
            |offset: usize, token: &[u8], expected: String| load::unexpected(origin, no, line, offset, token, expected);
        match key {
            b"v" => {
                let mut values = [0.0; 6];
                let (n, end) = numbers(line, &mut pos, &mut values, &VERTEX_VALUES, &unexpected)?;
                if n < 3 || n == 5 {
                    return Err(unexpected(end, b"", format!("a number ({})", VERTEX_VALUES[n])));
                }
                if self.positions.len() >= ABSENT as usize {
                    return Err(too_many(origin, no, line, "vertices"));
                }
                self.positions.push(DVec3::new(values[0], values[1], values[2]));
                if n == 6 {
                    self.colored += 1;
                    // Kept only while every vertex so far has one; the count decides at the end.
                    if self.colors.len() + 1 == self.positions.len() {
                        self.colors.push(DVec3::new(values[3], values[4], values[5]));
                    }
                } else if self.first_uncolored == 0 {
                    self.first_uncolored = no;
                }
            }
            b"vt" => {
                let mut values = [0.0; 3];
                let names = ["u coordinate", "v coordinate", "w coordinate"];
                let (n, end) = numbers(line, &mut pos, &mut values, &names, &unexpected)?;
                if n == 0 {
                    return Err(unexpected(end, b"", String::from("a number (u coordinate)")));
                }
                if self.tex.len() >= ABSENT as usize {
                    return Err(too_many(origin, no, line, "texture coordinates"));
                }
                self.tex.push(DVec2::new(values[0], values[1]));
            }
            b"vn" => {
                let mut values = [0.0; 3];
                let names = ["x component", "y component", "z component"];
                let (n, end) = numbers(line, &mut pos, &mut values, &names, &unexpected)?;
                if n < 3 {
                    return Err(unexpected(end, b"", format!("a number ({})", names[n])));
                }
                if self.normals.len() >= ABSENT as usize {
                    return Err(too_many(origin, no, line, "normals"));
                }
                self.normals.push(DVec3::from_array(values));
            }
            b"f" => {
                let start = self.face_vertices.len();
                let mut end = pos;
                while let Some((offset, token)) = next_token(line, &mut pos) {
                    end = pos;
                    let counts = [self.positions.len(), self.tex.len(), self.normals.len()];
                    let forward = &mut self.forward;
                    let corner = parse_reference(token, offset, counts, &unexpected, &mut |list, index, at| {
                        forward.push(Forward {
                            list,
                            index,
                            token: token_at(line, at).to_vec(),
                            pos: SourcePos::new(no, load::column(line, at)),
                        });
                    })?;
                    self.face_vertices.push(corner[0]);
                    self.face_tex.push(corner[1]);
                    self.face_normals.push(corner[2]);
                }
                let corners = self.face_vertices.len() - start;
                if corners == 0 {
                    return Err(unexpected(end, b"", String::from("a vertex reference v, v/vt, v//vn or v/vt/vn")));
                }
                let with_tex = self.face_tex[start..].iter().filter(|&&t| t != ABSENT).count();
                let with_normal = self.face_normals[start..].iter().filter(|&&t| t != ABSENT).count();
                self.tex_presence.face(no, with_tex, corners);
                self.normal_presence.face(no, with_normal, corners);
                self.face_offsets.push(self.face_vertices.len() as u32);
            }
            b"t" => self.tags.statement(origin, no, line, pos, &mut self.warnings)?,
            _ if IGNORED.contains(&key) => {}
            _ => match SKIPPED_GEOMETRY.iter().position(|(k, _)| k.as_bytes() == key) {
                Some(k) => {
                    let (count, first) = &mut self.skipped[k];
                    *count += 1;
                    if *first == 0 {
                        *first = no;
                    }
                }
                None => self.warnings.unknown(no, line),
            },
        }
        Ok(())
    }

    /// Checks the forward references and crease tags, and makes the mesh.
    fn finish(mut self, origin: &str) -> Result<LoadedMesh, MeshIoError> {
        // Forward references, in file order.
        for f in &self.forward {
            let count = match f.list {
                List::Vertex => self.positions.len(),
                List::TexCoord => self.tex.len(),
                List::Normal => self.normals.len(),
            };
            if f.index as usize >= count {
                let kind = MeshIoErrorKind::UnexpectedToken {
                    found: String::from_utf8_lossy(&f.token).into_owned(),
                    expected: range_message(f.list, count, true),
                };
                return Err(MeshIoError::at(origin, f.pos, kind));
            }
        }
        let surfaces = SKIPPED_GEOMETRY.iter().position(|(k, _)| *k == "surf").map_or(0, |k| self.skipped[k].0);
        if self.face_offsets.len() == 1 && surfaces > 0 {
            let plural = if surfaces == 1 { "" } else { "s" };
            let kind = MeshIoErrorKind::NoFacesRead {
                records: format!("{surfaces} free-form surface{plural} (surf)"),
                reason: String::from("free-form surfaces are not read; export them as polygons"),
            };
            return Err(load::error_in(origin, kind));
        }
        for (&(keyword, reason), &(count, first)) in SKIPPED_GEOMETRY.iter().zip(&self.skipped) {
            if count > 0 {
                self.warnings.insert(first, ReadWarningKind::SkippedStatements { keyword, count, reason });
            }
        }

        let subdiv_tags = self.tags.options();
        let creases = self.tags.finish(origin, self.positions.len())?;
        let keep_colors = self.colored > 0 && self.colored == self.positions.len();
        if self.colored > 0 && !keep_colors {
            self.warnings.push(
                0,
                ReadWarningKind::ColorsDropped {
                    vertices_with: self.colored,
                    vertices_without: self.positions.len() - self.colored,
                    first_without: self.first_uncolored,
                },
            );
        }
        let uvs = self
            .tex_presence
            .keep("texture coordinates", &mut self.warnings)
            .then_some(FaceVarying { values: self.tex, indices: self.face_tex });
        let normals = self
            .normal_presence
            .keep("normals", &mut self.warnings)
            .then_some(FaceVarying { values: self.normals, indices: self.face_normals });
        let mesh = PolyMesh {
            positions: self.positions,
            colors: if keep_colors { self.colors } else { Vec::new() },
            face_offsets: self.face_offsets,
            face_vertices: self.face_vertices,
            normals,
            uvs,
        };
        Ok(LoadedMesh { mesh, warnings: self.warnings.finish(), creases, subdiv_tags })
    }
}

/// The token of `line` starting at byte `at`.
fn token_at(line: &[u8], at: usize) -> &[u8] {
    let end = line[at..].iter().position(|&b| b.is_ascii_whitespace() || b == b'/').map_or(line.len(), |e| at + e);
    &line[at..end]
}

fn too_many(origin: &str, no: usize, line: &[u8], what: &str) -> MeshIoError {
    load::error_at(
        origin,
        no,
        line,
        0,
        MeshIoErrorKind::Unrepresentable { format: "32-bit indices", what: format!("more than 4294967294 {what}") },
    )
}

/// Reads up to `values.len()` numbers from the rest of the line; returns how many, and the
/// byte offset just after the last token (for "expected more" errors).
fn numbers<F>(
    line: &[u8],
    pos: &mut usize,
    values: &mut [f64],
    names: &[&str],
    unexpected: &F,
) -> Result<(usize, usize), MeshIoError>
where
    F: Fn(usize, &[u8], String) -> MeshIoError,
{
    let mut n = 0;
    let mut end = *pos;
    while let Some((offset, token)) = next_token(line, pos) {
        if n == values.len() {
            return Err(unexpected(offset, token, String::from("end of line")));
        }
        values[n] = parse_f64(token).ok_or_else(|| unexpected(offset, token, format!("a number ({})", names[n])))?;
        n += 1;
        end = *pos;
    }
    Ok((n, end))
}

/// Parses one face corner reference `v`, `v/vt`, `v//vn` or `v/vt/vn` at byte `offset`;
/// returns the 0-based indices (or [`ABSENT`]). Positive indices beyond the lists so far go
/// to `forward(list, index, byte offset)`.
fn parse_reference<F>(
    token: &[u8],
    offset: usize,
    counts: [usize; 3],
    unexpected: &F,
    forward: &mut dyn FnMut(List, u32, usize),
) -> Result<[u32; 3], MeshIoError>
where
    F: Fn(usize, &[u8], String) -> MeshIoError,
{
    let form = "a vertex reference v, v/vt, v//vn or v/vt/vn";
    let mut out = [ABSENT; 3];
    let mut start = 0;
    for (k, list) in [List::Vertex, List::TexCoord, List::Normal].into_iter().enumerate() {
        if start > token.len() {
            break;
        }
        let end = token[start..].iter().position(|&b| b == b'/').map_or(token.len(), |e| start + e);
        let part = &token[start..end];
        let at = offset + start;
        if !part.is_empty() {
            let value = parse_i64(part)
                .ok_or_else(|| unexpected(at, part, format!("an integer {} index (in {form})", list.name())))?;
            out[k] = resolve(value, counts[k], list, at, part, unexpected, forward)?;
        } else if k == 0 {
            return Err(unexpected(offset, token, String::from(form)));
        }
        start = end + 1;
    }
    if start <= token.len() {
        // A fourth part.
        return Err(unexpected(offset, token, String::from(form)));
    }
    Ok(out)
}

/// Turns a 1-based or negative OBJ index into a 0-based one.
fn resolve<F>(
    value: i64,
    count: usize,
    list: List,
    at: usize,
    part: &[u8],
    unexpected: &F,
    forward: &mut dyn FnMut(List, u32, usize),
) -> Result<u32, MeshIoError>
where
    F: Fn(usize, &[u8], String) -> MeshIoError,
{
    let count_i = count as i64;
    if value == 0 {
        return Err(unexpected(at, part, format!("a non-zero {} index (OBJ counts from 1)", list.name())));
    }
    if value < 0 {
        if value < -count_i {
            return Err(unexpected(at, part, range_message(list, count, false)));
        }
        return Ok((count_i + value) as u32);
    }
    let index = value - 1;
    if index >= i64::from(ABSENT) {
        return Err(unexpected(at, part, range_message(list, count, false)));
    }
    if index >= count_i {
        forward(list, index as u32, at);
    }
    Ok(index as u32)
}

/// "a vertex index from 1 to N or from -N to -1" (`in_file`: the count is the whole file's).
fn range_message(list: List, count: usize, in_file: bool) -> String {
    let name = list.name();
    if count == 0 {
        let plural = match list {
            List::Vertex => "vertices",
            List::TexCoord => "texture coordinates",
            List::Normal => "normals",
        };
        let scope = if in_file { "in the file" } else { "before this line" };
        return format!("a {name} index, but there are no {plural} {scope}");
    }
    format!("a {name} index from 1 to {count} or from -{count} to -1")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<LoadedMesh, MeshIoError> {
        read_obj(text.as_bytes(), "t.obj")
    }

    fn err(text: &str) -> String {
        read(text).unwrap_err().to_string()
    }

    #[test]
    fn forms_and_relative_indices() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n\
                    f 1/1/1 2/2/1 3/3/1\nf -3/-3/-1 -2/-2/-1 -1/-1/-1\n";
        let m = read(text).unwrap().mesh;
        assert_eq!(m.face_vertices, vec![0, 1, 2, 0, 1, 2]);
        assert_eq!(m.uvs.as_ref().unwrap().indices, vec![0, 1, 2, 0, 1, 2]);
        assert_eq!(m.normals.as_ref().unwrap().indices, vec![0; 6]);
        assert_eq!(m.uvs.unwrap().values[1], DVec2::new(1.0, 0.0));
        let m = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n").unwrap().mesh;
        assert!(m.uvs.is_none());
        assert_eq!(m.normals.unwrap().indices, vec![0; 3]);
        let m = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nf 1/1 2/1 3/1\n").unwrap().mesh;
        assert_eq!(m.uvs.unwrap().values, vec![DVec2::new(0.5, 0.0)]);
    }

    #[test]
    fn colours_and_weights() {
        let m = read("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n").unwrap();
        assert_eq!(m.mesh.colors, vec![DVec3::X, DVec3::Y, DVec3::Z]);
        assert!(m.warnings.is_empty());
        let m = read("v 0 0 0 1\nv 1 0 0 2\nv 0 1 0 3\nf 1 2 3\n").unwrap();
        assert!(m.mesh.colors.is_empty());
        assert_eq!(m.mesh.positions[2], DVec3::Y);
        let m = read("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n").unwrap();
        assert!(m.mesh.colors.is_empty());
        assert_eq!(
            m.warnings[0].to_string(),
            "dropped the vertex colours: 2 vertices have one, 1 do not (the first at line 2)"
        );
    }

    #[test]
    fn mixed_attributes_are_dropped_with_a_warning() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\n\
                    f 1/1 2/1 3/1\nf 2/1 4 3\n";
        let m = read(text).unwrap();
        assert!(m.mesh.uvs.is_none());
        assert_eq!(
            m.warnings[0].to_string(),
            "dropped the texture coordinates: 1 faces have them, 1 do not (the first at line 7)"
        );
    }

    #[test]
    fn ignored_and_unknown_statements() {
        let text = "# c\nmtllib a.mtl\no obj\ng grp\ns 1\nusemtl m\nv 0 0 0 # inline\nv 1 0 0\nv 0 1 0\n\
                    l 1 2\np 1\nvp 0.5\n<html><pre># x\nf 1 2 3\nl 2 3\nl 3 1\nlod 1\nbevel off\n\n";
        let m = read(text).unwrap();
        assert_eq!(m.mesh.num_faces(), 1);
        let w: Vec<String> = m.warnings.iter().map(ToString::to_string).collect();
        // One warning per kind of geometry skipped (#39), in the order of their first lines.
        assert_eq!(
            w,
            vec![
                r#"line 10: skipped 3 "l" statements, the first on this line (lines are not read)"#,
                r#"line 11: skipped 1 "p" statement (points are not read)"#,
                r#"line 12: skipped 1 "vp" statement (free-form geometry is not read)"#,
                r#"line 13: skipped unknown statement "<html><pre># x""#,
            ]
        );
    }

    #[test]
    fn forward_references() {
        let m = read("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(m.mesh.face(0), &[0, 1, 2]);
        assert_eq!(
            err("f 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"),
            r#"t.obj:1:7: found "4", expected a vertex index from 1 to 3 or from -3 to -1"#
        );
    }

    #[test]
    fn errors_name_line_column_and_expectation() {
        let v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        assert_eq!(err("v 0 0\n"), "t.obj:1:6: found end of line, expected a number (z coordinate)");
        assert_eq!(err("v 0 0 0 1 2\n"), "t.obj:1:12: found end of line, expected a number (blue component)");
        assert_eq!(err("v 0 0 0 1 2 3 4\n"), r#"t.obj:1:15: found "4", expected end of line"#);
        assert_eq!(err("v 0 x 0\n"), r#"t.obj:1:5: found "x", expected a number (y coordinate)"#);
        assert_eq!(err("vn 0 0\n"), "t.obj:1:7: found end of line, expected a number (z component)");
        assert_eq!(err("vt\n"), "t.obj:1:3: found end of line, expected a number (u coordinate)");
        assert_eq!(
            err(&format!("{v3}f 1 0 3\n")),
            r#"t.obj:4:5: found "0", expected a non-zero vertex index (OBJ counts from 1)"#
        );
        assert_eq!(
            err(&format!("{v3}f 1 2 -4\n")),
            r#"t.obj:4:7: found "-4", expected a vertex index from 1 to 3 or from -3 to -1"#
        );
        for extreme in ["-9223372036854775808", "9223372036854775807", "99999999999999999999"] {
            assert!(err(&format!("{v3}f 1 2 {extreme}\n")).starts_with("t.obj:4:7: found "), "{extreme}");
        }
        assert_eq!(
            err(&format!("{v3}f 1/1 2 3\n")),
            r#"t.obj:4:5: found "1", expected a texture coordinate index, but there are no texture coordinates in the file"#
        );
        assert_eq!(
            err(&format!("{v3}f 1//x 2 3\n")),
            r#"t.obj:4:6: found "x", expected an integer normal index (in a vertex reference v, v/vt, v//vn or v/vt/vn)"#
        );
        assert_eq!(
            err(&format!("{v3}f 1/1/1/1 2 3\n")),
            r#"t.obj:4:3: found "1/1/1/1", expected a vertex reference v, v/vt, v//vn or v/vt/vn"#
        );
        assert_eq!(
            err(&format!("{v3}f /1 2 3\n")),
            r#"t.obj:4:3: found "/1", expected a vertex reference v, v/vt, v//vn or v/vt/vn"#
        );
        assert_eq!(
            err(&format!("{v3}f\n")),
            "t.obj:4:2: found end of line, expected a vertex reference v, v/vt, v//vn or v/vt/vn"
        );
        assert_eq!(
            err(&format!("{v3}f 1 2 3.0\n")),
            r#"t.obj:4:7: found "3.0", expected an integer vertex index (in a vertex reference v, v/vt, v//vn or v/vt/vn)"#
        );
        // Columns count characters, not bytes.
        assert_eq!(err("g é\nv 0 é 0\n"), r#"t.obj:2:5: found "é", expected a number (y coordinate)"#);
    }

    #[test]
    fn continued_lines_map_back_to_their_columns() {
        assert_eq!(continuation(b"f 1 2 \\"), Some(6));
        assert_eq!(continuation(b"f 1 2\\ \t"), Some(5));
        assert_eq!(continuation(b"f 1 2 # a\\"), None);
        assert_eq!(continuation(b"#\\"), None);
        assert_eq!(continuation(b"g a#b\\"), Some(5));
        assert_eq!(continuation(b"f 1 2"), None);
        // Columns count characters on each line.
        assert_eq!(err("v 0 é \\\n 0\n"), r#"t.obj:1:5: found "é", expected a number (y coordinate)"#);
        assert_eq!(err("v 0 0 \\\n   é\n"), r#"t.obj:2:4: found "é", expected a number (z coordinate)"#);
        assert_eq!(err("v 0 \\\n0 \\\n\t x\n"), r#"t.obj:3:3: found "x", expected a number (z coordinate)"#);
        assert_eq!(
            err("f \\\n \\\n"),
            "t.obj:1:2: found end of line, expected a vertex reference v, v/vt, v//vn or v/vt/vn"
        );
    }

    #[test]
    fn crlf_short_faces_and_trailing_slash() {
        let m = read("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1/ 2/ 3/\r\nf 1 2\r\n").unwrap().mesh;
        assert_eq!(m.face_offsets, vec![0, 3, 5]);
        assert!(m.uvs.is_none());
    }
}
