//! `splinekit curve`: a curve's points at uniform parameter steps (SPEC §1.3, mode 1).

use std::io::Write;
use std::path::PathBuf;

use clap::ValueEnum;
use splinekit::ParamCurve;
use splinekit_io::MAX_STEPS;

use crate::output::{JsonNum, json_array, json_str};
use crate::select;

/// Print a curve's points at uniform parameter steps, with their parameter u.
///
/// Each segment gives steps+1 points at t = i/steps; joined segments share their join point,
/// so a curve of m segments gives m·steps + 1 points, u = k + i/steps running over [0, m]. A
/// circle is one segment: steps+1 points counter-clockwise from angle 0. On a closed curve
/// the last point repeats the first exactly.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit curve scene.swp\n  \
    splinekit curve scene.swp --curve profile --steps 100\n  \
    splinekit curve scene.swp --curve 3 --format json\n\n\
    CSV has the header `u,x,y,z`; JSON is {\"curve\": NAME, \"steps\": N, \"points\": [{\"u\", \"x\", \"y\", \"z\"}, …]}. \
    2D curves have z = 0.")]
pub struct CurveArgs {
    /// SWP file to read
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Curve to print: a name, or a 0-based index (`2` or `#2`); a name wins [default: 0]
    #[arg(long, value_name = "NAME|INDEX", allow_negative_numbers = true)]
    pub curve: Option<String>,

    /// Steps per segment, 1 to 1000000 [default: the curve's STEPS in the file]
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    #[arg(value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_STEPS)))]
    pub steps: Option<u32>,

    /// Output format
    #[arg(long, value_enum, value_name = "FORMAT", default_value_t = Format::Csv)]
    pub format: Format,
}

/// Output format of `curve`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Comma-separated values with the header `u,x,y,z`
    Csv,
    /// One JSON object: curve, steps, points
    Json,
}

/// Runs the command, writing to `out`.
pub fn run(args: &CurveArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let doc = select::load(&args.file)?;
    let sel = select::select(&doc, &args.file, args.curve.as_deref())?;
    let curve = &sel.curve;
    let steps = u64::from(args.steps.unwrap_or(sel.swp.steps).max(1));
    let segments = curve.num_segments() as u64;
    let last = segments * steps;
    let closed = curve.is_closed();
    // u = j / steps for j = k·steps + i: integer arithmetic, then one division.
    let points = (0..=last).map(|j| {
        let u = j as f64 / steps as f64;
        let p = if closed && j == last { curve.eval(0.0) } else { curve.eval(u) };
        (u, p)
    });

    match args.format {
        Format::Csv => {
            out.write_all(b"u,x,y,z\n")?;
            for (u, p) in points {
                writeln!(out, "{u},{},{},{}", p.x, p.y, p.z)?;
            }
        }
        Format::Json => {
            write!(out, "{{\n  \"curve\": {},\n  \"steps\": {steps},\n  \"points\": ", json_str(&sel.name))?;
            json_array(out, "  ", points, |o, (u, p)| {
                write!(
                    o,
                    "{{\"u\": {}, \"x\": {}, \"y\": {}, \"z\": {}}}",
                    JsonNum(u),
                    JsonNum(p.x),
                    JsonNum(p.y),
                    JsonNum(p.z)
                )
            })?;
            out.write_all(b"\n}\n")?;
        }
    }
    Ok(())
}
