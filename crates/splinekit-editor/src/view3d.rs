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
//!   up from it) with spacing 1, 2 or 5 times a power of ten ([`view2d::grid_step`]) from
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

use eframe::egui::emath::GuiRounding as _;
use eframe::egui::{self, Color32, PointerButton, Rect, Sense, Vec2, pos2};
use eframe::egui_wgpu;
use eframe::wgpu;
use glam::{DMat4, DVec3, DVec4, Vec3};
use splinekit::TriMesh;

use crate::view2d;

/// Front faces, when the mesh has no per-vertex colours (light grey-blue, sRGB).
pub const FRONT_COLOUR: Color32 = Color32::from_rgb(168, 186, 214);
/// Back faces, with [`View3dSettings::show_backfaces_colour`] (orange-red, sRGB).
pub const BACK_COLOUR: Color32 = Color32::from_rgb(226, 92, 48);
/// The wireframe overlay.
pub const WIRE_COLOUR: Color32 = Color32::from_rgb(24, 26, 34);
/// The vertex-normal lines.
pub const NORMAL_COLOUR: Color32 = Color32::from_rgb(96, 224, 120);
/// The x, y and z axes ([`View3dSettings::axes`]).
pub const AXIS_COLOURS: [Color32; 3] =
    [Color32::from_rgb(230, 70, 70), Color32::from_rgb(80, 200, 90), Color32::from_rgb(90, 140, 255)];
/// The grid lines ([`View3dSettings::grid`]): dim grey, translucent (premultiplied).
pub const GRID_COLOUR: Color32 = Color32::from_rgba_premultiplied(35, 35, 35, 60);
/// The default background ([`View3dSettings::background`]).
pub const BACKGROUND: Color32 = Color32::from_rgb(44, 47, 54);

/// Orbit speed: radians of yaw or pitch per point of primary drag. Dragging right turns the
/// camera left around the target (`yaw` decreases), dragging down raises it (`pitch`
/// increases).
pub const ORBIT_RADIANS_PER_POINT: f64 = 0.01;
/// Scroll zoom: scrolling `dy` points multiplies the camera distance by
/// `exp(-ZOOM_PER_POINT * dy)` (scrolling up, `dy > 0`, moves closer).
pub const ZOOM_PER_POINT: f64 = 0.002;
/// The largest `|pitch|`, just short of looking straight down or up.
pub const PITCH_LIMIT: f64 = 1.55;

/// Width of the wireframe lines in pixels.
const WIRE_WIDTH_PX: f32 = 1.0;
/// Bytes per triangle corner: position (3 × f32), normal (3 × f32), sRGB colour (4 × u8).
const SURFACE_STRIDE: u64 = 28;
/// Bytes per normal-line end: position (3 × f32).
const LINE_STRIDE: u64 = 12;
const COLOUR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
const UNIFORM_SIZE: u64 = 64 + 7 * 16;
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

/// An orbit camera, Y up: the eye sits `distance` from `target`, in the direction given by
/// `yaw` (around +Y; 0 puts the eye on +Z) and `pitch` (above the XZ plane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The point the camera looks at and orbits around.
    pub target: DVec3,
    /// Radians around +Y; 0 puts the eye on the +Z side of the target.
    pub yaw: f64,
    /// Radians above the XZ plane, within ±[`PITCH_LIMIT`].
    pub pitch: f64,
    /// Distance from the eye to the target (> 0).
    pub distance: f64,
    /// Vertical field of view in radians.
    pub fov_y: f64,
}

impl Default for Camera {
    fn default() -> Self {
        Self { target: DVec3::ZERO, yaw: 0.6, pitch: 0.4, distance: 4.0, fov_y: 35f64.to_radians() }
    }
}

impl Camera {
    /// Unit vector from the target to the eye.
    #[must_use]
    pub fn back(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        DVec3::new(cp * sy, sp, cp * cy)
    }

    /// The eye position.
    #[must_use]
    pub fn eye(&self) -> DVec3 {
        self.target + self.distance * self.back()
    }

    /// Unit vectors to the right of and up the screen.
    #[must_use]
    pub fn right_up(&self) -> (DVec3, DVec3) {
        let (sy, cy) = self.yaw.sin_cos();
        let right = DVec3::new(cy, 0.0, -sy);
        (right, self.back().cross(right))
    }

    /// Turns the camera around the target by a drag of `delta` points
    /// ([`ORBIT_RADIANS_PER_POINT`]).
    pub fn orbit(&mut self, delta: Vec2) {
        self.yaw = (self.yaw - f64::from(delta.x) * ORBIT_RADIANS_PER_POINT).rem_euclid(std::f64::consts::TAU);
        self.pitch = (self.pitch + f64::from(delta.y) * ORBIT_RADIANS_PER_POINT).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }

    /// Moves the target so that a point at the target's depth follows a drag of `delta`
    /// points in a view `view_height` points high.
    pub fn pan(&mut self, delta: Vec2, view_height: f32) {
        let per_point = self.units_per_point(self.distance, view_height);
        let (right, up) = self.right_up();
        self.target += per_point * (-f64::from(delta.x) * right + f64::from(delta.y) * up);
    }

