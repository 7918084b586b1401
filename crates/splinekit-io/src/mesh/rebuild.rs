//! Rebuilding the surface of a spline-annotated OBJ file from its header alone
//! ([`SplineHeader::rebuild`]).
//!
//! The header ([`revolution_obj`](super::revolution_obj)) records the spline(s) and the tool's
//! settings; this module turns them back into the mesh, following what the CS 4620 tools did.
//!
//! # Sweep headers (the older sweep tool)
//!
//! The tool's rules were deduced from the four meshes it left in `data/obj/cs4620-splines/`,
//! and [`rebuild`](SweepHeader::rebuild) with [`MeshLayout::Compat`] reproduces each of them:
//! the same vertex and triangle counts, the same triangles index for index, positions within
//! `2.1e-6` (the files keep six decimals of `f32` arithmetic), normals within `2e-4` (up to
//! one global sign, see below).
//!
//! - **Splines.** Both splines are uniform cubic B-splines (the header does not say; the tool
//!   had no other kind). Open: `n ≥ 4` points, segment `k` from `P(k)..P(k+3)`. Closed: `n ≥
//!   3` points, `n` segments, indices mod n.
//! - **Tessellation (`epsilon`).** Each Bézier segment is halved at `t = ½` (De Casteljau)
//!   while an angle of its control polygon (at `p1` or at `p2`) exceeds **`epsilon`** radians.
//!   That is the angle-tolerance tessellation (split while an angle exceeds half the
//!   tolerance) with tolerance `2·epsilon`: the meshes have half the points that the rule
//!   "exceeds `epsilon/2`" of the later revolution tool would give, on all eight curves.
//!   Each piece contributes its *start* point, so a curve's samples are
//!   the starts of its pieces: a closed curve then repeats its first sample as a seam, an
//!   open one ends one piece short of its end point (a quirk kept by the compat layout only).
//! - **Placement.** The swept-along spline lies in the xz-plane (`(x, y) → (x, 0, y)`), and
//!   at each of its samples, with unit tangent `T = (tx, 0, ty)`, the cross-section sample
//!   `(x, y)` goes to `V + scale·(x·Y + y·(T × Y))` with `Y = +y`: the cross-section's x
//!   runs up, its y sideways. Cross-section samples are used in reverse order.
//! - **Normals.** The cross-section's right normal `(ty, −tx)`, placed like the points. In
//!   `challace_revolution.obj` they point inward while the triangles face outward; the
//!   rebuild makes normals agree with the triangles, so that file's normals come out negated.
//! - **Layout.** One ring per swept-along sample (a closed curve repeats its first ring at the
//!   end), ring by ring, vertex `j·P + i`; triangles `(a, a+P, a+1)` and `(a+1, a+P, a+P+1)`
//!   with `a = j·P + i`: [`generalized_cylinder`] in its compat layout, whose outward
//!   orientation picks exactly these. The tool wrote `vt 0 0` for every vertex; the rebuild
//!   has no UVs unless asked.
//!
//! [`MeshLayout::Welded`] (the default) shares the seams of closed curves instead, so a closed
//! cross-section swept along a closed curve is watertight, and samples open curves up to
//! their end point.
//!
//! # Revolution headers (the interactive revolution tool, revolving about +z)
//!
//! No mesh of that tool survives, so its layout cannot be checked; the rebuild follows the
//! tool's spline code and its revolution about +z (below), and [`revolve_z`] builds the mesh
//! (seams and poles shared, in every layout):
//!
//! - **Spline.** `isBSpline` picks a uniform cubic B-spline, else a uniform Catmull-Rom spline
//!   (same windows and point counts as above).
//! - **Tessellation.** The angle mode with tolerance `epsilon`: halve while a
//!   control-polygon angle exceeds `epsilon/2` (the tool's code). The whole curve is sampled,
//!   end point included.
//! - **Revolution.** About +z: `(x, y) → (s·x·cos φ, s·x·sin φ, s·y)` with `s = Scale`, and
//!   `ceil(2π / sliceTolerance)` slices. A profile drawn on the x < 0 side is mirrored (the
//!   same surface); one that crosses the axis is an error.
//!
//! # Differences from the tools
//!
//! The tools worked in `f32`; this works in `f64` (positions agree to about `1e-6`). They
//! halved a segment up to 11 times, this at most 10 ([`MAX_ANGLE_DEPTH`]): the two differ
//! only where pieces never straighten out, at a cusp or a corner of the curve (a control point
//! repeated three times), where the tools have a sample or two more right at that point. A
//! control polygon with a zero-length edge gave the tools NaN angles (and NaN normals); here it
//! follows the angle mode's rules for degenerate polygons: a zero-length edge takes the
//! direction of its neighbours, so no angle is NaN.
//!
//! [`MAX_ANGLE_DEPTH`]: splinekit::flatten::MAX_ANGLE_DEPTH

