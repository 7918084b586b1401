//! The surface panel on the right: the mesh and its subdivision, or the document's surfaces
//! (Revolve, Sweep, Lathe and each surface's settings), the 3D display settings, and the 3D view.

use std::sync::Arc;

use eframe::egui;
use splinekit::subdiv::Scheme;
use splinekit::sweep::Join;
use splinekit_io::surface::{ProfileAlign, ScaleMode};
use splinekit_io::{SwpFrames, SwpSurfaceKind, SwpSurfaceSettings, SwpTessellation};
use splinekit_render::{Curvature, SurfaceColour};

use crate::scene::paint_legend;
use crate::{EditorApp, Pending, compare, view3d};

/// The axis `Revolve` turns the active curve about.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RevolveAxis {
    /// +y, as SWP `srev` (steps of the profile, slices).
    #[default]
    Y,
    /// +z, as the revolution tool and SWP `zrev` (angle tolerance, slice tolerance, scale).
    Z,
}

/// The slices of a surface of revolution made with `Revolve`.
pub const DEFAULT_SLICES: u32 = 32;

impl EditorApp {
    pub(crate) fn right_panel(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
        ui.heading("Surface");
        // the controls scroll within at most about half the column, so that the 3D view keeps
        // its room however many surfaces the document has
        let most = (0.5 * ui.available_height()).max(160.0);
        egui::ScrollArea::vertical()
            .id_salt("surface controls")
            .max_height(most)
            .auto_shrink([false, true])
            .show(ui, |ui| self.surface_and_display_controls(ui));
        ui.separator();
        self.view_3d(ui, frame);
    }

    /// The loaded mesh's subdivision controls, or the document's surfaces with their
    /// settings, and the 3D display settings.
    fn surface_and_display_controls(&mut self, ui: &mut egui::Ui) {
        if let Some(m) = &self.mesh {
            ui.label(format!("Mesh {}", m.name));
            ui.label(format!("Level {}: {} vertices", m.level, m.vertices()));
            ui.label(format!("Faces: {}", m.faces()));
            let scheme = m.scheme;
            egui::ComboBox::from_label("Scheme").selected_text(scheme.title()).show_ui(ui, |ui| {
                for s in Scheme::ALL {
                    if ui.selectable_label(s == scheme, s.title()).on_hover_text(s.description()).clicked() {
                        self.set_scheme(s);
                    }
                }
            });
            let refining = self.refine_task.is_some();
            ui.horizontal(|ui| {
                if ui.add_enabled(!refining, egui::Button::new("Refine subdivision")).clicked() {
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
                        if ui
                            .add_enabled(room, egui::Checkbox::new(&mut on, format!("compare {}", s.title())))
                            .changed()
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
            self.colouring = menu(ui, "Colour", &choices, self.colouring).0;
        });
    }

    /// The 3D view (or the side-by-side comparison of schemes), with the handles of a 3D
    /// curve.
    fn view_3d(&mut self, ui: &mut egui::Ui, frame: &eframe::Frame) {
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
        let r = ui.add(egui::DragValue::new(&mut k).update_while_editing(false).range(1..=1000)).labelled_by(label.id);
        if r.changed() && k != steps {
            self.edit_value(&r);
            self.doc.set_curve_steps(curve, k);
        }
    }
}

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
        const FRAMES: [(SwpFrames, &str); 5] = [
            (SwpFrames::Auto, "auto"),
            (SwpFrames::Sequential, "sequential"),
            (SwpFrames::RotationMinimizing, "rotation-minimizing"),
            (SwpFrames::Frenet, "Frenet"),
            (SwpFrames::ZUp, "Z-up"),
        ];
        let hint = Some("auto: rotation-minimizing along a path that leaves the xy plane, sequential along one in it");
        let frames = setting_menu(ui, &format!("{name} frames"), &FRAMES, &mut settings.frames, hint);
        const ALIGN: [(ProfileAlign, &str); 3] =
            [(ProfileAlign::Origin, "origin"), (ProfileAlign::Centre, "centre"), (ProfileAlign::Start, "start")];
        let hint = Some("which point of the profile rides on the path");
        let align = setting_menu(ui, &format!("{name} align"), &ALIGN, &mut settings.align, hint);
        const JOINS: [(Join, &str); 3] = [(Join::Mitre, "mitre"), (Join::Round, "round"), (Join::Bevel, "bevel")];
        let hint = Some("how the walls meet at a sharp corner of the path");
        let join = setting_menu(ui, &format!("{name} join"), &JOINS, &mut settings.join, hint);
        const SCALE_MODES: [(ScaleMode, &str); 2] =
            [(ScaleMode::Multiply, "multiply"), (ScaleMode::Override, "override")];
        let hint = Some("multiply: the scale curve scales the profile as drawn; override: it gives the profile's size");
        let scale_mode = setting_menu(ui, &format!("{name} scale mode"), &SCALE_MODES, &mut settings.scale_mode, hint);
        edited = scale_mode.or(join).or(align).or(frames).or(edited);
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

/// `{name} layout`: welded or compat; the response when it changed.
fn layout_control(ui: &mut egui::Ui, name: &str, settings: &mut SwpSurfaceSettings) -> Option<egui::Response> {
    use splinekit::sweep::MeshLayout;
    const LAYOUTS: [(MeshLayout, &str); 2] = [(MeshLayout::Welded, "welded"), (MeshLayout::Compat, "compat")];
    let current = settings.layout.unwrap_or_default();
    let (layout, r) = menu(ui, &format!("{name} layout"), &LAYOUTS, current);
    let r = r.on_hover_text("welded: seams and poles shared; compat: the course program's vertices");
    if layout == current {
        return None;
    }
    settings.layout = Some(layout);
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
    let r = ui.add(egui::DragValue::new(value).update_while_editing(false).range(range)).labelled_by(label.id);
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
    let r = ui
        .add(egui::DragValue::new(value).update_while_editing(false).range(range).speed(speed).max_decimals(6))
        .labelled_by(label.id);
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

/// A menu labelled `label` of `choices` (value, text) showing `current`; returns the value
/// chosen (`current` if none) and the menu's response.
/// [`menu`] for a surface setting (`None`: the default, `T::default()`): sets it to the choice
/// made, and returns the response when it changed.
fn setting_menu<T: Copy + PartialEq + Default>(
    ui: &mut egui::Ui,
    label: &str,
    choices: &[(T, &str)],
    setting: &mut Option<T>,
    hint: Option<&str>,
) -> Option<egui::Response> {
    let current = setting.unwrap_or_default();
    let (chosen, r) = menu(ui, label, choices, current);
    let r = match hint {
        Some(hint) => r.on_hover_text(hint),
        None => r,
    };
    (chosen != current).then(|| {
        *setting = Some(chosen);
        r
    })
}

fn menu<T: Copy + PartialEq>(ui: &mut egui::Ui, label: &str, choices: &[(T, &str)], current: T) -> (T, egui::Response) {
    let mut chosen = current;
    let text = choices.iter().find(|(v, _)| *v == current).map_or("", |(_, t)| t);
    let r = egui::ComboBox::from_label(label)
        .selected_text(text)
        .show_ui(ui, |ui| {
            for &(value, text) in choices {
                ui.selectable_value(&mut chosen, value, text);
            }
        })
        .response;
    (chosen, r)
}
