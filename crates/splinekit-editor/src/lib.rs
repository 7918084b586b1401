//! The splinekit editor (`splinekit edit [FILE]`): 2D curve editing and the surfaces swept
//! from the curves, or a mesh opened for viewing with its subdivision.
//!
//! The window has a file bar (`Open…`, `Save`, `Save as…`, `Export mesh…`, undo, redo, the
//! preset scene, help), a left panel (curves, kind, closed, plane, what to show), the 2D curve
//! view in the middle, a right panel with the surface or mesh, its subdivision and the 3D view
//! ([`View3d`]), and a status line for messages and errors. An error never changes the
//! document.
//!
//! **Files.** The document knows its file and its kind ([`DocKind`]): Save (Ctrl+S) writes an
//! SWP document back to its file, and asks for a name (as Save as, Ctrl+Shift+S) for a new
//! document or a mesh opened for viewing, which is never written back. Open (Ctrl+O), Save as
//! and Export mesh use a file dialog in the window ([`files::FileDialog`]). A document is
//! checked before it is written, with the rules the reader applies: a file the editor cannot
//! read back is never written. The window title is `NAME — splinekit`, with a leading `*`
//! while the document has unsaved changes; closing the window, opening a file (also by
//! dropping it on the window), New (Ctrl+N), the preset scene and Close mesh ask first
//! (`Save` / `Discard` / `Cancel`). Opening a file is one undo step.
//!
//! The 3D view shows the document's surfaces, swept again whenever the document changes (so
//! they follow a dragged point live), or the mesh at the subdivision level shown. The
//! control points of an active 3D curve are handles there too, dragged in the plane parallel
//! to the screen.
//!
//! Keyboard (when no text field has focus; every press counts, however slow the frame): `r`
//! preset scene, `s` cycle the spline kind, `c` clear the curve, `a` arc-length markers, `l`
//! control polygon, `w` wireframe, `n` normals (curve and surface), `f` fit both views, `h` or
//! `?` help, Delete the selected point, Ctrl+Z undo, Ctrl+Shift+Z (or Ctrl+Y) redo, Ctrl+S save,
//! Ctrl+Shift+S save as, Ctrl+O open, Ctrl+N new.

pub mod compare;
pub mod doc;
pub mod files;
pub mod view2d;
pub mod view3d;
pub mod work;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use eframe::egui::{self, Key, Modifiers};
use splinekit::subdiv::{
    ButterflyOptions, CatmullClarkOptions, Creases, CreasingMethod, DooSabinOptions, LoopOptions, LoopPyramid,
    Sqrt3Options, butterfly_step, catmull_clark_step, catmull_clark_subdivide_creased, doo_sabin_subdivide,
    loop_subdivide_creased, sqrt3_subdivide,
};
use splinekit::{PolyMesh, Tcb, TriMesh};
use splinekit_io::mesh::{MeshFormat, RebuildOptions, SplineHeader};
use splinekit_io::surface::{SurfaceError, SurfaceOptions};
use splinekit_io::{SwpDocument, SwpFrames, SwpSurfaceKind, SwpSurfaceSettings, SwpTessellation};
use splinekit_render::legend::format_value;
use splinekit_render::{Curvature, Legend, SurfaceColour, diverging_colour, level_colour};

pub use doc::{DocKind, Document, ViewedMesh};
use files::{FileDialog, Outcome, Purpose, RecentFiles};
pub use view2d::{Plane, View2d};
pub use view3d::{View3d, View3dSettings};

/// The mouse actions, as the help window lists them.
pub const MOUSE: [(&str, &str); 10] = [
    ("Shift+click (2D view)", "add a point at the end of the curve"),
    ("click on the control polygon", "insert a point there (a Bézier spline is split, keeping its shape)"),
    ("click a point", "select it"),
    ("drag a point", "move it (in the 3D view too, parallel to the screen)"),
    ("right-click a point", "menu: delete the point"),
    ("drag the background (2D)", "pan"),
    ("scroll (2D)", "zoom about the pointer"),
    ("drag (3D view)", "orbit; Shift+drag or right-drag: pan; scroll: zoom"),
    ("double-click (file dialog)", "open a folder or choose a file"),
    ("drop a file on the window", "open it"),
];

/// The keyboard shortcuts, as the help window lists them.
pub const SHORTCUTS: [(&str, &str); 17] = [
    ("Ctrl+O / Ctrl+S", "open / save"),
    ("Ctrl+Shift+S", "save as"),
    ("Ctrl+N", "new document"),
    ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo (Ctrl+Y redoes too)"),
    ("Delete", "delete the selected point"),
    ("r", "preset scene (8 points, Catmull-Rom)"),
    ("s", "cycle the spline kind"),
    ("c", "clear the curve"),
    ("a", "arc-length markers"),
    ("l", "control polygon"),
    ("w", "wireframe (3D view)"),
    ("n", "normals (curve and surface)"),
    ("f", "fit both views"),
    ("h or ?", "this help"),
    ("Enter / Escape", "confirm / cancel a dialog"),
    ("Tab", "next field"),
    ("Escape", "leave a text field"),
];

/// Which panels are shown (the View menu): hide the 2D view to give the 3D view the room, or
/// the curve panel on a small screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The curve panel on the left.
    pub curves_panel: bool,
    /// The 2D curve view.
    pub view2d: bool,
    /// The surface panel with the 3D view.
    pub view3d: bool,
}

impl Default for Layout {
    fn default() -> Self {
        Self { curves_panel: true, view2d: true, view3d: true }
    }
}

/// An action that replaces or closes the document, so it asks first when the document has
/// unsaved changes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Pending {
    /// Close the window.
    Close,
    /// Open this file.
    Open(PathBuf),
    /// Show the Open dialog.
    OpenDialog,
    /// Load the preset scene.
    Preset,
    /// Start a new, empty document.
    New,
    /// Close the mesh shown (a new, empty document).
    CloseMesh,
}

impl Pending {
    /// What the action does, for the question.
    fn doing(&self) -> &'static str {
        match self {
            Self::Close => "closing the window",
            Self::Open(_) | Self::OpenDialog => "opening another file",
            Self::Preset => "loading the preset scene",
            Self::New => "starting a new document",
            Self::CloseMesh => "closing the mesh",
        }
    }
}

/// The subdivision schemes the editor offers for a loaded mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scheme {
    /// Loop (triangle meshes).
    #[default]
    Loop,
    /// Catmull-Clark (any polygon mesh; quads after one level).
    CatmullClark,
    /// Kobbelt's √3 (triangle meshes; the boundary is refined every second level).
    Sqrt3,
    /// Doo-Sabin (any polygon mesh; a face per face, edge and vertex).
    DooSabin,
    /// Modified butterfly (triangle meshes; interpolating: vertices stay where they are).
    Butterfly,
}

impl Scheme {
    /// Every scheme, in the menu's order.
    pub const ALL: [Self; 5] = [Self::Loop, Self::CatmullClark, Self::Sqrt3, Self::DooSabin, Self::Butterfly];

    /// The name in the scheme menu.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Loop => "Loop",
            Self::CatmullClark => "Catmull-Clark",
            Self::Sqrt3 => "√3",
            Self::DooSabin => "Doo-Sabin",
            Self::Butterfly => "Butterfly",
        }
    }

    /// Whether the scheme has creases (Loop and Catmull-Clark).
    #[must_use]
    pub fn has_creases(self) -> bool {
        matches!(self, Self::Loop | Self::CatmullClark)
    }

    /// Level `depth` of `base` (`depth ≥ 1`) from level `depth − 1`, `coarse`, for the
    /// schemes other than Loop without creases (whose levels are a [`LoopPyramid`]). With
    /// `creases` (on `base`), Loop and Catmull-Clark make it from `base` with them (Chaikin's
    /// creasing, as OpenSubdiv's default in the command line).
    pub(crate) fn polygon_level(
        self,
        base: &PolyMesh,
        coarse: &PolyMesh,
        creases: &Creases,
        depth: usize,
        color_by_level: bool,
    ) -> Result<PolyMesh, String> {
        let method = CreasingMethod::Chaikin;
        match self {
            Self::Loop if !creases.is_empty() => {
                let options = LoopOptions { color_by_level, ..LoopOptions::default() };
                loop_subdivide_creased(base, depth as u32, &options, creases, method).map(|(fine, _)| fine)
            }
            Self::CatmullClark if !creases.is_empty() => {
                let options = CatmullClarkOptions { color_by_level, ..CatmullClarkOptions::default() };
                catmull_clark_subdivide_creased(base, depth, &options, creases, method).map(|(fine, _)| fine)
            }
            Self::Loop | Self::CatmullClark => {
                let options = CatmullClarkOptions { color_by_level, ..CatmullClarkOptions::default() };
                catmull_clark_step(coarse, depth, &options)
            }
            // From the loaded mesh: the boundary rule depends on the level's parity.
            Self::Sqrt3 => sqrt3_subdivide(base, depth, &Sqrt3Options { color_by_level }),
            Self::DooSabin => doo_sabin_subdivide(coarse, 1, &DooSabinOptions::default()),
            Self::Butterfly => butterfly_step(coarse, depth, &ButterflyOptions { color_by_level }),
        }
        .map_err(|e| e.to_string())
    }
}

/// The mesh opened for viewing and its subdivision levels.
pub struct MeshState {
    /// Where it came from.
    pub name: String,
    /// The document's mesh: the loaded mesh (triangles or polygons) and its sharp and
    /// semi-sharp edges and vertices (its OBJ's crease tags), used by Loop and Catmull-Clark.
    pub source: Arc<ViewedMesh>,
    /// The Loop levels (level 0 is the loaded mesh), or why it cannot be Loop-subdivided.
    pub pyramid: Result<LoopPyramid, String>,
    /// The levels 1, 2, … made so far with `scheme` when it is not Loop without creases.
    pub levels: Vec<PolyMesh>,
    /// The scheme of the levels shown.
    pub scheme: Scheme,
    /// The level shown.
    pub level: usize,
}

impl MeshState {
    /// Whether the levels are the Loop pyramid's (Loop without creases).
    fn uses_pyramid(&self) -> bool {
        self.scheme == Scheme::Loop && self.source.creases.is_empty()
    }

    /// The level shown of a scheme other than Loop (the loaded mesh at level 0).
    fn polygon_level(&self) -> &PolyMesh {
        if self.level == 0 { &self.source.base } else { &self.levels[self.level - 1] }
    }

    /// The number of faces of the level shown.
    #[must_use]
    pub fn faces(&self) -> usize {
        match (self.uses_pyramid(), &self.pyramid) {
            (true, Ok(p)) => p.level(self.level).num_triangles(),
            (true, Err(_)) => self.source.base.num_faces(),
            _ => self.polygon_level().num_faces(),
        }
    }

