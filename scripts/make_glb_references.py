#!/usr/bin/env python3
"""Regenerates the binary glTF reference files of the .glb reader's tests.

Writes crates/splinekit-io/tests/data/glb/:

- trimesh_scene.glb: a small scene written by trimesh, an independent glTF writer: an
  icosphere (radius 0.5, 42 vertices, 80 triangles) on an untransformed node, and a
  1 x 2 x 3 box (8 vertices, 12 triangles) on a node with a matrix (rotation, non-uniform
  scale, translation) under a parent node. Both meshes have normals and UVs. The file is
  then repacked (see `repack`) so that it also exercises what trimesh itself never writes:
  u16 indices, the sphere's positions and normals interleaved in one buffer view with a
  byteStride of 24, and the parent's transform given as translation + rotation (TRS)
  instead of a matrix.
- trimesh_scene.json: what trimesh sees when it reads that file back: vertex and triangle
  counts, the bounding box of the transformed scene, and for each mesh node its world
  matrix and first vertex (position, normal and UV, transformed) and first triangle.

The Rust test `a_glb_written_by_trimesh_reads_as_trimesh_sees_it` (crates/splinekit-io/
tests/mesh_read.rs) checks the reader against these values.

Not run by CI. To regenerate (trimesh 5.2.0 made the committed files):

    python3 -m venv target/venv
    target/venv/bin/pip install trimesh==5.2.0 numpy pillow
    target/venv/bin/python scripts/make_glb_references.py
"""

import json
import logging
import pathlib
import struct

import numpy as np
import trimesh
from trimesh import transformations as tf

OUT = pathlib.Path(__file__).resolve().parent.parent / "crates/splinekit-io/tests/data/glb"
NAME = "trimesh_scene"

# Without scipy, trimesh logs a traceback when it computes vertex normals (it falls back to
# a dense computation, with the same result).
logging.getLogger("trimesh").setLevel(logging.ERROR)


def make_scene():
    """The scene: an untransformed icosphere and a transformed box under a parent node."""
    sphere = trimesh.creation.icosphere(subdivisions=1, radius=0.5)
    sphere.visual = trimesh.visual.TextureVisuals(uv=sphere.vertices[:, :2] + 0.5)
    box = trimesh.creation.box(extents=[1.0, 2.0, 3.0])
    corner = box.vertices[:, :2].min(axis=0)
    box.visual = trimesh.visual.TextureVisuals(uv=(box.vertices[:, :2] - corner) / np.ptp(box.vertices[:, :2], axis=0))

    scene = trimesh.Scene()
    scene.add_geometry(sphere, node_name="sphere", geom_name="sphere")
    base = tf.concatenate_matrices(tf.translation_matrix([0, 3, 0]), tf.rotation_matrix(np.pi / 2, [0, 0, 1]))
    scene.graph.update(frame_from=scene.graph.base_frame, frame_to="base", matrix=base)
    box_matrix = tf.concatenate_matrices(
        tf.translation_matrix([1, 0, 0]), tf.rotation_matrix(np.pi / 6, [1, 1, 0]), np.diag([1.0, 2.0, 0.5, 1.0])
    )
    scene.add_geometry(box, node_name="box", geom_name="box", parent_node_name="base", transform=box_matrix)
    return scene


def split_glb(data):
    """The JSON document and the BIN chunk of a .glb."""
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert magic == b"glTF" and version == 2 and length == len(data)
    json_length, kind = struct.unpack_from("<I4s", data, 12)
    assert kind == b"JSON"
    tree = json.loads(data[20 : 20 + json_length])
    at = 20 + json_length
    bin_length, kind = struct.unpack_from("<I4s", data, at)
    assert kind == b"BIN\0"
    return tree, data[at + 8 : at + 8 + bin_length]


