//! The options of Loop and Catmull-Clark subdivision, and of every scheme in one value
//! ([`SubdivisionOptions`]).

/// The even-vertex weights β(n).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LoopWeights {
    /// Loop's original `β(n) = (1/n)(5/8 − (3/8 + 1/4·cos(2π/n))²)` (OpenSubdiv, CGAL, PMP,
    /// trimesh). The default.
    #[default]
    Loop,
    /// Warren's `3/(8n)` for `n > 3`, `3/16` for `n = 3` (the course material, libigl, Open3D).
    Warren,
}

/// What boundary vertices do.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BoundaryRule {
    /// Every boundary vertex follows the crease rule `3/4·p + 1/8·(a + b)` (the default).
    #[default]
    Smooth,
    /// As `Smooth`, but a boundary vertex with a single face (a corner) stays fixed.
    Corners,
}

/// Options of Loop subdivision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct LoopOptions {
    /// Even-vertex weights.
    pub weights: LoopWeights,
    /// Boundary rule.
    pub boundary: BoundaryRule,
    /// Colour vertices by the level that created them ([`LEVEL_COLORS`](super::LEVEL_COLORS)), replacing any
    /// input colours.
    pub color_by_level: bool,
}

/// Options of Catmull-Clark subdivision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct CatmullClarkOptions {
    /// Boundary vertices: crease rule everywhere, or with one-face corners kept fixed.
    pub boundary: BoundaryRule,
    /// Colour the vertices by the level they were born at ([`LEVEL_COLORS`](super::LEVEL_COLORS)).
    pub color_by_level: bool,
    /// The edge points next to triangles (OpenSubdiv's `TriangleSubdivision`).
    pub triangles: TriangleSubdivision,
}

/// The edge-point rule of Catmull-Clark next to triangles (OpenSubdiv's
/// `Sdc::Options::TriangleSubdivision`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TriangleSubdivision {
    /// Catmull-Clark's edge points everywhere, `(v₀ + v₁ + f₀ + f₁)/4` (`TRI_SUB_CATMARK`, the
    /// default).
    #[default]
    Catmark,
    /// `TRI_SUB_SMOOTH`: on an interior edge with a triangle on either side, each face point
    /// weighs `w = (w₀ + w₁)/2`, with `wᵢ = 0.47` for a triangle and `1/4` for another face,
    /// and each end `(1 − 2w)/2` (`0.47` and `0.03` between two triangles), which makes the
    /// surface over triangles rounder. Only the first level has triangles, so only its edge
    /// points change.
    Smooth,
}

impl TriangleSubdivision {
    /// The weights `(end, face point)` of the smooth edge point of an interior edge between
    /// faces of `n0` and `n1` corners, where they are not Catmull-Clark's `1/4` and `1/4`.
    #[must_use]
    pub(super) fn edge_weights(self, n0: usize, n1: usize) -> Option<(f64, f64)> {
        /// OpenSubdiv's `CATMARK_SMOOTH_TRI_EDGE_WEIGHT`.
        const TRIANGLE: f64 = 0.470;
        if self == Self::Catmark || (n0 != 3 && n1 != 3) {
            return None;
        }
        let w = |n: usize| if n == 3 { TRIANGLE } else { 0.25 };
        let face = 0.5 * (w(n0) + w(n1));
        Some((0.5 * (1.0 - 2.0 * face), face))
    }
}

/// How an edge's sharpness is carried to its two halves (OpenSubdiv's `CreasingMethod`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CreasingMethod {
    /// Chaikin's rule: each half's sharpness also averages the other semi-sharp edges at its
    /// end vertex (3/4 its own, 1/4 theirs), minus 1. The default.
    #[default]
    Chaikin,
    /// Each half gets the edge's sharpness minus 1 (OpenSubdiv's default).
    Uniform,
}

/// The subdivision weights, with β tabulated for small valences.
#[derive(Clone, Debug)]
pub(super) struct Rules {
    beta: [f64; 16],
    warren: bool,
    pub(super) corners: bool,
}

impl Rules {
    pub(super) fn new(options: &LoopOptions) -> Self {
        let warren = options.weights == LoopWeights::Warren;
        let mut beta = [0.0; 16];
        for (n, b) in beta.iter_mut().enumerate().skip(1) {
            *b = Self::compute_beta(warren, n as u32);
        }
        Self { beta, warren, corners: options.boundary == BoundaryRule::Corners }
    }

