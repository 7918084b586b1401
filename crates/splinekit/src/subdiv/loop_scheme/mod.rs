//! Loop subdivision of triangle meshes.
//!
//! Each level splits every triangle into four, inserting one *odd* vertex per edge and moving
//! the *even* (old) vertices:
//!
//! - odd, interior edge `(v0, v1)` with opposite vertices `a`, `b`: `3/8·(v0 + v1) + 1/8·(a + b)`;
//! - odd, boundary edge: the midpoint;
//! - even, interior, valence `n`, neighbours `qᵢ`: `(1 − nβ)·p + β·Σqᵢ` with β from
//!   [`LoopWeights`](super::LoopWeights) — Loop's original `β(n) = (1/n)(5/8 − (3/8 + 1/4·cos(2π/n))²)` by default
//!   (what OpenSubdiv, CGAL, PMP and trimesh compute), or Warren's `3/(8n)`, `3/16` for `n = 3`
//!   (the course's formula; libigl and Open3D);
//! - even, boundary, boundary neighbours `a`, `b`: `3/4·p + 1/8·(a + b)` (the crease rule: the
//!   boundary curve is a cubic B-spline of its own); with [`BoundaryRule::Corners`](super::BoundaryRule::Corners) a vertex
//!   with a single face stays where it is. [`BoundaryRule::Smooth`](super::BoundaryRule::Smooth) is OpenSubdiv's
//!   `VTX_BOUNDARY_EDGE_ONLY`, `Corners` its `VTX_BOUNDARY_EDGE_AND_CORNER`.
//!
//! Triangle `(i0, i1, i2)` with odd vertices `m01, m12, m20` becomes `(i0, m01, m20)`,
//! `(i1, m12, m01)`, `(i2, m20, m12)`, `(m01, m12, m20)`, in that order at `4f .. 4f + 4`:
//! orientation is kept. A level's vertices are the parent's vertices (same indices) followed
//! by one odd vertex per parent edge, in the parent's edge order.
//!
//! **Attributes.** Colours (per vertex) are carried with the position weights. Normals and
//! UVs are face-varying: each is subdivided as a mesh of its own over the same triangles,
//! whose edges are joined only where both sides share the value indices — a UV seam is a
//! boundary of the UV mesh, so it gets the boundary rules and the two sides never blend.
//! Normals are renormalized at every level (the base's too), so that subdividing a written
//! level-k mesh once more gives level k + 1. With
//! [`LoopOptions::color_by_level`], vertices are instead coloured by the level that created
//! them ([`LEVEL_COLORS`]).
//!
//! **Non-manifold and degenerate meshes** (an edge of more than two triangles or of two running
//! the same way, a vertex whose triangles form several fans, a triangle that repeats a vertex)
//! are subdivided by [`loop_subdivide`] with OpenSubdiv's rules: their non-manifold edges are
//! infinitely sharp creases and their non-manifold vertices corners (see
//! [`nonmanifold`](super::nonmanifold)), level by level through the subdivision matrices, so more
//! slowly, carrying positions and colours (not normals and UVs). [`LoopPyramid`] refuses them.
//!
//! **Speed.** The base level's adjacency is built once ([`Topology::build`]); every further
//! level's adjacency follows in closed form ([`topology`](super::topology)), and each pass is
//! a parallel map (rayon) over vertices, edges or faces writing its own output slot, so
//! results do not depend on the number of threads. Per-vertex and per-edge code does not
//! allocate. A one-shot subdivision ([`LoopPyramid::into_refined`], [`loop_subdivide`]) goes
//! further: it makes each level from the tables of the level two above it (`grandchild`), and
//! the finest from those three above it (`great`), so tables and triangles are made only up
//! to three levels above the finest (for three levels: none beyond the base), and the finest
//! level's triangles and values are written straight from them, the triangles side by side
//! with the last steps' values (`rayon::join`), so that on several threads neither waits at
//! the ends of the other's passes.

mod stencils;
mod three_steps;
mod two_steps;

