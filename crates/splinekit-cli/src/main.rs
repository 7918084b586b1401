//! `splinekit`: the command-line tool of the splinekit toolkit.
//!
//! `main` stays thin: parse the command line, run one subcommand, and map the outcome to an
//! exit code (0 success, 1 error, 2 usage error from clap). A closed output pipe
//! (`splinekit curve f.swp | head`) counts as success.

#[cfg(all(feature = "huge-pages", target_os = "linux"))]
mod alloc;
mod arclen_cmd;
mod curve_cmd;
mod edit_cmd;
mod gallery_cmd;
mod info_cmd;
mod mesh_info;
mod mesh_read;
mod nearest_cmd;
mod output;
mod render_cmd;
mod select;
mod subdivide_cmd;
mod sweep_cmd;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Without the `huge-pages` feature, or off Linux: the system allocator as it is.
#[cfg(not(all(feature = "huge-pages", target_os = "linux")))]
mod alloc {
    /// Runs `f`.
    pub fn recycling<R>(f: impl FnOnce() -> R) -> R {
        f()
    }

    /// Nothing to tune.
    pub const fn keep_small_blocks() {}
}

#[cfg(all(feature = "huge-pages", target_os = "linux"))]
#[global_allocator]
static ALLOCATOR: alloc::HugePageAlloc = alloc::HugePageAlloc;

/// Spline curves and swept surfaces from SWP files: arc length, u–s tables, arc-length
/// resampling, tessellated points, meshes of surfaces of revolution and generalized
/// cylinders, and pictures of them (PNG, SVG) drawn without a display.
///
/// Reads SWP curve descriptions (bez2/bez3 Bézier, bsp2/bsp3 uniform B-spline, cr2/cr3
/// Catmull-Rom, her2/her3 Hermite, tcb2/tcb3 Kochanek–Bartels, bo2/bo3 Bessel–Overhauser,
/// circ, helix, trefoil) and meshes (OBJ, PLY, STL, glb), and prints results as text, CSV or JSON on
/// standard output. Errors go to standard error and give a non-zero exit status (1; 2 for
/// command-line usage errors); SWP syntax errors name the file, line and column.
#[derive(Debug, Parser)]
#[command(name = "splinekit", version, propagate_version = true)]
#[command(after_help = "Examples:\n  \
    splinekit arclen scene.swp --curve path --method gauss3\n  \
    splinekit arclen scene.swp --method adaptive --at-s 0.417 --spacing 0.5 --json\n  \
    splinekit curve scene.swp --curve 1 --steps 50 --format json\n  \
    splinekit nearest scene.swp --curve path --point 0.5 2 --json\n  \
    splinekit sweep wineglass.swp -o out --format glb\n  \
    splinekit info wineglass.swp\n  \
    splinekit render wineglass.swp -o wineglass.png\n  \
    splinekit gallery -o gallery\n  \
    splinekit edit wineglass.swp\n\n\
    Run `splinekit <COMMAND> --help` for the flags of each command.")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    Arclen(arclen_cmd::ArclenArgs),
    Nearest(nearest_cmd::NearestArgs),
    Curve(curve_cmd::CurveArgs),
    Sweep(sweep_cmd::SweepArgs),
    Info(info_cmd::InfoArgs),
    Subdivide(subdivide_cmd::SubdivideArgs),
    Render(render_cmd::RenderArgs),
    Gallery(gallery_cmd::GalleryArgs),
    Edit(edit_cmd::EditArgs),
}

fn run(cli: Cli) -> anyhow::Result<()> {
    let stdout = io::stdout();
    let mut out = io::BufWriter::new(stdout.lock());
    let force = match &cli.command {
        Command::Sweep(args) => args.force,
        Command::Subdivide(args) => args.force,
        Command::Render(args) => args.force,
        _ => false,
    };
    splinekit_io::atomic::set_replace_read_only(force);
    match cli.command {
        Command::Arclen(args) => arclen_cmd::run(&args, &mut out)?,
        Command::Nearest(args) => nearest_cmd::run(&args, &mut out)?,
        Command::Curve(args) => curve_cmd::run(&args, &mut out)?,
        Command::Sweep(args) => sweep_cmd::run(&args, &mut out)?,
        Command::Info(args) => info_cmd::run(&args, &mut out)?,
        Command::Subdivide(args) => subdivide_cmd::run(&args, &mut out)?,
        Command::Render(args) => render_cmd::run(&args, &mut out)?,
        Command::Gallery(args) => gallery_cmd::run(&args, &mut out)?,
        Command::Edit(args) => edit_cmd::run(&args)?,
    }
    out.flush()?;
    Ok(())
}

/// True when the error comes from writing to a closed pipe.
fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|e| e.downcast_ref::<io::Error>().is_some_and(|e| e.kind() == io::ErrorKind::BrokenPipe))
}

fn main() -> ExitCode {
    alloc::keep_small_blocks();
    // Ctrl-C or SIGTERM while a large file is written: remove its temporary file (the target
    // is untouched until the rename), then exit as interrupted programs do
    let _ = ctrlc::set_handler(|| {
        splinekit_io::atomic::remove_temporaries();
        std::process::exit(130);
    });
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) if is_broken_pipe(&err) => ExitCode::SUCCESS,
        Err(err) => {
            // If stderr is gone too there is nobody left to tell.
            let _ = writeln!(io::stderr(), "error: {}", output::error_message(&err));
            ExitCode::FAILURE
        }
    }
}
