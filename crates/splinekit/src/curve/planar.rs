//! Arc length of planar cubic segments with a rigorous error bound.
//!
//! A planar cubic's velocity, written as a complex number, is a quadratic
//! `q(t) = a + b·t + c·t²`, and its speed is `|q(t)| = √(q(t)·q̄(t))` where `q̄` has the
//! conjugate coefficients. That function is analytic away from the roots of `q` and of
//! `q̄` (conjugate pairs), so on a piece `[t₀, t₁]` the Gauss–Legendre error is bounded by
//! the Bernstein ellipse that reaches the nearest root ([`gauss::ellipse_error_bound`]),
//! and the number of nodes can be chosen *before* integrating: no error estimate is
//! guessed, and none can be fooled.
//!
//! - Roots that are real (exact cusps: the velocity vanishes) or near enough to real that
//!   moving them onto the real axis changes the integral by less than a small share of the
//!   budget are *snapped*: the speed is then `|C|·|t − x|·|rest|`, analytic on each side of
//!   `x`, so the piece is cut at `x` and the snap's effect is charged to the error.
//! - Pieces whose nearest root is too close for 20 nodes are split towards it, and
//!   budgets are shared in proportion to width, so the bounds add up to at most the
//!   requested accuracy.
//!
//! A 3D cubic is handled here when its velocity coefficients lie in a plane; the distance
//! of the coefficients from that plane, if any, is charged too.

use crate::arclen::ArclenEstimate;
use crate::gauss;
use crate::vector::Vector;
use glam::DVec2;

/// Deepest split before a piece is left to the general adaptive integrator.
const MAX_DEPTH: u32 = 40;

/// Complex arithmetic on `DVec2` (`x` real part, `y` imaginary part).
#[inline]
fn cmul(a: DVec2, b: DVec2) -> DVec2 {
    DVec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

#[inline]
fn cdiv(a: DVec2, b: DVec2) -> DVec2 {
    // Smith's algorithm: no overflow for large |b|
    if b.x.abs() >= b.y.abs() {
        let r = b.y / b.x;
        let d = 1.0 / (b.x + b.y * r);
        DVec2::new((a.x + a.y * r) * d, (a.y - a.x * r) * d)
    } else {
        let r = b.x / b.y;
        let d = 1.0 / (b.x * r + b.y);
        DVec2::new((a.x * r + a.y) * d, (a.y * r - a.x) * d)
    }
}

/// A square root (either sign), computed without cancellation.
#[inline]
fn csqrt(z: DVec2) -> DVec2 {
    let m = z.length();
    if z.x >= 0.0 {
        let re = (0.5 * (m + z.x)).sqrt();
        DVec2::new(re, if re > 0.0 { 0.5 * z.y / re } else { 0.0 })
    } else {
        let im = (0.5 * (m - z.x)).sqrt();
        DVec2::new(0.5 * z.y / im, im)
    }
}

/// `α²` for the Bernstein ellipse (foci ±1) through `r = x + iy`, `α` its semi-major
/// axis: `x²/α² + y²/(α² − 1) = 1` gives `α² = (s + √(s² − 4x²))/2` with `s = 1 + x² + y²`.
/// (`ρ = α + √(α² − 1)` grows with `α`.)
#[inline]
fn ellipse_alpha2(r: DVec2) -> f64 {
    let s = 1.0 + r.x * r.x + r.y * r.y;
    0.5 * (s + (s * s - 4.0 * r.x * r.x).max(0.0).sqrt())
}

/// A lower bound of `log2(x)` for `x ≥ 1` (within 0.09): exponent plus mantissa − 1
/// (`log2(1 + f) ≥ f` on `[0, 1]`).
#[inline]
fn log2_below(x: f64) -> f64 {
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as f64 - 1023.0;
    let mantissa = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    exponent + mantissa - 1.0
}

/// An upper bound of `log2(x)` for `x ≥ 1` (within 0.09): `log2(1 + f) ≤ f + 0.0861`.
#[inline]
fn log2_above(x: f64) -> f64 {
    log2_below(x) + 0.086_1
}

/// `|x| + |y|`: an upper bound of the modulus, without a square root.
#[inline]
fn l1(z: DVec2) -> f64 {
    z.x.abs() + z.y.abs()
}

/// The velocity of a planar cubic as a complex quadratic `a + b·t + c·t²`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlanarSpeed {
    a: DVec2,
    b: DVec2,
    c: DVec2,
    /// `|a⊥| + |b⊥| + |c⊥|`: bounds the distance between the true velocity and its
    /// projection by `off_plane·max(1, t²)`.
    off_plane: f64,
    /// Roots of `q` in `t` (`nroots` of them: 2 for a quadratic, 1 for a linear `q`, 0 for
    /// a constant one) and an upper bound of the modulus of the leading coefficient.
    roots: [DVec2; 2],
    nroots: usize,
    lead: f64,
}

