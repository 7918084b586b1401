//! Tessellation (SPEC §1.3) against independent checks: exact counts for uniform steps, the
//! control-polygon rule for angle mode, and — for distance mode — the two-sided Hausdorff
//! distance *measured* by dense sampling, independently of the method's own reasoning.
//!
//! The measurement is a lower bound of the true distance (so a reported excess is real):
//! - curve → polyline: exact distances from dense curve samples to the polyline;
//! - polyline → curve: points along every chord, distance to the dense curve polyline minus
//!   that polyline's own sagitta bound `max|C″|·Δu²/8` (the dense polyline and the curve are
//!   within that of each other).
//!
//! Dense sampling finds the true maxima to second order, so passing `≤ tolerance` here is
//! sharp, and a test checks that dropping one vertex is detected.

mod common;

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use splinekit::flatten::{
    DEFAULT_TOLERANCE, MAX_ANGLE_DEPTH, MAX_STEPS, Tessellation, flatten_any, flatten_cubic_distance, flatten_params,
};
use splinekit::{AnyCurve, BezierSpline, CatmullRom, Circle, CubicBezier, ParamCurve, PiecewiseCubic, Vector};

// ---------------------------------------------------------------------------------------
// Measuring the Hausdorff distance

/// Lower bound of the two-sided Hausdorff distance between `curve` (over its domain) and the
/// polyline through `curve.eval(u)` for the given parameters.
fn hausdorff_lower_bound<P: Vector, C: ParamCurve<P>>(curve: &C, params: &[f64], dense_per_unit: usize) -> f64 {
    let (u0, u1) = curve.domain();
    let n = ((u1 - u0) * dense_per_unit as f64).ceil() as usize;
    let du = (u1 - u0) / n as f64;
    let dense: Vec<DVec3> = (0..=n).map(|i| curve.eval(u0 + du * i as f64).to_dvec3()).collect();
    let poly: Vec<DVec3> = params.iter().map(|&u| curve.eval(u).to_dvec3()).collect();
    // the dense polyline is within the sagitta of the curve (|P″| sampled, with a margin)
    let max_d2 = (0..=4 * (u1 - u0).ceil() as usize)
        .map(|i| curve.deriv2(u0 + (u1 - u0) * i as f64 / (4.0 * (u1 - u0).ceil())).length())
        .fold(0.0, f64::max)
        * 1.5;
    common::hausdorff_lower_bound(&dense, &poly, max_d2 * du * du / 8.0, 16)
}

fn chain<P: Vector>(c: CubicBezier<P>) -> PiecewiseCubic<P> {
    PiecewiseCubic::new(vec![c], false).unwrap()
}

fn assert_ascending(u: &[f64], end: f64) {
    assert_eq!(u[0], 0.0);
    assert_eq!(*u.last().unwrap(), end);
    assert!(u.windows(2).all(|w| w[0] < w[1]), "not strictly ascending: {u:?}");
}

const FOLD_BACK: [(f64, f64); 4] = [(0.0, 0.0), (100.0, 50.0), (100.0, 50.0), (0.0, 0.0)];
const CUSP: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)];

fn cubic2(p: [(f64, f64); 4]) -> CubicBezier<DVec2> {
    let v = |(x, y): (f64, f64)| DVec2::new(x, y);
    CubicBezier::new(v(p[0]), v(p[1]), v(p[2]), v(p[3]))
}

// ---------------------------------------------------------------------------------------
// Uniform steps

#[test]
fn uniform_counts_open_bezier() {
    let pts: Vec<DVec2> = (0..10).map(|i| DVec2::new(i as f64, ((i * 7) % 5) as f64)).collect();
    let curve = BezierSpline::new(&pts, false).unwrap().to_piecewise();
    for steps in [1, 2, 5, 16] {
        let u = flatten_params(&curve, Tessellation::Uniform { steps });
        assert_eq!(u.len(), 3 * steps + 1, "steps {steps}");
        assert_ascending(&u, 3.0);
        for (i, &x) in u.iter().enumerate() {
            let expected = (i / steps) as f64 + (i % steps) as f64 / steps as f64;
            assert!((x - expected).abs() < 1e-15, "u[{i}] = {x}, expected {expected}");
        }
    }
}

