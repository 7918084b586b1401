//! Checking an in-memory document against the reader's rules; see [`SwpDocument::validate`].

use std::collections::HashMap;
use std::fmt;

use glam::DVec3;
use splinekit::{MAX_BEZIER_POINTS, MAX_NURBS_DEGREE, MAX_NURBS_POINTS, Tcb};

use super::error::quote;
use super::lexer::is_space;
use super::{
    MAX_HELIX_TURNS, MAX_STEPS, SETTING_WORDS, SwpCurve, SwpCurveKind, SwpDocument, SwpGeometry, SwpSurface,
    SwpSurfaceKind, SwpTessellation,
};

impl SwpDocument {
    /// Checks the document with the rules the reader applies, so that it can be saved and
    /// opened again.
    ///
    /// When this returns `Ok`, [`to_swp_string`](Self::to_swp_string) writes text that
    /// [`parse`](Self::parse) reads back to a document equal to this one except for the
    /// [`SourcePos`](super::SourcePos) fields. The rules are those of the [module docs](super):
    ///
    /// - each curve's point count fits its kind, closed or open
    ///   ([`SwpCurveKind::accepts_point_count`]); its geometry matches its kind (a Hermite curve
    ///   has one tangent per point, a Kochanek–Bartels curve one shape per key); `dim` is 2 or 3 (2 for circles, 3 for helices and
    ///   trefoils); circles and trefoils are closed and helices open;
    /// - `steps` is from 1 to [`MAX_STEPS`]; every number is finite; radii and sizes are ≥ 0,
    ///   helix turns in `(0, MAX_HELIX_TURNS]`, Catmull-Rom alpha in `[0, 1]` and every tension,
    ///   continuity and bias in `[−1, 1]`; the points and
    ///   tangents of 2D curves have z = 0 (z is not written);
    /// - names are writable tokens (not empty, not `.`, without whitespace, `[`, `]` or `#`)
    ///   and unique among all curves and surfaces;
    /// - each curve a surface uses exists and has a name; profiles, scale and twist curves are
    ///   2D.
    ///
    /// # Errors
    ///
    /// Returns the first problem: curves in order, then surfaces. [`SwpInvalid`] says which
    /// object it is and displays a message such as
    /// `curve "profile": a B-spline needs at least 4 points; this one has 2`.
    ///
    /// ```
    /// use splinekit_io::{SwpCurveKind, SwpDocument, SwpGeometry, SwpInvalidKind, SwpObject};
    ///
    /// let mut doc = SwpDocument::parse("bsp2 profile 10 4 [0 0] [1 0] [1 1] [0 1]", "a.swp")?;
    /// assert_eq!(doc.validate(), Ok(()));
    ///
    /// let SwpGeometry::Points(points) = &mut doc.curves[0].geometry else { unreachable!() };
    /// points.truncate(2);
    /// let err = doc.validate().unwrap_err();
    /// assert_eq!(err.object(), SwpObject::Curve(0));
    /// assert_eq!(err.kind(), &SwpInvalidKind::PointCount { kind: SwpCurveKind::BSpline, closed: false, found: 2 });
    /// assert_eq!(err.to_string(), r#"curve "profile": a B-spline needs at least 4 points; this one has 2"#);
    /// # Ok::<(), splinekit_io::SwpError>(())
    /// ```
    pub fn validate(&self) -> Result<(), SwpInvalid> {
        let mut names: HashMap<&str, SwpObject> = HashMap::new();
        for (index, curve) in self.curves.iter().enumerate() {
            let object = SwpObject::Curve(index);
            let fail = |kind| SwpInvalid { object, name: curve.name.clone(), kind };
            check_name(curve.name.as_deref(), object, &mut names).map_err(fail)?;
            check_curve(curve).map_err(fail)?;
        }
        for (index, surface) in self.surfaces.iter().enumerate() {
            let object = SwpObject::Surface(index);
            let fail = |kind| SwpInvalid { object, name: surface.name.clone(), kind };
            check_name(surface.name.as_deref(), object, &mut names).map_err(fail)?;
            check_surface(&self.curves, surface).map_err(fail)?;
        }
        Ok(())
    }
}

/// A problem that keeps an [`SwpDocument`] from being saved: the file would not open, or would
/// open differently. Returned by [`SwpDocument::validate`].
///
/// It says which object the problem is about ([`object`](Self::object)), that object's name,
/// and what is wrong ([`kind`](Self::kind)). It displays as `curve "NAME": <problem>` or
/// `surface "NAME": <problem>` (anonymous objects as `curve #3`), in lowercase and without a
/// final period, for example
/// `surface "glass": its profile "path" is a 3D curve; a profile must be a 2D curve`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {kind}", Label(self.object, self.name.as_deref()))]
pub struct SwpInvalid {
    object: SwpObject,
    name: Option<String>,
    kind: SwpInvalidKind,
}

impl SwpInvalid {
    /// The curve or surface with the problem.
    #[must_use]
    pub fn object(&self) -> SwpObject {
        self.object
    }

    /// The object's name, or `None` if it is anonymous.
    #[must_use]
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// The object's name, or `#<index>` for an anonymous object (as
    /// [`SwpCurve::display_name`] and [`SwpSurface::display_name`]).
    #[must_use]
    pub fn display_name(&self) -> String {
        match (&self.name, self.object) {
            (Some(name), _) => name.clone(),
            (None, SwpObject::Curve(index) | SwpObject::Surface(index)) => format!("#{index}"),
        }
    }

    /// What is wrong.
    #[must_use]
    pub fn kind(&self) -> &SwpInvalidKind {
        &self.kind
    }
}

/// Formats an object as `curve "NAME"` or `curve #INDEX`.
struct Label<'a>(SwpObject, Option<&'a str>);

impl fmt::Display for Label<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (noun, index) = match self.0 {
            SwpObject::Curve(index) => ("curve", index),
            SwpObject::Surface(index) => ("surface", index),
        };
        match self.1 {
            Some(name) => write!(f, "{noun} {}", quote(name)),
            None => write!(f, "{noun} #{index}"),
        }
    }
}

/// Which object of an [`SwpDocument`] a problem is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SwpObject {
    /// The curve at this index of [`SwpDocument::curves`].
    Curve(usize),
    /// The surface at this index of [`SwpDocument::surfaces`].
    Surface(usize),
}

/// What a surface uses a curve for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SwpCurveRole {
    /// The profile of an `srev` or `gcyl` (must be 2D).
    Profile,
    /// The sweep curve of a `gcyl` (2D or 3D).
    Sweep,
    /// The scale curve of a `gcyl` (must be 2D).
    Scale,
    /// The twist curve of a `gcyl` (must be 2D).
    Twist,
    /// The radius curve of a `lathe` (must be 2D).
    Radius,
    /// The height curve of a `lathe` (must be 2D).
    Height,
}

impl SwpCurveRole {
    /// The role in one word: `profile`, `sweep`, `scale`, `twist`, `radius` or `height`.
    #[must_use]
    pub fn word(self) -> &'static str {
        match self {
            Self::Profile => "profile",
            Self::Sweep => "sweep",
            Self::Scale => "scale",
            Self::Twist => "twist",
            Self::Radius => "radius",
            Self::Height => "height",
        }
    }

    /// How messages call a curve in this role: `profile`, `sweep`, `scale curve`, `twist curve`.
    fn noun(self) -> &'static str {
        match self {
            Self::Profile => "profile",
            Self::Sweep => "sweep",
            Self::Scale => "scale curve",
            Self::Twist => "twist curve",
            Self::Radius => "radius curve",
            Self::Height => "height curve",
        }
    }
}

