//! The 2D curve view: draws the active curve and edits its points.
//!
//! Screen and model are linked by a plane (xy, yz or zx) and a similarity: a model point `p`
//! in plane coordinates `q` appears at `centre_of_view + (q − center)·scale`, y up. Every
//! control point is a widget labelled `P0`, `P1`, … (for accessibility and tests).

use eframe::egui::{self, Color32, Pos2, Rect, Sense, Shape, Stroke, Vec2, WidgetInfo};
use glam::{DVec2, DVec3};
use splinekit::arclen::ArclenIndex;
use splinekit::flatten::{Tessellation, flatten_at_most};
use splinekit::frame::{self, Frame, FrameMethod, FrameOptions, Side};
use splinekit::{AnyCurve, ParamCurve};

use crate::doc::Document;

/// Radius (points) within which a click or drag picks a control point or a polygon edge.
pub const PICK_RADIUS: f32 = 7.0;

/// The most points a curve is drawn with in the 2D view (finer curves, such as a helix of
/// thousands of turns, are drawn with equal steps instead of to the pixel tolerance).
pub const MAX_DRAWN: usize = 200_000;

/// A press and release closer than this (points) are a click; farther apart, a drag.
pub const CLICK_DISTANCE: f32 = 6.0;

/// Colours of consecutive curve segments.
pub const SEGMENT_COLORS: [Color32; 6] = [
    Color32::from_rgb(230, 90, 60),
    Color32::from_rgb(60, 170, 90),
    Color32::from_rgb(70, 120, 230),
    Color32::from_rgb(210, 160, 40),
    Color32::from_rgb(170, 80, 200),
    Color32::from_rgb(40, 180, 190),
];

/// The plane in which a 3D curve is edited.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plane {
    /// x right, y up.
    Xy,
    /// y right, z up.
    Yz,
    /// z right, x up.
    Zx,
}

impl Plane {
    /// The point's coordinates in the plane.
    #[must_use]
    pub fn project(self, p: DVec3) -> DVec2 {
        match self {
            Self::Xy => DVec2::new(p.x, p.y),
            Self::Yz => DVec2::new(p.y, p.z),
            Self::Zx => DVec2::new(p.z, p.x),
        }
    }

    /// `p` with its two in-plane coordinates replaced by `q` (the third kept).
    #[must_use]
    pub fn replace(self, p: DVec3, q: DVec2) -> DVec3 {
        match self {
            Self::Xy => DVec3::new(q.x, q.y, p.z),
            Self::Yz => DVec3::new(p.x, q.x, q.y),
            Self::Zx => DVec3::new(q.y, p.y, q.x),
        }
    }

    /// The name shown in the plane switch.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Xy => "xy",
            Self::Yz => "yz",
            Self::Zx => "zx",
        }
    }

    /// The names of the plane's horizontal and vertical axes.
    #[must_use]
    pub fn axes(self) -> (&'static str, &'static str) {
        match self {
            Self::Xy => ("x", "y"),
            Self::Yz => ("y", "z"),
            Self::Zx => ("z", "x"),
        }
    }
}

/// What the view shows (the toggles of the side panel and the keyboard).
#[derive(Clone, Debug, PartialEq)]
pub struct Show {
    /// The control polygon (`l`).
    pub polygon: bool,
    /// Markers equally spaced by arc length (`a`).
    pub markers: bool,
    /// Spacing of the markers, in model units.
    pub marker_spacing: f64,
    /// Tangents and normals (`n`): T blue, N red (and B green in the 3D view).
    pub normals: bool,
    /// Which side of the direction of travel N points to on 2D curves, in the 2D and 3D
    /// views ([`Self::frame_options`]): [`Side::Left`] `N = (−T.y, T.x)` (the default, the
    /// course software's sequential frames) or [`Side::Right`] `N = (T.y, −T.x)` (a
    /// counter-clockwise loop then has outward normals). B follows (`+z` or `−z`).
    pub normal_side: Side,
    /// Every curve of the document, not only the active one (2D and 3D views).
    pub curves: bool,
    /// Whole frames: T, N, B in blue, red, green.
    pub frames: bool,
    /// The curvature comb.
    pub comb: bool,
    /// Length of a comb tooth per unit of curvature, in model units.
    pub comb_scale: f64,
}

impl Default for Show {
    fn default() -> Self {
        Self {
            polygon: true,
            markers: false,
            marker_spacing: 0.1,
            normals: false,
            normal_side: Side::Left,
            curves: true,
            frames: false,
            comb: false,
            comb_scale: 0.05,
        }
    }
}

