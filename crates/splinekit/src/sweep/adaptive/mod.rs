//! How finely to sample a sweep for a distance tolerance: which profile points, how many
//! slices of a revolution, which path points of a generalized cylinder, so that the *surface*
//! (triangle interiors included, not only the curves) stays within the tolerance of the exact
//! swept surface, with as few triangles as the bound allows.
//!
//! The mesh is built elsewhere ([`super::revolve`], [`super::generalized_cylinder`]); this
//! module only makes the decisions, so both stay independent.
//!
//! # Surfaces of revolution
//!
//! The exact surface turns the profile `Γ` (the curve in the `xy` plane) about `+y`. The mesh
//! is `n` equal slices of angle `θ = 2π/n` of a polyline through profile points `qᵢ`. Each
//! profile chord `[qᵢ, qᵢ₊₁]` and slice `[φ, φ + θ]` make a planar trapezoid, cut into two
//! triangles. Write `k = 1 − cos(θ/2)`.
//!
//! **Lemma (a triangle against its chord).** A point `P = Σ wⱼ·rot(φⱼ, qⱼ)` of a triangle
//! (weights `wⱼ ≥ 0` summing to 1, corners at the angles `φⱼ ∈ {φ, φ + θ}` and the profile points
//! `qⱼ ∈ {qᵢ, qᵢ₊₁}`) has the height `ȳ` and the distance `ρ` from the axis of the chord point
//! `c = Σ wⱼ·qⱼ` (at `x̄ = Σ wⱼ·xⱼ`) but for `ρ`: its horizontal part is `α·e(φ) + β·e(φ + θ)`,
//! `α + β = x̄`, so `ρ² = x̄² − 2αβ·(1 − cos θ)`. When `α` and `β` have the same sign (the two
//! chord ends on one side of the axis), `|x̄|·cos(θ/2) ≤ ρ ≤ |x̄|`: `P` lies, in its meridian
//! half-plane, within `k·|x̄|` of `c` folded to that side. Otherwise `|x̄| ≤ ρ ≤ |x̄| +
//! 2·sin(θ/2)·√(|α|·|β|)`.
//!
//! The distance from `P` to the exact surface is the distance, in the meridian half-plane,
//! from `(ρ, ȳ)` to `Γ` folded onto `x ≥ 0` (rotation about the axis is an isometry, and
//! folding is 1-Lipschitz). Hence, if the profile polyline is within `ε` of `Γ` (two-sided
//! Hausdorff, [`flatten`]), every mesh point is within `ε + k·R` of the exact
//! surface, `R` the largest `|x|` of the chord (a bound of `|x̄|`). The other way, a surface
//! point `rot(φ′, C)` has a chord point `c` within `ε` of `C`, and the trapezoid of that chord
//! contains the chord `[rot(φ, c), rot(φ + θ, c)]` of the circle of `c`, within `k·|c.x|` of
//! `rot(φ′, c)`. So **the two-sided Hausdorff distance between the mesh and the exact surface
//! is at most `max over chords of (εᵢ + k·Rᵢ)`**, where `εᵢ` is the tolerance the chord's
//! piece of the profile was flattened to. Where the profile crosses the axis (`x` of both
//! signs, a self-intersecting surface) the mesh-to-surface term is `2·sin(θ/2)·√(x₋·x₊)`
//! instead (`x₋`, `x₊` the largest distances on each side); the surface-to-mesh direction is
//! not claimed there.
//!
//! The bound is tight: on a bulge (the chord inside the profile, which the shrinking of the
//! slices moves further inside) the two errors add at the midpoint of a triangle's diagonal.
//!
//! # Signs: where the two errors cancel
//!
//! The lemma adds the chord's sagitta and the slices' shrinking everywhere; they add only
//! where the shrinking moves the mesh further from the profile. Take one chord `[q₀, q₃]`
//! (length `L`, unit direction `t̂`, normal `n̂ = t̂⊥`) whose piece of the profile, the
//! sub-cubic `q₀ p₁ p₂ q₃`, is a graph over it (every control leg runs forward along `t̂`, so
//! every tangent does) and does not cross the axis. Write `ê_r` for the direction away from
//! the axis in the meridian half-plane, `a = ê_r·n̂`, `b = ê_r·t̂`, `δ = k·max(|x₀|, |x₃|)`.
//! The piece's height over the chord, `h(s) = 3(1−s)²s·h₁ + 3(1−s)s²·h₂` (`hⱼ` the heights of
//! `pⱼ`), has its exact range `[h₋, h₊]` from the roots of a quadratic.
//!
//! *Mesh to surface.* By the lemma a point `P` of the chord's triangles is, in its meridian
//! half-plane, `c − d·ê_r` with `c` on the chord (at `λ ∈ [0, L]` along it) and `0 ≤ d ≤ δ`:
//! at `λ − d·b` along the chord and `−d·a` across it. While `λ − d·b ∈ [0, L]`, the profile
//! point over it is at a height in `[h₋, h₊]`, so the distance is at most
//! `main = max |h + d·a|` over `h ∈ {h₋, h₊}`, `d ∈ {0, δ}` (the expression is convex in both).
//! A bulge away from the axis (`h ≥ 0` with `a > 0`) gives `h₊ + δ·a`, the lemma's sum when
//! `a = 1`; one toward the axis gives `max(h₊, δ·|a|)`; a flat part (`a ≈ 0`) about `h₊`.
//!
//! *Surface to mesh.* The mesh's section by the meridian half-plane of a surface point
//! `C` (at `λ` along the chord, height `h`) is the chord scaled toward the axis by a factor
//! `g ∈ [cos(θ/2), 1]`: the points `c(μ) − (1−g)·|x(μ)|·ê_r`. The one at `λ` along the chord
//! (it exists while `λ` is within the section's span) is `|h + d·a|` from `C` with `d ≤ δ`:
//! the same `main`.
//!
//! *Past the chord's ends* (within `τ = δ·|b|` of a vertex, the shift along the chord) the
//! other side's profile and mesh take over: the neighbouring chords and their sub-cubics'
//! legs run within an angle `ψ` of `t̂` (checked, `ψ < π/4`, plus `k` for the tilt that
//! scaling by `g` gives a chord, and the neighbours longer than `2τ`), so both stay within
//! `τ·tan ψ` of the line through the vertex, and the distance is at most
//! `end = δ·(|a| + 2·|b|·tan ψ)`. At the profile's ends, or when a check fails, the lemma's
//! own `εᵢ + δ` stands in (with `εᵢ` the tolerance the piece was flattened to).
//!
//! So **the two-sided distance is at most `max over chords of max(main, end)`**, each term
//! computed from the chord as built. [`revolution_plan`] flattens each piece to
//! `T − k·R·w` with `w` the largest `max(0, ê_r·n̂)` over its control legs (`n̂` toward the
//! side it bulges to; `w = 1` for an S-shaped piece), checks every plan chord by chord, and
//! keeps it only when that bound is within `T`; otherwise the lemma's plan (`w = 1`). On the
//! wineglass this only helps the stem, the foot and the rim's top: its walls bulge away from
//! the axis, where the sum is reached.
//!
//! # Inflated rings
//!
//! With every vertex on the surface the slices only shrink the mesh (`d ∈ [0, k·|x̄|]` above),
//! so on a wall bulging away from the axis the two errors add in full. Scaling every ring's
//! radius by `σ = 1/(1 − c·k)` (`c ∈ [0, 1)`, [`RevolutionPlan::ring_scale`]) puts the
//! vertices up to `(σ − 1)·|x|` outside the surface and the lemma's `ρ` in
//! `σ·|x̄|·[cos(θ/2), 1]`: `P = c − d·ê_r` with `d ∈ [(1 − σ)·|x̄|, (1 − σ·(1 − k))·|x̄|]`,
//! an interval around 0 instead of above it. Every argument of "Signs" holds with `d` in that
//! interval (`main` takes both ends, `δ` becomes the larger `|d|`, and `ψ` gains the scaled
//! chords' tilt, at most the interval's width per unit of `|x|`); the lemma's fallback
//! `εᵢ + δ` too (a mesh point is still within `δ` of its chord point, radially). A piece is
//! flattened to `T − R·max(a_max·d_hi, a_min·d_lo, 0)` per unit shift, `[a_min, a_max]` the
//! range of `ê_r·n̂` over its legs: an outward bulge meets the positive end, an inward one
//! the negative end. [`revolution_plan`] tries a few `c` (0 among them) and keeps the plan
//! with the fewest triangles whose checked bound is within `T`. The mesh's vertices are then
//! not on the exact surface, but the mesh as a whole (what the tolerance bounds) is closer to
//! it: on the wineglass at the uniform sweep's accuracy 14 840 triangles instead of 20 672.
//!
//! **The choice.** Every piece of the profile (a cubic segment, or half of one, down to
//! [`MAX_SPLIT_DEPTH`] halvings when that saves points) is flattened to its own tolerance
//! `εᵢ = T − k·Rᵢ`, with `Rᵢ` the largest `|x|` of its control points (the convex hull holds
//! the piece and its chords). Near the axis the profile gets almost all of `T`, at the rim
//! only what the slices leave. The triangle count is about `2·n·(points − 1)`; it is
//! minimised over `n` by evaluating it (the points are counted by flattening, which costs
//! `O(points)`) on a geometric grid of `n` from the fewest slices that leave any tolerance
//! at the largest radius, then around the best. A profile that is not a chain of cubics
//! (a circle, a NURBS…) is one piece with `R` from its bounding box.
//!
//! Cost: about `(T/R)^-½` slices and `(T/size)^-½` profile points, so triangles grow as `1/T`.
//!
//! # Generalized cylinders
//!
//! The exact surface is `S(u, v) = P(u) + N(u)·x(v) + B(u)·y(v)`: the profile `q = (x, y)`
//! (less its anchor, see `ProfileAlign` in `splinekit-io`) carried along the path `P` by the
//! frames `(T, N, B)`. The mesh joins profile points `qⱼ` (a polyline within `ε` of the
//! profile, [`flatten`]) at path points `Pᵢ` with the frames `Fᵢ` the sweep computes there.
//! The exact frames are, for a path in a plane `z = const`, `N` the left normal and `B = +z`
//! (what the sequential, rotation-minimizing and Z-up methods give there, at every sample,
//! to rounding); off the plane, continuous rotation-minimizing frames from the same first
//! frame, with the closed-curve correction spread by arc length.
//!
//! **Decomposition.** Take a triangle of the quad between path points `P₀, P₁` (frames `F₀,
//! F₁`) and profile points `qⱼ, qⱼ₊₁`, and a point `M` of it; `α` the weight of its corners at
//! `P₁`, `c₀`, `c₁` the weighted means of the profile points of its corners at either end
//! (both on the chord `[qⱼ, qⱼ₊₁]`), `c = (1−α)·c₀ + α·c₁` (on the chord too). Then exactly
//!
//! `M = (1−α)·(P₀ + F₀c) + α·(P₁ + F₁c) + α(1−α)·(F₁ − F₀)(c₁ − c₀)`,
//!
//! and with `q(v*)` the profile point nearest to `c` (`|c − q(v*)| ≤ ε`) and `γ_c(u) = P(u) +
//! F(u)c` the curve one profile point sweeps, the distance from `M` to the surface is at most
//!
//! 1. `ε`, the profile's flattening: `|γ_c(u) − S(u, v*)| = |c − q(v*)|` (frames are
//!    isometries);
//! 2. the chord deviation of `γ_c` over the interval, taken as **`d + r·(1 − cos(ψ/2))`**:
//!    `d` the path chord's own deviation (two-sided Hausdorff, computed exactly from the
//!    height polynomial of the sub-cubic over its chord when it is a graph over it, else from
//!    its convex hull), `ψ` a bound of the frames' rotation over the interval (the turning
//!    of the tangent, which bounds a rotation-minimizing frame's rotation and is the planar
//!    frame's: at most the angles between consecutive control legs of the sub-cubic, whose
//!    hodograph lies in their cone, π when they do not lie in a half-space), and `r` the
//!    profile polyline's reach (`|x|` in the plane, where `y` rides along the fixed `B`;
//!    `|q|` off it). For a circular path this is the revolution lemma above; for other
//!    paths it is the osculating circle's version of it, **argued to leading order in the
//!    interval, not proved** (the exact offset curve of a non-circular arc differs at the
//!    next order);
//! 3. the twist term `α(1−α)·|(F₁ − F₀)(c₁ − c₀)| ≤ ¼·|Δq|·2 sin(ψ/2)`, `|Δq|` the longest
//!    profile chord. To first order this displacement runs along the path's tangent (the
//!    rotation's axis is `B` in the plane, `κ·B_Frenet ⊥ T` for rotation-minimizing frames,
//!    and `c₁ − c₀ ⊥ T`), and the surface's tangent plane at `S(u, ·)` contains `T(u)`
//!    (`∂S/∂u ∥ T` for both kinds of frames), within `ψ` of it: the term is taken as
//!    `¼·|Δq|` times the part of `F₁ − F₀` off the bisector `t_b` of the end tangents plus
//!    `sin ψ` times its whole, measured on the frames (for a 3D path: while planning on the
//!    frames computed on `FRAME_TABLE_STEPS` samples a segment and interpolated, in the
//!    final check on the mesh's own), `¼·|Δq|·2 sin(ψ/2)·sin ψ` in the plane (where it lies
//!    along `t_b`). The displacement's own curvature effect (`O(|Δq|²ψ²)`) is left out;
//! 4. off the plane, the frames' error: the mesh's frames come from double reflection on the
//!    plan's samples (and its own closed-curve correction), not the exact ones; each vertex
//!    moves by at most `2r·sin(e/2)` for a frame angle error `e`, estimated as 1.25 times the
//!    difference from the same frames on `FRAME_CHECK_REFINE` times as many samples (the
//!    method's error is `O(h⁴)`). An estimate, not a bound.
//!
//! So **the mesh-to-surface distance is at most `ε + max over path pieces of (d + r·(1 −
//! cos(ψ/2)) + twist + frames)`**, with the caveats of 2–4. The surface-to-mesh direction is
//! not claimed (it holds for circular paths, by the revolution's argument; elsewhere the
//! same decomposition read backwards gives it to the same leading order). Joints of the
//! welded layout (a corner of a C0 path is sampled twice and joined by
//! [`super::welded`]'s mitre or round joint) are left out: the bound covers the pieces
//! between path samples only, not the joint's own geometry. Sequential, Frenet and Z-up
//! frames off the plane are planned the same way, with no error estimate and no claim:
//! their exact frames turn about `T` too, which `ψ` does not bound.
//!
//! **The plan.** [`cylinder_plan`] splits `T` into the profile's share `ε = s·T` (the whole
//! profile flattened to it) and the path's `(1 − s)·T`; each cubic segment of the path is
//! cut by a greedy march (the longest piece within the budget, found by bisection, then
//! equal steps of the same count when they all fit). The triangle count `2·(profile points −
//! 1)·(path points − 1)` is minimised over `s` on a grid (and ±`SHARE_REFINE` around the
//! best). Off the plane a reserve of the path's budget (1 %) is kept for term 4 and the
//! difference between the table's frames and the mesh's, and grown while the plan's checked
//! bound (every term on the mesh's own frames) exceeds `T`. A circle path (always about the origin in the
//! xy plane, `N` toward its centre) with a chain-of-cubics profile is exactly the surface of
//! revolution of the meridian `(R − x, y)` about `+z`, planned by [`revolution_plan`] (its
//! inflated rings included, [`CylinderPlan::ring_scale`]): every claim of the sections
//! above holds for it. A helix is planned by [`shaped_cylinder_plan`] (no shape; its
//! curvature and torsion are constants). A path of another kind (knot, Bézier of any degree,
//! NURBS) gets both curves flattened to [`MIN_SHARE`] of `T`, with no bound claimed.
//!
//! A generalized cylinder with a **scale or twist curve** is planned by
//! [`shaped_cylinder_plan`], with its own bound (proved for the exact frames; see
//! [`shaped`]).
//!
//! Bounded work: no profile flattening finer than [`MIN_SHARE`] of `T` (callers bound its
//! points beforehand), at most `max_path_points` path points (counted as the march goes;
//! past them the fallback), each piece's bisection `BISECTIONS` steps, and a piece no budget admits (a
//! cusp) one step of `2⁻²⁰` of its segment.

