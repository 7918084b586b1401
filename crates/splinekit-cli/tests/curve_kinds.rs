//! The curve kinds of any degree (`bezn2`, `bezn3`) and NURBS (`nurbs2`, `nurbs3`) through the
//! commands users run on them: `info`, `curve`, `arclen`, `nearest`, `sweep` and `render`,
//! checked against closed forms (the exact circle) and the curves' own dense samples.

use std::f64::consts::TAU;
use std::path::PathBuf;

mod common;
use common::splinekit;

const KINDS: &str = "\
bezn2 hump 20 5 [0 0] [1 2] [2 -1] [3 2] [4 0]
nurbs2 ring 8 9 degree 2 knots 0 0 0 1 1 2 2 3 3 4 4 4
[1 0 1] [1 1 0.7071067811865476] [0 1 1] [-1 1 0.7071067811865476] [-1 0 1]
[-1 -1 0.7071067811865476] [0 -1 1] [1 -1 0.7071067811865476] [1 0 1]
nurbs3 path 10 5 degree 3 knots [0 0 0 0 0.5 1 1 1 1]
[0 0 0 1] [1 0 1 2] [2 1 1 0.5] [3 1 2 1] [4 2 2 1]
gcyl tube ring path
";

fn swp(dir: &tempfile::TempDir, text: &str) -> PathBuf {
    let path = dir.path().join("kinds.swp");
    std::fs::write(&path, text).expect("writing test file");
    path
}

#[test]
fn info_names_kind_degree_and_segments() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, KINDS);
    let out = splinekit(&["info", path.to_str().unwrap()]).ok().to_owned();
    assert!(out.contains("hump  bezn2  5 points, degree 4, 1 segment, steps 20, open"), "{out}");
    assert!(out.contains("ring  nurbs2  9 points, degree 2, 4 segments, steps 8, open"), "{out}");
    assert!(out.contains("path  nurbs3  5 points, degree 3, 2 segments, steps 10, open"), "{out}");
    let json = splinekit(&["info", path.to_str().unwrap(), "--json"]).json();
    assert_eq!(json["curves"][1]["kind"], "nurbs2");
    assert_eq!(json["curves"][1]["segments"], 4);
}

#[test]
fn the_nurbs_circle_is_exact_in_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, KINDS);
    let file = path.to_str().unwrap();
    // every tessellated point on the unit circle, by steps and by tolerance
    for extra in [&["--steps", "50"][..], &["--tolerance", "1e-4"][..]] {
        let mut args = vec!["curve", file, "--curve", "ring", "--format", "json"];
        args.extend_from_slice(extra);
        let json = splinekit(&args).json();
        let points = json["points"].as_array().unwrap();
        assert!(points.len() > 16, "{extra:?}: {}", points.len());
        for p in points {
            let r = p["x"].as_f64().unwrap().hypot(p["y"].as_f64().unwrap());
            assert!((r - 1.0).abs() < 1e-14, "{extra:?}: radius {r}");
        }
    }
    // its length is 2π to the accuracy asked
    let json =
        splinekit(&["arclen", file, "--curve", "ring", "--method", "adaptive", "--accuracy", "1e-10", "--json"]).json();
    let length = json["length"].as_f64().unwrap();
    assert!((length - TAU).abs() <= 1e-10, "{length}");
    // the nearest point to (2, 2) is at 45°, at distance 2√2 − 1
    let json = splinekit(&["nearest", file, "--curve", "ring", "--point", "2", "2", "--json"]).json();
    let d = json["distance"].as_f64().unwrap();
    assert!((d - (8f64.sqrt() - 1.0)).abs() < 1e-9, "{d}");
}

#[test]
fn nearest_on_a_bezier_of_degree_4_beats_its_dense_samples() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, KINDS);
    let file = path.to_str().unwrap();
    let q = (2.2, 0.9);
    let json = splinekit(&["curve", file, "--curve", "hump", "--steps", "20000", "--format", "json"]).json();
    let sampled = json["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p["x"].as_f64().unwrap() - q.0).hypot(p["y"].as_f64().unwrap() - q.1))
        .fold(f64::INFINITY, f64::min);
    let json = splinekit(&[
        "nearest",
        file,
        "--curve",
        "hump",
        "--point",
        &q.0.to_string(),
        &q.1.to_string(),
        "--accuracy",
        "1e-10",
        "--json",
    ])
    .json();
    let d = json["distance"].as_f64().unwrap();
    assert!(d <= sampled + 1e-10 && d >= sampled - 1e-6, "{d} vs sampled {sampled}");
}

#[test]
fn sweeps_and_pictures_of_the_new_kinds() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, KINDS);
    let file = path.to_str().unwrap();
    let out = dir.path().join("out");
    splinekit(&["sweep", file, "-o", out.to_str().unwrap()]).ok();
    let obj = std::fs::read_to_string(out.join("tube.obj")).unwrap();
    assert!(obj.lines().filter(|l| l.starts_with("f ")).count() > 100);
    let png = dir.path().join("kinds.png");
    splinekit(&["render", file, "-o", png.to_str().unwrap(), "--size", "64x48"]).ok();
    assert!(std::fs::metadata(&png).unwrap().len() > 100);
}

#[test]
fn a_bad_weight_or_knot_is_an_error_at_its_place() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, "nurbs2 c 10 3 degree 2\n[0 0 1] [1 1 0] [2 0 1]\n");
    let message = splinekit(&["curve", path.to_str().unwrap()]).fails().to_owned();
    assert!(message.contains("kinds.swp:2:14: found \"0\", expected a number > 0 (the weight of point 2"), "{message}");
    let path = swp(&dir, "nurbs2 c 10 3 degree 2 knots 0 0 1 0.5 1 1\n[0 0 1] [1 1 1] [2 0 1]\n");
    let message = splinekit(&["info", path.to_str().unwrap()]).fails().to_owned();
    assert!(message.contains("kinds.swp:1:36: found \"0.5\", expected a knot ≥ 1"), "{message}");
}
