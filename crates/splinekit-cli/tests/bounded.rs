//! #38: one-line inputs that broke a promise (a panic, a non-finite coordinate accepted) are
//! refused or handled, each a regression test run through the binary.

use std::fs;

mod common;
use common::splinekit;

/// `info` on a curve whose name is longer than a formatting width may be: the listing pads
/// short names only, and prints the long one whole.
#[test]
fn info_lists_a_curve_with_a_huge_name() {
    let dir = tempfile::tempdir().unwrap();
    let name = "n".repeat(70_000);
    let file = dir.path().join("long.swp");
    fs::write(&file, format!("bsp2 {name} 10 4 [0 0] [1 0] [1 1] [0 1]\nbsp2 b 10 4 [0 0] [1 0] [1 1] [0 1]\n"))
        .unwrap();
    let out = splinekit(&["info".as_ref(), file.as_os_str()]).ok().to_owned();
    assert!(out.contains(&name), "the name is printed whole");
    // the short name is padded to at most 40 columns
    let line = out.lines().find(|l| l.starts_with("    1  b ")).unwrap();
    assert!(line.starts_with(&format!("    1  b{}  bsp2", " ".repeat(39))), "{line:?}");
}

/// A NaN or infinite vertex is refused when the file is read: text formats name the line and
/// column of the token, binary ones the vertex. Nothing is drawn or written.
#[test]
fn non_finite_vertices_are_refused_at_read_time() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("nan.obj");
    fs::write(&obj, "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n").unwrap();
    let inf = dir.path().join("inf.obj");
    fs::write(&inf, "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n").unwrap();
    // a binary STL with one triangle whose second vertex has x = +inf
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&1u32.to_le_bytes());
    let floats: [f32; 12] = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, f32::INFINITY, 0.0, 0.0, 0.0, 1.0, 0.0];
    for f in floats {
        stl.extend_from_slice(&f.to_le_bytes());
    }
    stl.extend_from_slice(&[0, 0]);
    let bin = dir.path().join("inf.stl");
    fs::write(&bin, stl).unwrap();
    let png = dir.path().join("out.png");
    for (file, says) in [
        (&obj, "nan.obj:3:3: found \"nan\", expected a number (x coordinate)"),
        (&inf, "inf.obj:3:5: found \"1e999\", expected a number (y coordinate)"),
        (&bin, "inf.stl: vertex 2 has x = inf, expected a finite number"),
    ] {
        for command in ["info", "render"] {
            let mut args = vec![command.as_ref(), file.as_os_str()];
            if command == "render" {
                args.extend(["-o".as_ref(), png.as_os_str()]);
            }
            let stderr = splinekit(&args).fails_with_error().to_string();
            assert!(stderr.contains(says), "{command} {}: {stderr}", file.display());
        }
        assert!(!png.exists(), "nothing drawn");
    }
}

/// `sweep` writes every surface's file or none: when the last cannot be written, the first
/// two are not left behind either, and the message names the path once.
#[test]
fn sweep_writes_all_files_or_none() {
    let dir = tempfile::tempdir().unwrap();
    let swp = dir.path().join("three.swp");
    fs::write(&swp, "bsp2 p 10 4 [1 -1] [2 -1] [2 1] [1 1]\nzrev a p\nzrev b p\nzrev c p\n").unwrap();
    let out = dir.path().join("out");
    fs::create_dir_all(out.join("c.obj")).unwrap();
    let stderr =
        splinekit(&["sweep".as_ref(), swp.as_os_str(), "-o".as_ref(), out.as_os_str()]).fails_with_error().to_string();
    let path = out.join("c.obj").display().to_string();
    assert_eq!(stderr.matches(&path).count(), 1, "{stderr}");
    let mut left: Vec<String> =
        fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    left.sort();
    assert_eq!(left, ["c.obj"], "no other file, no temporary file");
    // with room for all three, all three are written
    fs::remove_dir(out.join("c.obj")).unwrap();
    let stdout = splinekit(&["sweep".as_ref(), swp.as_os_str(), "-o".as_ref(), out.as_os_str()]).ok().to_owned();
    assert_eq!(stdout.lines().count(), 3);
}

