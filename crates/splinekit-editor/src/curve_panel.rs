//! The curve panel on the left: the curves, the active curve's kind, closed and plane, and
//! what the views show.

use eframe::egui;

use splinekit_io::SwpCurveKind;

use crate::{EditorApp, Plane, doc};

impl EditorApp {
    pub(crate) fn left_panel(&mut self, ui: &mut egui::Ui) {
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
                    if ui.selectable_label(doc::same_kind(k, kind), name).clicked() {
                        self.doc.set_kind(k);
                        self.status_kind();
                    }
                }
            });
            let mut c = closed;
            if ui.add_enabled(kind != SwpCurveKind::BezierN, egui::Checkbox::new(&mut c, "Closed")).changed() {
                self.doc.set_closed(c);
            }
            self.nurbs_settings(ui);
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
}

impl EditorApp {
    /// A NURBS's degree (typed or dragged, one undo step) and its knot vector as the curve
    /// uses it.
    fn nurbs_settings(&mut self, ui: &mut egui::Ui) {
        let Some(degree) = self.doc.nurbs_degree() else { return };
        ui.horizontal(|ui| {
            let label = ui.label("Degree");
            let mut d = degree;
            let max = splinekit::MAX_NURBS_DEGREE as u32;
            let r = ui
                .add(egui::DragValue::new(&mut d).update_while_editing(false).range(1..=max).speed(0.05))
                .labelled_by(label.id);
            if r.changed() && d != degree {
                self.doc.set_degree(d);
            }
        });
        match self.doc.knots() {
            Some((knots, own)) => {
                let list: Vec<String> = knots.iter().map(|k| format!("{k}")).collect();
                let whose = if own { "from the file" } else { "default" };
                ui.label(format!("Knots ({whose}): {}", list.join(" ")));
            }
            None => {
                ui.label(format!("Knots: a NURBS of degree {degree} needs at least {} points", degree + 1));
            }
        }
    }
}

/// The number of editable points of a curve (0 for circles and the like).
fn point_count(c: &splinekit_io::SwpCurve) -> usize {
    c.geometry.points().len()
}
