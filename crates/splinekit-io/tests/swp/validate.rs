//! `SwpDocument::validate` against the reader: a document validates exactly when writing it
//! and reading it back gives it again, and every bundled file validates.

use std::path::{Path, PathBuf};

use glam::DVec3;
use proptest::prelude::*;
use proptest::sample::select;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, TestRunner};
use splinekit::Tcb;
use splinekit_io::{
    MAX_STEPS, SourcePos, SwpCurve, SwpCurveKind, SwpDocument, SwpGeometry, SwpSurface, SwpSurfaceKind,
};

use super::common::{data_dir, without_positions};

/// Every `.swp` file under `dir`, recursively, sorted.
fn swp_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(swp_files(&path));
        } else if path.extension().is_some_and(|e| e == "swp") {
            files.push(path);
        }
    }
    files.sort();
    files
}

#[test]
fn bundled_files_validate() {
    let files = swp_files(&data_dir());
    assert!(files.len() >= 16, "{files:?}");
    for path in files {
        let doc = SwpDocument::read(&path).unwrap_or_else(|e| panic!("{e}"));
        if let Err(problem) = doc.validate() {
            panic!("{}: {problem}", path.display());
        }
    }
}

/// Names: mostly good ones (which may repeat), sometimes anonymous, sometimes unwritable.
fn name() -> impl Strategy<Value = Option<String>> {
    let good =
        vec!["a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l", "profile", "scale", "gcyl", "_c1", "é", "-1"];
    let bad = vec!["", ".", "a b", "x[", "y]", "#c", "x#y", "k\n", "\t"];
    prop_oneof![
        24 => select(good).prop_map(|n| Some(n.to_owned())),
        8 => Just(None),
        1 => select(bad).prop_map(|n| Some(n.to_owned())),
    ]
}

/// A coordinate or parameter: nice values, any finite value, and rarely a non-finite one.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => (-40i32..40).prop_map(|n| f64::from(n) / 4.0),
        2 => -1e3f64..1e3,
        1 => select(vec![-0.0, 1e300, -1e-300, 5e-324, f64::MAX]),
    ]
}

fn bad_number() -> impl Strategy<Value = f64> {
    select(vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY])
}

/// Usually `good`, sometimes (1 in `odds + 1`) `bad`.
fn mostly<T: std::fmt::Debug + Clone + 'static>(
    odds: u32,
    good: impl Strategy<Value = T> + 'static,
    bad: impl Strategy<Value = T> + 'static,
) -> BoxedStrategy<T> {
    prop_oneof![odds => good, 1 => bad].boxed()
}

/// A Kochanek–Bartels tension, continuity or bias: almost always in [−1, 1].
fn shape_value() -> impl Strategy<Value = f64> {
    mostly(
        300,
        prop_oneof![Just(0.0), Just(-0.0), Just(1.0), Just(-1.0), -1.0f64..=1.0],
        select(vec![1.5, -1.0000001, f64::NAN, f64::INFINITY]),
    )
}