/// Runs the binary with `args`, failing the test if it has not finished after a minute (these
/// inputs once ran for hours; now they end in well under a second).
fn within_a_minute(args: &[&std::ffi::OsStr]) -> common::Run {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let mut child = Command::new(env!("CARGO_BIN_EXE_splinekit"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("still running after a minute: {args:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    common::Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// The one-line inputs of #38 that bisected for hours: each ends, and where the accuracy asked
/// cannot be met, standard error says so (the output keeps its shape).
#[test]
fn adaptive_loops_end_and_say_when_the_accuracy_cannot_be_met() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str, text: &str| {
        let p = dir.path().join(name);
        fs::write(&p, text).unwrap();
        p
    };
    let wiggle = file("wiggle.swp", "bez2 a 1 4 [0 0] [1 1] [2 0] [3 1]\n");
    let spike = file("spike.swp", "bez3 a 1 4 [0 0 0] [0 1e8 0] [1 0 1] [2 0 0]\n");
    let twist = file(
        "twist.swp",
        "circ ring 12 1\nbsp2 path 10 4 [0 0] [1e-300 0] [2e-300 1e-300] [3e-300 1e-300]\n\
         bsp2 tw 10 4 [0 0] [10 0] [20 0] [30 0]\ngcyl g ring path twist tw\n",
    );
    let scale = file(
        "scale.swp",
        "circ ring 12 1\nbsp2 path 10 4 [0 0] [1 0] [2 1] [3 1]\n\
         bsp2 tiny 10 4 [1e-9 1e-9] [2e-9 1e-9] [1e-9 2e-9] [1e-9 1e-9]\ngcyl g ring path scale tiny\n",
    );
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    let run = within_a_minute(&[
        os("arclen"),
        wiggle.as_os_str(),
        os("--method"),
        os("adaptive"),
        os("--at-s"),
        os("1e-300"),
    ]);
    run.ok();
    let run = within_a_minute(&[os("arclen"), spike.as_os_str(), os("--method"), os("adaptive")]);
    assert!(run.ok().contains("length: 8888888"), "{}", run.stdout);
    assert!(run.stderr.contains("not the --accuracy 1e-9"), "{}", run.stderr);
    let out = dir.path().join("out");
    within_a_minute(&[os("sweep"), twist.as_os_str(), os("-o"), out.as_os_str()]).ok();
    within_a_minute(&[os("info"), scale.as_os_str()]).ok();
    within_a_minute(&[os("sweep"), scale.as_os_str(), os("-o"), out.as_os_str()]).ok();
    let png = dir.path().join("m.png");
    within_a_minute(&[os("render"), spike.as_os_str(), os("-o"), png.as_os_str(), os("--markers"), os("1e7")]).ok();
}

/// A helix of 10 000 turns of radius 1e200: `curve --tolerance` refuses it from its point
/// count (22 billion) before making any, `render` draws it with equal steps, and a sweep along
/// it is refused from the count too. None allocates more than the limits allow.
#[test]
fn tessellations_are_counted_before_they_are_made() {
    let dir = tempfile::tempdir().unwrap();
    let helix = dir.path().join("helix.swp");
    fs::write(&helix, "helix h 20 1e200 1 10000\ncirc ring 8 1\ngcyl tube ring h\n").unwrap();
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    let stderr =
        within_a_minute(&[os("curve"), helix.as_os_str(), os("--curve"), os("h"), os("--tolerance"), os("0.01")])
            .fails_with_error()
            .to_string();
    assert!(stderr.contains("curve h: this tessellation would give up to 22326326821 points"), "{stderr}");
    assert!(stderr.contains("--max-points 50000000"), "{stderr}");
    let small = within_a_minute(&[
        os("curve"),
        helix.as_os_str(),
        os("--curve"),
        os("h"),
        os("--angle-tolerance"),
        os("10"),
        os("--max-points"),
        os("1000"),
    ]);
    assert!(small.fails_with_error().contains("--max-points 1000"));
    let png = dir.path().join("h.png");
    within_a_minute(&[os("render"), helix.as_os_str(), os("-o"), png.as_os_str()]).ok();
    let out = dir.path().join("out");
    let stderr =
        within_a_minute(&[os("sweep"), helix.as_os_str(), os("-o"), out.as_os_str(), os("--tolerance"), os("0.01")])
            .fails_with_error()
            .to_string();
    assert!(stderr.contains("would have about") && stderr.contains("points"), "{stderr}");
}

/// Coordinates near the top of the f64 range: `arclen` and `curve` refuse, naming the curve,
/// instead of printing `inf`, `null` or NaN as an answer.
#[test]
fn overflowing_curves_are_refused_not_answered_with_inf() {
    let dir = tempfile::tempdir().unwrap();
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    for (name, text) in
        [("big.swp", "bez2 a 20 4 [0 0] [1 1e308] [2 -1e308] [3 1]\n"), ("circle.swp", "circ a 20 1e300\n")]
    {
        let file = dir.path().join(name);
        fs::write(&file, text).unwrap();
        for args in [&["arclen"][..], &["arclen", "--json"], &["arclen", "--method", "adaptive"]] {
            let mut all: Vec<&std::ffi::OsStr> = args.iter().map(|a| os(a)).collect();
            all.push(file.as_os_str());
            let run = within_a_minute(&all);
            if name == "circle.swp" && args.len() == 3 {
                // the exact length of a circle does not overflow: 2π·1e300
                let out = run.ok().to_owned();
                let length: f64 = out.lines().find_map(|l| l.strip_prefix("length: ")).unwrap().parse().unwrap();
                assert!((length / (std::f64::consts::TAU * 1e300) - 1.0).abs() < 1e-12, "{out}");
                continue;
            }
            let stderr = run.fails_with_error().to_string();
            assert!(stderr.contains("curve a: its arc length overflows f64"), "{name} {args:?}: {stderr}");
        }
    }
}

/// A chord table that aliases (5 samples a segment on a helix of 10 000 turns: a length of
/// 1000 for 62 840) is printed as asked, with a warning that compares it with the adaptive
/// length; a table that agrees prints no warning.
#[test]
fn an_aliasing_chord_table_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let helix = dir.path().join("helix.swp");
    fs::write(&helix, "helix h 5 1 0.1 10000\nbez2 b 10 4 [0 0] [1 1] [2 1] [3 0]\n").unwrap();
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    let run = within_a_minute(&[os("arclen"), helix.as_os_str(), os("--curve"), os("h")]);
    assert!(run.ok().contains("length: 1000"));
    assert!(
        run.stderr.contains("differs from the adaptive length 62839.81") && run.stderr.contains("98%"),
        "{}",
        run.stderr
    );
    let run = within_a_minute(&[os("arclen"), helix.as_os_str(), os("--curve"), os("b")]);
    run.ok();
    assert!(run.stderr.is_empty(), "{}", run.stderr);
}

/// Outputs that are not regular files are written in place (`/dev/null` stays a device), and a
/// read-only file is not replaced unless `--force` says so.
#[test]
fn devices_are_written_in_place_and_read_only_files_kept() {
    use std::os::unix::fs::FileTypeExt as _;
    // (a device such as /dev/null is written the same way; a pipe can be made and checked here)
    let dir = tempfile::tempdir().unwrap();
    let swp = dir.path().join("p.swp");
    fs::write(&swp, "bsp2 p 10 4 [1 -1] [2 -1] [2 1] [1 1]\nsrev s 8 p\n").unwrap();
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    // a named pipe with an .obj name, read by another thread while subdivide writes it
    let obj = dir.path().join("s.obj");
    fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let fifo = dir.path().join("pipe.obj");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || fs::read_to_string(fifo).unwrap())
    };
    within_a_minute(&[os("subdivide"), obj.as_os_str(), os("-n"), os("1"), os("-o"), fifo.as_os_str()]).ok();
    let text = reader.join().unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 4, "{text}");
    assert!(fs::metadata(&fifo).unwrap().file_type().is_fifo(), "the pipe is still a pipe");

    let png = dir.path().join("kept.png");
    fs::write(&png, b"mine").unwrap();
    let mut perms = fs::metadata(&png).unwrap().permissions();
    perms.set_readonly(true);
    fs::set_permissions(&png, perms).unwrap();
    let stderr =
        within_a_minute(&[os("render"), swp.as_os_str(), os("-o"), png.as_os_str()]).fails_with_error().to_string();
    assert!(stderr.contains("read-only") && stderr.contains("--force"), "{stderr}");
    assert_eq!(fs::read(&png).unwrap(), b"mine");
    within_a_minute(&[os("render"), swp.as_os_str(), os("-o"), png.as_os_str(), os("--force")]).ok();
    assert!(fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

/// SIGTERM (or Ctrl-C) while a large file is being written: the temporary file is removed and
/// the target never appears.
#[test]
fn an_interrupted_write_leaves_no_temporary_file() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    let swp = dir.path().join("big.swp");
    // 2000 slices of a 1001-point profile: 4 million triangles, a second or more to write as OBJ
    fs::write(&swp, "bsp2 p 1000 4 [1 -1] [2 -1] [2 1] [1 1]\nsrev big 2000 p\n").unwrap();
    let out = dir.path().join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_splinekit"))
        .args(["sweep".as_ref(), swp.as_os_str(), "-o".as_ref(), out.as_os_str()])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let temporary = || {
        fs::read_dir(&out)
            .ok()
            .into_iter()
            .flatten()
            .any(|e| e.unwrap().file_name().to_string_lossy().ends_with(".tmp"))
    };
    let start = Instant::now();
    while !temporary() {
        assert!(start.elapsed() < Duration::from_secs(60), "no temporary file appeared");
        assert!(child.try_wait().unwrap().is_none(), "the sweep ended before it could be interrupted");
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(Command::new("kill").args(["-TERM", &child.id().to_string()]).status().unwrap().success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{status:?}");
    let left: Vec<String> =
        fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert!(left.is_empty(), "{left:?}");
}

/// `subdivide` estimates the memory of the finest level from its triangle count before making
/// anything, and refuses past the memory available or `--max-memory`, naming the estimate.
#[test]
fn subdivision_past_the_memory_is_refused_before_it_starts() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("ico.obj");
    fs::copy(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data/obj/icosahedron.obj"),
        &obj,
    )
    .unwrap();
    let out = dir.path().join("out.obj");
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    // 20·4¹³ = 1.3 billion triangles (their counts fit u32 indices): more than any machine here
    // has memory for
    let stderr = within_a_minute(&[os("subdivide"), obj.as_os_str(), os("-n"), os("13"), os("-o"), out.as_os_str()])
        .fails()
        .to_string();
    assert!(stderr.contains("13 levels of Loop would make up to 1.342e9 triangles"), "{stderr}");
    assert!(stderr.contains("of memory available"), "{stderr}");
    // 20·4⁶ = 81 920 triangles, about 13 MB: refused under 1 MB, made under 1 GB
    let small = [os("subdivide"), obj.as_os_str(), os("-n"), os("6"), os("-o"), out.as_os_str(), os("--max-memory")];
    let stderr = within_a_minute(&[&small[..], &[os("0.001")]].concat()).fails().to_string();
    assert!(stderr.contains("81920") || stderr.contains("8.192e4"), "{stderr}");
    assert!(stderr.contains("--max-memory allows"), "{stderr}");
    assert!(!out.exists());
    within_a_minute(&[&small[..], &[os("1")]].concat()).ok();
    assert!(out.exists());
}

/// A 50-byte SWP file whose surface `sweep` accepts (32 million triangles) is too large to draw:
/// `render` refuses it from its sample counts, before building it, instead of needing gigabytes.
#[test]
fn render_refuses_a_scene_past_its_triangle_budget() {
    let dir = tempfile::tempdir().unwrap();
    let swp = dir.path().join("big.swp");
    fs::write(&swp, "bsp2 p 4000 4 [1 -1] [2 -1] [2 1] [1 1]\nsrev s 4000 p\n").unwrap();
    let png = dir.path().join("big.png");
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    let stderr =
        within_a_minute(&[os("render"), swp.as_os_str(), os("-o"), png.as_os_str()]).fails_with_error().to_string();
    assert!(stderr.contains("surface s would have about 32000000 triangles"), "{stderr}");
    assert!(stderr.contains("more than the limit of 20000000"), "{stderr}");
    assert!(!png.exists());
}

/// `info` counts a surface from its samples and slices instead of building it: a 53-byte file
/// whose revolution has 48 million triangles (several gigabytes as a mesh) is listed within
/// half a gigabyte of address space, with the closed form's counts.
#[test]
fn info_counts_surfaces_without_building_them() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("big.swp");
    fs::write(&file, "bsp2 p 1000 4 [1 0] [2 1] [1 2] [1 3]\nsrev s 24000 p\n").unwrap();
    let out = std::process::Command::new("bash")
        .args(["-c", "ulimit -v 524288; exec \"$0\" info --json \"$1\""])
        .arg(env!("CARGO_BIN_EXE_splinekit"))
        .arg(&file)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // 1001 profile points off the axis in 24 000 copies, two triangles per quad, both layouts
    let counts = serde_json::json!({"vertices": 1001 * 24_000, "triangles": 2 * 1000 * 24_000});
    assert_eq!(json["surfaces"][0]["welded"], counts);
    assert_eq!(json["surfaces"][0]["compat"], counts);
}

