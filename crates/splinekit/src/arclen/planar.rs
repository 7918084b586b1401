//! Arc length of planar cubic segments with a rigorous error bound.
//!
//! A planar cubic's velocity, written as a complex number, is a quadratic
//! `q(t) = a + b·t + c·t²`, and its speed is `|q(t)| = √(q(t)·q̄(t))` where `q̄` has the
//! conjugate coefficients. That function is analytic away from the roots of `q` and of
//! `q̄` (conjugate pairs), so on a piece `[t₀, t₁]` the error of the `m`-point
//! Gauss–Legendre rule is bounded through the Bernstein ellipse that reaches the nearest
//! root (Trefethen, *Approximation Theory and Approximation Practice*, Theorem 19.3; stated
//! in [`gauss`]), and the number of nodes is chosen *before* integrating: no error
//! estimate is guessed, and none can be fooled.
//!
//! # One piece
//! In the piece's own coordinate `z ∈ [−1, 1]` (`t = cen + h·z`), for the nearest root at
//! `(x + iy)/h`, all in units of `t` so that nothing is divided by `h`:
//! 1. The ellipse through the root: with `P = h² − x² − y²` and `D = √(P² + 4y²h²)`,
//!    `h²α² = (h² + x² + y² + D)/2` and `h²(α² − 1) = E = 2y²h²/(P + D)` (for `P > 0`,
//!    else `(D − P)/2`), both free of cancellation; then `ρ = α + √(α² − 1)` gives
//!    `G = h²(ρ² − 1) = 2√E·(√E + hα)`.
//! 2. A bound `M` of `|q|` on the ellipse, where `|z| ≤ α`: the smaller of the Chebyshev
//!    form `|d₀| + |d₁|·α + |d₂|·(2α² − 1)` (`q = d₀ + d₁T₁ + d₂T₂`) and the factored form
//!    `|lead|·Π(α + |rᵢ|)`. Both bound `|q̄|` as well, so `|√(q·q̄)| ≤ M` there.
//! 3. The theorem's bound `h·(64/15)·M·ρ^(−2(m−1))/(ρ² − 1) ≤ budget` holds once
//!    `m − 1 ≥ log2(E₁/budget) / log2(ρ²)` (`E₁` the bound for one node). The logarithms
//!    are bounded from the floating-point representation (exponent, plus the mantissa with
//!    a quadratic correction, each in the safe direction) and by `ln(1 + g) ≥ 2g/(2 + g)`;
//!    the next whole number picks the rule from the table (1 to 20 nodes, then steps of 4 to
//!    64 and of 8 to 128) with no logarithm, power or second check. A relative margin of
//!    `1e-9` covers the rounding of this arithmetic. The bound itself, at most the budget,
//!    is the error estimate returned.
//!
//! The cost per piece is then a short chain (a few square roots and two divisions, mostly
//! side by side) and the nodes, in pairs (`q(±x)` share their even part), four pairs at a
//! time in packed arithmetic.
//!
//! # Roots near the interval
//! - Roots that are real (exact cusps: the velocity vanishes) or near enough to real that
//!   moving them onto the real axis changes the integral by less than a small share of the
//!   budget are *snapped*: the speed is then `|C|·|t − x|·|rest|`, analytic on each side of
//!   `x`, so the piece is cut at `x` and the snap's effect is charged to the error.
//! - Pieces whose nearest root is too close for 128 nodes are split towards it, and
//!   budgets are shared in proportion to width, so the bounds add up to at most the
//!   requested accuracy.
//!
//! The roots are those of the floating-point coefficients, found without cancellation; the
//! bound is rigorous for them. A 3D cubic is handled here when its velocity coefficients
//! lie in a plane; the distance of the coefficients from that plane, if any, is charged too.

use super::{ArclenEstimate, gauss};
use crate::vector::Vector;
use glam::DVec2;

/// Deepest split before a piece is left to the general adaptive integrator.
const MAX_DEPTH: u32 = 40;

/// The most pieces one integral is split into. Past it every piece left takes one
/// Gauss–Kronrod step and reports its own error, so an integral ends in bounded time whatever
/// the accuracy asked (only an accuracy below the length's rounding level, or rounding noise
/// in a curve whose coordinates dwarf its detail, gets there).
const MAX_PIECES: usize = 1 << 12;

