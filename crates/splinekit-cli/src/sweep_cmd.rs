//! `splinekit sweep`: the meshes of every surface of an SWP file, or the surface of a
//! spline-annotated OBJ file rebuilt from its header.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, anyhow, bail};
use clap::ValueEnum;
use splinekit::TriMesh;
use splinekit::mesh::PolyMesh;
use splinekit::sweep::{DEFAULT_MITRE_LIMIT, Join, MeshLayout, SweepOptions};
use splinekit_io::SwpDocument;
use splinekit_io::mesh::{MeshFormat, RebuildError, RebuildOptions, SplineHeader, stage_poly};
use splinekit_io::surface::{
    DEFAULT_MAX_TRIANGLES, ProfileAlign, ScaleMode, SurfaceError, SurfaceFrames, SurfaceOptions, SurfaceTessellation,
};

use crate::select;

/// Sweep every surface of an SWP file (srev, gcyl, zrev, lathe) into a mesh file, or rebuild
/// the surface of a spline-annotated OBJ file (`.obj`) from the spline in its header.
///
/// SWP: writes one file per surface into the output directory, named `<surface name>.<ext>`
/// (anonymous surfaces: `surface_<k>.<ext>`, k counting the file's surfaces from 0). A
/// surface's own settings in the file (`tolerance`, `angle-tolerance`, `layout`, `frames`,
/// `caps`, `no-caps`) apply unless the matching option below is given.
///
/// OBJ: the file must start with the comment header of the CS 4620 revolution tool (`#
/// Configs: closed, epsilon, isBSpline, Scale, sliceTolerance`) or sweep tool (`#
/// Cross-section: closed, epsilon >>+<< Swept-along: …`). The surface is rebuilt from the
/// spline(s) and settings there, ignoring the mesh stored after the header, and written as
/// `<input file stem>.<ext>` (never over the input file itself). With --compat a sweep-tool
/// file gets exactly the tool's mesh back (its vertex order, duplicated seams and
/// triangles); by default seams are welded. A revolution-tool file is revolved about +z in
/// ceil(2π / sliceTolerance) slices either way. The header fixes the tessellation and the
/// frames, so --tolerance, --angle-tolerance and --frames are refused; open sweeps are never
/// capped.
///
/// Prints one line per mesh: the path written, its vertex count and its triangle count.
/// Files are written to a temporary name and renamed into place, so an error never leaves
/// a partial file.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit sweep wineglass.swp -o out\n  \
    splinekit sweep tor.swp --format glb --frames rmf\n  \
    splinekit sweep wineglass.swp --tolerance 0.001\n  \
    splinekit sweep weirder.swp --compat\n  \
    splinekit sweep doughnut.obj -o out --format glb\n  \
    splinekit sweep doughnut.obj -o out --compat\n  \
    splinekit sweep vase.swp --format obj --annotated -o out\n\n\
    Layouts: by default seams and poles are welded (closed sweeps are watertight); --compat \
    reproduces the course program's vertex layout and counts (seam vertices duplicated, \
    poles repeated; the same triangles), or, for a \
    sweep-tool OBJ, the mesh stored in the file.")]
pub struct SweepArgs {
    /// SWP file, or spline-annotated OBJ file (by the extension .obj)
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Output directory (created if missing)
    #[arg(short = 'o', long = "output", value_name = "DIR", default_value = ".")]
    pub output: PathBuf,

    /// Replace output files that are read-only (refused otherwise)
    #[arg(long)]
    pub force: bool,

    /// Mesh file format
    #[arg(long, value_name = "FORMAT", default_value = "obj", value_parser = crate::output::mesh_format())]
    pub format: MeshFormat,

    /// The course program's vertex layout and counts: duplicated seams, repeated poles; for a
    /// sweep-tool OBJ, the tool's own mesh
    #[arg(long)]
    pub compat: bool,

