//! The 3D view: a [`TriMesh`] rendered with wgpu into an offscreen colour + depth texture that
//! egui shows as an image (over the background, the axes and the grid).
//!
//! - **Camera**: an orbit [`Camera`] around a target point, Y up. Primary drag orbits,
//!   secondary / middle drag or shift + primary drag pans, scroll or pinch zooms, a double
//!   click frames the mesh again ([`View3d::fit`]).
//! - **Shading**: smooth (the mesh's vertex normals, or area-weighted ones) or flat, lit on
//!   whichever side is seen; front faces (counter-clockwise, see [`TriMesh`]) in
//!   [`FRONT_COLOUR`] or the mesh's per-vertex colours (e.g. Loop colour-by-level), back faces
//!   in [`BACK_COLOUR`], so an inside-out surface is obvious.
//! - **Wireframe** with hidden lines removed: every triangle draws the part of its own edges
//!   it shows (barycentric distance in the fragment shader), so the depth test hides the rest.
//! - **Normals**: the vertex normals as short lines.
//! - **Axes and grid** ([`Guides`]), drawn over the image under the curves: the x, y, z axes
//!   from the origin in red, green and blue, labelled at their ends, and a faint grid in the
//!   xy plane (the plane of the 2D curves and profiles; the revolution tool's z axis stands
//!   up from it) with spacing 1, 2 or 5 times a power of ten ([`view2d::grid_step`](crate::view2d::grid_step)) from
//!   the scene's size. They are painted under the rendered image, which is transparent where
//!   there is no surface: the surface hides them wherever it covers them (also where they
//!   pass in front of it), and the curves and points are drawn over everything.
//!
//! [`View3d::set_mesh`] is cheap enough to call every frame while a curve is dragged: it
//! rebuilds the vertex data on the CPU, and the next [`View3d::ui`] uploads it into the
//! existing GPU buffers (grown only when too small) and renders one frame. The view renders
//! only when something changed (mesh, camera, settings, size); otherwise egui shows the
//! last image again.
//!
//! The rendering needs eframe's wgpu renderer; with any other (or none), [`View3d::ui`] shows
//! a note instead.

mod camera;
mod gpu;
mod guides;
mod interaction;
mod vertex_data;

use eframe::egui::emath::GuiRounding as _;
use eframe::egui::{self, Color32, Rect, Sense, pos2};
use glam::DVec3;
use splinekit::TriMesh;

pub use camera::{Camera, ORBIT_RADIANS_PER_POINT, PITCH_LIMIT, ZOOM_PER_POINT};
use gpu::Gpu;
pub use guides::{AXIS_COLOURS, GRID_COLOUR, GRID_LINES_PER_RADIUS, Guides, MAX_GRID_LINES};
use interaction::ActiveDrag;
pub use interaction::{HANDLE_ACTIVE_COLOUR, HANDLE_COLOUR, HANDLE_RADIUS, HandleDrag, POLYLINE_COLOUR};
use vertex_data::{MeshData, SURFACE_STRIDE, Scratch, prepare};
pub use vertex_data::{PreparedMesh, bounds, point_bounds};

/// Front faces, when the mesh has no per-vertex colours (light grey-blue, sRGB).
pub const FRONT_COLOUR: Color32 = Color32::from_rgb(168, 186, 214);
/// Back faces, with [`View3dSettings::show_backfaces_colour`] (orange-red, sRGB).
pub const BACK_COLOUR: Color32 = Color32::from_rgb(226, 92, 48);
/// The wireframe overlay.
pub const WIRE_COLOUR: Color32 = Color32::from_rgb(24, 26, 34);
/// The vertex-normal lines.
pub const NORMAL_COLOUR: Color32 = Color32::from_rgb(96, 224, 120);

/// The default background ([`View3dSettings::background`]).
pub const BACKGROUND: Color32 = Color32::from_rgb(44, 47, 54);

/// Shown (and the widget's accessibility label) without the wgpu renderer.
const NO_WGPU: &str = "3D view: needs the wgpu renderer";

