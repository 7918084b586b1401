//! The nearest point on 1000 random 2D cubics in [0, 100]² to 1000 random points in
//! [−20, 120]², at accuracy 1e-6 and 1e-9: splinekit and kurbo 0.13 side by side.
//!
//! Before timing, it prints an accuracy report: the largest (distance − reference) /
//! accuracy of each library's answers, with the reference from brute force (20 000 samples,
//! golden-section search around the best eight; an upper bound of the true minimum, within
//! about 1e-12 of it), and how many answers miss their accuracy.
//!
//! `cargo bench -p splinekit --bench nearest`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec2;
use kurbo::{CubicBez, ParamCurveNearest as _, Point};
use splinekit::{CubicBezier, ParamCurve};

#[path = "../tests/common/mod.rs"]
mod common;

const N: usize = 1000;

fn to_kurbo(c: &CubicBezier<DVec2>) -> CubicBez {
    let p = |v: DVec2| Point::new(v.x, v.y);
    CubicBez::new(p(c.p0), p(c.p1), p(c.p2), p(c.p3))
}

/// Query points: a fixed sequence in [−20, 120]².
fn queries() -> Vec<DVec2> {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..N).map(|_| DVec2::new(-20.0 + 140.0 * next(), -20.0 + 140.0 * next())).collect()
}

/// The brute-force distance from `q` to `c` (see the module docs).
fn reference(c: &CubicBezier<DVec2>, q: DVec2) -> f64 {
    const SAMPLES: usize = 20_000;
    let dist = |t: f64| (c.eval(t.clamp(0.0, 1.0)) - q).length();
    let mut samples: Vec<(f64, f64)> = (0..=SAMPLES).map(|i| i as f64 / SAMPLES as f64).map(|t| (dist(t), t)).collect();
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    let golden = (5f64.sqrt() - 1.0) / 2.0;
    let h = 1.0 / SAMPLES as f64;
    samples
        .iter()
        .take(8)
        .map(|&(_, t)| {
            let (mut a, mut b) = ((t - h).max(0.0), (t + h).min(1.0));
            for _ in 0..80 {
                let (x, y) = (b - golden * (b - a), a + golden * (b - a));
                if dist(x) < dist(y) { b = y } else { a = x }
            }
            dist(0.5 * (a + b))
        })
        .fold(samples[0].0, f64::min)
}

fn accuracy_report(ours: &[CubicBezier<DVec2>], theirs: &[CubicBez], qs: &[DVec2]) {
    let refs: Vec<f64> = ours.iter().zip(qs).map(|(c, &q)| reference(c, q)).collect();
    for acc in [1e-6, 1e-9] {
        let (mut worst_ours, mut worst_kurbo, mut miss_ours, mut miss_kurbo) = (0.0f64, 0.0f64, 0, 0);
        for ((c, k), (&q, &r)) in ours.iter().zip(theirs).zip(qs.iter().zip(&refs)) {
            let e = (ParamCurve::<DVec2>::nearest(c, q, acc).distance - r) / acc;
            worst_ours = worst_ours.max(e);
            miss_ours += usize::from(e > 1.0);
            let e = (k.nearest(Point::new(q.x, q.y), acc).distance_sq.sqrt() - r) / acc;
            worst_kurbo = worst_kurbo.max(e);
            miss_kurbo += usize::from(e > 1.0);
        }
        println!(
            "nearest accuracy {acc:e}: worst (distance − reference)/accuracy splinekit {worst_ours:.3} ({miss_ours} of {N} miss), kurbo {worst_kurbo:.3} ({miss_kurbo} of {N} miss)"
        );
    }
}

fn bench(c: &mut Criterion) {
    let ours = common::random_cubics(0x5EED, N);
    let theirs: Vec<CubicBez> = ours.iter().map(to_kurbo).collect();
    let qs = queries();
    accuracy_report(&ours, &theirs, &qs);

    let mut g = c.benchmark_group("nearest");
    g.throughput(Throughput::Elements(N as u64));
    for acc in [1e-6, 1e-9] {
        g.bench_with_input(BenchmarkId::new("splinekit", acc), &acc, |b, &acc| {
            b.iter(|| {
                ours.iter()
                    .zip(&qs)
                    .map(|(c, &q)| ParamCurve::<DVec2>::nearest(c, q, black_box(acc)).distance)
                    .sum::<f64>()
            })
        });
        g.bench_with_input(BenchmarkId::new("kurbo", acc), &acc, |b, &acc| {
            b.iter(|| {
                theirs
                    .iter()
                    .zip(&qs)
                    .map(|(c, q)| c.nearest(Point::new(q.x, q.y), black_box(acc)).distance_sq)
                    .sum::<f64>()
            })
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3)).warm_up_time(std::time::Duration::from_secs(1));
    targets = bench
}
criterion_main!(benches);
