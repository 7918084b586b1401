//! Triangle meshes of parametric surfaces: a general `(u, v)` grid mesher
//! ([`mesh_surface`]), the revolution about +z of the interactive revolution tool (the
//! "second convention", [`revolve_z`]) and a lathe with independent radius and height
//! curves ([`Lathe`]).
//!
//! # Conventions
//! All three builders share one grid: `u` runs along a row (around the axis for the
//! revolutions), `v` from row to row (along the profile).
//!
//! - **Orientation.** Triangles are counter-clockwise seen from the front. For
//!   [`mesh_surface`] the front is the side `∂f/∂u × ∂f/∂v` points to (the other side with
//!   [`SurfaceOptions::flip`]); the revolutions pick the side that faces outward (see
//!   [`revolve_z`]). Grid quad `(i, j)` is split along its diagonal `(i, j)–(i+1, j+1)`.
//! - **Vertex order.** Row by row (`v` outer, `u` inner); a pole row is one vertex.
//! - **Seams.** A wrapped direction shares its seam vertices (no duplicate column or row), so
//!   a closed surface comes out as a closed, consistently oriented 2-manifold
//!   ([`TriMesh::is_closed_oriented`]).
//! - **Poles.** A row whose samples all coincide (within `pole_tolerance` times the diagonal
//!   of the bounding box of all samples) becomes one vertex at their mean, and the quads
//!   next to it become a triangle fan: no zero-area triangles, no duplicate vertices. These
//!   are normally the rows `v = 0` and `v = 1` (the tips of a sphere); an inner row that
//!   collapses becomes a pinch point. Columns are never collapsed: put the degenerate
//!   direction in `v`.
//! - **Normals.** Unit length and never NaN. Where the builder knows an analytic normal
//!   (partials given by the caller, profile normals, the lathe's derivatives) it is used;
//!   elsewhere, and always at poles, a vertex gets the area-weighted mean of its faces'
//!   normals. An analytic normal more than 90° away from that mean (it disagrees with the
//!   triangles) is replaced by the mean. A vertex with neither gets the direction from the
//!   centroid of the mesh, or +z.
//! - **UVs.** See [`UvMode`]: by default `(u, v)` when no direction wraps and none when one
//!   does (so the seam stays shared); [`UvMode::SplitSeams`] duplicates the seam instead,
//!   as the sweeps of [`crate::sweep`] do when they are asked for UVs. A pole vertex has
//!   `u = 0.5`.
//! - **Degenerate input** never panics: every builder validates its input and returns a
//!   [`SurfaceError`].

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use crate::curve::{BezierSpline, ParamCurve, PiecewiseCubic, SplineError};
use crate::mesh::TriMesh;
use crate::sweep::MeshCounts;

/// Default relative tolerance for collapsing a row into a pole (and, for the
/// revolutions, for snapping a profile point onto the axis and merging repeated points):
/// `1e-9` times the size of the input.
pub const DEFAULT_POLE_TOLERANCE: f64 = 1e-9;

/// Default largest angle between adjacent slices of [`revolve_z`]: 10° (36 slices).
pub const DEFAULT_SLICE_TOLERANCE: f64 = TAU / 36.0;

/// Why a surface mesh could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SurfaceError {
    /// Too few grid quads (or slices, or stacks) in one direction.
    #[error("a surface needs at least {needed} quads along {direction}, got {given}")]
    TooFewQuads {
        /// `'u'` or `'v'`.
        direction: char,
        /// The minimum: 1, or 3 for a wrapped direction.
        needed: usize,
        /// The count given.
        given: usize,
    },
    /// A profile with too few points.
    #[error("a profile needs at least {needed} points, got {given}")]
    InsufficientPoints {
        /// The minimum.
        needed: usize,
        /// The count given.
        given: usize,
    },
    /// Profile normals and points differ in number.
    #[error("{normals} normals for {points} profile points")]
    NormalCount {
        /// Number of profile points.
        points: usize,
        /// Number of normals.
        normals: usize,
    },
    /// An input value is NaN or infinite.
    #[error("{what} {index} is not finite")]
    NonFiniteInput {
        /// `profile point` or `profile normal`.
        what: &'static str,
        /// Its index.
        index: usize,
    },
    /// The surface function returned a NaN or infinite point.
    #[error("the surface function is not finite at u = {u}, v = {v}")]
    NonFiniteSample {
        /// Parameter `u` of the bad sample.
        u: f64,
        /// Parameter `v` of the bad sample.
        v: f64,
    },
    /// A profile point or radius key below zero (beyond the pole tolerance).
    #[error("profile point or radius key {index} has negative radius {value}")]
    NegativeRadius {
        /// Index of the point or key.
        index: usize,
        /// The radius.
        value: f64,
    },
    /// The scale of a revolution is not finite and positive.
    #[error("scale must be finite and positive, got {scale}")]
    BadScale {
        /// The value given.
        scale: f64,
    },
    /// The slice tolerance is not finite and positive.
    #[error("slice tolerance must be a finite, positive angle in radians, got {slice_tolerance}")]
    BadSliceTolerance {
        /// The value given.
        slice_tolerance: f64,
    },
    /// The pole tolerance is negative or not finite.
    #[error("pole tolerance must be finite and non-negative, got {pole_tolerance}")]
    BadPoleTolerance {
        /// The value given.
        pole_tolerance: f64,
    },
    /// The mesh would have more vertices than 32-bit indices can address.
    #[error("about {vertices:e} vertices do not fit 32-bit indices")]
    TooLarge {
        /// The (approximate) vertex count.
        vertices: f64,
    },
    /// Nothing with area is left: all samples coincide, or every row is a pole.
    #[error("the surface is degenerate: all samples coincide or every row collapses to a point")]
    Degenerate,
    /// The radius or height keys of a [`Lathe`] do not make a Bézier spline.
    #[error("{curve} keys: {error}")]
    Keys {
        /// `radius` or `height`.
        curve: &'static str,
        /// What is wrong with them.
        error: SplineError,
    },
}

/// Which texture coordinates a surface mesh gets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum UvMode {
    /// No UVs (`uvs` stays empty).
    Omit,
    /// UVs when no direction wraps, none when one does: the seam stays shared and a closed
    /// surface stays watertight.
    #[default]
    Auto,
    /// Always UVs. A wrapped direction gets its seam column (row) twice, with the same
    /// positions and normals but `u = 1` (`v = 1`) on the second copy, so texture
    /// coordinates can run continuously. The surface is still closed geometrically, but
    /// by index the seam is a boundary (`is_closed_oriented()` is false).
    SplitSeams,
}

/// Options of [`mesh_surface`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SurfaceOptions {
    /// Number of quads along `u` (columns of quads).
    pub nu: usize,
    /// Number of quads along `v` (rows of quads).
    pub nv: usize,
    /// `f(1, v) = f(0, v)`: the last column is the first, shared.
    pub wrap_u: bool,
    /// `f(u, 1) = f(u, 0)`: the last row is the first, shared.
    pub wrap_v: bool,
    /// Make the front the side opposite to `∂f/∂u × ∂f/∂v` (reverses every triangle and normal).
    pub flip: bool,
    /// Texture coordinates.
    pub uvs: UvMode,
    /// Relative tolerance for collapsing a row into a pole (times the bounding-box diagonal).
    pub pole_tolerance: f64,
}

