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
use splinekit_io::swp::{SwpDocument, SwpSurfaceKind};

/// One row: a tolerance, the adaptive mesh and its measured deviation, and the uniform
/// mesh (the file's steps, every curve's and the revolution's scaled by one factor) with the
/// fewest steps whose measured deviation is within the tolerance.
fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "/work/shared/data/swp".to_owned());
    let load = |f: &str| {
        let path = format!("{dir}/{f}");
        SwpDocument::parse(&std::fs::read_to_string(&path).expect("read"), &path).expect("parse")
    };
    let opts = |t: SurfaceTessellation| SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Compat, uvs: false, caps: false, ..SweepOptions::default() },
        tessellation: t,
        ..SurfaceOptions::default()
    };
    // (file, profile index, r0, sx, axis): the exact surface as a revolution of the profile
    // (gentorus: a profile along a circle of radius 2.2 about +z, N toward the centre)
    let files = [("srev/wineglass.swp", 0.0, 1.0, DVec3::Y), ("gcyl/gentorus.swp", 2.2, -1.0, DVec3::Z)];
    println!(
        "| file | T | adaptive triangles | adaptive deviation | uniform triangles (steps ×f) | uniform deviation |"
    );
    println!("|---|---|---|---|---|---|");
    for (file, r0, sx, axis) in files {
        let doc = load(file);
        let curve = doc.curves[0].to_curve().unwrap();
        let surface = deviation::Revolution::new(&curve, r0, sx, axis);
        let measure = |m: &TriMesh| deviation::deviation(m, &surface, 6).0;
        let uniform = |f: f64| {
            let mut d = doc.clone();
            for c in &mut d.curves {
                c.steps = ((f64::from(c.steps) * f).round() as u32).max(1);
            }
            for sf in &mut d.surfaces {
                if let SwpSurfaceKind::Revolution { steps, .. } = &mut sf.kind {
                    *steps = ((f64::from(*steps) * f).round() as u32).max(3);
                }
            }
            let m = d.surface_mesh(0, &opts(SurfaceTessellation::FileSteps)).unwrap();
            let dev = measure(&m);
            (m.num_triangles(), dev)
        };
        let (n1, d1) = uniform(1.0);
        for t in [2.0 * d1, d1, 0.5 * d1, 0.25 * d1, 0.1 * d1] {
            let m = doc.surface_mesh(0, &opts(SurfaceTessellation::Distance(t))).unwrap();
            let dm = measure(&m);
            // deviation ~ 1/f²: start there and step by 2 % until within t
            let mut f = (d1 / t).sqrt();
            let (mut nu, mut du) = uniform(f);
            while du > t {
                f *= 1.02;
                (nu, du) = uniform(f);
            }
            while f > 0.05 {
                let (n2, d2) = uniform(f / 1.02);
                if d2 > t {
                    break;
                }
                (f, nu, du) = (f / 1.02, n2, d2);
            }
            let _ = n1;
            println!("| {file} | {t:.3e} | {} | {dm:.3e} | {nu} (×{f:.2}) | {du:.3e} |", m.num_triangles());
        }
    }
}