use glam::{DVec2, DVec3};

pub mod shaped;
pub use self::shaped::{CylinderShape, shape_covered, shaped_cylinder_plan};

use crate::curve::{AnyCurve, CubicBezier, ParamCurve};
use crate::flatten::{self, Tessellation};
use crate::frame::Frame;

/// The most times a profile segment is halved so that each half gets a tolerance suited to
/// its own distance from the axis.
pub const MAX_SPLIT_DEPTH: u32 = 4;

/// The smallest share of the tolerance a piece of the profile is flattened to: slices that
/// leave a piece less count as leaving it none (so the profile never has more points than a
/// flattening to this share of the tolerance gives, which callers bound beforehand with
/// [`flatten::flatten_count`]).
pub const MIN_SHARE: f64 = 1.0 / 16.0;

/// What [`revolution_plan`] chose.
#[derive(Clone, Debug, PartialEq)]
pub struct RevolutionPlan {
    /// Parameters of the profile samples, ascending over the curve's domain.
    pub params: Vec<f64>,
    /// Slices around the axis.
    pub slices: usize,
    /// The proved bound of the distance between the mesh and the exact surface (see the
    /// [module docs](self)): the sign-aware bound measured on the chosen chords, or the
    /// tolerance when the lemma's plan was chosen; at most the tolerance asked for.
    pub bound: f64,
    /// The factor the profile's distances from the axis are scaled by in the mesh (at least
    /// 1; 1 keeps every vertex on the exact surface): rings a little outside the surface
    /// centre the slices' chords on it (see the [module docs](self), "Inflated rings").
    pub ring_scale: f64,
}

