//! Frames along curves: the sequential method of the course software,
//! rotation-minimizing frames, Frenet frames, and the closed-curve fix.
//!
//! A [`Frame`] is a right-handed orthonormal triple `(T, N, B)` with `T × N = B`, always in
//! 3D ([`DVec3`]); 2D curves are embedded with `z = 0`. Frames are computed from
//! [`CurveSample`]s (parameter, position, unit tangent, curvature vector), so a caller can
//! pass two samples at a sharp corner of a C0 curve (same position, incoming and outgoing
//! tangent); [`sample`] and [`sample_with_corners`] build them from a curve.
//!
//! # Methods and conventions
//!
//! - [`sequential`] (the course software's method, the default for SWP input): reference
//!   binormal `B₋₁ = ±z`, then `Nᵢ = normalize(Bᵢ₋₁ × Tᵢ)`, `Bᵢ = Tᵢ × Nᵢ`. A curve in the xy
//!   plane gets N **left** of travel and `B = +z` with [`Side::Left`], right of travel and
//!   `B = −z` with [`Side::Right`].
//! - [`rotation_minimizing`] (double reflection): no twist about T. The first normal comes
//!   from [`StartNormal`]; with the default `Auto(Side::Left)` the first frame is the
//!   sequential method's, and a curve in the xy plane gets exactly the sequential frames
//!   (N left of travel, `B = +z`; right and `−z` with `Auto(Side::Right)`).
//! - [`frenet`]: N is `±` the principal normal, toward the centre of curvature at the first
//!   curved sample, then with the sign kept continuous (a planar curve keeps N on one side
//!   of travel through inflections); straight runs are bridged by rotation-minimizing steps.
//!
//! For 2D normals without frames, [`normal_2d`] takes the side explicitly:
//! [`Side::Left`] is `(−T.y, T.x)`, [`Side::Right`] is `(T.y, −T.x)` (the convention of
//! tools where a counter-clockwise loop has outward normals).
//!
//! # Degenerate input
//!
//! No function here panics, and the frame functions never return NaN, whatever the
//! samples: empty lists give empty lists, zero or non-finite tangents are replaced (by the chord through the neighbouring
//! samples, else the previous usable tangent, else the next one, else `+x`), repeated
//! positions are treated as a turn in place (the minimal rotation taking one tangent to the
//! next), and non-finite positions count as repeated ones.
//!
//! # Closed curves
//!
//! When the first and last samples coincide in position and tangent ([`is_closed_loop`]),
//! the transported normal generally comes back rotated by some angle θ about T.
//! [`close_by_index`] (the course software's way, used with the sequential method) and
//! [`close_by_arclen`] (used with rotation-minimizing and Frenet frames) rotate each frame
//! about its tangent by a share of θ growing linearly along the curve, so that the last
//! frame equals the first. [`frames`] does all of this from [`FrameOptions`].
//!
//! ```
//! use glam::DVec2;
//! use splinekit::{CatmullRom, frame::{self, FrameMethod, FrameOptions, Side}};
//! let pts = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(2.0, 1.0), DVec2::new(3.0, 1.0)];
//! let curve = CatmullRom::new(&pts, false, 0.5).unwrap().to_piecewise();
//! let params: Vec<f64> = (0..=10).map(|i| i as f64 / 10.0).collect();
//! let frames = frame::frames(&curve, &params, &FrameOptions::DEFAULT);
//! // The default is the sequential method with N to the left of travel, B = +z.
//! let f = frames[5];
//! let left = frame::normal_2d(f.t.truncate(), Side::Left);
//! assert!((f.n.truncate() - left).length() < 1e-12 && (f.b.z - 1.0).abs() < 1e-12);
//! ```

use glam::{DMat3, DVec2, DVec3};

use crate::curve::{ParamCurve, PiecewiseCubic};
use crate::vector::Vector;

/// Two unit directions whose cross product is at most this long (the sine of the angle
/// between them) count as parallel: the sequential method then picks another reference,
/// and an up vector or start normal along the tangent is replaced.
pub const PARALLEL_SINE: f64 = 1e-9;

/// Tangent angle (radians) within which [`frames`] treats the first and last samples as
/// matching, for the closed-curve fix.
pub const CLOSED_ANGLE_TOLERANCE: f64 = 1e-6;

/// Distance within which [`frames`] treats the first and last samples as the same point,
/// relative to the diagonal of the samples' bounding box.
pub const CLOSED_RELATIVE_TOLERANCE: f64 = 1e-9;

/// [`frenet`] counts a sample as straight (no principal normal) when its curvature times
/// the diagonal of the samples' bounding box is at most this.
pub const STRAIGHT_TOLERANCE: f64 = 1e-8;

/// A chord shorter than this times the coordinates' magnitude counts as a repeated position.
const REPEAT_RELATIVE: f64 = 1e-10;

/// The closed-curve fix copies the first frame onto the last when their tangents agree
/// within this angle (radians), so that closed sweeps weld bit for bit.
const SNAP_ANGLE: f64 = 1e-9;

/// A right-handed orthonormal frame: unit tangent `t`, normal `n`, binormal `b`, with
/// `t × n = b`.
///
/// A sweep places a profile point `p` at `[n b t]·p + position`, see
/// [`to_nbt_matrix`](Self::to_nbt_matrix).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Unit tangent (direction of travel).
    pub t: DVec3,
    /// Unit normal.
    pub n: DVec3,
    /// Unit binormal `t × n`.
    pub b: DVec3,
}

impl Frame {
    /// `T = +x`, `N = +y`, `B = +z`.
    pub const IDENTITY: Self = Self { t: DVec3::X, n: DVec3::Y, b: DVec3::Z };

    /// The frame with tangent `t` (normalized; `+x` if zero or not finite) whose normal is
    /// `normal` made perpendicular to it (Gram–Schmidt). When `normal` is (nearly) parallel
    /// to `t`, zero or not finite, an arbitrary perpendicular is used (glam's
    /// `any_orthonormal_vector`). Never NaN.
    #[must_use]
    pub fn from_tangent_normal(t: DVec3, normal: DVec3) -> Self {
        let t = t.try_normalize().unwrap_or(DVec3::X);
        frame_from(t, normal, t.any_orthonormal_vector())
    }

