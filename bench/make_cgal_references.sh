#!/usr/bin/env bash
# √3 and Doo-Sabin reference data for crates/splinekit/tests/subdivision_reference.rs: writes
# small input meshes (deterministic, %.17g) and CGAL's subdivision of each into
# crates/splinekit/tests/data/cgal/, with bench/drivers/cgal_sqrt3_doosabin.cpp:
#   √3 (Sqrt3_subdivision, levels 1 to 3, so that the boundary rule of every second level is
#   met once and the level after it too): a tetrahedron and an icosahedron (closed), an open
#   3 x 3 triangle grid and an icosahedron without the faces of one vertex (boundaries);
#   Doo-Sabin (DooSabin_subdivision, levels 1 and 2; the cube also 3): a cube, a pentagonal
#   prism of pentagons, quads and triangles, the icosahedron (closed), an open 4 x 4 quad grid
#   and the open triangle grid (boundaries); the cube, prism and quad grid are the inputs of
#   bench/make_catmark_references.sh (tests/data/catmark/), run that first.
# Needs libcgal-dev and g++ (bench/install_peers.sh); CI does not run it. Running it twice gives
# identical bytes.
set -euo pipefail
source "$(dirname "$0")/references_common.sh" cgal
data="$tests/cgal"
python3 - "$data" <<'PY'
import functools, itertools, math, sys
from meshgen import write_input
write = functools.partial(write_input, sys.argv[1])

def sub(a, b): return [a[i] - b[i] for i in range(3)]
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))

# a tetrahedron, counter-clockwise from outside
write("tetra4", "tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1)",
      [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)], [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])

# the icosahedron (0, ±1, ±φ) and cyclic permutations; faces are the triples of vertices 2 apart,
# turned to face outwards
phi = (1 + 5 ** 0.5) / 2
ico = []
for s1 in (-1, 1):
    for s2 in (-1, 1):
        ico += [(0, s1, s2 * phi), (s1, s2 * phi, 0), (s2 * phi, 0, s1)]
faces = []
for t in itertools.combinations(range(12), 3):
    if all(abs(math.dist(ico[a], ico[b]) - 2) < 1e-9 for a, b in itertools.combinations(t, 2)):
        a, b, c = (ico[k] for k in t)
        centre = [a[i] + b[i] + c[i] for i in range(3)]
        faces.append(list(t) if dot(cross(sub(b, a), sub(c, a)), centre) > 0 else [t[0], t[2], t[1]])
assert len(faces) == 20
write("icosahedron20", "icosahedron (0, ±1, ±φ) and cyclic permutations", ico, faces)

# the icosahedron without vertex 0 and its five faces: a boundary pentagon
keep = [f for f in faces if 0 not in f]
write("icoopen15", "icosahedron without vertex (0, -1, -φ) and its five faces", ico[1:],
      [[v - 1 for v in f] for f in keep])

# an open 3 x 3 grid over [0, 1]^2, each square split along (i, j)-(i+1, j+1), z bumped
n = 3
pos = [(i / n, j / n, 0.2 * math.sin(2 * i / n + 1) * math.cos(3 * j / n)) for j in range(n + 1) for i in range(n + 1)]
g = lambda i, j: j * (n + 1) + i
tris = []
for j in range(n):
    for i in range(n):
        tris += [[g(i, j), g(i + 1, j), g(i + 1, j + 1)], [g(i, j), g(i + 1, j + 1), g(i, j + 1)]]
write("trigrid18", "open 3 x 3 grid of squares split into two triangles, z = 0.2 sin(2x + 1) cos(3y)", pos, tris)

PY
driver="$peers/cgal_sqrt3_doosabin"
for m in tetra4 icosahedron20 icoopen15 trigrid18; do
    for l in 1 2 3; do
        "$driver" "$data/$m.in.obj" --scheme sqrt3 -n "$l" -o "$data/$m.cgal-sqrt3.l$l.obj" >/dev/null
    done
done
for m in catmark/cube6 catmark/prism8 cgal/icosahedron20 catmark/grid16 cgal/trigrid18; do
    for l in 1 2; do
        "$driver" "$tests/$m.in.obj" --scheme doo-sabin -n "$l" -o "$data/${m#*/}.cgal-doosabin.l$l.obj" >/dev/null
    done
done
"$driver" "$tests/catmark/cube6.in.obj" --scheme doo-sabin -n 3 -o "$data/cube6.cgal-doosabin.l3.obj" >/dev/null
ls -l "$data"