    /// The number of vertices of the level shown.
    #[must_use]
    pub fn vertices(&self) -> usize {
        match (self.uses_pyramid(), &self.pyramid) {
            (true, Ok(p)) => p.level(self.level).num_vertices(),
            (true, Err(_)) => self.source.base.positions.len(),
            _ => self.polygon_level().num_vertices(),
        }
    }

    /// The level shown, triangulated for the 3D view and export.
    #[must_use]
    pub fn shown(&self) -> TriMesh {
        match (self.uses_pyramid(), &self.pyramid) {
            (true, Ok(p)) => p.level(self.level).clone().into_tri_mesh(),
            (true, Err(_)) => self.source.base.to_tri_mesh(),
            _ => self.polygon_level().to_tri_mesh(),
        }
    }

    /// Whether the level shown can be refined.
    #[must_use]
    pub fn can_refine(&self) -> bool {
        !self.uses_pyramid() || self.pyramid.is_ok()
    }
}

/// The document's surfaces as the editor shows them: all of them in one mesh, and a line
/// per surface for the surface panel.
#[derive(Clone, Debug, Default)]
pub struct SweptSurfaces {
    /// Every surface that could be swept, merged (triangles of later surfaces after those
    /// of earlier ones).
    pub mesh: TriMesh,
    /// Per surface: its name and counts, or why it cannot be swept.
    pub lines: Vec<String>,
    /// Why surfaces cannot be swept (each also in `lines`).
    pub errors: Vec<String>,
}

impl SweptSurfaces {
    /// Sweeps every surface of `swp` with the default options.
    #[must_use]
    pub fn sweep(swp: &SwpDocument) -> Self {
        Self::sweep_with(swp, &SurfaceOptions::default())
    }

    /// Sweeps every surface of `swp` if they have at most `limit` triangles in all (the
    /// editor's path on every change of the document, e.g. every frame of a drag); else
    /// returns how many they would have (from the sample counts, before building them).
    ///
    /// # Errors
    ///
    /// The triangle count, when it is over `limit`.
    pub fn sweep_within(swp: &SwpDocument, limit: usize) -> Result<Self, u64> {
        let mut out = Self::default();
        // the triangles of the surfaces that did not fit (counted, not built)
        let mut skipped = 0u64;
        for (i, s) in swp.surfaces.iter().enumerate() {
            let total = out.mesh.num_triangles() as u64 + skipped;
            let left = usize::try_from((limit as u64).saturating_sub(total)).unwrap_or(usize::MAX);
            let options = SurfaceOptions { max_triangles: Some(left), ..SurfaceOptions::default() };
            let result = match swp.surface_mesh(i, &options) {
                Err(SurfaceError::TooLarge { triangles, .. }) if triangles <= EDITOR_MAX_TRIANGLES as u64 => {
                    skipped += triangles;
                    continue;
                }
                // too large for the editor: the message of its own limit
                Err(SurfaceError::TooLarge { .. }) => swp.surface_mesh(i, &editor_sweep_options()),
                result => result,
            };
            out.push(&s.display_name(i), result);
        }
        if skipped > 0 { Err(out.mesh.num_triangles() as u64 + skipped) } else { Ok(out) }
    }

    /// A preview of `swp`'s surfaces with about `limit` triangles, for surfaces of about
    /// `estimate` triangles: every curve's and revolution's steps divided by the same factor.
    /// Each line says it is a preview.
    #[must_use]
    pub fn preview(swp: &SwpDocument, limit: usize, estimate: u64) -> Self {
        let mut factor = (estimate as f64 / limit as f64).sqrt() * 1.05;
        for _ in 0..6 {
            let mut coarse = swp.clone();
            let scaled = |steps: u32, min: u32| ((f64::from(steps) / factor).ceil() as u32).clamp(min, steps.max(min));
            for c in &mut coarse.curves {
                c.steps = scaled(c.steps, 1);
            }
            for s in &mut coarse.surfaces {
                match &mut s.kind {
                    SwpSurfaceKind::Revolution { steps, .. } => *steps = scaled(*steps, 3),
                    SwpSurfaceKind::Lathe { stacks, slices, .. } => {
                        *stacks = scaled(*stacks, 1);
                        *slices = scaled(*slices, 3);
                    }
                    // coarser angles: the profile's pieces and the slices
                    SwpSurfaceKind::RevolutionZ { epsilon, slice_tolerance, .. } => {
                        *epsilon = (*epsilon * factor).min(std::f64::consts::PI);
                        *slice_tolerance = (*slice_tolerance * factor).min(std::f64::consts::TAU / 3.0);
                    }
                    SwpSurfaceKind::ToolSweep { epsilon, path_epsilon, .. } => {
                        *epsilon = (*epsilon * factor).min(std::f64::consts::PI);
                        *path_epsilon = (*path_epsilon * factor).min(std::f64::consts::PI);
                    }
                    SwpSurfaceKind::GeneralizedCylinder { .. } => {}
                }
                // the samples of a distance tolerance go as 1/√d
                match &mut s.settings.tessellation {
                    Some(SwpTessellation::Distance(d)) => *d *= factor * factor,
                    Some(SwpTessellation::AngleDegrees(a)) => *a = (*a * factor).min(180.0),
                    None => {}
                }
            }
            if let Ok(mut out) = Self::sweep_within(&coarse, limit) {
                let shown = out.mesh.num_triangles();
                for line in &mut out.lines {
                    line.push_str(" (preview while dragging)");
                }
                out.lines.push(format!(
                    "Preview: {shown} of about {estimate} triangles; the whole surface follows on release"
                ));
                return out;
            }
            // curves with many segments do not scale with their steps alone
            factor *= 2.0;
        }
        Self { lines: vec![format!("No preview: about {estimate} triangles")], ..Self::default() }
    }

    fn sweep_with(swp: &SwpDocument, options: &SurfaceOptions) -> Self {
        let mut out = Self::default();
        for (i, s) in swp.surfaces.iter().enumerate() {
            out.push(&s.display_name(i), swp.surface_mesh(i, options));
        }
        out
    }

    /// Adds surface `name`'s mesh, or why it cannot be swept.
    fn push(&mut self, name: &str, result: Result<TriMesh, SurfaceError>) {
        match result {
            Ok(m) => {
                self.lines.push(format!("{name}: {} vertices, {} triangles", m.num_vertices(), m.num_triangles()));
                append(&mut self.mesh, &m);
            }
            Err(e) => {
                self.lines.push(format!("{name}: {e}"));
                self.errors.push(format!("{name}: {e}"));
            }
        }
    }
}

/// The slices of a surface of revolution made with `Revolve`.
pub const DEFAULT_SLICES: u32 = 32;

/// Surfaces with more triangles than this are swept off the UI thread, and shown at reduced
/// resolution while a point is dragged (the whole surface follows on release).
pub const LIVE_TRIANGLES: usize = 200_000;

/// The most triangles the editor sweeps and shows (a larger surface gets a message instead):
/// 20 million triangles take about 1.7 GB of vertex data for the 3D view.
pub const EDITOR_MAX_TRIANGLES: usize = 20_000_000;

/// The size of the preview shown while a point of a larger surface is dragged: about 40 ms a
/// frame on this project's 2-core machine with a software renderer (sweep, vertex data, draw).
pub const PREVIEW_TRIANGLES: usize = 100_000;

/// What the 3D view was last given: the document's surfaces (at a revision, in full or as a
/// preview), or the loaded mesh's level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shown {
    Document { revision: u64, full: bool },
    Mesh { generation: u64, level: usize },
}

/// The document's surfaces swept in the background, with their vertex data for the 3D view.
type SweepResult = (SweptSurfaces, view3d::PreparedMesh);

/// The most triangles the 3D view colours by curvature or UVs (the colours are made on the
/// UI thread: about a second at this size).
pub const COLOUR_MAX_TRIANGLES: usize = 2_000_000;

/// Mesh files larger than this (bytes) are read on a worker thread.
pub const BACKGROUND_BYTES: u64 = 4_000_000;

/// Subdivision levels of more faces than this are made on a worker thread.
pub const BACKGROUND_FACES: usize = 200_000;

/// What Export mesh writes: a mesh, or a document whose surfaces it sweeps first.
enum ExportSource {
    Mesh(TriMesh),
    Sweep(SwpDocument),
}

/// A mesh file read on a worker thread, with its Loop level 0 and 3D view data.
struct Loaded {
    mesh: PolyMesh,
    creases: Creases,
    kind: DocKind,
    pyramid: Result<LoopPyramid, String>,
    prepared: view3d::PreparedMesh,
}

/// A subdivision level made on a worker thread, with its 3D view data.
enum Refined {
    /// The Loop pyramid, one level finer.
    Pyramid(LoopPyramid, view3d::PreparedMesh),
    /// The next level of another scheme.
    Level(PolyMesh, view3d::PreparedMesh),
    /// Every level made again with new colours.
    Recolored {
        pyramid: Result<LoopPyramid, String>,
        levels: Vec<PolyMesh>,
        level: usize,
        prepared: view3d::PreparedMesh,
    },
}

/// Which level of which mesh with which scheme is shown: the mesh (its address), the scheme
/// and the level.
type MeshKey = (usize, Scheme, usize);

fn mesh_key(m: &MeshState) -> MeshKey {
    (Arc::as_ptr(&m.source) as usize, m.scheme, m.level)
}

