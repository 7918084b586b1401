//! Exact circular helices (the SWP `helix` object, an extension).

use core::f64::consts::{PI, TAU};

use glam::DVec3;

use crate::arclen::ArclenEstimate;
use crate::curve::{Aabb, ParamCurve};
use crate::flatten::{DEFAULT_ANGLE_TOLERANCE, DEFAULT_TOLERANCE, MAX_ANGLE_DEPTH, Tessellation};
use crate::vector::Vector;

/// A circular helix about the +z axis, starting at `(r, 0, 0)`:
///
/// `P(u) = (r·cos θ, r·sin θ, c·θ)` with `θ = 2π·turns·u`, `c = pitch/2π`, `u ∈ [0, 1]` (one
/// segment).
///
/// # Interpolation
/// Starts at `(r, 0, 0)` and ends at angle `2π·turns`, height `pitch·turns`.
///
/// # Tangency
/// `P′(u) = ω·(−r·sin θ, r·cos θ, c)` with `ω = 2π·turns`: the tangent rises at the constant
/// angle `atan(c/r)` above the xy-plane.
///
/// # Continuity
/// C∞ (and open: [`AnyCurve::is_closed`](crate::AnyCurve::is_closed) is false even when a
/// pitch of 0 and a whole number of turns happen to bring the end back to the start).
///
/// # Parametrization
/// Proportional to arc length: the speed is `|ω|·√(r² + c²)`, so the length of `[u0, u1]` is
/// `2π·|turns|·√(r² + c²)·(u1 − u0)`, exactly. Curvature `r/(r² + c²)` and torsion
/// `c/(r² + c²)` are constant. `pitch` is the rise per turn: positive pitch gives a
/// right-handed helix (counter-clockwise seen from +z while rising), negative pitch a
/// left-handed one. Negative `turns` runs clockwise (and, with positive pitch, downward).
/// Outside `[0, 1]` the formula extrapolates. As a 2D curve (`ParamCurve<DVec2>`) the helix is
/// its projection on the xy-plane, a circle traced `turns` times, with that circle's length.
///
/// Degenerate values are allowed: `r = 0` is a straight segment along z, `pitch = 0` a circle
/// (traced `turns` times), `turns = 0` a point (whose tangent is still the direction of travel
/// at the start).
///
/// # Usage
/// ```
/// use glam::DVec3;
/// use splinekit::{Helix, ParamCurve};
/// let spring = Helix::new(1.0, 0.5, 3.0);
/// let end: DVec3 = spring.eval(1.0);
/// assert!((end - DVec3::new(1.0, 0.0, 1.5)).length() < 1e-12);
/// let c = 0.5 / std::f64::consts::TAU;
/// let exact = 3.0 * std::f64::consts::TAU * (1.0 + c * c).sqrt();
/// assert!((ParamCurve::<DVec3>::arclen(&spring, 1e-9) - exact).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Helix {
    /// Radius (≥ 0).
    pub radius: f64,
    /// Rise per turn along +z (negative: left-handed).
    pub pitch: f64,
    /// Number of turns (fractional allowed; negative: clockwise).
    pub turns: f64,
}

impl Helix {
    /// A helix of radius `radius` (negative values are taken as their magnitude), rising by
    /// `pitch` per turn, over `turns` turns.
    #[must_use]
    pub fn new(radius: f64, pitch: f64, turns: f64) -> Self {
        Self { radius: radius.abs(), pitch, turns }
    }

    /// `c = pitch / 2π`: the rise per radian.
    #[inline]
    fn rise(&self) -> f64 {
        self.pitch / TAU
    }

    /// `ω = 2π·turns`: the angle swept per unit of `u`.
    #[inline]
    fn omega(&self) -> f64 {
        TAU * self.turns
    }

