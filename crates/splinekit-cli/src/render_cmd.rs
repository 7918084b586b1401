//! `splinekit render`: a picture of an SWP or mesh file, without a display or GPU.

use std::io::Write;
use std::path::PathBuf;

use anyhow::bail;
use clap::ValueEnum;
use splinekit::subdiv::Scheme;
use splinekit_io::mesh::MeshFormat;
use splinekit_render::colour::{CHECKER_SQUARES, SCALE_PERCENTILE};
use splinekit_render::legend::format_value;
use splinekit_render::{
    Curvature, CurveOptions, FileOptions, ImageSize, Legend, PictureFormat, PictureKind, RenderError, Rendered,
    SurfaceColour, View, render_file, render_tri_mesh,
};

use crate::subdivide_cmd::{scheme_parser, subdivide_for_render};

/// Draw an SWP file or a mesh into a PNG (or, for curves, SVG) picture, on the CPU: no
/// display and no GPU are needed, and the same input gives the same bytes on every run.
///
/// What is drawn:
///
/// - An SWP file with surfaces (srev, gcyl): a 3D picture. Every surface is swept as by
///   `splinekit sweep` and shaded (front faces grey-blue, back faces orange-red), and every
///   curve of the file is drawn in 3D, coloured by segment, with its control polygon; a
///   surface in front of a curve hides it.
///
/// - An SWP file with only curves: a 2D plot (parallel projection) of every curve, coloured
///   by segment, with its dashed control polygon and control points. The default view is
///   `front` (the xy-plane) when all curves are 2D, `iso` otherwise. Writes SVG instead of
///   PNG when OUT ends in .svg.
///
/// - A mesh (.obj, .glb, .ply, .stl): a 3D picture of the mesh, smooth-shaded with the file's
///   vertex normals, flat-shaded without. With --levels N it is first subdivided N times
///   (--scheme, as `splinekit subdivide` with its default options and the OBJ's crease and
///   option tags).
///
/// --color colours surfaces and meshes by what they measure instead of one colour (still
/// lit; back faces stay orange-red):
///
/// - curvature-mean, curvature-gauss: the mean curvature H (cotangent Laplacian) or the
///   Gaussian curvature K (angle defect) at every vertex, with mixed Voronoi areas (Meyer et
///   al. 2003), on a colour map from blue (negative) through light grey (zero) to crimson
///   (positive). The scale −m..+m is symmetric about zero, shared by all surfaces, with m the
///   95th percentile of |H| or |K| (stronger values show the end colours, and the colour
///   bar's end is pointed). Vertices at one position (seams) count as one; boundary vertices
///   take their neighbours' average. A sphere of radius r is one colour (H = 1/r, K = 1/r²),
///   a plane the grey of zero. The picture carries a colour bar with −m, 0 and +m, and the
///   line printed gives m and the smallest and largest values.
///
/// - uv-checker: a checkerboard of 8×8 squares per unit of the texture coordinates, per pixel.
///   SWP surfaces are swept with arc-length UVs (0 to 1 around and along), so they show 8
///   squares each way; a mesh needs UVs of its own (OBJ vt), else it is an error.
///
/// - level: the subdivision level that made each vertex (level 0 grey, 1 blue, 2 green, 3
///   yellow, …), with a swatch per level in the picture; use it with --levels. Without
///   --levels everything is level 0.
///
/// Prints one line: the path written, the size, what was drawn, and the colouring with its
/// scale (`mean curvature from -5.00e-1 to +5.00e-1`). The file is written to a temporary
/// name and renamed into place, so an error never leaves a partial file.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit render wineglass.swp -o wineglass.png\n  \
    splinekit render bunny.obj -o bunny.png --size 1024x768 --view front --wireframe\n  \
    splinekit render scene.swp -o scene.svg --frames --markers 0.1\n  \
    splinekit render tor.swp -o tor.png --color curvature-gauss --view front\n  \
    splinekit render bunny.obj -o bunny2.png --levels 2 --color level\n\n\
    3D pictures use a perspective camera framing the whole scene, 2×2 supersampling and a \
    depth buffer; --wireframe draws the visible triangle edges only.")]
