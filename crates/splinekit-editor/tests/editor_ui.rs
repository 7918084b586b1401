//! The editor driven like a user: clicks on labelled widgets, drags of `P2`, keys, and the
//! model checked after each step. Rendered headless with wgpu (Mesa lavapipe, or GL through
//! EGL); snapshots of the main states are in `tests/snapshots/` (`UPDATE_SNAPSHOTS=1` to
//! rewrite them).

use std::path::{Path, PathBuf};

use eframe::egui::{self, Modifiers, Pos2, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::{DVec2, DVec3};
use splinekit::{BezierCurve, KochanekBartels, Nurbs, ParamCurve, Tcb};
use splinekit_editor::EditorApp;
use splinekit_io::{SwpCurveKind, SwpDocument};

#[path = "editor_ui/files.rs"]
mod files;
#[path = "editor_ui/input.rs"]
mod input;
#[path = "editor_ui/surfaces.rs"]
mod surfaces;
#[path = "editor_ui/views.rs"]
mod views;

/// A test data file, relative to the package (the tests' working directory), so that the
/// snapshots showing the path do not depend on where the repository is.
fn data(rel: &str) -> PathBuf {
    Path::new("../splinekit-io/tests/data").join(rel)
}

/// A file dropped on the window (what winit gives eframe).
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }
    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

fn harness(app: EditorApp) -> Harness<'static, EditorApp> {
    let mut h = Harness::builder().with_size(Vec2::new(1200.0, 760.0)).wgpu().build_eframe(move |_cc| app);
    h.run();
    h
}

/// An editor with a Bézier curve of four points.
/// A fresh directory under the system's temporary directory.
fn tempfile_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("splinekit-editor-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The `.rs` files under `dir`, in its subfolders too (sorted).
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files.sort();
    files
}

fn four_points() -> Harness<'static, EditorApp> {
    let mut app = EditorApp::new(None);
    for (x, y) in [(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)] {
        app.doc.add_point(DVec3::new(x, y, 0.0));
    }
    harness(app)
}

fn center(h: &Harness<'_, EditorApp>, label: &str) -> Pos2 {
    h.get_by_label(label).rect().center()
}

fn click_at(h: &mut Harness<'_, EditorApp>, pos: Pos2, modifiers: Modifiers) {
    h.hover_at(pos);
    h.run();
    h.event(egui::Event::ModifiersChanged(modifiers));
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton { pos, button: egui::PointerButton::Primary, pressed, modifiers });
    }
    h.event(egui::Event::ModifiersChanged(Modifiers::NONE));
    h.run();
}

/// Drags from `from` by `delta` in three moves.
fn drag(h: &mut Harness<'_, EditorApp>, from: Pos2, delta: Vec2) {
    h.hover_at(from);
    h.run();
    h.drag_at(from);
    h.run();
    for k in 1..=3 {
        h.hover_at(from + delta * (k as f32 / 3.0));
        h.run();
    }
    h.drop_at(from + delta);
    h.run();
}

#[test]
fn dragging_p2_moves_the_model_exactly_as_dragged() {
    let mut h = four_points();
    let before = h.state().doc.points()[2];
    let from = center(&h, "P2");
    let delta = Vec2::new(30.0, -20.0);
    drag(&mut h, from, delta);
    let scale = h.state().view.scale;
    let after = h.state().doc.points()[2];
    // screen y is down, model y is up
    let expected = before + DVec3::new(30.0 / scale, 20.0 / scale, 0.0);
    assert!((after - expected).length() < 1e-12 * (1.0 + expected.length()), "{after} vs {expected}");
    // the other points did not move, and the label followed the point
    assert_eq!(h.state().doc.points()[1], DVec3::new(1.0, 2.0, 0.0));
    assert!((center(&h, "P2") - (from + delta)).length() < 0.5);
    // one drag is one undo step
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state().doc.points()[2], before);
}

#[test]
fn shift_click_adds_and_a_click_on_the_polygon_inserts() {
    let mut h = harness(EditorApp::new(None));
    assert!(h.query_by_label("P0").is_none());
    // in the 2D view, whatever the panels around it take
    let c = h.state().view.rect.center();
    let clicks = [
        c + Vec2::new(-120.0, 50.0),
        c + Vec2::new(-40.0, -50.0),
        c + Vec2::new(40.0, -50.0),
        c + Vec2::new(120.0, 50.0),
    ];
    for &p in &clicks {
        click_at(&mut h, p, Modifiers::SHIFT);
    }
    let app = h.state();
    assert_eq!(app.doc.points().len(), 4);
    for (i, &p) in clicks.iter().enumerate() {
        let m = app.view.to_model(p);
        assert!((app.doc.points()[i].truncate() - m).length() < 1e-9, "P{i}");
    }
    assert!(app.doc.spline().is_ok(), "four points make a Catmull-Rom segment");
    for (i, &click) in clicks.iter().enumerate() {
        assert!((center(&h, &format!("P{i}")) - click).length() < 0.5);
    }
    // a plain click on the middle of the edge P0–P1 inserts a point there, as P1
    let mid = clicks[0] + (clicks[1] - clicks[0]) * 0.5;
    click_at(&mut h, mid + Vec2::new(2.0, 2.0), Modifiers::NONE);
    let app = h.state();
    assert_eq!(app.doc.points().len(), 5);
    let m: DVec2 = app.view.to_model(mid + Vec2::new(2.0, 2.0));
    assert!((app.doc.points()[1].truncate() - m).length() < 1e-9);
    // a click far from the polygon adds nothing
    click_at(&mut h, c + Vec2::new(0.0, -200.0), Modifiers::NONE);
    assert_eq!(h.state().doc.points().len(), 5);
}

#[test]
fn closed_curves_insert_on_the_closing_edge() {
    let mut h = four_points();
    h.get_by_label("Closed").click();
    h.run();
    assert!(h.state().doc.curve().unwrap().closed);
    let (a, b) = (center(&h, "P3"), center(&h, "P0"));
    click_at(&mut h, a + (b - a) * 0.5, Modifiers::NONE);
    assert_eq!(h.state().doc.points().len(), 5);
    // inserted after P3, on the edge back to P0 (y = 0), to within the pixel clicked
    let y = h.state().doc.points()[4].y;
    assert!(y.abs() < 1.0 / h.state().view.scale, "{y}");
}

