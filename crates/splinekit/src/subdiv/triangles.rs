//! What the triangle schemes made one level at a time (√3, butterfly) share: the walk over
//! the levels and how one level is made from its plan.

use glam::DVec2;

use super::attribute::Attribute;
use super::counts::Counts;
use super::error::{SubdivError, triangles_only};
use super::level_colors::{child_colors, parent_colors};
use super::rings::Rings;
use crate::mesh::{FaceVarying, PolyMesh};

/// Level `levels` of a triangle scheme whose level `depth` is `step(adjacency of level
/// depth − 1, depth)`; level 0 is `mesh` with seamless UVs per vertex and without normals, as
/// the levels carry them. An error naming `scheme` if `mesh` has a face that is not a
/// triangle, and `check`'s error for the counts of `mesh` before any level is made.
pub(super) fn triangle_levels(
    mesh: &PolyMesh,
    levels: usize,
    scheme: &'static str,
    check: impl FnOnce(Counts) -> Result<(), SubdivError>,
    step: impl Fn(&Rings<'_>, usize) -> PolyMesh,
) -> Result<PolyMesh, SubdivError> {
    triangles_only(mesh, scheme)?;
    if levels == 0 {
        let uvs = per_vertex_uvs(mesh).map(|values| FaceVarying { values, indices: mesh.face_vertices.clone() });
        return Ok(PolyMesh { normals: None, uvs, ..mesh.clone() });
    }
    let rings = Rings::new(mesh)?;
    check(Counts::of_rings(&rings))?;
    let mut level = step(&rings, 1);
    for depth in 2..=levels {
        let fine = step(&Rings::new(&level)?, depth);
        level = fine;
    }
    Ok(level)
}

/// The UVs of `mesh` per vertex, if it has UVs and every vertex has one value (zero for a
/// vertex without faces).
pub(super) fn per_vertex_uvs(mesh: &PolyMesh) -> Option<Vec<DVec2>> {
    let uvs = mesh.uvs.as_ref()?;
    if uvs.indices.len() != mesh.face_vertices.len() {
        return None;
    }
    let mut out = vec![None; mesh.num_vertices()];
    for (&v, &i) in mesh.face_vertices.iter().zip(&uvs.indices) {
        let value = *uvs.values.get(i as usize)?;
        match out[v as usize] {
            None => out[v as usize] = Some(value),
            Some(old) if old == value => {}
            Some(_) => return None,
        }
    }
    Some(out.into_iter().map(Option::unwrap_or_default).collect())
}

/// How a level of a triangle scheme is made from its parent: its values from the parent's,
/// and its triangles.
pub(super) trait TriangleLevel {
    /// The child values from the parent's values `p` (one per parent vertex).
    fn refine<T: Attribute>(&self, p: &[T]) -> Vec<T>;
    /// The child triangles, three vertex indices each.
    fn child_triangles(&self) -> Vec<u32>;
}

/// Level `depth` made from `mesh` by `plan`: positions, colours (carried, or by level with
/// `color_by_level`: at depth 1 the parent's vertices get [`LEVEL_COLORS`](super::LEVEL_COLORS)`[0]`), seamless
/// UVs carried, normals dropped.
pub(super) fn triangle_level(
    mesh: &PolyMesh,
    depth: usize,
    color_by_level: bool,
    plan: &impl TriangleLevel,
) -> PolyMesh {
    let positions = plan.refine(&mesh.positions);
    let parent = parent_colors(mesh, color_by_level, depth);
    let colors = child_colors(color_by_level, &parent, positions.len(), depth, |c| plan.refine(c));
    let face_vertices = plan.child_triangles();
    let uvs = per_vertex_uvs(mesh).map(|uv| FaceVarying { values: plan.refine(&uv), indices: face_vertices.clone() });
    let face_offsets = (0..=face_vertices.len() as u32).step_by(3).collect();
    PolyMesh { positions, colors, face_offsets, face_vertices, normals: None, uvs }
}
