//! `splinekit info MESH`: counts, topology and problems of OBJ, glb, PLY and STL files.

use std::path::Path;

use serde_json::Value;

mod common;
use common::{Run, course_mesh, splinekit};

fn info(file: &Path, json: bool) -> Run {
    let mut args = vec![std::ffi::OsStr::new("info"), file.as_os_str()];
    if json {
        args.push("--json".as_ref());
    }
    splinekit(&args)
}

fn ints(v: &Value) -> Vec<i64> {
    v.as_array().unwrap_or_else(|| panic!("not an array: {v}")).iter().map(|x| x.as_i64().unwrap()).collect()
}

#[test]
fn icosahedron() {
    let path = course_mesh("icosahedron.obj");
    let text = info(&path, false).ok().to_owned();
    for needle in [
        "icosahedron.obj: OBJ mesh, 12 vertices, 20 faces (20 triangles)\n",
        "attributes: none\n",
        "topology:\n  12 vertices, 30 edges, 20 faces\n  boundary: none (closed)\n  components: 1\n",
        "  Euler characteristic: 2\n  genus: 0\n  problems: none\n",
        "read warnings (3):\n  line 2: skipped unknown statement \"<!-- saved from url=",
        "  line 40: skipped unknown statement \"</pre>",
    ] {
        assert!(text.contains(needle), "{needle:?} missing in\n{text}");
    }
    let j = info(&path, true).json();
    assert_eq!(j["format"], "obj");
    assert_eq!((j["vertices"].as_u64(), j["faces"].as_u64(), j["triangles"].as_u64()), (Some(12), Some(20), Some(20)));
    assert_eq!((j["edges"].as_u64(), j["boundary_edges"].as_u64()), (Some(30), Some(0)));
    assert_eq!((j["euler_characteristic"].as_i64(), j["genus"].as_u64()), (Some(2), Some(0)));
    assert_eq!(j["closed"], true);
    assert_eq!(j["problems"]["count"], 0);
    let lines: Vec<i64> = j["warnings"].as_array().unwrap().iter().map(|w| w["line"].as_i64().unwrap()).collect();
    assert_eq!(lines, vec![2, 3, 40]);
    assert!(j["warnings"][0]["message"].as_str().unwrap().starts_with("skipped unknown statement \"<!--"));
}

#[test]
fn bunny() {
    let path = course_mesh("bunny.obj");
    let j = info(&path, true).json();
    assert_eq!((j["vertices"].as_u64(), j["faces"].as_u64()), (Some(2503), Some(4968)));
    let loops = ints(&j["boundary_loops"]);
    assert_eq!(loops.len(), 4);
    assert_eq!(loops.iter().sum::<i64>(), 42);
    assert_eq!(j["boundary_edges"], 42);
    assert_eq!((j["euler_characteristic"].as_i64(), j["genus"].as_u64()), (Some(-2), Some(0)));
    assert_eq!(
        (&j["components"], &j["closed"], &j["manifold"]),
        (&Value::from(1), &Value::from(false), &Value::from(true))
    );
    let text = info(&path, false).ok().to_owned();
    assert!(text.contains("  boundary: 42 edges in 4 loops ("), "{text}");
    assert!(text.contains("  Euler characteristic: -2\n  genus: 0\n"), "{text}");
}

/// An OBJ with problems of every kind: three faces on edge 0–1 (faces 0, 1, 2), a bowtie
/// at vertex 5 (faces 3, 4), a duplicate (face 5 of face 3), a face with a repeated vertex
/// (face 6), a short face (face 7), and unreferenced vertex 10.
const PROBLEMS_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n\
    v 5 0 0\nv 6 0 0\nv 5 1 0\nv 4 0 0\nv 5 -1 0\nv 9 9 9\n\
    f 1 2 3\nf 2 1 4\nf 1 2 5\nf 6 7 8\nf 6 9 10\nf 7 8 6\nf 1 1 3\nf 1 2\n";

