//! The exact trefoil knot (the SWP `trefoil` object, an extension).
//!
//! # Facts used below
//!
//! With `t = 2πu` and `C(t) = (sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t)` (the knot of size 1),
//! everything the algorithms need depends on `t` only through `cos 3t` (write `c = cos 3t`):
//!
//! - speed²: `|C′(t)|² = 17 + 8c + 9c²` (from `cos t·cos 2t − sin t·sin 2t = cos 3t`), so the
//!   speed lies in `[√(137)/3, √34] ≈ [3.90, 5.83]` and never vanishes; in the xy-plane
//!   `|C′ₓᵧ|² = 17 + 8c`;
//! - `|C″(t)|² = 146 − 16c − 81c²`, largest at `c = −8/81`: `max|C″| = √11890 / 9 ≈ 12.1157`,
//!   smallest `7` at `c = 1`; in the xy-plane `|C″ₓᵧ|² = 65 − 16c ≤ 81`.
//!
//! So the arc length is the integral of the 2π/3-periodic function `g(θ) = √(17 + 8 cos θ + 9 cos² θ)`
//! (`θ = 3t`), analytic except where `cos θ = (−4 ± i√137)/9`, at `|Im θ| ≈ 1.1078` (in the
//! plane: `cos θ = −17/8`, `|Im θ| ≈ 1.3863`). In the strip `|Im θ| ≤ 1` we have
//! `|cos θ| ≤ cosh 1`, so `|g| ≤ √(17 + 8 cosh 1 + 9 cosh² 1) ≈ 7.126` there.

use core::f64::consts::{PI, TAU};

use glam::DVec3;

use crate::arclen::ArclenEstimate;
use crate::curve::helix::{equal_params, valid_or};
use crate::curve::{Aabb, ParamCurve};
use crate::flatten::{DEFAULT_ANGLE_TOLERANCE, DEFAULT_TOLERANCE, MAX_ANGLE_DEPTH, MAX_STEPS, Tessellation};
use crate::vector::Vector;

/// Half-width of the strip `|Im θ| ≤ STRIP` in which the arc-length integrand is bounded.
const STRIP: f64 = 1.0;

/// Nodes of the periodic trapezoidal rule for one whole period of the integrand.
const PERIOD_NODES: usize = 48;

/// Bisection depth limit for the arc length of a partial period.
const MAX_DEPTH: u32 = 30;

/// The largest Gauss–Legendre rule used; a piece that needs more is halved.
const MAX_NODES: usize = 64;

/// The trefoil knot `P(u) = s·(sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t)`, `t = 2πu`,
/// `u ∈ [0, 1]` (one segment), `s` the size.
///
/// # Interpolation
/// Starts and ends at `s·(0, −1, 0)`. The knot lies in the box `|x| ≤ 2.7358·s`,
/// `−3s ≤ y ≤ 33s/16`, `|z| ≤ s`, which is also its tight [bounding box](ParamCurve::bounding_box).
///
/// # Tangency
/// `P′(u) = 2πs·(cos t + 4 cos 2t, −sin t + 4 sin 2t, −3 cos 3t)`, never zero for `s > 0`.
///
/// # Continuity
/// C∞ and closed: the curve is 1-periodic in `u` (it is evaluated at `u` modulo 1, so the
/// end `u = 1` equals the start bit for bit, and values outside `[0, 1]` wrap around).
///
/// # Parametrization
/// Not by arc length: the speed `2πs·√(17 + 8 cos 3t + 9 cos² 3t)` varies between
/// `2πs·3.90` and `2πs·5.83`, with period 1/3 in `u` (the knot's three-fold symmetry).
/// Arc length is computed to a stated accuracy with Gauss–Legendre rules chosen from a
/// rigorous error bound (see [`arclen_range`](ParamCurve::arclen_range)). As a 2D curve
/// (`ParamCurve<DVec2>`) the trefoil is its projection on the xy-plane, with that
/// projection's own length. A size of 0 is a point whose tangent is still the knot's
/// direction of travel.
///
/// # Usage
/// ```
/// use glam::DVec3;
/// use splinekit::{ParamCurve, Trefoil};
/// let knot = Trefoil::new(1.0);
/// assert_eq!(ParamCurve::<DVec3>::eval(&knot, 1.0), ParamCurve::<DVec3>::eval(&knot, 0.0));
/// let length = ParamCurve::<DVec3>::arclen(&knot, 1e-12);
/// assert!((length - 28.826_290_198_944_29).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trefoil {
    /// The size `s` (≥ 0): the knot is `s` times the unit knot.
    pub size: f64,
}