/// Complex arithmetic on `DVec2` (`x` real part, `y` imaginary part).
#[inline]
fn cmul(a: DVec2, b: DVec2) -> DVec2 {
    DVec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

/// `a / b`, without overflow or underflow in `|b|²`: `b` is first scaled by a power of two
/// (exact) to a largest component in `[1, 2)`. Branch-free: the arguments' signs and sizes
/// are not predictable.
#[inline]
fn cdiv(a: DVec2, b: DVec2) -> DVec2 {
    let big = b.x.abs().max(b.y.abs());
    // 2^(−e) for big = 2^e·(1 + f), through the exponent bits (clamped to stay normal)
    let biased = ((big.to_bits() >> 52) & 0x7ff).min(2045);
    let s = f64::from_bits((2046 - biased) << 52);
    let bs = b * s;
    let inv = s / (bs.x * bs.x + bs.y * bs.y);
    DVec2::new(a.x * bs.x + a.y * bs.y, a.y * bs.x - a.x * bs.y) * inv
}

/// A square root (either sign), computed without cancellation.
#[inline]
fn csqrt(z: DVec2) -> DVec2 {
    let m = z.length();
    // the larger part from a sum of like signs, the smaller one from it by division:
    // z.y/(2·big) = z.y·big/(m + |z.x|), whose division runs beside the square root
    let sum = m + z.x.abs();
    let big = (0.5 * sum).sqrt();
    let inv = if sum > 0.0 { 1.0 / sum } else { 0.0 };
    let small = z.y * big * inv;
    if z.x >= 0.0 { DVec2::new(big, small) } else { DVec2::new(small.abs(), big.copysign(z.y)) }
}

/// For the Bernstein ellipse through `(x + iy)/h` (`α` its semi-major axis, `ε = α² − 1`):
/// `(P, D, A)` with `P = h² − x² − y²`, `D = √(P² + 4y²h²)` and `A = h²·α² = (h² + x² + y² + D)/2`,
/// all without division or cancellation. Then `h²·ε = A − h² = (D − P)/2`, computed as
/// `2y²h²/(P + D)` when `P > 0` (where the difference cancels).
#[inline]
fn ellipse_terms(x: f64, y: f64, h2: f64) -> (f64, f64, f64) {
    let (x2, y2) = (x * x, y * y);
    let p = (h2 - x2) - y2;
    let d = (p * p + 4.0 * y2 * h2).sqrt();
    (p, d, 0.5 * ((h2 + x2 + y2) + d))
}

/// A lower bound of `log2(x)` for normal `x > 0` (within 0.021): with `x = 2^e·(1 + f)`,
/// `log2(1 + f) ≥ f + 0.2786·f(1 − f)`, because `(log2(1 + f) − f)/(f(1 − f))` falls from
/// `1/ln 2 − 1 = 0.44270` at `f = 0` to `1 − 1/(2 ln 2) = 0.27865` at `f = 1` (checked on
/// a fine grid by the tests). `1e-12` covers the rounding.
#[inline]
fn log2_below(x: f64) -> f64 {
    let (e, f) = exponent_and_fraction(x);
    e + f + 0.2786 * f * (1.0 - f) - 1e-12
}

/// An upper bound of `log2(x)` for normal `x > 0` (within 0.029):
/// `log2(1 + f) ≤ f + 0.4427·f(1 − f)` (see [`log2_below`]).
#[inline]
fn log2_above(x: f64) -> f64 {
    let (e, f) = exponent_and_fraction(x);
    e + f + 0.4427 * f * (1.0 - f) + 1e-12
}

/// `(e, f)` with `x = 2^e·(1 + f)`, `0 ≤ f < 1`, for normal `x > 0`.
#[inline]
fn exponent_and_fraction(x: f64) -> (f64, f64) {
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as f64 - 1023.0;
    let mantissa = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    (exponent, mantissa - 1.0)
}

/// An upper bound of `2^(−y)` for `y ≥ 0`: `2^(−⌊y⌋)·(1 − f/2)` with `f = y − ⌊y⌋`
/// (`2^(−f)` is convex, so below its chord on `[0, 1]`); `y` is clamped to `[0, 1000]`.
#[inline]
fn exp2_neg_above(y: f64) -> f64 {
    let y = y.clamp(0.0, 1000.0);
    let k = y as u64; // ⌊y⌋, without a call to `floor`
    let f = y - k as f64;
    f64::from_bits((1023 - k) << 52) * (1.0 - 0.5 * f)
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
            let sq = csqrt(disc);
            // the sign that adds to b: no cancellation in b + sq
            let sq = sq * 1f64.copysign(b.dot(sq));
            let big = -0.5 * (b + sq);
            // 1/c is ready before big is
            let r1 = cmul(big, cdiv(DVec2::X, c));
            // a/big = a·conj(big)/|big|², scaled only where |big|² could overflow or underflow
            let n2 = big.length_squared();
            let r2 = if n2 > 1e-290 && n2 < 1e290 {
                DVec2::new(a.x * big.x + a.y * big.y, a.y * big.x - a.x * big.y) * (1.0 / n2)
            } else if big != DVec2::ZERO {
                cdiv(a, big)
            } else {
                r1
            };
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
        let mut left = MAX_PIECES;
        self.piece(t0, t1, budget, 0, &mut left, &mut out);
        out
    }

    /// Integrates `[lo, cut]` and `[cut, hi]`, sharing `budget` in proportion to width.
    #[allow(clippy::too_many_arguments)]
    fn split(&self, lo: f64, cut: f64, hi: f64, budget: f64, depth: u32, pieces: &mut usize, out: &mut ArclenEstimate) {
        let left = budget * ((cut - lo) / (hi - lo));
        self.piece(lo, cut, left, depth + 1, pieces, out);
        self.piece(cut, hi, (budget - left).max(0.0), depth + 1, pieces, out);
    }

    /// Integrates one piece within `budget` (or the rounding floor, if larger).
    ///
    /// Everything is measured in units of `t` relative to the piece's centre (root offsets
    /// `Z = r − cen`, `E = h²·ε`, `G = h²·(ρ² − 1)`), so that no division by the half-width
    /// `h` is needed. Norms are L1 (`|x| + |y|`) where only an upper bound is needed.
    fn piece(&self, lo: f64, hi: f64, budget: f64, depth: u32, pieces: &mut usize, out: &mut ArclenEstimate) {
        if *pieces == 0 {
            // out of pieces: one Gauss–Kronrod step, with its own error
            let e = crate::arclen::integrate_speed(|t| self.speed(t), lo, hi, f64::INFINITY);
            out.length += e.length;
            out.error += e.error;
            return;
        }
        *pieces -= 1;
        if !(hi > lo) {
            // a cut rounded onto an end (pieces near the smallest numbers): nothing between
            return;
        }
        let cen = 0.5 * (lo + hi);
        let h = 0.5 * (hi - lo);
        // q in the piece's own coordinate z ∈ [−1, 1]: t = cen + h·z
        let d1 = self.b + self.c * (2.0 * cen); // q′(cen)
        let qa = self.a + (self.b + self.c * cen) * cen;
        let qb = d1 * h;
        let qc = self.c * (h * h);
        // bounds |q| on the piece: the scale of the rounding floor
        let size = l1(qa) + l1(qb) + l1(qc);
        let budget = budget.max(1e-14 * 2.0 * h * size);
        if !(size > 0.0) || !size.is_finite() {
            // a constant point (length 0), or non-finite input
            out.length += if size == 0.0 { 0.0 } else { f64::NAN };
            return;
        }
        let nroots = self.nroots;
        if nroots == 0 {
            // constant speed (within rounding): the midpoint rule is exact
            out.length += 2.0 * h * self.speed(cen);
            out.error += 2.0 * h * 1e-14 * size;
            return;
        }
        let h2 = h * h;
        let shift = DVec2::new(cen, 0.0);
        let z = [self.roots[0] - shift, self.roots[1] - shift];

        // Snap near-real roots to the real axis where that is cheap: in the piece's
        // coordinate q = lead·Π(z − rᵢ), and moving r₁ to a real x̂ changes |q| on [−1, 1] by
        // at most lead·|r₁ − x̂|·(1 + |r₂|); the integral and the rule each change by at most
        // twice that, times h. In units of t that is `scale·|Z₁ − X̂|` below.
        let mut penalty = 0.0;
        // of the nearest unsnapped root: A = h²·α² for its ellipse, and the x, y, p, d of
        // `ellipse_terms`
        let mut nearest = (f64::INFINITY, 0.0, 0.0, 0.0, 0.0);
        let mut snapped = [false; 2];
        for i in 0..nroots {
            let (x, y) = (z[i].x, z[i].y.abs());
            let scale = 4.0 * h * self.lead * if nroots == 2 { h + l1(z[1 - i]) } else { 1.0 };
            // snap only roots near the axis (farther ones leave a wide ellipse anyway), and only
            // where that is cheap: both tests are rarely true, so test them together
            if (y < 0.125 * h) & (scale * y <= 0.125 * budget) {
                if x.abs() < h {
                    let cut = cen + x;
                    if cut > lo && cut < hi && depth < MAX_DEPTH {
                        // an (almost) exact cusp inside: cut there
                        self.split(lo, cut, hi, budget, depth, pieces, out);
                        return;
                    }
                    // too near an end to cut: snap it onto that end instead
                    let cost = scale * (y + (h - x.abs()));
                    if cost <= 0.125 * budget {
                        penalty += cost;
                        snapped[i] = true;
                        continue;
                    }
                } else {
                    penalty += scale * y;
                    snapped[i] = true;
                    continue;
                }
            }
            let (p, d, a) = ellipse_terms(x, y, h2);
            // the smaller ellipse is the nearer root's
            nearest = if a < nearest.0 { (a, x, y, p, d) } else { nearest };
        }
        let (a_min, x_near, y_near, p, d) = nearest;

        let remaining = budget - penalty;
        let chosen = if a_min == f64::INFINITY {
            // every root snapped: the speed is ± a polynomial of degree ≤ 2 on the piece
            Some(Choice::EXACT) // RULES[1] = 2 nodes: exact to degree 3
        } else if remaining > 0.0 {
            // h·α, and h·√(α² − 1) = √E: E = 2y²h²/(p + d) for p > 0, else (d − p)/2, so
            // √E = y·h·√(2(p + d))/(p + d) or √(2(d − p))/2; the square roots and the
            // division run side by side
            let h_alpha = a_min.sqrt();
            let r = (2.0 * (p.abs() + d)).sqrt();
            let inv = 1.0 / (p.abs() + d);
            let sqrt_e = if p > 0.0 { y_near * h * r * inv } else { 0.5 * r };
            // G = h²·(ρ² − 1) = 2·h√(α² − 1)·hρ with ρ = α + √(α² − 1)
            let big_g = 2.0 * sqrt_e * (sqrt_e + h_alpha);
            // |q| on the ellipse (in the piece's coordinate, |z| ≤ α there): the Chebyshev form
            // q = d0 + d1·T1 + d2·T2 with |T1| ≤ α and |T2| ≤ 2α² − 1, or the factored form
            // lead·Π(α + |rᵢ|). Both bound |q̄| as well, so √(q·q̄) is below them. With
            // snapped roots only the factored form bounds the snapped function. The factors of
            // h are multiplied out.
            let mut fact = self.lead;
            for (i, r) in z[..nroots].iter().enumerate() {
                fact *= h_alpha + if snapped[i] { r.x.abs() } else { l1(*r) };
            }
            let bound = if snapped[0] || snapped[1] {
                fact
            } else {
                let cheb = l1(qa + qc * 0.5) + l1(d1) * h_alpha + 0.5 * l1(self.c) * (2.0 * a_min - h2);
                cheb.min(fact)
            };
            choose_rule(h, big_g, bound, remaining)
        } else {
            None
        };
        match chosen {
            Some(choice) => {
                out.length += h * gauss::sum_quadratic_modulus(qa, qb, qc, choice.rule);
                out.error += choice.error() + penalty;
            }
            None if depth < MAX_DEPTH => {
                // split towards the nearest unsnapped root
                let cut = cen + x_near.clamp(-0.75 * h, 0.75 * h);
                self.split(lo, cut, hi, budget, depth, pieces, out);
            }
            None => {
                let e = crate::arclen::integrate_speed(|t| self.speed(t), lo, hi, budget);
                out.length += e.length;
                out.error += e.error;
            }
        }
    }
}

