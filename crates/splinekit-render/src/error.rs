//! [`RenderError`]: why a file could not be drawn.

use std::io;

/// Why a picture could not be made or written. Messages name the file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The SWP file could not be read or parsed (its message names file, line and column).
    #[error(transparent)]
    Swp(#[from] splinekit_io::SwpError),
    /// The mesh file could not be read or parsed.
    #[error(transparent)]
    Mesh(#[from] splinekit_io::MeshIoError),
    /// A surface of the SWP file could not be swept.
    #[error("{path}: {error}")]
    Surface {
        /// The SWP file.
        path: String,
        /// What went wrong.
        error: splinekit_io::surface::SurfaceError,
    },
    /// A curve of the SWP file does not compile.
    #[error("{path}: curve {curve}: {error}")]
    Curve {
        /// The SWP file.
        path: String,
        /// Display name of the curve.
        curve: String,
        /// What is wrong with it.
        error: splinekit::SplineError,
    },
    /// The input's extension names no format that can be drawn.
    #[error("{path}: cannot draw a file of this kind ({extension}); expected .swp, .obj, .glb, .ply or .stl")]
    UnknownInput {
        /// The input file.
        path: String,
        /// Its extension (`.xyz`), or `no extension`.
        extension: String,
    },
    /// The output's extension names no picture format.
    #[error("{path}: cannot write a picture of this kind ({extension}); expected .png or .svg")]
    UnknownOutput {
        /// The output file.
        path: String,
        /// Its extension (`.xyz`), or `no extension`.
        extension: String,
    },
    /// SVG was asked for a file that is drawn in 3D.
    #[error("{path}: SVG output draws curves only, and this file has {what}; write a .png instead")]
    SvgOf3d {
        /// The input file.
        path: String,
        /// `surfaces` or `a mesh`.
        what: &'static str,
    },
    /// Nothing to draw.
    #[error("{path}: nothing to draw ({what})")]
    Empty {
        /// The input file.
        path: String,
        /// What is missing, e.g. `no curves or surfaces`.
        what: &'static str,
    },
    /// The UV checker was asked for a file or mesh without texture coordinates.
    #[error("{path} has no texture coordinates")]
    NoTextureCoordinates {
        /// The input file.
        path: String,
    },
    /// A marker spacing that is not a positive number.
    #[error("marker spacing must be a positive number, found {0}")]
    BadMarkerSpacing(f64),
    /// A bundled example could not be built (a bug: the tests build every one).
    #[error("bundled example {name}: {message}")]
    Example {
        /// The example's file name.
        name: String,
        /// What went wrong.
        message: String,
    },
    /// PNG encoding or decoding failed.
    #[error("PNG: {0}")]
    Png(String),
    /// Writing the output failed (the temporary file is removed; an old file is untouched).
    #[error(transparent)]
    WriteFile(#[from] splinekit_io::atomic::WriteFileError),
    /// Writing the bytes of the output failed.
    #[error("{path}: cannot write: {error}")]
    Write {
        /// The output file.
        path: String,
        /// The operating system's error.
        error: io::Error,
    },
}