/// A curve of a random kind, usually valid, with at most a few things wrong.
fn curve() -> impl Strategy<Value = SwpCurve> {
    let shape = (
        0usize..11,
        mostly(25, select(vec![0.0, 0.5, 1.0, 0.25]), select(vec![-0.5, 1.5, f64::NAN])),
        mostly(30, Just(None), (0u8..5).prop_map(Some)),
        (any::<bool>(), any::<bool>()),
        mostly(30, Just(None), any::<bool>().prop_map(Some)),
        mostly(30, 1..=40u32, select(vec![0, MAX_STEPS, MAX_STEPS + 1])),
    );
    let points = (
        0usize..12,
        mostly(10, Just(true), Just(false)),
        prop::collection::vec((number(), number(), number()), 14),
        prop::collection::vec((number(), number(), number()), 14),
        mostly(25, Just(None), (0usize..14, 0usize..3, bad_number()).prop_map(Some)),
        mostly(25, Just(None), (0usize..14, select(vec![0.5, -2.0, f64::NAN])).prop_map(Some)),
        mostly(25, Just(0isize), select(vec![-1isize, 1])),
        prop::collection::vec((shape_value(), shape_value(), shape_value()), 14),
    );
    let scalars = (
        mostly(30, Just(None), (0usize..7).prop_map(Some)),
        mostly(25, prop_oneof![Just(0.0), 0.0..5.0f64], select(vec![-1.0, f64::NAN, f64::INFINITY])),
        mostly(25, number(), bad_number()),
        mostly(25, select(vec![0.5, 1.0, 3.25, 10_000.0]), select(vec![0.0, -1.0, 10_000.5, f64::NAN])),
        name(),
    );
    // NURBS: the degree, the weights, and a knot vector (none, or increments to sum up, its
    // length off by the delta now and then, a decrease now and then)
    let nurbs = (
        mostly(40, 1u32..=4, select(vec![0u32, 33])),
        prop::collection::vec(mostly(60, prop_oneof![Just(1.0), 0.1f64..5.0], select(vec![0.0, -1.0, f64::NAN])), 14),
        prop::option::weighted(
            0.5,
            (
                prop::collection::vec(mostly(8, prop_oneof![Just(0.0), Just(1.0), 0.0f64..3.0], Just(-1.0)), 20),
                mostly(20, Just(0isize), select(vec![-1isize, 1])),
            ),
        ),
    );
    (shape, points, scalars, nurbs).prop_map(
        |(
            (kind, alpha, dim, (closed, three), fixed_closed, steps),
            (count, fix_count, raw_points, raw_tangents, non_finite, nonzero_z, tangent_delta, raw_shapes),
            (mismatch, radius, pitch, turns, name),
            (degree, raw_weights, raw_knots),
        )| {
            let kind = match kind {
                0 => SwpCurveKind::Bezier,
                1 => SwpCurveKind::BSpline,
                2 => SwpCurveKind::CatmullRom { alpha },
                3 => SwpCurveKind::Hermite,
                4 => SwpCurveKind::Circle,
                5 => SwpCurveKind::Helix,
                6 => SwpCurveKind::Trefoil,
                7 => SwpCurveKind::KochanekBartels,
                8 => SwpCurveKind::BesselOverhauser,
                9 => SwpCurveKind::BezierN,
                _ => SwpCurveKind::Nurbs { degree },
            };
            let natural_dim = match kind {
                SwpCurveKind::Circle => 2,
                SwpCurveKind::Helix | SwpCurveKind::Trefoil => 3,
                _ if three => 3,
                _ => 2,
            };
            let dim = dim.unwrap_or(natural_dim);
            let closed = match kind {
                SwpCurveKind::Circle | SwpCurveKind::Trefoil => fixed_closed.unwrap_or(true),
                SwpCurveKind::Helix => fixed_closed.unwrap_or(false),
                _ => fixed_closed.unwrap_or(closed),
            };
            // usually move the count up to the next one the kind accepts
            let count = if fix_count {
                (count..count + 4).find(|&n| kind.accepts_point_count(closed, n as u64)).unwrap_or(count)
            } else {
                count
            };
            let to_points = |raw: &[(f64, f64, f64)]| -> Vec<DVec3> {
                raw.iter().take(count).map(|&(x, y, z)| DVec3::new(x, y, if dim == 3 { z } else { 0.0 })).collect()
            };
            let mut points = to_points(&raw_points);
            let mut tangents = to_points(&raw_tangents);
            let mut shapes: Vec<Tcb> = raw_shapes.iter().take(count).map(|&(t, c, b)| Tcb::new(t, c, b)).collect();
            let mut weights: Vec<f64> = raw_weights.iter().take(count).copied().collect();
            let knots = raw_knots.map(|(increments, delta)| {
                let len = (count + degree as usize + 1).saturating_add_signed(delta).min(increments.len());
                increments[..len]
                    .iter()
                    .scan(0.0, |sum, step| {
                        *sum += step;
                        Some(*sum)
                    })
                    .collect::<Vec<f64>>()
            });
            if let Some((index, axis, value)) = non_finite
                && let Some(p) = points.get_mut(index)
            {
                p[axis] = value;
            }
            // a z in a point (index < 7) or a tangent
            if let Some((index, z)) = nonzero_z
                && let Some(p) = if index < 7 { points.get_mut(index) } else { tangents.get_mut(index - 7) }
            {
                p.z = z;
            }
            match tangent_delta {
                -1 => {
                    tangents.pop();
                    shapes.pop();
                    weights.pop();
                }
                1 => {
                    tangents.push(DVec3::X);
                    shapes.push(Tcb::default());
                    weights.push(1.0);
                }
                _ => {}
            }
            let helix = SwpGeometry::Helix { radius, pitch, turns };
            let geometry = match mismatch.unwrap_or(match kind {
                SwpCurveKind::Bezier
                | SwpCurveKind::BSpline
                | SwpCurveKind::CatmullRom { .. }
                | SwpCurveKind::BesselOverhauser
                | SwpCurveKind::BezierN => 0,
                SwpCurveKind::Hermite => 1,
                SwpCurveKind::Circle => 2,
                SwpCurveKind::Helix => 3,
                SwpCurveKind::Trefoil => 4,
                SwpCurveKind::KochanekBartels => 5,
                SwpCurveKind::Nurbs { .. } => 6,
            }) {
                0 => SwpGeometry::Points(points),
                1 => SwpGeometry::Hermite { points, tangents },
                2 => SwpGeometry::Circle { radius },
                3 => helix,
                4 => SwpGeometry::Trefoil { size: radius },
                5 => SwpGeometry::Tcb { points, shape: shapes },
                _ => SwpGeometry::Nurbs { points, weights, knots },
            };
            SwpCurve { name, kind, dim, steps, closed, geometry, pos: SourcePos::default() }
        },
    )
}

