//! Tessellation of curves into polylines: uniform steps, angle tolerance and distance tolerance.
//!
//! Every function here returns the *parameters* of the polyline's vertices, ascending, the
//! first at the start of the domain and the last at its end; evaluate the curve at them for
//! positions, tangents and frames. Three modes ([`Tessellation`]):
//!
//! 1. **Uniform steps** — the SWP meaning of `steps`: each segment gives `steps + 1`
//!    points at `t = i/steps`, joins are not repeated, so a curve of `m` segments gives
//!    `m·steps + 1` points. A circle of `steps` gives `steps + 1` points, `u = i/steps`,
//!    the last repeating the first position.
//! 2. **Angle tolerance** ε (radians) — each cubic segment is split at `t = ½` (De
//!    Casteljau) while either angle of its control polygon, at `p1` or at `p2`, turns by
//!    more than ε/2, down to [`MAX_ANGLE_DEPTH`] halvings. Only on-curve points are emitted.
//! 3. **Distance tolerance** — the polyline is within `tolerance` of the curve in both
//!    directions: the two-sided Hausdorff distance between the curve and the polyline is
//!    at most `tolerance`, on every input, cusps and curves that fold back included.
//!
//! # The distance guarantee
//!
//! Write a chord `[ta, tb]` of a cubic as `C(ta + s·h) = C(ta) + s·e + r(s)`, `s ∈ [0, 1]`,
//! `h = tb − ta`, `e = C(tb) − C(ta)`. If every curve point is within the tolerance of its
//! own chord *segment*, both directions of the Hausdorff distance follow:
//!
//! - curve → polyline directly;
//! - polyline → curve: the coordinate `α(s)` of the curve along the chord runs from 0 to
//!   `|e|`, so by the intermediate value theorem every chord point `x` has an `s` with
//!   `α(s) = x`, and that curve point is at distance `|normal part of r(s)|` from it.
//!
//! The chord lemma bounds that distance in closed form. `r(0) = r(1) = 0` and
//! `r″(s) = h²·C″(t)` is linear in `s` for a cubic, so with `tm` the chord's midpoint,
//! `Q(t) = C′×C″` (a quadratic), `Λ(t) = C′×c` (linear; `c = p3 − 3p2 + 3p1 − p0`) and
//! `V = e/h = C′(tm) + (h²/4)·c` (exact for cubics), the normal offset is at most
//!
//! ```text
//! ( (h²/8)·|Q(tm) − k2·h²/12| + h³/(12√3)·|Λ(tm)| ) / |V|        (A)
//! ```
//!
//! (`k2 = 6·b×c` is `Q`'s leading coefficient; the first term is exact for a parabola, the
//! second is third order), and the coordinate along the chord stays within `[0, |e|]` when
//! `2·|V| ≥ h·(|C″(tm)| + h·|c|)` (B), which fails only near cusps. Both conditions only
//! involve the midpoint `tm` and the width `h`, so they can be *certified ahead of time*:
//! `[0, 1]` is cut into 8 equal cells, and each cell gets a density `ρ_j` (chords per unit
//! of `t`) such that (A) ≤ tolerance and (B) hold for *every* chord with its midpoint in the
//! cell (ends included) and a width of at most `1/ρ_j`:
//!
//! - on the cell, `|Q(tm)|` is at most `Σ βᵢ·Nᵢ` and the speed `|V|·|C′(m)|` at least
//!   `Σ βᵢ·Gᵢ`, with `βᵢ(tm)` the quadratic Bernstein weights, `Nᵢ` the norms of `Q`'s
//!   Bernstein coefficients and `Gᵢ` those of `C′(t)·C′(m)` (`m` the cell's middle) less the
//!   `(h²/4)·c` term of `V`. Both are averages with the same weights, so
//!   `|Q|/|V| ≤ |C′(m)|·maxᵢ Nᵢ/Gᵢ`: the bound follows curvature and speed together
//!   instead of pairing the largest `|Q|` with the smallest speed;
//! - the higher-order terms of (A) and (B) are evaluated at a cap, an upper bound of every
//!   width the cell can certify (the leading-order width of the largest coefficients, from
//!   the exponent bits of the `f32` values, 0 to 15 % above it), so they only grow;
//! - (B) then holds for every width up to the root `hb` of `h·(max|C″| + h·|c|) = 2·gmin/|C′(m)|`
//!   (`gmin = minᵢ Gᵢ`), and the cell's width is the smaller of (A)'s and `hb` — near a slow
//!   end of the curve the chords get shorter there instead of the whole cell falling back;
//! - where some `Gᵢ` is not positive (near a cusp), and wherever it gives a
//!   lower density, Wang's bound `(h²/8)·max|C″| ≤ tolerance` — valid for any chord, cusps
//!   included — gives the density instead.
//!
//! The bounds are evaluated in `f32` (four cells per SIMD instruction on baseline x86-64)
//! from the power form of the curve scaled to unit size in `f64`. Every
//! quantity that can cancel gets an explicit rounding allowance (a multiple of the `f32`
//! roundoff times the magnitude of its terms, computed in `f64` from the coefficients), the
//! cells are widened by `2⁻¹⁸` to cover their `f32` middles, and `2⁻¹⁷` of the tolerance is
//! kept back for the relative rounding of the rest (about `2⁻²⁰`). No chord is ever emitted
//! unchecked, and no measurement is involved.
//!
//! # Placement
//!
//! Chords end at the counts `1, 2, …, n − 1` of the cumulative count `N(t) = ∫ρ dt`,
//! `n = ⌈N(1)⌉` chords in all (the last, up to `N(1)`, is the shortest), so a chord inside
//! one cell is at most `1/ρ_j` wide. Every cell is given at least one
//! chord's worth (`ρ_j ≥ 8`), so a chord spans at most two cells. A chord that crosses from
//! a sparser cell (density `ρs`) into a denser one (`ρd`) with its midpoint in the denser one
//! could be too wide by a factor of up to `1 + (ρd − ρs)/(ρd + ρs)`; to prevent it, the count
//! pauses at every cell boundary for `(ρd − ρs)/(ρd + ρs)` chords (the polyline makes no
//! progress in `t` there), which is exactly what such a chord can lack. The pause is always
//! shorter than a chord (the denser cell alone holds `ρd/8` chords), so no chord end repeats.
//! Where the floor of one chord per cell width costs more than it saves (nearly straight
//! curves, coarse tolerances: fewer than 16 chords), two other plans are tried and the one
//! with the fewest chords is kept: 4 cells of two, each with the largest density of the
//! cells in it; and chords placed one after the other, each as wide as the smallest `1/ρ` of
//! the cells it overlaps (so whichever cell holds its midpoint certifies it), which is the
//! fewest chords under that rule. A straight run gets a single chord. The chord ends come
//! from a table: per chord, a lookup, a multiply-add and a maximum, with no branch and no
//! division.
//!
//! # Near-optimal counts
//!
//! A short chord of a curve deviates from it by about `κ·ℓ²/8` (curvature κ, arc length
//! ℓ), the first term of (A); chords spread with that local density are optimal (R. Levien,
//! "Flattening quadratic Béziers", 2019, uses the same idea on parabolas). The cell
//! densities follow it up to its variation inside a cell. On random cubics at a tolerance
//! of 1 % of the size, the count is about 1.14× kurbo's (which does not guarantee the
//! tolerance) and 0.59× lyon's; the cost is a fixed set-up of 8 cells plus `O(n)` with
//! `n ∝ tolerance^-1/2`, and nothing is allocated besides the output.
//!
//! # Invalid input
//!
//! Nothing here panics. `steps = 0` is taken as 1 and `steps` above [`MAX_STEPS`] as
//! [`MAX_STEPS`]. A tolerance that is not finite and positive is replaced by the default
//! ([`DEFAULT_TOLERANCE`] for distances, [`DEFAULT_ANGLE_TOLERANCE`] for angles). A distance
//! tolerance below `1e-12 ×` the largest control-point coordinate (the accuracy of `f64`
//! evaluation itself) is raised to that floor.
//! A cubic with a control point that is not finite gives a single chord.

