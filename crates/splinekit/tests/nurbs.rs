//! NURBS against independent references: the Cox–de Boor basis recursion written out here,
//! central differences for derivatives, Richardson-extrapolated chord sums for arc length,
//! the circle's and ellipse's equations, dense samples for bounds and the nearest point.

use glam::{DVec2, DVec3, DVec4};
use proptest::prelude::*;
use splinekit::{BezierCurve, Nurbs, ParamCurve, SplineError, Vector};

/// `N_{i,p}(x)` by the Cox–de Boor recursion (half-open spans; the last span closed).
fn basis(knots: &[f64], i: usize, p: usize, x: f64, last: f64) -> f64 {
    if p == 0 {
        let inside = knots[i] <= x && x < knots[i + 1];
        let at_end = x == last && knots[i] < knots[i + 1] && knots[i + 1] == last;
        return if inside || at_end { 1.0 } else { 0.0 };
    }
    let left = if knots[i + p] > knots[i] {
        (x - knots[i]) / (knots[i + p] - knots[i]) * basis(knots, i, p - 1, x, last)
    } else {
        0.0
    };
    let right = if knots[i + p + 1] > knots[i + 1] {
        (knots[i + p + 1] - x) / (knots[i + p + 1] - knots[i + 1]) * basis(knots, i + 1, p - 1, x, last)
    } else {
        0.0
    };
    left + right
}

/// The curve at knot parameter `x`: `Σ Nᵢ wᵢ pᵢ / Σ Nᵢ wᵢ`.
fn reference<P: Vector>(c: &Nurbs<P>, x: f64) -> P {
    let (p, k) = (c.degree(), c.knots());
    let last = k[c.points().len()];
    let (mut sum, mut wsum) = (c.points()[0] * 0.0, 0.0);
    for (i, (&pt, &w)) in c.points().iter().zip(c.weights()).enumerate() {
        let n = basis(k, i, p, x, last) * w;
        sum = sum + pt * n;
        wsum += n;
    }
    sum * (1.0 / wsum)
}

/// A random NURBS: degree 1–4, 2–9 spans' worth of points, weights in [0.2, 5], a clamped
/// or an unclamped non-decreasing knot vector with repeated interior knots now and then.
fn curve3() -> impl Strategy<Value = Nurbs<DVec3>> {
    (1..=4usize, 0..=6usize, any::<bool>(), any::<u64>()).prop_map(|(p, extra, clamped, seed)| {
        let n = p + 1 + extra;
        let mut state = seed | 1;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let points: Vec<DVec3> = (0..n).map(|_| DVec3::new(next(), next(), next()) * 20.0 - 10.0).collect();
        let weights: Vec<f64> = (0..n).map(|_| 0.2 + 4.8 * next()).collect();
        let mut knots: Vec<f64> = (0..n + p + 1).map(|_| (next() * 8.0).round() / 2.0).collect();
        knots.sort_by(f64::total_cmp);
        if clamped {
            let (a, b) = (knots[p], knots[n]);
            for k in &mut knots[..=p] {
                *k = a;
            }
            for k in &mut knots[n..] {
                *k = b;
            }
        }
        // make sure the domain is not empty: spread the knots if it is
        if knots[p] >= knots[n] {
            knots = (0..n + p + 1).map(|i| i as f64).collect();
        }
        Nurbs::new(p, points, weights, Some(knots)).expect("a valid random NURBS")
    })
}

