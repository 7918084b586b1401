//! The harness shared by the CLI test binaries: run `splinekit`, check its outcome, find the
//! course meshes. (Each test binary uses part of it.)
#![allow(dead_code)]

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// The outcome of one run of the binary.
pub struct Run {
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// Asserts success and returns stdout.
    #[track_caller]
    pub fn ok(&self) -> &str {
        assert_eq!(self.code, Some(0), "expected success\nstdout:\n{}\nstderr:\n{}", self.stdout, self.stderr);
        &self.stdout
    }

    /// Asserts a non-zero exit with nothing on stdout and a message on stderr; returns stderr.
    #[track_caller]
    pub fn fails(&self) -> &str {
        assert!(
            self.code.is_some_and(|c| c != 0),
            "expected failure, got {:?}\nstdout:\n{}\nstderr:\n{}",
            self.code,
            self.stdout,
            self.stderr
        );
        assert!(self.stdout.is_empty(), "partial output on failure:\n{}", self.stdout);
        assert!(!self.stderr.trim().is_empty(), "no message on failure");
        &self.stderr
    }

    /// As [`Self::fails`], and the failure is a run-time error (exit status 1, `error: …`),
    /// not a command-line usage error.
    #[track_caller]
    pub fn fails_with_error(&self) -> &str {
        assert_eq!(self.code, Some(1), "expected failure\nstdout:\n{}\nstderr:\n{}", self.stdout, self.stderr);
        assert!(self.stderr.starts_with("error: "), "{}", self.stderr);
        self.fails()
    }

    /// Asserts success and parses stdout as one JSON value.
    #[track_caller]
    pub fn json(&self) -> Value {
        serde_json::from_str(self.ok()).unwrap_or_else(|e| panic!("bad JSON ({e}):\n{}", self.stdout))
    }
}

/// Runs the binary with `args`.
pub fn splinekit<S: AsRef<OsStr>>(args: &[S]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_splinekit")).args(args).output().expect("running splinekit");
    Run {
        code: out.status.code(),
        stdout: String::from_utf8(out.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(out.stderr).expect("stderr is UTF-8"),
    }
}

/// A folder of the bundled data (`obj`, `swp`) holding `probe`: the io crate's test copies,
/// else the shared data folder.
fn data_dir(kind: &str, probe: &str) -> PathBuf {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = [
        crate_dir.join("../splinekit-io/tests/data").join(kind),
        crate_dir.join("../../../shared/data").join(kind),
        crate_dir.join("../../shared/data").join(kind),
    ];
    candidates
        .iter()
        .find(|d| d.join(probe).is_file())
        .cloned()
        .unwrap_or_else(|| panic!("no {probe} in any of {candidates:?}"))
}

/// A course mesh (icosahedron.obj, bunny.obj, patch.obj, as shipped with their HTML lines).
pub fn course_mesh(name: &str) -> PathBuf {
    data_dir("obj", name).join(name)
}

/// The bundled SWP files' folder.
pub fn swp_dir() -> PathBuf {
    data_dir("swp", "core.swp")
}

/// The twelve course SWP files (plain SWP: everything but the io crate's `ext` folder of
/// extensions), relative to [`swp_dir`], sorted.
pub fn course_swp() -> Vec<String> {
    fn walk(dir: &Path, rel: &str, out: &mut Vec<String>) {
        for entry in fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let rel = if rel.is_empty() { name.clone() } else { format!("{rel}/{name}") };
            if path.is_dir() && name != "ext" {
                walk(&path, &rel, out);
            } else if path.extension().is_some_and(|e| e == "swp") {
                out.push(rel);
            }
        }
    }
    let mut files = Vec::new();
    walk(&swp_dir(), "", &mut files);
    files.sort();
    assert_eq!(files.len(), 12, "{files:?}");
    files
}

/// Runs `splinekit sweep FILE -o DIR` with more arguments.
pub fn sweep(file: &Path, dir: &Path, rest: &[&str]) -> Run {
    let mut args: Vec<&OsStr> = vec!["sweep".as_ref(), file.as_os_str(), "-o".as_ref(), dir.as_os_str()];
    args.extend(rest.iter().map(OsStr::new));
    splinekit(&args)
}

/// Files in a directory, sorted.
pub fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = match fs::read_dir(dir) {
        Ok(d) => d.map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect(),
        Err(_) => Vec::new(),
    };
    names.sort();
    names
}

/// Positions and triangles of an OBJ file (`v`; `f` with 1-based `a`, `a/b`, `a//c` or
/// `a/b/c` corners), 0-based.
pub fn read_obj(path: &Path) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let text = fs::read_to_string(path).unwrap();
    let (mut v, mut f) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first() {
            Some(&"v") => v.push([1, 2, 3].map(|i| w[i].parse::<f64>().unwrap())),
            Some(&"f") => {
                assert_eq!(w.len(), 4, "{line}");
                f.push([1, 2, 3].map(|i| w[i].split('/').next().unwrap().parse::<u32>().unwrap() - 1));
            }
            _ => {}
        }
    }
    (v, f)
}

/// `PATH: V vertices, T triangles`.
pub fn report_line(path: &Path, vertices: usize, triangles: usize) -> String {
    format!("{}: {vertices} vertices, {triangles} triangles\n", path.display())
}
