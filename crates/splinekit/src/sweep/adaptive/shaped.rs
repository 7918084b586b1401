//! Adaptive generalized cylinders with a scale or twist curve: the profile's size and turn
//! change along the path.
//!
//! The exact surface is `S(s, v) = P(s) + F(s)·A(s)·q(v)`, written by the path's arc length
//! `s ∈ [0, L]`: the profile point `q` (less its anchor), the linear map `A = R(θ)·D·U` of the
//! profile plane (`U` the unit factors of an overriding scale, `D = diag(sx, sy)` the scale
//! curve's point, `R(θ)` the turn by the twist curve's angle), then the frame `F = [N B]`.
//! The scale and twist curves are read at the normalized arc length `σ = s/L`, at the
//! parameter `σ·n` of a curve of `n` cubic segments (so `d/ds = (n/L)·d/dt`).
//!
//! **The bound.** A point `M` of a mesh triangle between path samples `s₀`, `s₁` (`h = s₁ −
//! s₀`) and profile points `qⱼ`, `qⱼ₊₁` is, with `α` the weight of its corners at `s₁` and
//! `c₀`, `c₁`, `c` as in the [parent module](super) ("Decomposition"), exactly
//!
//! `M = (1−α)·γ_c(s₀) + α·γ_c(s₁) + α(1−α)·(G₁ − G₀)(c₁ − c₀)`, `G = F·A`, `γ_c(s) = P(s) +
//! G(s)·c`.
//!
//! Compare it with the surface point `S(s_α, v*)`, `s_α = s₀ + α·h` and `q(v*)` the profile
//! point nearest to `c` (`|c − q(v*)| ≤ ε`, the profile's flattening):
//!
//! 1. `|γ_c(s_α) − S(s_α, v*)| = |F·A·(c − q(v*))| ≤ ‖A‖·ε` (`F` is an isometry of the profile
//!    plane);
//! 2. linear interpolation at the same parameter: `|(1−α)·γ(s₀) + α·γ(s₁) − γ(s_α)| ≤
//!    α(1−α)·h²/2·max|γ''| ≤ h²/8·max|γ''|` (Peano's kernel of the interpolation error is
//!    positive, so the bound holds for vector curves);
//! 3. `α(1−α)·|(G₁ − G₀)(c₁ − c₀)| ≤ ¼·|Δq|·(‖F₁ − F₀‖·‖A₁‖ + ‖A₁ − A₀‖) ≤ ¼·|Δq|·(ω·a₀ +
//!    a₁)·h`, `|Δq|` the longest profile chord.
//!
//! With `F' = Ω × F` (the frames' angular velocity, `|Ω| ≤ ω`), `γ'' = P'' + F''A c + 2F'A'c +
//! F A''c` and `|F''w| ≤ (|Ω'| + ω²)·|w|`:
//!
//! `|γ''| ≤ κ + (|Ω'| + ω²)·a₀·r + 2ω·a₁·r + a₂·r`,
//!
//! `r` the profile polyline's reach from its anchor, `a₀ ≥ ‖A‖`, `a₁ ≥ ‖A'‖ ≤ |θ'|·‖DU‖ +
//! ‖D'U‖`, `a₂ ≥ ‖A''‖ ≤ (θ'² + |θ''|)·‖DU‖ + 2|θ'|·‖D'U‖ + ‖D''U‖` over the piece. The frames
//! are those of the parent module's exact surface: in a plane `z = const`, `Ω = κ·z`
//! (`|Ω'| = |κ'|`); off it, rotation-minimizing frames, `Ω = κ·B + c·T` with `c` the closed
//! curve's correction spread by arc length (`|c| = Φ/L`, `Φ` the correction angle), so `ω ≤
//! κ + |c|` and `|Ω'| ≤ |κ'| + κ|τ| + |c|·κ`.
//!
//! Every quantity is bounded on the piece from control points, so **the bound is proved**
//! (for the exact frames): `κ ≤ M₁M₂/m³`, `|κ'| ≤ (M₁M₃/m³ + 3κM₂/m)/m` and `κ|τ| ≤ M₃/m³` from
//! the sub-cubic's derivatives (`Mᵢ` the largest `i`-th derivative, from the control points of
//! its hodographs; `m` a lower bound of its speed: the least projection of its hodograph's
//! control points on a direction), `h` at most the sub-cubic's control polygon length; the
//! scale and twist curves' values and derivatives over the piece's `σ` range from the control
//! points of their restrictions (the range itself enclosed by a table of arc lengths at
//! `STEPS` steps a segment and chords: `s(u) ≥ s(uⱼ) + |P(u) − P(uⱼ)|`).
//! A circle path has `κ = 1/R`, `κ' = 0` and exact `h`; a helix `(r cos θ, r sin θ, cθ)` has
//! `κ = r/(r² + c²)`, `τ = c/(r² + c²)`, `κ' = 0` and exact `h`.
//!
//! So **the mesh-to-surface distance is at most `a₀,max·ε + max over path pieces of (h²/8 ·
//! max|γ''| + ¼·|Δq|·(ω·a₀ + a₁)·h)`**, plus, off the plane, the mesh's frames' error (the
//! double reflection's, estimated as in the parent module: each vertex within `2·r·a₀·sin(e/2)`
//! of where the exact frames put it). The arc length the mesh reads the curves at is exact
//! to 1e-9 relative (left out). Corners of a C0 path are joints, left out as in the parent
//! module. Paths that are not chains of cubics, circles or helices, shape curves that are not
//! chains of cubics, Frenet frames, and frames other than rotation-minimizing off the plane
//! are not covered
//! ([`shaped_cylinder_plan`] returns `None`).
//!
//! The bound is not as tight as the parent module's for a plain cylinder (it uses the same
//! parameter on both sides, where that one measures the chord's own deviation), so a
//! constant scale and no twist are planned by the parent's [`super::cylinder_plan`].

