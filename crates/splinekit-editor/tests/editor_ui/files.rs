//! A person's files (#36): Save never writes a file that is not the document's, never
//! writes a file the editor cannot read back, replacing a file asks first, and unsaved changes
//! are never thrown away without asking.

use egui::{Key, ViewportCommand, ViewportEvent, ViewportId};
use splinekit_editor::files::{FileDialog, Purpose, RecentFiles};
use splinekit_editor::{DocKind, Pending};

use super::*;

/// A copy of the test data file `rel` in a fresh directory `dir`.
fn copy_to(dir: &Path, rel: &str) -> PathBuf {
    let from = data(rel);
    let to = dir.join(from.file_name().unwrap());
    std::fs::copy(&from, &to).unwrap();
    to
}

/// An editor whose recent files are kept in `dir` (not the user's settings).
fn app_in(dir: &Path, file: Option<&Path>) -> EditorApp {
    let mut app = EditorApp::default();
    app.recent = RecentFiles::load_from(Some(dir.join("recent-files")));
    if let Some(f) = file {
        assert!(app.open_file(f), "{}", app.status);
    }
    app
}

/// `swp` with every source position at line 1, column 1.
pub(crate) fn without_positions(swp: &SwpDocument) -> SwpDocument {
    let mut d = swp.clone();
    let p = splinekit_io::SourcePos::new(1, 1);
    d.curves.iter_mut().for_each(|c| c.pos = p);
    d.surfaces.iter_mut().for_each(|s| s.pos = p);
    d
}

fn dialog<'a>(h: &'a Harness<'static, EditorApp>) -> &'a FileDialog {
    h.state().dialog.as_ref().expect("a file dialog is open")
}

/// Points the open dialog at `dir` with `name` in its name field, and clicks `button`.
fn choose(h: &mut Harness<'static, EditorApp>, dir: &Path, name: &str, button: &str) {
    let d = h.state_mut().dialog.as_mut().expect("a file dialog is open");
    d.go_to(dir.to_path_buf());
    d.name = name.to_owned();
    h.run();
    click(h, button);
}

fn commands(h: &Harness<'_, EditorApp>) -> Vec<ViewportCommand> {
    h.output().viewport_output.get(&ViewportId::ROOT).map(|v| v.commands.clone()).unwrap_or_default()
}

fn request_close(h: &mut Harness<'static, EditorApp>) {
    h.input_mut().viewports.entry(ViewportId::ROOT).or_default().events.push(ViewportEvent::Close);
    h.step();
}

/// #36, item 1: after opening a mesh, Save asks for an SWP name; it never writes the mesh.
#[test]
fn save_after_opening_a_mesh_never_writes_the_mesh() {
    let dir = tempfile_dir("mesh-save");
    let mesh = copy_to(&dir, "obj/icosahedron.obj");
    let bytes = std::fs::read(&mesh).unwrap();
    let mut h = harness(app_in(&dir, Some(&mesh)));
    assert_eq!(h.state().doc.kind(), DocKind::Mesh);
    click(&mut h, "Save");
    assert_eq!(dialog(&h).purpose, Purpose::SaveAs);
    assert_eq!(dialog(&h).name, "icosahedron.swp");
    // the mesh's own name is refused: Save as writes SWP
    choose(&mut h, &dir, "icosahedron.obj", "Save");
    let error = dialog(&h).error.clone().unwrap();
    assert!(error.contains("Save as writes SWP files"), "{error}");
    h.get_by_label(&error);
    click(&mut h, "Cancel");
    assert!(h.state().dialog.is_none());
    // Ctrl+S asks again; Escape closes the dialog
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run();
    assert_eq!(dialog(&h).purpose, Purpose::SaveAs);
    h.key_press(Key::Escape);
    h.run();
    assert!(h.state().dialog.is_none());
    assert_eq!(std::fs::read(&mesh).unwrap(), bytes, "the mesh is untouched");
    let _ = std::fs::remove_dir_all(dir);
}

