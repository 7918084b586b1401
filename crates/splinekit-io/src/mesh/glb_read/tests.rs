use glam::{DVec2, DVec3};

use super::container::{decode_base64, u32_at};
use super::*;
use crate::mesh::glb::{CHUNK_BIN, CHUNK_JSON, MAGIC};
use crate::mesh::load::MAX_WARNINGS;

/// A `.glb` of `json` and, if not empty, the binary chunk `bin` (both padded).
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    j.resize(j.len().next_multiple_of(4), b' ');
    let mut b = bin.to_vec();
    b.resize(b.len().next_multiple_of(4), 0);
    let total = 12 + 8 + j.len() + if b.is_empty() { 0 } else { 8 + b.len() };
    let mut out = Vec::new();
    out.extend(MAGIC);
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(CHUNK_JSON);
    out.extend(j);
    if !b.is_empty() {
        out.extend((b.len() as u32).to_le_bytes());
        out.extend(CHUNK_BIN);
        out.extend(b);
    }
    out
}

fn f32s(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// A unit quad in z = 0 as a triangle strip: positions and normals interleaved (stride
/// 24), normalized u16 UVs, u8 indices; its node is moved by x + 10.
fn strip_quad() -> (String, Vec<u8>) {
    let json = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"translation":[10,0,0]}],
"meshes":[{"name":"quad","primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"mode":5}]}],
"buffers":[{"byteLength":116}],
"bufferViews":[{"buffer":0,"byteLength":96,"byteStride":24},{"buffer":0,"byteOffset":96,"byteLength":16},
{"buffer":0,"byteOffset":112,"byteLength":4}],
"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
{"bufferView":0,"byteOffset":12,"componentType":5126,"count":4,"type":"VEC3"},
{"bufferView":1,"componentType":5123,"normalized":true,"count":4,"type":"VEC2"},
{"bufferView":2,"componentType":5121,"count":4,"type":"SCALAR"}]}"#;
    let mut bin = Vec::new();
    for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0f32]] {
        bin.extend(f32s(&p));
        bin.extend(f32s(&[0.0, 0.0, 1.0]));
    }
    for uv in [[0u16, 65535], [65535, 65535], [0, 0], [65535, 0]] {
        bin.extend(uv.iter().flat_map(|x| x.to_le_bytes()));
    }
    bin.extend([0u8, 1, 2, 3]);
    (json.replace('\n', ""), bin)
}

fn read(bytes: &[u8]) -> LoadedMesh {
    parse_glb(bytes, "t.glb").unwrap_or_else(|e| panic!("{e}"))
}

fn err(bytes: &[u8]) -> String {
    parse_glb(bytes, "t.glb").unwrap_err().to_string()
}

/// The error for the strip quad with `from` replaced by `to` in its JSON.
fn json_err(from: &str, to: &str) -> String {
    let (json, bin) = strip_quad();
    assert!(json.contains(from), "{from}");
    err(&glb(&json.replacen(from, to, 1), &bin))
}

#[test]
fn strip_with_stride_normalized_uvs_and_translation() {
    let (json, bin) = strip_quad();
    let m = read(&glb(&json, &bin));
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    let m = m.mesh;
    let x = DVec3::X * 10.0;
    assert_eq!(m.positions, vec![x, x + DVec3::X, x + DVec3::Y, x + DVec3::new(1.0, 1.0, 0.0)]);
    assert_eq!(m.face_vertices, vec![0, 1, 2, 1, 3, 2]);
    assert_eq!(m.face_offsets, vec![0, 3, 6]);
    let normals = m.normals.unwrap();
    assert_eq!(normals.values, vec![DVec3::Z; 4]);
    assert_eq!(normals.indices, m.face_vertices);
    assert_eq!(m.uvs.unwrap().values, vec![DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::ONE]);
    assert!(m.colors.is_empty());
}

