//! Structure-aware mesh files: OBJ, PLY (ASCII, binary little and big endian), STL (ASCII
//! and binary) and binary glTF, valid in grammar, with extreme values and odd topology
//! (degenerate and duplicate faces, repeated and unreferenced vertices, non-manifold edges,
//! faces of one or two corners, large polygons, huge indices, negative OBJ indices). A few
//! files break one rule so that the errors are exercised too.

use std::fmt::Write as _;

use crate::rng::Rng;
use crate::values::{self, EXTREMES, Scale};

/// A mesh before it is written in some format.
#[derive(Clone, Debug, Default)]
pub struct MeshSpec {
    /// Vertex positions.
    pub positions: Vec<[f64; 3]>,
    /// Faces as 0-based vertex indices (in range unless a rule is broken on purpose).
    pub faces: Vec<Vec<usize>>,
    /// Per-vertex normals (empty or one per vertex).
    pub normals: Vec<[f64; 3]>,
    /// Per-vertex texture coordinates (empty or one per vertex).
    pub uvs: Vec<[f64; 2]>,
    /// Per-vertex colours (empty or one per vertex).
    pub colors: Vec<[f64; 3]>,
    /// OBJ crease tags: edges `(a, b, sharpness)`.
    pub creases: Vec<(usize, usize, f64)>,
    /// OBJ corner tags: `(vertex, sharpness)`.
    pub corners: Vec<(usize, f64)>,
}

/// Probability of breaking a rule at a given place.
const MISTAKES: f64 = 0.02;

/// A mesh: a shape (grid, closed solid, ring, fan, soup, non-manifold fin), its vertices
/// scaled by one scale for the mesh with some outliers, then odd topology on top.
pub fn mesh(rng: &mut Rng) -> MeshSpec {
    let scale = Scale::draw(rng);
    let mut m = MeshSpec::default();
    match rng.below(8) {
        0 => grid(rng, &mut m, false),
        1 => grid(rng, &mut m, true),
        2 => solid(rng, &mut m),
        3 => ring(rng, &mut m),
        4 => {
            // one polygon of many corners
            let n = rng.size(3, 300);
            for i in 0..n {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                m.positions.push([a.cos(), a.sin(), 0.0]);
            }
            m.faces.push((0..n).collect());
        }
        5 => soup(rng, &mut m),
        6 => {
            // a fin: k triangles on one edge (non-manifold for k > 2)
            m.positions.push([0.0, 0.0, 0.0]);
            m.positions.push([1.0, 0.0, 0.0]);
            for i in 0..rng.range(1, 6) {
                let a = i as f64;
                m.positions.push([0.5, a.cos(), a.sin()]);
                m.faces.push(vec![0, 1, i + 2]);
            }
        }
        _ => {
            // almost nothing: no faces, or no vertices at all
            for _ in 0..rng.below(4) {
                m.positions.push([0.0, 0.0, 0.0]);
            }
        }
    }
    for p in &mut m.positions {
        for x in p.iter_mut() {
            *x = *x * scale.magnitude + scale.magnitude * 0.01 * rng.uniform(-1.0, 1.0);
            if scale.outliers > 0.0 && rng.chance(scale.outliers) {
                *x = *rng.pick(&EXTREMES);
            }
        }
    }
    oddities(rng, &mut m, &scale);
    attributes(rng, &mut m);
    m
}

/// A `w × h` grid of quads or triangles.
fn grid(rng: &mut Rng, m: &mut MeshSpec, triangles: bool) {
    let (w, h) = (rng.size(1, 60), rng.size(1, 60));
    for j in 0..=h {
        for i in 0..=w {
            m.positions.push([i as f64 / w as f64, j as f64 / h as f64, 0.0]);
        }
    }
    let at = |i: usize, j: usize| j * (w + 1) + i;
    for j in 0..h {
        for i in 0..w {
            let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            if triangles {
                m.faces.push(vec![q[0], q[1], q[2]]);
                m.faces.push(vec![q[0], q[2], q[3]]);
            } else {
                m.faces.push(q.to_vec());
            }
        }
    }
}

