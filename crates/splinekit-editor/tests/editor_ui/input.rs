//! Hands and keys (#36): a drag that starts on a point moves it however fast the pointer
//! moves, and every key press and typed character of a slow frame counts, in order.

use egui::{Event, Key, PointerButton};
use splinekit_editor::doc::KINDS;

use super::*;

fn press(pos: Pos2, pressed: bool) -> Event {
    Event::PointerButton { pos, button: PointerButton::Primary, pressed, modifiers: Modifiers::NONE }
}

fn key(key: Key, modifiers: Modifiers) -> [Event; 2] {
    [true, false].map(|pressed| Event::Key { key, physical_key: None, pressed, repeat: false, modifiers })
}

/// #36, item 5: press on P2, move 100 points and release, all in one frame: P2 moves by
/// exactly that, the view does not pan, and the drag is one undo step.
#[test]
fn a_fast_drag_from_a_point_moves_the_point() {
    let mut h = four_points();
    let before = h.state().doc.points()[2];
    let center_before = h.state().view.center;
    let from = center(&h, "P2");
    let delta = Vec2::new(100.0, -40.0);
    h.event(Event::PointerMoved(from));
    h.event(press(from, true));
    h.event(Event::PointerMoved(from + delta));
    h.event(press(from + delta, false));
    h.run();
    let scale = h.state().view.scale;
    let after = h.state().doc.points()[2];
    let expected = before + DVec3::new(100.0 / scale, 40.0 / scale, 0.0);
    assert!((after - expected).length() < 1e-9, "{after} vs {expected}");
    assert_eq!(h.state().view.center, center_before, "the view did not pan");
    assert!(!h.state().view.is_dragging());
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().doc.points()[2], before);

    // press and a long move in one frame, more moves in later frames, then the release
    let from = center(&h, "P1");
    let before = h.state().doc.points()[1];
    h.event(Event::PointerMoved(from));
    h.event(press(from, true));
    h.event(Event::PointerMoved(from + Vec2::new(60.0, 0.0)));
    h.run();
    for k in 1..=3 {
        h.event(Event::PointerMoved(from + Vec2::new(60.0, 10.0 * k as f32)));
        h.run();
    }
    h.event(press(from + Vec2::new(60.0, 30.0), false));
    h.run();
    let scale = h.state().view.scale;
    let expected = before + DVec3::new(60.0 / scale, -30.0 / scale, 0.0);
    assert!((h.state().doc.points()[1] - expected).length() < 1e-9);
    assert_eq!(h.state().view.center, center_before);
    // a click on a point selects it and records no undo step
    let p0 = center(&h, "P0");
    h.event(Event::PointerMoved(p0));
    h.event(press(p0, true));
    h.event(press(p0, false));
    h.run();
    assert_eq!(h.state().view.selected, Some(0));
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().doc.points()[1], before, "the undo undid the drag, not a click");
}

/// The same for a 3D curve's handle in the 3D view: the camera stays, the handle follows.
#[test]
fn a_fast_drag_of_a_3d_handle_moves_it() {
    let dir = tempfile_dir("fast3d");
    let path = dir.join("path.swp");
    std::fs::write(&path, "bsp3 path 10 5\n[0 0 0]\n[1 0 1]\n[2 1 0]\n[3 0 1]\n[4 1 1]\n").unwrap();
    let mut h = harness(EditorApp::new(Some(&path)));
    let before = h.state().doc.points()[2];
    let camera = *h.state().view3d.camera();
    let view = h.get_by_label("3D view").rect();
    let from = center(&h, "3D P2");
    let delta = Vec2::new(70.0, 30.0);
    h.event(Event::PointerMoved(from));
    h.event(press(from, true));
    h.event(Event::PointerMoved(from + delta));
    h.event(press(from + delta, false));
    h.run();
    assert_eq!(*h.state().view3d.camera(), camera, "the camera did not orbit");
    let after = h.state().doc.points()[2];
    let (p0, p1) = (camera.project(before, view).unwrap(), camera.project(after, view).unwrap());
    assert!(((p1 - p0) - delta).length() < 1e-3, "moved on screen by {:?}, dragged {delta:?}", p1 - p0);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run();
    assert_eq!(h.state().doc.points()[2], before, "one undo step");
    let _ = std::fs::remove_dir_all(dir);
}

