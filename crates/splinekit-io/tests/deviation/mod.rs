//! How far a swept mesh strays from the exact surface of revolution it approximates,
//! sampled on triangle interiors (shared by the adaptive-sweep tests and the
//! `sweep_adaptive` example).
//!
//! The exact surface turns a meridian curve `m(v) = (r0 + sx·x(v), y(v))` (a 2D profile,
//! shifted and possibly mirrored) about an axis through the origin. The distance from a
//! point `P` to it is the distance, in `P`'s meridian half-plane, from `(ρ, h)` (`ρ` the
//! distance from the axis, `h` the height along it) to the meridian curve folded onto
//! `r ≥ 0`: **a true distance**, not a bound. It is found by the nearest of a dense sample of
//! the curve (a grid), refined by Newton steps on the curve itself, and the value reported is
//! the distance to that curve point, so it can only over-estimate the true distance (a test
//! asserting it ≤ T is conservative). [`Revolution::exact`] re-checks a point with the
//! curve's proved nearest-point search.
#![allow(dead_code)]

use glam::{DVec2, DVec3};
use splinekit::{AnyCurve, ParamCurve, TriMesh};

/// The exact surface: a meridian curve turned about an axis.
pub struct Revolution<'a> {
    curve: &'a AnyCurve<DVec3>,
    /// `r = r0 + sx·x`, `h = y`.
    r0: f64,
    sx: f64,
    /// The axis (unit): `+y` for `srev`, `+z` for a gcyl along a circle in the xy plane.
    axis: DVec3,
    /// Dense samples `(parameter, meridian point)` in a grid of cells.
    samples: Vec<(f64, DVec2)>,
    lo: DVec2,
    cell: f64,
    side: [usize; 2],
    cells: Vec<Vec<u32>>,
}

