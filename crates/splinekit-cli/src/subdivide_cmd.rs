//! `splinekit subdivide`: Loop, √3 or modified butterfly subdivision of a triangle mesh file,
//! Catmull-Clark, Doo-Sabin or bilinear of a polygon mesh file.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow, bail};
use clap::ValueEnum;
use splinekit::PolyMesh;
use splinekit::subdiv::{
    BoundaryRule, Creases, CreasingMethod, LoopWeights, Scheme, SubdivError, Subdivided, SubdivisionOptions,
    TopologyError, TriangleSubdivision, subdivide_with_progress,
};
use splinekit_io::mesh::{BoundaryInterpolation, MeshFormat, SavedPoly, SubdivTags, read_creases, save_poly_creased};

use crate::output::JsonNum;

/// Subdivide a mesh (OBJ, glb, PLY or STL): Loop's scheme (default), √3 (`--scheme sqrt3`) or
/// modified butterfly (`--scheme butterfly`) for triangle meshes, Catmull-Clark (`--scheme catmull-clark`), Doo-Sabin (`--scheme
/// doo-sabin`) or bilinear (`--scheme bilinear`) for any polygon mesh.
///
/// Each level splits every triangle into four; a closed mesh with V vertices,
/// E edges and F faces becomes V+E, 2E+3F, 4F. Weights: Loop's original β(n) (default; what
/// OpenSubdiv, CGAL and trimesh compute) or Warren's 3/(8n) (the course formula, libigl).
/// Boundaries follow the crease rules (boundary curves are cubic B-splines); `--boundary
/// corners` keeps vertices with a single face fixed. Colours, normals and UVs are carried
/// with the same weights, UV seams kept apart.
///
/// Catmull-Clark (OpenSubdiv's catmark weights) turns every n-gon into n quads: V+E+F
/// vertices and one quad per corner; boundaries are creases, `--boundary corners` keeps
/// single-face corners fixed; colours are carried (normals and UVs are not). OBJ output keeps
/// the quads, the other formats get two triangles per quad. `--cc-triangles smooth` is
/// OpenSubdiv's TRI_SUB_SMOOTH: on an edge beside a triangle the face points weigh 0.47 instead
/// of 1/4 (the ends 0.03), which rounds the surface over triangles; it changes the first level
/// only (below it every face is a quad).
///
/// Bilinear (OpenSubdiv's SCHEME_BILINEAR) splits every n-gon into n quads at its centroid and
/// edge midpoints and moves nothing: V+E+F vertices, one quad per corner, the surface stays the
/// polygons (use it to refine a mesh evenly). Colours, normals and UVs are carried linearly;
/// `--boundary`, `--limit`, `--creases` and `--creasing` are refused.
///
/// √3 (Kobbelt; CGAL's Sqrt3_subdivision) puts a point in every triangle and flips the old
/// edges: V+F vertices, 3F triangles. Interior vertices move by α(n) = (4 − 2cos(2π/n))/9;
/// boundaries are refined on every second level only (levels 2, 4, …: each boundary edge split
/// in three, weights /27) and stay as they are on the others. Colours and seamless UVs are
/// carried.
///
/// Doo-Sabin (CGAL's DooSabin_subdivision) makes a point for every face corner, weights
/// (n+5)/(4n) and (3+2cos(2πk/n))/(4n), and a face for every face, interior edge and interior
/// vertex (none along the boundary, which shrinks): Σ(face sizes) vertices. Colours and UVs are
/// carried; OBJ keeps the polygons. √3 and Doo-Sabin have fixed rules: `--boundary` and
/// `--limit` are refused, and so is `--color-by-level` for Doo-Sabin (every vertex is new at
/// every level); `--weights` is refused for every scheme but Loop.
///
/// Modified butterfly (Zorin, Schröder and Sweldens; OpenMesh's ModifiedButterflyT) is
/// interpolating: old vertices stay, one new vertex per edge from the eight-point butterfly
/// stencil (both ends of valence 6 or on the boundary; wings missing at a boundary
/// reflected), Zorin's masks around irregular ends, the four-point rule along boundary edges;
/// the counts are Loop's. Colours and seamless UVs are carried; `--boundary` is refused.
///
/// `--limit` moves every output vertex to its limit position and gives it the limit surface's
/// normal there (Loop or Catmull-Clark masks matching the weights and boundary rule, as
/// OpenSubdiv's; Catmull-Clark needs at least one level); OBJ, PLY and glb store the normals. Butterfly
/// vertices already lie on their limit surface, so `--limit` leaves them where they are.
///
/// Creases (Loop and Catmull-Clark): sharp and semi-sharp edges and vertices, as OpenSubdiv
/// defines them, from the input OBJ's tags or a side file (`--creases FILE`), lines like
/// `t crease 2/1 A B S` (edge A–B, 0-based vertices, sharpness S: 0 smooth, 10 or more
/// infinitely sharp; `t crease 3/1 A B C S` is the chain A–B–C) and `t corner 1/1 V S`. A
/// semi-sharp edge is sharp for ⌊S⌋ levels, then blended towards smooth; `--creasing` picks how
/// an edge's sharpness passes to its halves (Chaikin: averaged with the other creases at each
/// end, the default; uniform: S − 1). OBJ output carries the child creases as tags, so that
/// subdividing it again goes on where this run stopped. With `--limit`, a vertex on a sharp
/// crease goes to the crease's limit curve and a sharp corner stays (OpenSubdiv's limit rules).
///
/// An OBJ input may also ask for options with OpenSubdiv's tags: `t interpolateboundary 1/0/0
/// N` (N = 2: --boundary smooth; 1: --boundary corners; 0: none, OpenSubdiv's VTX_BOUNDARY_NONE,
/// which leaves the faces at the boundary out as holes — their vertices stay in the file, and
/// --limit is refused), `t creasemethod 0/0/1 normal|chaikin` (--creasing uniform or chaikin)
/// and `t smoothtriangles 0/0/1 catmark|smooth` (--cc-triangles). A flag given on the command
/// line overrides the file's tag; tags a scheme has no use for are ignored with a warning.
///
/// Writes the result by the extension of OUT (.obj, .ply, .stl, .glb) through a temporary
/// file, so an error never leaves a partial file; without -o nothing is written (use it to
/// measure). OBJ keeps the mesh's vertices and topology, normals and UVs with their own
/// indices (`f v/vt/vn`): a closed mesh stays closed, and subdividing a level-k file again
/// gives level k+1. PLY keeps them too, with UVs per corner where they differ at a vertex
/// (MeshLab's `texcoord` lists) and normals only when each vertex has one. glb holds one
/// normal and UV per vertex, so a vertex on a UV seam or a sharp normal is written once per
/// side (`--split-seams` does the same for OBJ and PLY). Prints the counts and the time of the subdivision
/// alone (no file I/O); with --json, one object `{"vertices": V, "faces": F, "seconds": S}`,
/// where S is the median of --repeat runs, and `"written_vertices": W` when the file holds
/// another number of vertices (seams split). Shows a progress bar on standard error when it
/// is a terminal.
///
/// Non-manifold and degenerate meshes (an edge of more than two faces or of two faces running
/// the same way, a vertex whose faces form several fans, a face that repeats a vertex): Loop
/// and Catmull-Clark subdivide them as OpenSubdiv does, with their non-manifold edges as
/// infinitely sharp creases and their non-manifold vertices as corners (normals and UVs are
/// not carried there). √3, Doo-Sabin and butterfly refuse them, naming the face, edge or
/// vertex. `--split-nonmanifold` instead splits non-manifold edges and vertices apart (see
/// `splinekit info MESH`) and goes on, with any scheme; it leaves faces that repeat a vertex
/// as they are. Non-triangle faces are errors for the triangle schemes.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit subdivide bunny.obj -n 2 -o bunny2.obj\n  \
    splinekit subdivide torus.ply -n 3 --threads 1 --json --repeat 5\n  \
    splinekit subdivide patch.obj -n 4 --boundary corners --color-by-level -o patch4.ply\n  \
    splinekit subdivide bunny.obj -n 3 --scheme sqrt3 -o bunny3.obj\n  \
    splinekit subdivide cube.obj -n 2 --scheme doo-sabin -o cube2.obj\n  \
    splinekit subdivide box.obj -n 3 --scheme catmull-clark --creases box-creases.txt -o box3.obj\n  \
    splinekit subdivide mixed.obj -n 2 --scheme catmull-clark --cc-triangles smooth -o mixed2.obj\n  \
    splinekit subdivide cage.obj -n 2 --scheme bilinear -o cage2.obj")]
