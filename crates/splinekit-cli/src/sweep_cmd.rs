//! `splinekit sweep`: the meshes of every surface of an SWP file.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context;
use clap::ValueEnum;
use splinekit::sweep::{MeshLayout, SweepOptions};
use splinekit_io::SwpDocument;
use splinekit_io::mesh::MeshFormat;
use splinekit_io::surface::{SurfaceFrames, SurfaceOptions, SurfaceTessellation};

use crate::select;

/// Sweep every surface of an SWP file (srev, gcyl) into a mesh file.
///
/// Writes one file per surface into the output directory, named `<surface name>.<ext>`
/// (anonymous surfaces: `surface_<k>.<ext>`, k counting the file's surfaces from 0), and
/// prints one line per surface: the path written, its vertex count and its triangle count.
/// Files are written to a temporary name and renamed into place, so an error never leaves
/// a partial file.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit sweep wineglass.swp -o out\n  \
    splinekit sweep tor.swp --format glb --frames rmf\n  \
    splinekit sweep wineglass.swp --tolerance 0.001\n  \
    splinekit sweep weirder.swp --compat\n\n\
    Layouts: by default seams and poles are welded (closed sweeps are watertight); --compat \
    reproduces the course program's vertex layout and counts (SPEC §2.3).")]
pub struct SweepArgs {
    /// SWP file to read
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Output directory (created if missing)
    #[arg(short = 'o', long = "output", value_name = "DIR", default_value = ".")]
    pub output: PathBuf,

    /// Mesh file format
    #[arg(long, value_enum, value_name = "FORMAT", default_value_t = Format::Obj)]
    pub format: Format,

    /// The course program's vertex layout: duplicated seams, repeated poles (SPEC §2.3 counts)
    #[arg(long)]
    pub compat: bool,

    /// Adaptive tessellation: every polyline within T (length units) of its curve
    #[arg(long, value_name = "T", conflicts_with = "angle_tolerance")]
    pub tolerance: Option<f64>,

    /// Adaptive tessellation by control-polygon angle, in degrees
    #[arg(long, value_name = "DEGREES")]
    pub angle_tolerance: Option<f64>,

    /// Frames along sweep curves
    #[arg(long, value_enum, value_name = "METHOD", default_value_t = Frames::Sequential)]
    pub frames: Frames,

    /// Add arc-length texture coordinates (welded seams are then split for the UV jump)
    #[arg(long)]
    pub uvs: bool,

    /// Leave open generalized cylinders open (by default a closed profile swept along an
    /// open curve gets flat end caps; --compat never adds them)
    #[arg(long)]
    pub no_caps: bool,
}

/// Mesh file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Wavefront OBJ (text)
    Obj,
    /// Binary glTF 2.0
    Glb,
    /// Binary little-endian PLY
    Ply,
    /// Binary STL
    Stl,
}

impl Format {
    fn extension(self) -> &'static str {
        match self {
            Self::Obj => "obj",
            Self::Glb => "glb",
            Self::Ply => "ply",
            Self::Stl => "stl",
        }
    }

    fn mesh_format(self) -> MeshFormat {
        match self {
            Self::Obj => MeshFormat::Obj,
            Self::Glb => MeshFormat::Glb,
            Self::Ply => MeshFormat::Ply,
            Self::Stl => MeshFormat::Stl,
        }
    }
}

/// Frame methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Frames {
    /// The course program's sequential frames (B₀ = +z), with the closed-curve fix
    Sequential,
    /// Rotation-minimizing frames (double reflection)
    Rmf,
}

fn options(args: &SweepArgs) -> anyhow::Result<SurfaceOptions> {
    let tessellation = match (args.tolerance, args.angle_tolerance) {
        (Some(t), _) if t > 0.0 && t.is_finite() => SurfaceTessellation::Distance(t),
        (Some(t), _) => anyhow::bail!("--tolerance must be a positive number, got {t}"),
        (None, Some(a)) if a > 0.0 && a.is_finite() => SurfaceTessellation::Angle(a.to_radians()),
        (None, Some(a)) => anyhow::bail!("--angle-tolerance must be a positive number of degrees, got {a}"),
        (None, None) => SurfaceTessellation::FileSteps,
    };
    Ok(SurfaceOptions {
        sweep: SweepOptions {
            layout: if args.compat { MeshLayout::Compat } else { MeshLayout::Welded },
            uvs: args.uvs,
            caps: !args.compat && !args.no_caps,
        },
        tessellation,
        frames: match args.frames {
            Frames::Sequential => SurfaceFrames::Sequential,
            Frames::Rmf => SurfaceFrames::RotationMinimizing,
        },
    })
}

/// A file name from a surface name: characters other than letters, digits, `-`, `_` and
/// `.` become `_` (a name cannot leave the output directory).
fn file_stem(doc: &SwpDocument, k: usize) -> String {
    match &doc.surfaces[k].name {
        Some(name) => {
            let stem: String =
                name.chars().map(|c| if c.is_alphanumeric() || "-_.".contains(c) { c } else { '_' }).collect();
            if stem.trim_matches('.').is_empty() { format!("surface_{k}") } else { stem }
        }
        None => format!("surface_{k}"),
    }
}

/// Compat and welded `(vertices, triangles)` of surface `k`, for `info`.
pub fn counts(doc: &SwpDocument, k: usize) -> anyhow::Result<[(usize, usize); 2]> {
    let mut out = [(0, 0); 2];
    for (slot, layout) in out.iter_mut().zip([MeshLayout::Compat, MeshLayout::Welded]) {
        let caps = layout == MeshLayout::Welded;
        let opts = SurfaceOptions { sweep: SweepOptions { layout, uvs: false, caps }, ..SurfaceOptions::default() };
        let mesh = doc.surface_mesh(k, &opts)?;
        *slot = (mesh.num_vertices(), mesh.num_triangles());
    }
    Ok(out)
}

/// Runs the command, writing the report to `out`.
pub fn run(args: &SweepArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let doc = select::load(&args.file)?;
    let opts = options(args)?;
    if doc.surfaces.is_empty() {
        anyhow::bail!("{} has no surfaces (srev or gcyl) to sweep", args.file.display());
    }
    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("cannot create output directory {}", args.output.display()))?;
    // every surface is swept before anything is written: an error leaves no files
    let mut meshes = Vec::with_capacity(doc.surfaces.len());
    for k in 0..doc.surfaces.len() {
        let mesh = doc.surface_mesh(k, &opts).with_context(|| format!("{}", args.file.display()))?;
        meshes.push(mesh);
    }
    let mut used = std::collections::HashSet::new();
    for (k, mesh) in meshes.iter().enumerate() {
        let mut stem = file_stem(&doc, k);
        if !used.insert(stem.clone()) {
            stem = format!("{stem}_{k}");
            used.insert(stem.clone());
        }
        let path: PathBuf = args.output.join(format!("{stem}.{}", args.format.extension()));
        splinekit_io::mesh::save(mesh, &path, args.format.mesh_format())
            .with_context(|| format!("cannot write {}", path.display()))?;
        writeln!(out, "{}: {} vertices, {} triangles", path.display(), mesh.num_vertices(), mesh.num_triangles())?;
    }
    Ok(())
}
