#!/usr/bin/env bash
# √3 and Doo-Sabin reference data for crates/splinekit/tests/subdivision_reference.rs: writes
# small input meshes (deterministic, %.17g) and CGAL's subdivision of each into
# crates/splinekit/tests/data/cgal/, with bench/drivers/cgal_sqrt3_doosabin.cpp:
#   √3 (Sqrt3_subdivision, levels 1 to 3, so that the boundary rule of every second level is
#   met once and the level after it too): a tetrahedron and an icosahedron (closed), an open
#   3 x 3 triangle grid and an icosahedron without the faces of one vertex (boundaries);
#   Doo-Sabin (DooSabin_subdivision, levels 1 and 2; the cube also 3): a cube, a pentagonal
#   prism of pentagons, quads and triangles, the icosahedron (closed), an open 4 x 4 quad grid
#   and the open triangle grid (boundaries).
# Needs libcgal-dev and g++ (bench/install_peers.sh); CI does not run it. Running it twice gives
# identical bytes.
set -euo pipefail
if [ "${CI:-}" = true ]; then
    echo "make_cgal_references.sh: not for CI" >&2
    exit 0
fi
here="$(cd "$(dirname "$0")" && pwd)"
root="$here/.."
data="$root/crates/splinekit/tests/data/cgal"
peers="${CARGO_TARGET_DIR:-$root/target}/bench-peers"
mkdir -p "$data"
bash "$here/drivers/build.sh" "$peers"
python3 - "$data" <<'PY'
import itertools, math, sys
out = sys.argv[1]

def write(name, comment, positions, faces):
    with open(f"{out}/{name}.in.obj", "w") as f:
        f.write(f"# {comment}\n")
        for p in positions:
            f.write("v %s %s %s\n" % tuple(repr(float(x)) for x in p))
        for face in faces:
            f.write("f " + " ".join(str(v + 1) for v in face) + "\n")

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

# the cube [-1, 1]^3
cube = [((i & 1) * 2 - 1, ((i >> 1) & 1) * 2 - 1, (i >> 2) * 2 - 1) for i in range(8)]
write("cube6", "cube [-1,1]^3, 6 quads", cube,
      [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]])

# a pentagonal prism with one side quad split into two triangles: pentagons, quads, triangles
pos = []
for z in (0.0, 1.3):
    for k in range(5):
        a = 2 * math.pi * k / 5 + 0.1
        pos.append((math.cos(a), math.sin(a), z + 0.1 * k))
write("prism8", "pentagonal prism, one side quad split into two triangles", pos,
      [[4, 3, 2, 1, 0], [5, 6, 7, 8, 9], [0, 1, 6, 5], [1, 2, 7], [1, 7, 6], [2, 3, 8, 7], [3, 4, 9, 8], [4, 0, 5, 9]])

# an open 4 x 4 grid of quads over [0, 1]^2, z = 0.2 sin(2x + 1) cos(3y)
n = 4
pos = [(i / n, j / n, 0.2 * math.sin(2 * i / n + 1) * math.cos(3 * j / n)) for j in range(n + 1) for i in range(n + 1)]
g = lambda i, j: j * (n + 1) + i
write("grid16", "open 4 x 4 quad grid, z = 0.2 sin(2x + 1) cos(3y)", pos,
      [[g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1)] for j in range(n) for i in range(n)])
PY
driver="$peers/cgal_sqrt3_doosabin"
for m in tetra4 icosahedron20 icoopen15 trigrid18; do
    for l in 1 2 3; do
        "$driver" "$data/$m.in.obj" --scheme sqrt3 -n "$l" -o "$data/$m.cgal-sqrt3.l$l.obj" >/dev/null
    done
done
for m in cube6 prism8 icosahedron20 grid16 trigrid18; do
    for l in 1 2; do
        "$driver" "$data/$m.in.obj" --scheme doo-sabin -n "$l" -o "$data/$m.cgal-doosabin.l$l.obj" >/dev/null
    done
done
"$driver" "$data/cube6.in.obj" --scheme doo-sabin -n 3 -o "$data/cube6.cgal-doosabin.l3.obj" >/dev/null
ls -l "$data"