#[test]
fn uniform_counts_closed_curve() {
    let pts: Vec<DVec3> = (0..5).map(|i| DVec3::new((i as f64).cos(), (i as f64).sin(), 0.1 * i as f64)).collect();
    let curve = CatmullRom::new(&pts, true, 0.5).unwrap().to_piecewise();
    assert_eq!(curve.num_segments(), 5);
    let u = flatten_params(&curve, Tessellation::Uniform { steps: 4 });
    assert_eq!(u.len(), 5 * 4 + 1);
    assert_ascending(&u, 5.0);
    // the last point repeats the first position
    assert!(curve.eval(u[0]).distance(curve.eval(*u.last().unwrap())) < 1e-12);
}

#[test]
fn uniform_counts_circle() {
    let circle = AnyCurve::<DVec2>::Circle(Circle::new(2.0));
    for steps in [1, 3, 12, 100] {
        let u = flatten_any(&circle, Tessellation::Uniform { steps });
        assert_eq!(u.len(), steps + 1);
        assert_ascending(&u, 1.0);
        let (first, last) = (circle.eval(u[0]), circle.eval(u[steps]));
        assert!(first.distance(DVec2::new(2.0, 0.0)) < 1e-12 && last.distance(first) < 1e-12);
    }
    // counter-clockwise from angle 0
    let u = flatten_any(&circle, Tessellation::Uniform { steps: 8 });
    let p = circle.eval(u[2]);
    assert!(p.distance(DVec2::new(0.0, 2.0)) < 1e-12, "{p}");
}

#[test]
fn uniform_steps_are_clamped() {
    let curve = chain(cubic2(CUSP));
    assert_eq!(flatten_params(&curve, Tessellation::Uniform { steps: 0 }), vec![0.0, 1.0]);
    assert_eq!(flatten_params(&curve, Tessellation::Uniform { steps: usize::MAX }).len(), MAX_STEPS + 1);
    let circle = AnyCurve::<DVec2>::Circle(Circle::new(1.0));
    assert_eq!(flatten_any(&circle, Tessellation::Uniform { steps: 0 }), vec![0.0, 1.0]);
}

// ---------------------------------------------------------------------------------------
// Angle tolerance

/// Turning angle of the control polygon of `c` at p1 and p2 (independent of the library:
/// zero-length edges are skipped, as documented).
fn polygon_turns(c: &CubicBezier<DVec2>) -> f64 {
    let edges: Vec<DVec2> = [c.p1 - c.p0, c.p2 - c.p1, c.p3 - c.p2].into_iter().filter(|e| e.length() > 1e-9).collect();
    edges.windows(2).map(|w| w[0].angle_to(w[1]).abs()).fold(0.0, f64::max)
}

#[test]
fn angle_mode_leaves_meet_the_rule_or_the_depth_limit() {
    let mut state = 3u64;
    for _ in 0..50 {
        let c = common::random_cubic(&mut state, 10.0);
        for eps in [0.5, 0.1, 0.02] {
            let u = flatten_params(&chain(c), Tessellation::Angle { tolerance: eps });
            assert_ascending(&u, 1.0);
            for w in u.windows(2) {
                let width = w[1] - w[0];
                // pieces come from halving: dyadic widths
                let levels = (-width.log2()).round();
                assert!((width - 0.5f64.powf(levels)).abs() < 1e-15 && levels <= MAX_ANGLE_DEPTH as f64);
                let piece = c.subsegment(w[0], w[1]);
                // a polygon where zero-length edges are skipped can only turn less than the
                // rule allows where a middle edge vanished (then its neighbours share a turn)
                if levels < MAX_ANGLE_DEPTH as f64 {
                    assert!(polygon_turns(&piece) <= eps + 1e-9, "eps {eps}: {piece:?}");
                }
            }
            // the parent of each leaf turned by more than ε/2 (otherwise it would not be split)
            if u.len() > 2 {
                assert!(polygon_turns(&c) > eps / 2.0);
            }
        }
    }
}

