//! Formatting shared by the commands: numbers, strings, error lines and the progress bar.
//!
//! Floats are written with the shortest text that reads back to the same `f64`, so output
//! is exact and the same bytes on every run. In JSON a float always keeps a decimal point
//! or an exponent (`0.0`, `1.5`, `1e-7`), so readers see a float, never an integer. JSON is written by hand, in a
//! fixed key order, one array element per line.

use std::fmt;

use splinekit_io::mesh::MeshFormat;

/// A float as JSON: shortest round-trip text with a `.0` or exponent (Rust's `{:?}`), or
/// `null` when not finite; a negative zero is written `0.0`
/// (JSON has no NaN or infinity).
#[derive(Clone, Copy)]
pub struct JsonNum(pub f64);

impl fmt::Display for JsonNum {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // `+ 0.0` writes a negative zero as 0.0
        if self.0.is_finite() { write!(f, "{:?}", self.0 + 0.0) } else { f.write_str("null") }
    }
}

/// A string as a JSON string literal (quoted and escaped).
pub fn json_str(s: &str) -> String {
    // Serializing a &str cannot fail.
    serde_json::to_string(s).unwrap_or_else(|_| String::from("\"\""))
}

/// Writes `[` + the items (one per line, indented, comma-separated) + `]`.
pub fn json_array<W, I, F>(out: &mut W, indent: &str, items: I, mut write_item: F) -> std::io::Result<()>
where
    W: std::io::Write,
    I: IntoIterator,
    F: FnMut(&mut W, I::Item) -> std::io::Result<()>,
{
    let mut first = true;
    out.write_all(b"[")?;
    for item in items {
        out.write_all(if first { b"\n" } else { b",\n" })?;
        write!(out, "{indent}  ")?;
        write_item(out, item)?;
        first = false;
    }
    if !first {
        write!(out, "\n{indent}")?;
    }
    out.write_all(b"]")
}

/// An error and its causes on one line, `outer: cause: …`.
///
/// Each error of splinekit's crates holds its whole story in its message (`file:line:col:
/// found …, expected …`, `cannot write: <the system's reason>`) and returns no source, so
/// the chain here is only the contexts this binary adds, each printed once.
pub fn error_message(err: &anyhow::Error) -> String {
    format!("{err:#}")
}

/// A bar on standard error when it is a terminal: `steps` steps, the elapsed time and what is
/// being done, redrawn while a long step runs.
pub fn progress_bar(steps: usize) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(steps as u64);
        let style = indicatif::ProgressStyle::with_template("[{bar:30}] {pos}/{len} {elapsed} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .progress_chars("=> ");
        bar.set_style(style);
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        bar
    })
}

/// The parser of a mesh format option: the extensions of [`MeshFormat::ALL`], each with its
/// description in `--help`.
pub fn mesh_format() -> impl clap::builder::TypedValueParser<Value = MeshFormat> {
    use clap::builder::TypedValueParser as _;
    let values = MeshFormat::ALL.map(|f| clap::builder::PossibleValue::new(f.extension()).help(f.description()));
    clap::builder::PossibleValuesParser::new(values)
        .try_map(|name: String| MeshFormat::from_extension(&name).ok_or_else(|| format!("unknown mesh format {name}")))
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::*;

    #[test]
    fn numbers_and_strings() {
        assert_eq!(JsonNum(0.0).to_string(), "0.0");
        assert_eq!(JsonNum(-0.0).to_string(), "0.0");
        assert_eq!(JsonNum(5.0).to_string(), "5.0");
        assert_eq!(JsonNum(0.1).to_string(), "0.1");
        assert_eq!(JsonNum(-1e-7).to_string(), "-1e-7");
        assert_eq!(JsonNum(1e300).to_string(), "1e300");
        for x in [0.0, 5.0, -1e-7, 1e300, 0.1 + 0.2] {
            assert!(serde_json::from_str::<serde_json::Value>(&JsonNum(x).to_string()).unwrap().is_f64());
        }
        assert_eq!(JsonNum(f64::NAN).to_string(), "null");
        assert_eq!(JsonNum(f64::INFINITY).to_string(), "null");
        assert_eq!(json_str("a\"b\\c"), r#""a\"b\\c""#);
        let x = 0.1 + 0.2;
        assert_eq!(JsonNum(x).to_string().parse::<f64>().unwrap(), x);
    }

    #[test]
    fn arrays() {
        let mut out = Vec::new();
        json_array(&mut out, "  ", [1, 2], |o, i| write!(o, "{i}")).unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), "[\n    1,\n    2\n  ]");
        let mut out = Vec::new();
        json_array(&mut out, "  ", Vec::<i32>::new(), |o, i| write!(o, "{i}")).unwrap();
        assert_eq!(out, b"[]");
    }

    #[test]
    fn error_messages_print_the_chain_once() {
        let e = anyhow::Error::new(std::io::Error::other("too big")).context("cannot write out.obj");
        assert_eq!(error_message(&e), "cannot write out.obj: too big");
        let e = anyhow::anyhow!("no curve named x").context("core.swp");
        assert_eq!(error_message(&e), "core.swp: no curve named x");
    }

    /// The crates' errors that wrap another print it and do not also return it as their
    /// source, so that a chain printer never shows a cause twice.
    #[test]
    fn wrapping_errors_print_their_cause_and_return_no_source() {
        let swp = splinekit_io::SwpDocument::read(std::path::Path::new("/nonexistent/dir/x.swp")).unwrap_err();
        let spline = splinekit::SplineError::InsufficientPoints { kind: "x", needed: 4, given: 1 };
        let curve = || splinekit_io::surface::SurfaceError::Curve { curve: "c".into(), error: spline.clone() };
        let surface = curve();
        let lathe = splinekit::sweep::surface::SurfaceError::Keys { curve: "radius", error: spline.clone() };
        let render = splinekit_render::RenderError::Surface { path: "a.swp".into(), error: curve() };
        let topology = splinekit::subdiv::SubdivError::from(splinekit::subdiv::TopologyError::RepeatedVertex {
            face: 1,
            vertex: 2,
        });
        let errors: [&dyn std::error::Error; 6] = [&swp, &spline, &surface, &lathe, &render, &topology];
        for e in errors {
            assert!(e.source().is_none(), "{e}");
        }
        assert!(render.to_string().ends_with(&spline.to_string()), "{render}");
    }
}
