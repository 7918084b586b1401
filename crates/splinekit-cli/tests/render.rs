//! `splinekit render`: the file is written with the asked size, the summary line, SVG for
//! curves, and bad input (a message naming the problem, a non-zero exit, no output file).

use std::path::{Path, PathBuf};

mod common;
use common::{course_mesh, splinekit, swp_dir};

fn swp(rel: &str) -> PathBuf {
    swp_dir().join(rel)
}

/// Width and height from a PNG's IHDR chunk.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    (be(16), be(20))
}

fn args<'a>(parts: &'a [&'a str]) -> Vec<&'a str> {
    parts.to_vec()
}

#[test]
fn renders_a_mesh_with_the_asked_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ico.png");
    let mesh = course_mesh("icosahedron.obj");
    let args: [&std::ffi::OsStr; 9] = [
        "render".as_ref(),
        mesh.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--size".as_ref(),
        "320x200".as_ref(),
        "--view".as_ref(),
        "front".as_ref(),
        "--wireframe".as_ref(),
    ];
    let run = splinekit(&args);
    let stdout = run.ok();
    assert!(stdout.ends_with(": 320x200, mesh of 20 triangles, front view\n"), "{stdout}");
    assert_eq!(png_size(&out), (320, 200));
    // The same bytes on a second run.
    let first = std::fs::read(&out).unwrap();
    splinekit(&args).ok();
    assert!(first == std::fs::read(&out).unwrap(), "two runs differ");
}

#[test]
fn renders_surfaces_and_plots_curves() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("glass.png");
    let glass = swp("srev/wineglass.swp");
    let run = splinekit(&["render".as_ref(), glass.as_os_str(), "-o".as_ref(), png.as_os_str()]);
    let stdout = run.ok();
    assert!(stdout.contains(": 800x600, 1 surfaces (32940 triangles) and 1 curves, iso view"), "{stdout}");
    assert_eq!(png_size(&png), (800, 600));

    let svg = dir.path().join("circles.svg");
    let circles = swp("circles.swp");
    let run = splinekit(&[
        "render".as_ref(),
        circles.as_os_str(),
        "-o".as_ref(),
        svg.as_os_str(),
        "--frames".as_ref(),
        "--markers".as_ref(),
        "0.5".as_ref(),
    ]);
    assert!(run.ok().contains("plot of 2 curves, front view"), "{}", run.stdout);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<?xml") && text.contains("<svg") && text.trim_end().ends_with("</svg>"));
    assert!(text.contains("<circle"), "markers are drawn");
}

#[test]
fn bad_input_names_the_problem_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let glass = swp("srev/wineglass.swp");
    let o = out.to_string_lossy().into_owned();
    let g = glass.to_string_lossy().into_owned();
    let check = |parts: &[&str], needle: &str, usage: bool| {
        let run = splinekit(&args(parts));
        let stderr = if usage { run.fails() } else { run.fails_with_error() };
        assert!(stderr.contains(needle), "{parts:?}: {stderr}");
        assert!(!out.exists(), "{parts:?}: an output file was written");
    };
    check(&["render", &g, "-o", &o, "--size", "0x5"], "width must be from 1 to 8192 pixels, found 0", true);
    check(&["render", &g, "-o", &o, "--size", "abc"], "expected WIDTHxHEIGHT such as 800x600, found \"abc\"", true);
    check(&["render", &g, "-o", &o, "--view", "sideways"], "unknown view \"sideways\"", true);
    check(&["render", &g, "-o", &o, "--markers", "-1"], "--markers must be a positive number", false);
    check(&["render", &g, "-o", &o.replace(".png", ".svg")], "SVG output draws curves only", false);
    check(&["render", &g, "-o", &o.replace(".png", ".jpg")], "expected .png or .svg", false);
    let missing = dir.path().join("missing.swp").to_string_lossy().into_owned();
    check(&["render", &missing, "-o", &o], "missing.swp", false);
    let txt = dir.path().join("notes.txt");
    std::fs::write(&txt, "hello").unwrap();
    check(&["render", &txt.to_string_lossy(), "-o", &o], "cannot draw a file of this kind (.txt)", false);
    let bad = dir.path().join("bad.swp");
    std::fs::write(&bad, "bez2 . 20 4\n[0 0]\n[1 1.2.3]").unwrap();
    check(&["render", &bad.to_string_lossy(), "-o", &o], "bad.swp:3:4", false);
    let no_dir = dir.path().join("no/such/dir/out.png").to_string_lossy().into_owned();
    let run = splinekit(&args(&["render", &g, "-o", &no_dir]));
    assert!(run.fails_with_error().contains("out.png"), "{}", run.stderr);
}

