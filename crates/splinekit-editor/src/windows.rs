//! The Help window (mouse actions, [`MOUSE`], and keys) and the arc-length table window.

use eframe::egui;

use crate::{EditorApp, SHORTCUTS};

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

impl EditorApp {
    pub(crate) fn windows(&mut self, ctx: &egui::Context) {
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
}
