//! Flattening of the kinds without a planner of their own: Bézier curves of any degree and
//! NURBS, through what every such curve gives: the bound of its second derivative over an
//! interval ([`ParamCurve::deriv2_bound`]) and the control polygon of its part over an
//! interval ([`Hull`]).
//!
//! - **Distance**: an interval of width `h` whose second derivative is at most `M` stays
//!   within `M·h²/8` of its chord (the error of linear interpolation), and every point of the
//!   chord within that of the curve's point at the same parameter; so halving each segment
//!   until `M·h²/8 ≤ tolerance` meets the tolerance in both directions (a two-sided
//!   Hausdorff bound, as the cubic planner's). Halving stops at the latest at the width where
//!   the whole segment's `M` meets it (the bound of a part can exceed its segment's), so a
//!   segment gives at most twice the pieces of that uniform width. The tolerance is raised to `4ε` of the
//!   curve's extent, below which the chords' own rounding is larger.
//! - **Angle**: halving while an exterior angle of the part's control polygon exceeds half
//!   the tolerance, at most [`MAX_ANGLE_DEPTH`] times, as for cubics.
//! - **Uniform**: `steps` equal parameter steps per segment.

use super::{
    DEFAULT_ANGLE_TOLERANCE, DEFAULT_TOLERANCE, MAX_ANGLE_DEPTH, MAX_STEPS, Tessellation, angle_between, valid_or,
};
use crate::curve::{BezierCurve, Nurbs, ParamCurve};
use crate::vector::Vector;

/// The deepest halving in the distance mode: 2⁴⁰ pieces of a segment is beyond any tolerance
/// above the rounding floor.
const MAX_DISTANCE_DEPTH: u32 = 40;

/// The control polygon of a curve's part over `[u0, u1]` (inside one segment), whose convex
/// hull holds that part.
pub(crate) trait Hull<P> {
    /// The polygon, first point at `u0`, last at `u1`.
    fn hull(&self, u0: f64, u1: f64) -> Vec<P>;
}

impl<P: Vector> Hull<P> for BezierCurve<P> {
    fn hull(&self, u0: f64, u1: f64) -> Vec<P> {
        self.segment(u0, u1).points().to_vec()
    }
}

impl<P: Vector> Hull<P> for Nurbs<P> {
    fn hull(&self, u0: f64, u1: f64) -> Vec<P> {
        self.part_polygon(u0, u1)
    }
}

/// The parameters of the polyline's vertices, in order, from 0 to `num_segments`.
pub(crate) fn flatten_general<P: Vector, C: ParamCurve<P> + Hull<P>>(curve: &C, mode: Tessellation) -> Vec<f64> {
    let m = curve.num_segments();
    let mut out = vec![0.0];
    match mode {
        Tessellation::Uniform { steps } => {
            let steps = steps.clamp(1, MAX_STEPS);
            for k in 0..m {
                out.extend((1..=steps).map(|i| k as f64 + i as f64 / steps as f64));
            }
        }
        Tessellation::Distance { tolerance } => {
            let tolerance = distance_tolerance(curve, tolerance);
            for k in 0..m {
                let (a, b) = (k as f64, (k + 1) as f64);
                // the segment's own bound meets the tolerance at this width: halving need not
                // (and, the bounds of parts being no smaller in general, must not) go finer
                let bound = curve.deriv2_bound(a, b);
                let enough = 1.0 / uniform_pieces(bound, tolerance);
                distance_split(curve, (a, b, bound), tolerance, enough, &mut out);
            }
        }
        Tessellation::Angle { tolerance } => {
            let half = 0.5 * valid_or(tolerance, DEFAULT_ANGLE_TOLERANCE);
            for k in 0..m {
                angle_split(curve, k as f64, (k + 1) as f64, half, 0, &mut out);
            }
        }
    }
    out
}

