//! The loaded mesh and its subdivision levels ([`MeshState`]): refining (on a worker thread
//! for large levels), coarsening, changing the scheme, and colouring by level.

use std::sync::Arc;

use splinekit::subdiv::{LoopOptions, LoopPyramid, Scheme, SubdivisionOptions, subdivide};
use splinekit::{PolyMesh, TriMesh};

use crate::app::cancel;
use crate::{EditorApp, ViewedMesh, view3d, work};

/// The mesh opened for viewing and its subdivision levels.
pub struct MeshState {
    /// Where it came from.
    pub name: String,
    /// The document's mesh: the loaded mesh (triangles or polygons) and its sharp and
    /// semi-sharp edges and vertices (its OBJ's crease tags), used by Loop and Catmull-Clark.
    pub source: Arc<ViewedMesh>,
    /// The Loop levels (level 0 is the loaded mesh), or why it cannot be Loop-subdivided
    /// this way (then [`subdivide`] makes Loop's levels, or says why not).
    pub pyramid: Result<LoopPyramid, String>,
    /// The levels 1, 2, … made so far with `scheme` by [`subdivide`] when they are not the
    /// Loop pyramid's.
    pub levels: Vec<PolyMesh>,
    /// The scheme of the levels shown.
    pub scheme: Scheme,
    /// The level shown.
    pub level: usize,
}

impl MeshState {
    /// The Loop pyramid, if the levels are its (Loop without creases, on a mesh it takes).
    fn loop_pyramid(&self) -> Option<&LoopPyramid> {
        if uses_pyramid(self.scheme, &self.source) { self.pyramid.as_ref().ok() } else { None }
    }

    /// The level shown when it is not the Loop pyramid's (the loaded mesh at level 0).
    fn polygon_level(&self) -> &PolyMesh {
        if self.level == 0 { &self.source.base } else { &self.levels[self.level - 1] }
    }

    /// The number of faces of the level shown.
    #[must_use]
    pub fn faces(&self) -> usize {
        match self.loop_pyramid() {
            Some(p) => p.level(self.level).num_triangles(),
            None => self.polygon_level().num_faces(),
        }
    }

    /// The number of vertices of the level shown.
    #[must_use]
    pub fn vertices(&self) -> usize {
        match self.loop_pyramid() {
            Some(p) => p.level(self.level).num_vertices(),
            None => self.polygon_level().num_vertices(),
        }
    }

    /// The level shown, triangulated for the 3D view and export.
    #[must_use]
    pub fn shown(&self) -> TriMesh {
        match self.loop_pyramid() {
            Some(p) => p.level(self.level).clone().into_tri_mesh(),
            None => self.polygon_level().to_tri_mesh(),
        }
    }
}

/// Whether the levels of `scheme` on `source` are made as a [`LoopPyramid`] (Loop without
/// creases: the interactive fast path, one level at a time), if the pyramid takes the mesh.
fn uses_pyramid(scheme: Scheme, source: &ViewedMesh) -> bool {
    scheme == Scheme::Loop && source.creases.is_empty()
}

/// The options the editor makes every scheme's levels with: the library's defaults (as the
/// command line's), the vertices coloured by level or not.
pub(crate) fn level_options(color_by_level: bool) -> SubdivisionOptions {
    SubdivisionOptions::DEFAULT.with_color_by_level(color_by_level)
}

/// Level `depth` of `source` by `scheme` with `options`: [`subdivide`] on the loaded mesh with
/// its creases (which only Loop and Catmull-Clark use), or the scheme's refusal in words.
pub(crate) fn scheme_level(
    source: &ViewedMesh,
    scheme: Scheme,
    depth: usize,
    options: &SubdivisionOptions,
) -> Result<PolyMesh, String> {
    subdivide(&source.base, depth, scheme, options, &source.creases).map(|s| s.mesh).map_err(|e| e.to_string())
}

/// Subdivision levels of more faces than this are made on a worker thread.
pub const BACKGROUND_FACES: usize = 200_000;

/// A subdivision level made on a worker thread, with its 3D view data.
pub(crate) enum Refined {
    /// The Loop pyramid, one level finer.
    Pyramid(LoopPyramid, view3d::PreparedMesh),
    /// The next level of another scheme.
    Level(PolyMesh, view3d::PreparedMesh),
    /// Every level made again with new colours.
    Recolored {
        pyramid: Result<LoopPyramid, String>,
        levels: Vec<PolyMesh>,
        level: usize,
        prepared: view3d::PreparedMesh,
    },
}

/// Which level of which mesh with which scheme is shown: the mesh (its address), the scheme
/// and the level.
pub(crate) type MeshKey = (usize, Scheme, usize);

pub(crate) fn mesh_key(m: &MeshState) -> MeshKey {
    (Arc::as_ptr(&m.source) as usize, m.scheme, m.level)
}

