//! de Casteljau's algorithm on control points of any kind: the points of a [`BezierCurve`]
//! and the homogeneous points `(w·p, w)` of a [`Nurbs`]' rational pieces, each with its own
//! interpolation `lerp(a, b, t)`.
//!
//! [`BezierCurve`]: super::BezierCurve
//! [`Nurbs`]: super::Nurbs

/// The point at `t` (`points` not empty).
pub(crate) fn eval<T: Copy>(points: &[T], t: f64, lerp: impl Fn(T, T, f64) -> T) -> T {
    let mut work = points.to_vec();
    let n = work.len();
    for level in 1..n {
        for i in 0..n - level {
            work[i] = lerp(work[i], work[i + 1], t);
        }
    }
    work[0]
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
