//! Opening files: an SWP document, an annotated OBJ as its spline, or a mesh for viewing
//! (read on a worker thread when it is large).

use std::path::Path;

use splinekit::PolyMesh;
use splinekit::subdiv::{Creases, LoopPyramid};
use splinekit_io::mesh::{RebuildOptions, SplineHeader};

use crate::app::cancel;
use crate::files::Purpose;
use crate::subdivision::mesh_key;
use crate::{DocKind, Document, EditorApp, ViewedMesh, view3d, work};

/// Mesh files larger than this (bytes) are read on a worker thread.
pub const BACKGROUND_BYTES: u64 = 4_000_000;

/// A mesh file read on a worker thread, with its Loop level 0 and 3D view data.
pub(crate) struct Loaded {
    mesh: PolyMesh,
    creases: Creases,
    kind: DocKind,
    pyramid: Result<LoopPyramid, String>,
    prepared: view3d::PreparedMesh,
}

impl EditorApp {
    /// Opens an SWP file as the document, or a mesh (OBJ, glb, PLY, STL; an OBJ with a spline
    /// header is rebuilt from its spline) as a document for viewing, without asking about
    /// unsaved changes (see [`request`](Self::request)); one undo step. Returns whether it
    /// opened; on error the status line says why and nothing changes.
    pub fn open_file(&mut self, path: &Path) -> bool {
        if let Some(why) = Purpose::Open.refuse_extension(path) {
            self.status = format!("Error: {why}");
            return false;
        }
        let big = std::fs::metadata(path).is_ok_and(|m| m.len() > BACKGROUND_BYTES);
        if big && DocKind::of_path(path) == Some(DocKind::Mesh) {
            // read, and make the Loop level 0 and the 3D view's data, on a worker thread
            self.cancel_load();
            let (file, options) = (path.to_path_buf(), self.loop_options());
            let size = std::fs::metadata(path).map_or(0, |m| m.len());
            let label = format!("Opening {} ({:.0} MB)", file.display(), size as f64 / 1e6);
            let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |_| {
                let (mesh, creases, kind) = load_mesh(&file)?;
                let pyramid = LoopPyramid::new(&mesh, options).map_err(|e| e.to_string());
                let prepared = view3d::PreparedMesh::new(&mesh.to_tri_mesh());
                Ok(Loaded { mesh, creases, kind, pyramid, prepared })
            });
            self.load_task = Some((path.to_path_buf(), task));
            self.status = format!("Opening {}…", path.display());
            return true;
        }
        let annotated = match path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj")) {
            true => annotated_document(path),
            false => Ok(None),
        };
        let loaded = if DocKind::of_path(path) == Some(DocKind::Swp) {
            Document::read(path).map(|doc| {
                self.doc.replace_with(doc);
                self.sync_mesh();
                self.status = format!("Loaded {}", path.display());
            })
        } else if let Err(e) = annotated {
            Err(e)
        } else if let Ok(Some(doc)) = annotated {
            self.doc.replace_with(doc);
            self.sync_mesh();
            self.status = format!("Loaded {}: the tool's splines and settings, editable", path.display());
            Ok(())
        } else {
            load_mesh(path).map(|(mesh, creases, kind)| {
                let pyramid = LoopPyramid::new(&mesh, self.loop_options()).map_err(|e| e.to_string());
                self.install_mesh(path, mesh, creases, kind, pyramid, None);
            })
        };
        match loaded {
            Ok(()) => {
                self.view.selected = None;
                self.recent.add(path);
                true
            }
            Err(e) => {
                self.status = format!("Error: {e}");
                false
            }
        }
    }

    /// Makes the mesh read from `path` the document (one undo step), with its Loop level 0
    /// and, if made already, its 3D view data.
    fn install_mesh(
        &mut self,
        path: &Path,
        mesh: PolyMesh,
        creases: Creases,
        kind: DocKind,
        pyramid: Result<LoopPyramid, String>,
        prepared: Option<view3d::PreparedMesh>,
    ) {
        let (vertices, faces) = (mesh.positions.len(), mesh.num_faces());
        let (crease_edges, crease_vertices) = (creases.edges.len(), creases.vertices.len());
        let viewed = ViewedMesh { base: mesh, creases };
        self.doc.replace_with(Document::from_mesh(viewed, path.to_path_buf(), kind));
        self.sync_mesh_with(Some(pyramid));
        if let (Some(prepared), Some(m)) = (prepared, &self.mesh) {
            self.prepared_mesh = Some((mesh_key(m), prepared));
        }
        self.status = format!("Loaded {}: {vertices} vertices, {faces} faces", path.display());
        if crease_edges + crease_vertices > 0 {
            self.status.push_str(&format!(
                ", {crease_edges} creased edges and {crease_vertices} creased vertices (Loop and Catmull-Clark keep them)"
            ));
        }
        if let Some(Err(e)) = self.mesh.as_ref().map(|m| &m.pyramid) {
            self.status.push_str(&format!(" (cannot subdivide: {e})"));
        }
    }

    /// Takes the result of a file being opened on a worker thread, if it is done.
    pub(crate) fn poll_load(&mut self) {
        let Some((path, task)) = &mut self.load_task else { return };
        let Some(result) = task.poll() else { return };
        let path = path.clone();
        self.load_task = None;
        match result.and_then(|r| r) {
            Ok(Loaded { mesh, creases, kind, pyramid, prepared }) => {
                self.install_mesh(&path, mesh, creases, kind, pyramid, Some(prepared));
                self.view.selected = None;
                self.recent.add(&path);
            }
            Err(e) => self.status = format!("Error: {e}"),
        }
    }

    /// Stops waiting for a file being opened.
    pub(crate) fn cancel_load(&mut self) {
        cancel(&mut self.load_task);
    }

    /// Whether a file is being opened on a worker thread.
    #[must_use]
    pub fn is_loading(&self) -> bool {
        self.load_task.is_some()
    }
}

/// The editable document of an OBJ file with the revolution tool's spline header (its
/// profile curve and `zrev` surface), `None` for an OBJ without one or with the sweep tool's
/// header (which opens as its rebuilt mesh).
fn annotated_document(path: &Path) -> Result<Option<Document>, String> {
    let Some(header) = SplineHeader::read(path).map_err(|e| e.to_string())? else { return Ok(None) };
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let swp = header.to_document(&stem).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(Some(Document::from_annotated(swp, path.to_path_buf())))
}

/// Reads a mesh file and its creases (an OBJ's crease tags), and whether it is a plain mesh
/// or an annotated OBJ (an OBJ with a spline header, rebuilt from its spline).
fn load_mesh(path: &Path) -> Result<(PolyMesh, Creases, DocKind), String> {
    let is_obj = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    if is_obj && let Ok(Some(header)) = SplineHeader::read(path) {
        let mesh = header.rebuild(&RebuildOptions::DEFAULT).map_err(|e| format!("{}: {e}", path.display()))?;
        return Ok((PolyMesh::from(&mesh), Creases::default(), DocKind::AnnotatedObj));
    }
    splinekit_io::load_mesh(path).map(|m| (m.mesh, m.creases, DocKind::Mesh)).map_err(|e| e.to_string())
}