#[test]
fn delete_by_key_and_by_context_menu_then_undo_and_redo() {
    let mut h = four_points();
    h.get_by_label("P1").click();
    h.run();
    assert_eq!(h.state().view.selected, Some(1));
    h.key_press(egui::Key::Delete);
    h.run();
    assert_eq!(h.state().doc.points().len(), 3);
    assert_eq!(h.state().doc.points()[1], DVec3::new(3.0, 2.0, 0.0));
    // right-click P0, then "Delete point"
    let p0 = center(&h, "P0");
    h.hover_at(p0);
    h.run();
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: p0,
            button: egui::PointerButton::Secondary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    h.run();
    h.get_by_label("Delete point").click();
    h.run();
    assert_eq!(h.state().doc.points().len(), 2);
    h.get_by_label("Undo").click();
    h.run();
    h.get_by_label("Undo").click();
    h.run();
    assert_eq!(h.state().doc.points().len(), 4);
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, egui::Key::Z);
    h.run();
    assert_eq!(h.state().doc.points().len(), 3);
    h.get_by_label("Redo").click();
    h.run();
    assert_eq!(h.state().doc.points().len(), 2);
}

/// Picks the kind called `name` from the kind menu.
fn pick_kind(h: &mut Harness<'static, EditorApp>, name: &str) {
    h.get_by_label("Kind").click();
    h.run();
    h.get_by_label(name).click();
    h.run();
}

#[test]
fn kinds_switch_by_key_and_by_the_kind_menu() {
    let mut h = four_points();
    // a new document's curve is uniform Catmull-Rom: four clicks make a curve
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::CatmullRom { alpha: 0.0 });
    assert!(h.state().doc.spline().is_ok());
    h.key_press(egui::Key::S);
    h.run();
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::CatmullRom { alpha: 0.5 });
    pick_kind(&mut h, "Hermite");
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::Hermite);
    assert!(h.state().doc.spline().is_ok());
    assert_eq!(h.state().doc.points().len(), 4, "points kept");
}

#[test]
fn preset_key_gives_the_reference_scene_and_its_table() {
    let mut h = harness(EditorApp::new(None));
    h.key_press(egui::Key::R);
    h.run();
    assert_eq!(h.state().doc.points().len(), 8);
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::CatmullRom { alpha: 0.0 });
    h.get_by_label("Arc-length table").click();
    h.run();
    // SPEC §1.4: chord 5.06923, Gauss 5.14943, true 5.14760; row u = 0.4 has s = 0.35788
    h.get_by_label("chord 5.06923   Gauss 5.14943   true 5.14760");
    h.get_by_label("0.35788");
    // the toggles of the lab software
    h.key_press(egui::Key::A);
    h.key_press(egui::Key::L);
    h.key_press(egui::Key::N);
    h.run();
    let show = &h.state().view.show;
    assert!(show.markers && !show.polygon && show.normals);
    h.snapshot("preset_scene");
}

#[test]
fn every_bundled_swp_file_loads_and_shows_its_triangle_count() {
    let mut h = harness(EditorApp::new(None));
    let files = [
        "circles.swp",
        "core.swp",
        "srev/wineglass.swp",
        "srev/norm.swp",
        "gcyl/flircle.swp",
        "gcyl/florus.swp",
        "gcyl/gentorus.swp",
        "gcyl/tor.swp",
        "gcyl/weird.swp",
        "gcyl/weirder.swp",
        "extra/dragonfly.swp",
        "extra/tube-table.swp",
    ];
    for file in files {
        let path = data(&format!("swp/{file}"));
        assert!(h.state_mut().open_file(&path), "{file}");
        h.run();
        assert!(h.state().status.starts_with("Loaded"), "{file}: {}", h.state().status);
        let doc = SwpDocument::read(&path).unwrap();
        let triangles: usize =
            (0..doc.surfaces.len()).map(|i| doc.surface_mesh(i, &Default::default()).unwrap().num_triangles()).sum();
        h.get_by_label(&format!("Triangles: {triangles}"));
        // the 3D view shows every triangle that has finite corners
        assert_eq!(h.state().view3d.num_triangles(), triangles, "{file}");
        if file == "srev/wineglass.swp" {
            h.snapshot("wineglass_loaded");
        }
    }
}

