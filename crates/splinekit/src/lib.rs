//! # splinekit — the geometry core
//!
//! Spline curves in 2D and 3D (`f64`, glam's [`DVec2`](glam::DVec2) /
//! [`DVec3`](glam::DVec3)), their arc length and its inverse. No I/O, no UI: file formats
//! live in `splinekit-io`, the command line in `splinekit-cli`.
//!
//! Every spline kind compiles to a [`PiecewiseCubic`], a chain of [`CubicBezier`]
//! segments over the concatenated parameter `u ∈ [0, segments]`; arc length and the
//! geometric queries are written once against the [`ParamCurve`] trait.
//!
//! ```
//! use glam::DVec2;
//! use splinekit::{CatmullRom, ParamCurve, ArclenTable};
//! let pts: Vec<DVec2> = (0..6).map(|i| DVec2::new(i as f64, (i % 2) as f64)).collect();
//! let curve = CatmullRom::new(&pts, false, CatmullRom::<DVec2>::CENTRIPETAL).unwrap().to_piecewise();
//! assert_eq!(curve.num_segments(), 3);
//! let length = curve.arclen(1e-9);            // adaptive, |error| ≤ 1e-9
//! let table = ArclenTable::chord(&curve, 5);  // 3·5 + 1 rows
//! assert_eq!(table.len(), 16);
//! assert!(table.length() <= length);          // chords never overshoot
//! ```
//!
//! Exact inverse arc length to a stated accuracy in length units:
//!
//! ```
//! use glam::DVec2;
//! use splinekit::{CubicBezier, ParamCurve};
//! let c = CubicBezier::new(DVec2::ZERO, DVec2::new(30.0, 90.0), DVec2::new(70.0, -40.0), DVec2::new(100.0, 10.0));
//! let t = c.inv_arclen(50.0, 1e-9);
//! assert!((c.arclen_range(0.0, t, 1e-12).length - 50.0).abs() <= 1e-9);
//! ```
//!
//! No cargo features yet.

pub mod arclen;
pub mod curve;
pub mod flatten;
pub mod frame;
pub mod mesh;
pub mod subdiv;
pub mod sweep;
pub mod vector;
mod wide;

pub use arclen::{
    ArcPoint, ArclenEstimate, ArclenIndex, ArclenTable, DEFAULT_ACCURACY, ResampleError, TableMethod, arclen_relative,
    inv_arclen, resample_equal, resample_every,
};
pub use curve::{
    Aabb, AnyCurve, BEZIER_BASIS, BSPLINE_BASIS, BSpline, BesselOverhauser, BezierCurve, BezierSpline,
    CATMULL_ROM_BASIS, CatmullRom, Circle, CubicBezier, Helix, Hermite, KochanekBartels, MAX_BEZIER_POINTS,
    MAX_NURBS_DEGREE, MAX_NURBS_POINTS, Nearest, Nurbs, ParamCurve, PiecewiseCubic, SplineError, Tcb, Trefoil,
};
pub use mesh::{Adjacency, FaceVarying, MeshError, PolyMesh, TriMesh, VertexCurvature, vertex_curvature};
pub use vector::Vector;