impl<'a> Revolution<'a> {
    /// A surface of revolution about `axis` of the meridian `(r0 + sx·x(v), y(v))`.
    pub fn new(curve: &'a AnyCurve<DVec3>, r0: f64, sx: f64, axis: DVec3) -> Self {
        let (a, b) = curve.domain();
        let n = 4000 * curve.num_segments().max(8);
        let samples: Vec<(f64, DVec2)> = (0..=n)
            .map(|i| {
                let v = a + (b - a) * i as f64 / n as f64;
                let p = curve.eval(v);
                (v, DVec2::new(r0 + sx * p.x, p.y))
            })
            .collect();
        let (lo, hi) =
            samples.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), s| (lo.min(s.1), hi.max(s.1)));
        let size = (hi - lo).max_element().max(1e-9);
        let cell = size / 256.0;
        let side = [((hi.x - lo.x) / cell) as usize + 1, ((hi.y - lo.y) / cell) as usize + 1];
        let mut cells = vec![Vec::new(); side[0] * side[1]];
        for (i, s) in samples.iter().enumerate() {
            let c = ((s.1 - lo) / cell).as_uvec2();
            cells[c.y as usize * side[0] + c.x as usize].push(i as u32);
        }
        Self { curve, r0, sx, axis, samples, lo, cell, side, cells }
    }

    fn meridian(&self, v: f64) -> (DVec2, DVec2, DVec2) {
        let (p, d, dd) = (self.curve.eval(v), self.curve.deriv(v), self.curve.deriv2(v));
        (DVec2::new(self.r0 + self.sx * p.x, p.y), DVec2::new(self.sx * d.x, d.y), DVec2::new(self.sx * dd.x, dd.y))
    }

    /// The meridian coordinates `(ρ, h)` of `p`.
    fn to_meridian(&self, p: DVec3) -> DVec2 {
        let h = p.dot(self.axis);
        DVec2::new((p - h * self.axis).length(), h)
    }

    /// The nearest dense sample to `q` (by rings of cells), if one is within `bound`.
    fn nearest_sample(&self, q: DVec2, bound: f64) -> Option<usize> {
        let c = (q - self.lo) / self.cell;
        let (cx, cy) = (c.x.floor() as i64, c.y.floor() as i64);
        let mut best = (f64::INFINITY, usize::MAX);
        // start at the ring of the box's nearest cell
        let clamp = |v: i64, n: usize| v.clamp(0, n as i64 - 1);
        let first = (cx - clamp(cx, self.side[0])).abs().max((cy - clamp(cy, self.side[1])).abs());
        for ring in first.. {
            // every sample outside the rings so far is at least this far
            let outside = (ring as f64 - 1.0).max(0.0) * self.cell;
            if best.0.sqrt() < outside || outside > bound || ring > first + (self.side[0] + self.side[1]) as i64 + 2 {
                break;
            }
            for y in cy - ring..=cy + ring {
                for x in cx - ring..=cx + ring {
                    if (y - cy).abs() != ring && (x - cx).abs() != ring {
                        continue;
                    }
                    if x < 0 || y < 0 || x >= self.side[0] as i64 || y >= self.side[1] as i64 {
                        continue;
                    }
                    for &i in &self.cells[y as usize * self.side[0] + x as usize] {
                        let d = self.samples[i as usize].1.distance_squared(q);
                        if d < best.0 {
                            best = (d, i as usize);
                        }
                    }
                }
            }
        }
        (best.1 != usize::MAX).then_some(best.1)
    }

    /// Distance from the meridian point `q` to the meridian curve (an upper bound: the
    /// distance to a point of the curve, found by Newton steps from the nearest sample).
    fn distance_2d(&self, q: DVec2, bound: f64) -> f64 {
        let Some(i) = self.nearest_sample(q, bound) else { return f64::INFINITY };
        let (a, b) = self.curve.domain();
        let mut v = self.samples[i].0;
        let mut best = self.samples[i].1.distance(q);
        for _ in 0..8 {
            let (p, d, dd) = self.meridian(v);
            let g = (p - q).dot(d);
            let h = d.length_squared() + (p - q).dot(dd);
            if h <= 0.0 {
                break;
            }
            v = (v - g / h).clamp(a, b);
            best = best.min(self.meridian(v).0.distance(q));
        }
        best
    }

    /// Distance from `p` to the surface (an upper bound, see the module docs).
    pub fn distance(&self, p: DVec3) -> f64 {
        let m = self.to_meridian(p);
        // folded: the curve at r < 0 is the same surface
        let (near, far) = if self.samples[self.samples.len() / 2].1.x < 0.0 {
            (DVec2::new(-m.x, m.y), m)
        } else {
            (m, DVec2::new(-m.x, m.y))
        };
        let d = self.distance_2d(near, f64::INFINITY);
        d.min(self.distance_2d(far, d))
    }

    /// Distance from `p` to the surface by the curve's proved nearest-point search.
    pub fn exact(&self, p: DVec3, accuracy: f64) -> f64 {
        let m = self.to_meridian(p);
        let d = |q: DVec2| {
            // back to the profile's coordinates: x = (r − r0)/sx
            let target = DVec3::new((q.x - self.r0) / self.sx, q.y, 0.0);
            // distances in x scale by |sx| = 1 for the surfaces here
            self.curve.nearest(target, accuracy).distance
        };
        d(m).min(d(DVec2::new(-m.x, m.y)))
    }
}

/// Points of each triangle at barycentric coordinates `(i, j, k)/m`, `i + j + k = m`
/// (corners, edges and interior; `m` even puts the edge midpoints in, where a diagonal
/// strays most).
pub fn triangle_points(mesh: &TriMesh, m: usize) -> impl Iterator<Item = (usize, DVec3)> + '_ {
    mesh.triangles.iter().enumerate().flat_map(move |(t, tri)| {
        let [a, b, c] = tri.map(|v| mesh.positions[v as usize]);
        (0..=m).flat_map(move |i| {
            (0..=m - i).map(move |j| {
                let k = m - i - j;
                (t, (a * i as f64 + b * j as f64 + c * k as f64) / m as f64)
            })
        })
    })
}

