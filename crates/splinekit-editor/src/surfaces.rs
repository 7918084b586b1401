//! The document's swept surfaces ([`SweptSurfaces`]): swept at once while small, as a
//! preview while a point of a larger one is dragged, else on a worker thread.

use eframe::egui;
use splinekit::TriMesh;
use splinekit_io::surface::{SurfaceError, SurfaceOptions};
use splinekit_io::{SwpDocument, SwpSurfaceKind, SwpTessellation};

use crate::app::cancel;
use crate::{EditorApp, view3d, work};

/// The document's surfaces as the editor shows them: all of them in one mesh, and a line
/// per surface for the surface panel.
#[derive(Clone, Debug, Default)]
pub struct SweptSurfaces {
    /// Every surface that could be swept, merged (triangles of later surfaces after those
    /// of earlier ones).
    pub mesh: TriMesh,
    /// Per surface: its name and counts, or why it cannot be swept.
    pub lines: Vec<String>,
    /// Why surfaces cannot be swept (each also in `lines`).
    pub errors: Vec<String>,
}

impl SweptSurfaces {
    /// Sweeps every surface of `swp` with the default options.
    #[must_use]
    pub fn sweep(swp: &SwpDocument) -> Self {
        Self::sweep_with(swp, &SurfaceOptions::default())
    }

    /// Sweeps every surface of `swp` if they have at most `limit` triangles in all (the
    /// editor's path on every change of the document, e.g. every frame of a drag); else
    /// returns how many they would have (from the sample counts, before building them).
    ///
    /// # Errors
    ///
    /// The triangle count, when it is over `limit`.
    pub fn sweep_within(swp: &SwpDocument, limit: usize) -> Result<Self, u64> {
        let mut out = Self::default();
        // the triangles of the surfaces that did not fit (counted, not built)
        let mut skipped = 0u64;
        for (i, s) in swp.surfaces.iter().enumerate() {
            let total = out.mesh.num_triangles() as u64 + skipped;
            let left = usize::try_from((limit as u64).saturating_sub(total)).unwrap_or(usize::MAX);
            let options = SurfaceOptions { max_triangles: Some(left), ..SurfaceOptions::default() };
            let result = match swp.surface_mesh(i, &options) {
                Err(SurfaceError::TooLarge { triangles, .. }) if triangles <= EDITOR_MAX_TRIANGLES as u64 => {
                    skipped += triangles;
                    continue;
                }
                // too large for the editor: the message of its own limit
                Err(SurfaceError::TooLarge { .. }) => swp.surface_mesh(i, &editor_sweep_options()),
                result => result,
            };
            out.push(&s.display_name(i), result);
        }
        if skipped > 0 { Err(out.mesh.num_triangles() as u64 + skipped) } else { Ok(out) }
    }

