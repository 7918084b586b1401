//! Subdivision matrices: the fine level's values as fixed weighted sums of the base mesh's
//! vertex values, so that edited base positions (or colours, or any other per-vertex value)
//! can be carried to the fine level again without building any topology.
//!
//! Subdivision is linear in the vertex values: `levels` levels of Loop or Catmull-Clark
//! subdivision give every fine vertex as `Σⱼ wᵢⱼ·Pⱼ` over base vertices `j`, with weights
//! that depend only on the connectivity and the options. [`SubdivisionMatrix`] holds those
//! weights in compressed rows (the fine vertices, in the order the subdivision numbers them),
//! built level by level from the same rules as [`loop_subdivide`](super::loop_subdivide)
//! and [`catmull_clark_subdivide`](super::catmull_clark_subdivide): one level's stencils,
//! multiplied into the product of the levels above. Every row's weights sum to 1 (the rules
//! are affine) and are nonnegative.
//!
//! ```
//! use glam::DVec3;
//! use splinekit::PolyMesh;
//! use splinekit::subdiv::{LoopOptions, SubdivisionMatrix, loop_subdivide};
//!
//! // A tetrahedron.
//! let p = [DVec3::new(1.0, 1.0, 1.0), DVec3::new(1.0, -1.0, -1.0), DVec3::new(-1.0, 1.0, -1.0), DVec3::new(-1.0, -1.0, 1.0)];
//! let mut mesh = PolyMesh::from_triangles(p.to_vec(), &[[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]);
//! let options = LoopOptions::default();
//! let s = SubdivisionMatrix::loop_scheme(&mesh, 2, &options)?;
//! assert_eq!((s.num_rows(), s.num_cols()), (34, 4));
//!
//! // Edit the base mesh and re-apply: no topology is rebuilt.
//! mesh.positions[0] = DVec3::new(2.0, 2.0, 2.0);
//! let fine = s.apply(&mesh.positions)?;
//! let direct = loop_subdivide(&mesh, 2, &options)?;
//! assert!(fine.iter().zip(&direct.positions).all(|(a, b)| (*a - *b).length() < 1e-14));
//! # Ok::<(), splinekit::subdiv::SubdivError>(())
//! ```

use rayon::prelude::*;

use super::catmull_clark::{CatmullClarkOptions, Rings};
use super::loop_scheme::{Attribute, BoundaryRule, LoopOptions, Rules, SubdivError};
use super::topology::{MIN_LEN, Table, Topology, next, prev};
use crate::mesh::{NONE, PolyMesh};

/// A sparse matrix in compressed rows: row `i` gives fine vertex `i` as a weighted sum of
/// base vertices. See the [module docs](self).
#[derive(Clone, Debug, PartialEq)]
pub struct SubdivisionMatrix {
    num_cols: usize,
    /// Row `i` is `entries[offsets[i] .. offsets[i + 1]]`.
    offsets: Vec<usize>,
    /// `(column, weight)`, columns ascending within a row.
    entries: Vec<(u32, f64)>,
}

impl SubdivisionMatrix {
    /// The weights of `levels` levels of Loop subdivision of the triangle mesh `mesh` with
    /// `options` (its weights and boundary rule; colour by level does not matter): row `i`
    /// gives vertex `i` of [`loop_subdivide`](super::loop_subdivide)`(mesh, levels, options)`.
    ///
    /// # Errors
    /// As [`loop_subdivide`](super::loop_subdivide): a face that is not a triangle, or
    /// non-manifold or inconsistently oriented topology, naming it.
    pub fn loop_scheme(mesh: &PolyMesh, levels: u32, options: &LoopOptions) -> Result<Self, SubdivError> {
        let mut triangles = Vec::with_capacity(mesh.num_faces());
        for (face, f) in mesh.faces().enumerate() {
            match f {
                &[a, b, c] => triangles.push([a, b, c]),
                _ => return Err(SubdivError::NotTriangles { face, corners: f.len(), scheme: "Loop" }),
            }
        }
        let rules = Rules::new(options);
        let mut topology = Topology::build(&triangles, mesh.num_vertices())?;
        let mut matrix = Self::identity(mesh.num_vertices());
        for level in 0..levels {
            let table = Table { triangles: &triangles, topology: &topology };
            matrix = loop_level(&table, &rules).times(&matrix);
            if level + 1 < levels {
                let (child, child_topology) = topology.refine(&triangles, true);
                triangles = child;
                topology = child_topology.expect("asked for the child's tables");
            }
        }
        Ok(matrix)
    }