#[test]
fn a_bad_file_leaves_the_document_unchanged_and_says_why() {
    let mut h = four_points();
    let dir = std::env::temp_dir().join(format!("splinekit-editor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.swp");
    std::fs::write(&bad, "bez2 p 4 [0 0] [1 1] [2 2]\n").unwrap();
    h.state_mut().open_file(&bad);
    h.run();
    let status = h.state().status.clone();
    assert!(status.starts_with("Error") && status.contains("bad.swp:1:"), "{status}");
    assert_eq!(h.state().doc.points().len(), 4);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn refine_a_loaded_icosahedron_to_level_two() {
    let mut h = harness(EditorApp::new(Some(&data("obj/icosahedron.obj"))));
    h.get_by_label("Faces: 20");
    h.get_by_label("Refine subdivision").click();
    h.run();
    h.get_by_label("Faces: 80");
    h.get_by_label("Refine subdivision").click();
    h.run();
    h.get_by_label("Faces: 320");
    assert_eq!(h.state().view3d.num_triangles(), 320);
    h.get_by_label("Coarsen subdivision").click();
    h.run();
    h.get_by_label("Faces: 80");
    assert_eq!(h.state().view3d.num_triangles(), 80);
    // colour by level gives the 3D view per-vertex colours; closing shows the document again
    h.get_by_label("Colour by level").click();
    h.run();
    assert_eq!(h.state().view3d.num_triangles(), 80);
    h.get_by_label("Close mesh").click();
    h.run();
    assert_eq!(h.state().view3d.num_triangles(), 0);
}

/// The wineglass with its profile active: dragging a profile point re-sweeps the surface in
/// the 3D view on every frame of the drag.
#[test]
fn the_surface_follows_a_dragged_point_live() {
    let mut h = harness(EditorApp::new(Some(&data("swp/srev/wineglass.swp"))));
    let g0 = h.state().view3d.generation();
    let from = center(&h, "P5");
    h.hover_at(from);
    h.run();
    h.drag_at(from);
    h.run();
    let mut last = h.state().view3d.generation();
    for k in 1..=3 {
        h.hover_at(from + Vec2::new(12.0 * k as f32, 0.0));
        h.run();
        let g = h.state().view3d.generation();
        assert!(g > last, "frame {k} of the drag: the 3D view was not given the new surface");
        last = g;
        // what the 3D view shows is the document's surface as it is now
        let swept = splinekit_editor::SweptSurfaces::sweep(&h.state().doc.swp);
        assert!(swept.errors.is_empty());
        assert_eq!(h.state().view3d.num_triangles(), swept.mesh.num_triangles());
        assert_eq!(h.state().view3d.bounds(), splinekit_editor::view3d::bounds(&swept.mesh));
    }
    h.drop_at(from + Vec2::new(36.0, 0.0));
    h.run();
    assert!(last > g0);
}

/// A 3D curve's control points are handles in the 3D view, dragged in the plane parallel to
/// the screen: the point's projection follows the pointer exactly and its depth stays.
#[test]
fn dragging_a_3d_point_in_the_3d_view_follows_the_pointer() {
    let dir = tempfile_dir("drag3d");
    let path = dir.join("helixish.swp");
    std::fs::write(&path, "bsp3 path 10 5\n[0 0 0]\n[1 0 1]\n[2 1 0]\n[3 0 1]\n[4 1 1]\n").unwrap();
    let mut h = harness(EditorApp::new(Some(&path)));
    assert!(h.state().status.starts_with("Loaded"), "{}", h.state().status);
    let before = h.state().doc.points()[2];
    let camera = *h.state().view3d.camera();
    let from = center(&h, "3D P2");
    let view = h.get_by_label("3D view").rect();
    let delta = Vec2::new(25.0, -15.0);
    drag(&mut h, from, delta);
    let after = h.state().doc.points()[2];
    assert_eq!(*h.state().view3d.camera(), camera, "a handle drag does not move the camera");
    let (p0, p1) = (camera.project(before, view).unwrap(), camera.project(after, view).unwrap());
    assert!(((p1 - p0) - delta).length() < 1e-3, "moved on screen by {:?}, dragged {delta:?}", p1 - p0);
    assert!((camera.depth(after) - camera.depth(before)).abs() < 1e-9 * (1.0 + camera.depth(before)));
    assert!((after - before).length() > 1e-3);
    // the other points stayed, and the drag is one undo step
    assert_eq!(h.state().doc.points()[1], DVec3::new(1.0, 0.0, 1.0));
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state().doc.points()[2], before);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_dropped_file_opens() {
    let mut h = harness(EditorApp::new(None));
    let path = data("obj/icosahedron.obj");
    h.input_mut().dropped_files.push(std::sync::Arc::new(Dropped(path.clone())));
    h.run();
    assert!(h.state().status.starts_with("Loaded"), "{}", h.state().status);
    h.get_by_label("Faces: 20");
    assert_eq!(h.state().view3d.num_triangles(), 20);
    assert_eq!(h.state().doc.path(), Some(path.as_path()));
    assert_eq!(h.state().title(), "icosahedron.obj — splinekit");
}

#[test]
fn w_and_n_switch_the_3d_overlays_and_f_fits() {
    let mut h = harness(EditorApp::new(Some(&data("swp/srev/wineglass.swp"))));
    let fitted = *h.state().view3d.camera();
    h.key_press(egui::Key::W);
    h.run();
    assert!(h.state().view3d.settings.wireframe);
    h.key_press(egui::Key::N);
    h.run();
    assert!(h.state().view3d.settings.normals && h.state().view.show.normals);
    h.key_press(egui::Key::N);
    h.run();
    assert!(!h.state().view3d.settings.normals && !h.state().view.show.normals);
    h.state_mut().view3d.camera_mut().distance *= 5.0;
    h.key_press(egui::Key::F);
    h.run();
    assert!((h.state().view3d.camera().distance - fitted.distance).abs() < 1e-9 * fitted.distance);
}

#[test]
fn the_empty_editor_and_its_help() {
    let mut h = harness(EditorApp::new(None));
    h.key_press(egui::Key::H);
    h.run();
    h.get_by_label("cycle the spline kind");
    h.snapshot("empty_with_help");
}

/// Clicks the widget labelled `label` and lets the editor react.
fn click(h: &mut Harness<'static, EditorApp>, label: &str) {
    h.get_by_label(label).click();
    h.run();
}

#[test]
fn catmull_clark_from_the_scheme_menu() {
    let mut h = harness(EditorApp::new(Some(&data("obj/icosahedron.obj"))));
    click(&mut h, "Scheme");
    click(&mut h, "Catmull-Clark");
    click(&mut h, "Refine subdivision");
    // 20 triangles → 60 quads (one per corner), 12 + 30 + 20 vertices; two triangles a quad in 3D
    h.get_by_label("Faces: 60");
    h.get_by_label("Level 1: 62 vertices");
    assert_eq!(h.state().view3d.num_triangles(), 120);
    click(&mut h, "Refine subdivision");
    h.get_by_label("Faces: 240");
    assert_eq!(h.state().view3d.num_triangles(), 480);
    click(&mut h, "Coarsen subdivision");
    h.get_by_label("Faces: 60");
}

/// A cube whose top face (z = 1) is an infinitely sharp crease loop with sharp corners, as
/// OpenSubdiv's OBJ tags (0-based vertices); `triangles` splits each quad in two for Loop.
fn creased_cube(triangles: bool) -> String {
    let mut text = String::from("v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n");
    for [a, b, c, d] in [[1, 3, 4, 2], [5, 6, 8, 7], [1, 2, 6, 5], [3, 7, 8, 4], [1, 5, 7, 3], [2, 4, 8, 6]] {
        if triangles {
            text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        } else {
            text += &format!("f {a} {b} {c} {d}\n");
        }
    }
    text + "t crease 5/1 4 5 7 6 4 10\nt corner 4/1 4 5 6 7 10\n"
}

/// The vertices of `mesh` on the cube's top rim (z = 1, |x| = 1 or |y| = 1).
fn on_top_rim(mesh: &splinekit::TriMesh) -> usize {
    let near = |x: f64, y: f64| (x - y).abs() < 1e-12;
    mesh.positions.iter().filter(|p| near(p.z, 1.0) && (near(p.x.abs(), 1.0) || near(p.y.abs(), 1.0))).count()
}

#[test]
fn creases_from_the_obj_are_kept_by_loop_and_catmull_clark() {
    let dir = tempfile_dir("creases");
    for (scheme, triangles) in [("Catmull-Clark", false), ("Loop", true)] {
        let file = dir.join(format!("cube-{scheme}.obj"));
        std::fs::write(&file, creased_cube(triangles)).unwrap();
        let mut h = harness(EditorApp::new(Some(&file)));
        assert!(h.state().status.contains("4 creased edges and 4 creased vertices"), "{}", h.state().status);
        if scheme == "Catmull-Clark" {
            click(&mut h, "Scheme");
            click(&mut h, "Catmull-Clark");
        }
        // the sharp top loop stays a square with 4·2ⁿ vertices, level after level
        for level in 1..=2 {
            click(&mut h, "Refine subdivision");
            let shown = h.state().mesh.as_ref().unwrap().shown();
            assert_eq!(on_top_rim(&shown), 4 << level, "{scheme} level {level}");
            assert!(shown.positions.iter().all(|p| p.z <= 1.0 + 1e-12), "{scheme} level {level}");
        }
        click(&mut h, "Coarsen subdivision");
        assert_eq!(on_top_rim(&h.state().mesh.as_ref().unwrap().shown()), 8, "{scheme} coarsened");
        // √3 has no creases: the rim is rounded off, and the status says the tags are left out
        click(&mut h, "Scheme");
        click(&mut h, "√3");
        assert!(h.state().status.contains("crease tags are left out"), "{}", h.state().status);
        if triangles {
            click(&mut h, "Refine subdivision");
            assert_eq!(on_top_rim(&h.state().mesh.as_ref().unwrap().shown()), 0, "√3 without creases");
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn sqrt3_doo_sabin_and_butterfly_from_the_scheme_menu() {
    let mut h = harness(EditorApp::new(Some(&data("obj/icosahedron.obj"))));
    click(&mut h, "Scheme");
    click(&mut h, "√3");
    click(&mut h, "Refine subdivision");
    // √3: a vertex per face, each triangle → 3 (F → 3F, V → V + F)
    h.get_by_label("Faces: 60");
    h.get_by_label("Level 1: 32 vertices");
    assert_eq!(h.state().view3d.num_triangles(), 60);
    click(&mut h, "Refine subdivision");
    h.get_by_label("Faces: 180");
    h.get_by_label("Level 2: 92 vertices");

    // Doo-Sabin starts again from the loaded mesh: a vertex per face corner (60), a face per
    // face, edge and vertex (20 triangles + 30 quads + 12 pentagons = 62; 116 triangles in 3D)
    click(&mut h, "Scheme");
    click(&mut h, "Doo-Sabin");
    h.get_by_label("Level 0: 12 vertices");
    click(&mut h, "Refine subdivision");
    h.get_by_label("Faces: 62");
    h.get_by_label("Level 1: 60 vertices");
    assert_eq!(h.state().view3d.num_triangles(), 116);
    click(&mut h, "Coarsen subdivision");
    h.get_by_label("Faces: 20");

    // Butterfly: Loop's counts (V + E, 4F), the loaded vertices kept where they are
    click(&mut h, "Scheme");
    click(&mut h, "Butterfly");
    click(&mut h, "Refine subdivision");
    h.get_by_label("Faces: 80");
    h.get_by_label("Level 1: 42 vertices");
    assert_eq!(h.state().view3d.num_triangles(), 80);
}

/// #40: the scheme menu offers every scheme of the core's `Scheme`, in its order and by its
/// titles, and each refines the loaded mesh as `subdiv::subdivide` does (the same vertex and
/// face counts at levels 1 and 2).
#[test]
fn every_core_scheme_is_in_the_menu_and_refines_as_subdivide() {
    use splinekit::subdiv::{Creases, Scheme, SubdivisionOptions, subdivide};
    let file = data("obj/icosahedron.obj");
    let base = splinekit_io::load_mesh(&file).unwrap().mesh;
    let mut h = harness(EditorApp::new(Some(&file)));
    assert!(h.query_by_label(Scheme::Bilinear.title()).is_none(), "the menu is closed");
    click(&mut h, "Scheme");
    // the menu's entries, top to bottom, in the core's order (the lowest of a title's nodes:
    // the shown scheme's title is on the closed box above the menu too)
    let tops: Vec<f32> = Scheme::ALL
        .iter()
        .map(|s| h.get_all_by_label(s.title()).map(|n| n.rect().top()).fold(f32::MIN, f32::max))
        .collect();
    assert!(tops.windows(2).all(|w| w[0] < w[1]), "{:?}: {tops:?}", Scheme::ALL);
    h.key_press(egui::Key::Escape);
    h.run();
    for scheme in Scheme::ALL {
        click(&mut h, "Scheme");
        click(&mut h, scheme.title());
        assert_eq!(h.state().mesh.as_ref().unwrap().scheme, scheme);
        for level in 1..=2 {
            click(&mut h, "Refine subdivision");
            let direct = subdivide(&base, level, scheme, &SubdivisionOptions::DEFAULT, &Creases::default()).unwrap();
            let m = h.state().mesh.as_ref().unwrap();
            assert_eq!(m.level, level, "{scheme}: {}", h.state().status);
            let (faces, vertices) = (direct.mesh.num_faces(), direct.mesh.num_vertices());
            assert_eq!((m.faces(), m.vertices()), (faces, vertices), "{scheme} level {level}");
            h.get_by_label(&format!("Faces: {faces}"));
        }
    }
}

/// #40: a non-manifold mesh (three triangles on one edge), which the interactive Loop levels
/// refuse, is refined by Loop as `subdiv::subdivide` refines it.
#[test]
fn a_nonmanifold_mesh_refines_by_loop() {
    use splinekit::subdiv::{Creases, Scheme, SubdivisionOptions, subdivide};
    let dir = tempfile_dir("nonmanifold");
    let file = dir.join("book.obj");
    std::fs::write(&file, "v 0 0 0\nv 0 0 1\nv 1 0 0\nv -1 0 0\nv 0 1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\n").unwrap();
    let base = splinekit_io::load_mesh(&file).unwrap().mesh;
    let mut h = harness(EditorApp::new(Some(&file)));
    click(&mut h, "Refine subdivision");
    let direct = subdivide(&base, 1, Scheme::Loop, &SubdivisionOptions::DEFAULT, &Creases::default()).unwrap();
    let m = h.state().mesh.as_ref().unwrap();
    assert_eq!((m.level, m.faces(), m.vertices()), (1, 12, direct.mesh.num_vertices()), "{}", h.state().status);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn sqrt3_of_a_quad_mesh_is_an_error_on_the_status_line() {
    let cube = std::env::temp_dir().join(format!("splinekit-editor-cube-{}.obj", std::process::id()));
    std::fs::write(
        &cube,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
         f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n",
    )
    .unwrap();
    let mut h = harness(EditorApp::new(Some(&cube)));
    std::fs::remove_file(&cube).unwrap();
    click(&mut h, "Scheme");
    click(&mut h, "√3");
    click(&mut h, "Refine subdivision");
    assert!(h.state().status.starts_with("Error: "), "{}", h.state().status);
    assert!(h.state().status.contains("triangle"), "{}", h.state().status);
    h.get_by_label("Level 0: 8 vertices");
}

/// #36: messages in words that follow the kind, and nothing the user sees points at a
/// document they do not have.
#[test]
fn curve_messages_are_in_words_and_follow_the_kind() {
    let mut app = EditorApp::new(None);
    app.doc.set_kind(SwpCurveKind::Bezier);
    for k in 0..5 {
        app.doc.add_point(DVec3::new(f64::from(k), f64::from(k % 2), 0.0));
    }
    let mut h = harness(app);
    h.get_by_label("profile: a Bézier spline needs 4, 7, 10, … points; this one has 5");
    h.key_press(egui::Key::S);
    h.run();
    assert_eq!(h.state().status, "Kind: B-spline");
    assert!(h.query_by_label_contains("needs").is_none(), "5 points make a B-spline");
    h.get_by_label("Closed").click();
    h.run();
    h.key_press(egui::Key::S);
    h.key_press(egui::Key::S);
    h.key_press(egui::Key::S);
    h.run();
    assert_eq!(h.state().status, "Kind: Hermite");
    // the user-visible strings of the editor: no "SPEC §" (users do not have that document)
    let sources = rust_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    assert!(sources.iter().any(|f| f.ends_with("src/lib.rs")), "the editor's source files: {sources:?}");
    for file in &sources {
        let text = std::fs::read_to_string(file).unwrap();
        let file = file.display();
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            assert!(!code.contains("SPEC"), "{file}:{}: {line}", n + 1);
        }
    }
}

/// #36: usable at 800×600 (the file bar and panels inside the window), panels hidden from the
/// View menu give the 3D view the room, and both views frame the scene again after a resize,
/// a load, Close mesh and Undo of Preset.
#[test]
fn usable_at_800_by_600_with_panels_to_hide_and_views_that_refit() {
    let app = EditorApp::new(Some(&data("swp/srev/wineglass.swp")));
    let mut h = Harness::builder().with_size(Vec2::new(800.0, 600.0)).wgpu().build_eframe(move |_cc| app);
    h.run();
    h.snapshot("small_window");
    let window = egui::Rect::from_min_size(Pos2::ZERO, Vec2::new(800.0, 600.0));
    for label in ["New", "Open…", "Save", "Save as…", "Export mesh…", "Undo", "Preset", "View", "Help", "3D view"]
    {
        let r = h.get_by_label(label).rect();
        assert!(window.contains_rect(r), "{label} at {r:?}");
    }
    let narrow = h.get_by_label("3D view").rect().width();
    click(&mut h, "View");
    click(&mut h, "Show 2D view");
    h.key_press(egui::Key::Escape);
    h.run();
    assert!(!h.state().layout.view2d);
    let wide = h.get_by_label("3D view").rect().width();
    assert!(wide > narrow + 200.0, "{narrow} → {wide}");
    // switching the 3D view off too leaves the 2D view on
    click(&mut h, "View");
    click(&mut h, "Show 3D view");
    h.key_press(egui::Key::Escape);
    h.run();
    assert!(h.state().layout.view2d && !h.state().layout.view3d);
    h.state_mut().layout = splinekit_editor::Layout::default();
    h.run();

    // a resize frames the 2D view again
    h.state_mut().view.scale *= 7.0;
    h.set_size(Vec2::new(900.0, 650.0));
    h.run();
    let fitted = h.state().view.scale;
    h.state_mut().view.fit_pending = true;
    h.run();
    assert!((h.state().view.scale - fitted).abs() < 1e-9 * fitted, "the resize fitted the view");
    // Undo of the preset scene frames the wineglass again
    h.key_press(egui::Key::R);
    h.run();
    h.state_mut().view.scale *= 7.0;
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert!((h.state().view.scale - fitted).abs() < 1e-9 * fitted, "{} vs {fitted}", h.state().view.scale);
}

/// #36: a click on a Bézier spline's control polygon splits that segment by De Casteljau:
/// three points more, the curve keeps its shape and stays valid.
#[test]
fn a_click_on_a_bezier_polygon_splits_the_segment() {
    let mut app = EditorApp::new(None);
    app.doc.set_kind(SwpCurveKind::Bezier);
    for (x, y) in [(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)] {
        app.doc.add_point(DVec3::new(x, y, 0.0));
    }
    let mut h = harness(app);
    let before = h.state().doc.spline().unwrap();
    let (a, b) = (center(&h, "P1"), center(&h, "P2"));
    click_at(&mut h, a + (b - a) * 0.5, Modifiers::NONE);
    let doc = &h.state().doc;
    assert_eq!(doc.points().len(), 7);
    let after = doc.spline().expect("still a valid Bézier spline");
    // the middle edge at its middle is parameter 1/2 (to the pixel clicked); the left half's
    // first inner point is P0 + u·(P1 − P0) with P0 = (0, 0), P1 = (1, 2): u is its x
    use splinekit::ParamCurve as _;
    let u = doc.points()[1].x;
    assert!((u - 0.5).abs() < 0.01, "{u}");
    assert!((doc.points()[3] - before.eval(u)).length() < 1e-12, "the new point is on the curve");
    assert_eq!(h.state().view.selected, Some(3));
    // the halves are the old curve over [0, u] and [u, 1]
    for k in 0..=20 {
        let v = f64::from(k) / 20.0;
        assert!((after.eval(v) - before.eval(v * u)).length() < 1e-12, "left half at {v}");
        assert!((after.eval(1.0 + v) - before.eval(u + v * (1.0 - u))).length() < 1e-12, "right half at {v}");
    }
}

/// #37 (first slice): every curve of the document in both views. `core.swp` has four curves
/// (two 2D, two 3D): the 2D view draws the three that are not active, dimmed, and a click on
/// one makes it active; the 3D view draws all four (its pixels differ from an empty
/// document's), and `Draw normals` adds frames along every curve in 3D.
#[test]
fn every_curve_is_drawn_in_2d_and_3d() {
    let mut empty = harness(EditorApp::new(None));
    let mut h = harness(EditorApp::new(Some(&data("swp/core.swp"))));
    assert_eq!(h.state().doc.swp.curves.len(), 4);
    assert_eq!(h.state().view.other_curves_drawn(), 3);
    // one polyline a segment: each curve has one
    assert_eq!(h.state().view3d.overlay_lines(), 4);
    let view = h.get_by_label("3D view").rect();
    let (a, b) = (h.render().unwrap(), empty.render().unwrap());
    // the harness draws one pixel a point
    let differing = (view.min.y as u32..view.max.y as u32)
        .flat_map(|y| (view.min.x as u32..view.max.x as u32).map(move |x| (x, y)))
        .filter(|&(x, y)| x < a.width() && y < a.height() && a.get_pixel(x, y) != b.get_pixel(x, y))
        .count();
    assert!(differing > 500, "{differing} pixels of the 3D view differ from an empty document's");
    click(&mut h, "Draw normals");
    // T, N and B at 9 places along each of the 4 curves
    assert_eq!(h.state().view3d.overlay_lines(), 4 + 4 * 9 * 3);
    click(&mut h, "Draw normals");
    // a click on the B-spline (x from −3 to −1, y from 0 to 1) makes it the active curve
    let app = h.state();
    let c = app.doc.swp.curves[1].to_curve().unwrap();
    use splinekit::ParamCurve as _;
    let p = c.eval(0.5);
    let at = app.view.to_screen(DVec2::new(p.x, p.y));
    click_at(&mut h, at, Modifiers::NONE);
    assert_eq!(h.state().doc.active, 1);
    assert_eq!(h.state().doc.points().len(), 4, "no point was added");
    // Draw curves off: only the active curve in 2D, nothing over the 3D view
    click(&mut h, "Draw curves");
    assert_eq!(h.state().view.other_curves_drawn(), 0);
    assert_eq!(h.state().view3d.overlay_lines(), 0);
    // Draw surface: off hides the surface of the wineglass
    let mut g = harness(EditorApp::new(Some(&data("swp/srev/wineglass.swp"))));
    let shown = g.render().unwrap();
    click(&mut g, "Draw surface");
    assert!(!g.state().view3d.settings.surface);
    let hidden = g.render().unwrap();
    let view = g.get_by_label("3D view").rect();
    let centre = view.center();
    assert_ne!(
        shown.get_pixel(centre.x as u32, centre.y as u32),
        hidden.get_pixel(centre.x as u32, centre.y as u32),
        "the glass's middle is drawn, then not"
    );
}

/// Types `value` into the value widget labelled `label` (click, select all, type, Enter).
fn type_value(h: &mut Harness<'static, EditorApp>, label: &str, value: &str) {
    h.get_by_label(label).click();
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text(value.to_owned()));
    h.key_press(egui::Key::Enter);
    h.run();
}

/// #37: the CS 4620 workflow: draw a profile, `Revolve`, change the slices and the profile's
/// steps: the triangle count follows 2 · slices · (samples − 1) (a profile off the axis:
/// no poles), each change one undo step; the document saves and re-opens the same.
#[test]
fn draw_a_profile_revolve_it_and_change_its_slices() {
    let dir = tempfile_dir("revolve");
    let mut h = harness(EditorApp::new(None));
    // four clicks right of the axis: a Catmull-Rom spline of one segment
    for (x, y) in [(0.5, 0.0), (1.0, 0.5), (1.5, 1.0), (2.0, 2.0)] {
        let at = h.state().view.to_screen(DVec2::new(x, y));
        click_at(&mut h, at, Modifiers::SHIFT);
    }
    assert_eq!(h.state().doc.points().len(), 4);
    assert!(h.state().doc.spline().is_ok());
    click(&mut h, "Revolve");
    // 16 steps a segment: 17 samples; 32 slices
    assert_eq!(h.state_mut().surface_triangles(), 2 * 32 * 16);
    h.get_by_label(&format!("Triangles: {}", 2 * 32 * 16));
    assert!(h.state().view3d.num_triangles() == 2 * 32 * 16);
    type_value(&mut h, "surface slices", "40");
    assert_eq!(h.state_mut().surface_triangles(), 2 * 40 * 16);
    type_value(&mut h, "surface steps", "10");
    assert_eq!(h.state_mut().surface_triangles(), 2 * 40 * 10);
    assert_eq!(h.state().view3d.num_triangles(), 2 * 40 * 10);
    // each change is one undo step
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state_mut().surface_triangles(), 2 * 40 * 16);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state_mut().surface_triangles(), 2 * 32 * 16);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Y);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Y);
    h.run();
    // saved and re-opened: the same document and surface
    let path = dir.join("revolved.swp");
    assert!(h.state_mut().save_swp(&path), "{}", h.state().status);
    let back = splinekit_editor::Document::read(&path).unwrap();
    let mut reopened = EditorApp::new(Some(&path));
    assert_eq!(reopened.surface_triangles(), 2 * 40 * 10);
    assert_eq!(back.swp.surfaces.len(), 1);
    let _ = std::fs::remove_dir_all(dir);
}

