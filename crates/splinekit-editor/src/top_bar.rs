//! The file bar at the top: file actions, undo and redo, the preset, the View menu
//! ([`Layout`]) and Help.

use eframe::egui;

use crate::files::Purpose;
use crate::{EditorApp, Pending};

/// Which panels are shown (the View menu): hide the 2D view to give the 3D view the room, or
/// the curve panel on a small screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The curve panel on the left.
    pub curves_panel: bool,
    /// The 2D curve view.
    pub view2d: bool,
    /// The surface panel with the 3D view.
    pub view3d: bool,
}

impl Default for Layout {
    fn default() -> Self {
        Self { curves_panel: true, view2d: true, view3d: true }
    }
}

impl EditorApp {
    pub(crate) fn file_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            if self.modal_open() {
                // the dialog's own buttons (Save, Cancel, …) are the only ones with their labels
                ui.label(self.title());
                return;
            }
            if ui.button("New").on_hover_text("Ctrl+N").clicked() {
                self.request(Pending::New);
            }
            if ui.button("Open…").on_hover_text("Ctrl+O").clicked() {
                self.request(Pending::OpenDialog);
            }
            if ui.button("Save").on_hover_text("Ctrl+S").clicked() {
                self.save();
            }
            if ui.button("Save as…").on_hover_text("Ctrl+Shift+S").clicked() {
                self.open_dialog(Purpose::SaveAs);
            }
            if ui.button("Export mesh…").clicked() {
                self.open_dialog(Purpose::Export);
            }
            ui.separator();
            if ui.add_enabled(self.doc.can_undo(), egui::Button::new("Undo")).clicked() {
                self.undo();
            }
            if ui.add_enabled(self.doc.can_redo(), egui::Button::new("Redo")).clicked() {
                self.redo();
            }
            if ui.button("Preset").clicked() {
                self.request(Pending::Preset);
            }
            ui.menu_button("View", |ui| {
                let before = self.layout;
                ui.checkbox(&mut self.layout.curves_panel, "Show curve panel");
                ui.checkbox(&mut self.layout.view2d, "Show 2D view");
                ui.checkbox(&mut self.layout.view3d, "Show 3D view");
                if !self.layout.view2d && !self.layout.view3d {
                    // one view stays: the one not just switched off
                    if before.view2d {
                        self.layout.view3d = true;
                    } else {
                        self.layout.view2d = true;
                    }
                }
            });
            if ui.button("Help").clicked() {
                self.show_help ^= true;
            }
        });
    }
}
