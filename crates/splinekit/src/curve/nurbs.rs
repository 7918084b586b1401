//! NURBS: rational B-spline curves of any degree, with exact conics.

use core::f64::consts::FRAC_1_SQRT_2;

use glam::{DVec3, DVec4};

use crate::arclen::{self, ArclenEstimate};
use crate::curve::by_segment::arclen_by_segment;
use crate::curve::{Aabb, BezierCurve, ParamCurve, SplineError, casteljau};
use crate::vector::Vector;

/// The most control points a [`Nurbs`] takes.
pub const MAX_NURBS_POINTS: usize = 1 << 20;
/// The highest degree a [`Nurbs`] takes (de Boor's algorithm costs `degree²` per point).
pub const MAX_NURBS_DEGREE: usize = 32;

/// A NURBS curve: `C(x) = Σ Nᵢ,ₚ(x)·wᵢ·pᵢ / Σ Nᵢ,ₚ(x)·wᵢ` over a non-decreasing knot vector,
/// with degree `p ≥ 1`, `n` control points `pᵢ` and weights `wᵢ > 0`.
///
/// # Parametrization
/// Each knot span of positive length `[xₖ, xₖ₊₁]` inside the domain `[x_p, x_n]` is one unit
/// segment of the curve parameter `u` (`u ∈ [0, spans]`), mapped linearly, as for the other
/// kinds; [`knot_at`](Self::knot_at) gives the knot-vector parameter `x` of a `u`.
///
/// # Interpolation
/// With a clamped knot vector (the first and last knots repeated `p + 1` times, the default)
/// the curve starts at the first control point and ends at the last; [`Nurbs::periodic`]
/// makes a closed curve through none of them.
///
/// # Continuity
/// `C^(p−k)` at a knot of multiplicity `k`, `C∞` inside a span.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{Nurbs, ParamCurve};
/// let circle = Nurbs::<DVec2>::circle(2.0);
/// for i in 0..=100 {
///     assert!((circle.eval(circle.num_segments() as f64 * i as f64 / 100.0).length() - 2.0).abs() < 1e-14);
/// }
/// assert!((circle.arclen(1e-12) - 4.0 * std::f64::consts::PI).abs() < 1e-11);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Nurbs<P> {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<P>,
    weights: Vec<f64>,
    closed: bool,
    /// The knot spans `k` (`knots[k] < knots[k + 1]`, `degree ≤ k < n`), one per segment.
    spans: Vec<usize>,
    /// Per span, its rational Bézier piece: `degree + 1` homogeneous points `(w·p, w)`.
    pieces: Vec<Vec<DVec4>>,
}

impl<P: Vector> Nurbs<P> {
    /// A NURBS of `degree` through `points` with `weights` (one each, finite, positive) over
    /// `knots` (`points.len() + degree + 1` finite non-decreasing values), or over the clamped
    /// uniform knot vector when `knots` is `None`. Needs at least `degree + 1` points.
    pub fn new(degree: usize, points: Vec<P>, weights: Vec<f64>, knots: Option<Vec<f64>>) -> Result<Self, SplineError> {
        let n = points.len();
        check_definition(degree, &points, &weights)?;
        let knots = match knots {
            Some(knots) => {
                if knots.len() != n + degree + 1 {
                    return Err(SplineError::KnotCount { expected: n + degree + 1, given: knots.len() });
                }
                if let Some(index) = knots.iter().position(|k| !k.is_finite()) {
                    return Err(SplineError::BadKnot { index, why: "is not finite" });
                }
                if let Some(index) = knots.windows(2).position(|w| w[1] < w[0]) {
                    return Err(SplineError::BadKnot { index: index + 1, why: "is smaller than the knot before it" });
                }
                knots
            }
            None => clamped_uniform(n, degree),
        };
        Self::build(degree, knots, points, weights, false)
    }

