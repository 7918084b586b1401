//! `splinekit sweep FILE.obj`: rebuilding the surface of a spline-annotated OBJ file (the CS
//! 4620 revolution and sweep tools) from its header, run through the binary.
//!
//! The bundled sweep-tool files are rebuilt with `--compat` and the written OBJ is compared
//! with the mesh stored in the input (read by a small reader here, independent of the
//! crates): same counts, same triangles, positions within the files' six decimals.

use std::fs;
use std::path::{Path, PathBuf};

mod common;
use common::{entries, read_obj, report_line, splinekit, sweep};

// ---------------------------------------------------------------------------------------
// Harness (the rest is shared: tests/common)

/// The bundled spline-annotated OBJ files: the io crate's test data, else the shared data.
fn annotated_objs() -> Vec<PathBuf> {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = [
        crate_dir.join("../splinekit-io/tests/data/obj/cs4620-splines"),
        crate_dir.join("../../../shared/data/obj/cs4620-splines"),
        crate_dir.join("../../shared/data/obj/cs4620-splines"),
    ];
    let dir = candidates
        .iter()
        .find(|d| d.join("doughnut.obj").is_file())
        .unwrap_or_else(|| panic!("no doughnut.obj in any of {candidates:?}"));
    let mut files: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 4, "{files:?}");
    files
}

// ---------------------------------------------------------------------------------------
// Tests

#[test]
fn compat_rebuild_of_every_bundled_file_is_its_stored_mesh() {
    let out = tempfile::tempdir().unwrap();
    for input in annotated_objs() {
        let stem = input.file_stem().unwrap().to_string_lossy().into_owned();
        let run = sweep(&input, out.path(), &["--compat"]);
        let written = out.path().join(format!("{stem}.obj"));
        let (stored_v, stored_f) = read_obj(&input);
        assert_eq!(run.ok(), report_line(&written, stored_v.len(), stored_f.len()), "{stem}");
        let (v, f) = read_obj(&written);
        assert_eq!((v.len(), f.len()), (stored_v.len(), stored_f.len()), "{stem}");
        assert!(f == stored_f, "{stem}: triangles differ");
        let error =
            v.iter().zip(&stored_v).flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs())).fold(0.0, f64::max);
        assert!(error <= 5e-6, "{stem}: positions differ by {error:e}");
        // the output has no spline header: it is a plain mesh
        assert!(!fs::read_to_string(&written).unwrap().contains("Cross-section"), "{stem}");
    }
}

#[test]
fn welded_rebuild_and_other_formats() {
    let out = tempfile::tempdir().unwrap();
    let doughnut = annotated_objs().into_iter().find(|p| p.ends_with("doughnut.obj")).unwrap();
    // 80 cross-section samples × 80 swept-along samples, seams shared: a watertight torus
    let obj = out.path().join("doughnut.obj");
    assert_eq!(sweep(&doughnut, out.path(), &[]).ok(), report_line(&obj, 6400, 12800));
    let (v, f) = read_obj(&obj);
    assert_eq!((v.len(), f.len()), (6400, 12800));
    let mut edges = std::collections::HashMap::new();
    for t in &f {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    assert!(edges.keys().all(|&(a, b)| edges.get(&(b, a)) == Some(&1)), "not closed and oriented");

    let run = sweep(&doughnut, out.path(), &["--format", "stl", "--compat"]);
    let stl = out.path().join("doughnut.stl");
    assert_eq!(run.ok(), report_line(&stl, 6561, 12800));
    assert_eq!(fs::metadata(&stl).unwrap().len(), 84 + 50 * 12800);
    let run = sweep(&doughnut, out.path(), &["--format", "glb", "--uvs"]);
    assert!(run.ok().starts_with(&format!("{}: ", out.path().join("doughnut.glb").display())));
    assert_eq!(entries(out.path()), ["doughnut.glb", "doughnut.obj", "doughnut.stl"]);
    // deterministic: the same bytes again
    let before = fs::read(&obj).unwrap();
    sweep(&doughnut, out.path(), &[]).ok();
    assert!(fs::read(&obj).unwrap() == before);
}

#[test]
fn revolution_tool_file() {
    let dir = tempfile::tempdir().unwrap();
    // as the Java revolution tool writes it, with a stand-in mesh after the header
    let text = "# This mesh is a Surface of Revolution: the comments below describe a Spline (cross-section) swept along\n\
                # an axis that generated this mesh.\n#\n\
                # Configs: closed, epsilon, isBSpline, Scale, sliceTolerance\n\
                # true 0.3 false 1.5 0.1\n#\n\
                # Cross-section Spline control points: \n\
                # 1.0 0.0\n# 1.5 -0.4\n# 2.0 0.0\n# 1.8 0.5\n# 1.2 0.4\n\
                v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let input = dir.path().join("Ring Vase.OBJ");
    fs::write(&input, text).unwrap();
    let out = dir.path().join("out");
    let run = sweep(&input, &out, &[]);
    // ceil(2π / 0.1) = 63 slices of a closed profile: a watertight ring, 2 triangles per vertex
    let written = out.join("Ring_Vase.obj");
    let (v, f) = read_obj(&written);
    assert_eq!(run.ok(), report_line(&written, v.len(), f.len()));
    assert_eq!(v.len() % 63, 0);
    assert_eq!(f.len(), 2 * v.len());
    // scale 1.5: radii from 1.5·min x to 1.5·max x of the closed Catmull-Rom (through its points)
    let r: Vec<f64> = v.iter().map(|p| p[0].hypot(p[1])).collect();
    assert!((r.iter().cloned().fold(f64::INFINITY, f64::min) - 1.5).abs() < 0.05, "{r:?}");
    assert!((r.iter().cloned().fold(0.0, f64::max) - 3.0).abs() < 0.05);
    // --compat gives the same mesh for a revolution-tool file
    let compat = dir.path().join("compat");
    sweep(&input, &compat, &["--compat"]).ok();
    assert!(fs::read(compat.join("Ring_Vase.obj")).unwrap() == fs::read(&written).unwrap());
}

#[test]
fn obj_without_a_spline_header_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let plain = dir.path().join("cube.obj");
    fs::write(&plain, "# Blender v2.79 OBJ File\no Cube\nv 1 1 1\nv 0 1 1\nv 0 0 1\nf 1 2 3\n").unwrap();
    let out = dir.path().join("out");
    let stderr = sweep(&plain, &out, &[]).fails_with_error().to_string();
    assert!(stderr.contains("cube.obj: no spline header found"), "{stderr}");
    assert!(stderr.contains("# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance"), "{stderr}");
    assert!(stderr.contains("Swept-along"), "{stderr}");
    assert!(entries(&out).is_empty(), "nothing written");
}

