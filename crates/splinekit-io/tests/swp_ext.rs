//! SWP extensions of issue #3: the `helix` and `trefoil` primitives and the gcyl `scale` and
//! `twist` clauses — parsing (including the rule that keeps clause words from being confused
//! with names or objects), errors with positions, writing and reading back, and the meshes
//! they sweep to, checked against closed forms and invariants.

use core::f64::consts::TAU;
use std::collections::HashSet;

use glam::{DVec2, DVec3};
use splinekit::sweep::{MeshLayout, SweepOptions};
use splinekit::{AnyCurve, ParamCurve, TriMesh};
use splinekit_io::surface::{SurfaceError, SurfaceOptions, SurfaceTessellation};
use splinekit_io::swp::SwpClause;
use splinekit_io::{SwpCurveKind, SwpDocument, SwpErrorKind, SwpGeometry, SwpSurfaceKind};

#[allow(dead_code)]
#[path = "swp/common.rs"]
mod common;

use common::{DATA_FILES, assert_error, parse, parse_err, without_positions};

/// The extension sample files, relative to `tests/data/swp`.
const EXT_FILES: [&str; 4] =
    ["ext/helix-spring.swp", "ext/trefoil.swp", "ext/scale-twist.swp", "ext/keyword-names.swp"];

/// Positions computed along different paths (frames, arc length) agree to this.
const GEOM_EQ: f64 = 1e-9;

fn opts(layout: MeshLayout, caps: bool) -> SurfaceOptions {
    SurfaceOptions {
        sweep: SweepOptions { layout, uvs: false, caps, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    }
}

fn mesh(doc: &SwpDocument, k: usize, layout: MeshLayout) -> TriMesh {
    doc.surface_mesh(k, &opts(layout, false)).unwrap_or_else(|e| panic!("surface {k}: {e}"))
}

fn gcyl(profile: usize, sweep: usize, scale: Option<usize>, twist: Option<usize>) -> SwpSurfaceKind {
    SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale, twist }
}

/// The mesh with vertices at bit-identical positions merged (`-0.0` counts as `0.0`) and the
/// triangles that this collapses left out. Welded meshes keep two vertices at a crease, and
/// caps have their own rim vertices (for sharp normals); a cap of a profile with creases also
/// has zero-area triangles over the doubled corners. Merged, a watertight surface is a closed
/// 2-manifold.
fn merged(m: &TriMesh) -> TriMesh {
    let key = |p: DVec3| (p + DVec3::ZERO).to_array().map(f64::to_bits);
    let mut first = std::collections::HashMap::new();
    let ids: Vec<u32> =
        m.positions.iter().enumerate().map(|(i, &p)| *first.entry(key(p)).or_insert(i as u32)).collect();
    let mut w = m.clone();
    w.triangles = m
        .triangles
        .iter()
        .map(|t| t.map(|v| ids[v as usize]))
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    w
}

/// Closed and consistently oriented once coincident vertices are merged, with positive volume;
/// returns the Euler characteristic `V − E + F` of the merged surface.
#[track_caller]
fn assert_watertight(m: &TriMesh, what: &str) -> i64 {
    m.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
    let w = merged(m);
    assert!(w.is_closed_oriented(), "{what}: {} boundary edges after merging", w.boundary_edges().len());
    assert!(m.signed_volume() > 0.0, "{what}: volume {}", m.signed_volume());
    let used: HashSet<u32> = w.triangles.iter().flatten().copied().collect();
    let edges = 3 * w.num_triangles() / 2;
    used.len() as i64 - edges as i64 + w.num_triangles() as i64
}

/// `V − E + F`, counting each undirected edge once.
fn euler_characteristic(m: &TriMesh) -> i64 {
    let edges: HashSet<(u32, u32)> = m
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |i| (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3]))))
        .collect();
    m.num_vertices() as i64 - edges.len() as i64 + m.num_triangles() as i64
}

// ---------------------------------------------------------------------------------------
// Parsing

