//! The axes and grid of the 3D view ([`Guides`]), and how they are drawn under the image.

use eframe::egui::{self, Color32, Rect, pos2};
use glam::DVec3;

use super::View3d;
use crate::view2d;

/// The x, y and z axes ([`View3dSettings::axes`](super::View3dSettings::axes)).
pub const AXIS_COLOURS: [Color32; 3] =
    [Color32::from_rgb(230, 70, 70), Color32::from_rgb(80, 200, 90), Color32::from_rgb(90, 140, 255)];
/// The grid lines ([`View3dSettings::grid`](super::View3dSettings::grid)): dim grey, translucent (premultiplied).
pub const GRID_COLOUR: Color32 = Color32::from_rgba_premultiplied(35, 35, 35, 60);

/// Grid lines per radius of the scene, at least ([`Guides::new`]).
pub const GRID_LINES_PER_RADIUS: f64 = 5.0;
/// The most grid lines in each direction, whatever the numbers.
pub const MAX_GRID_LINES: f64 = 64.0;

/// The axes and the grid of the 3D view ([`View3dSettings::axes`](super::View3dSettings::axes),
/// [`View3dSettings::grid`](super::View3dSettings::grid)) for a scene, in world coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Guides {
    /// The grid spacing: 1, 2 or 5 times a power of ten ([`view2d::grid_step`]).
    pub step: f64,
    /// How far each axis reaches from the origin (its label is at the end).
    pub axis_length: f64,
    /// The grid lines in the xy plane (z = 0): first those of constant x, then those of
    /// constant y, from low to high.
    pub grid: Vec<[DVec3; 2]>,
}

impl Guides {
    /// The guides of a scene within `radius` of `centre` (e.g. [`point_bounds`](super::point_bounds)): grid lines
    /// [`GRID_LINES_PER_RADIUS`] or more per radius, over the square in xy that holds the
    /// scene's bounding sphere (rounded out to whole steps); axes reaching 1.2 times as far
    /// as the scene's farthest point from the origin, rounded up to a whole step. A radius
    /// that is not positive and finite counts as 1, a centre that is not finite as the
    /// origin.
    #[must_use]
    pub fn new(centre: DVec3, radius: f64) -> Self {
        let centre = if centre.is_finite() { centre } else { DVec3::ZERO };
        let radius = if radius.is_finite() && radius > 0.0 { radius } else { 1.0 };
        let step = view2d::grid_step(radius / GRID_LINES_PER_RADIUS);
        let range = |c: f64| {
            let lo = ((c - radius) / step).floor();
            (lo, ((c + radius) / step).ceil().clamp(lo, lo + MAX_GRID_LINES))
        };
        let ((x0, x1), (y0, y1)) = (range(centre.x), range(centre.y));
        // counted in integers: far from the origin `k + 1.0` may equal `k`
        let ks = |lo: f64, hi: f64| (0..=(hi - lo) as usize).map(move |i| (lo + i as f64) * step);
        let mut grid: Vec<[DVec3; 2]> =
            ks(x0, x1).map(|x| [DVec3::new(x, y0 * step, 0.0), DVec3::new(x, y1 * step, 0.0)]).collect();
        grid.extend(ks(y0, y1).map(|y| [DVec3::new(x0 * step, y, 0.0), DVec3::new(x1 * step, y, 0.0)]));
        let axis_length = (1.2 * (centre.length() + radius) / step).ceil() * step;
        grid.retain(|[a, b]| a.is_finite() && b.is_finite());
        Self { step, axis_length: if axis_length.is_finite() { axis_length } else { radius }, grid }
    }
}

impl View3d {
    /// Draws the grid, then the axes and their labels, with `painter` over the image in `rect`.
    pub(super) fn draw_guides(&self, painter: &egui::Painter, rect: Rect) {
        if !(self.settings.axes || self.settings.grid) {
            return;
        }
        let guides = self.guides();
        if self.settings.grid {
            for &[a, b] in &guides.grid {
                if let Some(line) = self.camera.project_segment(a, b, rect) {
                    painter.line_segment(line, (1.0, GRID_COLOUR));
                }
            }
        }
        if self.settings.axes {
            for ((axis, colour), name) in
                [DVec3::X, DVec3::Y, DVec3::Z].into_iter().zip(AXIS_COLOURS).zip(["x", "y", "z"])
            {
                let Some([a, b]) = self.camera.project_segment(DVec3::ZERO, guides.axis_length * axis, rect) else {
                    continue;
                };
                painter.line_segment([a, b], (1.5, colour));
                // the label just beyond the end, or where the axis leaves the view
                let Some([a, b]) = clip_segment(a, b, rect.shrink(14.0)) else { continue };
                let beyond = (b - a).normalized() * 7.0;
                let at = if beyond.is_finite() { b + beyond } else { b };
                painter.text(at, egui::Align2::CENTER_CENTER, name, egui::FontId::proportional(11.0), colour);
            }
        }
    }
}