    /// Adaptive tessellation: the surface within T (length units) of the exact sweep, triangle
    /// interiors included (SWP only)
    #[arg(long, value_name = "T", conflicts_with = "angle_tolerance", allow_negative_numbers = true)]
    pub tolerance: Option<f64>,

    /// Adaptive tessellation by control-polygon angle, in degrees (SWP only)
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    pub angle_tolerance: Option<f64>,

    /// Frames along sweep curves (SWP only) [default: auto]
    #[arg(long, value_enum, value_name = "METHOD")]
    pub frames: Option<Frames>,

    /// Which point of each gcyl's profile rides on the path (SWP only) [default: origin]
    #[arg(long, value_enum, value_name = "POINT")]
    pub align: Option<Align>,

    /// Whether a gcyl's scale curve multiplies its profile as drawn or gives its size (its
    /// farthest point from the path sx along N and sy along B) (SWP only) [default: multiply]
    #[arg(long, value_enum, value_name = "MODE")]
    pub scale_mode: Option<ScaleModeArg>,

    /// How the walls of a gcyl meet at a sharp corner of its path (SWP only) [default: mitre]
    #[arg(long, value_enum, value_name = "JOIN")]
    pub join: Option<JoinArg>,

    /// The longest mitre, as a multiple of the profile's offset from the path, before a mitre
    /// join becomes a bevel (SWP only) [default: 4]
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    pub mitre_limit: Option<f64>,

    /// Add arc-length texture coordinates (per face corner: the UV seam stays one vertex in
    /// OBJ and PLY)
    #[arg(long)]
    pub uvs: bool,

    /// Write a vertex for each side of a sharp edge or UV seam (one normal and UV per vertex,
    /// as glb always does), instead of one vertex with per-corner normals and UVs
    #[arg(long)]
    pub split_seams: bool,

    /// Leave open generalized cylinders open (by default a closed profile swept along an
    /// open curve gets flat end caps; --compat never adds them, nor does an OBJ rebuild)
    #[arg(long)]
    pub no_caps: bool,

    /// Refuse, before building it, a surface that would have more triangles than this (a
    /// tolerance far too fine for the size of the surface)
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_TRIANGLES)]
    pub max_triangles: usize,

    /// Write each surface as a CS 4620 tool's annotated OBJ (its splines and settings in the
    /// leading comments, then the mesh), which `splinekit sweep FILE.obj` and `splinekit edit`
    /// open again. Needs --format obj, and zrev surfaces of a bsp2 or uniform cr2 profile (the
    /// revolution tool) or xsweep surfaces of two bsp2 curves (the sweep tool); the header
    /// fixes the tessellation, so --tolerance and --angle-tolerance are refused
    #[arg(long)]
    pub annotated: bool,
}

/// Which point of a profile rides on the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Align {
    /// The profile's origin (0, 0), as the course program
    Origin,
    /// The centre of the profile's bounding box
    #[value(alias = "center")]
    Centre,
    /// The profile's first point
    Start,
}

/// What a scale curve does to a profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ScaleModeArg {
    /// The scale multiplies the profile as drawn
    Multiply,
    /// The scale is the profile's size: the profile is first resized to reach 1 along each axis
    Override,
}

/// Joins at path corners.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum JoinArg {
    /// The walls extended to meet in the plane that halves the corner
    #[value(alias = "miter")]
    Mitre,
    /// The outer side rounded by an arc about the corner
    Round,
    /// The outer side cut flat
    Bevel,
}

/// Frame methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Frames {
    /// Rotation-minimizing along a path that leaves the xy plane, the course's sequential
    /// frames along one in it (the same frames there); sequential with --compat
    Auto,
    /// The course program's sequential frames (B₀ = +z), with the closed-curve fix
    Sequential,
    /// Rotation-minimizing frames (double reflection)
    Rmf,
    /// Frenet frames: N toward the centre of curvature (carried across straight parts)
    Frenet,
    /// Z-up frames (Blender's "Z-Up"): the profile's y leans toward +z, no twist builds up
    Zup,
}

