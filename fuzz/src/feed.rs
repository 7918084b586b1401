//! What every input is fed to, in-process: the library paths of the `splinekit` commands.
//!
//! - **SWP** (`info`, `curve`, `arclen`, `sweep`, `render`): the reader, then the writer and
//!   the reader again (the round trip `to_swp_string` promises); for every curve: compiling
//!   (`to_curve`), bounding box, tessellation in the three modes (uniform steps, distance and
//!   angle tolerance, bounded as `curve --max-points` and the renderer bound them), the three
//!   frame methods, the chord or Gauss table, the adaptive arc length with its inverse and
//!   points spaced by arc length; for every surface: the two-layout counts of `info`, a sweep
//!   with random options, the annotated OBJ header (written, read back, rebuilt), and the
//!   mesh written in a random format and read back; a small picture of the whole file now
//!   and then.
//! - **Meshes** (`info`, `subdivide`, `render`, `sweep FILE.obj`): the reader, the topology
//!   report, subdivision by a random scheme (1–3 levels, only when the result stays small),
//!   limit positions and normals, the mesh written in a random format and read back, a small
//!   picture now and then, and for OBJ the spline header (parsed and rebuilt) and the crease
//!   tags read as a side file.
//!
//! Every choice of option comes from the case's random numbers, so a case replays exactly.

use glam::DVec3;
use splinekit::flatten::{self, Tessellation};
use splinekit::frame::{self, FrameMethod, FrameOptions, Side, StartNormal};
use splinekit::mesh::{DEFAULT_DEGENERATE_TOLERANCE, DEFAULT_LISTED, TopologyReport, split_nonmanifold};
use splinekit::subdiv::{
    BoundaryRule, ButterflyOptions, CatmullClarkOptions, Creases, CreasingMethod, DooSabinOptions, LoopOptions,
    LoopPyramid, LoopWeights, Sqrt3Options, SubdivError, butterfly_subdivide, catmull_clark_limit_creased,
    catmull_clark_limit_normals, catmull_clark_limit_positions, catmull_clark_subdivide,
    catmull_clark_subdivide_creased, doo_sabin_subdivide, loop_limit_creased, loop_limit_normals, loop_limit_positions,
    loop_subdivide, loop_subdivide_creased, sqrt3_subdivide,
};
use splinekit::sweep::{DEFAULT_MITRE_LIMIT, Join, MeshLayout, SweepOptions};
use splinekit::{AnyCurve, ArclenIndex, ArclenTable, ParamCurve, PolyMesh, TableMethod, TriMesh};
use splinekit_io::mesh::{
    MeshFormat, RebuildOptions, SplineHeader, read_creases, read_mesh, write_mesh, write_obj, write_obj_poly,
};
use splinekit_io::surface::{ProfileAlign, ScaleMode, SurfaceFrames, SurfaceOptions, SurfaceTessellation};
use splinekit_io::{SwpCurve, SwpDocument, SwpGeometry, SwpSurfaceKind};
use splinekit_render::{
    Curvature, CurveOptions, FileOptions, ImageSize, PictureFormat, SurfaceColour, View, render_swp_document,
    render_tri_mesh,
};

use crate::check::{self, is_large, max_abs};
use crate::rng::Rng;
use crate::{Finding, FindingKind, Format, Outcome};

/// The name inputs are given in messages.
const ORIGIN: &str = "fuzz-input";
/// The most points a tessellation may have here (the renderer's and editor's kind of bound;
/// `splinekit curve` allows 50 million with `--max-points`).
pub const MAX_POINTS: usize = 200_000;
/// The most triangles a surface may have here (`--max-triangles`).
pub const MAX_TRIANGLES: usize = 200_000;
/// The most triangles a subdivision may make here.
pub const MAX_SUBDIVIDED: f64 = 100_000.0;
/// At most this many curves and surfaces of a document go through the curve and surface paths.
const MAX_OBJECTS: usize = 24;
/// The largest picture side.
const MAX_SIDE: u32 = 96;

/// Whether [`trace`] prints.
static TRACE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Makes every path print its name, the peak memory and the time so far to standard error
/// (`--trace`, for finding which path of a failing case is slow or big).
pub fn set_trace(on: bool) {
    TRACE.store(on, std::sync::atomic::Ordering::Relaxed);
}

