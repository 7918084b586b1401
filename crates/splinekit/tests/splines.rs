//! Spline kinds against independent references: the matrix forms of SPEC §1.1, de Boor's
//! algorithm, Hermite with computed tangents, and closed-form curvature and torsion.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use splinekit::{
    BEZIER_BASIS, BSPLINE_BASIS, BSpline, BezierSpline, CATMULL_ROM_BASIS, CatmullRom, CubicBezier, Hermite,
    ParamCurve, SplineError,
};

const EPS: f64 = 1e-9;

/// `G · B · [1 t t² t³]ᵀ` (SPEC §1.1), written out independently of the conversions.
fn matrix_eval(basis: &[[f64; 4]; 4], g: [DVec3; 4], t: f64) -> DVec3 {
    let powers = [1.0, t, t * t, t * t * t];
    let mut out = DVec3::ZERO;
    for (row, p) in basis.iter().zip(g) {
        out += p * row.iter().zip(powers).map(|(b, x)| b * x).sum::<f64>();
    }
    out
}

/// de Boor's algorithm for a uniform cubic B-spline with integer knots (independent of the
/// Bézier window conversion): the segment on knot span [k+3, k+4) evaluated at local t.
fn de_boor(points: &[DVec3], k: usize, t: f64) -> DVec3 {
    let x = 3.0 + t;
    let mut d: Vec<DVec3> = (0..4).map(|j| points[k + j]).collect();
    for r in 1..=3 {
        for j in (r..=3).rev() {
            // control j of the window has knots j .. j+4 (integer knots)
            let left = j as f64;
            let alpha = (x - left) / (3.0 + 1.0 - r as f64);
            d[j] = d[j - 1] * (1.0 - alpha) + d[j] * alpha;
        }
    }
    d[3]
}