use glam::{DVec2, DVec3};

use super::{CylinderFrames, CylinderPlan, MAX_PATH_POINTS, MIN_SHARE, SHARE_REFINE, SHARES, march};
use crate::curve::{AnyCurve, CubicBezier, ParamCurve};
use crate::flatten::{self, Tessellation};
use crate::frame::FrameMethod;

/// A generalized cylinder's scale and twist curves, as `splinekit-io` reads them (see the
/// [module docs](self)).
#[derive(Clone, Copy, Debug)]
pub struct CylinderShape<'a> {
    /// The scale curve: its point's `(x, y)` multiplies the profile's `(x, y)`.
    pub scale: Option<&'a AnyCurve<DVec3>>,
    /// The twist curve: its point's `x` is the profile's turn about the path, in degrees.
    pub twist: Option<&'a AnyCurve<DVec3>>,
    /// Factors applied to the profile (less its anchor) before the scale (an overriding
    /// scale's unit size; `(1, 1)` otherwise).
    pub unit: DVec2,
}

impl CylinderShape<'_> {
    /// The largest factor the shape scales the profile by anywhere (`‖D·U‖` over the scale
    /// curve's control points, which hold it), or `None` when a curve is not a chain of cubics.
    #[must_use]
    pub fn largest_factor(&self) -> Option<f64> {
        let unit = self.unit.abs();
        match self.scale {
            None => Some(unit.max_element()),
            Some(AnyCurve::Piecewise(c)) => Some(
                c.segments()
                    .iter()
                    .flat_map(|b| [b.p0, b.p1, b.p2, b.p3])
                    .map(|p| (p.x.abs() * unit.x).max(p.y.abs() * unit.y))
                    .fold(0.0, f64::max),
            ),
            Some(_) => None,
        }
    }
}

/// Bounds of a shape curve's `x` and `y` over a parameter range: the largest `|value|`, `|d/dt|`
/// and `|d²/dt²|`.
#[derive(Clone, Copy, Default)]
struct ShapeBounds {
    value: DVec2,
    d1: DVec2,
    d2: DVec2,
}