    /// Multiplies the distance by `factor` (< 1 moves closer), keeping it within
    /// `[min, max]`.
    pub fn zoom(&mut self, factor: f64, min: f64, max: f64) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance * factor).clamp(min, max);
        }
    }

    /// The distance in front of the eye of `p`, along the view direction.
    #[must_use]
    pub fn depth(&self, p: DVec3) -> f64 {
        (self.eye() - p).dot(self.back())
    }

    /// World units per point at `depth` in a view `view_height` points high.
    #[must_use]
    pub fn units_per_point(&self, depth: f64, view_height: f32) -> f64 {
        2.0 * depth * (0.5 * self.fov_y).tan() / f64::from(view_height.max(1.0))
    }

    /// Where `p` appears in a view filling `rect` (points), or `None` behind the eye.
    #[must_use]
    pub fn project(&self, p: DVec3, rect: Rect) -> Option<egui::Pos2> {
        let depth = self.depth(p);
        if !(depth > 0.0) {
            return None;
        }
        let per_point = self.units_per_point(depth, rect.height());
        let (right, up) = self.right_up();
        let d = p - self.eye();
        let c = rect.center();
        Some(pos2(c.x + (d.dot(right) / per_point) as f32, c.y - (d.dot(up) / per_point) as f32))
    }

    /// The part of the segment `ab` in front of the eye (deeper than a thousandth of the
    /// camera's distance) projected into `rect` as [`Self::project`] does, or `None` when no
    /// part is (or an end is not finite).
    #[must_use]
    pub fn project_segment(&self, a: DVec3, b: DVec3, rect: Rect) -> Option<[egui::Pos2; 2]> {
        let near = 1e-3 * self.distance;
        let (da, db) = (self.depth(a) - near, self.depth(b) - near);
        if !(da >= 0.0 || db >= 0.0) {
            return None;
        }
        // the end behind moved along the segment to the near depth
        let cut = |p: DVec3, q: DVec3, dp: f64, dq: f64| p + (q - p) * (dp / (dp - dq));
        let (a, b) = if da < 0.0 {
            (cut(a, b, da, db), b)
        } else if db < 0.0 {
            (a, cut(b, a, db, da))
        } else {
            (a, b)
        };
        Some([self.project(a, rect)?, self.project(b, rect)?])
    }

    /// `p` moved in the plane through it parallel to the screen, so that it follows a drag
    /// of `delta` points in a view `view_height` points high (its projection moves by
    /// exactly `delta`, its depth stays).
    #[must_use]
    pub fn drag_in_view_plane(&self, p: DVec3, delta: Vec2, view_height: f32) -> DVec3 {
        let per_point = self.units_per_point(self.depth(p), view_height);
        let (right, up) = self.right_up();
        p + per_point * (f64::from(delta.x) * right - f64::from(delta.y) * up)
    }

    /// Projection × view for a viewport of aspect `width / height`, in render space (world
    /// minus `origin`), with the given near and far planes (wgpu depth 0..1).
    #[must_use]
    pub fn view_proj(&self, origin: DVec3, aspect: f64, near: f64, far: f64) -> DMat4 {
        let (s, u) = self.right_up();
        let f = -self.back();
        let eye = self.eye() - origin;
        let view = DMat4::from_cols(
            DVec4::new(s.x, u.x, -f.x, 0.0),
            DVec4::new(s.y, u.y, -f.y, 0.0),
            DVec4::new(s.z, u.z, -f.z, 0.0),
            DVec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
        );
        // Right-handed, depth 0 at `near` and 1 at `far`.
        let h = 1.0 / (0.5 * self.fov_y).tan();
        let r = far / (near - far);
        let proj = DMat4::from_cols(
            DVec4::new(h / aspect, 0.0, 0.0, 0.0),
            DVec4::new(0.0, h, 0.0, 0.0),
            DVec4::new(0.0, 0.0, r, -1.0),
            DVec4::new(0.0, 0.0, r * near, 0.0),
        );
        proj * view
    }
}

/// The vertex data of the current mesh, ready to upload.
#[derive(Default)]
struct MeshData {
    /// Three corners per drawn triangle, [`SURFACE_STRIDE`] bytes each.
    surface: Vec<u8>,
    /// Two ends per normal line, [`LINE_STRIDE`] bytes each.
    lines: Vec<u8>,
    /// Subtracted from positions before they go to f32 (the bounding-box centre).
    origin: DVec3,
    /// Largest distance of a finite position from `origin`.
    radius: f64,
    has_colours: bool,
    /// Bumped whenever the data changes.
    generation: u64,
}

impl MeshData {
    /// Centre and radius of the bounding sphere (radius 1 when there is no extent).
    fn centre_radius(&self) -> (DVec3, f64) {
        let r = self.radius;
        (self.origin, if r > 0.0 && r.is_finite() { r } else { 1.0 })
    }
}

/// Scratch space of [`View3d::set_mesh`], kept to avoid reallocating every frame.
#[derive(Default)]
struct Scratch {
    normals: Vec<Vec3>,
    normal_sums: Vec<DVec3>,
    records: Vec<[u8; SURFACE_STRIDE as usize]>,
    surface: Vec<u8>,
    lines: Vec<u8>,
}