pub struct RenderArgs {
    /// SWP file, or mesh file (.obj, .glb, .ply, .stl), to draw
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Output picture: .png, or .svg (2D curve plots only)
    #[arg(short = 'o', long = "output", value_name = "OUT")]
    pub output: PathBuf,

    /// Replace output files that are read-only (refused otherwise)
    #[arg(long)]
    pub force: bool,

    /// Picture size in pixels, WIDTHxHEIGHT (each 1 to 8192)
    #[arg(long, value_name = "WxH", default_value = "800x600")]
    pub size: ImageSize,

    /// Direction to look from: iso (from +x+y+z), front (from +z), back, top (from +y),
    /// bottom, left (from −x) or right [default: iso; front for a plot of 2D curves]
    #[arg(long, value_name = "VIEW")]
    pub view: Option<View>,

    /// Draw the visible triangle edges over surfaces and meshes (3D pictures)
    #[arg(long)]
    pub wireframe: bool,

    /// Draw frames along curves: tangent (blue), normal (red) and binormal (green) arrows,
    /// 8 per segment
    #[arg(long)]
    pub frames: bool,

    /// Draw a dot every DS of arc length along each curve, from its start
    #[arg(long, value_name = "DS", allow_negative_numbers = true)]
    pub markers: Option<f64>,

    /// Colour surfaces and meshes by: shade (one colour, or the mesh's own vertex colours),
    /// curvature-mean, curvature-gauss, uv-checker or level (see above)
    #[arg(long = "color", value_enum, value_name = "COLOR", default_value_t = ColorChoice::Shade)]
    pub color: ColorChoice,

    /// Subdivide the mesh N times before drawing it (mesh files only; at most 20000000
    /// triangles); with --color level its vertices are coloured by the level that made them
    #[arg(long, value_name = "N")]
    pub levels: Option<u32>,

    /// Subdivision scheme of --levels [default: loop]
    #[arg(long, value_parser = scheme_parser(), requires = "levels")]
    pub scheme: Option<Scheme>,
}

/// The colourings of `--color`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ColorChoice {
    /// One lit colour (grey-blue), or the mesh's own vertex colours
    Shade,
    /// Mean curvature H at the vertices: blue negative, grey zero, crimson positive
    CurvatureMean,
    /// Gaussian curvature K at the vertices: blue negative, grey zero, crimson positive
    CurvatureGauss,
    /// A checkerboard of the texture coordinates, 8×8 squares per unit
    UvChecker,
    /// The subdivision level that made each vertex (with --levels)
    Level,
}

