//! Integration tests of the `splinekit` binary: run it on small SWP files in a temporary
//! directory and check its output, exit status and messages.

use std::ffi::OsStr;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use serde_json::Value;

mod common;
use common::{Run, splinekit, swp_dir};

// ---------------------------------------------------------------------------------------
// Harness

/// Runs `splinekit` with `file` as the argument after the subcommand.
fn on(command: &str, file: &Path, rest: &[&str]) -> Run {
    let mut args: Vec<&OsStr> = vec![command.as_ref(), file.as_os_str()];
    args.extend(rest.iter().map(OsStr::new));
    splinekit(&args)
}

#[track_caller]
fn assert_close(a: f64, b: f64, eps: f64, what: &str) {
    assert!((a - b).abs() <= eps, "{what}: {a} vs {b}, diff {} > {eps}", (a - b).abs());
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A temporary directory holding SWP files.
struct Dir(tempfile::TempDir);

impl Dir {
    fn new() -> Self {
        Self(tempfile::tempdir().expect("temp dir"))
    }
    fn file(&self, name: &str, text: &str) -> PathBuf {
        let path = self.0.path().join(name);
        std::fs::write(&path, text).expect("writing test file");
        path
    }
}

// ---------------------------------------------------------------------------------------
// The reference scene of SPEC §1.4

/// Chord table `s` column of SPEC §1.4 (u = 0.0, 0.2, …, 5.0).
const REFERENCE_CHORD_S: [f64; 26] = [
    0.00000, 0.13984, 0.35788, 0.59640, 0.77689, 0.82383, 0.99348, 1.31196, 1.68453, 2.01578, 2.21177, 2.28435,
    2.43888, 2.63035, 2.78487, 2.85746, 3.05345, 3.38470, 3.75727, 4.07574, 4.24539, 4.29233, 4.47283, 4.71135,
    4.92939, 5.06923,
];
/// Agreement "to 5 decimals": half a unit in the 5th decimal, plus rounding slack.
const DEC5: f64 = 5e-6 + 1e-12;

/// The 8 control points: αᵢ = i/7, θ = 2παᵢ, r = cos 2θ, Pᵢ = (r cos θ, r sin θ, −0.5 + αᵢ).
fn scene_points() -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| {
            let a = i as f64 / 7.0;
            let theta = std::f64::consts::TAU * a;
            let r = (2.0 * theta).cos();
            [r * theta.cos(), r * theta.sin(), -0.5 + a]
        })
        .collect()
}

/// The scene as a `cr3` curve named `scene`, followed by an anonymous circle of radius 1.
fn scene_swp() -> String {
    let mut text = String::from("# SPEC 1.4 reference scene\ncr3 scene 20 8\n");
    for [x, y, z] in scene_points() {
        text.push_str(&format!("[{x} {y} {z}]\n"));
    }
    text.push_str("circ . 30 1\n");
    text
}

fn scene() -> (Dir, PathBuf) {
    let dir = Dir::new();
    let path = dir.file("scene.swp", &scene_swp());
    (dir, path)
}

// ---------------------------------------------------------------------------------------
// arclen

#[test]
fn arclen_chord_table_matches_reference() {
    let (_dir, path) = scene();
    let json = on("arclen", &path, &["--json"]).json();
    assert_eq!(json["curve"], "scene");
    assert_eq!(json["method"], "chord");
    assert_eq!(json["samples_per_segment"], 5);
    let table = json["table"].as_array().unwrap();
    assert_eq!(table.len(), 26);
    for (i, row) in table.iter().enumerate() {
        assert_close(num(&row["u"]), i as f64 / 5.0, 1e-15, &format!("u of row {i}"));
        assert_close(num(&row["s"]), REFERENCE_CHORD_S[i], DEC5, &format!("s of row {i}"));
    }
    assert_eq!(num(&json["length"]), num(&table[25]["s"]), "length is the last row's s");
    assert_close(num(&json["length"]), 5.06923, DEC5, "chord length");
}

#[test]
fn arclen_gauss3_length() {
    let (_dir, path) = scene();
    let json = on("arclen", &path, &["--method", "gauss3", "--json"]).json();
    assert_eq!(json["method"], "gauss3");
    let table = json["table"].as_array().unwrap();
    assert_eq!(table.len(), 26);
    assert_eq!(num(&json["length"]), num(&table[25]["s"]));
    assert_close(num(&json["length"]), 5.14943, DEC5, "gauss3 length");
}

#[test]
fn arclen_adaptive_length() {
    let (_dir, path) = scene();
    let json = on("arclen", &path, &["--method", "adaptive", "--json"]).json();
    assert_eq!(json["method"], "adaptive");
    assert_eq!(json["table"], Value::Array(vec![]));
    assert_close(num(&json["length"]), 5.147598456, 1e-9, "adaptive length");
    // a looser accuracy still holds its bound
    let json = on("arclen", &path, &["--method", "adaptive", "--accuracy", "1e-4", "--json"]).json();
    assert_close(num(&json["length"]), 5.147598456, 1e-4, "adaptive length to 1e-4");
}