/// A handle being dragged in the view ([`View3d::ui_with_handles`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandleDrag {
    /// Which handle.
    pub index: usize,
    /// Where it is now: its position when the drag started, moved in the plane parallel to
    /// the screen by the whole drag ([`Camera::drag_in_view_plane`]).
    pub position: DVec3,
    /// The first frame of the drag (one undo step per drag starts here).
    pub started: bool,
}

/// The handle drag under way: which handle and where it was when the drag started.
#[derive(Clone, Copy, Debug)]
struct ActiveDrag {
    index: usize,
    start: DVec3,
    /// Where the button went down.
    origin: egui::Pos2,
    /// Whether the handle has moved (the first move starts the undo step).
    moved: bool,
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

/// Grid lines per radius of the scene, at least ([`Guides::new`]).
pub const GRID_LINES_PER_RADIUS: f64 = 5.0;
/// The most grid lines in each direction, whatever the numbers.
pub const MAX_GRID_LINES: f64 = 64.0;

/// The axes and the grid of the 3D view ([`View3dSettings::axes`], [`View3dSettings::grid`])
/// for a scene, in world coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Guides {
    /// The grid spacing: 1, 2 or 5 times a power of ten ([`view2d::grid_step`]).
    pub step: f64,
    /// How far each axis reaches from the origin (its label is at the end).
    pub axis_length: f64,
    /// The grid lines in the xy plane (z = 0): first those of constant x, then those of
    /// constant y, from low to high.
    pub grid: Vec<[DVec3; 2]>,
}

impl Guides {
    /// The guides of a scene within `radius` of `centre` (e.g. [`point_bounds`]): grid lines
    /// [`GRID_LINES_PER_RADIUS`] or more per radius, over the square in xy that holds the
    /// scene's bounding sphere (rounded out to whole steps); axes reaching 1.2 times as far
    /// as the scene's farthest point from the origin, rounded up to a whole step. A radius
    /// that is not positive and finite counts as 1, a centre that is not finite as the
    /// origin.
    #[must_use]
    pub fn new(centre: DVec3, radius: f64) -> Self {
        let centre = if centre.is_finite() { centre } else { DVec3::ZERO };
        let radius = if radius.is_finite() && radius > 0.0 { radius } else { 1.0 };
        let step = view2d::grid_step(radius / GRID_LINES_PER_RADIUS);
        let range = |c: f64| {
            let lo = ((c - radius) / step).floor();
            (lo, ((c + radius) / step).ceil().clamp(lo, lo + MAX_GRID_LINES))
        };
        let ((x0, x1), (y0, y1)) = (range(centre.x), range(centre.y));
        // counted in integers: far from the origin `k + 1.0` may equal `k`
        let ks = |lo: f64, hi: f64| (0..=(hi - lo) as usize).map(move |i| (lo + i as f64) * step);
        let mut grid: Vec<[DVec3; 2]> =
            ks(x0, x1).map(|x| [DVec3::new(x, y0 * step, 0.0), DVec3::new(x, y1 * step, 0.0)]).collect();
        grid.extend(ks(y0, y1).map(|y| [DVec3::new(x0 * step, y, 0.0), DVec3::new(x1 * step, y, 0.0)]));
        let axis_length = (1.2 * (centre.length() + radius) / step).ceil() * step;
        grid.retain(|[a, b]| a.is_finite() && b.is_finite());
        Self { step, axis_length: if axis_length.is_finite() { axis_length } else { radius }, grid }
    }
}