/// The largest distance from the points of [`triangle_points`] to `surface`, and the point.
pub fn deviation(mesh: &TriMesh, surface: &Revolution<'_>, m: usize) -> (f64, DVec3) {
    triangle_points(mesh, m)
        .map(|(_, p)| (surface.distance(p), p))
        .fold((0.0, DVec3::ZERO), |a, b| if b.0 > a.0 { b } else { a })
}

/// The exact surface of a generalized cylinder, `S(u, v) = P(u) + N(u)·x(v) + B(u)·y(v)`
/// (`(x, y)` the profile less its anchor), for a distance measure independent of the sweep
/// code. With a shape ([`Cylinder::shaped`]), `(x, y)` is also multiplied by the unit factors
/// and the scale curve's point and `(N, B)` turned by the twist curve's angle (degrees, `N`
/// toward `B`), both read at the path's normalized arc length `σ` as the curve's parameter
/// `σ·(its domain's end)`; `σ` from chord lengths on the reference samples.
///
/// The frames are the exact ones: for a path in a plane `z = const`, `N` the left normal of
/// the exact tangent and `B = +z`; otherwise rotation-minimizing frames integrated by the
/// double reflection on [`Cylinder::REFERENCE_SAMPLES`] samples equally spaced in parameter
/// (global error `O(h⁴)`, far below 1e-12 here), with the closed-curve correction spread by
/// arc length, and interpolated linearly between those samples. The distance from a point is
/// found by the nearest point of a coarse grid of the surface, then Gauss–Newton steps on
/// `(u, v)`; the value reported is the distance to the surface point found, so it can only
/// over-estimate the true distance (a test asserting it ≤ T is conservative).
pub struct Cylinder<'a> {
    profile: &'a AnyCurve<DVec3>,
    anchor: DVec2,
    path: &'a AnyCurve<DVec3>,
    planar: bool,
    /// `(N, B)` at the reference samples (3D paths).
    frames: Vec<(DVec3, DVec3)>,
    path_closed: bool,
    profile_closed: bool,
    shape: Option<Shape<'a>>,
    /// The coarse grid: `(u, v, S(u, v))`, hashed by cells of side `cell`.
    grid: Vec<(f64, f64, DVec3)>,
    cell: f64,
    cells: std::collections::HashMap<(i64, i64, i64), Vec<u32>>,
}

/// A gcyl's scale and twist curves, and the normalized arc length at the reference samples.
struct Shape<'a> {
    scale: Option<&'a AnyCurve<DVec3>>,
    twist: Option<&'a AnyCurve<DVec3>>,
    unit: DVec2,
    sigma: Vec<f64>,
}

impl<'a> Cylinder<'a> {
    /// Rotation-minimizing frames are integrated on this many steps.
    pub const REFERENCE_SAMPLES: usize = 100_000;

    /// The gcyl with a scale curve (`(x, y)` factors) and a twist curve (`x` in degrees), the
    /// profile (less `anchor`) multiplied by `unit` first.
    #[allow(clippy::too_many_arguments)]
    pub fn shaped(
        profile: &'a AnyCurve<DVec3>,
        anchor: DVec2,
        path: &'a AnyCurve<DVec3>,
        scale: Option<&'a AnyCurve<DVec3>>,
        twist: Option<&'a AnyCurve<DVec3>>,
        unit: DVec2,
        grid_u: usize,
        grid_v: usize,
    ) -> Self {
        let (a, b) = path.domain();
        let n = Self::REFERENCE_SAMPLES;
        let mut sigma = Vec::with_capacity(n + 1);
        let mut acc = 0.0;
        let mut last = path.eval(a);
        for i in 0..=n {
            let p = path.eval(a + (b - a) * i as f64 / n as f64);
            acc += p.distance(last);
            last = p;
            sigma.push(acc);
        }
        sigma.iter_mut().for_each(|s| *s /= acc);
        Self::build(profile, anchor, path, Some(Shape { scale, twist, unit, sigma }), grid_u, grid_v)
    }

    /// The gcyl of `profile` (less `anchor`) along `path`, with a coarse grid of
    /// `grid_u × grid_v` points.
    pub fn new(
        profile: &'a AnyCurve<DVec3>,
        anchor: DVec2,
        path: &'a AnyCurve<DVec3>,
        grid_u: usize,
        grid_v: usize,
    ) -> Self {
        Self::build(profile, anchor, path, None, grid_u, grid_v)
    }