/// The bounds of the chain `segs` over its parameter range `[t0, t1]` (within `[0, n]`).
fn shape_bounds(segs: &[CubicBezier<DVec3>], t0: f64, t1: f64) -> ShapeBounds {
    let n = segs.len();
    let mut out = ShapeBounds::default();
    if n == 0 {
        return out;
    }
    let (t0, t1) = (t0.clamp(0.0, n as f64), t1.clamp(0.0, n as f64));
    let first = (t0.floor() as usize).min(n - 1);
    let last = ((t1.ceil() as usize).max(first + 1)).min(n);
    let abs = |p: DVec3| p.truncate().abs();
    for (k, seg) in segs.iter().enumerate().take(last).skip(first) {
        let a = (t0 - k as f64).clamp(0.0, 1.0);
        let b = (t1 - k as f64).clamp(a, 1.0);
        let sub = seg.subsegment(a, b);
        for p in [sub.p0, sub.p1, sub.p2, sub.p3] {
            out.value = out.value.max(abs(p));
        }
        // the hodograph (a quadratic in t) restricted to [a, b]: its values at the ends and
        // its blossom there are the restriction's control points
        let h = [3.0 * (seg.p1 - seg.p0), 3.0 * (seg.p2 - seg.p1), 3.0 * (seg.p3 - seg.p2)];
        let blossom =
            |x: f64, y: f64| h[0] * ((1.0 - x) * (1.0 - y)) + h[1] * ((1.0 - x) * y + x * (1.0 - y)) + h[2] * (x * y);
        for p in [blossom(a, a), blossom(a, b), blossom(b, b)] {
            out.d1 = out.d1.max(abs(p));
        }
        // the second derivative is linear in t
        let g = |x: f64| {
            (seg.p2 - 2.0 * seg.p1 + seg.p0) * (6.0 * (1.0 - x)) + (seg.p3 - 2.0 * seg.p2 + seg.p1) * (6.0 * x)
        };
        out.d2 = out.d2.max(abs(g(a))).max(abs(g(b)));
    }
    out
}

/// Curvature bounds of a piece of the path: `κ`, `|κ'|` (by arc length), `κ|τ|`, and its length
/// (at most).
#[derive(Clone, Copy)]
struct Bending {
    kappa: f64,
    dkappa: f64,
    ktau: f64,
    length: f64,
}

/// The bounds of [`Bending`] on a cubic (infinite where its speed may vanish).
fn bending(c: &CubicBezier<DVec3>) -> Bending {
    let h = [3.0 * (c.p1 - c.p0), 3.0 * (c.p2 - c.p1), 3.0 * (c.p3 - c.p2)];
    let g = [6.0 * (c.p2 - 2.0 * c.p1 + c.p0), 6.0 * (c.p3 - 2.0 * c.p2 + c.p1)];
    let j = 6.0 * (c.p3 - 3.0 * c.p2 + 3.0 * c.p1 - c.p0);
    let length = h.iter().map(|d| d.length()).sum::<f64>() / 3.0;
    let m1 = h.iter().map(|d| d.length()).fold(0.0, f64::max);
    let m2 = g[0].length().max(g[1].length());
    let m3 = j.length();
    // the speed is at least the least projection of the hodograph's control points on a
    // direction (the hodograph lies in their convex hull)
    let mut m: f64 = 0.0;
    for e in [c.p3 - c.p0, h[0] + h[1] + h[2], h[1]] {
        if let Some(e) = e.try_normalize() {
            m = m.max(h.iter().map(|d| d.dot(e)).fold(f64::INFINITY, f64::min));
        }
    }
    if !(m > 1e-12 * m1) || !m.is_finite() {
        return Bending { kappa: f64::INFINITY, dkappa: f64::INFINITY, ktau: f64::INFINITY, length };
    }
    // κ = |P' × P''|/|P'|³, with P' × P'' a cubic whose Bernstein coefficients are products
    // of the hodographs' (and at most M₂/m²); κ' by t is at most |P' × P'''|/|P'|³ +
    // 3κ·|P'·P''|/|P'|², by arc length over the speed; κτ = (P' × P'')·P'''/(|P' × P''|·|P'|³)
    // ≤ M₃/m³
    let cross = [
        h[0].cross(g[0]),
        h[1].cross(g[0]) * (2.0 / 3.0) + h[0].cross(g[1]) * (1.0 / 3.0),
        h[2].cross(g[0]) * (1.0 / 3.0) + h[1].cross(g[1]) * (2.0 / 3.0),
        h[2].cross(g[1]),
    ];
    let dot = [
        h[0].dot(g[0]),
        h[1].dot(g[0]) * (2.0 / 3.0) + h[0].dot(g[1]) * (1.0 / 3.0),
        h[2].dot(g[0]) * (1.0 / 3.0) + h[1].dot(g[1]) * (2.0 / 3.0),
        h[2].dot(g[1]),
    ];
    let cross_max = cross.iter().map(|x| x.length()).fold(0.0, f64::max);
    let dot_max = dot.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let jerk_cross = h.iter().map(|d| d.cross(j).length()).fold(0.0, f64::max);
    let kappa = (cross_max / (m * m * m)).min(m2 / (m * m));
    let dkappa = ((jerk_cross / (m * m * m)).min(m3 / (m * m)) + 3.0 * kappa * dot_max.min(m1 * m2) / (m * m)) / m;
    Bending { kappa, dkappa, ktau: m3 / (m * m * m), length }
}

