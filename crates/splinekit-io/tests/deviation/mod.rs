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
