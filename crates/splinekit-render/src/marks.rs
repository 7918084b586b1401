//! Curves as drawing marks: [`PlotCurve`] and [`curve_marks`].
//!
//! A [`Mark`] is a line, dot or arrow placed in world space with its size in pixels. The 3D
//! renderer draws marks into its depth buffer (so a surface hides them), the 2D plot projects
//! them and draws them with tiny-skia or as SVG: both pictures of a curve come from the same
//! list.

use glam::DVec3;
use splinekit::flatten::{Tessellation, flatten_at_most, flatten_count};
use splinekit::frame::{self, FrameOptions};
use splinekit::{Aabb, AnyCurve, ArclenIndex, ParamCurve};
use splinekit_io::SwpCurve;

use crate::{ImageSize, Rgb};

/// Colours of consecutive curve segments (as the editor's 2D view).
pub const SEGMENT_COLOURS: [Rgb; 6] =
    [[230, 90, 60], [60, 170, 90], [70, 120, 230], [210, 160, 40], [170, 80, 200], [40, 180, 190]];

/// Frame arrows: tangent, normal, binormal (blue, red, green, as the editor).
pub const FRAME_COLOURS: [Rgb; 3] = [[40, 80, 230], [220, 40, 40], [30, 160, 60]];

/// Frames drawn per curve segment with `frames`.
pub const FRAMES_PER_SEGMENT: usize = 8;

/// Length of a frame arrow, as a fraction of the scene's radius.
pub const FRAME_LENGTH: f64 = 0.12;

/// Most markers drawn on one curve (the spacing is raised to stay below).
pub const MAX_MARKERS: usize = 5000;

/// Accuracy of the arc lengths that place markers, relative to the size of the curve's
/// bounding box: a millionth of it is far below a pixel of any picture (and a curve of wild control points, such as a Bézier
/// of degree 20 hundreds of units wide, places its 5000 markers in a fraction of the time a
/// billionth takes).
const MARKER_ACCURACY: f64 = 1e-6;

/// Curve tessellation tolerance, as a fraction of the scene's radius ...
const CURVE_TOLERANCE: f64 = 1e-4;
/// ... or, in 2D plots, in pixels, whichever is coarser: a picture framing the scene's
/// diameter in its smaller side draws curves no closer than this to the pixel (a small picture
/// of a fine curve, such as a helix of 10 000 turns at 64×48, needs far fewer points than a
/// large one). Not in 3D pictures, where a curve on a surface must not sink into it.
const PIXEL_TOLERANCE: f64 = 0.1;

/// A curve to draw, with its control polygon.
#[derive(Clone, Debug)]
pub struct PlotCurve {
    /// A name for messages.
    pub name: String,
    /// The curve.
    pub curve: AnyCurve<DVec3>,
    /// Its control points (empty for circles, helices and knots).
    pub control_points: Vec<DVec3>,
    /// Whether the control polygon closes.
    pub closed: bool,
}

impl PlotCurve {
    /// Curve `index` of an SWP file.
    ///
    /// # Errors
    /// The curve's [`SplineError`](splinekit::SplineError) when it does not compile.
    pub fn from_swp(curve: &SwpCurve, index: usize) -> Result<Self, splinekit::SplineError> {
        let control_points = curve.geometry.points().to_vec();
        Ok(Self { name: curve.display_name(index), curve: curve.to_curve()?, control_points, closed: curve.closed })
    }

    /// Points for framing: the control points, samples of the curve and the corners of its box.
    pub(crate) fn bound_points(&self) -> impl Iterator<Item = DVec3> + Clone + '_ {
        let m = self.curve.num_segments().max(1);
        let n = 16 * m;
        let (a, b) = self.curve.domain();
        // The tight box's corners hold the whole curve, where samples may all fall on the same
        // points (17 samples of a helix of 10 000 turns are 17 times its start).
        let Aabb { min, max } = self.curve.bounding_box();
        let corners = (0..8).map(move |k| {
            let pick = |bit: usize, lo: f64, hi: f64| if k & bit == 0 { lo } else { hi };
            DVec3::new(pick(1, min.x, max.x), pick(2, min.y, max.y), pick(4, min.z, max.z))
        });
        self.control_points
            .iter()
            .copied()
            .chain((0..=n).map(move |i| self.curve.eval(a + (b - a) * i as f64 / n as f64)))
            .chain(corners)
    }
}

