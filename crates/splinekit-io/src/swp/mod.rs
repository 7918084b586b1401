//! The SWP format: curve and sweep descriptions (reader and writer).
//!
//! SWP is the plain-text format of the MIT 6.837 / Aalto ME-C3100 "curves and surfaces"
//! assignments: a stream of whitespace-separated tokens that describes spline curves and the
//! surfaces swept from them. [`SwpDocument::parse`] reads it into an [`SwpDocument`], and
//! [`SwpDocument::to_swp_string`] writes one back. [`SwpDocument::validate`] checks a document
//! built in memory against the reader's rules before it is written.
//!
//! # Grammar
//!
//! ```text
//! document := object*
//! object   := curve | hermite | tcb | bezn | nurbs | circle | helix | trefoil | srev | gcyl
//! curve    := ("bez2"|"bsp2"|"cr2"|"bo2"|"bez3"|"bsp3"|"cr3"|"bo3") NAME STEPS NPOINTS option* point{NPOINTS}
//! hermite  := ("her2"|"her3") NAME STEPS NPAIRS option* (point point){NPAIRS}   point, then tangent
//! tcb      := ("tcb2"|"tcb3") NAME STEPS NKEYS option* key{NKEYS}
//! bezn     := ("bezn2"|"bezn3") NAME STEPS NPOINTS ["open"] point{NPOINTS}   one Bézier curve of degree NPOINTS − 1
//! nurbs    := ("nurbs2"|"nurbs3") NAME STEPS NPOINTS nopt* wpoint{NPOINTS}
//! nopt     := "closed" | "open" | "degree" D | "knots" k{NPOINTS+D+1} | "knots" "[" k{NPOINTS+D+1} "]" | "[" "knots" k{NPOINTS+D+1} "]"
//! wpoint   := "[" x y w "]" | "[" x y z w "]"   nurbs2 | nurbs3: a control point and its weight w > 0
//! point    := "[" x y "]"        2D kinds (bez2 bsp2 cr2 bo2 her2); z is 0 in the model
//!           | "[" x y z "]"      3D kinds (bez3 bsp3 cr3 bo3 her3)
//! key      := "[" x y t c b "]" | "[" x y z t c b "]"   tcb2 | tcb3: tension, continuity, bias in [−1, 1]
//! circle   := "circ" NAME STEPS RADIUS          xy-plane, centred at the origin
//! helix    := "helix" NAME STEPS RADIUS PITCH TURNS     3D, about +z from (RADIUS, 0, 0)
//! trefoil  := "trefoil" NAME STEPS SIZE         3D, closed
//! srev     := "srev" NAME STEPS PROFILE         surface of revolution
//! gcyl     := "gcyl" NAME PROFILE SWEEP clause* generalized cylinder
//! clause   := "scale" SCALE | "twist" TWIST     each at most once, in either order
//! option   := "closed" | "open" | "alpha" A | "uniform" | "centripetal" | "chordal"
//! NAME     := "."                               anonymous, may repeat
//!           | any other token                   unique among all curves and surfaces
//! ```
//!
//! - **Tokens** are separated by whitespace: space, tab, CR, LF, vertical tab and form feed,
//!   so LF and CRLF files read the same. `[` and `]` are tokens of their own even when glued to
//!   other text: `[3 0]`, `[ 3 0 ]` and `[-2 2] [-4 0]` on one line all work. A UTF-8 byte
//!   order mark at the very start is skipped (it does not count as a column).
//! - **Keywords** are lowercase. `bez2 bsp2 bez3 bsp3 circ srev gcyl` are the original SWP
//!   keywords; `cr2 cr3 her2 her3 tcb2 tcb3 bo2 bo3 bezn2 bezn3 nurbs2 nurbs3 helix trefoil` and
//!   the gcyl clause words `scale` and `twist`
//!   are ours (see *Extensions*).
//! - **Names**: `.` is anonymous and may repeat; every other token is a name that must be unique
//!   across all curves *and* surfaces. `[` and `]` cannot be names, and neither can anything
//!   starting with `#` (that is a comment). A curve is referenced by name, and only after its
//!   definition; anonymous curves cannot be referenced. Names that look like keywords or numbers
//!   are allowed, because every position in the grammar is fixed.
//! - **STEPS** is an integer from 1 to [`MAX_STEPS`] (1 000 000).
//! - **NPOINTS** is a non-negative integer that must satisfy the kind's point-count rule:
//!
//!   | kind | open | closed |
//!   |---|---|---|
//!   | Bézier (`bez2`, `bez3`) | 3m+1 points, m ≥ 1 (4, 7, 10, …) | 3m points, m ≥ 1 (3, 6, 9, …); the last segment returns to the first point |
//!   | B-spline (`bsp2`, `bsp3`) | ≥ 4 | ≥ 3 |
//!   | Catmull-Rom (`cr2`, `cr3`) | ≥ 4 | ≥ 3 |
//!   | Kochanek–Bartels (`tcb2`, `tcb3`) | ≥ 4 | ≥ 3 |
//!   | Bessel–Overhauser (`bo2`, `bo3`) | ≥ 4 | ≥ 3 |
//!   | Hermite (`her2`, `her3`) | ≥ 2 pairs | ≥ 2 pairs |
//!   | Bézier of any degree (`bezn2`, `bezn3`) | 2 to 65 | — |
//!   | NURBS of degree D (`nurbs2`, `nurbs3`) | ≥ D + 1 | ≥ D + 1 and ≥ 3 |
//!
//! - **Numbers** are decimal floating-point numbers such as `-0.765483`, `2`, `1e-3` or `.5`.
//!   `nan`, `inf` and numbers too large for an `f64` are errors. RADIUS must be ≥ 0 (a radius of
//!   0 is valid: real files use it as a degenerate sweep).
//! - **Profiles** of `srev` and `gcyl` must be 2D curves (`bez2`, `bsp2`, `cr2`, `her2`, `tcb2`,
//!   `bo2`, `bezn2`, `nurbs2`, `circ`);
//!   a `gcyl` sweep may be 2D or 3D. Scale and twist curves must be 2D as well.
//! - **Quirks of real files** that are accepted: CRLF line endings, brackets with or without
//!   inner spaces, several points on one line, repeated end points, trailing spaces, no final
//!   newline, whitespace-only trailing lines.
//!
//! # Extensions
//!
//! A plain SWP file never uses these, so it parses exactly as it always did.
//!
//! - **Comments**: `#` starts a comment that runs to the end of the line, wherever it appears
//!   (also glued to a token: `[1 2]# note`).
//! - **Catmull-Rom** curves `cr2` / `cr3` have exactly the shape of `bsp2` / `bsp3`:
//!   `cr3 NAME STEPS N [x y z] …`.
//! - **Hermite** curves `her2` / `her3`: `her2 NAME STEPS N` followed by N pairs
//!   `[point] [tangent]`.
//! - **Kochanek–Bartels** curves `tcb2` / `tcb3` ([`splinekit::KochanekBartels`]): the shape
//!   of `cr2` / `cr3` with each key's tension, continuity and bias (each from −1 to 1) after its
//!   coordinates, `tcb2 NAME STEPS N [x y t c b] …`; all zero is the uniform Catmull-Rom curve.
//! - **Bessel–Overhauser** curves `bo2` / `bo3` ([`splinekit::BesselOverhauser`]): exactly the
//!   shape of `cr2` / `cr3`, `bo3 NAME STEPS N [x y z] …`.
//!
//!   Like Catmull-Rom curves, both interpolate their inner keys: open, N ≥ 4 and N − 3 segments
//!   from the second key to the second-to-last; closed, N ≥ 3 and N segments. STEPS counts
//!   the steps of each segment.
//! - **Bézier curves of any degree** `bezn2` / `bezn3` ([`splinekit::BezierCurve`]): one curve
//!   through its first and last point, of degree NPOINTS − 1 (2 to 65 points: a line, a
//!   quadratic, a cubic, … up to degree 64), `bezn2 NAME STEPS N [x y] …`. One segment: STEPS
//!   counts the steps of the whole curve. Always open.
//! - **NURBS** `nurbs2` / `nurbs3` ([`splinekit::Nurbs`]): control points with a weight each
//!   (w > 0) inside the brackets, `nurbs2 NAME STEPS N degree D [x y w] …`. `degree D`
//!   (1 to 32; default 3) and `knots k1 … kM` (M = N + D + 1 non-decreasing numbers; default
//!   the clamped uniform vector, so the curve starts at its first point and ends at its last)
//!   are options; `degree` comes before `knots`, and the knots may stand in brackets
//!   (`knots [0 0 0 1 1 1]` or `[knots 0 0 0 1 1 1]`). `closed` makes a periodic curve with
//!   uniform knots (no `knots` then). Each knot span of positive length is one segment:
//!   STEPS counts the steps of each span.
//!
//! ```text
//! # a quarter circle: the exact arc as a rational quadratic
//! nurbs2 arc 16 3 degree 2
//! [1 0 1] [1 1 0.7071067811865476] [0 1 1]
//! ```
//!
//! - **Curve options** stand between NPOINTS and the first `[`:
//!   - `closed` makes the curve closed (see the point-count table), `open` is the default;
//!   - Catmull-Rom only: `alpha A` with 0 ≤ A ≤ 1 picks the knot parametrization (0 uniform,
//!     0.5 centripetal, 1 chordal; the default is 0), and the words `uniform`, `centripetal`
//!     and `chordal` are short for `alpha 0`, `alpha 0.5` and `alpha 1`.
//!
//!   Each group (open/closed, parametrization) may be given at most once, and an option on a
//!   kind it does not apply to (such as `alpha` on `bsp2`) is an error. Circles are always
//!   closed and take no options.
//!
//! ```text
//! # a closed centripetal Catmull-Rom loop and a Hermite arc
//! cr2 loop 30 4 closed centripetal
//! [0 0] [1 0] [1 1] [0 1]
//!
//! her3 arc 20 2
//! [0 0 0] [1 0 0]
//! [1 1 0] [0 1 0]
//! ```
//!
//! - **Helix** `helix NAME STEPS RADIUS PITCH TURNS`: the exact helix
//!   `(r·cos θ, r·sin θ, PITCH·θ/2π)`, `θ` from 0 to `2π·TURNS` ([`splinekit::Helix`]). RADIUS
//!   ≥ 0; PITCH, the rise per turn, is any number (negative: left-handed); TURNS is a number
//!   with 0 < TURNS ≤ [`MAX_HELIX_TURNS`]. Open, one segment: STEPS counts the steps of the
//!   whole helix (STEPS + 1 points), as for `circ`.
//! - **Trefoil knot** `trefoil NAME STEPS SIZE`: the exact, closed knot
//!   `SIZE·(sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t)`, `t` from 0 to 2π
//!   ([`splinekit::Trefoil`]); SIZE ≥ 0. One segment: STEPS + 1 points.
//!
//!   Both are 3D curves (like `bez3`): they can be sweeps, not profiles, and they take no
//!   options.
//! - **Scale and twist curves** for `gcyl`: `gcyl NAME PROFILE SWEEP [scale SCALE] [twist TWIST]`
//!   (each clause at most once, in either order). At the sweep point at normalized arc length
//!   `σ ∈ [0, 1]` of the sweep curve, the curves are read at the same fraction `σ` of their own
//!   *parameter* range (`u = σ·segments`):
//!   - the SCALE curve's point `(sx, sy)` scales the profile's x by `sx` and its y by `sy`;
//!   - the TWIST curve's x coordinate is an angle in degrees by which the profile turns about
//!     the sweep tangent (from N toward B); its y is not used.
//!
//!   Both must be 2D curves defined earlier. The words `scale` and `twist` are recognized only
//!   right after a gcyl's SWEEP (or after a previous clause); every other position is fixed, so
//!   curves and surfaces may still be *named* `scale` or `twist`, and no object keyword can be
//!   mistaken for a clause.
//!
//! ```text
//! circ wire 24 0.15
//! helix coil 300 1 0.6 5
//! bsp2 taper 8 6 [0.3 0.3] [1 1] [1 1] [1 1] [1 1] [0.3 0.3]
//! gcyl spring wire coil scale taper
//! ```
//!
//! # Errors
//!
//! Parsing stops at the first error and produces nothing. [`SwpError`] displays as
//! `FILE:LINE:COL: found <what was found>, expected <what>`, for example
//! `core.swp:3:7: found "1.2.3", expected a number (x coordinate of point 2 of bsp2 curve "profile")`.
//! Lines and columns are 1-based, and columns count characters. An unexpected end of file
//! points just after the last token.
//!
//! # Example
//!
//! ```
//! use splinekit_io::swp::{SwpCurveKind, SwpDocument, SwpGeometry, SwpSurfaceKind};
//!
//! let text = "bez2 profile 50 4\r\n[-2 2] [-4 0] [0 0] [-2 -2]\r\n\r\nsrev . 90 profile\r\n";
//! let doc = SwpDocument::parse(text, "norm.swp")?;
//! assert_eq!(doc.curves[0].kind, SwpCurveKind::Bezier);
//! let SwpGeometry::Points(points) = &doc.curves[0].geometry else { unreachable!() };
//! assert_eq!(points[1], glam::DVec3::new(-4.0, 0.0, 0.0));
//! assert_eq!(doc.surfaces[0].kind, SwpSurfaceKind::Revolution { steps: 90, profile: 0 });
//!
//! let err = SwpDocument::parse("bez2 . 20 5", "bad.swp").unwrap_err();
//! assert_eq!((err.line(), err.column()), (1, 11));
//! # Ok::<(), splinekit_io::swp::SwpError>(())
//! ```