#[test]
fn arclen_at_s() {
    let (_dir, path) = scene();
    let json = on("arclen", &path, &["--at-s", "0.417", "--json"]).json();
    let at = json["at_s"].as_array().unwrap();
    assert_eq!(at.len(), 1);
    assert_eq!(num(&at[0]["s"]), 0.417);
    assert_close(num(&at[0]["u"]), 0.4496, 5e-5, "u(0.417) from the chord table");

    // repeatable, in the given order; clamped to [0, length]
    let json = on("arclen", &path, &["--at-s", "0", "--at-s", "100", "--at-s=-1", "--at-s", "0.417", "--json"]).json();
    let u: Vec<f64> = json["at_s"].as_array().unwrap().iter().map(|r| num(&r["u"])).collect();
    assert_eq!(u.len(), 4);
    assert_eq!((u[0], u[1], u[2]), (0.0, 5.0, 0.0));
    assert_close(u[3], 0.4496, 5e-5, "u(0.417)");

    // adaptive: the exact inverse differs from the table's, and is the curve's true u(s)
    let json = on("arclen", &path, &["--method", "adaptive", "--at-s", "0.417", "--json"]).json();
    let u = num(&json["at_s"][0]["u"]);
    assert!(u > 0.4 && u < 0.5 && (u - 0.4496).abs() > 1e-3, "exact u(0.417) = {u}");
}

#[test]
fn arclen_spacing_point_count() {
    let (_dir, path) = scene();
    for method in ["chord", "gauss3", "adaptive"] {
        let json = on("arclen", &path, &["--method", method, "--spacing", "0.5", "--json"]).json();
        let length = num(&json["length"]);
        let points = json["points"].as_array().unwrap();
        assert_eq!(points.len(), (length / 0.5).floor() as usize + 1, "{method}: length {length}");
        // the first point is the curve's start: P1 of the Catmull-Rom control points
        let first: Vec<f64> = points[0].as_array().unwrap().iter().map(num).collect();
        let p1 = scene_points()[1];
        for c in 0..3 {
            assert_close(first[c], p1[c], 1e-12, &format!("{method}: start coordinate {c}"));
        }
        assert!(points.iter().all(|p| p.as_array().unwrap().len() == 3));
    }
}

#[test]
fn arclen_json_keys_in_order() {
    let (_dir, path) = scene();
    let cases: [(&[&str], &[&str]); 4] = [
        (&["--json"], &["curve", "method", "samples_per_segment", "table", "length"]),
        (&["--json", "--at-s", "1"], &["curve", "method", "samples_per_segment", "table", "length", "at_s"]),
        (&["--json", "--spacing", "1"], &["curve", "method", "samples_per_segment", "table", "length", "points"]),
        (
            &["--json", "--spacing", "1", "--at-s", "1", "--method", "adaptive"],
            &["curve", "method", "samples_per_segment", "table", "length", "at_s", "points"],
        ),
    ];
    for (args, keys) in cases {
        let run = on("arclen", &path, args);
        let json = run.json();
        let object = json.as_object().unwrap();
        let mut present: Vec<&str> = object.keys().map(String::as_str).collect();
        let mut expected = keys.to_vec();
        present.sort_unstable();
        expected.sort_unstable();
        assert_eq!(present, expected, "keys for {args:?}");
        // key order in the text
        let positions: Vec<usize> =
            keys.iter().map(|k| run.stdout.find(&format!("\"{k}\":")).unwrap_or_else(|| panic!("{k}"))).collect();
        assert!(positions.windows(2).all(|w| w[0] < w[1]), "key order for {args:?}:\n{}", run.stdout);
        // exactly one JSON object
        assert!(run.stdout.trim_start().starts_with('{') && run.stdout.trim_end().ends_with('}'));
    }
}

#[test]
fn arclen_human_output() {
    let (_dir, path) = scene();
    let text = on("arclen", &path, &[]).ok().to_string();
    let json = on("arclen", &path, &["--json"]).json();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].contains("scene"), "header names the curve:\n{text}");
    assert!(text.contains("chord") && text.contains("5 samples"), "header names method and samples:\n{text}");
    let header = lines.iter().position(|l| l.split_whitespace().collect::<Vec<_>>() == ["u", "s"]).unwrap();
    let rows: Vec<(f64, f64)> = lines[header + 1..header + 27]
        .iter()
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            (v[0], v[1])
        })
        .collect();
    for (i, (u, s)) in rows.iter().enumerate() {
        assert_close(*u, i as f64 / 5.0, 1e-6, "u column");
        assert_close(*s, REFERENCE_CHORD_S[i], DEC5 + 5e-7, "s column");
    }
    let length_line = lines.iter().find(|l| l.starts_with("length:")).expect("a length line");
    let length: f64 = length_line["length:".len()..].trim().parse().unwrap();
    assert_eq!(length, num(&json["length"]));

    let text = on("arclen", &path, &["--at-s", "0.417", "--spacing", "0.5"]).ok().to_string();
    assert!(text.contains("length: "), "{text}");
    assert!(text.contains("0.4495"), "the at-s answer:\n{text}");
    assert!(text.contains("(11)"), "11 resampled points:\n{text}");

    let text = on("arclen", &path, &["--method", "adaptive"]).ok().to_string();
    assert!(text.contains("adaptive") && text.contains("length: 5.1475984"), "{text}");
}

