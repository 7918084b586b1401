//! Arc length: quadrature tables, adaptive arc length to a stated accuracy, inverse
//! arc length, and resampling by arc length (`s(u)`: the distance along the curve from `u = 0`).
//!
//! # Accuracy
//! Every adaptive function takes `accuracy`: a bound, in length units, on the absolute
//! error of the length (or, for the inverse, on `|s(u) − s|` at the returned `u`).
//! Values at or below the rounding level of the computation (about `1e-14` times the
//! length) cannot be met; they are clamped to that level.
//!
//! # Method
//! Planar cubic segments (every 2D curve, and 3D segments whose velocity lies in a plane)
//! choose their Gauss–Legendre rule from a rigorous error bound: the speed is analytic up
//! to the complex roots of the velocity, and the Bernstein ellipse through the nearest one
//! bounds the quadrature error before any node is evaluated (`arclen/planar.rs`). Other
//! segments use the adaptive integrator below.
//!
//! [`integrate_speed`] integrates the speed `|P′(t)|` with the 15-point Gauss–Kronrod
//! rule (the 7-point Gauss rule embedded), bisecting any interval where the two rules
//! differ by more than its share of the budget. The share halves with each bisection, so
//! the accepted differences sum to at most `accuracy`. Their sum is reported as the error
//! estimate; it is conservative (the Kronrod value returned is far more accurate than the
//! Gauss value the difference measures). Cost grows with `log(1/accuracy)` per
//! non-smooth point (cusps, where the speed has a kink) and very slowly elsewhere.

mod gauss;
mod gauss_tables;
pub(crate) mod planar;

use crate::curve::ParamCurve;
use crate::vector::Vector;

/// Default accuracy for arc-length computations, in length units.
pub const DEFAULT_ACCURACY: f64 = 1e-9;

/// Bisection depth limit for the adaptive integrator (intervals of width `2^-48`).
const MAX_DEPTH: u32 = 48;

/// The most Gauss–Kronrod intervals one integral is split into. Bisection stops there, so an
/// integral takes at most about 250 000 speed evaluations whatever the curve and the accuracy
/// asked; the error estimate then tells what was reached (more than asked). Smooth curves
/// need a handful of intervals, a cusp a few hundred; rounding noise in the speed (a curve
/// with coordinates far larger than its detail, say `1e8` beside `1`) stops bisection where
/// halving no longer shrinks the error (from the sixth halving on, where the two halves keep
/// three quarters of the error or more), so only an accuracy below the rounding level of a
/// curve's length over a long range meets the limit.
pub const MAX_INTERVALS: usize = 1 << 14;

/// The depth from which [`adapt`] stops where halving does not shrink the error estimate
/// below [`NOISE_RATIO`] of it: rounding noise, not a feature of the curve.
const NOISE_DEPTH: u32 = 6;
/// See [`NOISE_DEPTH`]: a smooth speed's error falls by orders of magnitude when an interval
/// is halved, a kink's (a cusp) to about a quarter, a jump's to about a half.
const NOISE_RATIO: f64 = 0.75;

/// The smallest accuracy an integral is refined for, relative to `∫|speed|`: an absolute
/// accuracy below this cannot be met in `f64` arithmetic, so asking for less stops here.
pub const RELATIVE_FLOOR: f64 = 1e-15;

/// The smallest accuracy an inverse query ([`ArclenIndex::u_at`]) asks of its root finder,
/// relative to the curve's length: ten times [`RELATIVE_FLOOR`], so that the integrals of its
/// steps (each within `RELATIVE_FLOOR` of its own length) can meet their share and the root
/// finder converges instead of stopping at its first step.
pub const QUERY_FLOOR: f64 = 10.0 * RELATIVE_FLOOR;

/// A length with an estimate of its absolute error.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ArclenEstimate {
    /// The computed length.
    pub length: f64,
    /// Estimated absolute error (conservative: the sum of the Gauss–Kronrod differences
    /// of the accepted intervals).
    pub error: f64,
}

