//! Loop and Catmull-Clark subdivision with creases: the levels walked one at a time through
//! the crease rules ([`crease`](super::crease)), and the subdivision matrices they give.

use glam::DVec3;

use super::catmull_clark::catmull_clark_subdivide;
use super::counts::{self, Counts};
use super::crease::{CreasedLevel, Creases, LoopLevelRules, Values, creased_level};
use super::error::{SubdivError, triangles_only};
use super::loop_scheme::loop_subdivide;
use super::matrix::SubdivisionMatrix;
use super::nonmanifold::{General, is_nonmanifold};
use super::options::{CatmullClarkOptions, CreasingMethod, LoopOptions, Rules};
use super::rings::Rings;
use super::topology::{Table, Topology};
use crate::mesh::PolyMesh;

/// Walks `levels` levels of Loop subdivision of `mesh` with `creases`, giving each level's
/// matrix to `visit`; returns the finest level's creases.
pub(super) fn loop_levels(
    mesh: &PolyMesh,
    levels: u32,
    options: &LoopOptions,
    creases: &Creases,
    method: CreasingMethod,
    mut visit: impl FnMut(SubdivisionMatrix),
) -> Result<Creases, SubdivError> {
    triangles_only(mesh, "Loop")?;
    let mut triangles: Vec<[u32; 3]> = mesh.face_vertices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    let rules = Rules::new(options);
    let mut topology = match Topology::build(&triangles, mesh.num_vertices()) {
        Err(e) if e.is_nonmanifold() => {
            return General::loop_scheme(options, creases, method).levels(mesh, levels as usize, visit).map(|(c, _)| c);
        }
        topology => topology?,
    };
    counts::loop_levels("Loop", "vertices", Counts::of_triangles(&topology, triangles.len()), 0, levels as usize)?;
    let mut creases = creases.clone();
    for level in 0..levels {
        let this = LoopLevelRules { table: Table { triangles: &triangles, topology: &topology }, rules: &rules };
        let CreasedLevel { matrix, child } = creased_level(&this, &creases, options.boundary, method)?;
        visit(matrix);
        creases = child;
        if level + 1 < levels {
            let (child, child_topology) = topology.refine(&triangles, true);
            triangles = child;
            topology = child_topology.expect("asked for the child's tables");
        }
    }
    Ok(creases)
}

/// Walks `levels` levels of Catmull-Clark subdivision of `mesh` with `creases`, giving each
/// level's matrix to `visit`; returns the finest level's creases and faces (a mesh whose
/// positions are all zero; `None` for no levels).
pub(super) fn catmull_clark_levels(
    mesh: &PolyMesh,
    levels: usize,
    options: &CatmullClarkOptions,
    creases: &Creases,
    method: CreasingMethod,
    mut visit: impl FnMut(SubdivisionMatrix),
) -> Result<(Creases, Option<PolyMesh>), SubdivError> {
    if levels > 0 && is_nonmanifold(mesh) {
        let (child, level) = General::catmark(options, creases, method).levels(mesh, levels, visit)?;
        return Ok((child, Some(level.to_mesh(vec![DVec3::ZERO; level.num_vertices()], Vec::new()))));
    }
    let mut creases = creases.clone();
    let mut current: Option<PolyMesh> = None;
    for depth in 0..levels {
        let m = current.as_ref().unwrap_or(mesh);
        let mut rings = Rings::new(m)?;
        rings.triangles = options.triangles;
        if depth == 0 {
            counts::catmull_clark_levels(Counts::of_rings(&rings), 0, levels)?;
        }
        let CreasedLevel { matrix, child } = creased_level(&rings, &creases, options.boundary, method)?;
        creases = child;
        // the child's connectivity only: its positions are never read
        let (face_offsets, face_vertices) = rings.child_faces();
        let positions = vec![DVec3::ZERO; matrix.num_rows()];
        current = Some(PolyMesh { positions, face_offsets, face_vertices, ..PolyMesh::default() });
        visit(matrix);
    }
    Ok((creases, current))
}

/// `levels` levels of Loop subdivision of `mesh` (as [`loop_subdivide`]) with sharp and
/// semi-sharp `creases` carried by `method` (see the [crease rules](super::crease)): the subdivided mesh
/// and its creases. Positions and colours follow the crease rules; face-varying normals and
/// UVs are carried by the smooth rules, as without creases.
///
/// # Errors
/// As [`loop_subdivide`], and [`SubdivError::Crease`] for a crease on an edge or vertex the
/// mesh does not have, or with a negative sharpness.
pub fn loop_subdivide_creased(
    mesh: &PolyMesh,
    levels: u32,
    options: &LoopOptions,
    creases: &Creases,
    method: CreasingMethod,
) -> Result<(PolyMesh, Creases), SubdivError> {
    if is_nonmanifold(mesh) {
        let general = General::loop_scheme(options, creases, method);
        return general.subdivide(mesh, levels as usize, options.color_by_level).map(|(m, c, _)| (m, c));
    }
    let mut values = Values::new(mesh, options.color_by_level);
    let child = loop_levels(mesh, levels, options, creases, method, |m| values.step(&m))?;
    // the faces and the face-varying channels (and colours by level) of the plain subdivision
    let mut fine = loop_subdivide(mesh, levels, options)?;
    fine.positions = values.positions;
    if !options.color_by_level && !values.colors.is_empty() {
        fine.colors = values.colors;
    }
    Ok((fine, child))
}

