//! Subdivision surfaces: Loop subdivision of triangle meshes and Catmull-Clark
//! subdivision of polygon meshes, with OpenSubdiv's rules; √3 subdivision of
//! triangle meshes ([`sqrt3_subdivide`]) and Doo-Sabin subdivision of polygon meshes
//! ([`doo_sabin_subdivide`]), with CGAL's; the interpolating modified butterfly scheme
//! ([`butterfly_subdivide`]), with OpenMesh's; and bilinear subdivision of polygon meshes
//! ([`bilinear_subdivide`]), with OpenSubdiv's.
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

pub mod bilinear;
pub mod butterfly;
mod catmull_clark;
mod counts;
pub mod crease;
pub mod doo_sabin;
mod general;
mod grandchild;
mod great;
pub mod holes;
mod limit;
mod loop_scheme;
mod matrix;
mod quads;
mod regular;
pub mod sqrt3;
pub mod topology;

pub use bilinear::{BilinearOptions, bilinear_subdivide};
pub use butterfly::{ButterflyOptions, butterfly_step, butterfly_subdivide};
pub use catmull_clark::{CatmullClarkOptions, TriangleSubdivision, catmull_clark_step, catmull_clark_subdivide};
pub use crease::{
    Creases, CreasingMethod, EdgeCrease, VertexCrease, catmull_clark_subdivide_creased, loop_subdivide_creased,
};
pub use doo_sabin::{DooSabinOptions, doo_sabin_subdivide};
pub use general::is_nonmanifold;
pub use holes::{HoleSplit, boundary_holes, remove_holes};
pub use limit::{
    LimitMesh, catmull_clark_limit_creased, catmull_clark_limit_normals, catmull_clark_limit_positions,
    catmull_clark_subdivide_limit, loop_limit_creased, loop_limit_normals, loop_limit_positions, loop_subdivide_limit,
};
pub use loop_scheme::{
    Attribute, BoundaryRule, LEVEL_COLORS, LoopLevel, LoopOptions, LoopPyramid, LoopWeights, SubdivError,
    loop_subdivide,
};
pub use matrix::SubdivisionMatrix;
pub use sqrt3::{Sqrt3Options, sqrt3_subdivide};
pub use topology::{Topology, TopologyError};
