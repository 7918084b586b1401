//! `splinekit render`: a picture of an SWP or mesh file, without a display or GPU.

use std::io::Write;
use std::path::PathBuf;

use splinekit_render::{CurveOptions, FileOptions, ImageSize, PictureFormat, PictureKind, View, render_file};

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
///   vertex normals, flat-shaded without.
///
/// Prints one line: the path written, the size, and what was drawn. The file is written to
/// a temporary name and renamed into place, so an error never leaves a partial file.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit render wineglass.swp -o wineglass.png\n  \
    splinekit render bunny.obj -o bunny.png --size 1024x768 --view front --wireframe\n  \
    splinekit render scene.swp -o scene.svg --frames --markers 0.1\n\n\
    3D pictures use a perspective camera framing the whole scene, 2×2 supersampling and a \
    depth buffer; --wireframe draws the visible triangle edges only.")]
pub struct RenderArgs {
    /// SWP file, or mesh file (.obj, .glb, .ply, .stl), to draw
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Output picture: .png, or .svg (2D curve plots only)
    #[arg(short = 'o', long = "output", value_name = "OUT")]
    pub output: PathBuf,

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
}

/// Runs the command, writing its summary line to `out`.
pub fn run(args: &RenderArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let format = PictureFormat::from_path(&args.output)?;
    if let Some(ds) = args.markers
        && !(ds > 0.0 && ds.is_finite())
    {
        anyhow::bail!("--markers must be a positive number, got {ds}");
    }
    let options = FileOptions::DEFAULT
        .with_size(args.size)
        .with_view(args.view)
        .with_wireframe(args.wireframe)
        .with_curves(CurveOptions::DEFAULT.with_frames(args.frames).with_marker_spacing(args.markers));
    let rendered = render_file(&args.file, format, &options)?;
    rendered.picture.write(&args.output)?;
    let what = match rendered.kind {
        PictureKind::Surfaces => format!(
            "{} surfaces ({} triangles) and {} curves, {} view",
            rendered.num_surfaces, rendered.num_triangles, rendered.num_curves, rendered.view
        ),
        PictureKind::CurvePlot => format!("plot of {} curves, {} view", rendered.num_curves, rendered.view),
        PictureKind::Mesh => format!("mesh of {} triangles, {} view", rendered.num_triangles, rendered.view),
    };
    writeln!(out, "{}: {}, {what}", args.output.display(), args.size)?;
    Ok(())
}