/// The part of the segment `ab` inside `rect`, or `None` (the renderer's clip, in f64).
fn clip_segment(a: egui::Pos2, b: egui::Pos2, rect: Rect) -> Option<[egui::Pos2; 2]> {
    let f = |p: egui::Pos2| [f64::from(p.x), f64::from(p.y)];
    let (p, q) = splinekit_render::plot::clip_segment(f(a), f(b), f(rect.min), f(rect.max))?;
    let back = |p: [f64; 2]| pos2(p[0] as f32, p[1] as f32);
    Some([back(p), back(q)])
}

#[cfg(test)]
mod tests {
    use eframe::egui::Vec2;

    use super::*;
    use crate::view3d::Camera;

    #[test]
    fn guides_cover_the_scene_in_whole_steps() {
        let g = Guides::new(DVec3::new(2.0, 1.0, 0.5), 2.2);
        // a fifth of the radius, 0.44, up to 1, 2 or 5 times a power of ten
        assert!((g.step - 0.5).abs() < 1e-15, "{}", g.step);
        // 1.2 · (|c| + r) = 1.2 · (2.291… + 2.2) = 5.39…, up to a whole step
        assert!((g.axis_length - 5.5).abs() < 1e-12, "{}", g.axis_length);
        // x from −0.5 to 4.5 and y from −1.5 to 3.5: 11 lines each way, in the xy plane
        assert_eq!(g.grid.len(), 22);
        let (first, last) = (g.grid[0], g.grid[10]);
        assert!((first[0] - DVec3::new(-0.5, -1.5, 0.0)).length() < 1e-12, "{first:?}");
        assert!((last[1] - DVec3::new(4.5, 3.5, 0.0)).length() < 1e-12, "{last:?}");
        assert!(g.grid.iter().flatten().all(|p| p.z == 0.0));
        // lines at whole multiples of the step
        for [a, b] in &g.grid {
            let k = if a.x == b.x { a.x / g.step } else { a.y / g.step };
            assert!((k - k.round()).abs() < 1e-9, "{a} {b}");
        }
    }

    #[test]
    fn guides_of_degenerate_scenes_are_finite_and_few() {
        for (centre, radius) in [
            (DVec3::ZERO, 0.0),
            (DVec3::NAN, f64::NAN),
            (DVec3::splat(1e12), 1e-6),
            (DVec3::ZERO, f64::INFINITY),
            (DVec3::splat(1e300), 1e300),
            (DVec3::ZERO, 1e-300),
        ] {
            let g = Guides::new(centre, radius);
            assert!(g.step > 0.0 && g.step.is_finite() && g.axis_length.is_finite(), "{centre} {radius}: {g:?}");
            assert!(g.grid.len() <= 2 * (MAX_GRID_LINES as usize + 1), "{centre} {radius}: {}", g.grid.len());
            assert!(g.grid.iter().flatten().all(|p| p.is_finite()));
        }
    }

    #[test]
    fn segments_are_cut_at_the_near_plane_and_the_rect() {
        let camera = Camera { target: DVec3::ZERO, yaw: 0.0, pitch: 0.0, distance: 4.0, ..Camera::default() };
        let rect = Rect::from_min_size(pos2(0.0, 0.0), Vec2::new(200.0, 100.0));
        // along x through the target: on the horizontal through the centre
        let [a, b] = camera.project_segment(DVec3::new(-1.0, 0.0, 0.0), DVec3::X, rect).unwrap();
        assert!((a.y - 50.0).abs() < 1e-4 && (b.y - 50.0).abs() < 1e-4 && a.x < 100.0 && b.x > 100.0);
        // from the target to behind the eye (the eye is at z = 4): cut, not dropped
        let [a, b] = camera.project_segment(DVec3::ZERO, DVec3::new(1.0, 0.0, 8.0), rect).unwrap();
        assert_eq!(a, pos2(100.0, 50.0));
        assert!(b.x.is_finite() && b.x > 100.0);
        // all behind
        assert!(camera.project_segment(DVec3::new(0.0, 0.0, 5.0), DVec3::new(1.0, 0.0, 9.0), rect).is_none());
        assert!(camera.project_segment(DVec3::NAN, DVec3::ZERO, rect).is_none());

        let [a, b] = clip_segment(pos2(100.0, 50.0), pos2(300.0, 150.0), rect).unwrap();
        assert_eq!((a, b), (pos2(100.0, 50.0), pos2(200.0, 100.0)));
        assert!(clip_segment(pos2(-10.0, -10.0), pos2(-1.0, 300.0), rect).is_none());
    }
}