#[test]
fn arclen_curve_selection() {
    let (_dir, path) = scene();
    let default = on("arclen", &path, &["--json"]).ok().to_string();
    assert_eq!(on("arclen", &path, &["--json", "--curve", "scene"]).ok(), default);
    assert_eq!(on("arclen", &path, &["--json", "--curve", "0"]).ok(), default);

    for token in ["1", "#1"] {
        let json = on("arclen", &path, &["--json", "--curve", token, "--method", "adaptive"]).json();
        assert_eq!(json["curve"], "#1");
        assert_close(num(&json["length"]), std::f64::consts::TAU, 1e-9, "circle of radius 1");
    }
    let json = on("arclen", &path, &["--json", "--curve", "1"]).json();
    assert_eq!(json["table"].as_array().unwrap().len(), 6, "a circle is one segment");

    // a name wins over an index
    let dir = Dir::new();
    let path = dir.file("names.swp", "circ . 10 1\ncirc 0 10 2\n");
    let json = on("arclen", &path, &["--json", "--curve", "0", "--method", "adaptive"]).json();
    assert_eq!(json["curve"], "0");
    assert_close(num(&json["length"]), 2.0 * std::f64::consts::TAU, 1e-9, "the circle named 0");
    let json = on("arclen", &path, &["--json", "--curve", "#0", "--method", "adaptive"]).json();
    assert_eq!(json["curve"], "#0");
}

// ---------------------------------------------------------------------------------------
// curve

/// Parses `u,x,y,z,tx,…,bz` CSV into `u,x,y,z` rows, checking each frame is orthonormal.
fn csv_rows(text: &str) -> Vec<[f64; 4]> {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("u,x,y,z,tx,ty,tz,nx,ny,nz,bx,by,bz"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), 13, "{l}");
            let (t, n, b) = (
                glam::DVec3::new(v[4], v[5], v[6]),
                glam::DVec3::new(v[7], v[8], v[9]),
                glam::DVec3::new(v[10], v[11], v[12]),
            );
            assert!((t.cross(n) - b).length() < 1e-9 && (t.length() - 1.0).abs() < 1e-9, "{l}");
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

#[test]
fn curve_point_counts_on_bundled_files() {
    let data = swp_dir();
    let core = data.join("core.swp");
    for index in 0..4 {
        let rows = csv_rows(on("curve", &core, &["--curve", &index.to_string()]).ok());
        assert_eq!(rows.len(), 21, "core.swp curve {index}");
        for (j, row) in rows.iter().enumerate() {
            assert_eq!(row[0], j as f64 / 20.0);
        }
    }
    // bez2 #0 interpolates its end points [3 0] and [1 0]
    let rows = csv_rows(on("curve", &core, &[]).ok());
    assert_eq!(rows[0][1..], [3.0, 0.0, 0.0]);
    assert_eq!(rows[20][1..], [1.0, 0.0, 0.0]);
    assert!(on("curve", &core, &["--curve", "4"]).fails().contains("no curve"));

    let circles = data.join("circles.swp");
    for (index, count, radius) in [(0, 31, 1.0), (1, 51, 2.0)] {
        let rows = csv_rows(on("curve", &circles, &["--curve", &index.to_string()]).ok());
        assert_eq!(rows.len(), count, "circles.swp curve {index}");
        assert_eq!(rows[0][1..], [radius, 0.0, 0.0], "starts at angle 0");
        assert_eq!(rows[0][1..], rows[count - 1][1..], "the last point repeats the first");
        assert!(rows[1][2] > 0.0, "counter-clockwise");
        for row in &rows {
            assert_close(row[1].hypot(row[2]), radius, 1e-12, "on the circle");
        }
    }
}

#[test]
fn curve_steps_and_json() {
    let (_dir, path) = scene();
    // own steps: 5 segments · 20 + 1
    assert_eq!(csv_rows(on("curve", &path, &[]).ok()).len(), 101);
    let rows = csv_rows(on("curve", &path, &["--steps", "7"]).ok());
    assert_eq!(rows.len(), 36);
    for (j, row) in rows.iter().enumerate() {
        assert_eq!(row[0], j as f64 / 7.0, "u = (k·steps + i)/steps");
    }
    // a Catmull-Rom curve passes through P1..P6 at u = 0..5
    let p = scene_points();
    for k in 0..=5 {
        for c in 0..3 {
            assert_close(rows[7 * k][c + 1], p[k + 1][c], 1e-12, &format!("knot {k}"));
        }
    }

    let json = on("curve", &path, &["--steps", "7", "--format", "json"]).json();
    assert_eq!(json["curve"], "scene");
    assert_eq!(json["steps"], 7);
    let points = json["points"].as_array().unwrap();
    assert_eq!(points.len(), 36);
    for (row, point) in rows.iter().zip(points) {
        let mut keys: Vec<&str> = point.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(keys, ["b", "n", "t", "u", "x", "y", "z"]);
        for (i, key) in ["u", "x", "y", "z"].iter().enumerate() {
            assert_eq!(num(&point[key]), row[i], "CSV and JSON agree exactly");
        }
    }
    let json = on("curve", &path, &["--curve", "1", "--format", "json"]).json();
    assert_eq!(json["curve"], "#1");
    assert_eq!(json["points"].as_array().unwrap().len(), 31);
}

/// A 2D chain of two cubics and a 3D cubic, as control points (z = 0 for the 2D one).
const WAVE: [[f64; 3]; 7] = [
    [0.0, 0.0, 0.0],
    [1.0, 2.0, 0.0],
    [3.0, 2.0, 0.0],
    [4.0, 0.0, 0.0],
    [5.0, -2.0, 0.0],
    [7.0, -3.0, 0.0],
    [8.0, 1.0, 0.0],
];
const PATH: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 0.0, 1.0], [3.0, 1.0, 0.0]];