/// A closed solid: tetrahedron, cube (quads) or octahedron.
fn solid(rng: &mut Rng, m: &mut MeshSpec) {
    match rng.below(3) {
        0 => {
            m.positions = vec![[1.0, 1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [-1.0, -1.0, 1.0]];
            m.faces = vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]];
        }
        1 => {
            for k in 0..8 {
                m.positions.push([(k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64]);
            }
            m.faces = vec![
                vec![0, 2, 3, 1],
                vec![4, 5, 7, 6],
                vec![0, 1, 5, 4],
                vec![2, 6, 7, 3],
                vec![0, 4, 6, 2],
                vec![1, 3, 7, 5],
            ];
        }
        _ => {
            m.positions = vec![
                [1.0, 0.0, 0.0],
                [-1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, -1.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.0, 0.0, -1.0],
            ];
            m.faces = vec![
                vec![0, 2, 4],
                vec![2, 1, 4],
                vec![1, 3, 4],
                vec![3, 0, 4],
                vec![2, 0, 5],
                vec![1, 2, 5],
                vec![3, 1, 5],
                vec![0, 3, 5],
            ];
        }
    }
}

/// A tube of quads, closed around.
fn ring(rng: &mut Rng, m: &mut MeshSpec) {
    let (w, h) = (rng.size(3, 40), rng.size(1, 20));
    for j in 0..=h {
        for i in 0..w {
            let a = std::f64::consts::TAU * i as f64 / w as f64;
            m.positions.push([a.cos(), a.sin(), j as f64]);
        }
    }
    for j in 0..h {
        for i in 0..w {
            let i1 = (i + 1) % w;
            m.faces.push(vec![j * w + i, j * w + i1, (j + 1) * w + i1, (j + 1) * w + i]);
        }
    }
}

/// Random faces on random vertices: anything goes (repeats, both orientations, overlaps).
fn soup(rng: &mut Rng, m: &mut MeshSpec) {
    let v = rng.size(1, 200);
    for _ in 0..v {
        m.positions.push([rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)]);
    }
    for _ in 0..rng.size(1, 400) {
        let n = if rng.chance(0.8) { 3 } else { rng.range(4, 8) };
        m.faces.push((0..n).map(|_| rng.below(v)).collect());
    }
}

/// Odd topology and geometry on top of a shape.
fn oddities(rng: &mut Rng, m: &mut MeshSpec, scale: &Scale) {
    let nv = m.positions.len();
    if nv > 0 && !m.faces.is_empty() {
        for _ in 0..rng.below(4) {
            match rng.below(7) {
                0 => {
                    let f = m.faces[rng.below(m.faces.len())].clone();
                    m.faces.push(f);
                }
                1 => {
                    let i = rng.below(m.faces.len());
                    m.faces[i].reverse();
                }
                2 => {
                    let i = rng.below(m.faces.len());
                    let f = &mut m.faces[i];
                    let k = rng.below(f.len());
                    let (next, v) = ((k + 1) % f.len(), f[k]);
                    f[next] = v;
                }
                3 => m.positions.push([scale.magnitude; 3]),
                4 => {
                    let n = rng.range(1, 2);
                    m.faces.push((0..n).map(|_| rng.below(nv)).collect());
                }
                5 => {
                    // collapse every position to one point (zero-area faces)
                    let p = m.positions[0];
                    m.positions.iter_mut().for_each(|q| *q = p);
                }
                _ => {
                    let i = rng.below(m.faces.len());
                    let f = m.faces[i].clone();
                    let extra = rng.below(nv);
                    m.faces.push(vec![f[0], f[f.len() - 1], extra]);
                }
            }
        }
    }
    if rng.chance(MISTAKES) && !m.faces.is_empty() {
        let i = rng.below(m.faces.len());
        m.faces[i][0] = nv + rng.below(3);
    }
    if nv > 1 && rng.chance(0.1) {
        for _ in 0..rng.range(1, 5) {
            let (a, b) = (rng.below(nv), rng.below(nv));
            m.creases.push((a, b, sharpness(rng)));
        }
        if rng.chance(0.5) {
            m.corners.push((rng.below(nv), sharpness(rng)));
        }
    }
}

