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

use core::f64::consts::PI;

use crate::curve::{AnyCurve, Circle, CubicBezier, PiecewiseCubic};
use crate::vector::Vector;

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
fn valid_or(tolerance: f64, default: f64) -> f64 {
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
        AnyCurve::Piecewise(c) => {
            let segments = c.segments().len().max(1);
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
fn angle_between<P: Vector>(a: P, b: P) -> f64 {
    a.cross3(b).length().atan2(a.dot(b))
}

// ---------------------------------------------------------------------------------------
// Distance mode

/// Number of cells of the certified density table.
const CELLS: usize = 8;

/// Width of a cell.
const CELL: f64 = 1.0 / CELLS as f64;

/// Half-width of a cell in `f32`, rounded up so that `[m − hw, m + hw]` covers the cell
/// around its `f32` middle `m`.
const HALF_CELL: f32 = (0.5 * CELL * (1.0 + 1.0 / 262_144.0)) as f32;

/// Chord ends per pass of the table march; plans with more chords take the long march.
const CHUNK: usize = 128;

/// `8 / (12·√3)`: the third-order term of the chord bound, in units of `h³/8`.
const THIRD_ORDER: f32 = 0.384_900_18;

/// `f32` unit roundoff.
const F32_ROUNDOFF: f64 = 1.0 / (1u64 << 24) as f64;

/// Share of the tolerance kept back for the relative rounding of the `f32` cell bounds.
const F32_SHARE: f64 = 1.0 / (1u64 << 17) as f64;

/// `2⁵²`: adding and subtracting it rounds an `f64` in `[0, 2⁵²)` to an integer.
const TWO_52: f64 = 4_503_599_627_370_496.0;

/// Bits of `1.0f32`.
const ONE_BITS: i32 = 0x3f80_0000;

/// Cell middles.
const MIDDLES: [f32; CELLS] = {
    let mut m = [0.0; CELLS];
    let mut j = 0;
    while j < CELLS {
        m[j] = ((j as f64 + 0.5) * CELL) as f32;
        j += 1;
    }
    m
};

/// How many chord ends the short walk reads ahead of the vertices it writes (see
/// [`ChordPlan::extend_map`]).
const AHEAD: usize = 4;

/// `0.0, 1.0, 2.0, …` (`AHEAD` past `CHUNK` for the short walk's look-ahead)
const COUNTS: [f64; CHUNK + AHEAD + 1] = {
    let mut k = [0.0; CHUNK + AHEAD + 1];
    let mut i = 0;
    while i < CHUNK + AHEAD + 1 {
        k[i] = i as f64;
        i += 1;
    }
    k
};

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

/// The power form `C′(0) = a`, `b`, `c` of `c` at unit scale (the largest coordinate
/// brought into `[1, 2)` by a power of two, which scales exactly) and `8·limit`, the scaled
/// tolerance less the rounding allowances; `None` for a point at the origin or a curve that
/// is not finite.
fn unit_scale<P: Vector>(c: &CubicBezier<P>, tolerance: f64) -> Option<(P, P, P, f64)> {
    let tolerance = valid_or(tolerance, DEFAULT_TOLERANCE);
    if !c.is_finite() {
        return None;
    }
    // the largest |coordinate|, as a tree of maxima
    let per_point = c.points().map(|p| (0..P::DIM).fold(0.0, |m, i| max64(m, p.component(i).abs())));
    let magnitude = max64(max64(per_point[0], per_point[1]), max64(per_point[2], per_point[3]));
    if !(magnitude > 0.0) {
        return None;
    }
    let biased = ((magnitude.to_bits() >> 52) as i64).clamp(1, 2045);
    let scale = f64::from_bits(((2046 - biased) as u64) << 52);
    let m = magnitude * scale;
    // the tolerance floor, and a ceiling far above the size of the curve
    let tol = (tolerance * scale).max(1e-12 * m).min(1e6);
    // rounding allowance: a relative share for the f32 bounds and a few ulps of the coordinates
    let limit = tol * (1.0 - F32_SHARE) - 1e-14 * m;
    let (p0, p1, p2, p3) = (c.p0 * scale, c.p1 * scale, c.p2 * scale, c.p3 * scale);
    let a = (p1 - p0) * 3.0;
    let b = (p2 - p1 * 2.0 + p0) * 3.0;
    let cc = p3 - p0 + (p1 - p2) * 3.0;
    Some((a, b, cc, 8.0 * limit))
}

#[inline(always)]
fn max32(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

#[inline(always)]
fn max64(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

#[inline(always)]
fn min32(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// `⌈x⌉` for `0 ≤ x < 2⁵²`, without a libm call (baseline x86-64 has no rounding instruction).
#[inline(always)]
fn ceil(x: f64) -> f64 {
    let r = (x + TWO_52) - TWO_52;
    if r < x { r + 1.0 } else { r }
}

/// `1.5·2⁵²`: an `f64` in `[2⁵², 2⁵³)`, where the spacing is 1, so adding it to an `x` in
/// `[−2⁵¹, 2⁵¹)` rounds `x` to an integer and leaves that integer in the low bits.
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// `⌊x⌋ + 1` as an integer for `0 ≤ x < 2⁵¹`, except that an integer `x` may give `x` instead
/// of `x + 1` (a tie of the rounding; where this is used, both are right: see
/// [`ChordPlan::build`]). Three instructions, no saturating conversion.
#[inline(always)]
fn floor_plus_one(x: f64) -> u64 {
    ((x - 0.5) + ROUNDER).to_bits().wrapping_sub(ROUNDER.to_bits()).wrapping_add(1)
}

/// An integer-valued `x` in `[0, 2⁵¹)` as a `u64`, without a saturating conversion.
#[inline(always)]
fn integer_to_u64(x: f64) -> u64 {
    (x + ROUNDER).to_bits().wrapping_sub(ROUNDER.to_bits())
}

/// Per-curve inputs of the cell bounds (`f32`, at unit scale) and their rounding allowances.
#[derive(Clone, Copy)]
struct CellInputs {
    /// `a = C′(0)`, `2b` and `c` per coordinate (2D: z is 0).
    a: [f32; 3],
    b2: [f32; 3],
    c: [f32; 3],
    /// `k2 = 6·b×c`, the leading coefficient of `Q` (2D: in z).
    k2: [f32; 3],
    /// `|k2| / 12`.
    k2n: f32,
    /// `hw·|Λ′|` with `Λ′ = 2·b×c`, plus the allowance of `|Λ|`.
    lhw: f32,
    /// Rounding allowances of the Bernstein coefficients of `|Q|`, of `|C′(m)|²`, of the
    /// speed coefficients, and of `c·C′(m)` (scaled by `3hw²`).
    eq: f32,
    es: f32,
    eg: f32,
    ecd: f32,
    /// `8·limit` and its reciprocal.
    e8: f32,
    ie8: f32,
    /// `max|C″|` over `[0, 1]`, `|c|`, and Wang's density `√(max|C″| / (8·limit))`.
    dd: f32,
    cn: f32,
    wang: f32,
    /// 2 or 3.
    dim: usize,
}

impl CellInputs {
    /// Inputs for cells of half-width `hw` of the cubic with power form `a`, `b`, `c`
    /// (at unit scale).
    ///
    /// The allowances bound the `f32` rounding of [`densities`](Self::densities): with `D`,
    /// `E`, `Cm` bounds of the coordinates of `C′(m)`, `C″(m)` and `c` on `[0, 1]`, each
    /// coordinate of the computed `C′(m)` is within `5u·D` of the exact one (`u` the `f32`
    /// roundoff), and the products that follow add a few `u` times the product of the
    /// magnitudes; the constants (16 to 48) cover them with room, for 2D and 3D.
    #[inline(always)]
    fn new<P: Vector>(a: P, b: P, c: P, e8: f64, hw: f64) -> Self {
        let (a3, b3, c3) = (a.to_dvec3(), b.to_dvec3(), c.to_dvec3());
        let (aa, ba, ca) = (a3.abs(), b3.abs(), c3.abs());
        // largest coordinates (plain comparisons: the curve is finite)
        let max_element = |v: glam::DVec3| max64(max64(v.x, v.y), v.z);
        let dm = max_element(aa + ba * 2.0 + ca * 3.0);
        let em = max_element(ba * 2.0 + ca * 6.0);
        let cm = max_element(ca);
        let bc = b3.cross(c3);
        let bcn = if P::DIM == 2 { bc.z.abs() } else { bc.length() };
        let u = F32_ROUNDOFF;
        let el = 32.0 * u * dm * cm;
        let eg = 32.0 * u * (dm * dm + hw * dm * em + 3.0 * hw * hw * dm * cm);
        let dd = max64((b * 2.0).length_squared(), (b * 2.0 + c * 6.0).length_squared()).sqrt();
        let f = |v: glam::DVec3| [v.x as f32, v.y as f32, v.z as f32];
        Self {
            a: f(a3),
            b2: f(b3 * 2.0),
            c: f(c3),
            k2: f(bc * 6.0),
            k2n: (bcn / 2.0) as f32,
            lhw: (2.0 * bcn * hw + el) as f32,
            eq: (48.0 * u * (dm * em + 6.0 * hw * dm * cm) + 24.0 * u * hw * hw * bcn) as f32,
            es: (16.0 * u * dm * dm) as f32,
            eg: eg as f32,
            ecd: (3.0 * hw * hw * eg) as f32,
            e8: e8 as f32,
            ie8: (1.0 / e8) as f32,
            dd: dd as f32,
            cn: c.length() as f32,
            wang: (dd / e8).sqrt() as f32,
            dim: P::DIM,
        }
    }

    /// For each middle `m`: a density `ρ ≥ 1` (chords per unit of `t`) such that every
    /// chord with its midpoint in `[m − hw, m + hw]` and a width of at most `1/ρ` is within
    /// the tolerance (the module docs explain why); Wang's density where the chord lemma
    /// does not apply.
    #[inline(always)]
    fn densities(&self, mid: &[f32; CELLS], hw: f32, out: &mut [f32; CELLS]) {
        let hw2 = hw * hw;
        // (c·C′(m))⁻/4 from cd = 3hw²·c·C′(m), rounded up
        let icd = (1.0 + 1.0 / 65536.0) / (12.0 * hw2);
        // one loop over the cells, which the compiler turns into SIMD instructions
        for j in 0..CELLS {
            out[j] = self.cell(mid[j], hw, hw2, icd);
        }
    }

    /// The density of the cell around `m` (see [`densities`](Self::densities)).
    #[inline(always)]
    fn cell(&self, m: f32, hw: f32, hw2: f32, icd: f32) -> f32 {
        // C′(m)·C′(m), C″(m)·C′(m), c·C′(m), and the Bernstein coefficients over the
        // cell of Q = C′×C″ (norms), and |Λ(m)| = |C′(m)×c|
        let (ss, de, dc, n0, n1, n2, lam);
        if self.dim == 2 {
            let dx = self.a[0] + m * (self.b2[0] + (3.0 * m) * self.c[0]);
            let dy = self.a[1] + m * (self.b2[1] + (3.0 * m) * self.c[1]);
            let ex = self.b2[0] + (6.0 * m) * self.c[0];
            let ey = self.b2[1] + (6.0 * m) * self.c[1];
            ss = dx * dx + dy * dy;
            de = dx * ex + dy * ey;
            dc = dx * self.c[0] + dy * self.c[1];
            let q = dx * ey - dy * ex;
            let l = dx * self.c[1] - dy * self.c[0];
            // Q(m ± hw) = Q(m) ± hw·Q′(m) + hw²·k2, Q′ = 6Λ
            let (qd, qq) = ((6.0 * hw) * l, hw2 * self.k2[2]);
            n0 = (q + qq - qd).abs();
            n1 = (q - qq).abs();
            n2 = (q + qq + qd).abs();
            lam = l.abs();
        } else {
            let mut d = [0.0f32; 3];
            let mut e = [0.0f32; 3];
            for k in 0..3 {
                d[k] = self.a[k] + m * (self.b2[k] + (3.0 * m) * self.c[k]);
                e[k] = self.b2[k] + (6.0 * m) * self.c[k];
            }
            ss = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            de = d[0] * e[0] + d[1] * e[1] + d[2] * e[2];
            dc = d[0] * self.c[0] + d[1] * self.c[1] + d[2] * self.c[2];
            let cross = |u: [f32; 3], v: [f32; 3]| {
                [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            };
            let (q, l) = (cross(d, e), cross(d, self.c));
            let (mut s0, mut s1, mut s2, mut sl) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
            for k in 0..3 {
                let (qd, qq) = ((6.0 * hw) * l[k], hw2 * self.k2[k]);
                let (v0, v1, v2) = (q[k] + qq - qd, q[k] - qq, q[k] + qq + qd);
                s0 += v0 * v0;
                s1 += v1 * v1;
                s2 += v2 * v2;
                sl += l[k] * l[k];
            }
            n0 = s0.sqrt();
            n1 = s1.sqrt();
            n2 = s2.sqrt();
            lam = sl.sqrt();
        }
        // Bernstein coefficients over the cell of C′(t)·C′(m), less their allowance
        let g = hw * de;
        let cd = (3.0 * hw2) * dc;
        let base = ss + cd - self.eg;
        let (g0, g1, g2) = (base - g, ss - cd - self.eg, base + g);
        // |C′(m)|², rounded up
        let sse = ss + self.es;
        // cap: at least every width the cell can certify — the leading-order width of the
        // largest |Q| coefficient with the largest speed coefficient, √(e8·g/n)·(ss + es)^(−1/4),
        // from the exponent bits (0 to 15 % above it) — so the higher-order terms only grow.
        // (Wrapping: a cell with a negative speed coefficient fails below, whatever the cap.)
        let eb = (self.e8 * max32(max32(g0, g1), g2)).to_bits() as i32;
        let nb = (max32(max32(n0, n1), n2) + self.eq).to_bits() as i32;
        let sb = sse.to_bits() as i32;
        let cb =
            (eb.wrapping_sub(nb) >> 1).wrapping_sub(sb.wrapping_sub(ONE_BITS) >> 2).wrapping_add(ONE_BITS + 369_099);
        let cap = min32(f32::from_bits(cb as u32), 1.0);
        let cap2 = cap * cap;
        // (A): the terms |k2|·h²/12 and h·|Λ|·8/(12√3) join |Q|, (h²/4)·(c·û)⁻ leaves the speed
        let add = self.k2n * cap2 + THIRD_ORDER * cap * (lam + self.lhw) + self.eq;
        let drop = max32(self.ecd - cd, 0.0) * icd * cap2;
        let (a0, a1, a2) = (g0 - drop, g1 - drop, g2 - drop);
        let (n0, n1, n2) = (n0 + add, n1 + add, n2 + add);
        // the largest ratio nᵢ/aᵢ (all aᵢ > 0 where it counts: gmin > 0); three independent
        // divisions, so that the chain from the coefficients to the density stays short; the
        // least aᵢ is the least gᵢ less the drop, to the bit (rounding is monotonic), one
        // subtraction after the drop instead of a subtraction and two minima
        let gmin = min32(min32(g0, g1), g2) - drop;
        let ratio = max32(max32(n0 / a0, n1 / a1), n2 / a2);
        let s = sse.sqrt();
        let lemma = (s * self.ie8 * ratio).sqrt();
        // (B): with R = 2·gmin/|C′(m)| (gmin is a lower bound for every width up to the cap),
        // h·(max|C″| + h·|c|) ≤ R holds for every width h up to the root hb of the
        // quadratic, and 1/hb ≤ max|C″|/R + √(|c|/R); the chord lemma needs the smaller of
        // its own width and hb, so the larger density.
        let ir = (0.5 * s) / gmin;
        let ib = self.dd * ir + (self.cn * ir).sqrt();
        // 2⁻¹³ on the density (2⁻¹² on its square) covers the rounding of the divisions, the
        // square roots and (B); a NaN lemma density (ib first) falls back to Wang's
        let x = max32(ib, lemma) * (1.0 + 1.0 / 8192.0);
        // x < wang ? x : wang, and Wang's density where gmin ≤ 0 by making x a NaN there (all
        // bits set: the mask is ready long before x, so one `or` instead of a compare and a
        // blend follows x)
        let nan = if gmin > 0.0 { 0 } else { u32::MAX };
        let x = min32(f32::from_bits(x.to_bits() | nan), self.wang);
        max32(x, 1.0)
    }
}

/// Where the chords of one cubic end: chord end `k` (of `n`) lies in cell `j` and is at
/// `t = max(start_j, a_j + k·b_j)` (the maximum is the pause at the cell's start).
struct ChordPlan {
    a: [f64; 16],
    b: [f64; 16],
    start: [f64; 16],
    /// The first chord end of each cell.
    first: [u64; 16],
    /// `inc[k − 1]`: 8 × the number of cells whose first chord end is `k` (short plans only):
    /// the step of the walk's byte offset into the `f64` tables (see [`ChordPlan::end`]).
    inc: [u8; CHUNK + AHEAD],
    n: u64,
    /// At most `CHUNK` chords, and no pause long enough to repeat a chord end.
    short: bool,
}

impl ChordPlan {
    /// The certified plan of `c` (see the module docs).
    #[inline(never)]
    fn new<P: Vector>(c: &CubicBezier<P>, tolerance: f64) -> Self {
        let Some((a, b, cc, e8)) = unit_scale(c, tolerance) else {
            return Self::place(&[0.0; CELLS]);
        };
        let mut rho = [0.0f32; CELLS];
        CellInputs::new(a, b, cc, e8, f64::from(HALF_CELL)).densities(&MIDDLES, HALF_CELL, &mut rho);
        Self::place(&rho)
    }

    /// The plan for the densities `rho` of the cells (each certifying the chords with their
    /// midpoint in the cell; all 0 for a single chord): on the 8 cells, or on 4 cells of
    /// two or on one cell (taking the largest density of the cells in it, which lowers the
    /// floor of a chord per cell width) when that takes fewer chords.
    #[inline(always)]
    fn place(rho: &[f32; CELLS]) -> Self {
        if rho[0] == 0.0 {
            return Self::build(&[1.0]);
        }
        let fine: [f64; CELLS] = core::array::from_fn(|j| f64::from(rho[j]));
        // the count of the 8 cells without the pauses, a lower bound of theirs
        let mut base = 0.0;
        for &x in &fine {
            base += x.max(CELLS as f64);
        }
        if base < (2 * CELLS * CELLS) as f64 {
            let n_fine = Self::total(&fine);
            if n_fine < (2 * CELLS) as f64 {
                // nearly straight somewhere, or a coarse tolerance: the floor of a chord per
                // cell width costs more than it saves, so try chords across cells
                const GROUP: usize = CELLS / 4;
                const _: () = assert!(CELLS.is_multiple_of(4));
                let coarse: [f64; 4] =
                    core::array::from_fn(|i| fine[GROUP * i..GROUP * (i + 1)].iter().fold(0.0, |m, &x| max64(m, x)));
                let n_coarse = Self::total(&coarse);
                if let Some(greedy) = Self::greedy(&fine, n_coarse.min(n_fine) as u64) {
                    return greedy;
                }
                if n_coarse < n_fine {
                    return Self::build(&coarse);
                }
            }
        }
        Self::build(&fine)
    }

    /// The fewest chords (if fewer than `limit`, and at most 16) each as wide as the smallest
    /// `1/ρ` of the cells it overlaps, placed from the start: such a chord has its midpoint in
    /// one of those cells, so that cell certifies it. Going as far as allowed from each end is
    /// optimal, as a chord that is allowed stays allowed when its start moves forward.
    #[inline(always)]
    fn greedy(rho: &[f64; CELLS], limit: u64) -> Option<Self> {
        let limit = limit.min(17) as usize;
        let mut width = [0.0f64; CELLS];
        for j in 0..CELLS {
            width[j] = 1.0 / rho[j];
        }
        let mut ends = [0.0f64; 17];
        let (mut t, mut j, mut n) = (0.0f64, 0usize, 0usize);
        loop {
            let mut w = width[j];
            let mut k = j + 1;
            while k < CELLS && (k as f64) * CELL < t + w {
                w = w.min(width[k]);
                k += 1;
            }
            n += 1;
            if n >= limit {
                return None;
            }
            if t + w >= 1.0 {
                break;
            }
            t += w;
            ends[n] = t;
            // the cell the next chord starts in (a chord starting on a boundary overlaps only
            // the cells after it)
            while j + 1 < CELLS && ((j + 1) as f64) * CELL <= t {
                j += 1;
            }
        }
        let mut plan = Self::empty();
        plan.n = n as u64;
        plan.a[1..n].copy_from_slice(&ends[1..n]);
        plan.inc[..n - 1].fill(8);
        Some(plan)
    }

    /// A plan of one chord, to be filled in.
    #[inline(always)]
    fn empty() -> Self {
        Self {
            a: [0.0; 16],
            b: [0.0; 16],
            start: [0.0; 16],
            first: [u64::MAX; 16],
            inc: [0; CHUNK + AHEAD],
            n: 1,
            short: true,
        }
    }

    /// The cells' count `Σ w·max(ρ, 1/w)` plus the pauses, rounded up.
    #[inline(always)]
    fn total<const N: usize>(rho: &[f64; N]) -> f64 {
        let (w, floor) = (1.0 / N as f64, N as f64);
        let r: [f64; N] = core::array::from_fn(|j| rho[j].max(floor));
        let mut total = 0.0;
        for &x in &r {
            total += w * x;
        }
        for j in 1..N {
            total += (r[j - 1] - r[j]).abs() / (r[j - 1] + r[j]);
        }
        ceil(total)
    }

    /// The plan on `N` equal cells with densities `rho` (raised to at least `N`, a chord per
    /// cell width), chords at equal steps of the count with a pause before each cell.
    #[inline(always)]
    fn build<const N: usize>(rho: &[f64; N]) -> Self {
        let mut plan = Self::empty();
        let w = 1.0 / N as f64;
        let mut r = [0.0f64; N];
        let mut h = [0.0f64; N];
        for j in 0..N {
            r[j] = rho[j].max(N as f64);
            h[j] = 1.0 / r[j];
        }
        // the pause before cell j: (ρd − ρs)/(ρd + ρs), rounded up
        // (the density before cell 0 is taken as its own: no pause)
        let before: [f64; N] = core::array::from_fn(|j| r[j.saturating_sub(1)]);
        let mut pause = [0.0f64; N];
        let mut len = [0.0f64; N];
        for j in 0..N {
            pause[j] = (before[j] - r[j]).abs() / (before[j] + r[j]) * (1.0 + 1.0 / 262_144.0);
            len[j] = pause[j] + w * r[j];
        }
        // cumulative counts at the cell starts (two halves summed side by side, then joined)
        let mut cum = [0.0f64; N];
        let total = if N.is_multiple_of(2) {
            let half = N / 2;
            let (mut s0, mut s1) = (0.0, 0.0);
            for i in 0..half {
                cum[i] = s0;
                cum[half + i] = s1;
                s0 += len[i];
                s1 += len[half + i];
            }
            for i in 0..half {
                cum[half + i] += s0;
            }
            s0 + s1
        } else {
            let mut s = 0.0;
            for j in 0..N {
                cum[j] = s;
                s += len[j];
            }
            s
        };
        // chord ends at the counts 1, 2, …, n − 1 (the last chord, up to the count `total`,
        // is the shortest): no division by n on the way to the first chord end
        let nf = ceil(total);
        let mut repeat = false;
        // a chord end whose count falls exactly on a cell's start may be given to either
        // cell (`floor_plus_one`): both give that start, to rounding
        for j in 0..N {
            plan.start[j] = j as f64 * w;
            plan.b[j] = h[j];
            plan.a[j] = plan.start[j] - (cum[j] + pause[j]) * h[j];
            plan.first[j] = floor_plus_one(cum[j]);
            repeat |= pause[j] >= 1.0;
        }
        plan.n = integer_to_u64(nf);
        plan.short = plan.n <= CHUNK as u64 && !repeat;
        if plan.short {
            for j in 1..N {
                plan.inc[(plan.first[j] - 1) as usize & (CHUNK - 1)] += 8;
            }
        }
        plan
    }

    /// Calls `emit(t)` for every chord end before the last (`t = 1`), ascending.
    #[inline(always)]
    fn for_each_inner(&self, emit: &mut impl FnMut(f64)) {
        if self.short {
            self.short_ends().for_each(emit);
        } else {
            let mut buf = [0.0f64; CHUNK];
            let (mut base, mut j8, mut prev) = (1u64, 0usize, 0.0f64);
            while base < self.n {
                let len = self.chunk(&mut base, &mut j8, &mut prev, &mut buf);
                for &t in &buf[..len] {
                    emit(t);
                }
            }
        }
    }

    /// The chord ends from `base` on (at most `CHUNK` of them) of a long plan, leaving out
    /// any that a pause repeats.
    #[inline(always)]
    fn chunk(&self, base: &mut u64, j8: &mut usize, prev: &mut f64, buf: &mut [f64; CHUNK]) -> usize {
        let count = (self.n - *base).min(CHUNK as u64) as usize;
        let mut inc = [0u8; CHUNK + 1];
        for &f in &self.first[1..] {
            inc[f.wrapping_sub(*base).min(CHUNK as u64) as usize] += 8;
        }
        let bf = *base as f64;
        let mut len = 0;
        for (i, &d) in inc[..count].iter().enumerate() {
            let t = self.end(j8, bf + COUNTS[i], d);
            buf[len] = t;
            len += usize::from(t > *prev);
            *prev = if t > *prev { t } else { *prev };
        }
        *base += count as u64;
        len
    }

    /// The chord ends of a short plan before the last, one step of the walk each: slices
    /// zipped and mapped, an exact length, so that `Vec::extend` writes them in place.
    #[inline(always)]
    fn short_ends(&self) -> impl Iterator<Item = f64> + '_ {
        let mut j8 = 0usize;
        COUNTS[1..self.n as usize].iter().zip(&self.inc).map(move |(&k, &d)| self.end(&mut j8, k, d))
    }

    /// Chord end `k` of the walk over the cells: `j8` is the current cell's byte offset into
    /// the `f64` tables (8 × its index, which the compiler folds into the addressing: no
    /// shift), stepped by `d` (from `inc`) before the end is read from the cell's line.
    #[inline(always)]
    fn end(&self, j8: &mut usize, k: f64, d: u8) -> f64 {
        *j8 = (*j8 + d as usize) & 0x78;
        let j = *j8 >> 3;
        let t = self.a[j] + k * self.b[j];
        if t > self.start[j] { t } else { self.start[j] }
    }

    /// Appends the chord ends to `out`, the last `1.0`.
    ///
    /// Without the look-ahead of [`extend_map`](Self::extend_map): storing a chord end waits for
    /// nothing but the end itself, and the rotation of the read-ahead ends would only add
    /// instructions (parameters 230 against 216 µs a pass on the flatten bench's curves).
    #[inline(always)]
    fn extend(&self, out: &mut Vec<f64>) {
        if self.short {
            out.extend(self.short_ends());
            out.push(1.0);
        } else {
            self.extend_map(out, |t| t, 1.0);
        }
    }

    /// Appends `f(t)` for every chord end before the last to `out`, then `last`.
    #[inline(always)]
    fn extend_map<T>(&self, out: &mut Vec<T>, f: impl Fn(f64) -> T, last: T) {
        if self.short {
            let n = self.n as usize;
            out.reserve(n);
            // Each chord end is read from the table `AHEAD` steps before `f` takes it, so that
            // the walk runs ahead instead of every evaluation waiting for its own loads (the
            // last steps read past the plan's ends, which is harmless; the state moves into the
            // closure, which keeps it in registers). 2, 3, 4 and 6 steps ahead: polylines 283,
            // 279, 273 and 281 µs a pass on the flatten bench's curves, 296 µs with none.
            let mut j8 = 0usize;
            let [mut t0, mut t1, mut t2, mut t3]: [f64; AHEAD] =
                core::array::from_fn(|i| self.end(&mut j8, COUNTS[i + 1], self.inc[i]));
            // slices zipped and mapped: an exact length, so `extend` writes in place
            let (counts, incs) = (&COUNTS[AHEAD + 1..n + AHEAD], &self.inc[AHEAD..n + AHEAD - 1]);
            out.extend(counts.iter().zip(incs).map(move |(&k, &d)| {
                let next = self.end(&mut j8, k, d);
                let value = f(t0);
                (t0, t1, t2, t3) = (t1, t2, t3, next);
                value
            }));
        } else {
            out.reserve(self.n as usize);
            self.for_each_inner(&mut |t| out.push(f(t)));
        }
        out.push(last);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    fn cubic(p: [(f64, f64); 4]) -> CubicBezier<DVec2> {
        let v = |(x, y): (f64, f64)| DVec2::new(x, y);
        CubicBezier::new(v(p[0]), v(p[1]), v(p[2]), v(p[3]))
    }

    /// Distance from `x` to the segment `[a, b]`.
    fn seg_dist(x: DVec2, a: DVec2, b: DVec2) -> f64 {
        let e = b - a;
        let l2 = e.length_squared();
        let s = if l2 > 0.0 { ((x - a).dot(e) / l2).clamp(0.0, 1.0) } else { 0.0 };
        (a + e * s).distance(x)
    }

    /// Dense-sampled max distance from the sub-curve over [ta, tb] to its chord segment.
    fn sampled_chord_dev(c: &CubicBezier<DVec2>, ta: f64, tb: f64) -> f64 {
        let (a, b) = (c.eval(ta), c.eval(tb));
        (0..=2000).map(|i| seg_dist(c.eval(ta + (tb - ta) * i as f64 / 2000.0), a, b)).fold(0.0, f64::max)
    }

    /// splitmix64 in [0, 100).
    fn rng(state: &mut u64) -> f64 {
        *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 * 100.0
    }

    fn random_cubic(state: &mut u64) -> CubicBezier<DVec2> {
        let mut p = || DVec2::new(rng(state), rng(state));
        CubicBezier::new(p(), p(), p(), p())
    }

    /// The chord lemma of the module docs, written out from the Bernstein form: the normal
    /// offset of the chord `[tm − h/2, tm + h/2]` is at most
    /// `((h²/8)·|Q(tm) − k2·h²/12| + h³/(12√3)·|Λ(tm)|) / |C′(tm) + (h²/4)·c|`.
    fn lemma_bound(c: &CubicBezier<DVec2>, tm: f64, h: f64) -> f64 {
        let cr = |u: DVec2, v: DVec2| u.x * v.y - u.y * v.x;
        let cc = c.p3 - c.p0 + (c.p1 - c.p2) * 3.0;
        let (d1, d2) = (c.deriv(tm), c.deriv2(tm));
        let q = cr(d1, d2) - h * h / 12.0 * 6.0 * cr((c.p2 - c.p1 * 2.0 + c.p0) * 3.0, cc);
        let v = d1 + cc * (h * h / 4.0);
        (h * h / 8.0 * q.abs() + h * h * h / (12.0 * 3f64.sqrt()) * cr(d1, cc).abs()) / v.length()
    }

    #[test]
    fn chord_lemma_bounds_and_matches_sampling() {
        let mut state = 7u64;
        for _ in 0..200 {
            let c = random_cubic(&mut state);
            for _ in 0..10 {
                let h = 0.002 + 0.2 * rng(&mut state) / 100.0;
                let tm = h / 2.0 + (1.0 - h) * rng(&mut state) / 100.0;
                let (ta, tb) = (tm - h / 2.0, tm + h / 2.0);
                let (pa, pb) = (c.eval(ta), c.eval(tb));
                let e = (pb - pa).normalize();
                // the normal offset of every sample is within the bound
                let normal = (0..=1000)
                    .map(|i| {
                        let d = c.eval(ta + h * i as f64 / 1000.0) - pa;
                        (d.x * e.y - d.y * e.x).abs()
                    })
                    .fold(0.0, f64::max);
                let bound = lemma_bound(&c, tm, h);
                assert!(normal <= bound * (1.0 + 1e-9) + 1e-12, "{c:?} tm {tm} h {h}: {normal} > {bound}");
                // and is nearly exact for short chords (the third-order term is small)
                if h < 0.02 && normal > 1e-6 {
                    assert!(bound <= normal * 1.2, "{c:?} tm {tm} h {h}: bound {bound} ≫ {normal}");
                }
            }
        }
    }

    /// The certified cell densities of `c` (chords per unit of t).
    fn densities(c: &CubicBezier<DVec2>, tol: f64) -> [f64; CELLS] {
        let (a, b, cc, e8) = unit_scale(c, tol).unwrap();
        let mut rho = [0.0f32; CELLS];
        CellInputs::new(a, b, cc, e8, f64::from(HALF_CELL)).densities(&MIDDLES, HALF_CELL, &mut rho);
        rho.map(f64::from)
    }

    fn test_cases(state: &mut u64) -> Vec<CubicBezier<DVec2>> {
        let mut cases: Vec<CubicBezier<DVec2>> = (0..100).map(|_| random_cubic(state)).collect();
        cases.push(cubic([(0.0, 0.0), (100.0, 50.0), (100.0, 50.0), (0.0, 0.0)]));
        cases.push(cubic([(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)]));
        cases.push(cubic([(0.0, 0.0), (30.0, 0.0), (70.0, 0.5), (100.0, 0.0)]));
        cases.push(cubic([(0.0, 0.0), (99.0, 0.0), (100.0, 1.0), (100.0, 100.0)]));
        cases.push(cubic([(0.0, 0.0), (3.0, 0.0), (-1.0, 0.0), (1.0, 0.0)]));
        cases
    }

    #[test]
    fn certified_densities_hold_for_any_chord() {
        // Any chord no wider than 1/ρ of the cell holding its midpoint is within the
        // tolerance — not only the chords the march picks.
        let mut state = 11u64;
        for c in &test_cases(&mut state) {
            for tol in [1.0, 0.1, 0.01, 1e-3] {
                for (j, r) in densities(c, tol).into_iter().enumerate() {
                    for i in 0..=4 {
                        // the cell is closed: its ends included
                        let tm = (j as f64 + i as f64 / 4.0) / CELLS as f64;
                        let h = (1.0 / r).min(2.0 * tm).min(2.0 * (1.0 - tm));
                        let dev = sampled_chord_dev(c, tm - h / 2.0, tm + h / 2.0);
                        assert!(dev <= tol, "{c:?} tol {tol} cell {j} tm {tm} h {h}: {dev}");
                    }
                }
            }
        }
    }

    #[test]
    fn densities_are_near_the_optimal_chord_length() {
        // A circle-like arc: the optimal chord deviates by exactly the tolerance; the
        // certified widths must not be much shorter.
        let c = cubic([(100.0, 0.0), (100.0, 55.228), (55.228, 100.0), (0.0, 100.0)]);
        let tol = 0.01;
        for (j, &r) in densities(&c, tol).iter().enumerate() {
            let tm = (j as f64 + 0.5) / CELLS as f64;
            let h = (1.0 / r).min(2.0 * tm).min(2.0 * (1.0 - tm));
            let dev = sampled_chord_dev(&c, tm - h / 2.0, tm + h / 2.0);
            assert!(dev > 0.8 * tol && dev <= tol, "cell {j}: {dev}");
        }
    }

    #[test]
    fn every_chord_is_certified_by_its_midpoint() {
        // The placement invariant behind the guarantee: every chord the plan emits is at
        // most 1/ρ wide for a cell holding its midpoint (either cell at a shared end). Covers
        // the four shapes of plan: 8, 4 or 1 equal-step cells, chords placed one by one
        // across cells, and long plans (more than CHUNK chords).
        let mut state = 5u64;
        let mut seen = [0usize; 5];
        for c in &test_cases(&mut state) {
            for tol in [10.0, 1.0, 0.3, 0.1, 0.03, 0.01, 1e-3, 1e-5] {
                let plan = ChordPlan::new(c, tol);
                let shape = if plan.n > 1 && plan.b[1] == 0.0 {
                    3
                } else if plan.first[1] == u64::MAX {
                    0
                } else {
                    usize::from((1.0 / plan.start[1]).round() as usize == CELLS) + 1
                };
                seen[shape] += 1;
                seen[4] += usize::from(plan.n > CHUNK as u64);
                let rho = densities(c, tol);
                let allowed = |cell: usize| 1.0 / rho[cell];
                let mut t = vec![0.0];
                plan.extend(&mut t);
                assert_eq!(*t.last().unwrap(), 1.0);
                for w in t.windows(2) {
                    assert!(w[1] > w[0], "{c:?} tol {tol}: not ascending at {}", w[0]);
                    let x = 0.5 * (w[0] + w[1]) * CELLS as f64;
                    let j = (x as usize).min(CELLS - 1);
                    let mut max = allowed(j);
                    if x.fract() < 1e-12 && j > 0 {
                        max = max.max(allowed(j - 1));
                    }
                    assert!(w[1] - w[0] <= max * (1.0 + 1e-12), "{c:?} tol {tol}: chord {w:?} wider than {max}");
                }
                // the sink variant emits the same parameters, and positions on the curve
                let mut u = vec![0.0];
                let mut with = vec![c.p0];
                flatten_cubic_distance_with(c, tol, &mut |t, p| {
                    assert!(p.distance(c.eval(t)) < 1e-9, "{t}");
                    u.push(t);
                    with.push(p);
                });
                assert_eq!(t, u);
                // and so does the polyline variant, the same positions
                let mut points = vec![c.p0];
                flatten_cubic_distance_points(c, tol, &mut points);
                assert_eq!(points, with);
            }
        }
        assert!(seen.iter().all(|&k| k > 0), "{seen:?}");
    }

    #[test]
    fn pauses_never_repeat_a_chord_end() {
        // With every density at least CELLS (a chord per cell width), a pause is always
        // shorter than the step: total ≥ ρd/CELLS, so step ≥ ρd/(ρd + CELLS) > (ρd − ρs)/(ρd + ρs).
        for dense in [13.0, 100.0, 1e4, 1e6] {
            for at in [0, CELLS / 2 - 1, CELLS - 1] {
                let mut rho = [CELLS as f64; CELLS];
                rho[at] = dense;
                let plan = ChordPlan::build(&rho);
                assert!(plan.short || plan.n > CHUNK as u64, "{dense} {at}");
            }
        }
        // Should a pause hold two chord ends (here forced by moving a cell's line back by
        // three steps), the long march leaves the repeats out, so the ends stay ascending.
        let mut rho = [CELLS as f64; CELLS];
        let at = CELLS - 2;
        rho[at] = 200.0;
        let mut plan = ChordPlan::build(&rho);
        assert!(plan.short);
        plan.a[at] -= 3.0 * plan.b[at];
        // the short march (one end per count, no check) shows the repeats
        let mut raw = vec![0.0];
        plan.extend(&mut raw);
        assert_eq!(raw.len() as u64, plan.n + 1);
        let mut distinct = raw.clone();
        distinct.dedup();
        assert!(distinct.len() + 2 <= raw.len(), "{raw:?}");
        plan.short = false;
        let mut t = vec![0.0];
        plan.extend(&mut t);
        assert_eq!(t, distinct);
        assert!(t.windows(2).all(|w| w[1] > w[0]), "{t:?}");
        assert_eq!(*t.last().unwrap(), 1.0);
        // a single chord for a point
        let mut t = Vec::new();
        ChordPlan::place(&[0.0; CELLS]).extend(&mut t);
        assert_eq!(t, vec![1.0]);
    }

    #[test]
    fn integer_conversions_without_saturation() {
        // ⌊x⌋ + 1, where an integer x may also give x
        let mut state = 9u64;
        let mut xs: Vec<f64> = vec![0.0, 1e-300, 0.25, 0.5, 0.75, 1.0, 2.5, 3.0, 127.0, 128.0, 1e9 + 0.5];
        xs.extend((0..2000).map(|_| rng(&mut state) * 1.3));
        xs.extend((1..60).flat_map(|k| {
            let k = k as f64;
            [k, k.next_down(), k.next_up()]
        }));
        xs.push(((1u64 << 51) - 1) as f64);
        for x in xs {
            let f = floor_plus_one(x);
            let exact = x.floor() as u64 + 1;
            assert!(f == exact || (x.fract() == 0.0 && f == exact - 1), "{x}: {f}");
        }
        for n in [0u64, 1, 2, 127, 128, 1 << 20, (1 << 51) - 1] {
            assert_eq!(integer_to_u64(n as f64), n);
        }
    }

    #[test]
    fn offset_params_keeps_strict_order_and_exact_ends() {
        let mut v = vec![0.0, 0.5, 1.0 - 1e-17, 1.0];
        offset_params(&mut v, 1, 5.0);
        assert_eq!(v, vec![0.0, 5.5, 6.0]);
    }

    #[test]
    fn polygon_angles() {
        let straight = cubic([(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)]);
        assert!(!polygon_turns_more_than(&straight, 1e-9));
        let point = cubic([(1.0, 1.0); 4]);
        assert!(!polygon_turns_more_than(&point, 0.0));
        // right angle at p1
        let corner = cubic([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (1.0, 2.0)]);
        assert!(polygon_turns_more_than(&corner, 1.5));
        assert!(!polygon_turns_more_than(&corner, 1.6));
        // p1 = p2: the right angle is shared, 45° at each
        let shared = cubic([(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (1.0, 1.0)]);
        assert!(polygon_turns_more_than(&shared, 0.78));
        assert!(!polygon_turns_more_than(&shared, 0.79));
        // fold-back with a zero middle edge
        let fold = cubic([(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (0.0, 0.0)]);
        assert!(polygon_turns_more_than(&fold, 3.0));
        // 3D works the same way
        let c3 = CubicBezier::new(DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Z, DVec3::X + DVec3::Z * 2.0);
        assert!(polygon_turns_more_than(&c3, 1.5));
    }

    #[test]
    fn degenerate_and_invalid_input() {
        let point = cubic([(2.0, 3.0); 4]);
        for tol in [1e-3, 0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300] {
            let mut out = Vec::new();
            flatten_cubic_distance(&point, tol, &mut out);
            assert_eq!(out, vec![1.0]);
        }
        // a control point that is not finite: one chord (the curve has no finite polyline)
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for k in 0..4 {
                let mut p = [(0.0, 0.0), (30.0, 80.0), (70.0, -20.0), (100.0, 0.0)];
                p[k].1 = bad;
                let mut out = Vec::new();
                flatten_cubic_distance(&cubic(p), 1e-3, &mut out);
                assert_eq!(out, vec![1.0], "{p:?}");
            }
        }
        // huge but finite coordinates are scaled, not refused
        let huge = cubic([(0.0, 0.0), (1e308, 1e308), (-1e308, 1e308), (1e308, 0.0)]);
        let mut out = Vec::new();
        flatten_cubic_distance(&huge, 1e305, &mut out);
        assert!(out.len() > 3 && out.windows(2).all(|w| w[0] < w[1]), "{out:?}");
        let line = cubic([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]);
        out.clear();
        flatten_cubic_distance(&line, 1e-9, &mut out);
        assert_eq!(out, vec![1.0]);
        // a straight cubic that doubles back on itself must not be one chord
        let back = cubic([(0.0, 0.0), (3.0, 0.0), (-1.0, 0.0), (1.0, 0.0)]);
        out.clear();
        flatten_cubic_distance(&back, 1e-3, &mut out);
        assert!(out.len() >= 3, "{out:?}");
    }
}