// 15-point Kronrod nodes (positive half, descending) and weights, with the weights of the
// embedded 7-point Gauss rule (on the odd-indexed nodes). Values from QUADPACK `dqk15`.
const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];
const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];
const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// One Gauss–Kronrod 7/15 step on `[a, b]`: `(kronrod, |kronrod − gauss|, ∫|f|)`.
///
/// The difference is used as the error estimate *unscaled*: conservative, since the Kronrod
/// value returned is far more accurate than the Gauss value it is compared with. (QUADPACK
/// scales it as `resasc·(200·|K−G|/resasc)^1.5`; that is faster but a heuristic, not
/// adopted here without evidence that it holds on cusps.)
#[inline]
fn gk15<F: Fn(f64) -> f64>(f: &F, a: f64, b: f64) -> (f64, f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = fc * WGK[7];
    let mut g = fc * WG[3];
    let mut abs = fc.abs() * WGK[7];
    for j in 0..7 {
        let dx = h * XGK[j];
        let (f1, f2) = (f(c - dx), f(c + dx));
        k += WGK[j] * (f1 + f2);
        abs += WGK[j] * (f1.abs() + f2.abs());
        if j % 2 == 1 {
            g += WG[j / 2] * (f1 + f2);
        }
    }
    (k * h, ((k - g) * h).abs(), abs * h.abs())
}

/// Integrates a speed function `|P′(t)|` over `[a, b]` to within `accuracy` (absolute).
///
/// Adaptive Gauss–Kronrod 7/15 (see the module docs). `b < a` gives a negative length
/// with the same error bound. Non-finite or non-positive `accuracy` asks for the best
/// the rounding level allows.
#[must_use]
pub fn integrate_speed<F: Fn(f64) -> f64>(speed: F, a: f64, b: f64, accuracy: f64) -> ArclenEstimate {
    if !(a != b) || !a.is_finite() || !b.is_finite() {
        return ArclenEstimate::default();
    }
    let (k, err, abs) = gk15(&speed, a, b);
    let floor = RELATIVE_FLOOR * abs;
    let tol = if accuracy > floor { accuracy } else { floor };
    let mut out = ArclenEstimate::default();
    let mut left = MAX_INTERVALS;
    adapt(&speed, a, b, (k, err, abs), tol, 0, &mut left, &mut out);
    out
}

/// Refines `[a, b]` depth first; `left` counts the intervals the integral may still be split
/// into ([`MAX_INTERVALS`] in all).
#[allow(clippy::too_many_arguments)]
fn adapt<F: Fn(f64) -> f64>(
    f: &F,
    a: f64,
    b: f64,
    (k, err, abs): (f64, f64, f64),
    tol: f64,
    depth: u32,
    left: &mut usize,
    out: &mut ArclenEstimate,
) {
    // Accept within budget, at the rounding floor, at the depth or work limit, or on
    // non-finite values (which no bisection would fix).
    if err <= tol || err <= 1e-14 * abs || depth >= MAX_DEPTH || *left < 2 || !err.is_finite() {
        out.length += k;
        out.error += err;
        return;
    }
    *left -= 2;
    let m = 0.5 * (a + b);
    let lower = gk15(f, a, m);
    let upper = gk15(f, m, b);
    // Rounding noise in the speed: halving no longer shrinks the error (a smooth speed's
    // drops by orders of magnitude, a kink's or a jump's by at least half), so no bisection
    // will; keep the halves' estimate and stop, instead of running to the interval limit.
    if depth >= NOISE_DEPTH && lower.1 + upper.1 >= NOISE_RATIO * err {
        out.length += lower.0 + upper.0;
        out.error += lower.1 + upper.1;
        return;
    }
    adapt(f, a, m, lower, 0.5 * tol, depth + 1, left, out);
    adapt(f, m, b, upper, 0.5 * tol, depth + 1, left, out);
}

