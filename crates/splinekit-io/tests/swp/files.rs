//! The 12 bundled SWP files: the facts listed in tests/data/SOURCES.md, exact coordinates,
//! line-ending independence, round trips and golden written output.

use std::path::Path;

use glam::DVec3;
use splinekit_io::{SwpCurveKind, SwpDocument, SwpSurfaceKind};

use super::common::{DATA_FILES, load, points, radius, text, without_positions};

/// (keyword, name, steps, number of control points or None for circles) of every curve.
fn summary(doc: &SwpDocument) -> Vec<(&'static str, Option<&str>, u32, Option<usize>)> {
    doc.curves
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let count = (c.kind != SwpCurveKind::Circle).then(|| points(doc, i).len());
            (c.keyword(), c.name.as_deref(), c.steps, count)
        })
        .collect()
}

fn gcyl(profile: usize, sweep: usize) -> SwpSurfaceKind {
    SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale: None, twist: None }
}

/// Checks that the last three control points repeat the first three: how these files write a
/// closed uniform B-spline in plain SWP (the `closed` flag itself stays false).
#[track_caller]
fn assert_wrapped(doc: &SwpDocument, index: usize) {
    let p = points(doc, index);
    assert_eq!(p[p.len() - 3..], p[..3], "curve {index}");
    assert!(!doc.curves[index].closed);
}

#[test]
fn circles() {
    let doc = load("circles.swp");
    assert_eq!(summary(&doc), [("circ", None, 30, None), ("circ", None, 50, None)]);
    assert_eq!((radius(&doc, 0), radius(&doc, 1)), (1.0, 2.0));
    assert!(doc.curves.iter().all(|c| c.dim == 2 && c.closed));
    assert!(doc.surfaces.is_empty());
}

#[test]
fn core() {
    let doc = load("core.swp");
    assert_eq!(
        summary(&doc),
        [
            ("bez2", None, 20, Some(4)),
            ("bsp2", None, 20, Some(4)),
            ("bez3", None, 20, Some(4)),
            ("bsp3", None, 20, Some(4)),
        ]
    );
    let dims: Vec<u8> = doc.curves.iter().map(|c| c.dim).collect();
    assert_eq!(dims, [2, 2, 3, 3]);
    assert_eq!(
        points(&doc, 0),
        [DVec3::new(3.0, 0.0, 0.0), DVec3::new(3.0, 1.0, 0.0), DVec3::new(1.0, 1.0, 0.0), DVec3::new(1.0, 0.0, 0.0),]
    );
    assert_eq!(points(&doc, 2)[1], DVec3::new(0.0, -1.0, 1.0));
    assert_eq!(points(&doc, 3)[3], DVec3::new(2.0, 0.0, -1.0));
    assert_eq!((doc.curves[0].pos.line, doc.curves[1].pos.line, doc.curves[3].pos.line), (1, 7, 19));
    assert!(doc.surfaces.is_empty());
    assert_eq!(doc.curves[1].display_name(1), "#1");
}

#[test]
fn flircle() {
    let doc = load("gcyl/flircle.swp");
    assert_eq!(summary(&doc), [("bsp2", Some("sweep"), 20, Some(28)), ("circ", Some("profile"), 50, None)]);
    assert_eq!(radius(&doc, 1), 0.4);
    let p = points(&doc, 0);
    assert_eq!(p[0], DVec3::new(-3.326404, -1.505451, 0.0));
    assert_eq!(p[2], DVec3::new(-0.765483, -0.567379, 0.0));
    assert_eq!(p[7], DVec3::new(0.352010, -0.660155, 0.0));
    assert_wrapped(&doc, 0);
    assert_eq!(doc.surfaces.len(), 1);
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("flircle"));
    assert_eq!(doc.surfaces[0].kind, gcyl(1, 0));
    assert_eq!(doc.surfaces[0].pos.line, 33);
    assert_eq!(doc.curve_index("profile"), Some(1));
    assert_eq!(doc.surface_index("flircle"), Some(0));
}