/// The axis `Revolve` turns the active curve about.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RevolveAxis {
    /// +y, as SWP `srev` (steps of the profile, slices).
    #[default]
    Y,
    /// +z, as the revolution tool and SWP `zrev` (angle tolerance, slice tolerance, scale).
    Z,
}

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
    legend: Option<Legend>,
    /// The loaded mesh refined by two to four schemes side by side (`compare SCHEME`).
    pub compare: compare::Comparison,
    /// The colouring the 3D view's data was made with.
    shown_colouring: Option<(SurfaceColour, bool)>,
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
    dialog_then: Option<Pending>,
    /// The action waiting for an answer to "unsaved changes: Save / Discard / Cancel".
    pub prompt: Option<Pending>,
    /// The recent files (the Open dialog lists them).
    pub recent: RecentFiles,
    /// Whether the window may close (the user answered, or nothing was unsaved).
    close_allowed: bool,
    /// Whether the window was told to close.
    close_sent: bool,
    /// The title last given to the window.
    title_sent: String,
    /// The document's surfaces, swept at `surfaces_for`'s revision (in full, or a preview).
    surfaces: SweptSurfaces,
    surfaces_for: Option<(u64, bool)>,
    /// Their vertex data when they were swept in the background, for the 3D view.
    prepared: Option<view3d::PreparedMesh>,
    /// The sweep running in the background, and the revision it sweeps.
    sweep_task: Option<(u64, work::Task<SweepResult>)>,
    /// The revision whose sweep the user cancelled (not started again until an edit).
    sweep_cancelled: Option<u64>,
    /// The value widget being dragged or typed into (its edits make one undo step).
    value_edit: Option<egui::Id>,
    /// The window's context (once it has drawn), woken by workers when they finish.
    egui_ctx: Option<egui::Context>,
    /// A mesh being exported on a worker thread (its file, and how many triangles it wrote).
    export_task: Option<(PathBuf, work::Task<Result<usize, String>>)>,
    /// A mesh file being read on a worker thread.
    load_task: Option<(PathBuf, work::Task<Result<Loaded, String>>)>,
    /// A subdivision level being made on a worker thread, for the mesh level it refines.
    refine_task: Option<(MeshKey, work::Task<Result<Refined, String>>)>,
    /// The 3D view data of a mesh level made on a worker thread.
    prepared_mesh: Option<(MeshKey, view3d::PreparedMesh)>,
    /// Bumped whenever the mesh or its levels change.
    mesh_generation: u64,
    shown: Option<Shown>,
    /// The [`Document::file_id`] of the document the views were last fitted to.
    fitted_file: Option<u64>,
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

    /// Whether the window may close now (no unsaved changes, or the user answered).
    #[must_use]
    pub fn close_allowed(&self) -> bool {
        self.close_allowed
    }

    /// Does `action`, first asking `Save` / `Discard` / `Cancel` if the document has unsaved
    /// changes.
    pub fn request(&mut self, action: Pending) {
        if self.doc.is_modified() {
            self.prompt = Some(action);
        } else {
            self.perform(action);
        }
    }

    /// Does `action` without asking.
    fn perform(&mut self, action: Pending) {
        match action {
            Pending::Close => self.close_allowed = true,
            Pending::Open(path) => {
                self.open_file(&path);
            }
            Pending::OpenDialog => self.open_dialog(Purpose::Open),
            Pending::Preset => self.preset_now(),
            Pending::New => {
                self.doc.replace_with(Document::new());
                self.status = "New document".to_owned();
            }
            Pending::CloseMesh => {
                self.doc.replace_with(Document::new());
                self.status = "Closed the mesh: a new document".to_owned();
            }
        }
    }

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
    fn poll_load(&mut self) {
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
    fn cancel_load(&mut self) {
        cancel(&mut self.load_task);
    }

    /// Whether a file is being opened on a worker thread.
    #[must_use]
    pub fn is_loading(&self) -> bool {
        self.load_task.is_some()
    }

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

    /// Shows the file dialog for `purpose` (in the document's folder).
    pub fn open_dialog(&mut self, purpose: Purpose) {
        let dir = self
            .doc
            .path()
            .and_then(Path::parent)
            .filter(|d| !d.as_os_str().is_empty())
            .map(Path::to_path_buf)
            .or_else(|| std::env::current_dir().ok())
            .unwrap_or_else(|| PathBuf::from("."));
        let stem = self.doc.path().and_then(Path::file_stem).map(|s| s.to_string_lossy().into_owned());
        let name = match purpose {
            Purpose::Open => String::new(),
            Purpose::SaveAs => format!("{}.swp", stem.as_deref().unwrap_or("untitled")),
            Purpose::Export => format!("{}.obj", stem.as_deref().unwrap_or("surface")),
        };
        let mut dialog = FileDialog::new(purpose, dir, name);
        if purpose == Purpose::Export {
            dialog.forbidden = self.doc.path().map(Path::to_path_buf);
        }
        if purpose == Purpose::SaveAs {
            dialog.obj_refused =
                self.annotated_refusal().map(|why| format!("Save as writes SWP files (.swp) here: {why}"));
        }
        if purpose == Purpose::Open {
            dialog.recent = self.recent.list.clone();
        }
        self.dialog = Some(dialog);
    }

    /// Makes [`mesh`](Self::mesh) the document's mesh with its levels (Loop, level 0), if
    /// the document's mesh changed (a file opened, undo of an open, …), and fits the views
    /// to a document that is another file.
    fn sync_mesh(&mut self) {
        self.sync_mesh_with(None);
    }

    /// [`sync_mesh`](Self::sync_mesh), with the Loop level 0 of a new mesh if it was made
    /// already.
    fn sync_mesh_with(&mut self, pyramid: Option<Result<LoopPyramid, String>>) {
        let source = self.doc.mesh().cloned();
        let key = source.as_ref().map_or(0, |m| Arc::as_ptr(m) as usize);
        let current = self.mesh.as_ref().map_or(0, |m| Arc::as_ptr(&m.source) as usize);
        if key != current {
            self.cancel_refine();
            let options = self.loop_options();
            self.mesh = source.map(|source| MeshState {
                name: self.doc.path().map_or_else(String::new, |p| p.display().to_string()),
                pyramid: pyramid.unwrap_or_else(|| LoopPyramid::new(&source.base, options).map_err(|e| e.to_string())),
                levels: Vec::new(),
                scheme: Scheme::Loop,
                level: 0,
                source,
            });
            self.mesh_generation += 1;
        }
        let file = self.doc.file_id();
        if self.fitted_file != Some(file) {
            self.fitted_file = Some(file);
            self.view.fit_pending = true;
            self.view.selected = None;
            self.view3d.fit_on_next_mesh();
        }
    }

    fn loop_options(&self) -> LoopOptions {
        LoopOptions { color_by_level: self.color_by_level, ..LoopOptions::default() }
    }

    /// Refines the loaded mesh one level with its scheme (kept levels are reused when
    /// coarsening). An error (e.g. a non-manifold mesh for Catmull-Clark) goes to the status
    /// line.
    pub fn refine(&mut self) {
        if self.refine_task.is_some() {
            return;
        }
        let color_by_level = self.color_by_level;
        let Some(m) = &mut self.mesh else { return };
        let key = mesh_key(m);
        match m.scheme {
            Scheme::Loop if m.uses_pyramid() => {
                let Ok(p) = &mut m.pyramid else { return };
                if m.level + 1 > p.finest().depth() {
                    if 4 * p.finest().num_triangles() > BACKGROUND_FACES {
                        let mut p = p.clone();
                        let label = format!("Refining to {} triangles", 4 * p.finest().num_triangles());
                        let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |_| {
                            p.refine().map_err(|e| e.to_string())?;
                            let prepared = view3d::PreparedMesh::new(&p.finest().clone().into_tri_mesh());
                            Ok(Refined::Pyramid(p, prepared))
                        });
                        self.refine_task = Some((key, task));
                        return;
                    }
                    if let Err(e) = p.refine() {
                        self.status = format!("Error: {}: {e}", m.name);
                        return;
                    }
                }
                m.level = (m.level + 1).min(p.finest().depth());
            }
            scheme => {
                if m.level >= m.levels.len() {
                    let depth = m.levels.len() + 1;
                    let coarse = m.levels.last().unwrap_or(&m.source.base);
                    if 4 * coarse.num_faces() > BACKGROUND_FACES {
                        let (source, coarse) = (Arc::clone(&m.source), m.levels.last().cloned());
                        let label = format!("Refining to level {depth} ({})", scheme.name());
                        let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |_| {
                            let coarse = coarse.as_ref().unwrap_or(&source.base);
                            let fine =
                                scheme.polygon_level(&source.base, coarse, &source.creases, depth, color_by_level)?;
                            let prepared = view3d::PreparedMesh::new(&fine.to_tri_mesh());
                            Ok(Refined::Level(fine, prepared))
                        });
                        self.refine_task = Some((key, task));
                        return;
                    }
                    match scheme.polygon_level(&m.source.base, coarse, &m.source.creases, depth, color_by_level) {
                        Ok(fine) => m.levels.push(fine),
                        Err(e) => {
                            self.status = format!("Error: {}: {e}", m.name);
                            return;
                        }
                    }
                }
                m.level += 1;
            }
        }
        self.status = format!("Level {}: {} faces", m.level, m.faces());
    }

    /// Takes a level refined on a worker thread, if it is done and still wanted (the same
    /// mesh, scheme and level as when it started).
    fn poll_refine(&mut self) {
        let Some((key, task)) = &mut self.refine_task else { return };
        let Some(result) = task.poll() else { return };
        let key = *key;
        self.refine_task = None;
        let Some(m) = &mut self.mesh else { return };
        if mesh_key(m) != key {
            return;
        }
        match result.and_then(|r| r) {
            Ok(Refined::Pyramid(p, prepared)) => {
                m.level = p.finest().depth();
                m.pyramid = Ok(p);
                self.prepared_mesh = Some((mesh_key(m), prepared));
            }
            Ok(Refined::Level(fine, prepared)) => {
                m.levels.push(fine);
                m.level = m.levels.len();
                self.prepared_mesh = Some((mesh_key(m), prepared));
            }
            Ok(Refined::Recolored { pyramid, levels, level, prepared }) => {
                m.pyramid = pyramid;
                m.levels = levels;
                m.level = level;
                self.mesh_generation += 1;
                self.prepared_mesh = Some((mesh_key(m), prepared));
                return;
            }
            Err(e) => {
                self.status = format!("Error: {}: {e}", m.name);
                return;
            }
        }
        self.status = format!("Level {}: {} faces", m.level, m.faces());
    }

    /// Stops waiting for a level being refined.
    fn cancel_refine(&mut self) {
        cancel(&mut self.refine_task);
    }

    /// Whether a subdivision level is being made on a worker thread.
    #[must_use]
    pub fn is_refining(&self) -> bool {
        self.refine_task.is_some()
    }

    /// Subdivides the loaded mesh with `scheme` from now on (showing the loaded mesh again).
    pub fn set_scheme(&mut self, scheme: Scheme) {
        self.cancel_refine();
        let Some(m) = &mut self.mesh else { return };
        if m.scheme != scheme {
            m.scheme = scheme;
            m.level = 0;
            m.levels.clear();
            self.mesh_generation += 1;
            self.status = format!("{} subdivision", scheme.name());
            if !m.source.creases.is_empty() && !scheme.has_creases() {
                self.status.push_str(" (it has no creases: the mesh's crease tags are left out)");
            }
        }
    }

    /// Rebuilds the loaded mesh's levels with the current colour setting, keeping the level shown.
    fn recolor(&mut self) {
        self.cancel_refine();
        let options = self.loop_options();
        let Some(m) = &mut self.mesh else { return };
        let (source, scheme, pyramid, level, count) =
            (Arc::clone(&m.source), m.scheme, m.uses_pyramid(), m.level, m.levels.len());
        let finest = match (&m.pyramid, pyramid) {
            (Ok(p), true) => p.finest().num_triangles(),
            _ => m.levels.last().map_or(0, PolyMesh::num_faces),
        };
        if finest > BACKGROUND_FACES {
            let key = mesh_key(m);
            let label = format!("Colouring {finest} faces");
            let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |_| {
                let (pyramid, levels, level) = recolored(&source, scheme, pyramid, level, count, options);
                let shown = match (&pyramid, level) {
                    (_, 0) => source.base.to_tri_mesh(),
                    (Ok(p), l) if levels.is_empty() => p.level(l).clone().into_tri_mesh(),
                    (_, l) => levels[l - 1].to_tri_mesh(),
                };
                let prepared = view3d::PreparedMesh::new(&shown);
                Ok(Refined::Recolored { pyramid, levels, level, prepared })
            });
            self.refine_task = Some((key, task));
            return;
        }
        let (p, levels, level) = recolored(&source, scheme, pyramid, level, count, options);
        m.pyramid = p;
        m.levels = levels;
        m.level = level;
        self.mesh_generation += 1;
    }

    /// Shows the next coarser level of the loaded mesh.
    pub fn coarsen(&mut self) {
        self.cancel_refine();
        if let Some(m) = &mut self.mesh
            && m.level > 0
        {
            m.level -= 1;
            self.status = format!("Level {}: {} faces", m.level, m.faces());
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
    fn annotated_refusal(&self) -> Option<String> {
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
                self.status = format!("Error: cannot write {}: {e}", path.display());
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
    fn poll_export(&mut self) {
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

    /// The mesh of the 3D view: the loaded mesh's level, or the document's surfaces merged
    /// (in full, also while a preview or the background sweep is shown).
    ///
    /// # Errors
    ///
    /// Why there is none (no surface in the document, or a surface that cannot be built).
    pub fn shown_mesh(&mut self) -> Result<TriMesh, String> {
        if let Some(m) = &self.mesh {
            return Ok(m.shown());
        }
        if self.doc.swp.surfaces.is_empty() {
            return Err("the document has no surface (add srev or gcyl to the SWP file)".to_owned());
        }
        // the sweep the surface panel and the 3D view already show, if it is the whole one
        let full;
        let swept = if self.surfaces_for == Some((self.doc.revision(), true)) {
            &self.surfaces
        } else {
            full = SweptSurfaces::sweep(&self.doc.swp);
            &full
        };
        match swept.errors.first() {
            Some(e) => Err(e.clone()),
            None => Ok(swept.mesh.clone()),
        }
    }

    /// Gives the 3D view the loaded mesh's level, or the document's surfaces, if they changed
    /// since it was last given them.
    fn update_view3d(&mut self, ctx: Option<&egui::Context>) {
        if self.mesh.is_none() {
            self.update_surfaces(ctx);
        }
        let shown = match (&self.mesh, self.surfaces_for) {
            (Some(m), _) => Shown::Mesh { generation: self.mesh_generation, level: m.level },
            (None, Some((revision, full))) => Shown::Document { revision, full },
            (None, None) => return,
        };
        let colouring = (self.colouring, self.color_by_level);
        if self.shown == Some(shown) && self.shown_colouring == Some(colouring) {
            return;
        }
        self.shown = Some(shown);
        self.shown_colouring = Some(colouring);
        self.view3d.settings.checker = false;
        self.legend = match &self.mesh {
            Some(m) if self.color_by_level && self.colouring == SurfaceColour::Shade => {
                Some(Legend::Levels { levels: u32::try_from(m.level).unwrap_or(u32::MAX) })
            }
            _ => None,
        };
        if self.colouring != SurfaceColour::Shade {
            match self.coloured_mesh() {
                Ok((mesh, legend)) => {
                    self.prepared = None;
                    self.prepared_mesh = None;
                    self.view3d.settings.checker = self.colouring == SurfaceColour::UvChecker;
                    self.view3d.set_mesh(&mesh);
                    self.legend = legend;
                    return;
                }
                Err(why) => self.status = format!("Error: {why}; shown shaded"),
            }
        }
        match &self.mesh {
            Some(m) => match self.prepared_mesh.take() {
                Some((key, prepared)) if key == mesh_key(m) => self.view3d.set_prepared(prepared),
                _ => self.view3d.set_mesh(&m.shown()),
            },
            None => match self.prepared.take() {
                Some(prepared) => self.view3d.set_prepared(prepared),
                None => self.view3d.set_mesh(&self.surfaces.mesh),
            },
        }
    }

    /// The mesh shown (the mesh's level, or the document's surfaces) coloured by
    /// [`colouring`](Self::colouring), and its legend: vertex colours from the curvature with
    /// the render crate's map and scale, or the UVs (in the red and green of the vertex
    /// colours) for the checker. The surfaces are swept again with UVs for the checker.
    ///
    /// # Errors
    /// A mesh of more than [`COLOUR_MAX_TRIANGLES`] triangles, or no UVs for the checker.
    fn coloured_mesh(&self) -> Result<(TriMesh, Option<Legend>), String> {
        let triangles = match &self.mesh {
            Some(m) => m.faces(),
            None => self.surfaces.mesh.num_triangles(),
        };
        if triangles > COLOUR_MAX_TRIANGLES {
            return Err(format!(
                "colouring by {} takes at most {COLOUR_MAX_TRIANGLES} triangles; this has {triangles}",
                self.colouring.name()
            ));
        }
        let mut mesh = match (&self.mesh, self.colouring) {
            (Some(m), _) => m.shown(),
            (None, SurfaceColour::UvChecker) => {
                let mut options = editor_sweep_options();
                options.sweep.uvs = true;
                SweptSurfaces::sweep_with(&self.doc.swp, &options).mesh
            }
            (None, _) => self.surfaces.mesh.clone(),
        };
        if mesh.triangles.is_empty() {
            return Ok((mesh, None));
        }
        match self.colouring {
            SurfaceColour::UvChecker => {
                if mesh.uvs.len() != mesh.positions.len() {
                    return Err("the UV checker needs texture coordinates, and this mesh has none".to_owned());
                }
                mesh.colors = mesh
                    .uvs
                    .iter()
                    .map(|uv| glam::DVec3::new(uv.x.rem_euclid(1.0), uv.y.rem_euclid(1.0), 0.0))
                    .collect();
                Ok((mesh, None))
            }
            SurfaceColour::Curvature(_) => {
                let radius = splinekit_render::camera::bounding_radius(mesh.positions.iter().copied());
                let (mut colours, legend) = splinekit_render::surface_colours(&[&mesh], self.colouring, radius);
                if let Some(Some(c)) = colours.pop() {
                    mesh.colors = c;
                }
                Ok((mesh, legend))
            }
            SurfaceColour::Shade | SurfaceColour::Level { .. } => Ok((mesh, None)),
        }
    }

    /// The triangle count of the document's surfaces (0 if there are none or they fail). When
    /// the window shows a preview or is still sweeping them on a worker thread, they are swept
    /// in full here first, so the count is always the whole surfaces'.
    #[must_use]
    pub fn surface_triangles(&mut self) -> usize {
        self.update_surfaces(None);
        let revision = self.doc.revision();
        if self.surfaces_for != Some((revision, true)) {
            self.cancel_sweep();
            self.surfaces = SweptSurfaces::sweep_with(&self.doc.swp, &editor_sweep_options());
            self.prepared = None;
            self.surfaces_for = Some((revision, true));
        }
        self.surfaces.mesh.num_triangles()
    }

    /// The document's surfaces, swept in full (as [`surface_triangles`](Self::surface_triangles)
    /// does): the merged mesh, and a line per surface.
    pub fn surfaces(&mut self) -> &SweptSurfaces {
        let _ = self.surface_triangles();
        &self.surfaces
    }

    /// Whether the surfaces are being swept in the background.
    #[must_use]
    pub fn is_sweeping(&self) -> bool {
        self.sweep_task.is_some()
    }

    /// Brings the document's surfaces up to date: at once when they have at most
    /// [`LIVE_TRIANGLES`]; else at reduced resolution while a point is dragged, and in full
    /// on a worker thread otherwise (the last surfaces stay shown until it is done). `ctx` is
    /// asked to redraw when the worker finishes.
    fn update_surfaces(&mut self, ctx: Option<&egui::Context>) {
        let revision = self.doc.revision();
        if let Some((r, task)) = &mut self.sweep_task
            && let Some(result) = task.poll()
        {
            let r = *r;
            self.sweep_task = None;
            match result {
                Ok((swept, prepared)) if r == revision => {
                    self.surfaces = swept;
                    self.prepared = Some(prepared);
                    self.surfaces_for = Some((r, true));
                }
                Ok(_) => {}
                Err(e) => self.status = format!("Error: {e}"),
            }
        }
        let dragging = self.view.is_dragging() || self.view3d.is_dragging();
        match self.surfaces_for {
            Some((r, true)) if r == revision => return,
            Some((r, false)) if r == revision && dragging => return,
            _ => {}
        }
        if self.sweep_task.as_ref().is_some_and(|(r, _)| *r == revision) || self.sweep_cancelled == Some(revision) {
            return;
        }
        match SweptSurfaces::sweep_within(&self.doc.swp, LIVE_TRIANGLES) {
            Ok(swept) => {
                self.cancel_sweep();
                self.surfaces = swept;
                self.prepared = None;
                self.surfaces_for = Some((revision, true));
            }
            Err(estimate) if dragging => {
                self.cancel_sweep();
                self.surfaces = SweptSurfaces::preview(&self.doc.swp, PREVIEW_TRIANGLES, estimate);
                self.prepared = None;
                self.surfaces_for = Some((revision, false));
            }
            Err(estimate) => {
                self.cancel_sweep();
                let swp = self.doc.swp.clone();
                let label = format!("Sweeping {:.1} M triangles", estimate as f64 / 1e6);
                let task = work::Task::spawn(label, 0, ctx.cloned(), move |_| {
                    let swept = SweptSurfaces::sweep_with(&swp, &editor_sweep_options());
                    let prepared = view3d::PreparedMesh::new(&swept.mesh);
                    (swept, prepared)
                });
                self.sweep_task = Some((revision, task));
            }
        }
    }

    /// Stops waiting for the background sweep (its result is dropped).
    fn cancel_sweep(&mut self) {
        cancel(&mut self.sweep_task);
    }

    /// Applies every key press of the frame, in order (several presses of one key in one
    /// slow frame act several times). Letter keys act when no text field has focus; nothing
    /// acts while a dialog or question is open (they read their own keys).
    fn keyboard(&mut self, ctx: &egui::Context) {
        if self.modal_open() {
            return;
        }
        let typing = ctx.egui_wants_keyboard_input();
        let events = ctx.input(|i| i.events.clone());
        for event in events {
            match event {
                egui::Event::Key { key, pressed: true, repeat, modifiers, .. } => {
                    self.key(key, modifiers, repeat, typing);
                }
                egui::Event::Text(t) if !typing && t == "?" => self.show_help ^= true,
                _ => {}
            }
            if self.modal_open() {
                // the rest of the frame's keys belong to the dialog
                break;
            }
        }
    }

    /// One key press.
    fn key(&mut self, key: Key, modifiers: Modifiers, repeat: bool, typing: bool) {
        // Ctrl on Linux and Windows (egui sets `command` for it; some input sources set only `ctrl`)
        let command = (modifiers.command || modifiers.ctrl) && !modifiers.alt;
        if command {
            match (key, modifiers.shift) {
                (Key::S, true) => self.open_dialog(Purpose::SaveAs),
                (Key::S, false) => {
                    self.save();
                }
                (Key::O, false) => self.request(Pending::OpenDialog),
                (Key::N, false) => self.request(Pending::New),
                // a text field has its own undo
                (Key::Z, true) | (Key::Y, false) if !typing => self.redo(),
                (Key::Z, false) if !typing => self.undo(),
                _ => {}
            }
            return;
        }
        if typing || modifiers.any() {
            return;
        }
        if matches!(key, Key::Delete | Key::Backspace) {
            if let Some(i) = self.view.selected.take() {
                self.doc.delete_point(i);
            }
            return;
        }
        if repeat {
            return;
        }
        match key {
            Key::R => self.request(Pending::Preset),
            Key::S => {
                self.doc.cycle_kind();
                self.status_kind();
            }
            Key::C => {
                self.doc.clear();
                self.view.selected = None;
            }
            Key::A => self.view.show.markers ^= true,
            Key::L => self.view.show.polygon ^= true,
            Key::W => self.view3d.settings.wireframe ^= true,
            Key::N => {
                let on = !self.view3d.settings.normals;
                self.view3d.settings.normals = on;
                self.view.show.normals = on;
            }
            Key::F => {
                self.view.fit_pending = true;
                self.view3d.fit();
            }
            Key::H => self.show_help ^= true,
            _ => {}
        }
    }

    /// Says the active curve's kind on the status line (after the kind changed).
    fn status_kind(&mut self) {
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
    fn preset_now(&mut self) {
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

    fn file_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            if self.modal_open() {
                // the dialog's own buttons (Save, Cancel, …) are the only ones with their labels
                ui.label(self.title());
                return;
            }
            if ui.button("New").on_hover_text("Ctrl+N").clicked() {
                self.request(Pending::New);
            }
            if ui.button("Open…").on_hover_text("Ctrl+O").clicked() {
                self.request(Pending::OpenDialog);
            }
            if ui.button("Save").on_hover_text("Ctrl+S").clicked() {
                self.save();
            }
            if ui.button("Save as…").on_hover_text("Ctrl+Shift+S").clicked() {
                self.open_dialog(Purpose::SaveAs);
            }
            if ui.button("Export mesh…").clicked() {
                self.open_dialog(Purpose::Export);
            }
            ui.separator();
            if ui.add_enabled(self.doc.can_undo(), egui::Button::new("Undo")).clicked() {
                self.undo();
            }
            if ui.add_enabled(self.doc.can_redo(), egui::Button::new("Redo")).clicked() {
                self.redo();
            }
            if ui.button("Preset").clicked() {
                self.request(Pending::Preset);
            }
            ui.menu_button("View", |ui| {
                let before = self.layout;
                ui.checkbox(&mut self.layout.curves_panel, "Show curve panel");
                ui.checkbox(&mut self.layout.view2d, "Show 2D view");
                ui.checkbox(&mut self.layout.view3d, "Show 3D view");
                if !self.layout.view2d && !self.layout.view3d {
                    // one view stays: the one not just switched off
                    if before.view2d {
                        self.layout.view3d = true;
                    } else {
                        self.layout.view2d = true;
                    }
                }
            });
            if ui.button("Help").clicked() {
                self.show_help ^= true;
            }
        });
    }

    fn left_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Curves");
        let names: Vec<String> = self
            .doc
            .swp
            .curves
            .iter()
            .enumerate()
            .map(|(i, c)| format!("{} ({}, {} points)", c.display_name(i), doc::kind_name(c.kind), point_count(c)))
            .collect();
        for (i, name) in names.iter().enumerate() {
            if ui.selectable_label(i == self.doc.active, name).clicked() {
                self.doc.select_curve(i);
                self.view.selected = None;
                self.view.fit_pending = true;
            }
        }
        if ui.button("Add curve").clicked() {
            self.doc.add_curve();
        }
        ui.separator();
        if let Some(curve) = self.doc.curve() {
            let (kind, closed) = (curve.kind, curve.closed);
            egui::ComboBox::from_label("Kind").selected_text(doc::kind_name(kind)).show_ui(ui, |ui| {
                for (k, name) in doc::KINDS {
                    if ui.selectable_label(k == kind, name).clicked() {
                        self.doc.set_kind(k);
                        self.status_kind();
                    }
                }
            });
            let mut c = closed;
            if ui.checkbox(&mut c, "Closed").changed() {
                self.doc.set_closed(c);
            }
            if !self.doc.is_2d() {
                ui.horizontal(|ui| {
                    ui.label("Plane");
                    for plane in [Plane::Xy, Plane::Yz, Plane::Zx] {
                        if ui.selectable_label(self.view.plane == plane, plane.name()).clicked() {
                            self.view.plane = plane;
                            self.view.fit_pending = true;
                        }
                    }
                });
            }
            if ui.button("Clear curve").clicked() {
                self.doc.clear();
            }
            self.selected_point(ui);
        }
        ui.separator();
        ui.heading("Show");
        let show = &mut self.view.show;
        ui.checkbox(&mut show.polygon, "Control polygon");
        ui.checkbox(&mut show.markers, "Arc-length markers");
        ui.add(egui::Slider::new(&mut show.marker_spacing, 0.001..=10.0).logarithmic(true).text("spacing"));
        ui.checkbox(&mut show.curves, "Draw curves").on_hover_text("every curve, in 2D and 3D");
        ui.checkbox(&mut show.normals, "Draw normals").on_hover_text("T, N, B in blue, red, green, in 2D and 3D");
        ui.horizontal(|ui| show.normal_side_ui(ui));
        ui.checkbox(&mut show.frames, "Frames (T, N, B)");
        ui.checkbox(&mut show.comb, "Curvature comb");
        ui.add(egui::Slider::new(&mut show.comb_scale, 0.001..=10.0).logarithmic(true).text("comb scale"));
        ui.checkbox(&mut self.show_table, "Arc-length table");
        if ui.button("Fit view").clicked() {
            self.view.fit_pending = true;
        }
    }

    fn right_panel(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        ui.heading("Surface");
        if let Some(m) = &self.mesh {
            ui.label(format!("Mesh {}", m.name));
            ui.label(format!("Level {}: {} vertices", m.level, m.vertices()));
            ui.label(format!("Faces: {}", m.faces()));
            let (can_refine, scheme) = (m.can_refine(), m.scheme);
            egui::ComboBox::from_label("Scheme").selected_text(scheme.name()).show_ui(ui, |ui| {
                for s in Scheme::ALL {
                    if ui.selectable_label(s == scheme, s.name()).clicked() {
                        self.set_scheme(s);
                    }
                }
            });
            let refining = self.refine_task.is_some();
            ui.horizontal(|ui| {
                if ui.add_enabled(can_refine && !refining, egui::Button::new("Refine subdivision")).clicked() {
                    self.refine();
                }
                let coarser = self.mesh.as_ref().is_some_and(|m| m.level > 0);
                if ui
                    .add_enabled(coarser, egui::Button::new("Coarsen subdivision"))
                    .on_disabled_hover_text("level 0 is the mesh as loaded")
                    .clicked()
                {
                    self.coarsen();
                }
            });
            egui::CollapsingHeader::new("Compare schemes").default_open(false).show(ui, |ui| {
                ui.label("two to four schemes side by side, one camera");
                ui.horizontal_wrapped(|ui| {
                    let chosen = self.compare.schemes();
                    for s in Scheme::ALL {
                        let mut on = chosen.contains(&s);
                        let room = on || chosen.len() < compare::MAX_COMPARED;
                        if ui.add_enabled(room, egui::Checkbox::new(&mut on, format!("compare {}", s.name()))).changed()
                        {
                            self.compare.set(s, on);
                        }
                    }
                });
            });
            if let Some((_, task)) = &self.refine_task
                && task.ui(ui)
            {
                let what = task.label.clone();
                self.cancel_refine();
                self.status = format!("Cancelled: {what}");
            }
            if ui.checkbox(&mut self.color_by_level, "Colour by level").changed() {
                self.recolor();
            }
            if ui.button("Close mesh").clicked() {
                self.request(Pending::CloseMesh);
            }
        } else {
            self.update_surfaces(Some(ui.ctx()));
            if let Some((_, task)) = &self.sweep_task
                && task.ui(ui)
            {
                self.cancel_sweep();
                self.sweep_cancelled = Some(self.doc.revision());
                self.status =
                    "Cancelled the sweep: the surface shown is not the curves' (edit to sweep again)".to_owned();
            }
            self.surface_controls(ui);
            if self.surfaces.lines.is_empty() {
                ui.label("No surface in the document");
            }
            for line in &self.surfaces.lines {
                ui.label(line);
            }
            ui.label(format!("Triangles: {}", self.surfaces.mesh.num_triangles()));
        }
        egui::CollapsingHeader::new("3D display").default_open(true).show(ui, |ui| {
            ui.horizontal_wrapped(|ui| self.view3d.settings.ui(ui));
            let choices = [
                (SurfaceColour::Shade, "shaded"),
                (SurfaceColour::Curvature(Curvature::Mean), "mean curvature"),
                (SurfaceColour::Curvature(Curvature::Gaussian), "Gaussian curvature"),
                (SurfaceColour::UvChecker, "UV checker"),
            ];
            let current = choices.iter().find(|(c, _)| *c == self.colouring).map_or("shaded", |(_, n)| n);
            egui::ComboBox::from_label("Colour").selected_text(current).show_ui(ui, |ui| {
                for (c, name) in choices {
                    ui.selectable_value(&mut self.colouring, c, name);
                }
            });
        });
        ui.separator();
        self.update_view3d(Some(ui.ctx()));
        // the control points of a 3D curve, dragged in the 3D view; every curve drawn over it
        let handles = if self.mesh.is_none() && !self.doc.is_2d() { self.doc.points().to_vec() } else { Vec::new() };
        let mut overlay = if self.mesh.is_none() { self.scene_overlay() } else { view3d::Overlay::default() };
        overlay.selected = self.view.selected;
        if let Some(m) = &self.mesh
            && self.compare.is_active()
        {
            let (source, level) = (Arc::clone(&m.source), m.level);
            self.compare.update(&source, self.mesh_generation, level, self.color_by_level, self.view3d.settings);
            self.compare.ui(ui, frame, level);
            return;
        }
        let (response, drag) = self.view3d.ui_with_overlay(ui, frame, &handles, &overlay);
        if let Some(legend) = &self.legend {
            paint_legend(ui, response.rect, legend);
        }
        if let Some(i) = self.view3d.take_clicked_handle() {
            self.view.selected = Some(i);
        }
        if let Some(d) = drag {
            if d.started {
                self.doc.begin_move();
            }
            self.doc.set_point(d.index, d.position);
            self.view.selected = Some(d.index);
        }
    }

    /// `Revolve` (a surface of revolution of the active 2D curve about +y, SWP `srev`, or
    /// about +z with the revolution tool's settings, SWP `zrev`), `Sweep` (the active 2D curve
    /// swept along another curve, SWP `gcyl`) and `Lathe` (separate radius and height curves,
    /// SWP `lathe`), then the controls of every surface. Every change is one undo step (a drag
    /// of a value: one step for the whole drag).
    fn surface_controls(&mut self, ui: &mut egui::Ui) {
        let profile_ok = self.doc.curve().is_some_and(|c| c.dim != 3) && self.doc.spline().is_ok();
        let active = self.doc.active;
        // the sweep curve: the first other curve, 3D ones first
        let path = {
            let others =
                || self.doc.swp.curves.iter().enumerate().filter(|&(i, c)| i != active && c.to_curve().is_ok());
            others().find(|(_, c)| c.dim == 3).or_else(|| others().next()).map(|(i, _)| i)
        };
        ui.horizontal_wrapped(|ui| {
            let r = ui
                .add_enabled(profile_ok, egui::Button::new("Revolve"))
                .on_hover_text("a surface of revolution of the active curve about the chosen axis")
                .on_disabled_hover_text("needs a valid 2D curve");
            if r.clicked() {
                let (i, how) = match self.revolve_axis {
                    RevolveAxis::Y => {
                        (self.doc.add_revolution(active, DEFAULT_SLICES), format!("about y: {DEFAULT_SLICES} slices"))
                    }
                    RevolveAxis::Z => {
                        (self.doc.add_revolution_z(active), "about z (the revolution tool's settings)".to_owned())
                    }
                };
                self.status = format!("Revolved {} {how}", self.doc.swp.surfaces[i].display_name(i));
            }
            ui.label("about");
            ui.selectable_value(&mut self.revolve_axis, RevolveAxis::Y, "+y")
                .on_hover_text("SWP srev: steps and slices");
            ui.selectable_value(&mut self.revolve_axis, RevolveAxis::Z, "+z").on_hover_text(
                "the revolution tool: angle tolerance, slice tolerance and scale; saves as its annotated OBJ",
            );
        });
        ui.horizontal_wrapped(|ui| {
            let r = ui
                .add_enabled(profile_ok && path.is_some(), egui::Button::new("Sweep"))
                .on_hover_text("the active 2D curve swept along another curve (a generalized cylinder)")
                .on_disabled_hover_text("needs a valid 2D curve as the profile and another curve to sweep along");
            if r.clicked()
                && let Some(path) = path
            {
                let i = self.doc.add_sweep(active, path);
                let along = self.doc.swp.curves[path].display_name(path);
                self.status =
                    format!("Swept the active curve along {along}: {}", self.doc.swp.surfaces[i].display_name(i));
            }
            if ui
                .button("Lathe")
                .on_hover_text("a lathe: new radius and height curves, r(v) and z(v) as the y of each graph")
                .clicked()
            {
                let i = self.doc.add_lathe();
                self.view.selected = None;
                self.view.fit_pending = true;
                self.status = format!(
                    "Lathe {}: drag the points of its radius and height curves (y is r(v) and z(v))",
                    self.doc.swp.surfaces[i].display_name(i)
                );
            }
        });
        let surfaces: Vec<(usize, String, SwpSurfaceKind)> =
            self.doc.swp.surfaces.iter().enumerate().map(|(i, s)| (i, s.display_name(i), s.kind)).collect();
        let curve_names: Vec<String> = self.doc.swp.curves.iter().enumerate().map(|(i, c)| c.display_name(i)).collect();
        for (i, name, kind) in surfaces {
            ui.separator();
            ui.label(format!("{name} ({})", kind.keyword()));
            ui.horizontal_wrapped(|ui| {
                let mut next = kind;
                let mut edited: Option<egui::Response> = None;
                match &mut next {
                    SwpSurfaceKind::Revolution { steps, profile } => {
                        edited = edited.or(int_value(ui, &format!("{name} slices"), steps, 3..=4096, "slices about the y axis"));
                        self.curve_steps_value(ui, &name, *profile);
                    }
                    SwpSurfaceKind::RevolutionZ { profile: _, epsilon, slice_tolerance, scale } => {
                        let hint = "angle tolerance ε of the profile, radians: a piece is halved while its control polygon turns by more than ε/2";
                        edited = edited.or(float_value(ui, &format!("{name} epsilon"), epsilon, 1e-4..=3.0, hint));
                        let hint = "largest angle between slices, radians";
                        let range = std::f64::consts::TAU / 100_000.0..=std::f64::consts::TAU / 3.0;
                        edited = edited.or(float_value(ui, &format!("{name} slice tolerance"), slice_tolerance, range, hint));
                        edited = edited.or(float_value(ui, &format!("{name} scale"), scale, 1e-6..=1e6, "uniform scale"));
                    }
                    SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale, twist } => {
                        edited = edited.or(curve_choice(ui, &format!("{name} profile"), &curve_names, profile));
                        edited = edited.or(curve_choice(ui, &format!("{name} sweep"), &curve_names, sweep));
                        edited = edited.or(optional_curve_choice(ui, &format!("{name} scale curve"), &curve_names, scale));
                        edited = edited.or(optional_curve_choice(ui, &format!("{name} twist curve"), &curve_names, twist));
                        self.curve_steps_value(ui, &name, *sweep);
                    }
                    SwpSurfaceKind::ToolSweep { profile, path, epsilon, path_epsilon, scale } => {
                        edited = edited.or(curve_choice(ui, &format!("{name} profile"), &curve_names, profile));
                        edited = edited.or(curve_choice(ui, &format!("{name} path"), &curve_names, path));
                        let hint = "the cross-section's angle tolerance, radians (the sweep tool's epsilon)";
                        edited = edited.or(float_value(ui, &format!("{name} epsilon"), epsilon, 1e-4..=3.0, hint));
                        let hint = "the swept-along curve's angle tolerance, radians";
                        edited = edited.or(float_value(ui, &format!("{name} path epsilon"), path_epsilon, 1e-4..=3.0, hint));
                        edited = edited.or(float_value(ui, &format!("{name} scale"), scale, 1e-6..=1e6, "the cross-section's scale"));
                    }
                    SwpSurfaceKind::Lathe { stacks, slices, radius, height } => {
                        edited = edited.or(int_value(ui, &format!("{name} stacks"), stacks, 1..=4096, "intervals along v"));
                        edited = edited.or(int_value(ui, &format!("{name} slices"), slices, 3..=4096, "slices about the z axis"));
                        edited = edited.or(curve_choice(ui, &format!("{name} radius"), &curve_names, radius));
                        edited = edited.or(curve_choice(ui, &format!("{name} height"), &curve_names, height));
                    }
                }
                if let Some(r) = edited
                    && next != kind
                {
                    self.edit_value(&r);
                    self.doc.set_surface_kind(i, next);
                }
            });
            ui.horizontal_wrapped(|ui| {
                let settings = self.doc.swp.surfaces[i].settings;
                let mut next = settings;
                if let Some(r) = settings_controls(ui, &name, kind, &mut next)
                    && next != settings
                {
                    self.edit_value(&r);
                    self.doc.set_surface_settings(i, next);
                }
            });
        }
    }

    /// The steps of curve `curve`, labelled `{name} steps`, as a value to drag or type.
    fn curve_steps_value(&mut self, ui: &mut egui::Ui, name: &str, curve: usize) {
        let steps = self.doc.swp.curves.get(curve).map_or(1, |c| c.steps);
        let mut k = steps;
        let label = ui.label(format!("{name} steps")).on_hover_text("tessellation steps of each segment of the curve");
        let r = ui.add(egui::DragValue::new(&mut k).range(1..=1000)).labelled_by(label.id);
        if r.changed() && k != steps {
            self.edit_value(&r);
            self.doc.set_curve_steps(curve, k);
        }
    }

    /// The selected point's coordinates, to type or drag (`Point x`, `Point y`, and `Point z`
    /// for a 3D curve), and a Kochanek–Bartels key's `Tension`, `Continuity` and `Bias`; each
    /// change one undo step.
    fn selected_point(&mut self, ui: &mut egui::Ui) {
        let Some(i) = self.view.selected else { return };
        let Some(&p) = self.doc.points().get(i) else { return };
        ui.label(format!("Selected P{i}"));
        let axes: &[(&str, usize)] =
            if self.doc.is_2d() { &[("x", 0), ("y", 1)] } else { &[("x", 0), ("y", 1), ("z", 2)] };
        ui.horizontal_wrapped(|ui| {
            for &(name, k) in axes {
                let label = ui.label(format!("Point {name}"));
                let mut v = p[k];
                let speed = 0.01 * (1.0 + p.length());
                let r = ui.add(egui::DragValue::new(&mut v).speed(speed).max_decimals(6)).labelled_by(label.id);
                if r.changed() && v != p[k] && v.is_finite() {
                    self.edit_value(&r);
                    let mut q = p;
                    q[k] = v;
                    self.doc.set_point(i, q);
                }
            }
        });
        // a Kochanek–Bartels key's tension, continuity and bias, each in [−1, 1]
        let Some(shape) = self.doc.shape(i) else { return };
        ui.horizontal_wrapped(|ui| {
            let values = [shape.tension, shape.continuity, shape.bias];
            for (k, name) in ["Tension", "Continuity", "Bias"].into_iter().enumerate() {
                let label = ui.label(name);
                let mut v = values[k];
                let r = ui
                    .add(egui::DragValue::new(&mut v).range(-1.0..=1.0).speed(0.01).max_decimals(4))
                    .labelled_by(label.id);
                if r.changed() && v != values[k] {
                    self.edit_value(&r);
                    let mut next = values;
                    next[k] = v;
                    self.doc.set_shape(i, Tcb::new(next[0], next[1], next[2]));
                }
            }
        });
    }

    /// Records the undo step of a value edited with `r` once per drag or typing (not once per
    /// frame of it).
    fn edit_value(&mut self, r: &egui::Response) {
        let continuing = self.value_edit == Some(r.id) && (r.dragged() || r.has_focus());
        if !continuing {
            self.doc.begin_move();
        }
        self.value_edit = (r.dragged() || r.has_focus()).then_some(r.id);
    }

    /// Every curve of the document for the 3D view (2D curves in the xy plane), coloured by
    /// segment, the active one brighter and wider, with the control points of the others
    /// (the active 3D curve's are its handles) (`Draw curves`); frames T, N, B in blue, red and
    /// green along every curve (`Draw normals`); the active curve's arc-length markers.
    fn scene_overlay(&self) -> view3d::Overlay {
        use splinekit::ParamCurve as _;
        let mut overlay = view3d::Overlay::default();
        let show = &self.view.show;
        if !show.curves && !show.normals && !show.markers {
            return overlay;
        }
        let curves: Vec<(usize, splinekit::AnyCurve<glam::DVec3>)> =
            self.doc.swp.curves.iter().enumerate().filter_map(|(i, c)| c.to_curve().ok().map(|c| (i, c))).collect();
        // frame arrows a twentieth of the scene's size
        let (_, radius) = view3d::point_bounds(|| {
            curves.iter().flat_map(|(_, c)| {
                let n = c.num_segments().max(1);
                (0..=4 * n).map(move |k| c.eval(n as f64 * k as f64 / (4 * n) as f64))
            })
        });
        let arrow = 0.1 * if radius > 0.0 { radius } else { 1.0 };
        for (i, c) in &curves {
            let active = *i == self.doc.active;
            let segments = c.num_segments().max(1);
            if show.curves {
                for seg in 0..segments {
                    let points = (0..=24).map(|k| c.eval(seg as f64 + f64::from(k) / 24.0)).collect();
                    let colour = view2d::SEGMENT_COLORS[seg % view2d::SEGMENT_COLORS.len()];
                    let (colour, width) = if active { (colour, 2.5) } else { (colour.gamma_multiply(0.55), 1.5) };
                    overlay.lines.push((points, colour, width));
                }
                let is_3d = self.doc.swp.curves[*i].dim == 3;
                if !(active && is_3d) {
                    let points = self.doc.swp.curves[*i].geometry.points();
                    let colour = if active { view3d::HANDLE_COLOUR } else { egui::Color32::from_gray(150) };
                    overlay.dots.extend(points.iter().map(|&p| (p, colour)));
                }
            }
            if show.normals {
                let n = segments * 8;
                let us: Vec<f64> = (0..=n).map(|k| segments as f64 * k as f64 / n as f64).collect();
                let frames = splinekit::frame::frames(c, &us, &show.frame_options(self.doc.swp.curves[*i].dim != 3));
                for (&u, f) in us.iter().zip(&frames) {
                    let p = c.eval(u);
                    for (v, colour) in [
                        (f.t, egui::Color32::from_rgb(60, 110, 255)),
                        (f.n, egui::Color32::from_rgb(230, 50, 50)),
                        (f.b, egui::Color32::from_rgb(40, 180, 70)),
                    ] {
                        overlay.lines.push((vec![p, p + v * arrow], colour, 1.5));
                    }
                }
            }
            if show.markers && active {
                let index = splinekit::arclen::ArclenIndex::new(c, 1e-9);
                let spacing = show.marker_spacing.max(index.length() / 5000.0).max(1e-12);
                let count = (index.length() / spacing).floor() as usize;
                for k in 0..=count {
                    let u = index.u_at(c, k as f64 * spacing);
                    overlay.dots.push((c.eval(u), egui::Color32::from_gray(20)));
                }
            }
        }
        overlay
    }

    fn windows(&mut self, ctx: &egui::Context) {
        let mut open = self.show_help;
        // at the window's right, over the 3D view: the curve panel and the 2D view stay readable
        egui::Window::new("Help")
            .open(&mut open)
            .vscroll(true)
            .anchor(egui::Align2::RIGHT_TOP, [-12.0, 40.0])
            .default_height((ctx.content_rect().height() - 90.0).max(200.0))
            .show(ctx, |ui| {
                ui.strong("Mouse");
                egui::Grid::new("mouse").striped(true).show(ui, |ui| {
                    for (what, does) in MOUSE {
                        ui.monospace(what);
                        ui.label(does);
                        ui.end_row();
                    }
                });
                ui.strong("Keys");
                egui::Grid::new("shortcuts").striped(true).show(ui, |ui| {
                    for (key, what) in SHORTCUTS {
                        ui.monospace(key);
                        ui.label(what);
                        ui.end_row();
                    }
                });
            });
        self.show_help = open;
        let mut open = self.show_table;
        egui::Window::new("Arc-length table").open(&mut open).show(ctx, |ui| match self.doc.spline() {
            Ok(c) => {
                let chord = splinekit::arclen::ArclenTable::chord(&c, 5);
                let gauss = splinekit::arclen::ArclenTable::gauss3(&c, 5);
                let exact = splinekit::arclen::arclen_relative(&c, 1e-12);
                ui.label(format!(
                    "chord {:.5}   Gauss {:.5}   true {:.5}",
                    chord.length(),
                    gauss.length(),
                    exact.length
                ));
                egui::ScrollArea::vertical().max_height(300.0).show(ui, |ui| {
                    egui::Grid::new("arclen").striped(true).show(ui, |ui| {
                        ui.strong("u");
                        ui.strong("s (chord)");
                        ui.strong("s (Gauss)");
                        ui.end_row();
                        for ((u, s), (_, g)) in chord.iter_rows().zip(gauss.iter_rows()) {
                            ui.monospace(format!("{u:.1}"));
                            ui.monospace(format!("{s:.5}"));
                            ui.monospace(format!("{g:.5}"));
                            ui.end_row();
                        }
                    });
                });
            }
            Err(e) => {
                ui.label(format!("No curve: {e}"));
            }
        });
        self.show_table = open;
    }

    /// A window close request (the window manager's close button): allowed at once without
    /// unsaved changes, else cancelled and the question asked.
    fn on_close_request(&mut self, ctx: &egui::Context) {
        if !ctx.input(|i| i.viewport().close_requested()) || self.close_allowed {
            return;
        }
        if self.doc.is_modified() {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.dialog = None;
            self.prompt = Some(Pending::Close);
        } else {
            self.close_allowed = true;
        }
    }

    /// The question "unsaved changes: Save / Discard / Cancel" before `self.prompt`.
    fn unsaved_prompt(&mut self, ctx: &egui::Context) {
        let Some(pending) = self.prompt.clone() else { return };
        let mut choice = None;
        let name = self.doc.display_name();
        egui::Modal::new(egui::Id::unique("unsaved changes")).show(ctx, |ui| {
            ui.heading("Unsaved changes");
            ui.label(format!("{name} has changes that are not saved. Save them before {}?", pending.doing()));
            ui.horizontal(|ui| {
                if ui.button("Save").clicked() {
                    choice = Some("save");
                }
                if ui.button("Discard").clicked() {
                    choice = Some("discard");
                }
                if ui.button("Cancel").clicked() {
                    choice = Some("cancel");
                }
            });
        });
        if choice.is_none() && ctx.input_mut(|i| i.consume_key(Modifiers::NONE, Key::Escape)) {
            choice = Some("cancel");
        }
        let Some(choice) = choice else { return };
        self.prompt = None;
        match choice {
            "save" => match self.doc.save_path().map(Path::to_path_buf) {
                Some(path) => {
                    if self.save_swp(&path) {
                        self.perform(pending);
                    }
                }
                None => {
                    self.open_dialog(Purpose::SaveAs);
                    self.dialog_then = Some(pending);
                }
            },
            "discard" => self.perform(pending),
            _ => self.status = "Cancelled".to_owned(),
        }
    }

    /// The file dialog, and what its choice does.
    fn file_dialog(&mut self, ctx: &egui::Context) {
        let Some(dialog) = &mut self.dialog else { return };
        let purpose = dialog.purpose;
        match dialog.show(ctx) {
            Outcome::Open => {}
            Outcome::Cancelled => {
                self.dialog = None;
                self.dialog_then = None;
            }
            Outcome::Chosen(path) => {
                self.dialog = None;
                let then = self.dialog_then.take();
                match purpose {
                    Purpose::Open => {
                        self.open_file(&path);
                    }
                    Purpose::SaveAs => {
                        if self.save_to(&path)
                            && let Some(then) = then
                        {
                            self.perform(then);
                        }
                    }
                    Purpose::Export => self.export(&path),
                }
            }
        }
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

/// The editor's sweep options: the defaults, at most [`EDITOR_MAX_TRIANGLES`] triangles.
/// A surface's own settings: its tessellation (`{name} tessellation`: the curves' steps, a
/// distance or an angle tolerance, with `{name} tolerance` or `{name} angle tolerance` in
/// degrees), `{name} layout` (srev, gcyl), `{name} frames` and `{name} caps` (gcyl). Returns
/// the response of the control that changed.
fn settings_controls(
    ui: &mut egui::Ui,
    name: &str,
    kind: SwpSurfaceKind,
    settings: &mut SwpSurfaceSettings,
) -> Option<egui::Response> {
    let mut edited = None;
    let keyword = kind.keyword();
    if keyword == "xsweep" {
        // the sweep tool's own angle rule: only the layout is a setting
        return layout_control(ui, name, settings);
    }
    let mode = match settings.tessellation {
        None => 0,
        Some(SwpTessellation::Distance(_)) => 1,
        Some(SwpTessellation::AngleDegrees(_)) => 2,
    };
    let modes = ["steps", "distance", "angle"];
    let mut chosen = mode;
    let r = egui::ComboBox::from_label(format!("{name} tessellation"))
        .selected_text(modes[mode])
        .show_ui(ui, |ui| {
            for (k, m) in modes.iter().enumerate() {
                ui.selectable_value(&mut chosen, k, *m);
            }
        })
        .response
        .on_hover_text("the curves' steps, or adaptive: within a distance, or by angle");
    if chosen != mode {
        settings.tessellation = match chosen {
            0 => None,
            1 => Some(SwpTessellation::Distance(0.01)),
            _ => Some(SwpTessellation::AngleDegrees(5.0)),
        };
        edited = Some(r);
    }
    match &mut settings.tessellation {
        Some(SwpTessellation::Distance(d)) => {
            let hint = "every polyline within this distance of its curve";
            edited = edited.or(float_value(ui, &format!("{name} tolerance"), d, 1e-6..=1e6, hint));
        }
        Some(SwpTessellation::AngleDegrees(a)) => {
            let hint = "degrees: control-polygon angle, and the largest angle between slices";
            edited = edited.or(float_value(ui, &format!("{name} angle tolerance"), a, 0.01..=180.0, hint));
        }
        None => {}
    }
    if matches!(keyword, "srev" | "gcyl") {
        edited = layout_control(ui, name, settings).or(edited);
    }
    if keyword == "gcyl" {
        let rmf = settings.frames == Some(SwpFrames::RotationMinimizing);
        let mut f = rmf;
        let r = egui::ComboBox::from_label(format!("{name} frames"))
            .selected_text(if rmf { "rotation-minimizing" } else { "sequential" })
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut f, false, "sequential");
                ui.selectable_value(&mut f, true, "rotation-minimizing");
            })
            .response;
        if f != rmf {
            settings.frames = Some(if f { SwpFrames::RotationMinimizing } else { SwpFrames::Sequential });
            edited = Some(r);
        }
        let mut caps = settings.caps.unwrap_or(true);
        let r = ui
            .checkbox(&mut caps, format!("{name} caps"))
            .on_hover_text("flat caps on an open sweep of a closed profile");
        if r.changed() {
            settings.caps = Some(caps);
            edited = Some(r);
        }
    }
    edited
}

