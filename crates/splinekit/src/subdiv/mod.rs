//! Subdivision surfaces: Loop subdivision of triangle meshes and Catmull-Clark
//! subdivision of polygon meshes, with OpenSubdiv's rules; √3 subdivision of
//! triangle meshes ([`sqrt3_subdivide`]) and Doo-Sabin subdivision of polygon meshes
//! ([`doo_sabin_subdivide`]), with CGAL's; the interpolating modified butterfly scheme
//! ([`butterfly_subdivide`]), with OpenMesh's; and bilinear subdivision of polygon meshes
//! ([`bilinear_subdivide`]), with OpenSubdiv's.
//!
//! [`subdivide`] runs any of them, a [`Scheme`] with [`SubdivisionOptions`] (the capability
//! methods of [`Scheme`] say what each takes and offers); the functions of each scheme are the
//! lower level it calls.
//!
//! ```
//! use glam::DVec3;
//! use splinekit::PolyMesh;
//! use splinekit::subdiv::{LoopOptions, loop_subdivide};
//! // A tetrahedron: V = 4, E = 6, F = 4.
//! let mesh = PolyMesh::from_triangles(
//!     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
//!     &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
//! );
//! let fine = loop_subdivide(&mesh, 1, &LoopOptions::default())?;
//! assert_eq!((fine.num_vertices(), fine.num_faces()), (4 + 6, 4 * 4));
//! # Ok::<(), splinekit::subdiv::SubdivError>(())
//! ```

mod attribute;
pub mod bilinear;
pub mod butterfly;
pub mod catmull_clark;
mod counts;
pub mod crease;
mod creased;
pub mod doo_sabin;
mod error;
pub mod holes;
mod level_colors;
pub mod limit;
pub mod loop_scheme;
pub mod matrix;
pub mod nonmanifold;
mod options;
mod rings;
mod scheme;
pub mod sqrt3;
mod subdivide;
pub mod topology;
mod triangles;

pub use attribute::Attribute;
pub use bilinear::{BilinearOptions, bilinear_subdivide};
pub use butterfly::{ButterflyOptions, butterfly_step, butterfly_subdivide};
pub use catmull_clark::{catmull_clark_step, catmull_clark_subdivide};
pub use crease::{Creases, EdgeCrease, VertexCrease};
pub use creased::{catmull_clark_subdivide_creased, loop_subdivide_creased};
pub use doo_sabin::{DooSabinOptions, doo_sabin_subdivide};
pub use error::SubdivError;
pub use holes::{HoleSplit, boundary_holes, remove_holes};
pub use level_colors::LEVEL_COLORS;
pub use limit::{
    LimitMesh, catmull_clark_limit_creased, catmull_clark_limit_normals, catmull_clark_limit_positions,
    catmull_clark_subdivide_limit, loop_limit_creased, loop_limit_normals, loop_limit_positions, loop_subdivide_limit,
};
pub use loop_scheme::{LoopLevel, LoopPyramid, loop_subdivide};
pub use matrix::SubdivisionMatrix;
pub use nonmanifold::is_nonmanifold;
pub use options::{
    BoundaryRule, CatmullClarkOptions, CreasingMethod, LoopOptions, LoopWeights, SubdivisionOptions,
    TriangleSubdivision,
};
pub use scheme::{CarriedAttributes, Scheme};
pub use sqrt3::{Sqrt3Options, sqrt3_subdivide};
pub use subdivide::{Subdivided, subdivide, subdivide_with_progress};
pub use topology::{Topology, TopologyError};
