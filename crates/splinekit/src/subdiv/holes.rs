//! OpenSubdiv's boundary interpolation "none" (`VTX_BOUNDARY_NONE`): the subdivision is the same
//! as with boundary edges as creases, but the faces at the boundary are holes, left out of the
//! surface.
//!
//! As OpenSubdiv's `TopologyRefinerFactory` tags them, a base face is a hole when one of its
//! vertices is on the boundary (or non-manifold) and has a boundary edge that is not an
//! infinitely sharp crease; a hole's children are holes. Every level's faces follow their
//! parent's order (a parent's children are consecutive), so a face of level `L` descends from
//! the base face found by dividing its index: by `4ᴸ` for Loop's triangles, by `4ᴸ⁻¹` into the
//! base face corners for Catmull-Clark's quads (one child per corner at the first level).

use std::collections::HashMap;

use super::crease::{Creases, INFINITELY_SHARP};
use crate::mesh::{FaceVarying, PolyMesh};

/// How a scheme splits faces, for finding a face's base face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HoleSplit {
    /// Loop: every triangle into four.
    Triangles,
    /// Catmull-Clark: every n-gon into n quads, then every quad into four.
    Quads,
}

/// Which faces of `mesh` OpenSubdiv's `VTX_BOUNDARY_NONE` makes holes, given its `creases`
/// (a boundary edge with an infinitely sharp crease does not make holes).
#[must_use]
pub fn boundary_holes(mesh: &PolyMesh, creases: &Creases) -> Vec<bool> {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let sides = |f: usize| {
        let face = mesh.face(f);
        (0..face.len()).map(move |i| key(face[i], face[(i + 1) % face.len()]))
    };
    let mut faces_of_edge: HashMap<(u32, u32), u32> = HashMap::new();
    for f in 0..mesh.num_faces() {
        for e in sides(f) {
            *faces_of_edge.entry(e).or_default() += 1;
        }
    }
    let mut sharp: HashMap<(u32, u32), f32> = HashMap::new();
    for c in &creases.edges {
        sharp.insert(key(c.a, c.b), c.sharpness);
    }
    // the vertices with a boundary edge that is not infinitely sharp
    let mut open = vec![false; mesh.num_vertices()];
    for (&(a, b), &n) in &faces_of_edge {
        if n == 1 && sharp.get(&(a, b)).is_none_or(|&s| s < INFINITELY_SHARP) {
            open[a as usize] = true;
            open[b as usize] = true;
        }
    }
    mesh.faces().map(|face| face.iter().any(|&v| open[v as usize])).collect()
}

/// Leaves out of `fine` — `levels` levels of `split` below `base` — the faces that descend from
/// a hole of `base` (`holes`, one flag per base face); vertices stay, so vertex numbers and
/// creases keep their meaning.
pub fn remove_holes(fine: &mut PolyMesh, base: &PolyMesh, levels: usize, split: HoleSplit, holes: &[bool]) {
    let ancestor = |f: usize| -> usize {
        match (split, levels) {
            (_, 0) => f,
            (HoleSplit::Triangles, l) => f >> (2 * l),
            (HoleSplit::Quads, l) => {
                let corner = (f >> (2 * (l - 1))) as u32;
                base.face_offsets.partition_point(|&o| o <= corner) - 1
            }
        }
    };
    let keep: Vec<bool> = (0..fine.num_faces()).map(|f| !holes[ancestor(f)]).collect();
    let corners = |f: usize| fine.face_offsets[f] as usize..fine.face_offsets[f + 1] as usize;
    let kept_corners: Vec<usize> = (0..fine.num_faces()).filter(|&f| keep[f]).flat_map(corners).collect();
    let mut face_offsets = vec![0];
    for f in (0..fine.num_faces()).filter(|&f| keep[f]) {
        face_offsets
            .push(face_offsets.last().copied().unwrap_or(0) + (fine.face_offsets[f + 1] - fine.face_offsets[f]));
    }
    fn channel<T: Copy>(fv: &mut Option<FaceVarying<T>>, kept: &[usize]) {
        if let Some(fv) = fv {
            fv.indices = kept.iter().map(|&c| fv.indices[c]).collect();
        }
    }
    channel(&mut fine.normals, &kept_corners);
    channel(&mut fine.uvs, &kept_corners);
    fine.face_vertices = kept_corners.iter().map(|&c| fine.face_vertices[c]).collect();
    fine.face_offsets = face_offsets;
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::subdiv::EdgeCrease;

    /// An open 2 × 2 grid of quads: every face has a boundary vertex.
    fn grid() -> PolyMesh {
        let positions = (0..9).map(|k| DVec3::new(f64::from(k % 3), f64::from(k / 3), 0.0)).collect();
        let face_vertices = vec![0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7];
        PolyMesh { positions, face_offsets: vec![0, 4, 8, 12, 16], face_vertices, ..PolyMesh::default() }
    }

    #[test]
    fn boundary_faces_are_holes_unless_their_boundary_is_infinitely_sharp() {
        let mesh = grid();
        assert_eq!(boundary_holes(&mesh, &Creases::default()), [true; 4]);
        // every boundary edge infinitely sharp: no holes; one of them only semi-sharp: the faces
        // at its two ends
        let ring = [0, 1, 2, 5, 8, 7, 6, 3, 0];
        let edges = ring.windows(2).map(|w| EdgeCrease { a: w[0], b: w[1], sharpness: 10.0 }).collect();
        let mut creases = Creases { edges, ..Creases::default() };
        assert_eq!(boundary_holes(&mesh, &creases), [false; 4]);
        creases.edges[0].sharpness = 3.0; // 0–1: faces 0 and 1 (at vertex 1)
        assert_eq!(boundary_holes(&mesh, &creases), [true, true, false, false]);
    }

    #[test]
    fn children_follow_their_base_face() {
        let mesh = grid();
        let options = crate::subdiv::CatmullClarkOptions::default();
        let holes = [true, false, false, true];
        for levels in 0..3 {
            let mut fine = crate::subdiv::catmull_clark_subdivide(&mesh, levels, &options).unwrap();
            let all = fine.num_faces();
            remove_holes(&mut fine, &mesh, levels, HoleSplit::Quads, &holes);
            assert_eq!(fine.num_faces(), all / 2, "level {levels}");
            // what is left lies in the two kept base faces: x ≥ 1 ≥ y or x ≤ 1 ≤ y
            for face in fine.faces() {
                let c = face.iter().map(|&v| fine.positions[v as usize]).sum::<DVec3>() / face.len() as f64;
                assert!((c.x - 1.0) * (c.y - 1.0) <= 0.0, "level {levels}: a face centred at {c}");
            }
        }
    }
}