fn options(args: &SweepArgs) -> anyhow::Result<SurfaceOptions> {
    let tessellation = match (args.tolerance, args.angle_tolerance) {
        (Some(t), _) if t > 0.0 && t.is_finite() => SurfaceTessellation::Distance(t),
        (Some(t), _) => anyhow::bail!("--tolerance must be a positive number, got {t}"),
        (None, Some(a)) if a > 0.0 && a.is_finite() => SurfaceTessellation::Angle(a.to_radians()),
        (None, Some(a)) => anyhow::bail!("--angle-tolerance must be a positive number of degrees, got {a}"),
        (None, None) => SurfaceTessellation::FileSteps,
    };
    let mitre_limit = match args.mitre_limit {
        Some(r) if r >= 1.0 && r.is_finite() => r,
        Some(r) => anyhow::bail!("--mitre-limit must be a number of at least 1, got {r}"),
        None => DEFAULT_MITRE_LIMIT,
    };
    Ok(SurfaceOptions {
        sweep: SweepOptions {
            layout: if args.compat { MeshLayout::Compat } else { MeshLayout::Welded },
            uvs: args.uvs,
            caps: !args.compat && !args.no_caps,
            join: match args.join {
                Some(JoinArg::Round) => Join::Round,
                Some(JoinArg::Bevel) => Join::Bevel,
                Some(JoinArg::Mitre) | None => Join::Mitre,
            },
            mitre_limit,
            ..SweepOptions::default()
        },
        tessellation,
        frames: match args.frames.unwrap_or(Frames::Auto) {
            Frames::Auto => SurfaceFrames::Auto,
            Frames::Sequential => SurfaceFrames::Sequential,
            Frames::Rmf => SurfaceFrames::RotationMinimizing,
            Frames::Frenet => SurfaceFrames::Frenet,
            Frames::Zup => SurfaceFrames::ZUp,
        },
        align: match args.align {
            Some(Align::Centre) => ProfileAlign::Centre,
            Some(Align::Start) => ProfileAlign::Start,
            Some(Align::Origin) | None => ProfileAlign::Origin,
        },
        scale_mode: match args.scale_mode {
            Some(ScaleModeArg::Override) => ScaleMode::Override,
            Some(ScaleModeArg::Multiply) | None => ScaleMode::Multiply,
        },
        max_triangles: Some(args.max_triangles),
    })
}

/// A file name from a surface name: characters other than letters, digits, `-`, `_` and
/// `.` become `_` (a name cannot leave the output directory).
fn file_stem(doc: &SwpDocument, k: usize) -> String {
    doc.surfaces[k].name.as_deref().and_then(safe_stem).unwrap_or_else(|| format!("surface_{k}"))
}

/// `name` with characters other than letters, digits, `-`, `_` and `.` replaced by `_`, or
/// `None` if nothing but dots would be left.
fn safe_stem(name: &str) -> Option<String> {
    let stem: String = name.chars().map(|c| if c.is_alphanumeric() || "-_.".contains(c) { c } else { '_' }).collect();
    (!stem.trim_matches('.').is_empty()).then_some(stem)
}

/// Compat and welded `(vertices, triangles)` of surface `k`, for `info`: counted from the
/// samples and slices, without building the meshes.
pub fn counts(doc: &SwpDocument, k: usize) -> anyhow::Result<[(u64, u64); 2]> {
    let mut out = [(0, 0); 2];
    // the two layouts, whatever the surface's own layout; the compat layout never has caps
    let mut doc = doc.clone();
    let own_caps = doc.surfaces.get(k).and_then(|s| s.settings.caps);
    if let Some(s) = doc.surfaces.get_mut(k) {
        s.settings.layout = None;
    }
    for (slot, layout) in out.iter_mut().zip([MeshLayout::Compat, MeshLayout::Welded]) {
        let caps = layout == MeshLayout::Welded;
        if let Some(s) = doc.surfaces.get_mut(k) {
            s.settings.caps = if caps { own_caps } else { None };
        }
        let opts = SurfaceOptions {
            sweep: SweepOptions { layout, uvs: false, caps, ..SweepOptions::default() },
            ..SurfaceOptions::default()
        };
        // counted from the samples: nothing the size of the mesh is built
        let counts = doc.surface_counts(k, &opts)?;
        *slot = (counts.vertices, counts.triangles);
    }
    Ok(out)
}

