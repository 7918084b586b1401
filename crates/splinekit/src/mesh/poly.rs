//! [`PolyMesh`]: the indexed polygon mesh that mesh files are read into and that
//! subdivision works on.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::TriMesh;

/// A face-varying attribute: a pool of values and, for every face corner, the index of its
/// value. A vertex on a seam (of UVs, or of normals at a crease) has several values, one per
/// side; a per-vertex attribute is the special case `indices == face_vertices`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FaceVarying<T> {
    /// The distinct values.
    pub values: Vec<T>,
    /// One index into `values` per face corner, parallel to [`PolyMesh::face_vertices`].
    pub indices: Vec<u32>,
}

/// An indexed polygon mesh (triangles and n-gons).
///
/// Faces are stored flat: face `f` has the corners `face_offsets[f] .. face_offsets[f + 1]`
/// of `face_vertices`, counter-clockwise seen from the front. *Corner* `c` is an index into
/// `face_vertices`; it also names the half-edge from corner `c`'s vertex to the next corner's
/// vertex of the same face (see [`Adjacency`](super::Adjacency)).
///
/// Attributes: `colors` is empty or holds one RGB value per vertex; `normals` and `uvs` are
/// optional face-varying attributes ([`FaceVarying`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PolyMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Per-vertex RGB colours in `[0, 1]` (empty, or one per vertex).
    pub colors: Vec<DVec3>,
    /// Face `f` is `face_vertices[face_offsets[f] .. face_offsets[f + 1]]`; starts with 0.
    pub face_offsets: Vec<u32>,
    /// Vertex index of every corner, face after face.
    pub face_vertices: Vec<u32>,
    /// Normals per corner, if any.
    pub normals: Option<FaceVarying<DVec3>>,
    /// Texture coordinates per corner, if any.
    pub uvs: Option<FaceVarying<DVec2>>,
}

impl Default for PolyMesh {
    fn default() -> Self {
        Self {
            positions: Vec::new(),
            colors: Vec::new(),
            face_offsets: vec![0],
            face_vertices: Vec::new(),
            normals: None,
            uvs: None,
        }
    }
}

impl PolyMesh {
    /// A mesh of triangles only, without attributes.
    #[must_use]
    pub fn from_triangles(positions: Vec<DVec3>, triangles: &[[u32; 3]]) -> Self {
        let face_offsets = (0..=triangles.len()).map(|f| (3 * f) as u32).collect();
        let face_vertices = triangles.iter().flatten().copied().collect();
        Self { positions, face_offsets, face_vertices, ..Self::default() }
    }

    /// Number of vertices.
    #[must_use]
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    #[must_use]
    pub fn num_faces(&self) -> usize {
        self.face_offsets.len() - 1
    }