    /// The frame turned by `angle` (radians, right-handed) about its tangent: `n` turns
    /// toward `b`. A non-finite angle leaves the frame unchanged.
    #[must_use]
    pub fn rotated(self, angle: f64) -> Self {
        if !angle.is_finite() {
            return self;
        }
        let (s, c) = angle.sin_cos();
        Self { t: self.t, n: self.n * c + self.b * s, b: self.b * c - self.n * s }
    }

    /// The frame turned by half a turn about its tangent (`n` and `b` negated): switches a
    /// planar curve's normal between the left and the right of travel.
    #[must_use]
    pub fn flipped(self) -> Self {
        Self { t: self.t, n: -self.n, b: -self.b }
    }

    /// The matrix with columns `[n b t]`: maps profile coordinates `(x, y, z)` to
    /// `n·x + b·y + t·z`.
    #[must_use]
    pub fn to_nbt_matrix(self) -> DMat3 {
        DMat3::from_cols(self.n, self.b, self.t)
    }

    /// True when every component is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.t.is_finite() && self.n.is_finite() && self.b.is_finite()
    }
}

/// Which side of the direction of travel a 2D normal points to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Side {
    /// `N = (−T.y, T.x)`: T turned a quarter turn counter-clockwise (the course software;
    /// in 3D, the reference binormal `+z`).
    #[default]
    Left,
    /// `N = (T.y, −T.x)`: T turned a quarter turn clockwise (a counter-clockwise closed
    /// loop then has outward normals; in 3D, the reference binormal `−z`).
    Right,
}

impl Side {
    /// The binormal that puts N on this side for a curve in the xy plane: `+z` or `−z`.
    #[must_use]
    pub fn up(self) -> DVec3 {
        match self {
            Self::Left => DVec3::Z,
            Self::Right => DVec3::NEG_Z,
        }
    }
}

/// The 2D normal of the tangent `t` on the given side of travel: `(−t.y, t.x)` for
/// [`Side::Left`], `(t.y, −t.x)` for [`Side::Right`]. Same length as `t` (unit for unit `t`).
#[must_use]
pub fn normal_2d(t: DVec2, side: Side) -> DVec2 {
    match side {
        Side::Left => DVec2::new(-t.y, t.x),
        Side::Right => DVec2::new(t.y, -t.x),
    }
}

/// How [`rotation_minimizing`] chooses its first normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StartNormal {
    /// As the sequential method: reference binormal [`Side::up`] (`±z`), so
    /// `N₀ = normalize(±z × T₀)`; if `T₀ ∥ z`, the reference `±y` is used instead. A curve in
    /// the xy plane gets N on the chosen side of travel, everywhere.
    Auto(Side),
    /// This normal, made perpendicular to `T₀`. If it is (nearly) parallel to `T₀`, zero or
    /// not finite, `Auto(Side::Left)` is used.
    Normal(DVec3),
    /// An up vector for the binormal: `B₀` is `up` made perpendicular to `T₀` and
    /// `N₀ = normalize(up × T₀)` (a sweep's profile y axis then leans toward `up`). If it is
    /// (nearly) parallel to `T₀`, zero or not finite, `Auto(Side::Left)` is used.
    Up(DVec3),
}

impl Default for StartNormal {
    fn default() -> Self {
        Self::Auto(Side::Left)
    }
}

/// A point on a curve with what frames need to know there.
///
/// Two samples with the same position and different tangents describe a sharp corner
/// (incoming tangent first). Every frame function accepts them without NaN:
/// [`rotation_minimizing`] turns the frame there by the minimal rotation between the two
/// tangents (N turns by at most the corner's angle), and so do [`sequential`] and [`frenet`]
/// on a curve in the xy plane; in 3D see their docs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveSample {
    /// Curve parameter (informational; frames do not use it).
    pub u: f64,
    /// Position.
    pub position: DVec3,
    /// Unit tangent in the direction of travel. A zero or non-finite tangent is replaced
    /// (see the [module docs](self)).
    pub tangent: DVec3,
    /// Curvature vector `κ·N = (P″ − (P″·T)·T) / |P′|²` (its length is the curvature), used
    /// only by [`frenet`]; zero where unknown, at a cusp, or on a straight piece.
    pub curvature: DVec3,
}

impl CurveSample {
    /// A sample from a position and tangent (normalized here when possible, else stored as
    /// zero), with unknown curvature.
    #[must_use]
    pub fn new(u: f64, position: DVec3, tangent: DVec3) -> Self {
        Self { u, position, tangent: tangent.try_normalize().unwrap_or(DVec3::ZERO), curvature: DVec3::ZERO }
    }

    /// A sample from the position and the first two derivatives `d1 = P′`, `d2 = P″` (2D
    /// input is embedded with z = 0). Where `d1` vanishes the tangent is the direction of
    /// `d2` (the limit at a cusp, approached from before it) and the curvature is zero.
    #[must_use]
    pub fn from_derivatives<P: Vector>(u: f64, position: P, d1: P, d2: P) -> Self {
        let (d1, d2) = (d1.to_dvec3(), d2.to_dvec3());
        let scale = d1.length() + d2.length();
        let tangent = if d1.length() > 1e-12 * scale { d1.try_normalize() } else { d2.try_normalize() };
        let tangent = tangent.unwrap_or(DVec3::ZERO);
        Self { u, position: position.to_dvec3(), tangent, curvature: curvature_vector(tangent, d1, d2) }
    }

    /// The sample of `curve` at `u`: position, [`ParamCurve::unit_tangent`] (with its
    /// fallbacks at cusps) and the curvature vector.
    #[must_use]
    pub fn at<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, u: f64) -> Self {
        let tangent = curve.unit_tangent(u).to_dvec3();
        let (d1, d2) = (curve.deriv(u).to_dvec3(), curve.deriv2(u).to_dvec3());
        Self { u, position: curve.eval(u).to_dvec3(), tangent, curvature: curvature_vector(tangent, d1, d2) }
    }
}

