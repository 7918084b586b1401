#!/usr/bin/env python3
"""Deterministic meshes for the subdivision comparisons (bench/compare_loop.sh) and the
reference data (bench/make_loop_references.sh): triangles, and quads for Catmull-Clark. Standard
library only.

    meshgen.py torus NU NV OUT.obj        2*NU*NV triangles, closed (genus 1), all valence 6
    meshgen.py quadtorus NU NV OUT.obj    NU*NV quads, closed (genus 1), all valence 4
    meshgen.py icosphere K OUT.obj        20*4^K triangles, closed (genus 0), valences 5 and 6
    meshgen.py grid NX NY OUT.obj         2*NX*NY triangles, open (one boundary loop, 4 corners)
    meshgen.py copy IN.obj OUT.obj        the `v` and `f` lines of IN (first three coordinates,
                                          vertex index of each corner), everything else dropped
    meshgen.py crop IN.obj AXIS MAX OUT.obj
                                          the triangles of IN whose three vertices have
                                          coordinate AXIS (x, y or z) below MAX, and the vertices
                                          they use (in their order in IN)

Every mesh is written as OBJ with `v x y z` lines (`%.17g`, so they read back exactly) and
`f a b c` lines (`f a b c d` for quads; 1-based), counter-clockwise seen from the front (outside). No other lines
except a leading comment saying how the file was made.

Shapes:
- torus: R = 1, r = 0.4, vertex (i, j) at u = 2*pi*i/NU around +z and v = 2*pi*j/NV around
  the tube, index i*NV + j; quad (i, j) (i+1, j) (i+1, j+1) (i, j+1) split along its
  (i, j)-(i+1, j+1) diagonal. quadtorus: the same vertices, quad (i, j) (i+1, j) (i+1, j+1)
  (i, j+1) kept whole.
- icosphere: the icosahedron (+-1, +-phi, 0 and cyclic, scaled to the unit sphere), each level
  splitting every triangle into four at its edge midpoints, which are pushed out to the unit
  sphere. Vertex order: the 12 corners, then the new vertices in order of creation.
- grid: vertex (i, j), i = 0..NX, j = 0..NY, index j*(NX+1) + i, at
  (i/NY, j/NY, 0.2*sin(2x + 1)*cos(3y)); square (i, j) split along its (i, j)-(i+1, j+1)
  diagonal. Corners (NX, 0) and (0, NY) belong to one triangle, (0, 0) and (NX, NY) to two.
"""

import math
import sys


def write_obj(path, positions, triangles, comment):
    with open(path, "w", encoding="ascii", newline="\n") as out:
        for line in comment.splitlines():
            out.write(f"# {line}\n")
        for p in positions:
            out.write("v %.17g %.17g %.17g\n" % (p[0], p[1], p[2]))
        for t in triangles:
            out.write("f " + " ".join(str(v + 1) for v in t) + "\n")


def write_input(folder, name, comment, positions, faces):
    """`folder/name.in.obj` for the reference scripts (bench/make_*_references.sh): a comment line,
    `v` lines with Python's shortest round-trip form, `f` lines of any size (0-based in `faces`)."""
    with open(f"{folder}/{name}.in.obj", "w") as f:
        f.write(f"# {comment}\n")
        for p in positions:
            f.write("v %s %s %s\n" % tuple(repr(float(x)) for x in p))
        for face in faces:
            f.write("f " + " ".join(str(v + 1) for v in face) + "\n")


def read_obj(path):
    """Positions and faces (0-based corner vertex lists) of the `v` and `f` lines."""
    positions, faces = [], []
    with open(path, encoding="latin-1") as f:
        for line in f:
            tok = line.split()
            if not tok:
                continue
            if tok[0] == "v":
                positions.append(tuple(float(x) for x in tok[1:4]))
            elif tok[0] == "f":
                face = []
                for c in tok[1:]:
                    k = int(c.split("/")[0])
                    face.append(k - 1 if k > 0 else len(positions) + k)
                faces.append(face)
    return positions, faces


def torus(nu, nv, big_r=1.0, small_r=0.4, quads=False):
    positions = []
    for i in range(nu):
        u = 2.0 * math.pi * i / nu
        for j in range(nv):
            v = 2.0 * math.pi * j / nv
            w = big_r + small_r * math.cos(v)
            positions.append((w * math.cos(u), w * math.sin(u), small_r * math.sin(v)))

    def idx(i, j):
        return (i % nu) * nv + (j % nv)

    triangles = []
    for i in range(nu):
        for j in range(nv):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            if quads:
                triangles.append((a, b, c, d))
            else:
                triangles.append((a, b, c))
                triangles.append((a, c, d))
    return positions, triangles


