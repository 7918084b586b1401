//! Curves: the [`ParamCurve`] trait, cubic segments, and the spline kinds that compile
//! into chains of them.
//!
//! Every kind (Bézier, uniform B-spline, Catmull-Rom, Hermite, Kochanek–Bartels,
//! Bessel–Overhauser) validates its input once
//! and compiles into a [`PiecewiseCubic`]: a chain of [`CubicBezier`] segments with the
//! *concatenated parameter* `u ∈ [0, segments]`, segment `k` covering `[k, k+1]`
//! with local `t = u − k`. Circles ([`Circle`]), helices ([`Helix`]) and the
//! trefoil knot ([`Trefoil`]) are exact parametric curves of one segment, not cubics.

/// The single-segment `ParamCurve` methods of an exact curve (circle, helix, trefoil) whose
/// inherent `at(u, order)` gives the position (order 0) or a derivative (1–3) in 3D.
macro_rules! one_segment_from_at {
    () => {
        fn num_segments(&self) -> usize {
            1
        }
        fn eval(&self, u: f64) -> P {
            P::from_dvec3(self.at(u, 0))
        }
        fn deriv(&self, u: f64) -> P {
            P::from_dvec3(self.at(u, 1))
        }
        fn deriv2(&self, u: f64) -> P {
            P::from_dvec3(self.at(u, 2))
        }
        fn deriv3(&self, u: f64) -> P {
            P::from_dvec3(self.at(u, 3))
        }
    };
}

mod any;
mod bezier;
mod bezier_n;
mod bspline;
mod by_segment;
mod casteljau;
mod catmull_rom;
mod circle;
mod helix;
mod hermite;
mod nearest;
mod nurbs;
mod piecewise;
mod tcb;
mod trefoil;

pub use any::AnyCurve;
pub use bezier::{BEZIER_BASIS, CubicBezier};
pub use bezier_n::{BezierCurve, MAX_BEZIER_POINTS};
pub use bspline::{BSPLINE_BASIS, BSpline};
pub use catmull_rom::{CATMULL_ROM_BASIS, CatmullRom};
pub use circle::Circle;
pub use helix::Helix;
pub use hermite::Hermite;
pub use nearest::{MAX_NEAREST_INTERVALS, Nearest, accuracy_floor};
pub use nurbs::{MAX_NURBS_DEGREE, MAX_NURBS_POINTS, Nurbs};
pub use piecewise::{BezierSpline, PiecewiseCubic};
pub use tcb::{BesselOverhauser, KochanekBartels, Tcb};
pub use trefoil::Trefoil;

use crate::arclen::ArclenEstimate;
use crate::vector::Vector;

