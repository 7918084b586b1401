//! The editor application: its state ([`EditorApp`]), one frame of its user interface
//! (panels, views, windows, the status line, the window title and close), and [`run`].

use std::path::{Path, PathBuf};

use eframe::egui;
use splinekit_render::{Legend, SurfaceColour};

use crate::files::{FileDialog, Purpose, RecentFiles};
use crate::open::Loaded;
use crate::scene::Shown;
use crate::subdivision::{MeshKey, Refined};
use crate::surfaces::SweepResult;
use crate::{
    Document, Layout, MeshState, Pending, Plane, RevolveAxis, SweptSurfaces, View2d, View3d, compare, doc, view3d, work,
};

/// The editor application.
pub struct EditorApp {
    /// The document.
    pub doc: Document,
    /// The 2D view.
    pub view: View2d,
    /// The document's mesh with its subdivision levels (shown instead of the surfaces).
    pub mesh: Option<MeshState>,
    /// Colour the subdivision levels.
    pub color_by_level: bool,
    /// The axis `Revolve` turns the active curve about.
    pub revolve_axis: RevolveAxis,
    /// How the 3D view colours the surfaces or the mesh (`Colour`): shaded, by mean or
    /// Gaussian curvature, or a UV checker (the level colours are `Colour by level`).
    pub colouring: SurfaceColour,
    /// The legend of the colours shown in the 3D view (curvature scale, or levels).
    pub(crate) legend: Option<Legend>,
    /// The loaded mesh refined by two to four schemes side by side (`compare SCHEME`).
    pub compare: compare::Comparison,
    /// The colouring the 3D view's data was made with.
    pub(crate) shown_colouring: Option<(SurfaceColour, bool)>,
    /// The 3D view (its settings: wireframe, normals, …).
    pub view3d: View3d,
    /// The last message (errors start with "Error").
    pub status: String,
    /// Show the help window.
    pub show_help: bool,
    /// Which panels are shown.
    pub layout: Layout,
    /// Show the arc-length table window.
    pub show_table: bool,
    /// The open file dialog.
    pub dialog: Option<FileDialog>,
    /// What to do once the Save as dialog has saved (an action that asked first).
    pub(crate) dialog_then: Option<Pending>,
    /// The action waiting for an answer to "unsaved changes: Save / Discard / Cancel".
    pub prompt: Option<Pending>,
    /// The recent files (the Open dialog lists them).
    pub recent: RecentFiles,
    /// Whether the window may close (the user answered, or nothing was unsaved).
    pub(crate) close_allowed: bool,
    /// Whether the window was told to close.
    pub(crate) close_sent: bool,
    /// The title last given to the window.
    pub(crate) title_sent: String,
    /// The document's surfaces, swept at `surfaces_for`'s revision (in full, or a preview).
    pub(crate) surfaces: SweptSurfaces,
    pub(crate) surfaces_for: Option<(u64, bool)>,
    /// Their vertex data when they were swept in the background, for the 3D view.
    pub(crate) prepared: Option<view3d::PreparedMesh>,
    /// The sweep running in the background, and the revision it sweeps.
    pub(crate) sweep_task: Option<(u64, work::Task<SweepResult>)>,
    /// The revision whose sweep the user cancelled (not started again until an edit).
    pub(crate) sweep_cancelled: Option<u64>,
    /// The value widget being dragged or typed into (its edits make one undo step).
    pub(crate) value_edit: Option<egui::Id>,
    /// The window's context (once it has drawn), woken by workers when they finish.
    pub(crate) egui_ctx: Option<egui::Context>,
    /// A mesh being exported on a worker thread (its file, and how many triangles it wrote).
    pub(crate) export_task: Option<(PathBuf, work::Task<Result<usize, String>>)>,
    /// A mesh file being read on a worker thread.
    pub(crate) load_task: Option<(PathBuf, work::Task<Result<Loaded, String>>)>,
    /// A subdivision level being made on a worker thread, for the mesh level it refines.
    pub(crate) refine_task: Option<(MeshKey, work::Task<Result<Refined, String>>)>,
    /// The 3D view data of a mesh level made on a worker thread.
    pub(crate) prepared_mesh: Option<(MeshKey, view3d::PreparedMesh)>,
    /// Bumped whenever the mesh or its levels change.
    pub(crate) mesh_generation: u64,
    pub(crate) shown: Option<Shown>,
    /// The [`Document::file_id`] of the document the views were last fitted to.
    pub(crate) fitted_file: Option<u64>,
}