pub struct SubdivideArgs {
    /// Input mesh (.obj, .glb, .ply, .stl)
    #[arg(value_name = "IN")]
    pub input: PathBuf,

    /// Number of subdivision levels
    #[arg(short = 'n', long = "levels", value_name = "LEVELS")]
    pub levels: u32,

    /// The most memory the subdivision may take, in gigabytes [default: the memory the system
    /// has available]. The need is estimated from the face count of the finest level before
    /// anything is made, and a subdivision that needs more is refused
    #[arg(long, value_name = "GB", value_parser = positive_gb)]
    pub max_memory: Option<f64>,

    /// Subdivision scheme
    #[arg(long, default_value = "loop", value_parser = scheme_parser())]
    pub scheme: Scheme,

    /// Even-vertex weights (Loop only): Loop's β(n) or Warren's 3/(8n) [default: loop]
    #[arg(long, value_enum)]
    pub weights: Option<Weights>,

    /// Boundary vertices (Loop and Catmull-Clark): crease rule everywhere (smooth) or
    /// single-face corners fixed [default: the input's `t interpolateboundary` tag, else
    /// smooth]; overrides a tag of none (holes)
    #[arg(long, value_enum)]
    pub boundary: Option<Boundary>,

    /// Worker threads [default: all cores]
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,

