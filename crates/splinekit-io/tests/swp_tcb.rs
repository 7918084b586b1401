//! SWP kinds of issue #41: Kochanek–Bartels (`tcb2`, `tcb3`) and Bessel–Overhauser (`bo2`,
//! `bo3`) curves — parsing into the library's curves, errors with positions, writing and
//! reading back, and their use as profiles and sweeps.

use glam::DVec3;
use splinekit::flatten::{Tessellation, flatten_any};
use splinekit::{AnyCurve, BesselOverhauser, CatmullRom, KochanekBartels, ParamCurve, Tcb};
use splinekit_io::surface::SurfaceOptions;
use splinekit_io::{SwpCurveKind, SwpDocument, SwpGeometry, SwpSurfaceKind};

#[allow(dead_code)]
#[path = "swp/common.rs"]
mod common;

use common::{assert_error, parse, parse_err, sweeps_every_surface, without_positions};

/// Positions of the file path and of the library agree to this (the same arithmetic).
const SAME: f64 = 1e-15;

/// Every new keyword, open and closed, 2D and 3D, with shapes of every sign.
const SAMPLE: &str = "\
# Kochanek-Bartels: [x y t c b]
tcb2 keys 12 5
[0 0 0 0 0] [1 1 0.5 0 0] [2 0 -0.5 1 0] [3 1 0 -1 0.25] [4 0 1 0 -1]
tcb3 loop3 8 4 closed
[1 0 0 0 0 0]
[0 1 0.5 -1 0.5 0]
[-1 0 -0.5 0 0 1]
[0 -1 1 0.25 -0.25 -1]
# Bessel-Overhauser: plain points, chord lengths shape the tangents
bo2 ring 10 5 closed [1 0] [0.3 0.9] [-0.8 0.6] [-0.8 -0.6] [0.3 -0.9]
bo3 path 6 6 [0 0 0] [1 0 0.5] [3 1 1] [4 3 1.5] [4 5 2] [3 7 3]
";

fn keys(doc: &SwpDocument, index: usize) -> (&[DVec3], &[Tcb]) {
    match &doc.curves[index].geometry {
        SwpGeometry::Tcb { points, shape } => (points, shape),
        other => panic!("curve {index} is not Kochanek–Bartels: {other:?}"),
    }
}

fn piecewise(curve: &AnyCurve<DVec3>) -> &splinekit::PiecewiseCubic<DVec3> {
    match curve {
        AnyCurve::Piecewise(c) => c,
        other => panic!("not a piecewise cubic: {other:?}"),
    }
}

/// The largest distance between two curves' positions at 64 parameters per segment.
fn max_distance(a: &AnyCurve<DVec3>, b: &AnyCurve<DVec3>) -> f64 {
    assert_eq!(a.num_segments(), b.num_segments());
    let n = 64 * a.num_segments();
    let (lo, hi) = a.domain();
    (0..=n)
        .map(|i| {
            let u = lo + (hi - lo) * i as f64 / n as f64;
            (a.eval(u) - b.eval(u)).length()
        })
        .fold(0.0, f64::max)
}

#[test]
fn keywords_parse_into_kinds_points_and_shapes() {
    let doc = parse(SAMPLE);
    let kinds: Vec<(&str, SwpCurveKind, u8, bool)> =
        doc.curves.iter().map(|c| (c.keyword(), c.kind, c.dim, c.closed)).collect();
    assert_eq!(
        kinds,
        [
            ("tcb2", SwpCurveKind::KochanekBartels, 2, false),
            ("tcb3", SwpCurveKind::KochanekBartels, 3, true),
            ("bo2", SwpCurveKind::BesselOverhauser, 2, true),
            ("bo3", SwpCurveKind::BesselOverhauser, 3, false),
        ]
    );
    let (points, shape) = keys(&doc, 0);
    assert_eq!(points[3], DVec3::new(3.0, 1.0, 0.0));
    assert_eq!(shape[3], Tcb::new(0.0, -1.0, 0.25));
    let (points, shape) = keys(&doc, 1);
    assert_eq!(points[1], DVec3::new(0.0, 1.0, 0.5));
    assert_eq!(shape[1], Tcb::new(-1.0, 0.5, 0.0));
    assert_eq!(doc.curves[2].geometry.points().len(), 5);
    assert_eq!(doc.validate(), Ok(()));
}

