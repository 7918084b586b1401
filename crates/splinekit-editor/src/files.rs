//! The editor's file dialog (in the window: headless machines have no desktop portal for
//! native dialogs) and its list of recent files.
//!
//! One dialog serves Open, Save as and Export mesh: the folder's entries filtered by the
//! extensions the action accepts, a name field, parent-folder and home shortcuts, Enter to
//! confirm and Escape to cancel. An extension the action cannot handle is refused with a
//! message, and replacing an existing file asks first (`Replace` / `Cancel`).

use std::path::{Path, PathBuf};

use eframe::egui::{self, Key};
use splinekit_io::mesh::MeshFormat;

/// The most recent files kept.
pub const MAX_RECENT: usize = 10;

/// What a file dialog is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Purpose {
    /// Open a document or a mesh.
    Open,
    /// Save the document as SWP under a new name.
    SaveAs,
    /// Export the surface shown in the 3D view as a mesh file.
    Export,
}

impl Purpose {
    /// The dialog's title.
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Self::Open => "Open a file",
            Self::SaveAs => "Save as",
            Self::Export => "Export mesh",
        }
    }

    /// The label of the button that confirms.
    #[must_use]
    pub fn confirm_label(self) -> &'static str {
        match self {
            Self::Open => "Open",
            Self::SaveAs => "Save",
            Self::Export => "Export",
        }
    }

    /// The extensions the action accepts (lowercase, without the dot); the first is added to
    /// a name typed without one when saving.
    #[must_use]
    pub fn extensions(self) -> Vec<&'static str> {
        let meshes = |keep: fn(MeshFormat) -> bool| {
            MeshFormat::ALL.into_iter().filter(move |&f| keep(f)).map(MeshFormat::extension)
        };
        match self {
            Self::Open => std::iter::once("swp").chain(meshes(|f| f.capabilities().reads)).collect(),
            Self::SaveAs => vec!["swp", "obj"],
            Self::Export => meshes(|f| f.capabilities().writes).collect(),
        }
    }

    /// Whether the action writes a file (and so asks before replacing one).
    fn writes(self) -> bool {
        self != Self::Open
    }

    /// Why `path`'s extension is refused, or `None` if the action accepts it.
    #[must_use]
    pub fn refuse_extension(self, path: &Path) -> Option<String> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        if ext.as_deref().is_some_and(|e| self.extensions().contains(&e)) {
            return None;
        }
        let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
        let list = self.extensions().iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(", ");
        Some(match self {
            Self::Open => format!("cannot open {name}: the editor opens {list} files"),
            Self::SaveAs if ext.as_deref().is_some_and(|e| Self::Export.extensions().contains(&e)) => {
                format!(
                    "cannot save the document as {name}: Save as writes SWP files (.swp) and the revolution \
                     tool's annotated OBJ (.obj); use Export mesh for a mesh"
                )
            }
            Self::SaveAs => format!(
                "cannot save the document as {name}: Save as writes SWP files (.swp) and the revolution tool's \
                 annotated OBJ (.obj)"
            ),
            Self::Export => format!("cannot export to {name}: Export mesh writes {list} files"),
        })
    }
}

/// One entry of the folder listing.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Entry {
    name: String,
    dir: bool,
}

/// What the dialog decided this frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Still open.
    Open,
    /// Closed without a choice.
    Cancelled,
    /// A file was chosen (for writing: a new file, or one the user agreed to replace).
    Chosen(PathBuf),
}

/// An open file dialog.
#[derive(Clone, Debug)]
pub struct FileDialog {
    /// What it is for.
    pub purpose: Purpose,
    /// The folder shown.
    pub dir: PathBuf,
    /// The name field.
    pub name: String,
    /// Why the last choice was refused.
    pub error: Option<String>,
    /// A file that exists and would be replaced: the dialog asks first.
    pub confirm_replace: Option<PathBuf>,
    /// A path the dialog refuses to write (the open document's file, for Export mesh).
    pub forbidden: Option<PathBuf>,
    /// Why `.obj` names are refused (Save as of a document that is not one curve and its
    /// revolution about +z, which is all an annotated OBJ holds).
    pub obj_refused: Option<String>,
    /// Recent files, shown by the Open dialog.
    pub recent: Vec<PathBuf>,
    entries: Vec<Entry>,
    focus_name: bool,
    /// Where the dialog was drawn last frame.
    last_rect: Option<egui::Rect>,
}

