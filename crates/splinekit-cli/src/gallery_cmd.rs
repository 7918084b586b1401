//! `splinekit gallery`: the bundled examples as meshes, pictures and one web page.

use std::io::Write;
use std::path::PathBuf;

use splinekit_render::ImageSize;
use splinekit_render::gallery::{self, GalleryOptions};

/// Make the gallery of the bundled examples: meshes (OBJ and glb), pictures (PNG, and SVG for
/// curve plots) and a self-contained index.html that shows them with their counts and
/// timings. Open DIR/index.html in a browser.
///
/// The examples are compiled into splinekit, so this needs no input files:
///
/// - every SWP file of the course set (surfaces of revolution, generalized cylinders,
///   curves), swept as `splinekit sweep` sweeps them;
///
/// - the arc-length reference scene (8-point Catmull-Rom rose) with its chord u–s table, and
///   a plot with a marker every 0.1 of arc length;
///
/// - the course's icosahedron and bunny after 0 to 3 levels of Loop subdivision;
///
/// - a flat ribbon swept along a trefoil knot with rotation-minimizing frames.
///
/// Files of the same names in DIR are replaced (each through a temporary file and a
/// rename); nothing else in DIR is touched. Meshes and pictures are the same bytes on every
/// run. Shows a progress bar on stderr when it is a terminal; prints the number of files
/// written and the path of the page.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit gallery                 # writes ./gallery/index.html and its files\n  \
    splinekit gallery -o /tmp/g --size 1024x768")]
pub struct GalleryArgs {
    /// Directory to write into (created if missing)
    #[arg(short = 'o', long = "output", value_name = "DIR", default_value = "gallery")]
    pub dir: PathBuf,

    /// Size of every picture in pixels, WIDTHxHEIGHT (each 1 to 8192)
    #[arg(long, value_name = "WxH", default_value = "800x600")]
    pub size: ImageSize,

    /// Finest Loop level of the subdivided meshes (0 to 4)
    #[arg(long, value_name = "N", default_value_t = 3, value_parser = clap::value_parser!(u32).range(0..=4))]
    pub levels: u32,
}

/// Runs the command, writing its summary to `out`.
pub fn run(args: &GalleryArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let options = GalleryOptions::DEFAULT.with_size(args.size).with_max_level(args.levels);
    let steps = gallery::num_steps(&options);
    let bar = crate::output::progress_bar(steps);
    let mut progress = |done: usize, what: &str| {
        if let Some(bar) = &bar {
            bar.set_position(done as u64);
            bar.set_message(what.to_string());
        }
    };
    let result = gallery::write_gallery(&args.dir, &options, &mut progress);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let made = result?;
    writeln!(
        out,
        "{} entries, {} files in {} ({:.1} s); open {}",
        made.entries.len(),
        made.files.len(),
        args.dir.display(),
        made.elapsed.as_secs_f64(),
        args.dir.join("index.html").display()
    )?;
    Ok(())
}
