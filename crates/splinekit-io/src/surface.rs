//! Sweeping the surfaces of an SWP document into meshes ([`SwpDocument::surface_mesh`]).
//!
//! Each curve is tessellated ([`Tessellation`]), given frames (by default rotation-minimizing
//! along a path that leaves the plane `z = const`, the course software's sequential method
//! along one in it, where the two agree; with the closed-curve fix when the ends meet in
//! position and tangent; see [`SurfaceFrames::Auto`]), and handed to [`splinekit::sweep`].
//!
//! In the welded layout, sharp corners of a piecewise curve (a join whose two tangents differ
//! by more than [`CREASE_ANGLE`]) are sampled twice, once with each tangent: a corner of a
//! profile becomes a crease with sharp normals, a corner of a path a joint
//! ([`SweepOptions::join`], see [`splinekit::sweep::welded`]); the compat layout keeps the
//! course program's one sample per point.
//!
//! # Scale and twist curves
//!
//! A `gcyl` with a `scale` or `twist` clause reads those curves at every sweep sample. The
//! sample's position along the sweep is its *normalized arc length* `σ = s(u)/L ∈ [0, 1]`
//! (exact arc length of the sweep curve, to [`SHAPE_ACCURACY`] relative, so uniform and
//! adaptive tessellations agree; by parameter if the sweep has no length). The scale and
//! twist curves are read at the same fraction of their *parameter* range, `u = σ·segments`:
//! a curve's control points are then its keyframes, spread evenly along the sweep, and a
//! constant stretch (repeated points) keeps its share of the sweep — which reading by the
//! scale curve's own arc length would squeeze to nothing (a constant scale has no length).
//!
//! - Scale: the point `(sx, sy)` of the scale curve multiplies the profile's x by `sx` and its
//!   y by `sy` (in the sweep frame: along N and B). Factors are meant to be positive; 0
//!   pinches the tube to a line or point. End caps use the scale at their end.
//! - Twist: the x coordinate of the twist curve is an angle in degrees; the sweep frame is
//!   turned by it about T (N toward B) after the closed-curve fix.
//!
//! With either clause, vertex normals are the area-weighted normals of the faces around each
//! vertex (a scaled or twisted tube is no longer described by the profile's normals). On a
//! closed sweep the welded layout joins the last ring to the first, so the scale there should
//! be the same at both ends and the twist should differ by a multiple of 360°.

use glam::{DVec2, DVec3};
use splinekit::flatten::{self, Tessellation};
use splinekit::frame::{self, CurveSample, Frame, FrameMethod, FrameOptions, Side, StartNormal};
use splinekit::sweep::surface::{Lathe, LatheOptions, RevolveOptions, UvMode};
use splinekit::sweep::{self, MeshCounts, MeshLayout, Profile, SweepOptions, SweepPath, SweptMesh, adaptive};
use splinekit::{AnyCurve, CubicBezier, ParamCurve, PiecewiseCubic, TriMesh};

use crate::mesh::rebuild::{Built, revolve_spline_z};
use crate::mesh::{HeaderSpline, RebuildError, RebuildOptions, SweepHeader};
use crate::swp::{
    SwpClause, SwpCurveKind, SwpDocument, SwpFrames, SwpGeometry, SwpSurfaceKind, SwpSurfaceSettings, SwpTessellation,
};

/// Joins whose tangents turn by more than this (radians, 1°) are creases.
pub const CREASE_ANGLE: f64 = std::f64::consts::PI / 180.0;

/// Relative accuracy of the sweep's arc length at which scale and twist curves are read.
pub const SHAPE_ACCURACY: f64 = 1e-9;

/// How curves are tessellated for a sweep.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum SurfaceTessellation {
    /// The `steps` of each curve in the file (and of each `srev`): the course program's counts.
    #[default]
    FileSteps,
    /// Adaptive: every polyline within this distance of its curve, and revolutions cut into
    /// enough slices that no chord strays further from the circle it approximates. Surfaces
    /// of revolution (`srev`) and generalized cylinders without scale or twist curves
    /// (`gcyl`) are planned as a whole so that the mesh, triangle interiors included, stays
    /// within this distance of the exact surface ([`splinekit::sweep::adaptive`]).
    Distance(f64),
    /// Adaptive by control-polygon angle (radians); revolutions use slices of at most this angle.
    Angle(f64),
}

/// Which frames carry the profile along a sweep curve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SurfaceFrames {
    /// Rotation-minimizing frames (minimum twist) for a path that leaves the plane `z = const`;
    /// the course program's sequential frames for a path in such a plane, where the two methods
    /// give the same frames (N in the plane, left of travel; B = +z) and the sequential ones
    /// reproduce the course's vertices bit for bit. The compat layout always uses the
    /// sequential frames (the course program's vertices).
    #[default]
    Auto,
    /// The course program's sequential method (`Nᵢ = normalize(Bᵢ₋₁ × Tᵢ)`, `Bᵢ = Tᵢ × Nᵢ`,
    /// from `B = +z`), with the closed-curve fix.
    Sequential,
    /// Rotation-minimizing frames (double reflection), closed-curve correction by arc length.
    RotationMinimizing,
    /// Frenet frames: N toward the centre of curvature (carried across straight parts).
    Frenet,
    /// Z-up frames (Blender's "Z-Up"): the profile's y leans toward +z everywhere, no twist
    /// builds up ([`splinekit::frame::fixed_up`]).
    ZUp,
}

