//! The 3D view on a mesh: `cargo run -p splinekit-editor --example view3d_demo [FILE]`.
//!
//! FILE is a mesh (OBJ, OFF, PLY, STL: anything `splinekit_io::load_mesh` reads) or an SWP
//! document (its first surface); without one, the wine glass of the SWP test data. The side
//! panel has the view settings, Loop subdivision with colour-by-level, an inside-out switch,
//! and "Live", which changes the mesh every frame the way dragging a curve does.

use std::path::{Path, PathBuf};
use std::time::Instant;

use eframe::egui;
use splinekit::subdiv::{LoopOptions, LoopPyramid};
use splinekit::{PolyMesh, TriMesh};
use splinekit_editor::view3d::View3d;

fn load(path: &Path) -> anyhow::Result<TriMesh> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("swp")) {
        let doc = splinekit_io::SwpDocument::read(path)?;
        Ok(doc.surface_mesh(0, &splinekit_io::surface::SurfaceOptions::default())?)
    } else {
        Ok(splinekit_io::load_mesh(path)?.mesh.to_tri_mesh())
    }
}

struct Demo {
    view: View3d,
    base: TriMesh,
    name: String,
    levels: usize,
    inside_out: bool,
    live: bool,
    /// The mesh as shown (subdivided, flipped) before the live wobble.
    shown: TriMesh,
    error: Option<String>,
    frame_ms: f32,
    start: Instant,
}

impl Demo {
    fn new(base: TriMesh, name: String) -> Self {
        let mut demo = Self {
            view: View3d::new(),
            shown: base.clone(),
            base,
            name,
            levels: 0,
            inside_out: false,
            live: false,
            error: None,
            frame_ms: 0.0,
            start: Instant::now(),
        };
        demo.rebuild();
        demo
    }

    /// Subdivides and flips the base mesh as asked, and shows the result.
    fn rebuild(&mut self) {
        let mut mesh = if self.levels == 0 {
            self.base.clone()
        } else {
            let options = LoopOptions { color_by_level: true, ..LoopOptions::default() };
            match LoopPyramid::new(&PolyMesh::from(&self.base), options)
                .and_then(|pyramid| pyramid.into_refined(self.levels, |_| {}))
            {
                Ok(fine) => {
                    self.error = None;
                    fine.into_tri_mesh()
                }
                Err(e) => {
                    self.error = Some(format!("Loop subdivision: {e}"));
                    self.base.clone()
                }
            }
        };
        if self.inside_out {
            for t in &mut mesh.triangles {
                t.swap(1, 2);
            }
            for n in &mut mesh.normals {
                *n = -*n;
            }
        }
        self.view.set_mesh(&mesh);
        self.shown = mesh;
    }
}

impl eframe::App for Demo {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        egui::Panel::left("controls").resizable(false).show(ui, |ui| {
            ui.heading(&self.name);
            ui.label(format!("{} vertices, {} triangles", self.shown.num_vertices(), self.shown.num_triangles()));
            ui.separator();
            self.view.settings.ui(ui);
            if ui.button("Fit").clicked() {
                self.view.fit();
            }
            ui.separator();
            let mut changed = ui.add(egui::Slider::new(&mut self.levels, 0..=5).text("Loop levels")).changed();
            changed |= ui.checkbox(&mut self.inside_out, "Inside out").changed();
            ui.checkbox(&mut self.live, "Live (new mesh every frame)");
            if changed {
                self.rebuild();
            }
            if let Some(e) = &self.error {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.separator();
            ui.label(format!("view: {:.1} ms", self.frame_ms));
            ui.label("drag: orbit\nright/middle or shift drag: pan\nscroll: zoom\ndouble click: fit");
        });
        if self.live {
            // What a curve drag does: a new mesh every frame, same size.
            let t = self.start.elapsed().as_secs_f64();
            let mut mesh = self.shown.clone();
            let s = 1.0 + 0.15 * (2.0 * t).sin();
            for p in &mut mesh.positions {
                p.y *= s;
            }
            mesh.normals.clear();
            self.view.set_mesh(&mesh);
            ui.ctx().request_repaint();
        }
        egui::CentralPanel::default().show(ui, |ui| {
            let start = Instant::now();
            self.view.ui(ui, frame);
            self.frame_ms = start.elapsed().as_secs_f32() * 1000.0;
        });
    }
}

fn main() -> eframe::Result {
    let path = std::env::args_os().nth(1).map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data/swp/srev/wineglass.swp"),
        PathBuf::from,
    );
    let (mesh, name) = match load(&path) {
        Ok(mesh) => (mesh, path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned())),
        Err(e) => {
            eprintln!("{}: {e:#}", path.display());
            std::process::exit(1);
        }
    };
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1000.0, 700.0]),
        ..Default::default()
    };
    eframe::run_native("splinekit 3D view", options, Box::new(move |_cc| Ok(Box::new(Demo::new(mesh, name)))))
}