def icosphere(levels):
    phi = (1.0 + math.sqrt(5.0)) / 2.0
    raw = [(-1, phi, 0), (1, phi, 0), (-1, -phi, 0), (1, -phi, 0),
           (0, -1, phi), (0, 1, phi), (0, -1, -phi), (0, 1, -phi),
           (phi, 0, -1), (phi, 0, 1), (-phi, 0, -1), (-phi, 0, 1)]
    norm = math.sqrt(1.0 + phi * phi)
    positions = [(x / norm, y / norm, z / norm) for x, y, z in raw]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
                 (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
                 (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
                 (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mids = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in mids:
                pa, pb = positions[a], positions[b]
                m = [(pa[k] + pb[k]) / 2.0 for k in range(3)]
                n = math.sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2])
                positions.append((m[0] / n, m[1] / n, m[2] / n))
                mids[key] = len(positions) - 1
            return mids[key]

        new = []
        for a, b, c in triangles:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = new
    # Outward orientation check (the table above is counter-clockwise seen from outside).
    for a, b, c in triangles[:1]:
        pa, pb, pc = positions[a], positions[b], positions[c]
        e1 = [pb[k] - pa[k] for k in range(3)]
        e2 = [pc[k] - pa[k] for k in range(3)]
        n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
        assert sum(n[k] * pa[k] for k in range(3)) > 0.0
    return positions, triangles


def grid(nx, ny):
    positions = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y = i / ny, j / ny
            positions.append((x, y, 0.2 * math.sin(2.0 * x + 1.0) * math.cos(3.0 * y)))

    def idx(i, j):
        return j * (nx + 1) + i

    triangles = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            triangles.append((a, b, c))
            triangles.append((a, c, d))
    return positions, triangles


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    kind = argv[1]
    if kind == "torus" and len(argv) == 5:
        nu, nv = int(argv[2]), int(argv[3])
        p, t = torus(nu, nv)
        comment = f"torus R=1 r=0.4, {nu} x {nv} quads split into {len(t)} triangles (bench/meshgen.py torus {nu} {nv})"
        out = argv[4]
    elif kind == "quadtorus" and len(argv) == 5:
        nu, nv = int(argv[2]), int(argv[3])
        p, t = torus(nu, nv, quads=True)
        comment = f"torus R=1 r=0.4, {nu} x {nv} = {len(t)} quads (bench/meshgen.py quadtorus {nu} {nv})"
        out = argv[4]
    elif kind == "icosphere" and len(argv) == 4:
        k = int(argv[2])
        p, t = icosphere(k)
        comment = f"unit icosphere, icosahedron split {k} times, {len(t)} triangles (bench/meshgen.py icosphere {k})"
        out = argv[3]
    elif kind == "grid" and len(argv) == 5:
        nx, ny = int(argv[2]), int(argv[3])
        p, t = grid(nx, ny)
        comment = (f"open grid {nx} x {ny} squares split into {len(t)} triangles, "
                   f"z = 0.2 sin(2x+1) cos(3y) (bench/meshgen.py grid {nx} {ny})")
        out = argv[4]
    elif kind == "copy" and len(argv) == 4:
        p, faces = read_obj(argv[2])
        if any(len(f) != 3 for f in faces):
            sys.exit(f"{argv[2]}: not a triangle mesh")
        t = [tuple(f) for f in faces]
        name = argv[2].replace("\\", "/").split("/")[-1]
        comment = f"v and f lines of {name}, {len(t)} triangles, rewritten with %.17g (bench/meshgen.py copy)"
        out = argv[3]
    elif kind == "crop" and len(argv) == 6:
        p, faces = read_obj(argv[2])
        axis, limit = "xyz".index(argv[3]), float(argv[4])
        kept = [f for f in faces if len(f) == 3 and all(p[v][axis] < limit for v in f)]
        used = sorted({v for f in kept for v in f})
        new_index = {v: k for k, v in enumerate(used)}
        t = [tuple(new_index[v] for v in f) for f in kept]
        p = [p[v] for v in used]
        name = argv[2].replace("\\", "/").split("/")[-1]
        comment = (f"the {len(t)} triangles of {name} with {argv[3]} < {argv[4]} at all three corners, "
                   f"rewritten with %.17g (bench/meshgen.py crop)")
        out = argv[5]
    else:
        sys.exit(__doc__)
    write_obj(out, p, t, comment)


if __name__ == "__main__":
    main(sys.argv)
