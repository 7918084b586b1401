//! The editor's live update while a control point is dragged (issue #5: re-sweeping a
//! 100k-triangle surface takes < 8 ms): each frame of a drag moves the point and sweeps the
//! document's surfaces again with [`SweptSurfaces::sweep`], the exact path the editor takes,
//! then hands the mesh to the 3D view ([`View3d::set_mesh`], CPU side: vertex records and
//! normal lines; the GPU upload and render are measured by the `view3d` test
//! `frame_time_100k_triangles`).
//!
//! Two documents of about 100k triangles: the course's wineglass (surface of revolution) and
//! gentorus (generalized cylinder), with their step counts raised.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use splinekit_editor::{Document, SweptSurfaces, View3d};
use splinekit_io::SwpDocument;

/// `file` from the I/O crate's test data, with its header lines replaced.
fn scaled(file: &str, replace: &[(&str, &str)]) -> Document {
    let path = format!("{}/../splinekit-io/tests/data/swp/{file}", env!("CARGO_MANIFEST_DIR"));
    let mut text = std::fs::read_to_string(&path).expect("bundled SWP file");
    for (from, to) in replace {
        assert!(text.contains(from), "{file}: no {from:?}");
        text = text.replacen(from, to, 1);
    }
    Document::from_swp(SwpDocument::parse(&text, file).expect("valid SWP"), None)
}

fn bench(c: &mut Criterion) {
    let docs = [
        (
            "wineglass",
            scaled(
                "srev/wineglass.swp",
                &[("bsp2 profile 8 26", "bsp2 profile 16 26"), ("srev wineglass 90", "srev wineglass 150")],
            ),
            5,
        ),
        (
            "gentorus",
            scaled(
                "gcyl/gentorus.swp",
                &[("bsp2 profile 5 11", "bsp2 profile 25 11"), ("circ sweep 80", "circ sweep 250")],
            ),
            3,
        ),
    ];
    let mut g = c.benchmark_group("editor_live_sweep");
    for (name, mut doc, point) in docs {
        let triangles = SweptSurfaces::sweep(&doc.swp).mesh.num_triangles();
        eprintln!("{name}: {triangles} triangles");
        assert!(triangles >= 100_000, "{name}: {triangles} triangles, want at least 100k");
        let start = doc.points()[point];
        let mut k = 0u32;
        // one drag frame: the point moves, the surfaces are swept again
        g.bench_function(format!("{name}_sweep"), |b| {
            b.iter(|| {
                k = k.wrapping_add(1);
                doc.set_point(point, start + DVec3::new(1e-3 * f64::from(k % 100), 0.0, 0.0));
                black_box(SweptSurfaces::sweep(&doc.swp))
            });
        });
        let mesh = SweptSurfaces::sweep(&doc.swp).mesh;
        let mut view = View3d::new();
        g.bench_function(format!("{name}_view3d_set_mesh"), |b| b.iter(|| view.set_mesh(black_box(&mesh))));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