impl Trefoil {
    /// `max |C″(t)|` of the knot of size 1 in 3D, per unit `t = 2πu`: `√11890 / 9` (at
    /// `cos 3t = −8/81`).
    pub const UNIT_MAX_DERIV2: f64 = 12.115_697_398_696_872;

    /// A trefoil knot of size `size` (negative values are taken as their magnitude).
    #[must_use]
    pub fn new(size: f64) -> Self {
        Self { size: size.abs() }
    }

    /// `max |P″(u)|` over the curve in 3D: `s·(2π)²·√11890/9` (exact, attained where
    /// `cos 6πu = −8/81`).
    #[must_use]
    pub fn max_deriv2(&self) -> f64 {
        self.size * TAU * TAU * Self::UNIT_MAX_DERIV2
    }

    /// The `order`-th derivative of the knot of size 1 with respect to `t`.
    fn unit_at(t: f64, order: u32) -> DVec3 {
        // dᵏ/dtᵏ sin(a·t) = aᵏ·sin(a·t + kπ/2), and likewise for cos
        let shifted = |x: f64| {
            let (s, c) = x.sin_cos();
            match order % 4 {
                0 => (s, c),
                1 => (c, -s),
                2 => (-s, -c),
                _ => (-c, s),
            }
        };
        let k = order as i32;
        let (s1, c1) = shifted(t);
        let (s2, c2) = shifted(2.0 * t);
        let (s3, _) = shifted(3.0 * t);
        let (p2, p3) = (2f64.powi(k), 3f64.powi(k));
        DVec3::new(s1 + 2.0 * p2 * s2, c1 - 2.0 * p2 * c2, -p3 * s3)
    }

    /// The `order`-th derivative with respect to `u`.
    fn at(&self, u: f64, order: u32) -> DVec3 {
        let t = TAU * u.rem_euclid(1.0);
        Self::unit_at(t, order) * (self.size * TAU.powi(order as i32))
    }

    /// An upper bound of the number of points [`flatten_params`](Self::flatten_params) makes: exact for
    /// uniform steps; 4·2^depth + 1 in the angle mode; in the distance mode the full turn over
    /// the smallest chord width the curvature bound allows.
    pub(crate) fn point_bound<P: Vector>(&self, mode: Tessellation) -> u64 {
        match mode {
            Tessellation::Uniform { steps } => steps.clamp(1, MAX_STEPS) as u64 + 1,
            Tessellation::Angle { .. } => (4u64 << MAX_ANGLE_DEPTH) + 1,
            Tessellation::Distance { tolerance } => {
                let s = self.size;
                if !(s > 0.0 && s.is_finite()) {
                    return 2;
                }
                let magnitude = 3.0 * s;
                let tol = valid_or(tolerance, DEFAULT_TOLERANCE).max(1e-12 * magnitude);
                let limit = tol * (1.0 - 1e-9) - 1e-14 * magnitude;
                let width = (8.0 * limit / s / max_deriv2(0.0, TAU, P::DIM < 3)).sqrt();
                let n = (TAU / width).ceil() + 2.0;
                if n.is_finite() && n < u64::MAX as f64 { n as u64 } else { u64::MAX }
            }
        }
    }

    /// Parameters of the polyline's vertices (see [`flatten_any`](crate::flatten::flatten_any)).
    pub(crate) fn flatten_params<P: Vector>(&self, mode: Tessellation) -> Vec<f64> {
        let planar = P::DIM < 3;
        match mode {
            Tessellation::Uniform { steps } => equal_params(steps.clamp(1, MAX_STEPS)),
            Tessellation::Angle { tolerance } => {
                let half = 0.5 * valid_or(tolerance, DEFAULT_ANGLE_TOLERANCE);
                let mut out = vec![0.0];
                // four quarters (no chord of a quarter is degenerate), each halved at most
                // MAX_ANGLE_DEPTH times: at most 4096 chords, as for a circle
                for q in 0..4 {
                    angle_split::<P>(0.25 * TAU * q as f64, 0.25 * TAU * (q + 1) as f64, half, 0, &mut out);
                }
                if let Some(last) = out.last_mut() {
                    *last = 1.0;
                }
                out
            }
            Tessellation::Distance { tolerance } => {
                let s = self.size;
                if !(s > 0.0 && s.is_finite()) {
                    return vec![0.0, 1.0];
                }
                let magnitude = 3.0 * s;
                let tol = valid_or(tolerance, DEFAULT_TOLERANCE).max(1e-12 * magnitude);
                let limit = tol * (1.0 - 1e-9) - 1e-14 * magnitude;
                distance_params(8.0 * limit / s, planar)
            }
        }
    }
}

