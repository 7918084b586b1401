//! OpenSubdiv's OBJ tags (its shape files' extension): sharp and semi-sharp edges and vertices,
//! and the subdivision options a mesh asks for, read in `.obj` files
//! ([`read_obj`](super::read_obj)); crease side files ([`read_creases`]) hold the crease and
//! corner tags, written by [`write_creases`].
//!
//! ```text
//! t crease 2/1 0 1 2.5          # edge 0–1, sharpness 2.5
//! t crease 5/1 4 5 7 6 4 10     # the chain 4–5–7–6–4, infinitely sharp
//! t crease 3/2 0 8 16 1 0.5     # 0–8 sharpness 1, 8–16 sharpness 0.5
//! t corner 1/1 3 1.25           # vertex 3, sharpness 1.25
//! t corner 2/1 0 7 10           # vertices 0 and 7, infinitely sharp
//! t interpolateboundary 1/0/0 1 # boundary: 0 none, 1 edge and corner, 2 edge only
//! t creasemethod 0/0/1 chaikin  # how creases pass to their halves: normal (uniform) or chaikin
//! t smoothtriangles 0/0/1 smooth # Catmull-Clark's edge points next to triangles: catmark or smooth
//! ```
//!
//! A tag line is `t NAME I/F[/S]` and then `I` integers, `F` numbers and `S` strings. Vertices
//! are **0-based** (as in OpenSubdiv's shape files, unlike OBJ's faces). `crease` lists a chain
//! of `I ≥ 2` vertices — its `I − 1` edges — with one sharpness for all (`F = 1`) or one per
//! edge (`F = I − 1`); `corner` lists `I ≥ 1` vertices with one sharpness or one each.
//! Sharpness is a number ≥ 0: 0 is smooth, 10 or more infinitely sharp (see
//! [`splinekit::subdiv::crease`]). `interpolateboundary`, `creasemethod` and `smoothtriangles`
//! take the values OpenSubdiv's shape reader gives them (into [`SubdivTags`]); when a tag is
//! given twice the last counts. Other tags (`hole`, `facevaryinginterpolateboundary`, …) are
//! skipped with a warning.

use std::io::{Read, Write};

use splinekit::subdiv::{Creases, CreasingMethod, EdgeCrease, TriangleSubdivision, VertexCrease};

use super::load::{self, ReadWarningKind, Warnings, next_token, parse_f64, parse_i64};
use super::{MeshIoError, MeshIoErrorKind};
use crate::swp::SourcePos;

/// A vertex index of a tag, checked against the vertex count at the end of the file.
struct VertexRef {
    index: u32,
    token: String,
    pos: SourcePos,
}

/// How boundary vertices are interpolated: OpenSubdiv's `Sdc::Options::VtxBoundaryInterpolation`,
/// set by a `t interpolateboundary 1/0/0 N` tag.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoundaryInterpolation {
    /// `N = 0`, `VTX_BOUNDARY_NONE`: the faces at the boundary are holes (not drawn).
    None,
    /// `N = 1`, `VTX_BOUNDARY_EDGE_AND_CORNER`: boundary edges are sharp creases and a boundary
    /// vertex of one face a sharp corner.
    EdgeAndCorner,
    /// `N = 2`, `VTX_BOUNDARY_EDGE_ONLY`: boundary edges are sharp creases.
    EdgeOnly,
}

/// The subdivision options an OBJ file's tags ask for; `None` where it has no such tag.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SubdivTags {
    /// `t interpolateboundary 1/0/0 N`.
    pub boundary: Option<BoundaryInterpolation>,
    /// `t creasemethod 0/0/1 normal|chaikin` (`normal` is [`CreasingMethod::Uniform`]).
    pub creasing: Option<CreasingMethod>,
    /// `t smoothtriangles 0/0/1 catmark|smooth` (Catmull-Clark only).
    pub triangles: Option<TriangleSubdivision>,
}

impl SubdivTags {
    /// No option tag.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }
}

/// Collects the tags of a file.
#[derive(Default)]
pub(crate) struct Tags {
    creases: Creases,
    refs: Vec<VertexRef>,
    options: SubdivTags,
}

