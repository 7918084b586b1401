//! [`PiecewiseCubic`], the compiled form of every spline kind, and [`BezierSpline`].

use crate::arclen::ArclenEstimate;
use crate::curve::by_segment::arclen_by_segment;
use crate::curve::{Aabb, CubicBezier, ParamCurve, SplineError};
use crate::vector::Vector;

/// A chain of cubic Bézier segments over the concatenated parameter `u ∈ [0, m]`;
/// segment `k` covers `[k, k+1]` with local `t = u − k` (at an integer `u = k` the
/// segment starting there is used, and `u = m` is the end of the last one).
///
/// Built by [`BezierSpline`], [`BSpline`](crate::BSpline),
/// [`CatmullRom`](crate::CatmullRom) and [`Hermite`](crate::Hermite), or directly from
/// segments with [`PiecewiseCubic::new`]. The chain need not be continuous.
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseCubic<P> {
    segments: Vec<CubicBezier<P>>,
    closed: bool,
}

impl<P: Vector> PiecewiseCubic<P> {
    /// A chain from its segments (at least one, all finite). `closed` records whether the
    /// definition was a closed loop (it does not change evaluation).
    pub fn new(segments: Vec<CubicBezier<P>>, closed: bool) -> Result<Self, SplineError> {
        if segments.is_empty() {
            return Err(SplineError::Empty);
        }
        if let Some(k) = segments.iter().position(|s| !s.is_finite()) {
            return Err(SplineError::NonFinite { index: 3 * k });
        }
        Ok(Self { segments, closed })
    }

    /// The segments in order.
    #[must_use]
    pub fn segments(&self) -> &[CubicBezier<P>] {
        &self.segments
    }

    /// Whether the definition was closed (the last segment ends where the first begins).
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Segment index and local parameter for the concatenated parameter `u`
    /// (values outside `[0, m]` extrapolate the first or last segment).
    #[inline]
    #[must_use]
    pub fn locate(&self, u: f64) -> (usize, f64) {
        let m = self.segments.len();
        // `as usize` saturates (NaN → 0), so this never panics.
        let k = if u > 0.0 { (u.floor() as usize).min(m - 1) } else { 0 };
        (k, u - k as f64)
    }

    #[inline]
    fn seg(&self, u: f64) -> (&CubicBezier<P>, f64) {
        let (k, t) = self.locate(u);
        (&self.segments[k], t)
    }
}

impl<P: Vector> ParamCurve<P> for PiecewiseCubic<P> {
    fn num_segments(&self) -> usize {
        self.segments.len()
    }
    fn eval(&self, u: f64) -> P {
        let (s, t) = self.seg(u);
        s.eval(t)
    }
    fn deriv(&self, u: f64) -> P {
        let (s, t) = self.seg(u);
        s.deriv(t)
    }
    fn deriv2(&self, u: f64) -> P {
        let (s, t) = self.seg(u);
        s.deriv2(t)
    }
    fn deriv3(&self, u: f64) -> P {
        self.seg(u).0.deriv3()
    }

    /// Sums per-segment adaptive integrals; the accuracy budget is shared among the
    /// pieces in proportion to their parameter width, so the total error stays within
    /// `accuracy`.
    fn arclen_range(&self, u0: f64, u1: f64, accuracy: f64) -> ArclenEstimate {
        arclen_by_segment(self.segments.len(), u0, u1, accuracy, |k, a, b, share| {
            self.segments[k].arclen_range(a - k as f64, b - k as f64, share)
        })
    }

    fn bounding_box(&self) -> Aabb<P> {
        let first = self.segments[0].bounding_box();
        self.segments[1..].iter().fold(first, |bb, s| bb.union(s.bounding_box()))
    }

    fn segment_end(&self, k: usize) -> P {
        self.segments[k.min(self.segments.len() - 1)].p3
    }

    /// The largest of the segments' exact bounds over the parts of `[u0, u1]` they cover.
    fn deriv2_bound(&self, u0: f64, u1: f64) -> f64 {
        let (k0, _) = self.locate(u0);
        let (k1, _) = self.locate(u1);
        (k0..=k1)
            .map(|k| {
                let a = if k == k0 { u0 - k as f64 } else { 0.0 };
                let b = if k == k1 { u1 - k as f64 } else { 1.0 };
                ParamCurve::<P>::deriv2_bound(&self.segments[k], a, b.max(a))
            })
            .fold(0.0, f64::max)
    }
}

