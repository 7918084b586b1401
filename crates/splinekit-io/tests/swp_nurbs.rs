//! SWP kinds of issue #41: Bézier curves of any degree (`bezn2`, `bezn3`) and NURBS (`nurbs2`,
//! `nurbs3`) — parsing into the library's curves, errors with positions, writing and reading
//! back, and their use as profiles and sweeps.

use std::f64::consts::FRAC_1_SQRT_2;

use glam::DVec3;
use splinekit::{AnyCurve, BezierCurve, Nurbs, ParamCurve};
use splinekit_io::surface::SurfaceOptions;
use splinekit_io::{SwpCurveKind, SwpDocument, SwpGeometry};

#[allow(dead_code)]
#[path = "swp/common.rs"]
mod common;

use common::{assert_error, parse, parse_err, sweeps_every_surface, without_positions};

/// Every new keyword: 2D and 3D, default and given knots (in each of the three spellings),
/// open and periodic.
const SAMPLE: &str = "\
# one Bézier curve of degree 4, and a 3D line
bezn2 hump 20 5 [0 0] [1 2] [2 -1] [3 2] [4 0]
bezn3 . 4 2 [0 0 0] [1 1 1]
# the quarter circle of radius 1: a rational quadratic
nurbs2 arc 16 3 degree 2 [1 0 1] [1 1 0.7071067811865476] [0 1 1]
# the full circle, four quarter arcs over knots of multiplicity 2
nurbs2 ring 8 9 degree 2 knots 0 0 0 1 1 2 2 3 3 4 4 4
[1 0 1] [1 1 0.7071067811865476] [0 1 1] [-1 1 0.7071067811865476] [-1 0 1]
[-1 -1 0.7071067811865476] [0 -1 1] [1 -1 0.7071067811865476] [1 0 1]
nurbs3 path 10 5 degree 3 knots [0 0 0 0 0.5 1 1 1 1]
[0 0 0 1] [1 0 1 2] [2 1 1 0.5] [3 1 2 1] [4 2 2 1]
nurbs3 loop 6 4 closed [1 0 0 1] [0 1 0.5 2] [-1 0 1 1] [0 -1 0.5 0.5]
nurbs2 cubic 12 4 [knots 0 0 0 0 1 1 1 1] [0 0 1] [1 1 1] [2 -1 1] [3 0 1]
";

fn nurbs_of(doc: &SwpDocument, index: usize) -> Nurbs<DVec3> {
    match doc.curves[index].to_curve().unwrap() {
        AnyCurve::Nurbs(c) => c,
        other => panic!("curve {index} is not a NURBS: {other:?}"),
    }
}

