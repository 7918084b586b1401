//! Reading a mesh file for a command: the reader's warnings on standard error, and a clear
//! error for a mesh without faces where the command needs faces.

use std::path::Path;

use anyhow::bail;
use splinekit::PolyMesh;
use splinekit_io::mesh::{LoadedMesh, load_mesh};

/// Reads the mesh file at `path` (the reader chosen by its extension) and prints what the
/// reader skipped or dropped on standard error, a line `warning: FILE: …` each.
pub fn load(path: &Path) -> anyhow::Result<LoadedMesh> {
    let loaded = load_mesh(path)?;
    for w in &loaded.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(loaded)
}

/// An error `FILE has no faces (N vertices): COMMAND needs faces` for a mesh without faces
/// (a file of points, say).
pub fn require_faces(mesh: &PolyMesh, path: &Path, command: &str) -> anyhow::Result<()> {
    if mesh.num_faces() == 0 {
        let n = mesh.num_vertices();
        bail!(
            "{} has no faces ({n} {}): {command} needs faces",
            path.display(),
            if n == 1 { "vertex" } else { "vertices" }
        );
    }
    Ok(())
}