/// Appends the end parameters `u` of the chords of `[t0, t1]` (in `t = 2πu`), splitting at the
/// middle while the chord turns by more than `half` from the tangent at either end.
fn angle_split<P: Vector>(t0: f64, t1: f64, half: f64, depth: u32, out: &mut Vec<f64>) {
    let dir = |t: f64| P::from_dvec3(Trefoil::unit_at(t, 1));
    let chord = P::from_dvec3(Trefoil::unit_at(t1, 0) - Trefoil::unit_at(t0, 0));
    // a chord without direction counts as turning by π
    let angle = |a: P, b: P| if b.length() > 0.0 { a.cross3(b).length().atan2(a.dot(b)) } else { PI };
    if depth < MAX_ANGLE_DEPTH && (angle(dir(t0), chord) > half || angle(chord, dir(t1)) > half) {
        let tm = 0.5 * (t0 + t1);
        angle_split::<P>(t0, tm, half, depth + 1, out);
        angle_split::<P>(tm, t1, half, depth + 1, out);
    } else {
        out.push(t1 / TAU);
    }
}

/// Range `(min, max)` of `cos 3t` over `t ∈ [ta, tb]`.
fn cos3_range(ta: f64, tb: f64) -> (f64, f64) {
    let (a, b) = (3.0 * ta, 3.0 * tb);
    let (ca, cb) = (a.cos(), b.cos());
    let hi = if hits(a, b, 0.0) { 1.0 } else { ca.max(cb) };
    let lo = if hits(a, b, PI) { -1.0 } else { ca.min(cb) };
    (lo, hi)
}

/// Whether `phase + 2πk` lies in `[a, b]` for some integer `k`.
fn hits(a: f64, b: f64, phase: f64) -> bool {
    let k = ((a - phase) / TAU).ceil();
    phase + TAU * k <= b
}

/// `max |C″(t)|` of the unit knot over `t ∈ [ta, tb]` (exact up to rounding): the maximum of
/// `146 − 16c − 81c²` (3D) or `65 − 16c` (plane) over the range of `c = cos 3t`.
fn max_deriv2(ta: f64, tb: f64, planar: bool) -> f64 {
    let (lo, hi) = cos3_range(ta, tb);
    let sq = if planar {
        65.0 - 16.0 * lo
    } else {
        let q = |c: f64| 146.0 - 16.0 * c - 81.0 * c * c;
        let vertex = -8.0 / 81.0;
        if lo <= vertex && vertex <= hi { q(vertex) } else { q(lo).max(q(hi)) }
    };
    sq.sqrt()
}

/// Distance mode on the unit knot: chords `[ta, tb]` (in `t`) with `(tb − ta)²·max|C″| ≤ e8`
/// over the chord (Wang's bound `(h²/8)·max|C″| ≤ tolerance`, with `e8 = 8·tolerance/s`).
///
/// Each width is one safe step of the decreasing map `f(h) = √(e8 / max|C″| over [ta, ta+h])`:
/// `h₀ = f(0)` is at least the widest valid width `h*`, so `h₁ = f(h₀) ≤ h*`, and `h₁` is valid
/// because `max|C″|` over `[ta, ta + h₁]` is at most that over `[ta, ta + h₀]`.
fn distance_params(e8: f64, planar: bool) -> Vec<f64> {
    let width = |ta: f64, h: f64| (e8 / max_deriv2(ta, ta + h, planar)).sqrt();
    let mut out = vec![0.0];
    let mut t = 0.0;
    loop {
        let h = width(t, width(t, 0.0));
        if !(t + h < TAU) {
            out.push(1.0);
            return out;
        }
        t += h;
        out.push(t / TAU);
    }
}