    /// Colour vertices by the level that created them (written to OBJ and PLY)
    #[arg(long)]
    pub color_by_level: bool,

    /// Split non-manifold edges and vertices instead of refusing the mesh
    #[arg(long)]
    pub split_nonmanifold: bool,

    /// Write a vertex on a UV seam or a sharp normal once per side in OBJ and PLY too (as glb
    /// always does), with one normal and UV per vertex, for programs that read only those
    #[arg(long)]
    pub split_seams: bool,

    /// Move every output vertex to its limit position (the surface after infinitely many
    /// levels; exact closed-form masks); not included in the time
    #[arg(long)]
    pub limit: bool,

    /// Crease side file: `t crease …` / `t corner …` lines (0-based vertices), added to the
    /// input OBJ's own tags (Loop and Catmull-Clark)
    #[arg(long, value_name = "FILE")]
    pub creases: Option<PathBuf>,

    /// How a crease's sharpness passes to its halves (Loop and Catmull-Clark) [default: the
    /// input's `t creasemethod` tag, else chaikin]
    #[arg(long, value_enum)]
    pub creasing: Option<Creasing>,

    /// Catmull-Clark's edge points next to triangles (OpenSubdiv's triangle subdivision rule)
    /// [default: the input's `t smoothtriangles` tag, else catmark]
    #[arg(long, value_enum, value_name = "RULE")]
    pub cc_triangles: Option<CcTriangles>,

    /// Print one JSON object {"vertices", "faces", "seconds"}
    #[arg(long)]
    pub json: bool,

    /// Run the subdivision N times; the reported time is the median
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub repeat: usize,

    /// Output mesh (.obj, .ply, .stl, .glb); omit to only measure
    #[arg(short = 'o', long = "output", value_name = "OUT")]
    pub output: Option<PathBuf>,

    /// Replace output files that are read-only (refused otherwise)
    #[arg(long)]
    pub force: bool,
}

/// The parser of `--scheme`: the names of [`Scheme::ALL`], each with its description in
/// `--help`.
pub fn scheme_parser() -> impl clap::builder::TypedValueParser<Value = Scheme> {
    use clap::builder::TypedValueParser as _;
    let values = Scheme::ALL.map(|s| clap::builder::PossibleValue::new(s.name()).help(s.description()));
    clap::builder::PossibleValuesParser::new(values)
        .try_map(|name: String| Scheme::from_name(&name).ok_or_else(|| format!("unknown scheme {name}")))
}

/// Even-vertex weights.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Weights {
    /// Loop's original β(n) = (5/8 − (3/8 + cos(2π/n)/4)²)/n
    Loop,
    /// Warren's 3/(8n), 3/16 for n = 3
    Warren,
}

/// Boundary rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Boundary {
    /// Crease rule 3/4·p + 1/8·(a + b) on every boundary vertex
    Smooth,
    /// As smooth, with single-face corners fixed
    Corners,
}