/// #37: the selected point's coordinates typed in (one undo step), the pointer's coordinates
/// read out over the 2D view, and a grid step of 1, 2 or 5 times a power of ten.
#[test]
fn typed_coordinates_and_the_pointer_readout() {
    let mut h = four_points();
    assert!(h.query_by_label("Point x").is_none(), "nothing selected yet");
    h.get_by_label("P1").click();
    h.run();
    h.get_by_label("Selected P1");
    type_value(&mut h, "Point x", "2.5");
    assert_eq!(h.state().doc.points()[1], DVec3::new(2.5, 2.0, 0.0));
    type_value(&mut h, "Point y", "-1.25");
    assert_eq!(h.state().doc.points()[1], DVec3::new(2.5, -1.25, 0.0));
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state().doc.points()[1], DVec3::new(2.5, 2.0, 0.0), "one undo step per value typed");
    // the readout follows the pointer
    let c = h.state().view.rect.center() + Vec2::new(30.0, -20.0);
    h.hover_at(c);
    h.run();
    let expected = h.state().view.to_model(c);
    assert_eq!(h.state().view.pointer, Some(expected));
    for (min, step) in [(0.3, 0.5), (1.0, 1.0), (1.01, 2.0), (3.0, 5.0), (7.0, 10.0), (0.0004, 0.0005)] {
        let got = splinekit_editor::view2d::grid_step(min);
        assert!((got - step).abs() < 1e-12 * step, "{min}: {got}");
    }
}

