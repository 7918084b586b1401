//! Bilinear subdivision of polygon meshes, as OpenSubdiv's `SCHEME_BILINEAR`.
//!
//! One level splits every `n`-gon into `n` quads, as Catmull-Clark does, but moves nothing:
//! the child's vertices are, in this order, the parent's vertices where they are, one **edge
//! point** per edge at its midpoint (edges numbered in the order of their first corner), and
//! one **face point** per face at the average of its corners. Child face `k` of parent face
//! `f` (corners `c₀ … cₙ₋₁`) is `(cₖ, edge point cₖcₖ₊₁, face point f, edge point cₖ₋₁cₖ)`,
//! oriented as its parent; the children of face 0 come first. The surface stays the polygons
//! it was (a quad's children are its bilinear patch at `u, v ∈ {0, ½, 1}`), so there are no
//! boundary, crease or limit rules.
//!
//! Colours and the face-varying normals and UVs are carried with the same weights (normals
//! renormalized), each face's corner values on its own: a UV seam stays a seam. Edges are
//! pairs of vertices, so non-manifold edges and vertices need nothing special (an edge of
//! three faces gets one midpoint, as in OpenSubdiv); a face that names a vertex twice is
//! refused.

use std::collections::HashMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::attribute::Attribute;
use super::counts::{self, Counts};
use super::error::{SubdivError, indices_in_range, polygons_only, repeated_vertex};
use super::level_colors::{child_colors, parent_colors};
use super::topology::{MIN_LEN, TopologyError};
use crate::mesh::{FaceVarying, NONE, PolyMesh};

/// Options of bilinear subdivision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct BilinearOptions {
    /// Colour the vertices by the level they were born at ([`LEVEL_COLORS`](super::LEVEL_COLORS)).
    pub color_by_level: bool,
}

/// Subdivides `mesh` `levels` times with the bilinear scheme (see the [module docs](self)).
///
/// # Errors
///
/// [`SubdivError::TooFewCorners`] for a face of fewer than 3 corners; [`SubdivError::Topology`]
/// for a face that repeats a vertex or a vertex index out of range;
/// [`SubdivError::TooLarge`] if the result would not fit `u32` indices (checked before any
/// level is made).
pub fn bilinear_subdivide(mesh: &PolyMesh, levels: usize, options: &BilinearOptions) -> Result<PolyMesh, SubdivError> {
    polygons_only(mesh)?;
    indices_in_range(mesh)?;
    if let Some((face, vertex)) = repeated_vertex(mesh) {
        return Err(TopologyError::RepeatedVertex { face: face as u32, vertex }.into());
    }
    let mut level = mesh.clone();
    let mut colors = parent_colors(mesh, options.color_by_level, 1).into_owned();
    for depth in 1..=levels {
        let edges = Edges::new(&level);
        if depth == 1 {
            let base = Counts {
                vertices: level.num_vertices() as u64,
                edges: edges.ends.len() as u64,
                faces: level.num_faces() as u64,
                corners: level.face_vertices.len() as u64,
            };
            counts::bilinear_levels(base, 0, levels)?;
        }
        let positions = edges.refine(&level, &level.positions);
        colors = child_colors(options.color_by_level, &colors, positions.len(), depth, |c| edges.refine(&level, c));
        let normals = level.normals.as_ref().map(|n| {
            let mut fine = refine_face_varying(&level, &edges, n);
            fine.values.iter_mut().for_each(|n: &mut DVec3| *n = n.normalize_or_zero());
            fine
        });
        let uvs = level.uvs.as_ref().map(|uv| refine_face_varying::<DVec2>(&level, &edges, uv));
        let (face_offsets, face_vertices) = edges.child_faces(&level);
        level = PolyMesh { positions, colors: Vec::new(), face_offsets, face_vertices, normals, uvs };
    }
    level.colors = colors;
    Ok(level)
}

/// The edges of one level: each corner's edge (to the next corner), numbered by first corner.
struct Edges {
    /// Per corner: its edge.
    of: Vec<u32>,
    /// Per edge: its two ends.
    ends: Vec<[u32; 2]>,
}