/// What the view draws. Public fields; change them at will, the view re-renders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View3dSettings {
    /// The surface itself (off: only what is drawn over it, e.g. the curves).
    pub surface: bool,
    /// Wireframe overlay (hidden lines removed).
    pub wireframe: bool,
    /// Vertex normals as short lines.
    pub normals: bool,
    /// Smooth shading with vertex normals; otherwise flat, one normal per triangle.
    pub smooth: bool,
    /// Back faces in [`BACK_COLOUR`]; otherwise in the front colour.
    pub show_backfaces_colour: bool,
    /// Front faces in the mesh's per-vertex colours, when it has them (e.g. Loop
    /// colour-by-level); otherwise in [`FRONT_COLOUR`].
    pub vertex_colours: bool,
    /// Front faces as a UV checker: the mesh's vertex colours hold its UVs (red u, green v,
    /// fractional parts), and 8 squares per unit are drawn from them per pixel. Set by the
    /// editor's `Colour` choice, not shown among the checkboxes.
    pub checker: bool,
    /// 4× multisampling (smoother silhouettes; slower on a software rasterizer). Ignored
    /// where the adapter cannot do it.
    pub msaa: bool,
    /// Background colour.
    pub background: Color32,
    /// The x, y, z axes from the origin, labelled ([`Guides`]).
    pub axes: bool,
    /// A grid in the xy plane ([`Guides`]).
    pub grid: bool,
}

impl Default for View3dSettings {
    fn default() -> Self {
        Self {
            surface: true,
            wireframe: false,
            normals: false,
            smooth: true,
            show_backfaces_colour: true,
            vertex_colours: true,
            checker: false,
            msaa: false,
            background: BACKGROUND,
            axes: true,
            grid: true,
        }
    }
}

impl View3dSettings {
    /// Checkboxes for the settings, labelled "Draw surface", "Wireframe", "Normals", "Smooth",
    /// "Back faces", "Vertex colours", "MSAA", "Axes" and "Grid".
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        ui.checkbox(&mut self.surface, "Draw surface");
        ui.checkbox(&mut self.wireframe, "Wireframe");
        ui.checkbox(&mut self.normals, "Normals");
        ui.checkbox(&mut self.smooth, "Smooth");
        ui.checkbox(&mut self.show_backfaces_colour, "Back faces");
        ui.checkbox(&mut self.vertex_colours, "Vertex colours");
        ui.checkbox(&mut self.msaa, "MSAA");
        ui.checkbox(&mut self.axes, "Axes");
        ui.checkbox(&mut self.grid, "Grid");
    }
}

/// What is drawn over the mesh in [`View3d::ui_with_overlay`]: polylines (curves, frame
/// arrows) and dots (control points), in world coordinates.
#[derive(Clone, Debug, Default)]
pub struct Overlay {
    /// Polylines: points, colour and width in points.
    pub lines: Vec<(Vec<DVec3>, Color32, f32)>,
    /// Dots: position and colour.
    pub dots: Vec<(DVec3, Color32)>,
    /// The selected handle (drawn in [`HANDLE_ACTIVE_COLOUR`], as the dragged one).
    pub selected: Option<usize>,
}

/// Everything that decides the rendered image; the view renders again when it changes.
#[derive(Clone, Copy, PartialEq)]
struct RenderKey {
    camera: Camera,
    settings: View3dSettings,
    size: [u32; 2],
    generation: u64,
}

/// The 3D view of a mesh. See the [module docs](self).
pub struct View3d {
    /// What is drawn and how.
    pub settings: View3dSettings,
    /// The view's accessible name (`3D view`; the scheme comparison's views are named after
    /// their schemes).
    pub label: String,
    camera: Camera,
    data: MeshData,
    scratch: Scratch,
    /// Frame the camera on the next non-empty mesh.
    fit_pending: bool,
    /// Width / height of the last viewport, for [`Self::fit`]; `None` before the first.
    aspect: Option<f64>,
    /// [`Self::fit`] ran before the viewport's aspect was known: fit again once it is.
    refit_on_aspect: bool,
    /// The viewport's size in pixels at the last frame.
    last_size: Option<[f32; 2]>,
    gpu: Option<Gpu>,
    last_render: Option<RenderKey>,
    drag: Option<ActiveDrag>,
    /// Whether a handle drag ended this frame (the camera then stays).
    dragged_this_frame: bool,
    /// Centre and radius of the last handles and overlay, if any.
    overlay_bounds: Option<(DVec3, f64)>,
    /// How many polylines the last overlay had.
    overlay_lines: usize,
    /// A handle clicked (pressed and released without moving) and not yet taken.
    clicked_handle: Option<usize>,
    /// A camera drag under way: the button pressed on the view and the pointer's last place.
    camera_drag: Option<(egui::PointerButton, egui::Pos2)>,
}