/// Draws `legend` in the bottom left corner of the 3D view `rect`: the curvature's colour bar
/// with `−m`, `0` and `+m` (pointed ends: values beyond show the end colours), or a swatch
/// per subdivision level.
fn paint_legend(ui: &egui::Ui, rect: egui::Rect, legend: &Legend) {
    use egui::{Align2, Color32, FontId, Rect, pos2, vec2};
    let painter = ui.painter_at(rect);
    let colour = |c: [u8; 3]| Color32::from_rgb(c[0], c[1], c[2]);
    let font = FontId::proportional(12.0);
    match *legend {
        Legend::Curvature { curvature, scale, .. } => {
            let (w, h) = (180.0, 10.0);
            // room for the end labels, centred under the ends
            let bar = Rect::from_min_size(rect.left_bottom() + vec2(40.0, -34.0), vec2(w, h));
            painter.rect_filled(
                Rect::from_min_max(bar.min - vec2(32.0, 22.0), bar.max + vec2(32.0, 22.0)),
                4.0,
                Color32::from_black_alpha(170),
            );
            painter.text(
                bar.left_top() - vec2(0.0, 4.0),
                Align2::LEFT_BOTTOM,
                curvature.title(),
                font.clone(),
                Color32::WHITE,
            );
            let steps = 60;
            for i in 0..steps {
                let t = -1.0 + (2.0 * i as f64 + 1.0) / f64::from(steps);
                let x0 = bar.left() + w * i as f32 / steps as f32;
                let cell = Rect::from_min_max(pos2(x0, bar.top()), pos2(x0 + w / steps as f32 + 0.5, bar.bottom()));
                painter.rect_filled(cell, 0.0, colour(diverging_colour(t)));
            }
            for (x, text) in [
                (bar.left(), format_value(-scale)),
                (bar.center().x, "0".to_owned()),
                (bar.right(), format_value(scale)),
            ] {
                painter.text(pos2(x, bar.bottom() + 2.0), Align2::CENTER_TOP, text, font.clone(), Color32::WHITE);
            }
        }
        Legend::Levels { levels } => {
            let shown = levels.min(7);
            let height = 16.0 * (shown as f32 + 1.0);
            let top = rect.left_bottom() + vec2(14.0, -12.0 - height);
            painter.rect_filled(
                Rect::from_min_size(top - vec2(8.0, 6.0), vec2(90.0, height + 12.0)),
                4.0,
                Color32::from_black_alpha(170),
            );
            for k in 0..=shown {
                let y = top.y + 16.0 * k as f32;
                painter.rect_filled(
                    Rect::from_min_size(pos2(top.x, y + 2.0), vec2(12.0, 12.0)),
                    2.0,
                    colour(level_colour(k)),
                );
                painter.text(
                    pos2(top.x + 18.0, y + 8.0),
                    Align2::LEFT_CENTER,
                    format!("level {k}"),
                    font.clone(),
                    Color32::WHITE,
                );
            }
        }
    }
}