/// #41: the kind menu offers Kochanek–Bartels and Bessel–Overhauser; a TCB key's tension,
/// continuity and bias are typed in the point panel (clamped to [−1, 1], one undo step each)
/// and the curve follows at once.
#[test]
fn tcb_shapes_are_edited_per_key_and_bessel_overhauser_is_a_kind() {
    let mut h = four_points();
    let before = h.state().doc.spline().unwrap();
    pick_kind(&mut h, "Kochanek–Bartels (TCB)");
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::KochanekBartels);
    assert_eq!(h.state().doc.points().len(), 4, "points kept");
    // every shape 0: the same curve as the uniform Catmull-Rom one it was
    let zero = h.state().doc.spline().unwrap();
    assert!((zero.eval(0.5) - before.eval(0.5)).length() < 1e-15);
    assert!(h.query_by_label("Tension").is_none(), "no key selected yet");
    h.get_by_label("P1").click();
    h.run();
    type_value(&mut h, "Tension", "0.5");
    type_value(&mut h, "Bias", "3");
    assert_eq!(h.state().doc.shape(1), Some(Tcb::new(0.5, 0.0, 1.0)), "typed values, clamped to [-1, 1]");
    let points = h.state().doc.points().to_vec();
    let mut shapes = [Tcb::default(); 4];
    shapes[1] = Tcb::new(0.5, 0.0, 1.0);
    let expected = KochanekBartels::new(&points, &shapes, false).unwrap().to_piecewise();
    let shaped = h.state().doc.spline().unwrap();
    assert!((shaped.eval(0.3) - expected.eval(0.3)).length() < 1e-15);
    assert!((shaped.eval(0.3) - zero.eval(0.3)).length() > 1e-3, "the curve follows the shape");
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state().doc.shape(1), Some(Tcb::new(0.5, 0.0, 0.0)), "one undo step per value typed");
    // saved as tcb2 and read back
    let text = h.state().doc.to_swp_string();
    assert!(text.contains("tcb2 profile 16 4\n"), "{text}");
    assert!(text.contains(" 0.5 0 0]\n"), "{text}");
    pick_kind(&mut h, "Bessel–Overhauser");
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::BesselOverhauser);
    assert!(h.state().doc.spline().is_ok());
    assert!(h.query_by_label("Tension").is_none(), "only Kochanek–Bartels keys have a shape");
}