mod error;
mod lexer;
mod parser;
mod validate;
mod writer;

use std::path::Path;

use glam::DVec3;
use splinekit::sweep::MeshLayout;
use splinekit::{MAX_BEZIER_POINTS, MAX_NURBS_DEGREE, MAX_NURBS_POINTS, Tcb};

pub use crate::location::SourcePos;
pub use error::{SwpError, SwpErrorKind};
pub use validate::{SwpCurveRole, SwpInvalid, SwpInvalidKind, SwpNumber, SwpObject};

/// The largest STEPS value accepted for curves and surfaces of revolution.
///
/// STEPS says how finely a curve or surface is tessellated; one million is far more than any
/// display needs and keeps a typo from asking for gigabytes of vertices.
pub const MAX_STEPS: u32 = 1_000_000;

/// The degree of a NURBS curve whose header gives no `degree D` (cubic, as the other kinds).
pub const DEFAULT_NURBS_DEGREE: u32 = 3;

/// The largest TURNS value accepted for a helix.
///
/// Adaptive tessellation of a helix needs a number of points proportional to its turns; ten
/// thousand turns is far more than any model needs and keeps a typo from asking for gigabytes.
pub const MAX_HELIX_TURNS: f64 = 10_000.0;

/// The contents of an SWP file: curves and the surfaces swept from them.
///
/// Curves and surfaces are kept in two lists in file order. Surfaces refer to curves by index
/// into [`curves`](Self::curves).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SwpDocument {
    /// The curves, in file order.
    pub curves: Vec<SwpCurve>,
    /// The surfaces, in file order.
    pub surfaces: Vec<SwpSurface>,
}

