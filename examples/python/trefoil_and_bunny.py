"""splinekit from Python, step by step: the gallery's trefoil-knot tube, then the bunny
subdivided with creases on its sharp edges.

    pip install ./crates/splinekit-py      # from the repository's root
    python examples/python/trefoil_and_bunny.py [OUT_DIR]

Writes trefoil-tube.glb, bunny-creased.obj and bunny-smooth.obj to OUT_DIR (default: the
current folder). Every step is a numpy call or a splinekit call: no loop over points.
"""

import sys
from pathlib import Path

import numpy as np

import splinekit as sk

ROOT = Path(__file__).resolve().parents[2]
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
out.mkdir(parents=True, exist_ok=True)

# %% 1. The trefoil tube of examples/trefoil-knot.swp, built in Python.
# A flattened closed B-spline as the cross-section ...
ellipse = sk.Curve.bspline(
    [[0.35, 0], [0.25, 0.1], [0, 0.14], [-0.25, 0.1], [-0.35, 0], [-0.25, -0.1], [0, -0.14], [0.25, -0.1]],
    closed=True,
    steps=6,
)
# ... carried along a trefoil knot, turning by 720° on the way round (two full turns, so the
# closed tube meets itself without a seam).
knot = sk.Curve.trefoil(1.0, steps=240)
print(f"knot: length {knot.arclen():.9f}, curvature {knot.curvature(0.0):.6f} at the start")

# Rotation-minimizing frames (the default): the tube turns by the 720° asked for and no more.
vertices, faces = sk.sweep(ellipse, knot, twist=720.0)
print(f"trefoil tube: {len(vertices)} vertices, {len(faces)} triangles")

# The same surface from the SWP file (whose frames are rotation-minimizing along a 3D path):
# the same function makes both, so the meshes are equal.
(tube_from_file,) = sk.read_swp(ROOT / "examples" / "trefoil-knot.swp").surfaces.values()
file_vertices, file_faces = tube_from_file.mesh()
assert np.array_equal(file_faces, faces) and np.allclose(file_vertices, vertices, rtol=0, atol=1e-12)

# The course's sequential frames instead: close to rotation-minimizing, but they drift with
# the knot's sampling.
seq_vertices, seq_faces = sk.sweep(ellipse, knot, twist=720.0, frames="sequential")
print(f"sequential frames move the tube's vertices by up to {np.abs(seq_vertices - vertices).max():.3f}")
sk.write_mesh(out / "trefoil-tube.glb", vertices, faces)

# Equally spaced rings, by arc length: 12 frames at constant speed along the knot.
s = np.linspace(0.0, knot.arclen(), 12, endpoint=False)
T, N, B = knot.frames(knot.inv_arclen(s), kind="rmf")
print("frame 0:", np.round(T[0], 6), np.round(N[0], 6), np.round(B[0], 6))

# %% 2. The Stanford bunny (4968 triangles), Loop-subdivided with creases.
vertices, faces = sk.read_mesh(ROOT / "crates" / "splinekit-io" / "tests" / "data" / "obj" / "clean" / "bunny.obj")
print(f"bunny: {len(vertices)} vertices, {len(faces)} triangles")

# Edges whose two faces meet at more than 60°: the sharp ones, found with numpy.
a, b, c = (vertices[faces[:, i]] for i in range(3))
normals = np.cross(b - a, c - a)
normals /= np.linalg.norm(normals, axis=1, keepdims=True)
half_edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
owner = np.tile(np.arange(len(faces)), 3)
key = np.sort(half_edges, axis=1)
order = np.lexsort(key.T[::-1])
key, owner = key[order], owner[order]
pair = np.all(key[1:] == key[:-1], axis=1)  # consecutive half-edges of one interior edge
e0, e1 = np.nonzero(pair)[0], np.nonzero(pair)[0] + 1
cosine = np.einsum("ij,ij->i", normals[owner[e0]], normals[owner[e1]])
sharp = key[e0][cosine < np.cos(np.radians(60))]
print(f"{len(sharp)} sharp edges (dihedral angle over 60°) made creases of sharpness 3")

creases = (sharp, np.full(len(sharp), 3.0))  # semi-sharp: sharp for three levels, then smoothed
fine_v, fine_f = sk.subdivide(vertices, faces, 2, scheme="loop", creases=creases)
smooth_v, smooth_f = sk.subdivide(vertices, faces, 2, scheme="loop")
print(f"subdivided twice: {len(fine_v)} vertices, {len(fine_f)} triangles")
moved = np.linalg.norm(fine_v - smooth_v, axis=1)
print(f"the creases keep vertices up to {moved.max():.2e} from where smooth Loop puts them")

sk.write_mesh(out / "bunny-creased.obj", fine_v, fine_f)
sk.write_mesh(out / "bunny-smooth.obj", smooth_v, smooth_f)

# Normals for shading: those of the Loop limit surface of the subdivided mesh.
limit_n = sk.limit_normals(fine_v, fine_f)
print("limit normals:", limit_n.shape, "unit:", bool(np.allclose(np.linalg.norm(limit_n, axis=1), 1)))