/// #41: the kind menu offers NURBS and a single Bézier curve of any degree; a NURBS point's
/// weight is typed in the point panel (one undo step), the degree in the curve panel, and the
/// knot vector the curve uses is shown; the curve follows at once and saves as nurbs2.
#[test]
fn nurbs_weights_degree_and_knots_and_one_bezier_of_any_degree() {
    let mut h = four_points();
    pick_kind(&mut h, "NURBS");
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::Nurbs { degree: 3 });
    let points = h.state().doc.points().to_vec();
    assert_eq!(points.len(), 4, "points kept");
    // weights 1 over the clamped knots: the cubic Bézier curve of the four points
    let bezier = BezierCurve::new(points.clone()).unwrap();
    let plain = h.state().doc.spline().unwrap();
    assert!((plain.eval(0.3) - bezier.eval(0.3)).length() < 1e-14);
    h.get_by_label("Knots (default): 0 0 0 0 1 1 1 1");
    assert!(h.query_by_label("Weight").is_none(), "no point selected yet");
    h.get_by_label("P1").click();
    h.run();
    type_value(&mut h, "Weight", "4");
    assert_eq!(h.state().doc.weight(1), Some(4.0));
    let expected = Nurbs::new(3, points.clone(), vec![1.0, 4.0, 1.0, 1.0], None).unwrap();
    let weighted = h.state().doc.spline().unwrap();
    assert!((weighted.eval(0.3) - expected.eval(0.3)).length() < 1e-15);
    assert!((weighted.eval(0.3) - plain.eval(0.3)).length() > 1e-2, "the curve follows the weight");
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state().doc.weight(1), Some(1.0), "one undo step per value typed");
    type_value(&mut h, "Degree", "2");
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::Nurbs { degree: 2 });
    h.get_by_label("Knots (default): 0 0 0 1 2 2 2");
    let text = h.state().doc.to_swp_string();
    assert!(text.contains("nurbs2 profile 16 4 degree 2\n[0 0 1]\n"), "{text}");
    // a single Bézier curve of degree 3 through the same points; never closed
    pick_kind(&mut h, "Bézier (one curve, any degree)");
    assert_eq!(h.state().doc.curve().unwrap().kind, SwpCurveKind::BezierN);
    assert!((h.state().doc.spline().unwrap().eval(0.7) - bezier.eval(0.7)).length() < 1e-15);
    assert!(h.query_by_label("Weight").is_none(), "only NURBS points have a weight");
    h.get_by_label("Closed").click();
    h.run();
    assert!(!h.state().doc.curve().unwrap().closed, "a single Bézier curve stays open");
    h.state_mut().doc.add_point(DVec3::new(5.0, 1.0, 0.0));
    let five = h.state().doc.spline().unwrap();
    assert!((five.eval(1.0) - DVec3::new(5.0, 1.0, 0.0)).length() < 1e-15, "degree 4 now, ending at the new point");
}