#[test]
fn angle_mode_counts_grow_as_tolerance_shrinks_and_lines_stay_single() {
    let c = cubic2([(0.0, 0.0), (30.0, 90.0), (70.0, -40.0), (100.0, 10.0)]);
    let counts: Vec<usize> = [1.0, 0.3, 0.1, 0.03, 0.01]
        .iter()
        .map(|&eps| flatten_params(&chain(c), Tessellation::Angle { tolerance: eps }).len())
        .collect();
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    assert!(counts[4] > counts[0]);
    let line = cubic2([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]);
    assert_eq!(flatten_params(&chain(line), Tessellation::Angle { tolerance: 1e-6 }), vec![0.0, 1.0]);
    // a cusp is split to the depth limit and no further
    let u = flatten_params(&chain(cubic2(CUSP)), Tessellation::Angle { tolerance: 1e-3 });
    assert!(u.len() <= (1 << MAX_ANGLE_DEPTH) + 1);
    let min_width = u.windows(2).map(|w| w[1] - w[0]).fold(1.0, f64::min);
    assert_eq!(min_width, 0.5f64.powi(MAX_ANGLE_DEPTH as i32));
}

#[test]
fn angle_mode_circle_and_invalid_tolerance() {
    let circle = AnyCurve::<DVec2>::Circle(Circle::new(1.0));
    let u = flatten_any(&circle, Tessellation::Angle { tolerance: 0.1 });
    assert_eq!(u.len(), 63 + 1); // ⌈2π/0.1⌉ = 63 chords
    assert_eq!(flatten_any(&circle, Tessellation::Angle { tolerance: 10.0 }).len(), 4); // at least a triangle
    let c = chain(cubic2(FOLD_BACK));
    let default = flatten_params(&c, Tessellation::Angle { tolerance: splinekit::flatten::DEFAULT_ANGLE_TOLERANCE });
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(flatten_params(&c, Tessellation::Angle { tolerance: bad }), default);
    }
}

// ---------------------------------------------------------------------------------------
// Distance tolerance

fn check_distance<P: Vector>(c: &CubicBezier<P>, tol: f64) -> (usize, f64) {
    let curve = chain(*c);
    let u = flatten_params(&curve, Tessellation::Distance { tolerance: tol });
    assert_ascending(&u, 1.0);
    let h = hausdorff_lower_bound(&curve, &u, 6000);
    assert!(h <= tol * (1.0 + 1e-9), "{c:?} at tolerance {tol}: measured Hausdorff {h} ({:.4}× tol)", h / tol);
    (u.len() - 1, h)
}

#[test]
fn distance_mode_holds_on_random_cubics_with_a_fixed_seed() {
    let mut state = 0x5EED_F1A7u64;
    let (mut worst, mut sum) = (0.0f64, 0.0);
    let n = 150;
    for _ in 0..n {
        let c = common::random_cubic(&mut state, 100.0);
        let (_, h) = check_distance(&c, 0.01);
        worst = worst.max(h / 0.01);
        sum += h / 0.01;
    }
    // near-optimal: the error budget is used, not wasted
    assert!(worst > 0.95 && sum / n as f64 > 0.7, "worst {worst}, mean {}", sum / n as f64);
}

#[test]
fn distance_mode_cusp_and_fold_back() {
    for tol in [1.0, 0.1, 1e-2, 1e-3, 1e-4] {
        check_distance(&cubic2(FOLD_BACK), tol);
    }
    for tol in [0.1, 1e-2, 1e-3, 1e-4, 1e-5] {
        check_distance(&cubic2(CUSP), tol);
    }
    // the fold-back's tip (t = ½) is reached: a polyline that misses it is off by ~37
    let u = flatten_params(&chain(cubic2(FOLD_BACK)), Tessellation::Distance { tolerance: 0.01 });
    let c = cubic2(FOLD_BACK);
    let far = u.iter().map(|&t| c.eval(t).length()).fold(0.0, f64::max);
    assert!(far > c.eval(0.5).length() - 0.01, "{far}");
}

#[test]
fn distance_mode_tiny_huge_and_degenerate_curves() {
    let mut state = 99u64;
    for scale in [1e-9, 1e-3, 1.0, 1e6] {
        let c = common::random_cubic(&mut state, scale);
        for rel in [1e-2, 1e-4] {
            check_distance(&c, rel * scale);
        }
    }
    // far from the origin
    let off = DVec2::splat(1e6);
    let c = cubic2(FOLD_BACK);
    check_distance(&CubicBezier::new(c.p0 + off, c.p1 + off, c.p2 + off, c.p3 + off), 0.01);
    // degenerate: a point, a straight line, a line that doubles back, coincident inner points
    let p = DVec2::new(1.0, 2.0);
    assert_eq!(check_distance(&CubicBezier::new(p, p, p, p), 1e-3).0, 1);
    assert_eq!(check_distance(&cubic2([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]), 1e-6).0, 1);
    check_distance(&cubic2([(0.0, 0.0), (3.0, 0.0), (-1.0, 0.0), (1.0, 0.0)]), 1e-3);
    check_distance(&cubic2([(0.0, 0.0), (0.0, 0.0), (5.0, 5.0), (5.0, 0.0)]), 1e-3);
    check_distance(&cubic2([(0.0, 0.0), (5.0, 5.0), (5.0, 5.0), (5.0, 0.0)]), 1e-3);
    // a tolerance far below f64 resolution is raised to the documented floor, and holds there
    let c = cubic2(CUSP);
    let mut out = Vec::new();
    flatten_cubic_distance(&c, 1e-300, &mut out);
    assert!(out.len() > 1000 && out.len() < 10_000_000);
}