impl PlanarSpeed {
    /// The projection of a velocity `a + b·t + c·t²` (any dimension) into the plane of its
    /// coefficients. `None` when the coefficients are not coplanar within a relative
    /// `1e-12` (a twisted 3D cubic).
    pub(crate) fn new<P: Vector>(a: P, b: P, c: P) -> Option<Self> {
        let (a3, b3, c3) = (a.to_dvec3(), b.to_dvec3(), c.to_dvec3());
        if a3.z == 0.0 && b3.z == 0.0 && c3.z == 0.0 {
            return Some(Self::from_coefficients(a3.truncate(), b3.truncate(), c3.truncate(), 0.0));
        }
        let crosses = [a3.cross(b3), a3.cross(c3), b3.cross(c3)];
        let n = crosses.into_iter().max_by(|p, q| p.length_squared().total_cmp(&q.length_squared()))?;
        let longest = [a3, b3, c3].into_iter().max_by(|p, q| p.length_squared().total_cmp(&q.length_squared()))?;
        let e1 = longest.try_normalize()?; // all zero: the caller's constant-point path
        let n = n.try_normalize().unwrap_or_else(|| e1.any_orthonormal_vector());
        let e2 = n.cross(e1);
        let off_plane = a3.dot(n).abs() + b3.dot(n).abs() + c3.dot(n).abs();
        let scale = a3.length() + b3.length() + c3.length();
        if !(off_plane <= 1e-12 * scale) {
            return None;
        }
        let p = |v: glam::DVec3| DVec2::new(v.dot(e1), v.dot(e2));
        Some(Self::from_coefficients(p(a3), p(b3), p(c3), off_plane))
    }

    /// Finds the roots once; every piece maps them to its own coordinate.
    fn from_coefficients(a: DVec2, b: DVec2, c: DVec2, off_plane: f64) -> Self {
        let size = l1(a) + l1(b) + l1(c);
        let (lead, roots, nroots) = if l1(c) > 1e-14 * size {
            let disc = cmul(b, b) - 4.0 * cmul(a, c);
            let mut sq = csqrt(disc);
            if b.dot(sq) < 0.0 {
                sq = -sq;
            }
            let big = -0.5 * (b + sq);
            let r1 = cdiv(big, c);
            let r2 = if big != DVec2::ZERO { cdiv(a, big) } else { r1 };
            (l1(c), [r1, r2], 2)
        } else if l1(b) > 1e-14 * size {
            (l1(b), [-cdiv(a, b), DVec2::ZERO], 1)
        } else {
            (0.0, [DVec2::ZERO; 2], 0)
        };
        Self { a, b, c, off_plane, roots, nroots, lead }
    }

    /// The speed `|q(t)|` of the projected velocity.
    #[inline]
    pub(crate) fn speed(&self, t: f64) -> f64 {
        (self.a + (self.b + self.c * t) * t).length()
    }

    /// Arc length over `[t0, t1]` (negative for `t1 < t0`) with a rigorous bound on its error,
    /// at most `accuracy` unless `accuracy` is below the rounding level (about `1e-14` of
    /// the length) or the split depth runs out (then the adaptive integrator takes over).
    pub(crate) fn arclen(&self, t0: f64, t1: f64, accuracy: f64) -> ArclenEstimate {
        if t1 < t0 {
            let e = self.arclen(t1, t0, accuracy);
            return ArclenEstimate { length: -e.length, error: e.error };
        }
        let mut out = ArclenEstimate::default();
        if !(t1 > t0) {
            return out;
        }
        let reach = t0.abs().max(t1.abs()).max(1.0);
        let charge = (t1 - t0) * self.off_plane * reach * reach;
        let budget = (accuracy - charge).max(0.0);
        out.error = charge;
        self.piece(t0, t1, budget / (t1 - t0), 0, &mut out);
        out
    }

