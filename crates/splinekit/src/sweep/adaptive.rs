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
//! Hausdorff, [`flatten`](crate::flatten)), every mesh point is within `ε + k·R` of the exact
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

use glam::DVec3;

use crate::curve::{AnyCurve, CubicBezier, ParamCurve};
use crate::flatten::{self, Tessellation};

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
    /// [module docs](self)); at most the tolerance asked for.
    pub bound: f64,
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
    tolerance: f64,
    slices: usize,
    scratch: &mut Vec<f64>,
    mut out: Option<&mut Vec<f64>>,
) -> Option<(usize, f64)> {
    let (xmin, xmax) = x_range(piece);
    let radial = radial_term(xmin, xmax, slices);
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
        let a = plan_piece(&l, (base, t0, tm), depth + 1, tolerance, slices, scratch, None);
        let b = plan_piece(&r, (base, tm, t1), depth + 1, tolerance, slices, scratch, None);
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
                out.extend(scratch.iter().map(|&t| if t >= 1.0 { base + t1 } else { base + t0 + h * t }));
            }
            Some((n, tolerance))
        }
        (_, Some((_, _, l, r, tm))) => {
            let a = plan_piece(&l, (base, t0, tm), depth + 1, tolerance, slices, scratch, out.as_deref_mut())?;
            let b = plan_piece(&r, (base, tm, t1), depth + 1, tolerance, slices, scratch, out)?;
            Some((a.0 + b.0, a.1.max(b.1)))
        }
        _ => None,
    }
}

impl Pieces<'_> {
    /// The profile's points (and parameters into `out`) at `slices`, or `None` when the
    /// slices leave some piece no tolerance.
    fn plan(&self, tolerance: f64, slices: usize, mut out: Option<&mut Vec<f64>>) -> Option<usize> {
        let mut scratch = Vec::new();
        match self {
            Pieces::Cubics(segments) => {
                if let Some(out) = out.as_deref_mut() {
                    out.clear();
                    out.push(0.0);
                }
                let mut points = 1;
                for (k, seg) in segments.iter().enumerate() {
                    let (n, _) =
                        plan_piece(seg, (k as f64, 0.0, 1.0), 0, tolerance, slices, &mut scratch, out.as_deref_mut())?;
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
                        *out = flatten::flatten_any(curve, mode);
                        Some(out.len())
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
    let triangles = |n: usize| pieces.plan(tolerance, n, None).map(|p| 2 * (p as u64 - 1).max(1) * n as u64);
    // the fewest slices that leave every piece some tolerance (bisection: feasibility only
    // grows with n)
    let first = if triangles(3).is_some() {
        3
    } else if triangles(max_slices).is_none() {
        return fallback(&pieces, tolerance, max_slices);
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
    let mut best = (u64::MAX, first);
    let mut n = first;
    while n <= max_slices && n <= first.saturating_mul(16) {
        if let Some(t) = triangles(n) {
            best = best.min((t, n));
        }
        n = (n + 1).max((n as f64 * 1.02) as usize);
    }
    let around = best.1;
    for n in around.saturating_sub(around / 40 + 2).max(first)..=(around + around / 40 + 2).min(max_slices) {
        if let Some(t) = triangles(n) {
            best = best.min((t, n));
        }
    }
    let slices = best.1;
    let mut params = Vec::new();
    pieces.plan(tolerance, slices, Some(&mut params));
    RevolutionPlan { params, slices, bound: tolerance }
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
    RevolutionPlan { params: curve_params, slices, bound: eps + radial }
}