/// The path as [`shaped_cylinder_plan`] sees it.
enum Path<'a> {
    /// A chain of cubics with its arc length table (`STEPS + 1` cumulative
    /// lengths a segment, from 0) and total length.
    Cubics { segments: &'a [CubicBezier<DVec3>], planar: bool, table: Vec<f64> },
    /// A circle of this radius (parameter `[0, 1]`).
    Circle(f64),
    /// A helix (parameter `[0, 1]`, constant speed): its curvature, curvature times torsion
    /// and length.
    Helix { kappa: f64, ktau: f64, length: f64 },
}

/// Steps a segment of the path's arc length table (which encloses where the scale and twist
/// curves are read) and of the plan's estimate of its path points.
const STEPS: usize = 16;

impl Path<'_> {
    fn length(&self) -> f64 {
        match self {
            Path::Cubics { table, .. } => table.last().copied().unwrap_or(0.0),
            Path::Circle(r) => std::f64::consts::TAU * r,
            Path::Helix { length, .. } => *length,
        }
    }

    fn segments(&self) -> usize {
        match self {
            Path::Cubics { segments, .. } => segments.len(),
            Path::Circle(_) | Path::Helix { .. } => 1,
        }
    }

    /// An enclosure of the arc length at `u ∈ [0, 1]` of segment `k`.
    fn arclen(&self, k: usize, u: f64) -> (f64, f64) {
        match self {
            Path::Circle(_) | Path::Helix { .. } => {
                let s = self.length() * u;
                (s, s)
            }
            Path::Cubics { segments, table, .. } => {
                let x = (u.clamp(0.0, 1.0) * STEPS as f64).min(STEPS as f64);
                let j = (x.floor() as usize).min(STEPS - 1);
                let base = k * (STEPS + 1) + j;
                let (u0, u1) = (j as f64 / STEPS as f64, (j + 1) as f64 / STEPS as f64);
                let seg = &segments[k];
                let p = seg.eval(u);
                let lo = table[base] + p.distance(seg.eval(u0));
                let hi = table[base + 1] - p.distance(seg.eval(u1));
                (lo.min(hi), hi.max(lo))
            }
        }
    }

    /// The bending bounds of the piece `[a, b]` of segment `k`.
    fn bending(&self, k: usize, a: f64, b: f64) -> Bending {
        match self {
            Path::Cubics { segments, planar, .. } => {
                let mut bend = bending(&segments[k].subsegment(a, b));
                if *planar {
                    bend.ktau = 0.0;
                }
                bend
            }
            Path::Circle(r) => {
                Bending { kappa: 1.0 / r, dkappa: 0.0, ktau: 0.0, length: std::f64::consts::TAU * r * (b - a) }
            }
            Path::Helix { kappa, ktau, length } => {
                Bending { kappa: *kappa, dkappa: 0.0, ktau: *ktau, length: length * (b - a) }
            }
        }
    }
}

/// Everything a piece's bound needs besides the piece.
struct Context<'a> {
    path: Path<'a>,
    scale: Option<&'a [CubicBezier<DVec3>]>,
    twist: Option<&'a [CubicBezier<DVec3>]>,
    unit: DVec2,
    /// The closed-curve correction's rate (radians per unit length) of rotation-minimizing
    /// frames off the plane.
    correction: f64,
}

/// What the profile contributes: its reach from the anchor and its longest chord.
#[derive(Clone, Copy)]
struct Reach {
    r: f64,
    lq: f64,
}

