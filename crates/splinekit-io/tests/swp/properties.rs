//! Property tests: the parser never panics, errors always point inside the text, and valid
//! documents survive write → parse unchanged.

use glam::DVec3;
use proptest::prelude::*;
use proptest::sample::{Index, select};
use proptest::test_runner::Config;
use splinekit::Tcb;
use splinekit_io::{
    MAX_STEPS, SourcePos, SwpCurve, SwpCurveKind, SwpDocument, SwpError, SwpGeometry, SwpSurface, SwpSurfaceKind,
    SwpSurfaceSettings,
};

use super::common::without_positions;

/// Checks that a parse error has a position inside `text` (the end-of-file position is just
/// after the last token, so at most one column past the end of its line) and the documented
/// message prefix.
fn check_error(text: &str, err: &SwpError) -> Result<(), TestCaseError> {
    let (line, column) = (err.line(), err.column());
    prop_assert!(line >= 1 && column >= 1, "{err}");
    let Some(line_text) = text.split('\n').nth(line - 1) else {
        return Err(TestCaseError::fail(format!("line {line} is past the end: {err}")));
    };
    prop_assert!(column <= line_text.chars().count() + 1, "column {column} is past the end of line {line:?}: {err}");
    let message = err.to_string();
    let prefix = format!("{}:{line}:{column}: found ", err.origin());
    prop_assert!(message.starts_with(&prefix), "{message}");
    prop_assert!(message.contains(", expected "), "{message}");
    Ok(())
}

/// Parses `text`; an error must be well formed, and a document must round-trip.
fn check_text(text: &str) -> Result<(), TestCaseError> {
    match SwpDocument::parse(text, "prop.swp") {
        Err(err) => check_error(text, &err),
        Ok(doc) => check_round_trip(&doc),
    }
}

/// write → parse returns the same document (up to positions), and writing it again gives the
/// same text (so every float keeps its bits, including the sign of zero).
fn check_round_trip(doc: &SwpDocument) -> Result<(), TestCaseError> {
    let written = doc.to_swp_string();
    let again = match SwpDocument::parse(&written, "written.swp") {
        Ok(again) => again,
        Err(e) => return Err(TestCaseError::fail(format!("{e}\n{written}"))),
    };
    prop_assert_eq!(again.to_swp_string(), written.clone());
    prop_assert_eq!(without_positions(again), without_positions(doc.clone()), "{}", written);
    Ok(())
}

const KEYWORDS: [&str; 15] = [
    "bez2", "bsp2", "bez3", "bsp3", "cr2", "cr3", "her2", "her3", "tcb2", "tcb3", "bo2", "bo3", "circ", "srev", "gcyl",
];

fn keyword() -> impl Strategy<Value = &'static str> {
    select(KEYWORDS.to_vec())
}

fn token() -> impl Strategy<Value = String> {
    let punctuation = vec!["[", "]", "[", "]", ".", "#", "[0", "0]"];
    let words = vec![
        "closed",
        "open",
        "alpha",
        "uniform",
        "centripetal",
        "chordal",
        "a",
        "b",
        "profile",
        "sweep",
        "#x",
        "BEZ2",
        "é",
        "\u{feff}",
    ];
    let numbers = vec![
        "0",
        "1",
        "2",
        "3",
        "4",
        "5",
        "6",
        "7",
        "10",
        "20",
        "-1",
        "0.5",
        ".5",
        "1e-3",
        "1.2.3",
        "nan",
        "inf",
        "-0",
        "1000000",
        "1000001",
        "99999999999999999999",
        "1000000000",
    ];
    prop_oneof![
        3 => keyword().prop_map(str::to_owned),
        4 => select(punctuation).prop_map(str::to_owned),
        2 => select(words).prop_map(str::to_owned),
        5 => select(numbers).prop_map(str::to_owned),
        2 => any::<f64>().prop_map(|f| f.to_string()),
        1 => "\\PC{1,4}",
    ]
}

fn separator() -> impl Strategy<Value = &'static str> {
    select(vec![" ", " ", "\n", "\r\n", "\t", "", "  # note\n", "\r"])
}

/// Finite f64 values: small "nice" ones, and every finite bit pattern.
fn coordinate() -> impl Strategy<Value = f64> {
    use proptest::num::f64 as f;
    prop_oneof![
        3 => (-1000i32..1000).prop_map(|n| f64::from(n) / 8.0),
        3 => -10.0f64..10.0,
        2 => f::POSITIVE | f::NEGATIVE | f::NORMAL | f::SUBNORMAL | f::ZERO,
    ]
}

fn point() -> impl Strategy<Value = DVec3> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A Kochanek–Bartels shape value in [−1, 1]: the ends, zero (of either sign) and any between.
fn shape_value() -> impl Strategy<Value = f64> {
    prop_oneof![Just(-1.0), Just(1.0), Just(0.0), Just(-0.0), -1.0f64..=1.0]
}

fn shape() -> impl Strategy<Value = Tcb> {
    (shape_value(), shape_value(), shape_value()).prop_map(|(t, c, b)| Tcb::new(t, c, b))
}