impl SurfaceOptions {
    /// 32 × 16 quads, no wrap, no flip, [`UvMode::Auto`], [`DEFAULT_POLE_TOLERANCE`].
    pub const DEFAULT: Self = Self {
        nu: 32,
        nv: 16,
        wrap_u: false,
        wrap_v: false,
        flip: false,
        uvs: UvMode::Auto,
        pole_tolerance: DEFAULT_POLE_TOLERANCE,
    };

    /// The defaults with an `nu × nv` grid of quads.
    #[must_use]
    pub const fn new(nu: usize, nv: usize) -> Self {
        Self::DEFAULT.with_grid(nu, nv)
    }

    /// Sets the grid size in quads.
    #[must_use]
    pub const fn with_grid(mut self, nu: usize, nv: usize) -> Self {
        self.nu = nu;
        self.nv = nv;
        self
    }

    /// Sets which directions wrap.
    #[must_use]
    pub const fn with_wrap(mut self, wrap_u: bool, wrap_v: bool) -> Self {
        self.wrap_u = wrap_u;
        self.wrap_v = wrap_v;
        self
    }

    /// Sets whether the front is the side opposite to `∂f/∂u × ∂f/∂v`.
    #[must_use]
    pub const fn with_flip(mut self, flip: bool) -> Self {
        self.flip = flip;
        self
    }

    /// Sets the texture coordinates.
    #[must_use]
    pub const fn with_uvs(mut self, uvs: UvMode) -> Self {
        self.uvs = uvs;
        self
    }

    /// Sets the relative pole tolerance.
    #[must_use]
    pub const fn with_pole_tolerance(mut self, pole_tolerance: f64) -> Self {
        self.pole_tolerance = pole_tolerance;
        self
    }
}

impl Default for SurfaceOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Meshes the parametric surface `f(u, v)`, `u, v ∈ [0, 1]`, on a grid of
/// `nu × nv` quads (two triangles each), sampling `f(i/nu, j/nv)`.
///
/// Vertex normals are the area-weighted means of the adjacent face normals (no extra
/// evaluations of `f`; they converge to the surface normal as the grid refines). For
/// analytic normals use [`mesh_surface_with_partials`]. Orientation, poles, seams and UVs
/// follow the [module conventions](self); a wrapped direction never samples its last
/// parameter value (`u = 1` or `v = 1`), it reuses the first.
///
/// Cost: `(nu+1)(nv+1)` evaluations of `f` and `2·nu·nv` triangles at most.
///
/// # Errors
/// `nu` or `nv` below 1 (below 3 when wrapped), a bad `pole_tolerance`, a grid too large
/// for 32-bit indices, a non-finite sample, or a surface with no area left.
///
/// # Usage
/// ```
/// use glam::DVec3;
/// use splinekit::sweep::surface::{SurfaceOptions, mesh_surface};
/// use std::f64::consts::{PI, TAU};
/// let sphere = |u: f64, v: f64| {
///     let (theta, phi) = (TAU * u, PI * (v - 0.5));
///     DVec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin())
/// };
/// let mesh = mesh_surface(sphere, &SurfaceOptions::new(32, 16).with_wrap(true, false)).unwrap();
/// assert_eq!(mesh.num_vertices(), 2 + 32 * 15); // one vertex per pole
/// assert!(mesh.is_closed_oriented());
/// assert!((mesh.signed_volume() - 4.0 / 3.0 * PI).abs() < 0.1);
/// ```
pub fn mesh_surface<F>(f: F, options: &SurfaceOptions) -> Result<TriMesh, SurfaceError>
where
    F: Fn(f64, f64) -> DVec3,
{
    sample_surface(f, None::<fn(f64, f64) -> (DVec3, DVec3)>, options)
}

/// [`mesh_surface`] with analytic partial derivatives: `partials(u, v)` returns
/// `(∂f/∂u, ∂f/∂v)`, and the vertex normal is `∂f/∂u × ∂f/∂v` normalized (negated with
/// `flip`).
///
/// Where that cross product vanishes or is not finite (a pole, a degenerate parametrization),
/// or points more than 90° away from the adjacent faces, the vertex falls back to the
/// area-weighted mean of its face normals. Pole vertices always do.
///
/// # Errors
/// As [`mesh_surface`].
pub fn mesh_surface_with_partials<F, D>(f: F, partials: D, options: &SurfaceOptions) -> Result<TriMesh, SurfaceError>
where
    F: Fn(f64, f64) -> DVec3,
    D: Fn(f64, f64) -> (DVec3, DVec3),
{
    sample_surface(f, Some(partials), options)
}

fn sample_surface<F, D>(f: F, partials: Option<D>, o: &SurfaceOptions) -> Result<TriMesh, SurfaceError>
where
    F: Fn(f64, f64) -> DVec3,
    D: Fn(f64, f64) -> (DVec3, DVec3),
{
    for (direction, given, wrap) in [('u', o.nu, o.wrap_u), ('v', o.nv, o.wrap_v)] {
        let needed = if wrap { 3 } else { 1 };
        if given < needed {
            return Err(SurfaceError::TooFewQuads { direction, needed, given });
        }
    }
    check_pole_tolerance(o.pole_tolerance)?;
    check_size(o.nu, o.nv)?;
    let us: Vec<f64> = (0..=o.nu).map(|i| i as f64 / o.nu as f64).collect();
    let vs: Vec<f64> = (0..=o.nv).map(|j| j as f64 / o.nv as f64).collect();
    let cols = if o.wrap_u { o.nu } else { o.nu + 1 };
    let rows = if o.wrap_v { o.nv } else { o.nv + 1 };
    let mut points = Vec::with_capacity(rows * cols);
    let mut hints = Vec::with_capacity(if partials.is_some() { rows * cols } else { 0 });
    for &v in &vs[..rows] {
        for &u in &us[..cols] {
            let p = f(u, v);
            if !p.is_finite() {
                return Err(SurfaceError::NonFiniteSample { u, v });
            }
            points.push(p);
            if let Some(d) = &partials {
                let (du, dv) = d(u, v);
                hints.push(du.cross(dv));
            }
        }
    }
    build(Grid {
        nu: o.nu,
        nv: o.nv,
        wrap_u: o.wrap_u,
        wrap_v: o.wrap_v,
        points,
        hints,
        poles: None,
        us,
        vs,
        flip: o.flip,
        uvs: o.uvs,
        pole_tolerance: o.pole_tolerance,
    })
}