    /// The `order`-th derivative with respect to `u` (0 is the position).
    fn at(&self, u: f64, order: u32) -> DVec3 {
        let w = self.omega();
        let theta = w * u;
        let (s, c) = theta.sin_cos();
        let r = self.radius;
        if order == 0 {
            return DVec3::new(r * c, r * s, self.rise() * theta);
        }
        let k = w.powi(order as i32);
        let z = if order == 1 { self.rise() * w } else { 0.0 };
        let rk = r * k;
        match order % 4 {
            1 => DVec3::new(-s * rk, c * rk, z),
            2 => DVec3::new(-c * rk, -s * rk, z),
            3 => DVec3::new(s * rk, -c * rk, z),
            _ => DVec3::new(c * rk, s * rk, z),
        }
    }

    /// Rise per radian as seen in `P`'s space: `c` in 3D, 0 for the 2D projection.
    #[inline]
    fn rise_in<P: Vector>(&self) -> f64 {
        if P::DIM >= 3 { self.rise() } else { 0.0 }
    }

    /// Parameters of the polyline's vertices (see [`flatten_any`](crate::flatten::flatten_any)):
    /// `n + 1` equal steps `u = i/n`, the last exactly 1.
    pub(crate) fn flatten_params<P: Vector>(&self, mode: Tessellation) -> Vec<f64> {
        equal_params(self.chords::<P>(mode))
    }

    /// The number of chords [`flatten_params`](Self::flatten_params) makes, without making them.
    pub(crate) fn chord_count<P: Vector>(&self, mode: Tessellation) -> u64 {
        self.chords::<P>(mode) as u64
    }