/// #36, item 6: several presses of one key in one slow frame act several times, in order.
#[test]
fn every_key_press_of_a_slow_frame_counts() {
    let mut h = four_points();
    let start = KINDS.iter().position(|(k, _)| *k == h.state().doc.curve().unwrap().kind).unwrap();
    for _ in 0..3 {
        for e in key(Key::S, Modifiers::NONE) {
            h.event(e);
        }
    }
    h.run();
    assert_eq!(h.state().doc.curve().unwrap().kind, KINDS[(start + 3) % KINDS.len()].0);
    // `a` twice in one frame: on, then off again; `l` once: off
    for k in [Key::A, Key::A, Key::L] {
        for e in key(k, Modifiers::NONE) {
            h.event(e);
        }
    }
    h.run();
    assert!(!h.state().view.show.markers && !h.state().view.show.polygon);
    // two undos in one frame undo two kind changes
    for _ in 0..2 {
        for e in key(Key::Z, Modifiers::COMMAND) {
            h.event(e);
        }
    }
    h.run();
    assert_eq!(h.state().doc.curve().unwrap().kind, KINDS[(start + 1) % KINDS.len()].0);
    // Ctrl reported as `ctrl` alone counts as the command key too
    h.key_press_modifiers(Modifiers::CTRL, Key::N);
    h.run();
    assert_eq!(h.state().prompt, Some(splinekit_editor::Pending::New));
}

/// #36, item 6: characters typed into the Save as dialog's name field just before a click on
/// Save, in the same frame, are all kept (the file was once saved as `typed_trial2.sw`).
#[test]
fn characters_typed_just_before_a_click_are_kept() {
    let dir = tempfile_dir("typed");
    let mut h = four_points();
    h.get_by_label("Save as…").click();
    h.run();
    let d = h.state_mut().dialog.as_mut().unwrap();
    d.go_to(dir.clone());
    d.name.clear();
    h.run();
    let save = center(&h, "Save");
    for c in "typed_trial2.swp".chars() {
        h.event(Event::Text(c.to_string()));
    }
    h.event(Event::PointerMoved(save));
    h.event(press(save, true));
    h.event(press(save, false));
    h.run();
    assert!(h.state().dialog.is_none(), "{:?}", h.state().dialog.as_ref().map(|d| &d.name));
    assert!(dir.join("typed_trial2.swp").is_file(), "{}", h.state().status);
    assert!(!dir.join("typed_trial2.sw").exists());
    let _ = std::fs::remove_dir_all(dir);
}