/// A crease sharpness: 0 to 10, infinitely sharp, or extreme.
fn sharpness(rng: &mut Rng) -> f64 {
    match rng.below(8) {
        0 => *rng.pick(&[0.0, 10.0, 1e300, 1e-300, 3.5e38, 1e39]),
        _ => rng.uniform(0.0, 5.0),
    }
}

/// Normals, texture coordinates and colours, now and then.
fn attributes(rng: &mut Rng, m: &mut MeshSpec) {
    let n = m.positions.len();
    // a value in [lo, hi), now and then an extreme one
    let value =
        |rng: &mut Rng, lo: f64, hi: f64| if rng.chance(0.01) { *rng.pick(&EXTREMES) } else { rng.uniform(lo, hi) };
    if rng.chance(0.3) {
        m.normals = (0..n).map(|_| [value(rng, -1.0, 1.0), value(rng, -1.0, 1.0), 0.5]).collect();
    }
    if rng.chance(0.3) {
        m.uvs = (0..n).map(|_| [value(rng, 0.0, 1.0), value(rng, 0.0, 1.0)]).collect();
    }
    if rng.chance(0.2) {
        m.colors = (0..n).map(|_| [value(rng, 0.0, 1.0), value(rng, 0.0, 1.0), value(rng, 0.0, 1.0)]).collect();
    }
}

/// Pushes a line of text and a line end (LF, sometimes CRLF).
fn line(out: &mut String, rng: &mut Rng, text: &str) {
    out.push_str(text);
    out.push_str(if rng.chance(0.1) { "\r\n" } else { "\n" });
}

/// Numbers joined by spaces.
fn nums(rng: &mut Rng, xs: &[f64]) -> String {
    let parts: Vec<String> = xs.iter().map(|&x| values::format(rng, x)).collect();
    parts.join(if rng.chance(0.1) { "\t" } else { " " })
}

/// A Wavefront OBJ file.
pub fn obj(rng: &mut Rng, m: &MeshSpec) -> Vec<u8> {
    let mut out = String::new();
    if rng.chance(0.05) {
        out.push('\u{feff}');
    }
    if rng.chance(0.3) {
        line(&mut out, rng, "# generated by splinekit-fuzz");
    }
    if rng.chance(0.1) {
        let junk = *rng.pick(&["<html><pre>", "mtllib a.mtl", "o thing", "vp 0.5 0.5", "curv 0 1 1 2", "g a b"]);
        line(&mut out, rng, junk);
    }
    let n = m.positions.len();
    let w = rng.chance(0.1);
    for (i, p) in m.positions.iter().enumerate() {
        let mut xs = p.to_vec();
        if let Some(c) = m.colors.get(i) {
            xs.extend(c);
        } else if w {
            xs.push(1.0);
        }
        let text = format!("v {}", nums(rng, &xs));
        line(&mut out, rng, &text);
    }
    for t in &m.uvs {
        let text = format!("vt {}", nums(rng, t));
        line(&mut out, rng, &text);
    }
    for v in &m.normals {
        let text = format!("vn {}", nums(rng, v));
        line(&mut out, rng, &text);
    }
    if rng.chance(0.2) {
        let s = *rng.pick(&["s off", "s 1", "usemtl red", "g part"]);
        line(&mut out, rng, s);
    }
    let negative = rng.chance(0.2);
    for f in &m.faces {
        let mut text = String::from("f");
        for &v in f {
            // 1-based, or negative: relative to the end of the lists
            let index = |k: usize, count: usize| -> String {
                if negative && k < count { format!("{}", k as i64 - count as i64) } else { format!("{}", k + 1) }
            };
            let pos = index(v, n);
            let has_t = !m.uvs.is_empty();
            let has_n = !m.normals.is_empty();
            let _ = match (has_t, has_n) {
                (true, true) => write!(text, " {pos}/{}/{}", index(v, m.uvs.len()), index(v, m.normals.len())),
                (true, false) => write!(text, " {pos}/{}", index(v, m.uvs.len())),
                (false, true) => write!(text, " {pos}//{}", index(v, m.normals.len())),
                (false, false) => write!(text, " {pos}"),
            };
        }
        if rng.chance(MISTAKES) {
            let bad = *rng.pick(&[" 0", " 99999999999999999999", " -99999", " 1//", " 1/2/3/4", " x"]);
            text.push_str(bad);
        }
        if rng.chance(0.02) {
            text.push_str(" # trailing comment");
        }
        line(&mut out, rng, &text);
    }
    for &(a, b, s) in &m.creases {
        let text = format!("t crease 2/1 {a} {b} {}", values::format(rng, s));
        line(&mut out, rng, &text);
    }
    for &(v, s) in &m.corners {
        let text = format!("t corner 1/1 {v} {}", values::format(rng, s));
        line(&mut out, rng, &text);
    }
    if rng.chance(0.05) {
        line(&mut out, rng, "t hole 1/0 0");
    }
    if rng.chance(0.05) {
        out.push_str("f 1 2");
    }
    out.into_bytes()
}

