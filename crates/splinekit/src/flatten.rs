//! Tessellation of curves into polylines (SPEC §1.3).
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
//! `[0, 1]` is cut into 16 cells, and on each cell rigorous bounds of `|Q|`, `|Λ|`, `|C″|`
//! and a lower bound of the speed `|C′|` (from `C′(t)·û` with `û` the unit tangent at the
//! cell's middle, exact to second order) give the largest width `h_j` for which (A) ≤
//! tolerance and (B) hold for *every* chord with its midpoint in the cell. Where that fails
//! (at a cusp), Wang's bound `(h²/8)·max|C″| ≤ tolerance` — valid for any chord, cusps
//! included — gives the width instead. The placement then only has to respect the widths:
//! no chord is ever emitted unchecked, and no measurement is involved.
//!
//! # Near-optimal counts
//!
//! A short chord of a curve deviates from it by about `κ·ℓ²/8` (curvature κ, arc length
//! ℓ), the first term of (A); chords spread with that local density are optimal (R. Levien,
//! "Flattening quadratic Béziers", 2019, uses the same idea on parabolas). The widths `h_j`
//! follow it up to the variation inside a cell. The polyline has `n = ⌈Σ w/h_j⌉` chords,
//! placed at equal steps of the cumulative count `∫ dt/h(t)`, so that a chord inside one
//! cell is never wider than `h_j`; a chord entering a narrower cell is checked against its
//! midpoint's width, shortened if needed, and the rest re-planned. On random cubics this is
//! within about 10% of the optimum; the cost is `O(n)` with `n ∝ tolerance^-1/2`, and
//! nothing is allocated besides the output.
//!
//! # Invalid input
//!
//! Nothing here panics. `steps = 0` is taken as 1 and `steps` above [`MAX_STEPS`] as
//! [`MAX_STEPS`]. A tolerance that is not finite and positive is replaced by the default
//! ([`DEFAULT_TOLERANCE`] for distances, [`DEFAULT_ANGLE_TOLERANCE`] for angles). A distance
//! tolerance below `1e-12 ×` the largest control-point coordinate (the accuracy of `f64`
//! evaluation itself) is raised to that floor.

use core::f64::consts::PI;

use crate::curve::{AnyCurve, Circle, CubicBezier, PiecewiseCubic};
use crate::vector::Vector;

/// Default distance tolerance (length units) used in place of an invalid one.
pub const DEFAULT_TOLERANCE: f64 = 1e-3;

/// Default angle tolerance (radians, about 5.7°) used in place of an invalid one.
pub const DEFAULT_ANGLE_TOLERANCE: f64 = 0.1;

/// Largest number of uniform steps per segment; larger requests are clamped to it.
pub const MAX_STEPS: usize = 1 << 16;

/// Largest number of halvings of a cubic segment in angle mode (SPEC §1.3: depth 10, so at
/// most 1024 chords per segment).
pub const MAX_ANGLE_DEPTH: u32 = 10;

/// Largest number of chords for a circle in angle mode (as for four cubic segments at the
/// maximum depth).
const MAX_CIRCLE_ANGLE_CHORDS: usize = 4 << MAX_ANGLE_DEPTH;

/// How a curve is turned into a polyline (SPEC §1.3).
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

/// Number of cells of the certified width table.
const CELLS: usize = 16;

/// `8 / (12·√3)`: the third-order term of the chord bound, in units of `h³/8`.
const THIRD_ORDER: f64 = 0.384_900_179_459_750_5;