/// `(d2 − (d2·t)t) / |d1|²`, or zero where `d1` (nearly) vanishes or the result is not finite.
fn curvature_vector(t: DVec3, d1: DVec3, d2: DVec3) -> DVec3 {
    let speed = d1.length();
    if !(speed > 1e-12 * (speed + d2.length())) || t == DVec3::ZERO {
        return DVec3::ZERO;
    }
    let k = (d2 - t * d2.dot(t)) / (speed * speed);
    if k.is_finite() { k } else { DVec3::ZERO }
}

/// Samples `curve` at each parameter (see [`CurveSample::at`]). At the joint of a C0
/// piecewise curve this gives the outgoing tangent only; use [`sample_with_corners`] for two
/// samples there.
#[must_use]
pub fn sample<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, params: &[f64]) -> Vec<CurveSample> {
    params.iter().map(|&u| CurveSample::at(curve, u)).collect()
}

/// Like [`sample`], but at an inner joint `u = k` (`0 < k < segments`, within `1e-12·k` of
/// an integer) where the incoming and outgoing unit tangents differ by more than
/// `angle_tolerance` radians, emits two samples: the end of segment `k − 1` (incoming
/// tangent), then the start of segment `k` (outgoing tangent), both with `u = k`.
/// Everywhere else one sample per parameter. The seam of a closed curve (`u = 0` or
/// `u = segments`) is not split.
#[must_use]
pub fn sample_with_corners<P: Vector>(
    curve: &PiecewiseCubic<P>,
    params: &[f64],
    angle_tolerance: f64,
) -> Vec<CurveSample> {
    let segments = curve.segments();
    let m = segments.len();
    let mut out = Vec::with_capacity(params.len());
    for &u in params {
        let k = u.round();
        if k >= 1.0 && k < m as f64 && (u - k).abs() <= 1e-12 * k {
            let (inc, out_seg) = (&segments[k as usize - 1], &segments[k as usize]);
            let a = CurveSample::at(inc, 1.0);
            let b = CurveSample::at(out_seg, 0.0);
            if angle(a.tangent, b.tangent) > angle_tolerance {
                out.push(CurveSample { u: k, ..a });
                out.push(CurveSample { u: k, ..b });
                continue;
            }
        }
        out.push(CurveSample::at(curve, u));
    }
    out
}

/// Frames by the sequential method of the course software: with the reference
/// `B₋₁ = side.up()` (`+z` for [`Side::Left`], `−z` for [`Side::Right`]), at each sample
/// `Nᵢ = normalize(Bᵢ₋₁ × Tᵢ)` and `Bᵢ = Tᵢ × Nᵢ`, carried through all samples (so a curve's
/// later segments continue from the previous segment's last B).
///
/// Fallbacks (never NaN): if `T₀ ∥ z`, the reference `±y` is used instead; if a later `Tᵢ`
/// is parallel to `Bᵢ₋₁` (a turn of 90° in one step), the previous normal is carried:
/// `Nᵢ = Nᵢ₋₁` made perpendicular to `Tᵢ`, which is then the minimal rotation.
///
/// **Side**: for a curve in the xy plane, N is `(−T.y, T.x, 0)` (left of travel) and
/// `B = +z` with [`Side::Left`]; `(T.y, −T.x, 0)` and `B = −z` with [`Side::Right`]. The two
/// sides differ exactly by [`Frame::flipped`].
///
/// At a sharp corner (two samples at one position) of a curve in the xy plane, N turns
/// exactly by the corner's angle. In 3D the method is not rotation-minimizing: N turns by
/// the angle between the two tangents projected on the plane ⊥ `Bᵢ₋₁`, which can be much
/// more where T passes near the previous B; prefer [`rotation_minimizing`] there.
/// Closed curves: see [`close_by_index`].
#[must_use]
pub fn sequential(samples: &[CurveSample], side: Side) -> Vec<Frame> {
    let ts = unit_tangents(samples);
    let mut frames: Vec<Frame> = Vec::with_capacity(ts.len());
    for &t in &ts {
        let f = match frames.last() {
            None => auto_frame(t),
            Some(p) => up_frame(t, p.b).unwrap_or_else(|| frame_from(t, p.n, t.any_orthonormal_vector())),
        };
        frames.push(f);
    }
    if side == Side::Right {
        frames.iter_mut().for_each(|f| *f = f.flipped());
    }
    frames
}

/// Rotation-minimizing frames by the double-reflection method (Wang, Jüttler, Zheng, Liu:
/// "Computation of rotation minimizing frames", ACM TOG 27(1), article 2, 2008,
/// <https://doi.org/10.1145/1330511.1330513>), from the samples' exact positions and tangents.
///
/// Each step reflects the frame in the plane bisecting the chord `xᵢ₊₁ − xᵢ`, then in the
/// plane that maps the reflected tangent onto `Tᵢ₊₁`; the result is a rotation. The global
/// error against the exact rotation-minimizing frame is O(h⁴) in the sample spacing h.
/// There is no twist about T beyond that error (angular velocity `ω·T ≈ 0`).
///
/// The first normal comes from `start` (see [`StartNormal`]; with `Auto(side)` a curve in
/// the xy plane gets N on that side of travel and `B = ±z` throughout, exactly like
/// [`sequential`]).
///
/// Degenerate steps: a repeated position (a sharp corner given as two samples) turns the
/// frame by the minimal rotation taking one tangent to the next, so N changes by at most
/// the turning angle; a reversal (`Tᵢ₊₁ = −Tᵢ`) turns half a turn about the binormal (B
/// kept, N negated). Closed curves: see [`close_by_arclen`]; twist: [`twist_by_arclen`].
#[must_use]
pub fn rotation_minimizing(samples: &[CurveSample], start: StartNormal) -> Vec<Frame> {
    let ts = unit_tangents(samples);
    let Some(&t0) = ts.first() else { return Vec::new() };
    let mut frames = Vec::with_capacity(ts.len());
    frames.push(start_frame(t0, start));
    for i in 1..ts.len() {
        let p: Frame = frames[i - 1];
        let r = transport(samples[i - 1].position, p.t, p.n, samples[i].position, ts[i]);
        frames.push(frame_from(ts[i], r, p.n));
    }
    frames
}