/// What to draw with each curve.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct CurveOptions {
    /// The control polygon (dashed) and control points.
    pub polygon: bool,
    /// Frames (T, N, B arrows), [`FRAMES_PER_SEGMENT`] per segment.
    pub frames: bool,
    /// Dots every this much arc length, from the start.
    pub marker_spacing: Option<f64>,
}

impl CurveOptions {
    /// Control polygons, no frames, no markers.
    pub const DEFAULT: Self = Self { polygon: true, frames: false, marker_spacing: None };

    /// With or without the control polygon.
    #[must_use]
    pub fn with_polygon(mut self, polygon: bool) -> Self {
        self.polygon = polygon;
        self
    }

    /// With or without frames.
    #[must_use]
    pub fn with_frames(mut self, frames: bool) -> Self {
        self.frames = frames;
        self
    }

    /// With markers every `spacing` of arc length (`None`: no markers).
    #[must_use]
    pub fn with_marker_spacing(mut self, spacing: Option<f64>) -> Self {
        self.marker_spacing = spacing;
        self
    }
}

impl Default for CurveOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Light marks on a dark background, or dark ones on a light background.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Theme {
    /// For a light background (the 2D plot).
    #[default]
    Light,
    /// For a dark background (the 3D picture).
    Dark,
}

impl Theme {
    fn polygon(self) -> Rgb {
        match self {
            Self::Light => [140, 140, 140],
            Self::Dark => [175, 178, 186],
        }
    }
    fn point(self) -> (Rgb, Rgb) {
        match self {
            Self::Light => ([255, 255, 255], [60, 60, 60]),
            Self::Dark => ([250, 226, 120], [20, 20, 24]),
        }
    }
    fn marker(self) -> (Rgb, Rgb) {
        match self {
            Self::Light => ([20, 20, 20], [255, 255, 255]),
            Self::Dark => ([255, 255, 255], [20, 20, 24]),
        }
    }
}

/// One drawing mark in world space; sizes are in pixels of the picture.
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// A polyline.
    Line {
        /// Its vertices.
        points: Vec<DVec3>,
        /// Colour.
        colour: Rgb,
        /// Width in pixels.
        width: f64,
        /// Dash and gap lengths in pixels, or `None` for a solid line.
        dash: Option<[f64; 2]>,
    },
    /// A filled disc, facing the viewer.
    Dot {
        /// Centre.
        at: DVec3,
        /// Radius in pixels.
        radius: f64,
        /// Fill colour.
        fill: Rgb,
        /// Colour of a one-pixel ring around it.
        outline: Option<Rgb>,
    },
    /// An arrow from `from` to `to`, its head drawn at `to`.
    Arrow {
        /// Tail.
        from: DVec3,
        /// Tip.
        to: DVec3,
        /// Colour.
        colour: Rgb,
        /// Width in pixels.
        width: f64,
    },
}

impl Mark {
    /// The world points of the mark.
    pub fn points(&self) -> impl Iterator<Item = DVec3> + Clone + '_ {
        let (slice, pair): (&[DVec3], [Option<DVec3>; 2]) = match self {
            Self::Line { points, .. } => (points, [None, None]),
            Self::Dot { at, .. } => (&[], [Some(*at), None]),
            Self::Arrow { from, to, .. } => (&[], [Some(*from), Some(*to)]),
        };
        slice.iter().copied().chain(pair.into_iter().flatten())
    }
}