impl Show {
    /// The frames drawn along a curve (`Draw normals`, `Frames`): the sequential method,
    /// with N on [`Self::normal_side`] of travel for a 2D curve (`planar`), on the left (the
    /// method's default) for a 3D one, where left and right of travel mean nothing.
    #[must_use]
    pub fn frame_options(&self, planar: bool) -> FrameOptions {
        let side = if planar { self.normal_side } else { Side::Left };
        FrameOptions::DEFAULT.with_method(FrameMethod::Sequential(side))
    }

    /// Two selectable labels, `Normals left` and `Normals right`, for [`Self::normal_side`].
    pub fn normal_side_ui(&mut self, ui: &mut egui::Ui) {
        ui.selectable_value(&mut self.normal_side, Side::Left, "Normals left")
            .on_hover_text("2D curves: N = (−T.y, T.x), left of the direction of travel");
        ui.selectable_value(&mut self.normal_side, Side::Right, "Normals right")
            .on_hover_text("2D curves: N = (T.y, −T.x), right of travel (outward on a counter-clockwise loop)");
    }
}

/// Where the views draw frame arrows along `c`: 8 per segment, evenly in the parameter from
/// start to end, each point of the curve with its frame by `options` (e.g.
/// [`Show::frame_options`]). The normal arrows go from `p` to `p + length·frame.n`.
#[must_use]
pub fn frame_arrows(c: &AnyCurve<DVec3>, options: &FrameOptions) -> Vec<(DVec3, Frame)> {
    let segments = c.num_segments().max(1);
    let n = segments * 8;
    let us: Vec<f64> = (0..=n).map(|i| segments as f64 * i as f64 / n as f64).collect();
    let frames = frame::frames(c, &us, options);
    us.iter().zip(frames).map(|(&u, f)| (c.eval(u), f)).collect()
}

/// An ongoing drag of a control point.
#[derive(Clone, Copy, Debug)]
struct Drag {
    index: usize,
    start_model: DVec2,
    start_pointer: Pos2,
    /// Whether the point has moved (the undo step is recorded at the first move, so a click
    /// records none).
    moved: bool,
}

/// The state of the 2D view.
#[derive(Clone, Debug)]
pub struct View2d {
    /// The editing plane (2D curves always use xy).
    pub plane: Plane,
    /// The model point (plane coordinates) at the centre of the view.
    pub center: DVec2,
    /// Screen points per model unit.
    pub scale: f64,
    /// What is drawn.
    pub show: Show,
    /// The selected control point.
    pub selected: Option<usize>,
    /// Fit the view to the curve at the next frame.
    pub fit_pending: bool,
    drag: Option<Drag>,
    /// Whether a point drag ended in this frame (the background then neither pans nor
    /// takes the release as a click).
    dragged_this_frame: bool,
    /// The other curves drawn last frame (their index and screen polyline), for picking.
    others: Vec<(usize, Vec<Pos2>)>,
    /// A primary press on the background not yet released: where, and its modifiers.
    press: Option<(Pos2, egui::Modifiers)>,
    /// The pointer's plane coordinates when it is over the view (the readout).
    pub pointer: Option<DVec2>,
    /// Where the view was last drawn (screen points).
    pub rect: Rect,
}

impl Default for View2d {
    fn default() -> Self {
        Self {
            plane: Plane::Xy,
            center: DVec2::ZERO,
            scale: 100.0,
            show: Show::default(),
            selected: None,
            fit_pending: true,
            drag: None,
            dragged_this_frame: false,
            others: Vec::new(),
            press: None,
            pointer: None,
            rect: Rect::from_min_size(Pos2::ZERO, Vec2::splat(1.0)),
        }
    }
}

impl View2d {
    /// Screen position of plane coordinates `q`.
    #[must_use]
    pub fn to_screen(&self, q: DVec2) -> Pos2 {
        let c = self.rect.center();
        let d = (q - self.center) * self.scale;
        Pos2::new(c.x + d.x as f32, c.y - d.y as f32)
    }

    /// Plane coordinates of screen position `s`.
    #[must_use]
    pub fn to_model(&self, s: Pos2) -> DVec2 {
        let c = self.rect.center();
        self.center + DVec2::new(f64::from(s.x - c.x), -f64::from(s.y - c.y)) / self.scale
    }

    /// The plane used for `doc`'s active curve.
    fn plane_for(&self, doc: &Document) -> Plane {
        if doc.is_2d() { Plane::Xy } else { self.plane }
    }