/// `|g|` on the strip `|Im θ| ≤ STRIP`: `√(17 + 8 cosh + 9 cosh²)` (plane: without the last term).
fn strip_bound(planar: bool) -> f64 {
    let ch = STRIP.cosh();
    (17.0 + 8.0 * ch + if planar { 0.0 } else { 9.0 * ch * ch }).sqrt()
}

/// The arc-length integrand in `θ = 3t = 6πu`: `g(θ) = √(17 + 8 cos θ + 9 cos² θ)` (plane:
/// `√(17 + 8 cos θ)`); the length of the knot of size `s` over `[θa, θb]` is `(s/3)·∫g dθ`.
fn speed_theta(theta: f64, planar: bool) -> f64 {
    let c = theta.cos();
    (17.0 + 8.0 * c + if planar { 0.0 } else { 9.0 * c * c }).sqrt()
}

/// `∫₀^{2π} g dθ` by the periodic trapezoidal rule with [`PERIOD_NODES`] nodes, with its error
/// bound `4π·M/(e^{a·N} − 1)` (Trefethen & Weideman, "The exponentially convergent
/// trapezoidal rule", SIAM Review 56(3), 2014, Theorem 3.2; `a` = [`STRIP`], `M` its bound).
fn full_period(planar: bool) -> (f64, f64) {
    let n = PERIOD_NODES;
    let sum: f64 = (0..n).map(|j| speed_theta(TAU * j as f64 / n as f64, planar)).sum();
    let bound = 2.0 * TAU * strip_bound(planar) / ((STRIP * n as f64).exp() - 1.0);
    (sum * TAU / n as f64, bound)
}

/// `∫ g dθ` over `[θa, θb]` (a part of one period) to within `budget`, added to `out`.
///
/// The `m`-point Gauss–Legendre rule on a piece of half-width `h` errs by at most
/// `h·(64/15)·M·ρ^(−2(m−1))/(ρ² − 1)` for a function analytic and bounded by `M` in the
/// Bernstein ellipse `E_ρ` (Trefethen, *Approximation Theory and Approximation Practice*,
/// Theorem 19.3). The ellipse `ρ = y/h + √((y/h)² + 1)` has semi-minor axis `y` = [`STRIP`],
/// so it lies in the strip where `|g| ≤ M`. The smallest `m ≤` [`MAX_NODES`] within budget
/// is used; if there is none, the piece is halved.
fn partial(a: f64, b: f64, budget: f64, planar: bool, depth: u32, out: &mut ArclenEstimate) {
    let h = 0.5 * (b - a);
    if !(h > 0.0) {
        return;
    }
    let c = 0.5 * (a + b);
    // the rounding level of the sum (|g| ≤ 6 on the real line)
    let budget = budget.max(1e-14 * 6.0 * (b - a));
    let ratio = STRIP / h;
    let rho = ratio + (ratio * ratio + 1.0).sqrt();
    let rho2 = rho * rho;
    // ρ² − 1 = 2·ratio·ρ, without cancellation
    let lead = h * (64.0 / 15.0) * strip_bound(planar) / (2.0 * ratio * rho);
    let bound = |m: usize| lead * rho2.powi(1 - m as i32);
    // the smallest m from the logarithms, then checked directly (rounding at the margin)
    let guess = 1.0 + ((lead / budget).ln() / rho2.ln()).ceil();
    let first = if guess.is_finite() { guess.clamp(1.0, MAX_NODES as f64) as usize } else { MAX_NODES };
    let chosen = (first..=MAX_NODES).find(|&m| bound(m) <= budget);
    let speed = |theta: f64| speed_theta(theta, planar);
    match chosen {
        Some(m) => {
            out.length += gauss_legendre(&speed, c, h, m);
            out.error += bound(m);
        }
        None if depth < MAX_DEPTH => {
            partial(a, c, 0.5 * budget, planar, depth + 1, out);
            partial(c, b, 0.5 * budget, planar, depth + 1, out);
        }
        None => {
            out.length += gauss_legendre(&speed, c, h, MAX_NODES);
            out.error += bound(MAX_NODES);
        }
    }
}

