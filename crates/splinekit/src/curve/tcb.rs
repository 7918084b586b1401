//! Kochanek–Bartels splines (tension, continuity, bias per key) and Bessel–Overhauser splines
//! (tangents from the parabola through each key and its neighbours, chord-length
//! parameterization): interpolating cubic Hermite splines shaped as Catmull-Rom's.

use crate::curve::piecewise::{chain, check_finite};
use crate::curve::{CubicBezier, PiecewiseCubic, SplineError};
use crate::vector::Vector;

/// The tension `t`, continuity `c` and bias `b` of a Kochanek–Bartels key, each in `[−1, 1]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tcb {
    /// Tension: 1 pulls the tangents to zero (a sharp, tight key), −1 doubles them.
    pub tension: f64,
    /// Continuity: 0 keeps the curve C1 at the key; ±1 make its incoming and outgoing
    /// tangents differ (a corner).
    pub continuity: f64,
    /// Bias: −1 takes the tangent from the next chord, 1 from the previous one.
    pub bias: f64,
}

impl Tcb {
    /// Tension, continuity and bias.
    #[must_use]
    pub const fn new(tension: f64, continuity: f64, bias: f64) -> Self {
        Self { tension, continuity, bias }
    }
}

/// Kochanek–Bartels spline ("TCB"): an interpolating cubic Hermite spline whose tangents at
/// each key are shaped by the key's tension, continuity and bias.
///
/// # Tangents
/// With `d₀ = P(i) − P(i−1)` and `d₁ = P(i+1) − P(i)` and key `i`'s `(t, c, b)`, the tangent
/// arriving at key `i` (ending segment `i−1`) and the one leaving it (starting segment `i`)
/// are, by Kochanek and Bartels (SIGGRAPH 1984):
///
/// - arriving: `(1−t)(1−c)(1+b)/2 · d₀ + (1−t)(1+c)(1−b)/2 · d₁`
/// - leaving: `(1−t)(1+c)(1+b)/2 · d₀ + (1−t)(1−c)(1−b)/2 · d₁`
///
/// so `t = c = b = 0` gives `(P(i+1) − P(i−1))/2` on both sides: the uniform Catmull-Rom
/// spline. Segment `k` is the Bézier `(Pk, Pk + Lk/3, Pk+1 − Ak+1/3, Pk+1)`.
///
/// # Parametrization
/// As [`CatmullRom`](crate::CatmullRom): open, `n ≥ 4` keys and `n − 3` segments from the
/// second key to the second-to-last (the end keys only shape the end tangents); closed,
/// `n ≥ 3` keys and `n` segments from the second key round to it, indices mod n. Each
/// segment takes one unit of `u`.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{KochanekBartels, ParamCurve, Tcb};
/// let keys = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
/// let tight = KochanekBartels::new(&keys, &[Tcb::new(1.0, 0.0, 0.0); 4], false).unwrap().to_piecewise();
/// // tension 1: zero tangents, so the segment is the straight line, traversed with easing
/// assert!((tight.eval(0.5) - DVec2::new(1.0, 0.5)).length() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct KochanekBartels<P> {
    keys: Vec<P>,
    shape: Vec<Tcb>,
    closed: bool,
}

impl<P: Vector> KochanekBartels<P> {
    /// Validates the key count (open ≥ 4, closed ≥ 3), one [`Tcb`] per key, every value in
    /// `[−1, 1]`, and finiteness.
    ///
    /// # Errors
    /// [`SplineError::InsufficientPoints`], [`SplineError::ShapeCount`],
    /// [`SplineError::BadShape`] or [`SplineError::NonFinite`].
    pub fn new(keys: &[P], shape: &[Tcb], closed: bool) -> Result<Self, SplineError> {
        check_interpolating_count("kochanek-bartels", keys.len(), closed)?;
        if shape.len() != keys.len() {
            return Err(SplineError::ShapeCount { points: keys.len(), shapes: shape.len() });
        }
        for (index, s) in shape.iter().enumerate() {
            for (name, value) in [("tension", s.tension), ("continuity", s.continuity), ("bias", s.bias)] {
                if !(-1.0..=1.0).contains(&value) {
                    return Err(SplineError::BadShape { index, name, value });
                }
            }
        }
        check_finite(keys)?;
        Ok(Self { keys: keys.to_vec(), shape: shape.to_vec(), closed })
    }

    /// The keys.
    #[must_use]
    pub fn keys(&self) -> &[P] {
        &self.keys
    }

    /// Each key's tension, continuity and bias.
    #[must_use]
    pub fn shape(&self) -> &[Tcb] {
        &self.shape
    }

    /// Compiles to Bézier segments.
    #[must_use]
    pub fn to_piecewise(&self) -> PiecewiseCubic<P> {
        let n = self.keys.len();
        let key = |i: usize| self.keys[i % n];
        // (arriving, leaving) tangents at key i, from its neighbours
        let tangents = |i: usize| {
            let Tcb { tension: t, continuity: c, bias: b } = self.shape[i % n];
            let (d0, d1) = (key(i) - key(i + n - 1), key(i + 1) - key(i));
            let arriving =
                d0 * ((1.0 - t) * (1.0 - c) * (1.0 + b) / 2.0) + d1 * ((1.0 - t) * (1.0 + c) * (1.0 - b) / 2.0);
            let leaving =
                d0 * ((1.0 - t) * (1.0 + c) * (1.0 + b) / 2.0) + d1 * ((1.0 - t) * (1.0 - c) * (1.0 - b) / 2.0);
            (arriving, leaving)
        };
        let segments = interpolated_segments(n, self.closed)
            .map(|k| {
                let (a, b) = (key(k), key(k + 1));
                CubicBezier::new(a, a + tangents(k).1 * (1.0 / 3.0), b - tangents(k + 1).0 * (1.0 / 3.0), b)
            })
            .collect();
        chain(segments, self.closed)
    }
}