use glam::{DVec2, DVec3};
use splinekit::flatten::{Tessellation, flatten_count, flatten_params};
use splinekit::frame::Frame;
use splinekit::mesh::PolyMesh;
use splinekit::sweep::surface::{
    Lathe, LatheOptions, RevolveOptions, SurfaceError, UvMode, revolve_z, revolve_z_counts,
};
use splinekit::sweep::{
    self, MeshCounts, MeshLayout, Profile, SweepError, SweepOptions, SweepPath, SweptMesh, generalized_cylinder,
    generalized_cylinder_counts, revolve_counts,
};
use splinekit::{AnyCurve, BSpline, CatmullRom, ParamCurve, PiecewiseCubic, SplineError, TriMesh};

use super::revolution_obj::{HeaderSpline, RevolutionHeader, SplineHeader, SweepHeader};
use crate::surface::DEFAULT_MAX_TRIANGLES;

/// Relative tolerance (times the size of the profile) within which a revolution profile
/// point counts as on the axis when deciding which side the profile is on.
const AXIS_TOLERANCE: f64 = 1e-9;

/// What a surface builder makes: the mesh ([`TriMesh`]), or only its counts
/// ([`MeshCounts`], found from the samples without building the mesh).
pub(crate) trait Built: Sized {
    /// [`sweep::revolve`], or its counts.
    fn revolve(profile: &Profile, steps: usize, options: SweepOptions) -> Result<Self, SweepError>;
    /// [`generalized_cylinder`], or its counts.
    fn cylinder(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<Self, SweepError>;
    /// [`revolve_z`], or its counts.
    fn revolve_z(points: &[DVec2], normals: Option<&[DVec2]>, options: &RevolveOptions) -> Result<Self, SurfaceError>;
    /// [`Lathe::to_mesh`], or its counts.
    fn lathe(lathe: &Lathe, options: &LatheOptions) -> Result<Self, SurfaceError>;
}

impl Built for TriMesh {
    fn revolve(profile: &Profile, steps: usize, options: SweepOptions) -> Result<Self, SweepError> {
        sweep::revolve(profile, steps, options)
    }
    fn cylinder(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<Self, SweepError> {
        generalized_cylinder(profile, path, options)
    }
    fn revolve_z(points: &[DVec2], normals: Option<&[DVec2]>, options: &RevolveOptions) -> Result<Self, SurfaceError> {
        revolve_z(points, normals, options)
    }
    fn lathe(lathe: &Lathe, options: &LatheOptions) -> Result<Self, SurfaceError> {
        lathe.to_mesh(options)
    }
}

impl Built for SweptMesh {
    fn revolve(profile: &Profile, steps: usize, options: SweepOptions) -> Result<Self, SweepError> {
        Ok(SweptMesh { mesh: sweep::revolve_poly(profile, steps, options)?, unfit_corners: Vec::new() })
    }
    fn cylinder(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<Self, SweepError> {
        sweep::generalized_cylinder_poly(profile, path, options)
    }
    fn revolve_z(points: &[DVec2], normals: Option<&[DVec2]>, options: &RevolveOptions) -> Result<Self, SurfaceError> {
        let mesh = revolve_z(points, normals, options)?;
        Ok(SweptMesh { mesh: PolyMesh::from(&mesh), unfit_corners: Vec::new() })
    }
    fn lathe(lathe: &Lathe, options: &LatheOptions) -> Result<Self, SurfaceError> {
        Ok(SweptMesh { mesh: PolyMesh::from(&lathe.to_mesh(options)?), unfit_corners: Vec::new() })
    }
}

impl Built for MeshCounts {
    fn revolve(profile: &Profile, steps: usize, options: SweepOptions) -> Result<Self, SweepError> {
        revolve_counts(profile, steps, options)
    }
    fn cylinder(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<Self, SweepError> {
        generalized_cylinder_counts(profile, path, options)
    }
    fn revolve_z(points: &[DVec2], normals: Option<&[DVec2]>, options: &RevolveOptions) -> Result<Self, SurfaceError> {
        revolve_z_counts(points, normals, options)
    }
    fn lathe(lathe: &Lathe, options: &LatheOptions) -> Result<Self, SurfaceError> {
        lathe.counts(options)
    }
}

/// Options of [`SplineHeader::rebuild`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct RebuildOptions {
    /// Vertex layout of sweep headers: [`MeshLayout::Compat`] reproduces the sweep tool's mesh
    /// (duplicated seams, its samples), [`MeshLayout::Welded`] shares the seams. Revolution
    /// headers give the same mesh in both (see the [module docs](self)).
    pub layout: MeshLayout,
    /// Add texture coordinates: arc-length `(u, v)` for sweeps (a welded seam is then split
    /// for the jump in `u`), `(φ/2π, chord length)` for revolutions (seam split likewise).
    pub uvs: bool,
    /// The most triangles the mesh may have (`None`: as many as 32-bit indices allow),
    /// checked from the sample and slice counts before the mesh is built.
    pub max_triangles: Option<usize>,
}

impl RebuildOptions {
    /// [`MeshLayout::Welded`], no UVs, at most [`DEFAULT_MAX_TRIANGLES`] triangles.
    pub const DEFAULT: Self =
        Self { layout: MeshLayout::Welded, uvs: false, max_triangles: Some(DEFAULT_MAX_TRIANGLES) };

