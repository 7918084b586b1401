//! The splinekit editor (`splinekit edit [FILE]`): 2D curve editing and the surfaces swept
//! from the curves, or a loaded mesh with Loop subdivision.
//!
//! Files open from the command line, the path field, or by dropping them on the window.
//!
//! The window has a file bar (path field: load SWP, OBJ, glb, PLY, STL; save SWP; export the
//! surface as OBJ, glb, PLY or STL), a left panel (curves, kind, closed, plane, what to show),
//! the 2D curve view in the middle, a right panel with the surface or mesh, its subdivision
//! and the 3D view ([`View3d`]), and a status line for messages and errors. An error never
//! changes the document.
//!
//! The 3D view shows the document's surfaces, swept again whenever the document changes (so
//! they follow a dragged point live), or the loaded mesh at the subdivision level shown. The
//! control points of an active 3D curve are handles there too, dragged in the plane parallel
//! to the screen.
//!
//! Keyboard (when no text field has focus): `r` preset scene, `s` cycle the spline kind, `c`
//! clear the curve, `a` arc-length markers, `l` control polygon, `w` wireframe, `n` normals
//! (curve and surface), `f` fit both views, `h` or `?` help, Delete the selected point,
//! Ctrl+Z undo, Ctrl+Shift+Z (or Ctrl+Y) redo.

pub mod doc;
pub mod view2d;
pub mod view3d;

use std::path::{Path, PathBuf};

use eframe::egui::{self, Key, Modifiers};
use splinekit::subdiv::{
    ButterflyOptions, CatmullClarkOptions, Creases, CreasingMethod, DooSabinOptions, LoopOptions, LoopPyramid,
    Sqrt3Options, butterfly_step, catmull_clark_step, catmull_clark_subdivide_creased, doo_sabin_subdivide,
    loop_subdivide_creased, sqrt3_subdivide,
};
use splinekit::{PolyMesh, TriMesh};
use splinekit_io::SwpDocument;
use splinekit_io::mesh::{MeshFormat, RebuildOptions, SplineHeader};
use splinekit_io::surface::SurfaceOptions;

pub use doc::Document;
pub use view2d::{Plane, View2d};
pub use view3d::{View3d, View3dSettings};

