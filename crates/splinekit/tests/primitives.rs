//! The exact parametric primitives usable as sweep curves (issue #3): helix and trefoil knot.
//!
//! Geometry against closed forms written out here (positions, curvature, torsion, arc length),
//! arc length against an independent quadrature and published-precision references, the
//! three tessellation modes (counts, the two-sided distance guarantee measured by dense
//! sampling, the angle rule), bounding boxes, and frames on the closed knot.

mod common;

use core::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};
use splinekit::arclen::integrate_speed;
use splinekit::flatten::{Tessellation, flatten_any};
use splinekit::frame::{self, FrameMethod, FrameOptions, Side, StartNormal};
use splinekit::{AnyCurve, ArclenTable, Helix, ParamCurve, Trefoil};

/// Tolerance for quantities computed in closed form.
const EXACT: f64 = 1e-12;

#[track_caller]
fn assert_close(a: f64, b: f64, eps: f64, what: &str) {
    assert!((a - b).abs() <= eps, "{what}: {a} vs {b} (diff {:e}, allowed {eps:e})", (a - b).abs());
}

fn helices() -> Vec<Helix> {
    vec![
        Helix::new(1.0, 0.5, 3.0),
        Helix::new(2.5, -1.2, 1.75),
        Helix::new(0.3, 4.0, 0.4),
        Helix::new(1.0, 0.0, 1.0),
        Helix::new(0.7, 0.9, -2.5),
    ]
}

/// The helix written out: `(r cos θ, r sin θ, pitch·θ/2π)`, `θ = 2π·turns·u`.
fn helix_point(h: &Helix, u: f64) -> DVec3 {
    let theta = TAU * h.turns * u;
    DVec3::new(h.radius * theta.cos(), h.radius * theta.sin(), h.pitch * theta / TAU)
}

/// The trefoil written out: `s·(sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t)`, `t = 2πu`.
fn trefoil_point(s: f64, u: f64) -> DVec3 {
    let t = TAU * u;
    DVec3::new(t.sin() + 2.0 * (2.0 * t).sin(), t.cos() - 2.0 * (2.0 * t).cos(), -(3.0 * t).sin()) * s
}

// ---------------------------------------------------------------------------------------
// Helix

#[test]
fn helix_positions_and_documented_conventions() {
    for h in helices() {
        for i in 0..=40 {
            let u = i as f64 / 40.0;
            let p: DVec3 = h.eval(u);
            assert!((p - helix_point(&h, u)).length() <= EXACT, "{h:?} at {u}");
        }
        // starts at (r, 0, 0); rises by `pitch` per turn
        let start: DVec3 = h.eval(0.0);
        assert!((start - DVec3::new(h.radius, 0.0, 0.0)).length() <= EXACT);
        let end: DVec3 = h.eval(1.0);
        assert_close(end.z, h.pitch * h.turns, EXACT, "height");
        assert!(!AnyCurve::<DVec3>::Helix(h).is_closed());
    }
    // right-handed for positive pitch: the tangent's xy part turns counter-clockwise while rising
    let h = Helix::new(1.0, 1.0, 1.0);
    let t: DVec3 = h.unit_tangent(0.0);
    assert!(t.y > 0.0 && t.z > 0.0, "{t}");
    assert!(ParamCurve::<DVec3>::torsion(&h, 0.3) > 0.0);
    assert!(ParamCurve::<DVec3>::torsion(&Helix::new(1.0, -1.0, 1.0), 0.3) < 0.0);
}

#[test]
fn helix_curvature_and_torsion_are_the_closed_forms() {
    for h in helices() {
        let c = h.pitch / TAU;
        let l2 = h.radius * h.radius + c * c;
        for i in 0..=10 {
            let u = i as f64 / 10.0;
            // from the derivatives, independently of the overrides
            let (d1, d2, d3): (DVec3, DVec3, DVec3) = (h.deriv(u), h.deriv2(u), h.deriv3(u));
            let kappa = d1.cross(d2).length() / d1.length().powi(3);
            let tau = d1.cross(d2).dot(d3) / d1.cross(d2).length_squared();
            assert_close(ParamCurve::<DVec3>::curvature(&h, u), h.radius / l2, EXACT, "curvature");
            assert_close(kappa, h.radius / l2, 1e-10, "curvature from derivatives");
            assert_close(ParamCurve::<DVec3>::torsion(&h, u), c / l2, EXACT, "torsion");
            assert_close(tau, c / l2, 1e-10, "torsion from derivatives");
            let t: DVec3 = h.unit_tangent(u);
            assert!((t - d1.normalize()).length() <= EXACT);
        }
    }
}

