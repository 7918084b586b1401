//! The cubic Bézier segment, the shared currency of every spline kind.

use crate::arclen::planar::PlanarSpeed;
use crate::arclen::{self, ArclenEstimate};
use crate::curve::{Aabb, ParamCurve};
use crate::vector::Vector;

/// Cubic Bézier basis matrix: rows per control point, columns per power of t,
/// so that `P(t) = [p0 p1 p2 p3] · BEZIER_BASIS · [1, t, t², t³]ᵀ`.
pub const BEZIER_BASIS: [[f64; 4]; 4] =
    [[1.0, -3.0, 3.0, -1.0], [0.0, 3.0, -6.0, 3.0], [0.0, 0.0, 3.0, -3.0], [0.0, 0.0, 0.0, 1.0]];

/// A cubic Bézier segment `P(t) = (1−t)³·p0 + 3(1−t)²t·p1 + 3(1−t)t²·p2 + t³·p3`, `t ∈ [0, 1]`.
///
/// # Interpolation
/// Passes through `p0` (t = 0) and `p3` (t = 1); `p1` and `p2` are approached, not met.
///
/// # Tangency
/// `P′(0) = 3(p1 − p0)` and `P′(1) = 3(p3 − p2)`.
///
/// # Continuity
/// A single polynomial: C∞ inside the segment.
///
/// # Parametrization
/// `t ∈ [0, 1]`. Evaluation outside that range extrapolates the polynomial.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{CubicBezier, ParamCurve};
/// let c = CubicBezier::new(DVec2::ZERO, DVec2::new(1.0, 0.0), DVec2::new(2.0, 0.0), DVec2::new(3.0, 0.0));
/// assert_eq!(c.eval(0.5), DVec2::new(1.5, 0.0));
/// assert!((c.arclen(1e-9) - 3.0).abs() <= 1e-9);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct CubicBezier<P> {
    /// Start point.
    pub p0: P,
    /// First inner control point.
    pub p1: P,
    /// Second inner control point.
    pub p2: P,
    /// End point.
    pub p3: P,
}

impl<P: Vector> CubicBezier<P> {
    /// A segment from its four control points.
    #[inline]
    #[must_use]
    pub const fn new(p0: P, p1: P, p2: P, p3: P) -> Self {
        Self { p0, p1, p2, p3 }
    }

    /// The control points as an array.
    #[inline]
    #[must_use]
    pub fn points(&self) -> [P; 4] {
        [self.p0, self.p1, self.p2, self.p3]
    }

    /// Position at `t`: the Bernstein form written relative to the nearer end point
    /// (`p0 + Σ bᵢ(t)·(pᵢ − p0)` for `t < ½`, mirrored about `p3` otherwise), so the end
    /// points are hit exactly and a curve whose control points coincide is exactly constant.
    #[inline]
    #[must_use]
    pub fn eval(&self, t: f64) -> P {
        let mt = 1.0 - t;
        let (mt2, t2) = (mt * mt, t * t);
        let (b0, b1, b2, b3) = (mt2 * mt, 3.0 * mt2 * t, 3.0 * mt * t2, t2 * t);
        if t < 0.5 {
            self.p0 + (self.p1 - self.p0) * b1 + (self.p2 - self.p0) * b2 + (self.p3 - self.p0) * b3
        } else {
            self.p3 + (self.p0 - self.p3) * b0 + (self.p1 - self.p3) * b1 + (self.p2 - self.p3) * b2
        }
    }

    /// First derivative `dP/dt`.
    #[inline]
    #[must_use]
    pub fn deriv(&self, t: f64) -> P {
        let mt = 1.0 - t;
        ((self.p1 - self.p0) * (mt * mt) + (self.p2 - self.p1) * (2.0 * mt * t) + (self.p3 - self.p2) * (t * t)) * 3.0
    }

    /// Second derivative.
    #[inline]
    #[must_use]
    pub fn deriv2(&self, t: f64) -> P {
        let a = self.p2 - self.p1 * 2.0 + self.p0;
        let b = self.p3 - self.p2 * 2.0 + self.p1;
        (a * (1.0 - t) + b * t) * 6.0
    }

    /// Third derivative (constant along the segment).
    #[inline]
    #[must_use]
    pub fn deriv3(&self) -> P {
        (self.p3 - self.p2 * 3.0 + self.p1 * 3.0 - self.p0) * 6.0
    }

