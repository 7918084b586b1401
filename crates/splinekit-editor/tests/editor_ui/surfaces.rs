//! Surfaces made in the UI (#37): `Revolve` about +z with the revolution tool's settings,
//! `Sweep` and `Lathe`, each with its controls (every change one undo step), and the
//! revolution tool's annotated OBJ opened as an editable document and saved back.

use splinekit_io::SwpSurfaceKind;
use splinekit_io::mesh::SplineHeader;

use super::*;

/// Four collinear clicks right of the axis: a straight Catmull-Rom segment, which the angle
/// tessellation keeps as its two end points, so a revolution about +z has 2 · slices
/// triangles.
fn straight_profile() -> Harness<'static, EditorApp> {
    let mut h = harness(EditorApp::new(None));
    for (x, y) in [(0.5, 0.0), (1.0, 0.5), (1.5, 1.0), (2.0, 1.5)] {
        let at = h.state().view.to_screen(DVec2::new(x, y));
        click_at(&mut h, at, Modifiers::SHIFT);
    }
    assert_eq!(h.state().doc.points().len(), 4);
    h
}

#[test]
fn revolve_about_z_with_the_revolution_tools_settings() {
    let dir = tempfile_dir("zrev");
    let mut h = straight_profile();
    click(&mut h, "+z");
    click(&mut h, "Revolve");
    // 32 slices (2π/32) of one straight piece
    assert_eq!(h.state_mut().surface_triangles(), 2 * 32);
    // ceil(2π / 0.5) = 13 slices
    type_value(&mut h, "surface slice tolerance", "0.5");
    assert_eq!(h.state_mut().surface_triangles(), 2 * 13);
    assert_eq!(h.state().view3d.num_triangles(), 2 * 13);
    type_value(&mut h, "surface scale", "3");
    let kind = h.state().doc.swp.surfaces[0].kind;
    assert_eq!(
        kind,
        SwpSurfaceKind::RevolutionZ {
            profile: 0,
            epsilon: splinekit_io::swp::DEFAULT_ZREV_EPSILON,
            slice_tolerance: 0.5,
            scale: 3.0
        }
    );
    // one undo step each
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert!(matches!(h.state().doc.swp.surfaces[0].kind, SwpSurfaceKind::RevolutionZ { scale: 1.0, .. }));
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Y);
    h.run();

    // Save as an annotated OBJ: the revolution tool's header, then the mesh
    let obj = dir.join("vase.obj");
    assert!(h.state_mut().save_to(&obj), "{}", h.state().status);
    let Some(SplineHeader::Revolution(header)) = SplineHeader::read(&obj).unwrap() else { panic!("no header") };
    assert_eq!((header.is_bspline, header.closed, header.scale, header.slice_tolerance), (false, false, 3.0, 0.5));
    assert_eq!(h.state().doc.kind(), splinekit_editor::DocKind::AnnotatedObj);
    assert!(!h.state().doc.is_modified());

    // opened again: the same curve and surface, editable; Save writes it back
    let mut g = harness(EditorApp::new(Some(&obj)));
    assert_eq!(g.state().doc.kind(), splinekit_editor::DocKind::AnnotatedObj);
    assert_eq!(g.state().doc.swp.surfaces[0].kind, kind);
    assert_eq!(g.state().doc.points(), h.state().doc.points());
    assert_eq!(g.state_mut().surface_triangles(), 2 * 13);
    type_value(&mut g, "vase slice tolerance", "0.25");
    // ceil(2π / 0.25) = 26 slices
    assert_eq!(g.state_mut().surface_triangles(), 2 * 26);
    g.key_press_modifiers(Modifiers::COMMAND, egui::Key::S);
    g.run();
    assert!(!g.state().doc.is_modified(), "{}", g.state().status);
    let Some(SplineHeader::Revolution(header)) = SplineHeader::read(&obj).unwrap() else { panic!("no header") };
    assert_eq!(header.slice_tolerance, 0.25);
    // the mesh stored after the header is the one shown
    let stored = splinekit_io::load_mesh(&obj).unwrap().mesh;
    assert_eq!(stored.num_faces(), 2 * 26);

    // a document the header cannot describe is refused, and nothing is written
    click(&mut g, "Lathe");
    let other = dir.join("two.obj");
    assert!(!g.state_mut().save_to(&other));
    assert!(g.state().status.contains("an annotated OBJ holds one surface"), "{}", g.state().status);
    assert!(!other.exists());
    let _ = std::fs::remove_dir_all(dir);
}