impl EditorApp {
    /// Makes [`mesh`](Self::mesh) the document's mesh with its levels (Loop, level 0), if
    /// the document's mesh changed (a file opened, undo of an open, …), and fits the views
    /// to a document that is another file.
    pub(crate) fn sync_mesh(&mut self) {
        self.sync_mesh_with(None);
    }

    /// [`sync_mesh`](Self::sync_mesh), with the Loop level 0 of a new mesh if it was made
    /// already.
    pub(crate) fn sync_mesh_with(&mut self, pyramid: Option<Result<LoopPyramid, String>>) {
        let source = self.doc.mesh().cloned();
        let key = source.as_ref().map_or(0, |m| Arc::as_ptr(m) as usize);
        let current = self.mesh.as_ref().map_or(0, |m| Arc::as_ptr(&m.source) as usize);
        if key != current {
            self.cancel_refine();
            let options = self.loop_options();
            self.mesh = source.map(|source| MeshState {
                name: self.doc.path().map_or_else(String::new, |p| p.display().to_string()),
                pyramid: pyramid.unwrap_or_else(|| LoopPyramid::new(&source.base, options).map_err(|e| e.to_string())),
                levels: Vec::new(),
                scheme: Scheme::Loop,
                level: 0,
                source,
            });
            self.mesh_generation += 1;
        }
        let file = self.doc.file_id();
        if self.fitted_file != Some(file) {
            self.fitted_file = Some(file);
            self.view.fit_pending = true;
            self.view.selected = None;
            self.view3d.fit_on_next_mesh();
        }
    }

    /// The options of every scheme's levels ([`level_options`]).
    pub(crate) fn subdivision_options(&self) -> SubdivisionOptions {
        level_options(self.color_by_level)
    }

    /// The options of the Loop pyramid, [`subdivision_options`](Self::subdivision_options)'.
    pub(crate) fn loop_options(&self) -> LoopOptions {
        self.subdivision_options().loop_options()
    }

