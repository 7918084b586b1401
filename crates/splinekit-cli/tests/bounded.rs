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