/// Bessel–Overhauser spline: an interpolating cubic Hermite spline over chord-length knots
/// whose tangent at each key is the derivative there of the parabola through the key and its
/// two neighbours.
///
/// # Tangents
/// With chords `Δ₀ = |P(i) − P(i−1)|`, `Δ₁ = |P(i+1) − P(i)|` and the secant directions
/// `v₀ = (P(i) − P(i−1))/Δ₀`, `v₁ = (P(i+1) − P(i))/Δ₁`, the tangent (per unit of chord
/// length) at key `i` is `(Δ₁·v₀ + Δ₀·v₁)/(Δ₀ + Δ₁)`. Segment `k` is the Hermite cubic over
/// its chord `Δ`: the Bézier `(Pk, Pk + Δ·mk/3, Pk+1 − Δ·mk+1/3, Pk+1)`. Points sampled from
/// a smooth curve are interpolated with an error of order `h³` in the spacing `h`.
///
/// A zero chord next to a key takes the tangent from the other chord (both zero: no
/// tangent), and a segment between equal keys is that point: never NaN.
///
/// # Parametrization
/// As [`CatmullRom`](crate::CatmullRom): open, `n ≥ 4` keys and `n − 3` segments from the
/// second key to the second-to-last; closed, `n ≥ 3` keys and `n` segments. Each segment
/// takes one unit of `u` (the chord lengths shape the curve, not its parameter).
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{BesselOverhauser, ParamCurve};
/// // equally spaced points on a line: the parabolas are the line, so is the curve
/// let keys: Vec<DVec2> = (0..5).map(|i| DVec2::new(i as f64, 2.0 * i as f64)).collect();
/// let curve = BesselOverhauser::new(&keys, false).unwrap().to_piecewise();
/// assert!((curve.eval(0.5) - DVec2::new(1.5, 3.0)).length() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BesselOverhauser<P> {
    keys: Vec<P>,
    closed: bool,
}

impl<P: Vector> BesselOverhauser<P> {
    /// Validates the key count (open ≥ 4, closed ≥ 3) and finiteness.
    ///
    /// # Errors
    /// [`SplineError::InsufficientPoints`] or [`SplineError::NonFinite`].
    pub fn new(keys: &[P], closed: bool) -> Result<Self, SplineError> {
        check_interpolating_count("bessel-overhauser", keys.len(), closed)?;
        check_finite(keys)?;
        Ok(Self { keys: keys.to_vec(), closed })
    }

    /// The keys.
    #[must_use]
    pub fn keys(&self) -> &[P] {
        &self.keys
    }

    /// Compiles to Bézier segments.
    #[must_use]
    pub fn to_piecewise(&self) -> PiecewiseCubic<P> {
        let n = self.keys.len();
        let key = |i: usize| self.keys[i % n];
        // the unit-speed tangent at key i
        let tangent = |i: usize| {
            let (c0, c1) = (key(i) - key(i + n - 1), key(i + 1) - key(i));
            let (l0, l1) = (c0.length(), c1.length());
            match (l0 > 0.0, l1 > 0.0) {
                (true, true) => (c0 * (l1 / l0) + c1 * (l0 / l1)) * (1.0 / (l0 + l1)),
                (true, false) => c0 * (1.0 / l0),
                (false, true) => c1 * (1.0 / l1),
                (false, false) => P::ZERO,
            }
        };
        let segments = interpolated_segments(n, self.closed)
            .map(|k| {
                let (a, b) = (key(k), key(k + 1));
                let chord = (b - a).length();
                CubicBezier::new(a, a + tangent(k) * (chord / 3.0), b - tangent(k + 1) * (chord / 3.0), b)
            })
            .collect();
        chain(segments, self.closed)
    }
}

/// At least 4 keys for an open curve, 3 for a closed one.
fn check_interpolating_count(kind: &'static str, given: usize, closed: bool) -> Result<(), SplineError> {
    let needed = if closed { 3 } else { 4 };
    if given < needed { Err(SplineError::InsufficientPoints { kind, needed, given }) } else { Ok(()) }
}

/// The first key of each segment: from the second key, as Catmull-Rom's windows, to the
/// second-to-last (open: `n − 3` segments) or around all `n` (closed; indices mod n).
fn interpolated_segments(n: usize, closed: bool) -> std::ops::Range<usize> {
    if closed { 1..n + 1 } else { 1..n - 2 }
}

#[cfg(test)]
mod tests {
    use glam::DVec2;

    use super::*;
    use crate::{CatmullRom, ParamCurve};

    #[test]
    fn zero_tcb_is_uniform_catmull_rom() {
        let keys: Vec<DVec2> = (0..7).map(|i| DVec2::new(i as f64, ((i * i) % 5) as f64 - 2.0)).collect();
        for closed in [false, true] {
            let kb = KochanekBartels::new(&keys, &[Tcb::default(); 7], closed).unwrap().to_piecewise();
            let cr = CatmullRom::new(&keys, closed, 0.0).unwrap().to_piecewise();
            assert_eq!(kb.num_segments(), cr.num_segments());
            for (a, b) in kb.segments().iter().zip(cr.segments()) {
                for (p, q) in [(a.p0, b.p0), (a.p1, b.p1), (a.p2, b.p2), (a.p3, b.p3)] {
                    assert!((p - q).length() <= 1e-15 * 8.0, "{p} {q}");
                }
            }
        }
    }
}