/// Arc length of segment range `[a, b]` of the curve parameter by chord sums at `n` and `2n`
/// steps per segment, Richardson-extrapolated (error O(n⁻⁴) inside smooth spans).
fn reference_length<P: Vector>(c: &Nurbs<P>, a: f64, b: f64) -> f64 {
    let chords = |steps: usize| -> f64 {
        let mut total = 0.0;
        let (k0, k1) = (a.floor() as usize, (b.ceil() as usize).max(a.floor() as usize + 1));
        for k in k0..k1 {
            let (lo, hi) = ((k as f64).max(a), ((k + 1) as f64).min(b));
            if hi <= lo {
                continue;
            }
            // the segment's own end: just before it, where the next span (which may start
            // elsewhere, after a knot of multiplicity above the degree) has not begun
            let at = |i: usize| {
                let u = lo + (hi - lo) * i as f64 / steps as f64;
                c.eval(if i == steps && hi == (k + 1) as f64 { hi - 1e-13 } else { u })
            };
            total += (1..=steps).map(|i| (at(i) - at(i - 1)).length()).sum::<f64>();
        }
        total
    };
    let (l1, l2) = (chords(20_000), chords(40_000));
    (4.0 * l2 - l1) / 3.0
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn evaluation_matches_the_basis_sum(c in curve3(), f in 0.0..=1.0f64) {
        let u = f * c.num_segments() as f64;
        let x = c.knot_at(u);
        let scale = c.points().iter().map(|p| p.length()).fold(1.0, f64::max);
        prop_assert!((c.eval(u) - reference(&c, x)).length() <= 1e-11 * scale, "{} vs {}", c.eval(u), reference(&c, x));
    }

    #[test]
    fn derivatives_match_central_differences(c in curve3(), f in 0.05..0.95f64) {
        // inside a segment, away from its ends, where the curve is smooth
        let k = (f * c.num_segments() as f64).floor();
        let u = k + 0.2 + 0.6 * (f * c.num_segments() as f64 - k);
        let h = 1e-5;
        let scale = c.points().iter().map(|p| p.length()).fold(1.0, f64::max);
        let d1 = (c.eval(u + h) - c.eval(u - h)) * (0.5 / h);
        let d2 = (c.eval(u + h) - c.eval(u) * 2.0 + c.eval(u - h)) * (1.0 / (h * h));
        let d3 = (c.deriv2(u + h) - c.deriv2(u - h)) * (0.5 / h);
        let big = c.deriv(u).length() + c.deriv2(u).length() + c.deriv3(u).length() + scale;
        prop_assert!((c.deriv(u) - d1).length() <= 1e-6 * big);
        prop_assert!((c.deriv2(u) - d2).length() <= 1e-3 * big);
        prop_assert!((c.deriv3(u) - d3).length() <= 1e-5 * big);
    }

    #[test]
    fn knot_insertion_and_bezier_pieces_keep_the_curve(c in curve3(), f in 0.0..1.0f64, s in 0.0..=1.0f64) {
        let scale = c.points().iter().map(|p| p.length()).fold(1.0, f64::max);
        let x = c.knot_at(f * c.num_segments() as f64);
        let finer = c.insert_knot(x);
        for i in 0..=20 {
            let x = c.knot_at(c.num_segments() as f64 * i as f64 / 20.0);
            let (ua, ub) = (reference(&c, x), reference(&finer, x));
            prop_assert!((ua - ub).length() <= 1e-10 * scale, "at x = {x}: {ua} vs {ub}");
        }
        for (k, piece) in c.bezier_pieces().iter().enumerate() {
            // rational de Casteljau, written out
            let mut d: Vec<DVec4> = piece.clone();
            for level in 1..d.len() {
                for i in 0..d.len() - level {
                    d[i] = d[i].lerp(d[i + 1], s);
                }
            }
            let p = d[0].truncate() / d[0].w;
            let u = k as f64 + s.min(1.0 - 1e-13);
            prop_assert!((p - c.eval(u)).length() <= 1e-10 * scale, "piece {k} at {s}: {p} vs {}", c.eval(u));
        }
    }

    #[test]
    fn arc_length_matches_extrapolated_chords(c in curve3()) {
        let m = c.num_segments() as f64;
        let reference = reference_length(&c, 0.0, m);
        let got = c.arclen(1e-8);
        prop_assert!((got - reference).abs() <= 1e-8 + 1e-9 * reference, "{got} vs {reference}");
    }

    #[test]
    fn second_derivative_bound_holds(c in curve3(), f0 in 0.0..1.0f64, w in 0.0..1.0f64) {
        let m = c.num_segments() as f64;
        let u0 = f0 * m;
        let u1 = (u0 + w * (m - u0)).min(m);
        let bound = c.deriv2_bound(u0, u1);
        for i in 0..=100 {
            let u = u0 + (u1 - u0) * i as f64 / 100.0;
            // at a segment's start the next span's derivative applies; stay within [u0, u1]
            let d = c.deriv2(u).length();
            prop_assert!(d <= bound * (1.0 + 1e-9) + 1e-9, "at {u} in [{u0}, {u1}]: {d} > {bound}");
        }
    }

    #[test]
    fn nearest_agrees_with_dense_samples(c in curve3(), q in (-12.0..12.0f64, -12.0..12.0f64, -12.0..12.0f64)) {
        let q = DVec3::new(q.0, q.1, q.2);
        let n = c.nearest(q, 1e-9);
        let m = c.num_segments();
        let sampled = (0..=20_000 * m).map(|i| (c.eval(i as f64 / 20_000.0) - q).length()).fold(f64::INFINITY, f64::min);
        prop_assert!(n.distance <= sampled + 1e-9 && n.error <= 1e-9, "{} vs {sampled}, error {}", n.distance, n.error);
    }
}

