//! The point of a curve nearest to a query point, over the whole curve, to a stated accuracy.
//!
//! # The bound
//!
//! On a parameter interval `[u0, u1]` of width `h`, a curve whose second derivative is at
//! most `M` in length stays within `M·h²/8` of the chord from `P(u0)` to `P(u1)` (the error
//! of linear interpolation, `e = P − L`, vanishes at both ends and has `e″ = P″`; its Green's
//! function gives `|e(u)| ≤ M·(u − u0)(u1 − u)/2`). So no point of the interval is nearer to
//! `q` than `dist(q, chord) − M·h²/8`: a lower bound that tightens as `h²`. Each kind gives
//! `M` through [`ParamCurve::deriv2_bound`]: exact for cubic Béziers (the second derivative
//! is linear, so its largest length on an interval is at an end), exact constants for
//! circles and helices, the knot's exact maximum for the trefoil.
//!
//! # The search
//!
//! Branch and bound: the intervals, each with its lower bound, wait in a queue ordered by
//! it; the best distance found so far (at chord feet and interval ends) is the upper bound.
//! The interval with the smallest lower bound is split in two until that bound is within
//! `accuracy` of the best distance, which is then within `accuracy` of the true minimum over
//! the whole curve (every interval not split has a larger lower bound). An interval on which
//! `|P(u) − q|²` is provably monotone (its derivative's sign at the middle outlasts the
//! derivative's bounded slope) or convex (its second derivative bounded below by a positive
//! number) is solved outright: at an end, or by Newton's method with the tangent-parabola
//! bound. A local Newton step from the best point only ever lowers the upper bound. No
//! starting guess, so no local minimum is mistaken for the global one.
//!
//! Floating point: distances are computed to about `ε·(|q| + size of the curve)`, so the
//! accuracy is raised to [`accuracy_floor`] of that scale. Work is bounded by
//! [`MAX_NEAREST_INTERVALS`] splits; a search that reaches it (only when very many points
//! are almost equally near, like the centre of a circle at an accuracy near the floor)
//! returns its best point with the gap it could prove, in [`Nearest::error`].

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::curve::ParamCurve;
use crate::vector::Vector;

/// The most intervals a search splits (each split costs two evaluations); see the module
/// docs.
pub const MAX_NEAREST_INTERVALS: usize = 2_000_000;

/// The point of a curve nearest to a query point (see [`ParamCurve::nearest`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest<P> {
    /// The curve parameter of the point, in the curve's domain.
    pub u: f64,
    /// The point, `eval(u)`.
    pub point: P,
    /// Its distance to the query point, `|point − q|`.
    pub distance: f64,
    /// A proved bound of `distance − (the true minimum distance)`: at most
    /// [`accuracy`](Self::accuracy), unless the search reached [`MAX_NEAREST_INTERVALS`].
    pub error: f64,
    /// The accuracy the search worked to: the one asked for, raised to [`accuracy_floor`].
    pub accuracy: f64,
}

/// The smallest accuracy a search can prove for a query point `q` and a curve whose
/// bounding box reaches `extent` (the largest absolute coordinate): `16ε·(|q| + extent)`,
/// the rounding of the distances and chord bounds it compares.
#[must_use]
pub fn accuracy_floor(q_length: f64, extent: f64) -> f64 {
    16.0 * f64::EPSILON * (q_length + extent)
}

/// An interval waiting in the queue, ordered by its lower bound (smallest first).
struct Pending<P> {
    lower: f64,
    u0: f64,
    u1: f64,
    /// The curve at `u0` and, as the interval's own piece reaches it, at `u1` (a chain may
    /// jump where a segment ends; the next segment's start is not this interval's end).
    ends: (P, P),
    /// Whether the curve is continuous at `u1` (the interval can be solved outright).
    joined: bool,
}

impl<P> PartialEq for Pending<P> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl<P> Eq for Pending<P> {}
impl<P> PartialOrd for Pending<P> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<P> Ord for Pending<P> {
    /// Reversed, so that `BinaryHeap` (a max-heap) pops the smallest lower bound; ties by
    /// parameter, so that the search is deterministic.
    fn cmp(&self, other: &Self) -> Ordering {
        other.lower.total_cmp(&self.lower).then_with(|| other.u0.total_cmp(&self.u0))
    }
}

/// The search state: the best point so far.
struct Best<P> {
    u: f64,
    point: P,
    distance: f64,
}

