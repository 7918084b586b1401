//! `splinekit nearest`: the point of a curve nearest to a given point, over the whole curve.

use std::io::Write;
use std::path::PathBuf;

use anyhow::bail;
use glam::DVec3;
use splinekit::ParamCurve;

use crate::arclen_cmd::{finite, positive_finite};
use crate::output::{JsonNum, json_str};
use crate::select;

/// Print the point of a curve nearest to a given point: its parameter u, the point and the
/// distance.
///
/// The search covers the whole curve (not a local search from a guess): the distance printed
/// is within --accuracy of the smallest distance from the point to any point of the curve.
/// 2D curves lie in the plane z = 0; a Z given for them counts in the distance.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit nearest scene.swp --point 0.5 2\n  \
    splinekit nearest scene.swp --curve path --point 1 -2 0.5 --accuracy 1e-12 --json\n\n\
    JSON output (--json) is one object: {\"curve\": NAME, \"u\": U, \"point\": [x, y, z], \"distance\": D}.")]
pub struct NearestArgs {
    /// SWP file to read
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Curve to search: a name, or a 0-based index (`2` or `#2`); a name wins [default: 0]
    #[arg(long, value_name = "NAME|INDEX", allow_negative_numbers = true)]
    pub curve: Option<String>,

    /// The point: X Y, or X Y Z (Z is 0 when left out)
    #[arg(long, value_names = ["X", "Y", "Z"], num_args = 2..=3, required = true, allow_negative_numbers = true)]
    #[arg(value_parser = finite)]
    pub point: Vec<f64>,

    /// How far the distance printed may exceed the smallest one, in length units; positive
    #[arg(long, value_name = "A", default_value = "1e-9", allow_hyphen_values = true, value_parser = positive_finite)]
    pub accuracy: f64,

    /// Print one JSON object instead of text
    #[arg(long)]
    pub json: bool,
}

/// Runs the command, writing to `out`.
pub fn run(args: &NearestArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let doc = select::load(&args.file)?;
    let sel = select::select(&doc, &args.file, args.curve.as_deref())?;
    let q = DVec3::new(args.point[0], args.point[1], args.point.get(2).copied().unwrap_or(0.0));
    let n = sel.curve.nearest(q, args.accuracy);
    if !n.distance.is_finite() || !n.point.is_finite() {
        bail!(
            "curve {}: the distance overflows f64 arithmetic (the curve or the point is too close to the largest \
             number, about 1.8e308); scale them down",
            sel.name
        );
    }
    if n.error > args.accuracy {
        eprintln!(
            "warning: curve {}: the distance is within {:.1e} of the smallest, not the --accuracy {:?}: {}",
            sel.name,
            n.error,
            args.accuracy,
            if n.error <= n.accuracy {
                "f64 arithmetic cannot resolve more for this curve and point"
            } else {
                "very many points of the curve are almost equally near (the search stopped at its work limit)"
            }
        );
    }
    let p = n.point;
    if args.json {
        writeln!(
            out,
            "{{\"curve\": {}, \"u\": {}, \"point\": [{}, {}, {}], \"distance\": {}}}",
            json_str(&sel.name),
            JsonNum(n.u),
            JsonNum(p.x),
            JsonNum(p.y),
            JsonNum(p.z),
            JsonNum(n.distance)
        )?;
        return Ok(());
    }
    let segments = sel.curve.num_segments();
    let plural = if segments == 1 { "" } else { "s" };
    writeln!(out, "curve: {} ({}, {segments} segment{plural})", sel.name, sel.swp.keyword())?;
    writeln!(out, "u: {}", n.u)?;
    writeln!(out, "point: {} {} {}", p.x + 0.0, p.y + 0.0, p.z + 0.0)?;
    writeln!(out, "distance: {}", n.distance)?;
    Ok(())
}
