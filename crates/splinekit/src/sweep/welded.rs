//! The welded layout of a generalized cylinder, built as a list of *rings*: copies of the
//! profile, each a position id per profile point (its *slot*) and a normal per slot.
//!
//! Every point of the surface is one position: a crease of the profile (a corner sampled
//! twice), the closing point of a closed profile, the closing copy of a closed path, the rim
//! of an end cap and the points where a joint at a path corner meets the walls are each one
//! vertex, and the sharp edges keep sharp shading through face-varying normals (a ring may
//! be repeated with the same positions and other normals: the strip between the two copies
//! has no area and gets no triangles). The split mesh, with a vertex per (ring, slot) and
//! per cap corner, is what a renderer draws; welding it by position id gives the file's
//! mesh ([`super::generalized_cylinder_poly`]).
//!
//! # Joints at path corners
//!
//! A sharp corner of the path is two samples at one position with the incoming and the
//! outgoing tangent. The profile at the corner, placed with the incoming frame, is turned
//! onto the outgoing direction by the rotation `R` about `T_in × T_out` through the corner's
//! angle `α` (the smallest rotation taking `T_in` to `T_out`; the frame method's own
//! outgoing frame is not used there, so a method that turns the profile about the path at a
//! corner, Frenet or Z-up on a 3D path, turns it over the next step instead). With the
//! mitre plane through the corner, normal `m = normalize(T_in + T_out)`, a profile offset
//! `o` is on the *inner* side of the turn when `o·T_out > 0`:
//! - inner points go to the mitre point `V + o − (o·m)/(T_in·m)·T_in` (where the incoming
//!   wall meets the outgoing one) for every join: the walls end there, nothing folds back;
//! - outer points go to the mitre point with [`Join::Mitre`], are joined by a straight band
//!   from `V + o` to `V + R·o` with [`Join::Bevel`], and by an arc `V + R(β)·o` with
//!   [`Join::Round`] (steps of at most [`SweepOptions::round_step`]).
//!
//! A mitre longer than [`SweepOptions::mitre_limit`] times the profile's offset (ratio
//! `1/cos(α/2)`, as SVG's `stroke-miterlimit`) falls back to a bevel.
//!
//! The walls near a corner are cut at the mitre plane: an inner point of a ring beyond the
//! plane is moved to its mitre point. The joint is free of self-intersection while the
//! profile *fits inside the turn*: every inner point's cut, `|o·T_out|/sin α·(1 − cos α)`
//! (`|o|·tan(α/2)` for a point in the plane of the turn), is shorter than the path's length
//! to the neighbouring corner or end on each side, and the path's radius of curvature near
//! the corner exceeds the profile's extent. [`CornerFit`] reports the corners where the cut
//! reaches a neighbouring corner or an end of the path.

use glam::{DQuat, DVec2, DVec3};

use super::{Profile, SweepError, SweepOptions, SweepPath, extent, twins};
use crate::frame::Frame;
use crate::mesh::TriMesh;

/// How the walls of a sweep meet at a sharp corner of its path, as stroke outlines join in
/// 2D; see the [`welded`](self) module docs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Join {
    /// The walls are extended until they meet in the plane that halves the corner (falls
    /// back to [`Join::Bevel`] past [`SweepOptions::mitre_limit`]).
    #[default]
    Mitre,
    /// The outer side is rounded by an arc about the corner.
    Round,
    /// The outer side is cut flat from one wall's end to the other's.
    Bevel,
}

/// A corner of the path whose joint may fold or intersect itself: the cut of the walls at
/// its mitre plane reached a neighbouring corner or an end of the path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerFit {
    /// The index of the corner's first sample (incoming tangent) in the path.
    pub sample: usize,
    /// Where the corner is.
    pub position: DVec3,
    /// The corner's turning angle, in radians.
    pub angle: f64,
}

/// The welded layout built: the split mesh and the position id of each of its vertices.
pub(super) struct Welded {
    /// A vertex per (ring, slot) and per cap corner, with per-vertex normals and UVs.
    pub split: TriMesh,
    /// Position id of each split vertex (into `positions`).
    pub pid: Vec<u32>,
    /// The distinct positions.
    pub positions: Vec<DVec3>,
    /// Corners whose joints may fold.
    pub unfit: Vec<CornerFit>,
}

