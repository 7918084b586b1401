//! Integration tests of the mesh writers, atomic writes and the spline-annotated OBJ header.
//!
//! Every writer's output is read back by an independent reader from crates.io: `tobj` (OBJ),
//! `gltf` (binary glTF), `ply-rs-bw` (PLY) and `stl_io` (STL).

use std::f64::consts::TAU;
use std::fs;
use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use splinekit::TriMesh;
use splinekit_io::mesh::{
    MeshFormat, MeshIoErrorKind, SplineHeader, save, save_cancellable, save_revolution_obj, write_glb, write_mesh,
    write_obj, write_ply, write_revolution_obj, write_stl,
};

// ---------------------------------------------------------------------------------------
// Fixtures and helpers

/// A regular tetrahedron, outward and counter-clockwise, with no normals or UVs.
fn tetrahedron() -> TriMesh {
    let mesh = TriMesh {
        positions: vec![
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ],
        triangles: vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
        ..TriMesh::default()
    };
    assert!(mesh.signed_volume() > 0.0);
    mesh
}

/// A wavy `nu × nv` quad grid over [0, 1]² with normals and UVs, with coordinates that are
/// not exact in binary (so that f64 → text → f64 is really exercised).
fn grid(nu: u32, nv: u32) -> TriMesh {
    let mut mesh = TriMesh::default();
    for j in 0..=nv {
        for i in 0..=nu {
            let (u, v) = (f64::from(i) / f64::from(nu), f64::from(j) / f64::from(nv));
            let h = 0.1 * (TAU * u).sin() * (TAU * v).cos();
            mesh.positions.push(DVec3::new(u * 0.3, v / 0.7, h + 1e-17 * u));
            let dh = DVec2::new(
                0.1 * TAU * (TAU * u).cos() * (TAU * v).cos(),
                -0.1 * TAU * (TAU * u).sin() * (TAU * v).sin(),
            );
            mesh.normals.push(DVec3::new(-dh.x, -dh.y, 1.0).normalize());
            mesh.uvs.push(DVec2::new(u, v));
        }
    }
    let row = nu + 1;
    for j in 0..nv {
        for i in 0..nu {
            let a = j * row + i;
            mesh.triangles.push([a, a + 1, a + row + 1]);
            mesh.triangles.push([a, a + row + 1, a + row]);
        }
    }
    mesh.validate().unwrap();
    mesh
}

/// The grid with normals only, and with UVs only.
fn grid_variants() -> [TriMesh; 2] {
    let mut normals_only = grid(3, 2);
    normals_only.uvs.clear();
    let mut uvs_only = grid(3, 2);
    uvs_only.normals.clear();
    [normals_only, uvs_only]
}

fn to_bytes(mesh: &TriMesh, format: MeshFormat) -> Vec<u8> {
    let mut out = Vec::new();
    write_mesh(mesh, &mut out, format).unwrap();
    out
}

fn f32_of(p: DVec3) -> [f32; 3] {
    p.as_vec3().to_array()
}

/// A fresh scratch directory, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("splinekit-mesh-io-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }

    fn entries(&self) -> Vec<String> {
        let mut names: Vec<String> =
            fs::read_dir(&self.0).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        names.sort();
        names
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

// ---------------------------------------------------------------------------------------
// OBJ, read back with tobj

/// Reads OBJ bytes with tobj without reindexing; returns the one model's mesh.
fn tobj_read(bytes: &[u8]) -> tobj::Mesh {
    let options = tobj::LoadOptions { single_index: false, triangulate: false, ..tobj::LoadOptions::default() };
    let (mut models, _) =
        tobj::load_obj_buf(&mut Cursor::new(bytes), &options, |_| Err(tobj::LoadError::OpenFileFailed)).unwrap();
    assert_eq!(models.len(), 1);
    models.remove(0).mesh
}

/// A cube of quads with flat normals and a UV seam (side 5 has UVs of its own).
fn seamed_cube() -> splinekit::PolyMesh {
    use splinekit::{FaceVarying, PolyMesh};
    let positions: Vec<DVec3> =
        (0..8).map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2))).collect();
    let quads: [[u32; 4]; 6] = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let axes = [DVec3::NEG_Z, DVec3::Z, DVec3::NEG_Y, DVec3::Y, DVec3::NEG_X, DVec3::X];
    let uv = |k: u32| DVec2::new(f64::from(k & 1), f64::from(k >> 1));
    PolyMesh {
        positions,
        face_offsets: (0..=6).map(|f| 4 * f).collect(),
        face_vertices: quads.iter().flatten().copied().collect(),
        normals: Some(FaceVarying { values: axes.to_vec(), indices: (0..24).map(|c| c / 4).collect() }),
        uvs: Some(FaceVarying {
            values: (0..8).map(|k| uv(k % 4) * if k < 4 { 1.0 } else { 0.5 }).collect(),
            indices: (0..24).map(|c| if c >= 20 { 4 + c % 4 } else { c % 4 }).collect(),
        }),
        ..PolyMesh::default()
    }
}

