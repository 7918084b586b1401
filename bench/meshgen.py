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
    meshgen.py nonmanifold DIR            the non-manifold and degenerate meshes of
                                          nonmanifold_meshes() as DIR/NAME.in.obj
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


def _jitter(k, scale=0.05):
    """A small deterministic offset for vertex k, so that distinct vertices of the
    non-manifold meshes never coincide (a golden-ratio sequence per axis)."""
    return tuple(scale * (((k + 1) * c) % 1.0 - 0.5) for c in (0.6180339887, 0.7548776662, 0.5698402910))


def _jittered(points):
    return [tuple(x + d for x, d in zip(p, _jitter(k))) for k, p in enumerate(points)]


def _fins(nfins, nspine, flip_odd=True):
    """Fins around a spine on the z axis: spine vertices 0..nspine-1 at z = 0, 1, ..; fin k is a
    strip of triangles out to a row at radius 1 and angle 2*pi*k/nfins. Every spine edge is used
    by nfins triangles; odd fins are wound the other way when flip_odd."""
    pos = [(0.0, 0.0, float(i)) for i in range(nspine)]
    tris = []
    for k in range(nfins):
        a = 2 * math.pi * k / nfins
        row = len(pos)
        pos += [(math.cos(a), math.sin(a), float(i) + 0.2 * math.sin(3 * a)) for i in range(nspine)]
        for i in range(nspine - 1):
            s0, s1, f0, f1 = i, i + 1, row + i, row + i + 1
            quad = [(s0, s1, f1), (s0, f1, f0)]
            if flip_odd and k % 2:
                quad = [t[::-1] for t in quad]
            tris += quad
    return _jittered(pos), tris


def _fan(center, ring, z, radius, n, start, phase=0.0, down=False):
    """A closed fan (cone) of n triangles around vertex `center` over ring vertices start..start+n-1."""
    pts = [(radius * math.cos(phase + 2 * math.pi * i / n), radius * math.sin(phase + 2 * math.pi * i / n), z)
           for i in range(n)]
    tris = [(center, start + i, start + (i + 1) % n) for i in range(n)]
    if down:
        tris = [t[::-1] for t in tris]
    return pts, tris