/// One curve of an SWP file.
#[derive(Debug, Clone, PartialEq)]
pub struct SwpCurve {
    /// The curve's name, or `None` for the anonymous name `.`.
    pub name: Option<String>,
    /// The kind of curve (Bézier, B-spline, …).
    pub kind: SwpCurveKind,
    /// 2 or 3: the dimension of the keyword (`bez2` is 2, `bez3` is 3, `circ` is 2, `helix` and
    /// `trefoil` are 3).
    pub dim: u8,
    /// Tessellation steps per segment (for circles, helices and trefoils: for the whole
    /// curve), 1..=[`MAX_STEPS`].
    pub steps: u32,
    /// Whether the curve is closed (the `closed` option). Always `true` for circles and
    /// trefoils, `false` for helices.
    pub closed: bool,
    /// Control points, Hermite data or the parameters of a circle, helix or trefoil,
    /// depending on [`kind`](Self::kind).
    pub geometry: SwpGeometry,
    /// Where the curve's keyword stood.
    pub pos: SourcePos,
}

impl SwpCurve {
    /// The curve's name, or `#<index>` for an anonymous curve (`index` being its position in
    /// [`SwpDocument::curves`]), for use in messages.
    #[must_use]
    pub fn display_name(&self, index: usize) -> String {
        match &self.name {
            Some(name) => name.clone(),
            None => format!("#{index}"),
        }
    }

