//! `splinekit sweep FILE.swp` and `splinekit info FILE.swp`, run through the binary on the
//! bundled course files: one file per surface named after it (`surface_<k>` when anonymous),
//! one report line per surface, the counts of SPEC §2.3 with `--compat`, the written meshes
//! read back by a small reader here (independent of the crates), every format, adaptive
//! tessellation, and the refusals that leave no file behind.

use std::collections::HashMap;
use std::fs;
use std::path::PathBuf;

mod common;
use common::{course_swp, entries, read_obj, report_line, splinekit, sweep, swp_dir};

// ---------------------------------------------------------------------------------------
// Harness (the rest is shared: tests/common)

/// The output file stems of a plain SWP file's surfaces, read from its tokens (in the
/// course files the words `srev` and `gcyl` occur only as keywords): the name after the
/// keyword, or `surface_<k>` for `.`, k counting the surfaces from 0.
fn surface_stems(text: &str) -> Vec<String> {
    let tokens: Vec<&str> = text.split_whitespace().collect();
    let names = tokens.windows(2).filter(|w| w[0] == "srev" || w[0] == "gcyl").map(|w| w[1]);
    names.enumerate().map(|(k, name)| if name == "." { format!("surface_{k}") } else { name.to_string() }).collect()
}

/// Directed edges of the triangles, counted.
fn directed_edges(triangles: &[[u32; 3]]) -> HashMap<(u32, u32), usize> {
    let mut edges = HashMap::new();
    for t in triangles {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    edges
}

/// Six times the signed volume enclosed by the triangles.
fn six_volume(positions: &[[f64; 3]], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum()
}

/// `(vertices, triangles)` from a report line `PATH: V vertices, T triangles`.
fn counts_of(line: &str) -> (usize, usize) {
    let (_, rest) = line.rsplit_once(": ").unwrap();
    let words: Vec<&str> = rest.split_whitespace().collect();
    assert_eq!((words.len(), words[1], words[3]), (4, "vertices,", "triangles"), "{line}");
    (words[0].parse().unwrap(), words[2].parse().unwrap())
}

// ---------------------------------------------------------------------------------------
// Tests

#[test]
fn every_course_file_sweeps_one_file_per_surface_with_spec_counts_in_compat() {
    // SPEC §2.3
    let spec: HashMap<&str, (usize, usize)> = [
        ("srev/norm.swp", (4590, 9000)),
        ("srev/wineglass.swp", (16650, 33120)),
        ("gcyl/tor.swp", (1891, 3600)),
        ("gcyl/gentorus.swp", (3321, 6400)),
        ("gcyl/florus.swp", (7686, 15000)),
        ("gcyl/flircle.swp", (25551, 50000)),
        ("gcyl/weird.swp", (8385, 16384)),
        ("gcyl/weirder.swp", (5537, 10752)),
    ]
    .into();
    let dir = swp_dir();
    for file in course_swp() {
        let file = file.as_str();
        let input = dir.join(file);
        let stems = surface_stems(&fs::read_to_string(&input).unwrap());
        for compat in [true, false] {
            let out = tempfile::tempdir().unwrap();
            let run = sweep(&input, out.path(), if compat { &["--compat"] } else { &[] });
            if stems.is_empty() {
                // curves only: a clear error, and nothing written
                assert!(run.fails_with_error().contains("has no surfaces"), "{file}: {}", run.stderr);
                assert!(entries(out.path()).is_empty(), "{file}");
                continue;
            }
            let lines: Vec<&str> = run.ok().lines().collect();
            assert_eq!(lines.len(), stems.len(), "{file}: one line per surface\n{}", run.stdout);
            let mut expected_files: Vec<String> = stems.iter().map(|s| format!("{s}.obj")).collect();
            expected_files.sort();
            assert_eq!(entries(out.path()), expected_files, "{file}");
            for (line, stem) in lines.iter().zip(&stems) {
                let path = out.path().join(format!("{stem}.obj"));
                let (v, t) = counts_of(line);
                assert_eq!(format!("{line}\n"), report_line(&path, v, t), "{file}");
                let (positions, triangles) = read_obj(&path);
                assert_eq!((positions.len(), triangles.len()), (v, t), "{file}: the report and the file agree");
                assert!(triangles.iter().flatten().all(|&i| (i as usize) < v), "{file}: index out of range");
                if compat && let Some(&counts) = spec.get(file) {
                    assert_eq!((v, t), counts, "{file}: SPEC §2.3");
                }
            }
        }
    }
}

#[test]
fn welded_closed_surfaces_are_watertight_and_outward_as_written() {
    let dir = swp_dir();
    for file in [
        "srev/wineglass.swp",
        "gcyl/tor.swp",
        "gcyl/gentorus.swp",
        "gcyl/florus.swp",
        "gcyl/weird.swp",
        "gcyl/weirder.swp",
    ] {
        let out = tempfile::tempdir().unwrap();
        let line = sweep(&dir.join(file), out.path(), &[]).ok().to_string();
        let path = PathBuf::from(line.rsplit_once(": ").unwrap().0);
        let (positions, triangles) = read_obj(&path);
        let edges = directed_edges(&triangles);
        // every directed edge once, and its reverse once: closed, 2-manifold, consistently oriented
        assert!(edges.iter().all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1)), "{file}");
        assert!(six_volume(&positions, &triangles) > 0.0, "{file}: faces point inwards");
    }
}