impl Default for EditorApp {
    fn default() -> Self {
        Self {
            doc: Document::new(),
            view: View2d::default(),
            mesh: None,
            color_by_level: false,
            revolve_axis: RevolveAxis::Y,
            colouring: SurfaceColour::Shade,
            legend: None,
            compare: compare::Comparison::default(),
            shown_colouring: None,
            view3d: View3d::new(),
            status: "Shift+click to add points; press h for help".to_owned(),
            show_help: false,
            layout: Layout::default(),
            show_table: false,
            dialog: None,
            dialog_then: None,
            prompt: None,
            recent: RecentFiles::default(),
            close_allowed: false,
            close_sent: false,
            title_sent: String::new(),
            surfaces: SweptSurfaces::default(),
            surfaces_for: None,
            prepared: None,
            sweep_task: None,
            sweep_cancelled: None,
            value_edit: None,
            egui_ctx: None,
            export_task: None,
            load_task: None,
            refine_task: None,
            prepared_mesh: None,
            mesh_generation: 0,
            shown: None,
            fitted_file: None,
        }
    }
}

impl EditorApp {
    /// A new editor with the recent files of the settings folder; opens `file` if given (an
    /// error goes to the status line, and the editor starts with a new document).
    #[must_use]
    pub fn new(file: Option<&Path>) -> Self {
        let mut app = Self { recent: RecentFiles::load(), ..Self::default() };
        if let Some(file) = file {
            app.open_file(file);
        }
        app
    }

    /// The window title: `NAME — splinekit`, with a leading `*` while the document has
    /// unsaved changes (`untitled` for a new document).
    #[must_use]
    pub fn title(&self) -> String {
        let star = if self.doc.is_modified() { "*" } else { "" };
        format!("{star}{} — splinekit", self.doc.display_name())
    }

    /// Whether a dialog or question is open (the rest of the window then waits).
    #[must_use]
    pub fn modal_open(&self) -> bool {
        self.dialog.is_some() || self.prompt.is_some()
    }

    /// Says the active curve's kind on the status line (after the kind changed).
    pub(crate) fn status_kind(&mut self) {
        if let Some(c) = self.doc.curve() {
            self.status = format!("Kind: {}", doc::kind_name(c.kind));
        }
    }

    /// Loads the preset scene, first asking about unsaved changes.
    pub fn preset(&mut self) {
        self.request(Pending::Preset);
    }

    /// Loads the preset scene (one undo step): an open uniform Catmull-Rom spline through 8
    /// points of a 3D curve, the arc-length lab's reference scene.
    pub(crate) fn preset_now(&mut self) {
        self.doc.preset();
        self.sync_mesh();
        self.view.plane = Plane::Xy;
        self.view.fit_pending = true;
        self.view3d.fit_on_next_mesh();
        self.status = "Preset scene: open uniform Catmull-Rom spline through 8 points".to_owned();
    }

    /// Undoes the last edit.
    pub fn undo(&mut self) {
        if !self.doc.undo() {
            self.status = "Nothing to undo".to_owned();
        }
        self.sync_mesh();
        self.view.selected = None;
    }

    /// Redoes the last undone edit.
    pub fn redo(&mut self) {
        if !self.doc.redo() {
            self.status = "Nothing to redo".to_owned();
        }
        self.sync_mesh();
        self.view.selected = None;
    }