use std::collections::HashMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use stencils::even_ring;
use three_steps::{great_grandchild_triangles, great_grandchild_values};
use two_steps::{grandchild_triangles, grandchild_values};

use super::attribute::Attribute;
use super::counts::{self, Counts};
use super::crease::Creases;
use super::error::SubdivError;
use super::level_colors::{LEVEL_COLORS, child_colors};
use super::nonmanifold::General;
use super::options::{CreasingMethod, LoopOptions, Rules};
use super::topology::{MIN_LEN, MIN_RINGS, Table, Topology, child_level, next, prev};
use crate::mesh::{FaceVarying, NONE, PolyMesh, TriMesh};

/// The new value of even vertex `v`.
#[inline]
fn even<T: Attribute>(topo: &Table<'_>, p: &[T], v: u32, rules: &Rules) -> T {
    let out = |h: u32| p[topo.tri(h / 3)[next(h % 3) as usize] as usize];
    let inc = |h: u32| p[topo.tri(h / 3)[(h % 3) as usize] as usize];
    even_ring(topo, p[v as usize], v, rules, out, inc)
}

/// The value of the odd vertex on edge `e`.
#[inline]
fn odd<T: Attribute>(topo: &Table<'_>, p: &[T], e: u32) -> T {
    let h = topo.edge_owner(e);
    let i = h % 3;
    let t = topo.tri(h / 3);
    let a = p[t[i as usize] as usize];
    let b = p[t[next(i) as usize] as usize];
    let tw = topo.twin(h);
    if tw == NONE {
        return (a + b) * 0.5;
    }
    let c = p[t[prev(i) as usize] as usize];
    let d = p[topo.tri(tw / 3)[prev(tw % 3) as usize] as usize];
    (a + b) * 0.375 + (c + d) * 0.125
}

/// One level of values: the parent's evens, then one odd value per parent edge.
fn refine_values<T: Attribute>(topo: &Table<'_>, p: &[T], rules: &Rules) -> Vec<T> {
    let nv = topo.num_vertices() as u32;
    let mut out = Vec::new();
    (0..nv + topo.num_edges() as u32)
        .into_par_iter()
        .with_min_len(MIN_RINGS)
        .map(|k| if k < nv { even(topo, p, k, rules) } else { odd(topo, p, k - nv) })
        .collect_into_vec(&mut out);
    out
}

/// A face-varying attribute at one level: its own triangles (value indices) and topology.
#[derive(Clone, Debug)]
struct Channel<T> {
    triangles: Vec<[u32; 3]>,
    topology: Option<Topology>,
    values: Vec<T>,
}

impl Channel<DVec3> {
    /// The channel with its values scaled to unit length (zero stays zero).
    fn renormalized(mut self) -> Self {
        for n in &mut self.values {
            *n = n.normalize_or_zero();
        }
        self
    }
}

