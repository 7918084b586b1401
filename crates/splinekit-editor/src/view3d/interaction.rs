//! Input in the 3D view: handles dragged in the plane parallel to the screen
//! ([`HandleDrag`]), and the camera's orbit, pan and zoom from the pointer.

use eframe::egui::{self, Color32, PointerButton, Rect, Sense, Vec2};
use glam::DVec3;

use super::{View3d, ZOOM_PER_POINT};

/// A handle being dragged in the view ([`View3d::ui_with_handles`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandleDrag {
    /// Which handle.
    pub index: usize,
    /// Where it is now: its position when the drag started, moved in the plane parallel to
    /// the screen by the whole drag ([`Camera::drag_in_view_plane`](super::Camera::drag_in_view_plane)).
    pub position: DVec3,
    /// The first frame of the drag (one undo step per drag starts here).
    pub started: bool,
}

/// The handle drag under way: which handle and where it was when the drag started.
#[derive(Clone, Copy, Debug)]
pub(super) struct ActiveDrag {
    index: usize,
    start: DVec3,
    /// Where the button went down.
    origin: egui::Pos2,
    /// Whether the handle has moved (the first move starts the undo step).
    moved: bool,
}

/// Radius of a handle's dot, and of the area that grabs it, in points.
pub const HANDLE_RADIUS: f32 = 5.0;
/// The polyline of [`View3d::ui_with_handles`].
pub const POLYLINE_COLOUR: Color32 = Color32::from_rgb(250, 170, 40);
/// Handle dots (the selected / dragged one in [`HANDLE_ACTIVE_COLOUR`]).
pub const HANDLE_COLOUR: Color32 = Color32::from_rgb(250, 210, 60);
/// The handle being dragged.
pub const HANDLE_ACTIVE_COLOUR: Color32 = Color32::from_rgb(255, 255, 255);

impl View3d {
    /// The handle widgets over `rect` (labelled for accessibility), and the handle drags
    /// from the frame's pointer events in order: a primary press within the grab radius of
    /// a handle picks it (where the button went down, so a drag that leaves the handle within
    /// one frame still moves it), each move puts it under the pointer, the release ends the
    /// drag. Returns the drag's position this frame, and each visible handle's dot and
    /// whether it is the one dragged.
    pub(super) fn handles(
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

    pub(super) fn handle_input(&mut self, ui: &egui::Ui, response: &egui::Response, rect: Rect) {
        let (_, radius) = self.data.centre_radius();
        let (min, max) = (1e-4 * radius, 1e4 * radius);
        // A drag that picked a handle moves the handle, not the camera. The camera follows
        // the frame's pointer events, as the handles do, so that a press, moves and release
        // arriving in one frame (a fast flick, a slow frame) still orbit or pan.
        let handle_drag = self.drag.is_some() || std::mem::take(&mut self.dragged_this_frame);
        let layer = ui.layer_id();
        let shift = ui.input(|i| i.modifiers.shift);
        for event in ui.input(|i| i.events.clone()) {
            match event {
                egui::Event::PointerButton { pos, button, pressed: true, .. }
                    if self.camera_drag.is_none()
                        && !(button == PointerButton::Primary && handle_drag)
                        && rect.contains(pos)
                        && ui.ctx().layer_id_at(pos).is_none_or(|l| l == layer) =>
                {
                    self.camera_drag = Some((button, pos));
                }
                egui::Event::PointerMoved(pos) => {
                    if let Some((button, last)) = self.camera_drag {
                        let delta = pos - last;
                        match button {
                            PointerButton::Primary if !shift => self.camera.orbit(delta),
                            PointerButton::Primary | PointerButton::Secondary | PointerButton::Middle => {
                                self.camera.pan(delta, rect.height())
                            }
                            _ => {}
                        }
                        self.camera_drag = Some((button, pos));
                    }
                }
                egui::Event::PointerButton { button, pressed: false, .. }
                    if self.camera_drag.is_some_and(|(b, _)| b == button) =>
                {
                    self.camera_drag = None;
                }
                egui::Event::PointerGone => self.camera_drag = None,
                _ => {}
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