/// The smallest rule whose error bound is within `budget`; `None` when 128 nodes would
/// not do.
///
/// The integrand is bounded by `bound` on the Bernstein ellipse with `ρ² − 1 = big_g/h²`
/// (in the piece's coordinate), so by the theorem in [`gauss`] the `m`-point rule's
/// error, times the half-width `h`, is at most `E₁·ρ^(−2(m−1))` with
/// `E₁ = (64/15)·h·bound/(ρ² − 1)`. The rule needs `m − 1 ≥ log2(E₁/budget) / log2(ρ²)`:
/// an upper bound of the numerator over a lower bound of the denominator (both from the
/// floating-point representation, see [`log2_above`], plus `ln(1 + g) ≥ 2g/(2 + g)`), then
/// the next whole number, gives a rule that meets it with no further check. A relative
/// margin of `1e-9`, and absolute ones of `1e-12` in the logarithms, cover the rounding.
#[inline]
fn choose_rule(h: f64, big_g: f64, bound: f64, budget: f64) -> Option<Choice> {
    let h2 = h * h;
    // E₁ = num/G
    let num = (1.0 + 1e-9) * (64.0 / 15.0) * h * bound * h2;
    let den = big_g * budget;
    // below this ρ² − 1 (1e-6) more than 128 nodes are needed anyway; also keeps the
    // logarithms' arguments normal
    if !(big_g >= 1e-6 * h2 && den >= f64::MIN_POSITIVE && (f64::MIN_POSITIVE..f64::MAX).contains(&num)) {
        return None;
    }
    // m − 1 ≥ log_k / l with l ≤ log2(ρ²): for g = ρ² − 1 < 1, l = (2/ln 2)·g/(2 + g);
    // else the difference of the logarithms of h² + G and h². 1/l depends on G only, so its
    // division runs while the bound is computed.
    let small = big_g < h2;
    let p = if small { std::f64::consts::LN_2 * (2.0 * h2 + big_g) } else { 1.0 };
    let q = if small { 2.0 * big_g } else { log2_below(h2 + big_g) - log2_above(h2) };
    let inv_l = p / q;
    let log_k = log2_above(num) - log2_below(den); // ≥ log2(E₁/budget)
    let n = log_k * inv_l;
    if !(n < (gauss::MAX_NODES - 1) as f64) {
        return None;
    }
    // m − 1 = ⌊n⌋ + 1 > n; n < 0 (E₁ < budget) saturates to 0, and the rule has at least 2 nodes
    Some(Choice { rule: gauss::FIRST_RULE[n as usize + 2] as usize, log_k, l_num: q, l_den: p, budget })
}

