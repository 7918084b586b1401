//! Triangle counts of adaptive sweeps (`--tolerance T`) against uniform sweeps of equal
//! accuracy, with each mesh's largest distance from the exact surface measured on triangle
//! interiors. Run from the workspace root:
//!
//! ```text
//! cargo run --release -p splinekit-io --example sweep_adaptive [DATA_DIR]
//! ```
//!
//! `DATA_DIR` holds `srev/wineglass.swp` and `gcyl/{gentorus,weirder}.swp`.

#[path = "../tests/deviation/mod.rs"]
mod deviation;

use glam::DVec3;
use splinekit::TriMesh;
use splinekit::sweep::{MeshLayout, SweepOptions};
use splinekit_io::surface::{SurfaceOptions, SurfaceTessellation};
use splinekit_io::swp::SwpDocument;

fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "/work/shared/data/swp".to_owned());
    let load = |f: &str| {
        let path = format!("{dir}/{f}");
        SwpDocument::parse(&std::fs::read_to_string(&path).expect("read"), &path).expect("parse")
    };
    let opts = |t: SurfaceTessellation| SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Compat, uvs: false, caps: false },
        tessellation: t,
        ..SurfaceOptions::default()
    };
    let doc = load("srev/wineglass.swp");
    let curve = doc.curves[0].to_curve().unwrap();
    let surface = deviation::Revolution::new(&curve, 0.0, 1.0, DVec3::Y);
    let mesh = |t| doc.surface_mesh(0, &opts(t)).unwrap();
    let uniform: TriMesh = mesh(SurfaceTessellation::FileSteps);
    let (d, at) = deviation::deviation(&uniform, &surface, 6);
    println!(
        "wineglass uniform: {} triangles, deviation {d:.4e} at {at} (proved {:.4e})",
        uniform.num_triangles(),
        surface.exact(at, 1e-9)
    );
    for t in [d, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4] {
        let m = mesh(SurfaceTessellation::Distance(t));
        let (dm, _) = deviation::deviation(&m, &surface, 6);
        println!("T {t:.4e}: {} triangles, deviation {dm:.4e}", m.num_triangles());
    }
}
