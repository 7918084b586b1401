//! `splinekit subdivide`: counts, the JSON contract, output files read back, and bad input
//! (a clear message, a non-zero exit, no output file).

use std::path::{Path, PathBuf};

use serde_json::Value;

mod common;
use common::{course_mesh, splinekit};

/// A course mesh as shipped (HTML lines included).
fn shared(name: &str) -> String {
    course_mesh(name).to_string_lossy().into_owned()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("splinekit-subdivide-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Counts `v` and `f` lines of an OBJ file.
fn obj_counts(path: &Path) -> (usize, usize) {
    let text = std::fs::read_to_string(path).unwrap();
    let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count();
    (count("v "), count("f "))
}

#[test]
fn json_contract_and_counts() {
    let ico = shared("icosahedron.obj");
    for (levels, v, f) in [(1, 42, 80), (2, 162, 320), (3, 642, 1280)] {
        let run =
            splinekit(&["subdivide", &ico, "-n", &levels.to_string(), "--json", "--repeat", "3", "--threads", "1"]);
        let json: Value = serde_json::from_str(run.ok()).unwrap();
        let keys: Vec<&str> = json.as_object().unwrap().keys().map(String::as_str).collect();
        assert_eq!(keys.len(), 3, "{json}");
        assert_eq!(json["vertices"], v);
        assert_eq!(json["faces"], f);
        assert!(json["seconds"].as_f64().unwrap() >= 0.0);
    }
}

#[test]
fn writes_every_format_and_warns_about_html_lines() {
    let dir = temp_dir("formats");
    let bunny = shared("bunny.obj");
    for ext in ["obj", "ply", "stl", "glb"] {
        let out = dir.join(format!("bunny.{ext}"));
        let run = splinekit(&["subdivide", &bunny, "-n", "1", "-o", out.to_str().unwrap()]);
        let text = run.ok();
        assert!(text.contains("vertices") && text.contains("19872 triangles"), "{text}");
        assert!(run.stderr.contains("warning"), "the HTML lines are reported: {}", run.stderr);
        assert!(out.metadata().unwrap().len() > 0);
    }
    // The .glb reads back: one more level.
    let glb = dir.join("bunny.glb");
    let run = splinekit(&["subdivide", glb.to_str().unwrap(), "-n", "1", "--json", "--threads", "1"]);
    assert_eq!(run.json()["faces"], 4 * 19872);
    assert!(!run.stderr.contains("warning"), "{}", run.stderr);
    // V + E for the bunny: V = 2503, F = 4968, 42 boundary edges → E = (3F + 42) / 2.
    let (v, f) = obj_counts(&dir.join("bunny.obj"));
    assert_eq!((v, f), (2503 + (3 * 4968 + 42) / 2, 4 * 4968));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn options_change_the_result() {
    let dir = temp_dir("options");
    let patch = shared("patch.obj");
    let mut outputs = Vec::new();
    for flags in [&["--weights", "loop"][..], &["--weights", "warren"], &["--boundary", "corners"]] {
        let out = dir.join(format!("patch{}.obj", outputs.len()));
        let mut args = vec!["subdivide", &patch, "-n", "2", "-o", out.to_str().unwrap()];
        args.extend_from_slice(flags);
        splinekit(&args).ok();
        outputs.push(std::fs::read_to_string(&out).unwrap());
    }
    assert_ne!(outputs[0], outputs[2], "corners fixed moves fewer vertices");
    // Colour by level: OBJ vertices get r g b.
    let out = dir.join("colored.obj");
    splinekit(&["subdivide", &patch, "-n", "2", "--color-by-level", "-o", out.to_str().unwrap()]).ok();
    let text = std::fs::read_to_string(&out).unwrap();
    let v: Vec<&str> = text.lines().filter(|l| l.starts_with("v ")).collect();
    assert!(v.iter().all(|l| l.split_whitespace().count() == 7), "v x y z r g b");
    // The 16 base vertices are grey (0.6), the rest coloured.
    assert!(v[..16].iter().all(|l| l.ends_with(" 0.6 0.6 0.6")));
    assert!(!v[16].ends_with(" 0.6 0.6 0.6"));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_input_fails_cleanly() {
    let dir = temp_dir("bad");
    let quad = dir.join("quad.obj");
    std::fs::write(&quad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    let out = dir.join("out.obj");
    let err =
        splinekit(&["subdivide", quad.to_str().unwrap(), "-n", "1", "-o", out.to_str().unwrap()]).fails().to_owned();
    assert!(err.contains("face 0 has 4 corners"), "{err}");
    assert!(!out.exists());

    let bowtie = dir.join("bowtie.obj");
    std::fs::write(&bowtie, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n").unwrap();
    // Loop takes the bowtie (issue #39): V + E vertices, 4F triangles
    splinekit(&["subdivide", bowtie.to_str().unwrap(), "-n", "1", "-o", out.to_str().unwrap()]).ok();
    assert_eq!(obj_counts(&out), (5 + 6, 8));
    let run = splinekit(&[
        "subdivide",
        bowtie.to_str().unwrap(),
        "-n",
        "1",
        "--split-nonmanifold",
        "-o",
        out.to_str().unwrap(),
    ]);
    run.ok();
    assert_eq!(obj_counts(&out), (6 + 6, 8));

    let broken = dir.join("broken.obj");
    std::fs::write(&broken, "v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n").unwrap();
    let err =
        splinekit(&["subdivide", broken.to_str().unwrap(), "-n", "1", "-o", out.to_str().unwrap()]).fails().to_owned();
    assert!(err.contains("broken.obj:2:"), "{err}");
    let err = splinekit(&["subdivide", &shared("patch.obj"), "-n", "1", "-o", "x.xyz"]).fails().to_owned();
    assert!(err.contains("unknown output format"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn catmull_clark_on_quads_and_a_mixed_mesh() {
    let dir = temp_dir("catmull-clark");
    // a cube of quads: V 8, E 12, F 6 → 26 vertices, 24 quads → 98, 96
    let cube = dir.join("cube.obj");
    std::fs::write(
        &cube,
        "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n\
         f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n",
    )
    .unwrap();
    let cube = cube.to_str().unwrap();
    for (levels, v, f) in [(1, 26, 24), (2, 98, 96)] {
        let run = splinekit(&["subdivide", cube, "-n", &levels.to_string(), "--scheme", "catmull-clark", "--json"]);
        let json: Value = serde_json::from_str(run.ok()).unwrap();
        assert_eq!((json["vertices"].as_u64(), json["faces"].as_u64()), (Some(v), Some(f)), "{json}");
    }
    // OBJ keeps the quads; a corner of the cube moves to 5/9 of itself after one level
    let out = dir.join("cube1.obj");
    let run = splinekit(&["subdivide", cube, "-n", "1", "--scheme", "catmull-clark", "-o", out.to_str().unwrap()]);
    assert!(run.ok().contains("26 vertices, 24 quads after 1 level of Catmull-Clark"), "{}", run.stdout);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.lines().filter(|l| l.starts_with("f ")).all(|l| l.split_whitespace().count() == 5));
    let first: Vec<f64> = text.lines().next().unwrap().split_whitespace().skip(1).map(|x| x.parse().unwrap()).collect();
    for x in first {
        assert!((x + 5.0 / 9.0).abs() < 1e-15, "{text}");
    }
    // --limit: positions and limit normals, the quads' corners `v//n`; by symmetry the normal
    // at a corner of the cube is its diagonal
    let run =
        splinekit(&["subdivide", cube, "-n", "1", "--scheme", "catmull-clark", "--limit", "-o", out.to_str().unwrap()]);
    run.ok();
    let text = std::fs::read_to_string(&out).unwrap();
    let normals: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| l.starts_with("vn "))
        .map(|l| l.split_whitespace().skip(1).map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(normals.len(), 26);
    for n in &normals[..8] {
        assert!(n.iter().all(|x| (x.abs() - 3f64.sqrt().recip()).abs() < 1e-12), "{n:?}");
    }
    assert!(
        text.lines().filter(|l| l.starts_with("f ")).all(|l| l.split_whitespace().skip(1).all(|c| c.contains("//")))
    );
    // the triangle icosahedron: 12 + 30 + 20 vertices, 60 quads; STL gets two triangles a quad
    let stl = dir.join("ico.stl");
    let ico = shared("icosahedron.obj");
    let run = splinekit(&["subdivide", &ico, "-n", "1", "--scheme", "catmull-clark", "-o", stl.to_str().unwrap()]);
    assert!(run.ok().contains("62 vertices, 60 quads"), "{}", run.stdout);
    assert_eq!(std::fs::metadata(&stl).unwrap().len(), 84 + 50 * 120);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn limit_moves_vertices_onto_the_limit_surface() {
    let dir = temp_dir("limit");
    let ico = shared("icosahedron.obj");
    let (plain, limit) = (dir.join("plain.obj"), dir.join("limit.obj"));
    splinekit(&["subdivide", &ico, "-n", "1", "-o", plain.to_str().unwrap()]).ok();
    splinekit(&["subdivide", &ico, "-n", "1", "--limit", "-o", limit.to_str().unwrap()]).ok();
    let radii = |p: &Path| -> Vec<f64> {
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .filter(|l| l.starts_with("v "))
            .map(|l| l.split_whitespace().skip(1).map(|x| x.parse::<f64>().unwrap().powi(2)).sum::<f64>().sqrt())
            .collect()
    };
    let (a, b) = (radii(&plain), radii(&limit));
    assert_eq!(a.len(), b.len());
    // Loop shrinks a convex mesh level by level: the limit lies inside every level, and the
    // icosahedron's symmetry puts all 12 old vertices at one radius, all 30 new ones at another
    // (to the 6 digits of the course file's coordinates)
    assert!(a.iter().zip(&b).all(|(x, y)| y < x), "{a:?} vs {b:?}");
    for group in [&b[..12], &b[12..]] {
        assert!(group.iter().all(|r| (r - group[0]).abs() < 1e-6 * group[0]), "{group:?}");
    }
    // --limit also writes the limit normals, one `vn` per vertex: unit, outward on this convex
    // surface, and by symmetry along the radius at the 12 old vertices
    let text = std::fs::read_to_string(&limit).unwrap();
    let triples = |tag: &str| -> Vec<[f64; 3]> {
        text.lines()
            .filter(|l| l.split_whitespace().next() == Some(tag))
            .map(|l| {
                let x: Vec<f64> = l.split_whitespace().skip(1).map(|t| t.parse().unwrap()).collect();
                [x[0], x[1], x[2]]
            })
            .collect()
    };
    let (points, normals) = (triples("v"), triples("vn"));
    assert_eq!(normals.len(), points.len());
    let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for (k, (p, n)) in points.iter().zip(&normals).enumerate() {
        assert!((dot(n, n) - 1.0).abs() < 1e-12, "normal {k} is not unit: {n:?}");
        assert!(dot(n, p) > 0.0, "normal {k} points inwards: {n:?} at {p:?}");
        if k < 12 {
            let cos = dot(n, p) / dot(p, p).sqrt();
            assert!(cos > 1.0 - 1e-10, "normal {k} is not radial: {n:?} at {p:?}");
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn sqrt3_and_doo_sabin_counts_and_output() {
    let dir = temp_dir("sqrt3-doo-sabin");
    let ico = shared("icosahedron.obj"); // V 12, E 30, F 20, closed
    // √3: (V, F) → (V + F, 3F)
    for (levels, v, f) in [(1, 32, 60), (2, 92, 180), (3, 272, 540)] {
        let json =
            splinekit(&["subdivide", &ico, "-n", &levels.to_string(), "--scheme", "sqrt3", "--json", "--repeat", "2"])
                .json();
        assert_eq!((json["vertices"].as_u64(), json["faces"].as_u64()), (Some(v), Some(f)), "{json}");
    }
    // Doo-Sabin: Σ face sizes = 2E vertices, F + E + V faces
    for (levels, v, f) in [(1, 60, 62), (2, 240, 242)] {
        let json = splinekit(&["subdivide", &ico, "-n", &levels.to_string(), "--scheme", "doo-sabin", "--json"]).json();
        assert_eq!((json["vertices"].as_u64(), json["faces"].as_u64()), (Some(v), Some(f)), "{json}");
    }
    // the summary names the scheme; OBJ keeps Doo-Sabin's polygons: 20 triangles (the faces),
    // 30 quads (the edges), 12 pentagons (the vertices)
    let out = dir.join("ico-ds.obj");
    let run = splinekit(&["subdivide", &ico, "-n", "1", "--scheme", "doo-sabin", "-o", out.to_str().unwrap()]);
    assert!(run.ok().contains("60 vertices, 62 faces after 1 level of Doo-Sabin subdivision"), "{}", run.stdout);
    let text = std::fs::read_to_string(&out).unwrap();
    let mut sizes: Vec<usize> =
        text.lines().filter(|l| l.starts_with("f ")).map(|l| l.split_whitespace().count() - 1).collect();
    sizes.sort_unstable();
    assert_eq!(sizes, [vec![3; 20], vec![4; 30], vec![5; 12]].concat());
    // √3 on an open mesh, coloured by level: OBJ vertices get r g b
    let out = dir.join("patch-sqrt3.obj");
    let run = splinekit(&[
        "subdivide",
        &shared("patch.obj"),
        "-n",
        "2",
        "--scheme",
        "sqrt3",
        "--color-by-level",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.ok().contains("after 2 levels of √3 subdivision"), "{}", run.stdout);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.lines().filter(|l| l.starts_with("v ")).all(|l| l.split_whitespace().count() == 7));
    assert!(text.lines().filter(|l| l.starts_with("f ")).all(|l| l.split_whitespace().count() == 4));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn butterfly_interpolates_with_loops_counts() {
    let dir = temp_dir("butterfly");
    let ico = shared("icosahedron.obj"); // V 12, E 30, F 20, closed
    for (levels, v, f) in [(1, 42, 80), (2, 162, 320)] {
        let json = splinekit(&["subdivide", &ico, "-n", &levels.to_string(), "--scheme", "butterfly", "--json"]).json();
        assert_eq!((json["vertices"].as_u64(), json["faces"].as_u64()), (Some(v), Some(f)), "{json}");
    }
    // the input's vertices are the output's first ones, unmoved (--limit leaves them too)
    let out = dir.join("ico-bf.obj");
    let run =
        splinekit(&["subdivide", &ico, "-n", "2", "--scheme", "butterfly", "--limit", "-o", out.to_str().unwrap()]);
    assert!(run.ok().contains("162 vertices, 320 triangles after 2 levels of butterfly subdivision"), "{}", run.stdout);
    let coords = |text: &str| -> Vec<[f64; 3]> {
        text.lines()
            .filter(|l| l.starts_with("v "))
            .map(|l| {
                let x: Vec<f64> = l.split_whitespace().skip(1).take(3).map(|t| t.parse().unwrap()).collect();
                [x[0], x[1], x[2]]
            })
            .collect()
    };
    let (input, output) =
        (coords(&std::fs::read_to_string(&ico).unwrap()), coords(&std::fs::read_to_string(&out).unwrap()));
    assert_eq!(input.len(), 12);
    for (k, (a, b)) in input.iter().zip(&output).enumerate() {
        assert!((0..3).all(|i| (a[i] - b[i]).abs() <= 1e-15 * a[i].abs().max(1.0)), "vertex {k}: {a:?} became {b:?}");
    }
    // triangles only
    let quad = dir.join("quad.obj");
    std::fs::write(&quad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    let err = splinekit(&["subdivide", quad.to_str().unwrap(), "-n", "1", "--scheme", "butterfly"])
        .fails_with_error()
        .to_owned();
    assert!(err.contains("face 0 has 4 corners; butterfly subdivision needs triangles"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn sqrt3_and_doo_sabin_refuse_bad_input_and_options() {
    let dir = temp_dir("sqrt3-doo-sabin-bad");
    let quad = dir.join("quad.obj");
    std::fs::write(&quad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    let (quad, out) = (quad.to_str().unwrap(), dir.join("out.obj"));
    let out_s = out.to_str().unwrap();
    let err =
        splinekit(&["subdivide", quad, "-n", "1", "--scheme", "sqrt3", "-o", out_s]).fails_with_error().to_owned();
    assert!(err.contains("quad.obj: face 0 has 4 corners; √3 subdivision needs triangles"), "{err}");
    assert!(!out.exists());
    // Doo-Sabin takes the quad: one smaller quad
    let json = splinekit(&["subdivide", quad, "-n", "1", "--scheme", "doo-sabin", "--json"]).json();
    assert_eq!((json["vertices"].as_u64(), json["faces"].as_u64()), (Some(4), Some(1)), "{json}");

    let bowtie = dir.join("bowtie.obj");
    std::fs::write(&bowtie, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n").unwrap();
    for scheme in ["sqrt3", "doo-sabin", "butterfly"] {
        let err = splinekit(&["subdivide", bowtie.to_str().unwrap(), "-n", "1", "--scheme", scheme, "-o", out_s])
            .fails_with_error()
            .to_owned();
        assert!(err.contains("vertex 0 is non-manifold") && err.contains("--split-nonmanifold"), "{err}");
        assert!(!out.exists());
        // the flag the message suggests works
        splinekit(&["subdivide", bowtie.to_str().unwrap(), "-n", "1", "--scheme", scheme, "--split-nonmanifold"]).ok();
    }

    // options that mean nothing for the scheme are refused before anything is read or written
    let ico = shared("icosahedron.obj");
    for (scheme, flags, needle) in [
        ("sqrt3", &["--weights", "warren"][..], "--weights"),
        ("doo-sabin", &["--weights", "loop"], "--weights"),
        ("catmull-clark", &["--weights", "warren"], "--weights"),
        ("sqrt3", &["--boundary", "corners"], "--boundary"),
        ("doo-sabin", &["--boundary", "smooth"], "--boundary"),
        ("sqrt3", &["--limit"], "--limit"),
        ("doo-sabin", &["--limit"], "--limit"),
        ("doo-sabin", &["--color-by-level"], "--color-by-level"),
        ("butterfly", &["--weights", "warren"], "--weights"),
        ("butterfly", &["--boundary", "corners"], "--boundary"),
    ] {
        let mut args = vec!["subdivide", &ico, "-n", "1", "--scheme", scheme, "-o", out_s];
        args.extend_from_slice(flags);
        let err = splinekit(&args).fails_with_error().to_owned();
        assert!(err.contains(needle), "{scheme} {flags:?}: {err}");
        assert!(!out.exists());
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// The `v` lines of an OBJ file.
fn obj_points(path: &Path) -> Vec<[f64; 3]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().skip(1).map(|t| t.parse().unwrap()).collect();
            [x[0], x[1], x[2]]
        })
        .collect()
}

const CUBE: &str = "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n\
                    f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";

/// The cube's top face (z = 1: vertices 4, 5, 7, 6, 0-based) as one infinitely sharp crease
/// chain with infinitely sharp corners.
const TOP_LOOP: &str = "t crease 5/1 4 5 7 6 4 10\nt corner 4/1 4 5 6 7 10\n";

#[test]
fn creases_from_tags_and_side_files_carry_on() {
    let dir = temp_dir("creases");
    let (tagged, plain, side) = (dir.join("tagged.obj"), dir.join("plain.obj"), dir.join("top.txt"));
    std::fs::write(&tagged, format!("{CUBE}{TOP_LOOP}")).unwrap();
    std::fs::write(&plain, CUBE).unwrap();
    std::fs::write(&side, format!("# the top face's edges\n{TOP_LOOP}")).unwrap();
    let path = |p: &Path| p.to_str().unwrap().to_owned();
    for (scheme, levels) in [("catmull-clark", "3"), ("loop", "2")] {
        let input = if scheme == "loop" {
            // Loop needs triangles: split each quad a → b → c → d into a b c and a c d
            let tri = dir.join("tri.obj");
            let mut text = String::new();
            for l in CUBE.lines() {
                let w: Vec<&str> = l.split_whitespace().collect();
                if w[0] == "f" {
                    text += &format!("f {} {} {}\nf {} {} {}\n", w[1], w[2], w[3], w[1], w[3], w[4]);
                } else {
                    text += &format!("{l}\n");
                }
            }
            std::fs::write(&tri, format!("{text}{TOP_LOOP}")).unwrap();
            tri
        } else {
            tagged.clone()
        };
        let (whole, first, second) = (dir.join("whole.obj"), dir.join("first.obj"), dir.join("second.obj"));
        let run = |args: &[&str]| splinekit(&[&["subdivide", "--scheme", scheme][..], args].concat()).ok().to_owned();
        run(&[&path(&input), "-n", levels, "-o", &path(&whole)]);
        // the infinitely sharp top loop with sharp corners stays a square: its vertices have
        // |x| = 1 or |y| = 1 at z = 1
        let points = obj_points(&whole);
        let on_top_rim = points.iter().filter(|p| p[2] == 1.0 && (p[0].abs() == 1.0 || p[1].abs() == 1.0)).count();
        let n: usize = levels.parse().unwrap();
        assert_eq!(on_top_rim, 4 << n, "{scheme}: the top rim keeps {on_top_rim} vertices");
        // the output carries the child creases: one more level of it is the same as all at once
        let text = std::fs::read_to_string(&whole).unwrap();
        let info = splinekit(&["info", &path(&whole)]);
        assert!(info.ok().contains(&format!("creases ({} edges, 4 vertices)", 4 << n)), "{}", info.stdout);
        assert_eq!(text.lines().filter(|l| l.starts_with("t crease 2/1 ")).count(), 4 << n);
        run(&[&path(&input), "-n", &(n - 1).to_string(), "-o", &path(&first)]);
        run(&[&path(&first), "-n", "1", "-o", &path(&second)]);
        let mut a = obj_points(&whole);
        let mut b = obj_points(&second);
        let key = |p: &[f64; 3]| p.map(|x| (x * 1e9).round() as i64);
        a.sort_by_key(key);
        b.sort_by_key(key);
        assert_eq!(a.len(), b.len());
        assert!(a.iter().zip(&b).all(|(p, q)| (0..3).all(|k| (p[k] - q[k]).abs() < 1e-12)), "{scheme}");
        // --limit with creases: the rim's vertices go to the limit of the infinitely sharp
        // square (its own sides, the corners fixed), the rest inside; one unit normal each
        let limit = dir.join("limit.obj");
        run(&[&path(&input), "-n", levels, "--limit", "-o", &path(&limit)]);
        let near = |x: f64, y: f64| (x - y).abs() < 1e-12;
        let points = obj_points(&limit);
        let rim = points.iter().filter(|p| near(p[2], 1.0) && (near(p[0].abs(), 1.0) || near(p[1].abs(), 1.0)));
        assert_eq!(rim.count(), 4 << n, "{scheme} --limit");
        assert!(points.iter().all(|p| p.iter().all(|x| x.abs() <= 1.0 + 1e-12)), "{scheme} --limit");
        let text = std::fs::read_to_string(&limit).unwrap();
        assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), points.len(), "{scheme} --limit");
        // the side file gives the same surface as the tags
        if scheme == "catmull-clark" {
            let from_side = dir.join("side.obj");
            run(&[&path(&plain), "-n", levels, "--creases", &path(&side), "-o", &path(&from_side)]);
            assert_eq!(obj_points(&from_side), obj_points(&whole));
            // and no creases is the smooth surface: the rim is rounded off
            let smooth = dir.join("smooth.obj");
            run(&[&path(&plain), "-n", levels, "-o", &path(&smooth)]);
            assert!(obj_points(&smooth).iter().all(|p| p[2] < 1.0));
            // uniform creasing is accepted (the same here: every crease is infinitely sharp)
            let uniform = dir.join("uniform.obj");
            run(&[&path(&input), "-n", levels, "--creasing", "uniform", "-o", &path(&uniform)]);
            assert_eq!(obj_points(&uniform), obj_points(&whole));
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_creases_fail_cleanly() {
    let dir = temp_dir("bad-creases");
    let path = |p: &Path| p.to_str().unwrap().to_owned();
    let out = dir.join("out.obj");
    let fails = |input: &str, extra: &[&str]| {
        let f = dir.join("in.obj");
        std::fs::write(&f, input).unwrap();
        let (f, out) = (path(&f), path(&out));
        let args = [&["subdivide", &f, "-n", "1", "--scheme", "catmull-clark", "-o", &out][..], extra].concat();
        let run = splinekit(&args);
        assert!(!Path::new(&out).exists(), "no output file after an error");
        run.fails_with_error().to_owned()
    };
    let err = fails(&format!("{CUBE}t crease 2/1 0 9 1\n"), &[]);
    assert!(err.contains("in.obj:15:16: found \"9\", expected a vertex index from 0 to 7"), "{err}");
    let err = fails(&format!("{CUBE}t crease 2/1 0 7 1\n"), &[]);
    assert!(err.contains("crease on edge 0–7: no face has this edge"), "{err}");
    let side = dir.join("side.txt");
    std::fs::write(&side, "t corner 1/1 3 x\n").unwrap();
    let err = fails(CUBE, &["--creases", &path(&side)]);
    assert!(err.contains("side.txt:1:16: found \"x\", expected a sharpness"), "{err}");
    let err = fails(CUBE, &["--creases", &path(&dir.join("missing.txt"))]);
    assert!(err.contains("cannot open") && err.contains("missing.txt"), "{err}");
    // the other schemes have no creases: a side file is refused, the tags of a file ignored
    let f = dir.join("in.obj");
    std::fs::write(&f, format!("{CUBE}{TOP_LOOP}")).unwrap();
    let run = splinekit(&["subdivide", &path(&f), "-n", "1", "--scheme", "doo-sabin", "--creases", &path(&side)]);
    assert!(
        run.fails_with_error().contains("--creases and --creasing are for Loop and Catmull-Clark"),
        "{}",
        run.stderr
    );
    let run = splinekit(&["subdivide", &path(&f), "-n", "1", "--scheme", "doo-sabin"]);
    run.ok();
    assert!(run.stderr.contains("its crease tags are ignored"), "{}", run.stderr);
    let _ = std::fs::remove_dir_all(dir);
}

/// Too many levels for `u32` indices: refused before any work with the counts that would not
/// fit, a non-zero exit and no output file, for every scheme (Loop and Catmull-Clark with
/// creases too).
#[test]
fn too_many_levels_fail_before_any_work() {
    let dir = temp_dir("too-many-levels");
    let path = |p: &Path| p.to_str().unwrap().to_owned();
    let (cube, creased) = (dir.join("cube.obj"), dir.join("creased.obj"));
    std::fs::write(&cube, CUBE).unwrap();
    std::fs::write(&creased, format!("{CUBE}{TOP_LOOP}")).unwrap();
    let tetra = dir.join("tetra.obj");
    std::fs::write(&tetra, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n").unwrap();
    let creased_tetra = dir.join("creased-tetra.obj");
    std::fs::write(&creased_tetra, format!("{}t crease 2/1 0 1 2\n", std::fs::read_to_string(&tetra).unwrap()))
        .unwrap();
    let out = dir.join("out.obj");
    for (input, scheme, levels, name) in [
        (path(&tetra), "loop", "20", "Loop"),
        (path(&tetra), "loop", "4294967295", "Loop"),
        (path(&creased_tetra), "loop", "20", "Loop"),
        (path(&cube), "catmull-clark", "20", "Catmull-Clark"),
        (path(&creased), "catmull-clark", "20", "Catmull-Clark"),
        (path(&tetra), "sqrt3", "40", "√3"),
        (path(&tetra), "butterfly", "20", "butterfly"),
        (path(&cube), "doo-sabin", "20", "Doo-Sabin"),
    ] {
        let run = splinekit(&["subdivide", &input, "-n", levels, "--scheme", scheme, "-o", &path(&out)]);
        let err = run.fails_with_error();
        assert!(err.contains(&format!("of {name} subdivision would make")), "{scheme} -n {levels}: {err}");
        assert!(err.contains("; at most 4294967295 fit in u32 indices"), "{scheme} -n {levels}: {err}");
        assert!(!out.exists(), "{scheme} -n {levels}: no output file after an error");
    }
    // the tetrahedron's exact numbers: 2·4ᵏ + 2 vertices, 6·4ᵏ edges, 4·4ᵏ triangles, 12·4ᵏ
    // corners; 14 levels fit, at 15 the edges (6·4¹⁵ = 6 442 450 944) are the first count too many
    let run = splinekit(&["subdivide", &path(&tetra), "-n", "15", "-o", &path(&out)]);
    assert!(
        run.fails_with_error().contains(
            "15 levels of Loop subdivision would make 6442450944 edges; at most 4294967295 fit in u32 indices"
        ),
        "{}",
        run.stderr
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(dir);
}

/// A cube of 12 triangles, flat-shaded (one normal per side) and UV-mapped side by side: every
/// vertex has three normals and several UVs.
const FLAT_CUBE: &str = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1
vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1
f 1/1/1 4/4/1 3/3/1\nf 1/1/1 3/3/1 2/2/1\nf 5/1/2 6/2/2 7/3/2\nf 5/1/2 7/3/2 8/4/2
f 1/1/3 2/2/3 6/3/3\nf 1/1/3 6/3/3 5/4/3\nf 4/1/4 8/2/4 7/3/4\nf 4/1/4 7/3/4 3/4/4
f 1/1/5 5/2/5 8/3/5\nf 1/1/5 8/3/5 4/4/5\nf 2/1/6 3/2/6 7/3/6\nf 2/1/6 7/3/6 6/4/6\n";

/// An octahedron with smooth normals (one per vertex) and a UV seam along its equator: the
/// upper and lower halves have UVs of their own.
const SEAMED_OCTAHEDRON: &str = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1
vn 1 0 0\nvn -1 0 0\nvn 0 1 0\nvn 0 -1 0\nvn 0 0 1\nvn 0 0 -1
vt 1 0.5\nvt 0 0.5\nvt 0.5 1\nvt 0.5 0\nvt 0.5 0.5\nvt 0.9 0.4\nvt 0.1 0.4\nvt 0.4 0.9\nvt 0.4 0.1\nvt 0.6 0.6
f 1/1/1 3/3/3 5/5/5\nf 3/3/3 2/2/2 5/5/5\nf 2/2/2 4/4/4 5/5/5\nf 4/4/4 1/1/1 5/5/5
f 3/8/3 1/6/1 6/10/6\nf 2/7/2 3/8/3 6/10/6\nf 4/9/4 2/7/2 6/10/6\nf 1/6/1 4/9/4 6/10/6\n";

/// Every face of an OBJ file as its corners' (position, UV, normal), each face rotated to
/// start at its least corner and the faces sorted: the same surface numbered differently
/// gives the same list.
fn corners(path: &Path) -> Vec<Vec<[f64; 8]>> {
    let mesh = splinekit_io::mesh::load_mesh(path).unwrap().mesh;
    let (uvs, normals) = (mesh.uvs.as_ref().unwrap(), mesh.normals.as_ref().unwrap());
    let mut faces: Vec<Vec<[f64; 8]>> = mesh
        .face_offsets
        .windows(2)
        .map(|w| {
            let mut face: Vec<[f64; 8]> = (w[0] as usize..w[1] as usize)
                .map(|c| {
                    let (p, t) = (mesh.positions[mesh.face_vertices[c] as usize], uvs.values[uvs.indices[c] as usize]);
                    let n = normals.values[normals.indices[c] as usize];
                    [p.x, p.y, p.z, t.x, t.y, n.x, n.y, n.z]
                })
                .collect();
            let least = (0..face.len()).min_by(|&a, &b| face[a].partial_cmp(&face[b]).unwrap()).unwrap();
            face.rotate_left(least);
            face
        })
        .collect();
    // sorted by positions rounded well above the differences of summation order
    let key =
        |f: &Vec<[f64; 8]>| f.iter().flat_map(|c| c[..3].iter().map(|x| (x * 1e6).round() as i64)).collect::<Vec<_>>();
    faces.sort_by_key(key);
    faces
}

/// Attributes never tear a mesh: the OBJ written keeps one vertex per position with the
/// normals and UVs indexed per corner, so `-n 0` gives the input's topology, and subdividing a
/// level-1 file once more gives level 2 (positions, UVs and normals to 1e-12). glb splits the
/// seams and says how many vertices it wrote.
#[test]
fn attributes_keep_the_topology_and_levels_carry_on() {
    let dir = temp_dir("attributes");
    for (name, text, vertices, faces) in [("cube", FLAT_CUBE, 8, 12), ("octahedron", SEAMED_OCTAHEDRON, 6, 8)] {
        let input = dir.join(format!("{name}.obj"));
        std::fs::write(&input, text).unwrap();
        let file = |s: &str| dir.join(format!("{name}-{s}")).to_string_lossy().into_owned();
        let input = input.to_string_lossy().into_owned();
        // level 0: the input's vertices and faces, closed, attribute values per corner kept
        splinekit(&["subdivide", &input, "-n", "0", "-o", &file("0.obj")]).ok();
        let zero = splinekit_io::mesh::load_mesh(file("0.obj")).unwrap().mesh;
        let original = splinekit_io::mesh::load_mesh(&input).unwrap().mesh;
        assert_eq!((zero.num_vertices(), zero.num_faces()), (vertices, faces));
        assert_eq!(zero.face_vertices, original.face_vertices, "{name}");
        assert_eq!(corners(Path::new(&file("0.obj"))), corners(Path::new(&input)), "{name}");
        let info = splinekit(&["info", &file("0.obj")]).ok().to_owned();
        assert!(info.contains("boundary: none (closed)") && info.contains("components: 1"), "{info}");
        // one level, then one more, against two at once
        splinekit(&["subdivide", &input, "-n", "1", "-o", &file("1.obj")]).ok();
        splinekit(&["subdivide", &file("1.obj"), "-n", "1", "-o", &file("11.obj")]).ok();
        splinekit(&["subdivide", &input, "-n", "2", "-o", &file("2.obj")]).ok();
        let (again, twice) = (corners(Path::new(&file("11.obj"))), corners(Path::new(&file("2.obj"))));
        assert_eq!(again.len(), twice.len());
        let worst = again
            .iter()
            .flatten()
            .zip(twice.iter().flatten())
            .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
            .fold(0.0, f64::max);
        assert!(worst <= 1e-12, "{name}: level 1 twice differs from level 2 by {worst}");
        // glb: one normal and UV per vertex, so the seams are split, and the count says so
        let json: Value =
            serde_json::from_str(splinekit(&["subdivide", &input, "-n", "1", "-o", &file("1.glb"), "--json"]).ok())
                .unwrap();
        let glb = splinekit_io::mesh::load_mesh(file("1.glb")).unwrap().mesh;
        assert_eq!(json["written_vertices"], glb.num_vertices(), "{json}");
        assert!(glb.num_vertices() > json["vertices"].as_u64().unwrap() as usize);
        // PLY keeps the vertices (UVs per corner), and so does the file MeshLab reads
        let run = splinekit(&["subdivide", &input, "-n", "1", "-o", &file("1.ply"), "--json"]);
        let json: Value = serde_json::from_str(run.ok()).unwrap();
        assert!(json.get("written_vertices").is_none(), "{json}");
        let ply = splinekit_io::mesh::load_mesh(file("1.ply")).unwrap().mesh;
        assert_eq!(ply.num_vertices(), json["vertices"].as_u64().unwrap() as usize);
        let info = splinekit(&["info", &file("1.ply")]).ok().to_owned();
        assert!(info.contains("boundary: none (closed)"), "{info}");
        // the cube's flat normals cannot be held per vertex: left out, with a note
        assert_eq!(run.stderr.contains("written without normals"), name == "cube", "{}", run.stderr);
        // --split-seams: one normal and UV per vertex in OBJ too
        let run = splinekit(&["subdivide", &input, "-n", "1", "-o", &file("s.obj"), "--json", "--split-seams"]);
        let json: Value = serde_json::from_str(run.ok()).unwrap();
        let split = splinekit_io::mesh::load_mesh(file("s.obj")).unwrap().mesh;
        assert_eq!(json["written_vertices"], split.num_vertices(), "{json}");
        assert_eq!(split.uvs.as_ref().unwrap().indices, split.face_vertices);
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// A file without faces is a clear error (#39), and what the reader skips is a warning naming
/// the file.
#[test]
fn points_only_and_skipped_lines() {
    let dir = temp_dir("no-faces");
    let points = dir.join("points.obj");
    std::fs::write(&points, "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n").unwrap();
    let out = dir.join("out.obj");
    let run = splinekit(&["subdivide", points.to_str().unwrap(), "-n", "1", "-o", out.to_str().unwrap()]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.fails(),
        format!(
            "warning: {0}: line 4: skipped 1 \"p\" statement (points are not read)\n\
             error: {0} has no faces (3 vertices): subdivide needs faces\n",
            points.display()
        )
    );
    assert!(!out.exists());
    let lines = dir.join("lines.obj");
    std::fs::write(&lines, "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\nf 1 2 3\n").unwrap();
    let run = splinekit(&["subdivide", lines.to_str().unwrap(), "-n", "1", "--json"]);
    assert_eq!(run.json()["faces"], 4);
    assert_eq!(
        run.stderr,
        format!(
            "warning: {}: line 4: skipped 2 \"l\" statements, the first on this line (lines are not read)\n",
            lines.display()
        )
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// Issue #39: Loop and Catmull-Clark subdivide non-manifold and degenerate meshes (as
/// OpenSubdiv does); the other schemes refuse them with a message naming the face, edge or
/// vertex and a flag that works, which is then tried.
#[test]
fn nonmanifold_meshes_and_the_flags_that_work() {
    let dir = temp_dir("nonmanifold");
    let out = dir.join("out.obj");
    let out_s = out.to_str().unwrap();
    // three triangles on the edge 1–2 and a triangle 4 4 5 that repeats a vertex: 10 edges (the
    // degenerate one, and the side 4–5 twice)
    let fin = dir.join("fin.obj");
    std::fs::write(&fin, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\nf 4 4 5\n").unwrap();
    let fin_s = fin.to_str().unwrap();
    for (scheme, counts) in [("loop", (5 + 10, 16)), ("catmull-clark", (5 + 10 + 4, 12))] {
        for limit in [&[][..], &["--limit"]] {
            let mut args = vec!["subdivide", fin_s, "-n", "1", "--scheme", scheme, "-o", out_s];
            args.extend_from_slice(limit);
            splinekit(&args).ok();
            assert_eq!(obj_counts(&out), counts, "{scheme} {limit:?}");
        }
    }
    // the repeated vertex: --split-nonmanifold does not mend it, so the message points to the
    // schemes that take it
    for scheme in ["sqrt3", "doo-sabin", "butterfly"] {
        let _ = std::fs::remove_file(&out);
        let err = splinekit(&["subdivide", fin_s, "-n", "1", "--scheme", scheme, "-o", out_s]).fails().to_owned();
        assert!(err.contains("face 3 repeats vertex 3"), "{err}");
        assert!(err.contains("--split-nonmanifold does not mend it") && err.contains("--scheme loop"), "{err}");
        assert!(!out.exists());
        let split = ["subdivide", fin_s, "-n", "1", "--scheme", scheme, "--split-nonmanifold", "-o", out_s];
        assert!(splinekit(&split).fails().contains("face 3 repeats vertex 3"));
    }
    splinekit(&["subdivide", fin_s, "-n", "1", "--scheme", "loop", "-o", out_s]).ok();
    // without the degenerate face, --split-nonmanifold mends the edge, as the message says
    let edge = dir.join("edge.obj");
    std::fs::write(&edge, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n").unwrap();
    let edge_s = edge.to_str().unwrap();
    for scheme in ["sqrt3", "doo-sabin", "butterfly"] {
        let err = splinekit(&["subdivide", edge_s, "-n", "1", "--scheme", scheme, "-o", out_s]).fails().to_owned();
        assert!(err.contains("edge 0–1") && err.contains("--split-nonmanifold"), "{err}");
        splinekit(&["subdivide", edge_s, "-n", "1", "--scheme", scheme, "--split-nonmanifold", "-o", out_s]).ok();
    }
    // `--limit` equals OpenSubdiv's limit after the same levels (the core's reference data), also
    // on a manifold pillow whose levels have two edges between the same two vertices
    let data = format!("{}/../splinekit/tests/data/nonmanifold", env!("CARGO_MANIFEST_DIR"));
    let points = |path: &str| -> Vec<[f64; 3]> {
        let text = std::fs::read_to_string(path).unwrap();
        let v = text.lines().filter_map(|l| l.strip_prefix("v "));
        v.map(|l| {
            let c: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            [c[0], c[1], c[2]]
        })
        .collect()
    };
    for (name, scheme, peer) in
        [("pillow", "loop", "loop"), ("fins3", "catmull-clark", "catmark"), ("poles", "catmull-clark", "catmark")]
    {
        let input = format!("{data}/{name}.in.obj");
        splinekit(&["subdivide", &input, "-n", "2", "--scheme", scheme, "--limit", "-o", out_s]).ok();
        let (ours, theirs) = (points(out_s), points(&format!("{data}/{name}.osd-{peer}.limit.l2.obj")));
        assert_eq!(ours.len(), theirs.len(), "{name}");
        let far = |p: &[f64; 3]| {
            theirs.iter().map(|q| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()).fold(f64::INFINITY, f64::min)
        };
        assert!(ours.iter().all(|p| far(p) < 1e-24), "{name} {scheme}: a vertex is off OpenSubdiv's limit");
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// The largest distance from a point of `ours` to the nearest point of `theirs`, as a fraction
/// of the diagonal of `theirs`' bounding box.
fn relative_distance(ours: &[[f64; 3]], theirs: &[[f64; 3]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in theirs {
        for k in 0..3 {
            (lo[k], hi[k]) = (lo[k].min(p[k]), hi[k].max(p[k]));
        }
    }
    let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let nearest = |p: &[f64; 3]| {
        theirs.iter().map(|q| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()).fold(f64::INFINITY, f64::min)
    };
    ours.iter().map(|p| nearest(p).sqrt()).fold(0.0, f64::max) / diagonal
}

/// Issue #39: OpenSubdiv's options that users set, against OpenSubdiv (the core's reference
/// data, `bench/make_options_references.sh`) at levels 1 to 3 — `--cc-triangles smooth`
/// (TRI_SUB_SMOOTH), `--scheme bilinear`, and the tags `t interpolateboundary`,
/// `t creasemethod` and `t smoothtriangles` read from the input — to 1e-12 of the diagonal;
/// flags given override the tags.
#[test]
fn opensubdiv_options_from_flags_and_tags() {
    let dir = temp_dir("osd-options");
    let out = dir.join("out.obj");
    let out_s = out.to_str().unwrap();
    let data = format!("{}/../splinekit/tests/data/options", env!("CARGO_MANIFEST_DIR"));
    let cases: [(&str, &str, &[&str]); 4] = [
        ("gridmix", "osd-smooth", &["--scheme", "catmull-clark", "--cc-triangles", "smooth"]),
        ("prism8", "osd-bilinear", &["--scheme", "bilinear"]),
        ("gridmix", "osd-bilinear", &["--scheme", "bilinear"]),
        // corners, uniform creasing and smooth triangles from its tags
        ("tagged", "osd", &["--scheme", "catmull-clark"]),
    ];
    for (name, peer, flags) in cases {
        let input = format!("{data}/{name}.in.obj");
        for level in ["1", "2", "3"] {
            splinekit(&[&["subdivide", &input, "-n", level, "-o", out_s][..], flags].concat()).ok();
            let reference = dir.join("reference.obj");
            std::fs::copy(format!("{data}/{name}.{peer}.l{level}.obj"), &reference).unwrap();
            assert_eq!(obj_counts(&out), obj_counts(&reference), "{name} {flags:?} -n {level}");
            let error = relative_distance(&obj_points(&out), &obj_points(&reference));
            assert!(error < 1e-12, "{name} {flags:?} -n {level}: {error:.1e} off OpenSubdiv");
        }
    }
    // a flag given overrides the file's tag: each moves the surface off the reference
    let tagged = format!("{data}/tagged.in.obj");
    let reference = obj_points(Path::new(&format!("{data}/tagged.osd.l2.obj")));
    for flag in [["--boundary", "smooth"], ["--creasing", "chaikin"], ["--cc-triangles", "catmark"]] {
        splinekit(&[&["subdivide", &tagged, "-n", "2", "--scheme", "catmull-clark", "-o", out_s][..], &flag].concat())
            .ok();
        let error = relative_distance(&obj_points(&out), &reference);
        assert!(error > 1e-6, "{flag:?} did not override the tag ({error:.1e} off the tagged reference)");
    }
    // options a scheme has no use for are refused, tags it has no use for ignored with a warning
    let gridmix = format!("{data}/gridmix.in.obj");
    let refused: [(&[&str], &str); 4] = [
        (&["--scheme", "loop", "--cc-triangles", "smooth"], "--cc-triangles chooses Catmull-Clark's edge points"),
        (&["--scheme", "bilinear", "--boundary", "corners"], "bilinear subdivision moves no vertex"),
        (&["--scheme", "bilinear", "--limit"], "the bilinear surface is its polygons"),
        (&["--scheme", "bilinear", "--creasing", "uniform"], "bilinear subdivision has no creases"),
    ];
    for (flags, message) in refused {
        let err = splinekit(&[&["subdivide", &gridmix, "-n", "1", "-o", out_s][..], flags].concat()).fails().to_owned();
        assert!(err.contains(message), "{flags:?}: {err}");
    }
    let run = splinekit(&["subdivide", &tagged, "-n", "1", "--scheme", "bilinear", "-o", out_s]);
    run.ok();
    assert!(
        run.stderr.contains("its interpolateboundary, creasemethod, smoothtriangles tags are ignored: bilinear"),
        "{}",
        run.stderr
    );
    // no boundary interpolation (VTX_BOUNDARY_NONE): the faces at the boundary are left out as
    // OpenSubdiv leaves them (the vertices stay), for Catmull-Clark with an infinitely sharp
    // crease along one side (whose faces stay) and for Loop; --limit is refused there
    let grid32 = dir.join("grid32.obj");
    let loop_grid = std::fs::read_to_string(format!("{data}/grid32.in.obj")).unwrap();
    std::fs::write(&grid32, format!("{loop_grid}t interpolateboundary 1/0/0 0\n")).unwrap();
    let grid32_s = grid32.to_str().unwrap().to_owned();
    let holes = format!("{data}/holes.in.obj");
    for (input, scheme, reference) in [(&holes, "catmull-clark", "holes.osd"), (&grid32_s, "loop", "grid32.osd-none")] {
        for level in ["1", "2", "3"] {
            splinekit(&["subdivide", input, "-n", level, "--scheme", scheme, "-o", out_s]).ok();
            let theirs = format!("{data}/{reference}.l{level}.obj");
            assert_eq!(obj_counts(&out), obj_counts(Path::new(&theirs)), "{reference} -n {level}");
            let error = relative_distance(&obj_points(&out), &obj_points(Path::new(&theirs)));
            assert!(error < 1e-12, "{reference} -n {level}: {error:.1e} off OpenSubdiv");
        }
        let err =
            splinekit(&["subdivide", input, "-n", "1", "--scheme", scheme, "--limit", "-o", out_s]).fails().to_owned();
        assert!(err.contains("--limit") && err.contains("holes"), "{err}");
        // --boundary overrides it: every face is there
        splinekit(&["subdivide", input, "-n", "1", "--scheme", scheme, "--boundary", "smooth", "-o", out_s]).ok();
        let (_, faces) = obj_counts(&out);
        let (_, holed) = obj_counts(Path::new(&format!("{data}/{reference}.l1.obj")));
        assert!(faces > holed, "{reference}: --boundary smooth left {faces} faces");
    }
    // --help describes the new options
    let help = splinekit(&["subdivide", "--help"]).ok().to_owned();
    for text in ["--cc-triangles", "TRI_SUB_SMOOTH", "bilinear", "t interpolateboundary", "t creasemethod"] {
        assert!(help.contains(text), "--help lacks {text:?}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// Nothing is dropped without a word (#39): where the scheme, or the non-manifold path, does not
/// carry the input's texture coordinates, `subdivide` says so and names the file written; a
/// scheme that carries them says nothing and writes them.
#[test]
fn attributes_a_scheme_drops_are_named() {
    let dir = tempfile::tempdir().unwrap();
    // three triangles on one edge (non-manifold), and a tetrahedron, both with UVs
    let fin = dir.path().join("fin.obj");
    std::fs::write(
        &fin,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n\
         f 1/1 2/2 3/3\nf 2/2 1/1 4/3\nf 1/1 2/2 5/3\n",
    )
    .unwrap();
    let tet = dir.path().join("tet.obj");
    std::fs::write(
        &tet,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n\
         f 1/1 3/3 2/2\nf 1/1 2/2 4/3\nf 1/1 4/3 3/3\nf 2/2 3/3 4/3\n",
    )
    .unwrap();
    let out = dir.path().join("out.obj");
    let run = |file: &Path, scheme: &str| {
        splinekit(&[
            "subdivide".as_ref(),
            file.as_os_str(),
            "-n".as_ref(),
            "1".as_ref(),
            "--scheme".as_ref(),
            scheme.as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
    };
    for (file, scheme, dropped) in [
        (&fin, "loop", true),
        (&tet, "catmull-clark", true),
        (&tet, "loop", false),
        (&tet, "sqrt3", false),
        (&tet, "butterfly", false),
        (&tet, "bilinear", false),
    ] {
        let r = run(file, scheme);
        r.ok();
        let written = std::fs::read_to_string(&out).unwrap();
        let has_uvs = written.lines().any(|l| l.starts_with("vt "));
        assert_eq!(has_uvs, !dropped, "{scheme} on {}", file.display());
        assert_eq!(
            r.stderr.contains("does not carry its texture coordinates; ")
                && r.stderr.contains("out.obj written without them"),
            dropped,
            "{scheme} on {}: {}",
            file.display(),
            r.stderr
        );
    }
}