#[test]
fn broken_header_and_bad_splines_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let doughnut = annotated_objs().into_iter().find(|p| p.ends_with("doughnut.obj")).unwrap();
    let text = fs::read_to_string(&doughnut).unwrap();

    let bad = dir.path().join("bad.obj");
    fs::write(&bad, text.replacen("# 0.809017 -0.58778524", "# 0.809017 -0.58x", 1)).unwrap();
    let stderr = sweep(&bad, &out, &[]).fails_with_error().to_string();
    assert!(
        stderr.contains(
            "bad.obj:10:12: found \"-0.58x\", expected a number (y coordinate of cross-section control point 3)"
        ),
        "{stderr}"
    );

    // two swept-along points: too few for a closed B-spline
    let i = text.find("# Swept-along Spline control points:").unwrap();
    let short: String = text[..i].to_string() + "# Swept-along Spline control points:\n# 0.0 1.0\n# 1.0 0.0\nv 0 0 0\n";
    let few = dir.path().join("few.obj");
    fs::write(&few, short).unwrap();
    let stderr = sweep(&few, &out, &[]).fails_with_error().to_string();
    assert!(stderr.contains("few.obj"), "{stderr}");
    assert!(stderr.contains("swept-along spline: b-spline needs at least 3 control points, got 2"), "{stderr}");

    let missing = dir.path().join("missing.obj");
    assert!(sweep(&missing, &out, &[]).fails_with_error().contains("missing.obj"));
    assert!(entries(&out).is_empty(), "nothing written");
}

#[test]
fn swp_only_flags_are_refused_and_the_input_is_never_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    let doughnut = annotated_objs().into_iter().find(|p| p.ends_with("doughnut.obj")).unwrap();
    let input = dir.path().join("doughnut.obj");
    fs::copy(&doughnut, &input).unwrap();
    let out = dir.path().join("out");
    for (flags, name) in [
        (&["--tolerance", "0.01"][..], "--tolerance"),
        (&["--angle-tolerance", "5"][..], "--angle-tolerance"),
        (&["--frames", "rmf"][..], "--frames"),
        (&["--frames", "sequential"][..], "--frames"),
    ] {
        let stderr = sweep(&input, &out, flags).fails_with_error().to_string();
        assert!(stderr.contains(&format!("{name} does not apply to")), "{stderr}");
    }
    assert!(entries(&out).is_empty());
    // writing next to the input, in the input's format, would replace it: refused
    let before = fs::read(&input).unwrap();
    let stderr = sweep(&input, dir.path(), &[]).fails_with_error().to_string();
    assert!(stderr.contains("would overwrite the input file"), "{stderr}");
    assert!(fs::read(&input).unwrap() == before);
    // another format next to it is fine; --no-caps is accepted (rebuilt sweeps have no caps)
    sweep(&input, dir.path(), &["--format", "ply", "--no-caps"]).ok();
    assert!(dir.path().join("doughnut.ply").is_file());
}