def nonmanifold_meshes():
    """The non-manifold and degenerate test meshes: name -> (comment, positions, faces, schemes),
    schemes a subset of "loop" (all triangles) and "catmark"."""
    out = {}
    # an edge shared by 3 triangles, two spine edges: the middle spine vertex is an interior
    # non-manifold crease (more faces than edges, no boundary edge)
    p, t = _fins(3, 3)
    out["fins3"] = ("3 fins of 4 triangles on a spine of 2 edges (each used by 3 faces)", p, t, ("loop", "catmark"))
    p, t = _fins(4, 3, flip_odd=False)
    out["fins4"] = ("4 fins on a spine of 2 edges, all wound alike (each spine edge used by 4 faces)", p, t,
                    ("loop", "catmark"))
    # 100 triangles on one edge
    pos = [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0)]
    tris = []
    for k in range(100):
        a = 2 * math.pi * k / 100
        pos.append((math.cos(a), math.sin(a), 0.5 + 0.3 * math.sin(5 * a)))
        tris.append((0, 1, 2 + k) if k % 2 == 0 else (1, 0, 2 + k))
    out["edge100"] = ("100 triangles on the edge 1-2, alternately wound", _jittered(pos), tris, ("loop", "catmark"))
    # two cones touching at their apex (a vertex with two fans), and a bowtie of two triangles
    p1, t1 = _fan(0, None, 1.0, 1.0, 5, 1)
    p2, t2 = _fan(0, None, -1.0, 0.8, 6, 6, phase=0.3, down=True)
    pos = [(0.0, 0.0, 0.0)] + p1 + p2
    bow = len(pos)
    pos += [(2.0, 0.0, 0.0), (3.0, 1.0, 0.2), (3.0, -1.0, 0.1), (1.0, 1.0, -0.2), (1.0, -1.0, 0.3)]
    tris = t1 + t2 + [(bow, bow + 2, bow + 1), (bow, bow + 3, bow + 4)]
    out["cones"] = ("two cones of 5 and 6 triangles touching at their apex (vertex 1), and a bowtie of two "
                    "triangles at vertex 12", _jittered(pos), tris, ("loop", "catmark"))
    # back-to-back triangles: a pillow of two (interior vertices of valence 2), and one glued to an
    # open grid along an edge (that edge then has 3 faces)
    pos = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.1), (0.3, 0.9, -0.1)]
    tris = [(0, 1, 2), (0, 2, 1)]
    gp = [(2.0 + i * 0.5, j * 0.5, 0.1 * math.sin(i + 2 * j)) for j in range(3) for i in range(3)]
    g = lambda i, j: 3 + j * 3 + i
    pos += gp
    for j in range(2):
        for i in range(2):
            tris += [(g(i, j), g(i + 1, j), g(i + 1, j + 1)), (g(i, j), g(i + 1, j + 1), g(i, j + 1))]
    apex = len(pos)
    pos.append((2.6, 0.4, 0.8))
    tris += [(g(1, 1), g(2, 1), apex), (g(1, 1), apex, g(2, 1))]
    out["backtoback"] = ("a pillow of two back-to-back triangles (valence-2 interior vertices); an open grid with "
                         "two back-to-back triangles on one of its edges", _jittered(pos), tris, ("loop", "catmark"))
    # the pillow alone is manifold, but each level of it has two triangles on the same three
    # vertices, so two edges between the same two vertices
    out["pillow"] = ("two back-to-back triangles alone: manifold, valence-2 interior vertices",
                     _jittered([(0.0, 0.0, 0.0), (1.0, 0.0, 0.1), (0.3, 0.9, -0.1)]), [(0, 1, 2), (0, 2, 1)],
                     ("loop", "catmark"))
    # a grid with one triangle wound the other way (a fold-over: its edges are used twice the same way)
    # and degenerate triangles that repeat a vertex
    pos, tris = grid(4, 4)
    tris = [tuple(t) for t in tris]
    g = lambda i, j: j * 5 + i
    tris[11] = tris[11][::-1]
    out["foldgrid"] = ("open 4 x 4 grid of 32 triangles, triangle 12 wound the other way", _jittered(pos), tris,
                       ("loop", "catmark"))
    tris = [t for t in tris]
    tris[11] = tris[11][::-1]
    tris += [(g(2, 2), g(2, 2), g(3, 2)), (g(1, 3), g(1, 3), g(1, 3)), (g(3, 3), g(4, 4), g(3, 3))]
    out["degenerate"] = ("open 4 x 4 grid of 32 triangles and three degenerate ones: 13 13 14 (on a grid edge), "
                         "17 17 17, 19 25 19", _jittered(pos), tris, ("loop", "catmark"))
    # Catmull-Clark: a cube with two quad poles (faces a b a c) and a quad that repeats a vertex
    cube = [((i & 1) * 2 - 1, ((i >> 1) & 1) * 2 - 1, (i >> 2) * 2 - 1) for i in range(8)]
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    pos = [tuple(0.9 * x for x in c) for c in cube] + [(0.0, 0.0, 1.6), (1.6, 0.0, 0.0)]
    faces += [[4, 8, 4, 5], [8, 5, 8, 7], [3, 9, 3, 7], [1, 9, 1, 1]]
    out["poles"] = ("cube with quad poles 5 9 5 6 and 9 6 9 8 on its top, 4 10 4 8 on a side, and the quad 2 10 2 2",
                    _jittered(pos), faces, ("catmark",))
    # Catmull-Clark: valence-2 interior vertices: a quad pillow, and a cube with a vertex inserted on
    # two of its edges (two pentagons each)
    pos = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.1), (1.1, 1.0, 0.0), (-0.1, 0.9, 0.2)]
    faces = [[0, 1, 2, 3], [0, 3, 2, 1]]
    off = len(pos)
    pos += [(3.0 + x, y, z) for (x, y, z) in cube] + [(3.0, -1.0, -1.0), (4.0, 0.0, 1.0)]
    cf = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    cf = [[v + off for v in f] for f in cf]
    m0, m1 = off + 8, off + 9
    cf[0] = [off + 0, off + 2, off + 3, off + 1, m0]      # edge 1-0 gets m0
    cf[2] = [off + 0, m0, off + 1, off + 5, off + 4]
    cf[1] = [off + 4, off + 5, m1, off + 7, off + 6]      # edge 5-7 gets m1
    cf[5] = [off + 1, off + 3, off + 7, m1, off + 5]
    faces += cf
    out["valence2"] = ("a pillow of two back-to-back quads (valence-2 interior vertices) and a cube with a vertex "
                       "inserted on two edges (valence-2, faces of 5 corners)", _jittered(pos), faces, ("catmark",))
    # Catmull-Clark: two cubes sharing an edge (4 faces on it), a third touching at a vertex, a triangle fin
    pos, faces = [], []
    cube_faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    for (dx, dy, dz) in [(0, 0, 0), (2, 2, 0), (-2, 0, 2)]:
        o = len(pos)
        pos += [(x + dx, y + dy, z + dz) for (x, y, z) in cube]
        faces += [[v + o for v in f] for f in cube_faces]
    # cube 2 moved so that its edge 0-4 is cube 1's edge 3-7, cube 3 so that its vertex 3 is cube 1's vertex 6
    remap = {8: 3, 12: 7}
    remap3 = {16 + 3: 6}
    faces = [[remap.get(v, remap3.get(v, v)) for v in f] for f in faces]
    used = sorted({v for f in faces for v in f})
    new = {v: k for k, v in enumerate(used)}
    pos = [pos[v] for v in used]
    faces = [[new[v] for v in f] for f in faces]
    fin = len(pos)
    pos += [(-2.0, -2.0, -0.5)]
    faces.append([new[0], new[1], fin])
    out["cubes"] = ("three cubes: two sharing an edge (4 faces on it), one touching the first at a vertex; and a "
                    "triangle fin on the first cube's edge 1-2 (3 faces on it)", _jittered(pos), faces, ("catmark",))
    return out


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
    elif kind == "nonmanifold" and len(argv) == 3:
        for name, (comment, p, faces, schemes) in nonmanifold_meshes().items():
            write_input(argv[2], name, f"{comment}; for {' and '.join(schemes)} (bench/meshgen.py nonmanifold)",
                        p, faces)
        return
    else:
        sys.exit(__doc__)
    write_obj(out, p, t, comment)


if __name__ == "__main__":
    main(sys.argv)