impl<P: Vector> Best<P> {
    fn offer(&mut self, u: f64, point: P, q: P) {
        let distance = (point - q).length();
        // ties keep the smaller parameter, so that the answer does not depend on the order
        if distance < self.distance || (distance == self.distance && u < self.u) {
            *self = Self { u, point, distance };
        }
    }
}

/// The parameter in `[0, 1]` of the point of the segment `a b` nearest to `q`.
fn chord_foot<P: Vector>(a: P, b: P, q: P) -> f64 {
    let d = b - a;
    let dd = d.dot(d);
    if dd > 0.0 { ((q - a).dot(d) / dd).clamp(0.0, 1.0) } else { 0.0 }
}

/// See [`ParamCurve::nearest`].
pub(crate) fn nearest<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, q: P, accuracy: f64) -> Nearest<P> {
    let (lo, hi) = curve.domain();
    let bb = curve.bounding_box();
    let extent = (0..P::DIM).fold(0.0_f64, |m, i| m.max(bb.min.component(i).abs()).max(bb.max.component(i).abs()));
    let accuracy = accuracy.max(accuracy_floor(q.length(), extent));
    let start = curve.eval(lo);
    let mut best = Best { u: lo, point: start, distance: (start - q).length() };
    let mut queue = BinaryHeap::new();
    // `ends` are the points at u0 and u1 (see `Pending`)
    let push =
        |queue: &mut BinaryHeap<Pending<P>>, best: &mut Best<P>, u0: f64, u1: f64, ends: (P, P), joined: bool| {
            let foot = chord_foot(ends.0, ends.1, q);
            let chord_point = ends.0 + (ends.1 - ends.0) * foot;
            let h = u1 - u0;
            let sag = curve.deriv2_bound(u0, u1) * h * h / 8.0;
            let lower = (q - chord_point).length() - sag;
            // the curve at the chord's foot is often the best point of the interval
            let u = u0 + foot * h;
            if u > u0 && u < u1 {
                best.offer(u, curve.eval(u), q);
            }
            queue.push(Pending { lower, u0, u1, ends, joined });
        };
    let segments = curve.num_segments().max(1);
    for k in 0..segments {
        let u0 = lo + (hi - lo) * (k as f64 / segments as f64);
        let u1 = if k + 1 == segments { hi } else { lo + (hi - lo) * ((k + 1) as f64 / segments as f64) };
        let (first, next) = (curve.eval(u0), curve.eval(u1));
        best.offer(u0, first, q);
        best.offer(u1, next, q);
        let end = curve.segment_end(k);
        push(&mut queue, &mut best, u0, u1, (first, end), end == next);
    }
    polish(curve, q, &mut best, lo, hi);
    let mut splits = 0;
    // the smallest lower bound of the intervals solved exactly, and of the interval the search
    // stopped at
    let (mut solved, mut stopped) = (f64::INFINITY, f64::INFINITY);
    while let Some(top) = queue.pop() {
        if top.lower >= best.distance - accuracy {
            stopped = top.lower;
            break;
        }
        if top.joined
            && let Some(lower) = solve_convex(curve, q, top.u0, top.u1, accuracy, &mut best)
        {
            solved = solved.min(lower);
            continue;
        }
        let mid = 0.5 * (top.u0 + top.u1);
        if splits == MAX_NEAREST_INTERVALS || !(mid > top.u0 && mid < top.u1) {
            // out of work, or an interval at the rounding of its parameter: keep its bound
            stopped = top.lower;
            break;
        }
        splits += 1;
        let ((a, b), m) = (top.ends, curve.eval(mid));
        best.offer(mid, m, q);
        push(&mut queue, &mut best, top.u0, mid, (a, m), true);
        push(&mut queue, &mut best, mid, top.u1, (m, b), top.joined);
    }
    let waiting = queue.peek().map_or(f64::INFINITY, |p| p.lower);
    let proved = stopped.min(waiting).min(solved).min(best.distance);
    polish(curve, q, &mut best, lo, hi);
    let error = (best.distance - proved).max(0.0);
    Nearest { u: best.u, point: best.point, distance: best.distance, error, accuracy }
}

