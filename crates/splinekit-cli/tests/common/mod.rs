//! The harness shared by the CLI test binaries: run `splinekit`, check its outcome, find the
//! course meshes. (Each test binary uses part of it.)
#![allow(dead_code)]

use std::ffi::OsStr;
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

/// A course mesh (icosahedron.obj, bunny.obj, patch.obj, as shipped with their HTML lines):
/// the io crate's test copies, else the shared data folder.
pub fn course_mesh(name: &str) -> PathBuf {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = [
        crate_dir.join("../splinekit-io/tests/data/obj"),
        crate_dir.join("../../../shared/data/obj"),
        crate_dir.join("../../shared/data/obj"),
    ];
    candidates
        .iter()
        .map(|d| d.join(name))
        .find(|p| p.is_file())
        .unwrap_or_else(|| panic!("no {name} in any of {candidates:?}"))
}
