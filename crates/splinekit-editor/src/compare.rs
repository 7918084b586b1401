//! Subdivision schemes side by side: the loaded mesh refined to the same level by two to four
//! schemes, each in its own 3D view with its counts, all views sharing one camera (an orbit,
//! pan or zoom in one moves them all).

use eframe::egui;
use splinekit::TriMesh;
use splinekit::subdiv::Scheme;

use crate::doc::ViewedMesh;
use crate::subdivision::{level_options, scheme_level};
use crate::view3d::{Camera, Overlay, View3d, View3dSettings};

/// The most schemes shown at once.
pub const MAX_COMPARED: usize = 4;

/// The most faces a compared level may have (about; estimated before it is made, since the
/// levels are made on the UI thread).
pub const COMPARE_MAX_FACES: usize = 1_000_000;

/// What a compared view shows: the mesh's generation, the level, colour by level.
type Key = (u64, usize, bool);

/// A level's vertex and face counts, or why it could not be made.
pub type Counts = Result<(usize, usize), String>;

/// One scheme's view.
struct Compared {
    scheme: Scheme,
    view: View3d,
    key: Option<Key>,
    /// Vertices and faces of its level, or why it could not be made.
    counts: Counts,
}

/// The schemes compared and their views.
#[derive(Default)]
pub struct Comparison {
    views: Vec<Compared>,
    /// The camera all views share (the last one moved, or fitted).
    camera: Option<Camera>,
}

impl Comparison {
    /// The schemes compared, in the order chosen.
    #[must_use]
    pub fn schemes(&self) -> Vec<Scheme> {
        self.views.iter().map(|c| c.scheme).collect()
    }

    /// Whether the views are shown instead of the single 3D view (two schemes or more).
    #[must_use]
    pub fn is_active(&self) -> bool {
        self.views.len() >= 2
    }

    /// Adds or removes `scheme` (at most [`MAX_COMPARED`]).
    pub fn set(&mut self, scheme: Scheme, on: bool) {
        let present = self.views.iter().position(|c| c.scheme == scheme);
        match (present, on) {
            (None, true) if self.views.len() < MAX_COMPARED => {
                let mut view = View3d::new();
                view.label = format!("{} view", scheme.title());
                self.views.push(Compared { scheme, view, key: None, counts: Ok((0, 0)) });
            }
            (Some(i), false) => {
                self.views.remove(i);
            }
            _ => {}
        }
    }

    /// Every scheme's vertex and face counts (or why its level could not be made).
    #[must_use]
    pub fn counts(&self) -> Vec<(Scheme, Counts)> {
        self.views.iter().map(|c| (c.scheme, c.counts.clone())).collect()
    }

    /// Brings every view to `level` of `source` by its scheme (made again only when the
    /// mesh, the level or the colours changed), with the main view's `settings`.
    pub fn update(
        &mut self,
        source: &ViewedMesh,
        generation: u64,
        level: usize,
        color_by_level: bool,
        settings: View3dSettings,
    ) {
        let key = (generation, level, color_by_level);
        for c in &mut self.views {
            c.view.settings = settings;
            if c.key == Some(key) {
                continue;
            }
            c.key = Some(key);
            match compared_level(source, c.scheme, level, color_by_level) {
                Ok(mesh) => {
                    c.counts = Ok((mesh.num_vertices(), mesh.num_triangles_or_faces()));
                    c.view.set_mesh(&mesh.mesh);
                }
                Err(why) => {
                    c.counts = Err(why);
                    c.view.set_mesh(&TriMesh::default());
                }
            }
        }
    }

    /// Draws the views in a grid (side by side for two, two by two for three or four), each
    /// with its scheme, level and counts, and keeps their cameras together.
    pub fn ui(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame, level: usize) {
        if let Some(camera) = self.camera {
            for c in &mut self.views {
                *c.view.camera_mut() = camera;
            }
        }
        let n = self.views.len();
        let (columns, rows) = if n <= 2 { (n.max(1), 1) } else { (2, n.div_ceil(2)) };
        let area = ui.available_rect_before_wrap();
        let gap = 4.0;
        let w = (area.width() - gap * (columns as f32 - 1.0)) / columns as f32;
        let h = (area.height() - gap * (rows as f32 - 1.0)) / rows as f32;
        let mut moved: Option<Camera> = None;
        for (i, c) in self.views.iter_mut().enumerate() {
            let (col, row) = (i % columns, i / columns);
            let min = area.min + egui::vec2(col as f32 * (w + gap), row as f32 * (h + gap));
            let cell = egui::Rect::from_min_size(min, egui::vec2(w.max(1.0), h.max(1.0)));
            let before = *c.view.camera();
            let mut child = ui.new_child(egui::UiBuilder::new().max_rect(cell).id_salt(("compare", i)));
            let (response, _) = c.view.ui_with_overlay(&mut child, frame, &[], &Overlay::default());
            let text = match &c.counts {
                Ok((v, f)) => format!("{}: level {level}\n{v} vertices, {f} faces", c.scheme.title()),
                Err(why) => format!("{}: {why}", c.scheme.title()),
            };
            let painter = ui.painter_at(response.rect);
            let at = response.rect.left_top() + egui::vec2(8.0, 6.0);
            let font = egui::FontId::proportional(13.0);
            let galley = painter.layout_no_wrap(text, font, egui::Color32::WHITE);
            let back = egui::Rect::from_min_size(at - egui::vec2(4.0, 2.0), galley.size() + egui::vec2(8.0, 4.0));
            painter.rect_filled(back, 3.0, egui::Color32::from_black_alpha(160));
            painter.galley(at, galley, egui::Color32::WHITE);
            if moved.is_none() && *c.view.camera() != before {
                moved = Some(*c.view.camera());
            }
        }
        ui.allocate_rect(area, egui::Sense::hover());
        match (moved, self.camera, self.views.first()) {
            (Some(camera), _, _) => self.camera = Some(camera),
            (None, None, Some(first)) => self.camera = Some(*first.view.camera()),
            _ => {}
        }
    }
}

/// A compared level: the mesh to draw and its face count (the polygons', not the triangles
/// they are drawn with).
pub struct Level {
    /// The level, triangulated for drawing.
    pub mesh: TriMesh,
    faces: usize,
}

impl Level {
    /// Its vertices.
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.mesh.num_vertices()
    }

    /// Its faces (polygons).
    #[must_use]
    pub fn num_triangles_or_faces(&self) -> usize {
        self.faces
    }
}

/// Level `level` of `source` by `scheme` ([`subdivide`](splinekit::subdiv::subdivide) on
/// the loaded mesh), or why not: the scheme's own refusal, or a level estimated at more than
/// [`COMPARE_MAX_FACES`] faces.
///
/// # Errors
/// As above, in words.
pub fn compared_level(
    source: &ViewedMesh,
    scheme: Scheme,
    level: usize,
    color_by_level: bool,
) -> Result<Level, String> {
    let growth = f64::from(scheme.face_growth());
    let estimate = source.base.num_faces() as f64 * growth.powi(i32::try_from(level).unwrap_or(i32::MAX));
    if estimate > COMPARE_MAX_FACES as f64 {
        return Err(format!("about {estimate:.0} faces, too many to compare here"));
    }
    let shown = scheme_level(source, scheme, level, &level_options(color_by_level))?;
    Ok(Level { mesh: shown.to_tri_mesh(), faces: shown.num_faces() })
}