    /// Frames the active curve's points and curve, and the other curves when they are drawn
    /// (with a margin), but for curves that only shape a sweep (a scale or twist curve lives
    /// in its own units: a twist of 360° would shrink the scene to a dot).
    pub fn fit(&mut self, doc: &Document) {
        let plane = self.plane_for(doc);
        let mut pts: Vec<DVec2> = doc.points().iter().map(|&p| plane.project(p)).collect();
        let shapes = shape_only_curves(&doc.swp);
        // the active curve, and the others when they are drawn: the whole scene
        let curves = doc
            .swp
            .curves
            .iter()
            .enumerate()
            .filter(|(i, _)| *i == doc.active || (self.show.curves && !shapes[*i]))
            .filter_map(|(_, c)| c.to_curve().ok());
        for c in curves {
            let n = c.num_segments().max(1) * 16;
            pts.extend((0..=n).map(|i| plane.project(c.eval(c.num_segments() as f64 * i as f64 / n as f64))));
        }
        if pts.is_empty() {
            self.center = DVec2::ZERO;
            self.scale = f64::from(self.rect.width().min(self.rect.height())) / 4.0;
            return;
        }
        let (lo, hi) = pts.iter().fold((pts[0], pts[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let size = (hi - lo).max(DVec2::splat(1e-9));
        self.center = (lo + hi) / 2.0;
        let fit = (f64::from(self.rect.width()) / size.x).min(f64::from(self.rect.height()) / size.y) * 0.8;
        self.scale = if fit.is_finite() && fit > 0.0 { fit.min(1e9) } else { 100.0 };
    }

    /// Draws the view into the remaining space of `ui` and applies the user's edits to `doc`.
    pub fn ui(&mut self, ui: &mut egui::Ui, doc: &mut Document) -> egui::Response {
        let (rect, background) = ui.allocate_exact_size(ui.available_size(), Sense::click_and_drag());
        // a resized view (window, divider, a panel shown or hidden) frames the curve again
        if rect.size() != self.rect.size() && self.rect.width() > 1.0 {
            self.fit_pending = true;
        }
        self.rect = rect;
        if self.fit_pending && rect.width() > 1.0 && rect.height() > 1.0 {
            self.fit(doc);
            self.fit_pending = false;
        }
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 0.0, Color32::from_gray(250));
        self.pointer = ui.input(|i| i.pointer.hover_pos()).filter(|p| rect.contains(*p)).map(|p| self.to_model(p));
        self.draw_axes(&painter, doc);
        let plane = self.plane_for(doc);
        // the other curves, dimmed; a click on one makes it the active curve
        self.others.clear();
        if self.show.curves {
            for (i, c) in doc.swp.curves.iter().enumerate() {
                if i == doc.active {
                    continue;
                }
                let Ok(c) = c.to_curve() else { continue };
                let params = flatten_at_most(&c, Tessellation::Distance { tolerance: 0.5 / self.scale }, MAX_DRAWN);
                let line: Vec<Pos2> = params.iter().map(|&u| self.to_screen(plane.project(c.eval(u)))).collect();
                painter.add(Shape::line(line.clone(), Stroke::new(1.5, Color32::from_gray(175))));
                self.others.push((i, line));
            }
        }
        let curve = doc.spline().ok();
        if let Some(c) = &curve {
            self.draw_curve(&painter, c, plane, &self.show.frame_options(doc.is_2d()));
        }
        let points: Vec<Pos2> = doc.points().iter().map(|&p| self.to_screen(plane.project(p))).collect();
        if self.show.polygon && points.len() > 1 {
            let closed = doc.curve().is_some_and(|c| c.closed);
            let mut line = points.clone();
            if closed {
                line.push(points[0]);
            }
            painter.add(Shape::dashed_line(&line, Stroke::new(1.0, Color32::from_gray(140)), 6.0, 4.0));
        }

        // control points: widgets on top of the background (labelled P0, P1, … for
        // accessibility), clicked to select, right-clicked for their menu
        let id = ui.scope_id().with("control points").with(doc.active);
        let mut delete = None;
        for (i, &pos) in points.iter().enumerate() {
            let r = Rect::from_center_size(pos, Vec2::splat(2.0 * PICK_RADIUS));
            let response = ui.interact(r, id.with(i), Sense::click());
            response.widget_info(|| WidgetInfo::labeled(egui::Role::Button, true, format!("P{i}")));
            if response.clicked() {
                self.selected = Some(i);
            }
            response.context_menu(|ui| {
                if ui.button("Delete point").clicked() {
                    delete = Some(i);
                    ui.close();
                }
            });
        }
        // drags of control points, from the frame's pointer events in order: a point is picked
        // where the button went down, so a drag that leaves the point within one frame still
        // moves it, and a press, moves and release in one slow frame all count
        let dragging_before = self.drag.is_some();
        self.drag_points(ui, doc, plane, &points, rect);
        let points: Vec<Pos2> = doc.points().iter().map(|&p| self.to_screen(plane.project(p))).collect();
        for (i, &pos) in points.iter().enumerate() {
            let selected = self.selected == Some(i);
            let fill = if selected { Color32::from_rgb(255, 200, 0) } else { Color32::WHITE };
            painter.circle(pos, 5.0, fill, Stroke::new(1.5, Color32::BLACK));
        }
        self.draw_labels(&painter, &points);
        if let Some(i) = delete {
            doc.delete_point(i);
            self.selected = None;
        }
        let point_drag = dragging_before || self.drag.is_some() || self.dragged_this_frame;

        // the background: shift-click adds, a click on a polygon edge inserts (a click on
        // another curve makes it active), drag pans, scroll zooms about the pointer. Clicks
        // are read from the frame's events with their own modifiers, so every click of a slow
        // frame counts, and a Shift released within the frame still counts for its click.
        let layer = ui.layer_id();
        for event in ui.input(|i| i.events.clone()) {
            match event {
                egui::Event::PointerButton { pos, button: egui::PointerButton::Primary, pressed: true, modifiers }
                    if rect.contains(pos) && ui.ctx().layer_id_at(pos).is_none_or(|l| l == layer) =>
                {
                    // a press that picked a control point starts a drag, not a click
                    let on_point = !modifiers.shift
                        && doc.points().iter().any(|&p| self.to_screen(plane.project(p)).distance(pos) <= PICK_RADIUS);
                    self.press = (!on_point).then_some((pos, modifiers));
                }
                egui::Event::PointerButton { pos, button: egui::PointerButton::Primary, pressed: false, .. } => {
                    if let Some((at, modifiers)) = self.press.take()
                        && at.distance(pos) < CLICK_DISTANCE
                    {
                        self.click(doc, plane, at, modifiers.shift);
                    }
                }
                egui::Event::PointerGone => self.press = None,
                _ => {}
            }
        }
        if background.dragged() && !point_drag {
            let d = background.drag_delta();
            self.center -= DVec2::new(f64::from(d.x), -f64::from(d.y)) / self.scale;
        }
        if background.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y + (i.zoom_delta() - 1.0) * 200.0);
            if scroll != 0.0
                && let Some(pointer) = ui.input(|i| i.pointer.hover_pos())
            {
                let before = self.to_model(pointer);
                self.scale = (self.scale * (f64::from(scroll) / 200.0).exp()).clamp(1e-6, 1e12);
                let after = self.to_model(pointer);
                self.center += before - after;
            }
        }
        background
    }

