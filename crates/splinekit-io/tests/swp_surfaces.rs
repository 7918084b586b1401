//! The `zrev` (revolution about +z, the revolution tool's settings) and `lathe` (separate
//! radius and height curves) surfaces: parsing, errors with positions, validation, writing
//! and reading back, and their meshes against closed forms and the annotated-OBJ rebuild.

use core::f64::consts::{PI, TAU};

use glam::DVec2;
use splinekit::ParamCurve;
use splinekit::sweep::{MeshLayout, SweepOptions};
use splinekit_io::mesh::{RebuildOptions, RevolutionHeader};
use splinekit_io::surface::{SurfaceError, SurfaceOptions, SurfaceTessellation};
use splinekit_io::swp::{DEFAULT_ZREV_EPSILON, DEFAULT_ZREV_SLICE_TOLERANCE};
use splinekit_io::{SwpDocument, SwpInvalidKind, SwpNumber, SwpSurfaceKind};

fn parse(text: &str) -> SwpDocument {
    SwpDocument::parse(text, "t.swp").unwrap_or_else(|e| panic!("{e}"))
}

fn parse_err(text: &str) -> String {
    SwpDocument::parse(text, "t.swp").map(|_| ()).unwrap_err().to_string()
}

/// A profile from (1, −1) out to (2, 0) and back in to (1, 1): a B-spline on the x > 0 side.
const BSP: &str = "bsp2 p 10 5 [1 -1] [2 -1] [2.5 0] [2 1] [1 1]\n";

#[test]
fn zrev_parses_with_defaults_and_options() {
    let doc = parse(&format!("{BSP}zrev a p\nzrev b p scale 2 epsilon 0.05 slice-tolerance 0.5\n"));
    assert_eq!(
        doc.surfaces[0].kind,
        SwpSurfaceKind::RevolutionZ {
            profile: 0,
            epsilon: DEFAULT_ZREV_EPSILON,
            slice_tolerance: DEFAULT_ZREV_SLICE_TOLERANCE,
            scale: 1.0
        }
    );
    assert_eq!(
        doc.surfaces[1].kind,
        SwpSurfaceKind::RevolutionZ { profile: 0, epsilon: 0.05, slice_tolerance: 0.5, scale: 2.0 }
    );
    // written back: defaults left out, the rest exactly
    let text = doc.to_swp_string();
    assert!(text.contains("zrev a p\n"), "{text}");
    assert!(text.contains("zrev b p epsilon 0.05 slice-tolerance 0.5 scale 2\n"), "{text}");
    let again = SwpDocument::parse(&text, "again.swp").unwrap();
    assert_eq!(again.surfaces[1].kind, doc.surfaces[1].kind);
}

#[test]
fn lathe_parses_and_writes_back() {
    let doc = parse(
        "bez2 r 8 4 [0 0] [0.3 1] [0.6 1] [1 0]\nbez2 z 8 4 [0 -1] [0.3 -1] [0.6 1] [1 1]\nlathe vase 24 48 r z\n",
    );
    assert_eq!(doc.surfaces[0].kind, SwpSurfaceKind::Lathe { stacks: 24, slices: 48, radius: 0, height: 1 });
    let text = doc.to_swp_string();
    assert!(text.ends_with("lathe vase 24 48 r z\n"), "{text}");
    assert_eq!(SwpDocument::parse(&text, "again.swp").unwrap().surfaces[0].kind, doc.surfaces[0].kind);
}

#[test]
fn bad_numbers_are_errors_at_their_position() {
    let cases = [
        ("zrev a p epsilon 0", "t.swp:2:18", "an angle tolerance"),
        ("zrev a p scale -1", "t.swp:2:16", "a scale"),
        ("zrev a p slice-tolerance 0.000001", "t.swp:2:26", "a slice tolerance"),
        ("zrev a p scale 2 scale 3", "t.swp:2:18", "at most one"),
        ("lathe a 10 2 p p", "t.swp:2:12", "a slice count (an integer from 3"),
        ("lathe a 0 8 p p", "t.swp:2:9", "step"),
        ("bsp3 q 10 4 [0 0 0] [1 0 0] [1 1 0] [0 1 1]\nlathe a 10 8 p q", "t.swp:3:16", "as the height curve"),
    ];
    for (line, at, what) in cases {
        let message = parse_err(&format!("{BSP}{line}\n"));
        assert!(message.starts_with(at) && message.contains(what), "{line}: {message}");
    }
}

