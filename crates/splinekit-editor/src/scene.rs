//! What the 3D view shows: the mesh level or the document's surfaces, coloured as chosen
//! with their legend, and the curves, frames and markers drawn over them.

use eframe::egui;
use splinekit::TriMesh;
use splinekit_render::legend::format_value;
use splinekit_render::{Legend, SurfaceColour, diverging_colour, level_colour};

use crate::subdivision::mesh_key;
use crate::surfaces::editor_sweep_options;
use crate::{EditorApp, SweptSurfaces, view2d, view3d};

/// What the 3D view was last given: the document's surfaces (at a revision, in full or as a
/// preview), or the loaded mesh's level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shown {
    Document { revision: u64, full: bool },
    Mesh { generation: u64, level: usize },
}

/// The most triangles the 3D view colours by curvature or UVs (the colours are made on the
/// UI thread: about a second at this size).
pub const COLOUR_MAX_TRIANGLES: usize = 2_000_000;

impl EditorApp {
    /// The mesh of the 3D view: the loaded mesh's level, or the document's surfaces merged
    /// (in full, also while a preview or the background sweep is shown).
    ///
    /// # Errors
    ///
    /// Why there is none (no surface in the document, or a surface that cannot be built).
    pub fn shown_mesh(&mut self) -> Result<TriMesh, String> {
        if let Some(m) = &self.mesh {
            return Ok(m.shown());
        }
        if self.doc.swp.surfaces.is_empty() {
            return Err("the document has no surface (add srev or gcyl to the SWP file)".to_owned());
        }
        // the sweep the surface panel and the 3D view already show, if it is the whole one
        let full;
        let swept = if self.surfaces_for == Some((self.doc.revision(), true)) {
            &self.surfaces
        } else {
            full = SweptSurfaces::sweep(&self.doc.swp);
            &full
        };
        match swept.errors.first() {
            Some(e) => Err(e.clone()),
            None => Ok(swept.mesh.clone()),
        }
    }

    /// Gives the 3D view the loaded mesh's level, or the document's surfaces, if they changed
    /// since it was last given them.
    pub(crate) fn update_view3d(&mut self, ctx: Option<&egui::Context>) {
        if self.mesh.is_none() {
            self.update_surfaces(ctx);
        }
        let shown = match (&self.mesh, self.surfaces_for) {
            (Some(m), _) => Shown::Mesh { generation: self.mesh_generation, level: m.level },
            (None, Some((revision, full))) => Shown::Document { revision, full },
            (None, None) => return,
        };
        let colouring = (self.colouring, self.color_by_level);
        if self.shown == Some(shown) && self.shown_colouring == Some(colouring) {
            return;
        }
        self.shown = Some(shown);
        self.shown_colouring = Some(colouring);
        self.view3d.settings.checker = false;
        self.legend = match &self.mesh {
            Some(m) if self.color_by_level && self.colouring == SurfaceColour::Shade => {
                Some(Legend::Levels { levels: u32::try_from(m.level).unwrap_or(u32::MAX) })
            }
            _ => None,
        };
        if self.colouring != SurfaceColour::Shade {
            match self.coloured_mesh() {
                Ok((mesh, legend)) => {
                    self.prepared = None;
                    self.prepared_mesh = None;
                    self.view3d.settings.checker = self.colouring == SurfaceColour::UvChecker;
                    self.view3d.set_mesh(&mesh);
                    self.legend = legend;
                    return;
                }
                Err(why) => self.status = format!("Error: {why}; shown shaded"),
            }
        }
        match &self.mesh {
            Some(m) => match self.prepared_mesh.take() {
                Some((key, prepared)) if key == mesh_key(m) => self.view3d.set_prepared(prepared),
                _ => self.view3d.set_mesh(&m.shown()),
            },
            None => match self.prepared.take() {
                Some(prepared) => self.view3d.set_prepared(prepared),
                None => self.view3d.set_mesh(&self.surfaces.mesh),
            },
        }
    }