impl FileDialog {
    /// A dialog for `purpose` in `dir` with `name` in the name field.
    #[must_use]
    pub fn new(purpose: Purpose, dir: PathBuf, name: String) -> Self {
        let mut d = Self {
            purpose,
            dir,
            name,
            error: None,
            confirm_replace: None,
            forbidden: None,
            obj_refused: None,
            recent: Vec::new(),
            entries: Vec::new(),
            focus_name: true,
            last_rect: None,
        };
        d.refresh();
        d
    }

    /// Reads the folder again (folders first, then the files the action accepts, by name).
    pub fn refresh(&mut self) {
        self.entries.clear();
        let Ok(read) = std::fs::read_dir(&self.dir) else {
            self.error = Some(format!("cannot list the folder {}", self.dir.display()));
            return;
        };
        let exts = self.purpose.extensions();
        for entry in read.flatten().take(100_000) {
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with('.') {
                continue;
            }
            let dir = entry.file_type().is_ok_and(|t| t.is_dir())
                || (entry.file_type().is_ok_and(|t| t.is_symlink()) && entry.path().is_dir());
            let accepted = Path::new(&name)
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| exts.contains(&e.to_ascii_lowercase().as_str()));
            if dir || accepted {
                self.entries.push(Entry { name, dir });
            }
        }
        self.entries.sort_by(|a, b| b.dir.cmp(&a.dir).then_with(|| a.name.to_lowercase().cmp(&b.name.to_lowercase())));
    }

    /// The entries shown: `(name, is_folder)`.
    pub fn entries(&self) -> impl Iterator<Item = (&str, bool)> {
        self.entries.iter().map(|e| (e.name.as_str(), e.dir))
    }

    /// Shows folder `dir`.
    pub fn go_to(&mut self, dir: PathBuf) {
        // typing goes on in the name field, and Enter confirms it
        self.focus_name = true;
        self.dir = dir;
        self.error = None;
        self.confirm_replace = None;
        self.refresh();
    }

    /// Confirms the name field: a folder is entered; a file is checked (extension, the
    /// forbidden path, an existing file to replace) and chosen.
    pub fn confirm(&mut self) -> Outcome {
        let typed = self.name.trim();
        if typed.is_empty() {
            self.error = Some("type a file name".to_owned());
            return Outcome::Open;
        }
        let typed = expand_home(typed);
        let mut path = if typed.is_absolute() { typed } else { self.dir.join(typed) };
        if path.is_dir() {
            self.name.clear();
            self.go_to(path);
            return Outcome::Open;
        }
        if self.purpose.writes() && path.extension().is_none() {
            path.set_extension(self.purpose.extensions()[0]);
        }
        self.choose(path)
    }

    /// Checks `path` for the dialog's action and chooses it (or asks before replacing it).
    pub fn choose(&mut self, path: PathBuf) -> Outcome {
        self.error = None;
        if let Some(why) = self.purpose.refuse_extension(&path) {
            self.error = Some(why);
            return Outcome::Open;
        }
        if let Some(why) = &self.obj_refused
            && path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"))
        {
            self.error = Some(why.clone());
            return Outcome::Open;
        }
        if self.purpose.writes() {
            if self.forbidden.as_deref().is_some_and(|f| same_file(f, &path)) {
                self.error = Some(format!(
                    "{} is the open document's file; choose another name",
                    path.file_name().unwrap_or_default().to_string_lossy()
                ));
                return Outcome::Open;
            }
            if path.is_dir() {
                self.error = Some(format!("{} is a folder", path.display()));
                return Outcome::Open;
            }
            if path.exists() && self.confirm_replace.as_deref() != Some(path.as_path()) {
                self.confirm_replace = Some(path);
                return Outcome::Open;
            }
        } else if !path.is_file() {
            self.error = Some(format!("{} does not exist", path.display()));
            return Outcome::Open;
        }
        Outcome::Chosen(path)
    }

    /// Draws the dialog (a modal window) and returns what was decided.
    pub fn show(&mut self, ctx: &egui::Context) -> Outcome {
        let mut outcome = Outcome::Open;
        let modal = egui::Modal::new(egui::Id::unique("file dialog")).show(ctx, |ui| {
            ui.set_width(520.0_f32.min(ctx.content_rect().width() - 40.0));
            ui.heading(self.purpose.title());
            ui.horizontal(|ui| {
                if ui.button("Parent folder").clicked()
                    && let Some(parent) = self.dir.parent()
                {
                    let parent = parent.to_path_buf();
                    self.go_to(parent);
                }
                if ui.button("Home").clicked()
                    && let Some(home) = home_dir()
                {
                    self.go_to(home);
                }
                ui.label(egui::RichText::new(self.dir.display().to_string()).monospace());
            });
            ui.separator();
            let max_height = (ctx.content_rect().height() - 260.0).clamp(80.0, 320.0);
            let mut enter = None;
            let mut pick = None;
            egui::ScrollArea::vertical().max_height(max_height).auto_shrink([false, true]).show(ui, |ui| {
                if self.entries.is_empty() {
                    ui.weak("(no folders or matching files here)");
                }
                for e in &self.entries {
                    let label = if e.dir { format!("{}/", e.name) } else { e.name.clone() };
                    let r = ui.selectable_label(!e.dir && e.name == self.name, label);
                    if e.dir && (r.clicked() || r.double_clicked()) {
                        enter = Some(self.dir.join(&e.name));
                    } else if r.double_clicked() {
                        self.name = e.name.clone();
                        pick = Some(self.dir.join(&e.name));
                    } else if r.clicked() {
                        self.name = e.name.clone();
                        self.focus_name = true;
                    }
                }
            });
            if self.purpose == Purpose::Open && !self.recent.is_empty() {
                ui.separator();
                ui.label("Recent files");
                for p in self.recent.clone() {
                    if ui.selectable_label(false, p.display().to_string()).clicked() {
                        pick = Some(p);
                    }
                }
            }
            ui.separator();
            let mut confirm = false;
            ui.horizontal(|ui| {
                let label = ui.label("Name:");
                let id = egui::Id::unique("file dialog name");
                let r = text_field(ui, &mut self.name, id, 360.0).labelled_by(label.id);
                if self.focus_name {
                    r.request_focus();
                    self.focus_name = false;
                }
                if r.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter)) {
                    confirm = true;
                }
            });
            if let Some(e) = &self.error {
                ui.colored_label(egui::Color32::from_rgb(200, 30, 30), e);
            }
            ui.horizontal(|ui| {
                if let Some(path) = self.confirm_replace.clone() {
                    let name = path.file_name().unwrap_or_default().to_string_lossy().into_owned();
                    ui.label(format!("{name} already exists. Replace it?"));
                    if ui.button("Replace").clicked() {
                        outcome = Outcome::Chosen(path);
                    }
                    if ui.button("Cancel").clicked() {
                        self.confirm_replace = None;
                    }
                } else {
                    let b = ui.button(self.purpose.confirm_label());
                    if b.clicked() {
                        confirm = true;
                    }
                    if ui.button("Cancel").clicked() {
                        outcome = Outcome::Cancelled;
                    }
                }
            });
            if let Some(dir) = enter {
                self.go_to(dir);
            }
            let chose = pick.is_some() || confirm;
            if let Some(path) = pick {
                outcome = self.choose(path);
            } else if confirm {
                outcome = self.confirm();
            }
            if self.error.is_some() && chose {
                // the name can be typed again at once
                self.focus_name = true;
            }
        });
        if outcome == Outcome::Open && ctx.input_mut(|i| i.consume_key(egui::Modifiers::NONE, Key::Escape)) {
            // Escape backs out of the replace question first, then closes
            if self.confirm_replace.take().is_none() {
                outcome = Outcome::Cancelled;
            }
        }
        // the modal is centred by last frame's size: draw again until it stops moving, so
        // that what the user sees (and clicks) is where it stays
        if self.last_rect != Some(modal.response.rect) {
            self.last_rect = Some(modal.response.rect);
            ctx.request_repaint();
        }
        outcome
    }
}