impl<T: Attribute> Channel<T> {
    /// The base level of `fv` over triangles with position topology `pos`: edges join where
    /// both sides share value indices; a value whose corners fall into several fans is
    /// duplicated per fan, so every value is a manifold vertex of the channel's mesh.
    fn base(attribute: &'static str, pos: &Topology, fv: &FaceVarying<T>) -> Result<Self, SubdivError> {
        let nh = pos.twin.len();
        if fv.indices.len() != nh {
            return Err(SubdivError::Attribute {
                attribute,
                problem: format!("{} indices for {nh} face corners", fv.indices.len()),
            });
        }
        if let Some(c) = fv.indices.iter().position(|&i| i as usize >= fv.values.len()) {
            return Err(SubdivError::Attribute {
                attribute,
                problem: format!("face {} refers to value {}, but there are {}", c / 3, fv.indices[c], fv.values.len()),
            });
        }
        let mut idx = fv.indices.clone();
        let mut values = fv.values.clone();
        let nx = |h: usize| h - h % 3 + next((h % 3) as u32) as usize;
        let pv = |h: usize| h - h % 3 + prev((h % 3) as u32) as usize;
        let twin: Vec<u32> = (0..nh)
            .map(|h| {
                let t = pos.twin[h];
                if t != NONE && idx[h] == idx[nx(t as usize)] && idx[nx(h)] == idx[t as usize] { t } else { NONE }
            })
            .collect();
        let mut assigned = vec![false; nh];
        let mut used = vec![false; values.len()];
        for h0 in 0..nh {
            if assigned[h0] {
                continue;
            }
            // Rewind to the start of h0's fan (or stay, if the fan is closed).
            let mut s = h0;
            loop {
                let t = twin[s];
                if t == NONE {
                    break;
                }
                let b = nx(t as usize);
                if b == h0 {
                    break;
                }
                s = b;
            }
            let u = idx[s] as usize;
            let target = if used[u] {
                values.push(values[u]);
                (values.len() - 1) as u32
            } else {
                used[u] = true;
                u as u32
            };
            let mut h = s;
            loop {
                assigned[h] = true;
                idx[h] = target;
                let t = twin[pv(h)];
                if t == NONE || t as usize == s {
                    break;
                }
                h = t as usize;
            }
        }
        let triangles: Vec<[u32; 3]> = idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        let topology = Topology::from_twins(&triangles, twin, values.len());
        Ok(Self { triangles, topology: Some(topology), values })
    }

    fn refine(&mut self, rules: &Rules, with_topology: bool) -> Self {
        let topo = self.topology.as_ref().expect("a level is refined only with its topology");
        let values = refine_values(&Table { triangles: &self.triangles, topology: topo }, &self.values, rules);
        let (triangles, topology) = topo.refine(&self.triangles, with_topology);
        Self { triangles, topology, values }
    }

    fn face_varying(&self) -> FaceVarying<T> {
        FaceVarying { values: self.values.clone(), indices: self.triangles.iter().flatten().copied().collect() }
    }
}

/// One level of a [`LoopPyramid`].
#[derive(Clone, Debug)]
pub struct LoopLevel {
    /// Triangles, counter-clockwise from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Vertex colours (empty when the input has none and colour-by-level is off).
    pub colors: Vec<DVec3>,
    /// Which level this is (0 = base).
    depth: usize,
    topology: Option<Topology>,
    normals: Option<Channel<DVec3>>,
    uvs: Option<Channel<DVec2>>,
}

impl LoopLevel {
    /// Number of vertices.
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    #[must_use]
    pub fn num_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// Which level this is (0 = base).
    #[must_use]
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// This level as a triangle mesh for the writers, consuming it. Without normals and UVs
    /// the triangles and positions are moved, not copied; with them, a vertex on a seam
    /// becomes one vertex per distinct (position, normal, UV) corner, so every side keeps
    /// its own values (normals renormalized).
    #[must_use]
    pub fn into_tri_mesh(self) -> TriMesh {
        if self.normals.is_none() && self.uvs.is_none() {
            return TriMesh {
                positions: self.positions,
                triangles: self.triangles,
                colors: self.colors,
                ..TriMesh::default()
            };
        }
        let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
        let mut mesh = TriMesh::default();
        let mut triangles = Vec::with_capacity(self.triangles.len());
        for (f, t) in self.triangles.iter().enumerate() {
            let mut out = [0u32; 3];
            for (i, &v) in t.iter().enumerate() {
                let key = [
                    v,
                    self.normals.as_ref().map_or(0, |c| c.triangles[f][i]),
                    self.uvs.as_ref().map_or(0, |c| c.triangles[f][i]),
                ];
                out[i] = *ids.entry(key).or_insert_with(|| {
                    mesh.positions.push(self.positions[v as usize]);
                    if let Some(c) = self.colors.get(v as usize) {
                        mesh.colors.push(*c);
                    }
                    if let Some(c) = &self.normals {
                        mesh.normals.push(c.values[key[1] as usize].normalize_or_zero());
                    }
                    if let Some(c) = &self.uvs {
                        mesh.uvs.push(c.values[key[2] as usize]);
                    }
                    (mesh.positions.len() - 1) as u32
                });
            }
            triangles.push(out);
        }
        mesh.triangles = triangles;
        mesh
    }

