//! Saving (SWP, or the revolution tool's annotated OBJ; checked before anything is written)
//! and exporting the mesh shown (on a worker thread when it is large).

use std::path::Path;

use splinekit::TriMesh;
use splinekit_io::SwpDocument;
use splinekit_io::mesh::MeshFormat;
use splinekit_io::surface::SurfaceOptions;

use crate::files::Purpose;
use crate::{BACKGROUND_FACES, EDITOR_MAX_TRIANGLES, EditorApp, SweptSurfaces, files, work};

/// What Export mesh writes: a mesh, or a document whose surfaces it sweeps first.
enum ExportSource {
    Mesh(TriMesh),
    Sweep(SwpDocument),
}

impl EditorApp {
    /// Saves the document: to its own file when it is an SWP document, else asks for a name
    /// (Save as). Returns whether it was written.
    pub fn save(&mut self) -> bool {
        match self.doc.save_path().map(Path::to_path_buf) {
            Some(path) => self.save_to(&path),
            None => {
                self.open_dialog(Purpose::SaveAs);
                false
            }
        }
    }

    /// Saves the document to `path`: as the revolution tool's annotated OBJ for a `.obj`
    /// path ([`save_annotated`](Self::save_annotated)), else as SWP
    /// ([`save_swp`](Self::save_swp)). Returns whether it was written.
    pub fn save_to(&mut self, path: &Path) -> bool {
        if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj")) {
            self.save_annotated(path)
        } else {
            self.save_swp(path)
        }
    }

    /// Why the document cannot be saved as an annotated OBJ, if it cannot.
    pub(crate) fn annotated_refusal(&self) -> Option<String> {
        let swp = &self.doc.swp;
        let used = swp.surfaces.first().map_or(0, |s| {
            let mut curves: Vec<usize> = s.kind.references().iter().map(|&(_, c)| c).collect();
            curves.sort_unstable();
            curves.dedup();
            curves.len()
        });
        if swp.surfaces.len() != 1 || swp.curves.len() != used {
            return Some(format!(
                "an annotated OBJ holds one surface (a zrev or an xsweep) and the curves it uses; this document \
                 has {} curves and {} surfaces (Save as .swp keeps them all, Export mesh writes the mesh)",
                swp.curves.len(),
                swp.surfaces.len()
            ));
        }
        swp.annotated_header(0).err().map(|e| e.to_string())
    }

    /// Writes the document's one surface, a `zrev` of a `bsp2` or uniform `cr2` profile, as
    /// the revolution tool's annotated OBJ (its spline and settings in the leading comments,
    /// then the mesh), which opens again as the same curve and surface. Anything else is
    /// refused with the reason and nothing is written. Returns whether it was written.
    pub fn save_annotated(&mut self, path: &Path) -> bool {
        let swp = &self.doc.swp;
        let refuse = |why: String| format!("Error: not saved as {}: {why}", path.display());
        if let Some(why) = self.annotated_refusal() {
            self.status = refuse(why);
            return false;
        }
        let options = SurfaceOptions { max_triangles: Some(EDITOR_MAX_TRIANGLES), ..SurfaceOptions::default() };
        match swp.save_annotated_obj(0, &options, path) {
            Ok(mesh) => {
                self.doc.mark_saved(path);
                self.recent.add(path);
                self.status = format!(
                    "Saved {} (annotated OBJ: {} vertices, {} triangles)",
                    path.display(),
                    mesh.num_vertices(),
                    mesh.num_triangles()
                );
                true
            }
            Err(e) => {
                self.status = refuse(e.to_string());
                false
            }
        }
    }

    /// Saves the document as SWP to `path` (through a temporary file, so a failed write
    /// leaves the file as it was), which becomes the document's file. The document is first
    /// checked with the reader's rules: a curve the reader would refuse blocks the save with
    /// a message naming it, and nothing is written. Returns whether it was written.
    pub fn save_swp(&mut self, path: &Path) -> bool {
        let text = match writable_swp(&self.doc.swp) {
            Ok(text) => text,
            Err(why) => {
                self.status = format!("Error: not saved: {why}");
                return false;
            }
        };
        let result = splinekit_io::atomic::write_file(path, |w| -> std::io::Result<()> {
            use std::io::Write;
            w.write_all(text.as_bytes())
        });
        match result {
            Ok(()) => {
                self.doc.mark_saved(path);
                self.recent.add(path);
                self.status = format!("Saved {}", path.display());
                true
            }
            Err(e) => {
                // the editor has no --force: its way out is another file
                let why = e.to_string().replace(splinekit_io::atomic::READ_ONLY_HINT, "Save as… writes another file");
                self.status = format!("Error: cannot write {}: {why}", path.display());
                false
            }
        }
    }

    /// Exports the shown surface (the mesh's level, or the document's surfaces) in the format
    /// of `path`'s extension (obj, glb, ply, stl). Never writes the document's own file.
    pub fn export(&mut self, path: &Path) {
        if self.doc.path().is_some_and(|own| files::same_file(own, path)) {
            self.status = format!("Error: {} is the open document's file; export to another name", path.display());
            return;
        }
        let Some(format) = MeshFormat::from_path(path) else {
            self.status =
                format!("Error: {}: unknown extension (expected one of {})", path.display(), MeshFormat::list());
            return;
        };
        // the mesh shown, or the document to sweep in full if what is shown is a preview or
        // still being swept
        let source = if let Some(m) = &self.mesh {
            Ok(ExportSource::Mesh(m.shown()))
        } else if self.doc.swp.surfaces.is_empty() {
            Err("the document has no surface (add srev or gcyl to the SWP file)".to_owned())
        } else if self.surfaces_for == Some((self.doc.revision(), true)) {
            match self.surfaces.errors.first() {
                Some(e) => Err(e.clone()),
                None => Ok(ExportSource::Mesh(self.surfaces.mesh.clone())),
            }
        } else {
            Ok(ExportSource::Sweep(self.doc.swp.clone()))
        };
        let source = match source {
            Ok(source) => source,
            Err(e) => {
                self.status = format!("Error: {e}");
                return;
            }
        };
        let big = match &source {
            ExportSource::Mesh(m) => m.num_triangles() > BACKGROUND_FACES,
            ExportSource::Sweep(_) => true,
        };
        let file = path.to_path_buf();
        let work = move |progress: Option<&work::Progress>| -> Result<usize, String> {
            let mesh = match source {
                ExportSource::Mesh(m) => m,
                ExportSource::Sweep(swp) => {
                    let swept = SweptSurfaces::sweep(&swp);
                    if let Some(e) = swept.errors.first() {
                        return Err(e.clone());
                    }
                    swept.mesh
                }
            };
            let cancelled = || progress.is_some_and(work::Progress::is_cancelled);
            splinekit_io::mesh::save_cancellable(&mesh, &file, format, &cancelled).map_err(|e| e.to_string())?;
            Ok(mesh.num_triangles())
        };
        if big {
            let label = format!("Exporting {}", path.display());
            let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |p| work(Some(p)));
            self.export_task = Some((path.to_path_buf(), task));
            self.status = format!("Exporting {}…", path.display());
            return;
        }
        self.exported(path, work(None));
    }

    fn exported(&mut self, path: &Path, result: Result<usize, String>) {
        self.status = match result {
            Ok(n) => format!("Exported {} ({n} triangles)", path.display()),
            Err(e) => format!("Error: {e}"),
        };
    }

    /// Takes the result of an export on a worker thread, if it is done.
    pub(crate) fn poll_export(&mut self) {
        let Some((path, task)) = &mut self.export_task else { return };
        let Some(result) = task.poll() else { return };
        let path = path.clone();
        self.export_task = None;
        self.exported(&path, result.and_then(|r| r));
    }

    /// Whether a mesh is being exported on a worker thread.
    #[must_use]
    pub fn is_exporting(&self) -> bool {
        self.export_task.is_some()
    }
}

