//! The default scene: nodes with their transforms, and the triangles of their primitives
//! combined into one mesh.

use std::collections::{HashMap, HashSet};

use glam::{DMat3, DMat4, DQuat, DVec2, DVec3, DVec4};
use gltf_json as json;
use json::mesh::{Mode, Semantic};
use json::validation::Checked::{Invalid, Valid};
use splinekit::mesh::{FaceVarying, PolyMesh};
use splinekit::subdiv::Creases;

use super::super::load::{self, LoadedMesh, MAX_WARNINGS, ReadWarningKind, Warnings};
use super::super::{MeshIoError, MeshIoErrorKind, SubdivTags};
use super::accessor::{COLORS, Doc, INDICES, NORMALS, POSITIONS, TEXCOORDS};
use super::below;

/// The optional attributes, in the order of [`Builder::attributes`].
pub(super) const ATTRIBUTES: [&str; 3] = ["normals", "texture coordinates", "vertex colours"];

/// The combined mesh being built.
#[derive(Default)]
pub(super) struct Builder {
    pub(super) positions: Vec<DVec3>,
    pub(super) normals: Vec<DVec3>,
    pub(super) uvs: Vec<DVec2>,
    pub(super) colors: Vec<DVec3>,
    pub(super) face_vertices: Vec<u32>,
    /// Per optional attribute: primitives with it, without it, and the first without it.
    pub(super) attributes: [(usize, usize, Option<String>); 3],
}

/// Reads the meshes of a parsed document.
pub(super) struct Reader<'a> {
    pub(super) doc: Doc<'a>,
    pub(super) builder: Builder,
    /// Where the vertices of (instance, POSITION, NORMAL, TEXCOORD_0, COLOR_0) start.
    pub(super) blocks: HashMap<(usize, [Option<usize>; 4]), u32>,
    /// Primitives skipped, as (mesh, primitive); the first [`MAX_WARNINGS`] have a warning.
    pub(super) skipped: HashSet<(usize, usize)>,
    pub(super) warnings: Warnings,
    /// Primitives of triangles (modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) met, once per
    /// node, and how many of them were skipped for having no POSITION.
    pub(super) triangle_primitives: usize,
    pub(super) without_position: usize,
}

/// The transforms of one node instance.
pub(super) struct Placement {
    /// The node's world matrix.
    pub(super) matrix: DMat4,
    /// Whether it is the identity (positions and normals are kept as read).
    pub(super) identity: bool,
    /// The inverse transpose of the upper 3×3 block, up to a positive factor.
    pub(super) normal_matrix: DMat3,
    /// Whether the determinant is negative (triangles are reversed).
    pub(super) mirror: bool,
}

impl Placement {
    pub(super) fn new(matrix: DMat4) -> Self {
        let m = DMat3::from_mat4(matrix);
        let det = m.determinant();
        // The cofactor matrix is det · M⁻ᵀ; it exists even when M is singular.
        let cofactor = DMat3::from_cols(m.y_axis.cross(m.z_axis), m.z_axis.cross(m.x_axis), m.x_axis.cross(m.y_axis));
        let normal_matrix = if det < 0.0 { -cofactor } else { cofactor };
        Self { matrix, identity: matrix == DMat4::IDENTITY, normal_matrix, mirror: det < 0.0 }
    }
}