    /// This level's triangles and stored tables.
    ///
    /// # Panics
    /// If the level has no tables.
    fn table(&self) -> Table<'_> {
        Table { triangles: &self.triangles, topology: self.topology.as_ref().expect("a level with tables") }
    }

    /// This level as a polygon mesh (normals renormalized).
    #[must_use]
    pub fn to_mesh(&self) -> PolyMesh {
        let mut m = PolyMesh::from_triangles(self.positions.clone(), &self.triangles);
        m.colors.clone_from(&self.colors);
        m.normals = self.normals.as_ref().map(|c| {
            let mut fv = c.face_varying();
            for n in &mut fv.values {
                *n = n.normalize_or_zero();
            }
            fv
        });
        m.uvs = self.uvs.as_ref().map(Channel::face_varying);
        m
    }
}

/// The levels of a Loop subdivision, from the base mesh (level 0) to the finest: refine and
/// coarsen at will; edited base positions are pushed through every level without rebuilding
/// any topology ([`Self::set_base_positions`]).
#[derive(Clone, Debug)]
pub struct LoopPyramid {
    options: LoopOptions,
    rules: Rules,
    levels: Vec<LoopLevel>,
}

impl LoopPyramid {
    /// Level 0 of `mesh`.
    ///
    /// # Errors
    /// Non-triangle faces, non-manifold or inconsistently oriented topology or a triangle that
    /// repeats a vertex (which [`loop_subdivide`] takes), malformed attributes — naming the
    /// face, edge or vertex.
    pub fn new(mesh: &PolyMesh, options: LoopOptions) -> Result<Self, SubdivError> {
        // Triangles and positions are copied in parallel: the copy is cheap, the fresh pages
        // it writes are not (each is cleared by the one thread that touches it first). With
        // triangles only, the copies are made while the adjacency is built from the mesh's own
        // corners, so that on several threads they cost no time of their own.
        let n = mesh.num_vertices();
        let triangles_only = mesh.face_offsets.iter().enumerate().all(|(f, &o)| o as usize == 3 * f)
            && mesh.face_vertices.len() == 3 * mesh.num_faces();
        let (triangles, topology, positions) = if triangles_only {
            let corners: &[[u32; 3]] = bytemuck::cast_slice(&mesh.face_vertices);
            let (topology, (triangles, positions)) = rayon::join(
                || Topology::build(corners, n),
                || rayon::join(|| par_copy(corners), || par_copy(&mesh.positions)),
            );
            (triangles, topology?, positions)
        } else {
            let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(mesh.num_faces());
            for (face, f) in mesh.faces().enumerate() {
                match f {
                    &[a, b, c] => triangles.push([a, b, c]),
                    _ => return Err(SubdivError::NotTriangles { face, corners: f.len(), scheme: "Loop" }),
                }
            }
            let topology = Topology::build(&triangles, n)?;
            (triangles, topology, par_copy(&mesh.positions))
        };
        if !mesh.colors.is_empty() && mesh.colors.len() != n {
            return Err(SubdivError::Attribute {
                attribute: "colors",
                problem: format!("{} colours for {n} vertices", mesh.colors.len()),
            });
        }
        let normals = mesh
            .normals
            .as_ref()
            .map(|fv| Channel::base("normals", &topology, fv).map(Channel::renormalized))
            .transpose()?;
        let uvs = mesh.uvs.as_ref().map(|fv| Channel::base("uvs", &topology, fv)).transpose()?;
        let colors = if options.color_by_level { vec![LEVEL_COLORS[0]; n] } else { mesh.colors.clone() };
        let level = LoopLevel { triangles, positions, colors, depth: 0, topology: Some(topology), normals, uvs };
        Ok(Self { rules: Rules::new(&options), options, levels: vec![level] })
    }

