#!/usr/bin/env bash
# Catmull-Clark reference data for crates/splinekit/tests/subdivision_reference.rs: writes the
# input meshes (deterministic, %.17g) and OpenSubdiv's catmark subdivision of each (levels 1
# and 2; the grid also with --corners) into crates/splinekit/tests/data/catmark/. Needs the
# peers (bench/install_peers.sh); CI does not run it. Running it twice gives identical bytes.
set -euo pipefail
source "$(dirname "$0")/references_common.sh" catmark
data="$tests/catmark"
python3 - "$data" <<'PY'
import functools, math, sys
from meshgen import write_input
write = functools.partial(write_input, sys.argv[1])

# the cube [-1, 1]^3, counter-clockwise from outside
cube = [((i & 1) * 2 - 1, ((i >> 1) & 1) * 2 - 1, (i >> 2) * 2 - 1) for i in range(8)]
write("cube6", "cube [-1,1]^3, 6 quads", cube,
      [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]])

# a torus of 8 x 6 quads, R = 1, r = 0.4
nu, nv = 8, 6
pos = []
for j in range(nv):
    for i in range(nu):
        a, b = 2 * math.pi * i / nu, 2 * math.pi * j / nv
        pos.append(((1 + 0.4 * math.cos(b)) * math.cos(a), (1 + 0.4 * math.cos(b)) * math.sin(a), 0.4 * math.sin(b)))
idx = lambda i, j: (j % nv) * nu + (i % nu)
write("torus48", "torus 8 x 6 quads, R = 1, r = 0.4", pos,
      [[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)] for j in range(nv) for i in range(nu)])

# a pentagonal prism with one side split into two triangles: pentagons, quads, triangles
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
for m in cube6 torus48 prism8 grid16; do
    for l in 1 2; do
        "$peers/osd_catmark" "$data/$m.in.obj" -n "$l" -o "$data/$m.osd.l$l.obj" >/dev/null
    done
done
for l in 1 2; do
    "$peers/osd_catmark" "$data/grid16.in.obj" -n "$l" --corners -o "$data/grid16.osd-corners.l$l.obj" >/dev/null
done
ls -l "$data"