/// The `m`-point Gauss–Legendre rule applied to `f` on `[c − h, c + h]`. Nodes are the roots
/// of the Legendre polynomial `Pₘ`, found by Newton's method from `cos(π(i − ¼)/(m + ½))`;
/// weights `2/((1 − x²)·Pₘ′(x)²)`. Accurate to a few ulps for `m ≤ 64`.
fn gauss_legendre<F: Fn(f64) -> f64>(f: &F, c: f64, h: f64, m: usize) -> f64 {
    let mf = m as f64;
    // Pₘ(x) and Pₘ′(x) by the three-term recurrence
    let legendre = |x: f64| {
        let (mut p0, mut p1) = (1.0, x);
        for k in 2..=m {
            let kf = k as f64;
            (p0, p1) = (p1, ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf);
        }
        let p = if m == 0 { p0 } else { p1 };
        let previous = if m <= 1 { 1.0 } else { p0 };
        (p, mf * (x * p - previous) / (x * x - 1.0))
    };
    let mut sum = 0.0;
    for i in 1..=m.div_ceil(2) {
        let mut x = (PI * (i as f64 - 0.25) / (mf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre(x);
            dp = d;
            let step = p / d;
            x -= step;
            if step.abs() <= 1e-15 {
                break;
            }
        }
        let (_, d) = legendre(x);
        if d.is_finite() && d != 0.0 {
            dp = d;
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        if m % 2 == 1 && i == m.div_ceil(2) {
            sum += w * f(c); // the middle node, x = 0
        } else {
            sum += w * (f(c - h * x) + f(c + h * x));
        }
    }
    sum * h
}

impl<P: Vector> ParamCurve<P> for Trefoil {
    one_segment_from_at!();
    /// The knot's exact maximum [`max_deriv2`](Trefoil::max_deriv2) (the xy-projection's is no
    /// larger).
    fn deriv2_bound(&self, _u0: f64, _u1: f64) -> f64 {
        self.max_deriv2()
    }
    /// Arc length to within `accuracy`, with a rigorous error bound as the estimate.
    ///
    /// In `θ = 6πu` the length is `(s/3)·∫g dθ` with `g` of period 2π (see the module docs).
    /// Whole periods in `[u0, u1]` count the period's integral, computed by the periodic
    /// trapezoidal rule (error below 1e-18); the partial periods at either end use
    /// Gauss–Legendre rules chosen from the Bernstein-ellipse bound. Each partial period gets
    /// a third of the budget. Accuracies below the rounding level (about 1e-14 of the length)
    /// are raised to it. `u1 < u0` gives a negative length.
    fn arclen_range(&self, u0: f64, u1: f64, accuracy: f64) -> ArclenEstimate {
        if u1 < u0 {
            let e = ParamCurve::<P>::arclen_range(self, u1, u0, accuracy);
            return ArclenEstimate { length: -e.length, error: e.error };
        }
        let s = self.size;
        if !(u1 > u0) || !(s > 0.0) || !s.is_finite() || !u0.is_finite() || !u1.is_finite() {
            return ArclenEstimate::default();
        }
        let planar = P::DIM < 3;
        // in periods: p = 3u, θ = 2π·p
        let (pa, pb) = (3.0 * u0, 3.0 * u1);
        // the length is (s/3)·∫g dθ: the θ-integral may err by 3·accuracy/s in all, a third of
        // it for each partial period (whole periods add below 1e-18 each)
        let budget = if accuracy > 0.0 { accuracy / s } else { 0.0 };
        let mut out = ArclenEstimate::default();
        let in_period = |p: f64| TAU * (p - p.floor());
        let (ka, kb) = (pa.ceil(), pb.floor());
        if ka > kb {
            // inside one period
            let a = in_period(pa);
            partial(a, a + TAU * (pb - pa), budget, planar, 0, &mut out);
        } else {
            if ka > pa {
                partial(in_period(pa), TAU, budget, planar, 0, &mut out);
            }
            let whole = kb - ka;
            if whole > 0.0 {
                let (integral, bound) = full_period(planar);
                out.length += whole * integral;
                out.error += whole * bound;
            }
            if pb > kb {
                partial(0.0, TAU * (pb - kb), budget, planar, 0, &mut out);
            }
        }
        ArclenEstimate { length: out.length * s / 3.0, error: out.error * s / 3.0 }
    }
    fn bounding_box(&self) -> Aabb<P> {
        // x′ = cos t + 4 cos 2t = 0 at cos t = (√129 − 1)/16, where x = sin t·(1 + 4 cos t);
        // y′ = sin t·(8 cos t − 1) = 0 at t = π (y = −3) and cos t = 1/8 (y = 33/16)
        let a = (129f64.sqrt() - 1.0) / 16.0;
        let x = (1.0 - a * a).sqrt() * (1.0 + 4.0 * a);
        let s = self.size;
        Aabb {
            min: P::from_dvec3(DVec3::new(-x, -3.0, -1.0) * s),
            max: P::from_dvec3(DVec3::new(x, 33.0 / 16.0, 1.0) * s),
        }
    }
    /// The direction of `P′(u)` (also for size 0, from the unit knot).
    fn unit_tangent(&self, u: f64) -> P {
        let v = P::from_dvec3(Self::unit_at(TAU * u.rem_euclid(1.0), 1));
        let l = v.length();
        if l > 0.0 && l.is_finite() { v * (1.0 / l) } else { P::from_dvec3(DVec3::X) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        let k = Trefoil::new(0.8);
        for i in 0..=30 {
            let u = i as f64 / 30.0 * 0.98 + 0.01;
            for order in 0..3 {
                let d = 1e-6;
                let fd = (k.at(u + d, order) - k.at(u - d, order)) / (2.0 * d);
                let exact = k.at(u, order + 1);
                assert!((fd - exact).length() <= 1e-6 * exact.length().max(1.0), "order {order} at {u}");
            }
        }
    }

    #[test]
    fn closed_forms_of_speed_and_second_derivative() {
        for i in 0..=200 {
            let t = TAU * i as f64 / 200.0;
            let c = (3.0 * t).cos();
            let d1 = Trefoil::unit_at(t, 1);
            let d2 = Trefoil::unit_at(t, 2);
            assert!((d1.length_squared() - (17.0 + 8.0 * c + 9.0 * c * c)).abs() < 1e-12);
            assert!((d1.truncate().length_squared() - (17.0 + 8.0 * c)).abs() < 1e-12);
            assert!((d2.length_squared() - (146.0 - 16.0 * c - 81.0 * c * c)).abs() < 1e-11);
            assert!((d2.truncate().length_squared() - (65.0 - 16.0 * c)).abs() < 1e-11);
            assert!((speed_theta(3.0 * t, false) - d1.length()).abs() < 1e-12);
        }
        assert!((Trefoil::UNIT_MAX_DERIV2 - 11890f64.sqrt() / 9.0).abs() < 1e-15);
    }

    #[test]
    fn local_second_derivative_bound_holds() {
        let mut t0 = 0.0;
        while t0 < TAU {
            for h in [0.01, 0.1, 0.7, 2.5] {
                for planar in [false, true] {
                    let bound = max_deriv2(t0, t0 + h, planar);
                    let sampled = (0..=200)
                        .map(|i| {
                            let d = Trefoil::unit_at(t0 + h * i as f64 / 200.0, 2);
                            if planar { d.truncate().length() } else { d.length() }
                        })
                        .fold(0.0, f64::max);
                    assert!(sampled <= bound * (1.0 + 1e-12), "{t0} {h}: {sampled} > {bound}");
                    assert!(sampled >= bound * (1.0 - 1e-3) || h < 0.02, "{t0} {h}: {sampled} ≪ {bound}");
                }
            }
            t0 += 0.137;
        }
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        for m in 1..=MAX_NODES {
            for k in 0..(2 * m).min(60) {
                let exact = if k % 2 == 0 { 2.0 / (k + 1) as f64 } else { 0.0 };
                let got = gauss_legendre(&|x: f64| x.powi(k as i32), 0.0, 1.0, m);
                assert!((got - exact).abs() <= 1e-14, "m {m}, x^{k}: {got} vs {exact}");
            }
            // the weights sum to the interval's length, on any interval
            assert!((gauss_legendre(&|_| 1.0, 3.0, 0.25, m) - 0.5).abs() <= 1e-14, "m {m}");
        }
    }

    #[test]
    fn trapezoid_period_agrees_with_gauss() {
        for planar in [false, true] {
            let (integral, bound) = full_period(planar);
            assert!(bound < 1e-17);
            let mut out = ArclenEstimate::default();
            partial(0.0, TAU, 1e-15, planar, 0, &mut out);
            assert!((out.length - integral).abs() < 1e-12, "{} vs {integral}", out.length);
        }
    }
}