    /// The options.
    #[must_use]
    pub fn options(&self) -> &LoopOptions {
        &self.options
    }

    /// Number of levels, the base included.
    #[must_use]
    pub fn num_levels(&self) -> usize {
        self.levels.len()
    }

    /// Level `k` (0 = base).
    ///
    /// # Panics
    /// If `k >= self.num_levels()`.
    #[must_use]
    pub fn level(&self, k: usize) -> &LoopLevel {
        &self.levels[k]
    }

    /// The finest level.
    #[must_use]
    pub fn finest(&self) -> &LoopLevel {
        self.levels.last().expect("a pyramid has a base level")
    }

    /// The finest level, consuming the pyramid.
    #[must_use]
    pub fn into_finest(mut self) -> LoopLevel {
        self.levels.pop().expect("a pyramid has a base level")
    }

    /// Adds one level.
    ///
    /// # Errors
    /// [`SubdivError::TooLarge`] if the new level would not fit `u32` indices; then nothing
    /// changes.
    pub fn refine(&mut self) -> Result<(), SubdivError> {
        self.check_depth(self.levels.len())?;
        self.refine_step(false);
        Ok(())
    }

    /// Refines until there are `levels + 1` levels, calling `progress(k)` after level `k` is
    /// made. Only levels that will be refined again get adjacency tables.
    ///
    /// # Errors
    /// [`SubdivError::TooLarge`] if level `levels` would not fit `u32` indices, checked
    /// before any level is made.
    pub fn refine_to(&mut self, levels: usize, mut progress: impl FnMut(usize)) -> Result<(), SubdivError> {
        self.check_depth(levels)?;
        while self.levels.len() <= levels {
            let keep = self.levels.len() < levels;
            self.refine_step(keep);
            progress(self.levels.len() - 1);
        }
        Ok(())
    }

    /// [`SubdivError::TooLarge`] if level `depth` (its positions, or the values of its normals
    /// or UVs) would not fit `u32` indices, counted from the base level's tables.
    fn check_depth(&self, depth: usize) -> Result<(), SubdivError> {
        let base = &self.levels[0];
        let topology = base.topology.as_ref().expect("the base level keeps its tables");
        counts::loop_levels("Loop", "vertices", Counts::of_triangles(topology, base.triangles.len()), 0, depth)?;
        let channel = |topology: Option<&Topology>, triangles: usize, what| match topology {
            Some(t) => counts::loop_levels("Loop", what, Counts::of_triangles(t, triangles), 0, depth).map(|_| ()),
            None => Ok(()),
        };
        if let Some(c) = &base.normals {
            channel(c.topology.as_ref(), c.triangles.len(), "normal values")?;
        }
        if let Some(c) = &base.uvs {
            channel(c.topology.as_ref(), c.triangles.len(), "UV values")?;
        }
        Ok(())
    }

    /// Drops the finest level (never the base). Returns whether a level was dropped.
    pub fn coarsen(&mut self) -> bool {
        self.levels.len() > 1 && self.levels.pop().is_some()
    }

    /// Replaces the base positions and recomputes every finer level's positions and colours
    /// (topology and face-varying attributes are unchanged).
    ///
    /// # Errors
    /// When the number of positions differs from the base's.
    pub fn set_base_positions(&mut self, positions: Vec<DVec3>) -> Result<(), SubdivError> {
        let n = self.levels[0].positions.len();
        if positions.len() != n {
            return Err(SubdivError::Attribute {
                attribute: "positions",
                problem: format!("{} positions for {n} vertices", positions.len()),
            });
        }
        self.levels[0].positions = positions;
        for k in 1..self.levels.len() {
            self.ensure_topology(k - 1);
            let (parent, rest) = self.levels.split_at_mut(k);
            let parent = &parent[k - 1];
            let topo = parent.topology.as_ref().expect("ensured");
            rest[0].positions =
                refine_values(&Table { triangles: &parent.triangles, topology: topo }, &parent.positions, &self.rules);
        }
        Ok(())
    }