    /// The SWP keyword of this curve, such as `"bez2"` or `"circ"` (from [`kind`](Self::kind)
    /// and [`dim`](Self::dim); any `dim` other than 3 counts as 2).
    #[must_use]
    pub fn keyword(&self) -> &'static str {
        let three = self.dim == 3;
        match (self.kind, three) {
            (SwpCurveKind::Bezier, false) => "bez2",
            (SwpCurveKind::Bezier, true) => "bez3",
            (SwpCurveKind::BSpline, false) => "bsp2",
            (SwpCurveKind::BSpline, true) => "bsp3",
            (SwpCurveKind::CatmullRom { .. }, false) => "cr2",
            (SwpCurveKind::CatmullRom { .. }, true) => "cr3",
            (SwpCurveKind::KochanekBartels, false) => "tcb2",
            (SwpCurveKind::KochanekBartels, true) => "tcb3",
            (SwpCurveKind::BesselOverhauser, false) => "bo2",
            (SwpCurveKind::BesselOverhauser, true) => "bo3",
            (SwpCurveKind::BezierN, false) => "bezn2",
            (SwpCurveKind::BezierN, true) => "bezn3",
            (SwpCurveKind::Nurbs { .. }, false) => "nurbs2",
            (SwpCurveKind::Nurbs { .. }, true) => "nurbs3",
            (SwpCurveKind::Hermite, false) => "her2",
            (SwpCurveKind::Hermite, true) => "her3",
            (SwpCurveKind::Circle, _) => "circ",
            (SwpCurveKind::Helix, _) => "helix",
            (SwpCurveKind::Trefoil, _) => "trefoil",
        }
    }
}

/// The kind of an SWP curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SwpCurveKind {
    /// Piecewise cubic Bézier (`bez2`, `bez3`).
    Bezier,
    /// Uniform cubic B-spline (`bsp2`, `bsp3`).
    BSpline,
    /// Cubic Catmull-Rom spline (`cr2`, `cr3`, an extension).
    CatmullRom {
        /// Knot parametrization exponent in `[0, 1]`: 0 uniform, 0.5 centripetal, 1 chordal.
        alpha: f64,
    },
    /// Cubic Hermite spline from points and tangents (`her2`, `her3`, an extension).
    Hermite,
    /// Kochanek–Bartels spline, with a tension, continuity and bias per key (`tcb2`, `tcb3`,
    /// an extension; geometry [`SwpGeometry::Tcb`]).
    KochanekBartels,
    /// Bessel–Overhauser spline (`bo2`, `bo3`, an extension).
    BesselOverhauser,
    /// One Bézier curve of any degree: `n` control points make degree `n − 1` (`bezn2`,
    /// `bezn3`, an extension; [`splinekit::BezierCurve`]). Always open.
    BezierN,
    /// NURBS curve of `degree` (`nurbs2`, `nurbs3`, an extension; geometry
    /// [`SwpGeometry::Nurbs`], core [`splinekit::Nurbs`]). Closed means periodic.
    Nurbs {
        /// The degree, 1 to [`splinekit::MAX_NURBS_DEGREE`].
        degree: u32,
    },
    /// Circle in the xy-plane, centred at the origin (`circ`).
    Circle,
    /// Circular helix about +z (`helix`, an extension).
    Helix,
    /// Trefoil knot (`trefoil`, an extension).
    Trefoil,
}