    /// The mesh shown (the mesh's level, or the document's surfaces) coloured by
    /// [`colouring`](Self::colouring), and its legend: vertex colours from the curvature with
    /// the render crate's map and scale, or the UVs (in the red and green of the vertex
    /// colours) for the checker. The surfaces are swept again with UVs for the checker.
    ///
    /// # Errors
    /// A mesh of more than [`COLOUR_MAX_TRIANGLES`] triangles, or no UVs for the checker.
    fn coloured_mesh(&self) -> Result<(TriMesh, Option<Legend>), String> {
        let triangles = match &self.mesh {
            Some(m) => m.faces(),
            None => self.surfaces.mesh.num_triangles(),
        };
        if triangles > COLOUR_MAX_TRIANGLES {
            return Err(format!(
                "colouring by {} takes at most {COLOUR_MAX_TRIANGLES} triangles; this has {triangles}",
                self.colouring.name()
            ));
        }
        let mut mesh = match (&self.mesh, self.colouring) {
            (Some(m), _) => m.shown(),
            (None, SurfaceColour::UvChecker) => {
                let mut options = editor_sweep_options();
                options.sweep.uvs = true;
                SweptSurfaces::sweep_with(&self.doc.swp, &options).mesh
            }
            (None, _) => self.surfaces.mesh.clone(),
        };
        if mesh.triangles.is_empty() {
            return Ok((mesh, None));
        }
        match self.colouring {
            SurfaceColour::UvChecker => {
                if mesh.uvs.len() != mesh.positions.len() {
                    return Err("the UV checker needs texture coordinates, and this mesh has none".to_owned());
                }
                mesh.colors = mesh
                    .uvs
                    .iter()
                    .map(|uv| glam::DVec3::new(uv.x.rem_euclid(1.0), uv.y.rem_euclid(1.0), 0.0))
                    .collect();
                Ok((mesh, None))
            }
            SurfaceColour::Curvature(_) => {
                let radius = splinekit_render::camera::bounding_radius(mesh.positions.iter().copied());
                let (mut colours, legend) = splinekit_render::surface_colours(&[&mesh], self.colouring, radius);
                if let Some(Some(c)) = colours.pop() {
                    mesh.colors = c;
                }
                Ok((mesh, legend))
            }
            SurfaceColour::Shade | SurfaceColour::Level { .. } => Ok((mesh, None)),
        }
    }

    /// Every curve of the document for the 3D view (2D curves in the xy plane), coloured by
    /// segment, the active one brighter and wider, with the control points of the others
    /// (the active 3D curve's are its handles) (`Draw curves`); frames T, N, B in blue, red and
    /// green along every curve (`Draw normals`); the active curve's arc-length markers.
    pub(crate) fn scene_overlay(&self) -> view3d::Overlay {
        use splinekit::ParamCurve as _;
        let mut overlay = view3d::Overlay::default();
        let show = &self.view.show;
        if !show.curves && !show.normals && !show.markers {
            return overlay;
        }
        let curves: Vec<(usize, splinekit::AnyCurve<glam::DVec3>)> =
            self.doc.swp.curves.iter().enumerate().filter_map(|(i, c)| c.to_curve().ok().map(|c| (i, c))).collect();
        // frame arrows a twentieth of the scene's size
        let (_, radius) = view3d::point_bounds(|| {
            curves.iter().flat_map(|(_, c)| {
                let n = c.num_segments().max(1);
                (0..=4 * n).map(move |k| c.eval(n as f64 * k as f64 / (4 * n) as f64))
            })
        });
        let arrow = 0.1 * if radius > 0.0 { radius } else { 1.0 };
        for (i, c) in &curves {
            let active = *i == self.doc.active;
            let segments = c.num_segments().max(1);
            if show.curves {
                for seg in 0..segments {
                    let points = (0..=24).map(|k| c.eval(seg as f64 + f64::from(k) / 24.0)).collect();
                    let colour = view2d::SEGMENT_COLORS[seg % view2d::SEGMENT_COLORS.len()];
                    let (colour, width) = if active { (colour, 2.5) } else { (colour.gamma_multiply(0.55), 1.5) };
                    overlay.lines.push((points, colour, width));
                }
                let is_3d = self.doc.swp.curves[*i].dim == 3;
                if !(active && is_3d) {
                    let points = self.doc.swp.curves[*i].geometry.points();
                    let colour = if active { view3d::HANDLE_COLOUR } else { egui::Color32::from_gray(150) };
                    overlay.dots.extend(points.iter().map(|&p| (p, colour)));
                }
            }
            if show.normals {
                let n = segments * 8;
                let us: Vec<f64> = (0..=n).map(|k| segments as f64 * k as f64 / n as f64).collect();
                let frames = splinekit::frame::frames(c, &us, &show.frame_options(self.doc.swp.curves[*i].dim != 3));
                for (&u, f) in us.iter().zip(&frames) {
                    let p = c.eval(u);
                    for (v, colour) in [
                        (f.t, egui::Color32::from_rgb(60, 110, 255)),
                        (f.n, egui::Color32::from_rgb(230, 50, 50)),
                        (f.b, egui::Color32::from_rgb(40, 180, 70)),
                    ] {
                        overlay.lines.push((vec![p, p + v * arrow], colour, 1.5));
                    }
                }
            }
            if show.markers && active {
                let index = splinekit::arclen::ArclenIndex::new(c, 1e-9);
                let spacing = show.marker_spacing.max(index.length() / 5000.0).max(1e-12);
                let count = (index.length() / spacing).floor() as usize;
                for k in 0..=count {
                    let u = index.u_at(c, k as f64 * spacing);
                    overlay.dots.push((c.eval(u), egui::Color32::from_gray(20)));
                }
            }
        }
        overlay
    }
}