/// Frenet frames: N is the principal normal (the direction of the curvature vector
/// [`CurveSample::curvature`]), B = T × N, with two fallbacks that keep the frames
/// continuous.
///
/// - **Sign** (inflections): N is `±` the principal normal, the sign chosen at each sample
///   to agree with the previous frame carried forward by one rotation-minimizing step.
///   So N does not jump to the other side at an inflection of a planar curve; after one,
///   N points away from the centre of curvature. The first curved sample uses the true
///   principal normal (toward the centre of curvature).
/// - **Straight samples** (curvature · bounding-box diagonal ≤ [`STRAIGHT_TOLERANCE`], or
///   unknown curvature): the previous frame is carried by a rotation-minimizing step;
///   a leading straight run is carried backward from the first curved sample. A curve with
///   no curved sample at all gets [`rotation_minimizing`] with `StartNormal::Auto(Side::Left)`.
///
/// At a sharp corner (two samples at one position) each side keeps its own principal
/// normal up to sign, so N may turn by more than the tangent (at most a quarter turn
/// beyond the minimal rotation); for a planar curve it turns exactly by the tangent's angle.
/// Samples built with [`CurveSample::new`] have no curvature: use [`sample`].
#[must_use]
pub fn frenet(samples: &[CurveSample]) -> Vec<Frame> {
    let ts = unit_tangents(samples);
    let diag = bounding_diagonal(samples);
    let normals: Vec<Option<DVec3>> =
        samples.iter().zip(&ts).map(|(s, &t)| principal_normal(s.curvature, t, diag)).collect();
    // each principal normal up to sign: the side the carried normal is on
    frames_from_normals(samples, &ts, &normals, |nf, r| if nf.dot(r) >= 0.0 { nf } else { -nf })
        .unwrap_or_else(|| rotation_minimizing(samples, StartNormal::default()))
}

/// Frames with the given normals where known (`pick(normal, carried)` chooses each from it
/// and the previous frame's normal carried by a rotation-minimizing step), carried between
/// them and backward before the first; `None` when no sample has a normal.
fn frames_from_normals(
    samples: &[CurveSample],
    ts: &[DVec3],
    normals: &[Option<DVec3>],
    pick: impl Fn(DVec3, DVec3) -> DVec3,
) -> Option<Vec<Frame>> {
    let first = normals.iter().position(Option::is_some)?;
    let mut frames = vec![Frame::IDENTITY; ts.len()];
    let n0 = normals[first].unwrap_or(DVec3::ZERO);
    frames[first] = frame_from(ts[first], n0, ts[first].any_orthonormal_vector());
    for i in (0..first).rev() {
        let q = frames[i + 1];
        let r = transport(samples[i + 1].position, q.t, q.n, samples[i].position, ts[i]);
        frames[i] = frame_from(ts[i], r, q.n);
    }
    for i in first + 1..ts.len() {
        let p = frames[i - 1];
        let r = transport(samples[i - 1].position, p.t, p.n, samples[i].position, ts[i]);
        let n = normals[i].map_or(r, |nf| pick(nf, r));
        frames[i] = frame_from(ts[i], n, r);
    }
    Some(frames)
}

/// Frames whose binormal leans toward a fixed `up` everywhere (Blender's "Z-Up" twist method
/// with `up = +z`): `N = normalize(up × T)`, `B = T × N`, so B is `up` made perpendicular to
/// T and no twist builds up along the curve; a planar curve in a plane through `up` keeps its
/// profile upright.
///
/// Where T is (nearly) parallel to `up` (`|up × T|` below 1e-9) the previous frame is carried
/// by a rotation-minimizing step (a leading run backward from the first sample that has a
/// direction); a curve running along `up` everywhere, or an `up` of zero length or not finite,
/// gets [`rotation_minimizing`] with `StartNormal::Auto(Side::Left)`. Where the path passes
/// close to the `up` direction the frame turns quickly about T (by up to a half turn where it
/// passes through it), as Blender's does; rotation-minimizing frames do not.
#[must_use]
pub fn fixed_up(samples: &[CurveSample], up: DVec3) -> Vec<Frame> {
    let ts = unit_tangents(samples);
    let Some(up) = up.try_normalize() else { return rotation_minimizing(samples, StartNormal::default()) };
    let normals: Vec<Option<DVec3>> = ts
        .iter()
        .map(|&t| {
            let n = up.cross(t);
            (n.length() > 1e-9).then(|| n.normalize())
        })
        .collect();
    frames_from_normals(samples, &ts, &normals, |nf, _| nf)
        .unwrap_or_else(|| rotation_minimizing(samples, StartNormal::default()))
}

/// True when there are at least two samples, the first and last positions are within
/// `tolerance` (length units) of each other, and their tangents within `angle_tolerance`
/// radians: the condition for the closed-curve fix.
#[must_use]
pub fn is_closed_loop(samples: &[CurveSample], tolerance: f64, angle_tolerance: f64) -> bool {
    let n = samples.len();
    if n < 2 {
        return false;
    }
    let d = samples[0].position.distance(samples[n - 1].position);
    let ts = unit_tangents(samples);
    d <= tolerance && angle(ts[0], ts[n - 1]) <= angle_tolerance
}

/// The closed-curve fix with the correction spread by sample index (as the course software
/// does; the default for the sequential method): with θ the angle (about the last tangent)
/// from the last normal to the first, frame `i` of `n` is turned about its tangent by
/// `θ·i/(n−1)`, so the last frame matches the first. When the two tangents agree (within
/// 1e-9 rad) the last frame is then set to the first bit for bit, so seams weld exactly.
///
/// Apply it only to closed curves ([`is_closed_loop`]). If the last tangent differs from the
/// first (a corner at the seam), θ is measured to the first frame carried to the last
/// tangent by the minimal rotation, so the seam becomes a proper corner without twist.
/// Fewer than two frames: nothing to do.
pub fn close_by_index(frames: &mut [Frame]) {
    let n = frames.len();
    if n < 2 {
        return;
    }
    let theta = seam_angle(frames);
    let last = (n - 1) as f64;
    for (i, f) in frames.iter_mut().enumerate().skip(1) {
        *f = f.rotated(theta * (i as f64 / last));
    }
    snap_seam(frames);
}