impl Reader<'_> {
    pub(super) fn error(&self, at: impl Into<String>, message: impl Into<String>) -> MeshIoError {
        self.doc.error(at, message)
    }

    /// Reads the default scene (or every mesh, if there is no scene).
    pub(super) fn read_scene(&mut self) -> Result<(), MeshIoError> {
        let root = self.doc.root;
        let scene = match root.scene {
            Some(s) => Some((s.value(), "scene")),
            None if !root.scenes.is_empty() => Some((0, "scenes[0]")),
            None => None,
        };
        let Some((s, at)) = scene else {
            for m in 0..root.meshes.len() {
                self.add_mesh(m, root.nodes.len() + m, &Placement::new(DMat4::IDENTITY))?;
            }
            return Ok(());
        };
        let Some(scene) = root.scenes.get(s) else {
            return Err(self.error(at, format!("found scene {s}, {}", below(root.scenes.len(), "scenes"))));
        };
        let mut visited = vec![false; root.nodes.len()];
        for (k, &node) in scene.nodes.iter().enumerate() {
            let at = format!("scenes[{s}].nodes[{k}]");
            self.add_node(node.value(), &at, DMat4::IDENTITY, &mut visited)?;
        }
        Ok(())
    }

    /// Adds node `n` and its descendants, depth first, under the transform `parent`.
    pub(super) fn add_node(
        &mut self,
        n: usize,
        at: &str,
        parent: DMat4,
        visited: &mut [bool],
    ) -> Result<(), MeshIoError> {
        let root = self.doc.root;
        // (node, where it is referenced, the parent's world matrix)
        let mut stack = vec![(n, at.to_owned(), parent)];
        while let Some((n, at, parent)) = stack.pop() {
            let Some(node) = root.nodes.get(n) else {
                return Err(self.error(at, format!("found node {n}, {}", below(root.nodes.len(), "nodes"))));
            };
            if std::mem::replace(&mut visited[n], true) {
                return Err(self.error(
                    at,
                    format!("found node {n} a second time, expected every node at most once (nodes form trees)"),
                ));
            }
            let world = parent * local_matrix(node);
            if let Some(m) = node.mesh {
                let m = m.value();
                if m >= root.meshes.len() {
                    let message = format!("found mesh {m}, {}", below(root.meshes.len(), "meshes"));
                    return Err(self.error(format!("nodes[{n}].mesh"), message));
                }
                self.add_mesh(m, n, &Placement::new(world))?;
            }
            for (k, child) in node.children.as_deref().unwrap_or_default().iter().enumerate().rev() {
                stack.push((child.value(), format!("nodes[{n}].children[{k}]"), world));
            }
        }
        Ok(())
    }

    /// A warning that primitive `p` of mesh `m` is skipped (once per primitive).
    pub(super) fn skip(&mut self, m: usize, p: usize, reason: String) {
        if self.skipped.insert((m, p)) && self.skipped.len() <= MAX_WARNINGS {
            let primitive = match &self.doc.root.meshes[m].name {
                Some(name) => format!("meshes[{m}].primitives[{p}] (mesh {name:?})"),
                None => format!("meshes[{m}].primitives[{p}]"),
            };
            self.warnings.push(0, ReadWarningKind::SkippedPrimitive { primitive, reason });
        }
    }

    /// Adds the primitives of mesh `m`, placed by `placement`; `instance` identifies the node.
    pub(super) fn add_mesh(&mut self, m: usize, instance: usize, placement: &Placement) -> Result<(), MeshIoError> {
        let root = self.doc.root;
        let mesh = &root.meshes[m];
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let at = format!("meshes[{m}].primitives[{p}]");
            let mode = match primitive.mode {
                Valid(mode @ (Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan)) => mode,
                Valid(other) => {
                    let name = match other {
                        Mode::Points => "POINTS",
                        Mode::Lines => "LINES",
                        Mode::LineLoop => "LINE_LOOP",
                        _ => "LINE_STRIP",
                    };
                    self.skip(m, p, format!("its mode is {name}, not triangles"));
                    continue;
                }
                Invalid => {
                    self.skip(m, p, String::from("its mode is unknown"));
                    continue;
                }
            };
            self.triangle_primitives += 1;
            let attribute = |s: Semantic| primitive.attributes.get(&Valid(s)).map(|a| a.value());
            let Some(position) = attribute(Semantic::Positions) else {
                self.without_position += 1;
                self.skip(m, p, String::from("it has no POSITION attribute"));
                continue;
            };
            let optional =
                [attribute(Semantic::Normals), attribute(Semantic::TexCoords(0)), attribute(Semantic::Colors(0))];
            let key = (instance, [Some(position), optional[0], optional[1], optional[2]]);
            let (base, count) = match self.blocks.get(&key) {
                Some(&base) => (base, self.count_of(position)),
                None => {
                    let base = self.builder.positions.len() as u32;
                    let count = self.add_vertices(&at, position, optional, placement)?;
                    self.blocks.insert(key, base);
                    (base, count)
                }
            };
            for (k, a) in optional.iter().enumerate() {
                let stats = &mut self.builder.attributes[k];
                if a.is_some() {
                    stats.0 += 1;
                } else {
                    stats.1 += 1;
                    stats.2.get_or_insert_with(|| at.clone());
                }
            }
            self.add_triangles(&at, primitive.indices.map(|i| i.value()), mode, base, count, placement.mirror)?;
        }
        Ok(())
    }

    /// The count of an accessor already read.
    pub(super) fn count_of(&self, accessor: usize) -> usize {
        self.doc.root.accessors.get(accessor).map_or(0, |a| a.count.0 as usize)
    }

    /// Appends the vertices of a primitive; returns their number.
    pub(super) fn add_vertices(
        &mut self,
        at: &str,
        position: usize,
        optional: [Option<usize>; 3],
        placement: &Placement,
    ) -> Result<usize, MeshIoError> {
        let positions = self.doc.accessor(position, &format!("{at}.attributes.POSITION"), &POSITIONS)?;
        let n = positions.count;
        let names = ["NORMAL", "TEXCOORD_0", "COLOR_0"];
        let accepts = [&NORMALS, &TEXCOORDS, &COLORS];
        let mut read = [None, None, None];
        for k in 0..3 {
            if let Some(a) = optional[k] {
                let here = format!("{at}.attributes.{}", names[k]);
                let elements = self.doc.accessor(a, &here, accepts[k])?;
                if elements.count != n {
                    return Err(self.error(
                        format!("{here} (accessors[{a}])"),
                        format!("found {} elements, expected {n} (the count of POSITION)", elements.count),
                    ));
                }
                read[k] = Some(elements);
            }
        }
        if self.builder.positions.len() + n > u32::MAX as usize {
            return Err(load::error_in(
                self.doc.origin,
                MeshIoErrorKind::Unrepresentable {
                    format: "32-bit indices",
                    what: String::from("more than 2³² vertices"),
                },
            ));
        }
        let b = &mut self.builder;
        b.positions.extend((0..n).map(|i| {
            let p = positions.vec3(i);
            if placement.identity { p } else { placement.matrix.transform_point3(p) }
        }));
        match &read[0] {
            Some(e) => b.normals.extend((0..n).map(|i| {
                let v = e.vec3(i);
                if placement.identity { v } else { (placement.normal_matrix * v).normalize_or_zero() }
            })),
            None => b.normals.resize(b.positions.len(), DVec3::ZERO),
        }
        match &read[1] {
            Some(e) => b.uvs.extend((0..n).map(|i| DVec2::new(e.get(i, 0), 1.0 - e.get(i, 1)))),
            None => b.uvs.resize(b.positions.len(), DVec2::ZERO),
        }
        match &read[2] {
            Some(e) => b.colors.extend((0..n).map(|i| e.vec3(i))),
            None => b.colors.resize(b.positions.len(), DVec3::ZERO),
        }
        Ok(n)
    }

    /// Appends the triangles of a primitive whose `count` vertices start at `base`.
    pub(super) fn add_triangles(
        &mut self,
        at: &str,
        indices: Option<usize>,
        mode: Mode,
        base: u32,
        count: usize,
        mirror: bool,
    ) -> Result<(), MeshIoError> {
        let corners: Vec<u32> = match indices {
            Some(a) => {
                let here = format!("{at}.indices");
                let elements = self.doc.accessor(a, &here, &INDICES)?;
                let mut corners = Vec::with_capacity(elements.count);
                for i in 0..elements.count {
                    let v = elements.index(i);
                    if v as usize >= count {
                        return Err(self.error(
                            format!("{here} (accessors[{a}])"),
                            format!("found index {v} at element {i}, expected an index below {count} (the count of POSITION)"),
                        ));
                    }
                    corners.push(v);
                }
                corners
            }
            None => (0..count as u32).collect(),
        };
        let what = if indices.is_some() { "indices" } else { "vertices (no indices)" };
        let mut triangles = Vec::new();
        match mode {
            Mode::TriangleStrip => load::strip_triangles(&corners, |t| triangles.push(t)),
            Mode::TriangleFan => {
                for w in corners.get(1..).unwrap_or_default().windows(2) {
                    let t = [w[0], w[1], corners[0]];
                    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                        triangles.push(t);
                    }
                }
            }
            _ => {
                if !corners.len().is_multiple_of(3) {
                    return Err(self.error(
                        at,
                        format!("found {} {what} with mode TRIANGLES, expected a multiple of 3", corners.len()),
                    ));
                }
                triangles.extend(corners.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
            }
        }
        let b = &mut self.builder;
        if b.face_vertices.len() + 3 * triangles.len() > u32::MAX as usize {
            return Err(load::error_in(
                self.doc.origin,
                MeshIoErrorKind::Unrepresentable {
                    format: "32-bit indices",
                    what: String::from("more than 2³² face corners"),
                },
            ));
        }
        for [a, c, d] in triangles {
            let t = if mirror { [a, d, c] } else { [a, c, d] };
            b.face_vertices.extend(t.map(|v| base + v));
        }
        Ok(())
    }

    /// The mesh and the warnings; an error if there were primitives of triangles but not one
    /// triangle came of them.
    pub(super) fn finish(mut self) -> Result<LoadedMesh, MeshIoError> {
        if self.builder.face_vertices.is_empty() && self.triangle_primitives > 0 {
            let (n, without) = (self.triangle_primitives, self.without_position);
            let no_triangle = "no triangle with three different vertices";
            let they = if n == 1 { "it has" } else { "they have" };
            let reason = match without {
                0 => format!("{they} {no_triangle}"),
                _ if without == n => format!("{they} no POSITION attribute"),
                _ => format!("{without} have no POSITION attribute, the others {no_triangle}"),
            };
            let records = format!("{n} mesh primitive{} of triangles", if n == 1 { "" } else { "s" });
            return Err(load::error_in(self.doc.origin, MeshIoErrorKind::NoFacesRead { records, reason }));
        }
        if self.skipped.len() > MAX_WARNINGS {
            let count = self.skipped.len() - MAX_WARNINGS;
            self.warnings.push(0, ReadWarningKind::More { count });
        }
        let mut b = self.builder;
        let mut keep = [true; 3];
        for (k, (with, without, first)) in b.attributes.iter_mut().enumerate() {
            keep[k] = *with > 0 && *without == 0;
            if *with > 0 && *without > 0 {
                self.warnings.push(
                    0,
                    ReadWarningKind::PrimitiveAttributeDropped {
                        attribute: ATTRIBUTES[k],
                        primitives_with: *with,
                        primitives_without: *without,
                        first_without: first.take().unwrap_or_default(),
                    },
                );
            }
        }
        let faces = b.face_vertices.len() / 3;
        let face_offsets = (0..=faces).map(|f| (3 * f) as u32).collect();
        let normals = keep[0].then(|| FaceVarying { values: b.normals, indices: b.face_vertices.clone() });
        let uvs = keep[1].then(|| FaceVarying { values: b.uvs, indices: b.face_vertices.clone() });
        if !keep[2] {
            b.colors.clear();
        }
        let mesh = PolyMesh {
            positions: b.positions,
            colors: b.colors,
            face_offsets,
            face_vertices: b.face_vertices,
            normals,
            uvs,
        };
        Ok(LoadedMesh {
            mesh,
            warnings: self.warnings.finish(),
            creases: Creases::default(),
            subdiv_tags: SubdivTags::default(),
        })
    }
}

/// A node's local transform: `matrix` (column-major), or translation · rotation · scale.
pub(super) fn local_matrix(node: &json::Node) -> DMat4 {
    if let Some(m) = node.matrix {
        return DMat4::from_cols_array(&m.map(f64::from));
    }
    let translation = node.translation.map_or(DVec3::ZERO, |t| DVec3::from_array(t.map(f64::from)));
    let scale = node.scale.map_or(DVec3::ONE, |s| DVec3::from_array(s.map(f64::from)));
    let rotation = node.rotation.map_or(DQuat::IDENTITY, |q| {
        // glTF requires a unit quaternion; normalise what rounding left.
        DQuat::from_vec4(DVec4::from_array(q.0.map(f64::from)).try_normalize().unwrap_or(DVec4::W))
    });
    DMat4::from_scale_rotation_translation(scale, rotation, translation)
}
