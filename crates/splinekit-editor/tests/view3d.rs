//! The 3D view in egui_kittest: snapshots of shaded meshes (wgpu on whatever adapter the
//! machine has, lavapipe on CI), pixels where they mean something, and the camera controls.

use std::path::PathBuf;

use eframe::egui::{self, Modifiers, MouseWheelSource, MouseWheelUnit, PointerButton, TouchPhase, pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;
use glam::DVec3;
use splinekit::TriMesh;
use splinekit::subdiv::{LoopOptions, LoopPyramid};
use splinekit_editor::view3d::{
    BACK_COLOUR, BACKGROUND, FRONT_COLOUR, ORBIT_RADIANS_PER_POINT, View3d, ZOOM_PER_POINT,
};

const W: f32 = 240.0;
const H: f32 = 180.0;

/// Hosts one [`View3d`], optionally under a row of the settings' checkboxes.
struct TestApp {
    view: View3d,
    settings_panel: bool,
}

impl eframe::App for TestApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if self.settings_panel {
            egui::Panel::top("settings").show(ui, |ui| {
                ui.horizontal_wrapped(|ui| self.view.settings.ui(ui));
            });
        }
        self.view.ui(ui, frame);
    }
}

fn harness(mesh: &TriMesh, settings_panel: bool) -> Harness<'static, TestApp> {
    let mesh = mesh.clone();
    let mut harness = Harness::builder().with_size(vec2(W, H)).wgpu().build_eframe(move |cc| {
        assert!(cc.wgpu_render_state.is_some(), "kittest's wgpu renderer gives the app a render state");
        let mut view = View3d::new();
        view.set_mesh(&mesh);
        TestApp { view, settings_panel }
    });
    harness.run();
    harness
}

/// The bundled icosahedron (the course's file, HTML lines and all), on the unit sphere:
/// outward, counter-clockwise seen from outside.
fn icosahedron() -> TriMesh {
    let loaded = splinekit_io::load_mesh(data("obj/icosahedron.obj")).expect("bundled icosahedron");
    let mut mesh = loaded.mesh.to_tri_mesh();
    for p in &mut mesh.positions {
        *p = p.normalize();
    }
    assert_eq!(mesh.num_triangles(), 20);
    assert!(mesh.signed_volume() > 0.0 && mesh.is_closed_oriented());
    mesh
}

/// The same surface inside out: reversed triangles, reversed normals.
fn flipped(mesh: &TriMesh) -> TriMesh {
    let mut out = mesh.clone();
    for t in &mut out.triangles {
        t.swap(1, 2);
    }
    for n in &mut out.normals {
        *n = -*n;
    }
    out
}

fn data(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data").join(path)
}

fn swp_surface(path: &str) -> TriMesh {
    swp_surface_with(path, &splinekit_io::surface::SurfaceOptions::default())
}

fn swp_surface_with(path: &str, options: &splinekit_io::surface::SurfaceOptions) -> TriMesh {
    let doc = splinekit_io::SwpDocument::read(&data(path)).unwrap();
    doc.surface_mesh(0, options).unwrap()
}

/// Grey-blue, lit or in shadow.
fn is_front_colour([r, g, b, _]: [u8; 4]) -> bool {
    let [r, g, b] = [r, g, b].map(i32::from);
    b > r + 15 && g >= r
}

/// Orange-red: well away from the grey-blue front, the background and the wireframe.
fn is_back_colour([r, g, b, _]: [u8; 4]) -> bool {
    let [r, g, b] = [r, g, b].map(i32::from);
    r > b + 60 && r > g + 30
}

/// The pixel at the centre of the view (the view fills the window).
fn centre_pixel(harness: &mut Harness<'_, TestApp>) -> [u8; 4] {
    let image = harness.render().unwrap();
    let (w, h) = image.dimensions();
    image.get_pixel(w / 2, h / 2).0
}