    fn compute_beta(warren: bool, n: u32) -> f64 {
        let nf = f64::from(n);
        if warren {
            if n == 3 { 3.0 / 16.0 } else { 3.0 / (8.0 * nf) }
        } else {
            let c = 0.375 + 0.25 * (core::f64::consts::TAU / nf).cos();
            (0.625 - c * c) / nf
        }
    }

    #[inline]
    pub(super) fn beta(&self, n: u32) -> f64 {
        match self.beta.get(n as usize) {
            Some(&b) => b,
            None => Self::compute_beta(self.warren, n),
        }
    }
}

/// The options of every scheme in one value, for [`subdivide`](super::subdivide): each scheme
/// uses those that apply to it (see the capability methods of [`Scheme`](super::Scheme)) and
/// ignores the others. Build it from [`Self::DEFAULT`] with the `with_*` methods:
///
/// ```
/// use splinekit::subdiv::{BoundaryRule, LoopWeights, SubdivisionOptions};
/// let options = SubdivisionOptions::DEFAULT.with_weights(LoopWeights::Warren).with_boundary(BoundaryRule::Corners);
/// assert_eq!(options.weights, LoopWeights::Warren);
/// assert!(!options.color_by_level);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct SubdivisionOptions {
    /// Loop's even-vertex weights.
    pub weights: LoopWeights,
    /// What boundary vertices do (Loop and Catmull-Clark).
    pub boundary: BoundaryRule,
    /// Leave out the faces at the boundary, as holes (OpenSubdiv's `VTX_BOUNDARY_NONE`; Loop
    /// and Catmull-Clark): the faces that descend from a base face with a vertex on the
    /// boundary (see [`boundary_holes`](super::boundary_holes)) are not in the result, their
    /// vertices are.
    pub holes: bool,
    /// How a crease's sharpness passes to the halves of its edge (Loop and Catmull-Clark).
    pub creasing: CreasingMethod,
    /// Catmull-Clark's edge points next to triangles.
    pub triangles: TriangleSubdivision,
    /// Colour the vertices by the level that made them ([`LEVEL_COLORS`](super::LEVEL_COLORS)),
    /// replacing any input colours (every scheme but Doo-Sabin, which makes every vertex anew
    /// at every level).
    pub color_by_level: bool,
}

impl SubdivisionOptions {
    /// Loop's β, the smooth boundary rule, no holes, Chaikin's creasing, Catmull-Clark's edge
    /// points everywhere, the input's colours.
    pub const DEFAULT: Self = Self {
        weights: LoopWeights::Loop,
        boundary: BoundaryRule::Smooth,
        holes: false,
        creasing: CreasingMethod::Chaikin,
        triangles: TriangleSubdivision::Catmark,
        color_by_level: false,
    };

    /// With Loop's even-vertex `weights`.
    #[must_use]
    pub const fn with_weights(mut self, weights: LoopWeights) -> Self {
        self.weights = weights;
        self
    }

    /// With the `boundary` rule.
    #[must_use]
    pub const fn with_boundary(mut self, boundary: BoundaryRule) -> Self {
        self.boundary = boundary;
        self
    }

    /// With the faces at the boundary left out as holes, or not.
    #[must_use]
    pub const fn with_holes(mut self, holes: bool) -> Self {
        self.holes = holes;
        self
    }

    /// With the `creasing` method.
    #[must_use]
    pub const fn with_creasing(mut self, creasing: CreasingMethod) -> Self {
        self.creasing = creasing;
        self
    }

    /// With Catmull-Clark's edge points next to `triangles` by this rule.
    #[must_use]
    pub const fn with_triangles(mut self, triangles: TriangleSubdivision) -> Self {
        self.triangles = triangles;
        self
    }

    /// With the vertices coloured by level, or not.
    #[must_use]
    pub const fn with_color_by_level(mut self, color_by_level: bool) -> Self {
        self.color_by_level = color_by_level;
        self
    }

    /// The options of Loop subdivision among these.
    #[must_use]
    pub const fn loop_options(&self) -> LoopOptions {
        LoopOptions { weights: self.weights, boundary: self.boundary, color_by_level: self.color_by_level }
    }

    /// The options of Catmull-Clark subdivision among these.
    #[must_use]
    pub const fn catmull_clark_options(&self) -> CatmullClarkOptions {
        CatmullClarkOptions { boundary: self.boundary, color_by_level: self.color_by_level, triangles: self.triangles }
    }
}

impl Default for SubdivisionOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