/// `Lathe`: new radius and height curves and the surface; stacks and slices follow the
/// count of a lathe with one pole (the radius starts at 0): 2·slices·stacks − slices.
#[test]
fn lathe_from_the_panel() {
    let mut h = harness(EditorApp::new(None));
    click(&mut h, "Lathe");
    let doc = &h.state().doc;
    assert_eq!(doc.swp.curves.len(), 3);
    assert_eq!(doc.swp.curves[doc.active].name.as_deref(), Some("radius"));
    assert_eq!(h.state_mut().surface_triangles(), 2 * 32 * 32 - 32);
    type_value(&mut h, "lathe stacks", "10");
    assert_eq!(h.state_mut().surface_triangles(), 2 * 32 * 10 - 32);
    type_value(&mut h, "lathe slices", "12");
    assert_eq!(h.state_mut().surface_triangles(), 2 * 12 * 10 - 12);
    // the radius is the y of its curve: a wider curve, a wider lathe
    let before = h.state_mut().surfaces().mesh.positions.iter().map(|p| p.truncate().length()).fold(0.0, f64::max);
    let last = h.state().doc.points().len() - 1;
    let p = h.state().doc.points()[last];
    h.state_mut().doc.begin_move();
    h.state_mut().doc.set_point(last, p + DVec3::new(0.0, 1.0, 0.0));
    h.run();
    let after = h.state_mut().surfaces().mesh.positions.iter().map(|p| p.truncate().length()).fold(0.0, f64::max);
    assert!((after - before - 1.0).abs() < 1e-9, "{before} → {after}");
}

/// `Sweep`: the active 2D curve swept along the other curve, the same mesh as the same
/// gcyl written by hand; its curves are chosen in the panel.
#[test]
fn sweep_from_the_panel() {
    let dir = tempfile_dir("sweep");
    let path = dir.join("parts.swp");
    let curves = "bsp2 ring 8 4 closed [0.2 0] [0 0.2] [-0.2 0] [0 -0.2]
                  bez3 path 12 4 [0 0 0] [1 0 1] [2 1 1] [3 1 0]
                  circ hoop 24 0.3
";
    std::fs::write(&path, curves).unwrap();
    let mut h = harness(EditorApp::new(Some(&path)));
    assert_eq!(h.state().doc.active, 0);
    click(&mut h, "Sweep");
    let by_hand = SwpDocument::parse(
        &format!(
            "{curves}gcyl sweep ring path
"
        ),
        "hand.swp",
    )
    .unwrap();
    let expected = by_hand.surface_mesh(0, &Default::default()).unwrap();
    assert_eq!(h.state().doc.swp.surfaces[0].kind, by_hand.surfaces[0].kind);
    assert_eq!(h.state_mut().surface_triangles(), expected.num_triangles());
    // another profile, chosen in the panel: the circle
    h.get_by_label("sweep profile").click();
    h.run();
    h.get_by_label("hoop").click();
    h.run();
    let by_hand = SwpDocument::parse(
        &format!(
            "{curves}gcyl sweep hoop path
"
        ),
        "hand.swp",
    )
    .unwrap();
    assert_eq!(h.state().doc.swp.surfaces[0].kind, by_hand.surfaces[0].kind);
    assert_eq!(
        h.state_mut().surface_triangles(),
        by_hand.surface_mesh(0, &Default::default()).unwrap().num_triangles()
    );
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert!(matches!(h.state().doc.swp.surfaces[0].kind, SwpSurfaceKind::GeneralizedCylinder { profile: 0, .. }));
    let _ = std::fs::remove_dir_all(dir);
}

/// A surface's own settings from the panel: a distance tolerance, rotation-minimizing frames,
/// round joins and no caps give the mesh the same options give, are one undo step each, and
/// are saved.
#[test]
fn surface_settings_from_the_panel() {
    let dir = tempfile_dir("settings");
    let path = dir.join("tube.swp");
    let curves = "circ ring 12 0.2\nbez3 path 10 4 [0 0 0] [1 0 1] [2 1 1] [3 1 0]\n";
    std::fs::write(&path, format!("{curves}gcyl tube ring path\n")).unwrap();
    let mut h = harness(EditorApp::new(Some(&path)));
    h.get_by_label("tube tessellation").click();
    h.run();
    h.get_by_label("distance").click();
    h.run();
    type_value(&mut h, "tube tolerance", "0.001");
    h.get_by_label("tube frames").click();
    h.run();
    h.get_by_label("rotation-minimizing").click();
    h.run();
    h.get_by_label("tube join").click();
    h.run();
    h.get_by_label("round").click();
    h.run();
    h.get_by_label("tube caps").click();
    h.run();
    let by_hand = SwpDocument::parse(
        &format!("{curves}gcyl tube ring path tolerance 0.001 frames rmf join round no-caps\n"),
        "h.swp",
    )
    .unwrap();
    assert_eq!(h.state().doc.swp.surfaces[0].settings, by_hand.surfaces[0].settings);
    let expected = by_hand.surface_mesh(0, &Default::default()).unwrap().num_triangles();
    assert_eq!(h.state_mut().surface_triangles(), expected);
    // undo the caps, then redo
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run();
    assert_eq!(h.state().doc.swp.surfaces[0].settings.caps, None);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Y);
    h.run();
    assert!(h.state_mut().save_swp(&path), "{}", h.state().status);
    let saved = std::fs::read_to_string(&path).unwrap();
    assert!(saved.contains("gcyl tube ring path tolerance 0.001 frames rmf no-caps join round"), "{saved}");
    let _ = std::fs::remove_dir_all(dir);
}

