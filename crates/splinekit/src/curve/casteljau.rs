//! de Casteljau's algorithm on control points of any kind: the points of a [`BezierCurve`]
//! and the homogeneous points `(w·p, w)` of a [`Nurbs`]' rational pieces, each with its own
//! interpolation `lerp(a, b, t)`.
//!
//! [`BezierCurve`]: super::BezierCurve
//! [`Nurbs`]: super::Nurbs

use core::ops::{Add, Mul, Sub};

/// The most control points [`eval`] and [`derivs`] work on in place, on the stack (a
/// [`BezierCurve`]'s most; a [`Nurbs`]' pieces have at most 33): evaluation allocates nothing.
const STACK: usize = super::bezier_n::MAX_BEZIER_POINTS;

/// The point at `t` (`points` not empty; more than [`STACK`] of them are evaluated on the heap).
pub(crate) fn eval<T: Copy>(points: &[T], t: f64, lerp: impl Fn(T, T, f64) -> T) -> T {
    let n = points.len();
    let mut stack = [points[0]; STACK];
    let mut heap = Vec::new();
    let work: &mut [T] = if n <= STACK {
        stack[..n].copy_from_slice(points);
        &mut stack[..n]
    } else {
        heap.extend_from_slice(points);
        &mut heap
    };
    for level in 1..n {
        for i in 0..n - level {
            work[i] = lerp(work[i], work[i + 1], t);
        }
    }
    work[0]
}

/// The point and its first three derivatives at `t` (zero past the degree), from one de
/// Casteljau triangle: with `p` the degree, the `r`-th derivative is `p!/(p − r)!` times the
/// `r`-th forward difference of the triangle's level `p − r` (its `r + 1` points). `points`
/// not empty, at most [`STACK`] of them.
pub(crate) fn derivs<T>(points: &[T], t: f64, lerp: impl Fn(T, T, f64) -> T) -> [T; 4]
where
    T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f64, Output = T>,
{
    debug_assert!(points.len() <= STACK, "{} points", points.len());
    let n = points.len().min(STACK);
    let p = n - 1;
    let mut work = [points[0]; STACK];
    work[..n].copy_from_slice(&points[..n]);
    let mut out = [points[0] * 0.0; 4];
    // down to the level of four points (or fewer, for degrees below 3)
    let mut len = n;
    while len > 4 {
        for i in 0..len - 1 {
            work[i] = lerp(work[i], work[i + 1], t);
        }
        len -= 1;
    }
    loop {
        let r = len - 1;
        let difference = match r {
            0 => work[0],
            1 => work[1] - work[0],
            2 => work[2] - work[1] * 2.0 + work[0],
            _ => work[3] - work[2] * 3.0 + work[1] * 3.0 - work[0],
        };
        let falling: f64 = (0..r).map(|i| (p - i) as f64).product();
        out[r] = difference * falling;
        if r == 0 {
            return out;
        }
        for i in 0..r {
            work[i] = lerp(work[i], work[i + 1], t);
        }
        len -= 1;
    }
}

/// The control points of the halves over `[0, t]` and `[t, 1]`, each reparametrized to
/// `[0, 1]` (`points` not empty).
pub(crate) fn split<T: Copy>(points: &[T], t: f64, lerp: impl Fn(T, T, f64) -> T) -> (Vec<T>, Vec<T>) {
    let n = points.len();
    let mut work = points.to_vec();
    let mut left = Vec::with_capacity(n);
    let mut right = vec![work[n - 1]; n];
    left.push(work[0]);
    for level in 1..n {
        for i in 0..n - level {
            work[i] = lerp(work[i], work[i + 1], t);
        }
        left.push(work[0]);
        right[n - 1 - level] = work[n - 1 - level];
    }
    (left, right)
}

/// The control points of the part over `[t0, t1]`, reparametrized to `[0, 1]` (`t1 < t0`
/// reverses it; values outside `[0, 1]` extrapolate).
pub(crate) fn segment<T: Copy>(points: &[T], t0: f64, t1: f64, lerp: impl Fn(T, T, f64) -> T + Copy) -> Vec<T> {
    if t1 < t0 {
        // the forward part, reversed (splitting forward keeps the parameters in range)
        let mut part = segment(points, t1, t0, lerp);
        part.reverse();
        return part;
    }
    if t0 != 1.0 {
        // [t0, 1] first, then its start up to t1
        let right = split(points, t0, lerp).1;
        split(&right, (t1 - t0) / (1.0 - t0), lerp).0
    } else {
        // t0 = t1 = 1: the end point; [0, t1] then its end from t0/t1 otherwise
        let left = split(points, t1, lerp).0;
        if t1 == 0.0 { left } else { split(&left, t0 / t1, lerp).1 }
    }
}

/// The largest of `value` over the curve (`t ∈ [0, 1]`), to the rounding of the values:
/// branch and bound on the control points, whose values bound a piece's (the convex hull
/// property; for homogeneous points `value` divides by the weight, which is positive).
pub(crate) fn extreme<T: Copy>(points: &[T], value: impl Fn(&T) -> f64, lerp: impl Fn(T, T, f64) -> T + Copy) -> f64 {
    let scale = points.iter().map(|p| value(p).abs()).fold(0.0, f64::max);
    let slack = 8.0 * f64::EPSILON * scale;
    let ends = |p: &[T]| value(&p[0]).max(value(&p[p.len() - 1]));
    let top = |p: &[T]| p.iter().map(&value).fold(f64::NEG_INFINITY, f64::max);
    let mut best = ends(points);
    let mut pending = vec![points.to_vec()];
    // each split halves a piece; 60 levels reach the rounding of t, and only pieces near an
    // extreme are split, so the budget is never met by a polynomial of modelling degree
    let mut budget = 4096;
    while let Some(piece) = pending.pop() {
        if top(&piece) <= best + slack || budget == 0 {
            continue;
        }
        budget -= 1;
        let (a, b) = split(&piece, 0.5, lerp);
        best = best.max(value(&a[a.len() - 1]));
        pending.push(a);
        pending.push(b);
    }
    best
}