/// `{name} layout`: welded or compat; the response when it changed.
fn layout_control(ui: &mut egui::Ui, name: &str, settings: &mut SwpSurfaceSettings) -> Option<egui::Response> {
    use splinekit::sweep::MeshLayout;
    let compat = settings.layout == Some(MeshLayout::Compat);
    let mut c = compat;
    let r = egui::ComboBox::from_label(format!("{name} layout"))
        .selected_text(if compat { "compat" } else { "welded" })
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut c, false, "welded");
            ui.selectable_value(&mut c, true, "compat");
        })
        .response
        .on_hover_text("welded: seams and poles shared; compat: the course program's vertices");
    if c == compat {
        return None;
    }
    settings.layout = Some(if c { MeshLayout::Compat } else { MeshLayout::Welded });
    Some(r)
}

/// A labelled integer to drag or type; the response when it changed.
fn int_value(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut u32,
    range: std::ops::RangeInclusive<u32>,
    hint: &str,
) -> Option<egui::Response> {
    let label = ui.label(label).on_hover_text(hint);
    let r = ui.add(egui::DragValue::new(value).range(range)).labelled_by(label.id);
    r.changed().then_some(r)
}

/// A labelled number to drag or type (finite, within `range`); the response when it changed.
fn float_value(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut f64,
    range: std::ops::RangeInclusive<f64>,
    hint: &str,
) -> Option<egui::Response> {
    let label = ui.label(label).on_hover_text(hint);
    let speed = 0.005 * value.abs().max(1e-3);
    let r = ui.add(egui::DragValue::new(value).range(range).speed(speed).max_decimals(6)).labelled_by(label.id);
    r.changed().then_some(r)
}

