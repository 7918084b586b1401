//! The seed files for byte mutation: the repository's example and fixture files, read at
//! start-up, plus files the project's own writers make from them (the repository has no PLY
//! or STL fixtures), plus any directories given with `--corpus`.
//!
//! The course files under `shared/data/` (MIT 6.837 / Aalto SWP, the ME-C3100 OBJ meshes, the
//! CS 4620 annotated OBJ files) are already copied into `crates/splinekit-io/tests/data/`
//! with their sources; the fuzzer reads them there instead of keeping another copy. Files
//! longer than [`MAX_SEED_BYTES`] are cut to their first [`MAX_SEED_BYTES`] bytes (at a line
//! end for text), which keeps the CS 4620 spline headers and a few thousand mesh lines.

use std::path::{Path, PathBuf};

use splinekit_io::mesh::{MeshFormat, read_mesh, write_mesh};

use crate::Format;

/// Longest seed kept, in bytes.
pub const MAX_SEED_BYTES: usize = 24 * 1024;

/// Seed files by format.
#[derive(Clone, Debug, Default)]
pub struct Corpus {
    /// `(name, bytes)` per format, in [`Format::ALL`] order.
    pub seeds: [Vec<(String, Vec<u8>)>; 5],
}

/// The repository's root (the parent of this crate's directory).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Where the bundled seeds are, relative to the repository root.
const SEED_DIRS: [&str; 4] =
    ["examples", "crates/splinekit-io/tests/data", "crates/splinekit/tests/data", "fuzz/corpus"];

impl Corpus {
    /// The bundled seeds, and those under `extra` directories.
    pub fn load(extra: &[PathBuf]) -> Self {
        let root = repo_root();
        let mut files = Vec::new();
        for dir in SEED_DIRS {
            collect(&root.join(dir), &mut files);
        }
        for dir in extra {
            collect(dir, &mut files);
        }
        files.sort();
        files.dedup();
        let mut corpus = Self::default();
        for path in files {
            let Some(format) = Format::from_path(&path) else { continue };
            // subdivision references: only the inputs (`*.in.obj`) and first levels are worth it
            let name = path.strip_prefix(&root).unwrap_or(&path).display().to_string();
            if name.contains(".l2.") || name.contains(".l3.") || name.contains(".limit.") {
                continue;
            }
            let Ok(mut bytes) = std::fs::read(&path) else { continue };
            if bytes.len() > MAX_SEED_BYTES {
                let cut = if format.is_binary() {
                    MAX_SEED_BYTES
                } else {
                    bytes[..MAX_SEED_BYTES].iter().rposition(|&b| b == b'\n').map_or(MAX_SEED_BYTES, |i| i + 1)
                };
                bytes.truncate(cut);
            }
            corpus.seeds[format.index()].push((name, bytes));
        }
        corpus.add_written();
        corpus
    }

    /// PLY, STL and glb files written by the project's writers from the OBJ seeds.
    fn add_written(&mut self) {
        let objs: Vec<(String, Vec<u8>)> = self.seeds[Format::Obj.index()].iter().take(40).cloned().collect();
        for (name, bytes) in objs {
            let Ok(loaded) = read_mesh(bytes.as_slice(), MeshFormat::Obj, &name) else { continue };
            let tri = loaded.mesh.to_tri_mesh();
            for (format, mesh_format) in
                [(Format::Ply, MeshFormat::Ply), (Format::Stl, MeshFormat::Stl), (Format::Glb, MeshFormat::Glb)]
            {
                let mut out = Vec::new();
                if write_mesh(&tri, &mut out, mesh_format).is_ok() && out.len() <= MAX_SEED_BYTES {
                    self.seeds[format.index()].push((format!("{name} written as {format}"), out));
                }
            }
        }
    }

    /// How many seeds there are of each format.
    pub fn counts(&self) -> [usize; 5] {
        std::array::from_fn(|k| self.seeds[k].len())
    }
}

/// Every file under `dir`, recursively.
fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(&path, out);
        } else {
            out.push(path);
        }
    }
}