/// The SWP text of `swp`, if the reader reads it back to the same document; else why not
/// (the first curve or surface that breaks a rule, in words).
fn writable_swp(swp: &SwpDocument) -> Result<String, String> {
    swp.validate().map_err(|e| e.to_string())?;
    let text = swp.to_swp_string();
    let back = SwpDocument::parse(&text, "the saved text").map_err(|e| e.to_string())?;
    if without_positions(&back) != without_positions(swp) {
        return Err("the document would not read back the same".to_owned());
    }
    Ok(text)
}

/// `swp` with every source position set to line 1, column 1 (for comparing documents).
fn without_positions(swp: &SwpDocument) -> SwpDocument {
    let mut d = swp.clone();
    let p = splinekit_io::SourcePos::new(1, 1);
    d.curves.iter_mut().for_each(|c| c.pos = p);
    d.surfaces.iter_mut().for_each(|s| s.pos = p);
    d
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::*;
    use crate::{Document, doc};

    /// One edit a person can make in the editor.
    #[derive(Clone, Debug)]
    enum Edit {
        Add(f64, f64),
        Insert { edge: usize, t: f64 },
        Move { index: usize, x: f64, y: f64 },
        Delete(usize),
        Kind(usize),
        Closed(bool),
        AddCurve,
        Select(usize),
        Clear,
        Undo,
        Redo,
    }

    fn edit() -> impl Strategy<Value = Edit> {
        let coord = -10.0..10.0f64;
        prop_oneof![
            6 => (coord.clone(), coord.clone()).prop_map(|(x, y)| Edit::Add(x, y)),
            2 => (0..12usize, 0.0..1.0f64).prop_map(|(edge, t)| Edit::Insert { edge, t }),
            2 => (0..12usize, coord.clone(), coord).prop_map(|(index, x, y)| Edit::Move { index, x, y }),
            1 => (0..12usize).prop_map(Edit::Delete),
            2 => (0..doc::KINDS.len()).prop_map(Edit::Kind),
            1 => any::<bool>().prop_map(Edit::Closed),
            1 => Just(Edit::AddCurve),
            1 => (0..4usize).prop_map(Edit::Select),
            1 => Just(Edit::Clear),
            1 => Just(Edit::Undo),
            1 => Just(Edit::Redo),
        ]
    }

    fn apply(doc: &mut Document, e: &Edit) {
        match *e {
            Edit::Add(x, y) => doc.add_point(DVec3::new(x, y, 0.0)),
            Edit::Insert { edge, t } => {
                let n = doc.points().len();
                if n >= 2 {
                    let (a, b) = (doc.points()[edge % n], doc.points()[(edge % n + 1) % n]);
                    doc.insert_on_polygon(edge % n, t, a.lerp(b, t));
                }
            }
            Edit::Move { index, x, y } => doc.move_point(index, DVec3::new(x, y, 0.0)),
            Edit::Delete(i) => doc.delete_point(i),
            Edit::Kind(k) => doc.set_kind(doc::KINDS[k].0),
            Edit::Closed(c) => doc.set_closed(c),
            Edit::AddCurve => doc.add_curve(),
            Edit::Select(i) => doc.select_curve(i),
            Edit::Clear => doc.clear(),
            Edit::Undo => {
                doc.undo();
            }
            Edit::Redo => {
                doc.redo();
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

        /// Any sequence of edits, saved: either the save is refused and nothing is written,
        /// or the file re-opens to the same document (#36).
        #[test]
        fn a_saved_file_reopens_to_the_same_document(edits in proptest::collection::vec(edit(), 0..30)) {
            let dir = std::env::temp_dir().join(format!("splinekit-editor-prop-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let path = dir.join("doc.swp");
            let _ = std::fs::remove_file(&path);
            let mut app = EditorApp::default();
            for e in &edits {
                apply(&mut app.doc, e);
            }
            let valid = app.doc.swp.validate().is_ok();
            let saved = app.save_swp(&path);
            prop_assert_eq!(saved, valid, "{}", app.status);
            if saved {
                let back = Document::read(&path).unwrap();
                prop_assert_eq!(without_positions(&back.swp), without_positions(&app.doc.swp));
                prop_assert!(!app.doc.is_modified());
            } else {
                prop_assert!(!path.exists());
                prop_assert!(app.status.starts_with("Error: not saved: curve"), "{}", app.status);
            }
        }
    }

    /// Inserting on a Bézier spline's polygon splits the segment: the curve keeps its shape.
    #[test]
    fn inserting_on_a_bezier_polygon_keeps_the_shape() {
        use splinekit::ParamCurve as _;
        for closed in [false, true] {
            let mut doc = Document::new();
            doc.set_kind(splinekit_io::SwpCurveKind::Bezier);
            let n: u32 = if closed { 6 } else { 7 };
            for k in 0..n {
                let a = f64::from(k) * 0.9;
                doc.add_point(DVec3::new(a.cos() * (1.0 + a), a.sin(), 0.0));
            }
            doc.set_closed(closed);
            let before = doc.spline().unwrap();
            // the middle edge of the second segment, a third of the way along
            let at = doc.insert_on_polygon(4, 1.0 / 3.0, DVec3::ZERO);
            assert_eq!(doc.points().len(), n as usize + 3);
            let after = doc.spline().unwrap();
            assert_eq!(after.num_segments(), before.num_segments() + 1);
            // the new on-curve point is the old curve at u = 1 + (1 + 1/3)/3
            let u = 1.0 + (1.0 + 1.0 / 3.0) / 3.0;
            assert!((doc.points()[at] - before.eval(u)).length() < 1e-12, "closed {closed}");
            // the split segment's halves are the old segment over [0, u] and [u, 1]; the
            // other segments are as before
            let split = (1.0 + 1.0 / 3.0) / 3.0;
            let old_param = |v: f64| match v {
                v if v <= 1.0 => v,
                v if v <= 2.0 => 1.0 + (v - 1.0) * split,
                v if v <= 3.0 => 1.0 + split + (v - 2.0) * (1.0 - split),
                v => v - 1.0,
            };
            let m = after.num_segments();
            for j in 0..=50 * m {
                let v = j as f64 / 50.0;
                let d = (after.eval(v) - before.eval(old_param(v))).length();
                assert!(d < 1e-12, "closed {closed}: v = {v}: {d}");
            }
        }
    }
}