/// Which point of a `gcyl`'s profile rides on the path (the profile's other points keep
/// their offsets from it, in the frame's N and B).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ProfileAlign {
    /// The profile's origin `(0, 0)`, as the course program places it.
    #[default]
    Origin,
    /// The centre of the profile's tessellated points' bounding box.
    Centre,
    /// The profile's first point.
    Start,
}

impl ProfileAlign {
    /// The point of `points` that rides on the path (the origin for no points).
    #[must_use]
    pub fn anchor(self, points: &[DVec2]) -> DVec2 {
        match (self, points.first()) {
            (Self::Origin, _) | (_, None) => DVec2::ZERO,
            (Self::Start, Some(&first)) => first,
            (Self::Centre, Some(&first)) => {
                let (lo, hi) = points.iter().fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
                0.5 * (lo + hi)
            }
        }
    }
}

/// What a `gcyl`'s scale curve does to its profile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ScaleMode {
    /// The scale `(sx, sy)` multiplies the profile as drawn: `(1, 1)` leaves it as it is.
    #[default]
    Multiply,
    /// The scale `(sx, sy)` is the profile's size: the profile (measured from the point that
    /// rides on the path, see [`ProfileAlign`]) is first resized so that its largest `|x|` and
    /// its largest `|y|` are 1, then multiplied, so its farthest point from the path lies `sx`
    /// away along N and `sy` along B however large it was drawn. A profile with no extent
    /// along an axis (a segment on the other axis) keeps its zero there. Without a scale
    /// curve the profile is left as drawn.
    Override,
}

impl ScaleMode {
    /// The factors this mode applies to a profile before the scale curve's, given the
    /// profile's largest `|x|` and `|y|` from the point that rides on the path: `(1, 1)` for
    /// [`Self::Multiply`].
    #[must_use]
    pub fn unit_factors(self, reach: DVec2) -> DVec2 {
        match self {
            Self::Multiply => DVec2::ONE,
            Self::Override => {
                let unit = |r: f64| if r > 0.0 && r.is_finite() { 1.0 / r } else { 1.0 };
                DVec2::new(unit(reach.x.abs()), unit(reach.y.abs()))
            }
        }
    }
}

/// The default of [`SurfaceOptions::max_triangles`] and [`crate::mesh::RebuildOptions`]:
/// a mesh of this size takes a few gigabytes in memory and as OBJ text.
pub const DEFAULT_MAX_TRIANGLES: usize = 50_000_000;

/// Options for [`SwpDocument::surface_mesh`]; the default is what `splinekit sweep` does
/// without options, and what `render`, `gallery` and the editor sweep with: the course
/// program's file steps, the welded layout with end caps on open sweeps of closed profiles,
/// [`SurfaceFrames::Auto`] frames and at most [`DEFAULT_MAX_TRIANGLES`] triangles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceOptions {
    /// Vertex layout and UVs.
    pub sweep: SweepOptions,
    /// Tessellation of the curves.
    pub tessellation: SurfaceTessellation,
    /// Frames along sweep curves.
    pub frames: SurfaceFrames,
    /// Which point of a `gcyl`'s profile rides on the path.
    pub align: ProfileAlign,
    /// Whether a `gcyl`'s scale curve multiplies its profile or gives its size.
    pub scale_mode: ScaleMode,
    /// The most triangles a mesh may have (`None`: as many as 32-bit indices allow). Checked
    /// from the sample counts before the mesh is built (each curve's as soon as it is
    /// tessellated), so a tolerance far too fine for the size of a surface, or absurd steps in
    /// a file, fail at once with [`SurfaceError::TooLarge`] instead of exhausting memory.
    pub max_triangles: Option<usize>,
}

impl SurfaceOptions {
    /// These options with a surface's own settings in place of theirs (each setting the
    /// surface gives replaces the option; the angle tolerance goes from degrees to radians).
    #[must_use]
    pub fn with_settings(&self, settings: &SwpSurfaceSettings) -> Self {
        let mut o = *self;
        match settings.tessellation {
            Some(SwpTessellation::Distance(d)) => o.tessellation = SurfaceTessellation::Distance(d),
            Some(SwpTessellation::AngleDegrees(a)) => o.tessellation = SurfaceTessellation::Angle(a.to_radians()),
            None => {}
        }
        if let Some(layout) = settings.layout {
            o.sweep.layout = layout;
            // the course's layout has no caps unless the surface asks for them
            if layout == MeshLayout::Compat && settings.caps.is_none() {
                o.sweep.caps = false;
            }
        }
        match settings.frames {
            Some(SwpFrames::Auto) => o.frames = SurfaceFrames::Auto,
            Some(SwpFrames::Sequential) => o.frames = SurfaceFrames::Sequential,
            Some(SwpFrames::RotationMinimizing) => o.frames = SurfaceFrames::RotationMinimizing,
            Some(SwpFrames::Frenet) => o.frames = SurfaceFrames::Frenet,
            Some(SwpFrames::ZUp) => o.frames = SurfaceFrames::ZUp,
            None => {}
        }
        if let Some(caps) = settings.caps {
            o.sweep.caps = caps;
        }
        if let Some(align) = settings.align {
            o.align = align;
        }
        if let Some(join) = settings.join {
            o.sweep.join = join;
        }
        if let Some(limit) = settings.mitre_limit {
            o.sweep.mitre_limit = limit;
        }
        if let Some(mode) = settings.scale_mode {
            o.scale_mode = mode;
        }
        o
    }
}