impl Default for View3d {
    fn default() -> Self {
        Self::new()
    }
}

impl std::fmt::Debug for View3d {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("View3d")
            .field("settings", &self.settings)
            .field("camera", &self.camera)
            .field("triangles", &self.num_triangles())
            .field("gpu", &self.gpu.is_some())
            .finish_non_exhaustive()
    }
}

impl View3d {
    /// An empty view. No GPU work happens until the first [`Self::ui`].
    #[must_use]
    pub fn new() -> Self {
        Self {
            settings: View3dSettings::default(),
            label: "3D view".to_owned(),
            camera: Camera::default(),
            data: MeshData::default(),
            scratch: Scratch::default(),
            fit_pending: true,
            aspect: None,
            refit_on_aspect: false,
            last_size: None,
            gpu: None,
            last_render: None,
            drag: None,
            dragged_this_frame: false,
            overlay_bounds: None,
            overlay_lines: 0,
            clicked_handle: None,
            camera_drag: None,
        }
    }

    /// How many polylines (curve segments, frame arrows) the last frame drew over the mesh.
    #[must_use]
    pub fn overlay_lines(&self) -> usize {
        self.overlay_lines
    }

    /// The handle clicked (pressed and released without moving it) since the last call.
    pub fn take_clicked_handle(&mut self) -> Option<usize> {
        self.clicked_handle.take()
    }

    /// Whether a handle is being dragged.
    #[must_use]
    pub fn is_dragging(&self) -> bool {
        self.drag.is_some()
    }

    /// The camera.
    #[must_use]
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The camera, to set a view.
    pub fn camera_mut(&mut self) -> &mut Camera {
        &mut self.camera
    }

    /// Number of triangles drawn (those with valid indices and finite corners).
    #[must_use]
    pub fn num_triangles(&self) -> usize {
        self.data.surface.len() / (3 * SURFACE_STRIDE as usize)
    }

    /// Shows `mesh` from the next frame on. The first non-empty mesh frames the camera
    /// ([`Self::fit`]); later ones keep it. Cheap enough to call every frame: the vertex data
    /// is rebuilt on the CPU, and uploaded and rendered only if it changed.
    ///
    /// Triangles with an index out of range or a non-finite corner are left out. Normals
    /// come from the mesh when it has one per vertex, otherwise they are area-weighted;
    /// colours likewise, read as sRGB in `[0, 1]`.
    pub fn set_mesh(&mut self, mesh: &TriMesh) {
        let (origin, radius, colours) = prepare(mesh, &mut self.scratch);
        let (surface, lines) = (&mut self.scratch.surface, &mut self.scratch.lines);
        let changed = *surface != self.data.surface
            || *lines != self.data.lines
            || origin != self.data.origin
            || colours != self.data.has_colours
            || radius != self.data.radius;
        if changed {
            // swapped, so the scratch buffers keep their capacity for the next call
            let (mut surface, mut lines) = (std::mem::take(surface), std::mem::take(lines));
            self.install(&mut surface, &mut lines, origin, radius, colours);
            (self.scratch.surface, self.scratch.lines) = (surface, lines);
        } else if self.fit_pending && !self.data.surface.is_empty() {
            self.fit();
        }
    }

    /// Shows a mesh prepared off the UI thread ([`PreparedMesh::new`]), as
    /// [`set_mesh`](Self::set_mesh) would show it.
    pub fn set_prepared(&mut self, mesh: PreparedMesh) {
        let PreparedMesh { mut surface, mut lines, origin, radius, colours } = mesh;
        self.install(&mut surface, &mut lines, origin, radius, colours);
    }

    /// Makes `surface` and `lines` the vertex data shown (swapping the old data into them),
    /// and frames the camera if it waits for a mesh.
    fn install(&mut self, surface: &mut Vec<u8>, lines: &mut Vec<u8>, origin: DVec3, radius: f64, colours: bool) {
        std::mem::swap(surface, &mut self.data.surface);
        std::mem::swap(lines, &mut self.data.lines);
        self.data.radius = radius;
        self.data.origin = origin;
        self.data.has_colours = colours;
        self.data.generation += 1;
        if self.fit_pending && !self.data.surface.is_empty() {
            self.fit();
        }
    }