/// `n + 1` equally spaced parameters over the curve's domain.
fn params(curve: &impl ParamCurve<DVec3>, n: usize) -> impl Iterator<Item = f64> {
    let (lo, hi) = curve.domain();
    (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
}

#[test]
fn every_form_parses_into_the_model() {
    let doc = parse(SAMPLE);
    let kinds: Vec<(&str, SwpCurveKind, bool)> = doc.curves.iter().map(|c| (c.keyword(), c.kind, c.closed)).collect();
    assert_eq!(
        kinds,
        [
            ("bezn2", SwpCurveKind::BezierN, false),
            ("bezn3", SwpCurveKind::BezierN, false),
            ("nurbs2", SwpCurveKind::Nurbs { degree: 2 }, false),
            ("nurbs2", SwpCurveKind::Nurbs { degree: 2 }, false),
            ("nurbs3", SwpCurveKind::Nurbs { degree: 3 }, false),
            ("nurbs3", SwpCurveKind::Nurbs { degree: 3 }, true),
            ("nurbs2", SwpCurveKind::Nurbs { degree: 3 }, false),
        ]
    );
    let SwpGeometry::Nurbs { points, weights, knots } = &doc.curves[4].geometry else { panic!() };
    assert_eq!(points[2], DVec3::new(2.0, 1.0, 1.0));
    assert_eq!(weights, &[1.0, 2.0, 0.5, 1.0, 1.0]);
    assert_eq!(knots.as_deref(), Some(&[0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0][..]));
    let SwpGeometry::Nurbs { knots, .. } = &doc.curves[2].geometry else { panic!() };
    assert_eq!(*knots, None, "no knots: the default");
    let SwpGeometry::Nurbs { knots, .. } = &doc.curves[6].geometry else { panic!() };
    assert_eq!(knots.as_ref().map(Vec::len), Some(8), "[knots …] form");
}

#[test]
fn curves_are_the_library_kinds() {
    let doc = parse(SAMPLE);
    // bezn: one BezierCurve of degree N − 1, one segment
    let AnyCurve::Bezier(hump) = doc.curves[0].to_curve().unwrap() else { panic!() };
    assert_eq!((hump.degree(), hump.num_segments()), (4, 1));
    let direct = BezierCurve::new(doc.curves[0].geometry.points().to_vec()).unwrap();
    for u in params(&hump, 50) {
        assert_eq!(hump.eval(u), direct.eval(u));
    }
    // the exact arc and circle: every point at radius 1 (closed form)
    for index in [2, 3] {
        let circle = nurbs_of(&doc, index);
        for u in params(&circle, 400) {
            let r = circle.eval(u).length();
            assert!((r - 1.0).abs() < 1e-14, "curve {index} at u = {u}: radius {r}");
        }
    }
    let ring = nurbs_of(&doc, 3);
    assert_eq!(ring.num_segments(), 4, "one segment per knot span of positive length");
    assert!((ring.arclen(1e-12) - std::f64::consts::TAU).abs() < 1e-10);
    // the arc's middle is at 45° (a rational quadratic with w = cos 45° is the circle's own
    // parametrization only at its ends and middle)
    let arc = nurbs_of(&doc, 2);
    let mid = arc.eval(0.5);
    assert!((mid - DVec3::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0)).length() < 1e-15, "{mid}");
    // clamped knots (given or default): the curve starts at its first point and ends at its last
    for index in [4, 6] {
        let c = nurbs_of(&doc, index);
        let pts = doc.curves[index].geometry.points();
        let (lo, hi) = c.domain();
        assert!((c.eval(lo) - pts[0]).length() < 1e-15 && (c.eval(hi) - pts[pts.len() - 1]).length() < 1e-15);
    }
    // the 2D `[knots …]` cubic with weights 1 is the cubic Bézier of its points
    let cubic = nurbs_of(&doc, 6);
    let bezier = BezierCurve::new(doc.curves[6].geometry.points().to_vec()).unwrap();
    for u in params(&cubic, 40) {
        assert!((cubic.eval(u) - bezier.eval(u)).length() < 1e-14);
    }
    // closed: periodic, through none of its points, returning to its start
    let periodic = nurbs_of(&doc, 5);
    assert!(periodic.is_closed());
    assert_eq!(periodic.num_segments(), 4);
    let (lo, hi) = periodic.domain();
    assert!((periodic.eval(lo) - periodic.eval(hi)).length() < 1e-14);
}

#[test]
fn documents_write_and_read_back_unchanged() {
    let doc = parse(SAMPLE);
    let written = doc.to_swp_string();
    assert!(written.starts_with("bezn2 hump 20 5\n[0 0]\n[1 2]\n"), "{written}");
    assert!(written.contains("\nnurbs2 arc 16 3 degree 2\n[1 0 1]\n[1 1 0.7071067811865476]\n"), "{written}");
    assert!(written.contains("\nnurbs3 path 10 5 degree 3 knots 0 0 0 0 0.5 1 1 1 1\n[0 0 0 1]\n"), "{written}");
    assert!(written.contains("\nnurbs3 loop 6 4 closed degree 3\n[1 0 0 1]\n"), "{written}");
    let again = parse(&written);
    assert_eq!(without_positions(again.clone()), without_positions(doc.clone()));
    assert_eq!(again.to_swp_string(), written);
    assert_eq!(doc.validate(), Ok(()));
}