impl Context<'_> {
    /// The shape's norms `a₀`, `a₁`, `a₂` (`‖A‖`, `‖A'‖`, `‖A''‖` by arc length) over the
    /// normalized arc lengths `[σ0, σ1]`.
    fn shape_norms(&self, s0: f64, s1: f64) -> (f64, f64, f64) {
        let len = self.path.length();
        let per = |segs: &[CubicBezier<DVec3>]| segs.len() as f64 / len;
        let (v, d1, d2) = match self.scale {
            Some(segs) => {
                let n = segs.len() as f64;
                let b = shape_bounds(segs, s0 * n, s1 * n);
                let k = per(segs);
                let u = self.unit.abs();
                let norm = |d: DVec2| (d.x * u.x).max(d.y * u.y);
                (norm(b.value), norm(b.d1) * k, norm(b.d2) * k * k)
            }
            None => (self.unit.abs().max_element(), 0.0, 0.0),
        };
        let (t1, t2) = match self.twist {
            Some(segs) => {
                let n = segs.len() as f64;
                let b = shape_bounds(segs, s0 * n, s1 * n);
                let k = per(segs);
                let deg = std::f64::consts::PI / 180.0;
                (b.d1.x * k * deg, b.d2.x * k * k * deg)
            }
            None => (0.0, 0.0),
        };
        (v, t1 * v + d1, (t1 * t1 + t2) * v + 2.0 * t1 * d1 + d2)
    }

    /// The bound of the piece `[a, b]` of segment `k` (without the profile's flattening and
    /// the mesh frames' error), and the shape's largest factor `a₀` on it.
    fn bound(&self, k: usize, a: f64, b: f64, reach: Reach) -> (f64, f64) {
        let len = self.path.length();
        if !(len > 0.0) || !len.is_finite() {
            return (f64::INFINITY, 0.0);
        }
        let bend = self.path.bending(k, a, b);
        let (s0, s1) = (self.path.arclen(k, a).0 / len, self.path.arclen(k, b).1 / len);
        let (a0, a1, a2) = self.shape_norms(s0.clamp(0.0, 1.0), s1.clamp(0.0, 1.0));
        let omega = bend.kappa + self.correction;
        let domega = bend.dkappa + bend.ktau + self.correction * bend.kappa;
        let curvature =
            bend.kappa + (domega + omega * omega) * a0 * reach.r + 2.0 * omega * a1 * reach.r + a2 * reach.r;
        let h = bend.length;
        let b = h * h / 8.0 * curvature + 0.25 * reach.lq * (omega * a0 + a1) * h;
        (if b.is_finite() { b } else { f64::INFINITY }, a0)
    }

    /// An estimate of the path points a plan within `budget` takes: on each of `STEPS`
    /// equal pieces of every segment the bound is fitted as `c₂h² + c₁h` from the piece and its
    /// half, and the piece is counted as the `n` steps that bring that within the budget.
    fn estimate(&self, budget: f64, reach: Reach) -> f64 {
        let mut total = 1.0;
        for k in 0..self.path.segments() {
            for j in 0..STEPS {
                let (a, b) = (j as f64 / STEPS as f64, (j + 1) as f64 / STEPS as f64);
                let (whole, half) = (self.bound(k, a, b, reach).0, self.bound(k, a, 0.5 * (a + b), reach).0);
                if !whole.is_finite() || !half.is_finite() {
                    return f64::INFINITY;
                }
                let c2 = (2.0 * (whole - 2.0 * half)).max(0.0);
                let c1 = (4.0 * half - whole).max(0.0);
                total += (c2 / budget).sqrt().max(c1 / budget).max(1.0 / STEPS as f64);
            }
        }
        total
    }

    /// The path parameters of pieces within `budget`, or `None` past `max_points`.
    fn plan(&self, budget: f64, reach: Reach, max_points: usize, out: &mut Vec<f64>) -> Option<()> {
        out.clear();
        out.push(0.0);
        let mut pieces = Vec::new();
        for k in 0..self.path.segments() {
            march(&|a, b| self.bound(k, a, b, reach).0 <= budget, max_points.saturating_sub(out.len()), &mut pieces)?;
            out.extend(pieces.iter().map(|&t| if t >= 1.0 { (k + 1) as f64 } else { k as f64 + t }));
            if out.len() > max_points {
                return None;
            }
        }
        Some(())
    }
}

/// Whether [`shaped_cylinder_plan`] bounds the surface of `shape` along `path` with `frames`:
/// the path a chain of cubics, a circle or a helix, the scale and twist curves chains of
/// cubics, frames other than Frenet's (which flip at inflections), and rotation-minimizing
/// ones when the path leaves the plane `z = const`.
#[must_use]
pub fn shape_covered(path: &AnyCurve<DVec3>, frames: &CylinderFrames, shape: &CylinderShape<'_>) -> bool {
    let shape_ok = chain(shape.scale).is_some() && chain(shape.twist).is_some() && shape.unit.is_finite();
    // Frenet frames flip at an inflection, even in the plane: not the frames of the bound
    if matches!(frames.options.method, FrameMethod::Frenet) {
        return false;
    }
    let path_ok = match path {
        AnyCurve::Piecewise(c) if !c.segments().is_empty() => {
            planar(c.segments()) || matches!(frames.options.method, FrameMethod::RotationMinimizing(_))
        }
        AnyCurve::Circle(c) => c.radius > 0.0 && c.radius.is_finite(),
        AnyCurve::Helix(h) => {
            let finite = h.radius.is_finite() && h.pitch.is_finite() && h.turns.is_finite() && h.turns != 0.0;
            finite && (h.pitch == 0.0 || matches!(frames.options.method, FrameMethod::RotationMinimizing(_)))
        }
        _ => false,
    };
    shape_ok && path_ok && shape.largest_factor().is_some_and(f64::is_finite)
}