/// Options of [`revolve_z`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct RevolveOptions {
    /// Uniform scale `s > 0`: profile point `(x, y)` goes to `(s·x·cos φ, s·x·sin φ, s·y)`.
    pub scale: f64,
    /// Largest angle between adjacent slices, in radians (`> 0`); see
    /// [`num_slices`](Self::num_slices).
    pub slice_tolerance: f64,
    /// Texture coordinates: `u = φ/2π`, `v` = normalized chord length along the profile.
    pub uvs: UvMode,
    /// Relative tolerance (times the diagonal of the profile's bounding box) for snapping a
    /// point onto the axis (a pole), for merging repeated points, and for recognising a
    /// closed profile.
    pub pole_tolerance: f64,
}

impl RevolveOptions {
    /// Scale 1, [`DEFAULT_SLICE_TOLERANCE`], [`UvMode::Auto`] (no UVs: the seam wraps),
    /// [`DEFAULT_POLE_TOLERANCE`].
    pub const DEFAULT: Self = Self {
        scale: 1.0,
        slice_tolerance: DEFAULT_SLICE_TOLERANCE,
        uvs: UvMode::Auto,
        pole_tolerance: DEFAULT_POLE_TOLERANCE,
    };

    /// The defaults with this scale and slice tolerance.
    #[must_use]
    pub const fn new(scale: f64, slice_tolerance: f64) -> Self {
        Self { scale, slice_tolerance, ..Self::DEFAULT }
    }

    /// Sets the scale.
    #[must_use]
    pub const fn with_scale(mut self, scale: f64) -> Self {
        self.scale = scale;
        self
    }

    /// Sets the slice tolerance (radians).
    #[must_use]
    pub const fn with_slice_tolerance(mut self, slice_tolerance: f64) -> Self {
        self.slice_tolerance = slice_tolerance;
        self
    }

    /// Sets the texture coordinates.
    #[must_use]
    pub const fn with_uvs(mut self, uvs: UvMode) -> Self {
        self.uvs = uvs;
        self
    }

    /// Sets the relative pole tolerance.
    #[must_use]
    pub const fn with_pole_tolerance(mut self, pole_tolerance: f64) -> Self {
        self.pole_tolerance = pole_tolerance;
        self
    }

    /// The number of slices, `ceil(2π / slice_tolerance)`, and never fewer than 3.
    ///
    /// A ratio within `1e-9` (relative) of an integer counts as that integer, so that
    /// `slice_tolerance = 2π/36` gives 36 slices despite rounding.
    ///
    /// # Errors
    /// A slice tolerance that is not finite and positive, or so small that the slices do
    /// not fit 32-bit indices.
    pub fn num_slices(&self) -> Result<usize, SurfaceError> {
        let t = self.slice_tolerance;
        if !(t > 0.0 && t.is_finite()) {
            return Err(SurfaceError::BadSliceTolerance { slice_tolerance: t });
        }
        let ratio = TAU / t;
        if !(ratio < f64::from(u32::MAX)) {
            return Err(SurfaceError::TooLarge { vertices: ratio });
        }
        let k = ratio.round();
        let slices = if (ratio - k).abs() <= 1e-9 * k { k } else { ratio.ceil() };
        // in range: 0 < slices < u32::MAX
        Ok((slices as usize).max(3))
    }
}

impl Default for RevolveOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Revolves a profile polyline about +z (the interactive revolution tool's convention):
/// profile point `(x, y)`, `x ≥ 0`, goes to `(s·x·cos φ, s·x·sin φ, s·y)` for
/// the [`num_slices`](RevolveOptions::num_slices) angles `φ = 2πk/slices`; the seam at
/// `φ = 2π` is shared.
///
/// Row `j` of the mesh is the `j`-th distinct profile point (see repeated points below);
/// `u = φ/2π` runs counter-clockwise about +z.
///
/// - **Poles.** Points on the axis (`|x|` within the pole tolerance; such points may be
///   slightly negative and are snapped to `x = 0`) become single vertices, typically the two
///   ends of a closed profile such as a half circle.
/// - **Repeated points.** Consecutive points that coincide (within the pole tolerance) are
///   merged, so they add no zero-area ring.
/// - **Closed profiles.** When the last point repeats the first (and at least three other
///   points remain), the profile is a loop: the last point is dropped and the rows wrap,
///   so a circle off the axis gives a watertight torus.
/// - **Orientation.** The triangles face outward whichever way the profile runs. The
///   test is the signed volume `W = π·Σ (y₁ − y₀)(x₀² + x₀x₁ + x₁²)/3` over the profile
///   segments: the exact volume enclosed by the revolved profile, capped at both ends by
///   disks perpendicular to the axis (for a closed profile, the volume itself). If `W > 0`
///   the faces are counter-clockwise seen from the side the profile's right normal
///   `(T.y, −T.x)` points to (outside when the profile runs counter-clockwise around the
///   region it bounds, for example up the x > 0 side); if `W < 0` they are flipped. When `W`
///   is zero (a flat disk, a profile going back over itself) the given normals decide the
///   side, and without normals the right normal does.
/// - **Normals.** With `normals`, vertex normals are the profile normals rotated with the
///   points and normalized; if they point, on balance, to the inside, all of them are
///   negated so they agree with the faces. Without, each point gets the bisector of its
///   segments' normals. Poles, and zero normals, get the area-weighted face mean.
/// - **UVs** (see [`UvMode`]): `u = φ/2π`, `v` = chord length along the profile, normalized.
///
/// Counts (open profile of `n` distinct points, `p` of them poles, `k` slices):
/// `k·(n − p) + p` vertices and `2k(n − 1) − k·(number of segment ends that are poles)`
/// triangles.
///
/// # Errors
/// Fewer than 2 points, non-finite points or normals, `normals` of another length, a
/// point with `x` below zero, a bad scale, slice tolerance or pole tolerance, or a profile
/// with no area (all points equal, or all on the axis).
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::sweep::surface::{RevolveOptions, revolve_z};
/// use std::f64::consts::PI;
/// // a half circle from the south pole to the north pole: a sphere
/// let profile: Vec<DVec2> =
///     (0..=32).map(|i| { let a = PI * (i as f64 / 32.0 - 0.5); DVec2::new(a.cos(), a.sin()) }).collect();
/// let mesh = revolve_z(&profile, None, &RevolveOptions::new(2.0, PI / 32.0)).unwrap();
/// assert_eq!(mesh.num_vertices(), 2 + 64 * 31);
/// assert!(mesh.is_closed_oriented());
/// assert!((mesh.signed_volume() - 4.0 / 3.0 * PI * 8.0).abs() < 0.2);
/// ```
pub fn revolve_z(
    profile: &[DVec2],
    normals: Option<&[DVec2]>,
    options: &RevolveOptions,
) -> Result<TriMesh, SurfaceError> {
    let (axial, slices) = revolve_z_profile(profile, normals, options)?;
    axial.mesh(normals, None, slices, options.uvs, options.pole_tolerance)
}

/// The vertex and triangle counts of [`revolve_z`]`(profile, normals, options)`, without
/// building it: the work is linear in the profile's length, whatever the slices.
///
/// # Errors
/// As [`revolve_z`].
pub fn revolve_z_counts(
    profile: &[DVec2],
    normals: Option<&[DVec2]>,
    options: &RevolveOptions,
) -> Result<MeshCounts, SurfaceError> {
    let (axial, slices) = revolve_z_profile(profile, normals, options)?;
    axial.counts(slices, options.uvs)
}

/// [`revolve_z`]'s input checked and scaled, and its slices.
fn revolve_z_profile(
    profile: &[DVec2],
    normals: Option<&[DVec2]>,
    options: &RevolveOptions,
) -> Result<(AxialProfile, usize), SurfaceError> {
    let s = options.scale;
    if !(s > 0.0 && s.is_finite()) {
        return Err(SurfaceError::BadScale { scale: s });
    }
    check_pole_tolerance(options.pole_tolerance)?;
    let slices = options.num_slices()?;
    if profile.len() < 2 {
        return Err(SurfaceError::InsufficientPoints { needed: 2, given: profile.len() });
    }
    if let Some(index) = profile.iter().position(|p| !p.is_finite()) {
        return Err(SurfaceError::NonFiniteInput { what: "profile point", index });
    }
    if let Some(n) = normals {
        if n.len() != profile.len() {
            return Err(SurfaceError::NormalCount { points: profile.len(), normals: n.len() });
        }
        if let Some(index) = n.iter().position(|p| !p.is_finite()) {
            return Err(SurfaceError::NonFiniteInput { what: "profile normal", index });
        }
    }
    let points: Vec<DVec2> = profile.iter().map(|&p| p * s).collect();
    Ok((AxialProfile::new(&points, options.pole_tolerance)?, slices))
}

/// Options of [`Lathe::to_mesh`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct LatheOptions {
    /// Number of slices around the axis (at least 3).
    pub slices: usize,
    /// Number of intervals along `v` (at least 1): the curves are sampled at `v = j/stacks`.
    pub stacks: usize,
    /// Texture coordinates: `u` around the axis, `v` the lathe parameter.
    pub uvs: UvMode,
    /// Relative pole tolerance, as in [`RevolveOptions::pole_tolerance`].
    pub pole_tolerance: f64,
}