/// The closed-curve fix with the correction spread by arc length (the default for
/// rotation-minimizing and Frenet frames): as [`close_by_index`], with frame `i` turned by
/// `θ·sᵢ/L`, where `sᵢ` is the arc length from the first sample estimated from the samples
/// (each step's chord times `(φ/2)/sin(φ/2)`, φ the angle between its tangents: exact for
/// straight lines and circular arcs). If `frames` and `samples` differ in length, or the
/// samples have no length, the correction is spread by index instead.
pub fn close_by_arclen(frames: &mut [Frame], samples: &[CurveSample]) {
    let n = frames.len();
    if n < 2 {
        return;
    }
    let theta = seam_angle(frames);
    let shares = shares(frames.len(), samples);
    for (f, share) in frames.iter_mut().zip(shares).skip(1) {
        *f = f.rotated(theta * share);
    }
    snap_seam(frames);
}

/// Adds a total `twist` (radians, right-handed about T: N turns toward B) spread by arc
/// length as in [`close_by_arclen`]: frame `i` turns by `twist·sᵢ/L` (by index if the
/// samples have no length or differ in number from the frames). On a closed curve, a
/// multiple of 2π keeps the seam closed. A non-finite twist is ignored.
pub fn twist_by_arclen(frames: &mut [Frame], samples: &[CurveSample], twist: f64) {
    if twist == 0.0 || !twist.is_finite() {
        return;
    }
    let shares = shares(frames.len(), samples);
    for (f, share) in frames.iter_mut().zip(shares) {
        *f = f.rotated(twist * share);
    }
}

/// Which frames [`frames`] computes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FrameMethod {
    /// [`sequential`] (the SWP default; closed fix by sample index).
    Sequential(Side),
    /// [`rotation_minimizing`] (closed fix and twist by arc length).
    RotationMinimizing(StartNormal),
    /// [`frenet`] (closed fix and twist by arc length).
    Frenet,
    /// [`fixed_up`] with this up vector (Blender's "Z-Up" with `+z`; closed fix and twist by
    /// arc length).
    FixedUp(DVec3),
}

/// Options for [`frames`]: start from [`FrameOptions::DEFAULT`] and adjust with `with_*`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct FrameOptions {
    /// The method (default: `Sequential(Side::Left)`, the course software's).
    pub method: FrameMethod,
    /// Apply the closed-curve fix when the samples form a closed loop: first and last within
    /// [`CLOSED_RELATIVE_TOLERANCE`] × the samples' bounding-box diagonal in position and
    /// [`CLOSED_ANGLE_TOLERANCE`] in tangent (default: true).
    pub close: bool,
    /// Total twist in radians about T, spread by arc length, applied after the closed fix
    /// (default 0).
    pub twist: f64,
}

impl FrameOptions {
    /// Sequential method, N left of travel, closed fix on, no twist.
    pub const DEFAULT: Self = Self { method: FrameMethod::Sequential(Side::Left), close: true, twist: 0.0 };

    /// With this method.
    #[must_use]
    pub fn with_method(self, method: FrameMethod) -> Self {
        Self { method, ..self }
    }

    /// With the closed-curve fix on or off.
    #[must_use]
    pub fn with_close(self, close: bool) -> Self {
        Self { close, ..self }
    }

    /// With this total twist (radians).
    #[must_use]
    pub fn with_twist(self, twist: f64) -> Self {
        Self { twist, ..self }
    }
}

impl Default for FrameOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Frames of `curve` at `params` (see [`sample`] and [`frames_for_samples`]).
#[must_use]
pub fn frames<P: Vector, C: ParamCurve<P> + ?Sized>(curve: &C, params: &[f64], options: &FrameOptions) -> Vec<Frame> {
    frames_for_samples(&sample(curve, params), options)
}

/// Frames at `samples` by `options.method`, then the closed-curve fix (if `options.close`
/// and the samples form a closed loop: [`close_by_index`] for the sequential method,
/// [`close_by_arclen`] otherwise), then `options.twist` ([`twist_by_arclen`]).
#[must_use]
pub fn frames_for_samples(samples: &[CurveSample], options: &FrameOptions) -> Vec<Frame> {
    let mut frames = match options.method {
        FrameMethod::Sequential(side) => sequential(samples, side),
        FrameMethod::RotationMinimizing(start) => rotation_minimizing(samples, start),
        FrameMethod::Frenet => frenet(samples),
        FrameMethod::FixedUp(up) => fixed_up(samples, up),
    };
    let tolerance = CLOSED_RELATIVE_TOLERANCE * bounding_diagonal(samples);
    if options.close && is_closed_loop(samples, tolerance, CLOSED_ANGLE_TOLERANCE) {
        match options.method {
            FrameMethod::Sequential(_) => close_by_index(&mut frames),
            _ => close_by_arclen(&mut frames, samples),
        }
    }
    twist_by_arclen(&mut frames, samples, options.twist);
    frames
}

// ---------------------------------------------------------------------------------------
// Internals

/// Angle between two directions, in `[0, π]` (robust near 0 and π).
fn angle(a: DVec3, b: DVec3) -> f64 {
    let a = a.try_normalize().unwrap_or(DVec3::ZERO);
    let b = b.try_normalize().unwrap_or(DVec3::ZERO);
    a.cross(b).length().atan2(a.dot(b))
}

/// Unit tangents of the samples, with the fallbacks of the module docs.
fn unit_tangents(samples: &[CurveSample]) -> Vec<DVec3> {
    let n = samples.len();
    let mut ts: Vec<Option<DVec3>> = samples.iter().map(|s| s.tangent.try_normalize()).collect();
    if ts.iter().all(Option::is_some) {
        return ts.into_iter().map(|t| t.unwrap_or(DVec3::X)).collect();
    }
    let chords: Vec<Option<DVec3>> = (0..n)
        .map(|i| {
            let a = samples[i.saturating_sub(1)].position;
            let b = samples[(i + 1).min(n - 1)].position;
            if ts[i].is_some() { None } else { (b - a).try_normalize() }
        })
        .collect();
    for (t, c) in ts.iter_mut().zip(chords) {
        if t.is_none() {
            *t = c;
        }
    }
    let next_valid = ts.iter().flatten().next().copied().unwrap_or(DVec3::X);
    let mut prev: Option<DVec3> = None;
    ts.into_iter()
        .map(|t| {
            let t = t.or(prev).unwrap_or(next_valid);
            prev = Some(t);
            t
        })
        .collect()
}