/// How a crease's sharpness passes to the two halves of its edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Creasing {
    /// 3/4 its own sharpness + 1/4 the average of the other creases at that end, minus 1
    Chaikin,
    /// Its sharpness minus 1 (OpenSubdiv's default)
    Uniform,
}

/// Catmull-Clark's edge points next to triangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CcTriangles {
    /// Catmull-Clark's rule everywhere, (v₀ + v₁ + f₀ + f₁)/4 (OpenSubdiv's TRI_SUB_CATMARK)
    Catmark,
    /// Face points weigh 0.47 beside a triangle, for rounder surfaces over triangles
    /// (OpenSubdiv's TRI_SUB_SMOOTH)
    Smooth,
}

/// Refuses the options that mean nothing for the chosen scheme.
fn check_options(args: &SubdivideArgs) -> anyhow::Result<()> {
    let scheme = args.scheme;
    if !scheme.has_weights() && args.weights.is_some() {
        bail!("--weights chooses Loop's even-vertex weights; {scheme} subdivision has none to choose (drop --weights)");
    }
    if !scheme.has_boundary_rule() && args.boundary.is_some() {
        let with = schemes_with(Scheme::has_boundary_rule);
        if scheme.is_linear() {
            bail!("--boundary is for {with}; {scheme} subdivision moves no vertex (drop --boundary)");
        }
        bail!(
            "--boundary is for {with}; {scheme} subdivision has {}'s boundary rule only (drop --boundary)",
            scheme.reference()
        );
    }
    if scheme.is_linear() && args.limit {
        bail!(
            "--limit: the {scheme} surface is its polygons, so its vertices are at their limit already (drop --limit)"
        );
    }
    if !scheme.has_limit_positions() && !scheme.is_interpolating() && args.limit {
        let with = schemes_with(Scheme::has_limit_positions);
        bail!("--limit: limit positions are computed for {with} only, not {scheme} subdivision");
    }
    if !scheme.has_triangle_rule() && args.cc_triangles.is_some() {
        bail!(
            "--cc-triangles chooses Catmull-Clark's edge points next to triangles; {scheme} subdivision has none to \
             choose"
        );
    }
    if !scheme.supports_creases() && (args.creases.is_some() || args.creasing.is_some()) {
        let with = schemes_with(Scheme::supports_creases);
        bail!("--creases and --creasing are for {with}; {scheme} subdivision has no creases");
    }
    if !scheme.colors_by_level() && args.color_by_level {
        bail!("--color-by-level: {}", no_levels(scheme));
    }
    Ok(())
}

/// The schemes that have `capability`, in words: `Loop and Catmull-Clark`.
fn schemes_with(capability: fn(Scheme) -> bool) -> String {
    let names: Vec<String> = Scheme::ALL.into_iter().filter(|&s| capability(s)).map(|s| s.to_string()).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

/// Why `scheme` (one without [`Scheme::colors_by_level`]) cannot colour by level.
pub fn no_levels(scheme: Scheme) -> String {
    format!("{scheme} subdivision makes every vertex anew at every level, so there are no levels to colour by")
}

/// The most triangles `splinekit render --levels` makes (the editor's limit too): about
/// 2 GB of mesh and picture buffers.
pub const RENDER_MAX_TRIANGLES: u64 = 20_000_000;

/// `mesh` subdivided `levels` times by `scheme` with the options its tags ask for, else the
/// defaults (the mesh's `creases` for Loop and Catmull-Clark, `tags` for the boundary rule, the
/// creasing method and Catmull-Clark's triangles; see [`Choices`]), its vertices coloured by the
/// level that made them when `color_by_level`: what `splinekit render --levels` draws. Refused,
/// before anything is made, when the result could have more than [`RENDER_MAX_TRIANGLES`]
/// triangles; `input` names the mesh in errors.
pub fn subdivide_for_render(
    mesh: &PolyMesh,
    (creases, tags): (&Creases, &SubdivTags),
    scheme: Scheme,
    levels: u32,
    color_by_level: bool,
    input: &Path,
) -> anyhow::Result<PolyMesh> {
    if !scheme.colors_by_level() && color_by_level {
        bail!("--color level: {}", no_levels(scheme));
    }
    let bound = scheme.max_triangles(mesh, levels);
    if bound > RENDER_MAX_TRIANGLES as f64 {
        bail!(
            "{}: {levels} levels of {scheme} subdivision would make up to {bound:.0} triangles, more than the \
             {RENDER_MAX_TRIANGLES} that render draws; use fewer --levels",
            input.display()
        );
    }
    let options = Choices::new((None, None, None), tags, scheme).options(None, color_by_level);
    let fine = splinekit::subdiv::subdivide(mesh, levels as usize, scheme, &options, creases)
        .map_err(|e| anyhow!("{}: {e}", input.display()))?;
    Ok(fine.mesh)
}

/// Parses `--max-memory`: a positive number of gigabytes.
fn positive_gb(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(gb) if gb > 0.0 && gb.is_finite() => Ok(gb),
        _ => Err(format!("expected a positive number of gigabytes, got {text:?}")),
    }
}

