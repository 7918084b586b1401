//! `SwpDocument::surface_counts` gives the counts of the mesh `surface_poly` builds (the
//! file's), and `surface_mesh` (for drawing) has its triangles, for every
//! surface of every bundled SWP file and of every kind, in both layouts, with and without
//! caps, UVs, and each way of tessellating.

use std::path::{Path, PathBuf};

use splinekit::sweep::{MeshCounts, MeshLayout, SweepOptions};
use splinekit_io::SwpDocument;
use splinekit_io::surface::{SurfaceError, SurfaceFrames, SurfaceOptions, SurfaceTessellation};

fn swp_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            swp_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "swp") {
            out.push(path);
        }
    }
}

/// The options the commands use: both layouts, caps, UVs, file steps and both tolerances.
fn option_sets() -> Vec<SurfaceOptions> {
    let mut sets = Vec::new();
    for layout in [MeshLayout::Welded, MeshLayout::Compat] {
        for (uvs, caps) in [(false, false), (false, true), (true, false), (true, true)] {
            for tessellation in
                [SurfaceTessellation::FileSteps, SurfaceTessellation::Distance(0.01), SurfaceTessellation::Angle(0.2)]
            {
                sets.push(SurfaceOptions {
                    sweep: SweepOptions { layout, uvs, caps, ..SweepOptions::default() },
                    tessellation,
                    frames: SurfaceFrames::RotationMinimizing,
                    ..SurfaceOptions::default()
                });
            }
        }
    }
    sets
}

#[test]
fn counts_are_those_of_the_built_meshes_for_every_bundled_surface() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    swp_files(&root.join("tests/data/swp"), &mut files);
    swp_files(&root.join("../../examples"), &mut files);
    files.sort();
    // and the kinds of the extensions, as their documentation shows them
    let extensions = "bsp2 profile 10 6 [0 -1] [1.2 -1] [0.4 0] [0.5 0.6] [1.2 1.2] [1.3 1.4]
zrev vase profile epsilon 0.05 slice-tolerance 0.1 scale 2
bsp2 ring 10 5 closed [-1 0] [-0.309 -0.951] [0.809 -0.588] [0.809 0.588] [-0.309 0.951]
bsp2 arc 10 5 [-1 0] [-0.309 -0.951] [0.809 -0.588] [0.809 0.588] [-0.309 0.951]
xsweep doughnut ring ring epsilon 0.0558213 path-epsilon 0.050699063 scale 0.38264847
xsweep tube ring arc epsilon 0.1 path-epsilon 0.1 scale 0.2
bez2 r 8 7 [0 0] [0.1 0.55] [0.2 1] [0.5 1] [0.8 1] [0.9 0.55] [1 0]
bez2 z 8 7 [0 -1] [0.1 -1] [0.2 -0.55] [0.5 0] [0.8 0.55] [0.9 1] [1 1]
lathe ball 32 48 r z
";
    let mut docs = vec![(PathBuf::from("extensions"), SwpDocument::parse(extensions, "extensions.swp").unwrap())];
    docs.extend(files.iter().map(|f| (f.clone(), SwpDocument::read(f).unwrap())));
    let mut checked = 0;
    let mut kinds = std::collections::BTreeSet::new();
    for (file, doc) in &docs {
        for (k, surface) in doc.surfaces.iter().enumerate() {
            kinds.insert(format!("{:?}", surface.kind).split([' ', '{']).next().unwrap().to_owned());
            for options in option_sets() {
                let built = doc.surface_poly(k, &options).map(|m| MeshCounts {
                    vertices: m.mesh.num_vertices() as u64,
                    triangles: m.mesh.num_faces() as u64,
                });
                let counted = doc.surface_counts(k, &options);
                match (&counted, &built) {
                    (Ok(c), Ok(b)) => {
                        assert_eq!(c, b, "{} surface {k} {options:?}", file.display());
                        let drawn = doc.surface_mesh(k, &options).unwrap();
                        assert_eq!(drawn.num_triangles() as u64, c.triangles, "{}", file.display());
                    }
                    (Err(c), Err(b)) => assert_eq!(c.to_string(), b.to_string()),
                    _ => panic!("{} surface {k} {options:?}: {counted:?} but built {built:?}", file.display()),
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 300, "{checked} surface and option pairs");
    // every kind of surface is among them
    let all = ["GeneralizedCylinder", "Lathe", "Revolution", "RevolutionZ", "ToolSweep"];
    assert_eq!(kinds.iter().map(String::as_str).collect::<Vec<_>>(), all);
}

/// A revolution of a million slices around a 1001-point profile is counted, not built: its
/// counts are the closed form's, and past the triangle limit it is refused as the builder
/// refuses it.
#[test]
fn huge_surfaces_are_counted_from_their_samples() {
    let doc = SwpDocument::parse("bsp2 p 1000 4 [1 0] [2 1] [1 2] [1 3]\nsrev s 24000 p\n", "big.swp").unwrap();
    let counts = doc.surface_counts(0, &SurfaceOptions::default()).unwrap();
    // 1001 profile points off the axis, 24 000 copies, two triangles per quad
    assert_eq!(counts, MeshCounts { vertices: 1001 * 24_000, triangles: 2 * 1000 * 24_000 });
    let doc = SwpDocument::parse("bsp2 p 1000 4 [1 0] [2 1] [1 2] [1 3]\nsrev s 1000000 p\n", "big.swp").unwrap();
    assert!(matches!(
        doc.surface_counts(0, &SurfaceOptions::default()),
        Err(SurfaceError::TooLarge { triangles: 2_000_000_000, .. })
    ));
}