/// Diagonal of the bounding box of the finite sample positions (0 if none).
fn bounding_diagonal(samples: &[CurveSample]) -> f64 {
    let mut it = samples.iter().map(|s| s.position).filter(|p| p.is_finite());
    let Some(first) = it.next() else { return 0.0 };
    let (lo, hi) = it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
    let d = (hi - lo).length();
    if d.is_finite() { d } else { 0.0 }
}

/// The frame with unit tangent `t` whose normal is `normal` made perpendicular to `t`, else
/// `fallback` made perpendicular, else any perpendicular.
fn frame_from(t: DVec3, normal: DVec3, fallback: DVec3) -> Frame {
    let perp = |v: DVec3| {
        let p = v - t * v.dot(t);
        let l = p.length();
        (l.is_finite() && l > PARALLEL_SINE * v.length()).then(|| p / l)
    };
    let n = perp(normal).or_else(|| perp(fallback)).unwrap_or_else(|| t.any_orthonormal_vector());
    Frame { t, n, b: t.cross(n) }
}

/// `N = normalize(up × t)`, `B = t × N`, or `None` when `up` is (nearly) parallel to `t`,
/// zero or not finite.
fn up_frame(t: DVec3, up: DVec3) -> Option<Frame> {
    let up = up.try_normalize()?;
    let c = up.cross(t);
    let l = c.length();
    if !(l > PARALLEL_SINE) {
        return None;
    }
    let n = c / l;
    Some(Frame { t, n, b: t.cross(n) })
}

/// The sequential method's first frame: reference `+z`, else `+y`.
fn auto_frame(t: DVec3) -> Frame {
    up_frame(t, DVec3::Z).or_else(|| up_frame(t, DVec3::Y)).unwrap_or_else(|| frame_from(t, DVec3::Y, DVec3::X))
}

fn start_frame(t: DVec3, start: StartNormal) -> Frame {
    match start {
        StartNormal::Auto(Side::Left) => auto_frame(t),
        StartNormal::Auto(Side::Right) => auto_frame(t).flipped(),
        StartNormal::Up(up) => up_frame(t, up).unwrap_or_else(|| auto_frame(t)),
        StartNormal::Normal(v) => {
            // v's part across t, as (t × v) × t: orthogonal to t to rounding even when v is
            // nearly along t (subtracting (v·t)·t would cancel there)
            let c = t.cross(v);
            let l = c.length();
            if l.is_finite() && l > PARALLEL_SINE * v.length() {
                let n = (c / l).cross(t).normalize();
                Frame { t, n, b: t.cross(n) }
            } else {
                auto_frame(t)
            }
        }
    }
}

/// The unit principal normal from a curvature vector, or `None` on a straight sample.
fn principal_normal(curvature: DVec3, t: DVec3, diag: f64) -> Option<DVec3> {
    let k = curvature - t * curvature.dot(t);
    let l = k.length();
    if !l.is_finite() || l == 0.0 || l * diag <= STRAIGHT_TOLERANCE {
        return None;
    }
    Some(k / l)
}

/// One double-reflection step: carries the normal `r0` (⊥ `t0`) at `x0` to `x1`, where the
/// tangent is `t1` (unit vectors). Returns a vector ⊥ `t1` (up to rounding), not
/// re-normalized.
///
/// A repeated (or non-finite) position uses `v1 = t0` for the first reflection, which makes
/// the pair of reflections the minimal rotation from `t0` to `t1`. When the first
/// reflection already maps `t0` onto `t1`, the second reflects in a plane through `t1`
/// chosen so that the pair is again the minimal rotation (or, for `t1 = −t0`, half a turn
/// about the binormal).
fn transport(x0: DVec3, t0: DVec3, r0: DVec3, x1: DVec3, t1: DVec3) -> DVec3 {
    let mut v1 = x1 - x0;
    let mut c1 = v1.length_squared();
    let magnitude = x0.abs().max_element().max(x1.abs().max_element());
    if !c1.is_finite() || c1 == 0.0 || c1.sqrt() <= REPEAT_RELATIVE * magnitude {
        v1 = t0;
        c1 = 1.0;
    }
    let rl = r0 - v1 * (2.0 / c1 * v1.dot(r0));
    let tl = t0 - v1 * (2.0 / c1 * v1.dot(t0));
    let mut v2 = t1 - tl;
    let mut c2 = v2.length_squared();
    if !(c2 > 1e-12) {
        v2 = v1 - tl * v1.dot(tl);
        c2 = v2.length_squared();
        if !(c2 > 1e-12 * c1) {
            v2 = rl;
            c2 = rl.length_squared();
        }
    }
    if !(c2 > 0.0) || !c2.is_finite() {
        return rl;
    }
    rl - v2 * (2.0 / c2 * v2.dot(rl))
}

/// Angle about the last tangent from the last normal to the first frame's normal carried to
/// the last tangent by the minimal rotation.
fn seam_angle(frames: &[Frame]) -> f64 {
    let (first, last) = (frames[0], frames[frames.len() - 1]);
    let target = transport(DVec3::ZERO, first.t, first.n, DVec3::ZERO, last.t);
    let target = target - last.t * target.dot(last.t);
    let theta = last.n.cross(target).dot(last.t).atan2(last.n.dot(target));
    if theta.is_finite() { theta } else { 0.0 }
}

fn snap_seam(frames: &mut [Frame]) {
    let n = frames.len();
    if angle(frames[0].t, frames[n - 1].t) <= SNAP_ANGLE {
        frames[n - 1] = frames[0];
    }
}