/// The keyboard shortcuts, as the help panel lists them.
pub const SHORTCUTS: [(&str, &str); 13] = [
    ("Shift+click", "add a point"),
    ("click on the polygon", "insert a point there"),
    ("drag a point", "move it (drag the background to pan, scroll to zoom)"),
    ("Delete", "delete the selected point (or right-click it)"),
    ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo"),
    ("r", "preset scene (SPEC §1.4)"),
    ("s", "cycle the spline kind"),
    ("c", "clear the curve"),
    ("a", "arc-length markers"),
    ("l", "control polygon"),
    ("w", "wireframe (3D view)"),
    ("n", "normals (curve and surface)"),
    ("f", "fit both views"),
];

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
    fn polygon_level(
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

/// A loaded mesh and its subdivision levels.
pub struct MeshState {
    /// Where it came from.
    pub name: String,
    /// The Loop levels (level 0 is the loaded mesh), or why it cannot be Loop-subdivided.
    pub pyramid: Result<LoopPyramid, String>,
    /// The levels 1, 2, … made so far with `scheme` when it is not Loop without creases.
    pub levels: Vec<PolyMesh>,
    /// The loaded mesh's sharp and semi-sharp edges and vertices (its OBJ's crease tags), used
    /// by Loop and Catmull-Clark.
    pub creases: Creases,
    /// The scheme of the levels shown.
    pub scheme: Scheme,
    /// The loaded mesh (triangles or polygons).
    pub base: PolyMesh,
    /// The level shown.
    pub level: usize,
}

impl MeshState {
    /// Whether the levels are the Loop pyramid's (Loop without creases).
    fn uses_pyramid(&self) -> bool {
        self.scheme == Scheme::Loop && self.creases.is_empty()
    }

    /// The level shown of a scheme other than Loop (the loaded mesh at level 0).
    fn polygon_level(&self) -> &PolyMesh {
        if self.level == 0 { &self.base } else { &self.levels[self.level - 1] }
    }

    /// The number of faces of the level shown.
    #[must_use]
    pub fn faces(&self) -> usize {
        match (self.uses_pyramid(), &self.pyramid) {
            (true, Ok(p)) => p.level(self.level).num_triangles(),
            (true, Err(_)) => self.base.num_faces(),
            _ => self.polygon_level().num_faces(),
        }
    }

    /// The number of vertices of the level shown.
    #[must_use]
    pub fn vertices(&self) -> usize {
        match (self.uses_pyramid(), &self.pyramid) {
            (true, Ok(p)) => p.level(self.level).num_vertices(),
            (true, Err(_)) => self.base.positions.len(),
            _ => self.polygon_level().num_vertices(),
        }
    }

    /// The level shown, triangulated for the 3D view and export.
    #[must_use]
    pub fn shown(&self) -> TriMesh {
        match (self.uses_pyramid(), &self.pyramid) {
            (true, Ok(p)) => p.level(self.level).clone().into_tri_mesh(),
            (true, Err(_)) => self.base.to_tri_mesh(),
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
    /// Sweeps every surface of `swp` with the default options (the path the editor takes on
    /// every change of the document, e.g. every frame of a drag).
    #[must_use]
    pub fn sweep(swp: &SwpDocument) -> Self {
        let mut out = Self::default();
        for (i, s) in swp.surfaces.iter().enumerate() {
            let name = s.display_name(i);
            match swp.surface_mesh(i, &SurfaceOptions::default()) {
                Ok(m) => {
                    out.lines.push(format!("{name}: {} vertices, {} triangles", m.num_vertices(), m.num_triangles()));
                    append(&mut out.mesh, &m);
                }
                Err(e) => {
                    out.lines.push(format!("{name}: {e}"));
                    out.errors.push(format!("{name}: {e}"));
                }
            }
        }
        out
    }
}

/// What the 3D view was last given: the document's revision, or the loaded mesh's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shown {
    Document(u64),
    Mesh { generation: u64, level: usize },
}

/// The editor application.
pub struct EditorApp {
    /// The document.
    pub doc: Document,
    /// The 2D view.
    pub view: View2d,
    /// A loaded mesh (shown instead of the document's surfaces).
    pub mesh: Option<MeshState>,
    /// Colour the subdivision levels.
    pub color_by_level: bool,
    /// The 3D view (its settings: wireframe, normals, …).
    pub view3d: View3d,
    /// The last message (errors start with "Error").
    pub status: String,
    /// The path field of the file bar.
    pub path_field: String,
    /// Show the help window.
    pub show_help: bool,
    /// Show the arc-length table window.
    pub show_table: bool,
    /// The document's surfaces, swept at `surfaces_revision`.
    surfaces: SweptSurfaces,
    surfaces_revision: Option<u64>,
    /// Bumped whenever the loaded mesh or its levels change.
    mesh_generation: u64,
    shown: Option<Shown>,
}

impl Default for EditorApp {
    fn default() -> Self {
        Self {
            doc: Document::new(),
            view: View2d::default(),
            mesh: None,
            color_by_level: false,
            view3d: View3d::new(),
            status: "Shift+click to add points; press h for help".to_owned(),
            path_field: String::new(),
            show_help: false,
            show_table: false,
            surfaces: SweptSurfaces::default(),
            surfaces_revision: None,
            mesh_generation: 0,
            shown: None,
        }
    }
}

impl EditorApp {
    /// A new editor; opens `file` if given (an error goes to the status line).
    #[must_use]
    pub fn new(file: Option<&Path>) -> Self {
        let mut app = Self::default();
        if let Some(file) = file {
            app.path_field = file.display().to_string();
            app.open(file);
        }
        app
    }

    /// Opens an SWP file (as the document) or a mesh (OBJ, glb, PLY, STL; an OBJ with a spline
    /// header is rebuilt from its spline). On error the status line says why and nothing
    /// changes.
    pub fn open(&mut self, path: &Path) {
        let is_swp = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("swp"));
        if is_swp {
            match Document::read(path) {
                Ok(doc) => {
                    self.doc = doc;
                    self.set_mesh_state(None);
                    self.view.fit_pending = true;
                    self.view3d.fit_on_next_mesh();
                    self.view.selected = None;
                    self.status = format!("Loaded {}", path.display());
                }
                Err(e) => self.status = format!("Error: {e}"),
            }
            return;
        }
        match load_mesh(path) {
            Ok((mesh, creases)) => {
                let pyramid = LoopPyramid::new(&mesh, self.loop_options()).map_err(|e| e.to_string());
                self.status =
                    format!("Loaded {}: {} vertices, {} faces", path.display(), mesh.positions.len(), mesh.num_faces());
                if !creases.is_empty() {
                    self.status.push_str(&format!(
                        ", {} creased edges and {} creased vertices (Loop and Catmull-Clark keep them)",
                        creases.edges.len(),
                        creases.vertices.len()
                    ));
                }
                if let Err(e) = &pyramid {
                    self.status.push_str(&format!(" (cannot subdivide: {e})"));
                }
                self.set_mesh_state(Some(MeshState {
                    name: path.display().to_string(),
                    pyramid,
                    levels: Vec::new(),
                    creases,
                    scheme: Scheme::Loop,
                    base: mesh,
                    level: 0,
                }));
                self.view3d.fit_on_next_mesh();
            }
            Err(e) => self.status = format!("Error: {e}"),
        }
    }

    /// Replaces the loaded mesh (`None`: show the document's surfaces again).
    fn set_mesh_state(&mut self, mesh: Option<MeshState>) {
        self.mesh = mesh;
        self.mesh_generation += 1;
    }

    fn loop_options(&self) -> LoopOptions {
        LoopOptions { color_by_level: self.color_by_level, ..LoopOptions::default() }
    }

    /// Refines the loaded mesh one level with its scheme (kept levels are reused when
    /// coarsening). An error (e.g. a non-manifold mesh for Catmull-Clark) goes to the status
    /// line.
    pub fn refine(&mut self) {
        let color_by_level = self.color_by_level;
        let Some(m) = &mut self.mesh else { return };
        match m.scheme {
            Scheme::Loop if m.uses_pyramid() => {
                let Ok(p) = &mut m.pyramid else { return };
                if m.level + 1 > p.finest().depth()
                    && let Err(e) = p.refine()
                {
                    self.status = format!("Error: {}: {e}", m.name);
                    return;
                }
                m.level = (m.level + 1).min(p.finest().depth());
            }
            scheme => {
                if m.level >= m.levels.len() {
                    let coarse = m.levels.last().unwrap_or(&m.base);
                    match scheme.polygon_level(&m.base, coarse, &m.creases, m.levels.len() + 1, color_by_level) {
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

    /// Subdivides the loaded mesh with `scheme` from now on (showing the loaded mesh again).
    pub fn set_scheme(&mut self, scheme: Scheme) {
        let Some(m) = &mut self.mesh else { return };
        if m.scheme != scheme {
            m.scheme = scheme;
            m.level = 0;
            m.levels.clear();
            self.mesh_generation += 1;
            self.status = format!("{} subdivision", scheme.name());
            if !m.creases.is_empty() && !scheme.has_creases() {
                self.status.push_str(" (it has no creases: the mesh's crease tags are left out)");
            }
        }
    }

    /// Rebuilds the loaded mesh's levels with the current colour setting, keeping the level shown.
    fn recolor(&mut self) {
        let options = self.loop_options();
        let Some(m) = &mut self.mesh else { return };
        m.pyramid = LoopPyramid::new(&m.base, options).map_err(|e| e.to_string());
        let pyramid = m.uses_pyramid();
        if let Ok(p) = &mut m.pyramid
            && pyramid
        {
            // the level shown was made before, so it fits; were it refused, show the finest
            if p.refine_to(m.level, |_| {}).is_err() {
                m.level = p.finest().depth();
            }
        }
        // the other scheme's levels made so far, again with the new colours
        let mut levels: Vec<PolyMesh> = Vec::with_capacity(m.levels.len());
        if !pyramid {
            for depth in 1..=m.levels.len() {
                let coarse = levels.last().unwrap_or(&m.base);
                match m.scheme.polygon_level(&m.base, coarse, &m.creases, depth, options.color_by_level) {
                    Ok(fine) => levels.push(fine),
                    Err(_) => break,
                }
            }
        }
        if !pyramid {
            m.level = m.level.min(levels.len());
        }
        m.levels = levels;
        self.mesh_generation += 1;
    }

    /// Shows the next coarser level of the loaded mesh.
    pub fn coarsen(&mut self) {
        if let Some(m) = &mut self.mesh
            && m.level > 0
        {
            m.level -= 1;
            self.status = format!("Level {}: {} faces", m.level, m.faces());
        }
    }

    /// Saves the document as SWP to `path` (through a temporary file).
    pub fn save_swp(&mut self, path: &Path) {
        let text = self.doc.to_swp_string();
        let result = splinekit_io::atomic::write_file(path, |w| -> std::io::Result<()> {
            use std::io::Write;
            w.write_all(text.as_bytes())
        });
        match result {
            Ok(()) => {
                self.doc.path = Some(path.to_path_buf());
                self.status = format!("Saved {}", path.display());
            }
            Err(e) => self.status = format!("Error: cannot write {}: {e}", path.display()),
        }
    }

    /// Exports the shown surface (the loaded mesh's level, or the document's first surface)
    /// in the format of `path`'s extension (obj, glb, ply, stl).
    pub fn export(&mut self, path: &Path) {
        let Some(format) = MeshFormat::from_path(path) else {
            self.status = format!("Error: {}: unknown extension (expected .obj, .glb, .ply or .stl)", path.display());
            return;
        };
        let mesh = match self.shown_mesh() {
            Ok(m) => m,
            Err(e) => {
                self.status = format!("Error: {e}");
                return;
            }
        };
        match splinekit_io::mesh::save(&mesh, path, format) {
            Ok(()) => self.status = format!("Exported {} ({} triangles)", path.display(), mesh.num_triangles()),
            Err(e) => self.status = format!("Error: {e}"),
        }
    }

    /// The mesh of the 3D view: the loaded mesh's level, or the document's surfaces merged.
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
        // the sweep the surface panel and the 3D view already show
        self.update_surfaces();
        match self.surfaces.errors.first() {
            Some(e) => Err(e.clone()),
            None => Ok(self.surfaces.mesh.clone()),
        }
    }

    /// Gives the 3D view the loaded mesh's level, or the document's surfaces, if they changed
    /// since it was last given them.
    fn update_view3d(&mut self) {
        let shown = match &self.mesh {
            Some(m) => Shown::Mesh { generation: self.mesh_generation, level: m.level },
            None => Shown::Document(self.doc.revision()),
        };
        if self.shown == Some(shown) {
            return;
        }
        self.shown = Some(shown);
        match &self.mesh {
            Some(m) => self.view3d.set_mesh(&m.shown()),
            None => {
                self.update_surfaces();
                self.view3d.set_mesh(&self.surfaces.mesh);
            }
        }
    }

    /// The triangle count of the document's surfaces (0 if there are none or they fail).
    #[must_use]
    pub fn surface_triangles(&mut self) -> usize {
        self.update_surfaces();
        self.surfaces.mesh.num_triangles()
    }

    fn update_surfaces(&mut self) {
        if self.surfaces_revision == Some(self.doc.revision()) {
            return;
        }
        self.surfaces = SweptSurfaces::sweep(&self.doc.swp);
        self.surfaces_revision = Some(self.doc.revision());
    }

    fn keyboard(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let pressed = |key: Key| ctx.input_mut(|i| i.consume_key(Modifiers::NONE, key));
        if ctx.input_mut(|i| i.consume_key(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z))
            || ctx.input_mut(|i| i.consume_key(Modifiers::COMMAND, Key::Y))
        {
            self.redo();
        }
        if ctx.input_mut(|i| i.consume_key(Modifiers::COMMAND, Key::Z)) {
            self.undo();
        }
        if pressed(Key::R) {
            self.preset();
        }
        if pressed(Key::S) {
            self.doc.cycle_kind();
        }
        if pressed(Key::C) {
            self.doc.clear();
            self.view.selected = None;
        }
        if pressed(Key::A) {
            self.view.show.markers ^= true;
        }
        if pressed(Key::L) {
            self.view.show.polygon ^= true;
        }
        if pressed(Key::W) {
            self.view3d.settings.wireframe ^= true;
        }
        if pressed(Key::N) {
            let on = !self.view3d.settings.normals;
            self.view3d.settings.normals = on;
            self.view.show.normals = on;
        }
        if pressed(Key::F) {
            self.view.fit_pending = true;
            self.view3d.fit();
        }
        if pressed(Key::H) || ctx.input(|i| i.events.iter().any(|e| matches!(e, egui::Event::Text(t) if t == "?"))) {
            self.show_help ^= true;
        }
        if (pressed(Key::Delete) || pressed(Key::Backspace))
            && let Some(i) = self.view.selected.take()
        {
            self.doc.delete_point(i);
        }
    }

    /// Loads the preset scene (SPEC §1.4) and frames it.
    pub fn preset(&mut self) {
        self.doc.preset();
        self.set_mesh_state(None);
        self.view3d.fit_on_next_mesh();
        self.view.plane = Plane::Xy;
        self.view.fit_pending = true;
        self.view.selected = None;
        self.status = "Preset scene: open uniform Catmull-Rom, 8 points (SPEC §1.4)".to_owned();
    }

    /// Undoes the last edit.
    pub fn undo(&mut self) {
        if !self.doc.undo() {
            self.status = "Nothing to undo".to_owned();
        }
        self.view.selected = None;
    }

    /// Redoes the last undone edit.
    pub fn redo(&mut self) {
        if !self.doc.redo() {
            self.status = "Nothing to redo".to_owned();
        }
        self.view.selected = None;
    }

    fn file_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.label("File:");
            ui.add(egui::TextEdit::singleline(&mut self.path_field).desired_width(320.0).hint_text("path/to/file.swp"));
            let path = PathBuf::from(self.path_field.trim());
            let empty = self.path_field.trim().is_empty();
            if ui.add_enabled(!empty, egui::Button::new("Open")).clicked() {
                self.open(&path);
            }
            if ui.add_enabled(!empty, egui::Button::new("Save SWP")).clicked() {
                self.save_swp(&path);
            }
            if ui.add_enabled(!empty, egui::Button::new("Export mesh")).clicked() {
                self.export(&path);
            }
            ui.separator();
            if ui.add_enabled(self.doc.can_undo(), egui::Button::new("Undo")).clicked() {
                self.undo();
            }
            if ui.add_enabled(self.doc.can_redo(), egui::Button::new("Redo")).clicked() {
                self.redo();
            }
            if ui.button("Preset").clicked() {
                self.preset();
            }
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
        }
        ui.separator();
        ui.heading("Show");
        let show = &mut self.view.show;
        ui.checkbox(&mut show.polygon, "Control polygon");
        ui.checkbox(&mut show.markers, "Arc-length markers");
        ui.add(egui::Slider::new(&mut show.marker_spacing, 0.001..=10.0).logarithmic(true).text("spacing"));
        ui.checkbox(&mut show.normals, "Tangents and normals");
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
            ui.horizontal(|ui| {
                if ui.add_enabled(can_refine, egui::Button::new("Refine subdivision")).clicked() {
                    self.refine();
                }
                if ui.button("Coarsen subdivision").clicked() {
                    self.coarsen();
                }
            });
            if ui.checkbox(&mut self.color_by_level, "Colour by level").changed() {
                self.recolor();
            }
            if ui.button("Close mesh").clicked() {
                self.set_mesh_state(None);
                self.view3d.fit_on_next_mesh();
            }
        } else {
            self.update_surfaces();
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
        });
        ui.separator();
        self.update_view3d();
        // the control points of a 3D curve, dragged in the 3D view
        let (handles, curve) = if self.mesh.is_none() && !self.doc.is_2d() {
            let curve = self.doc.spline().map_or_else(|_| Vec::new(), |c| sample_curve(&c));
            (self.doc.points().to_vec(), curve)
        } else {
            (Vec::new(), Vec::new())
        };
        let (_, drag) = self.view3d.ui_with_handles(ui, frame, &handles, &curve);
        if let Some(d) = drag {
            if d.started {
                self.doc.begin_move();
            }
            self.doc.set_point(d.index, d.position);
            self.view.selected = Some(d.index);
        }
    }

    fn windows(&mut self, ctx: &egui::Context) {
        let mut open = self.show_help;
        egui::Window::new("Help").open(&mut open).show(ctx, |ui| {
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

    /// The whole user interface (one frame); the 3D view renders with `frame`'s wgpu
    /// renderer.
    pub fn ui(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.keyboard(&ctx);
        // a file dropped on the window opens like one typed in the path field
        let dropped = ctx.input(|i| i.raw.dropped_files.first().map(|f| f.path().to_path_buf()));
        if let Some(path) = dropped {
            self.path_field = path.display().to_string();
            self.open(&path);
        }
        egui::Panel::top("file bar").show(ui, |ui| self.file_bar(ui));
        // one line, so the views keep their size whatever it says
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                let error = self.status.starts_with("Error");
                let text = egui::RichText::new(&self.status);
                ui.label(if error { text.color(egui::Color32::from_rgb(200, 30, 30)) } else { text });
                if let Err(e) = self.doc.spline()
                    && !self.doc.points().is_empty()
                {
                    ui.separator();
                    ui.label(format!("Curve: {e}"));
                }
            });
        });
        egui::Panel::left("curves").show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| self.left_panel(ui));
        });
        let half = 0.45 * ui.available_width();
        egui::Panel::right("surface").default_size(half).min_size(220.0).resizable(true).show(ui, |ui| {
            self.right_panel(ui, frame);
        });
        egui::CentralPanel::default().show(ui, |ui| {
            self.view.ui(ui, &mut self.doc);
        });
        self.windows(&ctx);
    }
}

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        EditorApp::ui(self, ui, frame);
    }
}