#[test]
fn helix_arc_length_is_the_closed_form() {
    for h in helices() {
        let exact = TAU * h.turns.abs() * (h.radius.powi(2) + (h.pitch / TAU).powi(2)).sqrt();
        let any = AnyCurve::<DVec3>::Helix(h);
        assert_close(any.arclen(1e-9), exact, EXACT * exact.max(1.0), "closed form");
        // an independent quadrature of |P′|
        let quad = integrate_speed(|u| ParamCurve::<DVec3>::deriv(&h, u).length(), 0.0, 1.0, 1e-11);
        assert_close(quad.length, exact, 1e-9, "quadrature");
        // partial and reversed ranges
        let part = ParamCurve::<DVec3>::arclen_range(&h, 0.2, 0.7, 1e-9);
        assert_close(part.length, 0.5 * exact, EXACT * exact.max(1.0), "partial");
        assert_close(ParamCurve::<DVec3>::arclen_range(&h, 0.7, 0.2, 1e-9).length, -part.length, EXACT, "reversed");
        // the chord table converges to it from below
        let table = ArclenTable::chord(&any, 4000);
        assert!(table.length() <= exact && exact - table.length() < 1e-5 * exact, "{} {exact}", table.length());
        // the 2D projection is a circle traced |turns| times
        let flat = AnyCurve::<DVec2>::Helix(h);
        assert_close(flat.arclen(1e-9), TAU * h.turns.abs() * h.radius, EXACT * exact.max(1.0), "projection");
    }
}

#[test]
fn helix_bounding_box_is_tight() {
    for h in helices().into_iter().chain([Helix::new(1.5, 2.0, 0.3), Helix::new(1.0, 1.0, -0.6)]) {
        let b: splinekit::Aabb<DVec3> = h.bounding_box();
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for i in 0..=20000 {
            let p = helix_point(&h, i as f64 / 20000.0);
            assert!(b.contains(p, 1e-12), "{h:?}: {p} outside {b:?}");
            lo = lo.min(p);
            hi = hi.max(p);
        }
        assert!((lo - b.min).length() < 1e-6 && (hi - b.max).length() < 1e-6, "{h:?}: {lo} {hi} vs {b:?}");
    }
}

#[test]
fn helix_tessellation_modes() {
    let h = Helix::new(2.0, 0.8, 3.5);
    let curve = AnyCurve::<DVec3>::Helix(h);
    // uniform: steps + 1 points for the whole helix
    for steps in [1, 7, 100] {
        let u = flatten_any(&curve, Tessellation::Uniform { steps });
        assert_eq!(u.len(), steps + 1);
        assert_eq!((u[0], u[steps]), (0.0, 1.0));
    }
    // distance: within the tolerance both ways, and nearly the fewest equal chords possible
    for tol in [0.1, 0.01, 1e-3, 1e-4] {
        let u = flatten_any(&curve, Tessellation::Distance { tolerance: tol });
        let n = u.len() - 1;
        let poly: Vec<DVec3> = u.iter().map(|&u| curve.eval(u)).collect();
        let dense: Vec<DVec3> = (0..=200_000).map(|i| helix_point(&h, i as f64 / 200_000.0)).collect();
        let sagitta = h.radius * (TAU * h.turns / 200_000.0).powi(2) / 8.0;
        let measured = common::hausdorff_lower_bound(&dense, &poly, sagitta, 8);
        assert!(measured <= tol, "tol {tol}: measured {measured}");
        // one chord fewer would leave the exact sagitta of its arc above the tolerance
        let sag = |n: usize| h.radius * (1.0 - (PI * h.turns / n as f64).cos());
        assert!(sag(n - 1) > tol * 0.98, "tol {tol}: {n} chords, {} would do", n - 1);
    }
    // angle: consecutive chords turn by at most ε, and one chord fewer per helix would not do
    for eps in [0.5, 0.1, 0.02] {
        let u = flatten_any(&curve, Tessellation::Angle { tolerance: eps });
        let poly: Vec<DVec3> = u.iter().map(|&u| curve.eval(u)).collect();
        let chords: Vec<DVec3> = poly.windows(2).map(|w| w[1] - w[0]).collect();
        let worst = chords.windows(2).map(|w| w[0].angle_between(w[1])).fold(0.0, f64::max);
        assert!(worst <= eps + 1e-12, "ε {eps}: {worst}");
        assert!(worst > 0.9 * eps, "ε {eps}: {worst} (too many chords)");
    }
}