/// One number of a curve: a coordinate or a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SwpNumber {
    /// A coordinate of a control point (or of a Hermite point).
    Point {
        /// The index of the point in its list, from 0 (messages count from 1: `point 1`).
        index: usize,
        /// The coordinate: 0 for x, 1 for y, 2 for z.
        axis: usize,
    },
    /// A coordinate of a Hermite tangent.
    Tangent {
        /// The index of the tangent in its list, from 0 (messages count from 1).
        index: usize,
        /// The coordinate: 0 for x, 1 for y, 2 for z.
        axis: usize,
    },
    /// The tension, continuity or bias of a Kochanek–Bartels key.
    Shape {
        /// The index of the key, from 0 (messages count from 1: `point 1`).
        index: usize,
        /// Which value: 0 for the tension, 1 for the continuity, 2 for the bias.
        axis: usize,
    },
    /// The weight of a NURBS control point.
    Weight {
        /// The index of the point, from 0 (messages count from 1: `point 1`).
        index: usize,
    },
    /// A knot of a NURBS knot vector.
    Knot {
        /// The index of the knot, from 0 (messages count from 1: `knot 1`).
        index: usize,
    },
    /// The radius of a circle or helix.
    Radius,
    /// The pitch of a helix.
    Pitch,
    /// The number of turns of a helix.
    Turns,
    /// The size of a trefoil knot.
    Size,
    /// The alpha (parametrization) of a Catmull-Rom spline.
    Alpha,
    /// The angle tolerance ε of a `zrev` surface (or of an `xsweep`'s cross-section).
    Epsilon,
    /// The slice tolerance of a `zrev` surface.
    SliceTolerance,
    /// The swept-along curve's angle tolerance of an `xsweep` surface.
    PathEpsilon,
    /// The scale of a `zrev` or `xsweep` surface.
    Scale,
}

impl fmt::Display for SwpNumber {
    /// Formats in words, like `the x coordinate of point 3` or `the radius`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let coordinate = |f: &mut fmt::Formatter<'_>, role: &str, index: usize, axis: usize| {
            let axis = ["x", "y", "z"].get(axis).copied().unwrap_or("?");
            write!(f, "the {axis} coordinate of {role} {}", index.saturating_add(1))
        };
        match *self {
            Self::Point { index, axis } => coordinate(f, "point", index, axis),
            Self::Tangent { index, axis } => coordinate(f, "tangent", index, axis),
            Self::Shape { index, axis } => {
                let what = ["tension", "continuity", "bias"].get(axis).copied().unwrap_or("?");
                write!(f, "the {what} of point {}", index.saturating_add(1))
            }
            Self::Weight { index } => write!(f, "the weight of point {}", index.saturating_add(1)),
            Self::Knot { index } => write!(f, "knot {}", index.saturating_add(1)),
            Self::Radius => f.write_str("the radius"),
            Self::Pitch => f.write_str("the pitch"),
            Self::Turns => f.write_str("the number of turns"),
            Self::Size => f.write_str("the size"),
            Self::Alpha => f.write_str("the Catmull-Rom alpha"),
            Self::Epsilon => f.write_str("the angle tolerance epsilon"),
            Self::SliceTolerance => f.write_str("the slice tolerance"),
            Self::PathEpsilon => f.write_str("the path's angle tolerance path-epsilon"),
            Self::Scale => f.write_str("the scale"),
        }
    }
}

/// What is wrong with a curve or surface; see [`SwpInvalid`].
///
/// Each variant displays as a lowercase message without the object's name, such as
/// `a B-spline needs at least 4 points; this one has 2`. New variants may be added.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SwpInvalidKind {
    /// The name is empty.
    EmptyName,
    /// The name is `.`, which the file format uses for "no name".
    DotName,
    /// The name contains whitespace, `[`, `]` or `#`, which would split it or start a comment.
    NameCharacter {
        /// The first such character.
        found: char,
    },
    /// An earlier curve or surface already has this name.
    DuplicateName {
        /// The object that has the name first.
        first: SwpObject,
    },
    /// `dim` does not suit the kind: 2 or 3 for splines, 2 for circles, 3 for helices and
    /// trefoils.
    Dimension {
        /// The curve's kind.
        kind: SwpCurveKind,
        /// The curve's `dim`.
        dim: u8,
    },
    /// A circle or trefoil that is not closed, or a helix that is.
    Closed {
        /// The curve's kind.
        kind: SwpCurveKind,
        /// The curve's `closed` flag.
        closed: bool,
    },
    /// The geometry does not match the kind (such as a circle's radius for a B-spline).
    WrongGeometry {
        /// The curve's kind.
        kind: SwpCurveKind,
        /// What the geometry holds, in words, like `a circle's radius`.
        found: &'static str,
    },
    /// A Hermite curve with different numbers of points and tangents.
    TangentCount {
        /// The number of points.
        points: usize,
        /// The number of tangents.
        tangents: usize,
    },
    /// A Kochanek–Bartels curve with different numbers of keys and shapes.
    ShapeCount {
        /// The number of keys.
        points: usize,
        /// The number of tensions, continuities and biases.
        shapes: usize,
    },
    /// A NURBS curve with different numbers of points and weights.
    WeightCount {
        /// The number of points.
        points: usize,
        /// The number of weights.
        weights: usize,
    },
    /// A NURBS degree that is not from 1 to [`MAX_NURBS_DEGREE`].
    Degree {
        /// The degree.
        found: u32,
    },
    /// A NURBS knot vector whose length is not the number of points + degree + 1.
    KnotCount {
        /// The length needed.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// A NURBS knot smaller than the knot before it.
    KnotOrder {
        /// The index of the knot, from 0.
        index: usize,
        /// Its value.
        value: f64,
        /// The value of the knot before it.
        before: f64,
    },
    /// A NURBS knot vector that leaves the curve no domain: knot `degree + 1` equals knot
    /// `points + 1` (1-based), between which the curve runs.
    EmptyDomain {
        /// The common value of the two knots.
        value: f64,
    },
    /// A closed (periodic) NURBS curve with a knot vector of its own.
    PeriodicKnots,
    /// `steps` of a curve or surface of revolution is not in `1..=MAX_STEPS`.
    Steps {
        /// The steps.
        found: u32,
    },
    /// A surface setting that does not apply to its kind (such as `frames` on an `srev`).
    Setting {
        /// The setting's word, like `frames`.
        word: &'static str,
        /// The surface's keyword, like `srev`.
        keyword: &'static str,
    },
    /// A surface's `tolerance` is not a number > 0, or its `angle-tolerance` not in (0, 180].
    Tolerance {
        /// `tolerance` or `angle-tolerance`.
        word: &'static str,
        /// Its value.
        value: f64,
    },
    /// A surface's `mitre-limit` is not a number ≥ 1.
    MitreLimit {
        /// Its value.
        value: f64,
    },
    /// The slices of a lathe are not in `3..=MAX_STEPS`.
    Slices {
        /// The slices.
        found: u32,
    },
    /// The number of points breaks the kind's point-count rule
    /// ([`SwpCurveKind::accepts_point_count`]).
    PointCount {
        /// The curve's kind.
        kind: SwpCurveKind,
        /// Whether the curve is closed.
        closed: bool,
        /// The number of points (Hermite: of points, each with its tangent).
        found: usize,
    },
    /// A number is NaN or infinite.
    NonFinite {
        /// Which number.
        number: SwpNumber,
        /// Its value.
        value: f64,
    },
    /// A radius or size below 0, helix turns not in `(0, MAX_HELIX_TURNS]`, a Catmull-Rom
    /// alpha not in `[0, 1]`, or a tension, continuity or bias not in `[−1, 1]`.
    OutOfRange {
        /// Which number.
        number: SwpNumber,
        /// Its value.
        value: f64,
    },
    /// A point or tangent of a 2D curve has z ≠ 0 (the file stores only x and y).
    NonzeroZ {
        /// Which coordinate.
        number: SwpNumber,
        /// Its value.
        value: f64,
    },
    /// A surface refers to a curve index past the end of [`SwpDocument::curves`].
    MissingCurve {
        /// What the surface uses the curve for.
        role: SwpCurveRole,
        /// The curve index.
        curve: usize,
        /// How many curves the document has.
        curves: usize,
    },
    /// A surface's profile, scale or twist curve is a 3D curve.
    CurveNot2D {
        /// What the surface uses the curve for.
        role: SwpCurveRole,
        /// The curve index.
        curve: usize,
        /// The curve's name.
        curve_name: Option<String>,
    },
    /// A surface uses an anonymous curve, which a file cannot refer to.
    UnnamedCurve {
        /// What the surface uses the curve for.
        role: SwpCurveRole,
        /// The curve index.
        curve: usize,
    },
}

