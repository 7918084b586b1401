//! Bézier curves of any degree against independent references: the Bernstein sum written
//! out with binomial coefficients, its derivative term by term, composite Gauss–Legendre
//! quadrature for arc length, dense samples for boxes and bounds, the cubic type.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use splinekit::{BezierCurve, CubicBezier, ParamCurve, SplineError, Vector};

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// `Σ C(n, i)·tⁱ·(1 − t)ⁿ⁻ⁱ·pᵢ`.
fn bernstein<P: Vector>(points: &[P], t: f64) -> P {
    let n = points.len() - 1;
    points.iter().enumerate().fold(points[0] * 0.0, |sum, (i, &p)| {
        sum + p * (binomial(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32))
    })
}

/// The derivative of the Bernstein sum, term by term.
fn bernstein_deriv<P: Vector>(points: &[P], t: f64) -> P {
    let n = points.len() - 1;
    points.iter().enumerate().fold(points[0] * 0.0, |sum, (i, &p)| {
        let (i_, n_) = (i as i32, n as i32);
        let a = if i > 0 { i as f64 * t.powi(i_ - 1) * (1.0 - t).powi(n_ - i_) } else { 0.0 };
        let b = if i < n { (n - i) as f64 * t.powi(i_) * (1.0 - t).powi(n_ - i_ - 1) } else { 0.0 };
        sum + p * (binomial(n, i) * (a - b))
    })
}

/// Arc length by composite 10-point Gauss–Legendre on 800 panels of `[a, b]`, and how far
/// that is from the 400-panel sum: the reference's own error where the speed nearly stops
/// (its kink there slows the rule's convergence), bounded by the difference since the error
/// at least halves with twice the panels.
fn reference_length<P: Vector>(points: &[P], a: f64, b: f64) -> (f64, f64) {
    let coarse = gauss_legendre_length(points, a, b, 400);
    let fine = gauss_legendre_length(points, a, b, 800);
    (fine, (fine - coarse).abs())
}

/// Arc length by composite 10-point Gauss–Legendre on `panels` panels of `[a, b]`.
fn gauss_legendre_length<P: Vector>(points: &[P], a: f64, b: f64, panels: usize) -> f64 {
    const NODES: [(f64, f64); 5] = [
        (0.148_874_338_981_631_2, 0.295_524_224_714_752_9),
        (0.433_395_394_129_247_2, 0.269_266_719_309_996_4),
        (0.679_409_568_299_024_4, 0.219_086_362_515_982_0),
        (0.865_063_366_688_984_5, 0.149_451_349_150_580_6),
        (0.973_906_528_517_171_7, 0.066_671_344_308_688_1),
    ];
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|k| {
            let c = a + h * (k as f64 + 0.5);
            NODES
                .iter()
                .map(|&(x, w)| {
                    w * (bernstein_deriv(points, c - 0.5 * h * x).length()
                        + bernstein_deriv(points, c + 0.5 * h * x).length())
                })
                .sum::<f64>()
                * 0.5
                * h
        })
        .sum()
}

fn point2() -> impl Strategy<Value = DVec2> {
    (-10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y)| DVec2::new(x, y))
}

fn point3() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn evaluation_and_derivative_match_the_bernstein_sum(points in prop::collection::vec(point3(), 2..=12), t in 0.0..=1.0f64) {
        let curve = BezierCurve::new(points.clone()).unwrap();
        let scale = points.iter().map(|p| p.length()).fold(1.0, f64::max);
        prop_assert!((curve.eval(t) - bernstein(&points, t)).length() <= 1e-12 * scale);
        let n = points.len() as f64;
        prop_assert!((curve.deriv(t) - bernstein_deriv(&points, t)).length() <= 1e-11 * scale * n * n);
        // the second derivative against a central difference of the exact first
        let h = 1e-5;
        let fd = (bernstein_deriv(&points, t + h) - bernstein_deriv(&points, t - h)) * (0.5 / h);
        prop_assert!((curve.deriv2(t) - fd).length() <= 1e-5 * scale * n.powi(4));
    }

    #[test]
    fn splitting_and_elevating_keep_the_curve(points in prop::collection::vec(point2(), 2..=10), t0 in 0.0..1.0f64, t1 in 0.0..1.0f64, s in 0.0..=1.0f64) {
        let curve = BezierCurve::new(points.clone()).unwrap();
        let scale = points.iter().map(|p| p.length()).fold(1.0, f64::max);
        let part = curve.segment(t0, t1);
        prop_assert!((part.eval(s) - curve.eval(t0 + s * (t1 - t0))).length() <= 1e-11 * scale);
        let (left, right) = curve.split(t0);
        prop_assert!((left.eval(s) - curve.eval(s * t0)).length() <= 1e-11 * scale);
        prop_assert!((right.eval(s) - curve.eval(t0 + s * (1.0 - t0))).length() <= 1e-11 * scale);
        let up = curve.elevate().elevate();
        prop_assert_eq!(up.degree(), curve.degree() + 2);
        prop_assert!((up.eval(s) - curve.eval(s)).length() <= 1e-12 * scale);
        let pieces = curve.subdivide(3);
        prop_assert!((pieces[1].eval(s) - curve.eval((1.0 + s) / 3.0)).length() <= 1e-11 * scale);
    }

    /// Arc length to within its accuracy against composite Gauss–Legendre (degrees 2–8).
    #[test]
    fn arc_length_meets_its_accuracy(points in prop::collection::vec(point2(), 3..=9), a in 0.0..0.5f64, b in 0.5..=1.0f64) {
        let curve = BezierCurve::new(points.clone()).unwrap();
        let (reference, uncertainty) = reference_length(&points, a, b);
        for accuracy in [1e-6, 1e-10] {
            let got = curve.arclen_range(a, b, accuracy).length;
            let allowed = accuracy.max(1e-12 * reference) + uncertainty;
            prop_assert!((got - reference).abs() <= allowed, "{got} vs {reference} ± {uncertainty} at {accuracy}");
        }
    }

    /// The box holds every sample and is touched on each side; the second-derivative bound
    /// holds over random intervals.
    #[test]
    fn box_and_bounds_hold(points in prop::collection::vec(point2(), 2..=9), u0 in 0.0..0.5f64, u1 in 0.5..=1.0f64) {
        let curve = BezierCurve::new(points.clone()).unwrap();
        let bb = curve.bounding_box();
        let samples: Vec<DVec2> = (0..=4000).map(|i| curve.eval(i as f64 / 4000.0)).collect();
        let slack = 1e-12 * points.iter().map(|p| p.length()).fold(1.0, f64::max);
        for p in &samples {
            prop_assert!(bb.contains(*p, slack), "{p} outside {bb:?}");
        }
        let lo = samples.iter().fold(DVec2::MAX, |m, &p| m.min(p));
        let hi = samples.iter().fold(DVec2::MIN, |m, &p| m.max(p));
        // the samples come within their spacing's sag of the exact extremes
        prop_assert!((lo - bb.min).max_element() <= 1e-3 && (bb.max - hi).max_element() <= 1e-3, "{bb:?} vs {lo} {hi}");
        let bound = curve.deriv2_bound(u0, u1);
        for i in 0..=200 {
            let u = u0 + (u1 - u0) * i as f64 / 200.0;
            prop_assert!(curve.deriv2(u).length() <= bound * (1.0 + 1e-12) + 1e-12, "at {u}: {} > {bound}", curve.deriv2(u).length());
        }
    }

    /// The nearest point, through the same search as every kind, against dense samples.
    #[test]
    fn nearest_agrees_with_dense_samples(points in prop::collection::vec(point2(), 2..=8), q in point2()) {
        let curve = BezierCurve::new(points).unwrap();
        let n = curve.nearest(q, 1e-9);
        let sampled = (0..=20_000).map(|i| (curve.eval(i as f64 / 20_000.0) - q).length()).fold(f64::INFINITY, f64::min);
        prop_assert!(n.distance <= sampled + 1e-9 && n.error <= 1e-9, "{} vs {sampled}", n.distance);
    }
}

