//! Sweeping every bundled SWP file: compat counts (SPEC §2.3), welded watertightness and
//! orientation, and geometry checked against closed forms.

use glam::DVec3;
use splinekit::TriMesh;
use splinekit::sweep::{MeshLayout, SweepOptions};
use splinekit_io::SwpDocument;
use splinekit_io::surface::{SurfaceFrames, SurfaceOptions, SurfaceTessellation};
use splinekit_io::swp::SwpSurfaceKind;

#[allow(dead_code)]
#[path = "swp/common.rs"]
mod common;

use common::{DATA_FILES, load};

fn opts(layout: MeshLayout) -> SurfaceOptions {
    SurfaceOptions {
        sweep: SweepOptions { layout, uvs: false, caps: false, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    }
}

fn compat(doc: &SwpDocument, k: usize) -> TriMesh {
    doc.surface_mesh(k, &opts(MeshLayout::Compat)).unwrap()
}

fn welded(doc: &SwpDocument, k: usize) -> TriMesh {
    doc.surface_mesh(k, &opts(MeshLayout::Welded)).unwrap()
}

/// SPEC §2.3.
const COUNTS: [(&str, usize, usize); 8] = [
    ("srev/norm.swp", 4590, 9000),
    ("srev/wineglass.swp", 16650, 33120),
    ("gcyl/tor.swp", 1891, 3600),
    ("gcyl/gentorus.swp", 3321, 6400),
    ("gcyl/florus.swp", 7686, 15000),
    ("gcyl/flircle.swp", 25551, 50000),
    ("gcyl/weird.swp", 8385, 16384),
    ("gcyl/weirder.swp", 5537, 10752),
];

#[test]
fn compat_counts_match_the_course_program() {
    for (file, v, t) in COUNTS {
        let doc = load(file);
        assert_eq!(doc.surfaces.len(), 1, "{file}");
        let m = compat(&doc, 0);
        m.validate().unwrap();
        assert_eq!((m.num_vertices(), m.num_triangles()), (v, t), "{file}");
    }
}

/// Every vertex normal within 90° of each face around it.
fn normals_agree(m: &TriMesh) -> bool {
    (0..m.num_triangles()).all(|i| {
        let f = m.face_normal(i);
        f.length() == 0.0 || m.triangles[i].iter().all(|&v| m.normals[v as usize].dot(f) > 0.0)
    })
}

fn min_area(m: &TriMesh) -> f64 {
    (0..m.num_triangles()).map(|i| 0.5 * m.face_normal(i).length()).fold(f64::INFINITY, f64::min)
}

#[test]
fn welded_closed_surfaces_are_watertight_and_outward() {
    // the closed ones: wineglass (poles at both ends) and every gcyl with closed profile and sweep
    for file in [
        "srev/wineglass.swp",
        "gcyl/tor.swp",
        "gcyl/gentorus.swp",
        "gcyl/florus.swp",
        "gcyl/flircle.swp",
        "gcyl/weird.swp",
        "gcyl/weirder.swp",
    ] {
        let doc = load(file);
        let m = welded(&doc, 0);
        m.validate().unwrap();
        assert!(
            m.is_closed_oriented(),
            "{file}: not a closed oriented manifold ({} boundary edges)",
            m.boundary_edges().len()
        );
        assert!(m.signed_volume() > 0.0, "{file}: volume {}", m.signed_volume());
        assert!(min_area(&m) > 0.0, "{file}: zero-area triangle");
        // flircle's sweep turns tighter (radius 0.089) than its tube is thick (0.4): the tube
        // folds through itself there, and the folded faces face inwards whatever the normals
        if file != "gcyl/flircle.swp" {
            assert!(normals_agree(&m), "{file}: a vertex normal disagrees with a face");
        }
        let c = compat(&doc, 0);
        assert_eq!(m.num_triangles(), c.num_triangles() - if file.starts_with("srev") { 2 * 90 } else { 0 }, "{file}");
        // Euler characteristic: sphere 2, torus 0
        let edges = 3 * m.num_triangles() / 2;
        let chi = m.num_vertices() as i64 - edges as i64 + m.num_triangles() as i64;
        assert_eq!(chi, if file.starts_with("srev") { 2 } else { 0 }, "{file}");
    }
}

#[test]
fn compat_surfaces_are_outward_too() {
    // (compat normals are the course program's, including horizontal normals at the
    // wineglass's poles, so only the faces are checked here)
    for (file, _, _) in COUNTS {
        let m = compat(&load(file), 0);
        if file != "srev/norm.swp" {
            assert!(m.signed_volume() > 0.0, "{file}: volume {}", m.signed_volume());
        }
    }
}

#[test]
fn torus_vertices_lie_on_the_torus() {
    // tor.swp: profile circle r = 0.5 swept along a circle R = 2 in the xy-plane
    for m in [compat(&load("gcyl/tor.swp"), 0), welded(&load("gcyl/tor.swp"), 0)] {
        for p in &m.positions {
            let ring = DVec3::new(p.x, p.y, 0.0).normalize() * 2.0;
            assert!((p.distance(ring) - 0.5).abs() < 1e-12, "{p}");
        }
        // normals point from the ring to the vertex
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let ring = DVec3::new(p.x, p.y, 0.0).normalize() * 2.0;
            assert!((*p - ring).normalize().dot(*n) > 1.0 - 1e-12);
        }
        let exact = 2.0 * std::f64::consts::PI.powi(2) * 2.0 * 0.25;
        assert!((m.signed_volume() - exact).abs() < 0.01 * exact);
    }
}