/// A single-line text field that keeps every character typed in a frame, even when the same
/// frame has a click elsewhere (egui gives the focus away at the click, before the field
/// reads the frame's text; the focus is given up here after the field has read it).
pub fn text_field(ui: &mut egui::Ui, text: &mut String, id: egui::Id, width: f32) -> egui::Response {
    let had_focus = ui.memory(|m| m.has_focus(id));
    let before = ui.ctx().options(|o| o.input_options.surrender_focus_on);
    if had_focus {
        ui.ctx().options_mut(|o| o.input_options.surrender_focus_on = egui::SurrenderFocusOn::Never);
    }
    let response = ui.add(egui::TextEdit::singleline(text).id(id).desired_width(width));
    if had_focus {
        ui.ctx().options_mut(|o| o.input_options.surrender_focus_on = before);
        let clicked_elsewhere = ui.input(|i| i.pointer.any_click()) && !response.hovered();
        if clicked_elsewhere {
            ui.memory_mut(|m| m.surrender_focus(id));
        }
    }
    response
}

/// Whether `a` and `b` name the same file (compared canonically where both exist).
#[must_use]
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => absolute(a) == absolute(b),
    }
}

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// The user's home folder.
#[must_use]
pub fn home_dir() -> Option<PathBuf> {
    std::env::var_os("HOME").filter(|h| !h.is_empty()).map(PathBuf::from)
}