/// Finds `t ∈ [t_lo, t_hi]` with `|∫_{t_lo}^{t} speed − s| ≤ accuracy` (the integral taken
/// exactly). `integrate(t0, t1, accuracy)` must return the integral of `speed` over
/// `[t0, t1]` (signed, for `t1 < t0`) within its accuracy argument. `s` is clamped to
/// `[0, total]`, where `total` is the integral over the whole range.
///
/// Newton's method on `L(t) − s` with a bisection fallback inside a bracket; `L` is kept up
/// to date by integrating only the step taken. Half the budget bounds the integration
/// errors (the first integral takes `accuracy/4`, each later step half the previous
/// share), the other half the final residual. For `t_hi ≤ t_lo` the result is `t_lo`.
#[must_use]
pub fn solve_arclen<I, F>(integrate: I, speed: F, t_lo: f64, t_hi: f64, s: f64, accuracy: f64) -> f64
where
    I: Fn(f64, f64, f64) -> ArclenEstimate,
    F: Fn(f64) -> f64,
{
    if !(s > 0.0) || !(t_hi > t_lo) {
        return t_lo;
    }
    let acc = if accuracy > 0.0 { accuracy } else { 0.0 };
    let total = integrate(t_lo, t_hi, 0.25 * acc);
    if s >= total.length {
        return t_hi;
    }
    let (mut lo, mut hi) = (t_lo, t_hi);
    let mut t = t_lo + (t_hi - t_lo) * (s / total.length);
    let first = integrate(t_lo, t, 0.25 * acc);
    let mut len = first.length;
    // Each integral is charged its full budget (or its estimate, if larger), so the stopping
    // rule below holds without trusting the estimates to be bounds.
    let mut err_sum = first.error.max(0.25 * acc);
    let mut budget = 0.125 * acc;
    for _ in 0..200 {
        let r = len - s;
        if r.abs() <= acc - err_sum {
            return t;
        }
        if r < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        if !(hi - lo > 4.0 * f64::EPSILON * (hi.abs() + lo.abs())) {
            return t;
        }
        let newton = t - r / speed(t);
        let next = if newton.is_finite() && newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        let step = integrate(t, next, budget);
        len += step.length;
        err_sum += step.error.max(budget);
        budget *= 0.5;
        t = next;
        // the integrals cannot meet the accuracy (rounding in the curve, or an accuracy below
        // the length's rounding level): no later step can, so stop with the best `t`
        if err_sum >= acc {
            return t;
        }
    }
    t
}

/// A length bound for relative accuracy: the chord-polygon length (never more than the
/// true length), from `samples` points per segment.
#[must_use]
pub fn chord_lower_bound<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, samples: usize) -> f64 {
    let (a, b) = curve.domain();
    let n = (samples.max(1) * curve.num_segments()).max(1);
    let mut prev = curve.eval(a);
    let mut len = 0.0;
    for i in 1..=n {
        let p = curve.eval(a + (b - a) * (i as f64 / n as f64));
        len += p.distance(prev);
        prev = p;
    }
    len
}

/// Arc length to a *relative* accuracy: the error is at most `relative × true length`.
/// The absolute budget is `relative` times the chord-polygon length (a lower bound of the
/// true length), so the guarantee holds.
#[must_use]
pub fn arclen_relative<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, relative: f64) -> ArclenEstimate {
    let lower = chord_lower_bound(curve, 8);
    let (a, b) = curve.domain();
    curve.arclen_range(a, b, relative * lower)
}

/// Which quadrature an [`ArclenTable`] uses per interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TableMethod {
    /// Straight-line distance between consecutive samples (a lower bound of the length).
    Chord,
    /// 3-point Gauss–Legendre on each interval: `(uB−uA)/2 · Σ wᵢ |P′(…)|`,
    /// nodes `(−√(3/5), 0, √(3/5))`, weights `(5/9, 8/9, 5/9)`.
    Gauss3,
}

/// The u–s table (arc length `s` at parameter `u`): `N` samples per segment, rows `u = k + i/N`,
/// row 0 is `(0, 0)`; a curve of m segments has `N·m + 1` rows.
#[derive(Clone, Debug, PartialEq)]
pub struct ArclenTable {
    method: TableMethod,
    samples_per_segment: usize,
    u: Vec<f64>,
    s: Vec<f64>,
}

impl ArclenTable {
    /// Builds the table (`samples_per_segment` is taken as at least 1).
    #[must_use]
    pub fn new<P: Vector, C: ParamCurve<P> + ?Sized>(
        curve: &C,
        method: TableMethod,
        samples_per_segment: usize,
    ) -> Self {
        let n = samples_per_segment.max(1);
        let rows = n * curve.num_segments() + 1;
        let mut u = Vec::with_capacity(rows);
        let mut s = Vec::with_capacity(rows);
        let x = (3.0f64 / 5.0).sqrt();
        let (w0, w1) = (5.0 / 9.0, 8.0 / 9.0);
        let mut total = 0.0;
        let mut prev = curve.eval(0.0);
        u.push(0.0);
        s.push(0.0);
        for i in 1..rows {
            let (ua, ub) = ((i - 1) as f64 / n as f64, i as f64 / n as f64);
            let inc = match method {
                TableMethod::Chord => {
                    let p = curve.eval(ub);
                    let d = p.distance(prev);
                    prev = p;
                    d
                }
                TableMethod::Gauss3 => {
                    let (h, c) = (0.5 * (ub - ua), 0.5 * (ua + ub));
                    let speed = |y: f64| curve.deriv(c + h * y).length();
                    h * (w0 * speed(-x) + w1 * speed(0.0) + w0 * speed(x))
                }
            };
            total += inc;
            u.push(ub);
            s.push(total);
        }
        Self { method, samples_per_segment: n, u, s }
    }

