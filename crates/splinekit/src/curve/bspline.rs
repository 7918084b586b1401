//! Uniform cubic B-splines.

use crate::curve::piecewise::{chain, check_finite};
use crate::curve::{CubicBezier, PiecewiseCubic, SplineError};
use crate::vector::Vector;

/// Uniform cubic B-spline basis matrix (rows per control point, columns per
/// power of t): `P(t) = [P0 P1 P2 P3] · BSPLINE_BASIS · [1, t, t², t³]ᵀ`.
pub const BSPLINE_BASIS: [[f64; 4]; 4] = [
    [1.0 / 6.0, -3.0 / 6.0, 3.0 / 6.0, -1.0 / 6.0],
    [4.0 / 6.0, 0.0, -6.0 / 6.0, 3.0 / 6.0],
    [1.0 / 6.0, 3.0 / 6.0, 3.0 / 6.0, -3.0 / 6.0],
    [0.0, 0.0, 0.0, 1.0 / 6.0],
];

/// Uniform cubic B-spline with a sliding window of four control points.
///
/// # Interpolation
/// Approximating: the curve passes near, not through, the control points. Three equal
/// consecutive points force the curve through that point (the wineglass trick).
///
/// # Tangency
/// At the start of window `k` the tangent is `(P(k+2) − P(k)) / 2`.
///
/// # Continuity
/// C2 everywhere.
///
/// # Parametrization
/// Open: `n ≥ 4` points give `n − 3` segments, segment `k` from `P(k) … P(k+3)`.
/// Closed: `n ≥ 3` points give `n` segments with indices taken mod n.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{BSpline, ParamCurve};
/// let pts = [DVec2::new(-1.0, 0.0), DVec2::new(-1.0, 1.0), DVec2::new(-3.0, 1.0), DVec2::new(-3.0, 0.0)];
/// let curve = BSpline::new(&pts, false).unwrap().to_piecewise();
/// let start = (pts[0] + pts[1] * 4.0 + pts[2]) / 6.0;
/// assert!((curve.eval(0.0) - start).length() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BSpline<P> {
    points: Vec<P>,
    closed: bool,
}

impl<P: Vector> BSpline<P> {
    /// Validates the point count (open ≥ 4, closed ≥ 3) and finiteness.
    pub fn new(points: &[P], closed: bool) -> Result<Self, SplineError> {
        let needed = if closed { 3 } else { 4 };
        if points.len() < needed {
            return Err(SplineError::InsufficientPoints { kind: "b-spline", needed, given: points.len() });
        }
        check_finite(points)?;
        Ok(Self { points: points.to_vec(), closed })
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The four basis weights at local `t` (they sum to 1 and are ≥ 0 on `[0, 1]`).
    #[must_use]
    pub fn basis(t: f64) -> [f64; 4] {
        let mt = 1.0 - t;
        let t2 = t * t;
        [
            mt * mt * mt / 6.0,
            (3.0 * t2 * t - 6.0 * t2 + 4.0) / 6.0,
            (-3.0 * t2 * t + 3.0 * t2 + 3.0 * t + 1.0) / 6.0,
            t2 * t / 6.0,
        ]
    }

    /// Compiles to Bézier segments with the exact window conversion:
    /// `((P0+4P1+P2)/6, (4P1+2P2)/6, (2P1+4P2)/6, (P1+4P2+P3)/6)`.
    #[must_use]
    pub fn to_piecewise(&self) -> PiecewiseCubic<P> {
        let n = self.points.len();
        let m = if self.closed { n } else { n - 3 };
        let p = |i: usize| self.points[i % n];
        let segments = (0..m).map(|k| window_to_bezier([p(k), p(k + 1), p(k + 2), p(k + 3)])).collect();
        chain(segments, self.closed)
    }
}

/// One B-spline window as a Bézier segment.
#[must_use]
pub fn window_to_bezier<P: Vector>([p0, p1, p2, p3]: [P; 4]) -> CubicBezier<P> {
    const S: f64 = 1.0 / 6.0;
    CubicBezier::new(
        (p0 + p1 * 4.0 + p2) * S,
        (p1 * 4.0 + p2 * 2.0) * S,
        (p1 * 2.0 + p2 * 4.0) * S,
        (p1 + p2 * 4.0 + p3) * S,
    )
}
