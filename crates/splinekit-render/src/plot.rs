//! The 2D curve plot: [`plot_curves`] (tiny-skia, anti-aliased) and [`plot_curves_svg`].
//!
//! Curves are projected orthographically in a [`View`] (`front` is the xy-plane of 2D SWP
//! curves) and framed to fill the picture less a margin. On a light background: the world
//! axes through the origin in light grey, then per curve its dashed control polygon, the
//! curve coloured by segment, frames, arc-length markers and control points
//! ([`curve_marks`]). The PNG and the SVG draw the same marks at the same pixel positions.

use std::fmt::Write as _;

use glam::DVec3;
use tiny_skia::{FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Stroke, StrokeDash, Transform};

use crate::camera::{Camera, DEFAULT_MARGIN, Projection, View, bounding_radius};
use crate::image::{Image, ImageSize, Rgb};
use crate::marks::{CurveOptions, Mark, PlotCurve, Theme, curve_marks};
use crate::raster::{ARROW_HEAD_PX, arrow_head};

/// The background of 2D plots (as the editor's 2D view).
pub const PLOT_BACKGROUND: Rgb = [250, 250, 250];
/// The world axes in 2D plots.
pub const AXIS_COLOUR: Rgb = [205, 205, 205];

/// How to draw a 2D plot.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PlotOptions {
    /// Picture size.
    pub size: ImageSize,
    /// Direction to look from (orthographic).
    pub view: View,
    /// Free border, as a fraction of the smaller side.
    pub margin: f64,
    /// Background.
    pub background: Rgb,
    /// Draw the world axes through the origin.
    pub axes: bool,
}

impl PlotOptions {
    /// 800×600, front view (the xy-plane), axes on.
    pub const DEFAULT: Self = Self {
        size: ImageSize::DEFAULT,
        view: View::Front,
        margin: DEFAULT_MARGIN,
        background: PLOT_BACKGROUND,
        axes: true,
    };

    /// With this size.
    #[must_use]
    pub fn with_size(mut self, size: ImageSize) -> Self {
        self.size = size;
        self
    }

    /// With this view.
    #[must_use]
    pub fn with_view(mut self, view: View) -> Self {
        self.view = view;
        self
    }

    /// With or without axes.
    #[must_use]
    pub fn with_axes(mut self, axes: bool) -> Self {
        self.axes = axes;
        self
    }
}

impl Default for PlotOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The camera and marks of a plot.
fn plan(curves: &[PlotCurve], curve_options: &CurveOptions, options: &PlotOptions) -> (Camera, Vec<Mark>) {
    let points = curves.iter().flat_map(PlotCurve::bound_points);
    let camera = Camera::fit(options.view, Projection::Orthographic, points.clone(), options.size, options.margin);
    let radius = bounding_radius(points);
    let mut marks = Vec::new();
    if options.axes {
        // Long enough to cross the picture wherever the origin is.
        let reach =
            4.0 * (f64::from(options.size.width) + f64::from(options.size.height)) / camera.scale + camera.eye.length();
        for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
            marks.push(Mark::Line {
                points: vec![-axis * reach, axis * reach],
                colour: AXIS_COLOUR,
                width: 1.0,
                dash: None,
            });
        }
    }
    marks.extend(curve_marks(curves, curve_options, Theme::Light, radius, Some(options.size)));
    (camera, marks)
}

/// A mark projected to pixels.
enum Flat {
    Line { points: Vec<[f64; 2]>, colour: Rgb, width: f64, dash: Option<[f64; 2]> },
    Dot { at: [f64; 2], radius: f64, fill: Rgb, outline: Option<Rgb> },
}

/// Projects marks to pixel coordinates; arrows become a shaft and a head. Zero-length
/// arrows (a binormal seen end on) are left out.
fn flatten_marks(camera: &Camera, marks: &[Mark]) -> Vec<Flat> {
    let px = |p: DVec3| {
        let q = camera.project(p);
        [q.x, q.y]
    };
    let mut out = Vec::with_capacity(marks.len());
    for mark in marks {
        match mark {
            Mark::Line { points, colour, width, dash } => out.push(Flat::Line {
                points: points.iter().map(|&p| px(p)).collect(),
                colour: *colour,
                width: *width,
                dash: *dash,
            }),
            Mark::Dot { at, radius, fill, outline } => {
                out.push(Flat::Dot { at: px(*at), radius: *radius, fill: *fill, outline: *outline });
            }
            Mark::Arrow { from, to, colour, width } => {
                let (a, b) = (px(*from), px(*to));
                let wings = arrow_head(a, b, ARROW_HEAD_PX);
                if wings.len() == 2 {
                    out.push(Flat::Line { points: vec![a, b], colour: *colour, width: *width, dash: None });
                    out.push(Flat::Line {
                        points: vec![wings[0], b, wings[1]],
                        colour: *colour,
                        width: *width,
                        dash: None,
                    });
                }
            }
        }
    }
    out
}

