//! Views and the camera: [`View`] names a direction, [`Camera::fit`] frames points in it.
//!
//! World axes: y up. `front` looks at the xy-plane from +z (x right, y up), `top` from +y
//! (x right, −z up), `iso` from the (1, 1, 1) direction with y up.
//!
//! The camera frames the *projected* extent of the scene: the eye stays at a fixed distance
//! (so perspective does not depend on what is shown), and the image is scaled and shifted
//! until the points' projections fill the picture less a margin. For a perspective camera the
//! shift is a lens shift (the projection stays a true perspective).

use std::fmt;
use std::str::FromStr;

use glam::DVec3;

use crate::ImageSize;

/// Vertical field of view of the perspective camera (before the fit zooms), in degrees.
pub const FIELD_OF_VIEW_DEGREES: f64 = 30.0;

/// Fraction of the picture's smaller side left free on each side by [`Camera::fit`].
pub const DEFAULT_MARGIN: f64 = 0.06;

/// A direction to look from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum View {
    /// From (1, 1, 1), y up.
    #[default]
    Iso,
    /// From +z: x right, y up (the plane of 2D curves).
    Front,
    /// From −z: −x right, y up.
    Back,
    /// From +y: x right, −z up.
    Top,
    /// From −y: x right, +z up.
    Bottom,
    /// From −x: z right, y up.
    Left,
    /// From +x: −z right, y up.
    Right,
}

impl View {
    /// Every view, in the order of the docs.
    pub const ALL: [Self; 7] = [Self::Iso, Self::Front, Self::Back, Self::Top, Self::Bottom, Self::Left, Self::Right];

    /// The name used on the command line.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Iso => "iso",
            Self::Front => "front",
            Self::Back => "back",
            Self::Top => "top",
            Self::Bottom => "bottom",
            Self::Left => "left",
            Self::Right => "right",
        }
    }

    /// The unit direction from the scene towards the eye, and the world direction that is up
    /// on the screen.
    #[must_use]
    pub fn back_and_up(self) -> (DVec3, DVec3) {
        match self {
            Self::Iso => (DVec3::ONE.normalize(), DVec3::Y),
            Self::Front => (DVec3::Z, DVec3::Y),
            Self::Back => (DVec3::NEG_Z, DVec3::Y),
            Self::Top => (DVec3::Y, DVec3::NEG_Z),
            Self::Bottom => (DVec3::NEG_Y, DVec3::Z),
            Self::Left => (DVec3::NEG_X, DVec3::Y),
            Self::Right => (DVec3::X, DVec3::Y),
        }
    }
}

impl fmt::Display for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown view name.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown view {0:?}; expected iso, front, back, top, bottom, left or right")]
pub struct ViewError(pub String);

impl FromStr for View {
    type Err = ViewError;

    fn from_str(s: &str) -> Result<Self, ViewError> {
        Self::ALL.into_iter().find(|v| v.name().eq_ignore_ascii_case(s)).ok_or_else(|| ViewError(s.to_string()))
    }
}

/// Perspective or parallel projection.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Projection {
    /// Perspective, with the eye at the distance where a [`FIELD_OF_VIEW_DEGREES`] cone
    /// holds the scene's bounding sphere.
    #[default]
    Perspective,
    /// Parallel (orthographic): sizes do not change with depth.
    Orthographic,
}

/// A point projected by a [`Camera`]: pixel coordinates (x right, y down, pixel centres at
/// `i + 0.5`), and its depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    /// Column, in pixels.
    pub x: f64,
    /// Row, in pixels from the top.
    pub y: f64,
    /// Distance in front of the eye along the view direction (orthographic: from the eye
    /// plane), in world units.
    pub depth: f64,
}

/// A camera that maps world points to pixels of a picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye.
    pub eye: DVec3,
    /// World direction of screen right (unit).
    pub right: DVec3,
    /// World direction of screen up (unit).
    pub up: DVec3,
    /// World direction from the scene towards the eye (unit); the camera looks along −back.
    pub back: DVec3,
    /// The projection.
    pub projection: Projection,
    /// Pixels per world unit at depth 1 (perspective) or everywhere (orthographic).
    pub scale: f64,
    /// Pixel position of the view axis (the principal point).
    pub centre: [f64; 2],
}