#[test]
fn helix_and_trefoil_parse() {
    let doc = parse("helix coil 200 1.5 -0.25 3.5\ntrefoil knot 90 2\n");
    let (h, k) = (&doc.curves[0], &doc.curves[1]);
    assert_eq!((h.kind, h.keyword(), h.dim, h.steps, h.closed), (SwpCurveKind::Helix, "helix", 3, 200, false));
    assert_eq!(h.geometry, SwpGeometry::Helix { radius: 1.5, pitch: -0.25, turns: 3.5 });
    assert_eq!((k.kind, k.keyword(), k.dim, k.steps, k.closed), (SwpCurveKind::Trefoil, "trefoil", 3, 90, true));
    assert_eq!(k.geometry, SwpGeometry::Trefoil { size: 2.0 });
    assert!(matches!(h.to_curve().unwrap(), AnyCurve::Helix(_)));
    assert!(matches!(k.to_curve().unwrap(), AnyCurve::Trefoil(_)));
    // degenerate but valid values, as for circ
    let doc = parse("helix . 1 0 0 1e-3 trefoil . 1 0");
    assert_eq!(doc.curves[0].geometry, SwpGeometry::Helix { radius: 0.0, pitch: 0.0, turns: 1e-3 });
    assert_eq!(doc.curves[1].geometry, SwpGeometry::Trefoil { size: 0.0 });
    // `helix` and `trefoil` can still be names, as every keyword can
    let doc = parse("circ helix 10 1 helix trefoil 10 1 1 2 gcyl . helix trefoil");
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1, None, None));
}

#[test]
fn clauses_parse_in_either_order() {
    let curves = "circ p 10 1\nbsp3 w 10 4 [0 0 0] [0 0 1] [0 0 2] [0 0 3]\nbsp2 s 4 4 [1 1] [1 1] [2 2] [2 2]\nbez2 t 1 4 [0 0] [1 0] [2 0] [3 0]\n";
    for (clauses, scale, twist) in [
        ("", None, None),
        ("scale s", Some(2), None),
        ("twist t", None, Some(3)),
        ("scale s twist t", Some(2), Some(3)),
        ("twist t scale s", Some(2), Some(3)),
        ("\n  scale\ns # comment\n twist t", Some(2), Some(3)),
    ] {
        let doc = parse(&format!("{curves}gcyl g p w {clauses}\nsrev . 8 p\n"));
        assert_eq!(doc.surfaces[0].kind, gcyl(0, 1, scale, twist), "{clauses:?}");
        // the object after the clauses is read as before
        assert_eq!(doc.surfaces[1].kind, SwpSurfaceKind::Revolution { steps: 8, profile: 0 }, "{clauses:?}");
    }
}

