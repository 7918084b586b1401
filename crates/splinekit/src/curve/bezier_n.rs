//! Bézier curves of any degree: one polynomial piece from `n + 1` control points.

use crate::arclen::{self, ArclenEstimate};
use crate::curve::{Aabb, ParamCurve, SplineError, casteljau};
use crate::vector::Vector;

/// The most control points a [`BezierCurve`] takes (degree 64): de Casteljau's algorithm costs
/// `n²/2` operations per point, and beyond this degree the Bernstein basis has no use in
/// modelling.
pub const MAX_BEZIER_POINTS: usize = 65;

/// A Bézier curve of degree `n ≥ 1`: `P(t) = Σ Bᵢⁿ(t)·pᵢ`, `t ∈ [0, 1]`, with the Bernstein
/// polynomials `Bᵢⁿ(t) = C(n, i)·tⁱ·(1 − t)ⁿ⁻ⁱ`. Evaluated by de Casteljau's algorithm
/// (convex combinations only, so rounding stays at the level of the coordinates).
///
/// # Interpolation
/// Passes through the first and last control points; the others are approached.
///
/// # Tangency
/// `P′(0) = n·(p1 − p0)`, `P′(1) = n·(pₙ − pₙ₋₁)`.
///
/// # Parametrization
/// `t ∈ [0, 1]` (one segment); outside it the polynomial is extrapolated.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{BezierCurve, ParamCurve};
/// // a quadratic: the parabola y = x² − x on [0, 1]
/// let q = BezierCurve::new(vec![DVec2::ZERO, DVec2::new(0.5, -0.5), DVec2::X])?;
/// assert_eq!(q.eval(0.5), DVec2::new(0.5, -0.25));
/// let cubic = q.elevate();
/// assert_eq!(cubic.degree(), 3);
/// assert!((cubic.eval(0.3) - q.eval(0.3)).length() < 1e-15);
/// # Ok::<(), splinekit::SplineError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BezierCurve<P> {
    /// The control points, `degree + 1` of them (one for the constant hodographs made
    /// inside this module).
    points: Vec<P>,
}

