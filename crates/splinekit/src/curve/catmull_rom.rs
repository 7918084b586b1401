//! Catmull-Rom splines: uniform, centripetal, chordal (exponent α).

use crate::curve::piecewise::{chain, check_finite};
use crate::curve::{CubicBezier, PiecewiseCubic, SplineError};
use crate::vector::Vector;

/// Uniform Catmull-Rom basis matrix (rows per control point, columns per
/// power of t).
pub const CATMULL_ROM_BASIS: [[f64; 4]; 4] =
    [[0.0, -0.5, 1.0, -0.5], [1.0, 0.0, -2.5, 1.5], [0.0, 0.5, 2.0, -1.5], [0.0, 0.0, -0.5, 0.5]];

/// Catmull-Rom spline with parameterization exponent α.
///
/// # Interpolation
/// Interpolating: window `k` runs from `P(k+1)` to `P(k+2)`.
///
/// # Tangency
/// Uniform (α = 0): the tangent at `P(i)` is `(P(i+1) − P(i−1)) / 2`. For α > 0 the
/// tangents follow the Barry–Goldman pyramid with knot intervals `dᵢ = |P(i+1) − P(i)|^α`
/// (Yuksel, Schaefer, Keyser: "Parameterization and applications of Catmull-Rom curves",
/// 2011): `m1 = (P1−P0)/d0 − (P2−P0)/(d0+d1) + (P2−P1)/d1`, scaled by `d1` per segment.
///
/// # Continuity
/// C1 everywhere.
///
/// # Parametrization
/// Open: `n ≥ 4` points, `n − 3` segments. Closed: `n ≥ 3` points, `n` segments, indices
/// mod n. Every segment takes one unit of `u`, whatever α (α only shapes the curve).
/// α = 0.5 (centripetal) has no cusps or self-intersections within a segment.
/// Coincident neighbours never give NaN: a zero interval `d0` or `d2` is replaced by `d1`,
/// and a segment between two equal points is that point.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{CatmullRom, ParamCurve};
/// let pts = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
/// let curve = CatmullRom::new(&pts, false, 0.5).unwrap().to_piecewise();
/// assert_eq!(curve.eval(0.0), pts[1]);
/// assert_eq!(curve.eval(1.0), pts[2]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CatmullRom<P> {
    points: Vec<P>,
    closed: bool,
    alpha: f64,
}

impl<P: Vector> CatmullRom<P> {
    /// Uniform α = 0.
    pub const UNIFORM: f64 = 0.0;
    /// Centripetal α = 0.5.
    pub const CENTRIPETAL: f64 = 0.5;
    /// Chordal α = 1.
    pub const CHORDAL: f64 = 1.0;

    /// Validates the point count (open ≥ 4, closed ≥ 3), finiteness and `0 ≤ α ≤ 1`.
    pub fn new(points: &[P], closed: bool, alpha: f64) -> Result<Self, SplineError> {
        let needed = if closed { 3 } else { 4 };
        if points.len() < needed {
            return Err(SplineError::InsufficientPoints { kind: "catmull-rom", needed, given: points.len() });
        }
        if !(0.0..=1.0).contains(&alpha) {
            return Err(SplineError::BadAlpha { alpha });
        }
        check_finite(points)?;
        Ok(Self { points: points.to_vec(), closed, alpha })
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The parameterization exponent.
    #[must_use]
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// Compiles to Bézier segments; for α = 0 this is exactly the uniform window conversion
    /// `(P1, P1 + (P2−P0)/6, P2 − (P3−P1)/6, P2)`.
    #[must_use]
    pub fn to_piecewise(&self) -> PiecewiseCubic<P> {
        let n = self.points.len();
        let m = if self.closed { n } else { n - 3 };
        let p = |i: usize| self.points[i % n];
        let segments = (0..m).map(|k| window_to_bezier([p(k), p(k + 1), p(k + 2), p(k + 3)], self.alpha)).collect();
        chain(segments, self.closed)
    }
}

/// One Catmull-Rom window `P0..P3` (interpolating `P1 → P2`) as a Bézier segment.
#[must_use]
pub fn window_to_bezier<P: Vector>([p0, p1, p2, p3]: [P; 4], alpha: f64) -> CubicBezier<P> {
    if alpha == 0.0 {
        const S: f64 = 1.0 / 6.0;
        return CubicBezier::new(p1, p1 + (p2 - p0) * S, p2 - (p3 - p1) * S, p2);
    }
    let d1 = (p2 - p1).length().powf(alpha);
    if !(d1 > 0.0) {
        return CubicBezier::new(p1, p1, p2, p2);
    }
    let d0 = match (p1 - p0).length().powf(alpha) {
        d if d > 0.0 => d,
        _ => d1,
    };
    let d2 = match (p3 - p2).length().powf(alpha) {
        d if d > 0.0 => d,
        _ => d1,
    };
    // tangents at P1 and P2 with respect to the knot parameter, times d1 (segment width)
    let m1 = ((p1 - p0) * (1.0 / d0) - (p2 - p0) * (1.0 / (d0 + d1)) + (p2 - p1) * (1.0 / d1)) * d1;
    let m2 = ((p2 - p1) * (1.0 / d1) - (p3 - p1) * (1.0 / (d1 + d2)) + (p3 - p2) * (1.0 / d2)) * d1;
    CubicBezier::new(p1, p1 + m1 * (1.0 / 3.0), p2 - m2 * (1.0 / 3.0), p2)
}
