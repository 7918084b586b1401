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

use super::attribute::Attribute;
use super::error::SubdivError;
use super::topology::MIN_LEN;

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
    pub(super) fn times(&self, inner: &Self) -> Self {
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
pub(super) struct Builder {
    acc: Accumulator,
    matrix: SubdivisionMatrix,
}

impl Builder {
    pub(super) fn new(num_cols: usize) -> Self {
        Self {
            acc: Accumulator::new(num_cols),
            matrix: SubdivisionMatrix { num_cols, offsets: vec![0], entries: Vec::new() },
        }
    }

    /// Adds `w` to the weight of column `j` in the current row.
    #[inline]
    pub(super) fn add(&mut self, j: u32, w: f64) {
        self.acc.add(j, w);
    }

    /// Ends the current row.
    pub(super) fn end_row(&mut self) {
        self.acc.drain_into(&mut self.matrix.entries);
        self.matrix.offsets.push(self.matrix.entries.len());
    }

    /// The matrix of the rows ended.
    pub(super) fn finish(self) -> SubdivisionMatrix {
        self.matrix
    }
}
