//! The edited document: an SWP document, the active curve, the file it belongs to, and
//! undo/redo.
//!
//! Every edit goes through a method here, so the user interface stays thin and the edits are
//! tested without a window. Each method that changes the document records one undo step
//! (a drag records one step when it starts, however many moves follow). Replacing the whole
//! document (opening a file, New, the preset scene) is one undo step too: undoing it brings
//! back the document it replaced, with its file and its unsaved changes.

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;
use splinekit::subdiv::Creases;
use splinekit::{AnyCurve, ParamCurve, PolyMesh, Tcb};
use splinekit_io::mesh::MeshFormat;
use splinekit_io::{SourcePos, SwpCurve, SwpCurveKind, SwpDocument, SwpGeometry, SwpSurface, SwpSurfaceKind};

/// Most undo steps kept; older ones are dropped.
pub const MAX_UNDO: usize = 500;

/// The spline kinds the kind switch offers, in the order `s` cycles through them.
pub const KINDS: [(SwpCurveKind, &str); 9] = [
    (SwpCurveKind::Bezier, "Bézier"),
    (SwpCurveKind::BSpline, "B-spline"),
    (SwpCurveKind::CatmullRom { alpha: 0.0 }, "Catmull-Rom (uniform)"),
    (SwpCurveKind::CatmullRom { alpha: 0.5 }, "Catmull-Rom (centripetal)"),
    (SwpCurveKind::Hermite, "Hermite"),
    (SwpCurveKind::KochanekBartels, "Kochanek–Bartels (TCB)"),
    (SwpCurveKind::BesselOverhauser, "Bessel–Overhauser"),
    (SwpCurveKind::BezierN, "Bézier (one curve, any degree)"),
    (SwpCurveKind::Nurbs { degree: splinekit_io::DEFAULT_NURBS_DEGREE }, "NURBS"),
];

/// Whether `a` and `b` are the same entry of [`KINDS`] (a NURBS of any degree is "NURBS").
#[must_use]
pub fn same_kind(a: SwpCurveKind, b: SwpCurveKind) -> bool {
    a == b || matches!((a, b), (SwpCurveKind::Nurbs { .. }, SwpCurveKind::Nurbs { .. }))
}

/// The display name of a curve kind.
#[must_use]
pub fn kind_name(kind: SwpCurveKind) -> &'static str {
    match kind {
        SwpCurveKind::Circle => "circle",
        SwpCurveKind::Helix => "helix",
        SwpCurveKind::Trefoil => "trefoil",
        SwpCurveKind::CatmullRom { alpha } if alpha != 0.0 && alpha != 0.5 => "Catmull-Rom",
        SwpCurveKind::Nurbs { .. } => "NURBS",
        _ => KINDS.iter().find(|(k, _)| *k == kind).map_or("?", |(_, name)| name),
    }
}

/// What kind of file a document is, which decides what Save may write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DocKind {
    /// An SWP file (or a new document, which Save writes as SWP).
    Swp,
    /// An OBJ file with the revolution tool's spline header, opened as its profile curve and
    /// `zrev` surface; Save writes the annotated OBJ back (header and mesh).
    AnnotatedObj,
    /// A mesh opened for viewing (OBJ, glb, PLY, STL): never written back by Save.
    Mesh,
}

impl DocKind {
    /// The kind of the file at `path`, from its extension (`None`: not a file the editor
    /// opens).
    #[must_use]
    pub fn of_path(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "swp" => Some(Self::Swp),
            _ => MeshFormat::from_extension(&ext).filter(|f| f.capabilities().reads).map(|_| Self::Mesh),
        }
    }
}

/// A mesh opened for viewing, with the crease tags of its file.
#[derive(Debug)]
pub struct ViewedMesh {
    /// The mesh as read (triangles or polygons).
    pub base: PolyMesh,
    /// Its sharp and semi-sharp edges and vertices (an OBJ's crease tags).
    pub creases: Creases,
}

/// The file a document belongs to, and its contents as last read or written.
#[derive(Clone, Debug)]
struct FileState {
    path: Option<PathBuf>,
    kind: DocKind,
    /// The curves and surfaces as last read or written: the document is modified while it
    /// differs from them.
    saved: Arc<SwpDocument>,
    /// Bumped whenever `saved` is replaced.
    saved_generation: u64,
    mesh: Option<Arc<ViewedMesh>>,
    /// Different for every document made (opened, new, the preset scene): swapped by undo
    /// and redo of a replacement, kept by edits and saves.
    id: u64,
}

/// One undo (or redo) step.
#[derive(Clone, Debug)]
enum Step {
    /// An edit of the curves and surfaces.
    Edit { swp: SwpDocument, active: usize },
    /// The whole document was replaced (a file opened, New, the preset scene).
    Replace { swp: SwpDocument, active: usize, file: FileState },
}

/// The document being edited.
#[derive(Debug, Clone)]
pub struct Document {
    /// The curves and surfaces.
    pub swp: SwpDocument,
    /// The index of the curve being edited (always valid when there are curves).
    pub active: usize,
    file: FileState,
    undo: Vec<Step>,
    redo: Vec<Step>,
    /// Changes on every change, so views know when to rebuild what they derive from it.
    revision: u64,
    /// `(revision, saved_generation, modified)` of the last [`is_modified`](Self::is_modified).
    modified_cache: std::cell::Cell<Option<(u64, u64, bool)>>,
}

