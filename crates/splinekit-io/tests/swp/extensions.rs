//! Our extensions (Catmull-Rom, Hermite, options, comments) and the quirks of real files.

use glam::DVec3;
use splinekit_io::{SwpCurveKind, SwpDocument, SwpGeometry, SwpSurfaceKind};

use super::common::{parse, parse_err, points, without_positions};

fn v2(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

#[test]
fn catmull_rom() {
    let doc = parse(
        "cr2 path 12 4 [0 0] [1 0] [1 1] [0 1]\n\
         cr3 . 7 5 [0 0 0] [1 0 0] [1 1 0] [0 1 1] [0 0 2]",
    );
    assert_eq!(doc.curves[0].kind, SwpCurveKind::CatmullRom { alpha: 0.0 });
    assert_eq!((doc.curves[0].dim, doc.curves[0].steps), (2, 12));
    assert_eq!(doc.curves[0].keyword(), "cr2");
    assert_eq!(points(&doc, 0)[2], v2(1.0, 1.0));
    assert_eq!(doc.curves[1].keyword(), "cr3");
    assert_eq!(doc.curves[1].dim, 3);
    assert_eq!(points(&doc, 1)[4], DVec3::new(0.0, 0.0, 2.0));
    assert!(!doc.curves[0].closed && !doc.curves[1].closed);
}

#[test]
fn hermite() {
    let doc = parse(
        "her2 h 10 2\n[0 0] [1 0]\n[2 1] [0 3]\n\
         her3 . 4 3 [0 0 0] [1 0 0] [1 1 1] [0 1 0] [2 2 2] [0 0 1]",
    );
    assert_eq!(doc.curves[0].kind, SwpCurveKind::Hermite);
    assert_eq!(
        doc.curves[0].geometry,
        SwpGeometry::Hermite { points: vec![v2(0.0, 0.0), v2(2.0, 1.0)], tangents: vec![v2(1.0, 0.0), v2(0.0, 3.0)] }
    );
    let SwpGeometry::Hermite { points, tangents } = &doc.curves[1].geometry else {
        panic!("not Hermite: {:?}", doc.curves[1].geometry);
    };
    assert_eq!(points, &[DVec3::ZERO, DVec3::ONE, DVec3::splat(2.0)]);
    assert_eq!(tangents, &[DVec3::X, DVec3::Y, DVec3::Z]);
    assert_eq!(doc.curves[1].dim, 3);
}

#[test]
fn closed_point_counts() {
    // Closed Bézier: 3m points; the last segment returns to the first point.
    for n in [3, 6, 9] {
        let pts = "[0 0] ".repeat(n);
        let doc = parse(&format!("bez2 . 10 {n} closed {pts}"));
        assert!(doc.curves[0].closed);
        assert_eq!(points(&doc, 0).len(), n);
    }
    for n in [1, 2, 4, 5, 7] {
        parse_err(&format!("bez2 . 10 {n} closed {}", "[0 0] ".repeat(n)));
    }
    // Closed B-spline and Catmull-Rom: at least 3 points. Open: at least 4.
    for keyword in ["bsp2", "cr2"] {
        assert!(parse(&format!("{keyword} . 10 3 closed [0 0] [1 0] [0 1]")).curves[0].closed);
        parse_err(&format!("{keyword} . 10 2 closed [0 0] [1 0]"));
        parse_err(&format!("{keyword} . 10 3 [0 0] [1 0] [0 1]"));
        parse_err(&format!("{keyword} . 10 3 open [0 0] [1 0] [0 1]"));
    }
    // Closed Hermite: at least 2 pairs, like open.
    assert!(parse("her2 . 10 2 closed [0 0] [1 0] [1 1] [0 1]").curves[0].closed);
    parse_err("her2 . 10 1 closed [0 0] [1 0]");
    // `open` is the default, spelled out.
    let doc = parse("bsp3 . 10 4 open [0 0 0] [1 0 0] [1 1 0] [0 1 0]");
    assert!(!doc.curves[0].closed);
}

#[test]
fn alpha_option() {
    let alpha = |options: &str| {
        let doc = parse(&format!("cr2 . 10 4 {options} [0 0] [1 0] [1 1] [0 1]"));
        match doc.curves[0].kind {
            SwpCurveKind::CatmullRom { alpha } => (alpha, doc.curves[0].closed),
            other => panic!("{other:?}"),
        }
    };
    assert_eq!(alpha(""), (0.0, false));
    assert_eq!(alpha("alpha 0.25"), (0.25, false));
    assert_eq!(alpha("alpha 1"), (1.0, false));
    assert_eq!(alpha("alpha 0"), (0.0, false));
    assert_eq!(alpha("uniform"), (0.0, false));
    assert_eq!(alpha("centripetal"), (0.5, false));
    assert_eq!(alpha("chordal"), (1.0, false));
    assert_eq!(alpha("centripetal closed"), (0.5, true));
    assert_eq!(alpha("closed\nalpha .75\n"), (0.75, true));
    assert_eq!(alpha("open # comment\n uniform"), (0.0, false));
}

#[test]
fn comments() {
    let doc = parse(
        "# a file with comments\n\
         bez2 profile 20 4 # four points\n\
         [0 0]#glued\n\
         [1 0] [1 1] # two more\n\
         # [9 9] is commented out\n\
         [0 1]\n\
         srev . 90 profile#glued too\n\
         # the end",
    );
    assert_eq!(points(&doc, 0), [v2(0.0, 0.0), v2(1.0, 0.0), v2(1.0, 1.0), v2(0.0, 1.0)]);
    assert_eq!(doc.surfaces.len(), 1);
    assert_eq!(doc.curves[0].pos.line, 2);
    // A comment in the middle of a point is only whitespace.
    let doc = parse("bsp2 . 5 4 [0 # x\n 0] [1 0] [1 1] [0 1]");
    assert_eq!(points(&doc, 0)[0], v2(0.0, 0.0));
}

#[test]
fn names_may_look_like_keywords_or_numbers() {
    let doc = parse(
        "bsp2 circ 20 4 [0 0] [1 0] [1 1] [0 1]\n\
         circ 20 5 1\n\
         gcyl closed circ 20",
    );
    assert_eq!(doc.curve_index("circ"), Some(0));
    assert_eq!(doc.curve_index("20"), Some(1));
    assert_eq!(
        doc.surfaces[0].kind,
        SwpSurfaceKind::GeneralizedCylinder { profile: 0, sweep: 1, scale: None, twist: None }
    );
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("closed"));
}