    /// Coefficients `(a, b, c)` of the derivative in power form: `P′(t) = a + b·t + c·t²`.
    #[inline]
    #[must_use]
    pub fn deriv_coefficients(&self) -> (P, P, P) {
        let a = (self.p1 - self.p0) * 3.0;
        let b = (self.p2 - self.p1 * 2.0 + self.p0) * 6.0;
        let c = (self.p3 - self.p2 * 3.0 + self.p1 * 3.0 - self.p0) * 3.0;
        (a, b, c)
    }

    /// De Casteljau split at `t`: left half `p0, p01, p012, p0123`, right half
    /// `p0123, p123, p23, p3`. The halves share the split point exactly.
    #[must_use]
    pub fn split(&self, t: f64) -> (Self, Self) {
        let p01 = self.p0.lerp(self.p1, t);
        let p12 = self.p1.lerp(self.p2, t);
        let p23 = self.p2.lerp(self.p3, t);
        let p012 = p01.lerp(p12, t);
        let p123 = p12.lerp(p23, t);
        let p0123 = p012.lerp(p123, t);
        (Self::new(self.p0, p01, p012, p0123), Self::new(p0123, p123, p23, self.p3))
    }

    /// The part of the curve between `t0` and `t1`, reparametrized to `[0, 1]`
    /// (`t1 < t0` gives the reversed piece).
    #[must_use]
    pub fn subsegment(&self, t0: f64, t1: f64) -> Self {
        let (p0, p3) = (self.eval(t0), self.eval(t1));
        let scale = (t1 - t0) / 3.0;
        let p1 = p0 + self.deriv(t0) * scale;
        let p2 = p3 - self.deriv(t1) * scale;
        Self::new(p0, p1, p2, p3)
    }

    /// The same curve traversed backwards.
    #[inline]
    #[must_use]
    pub fn reversed(&self) -> Self {
        Self::new(self.p3, self.p2, self.p1, self.p0)
    }

    /// Tight axis-aligned bounding box over `t ∈ [0, 1]` (from the roots of the derivative).
    #[must_use]
    pub fn bounding_box(&self) -> Aabb<P> {
        let mut bb = Aabb::from_point(self.p0).union_point(self.p3);
        let (a, b, c) = self.deriv_coefficients();
        for i in 0..P::DIM {
            // roots of a_i + b_i t + c_i t² on (0, 1)
            for t in quadratic_roots(a.component(i), b.component(i), c.component(i)).into_iter().flatten() {
                if t > 0.0 && t < 1.0 {
                    bb = bb.union_point(self.eval(t));
                }
            }
        }
        bb
    }