#[test]
fn help_describes_obj_input() {
    let help = splinekit(&["sweep", "--help"]).ok().to_string();
    for word in ["spline-annotated OBJ", "Configs:", "Cross-section:", "--compat", "doughnut.obj", "SWP only"] {
        assert!(help.contains(word), "sweep help lacks {word:?}:\n{help}");
    }
    // an SWP file still works as before
    let dir = tempfile::tempdir().unwrap();
    let swp = dir.path().join("ring.swp");
    fs::write(&swp, "circ p 8 0.5\ncirc s 12 2\ngcyl torus p s\n").unwrap();
    let run = sweep(&swp, dir.path(), &["--compat"]);
    assert_eq!(run.ok(), report_line(&dir.path().join("torus.obj"), 9 * 13, 2 * 8 * 12));
}

/// `sweep FILE.swp --format obj --annotated`: one revolution-tool OBJ per zrev surface, whose
/// header the tool's layout holds (the lines it writes, in its order), and which reads back
/// (`sweep x.obj`) to the same mesh; surfaces the header cannot describe are refused before
/// anything is written.
#[test]
fn annotated_obj_from_swp_reads_back_to_the_same_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let swp = dir.path().join("vases.swp");
    fs::write(
        &swp,
        "bsp2 profile 10 6 [0 -1] [1.2 -1] [0.4 0] [0.5 0.6] [1.2 1.2] [1.3 1.4]\n\
         cr2 ring 10 4 closed [1 0] [2 -0.5] [2.5 0] [2 0.5]\n\
         zrev vase profile epsilon 0.1 slice-tolerance 0.2 scale 2\n\
         zrev torus ring\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let run = sweep(&swp, &out, &["--format", "obj", "--annotated"]);
    let lines: Vec<&str> = run.ok().lines().collect();
    assert_eq!(lines.len(), 2, "{lines:?}");
    for (stem, closed, bspline) in [("vase", "false", "true"), ("torus", "true", "false")] {
        let written = out.join(format!("{stem}.obj"));
        let text = fs::read_to_string(&written).unwrap();
        let head: Vec<&str> = text.lines().take(7).collect();
        assert_eq!(
            head[0],
            "# This mesh is a Surface of Revolution: the comments below describe a Spline (cross-section) swept along"
        );
        assert_eq!(head[3], "# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance");
        assert!(head[4].starts_with(&format!("# {closed} ")) && head[4].contains(&format!(" {bspline} ")), "{head:?}");
        assert_eq!(head[6], "# Cross-section Spline control points: ");
        // read back: the header rebuilt gives the mesh stored after it, byte for byte
        let back = dir.path().join("back");
        let rebuilt = sweep(&written, &back, &[]);
        let (v, f) = read_obj(&written);
        assert_eq!(rebuilt.ok(), report_line(&back.join(format!("{stem}.obj")), v.len(), f.len()));
        let stored: String = text.lines().filter(|l| !l.starts_with('#')).map(|l| format!("{l}\n")).collect();
        assert!(fs::read_to_string(back.join(format!("{stem}.obj"))).unwrap() == stored, "{stem}");
    }
    // the closed Catmull-Rom ring: ceil(2π / (2π/32)) = 32 slices, watertight
    let (v, f) = read_obj(&out.join("torus.obj"));
    assert_eq!((v.len() % 32, f.len()), (0, 2 * v.len()));

    // an srev cannot be described: an error naming it, and no file
    let mixed = dir.path().join("mixed.swp");
    fs::write(&mixed, "bsp2 p 10 4 [1 -1] [2 -1] [2 1] [1 1]\nzrev a p\nsrev glass 16 p\n").unwrap();
    let none = dir.path().join("none");
    let stderr = sweep(&mixed, &none, &["--annotated"]).fails_with_error().to_string();
    assert!(stderr.contains("surface glass cannot be written as an annotated OBJ"), "{stderr}");
    assert!(!none.exists() || entries(&none).is_empty());
    for (flags, says) in [
        (&["--annotated", "--format", "glb"][..], "--format obj"),
        (&["--annotated", "--tolerance", "0.1"][..], "--tolerance"),
    ] {
        let stderr = sweep(&swp, &none, flags).fails_with_error().to_string();
        assert!(stderr.contains(says), "{flags:?}: {stderr}");
    }
}

/// `sweep FILE.obj --annotated` of a sweep-tool file writes the tool's header again, then the
/// rebuilt mesh; `info`-free round trip: the written file rebuilds to the same mesh.
#[test]
fn annotated_rebuild_of_a_sweep_tool_file_keeps_its_header() {
    let out = tempfile::tempdir().unwrap();
    let doughnut = annotated_objs().into_iter().find(|p| p.ends_with("doughnut.obj")).unwrap();
    let first = out.path().join("first");
    sweep(&doughnut, &first, &["--annotated", "--compat"]).ok();
    let written = first.join("doughnut.obj");
    let header = |p: &Path| fs::read_to_string(p).unwrap().lines().take_while(|l| l.starts_with('#')).count();
    assert_eq!(header(&written), header(&doughnut));
    let again = out.path().join("again");
    sweep(&written, &again, &["--compat"]).ok();
    let stored: String = fs::read_to_string(&written)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(fs::read_to_string(again.join("doughnut.obj")).unwrap() == stored);
}