    /// A preview of `swp`'s surfaces with about `limit` triangles, for surfaces of about
    /// `estimate` triangles: every curve's and revolution's steps divided by the same factor.
    /// Each line says it is a preview.
    #[must_use]
    pub fn preview(swp: &SwpDocument, limit: usize, estimate: u64) -> Self {
        let mut factor = (estimate as f64 / limit as f64).sqrt() * 1.05;
        for _ in 0..6 {
            let mut coarse = swp.clone();
            let scaled = |steps: u32, min: u32| ((f64::from(steps) / factor).ceil() as u32).clamp(min, steps.max(min));
            for c in &mut coarse.curves {
                c.steps = scaled(c.steps, 1);
            }
            for s in &mut coarse.surfaces {
                match &mut s.kind {
                    SwpSurfaceKind::Revolution { steps, .. } => *steps = scaled(*steps, 3),
                    SwpSurfaceKind::Lathe { stacks, slices, .. } => {
                        *stacks = scaled(*stacks, 1);
                        *slices = scaled(*slices, 3);
                    }
                    // coarser angles: the profile's pieces and the slices
                    SwpSurfaceKind::RevolutionZ { epsilon, slice_tolerance, .. } => {
                        *epsilon = (*epsilon * factor).min(std::f64::consts::PI);
                        *slice_tolerance = (*slice_tolerance * factor).min(std::f64::consts::TAU / 3.0);
                    }
                    SwpSurfaceKind::ToolSweep { epsilon, path_epsilon, .. } => {
                        *epsilon = (*epsilon * factor).min(std::f64::consts::PI);
                        *path_epsilon = (*path_epsilon * factor).min(std::f64::consts::PI);
                    }
                    SwpSurfaceKind::GeneralizedCylinder { .. } => {}
                }
                // the samples of a distance tolerance go as 1/√d
                match &mut s.settings.tessellation {
                    Some(SwpTessellation::Distance(d)) => *d *= factor * factor,
                    Some(SwpTessellation::AngleDegrees(a)) => *a = (*a * factor).min(180.0),
                    None => {}
                }
            }
            if let Ok(mut out) = Self::sweep_within(&coarse, limit) {
                let shown = out.mesh.num_triangles();
                for line in &mut out.lines {
                    line.push_str(" (preview while dragging)");
                }
                out.lines.push(format!(
                    "Preview: {shown} of about {estimate} triangles; the whole surface follows on release"
                ));
                return out;
            }
            // curves with many segments do not scale with their steps alone
            factor *= 2.0;
        }
        Self { lines: vec![format!("No preview: about {estimate} triangles")], ..Self::default() }
    }

    pub(crate) fn sweep_with(swp: &SwpDocument, options: &SurfaceOptions) -> Self {
        let mut out = Self::default();
        for (i, s) in swp.surfaces.iter().enumerate() {
            out.push(&s.display_name(i), swp.surface_mesh(i, options));
        }
        out
    }

    /// Adds surface `name`'s mesh, or why it cannot be swept.
    fn push(&mut self, name: &str, result: Result<TriMesh, SurfaceError>) {
        match result {
            Ok(m) => {
                self.lines.push(format!("{name}: {} vertices, {} triangles", m.num_vertices(), m.num_triangles()));
                append(&mut self.mesh, &m);
            }
            Err(e) => {
                self.lines.push(format!("{name}: {e}"));
                self.errors.push(format!("{name}: {e}"));
            }
        }
    }
}

/// Surfaces with more triangles than this are swept off the UI thread, and shown at reduced
/// resolution while a point is dragged (the whole surface follows on release).
pub const LIVE_TRIANGLES: usize = 200_000;

/// The most triangles the editor sweeps and shows (a larger surface gets a message instead):
/// 20 million triangles take about 1.7 GB of vertex data for the 3D view.
pub const EDITOR_MAX_TRIANGLES: usize = 20_000_000;

/// The size of the preview shown while a point of a larger surface is dragged: about 40 ms a
/// frame on this project's 2-core machine with a software renderer (sweep, vertex data, draw).
pub const PREVIEW_TRIANGLES: usize = 100_000;

/// The document's surfaces swept in the background, with their vertex data for the 3D view.
pub(crate) type SweepResult = (SweptSurfaces, view3d::PreparedMesh);

impl EditorApp {
    /// The triangle count of the document's surfaces (0 if there are none or they fail). When
    /// the window shows a preview or is still sweeping them on a worker thread, they are swept
    /// in full here first, so the count is always the whole surfaces'.
    #[must_use]
    pub fn surface_triangles(&mut self) -> usize {
        self.update_surfaces(None);
        let revision = self.doc.revision();
        if self.surfaces_for != Some((revision, true)) {
            self.cancel_sweep();
            self.surfaces = SweptSurfaces::sweep_with(&self.doc.swp, &editor_sweep_options());
            self.prepared = None;
            self.surfaces_for = Some((revision, true));
        }
        self.surfaces.mesh.num_triangles()
    }

    /// The document's surfaces, swept in full (as [`surface_triangles`](Self::surface_triangles)
    /// does): the merged mesh, and a line per surface.
    pub fn surfaces(&mut self) -> &SweptSurfaces {
        let _ = self.surface_triangles();
        &self.surfaces
    }