fn pt() -> impl Strategy<Value = DVec3> {
    (-50.0..50.0f64, -50.0..50.0f64, -50.0..50.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn points(min: usize, max: usize) -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec(pt(), min..max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn bspline_conversion_is_exact(pts in points(4, 12), t in 0.0..1.0f64) {
        let c = BSpline::new(&pts, false).unwrap().to_piecewise();
        prop_assert_eq!(c.num_segments(), pts.len() - 3);
        for k in 0..c.num_segments() {
            let g = [pts[k], pts[k + 1], pts[k + 2], pts[k + 3]];
            let want = matrix_eval(&BSPLINE_BASIS, g, t);
            prop_assert!((c.eval(k as f64 + t) - want).length() < EPS, "segment {}", k);
            prop_assert!((de_boor(&pts, k, t) - want).length() < EPS, "de Boor, segment {}", k);
        }
    }

    #[test]
    fn closed_bspline_wraps_indices(pts in points(3, 9), t in 0.0..1.0f64) {
        let n = pts.len();
        let c = BSpline::new(&pts, true).unwrap().to_piecewise();
        prop_assert_eq!(c.num_segments(), n);
        for k in 0..n {
            let g = [pts[k], pts[(k + 1) % n], pts[(k + 2) % n], pts[(k + 3) % n]];
            prop_assert!((c.eval(k as f64 + t) - matrix_eval(&BSPLINE_BASIS, g, t)).length() < EPS);
        }
        // closed: C2 across the wrap
        let m = n as f64;
        prop_assert!((c.eval(m) - c.eval(0.0)).length() < EPS);
        prop_assert!((c.deriv(m) - c.deriv(0.0)).length() < EPS);
        prop_assert!((c.deriv2(m) - c.deriv2(0.0)).length() < 1e-8);
    }

    #[test]
    fn bspline_partition_of_unity(t in 0.0..1.0f64) {
        let w = BSpline::<DVec3>::basis(t);
        prop_assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        prop_assert!(w.iter().all(|&x| x >= 0.0));
        // the weights are the rows of the basis matrix applied to [1 t t² t³]
        for (i, row) in BSPLINE_BASIS.iter().enumerate() {
            let m: f64 = row.iter().zip([1.0, t, t * t, t * t * t]).map(|(b, x)| b * x).sum();
            prop_assert!((m - w[i]).abs() < 1e-15);
        }
    }

    #[test]
    fn catmull_rom_conversion_is_exact(pts in points(4, 12), t in 0.0..1.0f64) {
        let c = CatmullRom::new(&pts, false, 0.0).unwrap().to_piecewise();
        prop_assert_eq!(c.num_segments(), pts.len() - 3);
        for k in 0..c.num_segments() {
            let g = [pts[k], pts[k + 1], pts[k + 2], pts[k + 3]];
            prop_assert!((c.eval(k as f64 + t) - matrix_eval(&CATMULL_ROM_BASIS, g, t)).length() < EPS);
            prop_assert_eq!(c.eval(k as f64), pts[k + 1]);
        }
    }

    #[test]
    fn catmull_rom_equals_hermite_with_central_tangents(pts in points(4, 10), u in 0.0..1.0f64) {
        // Cross-representation: uniform Catmull-Rom = Hermite through P1..P(n-2) with
        // tangents (P(i+1) − P(i−1))/2.
        let c = CatmullRom::new(&pts, false, 0.0).unwrap().to_piecewise();
        let inner: Vec<DVec3> = pts[1..pts.len() - 1].to_vec();
        let tangents: Vec<DVec3> = (1..pts.len() - 1).map(|i| (pts[i + 1] - pts[i - 1]) * 0.5).collect();
        let h = Hermite::new(&inner, &tangents, false).unwrap().to_piecewise();
        let x = u * c.num_segments() as f64;
        prop_assert!((c.eval(x) - h.eval(x)).length() < EPS);
        prop_assert!((c.deriv(x) - h.deriv(x)).length() < 1e-8);
    }

    #[test]
    fn catmull_rom_alpha_interpolates_and_is_c1(pts in points(4, 9), alpha in 0.0..=1.0f64) {
        let c = CatmullRom::new(&pts, false, alpha).unwrap().to_piecewise();
        for k in 0..c.num_segments() {
            prop_assert!((c.eval(k as f64) - pts[k + 1]).length() < EPS);
            prop_assert!((c.eval(k as f64 + 1.0 - 1e-300) - pts[k + 2]).length() < 1e-8);
        }
        for k in 1..c.num_segments() {
            // C1 in direction (magnitudes differ per segment parametrization, direction does not)
            let left = c.segments()[k - 1].deriv(1.0);
            let right = c.segments()[k].deriv(0.0);
            if left.length() > 1e-9 && right.length() > 1e-9 {
                prop_assert!(left.normalize().dot(right.normalize()) > 1.0 - 1e-9);
            }
        }
    }

    #[test]
    fn bezier_spline_matches_matrix_form(pts in points(4, 5).prop_flat_map(|_| points(2, 5)).prop_map(|v| v.len()).prop_flat_map(|m| points(3 * m + 1, 3 * m + 2)), t in 0.0..1.0f64) {
        let c = BezierSpline::new(&pts, false).unwrap().to_piecewise();
        for k in 0..c.num_segments() {
            let g = [pts[3 * k], pts[3 * k + 1], pts[3 * k + 2], pts[3 * k + 3]];
            prop_assert!((c.eval(k as f64 + t) - matrix_eval(&BEZIER_BASIS, g, t)).length() < EPS);
        }
    }
}

#[test]
fn centripetal_with_coincident_points_has_no_nan() {
    let p = DVec2::new(1.0, 1.0);
    let q = DVec2::new(2.0, 0.5);
    let cases: [Vec<DVec2>; 4] =
        [vec![p, p, q, q * 2.0], vec![p, q, q, q * 2.0], vec![p, q, q * 2.0, q * 2.0], vec![p, p, p, p]];
    for pts in &cases {
        for alpha in [0.0, 0.5, 1.0] {
            for closed in [false, true] {
                let c = CatmullRom::new(pts, closed, alpha).unwrap().to_piecewise();
                for i in 0..=100 {
                    let u = c.num_segments() as f64 * i as f64 / 100.0;
                    assert!(c.eval(u).is_finite(), "{pts:?} α={alpha} u={u}");
                    assert!(c.deriv(u).is_finite());
                    assert!(c.unit_tangent(u).is_finite());
                    assert!(!c.curvature(u).is_nan());
                    assert!(!c.torsion(u).is_nan());
                }
                assert!(c.arclen(1e-9).is_finite());
            }
        }
    }
}

#[test]
fn closed_catmull_rom_has_n_segments_and_is_c1_loop() {
    let pts: Vec<DVec2> = (0..5).map(|i| DVec2::from_angle(i as f64 * 1.2566) * (1.0 + 0.3 * i as f64)).collect();
    for alpha in [0.0, 0.5, 1.0] {
        let c = CatmullRom::new(&pts, true, alpha).unwrap().to_piecewise();
        assert_eq!(c.num_segments(), 5);
        assert!((c.eval(5.0) - c.eval(0.0)).length() < EPS);
        let (a, b) = (c.segments()[4].deriv(1.0).normalize(), c.segments()[0].deriv(0.0).normalize());
        assert!(a.dot(b) > 1.0 - 1e-12);
    }
    assert!(matches!(
        CatmullRom::new(&pts[..2], true, 0.0),
        Err(SplineError::InsufficientPoints { needed: 3, given: 2, .. })
    ));
    assert!(matches!(CatmullRom::new(&pts, true, 1.5), Err(SplineError::BadAlpha { .. })));
}

#[test]
fn closed_hermite_wraps() {
    let pts = [DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0), DVec2::new(-1.0, 0.0), DVec2::new(0.0, -1.0)];
    let tan: Vec<DVec2> = pts.iter().map(|p| p.perp() * 1.5).collect();
    let c = Hermite::new(&pts, &tan, true).unwrap().to_piecewise();
    assert_eq!(c.num_segments(), 4);
    assert!((c.eval(4.0) - pts[0]).length() < EPS);
    assert!((c.deriv(3.999_999_999) - tan[0]).length() < 1e-6);
    assert!(matches!(Hermite::new(&pts, &tan[..3], false), Err(SplineError::TangentCount { .. })));
}

/// The twisted cubic r(t) = (t, t², t³) on [0, 1], as a Bézier (monomial → Bernstein).
fn twisted_cubic() -> CubicBezier<DVec3> {
    CubicBezier::new(DVec3::ZERO, DVec3::new(1.0 / 3.0, 0.0, 0.0), DVec3::new(2.0 / 3.0, 1.0 / 3.0, 0.0), DVec3::ONE)
}

#[test]
fn twisted_cubic_curvature_and_torsion_closed_forms() {
    let c = twisted_cubic();
    for i in 0..=20 {
        let t = i as f64 / 20.0;
        assert!((c.eval(t) - DVec3::new(t, t * t, t * t * t)).length() < 1e-14);
        let q = 36.0 * t.powi(4) + 36.0 * t * t + 4.0;
        let kappa = q.sqrt() / (1.0 + 4.0 * t * t + 9.0 * t.powi(4)).powf(1.5);
        let tau = 3.0 / (9.0 * t.powi(4) + 9.0 * t * t + 1.0);
        assert!((c.curvature(t) - kappa).abs() < 1e-12, "κ({t})");
        assert!((c.torsion(t) - tau).abs() < 1e-12, "τ({t})");
        let tangent = DVec3::new(1.0, 2.0 * t, 3.0 * t * t).normalize();
        assert!((c.unit_tangent(t) - tangent).length() < 1e-14);
    }
}

#[test]
fn quarter_circle_bezier_curvature_is_near_one() {
    // the classic quarter-circle approximation k = 4/3·tan(π/8): radius error ≤ 2.7e-4
    let k = 4.0 / 3.0 * (std::f64::consts::PI / 8.0).tan();
    let c = CubicBezier::new(DVec2::X, DVec2::new(1.0, k), DVec2::new(k, 1.0), DVec2::Y);
    // closed form at the ends: κ(0) = (2/3)·|d01 × d12| / |d01|³ = 2(1 − k) / (3k²)
    let kappa0 = 2.0 * (1.0 - k) / (3.0 * k * k);
    assert!((c.curvature(0.0) - kappa0).abs() < 1e-14);
    assert!((c.curvature(1.0) - kappa0).abs() < 1e-14);
    for i in 0..=10 {
        let t = i as f64 / 10.0;
        assert!((c.curvature(t) - 1.0).abs() < 0.025, "κ({t}) = {}", c.curvature(t));
        assert_eq!(c.torsion(t), 0.0);
        assert!((c.eval(t).length() - 1.0).abs() < 2.8e-4);
    }
}

#[test]
fn cusp_tangent_uses_limit_direction() {
    // (0,0)(1,1)(0,1)(1,0) has a cusp; (0,0)(100,50)(100,50)(0,0) folds back at t = 0.5
    let fold = CubicBezier::new(DVec2::ZERO, DVec2::new(100.0, 50.0), DVec2::new(100.0, 50.0), DVec2::ZERO);
    assert!(fold.deriv(0.5).length() < 1e-12);
    let t = fold.unit_tangent(0.5);
    assert!((t.length() - 1.0).abs() < 1e-12);
    // right-hand limit: travelling back towards the origin after the fold
    let after = fold.unit_tangent(0.5 + 1e-6);
    assert!(t.dot(after) > 0.999, "{t:?} vs {after:?}");
    assert_eq!(fold.curvature(0.5), f64::INFINITY);
    // a curve whose end has P′ = 0: tangent is the left-hand limit, −P″
    let end_cusp = CubicBezier::new(DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(2.0, 0.0), DVec2::new(2.0, 0.0));
    let te = end_cusp.unit_tangent(1.0);
    let before = end_cusp.unit_tangent(1.0 - 1e-6);
    assert!(te.dot(before) > 0.999, "{te:?} vs {before:?}");
}

#[test]
fn constructors_reject_bad_counts() {
    let p: Vec<DVec3> = (0..5).map(|i| DVec3::splat(i as f64)).collect();
    assert!(matches!(BSpline::new(&p[..3], false), Err(SplineError::InsufficientPoints { needed: 4, given: 3, .. })));
    assert!(BSpline::new(&p[..3], true).is_ok());
    assert!(matches!(BezierSpline::new(&p, false), Err(SplineError::BadPointCount { given: 5, .. })));
    assert!(matches!(Hermite::new(&p[..1], &p[..1], false), Err(SplineError::InsufficientPoints { .. })));
    let mut nan = p.clone();
    nan[3].y = f64::INFINITY;
    assert_eq!(BSpline::new(&nan, false), Err(SplineError::NonFinite { index: 3 }));
}