std::thread_local! {
    /// When the case being traced started.
    static STARTED: std::cell::Cell<Option<std::time::Instant>> = const { std::cell::Cell::new(None) };
    /// The path that raised the peak memory last, and the peak then.
    static PEAK_PATH: std::cell::Cell<(&'static str, usize)> = const { std::cell::Cell::new(("reader", 0)) };
    /// The path that took longest so far, its seconds, and when the last path ended.
    static SLOW_PATH: std::cell::Cell<(&'static str, f64, f64)> = const { std::cell::Cell::new(("reader", 0.0, 0.0)) };
}

/// The paths of the current case (on this thread) that raised the peak memory last and
/// that took longest: what a memory or time finding is about.
#[must_use]
pub fn heaviest_paths() -> (&'static str, &'static str) {
    (PEAK_PATH.get().0, SLOW_PATH.get().0)
}

/// Ends path `name`: notes whether it raised the peak or took longest, and prints it with
/// `what` when tracing.
fn trace(name: &'static str, what: std::fmt::Arguments<'_>) {
    let peak = crate::alloc::peak();
    if peak > PEAK_PATH.get().1 {
        PEAK_PATH.set((name, peak));
    }
    let seconds = STARTED.get().map_or(0.0, |t| t.elapsed().as_secs_f64());
    let (slowest, longest, last) = SLOW_PATH.get();
    SLOW_PATH.set(if seconds - last > longest { (name, seconds - last, seconds) } else { (slowest, longest, seconds) });
    if TRACE.load(std::sync::atomic::Ordering::Relaxed) {
        eprintln!("  trace: {name}: {what}: {seconds:.3} s, peak {:.1} MB", peak as f64 / 1e6);
    }
}

/// Feeds `input` in `format` to every path; `Ok` tells whether it was accepted.
///
/// # Errors
/// A [`Finding`]: a result that breaks the oracle (a panic is caught by the caller).
pub fn feed(format: Format, input: &[u8], rng: &mut Rng) -> Result<Outcome, Finding> {
    STARTED.set(Some(std::time::Instant::now()));
    PEAK_PATH.set(("reader", crate::alloc::peak()));
    SLOW_PATH.set(("reader", 0.0, 0.0));
    match format {
        Format::Swp => swp(input, rng),
        _ => mesh(format, input, rng),
    }
}

// ---------------------------------------------------------------------------------------
// SWP

fn swp(input: &[u8], rng: &mut Rng) -> Result<Outcome, Finding> {
    // as SwpDocument::read: text must be UTF-8 (its error points at the first bad byte)
    let Ok(text) = std::str::from_utf8(input) else { return Ok(Outcome::refused(true)) };
    let doc = match SwpDocument::parse(text, ORIGIN) {
        Ok(doc) => doc,
        Err(e) => return Ok(Outcome::refused(e.line() > 0).with_message(e.to_string())),
    };
    let mut outcome = Outcome::accepted();
    round_trip(&doc)?;
    let large = is_large(doc_magnitude(&doc));
    for c in doc.curves.iter().take(MAX_OBJECTS) {
        let Ok(curve) = c.to_curve() else { continue };
        curve_paths(&curve, c, rng).or_else(|f| overflow_or(f, large, &mut outcome))?;
        trace("curve", format_args!("{}", c.keyword()));
    }
    for k in 0..doc.surfaces.len().min(MAX_OBJECTS) {
        if rng.chance(0.3) {
            info_counts(&doc, k).or_else(|f| overflow_or(f, large, &mut outcome))?;
            trace("info counts", format_args!("surface {k}"));
        }
        sweep(&doc, k, rng).or_else(|f| overflow_or(f, large, &mut outcome))?;
        trace("sweep", format_args!("surface {k}"));
        annotated(&doc, k, rng).or_else(|f| overflow_or(f, large, &mut outcome))?;
        trace("annotated OBJ", format_args!("surface {k}"));
    }
    if rng.chance(0.25) {
        render_swp(&doc, rng)?;
        trace("render", format_args!("swp"));
    }
    Ok(outcome)
}

/// A finding that is no failure on an input with large numbers (see [`check::LARGE`]):
/// counted as an overflow, as the commands refuse such results.
fn overflow_or(f: Finding, large: bool, outcome: &mut Outcome) -> Result<(), Finding> {
    if large && f.kind == FindingKind::NonFinite {
        outcome.overflow = true;
        Ok(())
    } else {
        Err(f)
    }
}

/// The largest magnitude of any number of the document's curves and surfaces.
fn doc_magnitude(doc: &SwpDocument) -> f64 {
    let mut values: Vec<f64> = Vec::new();
    for c in &doc.curves {
        match &c.geometry {
            SwpGeometry::Points(p) | SwpGeometry::Tcb { points: p, .. } => {
                values.extend(p.iter().flat_map(|p| p.to_array()));
            }
            SwpGeometry::Hermite { points, tangents } => {
                values.extend(points.iter().chain(tangents).flat_map(|p| p.to_array()));
            }
            SwpGeometry::Nurbs { points, weights, knots } => {
                values.extend(points.iter().flat_map(|p| p.to_array()));
                values.extend(weights.iter().chain(knots.iter().flatten()));
            }
            SwpGeometry::Circle { radius } => values.push(*radius),
            SwpGeometry::Helix { radius, pitch, turns } => values.extend([*radius, *pitch, *turns]),
            SwpGeometry::Trefoil { size } => values.push(*size),
        }
    }
    for s in &doc.surfaces {
        match s.kind {
            SwpSurfaceKind::RevolutionZ { scale, .. } | SwpSurfaceKind::ToolSweep { scale, .. } => values.push(scale),
            _ => {}
        }
    }
    max_abs(values)
}

/// The document written and read back must be the same document: every parsed document
/// validates, and `to_swp_string` of a valid document parses to an equal one (except for
/// positions and the names given to anonymous curves).
fn round_trip(doc: &SwpDocument) -> Result<(), Finding> {
    let fail = |what: String| Err(Finding::new(FindingKind::RoundTrip, what));
    if let Err(e) = doc.validate() {
        return fail(format!("a parsed document does not validate: {e}"));
    }
    let text = doc.to_swp_string();
    let back = match SwpDocument::parse(&text, "written.swp") {
        Ok(back) => back,
        Err(e) => return fail(format!("the written document does not parse: {e}")),
    };
    if back.curves.len() != doc.curves.len() || back.surfaces.len() != doc.surfaces.len() {
        return fail(format!(
            "{} curves and {} surfaces read back as {} and {}",
            doc.curves.len(),
            doc.surfaces.len(),
            back.curves.len(),
            back.surfaces.len()
        ));
    }
    for (i, (a, b)) in doc.curves.iter().zip(&back.curves).enumerate() {
        let named = a.name.is_none() || a.name == b.name;
        if (a.kind, a.dim, a.steps, a.closed) != (b.kind, b.dim, b.steps, b.closed)
            || a.geometry != b.geometry
            || !named
        {
            return fail(format!("curve {i} reads back changed: {a:?} became {b:?}"));
        }
    }
    for (i, (a, b)) in doc.surfaces.iter().zip(&back.surfaces).enumerate() {
        if a.kind != b.kind || a.settings != b.settings || (a.name.is_some() && a.name != b.name) {
            return fail(format!("surface {i} reads back changed: {a:?} became {b:?}"));
        }
    }
    Ok(())
}

/// A tessellation mode as the commands make them (`--steps`, `--tolerance`,
/// `--angle-tolerance`), with ordinary and extreme tolerances.
fn tessellation(rng: &mut Rng, steps: u32, size: f64) -> Tessellation {
    match rng.below(3) {
        0 => Tessellation::Uniform { steps: steps as usize },
        1 => {
            let tolerance = match rng.below(6) {
                0 => *rng.pick(&[1e-300, 1e-12, 1e300, f64::MIN_POSITIVE]),
                _ => size * *rng.pick(&[1e-2, 1e-3, 1e-5]),
            };
            Tessellation::Distance { tolerance: if tolerance > 0.0 { tolerance } else { 1e-3 } }
        }
        _ => {
            let degrees = match rng.below(6) {
                0 => *rng.pick(&[1e-300, 1e-9, 180.0, 360.0, 1e300]),
                _ => rng.uniform(0.5, 30.0),
            };
            Tessellation::Angle { tolerance: degrees.to_radians() }
        }
    }
}

/// The curve's paths: `info` (segments, bounding box), `curve` (tessellation and frames),
/// `arclen` (table, adaptive length, inverse, spacing).
fn curve_paths(curve: &AnyCurve<DVec3>, swp: &SwpCurve, rng: &mut Rng) -> Result<(), Finding> {
    let m = curve.num_segments();
    let (lo, hi) = curve.domain();
    let bb = curve.bounding_box();
    check::points(&[bb.min, bb.max], "bounding box corner")?;
    let size = (bb.max - bb.min).max_element().max(1e-300);
    // `curve`: tessellation (counted first, as the command does) and frames
    for _ in 0..2 {
        let mode = tessellation(rng, swp.steps, size);
        let count = flatten::flatten_count(curve, mode);
        let params = if count <= MAX_POINTS as u64 {
            let params = flatten::flatten_any(curve, mode);
            if params.len() as u64 > count {
                return Err(Finding::new(
                    FindingKind::Invalid,
                    format!(
                        "flatten_count promised at most {count} points for {mode:?}, flatten_any gave {}",
                        params.len()
                    ),
                ));
            }
            params
        } else {
            flatten::flatten_at_most(curve, mode, MAX_POINTS)
        };
        if params.len() > MAX_POINTS.max(count.min(MAX_POINTS as u64) as usize) + 1 {
            return Err(Finding::new(
                FindingKind::Invalid,
                format!("flatten_at_most({MAX_POINTS}) gave {} points for {mode:?}", params.len()),
            ));
        }
        let ordered = params.windows(2).all(|w| w[0] <= w[1]);
        let ends = params.first() == Some(&lo) && params.last() == Some(&hi);
        if !ordered || !ends {
            return Err(Finding::new(
                FindingKind::Invalid,
                format!(
                    "tessellation {mode:?} of {} gave parameters not ascending from {lo} to {hi}: first {:?}, last {:?}",
                    swp.keyword(),
                    params.first(),
                    params.last()
                ),
            ));
        }
        let samples = frame::sample(curve, &params);
        let positions: Vec<DVec3> = samples.iter().map(|s| s.position).collect();
        check::points(&positions, &format!("{mode:?}: point"))?;
        let method = match rng.below(3) {
            0 => FrameMethod::Sequential(Side::Left),
            1 => FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left)),
            _ => FrameMethod::Frenet,
        };
        let frames = frame::frames_for_samples(&samples, &FrameOptions::DEFAULT.with_method(method));
        check::frames(&frames, &format!("{method:?}"))?;
        trace("tessellation", format_args!("{mode:?} ({} points) and {method:?} frames", params.len()));
    }
    // `arclen`: a table (as --method chord/gauss3), or the adaptive length and its inverse
    let samples = rng.range(1, 20);
    let length = if rng.chance(0.5) && samples.saturating_mul(m) < MAX_POINTS {
        let method = if rng.chance(0.5) { TableMethod::Chord } else { TableMethod::Gauss3 };
        let table = ArclenTable::new(curve, method, samples);
        let mut last = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for (u, s) in table.iter_rows() {
            check::scalar(u, "table u")?;
            check::scalar(s, "table s")?;
            if u < last.0 || s < last.1 {
                return Err(Finding::new(
                    FindingKind::Invalid,
                    format!("{method:?} table goes back: {last:?} then {u} {s}"),
                ));
            }
            last = (u, s);
        }
        let length = table.length();
        check::scalar(length, "table length")?;
        // the command compares it with the adaptive length
        let reference = ArclenIndex::new(curve, 1e-6 * length.max(f64::MIN_POSITIVE)).length();
        check::scalar(reference, "reference length")?;
        for s in [0.0, 0.5 * length, length, 2.0 * length, -1.0] {
            let u = table.u_at(s);
            in_domain(u, lo, hi, "table u_at")?;
        }
        length
    } else {
        let accuracy = match rng.below(8) {
            0 => *rng.pick(&[1e-300, 1e-15, 1e300]),
            _ => *rng.pick(&[1e-9, 1e-6, 1e-3]) * size.min(1e300),
        };
        let index = ArclenIndex::new(curve, accuracy.max(f64::MIN_POSITIVE));
        let length = index.length();
        check::scalar(length, "adaptive length")?;
        check::scalar(index.error(), "adaptive length error")?;
        for s in [0.0, 0.25 * length, rng.uniform(0.0, length), length, 1.5 * length, -1.0] {
            let u = index.u_at(curve, s);
            in_domain(u, lo, hi, "adaptive u_at")?;
        }
        // --spacing: points every length/k
        let k = rng.range(1, 200);
        if length > 0.0 {
            let ds = length / k as f64;
            let count = ((length / ds + 1e-9).floor() + 1.0).min(1000.0) as usize;
            let points: Vec<DVec3> =
                (0..count).map(|i| curve.eval(index.u_at(curve, (i as f64 * ds).min(length)))).collect();
            check::points(&points, "spaced point")?;
        }
        length
    };
    trace("arc length", format_args!("{}", swp.keyword()));
    if length < 0.0 {
        return Err(Finding::new(FindingKind::Invalid, format!("negative length {length}")));
    }
    Ok(())
}