    fn build(
        profile: &'a AnyCurve<DVec3>,
        anchor: DVec2,
        path: &'a AnyCurve<DVec3>,
        shape: Option<Shape<'a>>,
        grid_u: usize,
        grid_v: usize,
    ) -> Self {
        use splinekit::frame::{self, FrameMethod, FrameOptions, Side, StartNormal};
        let (a, b) = path.domain();
        let n = Self::REFERENCE_SAMPLES;
        let zs: Vec<f64> = (0..=64).map(|i| path.eval(a + (b - a) * i as f64 / 64.0).z).collect();
        let planar = zs.iter().all(|z| (z - zs[0]).abs() < 1e-12);
        let frames = if planar {
            Vec::new()
        } else {
            let params: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
            let samples = frame::sample(path, &params);
            let options =
                FrameOptions::DEFAULT.with_method(FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left)));
            frame::frames_for_samples(&samples, &options).iter().map(|f| (f.n, f.b)).collect()
        };
        let path_closed = path.eval(a).distance(path.eval(b)) < 1e-9;
        let (c, d) = profile.domain();
        let profile_closed = profile.eval(c).distance(profile.eval(d)) < 1e-9;
        let mut s = Self {
            profile,
            anchor,
            path,
            planar,
            frames,
            path_closed,
            profile_closed,
            shape,
            grid: Vec::new(),
            cell: 1.0,
            cells: std::collections::HashMap::new(),
        };
        let mut grid = Vec::with_capacity((grid_u + 1) * (grid_v + 1));
        for i in 0..=grid_u {
            let u = a + (b - a) * i as f64 / grid_u as f64;
            for j in 0..=grid_v {
                let v = c + (d - c) * j as f64 / grid_v as f64;
                grid.push((u, v, s.eval(u, v)));
            }
        }
        // cells about the grid's spacing
        let spacing = |k: usize| grid[k].2.distance(grid[k + 1].2);
        let mut sp: f64 = 0.0;
        for k in (0..grid.len() - 1).step_by(97) {
            sp = sp.max(spacing(k));
        }
        for k in (0..grid.len().saturating_sub(grid_v + 2)).step_by(89) {
            sp = sp.max(grid[k].2.distance(grid[k + grid_v + 1].2));
        }
        s.cell = sp.max(1e-9);
        for (k, g) in grid.iter().enumerate() {
            s.cells.entry(s.key(g.2)).or_default().push(k as u32);
        }
        s.grid = grid;
        s
    }

    fn key(&self, p: DVec3) -> (i64, i64, i64) {
        let c = (p / self.cell).floor();
        (c.x as i64, c.y as i64, c.z as i64)
    }

    /// `(N, B)` at `u`.
    fn frame(&self, u: f64) -> (DVec3, DVec3) {
        if self.planar {
            let t = self.path.deriv(u).truncate().normalize_or(DVec2::X);
            return (DVec3::new(-t.y, t.x, 0.0), DVec3::Z);
        }
        let (a, b) = self.path.domain();
        let n = Self::REFERENCE_SAMPLES;
        let x = ((u - a) / (b - a) * n as f64).clamp(0.0, n as f64);
        let i = (x.floor() as usize).min(n - 1);
        let f = x - i as f64;
        let (n0, b0) = self.frames[i];
        let (n1, b1) = self.frames[i + 1];
        (n0.lerp(n1, f).normalize(), b0.lerp(b1, f).normalize())
    }

    /// `S(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        let mut q = self.profile.eval(v).truncate() - self.anchor;
        let (mut n, mut b) = self.frame(u);
        if let Some(shape) = &self.shape {
            let (a, e) = self.path.domain();
            let m = Self::REFERENCE_SAMPLES;
            let x = ((u - a) / (e - a) * m as f64).clamp(0.0, m as f64);
            let i = (x.floor() as usize).min(m - 1);
            let sigma = shape.sigma[i] + (shape.sigma[i + 1] - shape.sigma[i]) * (x - i as f64);
            let at = |c: &AnyCurve<DVec3>| c.eval(sigma * c.domain().1);
            q *= shape.unit;
            if let Some(c) = shape.scale {
                q *= at(c).truncate();
            }
            if let Some(c) = shape.twist {
                let (sn, cs) = at(c).x.to_radians().sin_cos();
                (n, b) = (n * cs + b * sn, b * cs - n * sn);
            }
        }
        self.path.eval(u) + n * q.x + b * q.y
    }

    fn wrap(v: f64, (a, b): (f64, f64), closed: bool) -> f64 {
        if closed && b > a { a + (v - a).rem_euclid(b - a) } else { v.clamp(a, b) }
    }

    /// Distance from `p` to the surface (an upper bound, see the type's docs).
    pub fn distance(&self, p: DVec3) -> f64 {
        // the nearest grid point, by rings of cells
        let (cx, cy, cz) = self.key(p);
        let mut best = (f64::INFINITY, usize::MAX);
        for ring in 0i64..4096 {
            if best.1 != usize::MAX && best.0.sqrt() < (ring as f64 - 1.0) * self.cell {
                break;
            }
            for x in cx - ring..=cx + ring {
                for y in cy - ring..=cy + ring {
                    for z in cz - ring..=cz + ring {
                        if (x - cx).abs().max((y - cy).abs()).max((z - cz).abs()) != ring {
                            continue;
                        }
                        if let Some(list) = self.cells.get(&(x, y, z)) {
                            for &k in list {
                                let d = self.grid[k as usize].2.distance_squared(p);
                                if d < best.0 {
                                    best = (d, k as usize);
                                }
                            }
                        }
                    }
                }
            }
        }
        if best.1 == usize::MAX {
            return f64::INFINITY;
        }
        let (mut u, mut v, _) = self.grid[best.1];
        let (du, dv) = (self.path.domain(), self.profile.domain());
        let (hu, hv) = (1e-6 * (du.1 - du.0), 1e-6 * (dv.1 - dv.0));
        let mut dist = best.0.sqrt();
        for _ in 0..12 {
            let s = self.eval(u, v);
            let r = s - p;
            let su = (self.eval(Self::wrap(u + hu, du, self.path_closed), v)
                - self.eval(Self::wrap(u - hu, du, self.path_closed), v))
                / (2.0 * hu);
            let sv = (self.eval(u, Self::wrap(v + hv, dv, self.profile_closed))
                - self.eval(u, Self::wrap(v - hv, dv, self.profile_closed)))
                / (2.0 * hv);
            let (a11, a12, a22) = (su.dot(su), su.dot(sv), sv.dot(sv));
            let (g1, g2) = (su.dot(r), sv.dot(r));
            let det = a11 * a22 - a12 * a12;
            if !(det.abs() > 1e-300) {
                break;
            }
            let (s1, s2) = ((a22 * g1 - a12 * g2) / det, (a11 * g2 - a12 * g1) / det);
            // a step, halved while it does not get closer
            let mut improved = false;
            for h in [1.0, 0.5, 0.25, 0.125] {
                let nu = Self::wrap(u - h * s1, du, self.path_closed);
                let nv = Self::wrap(v - h * s2, dv, self.profile_closed);
                let nd = self.eval(nu, nv).distance(p);
                if nd < dist {
                    improved = dist - nd > 1e-15 * (1.0 + dist);
                    dist = nd;
                    (u, v) = (nu, nv);
                    break;
                }
            }
            if !improved {
                break;
            }
        }
        dist
    }
}

/// The largest distance from the points of [`triangle_points`] to the gcyl `surface`, and
/// the point.
pub fn cylinder_deviation(mesh: &TriMesh, surface: &Cylinder<'_>, m: usize) -> (f64, DVec3) {
    triangle_points(mesh, m)
        .map(|(_, p)| (surface.distance(p), p))
        .fold((0.0, DVec3::ZERO), |a, b| if b.0 > a.0 { b } else { a })
}