/// A labelled choice of one of the document's curves; the response when it changed.
fn curve_choice(ui: &mut egui::Ui, label: &str, names: &[String], curve: &mut usize) -> Option<egui::Response> {
    let before = *curve;
    let r = egui::ComboBox::from_label(label)
        .selected_text(names.get(*curve).map_or("?", String::as_str))
        .show_ui(ui, |ui| {
            for (i, n) in names.iter().enumerate() {
                ui.selectable_value(curve, i, n);
            }
        })
        .response;
    (*curve != before).then_some(r)
}

/// A labelled choice of one of the document's curves or none; the response when it changed.
fn optional_curve_choice(
    ui: &mut egui::Ui,
    label: &str,
    names: &[String],
    curve: &mut Option<usize>,
) -> Option<egui::Response> {
    let before = *curve;
    let r = egui::ComboBox::from_label(label)
        .selected_text(curve.and_then(|i| names.get(i)).map_or("none", String::as_str))
        .show_ui(ui, |ui| {
            ui.selectable_value(curve, None, "none");
            for (i, n) in names.iter().enumerate() {
                ui.selectable_value(curve, Some(i), n);
            }
        })
        .response;
    (*curve != before).then_some(r)
}

fn editor_sweep_options() -> SurfaceOptions {
    SurfaceOptions { max_triangles: Some(EDITOR_MAX_TRIANGLES), ..SurfaceOptions::default() }
}

