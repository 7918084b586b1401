//! `splinekit info`: what an SWP file holds.

use std::io::Write;
use std::path::PathBuf;

use splinekit::ParamCurve;
use splinekit_io::{SwpCurveKind, SwpDocument, SwpGeometry, SwpSurfaceKind};

use crate::output::{json_array, json_str};
use crate::select;
use crate::sweep_cmd;

/// List the curves (kind, points, segments, closed) and surfaces of an SWP file, with the
/// vertex and triangle counts each surface sweeps to.
///
/// For a mesh file (.obj, .glb, .ply, .stl): counts, boundary loops, components, Euler
/// characteristic, genus and every topology problem, by vertex and face index.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit info wineglass.swp\n  \
    splinekit info scene.swp --json\n\n\
    Surface counts are given for both layouts: compat (the course program's: seam vertices \
    duplicated, poles repeated) and welded (seams and poles shared; the default of \
    `splinekit sweep`). They are counted from the curves' samples and the slices, without \
    building the meshes, so even the largest surfaces are listed at once.")]
pub struct InfoArgs {
    /// SWP file, or mesh file (.obj, .glb, .ply, .stl), to read
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Print one JSON object instead of text
    #[arg(long, long_help = crate::mesh_info::JSON_HELP)]
    pub json: bool,
}

struct CurveRow {
    name: String,
    keyword: &'static str,
    /// How an exact curve (circle, helix, trefoil) is shown instead of its control points.
    shape: Option<String>,
    /// The degree of a Bézier curve of any degree or a NURBS (the other splines are cubic).
    degree: Option<usize>,
    points: usize,
    segments: usize,
    steps: u32,
    closed: bool,
}

struct SurfaceRow {
    name: String,
    kind: &'static str,
    curves: Vec<(&'static str, String)>,
    steps: Option<u32>,
    counts: Result<[(u64, u64); 2], String>,
}

/// Runs the command, writing to `out`.
pub fn run(args: &InfoArgs, out: &mut impl Write) -> anyhow::Result<()> {
    if crate::mesh_info::is_mesh(&args.file) {
        return crate::mesh_info::run(&args.file, args.json, out);
    }
    let doc = select::load(&args.file)?;
    let curves = curve_rows(&doc);
    let surfaces = surface_rows(&doc);
    if args.json {
        write_json(out, &args.file.display().to_string(), &curves, &surfaces)?;
    } else {
        write_text(out, &args.file.display().to_string(), &curves, &surfaces)?;
    }
    Ok(())
}

fn curve_rows(doc: &SwpDocument) -> Vec<CurveRow> {
    doc.curves
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let (points, shape) = match &c.geometry {
                SwpGeometry::Points(_)
                | SwpGeometry::Hermite { .. }
                | SwpGeometry::Tcb { .. }
                | SwpGeometry::Nurbs { .. } => (c.geometry.points().len(), None),
                SwpGeometry::Circle { .. } => (0, Some(String::from("circle"))),
                SwpGeometry::Helix { radius, pitch, turns } => {
                    (0, Some(format!("helix of radius {radius}, pitch {pitch}, {turns} turns")))
                }
                SwpGeometry::Trefoil { size } => (0, Some(format!("trefoil knot of size {size}"))),
            };
            let segments = c.to_curve().map(|k| k.num_segments()).unwrap_or(0);
            let degree = match c.kind {
                SwpCurveKind::BezierN => Some(c.geometry.points().len().saturating_sub(1)),
                SwpCurveKind::Nurbs { degree } => Some(degree as usize),
                _ => None,
            };
            CurveRow {
                name: c.display_name(i),
                keyword: c.keyword(),
                shape,
                degree,
                points,
                segments,
                steps: c.steps,
                closed: c.closed,
            }
        })
        .collect()
}

fn surface_rows(doc: &SwpDocument) -> Vec<SurfaceRow> {
    doc.surfaces
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let name = |i: usize| doc.curves[i].display_name(i);
            let curves = s.kind.references().into_iter().map(|(role, i)| (role.word(), name(i))).collect();
            let steps = match s.kind {
                SwpSurfaceKind::Revolution { steps, .. } | SwpSurfaceKind::Lathe { stacks: steps, .. } => Some(steps),
                _ => None,
            };
            let kind = s.kind.keyword();
            let counts = sweep_cmd::counts(doc, k).map_err(|e| crate::output::error_message(&e));
            SurfaceRow { name: s.display_name(k), kind, curves, steps, counts }
        })
        .collect()
}