/// #37: a click on a 3D curve's handle in the 3D view selects it (highlighted there, its
/// coordinates in the panel, z too), and typing its z moves it there.
#[test]
fn a_click_on_a_3d_handle_selects_it_and_its_z_can_be_typed() {
    let dir = tempfile_dir("select3d");
    let path = dir.join("path.swp");
    std::fs::write(&path, "bsp3 path 10 5\n[0 0 0]\n[1 0 1]\n[2 1 0]\n[3 0 1]\n[4 1 1]\n").unwrap();
    let mut h = harness(EditorApp::new(Some(&path)));
    let camera = *h.state().view3d.camera();
    h.get_by_label("3D P2").click();
    h.run();
    assert_eq!(h.state().view.selected, Some(2));
    assert_eq!(*h.state().view3d.camera(), camera, "a click on a handle does not orbit");
    assert_eq!(h.state().doc.points()[2], DVec3::new(2.0, 1.0, 0.0), "a click does not move it");
    h.get_by_label("Selected P2");
    type_value(&mut h, "Point z", "3");
    assert_eq!(h.state().doc.points()[2], DVec3::new(2.0, 1.0, 3.0));
    let _ = std::fs::remove_dir_all(dir);
}

/// A number is applied when typed in full (Enter), not at each key: typing "0.005" into a
/// tolerance does not first sweep at "0" (the smallest tolerance, a surface far too large,
/// whose progress line used to move the field from under the cursor and end the typing).
#[test]
fn typed_numbers_apply_on_enter_not_at_each_key() {
    let dir = tempfile_dir("typed");
    let path = dir.join("tube.swp");
    std::fs::write(
        &path,
        "circ ring 12 0.2\nbez3 path 8 4 [0 0 0] [1 0 0.5] [2 1 0] [3 1 0.5]\ngcyl tube ring path tolerance 0.01\n",
    )
    .unwrap();
    let mut h = harness(EditorApp::new(Some(&path)));
    h.run();
    let before = h.state_mut().surface_triangles();
    assert!(before > 0, "{}", h.state().status);
    h.get_by_label("tube tolerance").click();
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("0".to_owned()));
    h.run();
    assert_eq!(h.state_mut().surface_triangles(), before, "a half-typed number was applied");
    h.event(egui::Event::Text(".002".to_owned()));
    h.key_press(egui::Key::Enter);
    h.run();
    let after = h.state_mut().surface_triangles();
    assert!(after > before, "{before} → {after}");
    assert!(h.state().doc.swp.to_swp_string().contains("gcyl tube ring path tolerance 0.002"));
    let _ = std::fs::remove_dir_all(dir);
}