/// Fails unless `u` is finite and in `[lo, hi]`.
fn in_domain(u: f64, lo: f64, hi: f64, what: &str) -> Result<(), Finding> {
    check::scalar(u, what)?;
    if u < lo || u > hi {
        return Err(Finding::new(FindingKind::Invalid, format!("{what} gave {u}, outside [{lo}, {hi}]")));
    }
    Ok(())
}

/// `info`'s counts: the surface in both layouts, without its own layout setting (and caps
/// only in the welded one), as `sweep_cmd::counts` does.
fn info_counts(doc: &SwpDocument, k: usize) -> Result<(), Finding> {
    let mut doc = doc.clone();
    let own_caps = doc.surfaces[k].settings.caps;
    doc.surfaces[k].settings.layout = None;
    for layout in [MeshLayout::Compat, MeshLayout::Welded] {
        let caps = layout == MeshLayout::Welded;
        doc.surfaces[k].settings.caps = if caps { own_caps } else { None };
        let options = SurfaceOptions {
            sweep: SweepOptions { layout, uvs: false, caps, ..SweepOptions::default() },
            max_triangles: Some(MAX_TRIANGLES),
            ..SurfaceOptions::default()
        };
        if let Ok(mesh) = doc.surface_mesh(k, &options) {
            check::tri_mesh(&mesh, &format!("surface {k} ({layout:?} counts)"))?;
        }
    }
    Ok(())
}