/// #36, item 2: a failed open changes nothing, so Save writes the document's own file (or
/// asks, for a new document), never the file that failed to open.
#[test]
fn a_failed_open_never_makes_save_write_the_broken_file() {
    let dir = tempfile_dir("failed-open");
    let broken = dir.join("broken.swp");
    std::fs::write(&broken, "bsp2 p 10 4 [0 0] [1 1] [2 oops] [3 0]\n").unwrap();
    let good = dir.join("good.swp");
    std::fs::write(&good, "bsp2 p 10 4 [0 0] [1 1] [2 0] [3 1]\n").unwrap();

    // a new document: open the broken file through the dialog, then Save asks for a name
    let mut h = harness(app_in(&dir, None));
    click(&mut h, "Open…");
    choose(&mut h, &dir, "broken.swp", "Open");
    assert!(h.state().status.contains("broken.swp:1:"), "{}", h.state().status);
    assert_eq!(h.state().doc.path(), None);
    click(&mut h, "Save");
    assert_eq!(dialog(&h).purpose, Purpose::SaveAs);
    click(&mut h, "Cancel");

    // an SWP document: after the failed open, Save writes the document's own file
    h.state_mut().open_file(&good);
    h.run();
    h.key_press(Key::S);
    h.run();
    h.state_mut().open_file(&broken);
    h.run();
    assert!(h.state().status.starts_with("Error"), "{}", h.state().status);
    assert_eq!(h.state().doc.path(), Some(good.as_path()));
    click(&mut h, "Save");
    assert!(h.state().dialog.is_none());
    assert_eq!(std::fs::read_to_string(&broken).unwrap(), "bsp2 p 10 4 [0 0] [1 1] [2 oops] [3 0]\n");
    let saved = SwpDocument::read(&good).unwrap();
    assert_eq!(saved.curves[0].kind, SwpCurveKind::CatmullRom { alpha: 0.0 }, "the edit was saved there");
    let _ = std::fs::remove_dir_all(dir);
}

/// #36, item 3: a curve the reader would refuse blocks the save, with a message in words,
/// and nothing is written (a new file is not created, an existing one keeps its bytes).
#[test]
fn save_refuses_what_the_reader_would_refuse() {
    let dir = tempfile_dir("refuse");
    let mut app = app_in(&dir, None);
    app.doc.set_kind(SwpCurveKind::BSpline);
    app.doc.add_point(DVec3::new(0.0, 0.0, 0.0));
    app.doc.add_point(DVec3::new(1.0, 1.0, 0.0));
    app.doc.add_curve();
    for k in 0..4 {
        app.doc.add_point(DVec3::new(f64::from(k), 0.5, 0.0));
    }
    let mut h = harness(app);
    click(&mut h, "Save as…");
    choose(&mut h, &dir, "two.swp", "Save");
    assert_eq!(
        h.state().status,
        "Error: not saved: curve \"profile\": a B-spline needs at least 4 points; this one has 2"
    );
    assert!(!dir.join("two.swp").exists());

    // a 5-point Bézier spline, saved over an existing file: refused, the file kept
    let existing = dir.join("keep.swp");
    std::fs::write(&existing, "circ c 10 1\n").unwrap();
    h.state_mut().doc.delete_point(0);
    let app = h.state_mut();
    app.doc.select_curve(0);
    app.doc.set_kind(SwpCurveKind::Bezier);
    for k in 0..3 {
        app.doc.add_point(DVec3::new(2.0 + f64::from(k), 0.0, 0.0));
    }
    assert_eq!(h.state().doc.points().len(), 5);
    click(&mut h, "Save as…");
    choose(&mut h, &dir, "keep.swp", "Save");
    click(&mut h, "Replace");
    assert_eq!(
        h.state().status,
        "Error: not saved: curve \"profile\": a Bézier spline needs 4, 7, 10, … points; this one has 5"
    );
    assert_eq!(std::fs::read_to_string(&existing).unwrap(), "circ c 10 1\n");
    assert_eq!(h.state().doc.path(), None, "nothing was saved, so the document has no file yet");
    let _ = std::fs::remove_dir_all(dir);
}