    /// Bumped whenever [`Self::set_mesh`] is given a mesh that looks different.
    #[must_use]
    pub fn generation(&self) -> u64 {
        self.data.generation
    }

    /// The centre and radius ([`bounds`]) of the mesh shown.
    #[must_use]
    pub fn bounds(&self) -> (DVec3, f64) {
        (self.data.origin, self.data.radius)
    }

    /// Frames the camera on the next non-empty mesh given to [`Self::set_mesh`] (e.g. after
    /// a new file is opened).
    pub fn fit_on_next_mesh(&mut self) {
        self.fit_pending = true;
    }

    /// Frames the current mesh: the camera looks at the centre of its bounding box from far
    /// enough to see all of it, keeping its direction.
    ///
    /// With no mesh, it frames the handles and polyline of the last
    /// [`Self::ui_with_handles`] instead.
    pub fn fit(&mut self) {
        let (centre, radius) = self.scene_bounds();
        let half_y = 0.5 * self.camera.fov_y;
        let half_x = (half_y.tan() * self.aspect.unwrap_or(1.0)).atan();
        let half = half_y.min(half_x).max(1e-3);
        self.camera.target = centre;
        self.camera.distance = 1.05 * radius / half.sin();
        self.fit_pending = self.data.surface.is_empty() && self.overlay_bounds.is_none();
        self.refit_on_aspect = self.aspect.is_none();
    }

    /// The centre and radius of what the view shows: the mesh, or with no mesh the handles
    /// and overlay of the last frame (radius 1 when there is no extent).
    fn scene_bounds(&self) -> (DVec3, f64) {
        match self.overlay_bounds {
            Some(b) if self.data.surface.is_empty() => b,
            _ => self.data.centre_radius(),
        }
    }

    /// The axes and grid for what the view shows ([`Guides::new`] of the mesh's bounds, or
    /// with no mesh those of the last frame's handles and overlay), drawn when
    /// [`View3dSettings::axes`] and [`View3dSettings::grid`] are on.
    #[must_use]
    pub fn guides(&self) -> Guides {
        let (centre, radius) = self.scene_bounds();
        Guides::new(centre, radius)
    }

    /// Allocates all the available space, handles the camera input, renders the mesh at the
    /// pixel size of that space and shows it. Without eframe's wgpu renderer it shows a note
    /// instead.
    pub fn ui(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) -> egui::Response {
        self.ui_with_handles(ui, frame, &[], &[]).0
    }

    /// [`Self::ui`] with draggable handles at the world positions `handles` (e.g. the control
    /// points of a 3D curve), drawn over the mesh as dots whose accessibility labels are
    /// `3D P0`, `3D P1`, … A primary drag on a handle moves it in the plane through it
    /// parallel to the screen, so that it follows the pointer exactly; the returned
    /// [`HandleDrag`] says where it is now, on every frame of the drag. Dragging elsewhere
    /// moves the camera as in [`Self::ui`]. `polyline` (e.g. the curve itself) is drawn under
    /// the handles; handles and polyline are drawn over the mesh, not hidden by it.
    pub fn ui_with_handles(
        &mut self,
        ui: &mut egui::Ui,
        frame: &eframe::Frame,
        handles: &[DVec3],
        polyline: &[DVec3],
    ) -> (egui::Response, Option<HandleDrag>) {
        let overlay = Overlay { lines: vec![(polyline.to_vec(), POLYLINE_COLOUR, 2.0)], ..Overlay::default() };
        self.ui_with_overlay(ui, frame, handles, &overlay)
    }