/// A copy of the profile in the mesh.
#[derive(Clone, Debug)]
struct Ring {
    /// Position id per slot.
    pids: Vec<u32>,
    /// Normal per slot; `None`: the area-weighted normal of the faces around it (a bevel
    /// band, the inner side of a round joint).
    normals: Vec<Option<DVec3>>,
    /// The point of the path it is placed at (for orientation).
    centre: DVec3,
    /// Arc-length parameter along the path in `[0, 1]` (the UV's `u`).
    u: f64,
}

/// Where a joint sits in the ring list, for cutting the walls around it.
struct JointSite {
    /// Ring index of the joint's first ring (the incoming wall's end).
    first: usize,
    /// Ring index of its last ring (the outgoing wall's start).
    last: usize,
    /// The corner and the mitre plane's normal.
    corner: DVec3,
    m: DVec3,
    /// Path sample of the corner, and its angle.
    sample: usize,
    angle: f64,
}

/// The profile's slots: which position each profile point has.
pub(super) struct Slots {
    /// Distinct-point index per slot.
    pub(super) point: Vec<usize>,
    /// For each distinct point, its first slot.
    pub(super) first_slot: Vec<usize>,
    /// Strips `i → i + 1` with two distinct points.
    pub(super) strips: Vec<usize>,
}

impl Slots {
    pub(super) fn new(profile: &Profile) -> Self {
        let n = profile.points.len();
        let twin = twins(&profile.points, true);
        let closed = profile.is_closed();
        let mut point = Vec::with_capacity(n);
        let mut first_slot = Vec::new();
        for i in 0..n {
            let d = if i > 0 && twin[i - 1] {
                point[i - 1]
            } else if closed && i == n - 1 {
                0
            } else {
                first_slot.push(i);
                first_slot.len() - 1
            };
            point.push(d);
        }
        let strips = (0..n - 1).filter(|&i| point[i] != point[i + 1]).collect();
        Self { point, first_slot, strips }
    }
}

/// Builds the welded layout of [`super::generalized_cylinder`]; `profile` and `path` are
/// checked.
pub(super) fn build(profile: &Profile, path: &SweepPath, options: SweepOptions) -> Result<Welded, SweepError> {
    let slots = Slots::new(profile);
    let n = path.positions.len();
    let size = extent(path.positions.iter().copied()).max(1e-300);
    let near = |a: usize, b: usize| path.positions[a].distance(path.positions[b]) <= 1e-12 * size;
    // a corner is two samples at one point, not a run of them (a path that stays put, like a
    // circle of radius 0, turns the profile about the point: a revolution)
    let same = |a: usize, b: usize| {
        near(a, b) && !(a > 0 && near(a - 1, a)) && !(b + 1 < path.positions.len() && near(b, b + 1))
    };
    let turns = |a: usize, b: usize| path.frames[a].t.dot(path.frames[b].t) < 1.0 - 1e-12;
    let closed = path.is_closed();
    let seam_corner = closed && turns(n - 1, 0);
    let us = super::normalized_lengths(path.positions.windows(2).map(|w| w[0].distance(w[1])));
    let scale = |k: usize| path.scales.get(k).copied().unwrap_or(DVec2::ONE);
    let frames = carried_frames(path, &same, closed && seam_corner);
    let path = &SweepPath { frames, ..path.clone() };

    let mut b = Builder {
        positions: Vec::new(),
        rings: Vec::new(),
        joints: Vec::new(),
        unfit: Vec::new(),
        slots: &slots,
        profile,
        options,
        // points closer than this are one (a pole where the path stays put, a pinch)
        tolerance: 1e-12 * (size + extent(profile.points.iter().map(|q| q.extend(0.0)))),
    };
    // a seam corner: the joint is built at the end, and its last ring also starts the list
    let (start, end) = if seam_corner { (1, n - 1) } else { (0, n) };
    let mut k = start;
    while k < end {
        let (f, v, sc) = (path.frames[k], path.positions[k], scale(k));
        if k + 1 < end && same(k, k + 1) {
            if turns(k, k + 1) {
                b.joint(f, path.frames[k + 1].t, v, sc, us[k], k);
            } else {
                b.plain(f, v, sc, us[k]);
            }
            k += 2;
        } else {
            b.plain(f, v, sc, us[k]);
            k += 1;
        }
    }
    if seam_corner {
        let inner_joints = b.joints.len();
        b.joint(path.frames[n - 1], path.frames[0].t, path.positions[n - 1], scale(n - 1), 1.0, n - 1);
        // the joint's last ring also starts the path (u = 0), and the walls after the seam
        // are cut from there
        let mut first = b.rings[b.rings.len() - 1].clone();
        first.u = 0.0;
        b.rings.insert(0, first);
        // (a U-turn at the seam has no mitre plane and is no joint site to cut from)
        for (i, j) in b.joints.iter_mut().enumerate() {
            j.first += 1;
            j.last = if i == inner_joints { 0 } else { j.last + 1 };
        }
    }
    b.cut_walls(closed, size);
    if closed && !seam_corner {
        // the last copy is the first one again (with its own UV u = 1 and normals)
        let last = b.rings.len() - 1;
        let pids = b.rings[0].pids.clone();
        b.rings[last].pids = pids;
    }
    let capped = options.caps && !closed && profile.is_closed();
    let caps = capped.then(|| [-path.frames[0].t, path.frames[n - 1].t]);
    Ok(b.mesh(!path.scales.is_empty(), caps))
}