    /// Sets the vertex layout.
    #[must_use]
    pub const fn with_layout(mut self, layout: MeshLayout) -> Self {
        self.layout = layout;
        self
    }

    /// Sets whether texture coordinates are added.
    #[must_use]
    pub const fn with_uvs(mut self, uvs: bool) -> Self {
        self.uvs = uvs;
        self
    }

    /// Sets the most triangles the mesh may have.
    #[must_use]
    pub const fn with_max_triangles(mut self, max_triangles: Option<usize>) -> Self {
        self.max_triangles = max_triangles;
        self
    }

    /// Fails when `triangles` exceed the limit; `why` says where they come from.
    fn check(&self, triangles: u64, why: impl FnOnce() -> String) -> Result<(), RebuildError> {
        match self.max_triangles {
            Some(limit) if triangles > limit as u64 => Err(RebuildError::TooLarge { triangles, why: why(), limit }),
            _ => Ok(()),
        }
    }
}

/// Why the surface of a spline header could not be rebuilt.
///
/// The messages name the spline but not the file (a header does not know where it came
/// from): callers add the file name.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RebuildError {
    /// A spline of the header is not a valid spline of its kind (too few control points).
    #[error("{spline} spline: {error}")]
    Spline {
        /// `cross-section` or `swept-along`.
        spline: &'static str,
        /// What is wrong with it.
        error: SplineError,
    },
    /// The cross-section of a revolution has points on both sides of the axis.
    #[error(
        "the cross-section crosses the axis of revolution (x from {min_x} to {max_x} after scaling); \
         it must lie on one side of it"
    )]
    CrossesAxis {
        /// The smallest x of the tessellated, scaled cross-section.
        min_x: f64,
        /// The largest x.
        max_x: f64,
    },
    /// The surface of revolution could not be built.
    #[error("surface of revolution: {0}")]
    Revolve(SurfaceError),
    /// The sweep could not be built.
    #[error("sweep: {0}")]
    Sweep(SweepError),
    /// The mesh would have more triangles than [`RebuildOptions::max_triangles`].
    #[error("the surface would have about {triangles} triangles ({why}), more than the limit of {limit}")]
    TooLarge {
        /// The triangle count the samples give.
        triangles: u64,
        /// Where the count comes from, e.g. `6283186 slices of a 52-point cross-section`.
        why: String,
        /// The limit.
        limit: usize,
    },
}