// ---------------------------------------------------------------------------------------
// Trefoil

/// ∫₀^{2π} √(17 + 8 cos 3t + 9 cos² 3t) dt (mpmath, 30 digits): the unit knot's length.
const TREFOIL_LENGTH: f64 = 28.826_290_198_944_288_604;
/// The same for the xy projection, √(17 + 8 cos 3t).
const TREFOIL_XY_LENGTH: f64 = 25.526_998_863_398_128_466;
/// The unit knot's length over `u ∈ [0.1, 0.77]` (mpmath).
const TREFOIL_PART_LENGTH: f64 = 19.299_517_743_734_191_100;

#[test]
fn trefoil_positions_and_closure() {
    for s in [1.0, 0.35, 4.0] {
        let k = Trefoil::new(s);
        for i in 0..=60 {
            let u = i as f64 / 60.0;
            let p: DVec3 = k.eval(u);
            assert!((p - trefoil_point(s, u)).length() <= EXACT * s.max(1.0), "size {s} at {u}");
        }
        // closed, bit for bit, and periodic beyond the domain
        assert_eq!(ParamCurve::<DVec3>::eval(&k, 1.0), ParamCurve::<DVec3>::eval(&k, 0.0));
        assert_eq!(ParamCurve::<DVec3>::deriv(&k, 1.0), ParamCurve::<DVec3>::deriv(&k, 0.0));
        let (a, b): (DVec3, DVec3) = (k.eval(1.3), k.eval(0.3));
        assert!((a - b).length() <= EXACT * s);
        assert!(AnyCurve::<DVec3>::Trefoil(k).is_closed());
    }
}

#[test]
fn trefoil_second_derivative_bound_is_proven_and_attained() {
    let k = Trefoil::new(1.7);
    let sampled =
        (0..=300_000).map(|i| ParamCurve::<DVec3>::deriv2(&k, i as f64 / 300_000.0).length()).fold(0.0, f64::max);
    assert!(sampled <= k.max_deriv2() * (1.0 + 1e-14), "{sampled} > {}", k.max_deriv2());
    assert!(sampled >= k.max_deriv2() * (1.0 - 1e-9), "{sampled} ≪ {}", k.max_deriv2());
    assert_close(Trefoil::UNIT_MAX_DERIV2, 11890f64.sqrt() / 9.0, 1e-15, "√11890/9");
}

#[test]
fn trefoil_arc_length_meets_every_accuracy() {
    for s in [1.0, 0.01, 250.0] {
        let k = Trefoil::new(s);
        for exp in 1..=11 {
            let accuracy = 10f64.powi(-exp);
            let full = ParamCurve::<DVec3>::arclen_range(&k, 0.0, 1.0, accuracy);
            let allowed = accuracy.max(2e-14 * s * TREFOIL_LENGTH);
            assert!((full.length - s * TREFOIL_LENGTH).abs() <= allowed, "size {s}, accuracy {accuracy}: {full:?}");
            assert!(full.error <= allowed, "size {s}, accuracy {accuracy}: {full:?}");
            let part = ParamCurve::<DVec3>::arclen_range(&k, 0.1, 0.77, accuracy);
            assert!(
                (part.length - s * TREFOIL_PART_LENGTH).abs() <= allowed,
                "size {s}, accuracy {accuracy}: {part:?}"
            );
            let flat = ParamCurve::<DVec2>::arclen_range(&k, 0.0, 1.0, accuracy);
            assert!((flat.length - s * TREFOIL_XY_LENGTH).abs() <= allowed, "xy, accuracy {accuracy}: {flat:?}");
        }
    }
}