    /// A closed (periodic) NURBS of `degree` over `points` with `weights` (at least
    /// `degree + 1` points, and at least 3): uniform knots, the first `degree` points
    /// repeated at the end, so that the curve is `C^(degree−1)` everywhere, also where it
    /// closes. It passes through no control point (for `degree ≥ 2`).
    pub fn periodic(degree: usize, points: Vec<P>, weights: Vec<f64>) -> Result<Self, SplineError> {
        check_definition(degree, &points, &weights)?;
        if points.len() < 3 {
            return Err(SplineError::InsufficientPoints { kind: "closed NURBS", needed: 3, given: points.len() });
        }
        let mut wrapped = points.clone();
        let mut wrapped_weights = weights.clone();
        for i in 0..degree {
            wrapped.push(points[i % points.len()]);
            wrapped_weights.push(weights[i % weights.len()]);
        }
        let knots = (0..wrapped.len() + degree + 1).map(|i| i as f64).collect();
        Self::build(degree, knots, wrapped, wrapped_weights, true)
    }

    /// The exact circle of `radius` about the origin in the xy-plane, counter-clockwise from
    /// `(radius, 0)`: nine control points of a quadratic with weights 1 and `1/√2` at the
    /// corners of the square around it, four spans (quarter circles).
    #[must_use]
    pub fn circle(radius: f64) -> Self {
        Self::ellipse(radius, radius)
    }

    /// The exact axis-aligned ellipse with semi-axes `rx` (along x) and `ry`, counter-clockwise
    /// from `(rx, 0)` (the circle's NURBS, scaled).
    #[must_use]
    pub fn ellipse(rx: f64, ry: f64) -> Self {
        let corners = [
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (-1.0, 1.0),
            (-1.0, 0.0),
            (-1.0, -1.0),
            (0.0, -1.0),
            (1.0, -1.0),
            (1.0, 0.0),
        ];
        let points = corners.iter().map(|&(x, y)| P::from_dvec3(DVec3::new(rx * x, ry * y, 0.0))).collect();
        let weights = (0..9).map(|i| if i % 2 == 1 { FRAC_1_SQRT_2 } else { 1.0 }).collect();
        let knots = vec![0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0];
        // a valid definition by construction
        Self::build(2, knots, points, weights, true).unwrap_or_else(|_| unreachable!("the circle's NURBS is valid"))
    }

    /// The chain of Bézier curves `pieces` as one NURBS: each piece raised to the highest
    /// degree among them ([`BezierCurve::elevate`], the same curve), the pieces joined end to
    /// start over knots of multiplicity `degree` at the joins (so the curve is exactly the
    /// chain, continuous there and no more), all weights 1. Segment `k` is piece `k`, with the
    /// same parameter: `eval(k + t)` is `pieces[k].eval(t)`.
    ///
    /// # Errors
    ///
    /// [`SplineError::Empty`] without pieces, [`SplineError::BadDegree`] above
    /// [`MAX_NURBS_DEGREE`], and [`SplineError::NotJoined`] where a piece does not start
    /// exactly at the point where the one before it ends.
    pub fn from_beziers(pieces: &[BezierCurve<P>]) -> Result<Self, SplineError> {
        let Some(degree) = pieces.iter().map(BezierCurve::degree).max() else { return Err(SplineError::Empty) };
        if degree > MAX_NURBS_DEGREE {
            return Err(SplineError::BadDegree { degree, max: MAX_NURBS_DEGREE });
        }
        let mut points: Vec<P> = Vec::with_capacity(pieces.len() * degree + 1);
        let mut knots = vec![0.0; degree + 1];
        for (k, piece) in pieces.iter().enumerate() {
            let mut raised = piece.clone();
            while raised.degree() < degree {
                raised = raised.elevate();
            }
            let own = raised.points();
            if let Some(&end) = points.last() {
                if own[0] != end {
                    return Err(SplineError::NotJoined { index: k });
                }
                points.extend_from_slice(&own[1..]);
            } else {
                points.extend_from_slice(own);
            }
            let knot = (k + 1) as f64;
            knots.extend(std::iter::repeat_n(knot, if k + 1 < pieces.len() { degree } else { degree + 1 }));
        }
        let weights = vec![1.0; points.len()];
        check_definition(degree, &points, &weights)?;
        Self::build(degree, knots, points, weights, false)
    }