#[test]
fn problems_are_listed_and_exit_is_zero() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.obj");
    std::fs::write(&path, PROBLEMS_OBJ).unwrap();
    let text = info(&path, false).ok().to_owned();
    for needle in [
        "bad.obj: OBJ mesh, 11 vertices, 8 faces (7 triangles, 1 other)\n",
        "non-manifold edges (1):\n      edge 0–1: faces 0, 1, 2\n",
        "non-manifold vertices (1):\n      vertex 5: 2 fans\n",
        "face 6: vertex 0 repeated\n",
        "face 5: same vertices as face 3\n",
        "face 7: 2 vertices\n",
        "unreferenced vertices (1): 10\n",
    ] {
        assert!(text.contains(needle), "{needle:?} missing in\n{text}");
    }
    let j = info(&path, true).json();
    let p = &j["problems"];
    assert_eq!(ints(&p["nonmanifold_edges"][0]["vertices"]), vec![0, 1]);
    assert_eq!(ints(&p["nonmanifold_edges"][0]["faces"]), vec![0, 1, 2]);
    assert_eq!(
        (p["nonmanifold_vertices"][0]["vertex"].as_u64(), p["nonmanifold_vertices"][0]["fans"].as_u64()),
        (Some(5), Some(2))
    );
    assert_eq!(p["degenerate_faces"][0], serde_json::json!({"face": 6, "reason": "repeated vertex", "vertex": 0}));
    assert_eq!(p["duplicate_faces"][0], serde_json::json!({"face": 5, "first": 3}));
    assert_eq!(p["short_faces"][0], serde_json::json!({"face": 7, "corners": 2}));
    assert_eq!(ints(&p["unreferenced_vertices"]), vec![10]);
    // Faces 3 and 5 run the same way around the same triangle.
    assert_eq!(ints(&p["inconsistent_edges"][0]["faces"]), vec![3, 5]);
    assert_eq!(j["manifold"], false);
    assert_eq!(j["genus"], Value::Null);
    assert!(p["count"].as_u64().unwrap() >= 7);
}

#[test]
fn flipped_face_and_long_lists() {
    let dir = tempfile::tempdir().unwrap();
    // A tetrahedron with face 3 flipped, and 25 unreferenced vertices.
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n");
    for k in 0..25 {
        obj += &format!("v {k} 7 7\n");
    }
    let path = dir.path().join("tet.obj");
    std::fs::write(&path, obj).unwrap();
    let text = info(&path, false).ok().to_owned();
    assert!(text.contains("faces to flip for a consistent orientation (1): 3\n"), "{text}");
    assert!(text.contains("unreferenced vertices (25): 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, … and 15 more\n"), "{text}");
    assert!(text.contains("genus: 0\n"), "{text}");
    let j = info(&path, true).json();
    assert_eq!(ints(&j["problems"]["misoriented_faces"]), vec![3]);
    assert_eq!(ints(&j["problems"]["unreferenced_vertices"]).len(), 25);
    assert_eq!((&j["orientable"], &j["consistently_oriented"]), (&Value::from(true), &Value::from(false)));
}

#[test]
fn ply_and_stl() {
    let dir = tempfile::tempdir().unwrap();
    let ply = dir.path().join("quad.ply");
    std::fs::write(
        &ply,
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
    )
    .unwrap();
    let text = info(&ply, false).ok().to_owned();
    assert!(text.starts_with(&format!("{}: PLY mesh, 4 vertices, 1 face (1 quad)\n", ply.display())), "{text}");
    assert!(text.contains("boundary: 4 edges in 1 loop (4)\n"), "{text}");
    let stl = dir.path().join("tri.stl");
    std::fs::write(
        &stl,
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n\
         facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n",
    )
    .unwrap();
    let j = info(&stl, true).json();
    assert_eq!((j["format"].as_str(), j["vertices"].as_u64(), j["edges"].as_u64()), (Some("stl"), Some(4), Some(5)));
    assert_eq!(j["euler_characteristic"], 1);
}

#[test]
fn glb_written_by_trimesh() {
    // An icosphere and a transformed box (crates/splinekit-io/tests/data/glb, made by
    // scripts/make_glb_references.py).
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data/glb/trimesh_scene.glb");
    let text = info(&path, false).ok().to_owned();
    assert!(
        text.starts_with(&format!("{}: GLB mesh, 50 vertices, 92 faces (92 triangles)\n", path.display())),
        "{text}"
    );
    let j = info(&path, true).json();
    assert_eq!(j["format"], "glb");
    assert_eq!((&j["normals"], &j["uvs"], &j["colors"]), (&Value::from(true), &Value::from(true), &Value::from(false)));
    assert_eq!((&j["components"], &j["closed"]), (&Value::from(2), &Value::from(true)));
    assert_eq!(j["problems"]["count"], 0);
}