    /// The weights of `levels` levels of Catmull-Clark subdivision of the polygon mesh
    /// `mesh` with `options` (the boundary rule; colour by level does not matter): row `i`
    /// gives vertex `i` of [`catmull_clark_subdivide`](super::catmull_clark_subdivide)`(mesh,
    /// levels, options)`.
    ///
    /// # Errors
    /// As [`catmull_clark_subdivide`](super::catmull_clark_subdivide): non-manifold or
    /// inconsistently oriented topology, naming it.
    pub fn catmull_clark(mesh: &PolyMesh, levels: usize, options: &CatmullClarkOptions) -> Result<Self, SubdivError> {
        let mut matrix = Self::identity(mesh.num_vertices());
        let mut current: Option<PolyMesh> = None;
        for level in 0..levels {
            let m = current.as_ref().unwrap_or(mesh);
            let rings = Rings::new(m)?;
            matrix = catmull_clark_level(&rings, options.boundary).times(&matrix);
            if level + 1 < levels {
                // The child's connectivity only: its positions are never read.
                let (face_offsets, face_vertices) = rings.child_faces();
                let positions = vec![glam::DVec3::ZERO; matrix.num_rows()];
                current = Some(PolyMesh { positions, face_offsets, face_vertices, ..PolyMesh::default() });
            }
        }
        Ok(matrix)
    }

    /// The `n × n` identity (zero levels).
    #[must_use]
    pub fn identity(n: usize) -> Self {
        Self { num_cols: n, offsets: (0..=n).collect(), entries: (0..n as u32).map(|j| (j, 1.0)).collect() }
    }

    /// Number of rows: the fine level's vertices.
    #[must_use]
    pub fn num_rows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of columns: the base mesh's vertices.
    #[must_use]
    pub fn num_cols(&self) -> usize {
        self.num_cols
    }

    /// Number of stored weights.
    #[must_use]
    pub fn num_nonzeros(&self) -> usize {
        self.entries.len()
    }

    /// Row `i`: `(base vertex, weight)` pairs, base vertices ascending.
    ///
    /// # Panics
    /// If `i ≥ num_rows()`.
    #[must_use]
    pub fn row(&self, i: usize) -> &[(u32, f64)] {
        &self.entries[self.offsets[i]..self.offsets[i + 1]]
    }

    /// The fine level's values from the base values `base` (one per base vertex): positions,
    /// colours or any other [`Attribute`]. Rows are computed in parallel.
    ///
    /// # Errors
    /// [`SubdivError::Attribute`] if `base` does not have one value per column.
    pub fn apply<T: Attribute>(&self, base: &[T]) -> Result<Vec<T>, SubdivError> {
        if base.len() != self.num_cols {
            return Err(SubdivError::Attribute {
                attribute: "values",
                problem: format!("{} values for a matrix of {} columns", base.len(), self.num_cols),
            });
        }
        let mut out = Vec::new();
        (0..self.num_rows())
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|i| self.row(i).iter().fold(T::default(), |s, &(j, w)| s + base[j as usize] * w))
            .collect_into_vec(&mut out);
        Ok(out)
    }

    /// `self · inner`: the rows of `self` (over `inner`'s rows) expanded into `inner`'s
    /// columns.
    fn times(&self, inner: &Self) -> Self {
        debug_assert_eq!(self.num_cols, inner.num_rows());
        let mut acc = Accumulator::new(inner.num_cols);
        let mut out = Self { num_cols: inner.num_cols, offsets: vec![0], entries: Vec::new() };
        for i in 0..self.num_rows() {
            for &(k, w) in self.row(i) {
                for &(j, v) in inner.row(k as usize) {
                    acc.add(j, w * v);
                }
            }
            acc.drain_into(&mut out.entries);
            out.offsets.push(out.entries.len());
        }
        out
    }
}

/// Sums weights per column for one row at a time.
struct Accumulator {
    weight: Vec<f64>,
    used: Vec<bool>,
    columns: Vec<u32>,
}

impl Accumulator {
    fn new(n: usize) -> Self {
        Self { weight: vec![0.0; n], used: vec![false; n], columns: Vec::new() }
    }

    #[inline]
    fn add(&mut self, j: u32, w: f64) {
        let k = j as usize;
        if !self.used[k] {
            self.used[k] = true;
            self.columns.push(j);
        }
        self.weight[k] += w;
    }

    /// Appends the row, columns ascending, and clears it.
    fn drain_into(&mut self, out: &mut Vec<(u32, f64)>) {
        self.columns.sort_unstable();
        for &j in &self.columns {
            let k = j as usize;
            out.push((j, self.weight[k]));
            self.weight[k] = 0.0;
            self.used[k] = false;
        }
        self.columns.clear();
    }
}

/// Builds a matrix row by row.
struct Builder {
    acc: Accumulator,
    matrix: SubdivisionMatrix,
}

