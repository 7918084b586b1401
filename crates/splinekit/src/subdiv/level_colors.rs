//! The colours of subdivision levels ([`LEVEL_COLORS`]) and how the schemes give them to the
//! vertices of each level.

use std::borrow::Cow;

use glam::DVec3;

use crate::mesh::PolyMesh;

/// The colours of [`LoopOptions::color_by_level`](super::LoopOptions::color_by_level): level `k` uses entry `k % 8` (base mesh
/// grey, then blue, green, yellow, magenta, cyan, pink, violet). None is near the renderers'
/// orange-red of back faces, so a level never reads as a surface seen from behind.
pub const LEVEL_COLORS: [DVec3; 8] = [
    DVec3::new(0.6, 0.6, 0.6),
    DVec3::new(0.25, 0.45, 0.95),
    DVec3::new(0.25, 0.8, 0.35),
    DVec3::new(0.95, 0.85, 0.15),
    DVec3::new(0.85, 0.3, 0.85),
    DVec3::new(0.15, 0.8, 0.85),
    DVec3::new(0.95, 0.6, 0.75),
    DVec3::new(0.6, 0.4, 0.95),
];

/// The colours of `mesh` as the parent of level `depth` (≥ 1) of a subdivision, for
/// [`child_colors`]: with `color_by_level`, [`LEVEL_COLORS`]`[0]` at depth 1 (the base level's
/// own colour) and the mesh's colours below; else the mesh's colours when every vertex has
/// one, none otherwise.
pub(super) fn parent_colors(mesh: &PolyMesh, color_by_level: bool, depth: usize) -> Cow<'_, [DVec3]> {
    if color_by_level && depth <= 1 {
        Cow::Owned(vec![LEVEL_COLORS[0]; mesh.positions.len()])
    } else if color_by_level || mesh.colors.len() == mesh.positions.len() {
        Cow::Borrowed(&mesh.colors)
    } else {
        Cow::Borrowed(&[])
    }
}

/// The colours of a level of `n` vertices made at `depth` from its parent's `colors`: with
/// `color_by_level`, the parent's followed by the level's colour ([`LEVEL_COLORS`]); none
/// when the parent has none; else `subdivide(colors)`, the parent's carried with the
/// positions' weights.
pub(super) fn child_colors(
    color_by_level: bool,
    colors: &[DVec3],
    n: usize,
    depth: usize,
    subdivide: impl FnOnce(&[DVec3]) -> Vec<DVec3>,
) -> Vec<DVec3> {
    if color_by_level {
        let mut c = Vec::with_capacity(n);
        c.extend_from_slice(colors);
        c.resize(n, LEVEL_COLORS[depth % LEVEL_COLORS.len()]);
        c
    } else if colors.is_empty() {
        Vec::new()
    } else {
        subdivide(colors)
    }
}