#[test]
fn clause_words_are_not_names_and_names_are_not_clause_words() {
    // positions are fixed: a curve called `scale` as the sweep, then a scale clause using it;
    // a surface called `scale`; a curve called `twist` as the profile
    let doc = parse(
        "circ twist 10 0.2\nbsp2 scale 10 4 closed [1 0] [0 1] [-1 0] [0 -1]\n\
         gcyl g twist scale scale scale twist twist\n\
         gcyl h twist scale\n\
         circ other 5 1\n",
    );
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1, Some(1), Some(0)));
    assert_eq!(doc.surfaces[1].kind, gcyl(0, 1, None, None));
    assert_eq!(doc.curves.len(), 3);
    let doc = parse("circ p 10 1\ncirc w 10 2\ngcyl scale p w\ngcyl twist p w scale p");
    assert_eq!(doc.surface_index("scale"), Some(0));
    assert_eq!(doc.surfaces[1].kind, gcyl(0, 1, Some(0), None));
    // outside a gcyl, the clause words are not keywords
    let err = parse_err("circ p 10 1\nscale p");
    assert_error(&err, 2, 1, &[r#"found "scale", expected a keyword"#]);
    let err = parse_err("circ p 10 1\ncirc w 10 2\nsrev s 10 p twist w");
    assert_error(&err, 3, 13, &[r#"found "twist", expected a keyword"#]);
    // the sample file
    let doc = common::load("ext/keyword-names.swp");
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1, Some(2), Some(3)));
    assert_eq!(doc.surfaces[1].kind, gcyl(0, 1, None, None));
}

#[test]
fn plain_files_parse_exactly_as_before() {
    // none of the bundled course files has a clause or a new primitive, and writing one back
    // gives plain SWP again
    for rel in DATA_FILES {
        let doc = common::load(rel);
        for s in &doc.surfaces {
            if let SwpSurfaceKind::GeneralizedCylinder { scale, twist, .. } = s.kind {
                assert_eq!((scale, twist), (None, None), "{rel}");
            }
        }
        assert!(doc.curves.iter().all(|c| !matches!(c.kind, SwpCurveKind::Helix | SwpCurveKind::Trefoil)));
        let text = doc.to_swp_string();
        assert!(!text.contains("scale") && !text.contains("twist") && !text.contains("helix"), "{rel}");
    }
}

// ---------------------------------------------------------------------------------------
// Errors

#[test]
fn primitive_errors_point_at_the_token() {
    let cases: [(&str, usize, usize, &str); 9] = [
        ("helix h 10 -1 1 1", 1, 12, r#"found "-1", expected a radius (a number ≥ 0) for helix curve "h""#),
        (
            "helix h 10 1 nan 1",
            1,
            14,
            r#"found "nan", expected a pitch (the rise per turn, a number) for helix curve "h""#,
        ),
        ("helix h 10 1 1 0", 1, 16, r#"found "0", expected a number of turns (a number > 0 and ≤ 10000)"#),
        ("helix h 10 1 1 10001", 1, 16, r#"found "10001", expected a number of turns"#),
        ("helix . 10 1 1 [", 1, 16, r#"found "[", expected a number of turns"#),
        ("helix h 0 1 1 1", 1, 9, r#"found "0", expected a step count from 1 to 1000000 for helix curve "h""#),
        ("trefoil k 10 -2", 1, 14, r#"found "-2", expected a size (a number ≥ 0) for trefoil curve "k""#),
        ("trefoil k 10 1 closed", 1, 16, r#"found "closed", expected a keyword"#),
        ("HELIX h 10 1 1 1", 1, 1, "(keywords are lowercase)"),
    ];
    for (text, line, column, message) in cases {
        assert_error(&parse_err(text), line, column, &[message]);
    }
    let err = parse_err("helix h 10 1 1");
    assert_error(&err, 1, 15, &["found end of file, expected a number of turns"]);
    assert!(matches!(err.kind(), SwpErrorKind::UnexpectedEnd { .. }));
    // 3D curves cannot be profiles
    let err = parse_err("trefoil k 10 1\ncirc w 10 1\ngcyl g k w");
    assert_error(&err, 3, 8, &[r#"found 3D curve "k" (trefoil), expected a 2D curve"#, "as the profile of"]);
}

#[test]
fn clause_errors_point_at_the_token() {
    let head = "circ p 10 1\nhelix w 10 1 1 1\nbez3 d 10 4 [0 0 0] [1 0 0] [2 0 0] [3 0 0]\ncirc s 10 1\n";
    let cases: [(&str, usize, usize, &str); 8] = [
        ("gcyl g p w scale", 5, 17, r#"found end of file, expected the name of the scale curve of gcyl surface "g""#),
        (
            "gcyl g p w scale nope",
            5,
            18,
            r#"found "nope", expected the name of the scale curve of gcyl surface "g" (no curve of this name"#,
        ),
        ("gcyl g p w twist .", 5, 18, "(anonymous curves cannot be referenced)"),
        ("gcyl g p w scale [", 5, 18, r#"found "[", expected the name of the scale curve"#),
        (
            "gcyl g p w scale d",
            5,
            18,
            r#"found 3D curve "d" (bez3), expected a 2D curve (bez2, bsp2, cr2, her2, tcb2, bo2, bezn2, nurbs2 or circ) as the scale curve of gcyl surface "g""#,
        ),
        (
            "gcyl g p w twist w",
            5,
            18,
            r#"found 3D curve "w" (helix), expected a 2D curve (bez2, bsp2, cr2, her2, tcb2, bo2, bezn2, nurbs2 or circ) as the twist curve"#,
        ),
        (
            "gcyl g p w scale s scale s",
            5,
            20,
            "at most one scale clause for gcyl surface \"g\" (already given at line 5, column 12)",
        ),
        ("gcyl g p w twist s scale s twist p", 5, 28, "at most one twist clause"),
    ];
    for (tail, line, column, message) in cases {
        assert_error(&parse_err(&format!("{head}{tail}")), line, column, &[message]);
    }
    assert!(matches!(
        parse_err(&format!("{head}gcyl g p w scale d")).kind(),
        SwpErrorKind::CurveNot2D { role: SwpClause::Scale, .. }
    ));
    assert!(matches!(parse_err(&format!("{head}gcyl g p w scale s scale s")).kind(), SwpErrorKind::BadOption { .. }));
    // a surface is not a curve
    let err = parse_err(&format!("{head}gcyl g p w\ngcyl h p w scale g"));
    assert_error(&err, 6, 18, &["(this name is a surface)"]);
}

#[test]
fn sweeping_a_hand_built_document_checks_the_clause_curves() {
    let mut doc = parse("circ p 10 1\ncirc w 10 2\ntrefoil k 10 1\ngcyl g p w");
    doc.surfaces[0].kind = gcyl(0, 1, None, Some(2));
    let err = doc.surface_mesh(0, &SurfaceOptions::default()).unwrap_err();
    assert!(matches!(err, SurfaceError::ShapeNot2d { role: SwpClause::Twist, .. }), "{err}");
    assert_eq!(err.to_string(), "twist curve k of surface g is 3D; a twist curve must be a 2D curve");
}

// ---------------------------------------------------------------------------------------
// Writing

#[test]
fn writer_round_trips_the_extensions() {
    let text = "circ p 10 0.5\nhelix h 40 1.25 -0.5 2.75\ntrefoil k 64 0.1\n\
                bsp2 . 5 4 [1 1] [2 2] [2 2] [1 1]\nbez2 t 1 4 [0 0] [1 0] [2 0] [3 0]\n\
                gcyl a p h twist t scale 3\ngcyl b p k\ngcyl . p k scale t";
    // the anonymous scale curve cannot be referenced in a file, so the test names it by index
    let mut doc = parse(&text.replace(" scale 3", ""));
    doc.surfaces[0].kind = gcyl(0, 1, Some(3), Some(4));
    let written = doc.to_swp_string();
    assert_eq!(
        written,
        "circ p 10 0.5\n\nhelix h 40 1.25 -0.5 2.75\n\ntrefoil k 64 0.1\n\n\
         bsp2 _c3 5 4\n[1 1]\n[2 2]\n[2 2]\n[1 1]\n\nbez2 t 1 4\n[0 0]\n[1 0]\n[2 0]\n[3 0]\n\n\
         gcyl a p h scale _c3 twist t\n\ngcyl b p k\n\ngcyl . p k scale t\n"
    );
    let back = parse(&written);
    let mut expected = without_positions(doc);
    expected.curves[3].name = Some("_c3".into());
    assert_eq!(without_positions(back), expected);
}

#[test]
fn sample_files_round_trip_and_sweep() {
    for rel in EXT_FILES {
        let doc = common::load(rel);
        let back = parse(&doc.to_swp_string());
        assert_eq!(without_positions(back), without_positions(doc.clone()), "{rel}");
        for k in 0..doc.surfaces.len() {
            for layout in [MeshLayout::Compat, MeshLayout::Welded] {
                let m = doc.surface_mesh(k, &opts(layout, true)).unwrap_or_else(|e| panic!("{rel} {k}: {e}"));
                let what = format!("{rel} surface {k} {layout:?}");
                if layout == MeshLayout::Compat {
                    // (seams duplicated, as the course program does)
                    m.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
                    assert!(m.signed_volume() > 0.0, "{what}: volume {}", m.signed_volume());
                } else {
                    // a capped tube is a sphere, a closed one a torus
                    let chi = assert_watertight(&m, &what);
                    assert_eq!(chi, if sweeps_closed(&doc, k) { 0 } else { 2 }, "{what}");
                }
            }
        }
    }
}

/// Whether surface `k` sweeps along a closed curve.
fn sweeps_closed(doc: &SwpDocument, k: usize) -> bool {
    match doc.surfaces[k].kind {
        SwpSurfaceKind::GeneralizedCylinder { sweep, .. } | SwpSurfaceKind::ToolSweep { path: sweep, .. } => {
            doc.curves[sweep].closed
        }
        SwpSurfaceKind::Revolution { .. } | SwpSurfaceKind::RevolutionZ { .. } | SwpSurfaceKind::Lathe { .. } => true,
    }
}

// ---------------------------------------------------------------------------------------
// Meshes

#[test]
fn helix_sweep_rings_are_circles_around_the_helix() {
    // every vertex of ring k is at distance ρ from the helix point P(u_k), in its normal plane,
    // and so between r − ρ and r + ρ from the helix's axis
    let (r, pitch, turns, rho) = (1.5, 0.8, 2.5, 0.2);
    let doc = parse(&format!("circ wire 16 {rho}\nhelix coil 120 {r} {pitch} {turns}\ngcyl spring wire coil"));
    let helix = doc.curves[1].to_curve().unwrap();
    let m = mesh(&doc, 0, MeshLayout::Compat);
    let p = 17;
    assert_eq!((m.num_vertices(), m.num_triangles()), (121 * p, 120 * 16 * 2));
    for (v, q) in m.positions.iter().enumerate() {
        let u = (v / p) as f64 / 120.0;
        let centre = helix.eval(u);
        let tangent = helix.unit_tangent(u);
        assert!((q.distance(centre) - rho).abs() < GEOM_EQ, "vertex {v}: {}", q.distance(centre));
        assert!((*q - centre).dot(tangent).abs() < GEOM_EQ, "vertex {v} not in the normal plane");
        let axis = q.truncate().length();
        assert!(axis >= r - rho - GEOM_EQ && axis <= r + rho + GEOM_EQ, "vertex {v}: {axis}");
    }
    // the spring's volume: a tube of radius ρ along the helix's length, up to the polygon
    let welded = doc.surface_mesh(0, &opts(MeshLayout::Welded, true)).unwrap();
    assert_eq!(assert_watertight(&welded, "capped spring"), 2);
    let length = TAU * turns * (r * r + (pitch / TAU).powi(2)).sqrt();
    let polygon = 0.5 * 16.0 * rho * rho * (TAU / 16.0).sin();
    let volume = welded.signed_volume();
    assert!((volume - polygon * length).abs() < 0.01 * volume, "{volume} vs {}", polygon * length);
}

#[test]
fn constant_scale_doubles_every_profile_offset() {
    let base = "bsp2 prof 6 5 closed [1 0] [0.3 0.8] [-0.9 0.4] [-0.6 -0.7] [0.5 -0.6]\n\
                bsp3 path 12 6 [0 0 0] [1 0 1] [2 1 0] [3 0 -1] [4 1 0] [5 0 1]\n\
                bez2 two 3 4 [2 2] [2 2] [2 2] [2 2]\n";
    let plain = parse(&format!("{base}gcyl g prof path"));
    let scaled = parse(&format!("{base}gcyl g prof path scale two"));
    let path = plain.curves[1].to_curve().unwrap();
    let p = 5 * 6 + 1;
    for layout in [MeshLayout::Compat, MeshLayout::Welded] {
        let (a, b) = (mesh(&plain, 0, layout), mesh(&scaled, 0, layout));
        assert_eq!((a.num_vertices(), a.triangles.clone()), (b.num_vertices(), b.triangles.clone()));
        if layout == MeshLayout::Compat {
            for (v, (qa, qb)) in a.positions.iter().zip(&b.positions).enumerate() {
                let centre = path.eval((v / p) as f64 / 12.0);
                assert!(((*qb - centre) - (*qa - centre) * 2.0).length() < GEOM_EQ, "vertex {v}");
            }
        }
    }
    // anisotropic: (sx, sy) scales the offsets along N and B separately
    let aniso = parse(&format!("{base}bez2 flat 3 4 [3 0.5] [3 0.5] [3 0.5] [3 0.5]\ngcyl g prof path scale flat"));
    let (a, b) = (mesh(&plain, 0, MeshLayout::Compat), mesh(&aniso, 0, MeshLayout::Compat));
    let params: Vec<f64> = (0..=3 * 12).map(|i| i as f64 / 12.0).collect();
    let frames = splinekit::frame::frames(&path, &params, &splinekit::frame::FrameOptions::DEFAULT);
    for (v, (qa, qb)) in a.positions.iter().zip(&b.positions).enumerate() {
        let (f, centre) = (frames[v / p], path.eval((v / p) as f64 / 12.0));
        let (da, db) = (*qa - centre, *qb - centre);
        assert!((db.dot(f.n) - 3.0 * da.dot(f.n)).abs() < GEOM_EQ, "vertex {v}");
        assert!((db.dot(f.b) - 0.5 * da.dot(f.b)).abs() < GEOM_EQ, "vertex {v}");
    }
}

#[test]
fn linear_scale_grows_with_arc_length_not_parameter() {
    // a straight sweep whose parameter is far from its arc length (control points bunched at
    // the start), a circle profile of radius 0.5, and a scale line from (1, 1) to (2, 2): the
    // ring at distance z along the line has radius 0.5·(1 + z/3), whatever the tessellation
    let text = "circ c 24 0.5\nbez3 line 16 4 [0 0 0] [0 0 0.2] [0 0 0.5] [0 0 3]\n\
                bez2 grow 1 4 [1 1] [1.3333333333333333 1.3333333333333333] [1.6666666666666667 1.6666666666666667] [2 2]\n\
                gcyl horn c line scale grow";
    let doc = parse(text);
    for tessellation in [SurfaceTessellation::FileSteps, SurfaceTessellation::Distance(1e-3)] {
        for layout in [MeshLayout::Compat, MeshLayout::Welded] {
            let options = SurfaceOptions { tessellation, ..opts(layout, true) };
            let m = doc.surface_mesh(0, &options).unwrap();
            for q in &m.positions {
                let expected = 0.5 * (1.0 + q.z / 3.0);
                let radius = q.truncate().length();
                // cap vertices: the rim, and no others (the caps are fans of the rim)
                assert!(
                    (radius - expected).abs() < GEOM_EQ,
                    "{q}: {radius} vs {expected}, {tessellation:?} {layout:?}"
                );
            }
            // the parameter is not the arc length here: rings are not evenly spaced in z
            if tessellation == SurfaceTessellation::FileSteps && layout == MeshLayout::Compat {
                let zs: Vec<f64> = m.positions.iter().step_by(25).map(|q| q.z).collect();
                assert!((zs[8] - 1.5).abs() > 0.1, "{zs:?}");
            }
        }
    }
}

#[test]
fn twist_turns_each_ring_by_its_arc_length_share() {
    // the sample horn: a square (4 straight Bézier sides of 1 step: its 4 corners and the first
    // again) on a line along +z, where the sequential frames are N = +x, B = +y. The ring at
    // height z is the square scaled by 1 + z/3 and turned by 90°·z/3 counter-clockwise.
    let doc = common::load("ext/scale-twist.swp");
    let corners = [DVec2::new(-0.5, -0.5), DVec2::new(0.5, -0.5), DVec2::new(0.5, 0.5), DVec2::new(-0.5, 0.5)];
    let m = mesh(&doc, 0, MeshLayout::Compat);
    assert_eq!(m.num_vertices(), 17 * 5);
    for (v, q) in m.positions.iter().enumerate() {
        let sigma = q.z / 3.0;
        let corner = corners[(v % 5) % 4] * (1.0 + sigma);
        let expected = DVec2::from_angle((90.0 * sigma).to_radians()).rotate(corner);
        assert!((q.truncate() - expected).length() < GEOM_EQ, "vertex {v}: {q} vs {expected}");
    }
    // welded: the same surface with creases at the corners, closed by its caps
    let w = doc.surface_mesh(0, &opts(MeshLayout::Welded, true)).unwrap();
    assert_eq!(assert_watertight(&w, "horn"), 2);
    // volume: ∫ (1 + z/3)² dz over [0, 3] = 7 for the smooth horn. Without the twist the
    // rings are joined by planar trapezoids and the mesh encloses exactly that; with it each
    // twisted side quad is cut along the same diagonal, which adds a volume of first order in
    // the step: four times the steps, about a quarter of the error
    let text = common::text("ext/scale-twist.swp");
    let volume = |text: &str| parse(text).surface_mesh(0, &opts(MeshLayout::Welded, true)).unwrap().signed_volume();
    assert!((volume(&text.replace(" twist quarter", "")) - 7.0).abs() < GEOM_EQ);
    let coarse = volume(&text) - 7.0;
    let fine = volume(&text.replace("bez3 line 16 4", "bez3 line 64 4")) - 7.0;
    assert!(coarse.abs() < 0.1 * 7.0 && fine.abs() < coarse.abs() / 3.0, "{coarse} {fine}");
}

#[test]
fn full_twist_on_a_closed_sweep_still_closes() {
    // a square profile along a circle, twisted by 360°: the last ring of the compat layout
    // equals the first, and the welded mesh is closed and oriented, a torus
    let text = "bez2 square 1 12 closed [-0.2 -0.2] [0 -0.2] [0.2 -0.2] [0.2 -0.2] [0.2 0] [0.2 0.2] \
                [0.2 0.2] [0 0.2] [-0.2 0.2] [-0.2 0.2] [-0.2 0] [-0.2 -0.2]\n\
                circ ring 60 2\nbez2 turn 1 4 [0 0] [120 0] [240 0] [360 0]\n\
                gcyl g square ring twist turn";
    let doc = parse(text);
    let c = mesh(&doc, 0, MeshLayout::Compat);
    let p = 5;
    let rings = c.num_vertices() / p;
    assert_eq!(rings, 61);
    for i in 0..p {
        let (first, last) = (c.positions[i], c.positions[(rings - 1) * p + i]);
        assert!(first.distance(last) < GEOM_EQ, "profile point {i}: {first} vs {last}");
    }
    // halfway round, the square has turned by half a turn: each corner is where the opposite
    // corner would be without the twist
    let plain = mesh(&parse(&text.replace(" twist turn", "")), 0, MeshLayout::Compat);
    for i in 0..4 {
        let (twisted, untwisted) = (c.positions[30 * p + i], plain.positions[30 * p + (i + 2) % 4]);
        assert!(twisted.distance(untwisted) < GEOM_EQ, "corner {i}: {twisted} vs {untwisted}");
    }
    // welded: closed up to the creases at the square's corners (two vertices each, for sharp
    // normals), a torus
    let w = mesh(&doc, 0, MeshLayout::Welded);
    assert_eq!(assert_watertight(&w, "twisted square torus"), 0);
    // with a circle profile there are no creases: closed as it is
    let round = parse(&format!("circ c 12 0.2\n{}", &text[text.find("circ ring").unwrap()..]).replace("square", "c"));
    let w = mesh(&round, 0, MeshLayout::Welded);
    assert!(w.is_closed_oriented(), "{} boundary edges", w.boundary_edges().len());
    assert_eq!(euler_characteristic(&w), 0);
}

#[test]
fn welded_trefoil_tube_is_a_watertight_torus() {
    for text in [
        "circ c 16 0.3\ntrefoil k 150 1\ngcyl t c k",
        "circ c 16 0.3\ntrefoil k 150 1\nbsp2 s 4 5 closed [1 1] [1.3 0.8] [1 1] [0.8 1.3] [1 1]\ngcyl t c k scale s",
    ] {
        let doc = parse(text);
        for tessellation in [SurfaceTessellation::FileSteps, SurfaceTessellation::Distance(0.01)] {
            let options = SurfaceOptions { tessellation, ..opts(MeshLayout::Welded, true) };
            let m = doc.surface_mesh(0, &options).unwrap();
            m.validate().unwrap();
            assert!(m.is_closed_oriented(), "{} boundary edges", m.boundary_edges().len());
            assert!(m.signed_volume() > 0.0, "volume {}", m.signed_volume());
            assert_eq!(euler_characteristic(&m), 0, "{tessellation:?}");
        }
    }
    // the plain tube: every vertex at distance 0.3 from the knot point of its ring, and the
    // volume is about π·0.3²·length (Pappus for tubes, exact up to the polygon and curvature)
    let doc = parse("circ c 32 0.3\ntrefoil k 300 1\ngcyl t c k");
    let knot = doc.curves[1].to_curve().unwrap();
    let c = mesh(&doc, 0, MeshLayout::Compat);
    for (v, q) in c.positions.iter().enumerate() {
        let centre = knot.eval((v / 33) as f64 / 300.0);
        assert!((q.distance(centre) - 0.3).abs() < GEOM_EQ, "vertex {v}");
    }
    let w = mesh(&doc, 0, MeshLayout::Welded);
    let polygon = 0.5 * 32.0 * 0.09 * (TAU / 32.0).sin();
    let expected = polygon * knot.arclen(1e-9);
    assert!((w.signed_volume() - expected).abs() < 0.01 * expected, "{} vs {expected}", w.signed_volume());
}

#[test]
fn caps_follow_the_scale() {
    // an open helix sweep of a circle, scale (0.5, 0.5) at the start and (2, 2) at the end:
    // caps close it, and each cap's rim is the scaled ring
    let doc =
        parse("circ c 12 0.1\nhelix h 90 1 0.5 1.5\nbez2 s 1 4 [0.5 0.5] [1 1] [1.5 1.5] [2 2]\ngcyl g c h scale s");
    let helix = doc.curves[1].to_curve().unwrap();
    let m = doc.surface_mesh(0, &opts(MeshLayout::Welded, true)).unwrap();
    assert_eq!(assert_watertight(&m, "capped, scaled helix"), 2);
    let (start, end) = (helix.eval(0.0), helix.eval(1.0));
    let near = |centre: DVec3, radius: f64| {
        m.positions.iter().filter(|q| (q.distance(centre) - radius).abs() < GEOM_EQ).count()
    };
    // ring vertices plus cap vertices at each end
    assert!(near(start, 0.05) >= 2 * 12, "{}", near(start, 0.05));
    assert!(near(end, 0.2) >= 2 * 12, "{}", near(end, 0.2));
}

// ---------------------------------------------------------------------------------------
// Properties

mod properties {
    use proptest::prelude::*;
    use proptest::sample::select;

    use super::*;

    fn finite() -> impl Strategy<Value = f64> {
        prop_oneof![-1e6..1e6f64, Just(0.0), Just(-0.0), any::<f64>().prop_filter("finite", |v| v.is_finite())]
    }

    /// Random documents with helices, trefoils, 2D curves and gcyls with random clauses.
    fn document() -> impl Strategy<Value = SwpDocument> {
        let helix = (1..=1000u32, 0.0..1e3f64, finite(), 1e-6..=1e4f64);
        let trefoil = (1..=1000u32, prop_oneof![Just(0.0), 0.0..1e3f64]);
        let gcyl = (any::<prop::sample::Index>(), proptest::option::of(0..3usize), proptest::option::of(0..3usize));
        (prop::collection::vec(helix, 0..3), prop::collection::vec(trefoil, 0..3), prop::collection::vec(gcyl, 0..4))
            .prop_map(|(helices, trefoils, surfaces)| {
                // three 2D curves first: the profiles, scale and twist curves
                let mut text = String::from(
                    "circ c0 8 0.5\nbsp2 c1 4 4 [1 1] [2 2] [2 1] [1 1]\nbez2 c2 1 4 [0 0] [1 0] [2 0] [3 0]\n",
                );
                for (i, (steps, radius, pitch, turns)) in helices.iter().enumerate() {
                    text += &format!("helix h{i} {steps} {radius} {pitch} {turns}\n");
                }
                for (i, (steps, size)) in trefoils.iter().enumerate() {
                    text += &format!("trefoil k{i} {steps} {size}\n");
                }
                let sweeps: Vec<String> = (0..3)
                    .map(|i| format!("c{i}"))
                    .chain((0..helices.len()).map(|i| format!("h{i}")))
                    .chain((0..trefoils.len()).map(|i| format!("k{i}")))
                    .collect();
                for (j, (sweep, scale, twist)) in surfaces.iter().enumerate() {
                    text += &format!("gcyl g{j} c0 {}", sweeps[sweep.index(sweeps.len())]);
                    if let Some(s) = scale {
                        text += &format!(" scale c{s}");
                    }
                    if let Some(t) = twist {
                        text += &format!(" twist c{t}");
                    }
                    text.push('\n');
                }
                parse(&text)
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

        #[test]
        fn documents_round_trip(doc in document()) {
            let written = doc.to_swp_string();
            let again = SwpDocument::parse(&written, "written.swp").map_err(|e| TestCaseError::fail(format!("{e}\n{written}")))?;
            prop_assert_eq!(again.to_swp_string(), written.clone());
            prop_assert_eq!(without_positions(again), without_positions(doc), "{}", written);
        }

        #[test]
        fn token_soup_never_panics_and_errors_point_inside(
            words in prop::collection::vec(select(vec![
                "helix", "trefoil", "gcyl", "scale", "twist", "circ", "c", "d", ".", "1", "0", "-1", "2.5",
                "1e9", "nan", "[", "]", "#", "\n", "bsp3", "srev", "3",
            ]), 0..40)
        ) {
            let text = format!("circ c 8 1\nbsp3 d 4 4 [0 0 0] [1 0 0] [2 0 0] [3 0 0]\n{}", words.join(" "));
            match SwpDocument::parse(&text, "soup.swp") {
                Ok(doc) => {
                    let again = parse(&doc.to_swp_string());
                    prop_assert_eq!(without_positions(again), without_positions(doc));
                }
                Err(err) => {
                    let line = text.split('\n').nth(err.line() - 1);
                    prop_assert!(line.is_some_and(|l| err.column() <= l.chars().count() + 1), "{err}");
                    prop_assert!(err.to_string().contains(", expected "), "{err}");
                }
            }
        }
    }
}