def join_glb(tree, bin_data):
    """A .glb of a JSON document and a BIN chunk, both padded to 4 bytes."""
    text = json.dumps(tree, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    bin_data = bytes(bin_data) + b"\0" * (-len(bin_data) % 4)
    total = 12 + 8 + len(text) + 8 + len(bin_data)
    return (
        struct.pack("<4sII", b"glTF", 2, total)
        + struct.pack("<I4s", len(text), b"JSON")
        + text
        + struct.pack("<I4s", len(bin_data), b"BIN\0")
        + bin_data
    )


def repack(data):
    """Rewrites trimesh's .glb: u16 indices, the first mesh's positions and normals
    interleaved (byteStride 24), and every node transform without scale given as TRS."""
    tree, old = split_glb(data)
    views, accessors = tree["bufferViews"], tree["accessors"]

    def accessor_bytes(a):
        view = views[a["bufferView"]]
        assert "byteStride" not in view
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        return old[start : start + view["byteLength"] - a.get("byteOffset", 0)]

    new = bytearray()
    new_views = []

    def add_view(payload, stride=None):
        new.extend(b"\0" * (-len(new) % 4))
        view = {"buffer": 0, "byteOffset": len(new), "byteLength": len(payload)}
        if stride:
            view["byteStride"] = stride
        new.extend(payload)
        new_views.append(view)
        return len(new_views) - 1

    done = set()
    for m, mesh in enumerate(tree["meshes"]):
        for primitive in mesh["primitives"]:
            i = primitive["indices"]
            if i not in done:
                a = accessors[i]
                assert a["componentType"] == 5125
                values = np.frombuffer(accessor_bytes(a), dtype="<u4", count=a["count"])
                assert values.max() < 65536
                a["bufferView"] = add_view(values.astype("<u2").tobytes())
                a["componentType"] = 5123
                a.pop("byteOffset", None)
                done.add(i)
            attributes = primitive["attributes"]
            p, n = attributes["POSITION"], attributes.get("NORMAL")
            if m == 0 and n is not None and p not in done and n not in done:
                count = accessors[p]["count"]
                pos = np.frombuffer(accessor_bytes(accessors[p]), dtype="<f4", count=3 * count).reshape(-1, 3)
                nor = np.frombuffer(accessor_bytes(accessors[n]), dtype="<f4", count=3 * count).reshape(-1, 3)
                view = add_view(np.hstack([pos, nor]).astype("<f4").tobytes(), stride=24)
                accessors[p].update(bufferView=view, byteOffset=0)
                accessors[n].update(bufferView=view, byteOffset=12)
                done.update([p, n])
    # Everything else (the other attributes, trimesh's default texture image) keeps its
    # bytes, in a view of its own.
    old_to_new = {}
    for i, a in enumerate(accessors):
        if i not in done:
            a["bufferView"] = add_view(accessor_bytes(a)[: a["count"] * component_bytes(a)])
            a["byteOffset"] = 0
    for image in tree.get("images", []):
        v = image["bufferView"]
        if v not in old_to_new:
            view = views[v]
            start = view.get("byteOffset", 0)
            old_to_new[v] = add_view(old[start : start + view["byteLength"]])
        image["bufferView"] = old_to_new[v]
    tree["bufferViews"] = new_views
    tree["buffers"] = [{"byteLength": len(new)}]

    for node in tree["nodes"]:
        if "matrix" in node:
            matrix = np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
            rotation = matrix[:3, :3]
            if np.allclose(rotation @ rotation.T, np.eye(3)):
                w, x, y, z = tf.quaternion_from_matrix(matrix)
                del node["matrix"]
                node["translation"] = matrix[:3, 3].tolist()
                node["rotation"] = [x, y, z, w]
    return join_glb(tree, new)


def component_bytes(a):
    """Bytes per element of a tightly packed accessor."""
    size = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}[a["componentType"]]
    return size * {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[a["type"]]


def rounded(values):
    return [float(f"{float(x):.9g}") for x in np.asarray(values).ravel()]


def references(path):
    """What trimesh sees in the file: counts, bounds, and per mesh node its first vertex and
    triangle, transformed to world coordinates."""
    scene = trimesh.load(path, force="scene", process=False, maintain_order=True)
    tree, _ = split_glb(path.read_bytes())
    nodes = []
    all_vertices = []
    triangles = 0
    for node_name in scene.graph.nodes_geometry:
        matrix, geometry_name = scene.graph[node_name]
        mesh = scene.geometry[geometry_name]
        world = trimesh.transform_points(mesh.vertices, matrix)
        all_vertices.append(world)
        triangles += len(mesh.faces)
        # Normals transform by the inverse transpose of the linear part.
        normal = np.linalg.inv(matrix[:3, :3]).T @ mesh.vertex_normals[0]
        nodes.append(
            {
                "node": node_name,
                "mesh": geometry_name,
                "vertices": len(mesh.vertices),
                "triangles": len(mesh.faces),
                "world_matrix": rounded(matrix),
                "first_vertex": rounded(world[0]),
                "first_normal": rounded(normal / np.linalg.norm(normal)),
                "first_uv": rounded(mesh.visual.uv[0]),
                "first_triangle": [rounded(world[v]) for v in mesh.faces[0]],
            }
        )
    vertices = np.vstack(all_vertices)
    index_types = sorted({tree["accessors"][p["indices"]]["componentType"] for m in tree["meshes"] for p in m["primitives"]})
    return {
        "file": path.name,
        "made_by": f"trimesh {trimesh.__version__} (scripts/make_glb_references.py)",
        "index_component_types": index_types,
        "vertices": len(vertices),
        "triangles": triangles,
        "bounds": [rounded(vertices.min(axis=0)), rounded(vertices.max(axis=0))],
        "nodes": sorted(nodes, key=lambda n: n["node"]),
    }


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    data = trimesh.exchange.gltf.export_glb(make_scene(), include_normals=True)
    path = OUT / f"{NAME}.glb"
    path.write_bytes(repack(data))
    refs = references(path)
    (OUT / f"{NAME}.json").write_text(json.dumps(refs, indent=1) + "\n")
    print(f"wrote {path} ({path.stat().st_size} bytes)")
    print(json.dumps({k: refs[k] for k in ["vertices", "triangles", "bounds", "index_component_types"]}))
    for node in refs["nodes"]:
        print(node["node"], "first vertex", node["first_vertex"], "normal", node["first_normal"], "uv", node["first_uv"])


if __name__ == "__main__":
    main()