/// Width of curves in pixels.
pub const CURVE_WIDTH: f64 = 2.5;
/// Radius of control points in pixels.
pub const POINT_RADIUS: f64 = 3.5;
/// Radius of arc-length markers in pixels.
pub const MARKER_RADIUS: f64 = 2.5;

/// The marks that draw `curves`: per curve its control polygon (dashed), the curve coloured by
/// segment ([`SEGMENT_COLOURS`]), frames, markers and control points, in that order.
/// `radius` is the scene's size (frame arrows are [`FRAME_LENGTH`] of it, and curves are
/// tessellated to 1e-4 of it). With `plot`, the size of a 2D plot framing the scene, curves
/// are tessellated to a tenth of its pixel where that is coarser.
#[must_use]
pub fn curve_marks(
    curves: &[PlotCurve],
    options: &CurveOptions,
    theme: Theme,
    radius: f64,
    plot: Option<ImageSize>,
) -> Vec<Mark> {
    let radius = if radius.is_finite() && radius > 0.0 { radius } else { 1.0 };
    let pixel = plot.map_or(0.0, |size| 2.0 * radius / f64::from(size.width.min(size.height).max(1)));
    let tolerance = (CURVE_TOLERANCE * radius).max(PIXEL_TOLERANCE * pixel);
    let mode = Tessellation::Distance { tolerance };
    // curves that need more points than the picture's budget share it by their need
    let budget = if plot.is_some() { MAX_DRAWN_POINTS } else { MAX_DRAWN_POINTS_3D };
    let needs: Vec<u64> = curves.iter().map(|c| flatten_count(&c.curve, mode)).collect();
    let total = needs.iter().fold(0u64, |sum, &n| sum.saturating_add(n));
    let mut marks = Vec::new();
    for (c, &need) in curves.iter().zip(&needs) {
        let share = if total <= budget as u64 { need } else { (need as f64 / total as f64 * budget as f64) as u64 };
        let at_most = usize::try_from(share).unwrap_or(usize::MAX).max(c.curve.num_segments() + 1);
        let polygon = options.polygon && c.control_points.len() > 1;
        if polygon {
            let mut points = c.control_points.clone();
            if c.closed {
                points.push(points[0]);
            }
            marks.push(Mark::Line { points, colour: theme.polygon(), width: 1.0, dash: Some([6.0, 4.0]) });
        }
        marks.extend(segment_lines(&c.curve, mode, at_most));
        if options.frames {
            frame_arrows(&c.curve, FRAME_LENGTH * radius, &mut marks);
        }
        if let Some(spacing) = options.marker_spacing {
            let (fill, outline) = theme.marker();
            for at in markers(&c.curve, spacing) {
                marks.push(Mark::Dot { at, radius: MARKER_RADIUS, fill, outline: Some(outline) });
            }
        }
        if polygon || (options.polygon && c.control_points.len() == 1) {
            let (fill, outline) = theme.point();
            for &at in &c.control_points {
                marks.push(Mark::Dot { at, radius: POINT_RADIUS, fill, outline: Some(outline) });
            }
        }
    }
    marks
}

/// The most points the curves of a 2D plot are drawn with, all together (curves finer than
/// that, such as a helix of thousands of turns, are drawn with equal steps instead of to the
/// picture's tolerance, each with a share of the points in proportion to its need).
pub const MAX_DRAWN_POINTS: usize = 1_000_000;

/// The same for a 3D picture, whose marks take about 350 bytes a point (about 90 MB).
pub const MAX_DRAWN_POINTS_3D: usize = 250_000;

/// One polyline per segment, in that segment's colour: `mode`'s points, or `at_most` equal steps.
fn segment_lines(c: &AnyCurve<DVec3>, mode: Tessellation, at_most: usize) -> Vec<Mark> {
    let params = flatten_at_most(c, mode, at_most);
    let segments = c.num_segments().max(1);
    let mut lines = Vec::new();
    let mut start = 0;
    while start + 1 < params.len() {
        let seg = (params[start].max(0.0) as usize).min(segments - 1);
        let mut end = start + 1;
        while end + 1 < params.len() && params[end] < (seg + 1) as f64 {
            end += 1;
        }
        let points = params[start..=end].iter().map(|&u| c.eval(u)).collect();
        lines.push(Mark::Line {
            points,
            colour: SEGMENT_COLOURS[seg % SEGMENT_COLOURS.len()],
            width: CURVE_WIDTH,
            dash: None,
        });
        start = end;
    }
    lines
}