/// Profile samples as planned: the parameters, and the tolerance each chord's piece was
/// flattened to (`eps[i]` for the chord ending at `params[i + 1]`).
#[derive(Default)]
struct Samples {
    params: Vec<f64>,
    eps: Vec<f64>,
}

/// The pieces of a profile that get a tolerance each.
enum Pieces<'a> {
    Cubics(&'a [CubicBezier<DVec3>]),
    Whole { curve: &'a AnyCurve<DVec3>, xmin: f64, xmax: f64 },
}

/// The radial term of a piece whose `x` spans `[xmin, xmax]`: how far the slices may move
/// its mesh points from its chords (see the lemma in the [module docs](self)).
fn radial_term(xmin: f64, xmax: f64, slices: usize) -> f64 {
    let half = std::f64::consts::PI / slices as f64;
    let k = 1.0 - half.cos();
    let r = xmin.abs().max(xmax.abs());
    if xmin < 0.0 && xmax > 0.0 { (k * r).max(2.0 * half.sin() * (-xmin * xmax).sqrt()) } else { k * r }
}

fn x_range(c: &CubicBezier<DVec3>) -> (f64, f64) {
    let xs = [c.p0.x, c.p1.x, c.p2.x, c.p3.x];
    (xs.iter().copied().fold(f64::INFINITY, f64::min), xs.iter().copied().fold(f64::NEG_INFINITY, f64::max))
}

/// Flattens `piece` (the part `[t0, t1]` of a segment starting at parameter `base`) to the
/// tolerance its radius leaves at `slices`, halving it while that saves points; appends the
/// parameters after its start to `out` (when given) and returns how many and the largest
/// `εᵢ + radial` term, or `None` when the slices leave it no tolerance.
fn plan_piece(
    piece: &CubicBezier<DVec3>,
    (base, t0, t1): (f64, f64, f64),
    depth: u32,
    (tolerance, slices, inflate): (f64, usize, Option<f64>),
    scratch: &mut Vec<f64>,
    mut out: Option<&mut Samples>,
) -> Option<(usize, f64)> {
    let knobs = (tolerance, slices, inflate);
    let (xmin, xmax) = x_range(piece);
    let radial = match inflate {
        Some(c) => {
            let (lo, hi) = shift_range(slices, c);
            let (amin, amax) = bulge_range(piece);
            xmin.abs().max(xmax.abs()) * (amax * hi).max(amin * lo).max(0.0)
        }
        None => radial_term(xmin, xmax, slices),
    };
    let eps = tolerance - radial;
    let whole = if eps >= MIN_SHARE * tolerance {
        scratch.clear();
        flatten::flatten_cubic_distance(piece, eps, scratch);
        Some(scratch.len())
    } else {
        None
    };
    // halving helps only where the radial term takes a real share
    let try_split = depth < MAX_SPLIT_DEPTH && radial > 0.05 * tolerance;
    let split = if try_split {
        let (l, r) = piece.split(0.5);
        let tm = 0.5 * (t0 + t1);
        let a = plan_piece(&l, (base, t0, tm), depth + 1, knobs, scratch, None);
        let b = plan_piece(&r, (base, tm, t1), depth + 1, knobs, scratch, None);
        a.zip(b).map(|(a, b)| (a.0 + b.0, a.1.max(b.1), l, r, tm))
    } else {
        None
    };
    match (whole, split) {
        (Some(n), s) if s.as_ref().is_none_or(|s| s.0 >= n) => {
            if let Some(out) = out.as_deref_mut() {
                scratch.clear();
                flatten::flatten_cubic_distance(piece, eps, scratch);
                let h = t1 - t0;
                out.params.extend(scratch.iter().map(|&t| if t >= 1.0 { base + t1 } else { base + t0 + h * t }));
                out.eps.extend(scratch.iter().map(|_| eps));
            }
            Some((n, tolerance))
        }
        (_, Some((_, _, l, r, tm))) => {
            let a = plan_piece(&l, (base, t0, tm), depth + 1, knobs, scratch, out.as_deref_mut())?;
            let b = plan_piece(&r, (base, tm, t1), depth + 1, knobs, scratch, out)?;
            Some((a.0 + b.0, a.1.max(b.1)))
        }
        _ => None,
    }
}

impl Pieces<'_> {
    /// The profile's points (and parameters into `out`) at `slices`, or `None` when the
    /// slices leave some piece no tolerance.
    fn plan(
        &self,
        tolerance: f64,
        slices: usize,
        inflate: Option<f64>,
        mut out: Option<&mut Samples>,
    ) -> Option<usize> {
        let mut scratch = Vec::new();
        match self {
            Pieces::Cubics(segments) => {
                if let Some(out) = out.as_deref_mut() {
                    out.params.clear();
                    out.eps.clear();
                    out.params.push(0.0);
                }
                let mut points = 1;
                for (k, seg) in segments.iter().enumerate() {
                    let (n, _) = plan_piece(
                        seg,
                        (k as f64, 0.0, 1.0),
                        0,
                        (tolerance, slices, inflate),
                        &mut scratch,
                        out.as_deref_mut(),
                    )?;
                    points += n;
                }
                Some(points)
            }
            Pieces::Whole { curve, xmin, xmax } => {
                let eps = tolerance - radial_term(*xmin, *xmax, slices);
                if eps < MIN_SHARE * tolerance {
                    return None;
                }
                let mode = Tessellation::Distance { tolerance: eps };
                match out {
                    Some(out) => {
                        out.params = flatten::flatten_any(curve, mode);
                        out.eps = vec![eps; out.params.len().saturating_sub(1)];
                        Some(out.params.len())
                    }
                    None => usize::try_from(flatten::flatten_count(curve, mode)).ok(),
                }
            }
        }
    }
}

/// The profile samples and slices of a surface of revolution of `profile` (about `+y`, the
/// profile in the `xy` plane) whose mesh stays within `tolerance` of the exact surface, both
/// ways, with about the fewest triangles that bound allows; see the [module docs](self).
/// At most `max_slices` slices (at least 3); if even that many leave the profile no
/// tolerance, `max_slices` with the profile flattened to a tiny share and `bound` above the
/// tolerance.
#[must_use]
pub fn revolution_plan(profile: &AnyCurve<DVec3>, tolerance: f64, max_slices: usize) -> RevolutionPlan {
    let tolerance = if tolerance > 0.0 && tolerance.is_finite() { tolerance } else { flatten::DEFAULT_TOLERANCE };
    let max_slices = max_slices.max(3);
    let pieces = match profile {
        AnyCurve::Piecewise(c) => Pieces::Cubics(c.segments()),
        other => {
            let b = other.bounding_box();
            Pieces::Whole { curve: other, xmin: b.min.x, xmax: b.max.x }
        }
    };
    let mut best = best_plan(&pieces, tolerance, max_slices, None);
    // the inflated plans check every chord of every candidate: worth it for the profiles of
    // modelling (a few hundred points), not for a profile of many thousands
    let small = best.as_ref().is_none_or(|b| b.params.len() <= INFLATE_MAX_POINTS);
    if let (Pieces::Cubics(_), true) = (&pieces, small) {
        for c in INFLATIONS {
            if let Some(p) = best_plan(&pieces, tolerance, max_slices, Some(c)) {
                let count = |p: &RevolutionPlan| (p.params.len() - 1) * p.slices;
                if best.as_ref().is_none_or(|b| count(&p) < count(b)) {
                    best = Some(p);
                }
            }
        }
    }
    best.unwrap_or_else(|| fallback(&pieces, tolerance, max_slices))
}