#[test]
fn revolution_vertices_keep_their_profile_radius() {
    use splinekit::ParamCurve;
    for file in ["srev/norm.swp", "srev/wineglass.swp"] {
        let doc = load(file);
        let m = compat(&doc, 0);
        let curve = doc.curves[0].to_curve().unwrap();
        let steps = doc.curves[0].steps as usize;
        let p = curve.num_segments() * steps + 1;
        for (v, q) in m.positions.iter().enumerate() {
            let i = v % p;
            let u = i as f64 / steps as f64;
            let prof = curve.eval(u);
            assert!((q.x.hypot(q.z) - prof.x.abs()).abs() < 1e-12, "{file} vertex {v}");
            assert!((q.y - prof.y).abs() < 1e-12, "{file} vertex {v}");
        }
    }
}

#[test]
fn weirder_seam_has_no_twist() {
    // the closed-sweep frame fix: the last copy of the profile equals the first
    let doc = load("gcyl/weirder.swp");
    let m = compat(&doc, 0);
    let p = doc.curves[0].steps as usize * 6 + 1; // bsp2 with 9 points: 6 segments
    let s = m.num_vertices() / p;
    for i in 0..p {
        let (first, last) = (m.positions[i], m.positions[(s - 1) * p + i]);
        assert!(first.distance(last) < 1e-9, "profile point {i}: {first} vs {last}");
    }
}

#[test]
fn every_bundled_file_sweeps() {
    for file in DATA_FILES {
        let doc = load(file);
        for k in 0..doc.surfaces.len() {
            for layout in [MeshLayout::Compat, MeshLayout::Welded] {
                for frames in [SurfaceFrames::Sequential, SurfaceFrames::RotationMinimizing] {
                    let o = SurfaceOptions { frames, ..opts(layout) };
                    let m = doc.surface_mesh(k, &o).unwrap_or_else(|e| panic!("{file} surface {k}: {e}"));
                    m.validate().unwrap_or_else(|e| panic!("{file} surface {k}: {e}"));
                }
            }
        }
    }
}

/// The adaptive sweep at the uniform sweep's accuracy has fewer triangles, and its welded
/// mesh is closed. The accuracy is the uniform mesh's largest distance from the exact
/// surface on its triangles' interiors (1.4605e-3, see `adaptive_sweeps.rs`), not the larger
/// of its curves' deviations (about 8.7e-4) that this test used when the adaptive sweep
/// bounded only its curves: profile and slice errors add inside the triangles.
#[test]
fn adaptive_wineglass_same_accuracy_fewer_triangles() {
    let doc = load("srev/wineglass.swp");
    let accuracy = 1.4605e-3;
    let uniform = compat(&doc, 0);
    let o = SurfaceOptions { tessellation: SurfaceTessellation::Distance(accuracy), ..opts(MeshLayout::Compat) };
    let adaptive = doc.surface_mesh(0, &o).unwrap();
    // 33 120 uniform against 14 840 adaptive (course figure: 18 540)
    assert!(
        adaptive.num_triangles() < uniform.num_triangles(),
        "{} vs {}",
        adaptive.num_triangles(),
        uniform.num_triangles()
    );
    let w = doc
        .surface_mesh(
            0,
            &SurfaceOptions { tessellation: SurfaceTessellation::Distance(accuracy), ..opts(MeshLayout::Welded) },
        )
        .unwrap();
    assert!(w.is_closed_oriented() && w.signed_volume() > 0.0);
}