#[test]
fn trefoil_arc_length_agrees_with_an_independent_quadrature() {
    let k = Trefoil::new(0.8);
    let speed = |u: f64| ParamCurve::<DVec3>::deriv(&k, u).length();
    for (u0, u1) in [(0.0, 0.05), (0.13, 0.5), (0.31, 0.34), (0.2, 1.9), (-0.4, 0.25), (0.7, 0.1)] {
        let ours = ParamCurve::<DVec3>::arclen_range(&k, u0, u1, 1e-12);
        let reference = integrate_speed(speed, u0, u1, 1e-12);
        assert_close(ours.length, reference.length, 3e-12, &format!("[{u0}, {u1}]"));
    }
    // additive across a split, and whole periods count exactly
    let whole = ParamCurve::<DVec3>::arclen_range(&k, 0.0, 1.0, 1e-12).length;
    let third = ParamCurve::<DVec3>::arclen_range(&k, 0.0, 1.0 / 3.0, 1e-12).length;
    assert_close(whole, 3.0 * third, 1e-11, "three-fold symmetry");
    assert_close(ParamCurve::<DVec3>::arclen_range(&k, 0.0, 5.0, 1e-12).length, 5.0 * whole, 1e-10, "5 laps");
}

#[test]
fn trefoil_bounding_box_is_tight() {
    let k = Trefoil::new(1.25);
    let b: splinekit::Aabb<DVec3> = k.bounding_box();
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for i in 0..=200_000 {
        let p = trefoil_point(1.25, i as f64 / 200_000.0);
        assert!(b.contains(p, 1e-12), "{p} outside {b:?}");
        lo = lo.min(p);
        hi = hi.max(p);
    }
    assert!((lo - b.min).length() < 1e-8 && (hi - b.max).length() < 1e-8, "{lo} {hi} vs {b:?}");
}

#[test]
fn trefoil_tessellation_modes() {
    let k = Trefoil::new(1.5);
    let curve = AnyCurve::<DVec3>::Trefoil(k);
    for steps in [1, 3, 90] {
        let u = flatten_any(&curve, Tessellation::Uniform { steps });
        assert_eq!(u.len(), steps + 1);
        assert_eq!((u[0], u[steps]), (0.0, 1.0));
    }
    let dense: Vec<DVec3> = (0..=400_000).map(|i| trefoil_point(1.5, i as f64 / 400_000.0)).collect();
    let dense_sagitta = k.max_deriv2() / 8.0 / 400_000f64.powi(2);
    for tol in [0.1, 0.01, 1e-3] {
        let u = flatten_any(&curve, Tessellation::Distance { tolerance: tol });
        assert!(u.windows(2).all(|w| w[0] < w[1]) && u[0] == 0.0 && *u.last().unwrap() == 1.0);
        let poly: Vec<DVec3> = u.iter().map(|&u| curve.eval(u)).collect();
        let measured = common::hausdorff_lower_bound(&dense, &poly, dense_sagitta, 8);
        assert!(measured <= tol, "tol {tol}: measured {measured}");
        // fewer chords than equal steps under the global bound (h²/8)·max|C″| ≤ tol
        let uniform = (1.0 / (8.0 * tol / k.max_deriv2()).sqrt()).ceil() as usize;
        assert!(u.len() - 1 < uniform, "tol {tol}: {} chords, equal steps need {uniform}", u.len() - 1);
        // and not far above a lower bound: every chord of the optimal polyline deviates by at
        // least about κℓ²/8, so it needs about ∫√(κ/8tol) ds chords
        let n_opt: f64 = (0..20000)
            .map(|i| {
                let u = (i as f64 + 0.5) / 20000.0;
                let kappa = ParamCurve::<DVec3>::curvature(&k, u);
                (kappa / (8.0 * tol)).sqrt() * ParamCurve::<DVec3>::deriv(&k, u).length() / 20000.0
            })
            .sum();
        assert!(((u.len() - 1) as f64) < 1.2 * n_opt + 2.0, "tol {tol}: {} chords vs ~{n_opt:.1}", u.len() - 1);
    }
    for eps in [0.5, 0.1, 0.02] {
        let u = flatten_any(&curve, Tessellation::Angle { tolerance: eps });
        let poly: Vec<DVec3> = u.iter().map(|&u| curve.eval(u)).collect();
        let mut chords: Vec<DVec3> = poly.windows(2).map(|w| w[1] - w[0]).collect();
        chords.push(chords[0]); // closed: the last chord meets the first
        let worst = chords.windows(2).map(|w| w[0].angle_between(w[1])).fold(0.0, f64::max);
        assert!(worst <= eps + 1e-12, "ε {eps}: {worst}");
        // the same parameters for any size
        assert_eq!(
            u,
            flatten_any(&AnyCurve::<DVec3>::Trefoil(Trefoil::new(0.0)), Tessellation::Angle { tolerance: eps })
        );
    }
}