/// A rule chosen by [`choose_rule`], with what its error bound is computed from.
#[derive(Clone, Copy, Debug)]
struct Choice {
    rule: usize,
    log_k: f64,
    l_num: f64,
    l_den: f64,
    budget: f64,
}

impl Choice {
    /// A rule that is exact (the snapped speed is a polynomial of degree ≤ 2).
    const EXACT: Self = Self { rule: 1, log_k: f64::NEG_INFINITY, l_num: 1.0, l_den: 1.0, budget: 0.0 };

    /// The bound itself, `E₁·ρ^(−2(m−1)) ≤ budget·2^(log_k − (m−1)·l)`, at most the budget.
    /// Computed after the nodes, which do not wait for it.
    #[inline]
    fn error(&self) -> f64 {
        let l = self.l_num / self.l_den;
        (self.budget * exp2_neg_above((gauss::RULES[self.rule] - 1) as f64 * l - self.log_k)).min(self.budget)
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
        for z in [
            DVec2::new(2.0, 0.0),
            DVec2::new(-2.0, 0.0),
            DVec2::new(0.0, -5.0),
            DVec2::new(-1e10, 1e-3),
            DVec2::new(1e-300, -1e-300),
            DVec2::ZERO,
        ] {
            let r = csqrt(z);
            assert!((cmul(r, r) - z).length() <= 4e-16 * z.length(), "{z}");
        }
        // division without overflow or underflow of |b|², at any scale
        for (a, b) in [
            (DVec2::new(1.5, -2.0), DVec2::new(1e-3, 7.0)),
            (DVec2::new(1e-200, 3e-200), DVec2::new(-2e-200, 1e-201)),
            (DVec2::new(1e200, -1e199), DVec2::new(3e200, 4e200)),
            (DVec2::new(1.0, 0.0), DVec2::new(0.0, -1e-170)),
        ] {
            let q = cdiv(a, b);
            assert!((cmul(q, b) - a).length() <= 4e-16 * a.length(), "{a} / {b} = {q}");
        }
    }