impl Edges {
    fn new(mesh: &PolyMesh) -> Self {
        let nc = mesh.face_vertices.len();
        let mut sides: Vec<(u32, u32, u32)> = (0..mesh.num_faces())
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .flat_map_iter(|f| {
                let (s, e) = (mesh.face_offsets[f], mesh.face_offsets[f + 1]);
                (s..e).map(move |c| {
                    let next = if c + 1 == e { s } else { c + 1 };
                    let (a, b) = (mesh.face_vertices[c as usize], mesh.face_vertices[next as usize]);
                    (a.min(b), a.max(b), c)
                })
            })
            .collect();
        sides.par_sort_unstable();
        // the first corner of each run of equal ends names the edge; edges are numbered in the
        // order of those first corners
        let mut first = vec![0u32; nc];
        let mut owners = Vec::new();
        for run in sides.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let owner = run[0].2;
            owners.push(owner);
            for &(_, _, c) in run {
                first[c as usize] = owner;
            }
        }
        owners.par_sort_unstable();
        let mut number = vec![NONE; nc];
        let mut ends = Vec::with_capacity(owners.len());
        for (e, &c) in owners.iter().enumerate() {
            number[c as usize] = e as u32;
            let (a, b) = (mesh.face_vertices[c as usize], mesh.face_vertices[next_corner(mesh, c) as usize]);
            ends.push([a, b]);
        }
        let of = first.par_iter().map(|&c| number[c as usize]).collect();
        Self { of, ends }
    }

    /// The child values: the parent's, edge midpoints, face centroids.
    fn refine<T: Attribute>(&self, mesh: &PolyMesh, p: &[T]) -> Vec<T> {
        let mut out = Vec::with_capacity(p.len() + self.ends.len() + mesh.num_faces());
        out.extend_from_slice(p);
        out.par_extend(self.ends.par_iter().map(|&[a, b]| (p[a as usize] + p[b as usize]) * 0.5));
        out.par_extend(
            (0..mesh.num_faces()).into_par_iter().map(|f| centroid(mesh.face(f).iter().map(|&v| p[v as usize]))),
        );
        out
    }

    /// The child faces (all quads): face offsets and corners.
    fn child_faces(&self, mesh: &PolyMesh) -> (Vec<u32>, Vec<u32>) {
        let (nv, ne) = (mesh.num_vertices() as u32, self.ends.len() as u32);
        let corners = mesh.face_vertices.len();
        let offsets = (0..=corners as u32).map(|k| 4 * k).collect();
        let quads: Vec<[u32; 4]> = (0..mesh.num_faces())
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .flat_map_iter(|f| {
                let (s, e) = (mesh.face_offsets[f], mesh.face_offsets[f + 1]);
                (s..e).map(move |c| {
                    let prev = if c == s { e - 1 } else { c - 1 };
                    let centre = nv + ne + f as u32;
                    [mesh.face_vertices[c as usize], nv + self.of[c as usize], centre, nv + self.of[prev as usize]]
                })
            })
            .collect();
        (offsets, bytemuck::cast_vec(quads))
    }
}

/// The corner after `c` in its face.
fn next_corner(mesh: &PolyMesh, c: u32) -> u32 {
    let f = mesh.face_offsets.partition_point(|&o| o <= c) - 1;
    if c + 1 == mesh.face_offsets[f + 1] { mesh.face_offsets[f] } else { c + 1 }
}

/// The average of `values`.
fn centroid<T: Attribute>(values: impl ExactSizeIterator<Item = T>) -> T {
    let n = values.len() as f64;
    values.fold(T::default(), |s, x| s + x) * (1.0 / n)
}