mod cells;
mod general;
mod plan;
#[cfg(test)]
mod tests;

use core::f64::consts::PI;

use crate::curve::{AnyCurve, Circle, CubicBezier, ParamCurve, PiecewiseCubic};
use crate::vector::Vector;
use plan::ChordPlan;

/// Default distance tolerance (length units) used in place of an invalid one.
pub const DEFAULT_TOLERANCE: f64 = 1e-3;

/// Default angle tolerance (radians, about 5.7°) used in place of an invalid one.
pub const DEFAULT_ANGLE_TOLERANCE: f64 = 0.1;

/// Largest number of uniform steps per segment; larger requests are clamped to it.
pub const MAX_STEPS: usize = 1 << 16;

/// Largest number of halvings of a cubic segment in angle mode (depth 10, so at
/// most 1024 chords per segment).
pub const MAX_ANGLE_DEPTH: u32 = 10;

/// Largest number of chords for a circle in angle mode (as for four cubic segments at the
/// maximum depth).
const MAX_CIRCLE_ANGLE_CHORDS: usize = 4 << MAX_ANGLE_DEPTH;

/// How a curve is turned into a polyline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tessellation {
    /// `steps` equal parameter steps per segment (`m·steps + 1` points for `m` segments).
    Uniform {
        /// Steps per segment (0 is taken as 1, at most [`MAX_STEPS`]).
        steps: usize,
    },
    /// Adaptive by control-polygon angle: split while a control-polygon angle turns by more
    /// than `tolerance / 2` radians, at most [`MAX_ANGLE_DEPTH`] times.
    Angle {
        /// Angle tolerance ε in radians.
        tolerance: f64,
    },
    /// Adaptive with a guaranteed two-sided Hausdorff distance of at most `tolerance`
    /// (length units) between the curve and the polyline.
    Distance {
        /// Distance tolerance in length units.
        tolerance: f64,
    },
}

