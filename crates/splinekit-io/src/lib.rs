//! File formats for splinekit.
//!
//! All file input and output of the project lives here, so that the geometry core
//! (`splinekit`) stays free of I/O. This crate reads and writes
//!
//! - **SWP** files, the curve and sweep descriptions of the MIT 6.837 / Aalto ME-C3100 course
//!   software (module [`swp`]);
//! - mesh files (module [`mesh`]): [`load_mesh`] reads OBJ, binary glTF (`.glb`), PLY and STL
//!   into a [`PolyMesh`](splinekit::PolyMesh), and [`mesh::save`] writes a
//!   [`TriMesh`](splinekit::TriMesh) in any of the four, atomically.
//!
//! Readers report *where* a problem is: every error carries the file name and what was found
//! and expected, with a 1-based line and column in text files (in binary files, the record,
//! or for `.glb` a JSON path such as `meshes[0].primitives[1].indices`). They never panic,
//! whatever the input.
//!
//! # Reading an SWP file
//!
//! ```
//! use splinekit_io::{SwpCurveKind, SwpDocument, SwpGeometry, SwpSurfaceKind};
//!
//! let text = "bsp2 sweep 20 4\n[0 0] [1 0] [1 1] [0 1]\n\
//!             circ profile 50 0.4\n\
//!             gcyl tube profile sweep\n";
//! let doc = SwpDocument::parse(text, "tube.swp")?;
//! assert_eq!(doc.curves.len(), 2);
//! assert_eq!(doc.curves[1].geometry, SwpGeometry::Circle { radius: 0.4 });
//! let profile = doc.curve_index("profile").unwrap();
//! let sweep = doc.curve_index("sweep").unwrap();
//! let (scale, twist) = (None, None);
//! assert_eq!(doc.surfaces[0].kind, SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale, twist });
//! # Ok::<(), splinekit_io::SwpError>(())
//! ```
//!
//! # Errors point at the problem, and writing round-trips
//!
//! ```
//! use splinekit_io::SwpDocument;
//!
//! let err = SwpDocument::parse("bez2 . 20 4\n[0 0]\n[1 1.2.3]", "bad.swp").unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     r#"bad.swp:3:4: found "1.2.3", expected a number (y coordinate of point 2 of bez2 curve #0)"#
//! );
//!
//! let doc = SwpDocument::parse("cr2 loop 30 3 closed centripetal [0 0] [1 0] [0 1]", "a.swp")?;
//! let text = doc.to_swp_string();
//! assert_eq!(text, "cr2 loop 30 3 closed centripetal\n[0 0]\n[1 0]\n[0 1]\n");
//! assert_eq!(SwpDocument::parse(&text, "b.swp")?.curves[0].geometry, doc.curves[0].geometry);
//! # Ok::<(), splinekit_io::SwpError>(())
//! ```
//!
//! # Errors
//!
//! Every error's message is whole: [`SwpError`] and [`MeshIoError`] start with a [`Location`]
//! (the file, and a line and column, or a place in a binary file's structure), say what was
//! found and what was expected, and include the message of any error they wrap. No error of
//! this crate returns a [`source`](std::error::Error::source), so a program that prints an
//! error's chain (anyhow's `{:#}`) shows each cause once.
//!
//! # Feature flags
//!
//! None yet.

pub mod annotated;
pub mod convert;
pub mod location;
pub mod mesh;
pub mod surface;
pub mod swp;

pub use location::{Location, Position, SourcePos};
pub use mesh::atomic;
pub use mesh::{LoadedMesh, MeshFormat, MeshIoError, MeshIoErrorKind, ReadWarning, load_mesh};
pub use swp::{
    DEFAULT_NURBS_DEGREE, MAX_STEPS, SwpCurve, SwpCurveKind, SwpCurveRole, SwpDocument, SwpError, SwpErrorKind,
    SwpFrames, SwpGeometry, SwpInvalid, SwpInvalidKind, SwpNumber, SwpObject, SwpSurface, SwpSurfaceKind,
    SwpSurfaceSettings, SwpTessellation,
};