    /// Chord-method table.
    #[must_use]
    pub fn chord<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, samples_per_segment: usize) -> Self {
        Self::new(curve, TableMethod::Chord, samples_per_segment)
    }

    /// 3-point Gauss–Legendre table.
    #[must_use]
    pub fn gauss3<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, samples_per_segment: usize) -> Self {
        Self::new(curve, TableMethod::Gauss3, samples_per_segment)
    }

    /// The quadrature used.
    #[must_use]
    pub fn method(&self) -> TableMethod {
        self.method
    }

    /// Samples per segment.
    #[must_use]
    pub fn samples_per_segment(&self) -> usize {
        self.samples_per_segment
    }

    /// Number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.u.len()
    }

    /// Never true (row 0 always exists); here for API completeness.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.u.is_empty()
    }

    /// The rows `(u, s)`.
    pub fn iter_rows(&self) -> impl ExactSizeIterator<Item = (f64, f64)> + '_ {
        self.u.iter().copied().zip(self.s.iter().copied())
    }

    /// The last row's `s`: the table's total length.
    #[must_use]
    pub fn length(&self) -> f64 {
        *self.s.last().unwrap_or(&0.0)
    }

    /// `u(s)` from the table: binary search for the two rows bracketing `s`, then linear
    /// interpolation `α = (s−s0)/(s1−s0)`, `u = (1−α)u0 + αu1`. Clamped to the table's range;
    /// in a run of equal `s` (a zero-length piece) the first such row is returned.
    #[must_use]
    pub fn u_at(&self, s: f64) -> f64 {
        let last = self.u.len() - 1;
        if !(s > 0.0) {
            return self.u[0];
        }
        if s >= self.s[last] {
            return self.u[last];
        }
        // first row with s_row >= s (exists: s < s[last])
        let i1 = self.s.partition_point(|&x| x < s);
        if i1 == 0 {
            return self.u[0];
        }
        let i0 = i1 - 1;
        let (s0, s1) = (self.s[i0], self.s[i1]);
        let alpha = if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 };
        (1.0 - alpha) * self.u[i0] + alpha * self.u[i1]
    }
}

/// Prefix arc lengths at every segment boundary, for exact inverse queries on a curve.
///
/// Built once to half the accuracy (spread over the segments by parameter width); each
/// [`ArclenIndex::u_at`] query solves inside one segment with the other half, so every
/// answer `u` satisfies `|s_true(u) − s| ≤ accuracy`.
#[derive(Clone, Debug, PartialEq)]
pub struct ArclenIndex {
    prefix: Vec<f64>,
    accuracy: f64,
    /// The sum of the segments' error estimates.
    error: f64,
}