    /// The vertex indices of face `f`.
    #[must_use]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_vertices[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// Iterator over the faces' vertex lists.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.face_offsets.windows(2).map(|w| &self.face_vertices[w[0] as usize..w[1] as usize])
    }

    /// Whether every face is a triangle.
    #[must_use]
    pub fn is_triangle_mesh(&self) -> bool {
        self.face_offsets.windows(2).all(|w| w[1] - w[0] == 3)
    }

    /// The triangles, if every face is one.
    #[must_use]
    pub fn triangles(&self) -> Option<Vec<[u32; 3]>> {
        self.is_triangle_mesh().then(|| self.face_vertices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
    }

    /// A triangle mesh for the writers: polygons are fanned from their first corner, colours
    /// kept, normals and UVs dropped unless they are per-vertex (one value per vertex).
    #[must_use]
    pub fn to_tri_mesh(&self) -> TriMesh {
        let mut triangles = Vec::with_capacity(self.face_vertices.len());
        for f in self.faces() {
            for k in 1..f.len().saturating_sub(1) {
                triangles.push([f[0], f[k], f[k + 1]]);
            }
        }
        let n = self.positions.len();
        let per_vertex = |indices: &[u32], len: usize| indices == self.face_vertices.as_slice() && len == n;
        TriMesh {
            positions: self.positions.clone(),
            normals: self
                .normals
                .as_ref()
                .filter(|a| per_vertex(&a.indices, a.values.len()))
                .map(|n| n.values.clone())
                .unwrap_or_default(),
            uvs: self
                .uvs
                .as_ref()
                .filter(|a| per_vertex(&a.indices, a.values.len()))
                .map(|u| u.values.clone())
                .unwrap_or_default(),
            colors: self.colors.clone(),
            triangles,
        }
    }

    /// A triangle mesh that keeps face-varying normals and UVs: polygons are fanned from
    /// their first corner as in [`Self::to_tri_mesh`], and every distinct (vertex, normal,
    /// UV) of a corner becomes a vertex of its own, numbered in order of first use, so a
    /// vertex on a seam appears once per side (at the same position). Colours (one per vertex)
    /// go with their vertex; vertices of no face are left out. A mesh with neither normals nor
    /// UVs gives [`Self::to_tri_mesh`]'s mesh. An attribute whose indices do not match the
    /// corners is dropped, and an index out of range gives a zero value.
    #[must_use]
    pub fn to_tri_mesh_with_seams(&self) -> TriMesh {
        let corners = self.face_vertices.len();
        let normals = self.normals.as_ref().filter(|a| a.indices.len() == corners);
        let uvs = self.uvs.as_ref().filter(|a| a.indices.len() == corners);
        if normals.is_none() && uvs.is_none() {
            return self.to_tri_mesh();
        }
        let colours = self.colors.len() == self.positions.len();
        let mut ids: HashMap<[u32; 3], u32> = HashMap::with_capacity(self.positions.len());
        let mut mesh = TriMesh::default();
        let mut corner_ids = Vec::with_capacity(corners);
        for (c, &v) in self.face_vertices.iter().enumerate() {
            let key = [v, normals.map_or(0, |a| a.indices[c]), uvs.map_or(0, |a| a.indices[c])];
            let id = *ids.entry(key).or_insert_with(|| {
                mesh.positions.push(self.positions.get(v as usize).copied().unwrap_or(DVec3::NAN));
                if colours {
                    mesh.colors.push(self.colors.get(v as usize).copied().unwrap_or(DVec3::ZERO));
                }
                if let Some(a) = normals {
                    mesh.normals.push(a.values.get(key[1] as usize).copied().unwrap_or(DVec3::ZERO));
                }
                if let Some(a) = uvs {
                    mesh.uvs.push(a.values.get(key[2] as usize).copied().unwrap_or(DVec2::ZERO));
                }
                (mesh.positions.len() - 1) as u32
            });
            corner_ids.push(id);
        }
        for w in self.face_offsets.windows(2) {
            let f = &corner_ids[w[0] as usize..w[1] as usize];
            for k in 1..f.len().saturating_sub(1) {
                mesh.triangles.push([f[0], f[k], f[k + 1]]);
            }
        }
        mesh
    }
}

impl From<&TriMesh> for PolyMesh {
    fn from(m: &TriMesh) -> Self {
        let mut p = Self::from_triangles(m.positions.clone(), &m.triangles);
        p.colors.clone_from(&m.colors);
        if !m.normals.is_empty() {
            p.normals = Some(FaceVarying { values: m.normals.clone(), indices: p.face_vertices.clone() });
        }
        if !m.uvs.is_empty() {
            p.uvs = Some(FaceVarying { values: m.uvs.clone(), indices: p.face_vertices.clone() });
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seams_split_into_vertices_of_their_own() {
        // Two triangles sharing the edge 1–2, whose UVs differ on the two sides at vertex 2,
        // and a quad fanned into two triangles; vertex 5 belongs to no face.
        let mut mesh = PolyMesh::from_triangles(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE, DVec3::Z, DVec3::NEG_ONE],
            &[[0, 1, 2], [2, 1, 3]],
        );
        mesh.face_vertices.extend([0, 2, 3, 4]);
        mesh.face_offsets.push(10);
        mesh.colors = (0..6).map(|i| DVec3::splat(f64::from(i) / 10.0)).collect();
        let uv = |i: u32| DVec2::new(f64::from(i), 0.5);
        // Corner UV indices: the second triangle sees vertex 2 with UV 9.
        mesh.uvs = Some(FaceVarying { values: (0..10).map(uv).collect(), indices: vec![0, 1, 2, 9, 1, 3, 0, 2, 3, 4] });
        let plain = mesh.to_tri_mesh();
        assert!(plain.uvs.is_empty(), "to_tri_mesh drops face-varying UVs");
        let split = mesh.to_tri_mesh_with_seams();
        split.validate().unwrap();
        assert_eq!(split.num_vertices(), 6, "vertex 2 twice, vertex 5 left out");
        assert_eq!(split.triangles, vec![[0, 1, 2], [3, 1, 4], [0, 2, 4], [0, 4, 5]]);
        assert_eq!(split.positions[3], split.positions[2]);
        assert_eq!((split.uvs[2], split.uvs[3]), (uv(2), uv(9)));
        assert_eq!(split.colors[3], DVec3::splat(0.2));
        assert!(split.normals.is_empty());
        // No face-varying attributes: the same as to_tri_mesh.
        mesh.uvs = None;
        assert_eq!(mesh.to_tri_mesh_with_seams(), mesh.to_tri_mesh());
    }
}