/// The file path builds exactly the library's curves; open curves run from the second key to
/// the second-to-last (n − 3 segments), closed ones around all n keys, and STEPS counts the
/// steps of each segment.
#[test]
fn curves_are_the_library_curves_and_interpolate_their_keys() {
    let doc = parse(SAMPLE);
    for (index, curve) in doc.curves.iter().enumerate() {
        let built = curve.to_curve().unwrap();
        let points = curve.geometry.points();
        let direct = match &curve.geometry {
            SwpGeometry::Tcb { shape, .. } => KochanekBartels::new(points, shape, curve.closed).unwrap().to_piecewise(),
            _ => BesselOverhauser::new(points, curve.closed).unwrap().to_piecewise(),
        };
        assert_eq!(piecewise(&built), &direct, "curve {index}");
        let n = points.len();
        let segments = if curve.closed { n } else { n - 3 };
        assert_eq!(built.num_segments(), segments, "curve {index}");
        assert_eq!(built.is_closed(), curve.closed);
        // key k + 1 sits at u = k
        for k in 0..=segments {
            let key = points[(k + 1) % n];
            assert!((built.eval(k as f64) - key).length() <= SAME, "curve {index} key {}", k + 1);
        }
        let steps = Tessellation::Uniform { steps: curve.steps as usize };
        assert_eq!(flatten_any(&built, steps).len(), segments * curve.steps as usize + 1, "curve {index}");
    }
}

/// Tension, continuity and bias 0 at every key is the uniform Catmull-Rom curve of the same
/// points, through the files.
#[test]
fn zero_shapes_are_the_catmull_rom_curve() {
    let points = "[0 0 0] [1 2 0.5] [3 1 -1] [4 -1 2] [6 0 1] [7 3 0]";
    let keys = "[0 0 0 0 0 0] [1 2 0.5 0 0 0] [3 1 -1 0 -0 0] [4 -1 2 0 0 0] [6 0 1 0 0 0] [7 3 0 0 0 0]";
    for closed in ["", "closed"] {
        let doc = parse(&format!("cr3 a 10 6 {closed} {points}\ntcb3 b 10 6 {closed} {keys}"));
        let (cr, kb) = (doc.curves[0].to_curve().unwrap(), doc.curves[1].to_curve().unwrap());
        assert!(max_distance(&cr, &kb) <= SAME, "{closed}: {}", max_distance(&cr, &kb));
        let library = CatmullRom::new(doc.curves[0].geometry.points(), !closed.is_empty(), 0.0).unwrap();
        assert_eq!(piecewise(&cr), &library.to_piecewise());
    }
}

/// Keys at equal distances (here the corners of a regular hexagon) make every Bessel–Overhauser
/// tangent the uniform Catmull-Rom one.
#[test]
fn equally_spaced_bessel_overhauser_is_catmull_rom() {
    let corners: Vec<String> = (0..6)
        .map(|i| f64::from(i) * core::f64::consts::TAU / 6.0)
        .map(|a| format!("[{} {}]", 2.0 * a.cos(), 2.0 * a.sin()))
        .collect();
    let corners = corners.join(" ");
    for closed in ["", "closed"] {
        let doc = parse(&format!(
            "cr2 a 10 6 {closed} {corners}
bo2 b 10 6 {closed} {corners}"
        ));
        let (cr, bo) = (doc.curves[0].to_curve().unwrap(), doc.curves[1].to_curve().unwrap());
        assert!(max_distance(&cr, &bo) <= 1e-14, "{closed}: {}", max_distance(&cr, &bo));
    }
}

#[test]
fn shape_values_are_checked_with_their_position() {
    let cases: [(&str, usize, usize, &str); 4] = [
        (
            "tcb2 k 10 4\n[0 0 0 0 0] [1 0 1.5 0 0] [2 0 0 0 0] [3 0 0 0 0]",
            2,
            18,
            "the tension of point 2 of tcb2 curve \"k\"",
        ),
        ("tcb2 k 10 4\n[0 0 0 0 0] [1 0 0 -1.01 0] [2 0 0 0 0] [3 0 0 0 0]", 2, 20, "the continuity of point 2"),
        ("tcb3 k 10 3 closed\n[0 0 0 0 0 0]\n[1 0 0 0 0 2]", 3, 12, "the bias of point 2 of tcb3 curve \"k\""),
        ("tcb2 . 10 4\n[0 0 0 zero 0]", 2, 8, "the continuity of point 1 of tcb2 curve #0"),
    ];
    for (text, line, column, part) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &["expected a number from -1 to 1", part]);
    }
    let err = parse_err("tcb2 k 10 4\n[0 0 0 0 nan]");
    assert_error(&err, 2, 10, &["found \"nan\"", "the bias of point 1"]);
}

#[test]
fn malformed_keys_say_what_a_key_holds() {
    // a key without its shape: the `]` stands where the tension should
    let err = parse_err("tcb2 k 10 4\n[0 0] [1 0] [2 0] [3 0]");
    assert_error(&err, 2, 5, &["found \"]\"", "tension of point 1 of tcb2 curve \"k\", whose points are [x y t c b]"]);
    // one number too many
    let err = parse_err("tcb3 k 10 4\n[0 0 0 0 0 0 0]");
    assert_error(&err, 2, 14, &["found \"0\"", "expected `]` closing point 1", "its points are [x y z t c b]"]);
    // Bessel–Overhauser points are plain points
    let err = parse_err("bo2 k 10 4\n[0 0 0]");
    assert_error(&err, 2, 6, &["expected `]` closing point 1 of bo2 curve \"k\" (its points have 2 coordinates)"]);
    let err = parse_err("bo3 k 10 4 [0 0 x]");
    assert_error(&err, 1, 17, &["found \"x\"", "a number (z coordinate of point 1 of bo3 curve \"k\")"]);
    // the file ends inside the shape
    let err = parse_err("tcb2 k 10 4\n[0 0 0 0");
    assert!(
        err.to_string().contains("found end of file, expected a number from -1 to 1 (the bias of point 1"),
        "{err}"
    );
}