#[test]
fn validate_checks_the_numbers() {
    let mut doc = parse(&format!("{BSP}zrev a p\nlathe b 4 8 p p\n"));
    assert_eq!(doc.validate(), Ok(()));
    doc.surfaces[0].kind =
        SwpSurfaceKind::RevolutionZ { profile: 0, epsilon: f64::NAN, slice_tolerance: 0.1, scale: 1.0 };
    let err = doc.validate().unwrap_err();
    assert!(matches!(err.kind(), SwpInvalidKind::NonFinite { number: SwpNumber::Epsilon, .. }), "{err}");
    doc.surfaces[0].kind = SwpSurfaceKind::RevolutionZ { profile: 0, epsilon: 0.1, slice_tolerance: 1e-9, scale: 1.0 };
    assert!(doc.validate().unwrap_err().to_string().contains("at most 1000000 slices"));
    doc.surfaces[0].kind = SwpSurfaceKind::Lathe { stacks: 4, slices: 2, radius: 0, height: 0 };
    assert_eq!(doc.validate().unwrap_err().kind(), &SwpInvalidKind::Slices { found: 2 });
}

/// A `zrev` of a B-spline is the revolution tool's surface: the same mesh as the annotated
/// OBJ header with the same spline and settings, rebuilt.
#[test]
fn zrev_is_the_revolution_tools_surface() {
    let doc = parse(&format!("{BSP}zrev a p epsilon 0.2 slice-tolerance 0.4 scale 1.5\n"));
    let mesh = doc.surface_mesh(0, &SurfaceOptions::default()).unwrap();
    let header = RevolutionHeader {
        closed: false,
        epsilon: 0.2,
        is_bspline: true,
        scale: 1.5,
        slice_tolerance: 0.4,
        control_points: [(1.0, -1.0), (2.0, -1.0), (2.5, 0.0), (2.0, 1.0), (1.0, 1.0)]
            .map(|(x, y)| DVec2::new(x, y))
            .to_vec(),
    };
    let rebuilt = header.rebuild(&RebuildOptions::DEFAULT).unwrap();
    assert_eq!(mesh, rebuilt);
    // ceil(2π/0.4) = 16 slices, the profile's samples in each
    assert_eq!(mesh.num_vertices() % 16, 0);
    assert_eq!(mesh.num_triangles(), 2 * 16 * (mesh.num_vertices() / 16 - 1));
}

/// A half circle about +z is a sphere of radius `s·r`: closed, outward, its volume close to
/// 4/3·π·(s·r)³, and every vertex at that distance within the chord error.
#[test]
fn zrev_of_a_half_circle_is_a_sphere() {
    // a Bézier half circle of radius 1 from the south to the north pole
    let k = 0.552_284_75;
    let doc = parse(&format!(
        "bez2 half 10 7 [0 -1] [{k} -1] [1 -{k}] [1 0] [1 {k}] [{k} 1] [0 1]\nzrev ball half epsilon 0.05 slice-tolerance {} scale 2\n",
        TAU / 64.0
    ));
    let mesh = doc.surface_mesh(0, &SurfaceOptions::default()).unwrap();
    assert!(mesh.is_closed_oriented());
    let volume = 4.0 / 3.0 * PI * 8.0;
    assert!((mesh.signed_volume() - volume).abs() < 0.02 * volume, "{}", mesh.signed_volume());
    for p in &mesh.positions {
        assert!((p.length() - 2.0).abs() < 2.0 * 1e-3 + 2.0 * (1.0 - (PI / 64.0).cos()), "{p}");
    }
    // the profile's y is the height
    let (lo, hi) = mesh.positions.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p.z), hi.max(p.z)));
    assert!((lo + 2.0).abs() < 1e-12 && (hi - 2.0).abs() < 1e-12);
}