impl Tags {
    /// Reads the rest of the `t` statement `line` (number `no`) from byte `pos`.
    pub(crate) fn statement(
        &mut self,
        origin: &str,
        no: usize,
        line: &[u8],
        mut pos: usize,
        warnings: &mut Warnings,
    ) -> Result<(), MeshIoError> {
        let unexpected = |offset: usize, token: &[u8], expected: &str| {
            load::unexpected(origin, no, line, offset, token, String::from(expected))
        };
        let end_of = |pos: usize| (pos, &b""[..]);
        let Some((_, name)) = next_token(line, &mut pos) else {
            let (at, t) = end_of(pos);
            return Err(unexpected(at, t, "a tag name (crease or corner)"));
        };
        if matches!(name, b"interpolateboundary" | b"creasemethod" | b"smoothtriangles") {
            return self.option(name, line, pos, &unexpected);
        }
        if name != b"crease" && name != b"corner" {
            warnings.push(no, ReadWarningKind::SkippedTag { name: String::from_utf8_lossy(name).into_owned() });
            return Ok(());
        }
        let crease = name == b"crease";
        let counts_form = "argument counts I/F (integers/numbers), like 2/1";
        let (at, counts) = next_token(line, &mut pos).unwrap_or(end_of(pos));
        let mut parts = counts.split(|&b| b == b'/').map(|p| parse_i64(p).filter(|&n| (0..=1 << 20).contains(&n)));
        let (Some(Some(ni)), Some(Some(nf)), None | Some(Some(0))) = (parts.next(), parts.next(), parts.next()) else {
            return Err(unexpected(at, counts, counts_form));
        };
        let (ni, nf) = (ni as usize, nf as usize);
        let items = if crease { ni.saturating_sub(1) } else { ni };
        if items == 0 || (nf != 1 && nf != items) {
            let expected = if crease {
                "a chain of at least 2 vertices with 1 sharpness or one per edge (like 2/1 or 3/2)"
            } else {
                "at least 1 vertex with 1 sharpness or one per vertex (like 1/1 or 2/2)"
            };
            return Err(unexpected(at, counts, expected));
        }
        let mut vertices = Vec::with_capacity(ni);
        for _ in 0..ni {
            let (at, token) = next_token(line, &mut pos).unwrap_or(end_of(pos));
            let index = parse_i64(token)
                .filter(|&k| (0..i64::from(u32::MAX)).contains(&k))
                .ok_or_else(|| unexpected(at, token, "a vertex index (0-based)"))?;
            self.refs.push(VertexRef {
                index: index as u32,
                token: String::from_utf8_lossy(token).into_owned(),
                pos: SourcePos::new(no, load::column(line, at)),
            });
            vertices.push(index as u32);
        }
        let mut sharpness = Vec::with_capacity(nf);
        for _ in 0..nf {
            let (at, token) = next_token(line, &mut pos).unwrap_or(end_of(pos));
            let s = parse_f64(token)
                .filter(|s| *s >= 0.0)
                .ok_or_else(|| unexpected(at, token, "a sharpness (a number ≥ 0)"))?;
            sharpness.push(s as f32);
        }
        if let Some((at, token)) = next_token(line, &mut pos) {
            return Err(unexpected(at, token, "end of line (the counts say there is nothing more)"));
        }
        let s = |k: usize| if nf == 1 { sharpness[0] } else { sharpness[k] };
        if crease {
            self.creases.edges.extend(vertices.windows(2).enumerate().map(|(k, w)| EdgeCrease {
                a: w[0],
                b: w[1],
                sharpness: s(k),
            }));
        } else {
            self.creases
                .vertices
                .extend(vertices.iter().enumerate().map(|(k, &vertex)| VertexCrease { vertex, sharpness: s(k) }));
        }
        Ok(())
    }