impl SwpCurveKind {
    /// Whether a curve of this kind may have `count` control points (point-tangent pairs for
    /// [`Hermite`](Self::Hermite)), closed or open: the point-count rule of the
    /// [module docs](self), which the reader and [`SwpDocument::validate`] both apply.
    ///
    /// Circles, helices and trefoils have no control points: they accept only 0. A Bézier
    /// curve of any degree ([`BezierN`](Self::BezierN)) takes 2 to
    /// [`MAX_BEZIER_POINTS`] points and is never closed; a NURBS
    /// at least `degree + 1` points (closed: also at least 3), at most
    /// [`MAX_NURBS_POINTS`].
    ///
    /// ```
    /// use splinekit_io::SwpCurveKind;
    ///
    /// let open: Vec<u64> = (0..12).filter(|&n| SwpCurveKind::Bezier.accepts_point_count(false, n)).collect();
    /// assert_eq!(open, [4, 7, 10]);
    /// assert!(SwpCurveKind::BSpline.accepts_point_count(true, 3));
    /// assert!(!SwpCurveKind::BSpline.accepts_point_count(false, 3));
    /// ```
    #[must_use]
    pub fn accepts_point_count(self, closed: bool, count: u64) -> bool {
        match (self, closed) {
            (Self::Bezier, false) => count >= 4 && (count - 1).is_multiple_of(3),
            (Self::Bezier, true) => count >= 3 && count.is_multiple_of(3),
            (Self::BSpline | Self::CatmullRom { .. } | Self::KochanekBartels | Self::BesselOverhauser, false) => {
                count >= 4
            }
            (Self::BSpline | Self::CatmullRom { .. } | Self::KochanekBartels | Self::BesselOverhauser, true) => {
                count >= 3
            }
            (Self::Hermite, _) => count >= 2,
            (Self::BezierN, false) => count >= 2 && count <= MAX_BEZIER_POINTS as u64,
            (Self::BezierN, true) => false,
            (Self::Nurbs { degree }, closed) => {
                (1..=MAX_NURBS_DEGREE as u32).contains(&degree)
                    && count > u64::from(degree)
                    && count <= MAX_NURBS_POINTS as u64
                    && (!closed || count >= 3)
            }
            (Self::Circle | Self::Helix | Self::Trefoil, _) => count == 0,
        }
    }
}

/// The geometric data of an SWP curve.
#[derive(Debug, Clone, PartialEq)]
pub enum SwpGeometry {
    /// Control points of a Bézier, B-spline, Catmull-Rom or Bessel–Overhauser curve; z = 0
    /// for 2D kinds.
    Points(Vec<DVec3>),
    /// Points and tangents of a Hermite curve (same length); z = 0 for `her2`.
    Hermite {
        /// The interpolated points.
        points: Vec<DVec3>,
        /// The tangent at each point.
        tangents: Vec<DVec3>,
    },
    /// Keys of a Kochanek–Bartels curve and the tension, continuity and bias of each (same
    /// length); z = 0 for `tcb2`.
    Tcb {
        /// The keys.
        points: Vec<DVec3>,
        /// Each key's tension, continuity and bias, each in `[−1, 1]`.
        shape: Vec<Tcb>,
    },
    /// Control points and weights of a NURBS curve (same length; z = 0 for `nurbs2`), and its
    /// knot vector if the file gives one (`None`: clamped uniform, or periodic when closed).
    Nurbs {
        /// The control points.
        points: Vec<DVec3>,
        /// Each point's weight (> 0).
        weights: Vec<f64>,
        /// `points.len() + degree + 1` non-decreasing knots, or `None` for the default.
        knots: Option<Vec<f64>>,
    },
    /// A circle of the given radius (≥ 0).
    Circle {
        /// The radius.
        radius: f64,
    },
    /// A helix (see [`splinekit::Helix`]).
    Helix {
        /// The radius (≥ 0).
        radius: f64,
        /// The rise per turn along +z (negative: left-handed).
        pitch: f64,
        /// The number of turns (in `(0, MAX_HELIX_TURNS]` when parsed).
        turns: f64,
    },
    /// A trefoil knot (see [`splinekit::Trefoil`]).
    Trefoil {
        /// The size (≥ 0).
        size: f64,
    },
}

