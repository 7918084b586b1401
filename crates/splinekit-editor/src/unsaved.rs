//! The unsaved-changes question: actions that replace or close the document ([`Pending`])
//! ask `Save` / `Discard` / `Cancel` first, also when the window is closed.

use std::path::{Path, PathBuf};

use eframe::egui::{self, Key, Modifiers};

use crate::files::Purpose;
use crate::{Document, EditorApp};

/// An action that replaces or closes the document, so it asks first when the document has
/// unsaved changes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Pending {
    /// Close the window.
    Close,
    /// Open this file.
    Open(PathBuf),
    /// Show the Open dialog.
    OpenDialog,
    /// Load the preset scene.
    Preset,
    /// Start a new, empty document.
    New,
    /// Close the mesh shown (a new, empty document).
    CloseMesh,
}

impl Pending {
    /// What the action does, for the question.
    fn doing(&self) -> &'static str {
        match self {
            Self::Close => "closing the window",
            Self::Open(_) | Self::OpenDialog => "opening another file",
            Self::Preset => "loading the preset scene",
            Self::New => "starting a new document",
            Self::CloseMesh => "closing the mesh",
        }
    }
}

impl EditorApp {
    /// Whether the window may close now (no unsaved changes, or the user answered).
    #[must_use]
    pub fn close_allowed(&self) -> bool {
        self.close_allowed
    }

    /// Does `action`, first asking `Save` / `Discard` / `Cancel` if the document has unsaved
    /// changes.
    pub fn request(&mut self, action: Pending) {
        if self.doc.is_modified() {
            self.prompt = Some(action);
        } else {
            self.perform(action);
        }
    }

    /// Does `action` without asking.
    pub(crate) fn perform(&mut self, action: Pending) {
        match action {
            Pending::Close => self.close_allowed = true,
            Pending::Open(path) => {
                self.open_file(&path);
            }
            Pending::OpenDialog => self.open_dialog(Purpose::Open),
            Pending::Preset => self.preset_now(),
            Pending::New => {
                self.doc.replace_with(Document::new());
                self.status = "New document".to_owned();
            }
            Pending::CloseMesh => {
                self.doc.replace_with(Document::new());
                self.status = "Closed the mesh: a new document".to_owned();
            }
        }
    }

    /// A window close request (the window manager's close button): allowed at once without
    /// unsaved changes, else cancelled and the question asked.
    pub(crate) fn on_close_request(&mut self, ctx: &egui::Context) {
        if !ctx.input(|i| i.viewport().close_requested()) || self.close_allowed {
            return;
        }
        if self.doc.is_modified() {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.dialog = None;
            self.prompt = Some(Pending::Close);
        } else {
            self.close_allowed = true;
        }
    }

    /// The question "unsaved changes: Save / Discard / Cancel" before `self.prompt`.
    pub(crate) fn unsaved_prompt(&mut self, ctx: &egui::Context) {
        let Some(pending) = self.prompt.clone() else { return };
        let mut choice = None;
        let name = self.doc.display_name();
        egui::Modal::new(egui::Id::unique("unsaved changes")).show(ctx, |ui| {
            ui.heading("Unsaved changes");
            ui.label(format!("{name} has changes that are not saved. Save them before {}?", pending.doing()));
            ui.horizontal(|ui| {
                if ui.button("Save").clicked() {
                    choice = Some("save");
                }
                if ui.button("Discard").clicked() {
                    choice = Some("discard");
                }
                if ui.button("Cancel").clicked() {
                    choice = Some("cancel");
                }
            });
        });
        if choice.is_none() && ctx.input_mut(|i| i.consume_key(Modifiers::NONE, Key::Escape)) {
            choice = Some("cancel");
        }
        let Some(choice) = choice else { return };
        self.prompt = None;
        match choice {
            "save" => match self.doc.save_path().map(Path::to_path_buf) {
                Some(path) => {
                    if self.save_swp(&path) {
                        self.perform(pending);
                    }
                }
                None => {
                    self.open_dialog(Purpose::SaveAs);
                    self.dialog_then = Some(pending);
                }
            },
            "discard" => self.perform(pending),
            _ => self.status = "Cancelled".to_owned(),
        }
    }
}