/// `levels` levels of Catmull-Clark subdivision of `mesh` (as [`catmull_clark_subdivide`])
/// with sharp and semi-sharp `creases` carried by `method` (see the [crease rules](super::crease)): the
/// subdivided mesh and its creases.
///
/// # Errors
/// As [`catmull_clark_subdivide`], and [`SubdivError::Crease`] for a crease on an edge or
/// vertex the mesh does not have, or with a negative sharpness.
pub fn catmull_clark_subdivide_creased(
    mesh: &PolyMesh,
    levels: usize,
    options: &CatmullClarkOptions,
    creases: &Creases,
    method: CreasingMethod,
) -> Result<(PolyMesh, Creases), SubdivError> {
    if levels > 0 && is_nonmanifold(mesh) {
        let general = General::catmark(options, creases, method);
        return general.subdivide(mesh, levels, options.color_by_level).map(|(m, c, _)| (m, c));
    }
    let mut values = Values::new(mesh, options.color_by_level);
    let (child, faces) = catmull_clark_levels(mesh, levels, options, creases, method, |m| values.step(&m))?;
    let Some(mut fine) = faces else {
        return Ok((catmull_clark_subdivide(mesh, 0, options)?, child));
    };
    (fine.positions, fine.colors) = (values.positions, values.colors);
    Ok((fine, child))
}

impl SubdivisionMatrix {
    /// The weights of `levels` levels of Loop subdivision of the triangle mesh `mesh` with
    /// `options` (its weights and boundary rule; colour by level does not matter): row `i`
    /// gives vertex `i` of [`loop_subdivide`]`(mesh, levels, options)`.
    ///
    /// # Errors
    /// As [`loop_subdivide`]: a face that is not a triangle, or
    /// non-manifold or inconsistently oriented topology, naming it.
    pub fn loop_scheme(mesh: &PolyMesh, levels: u32, options: &LoopOptions) -> Result<Self, SubdivError> {
        Self::loop_creased(mesh, levels, options, &Creases::default(), CreasingMethod::default())
    }

    /// [`Self::loop_scheme`] with sharp and semi-sharp `creases` carried by `method`: row `i`
    /// gives vertex `i` of [`loop_subdivide_creased`].
    ///
    /// # Errors
    /// As [`Self::loop_scheme`], and a crease on an edge or vertex the mesh does not have or
    /// with a negative sharpness.
    pub fn loop_creased(
        mesh: &PolyMesh,
        levels: u32,
        options: &LoopOptions,
        creases: &Creases,
        method: CreasingMethod,
    ) -> Result<Self, SubdivError> {
        let mut matrix = Self::identity(mesh.num_vertices());
        loop_levels(mesh, levels, options, creases, method, |level| matrix = level.times(&matrix))?;
        Ok(matrix)
    }

    /// The weights of `levels` levels of Catmull-Clark subdivision of the polygon mesh
    /// `mesh` with `options` (the boundary rule; colour by level does not matter): row `i`
    /// gives vertex `i` of [`catmull_clark_subdivide`]`(mesh,
    /// levels, options)`.
    ///
    /// # Errors
    /// As [`catmull_clark_subdivide`]: non-manifold or
    /// inconsistently oriented topology, naming it.
    pub fn catmull_clark(mesh: &PolyMesh, levels: usize, options: &CatmullClarkOptions) -> Result<Self, SubdivError> {
        Self::catmull_clark_creased(mesh, levels, options, &Creases::default(), CreasingMethod::default())
    }

    /// [`Self::catmull_clark`] with sharp and semi-sharp `creases` carried by `method`: row `i`
    /// gives vertex `i` of
    /// [`catmull_clark_subdivide_creased`].
    ///
    /// # Errors
    /// As [`Self::catmull_clark`], and a crease on an edge or vertex the mesh does not have or
    /// with a negative sharpness.
    pub fn catmull_clark_creased(
        mesh: &PolyMesh,
        levels: usize,
        options: &CatmullClarkOptions,
        creases: &Creases,
        method: CreasingMethod,
    ) -> Result<Self, SubdivError> {
        let mut matrix = Self::identity(mesh.num_vertices());
        catmull_clark_levels(mesh, levels, options, creases, method, |level| matrix = level.times(&matrix))?;
        Ok(matrix)
    }
}
