#!/usr/bin/env bash
# Modified butterfly reference data for crates/splinekit/tests/subdivision_reference.rs: OpenMesh's
# ModifiedButterflyT (bench/drivers/openmesh_loop.cpp --scheme butterfly) on small meshes, into
# crates/splinekit/tests/data/openmesh/:
#   levels 1 to 3 of a tetrahedron (valence 3), an octahedron (valence 4), a bipyramid over a
#   heptagon (apexes of valence 7, the rest 4) and the icosahedron (valence 5), all closed; an
#   open 3 x 3 triangle grid and the icosahedron with a hole (boundaries: the 4-point rule,
#   reflected wings, boundary ends); level 1 of the bunny's base mesh (883 triangles, four holes).
# The tetrahedron, icosahedron, grid and holed icosahedron are the inputs of
# bench/make_cgal_references.sh (tests/data/cgal/), the bunny that of
# bench/make_loop_references.sh (tests/data/loop/); the octahedron and the bipyramid are written
# here (%.17g). Needs libopenmesh-dev and g++ (bench/install_peers.sh); CI does not run it.
# Running it twice gives identical bytes.
set -euo pipefail
source "$(dirname "$0")/references_common.sh" openmesh
data="$tests/openmesh"
python3 - "$data" <<'PY'
import functools, math, sys
from meshgen import write_input
write = functools.partial(write_input, sys.argv[1])

# the octahedron, counter-clockwise from outside
octa = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
faces = []
for x in (0, 1):
    for y in (2, 3):
        for z in (4, 5):
            s = (1 if x == 0 else -1) * (1 if y == 2 else -1) * (1 if z == 4 else -1)
            faces.append([x, y, z] if s > 0 else [x, z, y])
write("octahedron8", "octahedron (±1, 0, 0) and permutations", octa, faces)

# a bipyramid over a heptagon, apexes at different heights, ring slightly wavy
n = 7
ring = [(math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n), 0.1 * math.sin(3 * k)) for k in range(n)]
pos = ring + [(0, 0, 1.2), (0.1, 0, -0.9)]
top, bottom = n, n + 1
faces = [[k, (k + 1) % n, top] for k in range(n)] + [[(k + 1) % n, k, bottom] for k in range(n)]
write("bipyramid14", "bipyramid over a heptagon (apexes of valence 7)", pos, faces)
PY
driver="$peers/openmesh_loop"
for m in cgal/tetra4 openmesh/octahedron8 openmesh/bipyramid14 cgal/icosahedron20 cgal/trigrid18 cgal/icoopen15; do
    for l in 1 2 3; do
        "$driver" "$tests/$m.in.obj" --scheme butterfly -n "$l" -o "$data/${m#*/}.openmesh-butterfly.l$l.obj" >/dev/null
    done
done
"$driver" "$tests/loop/bunnybase883.in.obj" --scheme butterfly -n 1 -o "$data/bunnybase883.openmesh-butterfly.l1.obj" >/dev/null
ls -l "$data"