impl fmt::Display for SwpInvalidKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::EmptyName => f.write_str("a name cannot be empty"),
            Self::DotName => f.write_str(r#"a name cannot be "." (a dot means no name)"#),
            Self::NameCharacter { found } => match found {
                '[' | ']' => f.write_str("a name cannot contain [ or ]"),
                '#' => f.write_str("a name cannot contain # (it starts a comment)"),
                _ => f.write_str("a name cannot contain spaces, tabs or line breaks"),
            },
            Self::DuplicateName { first } => {
                let noun = match first {
                    SwpObject::Curve(_) => "curve",
                    SwpObject::Surface(_) => "surface",
                };
                write!(f, "another {noun} already has this name; every curve and surface needs its own name")
            }
            Self::Dimension { kind, dim } => {
                let need = match kind {
                    SwpCurveKind::Circle => "2D",
                    SwpCurveKind::Helix | SwpCurveKind::Trefoil => "3D",
                    _ => "2D or 3D",
                };
                write!(f, "{} must be {need}; this one has dimension {dim}", noun(*kind, false))
            }
            Self::Closed { kind, closed } => {
                let (always, marked) = if *closed { ("open", "closed") } else { ("closed", "open") };
                write!(f, "{} is always {always}; this one is marked {marked}", noun(*kind, false))
            }
            Self::WrongGeometry { kind, found } => {
                write!(f, "{} is described by {}, but this one holds {found}", noun(*kind, false), expected_data(*kind))
            }
            Self::TangentCount { points, tangents } => write!(
                f,
                "a Hermite spline needs one tangent for each point; this one has {} and {}",
                plural(*points, "point"),
                plural(*tangents, "tangent")
            ),
            Self::ShapeCount { points, shapes } => write!(
                f,
                "a Kochanek–Bartels spline needs one tension, continuity and bias for each point; this one has {} and {}",
                plural(*points, "point"),
                plural(*shapes, "shape")
            ),
            Self::WeightCount { points, weights } => write!(
                f,
                "a NURBS curve needs one weight for each point; this one has {} and {}",
                plural(*points, "point"),
                plural(*weights, "weight")
            ),
            Self::Degree { found } => {
                write!(f, "the degree of a NURBS curve must be from 1 to {MAX_NURBS_DEGREE}; this one has {found}")
            }
            Self::KnotCount { expected, found } => write!(
                f,
                "the knot vector must have {expected} knots (points + degree + 1); this one has {}",
                plural(*found, "knot")
            ),
            Self::KnotOrder { index, value, before } => write!(
                f,
                "knot {} is {value}, less than the knot before it ({before}); knots never decrease",
                index.saturating_add(1)
            ),
            Self::EmptyDomain { value } => write!(
                f,
                "the knot vector leaves the curve no domain: the knots it runs between (degree + 1 and points + 1) are both {value}"
            ),
            Self::PeriodicKnots => f.write_str(
                "a closed NURBS curve is periodic with uniform knots of its own, so it takes no knot vector",
            ),
            Self::Steps { found } => {
                write!(f, "the number of steps must be from 1 to {MAX_STEPS}; this one has {found}")
            }
            Self::Setting { word, keyword } => write!(f, "{word} does not apply to {keyword} surfaces"),
            Self::Tolerance { word: "angle-tolerance", value } => {
                write!(f, "its angle-tolerance must be more than 0 and at most 180 degrees; it is {value}")
            }
            Self::Tolerance { word, value } => write!(f, "its {word} must be a number more than 0; it is {value}"),
            Self::MitreLimit { value } => write!(f, "its mitre-limit must be a number of at least 1; it is {value}"),
            Self::Slices { found } => {
                write!(f, "the number of slices must be from 3 to {MAX_STEPS}; this one has {found}")
            }
            Self::PointCount { kind, closed, found } => {
                let need = match (kind, closed) {
                    (SwpCurveKind::Bezier, false) => "4, 7, 10, … points",
                    (SwpCurveKind::Bezier, true) => "3, 6, 9, … points",
                    (SwpCurveKind::Hermite, _) => "at least 2 points",
                    (SwpCurveKind::BezierN, _) => &format!("2 to {MAX_BEZIER_POINTS} points"),
                    (SwpCurveKind::Nurbs { degree }, closed) => &format!(
                        "at least {} points (degree + 1) and at most {MAX_NURBS_POINTS}",
                        (u64::from(*degree) + 1).max(if *closed { 3 } else { 2 })
                    ),
                    // the interpolating kinds shaped as Catmull-Rom's, and the B-spline
                    (
                        SwpCurveKind::BSpline
                        | SwpCurveKind::CatmullRom { .. }
                        | SwpCurveKind::KochanekBartels
                        | SwpCurveKind::BesselOverhauser,
                        false,
                    ) => "at least 4 points",
                    (
                        SwpCurveKind::BSpline
                        | SwpCurveKind::CatmullRom { .. }
                        | SwpCurveKind::KochanekBartels
                        | SwpCurveKind::BesselOverhauser,
                        true,
                    ) => "at least 3 points",
                    (SwpCurveKind::Circle | SwpCurveKind::Helix | SwpCurveKind::Trefoil, _) => "no control points",
                };
                write!(f, "{} needs {need}; this one has {found}", noun(*kind, *closed))
            }
            Self::NonFinite { number, value } => write!(f, "{number} must be a finite number; it is {value}"),
            Self::OutOfRange { number, value } => match number {
                SwpNumber::Shape { .. } => write!(f, "{number} must be from -1 to 1; it is {value}"),
                SwpNumber::Turns => {
                    write!(f, "{number} must be more than 0 and at most {MAX_HELIX_TURNS}; it is {value}")
                }
                SwpNumber::Alpha => write!(f, "{number} must be from 0 to 1; it is {value}"),
                SwpNumber::SliceTolerance => write!(
                    f,
                    "{number} must be at least 2π/{MAX_STEPS} radians (at most {MAX_STEPS} slices); it is {value}"
                ),
                SwpNumber::Epsilon | SwpNumber::PathEpsilon | SwpNumber::Scale => {
                    write!(f, "{number} must be more than 0; it is {value}")
                }
                _ => write!(f, "{number} must be 0 or more; it is {value}"),
            },
            Self::NonzeroZ { number, value } => write!(f, "{number} is {value}; in a 2D curve it must be 0"),
            Self::MissingCurve { role, curve, curves } => {
                let there = match curves {
                    0 => "there are no curves".to_owned(),
                    1 => "there is 1 curve".to_owned(),
                    n => format!("there are {n} curves"),
                };
                write!(f, "its {} is curve #{curve}, which does not exist ({there})", role.noun())
            }
            Self::CurveNot2D { role, curve, curve_name } => {
                let role = role.noun();
                match curve_name {
                    Some(name) => write!(f, "its {role} {} is a 3D curve", quote(name))?,
                    None => write!(f, "its {role} (curve #{curve}) is a 3D curve")?,
                }
                write!(f, "; a {role} must be a 2D curve")
            }
            Self::UnnamedCurve { role, curve } => write!(
                f,
                "its {} is curve #{curve}, which has no name; a curve that a surface uses needs a name",
                role.noun()
            ),
        }
    }
}