/// Why a spline definition was rejected.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SplineError {
    /// Too few control points for the kind.
    #[error("{kind} needs at least {needed} control points, got {given}")]
    InsufficientPoints {
        /// The spline kind.
        kind: &'static str,
        /// The minimum count.
        needed: usize,
        /// The count given.
        given: usize,
    },
    /// The point count does not fit the kind (e.g. Bézier needs 3m+1 points).
    #[error("{kind} needs {rule} control points, got {given}")]
    BadPointCount {
        /// The spline kind.
        kind: &'static str,
        /// The rule, e.g. "3m+1".
        rule: &'static str,
        /// The count given.
        given: usize,
    },
    /// Hermite points and tangents differ in number.
    #[error("hermite needs one tangent per point, got {points} points and {tangents} tangents")]
    TangentCount {
        /// Number of points.
        points: usize,
        /// Number of tangents.
        tangents: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("control point {index} is not finite")]
    NonFinite {
        /// Index of the offending point.
        index: usize,
    },
    /// A Catmull-Rom exponent outside [0, 1].
    #[error("catmull-rom alpha must be in [0, 1], got {alpha}")]
    BadAlpha {
        /// The value given.
        alpha: f64,
    },
    /// A NURBS knot vector of the wrong length.
    #[error("a knot vector of {expected} knots (control points + degree + 1), got {given}")]
    KnotCount {
        /// The length needed.
        expected: usize,
        /// The length given.
        given: usize,
    },
    /// A knot that is not finite, is smaller than the one before it, or leaves no domain.
    #[error("knot {index} {why}")]
    BadKnot {
        /// Its index, from 0.
        index: usize,
        /// What is wrong.
        why: &'static str,
    },
    /// A piece of a chain of Bézier curves that does not start where the piece before it
    /// ends.
    #[error("Bézier piece {index} does not start where piece {} ends", .index - 1)]
    NotJoined {
        /// The piece's index, from 1.
        index: usize,
    },
    /// An elliptic arc that cannot be made: a non-finite value, or a sweep of 0 or past a full
    /// turn.
    #[error("an elliptic arc: {why}")]
    BadArc {
        /// What is wrong.
        why: &'static str,
    },
    /// A closed curve asked of a kind that is always open (a single Bézier curve), or a closed
    /// (periodic) NURBS given a knot vector of its own.
    #[error("{what}")]
    NotClosable {
        /// What cannot be, in words.
        what: &'static str,
    },
    /// A degree of 0 or above the largest supported.
    #[error("degree must be from 1 to {max}, got {degree}")]
    BadDegree {
        /// The degree given.
        degree: usize,
        /// The largest supported.
        max: usize,
    },
    /// Not one weight per control point.
    #[error("one weight per control point is needed, got {points} points and {weights} weights")]
    WeightCount {
        /// Control points.
        points: usize,
        /// Weights.
        weights: usize,
    },
    /// A weight that is not a positive finite number.
    #[error("weight {index} must be a positive finite number, got {weight}")]
    BadWeight {
        /// The control point, from 0.
        index: usize,
        /// The weight given.
        weight: f64,
    },
    /// A chain with no segments.
    #[error("a curve needs at least one segment")]
    Empty,
    /// Kochanek–Bartels keys and their shapes differ in number.
    #[error("kochanek-bartels needs one tension, continuity and bias per key, got {points} keys and {shapes}")]
    ShapeCount {
        /// Number of keys.
        points: usize,
        /// Number of shapes.
        shapes: usize,
    },
    /// A Kochanek–Bartels tension, continuity or bias outside [−1, 1].
    #[error("{name} of key {index} must be in [-1, 1], got {value}")]
    BadShape {
        /// The key.
        index: usize,
        /// `tension`, `continuity` or `bias`.
        name: &'static str,
        /// The value given.
        value: f64,
    },
}

/// Axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<P> {
    /// Lower corner.
    pub min: P,
    /// Upper corner.
    pub max: P,
}

impl<P: Vector> Aabb<P> {
    /// The box holding one point.
    #[must_use]
    pub fn from_point(p: P) -> Self {
        Self { min: p, max: p }
    }
    /// The smallest box holding `self` and `p`.
    #[must_use]
    pub fn union_point(self, p: P) -> Self {
        Self { min: self.min.min_components(p), max: self.max.max_components(p) }
    }
    /// The smallest box holding both boxes.
    #[must_use]
    pub fn union(self, o: Self) -> Self {
        Self { min: self.min.min_components(o.min), max: self.max.max_components(o.max) }
    }
    /// True when `p` lies inside the box grown by `slack` on every side.
    #[must_use]
    pub fn contains(&self, p: P, slack: f64) -> bool {
        (0..P::DIM)
            .all(|i| p.component(i) >= self.min.component(i) - slack && p.component(i) <= self.max.component(i) + slack)
    }
}

/// A parametric curve over the concatenated parameter `u ∈ [0, num_segments()]`.
///
/// Evaluation is total: it never panics and never returns NaN for finite input curves.
/// Outside the domain, positions and derivatives extrapolate the first or last segment.
pub trait ParamCurve<P: Vector> {
    /// Number of unit parameter intervals (`u` runs over `[0, num_segments]`).
    fn num_segments(&self) -> usize;
    /// Position at `u`.
    fn eval(&self, u: f64) -> P;
    /// First derivative `dP/du`.
    fn deriv(&self, u: f64) -> P;
    /// Second derivative.
    fn deriv2(&self, u: f64) -> P;
    /// Third derivative.
    fn deriv3(&self, u: f64) -> P;
    /// Arc length of `u ∈ [u0, u1]` to within `accuracy` (absolute, length units),
    /// with an error estimate. `u1 < u0` gives a negative length.
    fn arclen_range(&self, u0: f64, u1: f64, accuracy: f64) -> ArclenEstimate;
    /// Tight bounding box of the curve over its domain.
    fn bounding_box(&self) -> Aabb<P>;
    /// The end of segment `k` (`k < num_segments`) as the segment itself reaches it: the limit
    /// of `eval(u)` as `u` rises to `k + 1`, which differs from `eval(k + 1)` where a chain
    /// jumps. By default `eval(k + 1)` (curves without jumps).
    fn segment_end(&self, k: usize) -> P {
        self.eval((k + 1) as f64)
    }
    /// An upper bound of `|P″(u)|` over `u ∈ [u0, u1]` (`u0 ≤ u1`, within the domain): the
    /// chord bound of [`nearest`](Self::nearest) rests on it.
    fn deriv2_bound(&self, u0: f64, u1: f64) -> f64;