impl Builder {
    fn new(num_cols: usize) -> Self {
        Self {
            acc: Accumulator::new(num_cols),
            matrix: SubdivisionMatrix { num_cols, offsets: vec![0], entries: Vec::new() },
        }
    }

    #[inline]
    fn add(&mut self, j: u32, w: f64) {
        self.acc.add(j, w);
    }

    fn end_row(&mut self) {
        self.acc.drain_into(&mut self.matrix.entries);
        self.matrix.offsets.push(self.matrix.entries.len());
    }
}

/// One level of Loop: even vertices (the rule of `even_ring`), then one odd vertex per edge.
fn loop_level(topo: &Table<'_>, rules: &Rules) -> SubdivisionMatrix {
    let nv = topo.num_vertices() as u32;
    let mut b = Builder::new(nv as usize);
    let mut ring = Vec::new();
    for v in 0..nv {
        let start = topo.vertex_start(v);
        if start == NONE {
            b.add(v, 1.0);
            b.end_row();
            continue;
        }
        let out = |h: u32| topo.tri(h / 3)[next(h % 3) as usize];
        ring.clear();
        let mut h = start;
        let mut boundary = None;
        loop {
            ring.push(out(h));
            let pr = h - h % 3 + prev(h % 3);
            let tw = topo.twin(pr);
            if tw == NONE {
                boundary = Some(topo.tri(pr / 3)[(pr % 3) as usize]);
                break;
            }
            if tw == start {
                break;
            }
            h = tw;
        }
        match boundary {
            Some(_) if rules.corners && ring.len() == 1 => b.add(v, 1.0),
            Some(arriving) => {
                b.add(v, 0.75);
                b.add(out(start), 0.125);
                b.add(arriving, 0.125);
            }
            None => {
                let n = ring.len() as u32;
                let beta = rules.beta(n);
                b.add(v, 1.0 - f64::from(n) * beta);
                for &r in &ring {
                    b.add(r, beta);
                }
            }
        }
        b.end_row();
    }
    for e in 0..topo.num_edges() as u32 {
        let h = topo.edge_owner(e);
        let i = h % 3;
        let t = topo.tri(h / 3);
        let tw = topo.twin(h);
        if tw == NONE {
            b.add(t[i as usize], 0.5);
            b.add(t[next(i) as usize], 0.5);
        } else {
            b.add(t[i as usize], 0.375);
            b.add(t[next(i) as usize], 0.375);
            b.add(t[prev(i) as usize], 0.125);
            b.add(topo.tri(tw / 3)[prev(tw % 3) as usize], 0.125);
        }
        b.end_row();
    }
    b.matrix
}

/// One level of Catmull-Clark: vertex points, edge points, face points (the rules of
/// `Rings::refine`).
fn catmull_clark_level(rings: &Rings<'_>, boundary: BoundaryRule) -> SubdivisionMatrix {
    let (mesh, adj) = (rings.mesh, &rings.adj);
    let nv = mesh.num_vertices();
    let mut b = Builder::new(nv);
    let face_point = |b: &mut Builder, f: usize, w: f64| {
        let corners = mesh.face(f);
        let share = w / corners.len() as f64;
        for &v in corners {
            b.add(v, share);
        }
    };
    for v in 0..nv as u32 {
        let corners = adj.corners_of(v);
        if corners.is_empty() {
            b.add(v, 1.0);
        } else if let Some((a, c)) = rings.boundary_neighbours(v) {
            if boundary == BoundaryRule::Corners && corners.len() == 1 {
                b.add(v, 1.0);
            } else {
                b.add(v, 0.75);
                b.add(a, 0.125);
                b.add(c, 0.125);
            }
        } else {
            let n = corners.len() as f64;
            b.add(v, (n - 2.0) / n);
            let w = 1.0 / (n * n);
            for &c in corners {
                b.add(adj.to[c as usize], w);
                face_point(&mut b, adj.face_of[c as usize] as usize, w);
            }
        }
        b.end_row();
    }
    for e in 0..adj.num_edges() {
        let c = adj.edge_corner[e];
        let (v0, v1) = (mesh.face_vertices[c as usize], adj.to[c as usize]);
        let t = adj.twin[c as usize];
        if t == NONE {
            b.add(v0, 0.5);
            b.add(v1, 0.5);
        } else {
            b.add(v0, 0.25);
            b.add(v1, 0.25);
            face_point(&mut b, adj.face_of[c as usize] as usize, 0.25);
            face_point(&mut b, adj.face_of[t as usize] as usize, 0.25);
        }
        b.end_row();
    }
    for f in 0..mesh.num_faces() {
        face_point(&mut b, f, 1.0);
        b.end_row();
    }
    b.matrix
}