/// `~/x` as a path in the home folder.
fn expand_home(typed: &str) -> PathBuf {
    match (typed.strip_prefix("~/"), home_dir()) {
        (Some(rest), Some(home)) => home.join(rest),
        _ if typed == "~" => home_dir().unwrap_or_else(|| PathBuf::from(typed)),
        _ => PathBuf::from(typed),
    }
}

/// The recent files (most recent first), kept in `recent-files` in the editor's settings
/// folder (`$XDG_CONFIG_HOME/splinekit`, or `~/.config/splinekit`), one path a line.
#[derive(Clone, Debug, Default)]
pub struct RecentFiles {
    /// The files, most recent first, at most [`MAX_RECENT`].
    pub list: Vec<PathBuf>,
    /// Where the list is kept (`None`: not kept).
    pub store: Option<PathBuf>,
}

impl RecentFiles {
    /// The list kept in the settings folder (empty if there is none or it cannot be read).
    #[must_use]
    pub fn load() -> Self {
        let store = config_dir().map(|d| d.join("recent-files"));
        Self::load_from(store)
    }

    /// The list kept at `store`.
    #[must_use]
    pub fn load_from(store: Option<PathBuf>) -> Self {
        let list = store
            .as_deref()
            .and_then(|s| std::fs::read_to_string(s).ok())
            .map(|text| text.lines().filter(|l| !l.is_empty()).take(MAX_RECENT).map(PathBuf::from).collect())
            .unwrap_or_default();
        Self { list, store }
    }

    /// Puts `path` first (absolute) and keeps the list; a list that cannot be written is
    /// still kept for this session.
    pub fn add(&mut self, path: &Path) {
        let path = absolute(path);
        self.list.retain(|p| *p != path);
        self.list.insert(0, path);
        self.list.truncate(MAX_RECENT);
        let Some(store) = &self.store else { return };
        if let Some(dir) = store.parent() {
            let _ = std::fs::create_dir_all(dir);
        }
        let text: String = self.list.iter().map(|p| format!("{}\n", p.display())).collect();
        let _ = splinekit_io::atomic::write_file(store, |w| -> std::io::Result<()> {
            use std::io::Write;
            w.write_all(text.as_bytes())
        });
    }
}