#[test]
fn gallery_writes_its_page_and_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("gallery");
    let run = splinekit(&[
        "gallery".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
        "--size".as_ref(),
        "64x48".as_ref(),
        "--levels".as_ref(),
        "1".as_ref(),
    ]);
    let stdout = run.ok();
    // 12 course files, 2 curve-kind examples, 2 arc-length entries, 2 meshes × 2 levels, the
    // ribbon.
    assert!(stdout.starts_with("21 entries, "), "{stdout}");
    assert!(stdout.contains(&out.join("index.html").display().to_string()), "{stdout}");
    assert_eq!(png_size(&out.join("images/wineglass.png")), (64, 48));
    assert!(out.join("meshes/bunny-loop1.glb").is_file());
    assert!(!out.join("meshes/bunny-loop2.obj").exists());
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("<h2>Loop subdivision</h2>"));
    assert!(html.contains("<h2>Curve kinds</h2>"));
    assert_eq!(png_size(&out.join("images/curve-kinds.png")), (64, 48));

    let bad = splinekit(&["gallery", "--levels", "9"]);
    assert!(bad.fails().contains("--levels"), "{}", bad.stderr);
}

/// The number after `key` in `line` (as the summary writes it, e.g. `-1.33e0`).
fn number_after(line: &str, key: &str) -> f64 {
    let rest = &line[line.find(key).unwrap_or_else(|| panic!("{key:?} in {line}")) + key.len()..];
    let text: String = rest.chars().take_while(|c| !c.is_whitespace() && *c != ')' && *c != ';').collect();
    text.parse().unwrap_or_else(|e| panic!("{text:?} in {line}: {e}"))
}

/// The `values from A to B` of a curvature summary.
fn values_from(line: &str) -> (f64, f64) {
    let rest = &line[line.find("values from ").unwrap_or_else(|| panic!("no values in {line}"))..];
    (number_after(rest, "values from "), number_after(rest, " to "))
}

#[test]
fn every_colouring_writes_its_picture_and_says_its_scale() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let o = out.to_string_lossy().into_owned();
    let tor = swp("gcyl/tor.swp").to_string_lossy().into_owned();
    let glass = swp("srev/wineglass.swp").to_string_lossy().into_owned();
    let ico = course_mesh("icosahedron.obj").to_string_lossy().into_owned();
    let run = |parts: &[&str]| {
        let _ = std::fs::remove_file(&out);
        let stdout = splinekit(&args(parts)).ok().to_owned();
        assert_eq!(png_size(&out), (320, 240), "{parts:?}");
        assert!(stdout.starts_with(&format!("{o}: 320x240, ")), "{stdout}");
        stdout
    };

    let shade = run(&["render", &glass, "-o", &o, "--size", "320x240", "--color", "shade"]);
    assert!(shade.ends_with("1 surfaces (32940 triangles) and 1 curves, iso view\n"), "{shade}");
    let plain = std::fs::read(&out).unwrap();
    run(&["render", &glass, "-o", &o, "--size", "320x240"]);
    assert!(std::fs::read(&out).unwrap() == plain, "shade is the default");

    // The torus of tor.swp (R = 2, r = 0.5): K from −1/(r(R − r)) = −4/3 to 1/(r(R + r)) = 0.8.
    let gauss = run(&["render", &tor, "-o", &o, "--size", "320x240", "--color", "curvature-gauss", "--view", "front"]);
    assert!(gauss.contains(", front view, Gaussian curvature from -"), "{gauss}");
    assert!(gauss.contains(" (95th percentile of |K|; values from "), "{gauss}");
    let (low, high) = values_from(&gauss);
    assert!((low + 4.0 / 3.0).abs() < 0.02 && (high - 0.8).abs() < 0.02, "{gauss}");
    let scale = number_after(&gauss, "curvature from ");
    assert!(scale < 0.0 && -scale <= -low && -scale > 1.0, "{gauss}");
    let first = std::fs::read(&out).unwrap();
    run(&["render", &tor, "-o", &o, "--size", "320x240", "--color", "curvature-gauss", "--view", "front"]);
    assert!(std::fs::read(&out).unwrap() == first, "two runs differ");

    // The torus's H runs from (R − 2r)/(2r(R − r)) = 2/3 inside to (R + 2r)/(2r(R + r)) = 1.2 outside.
    let mean = run(&["render", &tor, "-o", &o, "--size", "320x240", "--color", "curvature-mean"]);
    assert!(mean.contains(", iso view, mean curvature from -"), "{mean}");
    let (low, high) = values_from(&mean);
    assert!((low - 2.0 / 3.0).abs() < 0.02 && (high - 1.2).abs() < 0.02, "{mean}");
    let glass_mean = run(&["render", &glass, "-o", &o, "--size", "320x240", "--color", "curvature-mean"]);
    assert!(glass_mean.contains("mean curvature from -1.26e1 to +1.26e1 (95th percentile of |H|"), "{glass_mean}");

    let checker = run(&["render", &tor, "-o", &o, "--size", "320x240", "--color", "uv-checker"]);
    assert!(checker.ends_with("2 curves, iso view, UV checker (8×8 squares per unit)\n"), "{checker}");

    let level = run(&["render", &ico, "-o", &o, "--size", "320x240", "--color", "level", "--levels", "2"]);
    assert!(
        level.ends_with(
            "mesh of 320 triangles after 2 levels of Loop subdivision, iso view, coloured by levels 0 to 2\n"
        ),
        "{level}"
    );
    let cc = run(&[
        "render",
        &ico,
        "-o",
        &o,
        "--size",
        "320x240",
        "--color",
        "level",
        "--levels",
        "2",
        "--scheme",
        "catmull-clark",
    ]);
    assert!(cc.contains("mesh of 480 triangles after 2 levels of Catmull-Clark subdivision"), "{cc}");
    let base = run(&["render", &ico, "-o", &o, "--size", "320x240", "--color", "level"]);
    assert!(base.ends_with("mesh of 20 triangles, iso view, coloured by level 0\n"), "{base}");
    let sqrt3 = run(&["render", &ico, "-o", &o, "--size", "320x240", "--levels", "1", "--scheme", "sqrt3"]);
    assert!(sqrt3.ends_with("mesh of 60 triangles after 1 level of √3 subdivision, iso view\n"), "{sqrt3}");
}