/// Radius of a handle's dot, and of the area that grabs it, in points.
pub const HANDLE_RADIUS: f32 = 5.0;
/// The polyline of [`View3d::ui_with_handles`].
pub const POLYLINE_COLOUR: Color32 = Color32::from_rgb(250, 170, 40);
/// Handle dots (the selected / dragged one in [`HANDLE_ACTIVE_COLOUR`]).
pub const HANDLE_COLOUR: Color32 = Color32::from_rgb(250, 210, 60);
/// The handle being dragged.
pub const HANDLE_ACTIVE_COLOUR: Color32 = Color32::from_rgb(255, 255, 255);

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

    /// Draws the grid, then the axes and their labels, with `painter` over the image in `rect`.
    fn draw_guides(&self, painter: &egui::Painter, rect: Rect) {
        if !(self.settings.axes || self.settings.grid) {
            return;
        }
        let guides = self.guides();
        if self.settings.grid {
            for &[a, b] in &guides.grid {
                if let Some(line) = self.camera.project_segment(a, b, rect) {
                    painter.line_segment(line, (1.0, GRID_COLOUR));
                }
            }
        }
        if self.settings.axes {
            for ((axis, colour), name) in
                [DVec3::X, DVec3::Y, DVec3::Z].into_iter().zip(AXIS_COLOURS).zip(["x", "y", "z"])
            {
                let Some([a, b]) = self.camera.project_segment(DVec3::ZERO, guides.axis_length * axis, rect) else {
                    continue;
                };
                painter.line_segment([a, b], (1.5, colour));
                // the label just beyond the end, or where the axis leaves the view
                let Some([a, b]) = clip_segment(a, b, rect.shrink(14.0)) else { continue };
                let beyond = (b - a).normalized() * 7.0;
                let at = if beyond.is_finite() { b + beyond } else { b };
                painter.text(at, egui::Align2::CENTER_CENTER, name, egui::FontId::proportional(11.0), colour);
            }
        }
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

    /// The handle widgets over `rect` (labelled for accessibility), and the handle drags
    /// from the frame's pointer events in order: a primary press within the grab radius of
    /// a handle picks it (where the button went down, so a drag that leaves the handle within
    /// one frame still moves it), each move puts it under the pointer, the release ends the
    /// drag. Returns the drag's position this frame, and each visible handle's dot and
    /// whether it is the one dragged.
    fn handles(
        &mut self,
        ui: &egui::Ui,
        rect: Rect,
        handles: &[DVec3],
    ) -> (Option<HandleDrag>, Vec<(usize, egui::Pos2, bool)>) {
        let mut moved = None;
        if self.drag.is_some_and(|d| d.index >= handles.len()) {
            self.drag = None;
        }
        let mut centres = Vec::with_capacity(handles.len());
        for (index, &p) in handles.iter().enumerate() {
            let Some(centre) = self.camera.project(p, rect).filter(|c| rect.contains(*c)) else { continue };
            let id = ui.scope_id().with(("view3d handle", index));
            let grab = Rect::from_center_size(centre, Vec2::splat(2.0 * HANDLE_RADIUS + 4.0));
            let r = ui.interact(grab, id, Sense::hover());
            r.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Button, true, format!("3D P{index}")));
            centres.push((index, centre));
        }
        let layer = ui.layer_id();
        let grab_radius = HANDLE_RADIUS + 2.0;
        for event in ui.input(|i| i.events.clone()) {
            match event {
                egui::Event::PointerButton { pos, button: PointerButton::Primary, pressed: true, .. }
                    if self.drag.is_none()
                        && rect.contains(pos)
                        && ui.ctx().layer_id_at(pos).is_none_or(|l| l == layer) =>
                {
                    let nearest = centres
                        .iter()
                        .map(|&(i, c)| (i, c.distance(pos)))
                        .filter(|&(_, d)| d <= grab_radius)
                        .min_by(|a, b| a.1.total_cmp(&b.1));
                    if let Some((index, _)) = nearest {
                        self.drag = Some(ActiveDrag { index, start: handles[index], origin: pos, moved: false });
                    }
                }
                egui::Event::PointerMoved(pos) => {
                    if let Some(m) = self.drag_handle_to(pos, rect) {
                        moved = Some(HandleDrag {
                            started: m.started || moved.is_some_and(|x: HandleDrag| x.started),
                            ..m
                        });
                    }
                }
                egui::Event::PointerButton { pos, button: PointerButton::Primary, pressed: false, .. }
                    if self.drag.is_some() =>
                {
                    if let Some(m) = self.drag_handle_to(pos, rect) {
                        moved = Some(HandleDrag {
                            started: m.started || moved.is_some_and(|x: HandleDrag| x.started),
                            ..m
                        });
                    }
                    // a press and release that did not move it: a click that selects it
                    if let Some(d) = self.drag.filter(|d| !d.moved) {
                        self.clicked_handle = Some(d.index);
                    }
                    self.drag = None;
                    self.dragged_this_frame = true;
                }
                egui::Event::PointerGone => self.drag = None,
                _ => {}
            }
        }
        let dots = centres
            .iter()
            .map(|&(index, centre)| {
                let dot = moved
                    .filter(|m| m.index == index)
                    .and_then(|m| self.camera.project(m.position, rect))
                    .unwrap_or(centre);
                (index, dot, self.drag.is_some_and(|d| d.index == index))
            })
            .collect();
        (moved, dots)
    }

    /// Moves the dragged handle under `pointer`: its position, if it moved.
    fn drag_handle_to(&mut self, pointer: egui::Pos2, rect: Rect) -> Option<HandleDrag> {
        let d = self.drag.as_mut()?;
        if pointer == d.origin && !d.moved {
            return None;
        }
        let started = !d.moved;
        d.moved = true;
        let position = self.camera.drag_in_view_plane(d.start, pointer - d.origin, rect.height());
        Some(HandleDrag { index: d.index, position, started })
    }

    fn handle_input(&mut self, ui: &egui::Ui, response: &egui::Response, rect: Rect) {
        let (_, radius) = self.data.centre_radius();
        let (min, max) = (1e-4 * radius, 1e4 * radius);
        // a drag that picked a handle moves the handle, not the camera
        let handle_drag = self.drag.is_some() || std::mem::take(&mut self.dragged_this_frame);
        if response.dragged() && !handle_drag {
            let delta = response.drag_delta();
            let shift = ui.input(|i| i.modifiers.shift);
            if response.dragged_by(PointerButton::Primary) && !shift {
                self.camera.orbit(delta);
            } else if response.dragged_by(PointerButton::Primary)
                || response.dragged_by(PointerButton::Secondary)
                || response.dragged_by(PointerButton::Middle)
            {
                self.camera.pan(delta, rect.height());
            }
        }
        if response.double_clicked() {
            self.fit();
        }
        if response.hovered() {
            let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
            if scroll != 0.0 {
                self.camera.zoom((-ZOOM_PER_POINT * f64::from(scroll)).exp(), min, max);
                ui.ctx().input_mut(|i| i.smooth_scroll_delta.y = 0.0);
            }
            if zoom != 1.0 {
                self.camera.zoom(1.0 / f64::from(zoom), min, max);
            }
        }
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

/// The centre of the bounding box of `mesh`'s finite positions (the origin if there are
/// A mesh's vertex data for the 3D view, made where it takes no time from the UI thread (a
/// few hundred milliseconds for millions of triangles); [`View3d::set_prepared`] shows it.
pub struct PreparedMesh {
    surface: Vec<u8>,
    lines: Vec<u8>,
    origin: DVec3,
    radius: f64,
    colours: bool,
}

impl PreparedMesh {
    /// The vertex data of `mesh` (as [`View3d::set_mesh`] makes it).
    #[must_use]
    pub fn new(mesh: &TriMesh) -> Self {
        let mut scratch = Scratch::default();
        let (origin, radius, colours) = prepare(mesh, &mut scratch);
        Self { surface: scratch.surface, lines: scratch.lines, origin, radius, colours }
    }

    /// The number of triangles it draws.
    #[must_use]
    pub fn num_triangles(&self) -> usize {
        self.surface.len() / (3 * SURFACE_STRIDE as usize)
    }
}

/// Fills `scratch.surface` and `scratch.lines` with the vertex data of `mesh`; returns its
/// origin, radius and whether it has colours.
///
/// Triangles with an index out of range or a non-finite corner are left out. Normals
/// come from the mesh when it has one per vertex, otherwise they are area-weighted;
/// colours likewise, read as sRGB in `[0, 1]`.
fn prepare(mesh: &TriMesh, scratch: &mut Scratch) -> (DVec3, f64, bool) {
    let n = mesh.positions.len();
    let (origin, radius) = bounds(mesh);
    let valid = |t: &[u32; 3]| t.iter().all(|&v| (v as usize) < n && mesh.positions[v as usize].is_finite());

    // Unit vertex normals.
    let normals = &mut scratch.normals;
    normals.clear();
    if mesh.normals.len() == n {
        normals.extend(mesh.normals.iter().map(|v| v.normalize_or_zero().as_vec3()));
    } else {
        let sums = &mut scratch.normal_sums;
        sums.clear();
        sums.resize(n, DVec3::ZERO);
        for t in mesh.triangles.iter().filter(|t| valid(t)) {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            let face = (b - a).cross(c - a);
            for &v in t {
                sums[v as usize] += face;
            }
        }
        normals.extend(sums.iter().map(|v| v.normalize_or_zero().as_vec3()));
    }
    let colours = mesh.colors.len() == n;
    let srgb8 = |c: DVec3| c.clamp(DVec3::ZERO, DVec3::ONE).to_array().map(|x| (x * 255.0).round() as u8);

    // One record per vertex, then three copied per triangle.
    let records = &mut scratch.records;
    records.clear();
    records.extend(mesh.positions.iter().zip(normals.iter()).enumerate().map(|(v, (p, nv))| {
        let mut r = [0u8; SURFACE_STRIDE as usize];
        let p = (*p - origin).as_vec3();
        for (k, x) in [p.x, p.y, p.z, nv.x, nv.y, nv.z].into_iter().enumerate() {
            r[4 * k..4 * k + 4].copy_from_slice(&x.to_le_bytes());
        }
        let [red, green, blue] = if colours { srgb8(mesh.colors[v]) } else { [255; 3] };
        r[24..].copy_from_slice(&[red, green, blue, 255]);
        r
    }));
    let surface = &mut scratch.surface;
    surface.clear();
    surface.reserve(mesh.triangles.len() * 3 * SURFACE_STRIDE as usize);
    let mut edge_sum = 0.0;
    let mut edges = 0usize;
    for t in mesh.triangles.iter().filter(|t| valid(t)) {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        edge_sum += a.distance(b) + b.distance(c) + c.distance(a);
        edges += 3;
        for &v in t {
            surface.extend_from_slice(&records[v as usize]);
        }
    }

    // Normal lines: half the mean edge length, at most a tenth of the radius.
    let length = if edges > 0 { 0.5 * edge_sum / edges as f64 } else { 0.05 * radius }.min(0.1 * radius);
    let lines = &mut scratch.lines;
    lines.clear();
    for (p, nv) in mesh.positions.iter().zip(normals.iter()) {
        if p.is_finite() && *nv != Vec3::ZERO {
            push_vec3(lines, (*p - origin).as_vec3());
            push_vec3(lines, (*p - origin + length * nv.as_dvec3()).as_vec3());
        }
    }

    (origin, radius, colours)
}

/// none), and the largest distance of one from it: the bounding sphere the view frames.
#[must_use]
pub fn bounds(mesh: &TriMesh) -> (DVec3, f64) {
    point_bounds(|| mesh.positions.iter().copied())
}

/// [`bounds`] of the points `points()` gives (called twice: box, then sphere).
pub fn point_bounds<I: Iterator<Item = DVec3>>(points: impl Fn() -> I) -> (DVec3, f64) {
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    for p in points().filter(|p| p.is_finite()) {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let origin = if lo.x <= hi.x { 0.5 * (lo + hi) } else { DVec3::ZERO };
    // Bounding sphere about the box centre, tighter than the box's.
    let radius = points().filter(|p| p.is_finite()).map(|p| p.distance_squared(origin)).fold(0.0, f64::max).sqrt();
    (origin, radius)
}

fn push_vec3(out: &mut Vec<u8>, v: Vec3) {
    for x in v.to_array() {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// Pushes the linear RGB of `c` and then `w`.
fn push_colour(out: &mut Vec<u8>, c: Color32, w: f32) {
    let rgba = egui::Rgba::from(c);
    for x in [rgba.r(), rgba.g(), rgba.b(), w] {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// The GPU side: pipelines, buffers and the render target.
struct Gpu {
    state: egui_wgpu::RenderState,
    shader: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    pipelines: Option<Pipelines>,
    surface: Option<wgpu::Buffer>,
    lines: Option<wgpu::Buffer>,
    uploaded: Option<u64>,
    target: Option<Target>,
    /// Sample count used with `msaa` (1 if the adapter cannot do 4).
    msaa_samples: u32,
}

struct Pipelines {
    samples: u32,
    surface: wgpu::RenderPipeline,
    lines: wgpu::RenderPipeline,
}

struct Target {
    size: [u32; 2],
    samples: u32,
    /// Single-sampled, shown by egui.
    colour: wgpu::TextureView,
    /// Multisampled, resolved into `colour`.
    msaa: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
    texture_id: egui::TextureId,
}

impl Gpu {
    fn new(state: &egui_wgpu::RenderState) -> Self {
        let device = &state.device;
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("view3d shader"),
            source: wgpu::ShaderSource::Wgsl(include_str!("view3d.wgsl").into()),
        });
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("view3d uniforms"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(UNIFORM_SIZE),
                },
                count: None,
            }],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("view3d"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view3d uniforms"),
            size: UNIFORM_SIZE,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("view3d uniforms"),
            layout: &bind_group_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() }],
        });
        let can_msaa = |format| state.adapter.get_texture_format_features(format).flags.sample_count_supported(4);
        let msaa_samples = if can_msaa(COLOUR_FORMAT) && can_msaa(DEPTH_FORMAT) { 4 } else { 1 };
        Self {
            state: state.clone(),
            shader,
            layout,
            uniforms,
            bind_group,
            pipelines: None,
            surface: None,
            lines: None,
            uploaded: None,
            target: None,
            msaa_samples,
        }
    }

    fn pipelines(&mut self, samples: u32) -> &Pipelines {
        if self.pipelines.as_ref().is_none_or(|p| p.samples != samples) {
            self.pipelines = Some(Pipelines {
                samples,
                surface: self.pipeline(samples, true),
                lines: self.pipeline(samples, false),
            });
        }
        self.pipelines.as_ref().unwrap()
    }

    fn pipeline(&self, samples: u32, surface: bool) -> wgpu::RenderPipeline {
        let surface_attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Unorm8x4];
        let line_attributes = wgpu::vertex_attr_array![0 => Float32x3];
        let (stride, attributes, topology, vs, fs) = if surface {
            (SURFACE_STRIDE, &surface_attributes[..], wgpu::PrimitiveTopology::TriangleList, "vs_surface", "fs_surface")
        } else {
            (LINE_STRIDE, &line_attributes[..], wgpu::PrimitiveTopology::LineList, "vs_line", "fs_line")
        };
        self.state.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(if surface { "view3d surface" } else { "view3d normals" }),
            layout: Some(&self.layout),
            vertex: wgpu::VertexState {
                module: &self.shader,
                entry_point: Some(vs),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: stride,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes,
                })],
            },
            primitive: wgpu::PrimitiveState { topology, cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(if surface {
                    wgpu::CompareFunction::Less
                } else {
                    wgpu::CompareFunction::LessEqual
                }),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState { count: samples, mask: !0, alpha_to_coverage_enabled: false },
            fragment: Some(wgpu::FragmentState {
                module: &self.shader,
                entry_point: Some(fs),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: COLOUR_FORMAT,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        })
    }

    /// (Re)creates the render target when the size or sample count changed.
    fn target(&mut self, size: [u32; 2], samples: u32) {
        if self.target.as_ref().is_some_and(|t| t.size == size && t.samples == samples) {
            return;
        }
        let device = &self.state.device;
        let texture = |label, format, samples, usage| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&wgpu::TextureViewDescriptor::default())
        };
        let colour = texture(
            "view3d colour",
            COLOUR_FORMAT,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let msaa = (samples > 1)
            .then(|| texture("view3d colour (msaa)", COLOUR_FORMAT, samples, wgpu::TextureUsages::RENDER_ATTACHMENT));
        let depth = texture("view3d depth", DEPTH_FORMAT, samples, wgpu::TextureUsages::RENDER_ATTACHMENT);
        let mut renderer = self.state.renderer.write();
        let texture_id = match &self.target {
            Some(old) => {
                renderer.update_egui_texture_from_wgpu_texture(
                    device,
                    &colour,
                    wgpu::FilterMode::Linear,
                    old.texture_id,
                );
                old.texture_id
            }
            None => renderer.register_native_texture(device, &colour, wgpu::FilterMode::Linear),
        };
        self.target = Some(Target { size, samples, colour, msaa, depth, texture_id });
    }

    fn render(&mut self, data: &MeshData, camera: &Camera, settings: &View3dSettings, size: [u32; 2]) {
        let samples = if settings.msaa { self.msaa_samples } else { 1 };
        self.target(size, samples);
        self.pipelines(samples);

        // Upload the mesh, into the existing buffers when they are large enough. A mesh too
        // large for one buffer is cut short rather than failing.
        let max_buffer = self.state.device.limits().max_buffer_size;
        let surface_len = clamp_len(data.surface.len(), 3 * SURFACE_STRIDE, max_buffer);
        let lines_len = clamp_len(data.lines.len(), 2 * LINE_STRIDE, max_buffer);
        if self.uploaded != Some(data.generation) {
            upload(&self.state, &mut self.surface, &data.surface[..surface_len], "view3d surface");
            upload(&self.state, &mut self.lines, &data.lines[..lines_len], "view3d normals");
            self.uploaded = Some(data.generation);
        }

        // Uniforms.
        let (centre, radius) = data.centre_radius();
        let eye = camera.eye();
        let reach = 1.2 * radius;
        let to_centre = (eye - centre).length();
        let far = (to_centre + reach).max(1e-9);
        let near = (to_centre - reach).max(far * 1e-4);
        let aspect = f64::from(size[0]) / f64::from(size[1]);
        let view_proj = camera.view_proj(data.origin, aspect, near, far).as_mat4();
        let (right, up) = camera.right_up();
        let light = (-0.45 * right + 0.65 * up + camera.back()).normalize();
        let mut u = Vec::with_capacity(UNIFORM_SIZE as usize);
        for x in view_proj.to_cols_array() {
            u.extend_from_slice(&x.to_le_bytes());
        }
        push_vec3(&mut u, (eye - data.origin).as_vec3());
        u.extend_from_slice(&1f32.to_le_bytes());
        push_vec3(&mut u, light.as_vec3());
        u.extend_from_slice(&0f32.to_le_bytes());
        push_colour(&mut u, FRONT_COLOUR, 1.0);
        push_colour(&mut u, BACK_COLOUR, 1.0);
        push_colour(&mut u, WIRE_COLOUR, 0.5 * WIRE_WIDTH_PX);
        push_colour(&mut u, NORMAL_COLOUR, 1.0);
        let flag = |b: bool| if b { 1f32 } else { 0f32 };
        for x in [
            flag(settings.wireframe),
            flag(settings.smooth),
            flag(settings.show_backfaces_colour),
            match (data.has_colours, settings.checker, settings.vertex_colours) {
                (true, true, _) => 2.0,
                (true, false, true) => 1.0,
                _ => 0.0,
            },
        ] {
            u.extend_from_slice(&x.to_le_bytes());
        }
        debug_assert_eq!(u.len() as u64, UNIFORM_SIZE);
        self.state.queue.write_buffer(&self.uniforms, 0, &u);

        let (Some(target), Some(pipelines)) = (&self.target, &self.pipelines) else { return };
        // Transparent (premultiplied) where nothing is drawn: egui paints the background,
        // the grid and the axes under the image.
        let clear = wgpu::Color::TRANSPARENT;
        let mut encoder =
            self.state.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("view3d") });
        {
            let (view, resolve_target, store) = match &target.msaa {
                Some(msaa) => (msaa, Some(&target.colour), wgpu::StoreOp::Discard),
                None => (&target.colour, None, wgpu::StoreOp::Store),
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("view3d"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &target.depth,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_bind_group(0, &self.bind_group, &[]);
            if let Some(buffer) = &self.surface
                && surface_len > 0
                && settings.surface
            {
                pass.set_pipeline(&pipelines.surface);
                pass.set_vertex_buffer(0, buffer.slice(..surface_len as u64));
                pass.draw(0..(surface_len as u64 / SURFACE_STRIDE) as u32, 0..1);
            }
            if settings.normals
                && let Some(buffer) = &self.lines
                && lines_len > 0
            {
                pass.set_pipeline(&pipelines.lines);
                pass.set_vertex_buffer(0, buffer.slice(..lines_len as u64));
                pass.draw(0..(lines_len as u64 / LINE_STRIDE) as u32, 0..1);
            }
        }
        self.state.queue.submit(Some(encoder.finish()));
    }
}