/// `a B-spline`, `a closed Bézier spline`, `a circle`, ….
fn noun(kind: SwpCurveKind, closed: bool) -> String {
    let noun = match kind {
        SwpCurveKind::Bezier => "Bézier spline",
        SwpCurveKind::BSpline => "B-spline",
        SwpCurveKind::CatmullRom { .. } => "Catmull-Rom spline",
        SwpCurveKind::Hermite => "Hermite spline",
        SwpCurveKind::KochanekBartels => "Kochanek–Bartels spline",
        SwpCurveKind::BesselOverhauser => "Bessel–Overhauser spline",
        SwpCurveKind::BezierN => "Bézier curve",
        SwpCurveKind::Nurbs { .. } => "NURBS curve",
        SwpCurveKind::Circle => "circle",
        SwpCurveKind::Helix => "helix",
        SwpCurveKind::Trefoil => "trefoil knot",
    };
    if closed { format!("a closed {noun}") } else { format!("a {noun}") }
}

/// The data a curve kind is described by, in words.
fn expected_data(kind: SwpCurveKind) -> &'static str {
    match kind {
        SwpCurveKind::Bezier | SwpCurveKind::BSpline | SwpCurveKind::CatmullRom { .. } => "control points",
        SwpCurveKind::BesselOverhauser => "points",
        SwpCurveKind::BezierN => "control points",
        SwpCurveKind::Nurbs { .. } => "control points with their weights",
        SwpCurveKind::Hermite => "points and tangents",
        SwpCurveKind::KochanekBartels => "points with their tension, continuity and bias",
        SwpCurveKind::Circle => "a radius",
        SwpCurveKind::Helix => "a radius, a pitch and a number of turns",
        SwpCurveKind::Trefoil => "a size",
    }
}

/// What a geometry holds, in words.
fn geometry_data(geometry: &SwpGeometry) -> &'static str {
    match geometry {
        SwpGeometry::Points(_) => "control points",
        SwpGeometry::Hermite { .. } => "points and tangents",
        SwpGeometry::Tcb { .. } => "points with their tension, continuity and bias",
        SwpGeometry::Nurbs { .. } => "control points with their weights",
        SwpGeometry::Circle { .. } => "a circle's radius",
        SwpGeometry::Helix { .. } => "a helix's radius, pitch and turns",
        SwpGeometry::Trefoil { .. } => "a trefoil knot's size",
    }
}

/// `1 point`, `3 points`.
fn plural(count: usize, unit: &str) -> String {
    if count == 1 { format!("1 {unit}") } else { format!("{count} {unit}s") }
}

/// Why `name` cannot be written as a NAME token that reads back as itself, if it cannot. The
/// writer renames exactly these names.
pub(crate) fn name_problem(name: &str) -> Option<SwpInvalidKind> {
    if name.is_empty() {
        Some(SwpInvalidKind::EmptyName)
    } else if name == "." {
        Some(SwpInvalidKind::DotName)
    } else {
        let found = name.chars().find(|&c| is_space(c) || matches!(c, '[' | ']' | '#'))?;
        Some(SwpInvalidKind::NameCharacter { found })
    }
}

/// Checks a name and records it in `names`.
fn check_name<'a>(
    name: Option<&'a str>,
    object: SwpObject,
    names: &mut HashMap<&'a str, SwpObject>,
) -> Result<(), SwpInvalidKind> {
    let Some(name) = name else { return Ok(()) };
    if let Some(problem) = name_problem(name) {
        return Err(problem);
    }
    match names.insert(name, object) {
        Some(first) => Err(SwpInvalidKind::DuplicateName { first }),
        None => Ok(()),
    }
}

/// Checks a number: finite, then `ok`.
fn check_number(number: SwpNumber, value: f64, ok: impl Fn(f64) -> bool) -> Result<(), SwpInvalidKind> {
    if !value.is_finite() {
        Err(SwpInvalidKind::NonFinite { number, value })
    } else if !ok(value) {
        Err(SwpInvalidKind::OutOfRange { number, value })
    } else {
        Ok(())
    }
}

/// Checks a point or tangent: finite coordinates, and z = 0 in 2D.
fn check_point(p: DVec3, dim: u8, number: impl Fn(usize) -> SwpNumber) -> Result<(), SwpInvalidKind> {
    for (axis, value) in p.to_array().into_iter().enumerate() {
        if axis == 2 && dim == 2 {
            if value != 0.0 {
                return Err(SwpInvalidKind::NonzeroZ { number: number(axis), value });
            }
        } else {
            check_number(number(axis), value, |_| true)?;
        }
    }
    Ok(())
}