#[test]
fn key_counts_and_options_are_those_of_catmull_rom() {
    for (text, column, rule) in [
        ("tcb2 k 10 3 [0 0 0 0 0] [1 0 0 0 0] [2 0 0 0 0]", 11, "found 3 points, expected at least 4 points"),
        ("tcb3 k 10 2 closed [0 0 0 0 0 0] [1 0 0 0 0 0]", 11, "found 2 points, expected at least 3 points"),
        ("bo2 k 10 3 [0 0] [1 0] [2 0]", 10, "found 3 points, expected at least 4 points for bo2 curve \"k\""),
        ("bo3 k 10 2 closed [0 0 0] [1 0 0]", 10, "found 2 points, expected at least 3 points"),
    ] {
        assert_error(&parse_err(text), 1, column, &[rule]);
    }
    // the smallest counts parse
    parse("tcb2 k 10 4 [0 0 0 0 0] [1 0 0 0 0] [2 0 0 0 0] [3 1 0 0 0]");
    parse("bo3 k 10 3 closed [0 0 0] [1 0 0] [0 1 0]");
    // a missing key
    let err = parse_err("bo2 k 10 5 [0 0] [1 0] [2 0] [3 0]");
    assert_error(&err, 1, 35, &["found end of file after 4 points, expected 5 points for bo2 curve \"k\""]);
    // Catmull-Rom's parametrization is not theirs
    let err = parse_err("bo2 k 10 4 centripetal [0 0] [1 0] [2 0] [3 0]");
    assert_error(
        &err,
        1,
        12,
        &["a curve option of bo2 curve \"k\" (closed or open); `centripetal` applies to cr2 and cr3 only"],
    );
    let err = parse_err("tcb2 k 10 4 open closed");
    assert_error(&err, 1, 18, &["at most one of closed or open"]);
    let err = parse_err("tcb2 k x 4");
    assert_error(
        &err,
        1,
        8,
        &["found \"x\", expected a step count (an integer from 1 to 1000000) for tcb2 curve \"k\""],
    );
    let err = parse_err("TCB2 k 10 4");
    assert_error(&err, 1, 1, &["tcb2, tcb3, bo2, bo3", "(keywords are lowercase)"]);
}

#[test]
fn documents_write_and_read_back_unchanged() {
    let doc = parse(SAMPLE);
    let written = doc.to_swp_string();
    assert!(
        written.starts_with(
            "tcb2 keys 12 5\n[0 0 0 0 0]\n[1 1 0.5 0 0]\n[2 0 -0.5 1 0]\n[3 1 0 -1 0.25]\n[4 0 1 0 -1]\n\n\
             tcb3 loop3 8 4 closed\n[1 0 0 0 0 0]\n[0 1 0.5 -1 0.5 0]\n"
        ),
        "{written}"
    );
    assert!(written.contains("\nbo2 ring 10 5 closed\n[1 0]\n[0.3 0.9]\n"), "{written}");
    assert!(written.contains("\nbo3 path 6 6\n[0 0 0]\n[1 0 0.5]\n"), "{written}");
    let again = parse(&written);
    assert_eq!(without_positions(again.clone()), without_positions(doc));
    assert_eq!(again.to_swp_string(), written);
}

#[test]
fn they_serve_as_profiles_and_sweeps() {
    let text = format!(
        "{SAMPLE}\
         srev vase 24 keys\n\
         gcyl tube ring path\n\
         gcyl knotty ring loop3 frames rmf\n\
         zrev turned keys\n"
    );
    let doc = parse(&text);
    sweeps_every_surface(&doc);
    let options = SurfaceOptions::default();
    // srev: STEPS per profile segment (2 segments of 12 steps) by 24 slices
    assert_eq!(doc.surface_mesh(0, &options).unwrap().num_triangles(), 2 * (2 * 12) * 24);
    assert!(matches!(doc.surfaces[1].kind, SwpSurfaceKind::GeneralizedCylinder { profile: 2, sweep: 3, .. }));
    // a 3D curve is no profile
    let err = parse_err(&format!("{SAMPLE}srev bad 10 path"));
    assert!(
        err.to_string()
            .contains("found 3D curve \"path\" (bo3), expected a 2D curve (bez2, bsp2, cr2, her2, tcb2, bo2, bezn2, nurbs2 or circ)"),
        "{err}"
    );
}