/// A read-only file is not replaced by Save, and the message names the editor's way out
/// (Save as), not the command line's flag.
#[test]
fn saving_over_a_read_only_file_is_refused_with_the_editors_way_out() {
    let dir = tempfile_dir("readonly");
    let path = dir.join("locked.swp");
    let text = "bez2 c 4 4 [0 0] [1 1] [2 1] [3 0]\n";
    std::fs::write(&path, text).unwrap();
    let mut perms = std::fs::metadata(&path).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&path, perms).unwrap();
    let mut app = EditorApp::new(Some(&path));
    assert!(!app.save_swp(&path));
    assert!(app.status.contains("read-only") && app.status.contains("Save as"), "{}", app.status);
    assert!(!app.status.contains("--force"), "{}", app.status);
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
    let mut perms = std::fs::metadata(&path).unwrap().permissions();
    #[allow(clippy::permissions_set_readonly_false)]
    perms.set_readonly(false);
    std::fs::set_permissions(&path, perms).unwrap();
    let _ = std::fs::remove_dir_all(dir);
}

/// A value typed and left with Tab is applied (the field commits when it loses focus), and
/// the next field starts from its own value.
#[test]
fn a_typed_value_left_with_tab_is_applied() {
    let mut h = four_points();
    h.get_by_label("P1").click();
    h.run();
    h.get_by_label("Point x").click();
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("3.25".to_owned()));
    h.run();
    h.key_press(egui::Key::Tab);
    h.run();
    h.run();
    assert_eq!(h.state().doc.points()[1], DVec3::new(3.25, 2.0, 0.0));
    h.event(egui::Event::Text("-0.5".to_owned()));
    h.key_press(egui::Key::Tab);
    h.run();
    h.run();
    assert_eq!(h.state().doc.points()[1], DVec3::new(3.25, -0.5, 0.0));
}