/// Runs the command, writing the report to `out`.
pub fn run(args: &SweepArgs, out: &mut impl Write) -> anyhow::Result<()> {
    if is_obj(&args.file) {
        return run_obj(args, out);
    }
    let mut doc = select::load(&args.file)?;
    let opts = options(args)?;
    // what the command line asks for replaces the surfaces' own settings
    for s in &mut doc.surfaces {
        let own = &mut s.settings;
        if args.tolerance.is_some() || args.angle_tolerance.is_some() {
            own.tessellation = None;
        }
        if args.frames.is_some() {
            own.frames = None;
        }
        if args.align.is_some() {
            own.align = None;
        }
        if args.scale_mode.is_some() {
            own.scale_mode = None;
        }
        if args.join.is_some() {
            own.join = None;
        }
        if args.mitre_limit.is_some() {
            own.mitre_limit = None;
        }
        if args.compat {
            own.layout = None;
            own.caps = None;
        }
        if args.no_caps {
            own.caps = None;
        }
    }
    if args.annotated {
        if args.format != MeshFormat::Obj {
            bail!("--annotated writes OBJ files; use it with --format obj");
        }
        if args.tolerance.is_some() || args.angle_tolerance.is_some() {
            bail!(
                "--annotated: the header of an annotated OBJ fixes the tessellation (each zrev's epsilon and \
                 slice-tolerance); leave out --tolerance and --angle-tolerance"
            );
        }
        // every surface must fit the header before anything is written
        for k in 0..doc.surfaces.len() {
            doc.annotated_header(k).map_err(|e| anyhow!("{}: {e}", args.file.display()))?;
        }
    }
    if doc.surfaces.is_empty() {
        anyhow::bail!("{} has no surfaces (srev or gcyl) to sweep", args.file.display());
    }
    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("cannot create output directory {}", args.output.display()))?;
    let bar = crate::output::progress_bar(2 * doc.surfaces.len());
    let result = sweep_surfaces(args, &doc, &opts, bar.as_ref(), out);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    result
}

/// Prints a note or warning on standard error, above the progress bar when there is one.
fn say(bar: Option<&indicatif::ProgressBar>, text: &str) {
    match bar {
        Some(bar) => bar.suspend(|| eprintln!("{text}")),
        None => eprintln!("{text}"),
    }
}