/// Bytes a triangle of the finest level ([`triangle_bound`]) takes while it is made and
/// written, at most: measured as the peak resident memory of `subdivide bunny.obj -n 5` over
/// its triangles (Loop 31, Catmull-Clark 47, butterfly 58, √3 80 bytes, Doo-Sabin below 100),
/// with room to spare.
const BYTES_PER_TRIANGLE: f64 = 160.0;

/// The memory `--max-memory` allows, in bytes: the option, else the memory the system says is
/// available (`MemAvailable` in `/proc/meminfo`), else no limit.
fn memory_limit(args: &SubdivideArgs) -> Option<f64> {
    if let Some(gb) = args.max_memory {
        return Some(gb * 1e9);
    }
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Refuses, before anything is made, a subdivision whose finest level would need more memory
/// than [`memory_limit`] (an estimate from [`triangle_bound`] and [`BYTES_PER_TRIANGLE`]).
fn check_memory(args: &SubdivideArgs, mesh: &PolyMesh) -> anyhow::Result<()> {
    let faces = args.scheme.max_triangles(mesh, args.levels);
    if faces > f64::from(u32::MAX) {
        // the library refuses these at once, with the exact count that does not fit u32
        return Ok(());
    }
    let need = faces * BYTES_PER_TRIANGLE;
    match memory_limit(args) {
        Some(limit) if need > limit => bail!(
            "{}: {} levels of {} would make up to {faces:.3e} triangles and need about {:.3} GB, more than the {:.3} GB \
             {}; ask for fewer levels{}",
            args.input.display(),
            args.levels,
            args.scheme,
            need / 1e9,
            limit / 1e9,
            if args.max_memory.is_some() { "--max-memory allows" } else { "of memory available" },
            if args.max_memory.is_some() { "" } else { " (or set --max-memory)" }
        ),
        _ => Ok(()),
    }
}

pub fn run(args: &SubdivideArgs, out: &mut impl Write) -> anyhow::Result<()> {
    if args.repeat == 0 {
        bail!("--repeat must be at least 1");
    }
    check_options(args)?;
    let format = match &args.output {
        Some(path) => Some(MeshFormat::from_path(path).ok_or_else(|| {
            anyhow!("{}: unknown output format (expected one of {})", path.display(), MeshFormat::list())
        })?),
        None => None,
    };
    let loaded = crate::mesh_read::load(&args.input)?;
    crate::mesh_read::require_faces(&loaded.mesh, &args.input, "subdivide")?;
    let choices = Choices::of_args(args, &loaded.subdiv_tags)?;
    let mut mesh = loaded.mesh;
    let mut creases = loaded.creases;
    if let Some(path) = &args.creases {
        let file = std::fs::File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
        let origin = path.display().to_string();
        let side = read_creases(std::io::BufReader::new(file), &origin, mesh.num_vertices())?;
        creases.edges.extend(side.edges);
        creases.vertices.extend(side.vertices);
    }
    check_memory(args, &mesh)?;
    let creased = !creases.is_empty();
    if creased && !args.scheme.supports_creases() {
        eprintln!(
            "warning: {}: its crease tags are ignored: {} subdivision has no creases",
            args.input.display(),
            args.scheme
        );
    }
    if args.split_nonmanifold && creased {
        bail!("--split-nonmanifold renumbers vertices, so the creases would name the wrong ones; fix the mesh first");
    }
    if args.split_nonmanifold {
        let (split, report) = splinekit::mesh::split_nonmanifold(&mesh);
        let (n_split, flipped) = (report.split_vertices.len(), report.flipped_faces.len());
        if n_split + flipped > 0 {
            eprintln!(
                "{}: split {n_split} non-manifold vertices into {} more, flipped {flipped} faces to orient them",
                args.input.display(),
                report.num_new_vertices()
            );
        }
        mesh = split;
    }
    let options = choices.options(args.weights, args.color_by_level);
    let pool = thread_pool(args)?;
    let show_progress = !args.json && std::io::stderr().is_terminal();
    let levels = args.levels as usize;
    let (fine, seconds) = timed(args, &pool, &mesh, |m, run| {
        let progress = show_progress.then(|| progress_bar(args.levels, run, args.repeat));
        let fine = subdivide_with_progress(m, levels, args.scheme, &options, &creases, |_| {
            if let Some(p) = &progress {
                p.inc(1);
            }
        });
        if let Some(p) = progress {
            p.finish_and_clear();
        }
        fine
    })?;
    let (vertices, faces) = (fine.mesh.num_vertices(), fine.mesh.num_faces());
    let mut written = None;
    if let (Some(path), Some(format)) = (&args.output, format) {
        let child = fine.creases.clone();
        let fine = if args.limit { limit(args, &pool, &mesh, &creases, fine)? } else { fine.mesh };
        if format != MeshFormat::Obj && !child.is_empty() {
            eprintln!("note: {} cannot hold crease tags; write .obj to keep the child creases", path.display());
        }
        let file = save_poly_creased(&fine, &child, path, format, args.split_seams)?;
        written = Some(saved(args, &mesh, &fine, path, file));
    }
    let noun = args.scheme.faces_made();
    report(args, out, (vertices, faces, noun), seconds, pool.current_num_threads(), written)
}

/// `fine`, subdivided from `mesh` with `creases`, at its limit positions with its limit normals
/// (`--limit`; not timed).
fn limit(
    args: &SubdivideArgs,
    pool: &rayon::ThreadPool,
    mesh: &PolyMesh,
    creases: &Creases,
    fine: Subdivided,
) -> anyhow::Result<PolyMesh> {
    pool.install(|| fine.into_limit(mesh, creases)).map_err(|e| anyhow!("{}: {e}", args.input.display()))
}

/// The options of Loop and Catmull-Clark subdivision that a flag or the input's tags set: the
/// flag when given, else the tag, else the default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Choices {
    /// `--boundary`, `t interpolateboundary`.
    pub boundary: BoundaryRule,
    /// `t interpolateboundary 1/0/0 0` without `--boundary` (OpenSubdiv's `VTX_BOUNDARY_NONE`):
    /// the faces at the boundary are holes, left out (Loop and Catmull-Clark).
    pub holes: bool,
    /// `--creasing`, `t creasemethod`.
    pub creasing: CreasingMethod,
    /// `--cc-triangles`, `t smoothtriangles`.
    pub triangles: TriangleSubdivision,
}

