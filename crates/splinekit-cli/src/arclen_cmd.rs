//! `splinekit arclen`: the u–s table of a curve, its length, `u(s)` queries and points
//! spaced evenly by arc length (`s(u)`, the distance travelled along the curve from `u = 0`).

use std::io::Write;
use std::path::PathBuf;

use anyhow::bail;
use clap::ValueEnum;
use glam::DVec3;
use splinekit::{AnyCurve, ArclenIndex, ArclenTable, ParamCurve, TableMethod};

use crate::output::{JsonNum, json_array, json_str};
use crate::select;

/// Refuse tables and resamplings with more points than this.
pub const MAX_POINTS: usize = 10_000_000;

/// Print the u–s arc-length table of a curve, its total length, u(s) queries and points
/// evenly spaced by arc length.
///
/// The table has N samples per segment: rows u = k + i/N over the curve's parameter range
/// [0, segments], row 0 being (u=0, s=0). `chord` sums straight-line distances between
/// samples (a lower bound), `gauss3` integrates the speed with 3-point Gauss–Legendre per
/// interval; `adaptive` computes the length to the stated accuracy and prints no table.
/// `--at-s` and `--spacing` invert s(u): by linear interpolation in the table for chord and
/// gauss3, exactly (to --accuracy, in length units) for adaptive.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    splinekit arclen scene.swp\n  \
    splinekit arclen scene.swp --curve path --method gauss3 --samples 10\n  \
    splinekit arclen scene.swp --curve 2 --at-s 0.417 --at-s 1.5\n  \
    splinekit arclen scene.swp --method adaptive --accuracy 1e-12 --spacing 0.5 --json\n\n\
    JSON output (--json) is one object with keys in this order: curve, method, samples_per_segment, \
    table ([{\"u\", \"s\"}], empty for adaptive), length, at_s ([{\"s\", \"u\"}], only with --at-s), \
    points ([[x, y, z]], only with --spacing).")]
pub struct ArclenArgs {
    /// SWP file to read
    #[arg(value_name = "FILE")]
    pub file: PathBuf,

    /// Curve to measure: a name, or a 0-based index (`2` or `#2`); a name wins [default: 0]
    #[arg(long, value_name = "NAME|INDEX", allow_negative_numbers = true)]
    pub curve: Option<String>,

    /// Table samples per curve segment, at least 1 (chord and gauss3). Too few for a curve that
    /// turns much within a segment (a helix of many turns) alias: the length is then compared
    /// with the adaptive one and a warning says when they differ by more than 2%
    #[arg(long, value_name = "N", default_value_t = 5, allow_hyphen_values = true)]
    #[arg(value_parser = clap::value_parser!(u32).range(1..))]
    pub samples: u32,

    /// How to measure arc length
    #[arg(long, value_enum, value_name = "METHOD", default_value_t = Method::Chord)]
    pub method: Method,

    /// Accuracy of the adaptive length and exact inverse, in length units; positive (adaptive only)
    #[arg(long, value_name = "A", default_value = "1e-9", allow_hyphen_values = true, value_parser = positive_finite)]
    pub accuracy: f64,

    /// Print the parameter u at arc length S from the start (repeatable; clamped to [0, length])
    #[arg(long = "at-s", value_name = "S", allow_hyphen_values = true, value_parser = finite)]
    pub at_s: Vec<f64>,

    /// Print the points at s = 0, DS, 2·DS, … up to the length; DS positive
    #[arg(long, value_name = "DS", allow_hyphen_values = true, value_parser = positive_finite)]
    pub spacing: Option<f64>,

    /// Print one JSON object instead of text
    #[arg(long)]
    pub json: bool,
}

/// Arc-length method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// Table: straight-line distance between consecutive samples
    Chord,
    /// Table: 3-point Gauss–Legendre quadrature of the speed on each interval
    Gauss3,
    /// No table: adaptive Gauss–Kronrod length to --accuracy, exact inverse
    Adaptive,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Self::Chord => "chord",
            Self::Gauss3 => "gauss3",
            Self::Adaptive => "adaptive",
        }
    }
}