/// Each format's capabilities say what its file keeps: written by `save_poly` and read back,
/// polygons stay polygons where it holds them, an attribute held per corner keeps the 8
/// vertices, one held per vertex splits the seams (or, for PLY's normals, is left out), and
/// one not held is gone.
#[test]
fn format_capabilities_are_what_the_files_keep() {
    use splinekit_io::mesh::{Carries, load_mesh, save_poly};
    let cube = seamed_cube();
    let dir = Scratch::new("capabilities");
    for format in MeshFormat::ALL {
        let caps = format.capabilities();
        assert!(caps.reads && caps.writes, "{format}");
        let path = dir.0.join(format!("cube.{format}"));
        let saved = save_poly(&cube, &path, format, false).unwrap();
        let back = load_mesh(&path).unwrap().mesh;
        assert_eq!(back.num_vertices(), saved.vertices, "{format}");
        assert_eq!(back.num_faces(), if caps.polygons { 6 } else { 12 }, "{format}");
        let split = caps.uvs == Carries::PerVertex || caps.normals == Carries::PerVertex && format != MeshFormat::Ply;
        assert_eq!(back.num_vertices() > 8, split, "{format}: {} vertices", back.num_vertices());
        assert_eq!(back.uvs.is_some(), caps.uvs != Carries::No, "{format}");
        assert_eq!(
            back.normals.is_some(),
            caps.normals == Carries::PerCorner || split && caps.normals != Carries::No,
            "{format}"
        );
        assert_eq!(saved.normals_left_out, format == MeshFormat::Ply, "{format}");
    }
}

/// Face-varying normals and UVs are written with their own indices: tobj reads back the same
/// positions, the same corners' indices into each pool, and the same values; the mesh keeps
/// its vertices (a closed quad cube with flat normals and a UV seam stays 8 vertices).
#[test]
fn obj_keeps_face_varying_attributes_with_their_own_indices() {
    use splinekit::FaceVarying;
    let mut mesh = seamed_cube();
    let mut bytes = Vec::new();
    splinekit_io::mesh::write_obj_poly(&mesh, &mut bytes).unwrap();
    let read = tobj_read(&bytes);
    // tobj numbers the pools in its own order: compare every corner's values
    assert_eq!(read.positions.len(), 3 * 8, "one v per vertex");
    assert_eq!((read.normals.len(), read.texcoords.len()), (3 * 6, 2 * 8), "one vn per side, one vt per value");
    let (normals, uvs) = (mesh.normals.as_ref().unwrap(), mesh.uvs.as_ref().unwrap());
    let at = |pool: &[f64], i: u32, n: usize| -> Vec<f64> { pool[n * i as usize..n * (i as usize + 1)].to_vec() };
    for c in 0..24 {
        assert_eq!(at(&read.positions, read.indices[c], 3), mesh.positions[mesh.face_vertices[c] as usize].to_array());
        assert_eq!(
            at(&read.normals, read.normal_indices[c], 3),
            normals.values[normals.indices[c] as usize].to_array()
        );
        assert_eq!(at(&read.texcoords, read.texcoord_indices[c], 2), uvs.values[uvs.indices[c] as usize].to_array());
    }
    // and our own reader gives the mesh back exactly
    let back = splinekit_io::mesh::read_obj(Cursor::new(&bytes), "cube.obj").unwrap().mesh;
    assert_eq!(back, mesh);
    // PLY keeps the 8 vertices too: the UVs per corner (MeshLab's texcoord lists), the
    // normals, which differ at every vertex, left out (and said so)
    let mut ply = Vec::new();
    assert!(splinekit_io::mesh::write_ply_poly(&mesh, &mut ply).unwrap(), "normals left out");
    let end = ply.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let header = std::str::from_utf8(&ply[..end]).unwrap();
    assert!(
        header.ends_with(
            "element face 6\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
        ),
        "{header}"
    );
    assert!(!header.contains("nx") && !header.contains("property float u"), "{header}");
    // 8 vertices of 3 floats, then 6 faces of (4 indices, 8 floats) with their counts
    assert_eq!(ply.len() - end, 8 * 12 + 6 * (1 + 16 + 1 + 32));
    let back = splinekit_io::mesh::read_ply(Cursor::new(&ply), "cube.ply").unwrap().mesh;
    assert_eq!(
        (&back.positions, &back.face_offsets, &back.face_vertices),
        (&mesh.positions, &mesh.face_offsets, &mesh.face_vertices)
    );
    let (a, b) = (back.uvs.as_ref().unwrap(), mesh.uvs.as_ref().unwrap());
    for c in 0..24 {
        assert_eq!(a.values[a.indices[c] as usize], b.values[b.indices[c] as usize], "corner {c}");
    }
    // a vertex's corners with equal UVs share one value: 4 shared corners and the seam's own
    // 4, each at every vertex that uses it
    let distinct: std::collections::HashSet<(u32, u32)> =
        back.face_vertices.iter().zip(&a.indices).map(|(&v, &i)| (v, i)).collect();
    assert_eq!(a.values.len(), distinct.len());
    // with one normal and one UV per vertex, they are vertex properties, as write_ply's
    let mut smooth = mesh.clone();
    smooth.normals = Some(FaceVarying { values: smooth.positions.clone(), indices: smooth.face_vertices.clone() });
    smooth.uvs = None;
    let mut ply = Vec::new();
    assert!(!splinekit_io::mesh::write_ply_poly(&smooth, &mut ply).unwrap());
    let back = splinekit_io::mesh::read_ply(Cursor::new(&ply), "smooth.ply").unwrap().mesh;
    assert_eq!(back.normals, smooth.normals);
    // an index past the values is refused before anything is written
    mesh.uvs.as_mut().unwrap().indices[7] = 8;
    let mut out = Vec::new();
    let err = splinekit_io::mesh::write_obj_poly(&mesh, &mut out).unwrap_err();
    assert!(out.is_empty());
    assert_eq!(err.to_string(), "invalid UVs: corner 7 names value 8 of 8");
}