    /// Reads the rest of an option tag `name` (`interpolateboundary`, `creasemethod` or
    /// `smoothtriangles`) from byte `pos` of `line`; `unexpected` makes its errors.
    fn option(
        &mut self,
        name: &[u8],
        line: &[u8],
        mut pos: usize,
        unexpected: &dyn Fn(usize, &[u8], &str) -> MeshIoError,
    ) -> Result<(), MeshIoError> {
        let boundary = name == b"interpolateboundary";
        let (at, counts) = next_token(line, &mut pos).unwrap_or((pos, &b""[..]));
        let parts: Vec<Option<i64>> = counts.split(|&b| b == b'/').map(parse_i64).collect();
        let given = match parts[..] {
            [Some(i), Some(f)] => Some((i, f, 0)),
            [Some(i), Some(f), Some(s)] => Some((i, f, s)),
            _ => None,
        };
        let (want, form) =
            if boundary { ((1, 0, 0), "1/0/0 (one integer)") } else { ((0, 0, 1), "0/0/1 (one string)") };
        if given != Some(want) {
            return Err(unexpected(at, counts, &format!("argument counts {form}")));
        }
        let (at, value) = next_token(line, &mut pos).unwrap_or((pos, &b""[..]));
        match name {
            b"interpolateboundary" => {
                self.options.boundary = Some(match parse_i64(value) {
                    Some(0) => BoundaryInterpolation::None,
                    Some(1) => BoundaryInterpolation::EdgeAndCorner,
                    Some(2) => BoundaryInterpolation::EdgeOnly,
                    _ => return Err(unexpected(at, value, "0 (none), 1 (edge and corner) or 2 (edge only)")),
                });
            }
            b"creasemethod" => {
                self.options.creasing = Some(match value {
                    b"normal" => CreasingMethod::Uniform,
                    b"chaikin" => CreasingMethod::Chaikin,
                    _ => return Err(unexpected(at, value, "normal or chaikin")),
                });
            }
            _ => {
                self.options.triangles = Some(match value {
                    b"catmark" => TriangleSubdivision::Catmark,
                    b"smooth" => TriangleSubdivision::Smooth,
                    _ => return Err(unexpected(at, value, "catmark or smooth")),
                });
            }
        }
        if let Some((at, token)) = next_token(line, &mut pos) {
            return Err(unexpected(at, token, "end of line (the counts say there is nothing more)"));
        }
        Ok(())
    }

    /// The option tags read.
    pub(crate) fn options(&self) -> SubdivTags {
        self.options
    }

    /// How many vertex references the tags have so far.
    pub(crate) fn num_refs(&self) -> usize {
        self.refs.len()
    }

    /// Moves the positions of the vertex references from the `from`-th on through `map`.
    pub(crate) fn map_refs(&mut self, from: usize, map: impl Fn(SourcePos) -> SourcePos) {
        for r in &mut self.refs[from..] {
            r.pos = map(r.pos);
        }
    }

    /// The creases, every vertex index checked against `num_vertices`.
    pub(crate) fn finish(self, origin: &str, num_vertices: usize) -> Result<Creases, MeshIoError> {
        if let Some(r) = self.refs.iter().find(|r| r.index as usize >= num_vertices) {
            let expected = if num_vertices == 0 {
                String::from("a vertex index, but there are no vertices")
            } else {
                format!("a vertex index from 0 to {} (tags count vertices from 0)", num_vertices - 1)
            };
            let kind = MeshIoErrorKind::UnexpectedToken { found: r.token.clone(), expected };
            return Err(MeshIoError::at(origin, r.pos, kind));
        }
        Ok(self.creases)
    }
}

/// Reads a crease side file: `t crease` and `t corner` tags (OpenSubdiv's OBJ extension:
/// `t crease 2/1 A B S` for the edge A–B with sharpness S, `t crease 3/1 A B C S` for a
/// chain, `t corner 1/1 V S`), comments and empty lines, for a mesh of `num_vertices` vertices; `origin` names it in errors.
///
/// # Errors
/// A [`MeshIoError`] at `origin:LINE:COL` for any other statement, a malformed tag or a vertex
/// index out of range.
pub fn read_creases<R: Read>(reader: R, origin: &str, num_vertices: usize) -> Result<Creases, MeshIoError> {
    let bytes = load::read_all(reader, origin)?;
    let mut tags = Tags::default();
    let mut warnings = Warnings::default();
    for (no, line) in load::lines(&bytes) {
        let mut pos = 0;
        let Some((at, key)) = next_token(line, &mut pos) else { continue };
        if key != b"t" {
            return Err(load::unexpected(
                origin,
                no,
                line,
                at,
                key,
                String::from("a tag line `t crease …` or `t corner …`"),
            ));
        }
        let mut peek = pos;
        if let Some((at, name @ (b"interpolateboundary" | b"creasemethod" | b"smoothtriangles"))) =
            next_token(line, &mut peek)
        {
            let expected = String::from("a crease or corner tag (option tags go in the mesh file)");
            return Err(load::unexpected(origin, no, line, at, name, expected));
        }
        tags.statement(origin, no, line, pos, &mut warnings)?;
    }
    tags.finish(origin, num_vertices)
}