impl SwpGeometry {
    /// The points of a spline (control points, Hermite points or Kochanek–Bartels keys);
    /// empty for circles, helices and trefoils.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        match self {
            Self::Points(points)
            | Self::Hermite { points, .. }
            | Self::Tcb { points, .. }
            | Self::Nurbs { points, .. } => points,
            Self::Circle { .. } | Self::Helix { .. } | Self::Trefoil { .. } => &[],
        }
    }

    /// The points of a spline, to edit (see [`points`](Self::points)); `None` for circles,
    /// helices and trefoils. Tangents, shapes and weights are not touched: keep their lists as
    /// long.
    #[must_use]
    pub fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        match self {
            Self::Points(points)
            | Self::Hermite { points, .. }
            | Self::Tcb { points, .. }
            | Self::Nurbs { points, .. } => Some(points),
            Self::Circle { .. } | Self::Helix { .. } | Self::Trefoil { .. } => None,
        }
    }
}

/// One surface of an SWP file.
#[derive(Debug, Clone, PartialEq)]
pub struct SwpSurface {
    /// The surface's name, or `None` for the anonymous name `.`.
    pub name: Option<String>,
    /// The kind of surface, with its curve references.
    pub kind: SwpSurfaceKind,
    /// Its own tessellation, layout, frames and caps (option words after the surface), which
    /// replace the sweep options given to [`SwpDocument::surface_mesh`].
    pub settings: SwpSurfaceSettings,
    /// Where the surface's keyword stood.
    pub pos: SourcePos,
}

/// A surface's own settings (an extension: option words after the surface, such as
/// `gcyl tube ring path tolerance 0.01 frames rmf no-caps`). `None` leaves the value to the
/// options the surface is swept with.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SwpSurfaceSettings {
    /// `tolerance D` or `angle-tolerance DEGREES`: adaptive tessellation instead of the
    /// curves' steps (any surface).
    pub tessellation: Option<SwpTessellation>,
    /// `layout welded` or `layout compat` (`srev`, `gcyl`).
    pub layout: Option<MeshLayout>,
    /// `frames auto`, `frames sequential`, `frames rmf`, `frames frenet` or `frames zup` (`gcyl`).
    pub frames: Option<SwpFrames>,
    /// `caps` or `no-caps`: flat caps on an open sweep of a closed profile (`gcyl`).
    pub caps: Option<bool>,
    /// `align origin`, `align centre` (or `center`) or `align start`: which point of the
    /// profile rides on the path (`gcyl`).
    pub align: Option<crate::surface::ProfileAlign>,
    /// `join mitre`, `join round` or `join bevel`: how the walls meet at a sharp corner of
    /// the path (`gcyl`).
    pub join: Option<splinekit::sweep::Join>,
    /// `mitre-limit R` (R ≥ 1): the longest mitre, as a multiple of the profile's offset,
    /// before a mitre join falls back to a bevel (`gcyl`).
    pub mitre_limit: Option<f64>,
    /// `scale-mode multiply` or `scale-mode override`: whether a scale curve multiplies the
    /// profile as drawn or gives its size (`gcyl`).
    pub scale_mode: Option<crate::surface::ScaleMode>,
}

impl SwpSurfaceSettings {
    /// Whether no setting is given.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }
}

/// A surface's own tessellation (see [`SwpSurfaceSettings`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SwpTessellation {
    /// `tolerance D`: every polyline within distance `D` of its curve, revolutions in enough
    /// slices that no chord strays further from its circle.
    Distance(f64),
    /// `angle-tolerance A`: adaptive by control-polygon angle, `A` in degrees; revolutions
    /// in slices of at most `A`.
    AngleDegrees(f64),
}

/// The frames a `gcyl` carries its profile with (see [`SwpSurfaceSettings`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum SwpFrames {
    /// `frames auto` (the default): rotation-minimizing along a path that leaves the plane
    /// `z = const`, sequential along one in it (where the two agree), sequential in the compat
    /// layout.
    #[default]
    Auto,
    /// `frames sequential`: the course program's frames.
    Sequential,
    /// `frames rmf`: rotation-minimizing frames.
    RotationMinimizing,
    /// `frames frenet`: Frenet frames.
    Frenet,
    /// `frames zup`: frames whose binormal leans toward +z (Blender's "Z-Up").
    ZUp,
}

/// The setting words and the surface keywords each applies to.
pub(crate) const SETTING_WORDS: [(&str, &[&str]); 9] = [
    ("tolerance", &["srev", "gcyl", "zrev", "lathe"]),
    ("angle-tolerance", &["srev", "gcyl", "zrev", "lathe"]),
    ("layout", &["srev", "gcyl", "xsweep"]),
    ("frames", &["gcyl"]),
    ("caps", &["gcyl"]),
    ("align", &["gcyl"]),
    ("join", &["gcyl"]),
    ("mitre-limit", &["gcyl"]),
    ("scale-mode", &["gcyl"]),
];