fn check_obj(mesh: &TriMesh) {
    let bytes = to_bytes(mesh, MeshFormat::Obj);
    let read = tobj_read(&bytes);
    // tobj renumbers vertices in order of first use, so compare corner by corner. It is built
    // with `use_f64`: the shortest round-trip text gives back the exact f64s.
    assert_eq!(read.positions.len(), 3 * mesh.positions.len());
    assert_eq!(read.normals.len(), 3 * mesh.normals.len());
    assert_eq!(read.texcoords.len(), 2 * mesh.uvs.len());
    assert_eq!(read.indices.len(), 3 * mesh.triangles.len());
    assert!(read.face_arities.iter().all(|&n| n == 3));
    let corners = mesh.triangles.iter().flatten().map(|&v| v as usize);
    for (k, v) in corners.enumerate() {
        let i = read.indices[k] as usize;
        assert_eq!(DVec3::from_slice(&read.positions[3 * i..]), mesh.positions[v], "corner {k}");
        if !mesh.normals.is_empty() {
            let i = read.normal_indices[k] as usize;
            assert_eq!(DVec3::from_slice(&read.normals[3 * i..]), mesh.normals[v], "normal of corner {k}");
        }
        if !mesh.uvs.is_empty() {
            let i = read.texcoord_indices[k] as usize;
            assert_eq!(DVec2::from_slice(&read.texcoords[2 * i..]), mesh.uvs[v], "uv of corner {k}");
        }
    }
    assert_eq!(read.normal_indices.is_empty(), mesh.normals.is_empty());
    assert_eq!(read.texcoord_indices.is_empty(), mesh.uvs.is_empty());
}

/// The positions tobj read, in the mesh's vertex order (every vertex must be used).
fn tobj_positions_in_mesh_order(read: &tobj::Mesh, mesh: &TriMesh) -> Vec<DVec3> {
    let mut out = vec![DVec3::NAN; mesh.positions.len()];
    for (k, &v) in mesh.triangles.iter().flatten().enumerate() {
        let i = read.indices[k] as usize;
        out[v as usize] = DVec3::from_slice(&read.positions[3 * i..]);
    }
    out
}

#[test]
fn obj_reads_back_exactly_with_tobj() {
    check_obj(&tetrahedron());
    check_obj(&grid(4, 3));
    for mesh in grid_variants() {
        check_obj(&mesh);
    }
}

// ---------------------------------------------------------------------------------------
// Binary glTF, read back with gltf

