//! `splinekit curve`: a curve's tessellated points (uniform steps, or adaptive by angle or
//! distance tolerance) with their frames `(T, N, B)`, as CSV, JSON or SVG.

use std::io::Write;
use std::path::PathBuf;

use anyhow::bail;
use clap::ValueEnum;
use splinekit::flatten::{self, Tessellation};
use splinekit::frame::{self, FrameMethod, FrameOptions, Side, StartNormal};
use splinekit_io::MAX_STEPS;

use crate::output::{JsonNum, json_array, json_str};
use crate::select;

/// The default of `--max-points`: 50 million points (a few gigabytes of text).
pub const DEFAULT_MAX_POINTS: u64 = 50_000_000;

/// Print a curve's tessellated points with their parameter u and frame (T, N, B).
///
/// Uniform steps by default: each segment gives steps+1 points at t = i/steps; joined
/// segments share their join point, so a curve of m segments gives m·steps + 1 points, u = k +
/// i/steps running over [0, m]. A circle is one segment: steps+1 points counter-clockwise
/// from angle 0; so are a helix (from (r, 0, 0), rising along +z), a trefoil knot and a Bézier
/// curve of any degree (bezn2, bezn3); a NURBS has a segment per knot span. On a closed curve
/// the last point repeats the first exactly. With
/// --tolerance the polyline stays within that distance of the curve (both ways); with
/// --angle-tolerance segments are split until their control polygons turn less than that.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit curve scene.swp\n  \
    splinekit curve scene.swp --curve profile --steps 100\n  \
    splinekit curve scene.swp --curve 3 --format json --frames rmf\n  \
    splinekit curve scene.swp --tolerance 0.001 --format svg > curve.svg\n\n\
    CSV has the header `u,x,y,z,tx,ty,tz,nx,ny,nz,bx,by,bz`; JSON is {\"curve\": NAME, \"steps\": N, \"points\": \
    [{\"u\", \"x\", \"y\", \"z\", \"t\": [..], \"n\": [..], \"b\": [..]}, …]} (\"steps\" is null for adaptive \
    modes). 2D curves have z = 0; with the default sequential frames their N is left of travel and B = +z. \
    SVG (2D curves only) draws the polyline, y up.")]
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
    #[arg(conflicts_with_all = ["tolerance", "angle_tolerance"])]
    pub steps: Option<u32>,

    /// Adaptive: the polyline stays within T (length units) of the curve, both ways
    #[arg(long, value_name = "T", conflicts_with = "angle_tolerance", allow_negative_numbers = true)]
    pub tolerance: Option<f64>,

    /// Adaptive by control-polygon angle, in degrees
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    pub angle_tolerance: Option<f64>,

    /// Frames: the course's sequential method (with the closed-curve fix), rotation-minimizing, or Frenet
    #[arg(long, value_enum, value_name = "METHOD", default_value_t = FrameChoice::Sequential)]
    pub frames: FrameChoice,

    /// Output format
    #[arg(long, value_enum, value_name = "FORMAT", default_value_t = Format::Csv)]
    pub format: Format,

    /// The most points the tessellation may give; counted before any is made, so a helix of
    /// many turns with a fine tolerance is refused at once instead of exhausting memory
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_POINTS)]
    pub max_points: u64,
}

/// Output format of `curve`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Comma-separated values with the header `u,x,y,z,tx,ty,tz,nx,ny,nz,bx,by,bz`
    Csv,
    /// One JSON object: curve, steps, points
    Json,
    /// An SVG drawing of the polyline (2D curves only)
    Svg,
}

/// Frame methods of `curve`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FrameChoice {
    /// Sequential (B₀ = +z), the course program's; N left of travel for 2D curves
    Sequential,
    /// Rotation-minimizing (double reflection)
    Rmf,
    /// Frenet, with fallbacks on straight runs
    Frenet,
}

