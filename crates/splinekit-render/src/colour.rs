//! What colours a surface: [`SurfaceColour`], and the colour maps behind it — the diverging
//! map of curvature pictures ([`diverging_colour`] on the scale of [`symmetric_scale`]) and
//! the UV checker ([`checker_colour`]).
//!
//! Every choice but [`SurfaceColour::Shade`] replaces the front colour of the surfaces; the
//! colour is still lit, and back faces keep the back colour. Which values a colour stands for
//! is told by a [`Legend`](crate::Legend) drawn into the picture.

use glam::{DVec2, DVec3};
use splinekit::subdiv::LEVEL_COLORS;

use crate::image::Rgb;

/// A curvature of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Curvature {
    /// Mean curvature `H` (1/length): positive where the surface bends away from its normal.
    Mean,
    /// Gaussian curvature `K` (1/length²): positive on caps, negative at saddles.
    Gaussian,
}

impl Curvature {
    /// `mean curvature` or `Gaussian curvature`, as the legend and messages write it.
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Self::Mean => "mean curvature",
            Self::Gaussian => "Gaussian curvature",
        }
    }

    /// The power of length in which this curvature is measured, negated: 1 for `H`, 2 for
    /// `K` (it scales by `1/s` or `1/s²` when the surface is scaled by `s`).
    #[must_use]
    pub fn inverse_length_power(self) -> i32 {
        match self {
            Self::Mean => 1,
            Self::Gaussian => 2,
        }
    }
}

/// What colours the front of surfaces in a 3D picture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SurfaceColour {
    /// The front colour, or the mesh's own vertex colours when it has them (the default).
    #[default]
    Shade,
    /// The curvature at the vertices ([`splinekit::mesh::vertex_curvature`]) on the diverging
    /// map ([`diverging_colour`]), blue for negative, light grey for zero, crimson for
    /// positive, on a scale symmetric about zero shared by every surface of the picture
    /// ([`symmetric_scale`] with [`SCALE_PERCENTILE`]); interpolated across the triangles.
    Curvature(Curvature),
    /// A checkerboard of the texture coordinates ([`checker_colour`]), per pixel with
    /// perspective-correct UVs and one shading per sample. A surface without UVs keeps the
    /// front colour.
    UvChecker,
    /// The colours a subdivision gave its vertices by level (the schemes' `color_by_level`,
    /// [`LEVEL_COLORS`]), for a mesh subdivided `levels` times; with `levels: 0`, or on a mesh
    /// without vertex colours, everything is level 0. The legend lists levels 0 to `levels`.
    Level {
        /// Subdivision levels applied (the legend shows `0..=levels`).
        levels: u32,
    },
}

impl SurfaceColour {
    /// The name used on the command line: `shade`, `curvature-mean`, `curvature-gauss`,
    /// `uv-checker` or `level`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Shade => "shade",
            Self::Curvature(Curvature::Mean) => "curvature-mean",
            Self::Curvature(Curvature::Gaussian) => "curvature-gauss",
            Self::UvChecker => "uv-checker",
            Self::Level { .. } => "level",
        }
    }
}

/// The stops of [`diverging_colour`] at `t = −1, −½, 0, ½, 1` (sRGB): blue, light blue, light
/// grey, pink, crimson. The positive end leans to magenta, away from the orange-red of back
/// faces ([`BACK_COLOUR`](crate::BACK_COLOUR)).
pub const DIVERGING_STOPS: [Rgb; 5] = [[45, 95, 215], [125, 165, 235], [225, 225, 225], [240, 150, 175], [200, 25, 95]];

/// The percentile of `|value|` that [`SurfaceColour::Curvature`] takes as its scale `m`:
/// values beyond `±m` (the sharpest 5 %: a rim, a crease, the tips of a mesh's noise) show
/// the end colours, and the rest keep a readable spread. (On the course's wine glass the
/// largest |H| is over 100 times the 95th percentile; a scale up to it would leave the whole
/// glass grey.)
pub const SCALE_PERCENTILE: f64 = 95.0;

/// The least scale of a curvature picture, relative to the scene: `1e-6/ρ` for mean and
/// `1e-6/ρ²` for Gaussian curvature, `ρ` the radius of the scene's bounding box. Curvatures
/// within rounding of zero (a plane) then show as zero instead of being stretched to the
/// end colours.
pub const MIN_RELATIVE_SCALE: f64 = 1e-6;

/// Squares of [`checker_colour`] per unit of `u` and of `v`. Sweeps normalize both to
/// `[0, 1]` by arc length, so a swept surface shows 8 squares around and 8 along its profile.
pub const CHECKER_SQUARES: f64 = 8.0;

/// The two colours of the UV checker (sRGB): light grey and steel blue.
pub const CHECKER_COLOURS: [Rgb; 2] = [[225, 225, 225], [70, 105, 165]];

/// The diverging colour map of curvature pictures: `t ∈ [−1, 1]` (clamped; NaN is 0) to sRGB,
/// piecewise linear through [`DIVERGING_STOPS`]: blue at `−1`, light grey at `0`, crimson at
/// `+1`. Symmetric in lightness about 0, readable on the dark background of 3D pictures.
#[must_use]
pub fn diverging_colour(t: f64) -> Rgb {
    let t = if t.is_nan() { 0.0 } else { t.clamp(-1.0, 1.0) };
    let x = (t + 1.0) * 2.0; // 0..=4
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let (a, b) = (DIVERGING_STOPS[i], DIVERGING_STOPS[i + 1]);
    std::array::from_fn(|k| (f64::from(a[k]) + f * (f64::from(b[k]) - f64::from(a[k]))).round() as u8)
}