#[test]
fn florus() {
    let doc = load("gcyl/florus.swp");
    assert_eq!(summary(&doc), [("bsp2", Some("profile"), 5, Some(28)), ("circ", Some("sweep"), 60, None)]);
    assert_eq!(radius(&doc, 1), 2.3);
    assert_eq!(points(&doc, 0)[0], DVec3::new(-0.173910, 0.213798, 0.0));
    assert_wrapped(&doc, 0);
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("florus"));
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1));
    assert!(!text("gcyl/florus.swp").ends_with('\n'), "no final newline");
}

#[test]
fn gentorus() {
    let doc = load("gcyl/gentorus.swp");
    assert_eq!(summary(&doc), [("bsp2", Some("profile"), 5, Some(11)), ("circ", Some("sweep"), 80, None)]);
    assert_eq!(radius(&doc, 1), 2.2);
    assert_eq!(points(&doc, 0)[1], DVec3::new(0.75, -0.75, 0.0));
    assert_wrapped(&doc, 0);
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("gentorus"));
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1));
}

#[test]
fn tor() {
    let doc = load("gcyl/tor.swp");
    assert_eq!(summary(&doc), [("circ", Some("profile"), 30, None), ("circ", Some("sweep"), 60, None)]);
    assert_eq!((radius(&doc, 0), radius(&doc, 1)), (0.5, 2.0));
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("fbf"));
    assert_eq!(doc.surface_index("tor"), None);
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1));
}

#[test]
fn weird() {
    let doc = load("gcyl/weird.swp");
    assert_eq!(summary(&doc), [("bsp2", Some("profile"), 8, Some(11)), ("bsp3", Some("sweep"), 16, Some(11))]);
    assert_eq!(doc.curves[1].dim, 3);
    assert_eq!(points(&doc, 1)[0], DVec3::new(-1.427273, 0.424545, 0.929339));
    assert_wrapped(&doc, 0);
    assert_wrapped(&doc, 1);
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("weird"));
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1));
}

#[test]
fn weirder() {
    let doc = load("gcyl/weirder.swp");
    assert_eq!(summary(&doc), [("bsp2", Some("profile"), 8, Some(9)), ("bsp3", Some("sweep"), 16, Some(10))]);
    assert_eq!(points(&doc, 1)[5], DVec3::new(0.212727, 1.034545, -1.260661));
    assert_wrapped(&doc, 0);
    assert_wrapped(&doc, 1);
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("weirder"));
    assert_eq!(doc.surfaces[0].kind, gcyl(0, 1));
}