/// Runs the command, writing to `out`.
pub fn run(args: &CurveArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let doc = select::load(&args.file)?;
    let sel = select::select(&doc, &args.file, args.curve.as_deref())?;
    let curve = &sel.curve;
    let (mode, steps) = match (args.tolerance, args.angle_tolerance) {
        (Some(t), _) if t > 0.0 && t.is_finite() => (Tessellation::Distance { tolerance: t }, None),
        (Some(t), _) => bail!("--tolerance must be a positive number, got {t}"),
        (None, Some(a)) if a > 0.0 && a.is_finite() => (Tessellation::Angle { tolerance: a.to_radians() }, None),
        (None, Some(a)) => bail!("--angle-tolerance must be a positive number of degrees, got {a}"),
        (None, None) => {
            let steps = args.steps.unwrap_or(sel.swp.steps).max(1);
            (Tessellation::Uniform { steps: steps as usize }, Some(steps))
        }
    };
    // counted before the points are made (a helix of many turns and a fine tolerance could
    // ask for billions)
    let count = flatten::flatten_count(curve, mode);
    if count > args.max_points {
        bail!(
            "curve {}: this tessellation would give {} points, more than --max-points {}; use a coarser \
             tolerance or fewer steps, or raise --max-points",
            sel.name,
            if count == u64::MAX { "too many".to_owned() } else { format!("up to {count}") },
            args.max_points
        );
    }
    let params = flatten::flatten_any(curve, mode);
    let method = match args.frames {
        FrameChoice::Sequential => FrameMethod::Sequential(Side::Left),
        FrameChoice::Rmf => FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left)),
        FrameChoice::Frenet => FrameMethod::Frenet,
    };
    let samples = frame::sample(curve, &params);
    let frames = frame::frames_for_samples(&samples, &FrameOptions::DEFAULT.with_method(method));
    // a point or frame past the largest f64 (coordinates near 1e308) is no answer
    let finite = samples.iter().all(|s| s.position.is_finite())
        && frames.iter().all(|f| f.t.is_finite() && f.n.is_finite() && f.b.is_finite());
    if !finite {
        bail!(
            "curve {}: its points or frames overflow f64 arithmetic (its coordinates are too close to the largest \
             number, about 1.8e308); scale the curve down",
            sel.name
        );
    }
    let closed = curve.is_closed();
    let last = samples.len().saturating_sub(1);
    // the last point of a closed curve repeats the first exactly
    let position = |i: usize| if closed && i == last { samples[0].position } else { samples[i].position };
    let rows = (0..samples.len()).map(|i| (samples[i].u, position(i), frames[i]));

    match args.format {
        Format::Csv => {
            out.write_all(b"u,x,y,z,tx,ty,tz,nx,ny,nz,bx,by,bz\n")?;
            for (u, p, f) in rows {
                // `+ 0.0` writes a negative zero as 0
                write!(out, "{u},{},{},{}", p.x + 0.0, p.y + 0.0, p.z + 0.0)?;
                for v in [f.t, f.n, f.b] {
                    write!(out, ",{},{},{}", v.x + 0.0, v.y + 0.0, v.z + 0.0)?;
                }
                out.write_all(b"\n")?;
            }
        }
        Format::Json => {
            let steps = steps.map_or_else(|| String::from("null"), |s| s.to_string());
            write!(out, "{{\n  \"curve\": {},\n  \"steps\": {steps},\n  \"points\": ", json_str(&sel.name))?;
            let vec = |v: glam::DVec3| format!("[{}, {}, {}]", JsonNum(v.x), JsonNum(v.y), JsonNum(v.z));
            json_array(out, "  ", rows, |o, (u, p, f)| {
                write!(
                    o,
                    "{{\"u\": {}, \"x\": {}, \"y\": {}, \"z\": {}, \"t\": {}, \"n\": {}, \"b\": {}}}",
                    JsonNum(u),
                    JsonNum(p.x),
                    JsonNum(p.y),
                    JsonNum(p.z),
                    vec(f.t),
                    vec(f.n),
                    vec(f.b)
                )
            })?;
            out.write_all(b"\n}\n")?;
        }
        Format::Svg => {
            if sel.swp.dim == 3 {
                bail!("--format svg draws 2D curves; curve {} is 3D", sel.name);
            }
            let pts: Vec<glam::DVec2> = (0..samples.len()).map(|i| position(i).truncate()).collect();
            write_svg(out, &sel.name, &pts)?;
        }
    }
    Ok(())
}

/// A self-contained SVG of a 2D polyline, y up, fitted with a 5 % margin.
fn write_svg(out: &mut impl Write, name: &str, pts: &[glam::DVec2]) -> std::io::Result<()> {
    let (mut lo, mut hi) = (glam::DVec2::splat(f64::INFINITY), glam::DVec2::splat(f64::NEG_INFINITY));
    for p in pts {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let size = (hi - lo).max_element().max(1e-9);
    let margin = 0.05 * size;
    let (x0, y0) = (lo.x - margin, -(hi.y + margin));
    let (w, h) = (hi.x - lo.x + 2.0 * margin, hi.y - lo.y + 2.0 * margin);
    let stroke = size / 400.0;
    writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{x0} {y0} {w} {h}\" width=\"800\" height=\"{}\">",
        (800.0 * h / w).round()
    )?;
    let title: String = name
        .chars()
        .map(|c| match c {
            '<' => '‹',
            '>' => '›',
            '&' => '+',
            c => c,
        })
        .collect();
    writeln!(out, "<title>{title}</title>")?;
    write!(
        out,
        "<polyline fill=\"none\" stroke=\"#1f4e9e\" stroke-width=\"{stroke}\" stroke-linejoin=\"round\" points=\""
    )?;
    for (i, p) in pts.iter().enumerate() {
        // `+ 0.0` and `0.0 −` turn a zero of either sign into +0 (no "-0" in the drawing)
        write!(out, "{}{},{}", if i == 0 { "" } else { " " }, p.x + 0.0, 0.0 - p.y)?;
    }
    writeln!(out, "\"/>")?;
    writeln!(out, "</svg>")
}