/// The path's frames with the profile carried through each corner by the smallest rotation:
/// where the frame method turns the outgoing frame about the tangent by `δ` more than that,
/// the turn is taken back and given out again along the wall after the corner, by arc
/// length, until the next corner or the end of the path.
fn carried_frames(path: &SweepPath, same: &impl Fn(usize, usize) -> bool, seam_corner: bool) -> Vec<Frame> {
    let n = path.positions.len();
    let mut frames = path.frames.clone();
    let turns = |a: usize, b: usize| frames[a].t.dot(frames[b].t) < 1.0 - 1e-12;
    let mut corners: Vec<(usize, usize)> =
        (0..n - 1).filter(|&k| same(k, k + 1) && turns(k, k + 1)).map(|k| (k, k + 1)).collect();
    if seam_corner {
        corners.push((n - 1, 0));
    }
    let starts: Vec<usize> = corners.iter().map(|c| c.0).collect();
    for &(k_in, k_out) in &corners {
        let (f_in, f_out) = (frames[k_in], frames[k_out]);
        let axis = f_in.t.cross(f_out.t);
        let carried = match axis.try_normalize() {
            Some(a) => DQuat::from_axis_angle(a, f_in.t.angle_between(f_out.t)) * f_in.n,
            None => f_in.n,
        };
        let delta = carried.cross(f_out.n).dot(f_out.t).atan2(carried.dot(f_out.n));
        if delta.abs() < 1e-12 {
            continue;
        }
        // the wall after the corner: up to the next corner or the end of the path
        let mut wall = vec![k_out];
        let mut j = k_out;
        while wall.len() < n {
            j = if seam_corner { (j + 1) % n } else { j + 1 };
            if j >= n || starts.contains(&j) || j == k_out {
                break;
            }
            wall.push(j);
        }
        let mut lengths = vec![0.0];
        for w in wall.windows(2) {
            lengths.push(lengths[lengths.len() - 1] + path.positions[w[0]].distance(path.positions[w[1]]));
        }
        let total = lengths[lengths.len() - 1];
        for (&j, &s) in wall.iter().zip(&lengths) {
            let share = if total > 0.0 { 1.0 - s / total } else { 1.0 };
            frames[j] = frames[j].rotated(-delta * share);
        }
    }
    frames
}

struct Builder<'a> {
    positions: Vec<DVec3>,
    rings: Vec<Ring>,
    joints: Vec<JointSite>,
    unfit: Vec<CornerFit>,
    slots: &'a Slots,
    profile: &'a Profile,
    options: SweepOptions,
    tolerance: f64,
}

