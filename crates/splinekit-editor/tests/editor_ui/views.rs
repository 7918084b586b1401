//! The views' guides and normals (#37): the 3D view's axes and grid switched by their
//! checkboxes, and the 2D normals left or right of travel.

use eframe::egui::{Pos2, Rect};
use egui_kittest::kittest::Queryable as _;
use splinekit::frame::Side;
use splinekit_editor::view2d;
use splinekit_editor::view3d::Camera;

use super::*;

/// A rendered frame's pixels (one pixel a point in the harness).
#[derive(PartialEq)]
struct Shot {
    width: u32,
    height: u32,
    rgba: Vec<u8>,
}

impl Shot {
    fn of(h: &mut Harness<'static, EditorApp>) -> Self {
        let image = h.render().unwrap();
        Self { width: image.width(), height: image.height(), rgba: image.into_raw() }
    }

    fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        let i = 4 * (y.min(self.height - 1) * self.width + x.min(self.width - 1)) as usize;
        [self.rgba[i], self.rgba[i + 1], self.rgba[i + 2], self.rgba[i + 3]]
    }

    /// Whether the pixels within `rect` are the same in `other` (the widgets around differ
    /// by the one hovered).
    fn same_in(&self, other: &Self, rect: Rect) -> bool {
        (rect.min.y as u32..rect.max.y as u32)
            .all(|y| (rect.min.x as u32..rect.max.x as u32).all(|x| self.pixel(x, y) == other.pixel(x, y)))
    }
}

impl std::fmt::Debug for Shot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Shot {}x{}", self.width, self.height)
    }
}

/// How many of `points` (screen points, one pixel a point in the harness) inside `rect` have
/// different pixels in `a` and `b`, and how many are inside.
fn differing(a: &Shot, b: &Shot, rect: Rect, points: &[Pos2]) -> (usize, usize) {
    let inside: Vec<(u32, u32)> = points
        .iter()
        .filter(|p| rect.shrink(2.0).contains(**p))
        .map(|p| (p.x as u32, p.y as u32))
        .filter(|&(x, y)| x < a.width && y < a.height)
        .collect();
    (inside.iter().filter(|&&(x, y)| a.pixel(x, y) != b.pixel(x, y)).count(), inside.len())
}

/// Points along the world segment `ab` (ends left out) where `camera` shows them in `rect`.
fn along(camera: &Camera, rect: Rect, a: DVec3, b: DVec3) -> Vec<Pos2> {
    (1..20).filter_map(|k| camera.project(a + (b - a) * (f64::from(k) / 20.0), rect)).collect()
}

#[test]
fn axes_and_grid_in_the_3d_view_switch_with_their_checkboxes() {
    let mut h = four_points();
    let settings = h.state().view3d.settings;
    assert!(settings.axes && settings.grid, "both on by default");
    let rect = h.get_by_label("3D view").rect();
    let camera = *h.state().view3d.camera();
    let guides = h.state().view3d.guides();
    // the scene: the curve from (0, 0) to (4, 0), up to y = 1.5, a radius of about 2
    assert!((guides.step - 0.5).abs() < 1e-12, "{}", guides.step);
    assert!(guides.axis_length > 4.0, "{}", guides.axis_length);
    let both = Shot::of(&mut h);

    click(&mut h, "Axes");
    assert!(!h.state().view3d.settings.axes);
    assert_eq!(*h.state().view3d.camera(), camera);
    let no_axes = Shot::of(&mut h);
    // (the camera looks along about −z: the z axis is short on the screen)
    for (k, axis) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
        let points = along(&camera, rect, DVec3::ZERO, guides.axis_length * axis);
        let (changed, inside) = differing(&both, &no_axes, rect, &points);
        assert!(inside >= 3 && 3 * changed >= 2 * inside, "axis {k}: {changed} of {inside} pixels changed");
    }

    click(&mut h, "Axes");
    click(&mut h, "Grid");
    assert!(h.state().view3d.settings.axes && !h.state().view3d.settings.grid);
    let no_grid = Shot::of(&mut h);
    // the grid lines away from the axes
    let points: Vec<Pos2> = guides
        .grid
        .iter()
        .filter(|[a, b]| if a.x == b.x { a.x.abs() } else { a.y.abs() } > 0.5 * guides.step)
        .flat_map(|&[a, b]| along(&camera, rect, a, b))
        .collect();
    let (changed, inside) = differing(&both, &no_grid, rect, &points);
    assert!(inside >= 50 && 3 * changed >= 2 * inside, "grid: {changed} of {inside} pixels changed");

    click(&mut h, "Grid");
    assert!(Shot::of(&mut h).same_in(&both, rect), "back as it was");
}

/// Whether a pixel next to `p` (screen points) is the normals' red.
fn is_normal_red(image: &Shot, p: Pos2) -> bool {
    (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy))).any(|(dx, dy)| {
        let [r, g, b, _] = image.pixel((p.x as i32 + dx) as u32, (p.y as i32 + dy) as u32);
        r > 150 && g < 110 && b < 110
    })
}

#[test]
fn normals_left_or_right_of_travel_in_the_2d_view() {
    let mut h = four_points();
    click(&mut h, "Draw normals");
    assert!(h.state().view.show.normals);
    assert_eq!(h.state().view.show.normal_side, Side::Left, "left of travel, as before");
    // the curve's middle, where it runs left to right near its top: N points up (+y) on the
    // left, down on the right, 28 points long
    let app = h.state();
    let curve = app.doc.spline().unwrap();
    let arrows = view2d::frame_arrows(&curve, &app.view.show.frame_options(true));
    let (p, f) = arrows[arrows.len() / 2];
    assert!(f.n.y > 0.9, "left normal of a curve going right points up: {}", f.n);
    let half = 14.0 / app.view.scale;
    let (up, down) = (app.view.to_screen((p + f.n * half).truncate()), app.view.to_screen((p - f.n * half).truncate()));
    let left = Shot::of(&mut h);
    assert!(is_normal_red(&left, up) && !is_normal_red(&left, down), "left: N drawn above the curve");

    click(&mut h, "Normals right");
    assert_eq!(h.state().view.show.normal_side, Side::Right);
    let right = Shot::of(&mut h);
    assert!(is_normal_red(&right, down) && !is_normal_red(&right, up), "right: N mirrored below the curve");
    // the frames in 3D follow (T, N, B at 9 places)
    assert_eq!(h.state().view3d.overlay_lines(), 1 + 9 * 3);

    click(&mut h, "Normals left");
    assert_eq!(h.state().view.show.normal_side, Side::Left);
    let (view2d, view3d) = (h.state().view.rect, h.get_by_label("3D view").rect());
    let back = Shot::of(&mut h);
    assert!(back.same_in(&left, view2d) && back.same_in(&left, view3d), "back as it was");
}