/// Draws `curves` as a 2D plot. See the [module docs](self).
#[must_use]
pub fn plot_curves(curves: &[PlotCurve], curve_options: &CurveOptions, options: &PlotOptions) -> Image {
    let (camera, marks) = plan(curves, curve_options, options);
    draw_marks(&camera, &marks, options)
}

/// The most segments stroked as one path (see [`draw_marks`]).
const STROKE_PIECE: usize = 256;

/// The part of the segment `a`–`b` inside the box `lo`–`hi` (Liang–Barsky), or `None`.
#[must_use]
pub fn clip_segment(a: [f64; 2], b: [f64; 2], lo: [f64; 2], hi: [f64; 2]) -> Option<([f64; 2], [f64; 2])> {
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for k in 0..2 {
        let d = b[k] - a[k];
        for (p, q) in [(-d, a[k] - lo[k]), (d, hi[k] - a[k])] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else if p < 0.0 {
                t0 = t0.max(q / p);
            } else {
                t1 = t1.min(q / p);
            }
        }
    }
    let at = |t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
    (t0 <= t1).then(|| (if t0 == 0.0 { a } else { at(t0) }, if t1 == 1.0 { b } else { at(t1) }))
}

/// The picture `width`×`height` with a margin for a stroke of `stroke` pixels: what of a line
/// can show.
fn stroke_box(stroke: f64, width: u32, height: u32) -> ([f64; 2], [f64; 2]) {
    let margin = stroke + 2.0;
    ([-margin; 2], [f64::from(width) + margin, f64::from(height) + margin])
}

/// The finite points of the polyline `points` clipped to the box `lo`–`hi` a segment at a time
/// ([`clip_segment`]): the runs that stay connected inside it, each with the polyline's length
/// before its first point (the phase of a dash pattern there).
fn clipped_runs(points: &[[f64; 2]], (lo, hi): ([f64; 2], [f64; 2])) -> Vec<(Vec<[f64; 2]>, f64)> {
    let mut runs: Vec<(Vec<[f64; 2]>, f64)> = Vec::new();
    let mut travelled = 0.0;
    let finite = points.iter().filter(|p| p[0].is_finite() && p[1].is_finite());
    for (a, b) in finite.clone().zip(finite.skip(1)) {
        if let Some((p, q)) = clip_segment(*a, *b, lo, hi) {
            match runs.last_mut() {
                Some((run, _)) if run.last() == Some(&p) => run.push(q),
                _ => runs.push((vec![p, q], travelled + (p[0] - a[0]).hypot(p[1] - a[1]))),
            }
        }
        travelled += (b[0] - a[0]).hypot(b[1] - a[1]);
    }
    runs
}