/// Stops waiting for the task in `slot` (the work stops at its next check; its result is
/// dropped).
fn cancel<K, T>(slot: &mut Option<(K, work::Task<T>)>) {
    if let Some((_, task)) = slot.take() {
        task.cancel();
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

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        EditorApp::ui(self, ui, frame);
    }
}

/// The number of editable points of a curve (0 for circles and the like).
fn point_count(c: &splinekit_io::SwpCurve) -> usize {
    c.geometry.points().len()
}

/// Appends `b` to `a` (per-vertex attributes kept only if both have them).
fn append(a: &mut TriMesh, b: &TriMesh) {
    let offset = a.positions.len() as u32;
    let keep = |x: usize, y: usize| (x == a.positions.len() || a.positions.is_empty()) && y == b.positions.len();
    let (normals, uvs, colors) =
        (keep(a.normals.len(), b.normals.len()), keep(a.uvs.len(), b.uvs.len()), keep(a.colors.len(), b.colors.len()));
    a.positions.extend_from_slice(&b.positions);
    if normals {
        a.normals.extend_from_slice(&b.normals)
    } else {
        a.normals.clear()
    }
    if uvs {
        a.uvs.extend_from_slice(&b.uvs)
    } else {
        a.uvs.clear()
    }
    if colors {
        a.colors.extend_from_slice(&b.colors)
    } else {
        a.colors.clear()
    }
    a.triangles.extend(b.triangles.iter().map(|t| t.map(|i| i + offset)));
}

