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

use glam::{DVec2, DVec3};

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
