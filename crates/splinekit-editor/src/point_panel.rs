//! The selected point's values (coordinates, a NURBS point's weight, and a Kochanek–Bartels
//! key's tension, continuity and bias), and the rule that a value dragged or typed is one undo
//! step.

use eframe::egui;
use splinekit::Tcb;

use crate::EditorApp;

impl EditorApp {
    /// The selected point's coordinates, to type or drag (`Point x`, `Point y`, and `Point z`
    /// for a 3D curve), a NURBS point's `Weight`, and a Kochanek–Bartels key's `Tension`,
    /// `Continuity` and `Bias`; each change one undo step.
    pub(crate) fn selected_point(&mut self, ui: &mut egui::Ui) {
        let Some(i) = self.view.selected else { return };
        let Some(&p) = self.doc.points().get(i) else { return };
        ui.label(format!("Selected P{i}"));
        let axes: &[(&str, usize)] =
            if self.doc.is_2d() { &[("x", 0), ("y", 1)] } else { &[("x", 0), ("y", 1), ("z", 2)] };
        // (applied at each key, unlike the surface's numbers: a coordinate typed halfway is a
        // cheap, nearby edit that moves nothing else on the screen)
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
        // a NURBS point's weight, > 0
        if let Some(w) = self.doc.weight(i) {
            ui.horizontal(|ui| {
                let label = ui.label("Weight");
                let mut v = w;
                let r = ui
                    .add(egui::DragValue::new(&mut v).range(1e-6..=1e6).speed(0.01 * w).max_decimals(6))
                    .labelled_by(label.id);
                if r.changed() && v != w {
                    self.edit_value(&r);
                    self.doc.set_weight(i, v);
                }
            });
        }
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
    pub(crate) fn edit_value(&mut self, r: &egui::Response) {
        let continuing = self.value_edit == Some(r.id) && (r.dragged() || r.has_focus());
        if !continuing {
            self.doc.begin_move();
        }
        self.value_edit = (r.dragged() || r.has_focus()).then_some(r.id);
    }
}