#[test]
fn formats_name_their_files_and_hold_the_reported_counts() {
    let wineglass = swp_dir().join("srev/wineglass.swp");
    let out = tempfile::tempdir().unwrap();
    let line = |format: &str| {
        let run = sweep(&wineglass, out.path(), &["--compat", "--format", format]);
        let path = out.path().join(format!("wineglass.{format}"));
        assert_eq!(run.ok(), report_line(&path, 16650, 33120), "{format}");
        fs::read(path).unwrap()
    };
    let stl = line("stl");
    assert_eq!(stl.len(), 84 + 50 * 33120);
    assert_eq!(u32::from_le_bytes(stl[80..84].try_into().unwrap()), 33120);
    let ply = line("ply");
    let header =
        String::from_utf8_lossy(&ply[..ply.windows(10).position(|w| w == b"end_header").unwrap()]).into_owned();
    assert!(header.starts_with("ply\nformat binary_little_endian 1.0\n"), "{header}");
    assert!(header.contains("element vertex 16650\n") && header.contains("element face 33120\n"), "{header}");
    let glb = line("glb");
    assert_eq!(&glb[..4], b"glTF");
    assert_eq!(u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize, glb.len());
    line("obj");
    assert_eq!(entries(out.path()), ["wineglass.glb", "wineglass.obj", "wineglass.ply", "wineglass.stl"]);
    // deterministic: the same bytes again
    let before = fs::read(out.path().join("wineglass.obj")).unwrap();
    line("obj");
    assert!(fs::read(out.path().join("wineglass.obj")).unwrap() == before);
}