impl Default for SurfaceOptions {
    fn default() -> Self {
        Self {
            sweep: SweepOptions::default(),
            tessellation: SurfaceTessellation::default(),
            frames: SurfaceFrames::default(),
            align: ProfileAlign::default(),
            scale_mode: ScaleMode::default(),
            max_triangles: Some(DEFAULT_MAX_TRIANGLES),
        }
    }
}

/// Why a surface could not be swept.
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    /// No surface with that index.
    #[error("no surface {0}")]
    NoSuchSurface(usize),
    /// A curve the surface uses does not compile.
    #[error("curve {curve}: {error}")]
    Curve {
        /// Display name of the curve.
        curve: String,
        /// What is wrong with it.
        error: splinekit::SplineError,
    },
    /// The profile of a surface is a 3D curve.
    #[error("profile {curve} of surface {surface} is 3D; a profile must be a 2D curve")]
    ProfileNot2d {
        /// Display name of the curve.
        curve: String,
        /// Display name of the surface.
        surface: String,
    },
    /// The scale or twist curve of a surface is a 3D curve.
    #[error("{role} curve {curve} of surface {surface} is 3D; a {role} curve must be a 2D curve")]
    ShapeNot2d {
        /// The clause that names the curve.
        role: SwpClause,
        /// Display name of the curve.
        curve: String,
        /// Display name of the surface.
        surface: String,
    },
    /// The mesh would have more triangles than [`SurfaceOptions::max_triangles`].
    #[error("surface {surface} would have about {triangles} triangles ({why}), more than the limit of {limit}")]
    TooLarge {
        /// Display name of the surface.
        surface: String,
        /// The triangle count the samples give (at least this many when `why` names one curve).
        triangles: u64,
        /// Where the count comes from, e.g. `65536 slices of a 16385-point profile`.
        why: String,
        /// The limit.
        limit: usize,
    },
    /// The sweep itself failed.
    #[error("surface {surface}: {error}")]
    Sweep {
        /// Display name of the surface.
        surface: String,
        /// What went wrong.
        error: sweep::SweepError,
    },
    /// A `zrev` or an `xsweep` could not be built (a profile across the axis, a negative
    /// radius…).
    #[error("surface {surface}: {error}")]
    Rebuild {
        /// Display name of the surface.
        surface: String,
        /// What went wrong.
        error: RebuildError,
    },
    /// A `lathe` could not be built (its keys do not make a spline, a radius is negative…).
    #[error("surface {surface}: {error}")]
    Lathe {
        /// Display name of the surface.
        surface: String,
        /// What went wrong.
        error: sweep::surface::SurfaceError,
    },
    /// The profile of a `zrev` or a key curve of a `lathe` is a circle, helix or knot, a
    /// Bézier curve of any degree or a NURBS, not a chain of cubics.
    #[error("surface {surface}: curve {curve} must be a cubic spline (bez2, bsp2, cr2, her2, tcb2 or bo2)")]
    NotSpline {
        /// Display name of the surface.
        surface: String,
        /// Display name of the curve.
        curve: String,
    },
    /// A curve of an `xsweep` is not a 2D B-spline, the only kind the sweep tool has.
    #[error("surface {surface}: curve {curve} must be a 2D B-spline (bsp2): the sweep tool's curves are")]
    NotToolCurve {
        /// Display name of the surface.
        surface: String,
        /// Display name of the curve.
        curve: String,
    },
}

impl SwpDocument {
    /// The mesh of surface `index`.
    ///
    /// Scale and twist curves of a `gcyl` are applied as the [module docs](self) describe.
    ///
    /// # Errors
    /// An unknown index, a curve that does not compile, a 3D profile, scale or twist curve, or
    /// a degenerate sweep.
    pub fn surface_mesh(&self, index: usize, options: &SurfaceOptions) -> Result<TriMesh, SurfaceError> {
        self.surface(index, options)
    }

    /// Surface `index` as a file holds it: [`Self::surface_mesh`]'s surface with every point
    /// one vertex in the welded layout (creases, seams, joints and caps shared, normals and
    /// UVs face-varying: see [`sweep::generalized_cylinder_poly`]), and the path corners whose
    /// joints may fold because the profile does not fit inside the turn.
    ///
    /// # Errors
    /// As [`Self::surface_mesh`].
    pub fn surface_poly(&self, index: usize, options: &SurfaceOptions) -> Result<SweptMesh, SurfaceError> {
        self.surface(index, options)
    }

