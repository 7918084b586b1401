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
//! the whole curve (every interval not split has a larger lower bound). A local Newton step
//! from the best point only ever lowers the upper bound. No starting guess, so no local
//! minimum is mistaken for the global one.
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
struct Pending {
    lower: f64,
    u0: f64,
    u1: f64,
}

impl PartialEq for Pending {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Pending {}
impl PartialOrd for Pending {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Pending {
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
    // `ends` are the points at u0 and u1, already offered to `best`
    let push = |queue: &mut BinaryHeap<Pending>, best: &mut Best<P>, u0: f64, u1: f64, ends: (P, P)| {
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
        queue.push(Pending { lower, u0, u1 });
    };
    let segments = curve.num_segments().max(1);
    let mut previous = start;
    for k in 0..segments {
        let u0 = lo + (hi - lo) * (k as f64 / segments as f64);
        let u1 = if k + 1 == segments { hi } else { lo + (hi - lo) * ((k + 1) as f64 / segments as f64) };
        let end = curve.eval(u1);
        best.offer(u1, end, q);
        push(&mut queue, &mut best, u0, u1, (previous, end));
        previous = end;
    }
    let mut splits = 0;
    let mut proved = f64::NEG_INFINITY;
    while let Some(top) = queue.pop() {
        proved = top.lower;
        if top.lower >= best.distance - accuracy {
            break;
        }
        let mid = 0.5 * (top.u0 + top.u1);
        if splits == MAX_NEAREST_INTERVALS || !(mid > top.u0 && mid < top.u1) {
            // out of work, or an interval at the rounding of its parameter: keep its bound
            queue.push(top);
            break;
        }
        splits += 1;
        let (a, m, b) = (curve.eval(top.u0), curve.eval(mid), curve.eval(top.u1));
        best.offer(mid, m, q);
        push(&mut queue, &mut best, top.u0, mid, (a, m));
        push(&mut queue, &mut best, mid, top.u1, (m, b));
    }
    let proved = queue.peek().map_or(proved, |p| p.lower.min(proved)).min(best.distance);
    polish(curve, q, &mut best, lo, hi);
    let error = (best.distance - proved).max(0.0);
    Nearest { u: best.u, point: best.point, distance: best.distance, error, accuracy }
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