#[test]
fn bad_headers_name_line_column_and_the_rule() {
    let cases: [(&str, usize, usize, &[&str]); 15] = [
        // the count rule comes first: the number of knots depends on it
        (
            "nurbs2 c 10 3 degree 3 knots 0 0 0 1 1 1 [0 0 1]",
            1,
            13,
            &["found 3 points", "at least 4 points (degree 3 + 1"][..],
        ),
        (
            "nurbs2 c 10 3 degree 2 knots 0 0 0 1 1 [0 0 1]",
            1,
            40,
            &[
                "found \"[\", expected a number (knot 6 of the 6 knots, NPOINTS + degree + 1 = 3 + 2 + 1, of nurbs2 curve \"c\")",
            ],
        ),
        (
            "nurbs2 c 10 3 degree 2\nknots 0 0 0 1 1 1 1 [0 0 1]",
            2,
            19,
            &[
                "found \"1\", expected `[` starting point 1 of nurbs2 curve \"c\", after its 6 knots (NPOINTS + degree + 1 = 3 + 2 + 1)",
            ],
        ),
        (
            "nurbs2 c 10 3 degree 2 knots 0 0 1 0.5 1 1 [0 0 1]",
            1,
            36,
            &["found \"0.5\", expected a knot ≥ 1 (knot 4 of nurbs2 curve \"c\"; knots never decrease)"],
        ),
        (
            "nurbs2 c 10 3 degree 2 knots 0 0 0 0 1 1 [0 0 1]",
            1,
            24,
            &["found \"knots\"", "knot 3 is less than its knot 4", "they are both 0"],
        ),
        ("nurbs2 c 10 3 degree 2 knots [0 0 0 1 1 1 1]", 1, 43, &["found \"1\", expected `]` closing the 6 knots"]),
        (
            "nurbs2 c 10 3 knots 0 0 0 1 1 1 degree 2",
            1,
            13,
            &[
                "found 3 points",
                "(degree 3 + 1; `degree D` sets another degree) and at most 1048576 for nurbs2 curve \"c\"",
            ],
        ),
        ("nurbs2 c 10 3 degree 2 knots 0 0 0 1 1 1 degree 2", 1, 42, &["at most one of degree"]),
        (
            "nurbs2 c 10 3 degree 2 knots 0 0 0 1 1 1 closed",
            1,
            42,
            &[
                "a closed NURBS is periodic with uniform knots of its own, so it takes no `knots` (line 1, column 24 has the other)",
            ],
        ),
        (
            "nurbs2 c 10 3 degree 0",
            1,
            22,
            &["found \"0\", expected a degree (an integer from 1 to 32) for nurbs2 curve \"c\""],
        ),
        ("nurbs3 c 10 3 degree 33", 1, 22, &["found \"33\", expected a degree (an integer from 1 to 32)"]),
        (
            "nurbs2 c 10 2 closed degree 1 [0 0 1] [1 0 1]",
            1,
            13,
            &[
                "found 2 points, expected at least 3 points (degree 1 + 1, and 3 for a closed curve) and at most 1048576 for nurbs2 curve \"c\"",
            ],
        ),
        ("bsp2 c 10 4 degree 2", 1, 13, &["`degree` applies to nurbs2 and nurbs3 only"]),
        ("bsp2 c 10 4 [knots 0 1]", 1, 13, &["`knots` applies to nurbs2 and nurbs3 only"]),
        (
            "cr2 c 10 4 knots 0 1",
            1,
            12,
            &[
                "found \"knots\", expected a curve option of cr2 curve \"c\" (closed, open, alpha A, uniform, centripetal or chordal)",
            ],
        ),
    ];
    for (text, line, column, parts) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, parts);
    }
}