/// Checks one curve (not its name).
fn check_curve(curve: &SwpCurve) -> Result<(), SwpInvalidKind> {
    let kind = curve.kind;
    let dim_ok = match kind {
        SwpCurveKind::Circle => curve.dim == 2,
        SwpCurveKind::Helix | SwpCurveKind::Trefoil => curve.dim == 3,
        _ => matches!(curve.dim, 2 | 3),
    };
    if !dim_ok {
        return Err(SwpInvalidKind::Dimension { kind, dim: curve.dim });
    }
    let closed_ok = match kind {
        SwpCurveKind::Circle | SwpCurveKind::Trefoil => curve.closed,
        SwpCurveKind::Helix | SwpCurveKind::BezierN => !curve.closed,
        _ => true,
    };
    if !closed_ok {
        return Err(SwpInvalidKind::Closed { kind, closed: curve.closed });
    }

    let empty: &[DVec3] = &[];
    let mut shape: &[Tcb] = &[];
    let mut weights: &[f64] = &[];
    let (points, tangents) = match (kind, &curve.geometry) {
        (
            SwpCurveKind::Bezier
            | SwpCurveKind::BSpline
            | SwpCurveKind::CatmullRom { .. }
            | SwpCurveKind::BesselOverhauser
            | SwpCurveKind::BezierN,
            SwpGeometry::Points(points),
        ) => (points.as_slice(), empty),
        (SwpCurveKind::Nurbs { degree }, SwpGeometry::Nurbs { points, weights: w, knots }) => {
            if w.len() != points.len() {
                return Err(SwpInvalidKind::WeightCount { points: points.len(), weights: w.len() });
            }
            check_nurbs_header(degree, curve.closed, points.len(), knots.as_deref())?;
            weights = w;
            (points.as_slice(), empty)
        }
        (SwpCurveKind::Hermite, SwpGeometry::Hermite { points, tangents }) => {
            if points.len() != tangents.len() {
                return Err(SwpInvalidKind::TangentCount { points: points.len(), tangents: tangents.len() });
            }
            (points.as_slice(), tangents.as_slice())
        }
        (SwpCurveKind::KochanekBartels, SwpGeometry::Tcb { points, shape: shapes }) => {
            if points.len() != shapes.len() {
                return Err(SwpInvalidKind::ShapeCount { points: points.len(), shapes: shapes.len() });
            }
            shape = shapes;
            (points.as_slice(), empty)
        }
        (SwpCurveKind::Circle, SwpGeometry::Circle { .. })
        | (SwpCurveKind::Helix, SwpGeometry::Helix { .. })
        | (SwpCurveKind::Trefoil, SwpGeometry::Trefoil { .. }) => (empty, empty),
        (_, geometry) => return Err(SwpInvalidKind::WrongGeometry { kind, found: geometry_data(geometry) }),
    };

    if !(1..=MAX_STEPS).contains(&curve.steps) {
        return Err(SwpInvalidKind::Steps { found: curve.steps });
    }
    let count = u64::try_from(points.len()).unwrap_or(u64::MAX);
    if !kind.accepts_point_count(curve.closed, count) {
        return Err(SwpInvalidKind::PointCount { kind, closed: curve.closed, found: points.len() });
    }

    if let SwpCurveKind::CatmullRom { alpha } = kind {
        check_number(SwpNumber::Alpha, alpha, |a| (0.0..=1.0).contains(&a))?;
    }
    match curve.geometry {
        SwpGeometry::Circle { radius } => check_number(SwpNumber::Radius, radius, |r| r >= 0.0)?,
        SwpGeometry::Helix { radius, pitch, turns } => {
            check_number(SwpNumber::Radius, radius, |r| r >= 0.0)?;
            check_number(SwpNumber::Pitch, pitch, |_| true)?;
            check_number(SwpNumber::Turns, turns, |t| t > 0.0 && t <= MAX_HELIX_TURNS)?;
        }
        SwpGeometry::Trefoil { size } => check_number(SwpNumber::Size, size, |s| s >= 0.0)?,
        SwpGeometry::Points(_) | SwpGeometry::Hermite { .. } | SwpGeometry::Tcb { .. } | SwpGeometry::Nurbs { .. } => {}
    }
    // In file order: each point, followed by its tangent for Hermite curves or its tension,
    // continuity and bias for Kochanek–Bartels curves.
    for (index, &p) in points.iter().enumerate() {
        check_point(p, curve.dim, |axis| SwpNumber::Point { index, axis })?;
        if let Some(&t) = tangents.get(index) {
            check_point(t, curve.dim, |axis| SwpNumber::Tangent { index, axis })?;
        }
        if let Some(&w) = weights.get(index) {
            check_number(SwpNumber::Weight { index }, w, |w| w > 0.0)?;
        }
        if let Some(s) = shape.get(index) {
            for (axis, value) in [s.tension, s.continuity, s.bias].into_iter().enumerate() {
                check_number(SwpNumber::Shape { index, axis }, value, |v| (-1.0..=1.0).contains(&v))?;
            }
        }
    }
    Ok(())
}

/// Checks what a NURBS curve's header says: its degree, and its knot vector (if any) against
/// the number of points `n`.
fn check_nurbs_header(degree: u32, closed: bool, n: usize, knots: Option<&[f64]>) -> Result<(), SwpInvalidKind> {
    if !(1..=MAX_NURBS_DEGREE as u32).contains(&degree) {
        return Err(SwpInvalidKind::Degree { found: degree });
    }
    let Some(knots) = knots else { return Ok(()) };
    if closed {
        return Err(SwpInvalidKind::PeriodicKnots);
    }
    let degree = degree as usize;
    let expected = n + degree + 1;
    if knots.len() != expected {
        return Err(SwpInvalidKind::KnotCount { expected, found: knots.len() });
    }
    for (index, &value) in knots.iter().enumerate() {
        check_number(SwpNumber::Knot { index }, value, |_| true)?;
        if let Some(&before) = index.checked_sub(1).and_then(|i| knots.get(i))
            && value < before
        {
            return Err(SwpInvalidKind::KnotOrder { index, value, before });
        }
    }
    // the curve runs from knot `degree` to knot `n` (0-based); too few points are the
    // point-count rule's to report
    match (knots.get(degree), knots.get(n)) {
        (Some(&a), Some(&b)) if a >= b && n > degree => Err(SwpInvalidKind::EmptyDomain { value: a }),
        _ => Ok(()),
    }
}