/// Piecewise cubic Bézier curve from `3m + 1` control points: segment `k` uses
/// `P(3k) … P(3k+3)`.
///
/// # Interpolation
/// Passes through every third point `P(3k)`; the inner points shape the segments.
///
/// # Tangency
/// At a joint `P(3k)` the incoming tangent is `3(P(3k) − P(3k−1))` and the outgoing one
/// `3(P(3k+1) − P(3k))`.
///
/// # Continuity
/// C0 in general; C1 where `P(3k−1), P(3k), P(3k+1)` are collinear and equally spaced.
///
/// # Parametrization
/// `u ∈ [0, m]`. **Closed**: `3m` points; the last segment is
/// `P(3m−3), P(3m−2), P(3m−1), P(0)`.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{BezierSpline, ParamCurve};
/// let pts = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(2.0, 1.0), DVec2::new(3.0, 0.0)];
/// let curve = BezierSpline::new(&pts, false).unwrap().to_piecewise();
/// assert_eq!(curve.num_segments(), 1);
/// assert_eq!(curve.eval(1.0), DVec2::new(3.0, 0.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BezierSpline<P> {
    points: Vec<P>,
    closed: bool,
}

impl<P: Vector> BezierSpline<P> {
    /// Validates the point count (open: `3m+1`, m ≥ 1; closed: `3m`, m ≥ 1) and finiteness.
    pub fn new(points: &[P], closed: bool) -> Result<Self, SplineError> {
        let n = points.len();
        let ok = if closed { n >= 3 && n.is_multiple_of(3) } else { n >= 4 && n % 3 == 1 };
        if !ok {
            let rule = if closed { "3m (m ≥ 1, closed)" } else { "3m+1 (m ≥ 1)" };
            return Err(SplineError::BadPointCount { kind: "bezier", rule, given: n });
        }
        check_finite(points)?;
        Ok(Self { points: points.to_vec(), closed })
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// Compiles to a chain of cubic segments.
    #[must_use]
    pub fn to_piecewise(&self) -> PiecewiseCubic<P> {
        let n = self.points.len();
        let m = if self.closed { n / 3 } else { (n - 1) / 3 };
        let p = |i: usize| self.points[i % n];
        let segments = (0..m).map(|k| CubicBezier::new(p(3 * k), p(3 * k + 1), p(3 * k + 2), p(3 * k + 3))).collect();
        PiecewiseCubic { segments, closed: self.closed }
    }
}

/// Fails on the first non-finite point.
pub(crate) fn check_finite<P: Vector>(points: &[P]) -> Result<(), SplineError> {
    match points.iter().position(|p| !p.is_finite_vector()) {
        Some(index) => Err(SplineError::NonFinite { index }),
        None => Ok(()),
    }
}

/// Builds a chain without re-validating (for constructors that already validated).
pub(crate) fn chain<P: Vector>(segments: Vec<CubicBezier<P>>, closed: bool) -> PiecewiseCubic<P> {
    debug_assert!(!segments.is_empty());
    PiecewiseCubic { segments, closed }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn bezier_counts() {
        let p = |i: usize| DVec2::new(i as f64, (i * i) as f64);
        let pts: Vec<_> = (0..10).map(p).collect();
        assert_eq!(BezierSpline::new(&pts[..7], false).unwrap().to_piecewise().num_segments(), 2);
        assert!(BezierSpline::new(&pts[..6], false).is_err());
        assert!(BezierSpline::new(&pts[..1], false).is_err());
        let closed = BezierSpline::new(&pts[..6], true).unwrap().to_piecewise();
        assert_eq!(closed.num_segments(), 2);
        assert_eq!(closed.eval(2.0), pts[0]);
        assert!(closed.is_closed());
        let mut bad = pts[..4].to_vec();
        bad[2].x = f64::NAN;
        assert_eq!(BezierSpline::new(&bad, false), Err(SplineError::NonFinite { index: 2 }));
    }

    #[test]
    fn locate_is_total() {
        let pts: Vec<_> = (0..7).map(|i| DVec2::new(i as f64, 0.0)).collect();
        let c = BezierSpline::new(&pts, false).unwrap().to_piecewise();
        assert_eq!(c.locate(0.0), (0, 0.0));
        assert_eq!(c.locate(1.0), (1, 0.0));
        assert_eq!(c.locate(2.0), (1, 1.0));
        assert_eq!(c.locate(2.5), (1, 1.5));
        assert_eq!(c.locate(-0.5), (0, -0.5));
        assert_eq!(c.locate(f64::NAN).0, 0);
        assert_eq!(c.locate(f64::INFINITY).0, 1);
    }
}