/// A flat helix of 10 000 turns (26 bytes) once made tiny-skia fail an assertion and abort the
/// process: its projected points lay 10¹² pixels away. Lines are clipped to the picture and
/// stroked a piece at a time, so the picture is drawn.
#[test]
fn render_draws_a_curve_far_outside_the_picture() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("flat.swp");
    fs::write(&file, "helix c 20 1 0 10000\n").unwrap();
    for size in ["64x48", "800x600"] {
        let png = dir.path().join(format!("flat-{size}.png"));
        let run = within_a_minute(&[
            "render".as_ref(),
            file.as_os_str(),
            "-o".as_ref(),
            png.as_os_str(),
            "--size".as_ref(),
            size.as_ref(),
        ]);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        assert!(fs::metadata(&png).unwrap().len() > 0);
    }
}

/// #38: a face of fewer than three corners is refused by name by Catmull-Clark and Doo-Sabin
/// at every number of levels, and nothing is written (an empty face gave a face point of
/// 0/0 and an output the writer refused; `-n 0` wrote a bare `f` and called the faces quads).
#[test]
fn faces_of_fewer_than_three_corners_are_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let ply = dir.path().join("empty-face.ply");
    fs::write(
        &ply,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
         element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0\n",
    )
    .unwrap();
    let obj = dir.path().join("two.obj");
    fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n").unwrap();
    let out = dir.path().join("out.obj");
    for (file, corners) in [(&ply, "0 corners"), (&obj, "2 corners")] {
        for scheme in ["catmull-clark", "doo-sabin", "bilinear"] {
            for levels in ["0", "1", "2"] {
                let args = [
                    "subdivide".as_ref(),
                    file.as_os_str(),
                    "-n".as_ref(),
                    levels.as_ref(),
                    "--scheme".as_ref(),
                    scheme.as_ref(),
                    "-o".as_ref(),
                    out.as_os_str(),
                ];
                let stderr = splinekit(&args).fails_with_error().to_string();
                let says = format!("face 1 has {corners}; every face needs at least 3 (remove it from the file)");
                assert!(stderr.contains(&says), "{scheme} -n {levels} {}: {stderr}", file.display());
                assert!(!out.exists());
            }
        }
    }
}