/// Save as onto an existing file asks `Replace` / `Cancel`; the file is written only after
/// Replace, and re-opens to the same document.
#[test]
fn replacing_a_file_asks_first() {
    let dir = tempfile_dir("replace");
    let target = dir.join("target.swp");
    std::fs::write(&target, "circ c 10 1\n").unwrap();
    let mut h = four_points();
    h.state_mut().recent = RecentFiles::default();
    click(&mut h, "Save as…");
    choose(&mut h, &dir, "target", "Save");
    h.get_by_label("target.swp already exists. Replace it?");
    click(&mut h, "Cancel");
    assert!(h.state().dialog.is_some(), "Cancel goes back to the dialog");
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "circ c 10 1\n");
    click(&mut h, "Save");
    click(&mut h, "Replace");
    assert!(h.state().dialog.is_none());
    assert_eq!(h.state().doc.path(), Some(target.as_path()));
    let back = SwpDocument::read(&target).unwrap();
    assert_eq!(back.curves[0].geometry, h.state().doc.swp.curves[0].geometry);
    assert!(!h.state().doc.is_modified());
    let _ = std::fs::remove_dir_all(dir);
}

/// #36, item 4: the title shows the file's name, with `*` while it has unsaved changes.
#[test]
fn the_title_shows_the_name_and_unsaved_changes() {
    let dir = tempfile_dir("title");
    let glass = copy_to(&dir, "swp/srev/wineglass.swp");
    let mut h = harness(app_in(&dir, None));
    assert_eq!(h.state().title(), "untitled — splinekit");
    h.state_mut().doc.add_point(DVec3::ZERO);
    h.step();
    assert_eq!(h.state().title(), "*untitled — splinekit");
    assert!(commands(&h).contains(&ViewportCommand::Title("*untitled — splinekit".to_owned())));
    h.state_mut().open_file(&glass);
    h.run();
    assert_eq!(h.state().title(), "wineglass.swp — splinekit");
    h.key_press(Key::S);
    h.run();
    assert_eq!(h.state().title(), "*wineglass.swp — splinekit");
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run();
    assert_eq!(h.state().title(), "wineglass.swp — splinekit");
    // what was saved re-opens to the document (but for where each object stands in the file)
    assert_eq!(without_positions(&SwpDocument::read(&glass).unwrap()), without_positions(&h.state().doc.swp));
    // undo of the edit after the save: modified again
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().title(), "*wineglass.swp — splinekit");
    let _ = std::fs::remove_dir_all(dir);
}

/// #36, item 4: closing the window with unsaved changes asks, and the process stays up;
/// Cancel keeps everything, Discard closes, Save writes the file and closes.
#[test]
fn closing_the_window_with_unsaved_changes_asks() {
    let dir = tempfile_dir("close");
    let glass = copy_to(&dir, "swp/srev/wineglass.swp");
    let bytes = std::fs::read(&glass).unwrap();
    let mut h = harness(app_in(&dir, Some(&glass)));
    // unmodified: the window closes at once
    request_close(&mut h);
    assert!(h.state().close_allowed() && h.state().prompt.is_none());
    assert!(!commands(&h).contains(&ViewportCommand::CancelClose));

    let mut h = harness(app_in(&dir, Some(&glass)));
    h.key_press(Key::S);
    h.run();
    request_close(&mut h);
    assert!(commands(&h).contains(&ViewportCommand::CancelClose), "the close is cancelled to ask");
    assert_eq!(h.state().prompt, Some(Pending::Close));
    h.run();
    h.get_by_label("Discard");
    click(&mut h, "Cancel");
    assert!(h.state().prompt.is_none() && !h.state().close_allowed());
    assert!(h.state().doc.is_modified(), "nothing was lost");
    request_close(&mut h);
    h.run();
    h.get_by_label("Discard").click();
    h.step();
    assert!(h.state().close_allowed());
    assert!(commands(&h).contains(&ViewportCommand::Close));
    assert_eq!(std::fs::read(&glass).unwrap(), bytes, "Discard writes nothing");

    // Save writes the document to its file, then closes
    let mut h = harness(app_in(&dir, Some(&glass)));
    h.key_press(Key::S);
    h.run();
    request_close(&mut h);
    h.run();
    click(&mut h, "Save");
    assert!(h.state().close_allowed());
    assert_ne!(std::fs::read(&glass).unwrap(), bytes);
    assert_eq!(SwpDocument::read(&glass).unwrap().curves[0].kind, h.state().doc.swp.curves[0].kind);
    let _ = std::fs::remove_dir_all(dir);
}