/// `tolerance` if it is finite and positive, else `default`.
#[inline]
pub(super) fn valid_or(tolerance: f64, default: f64) -> f64 {
    if tolerance > 0.0 && tolerance.is_finite() { tolerance } else { default }
}

/// Parameters `u` of the polyline's vertices for a chain of cubics, ascending: the first
/// is 0, the last `num_segments`, joins between segments appear once.
///
/// See the [module docs](self) for the three modes and what each tolerance bounds.
///
/// ```
/// use glam::DVec2;
/// use splinekit::{BezierSpline, ParamCurve};
/// use splinekit::flatten::{Tessellation, flatten_params};
/// let pts = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 2.0), DVec2::new(3.0, 2.0), DVec2::new(4.0, 0.0)];
/// let curve = BezierSpline::new(&pts, false).unwrap().to_piecewise();
/// assert_eq!(flatten_params(&curve, Tessellation::Uniform { steps: 8 }).len(), 9);
/// let u = flatten_params(&curve, Tessellation::Distance { tolerance: 1e-3 });
/// assert_eq!((u[0], *u.last().unwrap()), (0.0, 1.0));
/// let polyline: Vec<DVec2> = u.iter().map(|&u| curve.eval(u)).collect(); // within 1e-3 of the curve
/// # assert!(polyline.len() > 2);
/// ```
#[must_use]
pub fn flatten_params<P: Vector>(curve: &PiecewiseCubic<P>, mode: Tessellation) -> Vec<f64> {
    let segments = curve.segments();
    let mut out = Vec::new();
    out.push(0.0);
    match mode {
        Tessellation::Uniform { steps } => {
            let steps = steps.clamp(1, MAX_STEPS);
            out.reserve(segments.len().saturating_mul(steps));
            // u = j/steps for j = k·steps + i: integer arithmetic, then one division (so
            // u is the correctly rounded value of k + i/steps, and joins are exact integers)
            for k in 0..segments.len() {
                for i in 1..steps {
                    out.push((k * steps + i) as f64 / steps as f64);
                }
                out.push((k + 1) as f64);
            }
        }
        Tessellation::Angle { tolerance } => {
            let half = 0.5 * valid_or(tolerance, DEFAULT_ANGLE_TOLERANCE);
            for (k, seg) in segments.iter().enumerate() {
                angle_split(seg, 0.0, 1.0, half, 0, k as f64, &mut out);
            }
        }
        Tessellation::Distance { tolerance } => {
            let tolerance = valid_or(tolerance, DEFAULT_TOLERANCE);
            for (k, seg) in segments.iter().enumerate() {
                let start = out.len();
                flatten_cubic_distance(seg, tolerance, &mut out);
                offset_params(&mut out, start, k as f64);
            }
        }
    }
    out
}