/// A revision number never handed out before (in this process), so a cache keyed by it
/// cannot mistake one document for another.
fn next_revision() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

impl Default for Document {
    fn default() -> Self {
        Self::new()
    }
}

/// The kind of a new document's curve: uniform Catmull-Rom, so that four clicks draw a curve
/// through the middle two.
pub const NEW_CURVE_KIND: SwpCurveKind = SwpCurveKind::CatmullRom { alpha: 0.0 };

impl Document {
    /// A new, untitled document with one empty 2D Catmull-Rom curve called `profile`.
    #[must_use]
    pub fn new() -> Self {
        let mut swp = SwpDocument::default();
        swp.curves.push(empty_curve("profile", NEW_CURVE_KIND, 2));
        Self::from_swp(swp, None)
    }

    /// A document for `swp`, read from the SWP file `path` (if given): not modified.
    #[must_use]
    pub fn from_swp(swp: SwpDocument, path: Option<PathBuf>) -> Self {
        Self::with_file(swp, path, DocKind::Swp, None)
    }

    /// A document for viewing `mesh`, read from `path` (an annotated OBJ file if `kind` says
    /// so): no curves, not modified.
    #[must_use]
    pub fn from_mesh(mesh: ViewedMesh, path: PathBuf, kind: DocKind) -> Self {
        Self::with_file(SwpDocument::default(), Some(path), kind, Some(Arc::new(mesh)))
    }

    fn with_file(swp: SwpDocument, path: Option<PathBuf>, kind: DocKind, mesh: Option<Arc<ViewedMesh>>) -> Self {
        let file = FileState {
            path,
            kind,
            saved: Arc::new(swp.clone()),
            saved_generation: next_revision(),
            mesh,
            id: next_revision(),
        };
        Self {
            swp,
            active: 0,
            file,
            undo: Vec::new(),
            redo: Vec::new(),
            revision: next_revision(),
            modified_cache: std::cell::Cell::new(None),
        }
    }

    /// A document for the curves and surface of an annotated OBJ file `path` (see
    /// [`SplineHeader::to_document`](splinekit_io::mesh::SplineHeader::to_document)): not
    /// modified; Save writes the annotated OBJ back.
    #[must_use]
    pub fn from_annotated(swp: SwpDocument, path: PathBuf) -> Self {
        Self::with_file(swp, Some(path), DocKind::AnnotatedObj, None)
    }

    /// Reads an SWP file.
    ///
    /// # Errors
    ///
    /// The reader's message (file, line, column and what was expected).
    pub fn read(path: &Path) -> Result<Self, String> {
        let swp = SwpDocument::read(path).map_err(|e| e.to_string())?;
        Ok(Self::from_swp(swp, Some(path.to_path_buf())))
    }

    /// Replaces this document by `other` (a file just opened, a new document, the preset
    /// scene) as one undo step: undo brings this one back, with its file and unsaved changes.
    /// `other`'s own history is dropped.
    pub fn replace_with(&mut self, other: Document) {
        let Document { swp, active, file, .. } = other;
        let old_file = std::mem::replace(&mut self.file, file);
        let old_swp = std::mem::replace(&mut self.swp, swp);
        let old_active = std::mem::replace(&mut self.active, active);
        self.push_undo(Step::Replace { swp: old_swp, active: old_active, file: old_file });
        self.revision = next_revision();
    }

    /// The file the document was read from or last saved to (`None`: a new document).
    #[must_use]
    pub fn path(&self) -> Option<&Path> {
        self.file.path.as_deref()
    }

    /// What kind of file the document is.
    #[must_use]
    pub fn kind(&self) -> DocKind {
        self.file.kind
    }

    /// The path Save writes to without asking: the document's own file when it is a file the
    /// editor writes (SWP), else `None` (Save then asks for a name, as Save as).
    #[must_use]
    pub fn save_path(&self) -> Option<&Path> {
        if matches!(self.file.kind, DocKind::Swp | DocKind::AnnotatedObj) { self.path() } else { None }
    }

    /// A number that differs between documents (each file opened, new document or preset
    /// scene) and stays through edits and saves: views fit themselves again when it changes.
    #[must_use]
    pub fn file_id(&self) -> u64 {
        self.file.id
    }

    /// The mesh opened for viewing, if the document is one.
    #[must_use]
    pub fn mesh(&self) -> Option<&Arc<ViewedMesh>> {
        self.file.mesh.as_ref()
    }

