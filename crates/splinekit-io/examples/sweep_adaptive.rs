//! Triangle counts of adaptive sweeps (`--tolerance T`) against uniform sweeps of equal
//! accuracy, with each mesh's largest distance from the exact surface measured on triangle
//! interiors. Run from the workspace root:
//!
//! ```text
//! cargo run --release -p splinekit-io --example sweep_adaptive [DATA_DIR]
//! ```
//!
//! `DATA_DIR` (default: the crate's `tests/data/swp`) holds `srev/wineglass.swp` and `gcyl/{gentorus,weirder}.swp`.

#[path = "../tests/deviation/mod.rs"]
mod deviation;

use glam::{DVec2, DVec3};
use splinekit::TriMesh;
use splinekit::sweep::{MeshLayout, SweepOptions};
use splinekit_io::surface::{SurfaceFrames, SurfaceOptions, SurfaceTessellation};
use splinekit_io::swp::{SwpDocument, SwpSurfaceKind};

/// How a file's exact surface is measured.
#[derive(Clone, Copy)]
enum Exact {
    /// A revolution of the profile (curve 0) as `(r0 + sx·x, y)` about `axis`.
    Revolution(f64, f64, DVec3),
    /// A generalized cylinder of curve 0 along curve 1 (exact frames: `deviation::Cylinder`).
    Cylinder,
}

/// One row: a tolerance, the adaptive mesh and its measured deviation, and the uniform
/// mesh (the file's steps, every curve's and the revolution's scaled by one factor) with the
/// fewest steps whose measured deviation is within the tolerance.
fn main() {
    let dir =
        std::env::args().nth(1).unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/swp").to_owned());
    let load = |f: &str| {
        let path = format!("{dir}/{f}");
        SwpDocument::parse(&std::fs::read_to_string(&path).expect("read"), &path).expect("parse")
    };
    let opts = |t: SurfaceTessellation, frames: SurfaceFrames| SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Compat, uvs: false, caps: false, ..SweepOptions::default() },
        tessellation: t,
        frames,
        ..SurfaceOptions::default()
    };
    // (file, exact surface, frames): gentorus is a profile along a circle of radius 2.2
    // about +z, N toward the centre, so a revolution; weirder's path leaves the xy plane and
    // is measured with rotation-minimizing frames
    let files = [
        ("srev/wineglass.swp", Exact::Revolution(0.0, 1.0, DVec3::Y), SurfaceFrames::Sequential),
        ("gcyl/gentorus.swp", Exact::Revolution(2.2, -1.0, DVec3::Z), SurfaceFrames::Sequential),
        ("gcyl/weirder.swp", Exact::Cylinder, SurfaceFrames::RotationMinimizing),
    ];
    println!(
        "| file | T | adaptive triangles | adaptive deviation | uniform triangles (steps ×f) | uniform deviation |"
    );
    println!("|---|---|---|---|---|---|");
    for (file, exact, frames) in files {
        let doc = load(file);
        let profile = doc.curves[0].to_curve().unwrap();
        let path = doc.curves.get(1).map(|c| c.to_curve().unwrap());
        let (revolution, cylinder) = match exact {
            Exact::Revolution(r0, sx, axis) => (Some(deviation::Revolution::new(&profile, r0, sx, axis)), None),
            Exact::Cylinder => {
                let path = path.as_ref().expect("a path");
                (None, Some(deviation::Cylinder::new(&profile, DVec2::ZERO, path, 2048, 512)))
            }
        };
        let measure = |m: &TriMesh| match (&revolution, &cylinder) {
            (Some(r), _) => deviation::deviation(m, r, 6).0,
            (_, Some(c)) => deviation::cylinder_deviation(m, c, 6).0,
            _ => unreachable!(),
        };
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
            let m = d.surface_mesh(0, &opts(SurfaceTessellation::FileSteps, frames)).unwrap();
            let dev = measure(&m);
            (m.num_triangles(), dev)
        };
        let (_, d1) = uniform(1.0);
        for t in [2.0 * d1, d1, 0.5 * d1, 0.25 * d1, 0.1 * d1] {
            let m = doc.surface_mesh(0, &opts(SurfaceTessellation::Distance(t), frames)).unwrap();
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
            println!("| {file} | {t:.3e} | {} | {dm:.3e} | {nu} (×{f:.2}) | {du:.3e} |", m.num_triangles());
        }
    }
}