impl ArclenIndex {
    /// Computes the prefix lengths of `curve` for queries to within `accuracy`.
    #[must_use]
    pub fn new<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, accuracy: f64) -> Self {
        let m = curve.num_segments();
        let share = 0.5 * accuracy / m as f64;
        let mut prefix = Vec::with_capacity(m + 1);
        prefix.push(0.0);
        let mut total = 0.0;
        let mut error = 0.0;
        for k in 0..m {
            let e = curve.arclen_range(k as f64, (k + 1) as f64, share);
            total += e.length;
            error += e.error;
            prefix.push(total);
        }
        Self { prefix, accuracy, error }
    }

    /// The estimated error of the total length: at most half the accuracy, unless the
    /// accuracy cannot be met (below the length's rounding level, about `1e-15` of it, or
    /// rounding noise in a curve whose coordinates dwarf its detail); then queries are as
    /// close as the length allows, not within the accuracy.
    #[must_use]
    pub fn error(&self) -> f64 {
        self.error
    }

    /// Whether the length (and so every query) meets the accuracy asked.
    #[must_use]
    pub fn meets_accuracy(&self) -> bool {
        self.error <= 0.5 * self.accuracy
    }

    /// Total length (within half the accuracy).
    #[must_use]
    pub fn length(&self) -> f64 {
        *self.prefix.last().unwrap_or(&0.0)
    }

    /// The accuracy the index was built for.
    #[must_use]
    pub fn accuracy(&self) -> f64 {
        self.accuracy
    }

    /// `u` such that `|s_true(u) − s| ≤ accuracy`; `s` is clamped to `[0, length]`. An
    /// accuracy below what `f64` resolves (below `2·error` when
    /// [`meets_accuracy`](Self::meets_accuracy) is false, or below [`QUERY_FLOOR`] times the
    /// length) is raised to it: asking the root finder for more made every integral near a
    /// cusp run to its interval limit, a quarter of a second a query, and stopped the root
    /// finder after its first step, far from the answer (issue #38).
    #[must_use]
    pub fn u_at<P: Vector, C: ParamCurve<P> + ?Sized>(&self, curve: &C, s: f64) -> f64 {
        let m = self.prefix.len() - 1;
        if !(s > 0.0) {
            return 0.0;
        }
        if s >= self.length() {
            return m as f64;
        }
        // segment k with prefix[k] <= s < prefix[k+1]
        let k = (self.prefix.partition_point(|&x| x <= s) - 1).min(m - 1);
        let base = k as f64;
        let local = s - self.prefix[k];
        let t = solve_arclen(
            |t0, t1, acc| curve.arclen_range(base + t0, base + t1, acc),
            |t| curve.deriv(base + t).length(),
            0.0,
            1.0,
            local,
            0.5 * self.accuracy.max(2.0 * self.error).max(QUERY_FLOOR * self.length()),
        );
        base + t
    }
}

/// Exact inverse arc length of a curve: `u` with `|s_true(u) − s| ≤ accuracy`
/// (`s` clamped to `[0, length]`). For many queries build an [`ArclenIndex`] once.
#[must_use]
pub fn inv_arclen<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, s: f64, accuracy: f64) -> f64 {
    ArclenIndex::new(curve, accuracy).u_at(curve, s)
}

/// A point found by arc length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPoint<P> {
    /// Requested arc length from the start.
    pub s: f64,
    /// Parameter where the curve reaches it.
    pub u: f64,
    /// Position there.
    pub point: P,
}

/// Why a resampling request was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ResampleError {
    /// Spacing not a positive finite number.
    #[error("spacing must be a positive number, got {0}")]
    BadSpacing(f64),
    /// The request would produce more points than the stated limit.
    #[error("spacing {spacing} on a curve of length {length} gives more than {limit} points")]
    TooManyPoints {
        /// The spacing asked for.
        spacing: f64,
        /// The curve's length.
        length: f64,
        /// The limit.
        limit: usize,
    },
}

/// Points at `s = 0, ds, 2·ds, …` up to the curve's length (the end point is included only
/// when the length is a multiple of `ds`), each with `|s_true(u) − s| ≤ accuracy`.
/// Refuses more than `max_points` points.
pub fn resample_every<P: Vector, C: ParamCurve<P> + ?Sized>(
    curve: &C,
    ds: f64,
    accuracy: f64,
    max_points: usize,
) -> Result<Vec<ArcPoint<P>>, ResampleError> {
    if !(ds > 0.0) || !ds.is_finite() {
        return Err(ResampleError::BadSpacing(ds));
    }
    let index = ArclenIndex::new(curve, accuracy);
    let length = index.length();
    let count = (length / ds + 1e-9).floor() + 1.0;
    if !(count <= max_points as f64) {
        return Err(ResampleError::TooManyPoints { spacing: ds, length, limit: max_points });
    }
    Ok((0..count as usize)
        .map(|i| {
            let s = (i as f64 * ds).min(length);
            let u = index.u_at(curve, s);
            ArcPoint { s, u, point: curve.eval(u) }
        })
        .collect())
}

/// `k + 1` points that cut the curve into `k` pieces of equal arc length (the first at the
/// start, the last at the end), each with `|s_true(u) − s| ≤ accuracy`. `k = 0` is taken as 1.
#[must_use]
pub fn resample_equal<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, k: usize, accuracy: f64) -> Vec<ArcPoint<P>> {
    let k = k.max(1);
    let index = ArclenIndex::new(curve, accuracy);
    let length = index.length();
    (0..=k)
        .map(|i| {
            let s = length * (i as f64 / k as f64);
            let u = if i == k { curve.domain().1 } else { index.u_at(curve, s) };
            ArcPoint { s, u, point: curve.eval(u) }
        })
        .collect()
}