/// The part of the segment `ab` inside `rect`, or `None` (the renderer's clip, in f64).
fn clip_segment(a: egui::Pos2, b: egui::Pos2, rect: Rect) -> Option<[egui::Pos2; 2]> {
    let f = |p: egui::Pos2| [f64::from(p.x), f64::from(p.y)];
    let (p, q) = splinekit_render::plot::clip_segment(f(a), f(b), f(rect.min), f(rect.max))?;
    let back = |p: [f64; 2]| pos2(p[0] as f32, p[1] as f32);
    Some([back(p), back(q)])
}

/// `len` cut down to a multiple of `unit` bytes that fits in `max` bytes.
fn clamp_len(len: usize, unit: u64, max: u64) -> usize {
    let len = (len as u64).min(max);
    (len - len % unit) as usize
}

/// Writes `bytes` to the buffer in `slot`, replacing it with a larger one if needed.
fn upload(state: &egui_wgpu::RenderState, slot: &mut Option<wgpu::Buffer>, bytes: &[u8], label: &str) {
    if bytes.is_empty() {
        return;
    }
    let needed = bytes.len() as u64;
    if slot.as_ref().is_none_or(|b| b.size() < needed) {
        let max = state.device.limits().max_buffer_size;
        let size = (needed + needed / 2).next_multiple_of(256).min(max).max(needed);
        *slot = Some(state.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
    }
    if let Some(buffer) = slot {
        state.queue.write_buffer(buffer, 0, bytes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guides_cover_the_scene_in_whole_steps() {
        let g = Guides::new(DVec3::new(2.0, 1.0, 0.5), 2.2);
        // a fifth of the radius, 0.44, up to 1, 2 or 5 times a power of ten
        assert!((g.step - 0.5).abs() < 1e-15, "{}", g.step);
        // 1.2 · (|c| + r) = 1.2 · (2.291… + 2.2) = 5.39…, up to a whole step
        assert!((g.axis_length - 5.5).abs() < 1e-12, "{}", g.axis_length);
        // x from −0.5 to 4.5 and y from −1.5 to 3.5: 11 lines each way, in the xy plane
        assert_eq!(g.grid.len(), 22);
        let (first, last) = (g.grid[0], g.grid[10]);
        assert!((first[0] - DVec3::new(-0.5, -1.5, 0.0)).length() < 1e-12, "{first:?}");
        assert!((last[1] - DVec3::new(4.5, 3.5, 0.0)).length() < 1e-12, "{last:?}");
        assert!(g.grid.iter().flatten().all(|p| p.z == 0.0));
        // lines at whole multiples of the step
        for [a, b] in &g.grid {
            let k = if a.x == b.x { a.x / g.step } else { a.y / g.step };
            assert!((k - k.round()).abs() < 1e-9, "{a} {b}");
        }
    }

    #[test]
    fn guides_of_degenerate_scenes_are_finite_and_few() {
        for (centre, radius) in [
            (DVec3::ZERO, 0.0),
            (DVec3::NAN, f64::NAN),
            (DVec3::splat(1e12), 1e-6),
            (DVec3::ZERO, f64::INFINITY),
            (DVec3::splat(1e300), 1e300),
            (DVec3::ZERO, 1e-300),
        ] {
            let g = Guides::new(centre, radius);
            assert!(g.step > 0.0 && g.step.is_finite() && g.axis_length.is_finite(), "{centre} {radius}: {g:?}");
            assert!(g.grid.len() <= 2 * (MAX_GRID_LINES as usize + 1), "{centre} {radius}: {}", g.grid.len());
            assert!(g.grid.iter().flatten().all(|p| p.is_finite()));
        }
    }

    #[test]
    fn segments_are_cut_at_the_near_plane_and_the_rect() {
        let camera = Camera { target: DVec3::ZERO, yaw: 0.0, pitch: 0.0, distance: 4.0, ..Camera::default() };
        let rect = Rect::from_min_size(pos2(0.0, 0.0), Vec2::new(200.0, 100.0));
        // along x through the target: on the horizontal through the centre
        let [a, b] = camera.project_segment(DVec3::new(-1.0, 0.0, 0.0), DVec3::X, rect).unwrap();
        assert!((a.y - 50.0).abs() < 1e-4 && (b.y - 50.0).abs() < 1e-4 && a.x < 100.0 && b.x > 100.0);
        // from the target to behind the eye (the eye is at z = 4): cut, not dropped
        let [a, b] = camera.project_segment(DVec3::ZERO, DVec3::new(1.0, 0.0, 8.0), rect).unwrap();
        assert_eq!(a, pos2(100.0, 50.0));
        assert!(b.x.is_finite() && b.x > 100.0);
        // all behind
        assert!(camera.project_segment(DVec3::new(0.0, 0.0, 5.0), DVec3::new(1.0, 0.0, 9.0), rect).is_none());
        assert!(camera.project_segment(DVec3::NAN, DVec3::ZERO, rect).is_none());

        let [a, b] = clip_segment(pos2(100.0, 50.0), pos2(300.0, 150.0), rect).unwrap();
        assert_eq!((a, b), (pos2(100.0, 50.0), pos2(200.0, 100.0)));
        assert!(clip_segment(pos2(-10.0, -10.0), pos2(-1.0, 300.0), rect).is_none());
    }
}