    /// The point of the curve nearest to `q`, over the whole curve: its distance is within
    /// `accuracy` (absolute, length units) of the smallest distance from `q` to any point of
    /// the curve, proved by branch and bound on chord bounds, not found by a local search
    /// from a guess (see [`Nearest`] for what is returned, and the `nearest` module docs in
    /// the source for the bound).
    ///
    /// ```
    /// use glam::DVec2;
    /// use splinekit::{BezierSpline, ParamCurve};
    /// let points = [DVec2::ZERO, DVec2::new(0.0, 1.0), DVec2::new(1.0, 1.0), DVec2::X];
    /// let arch = BezierSpline::new(&points, false)?
    ///     .to_piecewise();
    /// let n = arch.nearest(DVec2::new(0.5, 2.0), 1e-12);
    /// assert!((n.u - 0.5).abs() < 1e-9 && (n.distance - 1.25).abs() < 1e-12);
    /// # Ok::<(), splinekit::SplineError>(())
    /// ```
    fn nearest(&self, q: P, accuracy: f64) -> Nearest<P> {
        nearest::nearest(self, q, accuracy)
    }

    /// The parameter domain `(0, num_segments)`.
    fn domain(&self) -> (f64, f64) {
        (0.0, self.num_segments() as f64)
    }

    /// Total arc length to within `accuracy` (absolute, length units).
    fn arclen(&self, accuracy: f64) -> f64 {
        let (a, b) = self.domain();
        self.arclen_range(a, b, accuracy).length
    }

    /// Unit tangent at `u`. Where `P′(u)` vanishes (a cusp or a degenerate segment;
    /// "vanishes" means `|P′| ≤ 1e-12·(|P′| + |P″| + |P‴|)`), the limit direction is
    /// used: `P″` (pointing along travel, so `−P″` at the end of the domain), then
    /// `P‴`, then the chord from start to end, then `+x`.
    fn unit_tangent(&self, u: f64) -> P {
        let (d1, d2, d3) = (self.deriv(u), self.deriv2(u), self.deriv3(u));
        let scale = d1.length() + d2.length() + d3.length();
        if let Some(t) = normalized(d1, scale) {
            return t;
        }
        let at_end = u >= self.domain().1;
        if let Some(t) = normalized(if at_end { -d2 } else { d2 }, scale) {
            return t;
        }
        if let Some(t) = normalized(d3, scale) {
            return t;
        }
        let (a, b) = self.domain();
        let chord = self.eval(b) - self.eval(a);
        if let Some(t) = normalized(chord, chord.length()) {
            return t;
        }
        P::from_dvec3(glam::DVec3::X)
    }

    /// Curvature `κ = |P′ × P″| / |P′|³` at `u` (always ≥ 0). Where `P′` vanishes
    /// (as in [`unit_tangent`](Self::unit_tangent)): `+∞` if `P″ ≠ 0` (a true cusp),
    /// else 0 (a degenerate, point-like or straight piece).
    fn curvature(&self, u: f64) -> f64 {
        let (d1, d2, d3) = (self.deriv(u), self.deriv2(u), self.deriv3(u));
        let scale = d1.length() + d2.length() + d3.length();
        let speed = d1.length();
        if speed <= 1e-12 * scale || scale == 0.0 {
            return if d2.length() <= 1e-12 * scale || scale == 0.0 { 0.0 } else { f64::INFINITY };
        }
        d1.cross3(d2).length() / (speed * speed * speed)
    }

    /// Torsion `τ = (P′ × P″)·P‴ / |P′ × P″|²` at `u`; 0 where the curve is locally
    /// straight (`|P′ × P″| ≤ 1e-12·|P′|·|P″|`), and always 0 for 2D curves.
    fn torsion(&self, u: f64) -> f64 {
        let (d1, d2) = (self.deriv(u), self.deriv2(u));
        let c = d1.cross3(d2);
        let cl = c.length();
        if cl <= 1e-12 * d1.length() * d2.length() || cl == 0.0 {
            return 0.0;
        }
        c.dot(self.deriv3(u).to_dvec3()) / (cl * cl)
    }
}

fn normalized<P: Vector>(v: P, scale: f64) -> Option<P> {
    let l = v.length();
    (l > 1e-12 * scale && l > 0.0 && l.is_finite()).then(|| v * (1.0 / l))
}