/// The plan with the fewest triangles whose bound is within `tolerance`: with `signed`, the
/// pieces get the sign-aware tolerances and every plan is checked chord by chord
/// ([`chord_bound`]); without, the pieces get `T − k·R` and the lemma's bound holds as built.
fn best_plan(pieces: &Pieces<'_>, tolerance: f64, max_slices: usize, inflate: Option<f64>) -> Option<RevolutionPlan> {
    let mut samples = Samples::default();
    let mut triangles = |n: usize| {
        if let Some(c) = inflate {
            pieces.plan(tolerance, n, inflate, Some(&mut samples))?;
            let Pieces::Cubics(segments) = pieces else { return None };
            let bound = chord_bounds(segments, &samples, n, c);
            (bound <= tolerance).then(|| 2 * (samples.params.len() as u64 - 1).max(1) * n as u64)
        } else {
            pieces.plan(tolerance, n, None, None).map(|p| 2 * (p as u64 - 1).max(1) * n as u64)
        }
    };
    // the fewest slices that leave every piece some tolerance (bisection: feasibility only
    // grows with n, for the signed plans nearly so)
    let first = if triangles(3).is_some() {
        3
    } else if triangles(max_slices).is_none() {
        return None;
    } else {
        let (mut lo, mut hi) = (3, max_slices);
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if triangles(mid).is_some() { hi = mid } else { lo = mid }
        }
        hi
    };
    // a geometric grid from there up to 16× (the optimum splits the tolerance between the
    // profile and the slices, a few times the fewest), then every n around the best
    // (each candidate is a whole plan of the profile: for a profile of many thousands of
    // points a coarser grid, and around the best at most 33 candidates, so the work stays a
    // few hundred plans whatever the tolerance)
    let mut best = (u64::MAX, first);
    let points_at_first = triangles(first).map_or(0, |t| t / (2 * first as u64) + 1);
    let factor = if points_at_first as usize > INFLATE_MAX_POINTS { 1.08 } else { 1.02 };
    let mut n = first;
    while n <= max_slices && n <= first.saturating_mul(16) {
        if let Some(t) = triangles(n) {
            best = best.min((t, n));
        }
        n = (n + 1).max((n as f64 * factor) as usize);
    }
    let around = best.1;
    let (lo, hi) = (around.saturating_sub(around / 40 + 2).max(first), (around + around / 40 + 2).min(max_slices));
    for n in (lo..=hi).step_by(((hi - lo.min(hi)) / 32).max(1)) {
        if let Some(t) = triangles(n) {
            best = best.min((t, n));
        }
    }
    if best.0 == u64::MAX {
        return None;
    }
    let slices = best.1;
    let mut samples = Samples::default();
    pieces.plan(tolerance, slices, inflate, Some(&mut samples));
    let (bound, ring_scale) = match (pieces, inflate) {
        (Pieces::Cubics(segments), Some(c)) => (chord_bounds(segments, &samples, slices, c), ring_scale(slices, c)),
        _ => (tolerance, 1.0),
    };
    Some(RevolutionPlan { params: samples.params, slices, bound, ring_scale })
}

/// `max_slices` slices leave some piece no tolerance: flatten to [`MIN_SHARE`] of the
/// tolerance and report the bound reached.
fn fallback(pieces: &Pieces<'_>, tolerance: f64, slices: usize) -> RevolutionPlan {
    let eps = tolerance * MIN_SHARE;
    let (curve_params, radial) = match pieces {
        Pieces::Cubics(segments) => {
            let mut params = vec![0.0];
            let mut radial: f64 = 0.0;
            let mut scratch = Vec::new();
            for (k, seg) in segments.iter().enumerate() {
                let (xmin, xmax) = x_range(seg);
                radial = radial.max(radial_term(xmin, xmax, slices));
                scratch.clear();
                flatten::flatten_cubic_distance(seg, eps, &mut scratch);
                params.extend(scratch.iter().map(|&t| if t >= 1.0 { (k + 1) as f64 } else { k as f64 + t }));
            }
            (params, radial)
        }
        Pieces::Whole { curve, xmin, xmax } => {
            (flatten::flatten_any(curve, Tessellation::Distance { tolerance: eps }), radial_term(*xmin, *xmax, slices))
        }
    };
    RevolutionPlan { params: curve_params, slices, bound: eps + radial, ring_scale: 1.0 }
}

/// The inflations tried: the share `c` of the slices' shrinking `k` moved outside the
/// surface by scaling the rings (see [`ring_scale`]); 0 keeps every vertex on the surface.
const INFLATIONS: [f64; 5] = [0.0, 0.25, 0.4, 0.5, 0.6];

/// Profiles whose plain plan has more points than this keep it (the inflated plans' chord
/// checks would take seconds).
const INFLATE_MAX_POINTS: usize = 2048;

/// The radius factor of the vertex rings for the inflation `c`: `1/(1 − c·k)`.
fn ring_scale(slices: usize, c: f64) -> f64 {
    let k = 1.0 - (std::f64::consts::PI / slices as f64).cos();
    1.0 / (1.0 - c * k)
}

/// The range `[d_lo, d_hi]`, per unit of distance from the axis, of how far the mesh lies
/// toward the axis from its profile chord: the rings scaled by `σ` = [`ring_scale`] put a
/// point of a chord at `|x̄|` between `σ·|x̄|·cos(θ/2)` and `σ·|x̄|` (the lemma), so
/// `d ∈ [1 − σ, 1 − σ·(1 − k)]`.
fn shift_range(slices: usize, c: f64) -> (f64, f64) {
    let k = 1.0 - (std::f64::consts::PI / slices as f64).cos();
    let sigma = ring_scale(slices, c);
    ((1.0 - sigma).min(0.0), (1.0 - sigma * (1.0 - k)).max(0.0))
}

/// The range of `ê_r·n̂` over the directions of a piece's control legs, `n̂` the normal
/// toward the side its inner control points bulge to and `ê_r` the direction away from the
/// axis (`[−1, 1]` when it bulges both ways). A guess for the plan; [`chord_bound`] checks
/// what was built.
fn bulge_range(c: &CubicBezier<DVec3>) -> (f64, f64) {
    let (q0, q3) = (c.p0.truncate(), c.p3.truncate());
    let chord = q3 - q0;
    let side = |p: DVec3| chord.perp_dot(p.truncate() - q0);
    let (h1, h2) = (side(c.p1), side(c.p2));
    if h1 * h2 < 0.0 {
        return (-1.0, 1.0);
    }
    let sigma = if h1 + h2 >= 0.0 { 1.0 } else { -1.0 };
    let xs = c.p0.x + c.p1.x + c.p2.x + c.p3.x;
    let er = if xs < 0.0 { -1.0 } else { 1.0 };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for d in [c.p1 - c.p0, c.p2 - c.p1, c.p3 - c.p2, c.p3 - c.p0] {
        if let Some(t) = d.truncate().try_normalize() {
            // the bulge side is sigma times the left normal t⊥
            let a = er * sigma * t.perp().x;
            (lo, hi) = (lo.min(a), hi.max(a));
        }
    }
    if lo > hi { (-1.0, 1.0) } else { (lo, hi) }
}

/// One chord's piece of the profile in the meridian plane: the sub-cubic between two
/// consecutive samples, in 2D.
struct Chord {
    p: [DVec2; 4],
}

/// The largest of [`chord_bound`] over the chords of the profile sampled at `params`.
fn chord_bounds(segments: &[CubicBezier<DVec3>], samples: &Samples, slices: usize, inflate: f64) -> f64 {
    let params = &samples.params;
    let last = segments.len().saturating_sub(1);
    let chords: Vec<Chord> = params
        .windows(2)
        .map(|w| {
            let k = (w[0].floor() as usize).min(last);
            let sub = segments[k].subsegment(w[0] - k as f64, w[1] - k as f64);
            Chord { p: [sub.p0, sub.p1, sub.p2, sub.p3].map(DVec3::truncate) }
        })
        .collect();
    let shift = shift_range(slices, inflate);
    (0..chords.len())
        .map(|i| {
            let prev = i.checked_sub(1).map(|j| &chords[j]);
            chord_bound(&chords[i], prev, chords.get(i + 1), shift, samples.eps[i])
        })
        .fold(0.0, f64::max)
}