impl LatheOptions {
    /// 32 slices, 32 stacks, [`UvMode::Auto`], [`DEFAULT_POLE_TOLERANCE`].
    pub const DEFAULT: Self =
        Self { slices: 32, stacks: 32, uvs: UvMode::Auto, pole_tolerance: DEFAULT_POLE_TOLERANCE };

    /// The defaults with this resolution.
    #[must_use]
    pub const fn new(slices: usize, stacks: usize) -> Self {
        Self { slices, stacks, ..Self::DEFAULT }
    }

    /// Sets the texture coordinates.
    #[must_use]
    pub const fn with_uvs(mut self, uvs: UvMode) -> Self {
        self.uvs = uvs;
        self
    }

    /// Sets the relative pole tolerance.
    #[must_use]
    pub const fn with_pole_tolerance(mut self, pole_tolerance: f64) -> Self {
        self.pole_tolerance = pole_tolerance;
        self
    }
}

impl Default for LatheOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A lathe surface with independent radius and height curves:
/// `P(u, v) = (r(v)·cos 2πu, r(v)·sin 2πu, z(v))`, `u, v ∈ [0, 1]`.
///
/// `r` and `z` are piecewise cubic Bézier curves of scalar keys, each `3m + 1` keys (the
/// rule of [`BezierSpline`]); the two may have different numbers of segments. Each curve's
/// own parameter `[0, m]` is stretched linearly onto `v ∈ [0, 1]`.
///
/// # Interpolation
/// Passes through every third key: `r(k/m) = key[3k]`.
///
/// # Tips
/// Where `r` reaches 0 at `v = 0` or `v = 1` the surface closes in a single pole vertex
/// (a rounded tip when the curves leave the axis perpendicularly). Radius keys must be
/// non-negative, which keeps `r(v) ≥ 0` everywhere (convex hull property).
///
/// # Usage
/// ```
/// use splinekit::sweep::surface::{Lathe, LatheOptions};
/// let k = 0.552_284_75; // quarter circles
/// let lathe = Lathe::new(&[0.0, k, 1.0, 1.0, 1.0, k, 0.0], &[-1.0, -1.0, -k, 0.0, k, 1.0, 1.0]).unwrap();
/// let mesh = lathe.to_mesh(&LatheOptions::new(48, 32)).unwrap();
/// assert!(mesh.is_closed_oriented());
/// assert_eq!(mesh.num_vertices(), 2 + 48 * 31);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Lathe {
    radius: PiecewiseCubic<DVec2>,
    height: PiecewiseCubic<DVec2>,
}

