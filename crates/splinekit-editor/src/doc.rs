//! The edited document: an SWP document, the active curve, and undo/redo.
//!
//! Every edit goes through a method here, so the user interface stays thin and the edits are
//! tested without a window. Each method that changes the document records one undo step
//! (a drag records one step when it starts, however many moves follow).

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;
use splinekit::{AnyCurve, ParamCurve};
use splinekit_io::{SourcePos, SwpCurve, SwpCurveKind, SwpDocument, SwpGeometry};

/// Most undo steps kept; older ones are dropped.
pub const MAX_UNDO: usize = 500;

/// The spline kinds the kind switch offers, in the order `s` cycles through them.
pub const KINDS: [(SwpCurveKind, &str); 5] = [
    (SwpCurveKind::Bezier, "Bézier"),
    (SwpCurveKind::BSpline, "B-spline"),
    (SwpCurveKind::CatmullRom { alpha: 0.0 }, "Catmull-Rom (uniform)"),
    (SwpCurveKind::CatmullRom { alpha: 0.5 }, "Catmull-Rom (centripetal)"),
    (SwpCurveKind::Hermite, "Hermite"),
];

/// The display name of a curve kind.
#[must_use]
pub fn kind_name(kind: SwpCurveKind) -> &'static str {
    match kind {
        SwpCurveKind::Circle => "circle",
        SwpCurveKind::Helix => "helix",
        SwpCurveKind::Trefoil => "trefoil",
        SwpCurveKind::CatmullRom { alpha } if alpha != 0.0 && alpha != 0.5 => "Catmull-Rom",
        _ => KINDS.iter().find(|(k, _)| *k == kind).map_or("?", |(_, name)| name),
    }
}

/// The document being edited.
#[derive(Debug, Clone)]
pub struct Document {
    /// The curves and surfaces.
    pub swp: SwpDocument,
    /// The index of the curve being edited (always valid when there are curves).
    pub active: usize,
    /// The file the document was loaded from or last saved to.
    pub path: Option<PathBuf>,
    undo: Vec<(SwpDocument, usize)>,
    redo: Vec<(SwpDocument, usize)>,
    /// Changes on every change, so views know when to rebuild what they derive from it.
    revision: u64,
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

impl Document {
    /// An empty document with one empty 2D Bézier curve called `profile`.
    #[must_use]
    pub fn new() -> Self {
        let mut swp = SwpDocument::default();
        swp.curves.push(empty_curve("profile", SwpCurveKind::Bezier, 2));
        Self::from_swp(swp, None)
    }

    /// A document for `swp` (loaded from `path`, if given).
    #[must_use]
    pub fn from_swp(swp: SwpDocument, path: Option<PathBuf>) -> Self {
        Self { swp, active: 0, path, undo: Vec::new(), redo: Vec::new(), revision: next_revision() }
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

    /// The editable points of the active curve (control points, or a Hermite curve's points);
    /// empty for circles, helices and trefoils.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        match self.curve().map(|c| &c.geometry) {
            Some(SwpGeometry::Points(p)) | Some(SwpGeometry::Hermite { points: p, .. }) => p,
            _ => &[],
        }
    }

    /// Whether the active curve lives in the xy-plane (a 2D SWP kind).
    #[must_use]
    pub fn is_2d(&self) -> bool {
        self.curve().is_some_and(|c| c.dim != 3)
    }

    /// Records an undo step for the current state.
    fn checkpoint(&mut self) {
        self.undo.push((self.swp.clone(), self.active));
        if self.undo.len() > MAX_UNDO {
            self.undo.remove(0);
        }
        self.redo.clear();
        self.revision = next_revision();
    }

    /// Undoes the last edit; `false` if there is none.
    pub fn undo(&mut self) -> bool {
        let Some((swp, active)) = self.undo.pop() else { return false };
        self.redo.push((std::mem::replace(&mut self.swp, swp), self.active));
        self.active = active;
        self.revision = next_revision();
        true
    }

    /// Redoes the last undone edit; `false` if there is none.
    pub fn redo(&mut self) -> bool {
        let Some((swp, active)) = self.redo.pop() else { return false };
        self.undo.push((std::mem::replace(&mut self.swp, swp), self.active));
        self.active = active;
        self.revision = next_revision();
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
        if !matches!(curve.geometry, SwpGeometry::Points(_) | SwpGeometry::Hermite { .. }) {
            let samples = sample_closed(curve);
            curve.closed = !matches!(curve.kind, SwpCurveKind::Helix);
            curve.kind = SwpCurveKind::BSpline;
            curve.geometry = SwpGeometry::Points(samples);
        }
        match &mut curve.geometry {
            SwpGeometry::Points(p) => Some(p),
            SwpGeometry::Hermite { points, .. } => Some(points),
            _ => None,
        }
    }