/// `--tolerance` and `--angle-tolerance` replace a zrev's own ε and slice tolerance, and a
/// finer distance gives more vertices, all within the tolerance of the exact sphere.
#[test]
fn zrev_follows_the_tessellation_options() {
    let k = 0.552_284_75;
    let doc = parse(&format!("bez2 half 10 7 [0 -1] [{k} -1] [1 -{k}] [1 0] [1 {k}] [{k} 1] [0 1]\nzrev ball half\n"));
    let with = |t| doc.surface_mesh(0, &SurfaceOptions { tessellation: t, ..SurfaceOptions::default() }).unwrap();
    let coarse = with(SurfaceTessellation::Distance(1e-2));
    let fine = with(SurfaceTessellation::Distance(1e-4));
    assert!(fine.num_vertices() > 4 * coarse.num_vertices());
    // the Bézier circle itself is within 2.8e-4 of the unit circle
    for p in &fine.positions {
        assert!((p.length() - 1.0).abs() < 1e-4 + 3e-4, "{p}");
    }
    let angle = with(SurfaceTessellation::Angle(TAU / 20.0));
    // 20 slices: every ring has 20 vertices, poles aside
    assert_eq!((angle.num_vertices() - 2) % 20, 0);
}

/// A lathe's radius and height are the y coordinates of its curves, at the same fraction of
/// their parameter ranges: rings of `slices` vertices at `z(v)` with radius `r(v)`.
#[test]
fn lathe_rings_follow_the_curves() {
    // r: a B-spline (not a Bézier): keys come from its Bézier segments
    let doc = parse(
        "bsp2 r 8 6 [0 1] [0.2 1.5] [0.4 0.5] [0.6 2] [0.8 1] [1 1.2]\nbez2 z 8 4 [0 0] [0.3 1] [0.6 2] [1 3]\nlathe vase 12 16 r z\n",
    );
    let mesh = doc.surface_mesh(0, &SurfaceOptions::default()).unwrap();
    assert_eq!(mesh.num_vertices(), 16 * 13);
    assert_eq!(mesh.num_triangles(), 2 * 16 * 12);
    let r = doc.curves[0].to_curve().unwrap();
    let z = doc.curves[1].to_curve().unwrap();
    for j in 0..=12 {
        let v = f64::from(j) / 12.0;
        let (radius, height) = (r.eval(v * r.domain().1).y, z.eval(v * z.domain().1).y);
        let ring: Vec<_> = mesh.positions.iter().filter(|p| (p.z - height).abs() < 1e-9).collect();
        assert_eq!(ring.len(), 16, "ring {j} at z = {height}");
        for p in ring {
            assert!((p.truncate().length() - radius).abs() < 1e-9, "ring {j}: {p}");
        }
    }
}

/// Rounded tips: a radius curve that starts and ends at 0 closes in one pole each.
#[test]
fn lathe_with_tips_is_closed() {
    let k = 0.552_284_75;
    let doc = parse(&format!(
        "bez2 r 8 7 [0 0] [0 {k}] [0 1] [0 1] [0 1] [0 {k}] [0 0]\nbez2 z 8 7 [0 -1] [0 -1] [0 -{k}] [0 0] [0 {k}] [0 1] [0 1]\nlathe ball 32 48 r z\n"
    ));
    let mesh = doc.surface_mesh(0, &SurfaceOptions::default()).unwrap();
    assert!(mesh.is_closed_oriented());
    assert_eq!(mesh.num_vertices(), 2 + 48 * 31);
    // a lathe too large for the limit is refused before it is built
    let small = SurfaceOptions { max_triangles: Some(1000), ..SurfaceOptions::default() };
    assert!(matches!(doc.surface_mesh(0, &small), Err(SurfaceError::TooLarge { .. })));
}

#[test]
fn what_cannot_be_revolved_says_why() {
    let across = parse("bsp2 p 10 4 [-2 0] [-2 1] [2 1] [2 0]\nzrev a p\n");
    let err = across.surface_mesh(0, &SurfaceOptions::default()).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("surface a") && err.contains("crosses the axis"), "{err}");
    let circle = parse("circ c 10 1\nzrev a c\n");
    let err = circle.surface_mesh(0, &SurfaceOptions::default()).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("must be a cubic spline"), "{err}");
    let negative = parse("bez2 r 8 4 [0 1] [0 -1] [0 1] [0 1]\nbez2 z 8 4 [0 0] [0 1] [0 2] [0 3]\nlathe a 4 8 r z\n");
    let err = negative.surface_mesh(0, &SurfaceOptions::default()).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("surface a"), "{err}");
    // layouts and caps do not change a revolution about +z
    let doc = parse(&format!("{BSP}zrev a p\n"));
    let compat = SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Compat, uvs: false, caps: false, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    };
    assert_eq!(doc.surface_mesh(0, &compat).unwrap(), doc.surface_mesh(0, &SurfaceOptions::default()).unwrap());
}