/// An upper bound of the number of points [`flatten_general`] gives: exact for uniform
/// steps; `2^MAX_ANGLE_DEPTH` per segment in the angle mode; in the distance mode, per
/// segment, twice the uniform count that the segment's own bound `M` needs
/// (`⌈√(M/(8·tolerance))⌉`), since halving stops by the time a piece is that narrow.
pub(crate) fn general_count<P: Vector, C: ParamCurve<P>>(curve: &C, mode: Tessellation) -> u64 {
    let m = curve.num_segments() as u64;
    let pieces = match mode {
        Tessellation::Uniform { steps } => m.saturating_mul(steps.clamp(1, MAX_STEPS) as u64),
        Tessellation::Angle { .. } => m.saturating_mul(1 << MAX_ANGLE_DEPTH),
        Tessellation::Distance { tolerance } => {
            let tolerance = distance_tolerance(curve, tolerance);
            (0..curve.num_segments()).fold(0u64, |n, k| {
                let uniform = uniform_pieces(curve.deriv2_bound(k as f64, (k + 1) as f64), tolerance);
                n.saturating_add((2.0 * uniform).min((1u64 << MAX_DISTANCE_DEPTH) as f64) as u64)
            })
        }
    };
    pieces.saturating_add(1)
}

/// The distance tolerance used: `tolerance` if finite and positive (else the default), at
/// least `4ε` of the curve's extent.
fn distance_tolerance<P: Vector, C: ParamCurve<P>>(curve: &C, tolerance: f64) -> f64 {
    let bb = curve.bounding_box();
    let extent = (0..P::DIM).fold(0.0_f64, |e, i| e.max(bb.min.component(i).abs()).max(bb.max.component(i).abs()));
    valid_or(tolerance, DEFAULT_TOLERANCE).max(4.0 * f64::EPSILON * extent)
}

/// The number of equal pieces of a unit segment whose second derivative is at most `bound`
/// that keeps each within `tolerance` of its chord (`M·h²/8 ≤ tolerance`), at least 1, at
/// most `2^MAX_DISTANCE_DEPTH` (also for an infinite or NaN bound).
fn uniform_pieces(bound: f64, tolerance: f64) -> f64 {
    let n = (bound / (8.0 * tolerance)).sqrt().ceil();
    if n.is_nan() { MAX_PIECES } else { n.clamp(1.0, MAX_PIECES) }
}

/// The most pieces the distance mode cuts a segment into.
const MAX_PIECES: f64 = (1u64 << MAX_DISTANCE_DEPTH) as f64;

/// Halves `[a, b]`, whose second derivative is at most `bound`, while that bound does not meet
/// the tolerance and it is wider than `enough` (at which width the segment's bound does).
fn distance_split<P: Vector, C: ParamCurve<P>>(
    curve: &C,
    (a, b, bound): (f64, f64, f64),
    tolerance: f64,
    enough: f64,
    out: &mut Vec<f64>,
) {
    let h = b - a;
    if h > enough && bound * h * h / 8.0 > tolerance {
        let mid = 0.5 * (a + b);
        distance_split(curve, (a, mid, curve.deriv2_bound(a, mid)), tolerance, enough, out);
        distance_split(curve, (mid, b, curve.deriv2_bound(mid, b)), tolerance, enough, out);
    } else {
        out.push(b);
    }
}

fn angle_split<P: Vector, C: Hull<P>>(curve: &C, a: f64, b: f64, half: f64, depth: u32, out: &mut Vec<f64>) {
    if depth < MAX_ANGLE_DEPTH && polygon_turns_more_than(&curve.hull(a, b), half) {
        let mid = 0.5 * (a + b);
        angle_split(curve, a, mid, half, depth + 1, out);
        angle_split(curve, mid, b, half, depth + 1, out);
    } else {
        out.push(b);
    }
}

/// Whether the polygon turns by more than `limit` radians at one of its corners (edges
/// shorter than 1e-12 of its length have no direction and are skipped).
fn polygon_turns_more_than<P: Vector>(points: &[P], limit: f64) -> bool {
    let total: f64 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    let mut edges = points.windows(2).map(|w| w[1] - w[0]).filter(|e| e.length() > 1e-12 * total);
    let Some(mut previous) = edges.next() else { return false };
    for edge in edges {
        if angle_between(previous, edge) > limit {
            return true;
        }
        previous = edge;
    }
    false
}