/// A PLY property type, with its size in bytes and whether it is a float.
#[derive(Clone, Copy, Debug)]
struct PlyType {
    name: &'static str,
    size: usize,
    float: bool,
    signed: bool,
}

const PLY_FLOAT: PlyType = PlyType { name: "float", size: 4, float: true, signed: true };
const PLY_DOUBLE: PlyType = PlyType { name: "double", size: 8, float: true, signed: true };
const PLY_TYPES: [PlyType; 10] = [
    PLY_FLOAT,
    PLY_DOUBLE,
    PlyType { name: "float32", size: 4, float: true, signed: true },
    PlyType { name: "float64", size: 8, float: true, signed: true },
    PlyType { name: "int", size: 4, float: false, signed: true },
    PlyType { name: "short", size: 2, float: false, signed: true },
    PlyType { name: "char", size: 1, float: false, signed: true },
    PlyType { name: "uchar", size: 1, float: false, signed: false },
    PlyType { name: "uint16", size: 2, float: false, signed: false },
    PlyType { name: "uint", size: 4, float: false, signed: false },
];
/// Types for list counts and face indices.
const PLY_INDEX_TYPES: [PlyType; 6] = [
    PlyType { name: "uchar", size: 1, float: false, signed: false },
    PlyType { name: "uint8", size: 1, float: false, signed: false },
    PlyType { name: "ushort", size: 2, float: false, signed: false },
    PlyType { name: "int", size: 4, float: false, signed: true },
    PlyType { name: "uint", size: 4, float: false, signed: false },
    PlyType { name: "int32", size: 4, float: false, signed: true },
];

/// PLY encodings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlyEncoding {
    /// `format ascii 1.0`.
    Ascii,
    /// `format binary_little_endian 1.0`.
    Little,
    /// `format binary_big_endian 1.0`.
    Big,
}

/// Writes one value of type `t` (clamped to an integer type's range).
fn ply_value(out: &mut Vec<u8>, rng: &mut Rng, encoding: PlyEncoding, t: PlyType, x: f64) {
    if encoding == PlyEncoding::Ascii {
        if out.last().is_some_and(|&b| b != b'\n') {
            out.push(b' ');
        }
        let text = if t.float { values::format(rng, x) } else { format!("{}", int_of(t, x)) };
        out.extend_from_slice(text.as_bytes());
        return;
    }
    let big = encoding == PlyEncoding::Big;
    let bytes: Vec<u8> = match (t.float, t.size) {
        (true, 4) => {
            let v = x as f32;
            if big { v.to_be_bytes().to_vec() } else { v.to_le_bytes().to_vec() }
        }
        (true, _) => {
            if big {
                x.to_be_bytes().to_vec()
            } else {
                x.to_le_bytes().to_vec()
            }
        }
        (false, size) => {
            let v = int_of(t, x);
            let all = if big { v.to_be_bytes() } else { v.to_le_bytes() };
            if big { all[8 - size..].to_vec() } else { all[..size].to_vec() }
        }
    };
    out.extend_from_slice(&bytes);
}