/// `sweep`: surface `k` with random options (command-line options replace the surface's
/// own settings, as the command does), the mesh checked, written and read back.
fn sweep(doc: &SwpDocument, k: usize, rng: &mut Rng) -> Result<(), Finding> {
    let mut doc = doc.clone();
    let own = &mut doc.surfaces[k].settings;
    let tessellation = match rng.below(5) {
        0 => SurfaceTessellation::Distance(*rng.pick(&[1e-3, 1e-2, 1e-6, 1e-300, 1e300])),
        1 => SurfaceTessellation::Angle(rng.pick(&[5.0f64, 30.0, 180.0, 1e-9]).to_radians()),
        _ => SurfaceTessellation::FileSteps,
    };
    if tessellation != SurfaceTessellation::FileSteps {
        own.tessellation = None;
    }
    let compat = rng.chance(0.3);
    if compat {
        own.layout = None;
        own.caps = None;
    }
    let frames = if rng.chance(0.3) {
        own.frames = None;
        *rng.pick(&[SurfaceFrames::RotationMinimizing, SurfaceFrames::Frenet, SurfaceFrames::ZUp])
    } else {
        SurfaceFrames::Auto
    };
    let align = if rng.chance(0.2) {
        own.align = None;
        *rng.pick(&[ProfileAlign::Origin, ProfileAlign::Centre, ProfileAlign::Start])
    } else {
        ProfileAlign::Origin
    };
    if rng.chance(0.2) {
        own.join = None;
        own.mitre_limit = None;
    }
    let join = *rng.pick(&[Join::Mitre, Join::Round, Join::Bevel]);
    let options = SurfaceOptions {
        sweep: SweepOptions {
            layout: if compat { MeshLayout::Compat } else { MeshLayout::Welded },
            uvs: rng.chance(0.3),
            caps: !compat && rng.chance(0.8),
            join,
            mitre_limit: if rng.chance(0.5) { rng.uniform(1.0, 11.0) } else { DEFAULT_MITRE_LIMIT },
            ..SweepOptions::default()
        },
        tessellation,
        frames,
        align,
        // from the draws above, so that the generator's stream (and the CI cases) stay put
        scale_mode: if align == ProfileAlign::Centre { ScaleMode::Override } else { ScaleMode::Multiply },
        max_triangles: Some(MAX_TRIANGLES),
    };
    let mesh = doc.surface_mesh(k, &options);
    trace("sweep mesh", format_args!("surface {k} with {options:?}"));
    let Ok(mesh) = mesh else { return Ok(()) };
    check::tri_mesh(&mesh, &format!("surface {k} swept with {options:?}"))?;
    // the file's mesh: the same triangles, welded
    if let Ok(swept) = doc.surface_poly(k, &options) {
        check::poly_mesh(&swept.mesh, &format!("welded surface {k} swept with {options:?}"))?;
    }
    write_and_read(&mesh, rng)
}