// ---------------------------------------------------------------------------------------
// A surface's own settings

/// A ring swept along an open curve, written with and without its own settings.
const TUBE: &str = "circ ring 12 0.2\nbez3 path 10 4 [0 0 0] [1 0 1] [2 1 1] [3 1 0]\n";

#[test]
fn settings_are_read_written_back_and_checked() {
    use splinekit_io::swp::{SwpFrames, SwpTessellation};
    let doc = parse(&format!(
        "{TUBE}gcyl a ring path tolerance 0.01 frames rmf no-caps layout compat\ngcyl b ring path scale ring angle-tolerance 5 caps\n"
    ));
    let a = doc.surfaces[0].settings;
    assert_eq!(a.tessellation, Some(SwpTessellation::Distance(0.01)));
    assert_eq!(
        (a.frames, a.caps, a.layout),
        (Some(SwpFrames::RotationMinimizing), Some(false), Some(MeshLayout::Compat))
    );
    let b = doc.surfaces[1].settings;
    assert_eq!((b.tessellation, b.caps), (Some(SwpTessellation::AngleDegrees(5.0)), Some(true)));
    let text = doc.to_swp_string();
    assert!(text.contains("gcyl a ring path tolerance 0.01 layout compat frames rmf no-caps\n"), "{text}");
    assert!(text.contains("gcyl b ring path scale ring angle-tolerance 5 caps\n"), "{text}");
    let again = SwpDocument::parse(&text, "again.swp").unwrap();
    assert_eq!((again.surfaces[0].settings, again.surfaces[1].settings), (a, b));

    let cases = [
        (format!("{BSP}srev s 10 p frames rmf\n"), "t.swp:2:13", "frames applies to gcyl only"),
        (format!("{BSP}zrev s p layout welded\n"), "t.swp:2:10", "layout applies to srev, gcyl, xsweep only"),
        (format!("{TUBE}gcyl s ring path tolerance 0.1 angle-tolerance 4\n"), "t.swp:3:32", "at most one of tolerance"),
        (format!("{TUBE}gcyl s ring path angle-tolerance 200\n"), "t.swp:3:34", "at most 180"),
        (format!("{TUBE}gcyl s ring path frames up\n"), "t.swp:3:25", "sequential or rmf or frenet or zup"),
        (format!("{TUBE}gcyl s ring path caps no-caps\n"), "t.swp:3:23", "at most one of caps or no-caps"),
    ];
    for (text, at, what) in cases {
        let message = parse_err(&text);
        assert!(message.starts_with(at) && message.contains(what), "{text}: {message}");
    }
    let mut doc = parse(&format!("{BSP}srev s 10 p\n"));
    doc.surfaces[0].settings.caps = Some(true);
    assert_eq!(doc.validate().unwrap_err().to_string(), r#"surface "s": caps does not apply to srev surfaces"#);
}

/// The settings do what the same sweep options do.
#[test]
fn settings_replace_the_sweep_options() {
    use splinekit_io::surface::SurfaceFrames;
    let plain = parse(&format!("{TUBE}gcyl a ring path\n"));
    let own = parse(&format!("{TUBE}gcyl a ring path tolerance 0.001 frames rmf no-caps\n"));
    let asked = SurfaceOptions {
        tessellation: SurfaceTessellation::Distance(0.001),
        frames: SurfaceFrames::RotationMinimizing,
        sweep: SweepOptions { caps: false, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    };
    let by_settings = own.surface_mesh(0, &SurfaceOptions::default()).unwrap();
    assert_eq!(by_settings, plain.surface_mesh(0, &asked).unwrap());
    assert_ne!(by_settings, plain.surface_mesh(0, &SurfaceOptions::default()).unwrap());
    // a lathe's angle tolerance sets its slices: ceil(360 / 10) = 36
    let lathe = parse(
        "bez2 r 8 4 [0 1] [0 1] [0 1] [0 1]\nbez2 z 8 4 [0 0] [0 1] [0 2] [0 3]\nlathe a 4 8 r z angle-tolerance 10\n",
    );
    assert_eq!(lathe.surface_mesh(0, &SurfaceOptions::default()).unwrap().num_vertices(), 36 * 5);
    // a zrev with its own tolerance has no revolution-tool header
    let zrev = parse(&format!("{BSP}zrev a p tolerance 0.01\n"));
    let err = zrev.revolution_header(0).unwrap_err().to_string();
    assert!(err.contains("its own tolerance"), "{err}");
}

// ---------------------------------------------------------------------------------------
// The sweep tool's surface

/// The bundled sweep-tool files, as documents: each header opens as two bsp2 curves and an
/// xsweep whose mesh is the header's rebuild (welded and compat), and the document writes
/// the same header back; the SWP text reads back to the same document.
#[test]
fn sweep_tool_files_open_as_xsweep_documents_and_write_back() {
    use splinekit_io::mesh::SplineHeader;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/obj/cs4620-splines");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let Some(header @ SplineHeader::Sweep(_)) = SplineHeader::read(&path).unwrap() else { continue };
        seen += 1;
        let doc = header.to_document("tube").unwrap();
        assert!(matches!(doc.surfaces[0].kind, SwpSurfaceKind::ToolSweep { profile: 0, path: 1, .. }));
        for layout in [MeshLayout::Welded, MeshLayout::Compat] {
            let options = SurfaceOptions {
                sweep: SweepOptions { layout, uvs: false, caps: false, ..SweepOptions::default() },
                ..SurfaceOptions::default()
            };
            let rebuilt = header.rebuild(&RebuildOptions::DEFAULT.with_layout(layout)).unwrap();
            assert_eq!(doc.surface_mesh(0, &options).unwrap(), rebuilt, "{}", path.display());
        }
        assert_eq!(doc.annotated_header(0).unwrap(), header);
        let text = doc.to_swp_string();
        let again = SwpDocument::parse(&text, "again.swp").unwrap();
        assert_eq!(again.surfaces[0].kind, doc.surfaces[0].kind, "{text}");
        // written back as an annotated OBJ: the same header, read by the tool's layout
        let out = std::env::temp_dir().join(format!("splinekit-xsweep-{}-{seen}.obj", std::process::id()));
        doc.save_annotated_obj(0, &SurfaceOptions::default(), &out).unwrap();
        assert_eq!(SplineHeader::read(&out).unwrap(), Some(header));
        let head: Vec<String> = std::fs::read_to_string(&out).unwrap().lines().take(7).map(str::to_owned).collect();
        let original: Vec<String> =
            std::fs::read_to_string(&path).unwrap().lines().take(7).map(str::to_owned).collect();
        assert_eq!((&head[..4], &head[5..]), (&original[..4], &original[5..]), "the tool's layout");
        let _ = std::fs::remove_file(out);
    }
    assert_eq!(seen, 4);
}

#[test]
fn xsweep_parses_and_refuses_what_the_tool_cannot_hold() {
    let doc = parse(
        "bsp2 c 10 4 closed [1 0] [0 1] [-1 0] [0 -1]\nbsp2 p 10 4 closed [3 0] [0 3] [-3 0] [0 -3]\nxsweep t c p epsilon 0.1 scale 0.5 layout compat\n",
    );
    assert_eq!(
        doc.surfaces[0].kind,
        SwpSurfaceKind::ToolSweep { profile: 0, path: 1, epsilon: 0.1, path_epsilon: 0.05, scale: 0.5 }
    );
    assert!(doc.to_swp_string().ends_with("xsweep t c p epsilon 0.1 scale 0.5 layout compat\n"));
    assert!(doc.surface_mesh(0, &SurfaceOptions::default()).unwrap().num_triangles() > 0);
    let message = parse_err("bsp2 c 10 4 [1 0] [0 1] [-1 0] [0 -1]\nxsweep t c c frames rmf\n");
    assert!(message.starts_with("t.swp:2:14") && message.contains("frames applies to gcyl only"), "{message}");
    let cr = parse("cr2 c 10 4 closed [1 0] [0 1] [-1 0] [0 -1]\nxsweep t c c\n");
    let err = cr.annotated_header(0).unwrap_err().to_string();
    assert!(err.contains("2D B-splines (bsp2)"), "{err}");
    let err = cr.surface_mesh(0, &SurfaceOptions::default()).map(|_| ()).unwrap_err().to_string();
    assert!(err.contains("must be a 2D B-spline"), "{err}");
}

/// #42: `frames frenet` and `frames zup` are read, written back and sweep as they say: a
/// straight bar profile along a helix about z keeps each cross-section level (its profile x
/// axis, N, horizontal) with Z-up frames, and with Frenet frames (a helix's principal normal
/// points at its axis), but not with rotation-minimizing ones (which turn against the helix's
/// torsion).
#[test]
fn frenet_and_z_up_frames_keep_a_bar_level_along_a_helix() {
    let text = "bez2 bar 1 4 [-0.3 0] [-0.1 0] [0.1 0] [0.3 0]\nhelix coil 90 1 0.8 1.5\n\
                gcyl z bar coil frames zup\ngcyl f bar coil frames frenet\ngcyl r bar coil frames rmf\n";
    let doc = parse(text);
    let written = doc.to_swp_string();
    assert!(written.contains("gcyl z bar coil frames zup\n") && written.contains("gcyl f bar coil frames frenet\n"));
    let back = parse(&written);
    for (a, b) in doc.surfaces.iter().zip(&back.surfaces) {
        assert_eq!((a.kind, a.settings), (b.kind, b.settings));
    }
    let options = SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Compat, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    };
    // the widest tilt of a cross-section: the z difference of its two ends (one segment of
    // one step: two vertices per ring, ring by ring)
    let tilt = |k: usize| {
        let mesh = doc.surface_mesh(k, &options).unwrap();
        assert_eq!(mesh.positions.len(), 2 * 91);
        mesh.positions.chunks(2).map(|ring| (ring[0].z - ring[1].z).abs()).fold(0.0, f64::max)
    };
    assert!(tilt(0) <= 1e-12, "zup: {}", tilt(0));
    assert!(tilt(1) <= 1e-12, "frenet: {}", tilt(1));
    assert!(tilt(2) > 1e-2, "rmf: {}", tilt(2));
}