    /// A click on the background at `pointer`: with Shift, a new point at the end of the
    /// curve; on the control polygon, a point inserted there; on another curve, that curve
    /// made active; elsewhere, no selection.
    fn click(&mut self, doc: &mut Document, plane: Plane, pointer: Pos2, shift: bool) {
        let points: Vec<Pos2> = doc.points().iter().map(|&p| self.to_screen(plane.project(p))).collect();
        let base = doc.points().last().copied().unwrap_or(DVec3::ZERO);
        let model = plane.replace(base, self.to_model(pointer));
        if shift {
            doc.add_point(model);
            self.selected = Some(doc.points().len() - 1);
        } else if let Some(edge) = self.edge_near(doc, &points, pointer) {
            let (a, b) = (doc.points()[edge], doc.points()[(edge + 1) % points.len()]);
            // the third coordinate: interpolated along the edge
            let t = closest_param(points[edge], points[(edge + 1) % points.len()], pointer);
            let p = plane.replace(a.lerp(b, t), self.to_model(pointer));
            self.selected = Some(doc.insert_on_polygon(edge, t, p));
        } else if let Some(i) = self.curve_near(pointer) {
            doc.select_curve(i);
            self.selected = None;
        } else if !points.iter().any(|p| p.distance(pointer) <= PICK_RADIUS) {
            self.selected = None;
        }
    }