#[test]
fn every_point_of_a_nurbs_circle_is_at_its_radius() {
    for r in [1e-3, 1.0, 7.5, 1e3] {
        let circle = Nurbs::<DVec2>::circle(r);
        assert_eq!(circle.num_segments(), 4);
        let mut worst: f64 = 0.0;
        for i in 0..=4000 {
            let u = 4.0 * i as f64 / 4000.0;
            worst = worst.max((circle.eval(u).length() - r).abs() / r);
        }
        assert!(worst <= 1e-14, "radius {r}: relative error {worst}");
        assert!((circle.arclen(1e-12 * r) - std::f64::consts::TAU * r).abs() <= 1e-11 * r);
        let bb = ParamCurve::<DVec2>::bounding_box(&circle);
        assert!((bb.min + DVec2::splat(r)).length() <= 1e-14 * r && (bb.max - DVec2::splat(r)).length() <= 1e-14 * r);
    }
    let ellipse = Nurbs::<DVec3>::ellipse(3.0, 0.5);
    for i in 0..=400 {
        let p = ellipse.eval(4.0 * i as f64 / 400.0);
        assert!(((p.x / 3.0).powi(2) + (p.y / 0.5).powi(2) - 1.0).abs() <= 1e-14 && p.z == 0.0, "{p}");
    }
}

/// Elliptic arcs: every point on the ellipse's equation (to 1e-14), the ends at the start and
/// end angles, each span's middle at its middle angle (the rational quadratic's property), a
/// circular arc as long as `r·|sweep|`, and bad arcs refused.
#[test]
fn elliptic_arcs_are_exact() {
    use std::f64::consts::{PI, TAU};
    let (rx, ry) = (2.5, 0.75);
    for (start, sweep) in [(0.0, 0.3), (0.4, PI / 2.0), (-1.0, 2.0), (1.0, -3.5), (0.25, TAU), (2.0, -TAU), (0.0, 4.7)]
    {
        let arc = Nurbs::<DVec2>::elliptic_arc(rx, ry, start, sweep).unwrap();
        let spans = arc.num_segments();
        assert_eq!(spans, ((sweep.abs() / (PI / 2.0)) - 1e-9).ceil().max(1.0) as usize, "{start} {sweep}");
        let at = |angle: f64| DVec2::new(rx * angle.cos(), ry * angle.sin());
        for i in 0..=1000 {
            let p = arc.eval(spans as f64 * i as f64 / 1000.0);
            assert!(((p.x / rx).powi(2) + (p.y / ry).powi(2) - 1.0).abs() <= 1e-14, "{start} {sweep}: {p}");
        }
        assert!((arc.eval(0.0) - at(start)).length() <= 1e-15 * rx);
        assert!((arc.eval(spans as f64) - at(start + sweep)).length() <= 1e-14 * rx);
        let delta = sweep / spans as f64;
        for k in 0..spans {
            let middle = at(start + delta * (k as f64 + 0.5));
            assert!((arc.eval(k as f64 + 0.5) - middle).length() <= 1e-14 * rx, "span {k} of {start} {sweep}");
        }
        assert_eq!(arc.is_closed(), sweep.abs() == TAU);
        let circle = Nurbs::<DVec2>::elliptic_arc(1.5, 1.5, start, sweep).unwrap();
        assert!((circle.arclen(1e-12) - 1.5 * sweep.abs()).abs() <= 1e-11, "{start} {sweep}");
    }
    for (rx, start, sweep) in [(1.0, 0.0, 0.0), (1.0, 0.0, 7.0), (f64::NAN, 0.0, 1.0), (1.0, f64::INFINITY, 1.0)] {
        assert!(matches!(Nurbs::<DVec2>::elliptic_arc(rx, 1.0, start, sweep), Err(SplineError::BadArc { .. })));
    }
}

#[test]
fn periodic_curves_close_smoothly() {
    let points = vec![
        DVec2::new(1.0, 0.0),
        DVec2::new(0.0, 2.0),
        DVec2::new(-1.5, 0.0),
        DVec2::new(0.0, -1.0),
        DVec2::new(0.7, -0.6),
    ];
    let weights = vec![1.0, 2.0, 0.5, 1.0, 3.0];
    for degree in 1..=4 {
        let c = Nurbs::periodic(degree, points.clone(), weights.clone()).unwrap();
        let m = c.num_segments() as f64;
        assert_eq!(c.num_segments(), points.len(), "degree {degree}");
        assert!((c.eval(0.0) - c.eval(m)).length() < 1e-13, "degree {degree}");
        if degree >= 2 {
            let (a, b) = (c.deriv(0.0), c.deriv(m - 1e-12));
            assert!((a - b).length() < 1e-6 * a.length(), "degree {degree}: {a} vs {b}");
        }
    }
}

