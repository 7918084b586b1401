//! Catmull-Clark subdivision: 1–3 levels of a 100k-quad torus (→ 6.4 M quads at 3 levels) and
//! of the same torus split into 100k triangles (its first level goes through the general
//! polygon adjacency), on one thread and on two. `bench/compare_loop.sh --scheme catmull-clark`
//! compares the quad torus with OpenSubdiv.

use std::f64::consts::TAU;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use splinekit::PolyMesh;
use splinekit::subdiv::{CatmullClarkOptions, catmull_clark_subdivide};

/// A torus of `n × m` quads (radii 1 and 0.4, as `bench/meshgen.py quadtorus`), or with
/// `triangles` each quad split in two.
fn torus(n: u32, m: u32, triangles: bool) -> PolyMesh {
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut positions = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (TAU * f64::from(i) / f64::from(n), TAU * f64::from(j) / f64::from(m));
            let w = 1.0 + 0.4 * v.cos();
            positions.push(DVec3::new(w * u.cos(), w * u.sin(), 0.4 * v.sin()));
        }
    }
    let mut face_offsets = vec![0];
    let mut face_vertices = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if triangles {
                face_vertices.extend([a, b, c]);
                face_offsets.push(face_vertices.len() as u32);
                face_vertices.extend([a, c, d]);
            } else {
                face_vertices.extend([a, b, c, d]);
            }
            face_offsets.push(face_vertices.len() as u32);
        }
    }
    PolyMesh { positions, face_offsets, face_vertices, ..PolyMesh::default() }
}

fn bench(c: &mut Criterion) {
    for (name, mesh) in [("quad_torus100k", torus(500, 200, false)), ("triangle_torus100k", torus(250, 200, true))] {
        let mut g = c.benchmark_group(format!("catmull_clark_{name}"));
        g.sample_size(10);
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            for levels in 1..=3 {
                let faces =
                    catmull_clark_subdivide(&mesh, levels, &CatmullClarkOptions::default()).unwrap().num_faces();
                g.throughput(Throughput::Elements(faces as u64));
                g.bench_with_input(BenchmarkId::new(format!("{threads}thr"), levels), &levels, |b, &levels| {
                    b.iter(|| {
                        pool.install(|| {
                            catmull_clark_subdivide(&mesh, levels, &CatmullClarkOptions::default()).unwrap().num_faces()
                        })
                    });
                });
            }
        }
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