impl SplineHeader {
    /// Rebuilds the mesh the header describes, from the spline(s) and settings alone; see
    /// [`RevolutionHeader::rebuild`] and [`SweepHeader::rebuild`], and the
    /// [module docs](self) for the tools' rules.
    ///
    /// # Errors
    ///
    /// A spline with too few control points, a revolution profile that crosses the axis, or
    /// a degenerate surface.
    ///
    /// # Example
    ///
    /// ```
    /// use splinekit::sweep::MeshLayout;
    /// use splinekit_io::mesh::{RebuildOptions, SplineHeader};
    ///
    /// let text = [
    ///     "# Cross-section: closed, epsilon >>+<< Swept-along: closed, epsilon >>+<< Scale of Cross-section",
    ///     "# true, 0.3 >>+<< true, 0.3 >>+<< 0.25",
    ///     "#",
    ///     "# Cross-section Spline control points: ",
    ///     "# 1.0 0.0",
    ///     "# -0.5 0.866",
    ///     "# -0.5 -0.866",
    ///     "# ",
    ///     "# Swept-along Spline control points:",
    ///     "# 1.0 0.0",
    ///     "# 0.0 1.0",
    ///     "# -1.0 0.0",
    ///     "# 0.0 -1.0",
    /// ]
    /// .join("\n");
    /// let header = SplineHeader::parse(&text, "ring.obj")?.unwrap();
    /// let welded = header.rebuild(&RebuildOptions::DEFAULT)?;
    /// assert!(welded.is_closed_oriented()); // a watertight ring
    /// let compat = header.rebuild(&RebuildOptions::DEFAULT.with_layout(MeshLayout::Compat))?;
    /// assert_eq!(compat.num_triangles(), welded.num_triangles());
    /// assert!(compat.num_vertices() > welded.num_vertices()); // seams duplicated
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn rebuild(&self, options: &RebuildOptions) -> Result<TriMesh, RebuildError> {
        match self {
            Self::Revolution(h) => h.rebuild(options),
            Self::Sweep(h) => h.rebuild(options),
        }
    }
}

impl RevolutionHeader {
    /// Rebuilds the surface of revolution: the cross-section (B-spline or Catmull-Rom,
    /// `closed`), tessellated by control-polygon angle with tolerance `epsilon`, scaled by
    /// `scale` and revolved about +z in `ceil(2π / slice_tolerance)` slices by [`revolve_z`]
    /// (seams and poles shared, outward faces and normals). `options.layout` does not matter
    /// here; see the [module docs](self).
    ///
    /// # Errors
    ///
    /// Too few control points (open: 4, closed: 3), a cross-section that crosses the axis,
    /// a bad scale or slice tolerance, or a profile with no area.
    ///
    /// # Example
    ///
    /// ```
    /// use glam::DVec2;
    /// use splinekit_io::mesh::{RebuildOptions, RevolutionHeader};
    ///
    /// // a closed B-spline off the axis: a torus-like ring, 16 slices
    /// let header = RevolutionHeader {
    ///     closed: true,
    ///     epsilon: 0.2,
    ///     is_bspline: true,
    ///     scale: 2.0,
    ///     slice_tolerance: std::f64::consts::TAU / 16.0,
    ///     control_points: vec![DVec2::new(1.0, 0.0), DVec2::new(2.0, -1.0), DVec2::new(3.0, 0.0), DVec2::new(2.0, 1.0)],
    /// };
    /// let mesh = header.rebuild(&RebuildOptions::DEFAULT)?;
    /// assert!(mesh.is_closed_oriented());
    /// assert_eq!(mesh.num_vertices() % 16, 0);
    /// # Ok::<(), splinekit_io::mesh::RebuildError>(())
    /// ```
    pub fn rebuild(&self, options: &RebuildOptions) -> Result<TriMesh, RebuildError> {
        let points = &self.control_points;
        let spline_err = |error| RebuildError::Spline { spline: "cross-section", error };
        let curve = if self.is_bspline {
            BSpline::new(points, self.closed).map_err(spline_err)?.to_piecewise()
        } else {
            CatmullRom::new(points, self.closed, CatmullRom::<DVec2>::UNIFORM).map_err(spline_err)?.to_piecewise()
        };
        let revolve = RevolveOptions::new(self.scale, self.slice_tolerance);
        revolve_spline_z(&curve, Tessellation::Angle { tolerance: self.epsilon }, &revolve, options)
    }
}