/// #42: `align origin|centre|start` puts the profile's origin, bounding-box centre or first
/// point on the path: a square away from the origin, swept up a straight line, stays where it
/// is, is centred on the line, or touches it with its first corner; read and written back.
#[test]
fn align_puts_the_chosen_point_of_the_profile_on_the_path() {
    let text = "bsp2 square 1 4 closed [1.5 0.5] [2.5 0.5] [2.5 1.5] [1.5 1.5]\n\
                bez3 up 4 4 [0 0 0] [0 0 1] [0 0 2] [0 0 3]\n\
                gcyl o square up frames zup\ngcyl c square up frames zup align centre\n\
                gcyl s square up frames zup align start\ngcyl a square up frames zup align center\n";
    let doc = parse(text);
    let written = doc.to_swp_string();
    assert!(written.contains("gcyl c square up frames zup align centre\n"), "{written}");
    assert!(written.contains("gcyl a square up frames zup align centre\n"), "`center` is read as `centre`");
    let back = parse(&written);
    for (a, b) in doc.surfaces.iter().zip(&back.surfaces) {
        assert_eq!(a.settings, b.settings);
    }
    let options =
        SurfaceOptions { sweep: SweepOptions { caps: false, ..SweepOptions::default() }, ..SurfaceOptions::default() };
    // the box of the walls' vertices across the path (x, y)
    let across = |k: usize| {
        let mesh = doc.surface_mesh(k, &options).unwrap();
        let lo = mesh.positions.iter().fold(DVec2::splat(f64::INFINITY), |m, p| m.min(p.truncate()));
        let hi = mesh.positions.iter().fold(DVec2::splat(f64::NEG_INFINITY), |m, p| m.max(p.truncate()));
        (lo, hi)
    };
    // origin: the profile's box centre stays at its distance from the line, |(2, 1)| = √5
    let (lo, hi) = across(0);
    let size = hi - lo;
    assert!(((0.5 * (lo + hi)).length() - 5f64.sqrt()).abs() < 1e-9, "{lo} {hi}");
    // centre (and center): the box centred on the line, the same size
    for k in [1, 3] {
        let (lo, hi) = across(k);
        assert!((0.5 * (lo + hi)).length() < 1e-9 && (hi - lo - size).length() < 1e-9, "surface {k}: {lo} {hi}");
    }
    // start: the profile's first point on the line, a vertex of every ring there
    let mesh = doc.surface_mesh(2, &options).unwrap();
    let on_line = mesh.positions.iter().filter(|p| p.truncate().length() < 1e-9).count();
    assert_eq!(on_line, 5, "one vertex on the line per path sample");
}