/// Counts the 3D view's pixels (outside the legend's corner) that `keep` accepts.
fn count_pixels(h: &mut Harness<'static, EditorApp>, keep: impl Fn([u8; 3]) -> bool) -> usize {
    let view = h.get_by_label("3D view").rect();
    let image = h.render().unwrap();
    let mut n = 0;
    for y in view.top() as u32..view.bottom() as u32 {
        for x in view.left() as u32..view.right() as u32 {
            let in_legend = x < view.left() as u32 + 230 && y > view.bottom() as u32 - 120;
            let p = image.get_pixel(x, y).0;
            if !in_legend && keep([p[0], p[1], p[2]]) {
                n += 1;
            }
        }
    }
    n
}

fn bluish(p: [u8; 3]) -> bool {
    i32::from(p[2]) > i32::from(p[0]) + 40
}

fn crimson(p: [u8; 3]) -> bool {
    i32::from(p[0]) > i32::from(p[1]) + 40 && i32::from(p[0]) > i32::from(p[2]) + 10
}

/// `Colour`: a torus about z shows negative Gaussian curvature (blue) inside and positive
/// (crimson) outside; a sphere is one colour under both curvatures; the UV checker shows its
/// two colours; back to shaded, neither.
#[test]
fn surfaces_coloured_by_curvature_and_a_uv_checker() {
    let dir = tempfile_dir("colour");
    let k = 0.552_284_75;
    let files = [
        (
            "torus.swp",
            "cr2 ring 8 4 closed [1 0] [1.5 -0.5] [2 0] [1.5 0.5]\nzrev torus ring slice-tolerance 0.1\n".to_owned(),
        ),
        (
            "ball.swp",
            format!(
                "bez2 half 10 7 [0 -1] [{k} -1] [1 -{k}] [1 0] [1 {k}] [{k} 1] [0 1]\nzrev ball half epsilon 0.05 slice-tolerance 0.1\n"
            ),
        ),
    ];
    for (name, text) in &files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let mut torus = harness(EditorApp::new(Some(&dir.join("torus.swp"))));
    let shaded_blue = count_pixels(&mut torus, bluish);
    torus.state_mut().colouring = splinekit_render::SurfaceColour::Curvature(splinekit_render::Curvature::Gaussian);
    torus.run();
    let (blue, red) = (count_pixels(&mut torus, bluish), count_pixels(&mut torus, crimson));
    assert!(blue > 1000 && red > 1000, "inside blue {blue}, outside crimson {red} (shaded: {shaded_blue} blue)");

    let mut ball = harness(EditorApp::new(Some(&dir.join("ball.swp"))));
    let mut least_red = usize::MAX;
    for curvature in [splinekit_render::Curvature::Mean, splinekit_render::Curvature::Gaussian] {
        ball.state_mut().colouring = splinekit_render::SurfaceColour::Curvature(curvature);
        ball.run();
        let (blue, red) = (count_pixels(&mut ball, bluish), count_pixels(&mut ball, crimson));
        assert!(red > 5000 && blue == 0, "{curvature:?}: a sphere is all positive: {red} crimson, {blue} blue");
        least_red = least_red.min(red);
    }
    ball.state_mut().colouring = splinekit_render::SurfaceColour::UvChecker;
    ball.run();
    let blue = count_pixels(&mut ball, bluish);
    let light = count_pixels(&mut ball, |p| p[0] > 150 && p[0].abs_diff(p[2]) < 20);
    assert!(blue > 2000 && light > 2000, "checker: {blue} steel blue, {light} light grey");
    // shaded: only the profile curve's red segments are crimson-ish
    ball.state_mut().colouring = splinekit_render::SurfaceColour::Shade;
    ball.run();
    let shaded = count_pixels(&mut ball, crimson);
    assert!(shaded * 10 < least_red, "shaded {shaded}, coloured {least_red}");
    torus.state_mut().colouring = splinekit_render::SurfaceColour::Curvature(splinekit_render::Curvature::Gaussian);
    // (the status line would name the temporary folder)
    torus.state_mut().status = "Colour: Gaussian curvature".to_owned();
    torus.run();
    torus.snapshot("torus_gaussian_curvature");
    let _ = std::fs::remove_dir_all(dir);
}

