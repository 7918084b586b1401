//! Tests of flattening: the chord lemma, the certified densities, the placement of chord
//! ends, the angle mode and invalid input.

use glam::{DVec2, DVec3};

use super::cells::*;
use super::plan::*;
use super::*;

fn cubic(p: [(f64, f64); 4]) -> CubicBezier<DVec2> {
    let v = |(x, y): (f64, f64)| DVec2::new(x, y);
    CubicBezier::new(v(p[0]), v(p[1]), v(p[2]), v(p[3]))
}

/// Distance from `x` to the segment `[a, b]`.
fn seg_dist(x: DVec2, a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let l2 = e.length_squared();
    let s = if l2 > 0.0 { ((x - a).dot(e) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (a + e * s).distance(x)
}

/// Dense-sampled max distance from the sub-curve over [ta, tb] to its chord segment.
fn sampled_chord_dev(c: &CubicBezier<DVec2>, ta: f64, tb: f64) -> f64 {
    let (a, b) = (c.eval(ta), c.eval(tb));
    (0..=2000).map(|i| seg_dist(c.eval(ta + (tb - ta) * i as f64 / 2000.0), a, b)).fold(0.0, f64::max)
}

/// splitmix64 in [0, 100).
fn rng(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 * 100.0
}

fn random_cubic(state: &mut u64) -> CubicBezier<DVec2> {
    let mut p = || DVec2::new(rng(state), rng(state));
    CubicBezier::new(p(), p(), p(), p())
}

/// The chord lemma of the module docs, written out from the Bernstein form: the normal
/// offset of the chord `[tm − h/2, tm + h/2]` is at most
/// `((h²/8)·|Q(tm) − k2·h²/12| + h³/(12√3)·|Λ(tm)|) / |C′(tm) + (h²/4)·c|`.
fn lemma_bound(c: &CubicBezier<DVec2>, tm: f64, h: f64) -> f64 {
    let cr = |u: DVec2, v: DVec2| u.x * v.y - u.y * v.x;
    let cc = c.p3 - c.p0 + (c.p1 - c.p2) * 3.0;
    let (d1, d2) = (c.deriv(tm), c.deriv2(tm));
    let q = cr(d1, d2) - h * h / 12.0 * 6.0 * cr((c.p2 - c.p1 * 2.0 + c.p0) * 3.0, cc);
    let v = d1 + cc * (h * h / 4.0);
    (h * h / 8.0 * q.abs() + h * h * h / (12.0 * 3f64.sqrt()) * cr(d1, cc).abs()) / v.length()
}

#[test]
fn chord_lemma_bounds_and_matches_sampling() {
    let mut state = 7u64;
    for _ in 0..200 {
        let c = random_cubic(&mut state);
        for _ in 0..10 {
            let h = 0.002 + 0.2 * rng(&mut state) / 100.0;
            let tm = h / 2.0 + (1.0 - h) * rng(&mut state) / 100.0;
            let (ta, tb) = (tm - h / 2.0, tm + h / 2.0);
            let (pa, pb) = (c.eval(ta), c.eval(tb));
            let e = (pb - pa).normalize();
            // the normal offset of every sample is within the bound
            let normal = (0..=1000)
                .map(|i| {
                    let d = c.eval(ta + h * i as f64 / 1000.0) - pa;
                    (d.x * e.y - d.y * e.x).abs()
                })
                .fold(0.0, f64::max);
            let bound = lemma_bound(&c, tm, h);
            assert!(normal <= bound * (1.0 + 1e-9) + 1e-12, "{c:?} tm {tm} h {h}: {normal} > {bound}");
            // and is nearly exact for short chords (the third-order term is small)
            if h < 0.02 && normal > 1e-6 {
                assert!(bound <= normal * 1.2, "{c:?} tm {tm} h {h}: bound {bound} ≫ {normal}");
            }
        }
    }
}

/// The certified cell densities of `c` (chords per unit of t).
fn densities(c: &CubicBezier<DVec2>, tol: f64) -> [f64; CELLS] {
    let (a, b, cc, e8) = unit_scale(c, tol).unwrap();
    let mut rho = [0.0f32; CELLS];
    CellInputs::new(a, b, cc, e8, f64::from(HALF_CELL)).densities(&MIDDLES, HALF_CELL, &mut rho);
    rho.map(f64::from)
}

fn test_cases(state: &mut u64) -> Vec<CubicBezier<DVec2>> {
    let mut cases: Vec<CubicBezier<DVec2>> = (0..100).map(|_| random_cubic(state)).collect();
    cases.push(cubic([(0.0, 0.0), (100.0, 50.0), (100.0, 50.0), (0.0, 0.0)]));
    cases.push(cubic([(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)]));
    cases.push(cubic([(0.0, 0.0), (30.0, 0.0), (70.0, 0.5), (100.0, 0.0)]));
    cases.push(cubic([(0.0, 0.0), (99.0, 0.0), (100.0, 1.0), (100.0, 100.0)]));
    cases.push(cubic([(0.0, 0.0), (3.0, 0.0), (-1.0, 0.0), (1.0, 0.0)]));
    cases
}

#[test]
fn certified_densities_hold_for_any_chord() {
    // Any chord no wider than 1/ρ of the cell holding its midpoint is within the
    // tolerance — not only the chords the march picks.
    let mut state = 11u64;
    for c in &test_cases(&mut state) {
        for tol in [1.0, 0.1, 0.01, 1e-3] {
            for (j, r) in densities(c, tol).into_iter().enumerate() {
                for i in 0..=4 {
                    // the cell is closed: its ends included
                    let tm = (j as f64 + i as f64 / 4.0) / CELLS as f64;
                    let h = (1.0 / r).min(2.0 * tm).min(2.0 * (1.0 - tm));
                    let dev = sampled_chord_dev(c, tm - h / 2.0, tm + h / 2.0);
                    assert!(dev <= tol, "{c:?} tol {tol} cell {j} tm {tm} h {h}: {dev}");
                }
            }
        }
    }
}

#[test]
fn densities_are_near_the_optimal_chord_length() {
    // A circle-like arc: the optimal chord deviates by exactly the tolerance; the
    // certified widths must not be much shorter.
    let c = cubic([(100.0, 0.0), (100.0, 55.228), (55.228, 100.0), (0.0, 100.0)]);
    let tol = 0.01;
    for (j, &r) in densities(&c, tol).iter().enumerate() {
        let tm = (j as f64 + 0.5) / CELLS as f64;
        let h = (1.0 / r).min(2.0 * tm).min(2.0 * (1.0 - tm));
        let dev = sampled_chord_dev(&c, tm - h / 2.0, tm + h / 2.0);
        assert!(dev > 0.8 * tol && dev <= tol, "cell {j}: {dev}");
    }
}

#[test]
fn every_chord_is_certified_by_its_midpoint() {
    // The placement invariant behind the guarantee: every chord the plan emits is at
    // most 1/ρ wide for a cell holding its midpoint (either cell at a shared end). Covers
    // the four shapes of plan: 8, 4 or 1 equal-step cells, chords placed one by one
    // across cells, and long plans (more than CHUNK chords).
    let mut state = 5u64;
    let mut seen = [0usize; 5];
    for c in &test_cases(&mut state) {
        for tol in [10.0, 1.0, 0.3, 0.1, 0.03, 0.01, 1e-3, 1e-5] {
            let plan = ChordPlan::new(c, tol);
            let shape = if plan.n > 1 && plan.b[1] == 0.0 {
                3
            } else if plan.first[1] == u64::MAX {
                0
            } else {
                usize::from((1.0 / plan.start[1]).round() as usize == CELLS) + 1
            };
            seen[shape] += 1;
            seen[4] += usize::from(plan.n > CHUNK as u64);
            let rho = densities(c, tol);
            let allowed = |cell: usize| 1.0 / rho[cell];
            let mut t = vec![0.0];
            plan.extend(&mut t);
            assert_eq!(*t.last().unwrap(), 1.0);
            for w in t.windows(2) {
                assert!(w[1] > w[0], "{c:?} tol {tol}: not ascending at {}", w[0]);
                let x = 0.5 * (w[0] + w[1]) * CELLS as f64;
                let j = (x as usize).min(CELLS - 1);
                let mut max = allowed(j);
                if x.fract() < 1e-12 && j > 0 {
                    max = max.max(allowed(j - 1));
                }
                assert!(w[1] - w[0] <= max * (1.0 + 1e-12), "{c:?} tol {tol}: chord {w:?} wider than {max}");
            }
            // the sink variant emits the same parameters, and positions on the curve
            let mut u = vec![0.0];
            let mut with = vec![c.p0];
            flatten_cubic_distance_with(c, tol, &mut |t, p| {
                assert!(p.distance(c.eval(t)) < 1e-9, "{t}");
                u.push(t);
                with.push(p);
            });
            assert_eq!(t, u);
            // and so does the polyline variant, the same positions
            let mut points = vec![c.p0];
            flatten_cubic_distance_points(c, tol, &mut points);
            assert_eq!(points, with);
        }
    }
    assert!(seen.iter().all(|&k| k > 0), "{seen:?}");
}

#[test]
fn pauses_never_repeat_a_chord_end() {
    // With every density at least CELLS (a chord per cell width), a pause is always
    // shorter than the step: total ≥ ρd/CELLS, so step ≥ ρd/(ρd + CELLS) > (ρd − ρs)/(ρd + ρs).
    for dense in [13.0, 100.0, 1e4, 1e6] {
        for at in [0, CELLS / 2 - 1, CELLS - 1] {
            let mut rho = [CELLS as f64; CELLS];
            rho[at] = dense;
            let plan = ChordPlan::build(&rho);
            assert!(plan.short || plan.n > CHUNK as u64, "{dense} {at}");
        }
    }
    // Should a pause hold two chord ends (here forced by moving a cell's line back by
    // three steps), the long march leaves the repeats out, so the ends stay ascending.
    let mut rho = [CELLS as f64; CELLS];
    let at = CELLS - 2;
    rho[at] = 200.0;
    let mut plan = ChordPlan::build(&rho);
    assert!(plan.short);
    plan.a[at] -= 3.0 * plan.b[at];
    // the short march (one end per count, no check) shows the repeats
    let mut raw = vec![0.0];
    plan.extend(&mut raw);
    assert_eq!(raw.len() as u64, plan.n + 1);
    let mut distinct = raw.clone();
    distinct.dedup();
    assert!(distinct.len() + 2 <= raw.len(), "{raw:?}");
    plan.short = false;
    let mut t = vec![0.0];
    plan.extend(&mut t);
    assert_eq!(t, distinct);
    assert!(t.windows(2).all(|w| w[1] > w[0]), "{t:?}");
    assert_eq!(*t.last().unwrap(), 1.0);
    // a single chord for a point
    let mut t = Vec::new();
    ChordPlan::place(&[0.0; CELLS]).extend(&mut t);
    assert_eq!(t, vec![1.0]);
}

#[test]
fn integer_conversions_without_saturation() {
    // ⌊x⌋ + 1, where an integer x may also give x
    let mut state = 9u64;
    let mut xs: Vec<f64> = vec![0.0, 1e-300, 0.25, 0.5, 0.75, 1.0, 2.5, 3.0, 127.0, 128.0, 1e9 + 0.5];
    xs.extend((0..2000).map(|_| rng(&mut state) * 1.3));
    xs.extend((1..60).flat_map(|k| {
        let k = k as f64;
        [k, k.next_down(), k.next_up()]
    }));
    xs.push(((1u64 << 51) - 1) as f64);
    for x in xs {
        let f = floor_plus_one(x);
        let exact = x.floor() as u64 + 1;
        assert!(f == exact || (x.fract() == 0.0 && f == exact - 1), "{x}: {f}");
    }
    for n in [0u64, 1, 2, 127, 128, 1 << 20, (1 << 51) - 1] {
        assert_eq!(integer_to_u64(n as f64), n);
    }
}

#[test]
fn offset_params_keeps_strict_order_and_exact_ends() {
    let mut v = vec![0.0, 0.5, 1.0 - 1e-17, 1.0];
    offset_params(&mut v, 1, 5.0);
    assert_eq!(v, vec![0.0, 5.5, 6.0]);
}

#[test]
fn polygon_angles() {
    let straight = cubic([(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)]);
    assert!(!polygon_turns_more_than(&straight, 1e-9));
    let point = cubic([(1.0, 1.0); 4]);
    assert!(!polygon_turns_more_than(&point, 0.0));
    // right angle at p1
    let corner = cubic([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (1.0, 2.0)]);
    assert!(polygon_turns_more_than(&corner, 1.5));
    assert!(!polygon_turns_more_than(&corner, 1.6));
    // p1 = p2: the right angle is shared, 45° at each
    let shared = cubic([(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (1.0, 1.0)]);
    assert!(polygon_turns_more_than(&shared, 0.78));
    assert!(!polygon_turns_more_than(&shared, 0.79));
    // fold-back with a zero middle edge
    let fold = cubic([(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (0.0, 0.0)]);
    assert!(polygon_turns_more_than(&fold, 3.0));
    // 3D works the same way
    let c3 = CubicBezier::new(DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Z, DVec3::X + DVec3::Z * 2.0);
    assert!(polygon_turns_more_than(&c3, 1.5));
}

#[test]
fn degenerate_and_invalid_input() {
    let point = cubic([(2.0, 3.0); 4]);
    for tol in [1e-3, 0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300] {
        let mut out = Vec::new();
        flatten_cubic_distance(&point, tol, &mut out);
        assert_eq!(out, vec![1.0]);
    }
    // a control point that is not finite: one chord (the curve has no finite polyline)
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for k in 0..4 {
            let mut p = [(0.0, 0.0), (30.0, 80.0), (70.0, -20.0), (100.0, 0.0)];
            p[k].1 = bad;
            let mut out = Vec::new();
            flatten_cubic_distance(&cubic(p), 1e-3, &mut out);
            assert_eq!(out, vec![1.0], "{p:?}");
        }
    }
    // huge but finite coordinates are scaled, not refused
    let huge = cubic([(0.0, 0.0), (1e308, 1e308), (-1e308, 1e308), (1e308, 0.0)]);
    let mut out = Vec::new();
    flatten_cubic_distance(&huge, 1e305, &mut out);
    assert!(out.len() > 3 && out.windows(2).all(|w| w[0] < w[1]), "{out:?}");
    let line = cubic([(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]);
    out.clear();
    flatten_cubic_distance(&line, 1e-9, &mut out);
    assert_eq!(out, vec![1.0]);
    // a straight cubic that doubles back on itself must not be one chord
    let back = cubic([(0.0, 0.0), (3.0, 0.0), (-1.0, 0.0), (1.0, 0.0)]);
    out.clear();
    flatten_cubic_distance(&back, 1e-3, &mut out);
    assert!(out.len() >= 3, "{out:?}");
}