impl SweepHeader {
    /// Rebuilds the swept surface: both splines as uniform cubic B-splines, tessellated by
    /// the sweep tool's angle rule (split while a control-polygon angle exceeds `epsilon`),
    /// the cross-section scaled by `scale` and placed at every sample of the swept-along
    /// spline, which lies in the xz-plane. With [`MeshLayout::Compat`] the mesh is the tool's
    /// own (see the [module docs](self) for the rules and how closely the bundled files are
    /// reproduced); with [`MeshLayout::Welded`] seams are shared. Open ends are not capped.
    ///
    /// # Errors
    ///
    /// A spline with too few control points (open: 4, closed: 3), or a degenerate sweep.
    pub fn rebuild(&self, options: &RebuildOptions) -> Result<TriMesh, RebuildError> {
        self.build(options)
    }

    /// [`Self::rebuild`], or its counts.
    pub(crate) fn build<B: Built>(&self, options: &RebuildOptions) -> Result<B, RebuildError> {
        let compat = options.layout == MeshLayout::Compat;
        let cross = sweep_samples(&self.cross_section, "cross-section", compat)?;
        let along = sweep_samples(&self.swept_along, "swept-along", compat)?;
        let (p, s) = (cross.points.len(), along.points.len());
        // two triangles per quad
        options.check(2 * (p as u64).saturating_sub(1) * (s as u64).saturating_sub(1), || {
            format!("a {p}-point cross-section swept along {s} points")
        })?;
        // the tool walked the cross-section backwards; N = +y carries the cross-section's x
        // and B = T × N its y, so the profile normal is the tool's right normal, negated
        // (generalized_cylinder negates it back)
        let profile = Profile {
            points: cross.points.iter().rev().map(|&p| p * self.scale).collect(),
            normals: cross.normals.iter().rev().map(|&n| -n).collect(),
        };
        let frames = along
            .tangents
            .iter()
            .map(|t| {
                let t = DVec3::new(t.x, 0.0, t.y);
                Frame { t, n: DVec3::Y, b: t.cross(DVec3::Y) }
            })
            .collect();
        let path = SweepPath {
            positions: along.points.iter().map(|p| DVec3::new(p.x, 0.0, p.y)).collect(),
            frames,
            scales: Vec::new(),
        };
        let sweep = SweepOptions { layout: options.layout, uvs: options.uvs, caps: false, ..SweepOptions::default() };
        B::cylinder(&profile, &path, sweep).map_err(RebuildError::Sweep)
    }
}

/// The revolution tool's surface of a 2D spline: `curve` tessellated by `mode` (the start
/// of every piece, and the end point of an open curve), mirrored when drawn on the x < 0 side,
/// refused when it crosses the axis, then scaled and revolved about +z by [`revolve_z`] with
/// `revolve`'s scale and slice tolerance (UVs as `options.uvs` asks).
///
/// # Errors
/// A profile across the axis, more triangles than `options` allow, or a bad scale, slice
/// tolerance or profile (see [`revolve_z`]).
pub(crate) fn revolve_spline_z<B: Built>(
    curve: &PiecewiseCubic<DVec2>,
    mode: Tessellation,
    revolve: &RevolveOptions,
    options: &RebuildOptions,
) -> Result<B, RebuildError> {
    let closed = curve.is_closed();
    if let Tessellation::Distance { .. } = mode {
        // counted before the points are made (issue #38): a distance tolerance far finer than
        // the profile asks for millions of points per segment (the angle mode has at most
        // 1024 a segment); every point makes at least two triangles with the slices
        let bound = flatten_count(&AnyCurve::Piecewise(curve.clone()), mode);
        options.check(2u64.saturating_mul(bound.saturating_sub(1)), || {
            format!("its cross-section alone would have up to {bound} points")
        })?;
    }
    let mut samples = sample_by(curve, mode, closed, true);
    // which side of the axis: mirror a profile drawn at x < 0, refuse one across it
    let (lo, hi) =
        samples.points.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let tol = AXIS_TOLERANCE * (hi - lo).length();
    if lo.x < -tol && hi.x > tol {
        return Err(RebuildError::CrossesAxis { min_x: lo.x * revolve.scale, max_x: hi.x * revolve.scale });
    }
    if hi.x <= tol {
        let mirror = |p: &mut DVec2| p.x = -p.x;
        samples.points.iter_mut().for_each(mirror);
        samples.normals.iter_mut().for_each(mirror);
    }
    let uvs = if options.uvs { UvMode::SplitSeams } else { UvMode::Omit };
    let revolve = revolve.with_uvs(uvs);
    if let Ok(slices) = revolve.num_slices() {
        let p = samples.points.len();
        // two triangles per cross-section segment and slice
        options.check(2 * slices as u64 * (p as u64).saturating_sub(1), || {
            format!("{slices} slices of a {p}-point cross-section")
        })?;
    }
    B::revolve_z(&samples.points, Some(&samples.normals), &revolve).map_err(RebuildError::Revolve)
}