/// Sweeps every surface of `doc`, then writes them (an error while sweeping leaves no files),
/// moving `bar` along.
fn sweep_surfaces(
    args: &SweepArgs,
    doc: &SwpDocument,
    opts: &SurfaceOptions,
    bar: Option<&indicatif::ProgressBar>,
    out: &mut impl Write,
) -> anyhow::Result<()> {
    let step = |done: usize, what: String| {
        if let Some(bar) = bar {
            bar.set_position(done as u64);
            bar.set_message(what);
        }
    };
    let mut meshes = Vec::with_capacity(doc.surfaces.len());
    for k in 0..doc.surfaces.len() {
        step(k, format!("sweeping {}", doc.surfaces[k].display_name(k)));
        let swept = doc.surface_poly(k, opts).map_err(|e| {
            let hint = match e {
                SurfaceError::TooLarge { .. } => {
                    "; use a coarser --tolerance or --angle-tolerance, or raise --max-triangles"
                }
                _ => "",
            };
            anyhow!("{}: {e}{hint}", args.file.display())
        })?;
        // the surface bound of a distance tolerance covers paths, scale and twist curves that
        // are chains of cubics, and circle and helix paths; otherwise each curve is within T
        let own = opts.with_settings(&doc.surfaces[k].settings);
        if let SurfaceTessellation::Distance(t) = own.tessellation
            && !doc.tolerance_bounds_surface(k, opts)
        {
            let note = format!(
                "note: {}: surface {}: with this path, scale or twist curve the tolerance {t} bounds each \
                 curve's tessellation, not the surface, which may stray further from the exact sweep (the \
                 surface is bounded for paths, scale and twist curves made of cubic segments, and circle and \
                 helix paths)",
                args.file.display(),
                doc.surfaces[k].display_name(k),
            );
            say(bar, &note);
        }
        for corner in &swept.unfit_corners {
            let p = corner.position;
            let warning = format!(
                "warning: {}: surface {}: the profile does not fit inside the turn of {:.1}° at ({}, {}, {}): the \
                 joint there may fold over or cut into the walls (a smaller profile, or a path with more room \
                 before and after the corner, avoids it)",
                args.file.display(),
                doc.surfaces[k].display_name(k),
                corner.angle.to_degrees(),
                p.x,
                p.y,
                p.z,
            );
            say(bar, &warning);
        }
        meshes.push(swept.mesh);
    }
    // every file is written to its temporary name before any is renamed into place: an error
    // on the last leaves none of them
    let mut used = std::collections::HashSet::new();
    let mut staged = Vec::with_capacity(meshes.len());
    for (k, mesh) in meshes.iter().enumerate() {
        let mut stem = file_stem(doc, k);
        if !used.insert(stem.clone()) {
            stem = format!("{stem}_{k}");
            used.insert(stem.clone());
        }
        let path: PathBuf = args.output.join(format!("{stem}.{}", args.format.extension()));
        step(meshes.len() + k, format!("writing {}", path.display()));
        // the errors name the path
        let (file, vertices) = if args.annotated {
            let header = doc.annotated_header(k).map_err(|e| anyhow!("{}: {e}", args.file.display()))?;
            (splinekit_io::mesh::stage_annotated_obj(&header, &mesh.to_tri_mesh(), &path)?, mesh.num_vertices())
        } else if per_vertex(mesh) {
            // one normal and UV a vertex (the course's layout): the triangle mesh writers
            let tri = mesh.to_tri_mesh();
            (splinekit_io::mesh::stage(&tri, &path, args.format)?, tri.num_vertices())
        } else {
            let (file, saved) = stage_poly(mesh, &path, args.format, args.split_seams)?;
            if saved.normals_left_out {
                let note = format!(
                    "note: {}: PLY holds one normal a vertex, and this mesh has sharp edges: written without \
                     normals; write .obj, or use --split-seams, to keep them",
                    path.display()
                );
                say(bar, &note);
            }
            (file, saved.vertices)
        };
        staged.push((file, vertices, mesh.num_faces(), path));
    }
    for (file, vertices, triangles, path) in staged {
        file.commit()?;
        // the report goes to standard output, above the bar
        let line =
            |out: &mut dyn Write| writeln!(out, "{}: {vertices} vertices, {triangles} triangles", path.display());
        match bar {
            Some(bar) => bar.suspend(|| line(out))?,
            None => line(out)?,
        }
    }
    Ok(())
}

/// Whether every vertex of `mesh` has one normal and one UV (each attribute's indices are
/// the corners' vertices).
fn per_vertex(mesh: &PolyMesh) -> bool {
    let same = |indices: &[u32], len: usize| indices == mesh.face_vertices.as_slice() && len == mesh.num_vertices();
    mesh.normals.as_ref().is_none_or(|a| same(&a.indices, a.values.len()))
        && mesh.uvs.as_ref().is_none_or(|a| same(&a.indices, a.values.len()))
}