impl Choices {
    /// The choices of the flags `boundary`, `creasing` and `triangles` over the input's `tags`
    /// for `scheme`.
    #[must_use]
    pub fn new(
        (boundary, creasing, triangles): (Option<Boundary>, Option<Creasing>, Option<CcTriangles>),
        tags: &SubdivTags,
        scheme: Scheme,
    ) -> Self {
        let (boundary, holes) = match (boundary, tags.boundary) {
            (Some(Boundary::Smooth), _) | (None, None | Some(BoundaryInterpolation::EdgeOnly)) => {
                (BoundaryRule::Smooth, false)
            }
            (Some(Boundary::Corners), _) | (None, Some(BoundaryInterpolation::EdgeAndCorner)) => {
                (BoundaryRule::Corners, false)
            }
            (None, Some(BoundaryInterpolation::None)) => (BoundaryRule::Smooth, scheme.has_boundary_rule()),
        };
        let creasing = match creasing {
            Some(Creasing::Chaikin) => CreasingMethod::Chaikin,
            Some(Creasing::Uniform) => CreasingMethod::Uniform,
            None => tags.creasing.unwrap_or(CreasingMethod::Chaikin),
        };
        let triangles = match triangles {
            Some(CcTriangles::Catmark) => TriangleSubdivision::Catmark,
            Some(CcTriangles::Smooth) => TriangleSubdivision::Smooth,
            None => tags.triangles.unwrap_or_default(),
        };
        Self { boundary, holes, creasing, triangles }
    }

