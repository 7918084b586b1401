//! The orbit [`Camera`] of the 3D view: orbit, pan and zoom, projection to the screen, and
//! the view-projection matrix.

use eframe::egui::{self, Rect, Vec2, pos2};
use glam::{DMat4, DVec3, DVec4};

/// Orbit speed: radians of yaw or pitch per point of primary drag. Dragging right turns the
/// camera left around the target (`yaw` decreases), dragging down raises it (`pitch`
/// increases).
pub const ORBIT_RADIANS_PER_POINT: f64 = 0.01;
/// Scroll zoom: scrolling `dy` points multiplies the camera distance by
/// `exp(-ZOOM_PER_POINT * dy)` (scrolling up, `dy > 0`, moves closer).
pub const ZOOM_PER_POINT: f64 = 0.002;
/// The largest `|pitch|`, just short of looking straight down or up.
pub const PITCH_LIMIT: f64 = 1.55;

/// An orbit camera, Y up: the eye sits `distance` from `target`, in the direction given by
/// `yaw` (around +Y; 0 puts the eye on +Z) and `pitch` (above the XZ plane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The point the camera looks at and orbits around.
    pub target: DVec3,
    /// Radians around +Y; 0 puts the eye on the +Z side of the target.
    pub yaw: f64,
    /// Radians above the XZ plane, within ±[`PITCH_LIMIT`].
    pub pitch: f64,
    /// Distance from the eye to the target (> 0).
    pub distance: f64,
    /// Vertical field of view in radians.
    pub fov_y: f64,
}

impl Default for Camera {
    fn default() -> Self {
        Self { target: DVec3::ZERO, yaw: 0.6, pitch: 0.4, distance: 4.0, fov_y: 35f64.to_radians() }
    }
}

impl Camera {
    /// Unit vector from the target to the eye.
    #[must_use]
    pub fn back(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        DVec3::new(cp * sy, sp, cp * cy)
    }

    /// The eye position.
    #[must_use]
    pub fn eye(&self) -> DVec3 {
        self.target + self.distance * self.back()
    }

    /// Unit vectors to the right of and up the screen.
    #[must_use]
    pub fn right_up(&self) -> (DVec3, DVec3) {
        let (sy, cy) = self.yaw.sin_cos();
        let right = DVec3::new(cy, 0.0, -sy);
        (right, self.back().cross(right))
    }

    /// Turns the camera around the target by a drag of `delta` points
    /// ([`ORBIT_RADIANS_PER_POINT`]).
    pub fn orbit(&mut self, delta: Vec2) {
        self.yaw = (self.yaw - f64::from(delta.x) * ORBIT_RADIANS_PER_POINT).rem_euclid(std::f64::consts::TAU);
        self.pitch = (self.pitch + f64::from(delta.y) * ORBIT_RADIANS_PER_POINT).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }

    /// Moves the target so that a point at the target's depth follows a drag of `delta`
    /// points in a view `view_height` points high.
    pub fn pan(&mut self, delta: Vec2, view_height: f32) {
        let per_point = self.units_per_point(self.distance, view_height);
        let (right, up) = self.right_up();
        self.target += per_point * (-f64::from(delta.x) * right + f64::from(delta.y) * up);
    }

    /// Multiplies the distance by `factor` (< 1 moves closer), keeping it within
    /// `[min, max]`.
    pub fn zoom(&mut self, factor: f64, min: f64, max: f64) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance * factor).clamp(min, max);
        }
    }

    /// The distance in front of the eye of `p`, along the view direction.
    #[must_use]
    pub fn depth(&self, p: DVec3) -> f64 {
        (self.eye() - p).dot(self.back())
    }

    /// World units per point at `depth` in a view `view_height` points high.
    #[must_use]
    pub fn units_per_point(&self, depth: f64, view_height: f32) -> f64 {
        2.0 * depth * (0.5 * self.fov_y).tan() / f64::from(view_height.max(1.0))
    }

    /// Where `p` appears in a view filling `rect` (points), or `None` behind the eye.
    #[must_use]
    pub fn project(&self, p: DVec3, rect: Rect) -> Option<egui::Pos2> {
        let depth = self.depth(p);
        if !(depth > 0.0) {
            return None;
        }
        let per_point = self.units_per_point(depth, rect.height());
        let (right, up) = self.right_up();
        let d = p - self.eye();
        let c = rect.center();
        Some(pos2(c.x + (d.dot(right) / per_point) as f32, c.y - (d.dot(up) / per_point) as f32))
    }

    /// The part of the segment `ab` in front of the eye (deeper than a thousandth of the
    /// camera's distance) projected into `rect` as [`Self::project`] does, or `None` when no
    /// part is (or an end is not finite).
    #[must_use]
    pub fn project_segment(&self, a: DVec3, b: DVec3, rect: Rect) -> Option<[egui::Pos2; 2]> {
        let near = 1e-3 * self.distance;
        let (da, db) = (self.depth(a) - near, self.depth(b) - near);
        if !(da >= 0.0 || db >= 0.0) {
            return None;
        }
        // the end behind moved along the segment to the near depth
        let cut = |p: DVec3, q: DVec3, dp: f64, dq: f64| p + (q - p) * (dp / (dp - dq));
        let (a, b) = if da < 0.0 {
            (cut(a, b, da, db), b)
        } else if db < 0.0 {
            (a, cut(b, a, db, da))
        } else {
            (a, b)
        };
        Some([self.project(a, rect)?, self.project(b, rect)?])
    }

    /// `p` moved in the plane through it parallel to the screen, so that it follows a drag
    /// of `delta` points in a view `view_height` points high (its projection moves by
    /// exactly `delta`, its depth stays).
    #[must_use]
    pub fn drag_in_view_plane(&self, p: DVec3, delta: Vec2, view_height: f32) -> DVec3 {
        let per_point = self.units_per_point(self.depth(p), view_height);
        let (right, up) = self.right_up();
        p + per_point * (f64::from(delta.x) * right - f64::from(delta.y) * up)
    }

    /// Projection × view for a viewport of aspect `width / height`, in render space (world
    /// minus `origin`), with the given near and far planes (wgpu depth 0..1).
    #[must_use]
    pub fn view_proj(&self, origin: DVec3, aspect: f64, near: f64, far: f64) -> DMat4 {
        let (s, u) = self.right_up();
        let f = -self.back();
        let eye = self.eye() - origin;
        let view = DMat4::from_cols(
            DVec4::new(s.x, u.x, -f.x, 0.0),
            DVec4::new(s.y, u.y, -f.y, 0.0),
            DVec4::new(s.z, u.z, -f.z, 0.0),
            DVec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
        );
        // Right-handed, depth 0 at `near` and 1 at `far`.
        let h = 1.0 / (0.5 * self.fov_y).tan();
        let r = far / (near - far);
        let proj = DMat4::from_cols(
            DVec4::new(h / aspect, 0.0, 0.0, 0.0),
            DVec4::new(0.0, h, 0.0, 0.0),
            DVec4::new(0.0, 0.0, r, -1.0),
            DVec4::new(0.0, 0.0, r * near, 0.0),
        );
        proj * view
    }
}