fn write_text(out: &mut impl Write, file: &str, curves: &[CurveRow], surfaces: &[SurfaceRow]) -> std::io::Result<()> {
    let plural = |n: usize, word: &str| format!("{n} {word}{}", if n == 1 { "" } else { "s" });
    writeln!(out, "{file}: {}, {}", plural(curves.len(), "curve"), plural(surfaces.len(), "surface"))?;
    if !curves.is_empty() {
        writeln!(out, "curves:")?;
        // names align up to 40 characters; longer ones run on (a padding width taken from
        // the input could be any size: format! refuses widths past u16::MAX)
        let width = curves.iter().map(|c| c.name.chars().count()).max().unwrap_or(0).min(40);
        for (i, c) in curves.iter().enumerate() {
            let shape = match &c.shape {
                Some(shape) => shape.clone(),
                None => {
                    let degree = c.degree.map(|d| format!(", degree {d}")).unwrap_or_default();
                    format!("{} points{degree}, {}", c.points, plural(c.segments, "segment"))
                }
            };
            writeln!(
                out,
                "  {i:>3}  {}{}  {:<4}  {shape}, steps {}, {}",
                c.name,
                " ".repeat(width.saturating_sub(c.name.chars().count())),
                c.keyword,
                c.steps,
                if c.closed { "closed" } else { "open" }
            )?;
        }
    }
    if !surfaces.is_empty() {
        writeln!(out, "surfaces:")?;
        for (i, s) in surfaces.iter().enumerate() {
            let refs: Vec<String> = s.curves.iter().map(|(role, n)| format!("{role} {n}")).collect();
            let steps = s.steps.map(|n| format!(", {n} steps")).unwrap_or_default();
            write!(out, "  {i:>3}  {}  {}: {}{steps}", s.name, s.kind, refs.join(", "))?;
            match &s.counts {
                Ok([(cv, ct), (wv, wt)]) => {
                    writeln!(out, "; compat {cv} vertices, {ct} triangles; welded {wv} vertices, {wt} triangles")?;
                }
                Err(e) => writeln!(out, "; cannot sweep: {e}")?,
            }
        }
    }
    Ok(())
}

fn write_json(out: &mut impl Write, file: &str, curves: &[CurveRow], surfaces: &[SurfaceRow]) -> std::io::Result<()> {
    write!(out, "{{\n  \"file\": {},\n  \"curves\": ", json_str(file))?;
    json_array(out, "  ", curves, |o, c| {
        write!(
            o,
            "{{\"name\": {}, \"kind\": \"{}\", \"points\": {}, \"segments\": {}, \"steps\": {}, \"closed\": {}}}",
            json_str(&c.name),
            c.keyword,
            c.points,
            c.segments,
            c.steps,
            c.closed
        )
    })?;
    out.write_all(b",\n  \"surfaces\": ")?;
    json_array(out, "  ", surfaces, |o, s| {
        write!(o, "{{\"name\": {}, \"kind\": \"{}\"", json_str(&s.name), s.kind)?;
        for (role, n) in &s.curves {
            write!(o, ", \"{role}\": {}", json_str(n))?;
        }
        if let Some(steps) = s.steps {
            write!(o, ", \"steps\": {steps}")?;
        }
        match &s.counts {
            Ok([(cv, ct), (wv, wt)]) => write!(
                o,
                ", \"compat\": {{\"vertices\": {cv}, \"triangles\": {ct}}}, \"welded\": {{\"vertices\": {wv}, \"triangles\": {wt}}}}}"
            ),
            Err(e) => write!(o, ", \"error\": {}}}", json_str(e)),
        }
    })?;
    out.write_all(b"\n}\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitives_and_clauses_are_listed() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("spring.swp");
        let text = "circ wire 8 0.1\nhelix coil 40 1 0.5 2\ntrefoil knot 30 1.5\n\
                    bez2 taper 4 4 [1 1] [2 2] [2 2] [1 1]\ngcyl spring wire coil scale taper twist taper\n";
        std::fs::write(&file, text).unwrap();
        let mut out = Vec::new();
        run(&InfoArgs { file: file.clone(), json: false }, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains("helix of radius 1, pitch 0.5, 2 turns, steps 40, open"), "{text}");
        assert!(text.contains("trefoil knot of size 1.5, steps 30, closed"), "{text}");
        assert!(text.contains("gcyl: profile wire, sweep coil, scale taper, twist taper;"), "{text}");
        // compat: 41 rings of 9 points, 40·8·2 triangles; welded: rings of 8 (41·8), and two
        // caps of 6 triangles on the end rings' vertices
        assert!(text.contains("compat 369 vertices, 640 triangles; welded 328 vertices, 652 triangles"), "{text}");
        let mut out = Vec::new();
        run(&InfoArgs { file, json: true }, &mut out).unwrap();
        let json: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(json["curves"][1]["kind"], "helix");
        assert_eq!(json["curves"][1]["segments"], 1);
        assert_eq!(json["surfaces"][0]["scale"], "taper");
        assert_eq!(json["surfaces"][0]["twist"], "taper");
    }
}