/// [`WAVE`] as `bez2 wave` (10 steps), a circle `ring` of radius 2 (24 steps) and [`PATH`] as
/// `bez3 path` (4 steps).
fn shapes_swp(dir: &Dir) -> PathBuf {
    let points = |p: &[[f64; 3]], dim: usize| {
        let point = |q: &[f64; 3]| format!("[{}]", q[..dim].iter().map(f64::to_string).collect::<Vec<_>>().join(" "));
        p.iter().map(point).collect::<Vec<_>>().join(" ")
    };
    let text = format!("bez2 wave 10 7 {}\ncirc ring 24 2\nbez3 path 4 4 {}\n", points(&WAVE, 2), points(&PATH, 3));
    dir.file("shapes.swp", &text)
}

/// The value of the first attribute `name` in `svg`.
fn svg_attr<'a>(svg: &'a str, name: &str) -> &'a str {
    let start = svg.find(&format!("{name}=\"")).unwrap_or_else(|| panic!("no {name} in:\n{svg}")) + name.len() + 2;
    &svg[start..start + svg[start..].find('"').unwrap()]
}

/// The SVG's `viewBox` numbers and its polyline's points, y flipped back up.
fn svg_polyline(svg: &str) -> ([f64; 4], Vec<[f64; 2]>) {
    let view: Vec<f64> = svg_attr(svg, "viewBox").split(' ').map(|x| x.parse().unwrap()).collect();
    let points = svg_attr(svg, "points")
        .split(' ')
        .map(|pair| {
            let (x, y) = pair.split_once(',').unwrap_or_else(|| panic!("bad point {pair:?}"));
            [x.parse().unwrap(), -y.parse::<f64>().unwrap()]
        })
        .collect();
    (view.try_into().unwrap(), points)
}

#[test]
fn curve_svg_draws_the_polyline() {
    let dir = Dir::new();
    let path = shapes_swp(&dir);
    for (curve, flags) in
        [("wave", &["--tolerance", "0.01"][..]), ("wave", &[][..]), ("ring", &["--tolerance", "0.001"][..])]
    {
        let args = |format: &'static str| [&["--curve", curve, "--format", format][..], flags].concat();
        let run = on("curve", &path, &args("svg"));
        let svg = run.ok();
        assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\"") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains(&format!("<title>{curve}</title>")), "{svg}");
        assert_eq!(on("curve", &path, &args("svg")).stdout, svg, "deterministic");
        // the same points as the JSON output, in order, to the bit
        let json = on("curve", &path, &args("json")).json();
        let expected: Vec<[f64; 2]> =
            json["points"].as_array().unwrap().iter().map(|p| [num(&p["x"]), num(&p["y"])]).collect();
        let (view, points) = svg_polyline(svg);
        assert_eq!(points, expected, "{curve} {flags:?}");
        // every point inside the view box (y down there), with a margin
        let [x0, y0, w, h] = view;
        assert!(w > 0.0 && h > 0.0);
        for [x, y] in &points {
            assert!(*x > x0 && *x < x0 + w && -*y > y0 && -*y < y0 + h, "({x}, {y}) outside {view:?}");
        }
        let height: f64 = svg_attr(svg, "height").parse().unwrap();
        assert_eq!(height, (800.0 * h / w).round(), "the picture keeps the curve's aspect");
        // zeros are written unsigned
        assert!(!svg.split([' ', ',', '"']).any(|token| token == "-0"), "{svg}");
        if curve == "ring" {
            // closed form: the circle of radius 2, from (2, 0) round to it again
            assert_eq!((points[0], *points.last().unwrap()), ([2.0, 0.0], [2.0, 0.0]));
            for [x, y] in &points {
                assert_close(x.hypot(*y), 2.0, 1e-12, "ring radius");
            }
        } else {
            assert_eq!((points[0], *points.last().unwrap()), ([0.0, 0.0], [8.0, 1.0]), "the curve's ends");
        }
    }
    // without --tolerance, the file's steps: 2 segments of 10
    assert_eq!(svg_polyline(on("curve", &path, &["--format", "svg"]).ok()).1.len(), 21);
    // a 3D curve cannot be drawn
    let stderr = on("curve", &path, &["--curve", "path", "--format", "svg"]).fails_with_error().to_string();
    assert!(stderr.contains("--format svg draws 2D curves; curve path is 3D"), "{stderr}");
}

/// A cubic Bézier and its derivatives, by de Casteljau (independent of the library).
fn bezier(p: &[[f64; 3]], t: f64) -> [[f64; 3]; 3] {
    let lerp = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i]));
    let diff = |a: [f64; 3], b: [f64; 3], k: f64| [0, 1, 2].map(|i| k * (b[i] - a[i]));
    let (a, b, c) = (lerp(p[0], p[1]), lerp(p[1], p[2]), lerp(p[2], p[3]));
    let (d, e) = (lerp(a, b), lerp(b, c));
    let dd = lerp(diff(p[0], p[1], 6.0), diff(p[1], p[2], 6.0));
    let dd2 = lerp(diff(p[1], p[2], 6.0), diff(p[2], p[3], 6.0));
    [lerp(d, e), diff(d, e, 3.0), [0, 1, 2].map(|i| dd[i] + t * (dd2[i] - dd[i]))]
}