    /// `h²·(α² − 1)` from [`ellipse_terms`], as `piece` computes it.
    fn ellipse_e(x: f64, y: f64, h2: f64) -> f64 {
        let (p, d, _) = ellipse_terms(x, y, h2);
        if p > 0.0 { 2.0 * y * y * h2 / (p + d) } else { 0.5 * (d - p) }
    }

    #[test]
    fn ellipse_through_a_point() {
        // on the real axis beyond the foci: α = |x|
        assert!((ellipse_e(3.0, 0.0, 1.0) - 8.0).abs() < 1e-14);
        assert!((ellipse_terms(3.0, 0.0, 1.0).2 - 9.0).abs() < 1e-14);
        // on the imaginary axis: the minor semi-axis is |y|
        assert!((ellipse_e(0.0, 0.5, 1.0) - 0.25).abs() < 1e-15);
        // a general point lies on the ellipse it names, A − h² = E, and scaling x, y, h by s
        // scales A and E by s²
        for (x, y) in [(0.7, 0.2), (-1.0, 1e-9), (0.5, 1e-7), (1.5, 0.0), (2.0, 3.0), (0.0, 1e-3)] {
            let e = ellipse_e(x, y, 1.0);
            let a = ellipse_terms(x, y, 1.0).2;
            assert!((x * x / (1.0 + e) + if y == 0.0 { 0.0 } else { y * y / e } - 1.0).abs() < 1e-14, "{x} {y}");
            assert!((a - 1.0 - e).abs() <= 1e-15 * a, "{x} {y}");
            let s = 0.37;
            let (e_s, a_s) = (ellipse_e(s * x, s * y, s * s), ellipse_terms(s * x, s * y, s * s).2);
            assert!((e_s - s * s * e).abs() <= 1e-14 * e && (a_s - s * s * a).abs() <= 1e-15 * a, "{x} {y}");
        }
        // near the interval: ε ≈ y²/(1 − x²), accurate although far below rounding of 1
        let e = ellipse_e(0.5, 1e-9, 1.0);
        assert!((e / (1e-18 / 0.75) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn log2_bounds() {
        for x in [1.0, 1.5, 2.0, 3.0, 7.9, 1e3, 1.234e17, 0.3, 1e-12, 3e-300, f64::MIN_POSITIVE] {
            let l = f64::log2(x);
            assert!(log2_below(x) <= l && l - log2_below(x) < 0.021, "{x}");
            assert!(log2_above(x) >= l && log2_above(x) - l < 0.029, "{x}");
        }
        // the ratio (log2(1 + f) − f)/(f(1 − f)) stays within [0.2786, 0.4427] on a fine grid,
        // and so the bounds hold at every mantissa (checked with the exponent 0 and 40)
        let n = 1 << 16;
        for i in 0..=n {
            let f = i as f64 / n as f64;
            for e in [0.0, 40.0] {
                let x = (1.0 + f) * f64::exp2(e);
                let l = e + f64::ln_1p(f) / std::f64::consts::LN_2;
                assert!(log2_below(x) <= l && log2_above(x) >= l, "f = {f}, e = {e}");
            }
        }
    }

    #[test]
    fn log_and_power_bounds() {
        // ln(1 + g) ≥ 2g/(2 + g), within a relative g²/12, the lower bound choose_rule uses
        for g in [1e-6, 0.01, 0.3, 0.999] {
            let l = f64::ln_1p(g);
            let b = 2.0 * g / (2.0 + g);
            assert!(b <= l && b >= l * (1.0 - g * g / 12.0), "{g}");
        }
        for y in [0.0f64, 0.25, 0.5, 0.999, 1.0, 3.7, 63.0, 200.5, 1e4] {
            let p = f64::exp2(-y.min(1000.0));
            let b = exp2_neg_above(y);
            assert!(b >= p && b <= 1.07 * p, "{y}: {b} vs {p}");
        }
    }

    /// For `ρ² − 1 = g` and a one-node bound `E₁`, the chosen `m` meets the theorem's
    /// `E₁·ρ^(−2(m−1)) ≤ budget` (checked with `ln_1p`), the estimate lies between that bound
    /// and the budget, and `m` is not far above the least such `m`: across both formulas of
    /// `log2(ρ²)` (`g` below and above 1), at `E₁` just below and above the budget, and at the
    /// 128-node end of the table.
    #[test]
    fn chosen_rule_meets_the_theorem() {
        let (h, budget) = (0.37, 1e-7);
        let mut big_rules = 0;
        for g in [1.0001e-6, 1e-4, 0.01, 0.1, 0.15, 0.2, 0.5, 0.999_999, 1.0, 1.000_001, 2.0, 10.0, 1e3, 1e8] {
            let exact = |e1: f64, m: usize| e1 * f64::exp(-((m - 1) as f64) * f64::ln_1p(g));
            for log_k in [-30.0, -1.0, -1e-9, 0.0, 1e-9, 0.5, 1.0, 7.0, 10.0, 13.2, 20.0, 33.3, 50.0, 100.0, 300.0] {
                let e1 = budget * f64::exp2(log_k);
                // E₁ = (64/15)·h·bound/(ρ² − 1) in the piece's coordinate
                let bound = e1 * g / ((64.0 / 15.0) * h);
                let least = (1..=100_000).find(|&m| exact(e1, m) <= budget).unwrap_or(usize::MAX);
                match choose_rule(h, g * h * h, bound, budget) {
                    Some(choice) => {
                        let (m, e) = (gauss::RULES[choice.rule], choice.error());
                        let want = exact(e1, m);
                        assert!(m >= 2 && want <= budget * (1.0 + 1e-12), "g {g}, log k {log_k}: m = {m}");
                        assert!(e >= want * (1.0 - 1e-12) && e <= budget, "g {g}, log k {log_k}: {e} vs {want}");
                        // the logarithm bounds lose at most 5 % and 0.06 bits
                        let slack = 1.05 * (least.max(2) - 1) as f64 + 0.06 / f64::log2(1.0 + g) + 2.0;
                        let allowed = gauss::RULES[gauss::FIRST_RULE[(slack as usize).min(gauss::MAX_NODES)] as usize];
                        assert!(m <= allowed, "g {g}, log k {log_k}: m = {m}, least {least}");
                        big_rules += usize::from(m > 64);
                    }
                    None => {
                        // only where about 128 nodes or more are needed (or ρ² − 1 < 1e-6)
                        let near_end = least as f64 >= 0.95 * (gauss::MAX_NODES - 1) as f64;
                        let wasteful = 0.06 / f64::log2(1.0 + g) > 100.0 && log_k.abs() < 0.1;
                        assert!(near_end || wasteful, "g {g}, log k {log_k}: none, least {least}");
                    }
                }
            }
        }
        assert!(big_rules >= 2, "the 80–128-node rules are exercised");
    }

    /// A velocity root close to the middle of `[0, 1]` needs the large rules or splits; the
    /// result is within its estimate of an independent adaptive integration, for every
    /// accuracy, and the estimate is within the accuracy.
    #[test]
    fn near_root_meets_its_estimate() {
        for (r1, r2) in [
            (DVec2::new(0.5, 0.03), DVec2::new(2.0, -1.5)),
            (DVec2::new(0.31, 0.004), DVec2::new(0.62, -0.05)),
            (DVec2::new(1.0001, 0.0002), DVec2::new(-0.3, 0.8)),
        ] {
            let lead = DVec2::new(30.0, -70.0);
            // q = lead·(t − r1)(t − r2)
            let (a, b, c) = (cmul(lead, cmul(r1, r2)), -cmul(lead, r1 + r2), lead);
            let q = PlanarSpeed::from_coefficients(a, b, c, 0.0);
            let speed = |t: f64| q.speed(t);
            let cut = r1.x.min(1.0);
            let truth = crate::arclen::integrate_speed(speed, 0.0, cut, 1e-14).length
                + crate::arclen::integrate_speed(speed, cut, 1.0, 1e-14).length;
            for acc in [1e-2, 1e-5, 1e-8, 1e-11] {
                let e = q.arclen(0.0, 1.0, acc);
                let err = (e.length - truth).abs();
                assert!(err <= e.error + 1e-13 * truth, "{r1}: accuracy {acc}: error {err:e} > estimate {:e}", e.error);
                assert!(e.error <= acc, "{r1}: accuracy {acc}: estimate {:e}", e.error);
            }
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