/// The sign-aware bound of the mesh of one chord (see the [module docs](self), "Signs"), or
/// infinity where its conditions fail.
fn chord_bound(c: &Chord, prev: Option<&Chord>, next: Option<&Chord>, shift: (f64, f64), eps: f64) -> f64 {
    let [q0, p1, p2, q3] = c.p;
    let len = (q3 - q0).length();
    let crosses = (q0.x < 0.0 && q3.x > 0.0) || (q0.x > 0.0 && q3.x < 0.0);
    let r = q0.x.abs().max(q3.x.abs());
    // the shift toward the axis is within [d_lo, d_hi] (d_lo ≤ 0 ≤ d_hi)
    let (d_lo, d_hi) = (shift.0 * r, shift.1 * r);
    let delta = d_hi.max(-d_lo);
    // the lemma's bound, from the tolerance the piece was flattened to
    let lemma = eps + delta;
    if crosses || len <= 0.0 {
        return if crosses { f64::INFINITY } else { lemma };
    }
    let t = (q3 - q0) / len;
    let n = t.perp();
    // a graph over the chord: every control leg runs forward
    let legs = [p1 - q0, p2 - p1, q3 - p2];
    if legs.iter().any(|d| d.dot(t) <= 0.0 && d.length_squared() > 0.0) {
        return lemma;
    }
    // the exact range of the height h(s) = 3(1−s)²s·h1 + 3(1−s)s²·h2 over the chord
    let (h1, h2) = ((p1 - q0).dot(n), (p2 - q0).dot(n));
    let h = |s: f64| 3.0 * (1.0 - s) * s * ((1.0 - s) * h1 + s * h2);
    // h′(s)/3 = h1·(1 − 4s + 3s²) + h2·(2s − 3s²) = A·s² + B·s + C
    let (qa, qb, qc) = (3.0 * h1 - 3.0 * h2, 2.0 * h2 - 4.0 * h1, h1);
    let (mut lo, mut hi) = (0.0f64, 0.0f64);
    let mut visit = |s: f64| {
        if (0.0..=1.0).contains(&s) {
            lo = lo.min(h(s));
            hi = hi.max(h(s));
        }
    };
    if qa.abs() < 1e-300 {
        if qb != 0.0 {
            visit(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let r = disc.sqrt();
            visit((-qb + r) / (2.0 * qa));
            visit((-qb - r) / (2.0 * qa));
        }
    }
    // rounding of the height polynomial, relative to the chord
    let slack = 1e-12 * len;
    let (lo, hi) = (lo - slack, hi + slack);
    let er = if q0.x + q3.x < 0.0 { -1.0 } else { 1.0 };
    let (a, b) = (er * n.x, er * t.x);
    let main = [lo + d_lo * a, hi + d_lo * a, lo + d_hi * a, hi + d_hi * a, lo, hi]
        .into_iter()
        .map(f64::abs)
        .fold(0.0, f64::max);
    let old = lo.abs().max(hi.abs()) + delta;
    // past the ends: the neighbours' legs and chords within ψ of the chord (plus the tilt of
    // the shrunk chords, at most k)
    if delta * b.abs() == 0.0 {
        return main;
    }
    let (Some(prev), Some(next)) = (prev, next) else { return main.max(old) };
    let mut sin_psi: f64 = 0.0;
    let mut forward = true;
    for ch in [c, prev, next] {
        let dirs = [ch.p[1] - ch.p[0], ch.p[2] - ch.p[1], ch.p[3] - ch.p[2], ch.p[3] - ch.p[0]];
        for d in dirs {
            if let Some(d) = d.try_normalize() {
                forward &= d.dot(t) > 0.0;
                sin_psi = sin_psi.max(t.perp_dot(d).abs());
            }
        }
    }
    // the neighbours reach past the shift along the chord
    let reach = 2.0 * delta * b.abs();
    let long = (prev.p[3] - prev.p[0]).length() > reach && (next.p[3] - next.p[0]).length() > reach;
    // the tilt of a scaled chord: at most the largest relative change of scale
    let psi = sin_psi.asin() + (shift.1 - shift.0);
    if !forward || !long || psi >= std::f64::consts::FRAC_PI_4 {
        return old;
    }
    let end = delta * (a.abs() + 2.0 * b.abs() * psi.tan());
    main.max(end.min(old))
}

// ---------------------------------------------------------------------------------------
// Generalized cylinders

/// The most path points [`cylinder_plan`] makes when its caller gives no smaller limit.
pub const MAX_PATH_POINTS: usize = 1 << 24;

/// The shares of the tolerance the profile is tried at (the path gets the rest), before the
/// best is refined by `SHARE_REFINE` on either side.
const SHARES: [f64; 8] = [MIN_SHARE, 0.15, 0.25, 0.35, 0.45, 0.55, 0.7, 0.85];
const SHARE_REFINE: f64 = 0.025;

/// Bisection steps of a path piece's end in [`cylinder_plan`]'s march.
const BISECTIONS: usize = 32;

/// How much finer than the plan the path is sampled to estimate the error of discrete
/// rotation-minimizing frames (the double reflection is `O(h⁴)`: the finer frames are
/// `8⁴` times closer, so the difference is the coarse frames' error to a few parts in 1000).
const FRAME_CHECK_REFINE: usize = 8;

/// What [`cylinder_plan`] chose.
#[derive(Clone, Debug, PartialEq)]
pub struct CylinderPlan {
    /// Parameters of the profile samples, ascending over its domain.
    pub profile_params: Vec<f64>,
    /// Parameters of the path samples, ascending over its domain (every segment joint of a
    /// chain of cubics among them).
    pub path_params: Vec<f64>,
    /// The bound of the distance from the mesh to the exact surface (see the
    /// [module docs](self), "Generalized cylinders"), computed on the chosen samples; at most
    /// the tolerance when the plan succeeded, infinity when the path is a curve the bound
    /// does not cover (a knot, Bézier curve of any degree or NURBS: the fallback plan).
    pub bound: f64,
    /// The factor the path (a circle about the origin) and the profile's `x` are scaled by
    /// in the mesh: the inflated rings of a revolution ([`RevolutionPlan::ring_scale`]); 1
    /// for every other path.
    pub ring_scale: f64,
}

/// The frames a generalized cylinder's mesh gets along its path, as far as the plan needs
/// to know them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CylinderFrames {
    /// The frame options the mesh's frames are computed with (from the path's samples).
    pub options: crate::frame::FrameOptions,
    /// `Some(angle)` when the path is sampled with [`crate::frame::sample_with_corners`]
    /// (two samples at joints turning by more than `angle`), `None` with
    /// [`crate::frame::sample`].
    pub corner_angle: Option<f64>,
}

/// The path as the plan sees it.
enum PathPieces<'a> {
    /// A chain of cubics; `planar` when every control point has the same `z` (the frames
    /// then turn about `±z` only); off the plane, `table` holds the frames of every segment
    /// at `FRAME_TABLE_STEPS` equal steps (computed as the mesh's are, on those samples).
    Cubics { segments: &'a [CubicBezier<DVec3>], planar: bool, table: Vec<Frame> },
    /// A circle of this radius in the xy plane (`AnyCurve::Circle`, parameter `[0, 1]`).
    Circle(f64),
}

/// The path's pieces and their exact tangent-turning bounds, for [`path_bounds`].
fn piece_of(pieces: &PathPieces<'_>, w: [f64; 2]) -> (f64, f64) {
    match pieces {
        PathPieces::Cubics { segments, .. } => {
            let k = (w[0].floor() as usize).min(segments.len().saturating_sub(1));
            piece_terms(&segments[k].subsegment(w[0] - k as f64, (w[1] - k as f64).min(1.0)))
        }
        PathPieces::Circle(radius) => {
            let psi = std::f64::consts::TAU * (w[1] - w[0]);
            (radius * (1.0 - (0.5 * psi).cos()), psi)
        }
    }
}

/// What a path piece contributes, with the profile fixed: the profile's reach `r` (`|x|` for
/// a planar path, `|q|` otherwise) and longest chord `lq`.
#[derive(Clone, Copy)]
struct ProfileReach {
    r: f64,
    lq: f64,
}