impl Lathe {
    /// Validates and compiles the key arrays (each `3m + 1` finite keys; radius keys `≥ 0`).
    ///
    /// # Errors
    /// [`SurfaceError::Keys`] for a bad count or a non-finite key,
    /// [`SurfaceError::NegativeRadius`] for a negative radius key.
    pub fn new(radius_keys: &[f64], height_keys: &[f64]) -> Result<Self, SurfaceError> {
        let compile = |curve: &'static str, keys: &[f64]| {
            let pts: Vec<DVec2> = keys.iter().map(|&k| DVec2::new(k, 0.0)).collect();
            BezierSpline::new(&pts, false)
                .map(|b| b.to_piecewise())
                .map_err(|error| SurfaceError::Keys { curve, error })
        };
        let radius = compile("radius", radius_keys)?;
        let height = compile("height", height_keys)?;
        if let Some(index) = radius_keys.iter().position(|&r| r < 0.0) {
            return Err(SurfaceError::NegativeRadius { index, value: radius_keys[index] });
        }
        Ok(Self { radius, height })
    }

    /// The profile point `(r(v), z(v))` (`v` outside `[0, 1]` extrapolates the end segments).
    #[must_use]
    pub fn profile(&self, v: f64) -> DVec2 {
        let (mr, mz) = self.widths();
        DVec2::new(self.radius.eval(v * mr).x, self.height.eval(v * mz).x)
    }

    /// The derivative `(dr/dv, dz/dv)`.
    #[must_use]
    pub fn profile_deriv(&self, v: f64) -> DVec2 {
        let (mr, mz) = self.widths();
        DVec2::new(self.radius.deriv(v * mr).x * mr, self.height.deriv(v * mz).x * mz)
    }

    /// The surface point `(r cos 2πu, r sin 2πu, z)` at `(u, v)`.
    #[must_use]
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let p = self.profile(v);
        let (sin, cos) = (TAU * u).sin_cos();
        DVec3::new(p.x * cos, p.x * sin, p.y)
    }

    /// Meshes the lathe: `slices` columns around the axis (seam shared), the curves sampled
    /// at `v = j/stacks`, and the sampled profile revolved as in [`revolve_z`] (poles where
    /// `r = 0`, repeated samples merged, outward orientation by signed volume, a loop if
    /// the last sample repeats the first). Vertex normals come from the derivatives:
    /// `(z′·cos 2πu, z′·sin 2πu, −r′)` normalized, oriented outward; where both derivatives
    /// vanish, and at poles, the area-weighted face mean is used.
    ///
    /// # Errors
    /// `slices < 3`, `stacks < 1`, a bad pole tolerance, too many vertices for 32-bit
    /// indices, or a profile with no area (for example `r = 0` everywhere).
    pub fn to_mesh(&self, options: &LatheOptions) -> Result<TriMesh, SurfaceError> {
        let (axial, vs) = self.axial_profile(options)?;
        let normals: Vec<DVec2> = vs
            .iter()
            .map(|&v| {
                let d = self.profile_deriv(v);
                DVec2::new(d.y, -d.x)
            })
            .collect();
        axial.mesh(Some(&normals), Some(&vs), options.slices, options.uvs, options.pole_tolerance)
    }

    /// The vertex and triangle counts of [`Self::to_mesh`]`(options)`, without building it:
    /// the work is linear in the stacks, whatever the slices.
    ///
    /// # Errors
    /// As [`Self::to_mesh`].
    pub fn counts(&self, options: &LatheOptions) -> Result<MeshCounts, SurfaceError> {
        self.axial_profile(options)?.0.counts(options.slices, options.uvs)
    }

    /// The options checked, and the profile at the stacks' `v`, with those `v`.
    fn axial_profile(&self, options: &LatheOptions) -> Result<(AxialProfile, Vec<f64>), SurfaceError> {
        if options.slices < 3 {
            return Err(SurfaceError::TooFewQuads { direction: 'u', needed: 3, given: options.slices });
        }
        if options.stacks < 1 {
            return Err(SurfaceError::TooFewQuads { direction: 'v', needed: 1, given: options.stacks });
        }
        check_pole_tolerance(options.pole_tolerance)?;
        check_size(options.slices, options.stacks)?;
        let n = options.stacks;
        let vs: Vec<f64> = (0..=n).map(|j| j as f64 / n as f64).collect();
        let points: Vec<DVec2> = vs
            .iter()
            .map(|&v| {
                let p = self.profile(v);
                DVec2::new(p.x.max(0.0), p.y)
            })
            .collect();
        Ok((AxialProfile::new(&points, options.pole_tolerance)?, vs))
    }

    fn widths(&self) -> (f64, f64) {
        (self.radius.num_segments() as f64, self.height.num_segments() as f64)
    }
}

fn check_pole_tolerance(pole_tolerance: f64) -> Result<(), SurfaceError> {
    if pole_tolerance >= 0.0 && pole_tolerance.is_finite() {
        Ok(())
    } else {
        Err(SurfaceError::BadPoleTolerance { pole_tolerance })
    }
}

/// Fails when an `(nu+1) × (nv+1)` grid of vertices would not fit 32-bit indices.
fn check_size(nu: usize, nv: usize) -> Result<(), SurfaceError> {
    let count = nu.checked_add(1).and_then(|a| nv.checked_add(1).and_then(|b| a.checked_mul(b)));
    match count {
        Some(c) if c <= u32::MAX as usize => Ok(()),
        _ => Err(SurfaceError::TooLarge { vertices: (nu as f64 + 1.0) * (nv as f64 + 1.0) }),
    }
}

/// A profile ready to be revolved about +z by [`revolve_z`] and [`Lathe::to_mesh`]: points
/// snapped onto the axis and repeated points merged.
struct AxialProfile {
    /// The distinct points, in order (a loop repeats its first point at the end).
    pts: Vec<DVec2>,
    /// The index in the caller's points of each of `pts`.
    keep: Vec<usize>,
    /// The last point repeats the first.
    closed: bool,
    /// Rows of the grid: the points, less the repeated first point of a loop.
    rows: usize,
    /// Quads along the profile.
    nv: usize,
    /// The size of the points' bounding box.
    size: f64,
}

impl AxialProfile {
    /// `points` are finite and already scaled.
    fn new(points: &[DVec2], pole_tolerance: f64) -> Result<Self, SurfaceError> {
        let (lo, hi) =
            points.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let size = (hi - lo).length();
        // revolved, the points span twice their largest radius: that too must be finite
        if !(size > 0.0 && (2.0 * size).is_finite()) {
            return Err(SurfaceError::Degenerate);
        }
        let tol = pole_tolerance * size;
        if let Some(index) = points.iter().position(|p| p.x < -tol) {
            return Err(SurfaceError::NegativeRadius { index, value: points[index].x });
        }
        // snap onto the axis, merge repeated points (keeping the first of each run)
        let mut keep: Vec<usize> = Vec::with_capacity(points.len());
        let mut pts: Vec<DVec2> = Vec::with_capacity(points.len());
        for (i, &p) in points.iter().enumerate() {
            let p = if p.x <= tol { DVec2::new(0.0, p.y) } else { p };
            if pts.last().is_none_or(|q| q.distance(p) > tol) {
                keep.push(i);
                pts.push(p);
            }
        }
        let closed = pts.len() >= 4 && pts[0].distance(pts[pts.len() - 1]) <= tol;
        let rows = if closed { pts.len() - 1 } else { pts.len() };
        if rows < 2 {
            return Err(SurfaceError::Degenerate);
        }
        let nv = if closed { rows } else { rows - 1 };
        Ok(Self { pts, keep, closed, rows, nv, size })
    }

    /// Which rows are poles (points on the axis).
    fn poles(&self) -> Vec<bool> {
        self.pts[..self.rows].iter().map(|p| p.x == 0.0).collect()
    }

    /// The vertex and triangle counts of [`Self::mesh`] with `slices` and `uvs`.
    fn counts(&self, slices: usize, uvs: UvMode) -> Result<MeshCounts, SurfaceError> {
        check_size(slices, self.nv)?;
        let poles = self.poles();
        let pole_at = |j: usize| poles[j % self.rows];
        let triangles = grid_triangle_count(slices, self.nv, &pole_at);
        if triangles == 0 {
            return Err(SurfaceError::Degenerate);
        }
        // the seam is shared unless UVs split it (see `build`)
        let (columns, rows) = if uvs == UvMode::SplitSeams { (slices + 1, self.nv + 1) } else { (slices, self.rows) };
        let vertices = (0..rows).map(|j| if pole_at(j) { 1 } else { columns as u64 }).sum();
        Ok(MeshCounts { vertices, triangles })
    }