    /// The vertex and triangle counts of [`Self::surface_poly`]`(index, options)`, found from
    /// the curves' samples and the slices without building the mesh: the time and memory
    /// this takes grow with the samples, not with the mesh (a revolution in a million slices
    /// is counted as fast as in ten).
    ///
    /// # Errors
    /// As [`Self::surface_mesh`], [`SurfaceError::TooLarge`] included.
    pub fn surface_counts(&self, index: usize, options: &SurfaceOptions) -> Result<MeshCounts, SurfaceError> {
        self.surface(index, options)
    }

    /// Whether a distance tolerance bounds surface `index`'s mesh as a whole (triangle
    /// interiors included) rather than each curve's tessellation alone: false only for a
    /// `gcyl` whose path is not a chain of cubics, a circle or a helix, or with a scale or
    /// twist curve that the shaped plan does not cover (one that is not a chain of cubics,
    /// Frenet frames, or frames other than rotation-minimizing along a path off the plane;
    /// see [`adaptive::shape_covered`]), and for an unknown index or curves that do not
    /// compile.
    #[must_use]
    pub fn tolerance_bounds_surface(&self, index: usize, options: &SurfaceOptions) -> bool {
        let Some(surface) = self.surfaces.get(index) else { return false };
        let SwpSurfaceKind::GeneralizedCylinder { sweep: path, scale, twist, .. } = surface.kind else { return true };
        let compile = |i: usize| self.curves.get(i).and_then(|c| c.to_curve().ok());
        let Some(c) = compile(path) else { return false };
        if scale.is_none() && twist.is_none() && matches!(c, AnyCurve::Piecewise(_) | AnyCurve::Circle(_)) {
            // the plain plan's paths (it hands a helix to the shaped plan)
            return true;
        }
        // a scale or twist curve named but not compiling covers nothing
        let (sc, tw) = (scale.map(compile), twist.map(compile));
        if matches!(sc, Some(None)) || matches!(tw, Some(None)) {
            return false;
        }
        let options = options.with_settings(&surface.settings);
        let frames = cylinder_frames(&options, path_frames(&options, &c));
        let shape = adaptive::CylinderShape {
            scale: sc.as_ref().and_then(Option::as_ref),
            twist: tw.as_ref().and_then(Option::as_ref),
            unit: DVec2::ONE,
        };
        adaptive::shape_covered(&c, &frames, &shape)
    }