fn check_glb(mesh: &TriMesh) {
    let bytes = to_bytes(mesh, MeshFormat::Glb);
    // Container layout: 4-byte alignment of both chunks, and lengths that add up.
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(u32_at(8), bytes.len());
    let json_len = u32_at(12);
    assert_eq!(json_len % 4, 0);
    let bin_at = 20 + json_len;
    assert_eq!(bin_at % 4, 0);
    assert_eq!(&bytes[bin_at + 4..bin_at + 8], b"BIN\0");
    assert_eq!(bin_at + 8 + u32_at(bin_at), bytes.len());
    assert_eq!(u32_at(bin_at) % 4, 0);

    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.as_deref().unwrap();
    assert_eq!(gltf.document.scenes().count(), 1);
    assert_eq!(gltf.document.nodes().count(), 1);
    assert_eq!(gltf.document.meshes().count(), 1);
    for view in gltf.document.views() {
        assert_eq!(view.offset() % 4, 0, "buffer view {} is not 4-byte aligned", view.index());
    }
    let gmesh = gltf.document.meshes().next().unwrap();
    let prim = gmesh.primitives().next().unwrap();
    assert_eq!(prim.mode(), gltf::mesh::Mode::Triangles);
    let reader = prim.reader(|b| match b.source() {
        gltf::buffer::Source::Bin => Some(blob),
        gltf::buffer::Source::Uri(_) => None,
    });

    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    let expected: Vec<[f32; 3]> = mesh.positions.iter().map(|&p| f32_of(p)).collect();
    assert_eq!(positions, expected);
    let bounds = prim.bounding_box();
    for k in 0..3 {
        assert_eq!(bounds.min[k], expected.iter().map(|p| p[k]).fold(f32::INFINITY, f32::min));
        assert_eq!(bounds.max[k], expected.iter().map(|p| p[k]).fold(f32::NEG_INFINITY, f32::max));
    }

    match reader.read_normals() {
        Some(normals) => {
            let normals: Vec<[f32; 3]> = normals.collect();
            let expected: Vec<[f32; 3]> = mesh.normals.iter().map(|&n| f32_of(n.normalize())).collect();
            assert_eq!(normals, expected);
        }
        None => assert!(mesh.normals.is_empty()),
    }
    match reader.read_tex_coords(0) {
        Some(uvs) => {
            // glTF's v runs down the image: written as 1 − v.
            let uvs: Vec<[f32; 2]> = uvs.into_f32().collect();
            let expected: Vec<[f32; 2]> = mesh.uvs.iter().map(|t| [t.x as f32, (1.0 - t.y) as f32]).collect();
            assert_eq!(uvs, expected);
        }
        None => assert!(mesh.uvs.is_empty()),
    }
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    assert_eq!(indices, mesh.triangles.iter().flatten().copied().collect::<Vec<_>>());
    let accessor = prim.indices().unwrap();
    assert_eq!(accessor.data_type(), gltf::accessor::DataType::U32);
}

#[test]
fn glb_reads_back_with_gltf() {
    check_glb(&tetrahedron());
    check_glb(&grid(4, 3));
    for mesh in grid_variants() {
        check_glb(&mesh);
    }
}

#[test]
fn glb_of_a_mesh_without_triangles_is_valid() {
    let mesh = TriMesh { positions: vec![DVec3::ONE], ..TriMesh::default() };
    let bytes = to_bytes(&mesh, MeshFormat::Glb);
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    assert_eq!(gltf.document.meshes().count(), 0);
    assert_eq!(gltf.document.nodes().count(), 1);
    assert!(gltf.blob.is_none());
}

// ---------------------------------------------------------------------------------------
// PLY, read back with ply-rs-bw

fn check_ply(mesh: &TriMesh) {
    use ply_rs_bw::ply::{DefaultElement, Encoding, Property};

    let bytes = to_bytes(mesh, MeshFormat::Ply);
    let parser = ply_rs_bw::parser::Parser::<DefaultElement>::new();
    let ply = parser.read_ply(&mut Cursor::new(&bytes)).unwrap();
    assert!(matches!(ply.header.encoding, Encoding::BinaryLittleEndian));
    let float = |e: &DefaultElement, key: &str| match e.get(key) {
        Some(Property::Float(x)) => *x,
        other => panic!("{key}: {other:?}"),
    };

    let vertices = &ply.payload["vertex"];
    assert_eq!(vertices.len(), mesh.positions.len());
    for (i, e) in vertices.iter().enumerate() {
        assert_eq!([float(e, "x"), float(e, "y"), float(e, "z")], f32_of(mesh.positions[i]), "vertex {i}");
        if mesh.normals.is_empty() {
            assert!(!e.contains_key("nx"));
        } else {
            assert_eq!([float(e, "nx"), float(e, "ny"), float(e, "nz")], f32_of(mesh.normals[i]), "normal {i}");
        }
        if mesh.uvs.is_empty() {
            assert!(!e.contains_key("u"));
        } else {
            assert_eq!([float(e, "u"), float(e, "v")], mesh.uvs[i].as_vec2().to_array(), "uv {i}");
        }
    }

    let faces = &ply.payload["face"];
    assert_eq!(faces.len(), mesh.triangles.len());
    for (f, e) in faces.iter().enumerate() {
        let Some(Property::ListInt(list)) = e.get("vertex_indices") else { panic!("face {f}: {e:?}") };
        let expected: Vec<i32> = mesh.triangles[f].iter().map(|&v| v as i32).collect();
        assert_eq!(list, &expected, "face {f}");
    }
}

#[test]
fn ply_reads_back_with_ply_rs() {
    check_ply(&tetrahedron());
    check_ply(&grid(4, 3));
    for mesh in grid_variants() {
        check_ply(&mesh);
    }
}

// ---------------------------------------------------------------------------------------
// STL, read back with stl_io