/// Whether every control point has the same `z` (to 1e-12 of the largest coordinate).
fn planar(s: &[CubicBezier<DVec3>]) -> bool {
    let z0 = s.first().map_or(0.0, |b| b.p0.z);
    let size = s.iter().flat_map(|b| [b.p0, b.p1, b.p2, b.p3]).fold(0.0, |m: f64, p| m.max(p.abs().max_element()));
    s.iter().flat_map(|b| [b.p0, b.p1, b.p2, b.p3]).all(|p| (p.z - z0).abs() <= 1e-12 * size)
}

/// The profile and path samples of a generalized cylinder with a scale or twist curve
/// (`shape`) whose mesh stays within `tolerance` of the exact surface (see the
/// [module docs](self)), with about the fewest triangles the bound allows; `None` when the
/// bound does not cover the curves ([`shape_covered`]), or is infinite somewhere along the
/// path (a cusp, a path of no length). A plan that needs more than
/// `max_path_points` path points falls back, as [`super::cylinder_plan`]'s does, to both
/// curves flattened to [`MIN_SHARE`] of the tolerance (the path within `max_path_points`
/// points), with `bound` infinite. The profile is never flattened finer than [`MIN_SHARE`] of
/// `tolerance` over [`CylinderShape::largest_factor`] (when that is positive).
#[must_use]
pub fn shaped_cylinder_plan(
    profile: &AnyCurve<DVec3>,
    anchor: DVec2,
    path: &AnyCurve<DVec3>,
    frames: &CylinderFrames,
    shape: &CylinderShape<'_>,
    tolerance: f64,
    max_path_points: usize,
) -> Option<CylinderPlan> {
    if !shape_covered(path, frames, shape) {
        return None;
    }
    let tolerance = if tolerance > 0.0 && tolerance.is_finite() { tolerance } else { flatten::DEFAULT_TOLERANCE };
    let (scale, twist) = (chain(shape.scale)?, chain(shape.twist)?);
    let largest = shape.largest_factor()?;
    let divisor = if largest > 0.0 { largest } else { 1.0 };
    let max_points = max_path_points.clamp(2, MAX_PATH_POINTS);
    let fallback = || {
        let eps = MIN_SHARE * tolerance;
        Some(CylinderPlan {
            profile_params: flatten::flatten_any(profile, Tessellation::Distance { tolerance: eps / divisor }),
            path_params: flatten::flatten_at_most(path, Tessellation::Distance { tolerance: eps }, max_points),
            bound: f64::INFINITY,
            ring_scale: 1.0,
        })
    };
    let (path_kind, correction) = match path {
        AnyCurve::Piecewise(c) => {
            let s = c.segments();
            let planar = planar(s);
            let mut table = Vec::with_capacity(s.len() * (STEPS + 1));
            let mut acc = 0.0;
            for seg in s {
                table.push(acc);
                for j in 0..STEPS {
                    let (u0, u1) = (j as f64 / STEPS as f64, (j + 1) as f64 / STEPS as f64);
                    acc += seg.arclen_range(u0, u1, 1e-12).length;
                    table.push(acc);
                }
            }
            let correction = if planar { 0.0 } else { closed_correction(s, frames, acc) };
            (Path::Cubics { segments: s, planar, table }, correction)
        }
        AnyCurve::Circle(c) => (Path::Circle(c.radius), 0.0),
        // (r cos θ, r sin θ, c·θ), θ = 2π·turns·u: κ = r/(r² + c²), τ = c/(r² + c²), and no
        // closed-curve correction (a helix that rises is open; one that does not is planar)
        AnyCurve::Helix(h) => {
            let c = h.pitch / std::f64::consts::TAU;
            let q = h.radius * h.radius + c * c;
            let length = std::f64::consts::TAU * h.turns.abs() * q.sqrt();
            let (kappa, ktau) = if q > 0.0 { (h.radius / q, h.radius * c.abs() / (q * q)) } else { (0.0, 0.0) };
            (Path::Helix { kappa, ktau, length }, 0.0)
        }
        _ => return None,
    };
    let planar = match &path_kind {
        Path::Cubics { planar, .. } => *planar,
        Path::Circle(_) => true,
        Path::Helix { ktau, .. } => *ktau == 0.0,
    };
    let ctx = Context { path: path_kind, scale, twist, unit: shape.unit, correction };
    let reach_of = |params: &[f64]| {
        let pts: Vec<DVec2> = params.iter().map(|&v| profile.eval(v).truncate() - anchor).collect();
        Reach {
            r: pts.iter().map(|p| p.length()).fold(0.0, f64::max),
            lq: pts.windows(2).map(|w| w[0].distance(w[1])).fold(0.0, f64::max),
        }
    };
    let triangles = |profile_points: usize, path_points: usize| {
        2 * (profile_points as u64).saturating_sub(1).max(1) * (path_points as u64).saturating_sub(1).max(1)
    };
    let mut reserve: f64 = if planar { 0.0 } else { 0.01 };
    // A share's profile, flattened once. Its path points are estimated before the path is
    // marched (tens of bound evaluations a point): a share whose estimate passes the point
    // limit twice over, or whose triangles by the estimate are twice `beat`, is not marched
    // (`Err` with whether the estimate was finite, `Ok(None)` when the march passes the limit).
    let try_share = |share: f64, reserve: f64, beat: Option<u64>| -> Result<Option<Share>, bool> {
        let params = flatten::flatten_any(profile, Tessellation::Distance { tolerance: share * tolerance / divisor });
        let reach = reach_of(&params);
        let budget = (1.0 - share) * tolerance * (1.0 - reserve);
        let estimate = ctx.estimate(budget, reach);
        let guess = triangles(params.len(), estimate.min(1e15) as usize);
        if estimate > 2.0 * max_points as f64 || beat.is_some_and(|b| guess >= 2 * b) {
            return Err(estimate.is_finite());
        }
        let mut path_params = Vec::new();
        Ok(ctx.plan(budget, reach, max_points, &mut path_params).map(|()| Share {
            triangles: triangles(params.len(), path_params.len()),
            share,
            profile_params: params,
            path_params,
            reach,
        }))
    };
    let mut choice: Option<Share> = None;
    let mut bounded = false;
    for share in SHARES {
        match try_share(share, reserve, choice.as_ref().map(|c| c.triangles)) {
            Err(finite) => bounded |= finite,
            Ok(s) => {
                bounded = true;
                if let Some(s) = s.filter(|s| choice.as_ref().is_none_or(|c| s.triangles < c.triangles)) {
                    choice = Some(s);
                }
            }
        }
    }
    // a bound infinite somewhere (a cusp, a path of no length) covers nothing
    if !bounded {
        return None;
    }
    let Some(mut best) = choice else { return fallback() };
    let base = best.share;
    for d in [-2.0, -1.0, 1.0, 2.0] {
        let s = (base + d * SHARE_REFINE).clamp(MIN_SHARE, 0.95);
        if let Ok(Some(plan)) = try_share(s, reserve, Some(best.triangles))
            && plan.triangles < best.triangles
        {
            best = plan;
        }
    }
    let share = best.share;
    let mut marched = Some(best);
    for _attempt in 0..6 {
        // the best share as marched, then again with the reserve grown
        let plan = match marched.take() {
            Some(plan) => plan,
            None => match try_share(share, reserve, None) {
                Ok(Some(plan)) => plan,
                _ => break,
            },
        };
        let Share { profile_params, path_params, reach, .. } = plan;
        let eps = share * tolerance / divisor;
        let mut worst: f64 = 0.0;
        let errors = (!planar).then(|| super::mesh_frames(path, &path_params, frames, true));
        for (i, w) in path_params.windows(2).enumerate() {
            let k = (w[0].floor() as usize).min(ctx.path.segments() - 1);
            let (a, b) = (w[0] - k as f64, (w[1] - k as f64).min(1.0));
            let (mut bound, a0) = ctx.bound(k, a, b, reach);
            if let Some(f) = &errors {
                let e = f[i].err.max(f[i + 1].err);
                bound += 2.0 * reach.r * a0 * (0.5 * e).min(std::f64::consts::FRAC_PI_2).sin();
            }
            worst = worst.max(bound);
        }
        let bound = largest * eps + worst;
        if bound <= tolerance {
            return Some(CylinderPlan { profile_params, path_params, bound, ring_scale: 1.0 });
        }
        // the frames' error took more than the reserve: the excess and half again
        let over = (bound - tolerance) / ((1.0 - share) * tolerance);
        reserve = (reserve + 1.5 * over).min(0.9);
    }
    fallback()
}

