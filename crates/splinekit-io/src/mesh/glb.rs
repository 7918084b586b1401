//! The binary glTF 2.0 (`.glb`) writer.

use std::collections::BTreeMap;
use std::io::{BufWriter, Write};

use gltf_json as json;
use json::validation::Checked::Valid;
use json::validation::USize64;
use splinekit::TriMesh;

use super::{MeshIoError, MeshIoErrorKind, to_f32};

/// The format name used in messages.
const FORMAT: &str = "binary glTF";

/// `glTF`, the magic number at the start of a `.glb`.
pub(super) const MAGIC: &[u8; 4] = b"glTF";
/// The chunk type of the JSON chunk.
pub(super) const CHUNK_JSON: &[u8; 4] = b"JSON";
/// The chunk type of the binary buffer chunk.
pub(super) const CHUNK_BIN: &[u8; 4] = b"BIN\0";
/// What `asset.generator` says.
const GENERATOR: &str = "splinekit-io";

/// Writes `mesh` as binary glTF 2.0 (a `.glb` file).
///
/// The file has one scene with one node holding one mesh with one triangle-list primitive:
///
/// - `POSITION`: `f32` VEC3 with `min` and `max` (of the rounded `f32` values);
/// - `NORMAL` (if the mesh has normals): `f32` VEC3, normalised (a zero normal stays zero);
/// - `TEXCOORD_0` (if the mesh has UVs): `f32` VEC2, written as `(u, 1 − v)`, because glTF
///   puts the UV origin at the top left of the image and OBJ and PLY at the bottom left — so
///   a texture looks the same in every format;
/// - indices: `u32` SCALAR, three per triangle, counter-clockwise from the front (glTF's
///   front-face convention).
///
/// The binary chunk holds four tightly packed buffer views in that order (positions, normals,
/// UVs, indices), each starting at a multiple of 4 bytes; the JSON chunk is padded with spaces
/// and the binary chunk with zeros to a multiple of 4 bytes. Coordinates are rounded to the
/// nearest `f32`. The axes are written as they are (glTF is right-handed with +Y up, like the
/// course's surfaces of revolution about +y). A mesh without triangles is written as a scene
/// with one empty node (no buffer), since glTF allows no empty accessors. The same mesh always
/// gives the same bytes.
///
/// Output is buffered internally; `out` need not be buffered.
///
/// # Errors
///
/// [`InvalidMesh`](MeshIoErrorKind::InvalidMesh) if the mesh fails [`TriMesh::validate`],
/// [`Unrepresentable`](MeshIoErrorKind::Unrepresentable) if a coordinate is beyond the `f32`
/// range or the file would be 4 GiB or larger (the `.glb` length field is a `u32`); nothing
/// is written in these cases. An [`Io`](MeshIoErrorKind::Io) error from `out`.
pub fn write_glb<W: Write + ?Sized>(mesh: &TriMesh, out: &mut W) -> Result<(), MeshIoError> {
    super::check(mesh)?;
    super::check_f32_range(mesh, FORMAT, true)?;

    let layout = Layout::new(mesh);
    let mut json_bytes = document(mesh, &layout).to_vec().map_err(|e| MeshIoError::write(std::io::Error::other(e)))?;
    json_bytes.resize(json_bytes.len().next_multiple_of(4), b' ');
    let bin_chunk = if layout.total == 0 { 0 } else { 8 + layout.total };
    let total = 12 + 8 + json_bytes.len() as u64 + bin_chunk;
    let too_large = || {
        MeshIoError::new(MeshIoErrorKind::Unrepresentable {
            format: FORMAT,
            what: format!("a file of {total} bytes (the limit is 4 GiB)"),
        })
    };
    let total = u32::try_from(total).map_err(|_| too_large())?;
    // Both fit, since they are smaller than the total.
    let json_len = u32::try_from(json_bytes.len()).map_err(|_| too_large())?;
    let bin_len = u32::try_from(layout.total).map_err(|_| too_large())?;

    let mut w = BufWriter::with_capacity(super::BUFFER_SIZE, out);
    let result = (|| {
        w.write_all(MAGIC)?;
        w.write_all(&2u32.to_le_bytes())?;
        w.write_all(&total.to_le_bytes())?;
        w.write_all(&json_len.to_le_bytes())?;
        w.write_all(CHUNK_JSON)?;
        w.write_all(&json_bytes)?;
        if bin_len > 0 {
            w.write_all(&bin_len.to_le_bytes())?;
            w.write_all(CHUNK_BIN)?;
            write_bin(mesh, &mut w)?;
        }
        w.flush()
    })();
    result.map_err(MeshIoError::write)
}