impl Builder<'_> {
    /// The offsets of the distinct profile points placed with `frame` and `scale`.
    fn offsets(&self, frame: Frame, scale: DVec2) -> Vec<DVec3> {
        self.slots
            .first_slot
            .iter()
            .map(|&i| {
                let q = self.profile.points[i];
                frame.n * (q.x * scale.x) + frame.b * (q.y * scale.y)
            })
            .collect()
    }

    /// The profile normals placed with `frame`, one per slot (turned by `turn`).
    fn normals(&self, frame: Frame, turn: DQuat) -> Vec<Option<DVec3>> {
        self.profile.normals.iter().map(|n| Some(turn * -(frame.n * n.x + frame.b * n.y))).collect()
    }

    /// New positions, one per distinct point; returns each slot's id.
    fn place(&mut self, points: impl Iterator<Item = DVec3>) -> Vec<u32> {
        let base = self.positions.len() as u32;
        self.positions.extend(points);
        self.slots.point.iter().map(|&d| base + d as u32).collect()
    }

    /// An ordinary copy of the profile.
    fn plain(&mut self, frame: Frame, centre: DVec3, scale: DVec2, u: f64) {
        let offsets = self.offsets(frame, scale);
        let mut pids = self.place(offsets.iter().map(|o| centre + *o));
        // a point that has not moved since the previous copy, or that meets another point
        // of this copy (a pinch), is the same vertex
        let previous = self.rings.last().map(|r| r.pids.clone());
        // earlier slots of this copy by cells of the tolerance's size (a long profile would
        // otherwise compare every pair)
        let cell = self.tolerance.max(f64::MIN_POSITIVE);
        let key = |p: DVec3| {
            let c = (p / cell).floor();
            (c.x as i64, c.y as i64, c.z as i64)
        };
        let mut cells: std::collections::HashMap<(i64, i64, i64), Vec<usize>> = std::collections::HashMap::new();
        for s in 0..pids.len() {
            let p = self.positions[pids[s] as usize];
            let close = |id: u32| self.positions[id as usize].distance(p) <= self.tolerance;
            if let Some(&id) = previous.as_ref().map(|prev| &prev[s]).filter(|&&id| close(id)) {
                pids[s] = id;
            } else {
                // the first earlier slot within the tolerance, as a scan in slot order finds
                let (cx, cy, cz) = key(p);
                let mut first: Option<usize> = None;
                for x in [cx.saturating_sub(1), cx, cx.saturating_add(1)] {
                    for y in [cy.saturating_sub(1), cy, cy.saturating_add(1)] {
                        for z in [cz.saturating_sub(1), cz, cz.saturating_add(1)] {
                            for &t in cells.get(&(x, y, z)).into_iter().flatten() {
                                if first.is_none_or(|f| t < f) && close(pids[t]) {
                                    first = Some(t);
                                }
                            }
                        }
                    }
                }
                if let Some(t) = first {
                    pids[s] = pids[t];
                }
            }
            cells.entry(key(self.positions[pids[s] as usize])).or_default().push(s);
        }
        let normals = self.normals(frame, DQuat::IDENTITY);
        self.rings.push(Ring { pids, normals, centre, u });
    }

    /// The rings of the joint at a corner: the profile placed with the incoming `frame` at
    /// `corner`, turned onto `t_out` (see the module docs).
    fn joint(&mut self, frame: Frame, t_out: DVec3, corner: DVec3, scale: DVec2, u: f64, sample: usize) {
        let t_in = frame.t;
        let angle = t_in.dot(t_out).clamp(-1.0, 1.0).acos();
        // a U-turn has no plane of turning: about N
        let axis = t_in.cross(t_out).try_normalize().unwrap_or(frame.n);
        let turn = |beta: f64| DQuat::from_axis_angle(axis, beta);
        let offsets = self.offsets(frame, scale);
        let first = self.rings.len();
        let Some(m) = (t_in + t_out).try_normalize().filter(|m| m.dot(t_in) > 1e-6) else {
            // a U-turn: the profile turns about the corner, and folds over itself
            self.unfit.push(CornerFit { sample, position: corner, angle });
            self.arc(&offsets, &vec![None; offsets.len()], frame, corner, u, angle, turn);
            return;
        };
        let cos_half = m.dot(t_in);
        let mitre = |o: DVec3| corner + o - o.dot(m) / cos_half * t_in;
        let join = match self.options.join {
            Join::Mitre if 1.0 / cos_half > self.options.mitre_limit => Join::Bevel,
            join => join,
        };
        if join == Join::Mitre {
            let pids = self.place(offsets.iter().map(|&o| mitre(o)));
            for turned in [DQuat::IDENTITY, turn(angle)] {
                let normals = self.normals(frame, turned);
                self.rings.push(Ring { pids: pids.clone(), normals, centre: corner, u });
            }
        } else {
            // inner points at their mitre points, shared by every ring of the joint; a point
            // on the axis of the turn (within rounding) stays put, so it counts as inner
            let reach = offsets.iter().fold(0.0, |r: f64, o| r.max(o.length()));
            let mut inner = Vec::with_capacity(offsets.len());
            for &o in &offsets {
                inner.push((o.dot(t_out) > -1e-9 * reach).then(|| {
                    self.positions.push(mitre(o));
                    (self.positions.len() - 1) as u32
                }));
            }
            self.arc(&offsets, &inner, frame, corner, u, angle, turn);
        }
        let last = self.rings.len() - 1;
        self.joints.push(JointSite { first, last, corner, m, sample, angle });
    }

    /// The rings of a round or bevelled joint: outer points turned about the corner by
    /// `turn(β)` for β from 0 to `angle`, inner points at the positions `inner` gives.
    #[allow(clippy::too_many_arguments)]
    fn arc(
        &mut self,
        offsets: &[DVec3],
        inner: &[Option<u32>],
        frame: Frame,
        corner: DVec3,
        u: f64,
        angle: f64,
        turn: impl Fn(f64) -> DQuat,
    ) {
        let round = self.options.join == Join::Round;
        let step = self.options.round_step;
        let arcs = if round && step > 0.0 { ((angle / step).ceil() as usize).clamp(1, 1024) } else { 1 };
        for j in 0..=arcs {
            let beta = angle * j as f64 / arcs as f64;
            let q = turn(beta);
            let mut ids = Vec::with_capacity(offsets.len());
            for (d, &o) in offsets.iter().enumerate() {
                ids.push(inner[d].unwrap_or_else(|| {
                    self.positions.push(corner + q * o);
                    (self.positions.len() - 1) as u32
                }));
            }
            let pids: Vec<u32> = self.slots.point.iter().map(|&d| ids[d]).collect();
            let given = self.normals(frame, q);
            // the band's own normals: averaged over a bevel, and on a round joint's inner
            // points; a round arc's outer points turn with it
            let band: Vec<Option<DVec3>> = if round {
                given.iter().zip(&self.slots.point).map(|(n, &d)| if inner[d].is_some() { None } else { *n }).collect()
            } else {
                vec![None; given.len()]
            };
            let ring = |normals| Ring { pids: pids.clone(), normals, centre: corner, u };
            // the walls' ends keep the walls' normals: a copy of the ring on each side
            if j == 0 {
                self.rings.push(ring(given.clone()));
            }
            self.rings.push(ring(band));
            if j == arcs {
                self.rings.push(ring(given));
            }
        }
    }

    /// Moves the points of the rings around each joint that lie beyond its mitre plane onto
    /// the joint's own points, and notes the corners where that reaches another joint or an
    /// end of the path.
    fn cut_walls(&mut self, closed: bool, size: f64) {
        let count = self.rings.len();
        let mut in_joint = vec![false; count];
        for j in &self.joints {
            let range = if j.last >= j.first { j.first..=j.last } else { j.first..=count - 1 };
            range.for_each(|r| in_joint[r] = true);
            in_joint[j.last] = true;
        }
        // the closing copy of a closed path is ring 0 again
        let walkable = if closed { count.saturating_sub(1) } else { count };
        for j in &self.joints {
            for (anchor, dir) in [(j.first, -1isize), (j.last, 1)] {
                let anchor_pids = self.rings[anchor].pids.clone();
                let mut at = anchor as isize;
                let mut cut_last = true;
                for _ in 0..walkable {
                    at += dir;
                    if closed {
                        at = at.rem_euclid(walkable.max(1) as isize);
                    }
                    if at < 0 || at as usize >= count || in_joint[at as usize] {
                        break;
                    }
                    let ring = &mut self.rings[at as usize];
                    cut_last = false;
                    for (pid, &anchor_pid) in ring.pids.iter_mut().zip(&anchor_pids) {
                        let side = (self.positions[*pid as usize] - j.corner).dot(j.m) * -(dir as f64);
                        if side > 1e-12 * size && *pid != anchor_pid {
                            *pid = anchor_pid;
                            cut_last = true;
                        }
                    }
                    if !cut_last {
                        break;
                    }
                }
                if cut_last {
                    self.unfit.push(CornerFit { sample: j.sample, position: j.corner, angle: j.angle });
                }
            }
        }
        self.unfit.sort_by_key(|c| c.sample);
        self.unfit.dedup_by_key(|c| c.sample);
    }

    /// The split mesh of the rings (and the caps facing `caps`), oriented outward.
    fn mesh(self, scaled: bool, caps: Option<[DVec3; 2]>) -> Welded {
        let p = self.slots.point.len();
        let vs = self.profile.normalized_lengths();
        let uvs = self.options.uvs;
        let mut split = TriMesh::default();
        let mut pid = Vec::with_capacity(self.rings.len() * p);
        let mut averaged = Vec::new();
        for ring in &self.rings {
            for (i, &id) in ring.pids.iter().enumerate() {
                split.positions.push(self.positions[id as usize]);
                pid.push(id);
                if ring.normals[i].is_none() {
                    averaged.push(split.normals.len());
                }
                split.normals.push(ring.normals[i].unwrap_or(DVec3::ZERO));
                if uvs {
                    split.uvs.push(DVec2::new(ring.u, vs[i]));
                }
            }
        }
        let distinct = |t: &[u32; 3]| {
            pid[t[0] as usize] != pid[t[1] as usize]
                && pid[t[1] as usize] != pid[t[2] as usize]
                && pid[t[0] as usize] != pid[t[2] as usize]
        };
        for r in 0..self.rings.len().saturating_sub(1) {
            for &i in &self.slots.strips {
                let (a, c) = ((r * p + i) as u32, ((r + 1) * p + i) as u32);
                for t in [[a, a + 1, c], [a + 1, c + 1, c]] {
                    if distinct(&t) {
                        split.triangles.push(t);
                    }
                }
            }
        }
        let given: Vec<bool> = {
            let mut g = vec![true; split.positions.len()];
            averaged.iter().for_each(|&v| g[v] = false);
            g
        };
        // one vertex where position, UV and normal agree (the seams of a smooth closed
        // profile or path), so that averaged normals average both sides
        let twin = super::attribute_twins(&split, &pid, |v| given[v]);
        for t in &mut split.triangles {
            *t = t.map(|v| twin[v as usize]);
        }
        // outward: away from the ring's point on the path
        let rings = &self.rings;
        super::orient_where(&mut split, |q, v| q - rings[v / p].centre, |v| given[v]);
        if scaled {
            super::face_average_normals(&mut split);
        } else if !averaged.is_empty() {
            let sums = split.vertex_normal_sums();
            for v in averaged {
                split.normals[v] = sums[v].try_normalize().unwrap_or(DVec3::ZERO);
            }
        }
        let mut out = Welded { split, pid, positions: self.positions, unfit: self.unfit };
        if let Some([start, end]) = caps {
            let ring =
                |r: usize| -> Vec<u32> { self.slots.first_slot.iter().map(|&i| self.rings[r].pids[i]).collect() };
            let points: Vec<DVec2> = self.slots.first_slot.iter().map(|&i| self.profile.points[i]).collect();
            out.cap(&points, &ring(0), start, uvs);
            out.cap(&points, &ring(self.rings.len() - 1), end, uvs);
        }
        out
    }
}

impl Welded {
    /// A flat cap over the ring `pids` (the distinct profile `points` in order), facing
    /// `outward`: its own split vertices (normal `outward`, UV the profile point) at the
    /// ring's positions.
    fn cap(&mut self, points: &[DVec2], pids: &[u32], outward: DVec3, uvs: bool) {
        let base = self.split.positions.len() as u32;
        let normal = outward.normalize_or_zero();
        for (q, &id) in points.iter().zip(pids) {
            self.split.positions.push(self.positions[id as usize]);
            self.split.normals.push(normal);
            if uvs {
                self.split.uvs.push(*q);
            }
            self.pid.push(id);
        }
        let first = self.split.triangles.len();
        for t in super::triangulate_polygon(points) {
            let ids = t.map(|i| pids[i]);
            if ids[0] != ids[1] && ids[1] != ids[2] && ids[0] != ids[2] {
                self.split.triangles.push(t.map(|i| base + i as u32));
            }
        }
        let facing: f64 = (first..self.split.triangles.len()).map(|i| self.split.face_normal(i).dot(outward)).sum();
        if facing < 0.0 {
            for t in &mut self.split.triangles[first..] {
                t.swap(1, 2);
            }
        }
    }
}
