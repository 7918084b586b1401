//! The cost of rationality: one 2D uniform cubic B-spline of 64 seeded random control points
//! (61 segments, about 100 units across) as
//! - `piecewise`: the cubic path (`BSpline::to_piecewise`, a chain of cubic Béziers),
//! - `nurbs w=1`: the same curve as a non-rational [`Nurbs`] (degree 3, the same uniform
//!   unclamped knots, all weights 1; the same parametrization, one unit of `u` per span),
//! - `nurbs rational`: the same control points and knots with weights in [0.5, 2],
//!
//! timed for `arclen` at accuracy 1e-6 and 1e-9 and for distance-mode flattening
//! (`flatten_any`) at tolerance 1e-2 and 1e-3, plus a degenerate rational NURBS (all
//! points equal). Before timing it prints how far the non-rational NURBS is from the cubic
//! path (the same curve to rounding), each length and each polyline's point count.
//!
//! `cargo bench -p splinekit --bench nurbs -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec2;
use splinekit::flatten::{Tessellation, flatten_any};
use splinekit::{AnyCurve, BSpline, Nurbs, ParamCurve};

#[path = "../tests/common/mod.rs"]
mod common;

const POINTS: usize = 64;

/// A wandering polyline: x grows by 1.5 ± 1 per point, y is random in [0, 20).
fn control_points(seed: u64) -> Vec<DVec2> {
    let mut state = seed;
    let mut x = 0.0;
    (0..POINTS)
        .map(|_| {
            x += 0.5 + common::splitmix(&mut state, 2.0);
            DVec2::new(x, common::splitmix(&mut state, 20.0))
        })
        .collect()
}

/// The uniform unclamped knots of a cubic B-spline over `n` points: its domain `[3, n]` has
/// `n − 3` unit spans, one per window of four points, as `BSpline` has.
fn uniform_knots(n: usize) -> Vec<f64> {
    (0..n + 4).map(|i| i as f64).collect()
}

fn curves() -> Vec<(&'static str, AnyCurve<DVec2>)> {
    let points = control_points(0x5EED);
    let piecewise = BSpline::new(&points, false).unwrap().to_piecewise();
    let plain = Nurbs::new(3, points.clone(), vec![1.0; POINTS], Some(uniform_knots(POINTS))).unwrap();
    let mut state = 0x41;
    let weights: Vec<f64> = (0..POINTS).map(|_| 0.5 + common::splitmix(&mut state, 1.5)).collect();
    let rational = Nurbs::new(3, points, weights, Some(uniform_knots(POINTS))).unwrap();
    vec![
        ("piecewise", AnyCurve::Piecewise(piecewise)),
        ("nurbs w=1", AnyCurve::Nurbs(plain)),
        ("nurbs rational", AnyCurve::Nurbs(rational)),
    ]
}

fn report(curves: &[(&str, AnyCurve<DVec2>)]) {
    let (piecewise, plain) = (&curves[0].1, &curves[1].1);
    let m = piecewise.num_segments();
    assert_eq!(m, plain.num_segments());
    let gap = (0..=100 * m).map(|i| (piecewise.eval(i as f64 / 100.0) - plain.eval(i as f64 / 100.0)).length());
    println!(
        "nurbs: {m} segments; |piecewise − nurbs w=1| ≤ {:.1e} at 100 points per segment",
        gap.fold(0.0, f64::max)
    );
    for (name, c) in curves {
        let counts: Vec<String> = [1e-2, 1e-3]
            .iter()
            .map(|&tolerance| {
                format!("{} at {tolerance:e}", flatten_any(c, Tessellation::Distance { tolerance }).len())
            })
            .collect();
        println!("nurbs {name:>15}: length {:.12}, flatten points {}", c.arclen(1e-12), counts.join(", "));
    }
}

fn bench(c: &mut Criterion) {
    let curves = curves();
    report(&curves);
    let segments = curves[0].1.num_segments() as u64;

    let mut g = c.benchmark_group("nurbs arclen");
    g.throughput(Throughput::Elements(segments));
    for accuracy in [1e-6, 1e-9] {
        for (name, curve) in &curves {
            g.bench_with_input(BenchmarkId::new(*name, accuracy), &accuracy, |b, &accuracy| {
                b.iter(|| black_box(curve).arclen(black_box(accuracy)))
            });
        }
    }
    g.finish();

    let mut g = c.benchmark_group("nurbs flatten");
    g.throughput(Throughput::Elements(segments));
    for tolerance in [1e-2, 1e-3] {
        for (name, curve) in &curves {
            g.bench_with_input(BenchmarkId::new(*name, tolerance), &tolerance, |b, &tolerance| {
                b.iter(|| {
                    flatten_any(black_box(curve), Tessellation::Distance { tolerance: black_box(tolerance) }).len()
                })
            });
        }
    }
    g.finish();

    let mut g = c.benchmark_group("nurbs degenerate");
    let p = DVec2::new(3.0, 4.0);
    let weights: Vec<f64> = (0..8).map(|i| 0.5 + 0.25 * i as f64).collect();
    let point = AnyCurve::Nurbs(Nurbs::new(3, vec![p; 8], weights, Some(uniform_knots(8))).unwrap());
    g.bench_function("rational point arclen 1e-9", |b| b.iter(|| black_box(&point).arclen(1e-9)));
    g.bench_function("rational point flatten 1e-3", |b| {
        b.iter(|| flatten_any(black_box(&point), Tessellation::Distance { tolerance: 1e-3 }).len())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
