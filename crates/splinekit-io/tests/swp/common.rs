//! Helpers shared by the SWP tests.

use std::path::{Path, PathBuf};

use splinekit_io::{SourcePos, SwpDocument, SwpError, SwpGeometry};

/// The folder holding the bundled SWP files.
pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/swp")
}

/// The 12 bundled SWP files, relative to [`data_dir`].
pub const DATA_FILES: [&str; 12] = [
    "circles.swp",
    "core.swp",
    "extra/dragonfly.swp",
    "extra/tube-table.swp",
    "gcyl/flircle.swp",
    "gcyl/florus.swp",
    "gcyl/gentorus.swp",
    "gcyl/tor.swp",
    "gcyl/weird.swp",
    "gcyl/weirder.swp",
    "srev/norm.swp",
    "srev/wineglass.swp",
];

/// Reads a bundled file, panicking with the error message if it does not parse.
pub fn load(rel: &str) -> SwpDocument {
    SwpDocument::read(&data_dir().join(rel)).unwrap_or_else(|e| panic!("{e}"))
}

/// The raw text of a bundled file.
pub fn text(rel: &str) -> String {
    std::fs::read_to_string(data_dir().join(rel)).unwrap()
}

/// Parses text that must be valid.
pub fn parse(text: &str) -> SwpDocument {
    SwpDocument::parse(text, "test.swp").unwrap_or_else(|e| panic!("{e}\n--- input ---\n{text}"))
}

/// Parses text that must fail, and returns the error.
pub fn parse_err(text: &str) -> SwpError {
    match SwpDocument::parse(text, "test.swp") {
        Ok(doc) => panic!("expected an error, got {doc:#?}\n--- input ---\n{text}"),
        Err(e) => e,
    }
}

/// The document with every source position reset, for comparing documents from different texts.
pub fn without_positions(mut doc: SwpDocument) -> SwpDocument {
    for c in &mut doc.curves {
        c.pos = SourcePos::default();
    }
    for s in &mut doc.surfaces {
        s.pos = SourcePos::default();
    }
    doc
}

/// The control points of a point-based curve (panics for Hermite and circles).
pub fn points(doc: &SwpDocument, index: usize) -> &[glam::DVec3] {
    match &doc.curves[index].geometry {
        SwpGeometry::Points(p) => p,
        other => panic!("curve {index} has no control points: {other:?}"),
    }
}

/// The radius of a circle (panics for other curves).
pub fn radius(doc: &SwpDocument, index: usize) -> f64 {
    match doc.curves[index].geometry {
        SwpGeometry::Circle { radius } => radius,
        ref other => panic!("curve {index} is not a circle: {other:?}"),
    }
}

/// Asserts that an error sits at `line:column` and that its message contains every one of
/// `parts`; prints the message on failure.
#[track_caller]
pub fn assert_error(err: &SwpError, line: usize, column: usize, parts: &[&str]) {
    let message = err.to_string();
    assert_eq!((err.line(), err.column()), (line, column), "wrong position in: {message}");
    assert!(message.starts_with(&format!("{}:{line}:{column}: found ", err.origin())), "wrong prefix: {message}");
    for part in parts {
        assert!(message.contains(part), "message lacks {part:?}:\n  {message}");
    }
}

/// Sweeps every surface of `doc` with the default options, panicking unless each gives a
/// mesh of finite positions with as many triangles as its counted estimate says.
#[allow(dead_code)] // for the files that include this one by path, not for tests/swp
pub fn sweeps_every_surface(doc: &SwpDocument) {
    let options = splinekit_io::surface::SurfaceOptions::default();
    for k in 0..doc.surfaces.len() {
        let mesh = doc.surface_mesh(k, &options).unwrap_or_else(|e| panic!("surface {k}: {e}"));
        assert!(mesh.num_triangles() > 0);
        assert!(mesh.positions.iter().all(|p| p.is_finite()), "surface {k}");
        assert_eq!(doc.surface_counts(k, &options).unwrap().triangles, mesh.num_triangles() as u64, "surface {k}");
    }
}