#[test]
fn open_sweep_with_caps_encloses_a_prism() {
    let doc =
        SwpDocument::parse("circ p 30 0.5\nbez3 s 10 4 [0 0 0] [0 0 1] [0 0 2] [0 0 3]\ngcyl tube p s\n", "t.swp")
            .unwrap();
    let o = SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Welded, uvs: false, caps: true, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    };
    let m = doc.surface_mesh(0, &o).unwrap();
    m.validate().unwrap();
    // 30-gon prism of circumradius 0.5 and height 3
    let exact = 15.0 * 0.25 * (std::f64::consts::TAU / 30.0).sin() * 3.0;
    assert!((m.signed_volume() - exact).abs() < 1e-12, "{} vs {exact}", m.signed_volume());
    assert!(normals_agree(&m));
    // side: 11 rings of 30; caps: 30 + 30 vertices, 28 + 28 triangles
    assert_eq!((m.num_vertices(), m.num_triangles()), (11 * 30 + 60, 10 * 60 + 56));
    // without caps the same sweep is open with two boundary loops of 30 edges
    let o = SurfaceOptions { sweep: SweepOptions { caps: false, ..o.sweep }, ..o };
    assert_eq!(doc.surface_mesh(0, &o).unwrap().boundary_edges().len(), 60);
}

#[test]
fn caps_of_a_creased_profile_have_no_zero_area_triangles() {
    // A square profile of four straight Bézier sides: four creases, each sampled twice by the
    // welded layout; the caps must use each corner once.
    let doc = SwpDocument::parse(
        "bez2 sq 4 13 [1 1] [0.3 1] [-0.3 1] [-1 1] [-1 0.3] [-1 -0.3] [-1 -1] [-0.3 -1] [0.3 -1] [1 -1] [1 -0.3] \
         [1 0.3] [1 1]\nbez3 s 10 4 [0 0 0] [0 0 1] [0 0 2] [0 0 3]\ngcyl box sq s\n",
        "t.swp",
    )
    .unwrap();
    let o = SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Welded, uvs: false, caps: true, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    };
    let m = doc.surface_mesh(0, &o).unwrap();
    m.validate().unwrap();
    assert!(min_area(&m) > 1e-6, "zero-area triangle");
    // A 2 × 2 × 3 box.
    assert!((m.signed_volume() - 12.0).abs() < 1e-9, "{}", m.signed_volume());
}

#[test]
fn open_revolution_faces_away_from_its_axis() {
    // norm.swp's profile is open (a tube): its faces must point away from the y axis
    for layout in [MeshLayout::Compat, MeshLayout::Welded] {
        let m = load("srev/norm.swp").surface_mesh(0, &opts(layout)).unwrap();
        let flux: f64 = (0..m.num_triangles())
            .map(|i| {
                let [a, b, c] = m.corners(i);
                let centre = (a + b + c) / 3.0;
                m.face_normal(i).dot(DVec3::new(centre.x, 0.0, centre.z))
            })
            .sum();
        assert!(flux > 0.0);
        assert!(normals_agree(&m));
    }
}