    /// Arc length of `t ∈ [t0, t1]` to within `accuracy` (absolute, length units), with an
    /// error estimate.
    ///
    /// A planar segment (2D, or 3D with its velocity in a plane) picks Gauss–Legendre rules
    /// from a rigorous bound (see the `arclen` module docs): the estimate is then an upper
    /// bound of the error. A twisted 3D segment is first cut at the local minima of the
    /// speed `|P′|` (the roots of `P′·P″`, a cubic), where cusps and near-cusps put a kink
    /// into the integrand, and each piece goes to [`arclen::integrate_speed`] with a share of
    /// the budget in proportion to its width. An accuracy below the rounding of the speed
    /// itself, `4ε·(|a| + |b| + |c|)·(t1 − t0)` for `P′(t) = a + b·t + c·t²`, is raised to it.
    #[must_use]
    pub fn arclen_range(&self, t0: f64, t1: f64, accuracy: f64) -> ArclenEstimate {
        if t1 < t0 {
            let e = self.arclen_range(t1, t0, accuracy);
            return ArclenEstimate { length: -e.length, error: e.error };
        }
        let (a, b, c) = self.deriv_coefficients();
        // The speed is computed to about 4ε·(|a| + |b| + |c|) on [0, 1]: no integral of it is
        // better than that times its width, and asking for more (1e-300) would only split
        // the pieces around a near-cusp, where the speed is all rounding, to the work limit.
        let noise = 4.0 * f64::EPSILON * (a.length() + b.length() + c.length());
        let accuracy = if accuracy > noise * (t1 - t0) { accuracy } else { noise * (t1 - t0) };
        if let Some(planar) = PlanarSpeed::new(a, b, c) {
            return planar.arclen(t0, t1, accuracy);
        }
        let speed = |t: f64| (a + (b + c * t) * t).length();
        let (minima, count) = speed_minima(a, b, c, t0, t1);
        if count == 0 {
            return arclen::integrate_speed(speed, t0, t1, accuracy);
        }
        let width = t1 - t0;
        let mut out = ArclenEstimate::default();
        let mut add = |lo: f64, hi: f64| {
            let e = arclen::integrate_speed(speed, lo, hi, accuracy * ((hi - lo) / width));
            out.length += e.length;
            out.error += e.error;
        };
        let mut lo = t0;
        for &m in &minima[..count] {
            // A near-cusp leaves a knee of width ε/|P″| at the minimum; Gauss–Kronrod
            // under-estimates its error (by a log factor) until the knee is resolved.
            // Its whole contribution is below (ε²/2a)·(ln(2ah/ε) + 1); where that could
            // exceed the budget, grade the pieces geometrically towards the minimum down
            // to the knee's width.
            let eps = speed(m);
            let acc2 = (b + c * (2.0 * m)).length();
            let knee = if eps > 0.0 && acc2 > 0.0 { eps / acc2 } else { 0.0 };
            let budget = 0.5 * accuracy * ((t1 - t0) / width);
            let grade = |h: f64| knee > 0.0 && eps * knee * 0.5 * ((2.0 * h / knee).ln().max(0.0) + 1.0) > budget;
            // left of the minimum: [lo, m]
            let mut x = lo;
            let mut h = m - lo;
            while grade(h) && h > 4.0 * knee {
                h *= 0.5;
                add(x, m - h);
                x = m - h;
            }
            add(x, m);
            // right of the minimum: [m, next]
            let next = minima[..count].iter().copied().find(|&v| v > m).unwrap_or(t1);
            let right_end = if next < t1 { 0.5 * (m + next) } else { t1 };
            let mut h = right_end - m;
            let mut pieces = [0.0f64; 64];
            let mut np = 0;
            while grade(h) && h > 4.0 * knee && np < 63 {
                h *= 0.5;
                pieces[np] = m + h;
                np += 1;
            }
            let mut x = m;
            for &p in pieces[..np].iter().rev() {
                add(x, p);
                x = p;
            }
            add(x, right_end);
            lo = right_end;
        }
        if lo < t1 {
            add(lo, t1);
        }
        out
    }

    /// Parameter `t ∈ [0, 1]` at which the arc length from `t = 0` equals `s`, such that
    /// the true arc length to the returned `t` differs from `s` by at most `accuracy`
    /// (length units). `s` is clamped to `[0, length]`.
    #[must_use]
    pub fn inv_arclen(&self, s: f64, accuracy: f64) -> f64 {
        let (a, b, c) = self.deriv_coefficients();
        if let Some(planar) = PlanarSpeed::new(a, b, c) {
            let integrate = |t0: f64, t1: f64, acc: f64| planar.arclen(t0, t1, acc);
            return arclen::solve_arclen(integrate, |t| planar.speed(t), 0.0, 1.0, s, accuracy);
        }
        let speed = |t: f64| (a + (b + c * t) * t).length();
        arclen::solve_arclen(|t0, t1, acc| self.arclen_range(t0, t1, acc), speed, 0.0, 1.0, s, accuracy)
    }

    /// True when every control point is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.points().iter().all(|p| p.is_finite_vector())
    }
}

impl<P: Vector> ParamCurve<P> for CubicBezier<P> {
    fn num_segments(&self) -> usize {
        1
    }
    fn eval(&self, u: f64) -> P {
        CubicBezier::eval(self, u)
    }
    fn deriv(&self, u: f64) -> P {
        CubicBezier::deriv(self, u)
    }
    fn deriv2(&self, u: f64) -> P {
        CubicBezier::deriv2(self, u)
    }
    fn deriv3(&self, _u: f64) -> P {
        CubicBezier::deriv3(self)
    }
    fn arclen_range(&self, u0: f64, u1: f64, accuracy: f64) -> ArclenEstimate {
        CubicBezier::arclen_range(self, u0, u1, accuracy)
    }
    fn bounding_box(&self) -> Aabb<P> {
        CubicBezier::bounding_box(self)
    }
    /// Exact: `P″` is linear in `t`, so its length is largest at an end of the interval.
    fn deriv2_bound(&self, u0: f64, u1: f64) -> f64 {
        CubicBezier::deriv2(self, u0).length().max(CubicBezier::deriv2(self, u1).length())
    }
}