#[test]
fn fans_lists_and_no_indices() {
    let (json, bin) = strip_quad();
    // Fan 0 1 3 2: triangles (1 3 0) and (3 2 0).
    let mut fan = bin.clone();
    fan[112..116].copy_from_slice(&[0, 1, 3, 2]);
    let m = read(&glb(&json.replace(r#""mode":5"#, r#""mode":6"#), &fan)).mesh;
    assert_eq!(m.face_vertices, vec![1, 3, 0, 3, 2, 0]);
    // A strip without indices: the vertices in order.
    let m = read(&glb(&json.replace(r#","indices":3"#, ""), &bin)).mesh;
    assert_eq!(m.face_vertices, vec![0, 1, 2, 1, 3, 2]);
    // A list (the default mode) of 4 indices does not make whole triangles.
    assert_eq!(
        err(&glb(&json.replace(r#","mode":5"#, ""), &bin)),
        "t.glb: meshes[0].primitives[0]: found 4 indices with mode TRIANGLES, expected a multiple of 3"
    );
    // A strip with a repeated index: the degenerate triangles are left out; none left is
    // an error (#39), a file of points is not.
    let mut degenerate = bin.clone();
    degenerate[112..116].copy_from_slice(&[0, 1, 1, 2]);
    assert_eq!(
        err(&glb(&json, &degenerate)),
        "t.glb: read no faces from 1 mesh primitive of triangles: it has no triangle with three different vertices"
    );
    let no_position = json.replace(r#""POSITION":0,"#, "");
    assert_eq!(
        err(&glb(&no_position.replace("}]}]", "},{\"attributes\":{},\"mode\":4}]}]"), &bin)),
        "t.glb: read no faces from 2 mesh primitives of triangles: they have no POSITION attribute"
    );
    let points = read(&glb(&json.replace(r#""mode":5"#, r#""mode":0"#), &bin));
    assert_eq!((points.mesh.num_vertices(), points.mesh.num_faces(), points.warnings.len()), (0, 0, 1));
}

#[test]
fn transforms_matrix_trs_hierarchy_and_mirror() {
    let (json, bin) = strip_quad();
    let positions = |node: &str| {
        let j = json.replace(r#"{"mesh":0,"translation":[10,0,0]}"#, node);
        read(&glb(&j, &bin)).mesh
    };
    // A quarter turn about z, then x + 1: as TRS and as a column-major matrix.
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let trs = positions(&format!(r#"{{"mesh":0,"rotation":[0,0,{s},{s}],"translation":[1,0,0]}}"#));
    let matrix = positions(r#"{"mesh":0,"matrix":[0,1,0,0, -1,0,0,0, 0,0,1,0, 1,0,0,1]}"#);
    for (a, b) in trs.positions.iter().zip(&matrix.positions) {
        assert!(a.distance(*b) < 1e-7, "{a} {b}");
    }
    assert!(matrix.positions[1].distance(DVec3::new(1.0, 1.0, 0.0)) < 1e-12);
    // Parent x + 10, child scaled by 2 (normals stay unit).
    let j = json.replace(
        r#""nodes":[{"mesh":0,"translation":[10,0,0]}]"#,
        r#""nodes":[{"children":[1],"translation":[10,0,0]},{"mesh":0,"scale":[2,2,2]}]"#,
    );
    let m = read(&glb(&j, &bin)).mesh;
    assert_eq!(m.positions[3], DVec3::new(12.0, 2.0, 0.0));
    assert_eq!(m.normals.unwrap().values[0], DVec3::Z);
    // A mirror in x: triangles reversed to stay counter-clockwise; the normals keep +z.
    let m = positions(r#"{"mesh":0,"scale":[-1,1,1]}"#);
    assert_eq!(m.positions[1], DVec3::new(-1.0, 0.0, 0.0));
    assert_eq!(m.face_vertices, vec![0, 2, 1, 1, 2, 3]);
    assert_eq!(m.normals.unwrap().values[0], DVec3::Z);
    // A shear: the normal is transformed by the inverse transpose (it stays
    // perpendicular to the transformed quad).
    let m = positions(r#"{"mesh":0,"matrix":[1,0,0,0, 0,1,0,0, 1,0,1,0, 0,0,0,1]}"#);
    assert_eq!(m.normals.as_ref().unwrap().values[0], DVec3::Z);
    let m = positions(r#"{"mesh":0,"matrix":[1,0,1,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}"#);
    let n = m.normals.as_ref().unwrap().values[0];
    let edge = m.positions[1] - m.positions[0];
    assert!(n.dot(edge).abs() < 1e-12 && (n.length() - 1.0).abs() < 1e-12, "{n} {edge}");
}

#[test]
fn several_nodes_primitives_and_no_scene() {
    let (json, bin) = strip_quad();
    // Two nodes share the mesh: each gets its own vertices.
    let j = json.replace(
        r#""scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[10,0,0]}]"#,
        r#""scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0,"translation":[10,0,0]},{"mesh":0}]"#,
    );
    let m = read(&glb(&j, &bin)).mesh;
    assert_eq!(m.num_vertices(), 8);
    assert_eq!(m.face_vertices[6..], [4, 5, 6, 5, 7, 6]);
    assert_eq!(m.positions[4], DVec3::ZERO);
    // Without scenes, every mesh once, untransformed.
    let j = json.replace(r#""scene":0,"scenes":[{"nodes":[0]}],"#, "");
    let m = read(&glb(&j, &bin)).mesh;
    assert_eq!(m.positions[0], DVec3::ZERO);
    // Without `scene`, the first of `scenes`.
    let m = read(&glb(&json.replace(r#""scene":0,"#, ""), &bin)).mesh;
    assert_eq!(m.positions[0], DVec3::X * 10.0);
    // Two primitives on the same accessors share vertices; one of lines is skipped, once
    // even though two nodes use the mesh; one without normals or UVs drops them.
    let prim = r#"{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"mode":5}"#;
    let j = json.replace(
        prim,
        &format!(
            r#"{prim},{prim},{{"attributes":{{"POSITION":0}},"mode":1}},{{"attributes":{{"POSITION":0}},"indices":3,"mode":5}},{{"attributes":{{}}}}"#
        ),
    );
    let j = j.replace(r#""nodes":[{"mesh":0,"translation":[10,0,0]}]"#, r#""nodes":[{"mesh":0},{"mesh":0}]"#);
    let j = j.replace(r#""nodes":[0]"#, r#""nodes":[0,1]"#);
    let m = read(&glb(&j, &bin));
    let text: Vec<String> = m.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        text,
        [
            r#"skipped meshes[0].primitives[2] (mesh "quad"): its mode is LINES, not triangles"#,
            r#"skipped meshes[0].primitives[4] (mesh "quad"): it has no POSITION attribute"#,
            "dropped the normals: 4 mesh primitives have them, 2 do not (the first is meshes[0].primitives[3])",
            "dropped the texture coordinates: 4 mesh primitives have them, 2 do not (the first is meshes[0].primitives[3])",
        ]
    );
    let m = m.mesh;
    // Per node: 4 vertices for primitives 0 and 1, 4 more for primitive 3.
    assert_eq!((m.num_vertices(), m.num_faces()), (16, 12));
    assert_eq!(m.face_vertices[..12], [0, 1, 2, 1, 3, 2, 0, 1, 2, 1, 3, 2]);
    assert!(m.normals.is_none() && m.uvs.is_none());
    // Many skipped primitives: the warnings are capped.
    let points = r#"{"attributes":{"POSITION":0},"mode":0}"#;
    let many = vec![points; MAX_WARNINGS + 3].join(",");
    let m = read(&glb(&json.replace(prim, &format!("{prim},{many}")), &bin));
    assert_eq!(m.warnings.len(), MAX_WARNINGS + 1);
    assert_eq!(m.warnings[MAX_WARNINGS].to_string(), "… and 3 more warnings like the previous one");
    assert_eq!(m.mesh.num_faces(), 2);
}

#[test]
fn colors_and_data_uris() {
    let (json, bin) = strip_quad();
    // Vertex colours: normalized u8 VEC4 appended to the buffer (alpha dropped).
    let mut b = bin.clone();
    b.extend([255u8, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 0]);
    let j = json
        .replace(r#""TEXCOORD_0":2"#, r#""TEXCOORD_0":2,"COLOR_0":4"#)
        .replace(r#""byteLength":116}]"#, r#""byteLength":132}]"#)
        .replace(
            r#"{"buffer":0,"byteOffset":112,"byteLength":4}"#,
            r#"{"buffer":0,"byteOffset":112,"byteLength":4},{"buffer":0,"byteOffset":116,"byteLength":16}"#,
        )
        .replace(
            r#""type":"SCALAR"}"#,
            r#""type":"SCALAR"},{"bufferView":3,"componentType":5121,"normalized":true,"count":4,"type":"VEC4"}"#,
        );
    let m = read(&glb(&j, &b)).mesh;
    assert_eq!(m.colors, vec![DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE]);
    // The same buffer as a base64 data URI, and no BIN chunk.
    let encoded = base64(&bin);
    let j = json.replace(
        r#""buffers":[{"byteLength":116}]"#,
        &format!(r#""buffers":[{{"byteLength":116,"uri":"data:application/octet-stream;base64,{encoded}"}}]"#),
    );
    let m = read(&glb(&j, &[])).mesh;
    assert_eq!(m.positions[3], DVec3::new(11.0, 1.0, 0.0));
    assert_eq!(decode_base64(b"TWFu"), Some(b"Man".to_vec()));
    assert_eq!(decode_base64(b"TWE="), Some(b"Ma".to_vec()));
    assert_eq!(decode_base64(b"TQ"), Some(b"M".to_vec()));
    assert_eq!(decode_base64(b"T"), None);
    assert_eq!(decode_base64(b"T*=="), None);
}

/// Standard base64 with padding, for the tests.
fn base64(bytes: &[u8]) -> String {
    const DIGITS: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let n = chunk.iter().enumerate().fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(DIGITS[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[test]
fn header_and_chunk_errors() {
    let (json, bin) = strip_quad();
    let good = glb(&json, &bin);
    assert_eq!(err(b"glTF"), "t.glb: found end of file, expected a 12-byte binary glTF header (the file has 4 bytes)");
    let mut b = good.clone();
    b[0] = b'g';
    b[3] = 0xFF;
    assert_eq!(err(&b), r#"t.glb: byte 0: found "glT\xff", expected glTF (the magic number of binary glTF)"#);
    assert_eq!(
        err(b" {\"asset\":{\"version\":\"2.0\"}}"),
        "t.glb: byte 0: found JSON text, expected binary glTF starting with glTF (text .gltf files are not supported)"
    );
    let mut b = good.clone();
    b[4] = 1;
    assert_eq!(err(&b), "t.glb: byte 4: found version 1, expected version 2 (glTF 2.0)");
    let n = good.len();
    assert_eq!(
        err(&good[..n - 1]),
        format!("t.glb: found end of file, expected {n} bytes (the length in the binary glTF header), found {}", n - 1)
    );
    let mut b = good.clone();
    b[8..12].copy_from_slice(&16u32.to_le_bytes());
    assert_eq!(
        err(&b),
        "t.glb: byte 8: found a total length of 16 bytes, expected at least 20 (the header and a JSON chunk)"
    );
    // A shorter total length: the BIN chunk is cut off.
    let mut b = good.clone();
    b[8..12].copy_from_slice(&((n - 4) as u32).to_le_bytes());
    let json_len = u32_at(&good, 12) as usize;
    let bin_at = 20 + json_len + 8;
    assert_eq!(
        err(&b),
        format!(
            "t.glb: found end of file, expected the 116 bytes of chunk 1 (\"BIN\\x00\") at byte {bin_at}, found 112"
        )
    );
    // A chunk longer than the file.
    let mut b = good.clone();
    b[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(err(&b).starts_with(
        "t.glb: found end of file, expected the 4294967295 bytes of chunk 0 (\"JSON\") at byte 20, found "
    ));
    // Only part of a chunk header.
    let mut b = good[..20 + json_len + 4].to_vec();
    let len = b.len() as u32;
    b[8..12].copy_from_slice(&len.to_le_bytes());
    assert_eq!(
        err(&b),
        format!(
            "t.glb: found end of file, expected the 8-byte header of chunk 1 at byte {} (the file has {} bytes)",
            20 + json_len,
            b.len()
        )
    );
    let mut b = good.clone();
    b[16..20].copy_from_slice(b"JSOX");
    assert_eq!(err(&b), r#"t.glb: chunk 0 at byte 12: found chunk type "JSOX", expected JSON (the first chunk)"#);
    // Trailing bytes after the declared length: a warning.
    let mut b = good.clone();
    b.extend([0; 5]);
    assert_eq!(read(&b).warnings[0].to_string(), "ignored 5 bytes after the end of the data");
    // Unknown chunks are skipped.
    let mut b = good;
    b.extend(4u32.to_le_bytes());
    b.extend(b"XTRA");
    b.extend([1, 2, 3, 4]);
    let total = b.len() as u32;
    b[8..12].copy_from_slice(&total.to_le_bytes());
    assert!(read(&b).warnings.is_empty());
}

#[test]
fn json_errors_have_line_column_and_byte() {
    let (_, bin) = strip_quad();
    let b = glb("{\"asset\":{\"version\":\"2.0\"},\n\"meshes\":[{}]}", &bin);
    assert_eq!(err(&b), "t.glb: JSON chunk line 2, column 12 (byte 59): invalid glTF JSON: missing field `primitives`");
    assert_eq!(b[59], b'}');
    let e = err(&glb("{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"mesh\":\"a\"}]}", &bin));
    assert_eq!(
        e,
        r#"t.glb: JSON chunk line 1, column 47 (byte 66): invalid glTF JSON: invalid type: string "a", expected index into child of root"#
    );
    assert_eq!(&glb("{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"mesh\":\"a\"}]}", &bin)[66..67], b"\"");
    let e = err(&glb("{\"asset\":", &bin));
    assert_eq!(e, "t.glb: JSON chunk line 1, column 9 (byte 28): invalid glTF JSON: EOF while parsing a value");
}

#[test]
fn document_errors_name_the_json_path() {
    assert_eq!(
        json_err(r#""indices":3"#, r#""indices":9"#),
        "t.glb: meshes[0].primitives[0].indices: found accessor 9, expected an index below 4 (the number of accessors)"
    );
    assert_eq!(
        json_err(r#"{"bufferView":0,"componentType":5126"#, r#"{"bufferView":0,"componentType":5123"#),
        "t.glb: meshes[0].primitives[0].attributes.POSITION (accessors[0]): found u16 VEC3, expected f32 VEC3 (quantized positions are not supported)"
    );
    assert_eq!(
        json_err(r#""type":"SCALAR""#, r#""type":"SCALAR","normalized":true"#),
        "t.glb: meshes[0].primitives[0].indices (accessors[3]): found normalized u8 SCALAR, expected u8, u16 or u32 SCALAR"
    );
    assert_eq!(
        json_err(r#""componentType":5121"#, r#""componentType":5124"#),
        "t.glb: meshes[0].primitives[0].indices (accessors[3]): found an invalid componentType, expected 5120, 5121, 5122, 5123, 5125 or 5126"
    );
    assert_eq!(
        json_err(
            r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":4"#,
            r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":5"#
        ),
        "t.glb: meshes[0].primitives[0].attributes.NORMAL (accessors[1]): found 5 elements of 12 bytes every 24 bytes from byte 12 (up to byte 120), expected them within bufferViews[0] of 96 bytes"
    );
    assert_eq!(
        json_err(
            r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":4"#,
            r#"{"bufferView":0,"byteOffset":12,"componentType":5126,"count":18446744073709551615"#
        ),
        "t.glb: meshes[0].primitives[0].attributes.NORMAL (accessors[1]): found 18446744073709551615 elements of 12 bytes every 24 bytes from byte 12 (up to byte beyond 2⁶⁴), expected them within bufferViews[0] of 96 bytes"
    );
    assert_eq!(
        json_err(r#""byteOffset":112,"byteLength":4"#, r#""byteOffset":114,"byteLength":4"#),
        "t.glb: bufferViews[2]: found bytes 114..118 of buffers[0], which has 116 bytes, expected a view within its buffer"
    );
    assert_eq!(
        json_err(r#""byteStride":24"#, r#""byteStride":8"#),
        "t.glb: bufferViews[0].byteStride: found 8, expected at least 12 (the size of an element of accessors[0])"
    );
    assert_eq!(
        json_err(r#""byteLength":116}"#, r#""byteLength":120}"#),
        "t.glb: buffers[0].byteLength: found 120 bytes, expected at most 116 (the size of the BIN chunk)"
    );
    assert_eq!(
        json_err(r#""byteLength":116}"#, r#""byteLength":116,"uri":"quad.bin"}"#),
        r#"t.glb: buffers[0].uri: external buffer "quad.bin" is not supported: only .glb with embedded buffers (the BIN chunk or base64 data: URIs)"#
    );
    assert_eq!(
        json_err(r#""byteLength":116}"#, r#""byteLength":116,"uri":"data:,abc"}"#),
        r#"t.glb: buffers[0].uri: found a data URI "data:,…", expected a base64 one (data:…;base64,…)"#
    );
    assert_eq!(
        json_err(
            r#""type":"SCALAR"}"#,
            r#""type":"SCALAR","sparse":{"count":1,"indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":2}}}"#
        ),
        "t.glb: meshes[0].primitives[0].indices (accessors[3]): found a sparse accessor, expected a plain one (sparse accessors are not supported)"
    );
    assert_eq!(
        json_err(r#"{"bufferView":2,"#, "{"),
        "t.glb: meshes[0].primitives[0].indices (accessors[3]): found no bufferView, expected one (accessors of zeros are not supported)"
    );
    assert_eq!(
        json_err(r#""count":4,"type":"VEC2""#, r#""count":3,"type":"VEC2""#),
        "t.glb: meshes[0].primitives[0].attributes.TEXCOORD_0 (accessors[2]): found 3 elements, expected 4 (the count of POSITION)"
    );
    assert_eq!(
        json_err(r#""nodes":[0]"#, r#""nodes":[1]"#),
        "t.glb: scenes[0].nodes[0]: found node 1, expected an index below 1 (the number of nodes)"
    );
    assert_eq!(
        json_err(r#"{"mesh":0,"translation":[10,0,0]}"#, r#"{"mesh":0,"children":[0]}"#),
        "t.glb: nodes[0].children[0]: found node 0 a second time, expected every node at most once (nodes form trees)"
    );
    assert_eq!(
        json_err(r#"{"mesh":0,"#, r#"{"mesh":3,"#),
        "t.glb: nodes[0].mesh: found mesh 3, expected an index below 1 (the number of meshes)"
    );
    assert_eq!(
        json_err(r#""scene":0"#, r#""scene":2"#),
        "t.glb: scene: found scene 2, expected an index below 1 (the number of scenes)"
    );
    assert_eq!(
        json_err(
            r#""asset":{"version":"2.0"}"#,
            r#""asset":{"version":"2.0"},"extensionsRequired":["KHR_draco_mesh_compression"]"#
        ),
        r#"t.glb: extensionsRequired[0]: found "KHR_draco_mesh_compression", expected uncompressed geometry (compressed meshes are not supported)"#
    );
    // No BIN chunk for the buffer without uri.
    let (json, _) = strip_quad();
    assert_eq!(
        err(&glb(&json, &[])),
        "t.glb: buffers[0]: found a buffer without uri and no BIN chunk, expected a BIN chunk holding it"
    );
}

#[test]
fn index_out_of_range_names_primitive_and_index() {
    let (json, mut bin) = strip_quad();
    bin[114] = 7;
    assert_eq!(
        err(&glb(&json, &bin)),
        "t.glb: meshes[0].primitives[0].indices (accessors[3]): found index 7 at element 2, expected an index below 4 (the count of POSITION)"
    );
}

#[test]
fn truncations_and_bit_flips_never_panic() {
    let (json, bin) = strip_quad();
    let good = glb(&json, &bin);
    for n in 0..good.len() {
        let _ = parse_glb(&good[..n], "t.glb");
        // Truncated, with the header's length fixed up: chunk errors, not header errors.
        let mut b = good[..n].to_vec();
        if n >= 12 {
            b[8..12].copy_from_slice(&(n as u32).to_le_bytes());
            let _ = parse_glb(&b, "t.glb");
        }
    }
    let mut ok = 0;
    for i in 0..good.len() * 8 {
        let mut b = good.clone();
        b[i / 8] ^= 1 << (i % 8);
        ok += usize::from(parse_glb(&b, "t.glb").is_ok());
    }
    // Flips in vertex data and JSON whitespace still read.
    assert!(ok > 0);
}