/// Byte sizes of the buffer views (each a multiple of 4, so every view starts aligned).
struct Layout {
    positions: u64,
    normals: u64,
    uvs: u64,
    indices: u64,
    total: u64,
}

impl Layout {
    fn new(mesh: &TriMesh) -> Self {
        if mesh.triangles.is_empty() {
            return Self { positions: 0, normals: 0, uvs: 0, indices: 0, total: 0 };
        }
        let n = mesh.positions.len() as u64;
        let positions = 12 * n;
        let normals = if mesh.normals.is_empty() { 0 } else { 12 * n };
        let uvs = if mesh.uvs.is_empty() { 0 } else { 8 * n };
        let indices = 12 * mesh.triangles.len() as u64;
        Self { positions, normals, uvs, indices, total: positions + normals + uvs + indices }
    }
}

/// Builds the glTF JSON document.
fn document(mesh: &TriMesh, layout: &Layout) -> json::Root {
    let mut root = json::Root {
        asset: json::Asset { generator: Some(GENERATOR.to_owned()), ..json::Asset::default() },
        ..json::Root::default()
    };
    let mut node = json::Node::default();
    if layout.total > 0 {
        let buffer = root.push(json::Buffer {
            byte_length: USize64(layout.total),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        let mut offset = 0;
        let mut view = |root: &mut json::Root, length: u64, target: json::buffer::Target| {
            let v = root.push(json::buffer::View {
                buffer,
                byte_length: USize64(length),
                byte_offset: Some(USize64(offset)),
                byte_stride: None,
                name: None,
                target: Some(Valid(target)),
                extensions: None,
                extras: Default::default(),
            });
            offset += length;
            v
        };
        let n = mesh.positions.len();
        let (min, max) = bounds(mesh);
        let position_view = view(&mut root, layout.positions, json::buffer::Target::ArrayBuffer);
        let positions =
            root.push(accessor(position_view, n, Element::Float(json::accessor::Type::Vec3), Some((min, max))));
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), positions);
        if layout.normals > 0 {
            let v = view(&mut root, layout.normals, json::buffer::Target::ArrayBuffer);
            let normals = root.push(accessor(v, n, Element::Float(json::accessor::Type::Vec3), None));
            attributes.insert(Valid(json::mesh::Semantic::Normals), normals);
        }
        if layout.uvs > 0 {
            let v = view(&mut root, layout.uvs, json::buffer::Target::ArrayBuffer);
            let uvs = root.push(accessor(v, n, Element::Float(json::accessor::Type::Vec2), None));
            attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), uvs);
        }
        let v = view(&mut root, layout.indices, json::buffer::Target::ElementArrayBuffer);
        let indices = root.push(accessor(v, 3 * mesh.triangles.len(), Element::Indices, None));
        let primitive = json::mesh::Primitive {
            attributes,
            extensions: None,
            extras: Default::default(),
            indices: Some(indices),
            material: None,
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        };
        let m = root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: None,
            primitives: vec![primitive],
            weights: None,
        });
        node.mesh = Some(m);
    }
    let node = root.push(node);
    let scene = root.push(json::Scene { extensions: None, extras: Default::default(), name: None, nodes: vec![node] });
    root.scene = Some(scene);
    root
}

/// The element kind of an accessor.
enum Element {
    /// `f32` components of the given type.
    Float(json::accessor::Type),
    /// `u32` scalar indices.
    Indices,
}