    /// Whether the surfaces are being swept in the background.
    #[must_use]
    pub fn is_sweeping(&self) -> bool {
        self.sweep_task.is_some()
    }

    /// Brings the document's surfaces up to date: at once when they have at most
    /// [`LIVE_TRIANGLES`]; else at reduced resolution while a point is dragged, and in full
    /// on a worker thread otherwise (the last surfaces stay shown until it is done). `ctx` is
    /// asked to redraw when the worker finishes.
    pub(crate) fn update_surfaces(&mut self, ctx: Option<&egui::Context>) {
        let revision = self.doc.revision();
        if let Some((r, task)) = &mut self.sweep_task
            && let Some(result) = task.poll()
        {
            let r = *r;
            self.sweep_task = None;
            match result {
                Ok((swept, prepared)) if r == revision => {
                    self.surfaces = swept;
                    self.prepared = Some(prepared);
                    self.surfaces_for = Some((r, true));
                }
                Ok(_) => {}
                Err(e) => self.status = format!("Error: {e}"),
            }
        }
        let dragging = self.view.is_dragging() || self.view3d.is_dragging();
        match self.surfaces_for {
            Some((r, true)) if r == revision => return,
            Some((r, false)) if r == revision && dragging => return,
            _ => {}
        }
        if self.sweep_task.as_ref().is_some_and(|(r, _)| *r == revision) || self.sweep_cancelled == Some(revision) {
            return;
        }
        match SweptSurfaces::sweep_within(&self.doc.swp, LIVE_TRIANGLES) {
            Ok(swept) => {
                self.cancel_sweep();
                self.surfaces = swept;
                self.prepared = None;
                self.surfaces_for = Some((revision, true));
            }
            Err(estimate) if dragging => {
                self.cancel_sweep();
                self.surfaces = SweptSurfaces::preview(&self.doc.swp, PREVIEW_TRIANGLES, estimate);
                self.prepared = None;
                self.surfaces_for = Some((revision, false));
            }
            Err(estimate) => {
                self.cancel_sweep();
                let swp = self.doc.swp.clone();
                let label = format!("Sweeping {:.1} M triangles", estimate as f64 / 1e6);
                let task = work::Task::spawn(label, 0, ctx.cloned(), move |_| {
                    let swept = SweptSurfaces::sweep_with(&swp, &editor_sweep_options());
                    let prepared = view3d::PreparedMesh::new(&swept.mesh);
                    (swept, prepared)
                });
                self.sweep_task = Some((revision, task));
            }
        }
    }

    /// Stops waiting for the background sweep (its result is dropped).
    pub(crate) fn cancel_sweep(&mut self) {
        cancel(&mut self.sweep_task);
    }
}

/// The editor's sweep options: the defaults, at most [`EDITOR_MAX_TRIANGLES`] triangles.
pub(crate) fn editor_sweep_options() -> SurfaceOptions {
    SurfaceOptions { max_triangles: Some(EDITOR_MAX_TRIANGLES), ..SurfaceOptions::default() }
}

/// Appends `b` to `a` (per-vertex attributes kept only if both have them).
fn append(a: &mut TriMesh, b: &TriMesh) {
    let offset = a.positions.len() as u32;
    let keep = |x: usize, y: usize| (x == a.positions.len() || a.positions.is_empty()) && y == b.positions.len();
    let (normals, uvs, colors) =
        (keep(a.normals.len(), b.normals.len()), keep(a.uvs.len(), b.uvs.len()), keep(a.colors.len(), b.colors.len()));
    a.positions.extend_from_slice(&b.positions);
    if normals {
        a.normals.extend_from_slice(&b.normals)
    } else {
        a.normals.clear()
    }
    if uvs {
        a.uvs.extend_from_slice(&b.uvs)
    } else {
        a.uvs.clear()
    }
    if colors {
        a.colors.extend_from_slice(&b.colors)
    } else {
        a.colors.clear()
    }
    a.triangles.extend(b.triangles.iter().map(|t| t.map(|i| i + offset)));
}
