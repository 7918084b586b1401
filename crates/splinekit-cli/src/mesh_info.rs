//! `splinekit info MESH`: counts, topology and problems of an OBJ, glb, PLY or STL mesh.

use std::io::Write;
use std::path::Path;

use splinekit::PolyMesh;
use splinekit::mesh::{DEFAULT_DEGENERATE_TOLERANCE, DEFAULT_LISTED, Degeneracy, NonManifold, TopologyReport};
use splinekit_io::mesh::{LoadedMesh, MeshFormat};

use crate::output::{json_array, json_str};

/// The `--json` fields for a mesh, shown in `splinekit info --help`.
pub const JSON_HELP: &str = "Print one JSON object instead of text.

For a mesh file (.obj, .glb, .ply, .stl) the object has: file, format; vertices and faces (as \
read), triangles, quads and other_faces (faces by corner count); normals, uvs, colors \
(booleans: whether the file gives them); edges, boundary_edges, boundary_loops (the edge \
count of each loop); components; euler_characteristic (V − E + F over the vertices used by \
faces and the faces with at least 3 distinct valid corners); genus (the sum over components \
of (2 − χ − b)/2, or null when a component is non-manifold or non-orientable); closed, \
manifold, orientable, consistently_oriented (booleans); problems: {count, \
nonmanifold_edges [{vertices: [a, b], faces}], nonmanifold_vertices [{vertex, fans}], \
inconsistent_edges [{vertices: [a, b], faces: [f, g]}] (both faces run a → b), \
misoriented_faces (the faces to flip), degenerate_faces [{face, reason: \"repeated vertex\" \
with vertex, or \"zero area\"}], duplicate_faces [{face, first}], short_faces [{face, \
corners}], invalid_indices [{face, vertex}], unreferenced_vertices, nonfinite_vertices}; \
warnings [{line, message}] (what the reader skipped; line 0 when not about a line). \
Indices are 0-based. Lists are complete (the text output caps each at 10 entries).";

/// Whether `path` names a mesh file (by extension), to be described by [`run`].
pub fn is_mesh(path: &Path) -> bool {
    MeshFormat::from_path(path).is_some()
}

/// Describes the mesh at `path` on `out`: text, or one JSON object. Problems in the mesh are
/// reported, not errors; an unreadable or malformed file is an error naming file, line and
/// column. The reader's warnings are part of the description, and go to standard error too.
pub fn run(path: &Path, json: bool, out: &mut impl Write) -> anyhow::Result<()> {
    let loaded = crate::mesh_read::load(path)?;
    let report = TopologyReport::new(&loaded.mesh, DEFAULT_DEGENERATE_TOLERANCE);
    let file = path.display().to_string();
    let format = MeshFormat::from_path(path).map_or("", MeshFormat::extension);
    if json {
        write_json(out, &file, format, &loaded, &report)?;
    } else {
        write_text(out, &file, format, &loaded, &report)?;
    }
    Ok(())
}

/// Faces by corner count: triangles, quads, others.
fn face_sizes(mesh: &PolyMesh) -> [usize; 3] {
    let mut sizes = [0; 3];
    for face in mesh.faces() {
        sizes[match face.len() {
            3 => 0,
            4 => 1,
            _ => 2,
        }] += 1;
    }
    sizes
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

fn write_text(
    out: &mut impl Write,
    file: &str,
    format: &str,
    loaded: &LoadedMesh,
    report: &TopologyReport,
) -> std::io::Result<()> {
    let m = &loaded.mesh;
    let [tris, quads, other] = face_sizes(m);
    let mut kinds = Vec::new();
    for (n, one, many) in [(tris, "triangle", "triangles"), (quads, "quad", "quads"), (other, "other", "other")] {
        if n > 0 {
            kinds.push(plural(n, one, many));
        }
    }
    let kinds = if kinds.is_empty() { String::new() } else { format!(" ({})", kinds.join(", ")) };
    writeln!(
        out,
        "{file}: {} mesh, {}, {}{kinds}",
        format.to_uppercase(),
        plural(m.num_vertices(), "vertex", "vertices"),
        plural(m.num_faces(), "face", "faces"),
    )?;
    let mut attributes = Vec::new();
    if let Some(n) = &m.normals {
        attributes.push(format!("normals ({} values)", n.values.len()));
    }
    if let Some(t) = &m.uvs {
        attributes.push(format!("texture coordinates ({} values)", t.values.len()));
    }
    if !m.colors.is_empty() {
        attributes.push(String::from("vertex colours"));
    }
    let c = &loaded.creases;
    if !c.edges.is_empty() || !c.vertices.is_empty() {
        attributes.push(format!("creases ({} edges, {} vertices)", c.edges.len(), c.vertices.len()));
    }
    writeln!(out, "attributes: {}", if attributes.is_empty() { String::from("none") } else { attributes.join(", ") })?;
    writeln!(out, "topology:")?;
    for line in report.display_listing(DEFAULT_LISTED).to_string().lines() {
        writeln!(out, "  {line}")?;
    }
    if !loaded.warnings.is_empty() {
        writeln!(out, "read warnings ({}):", loaded.warnings.len())?;
        for w in loaded.warnings.iter().take(DEFAULT_LISTED) {
            writeln!(out, "  {w}")?;
        }
        if loaded.warnings.len() > DEFAULT_LISTED {
            writeln!(out, "  … and {} more", loaded.warnings.len() - DEFAULT_LISTED)?;
        }
    }
    Ok(())
}

/// `[1, 2, 3]` on one line.
fn ints<T: std::fmt::Display>(values: impl IntoIterator<Item = T>) -> String {
    let items: Vec<String> = values.into_iter().map(|v| v.to_string()).collect();
    format!("[{}]", items.join(", "))
}

/// One `--json` entry of a non-manifold edge or vertex or an inconsistent edge.
fn write_nonmanifold(o: &mut impl Write, p: &NonManifold) -> std::io::Result<()> {
    match p {
        NonManifold::Edge { a, b, faces } => write!(o, "{{\"vertices\": [{a}, {b}], \"faces\": {}}}", ints(faces)),
        NonManifold::Vertex { vertex, fans } => write!(o, "{{\"vertex\": {vertex}, \"fans\": {fans}}}"),
        NonManifold::Inconsistent { a, b, faces } => {
            write!(o, "{{\"vertices\": [{a}, {b}], \"faces\": {}}}", ints(faces))
        }
    }
}

fn write_json(
    out: &mut impl Write,
    file: &str,
    format: &str,
    loaded: &LoadedMesh,
    r: &TopologyReport,
) -> std::io::Result<()> {
    let m = &loaded.mesh;
    let [tris, quads, other] = face_sizes(m);
    writeln!(out, "{{")?;
    writeln!(out, "  \"file\": {},", json_str(file))?;
    writeln!(out, "  \"format\": \"{format}\",")?;
    writeln!(out, "  \"vertices\": {},", m.num_vertices())?;
    writeln!(out, "  \"faces\": {},", m.num_faces())?;
    writeln!(out, "  \"triangles\": {tris},")?;
    writeln!(out, "  \"quads\": {quads},")?;
    writeln!(out, "  \"other_faces\": {other},")?;
    writeln!(out, "  \"normals\": {},", m.normals.is_some())?;
    writeln!(out, "  \"uvs\": {},", m.uvs.is_some())?;
    writeln!(out, "  \"colors\": {},", !m.colors.is_empty())?;
    writeln!(out, "  \"edges\": {},", r.num_edges)?;
    writeln!(out, "  \"boundary_edges\": {},", r.num_boundary_edges)?;
    writeln!(out, "  \"boundary_loops\": {},", ints(r.boundary_loops.iter().map(|l| l.num_edges())))?;
    writeln!(out, "  \"components\": {},", r.components.len())?;
    writeln!(out, "  \"euler_characteristic\": {},", r.euler_characteristic)?;
    writeln!(out, "  \"genus\": {},", r.genus().map_or_else(|| String::from("null"), |g| g.to_string()))?;
    writeln!(out, "  \"closed\": {},", r.is_closed())?;
    writeln!(out, "  \"manifold\": {},", r.is_manifold())?;
    writeln!(out, "  \"orientable\": {},", r.is_orientable())?;
    writeln!(out, "  \"consistently_oriented\": {},", r.is_consistently_oriented())?;
    writeln!(out, "  \"problems\": {{")?;
    writeln!(out, "    \"count\": {},", r.num_problems())?;
    let indent = "    ";
    write!(out, "    \"nonmanifold_edges\": ")?;
    json_array(out, indent, r.nonmanifold.iter().filter(|p| p.is_edge()), write_nonmanifold)?;
    write!(out, ",\n    \"nonmanifold_vertices\": ")?;
    json_array(out, indent, r.nonmanifold.iter().filter(|p| p.is_vertex()), write_nonmanifold)?;
    write!(out, ",\n    \"inconsistent_edges\": ")?;
    json_array(out, indent, r.nonmanifold.iter().filter(|p| p.is_inconsistent()), write_nonmanifold)?;
    write!(out, ",\n    \"misoriented_faces\": {}", ints(&r.misoriented_faces))?;
    write!(out, ",\n    \"degenerate_faces\": ")?;
    json_array(out, indent, &r.degenerate_faces, |o, d| match d.kind {
        Degeneracy::RepeatedVertex { vertex } => {
            write!(o, "{{\"face\": {}, \"reason\": \"repeated vertex\", \"vertex\": {vertex}}}", d.face)
        }
        Degeneracy::ZeroArea => write!(o, "{{\"face\": {}, \"reason\": \"zero area\"}}", d.face),
    })?;
    write!(out, ",\n    \"duplicate_faces\": ")?;
    json_array(out, indent, &r.duplicate_faces, |o, d| write!(o, "{{\"face\": {}, \"first\": {}}}", d.face, d.first))?;
    write!(out, ",\n    \"short_faces\": ")?;
    json_array(out, indent, &r.short_faces, |o, s| write!(o, "{{\"face\": {}, \"corners\": {}}}", s.face, s.len))?;
    write!(out, ",\n    \"invalid_indices\": ")?;
    json_array(out, indent, &r.invalid_indices, |o, i| {
        write!(o, "{{\"face\": {}, \"vertex\": {}}}", i.face, i.vertex)
    })?;
    write!(out, ",\n    \"unreferenced_vertices\": {}", ints(&r.unreferenced_vertices))?;
    write!(out, ",\n    \"nonfinite_vertices\": {}", ints(&r.nonfinite_vertices))?;
    write!(out, "\n  }},\n  \"warnings\": ")?;
    json_array(out, "  ", &loaded.warnings, |o, w| {
        // The message without the `line N: ` prefix, which is in `line`.
        let text = w.to_string();
        let message = text.strip_prefix(&format!("line {}: ", w.line)).unwrap_or(&text);
        write!(o, "{{\"line\": {}, \"message\": {}}}", w.line, json_str(message))
    })?;
    writeln!(out, "\n}}")
}