    /// The file name for the window title (`untitled` for a new document).
    #[must_use]
    pub fn display_name(&self) -> String {
        match self.path() {
            Some(p) => p.file_name().map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into_owned()),
            None => "untitled".to_owned(),
        }
    }

    /// Whether the curves and surfaces differ from those last read or written.
    #[must_use]
    pub fn is_modified(&self) -> bool {
        let key = (self.revision, self.file.saved_generation);
        if let Some((r, g, m)) = self.modified_cache.get()
            && (r, g) == key
        {
            return m;
        }
        let modified = *self.file.saved != self.swp;
        self.modified_cache.set(Some((key.0, key.1, modified)));
        modified
    }

    /// Records that the document was written to `path` (an SWP file, or an annotated OBJ
    /// for a `.obj` path): it becomes the document's file, and the document is no longer
    /// modified. Not an edit (no undo step).
    pub fn mark_saved(&mut self, path: &Path) {
        self.file.path = Some(path.to_path_buf());
        let obj = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"));
        self.file.kind = if obj { DocKind::AnnotatedObj } else { DocKind::Swp };
        self.file.saved = Arc::new(self.swp.clone());
        self.file.saved_generation = next_revision();
    }

    /// A number that changes whenever the document does, and differs between documents.
    #[must_use]
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The active curve, if the document has curves.
    #[must_use]
    pub fn curve(&self) -> Option<&SwpCurve> {
        self.swp.curves.get(self.active)
    }

    /// The active curve as a curve of the core library, or why it is not one (for example a
    /// Bézier curve whose point count is not `3k + 1`).
    ///
    /// # Errors
    ///
    /// The reason, for the status line.
    pub fn spline(&self) -> Result<AnyCurve<DVec3>, String> {
        let curve = self.curve().ok_or("no curve")?;
        curve.to_curve().map_err(|e| e.to_string())
    }

    /// What keeps the active curve from being a curve, in words for the status line (the
    /// reader's rule for its kind, e.g. `a Bézier spline needs 4, 7, 10, … points; this one
    /// has 5`), or `None` when it is one or has no points yet.
    #[must_use]
    pub fn curve_problem(&self) -> Option<String> {
        let curve = self.curve()?;
        if self.points().is_empty() {
            return None;
        }
        let one = SwpDocument { curves: vec![curve.clone()], surfaces: Vec::new() };
        if let Err(e) = one.validate() {
            let text = e.kind().to_string();
            return Some(format!("{}: {text}", curve.display_name(self.active)));
        }
        curve.to_curve().err().map(|e| format!("{}: {e}", curve.display_name(self.active)))
    }

    /// The editable points of the active curve (control points, or a Hermite curve's points,
    /// or a Kochanek–Bartels curve's keys); empty for circles, helices and trefoils.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        self.curve().map_or(&[], |c| c.geometry.points())
    }

    /// The tension, continuity and bias of key `i` of the active curve, if it is a
    /// Kochanek–Bartels curve.
    #[must_use]
    pub fn shape(&self, i: usize) -> Option<Tcb> {
        match self.curve().map(|c| &c.geometry) {
            Some(SwpGeometry::Tcb { shape, .. }) => shape.get(i).copied(),
            _ => None,
        }
    }

    /// Sets the tension, continuity and bias of key `i` of a Kochanek–Bartels curve, each
    /// clamped to `[−1, 1]` (NaN is ignored). Call [`begin_move`](Self::begin_move) first for
    /// one undo step per drag.
    pub fn set_shape(&mut self, i: usize, shape: Tcb) {
        let values = [shape.tension, shape.continuity, shape.bias];
        if values.iter().any(|v| v.is_nan()) {
            return;
        }
        let [tension, continuity, bias] = values.map(|v| v.clamp(-1.0, 1.0));
        if let Some(SwpGeometry::Tcb { shape: shapes, .. }) =
            self.swp.curves.get_mut(self.active).map(|c| &mut c.geometry)
            && let Some(s) = shapes.get_mut(i)
        {
            *s = Tcb::new(tension, continuity, bias);
            self.revision = next_revision();
        }
    }

    /// The weight of point `i` of the active curve, if it is a NURBS.
    #[must_use]
    pub fn weight(&self, i: usize) -> Option<f64> {
        match self.curve().map(|c| &c.geometry) {
            Some(SwpGeometry::Nurbs { weights, .. }) => weights.get(i).copied(),
            _ => None,
        }
    }

    /// Sets the weight of point `i` of a NURBS; ignored unless finite and positive. Call
    /// [`begin_move`](Self::begin_move) first for one undo step per drag.
    pub fn set_weight(&mut self, i: usize, weight: f64) {
        if !(weight.is_finite() && weight > 0.0) {
            return;
        }
        if let Some(SwpGeometry::Nurbs { weights, .. }) = self.swp.curves.get_mut(self.active).map(|c| &mut c.geometry)
            && let Some(w) = weights.get_mut(i)
        {
            *w = weight;
            self.revision = next_revision();
        }
    }

    /// The degree of the active curve if it is a NURBS.
    #[must_use]
    pub fn nurbs_degree(&self) -> Option<u32> {
        match self.curve().map(|c| c.kind) {
            Some(SwpCurveKind::Nurbs { degree }) => Some(degree),
            _ => None,
        }
    }

    /// Sets the degree of a NURBS (1 to 32) as one undo step; a knot vector of its own goes
    /// back to the default, since the number of knots depends on the degree.
    pub fn set_degree(&mut self, degree: u32) {
        let max = splinekit::MAX_NURBS_DEGREE as u32;
        if self.nurbs_degree().is_none_or(|d| d == degree) || !(1..=max).contains(&degree) {
            return;
        }
        self.checkpoint();
        if let Some(curve) = self.swp.curves.get_mut(self.active) {
            curve.kind = SwpCurveKind::Nurbs { degree };
            if let SwpGeometry::Nurbs { knots, .. } = &mut curve.geometry {
                *knots = None;
            }
        }
    }

    /// The knot vector of the active NURBS as the curve uses it (the file's own, or the
    /// clamped uniform or periodic default), and whether it is the file's own; `None` for
    /// other kinds or a NURBS that is not a curve yet (too few points).
    #[must_use]
    pub fn knots(&self) -> Option<(Vec<f64>, bool)> {
        let curve = self.curve()?;
        let SwpGeometry::Nurbs { knots, .. } = &curve.geometry else { return None };
        match curve.to_curve().ok()? {
            AnyCurve::Nurbs(nurbs) => Some((nurbs.knots().to_vec(), knots.is_some())),
            _ => None,
        }
    }

    /// Whether the active curve lives in the xy-plane (a 2D SWP kind).
    #[must_use]
    pub fn is_2d(&self) -> bool {
        self.curve().is_some_and(|c| c.dim != 3)
    }

    /// Records an undo step for the current state.
    fn checkpoint(&mut self) {
        self.push_undo(Step::Edit { swp: self.swp.clone(), active: self.active });
        self.revision = next_revision();
    }

    fn push_undo(&mut self, step: Step) {
        self.undo.push(step);
        if self.undo.len() > MAX_UNDO {
            self.undo.remove(0);
        }
        self.redo.clear();
    }

    /// Swaps the current state with `step`'s, returning the step that restores the current
    /// state.
    fn swap(&mut self, step: Step) -> Step {
        self.revision = next_revision();
        match step {
            Step::Edit { swp, active } => Step::Edit {
                swp: std::mem::replace(&mut self.swp, swp),
                active: std::mem::replace(&mut self.active, active),
            },
            Step::Replace { swp, active, file } => Step::Replace {
                swp: std::mem::replace(&mut self.swp, swp),
                active: std::mem::replace(&mut self.active, active),
                file: std::mem::replace(&mut self.file, file),
            },
        }
    }

    /// Undoes the last edit; `false` if there is none.
    pub fn undo(&mut self) -> bool {
        let Some(step) = self.undo.pop() else { return false };
        let back = self.swap(step);
        self.redo.push(back);
        true
    }

    /// Redoes the last undone edit; `false` if there is none.
    pub fn redo(&mut self) -> bool {
        let Some(step) = self.redo.pop() else { return false };
        let back = self.swap(step);
        self.undo.push(back);
        true
    }

    /// Whether [`undo`](Self::undo) would do something.
    #[must_use]
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether [`redo`](Self::redo) would do something.
    #[must_use]
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// The active curve's points for editing, converting a circle, helix or trefoil to the
    /// control points of a curve through samples of it (so it can be edited at all).
    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        let curve = self.swp.curves.get_mut(self.active)?;
        if curve.geometry.points_mut().is_none() {
            let samples = sample_closed(curve);
            curve.closed = !matches!(curve.kind, SwpCurveKind::Helix);
            curve.kind = SwpCurveKind::BSpline;
            curve.geometry = SwpGeometry::Points(samples);
        }
        curve.geometry.points_mut()
    }

    /// Appends a point to the active curve (a Hermite curve gets the tangent of its last
    /// segment direction, a Kochanek–Bartels key tension, continuity and bias 0).
    pub fn add_point(&mut self, p: DVec3) {
        let n = self.points().len();
        self.insert_point(n, p);
    }

    /// Inserts a point before index `at` (`at` = the number of points appends).
    pub fn insert_point(&mut self, at: usize, p: DVec3) {
        self.checkpoint();
        if self.curve().is_none() {
            self.swp.curves.push(empty_curve("profile", NEW_CURVE_KIND, 2));
            self.active = self.swp.curves.len() - 1;
        }
        let p = if self.is_2d() { DVec3::new(p.x, p.y, 0.0) } else { p };
        let Some(points) = self.points_mut() else { return };
        let at = at.min(points.len());
        let prev = if at > 0 { Some(points[at - 1]) } else { None };
        points.insert(at, p);
        match self.swp.curves.get_mut(self.active).map(|c| &mut c.geometry) {
            Some(SwpGeometry::Hermite { tangents, .. }) => {
                let t = prev.map_or(DVec3::X, |q| p - q);
                tangents.insert(at.min(tangents.len()), t);
            }
            Some(SwpGeometry::Tcb { shape, .. }) => shape.insert(at.min(shape.len()), Tcb::default()),
            Some(SwpGeometry::Nurbs { weights, knots, .. }) => {
                weights.insert(at.min(weights.len()), 1.0);
                // one knot more is needed: the default vector, rather than a guess
                *knots = None;
            }
            _ => {}
        }
    }

    /// Inserts a point on the control polygon's edge from point `edge` to the next one (the
    /// closing edge of a closed curve too), at fraction `t` of the edge; returns the index of
    /// the point to select.
    ///
    /// A Bézier spline keeps its shape and stays valid: the segment that owns the edge is
    /// split by De Casteljau at the parameter of the click (edge `j` of the segment's three at
    /// fraction `t` is parameter `(j + t)/3`), which puts three new points in place of two and
    /// the segment's new end point on the curve. Other kinds get `p` between the edge's ends.
    pub fn insert_on_polygon(&mut self, edge: usize, t: f64, p: DVec3) -> usize {
        let bezier = self.curve().is_some_and(|c| c.kind == SwpCurveKind::Bezier);
        let n = self.points().len();
        let closed = self.curve().is_some_and(|c| c.closed);
        let valid = SwpCurveKind::Bezier.accepts_point_count(closed, n as u64);
        let edges = if closed { n } else { n.saturating_sub(1) };
        if !bezier || !valid || edge >= edges {
            self.insert_point(edge + 1, p);
            return (edge + 1).min(self.points().len().saturating_sub(1));
        }
        let (k, j) = (edge / 3, edge % 3);
        let u = ((j as f64 + t.clamp(0.0, 1.0)) / 3.0).clamp(0.0, 1.0);
        let pts = self.points();
        let at = |i: usize| pts[(3 * k + i) % n];
        let segment = splinekit::CubicBezier::new(at(0), at(1), at(2), at(3));
        let (left, right) = segment.split(u);
        self.checkpoint();
        let Some(points) = self.points_mut() else { return 0 };
        // the segment's two inner points become five: left.p1, left.p2, the split point,
        // right.p1, right.p2
        let first = 3 * k + 1;
        points.splice(first..first + 2, [left.p1, left.p2, left.p3, right.p1, right.p2]);
        first + 2
    }

    /// Starts moving point `i` (records the undo step of the whole drag).
    pub fn begin_move(&mut self) {
        self.checkpoint();
    }

    /// Moves point `i` to `p` (z kept at 0 on 2D curves). Call [`begin_move`](Self::begin_move)
    /// first for one undo step per drag; [`move_point`](Self::move_point) does both.
    pub fn set_point(&mut self, i: usize, p: DVec3) {
        let flat = self.is_2d();
        if let Some(points) = self.points_mut()
            && let Some(q) = points.get_mut(i)
        {
            *q = if flat { DVec3::new(p.x, p.y, 0.0) } else { p };
            self.revision = next_revision();
        }
    }

    /// Moves point `i` to `p` as one undoable edit.
    pub fn move_point(&mut self, i: usize, p: DVec3) {
        if i < self.points().len() {
            self.begin_move();
            self.set_point(i, p);
        }
    }

    /// Deletes point `i` of the active curve.
    pub fn delete_point(&mut self, i: usize) {
        if i >= self.points().len() {
            return;
        }
        self.checkpoint();
        if let Some(curve) = self.swp.curves.get_mut(self.active) {
            match &mut curve.geometry {
                SwpGeometry::Points(p) => {
                    p.remove(i);
                }
                SwpGeometry::Hermite { points, tangents } => {
                    points.remove(i);
                    if i < tangents.len() {
                        tangents.remove(i);
                    }
                }
                SwpGeometry::Tcb { points, shape } => {
                    points.remove(i);
                    if i < shape.len() {
                        shape.remove(i);
                    }
                }
                SwpGeometry::Nurbs { points, weights, knots } => {
                    points.remove(i);
                    if i < weights.len() {
                        weights.remove(i);
                    }
                    *knots = None;
                }
                _ => {}
            }
        }
    }

    /// Removes every point of the active curve.
    pub fn clear(&mut self) {
        if self.points().is_empty() {
            return;
        }
        self.checkpoint();
        if let Some(curve) = self.swp.curves.get_mut(self.active) {
            curve.geometry = empty_geometry(curve.kind);
        }
    }

    /// Changes the active curve's kind, keeping its points (a Hermite curve gets
    /// Catmull-Rom tangents, a Kochanek–Bartels curve tension, continuity and bias 0 at every
    /// key, the same curve as uniform Catmull-Rom, a NURBS weights 1 and the clamped uniform
    /// knots, of degree 3 or, with fewer than 4 points, one less than their number; leaving
    /// them drops the tangents, shapes or weights). A single Bézier curve is open.
    pub fn set_kind(&mut self, kind: SwpCurveKind) {
        if self.curve().is_none_or(|c| same_kind(c.kind, kind)) {
            return;
        }
        self.checkpoint();
        let points = self.points_mut().map(|p| p.clone()).unwrap_or_default();
        let Some(curve) = self.swp.curves.get_mut(self.active) else { return };
        curve.kind = match kind {
            SwpCurveKind::Nurbs { degree } if points.len() >= 2 => {
                SwpCurveKind::Nurbs { degree: degree.min(points.len() as u32 - 1) }
            }
            _ => kind,
        };
        if kind == SwpCurveKind::BezierN {
            curve.closed = false;
        }
        curve.geometry = match kind {
            SwpCurveKind::Hermite => {
                let tangents = catmull_rom_tangents(&points, curve.closed);
                SwpGeometry::Hermite { points, tangents }
            }
            SwpCurveKind::KochanekBartels => SwpGeometry::Tcb { shape: vec![Tcb::default(); points.len()], points },
            SwpCurveKind::Nurbs { .. } => SwpGeometry::Nurbs { weights: vec![1.0; points.len()], points, knots: None },
            _ => SwpGeometry::Points(points),
        };
    }

    /// Switches to the next kind of [`KINDS`] (the `s` key).
    pub fn cycle_kind(&mut self) {
        let Some(curve) = self.curve() else { return };
        let next = KINDS.iter().position(|(k, _)| same_kind(*k, curve.kind)).map_or(0, |i| (i + 1) % KINDS.len());
        self.set_kind(KINDS[next].0);
    }

    /// Opens or closes the active curve (not a single Bézier curve, which is always open; a
    /// closed NURBS is periodic, with knots of its own).
    pub fn set_closed(&mut self, closed: bool) {
        if self.curve().is_none_or(|c| {
            c.closed == closed
                || c.kind == SwpCurveKind::BezierN
                || !matches!(
                    c.geometry,
                    SwpGeometry::Points(_)
                        | SwpGeometry::Hermite { .. }
                        | SwpGeometry::Tcb { .. }
                        | SwpGeometry::Nurbs { .. }
                )
        }) {
            return;
        }
        self.checkpoint();
        if let Some(curve) = self.swp.curves.get_mut(self.active) {
            curve.closed = closed;
            if let SwpGeometry::Nurbs { knots, .. } = &mut curve.geometry {
                *knots = None;
            }
        }
    }

    /// Adds a new empty 2D curve of the active curve's kind and makes it active.
    pub fn add_curve(&mut self) {
        self.checkpoint();
        let kind = self.curve().map_or(NEW_CURVE_KIND, |c| c.kind);
        let kind = if matches!(kind, SwpCurveKind::Circle | SwpCurveKind::Helix | SwpCurveKind::Trefoil) {
            NEW_CURVE_KIND
        } else {
            kind
        };
        let mut k = self.swp.curves.len();
        while self.swp.curve_index(&format!("curve{k}")).is_some() {
            k += 1;
        }
        self.swp.curves.push(empty_curve(&format!("curve{k}"), kind, 2));
        self.active = self.swp.curves.len() - 1;
    }

    /// Adds a surface of revolution of curve `profile` about +y with `slices` slices (SWP
    /// `srev`), named `surface`, `surface2`, …; one undo step. Returns its index.
    pub fn add_revolution(&mut self, profile: usize, slices: u32) -> usize {
        self.checkpoint();
        // a surface refers to its curve by name: an anonymous profile gets one
        self.name_curve(profile, "profile");
        let name = self.unused_name("surface");
        self.swp.surfaces.push(SwpSurface {
            name: Some(name),
            kind: SwpSurfaceKind::Revolution { steps: slices.clamp(1, splinekit_io::swp::MAX_STEPS), profile },
            settings: Default::default(),
            pos: SourcePos::new(1, 1),
        });
        self.swp.surfaces.len() - 1
    }

    /// Adds a surface of revolution of curve `profile` about +z with the revolution tool's
    /// settings (SWP `zrev`: default angle tolerance, 32 slices, scale 1), named `surface`,
    /// `surface2`, …; one undo step. Returns its index.
    pub fn add_revolution_z(&mut self, profile: usize) -> usize {
        self.checkpoint();
        self.name_curve(profile, "profile");
        let name = self.unused_name("surface");
        self.swp.surfaces.push(SwpSurface {
            name: Some(name),
            kind: SwpSurfaceKind::RevolutionZ {
                profile,
                epsilon: splinekit_io::swp::DEFAULT_ZREV_EPSILON,
                slice_tolerance: splinekit_io::swp::DEFAULT_ZREV_SLICE_TOLERANCE,
                scale: 1.0,
            },
            settings: Default::default(),
            pos: SourcePos::new(1, 1),
        });
        self.swp.surfaces.len() - 1
    }

    /// Adds a generalized cylinder (SWP `gcyl`): curve `profile` swept along curve `sweep`,
    /// named `sweep`, `sweep2`, …; one undo step. Returns its index.
    pub fn add_sweep(&mut self, profile: usize, sweep: usize) -> usize {
        self.checkpoint();
        self.name_curve(profile, "profile");
        self.name_curve(sweep, "path");
        let name = self.unused_name("sweep");
        self.swp.surfaces.push(SwpSurface {
            name: Some(name),
            kind: SwpSurfaceKind::GeneralizedCylinder { profile, sweep, scale: None, twist: None },
            settings: Default::default(),
            pos: SourcePos::new(1, 1),
        });
        self.swp.surfaces.len() - 1
    }

    /// Adds a lathe (SWP `lathe`) with two new Bézier curves, `radius` and `height` (graphs
    /// over x from 0 to 1 whose y are r(v) and z(v): a vase with a rounded bottom), 32 stacks
    /// and 32 slices; one undo step. The radius curve becomes the active one. Returns the
    /// surface's index.
    pub fn add_lathe(&mut self) -> usize {
        self.checkpoint();
        let graph = |name: &str, ys: [f64; 7]| {
            let mut curve = empty_curve(name, SwpCurveKind::Bezier, 2);
            let points = ys.iter().enumerate().map(|(i, &y)| DVec3::new(i as f64 / 6.0, y, 0.0)).collect();
            curve.geometry = SwpGeometry::Points(points);
            curve.steps = 16;
            curve
        };
        let radius_name = self.unused_name("radius");
        let mut radius = graph(&radius_name, [0.0, 0.6, 1.0, 0.6, 0.4, 0.7, 0.8]);
        radius.name = Some(radius_name);
        self.swp.curves.push(radius);
        let r = self.swp.curves.len() - 1;
        let height_name = self.unused_name("height");
        self.swp.curves.push(graph(&height_name, [0.0, 0.0, 0.4, 1.0, 1.6, 2.0, 2.4]));
        let h = self.swp.curves.len() - 1;
        let name = self.unused_name("lathe");
        self.swp.surfaces.push(SwpSurface {
            name: Some(name),
            kind: SwpSurfaceKind::Lathe { stacks: 32, slices: 32, radius: r, height: h },
            settings: Default::default(),
            pos: SourcePos::new(1, 1),
        });
        self.active = r;
        self.swp.surfaces.len() - 1
    }

    /// Replaces the kind of surface `i` (its settings or curves), no undo step of its own, as
    /// [`set_revolution_slices`](Self::set_revolution_slices); curves it now uses get names.
    pub fn set_surface_kind(&mut self, i: usize, kind: SwpSurfaceKind) {
        if i >= self.swp.surfaces.len() {
            return;
        }
        for (role, c) in kind.references() {
            self.name_curve(c, role.word());
        }
        self.swp.surfaces[i].kind = kind;
        self.revision = next_revision();
    }

    /// Replaces the settings of surface `i` (tessellation, layout, frames, caps), no undo step
    /// of its own, as [`set_revolution_slices`](Self::set_revolution_slices).
    pub fn set_surface_settings(&mut self, i: usize, settings: splinekit_io::SwpSurfaceSettings) {
        if let Some(s) = self.swp.surfaces.get_mut(i) {
            s.settings = settings;
            self.revision = next_revision();
        }
    }

    /// Gives curve `i` a name (`base`, `base2`, …) if it has none: a surface refers to its
    /// curves by name.
    fn name_curve(&mut self, i: usize, base: &str) {
        if self.swp.curves.get(i).is_some_and(|c| c.name.is_none()) {
            let name = self.unused_name(base);
            self.swp.curves[i].name = Some(name);
        }
    }

    /// `base`, or `base2`, `base3`, … : the first that names no curve or surface.
    fn unused_name(&self, base: &str) -> String {
        (1..)
            .map(|k| if k == 1 { base.to_owned() } else { format!("{base}{k}") })
            .find(|n| self.swp.curve_index(n).is_none() && self.swp.surface_index(n).is_none())
            .unwrap_or_else(|| base.to_owned())
    }

    /// Sets the slices of surface `i` if it is a surface of revolution (no undo step of its
    /// own: call [`begin_move`](Self::begin_move) first, once per drag of the value).
    pub fn set_revolution_slices(&mut self, i: usize, slices: u32) {
        if let Some(SwpSurfaceKind::Revolution { steps, .. }) = self.swp.surfaces.get_mut(i).map(|s| &mut s.kind) {
            *steps = slices.clamp(1, splinekit_io::swp::MAX_STEPS);
            self.revision = next_revision();
        }
    }

    /// Sets the tessellation steps of curve `i` (per segment; for circles, of the whole
    /// curve); no undo step of its own, as [`set_revolution_slices`](Self::set_revolution_slices).
    pub fn set_curve_steps(&mut self, i: usize, steps: u32) {
        if let Some(c) = self.swp.curves.get_mut(i) {
            c.steps = steps.clamp(1, splinekit_io::swp::MAX_STEPS);
            self.revision = next_revision();
        }
    }

    /// Makes curve `i` the active one (not an edit: no undo step).
    pub fn select_curve(&mut self, i: usize) {
        if i < self.swp.curves.len() && i != self.active {
            self.active = i;
            self.revision = next_revision();
        }
    }

    /// Replaces the document by the preset scene (the `r` key), as one undo step; see
    /// [`preset_scene`](Self::preset_scene).
    pub fn preset(&mut self) {
        self.replace_with(Self::preset_scene());
    }

    /// The preset scene of the arc-length lab: 8 points
    /// `Pᵢ = (r cos θ, r sin θ, −0.5 + αᵢ)`, `αᵢ = i/7`, `θ = 2π·αᵢ`, `r = cos 2θ`, an open
    /// uniform Catmull-Rom spline, 5 steps per segment; a new, untitled document (not
    /// modified: the key makes it again).
    #[must_use]
    pub fn preset_scene() -> Self {
        let points = (0..8)
            .map(|i| {
                let alpha = f64::from(i) / 7.0;
                let theta = TAU * alpha;
                let r = (2.0 * theta).cos();
                DVec3::new(r * theta.cos(), r * theta.sin(), -0.5 + alpha)
            })
            .collect();
        let mut curve = empty_curve("preset", SwpCurveKind::CatmullRom { alpha: 0.0 }, 3);
        curve.steps = 5;
        curve.geometry = SwpGeometry::Points(points);
        Self::from_swp(SwpDocument { curves: vec![curve], surfaces: Vec::new() }, None)
    }

    /// The SWP text of the document (see [`SwpDocument::to_swp_string`]).
    #[must_use]
    pub fn to_swp_string(&self) -> String {
        self.swp.to_swp_string()
    }
}