/// Draws `legend` in the bottom left corner of the 3D view `rect`: the curvature's colour bar
/// with `−m`, `0` and `+m` (pointed ends: values beyond show the end colours), or a swatch
/// per subdivision level.
pub(crate) fn paint_legend(ui: &egui::Ui, rect: egui::Rect, legend: &Legend) {
    use egui::{Align2, Color32, FontId, Rect, pos2, vec2};
    let painter = ui.painter_at(rect);
    let colour = |c: [u8; 3]| Color32::from_rgb(c[0], c[1], c[2]);
    let font = FontId::proportional(12.0);
    match *legend {
        Legend::Curvature { curvature, scale, .. } => {
            let (w, h) = (180.0, 10.0);
            // room for the end labels, centred under the ends
            let bar = Rect::from_min_size(rect.left_bottom() + vec2(40.0, -34.0), vec2(w, h));
            painter.rect_filled(
                Rect::from_min_max(bar.min - vec2(32.0, 22.0), bar.max + vec2(32.0, 22.0)),
                4.0,
                Color32::from_black_alpha(170),
            );
            painter.text(
                bar.left_top() - vec2(0.0, 4.0),
                Align2::LEFT_BOTTOM,
                curvature.title(),
                font.clone(),
                Color32::WHITE,
            );
            let steps = 60;
            for i in 0..steps {
                let t = -1.0 + (2.0 * i as f64 + 1.0) / f64::from(steps);
                let x0 = bar.left() + w * i as f32 / steps as f32;
                let cell = Rect::from_min_max(pos2(x0, bar.top()), pos2(x0 + w / steps as f32 + 0.5, bar.bottom()));
                painter.rect_filled(cell, 0.0, colour(diverging_colour(t)));
            }
            for (x, text) in [
                (bar.left(), format_value(-scale)),
                (bar.center().x, "0".to_owned()),
                (bar.right(), format_value(scale)),
            ] {
                painter.text(pos2(x, bar.bottom() + 2.0), Align2::CENTER_TOP, text, font.clone(), Color32::WHITE);
            }
        }
        Legend::Levels { levels } => {
            let shown = levels.min(7);
            let height = 16.0 * (shown as f32 + 1.0);
            let top = rect.left_bottom() + vec2(14.0, -12.0 - height);
            painter.rect_filled(
                Rect::from_min_size(top - vec2(8.0, 6.0), vec2(90.0, height + 12.0)),
                4.0,
                Color32::from_black_alpha(170),
            );
            for k in 0..=shown {
                let y = top.y + 16.0 * k as f32;
                painter.rect_filled(
                    Rect::from_min_size(pos2(top.x, y + 2.0), vec2(12.0, 12.0)),
                    2.0,
                    colour(level_colour(k)),
                );
                painter.text(
                    pos2(top.x + 18.0, y + 8.0),
                    Align2::LEFT_CENTER,
                    format!("level {k}"),
                    font.clone(),
                    Color32::WHITE,
                );
            }
        }
    }
}