#[test]
fn bad_points_and_weights_say_what_a_point_holds() {
    let cases: [(&str, usize, usize, &[&str]); 8] = [
        // a weight ≤ 0, or none
        (
            "nurbs2 c 10 3 degree 2\n[0 0 1] [1 1 0] [2 0 1]",
            2,
            14,
            &[
                "found \"0\", expected a number > 0 (the weight of point 2 of nurbs2 curve \"c\", whose points are [x y w])",
            ],
        ),
        ("nurbs3 c 10 4 [0 0 0 1] [1 1 0 -2]", 1, 32, &["found \"-2\"", "the weight of point 2", "[x y z w]"]),
        ("nurbs2 c 10 4 [0 0] [1 1]", 1, 19, &["found \"]\", expected a number > 0 (the weight of point 1"]),
        ("nurbs2 c 10 3 degree 2 [0 0 1] [1 1 1] [2 0 nan]", 1, 45, &["found \"nan\"", "the weight of point 3"]),
        // bezn: plain points, 2 to 65 of them, never closed
        (
            "bezn2 b 10 3 [0 0 1] [1 1] [2 0]",
            1,
            19,
            &["expected `]` closing point 1 of bezn2 curve \"b\" (its points have 2 coordinates)"],
        ),
        ("bezn3 b 10 1", 1, 12, &["found 1 point, expected 2 to 65 points (one Bézier curve of degree NPOINTS − 1)"]),
        ("bezn3 b 10 66", 1, 12, &["found 66 points, expected 2 to 65 points", "for bezn3 curve \"b\""]),
        (
            "bezn2 b 10 3 closed [0 0] [1 1] [2 0]",
            1,
            14,
            &["found \"closed\"", "a bezn2 curve is one open Bézier curve"],
        ),
    ];
    for (text, line, column, parts) in cases {
        assert_error(&parse_err(text), line, column, parts);
    }
    // the smallest counts parse: a line, and a NURBS of degree 1 with 2 points
    parse("bezn2 b 10 2 [0 0] [1 1]");
    parse("nurbs2 c 10 2 degree 1 [0 0 1] [1 1 3]");
    parse("nurbs2 c 10 3 closed degree 1 [0 0 1] [1 1 3] [1 0 1]");
    let err = parse_err("BEZN2 b 10 2 [0 0] [1 1]");
    assert_error(&err, 1, 1, &["bezn2, bezn3, nurbs2, nurbs3", "(keywords are lowercase)"]);
}

#[test]
fn they_serve_as_profiles_and_sweeps() {
    let text = format!(
        "{SAMPLE}\
         srev dome 24 arc\n\
         gcyl tube ring path\n\
         gcyl knotty ring loop frames rmf\n\
         gcyl bent ring hump\n"
    );
    let doc = parse(&text);
    sweeps_every_surface(&doc);
    let options = SurfaceOptions::default();
    // the quarter circle turned about y is the unit hemisphere: every vertex at radius 1
    let dome = doc.surface_mesh(0, &options).unwrap();
    for p in &dome.positions {
        let r = p.length();
        assert!((r - 1.0).abs() < 1e-6, "{p}: radius {r}");
    }
    // srev: STEPS per profile segment (1 span of 16 steps) by 24 slices, the last ring of
    // quads ending on the axis as one triangle each
    assert_eq!(dome.num_triangles(), 2 * 15 * 24 + 24);
    // a 3D NURBS is no profile; zrev takes cubic splines only
    let err = parse_err(&format!("{SAMPLE}srev bad 10 path"));
    assert!(err.to_string().contains("found 3D curve \"path\" (nurbs3), expected a 2D curve"), "{err}");
    let zrev = parse(&format!("{SAMPLE}zrev turned arc"));
    let err = zrev.surface_mesh(0, &options).unwrap_err();
    assert!(err.to_string().contains("must be a cubic spline (bez2, bsp2, cr2, her2, tcb2 or bo2)"), "{err}");
}