    /// Makes sure level `k` has its adjacency tables (derived from level `k − 1`'s).
    fn ensure_topology(&mut self, k: usize) {
        if self.levels[k].topology.is_some() {
            return;
        }
        self.ensure_topology(k - 1);
        let (parent, rest) = self.levels.split_at_mut(k);
        let parent = &parent[k - 1];
        let (_, topology) = parent.topology.as_ref().expect("ensured").refine(&parent.triangles, true);
        rest[0].topology = topology;
        derive_topology(&mut rest[0].normals, &parent.normals);
        derive_topology(&mut rest[0].uvs, &parent.uvs);
    }

    fn refine_step(&mut self, with_topology: bool) {
        self.ensure_topology(self.levels.len() - 1);
        let rules = &self.rules;
        let level = self.levels.last_mut().expect("a pyramid has a base level");
        let depth = level.depth + 1;
        let topo = level.topology.as_ref().expect("ensured");
        let table = Table { triangles: &level.triangles, topology: topo };
        let positions = refine_values(&table, &level.positions, rules);
        let colors = child_colors(self.options.color_by_level, &level.colors, positions.len(), depth, |c| {
            refine_values(&table, c, rules)
        });
        let (triangles, topology) = topo.refine(&level.triangles, with_topology);
        let normals = level.normals.as_mut().map(|c| c.refine(rules, with_topology).renormalized());
        let uvs = level.uvs.as_mut().map(|c| c.refine(rules, with_topology));
        self.levels.push(LoopLevel { triangles, positions, colors, depth, topology, normals, uvs });
    }
}

impl LoopPyramid {
    /// Refines `levels` levels below the finest level like [`Self::refine_to`] and returns
    /// the new finest level (the same to the bit), dropping every level as soon as it is no
    /// longer read: the least time and memory for a one-shot subdivision. Without normals and
    /// UVs, each level's values are made from the tables of the level two above it, and the
    /// finest level's values and triangles from those of the level three above it, so only
    /// levels up to `levels − 3` below get tables and triangles, and besides the output at
    /// most the values of its parent and the tables of two levels are alive.
    ///
    /// # Errors
    /// [`SubdivError::TooLarge`] if the finest level would not fit `u32` indices, checked
    /// before any level is made.
    pub fn into_refined(
        mut self,
        levels: usize,
        mut progress: impl FnMut(usize) + Send,
    ) -> Result<LoopLevel, SubdivError> {
        let last = self.levels.len() - 1;
        self.check_depth(last.saturating_add(levels))?;
        if levels < 2 || self.levels[last].normals.is_some() || self.levels[last].uvs.is_some() {
            for k in 1..=levels {
                self.refine_step(k < levels);
                self.levels.remove(0);
                progress(k);
            }
            return Ok(self.into_finest());
        }
        // Without face-varying channels: each level's values are made two steps below a level
        // with stored tables (the grandchild passes), the finest level's three steps below
        // (the great-grandchild passes), so only the levels up to `levels − 3` get tables and
        // triangles.
        self.ensure_topology(last);
        let mut level = self.levels.pop().expect("a pyramid has a base level");
        self.levels.clear();
        let d0 = level.depth;
        // Steps 1 to levels − 2 when there are four or more, each followed (from step 2 on) by
        // the tables of the level one step below `level`, until `level` is level
        // `levels − 3`, whose tables make the finest level's triangles.
        let before = if levels >= 4 { levels - 2 } else { 0 };
        let mut values = None;
        for k in 1..=before {
            let step = self.value_step(&level, k, levels, values.take());
            if k == 1 {
                (level.positions, level.colors) = (Vec::new(), Vec::new());
            } else {
                let (triangles, topology) = child_level(&level.table());
                level = LoopLevel {
                    triangles,
                    positions: Vec::new(),
                    colors: Vec::new(),
                    depth: d0 + k - 1,
                    topology: Some(topology),
                    normals: None,
                    uvs: None,
                };
            }
            values = Some(step);
            progress(k);
        }
        // The last steps (all of them for two or three levels), side by side with the
        // finest level's triangles, which only need `level`'s tables: on several threads each
        // fills the other's waits at the ends of its passes. On one thread the steps run first
        // and drop their inputs, whose memory then serves the triangles (see the CLI's
        // allocator).
        let great = levels >= 3;
        let ((positions, colors), triangles) = rayon::join(
            || {
                for k in before + 1..=levels {
                    values = Some(self.value_step(&level, k, levels, values.take()));
                    progress(k);
                }
                values.expect("at least one step")
            },
            || {
                let table = level.table();
                if great { great_grandchild_triangles(&table) } else { grandchild_triangles(&table) }
            },
        );
        Ok(LoopLevel { triangles, positions, colors, depth: d0 + levels, topology: None, normals: None, uvs: None })
    }