/// Adds `k` to the local parameters `out[start..]` and drops any that rounding made equal
/// to the previous one, so the sequence stays strictly ascending; the segment's end is
/// exactly `k + 1`.
fn offset_params(out: &mut Vec<f64>, start: usize, k: f64) {
    let mut w = start;
    for r in start..out.len() {
        let u = if out[r] >= 1.0 { k + 1.0 } else { k + out[r] };
        if w == 0 || u > out[w - 1] {
            out[w] = u;
            w += 1;
        } else if r + 1 == out.len() {
            out[w - 1] = u; // keep the exact segment end
        }
    }
    out.truncate(w);
}

/// Parameters of the polyline's vertices for any curve, ascending, from the domain start
/// to its end (see [`flatten_params`] for chains of cubics).
///
/// For a [`Circle`] (`u ∈ [0, 1]`, counter-clockwise from angle 0; every mode gives equal
/// steps `u = i/n`, the last point repeating the first):
/// - `Uniform { steps }`: `n = steps`;
/// - `Distance { tolerance }`: the smallest `n` whose sagitta `r·(1 − cos(π/n))` — the
///   exact Hausdorff distance between an arc and its chord — is within the tolerance;
/// - `Angle { tolerance }`: the smallest `n ≥ 3` with `2π/n ≤ ε` (consecutive chords turn by
///   at most ε), at most 4096 chords.
///
/// For a [`Helix`](crate::Helix) (`u ∈ [0, 1]`, angle `θ = 2π·turns·u`; a helix has constant
/// curvature, so every mode gives equal steps `u = i/n`):
/// - `Uniform { steps }`: `n = steps` (`steps + 1` points for the whole helix);
/// - `Distance { tolerance }`: the smallest `n` with Wang's chord bound
///   `(Δθ)²/8 · max|d²P/dθ²| = (Δθ)²·r/8` within the tolerance, `Δθ = 2π·|turns|/n`. The
///   bound holds both ways (two-sided Hausdorff) and exceeds the sagitta of the projected
///   circle `r·(1 − cos(Δθ/2))`, a lower bound of the chord's deviation, only by a factor
///   `1 + O(Δθ²)`, so `n` is near-optimal; it grows as `|turns|·√(r/tolerance)`;
/// - `Angle { tolerance }`: the smallest `n` (at least 3 per turn, at most 4096 per turn) for
///   which each chord makes an angle of at most ε/2 with the tangent at either end (computed
///   in closed form), so consecutive chords turn by at most ε. A straight or point-like helix
///   (`r = 0`) gives one chord.
///
/// For a [`Trefoil`](crate::Trefoil) (`u ∈ [0, 1]`, `t = 2πu`):
/// - `Uniform { steps }`: `steps + 1` points `u = i/steps`;
/// - `Distance { tolerance }`: chords from the start, each as wide as Wang's bound
///   `(h²/8)·max|C″| ≤ tolerance` allows with the maximum taken *over that chord* — exact, from
///   `|C″(t)|² = s²·(146 − 16c − 81c²)`, `c = cos 3t` (the global maximum is
///   [`Trefoil::max_deriv2`](crate::Trefoil::max_deriv2)). A guarantee both ways, with about
///   8 % fewer chords than equal steps for the global bound and within 10 % (2 % at a
///   tolerance of 1e-3 of the size) of the fewest chords any polyline with vertices on the knot
///   can have; the count grows as `tolerance^-1/2`;
/// - `Angle { tolerance }`: the four quarters of the knot, each halved while its chord makes an
///   angle of more than ε/2 with the tangent at either end, at most [`MAX_ANGLE_DEPTH`] times
///   (at most 4096 chords). A size of 0 gives the same parameters as size 1 (angles do not
///   depend on size) in angle mode, one chord in distance mode.
///
/// The tolerance rules of the [module docs](self) (invalid tolerances replaced, distances
/// raised to `1e-12 ×` the largest coordinate) apply to every curve. For the 2D projection
/// (`AnyCurve<DVec2>`), the same rules are applied to the projected curve.
#[must_use]
pub fn flatten_any<P: Vector>(curve: &AnyCurve<P>, mode: Tessellation) -> Vec<f64> {
    match curve {
        AnyCurve::Piecewise(c) => flatten_params(c, mode),
        AnyCurve::Circle(c) => {
            let n = circle_chords(c, mode);
            let mut out: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
            out.push(1.0);
            out
        }
        AnyCurve::Helix(h) => h.flatten_params::<P>(mode),
        AnyCurve::Trefoil(k) => k.flatten_params::<P>(mode),
        AnyCurve::Bezier(c) => general::flatten_general(c, mode),
        AnyCurve::Nurbs(c) => general::flatten_general(c, mode),
    }
}