impl<P: Vector> BezierCurve<P> {
    /// A curve of degree `points.len() − 1` (2 to [`MAX_BEZIER_POINTS`] finite points).
    pub fn new(points: Vec<P>) -> Result<Self, SplineError> {
        if points.len() < 2 {
            return Err(SplineError::InsufficientPoints { kind: "Bézier curve", needed: 2, given: points.len() });
        }
        if points.len() > MAX_BEZIER_POINTS {
            return Err(SplineError::BadPointCount {
                kind: "Bézier curve", rule: "from 2 to 65", given: points.len()
            });
        }
        if let Some(index) = points.iter().position(|p| !p.is_finite_vector()) {
            return Err(SplineError::NonFinite { index });
        }
        Ok(Self { points })
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The degree `n` (the number of control points less one).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The point at `t` by de Casteljau's algorithm.
    #[must_use]
    pub fn eval(&self, t: f64) -> P {
        casteljau::eval(&self.points, t, lerp)
    }

    /// The derivative curve (hodograph) `n·Σ Bᵢⁿ⁻¹(t)·(pᵢ₊₁ − pᵢ)`, of degree `n − 1` (a
    /// constant curve of one point for a line).
    #[must_use]
    pub fn derivative(&self) -> Self {
        Self { points: hodograph(&self.points) }
    }

    /// The `order`-th derivative at `t` (0 is the point); zero beyond the degree.
    #[must_use]
    pub fn deriv_at(&self, t: f64, order: usize) -> P {
        if order <= 3 {
            return casteljau::derivs(&self.points, t, lerp)[order];
        }
        let mut points = self.points.clone();
        for _ in 0..order {
            if points.len() == 1 {
                return points[0] * 0.0;
            }
            points = hodograph(&points);
        }
        casteljau::eval(&points, t, lerp)
    }

    /// The two halves at `t`: the curves over `[0, t]` and `[t, 1]`, each reparametrized to
    /// `[0, 1]` (de Casteljau's subdivision; exact up to rounding).
    #[must_use]
    pub fn split(&self, t: f64) -> (Self, Self) {
        let (left, right) = casteljau::split(&self.points, t, lerp);
        (Self { points: left }, Self { points: right })
    }

    /// The part over `[t0, t1]`, reparametrized to `[0, 1]` (`t1 < t0` reverses it; values
    /// outside `[0, 1]` extrapolate).
    #[must_use]
    pub fn segment(&self, t0: f64, t1: f64) -> Self {
        Self { points: casteljau::segment(&self.points, t0, t1, lerp) }
    }

    /// `pieces` curves over `[i/pieces, (i+1)/pieces]`, in order (at least one).
    #[must_use]
    pub fn subdivide(&self, pieces: usize) -> Vec<Self> {
        let pieces = pieces.max(1);
        (0..pieces).map(|i| self.segment(i as f64 / pieces as f64, (i + 1) as f64 / pieces as f64)).collect()
    }

    /// The same curve as degree `n + 1`: `qᵢ = (i/(n+1))·pᵢ₋₁ + (1 − i/(n+1))·pᵢ`.
    #[must_use]
    pub fn elevate(&self) -> Self {
        let n = self.points.len();
        let mut points = Vec::with_capacity(n + 1);
        points.push(self.points[0]);
        for i in 1..n {
            let a = i as f64 / n as f64;
            points.push(self.points[i - 1] * a + self.points[i] * (1.0 - a));
        }
        points.push(self.points[n - 1]);
        Self { points }
    }

    /// The box of the control points, which holds the curve over `[0, 1]`.
    #[must_use]
    pub fn control_box(&self) -> Aabb<P> {
        control_box(&self.points)
    }
}

/// The interpolation of control points for [`casteljau`].
fn lerp<P: Vector>(a: P, b: P, t: f64) -> P {
    a.lerp(b, t)
}

/// The hodograph's control points: `n·(pᵢ₊₁ − pᵢ)`; one zero point for a constant.
fn hodograph<P: Vector>(points: &[P]) -> Vec<P> {
    let n = points.len() - 1;
    if n == 0 {
        return vec![points[0] * 0.0];
    }
    points.windows(2).map(|w| (w[1] - w[0]) * n as f64).collect()
}

/// The box of `points` (at least one).
fn control_box<P: Vector>(points: &[P]) -> Aabb<P> {
    let first = Aabb { min: points[0], max: points[0] };
    points[1..].iter().fold(first, |b, &p| Aabb { min: b.min.min_components(p), max: b.max.max_components(p) })
}

impl<P: Vector> ParamCurve<P> for BezierCurve<P> {
    fn num_segments(&self) -> usize {
        1
    }
    fn eval(&self, u: f64) -> P {
        BezierCurve::eval(self, u)
    }
    fn deriv(&self, u: f64) -> P {
        self.deriv_at(u, 1)
    }
    fn deriv2(&self, u: f64) -> P {
        self.deriv_at(u, 2)
    }
    fn deriv3(&self, u: f64) -> P {
        self.deriv_at(u, 3)
    }
    /// Adaptive Gauss–Kronrod quadrature of the speed `|P′(t)|` (an error estimate, like the
    /// cubic's outside its certified planar path; tested against high-precision quadrature).
    fn arclen_range(&self, u0: f64, u1: f64, accuracy: f64) -> ArclenEstimate {
        let hodograph = self.derivative();
        arclen::integrate_speed(|t| hodograph.eval(t).length(), u0, u1, accuracy)
    }
    /// Exact to the rounding of the coordinates (branch and bound on control points).
    fn bounding_box(&self) -> Aabb<P> {
        let (mut lo, mut hi) = (glam::DVec3::ZERO, glam::DVec3::ZERO);
        for axis in 0..P::DIM {
            lo[axis] = -casteljau::extreme(&self.points, |p| -p.component(axis), lerp);
            hi[axis] = casteljau::extreme(&self.points, |p| p.component(axis), lerp);
        }
        Aabb { min: P::from_dvec3(lo), max: P::from_dvec3(hi) }
    }
    /// Exact up to the hull: the second derivative over `[u0, u1]` lies in the hull of the
    /// control points of the second hodograph's part over that interval.
    fn deriv2_bound(&self, u0: f64, u1: f64) -> f64 {
        let second = self.derivative().derivative();
        let part = if second.points.len() == 1 { second } else { second.segment(u0, u1) };
        part.points.iter().map(|p| p.length()).fold(0.0, f64::max)
    }
}