/// The annotated OBJ of a `zrev` or `xsweep`: its header written and read back, the surface
/// rebuilt from it, and the whole file read by the OBJ reader.
fn annotated(doc: &SwpDocument, k: usize, rng: &mut Rng) -> Result<(), Finding> {
    let Ok(header) = doc.annotated_header(k) else { return Ok(()) };
    let mut text = Vec::new();
    if header.write(&mut text).is_err() {
        return Ok(()); // refused: a value the tool's format cannot hold
    }
    let parsed = std::str::from_utf8(&text)
        .map_err(|e| Finding::new(FindingKind::RoundTrip, format!("the annotated header is not UTF-8: {e}")))?;
    let back = match SplineHeader::parse(parsed, "annotated.obj") {
        Ok(Some(back)) => back,
        Ok(None) => {
            return Err(Finding::new(FindingKind::RoundTrip, "the written annotated header is not found again"));
        }
        Err(e) => {
            return Err(Finding::new(
                FindingKind::RoundTrip,
                format!("the written annotated header does not parse: {e}"),
            ));
        }
    };
    if back != header {
        return Err(Finding::new(FindingKind::RoundTrip, format!("annotated header {header:?} read back as {back:?}")));
    }
    let layout = if rng.chance(0.5) { MeshLayout::Compat } else { MeshLayout::Welded };
    let options =
        RebuildOptions::DEFAULT.with_layout(layout).with_uvs(rng.chance(0.3)).with_max_triangles(Some(MAX_TRIANGLES));
    if let Ok(mesh) = back.rebuild(&options) {
        check::tri_mesh(&mesh, "rebuilt annotated surface")?;
        if write_obj(&mesh, &mut text).is_ok() {
            read_mesh(text.as_slice(), MeshFormat::Obj, "annotated.obj").map_err(|e| {
                Finding::new(FindingKind::RoundTrip, format!("the annotated OBJ does not read back: {e}"))
            })?;
        }
    }
    Ok(())
}