/// The terms of a path piece: the chord's own deviation and a bound of the frames' rotation.
fn piece_terms(c: &CubicBezier<DVec3>) -> (f64, f64) {
    let [q0, p1, p2, q3] = [c.p0, c.p1, c.p2, c.p3];
    let chord = q3 - q0;
    let len = chord.length();
    let legs = [p1 - q0, p2 - p1, q3 - p2];
    let scale = legs.iter().map(|d| d.length()).sum::<f64>();
    // the rotation of the frames is at most the turning of the tangent; the tangent is a
    // positive combination of the (non-zero) legs, and its path on the sphere (the central
    // projection of the hodograph, a planar parabola) is convex inside their spherical
    // triangle: no longer than the two sides through the middle leg
    let mut dirs = [DVec3::ZERO; 3];
    let mut m = 0;
    for d in legs {
        if d.length() > 1e-14 * scale {
            dirs[m] = d.normalize();
            m += 1;
        }
    }
    let dirs = &dirs[..m];
    let mut psi = 0.0;
    for w in dirs.windows(2) {
        psi += w[0].cross(w[1]).length().atan2(w[0].dot(w[1]));
    }
    let half_space = dirs.iter().all(|a| dirs.iter().all(|b| a.dot(*b) > 0.0));
    if !half_space || !psi.is_finite() {
        psi = std::f64::consts::PI;
    }
    // the chord's deviation (two-sided Hausdorff): a graph over the chord (every leg
    // forward) lies within the largest height of 3(1−s)s((1−s)|h1| + s|h2|)
    let forward = len > 0.0 && legs.iter().all(|d| d.dot(chord) > 0.0 || d.length() <= 1e-14 * scale);
    let dev = if forward {
        let t = chord / len;
        let perp = |v: DVec3| (v - t * v.dot(t)).length();
        let (h1, h2) = (perp(p1 - q0), perp(p2 - q0));
        let h = |s: f64| 3.0 * (1.0 - s) * s * ((1.0 - s) * h1 + s * h2);
        let (qa, qb, qc) = (3.0 * h1 - 3.0 * h2, 2.0 * h2 - 4.0 * h1, h1);
        let mut best = h(0.5);
        if qa.abs() < 1e-300 {
            if qb != 0.0 {
                best = best.max(h((-qc / qb).clamp(0.0, 1.0)));
            }
        } else {
            let disc = qb * qb - 4.0 * qa * qc;
            if disc >= 0.0 {
                let r = disc.sqrt();
                best = best.max(h(((-qb + r) / (2.0 * qa)).clamp(0.0, 1.0)));
                best = best.max(h(((-qb - r) / (2.0 * qa)).clamp(0.0, 1.0)));
            }
        }
        best + 1e-12 * len
    } else {
        // the convex hull: every control point's distance from the chord's start
        [p1, p2, q3].iter().map(|p| p.distance(q0)).fold(0.0, f64::max)
    };
    (dev, psi)
}

/// The bound of a path piece, without the profile's and the frames' own errors: the
/// chord's deviation, the slices' shrinking of the profile's reach and the diagonal's twist.
fn piece_bound(dev: f64, psi: f64, reach: ProfileReach, planar: bool) -> f64 {
    piece_shrink(dev, psi, reach) + twist_model(psi, reach, planar)
}

/// The chord's deviation and the slices' shrinking of the profile's reach.
fn piece_shrink(dev: f64, psi: f64, reach: ProfileReach) -> f64 {
    dev + reach.r * (1.0 - (0.5 * psi).cos())
}

/// The diagonal's twist term: `¼·|Δq|·2·sin(ψ/2)` along the path's tangent, of which at
/// most `sin ψ` leaves the surface's tangent plane (see the [module docs](self)); off the
/// plane the rotation's axis may tilt from the normal plane, which the plan guesses at as
/// much again and [`path_bounds`] checks on the frames as built.
fn twist_model(psi: f64, reach: ProfileReach, planar: bool) -> f64 {
    let t = 0.5 * reach.lq * (0.5 * psi).sin() * psi.min(std::f64::consts::FRAC_PI_2).sin();
    if planar { t } else { 2.0 * t }
}

impl PathPieces<'_> {
    fn planar(&self) -> bool {
        match self {
            PathPieces::Cubics { planar, .. } => *planar,
            PathPieces::Circle(_) => true,
        }
    }

    /// The bound of the piece `[a, b]` of segment `k` (parameter `[a, b]` of the circle).
    fn bound(&self, k: usize, a: f64, b: f64, reach: ProfileReach) -> f64 {
        match self {
            PathPieces::Cubics { segments, planar, table } => {
                let (dev, psi) = piece_terms(&segments[k].subsegment(a, b));
                if *planar || table.is_empty() {
                    piece_bound(dev, psi, reach, *planar)
                } else {
                    let at = |u: f64| table_frame(table, k, u);
                    piece_shrink(dev, psi, reach) + twist_of(at(a), at(b), psi, reach)
                }
            }
            PathPieces::Circle(radius) => {
                let psi = std::f64::consts::TAU * (b - a);
                piece_bound(radius * (1.0 - (0.5 * psi).cos()), psi, reach, true)
            }
        }
    }

    /// The path parameters whose every piece is within `budget` (appended to `out` when
    /// given), or `None` past `max_points`.
    fn plan(
        &self,
        budget: f64,
        reach: ProfileReach,
        max_points: usize,
        mut out: Option<&mut Vec<f64>>,
    ) -> Option<usize> {
        if let Some(out) = out.as_deref_mut() {
            out.clear();
            out.push(0.0);
        }
        let mut points = 1usize;
        match self {
            PathPieces::Circle(_) => {
                // equal steps: the fewest whose step is within the budget
                let ok = |n: usize| self.bound(0, 0.0, 1.0 / n as f64, reach) <= budget;
                let mut n = 3usize;
                if !ok(n) {
                    let mut hi = 6usize;
                    while !ok(hi) {
                        if hi >= max_points {
                            return None;
                        }
                        hi = (hi * 2).min(max_points);
                    }
                    let mut lo = hi / 2;
                    while hi - lo > 1 {
                        let mid = lo + (hi - lo) / 2;
                        if ok(mid) { hi = mid } else { lo = mid }
                    }
                    n = hi;
                }
                if n + 1 > max_points {
                    return None;
                }
                if let Some(out) = out {
                    out.extend((1..n).map(|i| i as f64 / n as f64));
                    out.push(1.0);
                }
                Some(n + 1)
            }
            PathPieces::Cubics { segments, .. } => {
                let mut pieces = Vec::new();
                for k in 0..segments.len() {
                    self.segment_pieces(k, budget, reach, max_points.saturating_sub(points), &mut pieces)?;
                    points += pieces.len();
                    if points > max_points {
                        return None;
                    }
                    if let Some(out) = out.as_deref_mut() {
                        out.extend(pieces.iter().map(|&t| if t >= 1.0 { (k + 1) as f64 } else { k as f64 + t }));
                    }
                }
                Some(points)
            }
        }
    }

    /// The ends (after 0, up to 1) of the pieces of segment `k` within the budget ([`march`]).
    fn segment_pieces(&self, k: usize, budget: f64, reach: ProfileReach, max: usize, out: &mut Vec<f64>) -> Option<()> {
        march(&|a, b| self.bound(k, a, b, reach) <= budget, max, out)
    }
}

/// The ends (after 0, up to 1) of pieces of `[0, 1]` that are each `ok`, at most `max` of
/// them (`None` past that): equal steps when they are all `ok`, else the greedy march (each
/// piece the longest found `ok` by bisection) that found their count.
fn march(ok: &dyn Fn(f64, f64) -> bool, max: usize, out: &mut Vec<f64>) -> Option<()> {
    out.clear();
    let mut a = 0.0;
    // the last piece's length: where the next one's search starts
    let mut step: f64 = 1.0;
    while a < 1.0 {
        if out.len() >= max {
            return None;
        }
        if ok(a, 1.0) {
            out.push(1.0);
            break;
        }
        // bracket the end from the last length (growing it while it fits), then bisect
        // to a thousandth of the piece
        let (mut lo, mut hi) = (a, 1.0);
        let mut probe = (a + step).min(1.0);
        for _ in 0..BISECTIONS {
            if probe >= hi {
                break;
            }
            if ok(a, probe) {
                lo = probe;
                probe = a + 2.0 * (probe - a);
            } else {
                hi = probe;
                break;
            }
        }
        for _ in 0..BISECTIONS {
            if hi - lo <= 1e-3 * (lo - a) {
                break;
            }
            let mid = 0.5 * (lo + hi);
            if ok(a, mid) { lo = mid } else { hi = mid }
        }
        step = (lo - a).max(1e-9);
        // a piece no budget admits (a cusp): one step of the bisection's resolution
        let b = if lo > a { lo } else { (a + 1.0 / (1u64 << 20) as f64).min(1.0) };
        out.push(b);
        a = b;
    }
    let m = out.len();
    if m > 1 && (0..m).all(|i| ok(i as f64 / m as f64, (i + 1) as f64 / m as f64)) {
        out.clear();
        out.extend((1..=m).map(|i| i as f64 / m as f64));
    }
    Some(())
}

/// The reach around `anchor` of the profile's polyline at `params` (`|x|` for a planar path,
/// `|q|` otherwise: every chord point is within it) and its longest chord.
fn profile_reach(profile: &AnyCurve<DVec3>, anchor: DVec2, params: &[f64], planar: bool) -> ProfileReach {
    let pts: Vec<DVec2> = params.iter().map(|&v| profile.eval(v).truncate() - anchor).collect();
    let r = pts.iter().map(|p| if planar { p.x.abs() } else { p.length() }).fold(0.0, f64::max);
    let lq = pts.windows(2).map(|w| w[0].distance(w[1])).fold(0.0, f64::max);
    ProfileReach { r, lq }
}