/// T, N, B arrows of `length` at [`FRAMES_PER_SEGMENT`] parameters per segment.
fn frame_arrows(c: &AnyCurve<DVec3>, length: f64, marks: &mut Vec<Mark>) {
    let segments = c.num_segments().max(1);
    let n = segments * FRAMES_PER_SEGMENT;
    let (a, b) = c.domain();
    let us: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
    let frames = frame::frames(c, &us, &FrameOptions::default());
    for (&u, f) in us.iter().zip(&frames) {
        let p = c.eval(u);
        for (v, colour) in [f.t, f.n, f.b].into_iter().zip(FRAME_COLOURS) {
            if v.is_finite() && v.length_squared() > 0.0 {
                marks.push(Mark::Arrow { from: p, to: p + v * length, colour, width: 1.5 });
            }
        }
    }
}

/// Points every `spacing` of arc length from the start (the spacing raised so that there are
/// at most [`MAX_MARKERS`]).
fn markers(c: &AnyCurve<DVec3>, spacing: f64) -> Vec<DVec3> {
    let b = c.bounding_box();
    let size = (b.max - b.min).length();
    let accuracy = if size > 0.0 && size.is_finite() { MARKER_ACCURACY * size } else { MARKER_ACCURACY };
    let index = ArclenIndex::new(c, accuracy);
    let length = index.length();
    if !(length > 0.0) || !length.is_finite() {
        return vec![c.eval(c.domain().0)];
    }
    let spacing = spacing.max(length / (MAX_MARKERS - 1) as f64);
    let count = (length / spacing * (1.0 + 1e-12)).floor() as usize;
    (0..=count).map(|k| c.eval(index.u_at(c, (k as f64 * spacing).min(length)))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use splinekit_io::SwpDocument;

    #[test]
    fn marks_of_a_bezier() {
        let doc = SwpDocument::parse("bez2 c 20 4 [0 0] [1 1] [2 1] [3 0]", "t.swp").unwrap();
        let c = PlotCurve::from_swp(&doc.curves[0], 0).unwrap();
        let marks = curve_marks(
            std::slice::from_ref(&c),
            &CurveOptions::DEFAULT.with_frames(true).with_marker_spacing(Some(0.5)),
            Theme::Light,
            1.5,
            None,
        );
        let lines = marks.iter().filter(|m| matches!(m, Mark::Line { dash: None, .. })).count();
        let dashed = marks.iter().filter(|m| matches!(m, Mark::Line { dash: Some(_), .. })).count();
        let arrows = marks.iter().filter(|m| matches!(m, Mark::Arrow { .. })).count();
        let dots = marks.iter().filter(|m| matches!(m, Mark::Dot { .. })).count();
        assert_eq!((lines, dashed), (1, 1));
        assert_eq!(arrows, 3 * (FRAMES_PER_SEGMENT + 1));
        // Markers at 0, 0.5, … up to the length, plus 4 control points.
        let length = ArclenIndex::new(&c.curve, 1e-9).length();
        assert_eq!(dots, (length / 0.5).floor() as usize + 1 + 4, "length {length}");
    }

    #[test]
    fn circles_have_no_polygon() {
        let doc = SwpDocument::parse("circ c 20 1", "t.swp").unwrap();
        let c = PlotCurve::from_swp(&doc.curves[0], 0).unwrap();
        let marks = curve_marks(&[c], &CurveOptions::DEFAULT, Theme::Dark, 1.0, None);
        assert!(marks.iter().all(|m| matches!(m, Mark::Line { dash: None, .. })));
    }
}