    /// Number of equal chords in the given mode (see the docs of
    /// [`flatten_any`](crate::flatten::flatten_any)).
    fn chords<P: Vector>(&self, mode: Tessellation) -> usize {
        let r = self.radius;
        let c = self.rise_in::<P>();
        // the total angle swept
        let big_theta = self.omega().abs();
        match mode {
            Tessellation::Uniform { steps } => steps.clamp(1, crate::flatten::MAX_STEPS),
            Tessellation::Angle { tolerance } => {
                if !(r > 0.0 && big_theta > 0.0 && big_theta.is_finite() && r.is_finite() && c.is_finite()) {
                    return 1;
                }
                let eps = valid_or(tolerance, DEFAULT_ANGLE_TOLERANCE);
                // at least 3 chords per turn (as for a circle), at most 4096 per turn
                let turns = big_theta / TAU;
                let cap = ((4usize << MAX_ANGLE_DEPTH) as f64 * turns.ceil()).max(1.0);
                let at_least = (3.0 * turns).ceil().max(1.0);
                // the fewest chords in [at_least, cap] within the angle (which falls as n grows),
                // or cap: bisection, about 26 tests (stepping by one from an estimate took
                // tens of millions where the estimate was far off)
                let ok = |n: f64| chord_tangent_angle(r, c, 0.5 * big_theta / n) <= 0.5 * eps;
                let (mut lo, mut hi) = (at_least - 1.0, cap);
                while hi - lo > 1.0 {
                    let mid = (0.5 * (lo + hi)).floor();
                    if ok(mid) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                hi as usize
            }
            Tessellation::Distance { tolerance } => {
                if !(r > 0.0 && big_theta > 0.0 && big_theta.is_finite() && r.is_finite() && c.is_finite()) {
                    return 1;
                }
                // Wang: a chord over Δθ strays at most Δθ²/8·max|d²P/dθ²| = Δθ²·r/8 from the
                // helix, both ways (d²P/dθ² = (−r·cos θ, −r·sin θ, 0))
                let magnitude = r.max((c * big_theta).abs());
                let tol = valid_or(tolerance, DEFAULT_TOLERANCE).max(1e-12 * magnitude);
                let limit = tol * (1.0 - 1e-9) - 1e-14 * magnitude;
                let width = (8.0 * limit / r).sqrt();
                let mut n = (big_theta / width).ceil().max(1.0);
                while big_theta / n > width {
                    n += 1.0;
                }
                n as usize
            }
        }
    }
}

/// The angle between a helix chord over `[θm − δ, θm + δ]` and the tangent at either end
/// (the same at both, by symmetry), for radius `r` and rise per radian `c`; π when the
/// chord has no direction.
fn chord_tangent_angle(r: f64, c: f64, delta: f64) -> f64 {
    // the angle does not depend on the helix's size: scaled to 1, so that a radius of 1e-300
    // does not underflow to a chord of length 0
    let size = r.abs().max(c.abs());
    let (r, c) = if size > 0.0 && size.is_finite() { (r / size, c / size) } else { (r, c) };
    // with θm = 0: chord ∥ (0, r·sin δ, c·δ), end tangent ∥ (−r·sin δ, r·cos δ, c)
    let chord = DVec3::new(0.0, r * delta.sin(), c * delta);
    let tangent = DVec3::new(-r * delta.sin(), r * delta.cos(), c);
    let (a, b) = (chord.length(), tangent.length());
    if !(a > 0.0 && b > 0.0) {
        return PI;
    }
    chord.cross(tangent).length().atan2(chord.dot(tangent))
}

/// `tolerance` if it is finite and positive, else `default`.
#[inline]
pub(crate) fn valid_or(tolerance: f64, default: f64) -> f64 {
    if tolerance > 0.0 && tolerance.is_finite() { tolerance } else { default }
}

/// `u = i/n` for `i = 0..n`, then exactly 1.
pub(crate) fn equal_params(n: usize) -> Vec<f64> {
    let n = n.max(1);
    let mut out: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
    out.push(1.0);
    out
}

/// Whether `phase + 2πk` lies in `[a, b]` for some integer `k`.
fn hits(a: f64, b: f64, phase: f64) -> bool {
    let k = ((a - phase) / TAU).ceil();
    phase + TAU * k <= b
}

impl<P: Vector> ParamCurve<P> for Helix {
    one_segment_from_at!();
    /// Exact: `2π·|turns|·√(r² + c²)·(u1 − u0)` (2D: `2π·|turns|·r·(u1 − u0)`), error 0.
    fn arclen_range(&self, u0: f64, u1: f64, _accuracy: f64) -> ArclenEstimate {
        let speed = self.omega().abs() * self.radius.hypot(self.rise_in::<P>());
        ArclenEstimate { length: speed * (u1 - u0), error: 0.0 }
    }
    fn bounding_box(&self) -> Aabb<P> {
        let r = self.radius;
        let end = self.omega();
        let (a, b) = if end < 0.0 { (end, 0.0) } else { (0.0, end) };
        let ends = [self.at(0.0, 0), self.at(1.0, 0)];
        let mut lo = ends[0].min(ends[1]);
        let mut hi = ends[0].max(ends[1]);
        // the extremes of x and y inside the swept angle range
        if hits(a, b, 0.0) {
            hi.x = r;
        }
        if hits(a, b, PI) {
            lo.x = -r;
        }
        if hits(a, b, 0.5 * PI) {
            hi.y = r;
        }
        if hits(a, b, 1.5 * PI) {
            lo.y = -r;
        }
        Aabb { min: P::from_dvec3(lo), max: P::from_dvec3(hi) }
    }
    /// Exact: `|P″| = r·ω²` everywhere (the rise is linear in `u`).
    fn deriv2_bound(&self, _u0: f64, _u1: f64) -> f64 {
        self.radius * self.omega() * self.omega()
    }
    /// The direction of travel `sign(turns)·(−r·sin θ, r·cos θ, c)`, normalized (2D: without
    /// the `c`); for `r = c = 0` (a point) the direction of `(−sin θ, cos θ)`.
    fn unit_tangent(&self, u: f64) -> P {
        let theta = self.omega() * u;
        let (s, c) = theta.sin_cos();
        let sign = if self.turns < 0.0 { -1.0 } else { 1.0 };
        let v = P::from_dvec3(DVec3::new(-s * self.radius, c * self.radius, self.rise()) * sign);
        let l = v.length();
        if l > 0.0 && l.is_finite() { v * (1.0 / l) } else { P::from_dvec3(DVec3::new(-s, c, 0.0) * sign) }
    }
    /// `r/(r² + c²)` (2D: `1/r`); `+∞` when `r = c = 0` (a point), 0 for a straight helix
    /// (`r = 0`, `c ≠ 0`).
    fn curvature(&self, _u: f64) -> f64 {
        let (r, c) = (self.radius, self.rise_in::<P>());
        let l2 = r * r + c * c;
        if l2 > 0.0 { r / l2 } else { f64::INFINITY }
    }
    /// `c/(r² + c²)`; 0 for a straight or point-like helix and for the 2D projection.
    fn torsion(&self, _u: f64) -> f64 {
        let (r, c) = (self.radius, self.rise_in::<P>());
        let l2 = r * r + c * c;
        if l2 > 0.0 && r > 0.0 { c / l2 } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    const EPS: f64 = 1e-12;

    #[test]
    fn derivatives_match_finite_differences() {
        let h = Helix::new(1.3, -0.7, 2.25);
        for i in 0..=20 {
            let u = i as f64 / 20.0;
            for order in 0..3 {
                let d = 1e-6;
                let fd = (h.at(u + d, order) - h.at(u - d, order)) / (2.0 * d);
                let exact = h.at(u, order + 1);
                assert!((fd - exact).length() <= 1e-6 * exact.length().max(1.0), "order {order} at {u}");
            }
        }
    }

    #[test]
    fn chord_angle_is_the_circle_angle_without_pitch() {
        for delta in [0.01, 0.3, 1.0] {
            assert!((chord_tangent_angle(2.0, 0.0, delta) - delta).abs() < EPS);
        }
        assert_eq!(chord_tangent_angle(1.0, 0.0, PI), PI);
        assert_eq!(chord_tangent_angle(0.0, 0.0, 0.5), PI);
    }

    #[test]
    fn bounding_box_of_partial_turns() {
        let quarter = Helix::new(2.0, 1.0, 0.25);
        let b: Aabb<DVec3> = quarter.bounding_box();
        assert!((b.min - DVec3::new(0.0, 0.0, 0.0)).length() < EPS, "{b:?}");
        assert!((b.max - DVec3::new(2.0, 2.0, 0.25)).length() < EPS, "{b:?}");
        let back = Helix::new(1.0, 1.0, -0.5);
        let b: Aabb<DVec3> = back.bounding_box();
        assert!((b.min - DVec3::new(-1.0, -1.0, -0.5)).length() < EPS, "{b:?}");
        assert!((b.max - DVec3::new(1.0, 0.0, 0.0)).length() < EPS, "{b:?}");
        let b: Aabb<DVec2> = Helix::new(1.0, 3.0, 1.5).bounding_box();
        assert_eq!((b.min, b.max), (DVec2::splat(-1.0), DVec2::splat(1.0)));
    }

    #[test]
    fn degenerate_helices() {
        let point = Helix::new(0.0, 0.0, 0.0);
        assert_eq!(ParamCurve::<DVec3>::eval(&point, 0.5), DVec3::ZERO);
        let t: DVec3 = point.unit_tangent(0.3);
        assert!((t - DVec3::Y).length() < EPS);
        assert_eq!(point.flatten_params::<DVec3>(Tessellation::Distance { tolerance: 1e-3 }), vec![0.0, 1.0]);
        let line = Helix::new(0.0, 2.0, 3.0);
        let t: DVec3 = line.unit_tangent(0.7);
        assert!((t - DVec3::Z).length() < EPS);
        assert_eq!(ParamCurve::<DVec3>::curvature(&line, 0.0), 0.0);
        assert_eq!(line.flatten_params::<DVec3>(Tessellation::Angle { tolerance: 0.1 }), vec![0.0, 1.0]);
        let nan = Helix::new(f64::NAN, 1.0, 1.0);
        assert_eq!(nan.flatten_params::<DVec3>(Tessellation::Distance { tolerance: 1e-3 }).len(), 2);
    }
}