#[test]
fn trefoil_frames_end_where_they_started() {
    let curve = AnyCurve::<DVec3>::Trefoil(Trefoil::new(1.0));
    let params = flatten_any(&curve, Tessellation::Uniform { steps: 240 });
    for method in [
        FrameMethod::Sequential(Side::Left),
        FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left)),
        FrameMethod::Frenet,
    ] {
        let frames = frame::frames(&curve, &params, &FrameOptions::DEFAULT.with_method(method));
        let (first, last) = (frames[0], frames[frames.len() - 1]);
        for (a, b) in [(first.t, last.t), (first.n, last.n), (first.b, last.b)] {
            assert!((a - b).length() < 1e-12, "{method:?}: {a} vs {b}");
        }
        for f in &frames {
            assert!((f.t.cross(f.n) - f.b).length() < 1e-12 && f.t.dot(f.n).abs() < 1e-12, "{method:?}");
        }
        // the frames turn smoothly: no jump between neighbours
        let jump = frames.windows(2).map(|w| w[0].n.angle_between(w[1].n)).fold(0.0, f64::max);
        assert!(jump < 0.3, "{method:?}: normal jumps by {jump}");
    }
    // a full twist keeps the seam closed
    let twisted = frame::frames(&curve, &params, &FrameOptions::DEFAULT.with_twist(TAU));
    assert!((twisted[0].n - twisted[twisted.len() - 1].n).length() < 1e-9);
}

#[test]
fn degenerate_primitives_never_fail() {
    let point = AnyCurve::<DVec3>::Trefoil(Trefoil::new(0.0));
    assert_eq!(point.eval(0.4), DVec3::ZERO);
    assert_eq!(point.arclen(1e-9), 0.0);
    assert!((point.unit_tangent(0.0).length() - 1.0).abs() < EXACT);
    assert_eq!(flatten_any(&point, Tessellation::Distance { tolerance: 1e-3 }), vec![0.0, 1.0]);
    for mode in [
        Tessellation::Distance { tolerance: f64::NAN },
        Tessellation::Angle { tolerance: -1.0 },
        Tessellation::Uniform { steps: 0 },
    ] {
        for curve in [AnyCurve::<DVec3>::Helix(Helix::new(1.0, 1.0, 2.0)), AnyCurve::Trefoil(Trefoil::new(1.0))] {
            let u = flatten_any(&curve, mode);
            assert!(u.len() >= 2 && u[0] == 0.0 && *u.last().unwrap() == 1.0, "{mode:?}");
        }
    }
    let flat = Helix::new(0.0, 0.0, 0.0);
    assert_eq!(ParamCurve::<DVec3>::arclen(&flat, 1e-9), 0.0);
}