#[test]
fn degree_three_is_the_cubic() {
    let p = [DVec2::ZERO, DVec2::new(1.0, 2.0), DVec2::new(3.0, -1.0), DVec2::new(4.0, 0.5)];
    let curve = BezierCurve::new(p.to_vec()).unwrap();
    let cubic = CubicBezier::new(p[0], p[1], p[2], p[3]);
    for i in 0..=10 {
        let t = i as f64 / 10.0;
        assert!((curve.eval(t) - cubic.eval(t)).length() < 1e-14);
        assert!((ParamCurve::deriv(&curve, t) - cubic.deriv(t)).length() < 1e-13);
        assert!((ParamCurve::deriv2(&curve, t) - cubic.deriv2(t)).length() < 1e-13);
    }
    assert!((curve.arclen(1e-12) - cubic.arclen(1e-12)).abs() < 1e-11);
    let (a, b) = (ParamCurve::<DVec2>::bounding_box(&curve), ParamCurve::<DVec2>::bounding_box(&cubic));
    assert!((a.min - b.min).length() < 1e-12 && (a.max - b.max).length() < 1e-12, "{a:?} {b:?}");
}

#[test]
fn bad_definitions_are_refused() {
    assert!(matches!(BezierCurve::new(vec![DVec2::ZERO]), Err(SplineError::InsufficientPoints { given: 1, .. })));
    assert!(matches!(BezierCurve::new(vec![DVec2::ZERO; 66]), Err(SplineError::BadPointCount { given: 66, .. })));
    assert!(matches!(
        BezierCurve::new(vec![DVec2::ZERO, DVec2::new(f64::NAN, 0.0)]),
        Err(SplineError::NonFinite { index: 1 })
    ));
    let line = BezierCurve::new(vec![DVec2::ZERO, DVec2::new(3.0, 4.0)]).unwrap();
    assert_eq!(line.derivative().points(), &[DVec2::new(3.0, 4.0)]);
    assert_eq!(ParamCurve::deriv2(&line, 0.3), DVec2::ZERO);
    assert!((line.arclen(1e-12) - 5.0).abs() < 1e-12);
}

/// A curve whose speed nearly stops near t = 0.42: 400 panels of Gauss–Legendre alone were
/// 6.6e-10 off, more than the 1e-10 asked (the reference, not the library, was wrong; 800
/// panels agree with the library).
#[test]
fn arc_length_near_a_stop_meets_its_accuracy() {
    let points = [
        (-1.3450397429491046, 8.980975244808182),
        (-1.2410772503975016, 8.968406525384989),
        (7.909231030091593, -9.736984309187996),
        (2.9211738951375277, -2.7774972726286022),
        (3.382396130997914, 7.629580468904007),
        (-4.46754988083569, 3.390923933767648),
        (5.048196084902311, -9.603681096256592),
    ]
    .map(|(x, y)| DVec2::new(x, y));
    let (a, b) = (0.0, 0.9721988658214143);
    let (reference, uncertainty) = reference_length(&points, a, b);
    assert!(uncertainty < 1e-9, "{uncertainty}");
    let got = BezierCurve::new(points.to_vec()).unwrap().arclen_range(a, b, 1e-10).length;
    assert!((got - reference).abs() <= 1e-10 + uncertainty, "{got} vs {reference} ± {uncertainty}");
}