    /// [`Self::surface_mesh`], or its counts.
    fn surface<B: Built>(&self, index: usize, options: &SurfaceOptions) -> Result<B, SurfaceError> {
        let surface = self.surfaces.get(index).ok_or(SurfaceError::NoSuchSurface(index))?;
        let options = &options.with_settings(&surface.settings);
        let surface_name = surface.display_name(index);
        let curve = |i: usize| {
            self.curves[i]
                .to_curve()
                .map_err(|error| SurfaceError::Curve { curve: self.curves[i].display_name(i), error })
        };
        let limit = Limit { surface: &surface_name, max: options.max_triangles };
        // a profile, sampled as `options` say or (adaptive revolutions) at the parameters a
        // plan gives
        let profile_at = |i: usize, params: Option<&[f64]>| -> Result<Profile, SurfaceError> {
            if self.curves[i].dim == 3 {
                return Err(SurfaceError::ProfileNot2d {
                    curve: self.curves[i].display_name(i),
                    surface: surface_name.clone(),
                });
            }
            let c = curve(i)?;
            let samples = match params {
                Some(params) => samples_at(&c, params, options, &limit)?,
                None => sample_curve(&c, self.curves[i].steps, options, &limit)?,
            };
            let frames = frames_for(&samples, SurfaceFrames::Sequential);
            Ok(Profile {
                points: samples.iter().map(|s| s.position.truncate()).collect(),
                normals: frames.iter().map(|f| f.n.truncate().try_normalize().unwrap_or(DVec2::Y)).collect(),
            })
        };
        let profile_of = |i: usize| profile_at(i, None);
        let sweep_err = |error| SurfaceError::Sweep { surface: surface_name.clone(), error };
        match surface.kind {
            SwpSurfaceKind::Revolution { steps, profile } => {
                let (prof, steps) = match options.tessellation {
                    SurfaceTessellation::Distance(tolerance) if self.curves[profile].dim != 3 => {
                        let c = curve(profile)?;
                        limit.check_planned_profile(&c, tolerance)?;
                        let plan = adaptive::revolution_plan(&c, tolerance, MAX_SLICES);
                        let mut prof = profile_at(profile, Some(&plan.params))?;
                        prof.points.iter_mut().for_each(|p| p.x *= plan.ring_scale);
                        (prof, plan.slices)
                    }
                    mode => {
                        let prof = profile_of(profile)?;
                        let steps = revolution_steps(&prof, steps, mode);
                        (prof, steps)
                    }
                };
                let p = prof.points.len();
                // two triangles per profile segment and slice
                limit.check(2 * steps as u64 * (p as u64).saturating_sub(1), || {
                    format!("{steps} slices of a {p}-point profile")
                })?;
                B::revolve(&prof, steps, options.sweep).map_err(sweep_err)
            }
            SwpSurfaceKind::GeneralizedCylinder { profile, sweep: path, scale, twist } => {
                let mut prof = profile_of(profile)?;
                // the anchor of the profile as each mode tessellates it alone (an adaptive
                // plan keeps it: with `align centre` the centre of the points flattened to T);
                // so are an overriding scale's unit factors
                let anchor = options.align.anchor(&prof.points);
                let c = curve(path)?;
                let frame_kind = path_frames(options, &c);
                // a scale or twist curve: 2D, read at the samples' normalized arc length
                let shape = |i: Option<usize>, role: SwpClause| -> Result<Option<AnyCurve<DVec3>>, SurfaceError> {
                    let Some(i) = i else { return Ok(None) };
                    if self.curves[i].dim == 3 {
                        return Err(SurfaceError::ShapeNot2d {
                            role,
                            curve: self.curves[i].display_name(i),
                            surface: surface_name.clone(),
                        });
                    }
                    curve(i).map(Some)
                };
                let (scale, twist) = (shape(scale, SwpClause::Scale)?, shape(twist, SwpClause::Twist)?);
                let unit = if scale.is_some() {
                    // the size of the profile curve itself (its tight bounding box), whatever
                    // its tessellation
                    let b = curve(profile)?.bounding_box();
                    let (lo, hi) = (b.min.truncate() - anchor, b.max.truncate() - anchor);
                    options.scale_mode.unit_factors(lo.abs().max(hi.abs()))
                } else {
                    DVec2::ONE
                };
                let cylinder_frames = cylinder_frames(options, frame_kind);
                let shaped = adaptive::CylinderShape { scale: scale.as_ref(), twist: twist.as_ref(), unit };
                let mut ring_scale = 1.0;
                let mut samples = match options.tessellation {
                    // adaptive: planned together so that the surface, not each curve, is
                    // within the tolerance
                    SurfaceTessellation::Distance(tolerance) if scale.is_none() && twist.is_none() => {
                        let pc = curve(profile)?;
                        limit.check_planned_profile(&pc, tolerance)?;
                        let max_path = max_path_points(&pc, tolerance, options);
                        let plan = adaptive::cylinder_plan(&pc, anchor, &c, &cylinder_frames, tolerance, max_path);
                        prof = profile_at(profile, Some(&plan.profile_params))?;
                        ring_scale = plan.ring_scale;
                        samples_at(&c, &plan.path_params, options, &limit)?
                    }
                    // with a scale or twist curve, when the bound covers the curves (else
                    // each curve is flattened to the tolerance)
                    SurfaceTessellation::Distance(tolerance)
                        if adaptive::shape_covered(&c, &cylinder_frames, &shaped) =>
                    {
                        let pc = curve(profile)?;
                        let largest = shaped.largest_factor().filter(|f| *f > 0.0).unwrap_or(1.0);
                        limit.check_planned_profile(&pc, tolerance / largest)?;
                        let max_path = max_path_points(&pc, tolerance / largest, options);
                        let plan = adaptive::shaped_cylinder_plan(
                            &pc,
                            anchor,
                            &c,
                            &cylinder_frames,
                            &shaped,
                            tolerance,
                            max_path,
                        );
                        match plan {
                            Some(plan) => {
                                if !plan.bound.is_finite() {
                                    // the plan needs more path points than the limit leaves
                                    let chords = plan.profile_params.len().saturating_sub(1).max(1) as u64;
                                    limit.check(2 * chords * max_path as u64, || {
                                        format!("the tolerance needs more than {max_path} points along its path")
                                    })?;
                                }
                                prof = profile_at(profile, Some(&plan.profile_params))?;
                                samples_at(&c, &plan.path_params, options, &limit)?
                            }
                            None => sample_curve(&c, self.curves[path].steps, options, &limit)?,
                        }
                    }
                    _ => sample_curve(&c, self.curves[path].steps, options, &limit)?,
                };
                prof.points.iter_mut().for_each(|p| *p -= anchor);
                if ring_scale != 1.0 {
                    // a circle's inflated rings: its radius and the profile's x scaled alike
                    samples.iter_mut().for_each(|s| s.position *= ring_scale);
                    prof.points.iter_mut().for_each(|p| p.x *= ring_scale);
                }
                let (p, s) = (prof.points.len(), samples.len());
                // two triangles per quad, and the caps
                let caps = if options.sweep.caps { 2 * (p as u64).saturating_sub(1) } else { 0 };
                limit.check(2 * (p as u64).saturating_sub(1) * (s as u64).saturating_sub(1) + caps, || {
                    format!("a {p}-point profile swept along {s} points")
                })?;
                let mut frames = frames_for(&samples, frame_kind);
                if scale.is_some() {
                    // the profile at unit size for an overriding scale (normals as the
                    // inverse transpose carries them)
                    prof.points.iter_mut().for_each(|p| *p *= unit);
                    prof.normals.iter_mut().for_each(|n| *n = (*n / unit).try_normalize().unwrap_or(*n));
                }
                let mut scales = Vec::new();
                if scale.is_some() || twist.is_some() {
                    let sigma = normalized_arclen(&c, &samples);
                    let at = |shape: &AnyCurve<DVec3>, s: f64| shape.eval(s * shape.domain().1);
                    scales = match &scale {
                        Some(sc) => sigma.iter().map(|&s| at(sc, s).truncate()).collect(),
                        // face normals, as with a scale (see the module docs)
                        None => vec![DVec2::ONE; samples.len()],
                    };
                    if let Some(tw) = &twist {
                        for (f, &s) in frames.iter_mut().zip(&sigma) {
                            *f = f.rotated(at(tw, s).x.to_radians());
                        }
                    }
                }
                let path = SweepPath { positions: samples.iter().map(|s| s.position).collect(), frames, scales };
                // round joints in arcs as fine as the tessellation, at the profile's largest size
                let largest = if path.scales.is_empty() {
                    1.0
                } else {
                    path.scales.iter().fold(0.0, |m: f64, s| m.max(s.abs().max_element()))
                };
                let reach = prof.points.iter().fold(0.0, |r: f64, p| r.max(p.length())) * largest;
                let round_step = match options.tessellation {
                    SurfaceTessellation::FileSteps => options.sweep.round_step,
                    SurfaceTessellation::Angle(a) => a,
                    SurfaceTessellation::Distance(d) => slice_angle(reach, d),
                };
                B::cylinder(&prof, &path, SweepOptions { round_step, ..options.sweep }).map_err(sweep_err)
            }
            SwpSurfaceKind::RevolutionZ { profile, epsilon, slice_tolerance, scale } => {
                let spline = spline_2d(&curve(profile)?, &self.curves[profile].display_name(profile), &surface_name)?;
                let (mode, slice_tolerance) = match options.tessellation {
                    SurfaceTessellation::FileSteps => (Tessellation::Angle { tolerance: epsilon }, slice_tolerance),
                    SurfaceTessellation::Angle(a) => (Tessellation::Angle { tolerance: a }, a),
                    SurfaceTessellation::Distance(d) => {
                        let radius = spline
                            .segments()
                            .iter()
                            .flat_map(|b| [b.p0, b.p1, b.p2, b.p3])
                            .fold(0.0, |r: f64, p| r.max(p.x.abs()))
                            * scale;
                        (Tessellation::Distance { tolerance: d / scale }, slice_angle(radius, d))
                    }
                };
                let revolve = RevolveOptions::new(scale, slice_tolerance);
                let rebuild =
                    RebuildOptions::DEFAULT.with_uvs(options.sweep.uvs).with_max_triangles(options.max_triangles);
                revolve_spline_z(&spline, mode, &revolve, &rebuild).map_err(|e| match e {
                    RebuildError::TooLarge { triangles, why, limit } => {
                        SurfaceError::TooLarge { surface: surface_name.clone(), triangles, why, limit }
                    }
                    error => SurfaceError::Rebuild { surface: surface_name.clone(), error },
                })
            }
            SwpSurfaceKind::ToolSweep { profile, path, epsilon, path_epsilon, scale } => {
                let spline = |i: usize, epsilon: f64| -> Result<HeaderSpline, SurfaceError> {
                    let c = &self.curves[i];
                    match (&c.kind, &c.geometry) {
                        (SwpCurveKind::BSpline, SwpGeometry::Points(points)) if c.dim == 2 => Ok(HeaderSpline {
                            closed: c.closed,
                            epsilon,
                            control_points: points.iter().map(|p| p.truncate()).collect(),
                        }),
                        _ => {
                            Err(SurfaceError::NotToolCurve { surface: surface_name.clone(), curve: c.display_name(i) })
                        }
                    }
                };
                let header = SweepHeader {
                    cross_section: spline(profile, epsilon)?,
                    swept_along: spline(path, path_epsilon)?,
                    scale,
                };
                let rebuild = RebuildOptions::DEFAULT
                    .with_layout(options.sweep.layout)
                    .with_uvs(options.sweep.uvs)
                    .with_max_triangles(options.max_triangles);
                header.build(&rebuild).map_err(|e| match e {
                    RebuildError::TooLarge { triangles, why, limit } => {
                        SurfaceError::TooLarge { surface: surface_name.clone(), triangles, why, limit }
                    }
                    error => SurfaceError::Rebuild { surface: surface_name.clone(), error },
                })
            }
            SwpSurfaceKind::Lathe { stacks, slices, radius, height } => {
                let keys = |i: usize| -> Result<Vec<f64>, SurfaceError> {
                    let spline = spline_2d(&curve(i)?, &self.curves[i].display_name(i), &surface_name)?;
                    let segments = spline.segments();
                    let mut keys: Vec<f64> = segments.iter().flat_map(|b| [b.p0.y, b.p1.y, b.p2.y]).collect();
                    keys.extend(segments.last().map(|b| b.p3.y));
                    Ok(keys)
                };
                let (r, z) = (keys(radius)?, keys(height)?);
                let max_r = r.iter().fold(0.0, |m: f64, &k| m.max(k));
                let slices = match options.tessellation {
                    SurfaceTessellation::FileSteps => slices as usize,
                    SurfaceTessellation::Angle(a) => slice_count(a),
                    SurfaceTessellation::Distance(d) => slice_count(slice_angle(max_r, d)),
                };
                limit.check(2 * slices as u64 * u64::from(stacks), || format!("{slices} slices of {stacks} stacks"))?;
                let failed = |error| SurfaceError::Lathe { surface: surface_name.clone(), error };
                let lathe = Lathe::new(&r, &z).map_err(failed)?;
                let uvs = if options.sweep.uvs { UvMode::SplitSeams } else { UvMode::Omit };
                B::lathe(&lathe, &LatheOptions::new(slices, stacks as usize).with_uvs(uvs)).map_err(failed)
            }
        }
    }
}

