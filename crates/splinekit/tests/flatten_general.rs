//! Flattening Bézier curves of any degree and NURBS: the distance mode's two-sided bound
//! checked by dense sampling of every piece, the point-count bounds, uniform steps, and the
//! NURBS circle against its sagitta.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use splinekit::flatten::{Tessellation, flatten_any, flatten_count};
use splinekit::{AnyCurve, BezierCurve, Nurbs, ParamCurve, Vector};

/// The distance from `p` to the segment `a b`.
fn to_segment<P: Vector>(p: P, a: P, b: P) -> f64 {
    let d = b - a;
    let dd = d.dot(d);
    let s = if dd > 0.0 { ((p - a).dot(d) / dd).clamp(0.0, 1.0) } else { 0.0 };
    (a + d * s - p).length()
}

/// The largest distance, both ways, between the curve over each piece and the piece's chord
/// (50 samples per piece; each curve sample against the chord, each chord point against the
/// curve's point at the same parameter).
fn deviation<P: Vector>(curve: &AnyCurve<P>, params: &[f64]) -> f64 {
    let mut worst: f64 = 0.0;
    for w in params.windows(2) {
        let (a, b) = (w[0], w[1]);
        // the piece's own end (a chain may jump where a segment ends)
        let (pa, pb) = (curve.eval(a), curve.eval(b - 1e-13 * (b - a)));
        for i in 0..=50 {
            let s = i as f64 / 50.0;
            let u = a + s * (b - a);
            let p = curve.eval(u.min(b - 1e-13 * (b - a)));
            worst = worst.max(to_segment(p, pa, pb)).max((pa.lerp(pb, s) - p).length());
        }
    }
    worst
}

fn point2() -> impl Strategy<Value = DVec2> {
    (-10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y)| DVec2::new(x, y))
}

fn nurbs2() -> impl Strategy<Value = Nurbs<DVec2>> {
    (1..=4usize, prop::collection::vec((point2(), 0.2..5.0f64), 5..=9), any::<bool>()).prop_map(|(p, pw, closed)| {
        let (points, weights): (Vec<DVec2>, Vec<f64>) = pw.into_iter().unzip();
        if closed {
            Nurbs::periodic(p, points, weights).unwrap()
        } else {
            Nurbs::new(p, points, weights, None).unwrap()
        }
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn bezier_curves_meet_the_distance_tolerance(points in prop::collection::vec(point2(), 2..=9), digits in 1..=5i32) {
        let curve = AnyCurve::Bezier(BezierCurve::new(points).unwrap());
        let tolerance = 10f64.powi(-digits);
        let params = flatten_any(&curve, Tessellation::Distance { tolerance });
        let bound = flatten_count(&curve, Tessellation::Distance { tolerance });
        prop_assert!(params.len() as u64 <= bound);
        prop_assert_eq!((params[0], *params.last().unwrap()), (0.0, 1.0));
        let worst = deviation(&curve, &params);
        prop_assert!(worst <= tolerance * (1.0 + 1e-9), "{worst} > {tolerance}");
    }

    #[test]
    fn nurbs_meet_the_distance_tolerance(c in nurbs2(), digits in 1..=5i32) {
        let m = c.num_segments() as f64;
        let curve = AnyCurve::Nurbs(c);
        let tolerance = 10f64.powi(-digits);
        let params = flatten_any(&curve, Tessellation::Distance { tolerance });
        let bound = flatten_count(&curve, Tessellation::Distance { tolerance });
        prop_assert!(params.len() as u64 <= bound);
        prop_assert_eq!((params[0], *params.last().unwrap()), (0.0, m));
        prop_assert!(params.windows(2).all(|w| w[0] < w[1]));
        let worst = deviation(&curve, &params);
        prop_assert!(worst <= tolerance * (1.0 + 1e-9), "{worst} > {tolerance}");
    }

    #[test]
    fn angle_and_uniform_modes_keep_their_counts(c in nurbs2(), steps in 1..=20usize) {
        let m = c.num_segments();
        let curve = AnyCurve::Nurbs(c);
        let uniform = flatten_any(&curve, Tessellation::Uniform { steps });
        prop_assert_eq!(uniform.len(), m * steps + 1);
        prop_assert_eq!(flatten_count(&curve, Tessellation::Uniform { steps }), (m * steps + 1) as u64);
        let coarse = flatten_any(&curve, Tessellation::Angle { tolerance: 0.5 });
        let fine = flatten_any(&curve, Tessellation::Angle { tolerance: 0.05 });
        prop_assert!(coarse.len() <= fine.len());
        let bound = flatten_count(&curve, Tessellation::Angle { tolerance: 0.05 });
        prop_assert!(fine.len() as u64 <= bound);
    }
}

#[test]
fn a_nurbs_circle_flattens_within_its_sagitta() {
    let r = 3.0;
    let curve = AnyCurve::<DVec3>::Nurbs(Nurbs::circle(r));
    for tolerance in [1e-1, 1e-3, 1e-6] {
        let params = flatten_any(&curve, Tessellation::Distance { tolerance });
        for w in params.windows(2) {
            let (a, b) = (curve.eval(w[0]), curve.eval(w[1]));
            assert!((a.length() - r).abs() < 1e-13);
            // the chord's middle is the farthest from the circle: its sagitta
            let sagitta = r - (0.5 * (a + b)).length();
            assert!(sagitta <= tolerance, "{tolerance}: sagitta {sagitta}");
        }
        // the bound holds but is not wasteful: within 4× of the fewest equal chords
        let fewest = (std::f64::consts::PI / (1.0 - tolerance / r).acos()).ceil();
        assert!((params.len() - 1) as f64 <= 4.0 * fewest, "{tolerance}: {} chords for {fewest}", params.len() - 1);
    }
}