/// The number of editable points of a curve (0 for circles and the like).
fn point_count(c: &splinekit_io::SwpCurve) -> usize {
    match &c.geometry {
        splinekit_io::SwpGeometry::Points(p) | splinekit_io::SwpGeometry::Hermite { points: p, .. } => p.len(),
        _ => 0,
    }
}

/// Points along `c`, 32 per segment, for the 3D view's overlay.
fn sample_curve(c: &splinekit::AnyCurve<glam::DVec3>) -> Vec<glam::DVec3> {
    use splinekit::ParamCurve as _;
    let segments = c.num_segments();
    let n = 32 * segments;
    (0..=n).map(|i| c.eval(segments as f64 * i as f64 / n.max(1) as f64)).collect()
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

/// Reads a mesh file and its creases (an OBJ's crease tags); an OBJ with a spline header is
/// rebuilt from its spline.
fn load_mesh(path: &Path) -> Result<(PolyMesh, Creases), String> {
    let is_obj = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    if is_obj && let Ok(Some(header)) = SplineHeader::read(path) {
        let mesh = header.rebuild(&RebuildOptions::DEFAULT).map_err(|e| format!("{}: {e}", path.display()))?;
        return Ok((PolyMesh::from(&mesh), Creases::default()));
    }
    splinekit_io::load_mesh(path).map(|m| (m.mesh, m.creases)).map_err(|e| e.to_string())
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