/// One cubic in distance mode: appends the parameters `t ∈ (0, 1]` of the polyline's
/// vertices after the start (`t = 0` is implied) to `out`, ascending, the last exactly 1.
///
/// The polyline through `c(0)` and `c(t)` for the appended `t` is within `tolerance` of the
/// curve in both directions (two-sided Hausdorff distance); see the [module docs](self) for
/// the method, why it is a bound, and how invalid tolerances are handled. A straight run (or
/// a point) gives the single chord `[1.0]`.
pub fn flatten_cubic_distance<P: Vector>(c: &CubicBezier<P>, tolerance: f64, out: &mut Vec<f64>) {
    distance_params(c, tolerance, &mut |t| out.push(t));
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
pub fn flatten_cubic_distance_with<P: Vector>(c: &CubicBezier<P>, tolerance: f64, sink: &mut impl FnMut(f64, P)) {
    let a = (c.p1 - c.p0) * 3.0;
    let b = (c.p2 - c.p1 * 2.0 + c.p0) * 3.0;
    let cc = c.p3 - c.p0 + (c.p1 - c.p2) * 3.0;
    distance_params(c, tolerance, &mut |t| {
        let p = if t >= 1.0 { c.p3 } else { c.p0 + (a + (b + cc * t) * t) * t };
        sink(t, p);
    });
}

/// Validates the input, works at unit scale when the coordinates are extreme (a power of two
/// scales exactly), and runs the certified march.
fn distance_params<P: Vector>(c: &CubicBezier<P>, tolerance: f64, emit: &mut impl FnMut(f64)) {
    let tolerance = valid_or(tolerance, DEFAULT_TOLERANCE);
    if !c.is_finite() {
        emit(1.0);
        return;
    }
    let mut magnitude = 0.0f64;
    for p in c.points() {
        for i in 0..P::DIM {
            magnitude = magnitude.max(p.component(i).abs());
        }
    }
    let tol = tolerance.max(1e-12 * magnitude);
    if magnitude > 1e100 || (magnitude < 1e-100 && magnitude > 0.0) {
        let s = 2.0f64.powi(-(magnitude.log2().round() as i32));
        let scaled = CubicBezier::new(c.p0 * s, c.p1 * s, c.p2 * s, c.p3 * s);
        let plan = WidthTable::new(&scaled, (tol * s).min(f64::MAX), magnitude * s);
        plan.march(emit);
    } else {
        WidthTable::new(c, tol, magnitude).march(emit);
    }
}

/// Certified chord widths: a chord `[ta, tb]` whose midpoint lies in cell `j` (closed) is
/// within the tolerance of the curve whenever `tb − ta ≤ width[j]` (see the module docs).
struct WidthTable {
    /// `cum[j]`: number of chords of maximal width needed to cover cells `0..j`.
    cum: [f64; CELLS + 1],
    /// Certified chord width per cell.
    width: [f64; CELLS],
}

/// Per-curve constants of the width computation.
struct CellInputs {
    e8: f64,
    cn: f64,
    k2n: f64,
    rho_floor: f64,
}

impl CellInputs {
    /// `1 / width` of a cell from bounds over it: `qmax ≥ |Q(tm)|`, `lmax ≥ |Λ(tm)|`, and the
    /// speed lower bound `smin`; Wang's floor where the certificate does not apply.
    #[inline(always)]
    fn rho(&self, qmax: f64, lmax: f64, smin: f64, dd_max: f64) -> f64 {
        // leading-order width h0, then the full condition (A) with its higher-order terms
        // evaluated at h0 ≥ h (one safe step of a decreasing fixed-point map)
        let h02 = (self.e8 * smin / qmax).min(1.0);
        let num = self.e8 * (smin - 0.25 * h02 * self.cn);
        let den = qmax + self.k2n * h02 / 12.0 + THIRD_ORDER * h02.sqrt() * lmax;
        let rho2 = (den / num).max(1.0);
        let rho = rho2.sqrt();
        // (B) no overshoot, 2·smin − h²·|c|/2 ≥ h·(max|C″| + h·|c|), times ρ² = 1/h²
        let no_overshoot = 2.0 * smin * rho2 >= rho * dd_max + 1.5 * self.cn;
        if num > 0.0 && smin > 0.0 && no_overshoot { rho.min(self.rho_floor) } else { self.rho_floor }
    }
}

impl WidthTable {
    fn new<P: Vector>(c: &CubicBezier<P>, tol: f64, magnitude: f64) -> Self {
        // Rounding allowance: a relative share of the tolerance and a few ulps of the coordinates.
        let limit = tol * (1.0 - 1e-9) - 1e-14 * magnitude;
        let e8 = 8.0 * limit;
        // power form: C′(t) = a + 2b·t + 3c·t², C″(t) = 2b + 6c·t
        let a = (c.p1 - c.p0) * 3.0;
        let b = (c.p2 - c.p1 * 2.0 + c.p0) * 3.0;
        let cc = c.p3 - c.p0 + (c.p1 - c.p2) * 3.0;
        // Q(t) = C′×C″ = k0 + k1·t + k2·t², Λ(t) = C′×c = l0 + l1·t
        let (k0, k1, k2) = (a.cross3(b) * 2.0, a.cross3(cc) * 6.0, b.cross3(cc) * 6.0);
        let (l0, l1) = (a.cross3(cc), b.cross3(cc) * 2.0);
        let planar = P::DIM == 2;
        let norm = |v: glam::DVec3| if planar { v.z.abs() } else { v.length() };
        // Wang's bound (h²/8)·max|C″| ≤ limit holds for any chord: a floor on every width.
        let dd_max = (b * 2.0).length().max((b * 2.0 + cc * 6.0).length());
        let rho_floor = (dd_max / e8).sqrt().max(1.0);
        let cn = cc.length();
        let inputs = CellInputs { e8, cn, k2n: norm(k2), rho_floor };
        // speed terms as scalar polynomials in t (dot products of a, b, c)
        let (aa, ab, ac, bb, bc, c2) = (a.dot(a), a.dot(b), a.dot(cc), b.dot(b), b.dot(cc), cc.dot(cc));
        let w = 1.0 / CELLS as f64;

        // |Q| and |Λ| at the cell ends
        let mut qe = [0.0f64; CELLS + 1];
        let mut le = [0.0f64; CELLS + 1];
        for (j, (q, l)) in qe.iter_mut().zip(le.iter_mut()).enumerate() {
            let t = j as f64 * w;
            *q = norm(k0 + (k1 + k2 * t) * t);
            *l = norm(l0 + l1 * t);
        }
        let mut rho = [0.0f64; CELLS];
        let mut smin = [0.0f64; CELLS];
        let mut qmax = [0.0f64; CELLS];
        let mut dd_cell = [0.0f64; CELLS];
        for j in 0..CELLS {
            let m = (j as f64 + 0.5) * w;
            // |C′(m)|², C″(m)·C′(m), c·C′(m)
            let s2 = aa + m * (4.0 * ab + m * (4.0 * bb + 6.0 * ac + m * (12.0 * bc + m * 9.0 * c2)));
            let g = 2.0 * ab + m * (4.0 * bb + 6.0 * ac + m * (18.0 * bc + m * 18.0 * c2));
            let cd = ac + m * (2.0 * bc + m * 3.0 * c2);
            // |C′(t)| ≥ C′(t)·û, û = C′(m)/|C′(m)|, and C′(t) = C′(m) + (t−m)·C″(m) + 3(t−m)²·c
            let x = s2 - 0.5 * w * g.abs() - 0.75 * w * w * (-cd).max(0.0);
            smin[j] = x / s2.sqrt();
            // max |C″| over the cell ≤ |C″(m)| + 3w·|c| (C″ is linear; the Euclidean norm keeps
            // the certificate, and so the count, independent of the curve's rotation)
            dd_cell[j] = (b * 2.0 + cc * (6.0 * m)).length() + 3.0 * w * cn;
            qmax[j] = if planar {
                qe[j].max(qe[j + 1])
            } else {
                // |Q(m)| + (w/2)·|Q′(m)| + (w/2)²·|k2|
                norm(k0 + (k1 + k2 * m) * m) + 0.5 * w * norm(k1 + k2 * (2.0 * m)) + 0.25 * w * w * inputs.k2n
            };
        }
        if planar && k2.z != 0.0 {
            // |Q| of a scalar quadratic may peak at its vertex, inside one cell
            let v = -k1.z / (2.0 * k2.z);
            if v > 0.0 && v < 1.0 {
                let j = ((v * CELLS as f64) as usize).min(CELLS - 1);
                qmax[j] = qmax[j].max(norm(k0 + (k1 + k2 * v) * v));
            }
        }
        for j in 0..CELLS {
            rho[j] = inputs.rho(qmax[j], le[j].max(le[j + 1]), smin[j], dd_cell[j]);
        }
        let mut cum = [0.0f64; CELLS + 1];
        let mut width = [0.0f64; CELLS];
        for j in 0..CELLS {
            width[j] = 1.0 / rho[j];
            cum[j + 1] = cum[j] + rho[j] * w;
        }
        Self { cum, width }
    }

    /// Cell holding parameter `t ∈ [0, 1]`.
    #[inline]
    fn cell(t: f64) -> usize {
        ((t * CELLS as f64) as i32 as usize).min(CELLS - 1)
    }

    /// The cumulative chord count at `t`.
    fn cumulative(&self, t: f64) -> f64 {
        let j = Self::cell(t);
        self.cum[j] + (t - j as f64 / CELLS as f64) / self.width[j]
    }

    /// Emits the chord ends: `n = ⌈total⌉` chords at equal steps of the cumulative count, so
    /// that a chord with both ends in one cell is at most that cell's width. The first chord
    /// entering a cell may cross into a cell of smaller width: it is checked against its
    /// midpoint's width and, if too long, shortened to it, and the rest is planned again.
    #[inline]
    fn march(&self, emit: &mut impl FnMut(f64)) {
        let total = self.cum[CELLS];
        let plan = |from: f64| {
            let rem = total - from;
            let n = ceil(rem);
            if n > 1.0 { ((n.min(1e15)) as usize, rem / n) } else { (1, rem) }
        };
        let w = 1.0 / CELLS as f64;
        let (mut n, mut step) = plan(0.0);
        let (mut base, mut k, mut j, mut ta) = (0.0, 1usize, 0usize, 0.0f64);
        loop {
            // the next target, and the cell it falls in
            let mut y = base + k as f64 * step;
            let mut tb = if k < n {
                while j + 1 < CELLS && self.cum[j + 1] < y {
                    j += 1;
                }
                (j as f64 * w + (y - self.cum[j]) * self.width[j]).min((j + 1) as f64 * w)
            } else {
                1.0
            };
            let allowed = self.width[Self::cell(0.5 * (ta + tb))];
            if !(tb - ta <= allowed && tb > ta) {
                // h takes strictly decreasing values from the finite set of widths
                let mut h = allowed.min(1.0 - ta);
                loop {
                    tb = ta + h;
                    let allowed = self.width[Self::cell(ta + 0.5 * h)];
                    if h <= allowed {
                        break;
                    }
                    h = allowed;
                }
                base = self.cumulative(tb);
                j = Self::cell(tb);
                (n, step) = plan(base);
                k = 0;
                y = base;
            }
            emit(tb);
            if tb >= 1.0 {
                return;
            }
            ta = tb;
            // the following targets in the same cell need no check: both ends lie in cell j
            let (end, width) = (self.cum[j + 1], self.width[j]);
            let offset = j as f64 * w - self.cum[j] * width;
            k += 1;
            y += step;
            while k < n && y <= end {
                ta = offset + y * width;
                emit(ta);
                k += 1;
                y = base + k as f64 * step;
            }
        }
    }
}

/// `⌈x⌉` for `0 ≤ x < 2⁵²` without a libm call (baseline x86-64 has no rounding instruction).
#[inline]
fn ceil(x: f64) -> f64 {
    if !(x < 4.5e15) {
        return x;
    }
    let f = x as i64 as f64;
    if f < x { f + 1.0 } else { f }
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

    #[test]
    fn certified_widths_hold_for_any_chord() {
        // Any chord no wider than the width of its midpoint's cell is within the tolerance —
        // not only the chords the march picks.
        let mut state = 11u64;
        let mut cases: Vec<CubicBezier<DVec2>> = (0..100).map(|_| random_cubic(&mut state)).collect();
        cases.push(cubic([(0.0, 0.0), (100.0, 50.0), (100.0, 50.0), (0.0, 0.0)]));
        cases.push(cubic([(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)]));
        for c in &cases {
            for tol in [0.1, 0.01, 1e-3] {
                let table = WidthTable::new(c, tol, 100.0);
                for _ in 0..20 {
                    let tm = rng(&mut state) / 100.0;
                    let h = table.width[WidthTable::cell(tm)].min(2.0 * tm).min(2.0 * (1.0 - tm));
                    let dev = sampled_chord_dev(c, tm - h / 2.0, tm + h / 2.0);
                    assert!(dev <= tol, "{c:?} tol {tol} tm {tm} h {h}: {dev}");
                }
            }
        }
    }

    #[test]
    fn widths_are_near_the_optimal_chord_length() {
        // A circle-like arc: the optimal chord deviates by exactly the tolerance; the
        // certified widths must not be much shorter.
        let c = cubic([(100.0, 0.0), (100.0, 55.228), (55.228, 100.0), (0.0, 100.0)]);
        let tol = 0.01;
        let table = WidthTable::new(&c, tol, 100.0);
        for j in 0..CELLS {
            let tm = (j as f64 + 0.5) / CELLS as f64;
            let h = table.width[j].min(2.0 * tm).min(2.0 * (1.0 - tm));
            let dev = sampled_chord_dev(&c, tm - h / 2.0, tm + h / 2.0);
            assert!(dev > 0.8 * tol && dev <= tol, "cell {j}: {dev}");
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
        let line = cubic([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]);
        let mut out = Vec::new();
        flatten_cubic_distance(&line, 1e-9, &mut out);
        assert_eq!(out, vec![1.0]);
        // a straight cubic that doubles back on itself must not be one chord
        let back = cubic([(0.0, 0.0), (3.0, 0.0), (-1.0, 0.0), (1.0, 0.0)]);
        out.clear();
        flatten_cubic_distance(&back, 1e-3, &mut out);
        assert!(out.len() >= 3, "{out:?}");
    }
}