/// The child of a face-varying channel: the parent's values, then one midpoint per distinct
/// (edge, pair of values) and one centroid per face, indexed like [`Edges::child_faces`].
fn refine_face_varying<T: Attribute>(mesh: &PolyMesh, edges: &Edges, fv: &FaceVarying<T>) -> FaceVarying<T> {
    let mut values = fv.values.clone();
    let mut midpoints: HashMap<(u32, u32, u32), u32> = HashMap::new();
    let mut corner_mid = vec![0u32; mesh.face_vertices.len()];
    for f in 0..mesh.num_faces() {
        let (s, e) = (mesh.face_offsets[f], mesh.face_offsets[f + 1]);
        for c in s..e {
            let next = if c + 1 == e { s } else { c + 1 };
            let (i, j) = (fv.indices[c as usize], fv.indices[next as usize]);
            let key = (edges.of[c as usize], i.min(j), i.max(j));
            corner_mid[c as usize] = *midpoints.entry(key).or_insert_with(|| {
                values.push((fv.values[i as usize] + fv.values[j as usize]) * 0.5);
                (values.len() - 1) as u32
            });
        }
    }
    let first_centre = values.len() as u32;
    values.extend((0..mesh.num_faces()).map(|f| {
        let corners = mesh.face_offsets[f] as usize..mesh.face_offsets[f + 1] as usize;
        centroid(fv.indices[corners].iter().map(|&i| fv.values[i as usize]))
    }));
    let mut indices = Vec::with_capacity(4 * mesh.face_vertices.len());
    for f in 0..mesh.num_faces() {
        let (s, e) = (mesh.face_offsets[f], mesh.face_offsets[f + 1]);
        for c in s..e {
            let prev = if c == s { e - 1 } else { c - 1 };
            indices.extend([
                fv.indices[c as usize],
                corner_mid[c as usize],
                first_centre + f as u32,
                corner_mid[prev as usize],
            ]);
        }
    }
    FaceVarying { values, indices }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygons(positions: Vec<DVec3>, faces: &[Vec<u32>]) -> PolyMesh {
        let mut face_offsets = vec![0];
        for f in faces {
            face_offsets.push(face_offsets.last().unwrap() + f.len() as u32);
        }
        let face_vertices = faces.concat();
        PolyMesh { positions, face_offsets, face_vertices, ..PolyMesh::default() }
    }

    /// A unit square and a triangle beside it, sharing the edge x = 1.
    fn square_and_triangle() -> PolyMesh {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(2.0, 0.5, 0.0),
        ];
        polygons(positions, &[vec![0, 1, 2, 3], vec![1, 4, 2]])
    }

    #[test]
    fn a_level_splits_every_face_at_midpoints_and_centroids() {
        let mesh = square_and_triangle();
        let fine = bilinear_subdivide(&mesh, 1, &BilinearOptions::default()).unwrap();
        // V + E + F vertices, one quad per corner
        assert_eq!((fine.num_vertices(), fine.num_faces()), (5 + 6 + 2, 7));
        assert_eq!(&fine.positions[..5], &mesh.positions[..]);
        // the shared edge 1–2 has one midpoint
        let mid = DVec3::new(1.0, 0.5, 0.0);
        assert_eq!(fine.positions.iter().filter(|&&p| p.distance(mid) < 1e-15).count(), 1);
        assert!(fine.positions.contains(&DVec3::new(0.5, 0.5, 0.0)));
        let centre = (mesh.positions[1] + mesh.positions[4] + mesh.positions[2]) / 3.0;
        assert!(fine.positions.iter().any(|p| p.distance(centre) < 1e-15));
        // the first child of face 0: its corner 0, edge 0–1's midpoint, its centre, edge 3–0's
        let f0: Vec<DVec3> = fine.face(0).iter().map(|&v| fine.positions[v as usize]).collect();
        assert_eq!(f0, [DVec3::ZERO, DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.5, 0.5, 0.0), DVec3::new(0.0, 0.5, 0.0)]);
    }

    #[test]
    fn uvs_follow_the_same_weights_and_keep_seams() {
        let mut mesh = square_and_triangle();
        // the triangle's UVs are apart from the square's (a seam along 1–2)
        let values = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(5.0, 5.0),
            DVec2::new(6.0, 5.0),
            DVec2::new(5.0, 6.0),
        ];
        mesh.uvs = Some(FaceVarying { values, indices: vec![0, 1, 2, 3, 4, 5, 6] });
        let fine = bilinear_subdivide(&mesh, 2, &BilinearOptions::default()).unwrap();
        let uvs = fine.uvs.as_ref().unwrap();
        // on the square, uv = xy at every corner of level 2
        for f in 0..16 {
            for c in fine.face_offsets[f] as usize..fine.face_offsets[f + 1] as usize {
                let p = fine.positions[fine.face_vertices[c] as usize];
                assert!(uvs.values[uvs.indices[c] as usize].distance(p.truncate()) < 1e-15, "corner {c}");
            }
        }
        // the triangle's corners keep the triangle's own values
        let triangle_uvs: Vec<DVec2> =
            (16 * 4..fine.face_vertices.len()).map(|c| uvs.values[uvs.indices[c] as usize]).collect();
        assert!(triangle_uvs.iter().all(|uv| uv.x >= 5.0 - 1e-15 && uv.y >= 5.0 - 1e-15));
    }

    #[test]
    fn a_face_that_repeats_a_vertex_is_refused() {
        let mesh = polygons(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[vec![0, 1, 0, 2]]);
        let err = bilinear_subdivide(&mesh, 1, &BilinearOptions::default()).unwrap_err();
        assert!(matches!(err, SubdivError::Topology(TopologyError::RepeatedVertex { face: 0, vertex: 0 })), "{err}");
    }
}