/// A valid curve; `name` is a base that the document makes unique.
fn curve() -> impl Strategy<Value = SwpCurve> {
    (
        (0u8..7, any::<bool>(), any::<bool>(), 1..=MAX_STEPS),
        prop_oneof![Just(0.0), Just(0.5), Just(1.0), 0.0f64..=1.0],
        (0usize..6, prop::option::of("[a-z]{1,5}")),
        prop_oneof![
            Just(0.0),
            0.0f64..100.0,
            proptest::num::f64::POSITIVE | proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL
        ],
        (prop::collection::vec(point(), 20), prop::collection::vec(point(), 20), prop::collection::vec(shape(), 20)),
    )
        .prop_map(
            |((family, three, closed, steps), alpha, (m, name), radius, (mut points, mut tangents, mut shapes))| {
                let dim: u8 = if three && family != 4 { 3 } else { 2 };
                if dim == 2 {
                    for p in points.iter_mut().chain(&mut tangents) {
                        p.z = 0.0;
                    }
                }
                let count = match (family, closed) {
                    (0, false) => 3 * (m + 1) + 1,
                    (0, true) => 3 * (m + 1),
                    (1 | 2 | 5 | 6, false) => 4 + m,
                    (1 | 2 | 5 | 6, true) => 3 + m,
                    _ => 2 + m,
                };
                points.truncate(count);
                tangents.truncate(count);
                shapes.truncate(count);
                let (kind, geometry) = match family {
                    0 => (SwpCurveKind::Bezier, SwpGeometry::Points(points)),
                    1 => (SwpCurveKind::BSpline, SwpGeometry::Points(points)),
                    2 => (SwpCurveKind::CatmullRom { alpha }, SwpGeometry::Points(points)),
                    3 => (SwpCurveKind::Hermite, SwpGeometry::Hermite { points, tangents }),
                    5 => (SwpCurveKind::KochanekBartels, SwpGeometry::Tcb { points, shape: shapes }),
                    6 => (SwpCurveKind::BesselOverhauser, SwpGeometry::Points(points)),
                    _ => (SwpCurveKind::Circle, SwpGeometry::Circle { radius }),
                };
                SwpCurve { name, kind, dim, steps, closed: closed || family == 4, geometry, pos: SourcePos::default() }
            },
        )
}

/// Raw draws of surface settings: which tessellation (none, distance, angle) with a distance
/// and an angle, then layout (compat?), frames (which of five), caps, align (which of
/// three), join (which of three) and mitre limit.
type RawSettings =
    ((u8, f64, f64), Option<bool>, Option<u8>, Option<bool>, Option<u8>, Option<u8>, Option<f64>, Option<bool>);

/// Valid settings for a surface of `kind` from raw draws: only those that apply to it.
fn settings_for(
    kind: SwpSurfaceKind,
    ((t, distance, degrees), layout, frames, caps, align, join, mitre_limit, override_scale): RawSettings,
) -> SwpSurfaceSettings {
    use splinekit::sweep::{Join, MeshLayout};
    use splinekit_io::surface::{ProfileAlign, ScaleMode};
    use splinekit_io::swp::{SwpFrames, SwpTessellation};
    let gcyl = matches!(kind, SwpSurfaceKind::GeneralizedCylinder { .. });
    let laid_out = gcyl || matches!(kind, SwpSurfaceKind::Revolution { .. } | SwpSurfaceKind::ToolSweep { .. });
    SwpSurfaceSettings {
        tessellation: match t {
            _ if matches!(kind, SwpSurfaceKind::ToolSweep { .. }) => None,
            0 => None,
            1 => Some(SwpTessellation::Distance(distance)),
            _ => Some(SwpTessellation::AngleDegrees(degrees)),
        },
        layout: layout.filter(|_| laid_out).map(|c| if c { MeshLayout::Compat } else { MeshLayout::Welded }),
        frames: frames.filter(|_| gcyl).map(|k| {
            [SwpFrames::Auto, SwpFrames::Sequential, SwpFrames::RotationMinimizing, SwpFrames::Frenet, SwpFrames::ZUp]
                [usize::from(k % 5)]
        }),
        caps: caps.filter(|_| gcyl),
        align: align
            .filter(|_| gcyl)
            .map(|k| [ProfileAlign::Origin, ProfileAlign::Centre, ProfileAlign::Start][usize::from(k % 3)]),
        join: join.filter(|_| gcyl).map(|k| [Join::Mitre, Join::Round, Join::Bevel][usize::from(k % 3)]),
        mitre_limit: mitre_limit.filter(|_| gcyl),
        scale_mode: override_scale.filter(|_| gcyl).map(|o| if o { ScaleMode::Override } else { ScaleMode::Multiply }),
    }
}