impl Camera {
    /// A camera looking from `view` at `points`, framing their projections in a picture of
    /// `size` with `margin` (a fraction of the smaller side) free on each side. With no finite
    /// point, frames the unit sphere about the origin.
    #[must_use]
    pub fn fit(
        view: View,
        projection: Projection,
        points: impl IntoIterator<Item = DVec3> + Clone,
        size: ImageSize,
        margin: f64,
    ) -> Self {
        let (lo, hi) = bounds(points.clone().into_iter());
        let (camera, radius) = Self::aimed(view, projection, lo, hi);
        let extent = points.into_iter().fold(Extent::EMPTY, |e, p| camera.extend(e, p));
        camera.zoomed(extent, radius, size, margin)
    }

    /// Looking at the centre of the box `lo..hi` (empty: the origin) from `view`, far
    /// enough to see its bounding sphere, at scale 1; and the sphere's radius.
    pub(crate) fn aimed(view: View, projection: Projection, lo: DVec3, hi: DVec3) -> (Self, f64) {
        // Bounding sphere about the box centre.
        let (target, mut radius) =
            if lo.x <= hi.x { (0.5 * (lo + hi), 0.5 * (hi - lo).length()) } else { (DVec3::ZERO, 1.0) };
        if !(radius > 1e-12 * target.length().max(1e-300)) || !radius.is_finite() {
            radius = target.length().max(1.0) * 1e-3;
        }
        let (back, up_hint) = view.back_and_up();
        let right = up_hint.cross(back).normalize();
        let up = back.cross(right);
        let half = (0.5 * FIELD_OF_VIEW_DEGREES).to_radians();
        let eye = match projection {
            Projection::Perspective => target + back * (radius / half.sin()),
            // Behind the nearest point, so depths are positive.
            Projection::Orthographic => target + back * (2.0 * radius),
        };
        (Self { eye, right, up, back, projection, scale: 1.0, centre: [0.0, 0.0] }, radius)
    }

    /// `extent` with the projection of `p` at this camera's scale and centre (unchanged
    /// when `p` is not finite).
    #[inline]
    pub(crate) fn extend(&self, extent: Extent, p: DVec3) -> Extent {
        if p.is_finite() { extent.with(self.project(p)) } else { extent }
    }

    /// This camera (from [`Self::aimed`], with its `radius`) scaled and centred so that the
    /// projections' `extent` at scale 1 fills a picture of `size` inside the margin.
    pub(crate) fn zoomed(mut self, extent: Extent, radius: f64, size: ImageSize, margin: f64) -> Self {
        let Extent { x0, x1, y0, y1 } = extent;
        let half = (0.5 * FIELD_OF_VIEW_DEGREES).to_radians();
        let (w, h) = (f64::from(size.width), f64::from(size.height));
        let free = margin.clamp(0.0, 0.45) * w.min(h);
        let (avail_w, avail_h) = ((w - 2.0 * free).max(1.0), (h - 2.0 * free).max(1.0));
        let (x0, x1, y0, y1) = if x0 <= x1 && y0 <= y1 { (x0, x1, y0, y1) } else { (-radius, radius, -radius, radius) };
        // A flat extent (a curve seen edge on) must not zoom without bound.
        let min_extent = 1e-3
            * (radius
                / match self.projection {
                    Projection::Perspective => radius / half.sin(),
                    Projection::Orthographic => 1.0,
                });
        let (ex, ey) = ((x1 - x0).max(min_extent), (y1 - y0).max(min_extent));
        let scale = (avail_w / ex).min(avail_h / ey);
        self.scale = if scale.is_finite() && scale > 0.0 { scale } else { 1.0 };
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        self.centre = [0.5 * w - self.scale * cx, 0.5 * h - self.scale * cy];
        self
    }

    /// The pixel position and depth of `p`. Points behind a perspective eye get a
    /// non-positive depth (and meaningless pixel coordinates).
    #[must_use]
    pub fn project(&self, p: DVec3) -> Projected {
        let v = p - self.eye;
        let (x, y, depth) = (v.dot(self.right), v.dot(self.up), -v.dot(self.back));
        let k = match self.projection {
            Projection::Perspective => self.scale / depth,
            Projection::Orthographic => self.scale,
        };
        Projected { x: self.centre[0] + k * x, y: self.centre[1] - k * y, depth }
    }

    /// `p` in camera coordinates: x right, y up, z towards the eye.
    #[must_use]
    pub fn to_view(&self, p: DVec3) -> DVec3 {
        let v = p - self.eye;
        DVec3::new(v.dot(self.right), v.dot(self.up), v.dot(self.back))
    }

    /// The world direction `d` in camera coordinates.
    #[must_use]
    pub fn dir_to_view(&self, d: DVec3) -> DVec3 {
        DVec3::new(d.dot(self.right), d.dot(self.up), d.dot(self.back))
    }

