//! The keyboard shortcuts ([`SHORTCUTS`]): every key press of a frame, in order.

use eframe::egui::{self, Key, Modifiers};

use crate::files::Purpose;
use crate::{EditorApp, Pending};

/// The keyboard shortcuts, as the help window lists them.
pub const SHORTCUTS: [(&str, &str); 17] = [
    ("Ctrl+O / Ctrl+S", "open / save"),
    ("Ctrl+Shift+S", "save as"),
    ("Ctrl+N", "new document"),
    ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo (Ctrl+Y redoes too)"),
    ("Delete", "delete the selected point"),
    ("r", "preset scene (8 points, Catmull-Rom)"),
    ("s", "cycle the spline kind"),
    ("c", "clear the curve"),
    ("a", "arc-length markers"),
    ("l", "control polygon"),
    ("w", "wireframe (3D view)"),
    ("n", "normals (curve and surface)"),
    ("f", "fit both views"),
    ("h or ?", "this help"),
    ("Enter / Escape", "confirm / cancel a dialog"),
    ("Tab", "next field"),
    ("Escape", "leave a text field"),
];

impl EditorApp {
    /// Applies every key press of the frame, in order (several presses of one key in one
    /// slow frame act several times). Letter keys act when no text field has focus; nothing
    /// acts while a dialog or question is open (they read their own keys).
    pub(crate) fn keyboard(&mut self, ctx: &egui::Context) {
        if self.modal_open() {
            return;
        }
        let typing = ctx.egui_wants_keyboard_input();
        let events = ctx.input(|i| i.events.clone());
        for event in events {
            match event {
                egui::Event::Key { key, pressed: true, repeat, modifiers, .. } => {
                    self.key(key, modifiers, repeat, typing);
                }
                egui::Event::Text(t) if !typing && t == "?" => self.show_help ^= true,
                _ => {}
            }
            if self.modal_open() {
                // the rest of the frame's keys belong to the dialog
                break;
            }
        }
    }

    /// One key press.
    fn key(&mut self, key: Key, modifiers: Modifiers, repeat: bool, typing: bool) {
        // Ctrl on Linux and Windows (egui sets `command` for it; some input sources set only `ctrl`)
        let command = (modifiers.command || modifiers.ctrl) && !modifiers.alt;
        if command {
            match (key, modifiers.shift) {
                (Key::S, true) => self.open_dialog(Purpose::SaveAs),
                (Key::S, false) => {
                    self.save();
                }
                (Key::O, false) => self.request(Pending::OpenDialog),
                (Key::N, false) => self.request(Pending::New),
                // a text field has its own undo
                (Key::Z, true) | (Key::Y, false) if !typing => self.redo(),
                (Key::Z, false) if !typing => self.undo(),
                _ => {}
            }
            return;
        }
        if typing || modifiers.any() {
            return;
        }
        if matches!(key, Key::Delete | Key::Backspace) {
            if let Some(i) = self.view.selected.take() {
                self.doc.delete_point(i);
            }
            return;
        }
        if repeat {
            return;
        }
        match key {
            Key::R => self.request(Pending::Preset),
            Key::S => {
                self.doc.cycle_kind();
                self.status_kind();
            }
            Key::C => {
                self.doc.clear();
                self.view.selected = None;
            }
            Key::A => self.view.show.markers ^= true,
            Key::L => self.view.show.polygon ^= true,
            Key::W => self.view3d.settings.wireframe ^= true,
            Key::N => {
                let on = !self.view3d.settings.normals;
                self.view3d.settings.normals = on;
                self.view.show.normals = on;
            }
            Key::F => {
                self.view.fit_pending = true;
                self.view3d.fit();
            }
            Key::H => self.show_help ^= true,
            _ => {}
        }
    }
}