#[test]
fn distance_mode_long_plans_coarse_cells_and_turnarounds() {
    // The three shapes of the plan, measured: more chords than one pass of the table march
    // (small tolerances), coarser cells for nearly straight curves and coarse tolerances, and
    // cells next to turnarounds (zero speed), where Wang's bound takes over.
    let mut state = 0xB16u64;
    for _ in 0..6 {
        let c = common::random_cubic(&mut state, 100.0);
        let (n, _) = check_distance(&c, 1e-5);
        assert!(n > 128, "{n}");
    }
    // nearly straight: fewer chords than the floor of one per cell (8 cells) would take
    let gentle = cubic2([(0.0, 0.0), (30.0, 1.0), (70.0, 1.0), (100.0, 0.0)]);
    assert!(check_distance(&gentle, 0.1).0 < 8);
    assert!(check_distance(&cubic2([(0.0, 0.0), (30.0, 0.0), (70.0, 0.5), (100.0, 0.0)]), 0.01).0 < 8);
    // straight with varying speed (the no-overshoot condition limits the chords there)
    check_distance(&cubic2([(0.0, 0.0), (0.1, 0.1), (2.0, 2.0), (3.0, 3.0)]), 1e-6);
    // turnarounds: a line that doubles back, and folds, at small tolerances
    for tol in [1e-2, 1e-4, 1e-6] {
        check_distance(&cubic2([(0.0, 0.0), (3.0, 0.0), (-1.0, 0.0), (1.0, 0.0)]), tol);
        check_distance(&cubic2([(0.0, 0.0), (100.0, 0.0), (100.0, 0.0), (0.0, 0.0)]), tol * 100.0);
        check_distance(&cubic2(CUSP), tol);
    }
}

#[test]
fn distance_mode_invalid_tolerance_means_default() {
    let curve = chain(cubic2(FOLD_BACK));
    let default = flatten_params(&curve, Tessellation::Distance { tolerance: DEFAULT_TOLERANCE });
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(flatten_params(&curve, Tessellation::Distance { tolerance: bad }), default);
    }
}

#[test]
fn distance_mode_tolerance_sweep_and_counts() {
    let c = cubic2([(0.0, 0.0), (30.0, 90.0), (70.0, -40.0), (100.0, 10.0)]);
    let mut last = 0;
    for tol in [1.0, 0.1, 1e-2, 1e-3, 1e-4] {
        let (n, _) = check_distance(&c, tol);
        assert!(n > last, "tolerance {tol}: {n} chords");
        // n ∝ tolerance^-1/2: a tenfold smaller tolerance costs about √10 times the chords
        if last > 10 {
            let ratio = n as f64 / last as f64;
            assert!(ratio > 2.5 && ratio < 4.0, "tolerance {tol}: ratio {ratio}");
        }
        last = n;
    }
}

#[test]
fn distance_mode_uses_far_fewer_points_than_uniform_steps() {
    // For each curve, the smallest uniform step count whose measured error is within the
    // tolerance (an oracle no uniform method has); the adaptive polyline needs fewer in total
    // (about 0.8× here; Wang's a-priori uniform count, as in lyon, is about 2.5× adaptive).
    let mut state = 0xC0FFEEu64;
    let tol = 0.05;
    let (mut adaptive, mut uniform) = (0usize, 0usize);
    for _ in 0..20 {
        let curve = chain(common::random_cubic(&mut state, 100.0));
        adaptive += flatten_params(&curve, Tessellation::Distance { tolerance: tol }).len() - 1;
        let within = |steps: usize| {
            let u = flatten_params(&curve, Tessellation::Uniform { steps });
            hausdorff_lower_bound(&curve, &u, 3000) <= tol
        };
        let (mut lo, mut hi) = (1usize, 1usize);
        while !within(hi) {
            lo = hi;
            hi *= 2;
        }
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if within(mid) { hi = mid } else { lo = mid }
        }
        uniform += hi;
    }
    assert!((adaptive as f64) < 0.9 * uniform as f64, "adaptive {adaptive} vs uniform {uniform}");
}