#[test]
fn bad_definitions_are_refused() {
    let p = vec![DVec2::ZERO, DVec2::X, DVec2::Y];
    let w = vec![1.0; 3];
    assert!(matches!(Nurbs::new(0, p.clone(), w.clone(), None), Err(SplineError::BadDegree { degree: 0, .. })));
    assert!(matches!(
        Nurbs::new(3, p.clone(), w.clone(), None),
        Err(SplineError::InsufficientPoints { needed: 4, .. })
    ));
    assert!(matches!(
        Nurbs::new(2, p.clone(), vec![1.0, 0.0, 1.0], None),
        Err(SplineError::BadWeight { index: 1, .. })
    ));
    assert!(matches!(Nurbs::new(2, p.clone(), vec![1.0; 2], None), Err(SplineError::WeightCount { .. })));
    assert!(matches!(
        Nurbs::new(2, p.clone(), w.clone(), Some(vec![0.0, 0.0, 0.0, 1.0, 1.0])),
        Err(SplineError::KnotCount { expected: 6, given: 5 })
    ));
    assert!(matches!(
        Nurbs::new(2, p.clone(), w.clone(), Some(vec![0.0, 0.0, 1.0, 0.5, 1.0, 1.0])),
        Err(SplineError::BadKnot { index: 3, .. })
    ));
    assert!(matches!(Nurbs::new(2, p, w, Some(vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0])), Err(SplineError::BadKnot { .. })));
    // a clamped default knot vector: through the end points
    let c = Nurbs::new(
        2,
        vec![DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(2.0, 0.0), DVec2::new(3.0, 1.0)],
        vec![1.0; 4],
        None,
    )
    .unwrap();
    assert_eq!(c.knots(), &[0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0]);
    assert!((c.eval(0.0) - DVec2::ZERO).length() < 1e-15 && (c.eval(2.0) - DVec2::new(3.0, 1.0)).length() < 1e-15);
}

/// A chain of Bézier curves of mixed degrees as one NURBS: segment `k` is piece `k` at the
/// same parameter (value and derivative), its length the pieces' lengths summed; pieces that
/// do not join, or a degree past the NURBS limit, are refused.
#[test]
fn chains_of_bezier_curves_of_any_degree() {
    let quadratic = BezierCurve::new(vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 2.0), DVec2::new(2.0, 0.0)]).unwrap();
    let quintic = BezierCurve::new(vec![
        DVec2::new(2.0, 0.0),
        DVec2::new(2.5, -1.0),
        DVec2::new(3.0, 1.5),
        DVec2::new(3.5, -2.0),
        DVec2::new(4.0, 2.0),
        DVec2::new(5.0, 0.5),
    ])
    .unwrap();
    let cubic =
        BezierCurve::new(vec![DVec2::new(5.0, 0.5), DVec2::new(6.0, 0.0), DVec2::new(6.0, 3.0), DVec2::new(4.0, 3.0)])
            .unwrap();
    let pieces = [quadratic, quintic, cubic];
    let chain = Nurbs::from_beziers(&pieces).unwrap();
    assert_eq!((chain.degree(), chain.num_segments()), (5, 3));
    for (k, piece) in pieces.iter().enumerate() {
        for i in 0..=50 {
            let t = i as f64 / 50.0;
            let u = k as f64 + t;
            assert!((chain.eval(u) - piece.eval(t)).length() <= 1e-14, "piece {k} at {t}");
            if t == 1.0 && k + 1 < pieces.len() {
                continue; // the join belongs to the next piece, whose derivative differs
            }
            let (d, e) = (ParamCurve::<DVec2>::deriv(&chain, u), piece.deriv_at(t, 1));
            assert!((d - e).length() <= 1e-12 * e.length().max(1.0), "piece {k} at {t}: {d} vs {e}");
        }
    }
    let sum: f64 = pieces.iter().map(|p| ParamCurve::<DVec2>::arclen(p, 1e-12)).sum();
    assert!((chain.arclen(1e-12) - sum).abs() <= 1e-10);
    // a gap, a degree past 32, no pieces
    let apart = BezierCurve::new(vec![DVec2::new(2.0, 1e-9), DVec2::new(3.0, 1.0)]).unwrap();
    assert_eq!(Nurbs::from_beziers(&[pieces[0].clone(), apart]), Err(SplineError::NotJoined { index: 1 }));
    let high = BezierCurve::new((0..40).map(|i| DVec2::new(i as f64, 0.0)).collect()).unwrap();
    assert!(matches!(Nurbs::from_beziers(&[high]), Err(SplineError::BadDegree { degree: 39, .. })));
    assert_eq!(Nurbs::<DVec2>::from_beziers(&[]), Err(SplineError::Empty));
}