#[test]
fn sharp_profile_corners_become_creases() {
    // a closed square profile of four straight Bézier segments (C0 at its corners) swept
    // along a circle of radius 3: a square torus
    let text = "bez2 sq 4 12 closed [1 1] [0.333333333333 1] [-0.333333333333 1] [-1 1] [-1 0.333333333333] \
                [-1 -0.333333333333] [-1 -1] [-0.333333333333 -1] [0.333333333333 -1] [1 -1] [1 -0.333333333333] \
                [1 0.333333333333]\ncirc ring 60 3\ngcyl sqtorus sq ring\n";
    let doc = SwpDocument::parse(text, "sq.swp").unwrap();
    let welded = doc.surface_mesh(0, &opts(MeshLayout::Welded)).unwrap();
    let compat = doc.surface_mesh(0, &opts(MeshLayout::Compat)).unwrap();
    // 4 segments · 4 steps = 16 profile chords; welded splits the 3 inner joins, and the
    // corner at the seam keeps both end samples (a crease too): 17 + 3 points per ring
    assert_eq!(compat.num_vertices(), 17 * 61);
    assert_eq!(welded.num_vertices(), (17 + 3) * 60);
    assert!(normals_agree(&welded), "normals must stay sharp at the corners");
    // every normal is one of the square's four face directions (radial, up, down, inward)
    for (p, n) in welded.positions.iter().zip(&welded.normals) {
        let radial = DVec3::new(p.x, p.y, 0.0).normalize();
        let best = [radial, -radial, DVec3::Z, -DVec3::Z].iter().map(|d| d.dot(*n)).fold(f64::MIN, f64::max);
        assert!(best > 0.99 || (p.z.abs() - 1.0).abs() < 1e-9, "{p}: {n}");
    }
    // Pappus: area 4 at distance 3 from the axis, less the 60-gon's shortfall
    let exact =
        4.0 * 2.0 * std::f64::consts::PI * 3.0 * (std::f64::consts::TAU / 60.0).sin() / (std::f64::consts::TAU / 60.0);
    assert!((welded.signed_volume() - exact).abs() < 1e-6 * exact, "{} vs {exact}", welded.signed_volume());
}

#[test]
fn the_triangle_limit_is_checked_before_the_mesh_is_built() {
    use splinekit_io::surface::SurfaceError;
    let limited = |o: SurfaceOptions, max: usize| SurfaceOptions { max_triangles: Some(max), ..o };
    // compat layouts: the count the limit is checked against is the mesh's own, so a limit of
    // exactly that count passes and one less fails, naming where the count comes from
    for (file, _, t) in COUNTS {
        let doc = load(file);
        let o = opts(MeshLayout::Compat);
        assert_eq!(doc.surface_mesh(0, &limited(o, t)).unwrap().num_triangles(), t, "{file}");
        match doc.surface_mesh(0, &limited(o, t - 1)) {
            Err(SurfaceError::TooLarge { triangles, limit, why, .. }) => {
                assert_eq!((triangles, limit), (t as u64, t - 1), "{file}");
                assert!(why.contains("slices") || why.contains("swept along"), "{file}: {why}");
            }
            other => panic!("{file}: {other:?}"),
        }
        // welded: poles and the split samples of creases drop a few triangles, so the count
        // checked is an upper bound, within 2% here
        let t = welded(&doc, 0).num_triangles();
        let o = opts(MeshLayout::Welded);
        match doc.surface_mesh(0, &limited(o, t - 1)) {
            Err(SurfaceError::TooLarge { triangles, .. }) => {
                assert!(triangles >= t as u64 && triangles as f64 <= 1.02 * t as f64, "{file}: {triangles} for {t}");
                assert_eq!(doc.surface_mesh(0, &limited(o, triangles as usize)).unwrap().num_triangles(), t);
            }
            other => panic!("{file}: {other:?}"),
        }
    }
    // a curve too finely tessellated by itself fails as soon as it is (here: 185 profile
    // points make at least 368 triangles)
    let doc = load("srev/wineglass.swp");
    let e = doc.surface_mesh(0, &limited(opts(MeshLayout::Compat), 100)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "surface wineglass would have about 368 triangles (one of its curves alone would have up to 185 \
         points), more than the limit of 100"
    );
    // caps count: an open sweep of a closed 13-point profile (12 distinct) along 4 points gets
    // 2·12·3 side triangles and two caps of 12 − 2; the check allows 12 a cap
    let text = "circ ring 12 1\nbez3 path 3 4 [0 0 0] [0 0 1] [0 0 2] [0 0 3]\ngcyl tube ring path\n";
    let doc = SwpDocument::parse(text, "tube.swp").unwrap();
    let capped = SurfaceOptions {
        sweep: SweepOptions { layout: MeshLayout::Welded, uvs: false, caps: true, ..SweepOptions::default() },
        ..opts(MeshLayout::Welded)
    };
    let m = doc.surface_mesh(0, &capped).unwrap();
    assert_eq!(m.num_triangles(), 2 * 12 * 3 + 2 * 10);
    match doc.surface_mesh(0, &limited(capped, 2 * 12 * 3 + 2 * 12 - 1)) {
        Err(SurfaceError::TooLarge { triangles, .. }) => assert_eq!(triangles, 2 * 12 * 3 + 2 * 12),
        other => panic!("{other:?}"),
    }
    assert_eq!(doc.surface_mesh(0, &limited(capped, 2 * 12 * 3 + 2 * 12)).unwrap(), m);
}

