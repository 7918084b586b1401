//! The nearest point of a curve against independent references: brute force (dense samples
//! refined by golden-section search around each of the best few), closed forms for circles
//! and helices, and curves built so that a local search from the wrong place finds the wrong
//! minimum.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use splinekit::{AnyCurve, BezierSpline, Circle, Helix, ParamCurve, Trefoil, Vector};

/// The smallest distance from `q` to the curve by brute force: `per_segment` samples per
/// unit of `u`, then golden-section search on the two sample steps around each of the eight
/// best samples. An upper bound of the true minimum, and close to it once the samples are
/// denser than the curve's features.
fn brute_force<P: Vector, C: ParamCurve<P>>(curve: &C, q: P, per_segment: usize) -> f64 {
    let (lo, hi) = curve.domain();
    let n = per_segment * curve.num_segments();
    let step = (hi - lo) / n as f64;
    let dist = |u: f64| (curve.eval(u.clamp(lo, hi)) - q).length();
    let mut samples: Vec<(f64, f64)> = (0..=n).map(|i| (dist(lo + step * i as f64), lo + step * i as f64)).collect();
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best = samples[0].0;
    for &(_, u) in samples.iter().take(8) {
        let (mut a, mut b) = ((u - step).max(lo), (u + step).min(hi));
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..80 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if dist(c) < dist(d) {
                b = d;
            } else {
                a = c;
            }
        }
        best = best.min(dist(0.5 * (a + b)));
    }
    best
}

/// What every answer must satisfy: the point is the curve's at `u`, the distance is its
/// distance, the proved gap is within the accuracy, and no sample of the brute force is
/// nearer by more than the accuracy.
fn check<P: Vector, C: ParamCurve<P>>(curve: &C, q: P, accuracy: f64, reference: f64) -> splinekit::Nearest<P> {
    let n = curve.nearest(q, accuracy);
    let (lo, hi) = curve.domain();
    assert!(n.u >= lo && n.u <= hi, "u = {} outside [{lo}, {hi}]", n.u);
    assert_eq!(n.point, curve.eval(n.u));
    assert_eq!(n.distance, (n.point - q).length());
    assert!(n.error <= accuracy, "proved gap {} > accuracy {accuracy}", n.error);
    assert!(n.distance <= reference + accuracy, "distance {} > brute force {reference} + {accuracy}", n.distance);
    n
}

fn point2() -> impl Strategy<Value = DVec2> {
    (-10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y)| DVec2::new(x, y))
}

