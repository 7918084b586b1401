//! Integration tests of the mesh readers (OBJ, glb, PLY, STL) and `load_mesh`: the bundled
//! course meshes with their known counts and topology, a `.glb` written by trimesh, round
//! trips through our writers, generated ASCII and binary samples, and errors with exact
//! positions.

use std::collections::HashMap;
use std::f64::consts::TAU;
use std::fs;
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use splinekit::TriMesh;
use splinekit::mesh::{Degeneracy, PolyMesh, TopologyReport};
use splinekit_io::mesh::{
    LoadedMesh, MeshFormat, ReadWarningKind, load_mesh, read_glb, read_mesh, read_obj, read_ply, read_stl, write_mesh,
};

// ---------------------------------------------------------------------------------------
// Helpers

/// The folder holding `name` among the test copies and the shared data folder.
fn data_file(name: &str) -> PathBuf {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = [
        crate_dir.join("tests/data/obj"),
        crate_dir.join("../../../shared/data/obj"),
        crate_dir.join("../../shared/data/obj"),
    ];
    candidates
        .iter()
        .map(|d| d.join(name))
        .find(|p| p.is_file())
        .unwrap_or_else(|| panic!("no {name} in any of {candidates:?}"))
}

fn load(name: &str) -> LoadedMesh {
    let path = data_file(name);
    load_mesh(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn report(mesh: &PolyMesh) -> TopologyReport {
    TopologyReport::new(mesh, 0.0)
}

/// A temporary directory, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("splinekit-mesh-read-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }

    fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let path = self.0.join(name);
        fs::write(&path, bytes).unwrap();
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// A torus of `n × m` quads split into triangles, with normals and UVs, coordinates not
/// exact in binary.
fn torus(n: u32, m: u32) -> TriMesh {
    let mut mesh = TriMesh::default();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(m));
            let (su, cu) = (TAU * u).sin_cos();
            let (sv, cv) = (TAU * v).sin_cos();
            let r = 1.0 + 0.3 * cv;
            mesh.positions.push(DVec3::new(r * cu, r * su, 0.3 * sv) * 0.7);
            mesh.normals.push(DVec3::new(cv * cu, cv * su, sv));
            mesh.uvs.push(DVec2::new(u, v));
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    for i in 0..n {
        for j in 0..m {
            mesh.triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            mesh.triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    mesh
}

fn bytes_of(mesh: &TriMesh, format: MeshFormat) -> Vec<u8> {
    let mut out = Vec::new();
    write_mesh(mesh, &mut out, format).unwrap();
    out
}

fn f32_round(p: DVec3) -> DVec3 {
    p.as_vec3().as_dvec3()
}

/// Merges equal positions (test-side welding of OBJ files with duplicated seams): exactly
/// equal ones with `decimals` `None`, else those equal when rounded to that many decimals
/// (correctly rounded, as Python's `round(x, n)`).
fn weld(mesh: &PolyMesh, decimals: Option<usize>) -> PolyMesh {
    let mut map: HashMap<[i64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let remap: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let key = match decimals {
                None => p.to_array().map(|x| x.to_bits() as i64),
                Some(n) => p.to_array().map(|x| (format!("{x:.n$}").parse::<f64>().unwrap() + 0.0).to_bits() as i64),
            };
            *map.entry(key).or_insert_with(|| {
                positions.push(*p);
                positions.len() as u32 - 1
            })
        })
        .collect();
    PolyMesh {
        positions,
        face_offsets: mesh.face_offsets.clone(),
        face_vertices: mesh.face_vertices.iter().map(|&v| remap[v as usize]).collect(),
        ..PolyMesh::default()
    }
}

// ---------------------------------------------------------------------------------------
// The course meshes (counts from shared/data/SOURCES.md)

#[test]
fn icosahedron_with_its_html_lines() {
    let loaded = load("icosahedron.obj");
    let m = &loaded.mesh;
    assert_eq!((m.num_vertices(), m.num_faces()), (12, 20));
    assert!(m.is_triangle_mesh() && m.normals.is_none() && m.uvs.is_none() && m.colors.is_empty());
    let warnings: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(warnings.len(), 3, "{warnings:#?}");
    assert!(
        warnings[0]
            .starts_with(r#"line 2: skipped unknown statement "<!-- saved from url=(0060)http://people.sc.fsu.edu"#)
    );
    assert!(warnings[1].starts_with(r#"line 3: skipped unknown statement "<html><head><meta http-equiv="#));
    assert!(warnings[2].starts_with(r#"line 40: skipped unknown statement "</pre></body>"#));
    assert!(warnings.iter().all(|w| w.chars().count() < 120), "{warnings:#?}");
    let r = report(m);
    assert!(r.is_clean(), "{r}");
    assert!(r.is_closed());
    assert_eq!((r.num_edges, r.euler_characteristic, r.genus(), r.components.len()), (30, 2, Some(0), 1));
    // Consistently oriented outward: positive signed volume.
    assert!(m.to_tri_mesh().signed_volume() > 0.0);

    let clean = load("clean/icosahedron.obj");
    assert!(clean.warnings.is_empty());
    assert_eq!(clean.mesh, loaded.mesh);
}

#[test]
fn bunny_has_four_holes() {
    let loaded = load("bunny.obj");
    let m = &loaded.mesh;
    assert_eq!((m.num_vertices(), m.num_faces()), (2503, 4968));
    let lines: Vec<usize> = loaded.warnings.iter().map(|w| w.line).collect();
    assert_eq!(lines, vec![2, 3, 7477]);
    let r = report(m);
    assert!(r.is_clean(), "{r}");
    assert_eq!(r.num_boundary_edges, 42);
    assert_eq!(r.boundary_loops.len(), 4);
    assert!(r.boundary_loops.iter().all(|l| l.closed));
    assert_eq!(r.boundary_loops.iter().map(|l| l.num_edges()).sum::<usize>(), 42);
    assert_eq!((r.euler_characteristic, r.components.len(), r.genus()), (-2, 1, Some(0)));
    assert!(r.is_consistently_oriented());

    let clean = load("clean/bunny.obj");
    assert!(clean.warnings.is_empty());
    assert_eq!(clean.mesh, loaded.mesh);
}

#[test]
fn patch_is_an_open_grid() {
    let loaded = load("patch.obj");
    assert!(loaded.warnings.is_empty());
    let m = &loaded.mesh;
    assert_eq!((m.num_vertices(), m.num_faces()), (16, 18));
    let r = report(m);
    assert!(r.is_clean(), "{r}");
    assert_eq!(r.boundary_loops.len(), 1);
    assert_eq!(r.boundary_loops[0].num_edges(), 12);
    assert_eq!((r.num_boundary_edges, r.euler_characteristic, r.genus()), (12, 1, Some(0)));
    // Faces point toward +z.
    let t = m.to_tri_mesh();
    assert!((0..t.num_triangles()).all(|i| t.face_normal(i).z > 0.0));
}

#[test]
fn spline_annotated_objs_read_with_attributes() {
    // (file, V, F; welded exactly: V, boundary edges; welded at 1e-4 (as SOURCES.md's
    // statistics were): boundary edges, faces with a repeated vertex, non-manifold edges)
    let expected = [
        ("cs4620-splines/challace_revolution.obj", 2310, 4416, 2240, 64, 64, 0, 0),
        ("cs4620-splines/doughnut.obj", 6561, 12800, 6400, 0, 0, 0, 0),
        ("cs4620-splines/pi.obj", 11160, 21896, 10948, 0, 0, 12, 0),
        ("cs4620-splines/tie_fighter.obj", 11336, 22248, 11124, 0, 0, 2700, 21),
    ];
    for (name, v, f, welded_v, boundary, coarse_boundary, degenerate, nonmanifold) in expected {
        let loaded = load(name);
        assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
        let m = &loaded.mesh;
        assert_eq!((m.num_vertices(), m.num_faces()), (v, f), "{name}");
        // `v`, `vt` and `vn` are 1:1 and faces are `f a/a/a`.
        let uvs = m.uvs.as_ref().unwrap();
        let normals = m.normals.as_ref().unwrap();
        assert_eq!((uvs.values.len(), normals.values.len()), (v, v), "{name}");
        assert_eq!(uvs.indices, m.face_vertices, "{name}");
        assert_eq!(normals.indices, m.face_vertices, "{name}");
        // Seam vertices are duplicated; welded, the topology of SOURCES.md appears.
        let welded = weld(m, None);
        let r = report(&welded);
        assert_eq!((welded.num_vertices(), r.num_boundary_edges), (welded_v, boundary), "{name}:\n{r}");
        assert!(r.is_clean(), "{name}:\n{r}");
        let coarse = weld(m, Some(4));
        let r = report(&coarse);
        assert_eq!(r.num_boundary_edges, coarse_boundary, "{name}:\n{r}");
        let repeated =
            r.degenerate_faces.iter().filter(|d| matches!(d.kind, Degeneracy::RepeatedVertex { .. })).count();
        assert_eq!(repeated, degenerate, "{name}:\n{r}");
        assert_eq!(r.nonmanifold.iter().filter(|p| p.is_edge()).count(), nonmanifold, "{name}:\n{r}");
        // Splitting makes it manifold.
        let (split, _) = splinekit::mesh::split_nonmanifold(&coarse);
        let r = report(&split);
        assert!(r.is_manifold() && r.is_consistently_oriented(), "{name}:\n{r}");
    }
}

#[test]
fn objs_agree_with_tobj() {
    for name in ["icosahedron.obj", "bunny.obj", "patch.obj", "cs4620-splines/doughnut.obj"] {
        let path = data_file(name);
        let ours = load_mesh(&path).unwrap().mesh;
        let options = tobj::LoadOptions { triangulate: false, single_index: false, ..Default::default() };
        let (models, _) = tobj::load_obj(&path, &options).unwrap();
        assert_eq!(models.len(), 1, "{name}");
        // tobj renumbers vertices by first use; compare corner by corner.
        let theirs = &models[0].mesh;
        let position = |i: u32| {
            let k = 3 * i as usize;
            DVec3::new(theirs.positions[k], theirs.positions[k + 1], theirs.positions[k + 2])
        };
        assert_eq!(theirs.indices.len(), ours.face_vertices.len(), "{name}");
        for (&t, &o) in theirs.indices.iter().zip(&ours.face_vertices) {
            assert_eq!(position(t), ours.positions[o as usize], "{name}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// Round trips through our writers

#[test]
fn obj_round_trip_is_exact() {
    for mesh in [torus(12, 7), TriMesh { normals: vec![], uvs: vec![], ..torus(5, 4) }] {
        let bytes = bytes_of(&mesh, MeshFormat::Obj);
        let read = read_obj(bytes.as_slice(), "rt.obj").unwrap();
        assert!(read.warnings.is_empty());
        let m = read.mesh;
        assert_eq!(m.positions, mesh.positions);
        assert_eq!(m.triangles().unwrap(), mesh.triangles);
        // Attributes come back face-varying with per-vertex indices, and convert back.
        assert_eq!(m.to_tri_mesh(), mesh);
        assert_eq!(m.uvs.is_some(), !mesh.uvs.is_empty());
    }
}

#[test]
fn ply_round_trip_rounds_to_f32() {
    let mesh = torus(9, 6);
    let m = read_ply(bytes_of(&mesh, MeshFormat::Ply).as_slice(), "rt.ply").unwrap().mesh;
    assert_eq!(m.positions, mesh.positions.iter().map(|&p| f32_round(p)).collect::<Vec<_>>());
    assert_eq!(m.triangles().unwrap(), mesh.triangles);
    assert_eq!(m.normals.as_ref().unwrap().values, mesh.normals.iter().map(|&p| f32_round(p)).collect::<Vec<_>>());
    let uvs: Vec<DVec2> = mesh.uvs.iter().map(|p| p.as_vec2().as_dvec2()).collect();
    assert_eq!(m.uvs.as_ref().unwrap().values, uvs);
    assert!(report(&m).is_clean());
}

#[test]
fn glb_round_trip_rounds_to_f32() {
    let r = |x: f64| f64::from(x as f32);
    for mesh in [torus(9, 6), TriMesh { normals: vec![], uvs: vec![], ..torus(5, 4) }] {
        let read = read_glb(bytes_of(&mesh, MeshFormat::Glb).as_slice(), "rt.glb").unwrap();
        assert!(read.warnings.is_empty());
        let m = read.mesh;
        assert_eq!(m.positions, mesh.positions.iter().map(|&p| f32_round(p)).collect::<Vec<_>>());
        assert_eq!(m.triangles().unwrap(), mesh.triangles);
        // Normals are written normalised; UVs as (u, 1 − v), read back as (u, 1 − v).
        let normals: Vec<DVec3> = mesh.normals.iter().map(|n| f32_round(n.normalize_or_zero())).collect();
        assert_eq!(m.normals.as_ref().map(|n| &n.values), (!normals.is_empty()).then_some(&normals));
        let uvs: Vec<DVec2> = mesh.uvs.iter().map(|t| DVec2::new(r(t.x), 1.0 - r(1.0 - t.y))).collect();
        assert_eq!(m.uvs.as_ref().map(|n| &n.values), (!uvs.is_empty()).then_some(&uvs));
        for (a, b) in uvs.iter().zip(&mesh.uvs) {
            assert!(a.distance(*b) < 1e-7);
        }
        assert!(report(&m).is_clean());
        // Back to the same TriMesh, up to f32 rounding.
        let back = m.to_tri_mesh();
        assert_eq!(back.triangles, mesh.triangles);
        assert_eq!(back.normals, normals);
    }
    // A mesh without triangles is written without vertices, and reads as an empty mesh.
    let empty = TriMesh { positions: vec![DVec3::ONE], ..TriMesh::default() };
    let m = read_glb(bytes_of(&empty, MeshFormat::Glb).as_slice(), "e.glb").unwrap();
    assert!(m.warnings.is_empty());
    assert_eq!((m.mesh.num_vertices(), m.mesh.num_faces()), (0, 0));
}

#[test]
fn a_glb_written_by_trimesh_reads_as_trimesh_sees_it() {
    // Made by scripts/make_glb_references.py: an icosphere on an untransformed node and a box
    // on a node with a matrix under a parent with translation and rotation; u16 indices; the
    // sphere's positions and normals interleaved. The JSON holds trimesh's reading of it.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/glb");
    let loaded = load_mesh(dir.join("trimesh_scene.glb")).unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let refs: gltf_json::Value =
        gltf_json::deserialize::from_slice(&fs::read(dir.join("trimesh_scene.json")).unwrap()).unwrap();
    assert_eq!(refs["index_component_types"], gltf_json::Value::from(vec![5123]));
    let m = &loaded.mesh;
    assert_eq!(m.num_vertices() as u64, refs["vertices"].as_u64().unwrap());
    assert_eq!(m.num_faces() as u64, refs["triangles"].as_u64().unwrap());
    let vec =
        |v: &gltf_json::Value| -> Vec<f64> { v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect() };
    let vec3 = |v: &gltf_json::Value| DVec3::from_slice(&vec(v));
    // The references have 9 significant digits; the node matrices are read as f32.
    const TOLERANCE: f64 = 2e-6;
    let (min, max) =
        m.positions.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    assert!(min.distance(vec3(&refs["bounds"][0])) < TOLERANCE, "{min}");
    assert!(max.distance(vec3(&refs["bounds"][1])) < TOLERANCE, "{max}");
    let normals = &m.normals.as_ref().unwrap().values;
    let uvs = &m.uvs.as_ref().unwrap().values;
    let find = |p: DVec3| m.positions.iter().position(|q| q.distance(p) < TOLERANCE);
    for node in refs["nodes"].as_array().unwrap() {
        let name = node["node"].as_str().unwrap();
        let p = vec3(&node["first_vertex"]);
        let i = find(p).unwrap_or_else(|| panic!("{name}: no vertex at {p}"));
        assert!(normals[i].distance(vec3(&node["first_normal"])) < TOLERANCE, "{name}: {}", normals[i]);
        assert!(uvs[i].distance(DVec2::from_slice(&vec(&node["first_uv"]))) < TOLERANCE, "{name}: {}", uvs[i]);
        // The first triangle, with its orientation.
        let corners: Vec<usize> =
            node["first_triangle"].as_array().unwrap().iter().map(|c| find(vec3(c)).unwrap()).collect();
        let oriented = m.faces().any(|f| (0..3).any(|k| (0..3).all(|j| f[(j + k) % 3] as usize == corners[j])));
        assert!(oriented, "{name}: no face {corners:?}");
    }
    // Both meshes are closed, and consistently oriented after the transforms.
    let r = report(m);
    assert!(r.is_clean() && r.is_closed(), "{r}");
    assert_eq!(r.components.len(), 2);
}

#[test]
fn stl_round_trip_welds_back_to_the_mesh() {
    let mesh = torus(10, 8);
    let m = read_stl(bytes_of(&mesh, MeshFormat::Stl).as_slice(), "rt.stl").unwrap().mesh;
    // Welding restores the shared vertices (every f32-rounded position is distinct), in
    // order of first appearance.
    assert_eq!(m.num_vertices(), mesh.num_vertices());
    assert_eq!(m.num_faces(), mesh.num_triangles());
    for (t, &tri) in m.triangles().unwrap().iter().zip(&mesh.triangles) {
        for k in 0..3 {
            assert_eq!(m.positions[t[k] as usize], f32_round(mesh.positions[tri[k] as usize]));
        }
    }
    let r = report(&m);
    assert!(r.is_clean() && r.is_closed(), "{r}");
    assert_eq!((r.euler_characteristic, r.genus()), (0, Some(1)));
}

// ---------------------------------------------------------------------------------------
// Generated ASCII and binary samples

/// The torus as ASCII PLY with uchar colours, written by hand.
fn ascii_ply(mesh: &TriMesh) -> String {
    let mut s = format!(
        "ply\nformat ascii 1.0\ncomment by hand\nelement vertex {}\nproperty double x\nproperty double y\n\
         property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face {}\n\
         property list uchar uint vertex_indices\nend_header\n",
        mesh.num_vertices(),
        mesh.num_triangles()
    );
    for (i, p) in mesh.positions.iter().enumerate() {
        s += &format!("{:?} {:?} {:?} {} 0 255\n", p.x, p.y, p.z, i % 256);
    }
    for t in &mesh.triangles {
        s += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
    }
    s
}

#[test]
fn ascii_and_big_endian_ply() {
    let mesh = torus(6, 5);
    let m = read_ply(ascii_ply(&mesh).as_bytes(), "a.ply").unwrap().mesh;
    assert_eq!(m.positions, mesh.positions);
    assert_eq!(m.triangles().unwrap(), mesh.triangles);
    assert_eq!(m.colors[7], DVec3::new(7.0 / 255.0, 0.0, 1.0));

    // Binary big endian, doubles and short indices, with quads.
    let mut b = format!(
        "ply\nformat binary_big_endian 1.0\nelement vertex {}\nproperty double x\nproperty double y\n\
         property double z\nelement face 2\nproperty list uchar short vertex_indices\nend_header\n",
        4
    )
    .into_bytes();
    let quad = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    for p in quad {
        for x in p.to_array() {
            b.extend(x.to_be_bytes());
        }
    }
    for face in [&[0i16, 1, 2, 3][..], &[0, 2, 1]] {
        b.push(face.len() as u8);
        for &i in face {
            b.extend(i.to_be_bytes());
        }
    }
    let m = read_ply(b.as_slice(), "b.ply").unwrap().mesh;
    assert_eq!(m.positions, quad);
    assert_eq!(m.face_offsets, vec![0, 4, 7]);
    assert_eq!(m.face_vertices, vec![0, 1, 2, 3, 0, 2, 1]);
}

#[test]
fn ascii_stl_welds_like_binary_stl() {
    let mesh = torus(7, 5);
    let mut s = String::from("solid torus\n");
    for t in &mesh.triangles {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for &v in t {
            // The f32 values, written exactly.
            let p = f32_round(mesh.positions[v as usize]);
            s += &format!("      vertex {:?} {:?} {:?}\n", p.x, p.y, p.z);
        }
        s += "    endloop\n  endfacet\n";
    }
    s += "endsolid torus\n";
    let ascii = read_stl(s.as_bytes(), "a.stl").unwrap().mesh;
    let binary = read_stl(bytes_of(&mesh, MeshFormat::Stl).as_slice(), "b.stl").unwrap().mesh;
    assert_eq!(ascii, binary);
    assert_eq!(ascii.num_vertices(), mesh.num_vertices());
}

#[test]
fn a_large_obj_reads() {
    // 100 000 triangles; reading is one pass without per-line allocation (time it with
    // `cargo test --release -- --nocapture a_large_obj`).
    let mesh = torus(250, 200);
    let bytes = bytes_of(&mesh, MeshFormat::Obj);
    let start = std::time::Instant::now();
    let m = read_obj(bytes.as_slice(), "big.obj").unwrap().mesh;
    eprintln!("read {} MB of OBJ ({} triangles) in {:?}", bytes.len() >> 20, m.num_faces(), start.elapsed());
    assert_eq!(m.num_faces(), 100_000);
    assert_eq!(m.positions, mesh.positions);
}

// ---------------------------------------------------------------------------------------
// load_mesh, streams and errors

#[test]
fn load_mesh_chooses_by_extension() {
    let dir = TempDir::new("ext");
    let mesh = torus(4, 3);
    let obj = dir.write("t.OBJ", bytes_of(&mesh, MeshFormat::Obj));
    let ply = dir.write("t.ply", bytes_of(&mesh, MeshFormat::Ply));
    let stl = dir.write("t.Stl", bytes_of(&mesh, MeshFormat::Stl));
    let glb = dir.write("t.GLB", bytes_of(&mesh, MeshFormat::Glb));
    for path in [obj, ply, stl, glb] {
        let m = load_mesh(&path).unwrap_or_else(|e| panic!("{e}")).mesh;
        assert_eq!((m.num_vertices(), m.num_faces()), (12, 24), "{}", path.display());
    }
    let e = load_mesh(dir.write("t.glb", b"glTF")).unwrap_err().to_string();
    assert!(
        e.ends_with("t.glb: found end of file, expected a 12-byte binary glTF header (the file has 4 bytes)"),
        "{e}"
    );
    let e = load_mesh(dir.write("t.off", b"OFF")).unwrap_err().to_string();
    assert!(e.ends_with(r#"t.off: found ".off", expected a mesh file ending in .obj, .glb, .ply or .stl"#), "{e}");
    let e = load_mesh(dir.0.join("missing.obj")).unwrap_err().to_string();
    assert!(e.contains("missing.obj: cannot read: "), "{e}");
    // Stream form.
    let m = read_mesh(bytes_of(&mesh, MeshFormat::Ply).as_slice(), MeshFormat::Ply, "s").unwrap();
    assert_eq!(m.mesh.num_faces(), 24);
    let m = read_mesh(bytes_of(&mesh, MeshFormat::Glb).as_slice(), MeshFormat::Glb, "s").unwrap();
    assert_eq!(m.mesh.num_faces(), 24);
    assert!(read_mesh(&b""[..], MeshFormat::Glb, "s").is_err());
}

#[test]
fn errors_name_file_line_and_column() {
    let dir = TempDir::new("err");
    let cases: [(&str, &[u8], &str); 7] = [
        ("a.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", r#"a.obj:4:7: found "4", expected a vertex index from 1 to 3 or from -3 to -1"#),
        ("b.obj", b"v 0 0 0\r\nv 1 0.5.0 0\r\n", r#"b.obj:2:5: found "0.5.0", expected a number (y coordinate)"#),
        ("c.obj", b"v 0 0 0\nf 1 1 0\n", r#"c.obj:2:7: found "0", expected a non-zero vertex index (OBJ counts from 1)"#),
        ("d.obj", b"v 0 0 0\nvt 0 0\nf 1/2 1/1 1/1\n", r#"d.obj:3:5: found "2", expected a texture coordinate index from 1 to 1 or from -1 to -1"#),
        ("e.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 nan0\n", r#"e.ply:8:5: found "nan0", expected a float (property z of vertex 0 of 1)"#),
        ("f.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0", "f.ply: found end of file, expected a float (property y of vertex 0 of 2)"),
        ("g.stl", b"solid g\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1\nendloop\n", r#"g.stl:7:1: found "endloop", expected a number (z coordinate of vertex 3)"#),
    ];
    for (name, bytes, message) in cases {
        let e = load_mesh(dir.write(name, bytes)).unwrap_err().to_string();
        assert_eq!(e, format!("{}/{message}", dir.0.display()));
    }
    // A binary STL of 0 triangles with trailing bytes reads, with a warning.
    let m = load_mesh(dir.write("h.stl", [0u8; 90])).unwrap();
    assert_eq!(m.mesh.num_faces(), 0);
    assert_eq!(m.warnings[0].kind, ReadWarningKind::TrailingBytes { count: 6 });
}

/// Issue #38 (found by the fuzz harness, `fuzz/`): binary PLY and glb files can hold
/// infinite or NaN normals, texture coordinates and colours; the readers kept them (only
/// positions were refused), and every writer then refused the mesh as invalid. Now they are
/// refused when read, as non-finite positions are.
#[test]
fn regression_38_non_finite_attributes_are_refused() {
    let header = |extra: &str| {
        format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\n{extra}element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        )
    };
    let file = |extra: &str, per_vertex: usize, bad: f32| {
        let mut bytes = header(extra).into_bytes();
        for v in 0..3 {
            for k in 0..3 + per_vertex {
                let x = if v == 1 && k == 4 {
                    bad
                } else if k == v {
                    1.0
                } else {
                    0.0
                };
                bytes.extend(x.to_le_bytes());
            }
        }
        bytes.push(3);
        for i in 0..3i32 {
            bytes.extend(i.to_le_bytes());
        }
        bytes
    };
    let cases = [
        ("property float nx\nproperty float ny\nproperty float nz\n", 3, "vertex 2 has normal y = inf"),
        ("property float u\nproperty float v\n", 2, "vertex 2 has v = NaN"),
        ("property float red\nproperty float green\nproperty float blue\n", 3, "vertex 2 has green = -inf"),
    ];
    for ((extra, per_vertex, expected), bad) in cases.into_iter().zip([f32::INFINITY, f32::NAN, f32::NEG_INFINITY]) {
        let bytes = file(extra, per_vertex, bad);
        let err = read_mesh(bytes.as_slice(), MeshFormat::Ply, "a.ply").unwrap_err();
        assert_eq!(err.to_string(), format!("a.ply: {expected}, expected a finite number"));
        // the same file with a finite value reads
        let good = file(extra, per_vertex, 0.5);
        assert!(read_mesh(good.as_slice(), MeshFormat::Ply, "a.ply").is_ok());
    }
}

// ---------------------------------------------------------------------------------------
// Files as people have them (#39)

/// The header of a PLY file of the 5 × 3 grid of vertices `3·x + y` at (x, y, 0), x in 0..5,
/// y in 0..3, and its `tristrips` element; `FORMAT` is replaced by the format.
const STRIP_HEADER: &str = "ply\nformat FORMAT 1.0\ncomment a 4 x 2 grid of quads in four strips\n\
                            element vertex 15\nproperty float x\nproperty float y\nproperty float z\n\
                            element tristrips 1\nproperty list int int vertex_indices\nend_header\n";

/// The strips of the grid, one column of two quads each.
const GRID_STRIPS: [i32; 27] =
    [0, 3, 1, 4, 2, 5, -1, 3, 6, 4, 7, 5, 8, -1, 6, 9, 7, 10, 8, 11, -1, 9, 12, 10, 13, 11, 14];

/// The triangles MeshLab reads from the grid's strips (pymeshlab 2025.7.post1, `face_matrix`
/// of the ASCII, little-endian and big-endian files, all three the same).
const MESHLAB_GRID_TRIANGLES: [[u32; 3]; 16] = [
    [0, 3, 1],
    [1, 3, 4],
    [1, 4, 2],
    [2, 4, 5],
    [3, 6, 4],
    [4, 6, 7],
    [4, 7, 5],
    [5, 7, 8],
    [6, 9, 7],
    [7, 9, 10],
    [7, 10, 8],
    [8, 10, 11],
    [9, 12, 10],
    [10, 12, 13],
    [10, 13, 11],
    [11, 13, 14],
];

/// An ASCII PLY of the grid with the strip list `strip`.
fn strip_ply(strip: &[i32]) -> String {
    let mut text = STRIP_HEADER.replace("FORMAT", "ascii");
    for v in 0..15 {
        text += &format!("{} {} 0\n", v / 3, v % 3);
    }
    let items: Vec<String> = strip.iter().map(ToString::to_string).collect();
    text + &format!("{} {}\n", strip.len(), items.join(" "))
}

/// A binary PLY of the grid with the strip list `strip`.
fn binary_strip_ply(strip: &[i32], big: bool) -> Vec<u8> {
    let format = if big { "binary_big_endian" } else { "binary_little_endian" };
    let mut bytes = STRIP_HEADER.replace("FORMAT", format).into_bytes();
    let f32_bytes = |x: f32| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    let i32_bytes = |x: i32| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    for v in 0..15 {
        for x in [v / 3, v % 3, 0] {
            bytes.extend(f32_bytes(x as f32));
        }
    }
    bytes.extend(i32_bytes(strip.len() as i32));
    for &i in strip {
        bytes.extend(i32_bytes(i));
    }
    bytes
}

/// A triangle turned to start at its smallest vertex (the same triangle, facing the same way).
fn canonical([a, b, c]: [u32; 3]) -> [u32; 3] {
    match a.min(b).min(c) {
        m if m == a => [a, b, c],
        m if m == b => [b, c, a],
        _ => [c, a, b],
    }
}

fn triangles(mesh: &PolyMesh) -> Vec<[u32; 3]> {
    mesh.faces().map(|f| canonical([f[0], f[1], f[2]])).collect()
}

#[test]
fn ply_tristrips_read_as_meshlab_reads_them() {
    let dir = TempDir::new("strips");
    let expected: Vec<[u32; 3]> = MESHLAB_GRID_TRIANGLES.iter().map(|&t| canonical(t)).collect();
    let files = [
        ("ascii.ply", strip_ply(&GRID_STRIPS).into_bytes()),
        ("little.ply", binary_strip_ply(&GRID_STRIPS, false)),
        ("big.ply", binary_strip_ply(&GRID_STRIPS, true)),
    ];
    for (name, bytes) in files {
        let loaded = load_mesh(dir.write(name, bytes)).unwrap();
        assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
        let m = &loaded.mesh;
        assert_eq!((m.num_vertices(), m.num_faces()), (15, 16), "{name}");
        assert_eq!(triangles(m), expected, "{name}");
        // Every triangle faces +z, as the first does: the alternate winding is right.
        for f in m.faces() {
            let [a, b, c] = [f[0], f[1], f[2]].map(|v| m.positions[v as usize]);
            assert!((b - a).cross(c - a).z > 0.0, "{name}: {f:?}");
        }
        // The strips make the whole grid: one disk, its 12 outer edges the boundary.
        let r = report(m);
        assert!(r.is_clean() && r.is_consistently_oriented(), "{name}: {r}");
        assert_eq!((r.num_boundary_edges, r.boundary_loops.len(), r.euler_characteristic), (12, 1, 1), "{name}");
    }
}

#[test]
fn ply_tristrip_restarts_and_degenerate_triangles() {
    let read = |strip: &[i32]| {
        let loaded = read_ply(strip_ply(strip).as_bytes(), "s.ply").unwrap_or_else(|e| panic!("{e}"));
        loaded.mesh.faces().map(|f| [f[0], f[1], f[2]]).collect::<Vec<_>>()
    };
    // Worked by hand: triangle k of a strip is (a, b, c) for even k and (a, c, b) for odd k,
    // k counted from the start of each strip, so the strip after an odd-length one starts
    // over with (a, b, c).
    assert_eq!(read(&[0, 3, 1, -1, 3, 6, 4, 7]), [[0, 3, 1], [3, 6, 4], [6, 7, 4]]);
    assert_eq!(read(&[0, 3, 1, 4]), [[0, 3, 1], [3, 4, 1]]);
    // Triangles with a repeated vertex are left out, and count for the winding: MeshLab
    // reads [0 3 1] and [4 1 2] from this strip.
    assert_eq!(read(&[0, 3, 1, 1, 4, 2]), [[0, 3, 1], [1, 2, 4]]);
    assert_eq!(read(&[5, 5, 8, 7]), [[5, 7, 8]]);
    // Strips too short for a triangle, and empty ones (two restarts in a row, which MeshLab
    // refuses), give nothing.
    assert_eq!(read(&[0, 3, 1, 4, -1, 5, 8]), [[0, 3, 1], [3, 4, 1]]);
    assert_eq!(read(&[-1, 0, 3, 1, -1, -1]), [[0, 3, 1]]);
    // `vertex_index`, as some writers name the list, and a face element beside the strips.
    let text = strip_ply(&[0, 3, 1]).replace("vertex_indices", "vertex_index");
    let text = text
        .replace("element tristrips 1", "element face 1\nproperty list uchar int vertex_indices\nelement tristrips 1");
    let text = text.replace("3 0 3 1\n", "4 1 4 5 2\n3 0 3 1\n");
    let m = read_ply(text.as_bytes(), "s.ply").unwrap().mesh;
    assert_eq!(m.face_offsets, [0, 4, 7]);
    assert_eq!(m.face_vertices, [1, 4, 5, 2, 0, 3, 1]);
}

#[test]
fn ply_tristrip_errors() {
    let dir = TempDir::new("strip-errors");
    let err = |name: &str, bytes: Vec<u8>| {
        let e = load_mesh(dir.write(name, bytes)).unwrap_err().to_string();
        e.strip_prefix(&format!("{}/", dir.0.display())).unwrap_or(&e).to_owned()
    };
    // ASCII: line and column of the index; binary: the element and item.
    assert_eq!(
        err("a.ply", strip_ply(&[0, 3, 15]).into_bytes()),
        r#"a.ply:26:7: found "15", expected a vertex index below 15, or -1 to restart the strip (item 2 of tristrips 0)"#
    );
    assert_eq!(
        err("b.ply", strip_ply(&[0, 3, 1, -2]).into_bytes()),
        r#"b.ply:26:9: found "-2", expected a vertex index below 15, or -1 to restart the strip (item 3 of tristrips 0)"#
    );
    assert_eq!(
        err("c.ply", binary_strip_ply(&[0, -7, 1], true)),
        r#"c.ply: found "-7", expected a vertex index below 15, or -1 to restart the strip (item 1 of tristrips 0)"#
    );
    let mut truncated = binary_strip_ply(&GRID_STRIPS, false);
    truncated.truncate(truncated.len() - 2);
    assert_eq!(
        err("d.ply", truncated),
        "d.ply: found end of file, expected an int (item 26 of list vertex_indices of tristrips 0)"
    );
    // Strips, and not one triangle from them: an error, not an empty mesh.
    assert_eq!(
        err("e.ply", strip_ply(&[0, 3, 3, 1, -1, 4, 5]).into_bytes()),
        r#"e.ply: read no faces from element "tristrips" (1 strip): no strip has a triangle of three different vertices"#
    );
    assert_eq!(
        err("f.ply", strip_ply(&[]).into_bytes()),
        r#"f.ply: read no faces from element "tristrips" (1 strip): no strip has a triangle of three different vertices"#
    );
    assert_eq!(
        err("g.ply", strip_ply(&[0, 1, 2]).replace("vertex_indices", "corners").into_bytes()),
        r#"g.ply:8:9: found "tristrips", expected an element with a list property vertex_indices or vertex_index"#
    );
}

#[test]
fn ply_skipped_elements_and_properties_are_warnings() {
    // A range scan as the Stanford repository has them: confidence and intensity per vertex,
    // a range grid, and a face with a flag and per-corner texture coordinates.
    let text = "ply\nformat ascii 1.0\nobj_info num_cols 2\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nproperty float confidence\nproperty float intensity\nproperty uchar alpha\n\
                element range_grid 2\nproperty list uchar int vertex_indices\nelement face 1\n\
                property uchar flags\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n\
                element material 0\nproperty float shininess\nend_header\n\
                0 0 0 0.5 0.5 1\n1 0 0 0.5 0.5 1\n0 1 0 0.5 0.5 1\n1 0\n0\n7 3 0 1 2 6 0 0 1 0 0 1\n";
    let loaded = read_ply(text.as_bytes(), "scan.ply").unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        w,
        [
            r#"line 8: skipped property "confidence" of element "vertex""#,
            r#"line 9: skipped property "intensity" of element "vertex""#,
            r#"line 10: skipped property "alpha" of element "vertex""#,
            r#"line 11: skipped element "range_grid" (2 in the file; the elements read are vertex, face and tristrips)"#,
            r#"line 14: skipped property "flags" of element "face""#,
        ]
    );
    // the per-corner texture coordinates are read, as face-varying UVs
    let uvs = loaded.mesh.uvs.as_ref().unwrap();
    let corner = |c: usize| uvs.values[uvs.indices[c] as usize];
    assert_eq!([corner(0), corner(1), corner(2)], [DVec2::ZERO, DVec2::X, DVec2::Y]);
    let short = text.replace("6 0 0 1 0 0 1", "4 0 0 1 0");
    assert_eq!(
        read_ply(short.as_bytes(), "scan.ply").unwrap_err().to_string(),
        "scan.ply: found \"4 numbers\", expected two texture coordinates for each of the 3 corners of face 0 (texcoord)"
    );
    assert_eq!(loaded.warnings[3].kind, ReadWarningKind::SkippedElement { name: "range_grid".into(), count: 2 });
    assert_eq!(loaded.mesh.face(0), &[0, 1, 2]);
    // Our own writer's files have nothing to skip.
    let ply = bytes_of(&torus(4, 3), MeshFormat::Ply);
    assert!(read_ply(ply.as_slice(), "t.ply").unwrap().warnings.is_empty());
}

/// `text` as UTF-16 with a byte-order mark.
fn utf16(text: &str, big: bool) -> Vec<u8> {
    let mut bytes = if big { vec![0xFE, 0xFF] } else { vec![0xFF, 0xFE] };
    for unit in text.encode_utf16() {
        bytes.extend(if big { unit.to_be_bytes() } else { unit.to_le_bytes() });
    }
    bytes
}

#[test]
fn utf16_text_is_decoded_or_refused() {
    let dir = TempDir::new("utf16");
    let obj = "# made by Notepad\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nvn 0 0 1\r\nf 1//1 2//1 3//1\r\n";
    let plain = read_obj(obj.as_bytes(), "p.obj").unwrap();
    for big in [false, true] {
        let loaded = load_mesh(dir.write("u.obj", utf16(obj, big))).unwrap();
        assert_eq!(loaded, plain, "big endian: {big}");
    }
    let loaded = load_mesh(dir.write("u8.obj", [b"\xEF\xBB\xBF", obj.as_bytes()].concat())).unwrap();
    assert_eq!(loaded, plain);
    // Errors count lines and characters of the decoded text.
    let e = load_mesh(dir.write("bad.obj", utf16("v 0 0 0\nv é 0 0\n", false))).unwrap_err();
    assert_eq!((e.line(), e.column()), (2, 3), "{e}");
    // Without a byte-order mark: refused, not read as an empty mesh.
    let no_bom = utf16(obj, false)[2..].to_vec();
    let e = load_mesh(dir.write("nobom.obj", &no_bom)).unwrap_err().to_string();
    assert!(
        e.ends_with("nobom.obj: found text that looks like UTF-16 without a byte-order mark, expected UTF-8 (or UTF-16 with a byte-order mark)"),
        "{e}"
    );
    let big_no_bom = utf16(obj, true)[2..].to_vec();
    assert!(load_mesh(dir.write("nobom-be.obj", big_no_bom)).unwrap_err().to_string().contains("UTF-16"));

    // ASCII PLY and STL too.
    let ply = strip_ply(&GRID_STRIPS);
    let plain = read_ply(ply.as_bytes(), "p.ply").unwrap();
    assert_eq!(load_mesh(dir.write("u.ply", utf16(&ply, true))).unwrap(), plain);
    assert_eq!(load_mesh(dir.write("u8.ply", [b"\xEF\xBB\xBF", ply.as_bytes()].concat())).unwrap(), plain);
    let e = load_mesh(dir.write("nobom.ply", &utf16(&ply, false)[2..])).unwrap_err().to_string();
    assert!(e.ends_with("nobom.ply: found text that looks like UTF-16 without a byte-order mark, expected UTF-8 (or UTF-16 with a byte-order mark)"), "{e}");
    let stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    let plain = read_stl(stl.as_bytes(), "p.stl").unwrap();
    assert_eq!(load_mesh(dir.write("u.stl", utf16(stl, false))).unwrap(), plain);
    let e = load_mesh(dir.write("nobom.stl", &utf16(stl, true)[2..])).unwrap_err().to_string();
    assert!(e.ends_with("nobom.stl: found text that looks like UTF-16 without a byte-order mark, expected UTF-8 (or UTF-16 with a byte-order mark)"), "{e}");
}

#[test]
fn obj_line_continuation() {
    let text = "v 0 0 0\nv 1 \\\n  0 0\nv 0 1 0 \\  \r\n\nvt 0 0\nf 1/1 \\\n2/1\\\n 3/1\n";
    let m = read_obj(text.as_bytes(), "c.obj").unwrap();
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    assert_eq!(m.mesh.positions, [DVec3::ZERO, DVec3::X, DVec3::Y]);
    assert_eq!(m.mesh.face(0), &[0, 1, 2]);
    assert_eq!(m.mesh.uvs.unwrap().indices, [0, 0, 0]);
    // Errors give the line and column where the token is, not where the statement starts.
    let err = |text: &str| read_obj(text.as_bytes(), "c.obj").unwrap_err().to_string();
    assert_eq!(err("v 0 0 \\\n  x\n"), r#"c.obj:2:3: found "x", expected a number (z coordinate)"#);
    assert_eq!(
        err("v 0 0 0\nv 1 0 0\nf 1 \\\n 2 \\\n\t\t-4\n"),
        r#"c.obj:5:3: found "-4", expected a vertex index from 1 to 2 or from -2 to -1"#
    );
    // A forward reference, checked at the end of the file, and a crease tag's vertex too.
    assert_eq!(
        err("f 1 2 \\\n   9\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"),
        r#"c.obj:2:4: found "9", expected a vertex index from 1 to 3 or from -3 to -1"#
    );
    assert_eq!(
        err("v 0 0 0\nv 1 0 0\nt crease 2/1 \\\n 0 5 \\\n 1\n"),
        r#"c.obj:4:4: found "5", expected a vertex index from 0 to 1 (tags count vertices from 0)"#
    );
    // A backslash at the end of a comment is part of the comment; at the end of the file it
    // continues into nothing.
    let m = read_obj("v 0 0 0 # C:\\dir\\\nv 1 0 0\nv 0 1 0\nf 1 2 3 \\".as_bytes(), "c.obj").unwrap();
    assert_eq!((m.mesh.num_vertices(), m.mesh.num_faces()), (3, 1));
}

#[test]
fn obj_geometry_that_is_not_read() {
    let dir = TempDir::new("obj-skipped");
    // A polyline and points beside a face: one warning per kind, with the count.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\nl 3 1\np 1\nf 1 2 3\nmg 1 0.5\nc_interp on\n";
    let loaded = load_mesh(dir.write("lines.obj", text)).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        w,
        [
            r#"line 4: skipped 3 "l" statements, the first on this line (lines are not read)"#,
            r#"line 7: skipped 1 "p" statement (points are not read)"#,
        ]
    );
    assert_eq!(
        loaded.warnings[0].kind,
        ReadWarningKind::SkippedStatements { keyword: "l", count: 3, reason: "lines are not read" }
    );
    // A points-only file reads: it has no face records (commands that need faces say so).
    let points = load_mesh(dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")).unwrap();
    assert_eq!((points.mesh.num_vertices(), points.mesh.num_faces(), points.warnings.len()), (3, 0, 0));
    // A free-form surface and nothing else: an error, not an empty mesh.
    let surface = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\n\
                   surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 1 1\nend\n";
    let e = load_mesh(dir.write("surface.obj", surface)).unwrap_err().to_string();
    assert!(
        e.ends_with(
            "surface.obj: read no faces from 1 free-form surface (surf): free-form surfaces are not read; export them as polygons"
        ),
        "{e}"
    );
    // With a face beside it, the surface is a warning.
    let loaded = load_mesh(dir.write("both.obj", format!("{surface}f 1 2 3\n"))).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        w,
        [
            r#"line 5: skipped 1 "cstype" statement (free-form geometry is not read)"#,
            r#"line 6: skipped 1 "deg" statement (free-form geometry is not read)"#,
            r#"line 7: skipped 1 "surf" statement (free-form surfaces are not read)"#,
            r#"line 8: skipped 2 "parm" statements, the first on this line (free-form geometry is not read)"#,
            r#"line 10: skipped 1 "end" statement (free-form geometry is not read)"#,
        ]
    );
}

// ---------------------------------------------------------------------------------------
// Never a panic

mod no_panic {
    use glam::{DVec2, DVec3};
    use proptest::prelude::*;
    use splinekit::TriMesh;
    use splinekit_io::mesh::{MeshFormat, read_mesh, write_mesh};

    /// Small valid files of each format, to be mutated.
    fn seeds() -> Vec<(MeshFormat, Vec<u8>)> {
        let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
                   element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let mut binary_ply = ply.replace("ascii", "binary_little_endian").into_bytes();
        binary_ply.truncate(binary_ply.len() - 26);
        binary_ply.extend([0u8; 36]);
        binary_ply.extend([3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0]);
        let mut stl = vec![0u8; 80];
        stl.extend(1u32.to_le_bytes());
        stl.extend([0u8; 50]);
        vec![
            (MeshFormat::Obj, b"v 0 0 0\nv 1 0 0 1 1 1\nv 0 1 0\nv 1 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2//1 -1/1\nf 1 2 3 4\n".to_vec()),
            (MeshFormat::Ply, ply.as_bytes().to_vec()),
            (MeshFormat::Ply, binary_ply),
            (MeshFormat::Stl, b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n".to_vec()),
            (MeshFormat::Stl, stl),
            (MeshFormat::Glb, glb()),
            (
                MeshFormat::Glb,
                std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/glb/trimesh_scene.glb")).unwrap(),
            ),
            (MeshFormat::Ply, super::binary_strip_ply(&super::GRID_STRIPS, false)),
            (MeshFormat::Obj, super::utf16("v 0 0 0\nv 1 0 \\\n 0\nv 0 1 0\nl 1 2\nf 1 2 3\n", true)),
        ]
    }

    /// A quad with normals and UVs, by our writer.
    fn glb() -> Vec<u8> {
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE],
            normals: vec![DVec3::Z; 4],
            uvs: vec![DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::ONE],
            triangles: vec![[0, 1, 2], [1, 3, 2]],
            ..TriMesh::default()
        };
        let mut out = Vec::new();
        write_mesh(&mesh, &mut out, MeshFormat::Glb).unwrap();
        out
    }

    #[test]
    fn seeds_are_valid() {
        for (format, bytes) in seeds() {
            read_mesh(bytes.as_slice(), format, "seed").unwrap_or_else(|e| panic!("{format}: {e}"));
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

        /// Flipping, inserting or deleting bytes of a valid file gives a mesh or an error.
        #[test]
        fn mutated_files_do_not_panic(
            seed in 0..9usize,
            edits in proptest::collection::vec((any::<u16>(), any::<u8>(), 0..3u8), 1..6),
        ) {
            let (format, mut bytes) = seeds().swap_remove(seed);
            for (at, byte, op) in edits {
                let at = at as usize % (bytes.len() + 1);
                match op {
                    0 if at < bytes.len() => bytes[at] = byte,
                    1 => bytes.insert(at, byte),
                    _ if at < bytes.len() => { bytes.remove(at); }
                    _ => {}
                }
            }
            if let Ok(loaded) = read_mesh(bytes.as_slice(), format, "m") {
                // Whatever is read has valid indices and can be analysed.
                let m = &loaded.mesh;
                prop_assert!(m.face_vertices.iter().all(|&v| (v as usize) < m.num_vertices()));
                for (indices, n) in [
                    m.normals.as_ref().map(|a| (&a.indices, a.values.len())),
                    m.uvs.as_ref().map(|a| (&a.indices, a.values.len())),
                ]
                .into_iter()
                .flatten()
                {
                    prop_assert_eq!(indices.len(), m.face_vertices.len());
                    prop_assert!(indices.iter().all(|&i| (i as usize) < n));
                }
                prop_assert!(m.colors.is_empty() || m.colors.len() == m.num_vertices());
                let _ = splinekit::mesh::TopologyReport::new(m, 0.0).to_string();
                let _ = splinekit::mesh::split_nonmanifold(m);
            }
        }

        /// Arbitrary bytes never panic any reader.
        #[test]
        fn random_bytes_do_not_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300), seed in 0..4usize) {
            let format = [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Stl, MeshFormat::Glb][seed];
            let _ = read_mesh(bytes.as_slice(), format, "r");
        }

        /// Bit flips in a valid `.glb` (its JSON, lengths and data) give a mesh or an error.
        #[test]
        fn glb_bit_flips_do_not_panic(seed in 5..7usize, flips in proptest::collection::vec(any::<u16>(), 1..4)) {
            let mut bytes = seeds().swap_remove(seed).1;
            for bit in flips {
                let bit = bit as usize % (8 * bytes.len());
                bytes[bit / 8] ^= 1 << (bit % 8);
            }
            if let Ok(loaded) = read_mesh(bytes.as_slice(), MeshFormat::Glb, "f") {
                let m = &loaded.mesh;
                prop_assert!(m.face_vertices.iter().all(|&v| (v as usize) < m.num_vertices()));
            }
        }
    }
}