    /// Integrates one piece; `density` is the budget per unit of `t`.
    ///
    /// Norms below are L1 (`|x| + |y|`) where only an upper bound is needed: no square roots.
    fn piece(&self, lo: f64, hi: f64, density: f64, depth: u32, out: &mut ArclenEstimate) {
        let cen = 0.5 * (lo + hi);
        let h = 0.5 * (hi - lo);
        // q in the piece's own coordinate z ∈ [−1, 1]: t = cen + h·z
        let qa = self.a + (self.b + self.c * cen) * cen;
        let qb = (self.b + self.c * (2.0 * cen)) * h;
        let qc = self.c * (h * h);
        let (na, nb, nc) = (l1(qa), l1(qb), l1(qc));
        // bounds |q| on the piece: the scale of the rounding floor
        let size = na + nb + nc;
        let budget = (density * (hi - lo)).max(1e-14 * 2.0 * h * size);
        let speed = |t: f64| self.speed(t);
        if !(size > 0.0) || !size.is_finite() {
            // a constant point (length 0), or non-finite input
            out.length += if size == 0.0 { 0.0 } else { f64::NAN };
            return;
        }
        let nroots = self.nroots;
        if nroots == 0 {
            // constant speed (within rounding): the midpoint rule is exact
            out.length += 2.0 * h * speed(cen);
            out.error += 2.0 * h * 1e-14 * size;
            return;
        }
        let inv_h = 1.0 / h;
        let roots = [(self.roots[0] - DVec2::new(cen, 0.0)) * inv_h, (self.roots[1] - DVec2::new(cen, 0.0)) * inv_h];
        let lead = if nroots == 2 { self.lead * h * h } else { self.lead * h };

        // Snap near-real roots to the real axis where that is cheap: with q = lead·Π(z − rᵢ),
        // moving r₁ to a real x̂ changes |q| on [−1, 1] by at most lead·|r₁ − x̂|·(1 + |r₂|);
        // the integral and the rule each change by at most twice that, times h.
        let mut penalty = 0.0;
        let mut alpha2 = f64::INFINITY; // α² of the nearest unsnapped root's ellipse
        let mut nearest = DVec2::ZERO;
        let mut snapped = [false; 2];
        for i in 0..nroots {
            let r = roots[i];
            let scale = 4.0 * h * lead * if nroots == 2 { 1.0 + l1(roots[1 - i]) } else { 1.0 };
            let cost = scale * r.y.abs();
            // snap only roots near the axis: farther ones leave a wide ellipse anyway
            if r.y.abs() < 0.125 && cost <= 0.125 * budget {
                if r.x > -1.0 && r.x < 1.0 {
                    let cut = cen + h * r.x;
                    if cut > lo && cut < hi && depth < MAX_DEPTH {
                        // an (almost) exact cusp inside: cut there
                        self.piece(lo, cut, density, depth + 1, out);
                        self.piece(cut, hi, density, depth + 1, out);
                        return;
                    }
                    // too near an end to cut: snap it onto that end instead
                    let cost = scale * (r.y.abs() + (1.0 - r.x.abs()));
                    if cost <= 0.125 * budget {
                        penalty += cost;
                        snapped[i] = true;
                        continue;
                    }
                } else {
                    penalty += cost;
                    snapped[i] = true;
                    continue;
                }
            }
            let a2 = ellipse_alpha2(r);
            if a2 < alpha2 {
                alpha2 = a2;
                nearest = r;
            }
        }

        let remaining = budget - penalty;
        let mut chosen = None;
        if alpha2.is_infinite() {
            // every root snapped: the speed is ± a polynomial of degree ≤ 2 on the piece
            chosen = Some((1, 0.0)); // RULES[1] = 2 nodes: exact to degree 3
        } else if alpha2 > 1.0 && remaining > 0.0 {
            // ρ = α + √(α² − 1), so ρ² = 2α² − 1 + 2√(α²(α² − 1)); α = (ρ + 1/ρ)/2 bounds |z|
            let rho2 = 2.0 * alpha2 - 1.0 + 2.0 * (alpha2 * (alpha2 - 1.0)).sqrt();
            let rho = rho2.sqrt();
            let a = alpha2.sqrt();
            // |q| on the ellipse: Chebyshev form q = d0 + d1·T1 + d2·T2 with |Tₖ| ≤ (ρᵏ + ρ⁻ᵏ)/2,
            // or the factored form lead·Π(a + |rᵢ|) (a bounds |z|); both bound |q̄| as well, so
            // √(q·q̄) is below them. With snapped roots only the factored form bounds the
            // snapped function.
            let mut fact = lead;
            for (i, r) in roots[..nroots].iter().enumerate() {
                fact *= a + if snapped[i] { r.x.abs() } else { l1(*r) };
            }
            let bound = if snapped[0] || snapped[1] {
                fact
            } else {
                let cheb = l1(qa + qc * 0.5) + nb * a + 0.5 * nc * (2.0 * a * a - 1.0);
                cheb.min(fact)
            };
            // smallest rule with h·(64/15)·bound·ρ^(−2(m−1))/(ρ²−1) ≤ remaining
            let e1 = h * gauss::ellipse_error_bound(1, rho, bound);
            let need = if e1 <= remaining { 1.0 } else { 1.0 + (log2_below(e1 / remaining) / log2_above(rho2)).ceil() };
            if let Some(first) = gauss::RULES.iter().position(|&n| n as f64 >= need) {
                // the logarithms may round `need` down at the margin: then a rule more
                for rule in first.max(1)..gauss::RULES.len() {
                    let e = e1 * rho2.powi(1 - gauss::RULES[rule] as i32);
                    if e <= remaining {
                        chosen = Some((rule, e));
                        break;
                    }
                }
            }
        }
        match chosen {
            Some((rule, e)) => {
                out.length += gauss::integrate(&speed, cen, h, rule);
                out.error += e + penalty;
            }
            None if depth < MAX_DEPTH => {
                // split towards the nearest unsnapped root
                let cut = cen + h * nearest.x.clamp(-0.75, 0.75);
                self.piece(lo, cut, density, depth + 1, out);
                self.piece(cut, hi, density, depth + 1, out);
            }
            None => {
                let e = crate::arclen::integrate_speed(speed, lo, hi, budget);
                out.length += e.length;
                out.error += e.error;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complex_helpers() {
        let z = DVec2::new(-3.0, 4.0);
        let r = csqrt(z);
        assert!((cmul(r, r) - z).length() < 1e-15 * z.length());
        for z in [DVec2::new(2.0, 0.0), DVec2::new(-2.0, 0.0), DVec2::new(0.0, -5.0), DVec2::ZERO] {
            let r = csqrt(z);
            assert!((cmul(r, r) - z).length() <= 1e-15 * z.length(), "{z}");
        }
        let (a, b) = (DVec2::new(1.5, -2.0), DVec2::new(1e-3, 7.0));
        assert!((cmul(cdiv(a, b), b) - a).length() < 1e-15);
    }

    #[test]
    fn ellipse_through_a_point() {
        // on the real axis beyond the foci: α = |x|
        assert!((ellipse_alpha2(DVec2::new(3.0, 0.0)) - 9.0).abs() < 1e-14);
        // on the imaginary axis: the minor semi-axis is |y|, α² = 1 + y²
        assert!((ellipse_alpha2(DVec2::new(0.0, 0.5)) - 1.25).abs() < 1e-15);
        // a general point lies on the ellipse it names
        let r = DVec2::new(0.7, 0.2);
        let a2 = ellipse_alpha2(r);
        assert!((r.x * r.x / a2 + r.y * r.y / (a2 - 1.0) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn log2_bounds() {
        for x in [1.0, 1.5, 2.0, 3.0, 7.9, 1e3, 1.234e17] {
            let l = f64::log2(x);
            assert!(log2_below(x) <= l + 1e-15 && l - log2_below(x) < 0.09, "{x}");
            assert!(log2_above(x) >= l && log2_above(x) - l < 0.09, "{x}");
        }
    }

    #[test]
    fn tilted_plane_matches_flat_curve() {
        use glam::DVec3;
        // the same planar velocity in the xy plane and rotated into a tilted plane
        let (a, b, c) = (DVec3::new(3.0, -1.0, 0.0), DVec3::new(-6.0, 8.0, 0.0), DVec3::new(4.0, -9.0, 0.0));
        let rot = glam::DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.9);
        let flat = PlanarSpeed::new(a, b, c).unwrap();
        let tilted = PlanarSpeed::new(rot * a, rot * b, rot * c).unwrap();
        assert!(tilted.off_plane <= 1e-12 * 20.0);
        let (l0, l1) = (flat.arclen(0.0, 1.0, 1e-12), tilted.arclen(0.0, 1.0, 1e-12));
        assert!((l0.length - l1.length).abs() <= 2e-12, "{} vs {}", l0.length, l1.length);
        // a twisted velocity is not planar
        assert!(PlanarSpeed::new(a, b, DVec3::new(0.0, 0.0, 1.0)).is_none());
    }
}
