//! Rendering benches: a ~100k-triangle torus at 800×600 (fresh buffers, reused buffers,
//! wireframe), and a 2D plot of the reference scene.

#![allow(missing_docs)]

use std::f64::consts::TAU;
use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use splinekit::TriMesh;
use splinekit_render::{
    CurveOptions, ImageSize, PlotCurve, PlotOptions, RenderOptions, Renderer, Shading, plot_curves, render_mesh,
};

/// A torus of `2·m·n` triangles with unit normals (major radius 1, minor 0.35).
fn torus(m: usize, n: usize) -> TriMesh {
    let mut mesh = TriMesh::default();
    for i in 0..m {
        let (su, cu) = (TAU * i as f64 / m as f64).sin_cos();
        for j in 0..n {
            let (sv, cv) = (TAU * j as f64 / n as f64).sin_cos();
            let normal = DVec3::new(cu * cv, sv, su * cv);
            mesh.positions.push(DVec3::new(cu, 0.0, su) + 0.35 * normal);
            mesh.normals.push(normal);
        }
    }
    let id = |i: usize, j: usize| ((i % m) * n + j % n) as u32;
    for i in 0..m {
        for j in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            mesh.triangles.push([a, c, b]);
            mesh.triangles.push([a, d, c]);
        }
    }
    mesh
}

fn bench_mesh(c: &mut Criterion) {
    let mesh = torus(250, 200);
    let mut group = c.benchmark_group("render_mesh");
    group.throughput(Throughput::Elements(mesh.triangles.len() as u64));
    group.sample_size(30);
    let options = RenderOptions::DEFAULT.with_size(ImageSize::new(800, 600).unwrap());
    group.bench_function(BenchmarkId::new("torus100k_800x600", "fresh"), |b| {
        b.iter(|| render_mesh(black_box(&mesh), black_box(&options)));
    });
    let mut renderer = Renderer::new();
    group.bench_function(BenchmarkId::new("torus100k_800x600", "reused"), |b| {
        b.iter(|| renderer.render(&[black_box(&mesh)], &[], black_box(&options)));
    });
    let variants = [
        ("wireframe", options.with_wireframe(true)),
        ("flat", options.with_shading(Shading::Flat)),
        ("no_supersampling", options.with_supersample(1)),
    ];
    for (name, opts) in variants {
        group.bench_function(BenchmarkId::new("torus100k_800x600", name), |b| {
            b.iter(|| renderer.render(&[black_box(&mesh)], &[], black_box(&opts)));
        });
    }
    // Degenerate: every vertex at one point.
    let mut point = mesh.clone();
    point.positions.iter_mut().for_each(|p| *p = DVec3::ONE);
    group.bench_function(BenchmarkId::new("torus100k_800x600", "degenerate"), |b| {
        b.iter(|| renderer.render(&[black_box(&point)], &[], black_box(&options)));
    });
    group.finish();
}

fn bench_plot(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/reference-scene.swp");
    let doc = splinekit_io::SwpDocument::read(std::path::Path::new(path)).unwrap();
    let curves: Vec<PlotCurve> =
        doc.curves.iter().enumerate().map(|(i, c)| PlotCurve::from_swp(c, i).unwrap()).collect();
    let options = PlotOptions::DEFAULT.with_size(ImageSize::new(800, 600).unwrap());
    let mut group = c.benchmark_group("plot_curves");
    group.bench_function("reference_scene_800x600", |b| {
        b.iter(|| plot_curves(black_box(&curves), &CurveOptions::DEFAULT, &options));
    });
    let full = CurveOptions::DEFAULT.with_frames(true).with_marker_spacing(Some(0.1));
    group.bench_function("reference_scene_800x600_frames_markers", |b| {
        b.iter(|| plot_curves(black_box(&curves), &full, &options));
    });
    group.finish();
}

criterion_group!(benches, bench_mesh, bench_plot);
criterion_main!(benches);