/// A 2D spline's compiled form in the plane, for `zrev` and `lathe` (circles are refused).
fn spline_2d(curve: &AnyCurve<DVec3>, name: &str, surface: &str) -> Result<PiecewiseCubic<DVec2>, SurfaceError> {
    let AnyCurve::Piecewise(c) = curve else {
        return Err(SurfaceError::NotSpline { surface: surface.to_owned(), curve: name.to_owned() });
    };
    let flat =
        |b: &CubicBezier<DVec3>| CubicBezier::new(b.p0.truncate(), b.p1.truncate(), b.p2.truncate(), b.p3.truncate());
    PiecewiseCubic::new(c.segments().iter().map(flat).collect(), c.is_closed())
        .map_err(|error| SurfaceError::Curve { curve: name.to_owned(), error })
}

/// The most slices of an adaptive revolution.
const MAX_SLICES: usize = crate::swp::MAX_STEPS as usize;

/// The largest slice angle whose chords stay within `tolerance` of a circle of `radius`
/// (a chord of angle θ strays r·(1 − cos(θ/2))); a full turn when any chord would do.
fn slice_angle(radius: f64, tolerance: f64) -> f64 {
    if radius > tolerance && tolerance > 0.0 {
        2.0 * (1.0 - tolerance / radius).clamp(-1.0, 1.0).acos()
    } else {
        std::f64::consts::TAU
    }
}

