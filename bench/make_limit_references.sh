#!/usr/bin/env bash
# Limit-position reference data for crates/splinekit/tests/subdivision_reference.rs:
# OpenSubdiv's PrimvarRefinerReal::Limit of the finest level after uniform Loop and
# Catmull-Clark refinement (bench/drivers/osd_loop.cpp, osd_catmark.cpp with --limit), with the
# unit limit normals as `vn` lines (tan1 x tan2 of PrimvarRefinerReal::Limit), on the input
# meshes of tests/data/loop and tests/data/catmark, the bunny's base mesh (Loop: boundary
# vertices with up to 6 faces) and the icosahedron with a hole of tests/data/cgal (Catmull-Clark:
# boundary vertices with 3 quads), into tests/data/limit/. Needs the peers
# (bench/install_peers.sh); CI does not run it. Deterministic.
set -euo pipefail
source "$(dirname "$0")/references_common.sh" limit
data="$tests"
for m in icosahedron20 torus96 grid32 bunnybase883; do
    "$peers/osd_loop" "$data/loop/$m.in.obj" -n 1 --limit -o "$data/limit/$m.osd-loop.l1.obj" >/dev/null
done
"$peers/osd_loop" "$data/loop/grid32.in.obj" -n 1 --limit --corners -o "$data/limit/grid32.osd-loop-corners.l1.obj" >/dev/null
for m in cube6 torus48 prism8 grid16; do
    "$peers/osd_catmark" "$data/catmark/$m.in.obj" -n 1 --limit -o "$data/limit/$m.osd-catmark.l1.obj" >/dev/null
done
"$peers/osd_catmark" "$data/catmark/grid16.in.obj" -n 1 --limit --corners -o "$data/limit/grid16.osd-catmark-corners.l1.obj" >/dev/null
"$peers/osd_catmark" "$data/cgal/icoopen15.in.obj" -n 1 --limit -o "$data/limit/icoopen15.osd-catmark.l1.obj" >/dev/null
ls -l "$data/limit"