/// Draws `marks` seen by `camera` with tiny-skia (anti-aliased).
#[must_use]
pub fn draw_marks(camera: &Camera, marks: &[Mark], options: &PlotOptions) -> Image {
    let size = options.size;
    let Some(mut pixmap) = Pixmap::new(size.width, size.height) else {
        return Image::filled(size, options.background);
    };
    let [r, g, b] = options.background;
    pixmap.fill(tiny_skia::Color::from_rgba8(r, g, b, 255));
    let paint = |c: Rgb| {
        let mut p = Paint::default();
        p.set_color_rgba8(c[0], c[1], c[2], 255);
        p.anti_alias = true;
        p
    };
    for flat in flatten_marks(camera, marks) {
        match flat {
            Flat::Line { points, colour, width, dash } => {
                let stroke = |travelled: f64| Stroke {
                    width: width as f32,
                    line_cap: if dash.is_some() { LineCap::Butt } else { LineCap::Round },
                    line_join: LineJoin::Round,
                    dash: dash.and_then(|[on, off]| {
                        StrokeDash::new(vec![on as f32, off as f32], (travelled % (on + off)) as f32)
                    }),
                    ..Stroke::default()
                };
                // Handed to tiny-skia clipped to the picture (with a margin for the stroke's
                // width) and a piece at a time: its scan converter fails an assertion, and the
                // process aborts, on coordinates far outside the picture or on one path of a
                // great many edges piled on the same pixels (a helix of 10 000 turns).
                let (mut piece, mut edges, mut phase) = (PathBuilder::new(), 0, 0.0);
                for (run, mut along) in clipped_runs(&points, stroke_box(width, size.width, size.height)) {
                    let mut open = false;
                    for w in run.windows(2) {
                        if edges == 0 {
                            phase = along;
                        }
                        if !open {
                            piece.move_to(w[0][0] as f32, w[0][1] as f32);
                            open = true;
                        }
                        piece.line_to(w[1][0] as f32, w[1][1] as f32);
                        edges += 1;
                        along += (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
                        if edges >= STROKE_PIECE {
                            if let Some(path) = std::mem::take(&mut piece).finish() {
                                pixmap.stroke_path(&path, &paint(colour), &stroke(phase), Transform::identity(), None);
                            }
                            (edges, open) = (0, false);
                        }
                    }
                }
                if let Some(path) = piece.finish() {
                    pixmap.stroke_path(&path, &paint(colour), &stroke(phase), Transform::identity(), None);
                }
            }
            Flat::Dot { at, radius, fill, outline } => {
                let circle = |r: f64| PathBuilder::from_circle(at[0] as f32, at[1] as f32, r as f32);
                if let Some(o) = outline
                    && let Some(path) = circle(radius + 1.0)
                {
                    pixmap.fill_path(&path, &paint(o), FillRule::Winding, Transform::identity(), None);
                }
                if let Some(path) = circle(radius) {
                    pixmap.fill_path(&path, &paint(fill), FillRule::Winding, Transform::identity(), None);
                }
            }
        }
    }
    Image::from_pixmap(&pixmap)
}

/// Draws `curves` as a 2D plot in SVG: the same marks as [`plot_curves`], in pixel
/// coordinates of a picture of the same size.
#[must_use]
pub fn plot_curves_svg(curves: &[PlotCurve], curve_options: &CurveOptions, options: &PlotOptions) -> String {
    let (camera, marks) = plan(curves, curve_options, options);
    marks_svg(&camera, &marks, options)
}

/// `marks` seen by `camera` as an SVG document.
#[must_use]
pub fn marks_svg(camera: &Camera, marks: &[Mark], options: &PlotOptions) -> String {
    let (w, h) = (options.size.width, options.size.height);
    let hex = |c: Rgb| format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
    let num = |x: f64| {
        let s = format!("{:.2}", x);
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" { "0".to_string() } else { s.to_string() }
    };
    let mut out = String::new();
    let _ = writeln!(out, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(out, r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#);
    let _ = writeln!(out, r#"<rect width="{w}" height="{h}" fill="{}"/>"#, hex(options.background));
    for flat in flatten_marks(camera, marks) {
        match flat {
            Flat::Line { points, colour, width, dash } => {
                // clipped to the picture, as in the PNG: an axis of a scene of size 1e-300
                // reaches 1e300 pixels, numbers of 300 digits
                let runs = clipped_runs(&points, stroke_box(width, w, h));
                for (run, start) in runs {
                    let pts: Vec<String> = run.iter().map(|p| format!("{},{}", num(p[0]), num(p[1]))).collect();
                    let dash = dash.map_or(String::new(), |[on, off]| {
                        let offset = start % (on + off);
                        let offset = if offset > 0.0 {
                            format!(r#" stroke-dashoffset="{}""#, num(offset))
                        } else {
                            String::new()
                        };
                        format!(r#" stroke-dasharray="{} {}"{offset}"#, num(on), num(off))
                    });
                    let cap = if dash.is_empty() { "round" } else { "butt" };
                    let _ = writeln!(
                        out,
                        r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="{cap}" stroke-linejoin="round"{dash}/>"#,
                        pts.join(" "),
                        hex(colour),
                        num(width)
                    );
                }
            }
            Flat::Dot { at, radius, fill, outline } => {
                if !(at[0].is_finite() && at[1].is_finite()) {
                    continue;
                }
                let stroke = outline.map_or(String::new(), |o| format!(r#" stroke="{}" stroke-width="1""#, hex(o)));
                let r = if outline.is_some() { radius + 0.5 } else { radius };
                let _ = writeln!(
                    out,
                    r#"<circle cx="{}" cy="{}" r="{}" fill="{}"{stroke}/>"#,
                    num(at[0]),
                    num(at[1]),
                    num(r),
                    hex(fill)
                );
            }
        }
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use splinekit_io::SwpDocument;

    fn curves(text: &str) -> Vec<PlotCurve> {
        let doc = SwpDocument::parse(text, "t.swp").unwrap();
        doc.curves.iter().enumerate().map(|(i, c)| PlotCurve::from_swp(c, i).unwrap()).collect()
    }

    #[test]
    fn plot_draws_segment_colours() {
        let c = curves("bsp2 c 20 5 [0 0] [1 0] [1 1] [0 1] [0 2]");
        let opts = PlotOptions::DEFAULT.with_size(ImageSize::new(200, 150).unwrap());
        let image = plot_curves(&c, &CurveOptions::DEFAULT, &opts);
        assert_eq!((image.width(), image.height()), (200, 150));
        let has = |c: Rgb| image.iter_pixels().any(|p| p[..3] == c);
        assert!(has(crate::SEGMENT_COLOURS[0]) && has(crate::SEGMENT_COLOURS[1]));
        assert!(has(PLOT_BACKGROUND));
    }

    #[test]
    fn svg_lists_the_marks() {
        let c = curves("bez2 c 20 4 [0 0] [1 1] [2 1] [3 0]");
        let svg = plot_curves_svg(&c, &CurveOptions::DEFAULT, &PlotOptions::DEFAULT);
        assert!(svg.starts_with("<?xml"));
        assert!(svg.ends_with("</svg>\n"));
        assert_eq!(svg.matches("<circle").count(), 4);
        assert_eq!(svg.matches("stroke-dasharray").count(), 1);
        // 3 axes + polygon + 1 segment
        assert_eq!(svg.matches("<polyline").count(), 5);
    }
}