/// Slices of at most `angle` radians, at least 3 (and at most [`MAX_STEPS`](crate::swp::MAX_STEPS)).
fn slice_count(angle: f64) -> usize {
    let n = (std::f64::consts::TAU / angle).ceil();
    if n.is_finite() { (n as usize).clamp(3, crate::swp::MAX_STEPS as usize) } else { 3 }
}

/// Slices around the axis: the file's steps, or enough for the tolerance at the largest radius.
fn revolution_steps(profile: &Profile, file_steps: u32, mode: SurfaceTessellation) -> usize {
    let radius = profile.points.iter().map(|p| p.x.abs()).fold(0.0, f64::max);
    match mode {
        SurfaceTessellation::FileSteps => file_steps.max(1) as usize,
        SurfaceTessellation::Distance(tol) => slice_count(slice_angle(radius, tol)),
        SurfaceTessellation::Angle(a) => slice_count(a),
    }
}

/// The most path points an adaptive gcyl plan may place: every path point makes two
/// triangles per profile chord, and no plan flattens the profile coarser than `tolerance`
/// (the profile's share over the shape's largest factor), so past this many the mesh would
/// be too large whatever the plan.
fn max_path_points(profile: &AnyCurve<DVec3>, tolerance: f64, options: &SurfaceOptions) -> usize {
    let coarsest = flatten::flatten_count(profile, Tessellation::Distance { tolerance });
    let chords = usize::try_from(coarsest.saturating_sub(1)).unwrap_or(usize::MAX).max(1);
    options.max_triangles.map_or(adaptive::MAX_PATH_POINTS, |m| m / chords.saturating_mul(2) + 2)
}

/// The triangle limit of one surface's mesh.
struct Limit<'a> {
    /// Display name of the surface.
    surface: &'a str,
    max: Option<usize>,
}

impl Limit<'_> {
    /// Fails when an adaptive plan's profile could alone pass the limit: a plan flattens it to
    /// no less than [`adaptive::MIN_SHARE`] of `tolerance`, so this bounds it before it starts.
    fn check_planned_profile(&self, profile: &AnyCurve<DVec3>, tolerance: f64) -> Result<(), SurfaceError> {
        let finest = Tessellation::Distance { tolerance: tolerance * adaptive::MIN_SHARE };
        let bound = flatten::flatten_count(profile, finest);
        self.check(2u64.saturating_mul(bound.saturating_sub(1)), || {
            format!("its profile alone could have up to {bound} points")
        })
    }

    /// Fails when `triangles` exceed the limit; `why` says where they come from.
    fn check(&self, triangles: u64, why: impl FnOnce() -> String) -> Result<(), SurfaceError> {
        match self.max {
            Some(limit) if triangles > limit as u64 => {
                Err(SurfaceError::TooLarge { surface: self.surface.to_string(), triangles, why: why(), limit })
            }
            _ => Ok(()),
        }
    }
}