/// A finite number.
pub(crate) fn finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err("must be a finite number".into()),
        Err(_) => Err(format!("{text:?} is not a number")),
    }
}

/// A positive finite number.
pub(crate) fn positive_finite(text: &str) -> Result<f64, String> {
    match finite(text)? {
        x if x > 0.0 => Ok(x),
        _ => Err("must be greater than 0".into()),
    }
}

/// How `s → u` is answered.
enum Inverse {
    /// Linear interpolation in a table.
    Table(ArclenTable),
    /// Exact to the index's accuracy.
    Exact(ArclenIndex),
}

impl Inverse {
    fn u_at(&self, curve: &AnyCurve<DVec3>, s: f64) -> f64 {
        match self {
            Self::Table(table) => table.u_at(s),
            Self::Exact(index) => index.u_at(curve, s),
        }
    }
}

/// Runs the command, writing to `out`.
pub fn run(args: &ArclenArgs, out: &mut impl Write) -> anyhow::Result<()> {
    let doc = select::load(&args.file)?;
    let sel = select::select(&doc, &args.file, args.curve.as_deref())?;
    let curve = &sel.curve;
    let segments = curve.num_segments();
    let samples = args.samples as usize;

    // Everything that can fail is checked before the first byte is written.
    let inverse = match args.method {
        Method::Chord | Method::Gauss3 => {
            let rows = samples.checked_mul(segments).and_then(|r| r.checked_add(1));
            if rows.is_none_or(|r| r > MAX_POINTS) {
                bail!(
                    "--samples {samples} on curve {} ({segments} segments) gives more than {MAX_POINTS} table rows",
                    sel.name
                );
            }
            let method = if args.method == Method::Chord { TableMethod::Chord } else { TableMethod::Gauss3 };
            Inverse::Table(ArclenTable::new(curve, method, samples))
        }
        Method::Adaptive => Inverse::Exact(ArclenIndex::new(curve, args.accuracy)),
    };
    let length = match &inverse {
        Inverse::Table(table) => table.length(),
        Inverse::Exact(index) => index.length(),
    };
    // a length past the largest f64 (coordinates near 1e308) is no answer
    let table_finite = match &inverse {
        Inverse::Table(table) => table.iter_rows().all(|(u, s)| u.is_finite() && s.is_finite()),
        Inverse::Exact(_) => true,
    };
    if !length.is_finite() || !table_finite {
        bail!(
            "curve {}: its arc length overflows f64 arithmetic (its coordinates are too close to the largest \
             number, about 1.8e308); scale the curve down",
            sel.name
        );
    }
    // a table that aliases (too few samples for the curve's turns) can be far off: compare
    // with the adaptive length, to a relative 1e-6, and say so
    if let Inverse::Table(_) = &inverse {
        let reference = ArclenIndex::new(curve, 1e-6 * length.max(f64::MIN_POSITIVE)).length();
        if reference.is_finite() && (length - reference).abs() > 0.02 * reference {
            eprintln!(
                "warning: curve {}: the {} table's length {length} differs from the adaptive length {reference} by \
                 {:.0}%: {samples} samples per segment are too few for this curve; raise --samples or use \
                 --method adaptive",
                sel.name,
                args.method.name(),
                100.0 * (length - reference).abs() / reference
            );
        }
    }
    // the accuracy met, when it is not the one asked (said on standard error)
    let met = match &inverse {
        Inverse::Exact(index) if !index.meets_accuracy() => {
            let error = 2.0 * index.error();
            eprintln!(
                "warning: curve {}: the length and positions are within about {error:.1e}, not the --accuracy {:?}: \
                 f64 arithmetic cannot resolve more on this curve (about 1e-15 of its length, more where its \
                 coordinates dwarf its detail)",
                sel.name, args.accuracy
            );
            Some(error)
        }
        _ => None,
    };
    let at_s: Vec<(f64, f64)> = args.at_s.iter().map(|&s| (s, inverse.u_at(curve, s))).collect();
    let spacing = match args.spacing {
        None => None,
        Some(ds) => {
            // Same count rule as splinekit::resample_every: the end point is included only
            // when the length is a multiple of ds (up to rounding).
            let count = (length / ds + 1e-9).floor() + 1.0;
            if count.is_nan() || count > MAX_POINTS as f64 {
                bail!(
                    "--spacing {ds:?} on curve {} of length {length} gives {count} points, more than the limit of {MAX_POINTS}",
                    sel.name
                );
            }
            Some((ds, count as usize))
        }
    };
    // Computed lazily while writing: (s, u, point).
    let points = spacing.map(|(ds, count)| {
        let inverse = &inverse;
        (0..count).map(move |i| {
            let s = (i as f64 * ds).min(length);
            let u = inverse.u_at(curve, s);
            (s, u, curve.eval(u))
        })
    });
    let table = match &inverse {
        Inverse::Table(table) => Some(table),
        Inverse::Exact(_) => None,
    };

    if args.json {
        write!(out, "{{\n  \"curve\": {},\n", json_str(&sel.name))?;
        writeln!(out, "  \"method\": {},", json_str(args.method.name()))?;
        write!(out, "  \"samples_per_segment\": {samples},\n  \"table\": ")?;
        let rows = table.into_iter().flat_map(ArclenTable::iter_rows);
        json_array(out, "  ", rows, |o, (u, s)| write!(o, "{{\"u\": {}, \"s\": {}}}", JsonNum(u), JsonNum(s)))?;
        write!(out, ",\n  \"length\": {}", JsonNum(length))?;
        if !args.at_s.is_empty() {
            out.write_all(b",\n  \"at_s\": ")?;
            json_array(out, "  ", &at_s, |o, &(s, u)| write!(o, "{{\"s\": {}, \"u\": {}}}", JsonNum(s), JsonNum(u)))?;
        }
        if let Some(points) = points {
            out.write_all(b",\n  \"points\": ")?;
            json_array(out, "  ", points, |o, (_, _, p)| {
                write!(o, "[{}, {}, {}]", JsonNum(p.x), JsonNum(p.y), JsonNum(p.z))
            })?;
        }
        out.write_all(b"\n}\n")?;
        return Ok(());
    }

    let kind = sel.swp.keyword();
    let plural = if segments == 1 { "" } else { "s" };
    writeln!(out, "curve: {} ({kind}, {segments} segment{plural})", sel.name)?;
    match table {
        Some(table) => {
            writeln!(out, "method: {}, {samples} samples per segment", args.method.name())?;
            writeln!(out, "{:>14} {:>14}", "u", "s")?;
            for (u, s) in table.iter_rows() {
                writeln!(out, "{u:>14.6} {s:>14.6}")?;
            }
        }
        None => writeln!(out, "method: adaptive, accuracy {:?}", args.accuracy)?,
    }
    writeln!(out, "length: {length}")?;
    if !at_s.is_empty() {
        let how = match table {
            Some(_) => "linear interpolation in the table".to_string(),
            None => format!("exact to {:?}", met.unwrap_or(args.accuracy)),
        };
        writeln!(out, "\nu at s ({how}):\n{:>14} {:>14}", "s", "u")?;
        for (s, u) in &at_s {
            writeln!(out, "{s:>14.9} {u:>14.9}")?;
        }
    }
    if let (Some(points), Some((ds, count))) = (points, spacing) {
        writeln!(out, "\npoints every {ds} of arc length ({count}):")?;
        writeln!(out, "{:>14} {:>14} {:>14} {:>14} {:>14}", "s", "u", "x", "y", "z")?;
        for (s, u, p) in points {
            writeln!(out, "{s:>14.9} {u:>14.9} {:>14.9} {:>14.9} {:>14.9}", p.x, p.y, p.z)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_parsers() {
        assert_eq!(finite("-1.5"), Ok(-1.5));
        assert!(finite("nan").is_err());
        assert!(finite("inf").is_err());
        assert!(finite("x").is_err());
        assert_eq!(positive_finite("1e-9"), Ok(1e-9));
        assert!(positive_finite("0").is_err());
        assert!(positive_finite("-2").is_err());
    }
}