#[test]
fn adaptive_tessellation_and_frames() {
    let tor = swp_dir().join("gcyl/tor.swp");
    let out = tempfile::tempdir().unwrap();
    let triangles = |args: &[&str]| counts_of(sweep(&tor, out.path(), args).ok().trim_end()).1;
    let (coarse, fine) = (triangles(&["--tolerance", "0.01"]), triangles(&["--tolerance", "0.0001"]));
    assert!(coarse < fine, "a finer tolerance gives more triangles: {coarse} against {fine}");
    let (wide, narrow) = (triangles(&["--angle-tolerance", "10"]), triangles(&["--angle-tolerance", "2"]));
    assert!(wide < narrow, "a finer angle gives more triangles: {wide} against {narrow}");
    // tor.swp sweeps a circle along a circle: its frames make no difference to the counts
    assert_eq!(triangles(&["--frames", "rmf"]), triangles(&["--frames", "sequential"]));

    for (args, expected) in [
        (&["--tolerance", "0"][..], "--tolerance must be a positive number"),
        (&["--tolerance", "nan"][..], "--tolerance must be a positive number"),
        (&["--angle-tolerance", "-3"][..], "--angle-tolerance must be a positive number"),
    ] {
        let run = sweep(&tor, out.path(), args);
        assert!(run.fails_with_error().contains(expected), "{args:?}: {}", run.stderr);
    }
    // one tessellation at a time: a usage error
    let run = sweep(&tor, out.path(), &["--tolerance", "0.1", "--angle-tolerance", "5"]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
}

#[test]
fn a_mesh_over_the_triangle_limit_is_refused_before_it_is_built() {
    let dir = swp_dir();
    let out = tempfile::tempdir().unwrap();
    let wineglass = dir.join("srev/wineglass.swp");
    // 90 slices of a 185-point profile: 33120 triangles, exactly the limit
    let ok = sweep(&wineglass, out.path(), &["--compat", "--max-triangles", "33120"]);
    assert_eq!(ok.ok(), report_line(&out.path().join("wineglass.obj"), 16650, 33120));
    let empty = tempfile::tempdir().unwrap();
    let run = sweep(&wineglass, empty.path(), &["--compat", "--max-triangles", "33119"]);
    let message = run.fails_with_error();
    assert!(
        message.contains("wineglass would have about 33120 triangles (90 slices of a 185-point profile)")
            && message.contains("more than the limit of 33119")
            && message.contains("--max-triangles"),
        "{message}"
    );
    assert!(entries(empty.path()).is_empty());

    // A typo found by mutating the course files: one profile point at x = 9000000 makes the
    // glass nine million units wide, and a tolerance of 0.01 would need some 368 million
    // triangles (gigabytes of memory and of OBJ text); the default limit refuses it at once.
    let text = fs::read_to_string(&wineglass).unwrap();
    let typo = text.replacen("[0.000000 -2.458800]", "[9000000 -2.458800]", 1);
    assert_ne!(typo, text);
    let input = empty.path().join("typo.swp");
    fs::write(&input, typo).unwrap();
    let run = sweep(&input, empty.path(), &["--tolerance", "0.01"]);
    let message = run.fails_with_error();
    assert!(
        message.contains("more than the limit of 50000000") && message.contains("coarser --tolerance"),
        "{message}"
    );
    assert_eq!(entries(empty.path()), ["typo.swp"]);

    // absurd steps in the file itself (20000 a segment and 20000 slices: 800 million
    // triangles): refused by `sweep`, `render` and `info` alike, the reason said once
    let big = empty.path().join("big.swp");
    fs::write(&big, "bsp2 p 20000 4 [1 0] [2 1] [1 2] [2 3]\nsrev big 20000 p\n").unwrap();
    let why = "surface big would have about 800000000 triangles (20000 slices of a 20001-point profile), \
               more than the limit of 50000000";
    let message = sweep(&big, empty.path(), &[]).fails_with_error().to_string();
    assert!(message.contains(why), "{message}");
    let png = empty.path().join("big.png");
    let run = splinekit(&[std::ffi::OsStr::new("render"), big.as_os_str(), "-o".as_ref(), png.as_os_str()]);
    let message = run.fails_with_error();
    // a picture has a smaller budget: 20 million triangles for the whole scene
    let drawn = why.replace("limit of 50000000", "limit of 20000000");
    assert_eq!(message.matches(&drawn).count(), 1, "{message}");
    assert_eq!(entries(empty.path()), ["big.swp", "typo.swp"]);
    let info = splinekit(&[std::ffi::OsStr::new("info"), big.as_os_str()]).ok().to_string();
    assert!(info.contains(&format!("cannot sweep: {why}")), "{info}");
}

#[test]
fn info_lists_curves_and_surfaces_with_both_layouts_counts() {
    let wineglass = swp_dir().join("srev/wineglass.swp");
    let text = splinekit(&[std::ffi::OsStr::new("info"), wineglass.as_os_str()]).ok().to_string();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].ends_with("wineglass.swp: 1 curve, 1 surface"), "{text}");
    assert_eq!(lines[1], "curves:");
    let curve: Vec<&str> = lines[2].split_whitespace().collect();
    assert_eq!(curve[..4], ["0", "profile", "bsp2", "26"], "{text}");
    assert!(lines[2].contains("23 segments, steps 8, open"), "{text}");
    assert_eq!(lines[3], "surfaces:");
    assert!(
        lines[4].contains("srev: profile profile, 90 steps; compat 16650 vertices, 33120 triangles; welded "),
        "{text}"
    );
    // the welded counts are those `sweep` writes
    let out = tempfile::tempdir().unwrap();
    let (v, t) = counts_of(sweep(&wineglass, out.path(), &[]).ok().trim_end());
    assert!(lines[4].ends_with(&format!("welded {v} vertices, {t} triangles")), "{text}");
}