/// Issue #38 (found by the fuzz harness, `fuzz/`): a `zrev` swept with a distance tolerance
/// far finer than its profile made every profile point (about a million a segment, hundreds
/// of megabytes for a 100-byte file) before the triangle limit was checked. Now the points
/// are counted first, as for `srev` and `gcyl`, and the surface is refused at once.
#[test]
fn regression_38_zrev_counts_its_profile_before_making_it() {
    use splinekit_io::surface::SurfaceError;
    let text = "bsp2 p 10 16 [0.2 0] [1.4 1] [0.5 -1.2] [1.1 0.5] [1.5 -0.2] [0.9 1.3] [0.3 0.7] [1.2 -0.6] \
                [0.8 0.1] [1.3 1.1] [0.4 -0.8] [1 0.6] [0.6 -0.3] [1.4 0.9] [0.7 -1] [0.5 0.2]\nzrev vase p\n";
    let doc = SwpDocument::parse(text, "vase.swp").unwrap();
    let fine = SurfaceOptions {
        tessellation: SurfaceTessellation::Distance(1e-300),
        max_triangles: Some(200_000),
        ..SurfaceOptions::default()
    };
    let start = std::time::Instant::now();
    match doc.surface_mesh(0, &fine) {
        Err(SurfaceError::TooLarge { why, .. }) => assert!(why.contains("cross-section alone"), "{why}"),
        other => panic!("{other:?}"),
    }
    // it used to take seconds and gigabytes in a debug build
    assert!(start.elapsed().as_secs_f64() < 2.0, "{:?}", start.elapsed());
    // an ordinary tolerance still sweeps
    let ordinary = SurfaceOptions { tessellation: SurfaceTessellation::Distance(1e-3), ..fine };
    assert!(doc.surface_mesh(0, &ordinary).unwrap().num_triangles() > 0);
}

/// The default frames: along a path in a plane `z = const` (tor, gentorus, florus, flircle)
/// the course's sequential frames, which there agree with the rotation-minimizing ones, so
/// the course's vertices come out bit for bit; along a 3D path (weird, weirder)
/// rotation-minimizing frames; the compat layout keeps the course's frames everywhere.
#[test]
fn auto_frames_are_rotation_minimizing_off_the_plane_and_the_courses_in_it() {
    let with = |doc: &SwpDocument, layout, frames| {
        doc.surface_mesh(0, &SurfaceOptions { frames, ..opts(layout) }).unwrap().positions
    };
    let largest_gap = |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).map(|(p, q)| p.distance(*q)).fold(0.0, f64::max);
    for (file, planar) in [
        ("gcyl/tor.swp", true),
        ("gcyl/gentorus.swp", true),
        ("gcyl/florus.swp", true),
        ("gcyl/flircle.swp", true),
        ("gcyl/weird.swp", false),
        ("gcyl/weirder.swp", false),
    ] {
        let doc = load(file);
        let SwpSurfaceKind::GeneralizedCylinder { sweep, .. } = doc.surfaces[0].kind else { panic!("{file}") };
        // control points (none for a circle, which lies in the xy plane)
        let z = doc.curves[sweep].geometry.points().iter().map(|p| p.z);
        let (lo, hi) = z.fold((0.0, 0.0), |(lo, hi): (f64, f64), z| (lo.min(z), hi.max(z)));
        assert_eq!(hi - lo < 1e-12, planar, "{file}: path z in [{lo}, {hi}]");
        for layout in [MeshLayout::Welded, MeshLayout::Compat] {
            let auto = with(&doc, layout, SurfaceFrames::Auto);
            let sequential = with(&doc, layout, SurfaceFrames::Sequential);
            let rmf = with(&doc, layout, SurfaceFrames::RotationMinimizing);
            let gap = largest_gap(&sequential, &rmf);
            if planar || layout == MeshLayout::Compat {
                assert_eq!(auto, sequential, "{file} {layout:?}");
            } else {
                assert_eq!(auto, rmf, "{file} {layout:?}");
            }
            // the two methods agree in the plane, and drift apart along a 3D path
            if planar {
                assert!(gap < 1e-12, "{file} {layout:?}: {gap:e}");
            } else {
                assert!(gap > 1e-3, "{file} {layout:?}: {gap:e}");
            }
        }
    }
}