/// A curve with no points.
fn empty_curve(name: &str, kind: SwpCurveKind, dim: u8) -> SwpCurve {
    SwpCurve {
        name: Some(name.to_owned()),
        kind,
        dim,
        steps: 16,
        closed: false,
        geometry: empty_geometry(kind),
        pos: SourcePos::new(1, 1),
    }
}

/// The geometry of a curve of `kind` with no points.
fn empty_geometry(kind: SwpCurveKind) -> SwpGeometry {
    match kind {
        SwpCurveKind::Hermite => SwpGeometry::Hermite { points: Vec::new(), tangents: Vec::new() },
        SwpCurveKind::KochanekBartels => SwpGeometry::Tcb { points: Vec::new(), shape: Vec::new() },
        SwpCurveKind::Nurbs { .. } => SwpGeometry::Nurbs { points: Vec::new(), weights: Vec::new(), knots: None },
        _ => SwpGeometry::Points(Vec::new()),
    }
}

/// Twelve points on a circle, helix or trefoil (equal parameter steps), for turning it into an
/// editable B-spline; empty if the curve cannot be built.
fn sample_closed(curve: &SwpCurve) -> Vec<DVec3> {
    let Ok(c) = curve.to_curve() else { return Vec::new() };
    let n = 12;
    let m = c.num_segments() as f64;
    let closed = c.is_closed();
    let count = if closed { n } else { n + 1 };
    (0..count).map(|i| c.eval(m * i as f64 / n as f64)).collect()
}