fn check_stl(mesh: &TriMesh) {
    let bytes = to_bytes(mesh, MeshFormat::Stl);
    assert_eq!(bytes.len(), 84 + 50 * mesh.triangles.len());
    let mut cursor = Cursor::new(&bytes);
    let triangles: Vec<stl_io::Triangle> =
        stl_io::create_stl_reader(&mut cursor).unwrap().collect::<Result<_, _>>().unwrap();
    assert_eq!(triangles.len(), mesh.triangles.len());
    for (i, t) in triangles.iter().enumerate() {
        let corners = mesh.corners(i).map(f32_of);
        assert_eq!(t.vertices.map(|v| v.0), corners, "triangle {i}");
        // The stored normal is the unit face normal, pointing to the counter-clockwise side.
        let normal = DVec3::from_array(t.normal.0.map(f64::from));
        let expected = mesh.face_normal(i).normalize();
        assert!((normal - expected).length() < 1e-6, "triangle {i}: {normal} vs {expected}");
    }
    // The indexed reader merges equal corners back into the mesh's vertices (all distinct here).
    let indexed = stl_io::read_stl(&mut Cursor::new(&bytes)).unwrap();
    assert_eq!(indexed.vertices.len(), mesh.positions.len());
    assert_eq!(indexed.faces.len(), mesh.triangles.len());
}

#[test]
fn stl_reads_back_with_stl_io() {
    check_stl(&tetrahedron());
    check_stl(&grid(4, 3));
}

// ---------------------------------------------------------------------------------------
// Determinism, validation, formats

#[test]
fn writing_twice_gives_identical_bytes() {
    let scratch = Scratch::new("determinism");
    for mesh in [tetrahedron(), grid(5, 4)] {
        for format in MeshFormat::ALL {
            let a = to_bytes(&mesh, format);
            let b = to_bytes(&mesh.clone(), format);
            assert_eq!(a, b, "{format}");
            // The path-level writer gives the same bytes as the stream writer.
            let path = scratch.0.join(format!("mesh.{format}"));
            save(&mesh, &path, format).unwrap();
            assert_eq!(fs::read(&path).unwrap(), a, "{format}");
            save(&mesh, &path, format).unwrap();
            assert_eq!(fs::read(&path).unwrap(), a, "{format}");
        }
    }
    assert_eq!(scratch.entries(), ["mesh.glb", "mesh.obj", "mesh.ply", "mesh.stl"]);
}

#[test]
fn stream_writers_match_write_mesh() {
    let mesh = grid(2, 2);
    let mut out = Vec::new();
    write_obj(&mesh, &mut out).unwrap();
    assert_eq!(out, to_bytes(&mesh, MeshFormat::Obj));
    out.clear();
    write_glb(&mesh, &mut out).unwrap();
    assert_eq!(out, to_bytes(&mesh, MeshFormat::Glb));
    out.clear();
    write_ply(&mesh, &mut out).unwrap();
    assert_eq!(out, to_bytes(&mesh, MeshFormat::Ply));
    out.clear();
    write_stl(&mesh, &mut out).unwrap();
    assert_eq!(out, to_bytes(&mesh, MeshFormat::Stl));
    // `dyn Write` works too.
    let dynamic: &mut dyn Write = &mut Vec::new();
    write_obj(&mesh, dynamic).unwrap();
}

#[test]
fn invalid_meshes_are_refused_by_every_writer_and_leave_no_file() {
    let scratch = Scratch::new("invalid");
    let mut bad = tetrahedron();
    bad.triangles.push([0, 1, 4]);
    let mut nan = tetrahedron();
    nan.positions[2].y = f64::NAN;
    for format in MeshFormat::ALL {
        for mesh in [&bad, &nan] {
            let mut out = Vec::new();
            let e = write_mesh(mesh, &mut out, format).unwrap_err();
            assert!(matches!(e.kind(), MeshIoErrorKind::InvalidMesh(_)), "{format}: {e}");
            assert!(out.is_empty(), "{format}");
            let path = scratch.0.join(format!("bad.{format}"));
            let e = save(mesh, &path, format).unwrap_err();
            assert!(e.to_string().starts_with(&format!("{}: invalid mesh: ", path.display())), "{e}");
        }
    }
    assert!(scratch.entries().is_empty(), "{:?}", scratch.entries());
}

#[test]
fn f32_formats_refuse_coordinates_beyond_f32() {
    let mut mesh = tetrahedron();
    mesh.positions[3].z = -1e39;
    for format in [MeshFormat::Glb, MeshFormat::Ply, MeshFormat::Stl] {
        let e = write_mesh(&mesh, &mut Vec::new(), format).unwrap_err();
        assert!(matches!(e.kind(), MeshIoErrorKind::Unrepresentable { .. }), "{format}: {e}");
        assert!(e.to_string().starts_with("z coordinate of vertex 3 (-1e39) does not fit in binary"), "{e}");
    }
    // OBJ is text in f64: fine.
    check_obj(&mesh);
}