    /// The positions and colours made by step `k` of `levels` from `parent`, those of the
    /// step before (dropped before it returns; `None` for `k = 1`, which makes the child of
    /// `level` from `level`'s own values), with the tables of `level`: the level two steps
    /// above the one made, or three for the finest of three or more steps.
    fn value_step(
        &self,
        level: &LoopLevel,
        k: usize,
        levels: usize,
        parent: Option<(Vec<DVec3>, Vec<DVec3>)>,
    ) -> (Vec<DVec3>, Vec<DVec3>) {
        let table = level.table();
        let Some((positions, colors)) = parent else {
            return self.child_values(&table, level);
        };
        let great = k == levels && levels >= 3;
        let depth = level.depth + if great { 3 } else { 2 };
        let values = |p: &[DVec3]| {
            if great {
                great_grandchild_values(&table, p, &self.rules)
            } else {
                grandchild_values(&table, p, &self.rules)
            }
        };
        let fine = values(&positions);
        drop(positions);
        let fine_colors = child_colors(self.options.color_by_level, &colors, fine.len(), depth, values);
        (fine, fine_colors)
    }

    /// The positions and colours of the child of `level`, whose topology `topo` is.
    fn child_values(&self, topo: &Table<'_>, level: &LoopLevel) -> (Vec<DVec3>, Vec<DVec3>) {
        let positions = refine_values(topo, &level.positions, &self.rules);
        let colors = child_colors(self.options.color_by_level, &level.colors, positions.len(), level.depth + 1, |c| {
            refine_values(topo, c, &self.rules)
        });
        (positions, colors)
    }
}

/// A copy of `from`, made in parallel.
fn par_copy<T: Copy + Send + Sync>(from: &[T]) -> Vec<T> {
    let mut to = Vec::new();
    from.par_iter().with_min_len(MIN_LEN).copied().collect_into_vec(&mut to);
    to
}

/// Gives a channel the adjacency tables derived from its parent's.
fn derive_topology<T>(channel: &mut Option<Channel<T>>, parent: &Option<Channel<T>>) {
    if let (Some(c), Some(pc)) = (channel.as_mut(), parent.as_ref()) {
        c.topology = pc.topology.as_ref().and_then(|t| t.refine(&pc.triangles, true).1);
    }
}

/// `levels` levels of Loop subdivision of a triangle mesh (see the module docs).
///
/// # Errors
/// As [`LoopPyramid::new`], and [`SubdivError::TooLarge`] if the result would not fit `u32`
/// indices (checked before any level is made).
pub fn loop_subdivide(mesh: &PolyMesh, levels: u32, options: &LoopOptions) -> Result<PolyMesh, SubdivError> {
    match LoopPyramid::new(mesh, *options) {
        Err(SubdivError::Topology(e)) if e.is_nonmanifold() => {
            let no = Creases::default();
            let general = General::loop_scheme(options, &no, CreasingMethod::default());
            general.subdivide(mesh, levels as usize, options.color_by_level).map(|(m, ..)| m)
        }
        pyramid => Ok(pyramid?.into_refined(levels as usize, |_| {})?.to_mesh()),
    }
}