impl SwpSurface {
    /// The surface's name, or `#<index>` for an anonymous surface (`index` being its position in
    /// [`SwpDocument::surfaces`]), for use in messages.
    #[must_use]
    pub fn display_name(&self, index: usize) -> String {
        match &self.name {
            Some(name) => name.clone(),
            None => format!("#{index}"),
        }
    }
}

/// The kind of an SWP surface. Curve references are indices into [`SwpDocument::curves`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SwpSurfaceKind {
    /// Surface of revolution (`srev`): a 2D profile turned around the y axis.
    Revolution {
        /// Tessellation steps around the axis, 1..=[`MAX_STEPS`].
        steps: u32,
        /// The 2D profile curve.
        profile: usize,
    },
    /// Generalized cylinder (`gcyl`): a 2D profile swept along a 2D or 3D curve, optionally
    /// scaled and twisted along the way (see *Extensions* in the [module docs](self)).
    GeneralizedCylinder {
        /// The 2D profile curve.
        profile: usize,
        /// The sweep curve.
        sweep: usize,
        /// The 2D scale curve (`scale` clause): its point `(sx, sy)` scales the profile's x and y.
        scale: Option<usize>,
        /// The 2D twist curve (`twist` clause): its x is the twist angle in degrees.
        twist: Option<usize>,
    },
    /// Surface of revolution about +z (`zrev`, an extension), as the CS 4620 revolution tool
    /// made them: the profile tessellated by control-polygon angle, profile point `(x, y)`
    /// going to `(s·x·cos φ, s·x·sin φ, s·y)` in `ceil(2π / slice_tolerance)` slices.
    RevolutionZ {
        /// The 2D profile curve (a spline: `bez2`, `bsp2`, `cr2` or `her2`).
        profile: usize,
        /// Angle tolerance ε in radians (`epsilon` option): a piece of the profile is halved
        /// while an angle of its control polygon exceeds ε/2.
        epsilon: f64,
        /// Largest angle between slices, in radians (`slice-tolerance` option).
        slice_tolerance: f64,
        /// Uniform scale `s` (`scale` option).
        scale: f64,
    },
    /// The CS 4620 sweep tool's surface (`xsweep`, an extension): a cross-section B-spline
    /// swept along a B-spline placed in the xz-plane, each cut by the tool's angle rule (a
    /// piece halved while a control-polygon angle exceeds its epsilon), the cross-section
    /// scaled; what the tool's annotated OBJ files hold.
    ToolSweep {
        /// The cross-section (a `bsp2` curve).
        profile: usize,
        /// The swept-along curve (a `bsp2` curve, its (x, y) placed at (x, 0, y)).
        path: usize,
        /// The cross-section's angle tolerance in radians (`epsilon` option).
        epsilon: f64,
        /// The swept-along curve's angle tolerance in radians (`path-epsilon` option).
        path_epsilon: f64,
        /// The cross-section's scale (`scale` option).
        scale: f64,
    },
    /// Lathe (`lathe`, an extension): separate radius and height curves,
    /// `P(u, v) = (r(v)·cos 2πu, r(v)·sin 2πu, z(v))` about +z. The keys of `r` and `z` are
    /// the y coordinates of the two curves' control points (their x only places the keys on
    /// the graph); both curves are `bez2` curves of `3m + 1` points.
    Lathe {
        /// Intervals along `v`, 1..=[`MAX_STEPS`].
        stacks: u32,
        /// Slices around the axis, 3..=[`MAX_STEPS`].
        slices: u32,
        /// The radius curve r(v).
        radius: usize,
        /// The height curve z(v).
        height: usize,
    },
}

/// The default angle tolerances of an `xsweep` surface, in radians (about 2.9°, as the
/// bundled files of the sweep tool).
pub const DEFAULT_XSWEEP_EPSILON: f64 = 0.05;
/// The default angle tolerance ε of a `zrev` surface, in radians (about 5.7°).
pub const DEFAULT_ZREV_EPSILON: f64 = 0.1;
/// The default slice tolerance of a `zrev` surface, in radians: 32 slices.
pub const DEFAULT_ZREV_SLICE_TOLERANCE: f64 = std::f64::consts::TAU / 32.0;