#[test]
fn format_from_path_and_extension() {
    assert_eq!(MeshFormat::from_path("a/b/vase.GLB"), Some(MeshFormat::Glb));
    assert_eq!(MeshFormat::from_path("x.obj"), Some(MeshFormat::Obj));
    assert_eq!(MeshFormat::from_path("x.tar.ply"), Some(MeshFormat::Ply));
    assert_eq!(MeshFormat::from_path("x.stl.bak"), None);
    assert_eq!(MeshFormat::from_path("stl"), None);
    assert_eq!(MeshFormat::from_extension(".Stl"), Some(MeshFormat::Stl));
    for format in MeshFormat::ALL {
        assert_eq!(MeshFormat::from_extension(&format.to_string()), Some(format));
    }
}

// ---------------------------------------------------------------------------------------
// Atomic writes

#[test]
fn saving_into_a_missing_directory_errors_and_leaves_nothing() {
    let scratch = Scratch::new("missing-dir");
    let path = scratch.0.join("no/such/dir/mesh.obj");
    for format in MeshFormat::ALL {
        let e = save(&tetrahedron(), &path, format).unwrap_err();
        assert_eq!(e.origin(), path.display().to_string());
        let MeshIoErrorKind::Io { error, .. } = e.kind() else { panic!("{e}") };
        assert_eq!(error.kind(), std::io::ErrorKind::NotFound, "{e}");
        assert!(e.to_string().starts_with(&format!("{}: cannot create temporary file: ", path.display())), "{e}");
    }
    assert!(scratch.entries().is_empty());
}

#[test]
fn failing_callback_leaves_no_file_and_no_temporary_file() {
    let scratch = Scratch::new("failing-callback");
    let path = scratch.0.join("out.obj");
    let result: std::io::Result<()> = splinekit_io::atomic::write_file(&path, |w| {
        write_obj(&grid(8, 8), w).map_err(std::io::Error::other)?;
        Err(std::io::Error::other("generator failed halfway"))
    });
    assert_eq!(result.unwrap_err().to_string(), "generator failed halfway");
    assert!(scratch.entries().is_empty(), "{:?}", scratch.entries());

    // An existing file keeps its old contents.
    fs::write(&path, "old").unwrap();
    let result: Result<(), splinekit_io::MeshIoError> = splinekit_io::atomic::write_file(&path, |w| {
        w.write_all(b"new and partial")?;
        write_obj(&tetrahedron(), w)?;
        let mut bad = tetrahedron();
        bad.triangles[0][0] = 9;
        write_obj(&bad, w)
    });
    assert!(matches!(result.unwrap_err().kind(), MeshIoErrorKind::InvalidMesh(_)));
    assert_eq!(fs::read_to_string(&path).unwrap(), "old");
    assert_eq!(scratch.entries(), ["out.obj"]);
}

#[test]
fn errors_convert_for_anyhow_style_callers() {
    // `io::Error` callers get the path in the message.
    let scratch = Scratch::new("io-error");
    let path = scratch.0.join("none/x.txt");
    let e: std::io::Error = splinekit_io::atomic::write_file(&path, |w| w.write_all(b"x")).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::NotFound);
    assert!(e.to_string().contains("none/x.txt: cannot create temporary file"), "{e}");
    // A boxed error works as well (like anyhow::Error, it converts from any std error).
    let r: Result<(), Box<dyn std::error::Error + Send + Sync>> = splinekit_io::atomic::write_file(&path, |_| Ok(()));
    assert!(r.unwrap_err().to_string().contains("cannot create temporary file"));
}

// ---------------------------------------------------------------------------------------
// Spline-annotated OBJ (CS 4620 revolution and sweep tools)

/// The bundled spline-annotated OBJ files (copies of the shared data, see their SOURCES.md).
fn spline_obj_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/obj/cs4620-splines")
}

#[test]
fn bundled_sweep_spline_objs_parse() {
    // (file, cross-section closed, cross-section points, swept-along points, scale)
    let expected = [
        ("challace_revolution.obj", false, 19, 4, 0.26302677),
        ("doughnut.obj", true, 5, 5, 0.38264847),
        ("pi.obj", true, 13, 20, 0.044668358),
        ("tie_fighter.obj", true, 13, 8, 0.044668358),
    ];
    let dir = spline_obj_dir();
    for (name, closed, n_cross, n_along, scale) in expected {
        let path = dir.join(name);
        let header = SplineHeader::read(&path).unwrap_or_else(|e| panic!("{e}"));
        let Some(SplineHeader::Sweep(h)) = header else { panic!("{name}: {header:?}") };
        assert_eq!(h.cross_section.closed, closed, "{name}");
        assert!(h.swept_along.closed, "{name}");
        assert_eq!(h.cross_section.control_points.len(), n_cross, "{name}");
        assert_eq!(h.swept_along.control_points.len(), n_along, "{name}");
        assert_eq!(h.scale, scale, "{name}");
        // Reading the whole text gives the same header as reading only the comments.
        let text = fs::read_to_string(&path).unwrap();
        assert_eq!(SplineHeader::parse(&text, name).unwrap(), Some(SplineHeader::Sweep(h.clone())));
        // The mesh after the header is plain OBJ: tobj reads it.
        let mesh = tobj_read(text.as_bytes());
        assert!(!mesh.positions.is_empty() && !mesh.indices.is_empty(), "{name}");
    }
    // Spot values of doughnut.obj (Java float text, including an exponent).
    let Some(SplineHeader::Sweep(h)) = SplineHeader::read(dir.join("doughnut.obj")).unwrap() else { panic!() };
    assert_eq!((h.cross_section.epsilon, h.swept_along.epsilon), (0.0558213, 0.050699063));
    assert_eq!(h.cross_section.control_points[0], DVec2::new(-1.0, -1.2246469e-16));
    assert_eq!(h.swept_along.control_points[4], DVec2::new(-0.309017, 0.95105654));
}