#[test]
fn icosahedron_front_faces_and_wireframe() {
    let mut harness = harness(&icosahedron(), false);
    harness.state_mut().view.settings.wireframe = true;
    harness.run();
    let pixel = centre_pixel(&mut harness);
    assert!(is_front_colour(pixel), "front colour (grey-blue) in the centre, got {pixel:?}");
    harness.snapshot("view3d_icosahedron_wireframe");
}

#[test]
fn inside_out_icosahedron_shows_back_faces() {
    let mut harness = harness(&flipped(&icosahedron()), false);
    harness.run();
    let pixel = centre_pixel(&mut harness);
    assert!(is_back_colour(pixel), "back colour (orange-red) in the centre, got {pixel:?}");
    harness.snapshot("view3d_icosahedron_inside_out");

    // Without the back-face colour the inside-out mesh looks like the normal one.
    harness.state_mut().view.settings.show_backfaces_colour = false;
    harness.run();
    let pixel = centre_pixel(&mut harness);
    assert!(is_front_colour(pixel), "front colour once back faces are not singled out, got {pixel:?}");
}

#[test]
fn flat_shading_and_normals() {
    let mut harness = harness(&icosahedron(), false);
    let view = &mut harness.state_mut().view;
    view.settings.smooth = false;
    view.settings.normals = true;
    harness.run();
    harness.snapshot("view3d_icosahedron_flat_normals");
}

#[test]
fn revolution_surface_from_swp() {
    let mut harness = harness(&swp_surface("swp/srev/wineglass.swp"), false);
    let pixel = centre_pixel(&mut harness);
    assert!(is_front_colour(pixel), "front colour in the centre, got {pixel:?}");
    harness.snapshot("view3d_wineglass");
}

#[test]
fn open_twisted_horn_shows_its_inside_in_the_back_colour() {
    // without its caps (on by default), so that its inside shows
    let mut options = splinekit_io::surface::SurfaceOptions::default();
    options.sweep.caps = false;
    let mut harness = harness(&swp_surface_with("swp/ext/scale-twist.swp", &options), false);
    harness.state_mut().view.settings.wireframe = true;
    harness.run();
    harness.snapshot("view3d_horn");
    let image = harness.render().unwrap();
    let back = image.pixels().filter(|p| is_back_colour(p.0)).count();
    assert!(back > 100, "the inside of the horn shows back faces ({back} pixels)");
}

#[test]
fn generalized_cylinder_from_swp() {
    let mut harness = harness(&swp_surface("swp/gcyl/gentorus.swp"), false);
    harness.run();
    harness.snapshot("view3d_gentorus");
}

#[test]
fn loop_levels_in_colour() {
    let base = splinekit::PolyMesh::from(&icosahedron());
    let options = LoopOptions { color_by_level: true, ..LoopOptions::default() };
    let mesh = LoopPyramid::new(&base, options).unwrap().into_refined(2, |_| {}).unwrap().into_tri_mesh();
    assert_eq!(mesh.colors.len(), mesh.positions.len());
    let mut harness = harness(&mesh, false);
    harness.state_mut().view.settings.wireframe = true;
    harness.run();
    harness.snapshot("view3d_loop_levels");
}

#[test]
fn settings_checkboxes_switch_the_overlay() {
    let mut harness = harness(&icosahedron(), true);
    assert!(!harness.state().view.settings.wireframe);
    harness.get_by_label("Wireframe").click();
    harness.run();
    assert!(harness.state().view.settings.wireframe);
    harness.get_by_label("Normals").click();
    harness.run();
    assert!(harness.state().view.settings.normals);
    harness.remove_cursor();
    harness.run();
    harness.snapshot("view3d_with_settings");
}