    /// The other curve (not the active one) drawn within [`PICK_RADIUS`] of `pointer`.
    fn curve_near(&self, pointer: Pos2) -> Option<usize> {
        self.others
            .iter()
            .filter_map(|(i, line)| {
                let d = line
                    .windows(2)
                    .map(|w| {
                        let t = closest_param(w[0], w[1], pointer);
                        (w[0] + (w[1] - w[0]) * t as f32).distance(pointer)
                    })
                    .fold(f32::INFINITY, f32::min);
                (d <= PICK_RADIUS).then_some((*i, d))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }

    /// How many other curves (not the active one) the last frame drew, dimmed.
    #[must_use]
    pub fn other_curves_drawn(&self) -> usize {
        self.others.len()
    }

    /// Whether a control point is being dragged.
    #[must_use]
    pub fn is_dragging(&self) -> bool {
        self.drag.is_some()
    }

    /// Moves control points by the frame's pointer events: a primary press within
    /// [`PICK_RADIUS`] of a point (the nearest; none under a dialog or another window) picks
    /// it, every pointer move puts it under the pointer by the offset since the press, and
    /// the release ends the drag. One undo step per drag that moved.
    fn drag_points(&mut self, ui: &egui::Ui, doc: &mut Document, plane: Plane, points: &[Pos2], rect: Rect) {
        self.dragged_this_frame = false;
        let layer = ui.layer_id();
        let events = ui.input(|i| i.events.clone());
        for event in events {
            match event {
                egui::Event::PointerButton { pos, button: egui::PointerButton::Primary, pressed: true, modifiers }
                    if self.drag.is_none() && rect.contains(pos) && !modifiers.shift =>
                {
                    // only where this view is on top (not under a window or a dialog)
                    if ui.ctx().layer_id_at(pos).is_some_and(|l| l != layer) {
                        continue;
                    }
                    let nearest = points
                        .iter()
                        .enumerate()
                        .map(|(i, p)| (i, p.distance(pos)))
                        .filter(|&(_, d)| d <= PICK_RADIUS)
                        .min_by(|a, b| a.1.total_cmp(&b.1));
                    if let Some((i, _)) = nearest {
                        let start_model = plane.project(doc.points()[i]);
                        self.drag = Some(Drag { index: i, start_model, start_pointer: pos, moved: false });
                        self.selected = Some(i);
                    }
                }
                egui::Event::PointerMoved(pos) => self.drag_to(doc, plane, pos),
                egui::Event::PointerButton { pos, button: egui::PointerButton::Primary, pressed: false, .. }
                    if self.drag.is_some() =>
                {
                    self.drag_to(doc, plane, pos);
                    self.drag = None;
                    self.dragged_this_frame = true;
                }
                egui::Event::PointerGone => self.drag = None,
                _ => {}
            }
        }
        if self.drag.is_some() {
            self.dragged_this_frame = true;
        }
    }

    /// Puts the dragged point under `pointer` (by the offset since the press).
    fn drag_to(&mut self, doc: &mut Document, plane: Plane, pointer: Pos2) {
        let Some(drag) = &mut self.drag else { return };
        let Some(&current) = doc.points().get(drag.index) else {
            self.drag = None;
            return;
        };
        if pointer == drag.start_pointer && !drag.moved {
            return;
        }
        if !drag.moved {
            doc.begin_move();
            drag.moved = true;
        }
        let d = pointer - drag.start_pointer;
        let q = drag.start_model + DVec2::new(f64::from(d.x), -f64::from(d.y)) / self.scale;
        doc.set_point(drag.index, plane.replace(current, q));
    }

    /// The labels `P0`, `P1`, … beside the points; points drawn on top of each other share
    /// one label (`P0,P7`), and labels that would still overlap are moved down until free.
    fn draw_labels(&self, painter: &egui::Painter, points: &[Pos2]) {
        let font = egui::FontId::proportional(11.0);
        // groups of points within 2 screen points of each other
        let mut groups: Vec<(Pos2, Vec<usize>)> = Vec::new();
        for (i, &p) in points.iter().enumerate() {
            match groups.iter_mut().find(|(q, _)| q.distance(p) < 2.0) {
                Some((_, members)) => members.push(i),
                None => groups.push((p, vec![i])),
            }
        }
        // the dots are obstacles too; each label tries the four corners beside its point,
        // then moves down until it is free
        let mut placed: Vec<Rect> =
            points.iter().take(2000).map(|&p| Rect::from_center_size(p, Vec2::splat(10.0))).collect();
        for (p, members) in groups.iter().take(2000) {
            let text = members.iter().map(|i| format!("P{i}")).collect::<Vec<_>>().join(",");
            let galley = painter.layout_no_wrap(text, font.clone(), Color32::from_gray(60));
            let size = galley.size();
            let corners = [
                *p + Vec2::new(7.0, -7.0 - size.y),
                *p + Vec2::new(7.0, 7.0),
                *p + Vec2::new(-7.0 - size.x, -7.0 - size.y),
                *p + Vec2::new(-7.0 - size.x, 7.0),
            ];
            let free = |r: Rect| !placed.iter().any(|q| q.intersects(r));
            let mut min = corners.into_iter().find(|&c| free(Rect::from_min_size(c, size))).unwrap_or(corners[0]);
            let mut rect = Rect::from_min_size(min, size);
            for _ in 0..12 {
                if free(rect) {
                    break;
                }
                min.y += size.y;
                rect = Rect::from_min_size(min, size);
            }
            placed.push(rect);
            painter.galley(min, galley, Color32::from_gray(60));
        }
    }

    /// The polygon edge (index of its first point) within [`PICK_RADIUS`] of `pointer`, the
    /// closing edge of a closed curve included.
    fn edge_near(&self, doc: &Document, points: &[Pos2], pointer: Pos2) -> Option<usize> {
        let n = points.len();
        if n < 2 {
            return None;
        }
        let closed = doc.curve().is_some_and(|c| c.closed) && n > 2;
        let edges = if closed { n } else { n - 1 };
        (0..edges)
            .map(|e| {
                let (a, b) = (points[e], points[(e + 1) % n]);
                let t = closest_param(a, b, pointer);
                (e, (a + (b - a) * t as f32).distance(pointer))
            })
            .filter(|&(_, d)| d <= PICK_RADIUS)
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .map(|(e, _)| e)
    }

    /// A grid with its values along the view's left and bottom edges (lines at 1, 2 or 5
    /// times a power of ten, at least 50 points apart), the axes, the plane's name, and the
    /// pointer's coordinates when it is over the view.
    fn draw_axes(&self, painter: &egui::Painter, doc: &Document) {
        let plane = self.plane_for(doc);
        let r = self.rect;
        let step = grid_step(50.0 / self.scale);
        let lo = self.to_model(r.left_bottom());
        let hi = self.to_model(r.right_top());
        let font = egui::FontId::proportional(10.0);
        let (grid, text) = (Stroke::new(1.0, Color32::from_gray(236)), Color32::from_gray(140));
        let decimals = (-step.log10().floor()).max(0.0) as usize;
        // at most a few hundred lines, whatever the numbers
        let count = |a: f64, b: f64| ((b - a) / step).abs().min(400.0) as i64;
        let x0 = (lo.x / step).ceil();
        for k in 0..=count(lo.x, hi.x) {
            let x = (x0 + k as f64) * step;
            let sx = self.to_screen(DVec2::new(x, 0.0)).x;
            painter.line_segment([Pos2::new(sx, r.top()), Pos2::new(sx, r.bottom())], grid);
            painter.text(
                Pos2::new(sx + 2.0, r.bottom() - 16.0),
                egui::Align2::LEFT_BOTTOM,
                format!("{x:.decimals$}"),
                font.clone(),
                text,
            );
        }
        let y0 = (lo.y / step).ceil();
        for k in 0..=count(lo.y, hi.y) {
            let y = (y0 + k as f64) * step;
            let sy = self.to_screen(DVec2::new(0.0, y)).y;
            painter.line_segment([Pos2::new(r.left(), sy), Pos2::new(r.right(), sy)], grid);
            // not over the x values and the plane's name along the bottom
            if sy > r.bottom() - 26.0 {
                continue;
            }
            painter.text(
                Pos2::new(r.left() + 2.0, sy - 1.0),
                egui::Align2::LEFT_BOTTOM,
                format!("{y:.decimals$}"),
                font.clone(),
                text,
            );
        }
        let o = self.to_screen(DVec2::ZERO);
        let axis = Stroke::new(1.0, Color32::from_gray(190));
        painter.line_segment([Pos2::new(r.left(), o.y), Pos2::new(r.right(), o.y)], axis);
        painter.line_segment([Pos2::new(o.x, r.top()), Pos2::new(o.x, r.bottom())], axis);
        let name = plane.name();
        painter.text(
            r.left_bottom() + Vec2::new(6.0, -6.0),
            egui::Align2::LEFT_BOTTOM,
            format!("plane {name}"),
            egui::FontId::proportional(11.0),
            Color32::from_gray(120),
        );
        if let Some(p) = self.pointer {
            let (a, b) = plane.axes();
            painter.text(
                r.right_bottom() + Vec2::new(-6.0, -6.0),
                egui::Align2::RIGHT_BOTTOM,
                format!("{a} {:.4}   {b} {:.4}", p.x, p.y),
                egui::FontId::monospace(11.0),
                Color32::from_gray(90),
            );
        }
    }

    /// The curve, and what [`Show`] asks for along it (frames by `frame_options`).
    fn draw_curve(&self, painter: &egui::Painter, c: &AnyCurve<DVec3>, plane: Plane, frame_options: &FrameOptions) {
        let tolerance = 0.2 / self.scale;
        let params = flatten_at_most(c, Tessellation::Distance { tolerance }, MAX_DRAWN);
        let segments = c.num_segments().max(1);
        // one polyline per segment, in that segment's colour
        let mut start = 0;
        while start + 1 < params.len() {
            let seg = (params[start] as usize).min(segments - 1);
            let mut end = start + 1;
            while end + 1 < params.len() && params[end] < (seg + 1) as f64 {
                end += 1;
            }
            let line: Vec<Pos2> =
                params[start..=end].iter().map(|&u| self.to_screen(plane.project(c.eval(u)))).collect();
            painter.add(Shape::line(line, Stroke::new(2.5, SEGMENT_COLORS[seg % SEGMENT_COLORS.len()])));
            start = end;
        }
        let len = 28.0 / self.scale;
        if self.show.normals || self.show.frames {
            for (p, f) in frame_arrows(c, frame_options) {
                let mut arrows = vec![(f.t, Color32::from_rgb(40, 80, 230)), (f.n, Color32::from_rgb(220, 40, 40))];
                if self.show.frames {
                    arrows.push((f.b, Color32::from_rgb(30, 160, 60)));
                }
                for (v, color) in arrows {
                    let a = self.to_screen(plane.project(p));
                    let b = self.to_screen(plane.project(p + v * len));
                    painter.arrow(a, b - a, Stroke::new(1.5, color));
                }
            }
        }
        if self.show.comb {
            let n = segments * 24;
            let mut tips = Vec::with_capacity(n + 1);
            for i in 0..=n {
                let u = segments as f64 * i as f64 / n as f64;
                let s = frame::CurveSample::at(c, u);
                // the tooth points away from the centre of curvature
                let tip = s.position - s.curvature * self.show.comb_scale;
                let (a, b) = (self.to_screen(plane.project(s.position)), self.to_screen(plane.project(tip)));
                painter.line_segment([a, b], Stroke::new(1.0, Color32::from_rgb(150, 110, 200)));
                tips.push(b);
            }
            painter.add(Shape::line(tips, Stroke::new(1.0, Color32::from_rgb(120, 80, 180))));
        }
        if self.show.markers {
            let index = ArclenIndex::new(c, 1e-9);
            let spacing = self.show.marker_spacing.max(index.length() / 5000.0).max(1e-12);
            let count = (index.length() / spacing).floor() as usize;
            for k in 0..=count {
                let u = index.u_at(c, k as f64 * spacing);
                let p = self.to_screen(plane.project(c.eval(u)));
                painter.circle(p, 3.0, Color32::from_rgb(20, 20, 20), Stroke::new(1.0, Color32::WHITE));
            }
        }
    }
}

/// The grid spacing for lines at least `min` model units apart: 1, 2 or 5 times a power of 10.
#[must_use]
pub fn grid_step(min: f64) -> f64 {
    if !(min.is_finite() && min > 0.0) {
        return 1.0;
    }
    let power = 10f64.powf(min.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * power).find(|&s| s >= min).unwrap_or(10.0 * power)
}

/// The parameter in `[0, 1]` of the point of segment `ab` closest to `p`.
fn closest_param(a: Pos2, b: Pos2, p: Pos2) -> f64 {
    let e = b - a;
    let l2 = e.length_sq();
    if l2 > 0.0 { f64::from(((p - a).dot(e) / l2).clamp(0.0, 1.0)) } else { 0.0 }
}

/// Which curves of `swp` only shape sweeps: named as a `gcyl`'s scale or twist curve and in
/// no other role (profile, path, lathe curve).
fn shape_only_curves(swp: &splinekit_io::SwpDocument) -> Vec<bool> {
    use splinekit_io::SwpCurveRole as R;
    let (mut shape, mut geometry) = (vec![false; swp.curves.len()], vec![false; swp.curves.len()]);
    for (role, i) in swp.surfaces.iter().flat_map(|s| s.kind.references()) {
        let list = if matches!(role, R::Scale | R::Twist) { &mut shape } else { &mut geometry };
        if let Some(x) = list.get_mut(i) {
            *x = true;
        }
    }
    shape.iter().zip(&geometry).map(|(s, g)| *s && !g).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A twist curve in degrees (x up to 360) does not shrink the fitted scene: only the
    /// profile and path (both within 8 units) are framed, unless the twist curve is the one
    /// being edited.
    #[test]
    fn fitting_leaves_out_curves_that_only_shape_a_sweep() {
        let text = "bez2 p 4 4 [0 -0.5] [0.3 -0.2] [0.3 0.2] [0 0.5]\n\
                    bez2 path 8 4 [0 0] [3 1] [5 -1] [8 0]\n\
                    bez2 tw 4 4 [0 0] [120 0] [240 0] [360 0]\n\
                    bez2 both 4 4 [0 0] [1 0] [2 0] [3 0]\n\
                    gcyl a p path twist tw\n\
                    gcyl b p both scale both\n";
        let swp = splinekit_io::SwpDocument::parse(text, "fit.swp").unwrap();
        // a curve that is also a path is geometry
        assert_eq!(shape_only_curves(&swp), vec![false, false, true, false]);
        let mut doc = Document::from_swp(swp, None);
        let mut view = View2d { rect: Rect::from_min_size(Pos2::ZERO, egui::vec2(800.0, 600.0)), ..View2d::default() };
        view.fit(&doc);
        // 8 units across 80% of 800 points
        assert!((view.scale - 80.0).abs() < 1e-9, "{}", view.scale);
        doc.active = 2;
        view.fit(&doc);
        assert!(view.scale < 3.0, "the twist curve framed when it is the active one: {}", view.scale);
    }

    #[test]
    fn planes_project_and_replace() {
        let p = DVec3::new(1.0, 2.0, 3.0);
        for plane in [Plane::Xy, Plane::Yz, Plane::Zx] {
            let q = plane.project(p);
            assert_eq!(plane.replace(p, q), p);
            let moved = plane.replace(p, q + DVec2::new(10.0, 20.0));
            assert_eq!(plane.project(moved), q + DVec2::new(10.0, 20.0));
            // the third coordinate stays
            assert_eq!((moved - p).length_squared(), 500.0);
        }
    }

    /// Left normals of a counter-clockwise circle point inward, right ones outward: the
    /// closed form `P(u) = r·(cos 2πu, sin 2πu)`, `N_left = −P/r`, `N_right = P/r`.
    #[test]
    fn normals_of_a_counter_clockwise_circle_by_side() {
        let r = 2.5;
        let circle = AnyCurve::Circle(splinekit::Circle::new(r));
        let arrows = |side| frame_arrows(&circle, &Show { normal_side: side, ..Show::default() }.frame_options(true));
        let (left, right) = (arrows(Side::Left), arrows(Side::Right));
        assert_eq!(left.len(), 9, "8 per segment, both ends");
        for (k, ((p, l), (q, rt))) in left.iter().zip(&right).enumerate() {
            let angle = std::f64::consts::TAU * k as f64 / 8.0;
            let expected = r * DVec3::new(angle.cos(), angle.sin(), 0.0);
            assert!((*p - expected).length() < 1e-12 && p == q, "point {k}: {p} vs {expected}");
            let inward = -expected / r;
            assert!((l.n - inward).length() < 1e-9, "left normal {k}: {} vs {inward}", l.n);
            assert!((rt.n + inward).length() < 1e-9, "right normal {k}: {} vs {}", rt.n, -inward);
            // mirrored across the curve: same tangent, N and B reversed
            assert!((l.t - rt.t).length() < 1e-12 && (l.b + rt.b).length() < 1e-12);
            assert!((l.b - DVec3::Z).length() < 1e-9, "B = +z on the left side");
        }
    }

    #[test]
    fn normal_side_is_left_by_default_and_only_for_2d_curves() {
        let show = Show::default();
        assert_eq!(show.normal_side, Side::Left);
        // today's frames: the core's default options
        assert_eq!(show.frame_options(true), FrameOptions::DEFAULT);
        let right = Show { normal_side: Side::Right, ..Show::default() };
        assert_eq!(right.frame_options(true).method, FrameMethod::Sequential(Side::Right));
        assert_eq!(right.frame_options(false), FrameOptions::DEFAULT, "3D curves keep their frames");
    }

    #[test]
    fn screen_and_model_are_inverse() {
        let mut v = View2d { center: DVec2::new(1.0, -2.0), scale: 37.5, ..View2d::default() };
        v.rect = Rect::from_min_size(Pos2::new(10.0, 20.0), Vec2::new(400.0, 300.0));
        let q = DVec2::new(1.5, -1.0);
        let s = v.to_screen(q);
        assert!((v.to_model(s) - q).length() < 1e-5);
        assert!(s.y < v.rect.center().y, "y is up");
    }
}