/// The half-width `m` of a scale `[−m, m]` symmetric about zero for `values`: the
/// `percentile`-th percentile (nearest rank, `0..=100`; 100 is the largest) of their
/// absolute values, ignoring NaN and infinities, and at least `floor` (0 when there is no
/// value and `floor` is not positive).
#[must_use]
pub fn symmetric_scale(values: impl IntoIterator<Item = f64>, percentile: f64, floor: f64) -> f64 {
    let mut abs: Vec<f64> = values.into_iter().filter(|v| v.is_finite()).map(f64::abs).collect();
    let floor = if floor.is_finite() { floor.max(0.0) } else { 0.0 };
    if abs.is_empty() {
        return floor;
    }
    let p = if percentile.is_nan() { 100.0 } else { percentile.clamp(0.0, 100.0) };
    // Nearest rank: the smallest value with at least p % of the values at or below it.
    let rank = ((p / 100.0 * abs.len() as f64).ceil() as usize).clamp(1, abs.len());
    let (_, m, _) = abs.select_nth_unstable_by(rank - 1, f64::total_cmp);
    m.max(floor)
}

/// The colour of the UV checker at `uv`: [`CHECKER_COLOURS`]`[0]` where
/// `⌊8u⌋ + ⌊8v⌋` is even, `[1]` where it is odd ([`CHECKER_SQUARES`] per unit).
#[must_use]
pub fn checker_colour(uv: DVec2) -> Rgb {
    CHECKER_COLOURS[checker_parity(uv.x, uv.y)]
}

/// 0 or 1: the parity of `⌊8u⌋ + ⌊8v⌋` (0 for NaN).
#[inline]
pub(crate) fn checker_parity<F: Into<f64>>(u: F, v: F) -> usize {
    let (u, v) = (u.into() * CHECKER_SQUARES, v.into() * CHECKER_SQUARES);
    let cell = |x: f64| if x.is_finite() { x.floor().rem_euclid(2.0) as usize } else { 0 };
    (cell(u) + cell(v)) % 2
}

/// The colour of subdivision level `level` ([`LEVEL_COLORS`], repeating every 8 levels) in
/// sRGB.
#[must_use]
pub fn level_colour(level: u32) -> Rgb {
    to_rgb(LEVEL_COLORS[level as usize % LEVEL_COLORS.len()])
}

/// An 8-bit colour as `[0, 1]` floats (vertex colours of a [`TriMesh`](splinekit::TriMesh)).
#[must_use]
pub fn to_unit(c: Rgb) -> DVec3 {
    DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2])) / 255.0
}

/// A `[0, 1]` colour as 8 bits (clamped, rounded; NaN is 0).
#[must_use]
pub fn to_rgb(c: DVec3) -> Rgb {
    c.to_array().map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BACK_COLOUR;

    #[test]
    fn diverging_map_ends_and_middle() {
        assert_eq!(diverging_colour(-1.0), DIVERGING_STOPS[0]);
        assert_eq!(diverging_colour(-7.0), DIVERGING_STOPS[0]);
        assert_eq!(diverging_colour(0.0), DIVERGING_STOPS[2]);
        assert_eq!(diverging_colour(f64::NAN), DIVERGING_STOPS[2]);
        assert_eq!(diverging_colour(1.0), DIVERGING_STOPS[4]);
        assert_eq!(diverging_colour(0.25), [233, 188, 200]);
        // Negative is blue, positive red.
        for t in [0.3, 0.6, 1.0] {
            let (n, p) = (diverging_colour(-t), diverging_colour(t));
            assert!(n[2] > n[0] && p[0] > p[2], "{t}: {n:?} {p:?}");
        }
    }

    #[test]
    fn no_colour_looks_like_a_back_face() {
        let far = |c: Rgb| (0..3).map(|k| c[k].abs_diff(BACK_COLOUR[k])).max().unwrap();
        for i in 0..=100 {
            let c = diverging_colour(f64::from(i) / 50.0 - 1.0);
            assert!(far(c) >= 45, "{c:?}");
        }
        for level in 0..8 {
            assert!(far(level_colour(level)) >= 75, "level {level}: {:?}", level_colour(level));
        }
    }

    #[test]
    fn scales_by_percentile() {
        let values: Vec<f64> = (1..=200).map(|i| if i % 2 == 0 { f64::from(i) } else { -f64::from(i) }).collect();
        assert_eq!(symmetric_scale(values.iter().copied(), 100.0, 0.0), 200.0);
        assert_eq!(symmetric_scale(values.iter().copied(), 99.0, 0.0), 198.0);
        assert_eq!(symmetric_scale(values.iter().copied(), 50.0, 0.0), 100.0);
        assert_eq!(symmetric_scale([f64::NAN, f64::INFINITY, -3.0], 99.0, 0.0), 3.0);
        assert_eq!(symmetric_scale([1e-17, -2e-17], 99.0, 1e-6), 1e-6);
        assert_eq!(symmetric_scale([], 99.0, f64::INFINITY), 0.0);
    }

    #[test]
    fn checker_squares() {
        let c = |u: f64, v: f64| checker_parity(u, v);
        assert_eq!((c(0.01, 0.01), c(0.13, 0.01), c(0.13, 0.13), c(-0.01, 0.01)), (0, 1, 0, 1));
        assert_eq!(c(f64::NAN, 0.0), 0);
        assert_eq!(checker_colour(DVec2::new(0.2, 0.0)), CHECKER_COLOURS[1]);
    }
}