fn point3() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A Bézier chain of the first `3m + 1` points against brute force at accuracy 10^-digits.
fn chain_case<P: Vector>(points: &[P], q: P, digits: i32) {
    let m = (points.len() - 1) / 3;
    let curve = BezierSpline::new(&points[..=3 * m], false).unwrap().to_piecewise();
    check(&curve, q, 10f64.powi(-digits), brute_force(&curve, q, 4000));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random Bézier chains in the plane (often looping, with cusps and several near-equal
    /// local minima), random query points, accuracy from 1e-3 to 1e-11.
    #[test]
    fn planar_chains_agree_with_brute_force(
        points in prop::collection::vec(point2(), 4..=13),
        q in point2(),
        digits in 3..=11i32,
    ) {
        chain_case(&points, q, digits);
    }

    #[test]
    fn space_chains_agree_with_brute_force(
        points in prop::collection::vec(point3(), 4..=10),
        q in point3(),
        digits in 3..=11i32,
    ) {
        chain_case(&points, q, digits);
    }

    /// Exact curves: the circle's nearest distance is `|‖q‖ − r|` in closed form.
    #[test]
    fn circles_give_the_closed_form(r in 0.01..100.0f64, q in point2()) {
        prop_assume!(q.length() > 1e-6);
        let n = check::<DVec2, _>(&Circle::new(r), q, 1e-10, (q.length() - r).abs());
        prop_assert!((n.distance - (q.length() - r).abs()).abs() <= 1e-10);
    }

    #[test]
    fn helices_and_trefoils_agree_with_brute_force(
        r in 0.1..5.0f64,
        pitch in -3.0..3.0f64,
        turns in 0.25..6.0f64,
        size in 0.1..5.0f64,
        q in point3(),
    ) {
        let helix = Helix::new(r, pitch, turns);
        check::<DVec3, _>(&helix, q, 1e-9, brute_force::<DVec3, _>(&helix, q, 20000));
        let knot = Trefoil::new(size);
        check::<DVec3, _>(&knot, q, 1e-9, brute_force::<DVec3, _>(&knot, q, 20000));
    }
}

/// A wave with two dips of almost equal depth: the one nearer the start is 7.5e-7
/// shallower, so a local search started at the start finds it, and the answer must be the
/// other.
#[test]
fn the_global_minimum_wins_over_a_local_one_nearly_as_deep() {
    // segment k dips to y = (2 − 6·depth)/8 at its middle
    let (shallow, deep) = (1.0 - 1e-6, 1.0);
    let points = [
        DVec2::new(-3.0, 1.0),
        DVec2::new(-2.5, -shallow),
        DVec2::new(-0.5, -shallow),
        DVec2::new(0.0, 1.0),
        DVec2::new(0.5, -deep),
        DVec2::new(2.5, -deep),
        DVec2::new(3.0, 1.0),
    ];
    let curve = BezierSpline::new(&points, false).unwrap().to_piecewise();
    let q = DVec2::new(0.0, -5.0);
    let n = check(&curve, q, 1e-12, brute_force(&curve, q, 200_000));
    assert!(n.u > 1.0, "found the shallower dip at u = {}", n.u);
}

/// Every point of a circle is as near to its centre as any other: the search must still
/// stop within its work bound, with the radius as the distance; where the bound cuts it
/// short (1e-13 needs about 10⁷ intervals), the gap it proved is what it says.
#[test]
fn the_centre_of_a_circle_is_answered_within_the_work_bound() {
    for accuracy in [1e-3, 1e-9, 1e-13] {
        let n = Circle::new(2.0).nearest(DVec2::ZERO, accuracy);
        assert!((n.distance - 2.0).abs() <= 1e-14, "{accuracy}: {}", n.distance);
        if accuracy >= 1e-9 {
            assert!(n.error <= accuracy, "{accuracy}: proved {}", n.error);
        } else {
            // cut short: the proved gap is honest (the true gap is 0 here) and small
            assert!(n.error > accuracy && n.error < 1e-9, "{accuracy}: proved {}", n.error);
        }
    }
}

/// Points on the curve are found at distance 0 (to rounding), also on closed chains where
/// the parameter wraps, and the same call gives the same bits.
#[test]
fn points_on_the_curve_are_found_and_answers_repeat() {
    let points = [DVec3::ZERO, DVec3::new(1.0, 2.0, 0.0), DVec3::new(3.0, -1.0, 1.0), DVec3::new(4.0, 0.0, 0.0)];
    let chain: AnyCurve<DVec3> = AnyCurve::Piecewise(BezierSpline::new(&points, false).unwrap().to_piecewise());
    for u in [0.0, 0.1, 0.37, 0.5, 0.99, 1.0] {
        let q = chain.eval(u);
        let n = chain.nearest(q, 1e-12);
        assert!(n.distance <= 1e-12, "u = {u}: {}", n.distance);
        assert_eq!(n, chain.nearest(q, 1e-12));
    }
    let knot: AnyCurve<DVec3> = AnyCurve::Trefoil(Trefoil::new(1.0));
    let q = knot.eval(0.3) + DVec3::new(0.0, 0.0, 1e-3);
    let n = knot.nearest(q, 1e-12);
    assert!(n.distance <= 1e-3 + 1e-12);
    let helix = Helix::new(1.0, 0.0, 1.0);
    assert!((ParamCurve::<DVec3>::nearest(&helix, DVec3::new(2.0, 0.0, 0.0), 1e-12).distance - 1.0).abs() < 1e-12);
}

/// A chain that jumps where its first segment ends: the first segment's end (its limit, not
/// the second segment's start at the same parameter) is the nearest place.
#[test]
fn a_jump_between_segments_is_not_bridged() {
    let line = |a: DVec2, b: DVec2| splinekit::CubicBezier::new(a, a.lerp(b, 1.0 / 3.0), a.lerp(b, 2.0 / 3.0), b);
    let chain = splinekit::PiecewiseCubic::new(
        vec![line(DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0)), line(DVec2::new(5.0, 3.0), DVec2::new(6.0, 3.0))],
        false,
    )
    .unwrap();
    let q = DVec2::new(1.2, 0.0);
    let n = chain.nearest(q, 1e-9);
    assert!((n.distance - 0.2).abs() <= 1e-9, "{n:?}");
    assert!(n.u < 1.0 && n.u > 1.0 - 1e-6, "{n:?}");
    // and a point between the pieces is not near the chord that would join them
    let n = chain.nearest(DVec2::new(3.0, 1.5), 1e-9);
    assert!((n.distance - DVec2::new(2.0, 1.5).length()).abs() <= 1e-9, "{n:?}");
}