/// Position, first and second derivative of a chain of cubics (`3m + 1` points) at `u ∈ [0, m]`.
fn chain(p: &[[f64; 3]], u: f64) -> [[f64; 3]; 3] {
    let k = (u.floor() as usize).min((p.len() - 1) / 3 - 1);
    bezier(&p[3 * k..3 * k + 4], u - k as f64)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Distance from `x` to the segment `[a, b]`.
fn segment_distance(x: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let (e, d) = ([0, 1, 2].map(|i| b[i] - a[i]), [0, 1, 2].map(|i| x[i] - a[i]));
    let s = if dot(e, e) > 0.0 { (dot(d, e) / dot(e, e)).clamp(0.0, 1.0) } else { 0.0 };
    let r = [0, 1, 2].map(|i| d[i] - s * e[i]);
    dot(r, r).sqrt()
}

/// `(u, position, [t, n, b])` of every point of `curve`'s JSON output.
fn frame_rows(json: &Value) -> Vec<(f64, [f64; 3], [[f64; 3]; 3])> {
    let v3 = |v: &Value| [0, 1, 2].map(|i| num(&v[i]));
    json["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (num(&p["u"]), [num(&p["x"]), num(&p["y"]), num(&p["z"])], [v3(&p["t"]), v3(&p["n"]), v3(&p["b"])]))
        .collect()
}

/// The angle-mode split of SPEC §1.3, written out plainly: local end parameters of the pieces
/// of `p` over `[t0, t1]`, halving while a control-polygon angle exceeds `half`, depth ≤ 10.
fn angle_split(p: [[f64; 3]; 4], t0: f64, t1: f64, half: f64, depth: u32, out: &mut Vec<f64>) {
    let edge = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|i| b[i] - a[i]);
    let angle = |a: [f64; 3], b: [f64; 3]| {
        let c = cross(a, b);
        dot(c, c).sqrt().atan2(dot(a, b))
    };
    let (d0, d1, d2) = (edge(p[0], p[1]), edge(p[1], p[2]), edge(p[2], p[3]));
    if depth < 10 && (angle(d0, d1) > half || angle(d1, d2) > half) {
        let mid = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|i| 0.5 * (a[i] + b[i]));
        let (a, b, c) = (mid(p[0], p[1]), mid(p[1], p[2]), mid(p[2], p[3]));
        let (d, e) = (mid(a, b), mid(b, c));
        let m = mid(d, e);
        let tm = 0.5 * (t0 + t1);
        angle_split([p[0], a, d, m], t0, tm, half, depth + 1, out);
        angle_split([m, e, c, p[3]], tm, t1, half, depth + 1, out);
    } else {
        out.push(t1);
    }
}