    /// The exact arc of the axis-aligned ellipse with semi-axes `rx` (along x) and `ry` about
    /// the origin in the xy-plane, from the point at angle `start` (radians) by `sweep`
    /// (negative: clockwise; at most a full turn), the point at angle `θ` being
    /// `(rx·cos θ, ry·sin θ)`: a quadratic with one span per quarter turn or less, each the
    /// rational quadratic through the span's end points whose middle control point is where
    /// their tangents meet, of weight `cos(Δ/2)` for a span of `Δ` (the circle's arc, scaled).
    /// The spans join at the angles `start + k·Δ`; a full turn is closed.
    ///
    /// # Errors
    ///
    /// [`SplineError::BadArc`] for a non-finite value, a sweep of 0 or more than a full turn.
    pub fn elliptic_arc(rx: f64, ry: f64, start: f64, sweep: f64) -> Result<Self, SplineError> {
        use core::f64::consts::{FRAC_PI_2, TAU};
        if ![rx, ry, start, sweep].iter().all(|v| v.is_finite()) {
            return Err(SplineError::BadArc { why: "its semi-axes and angles must be finite" });
        }
        if sweep == 0.0 || sweep.abs() > TAU {
            return Err(SplineError::BadArc { why: "its sweep must be nonzero and at most a full turn (2π)" });
        }
        // spans of at most a quarter turn (a little more from rounding is harmless)
        let n = ((sweep.abs() / FRAC_PI_2) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
        let delta = sweep / n as f64;
        let on_ellipse =
            |angle: f64, scale: f64| P::from_dvec3(DVec3::new(rx * angle.cos() * scale, ry * angle.sin() * scale, 0.0));
        let middle_weight = (0.5 * delta).cos();
        let mut points = Vec::with_capacity(2 * n + 1);
        let mut weights = Vec::with_capacity(2 * n + 1);
        let mut knots = vec![0.0; 3];
        points.push(on_ellipse(start, 1.0));
        weights.push(1.0);
        for k in 0..n {
            let a0 = start + delta * k as f64;
            points.push(on_ellipse(a0 + 0.5 * delta, 1.0 / middle_weight));
            weights.push(middle_weight);
            points.push(on_ellipse(a0 + delta, 1.0));
            weights.push(1.0);
            let knot = (k + 1) as f64;
            // interior knots double (the spans join with C¹ direction, C⁰ in the parameter), the
            // last one clamped
            let repeat = if k + 1 < n { 2 } else { 3 };
            knots.extend(std::iter::repeat_n(knot, repeat));
        }
        let closed = sweep.abs() == TAU;
        Self::build(2, knots, points, weights, closed)
    }

    fn build(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<P>,
        weights: Vec<f64>,
        closed: bool,
    ) -> Result<Self, SplineError> {
        let n = points.len();
        let spans: Vec<usize> = (degree..n).filter(|&k| knots[k] < knots[k + 1]).collect();
        if spans.is_empty() {
            return Err(SplineError::BadKnot {
                index: degree,
                why: "leaves the curve's domain empty (all its knots are equal)",
            });
        }
        let mut curve = Self { degree, knots, points, weights, closed, spans, pieces: Vec::new() };
        curve.pieces = curve.spans.iter().map(|&span| curve.bezier_piece(span)).collect();
        Ok(curve)
    }

    /// The rational Bézier piece of `span`: its control points are the blossoms
    /// `f(a, …, a, b, …, b)` (`degree − i` times `a = knots[span]`, `i` times `b`), each by de
    /// Boor's algorithm with one argument per level.
    fn bezier_piece(&self, span: usize) -> Vec<DVec4> {
        let p = self.degree;
        let (a, b) = (self.knots[span], self.knots[span + 1]);
        (0..=p)
            .map(|i| {
                let mut d: Vec<DVec4> = (span - p..=span).map(|j| self.homogeneous(j)).collect();
                for r in 1..=p {
                    let t = if r <= p - i { a } else { b };
                    for j in (r..=p).rev() {
                        let k = span - p + j;
                        let (lo, hi) = (self.knots[k], self.knots[k + p + 1 - r]);
                        let alpha = if hi > lo { (t - lo) / (hi - lo) } else { 0.0 };
                        d[j] = d[j - 1] * (1.0 - alpha) + d[j] * alpha;
                    }
                }
                d[p]
            })
            .collect()
    }

    /// The degree.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector (for a periodic curve, over the wrapped control points).
    #[must_use]
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control points (for a periodic curve, with the first `degree` repeated at the end).
    #[must_use]
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The weights, one per control point.
    #[must_use]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Whether the curve was made closed.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The knot-vector parameter `x` of the curve parameter `u`.
    #[must_use]
    pub fn knot_at(&self, u: f64) -> f64 {
        self.locate(u).2
    }

    /// The curve parameter `u` of the knot-vector parameter `x`, the inverse of
    /// [`knot_at`](Self::knot_at): `u = k + (x − xₛ)/(xₛ₊₁ − xₛ)` for the segment `k` whose
    /// span `[xₛ, xₛ₊₁)` holds `x` (at an interior knot, the segment that starts there, so
    /// the result is the integer `k` exactly; at the domain's end, `num_segments`). Outside
    /// the domain `[x_p, x_n]` it extrapolates linearly over the first or last span, as
    /// evaluation does. `dx/du` is that span's length.
    ///
    /// ```
    /// use glam::DVec2;
    /// use splinekit::{Nurbs, ParamCurve};
    /// let knots = vec![0.0, 0.0, 0.0, 0.5, 2.0, 2.0, 2.0];
    /// let c = Nurbs::new(2, vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y], vec![1.0; 4], Some(knots)).unwrap();
    /// assert_eq!(c.param_at_knot(0.5), 1.0);
    /// assert_eq!(c.param_at_knot(1.25), 1.5);
    /// assert_eq!(c.knot_at(c.param_at_knot(1.25)), 1.25);
    /// ```
    #[must_use]
    pub fn param_at_knot(&self, x: f64) -> f64 {
        // the spans' starts increase strictly: the last segment starting at or before x
        let k = self.spans.partition_point(|&span| self.knots[span] <= x).saturating_sub(1);
        let span = self.spans[k];
        let (a, b) = (self.knots[span], self.knots[span + 1]);
        k as f64 + (x - a) / (b - a)
    }

    /// For `u`: its segment, that segment's knot span, the knot parameter `x` and `dx/du`.
    fn locate(&self, u: f64) -> (usize, usize, f64, f64) {
        let m = self.spans.len();
        let k = if u > 0.0 { (u.floor() as usize).min(m - 1) } else { 0 };
        let span = self.spans[k];
        let (a, b) = (self.knots[span], self.knots[span + 1]);
        (k, span, a + (u - k as f64) * (b - a), b - a)
    }

    /// The homogeneous control point `(w·p, w)`.
    fn homogeneous(&self, i: usize) -> DVec4 {
        let w = self.weights[i];
        (self.points[i].to_dvec3() * w).extend(w)
    }

    /// The `order`-th derivative (0 to 3) with respect to the curve parameter `u`: from the
    /// derivatives of the segment's homogeneous rational Bézier piece `(A(t), w(t))` at
    /// `t = u − k` (one de Casteljau triangle; `u` and `t` differ by a constant), by the
    /// quotient rule `C = A/w`, `A⁽ʳ⁾ = Σ C(r, i)·w⁽ⁱ⁾·C⁽ʳ⁻ⁱ⁾`.
    fn at(&self, u: f64, order: usize) -> P {
        let m = self.pieces.len();
        let k = if u > 0.0 { (u.floor() as usize).min(m - 1) } else { 0 };
        let piece = &self.pieces[k];
        let t = u - k as f64;
        if order == 0 {
            let q = casteljau::eval(piece, t, DVec4::lerp);
            return P::from_dvec3(q.truncate() / q.w);
        }
        let [a0, a1, a2, a3] = casteljau::derivs(piece, t, DVec4::lerp);
        let (w0, w1, w2, w3) = (a0.w, a1.w, a2.w, a3.w);
        let c0 = a0.truncate() / w0;
        let c1 = (a1.truncate() - c0 * w1) / w0;
        let c = match order {
            1 => c1,
            2 => (a2.truncate() - c1 * (2.0 * w1) - c0 * w2) / w0,
            _ => {
                let c2 = (a2.truncate() - c1 * (2.0 * w1) - c0 * w2) / w0;
                (a3.truncate() - c2 * (3.0 * w1) - c1 * (3.0 * w2) - c0 * w3) / w0
            }
        };
        P::from_dvec3(c)
    }

    /// Inserts the knot `x` once (Boehm's algorithm); the curve is unchanged. `x` must lie in
    /// the domain `[x_p, x_n)`; otherwise, or for a knot already of multiplicity `degree`, the
    /// curve is returned as it is.
    #[must_use]
    pub fn insert_knot(&self, x: f64) -> Self {
        let p = self.degree;
        let (first, last) = (self.knots[p], self.knots[self.points.len()]);
        let multiplicity = self.knots.iter().filter(|&&k| k == x).count();
        if !(x >= first && x < last) || multiplicity >= p {
            return self.clone();
        }
        // the span k with knots[k] ≤ x < knots[k + 1]
        let Some(k) = (p..self.points.len()).find(|&k| self.knots[k] <= x && x < self.knots[k + 1]) else {
            return self.clone();
        };
        let homogeneous: Vec<DVec4> = (0..self.points.len()).map(|i| self.homogeneous(i)).collect();
        let mut inserted = Vec::with_capacity(homogeneous.len() + 1);
        for i in 0..=homogeneous.len() {
            let q = if i + p <= k {
                homogeneous[i]
            } else if i > k {
                homogeneous[i - 1]
            } else {
                let alpha = (x - self.knots[i]) / (self.knots[i + p] - self.knots[i]);
                homogeneous[i - 1] * (1.0 - alpha) + homogeneous[i] * alpha
            };
            inserted.push(q);
        }
        let mut knots = self.knots.clone();
        knots.insert(k + 1, x);
        let weights: Vec<f64> = inserted.iter().map(|h| h.w).collect();
        let points: Vec<P> = inserted.iter().map(|h| P::from_dvec3(h.truncate() / h.w)).collect();
        // the spans only gain a knot: the definition stays valid
        Self::build(p, knots, points, weights, self.closed).unwrap_or_else(|_| self.clone())
    }

    /// The projected control polygon of the part over `u ∈ [u0, u1]` inside one segment (the
    /// segment of `u0`): its convex hull holds that part, the weights being positive.
    pub(crate) fn part_polygon(&self, u0: f64, u1: f64) -> Vec<P> {
        let k = self.locate(u0).0;
        let (t0, t1) = ((u0 - k as f64).clamp(0.0, 1.0), (u1 - k as f64).clamp(0.0, 1.0));
        sub_piece(&self.pieces[k], t0, t1.max(t0)).iter().map(|q| P::from_dvec3(q.truncate() / q.w)).collect()
    }

    /// The rational Bézier pieces, one per segment: homogeneous control points `(w·p, w)`,
    /// `degree + 1` per piece, over `t ∈ [0, 1]` for the segment's knot span.
    #[must_use]
    pub fn bezier_pieces(&self) -> &[Vec<DVec4>] {
        &self.pieces
    }
}

/// The part of a homogeneous Bézier piece over `[t0, t1] ⊂ [0, 1]`.
fn sub_piece(points: &[DVec4], t0: f64, t1: f64) -> Vec<DVec4> {
    casteljau::segment(points, t0, t1, DVec4::lerp)
}

/// Checks the degree, the point and weight counts and values.
fn check_definition<P: Vector>(degree: usize, points: &[P], weights: &[f64]) -> Result<(), SplineError> {
    if degree == 0 || degree > MAX_NURBS_DEGREE {
        return Err(SplineError::BadDegree { degree, max: MAX_NURBS_DEGREE });
    }
    if points.len() < degree + 1 {
        return Err(SplineError::InsufficientPoints { kind: "NURBS", needed: degree + 1, given: points.len() });
    }
    if points.len() > MAX_NURBS_POINTS {
        return Err(SplineError::BadPointCount { kind: "NURBS", rule: "at most 1048576", given: points.len() });
    }
    if weights.len() != points.len() {
        return Err(SplineError::WeightCount { points: points.len(), weights: weights.len() });
    }
    if let Some(index) = points.iter().position(|p| !p.is_finite_vector()) {
        return Err(SplineError::NonFinite { index });
    }
    if let Some(index) = weights.iter().position(|w| !(w.is_finite() && *w > 0.0)) {
        return Err(SplineError::BadWeight { index, weight: weights[index] });
    }
    Ok(())
}

/// The clamped uniform knot vector of `n` points and `degree`: `degree + 1` zeros, the
/// interior knots `1 … n − degree − 1`, `degree + 1` times `n − degree`.
fn clamped_uniform(n: usize, degree: usize) -> Vec<f64> {
    let last = (n - degree) as f64;
    (0..n + degree + 1).map(|i| (i as f64 - degree as f64).clamp(0.0, last)).collect()
}

impl<P: Vector> ParamCurve<P> for Nurbs<P> {
    fn num_segments(&self) -> usize {
        self.spans.len()
    }
    fn eval(&self, u: f64) -> P {
        self.at(u, 0)
    }
    fn deriv(&self, u: f64) -> P {
        self.at(u, 1)
    }
    fn deriv2(&self, u: f64) -> P {
        self.at(u, 2)
    }
    fn deriv3(&self, u: f64) -> P {
        self.at(u, 3)
    }
    /// The last point of the segment's rational Bézier piece.
    fn segment_end(&self, k: usize) -> P {
        let piece = &self.pieces[k.min(self.pieces.len() - 1)];
        let last = piece[piece.len() - 1];
        P::from_dvec3(last.truncate() / last.w)
    }
    /// Adaptive Gauss–Kronrod quadrature of the speed, span by span (the speed of a rational
    /// curve is no polynomial's square root, so the error is an estimate; tested against
    /// high-precision quadrature and the circle's exact length).
    fn arclen_range(&self, u0: f64, u1: f64, accuracy: f64) -> ArclenEstimate {
        arclen_by_segment(self.spans.len(), u0, u1, accuracy, |_, a, b, share| {
            arclen::integrate_speed(|u| ParamCurve::<P>::deriv(self, u).length(), a, b, share)
        })
    }
    /// The box of the rational Bézier pieces' extremes, to the rounding of the coordinates
    /// (branch and bound on the pieces' projected control points, which hold the curve).
    fn bounding_box(&self) -> Aabb<P> {
        let pieces = &self.pieces;
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for piece in pieces {
            for axis in 0..P::DIM {
                lo[axis] = lo[axis].min(-casteljau::extreme(piece, |q| -q[axis] / q.w, DVec4::lerp));
                hi[axis] = hi[axis].max(casteljau::extreme(piece, |q| q[axis] / q.w, DVec4::lerp));
            }
        }
        Aabb { min: P::from_dvec3(lo), max: P::from_dvec3(hi) }
    }
    /// From the rational Bézier piece over the interval (translated to start at the origin):
    /// with `w ≥ w_min`, `|C| ≤ R`, and the homogeneous hodographs' hull bounds,
    /// `|C′| ≤ (|A′| + |w′|·R)/w_min` and `|C″| ≤ (|A″| + 2|w′|·|C′| + |w″|·R)/w_min`, times
    /// `(dx/du)²`.
    fn deriv2_bound(&self, u0: f64, u1: f64) -> f64 {
        if !(u1 > u0) {
            return ParamCurve::<P>::deriv2(self, u0).length();
        }
        let (k0, k1) = (self.locate(u0).0, self.locate(u1).0);
        let mut bound: f64 = 0.0;
        for k in k0..=k1 {
            let t0 = if k == k0 { u0 - k as f64 } else { 0.0 };
            let t1 = if k == k1 { u1 - k as f64 } else { 1.0 };
            let piece = sub_piece(&self.pieces[k], t0.clamp(0.0, 1.0), t1.clamp(t0.clamp(0.0, 1.0), 1.0));
            let origin = piece[0].truncate() / piece[0].w;
            let h: Vec<DVec4> = piece.iter().map(|q| (q.truncate() - origin * q.w).extend(q.w)).collect();
            let n = (h.len() - 1) as f64;
            let w_min = h.iter().map(|q| q.w).fold(f64::INFINITY, f64::min);
            let reach = h.iter().map(|q| q.truncate().length() / q.w).fold(0.0, f64::max);
            let d1: Vec<DVec4> = h.windows(2).map(|w| (w[1] - w[0]) * n).collect();
            let d2: Vec<DVec4> = d1.windows(2).map(|w| (w[1] - w[0]) * (n - 1.0)).collect();
            let norm = |v: &[DVec4]| v.iter().map(|q| q.truncate().length()).fold(0.0, f64::max);
            let wnorm = |v: &[DVec4]| v.iter().map(|q| q.w.abs()).fold(0.0, f64::max);
            let (a1, w1) = (norm(&d1), wnorm(&d1));
            let (a2, w2) = (norm(&d2), wnorm(&d2));
            let c1 = (a1 + w1 * reach) / w_min;
            let c2 = (a2 + 2.0 * w1 * c1 + w2 * reach) / w_min;
            // the piece runs over t ∈ [0, 1] for u ∈ [k + t0, k + t1]: d/du = d/dt / (t1 − t0)
            let width = t1 - t0;
            let scale = if width > 0.0 { 1.0 / width } else { 0.0 };
            bound = bound.max(c2 * scale * scale);
        }
        bound
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec2;

    use super::*;

    /// A cubic over non-uniform knots with a double interior knot and a domain away from 0.
    fn curve() -> Nurbs<DVec2> {
        let points: Vec<DVec2> = (0..7).map(|i| DVec2::new(i as f64, (i * i % 5) as f64)).collect();
        let knots = vec![1.0, 1.0, 1.0, 1.0, 1.5, 2.25, 2.25, 4.0, 4.0, 4.0, 4.0];
        Nurbs::new(3, points, vec![1.0, 2.0, 0.5, 1.0, 3.0, 1.0, 0.25], Some(knots)).unwrap()
    }

    #[test]
    fn param_at_knot_inverts_knot_at() {
        let c = curve();
        assert_eq!(ParamCurve::<DVec2>::num_segments(&c), 3);
        // the distinct knots of the domain are the segments' ends, exactly
        for (x, u) in [(1.0, 0.0), (1.5, 1.0), (2.25, 2.0), (4.0, 3.0)] {
            assert_eq!(c.param_at_knot(x), u, "x = {x}");
            assert_eq!(c.knot_at(u), x, "u = {u}");
        }
        for i in 0..=300 {
            let x = 1.0 + 3.0 * i as f64 / 300.0;
            let u = c.param_at_knot(x);
            assert!((c.knot_at(u) - x).abs() <= 4.0 * f64::EPSILON * x, "x = {x}, u = {u}");
            let k = c.knot_at(u.floor().min(2.0));
            assert!(k <= x, "x = {x} lies in the segment of u = {u}");
        }
    }

    #[test]
    fn param_at_knot_extrapolates_outside_the_domain() {
        let c = curve();
        // first span [1, 1.5], last span [2.25, 4]
        assert_eq!(c.param_at_knot(0.5), -1.0);
        assert_eq!(c.param_at_knot(5.75), 4.0);
        assert!(c.param_at_knot(f64::NAN).is_nan());
    }
}