/// `x` rounded into the range of integer type `t`.
fn int_of(t: PlyType, x: f64) -> i64 {
    let bits = 8 * t.size as u32;
    let (lo, hi) =
        if t.signed { (-(1i64 << (bits - 1)), (1i64 << (bits - 1)) - 1) } else { (0, ((1u64 << bits) - 1) as i64) };
    (x.round() as i64).clamp(lo, hi)
}

/// A PLY file in `encoding`.
pub fn ply(rng: &mut Rng, m: &MeshSpec, encoding: PlyEncoding) -> Vec<u8> {
    let mut h = String::from("ply\n");
    let format = match encoding {
        PlyEncoding::Ascii => "ascii",
        PlyEncoding::Little => "binary_little_endian",
        PlyEncoding::Big => "binary_big_endian",
    };
    let _ = writeln!(h, "format {format} 1.0");
    if rng.chance(0.3) {
        h.push_str("comment made by splinekit-fuzz\nobj_info nothing\n");
    }
    // vertex properties: (type, value source)
    let coord_type = if rng.chance(0.8) { *rng.pick(&[PLY_FLOAT, PLY_DOUBLE]) } else { *rng.pick(&PLY_TYPES) };
    let mut props: Vec<(PlyType, &str, usize)> = vec![(coord_type, "x", 0), (coord_type, "y", 1), (coord_type, "z", 2)];
    if !m.normals.is_empty() {
        props.extend([(PLY_FLOAT, "nx", 3), (PLY_FLOAT, "ny", 4), (PLY_FLOAT, "nz", 5)]);
    }
    if !m.colors.is_empty() {
        let t = if rng.chance(0.5) { PLY_TYPES[7] } else { PLY_FLOAT };
        let names =
            if rng.chance(0.5) { ["red", "green", "blue"] } else { ["diffuse_red", "diffuse_green", "diffuse_blue"] };
        props.extend(names.iter().enumerate().map(|(k, &n)| (t, n, 6 + k)));
    }
    if !m.uvs.is_empty() {
        let names = *rng.pick(&[["u", "v"], ["s", "t"], ["texture_u", "texture_v"], ["texture_s", "texture_t"]]);
        props.extend(names.iter().enumerate().map(|(k, &n)| (PLY_FLOAT, n, 9 + k)));
    }
    if rng.chance(0.2) {
        props.push((*rng.pick(&PLY_TYPES), "confidence", 11));
    }
    if rng.chance(0.3) {
        props.reverse();
    }
    let count_type = *rng.pick(&PLY_INDEX_TYPES[..3]);
    let index_type = *rng.pick(&PLY_INDEX_TYPES);
    let faces_first = rng.chance(0.05);
    let vertex_header = {
        let mut s = format!("element vertex {}\n", m.positions.len());
        for (t, name, _) in &props {
            let _ = writeln!(s, "property {} {name}", t.name);
        }
        s
    };
    let list_name = if rng.chance(0.8) { "vertex_indices" } else { "vertex_index" };
    let face_header = format!(
        "element face {}\nproperty list {} {} {list_name}\n{}",
        m.faces.len(),
        count_type.name,
        index_type.name,
        if rng.chance(0.2) { "property uchar flags\n" } else { "" }
    );
    let edges = if rng.chance(0.1) { 2 } else { 0 };
    if faces_first {
        h.push_str(&face_header);
        h.push_str(&vertex_header);
    } else {
        h.push_str(&vertex_header);
        h.push_str(&face_header);
    }
    if edges > 0 {
        h.push_str("element edge 2\nproperty int vertex1\nproperty int vertex2\n");
    }
    h.push_str("end_header\n");
    let mut out = h.into_bytes();
    let has_flags = face_header.contains("flags");
    let newline = |out: &mut Vec<u8>| {
        if encoding == PlyEncoding::Ascii {
            out.push(b'\n');
        }
    };
    let write_vertices = |out: &mut Vec<u8>, rng: &mut Rng| {
        for i in 0..m.positions.len() {
            for &(t, _, source) in &props {
                let x = match source {
                    0..=2 => m.positions[i][source],
                    3..=5 => m.normals[i][source - 3],
                    6..=8 => m.colors[i][source - 6] * if t.float { 1.0 } else { 255.0 },
                    9..=10 => m.uvs[i][source - 9],
                    _ => 0.5,
                };
                ply_value(out, rng, encoding, t, x);
            }
            newline(out);
        }
    };
    let write_faces = |out: &mut Vec<u8>, rng: &mut Rng| {
        for f in &m.faces {
            ply_value(out, rng, encoding, count_type, f.len() as f64);
            for &v in f {
                ply_value(out, rng, encoding, index_type, v as f64);
            }
            if has_flags {
                ply_value(out, rng, encoding, PLY_TYPES[7], 1.0);
            }
            newline(out);
        }
    };
    if faces_first {
        write_faces(&mut out, rng);
        write_vertices(&mut out, rng);
    } else {
        write_vertices(&mut out, rng);
        write_faces(&mut out, rng);
    }
    for k in 0..edges {
        let t = PLY_INDEX_TYPES[3];
        ply_value(&mut out, rng, encoding, t, 0.0);
        ply_value(&mut out, rng, encoding, t, k as f64);
        newline(&mut out);
    }
    if rng.chance(MISTAKES) {
        out.truncate(out.len().saturating_sub(rng.range(1, 9)));
    }
    out
}