/// An upper bound of the number of points [`flatten_any`] gives `curve` in `mode`, found without making
/// them (so a caller can refuse, or draw coarser, before allocating): exact for uniform steps,
/// circles and helices and in the distance mode of chains of cubics (each segment's chord
/// count is planned before its chords are placed); in the angle mode of cubics and for trefoil
/// knots an upper bound (the halving depth and the curvature bound). `u64::MAX` when it does
/// not fit.
#[must_use]
pub fn flatten_count<P: Vector>(curve: &AnyCurve<P>, mode: Tessellation) -> u64 {
    let plus_one = |n: u64| n.saturating_add(1);
    match curve {
        AnyCurve::Piecewise(c) => {
            let m = c.segments().len() as u64;
            match mode {
                Tessellation::Uniform { steps } => plus_one(m.saturating_mul(steps.clamp(1, MAX_STEPS) as u64)),
                Tessellation::Angle { .. } => plus_one(m.saturating_mul(1 << MAX_ANGLE_DEPTH)),
                Tessellation::Distance { tolerance } => {
                    let tolerance = valid_or(tolerance, DEFAULT_TOLERANCE);
                    plus_one(
                        c.segments().iter().fold(0u64, |n, seg| n.saturating_add(ChordPlan::new(seg, tolerance).n)),
                    )
                }
            }
        }
        AnyCurve::Circle(c) => plus_one(circle_chords(c, mode) as u64),
        AnyCurve::Helix(h) => plus_one(h.chord_count::<P>(mode)),
        AnyCurve::Trefoil(k) => k.point_bound::<P>(mode),
        AnyCurve::Bezier(c) => general::general_count(c, mode),
        AnyCurve::Nurbs(c) => general::general_count(c, mode),
    }
}

/// [`flatten_any`] in `mode` when that gives at most `max_points` points
/// ([`flatten_count`]); otherwise equal parameter steps, as many as fit `max_points` (at
/// least one per segment, at most [`MAX_STEPS`] each for chains of cubics; all of them for a
/// circle, helix or knot), and `mode`'s tolerance is not met.
/// For drawing, where a curve far finer than the picture must still come out in bounded time
/// and memory.
#[must_use]
pub fn flatten_at_most<P: Vector>(curve: &AnyCurve<P>, mode: Tessellation, max_points: usize) -> Vec<f64> {
    if flatten_count(curve, mode) <= max_points as u64 {
        return flatten_any(curve, mode);
    }
    let steps = max_points.saturating_sub(1).max(1);
    match curve {
        AnyCurve::Piecewise(_) | AnyCurve::Nurbs(_) => {
            let segments = curve.num_segments().max(1);
            flatten_any(curve, Tessellation::Uniform { steps: (steps / segments).clamp(1, MAX_STEPS) })
        }
        // one segment each, and equal steps of u are equal steps of angle (or of t): all of
        // `max_points`, not `MAX_STEPS` (a helix of 10 000 turns in 65 536 steps is a
        // polygon of 6.6 sides turning slowly, not a circle)
        _ => (0..=steps).map(|i| i as f64 / steps as f64).collect(),
    }
}