/// A surface's own settings in the file apply, and the matching option on the command line
/// replaces them: the same meshes either way.
#[test]
fn surface_settings_and_the_options_that_replace_them() {
    let dir = tempfile::tempdir().unwrap();
    let curves = "circ ring 12 0.2\nbez3 path 10 4 [0 0 0] [1 0 1] [2 1 1] [3 1 0]\n";
    let own = dir.path().join("own.swp");
    fs::write(&own, format!("{curves}gcyl tube ring path tolerance 0.001 frames rmf no-caps\n")).unwrap();
    let plain = dir.path().join("plain.swp");
    fs::write(&plain, format!("{curves}gcyl tube ring path\n")).unwrap();
    let read = |file: &PathBuf, out: &str, flags: &[&str]| {
        let out = dir.path().join(out);
        sweep(file, &out, flags).ok();
        fs::read(out.join("tube.obj")).unwrap()
    };
    let by_settings = read(&own, "a", &[]);
    assert!(by_settings == read(&plain, "b", &["--tolerance", "0.001", "--frames", "rmf", "--no-caps"]));
    // each option replaces its own setting only: the file's no-caps stays
    assert!(read(&own, "c", &["--tolerance", "0.001", "--frames", "rmf"]) == by_settings);
    let replaced = read(&own, "e", &["--angle-tolerance", "3", "--frames", "sequential"]);
    assert!(replaced == read(&plain, "f", &["--angle-tolerance", "3", "--frames", "sequential", "--no-caps"]));
    assert!(replaced != by_settings);
    read(&plain, "d", &[]);
    let (v, _) = read_obj(&dir.path().join("a/tube.obj"));
    let (w, _) = read_obj(&dir.path().join("d/tube.obj"));
    assert!(v.len() > 4 * w.len(), "the tolerance makes many more vertices: {} vs {}", v.len(), w.len());
}

/// #42: one meaning of "sweep": `sweep`, `info`'s welded count and `render` give a closed
/// profile swept along an open path the same triangles, end caps included (they once
/// differed: `render`, `gallery` and the editor swept without caps).
#[test]
fn sweep_info_and_render_agree_on_caps() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("tube.swp");
    fs::write(&file, "circ ring 12 0.3\nbez3 path 8 4 [0 0 0] [1 0 0] [2 1 0] [2 2 1]\ngcyl tube ring path\n").unwrap();
    let file = file.to_str().unwrap();
    let out = dir.path().join("out");
    let swept = splinekit(&["sweep", file, "-o", out.to_str().unwrap()]).ok().to_owned();
    // 12 profile steps by 9 path samples of walls, and a fan of 10 triangles per cap, on the
    // walls' 12 · 9 vertices
    let walls = 2 * 12 * 8;
    let capped = walls + 2 * 10;
    assert!(swept.contains(&format!("108 vertices, {capped} triangles")), "{swept}");
    let info = splinekit(&["info", file]).ok().to_owned();
    assert!(info.contains(&format!("welded 108 vertices, {capped} triangles")), "{info}");
    let png = dir.path().join("tube.png");
    let rendered = splinekit(&["render", file, "-o", png.to_str().unwrap(), "--size", "64x48"]).ok().to_owned();
    assert!(rendered.contains(&format!("1 surfaces ({capped} triangles)")), "{rendered}");
    // without caps, all three lose the same 20 triangles
    let open = splinekit(&["sweep", file, "-o", out.to_str().unwrap(), "--no-caps", "--force"]).ok().to_owned();
    assert!(open.contains(&format!("{walls} triangles")), "{open}");
}