    /// The options of the subdivision: these choices, Loop's `weights` (the default without)
    /// and `color_by_level`.
    #[must_use]
    pub fn options(&self, weights: Option<Weights>, color_by_level: bool) -> SubdivisionOptions {
        let weights = match weights.unwrap_or(Weights::Loop) {
            Weights::Loop => LoopWeights::Loop,
            Weights::Warren => LoopWeights::Warren,
        };
        SubdivisionOptions::DEFAULT
            .with_weights(weights)
            .with_boundary(self.boundary)
            .with_holes(self.holes)
            .with_creasing(self.creasing)
            .with_triangles(self.triangles)
            .with_color_by_level(color_by_level)
    }

    /// The choices of `args` over the input's `tags`, with a warning on standard error naming
    /// the tags that mean nothing for the scheme.
    fn of_args(args: &SubdivideArgs, tags: &SubdivTags) -> anyhow::Result<Self> {
        let ignored = ignored_tags(tags, args.scheme);
        if !ignored.is_empty() {
            eprintln!(
                "warning: {}: its {} tag{} ignored: {} subdivision has no such option",
                args.input.display(),
                ignored.join(", "),
                if ignored.len() == 1 { " is" } else { "s are" },
                args.scheme
            );
        }
        let choices = Self::new((args.boundary, args.creasing, args.cc_triangles), tags, args.scheme);
        if choices.holes && args.limit {
            bail!(
                "{}: --limit: its tag `t interpolateboundary 1/0/0 0` leaves the faces at the boundary out as holes, \
                 and the limit is not computed for such a surface; give --boundary smooth or corners",
                args.input.display()
            );
        }
        Ok(choices)
    }
}

/// The option tags among `tags` that mean nothing for `scheme`.
pub fn ignored_tags(tags: &SubdivTags, scheme: Scheme) -> Vec<&'static str> {
    let mut ignored = Vec::new();
    if tags.boundary.is_some() && !scheme.has_boundary_rule() {
        ignored.push("interpolateboundary");
    }
    if tags.creasing.is_some() && !scheme.supports_creases() {
        ignored.push("creasemethod");
    }
    if tags.triangles.is_some() && !scheme.has_triangle_rule() {
        ignored.push("smoothtriangles");
    }
    ignored
}

/// A subdivision error naming the input, with the way on for a topology problem: Loop and
/// Catmull-Clark take non-manifold and degenerate meshes, the other schemes need them split
/// (`--split-nonmanifold`), which mends non-manifold edges and vertices but not a face that
/// repeats a vertex.
fn explain(args: &SubdivideArgs, err: SubdivError) -> anyhow::Error {
    let input = args.input.display();
    let (scheme, info) = (args.scheme, "`splinekit info` lists every problem");
    match &err {
        SubdivError::Topology(TopologyError::RepeatedVertex { .. }) => anyhow!(
            "{input}: {err}; {scheme} subdivision cannot take such a face (--split-nonmanifold does not mend it): \
             --scheme loop (triangles) or --scheme catmull-clark subdivide it as OpenSubdiv does ({info})"
        ),
        SubdivError::Topology(e) if e.is_nonmanifold() => anyhow!(
            "{input}: {err}; run with --split-nonmanifold to split non-manifold edges and vertices and go on, or use \
             --scheme loop (triangles) or --scheme catmull-clark, which subdivide it as OpenSubdiv does ({info})"
        ),
        _ => anyhow!("{input}: {err}"),
    }
}

/// The worker threads of `--threads`.
fn thread_pool(args: &SubdivideArgs) -> anyhow::Result<rayon::ThreadPool> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = args.threads {
        if n == 0 {
            bail!("--threads must be at least 1");
        }
        builder = builder.num_threads(n);
    }
    builder.build().context("cannot start the worker threads")
}