#[test]
fn measurement_detects_a_missing_vertex() {
    // The test is sharp: drop the vertices nearest the fold-back's tip (t = ½; the curve is
    // symmetric about it, so one on each side) and the measured distance jumps far above the
    // tolerance.
    let curve = chain(cubic2(FOLD_BACK));
    let mut u = flatten_params(&curve, Tessellation::Distance { tolerance: 0.01 });
    let before = u.len();
    let left = u.iter().rposition(|&t| t <= 0.5).unwrap();
    u.drain(left..=left + 1);
    assert!(before - u.len() == 2 && u.iter().all(|&t| (t - 0.5).abs() > 0.01));
    assert!(hausdorff_lower_bound(&curve, &u, 6000) > 0.02);
}

#[test]
fn distance_mode_on_splines_and_circles() {
    // a closed centripetal Catmull-Rom in 3D and an open Bézier chain
    let pts: Vec<DVec3> =
        (0..7).map(|i| DVec3::new((i as f64).cos() * 10.0, (i as f64 * 1.3).sin() * 10.0, i as f64)).collect();
    let cr = CatmullRom::new(&pts, true, 0.5).unwrap().to_piecewise();
    for tol in [0.1, 0.01] {
        let u = flatten_params(&cr, Tessellation::Distance { tolerance: tol });
        assert_ascending(&u, cr.num_segments() as f64);
        let h = hausdorff_lower_bound(&cr, &u, 4000);
        assert!(h <= tol * (1.0 + 1e-9), "catmull-rom at {tol}: {h}");
    }
    // circles: the sagitta gives the exact minimal count
    for (r, tol) in [(1.0, 0.01), (100.0, 0.01), (5.0, 1e-6), (1.0, 3.0)] {
        let circle = AnyCurve::<DVec2>::Circle(Circle::new(r));
        let u = flatten_any(&circle, Tessellation::Distance { tolerance: tol });
        assert_ascending(&u, 1.0);
        let n = (u.len() - 1) as f64;
        let sagitta = |n: f64| r * (1.0 - (std::f64::consts::PI / n).cos());
        assert!(sagitta(n) <= tol, "r {r} tol {tol}: {n} chords");
        assert!(n == 1.0 || sagitta(n - 1.0) > tol * (1.0 - 1e-6), "r {r} tol {tol}: {n} chords not minimal");
    }
    let point = AnyCurve::<DVec2>::Circle(Circle::new(0.0));
    assert_eq!(flatten_any(&point, Tessellation::Distance { tolerance: 0.1 }), vec![0.0, 1.0]);
}

// ---------------------------------------------------------------------------------------
// Property tests

fn pt2() -> impl Strategy<Value = DVec2> {
    (0.0..100.0f64, 0.0..100.0f64).prop_map(|(x, y)| DVec2::new(x, y))
}