    /// The revolution: `normals` (finite, as long as the caller's points) are the caller's,
    /// in any orientation; `vs` (same length) are the `v` texture coordinates (chord length
    /// if `None`).
    fn mesh(
        &self,
        normals: Option<&[DVec2]>,
        vs: Option<&[f64]>,
        slices: usize,
        uvs: UvMode,
        pole_tolerance: f64,
    ) -> Result<TriMesh, SurfaceError> {
        let Self { pts, keep, closed, rows, nv, size } = self;
        let (closed, rows, nv, size) = (*closed, *rows, *nv, *size);
        let segment = |k: usize| (pts[k], pts[(k + 1) % rows]);

        // unit right normals (T.y, −T.x) of the segments, and their bisectors at the points
        let right: Vec<DVec2> = (0..nv)
            .map(|k| {
                let (a, b) = segment(k);
                DVec2::new(b.y - a.y, a.x - b.x).try_normalize().unwrap_or(DVec2::ZERO)
            })
            .collect();
        let bisector: Vec<DVec2> = (0..rows)
            .map(|j| {
                let before = if j > 0 {
                    right[j - 1]
                } else if closed {
                    right[nv - 1]
                } else {
                    DVec2::ZERO
                };
                let after = if j < nv { right[j] } else { DVec2::ZERO };
                (before + after).try_normalize().unwrap_or(DVec2::ZERO)
            })
            .collect();

        // which side is out: the capped volume, else the given normals, else the right normal
        let volume: f64 = (0..nv)
            .map(|k| {
                let (a, b) = segment(k);
                (b.y - a.y) * (a.x * a.x + a.x * b.x + b.x * b.x) / 3.0
            })
            .sum();
        let given: Option<Vec<DVec2>> =
            normals.map(|n| keep[..rows].iter().map(|&i| n[i].try_normalize().unwrap_or(DVec2::ZERO)).collect());
        let agreement: f64 = given.as_ref().map_or(0.0, |g| g.iter().zip(&bisector).map(|(a, b)| a.dot(*b)).sum());
        let sign = if agreement < 0.0 { -1.0 } else { 1.0 };
        let flip = if volume.abs() > 1e-12 * size * size * size { volume < 0.0 } else { agreement < 0.0 };
        // vertex normal hints, on the right-normal side (the grid flips them with the faces)
        let hints2: Vec<DVec2> = match &given {
            Some(g) => g.iter().map(|&n| n * sign).collect(),
            None => bisector,
        };

        let v_coords: Vec<f64> = match vs {
            Some(vs) => keep.iter().map(|&i| vs[i]).collect(),
            None => {
                let mut acc = Vec::with_capacity(pts.len());
                let mut total = 0.0;
                for (k, p) in pts.iter().enumerate() {
                    if k > 0 {
                        total += p.distance(pts[k - 1]);
                    }
                    acc.push(total);
                }
                acc.iter().map(|&d| d / total).collect()
            }
        };
        check_size(slices, nv)?;
        let us: Vec<f64> = (0..=slices).map(|i| i as f64 / slices as f64).collect();
        let angles: Vec<(f64, f64)> = us[..slices].iter().map(|&u| (TAU * u).sin_cos()).collect();
        let mut points3 = Vec::with_capacity(rows * slices);
        let mut hints3 = Vec::with_capacity(rows * slices);
        for (p, n) in pts[..rows].iter().zip(&hints2) {
            for &(sin, cos) in &angles {
                points3.push(DVec3::new(p.x * cos, p.x * sin, p.y));
                hints3.push(DVec3::new(n.x * cos, n.x * sin, n.y));
            }
        }
        build(Grid {
            nu: slices,
            nv,
            wrap_u: true,
            wrap_v: closed,
            points: points3,
            hints: hints3,
            poles: Some(self.poles()),
            us,
            vs: v_coords,
            flip,
            uvs,
            pole_tolerance,
        })
    }
}

/// A sampled grid, ready to be triangulated.
struct Grid {
    /// Quads along `u` and `v`.
    nu: usize,
    nv: usize,
    wrap_u: bool,
    wrap_v: bool,
    /// `rows × cols` samples, row-major (`cols = nu` if `wrap_u` else `nu + 1`, likewise rows).
    points: Vec<DVec3>,
    /// Analytic normals on the `∂f/∂u × ∂f/∂v` side, same layout (zero = none), or empty.
    hints: Vec<DVec3>,
    /// Which rows are poles; `None` to detect them with `pole_tolerance`.
    poles: Option<Vec<bool>>,
    /// Texture coordinates of the `nu + 1` columns and `nv + 1` rows.
    us: Vec<f64>,
    vs: Vec<f64>,
    flip: bool,
    uvs: UvMode,
    pole_tolerance: f64,
}

/// Triangulates a grid; see the module conventions. The caller has checked the counts
/// (`nu, nv ≥ 1`, `≥ 3` when wrapped, `(nu+1)(nv+1) ≤ u32::MAX`) and finiteness.
fn build(g: Grid) -> Result<TriMesh, SurfaceError> {
    let cols = if g.wrap_u { g.nu } else { g.nu + 1 };
    let rows = if g.wrap_v { g.nv } else { g.nv + 1 };
    let row = |j: usize| &g.points[j * cols..(j + 1) * cols];
    let (lo, hi) = g.points.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let size = (hi - lo).length();
    if !(size > 0.0 && size.is_finite()) {
        return Err(SurfaceError::Degenerate);
    }
    let tol = g.pole_tolerance * size;
    let poles: Vec<bool> = match g.poles {
        Some(p) => p,
        None => (0..rows)
            .map(|j| {
                let r = row(j);
                r.iter().all(|p| p.distance(r[0]) <= tol)
            })
            .collect(),
    };

    // welded layout: one vertex per sample, one per pole row, seams shared
    let mut base = Vec::with_capacity(rows);
    let mut positions = Vec::with_capacity(rows * cols);
    let mut hints = Vec::with_capacity(if g.hints.is_empty() { 0 } else { rows * cols });
    for (j, &pole) in poles.iter().enumerate() {
        base.push(positions.len() as u32);
        if pole {
            positions.push(row(j).iter().sum::<DVec3>() / cols as f64);
            if !g.hints.is_empty() {
                hints.push(DVec3::ZERO);
            }
        } else {
            positions.extend_from_slice(row(j));
            if !g.hints.is_empty() {
                hints.extend_from_slice(&g.hints[j * cols..(j + 1) * cols]);
            }
        }
    }
    let pole_at = |j: usize| poles[j % rows];
    let welded = |i: usize, j: usize| {
        let j = j % rows;
        if poles[j] { base[j] } else { base[j] + (i % cols) as u32 }
    };
    let triangles = grid_triangles(g.nu, g.nv, &pole_at, g.flip, &welded);
    if triangles.is_empty() {
        return Err(SurfaceError::Degenerate);
    }
    let normals = vertex_normals(&positions, &triangles, &hints, g.flip);
    let wrapped = g.wrap_u || g.wrap_v;
    let want_uvs = match g.uvs {
        UvMode::Omit => false,
        UvMode::Auto => !wrapped,
        UvMode::SplitSeams => true,
    };
    if !want_uvs {
        return Ok(TriMesh { positions, normals, triangles, ..TriMesh::default() });
    }

    // UV layout: every column 0..=nu and row 0..=nv has its own vertices (identical to the
    // welded layout when nothing wraps); positions and normals are copied from the welded mesh
    let mut split_base = Vec::with_capacity(g.nv + 1);
    let mut mesh = TriMesh::default();
    for j in 0..=g.nv {
        split_base.push(mesh.positions.len() as u32);
        let columns: &[f64] = if pole_at(j) { &[0.5] } else { &g.us };
        for (i, &u) in columns.iter().enumerate() {
            let w = welded(i, j) as usize;
            mesh.positions.push(positions[w]);
            mesh.normals.push(normals[w]);
            mesh.uvs.push(DVec2::new(u, g.vs[j]));
        }
    }
    let split = |i: usize, j: usize| if pole_at(j) { split_base[j] } else { split_base[j] + i as u32 };
    mesh.triangles = grid_triangles(g.nu, g.nv, &pole_at, g.flip, &split);
    Ok(mesh)
}