/// Number of equal chords for a circle in the given mode.
fn circle_chords(c: &Circle, mode: Tessellation) -> usize {
    match mode {
        Tessellation::Uniform { steps } => steps.clamp(1, MAX_STEPS),
        Tessellation::Angle { tolerance } => {
            let eps = valid_or(tolerance, DEFAULT_ANGLE_TOLERANCE);
            let n = (2.0 * PI / eps).ceil();
            if n >= MAX_CIRCLE_ANGLE_CHORDS as f64 { MAX_CIRCLE_ANGLE_CHORDS } else { (n as usize).max(3) }
        }
        Tessellation::Distance { tolerance } => {
            let r = c.radius;
            if !(r > 0.0 && r.is_finite()) {
                return 1;
            }
            let tol = valid_or(tolerance, DEFAULT_TOLERANCE).max(1e-12 * r);
            let limit = tol - 1e-14 * r;
            // sagitta of n chords: r·(1 − cos(π/n)) = 2r·sin²(π/2n)
            let sagitta = |n: f64| 2.0 * r * (0.5 * PI / n).sin().powi(2);
            let half_angle = (limit / (2.0 * r)).sqrt().min(1.0).asin(); // π/2n at the limit
            let mut n = (0.5 * PI / half_angle).ceil().max(1.0);
            while sagitta(n) > limit {
                n += 1.0;
            }
            while n > 1.0 && sagitta(n - 1.0) <= limit {
                n -= 1.0;
            }
            n as usize
        }
    }
}

// ---------------------------------------------------------------------------------------
// Angle mode

/// Appends the end parameters (offset by `k`) of the pieces of `c` over `[t0, t1]` in
/// order, splitting at the middle while a control-polygon angle exceeds `half`.
fn angle_split<P: Vector>(c: &CubicBezier<P>, t0: f64, t1: f64, half: f64, depth: u32, k: f64, out: &mut Vec<f64>) {
    if depth < MAX_ANGLE_DEPTH && polygon_turns_more_than(c, half) {
        let (l, r) = c.split(0.5);
        let tm = 0.5 * (t0 + t1);
        angle_split(&l, t0, tm, half, depth + 1, k, out);
        angle_split(&r, tm, t1, half, depth + 1, k, out);
    } else {
        out.push(k + t1);
    }
}

/// Whether the control polygon of `c` turns by more than `limit` radians at `p1` or at `p2`.
///
/// A zero-length edge (relative to the polygon's length) has no direction: a zero middle
/// edge takes the bisector of its neighbours (so the two angles split the turn between
/// them; opposite neighbours, a fold-back, count as a turn of π), a zero end edge takes the
/// middle edge's direction (no turn there). A polygon of one point does not turn.
pub(crate) fn polygon_turns_more_than<P: Vector>(c: &CubicBezier<P>, limit: f64) -> bool {
    let (d0, d1, d2) = (c.p1 - c.p0, c.p2 - c.p1, c.p3 - c.p2);
    let (l0, l1, l2) = (d0.length(), d1.length(), d2.length());
    let tiny = 1e-12 * (l0 + l1 + l2);
    let (z0, z1, z2) = (!(l0 > tiny), !(l1 > tiny), !(l2 > tiny));
    let mid = if !z1 {
        d1
    } else if !z0 && !z2 {
        let bisector = d0 * (1.0 / l0) + d2 * (1.0 / l2);
        if !(bisector.length() > 1e-12) {
            return PI > limit;
        }
        bisector
    } else if !z0 {
        d0
    } else if !z2 {
        d2
    } else {
        return false;
    };
    let first = if z0 { mid } else { d0 };
    let last = if z2 { mid } else { d2 };
    angle_between(first, mid) > limit || angle_between(mid, last) > limit
}