#[test]
fn lf_and_crlf_read_the_same() {
    let lf = "bez2 p 20 4\n[3 0]\n[3 1]\n[1 1]\n[1 0]\n\ncirc c 10 0.5\n\ngcyl g c p\n";
    let crlf = lf.replace('\n', "\r\n");
    assert_eq!(parse(lf), parse(&crlf));
    let double_spaced = lf.replace('\n', "\r\n\r\n");
    assert_eq!(without_positions(parse(lf)), without_positions(parse(&double_spaced)));
}

#[test]
fn bracket_spacing_does_not_matter() {
    let tight = parse("bez2 . 20 4 [3 0] [3 1] [1 1] [1 0]");
    for text in [
        "bez2 . 20 4 [ 3 0 ] [ 3 1 ] [ 1 1 ] [ 1 0 ]",
        "bez2 . 20 4 [3 0 ][ 3 1][1 1 ]\t[1 0]",
        "bez2 . 20 4\n[\n3\n0\n]\n[3\t1]\n\n[1 1][1 0]",
        "bez2 . 20 4[3 0][3 1][1 1][1 0]",
    ] {
        assert_eq!(without_positions(parse(text)), without_positions(tight.clone()), "{text}");
    }
}

#[test]
fn trailing_whitespace_and_missing_final_newline() {
    let base = "circ . 30 1\r\ncirc . 50 2";
    let expected = parse(base);
    for text in [
        base.to_owned(),
        format!("{base}\r\n"),
        format!("{base}   \r\n   \r\n\t\r\n     "),
        format!("{base} \n\n\n"),
        format!("\u{feff}{base}"),
    ] {
        assert_eq!(parse(&text), expected, "{text:?}");
    }
    assert_eq!(parse(""), SwpDocument::default());
    assert_eq!(parse(" \r\n\t\n# nothing\n"), SwpDocument::default());
}