/// One share's samples, as [`shaped_cylinder_plan`] marched them.
struct Share {
    triangles: u64,
    share: f64,
    profile_params: Vec<f64>,
    path_params: Vec<f64>,
    reach: Reach,
}

/// The segments of a shape curve that is a chain of cubics (`Some(None)` for no curve, `None`
/// for another kind).
fn chain(c: Option<&AnyCurve<DVec3>>) -> Option<Option<&[CubicBezier<DVec3>]>> {
    match c {
        None => Some(None),
        Some(AnyCurve::Piecewise(p)) if !p.segments().is_empty() => Some(Some(p.segments())),
        Some(_) => None,
    }
}

/// The rate (radians per unit length) at which the closed-curve fix turns rotation-minimizing
/// frames along a closed path of length `length` (0 on an open one): the angle between the
/// frames transported round the loop and the first, over the length.
fn closed_correction(segments: &[CubicBezier<DVec3>], frames: &CylinderFrames, length: f64) -> f64 {
    let open = super::frame_table(segments, &frames.options.with_close(false));
    let closed = super::frame_table(segments, &frames.options);
    let (Some(a), Some(b)) = (open.last(), closed.last()) else { return 0.0 };
    if a.n.distance(b.n) <= 1e-15 || !(length > 0.0) {
        return 0.0;
    }
    let angle = a.n.cross(b.n).length().atan2(a.n.dot(b.n));
    angle / length
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::PiecewiseCubic;
    use crate::frame::{Side, StartNormal};

    /// Rotation-minimizing frames from the left normal: what `frames auto` gives a path off
    /// the plane.
    fn rmf_frames() -> CylinderFrames {
        CylinderFrames {
            options: crate::frame::FrameOptions::DEFAULT
                .with_method(FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left))),
            corner_angle: None,
        }
    }

    fn line2(points: &[[f64; 2]]) -> AnyCurve<DVec3> {
        let segs = points
            .windows(2)
            .map(|w| {
                let (a, b) = (DVec3::new(w[0][0], w[0][1], 0.0), DVec3::new(w[1][0], w[1][1], 0.0));
                CubicBezier::new(a, a.lerp(b, 1.0 / 3.0), a.lerp(b, 2.0 / 3.0), b)
            })
            .collect();
        AnyCurve::Piecewise(PiecewiseCubic::new(segs, false).unwrap())
    }

    #[test]
    fn bending_bounds_hold_on_a_circle_arc() {
        // a quarter circle of radius 2 as a cubic: κ ≈ 0.5 everywhere
        let k = 0.5522847498 * 2.0;
        let c = CubicBezier::new(
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, k, 0.0),
            DVec3::new(k, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        );
        let whole = bending(&c);
        assert!(whole.kappa >= 0.5 && whole.kappa.is_finite(), "{}", whole.kappa);
        // on a short piece the bound is close to the true curvature
        let piece = bending(&c.subsegment(0.4, 0.45));
        assert!(piece.kappa >= 0.4999 && piece.kappa < 0.56, "{}", piece.kappa);
        assert!(piece.length >= c.arclen_range(0.4, 0.45, 1e-12).length);
    }

    #[test]
    fn shape_bounds_hold_the_curve_and_its_derivatives() {
        let c = line2(&[[1.0, 1.0], [3.0, 2.0], [2.0, 5.0]]);
        let AnyCurve::Piecewise(p) = &c else { unreachable!() };
        let b = shape_bounds(p.segments(), 0.5, 1.5);
        for i in 0..=100 {
            let t = 0.5 + i as f64 / 100.0;
            let v = c.eval(t).truncate().abs();
            let d = c.deriv(t).truncate().abs();
            assert!(v.x <= b.value.x + 1e-12 && v.y <= b.value.y + 1e-12);
            assert!(d.x <= b.d1.x + 1e-12 && d.y <= b.d1.y + 1e-12);
        }
    }

    #[test]
    fn unsupported_curves_are_not_planned() {
        let path = line2(&[[0.0, 0.0], [4.0, 0.0]]);
        let profile = AnyCurve::Circle(crate::curve::Circle::new(0.5));
        let helix = AnyCurve::Helix(crate::curve::Helix::new(1.0, 1.0, 2.0));
        let shape = CylinderShape { scale: Some(&helix), twist: None, unit: DVec2::ONE };
        let frames = rmf_frames();
        assert!(shaped_cylinder_plan(&profile, DVec2::ZERO, &path, &frames, &shape, 0.01, 1000).is_none());
    }
}
