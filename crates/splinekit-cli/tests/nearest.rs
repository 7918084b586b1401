//! `splinekit nearest` as users run it: the JSON shape, the text output, answers against
//! brute force over the curve's own points (from `splinekit curve`), and bad input.

use std::path::{Path, PathBuf};

use serde_json::Value;

mod common;
use common::splinekit;

/// A temporary SWP file.
fn swp(dir: &tempfile::TempDir, text: &str) -> PathBuf {
    let path = dir.path().join("curves.swp");
    std::fs::write(&path, text).expect("writing test file");
    path
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

/// The smallest distance from `q` to the points `splinekit curve --steps N` prints.
fn sampled_distance(path: &Path, curve: &str, q: [f64; 3]) -> f64 {
    let run = splinekit(&["curve", path.to_str().unwrap(), "--curve", curve, "--steps", "20000", "--format", "json"]);
    let json = run.json();
    let points = json["points"].as_array().expect("points");
    points
        .iter()
        .map(|p| {
            let p = [&p["x"], &p["y"], &p["z"]].map(|c| c.as_f64().expect("coordinate"));
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

const CURVES: &str = "\
bsp2 wave 10 7
[0 0] [1 3] [2 -2] [3 3] [4 -2] [5 3] [6 0]
cr3 knot 10 6 closed
[1 0 0] [0 1 1] [-1 0 0] [0 -1 -1] [0.5 0.5 2] [-0.5 0.2 -1]
helix spring 20 1 0.5 3
";

#[test]
fn json_has_the_documented_keys_and_agrees_with_the_curves_points() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, CURVES);
    let queries: [(&str, [f64; 3]); 5] = [
        ("wave", [2.5, 0.4, 0.0]),
        ("wave", [3.0, 10.0, 0.0]),
        ("wave", [-1.0, -1.0, 2.0]),
        ("knot", [0.1, -0.3, 0.2]),
        ("spring", [0.0, 0.0, 0.75]),
    ];
    for (curve, q) in queries {
        let [x, y, z] = q.map(|c| c.to_string());
        let run = splinekit(&[
            "nearest",
            path.to_str().unwrap(),
            "--curve",
            curve,
            "--point",
            &x,
            &y,
            &z,
            "--accuracy",
            "1e-10",
            "--json",
        ]);
        let json = run.json();
        // the keys, in this order
        let at = |key: &str| run.stdout.find(&format!("\"{key}\": ")).unwrap_or_else(|| panic!("no {key}"));
        assert!(at("curve") < at("u") && at("u") < at("point") && at("point") < at("distance"), "{}", run.stdout);
        assert_eq!(json.as_object().unwrap().len(), 4);
        assert_eq!(json["curve"], curve);
        let point = nums(&json["point"]);
        let distance = json["distance"].as_f64().unwrap();
        let own = ((point[0] - q[0]).powi(2) + (point[1] - q[1]).powi(2) + (point[2] - q[2]).powi(2)).sqrt();
        assert!((own - distance).abs() <= 1e-12, "{curve}: {own} vs {distance}");
        // the curve's own samples are never nearer (beyond the accuracy), and the densest of
        // them come within the sampling's sag of the answer
        let sampled = sampled_distance(&path, curve, q);
        assert!(distance <= sampled + 1e-10, "{curve} {q:?}: {distance} > sampled {sampled}");
        assert!(distance >= sampled - 1e-4, "{curve} {q:?}: {distance} far below sampled {sampled}");
        assert!(json["u"].as_f64().unwrap() >= 0.0);
    }
}

#[test]
fn text_names_the_curve_and_2d_points_take_z_as_zero() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, "bez2 arch 10 4\n[0 0] [0 1] [1 1] [1 0]\n");
    let run = splinekit(&["nearest", path.to_str().unwrap(), "--point", "0.5", "2"]);
    assert_eq!(run.ok(), "curve: arch (bez2, 1 segment)\nu: 0.5\npoint: 0.5 0.75 0\ndistance: 1.25\n");
    // a Z off the plane of a 2D curve counts in the distance
    let run = splinekit(&["nearest", path.to_str().unwrap(), "--point", "0.5", "2", "1", "--json"]);
    let d = run.json()["distance"].as_f64().unwrap();
    assert!((d - 1.25f64.hypot(1.0)).abs() < 1e-12, "{d}");
}

#[test]
fn bad_input_is_refused_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    let path = swp(&dir, CURVES);
    let file = path.to_str().unwrap();
    let run = splinekit(&["nearest", file, "--point", "1"]);
    assert_eq!(run.code, Some(2));
    assert!(run.stderr.contains("2 values required"), "{}", run.stderr);
    let run = splinekit(&["nearest", file, "--point", "1", "inf"]);
    assert!(run.fails().contains("must be a finite number"), "{}", run.stderr);
    let run = splinekit(&["nearest", file, "--point", "1", "2", "--accuracy", "0"]);
    assert!(run.fails().contains("must be greater than 0"), "{}", run.stderr);
    let run = splinekit(&["nearest", file, "--curve", "nope", "--point", "1", "2"]);
    assert!(run.fails_with_error().contains("no curve \"nope\""), "{}", run.stderr);
}