#[test]
fn empty_mesh_renders_background_only() {
    let mut harness = harness(&TriMesh::default(), false);
    // the axes and grid (of a unit scene about the origin) are drawn over it
    let with_guides = harness.render().unwrap();
    let settings = &mut harness.state_mut().view.settings;
    (settings.axes, settings.grid) = (false, false);
    harness.run();
    let image = harness.render().unwrap();
    assert_ne!(with_guides, image);
    let [r, g, b, _] = BACKGROUND.to_array();
    assert!(image.pixels().all(|p| p.0 == [r, g, b, 255]), "only the background");
    let camera = *harness.state().view.camera();
    assert!(camera.distance.is_finite() && camera.target.is_finite());

    // A mesh arriving later is framed.
    harness.state_mut().view.set_mesh(&icosahedron());
    harness.run();
    let pixel = centre_pixel(&mut harness);
    assert!(is_front_colour(pixel), "the icosahedron appears, got {pixel:?}");
}

#[test]
fn broken_meshes_do_not_panic() {
    let mut mesh = icosahedron();
    mesh.triangles.push([0, 1, 99]);
    mesh.positions.push(DVec3::NAN);
    mesh.triangles.push([0, 1, 12]);
    mesh.normals = vec![DVec3::Y; 3]; // wrong length: ignored
    let mut harness = harness(&mesh, false);
    assert_eq!(harness.state().view.num_triangles(), 20);
    // A single point: no area, no extent.
    let point = TriMesh { positions: vec![DVec3::ONE; 3], triangles: vec![[0, 1, 2]], ..TriMesh::default() };
    harness.state_mut().view.set_mesh(&point);
    harness.state_mut().view.fit();
    harness.run();
    let camera = *harness.state().view.camera();
    assert!(camera.distance.is_finite() && camera.distance > 0.0);
    harness.render().unwrap();
}

/// A view in a zero-size space renders nothing and does not panic.
#[test]
fn zero_size_view() {
    struct Tiny(View3d);
    impl eframe::App for Tiny {
        fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
            ui.allocate_ui(vec2(0.0, 0.0), |ui| {
                ui.set_max_size(vec2(0.0, 0.0));
                self.0.ui(ui, frame)
            });
        }
    }
    let mut harness = Harness::builder().with_size(vec2(64.0, 64.0)).wgpu().build_eframe(|_| {
        let mut view = View3d::new();
        view.set_mesh(&icosahedron());
        Tiny(view)
    });
    harness.run();
    harness.render().unwrap();
}

#[test]
fn without_wgpu_a_note_is_shown() {
    let mut harness = Harness::builder().with_size(vec2(W, H)).build_eframe(|cc| {
        assert!(cc.wgpu_render_state.is_none());
        let mut view = View3d::new();
        view.set_mesh(&icosahedron());
        TestApp { view, settings_panel: false }
    });
    harness.run();
    harness.get_by_label("3D view: needs the wgpu renderer");
}

/// A press, moves and release that arrive in one frame (a fast flick, or a slow frame)
/// orbit by the whole movement, as a drag over several frames does.
#[test]
fn a_drag_within_one_frame_orbits() {
    let mut harness = harness(&icosahedron(), false);
    let before = *harness.state().view.camera();
    let centre = pos2(W / 2.0, H / 2.0);
    harness.hover_at(centre);
    harness.run();
    let button = |pos, pressed| egui::Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers: Modifiers::NONE,
    };
    harness.event(button(centre, true));
    harness.event(egui::Event::PointerMoved(centre + vec2(20.0, 10.0)));
    harness.event(egui::Event::PointerMoved(centre + vec2(40.0, 20.0)));
    harness.event(button(centre + vec2(40.0, 20.0), false));
    harness.run();
    let after = *harness.state().view.camera();
    let expect_yaw = (before.yaw - 40.0 * ORBIT_RADIANS_PER_POINT).rem_euclid(std::f64::consts::TAU);
    assert!((after.yaw - expect_yaw).abs() < 1e-9, "yaw {} -> {}, expected {expect_yaw}", before.yaw, after.yaw);
    assert!((after.pitch - (before.pitch + 20.0 * ORBIT_RADIANS_PER_POINT)).abs() < 1e-9);
}