#[test]
fn curve_tolerance_angle_and_frames() {
    let (wave, path) = (WAVE, PATH);
    let dir = Dir::new();
    let file = shapes_swp(&dir);
    let json = |args: &[&str]| on("curve", &file, &[args, &["--format", "json"]].concat()).json();

    // --tolerance: vertices on the curve, every piece of the curve within T of its chord, and
    // every chord within T of its piece of the curve (two-sided), the count growing as T falls
    let mut previous = 0;
    for tolerance in ["0.1", "0.01", "0.001"] {
        let t: f64 = tolerance.parse().unwrap();
        let out = json(&["--curve", "wave", "--tolerance", tolerance]);
        assert_eq!(out["steps"], Value::Null);
        let rows = frame_rows(&out);
        assert!(rows.len() > previous, "{tolerance}: {} points", rows.len());
        previous = rows.len();
        assert_eq!((rows[0].0, rows.last().unwrap().0), (0.0, 2.0));
        for pair in rows.windows(2) {
            let ((ua, a, _), (ub, b, _)) = (pair[0], pair[1]);
            assert!(ub > ua);
            for (u, x) in [(ua, a), (ub, b)] {
                let p = chain(&wave, u)[0];
                assert!((0..3).all(|i| (p[i] - x[i]).abs() < 1e-12), "vertex at u {u}: {x:?} vs {p:?}");
            }
            let piece: Vec<[f64; 3]> = (0..=400).map(|i| chain(&wave, ua + (ub - ua) * i as f64 / 400.0)[0]).collect();
            let far = piece.iter().map(|&x| segment_distance(x, a, b)).fold(0.0, f64::max);
            assert!(far <= t * (1.0 + 1e-9), "{tolerance}: curve {far} from the chord over [{ua}, {ub}]");
            // chord → curve, against the sampled piece (its samples are < 1e-3 T apart)
            let back = (0..=100)
                .map(|i| {
                    let s = i as f64 / 100.0;
                    let x = [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k]));
                    piece.windows(2).map(|w| segment_distance(x, w[0], w[1])).fold(f64::INFINITY, f64::min)
                })
                .fold(0.0, f64::max);
            assert!(back <= t * (1.0 + 1e-3), "{tolerance}: chord {back} from the curve over [{ua}, {ub}]");
        }
    }

    // --angle-tolerance (degrees): the parameters of the split written out above
    for degrees in [20.0f64, 5.0, 0.5] {
        let rows = frame_rows(&json(&["--curve", "wave", "--angle-tolerance", &degrees.to_string()]));
        let mut expected = vec![0.0];
        for k in 0..2 {
            let mut local = Vec::new();
            let segment = [wave[3 * k], wave[3 * k + 1], wave[3 * k + 2], wave[3 * k + 3]];
            angle_split(segment, 0.0, 1.0, degrees.to_radians() / 2.0, 0, &mut local);
            expected.extend(local.iter().map(|t| k as f64 + t));
        }
        let got: Vec<f64> = rows.iter().map(|r| r.0).collect();
        assert_eq!(got, expected, "{degrees}°");
    }

    // frames: orthonormal and right-handed everywhere, T along the derivative; sequential
    // frames of a 2D curve have B = +z and N left of travel; Frenet's N turns towards C″ with
    // B along C′ × C″; rotation-minimizing frames do not spin about T
    for (curve, points) in [("wave", &wave[..]), ("path", &path[..])] {
        for method in ["sequential", "rmf", "frenet"] {
            let rows = frame_rows(&json(&["--curve", curve, "--frames", method, "--steps", "200"]));
            for &(u, _, [t, n, b]) in &rows {
                let what = format!("{curve} {method} u {u}");
                for (x, y, expected) in [(t, t, 1.0), (n, n, 1.0), (b, b, 1.0), (t, n, 0.0), (t, b, 0.0), (n, b, 0.0)] {
                    assert_close(dot(x, y), expected, 1e-9, &what);
                }
                assert!((0..3).all(|i| (cross(t, n)[i] - b[i]).abs() < 1e-9), "{what}: T × N ≠ B");
                let [_, d1, d2] = chain(points, u);
                assert_close(dot(t, d1), dot(d1, d1).sqrt(), 1e-9 * dot(d1, d1).sqrt(), &format!("{what}: T"));
                if method == "sequential" && curve == "wave" {
                    assert!(b[0] == 0.0 && b[1] == 0.0 && (b[2] - 1.0).abs() < 1e-12, "{what}: B = {b:?}");
                    assert!((n[0] + t[1]).abs() < 1e-12 && (n[1] - t[0]).abs() < 1e-12, "{what}: N = left of T");
                }
                if method == "frenet" {
                    let k = cross(d1, d2);
                    let kn = dot(k, k).sqrt();
                    if kn > 1e-6 {
                        assert!(dot(n, d2) > 0.0, "{what}: N turns away from C″");
                        assert_close(dot(b, k), kn, 1e-9 * kn, &format!("{what}: B along C′ × C″"));
                    }
                }
            }
            if method == "rmf" {
                // the spin about T between neighbours, (N₁·B₀ − B₁·N₀)/2, is O(h³) for a
                // rotation-minimizing frame; Frenet's spins with the torsion
                let spin = rows
                    .windows(2)
                    .map(|w| (dot(w[1].2[1], w[0].2[2]) - dot(w[1].2[2], w[0].2[1])).abs() / 2.0)
                    .fold(0.0, f64::max);
                assert!(spin < 1e-5, "{curve}: rmf spins by {spin} a step");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Errors

#[test]
fn error_missing_file() {
    let dir = Dir::new();
    let missing = dir.0.path().join("missing.swp");
    for command in ["arclen", "curve"] {
        let stderr = on(command, &missing, &[]).fails().to_string();
        assert!(stderr.contains("missing.swp"), "{stderr}");
        assert!(stderr.starts_with("error: "), "{stderr}");
    }
}

#[test]
fn error_malformed_swp_names_line_and_column() {
    let dir = Dir::new();
    let path = dir.file("bad.swp", "bsp2 . 20 4\n[0 0] [1 x]\n[2 0] [3 0]\n");
    for command in ["arclen", "curve"] {
        let run = on(command, &path, &[]);
        let stderr = run.fails();
        assert!(stderr.contains("bad.swp:2:10:"), "{stderr}");
        assert_eq!(run.code, Some(1));
    }
}

#[test]
fn error_unknown_curve_lists_the_curves() {
    let (_dir, path) = scene();
    for token in ["nope", "2", "#5", "-1"] {
        for command in ["arclen", "curve"] {
            let stderr = on(command, &path, &["--curve", token]).fails().to_string();
            assert!(stderr.contains(&format!("{token:?}")), "{stderr}");
            assert!(stderr.contains("0: scene (cr3)") && stderr.contains("1: #1 (circ)"), "{stderr}");
        }
    }
    let dir = Dir::new();
    let empty = dir.file("empty.swp", "# nothing here\n");
    assert!(on("arclen", &empty, &[]).fails().contains("no curves"));
}

#[test]
fn error_bad_flag_values() {
    let (_dir, path) = scene();
    let cases: [(&str, &[&str], &str); 16] = [
        ("arclen", &["--samples", "0"], "--samples"),
        ("arclen", &["--samples", "-3"], "--samples"),
        ("arclen", &["--samples", "x"], "--samples"),
        ("arclen", &["--accuracy", "0"], "--accuracy"),
        ("arclen", &["--accuracy", "-1e-9"], "--accuracy"),
        ("arclen", &["--accuracy", "nan"], "--accuracy"),
        ("arclen", &["--accuracy", "inf"], "--accuracy"),
        ("arclen", &["--spacing", "0"], "--spacing"),
        ("arclen", &["--spacing", "-0.5"], "--spacing"),
        ("arclen", &["--at-s", "nan"], "--at-s"),
        ("arclen", &["--method", "simpson"], "--method"),
        ("curve", &["--steps", "0"], "--steps"),
        ("curve", &["--format", "xml"], "--format"),
        ("curve", &["--tolerance", "-0.1"], "--tolerance must be a positive number"),
        ("curve", &["--tolerance", "0"], "--tolerance must be a positive number"),
        ("curve", &["--angle-tolerance", "-5"], "--angle-tolerance must be a positive number"),
    ];
    for (command, args, flag) in cases {
        let stderr = on(command, &path, args).fails().to_string();
        assert!(stderr.contains(flag), "{command} {args:?}: {stderr}");
    }
    // absurd point counts are refused, before any output
    let stderr = on("arclen", &path, &["--spacing", "1e-9"]).fails().to_string();
    assert!(stderr.contains("10000000"), "{stderr}");
    let stderr = on("arclen", &path, &["--samples", "4000000"]).fails().to_string();
    assert!(stderr.contains("10000000"), "{stderr}");
}

// ---------------------------------------------------------------------------------------
// Help, determinism, pipes

#[test]
fn help_describes_commands_and_flags() {
    let top = splinekit(&["--help"]).ok().to_string();
    for word in ["arclen", "curve", "SWP", "Examples"] {
        assert!(top.contains(word), "top-level help lacks {word}:\n{top}");
    }
    let arclen = splinekit(&["arclen", "--help"]).ok().to_string();
    for flag in ["--curve", "--samples", "--method", "--accuracy", "--at-s", "--spacing", "--json", "chord", "gauss3"] {
        assert!(arclen.contains(flag), "arclen help lacks {flag}:\n{arclen}");
    }
    assert!(arclen.contains("Examples") && arclen.contains("splinekit arclen "), "{arclen}");
    let curve = splinekit(&["curve", "--help"]).ok().to_string();
    for flag in ["--curve", "--steps", "--format", "csv", "json"] {
        assert!(curve.contains(flag), "curve help lacks {flag}:\n{curve}");
    }
    assert!(curve.contains("Examples") && curve.contains("splinekit curve "), "{curve}");
    assert!(splinekit(&["help", "arclen"]).ok().contains("--spacing"));
}

#[test]
fn output_is_deterministic() {
    let (_dir, path) = scene();
    let runs: [(&str, &[&str]); 5] = [
        ("arclen", &["--json", "--at-s", "0.417", "--spacing", "0.25"]),
        ("arclen", &["--method", "adaptive", "--json", "--at-s", "0.417", "--spacing", "0.25"]),
        ("arclen", &["--method", "gauss3", "--at-s", "1", "--spacing", "0.3"]),
        ("curve", &["--steps", "13"]),
        ("curve", &["--format", "json", "--curve", "1"]),
    ];
    for (command, args) in runs {
        let first = on(command, &path, args).ok().to_string();
        let second = on(command, &path, args).ok().to_string();
        assert!(first == second, "{command} {args:?} differs between runs");
    }
}

#[test]
fn closed_output_pipe_is_success() {
    let (_dir, path) = scene();
    let mut child = Command::new(env!("CARGO_BIN_EXE_splinekit"))
        .arg("curve")
        .arg(&path)
        .args(["--steps", "1000000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let mut head = [0u8; 64];
    child.stdout.as_mut().unwrap().read_exact(&mut head).unwrap();
    assert!(head.starts_with(b"u,x,y,z,tx,ty,tz,nx,ny,nz,bx,by,bz\n"));
    drop(child.stdout.take());
    let mut stderr = String::new();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    let status = child.wait().unwrap();
    assert!(status.success(), "exit {status:?}, stderr: {stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}

// ---------------------------------------------------------------------------------------
// Kochanek–Bartels and Bessel–Overhauser curves (issue #41)

/// The keys of the `tcb3` curve of [`interpolating_swp`]: (x, y, z, tension, continuity, bias).
const TCB_KEYS: [[f64; 6]; 6] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 0.5, 0.2, 0.5, 0.0, 0.0],
    [2.0, -0.5, 0.4, -0.3, 0.4, 0.0],
    [3.0, 1.0, 0.8, 0.0, -0.2, 0.6],
    [4.0, 0.0, 1.0, 0.2, 0.0, -0.5],
    [5.0, 0.5, 1.5, 0.0, 0.0, 0.0],
];

/// Eight keys on the unit circle, for the closed `bo2` curve.
fn ring_keys() -> Vec<[f64; 2]> {
    (0..8).map(|i| f64::from(i) * std::f64::consts::TAU / 8.0).map(|a| [a.cos(), a.sin()]).collect()
}

/// A `tcb3` curve `keys` (10 steps), a closed `bo2` curve `ring` (6 steps) and, for
/// comparison, `zero` (`tcb3` with every shape 0) and `cr` (`cr3`) on the same points.
fn interpolating_swp(dir: &Dir) -> PathBuf {
    let mut text = String::from("tcb3 keys 10 6\n");
    for k in TCB_KEYS {
        text.push_str(&format!("[{} {} {} {} {} {}]\n", k[0], k[1], k[2], k[3], k[4], k[5]));
    }
    text.push_str("bo2 ring 6 8 closed\n");
    for [x, y] in ring_keys() {
        text.push_str(&format!("[{x} {y}]\n"));
    }
    text.push_str("tcb3 zero 10 6\n");
    for k in TCB_KEYS {
        text.push_str(&format!("[{} {} {} 0 0 0]\n", k[0], k[1], k[2]));
    }
    text.push_str("cr3 cr 10 6\n");
    for k in TCB_KEYS {
        text.push_str(&format!("[{} {} {}]\n", k[0], k[1], k[2]));
    }
    dir.file("interpolating.swp", &text)
}

/// The length of a polyline through the rows' points.
fn polyline_length(rows: &[[f64; 4]]) -> f64 {
    rows.windows(2).map(|w| (1..4).map(|c| (w[1][c] - w[0][c]).powi(2)).sum::<f64>().sqrt()).sum()
}

#[test]
fn curve_tessellates_tcb_and_bo_through_their_keys() {
    let dir = Dir::new();
    let path = interpolating_swp(&dir);
    // tcb3, open: 6 keys, 3 segments from key 1 to key 4, 10 steps each
    let rows = csv_rows(on("curve", &path, &["--curve", "keys"]).ok());
    assert_eq!(rows.len(), 3 * 10 + 1);
    for k in 0..=3 {
        let key = TCB_KEYS[k + 1];
        assert_eq!(rows[10 * k][0], k as f64);
        for c in 0..3 {
            assert_close(rows[10 * k][c + 1], key[c], 1e-12, &format!("key {}", k + 1));
        }
    }
    // bo2, closed: 8 segments of 6 steps, from key 1 around to key 1
    let json = on("curve", &path, &["--curve", "ring", "--format", "json"]).json();
    assert_eq!(json["curve"], "ring");
    let points = json["points"].as_array().unwrap();
    assert_eq!(points.len(), 8 * 6 + 1);
    let keys = ring_keys();
    for k in 0..=8 {
        let [x, y] = keys[(k + 1) % 8];
        let p = &points[6 * k];
        assert_close(num(&p["x"]), x, 1e-12, &format!("ring key {k}"));
        assert_close(num(&p["y"]), y, 1e-12, &format!("ring key {k}"));
        assert_eq!(num(&p["z"]), 0.0);
    }
    // tension, continuity and bias 0 is the Catmull-Rom curve
    let zero = csv_rows(on("curve", &path, &["--curve", "zero", "--steps", "7"]).ok());
    let cr = csv_rows(on("curve", &path, &["--curve", "cr", "--steps", "7"]).ok());
    assert_eq!(zero.len(), cr.len());
    for (a, b) in zero.iter().zip(&cr) {
        for c in 0..4 {
            assert_close(a[c], b[c], 1e-15, "zero tcb against cr");
        }
    }
}

#[test]
fn arclen_measures_tcb_and_bo() {
    let dir = Dir::new();
    let path = interpolating_swp(&dir);
    for (curve, segments) in [("keys", 3), ("ring", 8)] {
        // the adaptive length against a fine polyline of the curve (which is shorter, by at
        // most about L·(h·κ)²/24 for steps h: far below 1e-6 here)
        let json = on("arclen", &path, &["--curve", curve, "--method", "adaptive", "--json"]).json();
        let length = num(&json["length"]);
        let fine = polyline_length(&csv_rows(on("curve", &path, &["--curve", curve, "--steps", "4000"]).ok()));
        assert!(fine <= length + 1e-9, "{curve}: polyline {fine} longer than {length}");
        assert_close(length, fine, 1e-6, curve);
        // the chord table: 5 rows per segment, its length that of the polyline of 5 steps
        let json = on("arclen", &path, &["--curve", curve, "--json"]).json();
        let table = json["table"].as_array().unwrap();
        assert_eq!(table.len(), 5 * segments + 1, "{curve}");
        assert_close(num(&table[5 * segments]["u"]), segments as f64, 1e-15, curve);
        let chords = polyline_length(&csv_rows(on("curve", &path, &["--curve", curve, "--steps", "5"]).ok()));
        assert_close(num(&json["length"]), chords, 1e-12, curve);
        assert!(chords < length, "{curve}");
    }
    // the ring of 8 keys on the unit circle is within 1% of the circle (0.43% short)
    let json = on("arclen", &path, &["--curve", "ring", "--method", "adaptive", "--json"]).json();
    assert_close(num(&json["length"]), std::f64::consts::TAU, 1e-2 * std::f64::consts::TAU, "ring length");
    let human = on("arclen", &path, &["--curve", "keys"]).ok().to_string();
    assert!(human.contains("keys"), "{human}");
}

#[test]
fn info_lists_tcb_and_bo_curves() {
    let dir = Dir::new();
    let path = interpolating_swp(&dir);
    let text = on("info", &path, &[]).ok().to_string();
    assert!(text.contains("4 curves, 0 surfaces"), "{text}");
    for line in [
        "keys  tcb3  6 points, 3 segments, steps 10, open",
        "ring  bo2   8 points, 8 segments, steps 6, closed",
        "zero  tcb3  6 points, 3 segments, steps 10, open",
    ] {
        assert!(text.contains(line), "no {line:?} in\n{text}");
    }
    let json = on("info", &path, &["--json"]).json();
    let curves = json["curves"].as_array().unwrap();
    assert_eq!(curves[0]["kind"], "tcb3");
    assert_eq!(curves[1]["kind"], "bo2");
    assert_eq!((num(&curves[1]["points"]), num(&curves[1]["segments"])), (8.0, 8.0));
    assert_eq!(curves[1]["closed"], true);
    // a bad key is an error with its line and column
    let bad = dir.file("bad.swp", "tcb2 k 10 4\n[0 0 0 0 0] [1 0 0 2 0]\n");
    for command in ["info", "curve", "arclen"] {
        let stderr = on(command, &bad, &[]).fails_with_error().to_string();
        assert!(stderr.contains("bad.swp:2:20: found \"2\", expected a number from -1 to 1"), "{stderr}");
    }
}