/// The triangles of an `nu × nv` grid of quads, with corners named by `id(i, j)`,
/// `0 ≤ i ≤ nu`, `0 ≤ j ≤ nv`. Quad `(i, j)` gives `(a, b, c)` and `(a, c, d)` with
/// `a = (i, j)`, `b = (i+1, j)`, `c = (i+1, j+1)`, `d = (i, j+1)`, counter-clockwise seen
/// from the `∂f/∂u × ∂f/∂v` side; the triangle that would collapse next to a pole row is
/// left out, and so are quads between two pole rows.
fn grid_triangles(
    nu: usize,
    nv: usize,
    pole: &impl Fn(usize) -> bool,
    flip: bool,
    id: &impl Fn(usize, usize) -> u32,
) -> Vec<[u32; 3]> {
    let tri = |a, b, c| if flip { [a, c, b] } else { [a, b, c] };
    let mut out = Vec::with_capacity(2usize.saturating_mul(nu).saturating_mul(nv));
    for j in 0..nv {
        let (p0, p1) = (pole(j), pole(j + 1));
        if p0 && p1 {
            continue;
        }
        for i in 0..nu {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if !p0 {
                out.push(tri(a, b, c));
            }
            if !p1 {
                out.push(tri(a, c, d));
            }
        }
    }
    out
}

/// How many triangles [`grid_triangles`] gives: the quads of every row of quads that is not
/// between two poles, less one triangle for each quad next to a pole.
fn grid_triangle_count(nu: usize, nv: usize, pole: &impl Fn(usize) -> bool) -> u64 {
    (0..nv).map(|j| (u64::from(!pole(j)) + u64::from(!pole(j + 1))) * nu as u64).sum()
}