/// Parameters in `(t0, t1)` where the speed `|a + b·t + c·t²|` has a local minimum: the
/// sign changes from − to + of `f(t) = P′·P″ = a·b + (b·b + 2a·c)·t + 3b·c·t² + 2c·c·t³`.
/// At most two; returned sorted, with their count.
fn speed_minima<P: Vector>(a: P, b: P, c: P, t0: f64, t1: f64) -> ([f64; 2], usize) {
    let d = [a.dot(b), b.dot(b) + 2.0 * a.dot(c), 3.0 * b.dot(c), 2.0 * c.dot(c)];
    let f = |t: f64| d[0] + t * (d[1] + t * (d[2] + t * d[3]));
    // cut (t0, t1) into pieces where f is monotone, at the roots of f′
    let mut cuts = [t0, t1, t1, t1];
    let mut n = 1;
    let mut crit: [f64; 2] = [f64::NAN; 2];
    for (slot, r) in crit.iter_mut().zip(quadratic_roots(d[1], 2.0 * d[2], 3.0 * d[3])) {
        *slot = r.unwrap_or(f64::NAN);
    }
    if crit[0] > crit[1] {
        crit.swap(0, 1);
    }
    for r in crit {
        if r > t0 && r < t1 {
            cuts[n] = r;
            n += 1;
        }
    }
    cuts[n] = t1;
    let mut out = [0.0; 2];
    let mut count = 0;
    for w in 0..n {
        let (mut lo, mut hi) = (cuts[w], cuts[w + 1]);
        let (flo, fhi) = (f(lo), f(hi));
        // a minimum of the speed: f rises through zero inside the piece
        if !(flo < 0.0 && fhi > 0.0) || count == 2 {
            continue;
        }
        // f is monotone on [lo, hi]: Newton steps kept inside the bracket (bisection when a
        // step leaves it); stops when the bracket or the step is at rounding level.
        let df = |t: f64| d[1] + t * (2.0 * d[2] + t * 3.0 * d[3]);
        let mut x = if fhi - flo > 0.0 { lo - flo * (hi - lo) / (fhi - flo) } else { 0.5 * (lo + hi) };
        for _ in 0..64 {
            let fx = f(x);
            if fx == 0.0 {
                break; // an exact root: keep it (the bracket would collapse onto it)
            }
            if fx < 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let step = fx / df(x);
            let nx = x - step;
            if nx > lo && nx < hi {
                x = nx;
                if !(step.abs() > 1e-15 * (1.0 + x.abs())) {
                    break;
                }
            } else {
                x = 0.5 * (lo + hi);
            }
            if !(hi - lo > 1e-15) {
                break;
            }
        }
        let root = x;
        if root > t0 && root < t1 {
            out[count] = root;
            count += 1;
        }
    }
    (out, count)
}

