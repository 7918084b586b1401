//! The file dialog of `Open…`, `Save as…` and `Export mesh…`: shown in the document's
//! folder, and what its choice does.

use std::path::{Path, PathBuf};

use eframe::egui;

use crate::EditorApp;
use crate::files::{FileDialog, Outcome, Purpose};

impl EditorApp {
    /// Shows the file dialog for `purpose` (in the document's folder).
    pub fn open_dialog(&mut self, purpose: Purpose) {
        let dir = self
            .doc
            .path()
            .and_then(Path::parent)
            .filter(|d| !d.as_os_str().is_empty())
            .map(Path::to_path_buf)
            .or_else(|| std::env::current_dir().ok())
            .unwrap_or_else(|| PathBuf::from("."));
        let stem = self.doc.path().and_then(Path::file_stem).map(|s| s.to_string_lossy().into_owned());
        let name = match purpose {
            Purpose::Open => String::new(),
            Purpose::SaveAs => format!("{}.swp", stem.as_deref().unwrap_or("untitled")),
            Purpose::Export => format!("{}.obj", stem.as_deref().unwrap_or("surface")),
        };
        let mut dialog = FileDialog::new(purpose, dir, name);
        if purpose == Purpose::Export {
            dialog.forbidden = self.doc.path().map(Path::to_path_buf);
        }
        if purpose == Purpose::SaveAs {
            dialog.obj_refused =
                self.annotated_refusal().map(|why| format!("Save as writes SWP files (.swp) here: {why}"));
        }
        if purpose == Purpose::Open {
            dialog.recent = self.recent.list.clone();
        }
        self.dialog = Some(dialog);
    }

    /// The file dialog, and what its choice does.
    pub(crate) fn file_dialog(&mut self, ctx: &egui::Context) {
        let Some(dialog) = &mut self.dialog else { return };
        let purpose = dialog.purpose;
        match dialog.show(ctx) {
            Outcome::Open => {}
            Outcome::Cancelled => {
                self.dialog = None;
                self.dialog_then = None;
            }
            Outcome::Chosen(path) => {
                self.dialog = None;
                let then = self.dialog_then.take();
                match purpose {
                    Purpose::Open => {
                        self.open_file(&path);
                    }
                    Purpose::SaveAs => {
                        if self.save_to(&path)
                            && let Some(then) = then
                        {
                            self.perform(then);
                        }
                    }
                    Purpose::Export => self.export(&path),
                }
            }
        }
    }
}