/// A valid document: unique names, references to earlier curves only, 2D profiles, and a name
/// on every referenced curve (so that the round trip is exact).
fn document() -> impl Strategy<Value = SwpDocument> {
    let positive = || prop_oneof![Just(1.0), 1e-3f64..10.0, proptest::num::f64::POSITIVE | proptest::num::f64::NORMAL];
    // zrev numbers: epsilon, slice tolerance (at most MAX_STEPS slices), scale; lathe slices
    let extension = (positive(), (core::f64::consts::TAU / f64::from(MAX_STEPS))..10.0, positive(), 3..=MAX_STEPS);
    // surface settings: a tessellation (none, distance, angle), layout, frames, caps, align
    let settings = (
        (0u8..3, positive(), 1e-3f64..=180.0),
        prop::option::of(any::<bool>()),
        prop::option::of(0u8..5),
        prop::option::of(any::<bool>()),
        prop::option::of(0u8..3),
        prop::option::of(0u8..3),
        prop::option::of(prop_oneof![Just(1.0), 1.0f64..20.0]),
        prop::option::of(any::<bool>()),
    );
    let surface =
        ((0u8..5, extension), 1..=MAX_STEPS, any::<Index>(), any::<Index>(), prop::option::of("[a-z]{1,5}"), settings);
    (prop::collection::vec(curve(), 0..6), prop::collection::vec(surface, 0..4)).prop_map(
        |(mut curves, raw_surfaces)| {
            for (i, c) in curves.iter_mut().enumerate() {
                c.name = c.name.take().map(|base| format!("{base}{i}"));
            }
            let flat: Vec<usize> = (0..curves.len()).filter(|&i| curves[i].dim == 2).collect();
            let mut surfaces = Vec::new();
            if !flat.is_empty() {
                for (j, ((which, (epsilon, slice_tolerance, scale, slices)), steps, profile, sweep, name, settings)) in
                    raw_surfaces.into_iter().enumerate()
                {
                    let other = flat[sweep.index(flat.len())];
                    let profile = flat[profile.index(flat.len())];
                    let sweep = sweep.index(curves.len());
                    let kind = match which {
                        0 => SwpSurfaceKind::Revolution { steps, profile },
                        1 => SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale: None, twist: None },
                        2 => SwpSurfaceKind::RevolutionZ { profile, epsilon, slice_tolerance, scale },
                        3 => SwpSurfaceKind::ToolSweep {
                            profile,
                            path: other,
                            epsilon,
                            path_epsilon: slice_tolerance,
                            scale,
                        },
                        _ => SwpSurfaceKind::Lathe { stacks: steps, slices, radius: profile, height: other },
                    };
                    surfaces.push(SwpSurface {
                        name: name.map(|base| format!("{base}S{j}")),
                        kind,
                        settings: settings_for(kind, settings),
                        pos: SourcePos::default(),
                    });
                }
            }
            for s in &surfaces {
                for (_, i) in s.kind.references() {
                    curves[i].name.get_or_insert_with(|| format!("r{i}"));
                }
            }
            SwpDocument { curves, surfaces }
        },
    )
}

proptest! {
    #![proptest_config(Config { cases: 512, ..Config::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        let text = String::from_utf8_lossy(&bytes);
        if let Err(err) = SwpDocument::parse(&text, "bytes.swp") {
            check_error(&text, &err)?;
        }
    }

    #[test]
    fn random_text_never_panics(text in "\\PC{0,200}") {
        check_text(&text)?;
    }

    #[test]
    fn token_soups_never_panic(parts in prop::collection::vec((token(), separator()), 0..60)) {
        let text: String = parts.iter().flat_map(|(t, s)| [t.as_str(), *s]).collect();
        check_text(&text)?;
    }

    /// Soups that start each run of tokens with a keyword, so that parsing gets deeper.
    #[test]
    fn keyword_led_soups_never_panic(
        objects in prop::collection::vec(
            (keyword(), prop::collection::vec((token(), separator()), 0..16)),
            0..6,
        ),
    ) {
        let text: String = objects
            .iter()
            .flat_map(|(keyword, parts)| {
                std::iter::once(format!("{keyword} "))
                    .chain(parts.iter().map(|(t, s)| format!("{t}{s}")))
            })
            .collect();
        check_text(&text)?;
    }
}

proptest! {
    #![proptest_config(Config { cases: 256, ..Config::default() })]

    #[test]
    fn valid_documents_round_trip(doc in document()) {
        prop_assert_eq!(doc.validate(), Ok(()));
        check_round_trip(&doc)?;
    }

    /// Valid documents with a few tokens deleted, duplicated or replaced: errors deep inside
    /// objects must still be well formed.
    #[test]
    fn mutated_documents_never_panic(
        doc in document(),
        edits in prop::collection::vec((0u8..3, any::<Index>(), token()), 1..4),
        separator in separator(),
    ) {
        let written = doc.to_swp_string();
        let mut tokens: Vec<String> = written.split_whitespace().map(str::to_owned).collect();
        for (op, at, replacement) in edits {
            if tokens.is_empty() {
                tokens.push(replacement);
                continue;
            }
            let i = at.index(tokens.len());
            match op {
                0 => { tokens.remove(i); }
                1 => { let t = tokens[i].clone(); tokens.insert(i, t); }
                _ => tokens[i] = replacement,
            }
        }
        check_text(&tokens.join(separator))?;
    }
}