/// Solves the interval `[u0, u1]` exactly when `f(u) = |P(u) − q|²` is provably monotone or
/// convex on it, offering its minimum to `best`; returns a lower bound of the distance over
/// the interval, or `None` when neither can be shown (the interval is then split).
///
/// A bound looser than `accuracy / 4` below the point found also gives `None`.
///
/// `f″/2 = |P′|² + (P − q)·P″`, and over the interval `|P′| ≥ |P′(m)| − M·h/2` and
/// `|P − q| ≤ |P(m) − q| + (|P′(m)| + M·h/2)·h/2` (`m` the middle, `M` the second-derivative
/// bound): when these give `f″ ≥ c > 0`, `f` has one minimum, found by Newton's method on
/// `f′` kept inside a bracket, and `f(u) ≥ f(x) − f′(x)²/(2c)` at any `x` bounds it from below
/// (the tangent parabola), which is tight once `f′(x)` is at rounding level.
fn solve_convex<P: Vector, C: ParamCurve<P> + ?Sized>(
    curve: &C,
    q: P,
    u0: f64,
    u1: f64,
    accuracy: f64,
    best: &mut Best<P>,
) -> Option<f64> {
    let h = u1 - u0;
    let m = 0.5 * (u0 + u1);
    let (p, d1) = (curve.eval(m), curve.deriv(m));
    let bound = curve.deriv2_bound(u0, u1);
    let speed = d1.length();
    let (speed_lo, speed_hi) = (speed - bound * h / 2.0, speed + bound * h / 2.0);
    let reach = (p - q).length() + speed_hi * h / 2.0;
    // monotone: |f″/2| ≤ |P′|² + |P − q|·|P″| over the interval, so f′/2 = (P − q)·P′ keeps
    // the sign it has at the middle when that is farther from 0 than its slope can carry it;
    // the minimum is then at an end
    let g_mid = (p - q).dot(d1);
    if g_mid.abs() > (speed_hi * speed_hi + reach * bound) * h / 2.0 {
        let end = if g_mid > 0.0 { u0 } else { u1 };
        let point = curve.eval(end);
        best.offer(end, point, q);
        return Some((point - q).length());
    }
    // c = a lower bound of f″ (twice the bound of f″/2)
    let c = 2.0 * (speed_lo * speed_lo - reach * bound);
    if !(speed_lo > 0.0 && c > 0.0) {
        return None;
    }
    // g = f′/2 = (P − q)·P′, increasing on the interval
    let g = |u: f64| (curve.eval(u) - q).dot(curve.deriv(u));
    let (ga, gb) = (g(u0), g(u1));
    let x = if ga >= 0.0 {
        u0
    } else if gb <= 0.0 {
        u1
    } else {
        let (mut a, mut b) = (u0, u1);
        let mut x = m;
        for _ in 0..60 {
            let (px, d1, d2) = (curve.eval(x), curve.deriv(x), curve.deriv2(x));
            let gx = (px - q).dot(d1);
            if gx == 0.0 {
                break;
            }
            if gx < 0.0 {
                a = x;
            } else {
                b = x;
            }
            let slope = d1.dot(d1) + (px - q).dot(d2);
            let newton = x - gx / slope;
            let next = if newton > a && newton < b { newton } else { 0.5 * (a + b) };
            // converged to the rounding of the parameter (Newton then only dithers)
            let settled = (next - x).abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0);
            x = next;
            if settled || !(b > a) {
                break;
            }
        }
        x
    };
    let px = curve.eval(x);
    best.offer(x, px, q);
    let fx = (px - q).length_squared();
    // at an end where f′ points outward the end is the minimum; inside, the tangent parabola
    let lower_sq = if (x == u0 && ga >= 0.0) || (x == u1 && gb <= 0.0) {
        fx
    } else {
        let gx = (px - q).dot(curve.deriv(x));
        fx - 2.0 * gx * gx / c
    };
    let lower = lower_sq.max(0.0).sqrt();
    (lower >= fx.sqrt() - 0.25 * accuracy).then_some(lower)
}

/// A few Newton steps on `|P(u) − q|²` from the best point, kept only where they lower the
/// distance (they sharpen the answer below the accuracy; the bound does not rely on them).
fn polish<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, q: P, best: &mut Best<P>, lo: f64, hi: f64) {
    let mut u = best.u;
    for _ in 0..8 {
        let (p, d1, d2) = (curve.eval(u), curve.deriv(u), curve.deriv2(u));
        let r = p - q;
        let g = r.dot(d1);
        let hess = d1.dot(d1) + r.dot(d2);
        if !(hess > 0.0) {
            return;
        }
        let next = (u - g / hess).clamp(lo, hi);
        if !next.is_finite() || next == u {
            return;
        }
        u = next;
        best.offer(u, curve.eval(u), q);
    }
}