/// The wineglass with `steps` steps a profile segment and `slices` slices, as a file in `dir`.
fn big_glass(dir: &Path, steps: u32, slices: u32) -> PathBuf {
    let text = std::fs::read_to_string(data("swp/srev/wineglass.swp")).unwrap();
    let text = text.replacen("bsp2 profile 8 26", &format!("bsp2 profile {steps} 26"), 1).replacen(
        "srev wineglass 90",
        &format!("srev wineglass {slices}"),
        1,
    );
    let path = dir.join(format!("big-{steps}-{slices}.swp"));
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs frames until `done` (at most 60 s), sleeping a little between frames as a window
/// waiting for its worker would.
fn run_until(h: &mut Harness<'static, EditorApp>, what: &str, done: impl Fn(&EditorApp) -> bool) {
    let start = std::time::Instant::now();
    while !done(h.state()) {
        assert!(start.elapsed().as_secs() < 60, "{what}: still waiting after 60 s");
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    h.run();
}

/// #36: a surface over 200 000 triangles is swept off the UI thread with a progress line and
/// a Cancel; while a point is dragged it is shown at reduced resolution, and in full again
/// after the release.
#[test]
fn big_surfaces_are_swept_in_the_background_and_previewed_while_dragging() {
    let dir = tempfile_dir("big-sweep");
    let path = big_glass(&dir, 16, 700);
    let full = splinekit_editor::SweptSurfaces::sweep(&SwpDocument::read(&path).unwrap()).mesh.num_triangles();
    assert!(full > 500_000, "{full}");
    let app = EditorApp::new(Some(&path));
    let mut h = Harness::builder().with_size(Vec2::new(1200.0, 760.0)).wgpu().build_eframe(move |_cc| app);
    // the first frames show the progress line while the worker sweeps (a spinner: frames keep coming)
    h.run_steps(3);
    assert!(h.state().is_sweeping());
    h.get_by_label("Cancel");
    assert!(h.query_by_label_contains("Sweeping 0.5 M triangles").is_some());
    run_until(&mut h, "the full sweep", |app| !app.is_sweeping());
    assert_eq!(h.state().view3d.num_triangles(), full);
    h.get_by_label(&format!("Triangles: {full}"));

    // a drag: a preview of at most about 200 000 triangles on every frame of it
    let from = center(&h, "P5");
    h.event(Event::PointerMoved(from));
    h.event(press(from, true));
    h.run();
    for k in 1..=3 {
        h.event(Event::PointerMoved(from + Vec2::new(0.0, 6.0 * k as f32)));
        h.run();
        let shown = h.state().view3d.num_triangles();
        assert!(shown <= 110_000 && shown > 50_000, "frame {k}: {shown} triangles");
        assert!(h.query_by_label_contains("Preview:").is_some());
    }
    h.event(press(from + Vec2::new(0.0, 18.0), false));
    h.step();
    h.step();
    run_until(&mut h, "the sweep after the release", |app| !app.is_sweeping() && app.view3d.num_triangles() == full);
    assert_eq!(h.state().view3d.num_triangles(), full);
    let now = splinekit_editor::SweptSurfaces::sweep(&h.state().doc.swp);
    assert_eq!(h.state().view3d.bounds(), splinekit_editor::view3d::bounds(&now.mesh), "the moved point's surface");

    // the count asked for by a program is the whole surface's, even during a drag's preview
    h.event(Event::PointerMoved(from + Vec2::new(0.0, 18.0)));
    h.event(press(from + Vec2::new(0.0, 18.0), true));
    h.event(Event::PointerMoved(from + Vec2::new(0.0, 30.0)));
    h.run();
    assert!(h.state().view3d.num_triangles() <= 110_000);
    let whole = splinekit_editor::SweptSurfaces::sweep(&h.state().doc.swp).mesh.num_triangles();
    assert_eq!(h.state_mut().surface_triangles(), whole);
    h.event(press(from + Vec2::new(0.0, 30.0), false));
    h.step();
    h.step();
    run_until(&mut h, "after the second drag", |app| !app.is_sweeping());

    // Cancel stops a sweep; the status says the surface shown is not the curves' (a surface
    // of 5.5 M triangles, so the sweep is surely still running when Cancel is clicked)
    let huge = big_glass(&dir, 40, 3000);
    assert!(h.state_mut().open_file(&huge));
    h.step();
    assert!(h.state().is_sweeping(), "{}", h.state().status);
    h.step();
    h.get_by_label("Cancel").click();
    h.step();
    assert!(!h.state().is_sweeping());
    assert!(h.state().status.starts_with("Cancelled the sweep"), "{}", h.state().status);
    let _ = std::fs::remove_dir_all(dir);
}

/// A closed torus of `n × m` quads, each split in two triangles, as OBJ text, after `padding`
/// bytes of comment lines.
fn torus_obj(n: usize, m: usize, padding: usize) -> String {
    let mut text = String::new();
    while text.len() < padding {
        text.push_str("# padding to make a large file, as a scanned mesh with a long header would be\n");
    }
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (std::f64::consts::TAU * i as f64 / n as f64, std::f64::consts::TAU * j as f64 / m as f64);
            let r = 2.0 + 0.5 * v.cos();
            text.push_str(&format!("v {} {} {}\n", r * u.cos(), r * u.sin(), 0.5 * v.sin()));
        }
    }
    let id = |i: usize, j: usize| (i % n) * m + (j % m) + 1;
    for i in 0..n {
        for j in 0..m {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            text.push_str(&format!("f {a} {b} {c}\nf {a} {c} {d}\n"));
        }
    }
    text
}

