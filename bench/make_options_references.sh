#!/usr/bin/env bash
# Reference data for OpenSubdiv's options that users set (issue #39), for
# crates/splinekit/tests/subdivision_reference.rs and crates/splinekit-cli/tests/subdivide.rs:
# OpenSubdiv's Catmull-Clark with TRI_SUB_SMOOTH (osd_catmark --triangles smooth), its bilinear
# scheme (osd_catmark --scheme bilinear) and VTX_BOUNDARY_NONE (--boundary-none), levels 1-3,
# into crates/splinekit/tests/data/options/. TRI_SUB_SMOOTH: Catmull-Clark's prism of
# triangles, quads and pentagons; an open grid with triangles among its quads (and a pentagon),
# also with VTX_BOUNDARY_EDGE_AND_CORNER; the icosahedron (all triangles); the creased prism
# (crease/prism8), with Chaikin and with Uniform creasing; fins of triangles on a spine
# (non-manifold). Bilinear: the cube, the prism, the grid, and cubes sharing an edge and a
# vertex with a triangle fin (non-manifold). `tagged.in.obj` is the grid with the option tags
# `interpolateboundary 1` (edge and corner), `creasemethod normal`, `smoothtriangles smooth` and
# creases: its reference is made with the same options given as flags (the driver reads only
# the crease tags). `holes.in.obj` is the grid with `interpolateboundary 0` (VTX_BOUNDARY_NONE:
# the faces at the boundary are holes, left out of the references, every vertex kept) and an
# infinitely sharp crease along most of one side (whose faces are then not holes); Loop's open
# grid (loop/grid32) is refined with VTX_BOUNDARY_NONE too. Needs the peers
# (bench/install_peers.sh); CI does not run it. Running it twice gives identical bytes.
set -euo pipefail
source "$(dirname "$0")/references_common.sh" options
data="$tests/options"
python3 - "$data" <<'PY'
import functools, math, sys
from meshgen import write_input
write = functools.partial(write_input, sys.argv[1])

# an open 4 x 4 grid over [0, 1]^2, z = 0.2 sin(2x + 1) cos(3y): quads, every third split into
# two triangles along alternating diagonals, and the top right two quads merged into a pentagon
# (their shared edge's ends joined through the middle vertex)
n = 4
pos = [(i / n, j / n, 0.2 * math.sin(2 * i / n + 1) * math.cos(3 * j / n)) for j in range(n + 1) for i in range(n + 1)]
g = lambda i, j: j * (n + 1) + i
faces = []
for j in range(n):
    for i in range(n):
        a, b, c, d = g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1)
        if (i, j) in ((2, 3), (3, 3)):
            continue
        k = j * n + i
        if k % 3 == 0:
            faces += [[a, b, c], [a, c, d]] if (i + j) % 2 == 0 else [[a, b, d], [b, c, d]]
        else:
            faces.append([a, b, c, d])
faces.append([g(2, 3), g(3, 3), g(4, 3), g(4, 4), g(2, 4)])
write("gridmix", "open 4 x 4 grid: quads, triangles (every third quad split), a pentagon", pos, faces)
PY
cp "$tests/catmark/prism8.in.obj" "$data/prism8.in.obj"
cp "$tests/catmark/cube6.in.obj" "$data/cube6.in.obj"
cp "$tests/loop/icosahedron20.in.obj" "$data/icosahedron20.in.obj"
cp "$tests/crease/prism8.in.obj" "$data/prism8creased.in.obj"
cp "$tests/nonmanifold/cubes.in.obj" "$data/cubes.in.obj"
cp "$tests/nonmanifold/fins3.in.obj" "$data/fins3.in.obj"
{
    cat "$data/gridmix.in.obj"
    printf '%s\n' "t crease 5/1 5 6 7 8 9 2.5" "t crease 3/2 2 7 12 0.5 3" "t corner 1/1 12 1.5" \
        "t interpolateboundary 1/0/0 1" "t creasemethod 0/0/1 normal" "t smoothtriangles 0/0/1 smooth"
} >"$data/tagged.in.obj"

{
    cat "$data/gridmix.in.obj"
    printf '%s\n' "t crease 5/1 0 1 2 3 4 10" "t interpolateboundary 1/0/0 0"
} >"$data/holes.in.obj"
cp "$tests/loop/grid32.in.obj" "$data/grid32.in.obj"

run() { # name suffix options...
    local name="$1" suffix="$2"
    shift 2
    for l in 1 2 3; do
        "$peers/osd_catmark" "$data/$name.in.obj" -n "$l" "$@" -o "$data/$name.$suffix.l$l.obj" >/dev/null
    done
}
for m in prism8 gridmix icosahedron20 prism8creased fins3; do
    run "$m" osd-smooth --triangles smooth
done
run gridmix osd-smooth-corners --triangles smooth --corners
run prism8creased osd-smooth-uniform --triangles smooth --creasing uniform
# the driver reads creases from the tags, not the options: these come from the flags
run tagged osd --triangles smooth --corners --creasing uniform
for m in cube6 prism8 gridmix cubes; do
    run "$m" osd-bilinear --scheme bilinear
done
run holes osd --boundary-none
for l in 1 2 3; do
    "$peers/osd_loop" "$data/grid32.in.obj" -n "$l" --boundary-none -o "$data/grid32.osd-none.l$l.obj" >/dev/null
done
ls -l "$data"