/// An accessor reading a whole buffer view.
fn accessor(
    view: json::Index<json::buffer::View>,
    count: usize,
    element: Element,
    min_max: Option<([f32; 3], [f32; 3])>,
) -> json::Accessor {
    let (component, type_) = match element {
        Element::Float(t) => (json::accessor::ComponentType::F32, t),
        Element::Indices => (json::accessor::ComponentType::U32, json::accessor::Type::Scalar),
    };
    let (min, max) = match min_max {
        Some((min, max)) => (Some(json::Value::from(min.to_vec())), Some(json::Value::from(max.to_vec()))),
        None => (None, None),
    };
    json::Accessor {
        buffer_view: Some(view),
        byte_offset: None,
        count: USize64::from(count),
        component_type: Valid(json::accessor::GenericComponentType(component)),
        extensions: None,
        extras: Default::default(),
        type_: Valid(type_),
        min,
        max,
        name: None,
        normalized: false,
        sparse: None,
    }
}

/// Per-axis minimum and maximum of the positions rounded to `f32` (the mesh is not empty).
fn bounds(mesh: &TriMesh) -> ([f32; 3], [f32; 3]) {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in &mesh.positions {
        for (k, x) in p.to_array().into_iter().enumerate() {
            let x = to_f32(x);
            min[k] = min[k].min(x);
            max[k] = max[k].max(x);
        }
    }
    (min, max)
}

/// Writes the binary chunk: positions, normals, UVs, indices.
fn write_bin<W: Write>(mesh: &TriMesh, w: &mut W) -> std::io::Result<()> {
    let mut put = |x: f64| w.write_all(&to_f32(x).to_le_bytes());
    for p in &mesh.positions {
        p.to_array().into_iter().try_for_each(&mut put)?;
    }
    for n in &mesh.normals {
        n.normalize_or_zero().to_array().into_iter().try_for_each(&mut put)?;
    }
    for t in &mesh.uvs {
        put(t.x)?;
        put(1.0 - t.y)?;
    }
    for tri in &mesh.triangles {
        for v in tri {
            w.write_all(&v.to_le_bytes())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    fn glb(mesh: &TriMesh) -> Vec<u8> {
        let mut out = Vec::new();
        write_glb(mesh, &mut out).unwrap();
        out
    }

    fn u32_at(bytes: &[u8], at: usize) -> u32 {
        u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn chunks_are_aligned_and_lengths_add_up() {
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 2]],
            ..TriMesh::default()
        };
        let out = glb(&mesh);
        assert_eq!(&out[..4], MAGIC);
        assert_eq!(u32_at(&out, 4), 2);
        assert_eq!(u32_at(&out, 8) as usize, out.len());
        let json_len = u32_at(&out, 12) as usize;
        assert_eq!(json_len % 4, 0);
        assert_eq!(&out[16..20], CHUNK_JSON);
        let bin_at = 20 + json_len;
        assert_eq!(u32_at(&out, bin_at) as usize, 3 * 12 + 3 * 4);
        assert_eq!(&out[bin_at + 4..bin_at + 8], CHUNK_BIN);
        assert_eq!(bin_at + 8 + 48, out.len());
        let text = std::str::from_utf8(&out[20..bin_at]).unwrap();
        assert!(text.contains(r#""min":[0.0,0.0,0.0],"max":[1.0,1.0,0.0]"#), "{text}");
    }

    #[test]
    fn mesh_without_triangles_has_no_buffer() {
        let mesh = TriMesh { positions: vec![DVec3::ONE], ..TriMesh::default() };
        let out = glb(&mesh);
        assert_eq!(u32_at(&out, 8) as usize, out.len());
        assert_eq!(out.len(), 20 + u32_at(&out, 12) as usize);
        let text = std::str::from_utf8(&out[20..]).unwrap();
        assert!(!text.contains("buffers") && !text.contains("meshes") && text.contains(r#""nodes":[{}]"#), "{text}");
    }
}