/// #36: a large mesh file is read on a worker thread (progress line and Cancel in the status
/// bar), and a subdivision level of more than 200 000 faces is made on one too.
#[test]
fn big_files_open_and_levels_refine_in_the_background() {
    let dir = tempfile_dir("big-mesh");
    let padded = dir.join("padded.obj");
    std::fs::write(&padded, torus_obj(16, 12, 4_200_000)).unwrap();
    let app = EditorApp::new(Some(&padded));
    // opened on a worker thread: the editor starts with the file still being read
    assert!(app.is_loading());
    assert!(app.status.starts_with("Opening"), "{}", app.status);
    let mut h = Harness::builder().with_size(Vec2::new(1200.0, 760.0)).wgpu().build_eframe(move |_cc| app);
    run_until(&mut h, "opening the padded file", |app| !app.is_loading());
    h.get_by_label("Faces: 384");
    assert_eq!(h.state().view3d.num_triangles(), 384);
    assert_eq!(h.state().title(), "padded.obj — splinekit");

    let torus = dir.join("torus.obj");
    std::fs::write(&torus, torus_obj(180, 150, 0)).unwrap();
    assert!(h.state_mut().open_file(&torus));
    h.run();
    h.get_by_label("Faces: 54000");
    h.get_by_label("Refine subdivision").click();
    h.step();
    assert!(h.state().is_refining());
    assert!(h.query_by_label_contains("Refining to 216000 triangles").is_some());
    run_until(&mut h, "refining", |app| !app.is_refining());
    h.get_by_label("Faces: 216000");
    assert_eq!(h.state().view3d.num_triangles(), 216_000);
    click(&mut h, "Coarsen subdivision");
    h.get_by_label("Faces: 54000");
    click(&mut h, "Refine subdivision");
    h.get_by_label("Faces: 216000");
    // colouring the levels of so many faces is made on a worker thread too
    h.get_by_label("Colour by level").click();
    h.step();
    assert!(h.state().is_refining());
    run_until(&mut h, "colouring", |app| !app.is_refining());
    h.get_by_label("Faces: 216000");
    let shown = h.state().mesh.as_ref().unwrap().shown();
    assert!(!shown.colors.is_empty() && shown.colors.len() == shown.positions.len(), "coloured by level");
    // exporting it too; the file has what the 3D view shows
    let out = dir.join("level1.ply");
    h.state_mut().export(&out);
    assert!(h.state().is_exporting());
    run_until(&mut h, "exporting", |app| !app.is_exporting());
    assert!(h.state().status.starts_with("Exported"), "{}", h.state().status);
    assert_eq!(splinekit_io::load_mesh(&out).unwrap().mesh.num_faces(), 216_000);
    h.get_by_label("Colour by level").click();
    h.step();
    run_until(&mut h, "colouring", |app| !app.is_refining());

    // Catmull-Clark: the first level in the background (162 000 quads); the second (648 000)
    // cancelled while it is made: level 1 stays
    click(&mut h, "Scheme");
    click(&mut h, "Catmull-Clark");
    h.get_by_label("Refine subdivision").click();
    h.step();
    assert!(h.state().is_refining());
    run_until(&mut h, "Catmull-Clark level 1", |app| !app.is_refining());
    h.get_by_label("Faces: 162000");
    h.get_by_label("Refine subdivision").click();
    h.step();
    assert!(h.state().is_refining());
    h.get_by_label("Cancel").click();
    h.run();
    assert!(!h.state().is_refining());
    assert!(h.state().status.starts_with("Cancelled: Refining"), "{}", h.state().status);
    h.get_by_label("Faces: 162000");
    // V + E + F = 27 000 + 81 000 + 54 000
    h.get_by_label("Level 1: 162000 vertices");
    let _ = std::fs::remove_dir_all(dir);
}

/// Every click of a slow frame counts, with the modifiers it was made with: four Shift+clicks
/// in one frame, Shift released before the frame ends (as `xdotool` sends them to a window
/// that draws slowly), add four points.
#[test]
fn every_click_of_a_slow_frame_counts() {
    let mut h = harness(EditorApp::new(None));
    let at: Vec<Pos2> = [(0.5, 0.0), (1.0, 0.5), (1.5, 1.0), (2.0, 2.0)]
        .iter()
        .map(|&(x, y)| h.state().view.to_screen(DVec2::new(x, y)))
        .collect();
    for &p in &at {
        h.event(Event::ModifiersChanged(Modifiers::SHIFT));
        h.event(Event::PointerMoved(p));
        for pressed in [true, false] {
            h.event(Event::PointerButton {
                pos: p,
                button: PointerButton::Primary,
                pressed,
                modifiers: Modifiers::SHIFT,
            });
        }
        h.event(Event::ModifiersChanged(Modifiers::NONE));
    }
    h.run();
    let app = h.state();
    assert_eq!(app.doc.points().len(), 4);
    for (i, &p) in at.iter().enumerate() {
        assert!((app.doc.points()[i].truncate() - app.view.to_model(p)).length() < 1e-9, "P{i}");
    }
}