/// The levels of `source` made again with `options`' colours: the Loop pyramid to `level`
/// when `pyramid` (Loop without creases), else `count` levels of `scheme`; and the level to
/// show (the same, or the finest that could be made).
fn recolored(
    source: &ViewedMesh,
    scheme: Scheme,
    pyramid: bool,
    level: usize,
    count: usize,
    options: LoopOptions,
) -> (Result<LoopPyramid, String>, Vec<PolyMesh>, usize) {
    let mut p = LoopPyramid::new(&source.base, options).map_err(|e| e.to_string());
    let mut level = level;
    if let Ok(p) = &mut p
        && pyramid
    {
        // the level shown was made before, so it fits; were it refused, show the finest
        if p.refine_to(level, |_| {}).is_err() {
            level = p.finest().depth();
        }
    }
    // the other scheme's levels made so far, again with the new colours
    let mut levels: Vec<PolyMesh> = Vec::with_capacity(count);
    if !pyramid {
        for depth in 1..=count {
            let coarse = levels.last().unwrap_or(&source.base);
            match scheme.polygon_level(&source.base, coarse, &source.creases, depth, options.color_by_level) {
                Ok(fine) => levels.push(fine),
                Err(_) => break,
            }
        }
        level = level.min(levels.len());
    }
    (p, levels, level)
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

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::*;

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