/// Schemes side by side: the icosahedron at level 2 by Loop and by butterfly (the same
/// counts: 162 vertices, 320 faces) and by √3 (180 faces), each view named after its scheme;
/// one camera (a drag in one view turns them all); Coarsen is disabled at level 0.
#[test]
fn schemes_compared_side_by_side() {
    use egui_kittest::kittest::NodeT as _;
    use splinekit::subdiv::Scheme;
    let mut h = harness(EditorApp::new(Some(&data("obj/icosahedron.obj"))));
    assert!(h.get_by_label("Coarsen subdivision").accesskit_node().is_disabled());
    for _ in 0..2 {
        h.get_by_label("Refine subdivision").click();
        h.run();
    }
    assert!(!h.get_by_label("Coarsen subdivision").accesskit_node().is_disabled());
    h.get_by_label("Compare schemes").click();
    h.run();
    h.get_by_label("compare Loop").click();
    h.run();
    // one scheme: still the single view
    h.get_by_label("3D view");
    h.get_by_label("compare Butterfly").click();
    h.get_by_label("compare √3").click();
    h.run();
    assert!(h.query_by_label("3D view").is_none());
    let counts = h.state().compare.counts();
    assert_eq!(counts[0], (Scheme::Loop, Ok((162, 320))));
    assert_eq!(counts[1], (Scheme::Butterfly, Ok((162, 320))));
    assert_eq!(counts[2].1.as_ref().map(|c| c.1), Ok(180));
    // a drag in the Loop view turns the butterfly view too
    let before = h.render().unwrap();
    let loop_view = h.get_by_label("Loop view").rect();
    let butterfly = h.get_by_label("Butterfly view").rect();
    h.drag_at(loop_view.center());
    h.run();
    h.hover_at(loop_view.center() + Vec2::new(60.0, 0.0));
    h.run();
    h.drop_at(loop_view.center() + Vec2::new(60.0, 0.0));
    h.run();
    let after = h.render().unwrap();
    let changed = |r: egui::Rect| {
        (r.top() as u32..r.bottom() as u32)
            .step_by(3)
            .flat_map(|y| (r.left() as u32..r.right() as u32).step_by(3).map(move |x| (x, y)))
            .filter(|&(x, y)| before.get_pixel(x, y) != after.get_pixel(x, y))
            .count()
    };
    assert!(changed(loop_view) > 100 && changed(butterfly) > 100, "{} {}", changed(loop_view), changed(butterfly));
    h.snapshot("compare_schemes");
}

/// A sweep-tool OBJ opens as its two B-splines and an xsweep surface (the same mesh as the
/// command line's rebuild: 12800 triangles for the doughnut); the scale typed in is saved back
/// into the file's header.
#[test]
fn a_sweep_tool_file_opens_editable_and_saves_back() {
    let dir = tempfile_dir("xsweep");
    let obj = dir.join("doughnut.obj");
    std::fs::copy(data("obj/cs4620-splines/doughnut.obj"), &obj).unwrap();
    let mut h = harness(EditorApp::new(Some(&obj)));
    assert_eq!(h.state().doc.kind(), splinekit_editor::DocKind::AnnotatedObj);
    assert_eq!(h.state().doc.swp.curves.len(), 2);
    assert!(matches!(h.state().doc.swp.surfaces[0].kind, SwpSurfaceKind::ToolSweep { .. }));
    assert_eq!(h.state_mut().surface_triangles(), 12800);
    type_value(&mut h, "doughnut scale", "0.5");
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::S);
    h.run();
    assert!(!h.state().doc.is_modified(), "{}", h.state().status);
    let Some(SplineHeader::Sweep(header)) = SplineHeader::read(&obj).unwrap() else { panic!("no sweep header") };
    assert_eq!(header.scale, 0.5);
    assert_eq!(header.cross_section.control_points.len(), 5);
    let _ = std::fs::remove_dir_all(dir);
}