impl SwpSurfaceKind {
    /// The surface's keyword: `srev`, `gcyl`, `zrev`, `xsweep` or `lathe`.
    #[must_use]
    pub fn keyword(&self) -> &'static str {
        match self {
            Self::Revolution { .. } => "srev",
            Self::GeneralizedCylinder { .. } => "gcyl",
            Self::RevolutionZ { .. } => "zrev",
            Self::ToolSweep { .. } => "xsweep",
            Self::Lathe { .. } => "lathe",
        }
    }

    /// The curves the surface uses, with their roles, in file order.
    #[must_use]
    pub fn references(&self) -> Vec<(SwpCurveRole, usize)> {
        match *self {
            Self::Revolution { profile, .. } | Self::RevolutionZ { profile, .. } => {
                vec![(SwpCurveRole::Profile, profile)]
            }
            Self::GeneralizedCylinder { profile, sweep, scale, twist } => {
                let mut refs = vec![(SwpCurveRole::Profile, profile), (SwpCurveRole::Sweep, sweep)];
                refs.extend(scale.map(|c| (SwpCurveRole::Scale, c)));
                refs.extend(twist.map(|c| (SwpCurveRole::Twist, c)));
                refs
            }
            Self::ToolSweep { profile, path, .. } => {
                vec![(SwpCurveRole::Profile, profile), (SwpCurveRole::Sweep, path)]
            }
            Self::Lathe { radius, height, .. } => vec![(SwpCurveRole::Radius, radius), (SwpCurveRole::Height, height)],
        }
    }
}

/// A `gcyl` clause (an extension): which shaping curve it names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SwpClause {
    /// `scale CURVE`: the profile's x and y are scaled by the curve's point.
    Scale,
    /// `twist CURVE`: the profile turns by the curve's x, in degrees.
    Twist,
}

impl SwpClause {
    /// The clause's word: `"scale"` or `"twist"`.
    #[must_use]
    pub fn keyword(self) -> &'static str {
        match self {
            Self::Scale => "scale",
            Self::Twist => "twist",
        }
    }
}

impl std::fmt::Display for SwpClause {
    /// Formats as the clause's word.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.keyword())
    }
}

impl SwpDocument {
    /// Parses SWP text. `origin` names the text in error messages (usually the file name).
    ///
    /// # Errors
    ///
    /// Returns the first error found, with its line and column; see the [module docs](self).
    pub fn parse(text: &str, origin: &str) -> Result<Self, SwpError> {
        parser::parse(text, origin)
    }

    /// Reads and parses an SWP file. Error messages name the file by `path`.
    ///
    /// # Errors
    ///
    /// Returns an error if the file cannot be read (with the operating system's message), is
    /// not UTF-8 (pointing at the first bad byte), or does not parse.
    pub fn read(path: &Path) -> Result<Self, SwpError> {
        let origin = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| SwpError::io(path, e))?;
        match std::str::from_utf8(&bytes) {
            Ok(text) => Self::parse(text, &origin),
            Err(e) => Err(SwpError::invalid_utf8(&origin, &bytes, e.valid_up_to())),
        }
    }

    /// The index of the curve called `name`, if there is one.
    #[must_use]
    pub fn curve_index(&self, name: &str) -> Option<usize> {
        self.curves.iter().position(|c| c.name.as_deref() == Some(name))
    }

    /// The index of the surface called `name`, if there is one.
    #[must_use]
    pub fn surface_index(&self, name: &str) -> Option<usize> {
        self.surfaces.iter().position(|s| s.name.as_deref() == Some(name))
    }

    /// Writes the document as SWP text.
    ///
    /// The output uses plain SWP keywords and no options wherever the options are the
    /// defaults (a NURBS header always says its `degree`, and its `knots` when it has them),
    /// LF line endings, one point (or Hermite point-tangent pair, Kochanek–Bartels key
    /// `[x y t c b]` or NURBS point `[x y w]`) per line, a blank
    /// line between objects, all curves before all surfaces, and Rust's shortest round-trip
    /// formatting of `f64` (so every coordinate reads back exactly).
    ///
    /// **Round trip.** For every document that [`parse`](Self::parse) can return,
    /// `parse(to_swp_string())` returns an equal document except for [`SourcePos`] fields and
    /// these names:
    ///
    /// - an anonymous curve that a surface references cannot be written as `.`, so it gets a
    ///   generated name `_c<index>` (or `_c<index>_<k>` if that is taken) that clashes with no
    ///   other name;
    /// - a name that cannot be written as a token (empty, `.`, containing whitespace, `[`, `]`
    ///   or `#`) or that repeats an earlier name is replaced the same way (`_c<index>` for
    ///   curves, `_s<index>` for surfaces). Parsed documents never contain such names.
    ///
    /// The writer does not validate. A document that breaks the rules (a wrong point count, a
    /// 3D profile, scale or twist curve, a reference out of range — written as `.` —, a
    /// non-finite number, `steps` or helix turns out of range, …) is written anyway, and the
    /// output then fails to parse. The z coordinates of 2D curves are not written; a Hermite
    /// curve writes as many pairs as its shorter list has entries (a Kochanek–Bartels curve as
    /// many keys as its shorter list of points and shapes, a NURBS curve as many points as its
    /// shorter list of points and weights). Scale and twist clauses are
    /// written after the sweep, `scale` first.
    ///
    /// Call [`validate`](Self::validate) first to refuse such a document before writing: when
    /// it returns `Ok`, the text written here parses back to a document equal to this one
    /// except for [`SourcePos`] fields (no name is replaced either).
    #[must_use]
    pub fn to_swp_string(&self) -> String {
        writer::write(self)
    }
}