#[test]
fn bundled_files_with_a_broken_value_report_file_line_and_column() {
    let scratch = Scratch::new("broken-header");
    let text = fs::read_to_string(spline_obj_dir().join("pi.obj")).unwrap();
    let broken = text.replacen("# -0.4524715 0.88973385", "# -0.4524715 0.8897e3385", 1);
    let path = scratch.0.join("pi.obj");
    fs::write(&path, broken).unwrap();
    let e = SplineHeader::read(&path).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            r#"{}:12:14: found "0.8897e3385", expected a finite number (y coordinate of cross-section control point 5)"#,
            path.display()
        )
    );
    assert_eq!((e.line(), e.column()), (12, 14));
}

/// A revolution-tool file as the original Java tool writes it (`Float.toString` numbers, the
/// trailing space after `points:`, `%f` mesh numbers).
const JAVA_REVOLUTION_OBJ: &str = "\
# This mesh is a Surface of Revolution: the comments below describe a Spline (cross-section) swept along
# an axis that generated this mesh.
#
# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance
# false 0.11220185 true 0.7943282 0.25118864
#
# Cross-section Spline control points: 
# 0.1 -1.0
# 0.6 -0.5
# 0.4 0.25
# 0.7 1.0
# 1.0E-4 1.0
v 0.100000 -1.000000 0.000000
v 0.600000 -0.500000 0.000000
v 0.400000 0.250000 0.000000
vn 1.000000 0.000000 0.000000
vn 1.000000 0.000000 0.000000
vn 1.000000 0.000000 0.000000
vt 0.000000 0.000000
vt 0.500000 0.500000
vt 1.000000 1.000000
f 1/1/1 2/2/2 3/3/3
";

#[test]
fn revolution_obj_as_the_java_tool_writes_it() {
    let Some(SplineHeader::Revolution(h)) = SplineHeader::parse(JAVA_REVOLUTION_OBJ, "lathe.obj").unwrap() else {
        panic!()
    };
    assert!(!h.closed && h.is_bspline);
    assert_eq!((h.epsilon, h.scale, h.slice_tolerance), (0.11220185, 0.7943282, 0.25118864));
    let points = [(0.1, -1.0), (0.6, -0.5), (0.4, 0.25), (0.7, 1.0), (1.0e-4, 1.0)];
    assert_eq!(h.control_points, points.map(|(x, y)| DVec2::new(x, y)));
    let mesh = tobj_read(JAVA_REVOLUTION_OBJ.as_bytes());
    assert_eq!(mesh.positions.len(), 9);
}

#[test]
fn revolution_obj_round_trips_through_a_file() {
    let scratch = Scratch::new("revolution");
    let Some(SplineHeader::Revolution(header)) = SplineHeader::parse(JAVA_REVOLUTION_OBJ, "lathe.obj").unwrap() else {
        panic!()
    };
    let mesh = grid(6, 4);
    let path = scratch.0.join("lathe.obj");
    save_revolution_obj(&header, &mesh, &path).unwrap();
    let bytes = fs::read(&path).unwrap();

    // Same bytes as the stream writer, and deterministic.
    let mut out = Vec::new();
    write_revolution_obj(&header, &mesh, &mut out).unwrap();
    assert_eq!(bytes, out);

    // The header lines are the Java tool's, byte for byte, except the number spelling of 1.0E-4.
    let text = String::from_utf8(bytes).unwrap();
    let java_header: String = JAVA_REVOLUTION_OBJ.lines().take(12).map(|l| format!("{l}\n")).collect();
    assert!(text.starts_with(&java_header.replace("1.0E-4", "0.0001")), "{text}");

    // The header reads back; the mesh after it reads back exactly with tobj.
    assert_eq!(SplineHeader::read(&path).unwrap(), Some(SplineHeader::Revolution(header.clone())));
    let read = tobj_read(text.as_bytes());
    assert_eq!(tobj_positions_in_mesh_order(&read, &mesh), mesh.positions);
    assert_eq!(read.indices.len(), 3 * mesh.triangles.len());

    // An invalid header value leaves no file.
    let mut bad = header;
    bad.slice_tolerance = -0.1;
    let other = scratch.0.join("other.obj");
    let e = save_revolution_obj(&bad, &mesh, &other).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{}: cannot write slice tolerance = -0.1, expected a positive finite number", other.display())
    );
    assert_eq!(scratch.entries(), ["lathe.obj"]);
}