/// A document of random curves and surfaces with random references (some out of range).
fn document() -> impl Strategy<Value = SwpDocument> {
    let reference = 0usize..24;
    let surface = (
        any::<bool>(),
        mostly(30, 1..=40u32, select(vec![0, MAX_STEPS + 1])),
        (reference.clone(), reference.clone()),
        (prop::option::weighted(0.3, reference.clone()), prop::option::weighted(0.3, reference)),
        name(),
    );
    let curves = prop_oneof![1 => prop::collection::vec(curve(), 0..1), 8 => prop::collection::vec(curve(), 1..6)];
    (curves, prop::collection::vec(surface, 0..3)).prop_map(|(curves, raw)| {
        // now and then one index past the end, which is out of range
        let pick = |raw: usize| if raw == 0 { curves.len() } else { (raw - 1) % curves.len().max(1) };
        // profiles, scale and twist curves: mostly 2D curves
        let flat: Vec<usize> = (0..curves.len()).filter(|&i| curves[i].dim == 2).collect();
        let pick_flat = |raw: usize| if raw % 4 == 1 || flat.is_empty() { pick(raw) } else { flat[raw % flat.len()] };
        let surfaces = raw
            .into_iter()
            .map(|(revolution, steps, (profile, sweep), (scale, twist), name)| SwpSurface {
                name,
                kind: if revolution {
                    SwpSurfaceKind::Revolution { steps, profile: pick_flat(profile) }
                } else {
                    SwpSurfaceKind::GeneralizedCylinder {
                        profile: pick_flat(profile),
                        sweep: pick(sweep),
                        scale: scale.map(pick_flat),
                        twist: twist.map(pick_flat),
                    }
                },
                settings: Default::default(),
                pos: SourcePos::default(),
            })
            .collect();
        SwpDocument { curves, surfaces }
    })
}

/// The document read back from its written text, if the text parses.
fn reread(doc: &SwpDocument) -> Option<SwpDocument> {
    SwpDocument::parse(&doc.to_swp_string(), "x").ok().map(without_positions)
}

proptest! {
    #![proptest_config(Config { cases: 256, ..Config::default() })]

    /// `validate` is `Ok` exactly when write → parse gives the document back.
    #[test]
    fn validate_agrees_with_the_round_trip(doc in document()) {
        let back = reread(&doc);
        let same = back.as_ref() == Some(&without_positions(doc.clone()));
        match doc.validate() {
            Ok(()) => prop_assert!(same, "valid, but reads back as {back:#?}\n--- written ---\n{}", doc.to_swp_string()),
            Err(problem) => {
                prop_assert!(!same, "{problem}, yet the round trip works:\n{}", doc.to_swp_string());
                let message = problem.to_string();
                prop_assert!(message.starts_with("curve ") || message.starts_with("surface "), "{message}");
                prop_assert!(!message.ends_with('.'), "{message}");
                prop_assert!(!message.contains("3m") && !message.contains("SPEC"), "{message}");
            }
        }
    }
}

/// The generator makes both valid and invalid documents often enough to test both sides.
#[test]
fn generator_covers_both_outcomes() {
    let mut runner = TestRunner::deterministic();
    let strategy = document();
    let valid = (0..400).filter(|_| strategy.new_tree(&mut runner).unwrap().current().validate().is_ok()).count();
    assert!((60..=340).contains(&valid), "{valid} of 400 valid");
}