    /// Refines the loaded mesh one level with its scheme (kept levels are reused when
    /// coarsening). An error (e.g. a non-manifold mesh for Catmull-Clark) goes to the status
    /// line.
    pub fn refine(&mut self) {
        if self.refine_task.is_some() {
            return;
        }
        let options = self.subdivision_options();
        let Some(m) = &mut self.mesh else { return };
        let key = mesh_key(m);
        match (&mut m.pyramid, m.scheme) {
            (Ok(p), scheme) if uses_pyramid(scheme, &m.source) => {
                if m.level + 1 > p.finest().depth() {
                    if 4 * p.finest().num_triangles() > BACKGROUND_FACES {
                        let mut p = p.clone();
                        let label = format!("Refining to {} triangles", 4 * p.finest().num_triangles());
                        let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |_| {
                            p.refine().map_err(|e| e.to_string())?;
                            let prepared = view3d::PreparedMesh::new(&p.finest().clone().into_tri_mesh());
                            Ok(Refined::Pyramid(p, prepared))
                        });
                        self.refine_task = Some((key, task));
                        return;
                    }
                    if let Err(e) = p.refine() {
                        self.status = format!("Error: {}: {e}", m.name);
                        return;
                    }
                }
                m.level = (m.level + 1).min(p.finest().depth());
            }
            (_, scheme) => {
                if m.level >= m.levels.len() {
                    let depth = m.levels.len() + 1;
                    let coarse = m.levels.last().unwrap_or(&m.source.base);
                    if scheme.face_growth() as usize * coarse.num_faces() > BACKGROUND_FACES {
                        let source = Arc::clone(&m.source);
                        let label = format!("Refining to level {depth} ({})", scheme.title());
                        let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |_| {
                            let fine = scheme_level(&source, scheme, depth, &options)?;
                            let prepared = view3d::PreparedMesh::new(&fine.to_tri_mesh());
                            Ok(Refined::Level(fine, prepared))
                        });
                        self.refine_task = Some((key, task));
                        return;
                    }
                    match scheme_level(&m.source, scheme, depth, &options) {
                        Ok(fine) => m.levels.push(fine),
                        Err(e) => {
                            self.status = format!("Error: {}: {e}", m.name);
                            return;
                        }
                    }
                }
                m.level += 1;
            }
        }
        self.status = format!("Level {}: {} faces", m.level, m.faces());
    }

    /// Takes a level refined on a worker thread, if it is done and still wanted (the same
    /// mesh, scheme and level as when it started).
    pub(crate) fn poll_refine(&mut self) {
        let Some((key, task)) = &mut self.refine_task else { return };
        let Some(result) = task.poll() else { return };
        let key = *key;
        self.refine_task = None;
        let Some(m) = &mut self.mesh else { return };
        if mesh_key(m) != key {
            return;
        }
        match result.and_then(|r| r) {
            Ok(Refined::Pyramid(p, prepared)) => {
                m.level = p.finest().depth();
                m.pyramid = Ok(p);
                self.prepared_mesh = Some((mesh_key(m), prepared));
            }
            Ok(Refined::Level(fine, prepared)) => {
                m.levels.push(fine);
                m.level = m.levels.len();
                self.prepared_mesh = Some((mesh_key(m), prepared));
            }
            Ok(Refined::Recolored { pyramid, levels, level, prepared }) => {
                m.pyramid = pyramid;
                m.levels = levels;
                m.level = level;
                self.mesh_generation += 1;
                self.prepared_mesh = Some((mesh_key(m), prepared));
                return;
            }
            Err(e) => {
                self.status = format!("Error: {}: {e}", m.name);
                return;
            }
        }
        self.status = format!("Level {}: {} faces", m.level, m.faces());
    }

    /// Stops waiting for a level being refined.
    pub(crate) fn cancel_refine(&mut self) {
        cancel(&mut self.refine_task);
    }

    /// Whether a subdivision level is being made on a worker thread.
    #[must_use]
    pub fn is_refining(&self) -> bool {
        self.refine_task.is_some()
    }

    /// Subdivides the loaded mesh with `scheme` from now on (showing the loaded mesh again).
    pub fn set_scheme(&mut self, scheme: Scheme) {
        self.cancel_refine();
        let Some(m) = &mut self.mesh else { return };
        if m.scheme != scheme {
            m.scheme = scheme;
            m.level = 0;
            m.levels.clear();
            self.mesh_generation += 1;
            self.status = format!("{} subdivision", scheme.title());
            if !m.source.creases.is_empty() && !scheme.supports_creases() {
                self.status.push_str(" (it has no creases: the mesh's crease tags are left out)");
            }
        }
    }

    /// Rebuilds the loaded mesh's levels with the current colour setting, keeping the level shown.
    pub(crate) fn recolor(&mut self) {
        self.cancel_refine();
        let options = self.subdivision_options();
        let Some(m) = &mut self.mesh else { return };
        let (source, scheme, pyramid, level, count) =
            (Arc::clone(&m.source), m.scheme, m.loop_pyramid().is_some(), m.level, m.levels.len());
        let finest = match (&m.pyramid, pyramid) {
            (Ok(p), true) => p.finest().num_triangles(),
            _ => m.levels.last().map_or(0, PolyMesh::num_faces),
        };
        if finest > BACKGROUND_FACES {
            let key = mesh_key(m);
            let label = format!("Colouring {finest} faces");
            let task = work::Task::spawn(label, 0, self.egui_ctx.clone(), move |_| {
                let (pyramid, levels, level) = recolored(&source, scheme, pyramid, level, count, options);
                let shown = match (&pyramid, level) {
                    (_, 0) => source.base.to_tri_mesh(),
                    (Ok(p), l) if levels.is_empty() => p.level(l).clone().into_tri_mesh(),
                    (_, l) => levels[l - 1].to_tri_mesh(),
                };
                let prepared = view3d::PreparedMesh::new(&shown);
                Ok(Refined::Recolored { pyramid, levels, level, prepared })
            });
            self.refine_task = Some((key, task));
            return;
        }
        let (p, levels, level) = recolored(&source, scheme, pyramid, level, count, options);
        m.pyramid = p;
        m.levels = levels;
        m.level = level;
        self.mesh_generation += 1;
    }

    /// Shows the next coarser level of the loaded mesh.
    pub fn coarsen(&mut self) {
        self.cancel_refine();
        if let Some(m) = &mut self.mesh
            && m.level > 0
        {
            m.level -= 1;
            self.status = format!("Level {}: {} faces", m.level, m.faces());
        }
    }
}

/// The levels of `source` made again with `options`' colours: the Loop pyramid to `level`
/// when `pyramid` (Loop without creases), else `count` levels of `scheme`; and the level to
/// show (the same, or the finest that could be made).
fn recolored(
    source: &ViewedMesh,
    scheme: Scheme,
    pyramid: bool,
    level: usize,
    count: usize,
    options: SubdivisionOptions,
) -> (Result<LoopPyramid, String>, Vec<PolyMesh>, usize) {
    let mut p = LoopPyramid::new(&source.base, options.loop_options()).map_err(|e| e.to_string());
    let mut level = level;
    if let Ok(p) = &mut p
        && pyramid
    {
        // the level shown was made before, so it fits; were it refused, show the finest
        if p.refine_to(level, |_| {}).is_err() {
            level = p.finest().depth();
        }
    }
    // the other scheme's levels made so far, again with the new colours
    let mut levels: Vec<PolyMesh> = Vec::with_capacity(count);
    if !pyramid {
        for depth in 1..=count {
            match scheme_level(source, scheme, depth, &options) {
                Ok(fine) => levels.push(fine),
                Err(_) => break,
            }
        }
        level = level.min(levels.len());
    }
    (p, levels, level)
}