#[test]
fn colouring_errors_name_the_problem_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let o = out.to_string_lossy().into_owned();
    // Without the HTML lines, whose warnings would come before the error.
    let ico = course_mesh("clean/icosahedron.obj").to_string_lossy().into_owned();
    let tor = swp("gcyl/tor.swp").to_string_lossy().into_owned();
    let check = |parts: &[&str], needle: &str, usage: bool| {
        let run = splinekit(&args(parts));
        let stderr = if usage { run.fails() } else { run.fails_with_error() };
        assert!(stderr.contains(needle), "{parts:?}: {stderr}");
        assert!(!out.exists(), "{parts:?}: an output file was written");
    };
    check(
        &["render", &ico, "-o", &o, "--color", "uv-checker"],
        &format!("error: --color uv-checker: {ico} has no texture coordinates\n"),
        false,
    );
    check(
        &["render", &ico, "-o", &o, "--color", "uv-checker", "--levels", "1"],
        &format!("error: --color uv-checker: {ico} has no texture coordinates\n"),
        false,
    );
    check(&["render", &ico, "-o", &o, "--levels", "12"], "use fewer --levels", false);
    check(&["render", &ico, "-o", &o, "--levels", "4000000000"], "more than the 20000000 that render draws", false);
    check(&["render", &tor, "-o", &o, "--levels", "1"], "--levels subdivides mesh files", false);
    check(
        &["render", &ico, "-o", &o, "--levels", "1", "--scheme", "doo-sabin", "--color", "level"],
        "--color level: Doo-Sabin subdivision makes every vertex anew",
        false,
    );
    check(&["render", &ico, "-o", &o.replace(".png", ".svg"), "--levels", "1"], "SVG output draws curves only", false);
    check(&["render", &ico, "-o", &o, "--scheme", "loop"], "--levels", true);
    check(&["render", &ico, "-o", &o, "--color", "rainbow"], "curvature-gauss", true);
}

/// A file without faces is a clear error (#39), with and without `--levels`; what the reader
/// skips is a warning naming the file.
#[test]
fn a_mesh_without_faces_and_reader_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let points = dir.path().join("points.ply");
    std::fs::write(
        &points,
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
    )
    .unwrap();
    let out = dir.path().join("out.png");
    for levels in [None, Some("1")] {
        let mut args = vec!["render", points.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend(levels.map(|n| ["--levels", n]).into_iter().flatten());
        let message = splinekit(&args).fails_with_error().to_owned();
        assert_eq!(message, format!("error: {} has no faces (1 vertex): render needs faces\n", points.display()));
        assert!(!out.exists());
    }
    let strips = dir.path().join("strips.ply");
    std::fs::write(
        &strips,
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
         element tristrips 1\nproperty list int int vertex_indices\nproperty uchar flags\nend_header\n\
         0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 2 3 0\n",
    )
    .unwrap();
    let run = splinekit(&["render", strips.to_str().unwrap(), "-o", out.to_str().unwrap(), "--size", "64x48"]);
    assert_eq!(run.ok(), format!("{}: 64x48, mesh of 2 triangles, iso view\n", out.display()));
    assert_eq!(
        run.stderr,
        format!("warning: {}: line 9: skipped property \"flags\" of element \"tristrips\"\n", strips.display())
    );
    assert_eq!(png_size(&out), (64, 48));
}