/// #42: `--frames frenet|zup` and `--align centre|center|start` are accepted and change the
/// surface (the file's own settings give way to them); a wrong word is refused by name.
#[test]
fn frames_and_align_flags() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bar.swp");
    fs::write(&file, "bsp2 square 2 4 closed [1 0] [2 0] [2 1] [1 1]\nhelix coil 40 1 0.5 1\ngcyl bar square coil\n")
        .unwrap();
    let file = file.to_str().unwrap();
    let read = |flags: &[&str]| {
        let out = dir.path().join(flags.join("_"));
        let mut args = vec!["sweep", file, "-o", out.to_str().unwrap()];
        args.extend_from_slice(flags);
        splinekit(&args).ok();
        fs::read_to_string(out.join("bar.obj")).unwrap()
    };
    let plain = read(&[]);
    for flags in [["--frames", "frenet"], ["--frames", "zup"], ["--align", "centre"], ["--align", "start"]] {
        assert_ne!(read(&flags), plain, "{flags:?} changes nothing");
    }
    assert_eq!(read(&["--align", "center"]), read(&["--align", "centre"]));
    assert_eq!(read(&["--align", "origin"]), plain);
    let run = splinekit(&["sweep", file, "-o", dir.path().join("x").to_str().unwrap(), "--align", "middle"]);
    assert_eq!(run.code, Some(2));
    assert!(run.stderr.contains("possible values: origin, centre, start"), "{}", run.stderr);
}

/// #42: `--scale-mode` replaces the file's own `scale-mode`; `--frames auto` is the default.
#[test]
fn scale_mode_flag() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, setting: &str| {
        let file = dir.path().join(name);
        let text = format!(
            "circ c 12 2\nbez2 s 1 4 [0.5 0.5] [0.4 0.4] [0.3 0.3] [0.2 0.2]\n\
             bez3 l 8 4 [0 0 0] [1 0 0.5] [2 0 0] [3 0 0.5]\ngcyl tube c l scale s{setting}\n"
        );
        fs::write(&file, text).unwrap();
        file.to_str().unwrap().to_owned()
    };
    let (plain, over) = (write("plain.swp", ""), write("over.swp", " scale-mode override"));
    let read = |file: &str, flags: &[&str]| {
        let out = dir.path().join(format!("{}{}", file.len(), flags.join("_")));
        let mut args = vec!["sweep", file, "-o", out.to_str().unwrap()];
        args.extend_from_slice(flags);
        splinekit(&args).ok();
        fs::read_to_string(out.join("tube.obj")).unwrap()
    };
    let multiplied = read(&plain, &[]);
    let overridden = read(&over, &[]);
    assert_ne!(multiplied, overridden);
    assert_eq!(read(&plain, &["--scale-mode", "override"]), overridden);
    assert_eq!(read(&over, &["--scale-mode", "multiply"]), multiplied);
    assert_eq!(read(&plain, &["--frames", "auto"]), multiplied);
    // a distance tolerance bounds the surface with a scale curve made of cubics (no note);
    // a twist curve the bound does not cover (a circle) is said, once a surface
    let run = splinekit(&["sweep", &plain, "-o", dir.path().join("t").to_str().unwrap(), "--tolerance", "0.01"]);
    assert!(run.code == Some(0) && !run.stderr.contains("note:"), "{}", run.stderr);
    let circled = write("circled.swp", "");
    fs::write(&circled, fs::read_to_string(&circled).unwrap().replace(" scale s", " twist c")).unwrap();
    let run = splinekit(&["sweep", &circled, "-o", dir.path().join("c").to_str().unwrap(), "--tolerance", "0.01"]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert_eq!(
        run.stderr.matches("surface tube: with this path, scale or twist curve the tolerance 0.01").count(),
        1,
        "{}",
        run.stderr
    );
    let bare = write("bare.swp", "");
    fs::write(&bare, fs::read_to_string(&bare).unwrap().replace(" scale s", "")).unwrap();
    let run = splinekit(&["sweep", &bare, "-o", dir.path().join("b").to_str().unwrap(), "--tolerance", "0.01"]);
    assert!(run.code == Some(0) && !run.stderr.contains("note:"), "{}", run.stderr);
    // a path the bound does not cover (a trefoil knot), without a scale or twist: said too
    let knot = dir.path().join("knot.swp");
    fs::write(&knot, "circ c 12 0.2\ntrefoil k 64 1\ngcyl tube c k\n").unwrap();
    let run = splinekit(&[
        "sweep",
        knot.to_str().unwrap(),
        "-o",
        dir.path().join("k").to_str().unwrap(),
        "--tolerance",
        "0.05",
    ]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stderr.contains("surface tube: with this path, scale or twist curve the tolerance 0.05"),
        "{}",
        run.stderr
    );
    let run = splinekit(&["sweep", &plain, "-o", dir.path().join("x").to_str().unwrap(), "--scale-mode", "add"]);
    assert_eq!(run.code, Some(2));
    assert!(run.stderr.contains("possible values: multiply, override"), "{}", run.stderr);
}