#[test]
fn plain_obj_has_no_spline_header() {
    let mut out = Vec::new();
    write_obj(&tetrahedron(), &mut out).unwrap();
    assert_eq!(SplineHeader::parse(std::str::from_utf8(&out).unwrap(), "t.obj").unwrap(), None);
    let header_less = "# Blender v2.79 OBJ File\n# www.blender.org\no Cube\nv 1 1 1\n";
    assert_eq!(SplineHeader::parse(header_less, "cube.obj").unwrap(), None);
}

#[test]
fn reading_a_missing_file_names_it() {
    let e = SplineHeader::read("/nonexistent/dir/x.obj").unwrap_err();
    assert!(e.to_string().starts_with("/nonexistent/dir/x.obj: cannot read file: "), "{e}");
}

#[test]
fn reading_stops_at_the_mesh_and_reports_bad_utf8_in_the_header() {
    let scratch = Scratch::new("utf8");
    let path = scratch.0.join("a.obj");
    // Invalid UTF-8 after the header (in the mesh part) is not the header reader's business.
    let mut bytes = JAVA_REVOLUTION_OBJ.as_bytes().to_vec();
    bytes.extend_from_slice(b"g \xff\xfe\n");
    fs::write(&path, &bytes).unwrap();
    assert!(matches!(SplineHeader::read(&path).unwrap(), Some(SplineHeader::Revolution(_))));
    // Invalid UTF-8 inside the header is an error at that line.
    let mut bytes =
        b"# Configs: closed, epsilon, isBSpline, Scale, sliceTolerance\n# false 0.1 true 1.0 0.5\n#\n".to_vec();
    bytes.extend_from_slice(b"# Cross-section Spline control points:\n# 1.0 \xff\n");
    fs::write(&path, &bytes).unwrap();
    let e = SplineHeader::read(&path).unwrap_err();
    assert_eq!((e.line(), e.column()), (5, 7));
    assert!(matches!(e.kind(), MeshIoErrorKind::InvalidUtf8));
}

/// A cancelled save leaves nothing behind: no new file, an existing file unchanged, no
/// temporary file; an uncancelled one writes what `save` writes.
#[test]
fn a_cancelled_save_writes_nothing() {
    let dir = Scratch::new("cancel");
    let mesh = grid(40, 30);
    for format in [MeshFormat::Obj, MeshFormat::Glb, MeshFormat::Ply, MeshFormat::Stl] {
        let name = format!("m.{}", format.extension());
        let path = dir.0.join(&name);
        // cancelled after a few writes: the first chunks went to the temporary file only
        let writes = std::sync::atomic::AtomicUsize::new(0);
        let after_two = || writes.fetch_add(1, std::sync::atomic::Ordering::Relaxed) >= 2;
        let err = save_cancellable(&mesh, &path, format, &after_two).unwrap_err();
        assert!(err.to_string().contains("cancelled"), "{err}");
        assert!(!path.exists(), "{name}");
        fs::write(&path, b"keep").unwrap();
        assert!(save_cancellable(&mesh, &path, format, &|| true).is_err());
        assert_eq!(fs::read(&path).unwrap(), b"keep");
        save_cancellable(&mesh, &path, format, &|| false).unwrap();
        assert_eq!(fs::read(&path).unwrap(), to_bytes(&mesh, format), "{name}");
        fs::remove_file(&path).unwrap();
    }
    assert!(dir.entries().is_empty(), "{:?}", dir.entries());
}

/// #38: an OBJ `f` line without corners is no face to a reader, so a mesh with an empty face
/// (a PLY face list may be empty) is refused by the OBJ writer, by name, before anything is
/// written; PLY keeps it, and reads it back.
#[test]
fn a_face_without_corners_is_not_written_as_a_bare_f() {
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
               element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0\n";
    let mesh = splinekit_io::mesh::read_ply(Cursor::new(ply), "empty-face.ply").unwrap().mesh;
    assert_eq!(mesh.face_offsets, [0, 3, 3]);
    let mut out = Vec::new();
    let err = splinekit_io::mesh::write_obj_poly(&mesh, &mut out).unwrap_err();
    assert!(out.is_empty());
    assert_eq!(err.to_string(), "face 1, with no corners, does not fit in OBJ");
    let mut bytes = Vec::new();
    splinekit_io::mesh::write_ply_poly(&mesh, &mut bytes).unwrap();
    let back = splinekit_io::mesh::read_ply(Cursor::new(&bytes), "back.ply").unwrap().mesh;
    assert_eq!((back.face_offsets, back.face_vertices), (mesh.face_offsets, mesh.face_vertices));
}