/// Writes `creases` as tag lines: one `t crease 2/1 a b s` per edge, one `t corner 1/1 v s`
/// per vertex (shortest round-trip numbers), so that [`read_creases`] and
/// [`read_obj`](super::read_obj) give them back exactly.
///
/// # Errors
/// The writer's.
pub fn write_creases<W: Write + ?Sized>(creases: &Creases, out: &mut W) -> std::io::Result<()> {
    for e in &creases.edges {
        writeln!(out, "t crease 2/1 {} {} {}", e.a, e.b, e.sharpness)?;
    }
    for v in &creases.vertices {
        writeln!(out, "t corner 1/1 {} {}", v.vertex, v.sharpness)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::read_obj;

    const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

    fn obj(tags: &str) -> Result<(Creases, Vec<String>), String> {
        read_obj(format!("{QUAD}{tags}").as_bytes(), "q.obj")
            .map(|l| (l.creases, l.warnings.iter().map(ToString::to_string).collect()))
            .map_err(|e| e.to_string())
    }

    fn edge(a: u32, b: u32, sharpness: f32) -> EdgeCrease {
        EdgeCrease { a, b, sharpness }
    }

    #[test]
    fn chains_corners_and_per_item_sharpness() {
        let (c, warnings) = obj("t crease 2/1 0 1 2.5\nt crease 5/1 0 1 2 3 0 10\nt crease 3/2 3 2 1 1 0.5\n\
                                 t corner 1/1 3 1.25\nt corner 2/2 0 2 10 0.75\nt hole 1/0 0\n")
        .unwrap();
        assert_eq!(
            c.edges,
            [edge(0, 1, 2.5), edge(0, 1, 10.0), edge(1, 2, 10.0), edge(2, 3, 10.0), edge(3, 0, 10.0)]
                .into_iter()
                .chain([edge(3, 2, 1.0), edge(2, 1, 0.5)])
                .collect::<Vec<_>>()
        );
        let v: Vec<(u32, f32)> = c.vertices.iter().map(|v| (v.vertex, v.sharpness)).collect();
        assert_eq!(v, [(3, 1.25), (0, 10.0), (2, 0.75)]);
        assert_eq!(
            warnings,
            [
                r#"line 11: skipped tag "hole" (only crease, corner, interpolateboundary, creasemethod and smoothtriangles are read)"#
            ]
        );
    }

    fn options(tags: &str) -> Result<SubdivTags, String> {
        read_obj(format!("{QUAD}{tags}").as_bytes(), "q.obj").map(|l| l.subdiv_tags).map_err(|e| e.to_string())
    }

    /// The values OpenSubdiv's shape reader (`regression/common/far_utils.h`) gives the option
    /// tags; the last of a kind counts.
    #[test]
    fn option_tags_as_opensubdiv_reads_them() {
        assert!(options("").unwrap().is_empty());
        let boundary = |n: &str| options(&format!("t interpolateboundary 1/0/0 {n}\n")).unwrap().boundary;
        assert_eq!(boundary("0"), Some(BoundaryInterpolation::None));
        assert_eq!(boundary("1"), Some(BoundaryInterpolation::EdgeAndCorner));
        assert_eq!(boundary("2"), Some(BoundaryInterpolation::EdgeOnly));
        let both =
            options("t creasemethod 0/0/1 normal\nt smoothtriangles 0/0/1 smooth\nt creasemethod 0/0/1 chaikin\n");
        let expected = SubdivTags {
            boundary: None,
            creasing: Some(CreasingMethod::Chaikin),
            triangles: Some(TriangleSubdivision::Smooth),
        };
        assert_eq!(both.unwrap(), expected);
        assert_eq!(options("t creasemethod 0/0/1 normal\n").unwrap().creasing, Some(CreasingMethod::Uniform));
        assert_eq!(options("t smoothtriangles 0/0/1 catmark\n").unwrap().triangles, Some(TriangleSubdivision::Catmark));
        // the I/F form without strings, as for creases
        assert_eq!(options("t interpolateboundary 1/0 2\n").unwrap().boundary, Some(BoundaryInterpolation::EdgeOnly));
        let err = |tags: &str| options(tags).unwrap_err();
        assert_eq!(
            err("t interpolateboundary 1/0/0 3\n"),
            r#"q.obj:6:29: found "3", expected 0 (none), 1 (edge and corner) or 2 (edge only)"#
        );
        assert_eq!(
            err("t interpolateboundary 0/0/1 edge\n"),
            r#"q.obj:6:23: found "0/0/1", expected argument counts 1/0/0 (one integer)"#
        );
        assert_eq!(err("t creasemethod 0/0/1 uniform\n"), r#"q.obj:6:22: found "uniform", expected normal or chaikin"#);
        assert_eq!(err("t smoothtriangles 0/0/1\n"), "q.obj:6:24: found end of line, expected catmark or smooth");
        assert_eq!(
            err("t creasemethod 0/0/1 chaikin x\n"),
            r#"q.obj:6:30: found "x", expected end of line (the counts say there is nothing more)"#
        );
        // not in side files, which hold creases
        let side = read_creases("t interpolateboundary 1/0/0 1\n".as_bytes(), "c.txt", 4).unwrap_err();
        assert_eq!(
            side.to_string(),
            r#"c.txt:1:3: found "interpolateboundary", expected a crease or corner tag (option tags go in the mesh file)"#
        );
    }

    #[test]
    fn errors_name_line_column_and_expectation() {
        let err = |tags: &str| obj(tags).unwrap_err();
        assert_eq!(
            err("t crease 2 0 1 1\n"),
            r#"q.obj:6:10: found "2", expected argument counts I/F (integers/numbers), like 2/1"#
        );
        assert_eq!(
            err("t crease 1/1 0 1\n"),
            r#"q.obj:6:10: found "1/1", expected a chain of at least 2 vertices with 1 sharpness or one per edge (like 2/1 or 3/2)"#
        );
        assert_eq!(
            err("t corner 2/3 0 1 1 1 1\n"),
            r#"q.obj:6:10: found "2/3", expected at least 1 vertex with 1 sharpness or one per vertex (like 1/1 or 2/2)"#
        );
        assert_eq!(err("t crease 2/1 0 x 1\n"), r#"q.obj:6:16: found "x", expected a vertex index (0-based)"#);
        assert_eq!(err("t crease 2/1 0 -1 1\n"), r#"q.obj:6:16: found "-1", expected a vertex index (0-based)"#);
        assert_eq!(err("t crease 2/1 0 1 -2\n"), r#"q.obj:6:18: found "-2", expected a sharpness (a number ≥ 0)"#);
        assert_eq!(err("t crease 2/1 0 1\n"), "q.obj:6:17: found end of line, expected a sharpness (a number ≥ 0)");
        assert_eq!(
            err("t crease 2/1 0 1 1 7\n"),
            r#"q.obj:6:20: found "7", expected end of line (the counts say there is nothing more)"#
        );
        assert_eq!(
            err("t crease 2/1 0 4 1\n"),
            r#"q.obj:6:16: found "4", expected a vertex index from 0 to 3 (tags count vertices from 0)"#
        );
        assert_eq!(err("t\n"), "q.obj:6:2: found end of line, expected a tag name (crease or corner)");
    }

    #[test]
    fn side_files_round_trip_and_reject_other_statements() {
        let creases = Creases {
            edges: vec![edge(0, 1, 2.5), edge(2, 3, 0.1), edge(1, 2, 10.0)],
            vertices: vec![VertexCrease { vertex: 3, sharpness: 1.0 / 3.0 }],
        };
        let mut text = Vec::new();
        write_creases(&creases, &mut text).unwrap();
        assert_eq!(
            String::from_utf8(text.clone()).unwrap(),
            "t crease 2/1 0 1 2.5\nt crease 2/1 2 3 0.1\nt crease 2/1 1 2 10\nt corner 1/1 3 0.33333334\n"
        );
        assert_eq!(read_creases(&text[..], "c.txt", 4).unwrap(), creases);
        let with_comments = b"# creases\n\nt crease 2/1 0 1 1 # the front\n";
        assert_eq!(read_creases(&with_comments[..], "c.txt", 2).unwrap().edges, [edge(0, 1, 1.0)]);
        let err = read_creases(&b"t crease 2/1 0 1 1\nv 0 0 0\n"[..], "c.txt", 4).unwrap_err();
        assert_eq!(err.to_string(), r#"c.txt:2:1: found "v", expected a tag line `t crease …` or `t corner …`"#);
        let err = read_creases(&text[..], "c.txt", 3).unwrap_err();
        assert_eq!(
            err.to_string(),
            r#"c.txt:2:16: found "3", expected a vertex index from 0 to 2 (tags count vertices from 0)"#
        );
    }
}