/// Share `sᵢ/L` of each of `n` frames (by index if the samples do not fit or have no length).
fn shares(n: usize, samples: &[CurveSample]) -> Vec<f64> {
    let by_index = || (0..n).map(|i| if n > 1 { i as f64 / (n - 1) as f64 } else { 0.0 }).collect();
    if samples.len() != n || n < 2 {
        return by_index();
    }
    let ts = unit_tangents(samples);
    let mut s = Vec::with_capacity(n);
    let mut acc = 0.0;
    s.push(0.0);
    for i in 1..n {
        let chord = samples[i].position.distance(samples[i - 1].position);
        let chord = if chord.is_finite() { chord } else { 0.0 };
        let half = 0.5 * angle(ts[i - 1], ts[i]);
        let factor = if half < 1e-4 { 1.0 + half * half / 6.0 } else { half / half.sin() };
        acc += chord * factor;
        s.push(acc);
    }
    if !(acc > 0.0) || !acc.is_finite() {
        return by_index();
    }
    s.iter().map(|&si| si / acc).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::{FRAC_PI_2, PI, TAU};

    const EPS: f64 = 1e-12;

    fn assert_close(a: DVec3, b: DVec3, eps: f64) {
        assert!((a - b).length() <= eps, "{a} vs {b}: diff {}", (a - b).length());
    }

    fn check_frame(f: &Frame) {
        assert!(f.is_finite(), "{f:?}");
        for v in [f.t, f.n, f.b] {
            assert!((v.length() - 1.0).abs() <= 1e-12, "{f:?}");
        }
        assert!(f.t.dot(f.n).abs() <= 1e-12, "{f:?}");
        assert_close(f.t.cross(f.n), f.b, 1e-12);
    }

    fn s(p: DVec3, t: DVec3) -> CurveSample {
        CurveSample::new(0.0, p, t)
    }

    #[test]
    fn empty_and_single() {
        assert!(sequential(&[], Side::Left).is_empty());
        assert!(rotation_minimizing(&[], StartNormal::default()).is_empty());
        assert!(frenet(&[]).is_empty());
        assert!(!is_closed_loop(&[], 1.0, 1.0));
        let mut none: [Frame; 0] = [];
        close_by_index(&mut none);
        close_by_arclen(&mut none, &[]);
        twist_by_arclen(&mut none, &[], 1.0);
        assert!(frames_for_samples(&[], &FrameOptions::DEFAULT).is_empty());
        let one = [s(DVec3::ONE, DVec3::X)];
        for f in [sequential(&one, Side::Left), rotation_minimizing(&one, StartNormal::default()), frenet(&one)] {
            assert_eq!(f.len(), 1);
            check_frame(&f[0]);
        }
    }

    #[test]
    fn frame_helpers() {
        check_frame(&Frame::IDENTITY);
        let f = Frame::from_tangent_normal(DVec3::new(0.0, 0.0, 2.0), DVec3::new(1.0, 0.0, 5.0));
        check_frame(&f);
        assert_close(f.n, DVec3::X, EPS);
        check_frame(&Frame::from_tangent_normal(DVec3::ZERO, DVec3::NAN));
        check_frame(&Frame::from_tangent_normal(DVec3::Y, DVec3::Y));
        let r = Frame::IDENTITY.rotated(FRAC_PI_2);
        assert_close(r.n, DVec3::Z, EPS);
        assert_close(r.b, -DVec3::Y, EPS);
        let m = Frame::IDENTITY.to_nbt_matrix();
        assert_close(m * DVec3::new(1.0, 2.0, 3.0), DVec3::new(3.0, 1.0, 2.0), EPS);
        assert_eq!(normal_2d(DVec2::X, Side::Left), DVec2::Y);
        assert_eq!(normal_2d(DVec2::X, Side::Right), -DVec2::Y);
    }

    #[test]
    fn degenerate_tangents_are_replaced() {
        let samples = [
            s(DVec3::ZERO, DVec3::ZERO),
            s(DVec3::X, DVec3::NAN),
            s(DVec3::new(2.0, 1.0, 0.0), DVec3::Y),
            s(DVec3::new(2.0, 1.0, 0.0), DVec3::ZERO),
        ];
        let ts = unit_tangents(&samples);
        assert_close(ts[0], DVec3::X, EPS);
        assert_close(ts[1], DVec3::new(2.0, 1.0, 0.0).normalize(), EPS);
        assert_close(ts[2], DVec3::Y, EPS);
        assert_close(ts[3], DVec3::Y, EPS);
        let all_bad = [s(DVec3::ONE, DVec3::ZERO), s(DVec3::ONE, DVec3::INFINITY)];
        assert_eq!(unit_tangents(&all_bad), vec![DVec3::X, DVec3::X]);
        let nan_pos = [s(DVec3::NAN, DVec3::ZERO), s(DVec3::ONE, DVec3::Z), s(DVec3::INFINITY, DVec3::X)];
        for fs in [
            sequential(&nan_pos, Side::Right),
            rotation_minimizing(&nan_pos, StartNormal::Up(DVec3::NAN)),
            frenet(&nan_pos),
            frames_for_samples(&nan_pos, &FrameOptions::DEFAULT.with_twist(1.0)),
        ] {
            fs.iter().for_each(check_frame);
        }
    }

    #[test]
    fn transport_corner_is_minimal_rotation() {
        let (t0, t1) = (DVec3::X, DVec3::new(1.0, 1.0, 1.0).normalize());
        for r0 in [DVec3::Y, DVec3::Z, DVec3::new(0.0, 0.6, 0.8)] {
            let r1 = transport(DVec3::ONE, t0, r0, DVec3::ONE, t1);
            let axis = t0.cross(t1).normalize();
            let expected = r0.rotate_axis(axis, angle(t0, t1));
            assert_close(r1, expected, 1e-14);
        }
        // Reversal: half a turn about the binormal.
        let r1 = transport(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ZERO, -DVec3::X);
        assert_close(r1, -DVec3::Y, EPS);
        let r1 = transport(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X, -DVec3::X);
        assert_close(r1, -DVec3::Y, EPS);
        // The first reflection maps t0 onto t1 exactly: the pair is the minimal rotation.
        let (t0, t1) = (DVec3::new(1.0, 1.0, 0.0).normalize(), DVec3::new(-1.0, 1.0, 0.0).normalize());
        let r1 = transport(DVec3::ZERO, t0, DVec3::Z, DVec3::X, t1);
        assert_close(r1, DVec3::Z, EPS);
        let r1 = transport(DVec3::ZERO, t0, DVec3::new(-1.0, 1.0, 0.0).normalize(), DVec3::X, t1);
        assert_close(r1, DVec3::new(-1.0, -1.0, 0.0).normalize(), EPS);
        // A straight step keeps the normal.
        let r1 = transport(DVec3::ZERO, DVec3::X, DVec3::Z, DVec3::X, DVec3::X);
        assert_close(r1, DVec3::Z, EPS);
    }

    #[test]
    fn sequential_fallbacks() {
        // First tangent along ±z: the reference +y is used.
        for t0 in [DVec3::Z, -DVec3::Z] {
            let f = sequential(&[s(DVec3::ZERO, t0), s(t0, DVec3::X)], Side::Left);
            f.iter().for_each(check_frame);
            assert_close(f[0].b, DVec3::Y, EPS);
        }
        // A later tangent parallel to the previous B: the previous N is carried.
        let samples = [s(DVec3::ZERO, DVec3::X), s(DVec3::X, DVec3::Z), s(DVec3::new(1.0, 0.0, 1.0), DVec3::Z)];
        let f = sequential(&samples, Side::Left);
        f.iter().for_each(check_frame);
        assert_close(f[0].n, DVec3::Y, EPS);
        assert_close(f[1].n, DVec3::Y, EPS);
        assert_close(f[1].b, -DVec3::X, EPS);
        assert_close(f[2].n, DVec3::Y, EPS);
        let r = sequential(&samples, Side::Right);
        for (a, b) in f.iter().zip(&r) {
            assert_eq!(*b, a.flipped());
        }
    }

    #[test]
    fn start_normals() {
        let t = DVec3::new(1.0, 0.0, 1.0).normalize();
        let samples = [s(DVec3::ZERO, t)];
        let n = rotation_minimizing(&samples, StartNormal::Normal(DVec3::X))[0].n;
        assert_close(n, DVec3::new(1.0, 0.0, -1.0).normalize(), EPS);
        let f = rotation_minimizing(&samples, StartNormal::Up(DVec3::Y))[0];
        assert_close(f.b, DVec3::Y, EPS);
        let auto = rotation_minimizing(&samples, StartNormal::Auto(Side::Left))[0];
        for bad in [DVec3::ZERO, t, DVec3::NAN] {
            assert_eq!(rotation_minimizing(&samples, StartNormal::Normal(bad))[0], auto);
            assert_eq!(rotation_minimizing(&samples, StartNormal::Up(bad))[0], auto);
        }
        assert_eq!(rotation_minimizing(&samples, StartNormal::Auto(Side::Right))[0], auto.flipped());
        // a normal nearly along the tangent (found by the frames proptest: t·n was 2.6e-12)
        let t = DVec3::new(0.9999999926662638, -0.00012110934177316303, 0.0);
        let f = rotation_minimizing(&[s(DVec3::ZERO, t)], StartNormal::Normal(DVec3::X))[0];
        assert!(f.t.dot(f.n).abs() < 1e-15, "t·n = {}", f.t.dot(f.n));
        assert!((f.n.length() - 1.0).abs() < 1e-15 && (f.t.cross(f.n) - f.b).length() < 1e-15);
        assert!(f.n.dot(DVec3::X) > 0.0);
    }

    #[test]
    fn arclen_shares_exact_on_circle() {
        let n = 7;
        let samples: Vec<_> = (0..n)
            .map(|i| {
                let a = TAU * i as f64 / (n - 1) as f64 * 0.75;
                s(DVec3::new(a.cos(), a.sin(), 0.0), DVec3::new(-a.sin(), a.cos(), 0.0))
            })
            .collect();
        for (i, share) in shares(n, &samples).into_iter().enumerate() {
            assert!((share - i as f64 / (n - 1) as f64).abs() <= 1e-14);
        }
        // Repeated positions give equal shares.
        let samples = [
            s(DVec3::ZERO, DVec3::X),
            s(DVec3::X, DVec3::X),
            s(DVec3::X, DVec3::Y),
            s(DVec3::new(1.0, 1.0, 0.0), DVec3::Y),
        ];
        assert_eq!(shares(4, &samples), vec![0.0, 0.5, 0.5, 1.0]);
        // No length: by index.
        let samples = [s(DVec3::ONE, DVec3::X); 3];
        assert_eq!(shares(3, &samples), vec![0.0, 0.5, 1.0]);
        assert_eq!(shares(2, &samples), vec![0.0, 1.0]);
    }

    #[test]
    fn close_by_index_spreads_linearly() {
        let mut frames: Vec<Frame> = (0..5).map(|i| Frame::IDENTITY.rotated(0.1 * i as f64)).collect();
        close_by_index(&mut frames);
        for f in &frames {
            check_frame(f);
            assert_close(f.n, DVec3::Y, 1e-15);
        }
        assert_eq!(frames[4], frames[0]);
        // A half turn mismatch is corrected without NaN.
        let mut frames = vec![Frame::IDENTITY, Frame::IDENTITY.rotated(PI)];
        close_by_index(&mut frames);
        assert_eq!(frames[1], frames[0]);
    }

    #[test]
    fn twist_is_spread_by_arclen() {
        let samples: Vec<_> = [0.0, 1.0, 3.0, 4.0].iter().map(|&x| s(DVec3::new(x, 0.0, 0.0), DVec3::X)).collect();
        let mut f = rotation_minimizing(&samples, StartNormal::Normal(DVec3::Y));
        twist_by_arclen(&mut f, &samples, 1.0);
        for (fr, x) in f.iter().zip([0.0f64, 0.25, 0.75, 1.0]) {
            assert_close(fr.n, DVec3::new(0.0, x.cos(), x.sin()), 1e-14);
        }
    }

    #[test]
    fn corners_in_samples_are_split() {
        let pts = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(3.0, 1.0, 0.0),
            DVec3::new(3.0, 2.0, 0.0),
            DVec3::new(3.0, 3.0, 0.0),
        ];
        let curve = crate::BezierSpline::new(&pts, false).unwrap().to_piecewise();
        let params = [0.0, 0.5, 1.0, 1.5, 2.0];
        let samples = sample_with_corners(&curve, &params, 1e-9);
        assert_eq!(samples.len(), 6);
        assert_eq!(samples[2].position, samples[3].position);
        assert_close(samples[2].tangent, DVec3::X, EPS);
        assert_close(samples[3].tangent, DVec3::Y, EPS);
        assert_eq!(sample(&curve, &params).len(), 5);
    }
}