#[test]
fn drag_orbits_and_pans_scroll_zooms() {
    let mut harness = harness(&icosahedron(), false);
    let before = *harness.state().view.camera();
    let centre = pos2(W / 2.0, H / 2.0);

    // Primary drag: orbit.
    harness.hover_at(centre);
    harness.run();
    harness.drag_at(centre);
    harness.run();
    harness.hover_at(centre + vec2(40.0, 20.0));
    harness.run();
    harness.drop_at(centre + vec2(40.0, 20.0));
    harness.run();
    let after = *harness.state().view.camera();
    let expect_yaw = (before.yaw - 40.0 * ORBIT_RADIANS_PER_POINT).rem_euclid(std::f64::consts::TAU);
    assert!((after.yaw - expect_yaw).abs() < 1e-9, "yaw {} -> {}, expected {expect_yaw}", before.yaw, after.yaw);
    assert!((after.pitch - (before.pitch + 20.0 * ORBIT_RADIANS_PER_POINT)).abs() < 1e-9);
    assert_eq!(after.target, before.target);
    assert_eq!(after.distance, before.distance);

    // Secondary drag: pan; the target moves, the angles stay.
    let before = after;
    harness.hover_at(centre);
    harness.run();
    harness.event(egui::Event::PointerButton {
        pos: centre,
        button: PointerButton::Secondary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    harness.run();
    harness.hover_at(centre + vec2(30.0, 0.0));
    harness.run();
    harness.event(egui::Event::PointerButton {
        pos: centre + vec2(30.0, 0.0),
        button: PointerButton::Secondary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    harness.run();
    let after = *harness.state().view.camera();
    assert_eq!((after.yaw, after.pitch, after.distance), (before.yaw, before.pitch, before.distance));
    let (right, _) = before.right_up();
    let moved = after.target - before.target;
    let per_point = 2.0 * before.distance * (0.5 * before.fov_y).tan() / f64::from(H);
    assert!((moved - (-30.0 * per_point * right)).length() < 1e-9, "dragging right moves the scene right: {moved}");

    // Scroll up: closer, by exp(-ZOOM_PER_POINT * total) once egui's smoothing has run out.
    let before = after;
    harness.hover_at(centre);
    harness.event(egui::Event::MouseWheel {
        unit: MouseWheelUnit::Point,
        delta: vec2(0.0, 100.0),
        phase: TouchPhase::Move,
        source: MouseWheelSource::Unknown,
        modifiers: Modifiers::NONE,
    });
    harness.run();
    let after = *harness.state().view.camera();
    let ratio = after.distance / before.distance;
    let expected = (-ZOOM_PER_POINT * 100.0).exp();
    assert!((ratio - expected).abs() < 0.02, "distance ratio {ratio}, expected about {expected}");
    assert_eq!(after.target, before.target);
}

#[test]
fn double_click_frames_the_mesh_again() {
    // Short steps: kittest runs one step per event, and a double click is two clicks within
    // 0.3 s.
    let mut harness = Harness::builder().with_size(vec2(W, H)).with_step_dt(0.05).wgpu().build_eframe(|_| {
        let mut view = View3d::new();
        view.set_mesh(&icosahedron());
        TestApp { view, settings_panel: false }
    });
    harness.run();
    let framed = *harness.state().view.camera();
    let camera = harness.state_mut().view.camera_mut();
    camera.target += DVec3::new(0.3, -0.2, 0.1);
    camera.distance *= 3.0;
    harness.get_by_label("3D view").click();
    harness.get_by_label("3D view").click();
    harness.run();
    let after = *harness.state().view.camera();
    assert!((after.target - framed.target).length() < 1e-12, "double click fits: {after:?}");
    assert!((after.distance - framed.distance).abs() < 1e-12);
}

#[test]
fn colour_tests_tell_the_colours_apart() {
    // The pixel tests rely on this.
    assert!(is_back_colour(BACK_COLOUR.to_array()));
    assert!(is_front_colour(FRONT_COLOUR.to_array()));
    assert!(!is_back_colour(BACKGROUND.to_array()) && !is_front_colour(BACKGROUND.to_array()));
}

/// A closed grid on the unit sphere with `2 · nu · nv` triangles.
fn sphere(nu: u32, nv: u32) -> TriMesh {
    let mut mesh = TriMesh::default();
    for j in 0..=nv {
        let v = std::f64::consts::PI * f64::from(j) / f64::from(nv);
        for i in 0..nu {
            let u = std::f64::consts::TAU * f64::from(i) / f64::from(nu);
            mesh.positions.push(DVec3::new(v.sin() * u.cos(), v.cos(), -v.sin() * u.sin()));
        }
    }
    for j in 0..nv {
        for i in 0..nu {
            let a = j * nu + i;
            let b = j * nu + (i + 1) % nu;
            let (c, d) = (a + nu, b + nu);
            mesh.triangles.push([a, c, b]);
            mesh.triangles.push([b, c, d]);
        }
    }
    mesh
}

/// Frame time for a ~100k-triangle mesh that changes every frame (what dragging a curve
/// does): `cargo test -p splinekit-editor --test view3d -- --ignored --nocapture frame_time`.
#[test]
#[ignore = "timing, prints only"]
fn frame_time_100k_triangles() {
    use std::time::{Duration, Instant};
    struct Timed {
        view: View3d,
        mesh: TriMesh,
        /// A new mesh every frame (a drag), or only a new camera angle (an orbit).
        new_mesh: bool,
        state: eframe::egui_wgpu::RenderState,
        frames: u32,
        set_mesh: Duration,
        render: Duration,
    }
    impl eframe::App for Timed {
        fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
            self.frames += 1;
            if self.new_mesh || self.frames == 1 {
                let s = 1.0 + 0.001 * f64::from(self.frames);
                let mut mesh = self.mesh.clone();
                for p in &mut mesh.positions {
                    p.y *= s;
                }
                let t = Instant::now();
                self.view.set_mesh(&mesh);
                self.set_mesh += t.elapsed();
            } else {
                self.view.camera_mut().yaw += 0.01;
            }
            let t = Instant::now();
            self.view.ui(ui, frame);
            self.state.device.poll(eframe::wgpu::PollType::wait_indefinitely()).unwrap();
            self.render += t.elapsed();
        }
    }
    let mesh = sphere(320, 160);
    println!("{} triangles", mesh.num_triangles());
    for (new_mesh, msaa, wireframe) in
        [(true, false, false), (true, false, true), (false, false, false), (false, false, true), (false, true, true)]
    {
        let mut harness = Harness::builder().with_size(vec2(800.0, 600.0)).wgpu().build_eframe(|cc| Timed {
            view: View3d::new(),
            mesh: mesh.clone(),
            new_mesh,
            state: cc.wgpu_render_state.clone().unwrap(),
            frames: 0,
            set_mesh: Duration::ZERO,
            render: Duration::ZERO,
        });
        harness.state_mut().view.settings.msaa = msaa;
        harness.state_mut().view.settings.wireframe = wireframe;
        harness.run_steps(3);
        let app = harness.state_mut();
        (app.frames, app.set_mesh, app.render) = (0, Duration::ZERO, Duration::ZERO);
        harness.run_steps(10);
        let app = harness.state();
        let n = f64::from(app.frames);
        println!(
            "800x600, {}, msaa {msaa}, wireframe {wireframe}: set_mesh {:.1} ms, upload + render {:.1} ms per frame",
            if new_mesh { "new mesh every frame" } else { "orbit only" },
            app.set_mesh.as_secs_f64() * 1e3 / n,
            app.render.as_secs_f64() * 1e3 / n
        );
    }
}