/// The editor's settings folder: `$XDG_CONFIG_HOME/splinekit` or `~/.config/splinekit`.
#[must_use]
pub fn config_dir() -> Option<PathBuf> {
    let base = std::env::var_os("XDG_CONFIG_HOME")
        .filter(|d| !d.is_empty())
        .map(PathBuf::from)
        .or_else(|| home_dir().map(|h| h.join(".config")))?;
    Some(base.join("splinekit"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("splinekit-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn extensions_are_checked_per_action() {
        assert!(Purpose::Open.refuse_extension(Path::new("a.SWP")).is_none());
        assert!(Purpose::Open.refuse_extension(Path::new("a.ply")).is_none());
        let why = Purpose::SaveAs.refuse_extension(Path::new("bunny.ply")).unwrap();
        assert!(why.contains("Save as writes SWP files") && why.contains("Export mesh"), "{why}");
        assert!(Purpose::SaveAs.refuse_extension(Path::new("vase.obj")).is_none());
        assert!(Purpose::SaveAs.refuse_extension(Path::new("a.swp")).is_none());
        assert!(Purpose::Export.refuse_extension(Path::new("a.swp")).is_some());
        assert!(Purpose::Export.refuse_extension(Path::new("a.glb")).is_none());
    }

    #[test]
    fn listing_filters_and_sorts_and_confirm_asks_before_replacing() {
        let dir = temp("list");
        for f in ["b.swp", "A.obj", "notes.txt", ".hidden.swp"] {
            std::fs::write(dir.join(f), "x").unwrap();
        }
        std::fs::create_dir(dir.join("sub")).unwrap();
        let d = FileDialog::new(Purpose::SaveAs, dir.clone(), String::new());
        let names: Vec<_> = d.entries().map(|(n, f)| (n.to_owned(), f)).collect();
        assert_eq!(names, [("sub".to_owned(), true), ("A.obj".to_owned(), false), ("b.swp".to_owned(), false)]);
        let d = FileDialog::new(Purpose::Open, dir.clone(), String::new());
        let names: Vec<_> = d.entries().map(|(n, _)| n.to_owned()).collect();
        assert_eq!(names, ["sub", "A.obj", "b.swp"]);

        let mut d = FileDialog::new(Purpose::SaveAs, dir.clone(), "b".to_owned());
        // b → b.swp, which exists: the dialog asks, and the same choice again replaces
        assert_eq!(d.confirm(), Outcome::Open);
        assert_eq!(d.confirm_replace.as_deref(), Some(dir.join("b.swp").as_path()));
        assert_eq!(d.confirm(), Outcome::Chosen(dir.join("b.swp")));
        d.name = "new".to_owned();
        d.confirm_replace = None;
        assert_eq!(d.confirm(), Outcome::Chosen(dir.join("new.swp")));
        d.name = "sub".to_owned();
        assert_eq!(d.confirm(), Outcome::Open);
        assert_eq!(d.dir, dir.join("sub"));
        d.name = "x.ply".to_owned();
        assert_eq!(d.confirm(), Outcome::Open);
        assert!(d.error.as_deref().unwrap().contains("SWP"));

        let mut e = FileDialog::new(Purpose::Export, dir.clone(), "b.swp".to_owned());
        e.forbidden = Some(dir.join("A.obj"));
        assert_eq!(e.confirm(), Outcome::Open, "an SWP name is not a mesh");
        e.name = "A.obj".to_owned();
        assert_eq!(e.confirm(), Outcome::Open);
        assert!(e.error.as_deref().unwrap().contains("open document"), "{:?}", e.error);
        assert!(e.confirm_replace.is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn recent_files_keep_ten_most_recent_first() {
        let dir = temp("recent");
        let store = dir.join("cfg/recent-files");
        let mut r = RecentFiles::load_from(Some(store.clone()));
        for k in 0..12 {
            r.add(&dir.join(format!("f{k}.swp")));
        }
        r.add(&dir.join("f5.swp"));
        let back = RecentFiles::load_from(Some(store));
        assert_eq!(back.list.len(), MAX_RECENT);
        assert_eq!(back.list[0], dir.join("f5.swp"));
        assert_eq!(back.list[1], dir.join("f11.swp"));
        assert_eq!(back.list.iter().filter(|p| p.ends_with("f5.swp")).count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