#[test]
fn numbers_in_many_spellings() {
    let doc = parse("bsp2 . 1 4 [-0.765483 2] [1e-3 .5] [+4 5.] [1E2 -0]");
    assert_eq!(points(&doc, 0), [v2(-0.765483, 2.0), v2(0.001, 0.5), v2(4.0, 5.0), v2(100.0, 0.0)]);
    assert!(points(&doc, 0)[3].y.is_sign_negative());
    let doc = parse("circ . 3 0 circ . 3 1e-300");
    assert_eq!(doc.curves[1].geometry, SwpGeometry::Circle { radius: 1e-300 });
}

#[test]
fn positions_are_recorded() {
    let doc = parse("  circ c 9 1\n\n\t  srev s 9 c");
    assert_eq!((doc.curves[0].pos.line, doc.curves[0].pos.column), (1, 3));
    assert_eq!((doc.surfaces[0].pos.line, doc.surfaces[0].pos.column), (3, 4));
    assert_eq!(doc.curves[0].pos.to_string(), "1:3");
}

#[test]
fn writer_uses_options_only_when_needed() {
    let text = "bez2 a 20 3 closed [0 0] [1 0] [0 1]\n\
                cr3 b 5 4 alpha 0.25 [0 0 0] [1 0 0] [1 1 0] [0 1 0]\n\
                cr2 c 5 4 chordal [0 0] [1 0] [1 1] [0 1]\n\
                cr2 d 5 4 uniform open [0 0] [1 0] [1 1] [0 1]\n\
                her2 e 6 2 closed [0 0] [1 0] [1 1] [-1 0]\n";
    let doc = parse(text);
    let written = doc.to_swp_string();
    assert_eq!(
        written,
        "bez2 a 20 3 closed\n[0 0]\n[1 0]\n[0 1]\n\n\
         cr3 b 5 4 alpha 0.25\n[0 0 0]\n[1 0 0]\n[1 1 0]\n[0 1 0]\n\n\
         cr2 c 5 4 chordal\n[0 0]\n[1 0]\n[1 1]\n[0 1]\n\n\
         cr2 d 5 4\n[0 0]\n[1 0]\n[1 1]\n[0 1]\n\n\
         her2 e 6 2 closed\n[0 0] [1 0]\n[1 1] [-1 0]\n"
    );
    assert_eq!(without_positions(parse(&written)), without_positions(doc));
}

/// Anonymous curves referenced by surfaces get generated names that clash with nothing.
#[test]
fn writer_names_referenced_anonymous_curves() {
    let mut doc = parse("circ _c0 5 1\ncirc p 5 1\ncirc s 5 2\ngcyl g p s\nsrev . 9 p");
    // Make the profile and the sweep anonymous, as a program building a document might.
    doc.curves[1].name = None;
    doc.curves[2].name = None;
    let written = doc.to_swp_string();
    assert!(written.contains("circ _c1 5 1\n"), "{written}");
    assert!(written.contains("gcyl g _c1 _c2\n"), "{written}");
    assert!(written.contains("srev . 9 _c1\n"), "{written}");
    let again = parse(&written);
    assert_eq!(again.curves[1].name.as_deref(), Some("_c1"));
    assert_eq!(again.curves[2].name.as_deref(), Some("_c2"));
    let mut expected = without_positions(doc);
    expected.curves[1].name = Some("_c1".into());
    expected.curves[2].name = Some("_c2".into());
    assert_eq!(without_positions(again), expected);
}