/// Unit vertex normals: the hint (negated with `flip`) when it is usable and within 90° of
/// the area-weighted face mean; else that mean; else the direction from the centroid; else +z.
fn vertex_normals(positions: &[DVec3], triangles: &[[u32; 3]], hints: &[DVec3], flip: bool) -> Vec<DVec3> {
    let acc = crate::mesh::normal_sums(positions, triangles);
    let centroid = positions.iter().sum::<DVec3>() / positions.len().max(1) as f64;
    let side = if flip { -1.0 } else { 1.0 };
    (0..positions.len())
        .map(|k| {
            let face = acc[k].try_normalize();
            let hint = hints.get(k).and_then(|&h| (h * side).try_normalize());
            match (hint, face) {
                (Some(h), Some(f)) if h.dot(f) >= 0.0 => h,
                (Some(h), None) => h,
                (_, Some(f)) => f,
                (None, None) => (positions[k] - centroid).try_normalize().unwrap_or(DVec3::Z),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;
    use std::f64::consts::PI;

    use super::*;

    /// Tolerance for exact-by-construction comparisons.
    const EXACT: f64 = 1e-12;

    fn euler(m: &TriMesh) -> i64 {
        let edges: HashSet<(u32, u32)> = m
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
            .collect();
        m.num_vertices() as i64 - edges.len() as i64 + m.num_triangles() as i64
    }

    fn torus(big: f64, small: f64) -> impl Fn(f64, f64) -> DVec3 {
        move |u, v| {
            let (a, b) = (TAU * u, TAU * v);
            let r = big + small * b.cos();
            DVec3::new(r * a.cos(), r * a.sin(), small * b.sin())
        }
    }

    fn sphere(u: f64, v: f64) -> DVec3 {
        let (theta, phi) = (TAU * u, PI * (v - 0.5));
        DVec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin())
    }

    #[test]
    fn quad_triangles_and_fans() {
        // 2 × 2 grid, no poles: corners by (i, j) = 3j + i
        let id = |i: usize, j: usize| (3 * j + i) as u32;
        let t = grid_triangles(2, 2, &|_| false, false, &id);
        assert_eq!(t.len(), 8);
        assert_eq!(t[0], [0, 1, 4]);
        assert_eq!(t[1], [0, 4, 3]);
        let flipped = grid_triangles(2, 2, &|_| false, true, &id);
        assert_eq!(flipped[0], [0, 4, 1]);
        // pole rows 0 and 2: only the fan triangles remain
        let t = grid_triangles(2, 2, &|j| j != 1, false, &id);
        assert_eq!(t.len(), 4);
        // both rows of a quad band are poles: nothing
        assert!(grid_triangles(3, 1, &|_| true, false, &id).is_empty());
    }

    #[test]
    fn flat_grid_counts_normals_uvs() {
        let m = mesh_surface(|u, v| DVec3::new(2.0 * u, v, 0.0), &SurfaceOptions::new(4, 3)).unwrap();
        m.validate().unwrap();
        assert_eq!((m.num_vertices(), m.num_triangles()), (20, 24));
        assert_eq!(m.boundary_edges().len(), 14);
        assert_eq!(m.uvs[5 + 2], DVec2::new(0.5, 1.0 / 3.0));
        for i in 0..m.num_triangles() {
            assert!(m.face_normal(i).normalize().distance(DVec3::Z) < EXACT);
        }
        assert!(m.normals.iter().all(|n| n.distance(DVec3::Z) < EXACT));
        let f = mesh_surface(|u, v| DVec3::new(2.0 * u, v, 0.0), &SurfaceOptions::new(4, 3).with_flip(true)).unwrap();
        assert!(f.normals.iter().all(|n| n.distance(-DVec3::Z) < EXACT));
        assert!((0..f.num_triangles()).all(|i| f.face_normal(i).z < 0.0));
    }

    #[test]
    fn torus_welded_and_split() {
        let o = SurfaceOptions::new(12, 8).with_wrap(true, true);
        let m = mesh_surface(torus(2.0, 0.5), &o).unwrap();
        assert_eq!(m.num_vertices(), 96);
        assert!(m.uvs.is_empty());
        assert!(m.is_closed_oriented());
        assert_eq!(euler(&m), 0);
        let s = mesh_surface(torus(2.0, 0.5), &o.with_uvs(UvMode::SplitSeams)).unwrap();
        s.validate().unwrap();
        assert_eq!(s.num_vertices(), 13 * 9);
        assert_eq!(s.num_triangles(), m.num_triangles());
        assert!((s.signed_volume() - m.signed_volume()).abs() < EXACT);
        // the seam copies sit exactly on the originals, with u = 1
        assert_eq!(s.positions[12], s.positions[0]);
        assert_eq!(s.normals[12], s.normals[0]);
        assert_eq!(s.uvs[12], DVec2::new(1.0, 0.0));
        assert_eq!(s.boundary_edges().len(), 2 * (12 + 8));
    }

    #[test]
    fn sphere_poles() {
        let m = mesh_surface(sphere, &SurfaceOptions::new(16, 8).with_wrap(true, false)).unwrap();
        assert_eq!(m.num_vertices(), 2 + 16 * 7);
        assert_eq!(m.num_triangles(), 2 * 16 * 7);
        assert!(m.is_closed_oriented());
        assert_eq!(euler(&m), 2);
        assert!(m.positions[0].distance(-DVec3::Z) < EXACT);
        assert!(m.normals[0].distance(-DVec3::Z) < EXACT);
        // UVs requested with a wrap: split seam, poles still single
        let s = mesh_surface(sphere, &SurfaceOptions::new(16, 8).with_wrap(true, false).with_uvs(UvMode::SplitSeams))
            .unwrap();
        assert_eq!(s.num_vertices(), 2 + 17 * 7);
        assert_eq!(s.uvs[0], DVec2::new(0.5, 0.0));
    }

    #[test]
    fn analytic_normals_are_used() {
        let (big, small) = (2.0, 0.5);
        let partials = move |u: f64, v: f64| {
            let (a, b) = (TAU * u, TAU * v);
            let r = big + small * b.cos();
            (
                DVec3::new(-r * a.sin(), r * a.cos(), 0.0) * TAU,
                DVec3::new(-small * b.sin() * a.cos(), -small * b.sin() * a.sin(), small * b.cos()) * TAU,
            )
        };
        let o = SurfaceOptions::new(10, 6).with_wrap(true, true);
        let m = mesh_surface_with_partials(torus(big, small), partials, &o).unwrap();
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let centre = DVec3::new(p.x, p.y, 0.0).normalize() * big;
            assert!(n.distance((*p - centre).normalize()) < 1e-12, "{n} at {p}");
        }
        // partials that point inward are overruled by the faces
        let inward = move |u, v| {
            let (a, b) = partials(u, v);
            (b, a)
        };
        let m = mesh_surface_with_partials(torus(big, small), inward, &o).unwrap();
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let centre = DVec3::new(p.x, p.y, 0.0).normalize() * big;
            assert!(n.dot(*p - centre) > 0.0);
        }
    }

    #[test]
    fn slice_counts() {
        let n = |t: f64| RevolveOptions::new(1.0, t).num_slices().unwrap();
        assert_eq!(n(TAU / 36.0), 36);
        assert_eq!(n(0.1), 63);
        assert_eq!(n(PI / 7.0), 14);
        assert_eq!(n(3.0), 3);
        assert_eq!(n(100.0), 3);
        assert!(matches!(RevolveOptions::new(1.0, 0.0).num_slices(), Err(SurfaceError::BadSliceTolerance { .. })));
        assert!(matches!(RevolveOptions::new(1.0, 1e-300).num_slices(), Err(SurfaceError::TooLarge { .. })));
    }

    #[test]
    fn revolve_cylinder_with_caps_counts() {
        // (0,0) → (1,0) → (1,1) → (0,1): bottom disk, side, top disk
        let profile = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let m = revolve_z(&profile, None, &RevolveOptions::new(1.0, TAU / 8.0)).unwrap();
        assert_eq!(m.num_vertices(), 2 + 2 * 8);
        assert_eq!(m.num_triangles(), 8 + 16 + 8);
        assert!(m.is_closed_oriented());
        let exact = 8.0 / 2.0 * (TAU / 8.0).sin(); // an octagonal prism of height 1
        assert!((m.signed_volume() - exact).abs() < EXACT);
        // the other way round is not inside-out
        let reversed: Vec<DVec2> = profile.iter().rev().copied().collect();
        let r = revolve_z(&reversed, None, &RevolveOptions::new(1.0, TAU / 8.0)).unwrap();
        assert!((r.signed_volume() - exact).abs() < EXACT);
        assert!(r.is_closed_oriented());
    }

    #[test]
    fn revolve_merges_repeats_and_snaps_axis() {
        let profile = [
            DVec2::new(-1e-13, -1.0),
            DVec2::new(1.0, -1.0),
            DVec2::new(1.0, -1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        let m = revolve_z(&profile, None, &RevolveOptions::new(1.0, TAU / 6.0)).unwrap();
        assert_eq!(m.num_vertices(), 2 + 2 * 6);
        assert!(m.is_closed_oriented());
        assert_eq!(m.positions[0], DVec3::new(0.0, 0.0, -1.0));
    }

    #[test]
    fn flat_disk_follows_normals() {
        let disk = [DVec2::ZERO, DVec2::X];
        let down = revolve_z(&disk, None, &RevolveOptions::new(1.0, TAU / 5.0)).unwrap();
        assert!((0..down.num_triangles()).all(|i| down.face_normal(i).z < 0.0));
        let up = revolve_z(&disk, Some(&[DVec2::Y, DVec2::Y]), &RevolveOptions::new(1.0, TAU / 5.0)).unwrap();
        assert!((0..up.num_triangles()).all(|i| up.face_normal(i).z > 0.0));
        assert!(up.normals.iter().all(|n| n.distance(DVec3::Z) < EXACT));
    }

    #[test]
    fn errors_not_panics() {
        use SurfaceError as E;
        let f = |u: f64, v: f64| DVec3::new(u, v, 0.0);
        assert_eq!(
            mesh_surface(f, &SurfaceOptions::new(0, 3)),
            Err(E::TooFewQuads { direction: 'u', needed: 1, given: 0 })
        );
        assert_eq!(
            mesh_surface(f, &SurfaceOptions::new(4, 2).with_wrap(false, true)),
            Err(E::TooFewQuads { direction: 'v', needed: 3, given: 2 })
        );
        assert!(matches!(mesh_surface(f, &SurfaceOptions::new(usize::MAX, 2)), Err(E::TooLarge { .. })));
        assert!(matches!(mesh_surface(f, &SurfaceOptions::new(70_000, 70_000)), Err(E::TooLarge { .. })));
        assert!(matches!(
            mesh_surface(f, &SurfaceOptions::new(2, 2).with_pole_tolerance(f64::NAN)),
            Err(E::BadPoleTolerance { .. })
        ));
        assert_eq!(
            mesh_surface(|u, v| DVec3::new(1.0 / (u - 0.5), v, 0.0), &SurfaceOptions::new(2, 1)),
            Err(E::NonFiniteSample { u: 0.5, v: 0.0 })
        );
        assert_eq!(mesh_surface(|_, _| DVec3::ONE, &SurfaceOptions::new(2, 2)), Err(E::Degenerate));
        assert_eq!(mesh_surface(|_, v| DVec3::Z * v, &SurfaceOptions::new(2, 2)), Err(E::Degenerate));
    }
}