#[test]
fn malformed_and_unreadable_files_fail_with_a_position() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.obj");
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap();
    let err = info(&path, false).fails().to_owned();
    assert!(
        err.contains(&format!("{}:4:7: found \"7\", expected a vertex index from 1 to 3", path.display())),
        "{err}"
    );
    let missing = dir.path().join("missing.ply");
    let err = info(&missing, true).fails().to_owned();
    assert!(err.contains("missing.ply: cannot read"), "{err}");
    let glb = dir.path().join("x.glb");
    std::fs::write(&glb, "glTF").unwrap();
    let err = info(&glb, false).fails().to_owned();
    assert!(
        err.contains(&format!(
            "{}: found end of file, expected a 12-byte binary glTF header (the file has 4 bytes)",
            glb.display()
        )),
        "{err}"
    );
}

#[test]
fn help_documents_meshes_and_json_fields() {
    let run = splinekit(&["info", "--help"]);
    let help = run.ok();
    for needle in ["mesh file (.obj, .glb, .ply, .stl)", "euler_characteristic", "nonmanifold_edges", "boundary_loops"]
    {
        assert!(help.contains(needle), "{needle:?} missing in\n{help}");
    }
}

/// Files as people have them (#39): triangle strips, UTF-16, continued lines; what the
/// reader skips is on standard error, `warning: FILE: …`, as well as in the report.
#[test]
fn files_as_people_have_them() {
    let dir = tempfile::tempdir().unwrap();
    // A scanner's PLY: two strips of a quad each, a confidence per vertex, a range grid.
    let ply = dir.path().join("scan.ply");
    let text = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n\
                property float confidence\nelement range_grid 1\nproperty list uchar int vertex_indices\n\
                element tristrips 1\nproperty list int int vertex_indices\nend_header\n\
                0 0 0 1\n0 1 0 1\n1 0 0 1\n1 1 0 1\n2 0 0 1\n2 1 0 1\n1 0\n9 0 2 1 3 -1 2 4 3 5\n";
    std::fs::write(&ply, text).unwrap();
    let run = info(&ply, false);
    let report = run.ok();
    assert!(
        report.starts_with(&format!("{}: PLY mesh, 6 vertices, 4 faces (4 triangles)\n", ply.display())),
        "{report}"
    );
    assert!(report.contains("  problems: none\n"), "{report}");
    assert!(report.contains("read warnings (2):\n"), "{report}");
    let file = ply.display();
    assert_eq!(
        run.stderr,
        format!(
            "warning: {file}: line 7: skipped property \"confidence\" of element \"vertex\"\n\
             warning: {file}: line 8: skipped element \"range_grid\" (1 in the file; the elements read are vertex, face and tristrips)\n"
        )
    );
    let j = info(&ply, true).json();
    assert_eq!(
        (j["faces"].as_u64(), j["boundary_edges"].as_u64(), j["consistently_oriented"].as_bool()),
        (Some(4), Some(6), Some(true))
    );

    // Notepad's UTF-16 OBJ, with a line continued.
    let obj = dir.path().join("notepad.obj");
    let mut bytes = vec![0xFF, 0xFE];
    for unit in "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 \\\r\n  3\r\n".encode_utf16() {
        bytes.extend(unit.to_le_bytes());
    }
    std::fs::write(&obj, &bytes).unwrap();
    let run = info(&obj, false);
    assert!(run.ok().starts_with(&format!("{}: OBJ mesh, 3 vertices, 1 face (1 triangle)\n", obj.display())));
    assert_eq!(run.stderr, "");
    // Without its byte-order mark: a clear error, not an empty mesh.
    std::fs::write(&obj, &bytes[2..]).unwrap();
    let message = info(&obj, false).fails_with_error().to_owned();
    assert_eq!(
        message,
        format!(
            "error: {}: found text that looks like UTF-16 without a byte-order mark, expected UTF-8 (or UTF-16 with a byte-order mark)\n",
            obj.display()
        )
    );
}
