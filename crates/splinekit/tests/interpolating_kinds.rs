//! Kochanek–Bartels and Bessel–Overhauser splines against closed forms: TCB's tangents for
//! each of tension, continuity and bias alone, zero TCB as uniform Catmull-Rom, and
//! Bessel–Overhauser on points of a circle converging to the circle as h³.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};
use splinekit::{BesselOverhauser, CatmullRom, KochanekBartels, ParamCurve, SplineError, Tcb};

/// Seven keys of a zig-zag, not evenly spaced.
fn keys() -> Vec<DVec3> {
    [
        [0.0, 0.0, 0.0],
        [1.0, 2.0, 0.5],
        [3.0, 1.5, -1.0],
        [4.0, 4.0, 0.0],
        [6.5, 3.0, 1.0],
        [7.0, 0.0, 2.0],
        [9.0, 1.0, 0.0],
    ]
    .map(DVec3::from_array)
    .to_vec()
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).length() <= 1e-13 * (1.0 + b.length())
}

#[test]
fn zero_tension_continuity_and_bias_is_uniform_catmull_rom() {
    let k = keys();
    for closed in [false, true] {
        let kb = KochanekBartels::new(&k, &vec![Tcb::default(); k.len()], closed).unwrap().to_piecewise();
        let cr = CatmullRom::new(&k, closed, 0.0).unwrap().to_piecewise();
        for i in 0..=400 {
            let u = kb.num_segments() as f64 * i as f64 / 400.0;
            assert!((kb.eval(u) - cr.eval(u)).length() <= 1e-15 * 16.0, "u = {u}");
        }
    }
}

/// Each of t, c and b alone against the closed form of the tangents at an interior key
/// (Catmull-Rom's `(P(i+1) − P(i−1))/2` scaled, or the chords weighted).
#[test]
fn tangents_follow_tension_continuity_and_bias() {
    let k = keys();
    let n = k.len();
    for (i, (t, c, b)) in
        [(0.5, 0.0, 0.0), (-0.5, 0.0, 0.0), (0.0, 0.6, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, -0.3)]
            .into_iter()
            .enumerate()
    {
        let key = 2 + i % 3; // an interior key with a segment on either side
        let mut shape = vec![Tcb::default(); n];
        shape[key] = Tcb::new(t, c, b);
        let curve = KochanekBartels::new(&k, &shape, false).unwrap().to_piecewise();
        // open curves start at key 1: key `key` is where segment key − 2 ends and key − 1 begins
        let (d0, d1) = (k[key] - k[key - 1], k[key + 1] - k[key]);
        let (want_in, want_out) = (
            d0 * ((1.0 - t) * (1.0 - c) * (1.0 + b) / 2.0) + d1 * ((1.0 - t) * (1.0 + c) * (1.0 - b) / 2.0),
            d0 * ((1.0 - t) * (1.0 + c) * (1.0 + b) / 2.0) + d1 * ((1.0 - t) * (1.0 - c) * (1.0 - b) / 2.0),
        );
        // the segments' own derivatives at their ends
        let seg = curve.segments();
        let (end_of_previous, start_of_next) = (seg[key - 2].deriv(1.0), seg[key - 1].deriv(0.0));
        assert!(close(end_of_previous, want_in), "t {t} c {c} b {b}: arriving {end_of_previous} want {want_in}");
        assert!(close(start_of_next, want_out), "t {t} c {c} b {b}: leaving {start_of_next} want {want_out}");
        match (t, c, b) {
            // tension alone scales Catmull-Rom's tangent by 1 − t, on both sides
            (t, 0.0, 0.0) => assert!(close(start_of_next, (k[key + 1] - k[key - 1]) * ((1.0 - t) / 2.0))),
            // full bias takes the previous chord
            (0.0, 0.0, 1.0) => assert!(close(start_of_next, d0) && close(end_of_previous, d0)),
            // continuity −1: arriving along the previous chord, leaving along the next
            (0.0, -1.0, 0.0) => assert!(close(end_of_previous, d0) && close(start_of_next, d1)),
            _ => {}
        }
        // every key interpolated
        for (j, &key) in k.iter().enumerate().take(n - 1).skip(1) {
            assert!(close(curve.eval((j - 1) as f64), key));
        }
    }
}

#[test]
fn bad_keys_are_refused() {
    let k = keys();
    let mut shape = vec![Tcb::default(); k.len()];
    shape[3].bias = 1.5;
    assert_eq!(
        KochanekBartels::new(&k, &shape, false).unwrap_err(),
        SplineError::BadShape { index: 3, name: "bias", value: 1.5 }
    );
    assert_eq!(
        KochanekBartels::new(&k, &shape[..2], false).unwrap_err().to_string(),
        "kochanek-bartels needs one tension, continuity and bias per key, got 7 keys and 2"
    );
    assert!(matches!(BesselOverhauser::new(&k[..3], false), Err(SplineError::InsufficientPoints { needed: 4, .. })));
    assert!(BesselOverhauser::new(&k[..3], true).is_ok());
}

/// The largest distance from the unit circle of a closed Bessel–Overhauser curve through `n`
/// points of it, unevenly spaced (angles wobbling by a third of the spacing).
fn circle_error(n: usize) -> f64 {
    let keys: Vec<DVec2> = (0..n)
        .map(|i| {
            let a = TAU * (i as f64 + 0.33 * (i as f64 * 2.1).sin()) / n as f64;
            DVec2::new(a.cos(), a.sin())
        })
        .collect();
    let curve = BesselOverhauser::new(&keys, true).unwrap().to_piecewise();
    (0..=20 * n).map(|i| (curve.eval(n as f64 * i as f64 / (20 * n) as f64).length() - 1.0).abs()).fold(0.0, f64::max)
}

#[test]
fn bessel_overhauser_converges_to_the_circle_at_least_as_h_cubed() {
    let errors: Vec<f64> = [16, 32, 64, 128].map(circle_error).to_vec();
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        // at least h³: halving the spacing divides the error by 8 or more (here 13–14, the
        // radial error of the evenly spaced part falling as h⁴), and not as a higher order
        assert!((7.0..17.0).contains(&ratio), "errors {errors:?}");
    }
    assert!(errors[3] < 1e-5, "{errors:?}");
}

#[test]
fn bessel_overhauser_keeps_lines_and_equal_keys() {
    // unevenly spaced keys on a line: the parabolas are the line, the curve stays on it
    let keys: Vec<DVec2> = [0.0, 0.3, 1.7, 2.0, 5.0].map(|x| DVec2::new(x, 0.5 * x)).to_vec();
    let curve = BesselOverhauser::new(&keys, false).unwrap().to_piecewise();
    for i in 0..=100 {
        let p = curve.eval(3.0 * i as f64 / 100.0);
        assert!((p.y - 0.5 * p.x).abs() < 1e-15, "{p}");
    }
    // a repeated key: finite everywhere, the zero segment a point
    let keys = [DVec2::ZERO, DVec2::X, DVec2::X, DVec2::ONE, DVec2::Y];
    let curve = BesselOverhauser::new(&keys, false).unwrap().to_piecewise();
    for i in 0..=60 {
        assert!(curve.eval(2.0 * i as f64 / 60.0).is_finite());
    }
    assert_eq!(curve.eval(0.5), DVec2::X);
}