fn pt3() -> impl Strategy<Value = DVec3> {
    (-50.0..50.0f64, -50.0..50.0f64, -50.0..50.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn distance_mode_guarantee_2d(p0 in pt2(), p1 in pt2(), p2 in pt2(), p3 in pt2(), e in 1.0..3.0f64) {
        check_distance(&CubicBezier::new(p0, p1, p2, p3), 10f64.powf(-e));
    }

    #[test]
    fn distance_mode_guarantee_3d(p0 in pt3(), p1 in pt3(), p2 in pt3(), p3 in pt3(), e in 1.0..3.0f64) {
        check_distance(&CubicBezier::new(p0, p1, p2, p3), 10f64.powf(-e));
    }

    #[test]
    fn distance_mode_is_invariant_under_rigid_motions(p0 in pt2(), p1 in pt2(), p2 in pt2(), p3 in pt2(), angle in 0.0..6.3f64) {
        let c = CubicBezier::new(p0, p1, p2, p3);
        let rot = DVec2::from_angle(angle);
        let moved = |p: DVec2| rot.rotate(p) + DVec2::new(-30.0, 70.0);
        let d = CubicBezier::new(moved(p0), moved(p1), moved(p2), moved(p3));
        let (n, _) = check_distance(&c, 0.01);
        let (m, _) = check_distance(&d, 0.01);
        // the certificate uses only rotation-invariant quantities, up to the L1 norm of C″
        prop_assert!((n as f64 - m as f64).abs() <= 0.05 * n as f64 + 1.0, "{n} vs {m}");
    }
}

/// #38: `flatten_count` tells the number of points before they are made: exactly for circles,
/// helices, uniform steps and cubics in the distance mode, an upper bound in the angle mode
/// and for trefoils; a helix that would take billions of points is counted, not made, and
/// `flatten_at_most` draws it with equal steps instead.
#[test]
fn point_counts_are_known_before_the_points_are_made() {
    use splinekit::flatten::{flatten_any, flatten_at_most, flatten_count};
    use splinekit::{BSpline, Helix, Trefoil};
    let spline = AnyCurve::Piecewise(
        BSpline::new(
            &[
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 0.0),
                DVec3::new(3.0, -1.0, 1.0),
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(6.0, 3.0, 2.0),
            ],
            false,
        )
        .unwrap()
        .to_piecewise(),
    );
    let curves = [
        spline,
        AnyCurve::Circle(Circle::new(2.0)),
        AnyCurve::Helix(Helix::new(1.5, 0.3, 7.5)),
        AnyCurve::Trefoil(Trefoil::new(1.0)),
    ];
    for (k, curve) in curves.iter().enumerate() {
        for mode in [
            Tessellation::Uniform { steps: 7 },
            Tessellation::Distance { tolerance: 1e-3 },
            Tessellation::Distance { tolerance: 1e-6 },
            Tessellation::Angle { tolerance: 0.05 },
        ] {
            let made = flatten_any(curve, mode).len() as u64;
            let counted = flatten_count(curve, mode);
            let exact = k != 3 && !matches!(mode, Tessellation::Angle { .. }) || k == 1 || k == 2;
            if exact {
                assert_eq!(counted, made, "curve {k}, {mode:?}");
            } else {
                assert!(counted >= made, "curve {k}, {mode:?}: counted {counted}, made {made}");
            }
        }
    }
    // 10 000 turns of radius 1e200 to 0.01: billions of points, counted in no time
    let huge: AnyCurve<DVec3> = AnyCurve::Helix(Helix::new(1e200, 1.0, 10_000.0));
    let mode = Tessellation::Distance { tolerance: 0.01 };
    assert!(flatten_count(&huge, mode) > 1_000_000_000);
    let drawn = flatten_at_most(&huge, mode, 100_000);
    // all of the budget, not `MAX_STEPS` (65 536 steps would be 6.6 chords a turn)
    assert_eq!(drawn.len(), 100_000);
    assert_eq!((drawn[0], *drawn.last().unwrap()), (0.0, 1.0));
    assert!(drawn.windows(2).all(|w| w[0] < w[1]));
}

/// #38: the angle mode's chord count of a helix depends on its shape, not its size: a radius
/// of 1e-300 (whose chords underflowed to length 0, so that the count crept up by one to its
/// cap of 4096 a turn: 2.3 s) gives the count of radius 1.
#[test]
fn helix_angle_chords_do_not_depend_on_size() {
    use splinekit::Helix;
    use splinekit::flatten::{flatten_any, flatten_count};
    let mode = Tessellation::Angle { tolerance: 0.11 };
    for (pitch, turns) in [(0.0, 10_000.0), (0.3, 7.5), (-2.0, 3.0), (50.0, 1.0)] {
        let unit = flatten_count(&AnyCurve::<DVec3>::Helix(Helix::new(1.0, pitch, turns)), mode);
        for scale in [1e-300, 1e-9, 1e9, 1e300] {
            let h = AnyCurve::<DVec3>::Helix(Helix::new(scale, pitch * scale, turns));
            assert_eq!(flatten_count(&h, mode), unit, "pitch {pitch}, turns {turns}, scale {scale}");
        }
        // at least 3 chords a turn, and the points made are the points counted
        let n = unit - 1;
        assert!(n as f64 >= 3.0 * turns, "{n} chords for {turns} turns");
        let params = flatten_any(&AnyCurve::<DVec3>::Helix(Helix::new(1.0, pitch, turns)), mode);
        assert_eq!(params.len() as u64, unit);
    }
}