/// #42: `scale-mode override` makes the scale curve the profile's size: circles of radius 0.25
/// and 3 with the scale (0.7, 0.4) along a straight line both reach 0.7 along N and 0.4 along
/// B, where `multiply` (the default) scales each as drawn; a segment with no width keeps its
/// zero; without a scale curve the mode changes nothing; read and written back.
#[test]
fn scale_mode_override_gives_the_profile_its_size() {
    let text = "circ small 24 0.25\ncirc large 24 3\nbez2 bar 1 4 [0 -2] [0 -1] [0 1] [0 2]\n\
                bez2 s 1 4 [0.7 0.4] [0.7 0.4] [0.7 0.4] [0.7 0.4]\n\
                bez3 line 6 4 [0 0 0] [1 0 0] [2 0 0] [3 0 0]\n\
                gcyl sm small line scale s\ngcyl lm large line scale s scale-mode multiply\n\
                gcyl so small line scale s scale-mode override\ngcyl lo large line scale s scale-mode override\n\
                gcyl bo bar line scale s scale-mode override\n\
                gcyl plain large line\ngcyl plain-o large line scale-mode override\n";
    let doc = parse(text);
    let written = doc.to_swp_string();
    assert!(written.contains("gcyl lo large line scale s scale-mode override\n"), "{written}");
    assert!(written.contains("gcyl lm large line scale s scale-mode multiply\n"), "{written}");
    let back = parse(&written);
    for (a, b) in doc.surfaces.iter().zip(&back.surfaces) {
        assert_eq!((a.kind, a.settings), (b.kind, b.settings));
    }
    let options =
        SurfaceOptions { sweep: SweepOptions { caps: false, ..SweepOptions::default() }, ..SurfaceOptions::default() };
    // along +x in the xy plane N is +y (left of travel) and B is +z: the largest |y| and |z|
    let reach = |k: usize| {
        let mesh = doc.surface_mesh(k, &options).unwrap();
        mesh.positions.iter().fold(DVec2::ZERO, |m, p| m.max(DVec2::new(p.y.abs(), p.z.abs())))
    };
    let close = |a: DVec2, b: DVec2| (a - b).length() < 1e-12;
    assert!(close(reach(0), DVec2::new(0.7, 0.4) * 0.25), "{}", reach(0));
    assert!(close(reach(1), DVec2::new(0.7, 0.4) * 3.0), "{}", reach(1));
    for k in [2, 3] {
        assert!(close(reach(k), DVec2::new(0.7, 0.4)), "surface {k}: {}", reach(k));
    }
    assert!(close(reach(4), DVec2::new(0.0, 0.4)), "{}", reach(4));
    let (small, large) = (doc.surface_mesh(2, &options).unwrap(), doc.surface_mesh(3, &options).unwrap());
    let gap = small.positions.iter().zip(&large.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    assert!(gap < 1e-12, "override: the two circles differ by {gap:e}");
    assert_eq!(doc.surface_mesh(5, &options).unwrap(), doc.surface_mesh(6, &options).unwrap());
    // errors name the word and what was expected
    let head = "circ c 10 1\nbez3 l 1 4 [0 0 0] [0 0 1] [0 0 2] [0 0 3]\n";
    let err = parse_err(&format!("{head}gcyl g c l scale-mode sideways\n"));
    assert!(err.contains("3:23") && err.contains("expected multiply or override for the scale mode"), "{err}");
    let err = parse_err(&format!("{head}gcyl g c l scale-mode override scale-mode multiply\n"));
    assert!(err.contains("at most one of scale-mode"), "{err}");
    let err = parse_err("bez2 p 1 4 [-1 0] [-1 1] [-1 2] [-1 3]\nsrev g 10 p scale-mode override\n");
    assert!(err.contains("scale-mode applies to gcyl only"), "{err}");
}