/// A tessellated 2D spline: positions, unit tangents and right normals `(t.y, −t.x)`.
struct Samples {
    points: Vec<DVec2>,
    tangents: Vec<DVec2>,
    normals: Vec<DVec2>,
}

/// Samples `curve` by the angle mode with `tolerance` (split while a control-polygon
/// angle exceeds `tolerance / 2`): the start of every piece, then, for a closed curve, the
/// first sample again (an exact seam copy), for an open one the end point if `with_end`.
fn sample(curve: &PiecewiseCubic<DVec2>, tolerance: f64, closed: bool, with_end: bool) -> Samples {
    sample_by(curve, Tessellation::Angle { tolerance }, closed, with_end)
}

/// Samples `curve` as [`sample`] does, tessellated by `mode`.
fn sample_by(curve: &PiecewiseCubic<DVec2>, mode: Tessellation, closed: bool, with_end: bool) -> Samples {
    let mut params = flatten_params(curve, mode);
    let end = params.pop();
    let mut s = Samples { points: Vec::new(), tangents: Vec::new(), normals: Vec::new() };
    let mut push = |u: f64| {
        let t = curve.unit_tangent(u);
        s.points.push(curve.eval(u));
        s.tangents.push(t);
        s.normals.push(DVec2::new(t.y, -t.x));
    };
    params.iter().for_each(|&u| push(u));
    match end {
        Some(u) if !closed && with_end => push(u),
        _ => {}
    }
    if closed && !s.points.is_empty() {
        s.points.push(s.points[0]);
        s.tangents.push(s.tangents[0]);
        s.normals.push(s.normals[0]);
    }
    s
}