/// Checks one surface (not its name). The curves have been checked already.
fn check_surface(curves: &[SwpCurve], surface: &SwpSurface) -> Result<(), SwpInvalidKind> {
    match surface.kind {
        SwpSurfaceKind::Revolution { steps, .. } | SwpSurfaceKind::Lathe { stacks: steps, .. }
            if !(1..=MAX_STEPS).contains(&steps) =>
        {
            return Err(SwpInvalidKind::Steps { found: steps });
        }
        SwpSurfaceKind::Lathe { slices, .. } if !(3..=MAX_STEPS).contains(&slices) => {
            return Err(SwpInvalidKind::Slices { found: slices });
        }
        SwpSurfaceKind::ToolSweep { epsilon, path_epsilon, scale, .. } => {
            check_number(SwpNumber::Epsilon, epsilon, |v| v > 0.0)?;
            check_number(SwpNumber::PathEpsilon, path_epsilon, |v| v > 0.0)?;
            check_number(SwpNumber::Scale, scale, |v| v > 0.0)?;
        }
        SwpSurfaceKind::RevolutionZ { epsilon, slice_tolerance, scale, .. } => {
            check_number(SwpNumber::Epsilon, epsilon, |v| v > 0.0)?;
            check_number(SwpNumber::SliceTolerance, slice_tolerance, |v| {
                v > 0.0 && std::f64::consts::TAU / v <= f64::from(MAX_STEPS)
            })?;
            check_number(SwpNumber::Scale, scale, |v| v > 0.0)?;
        }
        _ => {}
    }
    let settings = &surface.settings;
    let keyword = surface.kind.keyword();
    let given = [
        ("tolerance", settings.tessellation.is_some()),
        ("layout", settings.layout.is_some()),
        ("frames", settings.frames.is_some()),
        ("caps", settings.caps.is_some()),
        ("align", settings.align.is_some()),
        ("join", settings.join.is_some()),
        ("mitre-limit", settings.mitre_limit.is_some()),
        ("scale-mode", settings.scale_mode.is_some()),
    ];
    for (word, is_given) in given {
        let applies = SETTING_WORDS.iter().any(|(w, kinds)| *w == word && kinds.contains(&keyword));
        if is_given && !applies {
            return Err(SwpInvalidKind::Setting { word, keyword });
        }
    }
    match settings.tessellation {
        Some(SwpTessellation::Distance(value)) if !(value > 0.0 && value.is_finite()) => {
            return Err(SwpInvalidKind::Tolerance { word: "tolerance", value });
        }
        Some(SwpTessellation::AngleDegrees(value)) if !(value > 0.0 && value <= 180.0) => {
            return Err(SwpInvalidKind::Tolerance { word: "angle-tolerance", value });
        }
        _ => {}
    }
    if let Some(value) = settings.mitre_limit.filter(|v| !(*v >= 1.0 && v.is_finite())) {
        return Err(SwpInvalidKind::MitreLimit { value });
    }
    let references = surface.kind.references().into_iter().map(|(role, curve)| (role, Some(curve)));
    for (role, index) in references {
        let Some(curve) = index else { continue };
        let Some(target) = curves.get(curve) else {
            return Err(SwpInvalidKind::MissingCurve { role, curve, curves: curves.len() });
        };
        if role != SwpCurveRole::Sweep && target.dim != 2 {
            return Err(SwpInvalidKind::CurveNot2D { role, curve, curve_name: target.name.clone() });
        }
        if target.name.is_none() {
            return Err(SwpInvalidKind::UnnamedCurve { role, curve });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::swp::SourcePos;

    /// A document with one curve or surface of every kind, all valid.
    const VALID: &str = "\
        bez2 bez 10 4 [0 0] [1 0] [1 1] [0 1]\n\
        bez3 loop 10 3 closed [0 0 0] [1 0 0] [1 1 1]\n\
        bsp2 profile 10 4 [0 0] [1 0] [1 1] [0 1]\n\
        cr3 path 10 3 closed alpha 0.25 [0 0 0] [1 0 1] [0 1 2]\n\
        her2 arc 10 2 [0 0] [1 0] [1 1] [0 1]\n\
        circ ring 24 0.5\n\
        helix coil 100 1 0.5 3\n\
        trefoil knot 100 2\n\
        bsp2 . 5 4 [0 0] [1 0] [1 1] [0 1]\n\
        tcb2 keys 10 4 [0 0 0 0 0] [1 0 1 -1 0.5] [1 1 -1 1 -0.5] [0 1 0 0 0]\n\
        bo3 ring3 10 3 closed [0 0 0] [1 0 1] [0 1 2]\n\
        srev glass 30 profile\n\
        gcyl tube ring coil scale profile twist arc\n\
        gcyl . ring path\n";

    fn valid() -> SwpDocument {
        SwpDocument::parse(VALID, "valid.swp").unwrap()
    }

    /// The message of the first problem of `doc`, which must have one.
    #[track_caller]
    fn message(doc: &SwpDocument) -> String {
        doc.validate().unwrap_err().to_string()
    }

    /// The kind of the first problem of `doc`, which must have one.
    #[track_caller]
    fn kind(doc: &SwpDocument) -> SwpInvalidKind {
        doc.validate().unwrap_err().kind().clone()
    }

    fn points(doc: &mut SwpDocument, index: usize) -> &mut Vec<DVec3> {
        match &mut doc.curves[index].geometry {
            SwpGeometry::Points(points) => points,
            SwpGeometry::Hermite { points, .. } | SwpGeometry::Tcb { points, .. } => points,
            other => panic!("curve {index} has no points: {other:?}"),
        }
    }

    fn tangents(doc: &mut SwpDocument, index: usize) -> &mut Vec<DVec3> {
        match &mut doc.curves[index].geometry {
            SwpGeometry::Hermite { tangents, .. } => tangents,
            other => panic!("curve {index} has no tangents: {other:?}"),
        }
    }

    /// A point-based curve with `n` points (z = 0).
    fn spline(name: &str, kind: SwpCurveKind, closed: bool, n: usize) -> SwpCurve {
        let points = (0..n).map(|i| DVec3::new(i as f64, (i % 2) as f64, 0.0)).collect();
        let geometry = if kind == SwpCurveKind::Hermite {
            SwpGeometry::Hermite { points, tangents: vec![DVec3::X; n] }
        } else if kind == SwpCurveKind::KochanekBartels {
            SwpGeometry::Tcb { points, shape: vec![Tcb::default(); n] }
        } else {
            SwpGeometry::Points(points)
        };
        SwpCurve { name: Some(name.into()), kind, dim: 2, steps: 10, closed, geometry, pos: SourcePos::default() }
    }

    fn single(curve: SwpCurve) -> SwpDocument {
        SwpDocument { curves: vec![curve], surfaces: vec![] }
    }

    #[test]
    fn valid_documents_pass() {
        assert_eq!(valid().validate(), Ok(()));
        assert_eq!(SwpDocument::default().validate(), Ok(()));
    }

    #[test]
    fn point_counts() {
        let cases: [(&str, SwpCurveKind, bool, usize, &str); 9] = [
            ("profile", SwpCurveKind::BSpline, false, 2, "a B-spline needs at least 4 points; this one has 2"),
            ("ring", SwpCurveKind::BSpline, true, 2, "a closed B-spline needs at least 3 points; this one has 2"),
            ("profile", SwpCurveKind::Bezier, false, 5, "a Bézier spline needs 4, 7, 10, … points; this one has 5"),
            ("profile", SwpCurveKind::Bezier, false, 1, "a Bézier spline needs 4, 7, 10, … points; this one has 1"),
            ("loop", SwpCurveKind::Bezier, true, 4, "a closed Bézier spline needs 3, 6, 9, … points; this one has 4"),
            (
                "p",
                SwpCurveKind::CatmullRom { alpha: 0.5 },
                false,
                3,
                "a Catmull-Rom spline needs at least 4 points; this one has 3",
            ),
            (
                "p",
                SwpCurveKind::CatmullRom { alpha: 0.0 },
                true,
                2,
                "a closed Catmull-Rom spline needs at least 3 points; this one has 2",
            ),
            ("h", SwpCurveKind::Hermite, false, 1, "a Hermite spline needs at least 2 points; this one has 1"),
            ("h", SwpCurveKind::Hermite, true, 0, "a closed Hermite spline needs at least 2 points; this one has 0"),
        ];
        for (name, kind, closed, n, expected) in cases {
            let doc = single(spline(name, kind, closed, n));
            assert_eq!(message(&doc), format!("curve {name:?}: {expected}"));
            assert_eq!(doc.validate().unwrap_err().kind(), &SwpInvalidKind::PointCount { kind, closed, found: n });
            // and a few points more or one fewer fix it
            let fixed = (n.saturating_sub(1)..=n + 3).any(|m| single(spline(name, kind, closed, m)).validate().is_ok());
            assert!(fixed, "{expected}");
        }
    }

    #[test]
    fn anonymous_objects_are_numbered() {
        let mut doc = valid();
        points(&mut doc, 8).pop();
        let err = doc.validate().unwrap_err();
        assert_eq!(err.to_string(), "curve #8: a B-spline needs at least 4 points; this one has 3");
        assert_eq!((err.object(), err.name(), err.display_name()), (SwpObject::Curve(8), None, "#8".to_owned()));

        let mut doc = valid();
        doc.surfaces[2].kind = SwpSurfaceKind::GeneralizedCylinder { profile: 3, sweep: 3, scale: None, twist: None };
        let err = doc.validate().unwrap_err();
        assert_eq!(err.to_string(), r#"surface #2: its profile "path" is a 3D curve; a profile must be a 2D curve"#);
        assert_eq!((err.object(), err.display_name()), (SwpObject::Surface(2), "#2".to_owned()));
    }

    #[test]
    fn dimensions() {
        let mut doc = valid();
        doc.curves[0].dim = 4;
        assert_eq!(message(&doc), r#"curve "bez": a Bézier spline must be 2D or 3D; this one has dimension 4"#);
        let mut doc = valid();
        doc.curves[5].dim = 3;
        assert_eq!(message(&doc), r#"curve "ring": a circle must be 2D; this one has dimension 3"#);
        let mut doc = valid();
        doc.curves[6].dim = 2;
        assert_eq!(message(&doc), r#"curve "coil": a helix must be 3D; this one has dimension 2"#);
        let mut doc = valid();
        doc.curves[7].dim = 0;
        assert_eq!(kind(&doc), SwpInvalidKind::Dimension { kind: SwpCurveKind::Trefoil, dim: 0 });
    }

    #[test]
    fn closed_flags() {
        let mut doc = valid();
        doc.curves[5].closed = false;
        assert_eq!(message(&doc), r#"curve "ring": a circle is always closed; this one is marked open"#);
        let mut doc = valid();
        doc.curves[6].closed = true;
        assert_eq!(message(&doc), r#"curve "coil": a helix is always open; this one is marked closed"#);
        let mut doc = valid();
        doc.curves[7].closed = false;
        assert_eq!(kind(&doc), SwpInvalidKind::Closed { kind: SwpCurveKind::Trefoil, closed: false });
    }

    #[test]
    fn geometry_must_match_the_kind() {
        let mut doc = valid();
        doc.curves[2].geometry = SwpGeometry::Circle { radius: 1.0 };
        assert_eq!(
            message(&doc),
            r#"curve "profile": a B-spline is described by control points, but this one holds a circle's radius"#
        );
        let mut doc = valid();
        doc.curves[5].geometry = SwpGeometry::Points(vec![]);
        assert_eq!(
            message(&doc),
            r#"curve "ring": a circle is described by a radius, but this one holds control points"#
        );
        for (index, geometry) in [
            (4, SwpGeometry::Points(vec![DVec3::ZERO; 4])),
            (0, SwpGeometry::Hermite { points: vec![DVec3::ZERO; 4], tangents: vec![DVec3::ZERO; 4] }),
            (6, SwpGeometry::Trefoil { size: 1.0 }),
            (7, SwpGeometry::Helix { radius: 1.0, pitch: 1.0, turns: 1.0 }),
        ] {
            let mut doc = valid();
            doc.curves[index].geometry = geometry;
            assert!(matches!(kind(&doc), SwpInvalidKind::WrongGeometry { .. }), "{}", message(&doc));
        }
        let mut doc = valid();
        tangents(&mut doc, 4).pop();
        assert_eq!(
            message(&doc),
            r#"curve "arc": a Hermite spline needs one tangent for each point; this one has 2 points and 1 tangent"#
        );
    }

    #[test]
    fn steps() {
        for steps in [0, MAX_STEPS + 1] {
            let mut doc = valid();
            doc.curves[1].steps = steps;
            assert_eq!(
                message(&doc),
                format!(r#"curve "loop": the number of steps must be from 1 to 1000000; this one has {steps}"#)
            );
        }
        let mut doc = valid();
        doc.curves[1].steps = MAX_STEPS;
        assert_eq!(doc.validate(), Ok(()));
        doc.surfaces[0].kind = SwpSurfaceKind::Revolution { steps: 0, profile: 2 };
        assert_eq!(message(&doc), r#"surface "glass": the number of steps must be from 1 to 1000000; this one has 0"#);
    }

    #[test]
    fn numbers_must_be_finite() {
        let mut doc = valid();
        points(&mut doc, 1)[2].x = f64::NAN;
        assert_eq!(message(&doc), r#"curve "loop": the x coordinate of point 3 must be a finite number; it is NaN"#);
        let mut doc = valid();
        tangents(&mut doc, 4)[1].y = f64::INFINITY;
        assert_eq!(message(&doc), r#"curve "arc": the y coordinate of tangent 2 must be a finite number; it is inf"#);
        for (index, geometry, number) in [
            (5, SwpGeometry::Circle { radius: f64::NAN }, SwpNumber::Radius),
            (6, SwpGeometry::Helix { radius: f64::INFINITY, pitch: 1.0, turns: 1.0 }, SwpNumber::Radius),
            (6, SwpGeometry::Helix { radius: 1.0, pitch: f64::NEG_INFINITY, turns: 1.0 }, SwpNumber::Pitch),
            (6, SwpGeometry::Helix { radius: 1.0, pitch: 1.0, turns: f64::NAN }, SwpNumber::Turns),
            (7, SwpGeometry::Trefoil { size: f64::INFINITY }, SwpNumber::Size),
        ] {
            let mut doc = valid();
            doc.curves[index].geometry = geometry;
            assert!(matches!(kind(&doc), SwpInvalidKind::NonFinite { number: n, .. } if n == number), "{number:?}");
        }
        let mut doc = valid();
        doc.curves[3].kind = SwpCurveKind::CatmullRom { alpha: f64::NAN };
        assert_eq!(message(&doc), r#"curve "path": the Catmull-Rom alpha must be a finite number; it is NaN"#);
    }

    #[test]
    fn numbers_in_range() {
        let mut doc = valid();
        doc.curves[5].geometry = SwpGeometry::Circle { radius: -1.0 };
        assert_eq!(message(&doc), r#"curve "ring": the radius must be 0 or more; it is -1"#);
        let mut doc = valid();
        doc.curves[7].geometry = SwpGeometry::Trefoil { size: -0.5 };
        assert_eq!(message(&doc), r#"curve "knot": the size must be 0 or more; it is -0.5"#);
        for turns in [0.0, -1.0, MAX_HELIX_TURNS * 1.5] {
            let mut doc = valid();
            doc.curves[6].geometry = SwpGeometry::Helix { radius: 1.0, pitch: 0.5, turns };
            assert_eq!(
                message(&doc),
                format!(r#"curve "coil": the number of turns must be more than 0 and at most 10000; it is {turns}"#)
            );
        }
        let mut doc = valid();
        doc.curves[6].geometry = SwpGeometry::Helix { radius: -2.0, pitch: 0.5, turns: 1.0 };
        assert_eq!(kind(&doc), SwpInvalidKind::OutOfRange { number: SwpNumber::Radius, value: -2.0 });
        let mut doc = valid();
        doc.curves[3].kind = SwpCurveKind::CatmullRom { alpha: 1.5 };
        assert_eq!(message(&doc), r#"curve "path": the Catmull-Rom alpha must be from 0 to 1; it is 1.5"#);
        // the ends of every range are allowed
        let mut doc = valid();
        doc.curves[3].kind = SwpCurveKind::CatmullRom { alpha: 1.0 };
        doc.curves[5].geometry = SwpGeometry::Circle { radius: 0.0 };
        doc.curves[6].geometry = SwpGeometry::Helix { radius: 0.0, pitch: -3.0, turns: MAX_HELIX_TURNS };
        doc.curves[7].geometry = SwpGeometry::Trefoil { size: 0.0 };
        assert_eq!(doc.validate(), Ok(()));
    }

    #[test]
    fn flat_curves_have_zero_z() {
        let mut doc = valid();
        points(&mut doc, 2)[1].z = 0.5;
        assert_eq!(message(&doc), r#"curve "profile": the z coordinate of point 2 is 0.5; in a 2D curve it must be 0"#);
        let mut doc = valid();
        tangents(&mut doc, 4)[0].z = f64::NAN;
        let SwpInvalidKind::NonzeroZ { number, value } = kind(&doc) else { panic!("{}", message(&doc)) };
        assert_eq!(number, SwpNumber::Tangent { index: 0, axis: 2 });
        assert!(value.is_nan());
        // -0 is 0, and 3D curves may leave the plane
        let mut doc = valid();
        points(&mut doc, 2)[1].z = -0.0;
        points(&mut doc, 1)[1].z = 7.0;
        assert_eq!(doc.validate(), Ok(()));
    }

    #[test]
    fn names() {
        let cases = [
            ("", "a name cannot be empty"),
            (".", r#"a name cannot be "." (a dot means no name)"#),
            ("my curve", "a name cannot contain spaces, tabs or line breaks"),
            ("a\tb", "a name cannot contain spaces, tabs or line breaks"),
            ("a\nb", "a name cannot contain spaces, tabs or line breaks"),
            ("x[1]", "a name cannot contain [ or ]"),
            ("x]", "a name cannot contain [ or ]"),
            ("#2", "a name cannot contain # (it starts a comment)"),
            ("no#2", "a name cannot contain # (it starts a comment)"),
        ];
        for (name, expected) in cases {
            let mut doc = valid();
            doc.curves[1].name = Some(name.into());
            assert_eq!(message(&doc), format!("curve {name:?}: {expected}"));
            let mut doc = valid();
            doc.surfaces[0].name = Some(name.into());
            assert_eq!(message(&doc), format!("surface {name:?}: {expected}"));
        }
        // names that look like keywords, numbers or clause words are fine
        let mut doc = valid();
        for (curve, name) in doc.curves.iter_mut().zip(["bez2", "scale", "twist", "-1", "closed", "é"]) {
            curve.name = Some(name.into());
        }
        assert_eq!(doc.validate(), Ok(()));
    }

    #[test]
    fn names_are_unique() {
        let mut doc = valid();
        doc.curves[3].name = Some("bez".into());
        let err = doc.validate().unwrap_err();
        assert_eq!(
            err.to_string(),
            r#"curve "bez": another curve already has this name; every curve and surface needs its own name"#
        );
        assert_eq!(err.object(), SwpObject::Curve(3));
        assert_eq!(err.kind(), &SwpInvalidKind::DuplicateName { first: SwpObject::Curve(0) });

        let mut doc = valid();
        doc.surfaces[1].name = Some("ring".into());
        assert_eq!(kind(&doc), SwpInvalidKind::DuplicateName { first: SwpObject::Curve(5) });
        let mut doc = valid();
        doc.surfaces[1].name = Some("glass".into());
        assert_eq!(
            message(&doc),
            r#"surface "glass": another surface already has this name; every curve and surface needs its own name"#
        );
        // anonymous objects may repeat
        let mut doc = valid();
        doc.curves[0].name = None;
        doc.surfaces[0].name = None;
        assert_eq!(doc.validate(), Ok(()));
    }

    #[test]
    fn references() {
        let gcyl = |profile, sweep, scale, twist| SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale, twist };
        let mut doc = valid();
        doc.surfaces[0].kind = SwpSurfaceKind::Revolution { steps: 4, profile: 3 };
        assert_eq!(message(&doc), r#"surface "glass": its profile "path" is a 3D curve; a profile must be a 2D curve"#);
        let mut doc = valid();
        doc.surfaces[1].kind = gcyl(5, 6, Some(7), None);
        assert_eq!(
            message(&doc),
            r#"surface "tube": its scale curve "knot" is a 3D curve; a scale curve must be a 2D curve"#
        );
        let mut doc = valid();
        doc.surfaces[1].kind = gcyl(5, 6, None, Some(1));
        assert_eq!(
            kind(&doc),
            SwpInvalidKind::CurveNot2D { role: SwpCurveRole::Twist, curve: 1, curve_name: Some("loop".into()) }
        );
        // a 3D sweep is fine
        let mut doc = valid();
        doc.surfaces[1].kind = gcyl(5, 7, None, None);
        assert_eq!(doc.validate(), Ok(()));

        let mut doc = valid();
        doc.surfaces[1].kind = gcyl(5, 11, None, None);
        assert_eq!(
            message(&doc),
            r#"surface "tube": its sweep is curve #11, which does not exist (there are 11 curves)"#
        );
        let mut doc = SwpDocument {
            curves: vec![],
            surfaces: vec![SwpSurface {
                name: None,
                kind: SwpSurfaceKind::Revolution { steps: 4, profile: 0 },
                settings: Default::default(),
                pos: SourcePos::default(),
            }],
        };
        assert_eq!(message(&doc), "surface #0: its profile is curve #0, which does not exist (there are no curves)");
        doc.curves.push(spline("p", SwpCurveKind::BSpline, false, 4));
        doc.surfaces[0].kind = SwpSurfaceKind::Revolution { steps: 4, profile: 1 };
        assert!(message(&doc).ends_with("(there is 1 curve)"));

        let mut doc = valid();
        doc.surfaces[1].kind = gcyl(5, 8, None, None);
        assert_eq!(
            message(&doc),
            r#"surface "tube": its sweep is curve #8, which has no name; a curve that a surface uses needs a name"#
        );
        let mut doc = valid();
        doc.curves[3].name = None;
        doc.surfaces[0].kind = SwpSurfaceKind::Revolution { steps: 4, profile: 3 };
        assert_eq!(
            message(&doc),
            "surface \"glass\": its profile (curve #3) is a 3D curve; a profile must be a 2D curve"
        );
    }

    /// Issue #41: Kochanek–Bartels keys need one shape each, each value in [−1, 1]; both
    /// interpolating kinds count their keys as Catmull-Rom does.
    #[test]
    fn kochanek_bartels_and_bessel_overhauser() {
        fn shape(doc: &mut SwpDocument) -> &mut Vec<Tcb> {
            match &mut doc.curves[9].geometry {
                SwpGeometry::Tcb { shape, .. } => shape,
                other => panic!("curve 9 has no shape: {other:?}"),
            }
        }
        let mut doc = valid();
        shape(&mut doc)[1].continuity = -1.5;
        assert_eq!(message(&doc), r#"curve "keys": the continuity of point 2 must be from -1 to 1; it is -1.5"#);
        shape(&mut doc)[1].continuity = f64::NAN;
        assert_eq!(message(&doc), r#"curve "keys": the continuity of point 2 must be a finite number; it is NaN"#);
        shape(&mut doc).pop();
        assert_eq!(
            message(&doc),
            "curve \"keys\": a Kochanek–Bartels spline needs one tension, continuity and bias for each point; \
             this one has 4 points and 3 shapes"
        );
        let mut doc = valid();
        doc.curves[9].geometry = SwpGeometry::Points(vec![DVec3::ZERO; 4]);
        assert_eq!(
            message(&doc),
            "curve \"keys\": a Kochanek–Bartels spline is described by points with their tension, continuity and \
             bias, but this one holds control points"
        );
        for (kind, closed, n, expected) in [
            (SwpCurveKind::KochanekBartels, false, 3, "a Kochanek–Bartels spline needs at least 4 points"),
            (SwpCurveKind::KochanekBartels, true, 2, "a closed Kochanek–Bartels spline needs at least 3 points"),
            (SwpCurveKind::BesselOverhauser, false, 3, "a Bessel–Overhauser spline needs at least 4 points"),
            (SwpCurveKind::BesselOverhauser, true, 2, "a closed Bessel–Overhauser spline needs at least 3 points"),
        ] {
            let doc = single(spline("k", kind, closed, n));
            assert_eq!(message(&doc), format!("curve \"k\": {expected}; this one has {n}"));
            assert_eq!(single(spline("k", kind, closed, n + 1)).validate(), Ok(()));
        }
    }

    #[test]
    fn the_first_problem_is_reported() {
        // curves before surfaces, and earlier curves first
        let mut doc = valid();
        doc.surfaces[0].kind = SwpSurfaceKind::Revolution { steps: 0, profile: 2 };
        doc.curves[7].steps = 0;
        doc.curves[6].dim = 2;
        assert_eq!(doc.validate().unwrap_err().object(), SwpObject::Curve(6));
    }

    #[test]
    fn messages_read_as_sentences() {
        // every message starts in lowercase, ends without a period and uses no formulas
        let mut doc = valid();
        doc.curves[0].steps = 0;
        for message in [message(&doc), message(&single(spline("b", SwpCurveKind::Bezier, false, 2)))] {
            assert!(message.starts_with(|c: char| c.is_lowercase()), "{message}");
            assert!(!message.ends_with('.') && !message.contains("3m") && !message.contains('§'), "{message}");
        }
    }
}