    /// Unit direction from `p` towards the eye, in camera coordinates.
    #[must_use]
    pub fn to_eye_in_view(&self, view_pos: DVec3) -> DVec3 {
        match self.projection {
            Projection::Perspective => (-view_pos).normalize_or(DVec3::Z),
            Projection::Orthographic => DVec3::Z,
        }
    }
}

/// Radius of the bounding sphere about the box centre of the finite points (1 if none).
#[must_use]
pub fn bounding_radius(points: impl Iterator<Item = DVec3>) -> f64 {
    let (lo, hi) = bounds(points);
    box_radius(lo, hi)
}

/// Half the diagonal of the box `lo..hi` (1 when that is empty, zero or not finite).
pub(crate) fn box_radius(lo: DVec3, hi: DVec3) -> f64 {
    // halved first and scaled by the largest side: no overflow for any finite box (a box of
    // 1e304 is not "not finite" and drawn at the tolerances of a unit box)
    let half = 0.5 * hi - 0.5 * lo;
    let m = half.abs().max_element();
    let r = if m > 0.0 && m.is_finite() { m * (half / m).length() } else { m };
    if r.is_finite() && r > 0.0 { r } else { 1.0 }
}

/// The box of the finite points (`lo > hi` when there are none).
pub(crate) fn bounds(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.fold(EMPTY_BOX, grow_box)
}

/// The box of no points.
pub(crate) const EMPTY_BOX: (DVec3, DVec3) = (DVec3::INFINITY, DVec3::NEG_INFINITY);

/// The box `(lo, hi)` grown to hold `p` (unchanged when `p` is not finite).
#[inline]
pub(crate) fn grow_box((lo, hi): (DVec3, DVec3), p: DVec3) -> (DVec3, DVec3) {
    if p.is_finite() { (lo.min(p), hi.max(p)) } else { (lo, hi) }
}

/// The range of projected positions at scale 1 ([`Camera::zoomed`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Extent {
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
}

impl Extent {
    /// No points.
    pub const EMPTY: Self = Self { x0: f64::INFINITY, x1: f64::NEG_INFINITY, y0: f64::INFINITY, y1: f64::NEG_INFINITY };

    /// With the projection `q`.
    #[must_use]
    pub fn with(self, q: Projected) -> Self {
        Self { x0: self.x0.min(q.x), x1: self.x1.max(q.x), y0: self.y0.min(q.y), y1: self.y1.max(q.y) }
    }

    /// Both ranges.
    #[must_use]
    pub fn union(self, o: Self) -> Self {
        Self { x0: self.x0.min(o.x0), x1: self.x1.max(o.x1), y0: self.y0.min(o.y0), y1: self.y1.max(o.y1) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_parse_and_are_right_handed() {
        for v in View::ALL {
            assert_eq!(v.name().parse::<View>(), Ok(v));
            let cam = Camera::fit(v, Projection::Perspective, [DVec3::ZERO, DVec3::ONE], ImageSize::DEFAULT, 0.1);
            assert!(cam.right.cross(cam.up).distance(cam.back) < 1e-12, "{v}");
            assert!(cam.right.dot(cam.up).abs() < 1e-12, "{v}");
            assert!(cam.back.distance(v.back_and_up().0) < 1e-12, "{v}");
        }
        assert!("sideways".parse::<View>().is_err());
        assert_eq!("ISO".parse::<View>(), Ok(View::Iso));
    }

    #[test]
    fn front_view_maps_x_right_and_y_up() {
        let size = ImageSize::new(200, 100).unwrap();
        let pts = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
        for projection in [Projection::Perspective, Projection::Orthographic] {
            let cam = Camera::fit(View::Front, projection, pts, size, 0.1);
            let a = cam.project(pts[0]);
            let b = cam.project(pts[1]);
            assert!(b.x > a.x && b.y < a.y, "{projection:?}");
            // Framed: the square's height fills the picture less the margins (10 px each).
            assert!((a.y - b.y - 80.0).abs() < 1e-9, "{projection:?}: {a:?} {b:?}");
            assert!(((a.x + b.x) / 2.0 - 100.0).abs() < 1e-9);
            assert!(a.depth > 0.0);
        }
    }

    #[test]
    fn top_view_has_minus_z_up() {
        let cam = Camera::fit(View::Top, Projection::Orthographic, [DVec3::ZERO, DVec3::ONE], ImageSize::DEFAULT, 0.1);
        let o = cam.project(DVec3::ZERO);
        let z = cam.project(DVec3::Z);
        let x = cam.project(DVec3::X);
        assert!(z.y > o.y, "+z is down on the screen");
        assert!(x.x > o.x);
    }
}