/// One spline of a sweep header, compiled as a B-spline and sampled by the sweep tool's rule
/// (`epsilon` is the full angle, hence the tolerance `2·epsilon`); the open end point only
/// outside the compat layout.
fn sweep_samples(spline: &HeaderSpline, name: &'static str, compat: bool) -> Result<Samples, RebuildError> {
    let curve = BSpline::new(&spline.control_points, spline.closed)
        .map_err(|error| RebuildError::Spline { spline: name, error })?
        .to_piecewise();
    Ok(sample(&curve, 2.0 * spline.epsilon, spline.closed, !compat))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use super::*;

    /// Tolerance for values exact by construction, up to rounding.
    const EXACT: f64 = 1e-12;

    fn ring(closed: bool, points: &[[f64; 2]]) -> HeaderSpline {
        HeaderSpline { closed, epsilon: 0.3, control_points: points.iter().map(|&p| DVec2::from(p)).collect() }
    }

    fn triangle() -> [[f64; 2]; 3] {
        [[1.0, 0.0], [-0.5, 0.866], [-0.5, -0.866]]
    }

    #[test]
    fn samples_are_piece_starts_with_seam_or_end() {
        let pts: Vec<DVec2> = triangle().iter().map(|&p| DVec2::from(p)).collect();
        let curve = BSpline::new(&pts, true).unwrap().to_piecewise();
        let params = flatten_params(&curve, Tessellation::Angle { tolerance: 0.3 });
        let closed = sample(&curve, 0.3, true, true);
        assert_eq!(closed.points.len(), params.len());
        assert_eq!(closed.points[0], *closed.points.last().unwrap());
        let open = sample(&curve, 0.3, false, false);
        assert_eq!(open.points.len(), params.len() - 1);
        let with_end = sample(&curve, 0.3, false, true);
        assert!(with_end.points.last().unwrap().distance(curve.eval(3.0)) < EXACT);
        for (t, n) in closed.tangents.iter().zip(&closed.normals) {
            assert!((t.length() - 1.0).abs() < EXACT && t.dot(*n).abs() < EXACT && t.perp_dot(*n) < 0.0);
        }
    }

    #[test]
    fn sweep_placement_follows_the_tool() {
        // a straight swept-along spline along +x (2 segments, one piece each): T = +x, so the
        // cross-section's x goes to +y and its y to T × Y = +z
        let line = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 0.0]];
        let h = SweepHeader { cross_section: ring(true, &triangle()), swept_along: ring(false, &line), scale: 0.5 };
        let m = h.rebuild(&RebuildOptions::DEFAULT.with_layout(MeshLayout::Compat)).unwrap();
        let cross: Vec<DVec2> = triangle().iter().map(|&p| DVec2::from(p)).collect();
        let c = BSpline::new(&cross, true).unwrap().to_piecewise();
        let ring_len = sample(&c, 0.6, true, true).points.len();
        // compat: rings at the piece starts x = 1 and x = 2; the end (x = 3) is left out
        assert_eq!(m.num_vertices(), 2 * ring_len);
        let p0 = c.eval(0.0) * 0.5;
        assert!(m.positions[0].distance(DVec3::new(1.0, p0.x, p0.y)) < EXACT);
        assert!(m.positions[ring_len].distance(DVec3::new(2.0, p0.x, p0.y)) < EXACT);
        // walked backwards: after the seam sample (y = 0 at u = 0) comes the end of the loop
        let last = c.eval(3.0 - 1e-3) * 0.5;
        assert!(m.positions[1].z * last.y > 0.0);
        // welded: the seam is shared and the open end is reached
        let w = h.rebuild(&RebuildOptions::DEFAULT).unwrap();
        assert_eq!(w.num_vertices(), 3 * (ring_len - 1));
        assert!(w.positions.iter().any(|p| (p.x - 3.0).abs() < EXACT));
    }

    #[test]
    fn revolution_sides() {
        let mut h = RevolutionHeader {
            closed: false,
            epsilon: 0.1,
            is_bspline: false,
            scale: 1.0,
            slice_tolerance: TAU / 12.0,
            control_points: vec![
                DVec2::new(0.0, -2.0),
                DVec2::new(0.0, -1.0),
                DVec2::new(1.0, 0.0),
                DVec2::new(0.0, 1.0),
                DVec2::new(0.0, 2.0),
            ],
        };
        let right = h.rebuild(&RebuildOptions::DEFAULT).unwrap();
        assert!(right.is_closed_oriented());
        assert!(right.signed_volume() > 0.0);
        for p in &mut h.control_points {
            p.x = -p.x;
        }
        let left = h.rebuild(&RebuildOptions::DEFAULT).unwrap();
        assert_eq!(left.num_vertices(), right.num_vertices());
        assert!((left.signed_volume() - right.signed_volume()).abs() < 1e-12 * right.signed_volume());
        h.control_points[1].x = 0.5;
        assert!(matches!(h.rebuild(&RebuildOptions::DEFAULT), Err(RebuildError::CrossesAxis { .. })));
        h.control_points.truncate(3);
        let e = h.rebuild(&RebuildOptions::DEFAULT).unwrap_err();
        assert_eq!(e.to_string(), "cross-section spline: catmull-rom needs at least 4 control points, got 3");
        h.slice_tolerance = PI;
        h.control_points = vec![DVec2::ZERO; 4];
        assert!(matches!(h.rebuild(&RebuildOptions::DEFAULT), Err(RebuildError::Revolve(_))));
    }
}