/// The number of vertices written to `path`, after a note on standard error for each attribute
/// of `input` that `fine` does not carry (the scheme, or the non-manifold path, drops it) and
/// if normals had to be left out of a PLY.
fn saved(args: &SubdivideArgs, input: &PolyMesh, fine: &PolyMesh, path: &Path, saved: SavedPoly) -> usize {
    let scheme = args.scheme;
    let mut dropped = Vec::new();
    if input.uvs.is_some() && fine.uvs.is_none() {
        dropped.push("texture coordinates");
    }
    if input.normals.is_some() && fine.normals.is_none() {
        dropped.push("normals");
    }
    if !dropped.is_empty() {
        eprintln!(
            "note: {}: {scheme} subdivision of this mesh does not carry its {}; {} written without them",
            args.input.display(),
            dropped.join(" or "),
            path.display()
        );
    }
    if saved.normals_left_out {
        eprintln!(
            "note: {}: PLY holds one normal a vertex, and the normals differ at some vertices (sharp \
             edges): written without normals; write .obj, or use --split-seams, to keep them",
            path.display()
        );
    }
    saved.vertices
}

/// Prints the counts and the time (one JSON object with --json), and, when the file holds
/// another number of vertices (glb and PLY give a vertex on a UV seam or sharp normal once per
/// side), that number.
fn report(
    args: &SubdivideArgs,
    out: &mut impl Write,
    (vertices, faces, noun): (usize, usize, &str),
    seconds: f64,
    threads: usize,
    written: Option<usize>,
) -> anyhow::Result<()> {
    if args.json {
        // the shape stays {vertices, faces, seconds} unless the file holds more vertices
        let file = match written {
            Some(n) if n != vertices => format!(", \"written_vertices\": {n}"),
            _ => String::new(),
        };
        writeln!(out, "{{\"vertices\": {vertices}, \"faces\": {faces}, \"seconds\": {}{file}}}", JsonNum(seconds))?;
    } else {
        let target = args.output.as_ref().map_or_else(|| String::from("(not written)"), |p| p.display().to_string());
        let scheme = args.scheme;
        // no level made: the input's faces, whatever they are
        let noun = if args.levels == 0 { "faces" } else { noun };
        let noun = if faces == 1 { noun.strip_suffix('s').unwrap_or(noun) } else { noun };
        let split = match written {
            Some(n) if n != vertices => {
                format!("; the file has {n} vertices (a vertex on a UV seam or a sharp normal once per side)")
            }
            _ => String::new(),
        };
        writeln!(
            out,
            "{target}: {vertices} vertices, {faces} {noun} after {} level{} of {scheme} subdivision in {seconds:.3} s \
             ({threads} thread{}{}){split}",
            args.levels,
            if args.levels == 1 { "" } else { "s" },
            if threads == 1 { "" } else { "s" },
            if args.repeat > 1 { format!(", median of {}", args.repeat) } else { String::new() },
        )?;
    }
    Ok(())
}

/// `--repeat` runs of `subdivide` (given `mesh` and the run's number) in `pool`: the last
/// result and the median time.
fn timed<T: Send>(
    args: &SubdivideArgs,
    pool: &rayon::ThreadPool,
    mesh: &PolyMesh,
    subdivide: impl Fn(&PolyMesh, usize) -> Result<T, SubdivError> + Sync,
) -> anyhow::Result<(T, f64)> {
    let mut times = Vec::with_capacity(args.repeat);
    let mut result = None;
    for run in 0..args.repeat {
        drop(result.take()); // the previous run's output is not kept alive during this one
        let start = Instant::now();
        // Buffers freed during the run serve its later allocations (see `alloc`).
        let fine = crate::alloc::recycling(|| pool.install(|| subdivide(mesh, run))).map_err(|e| explain(args, e))?;
        times.push(start.elapsed());
        result = Some(fine);
    }
    times.sort_unstable();
    Ok((result.expect("at least one run"), times[times.len() / 2].as_secs_f64()))
}

fn progress_bar(levels: u32, run: usize, runs: usize) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(u64::from(levels));
    let style = indicatif::ProgressStyle::with_template("{prefix}[{bar:30}] level {pos}/{len} {elapsed}")
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
        .progress_chars("=> ");
    bar.set_style(style);
    bar.enable_steady_tick(Duration::from_millis(200));
    if runs > 1 {
        bar.set_prefix(format!("run {}/{runs} ", run + 1));
    }
    bar
}