#[test]
fn norm() {
    let doc = load("srev/norm.swp");
    assert_eq!(summary(&doc), [("bez2", Some("profile"), 50, Some(4))]);
    assert_eq!(
        points(&doc, 0),
        [
            DVec3::new(-2.0, 2.0, 0.0),
            DVec3::new(-4.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(-2.0, -2.0, 0.0),
        ]
    );
    assert_eq!(doc.surfaces.len(), 1);
    assert_eq!(doc.surfaces[0].name, None);
    assert_eq!(doc.surfaces[0].kind, SwpSurfaceKind::Revolution { steps: 90, profile: 0 });
    assert_eq!(doc.surfaces[0].display_name(0), "#0");
}

#[test]
fn wineglass() {
    let doc = load("srev/wineglass.swp");
    assert_eq!(summary(&doc), [("bsp2", Some("profile"), 8, Some(26))]);
    let p = points(&doc, 0);
    let ends: Vec<(f64, f64)> = p[..3].iter().chain(&p[23..]).map(|v| (v.x, v.y)).collect();
    assert_eq!(
        ends,
        [(0.0, -0.459543), (0.0, -0.459544), (0.0, -0.459545), (0.0, -2.458800), (0.0, -2.458801), (0.0, -2.458802),]
    );
    assert_eq!(p[8], DVec3::new(-1.029301, 2.503360, 0.0));
    assert_eq!(doc.surfaces[0].name.as_deref(), Some("wineglass"));
    assert_eq!(doc.surfaces[0].kind, SwpSurfaceKind::Revolution { steps: 90, profile: 0 });
    assert!(text("srev/wineglass.swp").ends_with("profile \r\n"), "trailing space");
}

#[test]
fn dragonfly() {
    let doc = load("extra/dragonfly.swp");
    assert_eq!(
        summary(&doc),
        [
            ("bez2", Some("body"), 30, Some(7)),
            ("bez2", Some("thorax"), 20, Some(4)),
            ("bez3", Some("ltwing"), 20, Some(4)),
            ("bez3", Some("rtwing"), 20, Some(4)),
            ("bez3", Some("lbwing"), 20, Some(4)),
            ("bez3", Some("rbwing"), 20, Some(4)),
        ]
    );
    assert_eq!(points(&doc, 0)[4], DVec3::new(-2.0, -7.0, 0.0));
    assert_eq!(points(&doc, 2)[1], DVec3::new(-7.0, 4.0, 2.0));
    let surfaces: Vec<_> = doc.surfaces.iter().map(|s| (s.name.as_deref(), s.kind)).collect();
    assert_eq!(
        surfaces,
        [
            (None, SwpSurfaceKind::Revolution { steps: 90, profile: 0 }),
            (None, SwpSurfaceKind::Revolution { steps: 90, profile: 1 }),
        ]
    );
}

#[test]
fn tube_table() {
    let doc = load("extra/tube-table.swp");
    assert_eq!(
        summary(&doc),
        [
            ("bsp3", Some("uloop"), 30, Some(8)),
            ("bsp3", Some("dloop"), 30, Some(8)),
            ("bez2", Some("bowl"), 20, Some(4)),
            ("bez2", Some("bowlin"), 20, Some(4)),
            ("circ", Some("little"), 30, None),
            ("circ", Some("round"), 60, None),
            ("circ", Some("profile"), 30, None),
        ]
    );
    assert_eq!(radius(&doc, 4), 0.0, "a circle of radius 0 used as a sweep");
    assert_eq!((radius(&doc, 5), radius(&doc, 6)), (3.0, 0.5));
    assert_eq!(points(&doc, 1)[2], DVec3::new(2.0, -5.0, -2.0));
    assert_eq!(points(&doc, 2)[1], DVec3::new(-1.0, 0.5, 0.0));
    let kinds: Vec<_> = doc.surfaces.iter().map(|s| s.kind).collect();
    assert_eq!(kinds, [gcyl(6, 0), gcyl(6, 1), gcyl(6, 5), gcyl(2, 4), gcyl(3, 4)]);
    assert!(doc.surfaces.iter().all(|s| s.name.is_none()));
}

/// The bundled CRLF files read exactly as their LF versions (positions included), and the LF
/// files exactly as their CRLF versions.
#[test]
fn line_endings_do_not_matter() {
    for rel in DATA_FILES {
        let original = text(rel);
        let lf = original.replace("\r\n", "\n");
        let crlf = lf.replace('\n', "\r\n");
        let doc = load(rel);
        for variant in [&lf, &crlf] {
            assert_eq!(SwpDocument::parse(variant, rel).unwrap(), doc, "{rel}");
        }
    }
}

/// parse → write → parse gives the same document (up to positions) for every bundled file,
/// and writing is deterministic.
#[test]
fn data_files_round_trip() {
    for rel in DATA_FILES {
        let doc = load(rel);
        let written = doc.to_swp_string();
        let again = SwpDocument::parse(&written, rel).unwrap_or_else(|e| panic!("{e}\n{written}"));
        assert_eq!(without_positions(again.clone()), without_positions(doc), "{rel}");
        assert_eq!(again.to_swp_string(), written, "{rel}");
    }
}

/// The written form of every bundled file matches `tests/data/golden/swp/<file>`.
/// Run with `UPDATE_GOLDEN=1` to regenerate.
#[test]
fn written_files_match_golden() {
    let golden_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/golden/swp");
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    let mut failures = Vec::new();
    for rel in DATA_FILES {
        let written = load(rel).to_swp_string();
        let path = golden_dir.join(rel);
        if update {
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, &written).unwrap();
            continue;
        }
        let expected = std::fs::read_to_string(&path).unwrap_or_else(|e| {
            panic!("{}: {e} (run `UPDATE_GOLDEN=1 cargo test -p splinekit-io` to create it)", path.display())
        });
        if expected != written {
            failures.push(format!("=== {rel}: expected ===\n{expected}=== actual ===\n{written}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