/// Angle between two non-zero vectors in `[0, π]`.
#[inline]
pub(super) fn angle_between<P: Vector>(a: P, b: P) -> f64 {
    a.cross3(b).length().atan2(a.dot(b))
}

// ---------------------------------------------------------------------------------------
// Distance mode (the certified densities are in cells.rs, the chord placement in plan.rs)

/// One cubic in distance mode: appends the parameters `t ∈ (0, 1]` of the polyline's
/// vertices after the start (`t = 0` is implied) to `out`, ascending, the last exactly 1.
///
/// The polyline through `c(0)` and `c(t)` for the appended `t` is within `tolerance` of the
/// curve in both directions (two-sided Hausdorff distance); see the [module docs](self) for
/// the method, why it is a bound, and how invalid tolerances are handled. A straight run (or
/// a point) gives the single chord `[1.0]`.
pub fn flatten_cubic_distance<P: Vector>(c: &CubicBezier<P>, tolerance: f64, out: &mut Vec<f64>) {
    ChordPlan::new(c, tolerance).extend(out);
}

/// Like [`flatten_cubic_distance`], but calls `sink(t, position)` for each vertex after the
/// start, in order (the last with `t = 1` and `position = c.p3`). Positions come from the
/// power form of the cubic and agree with [`CubicBezier::eval`] to rounding.
///
/// ```
/// use glam::DVec2;
/// use splinekit::CubicBezier;
/// use splinekit::flatten::flatten_cubic_distance_with;
/// let c = CubicBezier::new(DVec2::ZERO, DVec2::new(0.0, 1.0), DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0));
/// let mut polyline = vec![c.p0];
/// flatten_cubic_distance_with(&c, 1e-4, &mut |_t, p| polyline.push(p));
/// assert_eq!(*polyline.last().unwrap(), c.p3);
/// ```
#[inline]
pub fn flatten_cubic_distance_with<P: Vector>(c: &CubicBezier<P>, tolerance: f64, sink: &mut impl FnMut(f64, P)) {
    let plan = ChordPlan::new(c, tolerance);
    let position = power_form(c);
    plan.for_each_inner(&mut |t| sink(t, position(t)));
    sink(1.0, c.p3);
}

/// The position of `c` at `t` from its power form `p0 + (a + (b + c·t)·t)·t`, for the chord
/// ends (three multiply-adds a vertex; [`CubicBezier::eval`] takes more to hit its ends exactly,
/// which the chord ends here do not need: the last one is `p3` itself).
#[inline(always)]
fn power_form<P: Vector>(c: &CubicBezier<P>) -> impl Fn(f64) -> P + Copy {
    let p0 = c.p0;
    let a = (c.p1 - c.p0) * 3.0;
    let b = (c.p2 - c.p1 * 2.0 + c.p0) * 3.0;
    let cc = c.p3 - c.p0 + (c.p1 - c.p2) * 3.0;
    move |t| p0 + (a + (b + cc * t) * t) * t
}

/// Like [`flatten_cubic_distance`], but appends the polyline's vertices after the start
/// (`c.p0` is implied) to `out` as positions, the last exactly `c.p3`. Positions come from
/// the power form of the cubic and agree with [`CubicBezier::eval`] to rounding.
///
/// This is the fast way to collect a polyline: the vertex count is known before the first
/// one is computed, so the positions are written in place with no per-vertex check.
///
/// ```
/// use glam::DVec2;
/// use splinekit::CubicBezier;
/// use splinekit::flatten::flatten_cubic_distance_points;
/// let c = CubicBezier::new(DVec2::ZERO, DVec2::new(0.0, 1.0), DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0));
/// let mut polyline = vec![c.p0];
/// flatten_cubic_distance_points(&c, 1e-4, &mut polyline);
/// assert_eq!(*polyline.last().unwrap(), c.p3);
/// ```
pub fn flatten_cubic_distance_points<P: Vector>(c: &CubicBezier<P>, tolerance: f64, out: &mut Vec<P>) {
    ChordPlan::new(c, tolerance).extend_map(out, power_form(c), c.p3);
}