/// The connected components of a triangle list (by shared vertex indices, nothing merged).
fn components(vertices: usize, triangles: &[[u32; 3]]) -> usize {
    let mut parent: Vec<usize> = (0..vertices).collect();
    fn root(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    for t in triangles {
        for k in 1..3 {
            let (a, b) = (root(&mut parent, t[0] as usize), root(&mut parent, t[k] as usize));
            parent[a] = b;
        }
    }
    let used: std::collections::HashSet<usize> = triangles.iter().flatten().map(|&v| v as usize).collect();
    used.iter().map(|&v| root(&mut parent, v)).collect::<std::collections::HashSet<_>>().len()
}

/// #42: welded means welded: capped tubes, a square profile's creases, a square path's
/// corners (closed) and an L's (capped), with each join, are each one closed, consistently
/// oriented 2-manifold with positive volume in the OBJ file `sweep` writes, read back by
/// vertex index (no vertex merged by position); every vertex is used.
#[test]
fn capped_creased_and_cornered_sweeps_are_one_closed_solid_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("solids.swp");
    let square = "[-0.2 -0.2] [0 -0.2] [0.1 -0.2] [0.2 -0.2] [0.2 0] [0.2 0.1] [0.2 0.2] [0 0.2] [-0.1 0.2] \
                  [-0.2 0.2] [-0.2 0] [-0.2 -0.1] [-0.2 -0.2]";
    let text = format!(
        "bez2 square 2 13 {square}\ncirc ring 16 0.3\ncirc loop 24 2\n\
         bez3 bend 8 4 [0 0 0] [1 0 0] [2 1 0] [2 2 1]\n\
         bez3 el 2 7 [0 0 0] [1 0 0] [2 0 0] [3 0 0] [3 1 0] [3 2 0] [3 3 0]\n\
         bez3 box 2 13 [0 0 0] [1 0 0] [2 0 0] [3 0 0] [3 1 0] [3 2 0] [3 3 0] [2 3 0] [1 3 0] [0 3 0] [0 2 0] \
         [0 1 0] [0 0 0]\n\
         gcyl tube ring bend\ngcyl squaretorus square loop\ngcyl squaretube square bend\n\
         gcyl mitre square el\ngcyl round ring el join round\ngcyl bevel square el join bevel\n\
         gcyl frame square box\ngcyl roundframe ring box join round\n"
    );
    fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    let run = splinekit(&["sweep", file.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let report = run.ok().to_owned();
    assert!(run.stderr.is_empty(), "{}", run.stderr);
    for line in report.lines() {
        let path = PathBuf::from(line.rsplit_once(": ").unwrap().0);
        let (positions, triangles) = read_obj(&path);
        let edges = directed_edges(&triangles);
        assert!(edges.iter().all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1)), "{line}");
        assert!(six_volume(&positions, &triangles) > 0.0, "{line}: faces point inwards");
        assert_eq!(components(positions.len(), &triangles), 1, "{line}");
        let used: std::collections::HashSet<u32> = triangles.iter().flatten().copied().collect();
        assert_eq!(used.len(), positions.len(), "{line}: every vertex in a face");
        // no zero-area triangle
        let p = |v: u32| positions[v as usize];
        for t in &triangles {
            let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
            let (u, w) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
            let n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
            assert!(n.iter().map(|x| x * x).sum::<f64>() > 1e-20, "{line}: zero-area triangle {t:?}");
        }
    }
    assert_eq!(report.lines().count(), 8);
    // and a profile that does not fit inside the turn is named
    let wide = dir.path().join("wide.swp");
    fs::write(
        &wide,
        format!(
            "bez2 square 2 13 {square}\nbez3 u 1 10 [0 0 0] [1 0 0] [2 0 0] [3 0 0] [3 0.1 0] \
         [3 0.2 0] [3 0.3 0] [2 0.3 0] [1 0.3 0] [0 0.3 0]\ngcyl . square u\n"
        ),
    )
    .unwrap();
    let run = splinekit(&["sweep", wide.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(run.stderr.contains("does not fit inside the turn of 90.0° at (3, 0, 0)"), "{}", run.stderr);
}