    /// Appends a point to the active curve (a Hermite curve gets the tangent of its last
    /// segment direction).
    pub fn add_point(&mut self, p: DVec3) {
        let n = self.points().len();
        self.insert_point(n, p);
    }

    /// Inserts a point before index `at` (`at` = the number of points appends).
    pub fn insert_point(&mut self, at: usize, p: DVec3) {
        if self.curve().is_none() {
            self.swp.curves.push(empty_curve("profile", SwpCurveKind::Bezier, 2));
            self.active = self.swp.curves.len() - 1;
        }
        self.checkpoint();
        let p = if self.is_2d() { DVec3::new(p.x, p.y, 0.0) } else { p };
        let Some(points) = self.points_mut() else { return };
        let at = at.min(points.len());
        let prev = if at > 0 { Some(points[at - 1]) } else { None };
        points.insert(at, p);
        if let Some(SwpGeometry::Hermite { tangents, .. }) =
            self.swp.curves.get_mut(self.active).map(|c| &mut c.geometry)
        {
            let t = prev.map_or(DVec3::X, |q| p - q);
            tangents.insert(at.min(tangents.len()), t);
        }
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
            curve.geometry = match curve.geometry {
                SwpGeometry::Hermite { .. } => SwpGeometry::Hermite { points: Vec::new(), tangents: Vec::new() },
                _ => SwpGeometry::Points(Vec::new()),
            };
        }
    }

    /// Changes the active curve's kind, keeping its points (a Hermite curve gets
    /// Catmull-Rom tangents; leaving Hermite drops the tangents).
    pub fn set_kind(&mut self, kind: SwpCurveKind) {
        if self.curve().is_none_or(|c| c.kind == kind) {
            return;
        }
        self.checkpoint();
        let points = self.points_mut().map(|p| p.clone()).unwrap_or_default();
        let Some(curve) = self.swp.curves.get_mut(self.active) else { return };
        curve.kind = kind;
        curve.geometry = if kind == SwpCurveKind::Hermite {
            let tangents = catmull_rom_tangents(&points, curve.closed);
            SwpGeometry::Hermite { points, tangents }
        } else {
            SwpGeometry::Points(points)
        };
    }

    /// Switches to the next kind of [`KINDS`] (the `s` key).
    pub fn cycle_kind(&mut self) {
        let Some(curve) = self.curve() else { return };
        let next = KINDS.iter().position(|(k, _)| *k == curve.kind).map_or(0, |i| (i + 1) % KINDS.len());
        self.set_kind(KINDS[next].0);
    }

    /// Opens or closes the active curve.
    pub fn set_closed(&mut self, closed: bool) {
        if self.curve().is_none_or(|c| {
            c.closed == closed || !matches!(c.geometry, SwpGeometry::Points(_) | SwpGeometry::Hermite { .. })
        }) {
            return;
        }
        self.checkpoint();
        if let Some(curve) = self.swp.curves.get_mut(self.active) {
            curve.closed = closed;
        }
    }

    /// Adds a new empty 2D curve of the active curve's kind and makes it active.
    pub fn add_curve(&mut self) {
        self.checkpoint();
        let kind = self.curve().map_or(SwpCurveKind::Bezier, |c| c.kind);
        let kind = if matches!(kind, SwpCurveKind::Circle | SwpCurveKind::Helix | SwpCurveKind::Trefoil) {
            SwpCurveKind::Bezier
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

    /// Makes curve `i` the active one (not an edit: no undo step).
    pub fn select_curve(&mut self, i: usize) {
        if i < self.swp.curves.len() && i != self.active {
            self.active = i;
            self.revision = next_revision();
        }
    }

    /// Replaces the document by the reference scene of SPEC §1.4 (the `r` key): 8 points
    /// `Pᵢ = (r cos θ, r sin θ, −0.5 + αᵢ)`, `αᵢ = i/7`, `θ = 2π·αᵢ`, `r = cos 2θ`, an open
    /// uniform Catmull-Rom spline, 5 steps per segment. Undoable.
    pub fn preset(&mut self) {
        self.checkpoint();
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
        self.swp = SwpDocument { curves: vec![curve], surfaces: Vec::new() };
        self.active = 0;
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
        geometry: if kind == SwpCurveKind::Hermite {
            SwpGeometry::Hermite { points: Vec::new(), tangents: Vec::new() }
        } else {
            SwpGeometry::Points(Vec::new())
        },
        pos: SourcePos::new(1, 1),
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

    fn doc_with(points: &[(f64, f64)]) -> Document {
        let mut d = Document::new();
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
        // SPEC §1.4: chord table with 5 samples per segment ends at 5.06923
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