/// Runs the command, writing its summary line to `out`.
pub fn run(args: &RenderArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let format = PictureFormat::from_path(&args.output)?;
    if let Some(ds) = args.markers
        && !(ds > 0.0 && ds.is_finite())
    {
        anyhow::bail!("--markers must be a positive number, got {ds}");
    }
    let colour = match args.color {
        ColorChoice::Shade => SurfaceColour::Shade,
        ColorChoice::CurvatureMean => SurfaceColour::Curvature(Curvature::Mean),
        ColorChoice::CurvatureGauss => SurfaceColour::Curvature(Curvature::Gaussian),
        ColorChoice::UvChecker => SurfaceColour::UvChecker,
        ColorChoice::Level => SurfaceColour::Level { levels: args.levels.unwrap_or(0) },
    };
    let options = FileOptions::DEFAULT
        .with_size(args.size)
        .with_view(args.view)
        .with_wireframe(args.wireframe)
        .with_curves(CurveOptions::DEFAULT.with_frames(args.frames).with_marker_spacing(args.markers))
        .with_colour(colour);
    let rendered = if args.levels.is_some() || MeshFormat::from_path(&args.file).is_some() {
        render_mesh(args, format, &options)?
    } else {
        render_file(&args.file, format, &options).map_err(explain)?
    };
    rendered.picture.write(&args.output)?;
    let what = match rendered.kind {
        PictureKind::Surfaces => format!(
            "{} surfaces ({} triangles) and {} curves, {} view",
            rendered.num_surfaces, rendered.num_triangles, rendered.num_curves, rendered.view
        ),
        PictureKind::CurvePlot => format!("plot of {} curves, {} view", rendered.num_curves, rendered.view),
        PictureKind::Mesh => match args.levels {
            Some(levels) => format!(
                "mesh of {} triangles after {levels} level{} of {} subdivision, {} view",
                rendered.num_triangles,
                if levels == 1 { "" } else { "s" },
                args.scheme.unwrap_or_default(),
                rendered.view
            ),
            None => format!("mesh of {} triangles, {} view", rendered.num_triangles, rendered.view),
        },
    };
    // How the surfaces were coloured (nothing for a plot, which has none).
    let colouring = match (rendered.kind, args.color, rendered.legend) {
        (PictureKind::CurvePlot, ..) | (_, ColorChoice::Shade, _) => String::new(),
        (_, ColorChoice::UvChecker, _) => {
            format!(", UV checker ({CHECKER_SQUARES}×{CHECKER_SQUARES} squares per unit)")
        }
        (_, ColorChoice::Level, Some(legend)) => format!(", coloured by {}", legend.describe()),
        (_, _, Some(legend @ Legend::Curvature { curvature, min, max, .. })) => format!(
            ", {} ({SCALE_PERCENTILE}th percentile of |{}|; values from {} to {})",
            legend.describe(),
            if curvature == Curvature::Mean { "H" } else { "K" },
            format_value(min),
            format_value(max)
        ),
        (_, _, Some(legend)) => format!(", {}", legend.describe()),
        (_, _, None) => String::new(),
    };
    writeln!(out, "{}: {}, {what}{colouring}", args.output.display(), args.size)?;
    Ok(())
}

/// `--color uv-checker` on a file without UVs names the option.
fn explain(err: RenderError) -> anyhow::Error {
    match err {
        RenderError::NoTextureCoordinates { .. } => anyhow::Error::new(err).context("--color uv-checker"),
        _ => err.into(),
    }
}

/// A mesh file, drawn as [`render_file`] draws it (subdivided first with `--levels`), its
/// reader's warnings on standard error.
fn render_mesh(args: &RenderArgs, format: PictureFormat, options: &FileOptions) -> anyhow::Result<Rendered> {
    let path = args.file.display().to_string();
    let is_swp = args.file.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("swp"));
    if is_swp {
        bail!("--levels subdivides mesh files (.obj, .glb, .ply, .stl); {path} is an SWP file");
    }
    if format == PictureFormat::Svg {
        return Err(RenderError::SvgOf3d { path, what: "a mesh" }.into());
    }
    let loaded = crate::mesh_read::load(&args.file)?;
    crate::mesh_read::require_faces(&loaded.mesh, &args.file, "render")?;
    let checker = args.color == ColorChoice::UvChecker;
    if checker && loaded.mesh.uvs.is_none() {
        return Err(explain(RenderError::NoTextureCoordinates { path }));
    }
    let Some(levels) = args.levels else {
        let mesh = if checker { loaded.mesh.to_tri_mesh_with_seams() } else { loaded.mesh.to_tri_mesh() };
        return render_tri_mesh(&mesh, &path, options).map_err(explain);
    };
    let scheme = args.scheme.unwrap_or_default();
    let fine = subdivide_for_render(
        &loaded.mesh,
        (&loaded.creases, &loaded.subdiv_tags),
        scheme,
        levels,
        args.color == ColorChoice::Level,
        &args.file,
    )?;
    let mesh = if checker { fine.to_tri_mesh_with_seams() } else { fine.to_tri_mesh() };
    if checker && mesh.uvs.is_empty() {
        bail!("--color uv-checker: {scheme} subdivision of {path} did not keep its texture coordinates");
    }
    Ok(render_tri_mesh(&mesh, &path, options)?)
}