/// Real roots of `a + b·t + c·t²` (up to two); a degenerate polynomial gives none.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if !(scale > 0.0) || !scale.is_finite() {
        return [None, None];
    }
    let (a, b, c) = (a / scale, b / scale, c / scale);
    if c.abs() < 1e-12 {
        return if b.abs() < 1e-300 { [None, None] } else { [Some(-a / b), None] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    // numerically stable form
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let r1 = q / c;
    let r2 = if q != 0.0 { a / q } else { r1 };
    [Some(r1), Some(r2)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};
    use proptest::prelude::*;

    fn bernstein_reference(c: &CubicBezier<DVec3>, t: f64) -> DVec3 {
        // matrix form: G · B · [1 t t² t³]ᵀ, G = [p0 p1 p2 p3] as columns
        let powers = [1.0, t, t * t, t * t * t];
        let g = c.points();
        let mut out = DVec3::ZERO;
        for (row, p) in BEZIER_BASIS.iter().zip(g) {
            let w: f64 = row.iter().zip(powers).map(|(b, x)| b * x).sum();
            out += p * w;
        }
        out
    }

    fn pt() -> impl Strategy<Value = DVec3> {
        (-100.0..100.0f64, -100.0..100.0f64, -100.0..100.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn cubic() -> impl Strategy<Value = CubicBezier<DVec3>> {
        (pt(), pt(), pt(), pt()).prop_map(|(a, b, c, d)| CubicBezier::new(a, b, c, d))
    }

    proptest! {
        #[test]
        fn eval_matches_matrix_form(c in cubic(), t in 0.0..1.0f64) {
            prop_assert!((c.eval(t) - bernstein_reference(&c, t)).length() < 1e-9);
        }

        #[test]
        fn derivatives_match_finite_differences(c in cubic(), t in 0.05..0.95f64) {
            let h = 1e-5;
            let fd1 = (c.eval(t + h) - c.eval(t - h)) / (2.0 * h);
            let fd2 = (c.deriv(t + h) - c.deriv(t - h)) / (2.0 * h);
            let fd3 = (c.deriv2(t + h) - c.deriv2(t - h)) / (2.0 * h);
            prop_assert!((fd1 - c.deriv(t)).length() < 1e-5 * (1.0 + c.deriv(t).length()));
            prop_assert!((fd2 - c.deriv2(t)).length() < 1e-5 * (1.0 + c.deriv2(t).length()));
            prop_assert!((fd3 - c.deriv3()).length() < 1e-5 * (1.0 + c.deriv3().length()));
            let (a, b, cc) = c.deriv_coefficients();
            prop_assert!((a + b * t + cc * t * t - c.deriv(t)).length() < 1e-9);
        }

        #[test]
        fn split_halves_reproduce_curve(c in cubic(), s in 0.01..0.99f64, u in 0.0..1.0f64) {
            let (l, r) = c.split(s);
            prop_assert!((l.p3 - c.eval(s)).length() < 1e-9);
            prop_assert_eq!(l.p3, r.p0);
            prop_assert!((l.eval(u) - c.eval(s * u)).length() < 1e-9);
            prop_assert!((r.eval(u) - c.eval(s + (1.0 - s) * u)).length() < 1e-9);
        }

        #[test]
        fn subsegment_matches_lerp(c in cubic(), a in 0.0..1.0f64, b in 0.0..1.0f64, u in 0.0..1.0f64) {
            let sub = c.subsegment(a, b);
            prop_assert!((sub.eval(u) - c.eval(a + (b - a) * u)).length() < 1e-8);
        }

        #[test]
        fn bounding_box_contains_curve_and_touches_it(c in cubic()) {
            let bb = c.bounding_box();
            let mut lo = DVec3::splat(f64::INFINITY);
            let mut hi = DVec3::splat(f64::NEG_INFINITY);
            for i in 0..=2000 {
                let p = c.eval(i as f64 / 2000.0);
                prop_assert!(bb.contains(p, 1e-9));
                lo = lo.min(p);
                hi = hi.max(p);
            }
            // dense sampling comes within the sampling error of the exact box
            prop_assert!((bb.min - lo).abs().max_element() < 1e-3 * (1.0 + (hi - lo).max_element()));
            prop_assert!((bb.max - hi).abs().max_element() < 1e-3 * (1.0 + (hi - lo).max_element()));
        }
    }

    #[test]
    fn degenerate_point_curve_is_total() {
        let p = DVec2::new(1.0, 2.0);
        let c = CubicBezier::new(p, p, p, p);
        assert_eq!(c.eval(0.3), p);
        assert_eq!(c.deriv(0.3), DVec2::ZERO);
        assert_eq!(c.arclen(1e-9), 0.0);
        assert_eq!(c.inv_arclen(1.0, 1e-9), 1.0);
        assert_eq!(c.inv_arclen(0.0, 1e-9), 0.0);
        let bb = c.bounding_box();
        assert_eq!((bb.min, bb.max), (p, p));
        let t = c.unit_tangent(0.5);
        assert!(t.is_finite() && (t.length() - 1.0).abs() < 1e-12);
        assert_eq!(c.curvature(0.5), 0.0);
        assert_eq!(c.torsion(0.5), 0.0);
    }

    /// Regression: an exact cusp where f(t) = P′·P″ evaluates to exactly 0 during the
    /// search; the minimum was once returned as the bracket midpoint (t = 0.25).
    #[test]
    fn exact_root_is_kept() {
        let c = CubicBezier::new(
            DVec2::new(79.97580968484739, 68.14396312829524),
            DVec2::new(73.41002926711649, 69.73534318007778),
            DVec2::new(75.89722945009068, 65.65676294532105),
            DVec2::new(77.48860950187321, 72.22254336305195),
        );
        let (a, b, cc) = c.deriv_coefficients();
        for t1 in [1.0, 0.859508612951838, 0.7, 0.5000001] {
            let (m, n) = speed_minima(a, b, cc, 0.0, t1);
            assert_eq!(n, 1, "[0, {t1}]");
            assert!((m[0] - 0.5).abs() < 1e-12, "[0, {t1}]: {}", m[0]);
        }
    }
}