/// Catmull-Rom tangents `(P[i+1] − P[i−1]) / 2` (one-sided at the ends of an open curve).
fn catmull_rom_tangents(points: &[DVec3], closed: bool) -> Vec<DVec3> {
    let n = points.len();
    (0..n)
        .map(|i| {
            if n < 2 {
                return DVec3::X;
            }
            let (prev, next) = if closed {
                (points[(i + n - 1) % n], points[(i + 1) % n])
            } else {
                (points[i.saturating_sub(1)], points[(i + 1).min(n - 1)])
            };
            let scale = if closed || (i > 0 && i + 1 < n) { 0.5 } else { 1.0 };
            (next - prev) * scale
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Bézier curve through `points` (each added as an undoable edit).
    fn doc_with(points: &[(f64, f64)]) -> Document {
        let mut d = Document::new();
        d.swp.curves[0].kind = SwpCurveKind::Bezier;
        for &(x, y) in points {
            d.add_point(DVec3::new(x, y, 0.0));
        }
        d
    }

    #[test]
    fn add_insert_move_delete_and_undo_every_step() {
        let mut d = doc_with(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)]);
        assert_eq!(d.points().len(), 4);
        assert!(d.spline().is_ok(), "4 points make one Bézier segment");
        d.insert_point(2, DVec3::new(1.5, 1.0, 7.0));
        assert_eq!(d.points()[2], DVec3::new(1.5, 1.0, 0.0), "2D curves stay in the plane");
        assert!(d.spline().is_err(), "5 points are not 3k + 1");
        d.move_point(0, DVec3::new(-1.0, 2.0, 0.0));
        d.delete_point(4);
        assert_eq!(
            d.points(),
            &[DVec3::new(-1.0, 2.0, 0.0), DVec3::X, DVec3::new(1.5, 1.0, 0.0), DVec3::new(2.0, 0.0, 0.0)]
        );
        assert!(d.undo()); // delete
        assert_eq!(d.points().len(), 5);
        assert!(d.undo()); // move
        assert_eq!(d.points()[0], DVec3::ZERO);
        assert!(d.redo());
        assert_eq!(d.points()[0], DVec3::new(-1.0, 2.0, 0.0));
        for _ in 0..6 {
            d.undo();
        }
        assert!(d.points().is_empty() && !d.can_undo());
    }

    #[test]
    fn a_drag_is_one_undo_step() {
        let mut d = doc_with(&[(0.0, 0.0), (1.0, 0.0)]);
        d.begin_move();
        for k in 1..=10 {
            d.set_point(1, DVec3::new(1.0, f64::from(k), 0.0));
        }
        assert_eq!(d.points()[1], DVec3::new(1.0, 10.0, 0.0));
        d.undo();
        assert_eq!(d.points()[1], DVec3::X);
    }

    #[test]
    fn kinds_keep_points_and_hermite_gets_tangents() {
        let mut d = doc_with(&[(0.0, 0.0), (1.0, 1.0), (2.0, 0.0), (3.0, 1.0)]);
        let before = d.points().to_vec();
        for _ in 0..KINDS.len() {
            d.cycle_kind();
            assert_eq!(d.points(), before.as_slice());
            assert!(d.spline().is_ok(), "{:?}", d.curve().unwrap().kind);
        }
        assert_eq!(d.curve().unwrap().kind, SwpCurveKind::Bezier, "the cycle comes back");
        d.set_kind(SwpCurveKind::Hermite);
        let Some(SwpGeometry::Hermite { tangents, .. }) = d.curve().map(|c| &c.geometry) else { panic!() };
        assert_eq!(tangents[1], DVec3::X); // (P2 − P0)/2
    }

    #[test]
    fn preset_is_the_reference_scene() {
        let mut d = Document::new();
        d.preset();
        let c = d.spline().unwrap();
        assert_eq!(c.num_segments(), 5);
        // reference scene: the chord table with 5 samples per segment ends at 5.06923
        let table = splinekit::arclen::ArclenTable::chord(&c, 5);
        assert!((table.length() - 5.06923).abs() < 5e-6, "{}", table.length());
        assert!(d.undo() && d.curve().unwrap().name.as_deref() == Some("profile"));
    }

    #[test]
    fn save_round_trips() {
        let mut d = doc_with(&[(0.0, 0.0), (1.0, 1.0), (2.0, 0.0), (3.0, 1.0)]);
        d.add_curve();
        for k in 0..7 {
            d.add_point(DVec3::new(0.1 * f64::from(k), 0.2, 0.0));
        }
        let text = d.to_swp_string();
        let back = SwpDocument::parse(&text, "t.swp").unwrap();
        assert_eq!(back.to_swp_string(), text);
        assert_eq!(back.curves.len(), 2);
        assert_eq!(back.curves[0].geometry, d.swp.curves[0].geometry);
    }
}