/// A small picture options of random view, colouring, wireframe, frames and markers.
fn picture_options(rng: &mut Rng) -> FileOptions {
    let size = ImageSize::new(rng.range(1, MAX_SIDE as usize) as u32, rng.range(1, MAX_SIDE as usize) as u32)
        .unwrap_or(ImageSize::DEFAULT);
    let colour = match rng.below(6) {
        0 => SurfaceColour::Curvature(Curvature::Mean),
        1 => SurfaceColour::Curvature(Curvature::Gaussian),
        2 => SurfaceColour::UvChecker,
        3 => SurfaceColour::Level { levels: rng.range(0, 3) as u32 },
        _ => SurfaceColour::Shade,
    };
    let markers = match rng.below(4) {
        0 => Some(*rng.pick(&[1e-300, 1e-3, 0.1, 1.0, 1e300])),
        _ => None,
    };
    let view = if rng.chance(0.5) { None } else { Some(*rng.pick(&View::ALL)) };
    FileOptions::DEFAULT
        .with_size(size)
        .with_view(view)
        .with_wireframe(rng.chance(0.3))
        .with_curves(CurveOptions::DEFAULT.with_frames(rng.chance(0.3)).with_marker_spacing(markers))
        .with_colour(colour)
}

/// `render FILE.swp`: every surface swept with the default options (UVs for the checker)
/// within one budget, then the picture.
fn render_swp(doc: &SwpDocument, rng: &mut Rng) -> Result<(), Finding> {
    let options = picture_options(rng);
    let base = SurfaceOptions {
        sweep: SweepOptions { uvs: options.colour == SurfaceColour::UvChecker, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    };
    let mut left = MAX_TRIANGLES;
    let mut meshes = Vec::new();
    for k in 0..doc.surfaces.len() {
        let Ok(mesh) = doc.surface_mesh(k, &SurfaceOptions { max_triangles: Some(left), ..base }) else {
            return Ok(());
        };
        left = left.saturating_sub(mesh.num_triangles());
        meshes.push(mesh);
    }
    let format = if doc.surfaces.is_empty() && rng.chance(0.5) { PictureFormat::Svg } else { PictureFormat::Png };
    if let Ok(rendered) = render_swp_document(doc, &meshes, "fuzz-input.swp", format, &options)
        && let splinekit_render::Picture::Image(image) = &rendered.picture
        && rng.chance(0.2)
    {
        let _ = image.encode_png();
    }
    Ok(())
}

/// Writes `mesh` in a random format (all four now and then) and reads it back: a file the
/// project wrote must read, with as many triangles.
fn write_and_read(mesh: &TriMesh, rng: &mut Rng) -> Result<(), Finding> {
    let formats: Vec<MeshFormat> =
        if rng.chance(0.25) { MeshFormat::ALL.to_vec() } else { vec![*rng.pick(&MeshFormat::ALL)] };
    for format in formats {
        let mut bytes = Vec::new();
        if write_mesh(mesh, &mut bytes, format).is_err() {
            continue; // refused: a value the format cannot hold
        }
        let back = read_mesh(bytes.as_slice(), format, "written").map_err(|e| {
            Finding::new(FindingKind::RoundTrip, format!("a {format} file the writer made does not read back: {e}"))
        })?;
        if back.mesh.num_faces() != mesh.num_triangles() {
            return Err(Finding::new(
                FindingKind::RoundTrip,
                format!(
                    "{} triangles written as {format} read back as {} faces",
                    mesh.num_triangles(),
                    back.mesh.num_faces()
                ),
            ));
        }
        check::poly_mesh(&back.mesh, &format!("mesh read back from {format}"))?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Meshes

/// Whether `input` is a text file of `format` (errors of text readers carry a line and
/// column).
fn is_text(format: Format, input: &[u8]) -> bool {
    match format {
        Format::Obj | Format::Swp => true,
        Format::Ply => input.windows(12).take(64).any(|w| w == b"format ascii"),
        Format::Stl => {
            let declared = input.get(80..84).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
            let binary = declared.is_some_and(|n| 84 + 50 * u64::from(n) == input.len() as u64);
            let start = input.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(input.len());
            !binary
                && input[start..].get(..5).is_some_and(|k| k.eq_ignore_ascii_case(b"solid"))
                && !input[..input.len().min(1024)].contains(&0)
        }
        Format::Glb => false,
    }
}

fn mesh(format: Format, input: &[u8], rng: &mut Rng) -> Result<Outcome, Finding> {
    let mesh_format = format.mesh_format().unwrap_or(MeshFormat::Obj);
    let loaded = match read_mesh(input, mesh_format, ORIGIN) {
        Ok(loaded) => loaded,
        Err(e) => {
            let located = e.pos().is_some() || !is_text(format, input);
            return Ok(Outcome::refused(located).with_message(e.to_string()));
        }
    };
    let mut outcome = Outcome::accepted();
    let mesh = &loaded.mesh;
    check::poly_mesh(mesh, "mesh as read")?;
    let large = is_large(mesh_magnitude(mesh));
    // `info`
    let report = TopologyReport::new(mesh, DEFAULT_DEGENERATE_TOLERANCE);
    let _ = (report.display_listing(DEFAULT_LISTED).to_string(), report.genus(), report.num_problems());
    trace("reader and info", format_args!("mesh"));
    // `subdivide`
    for _ in 0..rng.range(1, 2) {
        if let Err(f) = subdivide(mesh, &loaded.creases, rng) {
            overflow_or(f, large, &mut outcome)?;
        }
    }
    trace("subdivide", format_args!("mesh"));
    // writers and readers
    let tri = if rng.chance(0.5) { mesh.to_tri_mesh() } else { mesh.to_tri_mesh_with_seams() };
    if tri.validate().is_ok() {
        write_and_read(&tri, rng)?;
    }
    let mut text = Vec::new();
    if write_obj_poly(mesh, &mut text).is_ok() {
        let back = read_mesh(text.as_slice(), MeshFormat::Obj, "written.obj").map_err(|e| {
            Finding::new(FindingKind::RoundTrip, format!("a polygon OBJ the writer made does not read back: {e}"))
        })?;
        if back.mesh.num_faces() != mesh.num_faces() {
            return Err(Finding::new(
                FindingKind::RoundTrip,
                format!("{} polygons written as OBJ read back as {}", mesh.num_faces(), back.mesh.num_faces()),
            ));
        }
    }
    trace("write and read", format_args!("mesh"));
    // `render`
    if rng.chance(0.25) && !tri.triangles.is_empty() {
        let options = picture_options(rng);
        let _ = render_tri_mesh(&tri, "fuzz-input", &options);
        trace("render", format_args!("mesh"));
    }
    // `sweep FILE.obj` and `subdivide --creases FILE`
    if format == Format::Obj {
        obj_extras(input, mesh.num_vertices(), rng)?;
    }
    Ok(outcome)
}

/// The largest magnitude of any position, colour, normal or texture coordinate of `mesh`.
fn mesh_magnitude(mesh: &PolyMesh) -> f64 {
    let vectors = mesh.positions.iter().chain(&mesh.colors).chain(mesh.normals.iter().flat_map(|n| &n.values));
    let uvs = mesh.uvs.iter().flat_map(|t| &t.values).flat_map(|t| t.to_array());
    max_abs(vectors.flat_map(|p| p.to_array()).chain(uvs))
}

/// A bound on the triangles of `levels` levels of a scheme (as `subdivide` estimates them):
/// `F·4ᴺ` (Loop, butterfly), `F·3ᴺ` (√3), `C·4ᴺ/2` (Catmull-Clark), `C·4ᴺ` (Doo-Sabin).
fn triangle_bound(mesh: &PolyMesh, scheme: usize, levels: u32) -> f64 {
    let (faces, corners) = (mesh.num_faces() as f64, mesh.face_vertices.len() as f64);
    let n = levels as i32;
    match scheme {
        0 | 4 => faces * 4f64.powi(n),
        2 => faces * 3f64.powi(n),
        1 => corners * 4f64.powi(n) / 2.0,
        _ => corners * 4f64.powi(n),
    }
}

/// `subdivide`: one scheme, 1 to 3 levels when the result stays small, with creases, limit
/// positions and split non-manifold edges now and then.
fn subdivide(mesh: &PolyMesh, creases: &Creases, rng: &mut Rng) -> Result<(), Finding> {
    let scheme = rng.below(5);
    let mut levels = rng.range(1, 3) as u32;
    while levels > 0 && triangle_bound(mesh, scheme, levels) > MAX_SUBDIVIDED {
        levels -= 1;
    }
    if levels == 0 {
        return Ok(());
    }
    let split;
    let mut mesh = mesh;
    let creased = !creases.is_empty() && rng.chance(0.8);
    if !creased && rng.chance(0.3) {
        split = split_nonmanifold(mesh).0;
        check::poly_mesh(&split, "split_nonmanifold")?;
        mesh = &split;
    }
    let boundary = if rng.chance(0.5) { BoundaryRule::Smooth } else { BoundaryRule::Corners };
    let color_by_level = rng.chance(0.2);
    let method = if rng.chance(0.5) { CreasingMethod::Chaikin } else { CreasingMethod::Uniform };
    let limit = rng.chance(0.3);
    let what = format!("scheme {scheme} (Loop, Catmull-Clark, sqrt3, Doo-Sabin, butterfly), {levels} levels");
    match scheme {
        0 => {
            let weights = if rng.chance(0.5) { LoopWeights::Loop } else { LoopWeights::Warren };
            let options = LoopOptions { weights, boundary, color_by_level };
            if creased {
                let limits = |fine: &PolyMesh, child: &Creases| loop_limit_creased(fine, &options, child);
                creased_result(loop_subdivide_creased(mesh, levels, &options, creases, method), limit, limits, &what)?;
            } else if rng.chance(0.5) {
                // the command's own path
                if let Ok(pyramid) = LoopPyramid::new(mesh, options)
                    && let Ok(fine) = pyramid.into_refined(levels as usize, |_| {})
                {
                    let fine = fine.into_tri_mesh();
                    check::tri_mesh(&fine, &what)?;
                    if limit {
                        let poly = PolyMesh::from_triangles(fine.positions.clone(), &fine.triangles);
                        if let Ok(p) = loop_limit_positions(&poly, &options) {
                            check::points(&p, "Loop limit position")?;
                        }
                        if let Ok(n) = loop_limit_normals(&poly, &options) {
                            check::points(&n, "Loop limit normal")?;
                        }
                    }
                }
            } else if let Ok(fine) = loop_subdivide(mesh, levels, &options) {
                check::poly_mesh(&fine, &what)?;
            }
        }
        1 => {
            let options = CatmullClarkOptions { boundary, color_by_level, ..CatmullClarkOptions::default() };
            let n = levels as usize;
            if creased {
                let limits = |fine: &PolyMesh, child: &Creases| catmull_clark_limit_creased(fine, &options, child);
                creased_result(
                    catmull_clark_subdivide_creased(mesh, n, &options, creases, method),
                    limit,
                    limits,
                    &what,
                )?;
            } else if let Ok(fine) = catmull_clark_subdivide(mesh, n, &options) {
                check::poly_mesh(&fine, &what)?;
                if limit {
                    if let Ok(p) = catmull_clark_limit_positions(&fine, &options) {
                        check::points(&p, "Catmull-Clark limit position")?;
                    }
                    if let Ok(nrm) = catmull_clark_limit_normals(&fine, &options) {
                        check::points(&nrm, "Catmull-Clark limit normal")?;
                    }
                }
            }
        }
        2 => {
            if let Ok(fine) = sqrt3_subdivide(mesh, levels as usize, &Sqrt3Options { color_by_level }) {
                check::poly_mesh(&fine, &what)?;
            }
        }
        3 => {
            if let Ok(fine) = doo_sabin_subdivide(mesh, levels as usize, &DooSabinOptions::default()) {
                check::poly_mesh(&fine, &what)?;
            }
        }
        _ => {
            if let Ok(fine) = butterfly_subdivide(mesh, levels as usize, &ButterflyOptions { color_by_level }) {
                check::poly_mesh(&fine, &what)?;
            }
        }
    }
    Ok(())
}

/// Checks a creased subdivision's result and, when `limit`, the limit positions and normals
/// `limits` gives for it.
fn creased_result(
    result: Result<(PolyMesh, Creases), SubdivError>,
    limit: bool,
    limits: impl Fn(&PolyMesh, &Creases) -> Result<(Vec<DVec3>, Vec<DVec3>), SubdivError>,
    what: &str,
) -> Result<(), Finding> {
    let Ok((fine, child)) = result else { return Ok(()) };
    check::poly_mesh(&fine, what)?;
    if limit && let Ok((p, n)) = limits(&fine, &child) {
        check::points(&p, &format!("{what}: creased limit position"))?;
        check::points(&n, &format!("{what}: creased limit normal"))?;
    }
    Ok(())
}

/// An OBJ file's spline header (`sweep FILE.obj`: parsed, rebuilt) and its crease tags read
/// as a side file (`subdivide --creases FILE`).
fn obj_extras(input: &[u8], num_vertices: usize, rng: &mut Rng) -> Result<(), Finding> {
    let _ = read_creases(input, ORIGIN, num_vertices);
    let Ok(text) = std::str::from_utf8(input) else { return Ok(()) };
    let Ok(Some(header)) = SplineHeader::parse(text, ORIGIN) else { return Ok(()) };
    let layout = if rng.chance(0.5) { MeshLayout::Compat } else { MeshLayout::Welded };
    let options =
        RebuildOptions::DEFAULT.with_layout(layout).with_uvs(rng.chance(0.3)).with_max_triangles(Some(MAX_TRIANGLES));
    if let Ok(mesh) = header.rebuild(&options) {
        check::tri_mesh(&mesh, "surface rebuilt from the spline header")?;
    }
    Ok(())
}