/// Tessellates a curve and samples positions and unit tangents; in the welded layout, sharp
/// joins are sampled twice (incoming and outgoing tangent). Before sampling, `limit` checks
/// the two triangles a point makes at least (one strip of quads).
fn sample_curve(
    curve: &AnyCurve<DVec3>,
    steps: u32,
    options: &SurfaceOptions,
    limit: &Limit<'_>,
) -> Result<Vec<CurveSample>, SurfaceError> {
    let mode = match options.tessellation {
        SurfaceTessellation::FileSteps => Tessellation::Uniform { steps: steps.max(1) as usize },
        SurfaceTessellation::Distance(tolerance) => Tessellation::Distance { tolerance },
        SurfaceTessellation::Angle(tolerance) => Tessellation::Angle { tolerance },
    };
    // counted before the points are made (a helix of many turns and a fine tolerance could
    // ask for billions)
    let bound = flatten::flatten_count(curve, mode);
    limit.check(2u64.saturating_mul(bound.saturating_sub(1)), || {
        format!("one of its curves alone would have up to {bound} points")
    })?;
    let params = flatten::flatten_any(curve, mode);
    samples_at(curve, &params, options, limit)
}

/// Samples `curve` at `params` as [`sample_curve`] does, after checking the two triangles a
/// point makes at least.
fn samples_at(
    curve: &AnyCurve<DVec3>,
    params: &[f64],
    options: &SurfaceOptions,
    limit: &Limit<'_>,
) -> Result<Vec<CurveSample>, SurfaceError> {
    let n = params.len();
    limit.check(2 * (n as u64).saturating_sub(1), || {
        format!("at least that many: one of its curves alone has {n} points")
    })?;
    Ok(match curve {
        AnyCurve::Piecewise(pc) if options.sweep.layout == MeshLayout::Welded => {
            frame::sample_with_corners(pc, params, CREASE_ANGLE)
        }
        _ => frame::sample(curve, params),
    })
}

/// The normalized arc length `s(u)/L ∈ [0, 1]` of the sweep curve at each sample (the
/// length of each step between consecutive samples to [`SHAPE_ACCURACY`] of the chord
/// polygon's length); `u` over the domain if the curve has no length.
fn normalized_arclen(curve: &AnyCurve<DVec3>, samples: &[CurveSample]) -> Vec<f64> {
    let chord: f64 = samples.windows(2).map(|w| w[0].position.distance(w[1].position)).sum();
    let share = SHAPE_ACCURACY * chord / samples.len().max(1) as f64;
    let mut acc = 0.0;
    let mut s: Vec<f64> = Vec::with_capacity(samples.len());
    for (i, sample) in samples.iter().enumerate() {
        if i > 0 {
            acc += curve.arclen_range(samples[i - 1].u, sample.u, share).length;
        }
        s.push(acc);
    }
    if acc > 0.0 && acc.is_finite() {
        s.iter_mut().for_each(|v| *v = (*v / acc).clamp(0.0, 1.0));
    } else {
        let (a, b) = curve.domain();
        for (v, sample) in s.iter_mut().zip(samples) {
            *v = if b > a { ((sample.u - a) / (b - a)).clamp(0.0, 1.0) } else { 0.0 };
        }
    }
    s
}

/// The frames [`SurfaceFrames::Auto`] stands for along `path` (any other choice as it is).
fn path_frames(options: &SurfaceOptions, path: &AnyCurve<DVec3>) -> SurfaceFrames {
    if options.frames != SurfaceFrames::Auto {
        return options.frames;
    }
    if options.sweep.layout == MeshLayout::Compat || in_z_plane(path) {
        SurfaceFrames::Sequential
    } else {
        SurfaceFrames::RotationMinimizing
    }
}

/// Whether the curve lies in one plane `z = const` (its bounding box's depth within 1e-12 of
/// its largest side).
fn in_z_plane(curve: &AnyCurve<DVec3>) -> bool {
    let b = curve.bounding_box();
    let extent = (b.max - b.min).max_element();
    !(b.max.z - b.min.z > 1e-12 * extent)
}

fn frames_for(samples: &[CurveSample], method: SurfaceFrames) -> Vec<Frame> {
    frame::frames_for_samples(samples, &frame_options(method))
}

/// The frames an adaptive gcyl plan expects the mesh to get: `method`'s, on samples with
/// corners sampled twice in the welded layout.
fn cylinder_frames(options: &SurfaceOptions, method: SurfaceFrames) -> adaptive::CylinderFrames {
    adaptive::CylinderFrames {
        options: frame_options(method),
        corner_angle: (options.sweep.layout == MeshLayout::Welded).then_some(CREASE_ANGLE),
    }
}

/// The frame options of `method`.
fn frame_options(method: SurfaceFrames) -> FrameOptions {
    let method = match method {
        SurfaceFrames::Auto | SurfaceFrames::Sequential => FrameMethod::Sequential(Side::Left),
        SurfaceFrames::RotationMinimizing => FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left)),
        SurfaceFrames::Frenet => FrameMethod::Frenet,
        SurfaceFrames::ZUp => FrameMethod::FixedUp(DVec3::Z),
    };
    FrameOptions::DEFAULT.with_method(method)
}