/// Saves `mesh` to `path` in the chosen format and reports it.
fn write_mesh(args: &SweepArgs, mesh: &TriMesh, path: &Path, out: &mut impl Write) -> anyhow::Result<()> {
    save_mesh(args, mesh, path)?;
    report(mesh, path, out)
}

/// Saves `mesh` to `path` in the chosen format.
fn save_mesh(args: &SweepArgs, mesh: &TriMesh, path: &Path) -> anyhow::Result<()> {
    // the error names the path
    Ok(splinekit_io::mesh::save(mesh, path, args.format)?)
}

/// The report line of a written mesh: its path, vertex count and triangle count.
fn report(mesh: &TriMesh, path: &Path, out: &mut impl Write) -> anyhow::Result<()> {
    writeln!(out, "{}: {} vertices, {} triangles", path.display(), mesh.num_vertices(), mesh.num_triangles())?;
    Ok(())
}

/// True for a path ending in `.obj` (any case): a spline-annotated OBJ file.
fn is_obj(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"))
}

/// What a spline-annotated OBJ's header looks like, for the "no header" message.
const EXPECTED_HEADER: &str = "expected the leading comments of the CS 4620 revolution tool \
    (\"# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance\", a values line, then \
    \"# Cross-section Spline control points:\" and one \"# x y\" line per point) or of its \
    sweep tool (\"# Cross-section: closed, epsilon >>+<< Swept-along: closed, epsilon >>+<< \
    Scale of Cross-section\", a values line, then the cross-section and swept-along control points)";

/// `sweep FILE.obj`: rebuilds the surface from the spline header and writes it.
fn run_obj(args: &SweepArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let file = &args.file;
    let refused = [
        (args.tolerance.is_some(), "--tolerance"),
        (args.angle_tolerance.is_some(), "--angle-tolerance"),
        (args.frames.is_some(), "--frames"),
    ];
    if let Some((_, flag)) = refused.iter().find(|(given, _)| *given) {
        bail!(
            "{flag} does not apply to {}: the spline header of an OBJ file fixes the tessellation and \
             the frames (--tolerance, --angle-tolerance and --frames are for SWP files)",
            file.display()
        );
    }
    let header = SplineHeader::read(file)?
        .ok_or_else(|| anyhow!("{}: no spline header found; {EXPECTED_HEADER}", file.display()))?;
    let layout = if args.compat { MeshLayout::Compat } else { MeshLayout::Welded };
    let options =
        RebuildOptions::DEFAULT.with_layout(layout).with_uvs(args.uvs).with_max_triangles(Some(args.max_triangles));
    let mesh = header.rebuild(&options).map_err(|e| {
        let hint = if matches!(e, RebuildError::TooLarge { .. }) { "; raise --max-triangles" } else { "" };
        anyhow!("cannot rebuild the surface of {}: {e}{hint}", file.display())
    })?;
    let stem = file.file_stem().and_then(|s| safe_stem(&s.to_string_lossy())).unwrap_or_else(|| "surface".into());
    let path = args.output.join(format!("{stem}.{}", args.format.extension()));
    // (an output directory that does not exist yet cannot hold the input)
    if let (Ok(a), Ok(b)) = (std::fs::canonicalize(&path), std::fs::canonicalize(file))
        && a == b
    {
        bail!(
            "{} would overwrite the input file; write elsewhere with -o DIR or choose another --format",
            path.display()
        );
    }
    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("cannot create output directory {}", args.output.display()))?;
    if args.annotated {
        if args.format != MeshFormat::Obj {
            bail!("--annotated writes OBJ files; use it with --format obj");
        }
        splinekit_io::mesh::save_annotated_obj(&header, &mesh, &path)?;
        return report(&mesh, &path, out);
    }
    write_mesh(args, &mesh, &path, out)
}
