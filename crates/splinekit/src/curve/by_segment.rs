//! Arc length over a range of the curve parameter, summed segment by segment.

use crate::arclen::ArclenEstimate;

/// The arc length of `u ∈ [u0, u1]` as the sum over the segments `k` it covers (of
/// `segments`) of `piece(k, a, b, share)`, where `[a, b]` is the part of `[k, k + 1]` inside
/// the range and `share` the accuracy budget in proportion to its width, so that the total
/// error stays within `accuracy`. `u1 < u0` gives a negative length.
pub(crate) fn arclen_by_segment(
    segments: usize,
    u0: f64,
    u1: f64,
    accuracy: f64,
    piece: impl Fn(usize, f64, f64, f64) -> ArclenEstimate,
) -> ArclenEstimate {
    if u1 < u0 {
        let e = arclen_by_segment(segments, u1, u0, accuracy, piece);
        return ArclenEstimate { length: -e.length, error: e.error };
    }
    let width = u1 - u0;
    if !(width > 0.0) || segments == 0 {
        return ArclenEstimate::default();
    }
    let last = segments - 1;
    let segment = |u: f64| if u > 0.0 { (u.floor() as usize).min(last) } else { 0 };
    let (k0, k1) = (segment(u0), segment(u1));
    let mut total = ArclenEstimate::default();
    for k in k0..=k1 {
        let a = if k == k0 { u0 } else { k as f64 };
        let b = if k == k1 { u1 } else { (k + 1) as f64 };
        if b > a {
            let e = piece(k, a, b, accuracy * ((b - a) / width));
            total.length += e.length;
            total.error += e.error;
        }
    }
    total
}