/// The triangles of a face, fanned from its first corner.
fn fan(f: &[usize]) -> impl Iterator<Item = [usize; 3]> + '_ {
    (1..f.len().saturating_sub(1)).map(move |k| [f[0], f[k], f[k + 1]])
}

/// The position of vertex `v`, or the origin for an index out of range.
fn position(m: &MeshSpec, v: usize) -> [f64; 3] {
    m.positions.get(v).copied().unwrap_or_default()
}

/// An ASCII STL file (polygons as `outer loop`s of any size, keywords in mixed case now and
/// then).
pub fn stl_ascii(rng: &mut Rng, m: &MeshSpec) -> Vec<u8> {
    let upper = rng.chance(0.1);
    let kw = |s: &str| if upper { s.to_uppercase() } else { s.to_owned() };
    let mut out = String::new();
    line(&mut out, rng, &format!("{} fuzz", kw("solid")));
    let polygons = rng.chance(0.3);
    for f in &m.faces {
        let loops: Vec<Vec<usize>> = if polygons { vec![f.clone()] } else { fan(f).map(|t| t.to_vec()).collect() };
        for l in loops {
            if l.len() < 3 && !rng.chance(MISTAKES) {
                continue;
            }
            let normal = nums(rng, &[0.0, 0.0, 1.0]);
            line(&mut out, rng, &format!("  {} {} {normal}", kw("facet"), kw("normal")));
            line(&mut out, rng, &format!("    {} {}", kw("outer"), kw("loop")));
            for &v in &l {
                let p = nums(rng, &position(m, v));
                line(&mut out, rng, &format!("      {} {p}", kw("vertex")));
            }
            line(&mut out, rng, &format!("    {}", kw("endloop")));
            line(&mut out, rng, &format!("  {}", kw("endfacet")));
        }
    }
    if !rng.chance(MISTAKES) {
        line(&mut out, rng, &format!("{} fuzz", kw("endsolid")));
    }
    out.into_bytes()
}