/// #36, item 4: Open, a dropped file, the preset scene and New ask before replacing a
/// modified document; Cancel keeps it, Discard goes on; a load is one undo step that brings
/// the replaced document back with its unsaved changes.
#[test]
fn open_drop_preset_and_new_ask_before_discarding_edits() {
    let dir = tempfile_dir("ask");
    let glass = copy_to(&dir, "swp/srev/wineglass.swp");
    let ico = copy_to(&dir, "obj/icosahedron.obj");
    type Trigger = fn(&mut Harness<'static, EditorApp>, &Path);
    let triggers: [(&str, Trigger, Pending); 4] = [
        ("Ctrl+O", |h, _| h.key_press_modifiers(Modifiers::COMMAND, Key::O), Pending::OpenDialog),
        (
            "drop",
            |h, f| h.input_mut().dropped_files.push(std::sync::Arc::new(Dropped(f.to_path_buf()))),
            Pending::Open(PathBuf::new()),
        ),
        ("r", |h, _| h.key_press(Key::R), Pending::Preset),
        ("Ctrl+N", |h, _| h.key_press_modifiers(Modifiers::COMMAND, Key::N), Pending::New),
    ];
    for (name, trigger, expected) in triggers {
        let mut h = harness(app_in(&dir, Some(&glass)));
        h.key_press(Key::S);
        h.run();
        let edited = h.state().doc.swp.clone();
        trigger(&mut h, &ico);
        h.run();
        let asked = h.state().prompt.clone();
        match (&asked, &expected) {
            (Some(Pending::Open(p)), Pending::Open(_)) => assert_eq!(p, &ico),
            _ => assert_eq!(asked.as_ref(), Some(&expected), "{name}"),
        }
        assert!(h.state().dialog.is_none(), "{name}: asked first");
        click(&mut h, "Cancel");
        assert_eq!(h.state().doc.swp, edited, "{name}: Cancel keeps the edits");
        assert_eq!(h.state().doc.path(), Some(glass.as_path()));

        trigger(&mut h, &ico);
        h.run();
        click(&mut h, "Discard");
        match expected {
            Pending::OpenDialog => {
                assert_eq!(dialog(&h).purpose, Purpose::Open, "{name}");
                choose(&mut h, &dir, "icosahedron.obj", "Open");
                assert_eq!(h.state().doc.kind(), DocKind::Mesh);
            }
            Pending::Open(_) => assert_eq!(h.state().doc.path(), Some(ico.as_path()), "{name}"),
            Pending::Preset => assert_eq!(h.state().doc.points().len(), 8, "{name}"),
            _ => assert!(h.state().doc.points().is_empty() && h.state().doc.path().is_none(), "{name}"),
        }
        assert!(!h.state().doc.is_modified(), "{name}");
        // one undo brings the edited wineglass back, unsaved changes and all
        h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
        h.run();
        assert_eq!(h.state().doc.swp, edited, "{name}: undo of the load");
        assert_eq!(h.state().doc.path(), Some(glass.as_path()), "{name}");
        assert_eq!(h.state().title(), "*wineglass.swp — splinekit", "{name}");
        assert!(h.state().mesh.is_none(), "{name}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// The Open dialog lists the recent files (most recent first); a click opens one.
#[test]
fn recent_files_in_the_open_dialog() {
    let dir = tempfile_dir("recent");
    let glass = copy_to(&dir, "swp/srev/wineglass.swp");
    let ico = copy_to(&dir, "obj/icosahedron.obj");
    let mut app = app_in(&dir, Some(&glass));
    app.open_file(&ico);
    let mut h = harness(app);
    click(&mut h, "Open…");
    assert_eq!(dialog(&h).recent, [ico.clone(), glass.clone()]);
    click(&mut h, &glass.display().to_string());
    assert!(h.state().dialog.is_none());
    assert_eq!(h.state().doc.path(), Some(glass.as_path()));
    // kept for the next session
    assert_eq!(RecentFiles::load_from(Some(dir.join("recent-files"))).list[0], glass);
    let _ = std::fs::remove_dir_all(dir);
}

/// Export mesh has its own dialog, and never writes the open document's file.
#[test]
fn export_never_targets_the_open_document() {
    let dir = tempfile_dir("export");
    let ico = copy_to(&dir, "obj/icosahedron.obj");
    let bytes = std::fs::read(&ico).unwrap();
    let mut h = harness(app_in(&dir, Some(&ico)));
    click(&mut h, "Export mesh…");
    assert_eq!(dialog(&h).purpose, Purpose::Export);
    choose(&mut h, &dir, "icosahedron.obj", "Export");
    assert!(dialog(&h).error.as_deref().unwrap().contains("open document's file"), "{:?}", dialog(&h).error);
    choose(&mut h, &dir, "out.ply", "Export");
    assert!(h.state().dialog.is_none());
    assert!(h.state().status.starts_with("Exported"), "{}", h.state().status);
    assert_eq!(splinekit_io::load_mesh(dir.join("out.ply")).unwrap().mesh.num_faces(), 20);
    assert_eq!(std::fs::read(&ico).unwrap(), bytes);
    let _ = std::fs::remove_dir_all(dir);
}

/// The dialog's shortcuts: Parent folder, Home, a folder entered by a click; after a refused
/// name the field has the focus again, so typing replaces it at once.
#[test]
fn the_dialog_walks_folders_and_keeps_the_name_field_ready() {
    let dir = tempfile_dir("walk");
    std::fs::create_dir_all(dir.join("inner")).unwrap();
    let mut h = four_points();
    click(&mut h, "Save as…");
    let d = h.state_mut().dialog.as_mut().unwrap();
    d.go_to(dir.join("inner"));
    h.run();
    click(&mut h, "Parent folder");
    assert_eq!(dialog(&h).dir, dir);
    click(&mut h, "inner/");
    assert_eq!(dialog(&h).dir, dir.join("inner"));
    if let Some(home) = splinekit_editor::files::home_dir() {
        click(&mut h, "Home");
        assert_eq!(dialog(&h).dir, home);
    }
    let d = h.state_mut().dialog.as_mut().unwrap();
    d.go_to(dir.clone());
    d.name = "mesh.obj".to_owned();
    h.run();
    h.key_press(Key::Enter);
    h.run();
    assert!(dialog(&h).error.is_some());
    // the field has the focus: select all, type a new name, Enter saves
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.event(egui::Event::Text("curve".to_owned()));
    h.run();
    h.key_press(Key::Enter);
    h.run();
    assert!(h.state().dialog.is_none(), "{:?}", h.state().dialog.as_ref().map(|d| (&d.name, &d.error)));
    assert!(dir.join("curve.swp").is_file());
    let _ = std::fs::remove_dir_all(dir);
}