/// The profile and path samples of a generalized cylinder (the profile `q`, less `anchor`,
/// carried along `path` by the frames `frames`) whose mesh stays within `tolerance` of the
/// exact surface `S(u, v) = P(u) + N(u)·q(v).x + B(u)·q(v).y`, with about the fewest
/// triangles the bound allows; see the [module docs](self), "Generalized cylinders".
///
/// At most `max_path_points` path points: a plan that needs more (or a path the bound does
/// not cover) falls back to flattening both curves to [`MIN_SHARE`] of the tolerance (the
/// path within `max_path_points` points, [`flatten::flatten_at_most`]), with `bound`
/// infinite. The profile is never flattened finer than [`MIN_SHARE`] of the tolerance
/// (callers bound its points beforehand with [`flatten::flatten_count`]).
#[must_use]
pub fn cylinder_plan(
    profile: &AnyCurve<DVec3>,
    anchor: DVec2,
    path: &AnyCurve<DVec3>,
    frames: &CylinderFrames,
    tolerance: f64,
    max_path_points: usize,
) -> CylinderPlan {
    let tolerance = if tolerance > 0.0 && tolerance.is_finite() { tolerance } else { flatten::DEFAULT_TOLERANCE };
    let max_points = max_path_points.clamp(2, MAX_PATH_POINTS);
    let fallback = || {
        let eps = MIN_SHARE * tolerance;
        CylinderPlan {
            profile_params: flatten::flatten_any(profile, Tessellation::Distance { tolerance: eps }),
            path_params: flatten::flatten_at_most(path, Tessellation::Distance { tolerance: eps }, max_points),
            bound: f64::INFINITY,
            ring_scale: 1.0,
        }
    };
    // a circle (about the origin in the xy plane, N toward its centre): the surface of
    // revolution of the meridian (R − x, y) about +z, planned as one
    if let (AnyCurve::Circle(c), AnyCurve::Piecewise(q)) = (path, profile) {
        let meridian = |p: DVec3| DVec3::new(c.radius - (p.x - anchor.x), p.y - anchor.y, 0.0);
        let segments: Vec<CubicBezier<DVec3>> = q
            .segments()
            .iter()
            .map(|b| CubicBezier::new(meridian(b.p0), meridian(b.p1), meridian(b.p2), meridian(b.p3)))
            .collect();
        if let Ok(m) = crate::curve::PiecewiseCubic::new(segments, q.is_closed()) {
            let plan = revolution_plan(&AnyCurve::Piecewise(m), tolerance, max_points - 1);
            let n = plan.slices;
            let mut path_params: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
            path_params.push(1.0);
            return CylinderPlan {
                profile_params: plan.params,
                path_params,
                bound: plan.bound,
                ring_scale: plan.ring_scale,
            };
        }
    }
    let pieces = match path {
        AnyCurve::Piecewise(c) if !c.segments().is_empty() => {
            let s = c.segments();
            let z0 = s[0].p0.z;
            let size =
                s.iter().flat_map(|b| [b.p0, b.p1, b.p2, b.p3]).fold(0.0, |m: f64, p| m.max(p.abs().max_element()));
            let planar = s.iter().flat_map(|b| [b.p0, b.p1, b.p2, b.p3]).all(|p| (p.z - z0).abs() <= 1e-12 * size);
            let table = if planar { Vec::new() } else { frame_table(s, &frames.options) };
            PathPieces::Cubics { segments: s, planar, table }
        }
        AnyCurve::Circle(c) => PathPieces::Circle(c.radius),
        // a helix: the shaped plan's bound (its curvature and torsion are constants), with no
        // shape
        _ => {
            let shape = CylinderShape { scale: None, twist: None, unit: DVec2::ONE };
            return shaped_cylinder_plan(profile, anchor, path, frames, &shape, tolerance, max_path_points)
                .unwrap_or_else(fallback);
        }
    };
    let planar = pieces.planar();
    // frames whose error the bound estimates: rotation-minimizing frames off the plane
    let rmf = !planar && matches!(frames.options.method, crate::frame::FrameMethod::RotationMinimizing(_));
    // the frames' error is found once a plan is made: keep a reserve of the path's budget
    // for it (and for the twist term off the plane), grown while the plan's checked bound
    // exceeds the tolerance
    let mut reserve = if planar { 0.0 } else { 0.01 };
    // Before marching the path for a share (tens of bound evaluations a point), its points are
    // estimated by flattening it to the whole path budget (the chord term alone, counted
    // without placing a chord): a share whose estimate exceeds the point limit twice over, or
    // whose triangles by that estimate cannot beat the best plan so far, is not marched.
    let triangles = |profile_points: usize, path_points: u64| {
        2 * (profile_points as u64).saturating_sub(1).max(1) * path_points.saturating_sub(1).max(1)
    };
    let try_share = |share: f64, reserve: f64, beat: Option<u64>| -> Option<(u64, Vec<f64>, ProfileReach)> {
        let eps = share * tolerance;
        let params = flatten::flatten_any(profile, Tessellation::Distance { tolerance: eps });
        let budget = (1.0 - share) * tolerance * (1.0 - reserve);
        if let AnyCurve::Piecewise(_) = path {
            let estimate = flatten::flatten_count(path, Tessellation::Distance { tolerance: budget });
            if estimate > 2 * max_points as u64 || beat.is_some_and(|b| triangles(params.len(), estimate) >= 2 * b) {
                return None;
            }
        }
        let reach = profile_reach(profile, anchor, &params, planar);
        let n = pieces.plan(budget, reach, max_points, None)?;
        Some((triangles(params.len(), n as u64), params, reach))
    };
    // the share with the fewest triangles: a grid, then a finer step around the best
    let mut choice: Option<(u64, f64)> = None;
    for share in SHARES {
        if let Some((t, _, _)) = try_share(share, reserve, choice.map(|c| c.0)) {
            choice = Some(choice.map_or((t, share), |c| if t < c.0 { (t, share) } else { c }));
        }
    }
    let Some((mut count, mut share)) = choice else { return fallback() };
    let base = share;
    for d in [-2.0, -1.0, 1.0, 2.0] {
        let s = (base + d * SHARE_REFINE).clamp(MIN_SHARE, 0.95);
        if let Some((t, _, _)) = try_share(s, reserve, Some(count))
            && t < count
        {
            (count, share) = (t, s);
        }
    }
    let mut best: Option<CylinderPlan> = None;
    for _attempt in 0..6 {
        let Some((_, profile_params, reach)) = try_share(share, reserve, None) else { break };
        let budget = (1.0 - share) * tolerance * (1.0 - reserve);
        let mut path_params = Vec::new();
        if pieces.plan(budget, reach, max_points, Some(&mut path_params)).is_none() {
            break;
        }
        let eps = share * tolerance;
        let mesh = (!planar).then(|| mesh_frames(path, &path_params, frames, rmf));
        let bound = eps + path_bounds(&pieces, &path_params, reach, mesh.as_deref());
        let plan = CylinderPlan { profile_params, path_params, bound, ring_scale: 1.0 };
        if bound <= tolerance {
            return plan;
        }
        if best.as_ref().is_none_or(|b| plan.bound < b.bound) {
            best = Some(plan);
        }
        // the reserve did not cover what the checks found: the excess and half again
        let over = (bound - tolerance) / ((1.0 - share) * tolerance);
        reserve = (reserve + 1.5 * over).min(0.9);
    }
    best.unwrap_or_else(fallback)
}

/// The twist term of a piece between the frames `f0` and `f1` (see the
/// [module docs](self)): `¼·|Δq|` times the part of `(F₁ − F₀)` off the end tangents'
/// bisector, plus `sin ψ` times its whole.
fn twist_of(f0: Frame, f1: Frame, psi: f64, reach: ProfileReach) -> f64 {
    let (a, c) = (f1.n - f0.n, f1.b - f0.b);
    let tb = (f0.t + f1.t).try_normalize().unwrap_or(f0.t);
    let perp = |v: DVec3| v - tb * v.dot(tb);
    let off = (perp(a).length_squared() + perp(c).length_squared()).sqrt();
    let along = (a.length_squared() + c.length_squared()).sqrt();
    0.25 * reach.lq * (off + along * psi.min(std::f64::consts::FRAC_PI_2).sin())
}

/// Steps per segment of the frame table the march reads the twist term from.
const FRAME_TABLE_STEPS: usize = 64;

/// The frames of every segment at `FRAME_TABLE_STEPS + 1` equal steps (each segment's ends
/// sampled with its own tangents, so a corner turns between two samples at one point), as
/// `options` computes them on those samples, closed-curve correction included.
fn frame_table(segments: &[CubicBezier<DVec3>], options: &crate::frame::FrameOptions) -> Vec<Frame> {
    let steps = FRAME_TABLE_STEPS;
    let samples: Vec<crate::frame::CurveSample> = segments
        .iter()
        .enumerate()
        .flat_map(|(k, seg)| {
            (0..=steps).map(move |j| {
                let t = j as f64 / steps as f64;
                crate::frame::CurveSample { u: k as f64 + t, ..crate::frame::CurveSample::at(seg, t) }
            })
        })
        .collect();
    crate::frame::frames_for_samples(&samples, options)
}