/// A binary STL file (its header starting with `solid` now and then, as many exporters
/// write; the triangle count wrong now and then).
pub fn stl_binary(rng: &mut Rng, m: &MeshSpec) -> Vec<u8> {
    let triangles: Vec<[usize; 3]> = m.faces.iter().flat_map(|f| fan(f)).collect();
    let mut out = vec![b' '; 80];
    if rng.chance(0.3) {
        out[..11].copy_from_slice(b"solid fuzz\n");
    }
    let mut count = triangles.len() as u32;
    if rng.chance(MISTAKES) {
        count = count.wrapping_add(*rng.pick(&[1, u32::MAX, 1000]));
    }
    out.extend_from_slice(&count.to_le_bytes());
    for t in &triangles {
        for x in [0.0f32, 0.0, 1.0] {
            out.extend_from_slice(&x.to_le_bytes());
        }
        for &v in t {
            for x in position(m, v) {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    if rng.chance(0.05) {
        out.extend_from_slice(b"trailing");
    }
    out
}

/// Base64 (standard alphabet, padded), for `data:` URIs.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                s.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// A binary glTF file: one mesh of one primitive (triangles, or a strip or fan of the same
/// vertices), indexed by `u8`, `u16` or `u32` or not at all, with normals, UVs and colours
/// when the mesh has them, placed by one or more nodes with extreme transforms now and then,
/// its buffer in the `BIN` chunk or a `data:` URI.
pub fn glb(rng: &mut Rng, m: &MeshSpec) -> Vec<u8> {
    use serde_json::{Value, json};
    let mut bin: Vec<u8> = Vec::new();
    let mut views: Vec<Value> = Vec::new();
    let mut accessors: Vec<Value> = Vec::new();
    // one buffer view per accessor, 4-byte aligned
    let mut add = |bin: &mut Vec<u8>, data: &[u8], accessor: Value, stride: Option<usize>| -> usize {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let mut view = json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": data.len()});
        if let Some(s) = stride {
            view["byteStride"] = json!(s);
        }
        bin.extend_from_slice(data);
        views.push(view);
        let mut accessor = accessor;
        accessor["bufferView"] = json!(views.len() - 1);
        accessors.push(accessor);
        accessors.len() - 1
    };
    let f32s = |xs: &mut dyn Iterator<Item = f64>| -> Vec<u8> { xs.flat_map(|x| (x as f32).to_le_bytes()).collect() };
    let n = m.positions.len();
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in &m.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k] as f32 as f64);
            hi[k] = hi[k].max(p[k] as f32 as f64);
        }
    }
    let finite = |a: [f64; 3]| a.iter().all(|x| x.is_finite());
    let mut position_accessor = json!({"componentType": 5126, "count": n, "type": "VEC3"});
    if n > 0 && finite(lo) && finite(hi) {
        position_accessor["min"] = json!(lo);
        position_accessor["max"] = json!(hi);
    }
    let positions = f32s(&mut m.positions.iter().flatten().copied());
    let pos = add(&mut bin, &positions, position_accessor, if rng.chance(0.2) { Some(12) } else { None });
    let mut attributes = json!({"POSITION": pos});
    if !m.normals.is_empty() {
        let data = f32s(&mut m.normals.iter().flatten().copied());
        attributes["NORMAL"] =
            json!(add(&mut bin, &data, json!({"componentType": 5126, "count": n, "type": "VEC3"}), None));
    }
    if !m.uvs.is_empty() {
        let data = f32s(&mut m.uvs.iter().flatten().copied());
        attributes["TEXCOORD_0"] =
            json!(add(&mut bin, &data, json!({"componentType": 5126, "count": n, "type": "VEC2"}), None));
    }
    if !m.colors.is_empty() {
        // RGB in 4-byte elements: vertex attributes are 4-byte aligned, so the stride is 4
        let data: Vec<u8> = m
            .colors
            .iter()
            .flat_map(|c| {
                let [r, g, b] = c.map(|x| (x.clamp(0.0, 1.0) * 255.0) as u8);
                [r, g, b, 0]
            })
            .collect();
        let accessor = json!({"componentType": 5121, "normalized": true, "count": n, "type": "VEC3"});
        attributes["COLOR_0"] = json!(add(&mut bin, &data, accessor, Some(4)));
    }
    let mode = match rng.below(10) {
        0 => 5, // strip
        1 => 6, // fan
        2 => *rng.pick(&[0, 1, 2, 3]),
        _ => 4,
    };
    let indices: Vec<usize> = match mode {
        4 => m.faces.iter().flat_map(|f| fan(f)).flatten().collect(),
        _ => m.faces.iter().flatten().copied().collect(),
    };
    let mut primitive = json!({"attributes": attributes, "mode": mode});
    if rng.chance(0.9) || n == 0 {
        let (component, size) = match rng.below(3) {
            0 if n <= 256 => (5121, 1),
            1 if n <= 65_536 => (5123, 2),
            _ => (5125, 4),
        };
        let data: Vec<u8> = indices.iter().flat_map(|&i| (i as u32).to_le_bytes()[..size].to_vec()).collect();
        let accessor = json!({"componentType": component, "count": indices.len(), "type": "SCALAR"});
        primitive["indices"] = json!(add(&mut bin, &data, accessor, None));
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    // nodes: the mesh once, or placed several times, nested, with odd transforms
    let mut nodes: Vec<Value> = vec![json!({"mesh": 0})];
    for _ in 0..rng.below(3) {
        let mut node = json!({"mesh": 0});
        match rng.below(4) {
            0 => {
                let s = *rng.pick(&[0.0, -1.0, 1e-30, 1e30, 2.0]);
                node["scale"] = json!([s, 1.0, 1.0]);
            }
            1 => node["rotation"] = json!([rng.uniform(-1.0, 1.0), 0.0, 0.0, rng.uniform(-1.0, 1.0)]),
            2 => node["translation"] = json!([1e30, -1.0, 0.5]),
            _ => {
                let mut mat = [0.0; 16];
                for x in &mut mat {
                    *x = if rng.chance(0.3) { rng.uniform(-2.0, 2.0) } else { 0.0 };
                }
                mat[15] = 1.0;
                node["matrix"] = json!(mat);
            }
        }
        nodes.push(node);
    }
    let roots: Vec<usize> = if nodes.len() > 1 && rng.chance(0.3) {
        nodes[0]["children"] = json!((1..nodes.len()).collect::<Vec<_>>());
        vec![0]
    } else {
        (0..nodes.len()).collect()
    };
    let uri = rng.chance(0.1);
    let mut buffer = json!({"byteLength": bin.len()});
    if uri {
        buffer["uri"] = json!(format!("data:application/octet-stream;base64,{}", base64(&bin)));
    }
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": "splinekit-fuzz"},
        "meshes": [{"primitives": [primitive]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [buffer],
        "nodes": nodes,
    });
    if rng.chance(0.9) {
        doc["scene"] = json!(0);
        doc["scenes"] = json!([{"nodes": roots}]);
    }
    let mut text = doc.to_string().into_bytes();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let bin_chunk = !uri && !bin.is_empty();
    let total = 12 + 8 + text.len() + if bin_chunk { 8 + bin.len() } else { 0 };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    if bin_chunk {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use splinekit_io::mesh::{MeshFormat, read_mesh};

    #[test]
    fn most_files_read() {
        let mut read = [0usize; 6];
        for i in 0..200 {
            let mut rng = Rng::for_case(2, i);
            let m = mesh(&mut rng);
            let files = [
                (obj(&mut rng, &m), MeshFormat::Obj),
                (ply(&mut rng, &m, PlyEncoding::Ascii), MeshFormat::Ply),
                (ply(&mut rng, &m, PlyEncoding::Big), MeshFormat::Ply),
                (stl_ascii(&mut rng, &m), MeshFormat::Stl),
                (stl_binary(&mut rng, &m), MeshFormat::Stl),
                (glb(&mut rng, &m), MeshFormat::Glb),
            ];
            for (k, (bytes, format)) in files.iter().enumerate() {
                if read_mesh(bytes.as_slice(), *format, "g").is_ok() {
                    read[k] += 1;
                }
            }
        }
        assert!(read.iter().all(|&n| n > 80), "files read per format: {read:?}");
    }

    #[test]
    fn base64_matches_known_text() {
        assert_eq!(base64(b"Man"), "TWFu");
        assert_eq!(base64(b"Ma"), "TWE=");
        assert_eq!(base64(b"M"), "TQ==");
    }
}