    /// The whole user interface (one frame); the 3D view renders with `frame`'s wgpu
    /// renderer.
    pub fn ui(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.egui_ctx.get_or_insert_with(|| ctx.clone());
        self.on_close_request(&ctx);
        self.keyboard(&ctx);
        // a file dropped on the window opens (asking first about unsaved changes)
        let dropped = ctx.input(|i| i.raw.dropped_files.first().map(|f| f.path().to_path_buf()));
        if let Some(path) = dropped
            && !self.modal_open()
        {
            // a file the editor cannot open is refused before anything is asked
            match Purpose::Open.refuse_extension(&path) {
                Some(why) => self.status = format!("Error: {why}"),
                None => self.request(Pending::Open(path)),
            }
        }
        self.poll_load();
        self.poll_refine();
        self.poll_export();
        self.sync_mesh();
        egui::Panel::top("file bar").show(ui, |ui| self.file_bar(ui));
        // one line, so the views keep their size whatever it says
        egui::Panel::bottom("status").show(ui, |ui| {
            if let Some((_, task)) = &self.load_task
                && task.ui(ui)
            {
                self.cancel_load();
                self.status = "Cancelled opening the file".to_owned();
            }
            if let Some((_, task)) = &self.export_task
                && task.ui(ui)
            {
                // the worker stops at its next write, and the file is written through a
                // temporary file: cancelled, it is not created or replaced
                cancel(&mut self.export_task);
                self.status = "Cancelled the export (the file was not written)".to_owned();
            }
            ui.horizontal(|ui| {
                let error = self.status.starts_with("Error");
                let text = egui::RichText::new(&self.status);
                ui.label(if error { text.color(egui::Color32::from_rgb(200, 30, 30)) } else { text });
                if let Some(problem) = self.doc.curve_problem() {
                    ui.separator();
                    ui.label(problem);
                }
            });
        });
        // wide grab areas for the panel dividers
        ctx.global_style_mut(|style| style.interaction.resize_grab_radius_side = 8.0);
        if self.layout.curves_panel {
            egui::Panel::left("curves").resizable(true).show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.left_panel(ui));
            });
        }
        match (self.layout.view2d, self.layout.view3d) {
            (true, true) => {
                let half = 0.45 * ui.available_width();
                egui::Panel::right("surface").default_size(half).min_size(220.0).resizable(true).show(ui, |ui| {
                    self.right_panel(ui, frame);
                });
                egui::CentralPanel::default().show(ui, |ui| {
                    self.view.ui(ui, &mut self.doc);
                });
            }
            (false, _) => {
                egui::CentralPanel::default().show(ui, |ui| self.right_panel(ui, frame));
            }
            (true, false) => {
                egui::CentralPanel::default().show(ui, |ui| {
                    self.view.ui(ui, &mut self.doc);
                });
            }
        }
        self.windows(&ctx);
        self.unsaved_prompt(&ctx);
        self.file_dialog(&ctx);
        if self.close_allowed && !self.close_sent && ctx.input(|i| !i.viewport().close_requested()) {
            // the user answered the question: close now
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            self.close_sent = true;
        }
        let title = self.title();
        if title != self.title_sent {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title_sent = title;
        }
    }
}

/// Stops waiting for the task in `slot` (the work stops at its next check; its result is
/// dropped).
pub(crate) fn cancel<K, T>(slot: &mut Option<(K, work::Task<T>)>) {
    if let Some((_, task)) = slot.take() {
        task.cancel();
    }
}

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        EditorApp::ui(self, ui, frame);
    }
}

/// Opens the editor window (blocks until it is closed).
///
/// # Errors
///
/// When the window or its renderer cannot be created (for example, no display).
pub fn run(file: Option<PathBuf>) -> anyhow::Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1280.0, 800.0]).with_title("splinekit"),
        ..Default::default()
    };
    eframe::run_native("splinekit", options, Box::new(move |_cc| Ok(Box::new(EditorApp::new(file.as_deref())))))
        .map_err(|e| anyhow::anyhow!("cannot open the editor window: {e}"))
}
