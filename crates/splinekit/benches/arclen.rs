//! Arc length on 1000 random 2D cubics in [0, 100]²: evaluation, adaptive arc length at
//! accuracy 1e-6 and 1e-9, and exact inverse arc length at 1e-6 — splinekit and kurbo 0.13
//! side by side in the same run, plus a degenerate case.
//!
//! Before timing, it prints an accuracy report: the largest |error| / accuracy over the
//! same curves for both libraries (reference: splinekit's adaptive length at 1e-13, whose
//! own accuracy is property-tested against an independent quadrature), and for splinekit
//! how large its error estimate gets and whether any error exceeds it.
//!
//! `cargo bench -p splinekit --bench arclen`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec2;
use kurbo::{CubicBez, ParamCurve as _, ParamCurveArclen as _, Point};
use splinekit::CubicBezier;

#[path = "../tests/common/mod.rs"]
mod common;

const N: usize = 1000;

fn to_kurbo(c: &CubicBezier<DVec2>) -> CubicBez {
    let p = |v: DVec2| Point::new(v.x, v.y);
    CubicBez::new(p(c.p0), p(c.p1), p(c.p2), p(c.p3))
}

fn accuracy_report(ours: &[CubicBezier<DVec2>], theirs: &[CubicBez]) {
    for acc in [1e-6, 1e-9] {
        let (mut worst_ours, mut worst_kurbo, mut miss_kurbo) = (0.0f64, 0.0f64, 0);
        // the estimate returned with each length is a bound: count where the error exceeds it
        // (beyond the reference's own 1e-13), and the largest estimate/accuracy
        let (mut above_estimate, mut worst_estimate) = (0, 0.0f64);
        for (c, k) in ours.iter().zip(theirs) {
            let truth = c.arclen_range(0.0, 1.0, 1e-13).length;
            let e = c.arclen_range(0.0, 1.0, acc);
            worst_ours = worst_ours.max((e.length - truth).abs() / acc);
            above_estimate += usize::from((e.length - truth).abs() > e.error + 2e-13);
            worst_estimate = worst_estimate.max(e.error / acc);
            let e = (k.arclen(acc) - truth).abs() / acc;
            worst_kurbo = worst_kurbo.max(e);
            miss_kurbo += usize::from(e > 1.0);
        }
        println!(
            "arclen  accuracy {acc:e}: worst |error|/accuracy splinekit {worst_ours:.3}, kurbo {worst_kurbo:.3} ({miss_kurbo} of {N} kurbo answers miss); splinekit estimate/accuracy ≤ {worst_estimate:.3}, error above estimate on {above_estimate} of {N}"
        );
    }
    for acc in [1e-6, 1e-9] {
        let (mut worst_ours, mut worst_kurbo, mut miss_kurbo) = (0.0f64, 0.0f64, 0);
        for (i, (c, k)) in ours.iter().zip(theirs).enumerate() {
            let total = c.arclen_range(0.0, 1.0, 1e-13).length;
            let s = total * ((i % 97) as f64 + 0.5) / 97.0;
            let t = c.inv_arclen(s, acc);
            worst_ours = worst_ours.max((c.arclen_range(0.0, t, 1e-13).length - s).abs() / acc);
            let tk = k.inv_arclen(s, acc);
            let e = (c.arclen_range(0.0, tk, 1e-13).length - s).abs() / acc;
            worst_kurbo = worst_kurbo.max(e);
            miss_kurbo += usize::from(e > 1.0);
        }
        println!(
            "inverse accuracy {acc:e}: worst |s(t) − s|/accuracy splinekit {worst_ours:.3}, kurbo {worst_kurbo:.3} ({miss_kurbo} of {N} kurbo answers miss)"
        );
    }
}

fn bench(c: &mut Criterion) {
    let ours = common::random_cubics(0x5EED, N);
    let theirs: Vec<CubicBez> = ours.iter().map(to_kurbo).collect();
    accuracy_report(&ours, &theirs);

    let mut g = c.benchmark_group("eval");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("splinekit", |b| {
        b.iter(|| ours.iter().map(|c| c.eval(black_box(0.37))).fold(DVec2::ZERO, |a, p| a + p))
    });
    g.bench_function("kurbo", |b| {
        b.iter(|| theirs.iter().map(|c| c.eval(black_box(0.37)).to_vec2()).fold(kurbo::Vec2::ZERO, |a, p| a + p))
    });
    g.finish();

    let mut g = c.benchmark_group("arclen");
    g.throughput(Throughput::Elements(N as u64));
    for acc in [1e-6, 1e-9] {
        g.bench_with_input(BenchmarkId::new("splinekit", acc), &acc, |b, &acc| {
            b.iter(|| ours.iter().map(|c| c.arclen_range(0.0, 1.0, black_box(acc)).length).sum::<f64>())
        });
        g.bench_with_input(BenchmarkId::new("kurbo", acc), &acc, |b, &acc| {
            b.iter(|| theirs.iter().map(|c| c.arclen(black_box(acc))).sum::<f64>())
        });
    }
    g.finish();

    let mut g = c.benchmark_group("inv_arclen");
    g.throughput(Throughput::Elements(N as u64));
    let targets: Vec<f64> = ours
        .iter()
        .enumerate()
        .map(|(i, c)| c.arclen_range(0.0, 1.0, 1e-12).length * ((i % 97) as f64 + 0.5) / 97.0)
        .collect();
    for acc in [1e-6, 1e-9] {
        g.bench_with_input(BenchmarkId::new("splinekit", acc), &acc, |b, &acc| {
            b.iter(|| ours.iter().zip(&targets).map(|(c, &s)| c.inv_arclen(s, black_box(acc))).sum::<f64>())
        });
        g.bench_with_input(BenchmarkId::new("kurbo", acc), &acc, |b, &acc| {
            b.iter(|| theirs.iter().zip(&targets).map(|(c, &s)| c.inv_arclen(s, black_box(acc))).sum::<f64>())
        });
    }
    g.finish();

    // degenerate: every control point equal, and a cusp
    let point = CubicBezier::new(DVec2::splat(3.0), DVec2::splat(3.0), DVec2::splat(3.0), DVec2::splat(3.0));
    let cusp = CubicBezier::new(DVec2::ZERO, DVec2::new(100.0, 100.0), DVec2::new(0.0, 100.0), DVec2::new(100.0, 0.0));
    let mut g = c.benchmark_group("arclen degenerate");
    g.bench_function("point", |b| b.iter(|| black_box(point).arclen_range(0.0, 1.0, 1e-9)));
    g.bench_function("cusp 1e-9", |b| b.iter(|| black_box(cusp).arclen_range(0.0, 1.0, 1e-9)));
    g.bench_function("cusp kurbo 1e-9", |b| b.iter(|| to_kurbo(&black_box(cusp)).arclen(1e-9)));
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(3)).warm_up_time(std::time::Duration::from_secs(1));
    targets = bench
}
criterion_main!(benches);