/// The frame of segment `k` at its parameter `u ∈ [0, 1]`, interpolated in [`frame_table`].
fn table_frame(table: &[Frame], k: usize, u: f64) -> Frame {
    let steps = FRAME_TABLE_STEPS;
    let x = (u.clamp(0.0, 1.0) * steps as f64).min(steps as f64);
    let j = (x.floor() as usize).min(steps - 1);
    let base = k * (steps + 1) + j;
    let (Some(a), Some(b)) = (table.get(base), table.get(base + 1)) else { return Frame::IDENTITY };
    let f = x - j as f64;
    Frame::from_tangent_normal(a.t.lerp(b.t, f), a.n.lerp(b.n, f))
}

/// The mesh's frames at one path parameter: at its first and last sample (two at a corner
/// of the welded layout), and an estimate of their angle from the exact frames.
#[derive(Clone, Copy)]
struct ParamFrames {
    first: Frame,
    last: Frame,
    err: f64,
}

/// The largest bound over the path's pieces at `params` (without the profile's own error):
/// [`piece_shrink`], the twist term (measured on the mesh's frames `frames` when given, else
/// [`twist_model`] of a planar path) and the frames' error as `2r·sin(e/2)`.
fn path_bounds(pieces: &PathPieces<'_>, params: &[f64], reach: ProfileReach, frames: Option<&[ParamFrames]>) -> f64 {
    let mut worst: f64 = 0.0;
    for (i, w) in params.windows(2).enumerate() {
        let (dev, psi) = piece_of(pieces, [w[0], w[1]]);
        let mut b = piece_shrink(dev, psi, reach);
        match frames {
            None => b += twist_model(psi, reach, true),
            Some(f) => {
                b += twist_of(f[i].last, f[i + 1].first, psi, reach);
                b += 2.0 * reach.r * (0.5 * f[i].err.max(f[i + 1].err)).min(std::f64::consts::FRAC_PI_2).sin();
            }
        }
        worst = worst.max(b);
    }
    worst
}

/// The mesh's frames at `params` ([`ParamFrames`]); with `estimate`, their error against the
/// exact rotation-minimizing frames: the difference from the frames computed the same way on
/// `FRAME_CHECK_REFINE` times as many samples, times 1.25.
fn mesh_frames(path: &AnyCurve<DVec3>, params: &[f64], frames: &CylinderFrames, estimate: bool) -> Vec<ParamFrames> {
    let sample = |params: &[f64]| match (path, frames.corner_angle) {
        (AnyCurve::Piecewise(pc), Some(angle)) => crate::frame::sample_with_corners(pc, params, angle),
        _ => crate::frame::sample(path, params),
    };
    let cs = sample(params);
    let cf = crate::frame::frames_for_samples(&cs, &frames.options);
    let (fs, ff) = if estimate {
        let mut fine_params = Vec::with_capacity(params.len().saturating_mul(FRAME_CHECK_REFINE));
        for w in params.windows(2) {
            fine_params
                .extend((0..FRAME_CHECK_REFINE).map(|j| w[0] + (w[1] - w[0]) * j as f64 / FRAME_CHECK_REFINE as f64));
        }
        fine_params.extend(params.last());
        let fs = sample(&fine_params);
        let ff = crate::frame::frames_for_samples(&fs, &frames.options);
        (fs, ff)
    } else {
        (Vec::new(), Vec::new())
    };
    let mut out: Vec<Option<ParamFrames>> = vec![None; params.len()];
    let (mut j, mut p) = (0usize, 0usize);
    for (s, f) in cs.iter().zip(&cf) {
        while p + 1 < params.len() && (params[p + 1] - s.u).abs() <= (params[p] - s.u).abs() {
            p += 1;
        }
        let mut e = 0.0;
        if estimate && !ff.is_empty() {
            // the fine sample at the same point (and the same side of a corner)
            while j + 1 < fs.len() && !(fs[j].u == s.u && fs[j].tangent == s.tangent) {
                j += 1;
            }
            let g = ff[j.min(ff.len() - 1)];
            e = 1.25 * f.n.cross(g.n).length().atan2(f.n.dot(g.n));
            j += 1;
        }
        let Some(slot) = out.get_mut(p) else { continue };
        *slot = Some(match *slot {
            None => ParamFrames { first: *f, last: *f, err: e },
            Some(q) => ParamFrames { first: q.first, last: *f, err: q.err.max(e) },
        });
    }
    let fallback = ParamFrames { first: Frame::IDENTITY, last: Frame::IDENTITY, err: std::f64::consts::PI };
    out.into_iter().map(|o| o.unwrap_or(fallback)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{Circle, Helix, PiecewiseCubic};
    use crate::frame::{FrameMethod, FrameOptions, Side, StartNormal};

    fn cubic(points: [[f64; 3]; 4]) -> AnyCurve<DVec3> {
        let [a, b, c, d] = points.map(DVec3::from);
        AnyCurve::Piecewise(PiecewiseCubic::new(vec![CubicBezier::new(a, b, c, d)], false).unwrap())
    }

    fn rmf() -> CylinderFrames {
        let method = FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left));
        CylinderFrames { options: FrameOptions::DEFAULT.with_method(method), corner_angle: Some(0.01) }
    }

    #[test]
    fn odd_input_gives_bounded_plans_without_panics() {
        let profile = cubic([[0.0, 0.0, 0.0], [0.3, 0.1, 0.0], [0.2, 0.4, 0.0], [-0.1, 0.3, 0.0]]);
        let point = cubic([[1.0, 1.0, 0.0]; 4]);
        let path = cubic([[0.0, 0.0, 0.0], [1.0, 0.0, 0.5], [2.0, 1.0, -0.5], [3.0, 1.0, 1.0]]);
        let cusp = cubic([[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]);
        let circle = AnyCurve::Circle(Circle::new(0.5));
        let helix = AnyCurve::Helix(Helix::new(1.0, 0.5, 3.0));
        let cases: [(&AnyCurve<DVec3>, &AnyCurve<DVec3>); 7] = [
            (&point, &path),
            (&profile, &point),
            (&point, &point),
            (&circle, &path),
            (&profile, &circle),
            (&profile, &cusp),
            (&profile, &helix),
        ];
        for (i, (q, p)) in cases.iter().enumerate() {
            for t in [1e-2, 1e-4, 0.0, f64::NAN, f64::INFINITY] {
                let plan = cylinder_plan(q, DVec2::ZERO, p, &rmf(), t, 10_000);
                assert!(plan.path_params.len() >= 2 && plan.path_params.len() <= 10_000, "{i} {t}");
                assert!(plan.profile_params.len() >= 2, "{i} {t}");
                assert!(plan.ring_scale >= 1.0 && plan.ring_scale.is_finite(), "{i} {t}");
                let t = if t > 0.0 && t.is_finite() { t } else { flatten::DEFAULT_TOLERANCE };
                // every path here is one the bound covers (the helix by the shaped plan):
                // a plan within the tolerance
                assert!(plan.bound <= t, "{i} {t}: {}", plan.bound);
            }
        }
    }

    #[test]
    fn the_path_pieces_meet_their_budget() {
        // a planar S-curve: every piece of the plan is within the path's share
        let profile = cubic([[-0.2, 0.0, 0.0], [0.0, 0.3, 0.0], [0.1, -0.3, 0.0], [0.2, 0.0, 0.0]]);
        let path = cubic([[0.0, 0.0, 0.0], [2.0, 2.0, 0.0], [2.0, -2.0, 0.0], [4.0, 0.0, 0.0]]);
        let frames = CylinderFrames { options: FrameOptions::DEFAULT, corner_angle: None };
        let plan = cylinder_plan(&profile, DVec2::ZERO, &path, &frames, 1e-3, 100_000);
        assert!(plan.bound <= 1e-3);
        let AnyCurve::Piecewise(pc) = &path else { unreachable!() };
        let pieces = PathPieces::Cubics { segments: pc.segments(), planar: true, table: Vec::new() };
        let reach = profile_reach(&profile, DVec2::ZERO, &plan.profile_params, true);
        assert!(reach.r > 0.1 && reach.lq > 0.0);
        let path_part = path_bounds(&pieces, &plan.path_params, reach, None);
        assert!(path_part > 0.0 && path_part < 1e-3);
    }
}
