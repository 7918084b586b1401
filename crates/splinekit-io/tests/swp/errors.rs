//! One test per error class: position, message, and structured kind.

use std::time::{Duration, Instant};

use splinekit_io::{SwpDocument, SwpErrorKind};

use super::common::{assert_error, parse_err};

const SQUARE: &str = "[0 0] [1 0] [1 1] [0 1]";

#[test]
fn message_format_matches_the_spec_example() {
    let err = SwpDocument::parse("bsp2 profile 20 4\n[0 0]\n     [1.2.3 0]", "core.swp").unwrap_err();
    assert_eq!(
        err.to_string(),
        r#"core.swp:3:7: found "1.2.3", expected a number (x coordinate of point 2 of bsp2 curve "profile")"#
    );
    assert_eq!((err.origin(), err.line(), err.column()), ("core.swp", 3, 7));
    assert!(matches!(err.kind(), SwpErrorKind::InvalidNumber { found, .. } if found == "1.2.3"));
}

#[test]
fn unknown_keyword() {
    let err = parse_err(&format!("bez2 . 20 4 {SQUARE}\n  BEZ2 . 20 4 {SQUARE}"));
    assert_error(
        &err,
        2,
        3,
        &[
            r#"found "BEZ2", expected a keyword (bez2, bsp2, bez3, bsp3, cr2, cr3, her2, her3, tcb2, tcb3, bo2, bo3, bezn2, bezn3, nurbs2, nurbs3, circ, helix, trefoil, srev or gcyl)"#,
            "(keywords are lowercase)",
        ],
    );
    assert!(matches!(err.kind(), SwpErrorKind::UnknownKeyword { .. }));

    let err = parse_err("bezier . 20 4");
    assert_error(&err, 1, 1, &[r#"found "bezier", expected a keyword"#]);
    assert!(!err.to_string().contains("lowercase"));

    // A stray bracket, and one point too many.
    assert_error(&parse_err("[0 0]"), 1, 1, &[r#"found "[", expected a keyword"#]);
    let err = parse_err(&format!("bez2 . 20 4 {SQUARE} [2 2]"));
    assert_error(&err, 1, 37, &[r#"found "[", expected a keyword"#]);
}

#[test]
fn malformed_number() {
    let cases = [
        (
            "bez2 . 20 4\n[0 0]\n[1 nan]",
            3,
            4,
            r#"found "nan", expected a number (y coordinate of point 2 of bez2 curve #0)"#,
        ),
        (
            "bez3 . 20 4\n[0 0 inf]",
            2,
            6,
            r#"found "inf", expected a number (z coordinate of point 1 of bez3 curve #0)"#,
        ),
        ("bez2 . 20 4 [1e999 0]", 1, 14, r#"found "1e999", expected a number (x coordinate"#),
        ("bez2 . 20 4 [1,5 0]", 1, 14, r#"found "1,5", expected a number"#),
        ("bez2 . 20 4 [1]", 1, 15, r#"found "]", expected a number (y coordinate of point 1"#),
        ("circ . 20 one", 1, 11, r#"found "one", expected a radius (a number ≥ 0) for circ curve #0"#),
        ("circ c 20 -1", 1, 11, r#"found "-1", expected a radius (a number ≥ 0) for circ curve "c""#),
        ("bez2 . 20 four", 1, 11, r#"found "four", expected the number of points (an integer ≥ 0) of bez2 curve #0"#),
        ("bez2 . 20 -4", 1, 11, r#"found "-4", expected the number of points"#),
        ("bez2 . 20 4.0", 1, 11, r#"found "4.0", expected the number of points"#),
        ("her2 . 20 x", 1, 11, r#"found "x", expected the number of point pairs"#),
        (
            "circ . 2.5 1",
            1,
            8,
            r#"found "2.5", expected a step count (an integer from 1 to 1000000) for circ curve #0"#,
        ),
    ];
    for (text, line, column, message) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &[message]);
        assert!(matches!(err.kind(), SwpErrorKind::InvalidNumber { .. }), "{err}");
    }
}

#[test]
fn unexpected_end_of_file_points_after_the_last_token() {
    let cases = [
        (
            "bez2 . 20 4\n[0 0]\n[1",
            3,
            3,
            "found end of file, expected a number (y coordinate of point 2 of bez2 curve #0)",
        ),
        ("bez2 . 20 4\n[0 0]\n[1 1", 3, 5, "found end of file, expected `]` closing point 2 of bez2 curve #0"),
        (
            "circ .   \n\n",
            1,
            7,
            "found end of file, expected a step count (an integer from 1 to 1000000) for circ curve #0",
        ),
        ("circ", 1, 5, "found end of file, expected a name or `.` for the circ curve"),
        ("bez2 p 20", 1, 10, r#"found end of file, expected the number of points (an integer ≥ 0) of bez2 curve "p""#),
        (
            "cr2 . 20 4 alpha # the value is missing\n",
            1,
            17,
            "found end of file, expected the alpha value (a number from 0 to 1) of cr2 curve #0",
        ),
        ("her2 . 20 2 [0 0]", 1, 18, "found end of file, expected `[` starting tangent 1 of 2 of her2 curve #0"),
        (
            "circ c 5 1 gcyl g c",
            1,
            20,
            r#"found end of file, expected the name of the sweep curve of gcyl surface "g""#,
        ),
    ];
    for (text, line, column, message) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &[message]);
        assert!(matches!(err.kind(), SwpErrorKind::UnexpectedEnd { .. }), "{err}");
    }

    let err = parse_err("bsp2 . 20 5\n[0 0] [1 1]\n");
    assert_error(&err, 2, 12, &["found end of file after 2 points, expected 5 points for bsp2 curve #0"]);
    assert!(matches!(err.kind(), SwpErrorKind::MissingPoints { expected: 5, found: 2, pairs: false, .. }));
    let err = parse_err("her3 h 20 3 [0 0 0] [1 0 0]");
    assert_error(&err, 1, 28, &[r#"found end of file after 1 point pair, expected 3 point pairs for her3 curve "h""#]);
}

/// A huge point count must neither allocate for it nor take long to fail.
#[test]
fn huge_point_count_fails_fast() {
    let start = Instant::now();
    let err = parse_err("bez2 . 20 1000000000 [0 0]");
    assert_error(&err, 1, 27, &["found end of file after 1 point, expected 1000000000 points for bez2 curve #0"]);
    for text in [
        "bsp2 . 20 18446744073709551615 [0 0]",
        "bsp3 . 20 99999999999999999999999999 [0 0 0] [1 1 1]",
        "her3 . 20 4000000000 [0 0 0] [1 1 1]",
    ] {
        let err = parse_err(text);
        assert!(matches!(err.kind(), SwpErrorKind::MissingPoints { .. }), "{err}");
    }
    assert!(start.elapsed() < Duration::from_secs(2), "{:?}", start.elapsed());
}

#[test]
fn wrong_point_count() {
    let cases = [
        ("bez2 . 20 5", 1, 11, "found 5 points, expected 3m+1 points with m ≥ 1 (4, 7, 10, …) for bez2 curve #0"),
        ("bez3 . 20 1", 1, 11, "found 1 point, expected 3m+1 points"),
        ("bez2 . 20 4 closed", 1, 11, "found 4 points, expected 3m points with m ≥ 1 (3, 6, 9, …) for bez2 curve #0"),
        ("bsp2 s 20 3", 1, 11, r#"found 3 points, expected at least 4 points for bsp2 curve "s""#),
        ("bsp3 . 20 2 closed", 1, 11, "found 2 points, expected at least 3 points for bsp3 curve #0"),
        ("cr2 . 20 3", 1, 10, "found 3 points, expected at least 4 points for cr2 curve #0"),
        ("cr3 . 20 2 closed", 1, 10, "found 2 points, expected at least 3 points"),
        ("her2 . 20 1 [0 0] [1 0]", 1, 11, "found 1 point pair, expected at least 2 point pairs for her2 curve #0"),
        ("her3 . 20 1 closed", 1, 11, "found 1 point pair, expected at least 2 point pairs"),
        ("bez2 . 20 0", 1, 11, "found 0 points, expected 3m+1 points"),
    ];
    for (text, line, column, message) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &[message]);
        assert!(matches!(err.kind(), SwpErrorKind::PointCount { .. }), "{err}");
    }
    let err = parse_err("bez2 . 20 5");
    assert!(matches!(err.kind(), SwpErrorKind::PointCount { keyword: "bez2", closed: false, found: 5, .. }));
}

#[test]
fn undefined_name() {
    let cases = [
        (
            "srev . 90 profile",
            1,
            11,
            r#"found "profile", expected the name of the profile curve of srev surface #0 (no curve of this name is defined before it)"#,
        ),
        // Defined after use: references only look backwards.
        (
            &format!("gcyl g p s\nbsp2 p 20 4 {SQUARE}"),
            1,
            8,
            r#"found "p", expected the name of the profile curve of gcyl surface "g""#,
        ),
        (&format!("bsp2 . 20 4 {SQUARE}\nsrev . 90 ."), 2, 11, "(anonymous curves cannot be referenced)"),
        (
            &format!("bsp2 p 20 4 {SQUARE}\nsrev s 9 p\ngcyl . p s"),
            3,
            10,
            r#"found "s", expected the name of the sweep curve of gcyl surface #1 (this name is a surface)"#,
        ),
    ];
    for (text, line, column, message) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &[message]);
        assert!(matches!(err.kind(), SwpErrorKind::UndefinedName { .. }), "{err}");
    }
}

#[test]
fn duplicate_name() {
    let err = parse_err("circ a 10 1\n\ncirc a 10 2");
    assert_error(
        &err,
        3,
        6,
        &[r#"found "a" again, expected a new name ("a" is already the name of the circ curve at line 1, column 6)"#],
    );
    assert!(matches!(
        err.kind(),
        SwpErrorKind::DuplicateName { name, first, .. } if name == "a" && (first.line, first.column) == (1, 6)
    ));
    // Curves and surfaces share one name space.
    let err = parse_err(&format!("bsp2 p 20 4 {SQUARE}\nsrev s 9 p\n  bsp2 s 20 4 {SQUARE}"));
    assert_error(&err, 3, 8, &["the srev surface at line 2, column 6"]);
    // Anonymous names may repeat.
    let doc = SwpDocument::parse("circ . 1 1 circ . 1 2 srev . 1 p circ p 1 1", "x");
    assert!(matches!(doc.unwrap_err().kind(), SwpErrorKind::UndefinedName { .. }));
    let doc = SwpDocument::parse("circ . 1 1 circ . 1 2 circ p 1 1 srev . 1 p srev . 1 p", "x");
    assert_eq!(doc.map(|d| (d.curves.len(), d.surfaces.len())).unwrap(), (3, 2));
}

#[test]
fn profile_must_be_2d() {
    let bez3 = "bez3 wing 20 4 [0 0 0] [1 0 0] [1 1 0] [0 1 1]\n";
    let err = parse_err(&format!("{bez3}srev s 90 wing"));
    assert_error(
        &err,
        2,
        11,
        &[
            r#"found 3D curve "wing" (bez3), expected a 2D curve (bez2, bsp2, cr2, her2, tcb2, bo2, bezn2, nurbs2 or circ) as the profile of srev surface "s""#,
        ],
    );
    assert!(matches!(err.kind(), SwpErrorKind::ProfileNot2D { keyword: "bez3", .. }));
    let err = parse_err(&format!("{bez3}circ c 9 1\ngcyl . wing c"));
    assert_error(&err, 3, 8, &["as the profile of gcyl surface #0"]);
    // A 3D sweep is fine.
    let doc = SwpDocument::parse(&format!("{bez3}circ c 9 1\ngcyl . c wing"), "x").unwrap();
    assert_eq!(doc.surfaces.len(), 1);
}

#[test]
fn missing_bracket() {
    let cases = [
        (
            "bez2 . 20 4\n[0 0 0] [1 0] [1 1] [0 1]",
            2,
            6,
            r#"found "0", expected `]` closing point 1 of bez2 curve #0 (its points have 2 coordinates)"#,
        ),
        ("bez2 . 20 4 [0 0] [1 0 [1 1] [0 1]", 1, 24, r#"found "[", expected `]` closing point 2 of bez2 curve #0"#),
        (
            "bez2 . 20 4 [0 0] [1 0] 1 1] [0 1]",
            1,
            25,
            r#"found "1", expected `[` starting point 3 of 4 of bez2 curve #0"#,
        ),
        (
            "her2 . 20 2 [0 0] [1 0] [1 1] 0 1]",
            1,
            31,
            r#"found "0", expected `[` starting tangent 2 of 2 of her2 curve #0"#,
        ),
        ("bsp2 . 20 4 ] [0 0]", 1, 13, r#"found "]", expected `[` starting point 1 of 4 of bsp2 curve #0"#),
        ("bsp2 [ 20 4", 1, 6, r#"found "[", expected a name or `.` for the bsp2 curve"#),
        ("circ c 9 1 srev ] 9 c", 1, 17, r#"found "]", expected a name or `.` for the srev surface"#),
        ("circ c 9 1 srev s 9 [", 1, 21, r#"found "[", expected the name of the profile curve of srev surface "s""#),
    ];
    for (text, line, column, message) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &[message]);
        assert!(matches!(err.kind(), SwpErrorKind::UnexpectedToken { .. }), "{err}");
    }
}

#[test]
fn bad_option() {
    let cases = [
        (
            "bsp2 . 20 4 alpha 0.5 [0 0]",
            1,
            13,
            r#"found "alpha", expected a curve option of bsp2 curve #0 (closed or open); `alpha` applies to cr2 and cr3 only"#,
        ),
        ("her3 . 20 2 centripetal", 1, 13, "`centripetal` applies to cr2 and cr3 only"),
        ("cr2 . 20 4 alpha 1.5", 1, 18, "found \"1.5\", expected an alpha value from 0 to 1 for cr2 curve #0"),
        ("cr2 . 20 4 alpha -0.1", 1, 18, "expected an alpha value from 0 to 1"),
        (
            "bsp2 . 20 4 closd [0 0]",
            1,
            13,
            r#"found "closd", expected `[` starting point 1 of bsp2 curve #0, or a curve option (closed or open)"#,
        ),
        ("cr3 . 20 4 loop", 1, 12, "or a curve option (closed, open, alpha A, uniform, centripetal or chordal)"),
        (
            "bsp2 . 20 4 closed open",
            1,
            20,
            r#"found "open", expected at most one of closed or open for bsp2 curve #0 (already given as "closed" at line 1, column 13)"#,
        ),
        (
            "cr2 . 20 4 chordal alpha 0",
            1,
            20,
            r#"expected at most one of a parametrization for cr2 curve #0 (already given as "chordal""#,
        ),
    ];
    for (text, line, column, message) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &[message]);
        assert!(matches!(err.kind(), SwpErrorKind::BadOption { .. }), "{err}");
    }
    // A non-number alpha is a malformed number.
    let err = parse_err("cr2 . 20 4 alpha half");
    assert_error(&err, 1, 18, &["found \"half\", expected the alpha value (a number from 0 to 1) of cr2 curve #0"]);
}

#[test]
fn steps_out_of_range() {
    let cases = [
        ("circ . 0 1", 1, 8, r#"found "0", expected a step count from 1 to 1000000 for circ curve #0"#),
        ("circ . 1000001 1", 1, 8, "expected a step count from 1 to 1000000"),
        ("circ . -5 1", 1, 8, "expected a step count from 1 to 1000000"),
        ("bez2 b 99999999999999999999999 4", 1, 8, r#"for bez2 curve "b""#),
        ("circ c 9 1\nsrev s 0 c", 2, 8, r#"found "0", expected a step count from 1 to 1000000 for srev surface "s""#),
    ];
    for (text, line, column, message) in cases {
        let err = parse_err(text);
        assert_error(&err, line, column, &[message]);
        assert!(matches!(err.kind(), SwpErrorKind::StepsOutOfRange { .. }), "{err}");
    }
    assert_eq!(SwpDocument::parse("circ . 1000000 1 circ . 1 1", "x").unwrap().curves[0].steps, 1_000_000);
}

#[test]
fn io_error_names_the_path() {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("no/such/file.swp");
    let err = SwpDocument::read(&path).unwrap_err();
    let message = err.to_string();
    assert_eq!((err.line(), err.column(), err.pos()), (0, 0, None));
    assert_eq!(err.origin(), path.display().to_string());
    assert!(message.starts_with(&format!("{}: cannot read file: ", path.display())), "{message}");
    assert!(matches!(
        err.kind(),
        SwpErrorKind::Io { error, path: p } if error.kind() == std::io::ErrorKind::NotFound && *p == path
    ));
    // The OS message follows the path.
    let os_message = std::fs::read(&path).unwrap_err().to_string();
    assert_eq!(message, format!("{}: cannot read file: {os_message}", path.display()));
}

#[test]
fn invalid_utf8_points_at_the_byte() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("swp-invalid-utf8");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("latin1.swp");
    std::fs::write(&path, b"circ . 9 1\r\ncirc na\xefve 9 1\r\n").unwrap();
    let err = SwpDocument::read(&path).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("{}:2:8: found invalid UTF-8 (byte 0xef), expected UTF-8 text", path.display())
    );
    assert!(matches!(err.kind(), SwpErrorKind::InvalidUtf8 { byte: 0xef }));
}

#[test]
fn long_tokens_are_shortened_in_messages() {
    let long = "x".repeat(1000);
    let err = parse_err(&format!("circ . 9 {long}"));
    let message = err.to_string();
    assert!(message.len() < 200, "{message}");
    assert!(message.contains(&format!("found \"{}\"…, expected", "x".repeat(40))), "{message}");
    assert!(matches!(err.kind(), SwpErrorKind::InvalidNumber { found, .. } if found.len() == 1000));
}

#[test]
fn control_characters_are_escaped_in_messages() {
    let err = parse_err("circ . 9 \u{7}1");
    assert_error(&err, 1, 10, &[r#"found "\u{7}1", expected a radius"#]);
}