    /// [`Self::ui_with_handles`] with a whole [`Overlay`] (curves, frames, points) drawn over
    /// the mesh under the handles. The camera frames the overlay when there is no mesh.
    pub fn ui_with_overlay(
        &mut self,
        ui: &mut egui::Ui,
        frame: &eframe::Frame,
        handles: &[DVec3],
        overlay: &Overlay,
    ) -> (egui::Response, Option<HandleDrag>) {
        let avail = ui.available_size();
        let size = egui::vec2(
            if avail.x.is_finite() { avail.x.max(0.0) } else { 400.0 },
            if avail.y.is_finite() { avail.y.max(0.0) } else { 300.0 },
        );
        let (rect, response) = ui.allocate_exact_size(size, Sense::click_and_drag());
        let points = || {
            handles
                .iter()
                .copied()
                .chain(overlay.lines.iter().flat_map(|(l, _, _)| l.iter().copied()))
                .chain(overlay.dots.iter().map(|d| d.0))
        };
        self.overlay_bounds = points().next().is_some().then(|| {
            let (centre, radius) = point_bounds(points);
            (centre, if radius > 0.0 { radius } else { 1.0 })
        });
        self.overlay_lines = overlay.lines.len();
        if self.fit_pending && self.data.surface.is_empty() && self.overlay_bounds.is_some() {
            self.fit();
        }
        let label = if frame.wgpu_render_state().is_some() { self.label.as_str() } else { NO_WGPU };
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, label));
        let (moved, dots) = self.handles(ui, rect, handles);
        self.handle_input(ui, &response, rect);

        let ppp = ui.pixels_per_point();
        let rect = rect.round_to_pixels(ppp);
        let width = (rect.width() * ppp).round();
        let height = (rect.height() * ppp).round();
        if !(width >= 1.0 && height >= 1.0 && ui.is_rect_visible(rect)) {
            return (response, moved);
        }
        let aspect = f64::from(width) / f64::from(height);
        // a resized view (window, divider, a panel shown or hidden) frames the scene again
        let resized = self.aspect.is_some_and(|a| a != aspect) || self.last_size.is_some_and(|s| s != [width, height]);
        self.aspect = Some(aspect);
        self.last_size = Some([width, height]);
        if self.refit_on_aspect || resized {
            self.fit();
        }

        let Some(state) = frame.wgpu_render_state() else {
            ui.painter().rect_filled(rect, 0.0, self.settings.background);
            ui.painter().text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                NO_WGPU,
                egui::FontId::proportional(14.0),
                Color32::LIGHT_GRAY,
            );
            return (response, moved);
        };
        let gpu = self.gpu.get_or_insert_with(|| Gpu::new(state));
        let max = gpu.state.device.limits().max_texture_dimension_2d;
        let size = [(width as u32).min(max), (height as u32).min(max)];
        let key = RenderKey { camera: self.camera, settings: self.settings, size, generation: self.data.generation };
        if self.last_render != Some(key) {
            gpu.render(&self.data, &self.camera, &self.settings, size);
            self.last_render = Some(key);
        }
        let painter = ui.painter().with_clip_rect(rect);
        painter.rect_filled(rect, 0.0, self.settings.background);
        self.draw_guides(&painter, rect);
        if let Some(target) = self.gpu.as_ref().and_then(|g| g.target.as_ref()) {
            let uv = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
            painter.image(target.texture_id, rect, uv, Color32::WHITE);
        }
        for (polyline, colour, width) in &overlay.lines {
            let mut line = Vec::with_capacity(polyline.len());
            for &p in polyline {
                match self.camera.project(p, rect) {
                    Some(q) => line.push(q),
                    None => {
                        painter.add(egui::Shape::line(std::mem::take(&mut line), (*width, *colour)));
                    }
                }
            }
            painter.add(egui::Shape::line(line, (*width, *colour)));
        }
        for &(p, colour) in &overlay.dots {
            if let Some(q) = self.camera.project(p, rect) {
                painter.circle(q, 3.5, colour, egui::Stroke::new(1.0, Color32::BLACK));
            }
        }
        for (index, centre, active) in dots {
            let highlighted = active || overlay.selected == Some(index);
            let colour = if highlighted { HANDLE_ACTIVE_COLOUR } else { HANDLE_COLOUR };
            painter.circle(centre, HANDLE_RADIUS, colour, egui::Stroke::new(1.0, Color32::BLACK));
            painter.text(
                centre + egui::vec2(7.0, -7.0),
                egui::Align2::LEFT_BOTTOM,
                format!("P{index}"),
                egui::FontId::proportional(11.0),
                Color32::from_gray(220),
            );
        }
        (response, moved)
    }
}

impl Drop for View3d {
    fn drop(&mut self) {
        if let Some(gpu) = &self.gpu
            && let Some(target) = &gpu.target
        {
            gpu.state.renderer.write().free_texture(&target.texture_id);
        }
    }
}
